// `!(x > 0.0)` is meant: it is also true for NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
//! The κ/εκ-curve solver, written once for points of any dimension `D` (2D and 3D).
//!
//! # Unknowns and equations
//! For each input point `p_j` that a segment must peak at, the unknowns are the middle
//! control point `c_j` (`D` numbers), the joint ratio `λ_j` and the peak parameter `t_j`
//! (block size `B = D + 2`). The segment `j` has control points
//! `c_{j,0} = (1-λ_{j-1}) c_{j-1} + λ_{j-1} c_j`, `c_j`, `c_{j,2} = (1-λ_j) c_j + λ_j c_{j+1}`
//! (seed 000 eq. 7, G1 by construction) and the equations are
//! - interpolation `C_j(t_j) = p_j` (seed 000 eq. 5),
//! - the G2 joint `κ_j(1) = κ_{j+1}(0)` written as `(1-λ_j)² X_j - λ_j² Y_j = 0` with
//!   `X_j = k_j (1-λ_{j-1}) T_j`, `Y_j = k_{j+1} λ_{j+1} T_{j+1}`,
//!   `T_j = Δ(c_{j-1}, c_j, c_{j+1})` (seed 000 eqs. 8–10; `k` is the basis' end
//!   coefficient). This squared form has bounded derivatives where a segment turns straight
//!   (`T → 0`), unlike `λ = √X / (√X + √Y)`, so Newton can pass through an orientation flip,
//! - the curvature peak `dκ_j/dt (t_j) = 0` in the area-free form of [`crate::basis`].
//!
//! # Method
//! A few iterations of the classic local/global loop (seed 000 Algorithm 1: λ, then `t` by a
//! bracketed 1-D root solve, then a (cyclic) tridiagonal solve for the `c_j`) give a start;
//! Newton's method on the whole system then converges quadratically. The Jacobian is
//! block-banded (block row `j` touches block columns `j-1 ..= j+2`); closed curves wrap
//! around, which is handled by a bordered solve. Long curves are cut in two halves and a
//! border ([`Split`](split::Split)) whose per-block work and band factorizations run side by side
//! ([`crate::parallel`]). Each Newton step costs `O(m)`. A
//! backtracking line search on the scaled residual globalizes it, with classic iterations as
//! the fallback when a step fails. Open curves are the same system with fixed "ghost"
//! control points `c_{-1} = p_first`, `c_n = p_last` and `λ_{-1} = 0`, `λ_{n-1} = 1`.
//!
//! # Layout
//! [`problem`] holds the data and the unknowns of a solve, [`workspace`] the buffers.
//! [`residual`] evaluates and assembles the block equations, [`check`] measures convergence,
//! and [`linear`], [`condense`] and [`split`] make up the linear system of a Newton step.
//! [`newton`] is the solve loop, started by the [`classic`] iteration and its [`peak`] root
//! solves. Cold solves fall back on the continuations of [`cascade`], [`nudge`], [`points`]
//! and [`tangent`], each ending with the [`collapse`] step; warm re-solves after a local edit
//! work on a [`window`].

mod cascade;
mod check;
mod classic;
mod collapse;
mod condense;
mod linear;
mod newton;
mod nudge;
mod peak;
mod points;
mod problem;
mod residual;
mod split;
mod tangent;
mod tuning;
mod window;
mod workspace;

#[cfg(test)]
mod jacobian_tests;
#[cfg(test)]
mod linear_tests;

pub(crate) use problem::{Outcome, Problem, Settings, State};
pub(crate) use tangent::{Tangent, TangentAt};
use tuning::system::{EPS_GRAM, LAMBDA_MIN};
pub(crate) use window::Edit;
pub(crate) use workspace::Workspace;

#[inline]
fn sub<const D: usize>(a: [f64; D], b: [f64; D]) -> [f64; D] {
    core::array::from_fn(|k| a[k] - b[k])
}

#[inline]
fn dot<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    (0..D).map(|k| a[k] * b[k]).sum()
}

#[inline]
pub(crate) fn lerp<const D: usize>(a: [f64; D], b: [f64; D], t: f64) -> [f64; D] {
    core::array::from_fn(|k| a[k] + t * (b[k] - a[k]))
}

/// The area of the triangle `a b c`, regularized, with its gradient with respect to `a` and
/// `c` (that for `b` is minus their sum). Computed from the cross product of `a - b` and
/// `c - b` (scalar in 2D, vector in 3D): its relative rounding error grows like `ε/θ` for a
/// thin triangle of angle `θ`, where the Gram determinant `|u|²|v|² - (u·v)²` would give
/// `ε/θ²`.
#[inline]
fn triangle<const D: usize>(a: [f64; D], b: [f64; D], c: [f64; D]) -> (f64, [f64; D], [f64; D]) {
    let u = sub(a, b);
    let v = sub(c, b);
    // x = u × v as up to three components; ∂|x|²/∂u = 2 v × x, ∂|x|²/∂v = 2 x × u.
    let (x, gu, gv): ([f64; 3], [f64; 3], [f64; 3]) = if D == 2 {
        let z = u[0] * v[1] - u[1] * v[0];
        (
            [0.0, 0.0, z],
            [v[1] * z, -v[0] * z, 0.0],
            [-u[1] * z, u[0] * z, 0.0],
        )
    } else {
        let (u3, v3) = (
            [u[0], u[1], u.get(2).copied().unwrap_or(0.0)],
            [v[0], v[1], v.get(2).copied().unwrap_or(0.0)],
        );
        let x = cross3(u3, v3);
        (x, cross3(v3, x), cross3(x, u3))
    };
    let g = x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + EPS_GRAM;
    let t2 = g.sqrt(); // twice the area
                       // dT = d|x|² / (4 · 2T)
    let f = 1.0 / (2.0 * t2);
    (
        0.5 * t2,
        core::array::from_fn(|k| f * gu[k]),
        core::array::from_fn(|k| f * gv[k]),
    )
}

#[inline]
fn cross3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The cyclic index `i mod n` for `-n ≤ i < 2n` (the stencils reach at most two blocks
/// away, and closed curves have at least three), without a division.
#[inline(always)]
fn wrap(i: isize, n: usize) -> usize {
    let n = n as isize;
    debug_assert!(i >= -n && i < 2 * n);
    (if i < 0 {
        i + n
    } else if i >= n {
        i - n
    } else {
        i
    }) as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangle_gradient_matches_finite_differences() {
        let (a, b, c) = ([0.3, 1.0, -0.2], [1.0, 0.1, 0.4], [2.0, 1.2, 0.0]);
        let (_, ga, gc) = triangle(a, b, c);
        let h = 1e-7;
        for k in 0..3 {
            let mut ap = a;
            ap[k] += h;
            let mut am = a;
            am[k] -= h;
            let fd = (triangle(ap, b, c).0 - triangle(am, b, c).0) / (2.0 * h);
            assert!((fd - ga[k]).abs() < 1e-6);
            let mut cp = c;
            cp[k] += h;
            let mut cm = c;
            cm[k] -= h;
            let fd = (triangle(a, b, cp).0 - triangle(a, b, cm).0) / (2.0 * h);
            assert!((fd - gc[k]).abs() < 1e-6);
        }
    }
}
