//! Pictures of drafted glyphs: the original outline filled in light grey, the drafted
//! contours in black with their curvature combs and anchors (feature `render`); and the
//! gallery figure of a word, original above its drafts (features `render` and `font`).

use kurbo::{Affine, BezPath, Point, Rect};

use super::DraftedGlyph;
use crate::render::{Color, PointStyle, Scene, Style};

/// Comb teeth reach this fraction of the em at the word's largest (capped) |κ|.
const COMB_FRACTION: f64 = 0.06;
/// |κ| above this many per em is not used to scale the combs (tight terminals would
/// flatten every other tooth).
const COMB_KAPPA_CAP: f64 = 40.0;
/// Comb samples per drafted segment.
const COMB_SAMPLES: usize = 12;
/// Width in pixels of the drafted outlines.
const DRAFT_WIDTH: f64 = 1.25;

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

/// The comb scale (tooth length per unit |κ|) of drafts: the largest |κ| of all their pieces,
/// capped at [`COMB_KAPPA_CAP`] per em, gets a tooth of `fraction` em.
fn comb_scale<'a>(
    drafts: impl Iterator<Item = &'a DraftedGlyph>,
    units_per_em: f64,
    fraction: f64,
) -> f64 {
    let kcap = COMB_KAPPA_CAP / units_per_em;
    let kmax = drafts
        .flat_map(|d| d.pieces())
        .map(|p| p.spline.max_abs_curvature().min(kcap))
        .fold(0.0, f64::max);
    if kmax > 0.0 {
        fraction * units_per_em / kmax
    } else {
        0.0
    }
}

/// The originals' bounding box, placed.
fn placed_bounds(glyphs: &[PlacedGlyph<'_>]) -> Option<Rect> {
    glyphs
        .iter()
        .filter(|g| !g.original.elements().is_empty())
        .map(|g| kurbo::Shape::bounding_box(&(Affine::translate(g.offset) * g.original.clone())))
        .filter(Rect::is_finite)
        .reduce(|a, b| a.union(b))
}

/// A comb (teeth `base → tip` joined tip to tip, as [`crate::analysis::curvature_comb`]
/// draws them) with every tooth cut to at most `max_len`: the teeth of tight terminals and
/// serifs, whose |κ| is beyond [`COMB_KAPPA_CAP`], would otherwise cross the whole picture.
fn clip_teeth(comb: &BezPath, max_len: f64) -> BezPath {
    // Each tooth, and whether the comb joins its tip to the next one (not across contours).
    let mut teeth: Vec<(Point, Point, bool)> = Vec::new();
    let mut base = None;
    for el in comb.elements() {
        match *el {
            kurbo::PathEl::MoveTo(p) => base = Some(p),
            kurbo::PathEl::LineTo(tip) => match base.take() {
                Some(b) => {
                    let v = tip - b;
                    let len = v.hypot();
                    let tip = if len > max_len {
                        b + v * (max_len / len)
                    } else {
                        tip
                    };
                    teeth.push((b, tip, false));
                }
                None => {
                    if let Some(t) = teeth.last_mut() {
                        t.2 = true;
                    }
                }
            },
            _ => {}
        }
    }
    let mut out = BezPath::new();
    for (j, &(b, tip, joined)) in teeth.iter().enumerate() {
        out.move_to(b);
        out.line_to(tip);
        if let (true, Some(&(_, next, _))) = (joined, teeth.get(j + 1)) {
            out.line_to(next);
        }
    }
    out
}

/// Adds drafted glyphs to a scene: originals in light grey, then the combs (at `scale`,
/// teeth at most `max_tooth` long), then the drafted outlines in black and their anchors in
/// red.
fn draw_drafts(
    mut scene: Scene,
    glyphs: &[PlacedGlyph<'_>],
    (scale, max_tooth): (f64, f64),
    anchor: PointStyle,
) -> Scene {
    for g in glyphs {
        let t = Affine::translate(g.offset);
        scene = scene.path(&(t * g.original.clone()), Style::filled(Color::LIGHT_GRAY));
    }
    for g in glyphs {
        let t = Affine::translate(g.offset);
        for piece in g.drafted.pieces() {
            let comb = piece.spline.curvature_comb(scale, COMB_SAMPLES);
            scene = scene.comb(&(t * clip_teeth(&comb, max_tooth)));
        }
    }
    for g in glyphs {
        let t = Affine::translate(g.offset);
        scene = scene.path(
            &(t * g.drafted.path.clone()),
            Style::new(Color::BLACK, DRAFT_WIDTH),
        );
        let anchors: Vec<Point> = g
            .drafted
            .pieces()
            .flat_map(|p| p.anchors.iter().map(|a| t * a.point))
            .collect();
        scene = scene.points(&anchors, anchor);
    }
    scene
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
    let scale = comb_scale(
        glyphs.iter().map(|g| g.drafted),
        units_per_em,
        COMB_FRACTION,
    );
    let scene = Scene::new().with_size(width, height).with_y_down(false);
    let max_tooth = scale * COMB_KAPPA_CAP / units_per_em;
    let mut scene = draw_drafts(scene, glyphs, (scale, max_tooth), PointStyle::INPUT);
    let pad = 0.05 * units_per_em;
    if let Some(v) = view.or(placed_bounds(glyphs).map(|b| b.inflate(pad, pad))) {
        scene = scene.with_view_box(v);
    }
    scene
}

#[cfg(feature = "font")]
pub use figure::{word_figure, FIGURE_WORD};

#[cfg(feature = "font")]
mod figure {
    use kurbo::{Affine, Vec2};

    use super::{clip_teeth, comb_scale, draw_drafts, placed_bounds, PlacedGlyph};
    use super::{Color, PointStyle, Scene, Style};
    use super::{COMB_KAPPA_CAP, COMB_SAMPLES};
    use crate::glyph::{draft, on_curve_split, DraftOptions, DraftedGlyph, FontOutlines, Glyph};
    use crate::Error;

    /// The word of the gallery figure.
    pub const FIGURE_WORD: &str = "Sample";
    /// Distance between the baselines of the figure's rows, in em.
    const ROW_PITCH: f64 = 1.3;
    /// Width in pixels of the original outlines in the top row.
    const ORIGINAL_WIDTH: f64 = 1.0;
    /// Comb teeth reach this fraction of the em at the largest (capped) |κ| of the drafts.
    const FIGURE_COMB_FRACTION: f64 = 0.12;
    /// The original's on-curve points: filled, and hollow where implied (see
    /// [`on_curve_split`]).
    const STORED: PointStyle = PointStyle::new(2.5, Color::BLACK);
    const IMPLIED: PointStyle = PointStyle::new(2.5, Color::WHITE).with_outline(Color::BLACK);
    /// The anchors of the drafts.
    const ANCHOR: PointStyle = PointStyle::new(3.0, Color::RED);

    /// The glyphs side by side from the origin, each at the previous one's advance, `dy`
    /// up.
    fn place<'a>(
        glyphs: &'a [Glyph],
        drafted: &'a [DraftedGlyph],
        dy: f64,
    ) -> Vec<PlacedGlyph<'a>> {
        let mut x = 0.0;
        glyphs
            .iter()
            .zip(drafted)
            .map(|(g, d)| {
                let p = PlacedGlyph {
                    original: &g.path,
                    drafted: d,
                    offset: Vec2::new(x, dy),
                };
                x += g.advance;
                p
            })
            .collect()
    }

    /// The gallery figure of `word` in `font`: the original outlines on top, filled in light
    /// grey with their curvature combs (TrueType quadratics: the comb jumps at every joint)
    /// and their on-curve points (filled; implied ones, see [`on_curve_split`], hollow);
    /// below, one row per entry of `drafts`, each drafted with those options and drawn as
    /// [`super::word_scene`] draws (draft in black, comb, anchors in red). One comb scale for
    /// every row, so that their curvature can be compared; baselines 1.3 em apart; a
    /// `width × height` picture of all of them.
    ///
    /// # Errors
    ///
    /// [`Error::MissingGlyph`] for a character the font lacks, and the errors of [`draft`].
    pub fn word_figure(
        font: &FontOutlines<'_>,
        word: &str,
        drafts: &[DraftOptions],
        width: u32,
        height: u32,
    ) -> Result<Scene, Error> {
        let upem = font.units_per_em();
        let glyphs: Vec<Glyph> = word
            .chars()
            .map(|ch| font.glyph(ch))
            .collect::<Result<_, _>>()?;
        let rows: Vec<Vec<DraftedGlyph>> = drafts
            .iter()
            .map(|options| glyphs.iter().map(|g| draft(&g.path, options)).collect())
            .collect::<Result<_, _>>()?;
        let pitch = ROW_PITCH * upem;
        let placed = |row: usize, drafted| place(&glyphs, drafted, -(row as f64) * pitch);
        let scale = comb_scale(rows.iter().flatten(), upem, FIGURE_COMB_FRACTION);
        let mut scene = Scene::new().with_size(width, height).with_y_down(false);
        // The originals, placed as the first row of drafts would be (any row's originals).
        let top = rows.first().map(|r| placed(0, r)).unwrap_or_default();
        let mut bounds = placed_bounds(&top);
        let (mut stored, mut implied) = (Vec::new(), Vec::new());
        for g in &top {
            let t = Affine::translate(g.offset);
            let original = t * g.original.clone();
            scene = scene.path(&original, Style::filled(Color::LIGHT_GRAY));
            let comb = crate::analysis::curvature_comb(&original, scale, COMB_SAMPLES);
            scene = scene.comb(&clip_teeth(&comb, scale * COMB_KAPPA_CAP / upem));
            let (s, i) = on_curve_split(&original);
            stored.extend(s);
            implied.extend(i);
        }
        for g in &top {
            let original = Affine::translate(g.offset) * g.original.clone();
            scene = scene.path(&original, Style::new(Color::BLACK, ORIGINAL_WIDTH));
        }
        scene = scene.points(&stored, STORED).points(&implied, IMPLIED);
        for (r, drafted) in rows.iter().enumerate() {
            let row = placed(r + 1, drafted);
            if let Some(b) = placed_bounds(&row) {
                bounds = Some(bounds.map_or(b, |a| a.union(b)));
            }
            scene = draw_drafts(scene, &row, (scale, scale * COMB_KAPPA_CAP / upem), ANCHOR);
        }
        let pad = 0.05 * upem;
        if let Some(b) = bounds {
            scene = scene.with_view_box(b.inflate(pad, pad));
        }
        Ok(scene)
    }
}
