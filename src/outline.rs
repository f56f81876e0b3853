//! A kurbo path from ttf-parser's outline calls, shared by glyph import and text labels.

use kurbo::{BezPath, PathEl, Point};

/// Collects ttf-parser's outline calls into a kurbo path.
///
/// A malformed font can draw before its first `move_to` or after a `close`; kurbo's path
/// asserts against that in debug builds (found by the `font` fuzz target), so such a subpath
/// starts at the current point, and a `close` without a subpath is dropped.
pub(crate) struct OutlinePath(pub(crate) BezPath);

impl OutlinePath {
    /// Starts a subpath at the current point if none is open.
    fn ensure_subpath(&mut self) {
        let open = matches!(
            self.0.elements().last(),
            Some(el) if !matches!(el, PathEl::ClosePath)
        );
        if !open {
            let at = match self.0.elements() {
                [] => Point::ZERO,
                els => els
                    .iter()
                    .rev()
                    .find_map(|el| match el {
                        PathEl::MoveTo(p) => Some(*p),
                        _ => None,
                    })
                    .unwrap_or(Point::ZERO),
            };
            self.0.move_to(at);
        }
    }
}

impl ttf_parser::OutlineBuilder for OutlinePath {
    fn move_to(&mut self, x: f32, y: f32) {
        self.0.move_to((f64::from(x), f64::from(y)));
    }

    fn line_to(&mut self, x: f32, y: f32) {
        self.ensure_subpath();
        self.0.line_to((f64::from(x), f64::from(y)));
    }

    fn quad_to(&mut self, x1: f32, y1: f32, x: f32, y: f32) {
        self.ensure_subpath();
        self.0
            .quad_to((f64::from(x1), f64::from(y1)), (f64::from(x), f64::from(y)));
    }

    fn curve_to(&mut self, x1: f32, y1: f32, x2: f32, y2: f32, x: f32, y: f32) {
        self.ensure_subpath();
        self.0.curve_to(
            (f64::from(x1), f64::from(y1)),
            (f64::from(x2), f64::from(y2)),
            (f64::from(x), f64::from(y)),
        );
    }

    fn close(&mut self) {
        if matches!(self.0.elements().last(), Some(el) if !matches!(el, PathEl::ClosePath)) {
            self.0.close_path();
        }
    }
}
