//! Continuation in the input points: the last fallback of a cold solve.
//!
//! Where Newton from the classic start and the continuations in the shape parameters all
//! fail, the input itself is the hard part: a walk that doubles back on itself (a hairpin
//! through a whole-pixel click), or a dense run of clicks whose curvature swings from one
//! point to the next. A slightly smoothed copy of the input, each free point moved to
//! `(p_{i-1} + 2 p_i + p_{i+1}) / 4` (open ends fixed; repeated `k` times), is an easy
//! problem of the same topology; its solution is then followed back to the input along the
//! straight path `p(s) = (1 - s) p_smooth + s p`, `s: 0 → 1`, with the adaptive steps of
//! the shape continuation ([`Workspace::follow`]). The solution followed from the smoothed
//! points can fold back before `s = 1` (measured on a 28-click walk: at `s ≈ 0.0036`);
//! where a step does not converge from the last solution, the blended input is therefore
//! solved from scratch, which can land on another branch, one that reaches the input.
//!
//! The κ- and εκ-curves are not unique, and this path may end on another solution than the
//! other strategies would: it is tried only after they have all failed, so no curve that
//! converged before changes. Measured on the integer-grid walks of
//! `tests/integer_input.rs`: every failure but the closed four-point loop that visits one
//! point twice converged after one smoothing pass, in three continuation steps.

use super::cascade::MIN_STEP;
use super::{Outcome, Problem, Settings, Workspace};

/// The smoothing passes tried, in this order: the least smoothing first, as the closest
/// easy problem.
const SMOOTHING_PASSES: [usize; 2] = [1, 4];
/// Newton budget of one step along the path: steps are long (a quarter of the way at
/// first), and on the grid walks 16 (the shape continuation's budget) or 40 iterations
/// lost three or one of the seven curves that 100 (a warm re-solve's budget) found.
const STEP_BUDGET: usize = 100;

/// `prob`'s free points after `passes` rounds of `(p_{i-1} + 2 p_i + p_{i+1}) / 4`: cyclic
/// neighbours on a closed curve, the fixed ends as neighbours on an open one.
fn smoothed<const D: usize>(prob: &Problem<D>, passes: usize) -> Vec<[f64; D]> {
    let mut p = prob.p.clone();
    let n = p.len();
    let mut prev = p.clone();
    for _ in 0..passes {
        prev.clone_from(&p);
        for (i, q) in p.iter_mut().enumerate() {
            let before = match (i, prob.closed) {
                (0, true) => prev[n - 1],
                (0, false) => prob.ghost[0],
                _ => prev[i - 1],
            };
            let after = match (i + 1 == n, prob.closed) {
                (true, true) => prev[0],
                (true, false) => prob.ghost[1],
                _ => prev[i + 1],
            };
            *q = core::array::from_fn(|k| 0.25 * (before[k] + 2.0 * prev[i][k] + after[k]));
        }
    }
    p
}

impl<const D: usize, const B: usize> Workspace<D, B> {
    /// Continuation from smoothed copies of the input ([`SMOOTHING_PASSES`]) after the
    /// cascade of [`Workspace::cascade`] failed with `failed` (its best state in
    /// `self.state`). Returns the first converged outcome, or the best of all attempts, its
    /// state in `self.state`; iterations counted on from `failed`'s.
    pub(super) fn point_continuation(
        &mut self,
        prob: &Problem<D>,
        set: &Settings,
        scratch: &mut Problem<D>,
        failed: Outcome,
    ) -> Outcome {
        let mut total = failed.iterations;
        let mut best = (failed, self.state.clone());
        let mut moving = prob.clone();
        for passes in SMOOTHING_PASSES {
            if total >= set.max_iterations || prob.p.len() < 2 {
                break;
            }
            let home = smoothed(prob, passes);
            moving.p.clone_from(&home);
            let rest = Settings {
                max_iterations: set.max_iterations - total,
                ..*set
            };
            let start = self.cascade(&moving, &rest, scratch, true);
            total += start.iterations;
            if !start.converged {
                continue;
            }
            let out = self.follow_points(prob, &mut moving, &home, set, scratch, total);
            total = out.iterations;
            if out.converged {
                return out;
            }
            if out.residual < best.0.residual {
                best = (out, self.state.clone());
            }
        }
        self.state = best.1;
        Outcome {
            iterations: total,
            ..best.0
        }
    }

    /// Follows the input from `home` (solved in the current state) to `prob`'s points
    /// along `p(s) = (1 - s) home + s p`: adaptive steps as in [`Workspace::follow`], each
    /// a Newton solve from the last solution; where that fails, a cold
    /// [`cascade`](Self::cascade) of the blended input, which may land on another
    /// solution branch (the branch through `home` can fold back before `s = 1`).
    fn follow_points(
        &mut self,
        prob: &Problem<D>,
        moving: &mut Problem<D>,
        home: &[[f64; D]],
        set: &Settings,
        scratch: &mut Problem<D>,
        mut total: usize,
    ) -> Outcome {
        let budget = |used: usize, cap: usize| Settings {
            max_iterations: cap.min(set.max_iterations.saturating_sub(used)),
            ..*set
        };
        let (mut s, mut ds) = (0.0f64, 0.25f64);
        let mut saved = self.state.clone();
        while s < 1.0 && total < set.max_iterations && ds > MIN_STEP {
            let s_try = (s + ds).min(1.0);
            for ((q, h), p) in moving.p.iter_mut().zip(home).zip(&prob.p) {
                *q = super::lerp(*h, *p, s_try);
            }
            let mut step = self.solve(moving, &budget(total, STEP_BUDGET), 0, false);
            total += step.iterations;
            if !step.converged {
                step = self.cascade(moving, &budget(total, usize::MAX), scratch, true);
                total += step.iterations;
            }
            if step.converged {
                s = s_try;
                saved.clone_from(&self.state);
                ds *= 1.5;
            } else {
                self.state.clone_from(&saved);
                ds *= 0.5;
            }
        }
        let fin = self.solve(prob, &budget(total, STEP_BUDGET), 0, false);
        Outcome {
            iterations: total + fin.iterations,
            ..fin
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smoothing_keeps_open_ends_and_wraps_closed_curves() {
        let mut prob = Problem::<2> {
            closed: false,
            p: vec![[1.0, 1.0], [2.0, 0.0]],
            ghost: [[0.0, 0.0], [3.0, 0.0]],
            basis: Vec::new(),
            tangents: Vec::new(),
        };
        // Open: the ends are the neighbours of the first and last free points.
        assert_eq!(smoothed(&prob, 1), vec![[1.0, 0.5], [2.0, 0.25]]);
        // Closed: a square's corners move halfway to its centre each pass; the centre stays.
        prob.closed = true;
        prob.p = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let s = smoothed(&prob, 2);
        let centre = s
            .iter()
            .fold([0.0; 2], |c, q| [c[0] + q[0] / 4.0, c[1] + q[1] / 4.0]);
        assert!((centre[0] - 0.5).abs() < 1e-15 && (centre[1] - 0.5).abs() < 1e-15);
        assert!(s
            .iter()
            .all(|q| (q[0] - 0.5).abs() == 0.125 && (q[1] - 0.5).abs() == 0.125));
    }
}
