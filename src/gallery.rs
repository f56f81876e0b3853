//! Figures of drawings: each curve of a [`Design`] solved with a scheme and drawn with its
//! input points and curvature comb; several schemes side by side (the εκ paper's Figs. 6, 8
//! and 9 show κ-curves beside εκ-curves with `a = 0.75, 0.85, 0.95`).

use kurbo::{BezPath, Point, Rect};

use crate::analysis::{curvature_comb, path_max_curvature};
use crate::fit::FitOptions;
use crate::render::{hstack, Pixmap, RenderError, Scene};
use crate::{Design, Error, Scheme, Shape, Solver};

/// The four variants of the paper's figures: κ, then εκ with `a = 0.75, 0.85, 0.95`.
pub const PAPER_VARIANTS: [(Scheme, f64); 4] = [
    (Scheme::Kappa, 2.0 / 3.0),
    (Scheme::EkCubic, 0.75),
    (Scheme::EkCubic, 0.85),
    (Scheme::EkCubic, 0.95),
];

/// Gap between the panels of [`paper_figure`], in pixels.
pub const FIGURE_GAP: u32 = 8;

/// Teeth of a curve's comb reach this fraction of that curve's size at its largest |κ|.
const COMB_FRACTION: f64 = 0.15;
/// Fitting tolerance for εκ-trig curves, relative to the curve's size.
const FIT_TOLERANCE: f64 = 1e-6;
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

/// The solved curves of a drawing as kurbo paths, with their input points.
pub fn solve_design(
    design: &Design,
    scheme: Scheme,
    a: f64,
) -> Result<Vec<(BezPath, Vec<Point>)>, GalleryError> {
    let mut solver = Solver::new();
    let mut out = Vec::with_capacity(design.curves.len());
    for (curve, c) in design.curves.iter().enumerate() {
        let pts = c.kurbo_points();
        let shape = match scheme {
            Scheme::Kappa => Shape::Neutral,
            Scheme::EkCubic | Scheme::EkTrig => Shape::Global(a),
        };
        let err = |source| GalleryError::Curve { curve, source };
        let spline = solver
            .solve(&pts, c.is_closed(), scheme, &shape)
            .map_err(err)?;
        // Trigonometric curves are fitted tightly, so that the combs drawn from the path
        // show the exact curve's curvature.
        let path = spline
            .fit(&FitOptions::relative(FIT_TOLERANCE))
            .map_err(err)?
            .path;
        out.push((path, pts));
    }
    Ok(out)
}

/// Comb scales (tooth length per unit |κ|), one per curve: the largest |κ| of each curve gets
/// a tooth of a fixed fraction (0.15) of that curve's size, so small contours (an eye) do not
/// flatten the comb of large ones.
pub fn comb_scales(curves: &[(BezPath, Vec<Point>)]) -> Vec<f64> {
    curves
        .iter()
        .map(|(path, _)| {
            let size = kurbo::Shape::bounding_box(path).size();
            let size = size.width.max(size.height).max(f64::MIN_POSITIVE);
            let kmax = path_max_curvature(path).value.min(COMB_KAPPA_CAP / size);
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

/// A `width × height` scene of solved curves (paths with their input points): curvature
/// combs, curves and points, in a view of the input points with a margin (y down). `combs`
/// are the tooth lengths per unit |κ|, one per curve (`None`: from these curves, see
/// [`comb_scales`]). This is how [`design_scene`] draws, for curves solved elsewhere (with
/// other options or per-point shapes).
pub fn curves_scene(
    curves: &[(BezPath, Vec<Point>)],
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
    let mut scene = Scene::new().with_size(width, height);
    if let Some(view) = view_box(curves.iter().flat_map(|(_, pts)| pts.iter().copied())) {
        scene = scene.with_view_box(view);
    }
    for ((path, _), &scale) in curves.iter().zip(scales) {
        scene = scene.comb(&curvature_comb(path, scale, COMB_SAMPLES));
    }
    for (path, pts) in curves {
        scene = scene.curve(path).input_points(pts);
    }
    scene
}

/// The view of a drawing: its points' bounding box with a margin of [`VIEW_MARGIN`] × its
/// larger side, the same for every scheme so that panels line up.
fn view_box(points: impl Iterator<Item = Point>) -> Option<Rect> {
    let bounds = points.fold(None, |acc: Option<Rect>, p| {
        Some(acc.map_or(Rect::from_points(p, p), |r| r.union_pt(p)))
    })?;
    let pad = VIEW_MARGIN * bounds.width().max(bounds.height());
    Some(bounds.inflate(pad, pad))
}

/// The panels of the paper-style figure as scenes: the drawing as a κ-curve and as εκ-curves
/// with `a = 0.75, 0.85, 0.95` ([`PAPER_VARIANTS`]), each `panel × panel` pixels, with the
/// comb scales of the κ panel in every panel so that their curvature can be compared.
pub fn paper_scenes(design: &Design, panel: u32) -> Result<Vec<Scene>, GalleryError> {
    let mut scales = Vec::new();
    let mut scenes = Vec::with_capacity(PAPER_VARIANTS.len());
    for (scheme, a) in PAPER_VARIANTS {
        // The first variant is the κ-curve, whose comb scales every panel uses.
        let curves = solve_design(design, scheme, a)?;
        if scales.is_empty() {
            scales = comb_scales(&curves);
        }
        scenes.push(curves_scene(&curves, panel, panel, Some(&scales)));
    }
    Ok(scenes)
}

/// The paper-style figure: the [`paper_scenes`] rendered side by side.
pub fn paper_figure(design: &Design, panel: u32) -> Result<Pixmap, GalleryError> {
    let scenes = paper_scenes(design, panel)?;
    let images = scenes
        .iter()
        .map(|s| s.render())
        .collect::<Result<Vec<_>, _>>()?;
    Ok(hstack(&images, FIGURE_GAP)?)
}
