//! Cold solves: Newton after a few classic iterations, then continuation in the shape
//! parameters.

use super::problem::{Outcome, Problem, Settings, State};
use super::tuning::cascade::{
    Descent, ATTEMPT_BUDGET, A_HOMES, A_HOMES_TRIG, CLASSIC_START, CLASSIC_STARTS, FINE,
};
use super::tuning::newton::NEWTON_CHORD_MIN_BLOCKS;
use super::workspace::Workspace;
use crate::basis::Basis;

/// The limits of [`Workspace::follow`]: the iteration budget and the smallest step.
#[derive(Clone, Copy, Debug)]
pub(super) struct Homotopy {
    pub(super) max_iterations: usize,
    pub(super) min_step: f64,
    /// Newton budget of one step.
    pub(super) step_budget: usize,
    /// The first step in `s`.
    pub(super) first_step: f64,
    /// The factor of the step after a converged one.
    pub(super) growth: f64,
    /// The iterations spent before the homotopy starts, which count towards
    /// `max_iterations`.
    pub(super) spent: usize,
}

impl<const D: usize, const B: usize> Workspace<D, B> {
    /// Solve from a cold start: the [`cascade`](Self::cascade) of direct attempts and
    /// shape continuations, then the [`nudge`](super::nudge) continuation out of
    /// inflections through input points, then continuation from smoothed and jittered input
    /// points ([`points`](super::points)) where all of those fail. Where points lie near
    /// their neighbours' line but none on it, the cascade leaves the nudge its
    /// [`BUDGET`](super::tuning::nudge::BUDGET) (a quarter of a smaller budget): such a
    /// cascade can spend all it is given (the 12-point whole-pixel lemniscate with its
    /// crossings 1e-9 of its size off their lines: 4 000 iterations, then the nudge solves
    /// it in 260). The total iteration count
    /// is reported, and the best state found is kept if nothing converges.
    pub(crate) fn solve_cold(
        &mut self,
        prob: &Problem<D>,
        set: &Settings,
        scratch: &mut Problem<D>,
    ) -> Outcome {
        let reserve = if super::nudge::near_only(prob) {
            super::tuning::nudge::BUDGET.min(set.max_iterations / 4)
        } else {
            0
        };
        let first = Settings {
            max_iterations: set.max_iterations.saturating_sub(reserve),
            ..*set
        };
        let out = self.cascade(prob, &first, scratch, true);
        if out.converged || out.iterations >= set.max_iterations {
            return out;
        }
        let out = self.nudge_continuation(prob, set, scratch, out);
        if out.converged || out.iterations >= set.max_iterations {
            return out;
        }
        self.point_continuation(prob, set, scratch, out)
    }

    /// Newton after a few classic iterations (3, 1, then 12), then, if `shapes`,
    /// continuation in the shape parameters from the first two of [`A_HOMES`], [`FINE`], then
    /// the other homes. Every attempt is capped; the total iteration count is reported, and
    /// the best state found is kept if none converges.
    pub(super) fn cascade(
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
        // Not on trigonometric segments: there it lost 6 of the 3 997 grid walks of seed 11
        // (the point continuation after it, which solves those, got less budget) and gained
        // no whole-pixel sample.
        let trig = matches!(prob.basis.first(), Some(Basis::Trig(_)));
        let fine = (shapes && !trig).then_some(FINE);
        let split = homes.len().min(2);
        let order = homes[..split]
            .iter()
            .map(|&h| Descent::coarse(h))
            .chain(fine)
            .chain(homes[split..].iter().map(|&h| Descent::coarse(h)));
        for descent in order {
            if total >= set.max_iterations {
                break;
            }
            let out = self.continuation(prob, set, scratch, total, descent);
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

    /// Continuation from the shape `descent.home` to the target shapes with adaptive steps.
    fn continuation(
        &mut self,
        prob: &Problem<D>,
        set: &Settings,
        scratch: &mut Problem<D>,
        used: usize,
        descent: Descent,
    ) -> Outcome {
        let home = descent.home;
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
        let mut first = self.solve(
            scratch,
            &budget(total, ATTEMPT_BUDGET),
            CLASSIC_START,
            false,
        );
        total += first.iterations;
        if !first.converged && descent.nudge_home {
            let home = scratch.clone();
            let mut inner = scratch.clone();
            let rest = Settings {
                max_iterations: descent.budget.min(set.max_iterations.saturating_sub(total)),
                ..*set
            };
            let failed = Outcome {
                iterations: 0,
                ..first
            };
            first = self.nudge_continuation(&home, &rest, &mut inner, failed);
            total += first.iterations;
        }
        if !first.converged {
            out.iterations = total;
            out.residual = f64::INFINITY;
            return out;
        }
        // (s = 1 exactly reproduces the shapes.)
        let steps = Homotopy {
            max_iterations: set.max_iterations.min(used.saturating_add(descent.budget)),
            min_step: descent.min_step,
            step_budget: descent.step_budget,
            first_step: descent.first_step,
            growth: 1.5,
            spent: total,
        };
        self.follow(prob, scratch, blend, |_, _, _, _| false, budget, steps)
    }

    /// Follows a homotopy from `s = 0`, solved in the current state, to `s = 1`: `blend`
    /// sets `moving` to the problem at `s`; steps start at `steps.first_step`, grow by
    /// `steps.growth` after a converged step and halve after a failed one (back to the last
    /// solution), until `s` reaches 1, the steps shrink below `steps.min_step` or the
    /// iterations (counted on from `steps.spent`, each step capped at
    /// [`STEP_BUDGET`](super::tuning::cascade::STEP_BUDGET) through `budget`) reach
    /// `steps.max_iterations`. A final polish solves `prob` itself, and where it fails, the
    /// [`collapse`](super::collapse) step from its state (within the same budget). Where the
    /// homotopy moves the input points, each step first moves every control point `c_j` with its
    /// point `p_j` (as a warm re-solve does): a segment near its collapsed limit has `c_j`
    /// within its tiny extent of `p_j`, and left behind it would start Newton on the wrong
    /// side of the point. Then `predict(state, moving, s, s_try)` may move the unknowns
    /// towards the step's solution (`true` if it did).
    pub(super) fn follow(
        &mut self,
        prob: &Problem<D>,
        moving: &mut Problem<D>,
        mut blend: impl FnMut(&mut Problem<D>, f64),
        mut predict: impl FnMut(&mut State<D>, &Problem<D>, f64, f64) -> bool,
        budget: impl Fn(usize, usize) -> Settings,
        steps: Homotopy,
    ) -> Outcome {
        let mut total = steps.spent;
        let (mut s, mut ds) = (0.0f64, steps.first_step);
        let mut saved = self.state.clone();
        // The points of the saved state.
        let mut at = moving.p.clone();
        let carry = |c: &mut [[f64; D]], to: &[[f64; D]], from: &[[f64; D]]| {
            for ((c, p), q) in c.iter_mut().zip(to).zip(from) {
                *c = core::array::from_fn(|k| c[k] + (p[k] - q[k]));
            }
        };
        while s < 1.0 && total < steps.max_iterations && ds > steps.min_step {
            let s_try = (s + ds).min(1.0);
            blend(moving, s_try);
            carry(&mut self.state.c, &moving.p, &at);
            if predict(&mut self.state, moving, s, s_try) {
                self.invalidate();
            }
            let step = self.solve(moving, &budget(total, steps.step_budget), 0, false);
            total += step.iterations;
            if step.converged {
                s = s_try;
                saved.clone_from(&self.state);
                at.clone_from(&moving.p);
                ds *= steps.growth;
            } else {
                self.state.clone_from(&saved);
                ds *= 0.5;
            }
        }
        carry(&mut self.state.c, &prob.p, &at);
        let fin = self.solve(prob, &budget(total, steps.step_budget), 0, false);
        let fin = Outcome {
            iterations: total + fin.iterations,
            ..fin
        };
        if fin.converged {
            return fin;
        }
        let rest = budget(fin.iterations, usize::MAX);
        let rest = Settings {
            max_iterations: fin.iterations + rest.max_iterations,
            ..rest
        };
        self.finish_collapse(prob, &rest, fin)
    }
}
