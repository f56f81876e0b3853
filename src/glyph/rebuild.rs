//! A whole font rebuilt with drafted outlines: every glyph kept at its glyph id, the
//! drafted ones replaced, and the tables that depend on outlines recomputed.

use std::collections::HashMap;

use kurbo::{BezPath, Point, Rect};
use write_fonts::from_obj::{FromTableRef, ToOwnedTable};
use write_fonts::read::tables::glyf::Anchor;
use write_fonts::read::{FontRef, TableProvider};
use write_fonts::tables::glyf::{GlyfLocaBuilder, Glyph as WGlyph, SimpleGlyph};
use write_fonts::tables::hmtx::{Hmtx, LongMetric};
use write_fonts::tables::maxp::Maxp;
use write_fonts::tables::name::{Name, NameRecord};
use write_fonts::tables::os2::Os2;
use write_fonts::tables::post::Post;
use write_fonts::types::{FWord, GlyphId, LongDateTime, NameId, Tag, UfWord};
use write_fonts::FontBuilder;

use super::direction::{orient, Direction};
use super::export::to_quadratic;
use super::grid::quantize;
use super::import::FontOutlines;
use crate::Error;

/// Options of [`rebuild_ttf`].
#[derive(Clone, Debug, PartialEq)]
pub struct RebuildOptions {
    /// The family name of the new font (name IDs 1, 3, 4 and 6). A modified font may not
    /// carry its source's Reserved Font Names (SIL Open Font License), so the source's
    /// family name is never reused: empty means [`super::FONT_FAMILY`].
    pub family: String,
    /// Largest distance of the TrueType quadratics from cubic outlines, in font units.
    pub quad_tolerance: f64,
    /// The time written as `head.modified` (and as `head.created` where the source has
    /// none), in seconds since 1970-01-01 UTC.
    pub timestamp: i64,
}

impl Default for RebuildOptions {
    fn default() -> Self {
        RebuildOptions {
            family: String::new(),
            quad_tolerance: 0.5,
            timestamp: 0,
        }
    }
}

/// Tables rebuilt from the outlines, or dropped because they describe the source's outlines
/// (device metrics, a signature, the CFF outlines or variations themselves).
const REBUILT: [&[u8; 4]; 21] = [
    b"glyf", b"loca", b"head", b"hhea", b"hmtx", b"maxp", b"OS/2", b"name", b"post", b"CFF ",
    b"CFF2", b"VORG", b"hdmx", b"LTSH", b"VDMX", b"DSIG", b"gvar", b"cvar", b"HVAR", b"VVAR",
    b"MVAR",
];

/// Seconds from 1904-01-01 (the `head` epoch) to 1970-01-01.
const MAC_EPOCH_OFFSET: i64 = 2_082_844_800;

/// Rebuilds a TrueType font from `source` (TrueType or CFF-flavoured OpenType), replacing
/// the outlines of the glyph ids in `replaced` (font units, y up; lines, quadratics and
/// cubics).
///
/// - **Outlines.** Replaced glyphs and, for a CFF source, every glyph are converted to
///   quadratics ([`to_quadratic`], within [`RebuildOptions::quad_tolerance`]), turned
///   TrueType's way ([`Direction::TrueType`]: outer contours clockwise) and rounded to the
///   integer grid. Other glyphs of a TrueType source are copied as they are, composites
///   and instructions included.
/// - **Kept from the source:** glyph ids and names, `cmap`, advance widths, the vertical
///   metrics (`hhea`, `OS/2`), the licence and copyright names, and every table that does
///   not describe outlines (layout, `gasp`, hinting programs…).
/// - **Recomputed:** `head` (bounding box = union of the glyph boxes, dates), `hhea` (side
///   bearing extremes, `xMaxExtent`), `hmtx` side bearings, `maxp` (version 1.0), `OS/2`
///   (version 4 at least: `sxHeight`, `sCapHeight` measured from `x` and `H`), `name` IDs
///   1–6 under the new family, `post` (format 2 with the glyph names).
/// - **Dropped:** `hdmx`, `LTSH`, `VDMX`, `DSIG`, the CFF tables.
///
/// # Errors
///
/// [`Error::Font`] for a font that cannot be read, a variable font, a glyph id out of
/// range, or an outline that does not fit TrueType's 16-bit coordinates; the errors of
/// [`to_quadratic`].
pub fn rebuild_ttf(
    source: &[u8],
    replaced: &HashMap<u16, BezPath>,
    options: &RebuildOptions,
) -> Result<Vec<u8>, Error> {
    let bad = |what: &'static str| {
        move |e: write_fonts::read::ReadError| Error::Font(format!("{what}: {e}"))
    };
    let font = FontRef::new(source).map_err(bad("cannot read the font"))?;
    let outlines = FontOutlines::parse(source)?;
    if font.table_data(Tag::new(b"fvar")).is_some() {
        return Err(Error::Font("variable fonts are not supported".into()));
    }
    let num_glyphs = font.maxp().map_err(bad("maxp"))?.num_glyphs();
    if let Some(id) = replaced.keys().find(|&&id| id >= num_glyphs) {
        return Err(Error::Font(format!(
            "glyph id {id} out of range (the font has {num_glyphs})"
        )));
    }
    let glyf = font.glyf().ok().zip(font.loca(None).ok());
    let mut glyphs = Vec::with_capacity(usize::from(num_glyphs));
    for id in 0..num_glyphs {
        let path = match replaced.get(&id) {
            Some(path) => Some(path.clone()),
            None if glyf.is_none() => Some(outlines.outline(id)?),
            None => None,
        };
        let glyph = match (path, &glyf) {
            (Some(path), _) => simple_glyph(&path, id, options.quad_tolerance)?,
            (None, Some((glyf, loca))) => match loca.get_glyf(GlyphId::new(id.into()), glyf) {
                Ok(Some(g)) => WGlyph::from_table_ref(&g),
                Ok(None) => WGlyph::Empty,
                Err(e) => return Err(Error::Font(format!("glyph {id}: {e}"))),
            },
            (None, None) => WGlyph::Empty,
        };
        glyphs.push(glyph);
    }
    let points = resolve_points(&glyphs)?;
    let boxes: Vec<Option<Rect>> = points.iter().map(|p| bounds(p)).collect();
    // Composite glyphs get the box of their resolved points.
    for (g, b) in glyphs.iter_mut().zip(&boxes) {
        if let (WGlyph::Composite(c), Some(b)) = (g, b) {
            c.bbox = (*b).into();
        }
    }
    let mut builder = GlyfLocaBuilder::new();
    for (id, g) in glyphs.iter().enumerate() {
        builder
            .add_glyph(g)
            .map_err(|e| Error::Font(format!("glyph {id}: {e}")))?;
    }
    let (glyf_table, loca_table, loca_format) = builder.build();

    // Metrics.
    let hmtx = font.hmtx().map_err(bad("hmtx"))?;
    let mut metrics = Vec::with_capacity(glyphs.len());
    let (mut min_lsb, mut min_rsb, mut max_extent) = (i16::MAX, i16::MAX, i16::MIN);
    let mut font_box: Option<Rect> = None;
    for (id, b) in boxes.iter().enumerate() {
        let advance = hmtx.advance(GlyphId::new(id as u32)).unwrap_or(0);
        let lsb = match b {
            Some(b) => {
                let (x0, x1) = (b.x0 as i16, b.x1 as i16);
                min_lsb = min_lsb.min(x0);
                min_rsb = min_rsb.min(saturate(f64::from(advance) - f64::from(x1)));
                max_extent = max_extent.max(x1);
                font_box = Some(font_box.map_or(*b, |r| r.union(*b)));
                x0
            }
            None => 0,
        };
        metrics.push(LongMetric::new(advance, lsb));
    }
    let font_box = font_box.unwrap_or_default();
    let advance_max = metrics.iter().map(|m| m.advance).max().unwrap_or(0);

    let mut head: write_fonts::tables::head::Head =
        font.head().map_err(bad("head"))?.to_owned_table();
    head.x_min = font_box.x0 as i16;
    head.y_min = font_box.y0 as i16;
    head.x_max = font_box.x1 as i16;
    head.y_max = font_box.y1 as i16;
    head.index_to_loc_format = loca_format as i16;
    let now = LongDateTime::new(options.timestamp.saturating_add(MAC_EPOCH_OFFSET));
    if head.created.as_secs() == 0 {
        head.created = now;
    }
    head.modified = now;

    let mut hhea: write_fonts::tables::hhea::Hhea =
        font.hhea().map_err(bad("hhea"))?.to_owned_table();
    hhea.advance_width_max = UfWord::new(advance_max);
    hhea.min_left_side_bearing = FWord::new(if font_box.is_zero_area() { 0 } else { min_lsb });
    hhea.min_right_side_bearing = FWord::new(if font_box.is_zero_area() { 0 } else { min_rsb });
    hhea.x_max_extent = FWord::new(if font_box.is_zero_area() {
        0
    } else {
        max_extent
    });
    hhea.number_of_h_metrics = num_glyphs;

    let maxp = maxp_of(&font, &glyphs, num_glyphs)?;
    let os2 = os2_of(&font, &outlines, &boxes)?;
    let name = name_of(&font, options, head.font_revision.to_f64())?;
    let post = post_of(&font, &outlines, num_glyphs)?;

    let err =
        |t: &'static str| move |e: write_fonts::BuilderError| Error::Font(format!("{t}: {e}"));
    let mut out = FontBuilder::new();
    out.add_table(&head).map_err(err("head"))?;
    out.add_table(&hhea).map_err(err("hhea"))?;
    out.add_table(&maxp).map_err(err("maxp"))?;
    out.add_table(&Hmtx::new(metrics, Vec::new()))
        .map_err(err("hmtx"))?;
    out.add_table(&os2).map_err(err("OS/2"))?;
    out.add_table(&name).map_err(err("name"))?;
    out.add_table(&post).map_err(err("post"))?;
    out.add_table(&loca_table).map_err(err("loca"))?;
    out.add_table(&glyf_table).map_err(err("glyf"))?;
    for record in font.table_directory.table_records() {
        let tag = record.tag();
        if REBUILT.iter().any(|t| Tag::new(t) == tag) {
            continue;
        }
        if let Some(data) = font.table_data(tag) {
            out.add_raw(tag, data.as_bytes());
        }
    }
    Ok(out.build())
}

/// The glyph ids whose outlines are drawn rather than composed: the simple glyphs with
/// contours of a TrueType font, every glyph with an outline of a CFF font. These are what
/// a whole-font draft replaces; composite glyphs follow their components.
///
/// # Errors
///
/// [`Error::Font`] for a font that cannot be read.
pub fn drawn_glyph_ids(source: &[u8]) -> Result<Vec<u16>, Error> {
    let font =
        FontRef::new(source).map_err(|e| Error::Font(format!("cannot read the font: {e}")))?;
    let outlines = FontOutlines::parse(source)?;
    let glyf = font.glyf().ok().zip(font.loca(None).ok());
    let mut ids = Vec::new();
    for id in 0..outlines.glyph_count() {
        let drawn = match &glyf {
            Some((glyf, loca)) => matches!(
                loca.get_glyf(GlyphId::new(id.into()), glyf),
                Ok(Some(write_fonts::read::tables::glyf::Glyph::Simple(s))) if s.number_of_contours() > 0
            ),
            None => outlines.outline(id).is_ok_and(|p| !p.elements().is_empty()),
        };
        if drawn {
            ids.push(id);
        }
    }
    Ok(ids)
}

/// A TrueType glyph from an outline: quadratics, TrueType direction, the integer grid.
fn simple_glyph(path: &BezPath, id: u16, tolerance: f64) -> Result<WGlyph, Error> {
    let quads = to_quadratic(&orient(path, Direction::TrueType), tolerance)?;
    let path = quantize(&quads.path);
    if path.elements().is_empty() {
        return Ok(WGlyph::Empty);
    }
    let limit = f64::from(i16::MAX);
    let b = kurbo::Shape::bounding_box(&path);
    if !b.is_finite() || b.x0 < -limit || b.y0 < -limit || b.x1 > limit || b.y1 > limit {
        return Err(Error::Font(format!(
            "glyph {id} exceeds 16-bit coordinates"
        )));
    }
    SimpleGlyph::from_bezpath(&path)
        .map(WGlyph::Simple)
        .map_err(|e| Error::Font(format!("glyph {id}: {e:?}")))
}

/// Clamps to the 16-bit range.
fn saturate(v: f64) -> i16 {
    v.round().clamp(f64::from(i16::MIN), f64::from(i16::MAX)) as i16
}

/// The box of points (on- and off-curve, as TrueType counts them).
fn bounds(points: &[Point]) -> Option<Rect> {
    let first = *points.first()?;
    Some(
        points
            .iter()
            .fold(Rect::from_points(first, first), |r, &p| r.union_pt(p)),
    )
}

/// Every glyph's points with its components resolved (offsets, point matching and
/// transforms), in point order.
fn resolve_points(glyphs: &[WGlyph]) -> Result<Vec<Vec<Point>>, Error> {
    fn resolve(
        id: usize,
        glyphs: &[WGlyph],
        memo: &mut Vec<Option<Vec<Point>>>,
        depth: usize,
    ) -> Result<Vec<Point>, Error> {
        if let Some(p) = &memo[id] {
            return Ok(p.clone());
        }
        if depth > 16 {
            return Err(Error::Font(format!("glyph {id}: components nest too deep")));
        }
        let points = match &glyphs[id] {
            WGlyph::Empty => Vec::new(),
            WGlyph::Simple(s) => s
                .contours
                .iter()
                .flat_map(|c| c.iter().map(|p| Point::new(p.x.into(), p.y.into())))
                .collect(),
            WGlyph::Composite(c) => {
                let mut out: Vec<Point> = Vec::new();
                for comp in c.components() {
                    let child = comp.glyph.to_u32() as usize;
                    if child >= glyphs.len() {
                        return Err(Error::Font(format!("glyph {id}: component out of range")));
                    }
                    let pts = resolve(child, glyphs, memo, depth + 1)?;
                    let t = comp.transform;
                    let (xx, yx, xy, yy) = (
                        t.xx.to_f32() as f64,
                        t.yx.to_f32() as f64,
                        t.xy.to_f32() as f64,
                        t.yy.to_f32() as f64,
                    );
                    let map = |p: Point| Point::new(xx * p.x + xy * p.y, yx * p.x + yy * p.y);
                    let offset = match comp.anchor {
                        Anchor::Offset { x, y } => kurbo::Vec2::new(x.into(), y.into()),
                        Anchor::Point { base, component } => {
                            match (out.get(usize::from(base)), pts.get(usize::from(component))) {
                                (Some(&b), Some(&c)) => b - map(c),
                                _ => {
                                    return Err(Error::Font(format!(
                                        "glyph {id}: component anchor point out of range"
                                    )))
                                }
                            }
                        }
                    };
                    out.extend(pts.into_iter().map(|p| map(p) + offset));
                }
                out
            }
        };
        memo[id] = Some(points.clone());
        Ok(points)
    }
    let mut memo = vec![None; glyphs.len()];
    (0..glyphs.len())
        .map(|id| resolve(id, glyphs, &mut memo, 0))
        .collect()
}

/// `maxp` version 1.0: the outline maxima measured, the hinting maxima of the source (or
/// none for a CFF source).
fn maxp_of(font: &FontRef, glyphs: &[WGlyph], num_glyphs: u16) -> Result<Maxp, Error> {
    let source = font.maxp().map_err(|e| Error::Font(format!("maxp: {e}")))?;
    // Points and contours of each glyph, components resolved; component depth.
    fn count(id: usize, glyphs: &[WGlyph], depth: usize) -> (usize, usize, usize) {
        if depth > 16 {
            return (0, 0, depth);
        }
        match &glyphs[id] {
            WGlyph::Empty => (0, 0, 0),
            WGlyph::Simple(s) => (
                s.contours.iter().map(|c| c.len()).sum(),
                s.contours.len(),
                0,
            ),
            WGlyph::Composite(c) => c.components().iter().fold((0, 0, 1), |acc, comp| {
                let child = comp.glyph.to_u32() as usize;
                let (p, k, d) = if child < glyphs.len() {
                    count(child, glyphs, depth + 1)
                } else {
                    (0, 0, 0)
                };
                (acc.0 + p, acc.1 + k, acc.2.max(d + 1))
            }),
        }
    }
    let narrow = |v: usize| u16::try_from(v).unwrap_or(u16::MAX);
    let (mut points, mut contours, mut cpoints, mut ccontours, mut elements, mut depth) =
        (0, 0, 0, 0, 0, 0);
    for (id, g) in glyphs.iter().enumerate() {
        let (p, k, d) = count(id, glyphs, 0);
        match g {
            WGlyph::Simple(_) => {
                points = points.max(p);
                contours = contours.max(k);
            }
            WGlyph::Composite(c) => {
                cpoints = cpoints.max(p);
                ccontours = ccontours.max(k);
                elements = elements.max(c.components().len());
                depth = depth.max(d);
            }
            WGlyph::Empty => {}
        }
    }
    Ok(Maxp {
        max_points: Some(narrow(points)),
        max_contours: Some(narrow(contours)),
        max_composite_points: Some(narrow(cpoints)),
        max_composite_contours: Some(narrow(ccontours)),
        max_zones: Some(source.max_zones().unwrap_or(1).clamp(1, 2)),
        max_twilight_points: Some(source.max_twilight_points().unwrap_or(0)),
        max_storage: Some(source.max_storage().unwrap_or(0)),
        max_function_defs: Some(source.max_function_defs().unwrap_or(0)),
        max_instruction_defs: Some(source.max_instruction_defs().unwrap_or(0)),
        max_stack_elements: Some(source.max_stack_elements().unwrap_or(0)),
        max_size_of_instructions: Some(source.max_size_of_instructions().unwrap_or(0)),
        max_component_elements: Some(narrow(elements)),
        max_component_depth: Some(narrow(depth)),
        ..Maxp::new(num_glyphs)
    })
}

/// `OS/2` from the source, raised to version 4 where it is older: `sxHeight` and
/// `sCapHeight` are the tops of `x` and `H`.
fn os2_of(font: &FontRef, outlines: &FontOutlines, boxes: &[Option<Rect>]) -> Result<Os2, Error> {
    let mut os2: Os2 = match font.os2() {
        Ok(os2) => os2.to_owned_table(),
        Err(_) => synthesized_os2(font, outlines, boxes)?,
    };
    let top = |ch: char| {
        outlines
            .glyph_id(ch)
            .and_then(|id| boxes.get(usize::from(id)).copied().flatten())
            .map_or(0, |b| saturate(b.y1))
    };
    os2.ul_code_page_range_1.get_or_insert(1);
    os2.ul_code_page_range_2.get_or_insert(0);
    os2.sx_height.get_or_insert_with(|| top('x'));
    os2.s_cap_height.get_or_insert_with(|| top('H'));
    os2.us_default_char.get_or_insert(0);
    os2.us_break_char.get_or_insert(32);
    os2.us_max_context.get_or_insert(0);
    Ok(os2)
}

/// An `OS/2` table for a source without one (older Mac fonts): the vertical metrics of
/// `hhea` and the glyph boxes, the average advance, the character range of the `cmap`, a
/// regular weight and width, installable embedding.
fn synthesized_os2(
    font: &FontRef,
    outlines: &FontOutlines,
    boxes: &[Option<Rect>],
) -> Result<Os2, Error> {
    let hhea = font.hhea().map_err(|e| Error::Font(format!("hhea: {e}")))?;
    let upem = outlines.units_per_em();
    let (ascender, descender) = (hhea.ascender().to_i16(), hhea.descender().to_i16());
    let all = boxes
        .iter()
        .flatten()
        .copied()
        .reduce(|a, b| a.union(b))
        .unwrap_or_default();
    let advances: Vec<f64> = (0..outlines.glyph_count())
        .map(|id| outlines.advance(id))
        .filter(|&a| a > 0.0)
        .collect();
    let average = advances.iter().sum::<f64>() / advances.len().max(1) as f64;
    let chars: Vec<u32> = outlines
        .char_map()
        .values()
        .flatten()
        .map(|&c| c as u32)
        .collect();
    let em = |f: f64| saturate(f * upem);
    Ok(Os2 {
        x_avg_char_width: saturate(average),
        y_subscript_x_size: em(0.65),
        y_subscript_y_size: em(0.6),
        y_subscript_y_offset: em(0.075),
        y_superscript_x_size: em(0.65),
        y_superscript_y_size: em(0.6),
        y_superscript_y_offset: em(0.35),
        y_strikeout_size: em(0.05),
        y_strikeout_position: em(0.26),
        ach_vend_id: Tag::new(b"NONE"),
        fs_selection: write_fonts::tables::os2::SelectionFlags::REGULAR,
        us_first_char_index: chars.iter().copied().min().unwrap_or(0).min(0xFFFF) as u16,
        us_last_char_index: chars.iter().copied().max().unwrap_or(0).min(0xFFFF) as u16,
        s_typo_ascender: ascender,
        s_typo_descender: descender,
        s_typo_line_gap: hhea.line_gap().to_i16(),
        us_win_ascent: saturate(all.y1.max(f64::from(ascender))).max(0) as u16,
        us_win_descent: saturate((-all.y0).max(-f64::from(descender))).max(0) as u16,
        ..Os2::default()
    })
}

/// The family and style names of the rebuilt font: [`RebuildOptions::family`] (or
/// [`super::FONT_FAMILY`]), and the source's subfamily where it is one of the four basic
/// styles (else "Regular").
pub(super) fn family_and_style(font: &FontRef, options: &RebuildOptions) -> (String, String) {
    let family = if options.family.trim().is_empty() {
        super::FONT_FAMILY.to_owned()
    } else {
        options.family.trim().to_owned()
    };
    let style = font
        .name()
        .ok()
        .and_then(|name| {
            name.name_record()
                .iter()
                .find(|r| r.name_id() == NameId::SUBFAMILY_NAME && r.platform_id() == 3)
                .and_then(|r| r.string(name.string_data()).ok())
                .map(|s| s.chars().collect::<String>())
        })
        .filter(|s| ["Regular", "Bold", "Italic", "Bold Italic"].contains(&s.as_str()))
        .unwrap_or_else(|| "Regular".to_owned());
    (family, style)
}

/// The PostScript name: `Family-Style` in printable ASCII without spaces or the characters
/// PostScript reserves, at most 63 characters.
pub(super) fn postscript_name(family: &str, style: &str) -> String {
    format!("{family}-{style}")
        .chars()
        .filter(|c| c.is_ascii_graphic() && !"[](){}<>/%".contains(*c))
        .take(63)
        .collect()
}

/// The `name` table: the source's records but those naming the family (IDs 1–6, 16–18,
/// 21, 22, 25), and IDs 1–6 for the new family (Windows, English).
fn name_of(font: &FontRef, options: &RebuildOptions, revision: f64) -> Result<Name, Error> {
    let (family, style) = family_and_style(font, options);
    let source: Name = match font.name() {
        Ok(n) => n.to_owned_table(),
        Err(_) => Name::default(),
    };
    let naming = [1u16, 2, 3, 4, 5, 6, 16, 17, 18, 21, 22, 25];
    let mut records: Vec<NameRecord> = source
        .name_record
        .into_iter()
        .filter(|r| !naming.contains(&r.name_id.to_u16()))
        .collect();
    let ps = postscript_name(&family, &style);
    let version = format!("Version {revision:.3}");
    for (id, text) in [
        (NameId::FAMILY_NAME, family.clone()),
        (NameId::SUBFAMILY_NAME, style.clone()),
        (NameId::UNIQUE_ID, format!("{revision:.3};KAPPA;{ps}")),
        (NameId::FULL_NAME, format!("{family} {style}")),
        (NameId::VERSION_STRING, version),
        (NameId::POSTSCRIPT_NAME, ps.clone()),
    ] {
        records.push(NameRecord::new(3, 1, 0x409, id, text.into()));
    }
    records.sort_by_key(|r| (r.platform_id, r.encoding_id, r.language_id, r.name_id));
    Ok(Name::new(records))
}

/// The glyph names of the source (its `post` table or CFF charset), made unique; a glyph
/// without one is `glyphNNNNN`.
pub(super) fn glyph_names(outlines: &FontOutlines, num_glyphs: u16) -> Vec<String> {
    let mut seen = std::collections::HashSet::new();
    (0..num_glyphs)
        .map(|id| {
            let base = match outlines.glyph_name(id) {
                Some(n) if !n.is_empty() => n.to_owned(),
                _ if id == 0 => ".notdef".to_owned(),
                _ => format!("glyph{id:05}"),
            };
            let mut name = base.clone();
            let mut k = 1;
            while !seen.insert(name.clone()) {
                name = format!("{base}.{k}");
                k += 1;
            }
            name
        })
        .collect()
}

/// `post` format 2 with the source's glyph names (from its `post` table or its CFF
/// charset), made unique; the source's italic angle and underline kept.
fn post_of(font: &FontRef, outlines: &FontOutlines, num_glyphs: u16) -> Result<Post, Error> {
    let names = glyph_names(outlines, num_glyphs);
    let mut post = Post::new_v2(names.iter().map(String::as_str));
    if let Ok(source) = font.post() {
        post.italic_angle = source.italic_angle();
        post.underline_position = source.underline_position();
        post.underline_thickness = source.underline_thickness();
        post.is_fixed_pitch = source.is_fixed_pitch();
    }
    Ok(post)
}
