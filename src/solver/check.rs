//! The convergence test: the residuals measured above their rounding floors, and segments
//! collapsing onto their input points.

use super::problem::Problem;
use super::residual::Local;
use super::split::split_min;
use super::tuning::check::{MAX_FLOOR, RATIO_FLOOR, RATIO_NEAR_ONE, ROUNDING_FLOOR, STRAIGHTISH};
use super::workspace::Workspace;
use super::{dot, sub};
use crate::parallel::join;

impl<const D: usize, const B: usize> Workspace<D, B> {
    /// Largest scaled residual component.
    pub(super) fn max_residual(&self) -> f64 {
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
    pub(super) fn check_row(r: [f64; B], g2: f64, loc: &Local<D>, tol: f64) -> [f64; B] {
        Self::check_scaled(r, g2, Self::check_scales(loc, tol))
    }

    /// [`check_row`](Self::check_row) with the scales of its G2 and peak rows given (as
    /// [`check_scales`](Self::check_scales) computes them).
    #[inline]
    pub(super) fn check_scaled(r: [f64; B], g2: f64, scales: [f64; 2]) -> [f64; B] {
        let mut c = r;
        c[D] = g2 * scales[0];
        c[D + 1] *= scales[1];
        c
    }

    /// The scales [`check_row`](Self::check_row) applies to the G2 and the peak row of a
    /// block: the tolerance over each row's rounding floor, at most 1.
    #[inline(always)]
    pub(super) fn check_scales(loc: &Local<D>, tol: f64) -> [f64; 2] {
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
}

/// The control polygon at a middle control point `c_j`: its edges `u = c_j - c_{j-1}` and
/// `v = c_{j+1} - c_j` by their lengths and dot products (what [`Workspace::check_scales`]
/// has at hand), for the tests of a segment shrinking onto its input point.
#[derive(Clone, Copy)]
pub(super) struct Joint {
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
    pub(super) fn of<const D: usize>(u: [f64; D], v: [f64; D]) -> Joint {
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
    pub(super) fn turn_within(self, sine: f64) -> bool {
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
    /// the ratios cannot reach (they stay at least [`LAMBDA_MIN`](super::LAMBDA_MIN) inside `(0, 1)`). So it is
    /// recognized: the segment spans `α |c_j - c_{j-1}| + β |c_{j+1} - c_j|` at most `tol`
    /// (normalized coordinates), and the polygon's turn at `c_j` has a sine of at most `tol`
    /// (G1). Its peak row and the G2 rows of its two joints then count as met.
    #[inline]
    fn collapsed(self, alpha: f64, beta: f64, tol: f64) -> bool {
        self.extent(alpha, beta) <= tol && self.turn_within(tol)
    }
}
