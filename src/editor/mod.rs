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
mod document;
mod drawing;
mod edits;
#[cfg(feature = "serde")]
mod file;
mod history;
mod pieces;
#[cfg(feature = "render")]
mod svg;
#[cfg(feature = "serde")]
mod svg_paths;
mod view;

pub use comb::{Comb, CombStyle};
pub use document::{join_line, EditPoint, PathDoc};
pub use drawing::Drawing;
#[cfg(feature = "serde")]
pub use file::{extract_svg_document, DrawingDoc, SVG_METADATA_ID};
pub use pieces::DRAG_WORK;
#[cfg(feature = "render")]
pub use svg::import_svg;
#[cfg(feature = "serde")]
pub use svg_paths::import_svg_paths;
pub use view::Hit;

use crate::{Error, Scheme, Spline};

use edits::Gesture;
use history::Snapshot;
use pieces::Piece;

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

    /// The pieces that did not solve, with the reason (see [`Change::errors`]): what the
    /// last edit, undo or redo left.
    pub fn errors(&self) -> Vec<(usize, Error)> {
        self.pieces
            .iter()
            .enumerate()
            .filter_map(|(k, p)| p.error.clone().map(|e| (k, e)))
            .collect()
    }
}
