//! The peak parameter `t`: the classic loop's root solve for it, and the peak row of the
//! Newton system.

use super::tuning::peak::{PEAK_T_TOLERANCE, QUADRATIC_PEAK_TOLERANCE, ROOT_ITERATIONS};
use super::{dot, sub};
use crate::basis::{Basis, SegmentBasis, Stationarity};

/// The peak row `t - clamp(t - g, 0, 1)` of a block with peak parameter `t` and scaled
/// stationarity residual `g` (a box complementarity, for the semi-smooth Newton step), and
/// the segment end the peak is forced to, if any.
#[inline(always)]
pub(super) fn peak_row(t: f64, g: f64) -> (f64, Option<f64>) {
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

/// The basis weights and stationarity coefficients at `t = 0` and `t = 1`, which decide
/// whether a segment's peak is forced to an end: constants of the basis, computed once per
/// basis and shared by every block that has it (`peak_parameter` keeps those of the last
/// basis it saw).
#[derive(Clone, Copy, Debug)]
pub(super) struct EndTerms {
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
/// iterations that start a cold solve: [`START_PEAK_T_TOLERANCE`](super::tuning::peak::START_PEAK_T_TOLERANCE)), otherwise to the full one.
#[inline]
pub(super) fn peak_parameter<const D: usize>(
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
}
