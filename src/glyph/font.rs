//! A small compiled TrueType font of drafted glyphs, built with write-fonts.

use kurbo::Rect;
use write_fonts::tables::cmap::Cmap;
use write_fonts::tables::glyf::{GlyfLocaBuilder, Glyph as WGlyph, SimpleGlyph};
use write_fonts::tables::head::Head;
use write_fonts::tables::hhea::Hhea;
use write_fonts::tables::hmtx::{Hmtx, LongMetric};
use write_fonts::tables::maxp::Maxp;
use write_fonts::tables::name::{Name, NameRecord};
use write_fonts::tables::post::Post;
use write_fonts::types::{FWord, Fixed, GlyphId, NameId, UfWord};
use write_fonts::FontBuilder;

use super::export::{is_quadratic, FontGlyph};
use super::grid::quantize;
use crate::Error;

/// The family name [`compile_font`] uses when given an empty one. (The vendored test font's
/// licence forbids its names on modified glyphs.)
pub const FONT_FAMILY: &str = "Kappa Draft";

/// Compiles glyphs into a TrueType font (`head`, `hhea`, `maxp`, `hmtx`, `cmap`, `loca`,
/// `glyf`, `name`, `post`), glyph 0 being an empty `.notdef`.
///
/// Outlines must be lines and quadratics ([`super::to_quadratic`]). **The integer grid:** a
/// `glyf` table stores integer font units, so every coordinate is rounded with
/// [`quantize`] (`⌊x + ½⌋`); on-curve points midway between two off-curve points are left
/// implied, which write-fonts decides on the rounded points, so a reader restores them
/// exactly. Read back (ttf-parser), each glyph's outline is `quantize(path)` segment for
/// segment: same points, same order, closed contours starting at their first point.
///
/// # Errors
///
/// [`Error::Font`] for a cubic segment, a coordinate or advance outside the 16-bit range,
/// two glyphs for one character, or a table that write-fonts cannot compile.
pub fn compile_font(
    family: &str,
    units_per_em: u16,
    ascender: i16,
    descender: i16,
    glyphs: &[FontGlyph],
) -> Result<Vec<u8>, Error> {
    let family = if family.is_empty() {
        FONT_FAMILY
    } else {
        family
    };
    if !(16..=16384).contains(&units_per_em) {
        return Err(Error::Font(format!(
            "units per em {units_per_em} outside 16..=16384"
        )));
    }
    let mut builder = GlyfLocaBuilder::new();
    builder
        .add_glyph(&WGlyph::Empty)
        .map_err(|e| Error::Font(format!("cannot write .notdef: {e}")))?;
    let mut metrics = vec![LongMetric::new(0, 0)];
    let mut bounds: Option<Rect> = None;
    let (mut max_points, mut max_contours) = (0u16, 0u16);
    let mut mappings = Vec::with_capacity(glyphs.len());
    for (i, g) in glyphs.iter().enumerate() {
        if !is_quadratic(&g.path) {
            return Err(Error::Font(format!(
                "glyph {} has cubic segments: convert them with to_quadratic",
                g.name
            )));
        }
        let path = quantize(&g.path);
        let b = kurbo::Shape::bounding_box(&path);
        let limit = f64::from(i16::MAX);
        if !b.is_finite() || b.x0 < -limit || b.y0 < -limit || b.x1 > limit || b.y1 > limit {
            return Err(Error::Font(format!(
                "glyph {} exceeds 16-bit coordinates",
                g.name
            )));
        }
        let advance = g.advance.round();
        if !(0.0..=f64::from(u16::MAX)).contains(&advance) {
            return Err(Error::Font(format!(
                "glyph {} advance out of range",
                g.name
            )));
        }
        let glyph = if path.elements().is_empty() {
            metrics.push(LongMetric::new(advance as u16, 0));
            WGlyph::Empty
        } else {
            let simple = SimpleGlyph::from_bezpath(&path)
                .map_err(|e| Error::Font(format!("glyph {}: {e:?}", g.name)))?;
            let points: usize = simple.contours.iter().map(|c| c.len()).sum();
            max_points = max_points.max(points.min(usize::from(u16::MAX)) as u16);
            max_contours =
                max_contours.max(simple.contours.len().min(usize::from(u16::MAX)) as u16);
            metrics.push(LongMetric::new(advance as u16, simple.bbox.x_min));
            bounds = Some(bounds.map_or(b, |r| r.union(b)));
            WGlyph::Simple(simple)
        };
        builder
            .add_glyph(&glyph)
            .map_err(|e| Error::Font(format!("glyph {}: {e}", g.name)))?;
        let gid = u16::try_from(i + 1).map_err(|_| Error::Font("too many glyphs".into()))?;
        mappings.push((g.ch, GlyphId::new(u32::from(gid))));
    }
    let num_glyphs =
        u16::try_from(glyphs.len() + 1).map_err(|_| Error::Font("too many glyphs".into()))?;
    let (glyf, loca, loca_format) = builder.build();
    let cmap =
        Cmap::from_mappings(mappings).map_err(|e| Error::Font(format!("character map: {e}")))?;
    let b = bounds.unwrap_or_default();
    let mut head = Head {
        units_per_em,
        x_min: b.x0 as i16,
        y_min: b.y0 as i16,
        x_max: b.x1 as i16,
        y_max: b.y1 as i16,
        font_revision: Fixed::from_f64(1.0),
        ..Head::default()
    };
    head.index_to_loc_format = loca_format as i16;
    let advance_max = metrics.iter().map(|m| m.advance).max().unwrap_or(0);
    let hhea = Hhea {
        ascender: FWord::new(ascender),
        descender: FWord::new(descender),
        advance_width_max: UfWord::new(advance_max),
        caret_slope_rise: 1,
        number_of_h_metrics: num_glyphs,
        ..Hhea::default()
    };
    let maxp = Maxp {
        max_points: Some(max_points),
        max_contours: Some(max_contours),
        max_composite_points: Some(0),
        max_composite_contours: Some(0),
        max_zones: Some(1),
        max_twilight_points: Some(0),
        max_storage: Some(0),
        max_function_defs: Some(0),
        max_instruction_defs: Some(0),
        max_stack_elements: Some(0),
        max_size_of_instructions: Some(0),
        max_component_elements: Some(0),
        max_component_depth: Some(0),
        ..Maxp::new(num_glyphs)
    };
    let hmtx = Hmtx::new(metrics, Vec::new());
    let name = Name::new(
        [
            (NameId::FAMILY_NAME, family.to_owned()),
            (NameId::SUBFAMILY_NAME, "Regular".to_owned()),
            (NameId::FULL_NAME, format!("{family} Regular")),
        ]
        .into_iter()
        .map(|(id, text)| NameRecord::new(3, 1, 0x409, id, text.into()))
        .collect(),
    );
    let post = Post {
        underline_thickness: FWord::new(i16::try_from(units_per_em / 20).unwrap_or(1)),
        ..Post::default()
    };
    let err =
        |t: &'static str| move |e: write_fonts::BuilderError| Error::Font(format!("{t}: {e}"));
    Ok(FontBuilder::new()
        .add_table(&head)
        .map_err(err("head"))?
        .add_table(&hhea)
        .map_err(err("hhea"))?
        .add_table(&maxp)
        .map_err(err("maxp"))?
        .add_table(&hmtx)
        .map_err(err("hmtx"))?
        .add_table(&cmap)
        .map_err(err("cmap"))?
        .add_table(&loca)
        .map_err(err("loca"))?
        .add_table(&glyf)
        .map_err(err("glyf"))?
        .add_table(&name)
        .map_err(err("name"))?
        .add_table(&post)
        .map_err(err("post"))?
        .build())
}
