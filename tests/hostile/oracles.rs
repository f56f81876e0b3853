//! Oracles: what every answer of an entry point must satisfy.
//!
//! Tolerances are relative to the drawing size, with a floor for what the numbers can hold:
//! a coordinate `X` carries a rounding error of `ε |X|`, so a drawing of size 1e-9 placed at
//! 1e9 from the origin can be checked no better than to about 1e-7 absolute.
//!
//! Comparisons are written so that a NaN fails them (`!(x <= bound)`), on purpose.
#![allow(clippy::neg_cmp_op_on_partial_ord, clippy::nonminimal_bool)]

use kappa::{Error, Extremum, Point3, Scheme, Segment, Shape, SolveOptions, Spline};
use kurbo::{ParamCurve, ParamCurveDeriv, PathSeg, Point, Vec2};

/// Interpolation error allowed at a peak, relative to the drawing size.
pub const INTERP: f64 = 1e-9;
/// Relative |κ| mismatch allowed at a G2 joint (above the rounding floor).
pub const G2: f64 = 1e-9;
/// Relative slack of "the peak is the largest |κ|".
pub const PEAK: f64 = 1e-6;
/// A control triangle whose legs are parallel to within this sine is degenerate (a straight
/// piece or a near-cusp): its peak is not checked.
pub const DEGENERATE: f64 = 1e-6;
/// Consecutive points closer than this (relative to the size) make an input fragile (see
/// [`check_spline2d`]).
pub const FRAGILE: f64 = 1e-6;
/// |κ| times the size above which a B-spline is at a near-cusp: its maximum is then only
/// checked for being reported (not NaN), since |κ| changes by orders of magnitude within the
/// rounding of the parameter there.
pub const NEAR_CUSP: f64 = 1e4;

/// The larger side of the bounding box of `D`-dimensional points (0 for one point).
pub fn size_of<const D: usize>(pts: &[[f64; D]]) -> f64 {
    let mut lo = [f64::INFINITY; D];
    let mut hi = [f64::NEG_INFINITY; D];
    for p in pts {
        for k in 0..D {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (0..D).map(|k| hi[k] - lo[k]).fold(0.0, f64::max)
}

/// The largest coordinate magnitude.
pub fn magnitude<const D: usize>(pts: &[[f64; D]]) -> f64 {
    pts.iter().flatten().fold(0.0, |m, v| m.max(v.abs()))
}

/// 2D points as arrays.
pub fn arrays(pts: &[Point]) -> Vec<[f64; 2]> {
    pts.iter().map(|p| [p.x, p.y]).collect()
}

/// 3D points as arrays.
pub fn arrays3(pts: &[Point3]) -> Vec<[f64; 3]> {
    pts.iter().map(|p| [p.x, p.y, p.z]).collect()
}

/// The κ/εκ solver's "repeated" threshold in units of the pair's rounding: consecutive
/// points with `|a − b| ≤ ULP_COINCIDENT · ε · max |coordinate|` are an
/// `Error::RepeatedPoint` (`ULP_COINCIDENT` in src/spline/checks.rs).
pub const ULP_COINCIDENT: f64 = 4.0;
/// The κ/εκ solver's collinearity threshold, relative to the size: open input whose points
/// are this close to one line is solved as a straight curve (`COINCIDENT` in
/// src/spline/checks.rs).
pub const COLLINEAR: f64 = 1e-12;

/// Whether two points coincide to within the rounding of their coordinates (the solver's
/// test, written independently, and 1e-6 inside its threshold so that the two roundings of
/// a pair right at the threshold do not disagree; halves first, as the difference of finite
/// points can overflow).
pub fn within_rounding(a: Point, b: Point) -> bool {
    let mag = a.x.abs().max(a.y.abs()).max(b.x.abs()).max(b.y.abs());
    let d = (0.5 * a.x - 0.5 * b.x).hypot(0.5 * a.y - 0.5 * b.y);
    d <= 0.5 * (1.0 - 1e-6) * ULP_COINCIDENT * f64::EPSILON * mag
}

/// The absolute error floor of positions near coordinates of magnitude `mag`.
pub fn floor(mag: f64) -> f64 {
    256.0 * f64::EPSILON * mag
}

/// Checks that an error is the one the input explains, for the validation every
/// point-based entry point shares: too few points, non-finite, overflowing or repeated
/// points. Returns `false` for any other variant (the caller decides).
pub fn check_point_error<const D: usize>(
    e: &Error,
    pts: &[[f64; D]],
    closed: bool,
    what: &str,
) -> bool {
    let size = size_of(pts);
    match *e {
        Error::TooFewPoints { needed, got, .. } => {
            assert_eq!(got, pts.len(), "{what}: {e}");
            assert!(got < needed, "{what}: {e}");
        }
        Error::NonFinitePoint { index } => {
            assert!(
                pts[index].iter().any(|v| !v.is_finite()),
                "{what}: {e}: {:?}",
                pts[index]
            );
        }
        Error::ExtentOverflow => {
            assert!(
                magnitude(pts) > 4e307 || !(size <= 1e304),
                "{what}: {e} with extent {size}"
            );
        }
        Error::RepeatedPoint { index, next } => {
            let n = pts.len();
            assert!(
                next == (index + 1) % n && (closed || next == index + 1),
                "{what}: {e}"
            );
            let d = (0..D)
                .map(|k| (pts[index][k] - pts[next][k]).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(
                d <= 1e-11 * size + floor(magnitude(pts)),
                "{what}: {e}, but they are {d} apart (size {size})"
            );
        }
        _ => return false,
    }
    true
}

/// The distance of the points from their best line through the first point and the farthest
/// one, relative to the size.
pub fn line_spread<const D: usize>(pts: &[[f64; D]]) -> f64 {
    // In units of the size (squares of coordinates near 1e308 overflow).
    let size = size_of(pts);
    if !(size > 0.0) {
        return 0.0;
    }
    let pts: Vec<[f64; D]> = pts
        .iter()
        .map(|p| core::array::from_fn(|k| p[k] / size))
        .collect();
    let size = 1.0;
    let p0 = pts[0];
    let d2 = |a: &[f64; D], b: &[f64; D]| (0..D).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>();
    let far = pts
        .iter()
        .max_by(|a, b| d2(a, &p0).total_cmp(&d2(b, &p0)))
        .copied()
        .unwrap_or(p0);
    let len = d2(&far, &p0).sqrt();
    if len == 0.0 {
        return 0.0;
    }
    let dir: [f64; D] = core::array::from_fn(|k| (far[k] - p0[k]) / len);
    pts.iter()
        .map(|q| {
            let along = (0..D).map(|k| (q[k] - p0[k]) * dir[k]).sum::<f64>();
            (0..D)
                .map(|k| (q[k] - p0[k] - along * dir[k]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0, f64::max)
        / size
}

/// Checks a shape error against the shapes given.
fn check_shape_error(e: &Error, scheme: Scheme, shape: &Shape, n: usize, closed: bool, what: &str) {
    match (e, shape) {
        (Error::ShapeCount { expected, got }, Shape::PerPoint(v)) => {
            assert_eq!(*expected, n, "{what}: {e}");
            assert_eq!(*got, v.len(), "{what}: {e}");
            assert_ne!(v.len(), n, "{what}: {e}");
        }
        (
            Error::ShapeOutOfRange {
                index,
                value,
                min,
                max,
            },
            _,
        ) => {
            assert!(
                !(value >= min && value < max) || !value.is_finite(),
                "{what}: {e} is in range"
            );
            assert_eq!((*min, *max), scheme.shape_range(), "{what}: {e}");
            let given = match shape {
                Shape::Global(a) => *a,
                Shape::PerPoint(v) => v[*index],
                Shape::Neutral => panic!("{what}: {e} for the neutral shape"),
            };
            assert!(
                given.to_bits() == value.to_bits() || (given.is_nan() && value.is_nan()),
                "{what}: {e}, given {given}"
            );
            // (The ends of an open curve have no segment, but their shapes are checked too.)
            let _ = closed;
        }
        _ => panic!("{what}: unexpected error {e:?}"),
    }
}

/// First derivative of a curve segment at `t` (exact for every scheme).
pub fn seg_deriv(seg: &Segment<Point>, t: f64) -> Vec2 {
    if seg.scheme == Scheme::EkTrig {
        return seg.to_trig().derivative(t);
    }
    match seg.to_path_seg() {
        PathSeg::Line(l) => l.deriv().eval(t).to_vec2(),
        PathSeg::Quad(q) => q.deriv().eval(t).to_vec2(),
        PathSeg::Cubic(c) => c.deriv().eval(t).to_vec2(),
    }
}

/// Second derivative of a curve segment at `t` (exact for every scheme).
pub fn seg_deriv2(seg: &Segment<Point>, t: f64) -> Vec2 {
    if seg.scheme == Scheme::EkTrig {
        return seg.to_trig().second_derivative(t);
    }
    match seg.to_path_seg() {
        PathSeg::Line(_) => Vec2::ZERO,
        PathSeg::Quad(q) => q.deriv().deriv().eval(t).to_vec2(),
        PathSeg::Cubic(c) => c.deriv().deriv().eval(t).to_vec2(),
    }
}

/// The relative error of `|κ(t)|` when the control points the segment is built from are
/// off by `delta`: `κ = (C′ × C″)/|C′|³`, and `C′`, `C″` move by a few `delta` (times the
/// degree), so `C′ × C″` moves by about `delta (|C′| + |C″|)` and `|C′|³` by `3 delta/|C′|`
/// relative (the constants are in the factor the caller puts into `delta`). Unlike a bound
/// from the legs `q` of the defining triangle, this sees the segment's own polygon: an
/// εκ-cubic with `a → 1` has an inner leg `(1 − a)` times shorter, and its end curvature
/// is made of that leg (found by fuzzing with `a = 1 − 1e-9`, where one side of a joint
/// evaluated to |κ| = 0).
fn kappa_rel_error(seg: &Segment<Point>, t: f64, delta: f64) -> f64 {
    let (d1, d2) = (seg_deriv(seg, t), seg_deriv2(seg, t));
    let cross = d1.cross(d2).abs().max(f64::MIN_POSITIVE);
    delta * ((d1.hypot() + d2.hypot()) / cross + 3.0 / d1.hypot().max(f64::MIN_POSITIVE))
}

/// Checks the answer of a 2D solve (κ, εκ-cubic, εκ-trig) of `points` with `options`.
pub fn check_solve2d(
    points: &[Point],
    closed: bool,
    scheme: Scheme,
    shape: &Shape,
    options: &SolveOptions,
    result: &Result<Spline, Error>,
    what: &str,
) {
    let pts = arrays(points);
    let n = points.len();
    // A pair that coincides to within its own rounding (see `within_rounding`) is always
    // refused: a curve through it is rounding noise. The solver checks it before anything
    // that can give another error (only the point count, non-finite points, the tolerance and
    // overflowing extents come first).
    // (For errors, the closing pair is left out: a failed warm re-solve is checked as
    // closed whatever its last problem was.)
    let rounded = |pairs: usize| {
        (0..pairs)
            .find(|&i| within_rounding(points[i], points[(i + 1) % n]))
            .filter(|_| points.iter().all(|p| p.is_finite()))
    };
    let rounded_pair = rounded(if closed { n } else { n.saturating_sub(1) });
    let spline = match result {
        Ok(s) => s,
        Err(e) => {
            if check_point_error(e, &pts, closed, what) {
                return;
            }
            if matches!(
                e,
                Error::Collinear
                    | Error::NotConverged { .. }
                    | Error::ShapeCount { .. }
                    | Error::ShapeOutOfRange { .. }
            ) {
                let open_pair = rounded(n.saturating_sub(1));
                assert!(
                    open_pair.is_none(),
                    "{what}: {e}, but points {open_pair:?} and the next coincide to within their rounding"
                );
            }
            match e {
                Error::Collinear => {
                    // On one line up to 1e-12 of the size, or to the rounding of the points.
                    let spread = line_spread(&pts);
                    let allowed = 1e-10 + floor(magnitude(&pts)) / size_of(&pts);
                    assert!(spread <= allowed, "{what}: {e} with spread {spread}");
                }
                Error::NotConverged {
                    iterations,
                    residual,
                } => {
                    assert!(
                        *iterations <= options.max_iterations,
                        "{what}: {e} above the cap {}",
                        options.max_iterations
                    );
                    assert!(!residual.is_nan(), "{what}: {e}");
                    assert!(!options.accept_unconverged, "{what}: {e}");
                }
                Error::InvalidOption(_) => {
                    // A bad tolerance, or a shape other than 2/3 for the κ scheme (which has
                    // no shape parameter).
                    let kappa_shape = scheme == Scheme::Kappa
                        && match shape {
                            Shape::Neutral => false,
                            Shape::Global(a) => *a != 2.0 / 3.0,
                            Shape::PerPoint(v) => v.iter().any(|&a| a != 2.0 / 3.0),
                        };
                    assert!(
                        kappa_shape || !(options.tolerance > 0.0 && options.tolerance.is_finite()),
                        "{what}: {e}"
                    );
                }
                _ => check_shape_error(e, scheme, shape, n, closed, what),
            }
            return;
        }
    };
    assert!(
        rounded_pair.is_none(),
        "{what}: solved, but points {rounded_pair:?} and the next coincide to within their rounding"
    );
    check_spline2d(spline, points, closed, scheme, options, what);
}

/// Checks every property a solved 2D spline claims.
pub fn check_spline2d(
    spline: &Spline,
    points: &[Point],
    closed: bool,
    scheme: Scheme,
    options: &SolveOptions,
    what: &str,
) {
    let pts = arrays(points);
    let n = points.len();
    let size = size_of(&pts);
    assert!(
        size > 0.0 && size.is_finite(),
        "{what}: solved with size {size}"
    );
    assert_eq!(spline.is_closed(), closed, "{what}");
    assert_eq!(spline.scheme(), scheme, "{what}");
    let report = spline.report();
    assert!(
        report.iterations <= options.max_iterations,
        "{what}: {report:?}"
    );
    assert!(
        report.converged || options.accept_unconverged,
        "{what}: {report:?}"
    );
    assert!(!report.residual.is_nan(), "{what}: {report:?}");
    let segs = spline.segments();
    for (j, s) in segs.iter().enumerate() {
        assert!(
            s.q.iter().all(|p| p.is_finite()) && s.t_max.is_finite() && s.a.is_finite(),
            "{what} seg {j}: not finite: {s:?}"
        );
        assert!((0.0..=1.0).contains(&s.t_max), "{what} seg {j}: {s:?}");
    }
    if !closed && n == 2 {
        assert_eq!(segs.len(), 1, "{what}");
        assert_eq!(segs[0].eval(0.0), points[0], "{what}");
        assert!(
            segs[0].eval(1.0).distance(points[1]) <= floor(magnitude(&pts)),
            "{what}"
        );
        return;
    }
    assert_eq!(segs.len(), if closed { n } else { n - 2 }, "{what}");
    if !report.converged {
        return;
    }
    // Two consecutive points closer than `FRAGILE` of the size (yet not repeated): the
    // solution exists, but its peak and G2 conditions are resolved only to a tolerance that
    // grows as the gap shrinks; there the oracle checks finiteness, interpolation and G0.
    let fragile = (0..if closed { n } else { n - 1 })
        .any(|i| points[i].distance(points[(i + 1) % n]) < FRAGILE * size);
    let mag = magnitude(&pts).max(
        segs.iter()
            .flat_map(|s| s.q)
            .fold(0.0, |m, p| m.max(p.x.abs()).max(p.y.abs())),
    );
    let tol = (INTERP * size).max(floor(mag)) + options.tolerance * size * 10.0;
    let off = if closed { 0 } else { 1 };
    for (j, seg) in segs.iter().enumerate() {
        let p = points[j + off];
        let err = seg.eval(seg.t_max).distance(p);
        assert!(
            err <= tol,
            "{what} seg {j}: interpolation error {err} (size {size}, tol {tol})"
        );
        if !fragile {
            check_peak(seg, mag, PEAK.max(1e3 * options.tolerance), what, j);
        }
    }
    // Joints: continuous, G1, equal |κ|.
    let joints = if closed { n } else { segs.len() - 1 };
    // (2×: the solver measures the spread in its own frame, rounded differently.)
    let straight = !closed && line_spread(&pts) <= 2.0 * COLLINEAR;
    for j in 0..joints {
        let (a, b) = (&segs[j], &segs[(j + 1) % segs.len()]);
        let (pa, pb) = (a.eval(1.0), b.eval(0.0));
        assert!(
            pa.distance(pb) <= floor(mag),
            "{what} joint {j}: gap {}",
            pa.distance(pb)
        );
        if fragile {
            continue;
        }
        let (da, db) = (seg_deriv(a, 1.0), seg_deriv(b, 0.0));
        let h = handle(a).min(handle(b));
        // The direction of a handle of length h is known to ε·mag/h.
        let angle_floor = floor(mag) / h.max(f64::MIN_POSITIVE);
        let (ta, tb) = (da / da.hypot(), db / db.hypot());
        let (cross, dot) = (ta.cross(tb), ta.dot(tb));
        assert!(
            (cross.abs() <= 1e-9_f64.max(angle_floor) && dot > 0.0) || angle_floor > 0.1,
            "{what} joint {j}: tangents {ta:?} {tb:?}"
        );
        // |κ| in a frame centred at the joint.
        let (ka, kb) = (curvature_at(a, 1.0, pa), curvature_at(b, 0.0, pa));
        let (ka, kb) = (ka.abs(), kb.abs());
        let thin = thinness(a).min(thinness(b));
        // Control points off by δ change |κ| at a joint by about δ/(h·thin) relative (the
        // cross product of the legs, |r||s|·thin, changes by δ(|r| + |s|)). δ is the
        // rounding of the coordinates, and for open input within `COLLINEAR` of a line
        // (which the solver solves as straight, with the control points at the points and
        // |κ| ≈ 0 up to that spread) also the spread itself.
        let delta = 1e3 * f64::EPSILON * mag
            + if straight {
                16.0 * COLLINEAR * size
            } else {
                0.0
            };
        let g2_floor = (delta / (h * thin).max(f64::MIN_POSITIVE))
            .max(kappa_rel_error(a, 1.0, delta))
            .max(kappa_rel_error(b, 0.0, delta));
        let g2 = G2.max(1e3 * options.tolerance).max(g2_floor);
        // Where the joint's |κ| is tiny next to the peaks (a → 1 flattens the joints), the
        // dimensionless G2 condition bounds the mismatch relative to the peaks.
        let peaks = a.curvature(a.t_max).abs().max(b.curvature(b.t_max).abs());
        let peaks = if peaks.is_finite() { peaks } else { 0.0 };
        assert!(
            (ka - kb).abs() <= g2 * ka.max(kb) + G2 * peaks || !(ka.max(kb) > 0.0),
            "{what} joint {j}: |κ| {ka} vs {kb} (floor {g2_floor})"
        );
    }
    if !closed {
        assert_eq!(segs[0].q[0], points[0], "{what}: start");
        assert_eq!(segs[segs.len() - 1].q[2], points[n - 1], "{what}: end");
    }
}

/// `sin` of the angle between the legs of the control triangle of a 3D segment at an end
/// (its last three control points at `t = 1` when `at_end`, else its first three).
fn end_thinness(s: &kappa::analysis::SpaceBez, at_end: bool) -> f64 {
    let p = s.control_points();
    let n = p.len();
    let (q0, q1, q2) = if at_end {
        (p[n - 3], p[n - 2], p[n - 1])
    } else {
        (p[0], p[1], p[2])
    };
    let (r, v) = (q1 - q0, q2 - q1);
    (r.cross(v).length() / (r.length() * v.length())).max(f64::MIN_POSITIVE)
}

/// The shorter handle of a segment's control triangle.
fn handle(s: &Segment<Point>) -> f64 {
    s.q[0].distance(s.q[1]).min(s.q[1].distance(s.q[2]))
}

/// `sin` of the angle between the legs of the control triangle.
fn thinness(s: &Segment<Point>) -> f64 {
    let (r, v) = (s.q[1] - s.q[0], s.q[2] - s.q[1]);
    (r.cross(v).abs() / (r.hypot() * v.hypot())).max(f64::MIN_POSITIVE)
}

/// The signed curvature of `s` at `t`, computed with `origin` moved to zero (so that the
/// control points' magnitude does not swamp a small segment).
fn curvature_at(s: &Segment<Point>, t: f64, origin: Point) -> f64 {
    let mut moved = *s;
    for q in &mut moved.q {
        *q = (*q - origin).to_point();
    }
    moved.curvature(t)
}

/// The peak at `t_max`: a maximum of |κ| on the segment for κ and εκ-cubic, the extremum
/// the segment reports for εκ-trig.
fn check_peak(seg: &Segment<Point>, mag: f64, peak: f64, what: &str, j: usize) {
    if thinness(seg) < DEGENERATE {
        // A straight piece (no peak to check) or a near-cusp (a doubled-back triangle),
        // where |κ| near t_max swings across orders of magnitude within rounding of t.
        return;
    }
    let origin = seg.eval(seg.t_max);
    let k = |t: f64| curvature_at(seg, t, origin).abs();
    let h = handle(seg).max(f64::MIN_POSITIVE);
    // |κ| from control points with rounding δ = ε·mag is known to about δ/h² absolute (a
    // straight-ish segment) and to δ/(h·thin) relative: κ = (C′ × C″)/|C′|³, where C′ × C″
    // is a multiple of the legs' cross product |r||s|·thin (changed by δ(|r| + |s|) ≤ 2δ|r||s|/h)
    // and |C′| ≥ about h·thin (the speed at a near-cusp's peak), changed by δ. Both
    // |κ(t_max)| and the probe carry that error, so the probe may exceed |κ(t_max)| by twice
    // it (found by fuzzing: a drawing 1e-12 of its coordinates wide, whose segments' peaks in
    // user coordinates differ by up to 100 % from the same solution solved at the origin).
    let thin = thinness(seg);
    let k_floor = 1e3 * f64::EPSILON * mag / (h * h * thin);
    let k_rel = 2e3 * f64::EPSILON * mag / (h * thin);
    let k0 = k(seg.t_max);
    let slack = |v: f64| v * (1.0 + peak + k_rel) + k_floor;
    match (seg.scheme, seg.extremum()) {
        (Scheme::Kappa | Scheme::EkCubic, kind) => {
            assert_eq!(kind, Extremum::Max, "{what} seg {j}: {seg:?}");
            for i in 0..=64 {
                let t = i as f64 / 64.0;
                assert!(
                    k(t) <= slack(k0),
                    "{what} seg {j}: |κ({t})| = {} above |κ(t_max = {})| = {k0}",
                    k(t),
                    seg.t_max
                );
            }
        }
        // εκ-trig: a local extremum of the kind reported, probed close to t_max (a sharp
        // peak near a segment end is narrow in t).
        (_, kind) => {
            let d = 1e-3 * seg.t_max.min(1.0 - seg.t_max);
            if d < 1e-9 {
                return;
            }
            for t in [seg.t_max - d, seg.t_max + d] {
                if kind == Extremum::Max {
                    assert!(k(t) <= slack(k0), "{what} seg {j}: not a local maximum");
                } else {
                    assert!(slack(k(t)) >= k0, "{what} seg {j}: not a local minimum");
                }
            }
        }
    }
}

/// Checks the answer of a Hermite solve.
pub fn check_hermite(
    h: &kappa::intrinsic::Hermite,
    profile: &kappa::intrinsic::Profile,
    result: &Result<kappa::intrinsic::IntrinsicSeg, Error>,
    what: &str,
) {
    use kappa::intrinsic::Control;
    let (p0, p1) = (h.start.point, h.end.point);
    let seg = match result {
        Ok(seg) => seg,
        Err(e) => {
            match *e {
                Error::NonFinitePoint { index } => {
                    assert!(![p0, p1][index].is_finite(), "{what}: {e}");
                }
                Error::RepeatedPoint { .. } => {
                    let scale = p0.to_vec2().hypot().max(p1.to_vec2().hypot());
                    assert!(p0.distance(p1) <= 1e-11 * scale, "{what}: {e}");
                }
                Error::ExtentOverflow => {
                    assert!(!p0.distance(p1).is_finite(), "{what}: {e}");
                }
                Error::InvalidOption(_) | Error::NoHermiteSolution { .. } => {}
                // The work cap ran out (the default cap of `Hermite::solve`): a count within
                // the cap and a residual that is a number, not a success.
                Error::NotConverged {
                    iterations,
                    residual,
                } => {
                    let cap = kappa::SolveOptions::default().max_iterations;
                    assert!(iterations <= cap, "{what}: {e}");
                    assert!(!residual.is_nan() && residual > 0.0, "{what}: {e}");
                }
                _ => panic!("{what}: unexpected error {e:?}"),
            }
            return;
        }
    };
    let n = profile.degree();
    assert_eq!(seg.degree(), n, "{what}");
    assert!(
        seg.length().is_finite() && seg.length() > 0.0,
        "{what}: length {}",
        seg.length()
    );
    let k = seg.curvatures();
    assert!(k.iter().all(|v| v.is_finite()), "{what}: {k:?}");
    let err = h.end_error(seg);
    assert!(
        err <= kappa::intrinsic::END_TOLERANCE,
        "{what}: end error {err}"
    );
    // The profile's constraints hold (curvatures in the data's units).
    let chord = p0.distance(p1);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs()) + 1e-12 / chord;
    for (i, c) in profile.controls.iter().enumerate() {
        match *c {
            Control::Given(v) => assert!(close(k[i], v), "{what}: κ{i} = {} not {v}", k[i]),
            Control::Same(j) => assert!(close(k[i], k[j]), "{what}: κ{i} ≠ κ{j}: {k:?}"),
            Control::Free => {}
        }
    }
    if let Some(w) = &profile.weights {
        assert_eq!(seg.weights(), Some(&w[..]), "{what}");
    }
}

/// Checks a B-spline given as Bézier segments `segs` (control points as arrays) against the
/// points it interpolates, with `curvature(t)` and the reported maximum.
#[allow(clippy::too_many_arguments)]
fn check_bspline_parts<const D: usize>(
    pts: &[[f64; D]],
    closed: bool,
    segs: &[[[f64; D]; 4]],
    eval: impl Fn(f64) -> [f64; D],
    curvature: impl Fn(f64) -> f64,
    max: &kappa::BSplineCurvatureMax,
    control: &[[f64; D]],
    what: &str,
) {
    let n = pts.len();
    let size = size_of(pts);
    let mag = magnitude(pts).max(magnitude(control));
    assert!(
        control.iter().flatten().all(|v| v.is_finite()),
        "{what}: control points not finite"
    );
    assert_eq!(segs.len(), if closed { n } else { n - 1 }, "{what}");
    let tol = 1e-9 * size + floor(mag);
    let dist = |a: [f64; D], b: [f64; D]| (0..D).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt();
    for (k, p) in pts.iter().enumerate() {
        let d = dist(eval(k as f64), *p);
        assert!(d <= tol, "{what}: point {k} missed by {d} (size {size})");
    }
    // C1 and C2 at every joint (they hold only if the interpolation system was solved).
    let d1 = |s: &[[f64; D]; 4], t: f64| -> [f64; D] {
        core::array::from_fn(|k| {
            let (a, b, c) = (s[1][k] - s[0][k], s[2][k] - s[1][k], s[3][k] - s[2][k]);
            3.0 * ((1.0 - t) * (1.0 - t) * a + 2.0 * (1.0 - t) * t * b + t * t * c)
        })
    };
    // Second differences as differences of differences: `s₂ − 2s₁ + s₀` overflows when the
    // coordinates are within a factor 2 of f64::MAX (2s₁ = ±∞) although the differences, at
    // most a few extents, are finite; this form is exact to the same rounding otherwise.
    let d2 = |s: &[[f64; D]; 4], t: f64| -> [f64; D] {
        core::array::from_fn(|k| {
            let (a, b) = (
                (s[2][k] - s[1][k]) - (s[1][k] - s[0][k]),
                (s[3][k] - s[2][k]) - (s[2][k] - s[1][k]),
            );
            6.0 * ((1.0 - t) * a + t * b)
        })
    };
    let joints = if closed { n } else { n - 2 };
    for j in 0..joints {
        let (a, b) = (&segs[j], &segs[(j + 1) % segs.len()]);
        assert!(dist(a[3], b[0]) <= floor(mag), "{what}: gap at joint {j}");
        let e1 = dist(d1(a, 1.0), d1(b, 0.0));
        let e2 = dist(d2(a, 1.0), d2(b, 0.0));
        assert!(
            e1 <= 1e-9 * size + 8.0 * floor(mag),
            "{what}: C1 at joint {j}: {e1}"
        );
        assert!(
            e2 <= 1e-8 * size + 64.0 * floor(mag),
            "{what}: C2 at joint {j}: {e2}"
        );
    }
    if !closed {
        // Relaxed ends: no curvature.
        for (s, t) in [(&segs[0], 0.0), (&segs[segs.len() - 1], 1.0)] {
            let e = dist(d2(s, t), [0.0; D]);
            assert!(
                e <= 1e-8 * size + 64.0 * floor(mag),
                "{what}: end curvature {e}"
            );
        }
    }
    // The maximum: not NaN, attained where reported, and no sample above it.
    assert!(max.value >= 0.0, "{what}: max {max:?}");
    let range = if closed { n as f64 } else { (n - 1) as f64 };
    assert!(
        max.params.iter().all(|&t| (0.0..=range).contains(&t)),
        "{what}: {max:?}"
    );
    if max.value.is_finite() && max.value > 0.0 {
        assert!(!max.params.is_empty(), "{what}: {max:?}");
        if max.value * size > NEAR_CUSP {
            return;
        }
        // |κ| from coordinates rounded to ε·mag is known to about ε·mag·κ relative (the
        // rounding against the radius of curvature): at a near-cusp much worse than 1e-6.
        let rel = 1e-6 + 1e3 * f64::EPSILON * mag * max.value;
        // The rounding floor of |κ| = |r′ × r″|/|r′|³ at t: with positions known to
        // e = floor(mag), r′ = 3Δ is known to 6e and r″ = 6Δ² to 24e, so r′ × r″ to
        // 6e|r″| + 24e|r′|, and |κ| to that over |r′|³. Nearly straight pieces (collinear to
        // within rounding) have |r′ × r″| at this floor, and next to a reversal of direction
        // (|r′| small) the floor of |κ| is large: neither the maximum nor a sample can be
        // resolved below it.
        let noise = |t: f64| -> f64 {
            let t = t.clamp(0.0, range);
            let i = (t.floor() as usize).min(segs.len() - 1);
            let u = t - i as f64;
            let norm = |v: [f64; D]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
            let (v, a) = (norm(d1(&segs[i], u)), norm(d2(&segs[i], u)));
            let e = floor(mag);
            let k = (6.0 * e * a + 24.0 * e * v) / (v * v * v);
            if k.is_nan() {
                f64::INFINITY
            } else {
                k
            }
        };
        for &t in &max.params {
            let k = curvature(t).abs();
            assert!(
                (k - max.value).abs() <= rel * max.value + 1e-9 / size + noise(t),
                "{what}: |κ({t})| = {k}, max {max:?}"
            );
        }
        for i in 0..segs.len() {
            for s in 0..=16 {
                let t = i as f64 + s as f64 / 16.0;
                let k = curvature(t.min(range)).abs();
                assert!(
                    !(k > max.value * (1.0 + rel) + 1e-9 / size + noise(t)),
                    "{what}: |κ({t})| = {k} above the maximum {max:?}"
                );
            }
        }
    }
}

/// A point type the B-spline oracles read as coordinates.
pub trait Coordinates<const D: usize>: kappa::BSplinePoint + Copy {
    /// The coordinates.
    fn array(self) -> [f64; D];
}

impl Coordinates<2> for Point {
    fn array(self) -> [f64; 2] {
        [self.x, self.y]
    }
}

impl Coordinates<3> for Point3 {
    fn array(self) -> [f64; 3] {
        [self.x, self.y, self.z]
    }
}

/// Checks the answer of a B-spline interpolation (2D or 3D) and its maximum curvature.
pub fn check_bspline<P: Coordinates<D>, const D: usize>(
    points: &[P],
    closed: bool,
    result: &Result<kappa::BSpline<P>, Error>,
    what: &str,
) {
    let pts: Vec<[f64; D]> = points.iter().map(|&p| p.array()).collect();
    let s = match result {
        Ok(s) => s,
        Err(e) => {
            assert!(check_point_error(e, &pts, closed, what), "{what}: {e:?}");
            return;
        }
    };
    let segs: Vec<[[f64; D]; 4]> = (0..s.segment_count())
        .map(|i| s.segment_points(i).unwrap().map(P::array))
        .collect();
    let control: Vec<[f64; D]> = s.control_points().iter().map(|&p| p.array()).collect();
    let max = s.max_curvature();
    check_bspline_parts(
        &pts,
        closed,
        &segs,
        |t| s.eval(t).array(),
        |t| s.curvature(t),
        &max,
        &control,
        what,
    );
}

/// Checks the answer of a 2D B-spline interpolation and its maximum curvature.
pub fn check_bspline2d(
    points: &[Point],
    closed: bool,
    result: &Result<kappa::BSpline, Error>,
    what: &str,
) {
    check_bspline(points, closed, result, what);
}

/// Checks the answer of a 3D B-spline interpolation and its maximum curvature.
pub fn check_bspline3d(
    points: &[Point3],
    closed: bool,
    result: &Result<kappa::BSpline3, Error>,
    what: &str,
) {
    check_bspline(points, closed, result, what);
}

/// Checks the answer of a κ-space curve.
pub fn check_space(
    points: &[Point3],
    closed: bool,
    options: &kappa::space::SpaceOptions,
    result: &Result<kappa::SpaceCurve, Error>,
    what: &str,
) {
    use kappa::analysis::CurvatureAnalysis;
    let pts = arrays3(points);
    let curve = match result {
        Ok(c) => c,
        Err(e) => {
            if check_point_error(e, &pts, closed, what) {
                return;
            }
            match e {
                Error::Collinear => assert!(
                    line_spread(&pts) <= 1e-10 + floor(magnitude(&pts)) / size_of(&pts),
                    "{what}: {e}"
                ),
                Error::NotConverged { residual, .. } => assert!(!residual.is_nan(), "{what}"),
                Error::InvalidOption(_) => {
                    // Exactly the documented option errors: a replaced range outside
                    // `[0, 1 − MIN_REPLACED]`, `[MIN_REPLACED, 1]`, or a γ list of the
                    // wrong length.
                    use kappa::space::{Gamma, Replace, MIN_REPLACED};
                    let bad_range = match options.replace {
                        Replace::None => false,
                        Replace::Partial { t1, t2 } => {
                            !(t1 >= 0.0 && 1.0 - t1 >= MIN_REPLACED)
                                || !(MIN_REPLACED..=1.0).contains(&t2)
                        }
                    };
                    // One joint per κ-segment of a closed curve; an open curve has one
                    // segment per interior point (one for two points), a joint between two.
                    let joints = if closed {
                        pts.len()
                    } else {
                        pts.len().saturating_sub(3)
                    };
                    let bad_list =
                        matches!(&options.gamma, Gamma::PerJoint(l) if l.len() != joints);
                    assert!(bad_range || bad_list, "{what}: {e}");
                }
                Error::GammaOutOfRange { .. } => {
                    assert!(
                        matches!(options.gamma, kappa::space::Gamma::PerJoint(_)),
                        "{what}: {e}"
                    );
                }
                _ => panic!("{what}: unexpected error {e:?}"),
            }
            return;
        }
    };
    let size = size_of(&pts);
    let segs = curve.segments();
    let mag = segs
        .iter()
        .flat_map(|s| s.control_points().to_vec())
        .fold(magnitude(&pts), |m, p| {
            m.max(p.x.abs()).max(p.y.abs()).max(p.z.abs())
        });
    for s in segs {
        assert!(
            s.control_points().iter().all(|p| p.is_finite()),
            "{what}: {s:?}"
        );
    }
    let n = pts.len();
    let fragile = (0..if closed { n } else { n - 1 }).any(|i| {
        let (a, b) = (points[i], points[(i + 1) % n]);
        a.distance(b) < FRAGILE * size
    });
    let gaps = curve.curvature_vector_gaps();
    for (j, gap) in curve.continuity().iter().zip(&gaps) {
        if fragile {
            break;
        }
        // The κ-curve's own joint, kept (documented G1 with equal |κ|, not G2): only G0, G1
        // and the equal |κ| are claimed there.
        let kept = curve.kept_joints().contains(&j.before);
        let c = j.continuity;
        assert!(c.position_gap <= floor(mag), "{what}: G0 at {j:?}");
        let (a, b) = (&segs[j.before], &segs[j.after]);
        let h = |s: &kappa::analysis::SpaceBez| {
            let p = s.control_points();
            p[0].distance(p[1])
                .min(p[p.len() - 2].distance(p[p.len() - 1]))
        };
        let hmin = h(a).min(h(b)).max(f64::MIN_POSITIVE);
        let angle_floor = floor(mag) / hmin;
        assert!(
            c.tangent_angle <= 1e-9f64.max(angle_floor) || angle_floor > 0.1,
            "{what}: G1 at {j:?}"
        );
        // The rounding floor of the curvature vector `κ = ((r′ × r″) × r′) / |r′|⁴` at an
        // end: control points rounded by `floor(mag)` move `r″`'s normal part by about
        // `ε mag` against `κ h²` (the first term), and they also turn the tangent `r′` (of
        // length ~h) by `angle_floor`, which turns the normal — and the curvature vector
        // with it — by the same angle and changes `|r′|³` by up to three times that: a
        // relative change of about `4 angle_floor` (the second term; it dominates at
        // near-cusps, where `κ h²` is large but `h` is a few units in the last place).
        // `kappa::analysis` reports κ = 0 at a stall, where `|r′|` is at most 1e-12 of the
        // largest hodograph control point (the curvature is undefined there): no G2 claim
        // can be checked at such an end.
        let stall = |s: &kappa::analysis::SpaceBez, at_end: bool| {
            let p = s.control_points();
            let longest = p.windows(2).fold(0.0f64, |m, w| m.max(w[0].distance(w[1])));
            let h = if at_end {
                p[p.len() - 2].distance(p[p.len() - 1])
            } else {
                p[0].distance(p[1])
            };
            h <= 1e-12 * longest
        };
        if stall(a, true) || stall(b, false) {
            continue;
        }
        if kept {
            let (ka, kb) = (
                CurvatureAnalysis::curvature(a, 1.0),
                CurvatureAnalysis::curvature(b, 0.0),
            );
            // As for 2D joints (`check_solution`): control points off by δ change |κ| at a
            // joint by about δ/(h·thin) relative, `thin` the sine of the angle between the
            // legs of a control triangle there. On nearly collinear data that dominates
            // (the solver's convergence test allows the same floor, `ROUNDING_FLOOR` over
            // the thinness of the triangles of middle control points).
            let thin = end_thinness(a, true).min(end_thinness(b, false));
            let g2_floor = (1e3 * f64::EPSILON * mag / (ka.max(kb) * hmin * hmin))
                .max(4.0 * angle_floor)
                .max(1e3 * f64::EPSILON * mag / (hmin * thin));
            assert!(
                !((ka - kb).abs() > 1e-8f64.max(g2_floor) * ka.max(kb)),
                "{what}: |κ| differs at the kept joint {j:?}"
            );
        } else if a.degree() == 4 || b.degree() == 4 {
            let kappa =
                CurvatureAnalysis::curvature(a, 1.0).max(CurvatureAnalysis::curvature(b, 0.0));
            let g2_floor =
                (1e3 * f64::EPSILON * mag / (kappa * hmin * hmin)).max(4.0 * angle_floor);
            assert!(
                !(*gap > 1e-8f64.max(g2_floor)),
                "{what}: G2 gap {gap:e} (floor {g2_floor:e}) at {j:?}"
            );
        }
    }
    // Interpolation at the peaks (points given up at a joint: near the curve).
    let inputs = if closed {
        points
    } else {
        &points[1..points.len() - 1]
    };
    assert_eq!(curve.point_params().len(), inputs.len(), "{what}");
    let missed: Vec<usize> = curve.missed_points().iter().map(|m| m.0).collect();
    let r = match options.replace {
        kappa::space::Replace::None => 0.0,
        kappa::space::Replace::Partial { t1, t2 } => (1.0 - t1).max(t2),
    };
    for (k, (&(seg, t), p)) in curve.point_params().iter().zip(inputs).enumerate() {
        let d = segs[seg].eval(t).distance(*p);
        let allowed = if missed.contains(&k) {
            size * 1e-2f64.max(r * r)
        } else {
            1e-9 * size
        };
        assert!(
            d <= allowed + floor(mag),
            "{what}: point {k} is {d} away (size {size})"
        );
    }
    if !closed {
        let (a, b) = curve.ends();
        assert_eq!(a, points[0], "{what}");
        assert_eq!(b, points[points.len() - 1], "{what}");
    }
}

/// Checks the state of an editor: every piece shown without an error is the solved curve of
/// its points; the path and the hit test are finite.
pub fn check_editor(ed: &kappa::editor::Editor, what: &str) {
    let doc = ed.doc();
    for k in 0..ed.pieces() {
        let idx = ed.piece_points(k);
        assert!(
            idx.iter().all(|&i| i < doc.points.len()),
            "{what}: piece {k}"
        );
        if let (Some(s), None) = (ed.piece_spline(k), ed.piece_error(k)) {
            let pts: Vec<Point> = idx.iter().map(|&i| doc.points[i].point()).collect();
            check_spline2d(
                s,
                &pts,
                s.is_closed(),
                doc.scheme,
                &SolveOptions::default(),
                &format!("{what}: piece {k}"),
            );
        }
    }
    for el in ed.to_bezpath().elements() {
        let ok = match *el {
            kurbo::PathEl::MoveTo(p) | kurbo::PathEl::LineTo(p) => p.is_finite(),
            kurbo::PathEl::QuadTo(a, b) => a.is_finite() && b.is_finite(),
            kurbo::PathEl::CurveTo(a, b, c) => a.is_finite() && b.is_finite() && c.is_finite(),
            kurbo::PathEl::ClosePath => true,
        };
        assert!(ok, "{what}: path element {el:?}");
    }
    if let Some(p) = doc.points.first() {
        if let Some(hit) = ed.hit_test(p.point()) {
            assert!(
                hit.distance >= 0.0 && hit.point.is_finite(),
                "{what}: {hit:?}"
            );
        }
    }
}

/// Checks a parsed font: outlines of a few characters, and drafts of the small ones.
#[cfg(feature = "font")]
pub fn check_font(font: &kappa::glyph::FontOutlines, data: &[u8]) {
    use kappa::glyph::{draft, DraftOptions};
    let upem = font.units_per_em();
    assert!(upem.is_finite() && upem > 0.0, "units per em {upem}");
    let extra = data.last().map_or('x', |&b| char::from(b));
    for ch in ['a', 'S', 'o', ' ', extra] {
        let glyph = match font.glyph(ch) {
            Ok(g) => g,
            Err(Error::MissingGlyph { ch: c }) => {
                assert_eq!(c, ch);
                continue;
            }
            Err(Error::Font(_)) => continue,
            Err(e) => panic!("glyph {ch:?}: unexpected error {e:?}"),
        };
        assert!(glyph.advance.is_finite(), "{glyph:?}");
        let els = glyph.path.elements();
        let finite = els.iter().all(|el| match *el {
            kurbo::PathEl::MoveTo(p) | kurbo::PathEl::LineTo(p) => p.is_finite(),
            kurbo::PathEl::QuadTo(a, b) => a.is_finite() && b.is_finite(),
            kurbo::PathEl::CurveTo(a, b, c) => a.is_finite() && b.is_finite() && c.is_finite(),
            kurbo::PathEl::ClosePath => true,
        });
        assert!(finite, "{glyph:?}");
        if els.is_empty() || els.len() > 48 {
            continue;
        }
        match draft(&glyph.path, &DraftOptions::for_units_per_em(upem)) {
            Ok(d) => {
                for piece in d.pieces() {
                    let pts: Vec<Point> = piece.anchors.iter().map(|a| a.point).collect();
                    check_spline2d(
                        &piece.spline,
                        &pts,
                        piece.closed,
                        piece.spline.scheme(),
                        &SolveOptions::default(),
                        &format!("draft of {ch:?}"),
                    );
                    if let Some(h) = piece.hausdorff {
                        assert!(h.is_finite() && h >= 0.0, "{ch:?}: Hausdorff {h}");
                    }
                }
            }
            Err(
                Error::NotConverged { .. }
                | Error::Collinear
                | Error::RepeatedPoint { .. }
                | Error::TooFewPoints { .. }
                | Error::InvalidOption(_)
                | Error::NonFinitePoint { .. },
            ) => {}
            Err(e) => panic!("draft of {ch:?}: unexpected error {e:?}"),
        }
    }
}
