//! Intrinsic curves (seed 003): segments, G1/G2 Hermite interpolation, analysis, splines.

use kappa::fit::FitOptions;
use kappa::intrinsic::{Control, Hermite, IntrinsicSeg, Profile, Turning};
use kappa::Error;
use kurbo::{Affine, ParamCurve, ParamCurveNearest, Point, Vec2};

/// The degree-1 G1 solution equals the clothoid of Bertolazzi & Frego on every problem of the
/// shared 40-digit reference (`tests/data/clothoid_g1.json`), to 1e-8 relative in length and
/// end curvatures.
#[cfg(feature = "serde")]
#[test]
fn intrinsic_g1_degree1_matches_clothoid_reference() {
    let text = include_str!("data/clothoid_g1.json");
    let json: serde_json::Value = serde_json::from_str(text).unwrap();
    let problems = json["problems"].as_array().unwrap();
    assert_eq!(problems.len(), 20);
    let num = |v: &serde_json::Value| -> f64 {
        v.as_f64()
            .unwrap_or_else(|| v.as_str().unwrap().parse::<f64>().unwrap())
    };
    for p in problems {
        let h = Hermite::g1(
            Point::new(num(&p["x0"]), num(&p["y0"])),
            num(&p["theta0"]),
            Point::new(num(&p["x1"]), num(&p["y1"])),
            num(&p["theta1"]),
        );
        let r = &p["ref"];
        let (l, k0, k1) = (num(&r["L"]), num(&r["kappa0"]), num(&r["kappa1"]));
        for degree in [1, 3] {
            let seg = h.solve(&Profile::free(degree)).unwrap();
            let scale = l.recip().max(k0.abs()).max(k1.abs());
            let id = &p["id"];
            assert!(
                (seg.length() - l).abs() <= 1e-8 * l,
                "problem {id}: L {} vs {l}",
                seg.length()
            );
            assert!(
                (seg.curvatures()[0] - k0).abs() <= 1e-8 * scale,
                "problem {id}: κ0 {} vs {k0}",
                seg.curvatures()[0]
            );
            assert!(
                (seg.curvatures()[degree] - k1).abs() <= 1e-8 * scale,
                "problem {id}: κ1"
            );
            assert!(h.end_error(&seg) < 1e-10);
        }
    }
}

/// A small deterministic generator (xorshift64*), so that the random problems are the same
/// on every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// A random solvable problem, generated forward (SPEC §4): a curve with random control
/// curvatures, length, start and (kinds 2, 3) weights is integrated, and its end point, angle
/// and curvature become the data. Kinds: 0 G1 with given interior control curvatures,
/// 1 G2 with linearly interpolated interior, 2 and 3 the same with weights.
fn forward_problem(rng: &mut Rng, kind: usize, n: usize, turn: f64) -> (Hermite, Profile) {
    let l = rng.range(0.5, 3.0);
    let mut k: Vec<f64> = (0..=n).map(|_| rng.range(-turn, turn) / l).collect();
    let start = Point::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0));
    let angle = rng.range(-3.0, 3.0);
    let weights: Option<Vec<f64>> =
        (kind >= 2).then(|| (0..=n).map(|_| rng.range(0.5, 2.0)).collect());
    let g2 = kind % 2 == 1;
    if g2 {
        for i in 2..n - 1 {
            let s = (i - 1) as f64 / (n - 2) as f64;
            k[i] = k[1] + s * (k[n - 1] - k[1]);
        }
    }
    let seg = match &weights {
        None => IntrinsicSeg::new(start, angle, l, &k).unwrap(),
        Some(w) => IntrinsicSeg::rational(start, angle, l, &k, w).unwrap(),
    };
    let mut h =
        Hermite::g1(seg.start(), angle, seg.end(), seg.end_angle()).with_turning(Turning::AsGiven);
    let mut controls = vec![Control::Free; n + 1];
    if g2 {
        h.start.curvature = Some(seg.curvature_at(0.0));
        h.end.curvature = Some(seg.curvature_at(1.0));
    } else {
        for i in 1..n {
            controls[i] = Control::Given(k[i]);
        }
    }
    let profile = Profile { controls, weights };
    (h, profile)
}

/// Thousands of random solvable G1 and G2 problems (polynomial and rational, degrees 1–7,
/// turning up to 6 rad per control curvature): every one is solved, meeting the end
/// conditions to 1e-9 (position relative to the chord, angles, curvatures times the chord).
#[test]
fn intrinsic_forward_problems_solve() {
    let mut rng = Rng(0x1234_5678_9abc_def1);
    let per_kind = 1000;
    for kind in 0..4 {
        let mut worst: f64 = 0.0;
        for case in 0..per_kind {
            let n = if kind % 2 == 0 {
                1 + case % 7
            } else {
                3 + case % 5
            };
            let turn = rng.range(0.2, 6.0);
            let (h, profile) = forward_problem(&mut rng, kind, n, turn);
            let seg = h
                .solve(&profile)
                .unwrap_or_else(|e| panic!("kind {kind} case {case}: {e}: {h:?} {profile:?}"));
            let err = h.end_error(&seg);
            assert!(err <= 1e-9, "kind {kind} case {case}: end error {err}");
            worst = worst.max(err);
        }
        eprintln!("kind {kind}: worst end error {worst:e}");
    }
}

/// The end error is dimensionless: the solution of similar data is the similar curve
/// (length × σ, curvatures / σ).
#[test]
fn intrinsic_similarity_invariance() {
    let h = Hermite::g2(Point::ZERO, 0.2, 0.8, Point::new(1.0, 0.7), 1.4, 1.9);
    let base = h.solve(&Profile::free(5)).unwrap();
    for (sigma, rot, shift) in [
        (3.0, 0.7, Vec2::new(5.0, -2.0)),
        (1e-3, -2.0, Vec2::new(1.0, 1.0)),
    ] {
        let a = Affine::translate(shift) * Affine::rotate(rot) * Affine::scale(sigma);
        let mut g = h;
        g.start.point = a * h.start.point;
        g.end.point = a * h.end.point;
        g.start.angle += rot;
        g.end.angle += rot;
        g.start.curvature = h.start.curvature.map(|k| k / sigma);
        g.end.curvature = h.end.curvature.map(|k| k / sigma);
        let seg = g.solve(&Profile::free(5)).unwrap();
        assert!((seg.length() - sigma * base.length()).abs() < 1e-12 * seg.length());
        for (k, kb) in seg.curvatures().iter().zip(base.curvatures()) {
            assert!((k * sigma - kb).abs() < 1e-9 * (1.0 + kb.abs()), "{k} {kb}");
        }
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            assert!((seg.eval(t) - a * base.eval(t)).hypot() < 1e-12 * sigma);
        }
    }
}

/// A straight chord with both tangents along it gives a straight segment, for G1 of any
/// profile and for G2 with zero end curvatures.
#[test]
fn intrinsic_straight_chord_is_straight() {
    let p0 = Point::new(1.0, 1.0);
    let p1 = Point::new(4.0, 5.0);
    let th = 4f64.atan2(3.0);
    let cases = [
        (Hermite::g1(p0, th, p1, th), Profile::clothoid()),
        (Hermite::g1(p0, th, p1, th), Profile::free(4)),
        (
            Hermite::g1(p0, th, p1, th),
            Profile::new(vec![
                Control::Free,
                Control::Same(0),
                Control::Same(3),
                Control::Free,
            ]),
        ),
        (
            Hermite::g1(p0, th, p1, th),
            Profile::free(3).with_weights(vec![1.0, 2.0, 0.5, 1.0]),
        ),
        (Hermite::g2(p0, th, 0.0, p1, th, 0.0), Profile::free(3)),
        (Hermite::g2(p0, th, 0.0, p1, th, 0.0), Profile::free(6)),
    ];
    for (h, profile) in &cases {
        let seg = h.solve(profile).unwrap();
        assert!((seg.length() - 5.0).abs() < 1e-14, "{}", seg.length());
        assert!(
            seg.curvatures().iter().all(|k| k.abs() < 1e-14),
            "{:?}",
            seg.curvatures()
        );
        assert!(seg.inflections().is_empty());
    }
}

/// Zero net turning: the symmetric S-curve (both tangents at +φ to the chord) solves, with
/// its inflection in the middle and point symmetry about the chord's midpoint.
#[test]
fn intrinsic_symmetric_s_curve() {
    let (p0, p1) = (Point::new(0.0, 0.0), Point::new(2.0, 0.0));
    for phi in [0.2, 0.5, 1.0, 1.5] {
        let cases = [
            (Hermite::g1(p0, phi, p1, phi), Profile::clothoid()),
            (Hermite::g1(p0, phi, p1, phi), Profile::free(5)),
            (
                Hermite::g2(p0, phi, -2.0 * phi, p1, phi, 2.0 * phi),
                Profile::free(3),
            ),
            (Hermite::g2(p0, phi, -1.0, p1, phi, 1.0), Profile::free(5)),
        ];
        for (h, profile) in &cases {
            assert_eq!(h.turning_angle(), 0.0);
            let seg = h.solve(profile).unwrap_or_else(|e| panic!("φ {phi}: {e}"));
            assert!(h.end_error(&seg) < 1e-12);
            assert!(seg.turning().abs() < 1e-12);
            let infl = seg.inflections();
            assert_eq!(infl.len(), 1, "φ {phi}: {infl:?}");
            assert!((infl[0] - 0.5).abs() < 1e-9, "{infl:?}");
            for i in 0..=10 {
                let t = i as f64 / 10.0;
                let (a, b) = (seg.eval(t), seg.eval(1.0 - t));
                assert!((a.midpoint(b) - Point::new(1.0, 0.0)).hypot() < 1e-12);
            }
        }
    }
}

/// Data no curve of the profile meets give the typed error, not a curve.
#[test]
fn intrinsic_unsolvable_is_typed_error() {
    // G2 with a cubic: a straight chord, aligned tangents, but strong equal curvatures at
    // both ends.
    let h = Hermite::g2(Point::ZERO, 0.0, 40.0, Point::new(1.0, 0.0), 0.0, 40.0);
    assert!(matches!(
        h.solve(&Profile::free(3)),
        Err(Error::NoHermiteSolution { .. })
    ));
}

/// Bad input is a typed error.
#[test]
fn intrinsic_bad_hermite_input() {
    let p = Point::new(1.0, 0.0);
    let ok = Hermite::g1(Point::ZERO, 0.0, p, 0.0);
    assert_eq!(
        Hermite::g1(p, 0.0, p, 0.0).solve(&Profile::clothoid()),
        Err(Error::RepeatedPoint { index: 0, next: 1 })
    );
    assert_eq!(
        Hermite::g1(Point::new(f64::NAN, 0.0), 0.0, p, 0.0).solve(&Profile::clothoid()),
        Err(Error::NonFinitePoint { index: 0 })
    );
    let invalid = |h: Hermite, profile: Profile| {
        assert!(
            matches!(h.solve(&profile), Err(Error::InvalidOption(_))),
            "{h:?} {profile:?}"
        )
    };
    invalid(
        Hermite::g1(Point::ZERO, f64::INFINITY, p, 0.0),
        Profile::clothoid(),
    );
    invalid(ok, Profile::free(0));
    invalid(ok, Profile::new(vec![]));
    invalid(
        Hermite::g2(Point::ZERO, 0.0, 1.0, p, 0.0, 1.0),
        Profile::free(2),
    );
    invalid(
        Hermite::g2(Point::ZERO, 0.0, f64::NAN, p, 0.0, 1.0),
        Profile::free(3),
    );
    let mut half = ok;
    half.start.curvature = Some(1.0);
    invalid(half, Profile::free(3));
    invalid(ok, Profile::new(vec![Control::Given(1.0), Control::Free]));
    invalid(
        ok,
        Profile::new(vec![Control::Free, Control::Same(7), Control::Free]),
    );
    invalid(
        ok,
        Profile::new(vec![Control::Free, Control::Given(f64::NAN), Control::Free]),
    );
    invalid(
        ok,
        Profile::new(vec![
            Control::Free,
            Control::Same(2),
            Control::Same(1),
            Control::Free,
        ]),
    );
    invalid(ok, Profile::free(2).with_weights(vec![1.0, -1.0, 1.0]));
    invalid(ok, Profile::free(2).with_weights(vec![1.0, 1.0]));
}

/// The turning is explicit: `AsGiven` with the end angle one turn further winds once more.
#[test]
fn intrinsic_turning_as_given_winds() {
    let p1 = Point::new(1.0, 0.0);
    let near = Hermite::g1(Point::ZERO, 0.5, p1, -0.5);
    let seg = near.solve(&Profile::free(3)).unwrap();
    assert!((seg.turning() + 1.0).abs() < 1e-12);
    let wound = Hermite::g1(Point::ZERO, 0.5, p1, -0.5 + std::f64::consts::TAU)
        .with_turning(Turning::AsGiven);
    assert!((wound.turning_angle() - (std::f64::consts::TAU - 1.0)).abs() < 1e-15);
    let seg = wound.solve(&Profile::free(3)).unwrap();
    assert!(wound.end_error(&seg) < 1e-10);
    assert!((seg.turning() - (std::f64::consts::TAU - 1.0)).abs() < 1e-12);
    // Nearest reduces the same angles to the short turn.
    let nearest = wound.with_turning(Turning::Nearest);
    assert!((nearest.turning_angle() + 1.0).abs() < 1e-12);
}

/// Position quadrature: the reference clothoids, built from their 40-digit length and end
/// curvatures, end at the reference end points to 1e-12 of their length.
#[cfg(feature = "serde")]
#[test]
fn intrinsic_position_accuracy_on_reference_clothoids() {
    let json: serde_json::Value =
        serde_json::from_str(include_str!("data/clothoid_g1.json")).unwrap();
    let num = |v: &serde_json::Value| -> f64 {
        v.as_f64()
            .unwrap_or_else(|| v.as_str().unwrap().parse::<f64>().unwrap())
    };
    for p in json["problems"].as_array().unwrap() {
        let r = &p["ref"];
        let l = num(&r["L"]);
        let seg = IntrinsicSeg::new(
            Point::new(num(&p["x0"]), num(&p["y0"])),
            num(&p["theta0"]),
            l,
            &[num(&r["kappa0"]), num(&r["kappa1"])],
        )
        .unwrap();
        let end = Point::new(num(&p["x1"]), num(&p["y1"]));
        assert!(
            (seg.end() - end).hypot() <= 1e-12 * l,
            "problem {}",
            p["id"]
        );
    }
}

/// Sign changes of `f` on a uniform grid of `samples` intervals.
fn sampled_sign_changes(f: impl Fn(f64) -> f64, samples: usize) -> Vec<f64> {
    let mut out = Vec::new();
    let mut prev = f(0.0);
    for i in 1..=samples {
        let t = i as f64 / samples as f64;
        let v = f(t);
        if v != 0.0 && prev != 0.0 && (v > 0.0) != (prev > 0.0) {
            out.push(t - 0.5 / samples as f64);
        }
        if v != 0.0 {
            prev = v;
        }
    }
    out
}

/// Inflections (roots of K) and curvature extrema (roots of K′, degree 2n − 2 for rational
/// functions) agree with dense sampling of random curvature functions.
#[test]
fn intrinsic_analysis_matches_sampling() {
    let mut rng = Rng(42);
    let samples = 20_000;
    let h = 1.0 / samples as f64;
    for case in 0..300 {
        let n = 1 + case % 8;
        let k: Vec<f64> = (0..=n).map(|_| rng.range(-3.0, 3.0)).collect();
        let seg = if case % 2 == 0 {
            IntrinsicSeg::new(Point::ZERO, 0.0, 1.0, &k).unwrap()
        } else {
            let w: Vec<f64> = (0..=n).map(|_| rng.range(0.3, 3.0)).collect();
            IntrinsicSeg::rational(Point::ZERO, 0.0, 1.0, &k, &w).unwrap()
        };
        for (found, sampled) in [
            (
                seg.inflections(),
                sampled_sign_changes(|t| seg.curvature_at(t), samples),
            ),
            (
                seg.curvature_extrema(),
                sampled_sign_changes(|t| seg.curvature_deriv_at(t), samples),
            ),
        ] {
            assert_eq!(
                found.len(),
                sampled.len(),
                "case {case}: {found:?} vs {sampled:?}"
            );
            for (a, b) in found.iter().zip(&sampled) {
                assert!((a - b).abs() <= h, "case {case}: {found:?} vs {sampled:?}");
            }
        }
        assert_eq!(seg.is_monotone(), seg.curvature_extrema().is_empty());
        // The curvature derivative is K′/L: check it against finite differences.
        let t = 0.37;
        let fd = (seg.curvature_at(t + 1e-6) - seg.curvature_at(t - 1e-6)) / 2e-6;
        assert!((seg.curvature_deriv_at(t) - fd).abs() < 1e-6 * (1.0 + fd.abs()));
    }
}

/// The fitted BezPath stays within the adapter's tolerance of the exact curve, checked by
/// sampling the exact curve densely.
#[test]
fn intrinsic_fitted_path_within_tolerance() {
    let h = Hermite::g1(Point::ZERO, 0.4, Point::new(10.0, 3.0), 2.5);
    let profiles = [
        Profile::clothoid(),
        Profile::new(vec![
            Control::Free,
            Control::Same(0),
            Control::Same(3),
            Control::Free,
        ]),
        Profile::free(3).with_weights(vec![1.0, 4.0, 0.5, 1.0]),
    ];
    for profile in &profiles {
        let seg = h.solve(profile).unwrap();
        for tol in [1e-2, 1e-4, 1e-6] {
            let fitted = seg.to_bezpath(&FitOptions::absolute(tol)).unwrap();
            assert!(fitted.max_distance <= tol, "{fitted:?}");
            let cubics: Vec<_> = fitted.path.segments().collect();
            for i in 0..=1000 {
                let p = seg.eval(i as f64 / 1000.0);
                let d = cubics
                    .iter()
                    .map(|c| c.nearest(p, 1e-12).distance_sq)
                    .fold(f64::INFINITY, f64::min)
                    .sqrt();
                assert!(d <= tol, "tolerance {tol}: distance {d}");
            }
        }
    }
}

/// An intrinsic spline through the points of a drawing: it interpolates them, its joints are
/// G2 (position, tangent angle, curvature) and the curvatures at the points are those of the
/// εκ-curve it was estimated from.
#[test]
fn intrinsic_spline_is_g2_and_interpolates() {
    use kappa::intrinsic::{IntrinsicSpline, SplineOptions};
    use kappa::{builtin_design, Design};
    let design = Design::from_json(builtin_design("bear").unwrap()).unwrap();
    let mut worst: f64 = 0.0;
    for c in design.curves.iter().filter(|c| c.points.len() >= 3) {
        let pts = c.kurbo_points();
        let closed = c.is_closed();
        let size = design.size();
        let spline = IntrinsicSpline::new(&pts, closed, &SplineOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
        let segs = spline.segments();
        assert_eq!(segs.len(), if closed { pts.len() } else { pts.len() - 1 });
        for (i, seg) in segs.iter().enumerate() {
            let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
            worst = worst
                .max(seg.start().distance(a) / size)
                .max(seg.end().distance(b) / size);
        }
        let joints = if closed { segs.len() } else { segs.len() - 1 };
        for i in 0..joints {
            let (s, t) = (&segs[i], &segs[(i + 1) % segs.len()]);
            let da = (s.end_angle() - t.start_angle()).rem_euclid(std::f64::consts::TAU);
            let da = da.min(std::f64::consts::TAU - da);
            assert!(da < 1e-9, "joint {i}: angle jump {da}");
            let dk = (s.curvature_at(1.0) - t.curvature_at(0.0)).abs() * size;
            assert!(dk < 1e-9, "joint {i}: curvature jump {dk}");
        }
    }
    assert!(worst < 1e-9, "{worst}");
}

/// The sampled viable region (seed 003 Fig. 4): the clothoid's own end curvatures are viable
/// (the linear profile of any degree reproduces the clothoid, whose curvature is linear), every
/// cell marked monotone is, and the region grows with the degree, as the paper reports.
#[test]
fn intrinsic_viable_region_grows_with_degree() {
    use kappa::intrinsic::{viable_region, Viability};
    let data = Hermite::g1(
        Point::ZERO,
        0.0,
        Point::new(1.0, 0.4),
        std::f64::consts::FRAC_PI_3,
    );
    let c = data.solve(&Profile::clothoid()).unwrap();
    let (k0, k1) = (c.curvature_at(0.0), c.curvature_at(1.0));
    let mut counts = Vec::new();
    for degree in [3, 5, 10] {
        // A grid through the clothoid's ends (k0, k1) at index (5, 5).
        let r = viable_region(&data, degree, k0 - 0.5..k0 + 1.5, k1 - 2.5..k1 + 7.5, 21).unwrap();
        assert_eq!(r.at(5, 5), Viability::Monotone, "degree {degree}");
        assert_eq!(r.cells.len(), 21 * 21);
        for j in 0..21 {
            for i in 0..21 {
                if r.at(i, j) == Viability::Monotone {
                    let mut h = data;
                    h.start.curvature = Some(r.k_start[i]);
                    h.end.curvature = Some(r.k_end[j]);
                    let seg = h.solve(&Profile::free(degree)).unwrap();
                    // Dense check of monotone, sign-constant curvature.
                    let ks: Vec<f64> = (0..=400)
                        .map(|s| seg.curvature_at(s as f64 / 400.0))
                        .collect();
                    let inc = ks.windows(2).all(|w| w[1] >= w[0] - 1e-12);
                    let dec = ks.windows(2).all(|w| w[1] <= w[0] + 1e-12);
                    assert!(inc || dec, "degree {degree} ({i}, {j})");
                    assert!(ks.iter().all(|k| *k >= -1e-12) || ks.iter().all(|k| *k <= 1e-12));
                }
            }
        }
        counts.push(r.count(Viability::Monotone));
    }
    assert!(counts[0] < counts[1] && counts[1] < counts[2], "{counts:?}");
    assert!(viable_region(&data, 2, 0.0..1.0, 0.0..1.0, 5).is_err());
    assert!(viable_region(&data, 3, 0.0..1.0, 0.0..1.0, 1).is_err());
    assert!(viable_region(&data, 3, 1.0..0.0, 0.0..1.0, 5).is_err());
}
