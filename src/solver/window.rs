//! Warm re-solves after a local edit: Newton's method on a window of blocks around the moved
//! points, with the rest of the curve following linearly.
//!
//! Moving one point changes the solution mostly nearby: on a jagged 50-point loop the
//! control points move about 7× less with every block of distance from the moved one. So the
//! unknowns are split into the window `W` (the moved blocks and [`HALF`] blocks on either
//! side) and the outer blocks `O`. The outer rows are linearized at the solution the edit
//! started from (their residual is zero there): `J_OO δ_O + J_OW δ_W = 0`, so the outer
//! unknowns follow the window as `δ_O = -X δ_W` with `X = J_OO⁻¹ J_OW`. Only the outer rows
//! next to the window touch window unknowns (its first two and last two blocks), so `X` has
//! `4 (D + 1)` columns; it is computed once per window (one band factorization of the outer
//! blocks and one pass over it for all columns) and kept while the edits stay inside.
//!
//! The window's own rows are solved with the outer unknowns eliminated: the Jacobian is
//! `J_WW - J_WO X`, the window's band plus terms that couple its two ends through the outer
//! blocks (a bordered system of the window's size, like a closed curve's). Its factors are
//! kept: the steps are chord steps (a residual and a back substitution each), the first one
//! with the factors of the previous re-solve, and the Jacobian is assembled and factored
//! anew (a Newton step) only where a chord step does not shrink the residual by
//! [`CHORD_RATE`]. A Newton step searches along its line: it is halved while it takes a `λ`
//! out of its range, and while the residual it leads to is not below the one it started
//! from. Each step costs `O(window)`, whatever the curve's length.
//!
//! At the end one `O(n)` pass moves the outer blocks (`c`, `λ` by `X`, `t` from their peak
//! rows) and measures the residual of the whole curve, which decides convergence: the
//! window's blocks as its last step measured them, and of the outer blocks those whose
//! stencil the pass changed (the others keep the measure of the previous re-solve). Where the
//! outer blocks' linearization is not accurate enough (long curves, whose solutions fall off
//! more slowly with distance), chord steps on the whole curve follow, by block elimination
//! with the two factors at hand: `y = J_OO⁻¹ r_O`, `(J_WW - J_WO X) δ_W = r_W - J_WO y`,
//! `δ_O = y - X δ_W`, one band back substitution over the curve each. Only where those do
//! not converge do the global chord and Newton steps take over.

use super::condense::{condense, Condensed};
use super::linear::{scatter, Columns};
use super::newton::lambda_valid;
use super::split::Split;
use super::tuning::window::{
    CHORD_RATE, FULL_RATE, HALF, MAX_FULL, MAX_MOVED, MAX_NEWTON, MAX_STEPS, MIN_DAMPING,
    WINDOW_MIN_BLOCKS,
};
use super::{Outcome, Problem, Settings, Workspace};
use crate::linalg::BandLu;

/// The blocks an edit moved: `count` consecutive blocks from `first` (cyclically for closed
/// curves).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Edit {
    first: usize,
    count: usize,
}

impl Edit {
    /// The edit that moved the input points `moved` (indices into the input points, in
    /// increasing order) of a curve with `n` unknown blocks, if they lie close together.
    /// Open curves: point `i` is the peak of block `i - 1`; the end points move the first
    /// and last blocks.
    pub(crate) fn of(closed: bool, n: usize, moved: &[usize]) -> Option<Edit> {
        if moved.is_empty() || moved.len() > MAX_MOVED || n == 0 {
            return None;
        }
        let block = |i: usize| {
            if closed {
                i
            } else {
                i.saturating_sub(1).min(n - 1)
            }
        };
        let mut blocks = [0; MAX_MOVED];
        for (b, &i) in blocks.iter_mut().zip(moved) {
            *b = block(i);
        }
        let blocks = &blocks[..moved.len()];
        let (first, last) = (blocks[0], blocks[blocks.len() - 1]);
        if !closed {
            let count = last - first + 1;
            return (count <= MAX_MOVED).then_some(Edit { first, count });
        }
        // The shortest arc covering the blocks starts after the largest cyclic gap.
        let mut best = (n - last + first, first);
        for pair in blocks.windows(2) {
            if pair[1] - pair[0] > best.0 {
                best = (pair[1] - pair[0], pair[1]);
            }
        }
        let count = n - best.0 + 1;
        (count <= MAX_MOVED).then_some(Edit {
            first: best.1,
            count,
        })
    }
}

/// Where a block sits in the split of [`Window`].
#[derive(Clone, Copy, Debug)]
enum Slot {
    /// Position within the window.
    Window(usize),
    /// Position among the outer blocks (the order of their band).
    Outer(usize),
}

/// The window of a local re-solve and the outer blocks' linear response (see the module
/// documentation).
#[derive(Clone, Debug, Default)]
pub(crate) struct Window<const B: usize> {
    /// Whether the fields below describe the current problem's structure and a recent
    /// solution.
    valid: bool,
    /// Whether the workspace's residual buffers hold the measure of the whole curve at the
    /// current state, from the end of the last window re-solve (see
    /// [`Workspace::measure_after_window`]).
    pub(super) measured: bool,
    /// Which blocks' unknowns the current re-solve changed (the window's all count).
    changed: Vec<bool>,
    n: usize,
    closed: bool,
    /// The window: `len` blocks from `a` (cyclically for closed curves).
    a: usize,
    len: usize,
    slot: Vec<Slot>,
    /// The outer blocks, in band order (closed: from the window's end around to its start).
    outer: Vec<usize>,
    /// Outer blocks within two blocks of the window: the window's rows read them.
    adj: Vec<usize>,
    /// `X = J_OO⁻¹ J_OW`, row-major (`(D + 1)` rows per outer block, [`Window::nq`] columns).
    x: Vec<f64>,
    /// The outer blocks' peak rows (recovering their `δt`).
    ocond: Vec<Condensed<B>>,
    band: BandLu,
    /// Whether `lin`, `jwo`, `wcond` and `wscale` hold the factored Newton system of a
    /// recent step on this window, with the current `X`.
    factored: bool,
    /// Whether `lin` holds that system assembled but not yet factored.
    assembled: bool,
    /// The window's Newton system (band storage: the terms that couple its two ends
    /// through the outer blocks fall outside the band and are left out, see
    /// [`Workspace::solve_window`]).
    lin: BandLu,
    /// Window rows' entries in outer columns: `(row, outer unknown, value)`.
    jwo: Vec<(usize, usize, f64)>,
    wres: Vec<[f64; B]>,
    /// The row scales of the window's blocks in the factored Jacobian.
    wscale: Vec<[f64; 2]>,
    /// The scales of the window's blocks' convergence measures (see
    /// [`Workspace::check_scales`]), computed at the first step of a re-solve and at each
    /// Newton step, and kept for the chord steps in between.
    wcheck: Vec<[f64; 2]>,
    /// The convergence measures of the window's blocks, as last evaluated.
    wmeasure: Vec<[f64; B]>,
    wcond: Vec<Condensed<B>>,
    /// The window's right-hand side, then its step.
    rhs: Vec<f64>,
    /// The condensed step in global numbering, where it is known.
    delta: Vec<f64>,
    /// The total change of the window unknowns that `X` reads.
    acc: Vec<f64>,
    /// The condensed unknowns of the window and adjacent blocks at the start of a re-solve.
    base: Vec<f64>,
    /// The outer blocks' part of a whole-curve chord step, in band order.
    yo: Vec<f64>,
    /// The last step from where it started (see [`Window::take`]): the window's unknowns
    /// and `t` there, `acc` there, the full step and each window block's full `δt`.
    prev: Vec<f64>,
    prev_t: Vec<f64>,
    acc_prev: Vec<f64>,
    z: Vec<f64>,
    dts: Vec<f64>,
}

impl<const B: usize> Window<B> {
    /// Columns of `X`: the unknowns of the window's first two and last two blocks.
    const fn nq() -> usize {
        4 * (B - 1)
    }

    /// The window-local unknown of column `q` of `X`.
    fn xcol(&self, q: usize) -> usize {
        xcol::<B>(self.len, q)
    }

    /// `(X acc)` at the condensed unknown `k` of outer block `p`: how far the outer
    /// unknown moves back for the window's total change so far.
    #[inline(always)]
    fn response(&self, p: usize, k: usize) -> f64 {
        let nq = Self::nq();
        let row = &self.x[(p * (B - 1) + k) * nq..][..nq];
        // Four partial sums (`nq` is a multiple of 4), which vectorize.
        let mut lanes = [0.0; 4];
        for (x, a) in row.chunks_exact(4).zip(self.acc[..nq].chunks_exact(4)) {
            for l in 0..4 {
                lanes[l] += x[l] * a[l];
            }
        }
        (lanes[0] + lanes[1]) + (lanes[2] + lanes[3])
    }

    /// `(X s)` at the condensed unknown `k` of outer block `p`, for the change `s(q)` of
    /// the window unknown of column `q`.
    fn response_to(&self, p: usize, k: usize, s: impl Fn(usize) -> f64) -> f64 {
        let nq = Self::nq();
        let row = &self.x[(p * (B - 1) + k) * nq..][..nq];
        row.iter().enumerate().map(|(q, x)| x * s(q)).sum()
    }

    /// The block at window position `i`.
    fn block(&self, i: usize) -> usize {
        let j = self.a + i;
        if j >= self.n {
            j - self.n
        } else {
            j
        }
    }

    /// Eliminate the outer unknowns from the assembled window system, `J_WW - J_WO X`, and
    /// factor it. `false` if singular.
    fn factor(&mut self) -> bool {
        let nq = Self::nq();
        let (kl, ku) = (2 * (B - 1) - 1, 2 * (B - 1) - 1);
        for &(row, o, v) in &self.jwo {
            for q in 0..nq {
                let xv = self.x[o * nq + q];
                let col = xcol::<B>(self.len, q);
                // Closed curves: the outer blocks also couple the window's two ends, by terms
                // that fall off geometrically with the outer blocks' count (about 7^-17 on
                // jagged loops). Left out, they make the step inexact by that much; the
                // residual, which decides convergence, is exact.
                if xv != 0.0 && col + kl >= row && col <= row + ku {
                    self.lin.add(row, col, -v * xv);
                }
            }
        }
        self.assembled = false;
        self.factored = self.lin.factor();
        self.factored
    }

    /// Move the window's unknowns the fraction `s` of the step in `z` from where it started
    /// (`prev`, `prev_t`, `acc_prev`), and the adjacent outer blocks with them. `false` if a
    /// value is not finite or a `λ` leaves its range.
    fn take<const D: usize>(&mut self, state: &mut super::State<D>, s: f64) -> bool {
        let bb = B - 1;
        let mut ok = true;
        for i in 0..self.len {
            let j = self.block(i);
            for k in 0..bb {
                *unknown_mut(state, j, k) = self.prev[i * bb + k] + s * self.z[i * bb + k];
            }
            let dt = s * self.dts[i];
            state.t[j] = (self.prev_t[i] + dt).clamp(0.0, 1.0);
            ok &= dt.is_finite() && lambda_valid(state.lam[j]);
        }
        for q in 0..Self::nq() {
            self.acc[q] = self.acc_prev[q] + s * self.z[self.xcol(q)];
        }
        let nw = self.len * bb;
        for ai in 0..self.adj.len() {
            let j = self.adj[ai];
            let Slot::Outer(p) = self.slot[j] else {
                unreachable!("adjacent blocks are outer ones")
            };
            for k in 0..bb {
                *unknown_mut(state, j, k) = self.base[nw + ai * bb + k] - self.response(p, k);
            }
            ok &= lambda_valid(state.lam[j]);
        }
        ok
    }

    /// Forget the window (the problem's structure changed, or its linearization failed).
    pub(crate) fn invalidate(&mut self) {
        self.valid = false;
        self.measured = false;
        self.factored = false;
        self.assembled = false;
    }
}

/// The window-local unknown of column `q` of `X` in a window of `len` blocks.
fn xcol<const B: usize>(len: usize, q: usize) -> usize {
    let bb = B - 1;
    if q < 2 * bb {
        q
    } else {
        q + (len - 4) * bb
    }
}

/// The column of `X` of window-local unknown `k` of window block `w` (of `len`), if any.
fn xq<const B: usize>(len: usize, w: usize, k: usize) -> Option<usize> {
    let bb = B - 1;
    if w < 2 {
        Some(w * bb + k)
    } else if w + 2 >= len {
        Some((w + 4 - len) * bb + k)
    } else {
        None
    }
}

/// The condensed unknown `k` of block `j` (`c` components, then `λ`).
fn unknown<const D: usize>(st: &super::State<D>, j: usize, k: usize) -> f64 {
    if k < D {
        st.c[j][k]
    } else {
        st.lam[j]
    }
}

/// The condensed unknown `k` of block `j`, to write.
fn unknown_mut<const D: usize>(st: &mut super::State<D>, j: usize, k: usize) -> &mut f64 {
    if k < D {
        &mut st.c[j][k]
    } else {
        &mut st.lam[j]
    }
}

impl<const D: usize, const B: usize> Workspace<D, B> {
    /// Split the blocks into the window (`len` blocks from `a`) and the outer blocks, and
    /// factor the outer rows' Jacobian at the current state for `X`. `false` if singular.
    fn build_window(&mut self, prob: &Problem<D>, a: usize, len: usize) -> bool {
        let n = prob.p.len();
        let bb = B - 1;
        let nq = Window::<B>::nq();
        let Workspace {
            state, window: w, ..
        } = self;
        w.valid = false;
        w.factored = false;
        w.assembled = false;
        (w.n, w.closed, w.a, w.len) = (n, prob.closed, a, len);
        w.slot.clear();
        w.slot.resize(n, Slot::Outer(0));
        w.outer.clear();
        if prob.closed {
            w.outer.extend((a + len..a + n).map(|j| j % n));
        } else {
            w.outer.extend((0..a).chain(a + len..n));
        }
        for i in 0..len {
            let j = w.block(i);
            w.slot[j] = Slot::Window(i);
        }
        for (p, &j) in w.outer.iter().enumerate() {
            w.slot[j] = Slot::Outer(p);
        }
        w.adj.clear();
        for d in 1..=2 {
            let (before, after) = if prob.closed {
                (Some((a + n - d) % n), Some((a + len - 1 + d) % n))
            } else {
                (a.checked_sub(d), Some(a + len - 1 + d).filter(|&j| j < n))
            };
            for j in [before, after].into_iter().flatten() {
                if matches!(w.slot[j], Slot::Outer(_)) && !w.adj.contains(&j) {
                    w.adj.push(j);
                }
            }
        }
        let no = w.outer.len();
        w.band.reset(no * bb, 2 * bb - 1, 2 * bb - 1);
        w.x.clear();
        w.x.resize(no * bb * nq, 0.0);
        w.ocond.clear();
        w.ocond.resize_with(no, Condensed::default);
        for p in 0..no {
            let j = w.outer[p];
            let loc = Self::local(prob, state, j);
            let (mut scale, mut g2) = ([1.0; 2], 0.0);
            let (_, mut jl) = Self::block_jacobian(prob, j, &loc, &mut scale, &mut g2);
            let columns = Columns::new::<D, B>(prob.closed, n, j, bb);
            condense::<D, B>(&mut jl, &columns, &mut w.ocond[p]);
            let (slot, band, x) = (&w.slot, &mut w.band, &mut w.x);
            let mut ok = true;
            scatter(p * bb, bb, &jl, &columns, |row, col, v| {
                match slot[col / bb] {
                    Slot::Outer(q) => band.add(row, q * bb + col % bb, v),
                    Slot::Window(i) => match xq::<B>(len, i, col % bb) {
                        Some(q) => x[row * nq + q] += v,
                        None => ok = false,
                    },
                }
            });
            if !ok {
                return false;
            }
        }
        if !w.band.factor() {
            return false;
        }
        w.band.solve_many(&mut w.x, nq);
        w.valid = w.x.iter().all(|v| v.is_finite());
        w.valid
    }

    /// Re-solve after `edit` by Newton's method on a window around it (see the module
    /// documentation). `None` if the curve is too short, the edit too wide, or the window's
    /// Newton steps failed (the state is then as it was); otherwise the outcome of the whole
    /// curve's convergence test, with the state moved.
    pub(super) fn solve_window(
        &mut self,
        prob: &Problem<D>,
        set: &Settings,
        edit: Edit,
        measured: bool,
    ) -> Option<Outcome> {
        let n = prob.p.len();
        let bb = B - 1;
        let nq = Window::<B>::nq();
        if n < WINDOW_MIN_BLOCKS || edit.count > MAX_MOVED || set.max_iterations == 0 {
            return None;
        }
        let (a, len) = if prob.closed {
            ((edit.first + n - HALF) % n, edit.count + 2 * HALF)
        } else {
            let a = edit.first.saturating_sub(HALF);
            (a, (edit.first + edit.count + HALF).min(n) - a)
        };
        let w = &self.window;
        let fits = w.valid && w.n == n && w.closed == prob.closed && w.a == a && w.len == len;
        if !(fits || self.build_window(prob, a, len)) {
            return None;
        }
        self.size_buffers(n);
        self.trial.clone_from(&self.state);
        let tol = set.tolerance;
        let Workspace {
            state, window: w, ..
        } = self;
        // The start: the window's and the adjacent blocks' unknowns.
        w.base.clear();
        for i in 0..len {
            let j = w.block(i);
            w.base.extend((0..bb).map(|k| unknown(state, j, k)));
        }
        for &j in &w.adj {
            w.base.extend((0..bb).map(|k| unknown(state, j, k)));
        }
        w.acc.clear();
        w.acc.resize(nq, 0.0);
        w.delta.clear();
        w.delta.resize(n * bb, 0.0);
        w.wres.resize(len, [0.0; B]);
        w.wcond.resize_with(len, Condensed::default);
        w.rhs.resize(len * bb, 0.0);
        w.wscale.resize(len, [1.0; 2]);
        w.wcheck.resize(len, [1.0; 2]);
        w.wmeasure.resize(len, [0.0; B]);
        let (mut steps, mut newton) = (0, 0);
        let (kl, ku) = (2 * bb - 1, 2 * bb - 1);
        // Chord steps reuse the factors of the last Newton step (the first one those of the
        // previous re-solve, at its solution): each costs a residual and a back
        // substitution. Where the residual does not fall by `CHORD_RATE` or better, the
        // Jacobian is assembled and factored anew at the current state.
        let mut chord = w.factored;
        let mut last = f64::INFINITY;
        // The fraction of the last step taken, and whether it is a Newton step still on
        // trial (its line search halves it until the residual falls).
        let (mut damp, mut trial) = (1.0, false);
        let ok = 'steps: loop {
            let mut worst = 0.0f64;
            let mut measure = |v: f64| {
                worst = if v.is_nan() {
                    f64::INFINITY
                } else {
                    worst.max(v.abs())
                };
            };
            if chord {
                // The residual with the row scales of the factored Jacobian.
                for i in 0..len {
                    let j = w.block(i);
                    let loc = Self::local(prob, state, j);
                    let (mut scale, mut g2) = (w.wscale[i], 0.0);
                    let mut ignore = |_: usize, _: super::linear::Var, _: f64| {};
                    let r = Self::eval_block::<false, true>(
                        prob,
                        j,
                        &loc,
                        &mut scale,
                        &mut g2,
                        &mut ignore,
                    );
                    if steps == 0 {
                        w.wcheck[i] = Self::check_scales(&loc, tol);
                    }
                    w.wmeasure[i] = Self::check_scaled(r, g2, w.wcheck[i]);
                    w.wmeasure[i].into_iter().for_each(&mut measure);
                    w.wcond[i].rhs(&r, &mut w.rhs[i * bb..]);
                    w.wres[i] = r;
                }
                if worst <= tol {
                    break true;
                }
                if trial && !(worst < last) {
                    // The Newton step made things worse: half of it.
                    loop {
                        damp *= 0.5;
                        if damp < MIN_DAMPING {
                            break 'steps false;
                        }
                        if w.take(state, damp) {
                            break;
                        }
                    }
                    continue;
                }
                trial = false;
                if !(worst <= CHORD_RATE * last) {
                    chord = false;
                    continue;
                }
            } else {
                // The window's residual and Jacobian at the current state.
                w.lin.reset(len * bb, kl, ku);
                w.jwo.clear();
                for i in 0..len {
                    let j = w.block(i);
                    let loc = Self::local(prob, state, j);
                    let (mut scale, mut g2) = ([1.0; 2], 0.0);
                    let (r, mut jl) = Self::block_jacobian(prob, j, &loc, &mut scale, &mut g2);
                    w.wcheck[i] = Self::check_scales(&loc, tol);
                    w.wmeasure[i] = Self::check_scaled(r, g2, w.wcheck[i]);
                    w.wmeasure[i].into_iter().for_each(&mut measure);
                    let columns = Columns::new::<D, B>(prob.closed, n, j, bb);
                    condense::<D, B>(&mut jl, &columns, &mut w.wcond[i]);
                    let (slot, lin, jwo) = (&w.slot, &mut w.lin, &mut w.jwo);
                    scatter(i * bb, bb, &jl, &columns, |row, col, v| {
                        match slot[col / bb] {
                            Slot::Window(c) => lin.add(row, c * bb + col % bb, v),
                            Slot::Outer(p) => jwo.push((row, p * bb + col % bb, v)),
                        }
                    });
                    w.wcond[i].rhs(&r, &mut w.rhs[i * bb..]);
                    w.wres[i] = r;
                    w.wscale[i] = scale;
                }
                (w.factored, w.assembled) = (false, true);
                if worst <= tol {
                    break true;
                }
            }
            if steps >= MAX_STEPS
                || steps >= set.max_iterations
                || !worst.is_finite()
                || (!chord && newton >= MAX_NEWTON)
            {
                break false;
            }
            steps += 1;
            if !chord {
                newton += 1;
                if !w.factor() {
                    break false;
                }
            }
            w.lin.solve(&mut w.rhs);
            // The step in global numbering: the window's here, the adjacent outer blocks'
            // below.
            for i in 0..len {
                let j = w.block(i);
                w.delta[j * bb..(j + 1) * bb].copy_from_slice(&w.rhs[i * bb..(i + 1) * bb]);
            }
            if chord {
                for q in 0..nq {
                    w.acc[q] += w.rhs[w.xcol(q)];
                }
                let mut finite = true;
                for (ai, &j) in w.adj.iter().enumerate() {
                    let Slot::Outer(p) = w.slot[j] else {
                        unreachable!("adjacent blocks are outer ones")
                    };
                    for k in 0..bb {
                        let now = w.base[(len + ai) * bb + k] - w.response(p, k);
                        let x = unknown_mut(state, j, k);
                        w.delta[j * bb + k] = now - *x;
                        *x = now;
                    }
                }
                for i in 0..len {
                    let j = w.block(i);
                    let (r, cond) = (&w.wres[i], &w.wcond[i]);
                    let dt = cond.dt(r[D + 1], &w.delta);
                    for k in 0..bb {
                        *unknown_mut(state, j, k) += w.rhs[i * bb + k];
                    }
                    state.t[j] = (state.t[j] + dt).clamp(0.0, 1.0);
                    finite &= dt.is_finite() && lambda_valid(state.lam[j]);
                }
                for &j in &w.adj {
                    finite &= lambda_valid(state.lam[j]);
                }
                if !finite {
                    break false;
                }
            } else {
                // A Newton step, with a line search: the full step (the adjacent outer
                // blocks' response, and each window block's `δt` from its peak row), from
                // where it starts; halved while it takes a `λ` out of its range, and then
                // while the residual it leads to (measured by the next chord step) is not
                // below the one it started from.
                for &j in &w.adj {
                    let Slot::Outer(p) = w.slot[j] else {
                        unreachable!("adjacent blocks are outer ones")
                    };
                    for k in 0..bb {
                        w.delta[j * bb + k] = -w.response_to(p, k, |q| w.rhs[w.xcol(q)]);
                    }
                }
                w.dts.clear();
                for i in 0..len {
                    let dt = w.wcond[i].dt(w.wres[i][D + 1], &w.delta);
                    w.dts.push(dt);
                }
                w.prev.clear();
                w.prev_t.clear();
                for i in 0..len {
                    let j = w.block(i);
                    w.prev.extend((0..bb).map(|k| unknown(state, j, k)));
                    w.prev_t.push(state.t[j]);
                }
                w.acc_prev.clone_from(&w.acc);
                w.z.clone_from(&w.rhs);
                (damp, trial) = (1.0, true);
                while !w.take(state, damp) {
                    damp *= 0.5;
                    if damp < MIN_DAMPING {
                        break 'steps false;
                    }
                }
            }
            last = worst;
            chord = w.factored;
        };
        if !ok {
            w.invalidate();
            self.state.clone_from(&self.trial);
            return None;
        }
        // The outer blocks follow: `δ_O = -X δ_W`, then `δt` from their peak rows.
        for (ai, &j) in w.adj.iter().enumerate() {
            for k in 0..bb {
                *unknown_mut(state, j, k) = w.base[(len + ai) * bb + k];
            }
        }
        for i in 0..len {
            let j = w.block(i);
            for k in 0..bb {
                w.delta[j * bb + k] = unknown(state, j, k) - w.base[i * bb + k];
            }
        }
        // Which blocks changed (the outer ones compared with where they started).
        w.changed.clear();
        w.changed.resize(n, false);
        for i in 0..len {
            let j = w.block(i);
            w.changed[j] = true;
        }
        for (p, &j) in w.outer.iter().enumerate() {
            for k in 0..bb {
                let dx = w.response(p, k);
                w.delta[j * bb + k] = -dx;
                let x = unknown_mut(state, j, k);
                let moved = *x - dx;
                w.changed[j] |= moved != *x;
                *x = moved;
            }
        }
        for (p, &j) in w.outer.iter().enumerate() {
            let cond = &w.ocond[p];
            let dt = cond.dt(0.0, &w.delta);
            let t = (state.t[j] + dt).clamp(0.0, 1.0);
            w.changed[j] |= t != state.t[j];
            state.t[j] = t;
        }
        // The whole curve's convergence test; where the outer blocks' linearization is not
        // accurate enough, chord steps on the whole curve.
        self.measure_after_window(prob, tol, measured);
        let mut residual = self.max_residual();
        let (mut chords, mut last) = (0, f64::INFINITY);
        while residual > tol
            && residual <= FULL_RATE * last
            && chords < MAX_FULL
            && steps < set.max_iterations
            && (self.window.factored || (self.window.assembled && self.window.factor()))
        {
            self.trial.clone_from(&self.state);
            chords += 1;
            steps += 1;
            if !self.full_chord(prob) {
                self.state.clone_from(&self.trial);
                break;
            }
            last = residual;
            self.measure_all(prob, tol);
            residual = self.max_residual();
            if !(residual <= FULL_RATE * last) {
                // Not contracting: back to where it was (the global steps go on from there).
                self.state.clone_from(&self.trial);
                self.swap_trial_residuals();
                residual = last;
                break;
            }
        }
        let converged = residual <= tol;
        self.window.measured = converged;
        if !converged {
            // Linearized too far from where `X` was computed: next time, anew.
            self.window.invalidate();
        }
        Some(Outcome {
            iterations: steps,
            newton_steps: newton,
            converged,
            residual,
        })
    }

    /// The residual of the whole curve at the current state into `res`, `check` and
    /// `scale` (the previous ones are kept in the `trial_` buffers).
    fn measure_all(&mut self, prob: &Problem<D>, tol: f64) {
        Self::residuals::<false>(
            prob,
            &self.state,
            &mut self.trial_scale,
            &mut self.trial_res,
            &mut self.trial_check,
            tol,
            super::residual::RawIo::Write(&mut []),
        );
        self.swap_trial_residuals();
    }

    /// [`measure_all`](Self::measure_all) right after the window's steps, in place: the
    /// window's blocks as its last step measured them (the state has not changed there
    /// since, only the row scales are those of the window's factors), the outer blocks
    /// anew. With `measured` (the buffers hold the measure of the state this re-solve
    /// started from), only the outer blocks whose stencil (blocks `j - 1 ..= j + 2`) holds
    /// a changed block: the response of the far ones rounds to nothing.
    fn measure_after_window(&mut self, prob: &Problem<D>, tol: f64, measured: bool) {
        let n = prob.p.len();
        if !measured && Split::of(prob.closed, n).is_some() {
            // Long curves measure in parallel pieces; the window is a small part of them.
            return self.measure_all(prob, tol);
        }
        let w = &self.window;
        for i in 0..w.len {
            let j = w.block(i);
            self.res[j] = w.wres[i];
            self.scale[j] = w.wscale[i];
            self.check[j] = w.wmeasure[i];
        }
        let touched = |j: usize| {
            let at = |d: isize| {
                let i = j as isize + d;
                if prob.closed {
                    w.changed[super::wrap(i, n)]
                } else {
                    (0..n as isize).contains(&i) && w.changed[i as usize]
                }
            };
            !measured || at(-1) || at(0) || at(1) || at(2)
        };
        let end = w.a + w.len;
        let outer = if end <= n {
            [0..w.a, end..n]
        } else {
            [end - n..w.a, 0..0]
        };
        for r in outer {
            // Runs of blocks to measure.
            let mut j = r.start;
            while j < r.end {
                if !touched(j) {
                    j += 1;
                    continue;
                }
                let run = j..(j + 1..r.end).find(|&i| !touched(i)).unwrap_or(r.end);
                Self::residuals_from::<false>(
                    prob,
                    &self.state,
                    run.start,
                    &mut self.scale[run.clone()],
                    &mut self.res[run.clone()],
                    &mut self.check[run.clone()],
                    tol,
                    super::residual::RawIo::Write(&mut []),
                );
                j = run.end;
            }
        }
    }

    /// One chord step on the whole curve from the residual in `res`, with the window's
    /// factored system and the outer blocks' band factor (block elimination: `y = J_OO⁻¹
    /// r_O`, then `(J_WW - J_WO X) δ_W = r_W - J_WO y` and `δ_O = y - X δ_W`). `false` if
    /// a value is not finite or a `λ` leaves its range.
    fn full_chord(&mut self, prob: &Problem<D>) -> bool {
        let n = prob.p.len();
        let bb = B - 1;
        let Workspace {
            state,
            window: w,
            res,
            ..
        } = self;
        let len = w.len;
        // Condensed right-hand sides: outer blocks in band order, then the window's.
        w.yo.resize(w.outer.len() * bb, 0.0);
        for (p, &j) in w.outer.iter().enumerate() {
            w.ocond[p].rhs(&res[j], &mut w.yo[p * bb..]);
        }
        w.band.solve(&mut w.yo);
        for i in 0..len {
            w.wcond[i].rhs(&res[w.block(i)], &mut w.rhs[i * bb..]);
        }
        for &(row, o, v) in &w.jwo {
            w.rhs[row] -= v * w.yo[o];
        }
        w.lin.solve(&mut w.rhs);
        // The step in global numbering.
        w.delta.clear();
        w.delta.resize(n * bb, 0.0);
        for i in 0..len {
            let j = w.block(i);
            w.delta[j * bb..(j + 1) * bb].copy_from_slice(&w.rhs[i * bb..(i + 1) * bb]);
        }
        for (p, &j) in w.outer.iter().enumerate() {
            for k in 0..bb {
                let back = w.response_to(p, k, |q| w.rhs[w.xcol(q)]);
                w.delta[j * bb + k] = w.yo[p * bb + k] - back;
            }
        }
        let mut ok = true;
        for (j, (r, slot)) in res.iter().zip(&w.slot).enumerate() {
            let cond = match *slot {
                Slot::Window(i) => &w.wcond[i],
                Slot::Outer(p) => &w.ocond[p],
            };
            let dt = cond.dt(r[D + 1], &w.delta);
            for k in 0..bb {
                *unknown_mut(state, j, k) += w.delta[j * bb + k];
            }
            state.t[j] = (state.t[j] + dt).clamp(0.0, 1.0);
            ok &= dt.is_finite() && lambda_valid(state.lam[j]);
        }
        ok && w.delta.iter().all(|d| d.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::basis::{Basis, CubicEk};

    #[test]
    fn edits_cover_the_moved_blocks() {
        assert_eq!(Edit::of(true, 40, &[7]), Some(Edit { first: 7, count: 1 }));
        // Around the wrap of a closed curve.
        assert_eq!(
            Edit::of(true, 40, &[0, 39]),
            Some(Edit {
                first: 39,
                count: 2
            })
        );
        assert_eq!(
            Edit::of(true, 40, &[0, 1, 39]),
            Some(Edit {
                first: 39,
                count: 3
            })
        );
        assert_eq!(
            Edit::of(true, 40, &[3, 5]),
            Some(Edit { first: 3, count: 3 })
        );
        // Open curves: point i peaks on block i - 1; the end points move the end blocks.
        assert_eq!(Edit::of(false, 40, &[0]), Some(Edit { first: 0, count: 1 }));
        assert_eq!(
            Edit::of(false, 40, &[41]),
            Some(Edit {
                first: 39,
                count: 1
            })
        );
        assert_eq!(
            Edit::of(false, 40, &[5, 6]),
            Some(Edit { first: 4, count: 2 })
        );
        // Too far apart, too many, or none.
        assert_eq!(Edit::of(true, 40, &[3, 20]), None);
        assert_eq!(Edit::of(false, 40, &[0, 41]), None);
        assert_eq!(Edit::of(true, 40, &[1, 2, 3, 4]), None);
        assert_eq!(Edit::of(true, 40, &[]), None);
    }

    /// A jagged loop (radii alternating 0.5 and 0.45; 3D: with a wave in z) in normalized
    /// coordinates.
    fn jagged<const D: usize>(n: usize) -> Vec<[f64; D]> {
        (0..n)
            .map(|i| {
                let th = i as f64 / n as f64 * std::f64::consts::TAU;
                let r = if i % 2 == 0 { 0.5 } else { 0.45 };
                core::array::from_fn(|k| match k {
                    0 => r * th.cos(),
                    1 => r * th.sin(),
                    _ => 0.1 * (3.0 * th).sin(),
                })
            })
            .collect()
    }

    fn cold<const D: usize, const B: usize>(prob: &Problem<D>, set: &Settings) -> Workspace<D, B> {
        let mut ws = Workspace::<D, B>::default();
        let mut scratch = Problem {
            closed: prob.closed,
            p: vec![],
            ghost: [[0.0; D]; 2],
            basis: vec![],
            tangents: Vec::new(),
        };
        assert!(ws.solve_cold(prob, set, &mut scratch).converged);
        ws
    }

    /// Drag the input points `moved` over three frames, re-solving each warm after the edit
    /// (as `SolverN::resolve` does): every frame converges through the window, in a few
    /// steps and at most three factorizations of the window, and lands on the cold solution of
    /// the moved points.
    fn check<const D: usize, const B: usize>(
        closed: bool,
        basis: Basis,
        n: usize,
        moved: &[usize],
    ) {
        // Moves of a tenth to a fifth of the spacing of the points (about 3 / n).
        let size = 3.0 / n as f64;
        let p = jagged::<D>(n);
        let ghost = [p[0], p[n - 1]];
        let p = if closed { p } else { p[1..n - 1].to_vec() };
        let blocks = p.len();
        let mut prob = Problem {
            closed,
            p,
            ghost,
            basis: vec![basis; blocks],
            tangents: Vec::new(),
        };
        let set = Settings {
            tolerance: 1e-12,
            max_iterations: 200,
            newton_chords: true,
        };
        let mut ws = cold::<D, B>(&prob, &set);
        let edit = Edit::of(closed, blocks, moved).unwrap();
        for (frame, step) in [0.1, 0.15, -0.2].into_iter().enumerate() {
            let step = step * size;
            ws.refresh_jacobian(&prob, set.tolerance);
            for &i in moved {
                let d: [f64; D] = core::array::from_fn(|k| step * [1.0, -0.6, 0.3][k]);
                // The control point moves with its input point.
                let block = if closed { Some(i) } else { i.checked_sub(1) };
                match block {
                    Some(j) if j < blocks => {
                        prob.p[j] = core::array::from_fn(|k| prob.p[j][k] + d[k]);
                        ws.state.c[j] = core::array::from_fn(|k| ws.state.c[j][k] + d[k]);
                    }
                    _ => {
                        let g = usize::from(i != 0);
                        prob.ghost[g] = core::array::from_fn(|k| prob.ghost[g][k] + d[k]);
                    }
                }
            }
            let out = if frame == 0 {
                let out = ws.solve_window(&prob, &set, edit, false);
                out.unwrap_or_else(|| panic!("{closed} {moved:?}: no window"))
            } else {
                ws.set_edit(Some(edit), false, false);
                ws.solve_warm(&prob, &set)
            };
            // The window's steps converge (with chord steps on the whole curve where the
            // outer blocks' linearization falls short), so the window stays valid: the
            // global steps did not take over.
            assert!(
                out.converged && out.newton_steps <= 3 && out.iterations <= 12 && ws.window.valid,
                "{closed} {moved:?} frame {frame}: {out:?}"
            );
            // The convergence measure it kept (partly from the frame before, where the
            // blocks did not change) is the measure of the state: exactly outside the
            // window, to a fraction of the tolerance inside (measured with the row scales
            // of the window's factors).
            let (mut scale, mut res, mut fresh) = (
                vec![[0.0; 2]; blocks],
                vec![[0.0; B]; blocks],
                vec![[0.0; B]; blocks],
            );
            let tol = set.tolerance;
            Workspace::<D, B>::residuals::<false>(
                &prob,
                &ws.state,
                &mut scale,
                &mut res,
                &mut fresh,
                tol,
                crate::solver::residual::RawIo::Write(&mut []),
            );
            for (j, (a, b)) in fresh.iter().zip(&ws.check).enumerate() {
                let inside = matches!(ws.window.slot[j], Slot::Window(_));
                for (x, y) in a.iter().zip(b) {
                    assert!(
                        if inside {
                            (x - y).abs() <= 0.1 * tol
                        } else {
                            x == y
                        },
                        "{closed} {moved:?} frame {frame} block {j}: measured {y:e}, is {x:e}"
                    );
                }
            }
            let reference = cold::<D, B>(&prob, &set);
            let (a, b) = (&ws.state, &reference.state);
            for j in 0..blocks {
                let dc = (0..D)
                    .map(|k| (a.c[j][k] - b.c[j][k]).abs())
                    .fold(0.0, f64::max);
                assert!(
                    dc < 1e-10,
                    "{closed} {moved:?} frame {frame} block {j}: {dc}"
                );
                assert!((a.lam[j] - b.lam[j]).abs() < 1e-9, "λ {j}");
                assert!((a.t[j] - b.t[j]).abs() < 1e-8, "t {j}");
            }
        }
    }

    /// On a densely sampled smooth loop (2 000 points) a move of a few percent of the
    /// points' spacing makes the window's first Newton step overshoot: in full it takes a
    /// `λ` out of its range, and without the line search the window gives up. Halved until
    /// the residual falls, the re-solve converges on the window, to the cold solution.
    #[test]
    fn window_newton_steps_search_along_the_line() {
        let n = 2000;
        let p: Vec<[f64; 2]> = (0..n)
            .map(|i| {
                let th = i as f64 / n as f64 * std::f64::consts::TAU;
                let r = 0.45 * (1.0 + 0.1 * (5.0 * th).sin());
                [r * th.cos(), r * th.sin()]
            })
            .collect();
        let mut prob = Problem {
            closed: true,
            ghost: [p[0], p[n - 1]],
            p,
            basis: vec![Basis::Cubic(CubicEk::new(0.85)); n],
            tangents: Vec::new(),
        };
        let set = Settings {
            tolerance: 1e-12,
            max_iterations: 200,
            newton_chords: true,
        };
        let mut ws = cold::<2, 4>(&prob, &set);
        let j = n / 3;
        let d = [4.5e-5, -2.25e-5];
        prob.p[j] = [prob.p[j][0] + d[0], prob.p[j][1] + d[1]];
        ws.state.c[j] = [ws.state.c[j][0] + d[0], ws.state.c[j][1] + d[1]];
        let out = ws.solve_window(&prob, &set, Edit::of(true, n, &[j]).unwrap(), false);
        let out = out.expect("the window re-solve gives up");
        assert!(out.converged, "{out:?}");
        let reference = cold::<2, 4>(&prob, &set);
        for (a, b) in ws.state.c.iter().zip(&reference.state.c) {
            assert!((a[0] - b[0]).abs().max((a[1] - b[1]).abs()) < 1e-10);
        }
    }

    #[test]
    fn window_resolves_match_cold_solves() {
        let kappa = Basis::QUADRATIC;
        let ek = Basis::Cubic(CubicEk::new(0.85));
        for basis in [kappa, ek] {
            check::<2, 4>(true, basis, 40, &[20]);
            check::<2, 4>(true, basis, 40, &[0]);
            check::<2, 4>(true, basis, 40, &[0, 38, 39]);
            check::<2, 4>(false, basis, 42, &[21]);
            check::<2, 4>(false, basis, 42, &[2, 3]);
            check::<2, 4>(false, basis, 42, &[0]);
            check::<2, 4>(false, basis, 42, &[41]);
        }
        check::<3, 5>(true, kappa, 36, &[5]);
        check::<3, 5>(false, kappa, 38, &[30]);
    }

    /// On long jagged loops the solution falls off more slowly with the distance from the
    /// moved point than on short ones, and the outer blocks' linearization leaves residuals
    /// above the tolerance: chord steps on the whole curve finish there.
    #[test]
    fn long_curves_finish_with_whole_curve_chords() {
        let kappa = Basis::QUADRATIC;
        let ek = Basis::Cubic(CubicEk::new(0.85));
        for basis in [kappa, ek] {
            check::<2, 4>(true, basis, 400, &[17]);
            check::<2, 4>(false, basis, 402, &[200]);
        }
    }
}
