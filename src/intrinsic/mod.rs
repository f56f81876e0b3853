//! Curves defined by their curvature: explicit (rational) Bézier curvature functions of arc
//! length (seed 003), G1/G2 Hermite segments and splines.

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

pub use hermite::{Control, Hermite, HermiteEnd, Profile, Turning, END_TOLERANCE};
pub use quad::PIECE_TURN;
pub use segment::{IntrinsicDeriv, IntrinsicDeriv2, IntrinsicSeg, MAX_TURNING};
pub use spline::{IntrinsicSpline, SplineOptions};
pub use viable::{viable_region, Viability, ViableRegion};
