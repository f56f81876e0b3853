//! The kappa path-tool engine for the browser.
//!
//! [`Session`] wraps a [`kappa::editor::Editor`] and writes everything a page draws or asks
//! for into flat buffers: `f64` arrays for points, paths, combs and curve samples, UTF-8
//! bytes for text. The [`ffi`] module exports it as plain C-ABI functions of a
//! `wasm32-unknown-unknown` module; the page's JavaScript calls them and reads the buffers
//! straight from the module's memory (`web/www/kappa.js`). Numbers in, numbers out: no
//! bindings generator and no serialisation on the way.
//!
//! **Path encoding** ([`encode_path`]): each element is a verb code followed by its points,
//! `MOVE_TO x y`, `LINE_TO x y`, `QUAD_TO x1 y1 x y`, `CURVE_TO x1 y1 x2 y2 x y`, `CLOSE`.

#![deny(missing_docs)]
// `#[no_mangle]` counts as unsafe code; it is allowed in `ffi` only, which has no unsafe
// blocks (results leave through buffers the page reads, nothing comes in by pointer).
#![deny(unsafe_code)]

use kappa::editor::{Change, Editor};
use kappa::Scheme;
use kurbo::{BezPath, PathEl, Point};

#[allow(unsafe_code)]
pub mod ffi;

/// Verb code of [`PathEl::MoveTo`] in an encoded path.
pub const MOVE_TO: f64 = 0.0;
/// Verb code of [`PathEl::LineTo`].
pub const LINE_TO: f64 = 1.0;
/// Verb code of [`PathEl::QuadTo`].
pub const QUAD_TO: f64 = 2.0;
/// Verb code of [`PathEl::CurveTo`].
pub const CURVE_TO: f64 = 3.0;
/// Verb code of [`PathEl::ClosePath`].
pub const CLOSE: f64 = 4.0;

/// Appends the elements of `path` to `out` in the encoding of the module docs.
pub fn encode_path(path: &BezPath, out: &mut Vec<f64>) {
    for el in path.elements() {
        match *el {
            PathEl::MoveTo(p) => out.extend([MOVE_TO, p.x, p.y]),
            PathEl::LineTo(p) => out.extend([LINE_TO, p.x, p.y]),
            PathEl::QuadTo(a, p) => out.extend([QUAD_TO, a.x, a.y, p.x, p.y]),
            PathEl::CurveTo(a, b, p) => out.extend([CURVE_TO, a.x, a.y, b.x, b.y, p.x, p.y]),
            PathEl::ClosePath => out.push(CLOSE),
        }
    }
}

/// Decodes a path encoded by [`encode_path`]; `None` for an unknown verb or a truncated
/// element.
pub fn decode_path(data: &[f64]) -> Option<BezPath> {
    let mut out = BezPath::new();
    let mut i = 0;
    let pt = |j: usize| Some(Point::new(*data.get(j)?, *data.get(j + 1)?));
    while i < data.len() {
        let verb = data[i];
        let el = if verb == MOVE_TO {
            PathEl::MoveTo(pt(i + 1)?)
        } else if verb == LINE_TO {
            PathEl::LineTo(pt(i + 1)?)
        } else if verb == QUAD_TO {
            PathEl::QuadTo(pt(i + 1)?, pt(i + 3)?)
        } else if verb == CURVE_TO {
            PathEl::CurveTo(pt(i + 1)?, pt(i + 3)?, pt(i + 5)?)
        } else if verb == CLOSE {
            PathEl::ClosePath
        } else {
            return None;
        };
        i += match el {
            PathEl::MoveTo(_) | PathEl::LineTo(_) => 3,
            PathEl::QuadTo(..) => 5,
            PathEl::CurveTo(..) => 7,
            PathEl::ClosePath => 1,
        };
        out.push(el);
    }
    Some(out)
}

/// The scheme of a code: 0 κ, 1 εκ-cubic, 2 εκ-trig.
pub fn scheme_from_code(code: u32) -> Option<Scheme> {
    match code {
        0 => Some(Scheme::Kappa),
        1 => Some(Scheme::EkCubic),
        2 => Some(Scheme::EkTrig),
        _ => None,
    }
}

/// The code of a scheme (see [`scheme_from_code`]).
pub fn scheme_code(scheme: Scheme) -> u32 {
    match scheme {
        Scheme::Kappa => 0,
        Scheme::EkCubic => 1,
        Scheme::EkTrig => 2,
    }
}

/// An editor with the output buffers a page reads (see the module docs).
#[derive(Debug, Default)]
pub struct Session {
    editor: Editor,
    last: Change,
    /// Numbers of the last query (points, piece info, evaluations, hits).
    nums: Vec<f64>,
    /// The encoded path.
    path: Vec<f64>,
    /// The encoded curvature comb.
    comb: Vec<f64>,
    /// Text of the last query (SVG export, error message).
    bytes: Vec<u8>,
}

impl Session {
    /// An empty session for `scheme`.
    pub fn new(scheme: Scheme) -> Session {
        Session {
            editor: Editor::new(scheme),
            ..Session::default()
        }
    }

    /// The editor.
    pub fn editor(&self) -> &Editor {
        &self.editor
    }

    /// What the last edit did.
    pub fn last_change(&self) -> &Change {
        &self.last
    }

    /// Records `change` as the last one and returns its number of errors.
    fn record(&mut self, change: Change) -> u32 {
        self.last = change;
        self.last.errors.len() as u32
    }

    /// Appends a point; returns the number of pieces that failed to solve.
    pub fn add_point(&mut self, x: f64, y: f64) -> u32 {
        let c = self.editor.add_point(Point::new(x, y));
        self.record(c)
    }

    /// Inserts a point on the curve nearest to `(x, y)`; its index, or `None` if there is
    /// no curve.
    pub fn insert_point(&mut self, x: f64, y: f64) -> Option<usize> {
        let (at, c) = self.editor.insert_on_curve(Point::new(x, y))?;
        self.record(c);
        Some(at)
    }

    /// Moves point `i` (its own undo step).
    pub fn move_point(&mut self, i: usize, x: f64, y: f64) -> u32 {
        let c = self.editor.move_point(i, Point::new(x, y));
        self.record(c)
    }

    /// Moves point `i` within a drag gesture (one undo step until [`Session::end_drag`]).
    pub fn drag_point(&mut self, i: usize, x: f64, y: f64) -> u32 {
        let c = self.editor.drag_point(i, Point::new(x, y));
        self.record(c)
    }

    /// Ends the drag gesture (pieces its capped updates left unconverged are solved with
    /// the full budget); returns the number of pieces that failed to solve.
    pub fn end_drag(&mut self) -> u32 {
        let c = self.editor.end_drag();
        if !c.resolved.is_empty() {
            self.last = c;
        }
        self.last.errors = self.editor.errors();
        self.last.errors.len() as u32
    }

    /// Deletes point `i`.
    pub fn delete_point(&mut self, i: usize) -> u32 {
        let c = self.editor.delete_point(i);
        self.record(c)
    }

    /// Sets the shape of point `i`.
    pub fn set_shape(&mut self, i: usize, a: f64) -> u32 {
        let c = self.editor.set_shape(i, a);
        self.record(c)
    }

    /// Sets the shape of point `i` within a slider drag (one undo step until
    /// [`Session::end_drag`]).
    pub fn drag_shape(&mut self, i: usize, a: f64) -> u32 {
        let c = self.editor.drag_shape(i, a);
        self.record(c)
    }

    /// Toggles the corner flag of point `i`.
    pub fn toggle_corner(&mut self, i: usize) -> u32 {
        let c = self.editor.toggle_corner(i);
        self.record(c)
    }

    /// Opens or closes the path.
    pub fn set_closed(&mut self, closed: bool) -> u32 {
        let c = self.editor.set_closed(closed);
        self.record(c)
    }

    /// Switches the scheme.
    pub fn set_scheme(&mut self, scheme: Scheme) -> u32 {
        let c = self.editor.set_scheme(scheme);
        self.record(c)
    }

    /// Undoes the last edit; whether there was one. The errors of the restored state are
    /// the last change's (an unconverged curve is flagged again).
    pub fn undo(&mut self) -> bool {
        let done = self.editor.undo();
        self.restored();
        done
    }

    /// Redoes the last undone edit; whether there was one (errors as for
    /// [`Session::undo`]).
    pub fn redo(&mut self) -> bool {
        let done = self.editor.redo();
        self.restored();
        done
    }

    /// After an undo or redo: the last change is the restored state's errors.
    fn restored(&mut self) {
        self.last = Change {
            errors: self.editor.errors(),
            ..Change::default()
        };
    }

    /// The numbers of the last query.
    pub fn nums(&self) -> &[f64] {
        &self.nums
    }

    /// The encoded path of the last [`Session::fill_path`].
    pub fn path(&self) -> &[f64] {
        &self.path
    }

    /// The encoded comb of the last [`Session::fill_comb`].
    pub fn comb(&self) -> &[f64] {
        &self.comb
    }

    /// The text of the last [`Session::export_svg`] or [`Session::last_error`].
    pub fn bytes(&self) -> &[u8] {
        &self.bytes
    }

    /// Writes `x, y, shape, corner (0 or 1)` of every point to the numbers; their count.
    pub fn fill_points(&mut self) -> usize {
        self.nums.clear();
        for p in &self.editor.doc().points {
            self.nums
                .extend([p.x, p.y, p.shape, if p.corner { 1.0 } else { 0.0 }]);
        }
        self.nums.len()
    }

    /// Writes piece `k` to the numbers: `closed, failed, m, n`, then its `m` point indices,
    /// then the peak parameter `t_max` of each of its `n` segments (`n = 0` while it has no
    /// curve). Nothing for an out-of-range `k`. Returns the count.
    pub fn fill_piece(&mut self, k: usize) -> usize {
        self.nums.clear();
        if k >= self.editor.pieces() {
            return 0;
        }
        let idx = self.editor.piece_points(k);
        let spline = self.editor.piece_spline(k);
        let closed = spline.is_some_and(|s| s.is_closed());
        let failed = self.editor.piece_error(k).is_some();
        let segs = spline.map_or(&[][..], |s| s.segments());
        self.nums.extend([
            f64::from(u8::from(closed)),
            f64::from(u8::from(failed)),
            idx.len() as f64,
            segs.len() as f64,
        ]);
        self.nums.extend(idx.iter().map(|&i| i as f64));
        self.nums.extend(segs.iter().map(|s| s.t_max));
        self.nums.len()
    }

    /// Writes `x, y, κ` of segment `j` of piece `k` at parameter `t` to the numbers (the
    /// exact curve, trigonometric segments included; κ positive for left turns in y-up
    /// coordinates). Nothing if there is no such segment. Returns the count.
    pub fn eval(&mut self, k: usize, j: usize, t: f64) -> usize {
        self.nums.clear();
        let seg = self
            .editor
            .piece_spline(k)
            .and_then(|s| s.segments().get(j));
        if let Some(seg) = seg {
            let p = seg.eval(t);
            self.nums.extend([p.x, p.y, seg.curvature(t)]);
        }
        self.nums.len()
    }

    /// Writes the nearest curve point to `(x, y)` to the numbers: `piece, segment, t, x, y,
    /// distance`; nothing if there is no curve. Returns the count.
    pub fn hit(&mut self, x: f64, y: f64) -> usize {
        self.nums.clear();
        if let Some(h) = self.editor.hit_test(Point::new(x, y)) {
            self.nums.extend([
                h.piece as f64,
                h.segment as f64,
                h.t,
                h.point.x,
                h.point.y,
                h.distance,
            ]);
        }
        self.nums.len()
    }

    /// The index of the input point nearest to `(x, y)` within `radius`, if any.
    pub fn nearest_point(&self, x: f64, y: f64, radius: f64) -> Option<usize> {
        let q = Point::new(x, y);
        self.editor
            .doc()
            .points
            .iter()
            .enumerate()
            .map(|(i, p)| (i, (p.point() - q).hypot()))
            .filter(|&(_, d)| d <= radius)
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(i, _)| i)
    }

    /// Encodes the whole path ([`Editor::to_bezpath`]); the count of numbers.
    pub fn fill_path(&mut self) -> usize {
        self.path.clear();
        encode_path(&self.editor.to_bezpath(), &mut self.path);
        self.path.len()
    }

    /// Encodes piece `k` ([`Editor::piece_bezpath`]) into the path buffer; the count of
    /// numbers.
    pub fn fill_piece_path(&mut self, k: usize) -> usize {
        self.path.clear();
        encode_path(&self.editor.piece_bezpath(k), &mut self.path);
        self.path.len()
    }

    /// Encodes the curvature comb ([`Editor::curvature_comb`]); the count of numbers.
    pub fn fill_comb(&mut self, scale: f64, samples: usize) -> usize {
        self.comb.clear();
        encode_path(&self.editor.curvature_comb(scale, samples), &mut self.comb);
        self.comb.len()
    }

    /// The largest |κ| over all pieces (0 without a curve).
    pub fn max_curvature(&self) -> f64 {
        (0..self.editor.pieces())
            .filter_map(|k| self.editor.piece_spline(k))
            .map(|s| s.max_abs_curvature())
            .fold(0.0, f64::max)
    }

    /// Writes the path as an SVG document ([`Editor::to_svg`]) to the bytes; their count.
    pub fn export_svg(&mut self, width: f64, height: f64, with_points: bool) -> usize {
        self.bytes = self.editor.to_svg(width, height, with_points).into_bytes();
        self.bytes.len()
    }

    /// Writes the errors of the last edit, one line each (`piece k: message`), to the
    /// bytes; their count (0 when the edit solved everything).
    pub fn last_error(&mut self) -> usize {
        let text: Vec<String> = self
            .last
            .errors
            .iter()
            .map(|(k, e)| match e {
                kappa::Error::NotConverged { .. } => {
                    format!("piece {k}: {e}; showing the closest curve found")
                }
                _ => format!("piece {k}: {e}"),
            })
            .collect();
        self.bytes = text.join("\n").into_bytes();
        self.bytes.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn star(n: usize) -> Vec<Point> {
        (0..n)
            .map(|i| {
                let th = i as f64 / n as f64 * std::f64::consts::TAU;
                let r = if i % 2 == 0 { 250.0 } else { 225.0 };
                Point::new(450.0 + r * th.cos(), 300.0 + r * th.sin())
            })
            .collect()
    }

    #[test]
    fn paths_round_trip_through_the_encoding() {
        let mut p = BezPath::new();
        p.move_to((1.0, 2.0));
        p.line_to((3.0, 4.0));
        p.quad_to((5.0, 6.0), (7.0, 8.0));
        p.curve_to((9.0, 10.0), (11.0, 12.0), (13.0, 14.0));
        p.close_path();
        let mut data = Vec::new();
        encode_path(&p, &mut data);
        assert_eq!(data.len(), 3 + 3 + 5 + 7 + 1);
        assert_eq!(decode_path(&data), Some(p));
        assert_eq!(decode_path(&data[..data.len() - 3]), None);
        assert_eq!(decode_path(&[9.0]), None);
    }

    #[test]
    fn scheme_codes_round_trip() {
        for s in [Scheme::Kappa, Scheme::EkCubic, Scheme::EkTrig] {
            assert_eq!(scheme_from_code(scheme_code(s)), Some(s));
        }
        assert_eq!(scheme_from_code(3), None);
    }

    #[test]
    fn buffers_describe_the_solved_curve() {
        for scheme in [Scheme::Kappa, Scheme::EkCubic, Scheme::EkTrig] {
            let mut s = Session::new(scheme);
            for p in star(12) {
                assert_eq!(s.add_point(p.x, p.y), 0);
            }
            s.set_shape(3, 0.9);
            assert_eq!(s.fill_points(), 48);
            assert_eq!(s.nums()[3 * 4 + 2], 0.9);
            // Open: one piece through all points; each interior point is its segment's peak.
            assert_eq!(s.fill_piece(0), 4 + 12 + 10);
            let info = s.nums().to_vec();
            assert_eq!(&info[..4], &[0.0, 0.0, 12.0, 10.0]);
            let pts = star(12);
            for j in 0..10 {
                let t = info[16 + j];
                assert_eq!(s.eval(0, j, t), 3);
                let (x, y) = (s.nums()[0], s.nums()[1]);
                assert!((Point::new(x, y) - pts[j + 1]).hypot() < 1e-9);
            }
            s.eval(0, 0, 0.0);
            assert!((Point::new(s.nums()[0], s.nums()[1]) - pts[0]).hypot() < 1e-9);
            assert_eq!(s.eval(0, 10, 0.5), 0);
            assert_eq!(s.fill_piece(1), 0);
            // The encoded path is the editor's path.
            let n = s.fill_path();
            assert_eq!(decode_path(&s.path()[..n]), Some(s.editor().to_bezpath()));
            let n = s.fill_comb(1000.0, 8);
            let comb = decode_path(&s.comb()[..n]).unwrap();
            assert_eq!(comb, s.editor().curvature_comb(1000.0, 8));
            assert!(s.max_curvature() > 0.0);
            // Close it: one closed piece with a segment per point.
            s.set_closed(true);
            s.fill_piece(0);
            assert_eq!(&s.nums()[..4], &[1.0, 0.0, 12.0, 12.0]);
        }
    }

    #[test]
    fn drags_hits_and_exports() {
        let mut s = Session::new(Scheme::EkCubic);
        for p in star(8) {
            s.add_point(p.x, p.y);
        }
        s.set_closed(true);
        let before = {
            s.export_svg(900.0, 600.0, true);
            String::from_utf8(s.bytes().to_vec()).unwrap()
        };
        assert!(before.starts_with("<svg") && before.matches("<circle").count() == 8);
        let p = star(8)[2];
        assert_eq!(s.nearest_point(p.x + 3.0, p.y - 2.0, 8.0), Some(2));
        assert_eq!(s.nearest_point(p.x + 30.0, p.y, 8.0), None);
        for k in 1..=10 {
            assert_eq!(s.drag_point(2, p.x + k as f64, p.y), 0);
        }
        s.end_drag();
        assert!(s.last_change().iterations > 0);
        s.export_svg(900.0, 600.0, true);
        let after = String::from_utf8(s.bytes().to_vec()).unwrap();
        assert_ne!(after, before);
        assert!(after.contains(&format!("cx=\"{}\"", p.x + 10.0)));
        // The whole gesture is one undo step.
        assert!(s.undo());
        s.export_svg(900.0, 600.0, true);
        assert_eq!(s.bytes(), before.as_bytes());
        assert!(s.redo());
        // A slider drag is one step too.
        for a in [0.8, 0.81, 0.82, 0.83, 0.84] {
            assert_eq!(s.drag_shape(4, a), 0);
        }
        s.end_drag();
        assert_eq!(s.editor().doc().points[4].shape, 0.84);
        assert!(s.undo());
        assert_eq!(s.editor().doc().points[4].shape, 2.0 / 3.0);
        assert!(s.redo());
        // A hit on the curve: distance zero at a point of the curve.
        assert_eq!(s.hit(p.x + 10.0, p.y), 6);
        assert!(s.nums()[5] < 1e-6);
        // No insertion on top of a point (the hit above is point 2 itself).
        assert_eq!(s.insert_point(p.x + 10.0, p.y), None);
        // Insert on the curve, then errors: a point dragged onto its neighbour.
        let (a, b) = (star(8)[2] + kurbo::Vec2::new(10.0, 0.0), star(8)[3]);
        let mid = a.midpoint(b);
        let at = s.insert_point(mid.x, mid.y).unwrap();
        assert_eq!(s.editor().doc().points.len(), 9);
        let q = s.editor().doc().points[at + 1].point();
        assert_eq!(s.drag_point(at, q.x, q.y), 1);
        assert!(s.last_error() > 0);
        let msg = String::from_utf8(s.bytes().to_vec()).unwrap();
        assert!(msg.starts_with("piece 0: "), "{msg}");
        // An empty session has no curve to hit or insert on.
        let mut e = Session::new(Scheme::Kappa);
        assert_eq!(e.hit(0.0, 0.0), 0);
        assert_eq!(e.insert_point(0.0, 0.0), None);
        assert_eq!(e.fill_path(), 0);
    }
}
