//! The degenerate-geometry catalogue: what every scheme does with repeated and near-repeated
//! points, collinear runs, collinear input, two and three points, points on a circle,
//! near-cusp turns, self-intersecting input, spirals, 10⁵ points and coordinates at 1e-9
//! and 1e9. Each case states its expected behaviour — a curve whose properties are checked
//! by the oracles of `tests/hostile/` (interpolation, peaks at the points, G1/G2 joints, C2,
//! exact maxima), or a named error. The table in docs/hostile-input.md lists them.

mod common;
mod hostile;

use std::f64::consts::{PI, TAU};

use hostile::*;
use kappa::intrinsic::{Hermite, Profile};
use kappa::space::SpaceOptions;
use kappa::{
    BSpline, BSpline3, Error, Point3, Scheme, Shape, SolveOptions, Solver, SpaceCurve, Spline,
};
use kurbo::Point;

/// The three 2D κ-family schemes with a shape each.
const SCHEMES: [(Scheme, f64); 3] = [
    (Scheme::Kappa, 2.0 / 3.0),
    (Scheme::EkCubic, 0.85),
    (Scheme::EkTrig, 0.75),
];

fn shape(scheme: Scheme, a: f64) -> Shape {
    if scheme == Scheme::Kappa {
        Shape::Neutral
    } else {
        Shape::Global(a)
    }
}

/// Solves with every 2D scheme and checks every result with the oracle; returns them.
fn solve_all(points: &[Point], closed: bool, what: &str) -> Vec<Result<Spline, Error>> {
    SCHEMES
        .iter()
        .map(|&(scheme, a)| {
            let shape = shape(scheme, a);
            let opts = SolveOptions::default();
            let r = Solver::new().solve(points, closed, scheme, &shape);
            let what = format!("{what} {scheme:?}");
            check_solve2d(points, closed, scheme, &shape, &opts, &r, &what);
            r
        })
        .collect()
}

/// Every 2D scheme solves (and the oracle accepts the curve).
fn all_solve(points: &[Point], closed: bool, what: &str) -> Vec<Spline> {
    solve_all(points, closed, what)
        .into_iter()
        .zip(SCHEMES)
        .map(|(r, (scheme, _))| r.unwrap_or_else(|e| panic!("{what} {scheme:?}: {e}")))
        .collect()
}

/// The B-spline (open and closed as asked), checked by the oracle.
fn bspline(points: &[Point], closed: bool, what: &str) -> Result<BSpline, Error> {
    let r = BSpline::new(points, closed);
    check_bspline2d(points, closed, &r, what);
    r
}

/// The κ-space curve of the points lifted to 3D (z from `lift`), checked by the oracle.
fn space(
    points: &[Point],
    closed: bool,
    lift: impl Fn(usize) -> f64,
    what: &str,
) -> Result<SpaceCurve, Error> {
    let pts: Vec<Point3> = points
        .iter()
        .enumerate()
        .map(|(i, p)| Point3::new(p.x, p.y, lift(i)))
        .collect();
    let options = SpaceOptions::default();
    let r = SpaceCurve::new(&pts, closed, &options);
    check_space(&pts, closed, &options, &r, what);
    r
}

fn pentagon() -> Vec<Point> {
    (0..5)
        .map(|i| {
            let th = i as f64 * TAU / 5.0 + 0.3;
            Point::new(100.0 * th.cos(), 80.0 * th.sin())
        })
        .collect()
}

fn circle(n: usize, r: f64) -> Vec<Point> {
    (0..n)
        .map(|i| {
            let th = i as f64 * TAU / n as f64;
            Point::new(r * th.cos(), r * th.sin())
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Repeated and near-repeated points

#[test]
fn repeated_points_are_named() {
    let mut pts = pentagon();
    pts.insert(2, pts[1]);
    for (r, (scheme, _)) in solve_all(&pts, true, "repeated").into_iter().zip(SCHEMES) {
        assert_eq!(
            r.unwrap_err(),
            Error::RepeatedPoint { index: 1, next: 2 },
            "{scheme:?}"
        );
    }
    assert_eq!(
        bspline(&pts, false, "repeated").unwrap_err(),
        Error::RepeatedPoint { index: 1, next: 2 }
    );
    assert_eq!(
        space(&pts, true, |_| 0.0, "repeated").unwrap_err(),
        Error::RepeatedPoint { index: 1, next: 2 }
    );
    // A closed curve whose last point repeats the first: the closing pair.
    let mut closed = pentagon();
    closed.push(closed[0]);
    for r in solve_all(&closed, true, "closing repeat") {
        assert_eq!(r.unwrap_err(), Error::RepeatedPoint { index: 5, next: 0 });
    }
    assert_eq!(
        bspline(&closed, true, "closing repeat").unwrap_err(),
        Error::RepeatedPoint { index: 5, next: 0 }
    );
    // ... which an open curve accepts (a loop that starts where it ends).
    all_solve(&closed, false, "open loop");
    bspline(&closed, false, "open loop").unwrap();
    // Hermite: the two ends coincide.
    let h = Hermite::g1(Point::new(3.0, 4.0), 0.0, Point::new(3.0, 4.0), 1.0);
    assert_eq!(
        h.solve(&Profile::clothoid()).unwrap_err(),
        Error::RepeatedPoint { index: 0, next: 1 }
    );
}

#[test]
fn near_repeated_points() {
    // Within 1e-12 of the drawing size: repeated. Just above: a curve (a tight turn).
    for (eps, repeated) in [(1e-13, true), (1e-9, false), (1e-6, false)] {
        let mut pts = pentagon();
        let size = size_of(&arrays(&pts));
        let near = pts[1] + kurbo::Vec2::new(eps * size, 0.0);
        pts.insert(2, near);
        let what = format!("near-repeated {eps:e}");
        let results = solve_all(&pts, false, &what);
        let b = bspline(&pts, false, &what);
        if repeated {
            for r in results {
                assert_eq!(
                    r.unwrap_err(),
                    Error::RepeatedPoint { index: 1, next: 2 },
                    "{what}"
                );
            }
            assert_eq!(b.unwrap_err(), Error::RepeatedPoint { index: 1, next: 2 });
        } else {
            // Every scheme either solves (checked by the oracle) or reports non-convergence.
            for r in results {
                assert!(
                    matches!(r, Ok(_) | Err(Error::NotConverged { .. })),
                    "{what}: {r:?}"
                );
            }
            // The B-spline interpolates them too (a sharp turn, checked by the oracle).
            assert!(b.is_ok(), "{what}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Collinear runs and collinear input

#[test]
fn collinear_run_between_curved_pieces() {
    // A rounded rectangle outline whose bottom side has three collinear points.
    let pts = [
        Point::new(0.0, 0.0),
        Point::new(50.0, 0.0),
        Point::new(100.0, 0.0),
        Point::new(150.0, 0.0),
        Point::new(170.0, 40.0),
        Point::new(75.0, 80.0),
        Point::new(-20.0, 40.0),
    ];
    let curves = all_solve(&pts, true, "collinear run");
    for c in &curves {
        // The curve still passes through the run's points with its peaks there; between them
        // it bends (a κ-curve cannot be straight between two peaks), but only a little.
        for seg in &c.segments()[1..=2] {
            for i in 0..=16 {
                let y = seg.eval(i as f64 / 16.0).y;
                assert!(y.abs() < 20.0, "{:?}: {y}", c.scheme());
            }
        }
    }
    bspline(&pts, true, "collinear run").unwrap();
    space(&pts, true, |_| 0.0, "collinear run").unwrap();
}

#[test]
fn collinear_input() {
    let line: Vec<Point> = (0..6)
        .map(|i| Point::new(i as f64 * 10.0, i as f64 * 5.0))
        .collect();
    // Open, in order along the line: straight curves (every point is a peak of |κ| = 0).
    for c in all_solve(&line, false, "collinear open") {
        for seg in c.segments() {
            for i in 0..=8 {
                let p = seg.eval(i as f64 / 8.0);
                assert!((p.y - 0.5 * p.x).abs() < 1e-9 * 50.0, "{:?}", c.scheme());
                assert!(seg.curvature(i as f64 / 8.0).abs() < 1e-9);
            }
        }
    }
    let b = bspline(&line, false, "collinear open").unwrap();
    assert_eq!(b.max_curvature().value, 0.0);
    // Closed, or doubling back along the line: no κ-curve exists.
    for r in solve_all(&line, true, "collinear closed") {
        assert_eq!(r.unwrap_err(), Error::Collinear);
    }
    let mut back = line.clone();
    back.swap(2, 4);
    for r in solve_all(&back, false, "collinear doubling back") {
        assert_eq!(r.unwrap_err(), Error::Collinear);
    }
    assert_eq!(
        space(&line, true, |_| 0.0, "collinear closed").unwrap_err(),
        Error::Collinear
    );
    // The B-spline has no such restriction: closed, it runs back and forth on the line, with
    // cusps where it turns (unbounded curvature, reported as infinite).
    let b = bspline(&line, true, "collinear closed").unwrap();
    for t in [0.5, 1.5, 2.5] {
        let p = b.eval(t);
        assert!((p.y - 0.5 * p.x).abs() < 1e-9 * 50.0);
    }
    // Hermite: both tangents along the chord give the straight segment.
    let h = Hermite::g1(
        Point::new(1.0, 1.0),
        PI / 4.0,
        Point::new(4.0, 4.0),
        PI / 4.0,
    );
    for degree in [1, 3, 5] {
        let seg = h.solve(&Profile::free(degree)).unwrap();
        check_hermite(&h, &Profile::free(degree), &Ok(seg.clone()), "straight");
        assert!(
            seg.curvatures().iter().all(|k| k.abs() < 1e-12),
            "{:?}",
            seg.curvatures()
        );
        assert!((kappa::intrinsic::IntrinsicSeg::length(&seg) - 18f64.sqrt()).abs() < 1e-12);
    }
}

// ---------------------------------------------------------------------------------------------
// Two and three points

#[test]
fn two_and_three_points() {
    let two = [Point::new(1.0, 2.0), Point::new(7.0, -3.0)];
    for c in all_solve(&two, false, "two open") {
        assert_eq!(c.segments().len(), 1);
        assert!(c.segments()[0].curvature(0.5).abs() < 1e-12);
    }
    for r in solve_all(&two, true, "two closed") {
        assert!(
            matches!(
                r,
                Err(Error::TooFewPoints {
                    needed: 3,
                    got: 2,
                    ..
                })
            ),
            "{r:?}"
        );
    }
    let b = bspline(&two, false, "two open").unwrap();
    assert!(b.max_curvature().value < 1e-12);
    assert!(matches!(
        bspline(&two, true, "two closed"),
        Err(Error::TooFewPoints {
            needed: 3,
            got: 2,
            ..
        })
    ));
    assert!(matches!(
        space(&two, true, |_| 0.0, "two closed"),
        Err(Error::TooFewPoints { .. })
    ));
    for one in [&two[..1], &[][..]] {
        for r in solve_all(one, false, "one") {
            assert!(
                matches!(r, Err(Error::TooFewPoints { needed: 2, .. })),
                "{r:?}"
            );
        }
    }
    // Three points: a closed curve with three peaks, an open one with one.
    let three = [
        Point::new(0.0, 0.0),
        Point::new(100.0, 0.0),
        Point::new(30.0, 60.0),
    ];
    for c in all_solve(&three, true, "three closed") {
        assert_eq!(c.segments().len(), 3);
    }
    for c in all_solve(&three, false, "three open") {
        assert_eq!(c.segments().len(), 1);
    }
    bspline(&three, true, "three closed").unwrap();
    bspline(&three, false, "three open").unwrap();
    space(&three, true, |i| 10.0 * i as f64, "three closed").unwrap();
    space(&three, false, |i| 10.0 * i as f64, "three open").unwrap();
}

// ---------------------------------------------------------------------------------------------
// Points on a circle: constant curvature, no unique maximum

#[test]
fn points_on_a_circle() {
    for n in [3, 4, 8, 24] {
        let pts = circle(n, 50.0);
        let what = format!("circle {n}");
        for c in all_solve(&pts, true, &what) {
            // Symmetric input, symmetric curve: every peak has the same |κ|, near 1/r.
            let peaks: Vec<f64> = c
                .segments()
                .iter()
                .map(|s| s.curvature(s.t_max).abs())
                .collect();
            let (lo, hi) = peaks
                .iter()
                .fold((f64::MAX, 0.0f64), |(l, h), &k| (l.min(k), h.max(k)));
            assert!(hi - lo <= 1e-9 * hi, "{what} {:?}: {peaks:?}", c.scheme());
            if n >= 8 && c.scheme() == Scheme::Kappa {
                // (The κ-curve through 8 points peaks 8.6 % above 1/r.)
                assert!(
                    (hi * 50.0 - 1.0).abs() < 0.1,
                    "{what} {:?}: {hi}",
                    c.scheme()
                );
            }
        }
        // The B-spline's maximum is attained n times (or 2n), once per stretch.
        let b = bspline(&pts, true, &what).unwrap();
        let max = b.max_curvature();
        assert!(
            max.params.len() % n == 0 && !max.params.is_empty(),
            "{what}: {max:?}"
        );
        if n >= 8 {
            // (5.7 % above 1/r for 8 points.)
            assert!((max.value * 50.0 - 1.0).abs() < 0.1, "{what}: {max:?}");
        }
        space(&pts, true, |_| 0.0, &what).unwrap();
    }
    // Hermite: an arc's G1 data give the arc itself (constant curvature) at every degree.
    let r = 5.0;
    let (a0, a1): (f64, f64) = (0.3, 1.9);
    let h = Hermite::g1(
        Point::new(r * a0.cos(), r * a0.sin()),
        a0 + PI / 2.0,
        Point::new(r * a1.cos(), r * a1.sin()),
        a1 + PI / 2.0,
    );
    for degree in [1, 2, 4] {
        let seg = h.solve(&Profile::free(degree)).unwrap();
        check_hermite(&h, &Profile::free(degree), &Ok(seg.clone()), "arc");
        for &k in seg.curvatures() {
            assert!((k * r - 1.0).abs() < 1e-9, "{:?}", seg.curvatures());
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Near-cusp turns, self-intersections, spirals

#[test]
fn near_cusp_turns() {
    // A spike: the path goes out and comes back almost on itself.
    for width in [10.0, 1.0, 1e-3] {
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(100.0, 0.0),
            Point::new(200.0, width),
            Point::new(100.0, 2.0 * width),
            Point::new(0.0, 60.0),
        ];
        let what = format!("spike {width}");
        for (r, (scheme, _)) in solve_all(&pts, false, &what).into_iter().zip(SCHEMES) {
            match r {
                // The tip is a sharp peak: |κ| there grows as the spike narrows.
                Ok(c) => {
                    let tip = &c.segments()[1];
                    assert!(
                        tip.curvature(tip.t_max).abs() * width > 1e-3,
                        "{what} {scheme:?}"
                    );
                }
                Err(Error::NotConverged { .. }) => assert!(width < 1.0, "{what} {scheme:?}"),
                Err(e) => panic!("{what} {scheme:?}: {e}"),
            }
        }
        bspline(&pts, false, &what).unwrap();
    }
    // Hermite: a U-turn (end tangent opposite to the start).
    let h = Hermite::g1(Point::new(0.0, 0.0), 0.0, Point::new(0.0, 1.0), PI);
    let seg = h.solve(&Profile::clothoid()).unwrap();
    check_hermite(&h, &Profile::clothoid(), &Ok(seg.clone()), "U-turn");
    assert!((seg.turning() - PI).abs() < 1e-9);
}

#[test]
fn self_intersecting_input() {
    // A pentagram {5/2} and a figure eight.
    let star: Vec<Point> = (0..5)
        .map(|i| {
            let th = (2 * i) as f64 * TAU / 5.0;
            Point::new(100.0 * th.cos(), 100.0 * th.sin())
        })
        .collect();
    let eight: Vec<Point> = (0..8)
        .map(|i| {
            let th = i as f64 * TAU / 8.0;
            Point::new(100.0 * th.sin(), 50.0 * (2.0 * th).sin())
        })
        .collect();
    for (pts, what) in [(&star, "pentagram"), (&eight, "figure eight")] {
        let results = solve_all(pts, true, what);
        // Every scheme solves the pentagram; the figure eight (eight points on a lemniscate)
        // does not converge with any of them (reported as NotConverged).
        if what == "pentagram" {
            assert!(results.iter().all(Result::is_ok), "{what}: {results:?}");
        }
        for r in &results {
            assert!(
                matches!(r, Ok(_) | Err(Error::NotConverged { .. })),
                "{what}: {r:?}"
            );
        }
        bspline(pts, true, what).unwrap();
        space(pts, true, |i| (i % 2) as f64 * 10.0, what).unwrap();
    }
}

#[test]
fn spirals() {
    let spiral: Vec<Point> = (0..30)
        .map(|i| {
            let th = 0.5 * i as f64;
            let r = 5.0 + 4.0 * th;
            Point::new(r * th.cos(), r * th.sin())
        })
        .collect();
    for c in all_solve(&spiral, false, "spiral") {
        // The peaks decrease outwards, as the spiral's own curvature does.
        let peaks: Vec<f64> = c
            .segments()
            .iter()
            .map(|s| s.curvature(s.t_max).abs())
            .collect();
        assert!(
            peaks.first().unwrap() > peaks.last().unwrap(),
            "{:?}",
            c.scheme()
        );
    }
    bspline(&spiral, false, "spiral").unwrap();
    let helix = space(&spiral, false, |i| 3.0 * i as f64, "conical helix").unwrap();
    assert!(helix.missed_points().is_empty() || helix.missed_points().len() < 3);
    // A clothoid is the spiral of the Hermite solver: linear curvature.
    let h = Hermite::g1(Point::new(0.0, 0.0), 0.0, Point::new(3.0, 2.0), 2.5);
    let seg = h.solve(&Profile::clothoid()).unwrap();
    check_hermite(&h, &Profile::clothoid(), &Ok(seg), "clothoid");
}

// ---------------------------------------------------------------------------------------------
// Size and scale

/// A jagged closed loop of `n` points (radii alternating 100 and 90): the benchmarks' input.
fn star_loop(n: usize) -> Vec<Point> {
    (0..n)
        .map(|i| {
            let th = i as f64 * TAU / n as f64;
            let r = if i % 2 == 0 { 100.0 } else { 90.0 };
            Point::new(r * th.cos(), r * th.sin())
        })
        .collect()
}

#[test]
fn a_hundred_thousand_points() {
    let pts = star_loop(100_000);
    for (scheme, a) in [(Scheme::Kappa, 2.0 / 3.0), (Scheme::EkCubic, 0.85)] {
        let shape = shape(scheme, a);
        let opts = SolveOptions::default();
        let r = Solver::new().solve(&pts, true, scheme, &shape);
        // 1e-12 is at the edge of double precision at this size: converged, or reported.
        match &r {
            Ok(c) => {
                assert_eq!(c.segments().len(), pts.len());
                check_solve2d(&pts, true, scheme, &shape, &opts, &r, "1e5 points");
            }
            Err(Error::NotConverged { residual, .. }) => assert!(*residual < 1e-10),
            Err(e) => panic!("{scheme:?}: {e}"),
        }
    }
    let b = bspline(&pts, true, "1e5 points").unwrap();
    assert_eq!(b.segment_count(), pts.len());
    let pts3: Vec<Point3> = pts
        .iter()
        .enumerate()
        .map(|(i, p)| Point3::new(p.x, p.y, (i % 2) as f64))
        .collect();
    let b3 = BSpline3::new(&pts3, true);
    check_bspline3d(&pts3, true, &b3, "1e5 points 3D");
}

#[test]
fn long_curves_open_and_closed_in_every_scheme() {
    // Curves of thousands of points are solved in two halves and a border, side by side:
    // open and closed, every 2D scheme, and the κ-space chain in 3D.
    let closed = star_loop(4_001);
    all_solve(&closed, true, "4001-point loop");
    let open: Vec<Point> = (0..3_000)
        .map(|i| {
            let x = i as f64;
            let wobble = if i % 2 == 0 { 3.0 } else { -3.0 };
            Point::new(x, 40.0 * (x * 0.013).sin() + wobble)
        })
        .collect();
    all_solve(&open, false, "3000-point open curve");
    space(&closed, true, |i| (i % 3) as f64, "4001-point loop in 3D").unwrap();
    space(
        &open,
        false,
        |i| 2.0 * (i % 2) as f64,
        "3000-point open curve in 3D",
    )
    .unwrap();
}

#[test]
fn coordinates_at_1e_minus_9_and_1e9() {
    let base = pentagon();
    let reference = all_solve(&base, true, "unit");
    for (scale, offset) in [(1e-9, 0.0), (1e9, 0.0), (1e-9, 1.0), (1e9, 1e9)] {
        let pts: Vec<Point> = base
            .iter()
            .map(|p| Point::new(p.x * scale + offset, p.y * scale - offset))
            .collect();
        let what = format!("scale {scale:e} offset {offset:e}");
        for (c, r) in all_solve(&pts, true, &what).iter().zip(&reference) {
            // The same curve, scaled: the peak parameters agree.
            for (s, t) in c.segments().iter().zip(r.segments()) {
                let allowed = 1e-9 + 1e-3 * (offset / (scale * 100.0)) * f64::EPSILON * 1e6;
                assert!(
                    (s.t_max - t.t_max).abs() <= allowed,
                    "{what} {:?}",
                    c.scheme()
                );
            }
        }
        let b = bspline(&pts, true, &what).unwrap();
        let b0 = BSpline::new(&base, true).unwrap();
        let (m, m0) = (b.max_curvature(), b0.max_curvature());
        assert!(
            (m.value * scale - m0.value).abs() <= 1e-6 * m0.value,
            "{what}"
        );
        space(&pts, true, |i| scale * i as f64, &what).unwrap();
    }
    // Beyond: extents that overflow f64 are named.
    let far = [
        Point::new(-1e308, 0.0),
        Point::new(1e308, 1.0),
        Point::new(0.0, 1e308),
    ];
    for r in solve_all(&far, true, "overflow") {
        assert_eq!(r.unwrap_err(), Error::ExtentOverflow);
    }
    assert_eq!(
        bspline(&far, true, "overflow").unwrap_err(),
        Error::ExtentOverflow
    );
    // Hermite at both scales.
    for scale in [1e-9, 1e9] {
        let h = Hermite::g2(
            Point::new(0.0, 0.0),
            0.3,
            -0.1 / scale,
            Point::new(10.0 * scale, 4.0 * scale),
            1.6,
            0.3 / scale,
        );
        let r = h.solve(&Profile::free(5));
        check_hermite(&h, &Profile::free(5), &r, "hermite scaled");
        assert!(r.is_ok());
    }
}
