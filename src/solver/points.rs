//! Continuation in the input points: the last fallback of a cold solve.
//!
//! Where Newton from the classic start and the continuations in the shape parameters all
//! fail, the input itself is the hard part: a walk that doubles back on itself (a hairpin
//! through a whole-pixel click), or a dense run of clicks whose curvature swings from one
//! point to the next. A nearby problem of the same topology is usually easy: first the
//! input smoothed once, each free point moved to `(p_{i-1} + 2 p_i + p_{i+1}) / 4` (open
//! ends fixed), which suits dense samples of a smooth curve; then jittered copies, each
//! free point `p_i` moved by a pseudo-random offset of up to [`JITTER`] of the distance to
//! its nearer neighbour in each coordinate, which break the special configurations that
//! make grid walks hard (a click exactly two steps back, three clicks on a line). The
//! home's solution is followed back to the input along the straight path
//! `p(s) = (1 - s) p_home + s p`, `s: 0 → 1`, with the adaptive steps of the shape
//! continuation ([`Workspace::follow`]). The branch followed can fold back before
//! `s = 1`; where a step does not converge from the last solution, the blended input is
//! therefore solved from scratch (without the shape continuations), which can land on
//! another branch, one that reaches the input. Each home has a budget
//! ([`SMOOTHED_BUDGET`], [`HOME_BUDGET`]); the next home (another pseudo-random draw,
//! seeded by its index, so a solve is reproducible) starts where one runs out.
//!
//! The κ- and εκ-curves are not unique, and this path may end on another solution than the
//! other strategies would: it is tried only after they have all failed, so no curve that
//! converged before changes.
//!
//! Measured on 4 000 integer-grid walks (`examples/walks.rs`, seed 7, the default 4 000
//! iterations): the κ-curve failed on 11 walks with the earlier homes (the input smoothed
//! once, then four times, each followed without a budget of its own down to steps of
//! 1e-6) and fails on 2 with these (as with the jittered homes alone, which lose the
//! 35-point sine). Every one of the 11 converges with a larger cap (3 577–20 018
//! iterations): the earlier homes spent the budget on one fold. Jitter of 1/16 or 1/4 of
//! the neighbour distance, per-home budgets of 200 or 400, or a secant predictor along the
//! path each lost more walks than these settings.

use super::tuning::points::{HOMES, HOME_BUDGET, JITTER, MIN_STEP, SMOOTHED_BUDGET, STEP_BUDGET};
use super::{Outcome, Problem, Settings, Workspace};

/// A pseudo-random number in `[-1, 1)` from `state` (a 64-bit LCG step, Knuth's
/// constants; the top 53 bits).
fn uniform(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6_364_136_223_846_793_005)
        .wrapping_add(1_442_695_040_888_963_407);
    (*state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
}

/// `prob`'s free points each moved by a pseudo-random offset ([`JITTER`]) drawn from
/// `seed`: cyclic neighbours on a closed curve, the fixed ends as neighbours on an open one.
/// A coordinate that every point shares is kept, so that a space curve through points in a
/// coordinate plane stays in it exactly.
fn jittered<const D: usize>(prob: &Problem<D>, seed: u64) -> Vec<[f64; D]> {
    let n = prob.p.len();
    let mut state = seed
        .wrapping_mul(0x9E37_79B9_7F4A_7C15)
        .wrapping_add(12_345);
    let dist = |a: [f64; D], b: [f64; D]| (0..D).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt();
    let fixed = shared_coordinates(prob);
    (0..n)
        .map(|i| {
            let (before, after) = neighbours(prob, i);
            let r = JITTER * dist(before, prob.p[i]).min(dist(after, prob.p[i]));
            core::array::from_fn(|k| {
                let u = uniform(&mut state);
                prob.p[i][k] + if fixed[k] { 0.0 } else { r * u }
            })
        })
        .collect()
}

/// The coordinates every input point shares (planar input in a coordinate plane): moves of
/// the input keep them.
pub(super) fn shared_coordinates<const D: usize>(prob: &Problem<D>) -> [bool; D] {
    let ends = if prob.closed {
        &prob.ghost[..0]
    } else {
        &prob.ghost[..]
    };
    core::array::from_fn(|k| prob.p.iter().chain(ends).all(|q| q[k] == prob.p[0][k]))
}

/// `prob`'s free points after one round of `(p_{i-1} + 2 p_i + p_{i+1}) / 4`: cyclic
/// neighbours on a closed curve, the fixed ends as neighbours on an open one.
fn smoothed<const D: usize>(prob: &Problem<D>) -> Vec<[f64; D]> {
    let n = prob.p.len();
    (0..n)
        .map(|i| {
            let (before, after) = neighbours(prob, i);
            core::array::from_fn(|k| 0.25 * (before[k] + 2.0 * prob.p[i][k] + after[k]))
        })
        .collect()
}

/// The neighbours of free point `i`: cyclic on a closed curve, the fixed ends next to the
/// first and last points of an open one.
pub(super) fn neighbours<const D: usize>(prob: &Problem<D>, i: usize) -> ([f64; D], [f64; D]) {
    let n = prob.p.len();
    let before = match (i, prob.closed) {
        (0, true) => prob.p[n - 1],
        (0, false) => prob.ghost[0],
        _ => prob.p[i - 1],
    };
    let after = match (i + 1 == n, prob.closed) {
        (true, true) => prob.p[0],
        (true, false) => prob.ghost[1],
        _ => prob.p[i + 1],
    };
    (before, after)
}

impl<const D: usize, const B: usize> Workspace<D, B> {
    /// Continuation from the smoothed input, then from jittered copies of it (up to
    /// [`HOMES`]), after the cascade of [`Workspace::cascade`] failed with `failed` (its
    /// best state in `self.state`).
    /// Returns the first converged outcome, or the best of all attempts, its state in
    /// `self.state`; iterations counted on from `failed`'s.
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
        // Home 0 is the smoothed input, then the jittered copies.
        for home in 0..=HOMES {
            if total >= set.max_iterations || prob.p.len() < 2 {
                break;
            }
            let (home, budget) = match home {
                0 => (smoothed(prob), SMOOTHED_BUDGET),
                seed => (jittered(prob, seed), HOME_BUDGET),
            };
            moving.p.clone_from(&home);
            let limit = set.max_iterations.min(total + budget);
            let rest = Settings {
                max_iterations: limit - total,
                ..*set
            };
            let start = self.cascade(&moving, &rest, scratch, false);
            total += start.iterations;
            if !start.converged {
                continue;
            }
            let out = self.follow_points(prob, &mut moving, &home, set, scratch, total, limit);
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
    /// along `p(s) = (1 - s) home + s p`, counting iterations on from `total` up to
    /// `limit`: adaptive steps as in [`Workspace::follow`], each a Newton solve from the
    /// last solution; where that fails, a cold [`cascade`](Self::cascade) of the blended
    /// input without shape continuations, which may land on another solution branch (the
    /// branch through `home` can fold back before `s = 1`).
    #[allow(clippy::too_many_arguments)]
    fn follow_points(
        &mut self,
        prob: &Problem<D>,
        moving: &mut Problem<D>,
        home: &[[f64; D]],
        set: &Settings,
        scratch: &mut Problem<D>,
        mut total: usize,
        limit: usize,
    ) -> Outcome {
        let budget = |used: usize, cap: usize| Settings {
            max_iterations: cap.min(limit.saturating_sub(used)),
            ..*set
        };
        let (mut s, mut ds) = (0.0f64, 0.25f64);
        let mut saved = self.state.clone();
        while s < 1.0 && total < limit && ds > MIN_STEP {
            let s_try = (s + ds).min(1.0);
            for ((q, h), p) in moving.p.iter_mut().zip(home).zip(&prob.p) {
                *q = super::lerp(*h, *p, s_try);
            }
            let mut step = self.solve(moving, &budget(total, STEP_BUDGET), 0, false);
            total += step.iterations;
            if !step.converged {
                step = self.cascade(moving, &budget(total, usize::MAX), scratch, false);
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
    fn jitter_stays_within_its_radius_and_is_reproducible() {
        let mut prob = Problem::<2> {
            closed: false,
            p: vec![[1.0, 0.0], [2.0, 0.0], [6.0, 0.0]],
            ghost: [[0.0, 0.0], [10.0, 0.0]],
            basis: Vec::new(),
            tangents: Vec::new(),
        };
        for closed in [false, true] {
            prob.closed = closed;
            // Nearer-neighbour distances: 1, 1, 4 open (the ends are neighbours); 1, 1, 4
            // closed as well (6 → 1 wraps to 5, 6 → 2 is 4).
            let radii = [1.0, 1.0, 4.0].map(|d| JITTER * d);
            let mut moved = 0.0f64;
            for seed in 1..=HOMES {
                let j = jittered(&prob, seed);
                assert_eq!(j, jittered(&prob, seed));
                for ((q, p), r) in j.iter().zip(&prob.p).zip(radii) {
                    for k in 0..2 {
                        assert!((q[k] - p[k]).abs() <= r);
                        moved = moved.max((q[k] - p[k]).abs() / r);
                    }
                }
            }
            // The draws use most of the radius.
            assert!(moved > 0.9, "{moved}");
        }
        assert_ne!(jittered(&prob, 1), jittered(&prob, 2));
    }

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
        assert_eq!(smoothed(&prob), vec![[1.0, 0.5], [2.0, 0.25]]);
        // Closed: a square's corners move halfway to its centre; the centre stays.
        prob.closed = true;
        prob.p = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let s = smoothed(&prob);
        let centre = s
            .iter()
            .fold([0.0; 2], |c, q| [c[0] + q[0] / 4.0, c[1] + q[1] / 4.0]);
        assert!((centre[0] - 0.5).abs() < 1e-15 && (centre[1] - 0.5).abs() < 1e-15);
        assert!(s
            .iter()
            .all(|q| (q[0] - 0.5).abs() == 0.25 && (q[1] - 0.5).abs() == 0.25));
    }
}
