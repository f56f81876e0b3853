//! Prescribed tangents (`Solver::solve_with_tangents`): what holds at a constrained point
//! and elsewhere, that the constrained curve tends to the free one as the direction does,
//! and the typed errors.

mod common;

use kappa::{Error, Scheme, Shape, Solver, Spline};
use kurbo::{Point, Vec2};
use proptest::prelude::*;

const SCHEMES: [(Scheme, f64); 3] = [
    (Scheme::Kappa, 2.0 / 3.0),
    (Scheme::EkCubic, 0.8),
    (Scheme::EkTrig, 0.7),
];

/// Signed angle from `d` to `v`.
fn angle(d: Vec2, v: Vec2) -> f64 {
    d.cross(v).atan2(d.dot(v))
}

/// Asserts what holds with tangents: each point interpolated, each prescribed tangent met
/// (within `1e-9` rad, in its sense), and the papers' G2 at every joint: equal |κ| (relative
/// mismatch within `1e-6`, or both within `1e-9` of the scale for a straight joint), the
/// sign flipping only at an inflection.
fn assert_conditions(
    spline: &Spline<Point>,
    points: &[Point],
    closed: bool,
    tans: &[Option<Vec2>],
) {
    let size = common::drawing_size(points);
    let segs = spline.segments();
    let off = usize::from(!closed);
    for (j, seg) in segs.iter().enumerate() {
        let err = (seg.eval(seg.t_max) - points[j + off]).hypot();
        assert!(err <= 1e-9 * size, "point {}: off by {err}", j + off);
        if let Some(d) = tans[j + off] {
            let a = angle(d, seg.derivative(seg.t_max));
            assert!(a.abs() <= 1e-9, "point {}: tangent off by {a} rad", j + off);
        }
    }
    if !closed {
        if let Some(d) = tans[0] {
            let a = angle(d, segs[0].derivative(0.0));
            assert!(a.abs() <= 1e-9, "start tangent off by {a} rad");
        }
        if let Some(d) = tans[points.len() - 1] {
            let a = angle(d, segs[segs.len() - 1].derivative(1.0));
            assert!(a.abs() <= 1e-9, "end tangent off by {a} rad");
        }
    }
    let joints = if closed { segs.len() } else { segs.len() - 1 };
    for j in 0..joints {
        let (k0, k1) = (
            segs[j].curvature(1.0),
            segs[(j + 1) % segs.len()].curvature(0.0),
        );
        let scale = k0.abs().max(k1.abs());
        assert!(
            (k0.abs() - k1.abs()).abs() <= 1e-6 * scale || scale * size <= 1e-9,
            "joint {j}: curvatures {k0} and {k1}"
        );
    }
}

/// An ellipse sampled every 45°, as a type designer places nodes: the extrema (0°, 90°, …)
/// carry axis-aligned tangents.
fn ellipse() -> (Vec<Point>, Vec<Option<Vec2>>) {
    let points = (0..8)
        .map(|i| {
            let t = i as f64 * std::f64::consts::FRAC_PI_4;
            Point::new(300.0 + 180.0 * t.cos(), 300.0 + 110.0 * t.sin())
        })
        .collect();
    let tans = (0..8)
        .map(|i| match i {
            0 => Some(Vec2::new(0.0, 1.0)),
            2 => Some(Vec2::new(-1.0, 0.0)),
            4 => Some(Vec2::new(0.0, -1.0)),
            6 => Some(Vec2::new(1.0, 0.0)),
            _ => None,
        })
        .collect();
    (points, tans)
}

#[test]
fn extremum_nodes_keep_axis_aligned_tangents() {
    let (points, tans) = ellipse();
    let mut solver = Solver::new();
    for (scheme, a) in SCHEMES {
        let spline = solver
            .solve_with_tangents(&points, true, scheme, &Shape::Global(a), &tans)
            .unwrap_or_else(|e| panic!("{scheme:?}: {e}"));
        assert_conditions(&spline, &points, true, &tans);
    }
}

#[test]
fn a_tangent_swept_near_the_free_one_converges_on_a_loop() {
    // The free oval's tangent at its first point turned by -10° … 10° in 5° steps. (Farther,
    // on this four-point loop, no curve meets the tangent with the point inside its segment:
    // measured, κ fails from -15° and 30°, εκ from ±30°; a tangent farther from the free
    // curve's needs more points around it.)
    let points = [(0.0, 0.0), (60.0, 30.0), (0.0, 70.0), (-50.0, 35.0)].map(Point::from);
    let mut solver = Solver::new();
    for (scheme, a) in SCHEMES {
        let shape = Shape::Global(a);
        let free = solver.solve(&points, true, scheme, &shape).unwrap();
        let seg = &free.segments()[0];
        let base = seg.derivative(seg.t_max);
        let base = base.y.atan2(base.x);
        for step in -2..=2 {
            let th = base + f64::from(step) * 5f64.to_radians();
            let mut tans = vec![None; 4];
            tans[0] = Some(Vec2::new(th.cos(), th.sin()));
            let spline = solver
                .solve_with_tangents(&points, true, scheme, &shape, &tans)
                .unwrap_or_else(|e| panic!("{scheme:?} at {}°: {e}", step * 5));
            assert_conditions(&spline, &points, true, &tans);
        }
    }
}

#[test]
fn the_constrained_curve_tends_to_the_free_one() {
    // Prescribing the free curve's own tangent turned by δ moves the curve by O(δ): the
    // distance (over the segments' points at 33 parameters) shrinks tenfold with δ.
    let (points, _) = ellipse();
    let mut solver = Solver::new();
    for (scheme, a) in SCHEMES {
        let shape = Shape::Global(a);
        let free = solver.solve(&points, true, scheme, &shape).unwrap();
        let seg = &free.segments()[2];
        let base = seg.derivative(seg.t_max);
        let base = base.y.atan2(base.x);
        let mut last = None;
        for delta in [1e-2, 1e-3, 1e-4, 1e-5] {
            let th = base + delta;
            let mut tans = vec![None; points.len()];
            tans[2] = Some(Vec2::new(th.cos(), th.sin()));
            let spline = solver
                .solve_with_tangents(&points, true, scheme, &shape, &tans)
                .unwrap();
            let dist = spline
                .segments()
                .iter()
                .zip(free.segments())
                .flat_map(|(s, f)| {
                    (0..=32)
                        .map(move |i| (s.eval(i as f64 / 32.0) - f.eval(i as f64 / 32.0)).hypot())
                })
                .fold(0.0f64, f64::max);
            assert!(
                dist > 0.0 && dist <= 1e3 * delta,
                "{scheme:?} δ = {delta}: {dist}"
            );
            if let Some(prev) = last {
                let ratio = prev / dist;
                assert!(
                    (7.0..=13.0).contains(&ratio),
                    "{scheme:?} δ = {delta}: ratio {ratio}"
                );
            }
            last = Some(dist);
        }
    }
}

#[test]
fn open_curves_take_tangents_at_their_ends_and_inside() {
    // Within 5° of the free curve's end directions (measured: κ to ±15°, εκ to ±5°), an open
    // curve meets tangents at both ends and one inside; a line-to-curve join is the case of
    // a tangent along the line.
    let points = [
        (0.0, 0.0),
        (50.0, 40.0),
        (100.0, 20.0),
        (150.0, 60.0),
        (200.0, 0.0),
    ]
    .map(Point::from);
    let mut solver = Solver::new();
    for (scheme, a) in SCHEMES {
        let shape = Shape::Global(a);
        let free = solver.solve(&points, false, scheme, &shape).unwrap();
        let segs = free.segments();
        let d0 = segs[0].derivative(0.0);
        let d1 = segs[segs.len() - 1].derivative(1.0);
        for deg in [-5.0f64, 0.0, 5.0] {
            let turn = |d: Vec2| {
                let th = d.y.atan2(d.x) + deg.to_radians();
                Some(Vec2::new(th.cos(), th.sin()))
            };
            let tans = [turn(d0), None, Some(Vec2::new(1.0, 0.0)), None, turn(d1)];
            let spline = solver
                .solve_with_tangents(&points, false, scheme, &shape, &tans)
                .unwrap_or_else(|e| panic!("{scheme:?} at {deg}°: {e}"));
            assert_conditions(&spline, &points, false, &tans);
        }
    }
}

#[test]
fn bad_tangents_get_typed_errors() {
    let (points, mut tans) = ellipse();
    let mut solver = Solver::new();
    let solve = |solver: &mut Solver, pts: &[Point], closed, tans: &[Option<Vec2>]| {
        solver.solve_with_tangents(pts, closed, Scheme::Kappa, &Shape::Neutral, tans)
    };
    assert!(matches!(
        solve(&mut solver, &points, true, &tans[..5]),
        Err(Error::InvalidTangent { index: 5, .. })
    ));
    for bad in [
        Vec2::ZERO,
        Vec2::new(f64::NAN, 1.0),
        Vec2::new(f64::INFINITY, 0.0),
    ] {
        tans[3] = Some(bad);
        assert!(matches!(
            solve(&mut solver, &points, true, &tans),
            Err(Error::InvalidTangent { index: 3, .. })
        ));
    }
    let open = [(0.0, 0.0), (50.0, 40.0), (100.0, 20.0), (150.0, 60.0)].map(Point::from);
    let h = Some(Vec2::new(1.0, 0.0));
    assert_eq!(
        solve(&mut solver, &open, false, &[h, h, None, None]),
        Err(Error::TangentConflict {
            first: 0,
            second: 1
        })
    );
    assert_eq!(
        solve(&mut solver, &open, false, &[None, None, h, h]),
        Err(Error::TangentConflict {
            first: 2,
            second: 3
        })
    );
    assert_eq!(
        solve(&mut solver, &open[..3], false, &[None, h, h]),
        Err(Error::TangentConflict {
            first: 1,
            second: 2
        })
    );
    assert_eq!(
        solve(&mut solver, &open[..2], false, &[h, None]),
        Err(Error::TangentConflict {
            first: 0,
            second: 1
        })
    );
    // A plain solve afterwards has no tangents.
    let free = solver
        .solve(&open, false, Scheme::Kappa, &Shape::Neutral)
        .unwrap();
    assert!(free.report().converged);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Whenever a solve with tangents converges, every condition it promises holds: on
    /// loops of 5–12 points around a circle with up to 20 % noise in the radius, with
    /// tangents within 20° of the free curve's at every other point.
    #[test]
    fn converged_solves_meet_their_tangents(
        radii in prop::collection::vec(0.8f64..1.2, 5..12),
        turns in prop::collection::vec(-20.0f64..20.0, 12),
        scheme in 0usize..3,
    ) {
        let n = radii.len();
        let points: Vec<Point> = radii
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let t = i as f64 / n as f64 * std::f64::consts::TAU;
                Point::new(200.0 * r * t.cos(), 200.0 * r * t.sin())
            })
            .collect();
        let (scheme, a) = SCHEMES[scheme];
        let shape = Shape::Global(a);
        let mut solver = Solver::new();
        let Ok(free) = solver.solve(&points, true, scheme, &shape) else {
            return Ok(());
        };
        let tans: Vec<Option<Vec2>> = free
            .segments()
            .iter()
            .enumerate()
            .map(|(j, seg)| {
                (j % 2 == 0).then(|| {
                    let d = seg.derivative(seg.t_max);
                    let th = d.y.atan2(d.x) + turns[j].to_radians();
                    Vec2::new(th.cos(), th.sin())
                })
            })
            .collect();
        match solver.solve_with_tangents(&points, true, scheme, &shape, &tans) {
            Ok(spline) => assert_conditions(&spline, &points, true, &tans),
            Err(Error::NotConverged { residual, .. }) => prop_assert!(residual > 1e-12),
            Err(e) => panic!("{e}"),
        }
    }
}

#[test]
fn solve_from_after_tangents_solves_the_free_curve() {
    let (points, tans) = ellipse();
    let mut solver = Solver::new();
    let shape = Shape::Global(0.8);
    let free = solver
        .solve(&points, true, Scheme::EkCubic, &shape)
        .unwrap();
    let state = solver.state().unwrap();
    let mut turned = tans.clone();
    turned[1] = Some(Vec2::new(-1.0, 0.7));
    solver
        .solve_with_tangents(&points, true, Scheme::EkCubic, &shape, &turned)
        .unwrap();
    let again = solver
        .solve_from(&points, true, Scheme::EkCubic, &shape, &state)
        .unwrap();
    for (a, b) in again.segments().iter().zip(free.segments()) {
        assert!((a.eval(0.5) - b.eval(0.5)).hypot() <= 1e-9);
    }
}
