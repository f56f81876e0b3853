//! Integration tests of κ-space curves (`kappa::space`, seed paper 004): G2 in 3D at every
//! joint, interpolation, peaks, the quartics' own extrema, planar input, options, errors,
//! projections, exports and golden pictures.

mod common;

use common::Lcg;
use kappa::analysis::{CurvatureAnalysis, SpaceBez};
use kappa::fit::FitOptions;
use kappa::space::{
    Gamma, PeakAtJoint, Piece, Projection, Replace, SpaceCurve, SpaceOptions, View,
};
use kappa::{Error, Point3, Scheme, Shape, Solver3, Spline, Vec3};
use kurbo::{ParamCurve, ParamCurveNearest, PathEl, Point};
use proptest::prelude::*;

// ---------------------------------------------------------------------------------------------
// Inputs

/// A random star-shaped loop in 3D: sorted angles, radii in [0.35, 1], heights in
/// [-0.5, 0.5], all times `scale`, shifted by up to 10 × `scale`. Open curves drop the last
/// point.
fn star3(raw: &[(f64, f64, f64)], scale: f64, shift: f64, closed: bool) -> Vec<Point3> {
    let mut v = raw.to_vec();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    let n = v.len();
    let shift = shift * scale;
    let mut pts: Vec<Point3> = v
        .iter()
        .enumerate()
        .map(|(i, &(jitter, r, z))| {
            let th = (i as f64 + 0.6 * jitter) / n as f64 * std::f64::consts::TAU;
            Point3::new(
                shift + scale * r * th.cos(),
                -shift + scale * r * th.sin(),
                0.5 * shift + scale * z,
            )
        })
        .collect();
    if !closed {
        pts.pop();
    }
    pts
}

fn random_input(rng: &mut Lcg, closed: bool) -> Vec<Point3> {
    let n = 4 + (rng.next() * 18.0) as usize;
    let raw: Vec<(f64, f64, f64)> = (0..n)
        .map(|_| (rng.next(), 0.35 + 0.65 * rng.next(), rng.next() - 0.5))
        .collect();
    let scale = 10f64.powf(rng.next() * 6.0 - 3.0);
    star3(&raw, scale, 20.0 * rng.next() - 10.0, closed)
}

/// Points on a helix of radius 50 and pitch 12 per radian, as an open curve.
fn helix(n: usize) -> Vec<Point3> {
    (0..n)
        .map(|i| {
            let th = 0.9 * i as f64;
            Point3::new(50.0 * th.cos(), 50.0 * th.sin(), 12.0 * th)
        })
        .collect()
}

/// Points on the trefoil knot `(sin t + 2 sin 2t, cos t − 2 cos 2t, −sin 3t)`, as a closed
/// curve.
fn trefoil(n: usize) -> Vec<Point3> {
    (0..n)
        .map(|i| {
            let t = i as f64 / n as f64 * std::f64::consts::TAU;
            Point3::new(
                30.0 * (t.sin() + 2.0 * (2.0 * t).sin()),
                30.0 * (t.cos() - 2.0 * (2.0 * t).cos()),
                -30.0 * (3.0 * t).sin(),
            )
        })
        .collect()
}

fn size_of(pts: &[Point3]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in pts {
        for (k, v) in [p.x, p.y, p.z].into_iter().enumerate() {
            lo[k] = lo[k].min(v);
            hi[k] = hi[k].max(v);
        }
    }
    (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max)
}

/// The input points that have a peak (all of a closed curve, the interior of an open one).
fn peak_inputs(pts: &[Point3], closed: bool) -> &[Point3] {
    if closed {
        pts
    } else {
        &pts[1..pts.len() - 1]
    }
}

// ---------------------------------------------------------------------------------------------
// The properties of the paper, checked on one curve

/// What [`check_curve`] measured.
#[derive(Default, Debug)]
struct Measured {
    joints: usize,
    /// Joints whose relative curvature-vector gap exceeds 1e-9 (allowed only at the
    /// floating-point floor, see `g2_floor`).
    above_1e9: usize,
    worst_gap: f64,
}

/// The rounding floor of the curvature-vector gap at a joint next to a quartic: the
/// curvature at a quartic end comes from a second difference of control points `h` apart
/// (its shorter end handle), each stored to within `ε · X` (X the largest coordinate), so
/// the relative gap cannot be resolved below `ε X / (κ h²)`. Measured on 58 094 joints of
/// random inputs: the gap stays below 1.12 × this.
fn g2_floor(curve: &SpaceCurve, before: usize, after: usize, x: f64) -> f64 {
    let segs = curve.segments();
    let quartic = if segs[before].degree() == 4 {
        &segs[before]
    } else {
        &segs[after]
    };
    let p = quartic.control_points();
    if p.len() != 5 {
        return 0.0;
    }
    let h = p[0].distance(p[1]).min(p[3].distance(p[4]));
    let kappa = CurvatureAnalysis::curvature(&segs[before], 1.0)
        .max(CurvatureAnalysis::curvature(&segs[after], 0.0));
    f64::EPSILON * x / (kappa * h * h)
}

/// Checks G0/G1/G2 at every joint of the chain (through `kappa::analysis`), interpolation of
/// every input point that was not given up, and that |κ| peaks at each input point on the
/// quadratic piece holding it.
fn check_curve(curve: &SpaceCurve, pts: &[Point3], closed: bool, label: &str) -> Measured {
    check_curve_with(curve, pts, closed, label, 1e-4)
}

/// [`check_curve`] with the allowed distance of a point given up at a joint, relative to
/// the drawing size (the miss is O(r²) in the replaced fraction r).
fn check_curve_with(
    curve: &SpaceCurve,
    pts: &[Point3],
    closed: bool,
    label: &str,
    miss_tolerance: f64,
) -> Measured {
    let size = size_of(pts);
    let x = curve
        .segments()
        .iter()
        .flat_map(|s| s.control_points().iter())
        .map(|p| p.x.abs().max(p.y.abs()).max(p.z.abs()))
        .fold(0.0, f64::max);
    let mut m = Measured::default();
    let gaps = curve.curvature_vector_gaps();
    let joints = curve.continuity();
    let n = curve.segments().len();
    assert_eq!(joints.len(), if closed { n } else { n - 1 }, "{label}");
    for (j, gap) in joints.iter().zip(&gaps) {
        let c = j.continuity;
        assert_eq!(c.position_gap, 0.0, "{label}: G0 at {j:?}");
        assert!(c.tangent_angle < 1e-9, "{label}: G1 at {j:?}");
        let allowed = 1e-9f64.max(4.0 * g2_floor(curve, j.before, j.after, x));
        assert!(
            *gap <= allowed,
            "{label}: G2 gap {gap:e} (allowed {allowed:e}) at {j:?}"
        );
        m.joints += 1;
        m.worst_gap = m.worst_gap.max(*gap);
        if *gap > 1e-9 {
            m.above_1e9 += 1;
        }
    }
    // Interpolation and peaks.
    let inputs = peak_inputs(pts, closed);
    assert_eq!(curve.point_params().len(), inputs.len(), "{label}");
    let missed: Vec<usize> = curve.missed_points().iter().map(|m| m.0).collect();
    for (k, (&(seg, t), p)) in curve.point_params().iter().zip(inputs).enumerate() {
        let s = &curve.segments()[seg];
        let d = s.eval(t).distance(*p);
        if missed.contains(&k) {
            // Given up at a joint: near the curve, O(r²) away.
            assert!(
                d <= miss_tolerance * size,
                "{label}: missed point {k} is {d} away (size {size})"
            );
            continue;
        }
        assert!(d <= 1e-9 * size, "{label}: point {k} is {d} away");
        assert_eq!(
            s.degree(),
            2,
            "{label}: point {k} lies on a quadratic piece"
        );
        let max = s.max_curvature();
        let k_here = CurvatureAnalysis::curvature(s, t);
        assert!(
            max.params.iter().any(|&u| (u - t).abs() <= 1e-6) || k_here >= max.value * (1.0 - 1e-9),
            "{label}: point {k}: |κ| {k_here} at t = {t}, max {} at {:?}",
            max.value,
            max.params
        );
    }
    // Open curves still start and end at the first and last points.
    if !closed {
        let (a, b) = curve.ends();
        assert_eq!(a, pts[0], "{label}");
        assert_eq!(b, pts[pts.len() - 1], "{label}");
    }
    m
}

// ---------------------------------------------------------------------------------------------
// G2 over random inputs

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn random_space_curves_are_g2_and_interpolate(
        raw in prop::collection::vec((0.0f64..1.0, 0.35f64..1.0, -0.5f64..0.5), 4..20),
        scale in 1e-3f64..1e3,
        shift in -10.0f64..10.0,
        closed in any::<bool>(),
        r in prop::sample::select(vec![0.01, 0.05, 0.2]),
    ) {
        let pts = star3(&raw, scale, shift, closed);
        let options = SpaceOptions::default().with_replace(r);
        match SpaceCurve::new(&pts, closed, &options) {
            Ok(curve) => {
                // A point given up at a joint is O(r²) off the curve.
                let miss = 1e-4f64.max(1e-2 * r * r);
                check_curve_with(&curve, &pts, closed, &format!("proptest r={r}"), miss);
            }
            Err(Error::NotConverged { .. }) => {}
            Err(e) => panic!("{e}"),
        }
    }
}

#[test]
fn thousands_of_random_space_curves_are_g2() {
    // 1500 closed and 1500 open random loops (4–21 points, sizes 1e-3 … 1e3, offsets up to
    // 10 × the size, heights up to ± half the size), default replacement.
    let mut rng = Lcg(2024);
    let mut total = Measured::default();
    let (mut solved, mut failed, mut missed, mut curves_missing) = (0, 0, 0, 0);
    let mut worst_miss: f64 = 0.0;
    for case in 0..3000 {
        let closed = case % 2 == 0;
        let pts = random_input(&mut rng, closed);
        match SpaceCurve::new(&pts, closed, &SpaceOptions::default()) {
            Ok(curve) => {
                let m = check_curve(&curve, &pts, closed, &format!("case {case}"));
                total.joints += m.joints;
                total.above_1e9 += m.above_1e9;
                total.worst_gap = total.worst_gap.max(m.worst_gap);
                missed += curve.missed_points().len();
                if !curve.missed_points().is_empty() {
                    curves_missing += 1;
                }
                let size = size_of(&pts);
                for &(_, d) in curve.missed_points() {
                    worst_miss = worst_miss.max(d / size);
                }
                solved += 1;
            }
            Err(Error::NotConverged { .. }) => failed += 1,
            Err(e) => panic!("case {case}: {e}"),
        }
    }
    println!(
        "{solved} curves ({failed} not converged), {} joints, {} above 1e-9 (at the rounding \
         floor), worst gap {:e}, {missed} points given up at joints on {curves_missing} \
         curves (at most {worst_miss:e} × the size away)",
        total.joints, total.above_1e9, total.worst_gap
    );
    assert!(solved >= 2950, "{solved}");
    // Almost every joint is G2 to 1e-9 relative; the rest (joints next to very short
    // segments of drawings far from the origin) sit at the floor checked above.
    assert!(total.above_1e9 * 200 <= total.joints, "{total:?}");
}

#[test]
fn helix_and_trefoil_are_g2_with_their_peaks_in_place() {
    for (pts, closed) in [(helix(10), false), (trefoil(12), true), (helix(4), false)] {
        for replace in [Replace::DEFAULT, Replace::fraction(0.1), Replace::FULL] {
            let options = SpaceOptions {
                replace,
                ..SpaceOptions::default()
            };
            let curve = SpaceCurve::new(&pts, closed, &options).unwrap();
            if replace == Replace::FULL {
                // Every stretch between input points is one quartic (an open curve keeps
                // its first and last quadratic pieces); the points are their ends and the
                // chain is G2 there.
                let n = curve.len();
                let inner = if closed { 0..n } else { 1..n - 1 };
                assert!(curve.segments()[inner].iter().all(|s| s.degree() == 4));
                let m = check_curve_without_peaks(&curve, &pts, closed);
                assert_eq!(m.above_1e9, 0);
                // The peaks leave the points (seed 004 Fig. 4: "the positions of the curvature
                // extrema are not preserved"): count the points that are no longer a local
                // maximum of |κ| along the chain.
                let n = curve.len();
                let moved = curve
                    .point_params()
                    .iter()
                    .filter(|&&(seg, t)| {
                        let u = seg as f64 + t;
                        let k = curve.curvature(u);
                        let before = if u > 0.0 || closed {
                            curve.curvature((u - 1e-4).rem_euclid(n as f64))
                        } else {
                            0.0
                        };
                        k < curve.curvature(u + 1e-4).max(before)
                    })
                    .count();
                println!(
                    "full replacement: {moved} of {} points no longer a peak",
                    curve.point_params().len()
                );
                assert!(moved > 0);
            } else {
                let m = check_curve(&curve, &pts, closed, "helix/trefoil");
                assert_eq!(m.above_1e9, 0, "{m:?}");
                assert!(curve.missed_points().is_empty());
            }
        }
    }
}

/// [`check_curve`] for full replacement, where the points end quartics: G2 and interpolation
/// only.
fn check_curve_without_peaks(curve: &SpaceCurve, pts: &[Point3], closed: bool) -> Measured {
    let size = size_of(pts);
    let mut m = Measured::default();
    for (j, gap) in curve.continuity().iter().zip(curve.curvature_vector_gaps()) {
        assert_eq!(j.continuity.position_gap, 0.0);
        assert!(j.continuity.tangent_angle < 1e-9);
        m.joints += 1;
        if gap > 1e-9 {
            m.above_1e9 += 1;
        }
    }
    for (&(seg, t), p) in curve.point_params().iter().zip(peak_inputs(pts, closed)) {
        assert!(curve.segments()[seg].eval(t).distance(*p) <= 1e-9 * size);
    }
    m
}

#[test]
fn quadratic_joints_alone_are_only_g1() {
    // Without replacement the chain is the κ-curve itself: equal |κ| at the joints, but the
    // curvature vectors point into different planes (why the quartics are needed).
    let pts = helix(8);
    let options = SpaceOptions {
        replace: Replace::None,
        ..SpaceOptions::default()
    };
    let curve = SpaceCurve::new(&pts, false, &options).unwrap();
    let spline = curve.spline();
    assert_eq!(curve.segments().len(), spline.segments().len());
    for (s, q) in curve.segments().iter().zip(spline.segments()) {
        assert_eq!(s.control_points(), &q.q[..]);
    }
    for (j, gap) in curve.continuity().iter().zip(curve.curvature_vector_gaps()) {
        let c = j.continuity;
        let k = CurvatureAnalysis::curvature(&curve.segments()[j.before], 1.0);
        assert!(c.curvature_diff <= 1e-9 * k, "{c:?}");
        assert!(gap > 1e-3, "the planes differ: gap {gap}");
    }
    assert!(curve.joints().iter().all(|j| j.quartic.is_none()));
}

// ---------------------------------------------------------------------------------------------
// The quartics' own extrema

/// `(max |κ| over the quartic, its arc length, the curvature of the κ-curve at the joint)`
/// per joint, for the replaced fraction `r`.
fn quartic_stats(pts: &[Point3], closed: bool, r: f64) -> Vec<(f64, f64, f64, Vec<f64>)> {
    let curve = SpaceCurve::new(pts, closed, &SpaceOptions::default().with_replace(r)).unwrap();
    let extrema = curve.quartic_extrema();
    let spline_segs = curve.spline().segments();
    curve
        .joints()
        .iter()
        .enumerate()
        .map(|(j, joint)| {
            let q = joint.quartic.expect("every joint replaced");
            let s = &curve.segments()[q.segment];
            let max = s.max_curvature().value;
            let len = s.arclen(1e-12);
            let left = SpaceBez::new(&spline_segs[joint.before].control_points()).unwrap();
            let k_joint = CurvatureAnalysis::curvature(&left, 1.0);
            let ts: Vec<f64> = extrema
                .iter()
                .filter(|e| e.joint == j)
                .map(|e| e.t)
                .collect();
            (max, len, k_joint, ts)
        })
        .collect()
}

#[test]
fn quartic_extremum_is_reported_and_shrinks_with_the_replacement() {
    let rs = [0.1, 0.03, 0.01, 0.003];
    for (pts, closed) in [(helix(10), false), (trefoil(12), true)] {
        let stats: Vec<_> = rs.iter().map(|&r| quartic_stats(&pts, closed, r)).collect();
        for j in 0..stats[0].len() {
            for (k, &r) in rs.iter().enumerate() {
                let (max, len, k_joint, ref ts) = stats[k][j];
                let curve = SpaceCurve::new(&pts, closed, &SpaceOptions::default().with_replace(r))
                    .unwrap();
                let s = &curve.segments()[curve.joints()[j].quartic.unwrap().segment];
                // The reported extrema are the interior stationary points of |κ| on the
                // quartic: check them against a dense sampling (independent of the roots).
                let n = 4000;
                let kap: Vec<f64> = (0..=n)
                    .map(|i| CurvatureAnalysis::curvature(s, i as f64 / n as f64))
                    .collect();
                for i in 1..n {
                    let (a, b, c) = (kap[i - 1], kap[i], kap[i + 1]);
                    let bump =
                        (b - a) * (c - b) < 0.0 && (b - a).abs().max((c - b).abs()) > 1e-9 * b;
                    if bump {
                        let t = i as f64 / n as f64;
                        assert!(
                            ts.iter().any(|&u| (u - t).abs() <= 2.0 / n as f64),
                            "joint {j}, r {r}: sampled extremum at {t} not in {ts:?}"
                        );
                    }
                }
                assert!(
                    !ts.is_empty(),
                    "joint {j}, r {r}: the quartic adds an extremum"
                );
                // It shrinks with the replacement: the quartic (and so the distance from any
                // of its extrema to the joint) is r times a length that converges …
                if k + 1 < rs.len() {
                    let (max2, len2, _, _) = stats[k + 1][j];
                    let ratio = (len / r) / (len2 / rs[k + 1]);
                    assert!(
                        (ratio - 1.0).abs() < 0.1,
                        "joint {j}: length/r ratio {ratio}"
                    );
                    // … and the largest |κ| on it decreases towards its limit (a fixed
                    // multiple of the curvature at the joint set by the angle between the
                    // two osculating planes, not 0).
                    assert!(
                        max2 <= max * (1.0 + 1e-12),
                        "joint {j}: {max} -> {max2} at r {r}"
                    );
                }
                // The extra extremum stays below the input points' peaks (seed 004 §3.2:
                // "relatively small").
                let peaks = curve.max_curvature().value;
                assert!(max < peaks, "joint {j}: quartic max {max} vs peaks {peaks}");
                assert!(max >= k_joint * 0.5, "joint {j}");
            }
            // The limit: the quartic's excess over the joint curvature changes less and less.
            let excess: Vec<f64> = stats.iter().map(|st| st[j].0 / st[j].2).collect();
            let steps: Vec<f64> = excess.windows(2).map(|w| (w[0] - w[1]).abs()).collect();
            assert!(steps[2] < steps[0], "joint {j}: {excess:?}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Planar input

#[test]
fn planar_input_reproduces_the_2d_kappa_curve_outside_the_quartics() {
    let mut rng = Lcg(77);
    for case in 0..200 {
        let closed = case % 2 == 0;
        let pts3: Vec<Point3> = random_input(&mut rng, closed)
            .into_iter()
            .map(|p| Point3::new(p.x, p.y, 0.0))
            .collect();
        let pts2: Vec<Point> = pts3.iter().map(|p| p.to_xy()).collect();
        let (Ok(flat), Ok(curve)) = (
            Spline::kappa(&pts2, closed),
            SpaceCurve::new(&pts3, closed, &SpaceOptions::default()),
        ) else {
            continue;
        };
        let size = size_of(&pts3);
        let segs2 = flat.segments();
        assert_eq!(curve.spline().segments().len(), segs2.len());
        for (s, piece) in curve.segments().iter().zip(curve.pieces()) {
            // Everything stays in the plane, exactly.
            assert!(s.control_points().iter().all(|p| p.z == 0.0), "case {case}");
            if let Piece::Quadratic { source, start, end } = *piece {
                let q =
                    kurbo::QuadBez::new(segs2[source].q[0], segs2[source].q[1], segs2[source].q[2])
                        .subsegment(start..end);
                for (a, b) in s.control_points().iter().zip([q.p0, q.p1, q.p2]) {
                    assert!(
                        (a.to_xy() - b).hypot() <= 1e-9 * size,
                        "case {case}: {a:?} vs {b:?}"
                    );
                }
            }
        }
        // And G2 in the plane, inflections included (signed curvature continuous).
        check_curve(&curve, &pts3, closed, &format!("planar case {case}"));
    }
}

// ---------------------------------------------------------------------------------------------
// γ

/// Seed 004 eq. 20 on the replaced pieces, by the trapezoid rule on 4000 intervals.
fn objective(quartic: &SpaceBez, left: &SpaceBez, right: &SpaceBez) -> f64 {
    let n = 4000;
    let f = |t: f64| {
        if t <= 0.5 {
            quartic.eval(t).distance(left.eval(2.0 * t))
        } else {
            quartic.eval(t).distance(right.eval(2.0 * t - 1.0))
        }
    };
    let h = 1.0 / n as f64;
    (0..n)
        .map(|i| 0.5 * h * (f(i as f64 * h) + f((i + 1) as f64 * h)))
        .sum()
}

#[test]
fn optimized_gamma_fits_better_and_stays_g2() {
    for (pts, closed) in [(helix(8), false), (trefoil(9), true)] {
        let base =
            SpaceCurve::new(&pts, closed, &SpaceOptions::default().with_replace(0.2)).unwrap();
        let opt = SpaceCurve::new(
            &pts,
            closed,
            &SpaceOptions::default()
                .with_replace(0.2)
                .with_gamma(Gamma::Optimized),
        )
        .unwrap();
        let m = check_curve(&opt, &pts, closed, "optimized γ");
        assert_eq!(m.above_1e9, 0);
        let spline = opt.spline().segments();
        let mut better = 0;
        for (jb, jo) in base.joints().iter().zip(opt.joints()) {
            let n = spline.len();
            let l = SpaceBez::new(&spline[jo.before].control_points())
                .unwrap()
                .subsegment(jo.t1..1.0);
            let r = SpaceBez::new(&spline[(jo.before + 1) % n].control_points())
                .unwrap()
                .subsegment(0.0..jo.t2);
            let fb = objective(&base.segments()[jb.quartic.unwrap().segment], &l, &r);
            let fo = objective(&opt.segments()[jo.quartic.unwrap().segment], &l, &r);
            assert!(fo <= fb * (1.0 + 1e-6), "joint {}: {fo} vs {fb}", jo.before);
            if fo < fb * (1.0 - 1e-6) {
                better += 1;
            }
            let q = jo.quartic.unwrap();
            assert!(q.gamma_prime > 0.0 && q.gamma_prime < 1.0);
        }
        assert!(better > 0, "the optimum differs from γ = λ somewhere");
    }
}

#[test]
fn per_joint_gamma_places_q2_on_the_middle_line() {
    let pts = trefoil(9);
    let base = SpaceCurve::new(&pts, true, &SpaceOptions::default().with_replace(0.1)).unwrap();
    // The middle of each joint's admissible interval (λ t1, λ + (1 − λ) t2).
    let gammas: Vec<f64> = base
        .joints()
        .iter()
        .map(|j| 0.5 * (j.lambda * j.t1 + j.lambda + (1.0 - j.lambda) * j.t2))
        .collect();
    let curve = SpaceCurve::new(
        &pts,
        true,
        &SpaceOptions::default()
            .with_replace(0.1)
            .with_gamma(Gamma::PerJoint(gammas.clone())),
    )
    .unwrap();
    check_curve(&curve, &pts, true, "per-joint γ");
    let segs = curve.spline().segments();
    let size = size_of(&pts);
    for (j, g) in curve.joints().iter().zip(&gammas) {
        let q = j.quartic.unwrap();
        assert!((q.gamma - g).abs() < 1e-12);
        // Eq. 14: Q2 = (1 − γ) c_{i,1} + γ c_{i+1,1}.
        let c0 = segs[j.before].q[1];
        let c1 = segs[(j.before + 1) % segs.len()].q[1];
        let q2 = curve.segments()[q.segment].control_points()[2];
        assert!(q2.distance(c0.lerp(c1, *g)) < 1e-12 * size);
        // Eqs. 17, 18.
        let a = (1.5 * (g - j.lambda * j.t1) / (j.lambda * (1.0 - j.t1))).sqrt();
        let b = 1.0 - (1.5 * (1.0 + (j.lambda - g) / ((1.0 - j.lambda) * j.t2))).sqrt();
        assert!(
            (q.a - a).abs() < 1e-9 && (q.b - b).abs() < 1e-9,
            "{q:?} vs {a} {b}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Points at joints

#[test]
fn points_at_joints_are_replaced_or_kept() {
    // Random inputs until a few have a point the κ solver put exactly at a joint.
    let mut rng = Lcg(5);
    let mut seen = 0;
    for case in 0..2000 {
        let closed = case % 2 == 0;
        let pts = random_input(&mut rng, closed);
        let Ok(curve) = SpaceCurve::new(&pts, closed, &SpaceOptions::default()) else {
            continue;
        };
        if curve.missed_points().is_empty() {
            continue;
        }
        seen += 1;
        let size = size_of(&pts);
        for &(k, d) in curve.missed_points() {
            // The point is at a joint of the κ-curve …
            let t = curve.spline().segments()[k].t_max;
            assert!(!(1e-3..=1.0 - 1e-3).contains(&t), "t_max {t}");
            // … and the G2 curve passes within O(r²) of it.
            assert!(d > 0.0 && d < 1e-4 * size, "{d}");
        }
        let kept = SpaceCurve::new(
            &pts,
            closed,
            &SpaceOptions {
                at_joint: PeakAtJoint::Keep,
                ..SpaceOptions::default()
            },
        )
        .unwrap();
        assert!(kept.missed_points().is_empty());
        let n_kept = kept.joints().iter().filter(|j| j.quartic.is_none()).count();
        assert!(n_kept >= 1);
        // Every point is interpolated; kept joints are G1 with equal |κ|.
        for (&(seg, t), p) in kept.point_params().iter().zip(peak_inputs(&pts, closed)) {
            assert!(kept.segments()[seg].eval(t).distance(*p) <= 1e-9 * size);
        }
        for (j, gap) in kept.continuity().iter().zip(kept.curvature_vector_gaps()) {
            let both_quadratic =
                kept.segments()[j.before].degree() == 2 && kept.segments()[j.after].degree() == 2;
            if !both_quadratic {
                assert!(gap <= 1e-9f64.max(1e-6), "{gap}");
            }
            let k = CurvatureAnalysis::curvature(&kept.segments()[j.before], 1.0);
            assert!(j.continuity.curvature_diff <= 1e-8 * k.max(1.0 / size));
        }
        if seen == 5 {
            break;
        }
    }
    assert!(seen >= 1);
}

// ---------------------------------------------------------------------------------------------
// Evaluation

#[test]
fn evaluation_matches_finite_differences_and_closed_forms() {
    let pts = helix(7);
    let curve = SpaceCurve::new(&pts, false, &SpaceOptions::default().with_replace(0.2)).unwrap();
    let n = curve.len();
    let h = 1e-5;
    let mut saw_torsion = false;
    for i in 0..n {
        for f in [0.2, 0.5, 0.8] {
            let u = i as f64 + f;
            let d1 = curve.deriv(u);
            let d2 = curve.deriv2(u);
            let fd1 = (curve.eval(u + h) - curve.eval(u - h)) * (0.5 / h);
            let fd2 = (curve.deriv(u + h) - curve.deriv(u - h)) * (0.5 / h);
            assert!((d1 - fd1).length() <= 1e-6 * d1.length().max(1.0), "u {u}");
            assert!((d2 - fd2).length() <= 1e-5 * d2.length().max(1.0), "u {u}");
            let c = d1.cross(d2);
            let kappa = c.length() / d1.length().powi(3);
            assert!((curve.curvature(u) - kappa).abs() <= 1e-12 * kappa.max(1e-300));
            let kv = curve.curvature_vector(u);
            assert!((kv.length() - kappa).abs() <= 1e-12 * kappa);
            assert!(kv.dot(d1).abs() <= 1e-12 * kv.length() * d1.length());
            // Torsion: (r′ × r″) · r‴ / |r′ × r″|², with r‴ by differences.
            let d3 = (curve.deriv2(u + h) - curve.deriv2(u - h)) * (0.5 / h);
            let tau = c.dot(d3) / c.hypot2();
            let got = curve.torsion(u);
            if curve.segments()[i].degree() == 2 {
                assert_eq!(got, 0.0);
            } else {
                assert!(
                    (got - tau).abs() <= 1e-5 * tau.abs().max(1e-3),
                    "u {u}: {got} vs {tau}"
                );
                saw_torsion |= got.abs() > 0.0;
            }
        }
    }
    assert!(saw_torsion);
    // A right-handed helix twists positively: the quartics carry the twist.
    let twist: f64 = curve
        .joints()
        .iter()
        .map(|j| curve.torsion(j.quartic.unwrap().segment as f64 + 0.5))
        .sum();
    assert!(twist > 0.0);
    assert_eq!(curve.locate(-1.0), (0, 0.0));
    assert_eq!(curve.locate(f64::NAN), (0, 0.0));
    assert_eq!(curve.locate(n as f64), (n - 1, 1.0));
    // Arc length against a fine polyline.
    let samples = 200_000;
    let poly: f64 = (0..samples)
        .map(|i| {
            let a = curve.eval(n as f64 * i as f64 / samples as f64);
            let b = curve.eval(n as f64 * (i + 1) as f64 / samples as f64);
            a.distance(b)
        })
        .sum();
    let len = curve.arclen(1e-9);
    assert!(len >= poly && len - poly < 1e-6 * len, "{len} vs {poly}");
}

// ---------------------------------------------------------------------------------------------
// Errors

#[test]
fn bad_input_is_a_typed_error() {
    let ok = helix(6);
    let d = SpaceOptions::default();
    let mut nan = ok.clone();
    nan[2].y = f64::NAN;
    assert_eq!(
        SpaceCurve::new(&nan, false, &d).unwrap_err(),
        Error::NonFinitePoint { index: 2 }
    );
    let mut inf = ok.clone();
    inf[0].z = f64::INFINITY;
    assert_eq!(
        SpaceCurve::new(&inf, true, &d).unwrap_err(),
        Error::NonFinitePoint { index: 0 }
    );
    assert!(matches!(
        SpaceCurve::new(&ok[..2], true, &d),
        Err(Error::TooFewPoints {
            needed: 3,
            got: 2,
            ..
        })
    ));
    assert!(matches!(
        SpaceCurve::new(&ok[..1], false, &d),
        Err(Error::TooFewPoints { .. })
    ));
    let mut rep = ok.clone();
    rep[3] = rep[2];
    assert_eq!(
        SpaceCurve::new(&rep, false, &d).unwrap_err(),
        Error::RepeatedPoint { index: 2, next: 3 }
    );
    let line: Vec<Point3> = (0..4)
        .map(|i| Point3::new(i as f64, 2.0 * i as f64, 0.5))
        .collect();
    assert_eq!(
        SpaceCurve::new(&line, true, &d).unwrap_err(),
        Error::Collinear
    );
    for (t1, t2) in [
        (1.0, 0.01),
        (-0.1, 0.01),
        (0.99, 0.0),
        (0.99, 1.5),
        (f64::NAN, 0.01),
        (0.99, f64::NAN),
        (0.99, f64::INFINITY),
    ] {
        let options = SpaceOptions {
            replace: Replace::Partial { t1, t2 },
            ..SpaceOptions::default()
        };
        assert!(
            matches!(
                SpaceCurve::new(&ok, false, &options),
                Err(Error::InvalidOption(_))
            ),
            "{t1} {t2}"
        );
    }
    for r in [-0.5, 1.5, f64::NAN] {
        assert!(matches!(
            SpaceCurve::new(&ok, false, &SpaceOptions::default().with_replace(r)),
            Err(Error::InvalidOption(_))
        ));
    }
    // γ: wrong count, out of range, NaN.
    let joints = SpaceCurve::new(&ok, false, &d).unwrap().joints().len();
    assert!(matches!(
        SpaceCurve::new(
            &ok,
            false,
            &d.clone().with_gamma(Gamma::PerJoint(vec![0.5; joints + 1]))
        ),
        Err(Error::InvalidOption(_))
    ));
    for bad in [-0.1, 1.2, f64::NAN] {
        let err = SpaceCurve::new(
            &ok,
            false,
            &d.clone().with_gamma(Gamma::PerJoint(vec![bad; joints])),
        )
        .unwrap_err();
        assert!(
            matches!(err, Error::GammaOutOfRange { joint: 0, .. }),
            "{err:?}"
        );
        assert!(err.to_string().starts_with("gamma of joint 0 is"));
    }
    // An εκ-curve is not made of quadratics.
    let ek = Solver3::new()
        .solve(&ok, false, Scheme::EkCubic, &Shape::Global(0.8))
        .unwrap();
    assert!(matches!(
        SpaceCurve::from_spline(ek, &d),
        Err(Error::InvalidOption(_))
    ));
    // Projections and exports.
    let curve = SpaceCurve::new(&ok, false, &d).unwrap();
    let behind = Projection::perspective(
        Point3::new(0.0, 0.0, 30.0),
        Point3::new(0.0, 0.0, 31.0),
        Vec3::new(0.0, 1.0, 0.0),
        1.0,
    )
    .unwrap();
    assert!(matches!(
        curve.project(&behind, &FitOptions::default()),
        Err(Error::InvalidOption(_))
    ));
    assert!(matches!(
        Projection::perspective(
            Point3::ORIGIN,
            Point3::ORIGIN,
            Vec3::new(0.0, 0.0, 1.0),
            1.0
        ),
        Err(Error::InvalidOption(_))
    ));
    assert!(matches!(
        Projection::perspective(
            Point3::ORIGIN,
            Point3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            1.0
        ),
        Err(Error::InvalidOption(_))
    ));
    assert!(matches!(
        Projection::perspective(
            Point3::ORIGIN,
            Point3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
            0.0
        ),
        Err(Error::InvalidOption(_))
    ));
    assert!(matches!(
        View::looking(Vec3::new(f64::NAN, 0.0, 1.0), Vec3::new(0.0, 1.0, 0.0)),
        Err(Error::InvalidOption(_))
    ));
    for tol in [0.0, -1.0, f64::NAN] {
        assert!(matches!(curve.to_obj(tol), Err(Error::InvalidOption(_))));
        assert!(matches!(
            curve.project(
                &Projection::Orthographic(View::TOP),
                &FitOptions::absolute(tol)
            ),
            Err(Error::InvalidOption(_))
        ));
    }
}

// ---------------------------------------------------------------------------------------------
// Projections

fn distance_to_path(p: Point, path: &kurbo::BezPath) -> f64 {
    // Through cubics: kurbo 0.13's `QuadBez::nearest` misses on collinear quadratics
    // (which projections along a quadratic's plane produce).
    path.segments()
        .map(|s| s.to_cubic().nearest(p, 1e-12).distance_sq)
        .fold(f64::INFINITY, f64::min)
        .sqrt()
}

#[test]
fn orthographic_projection_is_exact_for_quadratics_and_fitted_for_quartics() {
    let pts = trefoil(10);
    let curve = SpaceCurve::new(&pts, true, &SpaceOptions::default().with_replace(0.1)).unwrap();
    for view in [View::TOP, View::FRONT, View::SIDE, View::ISOMETRIC] {
        let projection = Projection::Orthographic(view);
        let options = FitOptions::relative(1e-6);
        let out = curve.project(&projection, &options).unwrap();
        assert_eq!(out.fitted, curve.joints().len());
        assert!(out.max_distance <= out.tolerance);
        let img = |p: Point3| {
            let v = p.to_vec3();
            Point::new(v.dot(view.right()), v.dot(view.up()))
        };
        // The quadratics appear verbatim, in order.
        let quads: Vec<(Point, Point)> = out
            .path
            .elements()
            .iter()
            .filter_map(|e| match *e {
                PathEl::QuadTo(a, b) => Some((a, b)),
                _ => None,
            })
            .collect();
        let expected: Vec<(Point, Point)> = curve
            .segments()
            .iter()
            .filter(|s| s.degree() == 2)
            .map(|s| (img(s.control_points()[1]), img(s.end())))
            .collect();
        assert_eq!(quads, expected);
        assert!(matches!(
            out.path.elements().last(),
            Some(PathEl::ClosePath)
        ));
        // Every point of every segment is within the tolerance of the path.
        for s in curve.segments() {
            for i in 0..=50 {
                let p = img(s.eval(i as f64 / 50.0));
                let d = distance_to_path(p, &out.path);
                assert!(
                    d <= out.tolerance * 1.01,
                    "{view:?} deg {} i {i}: {d} vs {}",
                    s.degree(),
                    out.tolerance
                );
            }
        }
    }
}

#[test]
fn perspective_projection_is_fitted_within_tolerance() {
    let pts = helix(8);
    let curve = SpaceCurve::new(&pts, false, &SpaceOptions::default()).unwrap();
    let eye = Point3::new(400.0, -300.0, 250.0);
    let target = Point3::new(0.0, 0.0, 40.0);
    let focal = 2.0;
    let projection = Projection::perspective(eye, target, Vec3::new(0.0, 0.0, 1.0), focal).unwrap();
    let out = curve
        .project(&projection, &FitOptions::relative(1e-5))
        .unwrap();
    assert_eq!(out.fitted, curve.len());
    // Independent projection: the ray from the eye through p meets the picture plane.
    let view = projection.view();
    let image = |p: Point3| {
        let d = p - eye;
        let w = d.dot(view.forward());
        Point::new(
            focal * d.dot(view.right()) / w,
            focal * d.dot(view.up()) / w,
        )
    };
    for s in curve.segments() {
        for i in 0..=40 {
            let p = image(s.eval(i as f64 / 40.0));
            assert!(distance_to_path(p, &out.path) <= out.tolerance * 1.01);
        }
    }
    // The joints stay G1 in the picture.
    let segs: Vec<kurbo::CubicBez> = out.path.segments().map(|s| s.to_cubic()).collect();
    for w in segs.windows(2) {
        let a = w[0].p3 - w[0].p2;
        let b = w[1].p1 - w[1].p0;
        assert!(a.cross(b).abs() <= 1e-6 * a.hypot() * b.hypot());
    }
    // Derivatives of the projection against differences.
    let p = Point3::new(10.0, 20.0, 30.0);
    let d = Vec3::new(1.0, -2.0, 0.5);
    let h = 1e-6;
    let (_, got) = projection.point_deriv(p, d).unwrap();
    let fd =
        (projection.point(p + d * h).unwrap() - projection.point(p - d * h).unwrap()) / (2.0 * h);
    assert!((got - fd).hypot() <= 1e-6 * got.hypot());
}

#[test]
fn views_are_orthonormal_and_right_handed() {
    let iso = View::looking(Vec3::new(-1.0, -1.0, -1.0), Vec3::new(0.0, 0.0, 1.0)).unwrap();
    for v in [View::TOP, View::FRONT, View::SIDE, View::ISOMETRIC, iso] {
        for (a, b) in [
            (v.right(), v.up()),
            (v.up(), v.forward()),
            (v.right(), v.forward()),
        ] {
            assert!(a.dot(b).abs() < 1e-15);
        }
        for a in [v.right(), v.up(), v.forward()] {
            assert!((a.length() - 1.0).abs() < 1e-15);
        }
        assert!((v.right().cross(v.up()) + v.forward()).length() < 1e-15);
    }
    let d = |a: Vec3, b: Vec3| (a - b).length();
    assert!(d(iso.right(), View::ISOMETRIC.right()) < 1e-15);
    assert!(d(iso.up(), View::ISOMETRIC.up()) < 1e-15);
    assert!(d(iso.forward(), View::ISOMETRIC.forward()) < 1e-15);
}

// ---------------------------------------------------------------------------------------------
// Exports

#[test]
fn obj_polyline_stays_within_its_tolerance() {
    for (pts, closed) in [(helix(8), false), (trefoil(9), true)] {
        let curve = SpaceCurve::new(&pts, closed, &SpaceOptions::default()).unwrap();
        let tol = 1e-3 * size_of(&pts);
        let obj = curve.to_obj(tol).unwrap();
        let verts: Vec<Point3> = obj
            .lines()
            .filter_map(|l| l.strip_prefix("v "))
            .map(|l| {
                let v: Vec<f64> = l.split(' ').map(|x| x.parse().unwrap()).collect();
                Point3::new(v[0], v[1], v[2])
            })
            .collect();
        let lines: Vec<&str> = obj.lines().filter(|l| l.starts_with("l ")).collect();
        assert_eq!(lines.len(), 1);
        let idx: Vec<usize> = lines[0][2..]
            .split(' ')
            .map(|x| x.parse().unwrap())
            .collect();
        let mut expect: Vec<usize> = (1..=verts.len()).collect();
        if closed {
            expect.push(1);
        }
        assert_eq!(idx, expect);
        assert_eq!(verts, curve.flatten(tol).unwrap());
        let poly: Vec<Point3> = idx.iter().map(|&i| verts[i - 1]).collect();
        let dist = |p: Point3| {
            poly.windows(2)
                .map(|w| {
                    let ab = w[1] - w[0];
                    let s = ((p - w[0]).dot(ab) / ab.hypot2()).clamp(0.0, 1.0);
                    p.distance(w[0] + ab * s)
                })
                .fold(f64::INFINITY, f64::min)
        };
        for s in curve.segments() {
            for i in 0..=100 {
                let p = s.eval(i as f64 / 100.0);
                assert!(dist(p) <= tol * (1.0 + 1e-9), "{}", dist(p));
            }
        }
        // Every vertex lies on the curve (they are curve points, split by de Casteljau).
        assert!(verts.len() > curve.len());
    }
}

#[cfg(feature = "serde")]
#[test]
fn json_export_is_exact() {
    let pts = trefoil(8);
    let curve = SpaceCurve::new(&pts, true, &SpaceOptions::default()).unwrap();
    let text = curve.to_json().unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let segs = v["segments"].as_array().unwrap();
    assert_eq!(segs.len(), curve.len());
    for (s, j) in curve.segments().iter().zip(segs) {
        assert_eq!(j["degree"].as_u64().unwrap() as usize, s.degree());
        let pts: Vec<Point3> = j["points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| {
                let c: Vec<f64> = p
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_f64().unwrap())
                    .collect();
                Point3::new(c[0], c[1], c[2])
            })
            .collect();
        // Bit for bit.
        assert_eq!(pts, s.control_points());
    }
    let t_max: Vec<f64> = v["t_max"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(t_max.len(), pts.len());
    for (u, p) in t_max.iter().zip(&pts) {
        assert!(curve.eval(*u).distance(*p) < 1e-9 * size_of(&pts));
    }
    let gaps: Vec<f64> = v["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j["curvature_vector_gap"].as_f64().unwrap())
        .collect();
    assert_eq!(gaps, curve.curvature_vector_gaps());
    assert!(gaps.iter().all(|&g| g < 1e-9));
}

// ---------------------------------------------------------------------------------------------
// Golden pictures

#[cfg(feature = "render")]
mod golden {
    use super::*;
    use kappa::render::golden::{check_golden, Tolerance};
    use kappa::space::views_figure;
    use std::path::Path;

    fn figure(name: &str, pts: &[Point3], closed: bool) {
        let curve = SpaceCurve::new(pts, closed, &SpaceOptions::default()).unwrap();
        let image = views_figure(&curve, 240).unwrap();
        let path =
            Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/golden/space-{name}.png"));
        if let Err(e) = check_golden(&path, &image, Tolerance::DEFAULT) {
            panic!("{e}");
        }
    }

    /// Re-bless with `KAPPA_BLESS=1 cargo test --all-features --test space golden`.
    #[test]
    fn golden_space_helix() {
        figure("helix", &helix(10), false);
    }

    #[test]
    fn golden_space_trefoil() {
        figure("trefoil", &trefoil(12), true);
    }
}

// ---------------------------------------------------------------------------------------------
// The `kappa space` command

#[cfg(feature = "cli")]
mod cli {
    use super::*;
    use serde_json::Value;
    use std::process::Output;

    fn kappa(args: &[&str], stdin: &str) -> Output {
        crate::common::run_kappa(args, stdin)
    }

    fn input(pts: &[Point3], closed: bool, replace: Option<f64>) -> String {
        let coords: Vec<String> = pts
            .iter()
            .map(|p| format!("[{}, {}, {}]", p.x, p.y, p.z))
            .collect();
        let replace = replace.map_or(String::new(), |r| format!(", \"replace\": {r}"));
        format!(
            "{{\"points\": [{}], \"closed\": {closed}{replace}}}",
            coords.join(", ")
        )
    }

    fn points(v: &Value) -> Vec<Point3> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|p| {
                let c: Vec<f64> = p
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_f64().unwrap())
                    .collect();
                assert_eq!(c.len(), 3);
                Point3::new(c[0], c[1], c[2])
            })
            .collect()
    }

    #[test]
    fn cli_space_follows_the_json_contract() {
        for (pts, closed) in [(helix(8), false), (trefoil(10), true)] {
            for replace in [None, Some(0.05)] {
                let out = kappa(&["space"], &input(&pts, closed, replace));
                assert!(
                    out.status.success(),
                    "{}",
                    String::from_utf8_lossy(&out.stderr)
                );
                assert!(out.stderr.is_empty());
                let v: Value = serde_json::from_slice(&out.stdout).unwrap();
                let keys: Vec<&String> = v.as_object().unwrap().keys().collect();
                assert_eq!(keys, ["joints", "segments", "t_max"]);
                // The segments are the library's, bit for bit.
                let options = SpaceOptions::default().with_replace(replace.unwrap_or(0.01));
                let curve = SpaceCurve::new(&pts, closed, &options).unwrap();
                let segs = v["segments"].as_array().unwrap();
                assert_eq!(segs.len(), curve.len());
                let mut chain: Vec<SpaceBez> = Vec::new();
                for (j, s) in segs.iter().zip(curve.segments()) {
                    let degree = j["degree"].as_u64().unwrap() as usize;
                    assert!(degree == 2 || degree == 4);
                    let p = points(&j["points"]);
                    assert_eq!(p.len(), degree + 1);
                    assert_eq!(p, s.control_points());
                    chain.push(SpaceBez::new(&p).unwrap());
                }
                // Checked from the JSON alone: the segments join, G2, and pass through the
                // points at t_max.
                let joints = kappa::analysis::segments_continuity(&chain, closed);
                let gaps = v["joints"].as_array().unwrap();
                assert_eq!(gaps.len(), joints.len());
                for (g, j) in gaps.iter().zip(&joints) {
                    let e = g["curvature_vector_gap"].as_f64().unwrap();
                    assert!(e < 1e-9, "{e}");
                    assert_eq!(j.continuity.position_gap, 0.0);
                    let k = CurvatureAnalysis::curvature(&chain[j.before], 1.0);
                    assert!(j.continuity.curvature_vector_diff <= 1e-9 * k);
                }
                let t_max: Vec<f64> = v["t_max"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_f64().unwrap())
                    .collect();
                let inputs = peak_inputs(&pts, closed);
                assert_eq!(t_max.len(), inputs.len());
                for (u, p) in t_max.iter().zip(inputs) {
                    let i = (u.floor() as usize).min(chain.len() - 1);
                    let q = chain[i].eval(u - i as f64);
                    assert!(q.distance(*p) < 1e-9 * size_of(&pts));
                }
            }
        }
    }

    #[test]
    fn cli_space_writes_obj_png_and_svg() {
        let dir = std::env::temp_dir().join(format!("kappa-space-cli-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (obj, png, svg) = (dir.join("c.obj"), dir.join("c.png"), dir.join("c.svg"));
        let out = kappa(
            &[
                "space",
                "--gamma",
                "optimized",
                "--obj",
                obj.to_str().unwrap(),
                "--png",
                png.to_str().unwrap(),
                "--svg",
                svg.to_str().unwrap(),
                "--view",
                "top",
                "--size",
                "120",
            ],
            &input(&trefoil(9), true, None),
        );
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let obj = std::fs::read_to_string(&obj).unwrap();
        assert!(obj.lines().filter(|l| l.starts_with("v ")).count() > 9);
        assert!(obj.lines().last().unwrap().starts_with("l 1 2 "));
        let image = kappa::render::Pixmap::load_png(&png).unwrap();
        assert_eq!((image.width(), image.height()), (4 * 120 + 3 * 8, 120));
        assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn cli_space_errors_are_one_line() {
        let ok = input(&helix(5), false, None);
        for (args, stdin, needle) in [
            (
                vec!["space"],
                r#"{"points": [[0, 0, 0], [1, 1]]}"#.to_owned(),
                "expected 3",
            ),
            (
                vec!["space"],
                r#"{"points": [[0, 0, null]]}"#.to_owned(),
                "null",
            ),
            (
                vec!["space"],
                r#"{"points": [], "gamma": 1}"#.to_owned(),
                "unknown field",
            ),
            (vec!["space"], input(&helix(5), false, Some(1.5)), "replace"),
            (
                vec!["space"],
                input(&helix(5), false, Some(-0.1)),
                "replace",
            ),
            (
                vec!["space"],
                input(&helix(2), true, None),
                "too few points",
            ),
            (
                vec!["space"],
                input(&[helix(3)[0], helix(3)[0], helix(3)[2]], false, None),
                "coincide",
            ),
            (vec!["space", "--tolerance", "-1"], ok.clone(), "tolerance"),
            (
                vec!["space", "--obj", "/nonexistent-dir/x.obj"],
                ok.clone(),
                "cannot write",
            ),
            (
                vec!["space", "--obj", "x.obj", "--obj-tolerance", "0"],
                ok.clone(),
                "tolerance",
            ),
            (
                vec!["space", "--gamma", "best"],
                ok.clone(),
                "invalid value",
            ),
        ] {
            let out = kappa(&args, &stdin);
            assert_eq!(out.status.code(), Some(2), "{args:?} {stdin}");
            assert!(out.stdout.is_empty(), "{args:?}");
            let err = String::from_utf8(out.stderr).unwrap();
            assert_eq!(err.lines().count(), 1, "{err}");
            assert!(err.starts_with("kappa: error: "), "{err}");
            assert!(err.contains(needle), "{args:?}: {err}");
        }
    }
}

#[test]
fn small_and_degenerate_inputs() {
    let d = SpaceOptions::default();
    // Two points: one straight segment; three open points: one quadratic; no joints.
    let two = [Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 2.0, 3.0)];
    let c = SpaceCurve::new(&two, false, &d).unwrap();
    assert_eq!((c.len(), c.joints().len()), (1, 0));
    assert_eq!(c.ends(), (two[0], two[1]));
    let three = [
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(1.0, 2.0, 3.0),
        Point3::new(3.0, 1.0, 0.0),
    ];
    let c = SpaceCurve::new(&three, false, &d).unwrap();
    assert_eq!((c.len(), c.joints().len()), (1, 0));
    check_curve(&c, &three, false, "three open");
    // Three closed points: three quadratics, three quartics.
    let c = SpaceCurve::new(&three, true, &d).unwrap();
    assert_eq!((c.len(), c.joints().len()), (6, 3));
    check_curve(&c, &three, true, "three closed");
    // Points on a line (open): straight pieces, straight quartics, κ ≡ 0, no torsion; seen
    // along the line the curve is a single point, and the projection still works.
    let line: Vec<Point3> = (0..5).map(|i| Point3::new(0.0, 0.0, i as f64)).collect();
    let c = SpaceCurve::new(&line, false, &d).unwrap();
    assert_eq!(c.joints().iter().filter(|j| j.quartic.is_some()).count(), 2);
    for u in [0.3, 1.5, 2.7] {
        assert_eq!(c.curvature(u), 0.0);
        assert_eq!(c.torsion(u), 0.0);
    }
    assert!(c.curvature_vector_gaps().iter().all(|&g| g == 0.0));
    let top = c.project(&Projection::Orthographic(View::TOP), &FitOptions::default());
    let top = top.unwrap();
    assert!(top
        .path
        .elements()
        .iter()
        .all(|e| e.end_point().map_or(true, |q| q == Point::ZERO)));
    // A curve whose tangent points along the view somewhere: a cusp in the picture.
    let hook = [
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(10.0, 0.0, 5.0),
        Point3::new(10.0, 0.0, 15.0),
        Point3::new(0.0, 1.0, 20.0),
    ];
    let c = SpaceCurve::new(&hook, false, &d).unwrap();
    let front = c
        .project(
            &Projection::Orthographic(View::FRONT),
            &FitOptions::relative(1e-5),
        )
        .unwrap();
    assert!(front.max_distance <= front.tolerance);
}
