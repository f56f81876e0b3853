// `!(x > 0.0)` is meant: it is also true for NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
//! The κ/εκ-curve solver, written once for points of any dimension `D` (2D and 3D).
//!
//! # Unknowns and equations
//! For each input point `p_j` that a segment must peak at, the unknowns are the middle
//! control point `c_j` (`D` numbers), the joint ratio `λ_j` and the peak parameter `t_j`
//! (block size `B = D + 2`). The segment `j` has control points
//! `c_{j,0} = (1-λ_{j-1}) c_{j-1} + λ_{j-1} c_j`, `c_j`, `c_{j,2} = (1-λ_j) c_j + λ_j c_{j+1}`
//! (seed 000 eq. 7, G1 by construction) and the equations are
//! - interpolation `C_j(t_j) = p_j` (seed 000 eq. 5),
//! - the G2 joint `κ_j(1) = κ_{j+1}(0)` written as `(1-λ_j)² X_j - λ_j² Y_j = 0` with
//!   `X_j = k_j (1-λ_{j-1}) T_j`, `Y_j = k_{j+1} λ_{j+1} T_{j+1}`,
//!   `T_j = Δ(c_{j-1}, c_j, c_{j+1})` (seed 000 eqs. 8–10; `k` is the basis' end
//!   coefficient). This squared form has bounded derivatives where a segment turns straight
//!   (`T → 0`), unlike `λ = √X / (√X + √Y)`, so Newton can pass through an orientation flip,
//! - the curvature peak `dκ_j/dt (t_j) = 0` in the area-free form of [`crate::basis`].
//!
//! # Method
//! A few iterations of the classic local/global loop (seed 000 Algorithm 1: λ, then `t` by a
//! bracketed 1-D root solve, then a (cyclic) tridiagonal solve for the `c_j`) give a start;
//! Newton's method on the whole system then converges quadratically. The Jacobian is
//! block-banded (block row `j` touches block columns `j-1 ..= j+2`); closed curves wrap
//! around, which is handled by a bordered solve. Long curves are cut in two halves and a
//! border ([`Split`]) whose per-block work and band factorizations run side by side
//! ([`crate::parallel`]). Each Newton step costs `O(m)`. A
//! backtracking line search on the scaled residual globalizes it, with classic iterations as
//! the fallback when a step fails. Open curves are the same system with fixed "ghost"
//! control points `c_{-1} = p_first`, `c_n = p_last` and `λ_{-1} = 0`, `λ_{n-1} = 1`.

use crate::basis::{Basis, SegmentBasis, Stationarity};
use crate::linalg::{solve_tridiagonal, BandLu, BorderedLu, DenseLu, SplitLu, TriScratch};
use crate::parallel::join;

mod points;
mod tangent;
mod window;

use tangent::TangentRow;
pub(crate) use tangent::{Tangent, TangentAt};
pub(crate) use window::Edit;

/// Regularization of the squared doubled triangle area, in normalized coordinates (drawing
/// size 1): keeps the area differentiable for straight stretches while far below any real
/// area (a triangle with sides 1e-10 has a squared doubled area ≈ 1e-40).
const EPS_GRAM: f64 = 1e-60;
/// Rounding floor of the dimensionless (G2 and peak) residuals times the local segment
/// length, in normalized coordinates: 64 ulps of a unit coordinate.
const ROUNDING_FLOOR: f64 = 64.0 * f64::EPSILON;
/// Bounds for λ during the line search (it must stay strictly inside (0, 1)).
const LAMBDA_MIN: f64 = 1e-12;
/// The largest rounding floor granted to a near-degenerate joint (see
/// [`Workspace::check_row`]): its relative |κ| mismatch still has to be below this.
const MAX_FLOOR: f64 = 1e-6;
/// The largest rounding floor granted to a row made of a ratio near 1 (see
/// [`Workspace::check_scales`]): `1 - λ` carries a relative error of about `ε/(1 - λ)`,
/// which this caps where `1 - λ` is as small as [`LAMBDA_MIN`] allows.
const RATIO_FLOOR: f64 = 1e-3;
/// A segment counts as shrinking towards its input point when `1 - λ_{j-1}` and `λ_j` are
/// both below this: its rows get the floors of [`RATIO_FLOOR`]'s doc. (A single ratio near
/// 1 is a curve heading elsewhere: relaxing its rows there measured worse window
/// re-solves.)
const RATIO_NEAR_ONE: f64 = 1e-4;
/// Iterations of the classic loop used to start Newton from a cold start, one attempt each.
const CLASSIC_STARTS: [usize; 3] = [3, 1, 12];
/// Classic iterations that start the first solve of a continuation.
const CLASSIC_START: usize = 3;
/// Smallest continuation step in the homotopy parameter before an attempt is given up.
const MIN_STEP: f64 = 1e-6;
/// Iteration budget of each direct attempt before the next strategy is tried.
const ATTEMPT_BUDGET: usize = 30;
/// Shape parameters where the solver converges most reliably (measured on the drawings of
/// the εκ paper), the starts of the continuation fallbacks, tried in this order.
const A_HOMES: [f64; 4] = [0.85, 0.75, 0.95, 0.7];
/// The same for trigonometric segments, plus a start below the usual targets: their
/// solution branches coming from large `a` can fold just above `a = 0.65` (a peak moving
/// into a segment end), where the branch coming from small `a` (peak at the end) goes on.
const A_HOMES_TRIG: [f64; 4] = [0.85, 0.75, 0.95, 0.6];
/// Within this factor of the tolerance, full Newton steps are taken without the line search's
/// decrease test (the merit is at rounding noise there for very large curves).
const QUADRATIC_REGION: f64 = 1e3;
/// Chord steps (warm re-solves) must shrink the merit by this factor or Newton takes over.
const CHORD_CONTRACTION: f64 = 1e-2;
/// Chord steps after a Newton step (with its factors) must shrink the merit by this
/// factor: only where the Jacobian hardly changes any more, so they cannot lead Newton
/// astray.
const NEWTON_CHORD_CONTRACTION: f64 = 1e-4;
/// The same for the near-solution chord steps of shorter curves ([`NEWTON_CHORD_NEAR`]):
/// there a Newton step costs only a few chord steps, and one chord step that contracts the
/// merit a thousandfold is still the cheaper way on (2.6 % of the bear's κ instructions
/// against `1e-4`; its εκ solve takes the same steps).
const NEAR_CHORD_CONTRACTION: f64 = 1e-3;
/// Chord steps follow every Newton step on curves with at least this many segments, where
/// assembling and factoring dominate (a chord step costs about a quarter of a Newton step
/// there). Shorter curves take them only near the solution ([`NEWTON_CHORD_NEAR`]): from
/// farther away the saving is small, and the different path through the iterations can
/// end on another solution branch.
const NEWTON_CHORD_MIN_BLOCKS: usize = 256;
/// Shorter curves follow a Newton step with chord steps once the step has brought the
/// residual below this (relative to the drawing size). That close, the chord steps (each
/// must contract the merit by [`NEAR_CHORD_CONTRACTION`], or Newton takes over again)
/// reach the solution Newton would, and the assembly and factorization of the last Newton
/// step or two are saved: 10 % of the bear's κ instructions, 14 % of its εκ ones. With the
/// extrapolated classic start, 3e-5 measured best on the bear (1e-4, 3e-4 and 1e-5 more
/// instructions) and on the 109 drawing curves (fewer iterations for every scheme).
const NEWTON_CHORD_NEAR: f64 = 3e-5;
/// At most this many chord steps per warm re-solve.
const MAX_CHORD: usize = 12;
/// A full Newton step that leaves more than this fraction of the merit is followed by a trial
/// of the same step again (kept if it lowers the merit further). Where the Newton model
/// undershoots, as on a stiff curve whose peak heads for a segment end while its λ shrinks
/// by a near-constant factor per step, this takes two steps' progress for one factorization.
/// Measured on the bear: 0.25 and 0.1 the same, 0.5 and 0.05 worse; doubling again more
/// than once gained nothing.
const EXPAND_RATIO: f64 = 0.25;
/// Least cosine between the last two classic steps for [`Workspace::extrapolate`].
const EXTRAPOLATE_COSINE: f64 = 0.9;
/// Newton budget of one continuation step.
const STEP_BUDGET: usize = 16;
/// Accuracy of `t` in the classic loop's root solve: Newton refines it afterwards, so the
/// start-up iterations need not resolve it to the last digit.
const PEAK_T_TOLERANCE: f64 = 1e-10;
/// Accuracy of `t` for quadratic segments, whose peak is the root of a cubic: to rounding.
const QUADRATIC_PEAK_TOLERANCE: f64 = 1e-14;
/// The same in the classic iterations that start the first Newton attempt of a cold solve.
/// The root solve stops once a Newton correction is below this, after applying it, so where
/// it converges quadratically `t` is still accurate to about the square of this; where it
/// does not, Newton refines `t` anyway: a start needs no more. (1e-8 in place of the full
/// tolerance took 13 % off the bear's εκ solve, 1e-2 in place of 1e-8 a further 10 %, at a
/// few more Newton and chord steps. The fallback attempts keep the tighter tolerances: on
/// hostile input their path is sensitive to every digit of the start.)
const START_PEAK_T_TOLERANCE: f64 = 1e-2;
/// The same for curves of [`NEWTON_CHORD_MIN_BLOCKS`] segments or more: their re-solves
/// after a small move work at the rounding floor of thousands of rows, and a smooth
/// 2 000-point loop started from the looser tolerance's solution stopped at 1.6 times
/// the tolerance.
const LONG_START_PEAK_T_TOLERANCE: f64 = 1e-8;
/// Iteration cap of the 1-D root solve for `t` in the classic loop.
const ROOT_ITERATIONS: usize = 60;
/// A Newton step that lands `t` within this of an end of `[0, 1]` is taken in full, `t`
/// clamped to the end: a peak forced to a segment end is reached in one step, not approached
/// at the rate of the step-to-bound factor.
const T_LANDING: f64 = 1e-9;

/// Whether a joint ratio is usable after a step: inside `(0, 1]` (1 up to rounding, for the
/// fixed last ratio of open curves).
#[inline]
fn lambda_valid(lam: f64) -> bool {
    lam > 0.0 && lam < 1.0 + 1e-15
}

/// Whether a step `dl` pushes ratio `j` further out of its range where it sits at its bound
/// ([`LAMBDA_MIN`] from 0 or 1) as part of a segment collapsing onto its input point (see
/// [`Joint::collapsed`]): `λ_j → 1` with `λ_{j+1} → 0` (the next segment collapses), or `λ_j → 0`
/// with `λ_{j-1} → 1` (this one does). Such a ratio is held where it is and the rest of the
/// step is taken: cutting every step to keep it inside would stall Newton there. A ratio at
/// its bound without the partner (a curve heading elsewhere) is not held. Indices wrap
/// (the fixed last ratio of an open curve, exactly 1, is never held).
#[inline(always)]
fn pinned<const D: usize>(st: &State<D>, j: usize, dl: f64) -> bool {
    let l = st.lam[j];
    if l > 2.0 * LAMBDA_MIN && l < 1.0 - 2.0 * LAMBDA_MIN {
        return false;
    }
    pinned_at_bound(st, j, dl)
}

/// [`pinned`] for a ratio at a bound.
#[cold]
fn pinned_at_bound<const D: usize>(st: &State<D>, j: usize, dl: f64) -> bool {
    let lam = &st.lam;
    let n = lam.len();
    let l = lam[j];
    let next = |i: usize| if i + 1 == n { 0 } else { i + 1 };
    let prev = |i: usize| if i == 0 { n - 1 } else { i - 1 };
    // The segment that collapses, and its control polygon's turn.
    let corner = |i: usize| {
        Joint::of(sub(st.c[i], st.c[prev(i)]), sub(st.c[next(i)], st.c[i])).turn_within(STRAIGHTISH)
    };
    if dl > 0.0 && (1.0 - 2.0 * LAMBDA_MIN..1.0).contains(&l) {
        lam[next(j)] <= PARTNER && corner(next(j))
    } else if dl < 0.0 && l <= 2.0 * LAMBDA_MIN {
        lam[prev(j)] >= 1.0 - PARTNER && corner(j)
    } else {
        false
    }
}

/// The largest sine of the control polygon's turn at a segment still counted as shrinking
/// towards its point (see [`Joint::turn_within`]): the polygon of a segment collapsing at
/// an inflection turns by `O(1 - λ)` (see [`Joint::collapsed`]); a segment shrinking at a
/// real corner is a curve heading to another solution.
const STRAIGHTISH: f64 = 1e-4;

/// How close to its bound the partner of a held ratio must be (see [`pinned`]).
const PARTNER: f64 = 1e-6;

#[inline]
fn sub<const D: usize>(a: [f64; D], b: [f64; D]) -> [f64; D] {
    core::array::from_fn(|k| a[k] - b[k])
}

#[inline]
fn dot<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    (0..D).map(|k| a[k] * b[k]).sum()
}

#[inline]
pub(crate) fn lerp<const D: usize>(a: [f64; D], b: [f64; D], t: f64) -> [f64; D] {
    core::array::from_fn(|k| a[k] + t * (b[k] - a[k]))
}

/// The area of the triangle `a b c`, regularized, with its gradient with respect to `a` and
/// `c` (that for `b` is minus their sum). Computed from the cross product of `a - b` and
/// `c - b` (scalar in 2D, vector in 3D): its relative rounding error grows like `ε/θ` for a
/// thin triangle of angle `θ`, where the Gram determinant `|u|²|v|² - (u·v)²` would give
/// `ε/θ²`.
#[inline]
fn triangle<const D: usize>(a: [f64; D], b: [f64; D], c: [f64; D]) -> (f64, [f64; D], [f64; D]) {
    let u = sub(a, b);
    let v = sub(c, b);
    // x = u × v as up to three components; ∂|x|²/∂u = 2 v × x, ∂|x|²/∂v = 2 x × u.
    let (x, gu, gv): ([f64; 3], [f64; 3], [f64; 3]) = if D == 2 {
        let z = u[0] * v[1] - u[1] * v[0];
        (
            [0.0, 0.0, z],
            [v[1] * z, -v[0] * z, 0.0],
            [-u[1] * z, u[0] * z, 0.0],
        )
    } else {
        let (u3, v3) = (
            [u[0], u[1], u.get(2).copied().unwrap_or(0.0)],
            [v[0], v[1], v.get(2).copied().unwrap_or(0.0)],
        );
        let x = cross3(u3, v3);
        (x, cross3(v3, x), cross3(x, u3))
    };
    let g = x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + EPS_GRAM;
    let t2 = g.sqrt(); // twice the area
                       // dT = d|x|² / (4 · 2T)
    let f = 1.0 / (2.0 * t2);
    (
        0.5 * t2,
        core::array::from_fn(|k| f * gu[k]),
        core::array::from_fn(|k| f * gv[k]),
    )
}

#[inline]
fn cross3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The cyclic index `i mod n` for `-n ≤ i < 2n` (the stencils reach at most two blocks
/// away, and closed curves have at least three), without a division.
#[inline(always)]
fn wrap(i: isize, n: usize) -> usize {
    let n = n as isize;
    debug_assert!(i >= -n && i < 2 * n);
    (if i < 0 {
        i + n
    } else if i >= n {
        i - n
    } else {
        i
    }) as usize
}

/// The data of one solve: targets, shapes and topology, in normalized coordinates.
#[derive(Clone, Debug)]
pub(crate) struct Problem<const D: usize> {
    /// Closed curve (cyclic indices) or open (ghost ends).
    pub closed: bool,
    /// The points the segments must peak at, one per unknown block.
    pub p: Vec<[f64; D]>,
    /// Open curves: the first and last input points.
    pub ghost: [[f64; D]; 2],
    /// The segment basis of each block.
    pub basis: Vec<Basis>,
    /// A prescribed tangent per block (empty: none anywhere; see [`Tangent`]).
    pub tangents: Vec<Option<Tangent<D>>>,
}

/// The unknowns.
#[derive(Debug, Default)]
pub(crate) struct State<const D: usize> {
    pub c: Vec<[f64; D]>,
    pub lam: Vec<f64>,
    pub t: Vec<f64>,
}

impl<const D: usize> Clone for State<D> {
    fn clone(&self) -> Self {
        State {
            c: self.c.clone(),
            lam: self.lam.clone(),
            t: self.t.clone(),
        }
    }

    /// Copies into the existing buffers (the derived `clone_from` would allocate new ones):
    /// the solver copies states between iterations.
    fn clone_from(&mut self, source: &Self) {
        self.c.clone_from(&source.c);
        self.lam.clone_from(&source.lam);
        self.t.clone_from(&source.t);
    }
}

impl<const D: usize> State<D> {
    /// The middle control point `c_i`, `i` taken cyclically for closed curves; for open ones
    /// `c_{-1}` and `c_n` are the first and last input points.
    #[inline]
    pub(crate) fn control(&self, prob: &Problem<D>, i: isize) -> [f64; D] {
        let n = self.t.len();
        if prob.closed {
            self.c[wrap(i, n)]
        } else if i < 0 {
            prob.ghost[0]
        } else if i as usize >= n {
            prob.ghost[1]
        } else {
            self.c[i as usize]
        }
    }

    /// The joint ratio `λ_i`, `i` taken cyclically for closed curves; for open ones
    /// `λ_{-1} = 0` and `λ_{n-1} = λ_n = 1` (the ends are the input points).
    #[inline]
    pub(crate) fn ratio(&self, prob: &Problem<D>, i: isize) -> f64 {
        let n = self.t.len();
        if prob.closed {
            self.lam[wrap(i, n)]
        } else if i < 0 {
            0.0
        } else if i as usize >= n {
            1.0
        } else {
            self.lam[i as usize]
        }
    }

    /// The three defining points of segment `j`: `c_{j,0} = lerp(c_{j-1}, c_j, λ_{j-1})`,
    /// `c_j`, `c_{j,2} = lerp(c_j, c_{j+1}, λ_j)` (seed 000 eq. 7).
    #[inline]
    pub(crate) fn segment(&self, prob: &Problem<D>, j: usize) -> [[f64; D]; 3] {
        let j = j as isize;
        let c = self.control(prob, j);
        [
            lerp(self.control(prob, j - 1), c, self.ratio(prob, j - 1)),
            c,
            lerp(c, self.control(prob, j + 1), self.ratio(prob, j)),
        ]
    }
}

/// The ingredients of the G2 condition at joint `j` (seed 000 eqs. 8–10):
/// `X = k_j (1-λ_{j-1}) T_j` and `Y = k_{j+1} λ_{j+1} T_{j+1}` with the end coefficients `k`
/// and the triangles `T_j = Δ(c_{j-1}, c_j, c_{j+1})`, `T_{j+1} = Δ(c_j, c_{j+1}, c_{j+2})`
/// (areas with their gradients, see [`triangle`]). G2 holds when `(1-λ_j)² X = λ_j² Y`.
#[derive(Clone, Copy)]
struct JointTerms<const D: usize> {
    k0: f64,
    k1: f64,
    tj: (f64, [f64; D], [f64; D]),
    tj1: (f64, [f64; D], [f64; D]),
    x: f64,
    y: f64,
}

/// A triangle's area with its gradient, as [`triangle`] gives them.
type Tri<const D: usize> = (f64, [f64; D], [f64; D]);

impl<const D: usize> JointTerms<D> {
    /// The terms of joint `j`. `carry` passes a triangle from one block to the next in a
    /// pass over consecutive blocks: block `j`'s `T_{j+1}` is block `j + 1`'s `T_j`, the
    /// same three control points in the same order. It holds `T_j` if known (taken), and
    /// receives `T_{j+1}`.
    #[inline(always)]
    fn new(prob: &Problem<D>, j: usize, l: &Local<D>, carry: &mut Option<Tri<D>>) -> Self {
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

/// The limits of [`Workspace::follow`]: the iteration budget and the smallest step.
#[derive(Clone, Copy, Debug)]
struct Homotopy {
    max_iterations: usize,
    min_step: f64,
    /// Newton budget of one step.
    step_budget: usize,
}

/// What a solve reports.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Outcome {
    pub iterations: usize,
    pub newton_steps: usize,
    pub converged: bool,
    pub residual: f64,
}

/// The variables a block equation depends on.
#[derive(Clone, Copy)]
struct Local<const D: usize> {
    cm: [f64; D],
    c0: [f64; D],
    c1: [f64; D],
    c2: [f64; D],
    lm: f64,
    l0: f64,
    l1: f64,
    t: f64,
}

/// The linear system of one Newton step: banded for open curves, bordered banded for closed
/// ones, dense when small, and cut in two halves and a border when long ([`Split`]).
#[derive(Clone, Debug, Default)]
struct Linear {
    mode: LinearMode,
    band: BandLu,
    bord: BorderedLu,
    dense: DenseLu,
    split: SplitLu,
    /// How the blocks are cut in [`LinearMode::Split`].
    cut: Option<Split>,
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

/// Curves of this many blocks or more are solved in two halves (see [`Split`]).
pub(crate) const SPLIT_MIN_BLOCKS: usize = 2048;

/// The length from which curves are cut ([`SPLIT_MIN_BLOCKS`]; the unit tests lower it to
/// cut short curves).
#[cfg(not(test))]
fn split_min() -> usize {
    SPLIT_MIN_BLOCKS
}

#[cfg(test)]
thread_local! {
    static SPLIT_MIN: core::cell::Cell<usize> = const { core::cell::Cell::new(SPLIT_MIN_BLOCKS) };
}

#[cfg(test)]
fn split_min() -> usize {
    SPLIT_MIN.with(|c| c.get())
}

/// How the blocks of a long curve are cut: the first half `0..m`, a separator of two blocks
/// `m..m + 2`, the second half `m + 2..end`, and the tail `end..n` (the two blocks that
/// close a closed curve; empty for an open one). The blocks of a half touch only their own
/// half and the border (separator and tail), so the halves are worked on side by side.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Split {
    m: usize,
    end: usize,
    n: usize,
}

impl Split {
    /// The cut of `n` blocks, if the curve is long enough to be cut.
    pub(crate) fn of(closed: bool, n: usize) -> Option<Split> {
        (n >= split_min().max(8)).then(|| Split {
            m: n / 2,
            end: if closed { n - 2 } else { n },
            n,
        })
    }

    /// Where the block ranges of [`ranges`](Self::ranges) meet.
    fn cuts(&self) -> [usize; 3] {
        [self.m, self.m + 2, self.end]
    }

    /// The block ranges: first half, separator, second half, tail.
    fn ranges(&self) -> [core::ops::Range<usize>; 4] {
        [
            0..self.m,
            self.m..self.m + 2,
            self.m + 2..self.end,
            self.end..self.n,
        ]
    }

    /// `f` on each of the four pieces of work (first half, separator, second half, tail):
    /// the halves side by side, then the border pieces; the results in the pieces' order.
    fn each<T: Send, R: Send>(pieces: [T; 4], f: impl Fn(T) -> R + Sync) -> [R; 4] {
        let [p0, p1, p2, p3] = pieces;
        let (r0, r2) = join(|| f(p0), || f(p2));
        let r1 = f(p1);
        let r3 = f(p3);
        [r0, r1, r2, r3]
    }
}

/// A block's condensed Jacobian: `jl[row][offset][variable]`, the stencil blocks `j - 1 ..=
/// j + 2` as offsets `0..4`.
type BlockJacobian<const B: usize> = [[[f64; B]; 4]; B];

/// Add the first `rows` rows of a condensed block Jacobian (variables `0..rows` of each
/// stencil block) at row `row0`, in the columns of `columns`, through `add(row, column, v)`.
#[inline(always)]
fn scatter<const B: usize>(
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

/// `s` cut at `cuts` (ascending) into four pieces.
fn split4<T>(s: &mut [T], [a, b, c]: [usize; 3]) -> [&mut [T]; 4] {
    let (s0, rest) = s.split_at_mut(a);
    let (s1, rest) = rest.split_at_mut(b - a);
    let (s2, s3) = rest.split_at_mut(c - b);
    [s0, s1, s2, s3]
}

/// Systems up to this order are solved densely (a few small closed curves are the common
/// case in drawings; the bordered solve only pays off above that).
const DENSE_ORDER: usize = 24;

impl Linear {
    fn reset(&mut self, closed: bool, n: usize, b: usize) {
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
    fn add_block<const B: usize>(
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

    fn factor(&mut self) -> bool {
        match self.mode {
            LinearMode::Dense => self.dense.factor(),
            LinearMode::Bordered => self.bord.factor(),
            LinearMode::Band => self.band.factor(),
            LinearMode::Split => self.split.factor(),
        }
    }

    fn solve(&mut self, x: &mut [f64]) {
        match self.mode {
            LinearMode::Dense => self.dense.solve(x),
            LinearMode::Bordered => self.bord.solve(x),
            LinearMode::Band => self.band.solve(x),
            LinearMode::Split => self.split.solve(x),
        }
    }
}

/// Solver options in normalized units.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Settings {
    pub tolerance: f64,
    pub max_iterations: usize,
    /// Follow each Newton step with chord steps while they contract well (cold solves of
    /// long curves gain most; warm re-solves do their own chord steps first).
    pub newton_chords: bool,
}

/// Reusable solver state: the unknowns, a trial copy for the line search, and all buffers.
/// After the first solve of a given size nothing is allocated.
#[derive(Clone, Debug, Default)]
pub(crate) struct Workspace<const D: usize, const B: usize> {
    pub state: State<D>,
    trial: State<D>,
    res: Vec<[f64; B]>,
    /// The residuals measured by the convergence test (`res`, with the G2 row replaced by
    /// the relative |κ| mismatch).
    check: Vec<[f64; B]>,
    scale: Vec<[f64; 2]>,
    /// `res`, `check` and `scale` of the trial state of the line search: swapped in with it
    /// when it is accepted, so that a step landing within the tolerance is recognized
    /// without assembling the Jacobian there.
    trial_res: Vec<[f64; B]>,
    trial_check: Vec<[f64; B]>,
    trial_scale: Vec<[f64; 2]>,
    /// What the line search measured of its trial state besides `trial_res` (curves cut in
    /// no halves), and of the state it was swapped in as: see [`Workspace::refreeze`].
    trial_raw: Vec<Raw>,
    raw: Vec<Raw>,
    step: Vec<f64>,
    /// Right-hand side and solution of the condensed system (`B - 1` unknowns per block).
    reduced: Vec<f64>,
    /// Per block, what eliminating `t_j` left behind (see [`Condensed`]).
    cond: Vec<Condensed<B>>,
    lin: Linear,
    /// What `lin` holds (for chord steps), and the row scales it was assembled with.
    lin_state: LinState,
    fact_scale: Vec<[f64; 2]>,
    tri: [Vec<f64>; 3],
    tri_d: Vec<[f64; D]>,
    /// The extrapolation of the classic loop ([`Workspace::extrapolate`]): the unknowns
    /// before the last classic iteration and the step of the one before, `B` per block.
    extra: [Vec<f64>; 2],
    scratch: TriScratch,
    /// The end terms of the last basis the classic loop met (a function of the basis
    /// alone, so they stay valid from one iteration and solve to the next).
    ends: Option<EndTerms>,
    /// The window of local re-solves ([`window`]) and the edit the next warm re-solve
    /// follows.
    window: window::Window<B>,
    edit: Option<Edit>,
}

impl<const D: usize, const B: usize> Workspace<D, B> {
    const CHECK: () = assert!(B == D + 2, "block size must be D + 2");

    /// Number of unknown blocks.
    fn n(&self) -> usize {
        self.state.t.len()
    }

    /// Record the unknowns before one of the last two classic iterations for
    /// [`extrapolate`](Self::extrapolate): before the second to last (`first`), the
    /// iterate; before the last, also the step from it.
    fn record_iterate(&mut self, first: bool) {
        let [prev, step] = &mut self.extra;
        let st = &self.state;
        let n = st.t.len();
        if first {
            prev.resize(n * B, 0.0);
            step.resize(n * B, 0.0);
        }
        // (The first call's step, from whatever `prev` held, is overwritten by the second:
        // one loop for both measured fewer instructions than a separate copy.)
        let blocks = prev.chunks_exact_mut(B).zip(step.chunks_exact_mut(B));
        for (j, (p, f)) in blocks.enumerate() {
            let x = Self::unknowns(st, j);
            for k in 0..B {
                f[k] = x[k] - p[k];
                p[k] = x[k];
            }
        }
    }

    /// The unknowns of block `j`: `c_j`, `λ_j`, `t_j`.
    #[inline(always)]
    fn unknowns(st: &State<D>, j: usize) -> [f64; B] {
        let (c, lam, t) = (st.c[j], st.lam[j], st.t[j]);
        core::array::from_fn(|k| match k {
            k if k < D => c[k],
            k if k == D => lam,
            _ => t,
        })
    }

    /// Extrapolate the last two classic steps `f₁`, `f₂` (Anderson acceleration of depth
    /// one, or a secant step along the iteration): `x ← x − γ f₂` with `γ` minimizing
    /// `|f₂ − γ (f₂ − f₁)|`. Where the classic loop contracts each step by a near-constant
    /// factor `ρ` (about 0.15 on the bear's three-point curves), `γ = ρ / (ρ − 1)` jumps to
    /// the limit of that geometric sequence, and Newton starts at a residual some twenty
    /// times smaller. `λ` and `t` are kept in their ranges.
    fn extrapolate(&mut self, prob: &Problem<D>) {
        let [prev, f1] = &self.extra;
        let st = &mut self.state;
        let n = st.t.len();
        if prev.len() != n * B || f1.len() != n * B {
            return;
        }
        let (mut a11, mut a12, mut a22) = (0.0, 0.0, 0.0);
        for (j, (p, f1)) in prev.chunks_exact(B).zip(f1.chunks_exact(B)).enumerate() {
            let x = Self::unknowns(st, j);
            for k in 0..B {
                let f2 = x[k] - p[k];
                a11 += f1[k] * f1[k];
                a12 += f1[k] * f2;
                a22 += f2 * f2;
            }
        }
        // γ = f₂·(f₂ − f₁) / |f₂ − f₁|².
        let gamma = (a22 - a12) / (a11 - 2.0 * a12 + a22);
        // Only where the two steps are near parallel (cosine ≥ EXTRAPOLATE_COSINE: one mode
        // dominates, as in a geometric sequence) and contract by ρ ≤ 4/9 (γ ≥ -0.8). On the
        // bear's stiff curves, whose steps turn (cosines 0.6–0.8), extrapolating cost
        // iterations; so did a six-point εκ curve contracting by ρ ≈ 0.49 (42 iterations
        // instead of 12).
        if !(a12 >= EXTRAPOLATE_COSINE * (a11 * a22).sqrt() && (-0.8..=0.0).contains(&gamma)) {
            return;
        }
        for (j, p) in prev.chunks_exact(B).enumerate() {
            let x = Self::unknowns(st, j);
            let y: [f64; B] = core::array::from_fn(|k| x[k] - gamma * (x[k] - p[k]));
            st.c[j] = core::array::from_fn(|k| y[k]);
            if prob.closed || j + 1 < n {
                st.lam[j] = y[D].clamp(LAMBDA_MIN, 1.0 - LAMBDA_MIN);
            }
            st.t[j] = y[D + 1].clamp(0.0, 1.0);
        }
    }

    /// Allocate for `n` blocks and set the cold start: `c = p`, `λ = ½`, `t = ½`.
    pub(crate) fn cold_start(&mut self, prob: &Problem<D>) {
        #[allow(clippy::let_unit_value)]
        let _ = Self::CHECK;
        self.window.measured = false;
        let n = prob.p.len();
        let st = &mut self.state;
        st.c.clear();
        st.c.extend_from_slice(&prob.p);
        st.lam.clear();
        st.lam.resize(n, 0.5);
        if !prob.closed {
            st.lam[n - 1] = 1.0;
        }
        st.t.clear();
        st.t.resize(n, 0.5);
        self.trial.clone_from(&self.state);
        self.lin_state = LinState::Empty;
        self.window.invalidate();
    }

    /// Allocate for `prob` and start from the given unknowns (in the normalized frame), as
    /// if a solve had just ended there: the next solve starts warm from them. `false`, with
    /// a cold start instead, if they do not fit `prob` (another count, a value out of its
    /// range or not finite).
    pub(crate) fn start_at(
        &mut self,
        prob: &Problem<D>,
        c: &[[f64; D]],
        lam: &[f64],
        t: &[f64],
    ) -> bool {
        self.cold_start(prob);
        let n = prob.p.len();
        let fits = c.len() == n
            && lam.len() == n
            && t.len() == n
            && c.iter().flatten().all(|x| x.is_finite())
            && lam.iter().all(|l| (0.0..=1.0).contains(l))
            && t.iter().all(|t| (0.0..=1.0).contains(t))
            && (prob.closed || lam[n - 1] == 1.0);
        if fits {
            let st = &mut self.state;
            st.c.copy_from_slice(c);
            st.lam.copy_from_slice(lam);
            st.t.copy_from_slice(t);
            self.trial.clone_from(&self.state);
        }
        self.edit = None;
        fits
    }

    /// Before a warm re-solve changes the problem: if the stored factors are stale, assemble
    /// the Jacobian at the current state, the solution of `prob` (it does not depend on the
    /// target points, only on the unknowns).
    pub(crate) fn refresh_jacobian(&mut self, prob: &Problem<D>, tol: f64) {
        let n = self.n();
        if self.lin_state == LinState::Stale && prob.p.len() == n && self.res.len() == n {
            self.lin.reset(prob.closed, n, B - 1);
            self.assemble(prob, tol);
            self.fact_scale.clone_from(&self.scale);
            self.lin_state = LinState::Assembled;
        }
    }

    /// Forget the stored factorization (the problem's structure or shapes changed).
    pub(crate) fn invalidate(&mut self) {
        self.lin_state = LinState::Empty;
        self.window.invalidate();
    }

    /// The edit the next warm re-solve follows (`None`: points moved all over, or not at
    /// all); `rescaled` if the normalization changed scale, which the window's linearization
    /// does not carry over; `reframed` if it changed at all, which moves every control point.
    pub(crate) fn set_edit(&mut self, edit: Option<Edit>, rescaled: bool, reframed: bool) {
        self.edit = edit;
        if rescaled {
            self.window.invalidate();
        }
        if reframed {
            // Every control point moved in the normalized frame.
            self.window.measured = false;
        }
    }

    /// Re-solve from the current state after a small change of the targets: chord steps with
    /// the Jacobian factored by the previous solve while they contract the residual by
    /// [`CHORD_CONTRACTION`] or better, then Newton.
    pub(crate) fn solve_warm(&mut self, prob: &Problem<D>, set: &Settings) -> Outcome {
        let n = prob.p.len();
        let mut out = Outcome::default();
        // Whether the residual buffers still hold the measure of the state (a window
        // re-solve's, which only this re-solve's own window steps can renew).
        let measured = core::mem::take(&mut self.window.measured);
        // (Tangent rows are not frozen: no window and no chord steps with them.)
        let plain = prob.tangents.is_empty();
        if let Some(edit) = self.edit.take().filter(|_| plain) {
            if let Some(local) = self.solve_window(prob, set, edit, measured) {
                if local.converged {
                    return local;
                }
                out.iterations = local.iterations;
                out.newton_steps = local.newton_steps;
            }
        }
        if self.lin_state == LinState::Assembled && self.fact_scale.len() == n {
            // The Jacobian at the previous solution, assembled by its convergence check.
            self.lin_state = if self.lin.factor() {
                LinState::Factored
            } else {
                LinState::Empty
            };
        }
        if plain
            && self.lin_state == LinState::Factored
            && self.fact_scale.len() == n
            && self.res.len() == n
            && self.chord_steps(prob, set, CHORD_CONTRACTION, None, false, &mut out)
        {
            return out;
        }
        let rest = self.solve(
            prob,
            &Settings {
                max_iterations: set.max_iterations.saturating_sub(out.iterations),
                newton_chords: false,
                ..*set
            },
            0,
            false,
        );
        Outcome {
            iterations: out.iterations + rest.iterations,
            ..rest
        }
    }

    /// Chord steps from the current state with the stored factorization while each one
    /// shrinks the merit by `contraction` or better; the state is left at the last accepted
    /// step. `start` is the merit of the current state with the factorization's row scales
    /// where `res` and `check` already hold them (measured here otherwise). With `reuse`
    /// (only with `start`), the convergence test's floor scales are those of the current
    /// state, kept in `raw`. Counts the steps in `out`; `true` (with `out` filled in) if
    /// converged.
    fn chord_steps(
        &mut self,
        prob: &Problem<D>,
        set: &Settings,
        contraction: f64,
        start: Option<f64>,
        reuse: bool,
        out: &mut Outcome,
    ) -> bool {
        let reuse = reuse && start.is_some();
        self.trial.clone_from(&self.state);
        let mut phi = match start {
            Some(phi) => phi,
            None => self.residual_frozen(prob, set.tolerance, false),
        };
        for _ in 0..MAX_CHORD {
            if self.max_residual() <= set.tolerance {
                out.converged = true;
                out.residual = self.max_residual();
                return true;
            }
            if out.iterations >= set.max_iterations {
                break;
            }
            out.iterations += 1;
            if !self.condensed_step() || !self.step_to_trial(1.0) {
                break;
            }
            core::mem::swap(&mut self.state, &mut self.trial);
            let phi_new = self.residual_frozen(prob, set.tolerance, reuse);
            if !(phi_new <= contraction * phi) {
                if self.max_residual() <= set.tolerance {
                    // Within the tolerance, with the merit at its rounding noise.
                    out.converged = true;
                    out.residual = self.max_residual();
                    return true;
                }
                // Not contracting: undo, and Newton takes over (it measures the state
                // again).
                core::mem::swap(&mut self.state, &mut self.trial);
                break;
            }
            phi = phi_new;
        }
        false
    }

    /// `trial = state + scale · step` (`t` clamped to `[0, 1]`); `false` if a `λ` leaves
    /// `(0, 1]`.
    fn step_to_trial(&mut self, scale: f64) -> bool {
        let n = self.n();
        let (st, tr) = (&self.state, &mut self.trial);
        let (c, lam, t) = (&mut tr.c[..n], &mut tr.lam[..n], &mut tr.t[..n]);
        if n < split_min() {
            return Self::step_from(st, 0, &self.step, scale, (c, lam, t));
        }
        // Halves (element-wise work: any cut gives the same result).
        let h = n / 2;
        let (c0, c1) = c.split_at_mut(h);
        let (l0, l1) = lam.split_at_mut(h);
        let (t0, t1) = t.split_at_mut(h);
        let (s0, s1) = self.step.split_at(h * B);
        let (ok0, ok1) = join(
            || Self::step_from(st, 0, s0, scale, (c0, l0, t0)),
            || Self::step_from(st, h, s1, scale, (c1, l1, t1)),
        );
        ok0 && ok1
    }

    /// [`step_to_trial`](Self::step_to_trial) for the blocks `j0..j0 + t.len()`.
    #[allow(clippy::type_complexity)]
    fn step_from(
        st: &State<D>,
        j0: usize,
        step: &[f64],
        scale: f64,
        (c, lam, t): (&mut [[f64; D]], &mut [f64], &mut [f64]),
    ) -> bool {
        let mut ok = true;
        let blocks = step.chunks_exact(B).zip(c).zip(lam).zip(t).enumerate();
        for (i, (((s, c), lam), t)) in blocks {
            let j = j0 + i;
            *c = core::array::from_fn(|k| st.c[j][k] + scale * s[k]);
            *lam = if pinned(st, j, s[D]) {
                st.lam[j]
            } else {
                st.lam[j] + scale * s[D]
            };
            *t = (st.t[j] + scale * s[D + 1]).clamp(0.0, 1.0);
            ok &= lambda_valid(*lam);
        }
        ok
    }

    /// The residual (and convergence measures) of the current state with the row scales of
    /// the stored factorization; returns the merit.
    fn residual_frozen(&mut self, prob: &Problem<D>, tol: f64, reuse: bool) -> f64 {
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
    fn residuals<const FROZEN: bool>(
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
    fn residuals_from<const FROZEN: bool>(
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
    fn refreeze(&mut self) -> f64 {
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

    /// Exchange the residual buffers (`res`, `check`, `scale`) with the trial ones.
    fn swap_trial_residuals(&mut self) {
        core::mem::swap(&mut self.res, &mut self.trial_res);
        core::mem::swap(&mut self.check, &mut self.trial_check);
        core::mem::swap(&mut self.scale, &mut self.trial_scale);
        core::mem::swap(&mut self.raw, &mut self.trial_raw);
    }

    /// Size the per-block buffers of the Newton steps for `n` blocks (no-op once sized).
    fn size_buffers(&mut self, n: usize) {
        self.res.resize(n, [0.0; B]);
        self.check.resize(n, [0.0; B]);
        self.scale.resize(n, [1.0; 2]);
        self.trial_res.resize(n, [0.0; B]);
        self.trial_check.resize(n, [0.0; B]);
        self.trial_scale.resize(n, [1.0; 2]);
        self.trial_raw.resize_with(n, Raw::default);
        self.raw.resize_with(n, Raw::default);
        self.step.resize(n * B, 0.0);
        self.cond.resize_with(n, Condensed::default);
    }

    /// Solve from the current state (a cold start or a previous solution), after `classic`
    /// iterations of the classic loop; with `loose`, those solve for `t` only to
    /// [`START_PEAK_T_TOLERANCE`] (the first attempt of a cold solve: the fallbacks start as
    /// carefully as they always did).
    pub(crate) fn solve(
        &mut self,
        prob: &Problem<D>,
        set: &Settings,
        classic: usize,
        loose: bool,
    ) -> Outcome {
        let n = prob.p.len();
        debug_assert_eq!(self.n(), n);
        self.trial.clone_from(&self.state);
        self.size_buffers(n);
        let mut out = Outcome::default();
        let classic = classic.min(set.max_iterations);
        // The first attempt of a cold solve extrapolates its classic iterations.
        let extrapolate = loose && classic >= 2;
        for i in 0..classic {
            if extrapolate && i + 2 >= classic {
                self.record_iterate(i + 2 == classic);
            }
            self.classic_iteration(prob, loose);
            out.iterations += 1;
        }
        if extrapolate {
            self.extrapolate(prob);
        }
        loop {
            self.lin.reset(prob.closed, n, B - 1);
            let phi = self.assemble(prob, set.tolerance);
            self.lin_state = LinState::Assembled;
            self.fact_scale.clone_from(&self.scale);
            out.residual = self.max_residual();
            if out.residual <= set.tolerance {
                out.converged = true;
                return out;
            }
            if out.iterations >= set.max_iterations {
                return out;
            }
            out.iterations += 1;
            if !phi.is_finite() || !self.newton_step(prob, phi, set.tolerance) {
                self.classic_iteration(prob, false);
            } else {
                out.newton_steps += 1;
                out.residual = self.max_residual();
                if out.residual <= set.tolerance {
                    // The step's line search measured the new state: converged without
                    // assembling the Jacobian there (a warm re-solve from here assembles it).
                    out.converged = true;
                    self.lin_state = LinState::Stale;
                    return out;
                }
                if !set.newton_chords
                    || (n < NEWTON_CHORD_MIN_BLOCKS && !(out.residual <= NEWTON_CHORD_NEAR))
                {
                    continue;
                }
                // Chord steps with this factorization while they contract well: much
                // cheaper than assembling and factoring again on long curves. Their first
                // residual is the line search's, rescaled (curves cut in no halves).
                let start = (n < split_min()).then(|| self.refreeze());
                // A Newton step that landed near the solution: the convergence test's floor
                // scales of its landing point (in `raw`) serve the chord steps, which move
                // the control points by about the residual, far less than the floors' own
                // precision (the scales change the test only where a floor nears the
                // tolerance).
                let reuse = out.residual <= NEWTON_CHORD_NEAR;
                let contraction = if n < NEWTON_CHORD_MIN_BLOCKS {
                    NEAR_CHORD_CONTRACTION
                } else {
                    NEWTON_CHORD_CONTRACTION
                };
                if self.chord_steps(prob, set, contraction, start, reuse, &mut out) {
                    // The factors may come from an early iterate: a warm re-solve from
                    // here assembles the Jacobian at its own start instead.
                    self.lin_state = LinState::Stale;
                    return out;
                }
            }
        }
    }

    /// Solve from a cold start: the [`cascade`](Self::cascade) of direct attempts and
    /// shape continuations, then continuation from smoothed input points
    /// ([`points`]) where all of those fail. The total iteration count is reported, and the
    /// best state found is kept if nothing converges.
    pub(crate) fn solve_cold(
        &mut self,
        prob: &Problem<D>,
        set: &Settings,
        scratch: &mut Problem<D>,
    ) -> Outcome {
        let out = self.cascade(prob, set, scratch, true);
        if out.converged || out.iterations >= set.max_iterations {
            return out;
        }
        self.point_continuation(prob, set, scratch, out)
    }

    /// Newton after a few classic iterations (3, 1, then 12), then continuation in the
    /// shape parameters from each of [`A_HOMES`]. Every attempt is capped; the total
    /// iteration count is reported, and the best state found is kept if none converges.
    fn cascade(
        &mut self,
        prob: &Problem<D>,
        set: &Settings,
        scratch: &mut Problem<D>,
        shapes: bool,
    ) -> Outcome {
        let mut total = 0;
        let mut best: Option<(Outcome, State<D>)> = None;
        let keep = |ws: &Self, out: Outcome, best: &mut Option<(Outcome, State<D>)>| {
            if best.as_ref().map_or(true, |b| out.residual < b.0.residual) {
                *best = Some((out, ws.state.clone()));
            }
        };
        for (attempt, classic) in CLASSIC_STARTS.into_iter().enumerate() {
            // One segment between fixed ends (an open curve through three points): its
            // control point and λ are fixed by the ends, and one classic iteration solves
            // for `t` and the control point directly; more repeat it.
            let single = !prob.closed && prob.p.len() == 1;
            let classic = if single { classic.min(1) } else { classic };
            let budget = Settings {
                max_iterations: ATTEMPT_BUDGET.min(set.max_iterations.saturating_sub(total)),
                ..*set
            };
            self.cold_start(prob);
            let mut out = self.solve(prob, &budget, classic, attempt == 0 && !single);
            total += out.iterations;
            out.iterations = total;
            if out.converged {
                return out;
            }
            keep(self, out, &mut best);
        }
        let homes: &[f64] = match prob.basis.first() {
            _ if !shapes => &[],
            Some(Basis::Trig(_)) => &A_HOMES_TRIG,
            _ => &A_HOMES,
        };
        for &home in homes {
            if total >= set.max_iterations {
                break;
            }
            let out = self.continuation(prob, set, scratch, total, home);
            total = out.iterations;
            if out.converged {
                return out;
            }
            keep(self, out, &mut best);
        }
        match best {
            Some((mut out, st)) => {
                self.state = st;
                out.iterations = total;
                out
            }
            None => Outcome {
                iterations: total,
                residual: f64::INFINITY,
                ..Outcome::default()
            },
        }
    }

    /// Continuation from the shape `home` to the target shapes with adaptive steps.
    fn continuation(
        &mut self,
        prob: &Problem<D>,
        set: &Settings,
        scratch: &mut Problem<D>,
        used: usize,
        home: f64,
    ) -> Outcome {
        let mut total = used;
        let mut out = Outcome::default();
        scratch.closed = prob.closed;
        scratch.ghost = prob.ghost;
        scratch.tangents.clone_from(&prob.tangents);
        scratch.p.clone_from(&prob.p);
        // Only the shapes move along the homotopy.
        let blend = |scratch: &mut Problem<D>, s: f64| {
            scratch.basis.clear();
            scratch.basis.extend(
                prob.basis
                    .iter()
                    .map(|b| b.with_a(b.a() + (1.0 - s) * (home - b.a()))),
            );
        };
        blend(scratch, 0.0);
        self.cold_start(scratch);
        // Short curves take no chord steps along the homotopy: each step's small budget
        // counts them, and the hard curves that get here need every Newton step of it.
        let budget = |total: usize, cap: usize| Settings {
            max_iterations: cap.min(set.max_iterations.saturating_sub(total)),
            newton_chords: set.newton_chords && prob.p.len() >= NEWTON_CHORD_MIN_BLOCKS,
            ..*set
        };
        let first = self.solve(
            scratch,
            &budget(total, ATTEMPT_BUDGET),
            CLASSIC_START,
            false,
        );
        total += first.iterations;
        if !first.converged {
            out.iterations = total;
            out.residual = f64::INFINITY;
            return out;
        }
        // (s = 1 exactly reproduces the shapes.)
        let steps = Homotopy {
            max_iterations: set.max_iterations,
            min_step: MIN_STEP,
            step_budget: STEP_BUDGET,
        };
        self.follow(prob, scratch, blend, budget, steps, total)
    }

    /// Follows a homotopy from `s = 0`, solved in the current state, to `s = 1`: `blend`
    /// sets `moving` to the problem at `s`; steps start at 0.25, grow by 1.5 after a
    /// converged step and halve after a failed one (back to the last solution), until `s`
    /// reaches 1, the steps shrink below `steps.min_step` or the iterations (counted from
    /// `total`, each step capped at [`STEP_BUDGET`] through `budget`) reach
    /// `steps.max_iterations`. A final polish solves `prob` itself.
    fn follow(
        &mut self,
        prob: &Problem<D>,
        moving: &mut Problem<D>,
        mut blend: impl FnMut(&mut Problem<D>, f64),
        budget: impl Fn(usize, usize) -> Settings,
        steps: Homotopy,
        mut total: usize,
    ) -> Outcome {
        let (mut s, mut ds) = (0.0f64, 0.25f64);
        let mut saved = self.state.clone();
        while s < 1.0 && total < steps.max_iterations && ds > steps.min_step {
            let s_try = (s + ds).min(1.0);
            blend(moving, s_try);
            let step = self.solve(moving, &budget(total, steps.step_budget), 0, false);
            total += step.iterations;
            if step.converged {
                s = s_try;
                saved.clone_from(&self.state);
                ds *= 1.5;
            } else {
                self.state.clone_from(&saved);
                ds *= 0.5;
            }
        }
        let fin = self.solve(prob, &budget(total, steps.step_budget), 0, false);
        Outcome {
            iterations: total + fin.iterations,
            ..fin
        }
    }

    /// Largest scaled residual component.
    fn max_residual(&self) -> f64 {
        Self::max_of(&self.check)
    }

    /// Largest component of `check` (NaN counts as infinite).
    fn max_of(check: &[[f64; B]]) -> f64 {
        // One running maximum per row of the block: independent chains. The maximum does
        // not depend on the order: long curves take halves.
        fn lanes<const B: usize>(check: &[[f64; B]]) -> f64 {
            let lanes = check.iter().fold([0.0f64; B], |mut m, r| {
                for (m, &x) in m.iter_mut().zip(r) {
                    let a = x.abs();
                    // Larger, or NaN: one comparison in the common case, where
                    // `f64::max` would also sort out NaN operands.
                    if !(a <= *m) {
                        *m = if a.is_nan() { f64::INFINITY } else { a };
                    }
                }
                m
            });
            // The lanes hold no NaN.
            lanes
                .into_iter()
                .fold(0.0, |m, x| if x > m { x } else { m })
        }
        if check.len() < split_min() {
            return lanes(check);
        }
        let (a, b) = check.split_at(check.len() / 2);
        let (a, b) = join(|| lanes(a), || lanes(b));
        a.max(b)
    }

    /// One Newton step with backtracking; `false` if no acceptable step was found.
    fn newton_step(&mut self, prob: &Problem<D>, phi: f64, tol: f64) -> bool {
        if !self.lin.factor() {
            self.lin_state = LinState::Empty;
            return false;
        }
        self.lin_state = LinState::Factored;
        if !self.condensed_step() {
            return false;
        }
        let smax = self.step_bound();
        let mut s = smax.max(0.0);
        while s > 1e-10 {
            // `s` keeps every λ inside (0, 1).
            self.step_to_trial(s);
            let phi_trial = self.trial_merit(prob, tol);
            // Near the solution (residual within QUADRATIC_REGION × tolerance) the merit is at
            // its rounding noise for large curves, and a full Newton step is reliable.
            let near =
                s == 1.0 && self.max_residual() <= QUADRATIC_REGION * tol && phi_trial.is_finite();
            if near || phi_trial <= (1.0 - 1e-4 * s) * phi {
                core::mem::swap(&mut self.state, &mut self.trial);
                self.swap_trial_residuals();
                if s == 1.0 && !near && phi_trial > EXPAND_RATIO * phi && self.step_bound() >= 1.0 {
                    // A full step that reduced the merit poorly: try going as far again.
                    if self.step_to_trial(1.0) {
                        let phi2 = self.trial_merit(prob, tol);
                        if phi2 < phi_trial {
                            core::mem::swap(&mut self.state, &mut self.trial);
                            self.swap_trial_residuals();
                        }
                    }
                }
                return true;
            }
            s *= 0.5;
        }
        false
    }

    /// The largest multiple (at most 1) of the step that keeps λ inside (0, 1) and t inside
    /// [0, 1].
    fn step_bound(&self) -> f64 {
        let n = self.n();
        let mut smax: f64 = 1.0;
        let st = &self.state;
        for j in 0..n {
            let dl = self.step[j * B + D];
            let l = st.lam[j];
            if pinned(st, j, dl) {
                // Held at its bound by `step_from` (a collapsing segment).
            } else if dl < 0.0 {
                smax = smax.min(0.99 * (l - LAMBDA_MIN) / -dl);
            } else if dl > 0.0 {
                smax = smax.min(0.99 * (1.0 - LAMBDA_MIN - l) / dl);
            }
            let dt = self.step[j * B + D + 1];
            let t = st.t[j];
            if dt < 0.0 && t + dt < -T_LANDING {
                smax = smax.min(0.999 * t / -dt + 1e-300);
            } else if dt > 0.0 && t + dt > 1.0 + T_LANDING {
                smax = smax.min(0.999 * (1.0 - t) / dt + 1e-300);
            }
        }
        smax
    }

    /// The Newton (or, with an older factorization, chord) step for the current residual:
    /// the condensed system is solved for `δc`, `δλ`, then each `δt_j` is recovered from its
    /// peak row. Fills `self.step`; `false` if it is not finite.
    fn condensed_step(&mut self) -> bool {
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

    /// Gather the variables of block `j` from `st`.
    #[inline(always)]
    fn local(prob: &Problem<D>, st: &State<D>, j: usize) -> Local<D> {
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

    /// The values the convergence test measures for one block: the interpolation residual,
    /// the relative |κ| mismatch `g2` at the joint and the peak residual. The dimensionless
    /// rows cannot be resolved below their rounding floor, so they are scaled for the
    /// tolerance to apply above that floor; interpolation keeps the tolerance as it is.
    ///
    /// The floors: coordinates are O(1) after normalization and carry rounding errors ~ε,
    /// so an edge `u` has relative error ~ε/|u|: the peak row's floor is ε/(local size). The
    /// G2 row is a ratio of triangle areas `|u × v|/2`, whose relative error is
    /// ~ε(|u| + |v|)/|u × v|: the same for a right angle, but growing as 1/sin θ at a sharp
    /// turn or a near-straight joint (capped at [`MAX_FLOOR`]).
    #[inline]
    fn check_row(r: [f64; B], g2: f64, loc: &Local<D>, tol: f64) -> [f64; B] {
        Self::check_scaled(r, g2, Self::check_scales(loc, tol))
    }

    /// [`check_row`](Self::check_row) with the scales of its G2 and peak rows given (as
    /// [`check_scales`](Self::check_scales) computes them).
    #[inline]
    fn check_scaled(r: [f64; B], g2: f64, scales: [f64; 2]) -> [f64; B] {
        let mut c = r;
        c[D] = g2 * scales[0];
        c[D + 1] *= scales[1];
        c
    }

    /// The scales [`check_row`](Self::check_row) applies to the G2 and the peak row of a
    /// block: the tolerance over each row's rounding floor, at most 1.
    #[inline(always)]
    fn check_scales(loc: &Local<D>, tol: f64) -> [f64; 2] {
        // The control polygon's edges into and out of `c_j` and out of `c_{j+1}`.
        let (a, b, e) = (
            sub(loc.c0, loc.cm),
            sub(loc.c1, loc.c0),
            sub(loc.c2, loc.c1),
        );
        let (aa, bb, ee) = (dot(a, a), dot(b, b), dot(e, e));
        let (na, nb, ne) = (aa.sqrt(), bb.sqrt(), ee.sqrt());
        let local = na + nb;
        // `(|u| + |v|)² / |u × v|²` at the joints `c_j` and `c_{j+1}`, without dividing by
        // zero; the larger one's square root is the `thin` measure.
        let thin2 = |nu: f64, nv: f64, uu: f64, vv: f64, uv: f64| {
            (nu + nv) * (nu + nv) / (uu * vv - uv * uv).max(f64::MIN_POSITIVE)
        };
        let (ab, be) = (dot(a, b), dot(b, e));
        let area = thin2(na, nb, aa, bb, ab)
            .max(thin2(nb, ne, bb, ee, be))
            .sqrt();
        let floor = ROUNDING_FLOOR / local.max(f64::MIN_POSITIVE);
        let g2_floor = floor.max((ROUNDING_FLOOR * area).min(MAX_FLOOR));
        let scales = [(tol / g2_floor).min(1.0), (tol / floor).min(1.0)];
        let (own, next) = (1.0 - loc.lm, 1.0 - loc.l0);
        if own < RATIO_NEAR_ONE || next < RATIO_NEAR_ONE {
            let joints = [
                Joint::new(na, nb, aa, bb, ab),
                Joint::new(nb, ne, bb, ee, be),
            ];
            Self::shrinking_scales(loc, tol, scales, joints, [floor, g2_floor])
        } else {
            scales
        }
    }

    /// [`check_scales`](Self::check_scales) where a ratio is near 1.
    ///
    /// A ratio near 1 is known to an absolute rounding error ~ε, so `1 - λ` to a relative
    /// one ~ε/(1 - λ). Where a segment shrinks towards its input point (`1 - λ_{j-1}` and
    /// `λ_j` both small, at a nearly straight turn of the control polygon: an inflection,
    /// [`Joint::collapsed`]) its start leg `r = (1 - λ_{j-1}) (c_j - c_{j-1})` and the G2 terms of
    /// its two joints are no more precise than that. Once it has collapsed, its peak row and
    /// both its G2 rows count as met.
    #[cold]
    fn shrinking_scales(
        loc: &Local<D>,
        tol: f64,
        scales: [f64; 2],
        [at_own, at_next]: [Joint; 2],
        [floor, g2_floor]: [f64; 2],
    ) -> [f64; 2] {
        let (own, next) = (1.0 - loc.lm, 1.0 - loc.l0);
        if at_own.collapsed(own, loc.l0, tol) {
            return [0.0, 0.0];
        }
        let shrinking = |r: f64, partner: f64, joint: Joint| {
            if r < RATIO_NEAR_ONE && partner < RATIO_NEAR_ONE && joint.turn_within(STRAIGHTISH) {
                (ROUNDING_FLOOR / r.max(f64::MIN_POSITIVE)).min(RATIO_FLOOR)
            } else {
                0.0
            }
        };
        let own_floor = shrinking(own, loc.l0, at_own);
        let next_floor = shrinking(next, loc.l1, at_next);
        if own_floor == 0.0 && next_floor == 0.0 {
            return scales;
        }
        let floor = floor.max(own_floor);
        let g2_floor = g2_floor.max(floor).max(next_floor);
        let mut scales = [(tol / g2_floor).min(1.0), (tol / floor).min(1.0)];
        if at_next.collapsed(next, loc.l1, tol) {
            scales[0] = 0.0;
        }
        scales
    }

    /// Whether block `j`'s segment has shrunk onto its input point: at most `tol` long
    /// (`(1 - λ_{j-1}) |c_j - c_{j-1}| + λ_j |c_{j+1} - c_j|`, normalized coordinates). In
    /// a converged solution that is the collapsed limit of [`Joint::collapsed`] or a segment within
    /// the tolerance of it; drawn as its point, it moves the curve by at most `tol`.
    pub(crate) fn is_collapsed(&self, prob: &Problem<D>, j: usize, tol: f64) -> bool {
        let st = &self.state;
        if st.ratio(prob, j as isize - 1) < 1.0 - RATIO_NEAR_ONE || st.lam[j] > RATIO_NEAR_ONE {
            return false;
        }
        let loc = Self::local(prob, st, j);
        let joint = Joint::of(sub(loc.c0, loc.cm), sub(loc.c1, loc.c0));
        joint.extent(1.0 - loc.lm, loc.l0) <= tol
    }

    /// Merit `½|R|²` of the trial state, with row scales computed at the trial state (which
    /// globalizes better on the drawings than the scales of the current state). Fills
    /// `trial_res`, `trial_check` and `trial_scale` as [`assemble`](Self::assemble) would
    /// at the trial state.
    fn trial_merit(&mut self, prob: &Problem<D>, tol: f64) -> f64 {
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
    fn assemble(&mut self, prob: &Problem<D>, tol: f64) -> f64 {
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

    /// The scaled residual of block `j` (row scales computed into `scale`, the relative |κ|
    /// mismatch into `g2`) and its Jacobian by stencil block and variable, `t_j` not yet
    /// eliminated.
    #[inline(always)]
    fn block_jacobian(
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
    fn block<const FROZEN: bool>(
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
    fn eval_block<const JAC: bool, const FROZEN: bool>(
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

    /// One iteration of the classic local/global loop (seed 000 Algorithm 1), generalized
    /// to the basis: λ from the G2 formula, `t` by a bracketed root solve of the peak
    /// condition with `c_j` eliminated (to the looser start tolerance with `start`), then the
    /// (cyclic) tridiagonal system for the `c_j`.
    pub(crate) fn classic_iteration(&mut self, prob: &Problem<D>, start: bool) {
        let n = self.n();
        let start = start.then_some(if n < NEWTON_CHORD_MIN_BLOCKS {
            START_PEAK_T_TOLERANCE
        } else {
            LONG_START_PEAK_T_TOLERANCE
        });
        for a in self.tri.iter_mut() {
            a.resize(n, 0.0);
        }
        self.tri_d.resize(n, [0.0; D]);
        let split = Split::of(prob.closed, n);
        // λ (Jacobi style: from the previous λ's), into `trial.lam`.
        let st = &self.state;
        match split {
            None => Self::ratios_from(prob, st, 0, &mut self.trial.lam),
            Some(split) => {
                let [l0, l1, l2, l3] = split4(&mut self.trial.lam, split.cuts());
                let [j0, j1, j2, j3] = split.ranges().map(|r| r.start);
                let pieces = [(j0, l0), (j1, l1), (j2, l2), (j3, l3)];
                Split::each(pieces, |(j, l)| Self::ratios_from(prob, st, j, l));
            }
        }
        for j in 0..n {
            if prob.closed || j + 1 < n {
                self.state.lam[j] = self.trial.lam[j];
            }
        }
        // t, and the coefficients of the linear system; `t` into `trial.t`.
        let st = &self.state;
        let [a, b, c] = &mut self.tri;
        match split {
            None => {
                let out = (&mut self.trial.t[..], &mut a[..], &mut b[..], &mut c[..]);
                Self::peaks_from(prob, st, 0, &mut self.ends, start, out, &mut self.tri_d);
            }
            Some(split) => {
                let cuts = split.cuts();
                let [t0, t1, t2, t3] = split4(&mut self.trial.t, cuts);
                let [a0, a1, a2, a3] = split4(a, cuts);
                let [b0, b1, b2, b3] = split4(b, cuts);
                let [c0, c1, c2, c3] = split4(c, cuts);
                let [d0, d1, d2, d3] = split4(&mut self.tri_d, cuts);
                let [j0, j1, j2, j3] = split.ranges().map(|r| r.start);
                // The end terms are a function of the basis: each piece keeps its own copy
                // of the cache, and the first half's is kept.
                let [mut e0, mut e1, mut e2, mut e3] = [self.ends; 4];
                let pieces = [
                    (j0, &mut e0, (t0, a0, b0, c0), d0),
                    (j1, &mut e1, (t1, a1, b1, c1), d1),
                    (j2, &mut e2, (t2, a2, b2, c2), d2),
                    (j3, &mut e3, (t3, a3, b3, c3), d3),
                ];
                Split::each(pieces, |(j, ends, out, d)| {
                    Self::peaks_from(prob, st, j, ends, start, out, d)
                });
                self.ends = e0;
            }
        }
        core::mem::swap(&mut self.state.t, &mut self.trial.t);
        let [a, b, c] = &self.tri;
        if solve_tridiagonal(a, b, c, &mut self.tri_d, prob.closed, &mut self.scratch)
            && self.tri_d.iter().all(|v| v.iter().all(|x| x.is_finite()))
        {
            self.state.c.copy_from_slice(&self.tri_d);
        }
    }

    /// The classic loop's `λ` of the blocks `j0..j0 + lam.len()` into `lam` (an open curve's
    /// last one is left as it is).
    fn ratios_from(prob: &Problem<D>, st: &State<D>, j0: usize, lam: &mut [f64]) {
        let n = st.t.len();
        let mut carry = None;
        for (i, out) in lam.iter_mut().enumerate() {
            let j = j0 + i;
            if !prob.closed && j == n - 1 {
                continue;
            }
            let l = Self::local(prob, st, j);
            let jt = JointTerms::new(prob, j, &l, &mut carry);
            let (a, b) = (jt.x.sqrt(), jt.y.sqrt());
            let lam = a / (a + b);
            *out = if lam.is_finite() {
                lam.clamp(LAMBDA_MIN, 1.0 - LAMBDA_MIN)
            } else {
                0.5
            };
        }
    }

    /// The classic loop's peak parameters `t` of the blocks `j0..j0 + t.len()` (into `t`)
    /// and their rows of the tridiagonal system for the control points (`a`, `b`, `c`, `d`).
    #[allow(clippy::type_complexity)]
    fn peaks_from(
        prob: &Problem<D>,
        st: &State<D>,
        j0: usize,
        ends: &mut Option<EndTerms>,
        start: Option<f64>,
        (t, a, b, c): (&mut [f64], &mut [f64], &mut [f64], &mut [f64]),
        d: &mut [[f64; D]],
    ) {
        let n = st.t.len();
        let rows = t.iter_mut().zip(a).zip(b).zip(c).zip(d).enumerate();
        for (i, ((((t, a), b), c), d)) in rows {
            let j = j0 + i;
            let l = Self::local(prob, st, j);
            // The segment's ends (as `State::segment` has them) from the gathered block.
            let (q0, q2) = (lerp(l.cm, l.c0, l.lm), lerp(l.c0, l.c1, l.l0));
            let basis = prob.basis[j];
            *t = peak_parameter(basis, ends, q0, q2, prob.p[j], l.t, start);
            let w = basis.weights(*t);
            let (w0, w2) = (w[0][0], w[0][1]);
            let mut dj = prob.p[j];
            let aj = w0 * (1.0 - l.lm);
            let cj = w2 * l.l0;
            *a = aj;
            *b = 1.0 - aj - cj;
            *c = cj;
            if !prob.closed {
                if j == 0 {
                    dj = core::array::from_fn(|k| dj[k] - aj * prob.ghost[0][k]);
                }
                if j == n - 1 {
                    dj = core::array::from_fn(|k| dj[k] - cj * prob.ghost[1][k]);
                }
            }
            *d = dj;
        }
    }
}

/// The control polygon at a middle control point `c_j`: its edges `u = c_j - c_{j-1}` and
/// `v = c_{j+1} - c_j` by their lengths and dot products (what [`Workspace::check_scales`]
/// has at hand), for the tests of a segment shrinking onto its input point.
#[derive(Clone, Copy)]
struct Joint {
    nu: f64,
    nv: f64,
    uu: f64,
    vv: f64,
    uv: f64,
}

impl Joint {
    #[inline]
    fn new(nu: f64, nv: f64, uu: f64, vv: f64, uv: f64) -> Joint {
        Joint { nu, nv, uu, vv, uv }
    }

    /// The joint of edges `u` and `v`.
    #[inline]
    fn of<const D: usize>(u: [f64; D], v: [f64; D]) -> Joint {
        let (uu, vv) = (dot(u, u), dot(v, v));
        Joint::new(uu.sqrt(), vv.sqrt(), uu, vv, dot(u, v))
    }

    /// The extent `α |u| + β |v|` of the segment with ratios `α = 1 - λ_{j-1}`, `β = λ_j`.
    #[inline]
    fn extent(self, alpha: f64, beta: f64) -> f64 {
        alpha * self.nu + beta * self.nv
    }

    /// Whether the polygon goes forward at `c_j` and turns there by a sine of at most `sine`.
    #[inline]
    fn turn_within(self, sine: f64) -> bool {
        let cross2 = (self.uu * self.vv - self.uv * self.uv).max(0.0);
        self.uv > 0.0 && cross2 <= sine * sine * self.uu * self.vv
    }

    /// Whether a segment has collapsed onto its input point at a straight joint (the limit of
    /// an inflection through an input point), `α` and `β` being its ratios `1 - λ_{j-1}`, `λ_j`.
    ///
    /// When an interior point `p_j` lies on the line through its neighbours and the curve is
    /// symmetric about it (a point-symmetric S or wave), the segment through `p_j` shrinks to
    /// `p_j` as the point approaches the line: with `α = 1 - λ_{j-1}` and `β = λ_j` its legs
    /// are `r = α (c_j - c_{j-1})` and `s = β (c_{j+1} - c_j)`, and the G2 conditions at its two
    /// joints (`α² X = β T_j`, `α T_j = β² Y` up to `O(α)`, seed 000 eqs. 8–10) give
    /// `T_j ∝ α`, `β ∝ α`: the segment's extent, the turn of the control polygon at `c_j` and
    /// `c_j - p_j` all vanish linearly with the offset (measured on the wave
    /// `(100,300) … (700,300)`: offsets 1 → 1e-3 take the segment's span from 2.5 to 0.003 with
    /// its peak parameter fixed near 0.784, or 0.216 from the other side). The limit curve is
    /// the two neighbouring segments meeting at `p_j`, tangent to the line `c_{j-1} c_{j+1}`:
    /// an inflection at the input point, G1 there and G2 everywhere else. Without the
    /// symmetry the segment does not collapse: the peak moves to a segment end (`t_j = 0` or 1)
    /// and `p_j` is the joint.
    ///
    /// The collapsed state satisfies the block's equations only in the limit `α = β = 0`, which
    /// the ratios cannot reach (they stay at least [`LAMBDA_MIN`] inside `(0, 1)`). So it is
    /// recognized: the segment spans `α |c_j - c_{j-1}| + β |c_{j+1} - c_j|` at most `tol`
    /// (normalized coordinates), and the polygon's turn at `c_j` has a sine of at most `tol`
    /// (G1). Its peak row and the G2 rows of its two joints then count as met.
    #[inline]
    fn collapsed(self, alpha: f64, beta: f64, tol: f64) -> bool {
        self.extent(alpha, beta) <= tol && self.turn_within(tol)
    }
}

/// The peak row `t - clamp(t - g, 0, 1)` of a block with peak parameter `t` and scaled
/// stationarity residual `g` (a box complementarity, for the semi-smooth Newton step), and
/// the segment end the peak is forced to, if any.
#[inline(always)]
fn peak_row(t: f64, g: f64) -> (f64, Option<f64>) {
    let z = t - g;
    let end = if z <= 0.0 {
        Some(0.0)
    } else if z >= 1.0 {
        Some(1.0)
    } else {
        None
    };
    match end {
        Some(end) => (t - end, Some(end)),
        None => (g, None),
    }
}

/// What [`Workspace::residuals_from`] does with the [`Raw`] records of its blocks: fill them
/// in (an empty slice: none), or take the convergence test's floor scales from them.
enum RawIo<'a> {
    Write(&'a mut [Raw]),
    Read(&'a [Raw]),
}

/// What the residual of a block is made of besides its interpolation rows, kept by the line
/// search so that [`Workspace::refreeze`] can rescale the joint and peak rows to other row
/// scales without evaluating the block again.
#[derive(Clone, Copy, Debug, Default)]
struct Raw {
    /// The joint row before its scale.
    joint: f64,
    /// The stationarity before its scale (the peak row is `t - clamp(t - g)` of it scaled).
    stationarity: f64,
    /// The relative |κ| mismatch of the convergence test.
    g2: f64,
    /// The convergence test's scales of the joint and peak rows.
    scales: [f64; 2],
}

/// The elimination of `t_j` from block row `j` (static condensation): `t_j` appears only in
/// the rows of its own block, so `δt_j` is eliminated there before the banded solve (which
/// then has `B - 1 = D + 1` unknowns per block) and recovered after it.
#[derive(Clone, Copy, Debug)]
struct Condensed<const B: usize> {
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

/// Most condensed unknowns in a block's stencil: four blocks of `D + 1` (3D: 16).
const BACK_MAX: usize = 16;

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
    fn rhs(&self, r: &[f64; B], out: &mut [f64]) {
        for (k, o) in out[..B - 1].iter_mut().enumerate() {
            *o = -(r[k] - self.m[k] * r[B - 1]);
        }
    }

    /// The block's `δt` from its peak residual `peak` and the condensed step `reduced`
    /// (all of it): the peak row solved for its own `t`.
    #[inline]
    fn dt(&self, peak: f64, reduced: &[f64]) -> f64 {
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

/// Smallest pivot magnitude accepted when eliminating `t_j` (the rows are scaled to O(1)); a
/// smaller one is clamped, which keeps the step finite at a degenerate peak.
const MIN_PIVOT: f64 = 1e-14;

/// What the linear system holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
enum LinState {
    /// Nothing usable.
    #[default]
    Empty,
    /// The Jacobian of the current state, not yet factored.
    Assembled,
    /// Factors of an earlier state than the current one, too old for a warm start: the
    /// next warm re-solve assembles its own.
    Stale,
    /// The factors of a Jacobian of this problem's structure.
    Factored,
}

/// Eliminate `t_j` from the local block rows `jl[row][offset][variable]` (offsets -1 ..= 2,
/// `t_j` is variable `D + 1` of offset 0, the peak row is row `D + 1`): subtract multiples of
/// the peak row from the other rows so that their `t_j` entries vanish. What the elimination
/// leaves behind is written into `out` in place (the entries of `out.cols` and `out.vals`
/// past its new `len` are left as they were, and never read).
#[inline]
fn condense<const D: usize, const B: usize>(
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

/// Which variable of the stencil of block `j` a Jacobian entry belongs to.
#[derive(Clone, Copy, Debug)]
enum Var {
    /// Component `k` of `c_{j+offset}`.
    C(isize, usize),
    /// `λ_{j+offset}`.
    L(isize),
    /// `t_j`.
    T,
}

/// The global columns of the variables of block `j`'s stencil in the condensed system
/// (`stride` unknowns per block: `c` then `λ`), computed once per block.
#[derive(Clone, Copy, Debug, Default)]
struct Columns {
    /// First column of blocks `j-1 ..= j+2` (`None`: a ghost block of an open curve).
    c: [Option<usize>; 4],
    /// Column of `λ_{j-1} ..= λ_{j+2}` (`None` where fixed).
    l: [Option<usize>; 4],
    /// The dimension `D` (variables `0..D` are `c`, `D` is `λ`).
    d: usize,
}

impl Columns {
    #[inline]
    fn new<const D: usize, const B: usize>(
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
    fn at(&self, o: usize, k: usize) -> Option<usize> {
        if k < self.d {
            self.c[o].map(|b| b + k)
        } else {
            self.l[o]
        }
    }
}

impl Var {
    /// The global column, or `None` for a constant (ghost point or fixed λ of open curves).
    #[inline]
    fn index<const D: usize, const B: usize>(
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

/// The basis weights and stationarity coefficients at `t = 0` and `t = 1`, which decide
/// whether a segment's peak is forced to an end: constants of the basis, computed once per
/// basis and shared by every block that has it (`peak_parameter` keeps those of the last
/// basis it saw).
#[derive(Clone, Copy, Debug)]
pub(crate) struct EndTerms {
    basis: Basis,
    w: [[[f64; 2]; 5]; 2],
    st: [Stationarity; 2],
}

impl EndTerms {
    fn of(basis: Basis) -> EndTerms {
        let w = [basis.weights(0.0), basis.weights(1.0)];
        EndTerms {
            basis,
            w,
            st: [Stationarity::new(&w[0]), Stationarity::new(&w[1])],
        }
    }
}

/// The parameter `t` at which the segment from `q0` to `q2` whose middle control point makes
/// it pass through `p` at `t` has its curvature peak (seed 000 §3.1; for the quadratic this
/// is the cubic of seed 004 eq. 4). The peak condition, with `c_1` eliminated and multiplied
/// by `w1²`, is `f(t) = c_rr r̃·r̃ + c_rs r̃·s̃ + c_ss s̃·s̃` with `r̃ = (p - q0) - w2 d`,
/// `s̃ = (q2 - p) - w0 d`, `d = q2 - q0`; `f(0) ≥ 0 ≥ f(1)`, and the root is found by
/// Newton's method safeguarded by bisection, to the tolerance `start` where given (the classic
/// iterations that start a cold solve: [`START_PEAK_T_TOLERANCE`]), otherwise to the full one.
pub(crate) fn peak_parameter<const D: usize>(
    basis: Basis,
    ends: &mut Option<EndTerms>,
    q0: [f64; D],
    q2: [f64; D],
    p: [f64; D],
    guess: f64,
    start: Option<f64>,
) -> f64 {
    let d = sub(q2, q0);
    if basis == Basis::QUADRATIC {
        // Seed 004 eq. 4: g(t) = |d|² t³ + 3 d·e t² + (3q0 - 2p - q2)·e t - |e|² = 0 with
        // e = q0 - p. g(0) = -|e|² ≤ 0 and g(1) = |q2 - p|² ≥ 0, and there is exactly one
        // root in [0, 1]: safeguarded Newton from the previous iterate's `t` finds it in a
        // few steps (a closed-form cubic solve costs ten times more).
        let e = sub(q0, p);
        let f: [f64; D] = core::array::from_fn(|k| 3.0 * q0[k] - 2.0 * p[k] - q2[k]);
        let (c3, c2, c1, c0) = (dot(d, d), 3.0 * dot(d, e), dot(f, e), -dot(e, e));
        if !(c0 < 0.0) {
            return 0.0;
        }
        if !(c3 + c2 + c1 + c0 > 0.0) {
            return 1.0;
        }
        // To rounding: Newton converges quadratically here, so this costs about one step
        // more than the classic loop's tolerance, and the start does not depend on it.
        // (`-g` decreases through the root.)
        let neg_g = |t: f64| {
            let v = ((c3 * t + c2) * t + c1) * t + c0;
            let dv = (3.0 * c3 * t + 2.0 * c2) * t + c1;
            (-v, -dv)
        };
        let tol = start.unwrap_or(QUADRATIC_PEAK_TOLERANCE);
        return bracketed_newton(neg_g, guess, tol);
    }
    let pa = sub(p, q0);
    let pb = sub(q2, p);
    let at = |w: &[[f64; 2]; 5], st: &Stationarity| -> (f64, f64) {
        let r: [f64; D] = core::array::from_fn(|k| pa[k] - w[0][1] * d[k]);
        let s: [f64; D] = core::array::from_fn(|k| pb[k] - w[0][0] * d[k]);
        let dr: [f64; D] = core::array::from_fn(|k| -w[1][1] * d[k]);
        let ds: [f64; D] = core::array::from_fn(|k| -w[1][0] * d[k]);
        let (rr, rs, ss) = (dot(r, r), dot(r, s), dot(s, s));
        let (drr, drs, dss) = (2.0 * dot(r, dr), dot(dr, s) + dot(r, ds), 2.0 * dot(s, ds));
        let v = st.c[0] * rr + st.c[1] * rs + st.c[2] * ss;
        let dv = st.dc[0] * rr
            + st.dc[1] * rs
            + st.dc[2] * ss
            + st.c[0] * drr
            + st.c[1] * drs
            + st.c[2] * dss;
        (v, dv)
    };
    let f = |t: f64| -> (f64, f64) {
        let w = basis.weights(t);
        at(&w, &Stationarity::new(&w))
    };
    let ends = match *ends {
        Some(e) if e.basis == basis => e,
        _ => *ends.insert(EndTerms::of(basis)),
    };
    let (flo, fhi) = (at(&ends.w[0], &ends.st[0]).0, at(&ends.w[1], &ends.st[1]).0);
    if !(flo > 0.0) {
        return 0.0;
    }
    if !(fhi < 0.0) {
        return 1.0;
    }
    let tol = start.unwrap_or(PEAK_T_TOLERANCE);
    bracketed_newton(f, guess, tol)
}

/// The root in `[0, 1]` of `f` (value, derivative), which decreases through it with
/// `f(0) > 0 > f(1)`: Newton's method from `guess` (or the middle), a bisection of the
/// bracket wherever Newton would leave it, until the bracket or the Newton correction is
/// below `tol` (at most [`ROOT_ITERATIONS`] steps; an exact or NaN value stops at once).
fn bracketed_newton(f: impl Fn(f64) -> (f64, f64), guess: f64, tol: f64) -> f64 {
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    let mut t = if guess > 0.0 && guess < 1.0 {
        guess
    } else {
        0.5
    };
    for _ in 0..ROOT_ITERATIONS {
        let (v, dv) = f(t);
        if v > 0.0 {
            lo = t;
        } else if v < 0.0 {
            hi = t;
        } else {
            return t;
        }
        let step = v / dv;
        let newton = t - step;
        // Inside the open bracket also means finite.
        t = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if hi - lo < tol || (t == newton && step.abs() < tol) {
            break;
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn peak_parameter_quadratic_is_the_root_to_rounding() {
        // The root in [0, 1] of seed 004 eq. 4, to the last few ulps: the Newton correction
        // left at the returned t is below 1e-13 (a closed-form cubic solve was off by up to
        // 5e-8 on these).
        let mut seed = 1u64;
        let mut r = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
        };
        for _ in 0..20_000 {
            let (q0, q2, p) = ([r(), r()], [r(), r()], [r(), r()]);
            let guess = 0.5 + 0.5 * r();
            let t = peak_parameter(Basis::QUADRATIC, &mut None, q0, q2, p, guess, None);
            assert!((0.0..=1.0).contains(&t));
            let (d, e) = (sub(q2, q0), sub(q0, p));
            let f: [f64; 2] = core::array::from_fn(|k| 3.0 * q0[k] - 2.0 * p[k] - q2[k]);
            let (c3, c2, c1, c0) = (dot(d, d), 3.0 * dot(d, e), dot(f, e), -dot(e, e));
            let g = ((c3 * t + c2) * t + c1) * t + c0;
            let dg = (3.0 * c3 * t + 2.0 * c2) * t + c1;
            let floor = 8.0 * f64::EPSILON * (c3.abs() + c2.abs() + c1.abs() + c0.abs());
            assert!(
                g.abs() <= floor || (g / dg).abs() < 1e-13,
                "{q0:?} {q2:?} {p:?}: t = {t}, g = {g}, g' = {dg}"
            );
        }
    }

    #[test]
    fn extrapolation_finds_the_limit_of_a_geometric_sequence_and_skips_turning_steps() {
        // Iterates x_k = x* + ρ^k v (one mode): the extrapolation from x_1, x_2, x_3 lands
        // on x*. Steps that turn (two modes of opposite sign) are left alone.
        let n = 3;
        let prob = Problem {
            closed: true,
            p: vec![[0.0; 2]; n],
            ghost: [[0.0; 2]; 2],
            basis: vec![Basis::QUADRATIC; n],
            tangents: Vec::new(),
        };
        let star = State {
            c: vec![[0.3, -0.2], [1.0, 0.5], [-0.4, 0.9]],
            lam: vec![0.4, 0.55, 0.6],
            t: vec![0.45, 0.5, 0.52],
        };
        let v = [[0.02, 0.01], [-0.03, 0.02], [0.01, -0.02]];
        let vl = [0.01, -0.02, 0.015];
        let vt = [-0.01, 0.02, 0.01];
        let iterate = |k: i32, rho: f64, turn: bool| {
            let mut st = star.clone();
            for j in 0..n {
                // A second mode of opposite sign on the first block when turning.
                let w = rho.powi(k)
                    + if turn && j == 0 {
                        0.9f64.powi(k) * (-1f64).powi(k)
                    } else {
                        0.0
                    };
                st.c[j] = core::array::from_fn(|d| star.c[j][d] + w * v[j][d]);
                st.lam[j] = star.lam[j] + w * vl[j];
                st.t[j] = star.t[j] + w * vt[j];
            }
            st
        };
        for (rho, turn, lands) in [(0.15, false, true), (0.3, false, true), (0.15, true, false)] {
            let mut ws = Workspace::<2, 4> {
                state: iterate(1, rho, turn),
                ..Default::default()
            };
            ws.record_iterate(true);
            ws.state = iterate(2, rho, turn);
            ws.record_iterate(false);
            ws.state = iterate(3, rho, turn);
            let before = ws.state.clone();
            ws.extrapolate(&prob);
            let err = |st: &State<2>| {
                (0..n)
                    .map(|j| {
                        let dc = (0..2).map(|d| (st.c[j][d] - star.c[j][d]).abs());
                        dc.fold((st.lam[j] - star.lam[j]).abs(), f64::max)
                            .max((st.t[j] - star.t[j]).abs())
                    })
                    .fold(0.0, f64::max)
            };
            if lands {
                assert!(err(&ws.state) < 1e-14, "ρ = {rho}: {}", err(&ws.state));
            } else {
                assert_eq!(ws.state.c, before.c, "turning steps are not extrapolated");
                assert_eq!(ws.state.lam, before.lam);
            }
        }
    }

    #[test]
    fn peak_parameter_quadratic_is_vertex() {
        // For the quadratic the peak t is where the parabola's vertex lies.
        let (q0, q2, p) = ([0.0, 0.0], [4.0, 0.0], [1.0, 1.5]);
        let t = peak_parameter(Basis::QUADRATIC, &mut None, q0, q2, p, 0.5, None);
        let w = Basis::QUADRATIC.weights(t);
        let c1: [f64; 2] = core::array::from_fn(|k| {
            (p[k] - w[0][0] * q0[k] - w[0][1] * q2[k]) / (1.0 - w[0][0] - w[0][1])
        });
        let r = sub(c1, q0);
        let s = sub(q2, c1);
        let rs = sub(r, s);
        let tv = dot(r, rs) / dot(rs, rs);
        assert!((t - tv).abs() < 1e-12, "{t} vs {tv}");
    }

    #[test]
    fn triangle_gradient_matches_finite_differences() {
        let (a, b, c) = ([0.3, 1.0, -0.2], [1.0, 0.1, 0.4], [2.0, 1.2, 0.0]);
        let (_, ga, gc) = triangle(a, b, c);
        let h = 1e-7;
        for k in 0..3 {
            let mut ap = a;
            ap[k] += h;
            let mut am = a;
            am[k] -= h;
            let fd = (triangle(ap, b, c).0 - triangle(am, b, c).0) / (2.0 * h);
            assert!((fd - ga[k]).abs() < 1e-6);
            let mut cp = c;
            cp[k] += h;
            let mut cm = c;
            cm[k] -= h;
            let fd = (triangle(a, b, cp).0 - triangle(a, b, cm).0) / (2.0 * h);
            assert!((fd - gc[k]).abs() < 1e-6);
        }
    }
}

#[cfg(test)]
mod jacobian_tests {
    use super::*;

    fn dense_jacobian<const D: usize, const B: usize>(
        prob: &Problem<D>,
        st: &State<D>,
    ) -> (Vec<f64>, Vec<f64>) {
        let n = st.t.len();
        let nn = n * B;
        let mut jac = vec![0.0; nn * nn];
        let mut res = vec![0.0; nn];
        for j in 0..n {
            let loc = Workspace::<D, B>::local(prob, st, j);
            let mut scale = [1.0; 2];
            let mut sink = |row: usize, col: Var, v: f64| {
                if let Some(c) = col.index::<D, B>(prob.closed, n, j) {
                    jac[(j * B + row) * nn + c] += v;
                }
            };
            let r = Workspace::<D, B>::eval_block::<true, false>(
                prob, j, &loc, &mut scale, &mut 0.0, &mut sink,
            );
            res[j * B..(j + 1) * B].copy_from_slice(&r);
        }
        (jac, res)
    }

    fn residual<const D: usize, const B: usize>(
        prob: &Problem<D>,
        st: &State<D>,
        scales: &[[f64; 2]],
    ) -> Vec<f64> {
        let n = st.t.len();
        let mut out = vec![0.0; n * B];
        for j in 0..n {
            let loc = Workspace::<D, B>::local(prob, st, j);
            let mut sc = scales[j];
            let r = Workspace::<D, B>::block::<true>(prob, j, &loc, &mut sc);
            out[j * B..(j + 1) * B].copy_from_slice(&r);
        }
        out
    }

    fn check<const D: usize, const B: usize>(
        closed: bool,
        a: f64,
        tangents: Vec<Option<Tangent<D>>>,
    ) {
        let n = 6;
        let mut seed = 5u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64) / ((1u64 << 53) as f64)
        };
        let p: Vec<[f64; D]> = (0..n)
            .map(|i| {
                let th = i as f64 / n as f64 * std::f64::consts::TAU;
                core::array::from_fn(|k| match k {
                    0 => th.cos() + 0.1 * rnd(),
                    1 => th.sin() + 0.1 * rnd(),
                    _ => 0.3 * rnd(),
                })
            })
            .collect();
        let prob = Problem {
            closed,
            p: p.clone(),
            ghost: [[0.5; D], [-0.5; D]],
            basis: vec![Basis::Cubic(crate::basis::CubicEk::new(a)); n],
            tangents,
        };
        let st = State {
            c: p.iter()
                .map(|q| core::array::from_fn(|k| q[k] * 1.1 + 0.05 * rnd()))
                .collect(),
            lam: (0..n)
                .map(|i| {
                    if !closed && i == n - 1 {
                        1.0
                    } else {
                        0.3 + 0.4 * rnd()
                    }
                })
                .collect(),
            t: (0..n).map(|_| 0.3 + 0.4 * rnd()).collect(),
        };
        let (jac, _) = dense_jacobian::<D, B>(&prob, &st);
        let n_all = n * B;
        let scales: Vec<[f64; 2]> = (0..n)
            .map(|j| {
                let loc = Workspace::<D, B>::local(&prob, &st, j);
                let mut s = [1.0; 2];
                Workspace::<D, B>::block::<false>(&prob, j, &loc, &mut s);
                s
            })
            .collect();
        let h = 1e-6;
        for col in 0..n_all {
            let (blk, k) = (col / B, col % B);
            if !closed && blk == n - 1 && k == D {
                continue;
            }
            let mut plus = st.clone();
            let mut minus = st.clone();
            match k {
                _ if k < D => {
                    plus.c[blk][k] += h;
                    minus.c[blk][k] -= h;
                }
                _ if k == D => {
                    plus.lam[blk] += h;
                    minus.lam[blk] -= h;
                }
                _ => {
                    plus.t[blk] += h;
                    minus.t[blk] -= h;
                }
            }
            let rp = residual::<D, B>(&prob, &plus, &scales);
            let rm = residual::<D, B>(&prob, &minus, &scales);
            for row in 0..n_all {
                if !closed && row == (n - 1) * B + D {
                    continue;
                }
                let fd = (rp[row] - rm[row]) / (2.0 * h);
                let an = jac[row * n_all + col];
                assert!(
                    (fd - an).abs() <= 1e-6 * (1.0 + fd.abs()),
                    "closed={closed} a={a} row {row} col {col}: fd {fd} analytic {an}"
                );
            }
        }
    }

    #[test]
    fn jacobian_matches_finite_differences() {
        for &closed in &[true, false] {
            for &a in &[2.0 / 3.0, 0.8] {
                check::<2, 4>(closed, a, Vec::new());
                check::<3, 5>(closed, a, Vec::new());
            }
        }
    }

    #[test]
    fn tangent_rows_match_finite_differences() {
        let tan = |x: f64, y: f64, at| {
            let n = x.hypot(y);
            Some(Tangent {
                dir: [x / n, y / n],
                at,
            })
        };
        for &a in &[2.0 / 3.0, 0.8] {
            let peak = vec![
                tan(1.0, 0.2, TangentAt::Peak),
                None,
                tan(-0.3, 1.0, TangentAt::Peak),
                None,
                None,
                tan(0.5, -1.0, TangentAt::Peak),
            ];
            check::<2, 4>(true, a, peak);
            let ends = vec![
                tan(1.0, 0.0, TangentAt::Start),
                None,
                tan(0.0, 1.0, TangentAt::Peak),
                None,
                None,
                tan(1.0, -1.0, TangentAt::End),
            ];
            check::<2, 4>(false, a, ends);
        }
    }
}

#[cfg(test)]
mod linear_tests {
    use super::*;
    use crate::linalg::DenseLu;

    /// The Newton system assembled into the banded/bordered solver gives the same step as a
    /// dense LU of the same entries.
    fn check<const D: usize, const B: usize>(closed: bool, n: usize) {
        check_with::<D, B>(closed, n, Vec::new());
    }

    fn check_with<const D: usize, const B: usize>(
        closed: bool,
        n: usize,
        tangents: Vec<Option<Tangent<D>>>,
    ) {
        let p: Vec<[f64; D]> = (0..n)
            .map(|i| {
                let th = i as f64 / n as f64 * std::f64::consts::TAU;
                core::array::from_fn(|k| match k {
                    0 => th.cos() * (1.0 + 0.2 * (3.0 * th).sin()),
                    1 => th.sin(),
                    _ => 0.2 * (2.0 * th).cos(),
                })
            })
            .collect();
        let prob = Problem {
            closed,
            p: p.clone(),
            ghost: [[1.5; D], [-1.5; D]],
            basis: vec![Basis::Cubic(crate::basis::CubicEk::new(0.7)); n],
            tangents,
        };
        let mut ws = Workspace::<D, B>::default();
        ws.cold_start(&prob);
        ws.classic_iteration(&prob, true);
        ws.size_buffers(n);
        ws.lin.reset(closed, n, B - 1);
        ws.assemble(&prob, 1e-12);
        // The full Newton system, dense.
        let nn = n * B;
        // (The rows as `eval_block` has them: `assemble` may order a block's rows otherwise,
        // which leaves the step as it is.)
        let mut dense = DenseLu::default();
        dense.reset(nn);
        let mut full = Vec::with_capacity(nn);
        for j in 0..n {
            let loc = Workspace::<D, B>::local(&prob, &ws.state, j);
            let mut scale = [1.0; 2];
            let mut sink = |row: usize, col: Var, v: f64| {
                if let Some(c) = col.index::<D, B>(closed, n, j) {
                    dense.add(j * B + row, c, v);
                }
            };
            let r = Workspace::<D, B>::eval_block::<true, false>(
                &prob, j, &loc, &mut scale, &mut 0.0, &mut sink,
            );
            full.extend(r.iter().map(|v| -v));
        }
        assert!(dense.factor());
        dense.solve(&mut full);
        // The condensed system through the banded / bordered / small dense solver.
        assert!(ws.lin.factor());
        assert!(ws.condensed_step());
        for (a, b) in ws.step.iter().zip(&full) {
            assert!(
                (a - b).abs() <= 1e-8 * (1.0 + b.abs()),
                "closed={closed} n={n}: {a} vs {b}"
            );
        }
    }

    #[test]
    fn condensed_step_with_tangents() {
        for (closed, n) in [(true, 7), (false, 7), (true, 40), (false, 40)] {
            let mut tangents = vec![None; n];
            let at = |end| if closed { TangentAt::Peak } else { end };
            tangents[0] = Some(Tangent {
                dir: [0.6, 0.8],
                at: at(TangentAt::Start),
            });
            tangents[3] = Some(Tangent {
                dir: [-1.0, 0.0],
                at: TangentAt::Peak,
            });
            tangents[n - 1] = Some(Tangent {
                dir: [0.0, -1.0],
                at: at(TangentAt::End),
            });
            check_with::<2, 4>(closed, n, tangents);
        }
    }

    /// After an accepted Newton step, the residual rescaled from the line search's
    /// measure equals the one evaluated with the factorization's row scales, bit for bit.
    fn check_refreeze<const D: usize, const B: usize>(closed: bool, n: usize, basis: Basis) {
        let p: Vec<[f64; D]> = (0..n)
            .map(|i| {
                let th = i as f64 / n as f64 * std::f64::consts::TAU;
                // Jagged and without symmetry (a symmetric start can be a solution).
                let r = if i % 2 == 0 { 1.0 } else { 0.8 } + 0.1 * (3.0 * th + 0.5).sin();
                core::array::from_fn(|k| match k {
                    0 => r * th.cos(),
                    1 => r * th.sin(),
                    _ => 0.1 * (2.0 * th).cos(),
                })
            })
            .collect();
        let prob = Problem {
            closed,
            p,
            ghost: [[1.5; D], [-1.5; D]],
            basis: vec![basis; n],
            tangents: Vec::new(),
        };
        let tol = 1e-12;
        let mut ws = Workspace::<D, B>::default();
        ws.cold_start(&prob);
        ws.trial.clone_from(&ws.state);
        ws.size_buffers(n);
        for _ in 0..3 {
            ws.classic_iteration(&prob, true);
        }
        let mut accepted = 0;
        for _ in 0..3 {
            ws.lin.reset(closed, n, B - 1);
            let phi = ws.assemble(&prob, tol);
            ws.fact_scale.clone_from(&ws.scale);
            if ws.max_residual() <= tol || !ws.newton_step(&prob, phi, tol) {
                break;
            }
            accepted += 1;
            let fast = ws.refreeze();
            let (res, check) = (ws.res.clone(), ws.check.clone());
            let slow = ws.residual_frozen(&prob, tol, false);
            assert_eq!(fast.to_bits(), slow.to_bits(), "closed={closed} n={n}");
            for (a, b) in res.iter().flatten().zip(ws.res.iter().flatten()) {
                assert_eq!(a.to_bits(), b.to_bits(), "closed={closed} n={n}");
            }
            for (a, b) in check.iter().flatten().zip(ws.check.iter().flatten()) {
                assert_eq!(a.to_bits(), b.to_bits(), "closed={closed} n={n}");
            }
        }
        assert!(
            accepted > 0,
            "closed={closed} n={n}: no Newton step to check"
        );
    }

    #[test]
    fn refrozen_residual_matches_a_frozen_evaluation() {
        let cubic = Basis::Cubic(crate::basis::CubicEk::new(0.8));
        for basis in [Basis::QUADRATIC, cubic] {
            for &n in &[3, 4, 5, 9, 17] {
                check_refreeze::<2, 4>(true, n, basis);
                check_refreeze::<2, 4>(false, n, basis);
                check_refreeze::<3, 5>(true, n, basis);
            }
        }
    }

    #[test]
    fn structured_solve_matches_dense() {
        for &n in &[17, 9, 6, 5, 4, 3] {
            check::<2, 4>(false, n);
            check::<3, 5>(false, n);
            check::<2, 4>(true, n);
            check::<3, 5>(true, n);
        }
    }

    /// Runs `f` with curves of `min` blocks or more cut in two halves.
    fn with_split_min<R>(min: usize, f: impl FnOnce() -> R) -> R {
        let old = super::SPLIT_MIN.with(|c| c.replace(min));
        let r = f();
        super::SPLIT_MIN.with(|c| c.set(old));
        r
    }

    #[test]
    fn split_solve_matches_dense() {
        // The halves, the separator and the tail of a cut curve (classic iteration, Jacobian
        // assembly, condensed solve, recovery of δt) against the dense Newton system.
        with_split_min(8, || {
            for &n in &[8, 9, 10, 17, 31] {
                check::<2, 4>(false, n);
                check::<3, 5>(false, n);
                check::<2, 4>(true, n);
                check::<3, 5>(true, n);
            }
        });
    }

    #[test]
    fn split_solves_match_whole_ones() {
        // Whole solves of curves cut in two halves converge to the same curves as uncut.
        for closed in [true, false] {
            for (basis, n) in [
                (Basis::QUADRATIC, 40),
                (Basis::Cubic(crate::basis::CubicEk::new(0.85)), 41),
            ] {
                let p: Vec<[f64; 2]> = (0..n)
                    .map(|i| {
                        let th = i as f64 / n as f64 * std::f64::consts::TAU;
                        let r = if i % 2 == 0 { 1.0 } else { 0.9 };
                        [r * th.cos(), r * th.sin()]
                    })
                    .collect();
                let prob = Problem {
                    closed,
                    p,
                    ghost: [[1.2, -0.1], [1.2, 0.1]],
                    basis: vec![basis; n],
                    tangents: Vec::new(),
                };
                let set = Settings {
                    tolerance: 1e-12,
                    max_iterations: 200,
                    newton_chords: true,
                };
                let solve = || {
                    let mut ws = Workspace::<2, 4>::default();
                    let mut scratch = Problem {
                        closed,
                        p: vec![],
                        ghost: [[0.0; 2]; 2],
                        basis: vec![],
                        tangents: Vec::new(),
                    };
                    let out = ws.solve_cold(&prob, &set, &mut scratch);
                    (out, ws.state)
                };
                let (whole, a) = solve();
                let (cut, b) = with_split_min(8, solve);
                assert!(whole.converged && cut.converged, "{closed} {n}");
                for (x, y) in a.c.iter().zip(&b.c) {
                    assert!(
                        (x[0] - y[0]).abs() + (x[1] - y[1]).abs() < 1e-10,
                        "{closed} {n}"
                    );
                }
                for (x, y) in a.t.iter().zip(&b.t) {
                    assert!((x - y).abs() < 1e-8, "{closed} {n}: {x} vs {y}");
                }
            }
        }
    }
}
