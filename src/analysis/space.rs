//! Bézier segments in 3D.

use core::ops::Range;

use super::bez::{blossom, subsegment_points, MAX_POINTS};
use crate::{Point3, Vec3};

/// A Bézier segment in 3D of degree 0–4 (1–5 control points),
/// `r(t) = Σ_{i=0}^{n} C(n,i) tⁱ (1−t)^{n−i} p_i`.
///
/// The method names mirror kurbo's `ParamCurve`. Its curvature (through
/// [`CurvatureAnalysis`](super::CurvatureAnalysis)) is the unsigned space-curve curvature
/// `|r′ × r″|/|r′|³`, also for a segment that lies in a plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpaceBez {
    /// Control points; the unused ones are kept at the origin so that `PartialEq` is exact.
    pts: [Point3; MAX_POINTS],
    len: usize,
}

impl SpaceBez {
    /// A segment with the given control points (1 to 5 of them, degree = count − 1), or `None`
    /// for an empty slice or more than 5 points.
    pub fn new(ctrl: &[Point3]) -> Option<SpaceBez> {
        if ctrl.is_empty() || ctrl.len() > MAX_POINTS {
            return None;
        }
        let mut pts = [Point3::ORIGIN; MAX_POINTS];
        pts[..ctrl.len()].copy_from_slice(ctrl);
        Some(SpaceBez {
            pts,
            len: ctrl.len(),
        })
    }

    /// A straight segment.
    pub fn line(p0: Point3, p1: Point3) -> SpaceBez {
        Self::from_array([p0, p1])
    }

    /// A quadratic segment.
    pub fn quad(p0: Point3, p1: Point3, p2: Point3) -> SpaceBez {
        Self::from_array([p0, p1, p2])
    }

    /// A cubic segment.
    pub fn cubic(p0: Point3, p1: Point3, p2: Point3, p3: Point3) -> SpaceBez {
        Self::from_array([p0, p1, p2, p3])
    }

    /// A quartic segment.
    pub fn quartic(p0: Point3, p1: Point3, p2: Point3, p3: Point3, p4: Point3) -> SpaceBez {
        Self::from_array([p0, p1, p2, p3, p4])
    }

    fn from_array<const N: usize>(ctrl: [Point3; N]) -> SpaceBez {
        const { assert!(N >= 1 && N <= MAX_POINTS) };
        let mut pts = [Point3::ORIGIN; MAX_POINTS];
        pts[..N].copy_from_slice(&ctrl);
        SpaceBez { pts, len: N }
    }

    /// The degree (number of control points − 1).
    #[inline]
    pub fn degree(&self) -> usize {
        self.len - 1
    }

    /// The control points.
    #[inline]
    pub fn control_points(&self) -> &[Point3] {
        &self.pts[..self.len]
    }

    fn vecs(&self) -> [Vec3; MAX_POINTS] {
        self.pts.map(Point3::to_vec3)
    }

    /// The point at `t` (de Casteljau).
    pub fn eval(&self, t: f64) -> Point3 {
        let v = self.vecs();
        let us = [t; MAX_POINTS - 1];
        blossom(&v[..self.len], &us[..self.len - 1]).to_point3()
    }

    /// The start point.
    #[inline]
    pub fn start(&self) -> Point3 {
        self.pts[0]
    }

    /// The end point.
    #[inline]
    pub fn end(&self) -> Point3 {
        self.pts[self.len - 1]
    }

    /// The derivative (hodograph), a segment of one degree less whose "points" are the
    /// derivative vectors `n (p_{i+1} − p_i)`: `self.deriv().eval(t).to_vec3()` is `r′(t)`.
    /// The derivative of a degree-0 segment is the single point at the origin.
    pub fn deriv(&self) -> SpaceBez {
        let n = self.degree();
        if n == 0 {
            return Self::from_array([Point3::ORIGIN]);
        }
        let mut pts = [Point3::ORIGIN; MAX_POINTS];
        for (i, d) in pts.iter_mut().enumerate().take(n) {
            *d = ((self.pts[i + 1] - self.pts[i]) * n as f64).to_point3();
        }
        SpaceBez { pts, len: n }
    }

    /// The piece `range` of the segment, reparameterized to `[0, 1]` (by blossoming).
    pub fn subsegment(&self, range: Range<f64>) -> SpaceBez {
        let v = self.vecs();
        let q = subsegment_points(&v[..self.len], range.start, range.end);
        let mut pts = [Point3::ORIGIN; MAX_POINTS];
        for (p, q) in pts.iter_mut().zip(&q[..self.len]) {
            *p = q.to_point3();
        }
        SpaceBez { pts, len: self.len }
    }

    /// The two halves `[0, ½]` and `[½, 1]`.
    pub fn subdivide(&self) -> (SpaceBez, SpaceBez) {
        (self.subsegment(0.0..0.5), self.subsegment(0.5..1.0))
    }

    /// The arc length `∫₀¹ |r′(t)| dt`, to within about `accuracy` (absolute).
    ///
    /// 16-point Gauss–Legendre quadrature, compared with the same rule on the two halves; the
    /// halves are refined (each with half the accuracy) until the two estimates agree, at most
    /// 12 levels deep. Exact up to rounding for lines and for segments with a polynomial speed
    /// of degree ≤ 31.
    pub fn arclen(&self, accuracy: f64) -> f64 {
        let d = self.deriv();
        let speed = |t: f64| d.eval(t).to_vec3().length();
        arclen_rec(&speed, 0.0, 1.0, accuracy, 0)
    }

    /// The projection onto the xy plane, as 2D control points.
    pub fn to_xy_points(&self) -> Vec<kurbo::Point> {
        self.control_points().iter().map(|p| p.to_xy()).collect()
    }

    /// Are all control points finite?
    pub fn is_finite(&self) -> bool {
        self.control_points().iter().all(|p| p.is_finite())
    }

    /// Is any control point NaN?
    pub fn is_nan(&self) -> bool {
        self.control_points().iter().any(|p| p.is_nan())
    }
}

/// How often [`SpaceBez::arclen`] may halve an interval.
const ARCLEN_MAX_DEPTH: usize = 12;

/// 16-point Gauss–Legendre estimate of `∫_a^b f`.
fn gauss_legendre(f: &impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    half * kurbo::common::GAUSS_LEGENDRE_COEFFS_16
        .iter()
        .map(|&(w, x)| w * f(mid + half * x))
        .sum::<f64>()
}

fn arclen_rec(f: &impl Fn(f64) -> f64, a: f64, b: f64, accuracy: f64, depth: usize) -> f64 {
    let m = 0.5 * (a + b);
    let whole = gauss_legendre(f, a, b);
    let halves = gauss_legendre(f, a, m) + gauss_legendre(f, m, b);
    let err = (whole - halves).abs();
    // Stops on NaN too.
    if err <= accuracy || err.is_nan() || depth >= ARCLEN_MAX_DEPTH {
        return halves;
    }
    arclen_rec(f, a, m, 0.5 * accuracy, depth + 1) + arclen_rec(f, m, b, 0.5 * accuracy, depth + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> SpaceBez {
        SpaceBez::new(&[
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 2.0, 0.5),
            Point3::new(2.0, -1.0, 1.5),
            Point3::new(3.0, 1.0, -1.0),
            Point3::new(4.0, 0.0, 0.0),
        ])
        .unwrap()
    }

    #[test]
    fn spacebez_new_checks_count() {
        assert!(SpaceBez::new(&[]).is_none());
        assert!(SpaceBez::new(&[Point3::ORIGIN; 6]).is_none());
        assert_eq!(SpaceBez::new(&[Point3::ORIGIN; 3]).unwrap().degree(), 2);
        assert_eq!(sample().degree(), 4);
        assert_eq!(sample().control_points().len(), 5);
    }

    #[test]
    fn spacebez_eval_endpoints_and_subsegment() {
        let s = sample();
        assert_eq!(s.eval(0.0), s.start());
        assert_eq!(s.eval(1.0), s.end());
        let piece = s.subsegment(0.25..0.75);
        for i in 0..=8 {
            let u = i as f64 / 8.0;
            assert!(piece.eval(u).distance(s.eval(0.25 + 0.5 * u)) < 1e-13);
        }
        let (a, b) = s.subdivide();
        assert!(a.end().distance(b.start()) < 1e-15);
    }

    #[test]
    fn spacebez_arclen_of_line_cubic_and_cusp() {
        let line = SpaceBez::line(Point3::new(1.0, 2.0, 3.0), Point3::new(4.0, 6.0, 15.0));
        assert!((line.arclen(1e-12) - 13.0).abs() < 1e-13);
        // A planar cubic agrees with kurbo's arclen.
        let c = kurbo::CubicBez::new((0.0, 0.0), (1.0, 2.0), (3.0, -1.0), (4.0, 1.0));
        let s = SpaceBez::cubic(
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 2.0, 0.0),
            Point3::new(3.0, -1.0, 0.0),
            Point3::new(4.0, 1.0, 0.0),
        );
        let want = kurbo::ParamCurveArclen::arclen(&c, 1e-13);
        assert!(
            (s.arclen(1e-12) - want).abs() < 1e-11,
            "{} vs {want}",
            s.arclen(1e-12)
        );
        // Rotating it out of the plane does not change the length.
        let rot = |p: Point3| Point3::new(p.x, 0.6 * p.y, 0.8 * p.y);
        let pts: Vec<Point3> = s.control_points().iter().map(|&p| rot(p)).collect();
        let r = SpaceBez::new(&pts).unwrap();
        assert!((r.arclen(1e-12) - want).abs() < 1e-11);
        // A cusp (|r′| has a kink) still converges to the sum of the two legs.
        let cusp = SpaceBez::quad(
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(2.0, 0.0, 0.0),
            Point3::new(0.0, 0.0, 0.0),
        );
        assert!((cusp.arclen(1e-10) - 2.0).abs() < 1e-9);
    }

    #[test]
    fn spacebez_deriv_matches_finite_difference() {
        let s = sample();
        let d = s.deriv();
        assert_eq!(d.degree(), 3);
        let h = 1e-6;
        for t in [0.2, 0.6] {
            let fd = (s.eval(t + h) - s.eval(t - h)) * (0.5 / h);
            assert!((d.eval(t).to_vec3() - fd).length() < 1e-6);
        }
        let p = SpaceBez::new(&[Point3::new(1.0, 2.0, 3.0)]).unwrap();
        assert_eq!(p.deriv().eval(0.5), Point3::ORIGIN);
    }
}
