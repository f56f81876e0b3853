//! The residual and Jacobian of a block, and their evaluation and assembly over the
//! curve.

use super::condense::{condense, Condensed};
use super::linear::{scatter, BlockJacobian, Columns, Var};
use super::peak::peak_row;
use super::problem::{Problem, State};
use super::split::{split4, Split};
use super::tangent::{self, TangentRow};
use super::workspace::Workspace;
use super::{dot, sub, triangle};
use crate::basis::{SegmentBasis, Stationarity};
use crate::parallel::join;

/// The variables a block equation depends on.
#[derive(Clone, Copy)]
pub(super) struct Local<const D: usize> {
    pub(super) cm: [f64; D],
    pub(super) c0: [f64; D],
    pub(super) c1: [f64; D],
    pub(super) c2: [f64; D],
    pub(super) lm: f64,
    pub(super) l0: f64,
    pub(super) l1: f64,
    pub(super) t: f64,
}

/// The ingredients of the G2 condition at joint `j` (seed 000 eqs. 8–10):
/// `X = k_j (1-λ_{j-1}) T_j` and `Y = k_{j+1} λ_{j+1} T_{j+1}` with the end coefficients `k`
/// and the triangles `T_j = Δ(c_{j-1}, c_j, c_{j+1})`, `T_{j+1} = Δ(c_j, c_{j+1}, c_{j+2})`
/// (areas with their gradients, see [`triangle`]). G2 holds when `(1-λ_j)² X = λ_j² Y`.
#[derive(Clone, Copy)]
pub(super) struct JointTerms<const D: usize> {
    k0: f64,
    k1: f64,
    tj: (f64, [f64; D], [f64; D]),
    tj1: (f64, [f64; D], [f64; D]),
    pub(super) x: f64,
    pub(super) y: f64,
}

/// A triangle's area with its gradient, as [`triangle`] gives them.
type Tri<const D: usize> = (f64, [f64; D], [f64; D]);

impl<const D: usize> JointTerms<D> {
    /// The terms of joint `j`. `carry` passes a triangle from one block to the next in a
    /// pass over consecutive blocks: block `j`'s `T_{j+1}` is block `j + 1`'s `T_j`, the
    /// same three control points in the same order. It holds `T_j` if known (taken), and
    /// receives `T_{j+1}`.
    #[inline(always)]
    pub(super) fn new(
        prob: &Problem<D>,
        j: usize,
        l: &Local<D>,
        carry: &mut Option<Tri<D>>,
    ) -> Self {
        let n = prob.basis.len();
        let k0 = prob.basis[j].end_coefficient();
        let k1 = prob.basis[if j + 1 == n { 0 } else { j + 1 }].end_coefficient();
        let tj = carry.take().unwrap_or_else(|| triangle(l.cm, l.c0, l.c1));
        let tj1 = triangle(l.c0, l.c1, l.c2);
        *carry = Some(tj1);
        JointTerms {
            k0,
            k1,
            tj,
            tj1,
            x: k0 * (1.0 - l.lm) * tj.0,
            y: k1 * l.l1 * tj1.0,
        }
    }
}

/// What [`Workspace::residuals_from`] does with the [`Raw`] records of its blocks: fill them
/// in (an empty slice: none), or take the convergence test's floor scales from them.
pub(super) enum RawIo<'a> {
    Write(&'a mut [Raw]),
    Read(&'a [Raw]),
}

/// What the residual of a block is made of besides its interpolation rows, kept by the line
/// search so that [`Workspace::refreeze`] can rescale the joint and peak rows to other row
/// scales without evaluating the block again.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Raw {
    /// The joint row before its scale.
    joint: f64,
    /// The stationarity before its scale (the peak row is `t - clamp(t - g)` of it scaled).
    stationarity: f64,
    /// The relative |κ| mismatch of the convergence test.
    g2: f64,
    /// The convergence test's scales of the joint and peak rows.
    scales: [f64; 2],
}

impl<const D: usize, const B: usize> Workspace<D, B> {
    /// The residual (and convergence measures) of the current state with the row scales of
    /// the stored factorization; returns the merit.
    pub(super) fn residual_frozen(&mut self, prob: &Problem<D>, tol: f64, reuse: bool) -> f64 {
        let raw = if reuse && self.raw.len() == self.res.len() {
            RawIo::Read(&self.raw)
        } else {
            RawIo::Write(&mut [])
        };
        Self::residuals::<true>(
            prob,
            &self.state,
            &mut self.fact_scale,
            &mut self.res,
            &mut self.check,
            tol,
            raw,
        )
    }

    /// The scaled residual `res`, the convergence measures `check` and the merit `½|R|²` of
    /// state `st`, block by block. With `FROZEN` the row scales are read from `scale`
    /// (and left as they are); otherwise they are computed and stored there.
    ///
    /// `raw` (as long as `res`, or empty) receives what [`refreeze`](Self::refreeze) needs,
    /// or gives the convergence test's floor scales, on curves cut in no halves only.
    pub(super) fn residuals<const FROZEN: bool>(
        prob: &Problem<D>,
        st: &State<D>,
        scale: &mut [[f64; 2]],
        res: &mut [[f64; B]],
        check: &mut [[f64; B]],
        tol: f64,
        raw: RawIo,
    ) -> f64 {
        debug_assert!(scale.len() == st.t.len() && res.len() == st.t.len());
        debug_assert_eq!(check.len(), st.t.len());
        let Some(split) = Split::of(prob.closed, st.t.len()) else {
            return Self::residuals_from::<FROZEN>(prob, st, 0, scale, res, check, tol, raw);
        };
        let cuts = split.cuts();
        let [s0, s1, s2, s3] = split4(scale, cuts);
        let [r0, r1, r2, r3] = split4(res, cuts);
        let [c0, c1, c2, c3] = split4(check, cuts);
        let [j0, j1, j2, j3] = split.ranges().map(|r| r.start);
        let pieces = [
            (j0, s0, r0, c0),
            (j1, s1, r1, c1),
            (j2, s2, r2, c2),
            (j3, s3, r3, c3),
        ];
        let [p0, p1, p2, p3] = Split::each(pieces, |(j, s, r, c)| {
            Self::residuals_from::<FROZEN>(prob, st, j, s, r, c, tol, RawIo::Write(&mut []))
        });
        ((p0 + p1) + p2) + p3
    }

    /// [`residuals`](Self::residuals) of the blocks `j0..j0 + res.len()`.
    ///
    /// With `raw` as long as `res` (empty otherwise), also what [`refreeze`](Self::refreeze)
    /// needs of each block.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn residuals_from<const FROZEN: bool>(
        prob: &Problem<D>,
        st: &State<D>,
        j0: usize,
        scale: &mut [[f64; 2]],
        res: &mut [[f64; B]],
        check: &mut [[f64; B]],
        tol: f64,
        mut raw: RawIo,
    ) -> f64 {
        let mut phi = 0.0;
        for (i, ((scale, res), check)) in scale.iter_mut().zip(res).zip(check).enumerate() {
            let j = j0 + i;
            let loc = Self::local(prob, st, j);
            let mut g2 = 0.0;
            let mut ignore = |_: usize, _: Var, _: f64| {};
            let mut rw = [0.0; 2];
            let r = Self::eval_block_raw::<false, FROZEN>(
                prob,
                j,
                &loc,
                scale,
                &mut g2,
                &mut rw,
                &mut ignore,
            );
            phi += r.iter().map(|v| 0.5 * v * v).sum::<f64>();
            *res = r;
            let scales = match &raw {
                RawIo::Read(known) => known[i].scales,
                RawIo::Write(_) => Self::check_scales(&loc, tol),
            };
            *check = Self::check_scaled(r, g2, scales);
            if let RawIo::Write(raw) = &mut raw {
                if let Some(out) = raw.get_mut(i) {
                    *out = Raw {
                        joint: rw[0],
                        stationarity: rw[1],
                        g2,
                        scales,
                    };
                }
            }
        }
        phi
    }

    /// The residual, convergence measures and merit of the current state with the row
    /// scales of the stored factorization, from what the line search measured of it
    /// (`raw`, kept by [`trial_merit`](Self::trial_merit) and swapped in with the state):
    /// the same numbers as [`residual_frozen`](Self::residual_frozen), bit for bit, without
    /// evaluating the blocks again. Only the joint and peak rows depend on the row scales;
    /// the interpolation rows are kept as they are.
    pub(super) fn refreeze(&mut self) -> f64 {
        let mut phi = 0.0;
        let blocks = self.res.iter_mut().zip(&mut self.check).zip(&self.raw);
        for (j, ((r, check), raw)) in blocks.enumerate() {
            let f = self.fact_scale[j];
            r[D] = raw.joint * f[0];
            // The complementarity switch with the frozen scale.
            r[D + 1] = peak_row(self.state.t[j], raw.stationarity * f[1]).0;
            phi += r.iter().map(|v| 0.5 * v * v).sum::<f64>();
            *check = Self::check_scaled(*r, raw.g2, raw.scales);
        }
        phi
    }

    /// Merit `½|R|²` of the trial state, with row scales computed at the trial state (which
    /// globalizes better on the drawings than the scales of the current state). Fills
    /// `trial_res`, `trial_check` and `trial_scale` as [`assemble`](Self::assemble) would
    /// at the trial state.
    pub(super) fn trial_merit(&mut self, prob: &Problem<D>, tol: f64) -> f64 {
        // Also what `refreeze` needs, should the state be accepted.
        let phi = Self::residuals::<false>(
            prob,
            &self.trial,
            &mut self.trial_scale,
            &mut self.trial_res,
            &mut self.trial_check,
            tol,
            RawIo::Write(&mut self.trial_raw),
        );
        if phi.is_nan() {
            f64::INFINITY
        } else {
            phi
        }
    }

    /// Evaluate the scaled residual and the scaled Jacobian (into the linear system) of the
    /// current state. Returns the merit `½|R|²`.
    pub(super) fn assemble(&mut self, prob: &Problem<D>, tol: f64) -> f64 {
        let n = self.n();
        let st = &self.state;
        let Some(split) = Split::of(prob.closed, n) else {
            let lin = &mut self.lin;
            let mut add = |row0: usize, jl: &BlockJacobian<B>, columns: &Columns| {
                lin.add_block::<B>(row0, D + 1, jl, columns)
            };
            let (cond, scale, check, res) = (
                &mut self.cond[..],
                &mut self.scale[..],
                &mut self.check[..],
                &mut self.res[..],
            );
            return Self::assemble_from(prob, st, 0, cond, scale, check, res, tol, &mut add);
        };
        // The halves' rows go to the halves' own storage, side by side; the border rows
        // (separator and tail) after them.
        let cuts = split.cuts();
        let [k0, k1, k2, k3] = split4(&mut self.cond, cuts);
        let [s0, s1, s2, s3] = split4(&mut self.scale, cuts);
        let [c0, c1, c2, c3] = split4(&mut self.check, cuts);
        let [r0, r1, r2, r3] = split4(&mut self.res, cuts);
        let [j0, j1, j2, j3] = split.ranges().map(|r| r.start);
        let [mut h0, mut h2] = self.lin.split.halves();
        let (p0, p2) = join(
            || {
                let mut add = |row0: usize, jl: &BlockJacobian<B>, columns: &Columns| {
                    scatter(row0, D + 1, jl, columns, |i, j, v| h0.add(i, j, v))
                };
                Self::assemble_from(prob, st, j0, k0, s0, c0, r0, tol, &mut add)
            },
            || {
                let mut add = |row0: usize, jl: &BlockJacobian<B>, columns: &Columns| {
                    scatter(row0, D + 1, jl, columns, |i, j, v| h2.add(i, j, v))
                };
                Self::assemble_from(prob, st, j2, k2, s2, c2, r2, tol, &mut add)
            },
        );
        let lin = &mut self.lin.split;
        let mut add = |row0: usize, jl: &BlockJacobian<B>, columns: &Columns| {
            scatter(row0, D + 1, jl, columns, |i, j, v| lin.add(i, j, v))
        };
        let p1 = Self::assemble_from(prob, st, j1, k1, s1, c1, r1, tol, &mut add);
        let p3 = Self::assemble_from(prob, st, j3, k3, s3, c3, r3, tol, &mut add);
        ((p0 + p1) + p2) + p3
    }

    /// [`assemble`](Self::assemble) for the blocks `j0..j0 + res.len()`: their residuals,
    /// convergence measures, row scales and condensations, and their condensed Jacobian
    /// rows through `add` (first row, the block's Jacobian, its columns).
    #[allow(clippy::too_many_arguments)]
    fn assemble_from(
        prob: &Problem<D>,
        st: &State<D>,
        j0: usize,
        cond: &mut [Condensed<B>],
        scale: &mut [[f64; 2]],
        check: &mut [[f64; B]],
        res: &mut [[f64; B]],
        tol: f64,
        add: &mut impl FnMut(usize, &BlockJacobian<B>, &Columns),
    ) -> f64 {
        let n = st.t.len();
        let mut phi = 0.0;
        let blocks = cond.iter_mut().zip(scale).zip(check).zip(res).enumerate();
        for (i, (((cond, scale_j), check), res)) in blocks {
            let j = j0 + i;
            let loc = Self::local(prob, st, j);
            let mut scale = [1.0; 2];
            let mut g2 = 0.0;
            let (r, mut jl) = Self::block_jacobian(prob, j, &loc, &mut scale, &mut g2);
            let columns = Columns::new::<D, B>(prob.closed, n, j, B - 1);
            condense::<D, B>(&mut jl, &columns, cond);
            add(j * (B - 1), &jl, &columns);
            *scale_j = scale;
            *check = Self::check_row(r, g2, &loc, tol);
            for v in r.iter() {
                phi += 0.5 * v * v;
            }
            *res = r;
        }
        phi
    }

    /// Gather the variables of block `j` from `st`.
    #[inline(always)]
    pub(super) fn local(prob: &Problem<D>, st: &State<D>, j: usize) -> Local<D> {
        if j >= 1 && j + 2 < st.t.len() {
            // Interior: no wrap-around and no ghost point.
            return Local {
                cm: st.c[j - 1],
                c0: st.c[j],
                c1: st.c[j + 1],
                c2: st.c[j + 2],
                lm: st.lam[j - 1],
                l0: st.lam[j],
                l1: st.lam[j + 1],
                t: st.t[j],
            };
        }
        if prob.closed {
            // Near the wrap-around: three cyclic indices, each used for `c` and `λ`. Each
            // can leave `0..n` on one side only, so it takes one test (`wrap` takes two:
            // with it the bear's κ solve measured 1.1 % more instructions).
            let n = st.t.len();
            let im = if j == 0 { n - 1 } else { j - 1 };
            let i1 = if j + 1 == n { 0 } else { j + 1 };
            let i2 = if i1 + 1 == n { 0 } else { i1 + 1 };
            return Local {
                cm: st.c[im],
                c0: st.c[j],
                c1: st.c[i1],
                c2: st.c[i2],
                lm: st.lam[im],
                l0: st.lam[j],
                l1: st.lam[i1],
                t: st.t[j],
            };
        }
        let c = |i: isize| st.control(prob, i);
        let lam = |i: isize| st.ratio(prob, i);
        let j = j as isize;
        Local {
            cm: c(j - 1),
            c0: c(j),
            c1: c(j + 1),
            c2: c(j + 2),
            lm: lam(j - 1),
            l0: lam(j),
            l1: lam(j + 1),
            t: st.t[j as usize],
        }
    }

    /// The scaled residual of block `j` (row scales computed into `scale`, the relative |κ|
    /// mismatch into `g2`) and its Jacobian by stencil block and variable, `t_j` not yet
    /// eliminated.
    #[inline(always)]
    pub(super) fn block_jacobian(
        prob: &Problem<D>,
        j: usize,
        loc: &Local<D>,
        scale: &mut [f64; 2],
        g2: &mut f64,
    ) -> ([f64; B], BlockJacobian<B>) {
        let mut jl = [[[0.0; B]; 4]; B];
        let mut sink = |row: usize, col: Var, v: f64| {
            let (o, k) = match col {
                Var::C(off, k) => ((off + 1) as usize, k),
                Var::L(off) => ((off + 1) as usize, D),
                Var::T => (1, D + 1),
            };
            jl[row][o][k] += v;
        };
        let mut r = Self::eval_block::<true, false>(prob, j, loc, scale, g2, &mut sink);
        if !prob.tangents.is_empty() {
            tangent::end_row_last(prob, j, &mut r, &mut jl);
        }
        (r, jl)
    }

    /// The scaled residual of block `j`; with `FROZEN`, the row scales in `scale` are used
    /// instead of computed (and stored there). The solver evaluates residuals with
    /// [`eval_block`](Self::eval_block) directly; the tests use this.
    #[cfg(test)]
    pub(super) fn block<const FROZEN: bool>(
        prob: &Problem<D>,
        j: usize,
        loc: &Local<D>,
        scale: &mut [f64; 2],
    ) -> [f64; B] {
        let mut ignore = |_: usize, _: Var, _: f64| {};
        let mut g2 = 0.0;
        Self::eval_block::<false, FROZEN>(prob, j, loc, scale, &mut g2, &mut ignore)
    }

    /// Scaled residual of block `j`; with `JAC`, also every Jacobian entry `(row, variable,
    /// value)` (multiplied by the row scale) through `sink`. With `FROZEN`, the row scales
    /// come from `scale`; otherwise they are computed and stored there.
    #[inline(always)]
    pub(super) fn eval_block<const JAC: bool, const FROZEN: bool>(
        prob: &Problem<D>,
        j: usize,
        l: &Local<D>,
        scale: &mut [f64; 2],
        g2: &mut f64,
        sink: &mut impl FnMut(usize, Var, f64),
    ) -> [f64; B] {
        let mut raw = [0.0; 2];
        Self::eval_block_raw::<JAC, FROZEN>(prob, j, l, scale, g2, &mut raw, sink)
    }

    /// [`eval_block`](Self::eval_block), also giving the two values its scaled rows are
    /// made of: the joint row before its scale and the stationarity before its scale
    /// (what [`Raw`] keeps).
    #[inline(always)]
    fn eval_block_raw<const JAC: bool, const FROZEN: bool>(
        prob: &Problem<D>,
        j: usize,
        l: &Local<D>,
        scale: &mut [f64; 2],
        g2: &mut f64,
        raw: &mut [f64; 2],
        sink: &mut impl FnMut(usize, Var, f64),
    ) -> [f64; B] {
        let n = prob.p.len();
        let basis = prob.basis[j];
        let w = basis.weights(l.t);
        let (w0, w2) = (w[0][0], w[0][1]);
        let em = sub(l.c0, l.cm); // c_j - c_{j-1}
        let e0 = sub(l.c1, l.c0); // c_{j+1} - c_j
        let om = 1.0 - l.lm;
        let r: [f64; D] = core::array::from_fn(|k| om * em[k]);
        let s: [f64; D] = core::array::from_fn(|k| l.l0 * e0[k]);
        let mut res = [0.0; B];
        // Interpolation.
        for k in 0..D {
            res[k] = l.c0[k] - w0 * r[k] + w2 * s[k] - prob.p[j][k];
        }
        // A prescribed tangent takes the place of the peak condition (see `Tangent`).
        let tangent = if prob.tangents.is_empty() {
            None
        } else {
            prob.tangents[j].map(|tan| TangentRow::new(tan, &basis, l.t, r, s))
        };
        // Curvature peak.
        let st = Stationarity::new(&w);
        let (rr, rs, ss) = (dot(r, r), dot(r, s), dot(s, s));
        let rt = st.c[0] * rr + st.c[1] * rs + st.c[2] * ss;
        raw[1] = rt;
        let mag = st.c[0].abs() * rr + st.c[1].abs() * rs.abs() + st.c[2].abs() * ss;
        let sc_t = if tangent.is_some() {
            1.0
        } else if FROZEN {
            scale[1]
        } else {
            -1.0 / (mag + 1e-300)
        };
        // Peak condition as a box complementarity (semi-smooth Newton): with `g` the scaled
        // stationarity residual (increasing in t through a maximum), `t - clamp(t - g, 0, 1)`
        // is `g` inside, `t` when the peak is forced to the start, `t - 1` at the end.
        // A tangent row has no complementarity: a tangent met by pinning `t_j` at a
        // segment end would not be met at the point.
        let (peak, peak_end) = match &tangent {
            Some(tr) => {
                raw[1] = tr.value;
                (tr.value, None)
            }
            None => peak_row(l.t, rt * sc_t),
        };
        res[D + 1] = peak;
        scale[1] = sc_t;
        // G2 joint (trivial for the last block of an open curve: λ_{n-1} = 1).
        let last_open = !prob.closed && j == n - 1;
        *g2 = 0.0;
        // (Two triangles per block, though the next block computes this one's second
        // again: passing it on measured more instructions, the pair computed together
        // being cheaper than the carry.)
        let joint = (!last_open).then(|| JointTerms::new(prob, j, l, &mut None));
        if let Some(JointTerms { x, y, .. }) = joint {
            let (u, v) = ((1.0 - l.l0).powi(2) * x, l.l0 * l.l0 * y);
            res[D] = u - v;
            // The convergence test measures (r - 1)/(r + 1) with r = κ_j(1)² / κ_{j+1}(0)²,
            // the relative |κ| mismatch whatever λ is; Newton's row scale 1/(X + Y)
            // globalizes better.
            *g2 = (u - v).abs() / (u + v + 1e-300);
            if !FROZEN {
                scale[0] = 1.0 / (x + y + 1e-300);
            }
        } else {
            // The last block of an open curve: λ_{n-1} = 1.
            res[D] = l.l0 - 1.0;
            if !FROZEN {
                scale[0] = 1.0;
            }
        }
        raw[0] = res[D];
        res[D] *= scale[0];
        if JAC {
            // Interpolation rows.
            let dt: [f64; D] = core::array::from_fn(|k| -w[1][0] * r[k] + w[1][1] * s[k]);
            for k in 0..D {
                sink(k, Var::C(-1, k), w0 * om);
                sink(k, Var::C(0, k), 1.0 - w0 * om - w2 * l.l0);
                sink(k, Var::C(1, k), w2 * l.l0);
                sink(k, Var::L(-1), w0 * em[k]);
                sink(k, Var::L(0), w2 * e0[k]);
                sink(k, Var::T, dt[k]);
            }
            // Peak row.
            let sc = sc_t;
            if let Some(_end) = peak_end {
                sink(D + 1, Var::T, 1.0);
            } else if let Some(tr) = &tangent {
                tr.jacobian(l, em, e0, om, &mut |var, v| sink(D + 1, var, v));
            } else {
                let gr: [f64; D] = core::array::from_fn(|k| 2.0 * st.c[0] * r[k] + st.c[1] * s[k]);
                let gs: [f64; D] = core::array::from_fn(|k| st.c[1] * r[k] + 2.0 * st.c[2] * s[k]);
                for k in 0..D {
                    sink(D + 1, Var::C(-1, k), -sc * om * gr[k]);
                    sink(D + 1, Var::C(0, k), sc * (om * gr[k] - l.l0 * gs[k]));
                    sink(D + 1, Var::C(1, k), sc * l.l0 * gs[k]);
                }
                sink(D + 1, Var::L(-1), -sc * dot(gr, em));
                sink(D + 1, Var::L(0), sc * dot(gs, e0));
                sink(
                    D + 1,
                    Var::T,
                    sc * (st.dc[0] * rr + st.dc[1] * rs + st.dc[2] * ss),
                );
            }
            // Joint row.
            let sc = scale[0];
            if let Some(JointTerms {
                k0,
                k1,
                tj,
                tj1,
                x,
                y,
            }) = joint
            {
                sink(D, Var::L(0), -sc * 2.0 * ((1.0 - l.l0) * x + l.l0 * y));
                let fa = sc * (1.0 - l.l0).powi(2);
                let fb = -sc * l.l0 * l.l0;
                // x = k0 (1-λ_{j-1}) T_j,  y = k1 λ_{j+1} T_{j+1}
                sink(D, Var::L(-1), -fa * k0 * tj.0);
                sink(D, Var::L(1), fb * k1 * tj1.0);
                let (ga, gc) = (tj.1, tj.2);
                let (ha, hc) = (tj1.1, tj1.2);
                let a_t = fa * k0 * om;
                let b_t = fb * k1 * l.l1;
                for k in 0..D {
                    sink(D, Var::C(-1, k), a_t * ga[k]);
                    sink(D, Var::C(0, k), -a_t * (ga[k] + gc[k]) + b_t * ha[k]);
                    sink(D, Var::C(1, k), a_t * gc[k] - b_t * (ha[k] + hc[k]));
                    sink(D, Var::C(2, k), b_t * hc[k]);
                }
            } else {
                sink(D, Var::L(0), 1.0);
            }
        }
        res
    }
}
