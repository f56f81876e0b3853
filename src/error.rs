//! The error type of the crate.

/// Everything that can go wrong when building a curve from user input.
///
/// Every public entry point validates its input and reports problems with one of these
/// variants; none of them panics, loops forever or returns NaN on bad input.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// Fewer input points than the curve type needs.
    #[error("too few points: {kind} needs at least {needed}, got {got}")]
    TooFewPoints {
        /// What was being built ("closed curve", "open curve", ...).
        kind: &'static str,
        /// The minimum number of points.
        needed: usize,
        /// The number of points given.
        got: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("point {index} has a coordinate that is NaN or infinite")]
    NonFinitePoint {
        /// Index of the offending point.
        index: usize,
    },
    /// Two consecutive input points coincide (or nearly so: relative to the drawing size, or
    /// for κ- and εκ-curves also to within a few units in the last place of their coordinates).
    #[error("points {index} and {next} coincide")]
    RepeatedPoint {
        /// Index of the first point of the pair.
        index: usize,
        /// Index of the second point of the pair (wraps around for closed curves).
        next: usize,
    },
    /// The points are so far apart that their extent overflows, or the curve through them
    /// could (coordinates near ±1e308; the κ-family solvers keep a thousand drawing sizes of
    /// headroom).
    #[error("the points span more than the largest finite number")]
    ExtentOverflow,
    /// All points lie on one line and the curve would have to turn back along it (every
    /// closed curve on one line, and open ones whose points double back), so no curve
    /// through them exists.
    #[error("the points are collinear and the curve would have to turn back along the line")]
    Collinear,
    /// A shape parameter is outside its admissible range or not finite.
    #[error("shape parameter {index} is {value}, outside [{min}, {max})")]
    ShapeOutOfRange {
        /// Index of the input point that the parameter belongs to.
        index: usize,
        /// The value given.
        value: f64,
        /// The smallest admissible value.
        min: f64,
        /// The bound that the value must stay below.
        max: f64,
    },
    /// A per-point shape list whose length does not match the number of points.
    #[error("expected {expected} shape parameters (one per point), got {got}")]
    ShapeCount {
        /// The number of input points.
        expected: usize,
        /// The number of shape parameters given.
        got: usize,
    },
    /// A tangent list whose length does not match the number of points, or a tangent
    /// that is zero or not finite.
    #[error("tangent {index}: {reason}")]
    InvalidTangent {
        /// Index of the point (the list's length when the count is wrong).
        index: usize,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// Two tangents fall on one segment: the first (last) point of an open curve and the
    /// point after (before) it, or both ends of an open curve of three points. A segment's
    /// peak condition makes room for one tangent only (see
    /// [`Solver::solve_with_tangents`](crate::Solver::solve_with_tangents)).
    #[error("tangents at points {first} and {second} fall on one segment; drop one or add a point between them")]
    TangentConflict {
        /// The first point.
        first: usize,
        /// The second point.
        second: usize,
    },
    /// The `γ` of a κ-space curve's joint lies outside the open interval where its quartic
    /// exists (`(λ t1, λ + (1 − λ) t2)`, seed 004 eqs. 17, 18), or is not finite.
    #[error("gamma of joint {joint} is {value}, outside ({min}, {max})")]
    GammaOutOfRange {
        /// Index of the joint.
        joint: usize,
        /// The value given.
        value: f64,
        /// The lower bound (excluded).
        min: f64,
        /// The upper bound (excluded).
        max: f64,
    },
    /// A solver option (tolerance, iteration cap, ...) is not usable.
    #[error("invalid option: {0}")]
    InvalidOption(&'static str),
    /// A curve handed to the fitting adapter evaluates to a NaN or infinite point or
    /// derivative.
    #[error("segment {segment} of the curve to fit is not finite")]
    NonFiniteCurve {
        /// Index of the offending segment.
        segment: usize,
    },
    /// A JSON input could not be used: malformed, of the wrong shape, or too large (the `input`
    /// module, feature `serde`); the message says what and where.
    #[error("{0}")]
    InvalidInput(String),
    /// An SVG document could not be read.
    #[error("invalid SVG: {0}")]
    InvalidSvg(String),
    /// No curve with the requested curvature profile meets the Hermite end conditions (for
    /// example G2 end curvatures outside the profile's viable region).
    #[error("no curve with this curvature profile meets the end conditions: {reason}")]
    NoHermiteSolution {
        /// Why the solver gave up.
        reason: &'static str,
    },
    /// A font could not be read or written (glyph outlines, UFO sources, compiled fonts).
    #[error("font: {0}")]
    Font(String),
    /// The font maps no glyph to a character.
    #[error("the font has no glyph for {ch:?}")]
    MissingGlyph {
        /// The character looked up.
        ch: char,
    },
    /// lyon could not tessellate a path.
    #[error("tessellation failed: {0}")]
    Tessellation(String),
    /// The solver stopped at its iteration cap before reaching the tolerance.
    #[error("did not converge in {iterations} iterations (relative residual {residual:e})")]
    NotConverged {
        /// Iterations performed.
        iterations: usize,
        /// The relative residual reached (interpolation error / drawing size).
        residual: f64,
    },
}
