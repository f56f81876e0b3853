//! Static condensation: `t_j` eliminated from its block before the banded solve, and
//! recovered after it.

use super::linear::Columns;
use super::split::{split4, Split};
use super::tuning::condense::{BACK_MAX, MIN_PIVOT};
use super::workspace::Workspace;

/// The elimination of `t_j` from block row `j` (static condensation): `t_j` appears only in
/// the rows of its own block, so `δt_j` is eliminated there before the banded solve (which
/// then has `B - 1 = D + 1` unknowns per block) and recovered after it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Condensed<const B: usize> {
    /// Multiplier of the peak row subtracted from each of the other rows of the block.
    m: [f64; B],
    /// The reciprocal of the pivot `∂R_t / ∂t_j`.
    inv: f64,
    /// The nonzero entries of the peak row (its own `t_j` entry excluded) in the condensed
    /// system's unknowns, as columns and values (the first `len`): what recovering `δt_j`
    /// from the condensed solution needs.
    cols: [u32; BACK_MAX],
    vals: [f64; BACK_MAX],
    len: usize,
}

impl<const B: usize> Default for Condensed<B> {
    fn default() -> Self {
        Condensed {
            m: [0.0; B],
            inv: 1.0,
            cols: [0; BACK_MAX],
            vals: [0.0; BACK_MAX],
            len: 0,
        }
    }
}

impl<const B: usize> Condensed<B> {
    /// The condensed right-hand side of a block with residual `r` (the peak row, last,
    /// subtracted from the others by its multipliers), into `out` (`B - 1` entries).
    #[inline]
    pub(super) fn rhs(&self, r: &[f64; B], out: &mut [f64]) {
        for (k, o) in out[..B - 1].iter_mut().enumerate() {
            *o = -(r[k] - self.m[k] * r[B - 1]);
        }
    }

    /// The block's `δt` from its peak residual `peak` and the condensed step `reduced`
    /// (all of it): the peak row solved for its own `t`.
    #[inline]
    pub(super) fn dt(&self, peak: f64, reduced: &[f64]) -> f64 {
        (-peak - self.row_dot(reduced)) * self.inv
    }

    /// `Σ row · δ` over the condensed unknowns `reduced`.
    #[inline]
    fn row_dot(&self, reduced: &[f64]) -> f64 {
        self.cols[..self.len]
            .iter()
            .zip(&self.vals[..self.len])
            .map(|(&c, &v)| v * reduced[c as usize])
            .sum()
    }
}

impl<const D: usize, const B: usize> Workspace<D, B> {
    /// The Newton (or, with an older factorization, chord) step for the current residual:
    /// the condensed system is solved for `δc`, `δλ`, then each `δt_j` is recovered from its
    /// peak row. Fills `self.step`; `false` if it is not finite.
    pub(super) fn condensed_step(&mut self) -> bool {
        let n = self.n();
        let bb = B - 1;
        self.reduced.resize(n * bb, 0.0);
        let Some(split) = self.lin.cut else {
            Self::reduce_from(&self.res, &self.cond, &mut self.reduced);
            self.lin.solve(&mut self.reduced);
            return Self::recover_from(0, &self.res, &self.cond, &self.reduced, &mut self.step);
        };
        let cuts = split.cuts();
        let (res, cond) = (&self.res, &self.cond);
        let [r0, r1, r2, r3] = split4(&mut self.reduced, cuts.map(|c| c * bb));
        let [j0, j1, j2, j3] = split.ranges();
        let pieces = [(j0, r0), (j1, r1), (j2, r2), (j3, r3)];
        Split::each(pieces, |(j, r)| {
            Self::reduce_from(&res[j.clone()], &cond[j], r)
        });
        self.lin.solve(&mut self.reduced);
        let reduced = &self.reduced;
        let [s0, s1, s2, s3] = split4(&mut self.step, cuts.map(|c| c * B));
        let [j0, j1, j2, j3] = split.ranges();
        let pieces = [(j0, s0), (j1, s1), (j2, s2), (j3, s3)];
        let ok = Split::each(pieces, |(j, s)| {
            Self::recover_from(j.start, &res[j.clone()], &cond[j], reduced, s)
        });
        ok.iter().all(|&ok| ok)
    }

    /// The condensed right-hand side of the blocks of `res` (`reduced` holds theirs).
    fn reduce_from(res: &[[f64; B]], cond: &[Condensed<B>], reduced: &mut [f64]) {
        let bb = B - 1;
        for ((r, c), out) in res.iter().zip(cond).zip(reduced.chunks_exact_mut(bb)) {
            c.rhs(r, out);
        }
    }

    /// The step of the blocks `j0..` of `res` (`step` holds theirs) from the condensed
    /// solution `reduced` (all of it): their condensed unknowns, and `δt` recovered from
    /// the peak rows. `false` if it is not finite.
    fn recover_from(
        j0: usize,
        res: &[[f64; B]],
        cond: &[Condensed<B>],
        reduced: &[f64],
        step: &mut [f64],
    ) -> bool {
        let bb = B - 1;
        let own = reduced[j0 * bb..].chunks_exact(bb);
        for (((r, c), out), x) in res.iter().zip(cond).zip(step.chunks_exact_mut(B)).zip(own) {
            out[..bb].copy_from_slice(x);
            out[D + 1] = c.dt(r[D + 1], reduced);
        }
        step.iter().all(|x| x.is_finite())
    }
}

/// Eliminate `t_j` from the local block rows `jl[row][offset][variable]` (offsets -1 ..= 2,
/// `t_j` is variable `D + 1` of offset 0, the peak row is row `D + 1`): subtract multiples of
/// the peak row from the other rows so that their `t_j` entries vanish. What the elimination
/// leaves behind is written into `out` in place (the entries of `out.cols` and `out.vals`
/// past its new `len` are left as they were, and never read).
#[inline]
pub(super) fn condense<const D: usize, const B: usize>(
    jl: &mut [[[f64; B]; 4]; B],
    columns: &Columns,
    out: &mut Condensed<B>,
) {
    let (tr, to, tk) = (D + 1, 1, D + 1);
    let mut p = jl[tr][to][tk];
    if !(p.abs() >= MIN_PIVOT) {
        p = if p < 0.0 { -MIN_PIVOT } else { MIN_PIVOT };
    }
    let inv = 1.0 / p;
    let peak = jl[tr];
    let mut m = [0.0; B];
    for (r, mr) in m.iter_mut().enumerate().take(D + 1) {
        let f = jl[r][to][tk] * inv;
        *mr = f;
        if f != 0.0 {
            for (row, prow) in jl[r].iter_mut().zip(&peak) {
                for (x, y) in row.iter_mut().zip(prow) {
                    *x -= f * y;
                }
            }
            jl[r][to][tk] = 0.0;
        }
    }
    out.m = m;
    out.inv = inv;
    let mut len = 0;
    for (o, block) in peak.iter().enumerate() {
        for (k, &v) in block.iter().enumerate().take(D + 1) {
            if v != 0.0 {
                if let Some(col) = columns.at(o, k) {
                    debug_assert!(u32::try_from(col).is_ok());
                    out.cols[len] = col as u32;
                    out.vals[len] = v;
                    len += 1;
                }
            }
        }
    }
    out.len = len;
}
