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
