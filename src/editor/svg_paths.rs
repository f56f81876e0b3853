//! SVG drawn elsewhere as a drawing (feature `serde`): the vertices of its shapes, in the
//! document's user space, read with roxmltree and svgtypes (no renderer needed, so the
//! browser's engine has it too).

use kurbo::{Affine, BezPath, PathEl, Point, Vec2};

use super::file::{DrawingDoc, MAX_POINTS};
use super::{EditPoint, PathDoc};
use crate::{Error, Scheme};

/// The sine of the largest turn between two segments that still counts as smooth: about 1°,
/// far above the rounding of coordinates written with a few decimals and below any corner
/// drawn on purpose.
const SMOOTH_SINE: f64 = 0.0175;

/// Elements whose content is not drawn where it stands (it is referenced, or it is not
/// geometry at all).
const NOT_DRAWN: [&str; 10] = [
    "defs", "clipPath", "mask", "marker", "pattern", "symbol", "metadata", "title", "desc", "style",
];

/// The vertices of the shapes of an SVG drawn elsewhere, as a drawing in `scheme` (the
/// shapes its default).
///
/// - Every `<path>`, `<polygon>`, `<polyline>`, `<line>`, `<rect>`, `<circle>` and
///   `<ellipse>` is read, in document order, with the `transform` of the element and of all
///   its ancestors applied (`matrix`, `translate`, `scale`, `rotate`, `skewX`, `skewY`). A
///   nested `<svg>` moves its content by its `x` and `y`; its `viewBox` is not applied.
/// - Each subpath becomes a contour through the end points of its segments (control points
///   are not taken), closed where the subpath is, without repeating its first point. A
///   rectangle gives its four corners, a circle or an ellipse its four extrema.
/// - A vertex where a curve segment meets another segment at a turn of more than about 1°
///   becomes a corner, so the straight stem of a `D` stays straight and the κ-curve is
///   solved on each side. Vertices between straight segments stay smooth: a polygon is read
///   as a sketch of a curve through its vertices.
/// - Content that is not drawn where it stands (`<defs>`, `<clipPath>`, `<mask>`,
///   `<symbol>`, `<marker>`, `<pattern>`) and elements with `display="none"` are skipped,
///   and so are lengths in units other than user units (`%`, `em`, `mm`, …).
///
/// # Errors
///
/// [`Error::InvalidSvg`] when the text is not XML, when no shape has a vertex, or when there
/// are more than 100 000 vertices.
///
/// # Examples
///
/// ```
/// use kappa::editor::import_svg_paths;
/// use kappa::Scheme;
///
/// let svg = r#"<svg xmlns="http://www.w3.org/2000/svg">
///   <g transform="translate(100 0)"><path d="M0 0 L10 0 L10 10 Z"/></g></svg>"#;
/// let doc = import_svg_paths(svg, Scheme::Kappa)?;
/// assert_eq!(doc.contours[0].points[1].x, 110.0);
/// # Ok::<(), kappa::Error>(())
/// ```
pub fn import_svg_paths(svg: &str, scheme: Scheme) -> Result<DrawingDoc, Error> {
    let xml = roxmltree::Document::parse(svg).map_err(|e| Error::InvalidSvg(e.to_string()))?;
    let mut contours = Vec::new();
    visit(
        xml.root_element(),
        Affine::IDENTITY,
        true,
        scheme,
        &mut contours,
    );
    let total: usize = contours.iter().map(|c: &PathDoc| c.points.len()).sum();
    if contours.is_empty() {
        return Err(Error::InvalidSvg("no path data in this SVG".into()));
    }
    if total > MAX_POINTS {
        return Err(Error::InvalidSvg(format!(
            "the paths have {total} vertices, more than {MAX_POINTS}"
        )));
    }
    Ok(DrawingDoc { contours })
}

/// Reads `node` and its descendants under the transform `outer` of its ancestors.
fn visit(node: roxmltree::Node, outer: Affine, root: bool, scheme: Scheme, out: &mut Vec<PathDoc>) {
    let name = node.tag_name().name();
    if NOT_DRAWN.contains(&name) || node.attribute("display") == Some("none") {
        return;
    }
    let mut ts = outer;
    if name == "svg" && !root {
        ts *= Affine::translate((number(node, "x"), number(node, "y")));
    }
    if let Some(t) = node.attribute("transform") {
        match t.parse::<svgtypes::Transform>() {
            Ok(t) => ts *= Affine::new([t.a, t.b, t.c, t.d, t.e, t.f]),
            // An element whose transform does not parse is not rendered (SVG 1.1, 7.5).
            Err(_) => return,
        }
    }
    if let Some(path) = shape(node) {
        contours_of(&(ts * path), scheme, out);
    }
    for child in node.children().filter(roxmltree::Node::is_element) {
        visit(child, ts, false, scheme, out);
    }
}

/// The geometry of a shape element, in its own coordinates.
fn shape(node: roxmltree::Node) -> Option<BezPath> {
    let poly = |closed: bool| {
        let mut path = BezPath::new();
        for (i, (x, y)) in svgtypes::PointsParser::from(node.attribute("points")?).enumerate() {
            if i == 0 {
                path.move_to((x, y));
            } else {
                path.line_to((x, y));
            }
        }
        if closed {
            path.close_path();
        }
        Some(path)
    };
    match node.tag_name().name() {
        "path" => BezPath::from_svg(node.attribute("d")?).ok(),
        "polygon" => poly(true),
        "polyline" => poly(false),
        "line" => {
            let mut path = BezPath::new();
            path.move_to((length(node, "x1")?, length(node, "y1")?));
            path.line_to((length(node, "x2")?, length(node, "y2")?));
            Some(path)
        }
        "rect" => {
            let (x, y) = (length(node, "x")?, length(node, "y")?);
            let (w, h) = (length(node, "width")?, length(node, "height")?);
            (w > 0.0 && h > 0.0)
                .then(|| kurbo::Shape::to_path(&kurbo::Rect::new(x, y, x + w, y + h), 0.1))
        }
        "circle" => {
            let r = length(node, "r")?;
            ellipse(length(node, "cx")?, length(node, "cy")?, r, r)
        }
        "ellipse" => ellipse(
            length(node, "cx")?,
            length(node, "cy")?,
            length(node, "rx")?,
            length(node, "ry")?,
        ),
        _ => None,
    }
}

/// An ellipse as four quarter arcs between its extrema.
fn ellipse(cx: f64, cy: f64, rx: f64, ry: f64) -> Option<BezPath> {
    if !(rx > 0.0 && ry > 0.0) {
        return None;
    }
    // The quarter arcs' handles: 4/3 tan(π/8) of the radius.
    let k = 4.0 / 3.0 * (core::f64::consts::PI / 8.0).tan();
    let mut path = BezPath::new();
    let at = |u: f64, v: f64| Point::new(cx + u * rx, cy + v * ry);
    path.move_to(at(1.0, 0.0));
    for (u, v) in [(0.0, 1.0), (-1.0, 0.0), (0.0, -1.0), (1.0, 0.0)] {
        // From the previous extremum (v, -u) rotated back by a quarter turn.
        let (pu, pv) = (v, -u);
        path.curve_to(
            at(pu + k * u, pv + k * v),
            at(u + k * pu, v + k * pv),
            at(u, v),
        );
    }
    path.close_path();
    Some(path)
}

/// A length attribute in user units (missing: 0, as SVG has it for coordinates); `None` for
/// other units or text that does not parse.
fn length(node: roxmltree::Node, name: &str) -> Option<f64> {
    let Some(text) = node.attribute(name) else {
        return Some(0.0);
    };
    let l: svgtypes::Length = text.parse().ok()?;
    matches!(
        l.unit,
        svgtypes::LengthUnit::None | svgtypes::LengthUnit::Px
    )
    .then_some(l.number)
}

/// A coordinate attribute in user units, 0 where missing or in other units.
fn number(node: roxmltree::Node, name: &str) -> f64 {
    length(node, name).unwrap_or(0.0)
}

/// One contour per subpath of `path`: its vertices, with corners where a curve meets another
/// segment at a turn.
fn contours_of(path: &BezPath, scheme: Scheme, out: &mut Vec<PathDoc>) {
    // Per vertex: the point, whether the segment into it is a curve, and the directions in
    // and out of it (zero where unknown).
    struct Vertex {
        p: Point,
        curve_in: bool,
        dir_in: Vec2,
        dir_out: Vec2,
    }
    let mut vertices: Vec<Vertex> = Vec::new();
    let flush = |vertices: &mut Vec<Vertex>, closed: bool, out: &mut Vec<PathDoc>| {
        if vertices.is_empty() {
            return;
        }
        let mut closed = closed;
        if closed
            && vertices.len() > 1
            && vertices.first().map(|v| v.p) == vertices.last().map(|v| v.p)
        {
            // The closing segment is drawn: the first vertex is entered by it.
            let last = vertices.pop().expect("two vertices");
            vertices[0].curve_in = last.curve_in;
            vertices[0].dir_in = last.dir_in;
        } else if closed {
            // The implicit closing line.
            let (first, last) = (vertices[0].p, vertices[vertices.len() - 1].p);
            let line = first - last;
            if let Some(v) = vertices.last_mut() {
                v.dir_out = line;
            }
            vertices[0].dir_in = line;
            vertices[0].curve_in = false;
        }
        if vertices.iter().any(|v| !v.p.is_finite()) {
            vertices.clear();
            return;
        }
        closed &= vertices.len() >= 3;
        let n = vertices.len();
        let points = (0..n)
            .map(|i| {
                let v = &vertices[i];
                // The segment out of `v` is a curve when the next vertex is entered by one.
                let curve_out = if i + 1 < n {
                    vertices[i + 1].curve_in
                } else {
                    closed && vertices[0].curve_in
                };
                let inner = closed || (i > 0 && i + 1 < n);
                let corner = inner && (v.curve_in || curve_out) && turns(v.dir_in, v.dir_out);
                EditPoint {
                    x: v.p.x,
                    y: v.p.y,
                    shape: scheme.neutral_shape(),
                    corner,
                    tangent: None,
                    tangent_in: None,
                }
            })
            .collect();
        out.push(PathDoc {
            points,
            closed,
            scheme,
            solution: Vec::new(),
        });
        vertices.clear();
    };
    let mut last = Point::ZERO;
    for el in path.elements() {
        // The segment's start and end directions (from its first and to its last distinct
        // control point).
        let (end, curve, start_dir, end_dir) = match *el {
            PathEl::MoveTo(p) => {
                flush(&mut vertices, false, out);
                vertices.push(Vertex {
                    p,
                    curve_in: false,
                    dir_in: Vec2::ZERO,
                    dir_out: Vec2::ZERO,
                });
                last = p;
                continue;
            }
            PathEl::ClosePath => {
                flush(&mut vertices, true, out);
                continue;
            }
            PathEl::LineTo(p) => (p, false, p - last, p - last),
            PathEl::QuadTo(c, p) => (p, true, first_nonzero(&[c, p], last), p - c),
            PathEl::CurveTo(c1, c2, p) => (
                p,
                true,
                first_nonzero(&[c1, c2, p], last),
                p - [c2, c1, last].into_iter().find(|q| *q != p).unwrap_or(last),
            ),
        };
        if end == last {
            // A zero-length segment: its vertex is taken once.
            continue;
        }
        if let Some(v) = vertices.last_mut() {
            v.dir_out = start_dir;
        }
        vertices.push(Vertex {
            p: end,
            curve_in: curve,
            dir_in: end_dir,
            dir_out: Vec2::ZERO,
        });
        last = end;
    }
    flush(&mut vertices, false, out);
}

/// The direction from `from` to the first of `points` that differs from it.
fn first_nonzero(points: &[Point], from: Point) -> Vec2 {
    points
        .iter()
        .find(|q| **q != from)
        .map_or(Vec2::ZERO, |q| *q - from)
}

/// Whether the path turns between the directions `a` and `b` by more than [`SMOOTH_SINE`]
/// (or turns back).
fn turns(a: Vec2, b: Vec2) -> bool {
    let (la, lb) = (a.hypot(), b.hypot());
    if la == 0.0 || lb == 0.0 {
        return false;
    }
    a.dot(b) <= 0.0 || a.cross(b).abs() > SMOOTH_SINE * la * lb
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::editor::Drawing;
    use kurbo::ParamCurve;

    fn xy(c: &PathDoc) -> Vec<(f64, f64)> {
        c.points.iter().map(|p| (p.x, p.y)).collect()
    }

    #[test]
    fn paths_of_other_tools_import_as_vertices() {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg"><g>
            <path fill="red" d="M10 10 L100 10 C120 50 120 60 100 100 L10 100 Z
                m 30 30 h 20 v 20"/>
            <path id="x" data-d="no" d='M0 0 Q 5 5 10 0'/><path d="nonsense"/></g></svg>"#;
        let doc = import_svg_paths(svg, Scheme::EkCubic).unwrap();
        assert_eq!(doc.contours.len(), 3);
        assert_eq!(
            xy(&doc.contours[0]),
            [(10.0, 10.0), (100.0, 10.0), (100.0, 100.0), (10.0, 100.0)]
        );
        assert!(doc.contours[0].closed);
        // The curve meets both lines at a turn: its two ends are corners; the line-to-line
        // vertices are not.
        let corners: Vec<bool> = doc.contours[0].points.iter().map(|p| p.corner).collect();
        assert_eq!(corners, [false, true, true, false]);
        // A relative move after Z starts from the subpath's start.
        assert_eq!(
            xy(&doc.contours[1]),
            [(40.0, 40.0), (60.0, 40.0), (60.0, 60.0)]
        );
        assert!(!doc.contours[1].closed);
        assert_eq!(xy(&doc.contours[2]), [(0.0, 0.0), (10.0, 0.0)]);
        assert!(doc.contours.iter().all(|c| c.scheme == Scheme::EkCubic));
        // Single points and repeated closes give contours of one point.
        let dots = import_svg_paths("<svg><path d=\"M0 0 Z Z m 1 1 Z\"/></svg>", Scheme::Kappa);
        let dots = dots.unwrap().contours;
        assert!(!dots.is_empty() && dots.iter().all(|c| c.points.len() == 1 && !c.closed));
        let (d, changes) = Drawing::from_docs(doc.contours, Scheme::Kappa);
        assert_eq!(d.len(), 3);
        assert!(changes.iter().all(|c| c.errors.is_empty()));
        for bad in [
            "<svg/>",
            "<path d=\"x\"/>",
            "<path",
            "<path d=\"M1e999 0 L 1 1\"/>",
            "not xml",
            "<svg><defs><path d=\"M0 0 L1 1\"/></defs></svg>",
        ] {
            assert!(
                matches!(
                    import_svg_paths(bad, Scheme::Kappa),
                    Err(Error::InvalidSvg(_))
                ),
                "{bad}"
            );
        }
    }

    #[test]
    fn transforms_of_the_element_and_its_ancestors_apply() {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">
            <g transform="translate(10 20)">
              <g transform="scale(2)">
                <path transform="rotate(90)" d="M0 0 L1 0 L1 1"/>
                <polygon points="0,0 3,0 3,3"/>
              </g>
              <svg x="5" y="7"><polyline points="0 0 1 0 1 1"/></svg>
              <path transform="skewX(45" d="M0 0 L 1 1"/>
            </g>
            <rect x="1" y="2" width="3" height="4" transform="matrix(1 0 0 -1 0 0)"/>
            <circle cx="50" cy="50" r="10"/>
            <line x1="0" y1="0" x2="5%" y2="1"/>
            <ellipse cx="0" cy="0" rx="2" ry="1" display="none"/>
          </svg>"#;
        let doc = import_svg_paths(svg, Scheme::Kappa).unwrap();
        let near = |a: &[(f64, f64)], b: &[(f64, f64)]| {
            a.len() == b.len()
                && a.iter()
                    .zip(b)
                    .all(|(p, q)| (p.0 - q.0).abs() < 1e-12 && (p.1 - q.1).abs() < 1e-12)
        };
        let got: Vec<Vec<(f64, f64)>> = doc.contours.iter().map(xy).collect();
        // rotate(90) takes (x, y) to (-y, x); then ×2, then +(10, 20).
        assert!(
            near(&got[0], &[(10.0, 20.0), (10.0, 22.0), (8.0, 22.0)]),
            "{got:?}"
        );
        assert!(
            near(&got[1], &[(10.0, 20.0), (16.0, 20.0), (16.0, 26.0)]),
            "{got:?}"
        );
        assert!(doc.contours[1].closed && !doc.contours[0].closed);
        assert!(
            near(&got[2], &[(15.0, 27.0), (16.0, 27.0), (16.0, 28.0)]),
            "{got:?}"
        );
        // The path with a transform that does not parse is not drawn; the rectangle is
        // flipped; the circle gives its four extrema, smooth; the line in % is skipped; the
        // hidden ellipse too.
        assert_eq!(got.len(), 5, "{got:?}");
        assert!(
            near(
                &got[3],
                &[(1.0, -2.0), (4.0, -2.0), (4.0, -6.0), (1.0, -6.0)]
            ),
            "{got:?}"
        );
        assert!(
            near(
                &got[4],
                &[(60.0, 50.0), (50.0, 60.0), (40.0, 50.0), (50.0, 40.0)]
            ),
            "{got:?}"
        );
        assert!(doc.contours[4].closed && doc.contours[4].points.iter().all(|p| !p.corner));
    }

    #[test]
    fn a_d_keeps_its_stem_straight() {
        // A `D`: a stem and one bowl of two cubics that meet smoothly at the right.
        let svg = r#"<svg><path d="M0 0 L0 100 C60 100 80 80 80 50 C80 20 60 0 0 0 Z"/></svg>"#;
        let doc = import_svg_paths(svg, Scheme::Kappa).unwrap();
        let c = &doc.contours[0];
        assert_eq!(xy(c), [(0.0, 0.0), (0.0, 100.0), (80.0, 50.0)]);
        let corners: Vec<bool> = c.points.iter().map(|p| p.corner).collect();
        assert_eq!(corners, [true, true, false]);
        let (d, changes) = Drawing::from_docs(doc.contours, Scheme::Kappa);
        assert!(changes.iter().all(|c| c.errors.is_empty()));
        // The stem is drawn as a straight line.
        let path = d.outline();
        // The stem is drawn straight: the segment from (0, 0) to (0, 100) stays on x = 0.
        let stem = path.segments().next().expect("a segment");
        assert_eq!(
            (stem.eval(0.0), stem.eval(1.0)),
            (Point::ZERO, Point::new(0.0, 100.0))
        );
        assert!((0..=10).all(|i| stem.eval(i as f64 / 10.0).x.abs() < 1e-9));
    }
}
