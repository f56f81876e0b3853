//! Continuation out of inflections through input points: a fallback of a cold solve.
//!
//! An interior point on the line through its neighbours is an inflection through the point;
//! on a curve symmetric about it (a point-symmetric S) the κ solution there is the limit of a
//! segment shrinking onto the point ([`Joint::collapsed`](super::check)). Where several such
//! points meet in one drawing, Newton from a cold start can stall next to that limit: the
//! whole-pixel lemniscates of `tests/integer_input.rs` pass through their crossing twice,
//! each time with an inflection at the point and collinear neighbours, and stall at relative
//! residuals of 2e-11 to 9e-2 in every scheme. Moved off their lines, the same points are an
//! ordinary input: each point `p_j` collinear with its neighbours is nudged along a normal
//! `n_j` of that line by `ε_j = NUDGE d_j` (`d_j` the distance to its nearer neighbour), the
//! nudged input is solved cold, and the solution is followed back as the nudges shrink
//! geometrically, `ε_j(s) = ε_j q^s` with `q` taking the largest nudge to `END` of the
//! tolerance at `s = 1` ([`Workspace::follow`]'s adaptive steps). The final polish solves
//! the input itself from there. This is the definition of the collinear case (issue: the
//! limit of the solutions for the point moved off the line) taken literally: on the
//! 32-point lemniscate of radius 20 (εκ-cubic, a = 0.8), nudges of 1e-1 to 1e-13 pixel each
//! converge warm in 1–14 iterations, and the input itself is then met in 0 (relative residual
//! 2e-14).
//!
//! Both signs of the normal are tried (`+n_j` first). Like the point continuation, this
//! runs only after the direct attempts and the shape continuations have failed, so no curve
//! that converged before changes.

use super::cascade::Homotopy;
use super::tuning::nudge::{BUDGET, COLLINEAR, END, MIN_STEP, NUDGE, STEP_BUDGET};
use super::{dot, Outcome, Problem, Settings, Workspace};

/// For each free point of `prob` collinear with its neighbours ([`COLLINEAR`]), its nudge:
/// a unit normal of the neighbours' line times [`NUDGE`] times the distance to the nearer
/// neighbour; zero for the other points. `None` if no point is collinear with its
/// neighbours. The normal is `e_k` made orthogonal to the line, `e_k` the coordinate axis
/// the line is least along among the coordinates the input does not share (a space curve in
/// a coordinate plane stays in it).
fn nudges<const D: usize>(prob: &Problem<D>) -> Option<Vec<[f64; D]>> {
    let fixed = super::points::shared_coordinates(prob);
    let mut any = false;
    let out = (0..prob.p.len())
        .map(|i| {
            if !collinear_at(prob, i) {
                return [0.0; D];
            }
            let (a, c) = super::points::neighbours(prob, i);
            let p = prob.p[i];
            let u = super::sub(c, a);
            let w = super::sub(p, a);
            let (uu, ww) = (dot(u, u), dot(w, w));
            let Some(k) = (0..D)
                .filter(|&k| !fixed[k])
                .min_by(|&x, &y| u[x].abs().total_cmp(&u[y].abs()))
            else {
                return [0.0; D];
            };
            let mut n: [f64; D] = core::array::from_fn(|j| f64::from(u8::from(j == k)));
            let along = u[k] / uu;
            for (nj, uj) in n.iter_mut().zip(u) {
                *nj -= along * uj;
            }
            let len = dot(n, n).sqrt();
            let d = ww.min(dot(super::sub(c, p), super::sub(c, p))).sqrt();
            if !(len > 1e-3) || !(d > 0.0) {
                return [0.0; D];
            }
            any = true;
            n.map(|x| x / len * NUDGE * d)
        })
        .collect();
    any.then_some(out)
}

/// Whether point `i` of `prob` is collinear with its neighbours (the ghost points at the
/// ends of an open curve): the sine of the angle between `p_i - p_{i-1}` and
/// `p_{i+1} - p_{i-1}` is at most [`COLLINEAR`].
pub(super) fn collinear_at<const D: usize>(prob: &Problem<D>, i: usize) -> bool {
    let (a, c) = super::points::neighbours(prob, i);
    let u = super::sub(c, a);
    let w = super::sub(prob.p[i], a);
    let (uu, ww, uw) = (dot(u, u), dot(w, w), dot(u, w));
    let cross2 = (uu * ww - uw * uw).max(0.0);
    uu > 0.0 && ww > 0.0 && cross2 <= COLLINEAR * COLLINEAR * uu * ww
}

impl<const D: usize, const B: usize> Workspace<D, B> {
    /// The continuation out of nudged inflections (see the module doc), after the cascade
    /// failed with `failed` (its best state in `self.state`). Returns the first converged
    /// outcome, or `failed` with its state restored; iterations counted on from `failed`'s.
    pub(super) fn nudge_continuation(
        &mut self,
        prob: &Problem<D>,
        set: &Settings,
        scratch: &mut Problem<D>,
        failed: Outcome,
    ) -> Outcome {
        let Some(nudge) = nudges(prob) else {
            return failed;
        };
        let mut total = failed.iterations;
        let best = self.state.clone();
        let largest = nudge.iter().fold(0.0f64, |m, v| m.max(dot(*v, *v).sqrt()));
        let q = END * set.tolerance / largest;
        let mut moving = prob.clone();
        for sign in [1.0, -1.0] {
            if total >= set.max_iterations || !(q < 1.0) {
                break;
            }
            let limit = set.max_iterations.min(total + BUDGET);
            let at = |moving: &mut Problem<D>, s: f64| {
                let f = sign * q.powf(s);
                for ((m, p), v) in moving.p.iter_mut().zip(&prob.p).zip(&nudge) {
                    *m = core::array::from_fn(|k| p[k] + f * v[k]);
                }
            };
            at(&mut moving, 0.0);
            let rest = Settings {
                max_iterations: limit - total,
                ..*set
            };
            let start = self.cascade(&moving, &rest, scratch, true);
            total += start.iterations;
            if !start.converged {
                continue;
            }
            let budget = |used: usize, cap: usize| Settings {
                max_iterations: cap.min(limit.saturating_sub(used)),
                ..*set
            };
            // One decade of nudge a step: each takes 5–50 Newton steps on the lemniscates
            // (the convergence is linear next to a collapsing segment), where longer steps
            // failed and cost their whole budget.
            let decades = -q.log10();
            let steps = Homotopy {
                max_iterations: limit,
                min_step: MIN_STEP,
                step_budget: STEP_BUDGET,
                first_step: 1.0 / decades,
                growth: 1.0,
            };
            let out = self.follow(prob, &mut moving, at, budget, steps, total);
            total = out.iterations;
            if out.converged {
                return out;
            }
        }
        self.state = best;
        Outcome {
            iterations: total,
            ..failed
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nudges_move_collinear_points_across_their_line() {
        // An open wave: the middle point is on the line through its neighbours, the others
        // are not.
        let prob = Problem::<2> {
            closed: false,
            p: vec![[1.0, 1.0], [2.0, 0.0], [3.0, -1.0]],
            ghost: [[0.0, 0.0], [4.0, 0.5]],
            basis: Vec::new(),
            tangents: Vec::new(),
        };
        let v = nudges(&prob).expect("a collinear point");
        assert_eq!(v[0], [0.0, 0.0]);
        assert_eq!(v[2], [0.0, 0.0]);
        // Normal to the line (1, 1) → (3, -1), both neighbours √2 away.
        let u = [2.0, -2.0];
        assert!(dot(v[1], u).abs() < 1e-15);
        let len = dot(v[1], v[1]).sqrt();
        assert!((len - NUDGE * 2f64.sqrt()).abs() < 1e-15, "{len}");
        // No collinear point: nothing to nudge.
        let mut bent = prob.clone();
        bent.p[1] = [2.0, 0.1];
        assert!(nudges(&bent).is_none());
    }

    #[test]
    fn nudges_keep_a_shared_coordinate() {
        // A space curve in the plane z = 5: the nudge stays in the plane.
        let prob = Problem::<3> {
            closed: true,
            p: vec![
                [0.0, 0.0, 5.0],
                [1.0, 1.0, 5.0],
                [2.0, 2.0, 5.0],
                [1.0, 3.0, 5.0],
            ],
            ghost: [[0.0; 3]; 2],
            basis: Vec::new(),
            tangents: Vec::new(),
        };
        let v = nudges(&prob).expect("a collinear point");
        assert_eq!(v[1][2], 0.0);
        assert!(v[1][0] != 0.0 && (v[1][0] + v[1][1]).abs() < 1e-15);
    }
}
