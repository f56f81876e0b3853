//! The file of a drawing (feature `serde`): JSON, on its own or kept inside an SVG export so
//! that the SVG opens for editing again.

use serde::{Deserialize, Serialize};

use super::{Drawing, PathDoc};
use crate::Error;

/// The `id` of the SVG `<metadata>` element that holds the drawing's JSON.
pub const SVG_METADATA_ID: &str = "kappa-document";

/// The most points a file may hold (over all contours): more is refused rather than solved.
pub(super) const MAX_POINTS: usize = 100_000;

/// The file of a [`Drawing`]: its contours, each a [`PathDoc`] with its points, shapes,
/// corners, closed flag, scheme and saved solution.
///
/// [`DrawingDoc::from_json`] also reads a single [`PathDoc`] (the file of one path, as
/// written before drawings had several contours) and a bare array of them.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct DrawingDoc {
    /// The contours in order.
    pub contours: Vec<PathDoc>,
}

impl DrawingDoc {
    /// The file of `drawing`.
    pub fn of(drawing: &Drawing) -> DrawingDoc {
        DrawingDoc {
            contours: drawing.docs(),
        }
    }

    /// Reads a drawing file, a single path's document or an array of them.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidInput`] when the text is not one of these, or holds more than
    /// 100 000 points.
    pub fn from_json(text: &str) -> Result<DrawingDoc, Error> {
        let bad = |e: serde_json::Error| Error::InvalidInput(format!("invalid drawing JSON: {e}"));
        let value: serde_json::Value = serde_json::from_str(text).map_err(bad)?;
        let doc = if value.get("contours").is_some() {
            serde_json::from_value(value).map_err(bad)?
        } else if value.is_array() {
            DrawingDoc {
                contours: serde_json::from_value(value).map_err(bad)?,
            }
        } else if value.get("points").is_some() {
            DrawingDoc {
                contours: vec![serde_json::from_value(value).map_err(bad)?],
            }
        } else {
            return Err(Error::InvalidInput(
                "invalid drawing JSON: neither \"contours\" nor \"points\"".into(),
            ));
        };
        let points: usize = doc.contours.iter().map(|c| c.points.len()).sum();
        if points > MAX_POINTS {
            return Err(Error::InvalidInput(format!(
                "the drawing has {points} points, more than {MAX_POINTS}"
            )));
        }
        Ok(doc)
    }

    /// The file as JSON.
    pub fn to_json(&self) -> String {
        // A document of numbers and strings always serialises (the coordinates of an
        // edited document are finite: the editor refuses others).
        serde_json::to_string(self).unwrap_or_default()
    }
}

impl Drawing {
    /// The drawing as an SVG document like [`Drawing::to_svg`], with its file
    /// ([`DrawingDoc`]) inside a `<metadata id="kappa-document">` element, so that
    /// [`extract_svg_document`] restores the editable drawing.
    pub fn to_svg_with_document(&self, width: f64, height: f64, fill: bool) -> String {
        let svg = self.to_svg(width, height, fill);
        let json = DrawingDoc::of(self).to_json();
        let mut escaped = String::with_capacity(json.len());
        for c in json.chars() {
            match c {
                '&' => escaped.push_str("&amp;"),
                '<' => escaped.push_str("&lt;"),
                '>' => escaped.push_str("&gt;"),
                c => escaped.push(c),
            }
        }
        let meta = format!("<metadata id=\"{SVG_METADATA_ID}\">{escaped}</metadata>\n");
        match svg.find(">\n") {
            Some(i) => format!("{}{meta}{}", &svg[..i + 2], &svg[i + 2..]),
            None => svg,
        }
    }
}

/// The drawing kept in an SVG written by [`Drawing::to_svg_with_document`].
///
/// # Errors
///
/// [`Error::InvalidSvg`] when the SVG holds no such element; the errors of
/// [`DrawingDoc::from_json`] for its content.
pub fn extract_svg_document(svg: &str) -> Result<DrawingDoc, Error> {
    let missing = || Error::InvalidSvg("no kappa document in this SVG".into());
    let xml = roxmltree::Document::parse(svg).map_err(|e| Error::InvalidSvg(e.to_string()))?;
    let meta = xml
        .descendants()
        .find(|n| n.attribute("id") == Some(SVG_METADATA_ID))
        .ok_or_else(missing)?;
    // The element's text, entities decoded and CDATA sections included.
    let json: String = meta
        .children()
        .filter(roxmltree::Node::is_text)
        .filter_map(|t| t.text())
        .collect();
    DrawingDoc::from_json(json.trim())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Scheme;
    use kurbo::Point;

    #[test]
    fn old_single_path_documents_load() {
        let old = r#"{"points":[{"x":0,"y":0,"shape":0.8},{"x":10,"y":5,"shape":0.8,
            "corner":true},{"x":20,"y":0,"shape":0.8}],"closed":false,"scheme":"ek-cubic"}"#;
        let doc = DrawingDoc::from_json(old).unwrap();
        assert_eq!(doc.contours.len(), 1);
        assert!(doc.contours[0].points[1].corner);
        let many = format!("[{old},{old}]");
        assert_eq!(DrawingDoc::from_json(&many).unwrap().contours.len(), 2);
        for bad in [
            "",
            "{}",
            "[1]",
            "{\"contours\":3}",
            "{\"points\":[{\"x\":1e999}]}",
        ] {
            assert!(
                matches!(DrawingDoc::from_json(bad), Err(Error::InvalidInput(_))),
                "{bad}"
            );
        }
    }

    #[test]
    fn drawings_round_trip_through_json_and_svg() {
        let mut d = Drawing::new(Scheme::EkTrig);
        for (r, n) in [(100.0, 5), (50.0, 4)] {
            let (k, _) = d.start_contour(Point::new(200.0 + r, 200.0));
            for i in 1..n {
                let th = i as f64 / n as f64 * std::f64::consts::TAU;
                d.add_point(k, Point::new(200.0 + r * th.cos(), 200.0 + r * th.sin()));
            }
            d.set_closed(k, true);
        }
        d.toggle_corner(0, 2);
        let doc = DrawingDoc::of(&d);
        let back = DrawingDoc::from_json(&doc.to_json()).unwrap();
        assert_eq!(back, doc);
        // The saved solutions reopen the same curves.
        let (again, changes) = Drawing::from_docs(back.contours, Scheme::Kappa);
        assert!(changes.iter().all(|c| c.errors.is_empty()));
        let (a, b) = (again.outline(), d.outline());
        assert_eq!(a.elements().len(), b.elements().len());
        let far = a
            .elements()
            .iter()
            .zip(b.elements())
            .flat_map(|(x, y)| {
                let (x, y) = (x.end_point(), y.end_point());
                x.zip(y).map(|(x, y)| (x - y).hypot())
            })
            .fold(0.0, f64::max);
        assert!(far < 1e-9, "{far}");
        let svg = d.to_svg_with_document(400.0, 400.0, true);
        assert!(svg.contains("<metadata id=\"kappa-document\">"));
        assert_eq!(extract_svg_document(&svg).unwrap(), doc);
        assert!(matches!(
            extract_svg_document("<svg/>"),
            Err(Error::InvalidSvg(_))
        ));
    }
}
