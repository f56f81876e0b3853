//! Dense LU with partial pivoting ([`DenseLu`]), for small systems and Schur complements.

use super::pivot;

/// A dense matrix factored by LU with partial pivoting.
#[derive(Clone, Debug, Default)]
pub(crate) struct DenseLu {
    n: usize,
    a: Vec<f64>,
    piv: Vec<usize>,
}

impl DenseLu {
    /// Reset to an `n × n` zero matrix, reusing storage.
    pub(crate) fn reset(&mut self, n: usize) {
        self.n = n;
        self.a.clear();
        self.a.resize(n * n, 0.0);
        self.piv.clear();
        self.piv.resize(n, 0);
    }

    /// Add `v` to the entry `(i, j)`.
    #[inline]
    pub(crate) fn add(&mut self, i: usize, j: usize, v: f64) {
        self.a[i * self.n + j] += v;
    }

    /// Row `i`, to add to.
    #[inline]
    pub(crate) fn row_mut(&mut self, i: usize) -> &mut [f64] {
        &mut self.a[i * self.n..(i + 1) * self.n]
    }

    /// Factor in place. Returns `false` if a pivot is zero or not finite.
    pub(crate) fn factor(&mut self) -> bool {
        // The orders of the small κ/εκ systems (blocks of 3 unknowns in 2D, 4 in 3D) get
        // kernels with the order known at compile time; the arithmetic is the same.
        match self.n {
            3 => self.factor_fixed::<3>(),
            4 => self.factor_fixed::<4>(),
            6 => self.factor_fixed::<6>(),
            8 => self.factor_fixed::<8>(),
            9 => self.factor_fixed::<9>(),
            12 => self.factor_fixed::<12>(),
            15 => self.factor_fixed::<15>(),
            16 => self.factor_fixed::<16>(),
            _ => self.factor_general(),
        }
    }

    /// [`DenseLu::factor`] with the order `N` known at compile time.
    fn factor_fixed<const N: usize>(&mut self) -> bool {
        debug_assert_eq!(self.n, N);
        let a = &mut self.a[..N * N];
        for k in 0..N {
            let below = (k + 1..N).map(|i| (i, a[i * N + k]));
            let Some(p) = pivot((k, a[k * N + k]), below) else {
                return false;
            };
            self.piv[k] = p;
            if p != k {
                for j in k..N {
                    a.swap(k * N + j, p * N + j);
                }
            }
            let inv = 1.0 / a[k * N + k];
            let (top, below) = a.split_at_mut((k + 1) * N);
            // The pivot row's active part, zero elsewhere: every row below is updated over
            // its whole (fixed) length, which leaves its multipliers (columns < k) as they
            // are and vectorizes.
            let prow = &top[k * N..(k + 1) * N];
            let pivot_row: [f64; N] = core::array::from_fn(|j| if j > k { prow[j] } else { 0.0 });
            // Once the active part lies in the second half, only that half is updated (a
            // slice of fixed length as well: about a sixth fewer operations in all).
            let half = k + 1 >= N / 2;
            for row in below.chunks_exact_mut(N) {
                let row: &mut [f64; N] = row.try_into().unwrap();
                let f = row[k] * inv;
                if f != 0.0 {
                    if half {
                        for (x, y) in row[N / 2..].iter_mut().zip(&pivot_row[N / 2..]) {
                            *x -= f * y;
                        }
                    } else {
                        for j in 0..N {
                            row[j] -= f * pivot_row[j];
                        }
                    }
                }
                row[k] = f;
            }
        }
        true
    }

    /// [`DenseLu::factor`] for any order.
    fn factor_general(&mut self) -> bool {
        let n = self.n;
        for k in 0..n {
            let below = (k + 1..n).map(|i| (i, self.a[i * n + k]));
            let Some(p) = pivot((k, self.a[k * n + k]), below) else {
                return false;
            };
            self.piv[k] = p;
            if p != k {
                // Swap only the active columns: the multipliers of earlier columns stay, as
                // the interleaved forward substitution in `solve` expects.
                for j in k..n {
                    self.a.swap(k * n + j, p * n + j);
                }
            }
            let inv = 1.0 / self.a[k * n + k];
            // Rows below k, each updated with the pivot row's active part (columns k+1..).
            let (top, below) = self.a.split_at_mut((k + 1) * n);
            let pivot_row = &top[k * n + k + 1..(k + 1) * n];
            for row in below.chunks_exact_mut(n) {
                let f = row[k] * inv;
                row[k] = f;
                if f != 0.0 {
                    for (x, y) in row[k + 1..].iter_mut().zip(pivot_row) {
                        *x -= f * y;
                    }
                }
            }
        }
        true
    }

    /// Solve `A x = b` in place with the factors from [`DenseLu::factor`].
    pub(crate) fn solve(&self, b: &mut [f64]) {
        // The same orders as `factor` get kernels of fixed order; the arithmetic is the same.
        match self.n {
            3 => self.solve_fixed::<3>(b),
            4 => self.solve_fixed::<4>(b),
            6 => self.solve_fixed::<6>(b),
            8 => self.solve_fixed::<8>(b),
            9 => self.solve_fixed::<9>(b),
            12 => self.solve_fixed::<12>(b),
            15 => self.solve_fixed::<15>(b),
            16 => self.solve_fixed::<16>(b),
            _ => self.solve_general(b),
        }
    }

    /// [`DenseLu::solve`] with the order `N` known at compile time.
    fn solve_fixed<const N: usize>(&self, b: &mut [f64]) {
        debug_assert_eq!(self.n, N);
        let b: &mut [f64; N] = b.try_into().unwrap();
        let piv: &[usize; N] = self.piv[..N].try_into().unwrap();
        let a = &self.a[..N * N];
        for k in 0..N {
            b.swap(k, piv[k]);
            let bk = b[k];
            for i in k + 1..N {
                b[i] -= a[i * N + k] * bk;
            }
        }
        for (k, row) in a.chunks_exact(N).enumerate().rev() {
            let row: &[f64; N] = row.try_into().unwrap();
            // As in `solve_general`: the latest unknown enters the sum last.
            let mut s = -0.0;
            for j in (k + 1..N).rev() {
                s += row[j] * b[j];
            }
            b[k] = (b[k] - s) * (1.0 / row[k]);
        }
    }

    /// [`DenseLu::solve`] for any order.
    fn solve_general(&self, b: &mut [f64]) {
        let n = self.n;
        for k in 0..n {
            b.swap(k, self.piv[k]);
            let bk = b[k];
            for (i, bi) in b.iter_mut().enumerate().skip(k + 1) {
                *bi -= self.a[i * n + k] * bk;
            }
        }
        for k in (0..n).rev() {
            let row = &self.a[k * n + k + 1..(k + 1) * n];
            // Summed from the far end: the unknown solved just before (`b[k + 1]`) enters
            // last, so the dependency chain between rows is one multiply-add, not `n - k`.
            let s: f64 = row.iter().zip(&b[k + 1..]).rev().map(|(a, x)| a * x).sum();
            b[k] = (b[k] - s) * (1.0 / self.a[k * n + k]);
        }
    }
}
#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::testing::lcg;

    #[test]
    fn dense_lu_solves_at_every_order() {
        // Matrices that need row swaps (small diagonal), with a zero column below the
        // diagonal.
        let mut seed = 5;
        for n in 1..=26 {
            let mut lu = DenseLu::default();
            lu.reset(n);
            let mut a = vec![0.0; n * n];
            for i in 0..n {
                for j in 0..n {
                    let v = if j == 1 && i > 1 { 0.0 } else { lcg(&mut seed) };
                    a[i * n + j] = v + if i == j { 1e-3 } else { 0.0 };
                    lu.add(i, j, a[i * n + j]);
                }
            }
            let rhs: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
            assert!(lu.factor(), "order {n}");
            let mut x = rhs.clone();
            lu.solve(&mut x);
            for i in 0..n {
                let ax: f64 = (0..n).map(|j| a[i * n + j] * x[j]).sum();
                assert!(
                    (ax - rhs[i]).abs() < 1e-9,
                    "order {n}, row {i}: {ax} vs {}",
                    rhs[i]
                );
            }
        }
        // Singular (a zero column) and non-finite matrices are refused at every order.
        for n in [3, 9, 24] {
            let mut lu = DenseLu::default();
            lu.reset(n);
            for i in 0..n {
                for j in 1..n {
                    lu.add(i, j, 1.0 + (i * j) as f64);
                }
            }
            assert!(!lu.factor(), "order {n}");
            lu.reset(n);
            for i in 0..n {
                lu.add(i, i, if i == n / 2 { f64::NAN } else { 1.0 });
            }
            assert!(!lu.factor(), "order {n}");
        }
    }
}
