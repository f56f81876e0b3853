//! The solver's options ([`SolveOptions`]) and what a solve did ([`SolveReport`]).

use crate::solver::Outcome;

/// Solver options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveOptions {
    /// Convergence tolerance, relative to the drawing size (the larger side of the points'
    /// bounding box): interpolation error, and the (dimensionless) G2 and peak conditions.
    pub tolerance: f64,
    /// Iteration cap (Newton steps plus classic iterations, over every attempt of a cold
    /// solve, continuation steps included; default 4000). A solve costs `O(n)` per iteration.
    pub max_iterations: usize,
    /// Return the best curve found instead of
    /// [`Error::NotConverged`](crate::Error::NotConverged) when the cap is hit;
    /// [`Spline::converged`](super::Spline::converged) then tells.
    pub accept_unconverged: bool,
}

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            tolerance: 1e-12,
            // Every iteration counts, continuation steps included: the hardest built-in curve
            // (deer[2], εκ-trig a = 0.65) takes 1514. The continuation from smoothed points
            // needs more on walks that double back: on 4 000 random grid walks, 2 000 left
            // 22 κ and 11 εκ-trig failures, 4 000 left 11 and 7, 8 000 left 6 and 5.
            max_iterations: 4000,
            accept_unconverged: false,
        }
    }
}

/// What a solve did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SolveReport {
    /// Iterations performed (classic start-up iterations plus Newton steps).
    pub iterations: usize,
    /// How many of them were Newton steps.
    pub newton_steps: usize,
    /// Whether the tolerance was reached.
    pub converged: bool,
    /// The largest residual left, relative to the drawing size.
    pub residual: f64,
}

impl From<Outcome> for SolveReport {
    fn from(o: Outcome) -> Self {
        SolveReport {
            iterations: o.iterations,
            newton_steps: o.newton_steps,
            converged: o.converged,
            residual: o.residual,
        }
    }
}
