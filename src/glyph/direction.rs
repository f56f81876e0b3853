//! Contour direction by target format.
//!
//! TrueType fills by the non-zero rule and expects outer contours clockwise; PostScript
//! (CFF) outlines and UFO sources expect outer contours counter-clockwise. Inner contours
//! (counters) run the other way. A contour's role comes from its nesting: it is outer when
//! an even number of other contours enclose it.

use kurbo::{BezPath, ParamCurve, PathEl, Point, Shape};

/// The direction convention of a font format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// TrueType `glyf`: outer contours clockwise (y up), inner ones counter-clockwise.
    TrueType,
    /// PostScript outlines (CFF) and UFO sources: outer contours counter-clockwise.
    PostScript,
}

/// The outline with every closed contour turned the way `direction` wants it (in font
/// units, y up), contours and their start points otherwise unchanged. Open contours and
/// contours without area are left as they are.
///
/// A contour's role is its nesting depth: the number of other contours whose winding
/// number at a point of it (the middle of its first segment) is not zero. Even depth is
/// outer. Contours that cross each other have no well-defined role; they get the role of
/// that test point.
///
/// ```
/// use kappa::glyph::{orient, Direction};
/// use kurbo::{BezPath, Shape};
///
/// // An "o": an outer square and a counter, both counter-clockwise (y up).
/// let mut o = BezPath::new();
/// for (a, b) in [(0.0, 100.0), (25.0, 75.0)] {
///     o.move_to((a, a));
///     o.line_to((b, a));
///     o.line_to((b, b));
///     o.line_to((a, b));
///     o.close_path();
/// }
/// let tt = orient(&o, Direction::TrueType);
/// let areas: Vec<f64> = contours_of(&tt).iter().map(|c| c.area()).collect();
/// // Outer clockwise (negative area with y up), counter counter-clockwise.
/// assert_eq!(areas, [-10000.0, 2500.0]);
/// # fn contours_of(p: &BezPath) -> Vec<BezPath> {
/// #     let mut out: Vec<BezPath> = Vec::new();
/// #     for el in p.elements() {
/// #         if let kurbo::PathEl::MoveTo(_) = el { out.push(BezPath::new()); }
/// #         out.last_mut().unwrap().push(*el);
/// #     }
/// #     out
/// # }
/// ```
pub fn orient(path: &BezPath, direction: Direction) -> BezPath {
    let subpaths = split(path);
    let probes: Vec<Option<Point>> = subpaths.iter().map(probe).collect();
    let mut out = BezPath::new();
    for (i, sub) in subpaths.iter().enumerate() {
        let closed = matches!(sub.elements().last(), Some(PathEl::ClosePath));
        let area = sub.area();
        let Some(at) = probes[i].filter(|_| closed && area != 0.0) else {
            out.extend(sub.elements().iter().copied());
            continue;
        };
        let depth = subpaths
            .iter()
            .enumerate()
            .filter(|&(j, other)| j != i && other.winding(at) != 0)
            .count();
        let outer = depth % 2 == 0;
        // Counter-clockwise (positive area, y up) wanted?
        let ccw = outer == (direction == Direction::PostScript);
        if (area > 0.0) == ccw {
            out.extend(sub.elements().iter().copied());
        } else {
            out.extend(sub.reverse_subpaths().elements().iter().copied());
        }
    }
    out
}

/// The subpaths of a path, each starting with its `MoveTo`.
fn split(path: &BezPath) -> Vec<BezPath> {
    let mut out: Vec<BezPath> = Vec::new();
    for el in path.elements() {
        if matches!(el, PathEl::MoveTo(_)) || out.is_empty() {
            out.push(BezPath::new());
        }
        if let Some(last) = out.last_mut() {
            last.push(*el);
        }
    }
    out
}

/// A point on the contour: the middle of its first segment.
fn probe(sub: &BezPath) -> Option<Point> {
    sub.segments().next().map(|s| s.eval(0.5))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(path: &mut BezPath, x0: f64, x1: f64, ccw: bool) {
        let pts = [(x0, x0), (x1, x0), (x1, x1), (x0, x1)];
        path.move_to(pts[0]);
        if ccw {
            for p in &pts[1..] {
                path.line_to(*p);
            }
        } else {
            for p in pts[1..].iter().rev() {
                path.line_to(*p);
            }
        }
        path.close_path();
    }

    #[test]
    fn nesting_decides_the_role() {
        // Outer, counter, island in the counter: depths 0, 1, 2.
        for ccw in [
            [true, true, true],
            [false, false, false],
            [true, false, true],
        ] {
            let mut p = BezPath::new();
            square(&mut p, 0.0, 100.0, ccw[0]);
            square(&mut p, 10.0, 90.0, ccw[1]);
            square(&mut p, 40.0, 60.0, ccw[2]);
            let areas: Vec<f64> = split(&orient(&p, Direction::TrueType))
                .iter()
                .map(Shape::area)
                .collect();
            assert!(
                areas[0] < 0.0 && areas[1] > 0.0 && areas[2] < 0.0,
                "{areas:?}"
            );
            let areas: Vec<f64> = split(&orient(&p, Direction::PostScript))
                .iter()
                .map(Shape::area)
                .collect();
            assert!(
                areas[0] > 0.0 && areas[1] < 0.0 && areas[2] > 0.0,
                "{areas:?}"
            );
        }
    }

    #[test]
    fn reversal_keeps_the_outline() {
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.quad_to((50.0, -20.0), (100.0, 0.0));
        p.curve_to((120.0, 50.0), (80.0, 90.0), (50.0, 100.0));
        p.line_to((0.0, 0.0));
        p.close_path();
        let r = orient(&p, Direction::TrueType);
        assert!((r.area() + p.area()).abs() < 1e-9);
        assert_eq!(orient(&r, Direction::TrueType), r);
        assert!((orient(&r, Direction::PostScript).area() - p.area()).abs() < 1e-9);
    }
}
