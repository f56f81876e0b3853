//! Finishing a collapse: the last step of a failed cold solve next to inflections through
//! input points.
//!
//! At an interior point `p_j` collinear with its neighbours, on a curve symmetric about it,
//! the κ solution is the limit of segment `j` shrinking onto `p_j`
//! ([`Joint::collapsed`](super::check)): its ratios `α = 1 - λ_{j-1}`, `β = λ_j` and the offset
//! `c_j - p_j` all vanish linearly, with `β / α` and the peak parameter `t_j` tending to
//! limits. That limit lies on the boundary of the unknowns' range, where the block's
//! Jacobian is singular, so Newton approaches it only linearly and, with other blocks still
//! to converge, can stall short of it: the whole-pixel lemniscates of `tests/integer_input.rs`
//! ended their κ solves with the segments at their crossing at `α ≈ β ≈ 1e-5 … 1e-12`
//! and relative residuals of 7e-7 to 3e-3 elsewhere.
//!
//! The step taken here follows that linear law: every such block is moved
//! [`SHRINK`] of the way to the limit at once (`α`, `β` and `c_j - p_j` scaled by it, `t_j`
//! kept), then Newton runs from there; a few rounds, while such blocks remain. Measured on the
//! κ solves of those samples: 4 of the 6 failing lemniscates then converge, in 5–78 Newton
//! iterations (the 12-point one of radius 50 in 6, at a relative residual of 2e-14). The
//! step changes no state that converged before it: it runs only where everything else failed.

use super::problem::{Outcome, Problem, Settings, State};
use super::tuning::collapse::{COLLAPSING, ROUNDS, ROUND_BUDGET, SHRINK};
use super::tuning::system::LAMBDA_MIN;
use super::Workspace;

impl<const D: usize, const B: usize> Workspace<D, B> {
    /// The collapse step of the module doc from the current state, the best of a solve that
    /// failed with `failed`: returns the first converged outcome, or `failed` with its state
    /// restored. Iterations are counted on from `failed`'s, within `set.max_iterations`.
    pub(super) fn finish_collapse(
        &mut self,
        prob: &Problem<D>,
        set: &Settings,
        failed: Outcome,
    ) -> Outcome {
        let mut total = failed.iterations;
        let best = self.state.clone();
        for _ in 0..ROUNDS {
            if total >= set.max_iterations || !self.shrink_collapsing(prob) {
                break;
            }
            let budget = Settings {
                max_iterations: ROUND_BUDGET.min(set.max_iterations - total),
                ..*set
            };
            let out = self.solve(prob, &budget, 0, false);
            total += out.iterations;
            if out.converged {
                return Outcome {
                    iterations: total,
                    ..out
                };
            }
        }
        self.state = best;
        Outcome {
            iterations: total,
            ..failed
        }
    }

    /// Moves every block collapsing at a point collinear with its neighbours ([`COLLAPSING`],
    /// [`collinear_at`](super::nudge::collinear_at)) [`SHRINK`] of the way to its limit;
    /// `false` if there is none.
    fn shrink_collapsing(&mut self, prob: &Problem<D>) -> bool {
        let n = self.n();
        let mut any = false;
        for j in 0..n {
            let prev = j as isize - 1;
            let alpha = 1.0 - self.state.ratio(prob, prev);
            let beta = self.state.lam[j];
            // (The first and last blocks of an open curve have `α = 1`, `β = 1`.)
            let collapsing = alpha < COLLAPSING && beta < COLLAPSING;
            if !(collapsing && super::nudge::collinear_at(prob, j)) {
                continue;
            }
            self.state.shrink_block(prob, j, SHRINK);
            any = true;
        }
        if any {
            self.invalidate();
        }
        any
    }
}

impl<const D: usize> State<D> {
    /// Moves block `j` along the collapse law of the module doc by the factor `r`: its
    /// ratios `α = 1 - λ_{j-1}`, `β = λ_j` and its offset `c_j - p_j` scaled by `r`, `t_j`
    /// kept (the ratios held above [`LAMBDA_MIN`]).
    pub(super) fn shrink_block(&mut self, prob: &Problem<D>, j: usize, r: f64) {
        let n = self.t.len();
        let alpha = 1.0 - self.ratio(prob, j as isize - 1);
        let p = prob.p[j];
        let c = &mut self.c[j];
        *c = core::array::from_fn(|k| p[k] + r * (c[k] - p[k]));
        if prob.closed || j > 0 {
            let i = if j == 0 { n - 1 } else { j - 1 };
            self.lam[i] = 1.0 - (r * alpha).max(LAMBDA_MIN);
        }
        if prob.closed || j + 1 < n {
            self.lam[j] = (r * self.lam[j]).max(LAMBDA_MIN);
        }
    }
}
