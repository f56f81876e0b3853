//! The edits: points added, inserted on the curve, moved, dragged and deleted; shapes,
//! corners, tangents, closing and the scheme.

use kurbo::{Point, Vec2};

use crate::{Error, Scheme};

use super::document::{is_smooth_join, join_line, neighbours, EditPoint, PathDoc};
use super::pieces::Resolve;
use super::{Change, Editor};

/// What an edit changed, for choosing the re-solve.
pub(super) enum Touched {
    /// The positions of these points (the same pieces).
    Positions(Vec<usize>),
    /// The shapes (or the scheme) of these points (the same pieces).
    Shapes(Vec<usize>),
    /// Positions and prescribed tangents of these points (the same pieces, solved cold).
    Tangents(Vec<usize>),
    /// Anything else: the pieces are re-cut.
    Structure,
}

/// A drag gesture: what is dragged, and of which point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Gesture {
    /// The point's position.
    Point(usize),
    /// The point's shape (a slider).
    Shape(usize),
    /// The point's prescribed tangent (`true`: the incoming one), by its handle.
    Tangent(usize, bool),
}

/// A new point closer than this to a neighbour, relative to the drawing size, is not
/// inserted by [`Editor::insert_on_curve`] (it would nearly repeat that point).
const INSERT_CLEARANCE: f64 = 1e-6;

impl Editor {
    /// The default shape for new points.
    fn default_shape(&self) -> f64 {
        let prev = self.doc.points.last().map(|p| p.shape);
        let (min, max) = self.doc.scheme.shape_range();
        match prev {
            Some(a) if a >= min && (a < max || min == max) => a,
            _ => self.doc.scheme.neutral_shape(),
        }
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
