//! Tangent constraints: a prescribed tangent direction at a point of a 2D curve.
//!
//! # The condition and what it replaces
//!
//! Block `j`'s segment is `P(t) = c_j - w0(t) r + w2(t) s` with the legs
//! `r = (1-λ_{j-1})(c_j - c_{j-1})` and `s = λ_j (c_{j+1} - c_j)` (seed 000 eq. 7 in the
//! basis form of the `basis` module). Its tangent at `τ` is
//! `P'(τ) = -w0'(τ) r + w2'(τ) s`, and "the tangent at `τ` points along the unit vector
//! `d`" is the one scalar equation `θ = atan2(d × P', d · P') = 0` (the angle form keeps the
//! sign: `P'` along `-d` is `θ = π`, not a solution).
//!
//! Each block has `D + 2` unknowns (`c_j`, `λ_j`, `t_j`) and `D + 2` conditions: the
//! interpolation `P(t_j) = p_j` (D rows), G2 at the joint `j|j+1` (seed 000 eq. 10) and the
//! peak `d|κ|/dt (t_j) = 0` (seed 000 eq. 11). A tangent adds one equation, so one condition
//! gives way: the peak of the block's segment, because the two others are what makes the
//! curve pass through the points and be G2. What then holds, with `τ = t_j` (an interior
//! point) or `τ = 0`/`1` (the first/last point of an open curve):
//! - every point is interpolated (all interpolation rows are kept);
//! - G2 at every joint as the papers have it (all joint rows are kept: equal |κ|, so G1
//!   only where the curvature changes sign at a joint, an inflection); the point itself
//!   lies inside its segment, where the curve is analytic;
//! - the tangent at the point is `d` (to the solver's tolerance, in radians);
//! - the constrained point is not, in general, a curvature extremum: moving `d` by `δ`
//!   moves `t_j` off the peak by about `δ / (κ |P'|)`. For an open curve's end, the
//!   released peak is that of the first (last) interior point.
//!
//! `tests/tangents.rs` asserts tangents within 1e-9 rad, points within 1e-9 of the drawing
//! size, and equal |κ| at the joints within 1e-6, and that the curve moves by O(δ) when a
//! direction does.
//!
//! Such a solution exists only while the constrained point stays inside its segment: for
//! directions near the free curve's (on a four-point loop, within 10–15°; farther off, the
//! solve fails rather than pin `t_j` at a segment end).
//!
//! A block holds one tangent at most, so an open curve's end and its neighbour cannot both
//! carry one (the spline API reports `Error::TangentConflict`).
//!
//! # Solving
//!
//! The row is `σ θ` with `σ = sign(P' × P'')` at an interior point: `d(σθ)/dt = |κ| |P'| ≥ 0`,
//! so the row increases with `t` like the peak row. It has no box complementarity (a
//! tangent met with `t_j` pinned at a segment end would not be met at the point). An end
//! tangent does not involve `t_j`, and the condensation that eliminates `t_j` pivots on the
//! last row: for such a block [`end_row_last`] swaps the last row with the interpolation row
//! whose `∂/∂t_j` is largest.
//!
//! From a cold start, [`Workspace::tangent_continuation`] solves the free curve, then turns
//! each direction from the free curve's tangent to the prescribed one in adaptive steps, so
//! the solution found is on the free curve's branch.

use super::cascade::Homotopy;
use super::linear::Var;
use super::residual::Local;
use super::tuning::cascade::CLASSIC_START;
use super::tuning::tangent::TANGENT_MIN_STEP;
use super::{dot, Outcome, Problem, Settings, State, Workspace};
use crate::basis::{Basis, SegmentBasis};

/// A tangent constraint on a block: the curve's tangent at a parameter of the block's
/// segment must point along `dir` (a unit vector, normalized coordinates; 2D only).
///
/// The constraint takes the place of one condition of the block, so the system stays
/// square:
/// - [`TangentAt::Peak`]: the tangent at the input point (`t = t_j`) replaces the peak
///   condition. The point is still interpolated and G2 still holds at both joints of the
///   segment, but the point is no longer a curvature extremum.
/// - [`TangentAt::Start`] / [`TangentAt::End`]: the tangent at the first (last) input point
///   of an open curve, which is the start (end) of the first (last) segment, replaces that
///   segment's peak condition: the next input point is then interpolated but not a
///   curvature extremum either (a block holds one tangent at most).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Tangent<const D: usize> {
    pub dir: [f64; D],
    pub at: TangentAt,
}

/// Where on its segment a [`Tangent`] applies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum TangentAt {
    /// At the block's input point (`t = t_j`).
    Peak,
    /// At the segment's start (`t = 0`): the first point of an open curve.
    Start,
    /// At the segment's end (`t = 1`): the last point of an open curve.
    End,
}

/// The row of a block's [`Tangent`]: the signed angle `θ` from the prescribed direction to
/// the curve's tangent `P'(τ) = -w0'(τ) r + w2'(τ) s` (`τ = t_j`, 0 or 1), with what its
/// Jacobian needs.
///
/// At the input point (`τ = t_j`) the angle is multiplied by the sign `σ` of
/// `P' × P''`, so that the row increases with `t` like the peak row (`dθ/dt = κ |P'|`).
/// Unlike the peak row it has no box complementarity: the step bound keeps `t_j` in
/// `[0, 1]`, and a tangent that would need `t_j` outside is not met (the solve fails).
#[derive(Clone, Copy, Debug)]
pub(super) struct TangentRow<const D: usize> {
    pub at: TangentAt,
    /// `σ θ` (radians).
    pub value: f64,
    /// `∂(σ θ)/∂P'`: `σ (-P'_y, P'_x) / |P'|²`.
    gp: [f64; D],
    /// `w0'(τ)`, `w2'(τ)`.
    w1: [f64; 2],
    /// `∂(σ θ)/∂t` (at the input point only).
    dt: f64,
}

impl<const D: usize> TangentRow<D> {
    pub fn new(tan: Tangent<D>, basis: &Basis, t: f64, r: [f64; D], s: [f64; D]) -> Self {
        let tau = match tan.at {
            TangentAt::Peak => t,
            TangentAt::Start => 0.0,
            TangentAt::End => 1.0,
        };
        let w = basis.weights(tau);
        let p1: [f64; D] = core::array::from_fn(|k| -w[1][0] * r[k] + w[1][1] * s[k]);
        let d = tan.dir;
        let theta = (d[0] * p1[1] - d[1] * p1[0]).atan2(dot(d, p1));
        let nn = dot(p1, p1) + 1e-300;
        let mut gp: [f64; D] = core::array::from_fn(|k| match k {
            0 => -p1[1] / nn,
            1 => p1[0] / nn,
            _ => 0.0,
        });
        let (mut value, mut dt) = (theta, 0.0);
        if tan.at == TangentAt::Peak {
            let p2: [f64; D] = core::array::from_fn(|k| -w[2][0] * r[k] + w[2][1] * s[k]);
            let sigma = if p1[0] * p2[1] - p1[1] * p2[0] < 0.0 {
                -1.0
            } else {
                1.0
            };
            value *= sigma;
            for g in gp.iter_mut() {
                *g *= sigma;
            }
            dt = dot(gp, p2);
        }
        TangentRow {
            at: tan.at,
            value,
            gp,
            w1: [w[1][0], w[1][1]],
            dt,
        }
    }

    /// The row's Jacobian entries, through `put`: `P'` depends on `r = (1-λ_{j-1})(c_j -
    /// c_{j-1})`, `s = λ_j (c_{j+1} - c_j)` and, at the input point, on `t_j`.
    pub fn jacobian(
        &self,
        l: &Local<D>,
        em: [f64; D],
        e0: [f64; D],
        om: f64,
        put: &mut impl FnMut(Var, f64),
    ) {
        let gr: [f64; D] = core::array::from_fn(|k| -self.w1[0] * self.gp[k]);
        let gs: [f64; D] = core::array::from_fn(|k| self.w1[1] * self.gp[k]);
        for k in 0..D {
            put(Var::C(-1, k), -om * gr[k]);
            put(Var::C(0, k), om * gr[k] - l.l0 * gs[k]);
            put(Var::C(1, k), l.l0 * gs[k]);
        }
        put(Var::L(-1), -dot(gr, em));
        put(Var::L(0), dot(gs, e0));
        if self.at == TangentAt::Peak {
            put(Var::T, self.dt);
        }
    }
}

/// For a block with an end tangent, exchanges its last row (the tangent row, which does not
/// involve `t_j`) with the interpolation row whose `∂/∂t_j` is largest, in the residual `r`
/// and the block Jacobian `jl`: the condensation eliminates `t_j` with the last row. The
/// Newton step is the same whatever the order of the rows.
pub(super) fn end_row_last<const D: usize, const B: usize>(
    prob: &Problem<D>,
    j: usize,
    r: &mut [f64; B],
    jl: &mut [[[f64; B]; 4]; B],
) {
    let Some(Tangent { at, .. }) = prob.tangents[j] else {
        return;
    };
    if at == TangentAt::Peak {
        return;
    }
    // `t_j` is variable `D + 1` of the block's own stencil entry (offset 0, stored at 1).
    let dt = |k: usize| jl[k][1][D + 1].abs();
    let k = (0..D).fold(0, |b, k| if dt(k) > dt(b) { k } else { b });
    r.swap(k, D + 1);
    jl.swap(k, D + 1);
}

impl<const D: usize, const B: usize> Workspace<D, B> {
    /// A cold solve of a problem with tangents:
    /// [`tangent_continuation`](Self::tangent_continuation) from the free curve, so that
    /// the solution found is on the free curve's branch; if that does not converge, Newton
    /// straight from the classic start (the iterations of both count). The second can land
    /// on another solution, with inflections at joints that the free curve does not have.
    pub(crate) fn solve_cold_tangents(
        &mut self,
        prob: &Problem<D>,
        set: &Settings,
        scratch: &mut Problem<D>,
        free: &mut Option<State<D>>,
    ) -> Outcome {
        // Half the budget each (a continuation that does not converge spends all it has).
        let half = Settings {
            max_iterations: set.max_iterations / 2,
            ..*set
        };
        let along = self.tangent_continuation(prob, &half, scratch, free);
        if along.converged || along.iterations >= set.max_iterations {
            return along;
        }
        let best = self.state.clone();
        self.cold_start(prob);
        let rest = Settings {
            max_iterations: set.max_iterations - along.iterations,
            ..*set
        };
        let direct = self.solve(prob, &rest, CLASSIC_START, false);
        let iterations = along.iterations + direct.iterations;
        if direct.converged || !(direct.residual >= along.residual) {
            return Outcome {
                iterations,
                ..direct
            };
        }
        self.state = best;
        Outcome {
            iterations,
            ..along
        }
    }

    /// Continuation in the tangent directions: solve the free curve (no tangents, the
    /// usual cold cascade), then turn each prescribed direction from the free curve's
    /// tangent at the same parameter to its target, in steps that grow by 1.5 after a
    /// success and halve after a failure (as the shape continuation does).
    ///
    /// `free` is the free curve's solution if known (it is then not solved again), and holds
    /// it on return when it was solved here.
    fn tangent_continuation(
        &mut self,
        prob: &Problem<D>,
        set: &Settings,
        scratch: &mut Problem<D>,
        free: &mut Option<State<D>>,
    ) -> Outcome {
        let budget = |used: usize, cap: usize| Settings {
            max_iterations: cap.min(set.max_iterations.saturating_sub(used)),
            ..*set
        };
        let mut moving = prob.clone();
        moving.tangents.clear();
        let mut total = 0;
        match free {
            Some(known) => self.state.clone_from(known),
            None => {
                let out = self.solve_cold(&moving, &budget(0, usize::MAX), scratch);
                total += out.iterations;
                if !out.converged {
                    return Outcome {
                        iterations: total,
                        ..out
                    };
                }
                *free = Some(self.state.clone());
            }
        }
        // Each constrained block's start direction and the angle to turn it by.
        let turns: Vec<Option<([f64; D], f64, Tangent<D>)>> = prob
            .tangents
            .iter()
            .enumerate()
            .map(|(j, tan)| {
                tan.map(|tan| {
                    let d0 = self.tangent_of(prob, j, tan.at);
                    let d = tan.dir;
                    let angle = (d0[0] * d[1] - d0[1] * d[0]).atan2(dot(d0, d));
                    (d0, angle, tan)
                })
            })
            .collect();
        let blend = |moving: &mut Problem<D>, s: f64| {
            moving.tangents.clear();
            moving.tangents.extend(turns.iter().map(|turn| {
                turn.map(|(d0, angle, tan)| {
                    let (sin, cos) = (s * angle).sin_cos();
                    let mut dir = [0.0; D];
                    dir[0] = cos * d0[0] - sin * d0[1];
                    dir[1] = sin * d0[0] + cos * d0[1];
                    Tangent { dir, at: tan.at }
                })
            }));
        };
        // (s = 1 reproduces the directions but for rounding.)
        let steps = Homotopy {
            max_iterations: set.max_iterations,
            min_step: TANGENT_MIN_STEP,
            step_budget: super::tuning::cascade::STEP_BUDGET,
            first_step: 0.25,
            growth: 1.5,
            spent: total,
        };
        self.follow(prob, &mut moving, blend, |_, _, _, _| false, budget, steps)
    }

    /// The unit tangent of block `j`'s segment at the parameter a tangent `at` there
    /// refers to, in the current state.
    fn tangent_of(&self, prob: &Problem<D>, j: usize, at: TangentAt) -> [f64; D] {
        let l = Self::local(prob, &self.state, j);
        let om = 1.0 - l.lm;
        let r: [f64; D] = core::array::from_fn(|k| om * (l.c0[k] - l.cm[k]));
        let s: [f64; D] = core::array::from_fn(|k| l.l0 * (l.c1[k] - l.c0[k]));
        let tau = match at {
            TangentAt::Peak => l.t,
            TangentAt::Start => 0.0,
            TangentAt::End => 1.0,
        };
        let w = prob.basis[j].weights(tau);
        let p1: [f64; D] = core::array::from_fn(|k| -w[1][0] * r[k] + w[1][1] * s[k]);
        let norm = dot(p1, p1).sqrt();
        if norm > 0.0 && norm.is_finite() {
            p1.map(|x| x / norm)
        } else {
            let mut x = [0.0; D];
            x[0] = 1.0;
            x
        }
    }
}
