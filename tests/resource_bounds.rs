//! Resource bounds: every solve is capped (`O(n · max_iterations)`, see the crate docs), so
//! input the solver cannot handle ends in `Error::NotConverged` — with no more iterations
//! than the cap — in bounded time, never in an endless loop.

use std::f64::consts::TAU;
use std::time::{Duration, Instant};

use kappa::{Error, Scheme, Shape, SolveOptions, Solver};
use kurbo::Point;

/// A loop densely sampled from a smooth curve of varying curvature: the κ solution
/// degenerates there (peaks pushed to segment ends) and the solver cannot converge
/// (docs/curves.md, "Known limits").
fn wavy_loop(n: usize, amplitude: f64, waves: f64) -> Vec<Point> {
    (0..n)
        .map(|i| {
            let th = i as f64 * TAU / n as f64;
            let r = 100.0 * (1.0 + amplitude * (waves * th).sin());
            Point::new(r * th.cos(), r * th.sin())
        })
        .collect()
}

/// Solves with a cap and returns the outcome and the time taken.
fn capped(
    points: &[Point],
    scheme: Scheme,
    shape: Shape,
    cap: usize,
) -> (Result<usize, Error>, Duration) {
    let options = SolveOptions {
        max_iterations: cap,
        ..SolveOptions::default()
    };
    let start = Instant::now();
    let r = Solver::with_options(options)
        .solve(points, true, scheme, &shape)
        .map(|s| s.iterations());
    (r, start.elapsed())
}

#[test]
fn pathological_input_is_not_converged_within_the_cap() {
    let pts = wavy_loop(50, 0.02, 3.0);
    for cap in [10, 100, 1000] {
        let (r, took) = capped(&pts, Scheme::Kappa, Shape::Neutral, cap);
        match r {
            Err(Error::NotConverged {
                iterations,
                residual,
            }) => {
                assert!(iterations <= cap, "cap {cap}: {iterations} iterations");
                assert!(
                    residual.is_finite() && residual > 1e-12,
                    "cap {cap}: {residual}"
                );
            }
            other => panic!("cap {cap}: expected NotConverged, got {other:?}"),
        }
        // 50 points, at most 1000 iterations of O(n) work each: well under a second even
        // in a debug build; the bound is generous for a loaded machine.
        assert!(took < Duration::from_secs(10), "cap {cap}: {took:?}");
    }
}

#[test]
fn the_cap_bounds_the_time_of_large_inputs() {
    // 20 000 points that do not converge as κ-curves, with a cap of 20: the time is that of
    // about 20 O(n) iterations, not of a search that runs on.
    let pts = wavy_loop(20_000, 0.3, 7.0);
    let (r, took) = capped(&pts, Scheme::Kappa, Shape::Neutral, 20);
    match r {
        Err(Error::NotConverged { iterations, .. }) => assert!(iterations <= 20),
        Ok(iterations) => assert!(iterations <= 20),
        Err(e) => panic!("{e}"),
    }
    assert!(took < Duration::from_secs(20), "{took:?}");
    // A cap of zero does no work at all beyond the set-up.
    let (r, _) = capped(&pts, Scheme::EkCubic, Shape::Global(0.9), 0);
    assert!(
        matches!(r, Err(Error::NotConverged { iterations: 0, .. })),
        "{r:?}"
    );
}

#[test]
fn every_scheme_reports_iterations_within_the_cap() {
    // Jagged, dense and wavy loops, for every scheme and a range of caps: a result or a
    // NotConverged, never more iterations than allowed.
    let inputs = [
        wavy_loop(50, 0.02, 3.0),
        wavy_loop(100, 0.3, 7.0),
        wavy_loop(12, 0.6, 2.0),
    ];
    for pts in &inputs {
        for (scheme, shape) in [
            (Scheme::Kappa, Shape::Neutral),
            (Scheme::EkCubic, Shape::Global(0.99)),
            (Scheme::EkTrig, Shape::Global(0.5)),
        ] {
            for cap in [1, 5, 37, 200] {
                let (r, _) = capped(pts, scheme, shape.clone(), cap);
                let iterations = match r {
                    Ok(i) | Err(Error::NotConverged { iterations: i, .. }) => i,
                    Err(e) => panic!("{scheme:?} cap {cap}: {e}"),
                };
                assert!(iterations <= cap, "{scheme:?}: {iterations} > {cap}");
            }
        }
    }
}
