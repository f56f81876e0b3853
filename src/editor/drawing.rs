//! A drawing of several contours (a glyph: the two of an `o`), each an [`Editor`], with one
//! undo history over all of them.

use kurbo::{BezPath, Point};

use super::{Change, Comb, CombStyle, Editor, Hit, PathDoc};
use crate::Scheme;

/// One step of a [`Drawing`]'s history.
#[derive(Clone, Debug)]
enum Step {
    /// One undo step in each of these contours' own histories.
    Edits(Vec<usize>),
    /// The contours `at..at + len` replaced `old` (a contour added or deleted, a clear, an
    /// open): undone by putting `old` back.
    Splice {
        at: usize,
        old: Vec<Editor>,
        len: usize,
    },
}

/// Maximum undo steps kept.
const UNDO_LIMIT: usize = 1000;

/// A drawing of several contours, each open or closed, in one scheme, with one undo
/// history: every edit of a contour, adding or deleting a contour, clearing and opening a
/// document are undone and redone in the order they were made.
///
/// Contours are addressed by index; edits with an out-of-range contour or point index
/// change nothing (and return an empty [`Change`]). A drag gesture is one undo step, as in
/// [`Editor::drag_point`].
#[derive(Clone, Debug, Default)]
pub struct Drawing {
    contours: Vec<Editor>,
    scheme: Scheme,
    undo: Vec<Step>,
    redo: Vec<Step>,
    /// The drag work of every contour ([`Editor::set_drag_work`]), if set.
    drag_work: Option<usize>,
}

impl Drawing {
    /// An empty drawing in `scheme`.
    pub fn new(scheme: Scheme) -> Drawing {
        Drawing {
            scheme,
            ..Drawing::default()
        }
    }

    /// A drawing of `docs` (each solved from its saved solution, or from scratch), with an
    /// empty history; the scheme is the first document's (`scheme` without documents), and
    /// the others are switched to it. Returns the changes, one per contour.
    pub fn from_docs(docs: Vec<PathDoc>, scheme: Scheme) -> (Drawing, Vec<Change>) {
        let scheme = docs.first().map_or(scheme, |d| d.scheme);
        let mut changes = Vec::with_capacity(docs.len());
        let contours = docs
            .into_iter()
            .map(|doc| {
                let (mut e, mut c) = Editor::from_doc(doc);
                if e.doc().scheme != scheme {
                    c = e.set_scheme(scheme);
                    e.undo.clear();
                }
                changes.push(c);
                e
            })
            .collect();
        let drawing = Drawing {
            contours,
            scheme,
            ..Drawing::default()
        };
        (drawing, changes)
    }

    /// Sets the work a drag update's solve may do in every contour, present and future (see
    /// [`Editor::set_drag_work`]).
    pub fn set_drag_work(&mut self, work: usize) {
        self.drag_work = Some(work);
        for e in &mut self.contours {
            e.set_drag_work(work);
        }
    }

    /// A new contour's editor.
    fn new_editor(&self) -> Editor {
        let mut e = Editor::new(self.scheme);
        if let Some(w) = self.drag_work {
            e.set_drag_work(w);
        }
        e
    }

    /// The scheme.
    pub fn scheme(&self) -> Scheme {
        self.scheme
    }

    /// The number of contours.
    pub fn len(&self) -> usize {
        self.contours.len()
    }

    /// Whether the drawing has no contour.
    pub fn is_empty(&self) -> bool {
        self.contours.is_empty()
    }

    /// Contour `k`.
    pub fn contour(&self, k: usize) -> Option<&Editor> {
        self.contours.get(k)
    }

    /// The contours.
    pub fn contours(&self) -> &[Editor] {
        &self.contours
    }

    /// The documents of the contours (each with its solution, see [`PathDoc::solution`]).
    pub fn docs(&self) -> Vec<PathDoc> {
        self.contours.iter().map(|e| e.doc().clone()).collect()
    }

    /// Whether there is something to undo.
    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    /// Whether there is something to redo.
    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }

    /// Applies `f` to contour `k` and records an undo step if the contour made one.
    fn record(&mut self, k: usize, f: impl FnOnce(&mut Editor) -> Change) -> Change {
        let Some(e) = self.contours.get_mut(k) else {
            return Change::default();
        };
        let steps = e.steps;
        let change = f(e);
        if e.steps != steps {
            self.push(Step::Edits(vec![k]));
        }
        change
    }

    fn push(&mut self, step: Step) {
        self.redo.clear();
        self.undo.push(step);
        if self.undo.len() > UNDO_LIMIT {
            self.undo.remove(0);
        }
    }

    /// Ends a drag gesture in every contour (see [`Editor::end_drag`]): the changes of the
    /// contours that finished a piece, merged.
    pub fn end_drag(&mut self) -> Change {
        let mut out = Change::default();
        for e in &mut self.contours {
            let c = e.end_drag();
            out.resolved.extend(c.resolved);
            out.iterations += c.iterations;
            out.errors.extend(c.errors);
        }
        out
    }

    /// Starts a new contour with one point at `p`: its index and the change. A point that is
    /// not finite starts nothing: the change is [`Change::rejected`] and the index is
    /// [`Drawing::len`], one past the last contour.
    pub fn start_contour(&mut self, p: Point) -> (usize, Change) {
        for e in &mut self.contours {
            e.end_drag();
        }
        let mut e = self.new_editor();
        let change = e.add_point(p);
        let at = self.contours.len();
        if change.rejected {
            return (at, change);
        }
        self.contours.push(e);
        self.push(Step::Splice {
            at,
            old: Vec::new(),
            len: 1,
        });
        (at, change)
    }

    /// Deletes contour `k`; whether there was one.
    pub fn delete_contour(&mut self, k: usize) -> bool {
        if k >= self.contours.len() {
            return false;
        }
        let e = self.contours.remove(k);
        self.push(Step::Splice {
            at: k,
            old: vec![e],
            len: 0,
        });
        true
    }

    /// Removes every contour (one undo step); whether there was any.
    pub fn clear(&mut self) -> bool {
        if self.contours.is_empty() {
            return false;
        }
        let old = core::mem::take(&mut self.contours);
        self.push(Step::Splice { at: 0, old, len: 0 });
        true
    }

    /// Replaces the whole drawing by `docs` as one undo step (opening a file), switched to
    /// the first document's scheme as in [`Drawing::from_docs`]. Returns the changes, one
    /// per contour.
    pub fn replace(&mut self, docs: Vec<PathDoc>) -> Vec<Change> {
        let (mut new, changes) = Drawing::from_docs(docs, self.scheme);
        if let Some(w) = self.drag_work {
            new.set_drag_work(w);
        }
        let len = new.contours.len();
        let old = core::mem::replace(&mut self.contours, new.contours);
        self.scheme = new.scheme;
        self.push(Step::Splice { at: 0, old, len });
        changes
    }

    /// Appends a point to contour `k`.
    pub fn add_point(&mut self, k: usize, p: Point) -> Change {
        self.record(k, |e| e.add_point(p))
    }

    /// Inserts a point on the curve nearest to `p`, in whichever contour it is: the contour,
    /// the point's index and the change; `None` as for [`Editor::insert_on_curve`].
    pub fn insert_on_curve(&mut self, p: Point) -> Option<(usize, usize, Change)> {
        let (k, _) = self.hit_test(p)?;
        let mut at = None;
        let change = self.record(k, |e| match e.insert_on_curve(p) {
            Some((i, c)) => {
                at = Some(i);
                c
            }
            None => Change::default(),
        });
        at.map(|i| (k, i, change))
    }

    /// Moves point `i` of contour `k` (one undo step).
    pub fn move_point(&mut self, k: usize, i: usize, p: Point) -> Change {
        self.record(k, |e| e.move_point(i, p))
    }

    /// Moves point `i` of contour `k` within a drag gesture (see [`Editor::drag_point`]).
    pub fn drag_point(&mut self, k: usize, i: usize, p: Point) -> Change {
        self.end_other_drags(k);
        self.record(k, |e| e.drag_point(i, p))
    }

    /// Sets the shape of point `i` of contour `k` within a slider drag (see
    /// [`Editor::drag_shape`]).
    pub fn drag_shape(&mut self, k: usize, i: usize, a: f64) -> Change {
        self.end_other_drags(k);
        self.record(k, |e| e.drag_shape(i, a))
    }

    /// A gesture in contour `k` ends those of the others.
    fn end_other_drags(&mut self, k: usize) {
        for (j, e) in self.contours.iter_mut().enumerate() {
            if j != k {
                e.end_drag();
            }
        }
    }

    /// Deletes point `i` of contour `k` (the contour stays, possibly empty).
    pub fn delete_point(&mut self, k: usize, i: usize) -> Change {
        self.record(k, |e| e.delete_point(i))
    }

    /// Sets the shape of point `i` of contour `k`.
    pub fn set_shape(&mut self, k: usize, i: usize, a: f64) -> Change {
        self.record(k, |e| e.set_shape(i, a))
    }

    /// Toggles the corner flag of point `i` of contour `k`.
    pub fn toggle_corner(&mut self, k: usize, i: usize) -> Change {
        self.record(k, |e| e.toggle_corner(i))
    }

    /// Sets or clears the prescribed tangent of point `i` of contour `k` (see
    /// [`Editor::set_tangent`]).
    pub fn set_tangent(
        &mut self,
        k: usize,
        i: usize,
        tangent: Option<kurbo::Vec2>,
        incoming: bool,
    ) -> Change {
        self.record(k, |e| e.set_tangent(i, tangent, incoming))
    }

    /// Sets the prescribed tangent of point `i` of contour `k` within a handle drag (see
    /// [`Editor::drag_tangent`]).
    pub fn drag_tangent(
        &mut self,
        k: usize,
        i: usize,
        tangent: kurbo::Vec2,
        incoming: bool,
    ) -> Change {
        self.end_other_drags(k);
        self.record(k, |e| e.drag_tangent(i, tangent, incoming))
    }

    /// Makes corner `i` of contour `k` a smooth line-to-curve join (see
    /// [`Editor::set_smooth_join`]).
    pub fn set_smooth_join(&mut self, k: usize, i: usize) -> Change {
        self.record(k, |e| e.set_smooth_join(i))
    }

    /// Opens or closes contour `k`.
    pub fn set_closed(&mut self, k: usize, closed: bool) -> Change {
        self.record(k, |e| e.set_closed(closed))
    }

    /// Switches every contour to `scheme` (one undo step).
    pub fn set_scheme(&mut self, scheme: Scheme) -> Change {
        let mut out = Change::default();
        let mut touched = Vec::new();
        for (k, e) in self.contours.iter_mut().enumerate() {
            let steps = e.steps;
            let c = e.set_scheme(scheme);
            if e.steps != steps {
                touched.push(k);
            }
            out.resolved.extend(c.resolved);
            out.iterations += c.iterations;
            out.restructured |= c.restructured;
            out.errors.extend(c.errors);
        }
        self.scheme = scheme;
        if !touched.is_empty() {
            self.push(Step::Edits(touched));
        }
        out
    }

    /// Undoes the last step; `false` if there is none.
    pub fn undo(&mut self) -> bool {
        let Some(step) = self.undo.pop() else {
            return false;
        };
        let back = self.apply(step, true);
        self.redo.push(back);
        true
    }

    /// Redoes the last undone step; `false` if there is none.
    pub fn redo(&mut self) -> bool {
        let Some(step) = self.redo.pop() else {
            return false;
        };
        let back = self.apply(step, false);
        self.undo.push(back);
        true
    }

    /// Undoes (`undo`) or redoes a step; returns the step that reverses it.
    fn apply(&mut self, step: Step, undo: bool) -> Step {
        for e in &mut self.contours {
            e.end_drag();
        }
        let back = match step {
            Step::Edits(ks) => {
                for &k in &ks {
                    if let Some(e) = self.contours.get_mut(k) {
                        if undo {
                            e.undo();
                        } else {
                            e.redo();
                        }
                    }
                }
                Step::Edits(ks)
            }
            Step::Splice { at, old, len } => {
                let at = at.min(self.contours.len());
                let end = (at + len).min(self.contours.len());
                let new_len = old.len();
                let removed: Vec<Editor> = self.contours.splice(at..end, old).collect();
                Step::Splice {
                    at,
                    old: removed,
                    len: new_len,
                }
            }
        };
        // The scheme is that of the contours (all share one).
        if let Some(e) = self.contours.first() {
            self.scheme = e.doc().scheme;
        }
        back
    }

    /// The pieces that did not solve, per contour: `(contour, piece, error)`.
    pub fn errors(&self) -> Vec<(usize, usize, crate::Error)> {
        self.contours
            .iter()
            .enumerate()
            .flat_map(|(k, e)| e.errors().into_iter().map(move |(j, err)| (k, j, err)))
            .collect()
    }

    /// The nearest point of any contour's curve to `p`: the contour and the hit.
    pub fn hit_test(&self, p: Point) -> Option<(usize, Hit)> {
        self.contours
            .iter()
            .enumerate()
            .filter_map(|(k, e)| e.hit_test(p).map(|h| (k, h)))
            .min_by(|a, b| a.1.distance.total_cmp(&b.1.distance))
    }

    /// The input point nearest to `p` within `radius`, of any contour: `(contour, index)`.
    /// On a tie the contour listed first wins.
    pub fn nearest_point(&self, p: Point, radius: f64) -> Option<(usize, usize)> {
        let mut best: Option<(usize, usize, f64)> = None;
        for (k, e) in self.contours.iter().enumerate() {
            for (i, q) in e.doc().points.iter().enumerate() {
                let d = (q.point() - p).hypot();
                if d <= radius && best.map_or(true, |b| d < b.2) {
                    best = Some((k, i, d));
                }
            }
        }
        best.map(|(k, i, _)| (k, i))
    }

    /// Every contour as one subpath ([`Editor::outline`]): the drawing's outline, a closed
    /// contour ending in `Z`.
    pub fn outline(&self) -> BezPath {
        let mut out = BezPath::new();
        for e in &self.contours {
            out.extend(e.outline().elements().iter().copied());
        }
        out
    }

    /// The bounding box of every contour's points, or `None` without points.
    pub fn bounds(&self) -> Option<kurbo::Rect> {
        let mut pts = self
            .contours
            .iter()
            .flat_map(|e| e.doc().points.iter().map(|q| q.point()));
        let first = pts.next()?;
        Some(pts.fold(kurbo::Rect::from_points(first, first), |r, q| r.union_pt(q)))
    }

    /// The curvature comb of every contour (see [`Comb`]), one scale for all.
    pub fn comb(&self, style: &CombStyle) -> Comb {
        let splines = self
            .contours
            .iter()
            .flat_map(|e| (0..e.pieces()).filter_map(move |j| e.piece_spline(j)));
        Comb::new(splines, style)
    }

    /// The drawing as an SVG document of the given size (user units): the outline as one
    /// path (even-odd filled when `fill`, else stroked).
    pub fn to_svg(&self, width: f64, height: f64, fill: bool) -> String {
        let d = crate::svg_path_data(&self.outline());
        let paint = if fill {
            "fill=\"black\" fill-rule=\"evenodd\""
        } else {
            "fill=\"none\" stroke=\"black\""
        };
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
             viewBox=\"0 0 {width} {height}\">\n<path d=\"{d}\" {paint}/>\n</svg>\n"
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::PathEl;

    fn ring(c: Point, r: f64, n: usize) -> Vec<Point> {
        (0..n)
            .map(|i| {
                let th = i as f64 / n as f64 * std::f64::consts::TAU;
                c + r * kurbo::Vec2::new(th.cos(), th.sin())
            })
            .collect()
    }

    /// An `o`: an outer and an inner closed contour.
    fn o() -> Drawing {
        let mut d = Drawing::new(Scheme::EkCubic);
        for r in [100.0, 60.0] {
            let pts = ring(Point::new(200.0, 200.0), r, 6);
            let (k, _) = d.start_contour(pts[0]);
            for &p in &pts[1..] {
                assert!(d.add_point(k, p).errors.is_empty());
            }
            assert!(d.set_closed(k, true).errors.is_empty());
        }
        d
    }

    #[test]
    fn contours_share_one_history() {
        let mut d = o();
        assert_eq!(d.len(), 2);
        let outline = d.outline();
        let closes = outline
            .elements()
            .iter()
            .filter(|e| matches!(e, PathEl::ClosePath))
            .count();
        assert_eq!(closes, 2);
        // 2 × (start, 5 adds, close) steps.
        let mut steps = 0;
        while d.undo() {
            steps += 1;
        }
        assert_eq!(steps, 14);
        assert!(d.is_empty());
        while d.redo() {}
        assert_eq!(d.outline(), outline);
    }

    #[test]
    fn clear_delete_and_drags_are_undone() {
        let mut d = o();
        let before = d.outline();
        assert!(d.clear());
        assert!(d.outline().elements().is_empty());
        assert!(d.undo());
        assert_eq!(d.outline(), before);
        assert!(d.delete_contour(0));
        assert_eq!(d.len(), 1);
        assert!(!d.delete_contour(5));
        assert!(d.undo());
        assert_eq!(d.outline(), before);
        // A drag of 10 updates is one step; an edit in another contour ends it.
        let p = d.contour(1).unwrap().doc().points[2].point();
        for j in 0..10 {
            d.drag_point(1, 2, p + kurbo::Vec2::new(j as f64, 0.0));
        }
        d.end_drag();
        d.toggle_corner(0, 1);
        assert!(d.undo() && d.undo());
        assert_eq!(d.outline(), before);
        assert!(d.redo());
        assert_eq!(d.contour(1).unwrap().doc().points[2].x, p.x + 9.0);
        // A contour is not started at a point that is not finite.
        let (k, c) = d.start_contour(Point::new(f64::NAN, 0.0));
        assert!(c.rejected && k == d.len() && d.len() == 2);
        // Out-of-range edits change nothing and record nothing.
        assert_eq!(d.move_point(7, 0, p), Change::default());
        assert_eq!(d.move_point(0, 70, p), Change::default());
        assert!(d.redo() && !d.redo());
    }

    #[test]
    fn scheme_hits_and_insertion_span_contours() {
        let mut d = o();
        d.set_scheme(Scheme::EkTrig);
        assert!(d
            .contours()
            .iter()
            .all(|e| e.doc().scheme == Scheme::EkTrig));
        assert!(d.undo());
        assert_eq!(d.scheme(), Scheme::EkCubic);
        assert!(d
            .contours()
            .iter()
            .all(|e| e.doc().scheme == Scheme::EkCubic));
        // A point near the inner ring is found in contour 1.
        let q = d.contour(1).unwrap().doc().points[3].point();
        assert_eq!(
            d.nearest_point(q + kurbo::Vec2::new(2.0, 0.0), 5.0),
            Some((1, 3))
        );
        let (k, hit) = d.hit_test(Point::new(200.0, 139.0)).unwrap();
        assert_eq!(k, 1);
        assert!(hit.distance < 2.0);
        let (k, at, _) = d.insert_on_curve(Point::new(200.0, 139.0)).unwrap();
        assert_eq!(k, 1);
        assert!((d.contour(1).unwrap().doc().points[at].y - 140.0).abs() < 1.0);
        assert_eq!(d.contour(1).unwrap().doc().points.len(), 7);
        assert!(d.undo());
        assert_eq!(d.contour(1).unwrap().doc().points.len(), 6);
        let comb = d.comb(&CombStyle::default());
        assert_eq!(comb.teeth.len(), 2);
        let b = d.bounds().unwrap();
        assert!((b.width() - 200.0).abs() < 1e-9);
    }

    #[test]
    fn a_closed_path_with_corners_is_one_subpath() {
        let mut d = o();
        d.toggle_corner(0, 0);
        d.toggle_corner(0, 3);
        let e = d.contour(0).unwrap();
        assert_eq!(e.pieces(), 2);
        let out = e.outline();
        let els = out.elements();
        assert_eq!(
            els.iter()
                .filter(|e| matches!(e, PathEl::MoveTo(_)))
                .count(),
            1
        );
        assert_eq!(els.last(), Some(&PathEl::ClosePath));
        let svg = d.to_svg(400.0, 400.0, true);
        assert_eq!(svg.matches('Z').count(), 2, "{svg}");
        assert_eq!(svg.matches('M').count(), 2, "{svg}");
    }
}
