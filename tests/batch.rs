//! Batches of curves solved at once (spread over rayon's pool with the `parallel` feature)
//! give, curve for curve, what one solve per curve gives: on every built-in drawing, each
//! scheme, with the drawings' own per-point shapes where they have them.

use kappa::{
    builtin_design, BatchCurve, BatchSolver, Design, Scheme, Shape, SolveOptions, Solver,
    BUILTIN_DESIGNS,
};
use kurbo::Point;
use proptest::prelude::*;

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

/// A random curve for a batch: 2–12 points on a jagged loop of random size and place,
/// closed or open, sometimes spoiled (a repeated point, a NaN, too few points) so that the
/// batch also carries errors.
fn random_curve() -> impl Strategy<Value = (Vec<Point>, bool)> {
    (
        2usize..12,
        any::<bool>(),
        0.5f64..500.0,
        -1000.0f64..1000.0,
        0u8..8,
        prop::collection::vec(0.6f64..1.0, 12),
    )
        .prop_map(|(n, closed, r, shift, spoil, radii)| {
            let mut pts: Vec<Point> = (0..n)
                .map(|i| {
                    let th = i as f64 / n as f64 * std::f64::consts::TAU;
                    let rr = r * radii[i];
                    Point::new(shift + rr * th.cos(), rr * th.sin())
                })
                .collect();
            match spoil {
                0 if n > 2 => pts[1] = pts[0],
                1 => pts[n - 1].x = f64::NAN,
                _ => {}
            }
            (pts, closed)
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// Any batch (valid and invalid curves mixed, any sizes, in any order) gives, curve for
    /// curve and in its order, what one solve per curve gives.
    #[test]
    fn random_batches_match_one_solve_per_curve(
        curves in prop::collection::vec(random_curve(), 0..24),
        scheme_i in 0usize..2,
    ) {
        let (scheme, shape) = [
            (Scheme::Kappa, Shape::Neutral),
            (Scheme::EkCubic, Shape::Global(0.8)),
        ][scheme_i].clone();
        let options = SolveOptions { accept_unconverged: true, ..SolveOptions::default() };
        let batch: Vec<BatchCurve<'_, Point>> = curves
            .iter()
            .map(|(p, c)| BatchCurve::new(p, *c, &shape))
            .collect();
        let got = BatchSolver::with_options(options).solve(&batch, scheme);
        prop_assert_eq!(got.len(), curves.len());
        let mut one = Solver::with_options(options);
        for ((p, c), g) in curves.iter().zip(&got) {
            prop_assert_eq!(g, &one.solve(p, *c, scheme, &shape));
        }
    }
}
