//! The linear system of a Newton step: where the block Jacobians go, and its band,
//! bordered, dense or split factorization.

use super::split::Split;
use super::tuning::linear::DENSE_ORDER;
use super::wrap;
use crate::linalg::{BandLu, BorderedLu, DenseLu, SplitLu};

/// The linear system of one Newton step: banded for open curves, bordered banded for closed
/// ones, dense when small, and cut in two halves and a border when long ([`Split`]).
#[derive(Clone, Debug, Default)]
pub(super) struct Linear {
    mode: LinearMode,
    band: BandLu,
    bord: BorderedLu,
    dense: DenseLu,
    pub(super) split: SplitLu,
    /// How the blocks are cut in [`LinearMode::Split`].
    pub(super) cut: Option<Split>,
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
enum LinearMode {
    #[default]
    Band,
    Bordered,
    Dense,
    /// Long curves: two halves and a border ([`SplitLu`]), side by side.
    Split,
}

impl Linear {
    pub(super) fn reset(&mut self, closed: bool, n: usize, b: usize) {
        // Block row j touches block columns j-1 ..= j+2, but only the G2 row (row D of the
        // block) reaches block j+2, and only its c part: ku = 2B - 1, kl = 2B - 1.
        let (kl, ku) = (2 * b - 1, 2 * b - 1);
        self.cut = Split::of(closed, n);
        if let Some(split) = self.cut {
            self.mode = LinearMode::Split;
            self.split
                .reset(split.cuts().map(|c| c * b), n * b, b, kl, ku);
            return;
        }
        self.mode = if n * b <= DENSE_ORDER {
            LinearMode::Dense
        } else if closed {
            LinearMode::Bordered
        } else {
            LinearMode::Band
        };
        match self.mode {
            LinearMode::Dense => self.dense.reset(n * b),
            LinearMode::Bordered => self.bord.reset((n - 2) * b, 2 * b, kl, ku),
            LinearMode::Band => self.band.reset(n * b, kl, ku),
            LinearMode::Split => unreachable!("set above"),
        }
    }

    /// Add the first `rows` rows of a condensed block Jacobian at row `row0`, in the columns
    /// of `columns` (see [`scatter`]).
    #[inline]
    pub(super) fn add_block<const B: usize>(
        &mut self,
        row0: usize,
        rows: usize,
        jl: &BlockJacobian<B>,
        columns: &Columns,
    ) {
        // One dispatch per block, not per entry.
        match self.mode {
            LinearMode::Dense => {
                // Every entry of the dense matrix exists: whole rows, zeros added as well
                // (the same sums), no test per entry.
                let d = columns.d;
                debug_assert_eq!(rows, d + 1);
                for (row, entries) in jl.iter().enumerate().take(rows) {
                    let r = self.dense.row_mut(row0 + row);
                    for (o, block) in entries.iter().enumerate() {
                        if let Some(cb) = columns.c[o] {
                            for (x, v) in r[cb..cb + d].iter_mut().zip(block) {
                                *x += v;
                            }
                        }
                        if let Some(cl) = columns.l[o] {
                            r[cl] += block[d];
                        }
                    }
                }
            }
            LinearMode::Bordered => {
                let m = &mut self.bord;
                scatter(row0, rows, jl, columns, |i, j, v| m.add(i, j, v));
            }
            LinearMode::Band => {
                let m = &mut self.band;
                scatter(row0, rows, jl, columns, |i, j, v| m.add(i, j, v));
            }
            LinearMode::Split => {
                let m = &mut self.split;
                scatter(row0, rows, jl, columns, |i, j, v| m.add(i, j, v));
            }
        }
    }

    pub(super) fn factor(&mut self) -> bool {
        match self.mode {
            LinearMode::Dense => self.dense.factor(),
            LinearMode::Bordered => self.bord.factor(),
            LinearMode::Band => self.band.factor(),
            LinearMode::Split => self.split.factor(),
        }
    }

    pub(super) fn solve(&mut self, x: &mut [f64]) {
        match self.mode {
            LinearMode::Dense => self.dense.solve(x),
            LinearMode::Bordered => self.bord.solve(x),
            LinearMode::Band => self.band.solve(x),
            LinearMode::Split => self.split.solve(x),
        }
    }
}

/// A block's condensed Jacobian: `jl[row][offset][variable]`, the stencil blocks `j - 1 ..=
/// j + 2` as offsets `0..4`.
pub(super) type BlockJacobian<const B: usize> = [[[f64; B]; 4]; B];

/// Add the first `rows` rows of a condensed block Jacobian (variables `0..rows` of each
/// stencil block) at row `row0`, in the columns of `columns`, through `add(row, column, v)`.
#[inline(always)]
pub(super) fn scatter<const B: usize>(
    row0: usize,
    rows: usize,
    jl: &BlockJacobian<B>,
    columns: &Columns,
    mut add: impl FnMut(usize, usize, f64),
) {
    for (row, entries) in jl.iter().enumerate().take(rows) {
        for (o, block) in entries.iter().enumerate() {
            for (k, &v) in block.iter().enumerate().take(rows) {
                if v != 0.0 {
                    if let Some(c) = columns.at(o, k) {
                        add(row0 + row, c, v);
                    }
                }
            }
        }
    }
}

/// Which variable of the stencil of block `j` a Jacobian entry belongs to.
#[derive(Clone, Copy, Debug)]
pub(super) enum Var {
    /// Component `k` of `c_{j+offset}`.
    C(isize, usize),
    /// `λ_{j+offset}`.
    L(isize),
    /// `t_j`.
    T,
}

impl Var {
    /// The global column, or `None` for a constant (ghost point or fixed λ of open curves).
    #[inline]
    pub(super) fn index<const D: usize, const B: usize>(
        self,
        closed: bool,
        n: usize,
        j: usize,
    ) -> Option<usize> {
        let block = |off: isize| -> Option<usize> {
            let i = j as isize + off;
            if closed {
                Some(wrap(i, n))
            } else if i < 0 || i as usize >= n {
                None
            } else {
                Some(i as usize)
            }
        };
        match self {
            Var::C(off, k) => block(off).map(|b| b * B + k),
            Var::L(off) => {
                let b = block(off)?;
                if !closed && b == n - 1 && off != 0 {
                    None
                } else {
                    Some(b * B + D)
                }
            }
            Var::T => Some(j * B + D + 1),
        }
    }
}

/// The global columns of the variables of block `j`'s stencil in the condensed system
/// (`stride` unknowns per block: `c` then `λ`), computed once per block.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Columns {
    /// First column of blocks `j-1 ..= j+2` (`None`: a ghost block of an open curve).
    c: [Option<usize>; 4],
    /// Column of `λ_{j-1} ..= λ_{j+2}` (`None` where fixed).
    l: [Option<usize>; 4],
    /// The dimension `D` (variables `0..D` are `c`, `D` is `λ`).
    d: usize,
}

impl Columns {
    #[inline]
    pub(super) fn new<const D: usize, const B: usize>(
        closed: bool,
        n: usize,
        j: usize,
        stride: usize,
    ) -> Columns {
        let c = core::array::from_fn(|o| {
            Var::C(o as isize - 1, 0)
                .index::<D, B>(closed, n, j)
                .map(|i| i / B * stride)
        });
        let l = core::array::from_fn(|o| {
            Var::L(o as isize - 1)
                .index::<D, B>(closed, n, j)
                .map(|i| i / B * stride + D)
        });
        Columns { c, l, d: D }
    }

    /// The column of variable `k` (`c` components, then `λ` at `k = D`) of stencil block `o`.
    #[inline]
    pub(super) fn at(&self, o: usize, k: usize) -> Option<usize> {
        if k < self.d {
            self.c[o].map(|b| b + k)
        } else {
            self.l[o]
        }
    }
}
