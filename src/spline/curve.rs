//! A solved curve ([`Spline`], [`Spline3`]): its segments, curvature samples and combs, and
//! its kurbo path and SVG data.

use kurbo::{BezPath, ParamCurve, PathSeg, Point};

use super::frame::{Coords, Frame};
use super::{Scheme, Segment, Shape, SolveReport, Solver};
use crate::fit::{FitOptions, Fitted};
use crate::trig::TrigBez;
use crate::{Error, Point3};

/// A solved κ- or εκ-curve through 2D points.
///
/// Segment `i` of a closed curve passes through point `i` at its parameter `t_max`, where its
/// |κ| is stationary (an open curve has a segment per interior point), and consecutive
/// segments meet with equal curvature (G2).
///
/// ```
/// use kappa::Spline;
/// use kurbo::Point;
///
/// let points = [(0.0, 0.0), (100.0, 10.0), (120.0, 90.0), (20.0, 110.0)].map(Point::from);
/// let curve = Spline::kappa(&points, true)?;
/// let segments = curve.segments();
/// assert_eq!(segments.len(), points.len());
/// for (i, seg) in segments.iter().enumerate() {
///     assert!((seg.eval(seg.t_max) - points[i]).hypot() < 1e-9);
///     let next = &segments[(i + 1) % segments.len()];
///     let (k0, k1) = (seg.curvature(1.0), next.curvature(0.0));
///     assert!((k0 - k1).abs() <= 1e-9 * k0.abs().max(k1.abs()));
/// }
/// // An open εκ-curve: cubic segments, one per interior point.
/// let open = Spline::ek_cubic(&points, false, 0.9)?;
/// assert_eq!(open.segments().len(), 2);
/// assert!(open.segments().iter().all(|s| s.degree == 3));
/// # Ok::<(), kappa::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Spline<P = Point> {
    pub(super) scheme: Scheme,
    pub(super) closed: bool,
    pub(super) segments: Vec<Segment<P>>,
    pub(super) report: SolveReport,
}

/// A solved κ- or εκ-curve through 3D points (the base of κ-space curves); solve with
/// [`Solver3`](super::Solver3).
pub type Spline3 = Spline<Point3>;

impl<P: Copy> Spline<P> {
    /// The scheme.
    pub fn scheme(&self) -> Scheme {
        self.scheme
    }

    /// Whether the curve is closed.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// The segments in order along the curve: one per input point (closed) or per interior
    /// input point (open; a two-point open curve is one straight segment).
    pub fn segments(&self) -> &[Segment<P>] {
        &self.segments
    }

    /// What the solver did.
    pub fn report(&self) -> SolveReport {
        self.report
    }

    /// Iterations used.
    pub fn iterations(&self) -> usize {
        self.report.iterations
    }

    /// Whether the solver reached its tolerance.
    pub fn converged(&self) -> bool {
        self.report.converged
    }
}

impl Spline<Point> {
    /// A κ-curve through `points` with default options.
    pub fn kappa(points: &[Point], closed: bool) -> Result<Spline, Error> {
        Solver::new().solve(points, closed, Scheme::Kappa, &Shape::Neutral)
    }

    /// A cubic εκ-curve through `points` with default options.
    pub fn ek_cubic(
        points: &[Point],
        closed: bool,
        shape: impl Into<Shape>,
    ) -> Result<Spline, Error> {
        Solver::new().solve(points, closed, Scheme::EkCubic, &shape.into())
    }

    /// An εκ-curve in the trigonometric basis through `points` with default options.
    pub fn ek_trig(
        points: &[Point],
        closed: bool,
        shape: impl Into<Shape>,
    ) -> Result<Spline, Error> {
        Solver::new().solve(points, closed, Scheme::EkTrig, &shape.into())
    }

    /// A curvature comb of the exact curve (every scheme, trigonometric segments included):
    /// `samples_per_segment` teeth per segment, uniform in `t` with both ends, each from the
    /// curve point `p` to `p − scale · κ · n` (see [`crate::analysis::curvature_comb`]).
    pub fn curvature_comb(&self, scale: f64, samples_per_segment: usize) -> BezPath {
        crate::analysis::comb_from_samples(self.curvature_samples(samples_per_segment), scale)
    }

    /// Samples `(p, k)` of the exact curve, `samples_per_segment` (at least 2) per segment
    /// evenly in each segment's parameter, ends included: the point and the curvature vector
    /// `κ n` (`n` the left unit normal; zero where the curve stalls).
    pub fn curvature_samples(&self, samples_per_segment: usize) -> Vec<(Point, kurbo::Vec2)> {
        let m = samples_per_segment.max(2);
        let mut samples = Vec::with_capacity(m * self.segments.len());
        for seg in &self.segments {
            // One curve object per segment; points and derivatives straight from it.
            let trig = (seg.scheme == Scheme::EkTrig).then(|| seg.to_trig());
            let poly = seg.to_path_seg();
            for i in 0..m {
                let t = i as f64 / (m - 1) as f64;
                let (p, d1, d2) = match &trig {
                    Some(c) => c.eval_derivs(t),
                    None => path_seg_derivs(&poly, t),
                };
                let len2 = d1.hypot2();
                let k = if len2 > 0.0 && len2.is_finite() {
                    // κ n with n the left unit normal: (d1 × d2)/|d1|⁴ · (-d1.y, d1.x).
                    d1.cross(d2) / (len2 * len2) * kurbo::Vec2::new(-d1.y, d1.x)
                } else {
                    kurbo::Vec2::ZERO
                };
                samples.push((p, k));
            }
        }
        samples
    }

    /// The largest |κ| of the curve: at the peak parameters, the segment ends, and 64
    /// samples per segment (exact for the peaks the scheme places at the input points).
    pub fn max_abs_curvature(&self) -> f64 {
        self.segments
            .iter()
            .flat_map(|seg| {
                (0..=64)
                    .map(|i| i as f64 / 64.0)
                    .chain([seg.t_max])
                    .map(move |t| seg.curvature(t).abs())
            })
            .filter(|k| k.is_finite())
            .fold(0.0, f64::max)
    }

    /// The curve as a kurbo path within `options`' tolerance, with the number of cubics per
    /// segment and the measured distance to the exact curve (see [`crate::fit`]). εκ-trig
    /// segments are fitted; the polynomial schemes give their exact path
    /// ([`Spline::to_bezpath`], one segment each, distance 0).
    pub fn fit(&self, options: &FitOptions) -> Result<Fitted, Error> {
        if self.scheme != Scheme::EkTrig {
            let path = self.to_bezpath();
            let tolerance = match options.tolerance {
                crate::fit::FitTolerance::Absolute(v) => v,
                crate::fit::FitTolerance::Relative(v) => {
                    let bbox = kurbo::Shape::bounding_box(&path);
                    v * bbox.width().max(bbox.height())
                }
            };
            return Ok(Fitted {
                path,
                cubics: self
                    .segments
                    .iter()
                    .map(|s| usize::from(!s.is_collapsed()))
                    .collect(),
                tolerance,
                max_distance: 0.0,
            });
        }
        // Fitted in a frame where the curve is about one unit wide around the origin, and
        // mapped back: the fitters' own thresholds are absolute, and at coordinates of 1e6
        // and more (or far from the origin) they measured errors of a tenth of the curve, or
        // tens of thousands of cubics.
        let points: Vec<[f64; 2]> = self
            .segments
            .iter()
            .flat_map(|s| s.q.map(Coords::coords))
            .collect();
        let Frame { center, size } = Frame::new(&points);
        let to_local = kurbo::Affine::translate((-center[0], -center[1])).then_scale(1.0 / size);
        let trig: Vec<TrigBez> = self
            .segments
            .iter()
            .map(|s| {
                let [q0, q1, q2] = s.q.map(|q| to_local * q);
                TrigBez::constrained(q0, q1, q2, s.a)
            })
            .collect();
        let local = FitOptions {
            tolerance: match options.tolerance {
                crate::fit::FitTolerance::Absolute(v) => {
                    crate::fit::FitTolerance::Absolute(v / size)
                }
                relative => relative,
            },
            ..*options
        };
        let mut fitted = crate::fit::fit(&trig, self.closed, &local)?;
        // (Not `to_local.inverse()`: its determinant underflows for sizes beyond 1e154.)
        fitted
            .path
            .apply_affine(kurbo::Affine::scale(size).then_translate((center[0], center[1]).into()));
        fitted.tolerance *= size;
        fitted.max_distance *= size;
        Ok(fitted)
    }

    /// The curve as a kurbo path: exact `QuadBez` (κ) or `CubicBez` (εκ-cubic) segments;
    /// for εκ-trig, cubics fitted within `1e-4` of the drawing size
    /// ([`FitOptions::default`]; use [`Spline::fit`] to choose).
    pub fn to_bezpath(&self) -> BezPath {
        if self.scheme == Scheme::EkTrig {
            // Fitting a solved curve cannot fail (its points are finite); an empty path
            // would only stand for that impossible case.
            return self
                .fit(&FitOptions::default())
                .map(|f| f.path)
                .unwrap_or_default();
        }
        let mut path = BezPath::new();
        for (i, seg) in self.segments.iter().enumerate() {
            let ps = seg.to_path_seg();
            if i == 0 {
                path.move_to(ps.start());
            }
            if seg.is_collapsed() {
                // An inflection at its input point: no length, nothing to draw.
                continue;
            }
            match ps {
                PathSeg::Line(l) => path.line_to(l.p1),
                PathSeg::Quad(q) => path.quad_to(q.p1, q.p2),
                PathSeg::Cubic(c) => path.curve_to(c.p1, c.p2, c.p3),
            }
        }
        if self.closed && !self.segments.is_empty() {
            path.close_path();
        }
        path
    }

    /// SVG path data of [`Spline::to_bezpath`]: the shortest decimal that reads back to the
    /// same `f64`, in exponent form where that is shorter (`1e300`, not 301 digits).
    pub fn to_svg(&self) -> String {
        svg_path_data(&self.to_bezpath())
    }
}

/// Point, first and second derivative of a kurbo segment at `t`.
pub(crate) fn path_seg_derivs(seg: &PathSeg, t: f64) -> (Point, kurbo::Vec2, kurbo::Vec2) {
    use kurbo::ParamCurveDeriv;
    match seg {
        PathSeg::Line(l) => (l.eval(t), l.p1 - l.p0, kurbo::Vec2::ZERO),
        PathSeg::Quad(q) => (
            q.eval(t),
            q.deriv().eval(t).to_vec2(),
            q.deriv().deriv().eval(t).to_vec2(),
        ),
        PathSeg::Cubic(c) => (
            c.eval(t),
            c.deriv().eval(t).to_vec2(),
            c.deriv().deriv().eval(t).to_vec2(),
        ),
    }
}

/// SVG path data of any kurbo path: absolute commands, and for every number the shortest
/// decimal that reads back to the same `f64`, in exponent form where that is shorter
/// (`1e300`, not 301 digits; `6.9e-18`, not 22 digits).
pub fn svg_path_data(path: &BezPath) -> String {
    use kurbo::PathEl;
    use std::fmt::Write as _;
    let mut out = String::new();
    let mut put = |cmd: char, pts: &[Point]| {
        if !out.is_empty() {
            out.push(' ');
        }
        out.push(cmd);
        for (i, p) in pts.iter().enumerate() {
            if i > 0 {
                out.push(' ');
            }
            let _ = write!(out, "{},{}", svg_number(p.x), svg_number(p.y));
        }
    };
    for el in path.elements() {
        match *el {
            PathEl::MoveTo(p) => put('M', &[p]),
            PathEl::LineTo(p) => put('L', &[p]),
            PathEl::QuadTo(p1, p2) => put('Q', &[p1, p2]),
            PathEl::CurveTo(p1, p2, p3) => put('C', &[p1, p2, p3]),
            PathEl::ClosePath => put('Z', &[]),
        }
    }
    out
}

/// A number for SVG: Rust's shortest round-trip decimal, or its exponent form when shorter.
fn svg_number(x: f64) -> String {
    let plain = format!("{x}");
    let exp = format!("{x:e}");
    if exp.len() < plain.len() {
        exp
    } else {
        plain
    }
}
