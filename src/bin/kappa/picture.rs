//! Pictures of solved curves: the curves, their input points and curvature combs, drawn as
//! `kappa::gallery::design_scene` draws a drawing (through `gallery::curves_scene`, because
//! here the curves are already solved with the user's options and shapes).

use kappa::gallery::curves_scene;
use kappa::render::Scene;
use kappa::Spline;
use kurbo::Point;

/// A `width × height` scene of solved curves with their input points and combs.
pub fn scene(curves: &[(Spline, Vec<Point>)], width: u32, height: u32) -> Scene {
    curves_scene(curves, width, height, None)
}
