//! κ-space curves through points on a helix and on a trefoil knot: how far from G2 the
//! quadratic κ-curve is at its joints, how close the κ-space curve is, the extra curvature
//! extrema the quartics add, and OBJ (and, with `--features render`, PNG) files in `target/`.
//!
//! `cargo run --release --features render --example space`

use kappa::space::{Replace, SpaceCurve, SpaceOptions};
use kappa::{Error, Point3};

fn helix() -> Vec<Point3> {
    (0..10)
        .map(|i| {
            let th = 0.9 * i as f64;
            Point3::new(50.0 * th.cos(), 50.0 * th.sin(), 12.0 * th)
        })
        .collect()
}

fn trefoil() -> Vec<Point3> {
    (0..12)
        .map(|i| {
            let t = i as f64 / 12.0 * std::f64::consts::TAU;
            Point3::new(
                30.0 * (t.sin() + 2.0 * (2.0 * t).sin()),
                30.0 * (t.cos() - 2.0 * (2.0 * t).cos()),
                -30.0 * (3.0 * t).sin(),
            )
        })
        .collect()
}

fn worst(gaps: &[f64]) -> f64 {
    gaps.iter().copied().fold(0.0, f64::max)
}

fn main() -> Result<(), Error> {
    for (name, points, closed) in [("helix", helix(), false), ("trefoil", trefoil(), true)] {
        let plain = SpaceCurve::new(
            &points,
            closed,
            &SpaceOptions {
                replace: Replace::None,
                ..SpaceOptions::default()
            },
        )?;
        let start = std::time::Instant::now();
        let curve = SpaceCurve::new(&points, closed, &SpaceOptions::default())?;
        let elapsed = start.elapsed();
        println!(
            "{name}: {} points, {} segments ({} quartics), built in {elapsed:.1?}",
            points.len(),
            curve.len(),
            curve.joints().len(),
        );
        println!(
            "  curvature-vector gap at the joints: κ-curve {:.2e}, κ-space curve {:.2e}",
            worst(&plain.curvature_vector_gaps()),
            worst(&curve.curvature_vector_gaps())
        );
        let peak = curve.max_curvature().value;
        let extra = curve
            .quartic_extrema()
            .iter()
            .map(|e| e.curvature)
            .fold(0.0, f64::max);
        println!(
            "  largest |κ| {peak:.5} (at the input points); largest extremum the quartics add \
             {extra:.5}; arc length {:.3}",
            curve.arclen(1e-9)
        );
        for r in [0.1, 0.01, 0.001] {
            let c = SpaceCurve::new(&points, closed, &SpaceOptions::default().with_replace(r))?;
            let first = c.joints()[0].quartic.expect("replaced");
            println!(
                "  r = {r:<5}: first quartic {:.4} long, worst gap {:.1e}",
                c.segments()[first.segment].arclen(1e-12),
                worst(&c.curvature_vector_gaps())
            );
        }
        let obj = format!("target/space-{name}.obj");
        std::fs::write(&obj, curve.to_obj(1e-3)?).expect("write OBJ");
        println!("  wrote {obj}");
        #[cfg(feature = "render")]
        {
            let png = format!("target/space-{name}.png");
            kappa::space::views_figure(&curve, 300)
                .expect("figure")
                .save_png(&png)
                .expect("write PNG");
            println!("  wrote {png}");
        }
    }
    Ok(())
}
