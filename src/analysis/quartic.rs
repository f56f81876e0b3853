//! Quartic Bézier segments in 2D.

use core::ops::{Mul, Range};

use kurbo::{Affine, CubicBez, ParamCurve, ParamCurveDeriv, Point, Vec2};

use super::bez::{blossom, subsegment_points};

/// A quartic Bézier segment in 2D,
/// `r(t) = Σ_{i=0}^{4} C(4,i) tⁱ (1−t)^{4−i} p_i`.
///
/// kurbo has no quartic type; the 3D κ-space curves (seed 004) produce quartics, and their
/// projections land here. It implements [`ParamCurve`] and [`ParamCurveDeriv`] (the derivative
/// is a [`CubicBez`] whose "points" are the hodograph vectors `4(p_{i+1} − p_i)`), and
/// [`CurvatureAnalysis`](super::CurvatureAnalysis). It deliberately does not implement kurbo's
/// `ParamCurveCurvature`, whose sign is the opposite of this crate's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuarticBez {
    /// The start point.
    pub p0: Point,
    /// The first interior control point.
    pub p1: Point,
    /// The second interior control point.
    pub p2: Point,
    /// The third interior control point.
    pub p3: Point,
    /// The end point.
    pub p4: Point,
}

impl QuarticBez {
    /// Create a new quartic Bézier segment.
    #[inline]
    pub fn new<P: Into<Point>>(p0: P, p1: P, p2: P, p3: P, p4: P) -> QuarticBez {
        QuarticBez {
            p0: p0.into(),
            p1: p1.into(),
            p2: p2.into(),
            p3: p3.into(),
            p4: p4.into(),
        }
    }

    /// The same curve as a quartic (exact degree elevation):
    /// `q_i = (i/4) c_{i−1} + (1 − i/4) c_i`.
    pub fn from_cubic(c: CubicBez) -> QuarticBez {
        let e = |a: Point, b: Point, i: f64| {
            (a.to_vec2() * (i / 4.0) + b.to_vec2() * (1.0 - i / 4.0)).to_point()
        };
        QuarticBez {
            p0: c.p0,
            p1: e(c.p0, c.p1, 1.0),
            p2: e(c.p1, c.p2, 2.0),
            p3: e(c.p2, c.p3, 3.0),
            p4: c.p3,
        }
    }

    /// The control points as an array.
    #[inline]
    pub fn points(&self) -> [Point; 5] {
        [self.p0, self.p1, self.p2, self.p3, self.p4]
    }

    fn vecs(&self) -> [Vec2; 5] {
        self.points().map(Point::to_vec2)
    }

    /// Is this curve finite?
    #[inline]
    pub fn is_finite(&self) -> bool {
        self.points().iter().all(|p| p.is_finite())
    }

    /// Is this curve NaN?
    #[inline]
    pub fn is_nan(&self) -> bool {
        self.points().iter().any(|p| p.is_nan())
    }
}

impl ParamCurve for QuarticBez {
    /// de Casteljau evaluation.
    fn eval(&self, t: f64) -> Point {
        blossom(&self.vecs(), &[t; 4]).to_point()
    }

    /// The piece `range` of the curve, by blossoming (exact up to rounding).
    fn subsegment(&self, range: Range<f64>) -> QuarticBez {
        let q = subsegment_points(&self.vecs(), range.start, range.end).map(Vec2::to_point);
        QuarticBez::new(q[0], q[1], q[2], q[3], q[4])
    }

    #[inline]
    fn start(&self) -> Point {
        self.p0
    }

    #[inline]
    fn end(&self) -> Point {
        self.p4
    }
}

impl ParamCurveDeriv for QuarticBez {
    type DerivResult = CubicBez;

    /// The hodograph `4(p_{i+1} − p_i)`, as a cubic whose points are the derivative vectors.
    fn deriv(&self) -> CubicBez {
        let d = |a: Point, b: Point| (4.0 * (b - a)).to_point();
        CubicBez::new(
            d(self.p0, self.p1),
            d(self.p1, self.p2),
            d(self.p2, self.p3),
            d(self.p3, self.p4),
        )
    }
}

impl Mul<QuarticBez> for Affine {
    type Output = QuarticBez;

    #[inline]
    fn mul(self, q: QuarticBez) -> QuarticBez {
        QuarticBez::new(
            self * q.p0,
            self * q.p1,
            self * q.p2,
            self * q.p3,
            self * q.p4,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> QuarticBez {
        QuarticBez::new((0.0, 0.0), (1.0, 3.0), (2.5, -1.0), (4.0, 2.0), (5.0, 0.5))
    }

    /// Bernstein form, independent of de Casteljau.
    fn bernstein(q: &QuarticBez, t: f64) -> Point {
        let mt = 1.0 - t;
        let w = [
            mt.powi(4),
            4.0 * t * mt.powi(3),
            6.0 * t * t * mt * mt,
            4.0 * t.powi(3) * mt,
            t.powi(4),
        ];
        let v = q
            .points()
            .iter()
            .zip(w)
            .fold(Vec2::ZERO, |acc, (p, w)| acc + p.to_vec2() * w);
        v.to_point()
    }

    #[test]
    fn quarticbez_eval_matches_bernstein() {
        let q = sample();
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            assert!((q.eval(t) - bernstein(&q, t)).hypot() < 1e-13);
        }
        assert_eq!(q.eval(0.0), q.p0);
        assert_eq!(q.eval(1.0), q.p4);
    }

    #[test]
    fn quarticbez_subsegment_traces_same_curve() {
        let q = sample();
        let s = q.subsegment(0.2..0.7);
        for i in 0..=10 {
            let u = i as f64 / 10.0;
            let t = 0.2 + 0.5 * u;
            assert!((s.eval(u) - q.eval(t)).hypot() < 1e-13);
        }
        let (a, b) = q.subdivide();
        assert!((a.end() - b.start()).hypot() < 1e-15);
        assert!((a.eval(0.5) - q.eval(0.25)).hypot() < 1e-13);
    }

    #[test]
    fn quarticbez_deriv_matches_finite_difference() {
        let q = sample();
        let d = q.deriv();
        let h = 1e-6;
        for t in [0.1, 0.5, 0.93] {
            let fd = (q.eval(t + h) - q.eval(t - h)) / (2.0 * h);
            assert!((d.eval(t).to_vec2() - fd).hypot() < 1e-6);
        }
    }

    #[test]
    fn quarticbez_from_cubic_is_same_curve() {
        let c = CubicBez::new((0.0, 0.0), (1.0, 2.0), (3.0, -1.0), (4.0, 1.0));
        let q = QuarticBez::from_cubic(c);
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            assert!((q.eval(t) - c.eval(t)).hypot() < 1e-13);
        }
    }

    #[test]
    fn quarticbez_affine() {
        let q = sample();
        let a = Affine::rotate(0.7).then_translate(Vec2::new(3.0, -2.0));
        let r = a * q;
        assert!((r.eval(0.3) - a * q.eval(0.3)).hypot() < 1e-13);
    }
}
