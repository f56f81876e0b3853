//! Curves in the generalized trigonometric basis (seed 000 §4 and App. B).
//!
//! With `S = sin(πt/2)`, `C = cos(πt/2)` and `u = 1 - S`, `v = S + C - 1`, `w = 1 - C`
//! (so `u + v + w = 1` and `v² = 2uw`, eq. 15), the curve of degree `n` with the `2n + 1`
//! control points `P_0..P_2n` is `[(uE_0 + vE_1 + wE_2)^n P]_0`, where `E_k` shifts the
//! index by `k`: it is evaluated by `n` rounds of the blending `u P_j + v P_{j+1} + w P_{j+2}`
//! (eq. 42), like de Casteljau's algorithm, with no coefficient table. Expanding the power
//! with `v² = 2uw` gives one basis function per control point, `c_{n,m} u^i v^j w^k` with
//! `j = m mod 2`, `k = ⌊m/2⌋`, `i = n - j - k`; the integers `c_{n,m}` form the triangle of
//! eq. 43.
//!
//! Because the shift operators commute, the derivative follows like that of a Bézier curve:
//! `C' = n [(u'E_0 + v'E_1 + w'E_2)(uE_0 + vE_1 + wE_2)^{n-1} P]_0`, with `u' = -(π/2)C`,
//! `v' = (π/2)(C - S)`, `w' = (π/2)S`.
//!
//! The linear curve (`n = 1`) with `P_1 - P_0 ⟂ P_2 - P_1` and equal legs is an exact
//! circular arc (a quarter circle), without rational weights.

use core::ops::Range;

use kurbo::{CurveFitSample, ParamCurve, ParamCurveArclen, ParamCurveFit, Point, Vec2};

use crate::fit::speed_cusp;

/// Control points kept on the stack during evaluation (degree ≤ 8).
const STACK_POINTS: usize = 17;

/// A curve in the generalized trigonometric basis of degree `n ≥ 1` (`2n + 1` control
/// points), restricted to a parameter range of the full curve so that
/// [`ParamCurve::subsegment`] is exact (the basis is not closed under reparametrization).
#[derive(Clone, Debug, PartialEq)]
pub struct TrigBez {
    points: Vec<Point>,
    range: Range<f64>,
}

impl TrigBez {
    /// The curve with these control points on the full range `[0, 1]`, or `None` unless
    /// there are `2n + 1 ≥ 3` of them.
    pub fn new(points: Vec<Point>) -> Option<TrigBez> {
        if points.len() < 3 || points.len() % 2 == 0 {
            return None;
        }
        Some(TrigBez {
            points,
            range: 0.0..1.0,
        })
    }

    /// The linear trigonometric curve `u P0 + v P1 + w P2` (seed 000 eq. 18).
    pub fn linear(p0: Point, p1: Point, p2: Point) -> TrigBez {
        TrigBez {
            points: vec![p0, p1, p2],
            range: 0.0..1.0,
        }
    }

    /// The constrained quadratic trigonometric curve of εκ-curves (seed 000 eq. 17) with
    /// defining points `Q0, Q1, Q2` and shape `a`: control points `P0 = Q0`,
    /// `P1 = (1-a)Q0 + aQ1`, `P2 = [(1-a)Q0 + 2aQ1 + (1-a)Q2]/2`, `P3 = aQ1 + (1-a)Q2`,
    /// `P4 = Q2`. At `a = 1/2` it is the linear curve through `Q0, Q1, Q2` (degree-elevated).
    pub fn constrained(q0: Point, q1: Point, q2: Point, a: f64) -> TrigBez {
        let b = 1.0 - a;
        let p2 = ((b * q0.to_vec2() + 2.0 * a * q1.to_vec2() + b * q2.to_vec2()) * 0.5).to_point();
        TrigBez {
            points: vec![q0, q0.lerp(q1, a), p2, q2.lerp(q1, a), q2],
            range: 0.0..1.0,
        }
    }

    /// The degree `n`.
    pub fn degree(&self) -> usize {
        self.points.len() / 2
    }

    /// The `2n + 1` control points.
    pub fn points(&self) -> &[Point] {
        &self.points
    }

    /// The parameter range of the full curve that this curve covers (`0..1` unless it is a
    /// subsegment).
    pub fn range(&self) -> Range<f64> {
        self.range.clone()
    }

    /// The full-curve parameter of `t` and `d(full)/dt`.
    #[inline]
    fn full(&self, t: f64) -> (f64, f64) {
        let w = self.range.end - self.range.start;
        (self.range.start + w * t, w)
    }

    /// Runs `f` on a mutable copy of the control points relative to the first one (on the
    /// stack up to degree 8). Blending differences keeps small curves far from the origin
    /// accurate: the derivatives do not carry the rounding of the absolute coordinates.
    #[inline]
    fn with_copy<R>(&self, f: impl FnOnce(&mut [Vec2]) -> R) -> R {
        /// The copy in an array of exactly `N` points (no unused entries to clear).
        #[inline(always)]
        fn exact<const N: usize, R>(points: &[Point], f: impl FnOnce(&mut [Vec2]) -> R) -> R {
            let mut buf: [Vec2; N] = core::array::from_fn(|i| points[i] - points[0]);
            f(&mut buf)
        }
        let n = self.points.len();
        // The degrees the εκ-curves use (the constrained quadratic and the linear curve)
        // get arrays of their own size: clearing the whole stack buffer cost more than the
        // evaluation.
        if n == 5 {
            exact::<5, R>(&self.points, f)
        } else if n == 3 {
            exact::<3, R>(&self.points, f)
        } else if n <= STACK_POINTS {
            let mut buf = [Vec2::ZERO; STACK_POINTS];
            for (b, p) in buf.iter_mut().zip(&self.points) {
                *b = *p - self.points[0];
            }
            f(&mut buf[..n])
        } else {
            let mut buf: Vec<Vec2> = self.points.iter().map(|p| *p - self.points[0]).collect();
            f(&mut buf)
        }
    }

    /// The point, first and second derivative at full-curve parameter `s`.
    fn eval_full(&self, s: f64) -> (Point, Vec2, Vec2) {
        let n = self.degree();
        let om = core::f64::consts::FRAC_PI_2;
        let (sn, cs) = (om * s).sin_cos();
        let k = [1.0 - sn, sn + cs - 1.0, 1.0 - cs];
        let k1 = [-om * cs, om * (cs - sn), om * sn];
        let k2 = [om * om * sn, -om * om * (sn + cs), om * om * cs];
        self.with_copy(|buf| {
            // Blend down to five points (three for the linear curve).
            let keep = if n >= 2 { 5 } else { 3 };
            let mut len = buf.len();
            while len > keep {
                blend(buf, len, k);
                len -= 2;
            }
            let nf = n as f64;
            let origin = self.points[0];
            if n == 1 {
                let p = origin + dot3(k, buf, 0);
                return (p, dot3(k1, buf, 0), dot3(k2, buf, 0));
            }
            // From the five points of level n-2: X'² and X''X, then X for the rest.
            let e1 = [dot3(k1, buf, 0), dot3(k1, buf, 1), dot3(k1, buf, 2)];
            let x = [dot3(k, buf, 0), dot3(k, buf, 1), dot3(k, buf, 2)];
            let d1 = nf * dot3(k1, &x, 0);
            let d2 = nf * (nf - 1.0) * dot3(k1, &e1, 0) + nf * dot3(k2, &x, 0);
            (origin + dot3(k, &x, 0), d1, d2)
        })
    }

    /// The point and the first and second derivatives (with respect to this curve's
    /// parameter) at `t`, from one evaluation.
    pub fn eval_derivs(&self, t: f64) -> (Point, Vec2, Vec2) {
        let (s, w) = self.full(t);
        let (p, d1, d2) = self.eval_full(s);
        (p, d1 * w, d2 * (w * w))
    }

    /// The first derivative with respect to this curve's parameter.
    pub fn derivative(&self, t: f64) -> Vec2 {
        let (s, w) = self.full(t);
        self.eval_full(s).1 * w
    }

    /// The second derivative with respect to this curve's parameter.
    pub fn second_derivative(&self, t: f64) -> Vec2 {
        let (s, w) = self.full(t);
        self.eval_full(s).2 * (w * w)
    }

    /// The signed curvature `(x′y″ − y′x″)/|C′|³`, positive for left turns (the crate's
    /// convention, opposite to kurbo's `ParamCurveCurvature`). NaN-free: 0 where the speed
    /// vanishes.
    pub fn curvature(&self, t: f64) -> f64 {
        let (s, _) = self.full(t);
        let (_, d1, d2) = self.eval_full(s);
        let speed2 = d1.hypot2();
        if speed2 == 0.0 {
            return 0.0;
        }
        // The parameter scale cancels in the curvature.
        d1.cross(d2) / (speed2 * speed2.sqrt())
    }
}

/// One blending round `b_j ← u b_j + v b_{j+1} + w b_{j+2}` over the first `len` entries.
#[inline]
fn blend(buf: &mut [Vec2], len: usize, k: [f64; 3]) {
    for j in 0..len - 2 {
        buf[j] = k[0] * buf[j] + k[1] * buf[j + 1] + k[2] * buf[j + 2];
    }
}

#[inline]
fn dot3(k: [f64; 3], b: &[Vec2], j: usize) -> Vec2 {
    k[0] * b[j] + k[1] * b[j + 1] + k[2] * b[j + 2]
}

impl ParamCurve for TrigBez {
    fn eval(&self, t: f64) -> Point {
        let (s, _) = self.full(t);
        self.eval_full(s).0
    }

    fn subsegment(&self, range: Range<f64>) -> TrigBez {
        let (a, _) = self.full(range.start);
        let (b, _) = self.full(range.end);
        TrigBez {
            points: self.points.clone(),
            range: a..b,
        }
    }

    fn start(&self) -> Point {
        if self.range.start == 0.0 {
            self.points[0]
        } else {
            self.eval(0.0)
        }
    }

    fn end(&self) -> Point {
        if self.range.end == 1.0 {
            self.points[self.points.len() - 1]
        } else {
            self.eval(1.0)
        }
    }
}

impl ParamCurveArclen for TrigBez {
    /// Arc length by Gauss–Legendre quadrature of the speed (24 and 32 nodes compared),
    /// subdividing until they agree to `accuracy` (at most 2^16 pieces).
    fn arclen(&self, accuracy: f64) -> f64 {
        arclen_rec(self, 0.0, 1.0, accuracy.max(1e-300), 16)
    }
}

fn arclen_rec(c: &TrigBez, a: f64, b: f64, accuracy: f64, depth: u32) -> f64 {
    let gl = |coeffs: &[(f64, f64)]| {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        coeffs
            .iter()
            .map(|&(wi, xi)| wi * c.derivative(mid + half * xi).hypot())
            .sum::<f64>()
            * half
    };
    let coarse = gl(kurbo::common::GAUSS_LEGENDRE_COEFFS_24);
    let fine = gl(kurbo::common::GAUSS_LEGENDRE_COEFFS_32);
    if (coarse - fine).abs() <= accuracy || depth == 0 || !fine.is_finite() {
        return fine;
    }
    let m = 0.5 * (a + b);
    arclen_rec(c, a, m, 0.5 * accuracy, depth - 1) + arclen_rec(c, m, b, 0.5 * accuracy, depth - 1)
}

impl ParamCurveFit for TrigBez {
    fn sample_pt_tangent(&self, t: f64, sign: f64) -> CurveFitSample {
        let (s, w) = self.full(t);
        let (p, d1, d2) = self.eval_full(s);
        // At a cusp the tangent is the direction of the second derivative, taken on the
        // side that `sign` asks for.
        let tangent = if d1.hypot2() > 1e-24 * (d2.hypot2() + 1e-300) {
            d1 * w
        } else {
            d2 * sign
        };
        CurveFitSample { p, tangent }
    }

    fn sample_pt_deriv(&self, t: f64) -> (Point, Vec2) {
        let (s, w) = self.full(t);
        let (p, d1, _) = self.eval_full(s);
        (p, d1 * w)
    }

    fn break_cusp(&self, range: Range<f64>) -> Option<f64> {
        speed_cusp(|t| self.derivative(t), range)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's coefficient triangle (seed 000 App. B eq. 43), degrees 1 to 6.
    const TRIANGLE: [&[f64]; 6] = [
        &[1.0, 1.0, 1.0],
        &[1.0, 2.0, 4.0, 2.0, 1.0],
        &[1.0, 3.0, 9.0, 8.0, 9.0, 3.0, 1.0],
        &[1.0, 4.0, 16.0, 20.0, 34.0, 20.0, 16.0, 4.0, 1.0],
        &[1.0, 5.0, 25.0, 40.0, 90.0, 74.0, 90.0, 40.0, 25.0, 5.0, 1.0],
        &[
            1.0, 6.0, 36.0, 70.0, 195.0, 204.0, 328.0, 204.0, 195.0, 70.0, 36.0, 6.0, 1.0,
        ],
    ];

    fn pseudo_points(n: usize, seed: u64) -> Vec<Point> {
        let mut x = seed;
        let mut next = || {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((x >> 11) as f64 / (1u64 << 53) as f64) * 10.0 - 5.0
        };
        (0..2 * n + 1).map(|_| Point::new(next(), next())).collect()
    }

    #[test]
    fn recursive_blending_matches_the_coefficient_triangle() {
        for (row, coeffs) in TRIANGLE.iter().enumerate() {
            let n = row + 1;
            let pts = pseudo_points(n, n as u64);
            let curve = TrigBez::new(pts.clone()).unwrap();
            for i in 0..=16 {
                let t = i as f64 / 16.0;
                let (s, c) = (core::f64::consts::FRAC_PI_2 * t).sin_cos();
                let (u, v, w) = (1.0 - s, s + c - 1.0, 1.0 - c);
                let mut expected = Vec2::ZERO;
                for (m, &cm) in coeffs.iter().enumerate() {
                    let (j, k) = (m % 2, m / 2);
                    let i = n - j - k;
                    let f = cm * u.powi(i as i32) * v.powi(j as i32) * w.powi(k as i32);
                    expected += f * pts[m].to_vec2();
                }
                let got = curve.eval(t);
                assert!((got.to_vec2() - expected).hypot() < 1e-12, "n={n} t={t}");
            }
            // The basis sums to one: (u + v + w)^n = 1.
            let sum: f64 = coeffs
                .iter()
                .enumerate()
                .map(|(m, &cm)| {
                    let (s, c) = (0.3f64, (1.0f64 - 0.09).sqrt());
                    let (u, v, w) = (1.0 - s, s + c - 1.0, 1.0 - c);
                    let (j, k) = (m % 2, m / 2);
                    cm * u.powi((n - j - k) as i32) * v.powi(j as i32) * w.powi(k as i32)
                })
                .sum();
            assert!((sum - 1.0).abs() < 1e-14, "n={n}: {sum}");
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        for n in 1..=7 {
            let curve = TrigBez::new(pseudo_points(n, 40 + n as u64)).unwrap();
            let h = 1e-5;
            for i in 1..10 {
                let t = i as f64 / 10.0;
                let fd1 = (curve.eval(t + h) - curve.eval(t - h)) / (2.0 * h);
                let fd2 = (curve.derivative(t + h) - curve.derivative(t - h)) / (2.0 * h);
                let (d1, d2) = (curve.derivative(t), curve.second_derivative(t));
                assert!((d1 - fd1).hypot() < 1e-8 * (1.0 + d1.hypot()), "n={n}");
                assert!((d2 - fd2).hypot() < 1e-7 * (1.0 + d2.hypot()), "n={n}");
            }
        }
    }

    /// `eval_derivs` is the three separate evaluations in one, on full curves and on
    /// subsegments, for every stack-buffer size (3, 5 and the general one).
    #[test]
    fn eval_derivs_matches_separate_evaluations() {
        for n in 1..=9 {
            let full = TrigBez::new(pseudo_points(n, 70 + n as u64)).unwrap();
            for curve in [full.clone(), full.subsegment(0.15..0.8)] {
                for i in 0..=10 {
                    let t = i as f64 / 10.0;
                    let (p, d1, d2) = curve.eval_derivs(t);
                    assert_eq!(p, curve.eval(t), "n={n}");
                    assert_eq!(d1, curve.derivative(t), "n={n}");
                    assert_eq!(d2, curve.second_derivative(t), "n={n}");
                }
            }
        }
    }

    #[test]
    fn linear_right_angle_is_a_quarter_circle() {
        let c = TrigBez::linear(
            Point::new(1.0, 0.0),
            Point::new(1.0, 1.0),
            Point::new(0.0, 1.0),
        );
        for i in 0..=100 {
            let t = i as f64 / 100.0;
            assert!((c.eval(t).to_vec2().hypot() - 1.0).abs() < 1e-15);
            assert!((c.curvature(t) - 1.0).abs() < 1e-12);
        }
        let len = c.arclen(1e-12);
        assert!((len - core::f64::consts::FRAC_PI_2).abs() < 1e-12, "{len}");
    }

    #[test]
    fn constrained_half_is_the_linear_curve() {
        let (q0, q1, q2) = (
            Point::new(0.0, 0.0),
            Point::new(2.0, 3.0),
            Point::new(5.0, 1.0),
        );
        let quad = TrigBez::constrained(q0, q1, q2, 0.5);
        let lin = TrigBez::linear(q0, q1, q2);
        for i in 0..=20 {
            let t = i as f64 / 20.0;
            assert!((quad.eval(t) - lin.eval(t)).hypot() < 1e-14);
            assert!((quad.derivative(t) - lin.derivative(t)).hypot() < 1e-13);
        }
    }

    #[test]
    fn constrained_matches_the_bernstein_like_form() {
        // Seed 000 eq. 29 with α = 2a: b0 Q0 + b1 Q1 + b2 Q2.
        let (q0, q1, q2) = (
            Point::new(0.0, 0.0),
            Point::new(2.0, 3.0),
            Point::new(5.0, 1.0),
        );
        for a in [0.5, 0.6, 0.75, 0.9, 0.99] {
            let curve = TrigBez::constrained(q0, q1, q2, a);
            let al = 2.0 * a;
            for i in 0..=20 {
                let t = i as f64 / 20.0;
                let (s, c) = (core::f64::consts::FRAC_PI_2 * t).sin_cos();
                let b0 = 1.0 + (al - 1.0) * s * s - al * s;
                let b1 = al * (s + c - 1.0);
                let b2 = 1.0 + (al - 1.0) * c * c - al * c;
                let expected = b0 * q0.to_vec2() + b1 * q1.to_vec2() + b2 * q2.to_vec2();
                assert!(
                    (curve.eval(t).to_vec2() - expected).hypot() < 1e-14,
                    "a={a}"
                );
            }
        }
    }

    #[test]
    fn subsegments_are_exact() {
        let curve = TrigBez::new(pseudo_points(3, 9)).unwrap();
        let sub = curve.subsegment(0.2..0.7);
        let subsub = sub.subsegment(0.5..1.0);
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            assert!((sub.eval(t) - curve.eval(0.2 + 0.5 * t)).hypot() < 1e-14);
            assert!((subsub.eval(t) - curve.eval(0.45 + 0.25 * t)).hypot() < 1e-14);
            let d = sub.derivative(t) - curve.derivative(0.2 + 0.5 * t) * 0.5;
            assert!(d.hypot() < 1e-13);
            assert!((sub.curvature(t) - curve.curvature(0.2 + 0.5 * t)).abs() < 1e-10);
        }
        let total = curve.arclen(1e-12);
        let parts =
            curve.subsegment(0.0..0.3).arclen(1e-13) + curve.subsegment(0.3..1.0).arclen(1e-13);
        assert!((total - parts).abs() < 1e-11);
    }

    #[test]
    fn bad_control_counts_are_rejected() {
        assert!(TrigBez::new(vec![Point::ZERO; 2]).is_none());
        assert!(TrigBez::new(vec![Point::ZERO; 4]).is_none());
        assert!(TrigBez::new(vec![Point::ZERO; 21]).is_some());
    }
}
