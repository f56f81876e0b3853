//! Banded LU with partial pivoting ([`BandLu`]), with unrolled kernels for the bandwidths
//! of the κ/εκ systems and a multi-right-hand-side solve for border columns.

use super::pivot;

/// A banded matrix with `kl` sub- and `ku` super-diagonals, factored in place by LU with
/// partial pivoting (as LAPACK's `dgbtf2`). Row `i` stores the columns
/// `i - kl ..= i + kl + ku`; the extra `kl` columns hold the fill-in of pivoting.
#[derive(Clone, Debug, Default)]
pub(crate) struct BandLu {
    pub(super) n: usize,
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
#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::testing::{assert_same_solution, lcg};
    use crate::linalg::DenseLu;

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
    fn singular_band_is_reported() {
        let mut band = BandLu::default();
        band.reset(3, 1, 1);
        band.add(0, 0, 1.0);
        band.add(1, 1, 1.0);
        assert!(!band.factor());
    }
}
