//! Pictures of drafted glyphs: the original outline filled in light grey, the drafted
//! contours in black with their curvature combs and anchors (feature `render`).

use kurbo::{Affine, BezPath, Point, Rect};

use super::DraftedGlyph;
use crate::render::{Color, Scene, Style};

/// Comb teeth reach this fraction of the em at the word's largest (capped) |κ|.
const COMB_FRACTION: f64 = 0.06;
/// |κ| above this many per em is not used to scale the combs (tight terminals would
/// flatten every other tooth).
const COMB_KAPPA_CAP: f64 = 40.0;
/// Comb samples per drafted segment.
const COMB_SAMPLES: usize = 12;

/// One glyph of a [`word_scene`]: the original outline, its draft, and where its origin
/// goes (font units; the next glyph usually starts at the previous one's advance).
#[derive(Clone, Copy, Debug)]
pub struct PlacedGlyph<'a> {
    /// The original outline.
    pub original: &'a BezPath,
    /// The draft.
    pub drafted: &'a DraftedGlyph,
    /// The glyph origin's offset in font units.
    pub offset: kurbo::Vec2,
}

/// A `width × height` picture of glyphs in font units (y up): originals filled in light grey,
/// drafts in black with curvature combs (one scale for the whole word) and the anchors in red.
/// `view` is the region shown (`None`: the originals' bounding box with a margin of 0.05 em).
pub fn word_scene(
    glyphs: &[PlacedGlyph<'_>],
    units_per_em: f64,
    width: u32,
    height: u32,
    view: Option<Rect>,
) -> Scene {
    let kcap = COMB_KAPPA_CAP / units_per_em;
    let kmax = glyphs
        .iter()
        .flat_map(|g| g.drafted.pieces())
        .map(|p| p.spline.max_abs_curvature().min(kcap))
        .fold(0.0, f64::max);
    let scale = if kmax > 0.0 {
        COMB_FRACTION * units_per_em / kmax
    } else {
        0.0
    };
    let mut bounds: Option<Rect> = None;
    let mut scene = Scene::new().with_size(width, height).with_y_down(false);
    for g in glyphs {
        let t = Affine::translate(g.offset);
        let original = t * g.original.clone();
        let b = kurbo::Shape::bounding_box(&original);
        if b.is_finite() && !original.elements().is_empty() {
            bounds = Some(bounds.map_or(b, |r| r.union(b)));
        }
        scene = scene.path(&original, Style::filled(Color::LIGHT_GRAY));
    }
    for g in glyphs {
        let t = Affine::translate(g.offset);
        for piece in g.drafted.pieces() {
            scene = scene.comb(&(t * piece.spline.curvature_comb(scale, COMB_SAMPLES)));
        }
    }
    for g in glyphs {
        let t = Affine::translate(g.offset);
        scene = scene.path(
            &(t * g.drafted.path.clone()),
            Style::new(Color::BLACK, 1.25),
        );
        let anchors: Vec<Point> = g
            .drafted
            .pieces()
            .flat_map(|p| p.anchors.iter().map(|a| t * a.point))
            .collect();
        scene = scene.input_points(&anchors);
    }
    let pad = 0.05 * units_per_em;
    if let Some(v) = view.or(bounds.map(|b| b.inflate(pad, pad))) {
        scene = scene.with_view_box(v);
    }
    scene
}
