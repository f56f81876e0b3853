//! Pictures of solved curves: the curves, their input points and curvature combs, drawn as
//! `kappa::gallery::design_scene` draws a drawing.
//!
//! `design_scene` solves the drawing itself with default options and one global shape; here
//! the curves are already solved (with the user's options and per-point shapes), so the scene
//! is built from them directly, with the gallery's comb scales ([`comb_scales`]) and the same
//! view box and comb sampling.

use kappa::analysis::curvature_comb;
use kappa::gallery::comb_scales;
use kappa::render::Scene;
use kappa::Spline;
use kurbo::{BezPath, Point, Rect};

/// Comb samples per segment (as in `kappa::gallery`).
const COMB_SAMPLES: usize = 16;
/// Margin around the input points, as a fraction of the drawing size (as in
/// `kappa::gallery`).
const VIEW_MARGIN: f64 = 0.1;

/// A `width × height` scene of solved curves with their input points and combs.
pub fn scene(curves: &[(Spline, Vec<Point>)], width: u32, height: u32) -> Scene {
    let paths: Vec<(BezPath, Vec<Point>)> = curves
        .iter()
        .map(|(s, pts)| (s.to_bezpath(), pts.clone()))
        .collect();
    let scales = comb_scales(&paths);
    let mut scene = Scene::new().with_size(width, height);
    if let Some(view) = view_box(curves.iter().flat_map(|(_, pts)| pts.iter().copied())) {
        scene = scene.with_view_box(view);
    }
    for ((path, _), &scale) in paths.iter().zip(&scales) {
        scene = scene.comb(&curvature_comb(path, scale, COMB_SAMPLES));
    }
    for (path, pts) in &paths {
        scene = scene.curve(path).input_points(pts);
    }
    scene
}

/// The bounding box of `points` with a margin of [`VIEW_MARGIN`] × its larger side.
fn view_box(points: impl Iterator<Item = Point>) -> Option<Rect> {
    let bounds = points.fold(None, |acc: Option<Rect>, p| {
        Some(acc.map_or(Rect::from_points(p, p), |r| r.union_pt(p)))
    })?;
    let pad = VIEW_MARGIN * bounds.width().max(bounds.height());
    Some(bounds.inflate(pad, pad))
}
