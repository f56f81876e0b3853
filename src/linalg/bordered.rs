//! A banded system with a small dense border ([`BorderedLu`]), solved through its Schur
//! complement: the form of a cyclic banded system.

use super::{BandLu, DenseLu};

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

/// `x -= W x_B` for a row-major `W` of `x_B.len()` columns: the back substitution of a
/// bordered solve ([`BorderedLu`], [`SplitLu`](super::SplitLu)).
pub(super) fn subtract_border(x: &mut [f64], w: &[f64], xb: &[f64]) {
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
#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::testing::{assert_same_solution, lcg};

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
