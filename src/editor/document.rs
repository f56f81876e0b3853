//! The document of a path tool: [`PathDoc`] and its [`EditPoint`]s, with the straight
//! segments and smooth joins at its corners.

use kurbo::{Point, Vec2};

use crate::{Error, Scheme, SolvedState};

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
    /// along it ([`Solver::solve_with_tangents`](crate::Solver::solve_with_tangents)). At a corner it is the direction of the
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

/// The document of a path tool: serialisable (feature `serde`), and all an [`Editor`](super::Editor) needs
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
    /// solve): kept up to date by the [`Editor`](super::Editor), so that a saved document reopens with the
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

/// Whether the segment from point `c` to its neighbour `l` is straight (a piece of two
/// points: two corners, or a corner and an open path's end).
fn is_line(doc: &PathDoc, c: usize, l: usize) -> bool {
    let n = doc.points.len();
    let end = !doc.closed && (l == 0 || l + 1 == n);
    doc.points[c].corner && (doc.points[l].corner || end)
}

/// The neighbours of point `i` (before, after), cyclically in a closed path.
pub(super) fn neighbours(doc: &PathDoc, i: usize) -> (Option<usize>, Option<usize>) {
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
pub(super) fn is_smooth_join(doc: &PathDoc, c: usize) -> Option<bool> {
    let (dir, incoming) = join_line(doc, c)?;
    let p = &doc.points[c];
    let [x, y] = if incoming { p.tangent_in } else { p.tangent }?;
    let t = Vec2::new(x, y);
    let len = t.hypot();
    let along = len > 0.0 && t.dot(dir) > 0.0 && (t.cross(dir) / len).abs() < 1e-6;
    along.then_some(incoming)
}

/// What is wrong with a prescribed tangent, if anything.
fn tangent_problem(v: [f64; 2]) -> Option<&'static str> {
    let len = v[0].hypot(v[1]);
    (!(len > 0.0 && len.is_finite())).then_some("a tangent must be a nonzero, finite vector")
}

/// The first non-finite coordinate or shape of a document, or unusable tangent, as an
/// error.
pub(super) fn non_finite(doc: &PathDoc) -> Option<Error> {
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
