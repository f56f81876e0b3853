//! Pictures of intrinsic curves: the curve (fitted cubics), a curvature comb from the exact
//! curvature, inflection points in red and curvature extrema in blue (the marks of seed 003's
//! figures), and the data points.

use kurbo::{BezPath, ParamCurve, Point, Rect};

use super::{viable_region, Control, Hermite, IntrinsicSeg, Profile};
use crate::fit::{fit, FitOptions};
use crate::render::{hstack, Color, Pixmap, PointStyle, RenderError, Scene};
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

/// Colour of [`Viability::Monotone`](super::Viability::Monotone) cells.
pub const MONOTONE_COLOR: Color = Color::rgb(31, 119, 180);
/// Colour of [`Viability::Solved`](super::Viability::Solved) cells.
pub const SOLVED_COLOR: Color = Color::rgb(210, 210, 210);

/// A `side × side` scene of a sampled viable region in the `(κ_s, κ_e)` plane (seed 003
/// Fig. 4), each axis scaled to the square: monotone cells blue, other solved cells light
/// grey, no solution white, the axes `κ_s = 0` and `κ_e = 0` in grey where they are in range,
/// a frame, and the clothoid's end curvatures `clothoid` (if given) as a red dot.
pub fn viable_scene(
    region: &super::ViableRegion,
    clothoid: Option<(f64, f64)>,
    side: u32,
) -> Scene {
    use crate::render::Style;
    let (ks, ke) = (&region.k_start, &region.k_end);
    let (nx, ny) = (ks.len() as f64, ke.len() as f64);
    // Cell (i, j) is the unit square's [i/nx, (i+1)/nx] × [j/ny, (j+1)/ny].
    let (x0, dx) = (ks[0], (ks[ks.len() - 1] - ks[0]) / (nx - 1.0));
    let (y0, dy) = (ke[0], (ke[ke.len() - 1] - ke[0]) / (ny - 1.0));
    let to_unit =
        |k0: f64, k1: f64| Point::new(((k0 - x0) / dx + 0.5) / nx, ((k1 - y0) / dy + 0.5) / ny);
    let mut monotone = BezPath::new();
    let mut solved = BezPath::new();
    for j in 0..ke.len() {
        for i in 0..ks.len() {
            let target = match region.at(i, j) {
                super::Viability::Monotone => &mut monotone,
                super::Viability::Solved => &mut solved,
                super::Viability::NoSolution => continue,
            };
            let (a, b) = (i as f64 / nx, j as f64 / ny);
            let (c, d) = ((i + 1) as f64 / nx, (j + 1) as f64 / ny);
            target.move_to((a, b));
            target.line_to((c, b));
            target.line_to((c, d));
            target.line_to((a, d));
            target.close_path();
        }
    }
    let mut axes = BezPath::new();
    let origin = to_unit(0.0, 0.0);
    if origin.x > 0.0 && origin.x < 1.0 {
        axes.move_to((origin.x, 0.0));
        axes.line_to((origin.x, 1.0));
    }
    if origin.y > 0.0 && origin.y < 1.0 {
        axes.move_to((0.0, origin.y));
        axes.line_to((1.0, origin.y));
    }
    let corners = [
        Point::new(0.0, 0.0),
        Point::new(1.0, 0.0),
        Point::new(1.0, 1.0),
        Point::new(0.0, 1.0),
    ];
    let mut scene = Scene::new()
        .with_size(side, side)
        .with_y_down(false)
        .with_view_box(Rect::new(0.0, 0.0, 1.0, 1.0))
        .path(&solved, Style::filled(SOLVED_COLOR))
        .path(&monotone, Style::filled(MONOTONE_COLOR))
        .path(&axes, Style::new(Color::GRAY, 1.0))
        .polygon(&corners, true, Style::new(Color::BLACK, 1.0));
    if let Some((a, b)) = clothoid {
        scene = scene.points(&[to_unit(a, b)], PointStyle::new(4.0, Color::RED));
    }
    scene
}

/// Size in pixels per em of the axis labels of [`viable_figure`].
const AXIS_LABEL_SIZE: f64 = 11.0;

/// Labels the axes of a [`viable_scene`] (titled or not): the range ends of `κ_s` under the
/// frame's bottom corners and of `κ_e` left of its left corners, and the two axis names.
/// The scene's view must be the unit square it draws the region in; it keeps the default
/// margin, which leaves room for one line of labels on each side.
pub fn with_viable_axes(scene: Scene, region: &super::ViableRegion) -> Result<Scene, RenderError> {
    use crate::render::TextAlign;
    let to_pixels = scene.view_transform()?;
    let (ks, ke) = (&region.k_start, &region.k_end);
    let (Some(&s0), Some(&s1), Some(&e0), Some(&e1)) =
        (ks.first(), ks.last(), ke.first(), ke.last())
    else {
        return Ok(scene);
    };
    let size = AXIS_LABEL_SIZE;
    let below = |u: f64| to_pixels * Point::new(u, 0.0) + kurbo::Vec2::new(0.0, size + 2.0);
    let left = |v: f64| to_pixels * Point::new(0.0, v) + kurbo::Vec2::new(-3.0, 0.35 * size);
    let label = |scene: Scene, text: &str, at: Point, align: TextAlign| {
        scene.label(text, at, size, align, Color::BLACK)
    };
    let scene = label(scene, &number(s0), below(0.0), TextAlign::Start);
    let scene = label(scene, "κs", below(0.5), TextAlign::Middle);
    let scene = label(scene, &number(s1), below(1.0), TextAlign::End);
    let scene = label(scene, &number(e0), left(0.0), TextAlign::End);
    let scene = label(scene, "κe", left(0.5), TextAlign::End);
    Ok(label(scene, &number(e1), left(1.0), TextAlign::End))
}

/// A range end as a label: at most three decimals, with a real minus sign.
fn number(x: f64) -> String {
    let rounded = (x * 1000.0).round() / 1000.0 + 0.0;
    format!("{rounded}").replace('-', "−")
}

/// Errors of figure making.
#[derive(Debug, thiserror::Error)]
pub enum FigureError {
    /// A curve could not be solved or fitted.
    #[error(transparent)]
    Curve(#[from] Error),
    /// Rendering failed.
    #[error(transparent)]
    Render(#[from] RenderError),
}

/// Gap between the panels of the figures, in pixels.
pub const FIGURE_GAP: u32 = 6;

/// The G1 data of [`variety_figure`]: from (0, 0) at 0.2 rad to (10, 0) at −1.3 rad.
pub fn variety_data() -> Hermite {
    Hermite::g1(Point::ZERO, 0.2, Point::new(10.0, 0.0), -1.3)
}

/// The profiles of [`variety_figure`] with their names (seed 003 Fig. 2 (a), (c)–(g)): the
/// clothoid; cubics with `κ₀ = κ₁ = κ₂` and `κ₁ = κ₂ = κ₃`; quintics with the first or the
/// last five control curvatures equal; a cubic with `κ₀ = κ₁`, `κ₂ = κ₃` (`dκ/ds = 0` at both
/// ends).
pub fn variety_profiles() -> Vec<(&'static str, Profile)> {
    let (free, same) = (Control::Free, Control::Same);
    vec![
        ("clothoid", Profile::clothoid()),
        (
            "cubic-start",
            Profile::new(vec![free, same(0), same(0), free]),
        ),
        (
            "cubic-end",
            Profile::new(vec![free, same(3), same(3), free]),
        ),
        (
            "quintic-start",
            Profile::new(vec![free, same(0), same(0), same(0), same(0), free]),
        ),
        (
            "quintic-end",
            Profile::new(vec![free, same(5), same(5), same(5), same(5), free]),
        ),
        (
            "flat-ends",
            Profile::new(vec![free, same(0), same(3), free]),
        ),
    ]
}

/// Seed 003 Fig. 2 in this crate's style: the same G1 data ([`variety_data`]) met by each
/// profile of [`variety_profiles`], side by side, `panel` pixels square each, with curvature
/// combs, inflections (red) and curvature extrema (blue).
///
/// # Errors
///
/// [`FigureError`] if a profile has no solution (it has) or rendering fails.
pub fn variety_figure(panel: u32) -> Result<Pixmap, FigureError> {
    let data = variety_data();
    let points = [data.start.point, data.end.point];
    let mut panels = Vec::new();
    for (name, profile) in variety_profiles() {
        let seg = data.solve(&profile)?;
        let scene = scene(core::slice::from_ref(&seg), &points, panel, panel)?.with_title(name);
        panels.push(scene.render()?);
    }
    Ok(hstack(&panels, FIGURE_GAP)?)
}

/// The G1 data of [`viable_figure`]: from (0, 0) along +x to (1, 0.4) at 60°.
pub fn viable_data() -> Hermite {
    Hermite::g1(
        Point::ZERO,
        0.0,
        Point::new(1.0, 0.4),
        core::f64::consts::FRAC_PI_3,
    )
}

/// The degrees of [`viable_figure`]'s panels (those of seed 003 Fig. 4).
pub const VIABLE_DEGREES: [usize; 3] = [3, 5, 10];
/// The `κ_s` range of [`viable_figure`].
pub const VIABLE_K_START: core::ops::Range<f64> = -0.5..1.5;
/// The `κ_e` range of [`viable_figure`].
pub const VIABLE_K_END: core::ops::Range<f64> = 0.0..6.0;

/// Seed 003 Fig. 4 in this crate's style: for [`viable_data`], which `(κ_s, κ_e)` in
/// [`VIABLE_K_START`] × [`VIABLE_K_END`] (`samples²` points) admit a G2 segment with monotone
/// curvature, for the degrees [`VIABLE_DEGREES`] side by side ([`viable_scene`]; the red dot
/// is the clothoid's end curvatures).
///
/// # Errors
///
/// [`FigureError`] for fewer than 2 samples or if rendering fails.
pub fn viable_figure(panel: u32, samples: usize) -> Result<Pixmap, FigureError> {
    let data = viable_data();
    let clothoid = data.solve(&Profile::clothoid())?;
    let ends = (clothoid.curvature_at(0.0), clothoid.curvature_at(1.0));
    let mut panels = Vec::new();
    for degree in VIABLE_DEGREES {
        let region = viable_region(&data, degree, VIABLE_K_START, VIABLE_K_END, samples)?;
        let scene =
            viable_scene(&region, Some(ends), panel).with_title(&format!("degree {degree}"));
        panels.push(with_viable_axes(scene, &region)?.render()?);
    }
    Ok(hstack(&panels, FIGURE_GAP)?)
}
