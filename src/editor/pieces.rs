//! The pieces of a path, cut at its corners, and their solves.

use kurbo::{Point, Vec2};

use crate::{Error, Scheme, Shape, SolveOptions, SolvedState, Solver, Spline};

use super::document::PathDoc;
use super::{Change, Editor};

/// A piece of the path between corners: input point indices in order (the ends are corners
/// or path ends) and whether it is one closed curve.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct PieceSpec {
    pub(super) indices: Vec<usize>,
    pub(super) closed: bool,
}

/// The pieces of a document (see the module docs).
pub(super) fn pieces_of(doc: &PathDoc) -> Vec<PieceSpec> {
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
pub(super) struct Piece {
    pub(super) spec: PieceSpec,
    solver: Solver,
    pub(super) spline: Option<Spline>,
    /// Why the last solve failed (the curve is then that of an earlier state).
    pub(super) error: Option<Error>,
    /// Where the next cold solve starts (a saved solution), if anywhere.
    start: Option<SolvedState>,
}

/// How a piece is re-solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Resolve {
    /// From scratch.
    Cold,
    /// Warm, after its points moved.
    Positions,
    /// Warm, after its shapes or scheme changed.
    Shapes,
}

/// The work a drag update's solve may do, in input points × solver iterations (an iteration
/// costs `O(n)`): a 300-point piece gets 50 iterations per update, a 20-point one 750.
/// Measured natively on a 300-point κ path that does not converge: about 0.13 ms per
/// iteration, so 6–7 ms per update.
pub const DRAG_WORK: usize = 15_000;

/// Fewest iterations a drag update's solve may take, however long the piece: enough for a
/// warm solve to follow a small move (a few iterations) while a cap set by the caller
/// ([`Editor::set_drag_work`]) still holds for pieces of hundreds of points (at 20, the
/// web page's cap did not apply below 200 points per piece).
const DRAG_MIN_ITERATIONS: usize = 10;

/// The options of the pieces' solvers: the best curve is returned when a solve does not
/// converge (the editor draws it, flagged).
fn piece_options() -> SolveOptions {
    SolveOptions {
        accept_unconverged: true,
        ..SolveOptions::default()
    }
}

/// The prescribed tangents of a piece's points (`None` if it has none): at a piece's first
/// point its outgoing [`EditPoint::tangent`](super::EditPoint::tangent); at an open piece's last point that is a
/// corner, its [`EditPoint::tangent_in`](super::EditPoint::tangent_in); elsewhere [`EditPoint::tangent`](super::EditPoint::tangent).
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

impl Editor {
    /// Re-cuts the pieces and solves all of them, each from the document's saved solution
    /// where it has one, else an unchanged piece from its own last solution, else from
    /// scratch.
    pub(super) fn rebuild(&mut self) -> Change {
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
    pub(super) fn solve_piece(&mut self, k: usize, how: Resolve, change: &mut Change) {
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::editor::EditPoint;

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
