//! κ-space curves: G2 interpolating curves in 3D (Wang, Sekine, Usuki, Miura, "Generation of
//! κ-space curve", CAD&A 2024 — seed paper 004).
//!
//! A κ-curve through 3D points ([`Solver3`](crate::Solver3)) is made of quadratic Bézier
//! segments. Each quadratic is planar, and consecutive ones lie in different planes, so at a
//! joint only the tangent and |κ| agree: the curvature *vectors* point into different planes
//! (G1 with equal |κ|). A [`SpaceCurve`] replaces a short piece around every joint — the last
//! part `[t1, 1]` of one quadratic and the first part `[0, t2]` of the next — by a quartic
//! Bézier whose end curvature vectors equal those of the quadratics (seed 004 eqs. 11–18; the
//! derivation is in the source of the `replace` module). The result is a chain of exact
//! Bézier segments of degree 2 and 4 that is G2 in 3D, still passes through every input
//! point, and still has its |κ| peaks there: the replaced pieces stay clear of the input
//! points.
//!
//! ```
//! use kappa::space::{SpaceCurve, SpaceOptions};
//! use kappa::Point3;
//!
//! // Points on a helix, as an open curve.
//! let points: Vec<Point3> = (0..8)
//!     .map(|i| {
//!         let th = 0.9 * i as f64;
//!         Point3::new(50.0 * th.cos(), 50.0 * th.sin(), 12.0 * th)
//!     })
//!     .collect();
//! let curve = SpaceCurve::new(&points, false, &SpaceOptions::default())?;
//! // Six quadratics (one per interior point), five quartics between them.
//! assert_eq!(curve.segments().len(), 11);
//! for joint in curve.continuity() {
//!     let c = joint.continuity;
//!     assert!(c.position_gap == 0.0 && c.tangent_angle < 1e-9);
//!     assert!(c.curvature_vector_diff < 1e-9 * curve.curvature(joint.after as f64).max(1e-12));
//! }
//! // Every interior point is still on the curve.
//! for (k, &(segment, t)) in curve.point_params().iter().enumerate() {
//!     assert!(curve.segments()[segment].eval(t).distance(points[k + 1]) < 1e-9);
//! }
//! # Ok::<(), kappa::Error>(())
//! ```
//!
//! # Options
//!
//! - [`Replace`]: which piece of the quadratics to replace. The default is the paper's plug-in
//!   setting, "replacement parameter 0.01" (seed 004 §5, Fig. 9), read as `t1 = 0.99`,
//!   `t2 = 0.01`: the last and the first 1 % of the *parameter* range of the two quadratics
//!   at each joint (§3.2 states its example the same way, `t ∈ (0.9, 1)` and `(0, 0.1)`). The
//!   replaced piece never reaches past an input point: at a joint whose neighbouring peak
//!   parameter `t_max` lies inside the requested range, the range is cut at `t_max`
//!   ([`Joint::t1`], [`Joint::t2`] tell). With `t1 = 0`, `t2 = 1` ([`Replace::FULL`]) every
//!   quartic therefore runs from one input point to the next: the paper's full replacement
//!   (§3.1), applied at every joint at once.
//! - [`Gamma`]: where the middle control point `Q2` sits on the line of the quadratics'
//!   middle control points: `γ = λ` (the paper's default, `Q2` is the old joint), the `γ`
//!   minimizing the paper's eq. 20, or values of your own.
//!
//! # Parameters
//!
//! Methods that take a position along the whole curve use `u ∈ [0, n]`, `n` the number of
//! segments: segment `⌊u⌋` at its own parameter `u − ⌊u⌋` (and `u = n` is the end). The
//! derivatives are with respect to `u`, which is each segment's own parameter.

mod export;
#[cfg(feature = "render")]
mod figure;
mod polycurve;
mod projection;
mod replace;

#[cfg(feature = "render")]
pub use figure::{views_figure, views_scene, FigureError, VIEWS};
pub use polycurve::{Joint, JointQuartic, Piece, QuarticExtremum, SpaceCurve};
pub use projection::{Projected, Projection, View};

/// Which piece of the two quadratics at each joint the quartic replaces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Replace {
    /// No replacement: the quadratic κ-curve itself (G1 with equal |κ| at the joints).
    None,
    /// Replace `t ∈ [t1, 1]` of the segment before each joint and `t ∈ [0, t2]` of the one
    /// after it (seed 004 §3.2), with `0 ≤ t1 ≤ 1 − MIN_REPLACED` and
    /// `MIN_REPLACED ≤ t2 ≤ 1` ([`MIN_REPLACED`] `= 10⁻³`, other values are
    /// [`Error::InvalidOption`](crate::Error::InvalidOption)); each range is cut at the
    /// neighbouring input point's parameter (see the [module docs](self)).
    Partial {
        /// Start of the replaced piece on the segment before the joint.
        t1: f64,
        /// End of the replaced piece on the segment after the joint.
        t2: f64,
    },
}

impl Replace {
    /// The paper's plug-in default: replacement parameter 0.01 (`t1 = 0.99`, `t2 = 0.01`).
    pub const DEFAULT: Replace = Replace::fraction(0.01);

    /// The whole stretch between consecutive input points becomes one quartic
    /// (`t1 = 0`, `t2 = 1`, cut at the input points). The chain is G2 and passes through the
    /// points, but |κ| no longer peaks at them: the quartics match the quadratic's curvature
    /// vector at a point but not the vanishing slope of |κ| there, so |κ| rises on one side
    /// (seed 004 Fig. 4 shows the same for a single joint; on the helix and the trefoil of the
    /// tests no point is a local maximum of |κ| any more).
    pub const FULL: Replace = Replace::Partial { t1: 0.0, t2: 1.0 };

    /// Replace the fraction `r` of the parameter range on each side of every joint:
    /// `t1 = 1 − r`, `t2 = r` (`r = 0` is [`Replace::None`]). Validated when used: other
    /// than 0, `r` must lie in `[MIN_REPLACED, 1]`.
    pub const fn fraction(r: f64) -> Replace {
        if r == 0.0 {
            Replace::None
        } else {
            Replace::Partial { t1: 1.0 - r, t2: r }
        }
    }
}

impl Default for Replace {
    fn default() -> Replace {
        Replace::DEFAULT
    }
}

/// The shortest replaced range, `1 − t1` and `t2` of [`Replace::Partial`]: `10⁻³` of the
/// quadratic's parameter range.
///
/// The quartic takes its end tangent and curvature from the replaced pieces' control points
/// (seed 004 eqs. 11–18): the end handle `Q3 Q4` is a multiple of `C − Q4`, which is about
/// `t2 |P3 − P2|` long, and the curvature comes from second differences over that length.
/// Coordinates rounded to `ε |p|` therefore turn the end tangent by about
/// `ε |p| / (t2 |P3 − P2|)` and change the end curvature by a relative
/// `ε |p| / (t2² |P3 − P2|)` or so: at `t2 = 3·10⁻¹⁴` the piece is a few hundred units in the
/// last place long and no quartic can be G1 there in `f64`. Ranges of at least `10⁻³` keep
/// every side (after the cut at an input point, at least a tenth of that, see
/// [`PeakAtJoint`]) long enough for G1 and G2 to within `10⁻⁸`.
pub const MIN_REPLACED: f64 = 1e-3;

/// Where the quartic's middle control point `Q2 = (1−γ) c_{i,1} + γ c_{i+1,1}` lies on the
/// line through the middle control points of the two quadratics (seed 004 eqs. 6, 14).
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Gamma {
    /// `γ = λ`, the joint ratio of the κ-curve: `Q2` is the old joint (the paper's default).
    #[default]
    Lambda,
    /// The `γ` minimizing the distance between the quartic and the pieces it replaces
    /// (seed 004 eq. 20, integrated over the replaced pieces), found by sampling and
    /// golden-section search per joint.
    Optimized,
    /// One `γ` per joint, in the order of [`SpaceCurve::joints`]; each must lie in the open
    /// interval `(λ t1, λ + (1 − λ) t2)` of its joint (where `a′` and `b′` of eqs. 17, 18
    /// are real and the end handles do not vanish).
    PerJoint(Vec<f64>),
}

/// What to do at a joint where the κ-curve put an input point (its peak forced to the end of
/// its segment, which κ-curves do).
///
/// There the quartics cannot keep both properties: a G2 quartic needs its middle control
/// point on the line where the two quadratics' planes meet, which is the tangent at the joint,
/// so a quartic ending at the joint would be straight there (and two quartics meeting there
/// would need zero curvature at the point). Such a point is within
/// `0.1 × min(r, 0.01)` (in its segment's parameter) of the joint, `r` the replaced length.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PeakAtJoint {
    /// Replace the joint anyway (G2 everywhere); the curve then passes near the point, not
    /// through it ([`SpaceCurve::missed_points`] gives the distance, `O(r²)`). Its segment's
    /// two replaced ranges are cut at `t = ½` instead of at the point.
    #[default]
    Replace,
    /// Keep the point and the κ-curve's joint there (G1 with equal |κ|, not G2).
    Keep,
}

/// Options of [`SpaceCurve::new`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SpaceOptions {
    /// The replaced pieces. Default: [`Replace::DEFAULT`].
    pub replace: Replace,
    /// The middle control point of each quartic. Default: [`Gamma::Lambda`].
    pub gamma: Gamma,
    /// Joints where an input point sits. Default: [`PeakAtJoint::Replace`].
    pub at_joint: PeakAtJoint,
    /// Options of the κ solver.
    pub solve: crate::SolveOptions,
}

impl SpaceOptions {
    /// Default options with the replaced fraction `r` (see [`Replace::fraction`]).
    pub fn with_replace(mut self, r: f64) -> SpaceOptions {
        self.replace = Replace::fraction(r);
        self
    }

    /// These options with another [`Gamma`].
    pub fn with_gamma(mut self, gamma: Gamma) -> SpaceOptions {
        self.gamma = gamma;
        self
    }
}
