//! Pictures of intrinsic curves: the curve (fitted cubics), a curvature comb from the exact
//! curvature, inflection points in red and curvature extrema in blue (the marks of seed 003's
//! figures), and the data points.

use kurbo::{BezPath, ParamCurve, Point, Rect};

use super::IntrinsicSeg;
use crate::fit::{fit, FitOptions};
use crate::render::{Color, PointStyle, Scene};
use crate::Error;

/// Teeth of the comb reach this fraction of the drawing's larger side at the largest |κ|.
const COMB_FRACTION: f64 = 0.2;
/// Comb teeth per curve (spread over its segments).
const COMB_TEETH: usize = 96;
/// Comb teeth per segment at least.
const MIN_TEETH: usize = 12;
/// Relative tolerance of the fitted curve in pictures (far below a pixel).
const PICTURE_TOLERANCE: f64 = 1e-5;

/// A `width × height` scene (y up) of one curve: segments joined end to end, with their
/// curvature comb, inflection points (red), curvature extrema (blue) and `points` (black).
///
/// # Errors
///
/// Those of [`crate::fit::fit`] for segments that cannot be fitted.
pub fn scene(
    segments: &[IntrinsicSeg],
    points: &[Point],
    width: u32,
    height: u32,
) -> Result<Scene, Error> {
    curves_scene(&[segments], points, width, height)
}

/// A `width × height` scene (y up) of several curves, each a slice of segments joined end to
/// end, drawn as [`scene`] draws one; each curve's comb has its own scale.
///
/// # Errors
///
/// Those of [`crate::fit::fit`] for segments that cannot be fitted.
pub fn curves_scene(
    curves: &[&[IntrinsicSeg]],
    points: &[Point],
    width: u32,
    height: u32,
) -> Result<Scene, Error> {
    let mut scene = Scene::new().with_size(width, height).with_y_down(false);
    let mut inflections = Vec::new();
    let mut extrema = Vec::new();
    let mut paths = Vec::new();
    for segments in curves.iter().filter(|s| !s.is_empty()) {
        let fitted = fit(segments, false, &FitOptions::relative(PICTURE_TOLERANCE))?;
        let size = bounds(&fitted.path).map_or(1.0, |r| r.width().max(r.height()));
        let kmax = segments
            .iter()
            .map(IntrinsicSeg::max_abs_curvature)
            .fold(0.0, f64::max);
        let scale = if kmax > 0.0 {
            COMB_FRACTION * size / kmax
        } else {
            0.0
        };
        let teeth = (COMB_TEETH / segments.len()).max(MIN_TEETH);
        let mut comb = BezPath::new();
        for seg in segments.iter() {
            comb.extend(seg.curvature_comb(scale, teeth));
            inflections.extend(seg.inflections().into_iter().map(|t| seg.eval(t)));
            extrema.extend(seg.curvature_extrema().into_iter().map(|t| seg.eval(t)));
        }
        scene = scene.comb(&comb);
        paths.push(fitted.path);
    }
    for path in &paths {
        scene = scene.curve(path);
    }
    Ok(scene
        .points(points, PointStyle::new(3.5, Color::BLACK))
        .points(&extrema, PointStyle::new(4.0, Color::BLUE))
        .points(&inflections, PointStyle::new(4.0, Color::RED)))
}

fn bounds(path: &BezPath) -> Option<Rect> {
    use kurbo::ParamCurveExtrema;
    path.segments()
        .map(|s| s.bounding_box())
        .reduce(|a, b| a.union(b))
}
