//! kappa: curves whose curvature is under the designer's control.
//!
//! A κ-curve passes through the points you give it, and its curvature peaks exactly at
//! those points; an εκ-curve adds a shape parameter `a` per point that sharpens or softens
//! each peak. kappa computes both, converging to 1e-12 of the drawing size where the
//! published local/global loop oscillates, and hands the result to the
//! [kurbo](https://docs.rs/kurbo) ecosystem as exact Bézier paths.
//!
//! ```
//! use kappa::{Scheme, Shape, Solver, Spline};
//! use kurbo::{ParamCurve, Point};
//!
//! let points = [
//!     Point::new(0.0, 0.0),
//!     Point::new(100.0, 10.0),
//!     Point::new(120.0, 90.0),
//!     Point::new(20.0, 110.0),
//! ];
//! // A closed κ-curve: one quadratic segment per point, peaking at the point.
//! let kappa = Spline::kappa(&points, true)?;
//! for (seg, p) in kappa.segments().iter().zip(&points) {
//!     assert!((seg.eval(seg.t_max) - *p).hypot() < 1e-9);
//! }
//! // A sharper εκ-curve (cubic segments), as an exact kurbo path.
//! let sharp = Spline::ek_cubic(&points, true, 0.9)?;
//! let path: kurbo::BezPath = sharp.to_bezpath();
//! assert_eq!(path.segments().count(), 4);
//!
//! // Interactive editing: keep the solver and re-solve after a point moves.
//! let mut solver = Solver::new();
//! solver.solve(&points, true, Scheme::EkCubic, &Shape::Global(0.8))?;
//! let mut moved = points;
//! moved[1].x += 2.0;
//! let again = solver.resolve(&moved)?;
//! assert!(again.converged());
//! # Ok::<(), kappa::Error>(())
//! ```
//!
//! # Curvature sign
//!
//! Signed curvature in this crate is the papers' `κ = (x′y″ − y′x″) / |r′|³`: **positive for
//! left (counter-clockwise in y-up) turns**. kurbo's `ParamCurveCurvature::curvature` has the
//! opposite sign; use [`analysis::CurvatureAnalysis`] for ours. In pixel coordinates (y
//! down) a left turn in the y-up sense looks like a clockwise turn on screen.
//!
//! # What is where
//!
//! - [`Spline`], [`Solver`]: κ-curves ([`Scheme::Kappa`]), cubic εκ-curves
//!   ([`Scheme::EkCubic`]) and trigonometric εκ-curves ([`Scheme::EkTrig`]), open and closed;
//!   [`Solver3`] for 3D points.
//! - [`TrigBez`] ([`trig`]): curves of the generalized trigonometric basis of any degree.
//! - [`BSpline`], [`BSpline3`]: uniform cubic B-splines through given points, open (relaxed)
//!   and closed (periodic), with their exact maximum curvature.
//! - [`analysis`]: curvature of Bézier segments of degree 1–4 in 2D and 3D, curvature
//!   extrema, maxima of paths, continuity at joints, curvature combs.
//! - [`space`]: κ-space curves, G2 in 3D ([`SpaceCurve`]): the 3D κ-curve with a quartic at
//!   every joint, projections to 2D, JSON and OBJ export, pictures from several views.
//! - [`editor`]: the engine of a curvature-pen path tool (edits, corners, undo/redo, hit
//!   testing, warm re-solves).
//! - [`fit`]: cubic Bézier paths for curves that are not polynomial, within a measured
//!   tolerance.
//! - [`intrinsic`]: curves whose curvature is an explicit (rational) Bézier function of arc
//!   length — G1/G2 Hermite segments (degree 1: clothoids), inflection and monotonicity
//!   checks, G2 splines through points, viable regions.
//! - `render` (feature `render`): deterministic SVG/PNG pictures and golden-image comparison.
//! - `gallery` (features `render` + `serde`): the paper-style figures.
//! - [`glyph`]: glyph outlines drafted as κ/εκ contours; TrueType quadratics and SVG out;
//!   font import, UFO and compiled fonts (feature `font`); lyon meshes (feature `tessellate`).
//! - [`BUILTIN_DESIGNS`]: the drawings of the εκ-curve paper, compiled in.
//!
//! # Method
//!
//! The solver treats the middle control point, joint ratio and peak parameter of every
//! segment as unknowns of one nonlinear system (interpolation, G2 at the joints, curvature
//! peak) and solves it by Newton's method with a line search, started by a few iterations of
//! the classic local/global loop; each step is `O(n)` (banded, with a small border for closed
//! curves). When that fails, continuation in the shape parameter from a value where the
//! system is easy takes over. Every solve is capped and reports its iterations and whether it
//! converged; non-convergence is an [`Error::NotConverged`], never a silent result.
//!
//! # Resource bounds
//!
//! Every solve finishes in `O(n · max_iterations)` time and `O(n)` memory for `n` points:
//! each iteration (a classic local/global step or a Newton step with its line search) is
//! `O(n)` with bounded inner loops (at most [`SolveOptions::max_iterations`] iterations over
//! all attempts of a cold solve — the classic starts and every continuation step count; the
//! root solves for `t` and the line search have fixed caps), and a warm re-solve spends at
//! most 100 of the iterations before the cold cascade takes the rest. An input the solver
//! cannot handle ends in [`Error::NotConverged`] with the iterations spent, never in an
//! endless loop. The other schemes need no iteration cap of this kind: B-spline
//! interpolation is a direct `O(n)` solve and its maximum curvature `O(n)` polynomial root
//! finding; κ-space curves add `O(n)` replacements to a capped κ solve; a Hermite solve
//! takes at most 40 Newton iterations per homotopy step and gives up when the step falls
//! below 1/4096. The `kappa` tool bounds its input size (`--max-points`, checked while the
//! JSON is read; see `input`, feature `serde`).
//!
//! # Feature flags
//!
//! - `parallel` (default): long curves (2 048 points or more) solved on two threads, and
//!   batches of curves spread over rayon's pool; the results are the same without it.
//! - `render`: [`render`] (resvg, tiny-skia).
//! - `serde`: JSON drawings ([`Design`]).
//! - `font`: glyph import (ttf-parser), UFO export (norad), compiled fonts (write-fonts).
//! - `tessellate`: fill and stroke meshes (lyon).
//! - `cli`: the `kappa` command-line tool (implies `render`, `serde` and `font`).
//!
//! A plain library build depends on kurbo, polycool and thiserror only.
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod analysis;
mod basis;
mod batch;
mod bspline;
#[cfg(feature = "serde")]
mod design;
mod designs;
pub mod editor;
mod error;
pub mod fit;
#[cfg(all(feature = "render", feature = "serde"))]
pub mod gallery;
pub mod glyph;
#[cfg(feature = "serde")]
pub mod input;
pub mod intrinsic;
mod linalg;
#[cfg(any(feature = "font", feature = "render"))]
mod outline;
mod parallel;
mod point3;
#[cfg(feature = "render")]
pub mod render;
mod solved;
mod solver;
pub mod space;
mod spline;
pub mod trig;

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

/// The examples of the guide pages in `docs/`, compiled and run as doctests.
#[cfg(doctest)]
mod guide_doctests {
    #[doc = include_str!("../docs/curves.md")]
    struct Curves;
    #[cfg(feature = "font")]
    #[doc = include_str!("../docs/glyphs.md")]
    struct Glyphs;
    #[doc = include_str!("../docs/space-curves.md")]
    struct SpaceCurves;
    #[doc = include_str!("../docs/bsplines.md")]
    struct BSplines;
    #[doc = include_str!("../docs/intrinsic.md")]
    struct Intrinsic;
    #[doc = include_str!("../docs/cli.md")]
    struct Cli;
    #[doc = include_str!("../docs/hostile-input.md")]
    struct HostileInput;
    #[doc = include_str!("../docs/performance.md")]
    struct Performance;
    #[doc = include_str!("../docs/golden-images.md")]
    struct GoldenImages;
}

pub use basis::Extremum;
pub use batch::{BatchCurve, BatchSolver, BatchSolver3, BatchSolverN, MIN_PARALLEL_SEGMENTS};
pub use bspline::{BSpline, BSpline3, BSplineCurvatureMax, BSplinePathElements, BSplinePoint};
#[cfg(feature = "serde")]
pub use design::{Design, DesignCurve};
pub use designs::{builtin_design, BUILTIN_DESIGNS};
pub use error::Error;
pub use point3::{Point3, Vec3};
pub use solved::SolvedState;
pub use space::{SpaceCurve, SpaceOptions};
pub use spline::{
    svg_path_data, Coords, Scheme, Segment, Shape, SolveOptions, SolveReport, Solver, Solver3,
    SolverN, Spline, Spline3, EK_TRIG_DEFAULT_SHAPE, TRIG_NODE_CUBICS,
};
pub use trig::TrigBez;
