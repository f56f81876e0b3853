//! Pictures of space curves: the curve seen from the top, the front, the side and
//! isometrically, with its 3D curvature comb.

use kurbo::{BezPath, Point};

use crate::analysis::CurvatureAnalysis;
use crate::fit::FitOptions;
use crate::render::{hstack, Color, Pixmap, PointStyle, RenderError, Scene, Style};
use crate::Error;

use super::{Projection, SpaceCurve, View};

/// The four standard views, with their names: top (plan), front, side and isometric.
pub const VIEWS: [(&str, View); 4] = [
    ("top", View::TOP),
    ("front", View::FRONT),
    ("side", View::SIDE),
    ("isometric", View::ISOMETRIC),
];

/// The longest comb tooth, as a fraction of the curve's size.
const COMB_FRACTION: f64 = 0.15;
/// The largest |κ| used to scale the comb, relative to 1 / size (a near-cusp must not flatten
/// every other tooth).
const COMB_KAPPA_CAP: f64 = 60.0;
/// Comb teeth per κ-segment.
const COMB_SAMPLES: usize = 16;
/// The most teeth on one segment.
const COMB_MAX_SAMPLES: usize = 1024;
/// Fitting tolerance of the projected quartics, relative to the picture's size (far below a
/// pixel).
const PICTURE_TOLERANCE: f64 = 1e-4;
/// The replacement quartics are drawn over the curve in this style, so that the joints show.
const QUARTIC_STYLE: Style = Style::new(Color::ORANGE, 3.0);
/// Gap between the panels of [`views_figure`], in pixels.
const PANEL_GAP: u32 = 8;

/// Errors of [`views_figure`].
#[derive(Debug, thiserror::Error)]
pub enum FigureError {
    /// The curve could not be projected.
    #[error(transparent)]
    Curve(#[from] Error),
    /// Rendering failed.
    #[error(transparent)]
    Render(#[from] RenderError),
}

impl SpaceCurve {
    /// The comb scale of [`views_scene`]: tooth length per unit κ such that the largest κ
    /// (capped at 60 / size) gets a tooth of 0.15 × the size of the curve (the larger side
    /// of its control points' bounding box); 0 for a straight curve.
    pub fn comb_scale(&self) -> f64 {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for s in self.segments() {
            for p in s.control_points() {
                for (k, v) in [p.x, p.y, p.z].into_iter().enumerate() {
                    lo[k] = lo[k].min(v);
                    hi[k] = hi[k].max(v);
                }
            }
        }
        let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        if !(size > 0.0 && size.is_finite()) {
            return 0.0;
        }
        let kmax = self.max_curvature().value.min(COMB_KAPPA_CAP / size);
        if kmax > 0.0 {
            COMB_FRACTION * size / kmax
        } else {
            0.0
        }
    }

    /// The 3D curvature comb seen through `projection`: teeth from curve points `p` to
    /// `p − scale · k` (`k` the curvature vector, so teeth point away from the centre of
    /// curvature), projected, with the outline through the tips; the same layout as
    /// [`crate::analysis::curvature_comb`]. The curve gets 16 teeth per
    /// κ-segment, shared out by arc length (uniform in `t` within a segment, both ends of
    /// every segment included, so a short quartic gets just its two ends). Teeth that do not
    /// project (behind a perspective eye) are left out.
    pub fn comb(&self, projection: &Projection, scale: f64) -> BezPath {
        let lengths: Vec<f64> = self
            .segments()
            .iter()
            .map(|s| {
                s.control_points()
                    .windows(2)
                    .map(|w| w[0].distance(w[1]))
                    .sum()
            })
            .collect();
        let total: f64 = lengths.iter().sum();
        let teeth_total = (COMB_SAMPLES * self.spline().segments().len()) as f64;
        let mut teeth: Vec<(Point, Point)> = Vec::new();
        for (s, len) in self.segments().iter().zip(&lengths) {
            let share = if total > 0.0 { len / total } else { 0.0 };
            let count = ((teeth_total * share).ceil() as usize).clamp(2, COMB_MAX_SAMPLES);
            for j in 0..count {
                let t = j as f64 / (count - 1) as f64;
                let p = s.eval(t);
                let tip = p - s.curvature_vector(t) * scale;
                if let (Some(a), Some(b)) = (projection.point(p), projection.point(tip)) {
                    if a.is_finite() && b.is_finite() {
                        teeth.push((a, b));
                    }
                }
            }
        }
        let mut out = BezPath::new();
        for (j, &(base, tip)) in teeth.iter().enumerate() {
            out.move_to(base);
            out.line_to(tip);
            if let Some(&(_, next)) = teeth.get(j + 1) {
                out.line_to(next);
            }
        }
        out
    }
}

/// One view of a space curve, `width × height` pixels: the orthographic projection of the
/// curve with its 3D curvature comb ([`SpaceCurve::comb`] with `comb_scale`, or
/// [`SpaceCurve::comb_scale`] if `None`), the replacement quartics in orange and the input
/// points in red; y up, the view fitted to the content.
///
/// # Errors
///
/// The errors of [`SpaceCurve::project`].
pub fn views_scene(
    curve: &SpaceCurve,
    view: View,
    width: u32,
    height: u32,
    comb_scale: Option<f64>,
) -> Result<Scene, Error> {
    let projection = Projection::Orthographic(view);
    let options = FitOptions::relative(PICTURE_TOLERANCE);
    let path = curve.project(&projection, &options)?.path;
    let scale = comb_scale.unwrap_or_else(|| curve.comb_scale());
    let mut scene = Scene::new()
        .with_size(width, height)
        .with_y_down(false)
        .comb(&curve.comb(&projection, scale))
        .curve(&path);
    let mut quartics = BezPath::new();
    for s in curve.segments().iter().filter(|s| s.degree() == 4) {
        let ends = [
            s.eval(0.0),
            s.eval(0.25),
            s.eval(0.5),
            s.eval(0.75),
            s.eval(1.0),
        ];
        for (k, p) in ends.iter().filter_map(|&p| projection.point(p)).enumerate() {
            if k == 0 {
                quartics.move_to(p);
            } else {
                quartics.line_to(p);
            }
        }
    }
    scene = scene.path(&quartics, QUARTIC_STYLE);
    let mut points: Vec<Point> = curve
        .peak_points()
        .into_iter()
        .filter_map(|p| projection.point(p))
        .collect();
    if !curve.is_closed() {
        let (a, b) = curve.ends();
        points.extend(projection.point(a));
        points.extend(projection.point(b));
    }
    Ok(scene.points(&points, PointStyle::INPUT))
}

/// The four [`VIEWS`] of a space curve side by side, each `panel × panel` pixels and titled
/// with its view's name, with one comb scale for all.
///
/// # Errors
///
/// The errors of [`views_scene`] and of rendering.
pub fn views_figure(curve: &SpaceCurve, panel: u32) -> Result<Pixmap, FigureError> {
    let scale = curve.comb_scale();
    let mut images = Vec::with_capacity(VIEWS.len());
    for (name, view) in VIEWS {
        let scene = views_scene(curve, view, panel, panel, Some(scale))?.with_title(name);
        images.push(scene.render()?);
    }
    Ok(hstack(&images, PANEL_GAP)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Point3, SpaceOptions};

    #[test]
    fn figure_comb_teeth_have_curvature_length() {
        let pts: Vec<Point3> = (0..6)
            .map(|i| {
                let th = 0.8 * i as f64;
                Point3::new(10.0 * th.cos(), 10.0 * th.sin(), 3.0 * th)
            })
            .collect();
        let curve = SpaceCurve::new(&pts, false, &SpaceOptions::default()).unwrap();
        // Seen from the top the comb of a helix lies in the xy plane except for z parts of k.
        let scale = 2.0;
        let comb = curve.comb(&Projection::Orthographic(View::TOP), scale);
        let teeth = comb
            .elements()
            .iter()
            .filter(|e| matches!(e, kurbo::PathEl::MoveTo(_)))
            .count();
        // About COMB_SAMPLES per κ-segment, at least the two ends of every segment.
        let kappa_segments = curve.spline().segments().len();
        assert!(teeth >= 2 * curve.segments().len(), "{teeth}");
        assert!(teeth <= (COMB_SAMPLES + 1) * kappa_segments + 2 * curve.segments().len());
        // Isometric view of the first tooth: its projected length is at most scale · κ.
        let s = &curve.segments()[0];
        let k = CurvatureAnalysis::curvature(s, 0.0);
        let comb = curve.comb(&Projection::Orthographic(View::ISOMETRIC), scale);
        let mut it = comb.elements().iter();
        let (Some(kurbo::PathEl::MoveTo(a)), Some(kurbo::PathEl::LineTo(b))) =
            (it.next(), it.next())
        else {
            panic!("comb starts with a tooth");
        };
        assert!((*b - *a).hypot() <= scale * k * (1.0 + 1e-12));
        assert!(curve.comb_scale() > 0.0);
    }

    #[test]
    fn figure_renders_four_panels() {
        let pts = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(10.0, 0.0, 3.0),
            Point3::new(10.0, 10.0, 0.0),
            Point3::new(0.0, 10.0, 3.0),
        ];
        let curve = SpaceCurve::new(&pts, true, &SpaceOptions::default()).unwrap();
        let image = views_figure(&curve, 64).unwrap();
        assert_eq!(image.width(), 4 * 64 + 3 * PANEL_GAP);
        assert_eq!(image.height(), 64);
    }
}
