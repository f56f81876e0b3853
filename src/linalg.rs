// `!(x > 0.0)` is meant: it is also true for NaN, which must count as a zero pivot.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
//! Small direct solvers: banded and dense LU with partial pivoting, a bordered solve for
//! cyclic (wrap-around) banded systems, and (cyclic) tridiagonal systems with vector
//! right-hand sides. All buffers are owned by the structs and reused between solves.

/// Partial pivoting: the index of the candidate of largest magnitude (the first of equals,
/// `first` winning ties), or `None` if that magnitude is zero or not finite.
#[inline(always)]
fn pivot(first: (usize, f64), rest: impl Iterator<Item = (usize, f64)>) -> Option<usize> {
    let (mut p, mut best) = (first.0, first.1.abs());
    for (i, v) in rest {
        let v = v.abs();
        if v > best {
            best = v;
            p = i;
        }
    }
    (best > 0.0 && best.is_finite()).then_some(p)
}

/// A banded matrix with `kl` sub- and `ku` super-diagonals, factored in place by LU with
/// partial pivoting (as LAPACK's `dgbtf2`). Row `i` stores the columns
/// `i - kl ..= i + kl + ku`; the extra `kl` columns hold the fill-in of pivoting.
#[derive(Clone, Debug, Default)]
pub(crate) struct BandLu {
    n: usize,
    kl: usize,
    ku: usize,
    w: usize,
    a: Vec<f64>,
    /// The multipliers of each column, contiguous (`kl` per column), for the forward pass.
    l: Vec<f64>,
    piv: Vec<usize>,
}

impl BandLu {
    /// Reset to an `n × n` zero matrix with the given bandwidths, reusing storage.
    pub(crate) fn reset(&mut self, n: usize, kl: usize, ku: usize) {
        self.n = n;
        self.kl = kl;
        self.ku = ku;
        self.w = 2 * kl + ku + 1;
        self.a.clear();
        self.a.resize(n * self.w, 0.0);
        self.l.clear();
        self.l.resize(n * kl, 0.0);
        self.piv.clear();
        self.piv.resize(n, 0);
    }

    #[inline]
    fn idx(&self, i: usize, j: usize) -> usize {
        debug_assert!(
            j + self.kl >= i && j <= i + self.kl + self.ku,
            "outside the band"
        );
        i * self.w + (j + self.kl - i)
    }

    /// Add `v` to the entry `(i, j)`, which must lie within the band.
    #[inline]
    pub(crate) fn add(&mut self, i: usize, j: usize, v: f64) {
        let k = self.idx(i, j);
        self.a[k] += v;
    }

    /// Factor in place. Returns `false` if a pivot is zero or not finite.
    ///
    /// Each row of `U` is stored divided by its pivot, with the pivot's reciprocal in its
    /// place: the backward substitution then takes one multiply-add per row on its
    /// dependency chain (`x_k = b_k / u_kk - Σ (u_kj / u_kk) x_j`).
    pub(crate) fn factor(&mut self) -> bool {
        let ok = match (self.kl, self.ku) {
            (5, 5) => self.factor_fixed::<5, 10, 16>(),
            (7, 7) => self.factor_fixed::<7, 14, 22>(),
            _ => self.factor_general(),
        };
        if ok {
            self.scale_rows();
        }
        ok
    }

    /// Divide each row of the factor `U` by its pivot, which is replaced by its reciprocal.
    fn scale_rows(&mut self) {
        let kl = self.kl;
        for row in self.a.chunks_exact_mut(self.w) {
            let inv = 1.0 / row[kl];
            row[kl] = inv;
            for x in &mut row[kl + 1..] {
                *x *= inv;
            }
        }
    }

    /// [`BandLu::factor`] with the bandwidths known at compile time (`U = kl + ku`, the
    /// width of `U` above its diagonal; rows of `W = 2 kl + ku + 1` entries). The last `U`
    /// steps, where the band is cut off by the matrix end, take the general step.
    fn factor_fixed<const KL: usize, const U: usize, const W: usize>(&mut self) -> bool {
        let n = self.n;
        debug_assert!(self.kl == KL && self.kl + self.ku == U && self.w == W);
        let full = n.saturating_sub(U);
        for k in 0..full {
            let (head, tail) = self.a.split_at_mut((k + 1) * W);
            let prow = &mut head[k * W..];
            // Row `k + 1 + d` holds column `k` at offset `KL - 1 - d`.
            let below = tail.chunks_exact(W).take(KL).enumerate();
            let Some(p) = pivot(
                (0, prow[KL]),
                below.map(|(d, row)| (d + 1, row[KL - 1 - d])),
            ) else {
                return false;
            };
            self.piv[k] = k + p;
            if p != 0 {
                let other = &mut tail[(p - 1) * W..p * W];
                for d in 0..=U {
                    core::mem::swap(&mut prow[KL + d], &mut other[KL - p + d]);
                }
            }
            let inv = 1.0 / prow[KL];
            let pivot: [f64; U] = prow[KL + 1..KL + 1 + U].try_into().unwrap();
            let col = &mut self.l[k * KL..(k + 1) * KL];
            for (d, row) in tail.chunks_exact_mut(W).take(KL).enumerate() {
                let off = KL - 1 - d;
                let f = row[off] * inv;
                row[off] = f;
                col[d] = f;
                if f != 0.0 {
                    for c in 0..U {
                        row[off + 1 + c] -= f * pivot[c];
                    }
                }
            }
        }
        (full..n).all(|k| self.factor_step(k))
    }

    /// [`BandLu::factor`] for any bandwidths.
    fn factor_general(&mut self) -> bool {
        (0..self.n).all(|k| self.factor_step(k))
    }

    /// Step `k` of the factorization: pivot search in column `k`, row swap, elimination
    /// below. `false` if the pivot is zero or not finite.
    fn factor_step(&mut self, k: usize) -> bool {
        let (n, kl, w) = (self.n, self.kl, self.w);
        let imax = (k + kl).min(n - 1);
        let len = (k + kl + self.ku).min(n - 1) - k + 1;
        let below = (k + 1..=imax).map(|i| (i, self.a[i * w + kl + k - i]));
        let Some(p) = pivot((k, self.a[k * w + kl]), below) else {
            return false;
        };
        self.piv[k] = p;
        // Row k's columns k.. start at offset kl; row i's at kl + k - i.
        let rk = k * w + kl;
        if p != k {
            let rp = p * w + kl + k - p;
            for d in 0..len {
                self.a.swap(rk + d, rp + d);
            }
        }
        let inv = 1.0 / self.a[rk];
        for i in k + 1..=imax {
            let ri = i * w + kl + k - i;
            let f = self.a[ri] * inv;
            self.a[ri] = f;
            self.l[k * kl + (i - k - 1)] = f;
            if f != 0.0 {
                let (head, tail) = self.a.split_at_mut(ri);
                let pivot_row = &head[rk + 1..rk + len];
                for (x, y) in tail[1..len].iter_mut().zip(pivot_row) {
                    *x -= f * y;
                }
            }
        }
        true
    }

    /// Solve `A x = b` in place with the factors from [`BandLu::factor`].
    pub(crate) fn solve(&self, b: &mut [f64]) {
        // The bandwidths of the κ/εκ solver's systems (2D and 3D) get unrolled kernels.
        match (self.kl, self.ku) {
            (5, 5) => self.solve_fixed::<5, 10, 16>(b),
            (7, 7) => self.solve_fixed::<7, 14, 22>(b),
            _ => self.solve_general(b),
        }
    }

    /// [`BandLu::solve`] with the bandwidths known at compile time: `KL` below the diagonal
    /// and `U = kl + ku` above it in the factor `U`, rows of `W = 2 kl + ku + 1` entries.
    fn solve_fixed<const KL: usize, const U: usize, const W: usize>(&self, b: &mut [f64]) {
        let n = self.n;
        debug_assert!(self.kl == KL && self.kl + self.ku == U && self.w == W);
        debug_assert_eq!(b.len(), n);
        // Forward: `L y = P b`, one column of multipliers per step.
        let full = n.saturating_sub(KL);
        for (k, (col, &p)) in self.l.chunks_exact(KL).zip(&self.piv).enumerate() {
            if p != k {
                b.swap(k, p);
            }
            let bk = b[k];
            if k < full {
                let below = &mut b[k + 1..k + 1 + KL];
                for i in 0..KL {
                    below[i] -= col[i] * bk;
                }
            } else {
                for (bi, li) in b[k + 1..].iter_mut().zip(col) {
                    *bi -= li * bk;
                }
            }
        }
        // Backward: `U x = y`; row `k` holds `U[k][k..=k+U]` from offset `KL`, divided by
        // the pivot, whose reciprocal is at `KL`.
        for (k, row) in self.a.chunks_exact(W).enumerate().rev() {
            b[k] = if k + U < n {
                let x = &b[k + 1..k + 1 + U];
                // `x[0]` was solved for just before: its product is subtracted last, so the
                // chain from one row's solution to the next is one multiply and one
                // subtraction, and the rest (two partial sums) runs ahead.
                let (mut s0, mut s1) = (b[k] * row[KL], 0.0);
                let mut i = 1;
                while i + 1 < U {
                    s0 -= row[KL + 1 + i] * x[i];
                    s1 -= row[KL + 2 + i] * x[i + 1];
                    i += 2;
                }
                if i < U {
                    s0 -= row[KL + 1 + i] * x[i];
                }
                (s0 + s1) - row[KL + 1] * x[0]
            } else {
                let s: f64 = row[KL + 1..]
                    .iter()
                    .zip(&b[k + 1..])
                    .rev()
                    .map(|(a, x)| a * x)
                    .sum();
                b[k] * row[KL] - s
            };
        }
    }

    /// [`BandLu::solve`] for any bandwidths.
    fn solve_general(&self, b: &mut [f64]) {
        let (n, kl, w) = (self.n, self.kl, self.w);
        for k in 0..n {
            let p = self.piv[k];
            if p != k {
                b.swap(k, p);
            }
            let bk = b[k];
            if bk != 0.0 {
                let m = kl.min(n - 1 - k);
                let col = &self.l[k * kl..k * kl + m];
                for (bi, li) in b[k + 1..k + 1 + m].iter_mut().zip(col) {
                    *bi -= li * bk;
                }
            }
        }
        for k in (0..n).rev() {
            let rk = k * w + kl;
            let len = (k + kl + self.ku).min(n - 1) - k + 1;
            let row = &self.a[rk + 1..rk + len];
            // As in `DenseLu::solve`: the latest unknown enters the sum last.
            let s: f64 = row
                .iter()
                .zip(&b[k + 1..k + len])
                .rev()
                .map(|(a, x)| a * x)
                .sum();
            b[k] = b[k] * self.a[rk] - s;
        }
    }

    /// Solve `A X = B` in place for `m` right-hand sides at once, `b` row-major (`n × m`):
    /// one pass over the factors for all of them.
    ///
    /// The right-hand sides here are border columns (the couplings of a cyclic band, or of
    /// a window's edges), nonzero in a few rows only; their solutions decay geometrically
    /// away from those rows, each column at its own rate. Entries below [`SPIKE_FLUSH`] of
    /// the largest right-hand-side entry are set to zero as they are computed, in both
    /// passes, and a zero row is skipped in the forward one: on a long band the decay would
    /// otherwise run through the subnormal range, where x86 arithmetic is many times slower
    /// (the 100 000-point εκ loop took 3.8 times as long). An infinite right-hand side
    /// flushes nothing, so that it reaches the solution as it would without the flush.
    pub(crate) fn solve_many(&self, b: &mut [f64], m: usize) {
        let big = b.iter().fold(0.0_f64, |big, v| big.max(v.abs()));
        let tiny = if big.is_finite() {
            big * SPIKE_FLUSH
        } else {
            0.0
        };
        match (self.kl, self.ku, m) {
            (5, 5, 6) => self.solve_many_fixed::<5, 10, 6>(b, tiny),
            (5, 5, 9) => self.solve_many_fixed::<5, 10, 9>(b, tiny),
            (7, 7, 8) => self.solve_many_fixed::<7, 14, 8>(b, tiny),
            (7, 7, 12) => self.solve_many_fixed::<7, 14, 12>(b, tiny),
            _ => self.solve_many_general(b, m, tiny),
        }
    }

    /// [`BandLu::solve_many`] with the bandwidths (as in [`BandLu::solve_fixed`]) and the
    /// number of right-hand sides `M` known at compile time.
    fn solve_many_fixed<const KL: usize, const U: usize, const M: usize>(
        &self,
        b: &mut [f64],
        tiny: f64,
    ) {
        let (n, w) = (self.n, self.w);
        debug_assert!(self.kl == KL && self.kl + self.ku == U);
        debug_assert_eq!(b.len(), n * M);
        for k in 0..n {
            let p = self.piv[k];
            if p != k {
                for r in 0..M {
                    b.swap(k * M + r, p * M + r);
                }
            }
            let (head, tail) = b.split_at_mut((k + 1) * M);
            let bk: &mut [f64; M] = (&mut head[k * M..]).try_into().unwrap();
            if flush(bk, tiny) {
                continue;
            }
            let bk = *bk;
            let rows = KL.min(n - 1 - k);
            let col = &self.l[k * KL..k * KL + rows];
            for (bi, &li) in tail.chunks_exact_mut(M).zip(col) {
                let bi: &mut [f64; M] = bi.try_into().unwrap();
                for r in 0..M {
                    bi[r] -= li * bk[r];
                }
            }
        }
        for k in (0..n).rev() {
            let rk = k * w + KL;
            let len = U.min(n - 1 - k);
            let (head, tail) = b.split_at_mut((k + 1) * M);
            let mut acc: [f64; M] = head[k * M..].try_into().unwrap();
            let inv = self.a[rk];
            for v in &mut acc {
                *v *= inv;
            }
            // The row solved just before (`i = 0`) comes last, off the other products'
            // dependency chain (as in [`BandLu::solve_fixed`]).
            let row = &self.a[rk + 1..rk + 1 + len];
            for (&a, bi) in row.iter().zip(tail.chunks_exact(M)).skip(1) {
                let bi: &[f64; M] = bi.try_into().unwrap();
                for r in 0..M {
                    acc[r] -= a * bi[r];
                }
            }
            if let (Some(&a), Some(bi)) = (row.first(), tail.chunks_exact(M).next()) {
                let bi: &[f64; M] = bi.try_into().unwrap();
                for r in 0..M {
                    acc[r] -= a * bi[r];
                }
            }
            flush(&mut acc, tiny);
            head[k * M..].copy_from_slice(&acc);
        }
    }

    /// [`BandLu::solve_many`] for any bandwidths and number of right-hand sides.
    fn solve_many_general(&self, b: &mut [f64], m: usize, tiny: f64) {
        let (n, kl, w) = (self.n, self.kl, self.w);
        debug_assert_eq!(b.len(), n * m);
        for k in 0..n {
            let p = self.piv[k];
            if p != k {
                for r in 0..m {
                    b.swap(k * m + r, p * m + r);
                }
            }
            let (head, tail) = b.split_at_mut((k + 1) * m);
            let bk = &mut head[k * m..];
            if flush(bk, tiny) {
                continue;
            }
            let bk = &*bk;
            let rows = kl.min(n - 1 - k);
            let col = &self.l[k * kl..k * kl + rows];
            for (bi, &li) in tail.chunks_exact_mut(m).zip(col) {
                for (x, y) in bi.iter_mut().zip(bk) {
                    *x -= li * y;
                }
            }
        }
        for k in (0..n).rev() {
            let rk = k * w + kl;
            let len = (k + kl + self.ku).min(n - 1) - k + 1;
            let (head, tail) = b.split_at_mut((k + 1) * m);
            let bk = &mut head[k * m..];
            let inv = self.a[rk];
            for x in bk.iter_mut() {
                *x *= inv;
            }
            for (&a, bi) in self.a[rk + 1..rk + len].iter().zip(tail.chunks_exact(m)) {
                if a != 0.0 {
                    for (x, y) in bk.iter_mut().zip(bi) {
                        *x -= a * y;
                    }
                }
            }
            flush(bk, tiny);
        }
    }
}

/// The fraction of a right-hand side's largest entry below which [`BandLu::solve_many`]
/// sets an entry of its solution to zero. Far below rounding (2⁻⁵² ≈ 2e-16) for any system
/// whose condition number is below 1e180, and far above the subnormal range (below
/// 2.2e-308) for right-hand sides of any size the solver builds.
const SPIKE_FLUSH: f64 = 1e-200;

/// Set the entries of `row` of magnitude at most `tiny` to zero (a NaN is kept: it must
/// propagate). Returns whether the whole row is zero.
#[inline(always)]
fn flush(row: &mut [f64], tiny: f64) -> bool {
    let mut zero = true;
    for v in row {
        if v.abs() <= tiny {
            *v = 0.0;
        } else {
            zero = false;
        }
    }
    zero
}

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

/// A bordered system `[[A_II, A_IB], [A_BI, A_BB]] x = f` with `A_II` banded and a small
/// dense border of `nb` unknowns: the form that a cyclic banded matrix takes when its last
/// few unknowns are moved to the border. Solved through the Schur complement
/// `S = A_BB - A_BI A_II⁻¹ A_IB`, in `O(n · band · nb)`.
#[derive(Clone, Debug, Default)]
pub(crate) struct BorderedLu {
    ni: usize,
    nb: usize,
    /// `A_II`.
    pub(crate) band: BandLu,
    /// `A_IB`, row-major (`ni` rows of length `nb`); replaced by `A_II⁻¹ A_IB`.
    ib: Vec<f64>,
    /// `A_BI` as triplets `(border row, interior column, value)`.
    bi: Vec<(usize, usize, f64)>,
    /// `A_BB`, replaced by the Schur complement and factored.
    s: DenseLu,
}

impl BorderedLu {
    /// Reset to zero with `ni` banded unknowns (bandwidths `kl`, `ku`) and `nb` border ones.
    pub(crate) fn reset(&mut self, ni: usize, nb: usize, kl: usize, ku: usize) {
        self.ni = ni;
        self.nb = nb;
        self.band.reset(ni, kl, ku);
        self.ib.clear();
        self.ib.resize(ni * nb, 0.0);
        self.bi.clear();
        self.s.reset(nb);
    }

    /// Add `v` to the entry `(i, j)` of the whole matrix (border unknowns come last).
    #[inline]
    pub(crate) fn add(&mut self, i: usize, j: usize, v: f64) {
        let ni = self.ni;
        match (i < ni, j < ni) {
            (true, true) => self.band.add(i, j, v),
            (true, false) => self.ib[i * self.nb + (j - ni)] += v,
            (false, true) => self.bi.push((i - ni, j, v)),
            (false, false) => self.s.add(i - ni, j - ni, v),
        }
    }

    /// Factor. Returns `false` if the system is singular.
    pub(crate) fn factor(&mut self) -> bool {
        if self.ni > 0 && !self.band.factor() {
            return false;
        }
        let nb = self.nb;
        if self.ni > 0 {
            // All border columns in one pass over the band factors.
            self.band.solve_many(&mut self.ib, nb);
        }
        for &(r, c, v) in &self.bi {
            for col in 0..nb {
                self.s.add(r, col, -v * self.ib[c * nb + col]);
            }
        }
        self.s.factor()
    }

    /// Solve in place with the factors from [`BorderedLu::factor`].
    pub(crate) fn solve(&mut self, x: &mut [f64]) {
        let ni = self.ni;
        let (xi, xb) = x.split_at_mut(ni);
        if ni > 0 {
            self.band.solve(xi);
        }
        for &(r, c, v) in &self.bi {
            xb[r] -= v * xi[c];
        }
        self.s.solve(xb);
        subtract_border(xi, &self.ib, xb);
    }
}

/// One of the two banded parts of a [`SplitLu`]: its band, the border columns it touches
/// (`A_PB`, replaced by `A_PP⁻¹ A_PB`) and the border rows' entries in its columns.
#[derive(Clone, Debug, Default)]
struct SplitPart {
    band: BandLu,
    /// First natural index of the part.
    start: usize,
    /// The border columns `c0..c0 + m` this part's rows touch.
    c0: usize,
    m: usize,
    /// `A_PB` restricted to those columns, row-major (`len × m`); `A_PP⁻¹ A_PB` once factored.
    w: Vec<f64>,
    /// `A_BP` as triplets `(border row, column within the part, value)`.
    bp: Vec<(usize, usize, f64)>,
}

impl SplitPart {
    fn reset(&mut self, start: usize, len: usize, (c0, m): (usize, usize), kl: usize, ku: usize) {
        self.band.reset(len, kl, ku);
        self.start = start;
        (self.c0, self.m) = (c0, m);
        self.w.clear();
        self.w.resize(len * m, 0.0);
        self.bp.clear();
    }

    /// Factor the band and solve for the border columns.
    fn factor(&mut self) -> bool {
        if self.band.n == 0 {
            return true;
        }
        if !self.band.factor() {
            return false;
        }
        self.band.solve_many(&mut self.w, self.m);
        true
    }

    /// `x_P -= (A_PP⁻¹ A_PB) x_B`.
    fn back(&self, x: &mut [f64], xb: &[f64]) {
        subtract_border(x, &self.w, &xb[self.c0..self.c0 + self.m]);
    }
}

/// The border index of the natural index `i` of a [`SplitLu`] cut at `cuts` with blocks of
/// `bs`: the separator first, then the last tail block, then the first.
#[inline]
fn border_index([a, b, c]: [usize; 3], bs: usize, i: usize) -> usize {
    if i < b {
        i - a
    } else if i >= c + bs {
        (b - a) + (i - c - bs)
    } else {
        (b - a) + bs + (i - c)
    }
}

/// The rows of one part of a [`SplitLu`], for adding entries (natural indices) in them.
pub(crate) struct SplitRows<'a> {
    part: &'a mut SplitPart,
    cuts: [usize; 3],
    bs: usize,
}

impl SplitRows<'_> {
    /// Add `v` to the entry `(i, j)`; `i` must be a row of this part.
    #[inline]
    pub(crate) fn add(&mut self, i: usize, j: usize, v: f64) {
        let part = &mut *self.part;
        let li = i - part.start;
        debug_assert!(li < part.band.n);
        if j >= part.start && j - part.start < part.band.n {
            part.band.add(li, j - part.start, v);
        } else {
            let bj = border_index(self.cuts, self.bs, j);
            debug_assert!(
                bj >= part.c0 && bj < part.c0 + part.m,
                "outside the part's columns"
            );
            part.w[li * part.m + (bj - part.c0)] += v;
        }
    }
}

/// `x -= W x_B` for a row-major `W` of `x_B.len()` columns: the back substitution of a
/// bordered solve ([`BorderedLu`], [`SplitLu`]).
fn subtract_border(x: &mut [f64], w: &[f64], xb: &[f64]) {
    /// With the border size known at compile time.
    fn fixed<const M: usize>(x: &mut [f64], w: &[f64], xb: &[f64]) {
        let xb: &[f64; M] = xb.try_into().unwrap();
        for (x, y) in x.iter_mut().zip(w.chunks_exact(M)) {
            let mut s = 0.0;
            for r in 0..M {
                s += y[r] * xb[r];
            }
            *x -= s;
        }
    }
    // The border sizes of the κ/εκ systems: two blocks of 3 (2D) or 4 (3D) unknowns, and a
    // split system's nine (2D) or twelve (3D) columns per part.
    match xb.len() {
        0 => {}
        6 => fixed::<6>(x, w, xb),
        8 => fixed::<8>(x, w, xb),
        9 => fixed::<9>(x, w, xb),
        12 => fixed::<12>(x, w, xb),
        m => {
            for (x, y) in x.iter_mut().zip(w.chunks_exact(m)) {
                *x -= y.iter().zip(xb).map(|(y, b)| y * b).sum::<f64>();
            }
        }
    }
}

/// A banded system cut in two by a separator: the unknowns `[0, a)` and `[b, c)` form two
/// banded parts that do not touch each other, and the separator `[a, b)` together with the
/// tail `[c, n)` (the wrap-around of a cyclic band, or nothing) forms a small dense border.
/// In the border's order,
///
/// ```text
/// [ A_11   0     A_1B ] [x_1]   [f_1]
/// [  0    A_22   A_2B ] [x_2] = [f_2]
/// [ A_B1  A_B2   A_BB ] [x_B]   [f_B]
/// ```
///
/// is solved through the Schur complement `S = A_BB − Σ A_Bp A_pp⁻¹ A_pB`, the two parts
/// side by side (on two threads with the `parallel` feature; the arithmetic is the same
/// either way).
///
/// The border is ordered separator, last tail block, first tail block, so that each part's
/// rows touch one contiguous range of border columns: the first part the separator and the
/// last tail block (the cyclic wrap), the second part the separator's second block and the
/// tail.
#[derive(Clone, Debug, Default)]
pub(crate) struct SplitLu {
    cuts: [usize; 3],
    /// Size of a block of unknowns (the tail holds two, the separator two).
    bs: usize,
    parts: [SplitPart; 2],
    s: DenseLu,
    xb: Vec<f64>,
}

impl SplitLu {
    /// Reset to zero: parts `[0, a)` and `[b, c)`, separator `[a, b)` (two blocks of `bs`),
    /// tail `[c, n)` (two blocks or none), bandwidths `kl`, `ku` within the parts.
    pub(crate) fn reset(
        &mut self,
        [a, b, c]: [usize; 3],
        n: usize,
        bs: usize,
        kl: usize,
        ku: usize,
    ) {
        debug_assert!(a <= b && b <= c && c <= n && b - a == 2 * bs);
        debug_assert!(n == c || n - c == 2 * bs);
        self.cuts = [a, b, c];
        self.bs = bs;
        let nb = (b - a) + (n - c);
        let tail = n - c;
        // First part: the separator and the last tail block; second part: the separator's
        // second block and the whole tail.
        let [p0, p1] = &mut self.parts;
        crate::parallel::join(
            || p0.reset(0, a, (0, (b - a) + tail / 2), kl, ku),
            || p1.reset(b, c - b, (bs, nb - bs), kl, ku),
        );
        self.s.reset(nb);
        self.xb.clear();
        self.xb.resize(nb, 0.0);
    }

    /// The border index of the natural index `i` (which must lie in the border).
    #[inline]
    fn border(&self, i: usize) -> usize {
        border_index(self.cuts, self.bs, i)
    }

    /// The two parts, to add their rows side by side (each row of a part touches only its
    /// own part and the border).
    pub(crate) fn halves(&mut self) -> [SplitRows<'_>; 2] {
        let (cuts, bs) = (self.cuts, self.bs);
        let [p0, p1] = &mut self.parts;
        [p0, p1].map(|part| SplitRows { part, cuts, bs })
    }

    /// Which part holds the natural index `i`, if any.
    #[inline]
    fn part(&self, i: usize) -> Option<usize> {
        let [a, b, c] = self.cuts;
        if i < a {
            Some(0)
        } else if i >= b && i < c {
            Some(1)
        } else {
            None
        }
    }

    /// Add `v` to the entry `(i, j)` of the whole matrix (natural indices).
    #[inline]
    pub(crate) fn add(&mut self, i: usize, j: usize, v: f64) {
        match (self.part(i), self.part(j)) {
            (Some(p), Some(q)) => {
                debug_assert_eq!(p, q, "the parts do not touch each other");
                let part = &mut self.parts[p];
                part.band.add(i - part.start, j - part.start, v);
            }
            (Some(p), None) => {
                let bj = self.border(j);
                let part = &mut self.parts[p];
                debug_assert!(
                    bj >= part.c0 && bj < part.c0 + part.m,
                    "outside the part's columns"
                );
                let k = (i - part.start) * part.m + (bj - part.c0);
                part.w[k] += v;
            }
            (None, Some(q)) => {
                let bi = self.border(i);
                let part = &mut self.parts[q];
                part.bp.push((bi, j - part.start, v));
            }
            (None, None) => {
                let (bi, bj) = (self.border(i), self.border(j));
                self.s.add(bi, bj, v);
            }
        }
    }

    /// Factor (the two parts side by side). Returns `false` if the system is singular.
    pub(crate) fn factor(&mut self) -> bool {
        let [p0, p1] = &mut self.parts;
        let (ok0, ok1) = crate::parallel::join(|| p0.factor(), || p1.factor());
        if !(ok0 && ok1) {
            return false;
        }
        for part in &self.parts {
            let (c0, m) = (part.c0, part.m);
            for &(r, c, v) in &part.bp {
                for (k, y) in part.w[c * m..(c + 1) * m].iter().enumerate() {
                    self.s.add(r, c0 + k, -v * y);
                }
            }
        }
        self.s.factor()
    }

    /// Solve in place (natural order) with the factors from [`SplitLu::factor`].
    pub(crate) fn solve(&mut self, x: &mut [f64]) {
        let [a, b, c] = self.cuts;
        let (x0, rest) = x.split_at_mut(a);
        let (xs, rest) = rest.split_at_mut(b - a);
        let (x1, xt) = rest.split_at_mut(c - b);
        let [p0, p1] = &self.parts;
        crate::parallel::join(
            || {
                if !x0.is_empty() {
                    p0.band.solve(x0)
                }
            },
            || {
                if !x1.is_empty() {
                    p1.band.solve(x1)
                }
            },
        );
        // The border's right-hand side, in border order.
        let bs = self.bs;
        let ns = b - a;
        let xb = &mut self.xb;
        xb[..ns].copy_from_slice(xs);
        if !xt.is_empty() {
            xb[ns..ns + bs].copy_from_slice(&xt[bs..]);
            xb[ns + bs..].copy_from_slice(&xt[..bs]);
        }
        for (part, xp) in [(p0, &*x0), (p1, &*x1)] {
            for &(r, c, v) in &part.bp {
                xb[r] -= v * xp[c];
            }
        }
        self.s.solve(xb);
        let xb = &*xb;
        crate::parallel::join(|| p0.back(x0, xb), || p1.back(x1, xb));
        xs.copy_from_slice(&xb[..ns]);
        if !xt.is_empty() {
            xt[bs..].copy_from_slice(&xb[ns..ns + bs]);
            xt[..bs].copy_from_slice(&xb[ns + bs..]);
        }
    }
}

/// Solve the tridiagonal system `a_i x_{i-1} + b_i x_i + c_i x_{i+1} = d_i` (with `a_0` and
/// `c_{n-1}` ignored), or its cyclic version where `a_0` couples to `x_{n-1}` and `c_{n-1}`
/// to `x_0` (Sherman–Morrison). `d` is overwritten with the solution. Returns `false` if a
/// pivot vanishes.
pub(crate) fn solve_tridiagonal<const D: usize>(
    a: &[f64],
    b: &[f64],
    c: &[f64],
    d: &mut [[f64; D]],
    cyclic: bool,
    scratch: &mut TriScratch,
) -> bool {
    let n = d.len();
    if cyclic && n == 3 {
        return cyclic3(a, b, c, d);
    }
    let TriScratch { cp, cp2, u } = scratch;
    // Every multiplier is written before it is read.
    cp.resize(n, 0.0);
    if !cyclic || n < 3 {
        return thomas(a, b, c, d, cp, None);
    }
    // Sherman–Morrison: A = T + u vᵀ with u = (γ, 0, …, 0, c_{n-1}), v = (1, 0, …, 0, a_0/γ).
    let gamma = -b[0];
    let b0 = b[0] - gamma;
    let bn = b[n - 1] - c[n - 1] * a[0] / gamma;
    u.clear();
    u.resize(n, [0.0]);
    u[0] = [gamma];
    u[n - 1] = [c[n - 1]];
    // Solve T z = u and T y = d (long systems side by side: each solve is one chain of
    // divisions).
    let ends = Some((b0, bn));
    let ok = if n >= PARALLEL_TRIDIAGONAL {
        cp2.resize(n, 0.0);
        let (ok_u, ok_d) = crate::parallel::join(
            || thomas(a, b, c, u, cp2, ends),
            || thomas(a, b, c, d, cp, ends),
        );
        ok_u && ok_d
    } else {
        let ok = thomas(a, b, c, u, cp, ends);
        ok & thomas(a, b, c, d, cp, ends)
    };
    if !ok {
        return false;
    }
    let fact_den = 1.0 + u[0][0] + a[0] / gamma * u[n - 1][0];
    if !(fact_den.abs() > 0.0) {
        return false;
    }
    let mut num = [0.0; D];
    for (k, x) in num.iter_mut().enumerate() {
        *x = d[0][k] + a[0] / gamma * d[n - 1][k];
    }
    for (di, &[ui]) in d.iter_mut().zip(u.iter()) {
        for k in 0..D {
            di[k] -= num[k] / fact_den * ui;
        }
    }
    true
}

/// The cyclic system of order 3, a full 3 × 3 matrix (row `i` is `a_i`, `b_i`, `c_i` on the
/// columns `i - 1`, `i`, `i + 1` modulo 3), by Gaussian elimination with partial pivoting:
/// about 230 instructions against 540 for the two Thomas passes and the Sherman–Morrison
/// correction (callgrind). `false` if a pivot vanishes or is not finite.
// Index loops of fixed length: the compiler unrolls them fully (the iterator form measured
// about 8 000 instructions more on the bear drawing).
#[allow(clippy::needless_range_loop)]
fn cyclic3<const D: usize>(a: &[f64], b: &[f64], c: &[f64], d: &mut [[f64; D]]) -> bool {
    let mut m = [[b[0], c[0], a[0]], [a[1], b[1], c[1]], [c[2], a[2], b[2]]];
    let mut x: [[f64; D]; 3] = [d[0], d[1], d[2]];
    for k in 0..3 {
        let below = (k + 1..3).map(|i| (i, m[i][k]));
        let Some(p) = pivot((k, m[k][k]), below) else {
            return false;
        };
        m.swap(k, p);
        x.swap(k, p);
        let inv = 1.0 / m[k][k];
        for i in k + 1..3 {
            let f = m[i][k] * inv;
            for j in k + 1..3 {
                m[i][j] -= f * m[k][j];
            }
            for q in 0..D {
                x[i][q] -= f * x[k][q];
            }
        }
    }
    for k in (0..3).rev() {
        let inv = 1.0 / m[k][k];
        for q in 0..D {
            let mut s = x[k][q];
            for j in k + 1..3 {
                s -= m[k][j] * x[j][q];
            }
            x[k][q] = s * inv;
        }
    }
    d[..3].copy_from_slice(&x);
    true
}

/// Buffers of [`solve_tridiagonal`], reused between solves.
#[derive(Clone, Debug, Default)]
pub(crate) struct TriScratch {
    cp: Vec<f64>,
    /// The multipliers of the second of two solves run side by side.
    cp2: Vec<f64>,
    u: Vec<[f64; 1]>,
}

/// Cyclic tridiagonal systems of this order or more solve their two Thomas passes side by
/// side.
const PARALLEL_TRIDIAGONAL: usize = 2048;

/// Thomas algorithm with vector right-hand sides; `ends` overrides `b_0` and `b_{n-1}`.
fn thomas<const D: usize>(
    a: &[f64],
    b: &[f64],
    c: &[f64],
    d: &mut [[f64; D]],
    cp: &mut [f64],
    ends: Option<(f64, f64)>,
) -> bool {
    let n = d.len();
    let bi = |i: usize| match ends {
        Some((b0, _)) if i == 0 => b0,
        Some((_, bn)) if i == n - 1 => bn,
        _ => b[i],
    };
    let mut den = bi(0);
    if !(den.abs() > 0.0) {
        return false;
    }
    cp[0] = c[0] / den;
    for x in d[0].iter_mut() {
        *x /= den;
    }
    for i in 1..n {
        den = bi(i) - a[i] * cp[i - 1];
        if !(den.abs() > 0.0) {
            return false;
        }
        cp[i] = c[i] / den;
        let prev = d[i - 1];
        for k in 0..D {
            d[i][k] = (d[i][k] - a[i] * prev[k]) / den;
        }
    }
    for i in (0..n - 1).rev() {
        let next = d[i + 1];
        for k in 0..D {
            d[i][k] -= cp[i] * next[k];
        }
    }
    true
}

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

    /// `solve` and the dense LU give the same solution for `rhs`.
    pub(super) fn assert_same_solution(
        mut solve: impl FnMut(&mut [f64]),
        dense: &DenseLu,
        rhs: &[f64],
    ) {
        let (mut x1, mut x2) = (rhs.to_vec(), rhs.to_vec());
        solve(&mut x1);
        dense.solve(&mut x2);
        for (a, b) in x1.iter().zip(&x2) {
            assert!((a - b).abs() < 1e-9 * (1.0 + b.abs()), "{a} vs {b}");
        }
    }

    /// A deterministic pseudo-random sequence for tests.
    fn lcg(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((*seed >> 11) as f64) / ((1u64 << 53) as f64) - 0.5
    }

    #[test]
    fn band_lu_matches_dense_lu() {
        let mut seed = 7;
        let (n, kl, ku) = (13, 3, 4);
        let mut band = BandLu::default();
        let mut dense = DenseLu::default();
        band.reset(n, kl, ku);
        dense.reset(n);
        for i in 0..n {
            for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                let v = lcg(&mut seed);
                band.add(i, j, v);
                dense.add(i, j, v);
            }
        }
        let rhs: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
        assert!(band.factor() && dense.factor());
        assert_same_solution(|x| band.solve(x), &dense, &rhs);
    }

    #[test]
    fn fixed_bandwidth_kernels_match_general_ones() {
        for (n, kl, ku) in [(40, 5, 5), (9, 5, 5), (3, 5, 5), (50, 7, 7), (12, 7, 7)] {
            let mut seed = 3 + n as u64;
            let mut band = BandLu::default();
            band.reset(n, kl, ku);
            for i in 0..n {
                for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                    band.add(i, j, lcg(&mut seed));
                }
            }
            let mut slow = band.clone();
            assert!(band.factor() && slow.factor_general());
            slow.scale_rows();
            assert_eq!(band.piv, slow.piv);
            for (x, y) in band.a.iter().zip(&slow.a) {
                assert!(
                    (x - y).abs() <= 1e-12 * (1.0 + y.abs()),
                    "n = {n}: {x} vs {y}"
                );
            }
            let rhs: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
            let (mut fast, mut general) = (rhs.clone(), rhs);
            band.solve(&mut fast);
            band.solve_general(&mut general);
            for (x, y) in fast.iter().zip(&general) {
                assert!(
                    (x - y).abs() <= 1e-12 * (1.0 + y.abs()),
                    "n = {n}: {x} vs {y}"
                );
            }
        }
    }

    #[test]
    fn split_lu_matches_dense_lu() {
        // The κ/εκ stencil on blocks of 3 (2D) and 4 (3D): block row j touches blocks
        // j-1 ..= j+1, and its G2 row also the position columns of block j+2.
        for (bs, blocks, closed) in [
            (3, 12, true),
            (3, 13, false),
            (4, 11, true),
            (4, 10, false),
            (3, 6, true),
        ] {
            let mut seed = 11 + blocks as u64;
            let n = bs * blocks;
            let m = blocks / 2 - 1;
            let cuts = [bs * m, bs * (m + 2), if closed { n - 2 * bs } else { n }];
            let (kl, ku) = (2 * bs - 1, 2 * bs - 1);
            let mut split = SplitLu::default();
            let mut dense = DenseLu::default();
            split.reset(cuts, n, bs, kl, ku);
            dense.reset(n);
            for j in 0..blocks {
                for r in 0..bs {
                    for o in -1isize..=2 {
                        let cols = if o == 2 {
                            if r != bs - 1 {
                                continue;
                            }
                            bs - 1
                        } else {
                            bs
                        };
                        let jb = j as isize + o;
                        let jb = if closed {
                            jb.rem_euclid(blocks as isize) as usize
                        } else if jb < 0 || jb >= blocks as isize {
                            continue;
                        } else {
                            jb as usize
                        };
                        for k in 0..cols {
                            let mut v = lcg(&mut seed);
                            if o == 0 && k == r {
                                v += 4.0;
                            }
                            split.add(j * bs + r, jb * bs + k, v);
                            dense.add(j * bs + r, jb * bs + k, v);
                        }
                    }
                }
            }
            assert!(split.factor() && dense.factor());
            let rhs: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
            assert_same_solution(|x| split.solve(x), &dense, &rhs);
            // Twice, as the chord steps use the factors.
            assert_same_solution(|x| split.solve(x), &dense, &rhs);
        }
    }

    #[test]
    fn band_solve_many_matches_single_solves() {
        let mut seed = 5;
        let (n, kl, ku, m) = (17, 3, 2, 4);
        let mut band = BandLu::default();
        band.reset(n, kl, ku);
        for i in 0..n {
            for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                band.add(i, j, lcg(&mut seed));
            }
        }
        assert!(band.factor());
        // Row-major right-hand sides, one of them zero (skipped by the forward pass).
        let mut many: Vec<f64> = (0..n * m)
            .map(|i| if i % m == 2 { 0.0 } else { lcg(&mut seed) })
            .collect();
        let columns: Vec<Vec<f64>> = (0..m)
            .map(|r| {
                let mut x: Vec<f64> = (0..n).map(|i| many[i * m + r]).collect();
                band.solve(&mut x);
                x
            })
            .collect();
        band.solve_many(&mut many, m);
        for (r, x) in columns.iter().enumerate() {
            for i in 0..n {
                assert!((many[i * m + r] - x[i]).abs() <= 1e-12 * (1.0 + x[i].abs()));
            }
        }
    }

    #[test]
    fn fixed_multi_solve_kernels_match_general() {
        for (n, kl, m) in [(30, 5, 6), (4, 5, 6), (25, 7, 8), (6, 7, 8)] {
            let mut seed = 17 + n as u64;
            let mut band = BandLu::default();
            band.reset(n, kl, kl);
            for i in 0..n {
                for j in i.saturating_sub(kl)..=(i + kl).min(n - 1) {
                    band.add(i, j, lcg(&mut seed));
                }
            }
            assert!(band.factor());
            let rhs: Vec<f64> = (0..n * m).map(|_| lcg(&mut seed)).collect();
            let (mut fast, mut general) = (rhs.clone(), rhs);
            band.solve_many(&mut fast, m);
            band.solve_many_general(&mut general, m, 0.0);
            for (x, y) in fast.iter().zip(&general) {
                assert!(
                    (x - y).abs() <= 1e-12 * (1.0 + y.abs()),
                    "n = {n}: {x} vs {y}"
                );
            }
        }
    }

    #[test]
    fn multi_solve_flushes_decaying_spikes_before_they_turn_subnormal() {
        // Border columns of a long diagonally dominant band: nonzero only in the first and
        // last rows, their solutions decay geometrically towards the middle. Without the
        // flush the tails run through the subnormal range (a slowdown, not an error), so
        // the test counts subnormals and checks the flushed solution against plain solves.
        let n = 3000;
        for (kl, m) in [(5, 6), (7, 12), (3, 4)] {
            let mut seed = 29 + kl as u64;
            let mut band = BandLu::default();
            band.reset(n, kl, kl);
            for i in 0..n {
                for j in i.saturating_sub(kl)..=(i + kl).min(n - 1) {
                    let v = if i == j {
                        2.0 * kl as f64
                    } else {
                        lcg(&mut seed)
                    };
                    band.add(i, j, v);
                }
            }
            assert!(band.factor());
            let mut many = vec![0.0; n * m];
            for r in 0..m {
                let row = if r % 2 == 0 { r / 2 } else { n - 1 - r / 2 };
                many[row * m + r] = 1.0 + lcg(&mut seed);
            }
            let columns: Vec<Vec<f64>> = (0..m)
                .map(|r| {
                    let mut x: Vec<f64> = (0..n).map(|i| many[i * m + r]).collect();
                    band.solve(&mut x);
                    x
                })
                .collect();
            // The same right-hand sides with an infinite and a NaN entry, for below.
            let mut infinite = many.clone();
            infinite[3 * m] = f64::INFINITY;
            infinite[(n - 4) * m + 1] = f64::NAN;
            band.solve_many(&mut many, m);
            let subnormal = many.iter().filter(|v| v.is_subnormal()).count();
            assert_eq!(subnormal, 0, "kl = {kl}: {subnormal} subnormal entries");
            assert!(many[n / 2 * m..(n / 2 + 1) * m].iter().all(|&v| v == 0.0));
            for (r, x) in columns.iter().enumerate() {
                assert!(x.iter().any(|v| v.is_subnormal()), "kl = {kl}: no tail");
                for i in 0..n {
                    assert!((many[i * m + r] - x[i]).abs() <= 1e-15 * (1.0 + x[i].abs()));
                }
            }
            // A non-finite right-hand side is not flushed away: it reaches the solution.
            band.solve_many(&mut infinite, m);
            for r in [0, 1] {
                assert!(
                    (0..n).any(|i| !infinite[i * m + r].is_finite()),
                    "kl = {kl}"
                );
            }
        }
    }

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

    #[test]
    fn bordered_matches_dense() {
        let mut seed = 11;
        let (ni, nb, kl, ku) = (10, 3, 2, 3);
        let n = ni + nb;
        let mut bord = BorderedLu::default();
        let mut dense = DenseLu::default();
        bord.reset(ni, nb, kl, ku);
        dense.reset(n);
        for i in 0..n {
            for j in 0..n {
                let in_band = i < ni && j < ni && j + kl >= i && j <= i + ku;
                let border = i >= ni || j >= ni;
                if in_band || (border && (i + j) % 3 != 0) {
                    let v = lcg(&mut seed) + if i == j { 2.0 } else { 0.0 };
                    bord.add(i, j, v);
                    dense.add(i, j, v);
                }
            }
        }
        let rhs: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
        assert!(bord.factor() && dense.factor());
        assert_same_solution(|x| bord.solve(x), &dense, &rhs);
    }

    #[test]
    fn singular_band_is_reported() {
        let mut band = BandLu::default();
        band.reset(3, 1, 1);
        band.add(0, 0, 1.0);
        band.add(1, 1, 1.0);
        assert!(!band.factor());
    }

    #[test]
    fn cyclic_tridiagonal_matches_dense() {
        let mut seed = 3;
        for &n in &[3usize, 4, 9] {
            for &cyclic in &[false, true] {
                let a: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
                let c: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
                let b: Vec<f64> = (0..n).map(|_| 2.5 + lcg(&mut seed)).collect();
                let d: Vec<[f64; 2]> = (0..n).map(|_| [lcg(&mut seed), lcg(&mut seed)]).collect();
                let mut dense = DenseLu::default();
                dense.reset(n);
                for i in 0..n {
                    dense.add(i, i, b[i]);
                    if i > 0 {
                        dense.add(i, i - 1, a[i]);
                    } else if cyclic {
                        dense.add(0, n - 1, a[0]);
                    }
                    if i + 1 < n {
                        dense.add(i, i + 1, c[i]);
                    } else if cyclic {
                        dense.add(n - 1, 0, c[n - 1]);
                    }
                }
                assert!(dense.factor());
                let mut x = d.clone();
                let mut scratch = TriScratch::default();
                assert!(solve_tridiagonal(&a, &b, &c, &mut x, cyclic, &mut scratch));
                for k in 0..2 {
                    let mut col: Vec<f64> = d.iter().map(|v| v[k]).collect();
                    dense.solve(&mut col);
                    for i in 0..n {
                        assert!((x[i][k] - col[i]).abs() < 1e-10, "n={n} cyclic={cyclic}");
                    }
                }
            }
        }
    }

    #[test]
    fn cyclic_order_three_pivots_and_reports_singular() {
        // b_0 = 0: the elimination must pivot (the Thomas passes would divide by it).
        let (a, b, c) = ([0.5, 0.25, 1.0], [0.0, 2.0, 0.5], [1.0, 0.75, 0.25]);
        let want = [[1.0, -2.0], [0.5, 3.0], [-1.5, 0.25]];
        let row = |i: usize, k: usize| {
            a[i] * want[(i + 2) % 3][k] + b[i] * want[i][k] + c[i] * want[(i + 1) % 3][k]
        };
        let mut x: Vec<[f64; 2]> = (0..3).map(|i| [row(i, 0), row(i, 1)]).collect();
        let mut scratch = TriScratch::default();
        assert!(solve_tridiagonal(&a, &b, &c, &mut x, true, &mut scratch));
        for i in 0..3 {
            for k in 0..2 {
                assert!((x[i][k] - want[i][k]).abs() < 1e-14, "{x:?}");
            }
        }
        // Rows summing to zero: the all-ones vector is in the kernel.
        let (a, b, c) = ([1.0, 1.0, 1.0], [-2.0, -2.0, -2.0], [1.0, 1.0, 1.0]);
        let mut x = vec![[1.0, 0.0]; 3];
        assert!(!solve_tridiagonal(&a, &b, &c, &mut x, true, &mut scratch));
        let mut x = vec![[f64::NAN, 0.0]; 3];
        let b = [f64::NAN, 2.0, 2.0];
        assert!(!solve_tridiagonal(&a, &b, &c, &mut x, true, &mut scratch));
    }

    #[test]
    fn long_cyclic_tridiagonal_solves() {
        // Long enough for the two Thomas passes to run side by side: A x = d checked row by
        // row.
        let mut seed = 9;
        let n = PARALLEL_TRIDIAGONAL + 5;
        let a: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
        let c: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
        let b: Vec<f64> = (0..n).map(|_| 2.5 + lcg(&mut seed)).collect();
        let d: Vec<[f64; 2]> = (0..n).map(|_| [lcg(&mut seed), lcg(&mut seed)]).collect();
        let mut x = d.clone();
        let mut scratch = TriScratch::default();
        assert!(solve_tridiagonal(&a, &b, &c, &mut x, true, &mut scratch));
        for i in 0..n {
            let (prev, next) = (x[(i + n - 1) % n], x[(i + 1) % n]);
            for k in 0..2 {
                let row = a[i] * prev[k] + b[i] * x[i][k] + c[i] * next[k];
                assert!(
                    (row - d[i][k]).abs() < 1e-12,
                    "row {i}: {row} vs {}",
                    d[i][k]
                );
            }
        }
    }
}

#[cfg(test)]
mod cyclic_tests {
    use super::*;

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

    #[test]
    fn bordered_cyclic_block_matrix_matches_dense() {
        let (n, b) = (7usize, 2usize);
        let nn = n * b;
        let mut bord = BorderedLu::default();
        bord.reset((n - 2) * b, 2 * b, 2 * b - 1, 3 * b - 1);
        let mut dense = DenseLu::default();
        dense.reset(nn);
        let mut v = 0.37;
        for i in 0..n {
            for off in [-1isize, 0, 1, 2] {
                let j = (i as isize + off).rem_euclid(n as isize) as usize;
                for r in 0..b {
                    for c in 0..b {
                        v = (v * 3.7 + 0.11) % 1.0;
                        let x = v - 0.5 + if off == 0 && r == c { 3.0 } else { 0.0 };
                        bord.add(i * b + r, j * b + c, x);
                        dense.add(i * b + r, j * b + c, x);
                    }
                }
            }
        }
        let rhs: Vec<f64> = (0..nn).map(|i| (i as f64 * 0.7).sin()).collect();
        assert!(bord.factor() && dense.factor());
        super::tests::assert_same_solution(|x| bord.solve(x), &dense, &rhs);
    }
}
