//! Newton's method on the whole system: the solve loop, Newton steps with their line
//! search, and chord steps with stored factors.

use super::check::Joint;
use super::problem::{Outcome, Problem, Settings, State};
use super::split::split_min;
use super::tuning::check::STRAIGHTISH;
use super::tuning::newton::{
    CHORD_CONTRACTION, EXPAND_RATIO, MAX_CHORD, NEAR_CHORD_CONTRACTION, NEWTON_CHORD_CONTRACTION,
    NEWTON_CHORD_MIN_BLOCKS, NEWTON_CHORD_NEAR, PARTNER, QUADRATIC_REGION, T_LANDING,
};
use super::workspace::{LinState, Workspace};
use super::{sub, LAMBDA_MIN};
use crate::parallel::join;

/// Whether a joint ratio is usable after a step: inside `(0, 1]` (1 up to rounding, for the
/// fixed last ratio of open curves).
#[inline]
pub(super) fn lambda_valid(lam: f64) -> bool {
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

impl<const D: usize, const B: usize> Workspace<D, B> {
    /// Solve from the current state (a cold start or a previous solution), after `classic`
    /// iterations of the classic loop; with `loose`, those solve for `t` only to
    /// [`START_PEAK_T_TOLERANCE`](super::tuning::peak::START_PEAK_T_TOLERANCE) (the first attempt of a cold solve: the fallbacks start as
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

    /// One Newton step with backtracking; `false` if no acceptable step was found.
    pub(super) fn newton_step(&mut self, prob: &Problem<D>, phi: f64, tol: f64) -> bool {
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
}
