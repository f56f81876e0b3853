//! Drafted outlines out: TrueType quadratic contours, the integer grid, SVG, and (feature
//! `font`) UFO glyphs through norad.

use std::fmt::Write as _;

use kurbo::{BezPath, ParamCurve, ParamCurveNearest, PathEl, PathSeg, Point, QuadBez};

use crate::Error;

/// An outline made of lines and quadratic Béziers, as a TrueType `glyf` table stores it.
#[derive(Clone, Debug)]
pub struct Quadratic {
    /// The path: `MoveTo`, `LineTo`, `QuadTo` and `ClosePath` only.
    pub path: BezPath,
    /// The tolerance requested for cubics.
    pub tolerance: f64,
    /// The largest distance measured from a cubic of the input to its quadratics (16
    /// samples per cubic, exact nearest points); 0 when the input had no cubics.
    pub max_error: f64,
    /// Whether the conversion was exact (the input had no cubics).
    pub exact: bool,
}

/// The outline as TrueType quadratics.
///
/// Lines and quadratics (κ-curves) are copied exactly. Each cubic (εκ-cubic segments; fitted
/// εκ-trig curves) becomes a G1 quadratic spline through kurbo's `CubicBez::approx_spline`
/// (the cu2qu method: the fewest quadratics, up to 16, within `tolerance`), or kurbo's
/// `CubicBez::to_quads` when no spline of at most 16 pieces is within it; the distance
/// actually reached is measured ([`Quadratic::max_error`]).
///
/// # Errors
///
/// [`Error::InvalidOption`] for a tolerance that is not finite and positive.
pub fn to_quadratic(path: &BezPath, tolerance: f64) -> Result<Quadratic, Error> {
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(Error::InvalidOption(
            "quadratic tolerance must be finite and positive",
        ));
    }
    let mut out = BezPath::new();
    let mut max_error = 0.0f64;
    let mut exact = true;
    let mut last = Point::ZERO;
    for el in path.elements() {
        match *el {
            PathEl::CurveTo(p1, p2, p3) => {
                exact = false;
                let c = kurbo::CubicBez::new(last, p1, p2, p3);
                let quads: Vec<QuadBez> = match c.approx_spline(tolerance) {
                    Some(spline) => spline.to_quads().collect(),
                    None => c.to_quads(tolerance).map(|(_, _, q)| q).collect(),
                };
                for k in 0..=16 {
                    let p = c.eval(k as f64 / 16.0);
                    let d = quads
                        .iter()
                        .map(|q| q.nearest(p, 1e-9).distance_sq)
                        .fold(f64::INFINITY, f64::min);
                    max_error = max_error.max(d.sqrt());
                }
                for q in quads {
                    out.quad_to(q.p1, q.p2);
                }
                last = p3;
            }
            el => {
                if let Some(p) = el.end_point() {
                    last = p;
                }
                out.push(el);
            }
        }
    }
    Ok(Quadratic {
        path: out,
        tolerance,
        max_error,
        exact,
    })
}

/// A standalone SVG document of an outline in font units (y up): the path filled with the
/// non-zero rule, flipped by a `scale(1 -1)` transform so that it shows upright, in a view of
/// its bounding box with a margin of `margin` font units.
pub fn to_svg(path: &BezPath, margin: f64) -> String {
    let b = kurbo::Shape::bounding_box(path);
    let m = if margin.is_finite() {
        margin.max(0.0)
    } else {
        0.0
    };
    let (x0, y0, w, h) = if b.is_finite() && !path.elements().is_empty() {
        (
            b.x0 - m,
            -b.y1 - m,
            b.width() + 2.0 * m,
            b.height() + 2.0 * m,
        )
    } else {
        (0.0, 0.0, 1.0, 1.0)
    };
    let mut s = String::new();
    let _ = write!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{x0} {y0} {w} {h}\">\n\
         <path transform=\"scale(1 -1)\" fill=\"black\" fill-rule=\"nonzero\" d=\"{}\"/>\n</svg>\n",
        path.to_svg()
    );
    s
}

#[cfg(feature = "font")]
pub use ufo::{from_glif, to_glif, to_norad_glyph, write_ufo, FontGlyph};

#[cfg(feature = "font")]
mod ufo {
    use std::path::Path;

    use kurbo::{BezPath, ParamCurve, PathEl, Point};
    use norad::{Contour, ContourPoint, PointType};

    use crate::analysis::continuity;
    use crate::Error;

    /// One glyph of a UFO or a compiled font.
    #[derive(Clone, Debug, PartialEq)]
    pub struct FontGlyph {
        /// The glyph name (for example `"a"`, `"S"`).
        pub name: String,
        /// The character it stands for.
        pub ch: char,
        /// The outline in font units (y up).
        pub path: BezPath,
        /// The horizontal advance in font units.
        pub advance: f64,
    }

    /// The glyph as a norad [`norad::Glyph`]: one contour per subpath — closed contours
    /// (`ClosePath`) list their start point last, as UFO does, open ones start with a `move`
    /// point — with `line`, `qcurve` (one off-curve point) and `curve` (two) points, and
    /// on-curve points marked `smooth` where the tangent turns by less than 1e-6 rad.
    pub fn to_norad_glyph(glyph: &FontGlyph) -> norad::Glyph {
        let mut out = norad::Glyph::new(&glyph.name);
        out.width = glyph.advance;
        out.codepoints.insert(glyph.ch);
        for (segs, closed) in super::super::contours(&glyph.path) {
            let n = segs.len();
            if n == 0 {
                continue;
            }
            let smooth = |j: usize| -> bool {
                // Joint after segment j.
                if !closed && j + 1 == n {
                    return false;
                }
                continuity(&segs[j], &segs[(j + 1) % n]).tangent_angle < 1e-6
            };
            let mut points = Vec::new();
            let on = |p: Point, typ: PointType, smooth: bool| {
                ContourPoint::new(p.x, p.y, typ, smooth, None, None)
            };
            let off =
                |p: Point| ContourPoint::new(p.x, p.y, PointType::OffCurve, false, None, None);
            if !closed {
                points.push(on(segs[0].start(), PointType::Move, false));
            }
            for (j, seg) in segs.iter().enumerate() {
                let sm = smooth(j);
                match *seg {
                    kurbo::PathSeg::Line(l) => points.push(on(l.p1, PointType::Line, sm)),
                    kurbo::PathSeg::Quad(q) => {
                        points.push(off(q.p1));
                        points.push(on(q.p2, PointType::QCurve, sm));
                    }
                    kurbo::PathSeg::Cubic(c) => {
                        points.push(off(c.p1));
                        points.push(off(c.p2));
                        points.push(on(c.p3, PointType::Curve, sm));
                    }
                }
            }
            out.contours.push(Contour::new(points, None));
        }
        out
    }

    /// The glyph as `.glif` XML (UFO 3, glif format 2).
    ///
    /// # Errors
    ///
    /// [`Error::Font`] when norad cannot encode it (an invalid glyph name).
    pub fn to_glif(glyph: &FontGlyph) -> Result<String, Error> {
        let bytes = to_norad_glyph(glyph)
            .encode_xml()
            .map_err(|e| Error::Font(format!("cannot encode glyph {}: {e}", glyph.name)))?;
        String::from_utf8(bytes).map_err(|e| Error::Font(format!("glif is not utf-8: {e}")))
    }

    /// The outline of a `.glif` read back with norad. norad's `Contour::to_kurbo` leaves
    /// closed contours open; this closes them, so that a closed contour reads back as
    /// `MoveTo … ClosePath` with its start point where [`to_norad_glyph`] put it.
    ///
    /// # Errors
    ///
    /// [`Error::Font`] for XML that norad rejects.
    pub fn from_glif(xml: &str) -> Result<BezPath, Error> {
        let glyph = norad::Glyph::parse_raw(xml.as_bytes())
            .map_err(|e| Error::Font(format!("cannot read glif: {e}")))?;
        let mut path = BezPath::new();
        for contour in &glyph.contours {
            let sub = contour
                .to_kurbo()
                .map_err(|e| Error::Font(format!("bad contour: {e}")))?;
            path.extend(sub.elements().iter().copied());
            if contour.is_closed() {
                path.push(PathEl::ClosePath);
            }
        }
        Ok(path)
    }

    /// Writes a UFO 3 source to the directory `dir` (replacing it): `fontinfo.plist` with the
    /// family name and the em, and one glyph per entry in the default layer.
    ///
    /// # Errors
    ///
    /// [`Error::Font`] when norad cannot write (an I/O error, a duplicate glyph name).
    pub fn write_ufo(
        dir: &Path,
        family: &str,
        units_per_em: f64,
        glyphs: &[FontGlyph],
    ) -> Result<(), Error> {
        let mut font = norad::Font::new();
        font.font_info.family_name = Some(family.to_owned());
        font.font_info.units_per_em = norad::fontinfo::NonNegativeIntegerOrFloat::new(units_per_em);
        let layer = font.default_layer_mut();
        for g in glyphs {
            if layer.get_glyph(&g.name).is_some() {
                return Err(Error::Font(format!("duplicate glyph name {}", g.name)));
            }
            layer.insert_glyph(to_norad_glyph(g));
        }
        font.save(dir)
            .map_err(|e| Error::Font(format!("cannot write {}: {e}", dir.display())))
    }
}

/// Whether a path holds only lines and quadratics (what a `glyf` table can store).
pub fn is_quadratic(path: &BezPath) -> bool {
    path.segments().all(|s| !matches!(s, PathSeg::Cubic(_)))
}
