//! εκ-curves in the trigonometric basis: solve, see which points sit at curvature maxima,
//! and fit the exact curve to cubics for kurbo.
//!
//! `cargo run --release --example trig`

use kappa::fit::{FitMethod, FitOptions};
use kappa::{Extremum, Spline};
use kurbo::Point;

fn main() -> Result<(), kappa::Error> {
    let points = [
        Point::new(0.0, 0.0),
        Point::new(100.0, 5.0),
        Point::new(150.0, 60.0),
        Point::new(110.0, 120.0),
        Point::new(30.0, 100.0),
    ];
    for a in [0.55, 0.7, 0.9] {
        let curve = Spline::ek_trig(&points, true, a)?;
        let kinds: Vec<&str> = curve
            .segments()
            .iter()
            .map(|s| match s.extremum() {
                Extremum::Max => "max",
                Extremum::Min => "min",
                Extremum::Inflection => "inflection",
                Extremum::EndOnly => "end-only",
            })
            .collect();
        println!(
            "a = {a}: {} iterations, |κ| at the points: {kinds:?}",
            curve.iterations()
        );
        for method in [FitMethod::Kurbo, FitMethod::Hermite] {
            let fitted = curve.fit(&FitOptions {
                method,
                ..FitOptions::relative(1e-4)
            })?;
            println!(
                "  {method:?}: {} cubics {:?}, max distance {:.2e} (tolerance {:.2e})",
                fitted.cubic_count(),
                fitted.cubics,
                fitted.max_distance,
                fitted.tolerance
            );
        }
    }
    Ok(())
}
