//! κ-curves and εκ-curves (cubic and trigonometric): the public front of the solver.
//!
//! The parts: the families and shapes ([`scheme`]); a curve ([`curve`]) and its segments
//! ([`segment`]) and its node path for font masters ([`nodes`]); the solver ([`solver`]) with its [`options`], its [`checks`] of the input
//! and the [`frame`] it works in.

mod checks;
mod curve;
mod frame;
mod nodes;
mod options;
mod scheme;
mod segment;
mod solver;

pub(crate) use curve::path_seg_derivs;
pub use curve::{svg_path_data, Spline, Spline3};
pub use frame::Coords;
pub use nodes::TRIG_NODE_CUBICS;
pub use options::{SolveOptions, SolveReport};
pub use scheme::{Scheme, Shape, EK_TRIG_DEFAULT_SHAPE};
pub use segment::Segment;
pub use solver::{Solver, Solver3, SolverN};
