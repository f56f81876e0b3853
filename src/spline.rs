//! κ-curves and εκ-curves (cubic and trigonometric): the public front of the solver.

use kurbo::{BezPath, CubicBez, ParamCurve, PathSeg, Point, QuadBez};

use crate::basis::{classify, Basis, CubicEk, Extremum, TrigEk};
use crate::fit::{FitOptions, Fitted};
use crate::solver::{Edit, Outcome, Problem, Settings, State, Tangent, TangentAt, Workspace};
use crate::trig::TrigBez;
use crate::{Error, Point3, SolvedState};

/// Iterations a warm re-solve may take before the cold cascade takes over.
const WARM_BUDGET: usize = 100;

/// Peak parameters within this of 0 or 1 sit at the segment end (as the analysis counts
/// them).
const END_PEAK: f64 = 1e-9;

/// How many drawing sizes beyond the points the arithmetic must stay finite: drawings that
/// reach within this of `±f64::MAX` (or whose centre is beyond a quarter of it) are an
/// [`Error::ExtentOverflow`] (found by fuzzing: a drawing 1e308 wide solved, but its curve
/// evaluated to infinity).
const EXTENT_HEADROOM: f64 = 1e3;

/// The relative size below which two consecutive points count as repeated, and below which
/// the spread of a closed curve's points off their best line counts as collinear.
const COINCIDENT: f64 = 1e-12;

/// Two consecutive points closer than this many `f64::EPSILON`s times their largest
/// coordinate magnitude (4 to 8 units in the last place) also count as repeated: their
/// difference is rounding noise of their own coordinates (a pair one ulp apart has one of
/// eight directions), so no curve through them means anything, and a drawing a few hundred
/// ulps wide cannot hold its own control points (found by fuzzing: peaks at such pairs
/// moved by up to 100 % of |κ| when the same solution was written in user coordinates).
/// Scale-invariant: it depends on where the points are, not on the units.
const ULP_COINCIDENT: f64 = 4.0;

/// The family of segments a curve is built from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
pub enum Scheme {
    /// κ-curves (Yan et al. 2017): quadratic Bézier segments, curvature peaks at the points.
    #[default]
    Kappa,
    /// εκ-curves with the constrained cubic Bernstein segment (seed 000 §3): a shape
    /// parameter `a ∈ [2/3, 1)` per point; larger `a` gives a sharper curvature peak.
    EkCubic,
    /// εκ-curves with the constrained quadratic trigonometric segment (seed 000 §4): a
    /// shape parameter `a ∈ [1/2, 1)` per point, rounder than [`Scheme::EkCubic`] at the
    /// same `a`. Not polynomial: [`Spline::to_bezpath`] fits cubics to it.
    ///
    /// For `a` below about 0.61 and gentle turns the stationary point placed at an input
    /// point is a curvature *minimum* (see [`Segment::extremum`]); the default shape
    /// ([`Scheme::neutral_shape`]) is [`EK_TRIG_DEFAULT_SHAPE`], which keeps maxima.
    EkTrig,
}

/// The default shape parameter of [`Scheme::EkTrig`]. A symmetric segment's stationary
/// point is a curvature minimum below `a ≈ 0.6104` (for a gentle 1° turn; less for sharper
/// turns), and asymmetric segments need more: on the built-in drawings, 9 of their points
/// sit at minima with `a = 0.65` and none with `a = 0.7`.
pub const EK_TRIG_DEFAULT_SHAPE: f64 = 0.7;

impl Scheme {
    /// The shape parameter of [`Shape::Neutral`]: `2/3` for κ and εκ-cubic (the εκ cubic is
    /// then the κ quadratic), [`EK_TRIG_DEFAULT_SHAPE`] for εκ-trig.
    pub const fn neutral_shape(self) -> f64 {
        match self {
            Scheme::Kappa | Scheme::EkCubic => 2.0 / 3.0,
            Scheme::EkTrig => EK_TRIG_DEFAULT_SHAPE,
        }
    }

    /// The admissible shape range `[min, max)`.
    pub const fn shape_range(self) -> (f64, f64) {
        match self {
            Scheme::Kappa => (2.0 / 3.0, 2.0 / 3.0),
            Scheme::EkCubic => (2.0 / 3.0, 1.0),
            Scheme::EkTrig => (0.5, 1.0),
        }
    }

    /// The degree of the output segments: 2 for κ (quadratic Bézier) and εκ-trig
    /// (quadratic trigonometric), 3 for εκ-cubic.
    pub const fn degree(self) -> usize {
        match self {
            Scheme::Kappa | Scheme::EkTrig => 2,
            Scheme::EkCubic => 3,
        }
    }

    /// Whether the segments are polynomial, so that [`Spline::to_bezpath`] is exact.
    pub const fn is_polynomial(self) -> bool {
        !matches!(self, Scheme::EkTrig)
    }

    /// The solver's segment family for shape `a`.
    fn basis(self, a: f64) -> Basis {
        match self {
            Scheme::Kappa | Scheme::EkCubic => Basis::Cubic(CubicEk::new(a)),
            Scheme::EkTrig => Basis::Trig(TrigEk::new(a)),
        }
    }
}

/// Shape parameters of εκ-curves.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Shape {
    /// The scheme's neutral value ([`Scheme::neutral_shape`]).
    #[default]
    Neutral,
    /// One value for every point.
    Global(f64),
    /// One value per input point (for open curves the first and last are ignored).
    PerPoint(Vec<f64>),
}

impl From<f64> for Shape {
    fn from(a: f64) -> Shape {
        Shape::Global(a)
    }
}

/// Solver options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveOptions {
    /// Convergence tolerance, relative to the drawing size (the larger side of the points'
    /// bounding box): interpolation error, and the (dimensionless) G2 and peak conditions.
    pub tolerance: f64,
    /// Iteration cap (Newton steps plus classic iterations, over every attempt of a cold
    /// solve, continuation steps included; default 2000). A solve costs `O(n)` per iteration.
    pub max_iterations: usize,
    /// Return the best curve found instead of [`Error::NotConverged`] when the cap is hit;
    /// [`Spline::converged`] then tells.
    pub accept_unconverged: bool,
}

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            tolerance: 1e-12,
            // Every iteration counts, continuation steps included: the hardest built-in curve
            // (deer[2], εκ-trig a = 0.65) takes 1514.
            max_iterations: 2000,
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

/// A segment of a κ- or εκ-curve whose curvature peaks at its input point, at parameter
/// `t_max`: a quadratic Bézier (κ), a constrained cubic Bézier (εκ-cubic, seed 000 eq. 1)
/// or a constrained quadratic trigonometric curve (εκ-trig, seed 000 eq. 17).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment<P> {
    /// The three defining points `Q0, Q1, Q2` (seed 000 eqs. 1 and 17).
    pub q: [P; 3],
    /// The shape parameter `a` (`2/3` for κ-curves).
    pub a: f64,
    /// The parameter of the curvature peak (where the input point lies).
    pub t_max: f64,
    /// The degree: 2 (κ; εκ-trig, quadratic trigonometric) or 3 (εκ-cubic).
    pub degree: usize,
    /// The scheme the segment belongs to.
    pub scheme: Scheme,
}

impl<P> Segment<P> {
    /// The solver's basis of this segment.
    fn basis(&self) -> Basis {
        if self.degree == 2 && self.scheme != Scheme::EkTrig {
            Basis::QUADRATIC
        } else {
            self.scheme.basis(self.a)
        }
    }
}

impl<P: PartialEq> Segment<P> {
    /// Whether the segment has collapsed onto its input point: its three defining points
    /// are that point. The input point is then an inflection of the curve, where the
    /// neighbouring segments meet tangent to each other ([`Extremum::Inflection`]); the
    /// segment has no length and contributes nothing to paths, combs or curvature maxima.
    ///
    /// It happens where an interior point lies on the line through its neighbours and the
    /// curve is symmetric about it (a point-symmetric S or wave): as the point approaches
    /// the line, the segment through it shrinks linearly to the point (see the solver's
    /// notes in [`Solver`]).
    ///
    /// ```
    /// use kappa::{Extremum, Spline};
    /// use kurbo::Point;
    ///
    /// // A wave whose middle point lies on the line through its neighbours.
    /// let wave = [(100.0, 300.0), (250.0, 200.0), (400.0, 300.0), (550.0, 400.0), (700.0, 300.0)]
    ///     .map(Point::from);
    /// let curve = Spline::kappa(&wave, false)?;
    /// assert!(curve.converged());
    /// let middle = &curve.segments()[1];
    /// assert!(middle.is_collapsed());
    /// assert_eq!(middle.extremum(), Extremum::Inflection);
    /// # Ok::<(), kappa::Error>(())
    /// ```
    pub fn is_collapsed(&self) -> bool {
        self.q[0] == self.q[1] && self.q[1] == self.q[2]
    }
}

impl Segment<Point> {
    /// The control points: the Bézier control points (3 for κ, 4 for εκ-cubic), or for
    /// εκ-trig the five control points `P0..P4` of the quadratic trigonometric curve
    /// (seed 000 eq. 17; see [`TrigBez::constrained`]).
    pub fn control_points(&self) -> Vec<Point> {
        if self.scheme == Scheme::EkTrig {
            return self.to_trig().points().to_vec();
        }
        match self.to_path_seg() {
            PathSeg::Quad(q) => vec![q.p0, q.p1, q.p2],
            PathSeg::Cubic(c) => vec![c.p0, c.p1, c.p2, c.p3],
            PathSeg::Line(l) => vec![l.p0, l.p1],
        }
    }

    /// The kurbo segment: exact `QuadBez` for κ and `CubicBez` for εκ-cubic. An εκ-trig
    /// segment has no exact polynomial form; it gives the cubic with the same end points
    /// and end derivatives (a rough stand-in — use [`Spline::fit`] or
    /// [`Spline::to_bezpath`] for a path within a stated tolerance).
    pub fn to_path_seg(&self) -> PathSeg {
        let [q0, q1, q2] = self.q;
        match (self.scheme, self.degree) {
            (Scheme::EkTrig, _) => {
                let trig = self.to_trig();
                let (d0, d1) = (trig.derivative(0.0) / 3.0, trig.derivative(1.0) / 3.0);
                PathSeg::Cubic(CubicBez::new(q0, q0 + d0, q2 - d1, q2))
            }
            (_, 2) => PathSeg::Quad(QuadBez::new(q0, q1, q2)),
            _ => {
                let a = self.a;
                PathSeg::Cubic(CubicBez::new(q0, q0.lerp(q1, a), q2.lerp(q1, a), q2))
            }
        }
    }

    /// An εκ-trig segment as a [`TrigBez`] (for the other schemes, the same defining points
    /// read as a constrained trigonometric curve — only meaningful for εκ-trig).
    pub fn to_trig(&self) -> TrigBez {
        let [q0, q1, q2] = self.q;
        TrigBez::constrained(q0, q1, q2, self.a)
    }

    /// The point at parameter `t`.
    pub fn eval(&self, t: f64) -> Point {
        if self.scheme == Scheme::EkTrig {
            return self.to_trig().eval(t);
        }
        self.to_path_seg().eval(t)
    }

    /// The derivative `dP/dt` at `t` (its direction is the tangent's), exact for every
    /// scheme.
    pub fn derivative(&self, t: f64) -> kurbo::Vec2 {
        use kurbo::ParamCurveDeriv;
        if self.scheme == Scheme::EkTrig {
            return self.to_trig().derivative(t);
        }
        match self.to_path_seg() {
            PathSeg::Line(l) => l.deriv().eval(t).to_vec2(),
            PathSeg::Quad(q) => q.deriv().eval(t).to_vec2(),
            PathSeg::Cubic(c) => c.deriv().eval(t).to_vec2(),
        }
    }

    /// The signed curvature at `t` (positive for left turns), exact for every scheme.
    pub fn curvature(&self, t: f64) -> f64 {
        if self.scheme == Scheme::EkTrig {
            return self.to_trig().curvature(t);
        }
        crate::analysis::CurvatureAnalysis::curvature(&self.to_path_seg(), t)
    }

    /// The curvature vector at `t` (`κ` times the left unit normal: it points to the centre
    /// of curvature), exact for every scheme; zero where the tangent is undefined.
    pub fn curvature_vector(&self, t: f64) -> kurbo::Vec2 {
        if self.scheme == Scheme::EkTrig {
            let trig = self.to_trig();
            let d = trig.derivative(t);
            let len = d.hypot();
            if len == 0.0 || !len.is_finite() {
                return kurbo::Vec2::ZERO;
            }
            return trig.curvature(t) * kurbo::Vec2::new(-d.y, d.x) / len;
        }
        crate::analysis::CurvatureAnalysis::curvature_vector(&self.to_path_seg(), t)
    }

    /// Whether `|κ|` is maximal or minimal at `t_max` (see [`Extremum`]). κ and εκ-cubic
    /// segments always peak there (or have collapsed onto an inflection); εκ-trig segments
    /// with `a` below about 0.61 may have a minimum there, and one whose peak was pushed to
    /// a segment end may be higher inside ([`Extremum::EndOnly`], found by sampling |κ| at
    /// 64 parameters).
    pub fn extremum(&self) -> Extremum {
        if self.is_collapsed() {
            return Extremum::Inflection;
        }
        if self.scheme != Scheme::EkTrig {
            // The quadratic and the constrained cubic have one stationary point of |κ|, a
            // maximum (seed 000 §3); classifying it numerically fails on nearly straight
            // segments, where r ≈ s cancels.
            return Extremum::Max;
        }
        let [q0, q1, q2] = self.q;
        let (r, s) = (q1 - q0, q2 - q1);
        let kind = classify(&self.basis(), r.dot(r), r.dot(s), s.dot(s), self.t_max);
        let at_end = self.t_max <= END_PEAK || self.t_max >= 1.0 - END_PEAK;
        if kind == Extremum::Max && at_end {
            // A local maximum at the end; is it the segment's? (|κ| sampled at 64 inner
            // parameters, against its value at the end with the rounding of its control
            // points allowed for.)
            let trig = self.to_trig();
            let k = trig.curvature(self.t_max).abs();
            let inside = (1..64)
                .map(|i| trig.curvature(i as f64 / 64.0).abs())
                .fold(0.0, f64::max);
            if inside > k * (1.0 + 1e-9) {
                return Extremum::EndOnly;
            }
        }
        kind
    }
}

impl Segment<Point3> {
    /// The Bézier control points (3 for degree 2, 4 for degree 3).
    pub fn control_points(&self) -> Vec<Point3> {
        let [q0, q1, q2] = self.q;
        if self.degree == 2 {
            vec![q0, q1, q2]
        } else {
            vec![q0, q0.lerp(q1, self.a), q2.lerp(q1, self.a), q2]
        }
    }

    /// The point at parameter `t` (de Casteljau).
    pub fn eval(&self, t: f64) -> Point3 {
        let mut pts = self.control_points();
        let n = pts.len();
        for level in 1..n {
            for i in 0..n - level {
                pts[i] = pts[i].lerp(pts[i + 1], t);
            }
        }
        pts[0]
    }
}

/// A solved κ- or εκ-curve through 2D points.
///
/// Segment `i` of a closed curve passes through point `i` at its parameter `t_max`, where its
/// |κ| is stationary (an open curve has a segment per interior point), and consecutive
/// segments meet with equal curvature (G2).
///
/// ```
/// use kappa::Spline;
/// use kurbo::Point;
///
/// let points = [(0.0, 0.0), (100.0, 10.0), (120.0, 90.0), (20.0, 110.0)].map(Point::from);
/// let curve = Spline::kappa(&points, true)?;
/// let segments = curve.segments();
/// assert_eq!(segments.len(), points.len());
/// for (i, seg) in segments.iter().enumerate() {
///     assert!((seg.eval(seg.t_max) - points[i]).hypot() < 1e-9);
///     let next = &segments[(i + 1) % segments.len()];
///     let (k0, k1) = (seg.curvature(1.0), next.curvature(0.0));
///     assert!((k0 - k1).abs() <= 1e-9 * k0.abs().max(k1.abs()));
/// }
/// // An open εκ-curve: cubic segments, one per interior point.
/// let open = Spline::ek_cubic(&points, false, 0.9)?;
/// assert_eq!(open.segments().len(), 2);
/// assert!(open.segments().iter().all(|s| s.degree == 3));
/// # Ok::<(), kappa::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Spline<P = Point> {
    scheme: Scheme,
    closed: bool,
    segments: Vec<Segment<P>>,
    report: SolveReport,
}

/// A solved κ- or εκ-curve through 3D points (the base of κ-space curves); solve with
/// [`Solver3`].
pub type Spline3 = Spline<Point3>;

impl<P: Copy> Spline<P> {
    /// The scheme.
    pub fn scheme(&self) -> Scheme {
        self.scheme
    }

    /// Whether the curve is closed.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// The segments in order along the curve: one per input point (closed) or per interior
    /// input point (open; a two-point open curve is one straight segment).
    pub fn segments(&self) -> &[Segment<P>] {
        &self.segments
    }

    /// What the solver did.
    pub fn report(&self) -> SolveReport {
        self.report
    }

    /// Iterations used.
    pub fn iterations(&self) -> usize {
        self.report.iterations
    }

    /// Whether the solver reached its tolerance.
    pub fn converged(&self) -> bool {
        self.report.converged
    }
}

impl Spline<Point> {
    /// A κ-curve through `points` with default options.
    pub fn kappa(points: &[Point], closed: bool) -> Result<Spline, Error> {
        Solver::new().solve(points, closed, Scheme::Kappa, &Shape::Neutral)
    }

    /// A cubic εκ-curve through `points` with default options.
    pub fn ek_cubic(
        points: &[Point],
        closed: bool,
        shape: impl Into<Shape>,
    ) -> Result<Spline, Error> {
        Solver::new().solve(points, closed, Scheme::EkCubic, &shape.into())
    }

    /// An εκ-curve in the trigonometric basis through `points` with default options.
    pub fn ek_trig(
        points: &[Point],
        closed: bool,
        shape: impl Into<Shape>,
    ) -> Result<Spline, Error> {
        Solver::new().solve(points, closed, Scheme::EkTrig, &shape.into())
    }

    /// A curvature comb of the exact curve (every scheme, trigonometric segments included):
    /// `samples_per_segment` teeth per segment, uniform in `t` with both ends, each from the
    /// curve point `p` to `p − scale · κ · n` (see [`crate::analysis::curvature_comb`]).
    pub fn curvature_comb(&self, scale: f64, samples_per_segment: usize) -> BezPath {
        crate::analysis::comb_from_samples(self.curvature_samples(samples_per_segment), scale)
    }

    /// Samples `(p, k)` of the exact curve, `samples_per_segment` (at least 2) per segment
    /// evenly in each segment's parameter, ends included: the point and the curvature vector
    /// `κ n` (`n` the left unit normal; zero where the curve stalls).
    pub fn curvature_samples(&self, samples_per_segment: usize) -> Vec<(Point, kurbo::Vec2)> {
        let m = samples_per_segment.max(2);
        let mut samples = Vec::with_capacity(m * self.segments.len());
        for seg in &self.segments {
            // One curve object per segment; points and derivatives straight from it.
            let trig = (seg.scheme == Scheme::EkTrig).then(|| seg.to_trig());
            let poly = seg.to_path_seg();
            for i in 0..m {
                let t = i as f64 / (m - 1) as f64;
                let (p, d1, d2) = match &trig {
                    Some(c) => c.eval_derivs(t),
                    None => path_seg_derivs(&poly, t),
                };
                let len2 = d1.hypot2();
                let k = if len2 > 0.0 && len2.is_finite() {
                    // κ n with n the left unit normal: (d1 × d2)/|d1|⁴ · (-d1.y, d1.x).
                    d1.cross(d2) / (len2 * len2) * kurbo::Vec2::new(-d1.y, d1.x)
                } else {
                    kurbo::Vec2::ZERO
                };
                samples.push((p, k));
            }
        }
        samples
    }

    /// The largest |κ| of the curve: at the peak parameters, the segment ends, and 64
    /// samples per segment (exact for the peaks the scheme places at the input points).
    pub fn max_abs_curvature(&self) -> f64 {
        self.segments
            .iter()
            .flat_map(|seg| {
                (0..=64)
                    .map(|i| i as f64 / 64.0)
                    .chain([seg.t_max])
                    .map(move |t| seg.curvature(t).abs())
            })
            .filter(|k| k.is_finite())
            .fold(0.0, f64::max)
    }

    /// The curve as a kurbo path within `options`' tolerance, with the number of cubics per
    /// segment and the measured distance to the exact curve (see [`crate::fit`]). εκ-trig
    /// segments are fitted; the polynomial schemes give their exact path
    /// ([`Spline::to_bezpath`], one segment each, distance 0).
    pub fn fit(&self, options: &FitOptions) -> Result<Fitted, Error> {
        if self.scheme != Scheme::EkTrig {
            let path = self.to_bezpath();
            let tolerance = match options.tolerance {
                crate::fit::FitTolerance::Absolute(v) => v,
                crate::fit::FitTolerance::Relative(v) => {
                    let bbox = kurbo::Shape::bounding_box(&path);
                    v * bbox.width().max(bbox.height())
                }
            };
            return Ok(Fitted {
                path,
                cubics: self
                    .segments
                    .iter()
                    .map(|s| usize::from(!s.is_collapsed()))
                    .collect(),
                tolerance,
                max_distance: 0.0,
            });
        }
        // Fitted in a frame where the curve is about one unit wide around the origin, and
        // mapped back: the fitters' own thresholds are absolute, and at coordinates of 1e6
        // and more (or far from the origin) they measured errors of a tenth of the curve, or
        // tens of thousands of cubics.
        let points: Vec<[f64; 2]> = self
            .segments
            .iter()
            .flat_map(|s| s.q.map(Coords::coords))
            .collect();
        let Frame { center, size } = Frame::new(&points);
        let to_local = kurbo::Affine::translate((-center[0], -center[1])).then_scale(1.0 / size);
        let trig: Vec<TrigBez> = self
            .segments
            .iter()
            .map(|s| {
                let [q0, q1, q2] = s.q.map(|q| to_local * q);
                TrigBez::constrained(q0, q1, q2, s.a)
            })
            .collect();
        let local = FitOptions {
            tolerance: match options.tolerance {
                crate::fit::FitTolerance::Absolute(v) => {
                    crate::fit::FitTolerance::Absolute(v / size)
                }
                relative => relative,
            },
            ..*options
        };
        let mut fitted = crate::fit::fit(&trig, self.closed, &local)?;
        // (Not `to_local.inverse()`: its determinant underflows for sizes beyond 1e154.)
        fitted
            .path
            .apply_affine(kurbo::Affine::scale(size).then_translate((center[0], center[1]).into()));
        fitted.tolerance *= size;
        fitted.max_distance *= size;
        Ok(fitted)
    }

    /// The curve as a kurbo path: exact `QuadBez` (κ) or `CubicBez` (εκ-cubic) segments;
    /// for εκ-trig, cubics fitted within `1e-4` of the drawing size
    /// ([`FitOptions::default`]; use [`Spline::fit`] to choose).
    pub fn to_bezpath(&self) -> BezPath {
        if self.scheme == Scheme::EkTrig {
            // Fitting a solved curve cannot fail (its points are finite); an empty path
            // would only stand for that impossible case.
            return self
                .fit(&FitOptions::default())
                .map(|f| f.path)
                .unwrap_or_default();
        }
        let mut path = BezPath::new();
        for (i, seg) in self.segments.iter().enumerate() {
            let ps = seg.to_path_seg();
            if i == 0 {
                path.move_to(ps.start());
            }
            if seg.is_collapsed() {
                // An inflection at its input point: no length, nothing to draw.
                continue;
            }
            match ps {
                PathSeg::Line(l) => path.line_to(l.p1),
                PathSeg::Quad(q) => path.quad_to(q.p1, q.p2),
                PathSeg::Cubic(c) => path.curve_to(c.p1, c.p2, c.p3),
            }
        }
        if self.closed && !self.segments.is_empty() {
            path.close_path();
        }
        path
    }

    /// SVG path data of [`Spline::to_bezpath`]: the shortest decimal that reads back to the
    /// same `f64`, in exponent form where that is shorter (`1e300`, not 301 digits).
    pub fn to_svg(&self) -> String {
        svg_path_data(&self.to_bezpath())
    }
}

/// Point, first and second derivative of a kurbo segment at `t`.
pub(crate) fn path_seg_derivs(seg: &PathSeg, t: f64) -> (Point, kurbo::Vec2, kurbo::Vec2) {
    use kurbo::ParamCurveDeriv;
    match seg {
        PathSeg::Line(l) => (l.eval(t), l.p1 - l.p0, kurbo::Vec2::ZERO),
        PathSeg::Quad(q) => (
            q.eval(t),
            q.deriv().eval(t).to_vec2(),
            q.deriv().deriv().eval(t).to_vec2(),
        ),
        PathSeg::Cubic(c) => (
            c.eval(t),
            c.deriv().eval(t).to_vec2(),
            c.deriv().deriv().eval(t).to_vec2(),
        ),
    }
}

/// SVG path data of any kurbo path: absolute commands, and for every number the shortest
/// decimal that reads back to the same `f64`, in exponent form where that is shorter
/// (`1e300`, not 301 digits; `6.9e-18`, not 22 digits).
pub fn svg_path_data(path: &BezPath) -> String {
    use kurbo::PathEl;
    use std::fmt::Write as _;
    let mut out = String::new();
    let mut put = |cmd: char, pts: &[Point]| {
        if !out.is_empty() {
            out.push(' ');
        }
        out.push(cmd);
        for (i, p) in pts.iter().enumerate() {
            if i > 0 {
                out.push(' ');
            }
            let _ = write!(out, "{},{}", svg_number(p.x), svg_number(p.y));
        }
    };
    for el in path.elements() {
        match *el {
            PathEl::MoveTo(p) => put('M', &[p]),
            PathEl::LineTo(p) => put('L', &[p]),
            PathEl::QuadTo(p1, p2) => put('Q', &[p1, p2]),
            PathEl::CurveTo(p1, p2, p3) => put('C', &[p1, p2, p3]),
            PathEl::ClosePath => put('Z', &[]),
        }
    }
    out
}

/// A number for SVG: Rust's shortest round-trip decimal, or its exponent form when shorter.
fn svg_number(x: f64) -> String {
    let plain = format!("{x}");
    let exp = format!("{x:e}");
    if exp.len() < plain.len() {
        exp
    } else {
        plain
    }
}

/// Affine map from user coordinates to the normalized frame (drawing size 1).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Frame<const D: usize> {
    center: [f64; D],
    size: f64,
}

impl<const D: usize> Frame<D> {
    fn new(points: &[[f64; D]]) -> Frame<D> {
        let mut lo = [f64::INFINITY; D];
        let mut hi = [f64::NEG_INFINITY; D];
        for p in points {
            for k in 0..D {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let size = (0..D).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        Frame {
            // Halves first: (lo + hi) / 2 can overflow where lo/2 + hi/2 does not.
            center: core::array::from_fn(|k| 0.5 * lo[k] + 0.5 * hi[k]),
            size: if size > 0.0 { size } else { 1.0 },
        }
    }

    fn to_local(self, p: [f64; D]) -> [f64; D] {
        core::array::from_fn(|k| (p[k] - self.center[k]) / self.size)
    }

    fn to_user(self, p: [f64; D]) -> [f64; D] {
        core::array::from_fn(|k| p[k] * self.size + self.center[k])
    }
}

/// Conversion between user point types and coordinate arrays.
pub trait Coords<const D: usize>: Copy {
    /// The coordinates.
    fn coords(self) -> [f64; D];
    /// The point with these coordinates.
    fn from_coords(c: [f64; D]) -> Self;
}

impl Coords<2> for Point {
    fn coords(self) -> [f64; 2] {
        [self.x, self.y]
    }
    fn from_coords(c: [f64; 2]) -> Self {
        Point::new(c[0], c[1])
    }
}

impl Coords<3> for Point3 {
    fn coords(self) -> [f64; 3] {
        [self.x, self.y, self.z]
    }
    fn from_coords(c: [f64; 3]) -> Self {
        Point3::new(c[0], c[1], c[2])
    }
}

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
/// the limit of the curves for the point moved off the line. Moving the middle point of
/// the wave `(100,300) (250,200) (400,300) (550,400) (700,300)` off the line by `ε`, the
/// segment through it shrinks linearly to the point (its span is about `3ε`, its peak
/// parameter stays near 0.784, or 0.216 for `-ε`) while the rest converges: the limit is
/// the two neighbouring segments meeting at the point, tangent to each other, with
/// curvatures of equal magnitude and opposite sign. The solver converges to it: the
/// shrinking segment's rows are measured above their rounding floor, its joint ratios are
/// held at their bounds once it has collapsed, and the collapsed segment counts as solved
/// where the control polygon is straight at the point (see the solver's `Joint::collapsed`). The
/// result reports the segment as [`Segment::is_collapsed`] ([`Extremum::Inflection`]).
/// Measured on that wave for every scheme: offsets of 1e-12 to 1e-2 of the drawing size on
/// either side converge, and the curve is within 1.8 to 3.1 times the offset of the
/// collinear one (up to 141 times for κ below 1e-10, where the shrinking segment is resolved
/// only to its rounding floor). Without the symmetry, a point on its neighbours' line sits
/// at a segment end instead (`t_max` 0 or 1), where the neighbouring segments meet: an
/// inflection at the joint.
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
    /// square (derivation in the `solver` module's [`Tangent`] notes):
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
            // capped attempt, then the cold cascade with what is left of the budget.
            let warm_settings = Settings {
                max_iterations: settings.max_iterations.min(WARM_BUDGET),
                ..settings
            };
            let warm = self.ws.solve_warm(&self.prob, &warm_settings);
            if warm.converged {
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

/// The input points that get a segment: all of a closed curve, the interior ones of an open
/// curve (`m ≥ 2`).
fn block_range(closed: bool, m: usize) -> core::ops::Range<usize> {
    if closed {
        0..m
    } else {
        1..m - 1
    }
}

/// Whether points on one line come in strictly monotone order along it.
fn monotone_along_line<const D: usize>(p: &[[f64; D]]) -> bool {
    // Along the line from the first point to the farthest one: the last point may coincide
    // with the first (a loop that doubles back), and then gives no direction.
    let d2 = |q: &[f64; D]| (0..D).map(|k| (q[k] - p[0][k]).powi(2)).sum::<f64>();
    let far = p
        .iter()
        .fold(p[0], |best, q| if d2(q) > d2(&best) { *q } else { best });
    let dir: [f64; D] = core::array::from_fn(|k| far[k] - p[0][k]);
    let along = |q: &[f64; D]| (0..D).map(|k| (q[k] - p[0][k]) * dir[k]).sum::<f64>();
    p.windows(2).all(|w| along(&w[1]) > along(&w[0]))
}

/// Whether two points coincide to within the rounding of their own coordinates:
/// `|a − b| ≤ ULP_COINCIDENT · ε · max |coordinate|` (see [`ULP_COINCIDENT`]).
fn within_rounding<const D: usize>(a: [f64; D], b: [f64; D]) -> bool {
    let mag = a.iter().chain(&b).fold(0.0f64, |m, v| m.max(v.abs()));
    if mag == 0.0 {
        return true;
    }
    // In units of the magnitude (squares of tiny differences underflow), halves first (the
    // difference of finite points can overflow).
    let d = (0..D)
        .map(|k| ((0.5 * a[k] - 0.5 * b[k]) / mag).powi(2))
        .sum::<f64>()
        .sqrt();
    d <= 0.5 * ULP_COINCIDENT * f64::EPSILON
}

/// Whether all points lie on one line (relative to the drawing size 1).
fn collinear<const D: usize>(p: &[[f64; D]]) -> bool {
    // Farthest point from p0, then the largest distance from the line through both.
    let far = p
        .iter()
        .map(|q| (0..D).map(|k| (q[k] - p[0][k]).powi(2)).sum::<f64>())
        .enumerate()
        .fold(
            (0, 0.0),
            |best, (i, d)| if d > best.1 { (i, d) } else { best },
        );
    let dir: [f64; D] = core::array::from_fn(|k| p[far.0][k] - p[0][k]);
    let len2 = far.1;
    if len2 <= 0.0 {
        return true;
    }
    p.iter().all(|q| {
        let v: [f64; D] = core::array::from_fn(|k| q[k] - p[0][k]);
        let along = (0..D).map(|k| v[k] * dir[k]).sum::<f64>() / len2;
        let off2 = (0..D).map(|k| (v[k] - along * dir[k]).powi(2)).sum::<f64>();
        off2.sqrt() <= COINCIDENT
    })
}

/// The shape parameter of point `i` of `shape` (validated by [`check_shapes`]).
fn shape_at(scheme: Scheme, shape: &Shape, i: usize) -> f64 {
    match shape {
        Shape::Neutral => scheme.neutral_shape(),
        Shape::Global(a) => *a,
        Shape::PerPoint(v) => v[i],
    }
}

/// Validate the shape parameters of `m` points (read back by [`shape_at`], with no copy).
fn check_shapes(scheme: Scheme, shape: &Shape, m: usize) -> Result<(), Error> {
    let (min, max) = scheme.shape_range();
    // A uniform shape is checked once (as the first point's).
    let count = match shape {
        Shape::PerPoint(v) if v.len() != m => {
            return Err(Error::ShapeCount {
                expected: m,
                got: v.len(),
            })
        }
        Shape::PerPoint(_) => m,
        Shape::Neutral | Shape::Global(_) => m.min(1),
    };
    for index in 0..count {
        let value = shape_at(scheme, shape, index);
        if scheme == Scheme::Kappa && value != min {
            return Err(Error::InvalidOption(
                "the kappa scheme has no shape parameter (use ek-cubic)",
            ));
        }
        if scheme != Scheme::Kappa && !(value >= min && value < max) {
            return Err(Error::ShapeOutOfRange {
                index,
                value,
                min,
                max,
            });
        }
    }
    Ok(())
}
