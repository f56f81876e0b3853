//! SVG import of path vertices (feature `render`, through usvg).

use kurbo::Point;
use resvg::usvg;

use super::{EditPoint, PathDoc};
use crate::{Error, Scheme};

/// The vertices of every path, polyline and polygon of an SVG document as path documents
/// (one per subpath, in document order), in the document's user space after all transforms:
/// a designer's rough polygon becomes the points of a curve. The end points of every
/// segment are taken (control points of curves are not); a closed subpath gives a closed
/// path, without repeating its first point. Coordinates pass through usvg's `f32` geometry.
/// Shapes are `scheme`'s default.
///
/// # Errors
///
/// [`Error::InvalidSvg`] when the text is not SVG usvg can read.
pub fn import_svg(text: &str, scheme: Scheme) -> Result<Vec<PathDoc>, Error> {
    let tree = usvg::Tree::from_str(text, &usvg::Options::default())
        .map_err(|e| Error::InvalidSvg(e.to_string()))?;
    let mut out = Vec::new();
    collect(tree.root(), scheme, &mut out);
    Ok(out)
}

fn collect(group: &usvg::Group, scheme: Scheme, out: &mut Vec<PathDoc>) {
    for node in group.children() {
        match node {
            usvg::Node::Group(g) => collect(g, scheme, out),
            usvg::Node::Path(path) => {
                let ts = path.abs_transform();
                let map = |p: usvg::tiny_skia_path::Point| {
                    let (x, y) = (f64::from(p.x), f64::from(p.y));
                    Point::new(
                        f64::from(ts.sx) * x + f64::from(ts.kx) * y + f64::from(ts.tx),
                        f64::from(ts.ky) * x + f64::from(ts.sy) * y + f64::from(ts.ty),
                    )
                };
                let mut current: Vec<Point> = Vec::new();
                let mut flush = |pts: &mut Vec<Point>, closed: bool| {
                    if closed && pts.len() > 1 && pts.first() == pts.last() {
                        pts.pop();
                    }
                    if !pts.is_empty() {
                        out.push(doc_of(pts, closed, scheme));
                    }
                    pts.clear();
                };
                use usvg::tiny_skia_path::PathSegment as S;
                for seg in path.data().segments() {
                    match seg {
                        S::MoveTo(p) => {
                            flush(&mut current, false);
                            current.push(map(p));
                        }
                        S::LineTo(p) | S::QuadTo(_, p) | S::CubicTo(_, _, p) => {
                            current.push(map(p))
                        }
                        S::Close => flush(&mut current, true),
                    }
                }
                flush(&mut current, false);
            }
            _ => {}
        }
    }
}

fn doc_of(pts: &[Point], closed: bool, scheme: Scheme) -> PathDoc {
    PathDoc {
        points: pts
            .iter()
            .map(|p| EditPoint {
                x: p.x,
                y: p.y,
                shape: scheme.neutral_shape(),
                corner: false,
                tangent: None,
                tangent_in: None,
            })
            .collect(),
        closed,
        scheme,
        solution: Vec::new(),
    }
}
