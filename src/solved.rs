//! The unknowns of a solved curve, saved to reproduce it.

/// The unknowns of a converged solve, in user coordinates: what
/// [`SolverN::solve_from`](crate::SolverN::solve_from) needs to give back exactly that curve.
///
/// The κ- and εκ-curve systems (seed 000 eq. 6–8) can have several solutions for the same
/// points, and which one a solve finds depends on where it starts: a cold solve starts from
/// `c_i = p_i`, `λ = t = ½` and continues in the shape parameters, while an interactive
/// session re-solves warm from the previous curve and follows the solution branch the user
/// dragged it along. The two can differ (measured in random editing runs: one reload in
/// three hundred, by up to 0.1 % of the drawing). A document saved with this state reopens
/// with the curve it showed: the solve starts at that solution, finds its residual within
/// the tolerance and stops after no iteration.
///
/// For a curve with `n` segments (a closed curve of `n` points, or an open one of `n + 2`):
///
/// ```
/// use kappa::{Scheme, Shape, Solver};
/// use kurbo::Point;
///
/// let pts = [(0.0, 0.0), (40.0, 60.0), (100.0, 40.0), (140.0, 90.0)].map(Point::from);
/// let mut solver = Solver::new();
/// let live = solver.solve(&pts, false, Scheme::EkCubic, &Shape::Global(0.8))?;
/// let saved = solver.state().expect("a converged solve has a state");
/// assert_eq!((saved.ratios.len(), saved.controls.len()), (2, 4));
///
/// // Later, in another solver: the same curve, without a single iteration.
/// let again = Solver::new().solve_from(&pts, false, Scheme::EkCubic, &Shape::Global(0.8), &saved)?;
/// assert_eq!(again.iterations(), 0);
/// assert_eq!(again.segments()[1].t_max, live.segments()[1].t_max);
/// # Ok::<(), kappa::Error>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SolvedState {
    /// The middle control points `c_i` of the segments, their coordinates one after the
    /// other (`2n` numbers in 2D, `3n` in 3D).
    pub controls: Vec<f64>,
    /// The joint ratios `λ_i ∈ [0, 1]`: segment `i` ends at `(1 − λ_i) c_i + λ_i c_{i+1}`
    /// (the last of an open curve is 1: it ends at the last point).
    pub ratios: Vec<f64>,
    /// The parameters `t_i ∈ [0, 1]` at which segment `i` passes through its input point.
    pub peaks: Vec<f64>,
}
