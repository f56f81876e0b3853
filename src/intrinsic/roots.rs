//! Where a Bernstein polynomial changes sign in `(0, 1)`: root isolation by subdivision.
//!
//! The variation-diminishing property of the Bernstein basis bounds the number of roots of
//! `p = Σ c_j B_j^m` in an interval by the number of sign changes `V` of its coefficients
//! there, with the same parity (Descartes' rule of signs in Bernstein form). So an interval
//! with `V = 0` holds no root, one with `V = 1` exactly one simple root, which is then
//! refined by ITP ([`kurbo::common::solve_itp`]); intervals with `V ≥ 2` are split in half by
//! de Casteljau's algorithm. Splitting stops at the resolution of `f64`, where a cluster of
//! roots counts as a sign change only if the signs at its ends differ (a double root, where
//! `p` touches zero, is no sign change). This is the subdivision variant of the root
//! isolation seed 003 (§5) does with Bézier clipping. Rounding can split a double root into
//! two sign changes a hair apart; a pair with no more than rounding noise between them is
//! dropped.

use kurbo::common::solve_itp;

use super::bernstein::{eval, split_half};

/// Intervals narrower than this are not split further.
const MIN_WIDTH: f64 = 1e-15;
/// Values of `p` below this fraction of its largest coefficient are rounding noise.
const NOISE: f64 = 1e-13;
/// Accuracy of the refined roots (ITP stops at this bracket width).
const ROOT_ACCURACY: f64 = 1e-15;

/// The parameters in the open interval `(0, 1)` where `p(τ) = Σ c_j B_j^m(τ)` changes sign,
/// in increasing order, appended to `out` (which is cleared first). Roots of even multiplicity
/// (where `p` touches zero without crossing) are not reported; neither are roots at 0 or 1.
/// A zero polynomial has no sign changes. Non-finite coefficients give no roots.
pub(crate) fn sign_changes(c: &[f64], out: &mut Vec<f64>) {
    out.clear();
    let n = c.len();
    if n < 2 || !c.iter().all(|v| v.is_finite()) || c.iter().all(|&v| v == 0.0) {
        return;
    }
    // A stack of intervals (a, b, offset of their coefficients in `coeffs`).
    let mut coeffs: Vec<f64> = c.to_vec();
    let mut stack: Vec<(f64, f64, usize)> = vec![(0.0, 1.0, 0)];
    let mut left = vec![0.0; n];
    let mut right = vec![0.0; n];
    while let Some((a, b, off)) = stack.pop() {
        let d = &coeffs[off..off + n];
        match variations(d) {
            0 => {}
            1 => {
                // ITP wants f(a) < 0 < f(b): flip p when it starts positive (the sign just
                // inside the interval's start is that of its first nonzero coefficient).
                let sign = -first_sign(d);
                let f = |t: f64| sign * eval(c, t);
                let eps = ROOT_ACCURACY.max(f64::EPSILON * b);
                let k1 = 0.2 / (b - a);
                let t = solve_itp(f, a, b, eps, 1, k1, -tiny(f(a)), tiny(f(b)));
                out.push(t.clamp(a, b));
            }
            _ if b - a < MIN_WIDTH => {
                // Ends of opposite sign: an odd cluster of roots, one sign change.
                if first_sign(d) == -last_sign(d) {
                    out.push(0.5 * (a + b));
                }
            }
            _ => {
                split_half(d, &mut left, &mut right);
                let m = 0.5 * (a + b);
                // A root exactly at the split point belongs to neither open half.
                let (l, r) = (last_sign(&left), first_sign(&right));
                if left[n - 1] == 0.0 && l != 0.0 && l == -r {
                    out.push(m);
                }
                let off_r = coeffs.len();
                coeffs.extend_from_slice(&right);
                let off_l = coeffs.len();
                coeffs.extend_from_slice(&left);
                stack.push((m, b, off_r));
                stack.push((a, m, off_l));
            }
        }
    }
    out.sort_by(f64::total_cmp);
    // Two sign changes with nothing but rounding noise between them are one root where `p`
    // touches zero (a double root, which rounding split in two): drop the pair.
    let scale = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut k = 0;
    while k + 1 < out.len() {
        let mid = 0.5 * (out[k] + out[k + 1]);
        if eval(c, mid).abs() <= NOISE * scale {
            out.drain(k..k + 2);
        } else {
            k += 1;
        }
    }
}

/// Sign changes in a coefficient sequence, zeros skipped.
fn variations(d: &[f64]) -> usize {
    let mut count = 0;
    let mut last = 0.0;
    for &v in d {
        if v != 0.0 {
            if last != 0.0 && (v > 0.0) != (last > 0.0) {
                count += 1;
            }
            last = v;
        }
    }
    count
}

/// The sign (±1) of the first nonzero coefficient: the sign of `p` just right of the
/// interval's start. 0 for a zero sequence.
fn first_sign(d: &[f64]) -> f64 {
    d.iter().find(|&&v| v != 0.0).map_or(0.0, |v| v.signum())
}

/// The sign (±1) of the last nonzero coefficient: the sign of `p` just left of the interval's
/// end.
fn last_sign(d: &[f64]) -> f64 {
    d.iter()
        .rev()
        .find(|&&v| v != 0.0)
        .map_or(0.0, |v| v.signum())
}

/// `|y|`, or the smallest positive float when `y` is 0 (ITP wants strictly signed ends).
fn tiny(y: f64) -> f64 {
    if y == 0.0 {
        f64::MIN_POSITIVE
    } else {
        y.abs()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bernstein coefficients of `∏ (τ − r_k)` (degree = number of roots), by multiplying
    /// linear factors in Bernstein form with degree elevation.
    fn from_roots(roots: &[f64]) -> Vec<f64> {
        let mut c = vec![1.0];
        for &r in roots {
            // (τ − r) = −r B_0^1 + (1 − r) B_1^1; product with degree elevation.
            let m = c.len() - 1;
            let mut out = vec![0.0; m + 2];
            for (j, cj) in c.iter().enumerate() {
                // c_j B_j^m · (−r (1 − τ) + (1 − r) τ)
                let lo = (m + 1 - j) as f64 / (m + 1) as f64;
                let hi = (j + 1) as f64 / (m + 1) as f64;
                out[j] += cj * -r * lo;
                out[j + 1] += cj * (1.0 - r) * hi;
            }
            c = out;
        }
        c
    }

    #[test]
    fn roots_simple() {
        let roots = [0.1, 0.35, 0.5, 0.9];
        let c = from_roots(&roots);
        let mut out = Vec::new();
        sign_changes(&c, &mut out);
        assert_eq!(out.len(), 4, "{out:?}");
        for (a, b) in out.iter().zip(&roots) {
            assert!((a - b).abs() < 1e-12, "{out:?}");
        }
    }

    #[test]
    fn roots_double_and_triple() {
        let mut out = Vec::new();
        // A double root touches zero: no sign change.
        sign_changes(&from_roots(&[0.3, 0.3]), &mut out);
        assert!(out.is_empty(), "{out:?}");
        // A triple root crosses.
        sign_changes(&from_roots(&[0.6, 0.6, 0.6]), &mut out);
        assert_eq!(out.len(), 1, "{out:?}");
        assert!((out[0] - 0.6).abs() < 1e-4);
        // Roots at the ends and outside are not reported.
        sign_changes(&from_roots(&[0.0, 1.0, 1.5, -0.2]), &mut out);
        assert!(out.is_empty(), "{out:?}");
        sign_changes(&[0.0, 0.0, 0.0], &mut out);
        assert!(out.is_empty());
        sign_changes(&[1.0, f64::NAN], &mut out);
        assert!(out.is_empty());
    }

    #[test]
    fn roots_exact_midpoint() {
        let mut out = Vec::new();
        sign_changes(&[-1.0, 1.0], &mut out);
        assert_eq!(out, vec![0.5]);
        // Three roots with one exactly at a split point.
        sign_changes(&from_roots(&[0.25, 0.5, 0.75]), &mut out);
        assert_eq!(out.len(), 3, "{out:?}");
        for (a, b) in out.iter().zip([0.25, 0.5, 0.75]) {
            assert!((a - b).abs() < 1e-12, "{out:?}");
        }
    }
}
