//! Undo and redo: each edit is an undo step, a snapshot of the document and of the curves
//! shown for it.

use crate::{Error, Spline};

use super::document::{non_finite, PathDoc};
use super::edits::Touched;
use super::pieces::{pieces_of, Resolve};
use super::{Change, Editor};

/// A snapshot for undo/redo: the document and the curves shown for it.
#[derive(Clone, Debug)]
pub(super) struct Snapshot {
    doc: PathDoc,
    splines: Vec<(Option<Spline>, Option<Error>)>,
}

/// Maximum undo steps kept.
const UNDO_LIMIT: usize = 1000;

impl Editor {
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
    pub(super) fn edit(&mut self, f: impl FnOnce(&mut PathDoc) -> Touched) -> Change {
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
    pub(super) fn apply_edit(&mut self, f: impl FnOnce(&mut PathDoc) -> Touched) -> Change {
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
}
