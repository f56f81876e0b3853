//! Pictures of B-splines with their maximum curvature marked (feature `render`).

use kurbo::{BezPath, Point};

use super::BSpline;
use crate::analysis::curvature_comb;
use crate::render::{Color, PointStyle, Scene, Style};
use crate::space::{Projection, View};
use crate::Point3;

/// The longest comb tooth (at the maximum |κ|) is this fraction of the drawing size.
const COMB_FRACTION: f64 = 0.15;
/// Comb samples per segment.
const COMB_SAMPLES: usize = 24;
/// How the points of maximum curvature are marked: a large purple dot with a black rim, drawn
/// over everything else.
const MAX_MARK: PointStyle = PointStyle::new(6.0, Color::PURPLE).with_outline(Color::BLACK);

impl BSpline<Point> {
    /// A `width × height` picture in y-up coordinates (as the paper's figures): the dashed
    /// control polygon, the curvature comb, the curve, the interpolated points (red) and every
    /// point of maximum curvature (purple, outlined).
    ///
    /// The comb's longest tooth, at the maximum |κ|, is 15% of the drawing size; its teeth
    /// point away from the centre of curvature. A spline with an unbounded or zero maximum
    /// gets no comb.
    pub fn scene(&self, width: u32, height: u32) -> Scene {
        let path = self.to_bezpath();
        let max = self.max_curvature();
        let mut scene = Scene::new()
            .with_size(width, height)
            .with_y_down(false)
            .control_polygon(self.control_points(), self.closed);
        if max.value > 0.0 && max.value.is_finite() {
            let size = kurbo::Shape::bounding_box(&path).size();
            let scale = COMB_FRACTION * size.width.max(size.height) / max.value;
            scene = scene.comb(&curvature_comb(&path, scale, COMB_SAMPLES));
        }
        let marks: Vec<Point> = max.params.iter().map(|&t| self.eval(t)).collect();
        scene
            .curve(&path)
            .input_points(self.points())
            .points(&marks, MAX_MARK)
    }
}

impl BSpline<Point3> {
    /// A `width × height` picture of the spline in the orthographic projection along `view`
    /// (y up): the dashed control polygon, the curve, the interpolated points (red) and every
    /// point of maximum curvature (purple, outlined). The projected curve is exact (an
    /// orthographic projection is affine).
    pub fn scene(&self, view: View, width: u32, height: u32) -> Scene {
        let projection = Projection::Orthographic(view);
        let project = |p: Point3| projection.point(p).unwrap_or(Point::ZERO);
        let path: BezPath = self.to_bezpath_projected(project);
        let max = self.max_curvature();
        let control: Vec<Point> = self.control_points().iter().map(|&p| project(p)).collect();
        let points: Vec<Point> = self.points().iter().map(|&p| project(p)).collect();
        let marks: Vec<Point> = max.params.iter().map(|&t| project(self.eval(t))).collect();
        Scene::new()
            .with_size(width, height)
            .with_y_down(false)
            .control_polygon(&control, self.closed)
            .path(&path, Style::CURVE)
            .input_points(&points)
            .points(&marks, MAX_MARK)
    }
}
