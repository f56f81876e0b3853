//! Text labels — panel titles, axis names — drawn as filled glyph outlines.
//!
//! The glyphs come from a subset of DejaVu Sans bundled with the crate
//! (`assets/DejaVuSans-labels.ttf`: printable ASCII, `κ`, `ε`, `×`, `−`, `°`, `≤`, `≥`), read
//! with ttf-parser and laid out by their horizontal advances (no kerning, no shaping). A label
//! is therefore an ordinary path: the SVG holds no `<text>`, rendering needs no system font,
//! and the pixels are the same on every machine.

use kurbo::{Affine, BezPath, Point};

use crate::outline::OutlinePath;

/// The bundled font subset (DejaVu Sans, Bitstream Vera licence; see `assets/README.md`).
const FONT: &[u8] = include_bytes!("../../assets/DejaVuSans-labels.ttf");

/// Where a label's anchor point lies along its baseline, as SVG's `text-anchor`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TextAlign {
    /// The anchor is the start (left end) of the text.
    #[default]
    Start,
    /// The anchor is the middle of the text.
    Middle,
    /// The anchor is the end (right end) of the text.
    End,
}

/// The outline of `text` set at `size_px` pixels per em in y-down pixel coordinates, with its
/// baseline through `at` aligned as `align` says (the text's advance width decides the shift).
///
/// A character the subset lacks is drawn as the font's `.notdef` box, so a missing glyph is
/// visible rather than silently dropped. Line breaks are not interpreted.
pub(crate) fn text_outline(text: &str, at: Point, size_px: f64, align: TextAlign) -> BezPath {
    // The bundled font is a fixed, valid file: parsing it cannot fail at run time once it has
    // passed the unit test below, but an empty path is the safe answer all the same.
    let Ok(face) = ttf_parser::Face::parse(FONT, 0) else {
        return BezPath::new();
    };
    let scale = size_px / f64::from(face.units_per_em());
    let mut glyphs = Vec::with_capacity(text.len());
    let mut pen_x = 0.0;
    for ch in text.chars() {
        let id = face.glyph_index(ch).unwrap_or(ttf_parser::GlyphId(0));
        let mut outline = OutlinePath(BezPath::new());
        face.outline_glyph(id, &mut outline);
        glyphs.push((pen_x, outline.0));
        pen_x += f64::from(face.glyph_hor_advance(id).unwrap_or(0)) * scale;
    }
    let shift = match align {
        TextAlign::Start => 0.0,
        TextAlign::Middle => 0.5 * pen_x,
        TextAlign::End => pen_x,
    };
    let mut path = BezPath::new();
    for (x, glyph) in glyphs {
        // Font units are y up: scale, flip, then move the glyph's origin to its pen position.
        let to_pixels = Affine::new([scale, 0.0, 0.0, -scale, at.x - shift + x, at.y]);
        path.extend(to_pixels * glyph);
    }
    path
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::Shape;

    #[test]
    fn the_bundled_font_has_every_label_character() {
        let face = ttf_parser::Face::parse(FONT, 0).expect("the bundled font parses");
        for ch in (' '..='~').chain("κε×−°≤≥".chars()) {
            assert!(face.glyph_index(ch).is_some(), "{ch:?} is missing");
        }
    }

    #[test]
    fn alignment_moves_the_text_by_its_width() {
        let at = Point::new(100.0, 50.0);
        let start = text_outline("κ, a = 0.75", at, 12.0, TextAlign::Start).bounding_box();
        let middle = text_outline("κ, a = 0.75", at, 12.0, TextAlign::Middle).bounding_box();
        let end = text_outline("κ, a = 0.75", at, 12.0, TextAlign::End).bounding_box();
        // Starts at the anchor (less the first glyph's side bearing), ends before it.
        assert!((start.x0 - at.x).abs() < 2.0, "{start:?}");
        assert!((end.x1 - at.x).abs() < 2.0, "{end:?}");
        let width = start.width();
        assert!(width > 40.0 && width < 90.0, "{width}");
        assert!((middle.center().x - at.x).abs() < 1.0, "{middle:?}");
        // Sits on the baseline: caps and digits above it, nothing far below (y down).
        assert!(start.y1 <= at.y + 3.0 && start.y0 < at.y - 7.0, "{start:?}");
    }

    #[test]
    fn a_missing_character_is_drawn_as_a_box() {
        let drawn = text_outline("漢", Point::ZERO, 10.0, TextAlign::Start);
        assert!(drawn.area().abs() > 1.0);
    }
}
