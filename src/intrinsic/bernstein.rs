//! Bernstein polynomials on `[0, 1]`: evaluation, basis values, derivative, antiderivative,
//! subdivision and the numerator of a rational function's derivative.
//!
//! A polynomial of degree `m` is given by its Bernstein coefficients `c_0..c_m`:
//! `p(τ) = Σ c_j B_j^m(τ)`, `B_j^m(τ) = C(m, j) τ^j (1 − τ)^{m−j}`.

/// `p(τ) = Σ c_j B_j^m(τ)`, by a scaled Horner scheme: `(1 − τ)^m Σ c_j C(m, j) r^j` with
/// `r = τ / (1 − τ)` for `τ < ½`, and the mirrored form for `τ ≥ ½`, so that `r ≤ 1`.
/// `O(m)`; exact at both ends. An empty slice is the zero polynomial.
pub(crate) fn eval(c: &[f64], t: f64) -> f64 {
    let Some(m) = c.len().checked_sub(1) else {
        return 0.0;
    };
    if m == 0 {
        return c[0];
    }
    let s = 1.0 - t;
    if t < 0.5 {
        // Σ_j c_j C(m, j) r^j, Horner from j = m down, binomials built on the way.
        let r = t / s;
        let mut binom = 1.0;
        let mut acc = c[m];
        for j in (0..m).rev() {
            // C(m, j) = C(m, j + 1) (j + 1) / (m − j)
            binom = binom * (j + 1) as f64 / (m - j) as f64;
            acc = acc * r + c[j] * binom;
        }
        acc * s.powi(m as i32)
    } else {
        let r = s / t;
        let mut binom = 1.0;
        let mut acc = c[0];
        for (j, &cj) in c.iter().enumerate().skip(1) {
            // C(m, j) = C(m, j − 1) (m − j + 1) / j
            binom = binom * (m - j + 1) as f64 / j as f64;
            acc = acc * r + cj * binom;
        }
        acc * t.powi(m as i32)
    }
}

/// The Bernstein coefficients of `p′` (degree `m − 1`): `m (c_{j+1} − c_j)`, into `out`.
pub(crate) fn derivative(c: &[f64], out: &mut Vec<f64>) {
    out.clear();
    let m = c.len().saturating_sub(1) as f64;
    out.extend(c.windows(2).map(|w| m * (w[1] - w[0])));
}

/// The Bernstein coefficients (degree `m + 1`) of `∫_0^τ p`: `C_j = (1/(m+1)) Σ_{i<j} c_i`
/// (seed 003 eq. 8 is the value at `τ = 1`).
pub(crate) fn antiderivative(c: &[f64], out: &mut Vec<f64>) {
    out.clear();
    let scale = 1.0 / c.len() as f64;
    let mut sum = 0.0;
    out.push(0.0);
    for &ci in c {
        sum += ci;
        out.push(sum * scale);
    }
}

/// The coefficients of `p` restricted to `[a, b] ⊂ [0, 1]` and reparameterized to `[0, 1]`
/// (two de Casteljau splits), in place.
pub(crate) fn restrict(c: &mut [f64], a: f64, b: f64) {
    if b < 1.0 {
        split_left(c, b);
    }
    if a > 0.0 {
        // After the first split the range [0, b] is [0, 1]; a maps to a / b.
        let u = if b > 0.0 { a / b } else { 0.0 };
        split_right(c, u);
    }
}

/// Coefficients of `p` on `[0, t]`, in place (de Casteljau, keeping the left diagonal).
pub(crate) fn split_left(c: &mut [f64], t: f64) {
    let n = c.len();
    for k in 1..n {
        for j in (k..n).rev() {
            c[j] = c[j - 1] + t * (c[j] - c[j - 1]);
        }
    }
}

/// Coefficients of `p` on `[t, 1]`, in place (de Casteljau, keeping the right diagonal).
pub(crate) fn split_right(c: &mut [f64], t: f64) {
    let n = c.len();
    for k in 1..n {
        for j in 0..n - k {
            c[j] += t * (c[j + 1] - c[j]);
        }
    }
}

/// Splits the coefficients `c` at `τ = ½` into `left` and `right` (same length as `c`).
pub(crate) fn split_half(c: &[f64], left: &mut [f64], right: &mut [f64]) {
    let n = c.len();
    right.copy_from_slice(c);
    for (k, l) in left.iter_mut().enumerate() {
        *l = right[0];
        for j in 0..n - 1 - k {
            right[j] = 0.5 * (right[j] + right[j + 1]);
        }
    }
    // Each pass leaves the last entry of its level in place, so `right[j]` ends as entry `j`
    // of level `n − 1 − j`: the right half's coefficient `j`.
}

/// The numerator `N = f′g − fg′` of the derivative of the rational function
/// `K_R = f / g`, `f = Σ w_i κ_i B_i^n`, `g = Σ w_i B_i^n`, as Bernstein coefficients of
/// degree `2n − 2` (seed 003 eq. 11: the apparent degree `2n − 1` drops by one):
///
/// ```text
/// N(τ) = n Σ_{i,j=0}^{n−1} D_{i+1,j} B_i^{n−1}(τ) B_j^{n−1}(τ),   D_{p,q} = w_p w_q (κ_p − κ_q),
/// ```
///
/// and `B_i^{n−1} B_j^{n−1} = C(n−1,i) C(n−1,j) / C(2n−2,i+j) · B_{i+j}^{2n−2}`. For `n ≤ 1`
/// the numerator is the constant `w_0 w_1 (κ_1 − κ_0)` (or 0).
pub(crate) fn rational_derivative_numerator(k: &[f64], w: &[f64], out: &mut Vec<f64>) {
    out.clear();
    let n = k.len().saturating_sub(1);
    if n == 0 {
        out.push(0.0);
        return;
    }
    let m = n - 1;
    let binom_m = binomials(m);
    let binom_2m = binomials(2 * m);
    out.resize(2 * m + 1, 0.0);
    for i in 0..=m {
        for j in 0..=m {
            let d = w[i + 1] * w[j] * (k[i + 1] - k[j]);
            out[i + j] += d * binom_m[i] * binom_m[j];
        }
    }
    for (kk, v) in out.iter_mut().enumerate() {
        *v *= n as f64 / binom_2m[kk];
    }
}

/// `C(m, 0), …, C(m, m)` as floats.
fn binomials(m: usize) -> Vec<f64> {
    let mut out = Vec::with_capacity(m + 1);
    let mut b = 1.0;
    out.push(b);
    for j in 1..=m {
        b = b * (m - j + 1) as f64 / j as f64;
        out.push(b);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn naive(c: &[f64], t: f64) -> f64 {
        let m = c.len() - 1;
        let b = binomials(m);
        c.iter()
            .enumerate()
            .map(|(j, cj)| cj * b[j] * t.powi(j as i32) * (1.0 - t).powi((m - j) as i32))
            .sum()
    }

    #[test]
    fn bernstein_eval_matches_definition() {
        let c = [0.3, -1.2, 2.5, 0.7, -0.4, 1.1];
        for i in 0..=20 {
            let t = i as f64 / 20.0;
            assert!((eval(&c, t) - naive(&c, t)).abs() < 1e-14, "t = {t}");
        }
        assert_eq!(eval(&c, 0.0), 0.3);
        assert_eq!(eval(&c, 1.0), 1.1);
        assert_eq!(eval(&[], 0.5), 0.0);
        assert_eq!(eval(&[2.0], 0.5), 2.0);
    }

    #[test]
    fn bernstein_derivative_and_antiderivative() {
        let c = [0.3, -1.2, 2.5, 0.7];
        let mut d = Vec::new();
        derivative(&c, &mut d);
        let mut a = Vec::new();
        antiderivative(&c, &mut a);
        let h = 1e-6;
        for t in [0.1, 0.4, 0.8] {
            let fd = (eval(&c, t + h) - eval(&c, t - h)) / (2.0 * h);
            assert!((eval(&d, t) - fd).abs() < 1e-8);
            let fa = (eval(&a, t + h) - eval(&a, t - h)) / (2.0 * h);
            assert!((eval(&c, t) - fa).abs() < 1e-8);
        }
        assert_eq!(eval(&a, 0.0), 0.0);
        // ∫_0^1 p = mean of the coefficients.
        assert!((eval(&a, 1.0) - c.iter().sum::<f64>() / 4.0).abs() < 1e-15);
    }

    #[test]
    fn bernstein_restrict_and_split() {
        let c = [0.3, -1.2, 2.5, 0.7, -0.4];
        let mut r = c;
        restrict(&mut r, 0.2, 0.7);
        for u in [0.0, 0.3, 1.0] {
            assert!((eval(&r, u) - eval(&c, 0.2 + 0.5 * u)).abs() < 1e-14);
        }
        let (mut l, mut rr) = ([0.0; 5], [0.0; 5]);
        split_half(&c, &mut l, &mut rr);
        for u in [0.0, 0.25, 1.0] {
            assert!((eval(&l, u) - eval(&c, 0.5 * u)).abs() < 1e-14);
            assert!((eval(&rr, u) - eval(&c, 0.5 + 0.5 * u)).abs() < 1e-14);
        }
    }

    #[test]
    fn rational_numerator_is_quotient_rule() {
        let k = [0.4, -1.0, 2.0, 0.3];
        let w = [1.0, 2.5, 0.4, 1.3];
        let n = 3;
        let f: Vec<f64> = k.iter().zip(&w).map(|(k, w)| k * w).collect();
        let (mut fd, mut gd, mut num) = (Vec::new(), Vec::new(), Vec::new());
        derivative(&f, &mut fd);
        derivative(&w, &mut gd);
        rational_derivative_numerator(&k, &w, &mut num);
        assert_eq!(num.len(), 2 * n - 1);
        for t in [0.0, 0.2, 0.55, 1.0] {
            let expect = eval(&fd, t) * eval(&w, t) - eval(&f, t) * eval(&gd, t);
            assert!((eval(&num, t) - expect).abs() < 1e-12, "{t}");
        }
    }
}
