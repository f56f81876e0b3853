//! Every built-in drawing solved cold twice: curve by curve on one thread, and as one batch
//! spread over the threads of rayon's pool. Checks that both give the same curves and prints
//! the fastest time of each (µs) over a few hundred repetitions.
//!
//! `cargo run --release --features serde --example batch [-- REPEAT]`
//! (`RAYON_NUM_THREADS=1` runs the batches on the calling thread alone.)

use kappa::{
    builtin_design, BatchCurve, BatchSolver, Design, Scheme, Shape, SolveOptions, Solver,
    BUILTIN_DESIGNS,
};
use kurbo::Point;
use std::hint::black_box;
use std::time::Instant;

fn main() {
    let repeat: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(301);
    let options = SolveOptions {
        accept_unconverged: true,
        ..SolveOptions::default()
    };
    let mut solver = Solver::with_options(options);
    let mut batch = BatchSolver::with_options(options);
    println!("drawing                       curves  scheme      one thread  batch  threads");
    for (name, _) in BUILTIN_DESIGNS {
        let design = Design::from_json(builtin_design(name).expect("built in")).expect("valid");
        let points: Vec<Vec<Point>> = design.curves.iter().map(|c| c.kurbo_points()).collect();
        for (label, scheme, shape) in [
            ("κ", Scheme::Kappa, Shape::Neutral),
            ("εκ 0.85", Scheme::EkCubic, Shape::Global(0.85)),
        ] {
            let curves: Vec<BatchCurve<'_, Point>> = design
                .curves
                .iter()
                .zip(&points)
                .map(|(c, p)| BatchCurve::new(p, c.is_closed(), &shape))
                .collect();
            let one_by_one = |solver: &mut Solver| {
                curves
                    .iter()
                    .map(|c| solver.solve(c.points, c.closed, scheme, c.shape))
                    .collect::<Vec<_>>()
            };
            assert_eq!(
                batch.solve(&curves, scheme),
                one_by_one(&mut solver),
                "{name}"
            );
            let best = |f: &mut dyn FnMut()| {
                (0..repeat)
                    .map(|_| {
                        let start = Instant::now();
                        f();
                        start.elapsed().as_secs_f64() * 1e6
                    })
                    .fold(f64::INFINITY, f64::min)
            };
            let seq = best(&mut || {
                black_box(one_by_one(&mut solver));
            });
            let par = best(&mut || {
                black_box(batch.solve(&curves, scheme));
            });
            println!(
                "{name:<30}{:>6}  {label:<10}{seq:>10.1}{par:>7.1}{:>9}",
                curves.len(),
                batch.threads_for(&curves)
            );
        }
    }
}
