//! Symmetric Toeplitz tridiagonal systems `x_{i−1} + q x_i + x_{i+1} = d_i`, open or
//! cyclic, solved in two streaming sweeps without buffers
//! ([`solve_symmetric_toeplitz_into`]).

/// Largest number of Thomas multipliers of [`solve_symmetric_toeplitz_into`] computed before they
/// are taken as settled. For `q ≥ 3` they converge to `α = (q − √(q² − 4))/2` like `α^{2i}`
/// (`α² ≤ 0.146`), i.e. to the last bit within about 20 steps.
const TOEPLITZ_PREFIX: usize = 64;

/// Terms of the geometric series `Σ (−α)^j d_{k−j}` that start the cyclic recursions of
/// [`solve_symmetric_toeplitz_into`]: `α^j` is below 2⁻⁶³ (far below rounding) from `j = 34` on for
/// `q ≥ 4` (`α ≤ 0.268`) and from `j = 46` on for `q = 3` (`α = 0.382`).
const TOEPLITZ_SERIES: usize = 48;

/// Vectors the streaming solver [`solve_symmetric_toeplitz_into`] works on: anything with
/// addition and scaling (coordinate arrays, points used as vectors).
pub(crate) trait Lin: Copy {
    /// The zero vector.
    const ZERO: Self;
    /// `self + s · other`.
    fn add_scaled(self, other: Self, s: f64) -> Self;
    /// `s · self`.
    fn scaled(self, s: f64) -> Self;
}

impl<const D: usize> Lin for [f64; D] {
    const ZERO: Self = [0.0; D];
    #[inline]
    fn add_scaled(self, other: Self, s: f64) -> Self {
        core::array::from_fn(|k| self[k] + s * other[k])
    }
    #[inline]
    fn scaled(self, s: f64) -> Self {
        self.map(|x| s * x)
    }
}

/// Solve the symmetric Toeplitz tridiagonal system `x_{i−1} + q x_i + x_{i+1} = d_i` in
/// place; see [`solve_symmetric_toeplitz_into`].
#[cfg(test)]
pub(crate) fn solve_symmetric_toeplitz<T: Lin>(q: f64, d: &mut [T], cyclic: bool) -> bool {
    let rhs = d.to_vec();
    let mut out = Vec::with_capacity(d.len());
    if !solve_symmetric_toeplitz_into(q, cyclic, d.len(), |i| rhs[i], &mut out, |x| x) {
        return false;
    }
    d.copy_from_slice(&out);
    true
}

/// Solve the symmetric Toeplitz tridiagonal system `x_{i−1} + q x_i + x_{i+1} = d_i`
/// (`i = 0 … n−1`, with `x_{−1} = x_n = 0`, or cyclically with `x_{−1} = x_{n−1}`,
/// `x_n = x_0`) for `q ≥ 3`, in `O(n)` and in two sweeps, without buffers: the right-hand
/// side is read through `rhs(i)` during the first sweep, and `finish(x_i)` is appended to
/// `out` (after what it already holds) during the second.
///
/// - Open: Thomas' algorithm. Its multipliers `m_0 = 1/q`, `m_i = 1/(q − m_{i−1})` do not
///   depend on `d` and settle to a constant after a few steps, so only a short prefix is kept
///   (on the stack) and the forward step is `y_i = (d_i − y_{i−1}) m_i`.
/// - Cyclic: the circulant factors as `(1/α)(I + αS)(I + αS⁻¹)` with the cyclic shift
///   `(Sx)_i = x_{i−1}` and `α + 1/α = q`, `α = (q − √(q² − 4))/2 < 1`, so the solve is one
///   forward recursion `w_i = α d_i − α w_{i−1}` and one backward recursion
///   `x_i = w_i − α x_{i+1}`, each started by the convergent series of its periodic solution,
///   `w_0 = α Σ_j (−α)^j d_{−j} / (1 − (−α)^n)` (indices mod n). Both recursions damp errors
///   by `α` per step, so the solve is backward stable. Also correct for n = 1 and 2, where the
///   shifted neighbours coincide.
///
/// `rhs` is called once per index in increasing order, except that the cyclic case first
/// reads up to [`TOEPLITZ_SERIES`] entries from the end. Returns `false` (leaving `out`
/// unspecified) if `q < 3` or `q` is not finite.
pub(crate) fn solve_symmetric_toeplitz_into<T: Lin>(
    q: f64,
    cyclic: bool,
    n: usize,
    rhs: impl Fn(usize) -> T,
    out: &mut Vec<T>,
    mut finish: impl FnMut(T) -> T,
) -> bool {
    if !(q >= 3.0 && q.is_finite()) {
        return false;
    }
    if n == 0 {
        return true;
    }
    let base = out.len();
    out.reserve(n);
    if cyclic {
        // (q − √(q² − 4))/2 without its cancellation for large q.
        let alpha = 2.0 / (q + (q * q - 4.0).sqrt());
        let terms = n.min(TOEPLITZ_SERIES);
        let denom = 1.0 - (-alpha).powi(n.min(i32::MAX as usize) as i32);
        // Forward: w_i + α w_{i−1} = α d_i, periodic.
        let mut series = T::ZERO;
        let mut f = 1.0;
        for j in 0..terms {
            series = series.add_scaled(rhs((n - j) % n), f);
            f *= -alpha;
        }
        let mut prev = series.scaled(alpha / denom);
        out.push(prev);
        for i in 1..n {
            prev = rhs(i).add_scaled(prev, -1.0).scaled(alpha);
            out.push(prev);
        }
        // Backward: x_i + α x_{i+1} = w_i, periodic.
        let w = &mut out[base..];
        let mut series = T::ZERO;
        let mut f = 1.0;
        for j in 0..terms {
            series = series.add_scaled(w[(n - 1 + j) % n], f);
            f *= -alpha;
        }
        let mut next = series.scaled(1.0 / denom);
        w[n - 1] = finish(next);
        for wi in w[..n - 1].iter_mut().rev() {
            next = wi.add_scaled(next, -alpha);
            *wi = finish(next);
        }
        return true;
    }
    // Thomas: multipliers m_i = 1 / (q − m_{i−1}), kept until they stop changing.
    let mut m = [0.0; TOEPLITZ_PREFIX];
    m[0] = 1.0 / q;
    let mut settled = TOEPLITZ_PREFIX;
    for i in 1..TOEPLITZ_PREFIX.min(n) {
        m[i] = 1.0 / (q - m[i - 1]);
        if m[i] == m[i - 1] {
            settled = i + 1;
            break;
        }
    }
    let last = settled.min(n) - 1;
    let mult = |i: usize| m[i.min(last)];
    let mut prev = T::ZERO;
    for i in 0..n {
        prev = rhs(i).add_scaled(prev, -1.0).scaled(mult(i));
        out.push(prev);
    }
    let y = &mut out[base..];
    let mut next = y[n - 1];
    y[n - 1] = finish(next);
    for i in (0..n - 1).rev() {
        next = y[i].add_scaled(next, -mult(i));
        y[i] = finish(next);
    }
    true
}
#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::DenseLu;

    #[test]
    fn symmetric_toeplitz_matches_dense() {
        let mut v = 0.41;
        for q in [3.0, 4.0, 6.0, 1e6] {
            for n in [1usize, 2, 3, 4, 5, 17, 70, 130] {
                for cyclic in [false, true] {
                    let mut dense = DenseLu::default();
                    dense.reset(n);
                    for i in 0..n {
                        dense.add(i, i, q);
                        if i > 0 || cyclic {
                            dense.add(i, (i + n - 1) % n, 1.0);
                        }
                        if i + 1 < n || cyclic {
                            dense.add(i, (i + 1) % n, 1.0);
                        }
                    }
                    assert!(dense.factor());
                    let d: Vec<[f64; 2]> = (0..n)
                        .map(|_| {
                            v = (v * 3.7 + 0.13) % 1.0;
                            [v - 0.5, (v * 7.0) % 1.0]
                        })
                        .collect();
                    let mut x = d.clone();
                    assert!(solve_symmetric_toeplitz(q, &mut x, cyclic));
                    for k in 0..2 {
                        let mut col: Vec<f64> = d.iter().map(|p| p[k]).collect();
                        dense.solve(&mut col);
                        for i in 0..n {
                            let err = (x[i][k] - col[i]).abs();
                            assert!(err < 1e-15, "q={q} n={n} cyclic={cyclic}: {err:e}");
                        }
                    }
                }
            }
        }
        let mut d = [[1.0]];
        assert!(!solve_symmetric_toeplitz(2.5, &mut d, true));
        assert!(!solve_symmetric_toeplitz(f64::NAN, &mut d, false));
    }
}
