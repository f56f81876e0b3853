//! Batches of curves solved at once (spread over rayon's pool with the `parallel` feature)
//! give, curve for curve, what one solve per curve gives: on every built-in drawing, each
//! scheme, with the drawings' own per-point shapes where they have them.

use kappa::{
    builtin_design, BatchCurve, BatchSolver, Design, Scheme, Shape, SolveOptions, Solver,
    BUILTIN_DESIGNS,
};
use kurbo::Point;

#[test]
fn batches_of_every_drawing_match_one_solve_per_curve() {
    let options = SolveOptions {
        accept_unconverged: true,
        ..SolveOptions::default()
    };
    // One batch solver for everything: its threads' solvers carry over from batch to
    // batch, which must not change any result.
    let mut batch = BatchSolver::with_options(options);
    let mut compared = 0;
    for (name, _) in BUILTIN_DESIGNS {
        let design = Design::from_json(builtin_design(name).unwrap()).unwrap();
        let points: Vec<Vec<Point>> = design.curves.iter().map(|c| c.kurbo_points()).collect();
        for (scheme, global) in [
            (Scheme::Kappa, Shape::Neutral),
            (Scheme::EkCubic, Shape::Global(0.85)),
            (Scheme::EkTrig, Shape::Global(0.75)),
        ] {
            let shapes: Vec<Shape> = design
                .curves
                .iter()
                .map(|c| match (&c.shape, scheme) {
                    (Some(a), Scheme::EkCubic | Scheme::EkTrig) => Shape::PerPoint(a.clone()),
                    _ => global.clone(),
                })
                .collect();
            let curves: Vec<BatchCurve<'_, Point>> = design
                .curves
                .iter()
                .zip(&points)
                .zip(&shapes)
                .map(|((c, p), s)| BatchCurve::new(p, c.is_closed(), s))
                .collect();
            let got = batch.solve(&curves, scheme);
            assert_eq!(got.len(), curves.len(), "{name}");
            for (i, (c, g)) in curves.iter().zip(&got).enumerate() {
                let want = Solver::with_options(options).solve(c.points, c.closed, scheme, c.shape);
                // Bit for bit, errors included.
                assert_eq!(g, &want, "{name} curve {i} {scheme:?}");
                compared += 1;
            }
        }
    }
    assert!(compared > 300, "{compared}");
}

#[test]
fn a_batch_spreads_over_the_pool_only_when_it_is_worth_it() {
    let tri = [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)].map(Point::from);
    let shape = Shape::Neutral;
    let batch = BatchSolver::new();
    let small = vec![BatchCurve::new(&tri[..], true, &shape); 5];
    assert_eq!(batch.threads_for(&small), 1);
    let large = vec![BatchCurve::new(&tri[..], true, &shape); 40];
    let threads = batch.threads_for(&large);
    assert!(threads >= 1 && threads <= rayon_threads());
}

/// The pool's size as the batch sees it (1 without the `parallel` feature).
fn rayon_threads() -> usize {
    std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .max(
            std::env::var("RAYON_NUM_THREADS")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(1),
        )
}
