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
