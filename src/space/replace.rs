//! The partial quartic replacement at a joint of a 3D κ-curve (seed 004 §3).
//!
//! Two consecutive quadratic segments `P0 P1 P2` and `P2 P3 P4` of a κ-curve meet at
//! `P2 = (1−λ) P1 + λ P3` (seed 004 eq. 7). Their pieces `t ∈ [t1, 1]` and `t ∈ [0, t2]` are
//! again quadratics, `Q0 B P2` and `P2 C Q4` with the de Casteljau points
//! `B = (1−t1) P1 + t1 P2`, `C = (1−t2) P2 + t2 P3`, `Q0 = C_i(t1)`, `Q4 = C_{i+1}(t2)` (eqs. 11,
//! 12), and they meet at `P2 = (1−λ′) B + λ′ C` with (eq. 15)
//!
//! ```text
//! λ′ = (λ t1 − λ) / (λ t1 + λ t2 − λ − t2).
//! ```
//!
//! Both pieces are replaced by the quartic (eq. 11)
//!
//! ```text
//! Q1 = (1−a′) Q0 + a′ B,   Q2 = (1−γ′) B + γ′ C,   Q3 = (1−b′) C + b′ Q4,
//! ```
//!
//! whose first three control points lie in the plane of the first quadratic and whose last
//! three lie in the plane of the second, so the osculating planes agree at both ends. The
//! curvatures agree too when (eqs. 16–18, which are eqs. 9 and 10 applied to the two pieces)
//!
//! ```text
//! γ′ = (γ − λ t1) / (t2 − λ (t1 + t2 − 1)),
//! a′ = √(3/2 · γ′/λ′) = √(3/2 · (γ − λ t1) / (λ (1 − t1))),
//! 1 − b′ = √(3/2 · (1−γ′)/(1−λ′)) = √(3/2 · (1 + (λ − γ) / ((1 − λ) t2))).
//! ```
//!
//! Why: at `t = 0` the quartic has `r′ = 4a′(B − Q0)` and a second derivative whose component
//! normal to the tangent is `12 γ′ n`, where `n` is that component of `C − B` (the points
//! `B, P2, Q2, C` all lie on the line `P1 P3`); the quadratic `Q0 B P2` has `r′ = 2(B − Q0)` and
//! `2 λ′ n`. Equal curvature vectors `12 γ′ n / (16 a′² |B−Q0|²) = 2 λ′ n / (4 |B−Q0|²)` give
//! `a′² = 3γ′/(2λ′)`; the end `t = 1` is the mirror image. So the joint is G2 in 3D — the
//! curvature *vectors* agree — for every `γ′ ∈ (0, 1)`, i.e. `γ ∈ (λ t1, λ + (1 − λ) t2)`, and
//! also where the quadratic κ-curve has an inflection (where it is only G1).
//!
//! `γ = λ` (the paper's default) gives `γ′ = λ′`, `Q2 = P2` and `a′ = 1 − b′ = √(3/2)`. The
//! paper's objective for choosing `γ` (eq. 20) is [`objective`].

use kurbo::common::GAUSS_LEGENDRE_COEFFS_16;

use crate::Point3;

/// A quadratic Bézier in 3D, as its three control points.
pub(crate) type Quad = [Point3; 3];

/// The point of a quadratic at `t` (de Casteljau).
#[inline]
pub(crate) fn quad_eval(q: &Quad, t: f64) -> Point3 {
    q[0].lerp(q[1], t).lerp(q[1].lerp(q[2], t), t)
}

/// The piece `[u, v]` of a quadratic: `C(u)`, the blossom `b(u, v)`, `C(v)`.
#[inline]
pub(crate) fn quad_piece(q: &Quad, u: f64, v: f64) -> Quad {
    // The blossom b(u, v) = lerp(lerp(q0, q1, u), lerp(q1, q2, u), v), in the form that is
    // exact at the ends of [0, 1].
    match (u == 0.0, v == 1.0) {
        (true, true) => *q,
        (true, false) => [q[0], q[0].lerp(q[1], v), quad_eval(q, v)],
        (false, true) => [quad_eval(q, u), q[1].lerp(q[2], u), q[2]],
        (false, false) => {
            let mid = q[0].lerp(q[1], u).lerp(q[1].lerp(q[2], u), v);
            [quad_eval(q, u), mid, quad_eval(q, v)]
        }
    }
}

/// The quartic replacing the pieces `[t1, 1]` of `left` and `[0, t2]` of `right`
/// (`left[2] == right[0]`), with `Q2` at the fraction `gamma_prime` of the way from `B` to `C`.
///
/// Returns the five control points and `(λ′, a′, 1 − b′)`, or `None` when the joint has no
/// usable ratio `λ′ ∈ (0, 1)` (a stalled end of one of the quadratics) or the result is not
/// finite.
pub(crate) fn quartic(
    left: &Quad,
    right: &Quad,
    t1: f64,
    t2: f64,
    gamma_prime: GammaPrime,
) -> Option<([Point3; 5], Replacement)> {
    let l = quad_piece(left, t1, 1.0);
    let r = quad_piece(right, 0.0, t2);
    // The joint itself, shared exactly by both pieces.
    let joint = left[2];
    let (q0, b, c, q4) = (l[0], l[1], r[1], r[2]);
    let bc = c - b;
    let bc2 = bc.hypot2();
    // λ′ measured on the pieces themselves (eq. 15 up to rounding), so that the curvature of
    // the quadratic `Q0 B P2` is matched for the points actually used.
    let lambda_p = (joint - b).dot(bc) / bc2;
    if !(lambda_p > 0.0 && lambda_p < 1.0) {
        return None;
    }
    let g = match gamma_prime {
        GammaPrime::Lambda => lambda_p,
        GammaPrime::Value(g) => g,
    };
    if !(g > 0.0 && g < 1.0) {
        return None;
    }
    // Eqs. 17 and 18 in the form of eqs. 9 and 10 for the two pieces.
    let a = (1.5 * g / lambda_p).sqrt();
    let e = (1.5 * (1.0 - g) / (1.0 - lambda_p)).sqrt();
    let q = [
        q0,
        q0.lerp(b, a),
        if matches!(gamma_prime, GammaPrime::Lambda) {
            // γ = λ: Q2 is the joint (eq. 14 with γ = λ is eq. 13).
            joint
        } else {
            b.lerp(c, g)
        },
        q4.lerp(c, e),
        q4,
    ];
    if !q.iter().all(|p| p.is_finite()) {
        return None;
    }
    Some((
        q,
        Replacement {
            lambda_prime: lambda_p,
            gamma_prime: g,
            a,
            b: 1.0 - e,
        },
    ))
}

/// How `Q2` is placed on `BC`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum GammaPrime {
    /// `γ = λ`: `Q2` is the joint.
    Lambda,
    /// `γ′` given.
    Value(f64),
}

/// The parameters of one replacement quartic (seed 004 eqs. 15–18).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Replacement {
    pub(crate) lambda_prime: f64,
    pub(crate) gamma_prime: f64,
    pub(crate) a: f64,
    pub(crate) b: f64,
}

/// `γ′` from `γ` (seed 004 eq. 16).
#[inline]
pub(crate) fn gamma_prime(gamma: f64, lambda: f64, t1: f64, t2: f64) -> f64 {
    (gamma - lambda * t1) / (t2 - lambda * (t1 + t2 - 1.0))
}

/// `γ` from `γ′` (eq. 16 solved for `γ`).
#[inline]
pub(crate) fn gamma_from_prime(gamma_prime: f64, lambda: f64, t1: f64, t2: f64) -> f64 {
    lambda * t1 + gamma_prime * (t2 - lambda * (t1 + t2 - 1.0))
}

/// The open interval of admissible `γ`: `(λ t1, λ + (1 − λ) t2)`, where `γ′ ∈ (0, 1)`.
#[inline]
pub(crate) fn gamma_range(lambda: f64, t1: f64, t2: f64) -> (f64, f64) {
    (lambda * t1, lambda + (1.0 - lambda) * t2)
}

/// The quartic's deviation from the pieces it replaces (seed 004 eq. 20, for the pieces):
///
/// ```text
/// F = ∫₀^½ |C(t) − L(2t)| dt + ∫_½^1 |C(t) − R(2t − 1)| dt
/// ```
///
/// with `C` the quartic, `L` the piece `Q0 B P2` and `R` the piece `P2 C Q4`, by 16-point
/// Gauss–Legendre quadrature on each half.
pub(crate) fn objective(quartic: &[Point3; 5], l: &Quad, r: &Quad) -> f64 {
    let mut sum = 0.0;
    for &(w, x) in GAUSS_LEGENDRE_COEFFS_16 {
        // x ∈ [-1, 1] → s ∈ [0, 1], the parameter of the replaced piece.
        let s = 0.5 * (x + 1.0);
        let left = quartic_eval(quartic, 0.5 * s).distance(quad_eval(l, s));
        let right = quartic_eval(quartic, 0.5 + 0.5 * s).distance(quad_eval(r, s));
        // dt = ds/2 on each half, and ds = dx/2.
        sum += w * (left + right);
    }
    0.25 * sum
}

/// The point of a quartic at `t` (de Casteljau).
#[inline]
pub(crate) fn quartic_eval(q: &[Point3; 5], t: f64) -> Point3 {
    let mut p = *q;
    for level in 1..5 {
        for i in 0..5 - level {
            p[i] = p[i].lerp(p[i + 1], t);
        }
    }
    p[0]
}

/// `γ′ ∈ [GAMMA_SEARCH_MARGIN, 1 − GAMMA_SEARCH_MARGIN]` is searched by [`optimal_gamma_prime`]:
/// towards 0 or 1 one end handle `a′` or `1 − b′` shrinks to nothing (a stall at the end).
const GAMMA_SEARCH_MARGIN: f64 = 0.01;
/// Coarse samples of the objective before the golden-section search.
const GAMMA_SAMPLES: usize = 16;
/// Golden-section iterations: the bracket (two sample steps, 0.12 wide) shrinks by 0.618
/// each, to below 1e-7 — far below what moves the objective.
const GAMMA_ITERATIONS: usize = 30;

/// The `γ′` minimizing [`objective`] (seed 004 §4, eq. 20): the best of [`GAMMA_SAMPLES`]
/// samples of `[0.01, 0.99]`, refined by golden-section search in the bracket around it.
/// `None` when the joint cannot be replaced at all.
pub(crate) fn optimal_gamma_prime(left: &Quad, right: &Quad, t1: f64, t2: f64) -> Option<f64> {
    let l = quad_piece(left, t1, 1.0);
    let r = quad_piece(right, 0.0, t2);
    let f = |g: f64| -> f64 {
        match quartic(left, right, t1, t2, GammaPrime::Value(g)) {
            Some((q, _)) => objective(&q, &l, &r),
            None => f64::INFINITY,
        }
    };
    let (lo, hi) = (GAMMA_SEARCH_MARGIN, 1.0 - GAMMA_SEARCH_MARGIN);
    let step = (hi - lo) / GAMMA_SAMPLES as f64;
    let at = |i: usize| lo + step * i as f64;
    let mut best = (usize::MAX, f64::INFINITY);
    for i in 0..=GAMMA_SAMPLES {
        let v = f(at(i));
        if v < best.1 {
            best = (i, v);
        }
    }
    if best.0 == usize::MAX {
        return None;
    }
    let (mut a, mut b) = (
        at(best.0.saturating_sub(1)),
        at((best.0 + 1).min(GAMMA_SAMPLES)),
    );
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let mut c = b - ratio * (b - a);
    let mut d = a + ratio * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..GAMMA_ITERATIONS {
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - ratio * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + ratio * (b - a);
            fd = f(d);
        }
    }
    let g = 0.5 * (a + b);
    // Keep the best point seen if the bracket's middle is worse (a kink of |·|).
    if f(g) <= best.1 {
        Some(g)
    } else {
        Some(at(best.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::{CurvatureAnalysis, SpaceBez};

    /// Two quadratics meeting at `P2 = (1−λ) P1 + λ P3`, in different planes.
    fn pair(lambda: f64) -> (Quad, Quad) {
        let p1 = Point3::new(1.0, 0.0, 0.0);
        let p3 = Point3::new(3.0, 0.2, 0.1);
        let p2 = p1.lerp(p3, lambda);
        (
            [Point3::new(0.0, 1.0, 0.2), p1, p2],
            [p2, p3, Point3::new(3.5, 0.5, 1.5)],
        )
    }

    fn rel_gap(a: crate::Vec3, b: crate::Vec3) -> f64 {
        (a - b).length() / a.length().max(b.length())
    }

    #[test]
    fn replace_quartic_is_g2_at_both_ends() {
        for lambda in [0.2, 0.5, 0.7] {
            let (l, r) = pair(lambda);
            for (t1, t2) in [(0.0, 1.0), (0.5, 0.5), (0.99, 0.01), (0.7, 0.2)] {
                for g in [
                    GammaPrime::Lambda,
                    GammaPrime::Value(0.3),
                    GammaPrime::Value(0.8),
                ] {
                    let (q, rep) = quartic(&l, &r, t1, t2, g).unwrap();
                    let quartic = SpaceBez::new(&q).unwrap();
                    let left = SpaceBez::new(&l).unwrap();
                    let right = SpaceBez::new(&r).unwrap();
                    assert!(quartic.start().distance(left.eval(t1)) < 1e-15);
                    assert!(quartic.end().distance(right.eval(t2)) < 1e-15);
                    let k0 = rel_gap(left.curvature_vector(t1), quartic.curvature_vector(0.0));
                    let k1 = rel_gap(quartic.curvature_vector(1.0), right.curvature_vector(t2));
                    assert!(
                        k0 < 1e-10 && k1 < 1e-10,
                        "λ {lambda} t {t1},{t2} {g:?}: {k0} {k1}"
                    );
                    // The closed forms of eqs. 15, 17, 18 agree with the pieces' own ratio.
                    let lp = (lambda * t1 - lambda) / (lambda * t1 + lambda * t2 - lambda - t2);
                    assert!((rep.lambda_prime - lp).abs() < 1e-12);
                    let gamma = gamma_from_prime(rep.gamma_prime, lambda, t1, t2);
                    let a17 = (1.5 * (gamma - lambda * t1) / (lambda * (1.0 - t1))).sqrt();
                    let b18 = 1.0 - (1.5 * (1.0 + (lambda - gamma) / ((1.0 - lambda) * t2))).sqrt();
                    assert!((rep.a - a17).abs() < 1e-9, "{} vs {a17}", rep.a);
                    assert!((rep.b - b18).abs() < 1e-9, "{} vs {b18}", rep.b);
                }
            }
        }
    }

    #[test]
    fn replace_full_matches_eqs_9_10() {
        let lambda = 0.35;
        let (l, r) = pair(lambda);
        let gamma = 0.5;
        let (q, rep) = quartic(&l, &r, 0.0, 1.0, GammaPrime::Value(gamma)).unwrap();
        assert!((rep.a - (3.0 * gamma / (2.0 * lambda)).sqrt()).abs() < 1e-12);
        assert!(
            (rep.b - (1.0 - (3.0 * (1.0 - gamma) / (2.0 * (1.0 - lambda))).sqrt())).abs() < 1e-12
        );
        // Eq. 6: Q0 = P0, Q4 = P4, Q2 on P1P3.
        assert_eq!(q[0], l[0]);
        assert_eq!(q[4], r[2]);
        assert!(q[2].distance(l[1].lerp(r[1], gamma)) < 1e-14);
    }

    #[test]
    fn replace_symmetry_eq_19() {
        // Swapping the roles (t2 ↔ 1 − t1, λ ↔ 1 − λ, γ ↔ 1 − γ) turns a′ into 1 − b′.
        let (lambda, gamma, t1, t2): (f64, f64, f64, f64) = (0.4, 0.45, 0.8, 0.3);
        let a = (1.5 * (gamma - lambda * t1) / (lambda * (1.0 - t1))).sqrt();
        let (l2, g2, t12, t22) = (1.0 - lambda, 1.0 - gamma, 1.0 - t2, 1.0 - t1);
        let b = 1.0 - (1.5 * (1.0 + (l2 - g2) / ((1.0 - l2) * t22))).sqrt();
        let _ = t12;
        assert!((1.0 - b - a).abs() < 1e-14);
    }

    #[test]
    fn replace_gamma_prime_round_trip_and_range() {
        let (lambda, t1, t2) = (0.3, 0.9, 0.05);
        for g in [0.1, 0.5, 0.9] {
            let gamma = gamma_from_prime(g, lambda, t1, t2);
            assert!((gamma_prime(gamma, lambda, t1, t2) - g).abs() < 1e-14);
        }
        let (lo, hi) = gamma_range(lambda, t1, t2);
        assert!(gamma_prime(lo, lambda, t1, t2).abs() < 1e-14);
        assert!((gamma_prime(hi, lambda, t1, t2) - 1.0).abs() < 1e-14);
        // γ = λ gives γ′ = λ′ (eq. 15).
        let lp = (lambda * t1 - lambda) / (lambda * t1 + lambda * t2 - lambda - t2);
        assert!((gamma_prime(lambda, lambda, t1, t2) - lp).abs() < 1e-14);
    }

    #[test]
    fn replace_rejects_unusable_ratios() {
        let (l, r) = pair(0.5);
        assert!(quartic(&l, &r, 0.5, 0.5, GammaPrime::Value(0.0)).is_none());
        assert!(quartic(&l, &r, 0.5, 0.5, GammaPrime::Value(1.0)).is_none());
        assert!(quartic(&l, &r, 0.5, 0.5, GammaPrime::Value(f64::NAN)).is_none());
        // A joint at P1 (λ = 0): the first quadratic stalls at its end.
        let (l, r) = pair(0.0);
        assert!(quartic(&l, &r, 0.5, 0.5, GammaPrime::Lambda).is_none());
    }

    #[test]
    fn replace_optimal_gamma_beats_lambda() {
        let (l, r) = pair(0.3);
        let (t1, t2) = (0.4, 0.6);
        let g = optimal_gamma_prime(&l, &r, t1, t2).unwrap();
        let lp = quad_piece(&l, t1, 1.0);
        let rp = quad_piece(&r, 0.0, t2);
        let f = |g: GammaPrime| objective(&quartic(&l, &r, t1, t2, g).unwrap().0, &lp, &rp);
        let best = f(GammaPrime::Value(g));
        assert!(best <= f(GammaPrime::Lambda) + 1e-15);
        // A local minimum: neighbours are no better.
        for h in [1e-4, -1e-4] {
            assert!(best <= f(GammaPrime::Value(g + h)) + 1e-12);
        }
    }

    #[test]
    fn replace_objective_is_zero_for_identical_curves() {
        // A quartic that *is* the two halves (degree-elevated line) has F = 0.
        let l: Quad = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(2.0, 0.0, 0.0),
        ];
        let r: Quad = [
            Point3::new(2.0, 0.0, 0.0),
            Point3::new(3.0, 0.0, 0.0),
            Point3::new(4.0, 0.0, 0.0),
        ];
        let q = [0.0, 1.0, 2.0, 3.0, 4.0].map(|x| Point3::new(x, 0.0, 0.0));
        assert!(objective(&q, &l, &r) < 1e-15);
        let moved = [0.0, 1.0, 2.0, 3.0, 4.0].map(|x| Point3::new(x, 0.0, 1.0));
        // Off by 1 everywhere: F = 1.
        assert!((objective(&moved, &l, &r) - 1.0).abs() < 1e-13);
    }
}
