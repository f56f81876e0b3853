//! A banded system cut in two halves by a separator ([`SplitLu`]), the halves factored and
//! solved side by side.

use super::bordered::subtract_border;
use super::{BandLu, DenseLu};

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
#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::testing::{assert_same_solution, lcg};

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
}
