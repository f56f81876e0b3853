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
//! A point just off its neighbours' line ([`NEAR`]) is the same problem seen from one side:
//! its solution tends to the collinear one linearly in the offset, and Newton from a cold
//! start stalls there as well (κ, the 12-point lemniscate of radius 50 with its crossings
//! moved 1e-9 of its size off their lines: relative residual 2e-7 after 4 000 iterations).
//! Such a point is nudged further to its own side, to `NUDGE d_j` from the line, and the
//! path ends at the input itself, so it stays on the branch the input is on.
//!
//! Along its path, the segment through such a point near its collapsed limit shrinks with
//! the point's distance `δ` from the line (the law of [`collapse`](super::collapse)): each
//! step first scales its ratios and its offset `c_j - p_j` by `δ(s_1) / δ(s_0)`
//! ([`PREDICT`]), then Newton corrects. On that lemniscate the path then takes 260 Newton
//! iterations; without the prediction a decade of nudge cost 40–100 and the path ran out of
//! budget halfway. (Points on their line are not predicted: on the grid walks of seed 7,
//! two more κ walks failed with it.) The solutions are 69.2 ε from the collinear one at
//! offsets ε from 1e-1 to 1e-9 of the drawing size (`tests/inflection.rs`).
//!
//! A point on its neighbours' line whose points two away both lie on one side of it is a
//! flat spot, not an inflection: the curve bends the same way before and after it. Such a
//! point is nudged to the other side only, where the input turns around it as it does around
//! its neighbours (a rounded square's side, a lobe of a whole-pixel lemniscate). Nudged to
//! the wrong side too, it took the 48-point lemniscates of radius 20 and 50 out of the κ
//! pixel samples (77 of 84 instead of 79). At the other points on their line, both signs of
//! the normal are tried (`+n_j` first). Like the
//! point continuation, this runs only after the direct attempts and the shape continuations
//! have failed, so no curve that converged before changes (but for a cascade with points
//! near their line, which now ends [`BUDGET`] iterations earlier, or a quarter of a smaller
//! budget).

use super::cascade::Homotopy;
use super::tuning::nudge::{BUDGET, COLLINEAR, END, MIN_STEP, NEAR, NUDGE, PREDICT, STEP_BUDGET};
use super::{dot, Outcome, Problem, Settings, State, Workspace};

/// One point's nudge: the displacement at the start of the path, and whether its sign is
/// free (a point on its neighbours' line can be nudged to either side, but for a flat spot;
/// a point just off the line is nudged further to its own side, so the path ends at the input
/// on the branch the input is on).
#[derive(Clone, Copy)]
struct Nudge<const D: usize> {
    v: [f64; D],
    signed: bool,
    /// The input point's distance from its neighbours' line.
    base: f64,
}

impl<const D: usize> Nudge<D> {
    /// The distance from the line at nudge factor `f` (`f |v|` past [`base`](Self::base)).
    fn offset(&self, f: f64) -> f64 {
        self.base + f * dot(self.v, self.v).sqrt()
    }
}

/// For each free point of `prob` collinear with its neighbours ([`COLLINEAR`]) or close to it
/// ([`NEAR`]), its nudge: a unit normal of the neighbours' line times the distance from the
/// line to [`NUDGE`] times the distance to the nearer neighbour; zero for the other points.
/// `None` if no point is near its neighbours' line. On the line, the normal is `e_k` made
/// orthogonal to the line, `e_k` the coordinate axis the line is least along among the
/// coordinates the input does not share (a space curve in a coordinate plane stays in it);
/// off it, the normal points to the point's side.
fn nudges<const D: usize>(prob: &Problem<D>) -> Option<Vec<Nudge<D>>> {
    let fixed = super::points::shared_coordinates(prob);
    let mut any = false;
    let none = Nudge {
        v: [0.0; D],
        signed: false,
        base: 0.0,
    };
    let out = (0..prob.p.len())
        .map(|i| {
            let Some(sine) = sine_at(prob, i) else {
                return none;
            };
            if sine > NEAR {
                return none;
            }
            let (a, c) = super::points::neighbours(prob, i);
            let p = prob.p[i];
            let u = super::sub(c, a);
            let w = super::sub(p, a);
            let (uu, ww) = (dot(u, u), dot(w, w));
            let d = ww.min(dot(super::sub(c, p), super::sub(c, p))).sqrt();
            // The point's offset from the line.
            let along = dot(u, w) / uu;
            let off: [f64; D] = core::array::from_fn(|k| w[k] - along * u[k]);
            let reach = NUDGE * d;
            let on_line = sine <= COLLINEAR;
            let base = if on_line { 0.0 } else { dot(off, off).sqrt() };
            let (n, to, signed) = if on_line {
                let Some(k) = (0..D)
                    .filter(|&k| !fixed[k])
                    .min_by(|&x, &y| u[x].abs().total_cmp(&u[y].abs()))
                else {
                    return none;
                };
                let mut n: [f64; D] = core::array::from_fn(|j| f64::from(u8::from(j == k)));
                let along = u[k] / uu;
                for (nj, uj) in n.iter_mut().zip(u) {
                    *nj -= along * uj;
                }
                // A flat spot: the points two away lie on one side of the line, so the
                // curve bends the same way on both sides; the point goes to the other side,
                // where the input turns the same way it does around it.
                match flat_side(prob, i, n) {
                    Some(side) => (n.map(|x| side * x), reach, false),
                    None => (n, reach, true),
                }
            } else {
                (off, reach - base, false)
            };
            let len = dot(n, n).sqrt();
            if !(len > 1e-3 * if on_line { 1.0 } else { d * sine }) || !(d > 0.0) || !(to > 0.0) {
                return none;
            }
            any = true;
            Nudge {
                v: n.map(|x| x / len * to),
                signed,
                base,
            }
        })
        .collect();
    any.then_some(out)
}

/// For a point on its neighbours' line with normal `n`: `Some(±1)` if the points two away
/// along the curve both lie strictly on one side of the line (the side `∓n`), `None` if they
/// lie on opposite sides or on the line, or one of them is missing (the ends of an open
/// curve).
fn flat_side<const D: usize>(prob: &Problem<D>, i: usize, n: [f64; D]) -> Option<f64> {
    let m = prob.p.len();
    // The neighbour before the one before, and after the one after (ghosts included).
    let before = match (i, prob.closed) {
        (0, false) => return None,
        (0, true) => m - 1,
        _ => i - 1,
    };
    let after = match (i + 1 == m, prob.closed) {
        (true, false) => return None,
        (true, true) => 0,
        _ => i + 1,
    };
    let a = super::points::neighbours(prob, before).0;
    let c = super::points::neighbours(prob, after).1;
    let p = prob.p[i];
    let (sa, sc) = (dot(n, super::sub(a, p)), dot(n, super::sub(c, p)));
    let scale = dot(n, n).sqrt() * dot(super::sub(a, c), super::sub(a, c)).sqrt();
    let tiny = COLLINEAR * scale;
    if sa > tiny && sc > tiny {
        Some(-1.0)
    } else if sa < -tiny && sc < -tiny {
        Some(1.0)
    } else {
        None
    }
}

/// Whether `prob` has a point near its neighbours' line ([`NEAR`]) but none on it
/// ([`COLLINEAR`]).
pub(super) fn near_only<const D: usize>(prob: &Problem<D>) -> bool {
    let mut near = false;
    for i in 0..prob.p.len() {
        match sine_at(prob, i) {
            Some(s) if s <= COLLINEAR => return false,
            Some(s) if s <= NEAR => near = true,
            _ => {}
        }
    }
    near
}

/// The sine of the angle between `p_i - p_{i-1}` and `p_{i+1} - p_{i-1}` at point `i` of
/// `prob` (the ghost points at the ends of an open curve); `None` where two of the points
/// coincide.
///
/// `|u × w|² = Σ_{j<k} (u_j w_k − u_k w_j)²` (Lagrange's identity), summed over the 2×2
/// minors: each minor is exact to a rounding of `|u| |w|`, so the sine is exact to about
/// 1e-16. The shorter `|u|²|w|² − (u·w)²` cancels, and reads collinear whole-pixel points
/// at sines near 1e-8, inside the near band.
fn sine_at<const D: usize>(prob: &Problem<D>, i: usize) -> Option<f64> {
    let (a, c) = super::points::neighbours(prob, i);
    let u = super::sub(c, a);
    let w = super::sub(prob.p[i], a);
    let (uu, ww) = (dot(u, u), dot(w, w));
    let mut cross2 = 0.0;
    for j in 0..D {
        for k in j + 1..D {
            let m = u[j] * w[k] - u[k] * w[j];
            cross2 += m * m;
        }
    }
    (uu > 0.0 && ww > 0.0).then(|| (cross2.sqrt() / (uu.sqrt() * ww.sqrt())).min(1.0))
}

/// Whether point `i` of `prob` is collinear with its neighbours (the ghost points at the
/// ends of an open curve): the sine of the angle between `p_i - p_{i-1}` and
/// `p_{i+1} - p_{i-1}` is at most [`COLLINEAR`].
pub(super) fn collinear_at<const D: usize>(prob: &Problem<D>, i: usize) -> bool {
    sine_at(prob, i).is_some_and(|s| s <= COLLINEAR)
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
        let largest = nudge
            .iter()
            .fold(0.0f64, |m, n| m.max(dot(n.v, n.v).sqrt()));
        let signs = if nudge.iter().any(|n| n.signed) { 2 } else { 1 };
        let q = END * set.tolerance / largest;
        let mut moving = prob.clone();
        for sign in [1.0, -1.0].into_iter().take(signs) {
            if total >= set.max_iterations || !(q < 1.0) {
                break;
            }
            let limit = set.max_iterations.min(total + BUDGET);
            let at = |moving: &mut Problem<D>, s: f64| {
                let f = q.powf(s);
                for ((m, p), n) in moving.p.iter_mut().zip(&prob.p).zip(&nudge) {
                    let f = if n.signed { sign * f } else { f };
                    *m = core::array::from_fn(|k| p[k] + f * n.v[k]);
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
                spent: total,
            };
            // A segment collapsing onto a nudged point shrinks with the point's distance from
            // its line (the law of [`collapse`](super::collapse)): each step first scales it
            // by the ratio of the distances.
            let predict = |st: &mut State<D>, moving: &Problem<D>, s0: f64, s1: f64| {
                let (f0, f1) = (q.powf(s0), q.powf(s1));
                let mut any = false;
                for (j, n) in nudge.iter().enumerate() {
                    let r = n.offset(f1) / n.offset(f0);
                    let alpha = 1.0 - st.ratio(moving, j as isize - 1);
                    if n.base > 0.0 && r < 1.0 && alpha < PREDICT && st.lam[j] < PREDICT {
                        st.shrink_block(moving, j, r);
                        any = true;
                    }
                }
                any
            };
            let out = self.follow(prob, &mut moving, at, predict, budget, steps);
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
        let v: Vec<_> = nudges(&prob)
            .expect("a collinear point")
            .iter()
            .map(|n| n.v)
            .collect();
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
    fn a_point_just_off_its_line_is_nudged_to_its_own_side() {
        let mut prob = Problem::<2> {
            closed: false,
            p: vec![[1.0, 1.0], [2.0, 0.0], [3.0, -1.0]],
            ghost: [[0.0, 0.0], [4.0, 0.5]],
            basis: Vec::new(),
            tangents: Vec::new(),
        };
        assert!(!near_only(&prob));
        // 1e-6 off the line x + y = 2, to the side of (1, 1).
        let delta = 1e-6;
        let side = [0.5f64.sqrt(), 0.5f64.sqrt()];
        prob.p[1] = [2.0 + delta * side[0], delta * side[1]];
        assert!(near_only(&prob));
        let v = nudges(&prob).expect("a near point");
        assert!(!v[1].signed);
        assert!((v[1].base - delta).abs() < 1e-15, "{}", v[1].base);
        // To `NUDGE d` from the line in all, on the point's side.
        let d = 2f64.sqrt();
        let along = dot(v[1].v, side);
        assert!((along - (NUDGE * d - delta)).abs() < 1e-12, "{along}");
        assert!((v[1].offset(1.0) - NUDGE * d).abs() < 1e-12);
        assert!((v[1].offset(0.0) - delta).abs() < 1e-15);
        // Far off the line: no nudge.
        prob.p[1] = [2.0, 0.1];
        assert!(!near_only(&prob));
    }

    #[test]
    fn a_flat_spot_is_nudged_outwards() {
        // A closed rounded square: (1, 0) is on the line through its neighbours, and the
        // points two away, (-1, 1) and (3, 1), are both above it. The curve bends up on both
        // sides, so the point goes down, and only down.
        let prob = Problem::<2> {
            closed: true,
            p: vec![
                [0.0, 0.0],
                [1.0, 0.0],
                [2.0, 0.0],
                [3.0, 1.0],
                [3.0, 2.0],
                [2.0, 3.0],
                [1.0, 3.0],
                [0.0, 3.0],
                [-1.0, 2.0],
                [-1.0, 1.0],
            ],
            ghost: [[0.0; 2]; 2],
            basis: Vec::new(),
            tangents: Vec::new(),
        };
        let v = nudges(&prob).expect("collinear points");
        assert!(!v[1].signed && !v[6].signed);
        assert_eq!(v[1].v[0], 0.0);
        assert!((v[1].v[1] + NUDGE).abs() < 1e-15, "{:?}", v[1].v);
        assert!((v[6].v[1] - NUDGE).abs() < 1e-15, "{:?}", v[6].v);
    }

    #[test]
    fn the_sine_of_collinear_points_does_not_cancel() {
        // Whole pixels scaled by 0.02: `|u|²|w|² − (u·w)²` reads a sine of 1.3e-8 here.
        let prob = Problem::<2> {
            closed: false,
            p: vec![[19.0 * 0.02, 13.0 * 0.02]],
            ghost: [[17.0 * 0.02, 15.0 * 0.02], [21.0 * 0.02, 11.0 * 0.02]],
            basis: Vec::new(),
            tangents: Vec::new(),
        };
        let sine = sine_at(&prob, 0).unwrap();
        assert!(sine < 1e-15, "{sine:e}");
        assert!(collinear_at(&prob, 0));
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
        let v: Vec<_> = nudges(&prob)
            .expect("a collinear point")
            .iter()
            .map(|n| n.v)
            .collect();
        assert_eq!(v[1][2], 0.0);
        assert!(v[1][0] != 0.0 && (v[1][0] + v[1][1]).abs() < 1e-15);
    }
}
