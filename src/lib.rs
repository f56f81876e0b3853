//! kappa: curves whose curvature is under the designer's control.
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod analysis;
mod error;
mod point3;
#[cfg(feature = "render")]
pub mod render;

pub use error::Error;
pub use point3::{Point3, Vec3};
mod basis;
mod linalg;
mod solver;
mod spline;

pub use spline::{
    Coords, Scheme, Segment, Shape, SolveOptions, SolveReport, Solver, Solver3, SolverN, Spline,
    Spline3,
};
#[cfg(feature = "serde")]
mod design;
#[cfg(feature = "serde")]
pub use design::{Design, DesignCurve};
mod designs;
pub use designs::{builtin_design, BUILTIN_DESIGNS};
#[cfg(all(feature = "render", feature = "serde"))]
pub mod gallery;
