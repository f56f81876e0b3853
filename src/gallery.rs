//! Figures of drawings: each curve of a [`Design`] solved with a scheme and drawn with its
//! input points and curvature comb; several schemes side by side (the εκ paper's Figs. 6, 8
//! and 9 show κ-curves beside εκ-curves with `a = 0.75, 0.85, 0.95`).

use kurbo::{BezPath, Point, Rect, Shape as _};

use crate::render::{hstack, Pixmap, RenderError, Scene};
use crate::{Design, Error, Scheme, Shape, Solver, Spline};

/// The four variants of the paper's figures: κ, then εκ with `a = 0.75, 0.85, 0.95`.
pub const PAPER_VARIANTS: [(Scheme, f64); 4] = [
    (Scheme::Kappa, 2.0 / 3.0),
    (Scheme::EkCubic, 0.75),
    (Scheme::EkCubic, 0.85),
    (Scheme::EkCubic, 0.95),
];

/// The variants of the εκ paper's Fig. 11: κ, εκ-cubic with `a = 0.75, 0.9`, and εκ-trig
/// with `a = 0.55, 0.6, 0.75, 0.9`.
pub const TRIG_VARIANTS: [(Scheme, f64); 7] = [
    (Scheme::Kappa, 2.0 / 3.0),
    (Scheme::EkCubic, 0.75),
    (Scheme::EkCubic, 0.9),
    (Scheme::EkTrig, 0.55),
    (Scheme::EkTrig, 0.6),
    (Scheme::EkTrig, 0.75),
    (Scheme::EkTrig, 0.9),
];

/// Gap between the panels of [`paper_figure`], in pixels.
pub const FIGURE_GAP: u32 = 8;

/// Teeth of a curve's comb reach this fraction of that curve's size at its largest |κ|.
const COMB_FRACTION: f64 = 0.15;
/// Comb samples per segment.
const COMB_SAMPLES: usize = 16;
/// Margin around the input points, as a fraction of the drawing's larger side.
const VIEW_MARGIN: f64 = 0.1;
/// The largest |κ| used to scale the comb, relative to 1 / drawing size: keeps a near-cusp
/// from flattening every other tooth.
const COMB_KAPPA_CAP: f64 = 60.0;

/// Errors of figure making.
#[derive(Debug, thiserror::Error)]
pub enum GalleryError {
    /// A curve of the drawing could not be solved.
    #[error("curve {curve}: {source}")]
    Curve {
        /// Index of the curve in the drawing.
        curve: usize,
        /// The solver's error.
        source: Error,
    },
    /// Rendering failed.
    #[error(transparent)]
    Render(#[from] RenderError),
}

/// The solved curves of a drawing with their input points.
pub fn solve_design(
    design: &Design,
    scheme: Scheme,
    a: f64,
) -> Result<Vec<(Spline, Vec<Point>)>, GalleryError> {
    let mut solver = Solver::new();
    let mut out = Vec::with_capacity(design.curves.len());
    for (curve, c) in design.curves.iter().enumerate() {
        let pts = c.kurbo_points();
        let shape = match scheme {
            Scheme::Kappa => Shape::Neutral,
            Scheme::EkCubic | Scheme::EkTrig => Shape::Global(a),
        };
        let spline = solver
            .solve(&pts, c.is_closed(), scheme, &shape)
            .map_err(|source| GalleryError::Curve { curve, source })?;
        out.push((spline, pts));
    }
    Ok(out)
}

/// Comb scales (tooth length per unit |κ|), one per curve: the largest |κ| of each curve gets
/// a tooth of a fixed fraction (0.15) of that curve's size, so small contours (an eye) do not
/// flatten the comb of large ones.
pub fn comb_scales(curves: &[(Spline, Vec<Point>)]) -> Vec<f64> {
    curves
        .iter()
        .map(|(spline, _)| {
            let size = kurbo::Shape::bounding_box(&spline.to_bezpath()).size();
            let size = size.width.max(size.height).max(f64::MIN_POSITIVE);
            let kmax = spline.max_abs_curvature().min(COMB_KAPPA_CAP / size);
            if kmax > 0.0 && kmax.is_finite() {
                COMB_FRACTION * size / kmax
            } else {
                0.0
            }
        })
        .collect()
}

/// A scene of one drawing solved with one scheme: curves, combs and input points, in a
/// `width × height` pixel panel (y down, as the drawings are). `combs` are the tooth lengths
/// per unit |κ|, one per curve (`None`: from this solution, see [`comb_scales`]).
pub fn design_scene(
    design: &Design,
    scheme: Scheme,
    a: f64,
    width: u32,
    height: u32,
    combs: Option<&[f64]>,
) -> Result<Scene, GalleryError> {
    let curves = solve_design(design, scheme, a)?;
    Ok(curves_scene(&curves, width, height, combs))
}

/// A `width × height` scene of solved curves with their input points: curvature combs of the
/// exact curves, the curves (εκ-trig ones fitted within 1e-4 of their size) and the points,
/// in a view of the input points with a margin (y down), widened where a comb reaches past
/// it so that every tooth stays inside the image. `combs` are the tooth lengths per unit
/// |κ|, one per curve (`None`: from these curves, see [`comb_scales`]). This is how
/// [`design_scene`] draws, for curves solved elsewhere (with other options or per-point
/// shapes).
pub fn curves_scene(
    curves: &[(Spline, Vec<Point>)],
    width: u32,
    height: u32,
    combs: Option<&[f64]>,
) -> Scene {
    let own;
    let scales = match combs {
        Some(c) if c.len() == curves.len() => c,
        _ => {
            own = comb_scales(curves);
            &own[..]
        }
    };
    let drawn = Drawn::new(curves, scales);
    drawn.scene(drawn.view(), width, height)
}

/// The curves of one panel, with their combs, ready to draw in a view.
struct Drawn<'a> {
    curves: &'a [(Spline, Vec<Point>)],
    combs: Vec<BezPath>,
}

impl<'a> Drawn<'a> {
    fn new(curves: &'a [(Spline, Vec<Point>)], scales: &[f64]) -> Drawn<'a> {
        let combs = curves
            .iter()
            .zip(scales)
            .map(|((spline, _), &scale)| spline.curvature_comb(scale, COMB_SAMPLES))
            .collect();
        Drawn { curves, combs }
    }

    /// The input points' view ([`view_box`]) joined with the combs' bounds.
    fn view(&self) -> Option<Rect> {
        let points = view_box(self.curves.iter().flat_map(|(_, pts)| pts.iter().copied()))?;
        Some(
            self.combs
                .iter()
                .filter(|c| c.is_finite() && c.segments().next().is_some())
                .fold(points, |view, comb| view.union(comb.bounding_box())),
        )
    }

    fn scene(&self, view: Option<Rect>, width: u32, height: u32) -> Scene {
        let mut scene = Scene::new().with_size(width, height);
        if let Some(view) = view {
            scene = scene.with_view_box(view);
        }
        for comb in &self.combs {
            scene = scene.comb(comb);
        }
        for (spline, pts) in self.curves {
            scene = scene.curve(&spline.to_bezpath()).input_points(pts);
        }
        scene
    }
}

/// The view of a drawing: its points' bounding box with a margin of [`VIEW_MARGIN`] × its
/// larger side.
fn view_box(points: impl Iterator<Item = Point>) -> Option<Rect> {
    let bounds = points.fold(None, |acc: Option<Rect>, p| {
        Some(acc.map_or(Rect::from_points(p, p), |r| r.union_pt(p)))
    })?;
    let pad = VIEW_MARGIN * bounds.width().max(bounds.height());
    Some(bounds.inflate(pad, pad))
}

/// The title of a variant's panel: `κ-curve`, `εκ-cubic, a = 0.75` or `εκ-trig, a = 0.6`.
pub fn variant_title(scheme: Scheme, a: f64) -> String {
    match scheme {
        Scheme::Kappa => "κ-curve".to_owned(),
        Scheme::EkCubic => format!("εκ-cubic, a = {a}"),
        Scheme::EkTrig => format!("εκ-trig, a = {a}"),
    }
}

/// The panels of the paper-style figure as scenes: the drawing as a κ-curve and as εκ-curves
/// with `a = 0.75, 0.85, 0.95` ([`PAPER_VARIANTS`]), each `panel × panel` pixels, with the
/// comb scales of the κ panel in every panel so that their curvature can be compared.
pub fn paper_scenes(design: &Design, panel: u32) -> Result<Vec<Scene>, GalleryError> {
    variant_scenes(design, &PAPER_VARIANTS, panel)
}

/// The panels of a figure of `variants` (scheme and shape) as scenes, each `panel × panel`
/// pixels, with the comb scales of the first variant in every panel so that their curvature
/// can be compared. Each panel is titled with its variant ([`variant_title`]), and all are
/// drawn in one view that holds every panel's points and combs, so they line up and no comb
/// leaves its panel. [`PAPER_VARIANTS`] and [`TRIG_VARIANTS`] are the paper's.
pub fn variant_scenes(
    design: &Design,
    variants: &[(Scheme, f64)],
    panel: u32,
) -> Result<Vec<Scene>, GalleryError> {
    let solved = variants
        .iter()
        .map(|&(scheme, a)| solve_design(design, scheme, a))
        .collect::<Result<Vec<_>, _>>()?;
    // The first variant's comb scales are used in every panel.
    let scales = solved.first().map(|c| comb_scales(c)).unwrap_or_default();
    let drawn: Vec<Drawn> = solved.iter().map(|c| Drawn::new(c, &scales)).collect();
    // One view for every panel, so that they line up, wide enough for every comb.
    let view = drawn
        .iter()
        .filter_map(Drawn::view)
        .reduce(|a, b| a.union(b));
    Ok(drawn
        .iter()
        .zip(variants)
        .map(|(d, &(scheme, a))| {
            d.scene(view, panel, panel)
                .with_title(&variant_title(scheme, a))
        })
        .collect())
}

/// The paper-style figure: the [`paper_scenes`] rendered side by side.
pub fn paper_figure(design: &Design, panel: u32) -> Result<Pixmap, GalleryError> {
    variant_figure(design, &PAPER_VARIANTS, panel)
}

/// The [`variant_scenes`] of `variants` rendered side by side (for [`TRIG_VARIANTS`], the
/// paper's Fig. 11 layout in one row).
pub fn variant_figure(
    design: &Design,
    variants: &[(Scheme, f64)],
    panel: u32,
) -> Result<Pixmap, GalleryError> {
    let scenes = variant_scenes(design, variants, panel)?;
    let images = scenes
        .iter()
        .map(|s| s.render())
        .collect::<Result<Vec<_>, _>>()?;
    Ok(hstack(&images, FIGURE_GAP)?)
}
