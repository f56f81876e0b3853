//! The kappa path-tool engine for the browser.
//!
//! [`Session`] wraps a [`kappa::editor::Drawing`] (several contours, one history) and writes
//! everything a page draws or asks for into flat buffers: `f64` arrays for points, paths,
//! combs and curve samples, UTF-8 bytes for text. The [`bindings`] module exports it to
//! JavaScript through wasm-bindgen as the class `Editor` (`web/build.sh` makes the npm
//! package with its TypeScript types); bulk results cross as `Float64Array`s or as plain
//! objects made in JavaScript from a view of the buffers.
//!
//! **Path encoding** ([`encode_path`]): each element is a verb code followed by its points,
//! `MOVE_TO x y`, `LINE_TO x y`, `QUAD_TO x1 y1 x y`, `CURVE_TO x1 y1 x2 y2 x y`, `CLOSE`.

#![deny(missing_docs)]
// The code wasm-bindgen generates counts as unsafe; it is allowed in `bindings` only, which
// has no unsafe blocks of its own.
#![deny(unsafe_code)]

use kappa::editor::{
    extract_svg_document, import_svg_paths, Change, CombStyle, Drawing, DrawingDoc, Editor,
};
use kappa::{Scheme, Shape, SolveOptions, Solver};
use kurbo::{BezPath, PathEl, Point};

#[allow(unsafe_code)]
pub mod bindings;

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

/// The scheme of a name: `"kappa"`, `"ek-cubic"` or `"ek-trig"` (as in the files).
pub fn scheme_from_name(name: &str) -> Option<Scheme> {
    match name {
        "kappa" => Some(Scheme::Kappa),
        "ek-cubic" => Some(Scheme::EkCubic),
        "ek-trig" => Some(Scheme::EkTrig),
        _ => None,
    }
}

/// The name of a scheme (see [`scheme_from_name`]).
pub fn scheme_name(scheme: Scheme) -> &'static str {
    match scheme {
        Scheme::Kappa => "kappa",
        Scheme::EkCubic => "ek-cubic",
        Scheme::EkTrig => "ek-trig",
    }
}

/// The work a drag update's solve may do here ([`Drawing::set_drag_work`]): a fifth of the
/// native [`kappa::editor::DRAG_WORK`], as a solver iteration costs three to four times as
/// much in WebAssembly in Chromium, so that a drag update with its drawing stays within a
/// frame where the solve does not converge. The end of the drag finishes the solve.
/// Measured by the browser test on a 240-point contour: at 20 iterations per update the p95
/// of an update with its drawing was 12.7–20.7 ms on the shared 2-core machine, against a
/// 16 ms frame; this cap gives 12.
pub const WEB_DRAG_WORK: usize = 3_000;

/// The most points of the active contour that [`Session::fill_preview`] solves through.
pub const PREVIEW_POINTS: usize = 6;

/// A drawing with the output buffers a page reads (see the module docs). Point edits go to
/// the *active* contour ([`Session::active`]); a click away from the drawing starts a new
/// one ([`Session::start_contour`]).
#[derive(Debug, Default)]
pub struct Session {
    drawing: Drawing,
    active: Option<usize>,
    last: Change,
    /// Errors of the last edit that are not a solve's (a file that did not open).
    message: Option<String>,
    /// Numbers of the last query (points, piece info, evaluations, hits).
    nums: Vec<f64>,
    /// The encoded path.
    path: Vec<f64>,
    /// The encoded curvature comb.
    comb: Vec<f64>,
    /// The scale of the last comb (drawing units per unit of curvature).
    comb_scale: f64,
    /// Text of the last query (SVG export, saved file, error message).
    bytes: Vec<u8>,
    /// Text the page writes in (a file to open), see [`Session::input_buffer`].
    input: Vec<u8>,
}

impl Session {
    /// An empty session for `scheme`.
    pub fn new(scheme: Scheme) -> Session {
        let mut drawing = Drawing::new(scheme);
        drawing.set_drag_work(WEB_DRAG_WORK);
        Session {
            drawing,
            ..Session::default()
        }
    }

    /// The drawing.
    pub fn drawing(&self) -> &Drawing {
        &self.drawing
    }

    /// The active contour's editor, if there is one.
    pub fn editor(&self) -> Option<&Editor> {
        self.active.and_then(|k| self.drawing.contour(k))
    }

    /// The active contour (`None` without contours, or after [`Session::set_active`] with an
    /// out-of-range index: the next click starts a new contour).
    pub fn active(&self) -> Option<usize> {
        self.active.filter(|&k| k < self.drawing.len())
    }

    /// Makes contour `k` the active one (`None`, or an index out of range, for none).
    pub fn set_active(&mut self, k: Option<usize>) {
        self.active = k.filter(|&k| k < self.drawing.len());
    }

    /// What the last edit did.
    pub fn last_change(&self) -> &Change {
        &self.last
    }

    /// Records `change` as the last one and returns its number of errors.
    fn record(&mut self, change: Change) -> u32 {
        self.last = change;
        self.message = None;
        self.last.errors.len() as u32
    }

    /// The active contour's index for an edit (`usize::MAX`, which changes nothing, without
    /// one).
    fn k(&self) -> usize {
        self.active().unwrap_or(usize::MAX)
    }

    /// Starts a new contour with a point at `(x, y)` and makes it active; its index.
    pub fn start_contour(&mut self, x: f64, y: f64) -> usize {
        let (k, c) = self.drawing.start_contour(Point::new(x, y));
        self.active = Some(k);
        self.record(c);
        k
    }

    /// Deletes contour `k`; whether there was one. No contour is active afterwards.
    pub fn delete_contour(&mut self, k: usize) -> bool {
        let done = self.drawing.delete_contour(k);
        self.active = None;
        self.record(Change::default());
        done
    }

    /// Removes every contour (one undo step); whether there was any.
    pub fn clear(&mut self) -> bool {
        self.active = None;
        self.record(Change::default());
        self.drawing.clear()
    }

    /// Appends a point to the active contour, or starts a contour without one; returns the
    /// number of pieces that failed to solve.
    pub fn add_point(&mut self, x: f64, y: f64) -> u32 {
        match self.active() {
            Some(k) => {
                let c = self.drawing.add_point(k, Point::new(x, y));
                self.record(c)
            }
            None => {
                self.start_contour(x, y);
                self.last.errors.len() as u32
            }
        }
    }

    /// Inserts a point on the curve nearest to `(x, y)` (in any contour, which becomes the
    /// active one); its index, or `None` if there is no curve.
    pub fn insert_point(&mut self, x: f64, y: f64) -> Option<usize> {
        let (k, at, c) = self.drawing.insert_on_curve(Point::new(x, y))?;
        self.active = Some(k);
        self.record(c);
        Some(at)
    }

    /// Moves point `i` of the active contour (its own undo step).
    pub fn move_point(&mut self, i: usize, x: f64, y: f64) -> u32 {
        let c = self.drawing.move_point(self.k(), i, Point::new(x, y));
        self.record(c)
    }

    /// Moves point `i` of the active contour within a drag gesture (one undo step until
    /// [`Session::end_drag`]).
    pub fn drag_point(&mut self, i: usize, x: f64, y: f64) -> u32 {
        let c = self.drawing.drag_point(self.k(), i, Point::new(x, y));
        self.record(c)
    }

    /// Ends the drag gesture (pieces its capped updates left unconverged are solved with
    /// the full budget); returns the number of pieces that failed to solve.
    pub fn end_drag(&mut self) -> u32 {
        let c = self.drawing.end_drag();
        if !c.resolved.is_empty() {
            self.last = c;
        }
        self.last.errors = self.active_errors();
        self.last.errors.len() as u32
    }

    /// The errors of the active contour's pieces.
    fn active_errors(&self) -> Vec<(usize, kappa::Error)> {
        self.editor().map(|e| e.errors()).unwrap_or_default()
    }

    /// Deletes point `i` of the active contour.
    pub fn delete_point(&mut self, i: usize) -> u32 {
        let c = self.drawing.delete_point(self.k(), i);
        self.record(c)
    }

    /// Sets the shape of point `i` of the active contour.
    pub fn set_shape(&mut self, i: usize, a: f64) -> u32 {
        let c = self.drawing.set_shape(self.k(), i, a);
        self.record(c)
    }

    /// Sets the shape of point `i` of the active contour within a slider drag (one undo
    /// step until [`Session::end_drag`]).
    pub fn drag_shape(&mut self, i: usize, a: f64) -> u32 {
        let c = self.drawing.drag_shape(self.k(), i, a);
        self.record(c)
    }

    /// Toggles the corner flag of point `i` of the active contour.
    pub fn toggle_corner(&mut self, i: usize) -> u32 {
        let c = self.drawing.toggle_corner(self.k(), i);
        self.record(c)
    }

    /// Sets the prescribed tangent of point `i` of the active contour to `(x, y)`
    /// (`incoming`: the side of a corner where a piece arrives). A zero or non-finite
    /// vector is rejected (the drawing is unchanged); [`Session::clear_tangent`] clears.
    pub fn set_tangent(&mut self, i: usize, x: f64, y: f64, incoming: bool) -> u32 {
        let v = kurbo::Vec2::new(x, y);
        let c = self.drawing.set_tangent(self.k(), i, Some(v), incoming);
        self.record(c)
    }

    /// Sets the prescribed tangent of point `i` of the active contour within a handle drag
    /// (one undo step until [`Session::end_drag`]).
    pub fn drag_tangent(&mut self, i: usize, x: f64, y: f64, incoming: bool) -> u32 {
        let v = kurbo::Vec2::new(x, y);
        let c = self.drawing.drag_tangent(self.k(), i, v, incoming);
        self.record(c)
    }

    /// Clears the prescribed tangent of point `i` of the active contour (`incoming`: the
    /// side of a corner where a piece arrives).
    pub fn clear_tangent(&mut self, i: usize, incoming: bool) -> u32 {
        let c = self.drawing.set_tangent(self.k(), i, None, incoming);
        self.record(c)
    }

    /// Makes corner `i` of the active contour a smooth line-to-curve join
    /// ([`kappa::editor::Editor::set_smooth_join`]); the number of pieces that failed, or
    /// `u32::MAX` where there is no line on one side and curve on the other.
    pub fn smooth_join(&mut self, i: usize) -> u32 {
        let c = self.drawing.set_smooth_join(self.k(), i);
        if c.rejected {
            return u32::MAX;
        }
        self.record(c)
    }

    /// Opens or closes the active contour.
    pub fn set_closed(&mut self, closed: bool) -> u32 {
        let c = self.drawing.set_closed(self.k(), closed);
        self.record(c)
    }

    /// Switches the scheme of every contour.
    pub fn set_scheme(&mut self, scheme: Scheme) -> u32 {
        let c = self.drawing.set_scheme(scheme);
        self.record(c)
    }

    /// Undoes the last step; whether there was one. The errors of the restored state are
    /// the last change's (an unconverged curve is flagged again).
    pub fn undo(&mut self) -> bool {
        let done = self.drawing.undo();
        self.restored();
        done
    }

    /// Redoes the last undone step; whether there was one (errors as for
    /// [`Session::undo`]).
    pub fn redo(&mut self) -> bool {
        let done = self.drawing.redo();
        self.restored();
        done
    }

    /// After an undo or redo: the active contour is kept if it still exists, and the last
    /// change is the errors of the drawing.
    fn restored(&mut self) {
        self.active = self.active();
        self.message = None;
        self.last = Change {
            errors: self
                .drawing
                .errors()
                .into_iter()
                .map(|(_, j, e)| (j, e))
                .collect(),
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

    /// The text of the last [`Session::export_svg`], [`Session::save`] or
    /// [`Session::last_error`].
    pub fn bytes(&self) -> &[u8] {
        &self.bytes
    }

    /// A buffer of `len` bytes for the page to write a file into (then
    /// [`Session::open_input`]); valid until the next call.
    pub fn input_buffer(&mut self, len: usize) -> &mut [u8] {
        self.input.clear();
        self.input.resize(len, 0);
        &mut self.input
    }

    /// Writes `x, y, shape, corner (0 or 1)` of every point of contour `k` to the numbers;
    /// their count (0 for an out-of-range `k`).
    pub fn fill_points(&mut self, k: usize) -> usize {
        self.nums.clear();
        if let Some(e) = self.drawing.contour(k) {
            for p in &e.doc().points {
                self.nums
                    .extend([p.x, p.y, p.shape, if p.corner { 1.0 } else { 0.0 }]);
            }
        }
        self.nums.len()
    }

    /// Writes the prescribed tangents of every point of contour `k` to the numbers:
    /// `tx, ty, tin_x, tin_y` each (outgoing, then incoming; NaN where there is none);
    /// their count.
    pub fn fill_tangents(&mut self, k: usize) -> usize {
        self.nums.clear();
        if let Some(e) = self.drawing.contour(k) {
            for p in &e.doc().points {
                let [a, b] = p.tangent.unwrap_or([f64::NAN; 2]);
                let [c, d] = p.tangent_in.unwrap_or([f64::NAN; 2]);
                self.nums.extend([a, b, c, d]);
            }
        }
        self.nums.len()
    }

    /// Encodes the outline of contour `k` alone ([`Editor::outline`]: one subpath, closed
    /// when the contour is) into the path buffer; the count of numbers.
    pub fn fill_contour_path(&mut self, k: usize) -> usize {
        self.path.clear();
        if let Some(e) = self.drawing.contour(k) {
            encode_path(&e.outline(), &mut self.path);
        }
        self.path.len()
    }

    /// Writes piece `j` of contour `k` to the numbers: `closed, failed, m, n`, then its `m`
    /// point indices, then the peak parameter `t_max` of each of its `n` segments (`n = 0`
    /// while it has no curve). Nothing for an out-of-range `k` or `j`. Returns the count.
    pub fn fill_piece(&mut self, k: usize, j: usize) -> usize {
        self.nums.clear();
        let Some(e) = self.drawing.contour(k) else {
            return 0;
        };
        if j >= e.pieces() {
            return 0;
        }
        let idx = e.piece_points(j);
        let spline = e.piece_spline(j);
        let closed = spline.is_some_and(|s| s.is_closed());
        let failed = e.piece_error(j).is_some();
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

    /// Writes `x, y, κ` of segment `s` of piece `j` of contour `k` at parameter `t` to the
    /// numbers (the exact curve, trigonometric segments included; κ positive for left turns
    /// in y-up coordinates). Nothing if there is no such segment. Returns the count.
    pub fn eval(&mut self, k: usize, j: usize, s: usize, t: f64) -> usize {
        self.nums.clear();
        let seg = self
            .drawing
            .contour(k)
            .and_then(|e| e.piece_spline(j))
            .and_then(|sp| sp.segments().get(s));
        if let Some(seg) = seg {
            let p = seg.eval(t);
            self.nums.extend([p.x, p.y, seg.curvature(t)]);
        }
        self.nums.len()
    }

    /// Writes the nearest curve point to `(x, y)` to the numbers: `contour, piece, segment,
    /// t, x, y, distance`; nothing if there is no curve. Returns the count.
    pub fn hit(&mut self, x: f64, y: f64) -> usize {
        self.nums.clear();
        if let Some((k, h)) = self.drawing.hit_test(Point::new(x, y)) {
            self.nums.extend([
                k as f64,
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

    /// Writes `contour, index` of the input point nearest to `(x, y)` within `radius`, of
    /// any contour, to the numbers (nothing if none); the count.
    pub fn nearest_point(&mut self, x: f64, y: f64, radius: f64) -> usize {
        self.nums.clear();
        if let Some((k, i)) = self.drawing.nearest_point(Point::new(x, y), radius) {
            self.nums.extend([k as f64, i as f64]);
        }
        self.nums.len()
    }

    /// Writes the bounding box of the points, `x0, y0, x1, y1`, to the numbers (nothing
    /// without points); the count.
    pub fn fill_bounds(&mut self) -> usize {
        self.nums.clear();
        if let Some(r) = self.drawing.bounds() {
            self.nums.extend([r.x0, r.y0, r.x1, r.y1]);
        }
        self.nums.len()
    }

    /// Encodes the drawing's outline ([`Drawing::outline`]: a subpath per contour, closed
    /// ones ending in `CLOSE`); the count of numbers.
    pub fn fill_path(&mut self) -> usize {
        self.path.clear();
        encode_path(&self.drawing.outline(), &mut self.path);
        self.path.len()
    }

    /// Encodes into the path buffer a preview of the stretch of curve a click at `(x, y)`
    /// would add to the active contour: the curve through the last points since the last
    /// corner (at most [`PREVIEW_POINTS`]) and `(x, y)`, from the last point on, as a
    /// polyline; a line where that does not solve. Nothing without an open active contour.
    /// Returns the count of numbers.
    pub fn fill_preview(&mut self, x: f64, y: f64) -> usize {
        self.path.clear();
        let cursor = Point::new(x, y);
        let Some(e) = self.editor() else {
            return 0;
        };
        let doc = e.doc();
        if doc.closed || doc.points.is_empty() || !cursor.is_finite() {
            return 0;
        }
        let pts = &doc.points;
        let n = pts.len();
        let mut start = n - 1;
        while start > 0 && n - start < PREVIEW_POINTS && !(pts[start].corner && start < n - 1) {
            start -= 1;
        }
        if pts[n - 1].corner {
            start = n - 1;
        }
        let mut tail: Vec<Point> = pts[start..].iter().map(|p| p.point()).collect();
        let last = tail[tail.len() - 1];
        tail.push(cursor);
        let mut out = BezPath::new();
        out.move_to(last);
        let curve = if tail.len() > 2 {
            let scheme = doc.scheme;
            let shape = match scheme {
                Scheme::Kappa => Shape::Neutral,
                _ => {
                    let mut a: Vec<f64> = pts[start..].iter().map(|p| p.shape).collect();
                    a.push(scheme.neutral_shape());
                    a[0] = scheme.neutral_shape();
                    Shape::PerPoint(a)
                }
            };
            let mut solver = Solver::with_options(SolveOptions {
                max_iterations: 100,
                accept_unconverged: true,
                ..SolveOptions::default()
            });
            solver.solve(&tail, false, scheme, &shape).ok()
        } else {
            None
        };
        match curve.as_ref().and_then(|c| c.segments().last()) {
            Some(seg) if seg.eval(1.0).is_finite() => {
                const STEPS: usize = 24;
                for i in 1..=STEPS {
                    let t = seg.t_max + (1.0 - seg.t_max) * i as f64 / STEPS as f64;
                    out.line_to(seg.eval(t));
                }
            }
            _ => out.line_to(cursor),
        }
        encode_path(&out, &mut self.path);
        self.path.len()
    }

    /// Encodes piece `j` of contour `k` ([`Editor::piece_bezpath`]) into the path buffer;
    /// the count of numbers.
    pub fn fill_piece_path(&mut self, k: usize, j: usize) -> usize {
        self.path.clear();
        if let Some(e) = self.drawing.contour(k) {
            encode_path(&e.piece_bezpath(j), &mut self.path);
        }
        self.path.len()
    }

    /// Encodes the curvature comb of every contour ([`Drawing::comb`]): teeth, then tip
    /// outlines. `scale` fixes the scale when positive (during a drag); otherwise the
    /// `percentile` of |κ| gets teeth `length` long. Teeth are cut at `clip × length`.
    /// Returns the count of numbers; [`Session::comb_scale`] gives the scale used.
    pub fn fill_comb(
        &mut self,
        length: f64,
        percentile: f64,
        clip: f64,
        samples: usize,
        scale: f64,
    ) -> usize {
        let style = CombStyle {
            samples,
            length,
            percentile,
            clip,
            scale: (scale > 0.0).then_some(scale),
        };
        let comb = self.drawing.comb(&style);
        self.comb_scale = comb.scale;
        self.comb.clear();
        encode_path(&comb.to_bezpath(), &mut self.comb);
        self.comb.len()
    }

    /// The scale of the last comb (drawing units per unit of curvature).
    pub fn comb_scale(&self) -> f64 {
        self.comb_scale
    }

    /// Writes the drawing as an SVG document with its file inside
    /// ([`Drawing::to_svg_with_document`]) to the bytes; their count.
    pub fn export_svg(&mut self, width: f64, height: f64, fill: bool) -> usize {
        self.bytes = self
            .drawing
            .to_svg_with_document(width, height, fill)
            .into_bytes();
        self.bytes.len()
    }

    /// Writes the drawing's file ([`DrawingDoc`] JSON) to the bytes; their count.
    pub fn save(&mut self) -> usize {
        self.bytes = DrawingDoc::of(&self.drawing).to_json().into_bytes();
        self.bytes.len()
    }

    /// Opens the text in the input buffer ([`Session::input_buffer`]): a drawing file, a
    /// single path's file, an SVG exported with its file, or another SVG, whose paths'
    /// vertices become the points ([`import_svg_paths`]). It replaces the drawing as one
    /// undo step (with `undoable`; else with an empty history, as for a drawing restored at
    /// start-up), with no active contour. Returns `Ok` with the number of pieces that failed
    /// to solve, or the error (the drawing is then unchanged).
    pub fn open_input(&mut self, undoable: bool) -> Result<u32, kappa::Error> {
        let text = String::from_utf8_lossy(&self.input).into_owned();
        let doc = if text.trim_start().starts_with('<') {
            // An SVG exported here holds its drawing; one from elsewhere gives its vertices.
            extract_svg_document(&text).or_else(|_| import_svg_paths(&text, self.drawing.scheme()))
        } else {
            DrawingDoc::from_json(&text)
        };
        let doc = match doc {
            Ok(d) => d,
            Err(e) => {
                self.last = Change::default();
                self.message = Some(e.to_string());
                return Err(e);
            }
        };
        let changes = if undoable {
            self.drawing.replace(doc.contours)
        } else {
            let (mut drawing, changes) = Drawing::from_docs(doc.contours, self.drawing.scheme());
            drawing.set_drag_work(WEB_DRAG_WORK);
            self.drawing = drawing;
            changes
        };
        self.active = None;
        let errors = changes
            .into_iter()
            .flat_map(|c| c.errors)
            .collect::<Vec<_>>();
        let n = errors.len() as u32;
        self.last = Change {
            errors,
            ..Change::default()
        };
        self.message = None;
        Ok(n)
    }

    /// Writes the errors of the last edit, one line each (`piece k: message`), to the
    /// bytes; their count (0 when the edit solved everything).
    pub fn last_error(&mut self) -> usize {
        let mut text: Vec<String> = self
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
        text.extend(self.message.clone());
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
    fn scheme_names_round_trip() {
        for s in [Scheme::Kappa, Scheme::EkCubic, Scheme::EkTrig] {
            assert_eq!(scheme_from_name(scheme_name(s)), Some(s));
        }
        assert_eq!(scheme_from_name("ek"), None);
    }

    #[test]
    fn buffers_describe_the_solved_curve() {
        for scheme in [Scheme::Kappa, Scheme::EkCubic, Scheme::EkTrig] {
            let mut s = Session::new(scheme);
            for p in star(12) {
                assert_eq!(s.add_point(p.x, p.y), 0);
            }
            assert_eq!(s.active(), Some(0));
            s.set_shape(3, 0.9);
            assert_eq!(s.fill_points(0), 48);
            assert_eq!(s.nums()[3 * 4 + 2], 0.9);
            // Open: one piece through all points; each interior point is its segment's peak.
            assert_eq!(s.fill_piece(0, 0), 4 + 12 + 10);
            let info = s.nums().to_vec();
            assert_eq!(&info[..4], &[0.0, 0.0, 12.0, 10.0]);
            let pts = star(12);
            for j in 0..10 {
                let t = info[16 + j];
                assert_eq!(s.eval(0, 0, j, t), 3);
                let (x, y) = (s.nums()[0], s.nums()[1]);
                assert!((Point::new(x, y) - pts[j + 1]).hypot() < 1e-9);
            }
            s.eval(0, 0, 0, 0.0);
            assert!((Point::new(s.nums()[0], s.nums()[1]) - pts[0]).hypot() < 1e-9);
            assert_eq!(s.eval(0, 0, 10, 0.5), 0);
            assert_eq!(s.fill_piece(0, 1), 0);
            assert_eq!(s.fill_piece(1, 0), 0);
            // The encoded path is the drawing's outline.
            let n = s.fill_path();
            assert_eq!(decode_path(&s.path()[..n]), Some(s.drawing().outline()));
            let n = s.fill_comb(50.0, 0.75, 3.0, 8, 0.0);
            assert!(decode_path(&s.comb()[..n]).is_some());
            assert!(s.comb_scale() > 0.0);
            // Close it: one closed piece with a segment per point.
            s.set_closed(true);
            s.fill_piece(0, 0);
            assert_eq!(&s.nums()[..4], &[1.0, 0.0, 12.0, 12.0]);
        }
    }

    /// Whether two paths have the same elements with end points within `1e-9`.
    fn close(a: &BezPath, b: &BezPath) -> bool {
        a.elements().len() == b.elements().len()
            && a.elements().iter().zip(b.elements()).all(|(x, y)| {
                match (x.end_point(), y.end_point()) {
                    (Some(p), Some(q)) => (p - q).hypot() < 1e-9,
                    (None, None) => true,
                    _ => false,
                }
            })
    }

    #[test]
    fn contours_files_and_undo() {
        let mut s = Session::new(Scheme::EkCubic);
        for p in star(8) {
            s.add_point(p.x, p.y);
        }
        s.set_closed(true);
        // A second contour inside the first: an `o`.
        let inner: Vec<Point> = star(8)
            .iter()
            .map(|p| Point::new(450.0 + 0.5 * (p.x - 450.0), 300.0 + 0.5 * (p.y - 300.0)))
            .collect();
        assert_eq!(s.start_contour(inner[0].x, inner[0].y), 1);
        for p in &inner[1..] {
            s.add_point(p.x, p.y);
        }
        s.set_closed(true);
        assert_eq!(s.drawing().len(), 2);
        assert_eq!(s.nearest_point(inner[2].x + 1.0, inner[2].y, 5.0), 2);
        assert_eq!(s.nums(), &[1.0, 2.0]);
        assert_eq!(s.hit(450.0 + 112.0, 300.0), 7);
        assert_eq!(s.nums()[0], 1.0);
        s.fill_bounds();
        assert_eq!(s.nums().len(), 4);
        // Save, clear, open: the same drawing.
        s.save();
        let file = s.bytes().to_vec();
        let path = s.drawing().outline();
        assert!(s.clear());
        assert_eq!(s.fill_path(), 0);
        s.input_buffer(file.len()).copy_from_slice(&file);
        assert_eq!(s.open_input(true).unwrap(), 0);
        assert!(close(&s.drawing().outline(), &path));
        // The SVG export opens too, and the bad file leaves the drawing as it is.
        s.export_svg(900.0, 600.0, true);
        let svg = s.bytes().to_vec();
        let text = String::from_utf8(svg.clone()).unwrap();
        assert_eq!(text.matches('Z').count(), 2);
        s.input_buffer(3).copy_from_slice(b"{x:");
        assert!(s.open_input(true).is_err());
        assert!(s.last_error() > 0);
        assert_eq!(s.drawing().len(), 2);
        // An SVG from elsewhere: its path's vertices.
        let other = b"<svg><path d=\"M0 0 L100 0 L100 100 Z\"/></svg>";
        s.input_buffer(other.len()).copy_from_slice(other);
        assert_eq!(s.open_input(true).unwrap(), 0);
        assert_eq!(s.drawing().len(), 1);
        assert!(s.drawing().contour(0).unwrap().doc().closed);
        assert!(s.undo());
        s.input_buffer(svg.len()).copy_from_slice(&svg);
        assert_eq!(s.open_input(true).unwrap(), 0);
        assert_eq!(s.drawing().len(), 2);
        // Undo: the opens, the clear, back to the drawing.
        assert!(s.undo() && s.undo() && s.undo());
        assert!(close(&s.drawing().outline(), &path));
        s.input_buffer(file.len()).copy_from_slice(&file);
        assert_eq!(s.open_input(false).unwrap(), 0);
        assert!(!s.drawing().can_undo());
        assert!(close(&s.drawing().outline(), &path));
        assert!(s.delete_contour(0));
        assert_eq!(s.drawing().len(), 1);
        assert!(s.undo());
        assert_eq!(s.drawing().len(), 2);
    }

    #[test]
    fn drags_hits_and_errors() {
        let mut s = Session::new(Scheme::EkCubic);
        for p in star(8) {
            s.add_point(p.x, p.y);
        }
        s.set_closed(true);
        let before = s.drawing().outline();
        let p = star(8)[2];
        assert_eq!(s.nearest_point(p.x + 3.0, p.y - 2.0, 8.0), 2);
        assert_eq!(s.nums(), &[0.0, 2.0]);
        assert_eq!(s.nearest_point(p.x + 30.0, p.y, 8.0), 0);
        for k in 1..=10 {
            assert_eq!(s.drag_point(2, p.x + k as f64, p.y), 0);
        }
        s.end_drag();
        assert!(s.last_change().iterations > 0);
        assert_ne!(s.drawing().outline(), before);
        // The whole gesture is one undo step.
        assert!(s.undo());
        assert_eq!(s.drawing().outline(), before);
        assert!(s.redo());
        // A slider drag is one step too.
        for a in [0.8, 0.81, 0.82, 0.83, 0.84] {
            assert_eq!(s.drag_shape(4, a), 0);
        }
        s.end_drag();
        assert_eq!(s.editor().unwrap().doc().points[4].shape, 0.84);
        assert!(s.undo());
        assert_eq!(s.editor().unwrap().doc().points[4].shape, 2.0 / 3.0);
        assert!(s.redo());
        // A hit on the curve: distance zero at a point of the curve.
        assert_eq!(s.hit(p.x + 10.0, p.y), 7);
        assert!(s.nums()[6] < 1e-6);
        // No insertion on top of a point (the hit above is point 2 itself).
        assert_eq!(s.insert_point(p.x + 10.0, p.y), None);
        // Insert on the curve, then errors: a point dragged onto its neighbour.
        let (a, b) = (star(8)[2] + kurbo::Vec2::new(10.0, 0.0), star(8)[3]);
        let mid = a.midpoint(b);
        let at = s.insert_point(mid.x, mid.y).unwrap();
        assert_eq!(s.editor().unwrap().doc().points.len(), 9);
        let q = s.editor().unwrap().doc().points[at + 1].point();
        assert_eq!(s.drag_point(at, q.x, q.y), 1);
        assert!(s.last_error() > 0);
        let msg = String::from_utf8(s.bytes().to_vec()).unwrap();
        assert!(msg.starts_with("piece 0: "), "{msg}");
        // The preview of the next click: nothing on a closed contour; from the last point of
        // an open one.
        s.end_drag();
        assert!(s.undo());
        assert_eq!(s.fill_preview(0.0, 0.0), 0);
        assert_eq!(s.set_closed(false), 0);
        let n = s.fill_preview(100.0, 100.0);
        let preview = decode_path(&s.path()[..n]).unwrap();
        let last = *s.editor().unwrap().doc().points.last().unwrap();
        assert_eq!(preview.elements()[0], kurbo::PathEl::MoveTo(last.point()));
        let end = preview.elements().last().unwrap().end_point().unwrap();
        assert!((end - Point::new(100.0, 100.0)).hypot() < 1e-6);
        assert_eq!(s.fill_preview(f64::NAN, 0.0), 0);
        // An empty session has no curve to hit or insert on; edits without an active
        // contour change nothing.
        let mut e = Session::new(Scheme::Kappa);
        assert_eq!(e.hit(0.0, 0.0), 0);
        assert_eq!(e.insert_point(0.0, 0.0), None);
        assert_eq!(e.fill_path(), 0);
        assert_eq!(e.move_point(0, 1.0, 1.0), 0);
        assert_eq!(e.set_closed(true), 0);
        assert!(!e.undo());
    }
}
