//! Iteration counts of the solver on every curve of the built-in drawings of the εκ paper,
//! for κ-curves and εκ-curves with a = 0.75, 0.85, 0.95, and the time for the whole set;
//! then the same for the designer drawing (first clicks: inflections through points, a curl
//! on whole pixels, straight runs), which εκ-trig a = 0.7 solves too.
//!
//! `cargo run --release --features serde --example convergence`

use kappa::{builtin_design, Design, Scheme, Shape, SolveOptions, Solver};
use std::collections::BTreeMap;
use std::time::Instant;

const PAPER_DRAWINGS: [&str; 9] = [
    "bear", "bird", "deer", "dinosaur", "elephant", "plane", "pumpkin", "rabbit", "rose",
];

fn main() {
    report(&PAPER_DRAWINGS, &SCHEMES[..4]);
    report(&["designer"], &SCHEMES);
}

const SCHEMES: [(Scheme, Shape); 5] = [
    (Scheme::Kappa, Shape::Neutral),
    (Scheme::EkCubic, Shape::Global(0.75)),
    (Scheme::EkCubic, Shape::Global(0.85)),
    (Scheme::EkCubic, Shape::Global(0.95)),
    (Scheme::EkTrig, Shape::Global(0.7)),
];

fn report(names: &[&str], schemes: &[(Scheme, Shape)]) {
    println!("{}:", names.join(", "));
    let designs: Vec<Design> = names
        .iter()
        .map(|n| Design::from_json(builtin_design(n).expect("built in")).expect("valid JSON"))
        .collect();
    let options = SolveOptions {
        accept_unconverged: true,
        ..SolveOptions::default()
    };
    for (scheme, shape) in schemes {
        let mut solver = Solver::with_options(options);
        let mut histogram = BTreeMap::new();
        let (mut curves, mut converged, mut worst) = (0, 0, 0.0f64);
        let start = Instant::now();
        for design in &designs {
            for curve in design.curves.iter().filter(|c| c.points.len() >= 3) {
                let spline = solver
                    .solve(&curve.kurbo_points(), curve.is_closed(), *scheme, shape)
                    .expect("valid input");
                curves += 1;
                converged += usize::from(spline.converged());
                worst = worst.max(spline.report().residual);
                *histogram.entry(spline.iterations()).or_insert(0) += 1;
            }
        }
        let elapsed = start.elapsed();
        println!(
            "{scheme:?} {shape:?}: {converged}/{curves} converged, largest residual {worst:.1e}, {elapsed:.2?} in all"
        );
        println!("  iterations → curves: {histogram:?}");
    }
}
