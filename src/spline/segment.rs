//! The segments of a solved curve ([`Segment`]): κ quadratics, εκ cubics and εκ-trig
//! curves, with their points, derivatives, curvature and the kind of their curvature
//! extremum.

use kurbo::{CubicBez, ParamCurve, PathSeg, Point, QuadBez};

use super::Scheme;
use crate::basis::{classify, Basis, Extremum};
use crate::trig::TrigBez;
use crate::Point3;

/// Peak parameters within this of 0 or 1 sit at the segment end (as the analysis counts
/// them).
const END_PEAK: f64 = 1e-9;

/// A segment of a κ- or εκ-curve whose curvature peaks at its input point, at parameter
/// `t_max`: a quadratic Bézier (κ), a constrained cubic Bézier (εκ-cubic, seed 000 eq. 1)
/// or a constrained quadratic trigonometric curve (εκ-trig, seed 000 eq. 17).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment<P> {
    /// The three defining points `Q0, Q1, Q2` (seed 000 eqs. 1 and 17).
    pub q: [P; 3],
    /// The shape parameter `a` (`2/3` for κ-curves).
    pub a: f64,
    /// The parameter of the curvature peak (where the input point lies).
    pub t_max: f64,
    /// The degree: 2 (κ; εκ-trig, quadratic trigonometric) or 3 (εκ-cubic).
    pub degree: usize,
    /// The scheme the segment belongs to.
    pub scheme: Scheme,
}

impl<P> Segment<P> {
    /// The solver's basis of this segment.
    fn basis(&self) -> Basis {
        if self.degree == 2 && self.scheme != Scheme::EkTrig {
            Basis::QUADRATIC
        } else {
            self.scheme.basis(self.a)
        }
    }
}

impl<P: PartialEq> Segment<P> {
    /// Whether the segment has collapsed onto its input point: its three defining points
    /// are that point. The input point is then an inflection of the curve, where the
    /// neighbouring segments meet tangent to each other ([`Extremum::Inflection`]); the
    /// segment has no length and contributes nothing to paths, combs or curvature maxima.
    ///
    /// It happens where an interior point lies on the line through its neighbours and the
    /// curve is symmetric about it (a point-symmetric S or wave): as the point approaches
    /// the line, the segment through it shrinks linearly to the point (see the solver's
    /// notes in [`Solver`](super::Solver)).
    ///
    /// ```
    /// use kappa::{Extremum, Spline};
    /// use kurbo::Point;
    ///
    /// // A wave whose middle point lies on the line through its neighbours.
    /// let wave = [(100.0, 300.0), (250.0, 200.0), (400.0, 300.0), (550.0, 400.0), (700.0, 300.0)]
    ///     .map(Point::from);
    /// let curve = Spline::kappa(&wave, false)?;
    /// assert!(curve.converged());
    /// let middle = &curve.segments()[1];
    /// assert!(middle.is_collapsed());
    /// assert_eq!(middle.extremum(), Extremum::Inflection);
    /// # Ok::<(), kappa::Error>(())
    /// ```
    pub fn is_collapsed(&self) -> bool {
        self.q[0] == self.q[1] && self.q[1] == self.q[2]
    }
}

impl Segment<Point> {
    /// The control points: the Bézier control points (3 for κ, 4 for εκ-cubic), or for
    /// εκ-trig the five control points `P0..P4` of the quadratic trigonometric curve
    /// (seed 000 eq. 17; see [`TrigBez::constrained`]).
    pub fn control_points(&self) -> Vec<Point> {
        if self.scheme == Scheme::EkTrig {
            return self.to_trig().points().to_vec();
        }
        match self.to_path_seg() {
            PathSeg::Quad(q) => vec![q.p0, q.p1, q.p2],
            PathSeg::Cubic(c) => vec![c.p0, c.p1, c.p2, c.p3],
            PathSeg::Line(l) => vec![l.p0, l.p1],
        }
    }

    /// The kurbo segment: exact `QuadBez` for κ and `CubicBez` for εκ-cubic. An εκ-trig
    /// segment has no exact polynomial form; it gives the cubic with the same end points
    /// and end derivatives (a rough stand-in — use [`Spline::fit`](super::Spline::fit) or
    /// [`Spline::to_bezpath`](super::Spline::to_bezpath) for a path within a stated
    /// tolerance).
    pub fn to_path_seg(&self) -> PathSeg {
        let [q0, q1, q2] = self.q;
        match (self.scheme, self.degree) {
            (Scheme::EkTrig, _) => {
                let trig = self.to_trig();
                let (d0, d1) = (trig.derivative(0.0) / 3.0, trig.derivative(1.0) / 3.0);
                PathSeg::Cubic(CubicBez::new(q0, q0 + d0, q2 - d1, q2))
            }
            (_, 2) => PathSeg::Quad(QuadBez::new(q0, q1, q2)),
            _ => {
                let a = self.a;
                PathSeg::Cubic(CubicBez::new(q0, q0.lerp(q1, a), q2.lerp(q1, a), q2))
            }
        }
    }

    /// An εκ-trig segment as a [`TrigBez`] (for the other schemes, the same defining points
    /// read as a constrained trigonometric curve — only meaningful for εκ-trig).
    pub fn to_trig(&self) -> TrigBez {
        let [q0, q1, q2] = self.q;
        TrigBez::constrained(q0, q1, q2, self.a)
    }

    /// The point at parameter `t`.
    pub fn eval(&self, t: f64) -> Point {
        if self.scheme == Scheme::EkTrig {
            return self.to_trig().eval(t);
        }
        self.to_path_seg().eval(t)
    }

    /// The derivative `dP/dt` at `t` (its direction is the tangent's), exact for every
    /// scheme.
    pub fn derivative(&self, t: f64) -> kurbo::Vec2 {
        use kurbo::ParamCurveDeriv;
        if self.scheme == Scheme::EkTrig {
            return self.to_trig().derivative(t);
        }
        match self.to_path_seg() {
            PathSeg::Line(l) => l.deriv().eval(t).to_vec2(),
            PathSeg::Quad(q) => q.deriv().eval(t).to_vec2(),
            PathSeg::Cubic(c) => c.deriv().eval(t).to_vec2(),
        }
    }

    /// The signed curvature at `t` (positive for left turns), exact for every scheme.
    pub fn curvature(&self, t: f64) -> f64 {
        if self.scheme == Scheme::EkTrig {
            return self.to_trig().curvature(t);
        }
        crate::analysis::CurvatureAnalysis::curvature(&self.to_path_seg(), t)
    }

    /// The curvature vector at `t` (`κ` times the left unit normal: it points to the centre
    /// of curvature), exact for every scheme; zero where the tangent is undefined.
    pub fn curvature_vector(&self, t: f64) -> kurbo::Vec2 {
        if self.scheme == Scheme::EkTrig {
            let trig = self.to_trig();
            let d = trig.derivative(t);
            let len = d.hypot();
            if len == 0.0 || !len.is_finite() {
                return kurbo::Vec2::ZERO;
            }
            return trig.curvature(t) * kurbo::Vec2::new(-d.y, d.x) / len;
        }
        crate::analysis::CurvatureAnalysis::curvature_vector(&self.to_path_seg(), t)
    }

    /// Whether `|κ|` is maximal or minimal at `t_max` (see [`Extremum`]). κ and εκ-cubic
    /// segments always peak there (or have collapsed onto an inflection); εκ-trig segments
    /// with `a` below about 0.61 may have a minimum there, and one whose peak was pushed to
    /// a segment end may be higher inside ([`Extremum::EndOnly`], found by sampling |κ| at
    /// 64 parameters).
    pub fn extremum(&self) -> Extremum {
        if self.is_collapsed() {
            return Extremum::Inflection;
        }
        if self.scheme != Scheme::EkTrig {
            // The quadratic and the constrained cubic have one stationary point of |κ|, a
            // maximum (seed 000 §3); classifying it numerically fails on nearly straight
            // segments, where r ≈ s cancels.
            return Extremum::Max;
        }
        let [q0, q1, q2] = self.q;
        let (r, s) = (q1 - q0, q2 - q1);
        let kind = classify(&self.basis(), r.dot(r), r.dot(s), s.dot(s), self.t_max);
        let at_end = self.t_max <= END_PEAK || self.t_max >= 1.0 - END_PEAK;
        if kind == Extremum::Max && at_end {
            // A local maximum at the end; is it the segment's? (|κ| sampled at 64 inner
            // parameters, against its value at the end with the rounding of its control
            // points allowed for.)
            let trig = self.to_trig();
            let k = trig.curvature(self.t_max).abs();
            let inside = (1..64)
                .map(|i| trig.curvature(i as f64 / 64.0).abs())
                .fold(0.0, f64::max);
            if inside > k * (1.0 + 1e-9) {
                return Extremum::EndOnly;
            }
        }
        kind
    }
}

impl Segment<Point3> {
    /// The Bézier control points (3 for degree 2, 4 for degree 3).
    pub fn control_points(&self) -> Vec<Point3> {
        let [q0, q1, q2] = self.q;
        if self.degree == 2 {
            vec![q0, q1, q2]
        } else {
            vec![q0, q0.lerp(q1, self.a), q2.lerp(q1, self.a), q2]
        }
    }

    /// The point at parameter `t` (de Casteljau).
    pub fn eval(&self, t: f64) -> Point3 {
        let mut pts = self.control_points();
        let n = pts.len();
        for level in 1..n {
            for i in 0..n - level {
                pts[i] = pts[i].lerp(pts[i + 1], t);
            }
        }
        pts[0]
    }
}
