//! Curves defined by their curvature: explicit (rational) Bézier curvature functions of arc
//! length (Yoshida & Saito, "Planar curves based on explicit Bézier curvature functions",
//! CAD&A 2020 — seed 003), G1/G2 Hermite segments and splines.
//!
//! - [`IntrinsicSeg`]: a segment from its control curvatures (and weights), length, start
//!   point and angle; kurbo traits, exact subsegments, inflections and curvature extrema by
//!   Bernstein root isolation, cubic Béziers through [`crate::fit`].
//! - [`Hermite`] with a [`Profile`]: the segment meeting G1 data (unknowns `κ_0`, `κ_n`) or
//!   G2 data (unknowns `κ_1`, `κ_{n−1}`); degree 1 is the clothoid.
//! - [`IntrinsicSpline`]: a G2 curve through points from G2 Hermite segments.
//! - [`viable_region`]: which end curvatures admit a monotone G2 segment (seed 003 Fig. 4).
//! - `picture` (feature `render`): curves with combs, and the viable region.
//!
//! Curvatures use the crate's sign (positive for left turns), angles are radians
//! anticlockwise from +x in y-up coordinates.
//!
//! ```
//! use kappa::intrinsic::{Hermite, Profile};
//! use kurbo::{ParamCurve, Point};
//!
//! // A symmetric S-curve: both tangents 0.5 rad above the chord, zero net turning.
//! let h = Hermite::g1(Point::new(0.0, 0.0), 0.5, Point::new(2.0, 0.0), 0.5);
//! let seg = h.solve(&Profile::free(3))?;
//! assert!((seg.end() - Point::new(2.0, 0.0)).hypot() < 1e-12);
//! assert!(seg.turning().abs() < 1e-12);
//! let inflections = seg.inflections();
//! assert!(inflections.len() == 1 && (inflections[0] - 0.5).abs() < 1e-9);
//! # Ok::<(), kappa::Error>(())
//! ```

mod bernstein;
mod clothoid;
mod hermite;
#[cfg(feature = "render")]
pub mod picture;
mod quad;
mod roots;
mod segment;
mod spline;
mod viable;

pub use hermite::{
    Control, Hermite, HermiteEnd, Profile, Turning, END_TOLERANCE, HERMITE_ITERATIONS,
    NODES_PER_ITERATION,
};
pub use quad::PIECE_TURN;
pub use segment::{IntrinsicDeriv, IntrinsicDeriv2, IntrinsicSeg, MAX_TURNING};
pub use spline::{IntrinsicSpline, SplineOptions};
pub use viable::{viable_region, Viability, ViableRegion};
