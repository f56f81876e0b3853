//! Figures of drawings: each curve of a [`Design`] solved with a scheme and drawn with its
//! input points and curvature comb; several schemes side by side (the εκ paper's Figs. 6, 8
//! and 9 show κ-curves beside εκ-curves with `a = 0.75, 0.85, 0.95`).

use kurbo::{BezPath, Point, Rect};

use crate::analysis::{curvature_comb, path_max_curvature};
use crate::render::{hstack, Pixmap, RenderError, Scene};
use crate::{Design, Error, Scheme, Shape, Solver};

/// The four variants of the paper's figures: κ, then εκ with `a = 0.75, 0.85, 0.95`.
pub const PAPER_VARIANTS: [(Scheme, f64); 4] = [
    (Scheme::Kappa, 2.0 / 3.0),
    (Scheme::EkCubic, 0.75),
    (Scheme::EkCubic, 0.85),
    (Scheme::EkCubic, 0.95),
];

/// Teeth of the curvature comb reach this fraction of the drawing size at the largest |κ|.
const COMB_FRACTION: f64 = 0.06;
/// Comb samples per segment.
const COMB_SAMPLES: usize = 24;
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
            Scheme::EkCubic => Shape::Global(a),
        };
        let spline = solver
            .solve(&pts, c.is_closed(), scheme, &shape)
            .map_err(|source| GalleryError::Curve { curve, source })?;
        out.push((spline.to_bezpath(), pts));
    }
    Ok(out)
}

/// A scene of one drawing solved with one scheme: curves, combs and input points, in a
/// `width × height` pixel panel (y down, as the drawings are).
pub fn design_scene(
    design: &Design,
    scheme: Scheme,
    a: f64,
    width: u32,
    height: u32,
) -> Result<Scene, GalleryError> {
    let curves = solve_design(design, scheme, a)?;
    let size = design.size().max(f64::MIN_POSITIVE);
    let mut kmax: f64 = 0.0;
    for (path, _) in &curves {
        kmax = kmax.max(path_max_curvature(path).value);
    }
    let kmax = kmax.min(COMB_KAPPA_CAP / size);
    let scale = if kmax > 0.0 {
        COMB_FRACTION * size / kmax
    } else {
        0.0
    };
    let mut bounds: Option<Rect> = None;
    for (path, _) in &curves {
        let b = kurbo::Shape::bounding_box(path);
        bounds = Some(bounds.map_or(b, |r| r.union(b)));
    }
    let mut scene = Scene::new().with_size(width, height);
    if let Some(b) = bounds {
        let pad = COMB_FRACTION * size;
        scene = scene.with_view_box(b.inflate(pad, pad));
    }
    for (path, _) in &curves {
        scene = scene.comb(&curvature_comb(path, scale, COMB_SAMPLES));
    }
    for (path, pts) in &curves {
        scene = scene.curve(path).input_points(pts);
    }
    Ok(scene)
}

/// The paper-style figure: the drawing as a κ-curve and as εκ-curves with `a = 0.75, 0.85,
/// 0.95` side by side, each panel `panel × panel` pixels.
pub fn paper_figure(design: &Design, panel: u32) -> Result<Pixmap, GalleryError> {
    let mut images = Vec::with_capacity(PAPER_VARIANTS.len());
    for (scheme, a) in PAPER_VARIANTS {
        images.push(design_scene(design, scheme, a, panel, panel)?.render()?);
    }
    Ok(hstack(&images, 8)?)
}
