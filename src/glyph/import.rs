//! Glyph outlines read from TrueType/OpenType fonts with ttf-parser.
//!
//! Coordinates are **font units, y up**, exactly as stored: ttf-parser reports the points of
//! the `glyf` (or `CFF`) outline in the glyph's own frame — x to the right, y up, the origin
//! on the baseline at the glyph's left side bearing origin — and this module only widens them
//! from `f32` to `f64` (exact). No scaling, no flip: to draw in y-down pixel coordinates apply
//! `Affine::new([s, 0, 0, -s, x0, y0])` (see [`crate::glyph`]).

use kurbo::BezPath;

use crate::outline::OutlinePath;
use crate::Error;

/// A font whose glyph outlines can be read, borrowing the font file's bytes.
#[derive(Clone)]
pub struct FontOutlines<'a> {
    face: ttf_parser::Face<'a>,
}

impl core::fmt::Debug for FontOutlines<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("FontOutlines")
            .field("units_per_em", &self.face.units_per_em())
            .field("glyphs", &self.face.number_of_glyphs())
            .finish()
    }
}

/// One glyph's outline.
#[derive(Clone, Debug, PartialEq)]
pub struct Glyph {
    /// The character it was looked up by.
    pub ch: char,
    /// Its glyph id in the font.
    pub id: u16,
    /// The outline in font units (y up): one closed subpath per contour, lines and quadratic
    /// Béziers for TrueType outlines (cubics for CFF), each contour ending back at its start.
    pub path: BezPath,
    /// The horizontal advance in font units.
    pub advance: f64,
}

impl<'a> FontOutlines<'a> {
    /// Parses the font (the first face of a collection).
    ///
    /// # Errors
    ///
    /// [`Error::Font`] when ttf-parser cannot read the data.
    pub fn parse(data: &'a [u8]) -> Result<FontOutlines<'a>, Error> {
        check_collection_header(data)?;
        ttf_parser::Face::parse(data, 0)
            .map(|face| FontOutlines { face })
            .map_err(|e| Error::Font(format!("cannot parse the font: {e}")))
    }

    /// The size of the em square in font units (2048 for DejaVu Sans).
    pub fn units_per_em(&self) -> f64 {
        f64::from(self.face.units_per_em())
    }

    /// The typographic ascender in font units.
    pub fn ascender(&self) -> f64 {
        f64::from(self.face.ascender())
    }

    /// The typographic descender in font units (negative below the baseline).
    pub fn descender(&self) -> f64 {
        f64::from(self.face.descender())
    }

    /// The glyph id the font maps `ch` to.
    pub fn glyph_id(&self, ch: char) -> Option<u16> {
        self.face.glyph_index(ch).map(|g| g.0)
    }

    /// Every character the font maps, by glyph id (in code point order).
    pub fn char_map(&self) -> std::collections::HashMap<u16, Vec<char>> {
        let mut map: std::collections::HashMap<u16, Vec<char>> = std::collections::HashMap::new();
        if let Some(cmap) = self.face.tables().cmap {
            for sub in cmap.subtables {
                if !sub.is_unicode() {
                    continue;
                }
                sub.codepoints(|cp| {
                    if let (Some(ch), Some(id)) = (char::from_u32(cp), sub.glyph_index(cp)) {
                        let chars = map.entry(id.0).or_default();
                        if !chars.contains(&ch) {
                            chars.push(ch);
                        }
                    }
                });
            }
        }
        for chars in map.values_mut() {
            chars.sort_unstable();
        }
        map
    }

    /// The number of glyphs.
    pub fn glyph_count(&self) -> u16 {
        self.face.number_of_glyphs()
    }

    /// The name of glyph `id` (from the `post` table or the CFF charset), if the font has
    /// one.
    pub fn glyph_name(&self, id: u16) -> Option<&str> {
        self.face.glyph_name(ttf_parser::GlyphId(id))
    }

    /// The advance width of glyph `id` in font units.
    pub fn advance(&self, id: u16) -> f64 {
        f64::from(
            self.face
                .glyph_hor_advance(ttf_parser::GlyphId(id))
                .unwrap_or(0),
        )
    }

    /// The outline of glyph `id` (components resolved), as [`FontOutlines::glyph`] reads it.
    ///
    /// # Errors
    ///
    /// [`Error::Font`] for a malformed outline.
    pub fn outline(&self, id: u16) -> Result<BezPath, Error> {
        let mut builder = OutlinePath(BezPath::new());
        let bbox = self
            .face
            .outline_glyph(ttf_parser::GlyphId(id), &mut builder);
        if bbox.is_none() && !builder.0.elements().is_empty() {
            return Err(Error::Font(format!(
                "the outline of glyph {id} is malformed"
            )));
        }
        Ok(builder.0)
    }

    /// The outline of the glyph the font maps `ch` to.
    ///
    /// # Errors
    ///
    /// [`Error::MissingGlyph`] when the font has no glyph for `ch`; [`Error::Font`] when the
    /// glyph's outline cannot be read. A glyph without contours (a space) gives an empty path.
    pub fn glyph(&self, ch: char) -> Result<Glyph, Error> {
        let id = self
            .face
            .glyph_index(ch)
            .ok_or(Error::MissingGlyph { ch })?;
        let mut builder = OutlinePath(BezPath::new());
        // `None` means "no outline" (empty glyph) or a malformed one; a glyph with a
        // bounding box but nothing drawn would be the latter.
        let bbox = self.face.outline_glyph(id, &mut builder);
        if bbox.is_none() && !builder.0.elements().is_empty() {
            return Err(Error::Font(format!("the outline of {ch:?} is malformed")));
        }
        let advance = f64::from(self.face.glyph_hor_advance(id).unwrap_or(0));
        Ok(Glyph {
            ch,
            id: id.0,
            path: builder.0,
            advance,
        })
    }
}

/// Rejects a font collection (`ttcf`) whose table of face offsets runs past the data.
///
/// ttf-parser reads that table with a length computed from the face count, and a count near
/// `u32::MAX` trips a `debug_assert!` there (a panic in debug builds) instead of its
/// "malformed font" error; found by the `font` fuzz target.
fn check_collection_header(data: &[u8]) -> Result<(), Error> {
    if data.len() >= 12 && &data[..4] == b"ttcf" {
        let faces = u32::from_be_bytes([data[8], data[9], data[10], data[11]]);
        if 12 + 4 * u64::from(faces) > data.len() as u64 {
            return Err(Error::Font(
                "cannot parse the font: the font collection's face table is truncated".into(),
            ));
        }
    }
    Ok(())
}
