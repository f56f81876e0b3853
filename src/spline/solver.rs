//! The solver's front end ([`SolverN`], [`Solver`], [`Solver3`]): input checked and
//! normalized, cold and warm solves, re-solves after edits, and the output curve.

use kurbo::Point;

use super::checks::{
    block_range, check_shapes, collinear, monotone_along_line, shape_at, within_rounding,
    COINCIDENT, ULP_COINCIDENT,
};
use super::frame::{Coords, Frame};
use super::{Scheme, Segment, Shape, SolveOptions, SolveReport, Spline};
use crate::basis::Basis;
use crate::solver::{Edit, Outcome, Problem, Settings, State, Tangent, TangentAt, Workspace};
use crate::{Error, Point3, SolvedState};

/// Iterations a warm re-solve may take before the cold cascade takes over.
const WARM_BUDGET: usize = 100;

/// How many drawing sizes beyond the points the arithmetic must stay finite: drawings that
/// reach within this of `±f64::MAX` (or whose centre is beyond a quarter of it) are an
/// [`Error::ExtentOverflow`] (found by fuzzing: a drawing 1e308 wide solved, but its curve
/// evaluated to infinity).
const EXTENT_HEADROOM: f64 = 1e3;

/// A reusable solver: keeps its buffers and the last solution, so that re-solving after the
/// points moved (the interactive case) starts from the previous curve.
///
/// `D` is the dimension and `B = D + 2` the block size of the Newton system; use the
/// aliases [`Solver`] (2D) and [`Solver3`] (3D).
///
/// # Inflections through input points
///
/// The papers promise G2 "except at inflection points" (seed 000 §1, §3), where only G1
/// holds, but say nothing of an inflection *at* an input point, which every symmetric S or
/// wave has: its middle point lies on the line through its neighbours. There the curve is
/// the limit of the curves for the point moved off the line. Moving the middle point of the
/// wave `(100,300) (250,200) (400,300) (550,400) (700,300)` off the line by `ε`, the
/// segment through it shrinks linearly to the point (its span is about `3ε`, its peak
/// parameter stays near 0.784, or 0.216 for `-ε`) while the rest converges: the limit is
/// the two neighbouring segments meeting at the point, tangent to each other, with
/// curvatures of equal magnitude and opposite sign. The solver converges to it: the
/// shrinking segment's rows are measured above their rounding floor, its joint ratios are
/// held at their bounds once it has collapsed, and the collapsed segment counts as solved
/// where the control polygon is straight at the point (see the solver's
/// `Joint::collapsed`). The result reports the segment as [`Segment::is_collapsed`]
/// ([`Extremum::Inflection`](crate::Extremum::Inflection)). Measured on that wave for every
/// scheme: offsets of 1e-12 to 1e-2 of the drawing size on either side converge, and the
/// curve is within 1.8 to 3.1 times the offset of the collinear one (up to 141 times for κ
/// below 1e-10, where the shrinking segment is resolved only to its rounding floor).
/// Without the symmetry, a point on its neighbours' line sits at a segment end instead
/// (`t_max` 0 or 1), where the neighbouring segments meet: an inflection at the joint.
///
/// ```
/// use kappa::{Scheme, Shape, Solver};
/// use kurbo::Point;
///
/// let s_curve = [(560.0, 150.0), (450.0, 95.0), (340.0, 150.0), (360.0, 250.0), (450.0, 300.0),
///     (540.0, 350.0), (560.0, 450.0), (450.0, 505.0), (340.0, 450.0)].map(Point::from);
/// let mut solver = Solver::new();
/// for scheme in [Scheme::Kappa, Scheme::EkCubic, Scheme::EkTrig] {
///     let curve = solver.solve(&s_curve, false, scheme, &Shape::Neutral)?;
///     // The middle point (index 4; segment 3 of the open curve) is an inflection.
///     assert!(curve.converged() && curve.segments()[3].is_collapsed());
/// }
/// # Ok::<(), kappa::Error>(())
/// ```
///
/// # Dense samples of a wave
///
/// Where κ-curves through many samples of a smooth wave exist, many of their peaks sit at
/// segment ends: `t_max` is 0 or 1, the input point is the joint, and |κ| changes sign
/// there (the peak condition of seed 004 eq. 4 then says only that the segment ends at the
/// point). Followed from εκ-cubic in `a`, that solution branch often folds before
/// `a = 2/3`: on the sine `(10i, 50 sin 0.3i)` it reaches 2/3 at 21, 31 and 40 points and
/// folds at a = 0.68–0.71 at 30, 45 and 60 to 1 000 points, where the κ solve reports
/// [`Error::NotConverged`]; the papers' local/global loop does not converge on that sine at
/// any of these lengths. εκ-cubic with `a ≥ 0.72` converges on all of them.
#[derive(Clone, Debug)]
pub struct SolverN<P, const D: usize, const B: usize> {
    options: SolveOptions,
    ws: Workspace<D, B>,
    prob: Problem<D>,
    /// A second problem, for the continuation fallback.
    scratch: Problem<D>,
    frame: Frame<D>,
    scheme: Scheme,
    /// Input points of the last solve (user coordinates).
    points: Vec<[f64; D]>,
    /// Whether `ws` holds a solution matching `prob`'s structure.
    warm: bool,
    /// The input points in the normalized frame (all of them; `prob` keeps those with a
    /// segment).
    local: Vec<[f64; D]>,
    /// Prescribed tangent directions by input point (empty: none), as given.
    tangents: Vec<Option<[f64; D]>>,
    /// The last free curve (no tangents) solved cold, by its input: a solve with tangents
    /// of the same input turns its directions from there without solving it again. Kept
    /// only once this solver has solved with tangents (a copy per cold solve otherwise
    /// costs the bear 3 % more instructions).
    free: Option<FreeCurve<D>>,
    _marker: core::marker::PhantomData<P>,
}

/// A free curve's solution and the input it solves (see `SolverN::free`).
#[derive(Clone, Debug)]
struct FreeCurve<const D: usize> {
    points: Vec<[f64; D]>,
    closed: bool,
    basis: Vec<Basis>,
    state: State<D>,
}

impl<const D: usize> FreeCurve<D> {
    fn input(&self) -> (&Vec<[f64; D]>, bool, &Vec<Basis>) {
        (&self.points, self.closed, &self.basis)
    }
}

/// The 2D solver.
///
/// Keep one across edits: [`SolverN::resolve`] starts from the last solution and reuses its
/// factored Jacobian, and [`SolverN::resolve_shapes`] changes the shapes `a_i` only.
///
/// ```
/// use kappa::{Scheme, Shape, Solver};
/// use kurbo::Point;
///
/// let mut points = [(0.0, 0.0), (100.0, 10.0), (120.0, 90.0), (20.0, 110.0)].map(Point::from);
/// let mut solver = Solver::new();
/// let cold = solver.solve(&points, true, Scheme::EkCubic, &Shape::Global(0.8))?;
/// points[2].y += 3.0;
/// let warm = solver.resolve(&points)?;
/// assert!(cold.converged() && warm.converged());
/// let seg = &warm.segments()[2];
/// assert!((seg.eval(seg.t_max) - points[2]).hypot() < 1e-9); // through the moved point
/// let softer = solver.resolve_shapes(Scheme::EkCubic, &Shape::Global(0.7))?;
/// assert!(softer.segments().iter().all(|s| s.a == 0.7));
/// # Ok::<(), kappa::Error>(())
/// ```
pub type Solver = SolverN<Point, 2, 4>;

/// The 3D solver.
pub type Solver3 = SolverN<Point3, 3, 5>;

impl Solver {
    /// Solve with a prescribed tangent direction at some of the points (`None`: free), one
    /// entry per point; the curve leaves each such point along its direction (the sign
    /// counts).
    ///
    /// A tangent takes the place of one condition per segment, which keeps the system
    /// square (derivation in the `solver` module's `Tangent` notes):
    /// - at an interior point (every point of a closed curve), the point is still
    ///   interpolated and the curve is G2 at every joint, but the point is no longer a
    ///   curvature extremum: the peak condition of its segment gives way to the tangent;
    /// - at the first (last) point of an open curve, the tangent is that of the first
    ///   (last) segment's start (end), whose peak condition gives way: the second (second to
    ///   last) point is then interpolated but not a curvature extremum. A smooth join of a
    ///   line and a curve is this case, with the line's direction: the join is G1, not G2
    ///   (the curve's curvature there is not zero).
    ///
    /// Such a curve exists only for directions near the free curve's: the constrained point
    /// must stay inside its segment. Measured on a four-point loop, a tangent turned by up
    /// to 10° from the free curve's converges in every scheme (κ up to 15°, none at 30°); a
    /// direction farther off needs more points around it. The solve follows the free
    /// curve: it turns the directions from the free curve's to the prescribed ones
    /// (continuation), so small changes of direction give small changes of the curve.
    ///
    /// Two tangents on one segment (an end of an open curve and its neighbour, or both ends
    /// of a three-point open curve) are a [`Error::TangentConflict`]; a two-point open curve
    /// takes no tangent either. [`resolve`](Self::resolve) and
    /// [`resolve_shapes`](Self::resolve_shapes) keep the tangents; [`solve`](Self::solve)
    /// drops them.
    ///
    /// ```
    /// use kappa::{Scheme, Shape, Solver};
    /// use kurbo::{Point, Vec2};
    ///
    /// // An oval whose top and bottom nodes keep horizontal tangents.
    /// let points = [(0.0, 0.0), (60.0, 30.0), (0.0, 70.0), (-50.0, 35.0)].map(Point::from);
    /// let tangents = [Some(Vec2::new(1.0, 0.0)), None, Some(Vec2::new(-1.0, 0.0)), None];
    /// let mut solver = Solver::new();
    /// let spline = solver
    ///     .solve_with_tangents(&points, true, Scheme::Kappa, &Shape::Neutral, &tangents)?;
    /// for (seg, tan) in spline.segments().iter().zip(tangents) {
    ///     if let Some(tan) = tan {
    ///         let d = seg.derivative(seg.t_max);
    ///         assert!(d.cross(tan).abs() <= 1e-9 * d.hypot() && d.dot(tan) > 0.0);
    ///     }
    /// }
    /// # Ok::<(), kappa::Error>(())
    /// ```
    pub fn solve_with_tangents(
        &mut self,
        points: &[Point],
        closed: bool,
        scheme: Scheme,
        shape: &Shape,
        tangents: &[Option<kurbo::Vec2>],
    ) -> Result<Spline<Point>, Error> {
        self.set_tangent_list(points, tangents)?;
        self.solve_again(points, closed, scheme, shape)
    }

    /// [`solve_with_tangents`](Self::solve_with_tangents) starting from a saved solution
    /// ([`SolverN::state`] of an earlier solve of the same input and tangents): that curve
    /// again, as [`SolverN::solve_from`] does for a free curve. A state that does not fit is
    /// ignored.
    pub fn solve_with_tangents_from(
        &mut self,
        points: &[Point],
        closed: bool,
        scheme: Scheme,
        shape: &Shape,
        tangents: &[Option<kurbo::Vec2>],
        start: &SolvedState,
    ) -> Result<Spline<Point>, Error> {
        self.set_tangent_list(points, tangents)?;
        self.solve_from_kept(points, closed, scheme, shape, start)
    }

    /// Keeps `tangents` for the next solves, or reports a list of the wrong length.
    fn set_tangent_list(
        &mut self,
        points: &[Point],
        tangents: &[Option<kurbo::Vec2>],
    ) -> Result<(), Error> {
        self.tangents.clear();
        self.tangents
            .extend(tangents.iter().map(|t| t.map(|v| [v.x, v.y])));
        // A list of the wrong length is reported before anything else is checked.
        if self.tangents.len() != points.len() {
            let index = self.tangents.len();
            self.tangents.clear();
            return Err(Error::InvalidTangent {
                index,
                reason: "expected one entry per point",
            });
        }
        Ok(())
    }
}

impl<P: Coords<D>, const D: usize, const B: usize> Default for SolverN<P, D, B> {
    fn default() -> Self {
        Self::new()
    }
}

impl<P: Coords<D>, const D: usize, const B: usize> SolverN<P, D, B> {
    /// A solver with default options.
    pub fn new() -> Self {
        Self::with_options(SolveOptions::default())
    }

    /// A solver with the given options.
    pub fn with_options(options: SolveOptions) -> Self {
        SolverN {
            options,
            ws: Workspace::default(),
            prob: Problem {
                closed: true,
                p: Vec::new(),
                ghost: [[0.0; D]; 2],
                basis: Vec::new(),
                tangents: Vec::new(),
            },
            scratch: Problem {
                closed: true,
                p: Vec::new(),
                ghost: [[0.0; D]; 2],
                basis: Vec::new(),
                tangents: Vec::new(),
            },
            frame: Frame {
                center: [0.0; D],
                size: 1.0,
            },
            scheme: Scheme::Kappa,
            points: Vec::new(),
            warm: false,
            local: Vec::new(),
            tangents: Vec::new(),
            free: None,
            _marker: core::marker::PhantomData,
        }
    }

    /// The options.
    pub fn options(&self) -> SolveOptions {
        self.options
    }

    /// Changes the options for the next solves (the last solution is kept: a warm re-solve
    /// still starts from it). An interactive caller can lower
    /// [`SolveOptions::max_iterations`] while a drag is in progress, so that a solve that
    /// will not converge stays within a frame, and raise it again at the end.
    pub fn set_options(&mut self, options: SolveOptions) {
        self.options = options;
    }

    /// Solve from scratch.
    pub fn solve(
        &mut self,
        points: &[P],
        closed: bool,
        scheme: Scheme,
        shape: &Shape,
    ) -> Result<Spline<P>, Error> {
        self.tangents.clear();
        self.solve_again(points, closed, scheme, shape)
    }

    /// [`solve`](Self::solve) with the tangents of the last solve kept.
    fn solve_again(
        &mut self,
        points: &[P],
        closed: bool,
        scheme: Scheme,
        shape: &Shape,
    ) -> Result<Spline<P>, Error> {
        // Whatever happens next, the previous solution no longer matches the problem.
        self.warm = false;
        self.setup(points, closed, scheme, Some(shape))?;
        self.run()
    }

    /// Solve starting from a saved solution ([`SolverN::state`] of an earlier solve of the
    /// same input): that curve again, after no iteration where it is still a solution. A
    /// state that does not fit the input (another number of segments, a value out of range)
    /// is ignored, as is one that does not converge within the warm budget: the solve then
    /// goes on as [`SolverN::solve`] from scratch.
    pub fn solve_from(
        &mut self,
        points: &[P],
        closed: bool,
        scheme: Scheme,
        shape: &Shape,
        start: &SolvedState,
    ) -> Result<Spline<P>, Error> {
        // (A free curve, as `solve` solves it: no tangents.)
        self.tangents.clear();
        self.solve_from_kept(points, closed, scheme, shape, start)
    }

    /// [`solve_from`](Self::solve_from) with the tangents of the last solve kept.
    fn solve_from_kept(
        &mut self,
        points: &[P],
        closed: bool,
        scheme: Scheme,
        shape: &Shape,
        start: &SolvedState,
    ) -> Result<Spline<P>, Error> {
        self.warm = false;
        self.setup(points, closed, scheme, Some(shape))?;
        // (Open input of two points has no unknowns: nothing to start from.)
        let n = self.prob.p.len();
        if n > 0 && start.controls.len() == n * D {
            let c: Vec<[f64; D]> = start
                .controls
                .chunks_exact(D)
                .map(|c| self.frame.to_local(core::array::from_fn(|k| c[k])))
                .collect();
            self.warm = self
                .ws
                .start_at(&self.prob, &c, &start.ratios, &start.peaks);
            self.ws.invalidate();
        }
        self.run()
    }

    /// The unknowns of the last solve, if it converged (see [`SolvedState`]); `None` before
    /// any solve, after one that failed, and for straight input (two points, or open input
    /// on one line), whose solution needs no search.
    pub fn state(&self) -> Option<SolvedState> {
        let m = self.points.len();
        let straight = !self.prob.closed && (m == 2 || collinear(&self.local));
        if !self.warm || straight || self.prob.p.is_empty() {
            return None;
        }
        let st = &self.ws.state;
        Some(SolvedState {
            controls: st.c.iter().flat_map(|&c| self.frame.to_user(c)).collect(),
            ratios: st.lam.clone(),
            peaks: st.t.clone(),
        })
    }

    /// Re-solve after the points moved (same count, same topology, scheme and shapes),
    /// starting from the previous solution. Falls back to a cold solve if the previous one did
    /// not converge or the number of points changed (a uniform shape carries over; per-point
    /// shapes then give [`Error::ShapeCount`]). Without any previous solve it is an
    /// [`Error::InvalidOption`].
    pub fn resolve(&mut self, points: &[P]) -> Result<Spline<P>, Error> {
        if self.prob.basis.is_empty() && self.points.len() != 2 {
            return Err(Error::InvalidOption("resolve needs a previous solve"));
        }
        if !self.warm || points.len() != self.points.len() {
            let closed = self.prob.closed;
            let shapes = if points.len() == self.points.len() {
                self.shapes()
            } else {
                // Another number of points: a uniform shape carries over, per-point ones not.
                let mut a = self.prob.basis.iter().map(|b| b.a());
                match a.next() {
                    Some(a0) if a.all(|x| x == a0) => Shape::Global(a0),
                    None => Shape::Neutral,
                    _ => {
                        return Err(Error::ShapeCount {
                            expected: points.len(),
                            got: self.points.len(),
                        })
                    }
                }
            };
            return self.solve_again(points, closed, self.scheme, &shapes);
        }
        self.ws.refresh_jacobian(&self.prob, self.options.tolerance);
        let old_frame = self.frame;
        let old_points = core::mem::take(&mut self.points);
        if let Err(e) = self.setup(points, self.prob.closed, self.scheme, None) {
            self.warm = false;
            return Err(e);
        }
        // Which points moved: a few close together are re-solved on a window around them.
        let mut moved = [0; 4];
        let mut count = 0;
        for (i, (new, old)) in self.points.iter().zip(&old_points).enumerate() {
            if new != old {
                if count == moved.len() {
                    count += 1;
                    break;
                }
                moved[count] = i;
                count += 1;
            }
        }
        let edit = moved
            .get(..count)
            .and_then(|m| Edit::of(self.prob.closed, self.prob.p.len(), m));
        let reframed = self.frame != old_frame;
        self.ws
            .set_edit(edit, self.frame.size != old_frame.size, reframed);
        // Carry the previous unknowns into the new frame, moving each control point with
        // its input point (in the same frame, only those of moved points change).
        let off = if self.prob.closed { 0 } else { 1 };
        let st = &mut self.ws.state;
        if !reframed {
            for (j, c) in st.c.iter_mut().enumerate() {
                if self.points[j + off] != old_points[j + off] {
                    // `local` holds the new points in this frame.
                    let (new, old) = (
                        self.local[j + off],
                        self.frame.to_local(old_points[j + off]),
                    );
                    *c = core::array::from_fn(|k| c[k] + (new[k] - old[k]));
                }
            }
            return self.run();
        }
        for (j, c) in st.c.iter_mut().enumerate() {
            let user = old_frame.to_user(*c);
            let moved: [f64; D] = core::array::from_fn(|k| {
                user[k] + self.points[j + off][k] - old_points[j + off][k]
            });
            *c = self.frame.to_local(moved);
        }
        self.run()
    }

    /// Re-solve with new shape parameters (same points), starting from the previous solution:
    /// the interactive "sharpness slider" case. Falls back to a cold solve if there is none.
    pub fn resolve_shapes(&mut self, scheme: Scheme, shape: &Shape) -> Result<Spline<P>, Error> {
        if !self.warm {
            let points: Vec<P> = self.points.iter().map(|&c| P::from_coords(c)).collect();
            return self.solve_again(&points, self.prob.closed, scheme, shape);
        }
        check_shapes(scheme, shape, self.points.len())?;
        self.set_shapes(scheme, shape);
        self.ws.invalidate();
        self.run()
    }

    fn shapes(&self) -> Shape {
        Shape::PerPoint(self.prob_shapes())
    }

    fn prob_shapes(&self) -> Vec<f64> {
        let mut a: Vec<f64> = Vec::with_capacity(self.points.len());
        if !self.prob.closed {
            a.push(2.0 / 3.0);
        }
        a.extend(self.prob.basis.iter().map(|b| b.a()));
        if !self.prob.closed {
            a.push(2.0 / 3.0);
        }
        a
    }

    /// Validate and normalize the input into `self.prob`, with new shapes, or (`None`, for
    /// a re-solve with as many points) the current ones.
    fn setup(
        &mut self,
        points: &[P],
        closed: bool,
        scheme: Scheme,
        shape: Option<&Shape>,
    ) -> Result<(), Error> {
        let m = points.len();
        // The points are kept even when they are rejected, so that a later `resolve_shapes`
        // reports the same error instead of solving an older or partial set.
        self.points.clear();
        self.points.extend(points.iter().map(|p| p.coords()));
        let (kind, needed) = if closed {
            ("a closed curve", 3)
        } else {
            ("an open curve", 2)
        };
        if m < needed {
            return Err(Error::TooFewPoints {
                kind,
                needed,
                got: m,
            });
        }
        if let Some(index) = self
            .points
            .iter()
            .position(|c| !c.iter().all(|x| x.is_finite()))
        {
            return Err(Error::NonFinitePoint { index });
        }
        let options = self.options;
        if !(options.tolerance > 0.0 && options.tolerance.is_finite()) {
            return Err(Error::InvalidOption(
                "tolerance must be positive and finite",
            ));
        }
        self.frame = Frame::new(&self.points);
        // Headroom: control points may lie well outside the points' box, and the curve is
        // evaluated in user coordinates, so the box must stay far from overflowing.
        let reach = 4.0 * self.frame.center.iter().fold(0.0f64, |m, c| m.max(c.abs()))
            + EXTENT_HEADROOM * self.frame.size;
        if !self.frame.size.is_finite() || !reach.is_finite() {
            return Err(Error::ExtentOverflow);
        }
        let frame = &self.frame;
        self.local.clear();
        self.local
            .extend(self.points.iter().map(|&p| frame.to_local(p)));
        let local = &self.local;
        // Points within rounding of each other in user coordinates are at most
        // `ULP_COINCIDENT ε max |coordinate|` apart, which bounds their local distance (with
        // room for the rounding of the normalization): pairs farther apart skip that test.
        let magnitude = frame.center.iter().fold(0.0f64, |m, c| m.max(c.abs())) + frame.size;
        let rounding = 2.0 * (ULP_COINCIDENT * magnitude / frame.size + 4.0) * f64::EPSILON;
        let pairs = if closed { m } else { m - 1 };
        for i in 0..pairs {
            let next = (i + 1) % m;
            let d2 = (0..D)
                .map(|k| (local[next][k] - local[i][k]).powi(2))
                .sum::<f64>();
            if d2 <= COINCIDENT * COINCIDENT
                || (d2 <= rounding * rounding && within_rounding(self.points[i], self.points[next]))
            {
                return Err(Error::RepeatedPoint { index: i, next });
            }
        }
        if closed && collinear(local) {
            return Err(Error::Collinear);
        }
        if let Some(shape) = shape {
            check_shapes(scheme, shape, m)?;
        }
        self.prob.closed = closed;
        self.prob.p.clear();
        self.prob
            .p
            .extend_from_slice(&local[block_range(closed, m)]);
        self.prob.ghost = [local[0], local[m - 1]];
        if let Some(shape) = shape {
            self.set_shapes(scheme, shape);
        }
        self.set_tangents()
    }

    /// The blocks' tangent constraints from [`tangents`](Self::tangents) (see
    /// [`Solver::solve_with_tangents`]).
    fn set_tangents(&mut self) -> Result<(), Error> {
        self.prob.tangents.clear();
        if self.tangents.is_empty() {
            return Ok(());
        }
        let m = self.points.len();
        if self.tangents.len() != m {
            return Err(Error::InvalidTangent {
                index: self.tangents.len(),
                reason: "expected one entry per point",
            });
        }
        let closed = self.prob.closed;
        let n = self.prob.p.len();
        self.prob.tangents.resize(n, None);
        let mut owner = vec![0; n];
        for (i, tan) in self.tangents.iter().enumerate() {
            let Some(v) = tan else { continue };
            let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            if !(norm > 0.0 && norm.is_finite()) {
                return Err(Error::InvalidTangent {
                    index: i,
                    reason: "a tangent must be a nonzero, finite vector",
                });
            }
            let dir = core::array::from_fn(|k| v[k] / norm);
            let (block, at) = if closed {
                (i, TangentAt::Peak)
            } else if n == 0 {
                // Two points: one straight segment, nothing to bend.
                return Err(Error::TangentConflict {
                    first: 0,
                    second: 1,
                });
            } else if i == 0 {
                (0, TangentAt::Start)
            } else if i + 1 == m {
                (n - 1, TangentAt::End)
            } else {
                (i - 1, TangentAt::Peak)
            };
            if self.prob.tangents[block].is_some() {
                return Err(Error::TangentConflict {
                    first: owner[block],
                    second: i,
                });
            }
            owner[block] = i;
            self.prob.tangents[block] = Some(Tangent { dir, at });
        }
        Ok(())
    }

    /// Set the scheme and the segment bases from validated per-point shapes (for open curves
    /// the first and last points have no segment).
    fn set_shapes(&mut self, scheme: Scheme, shape: &Shape) {
        self.scheme = scheme;
        self.prob.basis.clear();
        let range = block_range(self.prob.closed, self.points.len());
        self.prob
            .basis
            .extend(range.map(|i| scheme.basis(shape_at(scheme, shape, i))));
    }

    fn run(&mut self) -> Result<Spline<P>, Error> {
        let closed = self.prob.closed;
        let m = self.points.len();
        if !closed && m == 2 {
            // A straight segment.
            let (p0, p1) = (self.points[0], self.points[1]);
            // Halves first: p1 − p0 can overflow where p0/2 + p1/2 does not.
            let mid: [f64; D] = core::array::from_fn(|k| 0.5 * p0[k] + 0.5 * p1[k]);
            let report = SolveReport {
                converged: true,
                ..SolveReport::default()
            };
            return Ok(Spline {
                scheme: self.scheme,
                closed,
                segments: vec![Segment {
                    q: [P::from_coords(p0), P::from_coords(mid), P::from_coords(p1)],
                    a: self.scheme.neutral_shape(),
                    t_max: 0.5,
                    degree: self.scheme.degree(),
                    scheme: self.scheme,
                }],
                report,
            });
        }
        // All input points on one line (the ends may coincide, as in a loop that starts
        // where it ends, so they are checked together with the interior points; `local`
        // holds all of them, the ends included).
        if !closed && self.prob.tangents.is_empty() && collinear(&self.local) {
            if !monotone_along_line(&self.local) {
                // A curve through points that double back along one line would need a
                // cusp at every reversal: there is no κ- or εκ-curve through them.
                return Err(Error::Collinear);
            }
            self.straight_solution();
            self.warm = true;
            let report = SolveReport {
                converged: true,
                ..SolveReport::default()
            };
            return Ok(self.spline(report));
        }
        let settings = Settings {
            tolerance: self.options.tolerance,
            max_iterations: self.options.max_iterations,
            // (Tangent rows are not frozen for chord steps.)
            newton_chords: self.prob.tangents.is_empty(),
        };
        let outcome = if self.warm {
            // A warm start that does not converge quickly is far from the new solution: a
            // capped attempt, then the cold cascade with what is left of the budget. Where
            // the warm attempt spent the whole budget (a capped drag update), its iterate is
            // the best curve there is: a cold cascade with no iterations left would only
            // measure its starting guesses (three Jacobians, 5 ms on a 240-point εκ-trig
            // ring) and return the least bad of them.
            let warm_settings = Settings {
                max_iterations: settings.max_iterations.min(WARM_BUDGET),
                ..settings
            };
            let warm = self.ws.solve_warm(&self.prob, &warm_settings);
            if warm.converged || warm.iterations >= settings.max_iterations {
                warm
            } else {
                let rest = Settings {
                    max_iterations: settings.max_iterations.saturating_sub(warm.iterations),
                    ..settings
                };
                let mut cold = self.cold(&rest);
                cold.iterations += warm.iterations;
                cold
            }
        } else {
            self.cold(&settings)
        };
        self.warm = outcome.converged;
        if !outcome.converged && !self.options.accept_unconverged {
            return Err(Error::NotConverged {
                iterations: outcome.iterations,
                residual: outcome.residual,
            });
        }
        Ok(self.spline(outcome.into()))
    }

    /// The cold solve: the cascade of [`Workspace::solve_cold`], or with tangents
    /// [`Workspace::solve_cold_tangents`].
    fn cold(&mut self, settings: &Settings) -> Outcome {
        if self.prob.tangents.is_empty() && self.free.is_none() {
            // A solver that has not held tangents keeps no free curve.
            return self.ws.solve_cold(&self.prob, settings, &mut self.scratch);
        }
        let input = (&self.points, self.prob.closed, &self.prob.basis);
        let cached = self.free.take().filter(|f| f.input() == input);
        if self.prob.tangents.is_empty() {
            let out = self.ws.solve_cold(&self.prob, settings, &mut self.scratch);
            if out.converged {
                self.free = Some(self.free_curve(self.ws.state.clone()));
            }
            return out;
        }
        let mut free = cached.as_ref().map(|f| f.state.clone());
        let out = self
            .ws
            .solve_cold_tangents(&self.prob, settings, &mut self.scratch, &mut free);
        self.free = cached.or_else(|| free.map(|state| self.free_curve(state)));
        out
    }

    /// `state` as the free curve of the current input (see `SolverN::free`).
    fn free_curve(&self, state: State<D>) -> FreeCurve<D> {
        FreeCurve {
            points: self.points.clone(),
            closed: self.prob.closed,
            basis: self.prob.basis.clone(),
            state,
        }
    }

    /// The solution for open input on one line: straight segments with `c_j = p_j`, joints
    /// at the midpoints, and `t_j` where the segment passes `p_j` (|κ| is 0 everywhere, so
    /// every parameter is a peak).
    fn straight_solution(&mut self) {
        self.ws.cold_start(&self.prob);
        let n = self.prob.p.len();
        let st = &mut self.ws.state;
        for j in 0..n {
            st.lam[j] = if j + 1 == n { 1.0 } else { 0.5 };
        }
        for j in 0..n {
            let [q0, _, q2] = st.segment(&self.prob, j);
            // Along the line the position is monotone in t: bisect for the parameter of p_j.
            let basis = self.prob.basis[j];
            let p = self.prob.p[j];
            let dir: [f64; D] = core::array::from_fn(|k| q2[k] - q0[k]);
            let along = |x: [f64; D]| (0..D).map(|k| (x[k] - q0[k]) * dir[k]).sum::<f64>();
            let target = along(p);
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                let w = crate::basis::SegmentBasis::weights(&basis, mid);
                let x: [f64; D] = core::array::from_fn(|k| {
                    w[0][0] * q0[k] + (1.0 - w[0][0] - w[0][1]) * p[k] + w[0][1] * q2[k]
                });
                if along(x) < target {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            st.t[j] = 0.5 * (lo + hi);
        }
    }

    /// Build the output from the workspace state.
    fn spline(&self, report: SolveReport) -> Spline<P> {
        let st = &self.ws.state;
        let n = st.t.len();
        let prob = &self.prob;
        let mut segments = Vec::with_capacity(n);
        let user = |p: [f64; D]| P::from_coords(self.frame.to_user(p));
        // Segment j's end and segment j+1's start are the same `lerp(c_j, c_{j+1}, λ_j)`, so
        // consecutive segments meet exactly (each joint is computed once).
        let mut start = user(st.segment(prob, 0)[0]);
        for j in 0..n {
            let [_, c, q2] = st.segment(prob, j);
            let end = user(q2);
            segments.push(Segment {
                q: [core::mem::replace(&mut start, end), user(c), end],
                a: prob.basis[j].a(),
                t_max: st.t[j],
                degree: self.scheme.degree(),
                scheme: self.scheme,
            });
        }
        // Open curves end exactly at the first and last input points.
        if !prob.closed {
            segments[0].q[0] = P::from_coords(self.points[0]);
            segments[n - 1].q[2] = P::from_coords(self.points[self.points.len() - 1]);
        }
        // A segment that collapsed onto its input point (within the tolerance) is that
        // point, and its neighbours meet there.
        if report.converged {
            let off = if prob.closed { 0 } else { 1 };
            for j in 0..n {
                if self.ws.is_collapsed(prob, j, self.options.tolerance) {
                    let p = P::from_coords(self.points[j + off]);
                    segments[j].q = [p; 3];
                    if j > 0 || prob.closed {
                        segments[(j + n - 1) % n].q[2] = p;
                    }
                    if j + 1 < n || prob.closed {
                        segments[(j + 1) % n].q[0] = p;
                    }
                }
            }
        }
        Spline {
            scheme: self.scheme,
            closed: prob.closed,
            segments,
            report,
        }
    }
}
