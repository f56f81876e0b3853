//! Cubic Bézier paths for curves that are not polynomial.
//!
//! Trigonometric εκ-segments, curves given by their curvature and projected 3D quartics
//! have no exact cubic Bézier form. This module turns any sequence of such segments into
//! a [`BezPath`] and *measures* how far the result is from the exact curve instead of
//! trusting the fitter. Three methods ([`FitMethod`]):
//!
//! - kurbo's curve fitting, [`kurbo::fit_to_bezpath`] (the default) or the optimizing
//!   [`kurbo::fit_to_bezpath_opt`]: the fewest cubics, at about 0.1 ms (optimizing: 10 ms)
//!   per trigonometric segment;
//! - Hermite subdivision: each piece is the cubic with the source's end points and end
//!   derivatives, split (into as many equal pieces as the `h⁴` error law predicts) until 8
//!   interior samples of the *parametric* error are within the tolerance. The parametric
//!   error bounds the distance to the curve, so the check is conservative; it needs about
//!   twice the cubics but is over 20 times faster (interactive previews, large drawings).
//!
//! A segment only has to implement [`ParamCurveFit`] on `t ∈ [0, 1]`: position and
//! derivative ([`ParamCurveFit::sample_pt_deriv`]), a one-sided tangent
//! ([`ParamCurveFit::sample_pt_tangent`]) and, where the speed can vanish, a cusp
//! ([`ParamCurveFit::break_cusp`]; [`speed_cusp`] finds one by sampling).
//!
//! Each segment is fitted on its own, so the path has a joint at every segment boundary.
//! kurbo's fitted cubics take their end tangents from the source, so a joint that is G1 in
//! the source stays G1 in the path (up to the rounding of the tangent directions).
//!
//! ```
//! use kappa::fit::{fit, FitMethod, FitOptions};
//! use kappa::Spline;
//! use kurbo::{ParamCurveNearest, Point};
//!
//! // An εκ-curve in the trigonometric basis has no exact cubic form.
//! let points = [(0.0, 0.0), (100.0, 10.0), (120.0, 90.0), (20.0, 110.0)].map(Point::from);
//! let curve = Spline::ek_trig(&points, true, 0.75)?;
//! let trig: Vec<_> = curve.segments().iter().map(|s| s.to_trig()).collect();
//! let fitted = fit(&trig, true, &FitOptions::relative(1e-4))?;
//! assert_eq!(fitted.cubics.len(), trig.len()); // cubics per source segment
//! assert!(fitted.max_distance <= fitted.tolerance); // measured, not assumed
//! // The input points, on the exact curve, are within the tolerance of the path.
//! for p in points {
//!     let d = fitted.path.segments().map(|s| s.nearest(p, 1e-9).distance_sq.sqrt());
//!     assert!(d.fold(f64::INFINITY, f64::min) <= fitted.tolerance);
//! }
//! // Hermite subdivision: faster, more cubics, the same bound.
//! let options = FitOptions { method: FitMethod::Hermite, ..FitOptions::relative(1e-4) };
//! let quick = fit(&trig, true, &options)?;
//! assert!(quick.max_distance <= quick.tolerance);
//! # Ok::<(), kappa::Error>(())
//! ```

use core::ops::Range;

use kurbo::{
    fit_to_bezpath, fit_to_bezpath_opt, BezPath, CubicBez, ParamCurveFit, ParamCurveNearest,
    PathEl, PathSeg, Point, Vec2,
};

use crate::Error;

/// How close a fitted path must stay to the exact curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FitTolerance {
    /// A distance in the curve's own units.
    Absolute(f64),
    /// A fraction of the curve's size (the larger side of the bounding box of the segment
    /// ends and midpoints).
    Relative(f64),
}

/// How [`fit`] builds the cubics (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum FitMethod {
    /// [`kurbo::fit_to_bezpath`].
    #[default]
    Kurbo,
    /// [`kurbo::fit_to_bezpath_opt`]: fewer cubics, several times slower.
    KurboOptimized,
    /// Hermite cubics on split parameter ranges until the parametric error is within the
    /// tolerance (at most 12 levels of splitting).
    Hermite,
}

/// Options of [`fit`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitOptions {
    /// The accuracy requested from the fitter. Default: `Relative(1e-4)`.
    pub tolerance: FitTolerance,
    /// The fitting method. Default: [`FitMethod::Kurbo`].
    pub method: FitMethod,
    /// Source samples per segment used to measure [`Fitted::max_distance`] (clamped to
    /// `2..=4096`; 0 skips the measurement). Default: 32.
    pub check_samples: usize,
}

impl Default for FitOptions {
    fn default() -> FitOptions {
        FitOptions {
            tolerance: FitTolerance::Relative(1e-4),
            method: FitMethod::Kurbo,
            check_samples: 32,
        }
    }
}

impl FitOptions {
    /// Options with an absolute tolerance and the other fields at their defaults.
    pub fn absolute(tolerance: f64) -> FitOptions {
        FitOptions {
            tolerance: FitTolerance::Absolute(tolerance),
            ..FitOptions::default()
        }
    }

    /// Options with a relative tolerance and the other fields at their defaults.
    pub fn relative(tolerance: f64) -> FitOptions {
        FitOptions {
            tolerance: FitTolerance::Relative(tolerance),
            ..FitOptions::default()
        }
    }
}

/// The result of [`fit`].
#[derive(Clone, Debug)]
pub struct Fitted {
    /// The fitted path: one `MoveTo`, cubic `CurveTo`s, and a `ClosePath` for closed curves.
    pub path: BezPath,
    /// The number of cubics each source segment became.
    pub cubics: Vec<usize>,
    /// The absolute tolerance that was requested from the fitter.
    pub tolerance: f64,
    /// The largest distance measured from a source sample to the fitted cubics of its
    /// segment (0 when [`FitOptions::check_samples`] is 0). For [`FitMethod::Hermite`] this
    /// is the largest parametric error sampled while subdividing, an upper bound of the
    /// distance at those samples, and `check_samples` is not used.
    pub max_distance: f64,
}

impl Fitted {
    /// The total number of cubics in the path.
    pub fn cubic_count(&self) -> usize {
        self.cubics.iter().sum()
    }
}

/// The cubic that traces a segment exactly: lines and quadratics raised.
pub(crate) fn to_cubic(seg: PathSeg) -> CubicBez {
    match seg {
        PathSeg::Line(l) => CubicBez::new(
            l.p0,
            l.p0.lerp(l.p1, 1.0 / 3.0),
            l.p0.lerp(l.p1, 2.0 / 3.0),
            l.p1,
        ),
        PathSeg::Quad(q) => q.raise(),
        PathSeg::Cubic(c) => c,
    }
}

/// Appends every segment of `path` to `out` as a cubic ([`to_cubic`]).
pub(crate) fn push_cubics(path: &BezPath, out: &mut Vec<CubicBez>) {
    out.extend(path.segments().map(to_cubic));
}

/// Whether a segment is a single point: zero derivative at both ends and the same point at
/// its ends and middle.
fn is_point<C: ParamCurveFit>(segment: &C) -> bool {
    let (p0, d0) = segment.sample_pt_deriv(0.0);
    let (p1, d1) = segment.sample_pt_deriv(1.0);
    let (pm, _) = segment.sample_pt_deriv(0.5);
    d0 == Vec2::ZERO && d1 == Vec2::ZERO && p0 == p1 && p0 == pm
}

/// Fits cubic Béziers to a sequence of segments that join end to end. A segment that is a
/// single point gets no cubic.
///
/// `closed` adds a `ClosePath`; the last segment should end where the first starts, and an
/// end within the tolerance of the start is snapped onto it.
///
/// # Errors
///
/// [`Error::InvalidOption`] for a tolerance that is not finite and positive,
/// [`Error::NonFiniteCurve`] when a segment evaluates to NaN or infinity (checked at the
/// ends, the middle and every measurement sample), and [`Error::TooFewPoints`] for an empty
/// segment list.
pub fn fit<C: ParamCurveFit>(
    segments: &[C],
    closed: bool,
    options: &FitOptions,
) -> Result<Fitted, Error> {
    if segments.is_empty() {
        return Err(Error::TooFewPoints {
            kind: "fitted curve (segments)",
            needed: 1,
            got: 0,
        });
    }
    let tolerance = absolute_tolerance(segments, options.tolerance)?;
    let mut path = BezPath::new();
    let mut cubics = Vec::with_capacity(segments.len());
    let mut max_distance: f64 = 0.0;
    let mut pieces: Vec<CubicBez> = Vec::new();
    for (index, segment) in segments.iter().enumerate() {
        pieces.clear();
        if is_point(segment) {
            // A segment collapsed onto a point (an inflection at an input point): nothing
            // to draw.
            if path.elements().is_empty() {
                path.move_to(segment.sample_pt_deriv(0.0).0);
            }
            cubics.push(0);
            continue;
        }
        let piece = match options.method {
            FitMethod::Kurbo => fit_to_bezpath(segment, tolerance),
            FitMethod::KurboOptimized => fit_to_bezpath_opt(segment, tolerance),
            FitMethod::Hermite => {
                let err = hermite(segment, tolerance, &mut pieces)
                    .ok_or(Error::NonFiniteCurve { segment: index })?;
                max_distance = max_distance.max(err);
                BezPath::new()
            }
        };
        push_cubics(&piece, &mut pieces);
        if pieces.is_empty() || !pieces.iter().all(|c| c.is_finite()) {
            return Err(Error::NonFiniteCurve { segment: index });
        }
        if path.elements().is_empty() {
            path.move_to(pieces[0].p0);
        }
        for c in &pieces {
            path.curve_to(c.p1, c.p2, c.p3);
        }
        cubics.push(pieces.len());
        if options.check_samples > 0 && options.method != FitMethod::Hermite {
            let d = distance_to_pieces(segment, &pieces, options.check_samples, tolerance)
                .ok_or(Error::NonFiniteCurve { segment: index })?;
            max_distance = max_distance.max(d);
        }
    }
    if closed {
        // The last segment ends where the first starts up to rounding; make it exact so
        // that `ClosePath` adds no hairline segment.
        let start = pieces_start(&path);
        if let Some(PathEl::CurveTo(_, _, p3)) = path.elements_mut().last_mut() {
            if (*p3 - start).hypot() <= tolerance {
                *p3 = start;
            }
        }
        path.close_path();
    }
    Ok(Fitted {
        path,
        cubics,
        tolerance,
        max_distance,
    })
}

/// Maximum splitting depth of [`FitMethod::Hermite`].
const HERMITE_DEPTH: u32 = 12;
/// Interior samples of the parametric error per Hermite piece.
const HERMITE_SAMPLES: usize = 8;
/// Most cubics [`FitMethod::Hermite`] makes of one segment. The depth limit alone does not
/// bound the work (up to 64 pieces per split): a curve whose error cannot fall below the
/// tolerance — a tolerance under the rounding of its coordinates, a near-cusp — would split
/// without end; found by the `editor` fuzz target.
const HERMITE_MAX_PIECES: usize = 1 << 12;

/// Appends the Hermite cubics of `segment` to `pieces`; returns the largest parametric error
/// sampled, or `None` if the segment is not finite.
fn hermite<C: ParamCurveFit>(
    segment: &C,
    tolerance: f64,
    pieces: &mut Vec<CubicBez>,
) -> Option<f64> {
    let start = segment.sample_pt_deriv(0.0);
    let end = segment.sample_pt_deriv(1.0);
    let mut worst: f64 = 0.0;
    // Depth-first over ranges, left to right: (t0, t1, sample at t0, sample at t1, depth).
    let mut stack = vec![(0.0, 1.0, start, end, 0u32)];
    while let Some((t0, t1, (p0, d0), (p3, d3), depth)) = stack.pop() {
        if !(p0.is_finite() && d0.is_finite() && p3.is_finite() && d3.is_finite()) {
            return None;
        }
        let h = t1 - t0;
        let cubic = CubicBez::new(p0, p0 + d0 * (h / 3.0), p3 - d3 * (h / 3.0), p3);
        let mut err: f64 = 0.0;
        for i in 1..=HERMITE_SAMPLES {
            let tau = i as f64 / (HERMITE_SAMPLES + 1) as f64;
            let (p, _) = segment.sample_pt_deriv(t0 + tau * h);
            err = err.max((kurbo::ParamCurve::eval(&cubic, tau) - p).hypot());
        }
        if !err.is_finite() {
            return None;
        }
        // The error of Hermite interpolation shrinks like h⁴: split into the predicted number
        // of equal pieces (with a margin), each checked again, while the budget allows.
        let k = ((err / tolerance).powf(0.25) * 1.1).ceil().clamp(2.0, 64.0) as usize;
        if err <= tolerance
            || depth >= HERMITE_DEPTH
            || pieces.len() + stack.len() + k > HERMITE_MAX_PIECES
        {
            worst = worst.max(err);
            pieces.push(cubic);
        } else {
            let mut right = (p3, d3);
            // Right to left, so that the leftmost piece is taken next.
            for i in (0..k).rev() {
                let ta = t0 + h * i as f64 / k as f64;
                let tb = if i + 1 == k {
                    t1
                } else {
                    t0 + h * (i + 1) as f64 / k as f64
                };
                let left = if i == 0 {
                    (p0, d0)
                } else {
                    segment.sample_pt_deriv(ta)
                };
                stack.push((ta, tb, left, right, depth + 1));
                right = left;
            }
        }
    }
    Some(worst)
}

/// The start point of a path that begins with `MoveTo`.
fn pieces_start(path: &BezPath) -> Point {
    match path.elements().first() {
        Some(PathEl::MoveTo(p)) => *p,
        _ => Point::ZERO,
    }
}

/// The largest distance from `samples` evenly spaced points of `segment` to the nearest of
/// `pieces`, or `None` if a sample is not finite.
fn distance_to_pieces<C: ParamCurveFit>(
    segment: &C,
    pieces: &[CubicBez],
    samples: usize,
    tolerance: f64,
) -> Option<f64> {
    let samples = samples.clamp(2, 4096);
    let accuracy = tolerance * 1e-3;
    let mut worst: f64 = 0.0;
    for i in 0..=samples {
        let t = i as f64 / samples as f64;
        let (p, _) = segment.sample_pt_deriv(t);
        if !p.is_finite() {
            return None;
        }
        let d = pieces
            .iter()
            .map(|c| c.nearest(p, accuracy).distance_sq)
            .fold(f64::INFINITY, f64::min)
            .sqrt();
        worst = worst.max(d);
    }
    Some(worst)
}

/// Resolves a tolerance to an absolute distance, checking it and the segments' extent.
fn absolute_tolerance<C: ParamCurveFit>(
    segments: &[C],
    tolerance: FitTolerance,
) -> Result<f64, Error> {
    let (value, relative) = match tolerance {
        FitTolerance::Absolute(v) => (v, false),
        FitTolerance::Relative(v) => (v, true),
    };
    if !(value.is_finite() && value > 0.0) {
        return Err(Error::InvalidOption(
            "fit tolerance must be finite and positive",
        ));
    }
    let mut lo = Point::new(f64::INFINITY, f64::INFINITY);
    let mut hi = Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY);
    for (index, segment) in segments.iter().enumerate() {
        for t in [0.0, 0.5, 1.0] {
            let (p, d) = segment.sample_pt_deriv(t);
            if !(p.is_finite() && d.is_finite()) {
                return Err(Error::NonFiniteCurve { segment: index });
            }
            lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
            hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
        }
    }
    if !relative {
        return Ok(value);
    }
    // Halves first, so that an extent near the largest float does not overflow.
    let size = (0.5 * hi.x - 0.5 * lo.x).max(0.5 * hi.y - 0.5 * lo.y) * 2.0;
    if !size.is_finite() {
        return Err(Error::ExtentOverflow);
    }
    // A curve of zero extent (a point) still gets a positive tolerance.
    let scale = if size > 0.0 { size } else { 1.0 };
    Ok(value * scale)
}

/// A cusp of `range` found by sampling the speed `|d/dt|` of a curve: the parameter of the
/// smallest sampled speed, refined by golden-section search, if that speed is below
/// `1e-9` of the largest sampled speed. For [`ParamCurveFit::break_cusp`] implementations
/// of curves whose speed can vanish.
pub fn speed_cusp(deriv: impl Fn(f64) -> Vec2, range: Range<f64>) -> Option<f64> {
    const SAMPLES: usize = 16;
    let width = range.end - range.start;
    if width.is_nan() || width <= 0.0 {
        return None;
    }
    let at = |i: usize| range.start + width * i as f64 / SAMPLES as f64;
    let mut best = 0;
    let mut best_speed = f64::INFINITY;
    let mut top: f64 = 0.0;
    for i in 0..=SAMPLES {
        let s = deriv(at(i)).hypot();
        if !s.is_finite() {
            return None;
        }
        top = top.max(s);
        if s < best_speed {
            best = i;
            best_speed = s;
        }
    }
    // Golden-section search for the minimum of the speed around the best sample.
    let (mut a, mut b) = (at(best.saturating_sub(1)), at((best + 1).min(SAMPLES)));
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..60 {
        let c = b - ratio * (b - a);
        let d = a + ratio * (b - a);
        if deriv(c).hypot() < deriv(d).hypot() {
            b = d;
        } else {
            a = c;
        }
    }
    let t = 0.5 * (a + b);
    let speed = deriv(t).hypot();
    // A cusp at the very end of the range is not a break point inside it.
    let inside = t > range.start + 1e-9 * width && t < range.end - 1e-9 * width;
    (speed <= 1e-9 * top && inside).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::{CurveFitSample, ParamCurve, ParamCurveDeriv, QuadBez};

    /// A unit circle arc from angle `a0` to `a1`, exact.
    struct CircleArc {
        a0: f64,
        a1: f64,
    }

    impl ParamCurveFit for CircleArc {
        fn sample_pt_tangent(&self, t: f64, _sign: f64) -> CurveFitSample {
            let (p, tangent) = self.sample_pt_deriv(t);
            CurveFitSample { p, tangent }
        }
        fn sample_pt_deriv(&self, t: f64) -> (Point, Vec2) {
            let a = self.a0 + (self.a1 - self.a0) * t;
            let w = self.a1 - self.a0;
            (
                Point::new(a.cos(), a.sin()),
                Vec2::new(-a.sin() * w, a.cos() * w),
            )
        }
        fn break_cusp(&self, _: Range<f64>) -> Option<f64> {
            None
        }
    }

    #[test]
    fn circle_within_tolerance() {
        let quarter = core::f64::consts::FRAC_PI_2;
        let arcs: Vec<CircleArc> = (0..4)
            .map(|i| CircleArc {
                a0: i as f64 * quarter,
                a1: (i + 1) as f64 * quarter,
            })
            .collect();
        for method in [
            FitMethod::Kurbo,
            FitMethod::KurboOptimized,
            FitMethod::Hermite,
        ] {
            let options = FitOptions {
                method,
                check_samples: 200,
                ..FitOptions::relative(1e-6)
            };
            let fitted = fit(&arcs, true, &options).unwrap();
            assert!((fitted.tolerance - 2e-6).abs() < 1e-15);
            assert_eq!(fitted.cubics.len(), 4);
            assert!(fitted.max_distance <= fitted.tolerance, "{fitted:?}");
            // Independent check: every fitted cubic stays on the unit circle.
            for seg in fitted.path.segments() {
                for i in 0..=50 {
                    let r = seg.eval(i as f64 / 50.0).to_vec2().hypot();
                    assert!((r - 1.0).abs() <= fitted.tolerance, "radius {r}");
                }
            }
            // G1 joints: the tangent directions agree on both sides.
            let segs: Vec<CubicBez> = fitted.path.segments().map(|s| s.to_cubic()).collect();
            for k in 0..segs.len() {
                let a = segs[k].deriv().eval(1.0).to_vec2().normalize();
                let b = segs[(k + 1) % segs.len()]
                    .deriv()
                    .eval(0.0)
                    .to_vec2()
                    .normalize();
                assert!(a.cross(b).abs() < 1e-9, "joint {k}");
            }
        }
    }

    /// A quadratic with a cusp in the middle: p0 = p2, so the speed vanishes at t = 1/2.
    struct Cusp(QuadBez);

    impl ParamCurveFit for Cusp {
        fn sample_pt_tangent(&self, t: f64, sign: f64) -> CurveFitSample {
            let d = self.0.deriv().eval(t).to_vec2();
            let tangent = if d.hypot() > 1e-12 {
                d
            } else {
                sign * (self.0.p1 - self.0.p0)
            };
            CurveFitSample {
                p: self.0.eval(t),
                tangent,
            }
        }
        fn sample_pt_deriv(&self, t: f64) -> (Point, Vec2) {
            (self.0.eval(t), self.0.deriv().eval(t).to_vec2())
        }
        fn break_cusp(&self, range: Range<f64>) -> Option<f64> {
            speed_cusp(|t| self.0.deriv().eval(t).to_vec2(), range)
        }
    }

    #[test]
    fn cusp_is_split() {
        let q = QuadBez::new((0.0, 0.0), (1.0, 1.0), (0.0, 0.0));
        let t = speed_cusp(|t| q.deriv().eval(t).to_vec2(), 0.0..1.0).unwrap();
        assert!((t - 0.5).abs() < 1e-7, "{t}");
        assert_eq!(speed_cusp(|t| q.deriv().eval(t).to_vec2(), 0.0..0.4), None);
        let fitted = fit(&[Cusp(q)], false, &FitOptions::absolute(1e-6)).unwrap();
        assert!(fitted.cubics[0] >= 2);
        assert!(fitted.max_distance <= 1e-6, "{fitted:?}");
    }

    #[test]
    fn bad_input_is_typed() {
        let arcs = [CircleArc { a0: 0.0, a1: 1.0 }];
        for tol in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                fit(&arcs, false, &FitOptions::absolute(tol)),
                Err(Error::InvalidOption(_))
            ));
        }
        let none: [CircleArc; 0] = [];
        assert!(matches!(
            fit(&none, false, &FitOptions::default()),
            Err(Error::TooFewPoints { .. })
        ));
        let nan = [CircleArc {
            a0: 0.0,
            a1: f64::NAN,
        }];
        assert_eq!(
            fit(&nan, false, &FitOptions::default()).unwrap_err(),
            Error::NonFiniteCurve { segment: 0 }
        );
    }
}
