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

/// Writes `scene` as SVG and/or PNG to the paths given (the `--svg` / `--png` options of the
/// subcommands).
pub fn write_pictures(
    scene: &Scene,
    svg: Option<&std::path::Path>,
    png: Option<&std::path::Path>,
) -> crate::failure::Result<()> {
    use crate::failure::{self, Failure};
    if let Some(path) = svg {
        let text = scene
            .to_svg()
            .map_err(|e| Failure::new(format!("cannot draw: {e}")))?;
        failure::write_file(path, text.as_bytes())?;
    }
    if let Some(path) = png {
        let bytes = scene
            .render_png()
            .map_err(|e| Failure::new(format!("cannot draw: {e}")))?;
        failure::write_file(path, &bytes)?;
    }
    Ok(())
}
