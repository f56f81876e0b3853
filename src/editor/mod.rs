//! An editing engine for a curvature-pen path tool, independent of any UI.
//!
//! A [`PathDoc`] is what the user edits: points with a per-point εκ shape and a corner
//! flag, open or closed, and a scheme. An [`Editor`] holds a document and its solved curve
//! and applies edits — add, insert on the curve, move, delete, set shape, toggle corner,
//! open/close, change scheme — each followed by a re-solve that starts from the previous
//! solution, and undo/redo. A drag gesture (of a point, [`Editor::drag_point`], or of a shape
//! slider, [`Editor::drag_shape`], until [`Editor::end_drag`]) is one undo step however many
//! updates it has.
//!
//! **Corners** split the path into pieces: each piece runs from one corner (or path end) to
//! the next and is solved as its own open curve, so the path has a tangent break at every
//! corner. A closed path without corners is one closed curve. A piece of two points is a
//! straight segment. While a closed path has fewer than three points it is drawn open.
//!
//! **Failures never blank the drawing.** A solve that does not converge shows the best curve
//! it found, flagged: [`Editor::piece_error`] holds [`Error::NotConverged`] with the
//! residual, and so does the [`Change`]. During a drag each update's solve is capped at
//! [`DRAG_WORK`] (point × iterations), so a drag stays within a frame even where the solve
//! fails; [`Editor::end_drag`] then finishes any flagged piece with the full budget. A
//! move that leaves a piece with no curve at all (a point dragged onto its neighbour) keeps
//! that piece's last curve and reports the error; the document still takes the move, so the
//! user can drag on. An edit that changes the piece structure and would leave a piece with
//! no curve, and any edit with a coordinate or shape that is NaN or infinite, is not applied
//! ([`Change::rejected`]). Undo and redo restore the curves and errors shown for each
//! state ([`Editor::errors`]).
//!
//! ```
//! use kappa::editor::Editor;
//! use kappa::Scheme;
//! use kurbo::Point;
//!
//! let mut editor = Editor::new(Scheme::EkCubic);
//! for p in [(0.0, 0.0), (100.0, 20.0), (150.0, 100.0), (60.0, 140.0)] {
//!     editor.add_point(Point::from(p));
//! }
//! // A drag: ten updates, each a warm re-solve of the pieces holding the point.
//! for k in 1..=10 {
//!     let change = editor.drag_point(1, Point::new(100.0 + k as f64, 20.0));
//!     assert!(change.errors.is_empty() && change.resolved == [0]);
//! }
//! editor.end_drag();
//! assert_eq!(editor.doc().points[1].point(), Point::new(110.0, 20.0));
//! // The whole drag is one undo step.
//! assert!(editor.undo());
//! assert_eq!(editor.doc().points[1].point(), Point::new(100.0, 20.0));
//! ```

mod comb;
mod drawing;
#[cfg(feature = "serde")]
mod file;
#[cfg(feature = "render")]
mod svg;

pub use comb::{Comb, CombStyle};
pub use drawing::Drawing;
#[cfg(feature = "serde")]
pub use file::{extract_svg_document, import_svg_paths, DrawingDoc, SVG_METADATA_ID};

#[cfg(feature = "render")]
pub use svg::import_svg;

use kurbo::{BezPath, Point, Vec2};

use crate::fit::{FitMethod, FitOptions};
use crate::{Error, Scheme, Segment, Shape, SolveOptions, SolvedState, Solver, Spline};

/// One point of a path being edited.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EditPoint {
    /// x coordinate.
    pub x: f64,
    /// y coordinate.
    pub y: f64,
    /// The εκ shape parameter of this point (ignored by the κ scheme and at piece ends).
    pub shape: f64,
    /// A corner: the path has a tangent break here.
    #[cfg_attr(feature = "serde", serde(default))]
    pub corner: bool,
    /// A prescribed tangent direction (any length but zero): the curve leaves the point
    /// along it ([`Solver::solve_with_tangents`]). At a corner it is the direction of the
    /// piece that starts there; [`EditPoint::tangent_in`] is the other side's. A smooth join
    /// of a line and a curve is a corner whose tangent on the curve's side runs along the
    /// line.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub tangent: Option<[f64; 2]>,
    /// At a corner, the prescribed direction in which the piece that ends there arrives
    /// (ignored elsewhere).
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub tangent_in: Option<[f64; 2]>,
}

impl EditPoint {
    /// The position.
    pub fn point(&self) -> Point {
        Point::new(self.x, self.y)
    }
}

/// The document of a path tool: serialisable (feature `serde`), and all an [`Editor`] needs
/// to rebuild the curve.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PathDoc {
    /// The points in order.
    pub points: Vec<EditPoint>,
    /// Whether the path is closed.
    pub closed: bool,
    /// The curve scheme.
    pub scheme: Scheme,
    /// The solution each piece shows, in piece order (`None` for a piece that did not
    /// solve): kept up to date by the [`Editor`], so that a saved document reopens with the
    /// curves it showed (see [`SolvedState`]) however it was edited. Empty for a new
    /// document, or to solve from scratch; an entry that does not fit its piece is ignored.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Vec::is_empty")
    )]
    pub solution: Vec<Option<SolvedState>>,
}

impl Default for PathDoc {
    fn default() -> PathDoc {
        PathDoc {
            points: Vec::new(),
            closed: false,
            scheme: Scheme::Kappa,
            solution: Vec::new(),
        }
    }
}

/// A piece of the path between corners: input point indices in order (the ends are corners
/// or path ends) and whether it is one closed curve.
#[derive(Clone, Debug, PartialEq)]
struct PieceSpec {
    indices: Vec<usize>,
    closed: bool,
}

/// The pieces of a document (see the module docs).
fn pieces_of(doc: &PathDoc) -> Vec<PieceSpec> {
    let n = doc.points.len();
    if n < 2 {
        return Vec::new();
    }
    let closed = doc.closed && n >= 3;
    let corners: Vec<usize> = (0..n).filter(|&i| doc.points[i].corner).collect();
    if closed && corners.is_empty() {
        return vec![PieceSpec {
            indices: (0..n).collect(),
            closed: true,
        }];
    }
    let mut out = Vec::new();
    if closed {
        // From each corner to the next, cyclically.
        for (k, &c) in corners.iter().enumerate() {
            let next = corners[(k + 1) % corners.len()];
            let mut indices = vec![c];
            let mut i = c;
            loop {
                i = (i + 1) % n;
                indices.push(i);
                if i == next {
                    break;
                }
            }
            out.push(PieceSpec {
                indices,
                closed: false,
            });
        }
    } else {
        let mut start = 0;
        for i in 1..n {
            if i == n - 1 || doc.points[i].corner {
                out.push(PieceSpec {
                    indices: (start..=i).collect(),
                    closed: false,
                });
                start = i;
            }
        }
    }
    out
}

/// A solved piece: its spec, its solver (kept for warm re-solves) and its last curve.
#[derive(Clone, Debug)]
struct Piece {
    spec: PieceSpec,
    solver: Solver,
    spline: Option<Spline>,
    /// Why the last solve failed (the curve is then that of an earlier state).
    error: Option<Error>,
    /// Where the next cold solve starts (a saved solution), if anywhere.
    start: Option<SolvedState>,
}

/// What an edit did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Change {
    /// Pieces re-solved (indices into [`Editor::pieces`]).
    pub resolved: Vec<usize>,
    /// Solver iterations spent, over all re-solved pieces.
    pub iterations: usize,
    /// Whether the piece structure changed (pieces added, removed or re-cut).
    pub restructured: bool,
    /// Pieces that did not solve, with the reason: [`Error::NotConverged`] for a piece that
    /// shows its best unconverged curve, any other error for one that kept its previous
    /// curve.
    pub errors: Vec<(usize, Error)>,
    /// The edit was not applied and the document is as it was (see the module docs); the
    /// reason is in `errors`.
    pub rejected: bool,
}

/// The result of [`Editor::hit_test`]: the nearest point on the curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The piece.
    pub piece: usize,
    /// The segment within the piece.
    pub segment: usize,
    /// The parameter on that segment.
    pub t: f64,
    /// The nearest curve point.
    pub point: Point,
    /// Its distance from the query point.
    pub distance: f64,
}

/// What an edit changed, for choosing the re-solve.
enum Touched {
    /// The positions of these points (the same pieces).
    Positions(Vec<usize>),
    /// The shapes (or the scheme) of these points (the same pieces).
    Shapes(Vec<usize>),
    /// Positions and prescribed tangents of these points (the same pieces, solved cold).
    Tangents(Vec<usize>),
    /// Anything else: the pieces are re-cut.
    Structure,
}

/// A snapshot for undo/redo: the document and the curves shown for it.
#[derive(Clone, Debug)]
struct Snapshot {
    doc: PathDoc,
    splines: Vec<(Option<Spline>, Option<Error>)>,
}

/// How a piece is re-solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Resolve {
    /// From scratch.
    Cold,
    /// Warm, after its points moved.
    Positions,
    /// Warm, after its shapes or scheme changed.
    Shapes,
}

/// Maximum undo steps kept.
const UNDO_LIMIT: usize = 1000;

/// The work a drag update's solve may do, in input points × solver iterations (an iteration
/// costs `O(n)`): a 300-point piece gets 50 iterations per update, a 20-point one 750.
/// Measured natively on a 300-point κ path that does not converge: about 0.13 ms per
/// iteration, so 6–7 ms per update.
pub const DRAG_WORK: usize = 15_000;

/// Fewest iterations a drag update's solve may take, however long the piece.
const DRAG_MIN_ITERATIONS: usize = 20;

/// A new point closer than this to a neighbour, relative to the drawing size, is not
/// inserted by [`Editor::insert_on_curve`] (it would nearly repeat that point).
const INSERT_CLEARANCE: f64 = 1e-6;

/// The options of the pieces' solvers: the best curve is returned when a solve does not
/// converge (the editor draws it, flagged).
fn piece_options() -> SolveOptions {
    SolveOptions {
        accept_unconverged: true,
        ..SolveOptions::default()
    }
}

/// The editing engine (see the module docs).
///
/// ```
/// use kappa::editor::Editor;
/// use kappa::Scheme;
/// use kurbo::Point;
///
/// let mut editor = Editor::new(Scheme::Kappa);
/// for p in [(0.0, 0.0), (100.0, 20.0), (150.0, 100.0), (60.0, 140.0)] {
///     editor.add_point(Point::from(p));
/// }
/// assert_eq!(editor.pieces(), 1);
/// // A corner cuts the open path into two pieces, each solved on its own.
/// editor.toggle_corner(1);
/// assert_eq!(editor.pieces(), 2);
/// assert_eq!(editor.piece_points(0), [0, 1]);
/// assert_eq!(editor.piece_points(1), [1, 2, 3]);
/// // A move re-solves only the piece holding the point.
/// let change = editor.move_point(3, Point::new(50.0, 150.0));
/// assert_eq!(change.resolved, [1]);
/// // Undo restores the document and the curve shown.
/// assert!(editor.undo());
/// assert_eq!(editor.doc().points[3].point(), Point::new(60.0, 140.0));
/// assert!(editor.undo());
/// assert_eq!(editor.pieces(), 1);
/// ```
#[derive(Clone, Debug, Default)]
pub struct Editor {
    doc: PathDoc,
    pieces: Vec<Piece>,
    undo: Vec<Snapshot>,
    redo: Vec<Snapshot>,
    /// The drag gesture in progress, whose start is already on the undo stack.
    dragging: Option<Gesture>,
    /// Solves are capped at [`DRAG_WORK`] (a drag update is being applied).
    capped: bool,
    /// Undo steps pushed so far (a [`Drawing`] reads it to tell whether an edit made one).
    steps: u64,
    /// The work a drag update's solve may do, if not [`DRAG_WORK`].
    drag_work: Option<usize>,
}

/// A drag gesture: what is dragged, and of which point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Gesture {
    /// The point's position.
    Point(usize),
    /// The point's shape (a slider).
    Shape(usize),
    /// The point's prescribed tangent (`true`: the incoming one), by its handle.
    Tangent(usize, bool),
}

impl Editor {
    /// An empty editor for `scheme`.
    pub fn new(scheme: Scheme) -> Editor {
        Editor {
            doc: PathDoc {
                scheme,
                ..PathDoc::default()
            },
            ..Editor::default()
        }
    }

    /// An editor showing `doc` (solved from scratch).
    pub fn from_doc(doc: PathDoc) -> (Editor, Change) {
        let mut e = Editor {
            doc,
            ..Editor::default()
        };
        let change = e.rebuild();
        (e, change)
    }

    /// Sets the work a drag update's solve may do, in input points × solver iterations
    /// (default [`DRAG_WORK`]; at least 20 iterations are always allowed): lower it where an
    /// iteration costs more than natively, as in WebAssembly.
    pub fn set_drag_work(&mut self, work: usize) {
        self.drag_work = Some(work);
    }

    /// The document.
    pub fn doc(&self) -> &PathDoc {
        &self.doc
    }

    /// The number of pieces (see the module docs).
    pub fn pieces(&self) -> usize {
        self.pieces.len()
    }

    /// The solved curve of piece `k` (`None` if it has never been solved).
    pub fn piece_spline(&self, k: usize) -> Option<&Spline> {
        self.pieces.get(k).and_then(|p| p.spline.as_ref())
    }

    /// Why the last solve of piece `k` failed, if it did: its curve is then the last one
    /// that solved (`None` also for out-of-range `k`).
    pub fn piece_error(&self, k: usize) -> Option<&Error> {
        self.pieces.get(k).and_then(|p| p.error.as_ref())
    }

    /// The input point indices of piece `k`.
    pub fn piece_points(&self, k: usize) -> &[usize] {
        self.pieces.get(k).map_or(&[], |p| &p.spec.indices[..])
    }

    /// The default shape for new points.
    fn default_shape(&self) -> f64 {
        let prev = self.doc.points.last().map(|p| p.shape);
        let (min, max) = self.doc.scheme.shape_range();
        match prev {
            Some(a) if a >= min && (a < max || min == max) => a,
            _ => self.doc.scheme.neutral_shape(),
        }
    }

    /// Appends a point at the end of the path.
    pub fn add_point(&mut self, p: Point) -> Change {
        let shape = self.default_shape();
        self.edit(|doc| {
            doc.points.push(EditPoint {
                x: p.x,
                y: p.y,
                shape,
                corner: false,
                tangent: None,
                tangent_in: None,
            });
            Touched::Structure
        })
    }

    /// Inserts a point on the curve at the location nearest to `p` (between the two input
    /// points whose stretch of curve it falls on), so that the curve changes little. Returns
    /// `None` (and changes nothing) if the curve is empty or the nearest location is within
    /// `1e-6` of the drawing size of an existing point (a click beyond an open end, say).
    pub fn insert_on_curve(&mut self, p: Point) -> Option<(usize, Change)> {
        let hit = self.hit_test(p)?;
        let piece = &self.pieces[hit.piece];
        let spline = piece.spline.as_ref()?;
        let seg = spline.segments()[hit.segment];
        let idx = &piece.spec.indices;
        // Segment j peaks at the piece's point j (closed) or j + 1 (open); before its peak it
        // runs from the previous point.
        let peak = if piece.spec.closed {
            hit.segment
        } else if idx.len() == 2 {
            // A straight two-point piece: insert between its ends.
            0
        } else {
            hit.segment + 1
        };
        let after_local = if idx.len() == 2 || hit.t >= seg.t_max {
            peak
        } else {
            peak + idx.len() - 1
        } % idx.len();
        let after = idx[after_local];
        let at = after + 1;
        // Never a near-repeat of a neighbour (a click beyond an open end hits the end).
        let size = self.doc_size();
        let before_pt = self.doc.points[after].point();
        let after_pt = self.doc.points[at % self.doc.points.len()].point();
        let clear = |q: Point| (hit.point - q).hypot() > INSERT_CLEARANCE * size;
        if !clear(before_pt) || !clear(after_pt) {
            return None;
        }
        let shape = self.doc.points[after].shape;
        let change = self.edit(|doc| {
            doc.points.insert(
                at,
                EditPoint {
                    x: hit.point.x,
                    y: hit.point.y,
                    shape,
                    corner: false,
                    tangent: None,
                    tangent_in: None,
                },
            );
            Touched::Structure
        });
        Some((at, change))
    }

    /// Moves point `i` to `p` (the drag case: only the pieces holding `i` are re-solved,
    /// warm). Out-of-range indices change nothing.
    pub fn move_point(&mut self, i: usize, p: Point) -> Change {
        if i >= self.doc.points.len() {
            return Change::default();
        }
        self.edit(|doc| move_keeping_joins(doc, i, p))
    }

    /// Moves point `i` to `p` as one update of a drag gesture: like [`Editor::move_point`],
    /// but consecutive drags of the same point make one undo step (the state before the
    /// gesture's first update), so a drag of a thousand mouse moves is undone at once and
    /// costs no snapshot per update. The gesture ends at [`Editor::end_drag`], at any other
    /// edit, undo or redo, or at a drag of another point. Out-of-range indices change
    /// nothing.
    pub fn drag_point(&mut self, i: usize, p: Point) -> Change {
        if i >= self.doc.points.len() {
            return Change::default();
        }
        self.gesture(Gesture::Point(i), |doc| move_keeping_joins(doc, i, p))
    }

    /// Sets the shape of point `i` as one update of a slider drag: like
    /// [`Editor::set_shape`], with the undo steps of [`Editor::drag_point`] (consecutive
    /// shape drags of the same point are one step, until [`Editor::end_drag`]).
    pub fn drag_shape(&mut self, i: usize, a: f64) -> Change {
        if i >= self.doc.points.len() {
            return Change::default();
        }
        self.gesture(Gesture::Shape(i), |doc| {
            doc.points[i].shape = a;
            Touched::Shapes(vec![i])
        })
    }

    /// Applies an edit of a gesture: a new undo step unless it continues the gesture in
    /// progress.
    fn gesture(&mut self, g: Gesture, f: impl FnOnce(&mut PathDoc) -> Touched) -> Change {
        self.capped = true;
        let change = if self.dragging == Some(g) {
            self.apply_edit(f)
        } else {
            self.edit(f)
        };
        self.capped = false;
        self.dragging = Some(g);
        change
    }

    /// Ends the drag gesture in progress (on mouse up): the next [`Editor::drag_point`] or
    /// [`Editor::drag_shape`] starts a new undo step. Pieces whose capped drag solves did not
    /// converge are solved again with the full budget (the returned change says which).
    pub fn end_drag(&mut self) -> Change {
        let mut change = Change::default();
        if self.dragging.take().is_none() {
            return change;
        }
        // Finish what the capped drag updates left unconverged, with the full budget.
        for k in 0..self.pieces.len() {
            let flagged = matches!(self.pieces[k].error, Some(Error::NotConverged { .. }));
            if flagged {
                self.solve_piece(k, Resolve::Cold, &mut change);
            }
        }
        change
    }

    /// Deletes point `i`.
    pub fn delete_point(&mut self, i: usize) -> Change {
        if i >= self.doc.points.len() {
            return Change::default();
        }
        self.edit(|doc| {
            doc.points.remove(i);
            Touched::Structure
        })
    }

    /// Sets the shape of point `i` (validated by the scheme when solved).
    pub fn set_shape(&mut self, i: usize, a: f64) -> Change {
        if i >= self.doc.points.len() {
            return Change::default();
        }
        self.edit(|doc| {
            doc.points[i].shape = a;
            Touched::Shapes(vec![i])
        })
    }

    /// Toggles the corner flag of point `i`.
    pub fn toggle_corner(&mut self, i: usize) -> Change {
        if i >= self.doc.points.len() {
            return Change::default();
        }
        self.edit(|doc| {
            doc.points[i].corner = !doc.points[i].corner;
            Touched::Structure
        })
    }

    /// Sets or clears point `i`'s prescribed tangent ([`EditPoint::tangent`]; `incoming`:
    /// [`EditPoint::tangent_in`], the side of a corner where a piece ends). A zero or
    /// non-finite vector is rejected ([`Change::rejected`]).
    pub fn set_tangent(&mut self, i: usize, tangent: Option<Vec2>, incoming: bool) -> Change {
        if i >= self.doc.points.len() {
            return Change::default();
        }
        self.edit(|doc| {
            let v = tangent.map(|v| [v.x, v.y]);
            if incoming {
                doc.points[i].tangent_in = v;
            } else {
                doc.points[i].tangent = v;
            }
            Touched::Structure
        })
    }

    /// Sets point `i`'s prescribed tangent as one update of a handle drag: like
    /// [`Editor::set_tangent`], with the undo steps of [`Editor::drag_point`] (consecutive
    /// updates of the same handle are one step, until [`Editor::end_drag`]).
    pub fn drag_tangent(&mut self, i: usize, tangent: Vec2, incoming: bool) -> Change {
        if i >= self.doc.points.len() {
            return Change::default();
        }
        self.gesture(Gesture::Tangent(i, incoming), |doc| {
            let v = Some([tangent.x, tangent.y]);
            if incoming {
                doc.points[i].tangent_in = v;
            } else {
                doc.points[i].tangent = v;
            }
            Touched::Tangents(vec![i])
        })
    }

    /// Makes corner `i` a smooth line-to-curve join: where a straight segment is on one side
    /// of it and a curve on the other ([`join_line`]), the curve side's tangent is set along
    /// the line. Moving either point of the line keeps it along the line
    /// ([`Editor::move_point`]). Elsewhere nothing changes ([`Change::rejected`]).
    pub fn set_smooth_join(&mut self, i: usize) -> Change {
        let Some((dir, incoming)) = join_line(&self.doc, i) else {
            return Change {
                rejected: true,
                ..Change::default()
            };
        };
        self.set_tangent(i, Some(dir), incoming)
    }

    /// Opens or closes the path.
    pub fn set_closed(&mut self, closed: bool) -> Change {
        self.edit(|doc| {
            doc.closed = closed;
            Touched::Structure
        })
    }

    /// Switches the scheme; shapes outside the new scheme's range are moved to its default.
    pub fn set_scheme(&mut self, scheme: Scheme) -> Change {
        self.edit(|doc| {
            doc.scheme = scheme;
            let (min, max) = scheme.shape_range();
            for p in &mut doc.points {
                if scheme == Scheme::Kappa {
                    continue;
                }
                if !(p.shape >= min && p.shape < max) {
                    p.shape = scheme.neutral_shape();
                }
            }
            Touched::Shapes((0..doc.points.len()).collect())
        })
    }

    /// Undoes the last edit; `false` if there is none.
    pub fn undo(&mut self) -> bool {
        self.dragging = None;
        match self.undo.pop() {
            Some(snap) => {
                let current = self.snapshot();
                self.redo.push(current);
                self.restore(snap);
                true
            }
            None => false,
        }
    }

    /// Redoes the last undone edit; `false` if there is none.
    pub fn redo(&mut self) -> bool {
        self.dragging = None;
        match self.redo.pop() {
            Some(snap) => {
                let current = self.snapshot();
                self.undo.push(current);
                self.restore(snap);
                true
            }
            None => false,
        }
    }

    fn snapshot(&self) -> Snapshot {
        Snapshot {
            doc: self.doc.clone(),
            splines: self
                .pieces
                .iter()
                .map(|p| (p.spline.clone(), p.error.clone()))
                .collect(),
        }
    }

    /// Restores a snapshot: the document and exactly the curves shown for it; the solvers
    /// are primed by a solve of the restored document so that later edits start warm.
    fn restore(&mut self, snap: Snapshot) {
        self.doc = snap.doc.clone();
        self.rebuild();
        for (piece, (spline, error)) in self.pieces.iter_mut().zip(snap.splines) {
            piece.spline = spline;
            piece.error = error;
        }
        self.doc = snap.doc;
    }

    /// Applies an edit to the document as a new undo step and re-solves what it touched.
    fn edit(&mut self, f: impl FnOnce(&mut PathDoc) -> Touched) -> Change {
        self.dragging = None;
        let before = self.snapshot();
        self.undo.push(before);
        if self.undo.len() > UNDO_LIMIT {
            self.undo.remove(0);
        }
        self.steps = self.steps.wrapping_add(1);
        let change = self.apply_edit(f);
        if change.rejected {
            self.undo.pop();
            self.steps = self.steps.wrapping_sub(1);
        }
        change
    }

    /// Applies an edit to the document (within the current undo step) and re-solves what it
    /// touched. An edit with a non-finite value, or one that re-cuts the pieces and leaves
    /// one without a curve, is undone ([`Change::rejected`]).
    fn apply_edit(&mut self, f: impl FnOnce(&mut PathDoc) -> Touched) -> Change {
        let before = self.doc.clone();
        let touched = f(&mut self.doc);
        if let Some(e) = non_finite(&self.doc) {
            self.doc = before;
            return Change {
                errors: vec![(0, e)],
                rejected: true,
                ..Change::default()
            };
        }
        self.redo.clear();
        let specs = pieces_of(&self.doc);
        let same = specs.len() == self.pieces.len()
            && specs.iter().zip(&self.pieces).all(|(s, p)| *s == p.spec);
        let (points, how) = match touched {
            Touched::Positions(p) if same => (p, Resolve::Positions),
            Touched::Shapes(p) if same => (p, Resolve::Shapes),
            Touched::Tangents(p) if same => (p, Resolve::Cold),
            _ => {
                let saved = self.pieces.clone();
                // The saved solutions are those of the old pieces (an unchanged piece starts
                // from its solver's own).
                self.doc.solution.clear();
                let mut change = self.rebuild();
                if self
                    .pieces
                    .iter()
                    .any(|p| p.spline.is_none() && p.error.is_some())
                {
                    self.doc = before;
                    self.pieces = saved;
                    change.rejected = true;
                    change.resolved.clear();
                }
                return change;
            }
        };
        let mut change = Change::default();
        for k in 0..self.pieces.len() {
            if self.pieces[k]
                .spec
                .indices
                .iter()
                .any(|i| points.contains(i))
            {
                self.solve_piece(k, how, &mut change);
            }
        }
        change
    }

    /// Re-cuts the pieces and solves all of them, each from the document's saved solution
    /// where it has one, else an unchanged piece from its own last solution, else from
    /// scratch.
    fn rebuild(&mut self) -> Change {
        let specs = pieces_of(&self.doc);
        let mut old = core::mem::take(&mut self.pieces);
        let mut change = Change {
            restructured: true,
            ..Change::default()
        };
        let mut saved = core::mem::take(&mut self.doc.solution);
        saved.resize(specs.len(), None);
        self.doc.solution = vec![None; specs.len()];
        for (spec, saved) in specs.into_iter().zip(saved) {
            let reuse = old.iter().position(|p| p.spec == spec);
            let mut piece = match reuse {
                Some(i) => old.swap_remove(i),
                None => Piece {
                    spec,
                    solver: Solver::with_options(piece_options()),
                    spline: None,
                    error: None,
                    start: None,
                },
            };
            let own = match piece.error {
                None => piece.solver.state(),
                Some(_) => None,
            };
            piece.start = saved.or(own);
            self.pieces.push(piece);
        }
        for k in 0..self.pieces.len() {
            self.solve_piece(k, Resolve::Cold, &mut change);
        }
        change
    }

    /// Solves piece `k` from the document, warm from its last solution where `how` allows.
    fn solve_piece(&mut self, k: usize, how: Resolve, change: &mut Change) {
        let doc = &self.doc;
        let piece = &mut self.pieces[k];
        let pts: Vec<Point> = piece
            .spec
            .indices
            .iter()
            .map(|&i| doc.points[i].point())
            .collect();
        let shape = match doc.scheme {
            Scheme::Kappa => Shape::Neutral,
            _ => {
                let mut a: Vec<f64> = piece
                    .spec
                    .indices
                    .iter()
                    .map(|&i| doc.points[i].shape)
                    .collect();
                // Piece ends have no segment (open pieces): any admissible value will do.
                if !piece.spec.closed {
                    let neutral = doc.scheme.neutral_shape();
                    let last = a.len() - 1;
                    a[0] = neutral;
                    a[last] = neutral;
                }
                Shape::PerPoint(a)
            }
        };
        // A drag update's solve is capped (see the module docs).
        let full = piece_options();
        let max_iterations = if self.capped {
            let work = self.drag_work.unwrap_or(DRAG_WORK);
            (work / pts.len().max(1)).clamp(DRAG_MIN_ITERATIONS, full.max_iterations)
        } else {
            full.max_iterations
        };
        piece.solver.set_options(SolveOptions {
            max_iterations,
            ..full
        });
        let tangents = piece_tangents(doc, &piece.spec);
        // Warm only from a solver whose last solve succeeded (its state is that curve; a
        // warm re-solve keeps the tangents of that solve, and a change of tangents is a
        // structural edit, which solves cold).
        let solved = piece.spline.is_some() && piece.error.is_none();
        let closed = piece.spec.closed;
        let result = match how {
            Resolve::Positions if solved => piece.solver.resolve(&pts),
            Resolve::Shapes if solved => piece.solver.resolve_shapes(doc.scheme, &shape),
            _ => match (piece.start.take(), tangents) {
                (Some(start), None) => piece
                    .solver
                    .solve_from(&pts, closed, doc.scheme, &shape, &start),
                (None, None) => piece.solver.solve(&pts, closed, doc.scheme, &shape),
                (Some(start), Some(t)) => piece
                    .solver
                    .solve_with_tangents_from(&pts, closed, doc.scheme, &shape, &t, &start),
                (None, Some(t)) => piece
                    .solver
                    .solve_with_tangents(&pts, closed, doc.scheme, &shape, &t),
            },
        };
        change.resolved.push(k);
        let state = piece.solver.state();
        if let Some(slot) = self.doc.solution.get_mut(k) {
            *slot = state;
        }
        match result {
            Ok(s) if s.converged() => {
                change.iterations += s.iterations();
                piece.spline = Some(s);
                piece.error = None;
            }
            Ok(s) => {
                // The best curve found, drawn and flagged (or, should it not be finite,
                // the last one).
                change.iterations += s.iterations();
                let report = s.report();
                let e = Error::NotConverged {
                    iterations: report.iterations,
                    residual: report.residual,
                };
                if s.segments()
                    .iter()
                    .all(|g| g.q.iter().all(|q| q.is_finite()))
                {
                    piece.spline = Some(s);
                }
                piece.error = Some(e.clone());
                change.errors.push((k, e));
            }
            Err(e) => {
                piece.error = Some(e.clone());
                change.errors.push((k, e));
            }
        }
    }

    /// The pieces that did not solve, with the reason (see [`Change::errors`]): what the
    /// last edit, undo or redo left.
    pub fn errors(&self) -> Vec<(usize, Error)> {
        self.pieces
            .iter()
            .enumerate()
            .filter_map(|(k, p)| p.error.clone().map(|e| (k, e)))
            .collect()
    }

    /// The size of the drawing: the larger side of the points' bounding box (1 without
    /// points).
    fn doc_size(&self) -> f64 {
        let mut pts = self.doc.points.iter().map(EditPoint::point);
        let Some(first) = pts.next() else {
            return 1.0;
        };
        let r = pts.fold(kurbo::Rect::from_points(first, first), |r, p| r.union_pt(p));
        r.width().max(r.height()).max(f64::MIN_POSITIVE)
    }

    /// The whole path as a kurbo path (one subpath per piece; a closed path without corners
    /// is one closed subpath): exact for κ and εκ-cubic; εκ-trig pieces are fitted by
    /// Hermite subdivision within 1e-4 of their size (fast enough for every drag; export
    /// through [`Editor::piece_spline`] and [`Spline::fit`] for kurbo's fewer cubics).
    pub fn to_bezpath(&self) -> BezPath {
        let mut out = BezPath::new();
        for k in 0..self.pieces.len() {
            append(&mut out, self.piece_bezpath(k));
        }
        out
    }

    /// The path as one subpath, the pieces joined end to start, closed (`Z`) when the path
    /// is closed — what an SVG or font outline holds. A piece without a curve leaves a gap
    /// (the next piece starts a new subpath, and the path is not closed).
    pub fn outline(&self) -> BezPath {
        let mut out = BezPath::new();
        let mut joined = false;
        let mut whole = !self.pieces.is_empty();
        for k in 0..self.pieces.len() {
            let path = self.piece_bezpath(k);
            if path.elements().is_empty() {
                joined = false;
                whole = false;
                continue;
            }
            for (j, el) in path.elements().iter().enumerate() {
                match el {
                    kurbo::PathEl::MoveTo(_) if j == 0 && joined => {}
                    kurbo::PathEl::ClosePath => {}
                    el => out.push(*el),
                }
            }
            joined = true;
        }
        if whole && self.doc.closed && self.doc.points.len() >= 3 {
            out.close_path();
        }
        out
    }

    /// Piece `k` as a kurbo path, as [`Editor::to_bezpath`] draws it (empty without a
    /// curve or for an out-of-range `k`). A page can draw the pieces flagged by
    /// [`Editor::piece_error`] in a warning style.
    pub fn piece_bezpath(&self, k: usize) -> BezPath {
        let Some(s) = self.piece_spline(k) else {
            return BezPath::new();
        };
        if s.scheme().is_polynomial() {
            return s.to_bezpath();
        }
        let options = FitOptions {
            method: FitMethod::Hermite,
            ..FitOptions::default()
        };
        // A drawn curve is finite, so fitting it cannot fail.
        s.fit(&options).map(|f| f.path).unwrap_or_default()
    }

    /// A curvature comb of the exact curve, `samples` teeth per segment.
    pub fn curvature_comb(&self, scale: f64, samples: usize) -> BezPath {
        let mut out = BezPath::new();
        for piece in &self.pieces {
            if let Some(s) = &piece.spline {
                append(&mut out, s.curvature_comb(scale, samples));
            }
        }
        out
    }

    /// The nearest point of the curve to `p`, or `None` if there is no curve (or `p` is not
    /// finite).
    pub fn hit_test(&self, p: Point) -> Option<Hit> {
        if !p.is_finite() {
            return None;
        }
        let mut best: Option<Hit> = None;
        for (k, piece) in self.pieces.iter().enumerate() {
            let Some(spline) = &piece.spline else {
                continue;
            };
            for (j, seg) in spline.segments().iter().enumerate() {
                let (t, q) = nearest_on_segment(seg, p);
                // (f64::hypot: the squares of coordinates beyond 1e154 overflow.)
                let d = (q.x - p.x).hypot(q.y - p.y);
                if d.is_nan() {
                    continue;
                }
                if best.map_or(true, |b| d < b.distance) {
                    best = Some(Hit {
                        piece: k,
                        segment: j,
                        t,
                        point: q,
                        distance: d,
                    });
                }
            }
        }
        best
    }

    /// The path as an SVG document of the given size (user units), stroked, optionally
    /// with its points.
    pub fn to_svg(&self, width: f64, height: f64, with_points: bool) -> String {
        use core::fmt::Write as _;
        let d = crate::svg_path_data(&self.to_bezpath());
        let mut out = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
             viewBox=\"0 0 {width} {height}\">\n<path d=\"{}\" fill=\"none\" stroke=\"black\"/>\n",
            d
        );
        if with_points {
            for q in &self.doc.points {
                let _ = writeln!(
                    out,
                    "<circle cx=\"{}\" cy=\"{}\" r=\"3\" fill=\"red\"/>",
                    q.x, q.y
                );
            }
        }
        out.push_str("</svg>\n");
        out
    }
}

/// Whether the segment from point `c` to its neighbour `l` is straight (a piece of two
/// points: two corners, or a corner and an open path's end).
fn is_line(doc: &PathDoc, c: usize, l: usize) -> bool {
    let n = doc.points.len();
    let end = !doc.closed && (l == 0 || l + 1 == n);
    doc.points[c].corner && (doc.points[l].corner || end)
}

/// The neighbours of point `i` (before, after), cyclically in a closed path.
fn neighbours(doc: &PathDoc, i: usize) -> (Option<usize>, Option<usize>) {
    let n = doc.points.len();
    let closed = doc.closed && n >= 3;
    let prev = if i > 0 {
        Some(i - 1)
    } else {
        closed.then_some(n - 1)
    };
    let next = if i + 1 < n {
        Some(i + 1)
    } else {
        closed.then_some(0)
    };
    (prev, next)
}

/// At corner `c` with a straight segment on one side and a curve on the other: the line's
/// direction (unit, in the direction of travel) and which tangent of `c` the curve side
/// takes (`true`: [`EditPoint::tangent_in`], the curve arrives and the line leaves;
/// `false`: [`EditPoint::tangent`], the line arrives and the curve leaves). `None`
/// elsewhere.
pub fn join_line(doc: &PathDoc, c: usize) -> Option<(Vec2, bool)> {
    if c >= doc.points.len() || !doc.points[c].corner {
        return None;
    }
    let (Some(prev), Some(next)) = neighbours(doc, c) else {
        return None;
    };
    let at = doc.points[c].point();
    let (dir, incoming) = match (is_line(doc, c, prev), is_line(doc, c, next)) {
        (true, false) => (at - doc.points[prev].point(), false),
        (false, true) => (doc.points[next].point() - at, true),
        _ => return None,
    };
    let len = dir.hypot();
    (len > 0.0 && len.is_finite()).then(|| (dir / len, incoming))
}

/// Whether corner `c` is a smooth join: its curve side's tangent runs along the line
/// (within 1e-6 rad, see [`join_line`]).
fn is_smooth_join(doc: &PathDoc, c: usize) -> Option<bool> {
    let (dir, incoming) = join_line(doc, c)?;
    let p = &doc.points[c];
    let [x, y] = if incoming { p.tangent_in } else { p.tangent }?;
    let t = Vec2::new(x, y);
    let len = t.hypot();
    let along = len > 0.0 && t.dot(dir) > 0.0 && (t.cross(dir) / len).abs() < 1e-6;
    along.then_some(incoming)
}

/// Moves point `i` to `p`, keeping the smooth joins at `i` and its neighbours along their
/// lines (their tangents follow the line's new direction).
fn move_keeping_joins(doc: &mut PathDoc, i: usize, p: Point) -> Touched {
    let (prev, next) = neighbours(doc, i);
    let joins: Vec<(usize, bool)> = [prev, Some(i), next]
        .into_iter()
        .flatten()
        .filter_map(|c| is_smooth_join(doc, c).map(|incoming| (c, incoming)))
        .collect();
    doc.points[i].x = p.x;
    doc.points[i].y = p.y;
    if joins.is_empty() {
        return Touched::Positions(vec![i]);
    }
    let mut touched = vec![i];
    for (c, incoming) in joins {
        if let Some((dir, _)) = join_line(doc, c) {
            let v = Some([dir.x, dir.y]);
            if incoming {
                doc.points[c].tangent_in = v;
            } else {
                doc.points[c].tangent = v;
            }
            touched.push(c);
        }
    }
    Touched::Tangents(touched)
}

/// The prescribed tangents of a piece's points (`None` if it has none): at a piece's first
/// point its outgoing [`EditPoint::tangent`]; at an open piece's last point that is a
/// corner, its [`EditPoint::tangent_in`]; elsewhere [`EditPoint::tangent`].
fn piece_tangents(doc: &PathDoc, spec: &PieceSpec) -> Option<Vec<Option<Vec2>>> {
    let m = spec.indices.len();
    let tangents: Vec<Option<Vec2>> = spec
        .indices
        .iter()
        .enumerate()
        .map(|(k, &i)| {
            let p = &doc.points[i];
            let t = if !spec.closed && k + 1 == m && k > 0 && p.corner {
                p.tangent_in
            } else {
                p.tangent
            };
            t.map(|[x, y]| Vec2::new(x, y))
        })
        .collect();
    tangents.iter().any(Option::is_some).then_some(tangents)
}

/// What is wrong with a prescribed tangent, if anything.
fn tangent_problem(v: [f64; 2]) -> Option<&'static str> {
    let len = v[0].hypot(v[1]);
    (!(len > 0.0 && len.is_finite())).then_some("a tangent must be a nonzero, finite vector")
}

/// The first non-finite coordinate or shape of a document, or unusable tangent, as an
/// error.
fn non_finite(doc: &PathDoc) -> Option<Error> {
    doc.points.iter().enumerate().find_map(|(index, p)| {
        if !(p.x.is_finite() && p.y.is_finite()) {
            Some(Error::NonFinitePoint { index })
        } else if let Some(reason) = [p.tangent, p.tangent_in]
            .into_iter()
            .flatten()
            .find_map(tangent_problem)
        {
            Some(Error::InvalidTangent { index, reason })
        } else if !p.shape.is_finite() {
            let (min, max) = doc.scheme.shape_range();
            Some(Error::ShapeOutOfRange {
                index,
                value: p.shape,
                min,
                max,
            })
        } else {
            None
        }
    })
}

/// Appends `path` to `out`, taking it whole when `out` is empty (one piece: no copy).
fn append(out: &mut BezPath, path: BezPath) {
    if out.elements().is_empty() {
        *out = path;
    } else {
        out.extend(path.elements().iter().copied());
    }
}

/// The nearest point of a segment to `p`: 64 samples, then golden-section refinement.
fn nearest_on_segment(seg: &Segment<Point>, p: Point) -> (f64, Point) {
    const SAMPLES: usize = 64;
    // Distances compared in units of the segment's extent: squared differences of
    // coordinates near 1e154 and beyond overflow.
    let [q0, q1, q2] = seg.q;
    let unit = [q1 - q0, q2 - q1, p - q0]
        .iter()
        .map(|v| v.x.abs().max(v.y.abs()))
        .fold(f64::MIN_POSITIVE, f64::max);
    let dist = |t: f64| ((seg.eval(t) - p) / unit).hypot2();
    let mut best = 0;
    let mut best_d = f64::INFINITY;
    for i in 0..=SAMPLES {
        let d = dist(i as f64 / SAMPLES as f64);
        if d < best_d {
            best = i;
            best_d = d;
        }
    }
    let (mut a, mut b) = (
        best.saturating_sub(1) as f64 / SAMPLES as f64,
        (best + 1).min(SAMPLES) as f64 / SAMPLES as f64,
    );
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..50 {
        let (x1, x2) = (b - g * (b - a), a + g * (b - a));
        if dist(x1) < dist(x2) {
            b = x2;
        } else {
            a = x1;
        }
    }
    let t = 0.5 * (a + b);
    (t, seg.eval(t))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc(n: usize, closed: bool, corners: &[usize]) -> PathDoc {
        PathDoc {
            points: (0..n)
                .map(|i| EditPoint {
                    x: i as f64,
                    y: (i * i) as f64,
                    shape: 0.8,
                    corner: corners.contains(&i),
                    tangent: None,
                    tangent_in: None,
                })
                .collect(),
            closed,
            scheme: Scheme::EkCubic,
            solution: Vec::new(),
        }
    }

    #[test]
    fn smooth_joins_follow_their_line() {
        // An n shoulder: a stem (0 to 1) and an arch leaving its top along it.
        let pts = [(0.0, 0.0), (0.0, 400.0), (120.0, 500.0), (250.0, 420.0)];
        let mut e = Editor::new(Scheme::Kappa);
        for (x, y) in pts {
            e.add_point(Point::new(x, y));
        }
        e.toggle_corner(1);
        assert!(e.set_smooth_join(2).rejected);
        assert!(!e.set_smooth_join(1).rejected);
        assert_eq!(e.doc().points[1].tangent, Some([0.0, 1.0]));
        let leaves = |e: &Editor| {
            let d = e.piece_spline(1).unwrap().segments()[0].derivative(0.0);
            let [x, y] = e.doc().points[1].tangent.unwrap();
            (d.cross(Vec2::new(x, y)) / d.hypot()).abs()
        };
        assert!(e.errors().is_empty() && leaves(&e) < 1e-6);
        // Moving the line's other end turns the tangent with it, in the same undo step.
        for k in 1..=5 {
            e.drag_point(0, Point::new(4.0 * k as f64, 0.0));
        }
        e.end_drag();
        let [x, y] = e.doc().points[1].tangent.unwrap();
        assert!((Vec2::new(x, y).cross(Vec2::new(-20.0, 400.0))).abs() < 1e-9);
        assert!(e.errors().is_empty() && leaves(&e) < 1e-6);
        assert!(e.undo());
        assert_eq!(e.doc().points[1].tangent, Some([0.0, 1.0]));
        // A handle drag is one undo step.
        for k in 1..=4 {
            e.drag_tangent(2, Vec2::new(1.0, -0.1 * k as f64), false);
        }
        e.end_drag();
        assert_eq!(e.doc().points[2].tangent, Some([1.0, -0.4]));
        assert!(e.undo());
        assert_eq!(e.doc().points[2].tangent, None);
        // A tangent set by hand off the line is left alone.
        e.set_tangent(1, Some(Vec2::new(0.1, 1.0)), false);
        e.move_point(0, Point::new(10.0, 0.0));
        assert_eq!(e.doc().points[1].tangent, Some([0.1, 1.0]));
    }

    #[test]
    fn pieces_split_at_corners() {
        let open = pieces_of(&doc(6, false, &[2, 4]));
        let idx: Vec<Vec<usize>> = open.iter().map(|p| p.indices.clone()).collect();
        assert_eq!(idx, [vec![0, 1, 2], vec![2, 3, 4], vec![4, 5]]);
        let closed = pieces_of(&doc(6, true, &[1, 4]));
        let idx: Vec<Vec<usize>> = closed.iter().map(|p| p.indices.clone()).collect();
        assert_eq!(idx, [vec![1, 2, 3, 4], vec![4, 5, 0, 1]]);
        let one = pieces_of(&doc(5, true, &[3]));
        assert_eq!(one[0].indices, [3, 4, 0, 1, 2, 3]);
        assert!(!one[0].closed);
        let smooth = pieces_of(&doc(5, true, &[]));
        assert!(smooth[0].closed && smooth.len() == 1);
        assert!(pieces_of(&doc(1, false, &[])).is_empty());
        // A "closed" path of two points is drawn open.
        assert!(!pieces_of(&doc(2, true, &[]))[0].closed);
    }
}
