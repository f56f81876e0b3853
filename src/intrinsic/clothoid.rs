//! G1 Hermite interpolation by a clothoid (linear curvature), the degree-1 case of the
//! intrinsic segments, in the normalized frame (chord from (0, 0) to (1, 0)).
//!
//! Following Bertolazzi & Frego ("G1 fitting with clothoids", Math. Methods Appl. Sci. 38,
//! 2015), the tangent angle of a clothoid of length `L` from the origin is
//! `θ(τ) = A τ² + (δ − A) τ + φ₀` in `τ = s / L`, which meets both end angles
//! (`θ(1) = φ₀ + δ = φ₁`) for every `A`. The end lands on the chord's line when
//! `g(A) = ∫_0^1 sin θ(τ) dτ = 0`; then `L = 1 / ∫_0^1 cos θ`, `κ₀ = (δ − A) / L` and
//! `κ₁ = (δ + A) / L`. `g` has many roots (clothoids that wind more); the one taken is the
//! root Newton's method reaches from their fitted initial guess, which is the one their
//! clothoid library returns.

use kurbo::common::solve_itp;

use super::quad::Rule;

/// Newton iterations before the bracketing fallback.
const NEWTON_ITERATIONS: usize = 20;
/// Newton stops when `|g| ≤ G_TOLERANCE` (g is a dimensionless distance from the chord).
const G_TOLERANCE: f64 = 1e-15;
/// Step of the scan for a sign change of `g` in the fallback.
const SCAN_STEP: f64 = 0.25;
/// Steps of the scan in each direction.
const SCAN_STEPS: usize = 400;
/// The largest `|A|` the search tries: each evaluation integrates a turning of about `|A|`
/// (one quadrature piece per 6 radians), so the scan around a guess far beyond this took
/// seconds per solve (found by the `hermite` fuzz target with many turns, `Turning::AsGiven`).
const SEARCH_LIMIT: f64 = 1e4;

/// A clothoid in the normalized frame: length and end curvatures (chord length 1).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Clothoid {
    /// Arc length.
    pub length: f64,
    /// Curvature at the start.
    pub k0: f64,
    /// Curvature at the end.
    pub k1: f64,
}

impl Clothoid {
    /// The curvature at `τ = s / L`.
    pub fn at(&self, t: f64) -> f64 {
        self.k0 + (self.k1 - self.k0) * t
    }
}

/// `(X, Y, dX/dA, dY/dA)` with `X + iY = ∫_0^1 e^{iθ(τ)} dτ`, `θ = Aτ² + (δ − A)τ + φ₀`, by
/// the Gauss–Legendre rule of [`Rule::new`] for the turning bound `max |θ′|`.
fn moments(a: f64, delta: f64, phi0: f64) -> (f64, f64, f64, f64) {
    // |θ′(τ)| = |2Aτ + δ − A| is largest at an end.
    let bound = (delta - a).abs().max((delta + a).abs());
    let rule = Rule::new(bound, None);
    let h = 1.0 / rule.pieces as f64;
    let (mut x, mut y, mut dx, mut dy) = (0.0, 0.0, 0.0, 0.0);
    for p in 0..rule.pieces {
        let mid = (p as f64 + 0.5) * h;
        for &(wi, xi) in rule.coeffs {
            let t = mid + 0.5 * h * xi;
            let th = (a * t + delta - a) * t + phi0;
            let (s, c) = th.sin_cos();
            let dth = t * t - t;
            x += wi * c;
            y += wi * s;
            dx -= wi * s * dth;
            dy += wi * c * dth;
        }
    }
    let f = 0.5 * h;
    (x * f, y * f, dx * f, dy * f)
}

/// The fitted initial guess of Bertolazzi & Frego (2015, §3) for `A`, from the end angles
/// relative to the chord: `(φ₀ + φ₁)` times a polynomial in `x = φ₀/π`, `y = φ₁/π` fitted
/// over `[−π, π]²`.
fn guess(phi0: f64, phi1: f64) -> f64 {
    const C: [f64; 6] = [
        2.989696028701907,
        0.716228953608281,
        -0.458969738821509,
        -0.502821153340377,
        0.261062141752652,
        -0.045854475238709,
    ];
    let x = phi0 / core::f64::consts::PI;
    let y = phi1 / core::f64::consts::PI;
    let xy = x * y;
    let (x2, y2) = (x * x, y * y);
    (phi0 + phi1)
        * (C[0]
            + xy * (C[1] + xy * C[2])
            + (C[3] + xy * C[4]) * (x2 + y2)
            + C[5] * (x2 * x2 + y2 * y2))
}

/// The clothoid from the origin at angle `φ₀` to `(1, 0)` at angle `φ₀ + δ`, or `None` when
/// none is found (never for `|φ₀|, |φ₀ + δ| ≤ π`, where Bertolazzi & Frego prove a solution
/// exists).
pub(crate) fn solve(phi0: f64, delta: f64) -> Option<Clothoid> {
    let phi1 = phi0 + delta;
    let g = |a: f64| moments(a, delta, phi0).1;
    let mut a = guess(phi0, phi1);
    for _ in 0..NEWTON_ITERATIONS {
        if a.is_nan() || a.abs() > SEARCH_LIMIT {
            break;
        }
        let (x, y, _, dy) = moments(a, delta, phi0);
        if y.abs() <= G_TOLERANCE {
            if x > 0.0 {
                return finish(a, delta, x);
            }
            break;
        }
        let step = y / dy;
        if !step.is_finite() {
            break;
        }
        a -= step;
        if a.is_nan() || a.abs() > SEARCH_LIMIT {
            // Diverged: the quadrature of a turning this large costs as much as it says.
            break;
        }
    }
    // Fallback: the nearest sign change of g around the guess with X > 0, refined by ITP.
    let bracket = |lo: (f64, f64), hi: (f64, f64)| -> Option<Clothoid> {
        if lo.1 != 0.0 && hi.1 != 0.0 && (lo.1 > 0.0) == (hi.1 > 0.0) {
            return None;
        }
        let sign = if lo.1 < 0.0 || hi.1 > 0.0 { 1.0 } else { -1.0 };
        let root = solve_itp(
            |a| sign * g(a),
            lo.0,
            hi.0,
            1e-15 * lo.0.abs().max(hi.0.abs()).max(1.0),
            1,
            0.2 / (hi.0 - lo.0),
            -(lo.1.abs().max(f64::MIN_POSITIVE)),
            hi.1.abs().max(f64::MIN_POSITIVE),
        );
        let x = moments(root, delta, phi0).0;
        (x > 0.0).then(|| finish(root, delta, x)).flatten()
    };
    let a0 = guess(phi0, phi1);
    if a0.is_nan() || a0.abs() > SEARCH_LIMIT {
        // The guess is fitted for end angles in [−π, π]; far outside, it is no start.
        return None;
    }
    let mut right = (a0, g(a0));
    let mut left = right;
    for j in 1..=SCAN_STEPS {
        let r = a0 + j as f64 * SCAN_STEP;
        let next = (r, g(r));
        if let Some(c) = bracket(right, next) {
            return Some(c);
        }
        right = next;
        let l = a0 - j as f64 * SCAN_STEP;
        let next = (l, g(l));
        if let Some(c) = bracket(next, left) {
            return Some(c);
        }
        left = next;
    }
    None
}

/// The clothoid of the initial guess for `A` alone (no Newton iterations): it meets both end
/// angles and, approximately, the end point; a start for other profiles.
pub(crate) fn approximate(phi0: f64, delta: f64) -> Option<Clothoid> {
    let a = guess(phi0, phi0 + delta);
    if a.is_nan() || a.abs() > SEARCH_LIMIT {
        return None;
    }
    let x = moments(a, delta, phi0).0;
    (x > 0.0).then(|| finish(a, delta, x)).flatten()
}

/// Length and end curvatures for a root `a` of `g` with `X = ∫_0^1 cos θ = x`.
fn finish(a: f64, delta: f64, x: f64) -> Option<Clothoid> {
    let length = 1.0 / x;
    let c = Clothoid {
        length,
        k0: (delta - a) / length,
        k1: (delta + a) / length,
    };
    (length.is_finite() && length > 0.0 && c.k0.is_finite() && c.k1.is_finite()).then_some(c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clothoid_straight_and_arc() {
        let c = solve(0.0, 0.0).unwrap();
        assert!(
            (c.length - 1.0).abs() < 1e-15 && c.k0 == 0.0 && c.k1 == 0.0,
            "{c:?}"
        );
        // A symmetric circular arc: φ₀ = 0.3, φ₁ = −0.3 (turning right by 0.6 over a unit
        // chord): radius 1 / (2 sin 0.3), length 0.6 r.
        let c = solve(0.3, -0.6).unwrap();
        let r = 1.0 / (2.0 * 0.3f64.sin());
        assert!((c.k0 + 1.0 / r).abs() < 1e-13 && (c.k1 + 1.0 / r).abs() < 1e-13);
        assert!((c.length - 0.6 * r).abs() < 1e-13);
    }
}
