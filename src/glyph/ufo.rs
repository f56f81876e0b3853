//! A whole font written as a UFO 3 source with drafted outlines.

use std::collections::HashMap;
use std::path::Path;

use kurbo::{BezPath, PathEl};
use write_fonts::read::tables::glyf::{Anchor, Glyph as RGlyph};
use write_fonts::read::{FontRef, TableProvider};
use write_fonts::types::{GlyphId, NameId};

use super::direction::{orient, Direction};
use super::export::{to_norad_glyph, FontGlyph};
use super::import::FontOutlines;
use super::rebuild::{family_and_style, glyph_names, RebuildOptions};
use crate::Error;

/// The key of the glyph lib entry that holds a drafted glyph's κ source (see
/// [`rebuild_ufo`]).
pub const KAPPA_LIB_KEY: &str = "org.kappa.contours";

/// Writes `source` (TrueType or CFF-flavoured OpenType) as a UFO 3 source in `dir`
/// (replacing it), with the outlines of the glyph ids in `replaced` swapped for the given
/// ones (font units, y up).
///
/// - **Glyphs:** every glyph of the source, in glyph-id order (`public.glyphOrder`), under
///   its `post`/CFF name, with all the characters the `cmap` maps to it and its advance.
///   Outlines are cubic curves, quadratics raised to the cubics that trace them exactly
///   (fontmake's default overlap removal takes cubics only), turned PostScript's way ([`Direction::PostScript`]: outer contours
///   counter-clockwise); composite glyphs of a TrueType source stay components.
/// - **κ sources:** `lib` holds, per replaced glyph, the string given in `sources` under
///   [`KAPPA_LIB_KEY`] (a JSON document the caller chooses).
/// - **fontinfo:** the family of [`RebuildOptions::family`], the source's style,
///   `unitsPerEm`, ascender, descender, `xHeight`, `capHeight`, version, copyright and
///   licence, italic angle, underline, and the `OS/2`/`hhea` vertical metrics.
///
/// # Errors
///
/// [`Error::Font`] for a font that cannot be read or a UFO that cannot be written.
pub fn rebuild_ufo(
    source: &[u8],
    replaced: &HashMap<u16, BezPath>,
    sources: &HashMap<u16, String>,
    options: &RebuildOptions,
    dir: &Path,
) -> Result<(), Error> {
    let font =
        FontRef::new(source).map_err(|e| Error::Font(format!("cannot read the font: {e}")))?;
    let outlines = FontOutlines::parse(source)?;
    let n = outlines.glyph_count();
    let names = glyph_names(&outlines, n);
    let chars = outlines.char_map();
    let glyf = font.glyf().ok().zip(font.loca(None).ok());
    let mut ufo = norad::Font::new();
    for id in 0..n {
        let name = &names[usize::from(id)];
        let composite = match (replaced.contains_key(&id), &glyf) {
            (false, Some((glyf, loca))) => match loca.get_glyf(GlyphId::new(id.into()), glyf) {
                Ok(Some(RGlyph::Composite(c))) => Some(c),
                _ => None,
            },
            _ => None,
        };
        let mut glyph = match composite {
            Some(c) => {
                let mut g = norad::Glyph::new(name);
                for comp in c.components() {
                    let base = names.get(comp.glyph.to_u32() as usize).ok_or_else(|| {
                        Error::Font(format!("glyph {id}: component out of range"))
                    })?;
                    let (dx, dy) = match comp.anchor {
                        Anchor::Offset { x, y } => (f64::from(x), f64::from(y)),
                        // Point-matched components: placed where the outline reader puts them.
                        Anchor::Point { .. } => (0.0, 0.0),
                    };
                    let t = comp.transform;
                    let transform = norad::AffineTransform {
                        x_scale: f64::from(t.xx.to_f32()),
                        xy_scale: f64::from(t.yx.to_f32()),
                        yx_scale: f64::from(t.xy.to_f32()),
                        y_scale: f64::from(t.yy.to_f32()),
                        x_offset: dx,
                        y_offset: dy,
                    };
                    let base = norad::Name::new(base)
                        .map_err(|e| Error::Font(format!("glyph name {base}: {e}")))?;
                    g.components
                        .push(norad::Component::new(base, transform, None));
                }
                g
            }
            None => {
                let path = match replaced.get(&id) {
                    Some(p) => p.clone(),
                    None => outlines.outline(id)?,
                };
                let path = cubic(&closed_only(&orient(&path, Direction::PostScript)));
                to_norad_glyph(&FontGlyph {
                    name: name.clone(),
                    ch: '\0',
                    path,
                    advance: 0.0,
                })
            }
        };
        glyph.width = outlines.advance(id);
        glyph.codepoints = chars.get(&id).into_iter().flatten().copied().collect();
        if let Some(text) = sources.get(&id) {
            glyph
                .lib
                .insert(KAPPA_LIB_KEY.into(), plist::Value::String(text.clone()));
        }
        ufo.default_layer_mut().insert_glyph(glyph);
    }
    let order: Vec<plist::Value> = names.iter().cloned().map(plist::Value::String).collect();
    ufo.lib
        .insert("public.glyphOrder".into(), plist::Value::Array(order));
    fill_info(&mut ufo.font_info, &font, &outlines, options);
    ufo.save(dir)
        .map_err(|e| Error::Font(format!("cannot write {}: {e}", dir.display())))
}

/// The path with every quadratic raised to the cubic that traces it exactly (fontmake's
/// default overlap removal handles cubics only).
fn cubic(path: &BezPath) -> BezPath {
    let mut out = BezPath::new();
    let mut last = kurbo::Point::ZERO;
    for el in path.elements() {
        match *el {
            PathEl::QuadTo(p1, p2) => {
                let c = kurbo::QuadBez::new(last, p1, p2).raise();
                out.curve_to(c.p1, c.p2, c.p3);
            }
            el => out.push(el),
        }
        if let Some(p) = el.end_point() {
            last = p;
        }
    }
    out
}

/// The path with every subpath closed (UFO contours of an outline are closed).
fn closed_only(path: &BezPath) -> BezPath {
    let mut out = BezPath::new();
    let mut open = false;
    for el in path.elements() {
        match el {
            PathEl::MoveTo(_) if open => {
                out.close_path();
                out.push(*el);
            }
            PathEl::MoveTo(_) => {
                open = true;
                out.push(*el);
            }
            PathEl::ClosePath => {
                open = false;
                out.push(*el);
            }
            _ => out.push(*el),
        }
    }
    if open {
        out.close_path();
    }
    out
}

/// fontinfo.plist from the source's tables.
fn fill_info(
    info: &mut norad::FontInfo,
    font: &FontRef,
    outlines: &FontOutlines,
    options: &RebuildOptions,
) {
    let (family, style) = family_and_style(font, options);
    info.family_name = Some(family.clone());
    info.style_name = Some(style.clone());
    info.postscript_font_name = Some(super::rebuild::postscript_name(&family, &style));
    info.units_per_em = norad::fontinfo::NonNegativeIntegerOrFloat::new(outlines.units_per_em());
    let top = |ch: char| {
        outlines
            .glyph_id(ch)
            .and_then(|id| outlines.outline(id).ok())
            .map(|p| kurbo::Shape::bounding_box(&p).y1.round())
    };
    if let Ok(head) = font.head() {
        let rev = head.font_revision().to_f64();
        info.version_major = Some(rev.trunc() as i32);
        info.version_minor = Some(((rev.fract() * 1000.0).round() as u32).min(999));
    }
    if let Ok(hhea) = font.hhea() {
        info.open_type_hhea_ascender = Some(hhea.ascender().to_i16().into());
        info.open_type_hhea_descender = Some(hhea.descender().to_i16().into());
        info.open_type_hhea_line_gap = Some(hhea.line_gap().to_i16().into());
    }
    match font.os2() {
        Ok(os2) => {
            info.ascender = Some(f64::from(os2.s_typo_ascender()));
            info.descender = Some(f64::from(os2.s_typo_descender()));
            info.open_type_os2_typo_ascender = Some(os2.s_typo_ascender().into());
            info.open_type_os2_typo_descender = Some(os2.s_typo_descender().into());
            info.open_type_os2_typo_line_gap = Some(os2.s_typo_line_gap().into());
            info.open_type_os2_win_ascent = Some(os2.us_win_ascent().into());
            info.open_type_os2_win_descent = Some(os2.us_win_descent().into());
            info.open_type_os2_weight_class = Some(os2.us_weight_class().into());
            info.x_height = os2
                .sx_height()
                .map(f64::from)
                .filter(|&h| h > 0.0)
                .or(top('x'));
            info.cap_height = os2
                .s_cap_height()
                .map(f64::from)
                .filter(|&h| h > 0.0)
                .or(top('H'));
        }
        Err(_) => {
            info.ascender = Some(outlines.ascender());
            info.descender = Some(outlines.descender());
            info.x_height = top('x');
            info.cap_height = top('H');
        }
    }
    if let Ok(post) = font.post() {
        info.italic_angle = Some(post.italic_angle().to_f64());
        info.postscript_underline_position = Some(post.underline_position().to_i16().into());
        info.postscript_underline_thickness = Some(post.underline_thickness().to_i16().into());
    }
    if let Ok(name) = font.name() {
        let get = |id: NameId| {
            name.name_record()
                .iter()
                .find(|r| r.name_id() == id && r.platform_id() == 3)
                .and_then(|r| r.string(name.string_data()).ok())
                .map(|s| s.chars().collect::<String>())
        };
        info.copyright = get(NameId::COPYRIGHT_NOTICE);
        info.open_type_name_license = get(NameId::LICENSE_DESCRIPTION);
        info.open_type_name_license_url = get(NameId::LICENSE_URL);
        info.trademark = get(NameId::TRADEMARK);
        info.open_type_name_designer = get(NameId::DESIGNER);
        info.open_type_name_manufacturer = get(NameId::MANUFACTURER);
    }
}
