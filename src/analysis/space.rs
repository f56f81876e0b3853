//! Bézier segments in 3D.

use core::ops::Range;

use kurbo::common::{GAUSS_LEGENDRE_COEFFS_16, GAUSS_LEGENDRE_COEFFS_8};

use super::bez::{blossom, subsegment_points, Sealed, MAX_POINTS};
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

    /// The torsion `τ = ((r′ × r″) · r‴) / |r′ × r″|²` at `t`: the rate at which the
    /// osculating plane turns about the tangent, positive for a right-handed helix. It is 0
    /// for segments of degree ≤ 2 (they are planar) and, by convention, where the curvature
    /// vanishes (`|r′ × r″| ≤ 1e-12 · |r′| |r″|`: no osculating plane).
    pub fn torsion(&self, t: f64) -> f64 {
        if self.degree() < 3 {
            return 0.0;
        }
        let d = self.to_bez().derivs(t);
        let c = d.d1.cross(d.d2);
        let c2 = c.hypot2();
        let flat = TORSION_FLAT * d.d1.length() * d.d2.length();
        if c2.is_nan() || c2 <= flat * flat {
            return 0.0;
        }
        let tau = c.dot(d.d3) / c2;
        if tau.is_finite() {
            tau
        } else {
            0.0
        }
    }

    /// The arc length, to within `accuracy` (absolute): Gauss–Legendre quadrature of `|r′|`
    /// with 16 nodes, bisecting where 8 nodes disagree with 16 by more than the share of the
    /// accuracy of that piece (at most 20 levels deep). A non-positive or
    /// NaN accuracy is taken as `1e-9` of the control polygon's length.
    pub fn arclen(&self, accuracy: f64) -> f64 {
        let h = self.deriv();
        let polygon: f64 = self
            .control_points()
            .windows(2)
            .map(|w| w[0].distance(w[1]))
            .sum();
        if !polygon.is_finite() {
            // NaN or infinite control points: no length to speak of.
            return polygon;
        }
        if polygon <= 0.0 {
            return 0.0;
        }
        let accuracy = if accuracy > 0.0 {
            accuracy
        } else {
            1e-9 * polygon
        };
        arclen_rec(&h, 0.0, 1.0, accuracy, 0)
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

/// Below this value of `|r′ × r″| / (|r′| |r″|)` (the sine of the angle between the first two
/// derivatives) a segment counts as straight at that parameter and its torsion as 0.
const TORSION_FLAT: f64 = 1e-12;

/// The deepest bisection of [`SpaceBez::arclen`] (2⁻²⁰ of the parameter range).
const ARCLEN_MAX_DEPTH: usize = 20;

/// `∫_a^b |h(t)| dt` for the hodograph `h`, adaptively.
fn arclen_rec(h: &SpaceBez, a: f64, b: f64, accuracy: f64, depth: usize) -> f64 {
    let quad = |coeffs: &[(f64, f64)]| -> f64 {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        half * coeffs
            .iter()
            .map(|&(w, x)| w * h.eval(mid + half * x).to_vec3().length())
            .sum::<f64>()
    };
    let fine = quad(GAUSS_LEGENDRE_COEFFS_16);
    let coarse = quad(GAUSS_LEGENDRE_COEFFS_8);
    if (fine - coarse).abs() <= accuracy || depth >= ARCLEN_MAX_DEPTH {
        return fine;
    }
    let m = 0.5 * (a + b);
    arclen_rec(h, a, m, 0.5 * accuracy, depth + 1) + arclen_rec(h, m, b, 0.5 * accuracy, depth + 1)
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
    fn spacebez_torsion_of_helix_like_cubic() {
        // Exact check: torsion from the formula with derivatives by finite differences.
        let s = sample();
        let h = 1e-4;
        let d = |t: f64| (s.eval(t + h) - s.eval(t - h)) * (0.5 / h);
        for t in [0.3, 0.55] {
            let r1 = s.deriv().eval(t).to_vec3();
            let r2 = s.deriv().deriv().eval(t).to_vec3();
            let r3 = s.deriv().deriv().deriv().eval(t).to_vec3();
            let c = r1.cross(r2);
            let expect = c.dot(r3) / c.hypot2();
            assert!((s.torsion(t) - expect).abs() <= 1e-12 * expect.abs().max(1.0));
            // The osculating plane turns at rate τ|r′|: compare the binormal's change.
            let b = |t: f64| {
                let c = s
                    .deriv()
                    .eval(t)
                    .to_vec3()
                    .cross(s.deriv().deriv().eval(t).to_vec3());
                c * (1.0 / c.length())
            };
            let db = (b(t + h) - b(t - h)) * (0.5 / h);
            // Frenet: b′ = −τ |r′| n, so |b′| = |τ| |r′|.
            assert!(
                (db.length() - s.torsion(t).abs() * d(t).length()).abs()
                    < 1e-5 * db.length().max(1.0)
            );
        }
        // A circular helix as a cubic: positive torsion for a right-handed turn.
        let right = SpaceBez::cubic(
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(1.0, 0.5, 0.2),
            Point3::new(0.5, 1.0, 0.4),
            Point3::new(0.0, 1.0, 0.6),
        );
        assert!(right.torsion(0.5) > 0.0);
        let mirrored = SpaceBez::new(
            &right
                .control_points()
                .iter()
                .map(|p| Point3::new(p.x, p.y, -p.z))
                .collect::<Vec<_>>(),
        )
        .unwrap();
        assert!((mirrored.torsion(0.5) + right.torsion(0.5)).abs() < 1e-12);
        // Planar segments have none.
        let flat = SpaceBez::quad(
            Point3::ORIGIN,
            Point3::new(1.0, 1.0, 1.0),
            Point3::new(2.0, 0.0, 3.0),
        );
        assert_eq!(flat.torsion(0.4), 0.0);
        let line = SpaceBez::cubic(
            Point3::ORIGIN,
            Point3::new(1.0, 1.0, 1.0),
            Point3::new(2.0, 2.0, 2.0),
            Point3::new(3.0, 3.0, 3.0),
        );
        assert_eq!(line.torsion(0.4), 0.0);
    }

    #[test]
    fn spacebez_arclen_matches_closed_forms_and_sampling() {
        let line = SpaceBez::line(Point3::ORIGIN, Point3::new(1.0, 2.0, 2.0));
        assert!((line.arclen(1e-12) - 3.0).abs() < 1e-14);
        // A quadratic with a collinear but uneven polygon: still the chord length.
        let q = SpaceBez::quad(
            Point3::ORIGIN,
            Point3::new(0.5, 1.0, 1.0),
            Point3::new(1.5, 3.0, 3.0),
        );
        assert!((q.arclen(1e-12) - 4.5).abs() < 1e-12);
        // A curved quartic against a fine polyline (which is shorter by O(1/N²)).
        let s = sample();
        let n = 200_000;
        let poly: f64 = (0..n)
            .map(|i| {
                s.eval(i as f64 / n as f64)
                    .distance(s.eval((i + 1) as f64 / n as f64))
            })
            .sum();
        let len = s.arclen(1e-10);
        assert!(len >= poly && len - poly < 1e-8, "{len} vs {poly}");
        assert_eq!(
            SpaceBez::quad(Point3::ORIGIN, Point3::ORIGIN, Point3::ORIGIN).arclen(1e-9),
            0.0
        );
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
