//! What a draft gives: anchors, pieces, contours and the glyph.

use kurbo::{BezPath, Point, Vec2};

use crate::{SolvedState, Spline};

/// Why an anchor was placed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AnchorKind {
    /// A corner or an end of a straight segment (a piece end).
    Corner,
    /// An on-curve extremum (tangent horizontal or vertical).
    Extremum,
    /// A curvature peak of the original.
    Peak,
    /// Added by the refinement where the draft strayed furthest.
    Refined,
    /// Given by the user.
    User,
}

/// One point of a drafted piece.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Anchor {
    /// The point (on the original outline).
    pub point: Point,
    /// Why it is there.
    pub kind: AnchorKind,
    /// Its shape parameter (`2/3` for κ-curves and for the ends of open pieces).
    pub a: f64,
    /// The original's |κ| at the point (0 for user points).
    pub target_curvature: f64,
    /// The tangent direction the solve held at the anchor
    /// ([`Solver::solve_with_tangents`](crate::Solver::solve_with_tangents)), if any: the
    /// axis of an extremum anchor
    /// ([`DraftOptions::extremum_tangents`](super::DraftOptions::extremum_tangents)).
    pub tangent: Option<Vec2>,
}

/// A drafted piece: an open curve between two corners, or a whole closed contour.
#[derive(Clone, Debug)]
pub struct Piece {
    /// The anchors in order along the piece.
    pub anchors: Vec<Anchor>,
    /// Whether the piece is a closed contour.
    pub closed: bool,
    /// The solved curve.
    pub spline: Spline,
    /// The curve as a path (exact for κ and εκ-cubic; εκ-trig fitted within
    /// `tolerance / 20`).
    pub path: BezPath,
    /// The Hausdorff distance to the original piece (None for user points).
    pub hausdorff: Option<f64>,
    /// Whether [`Piece::hausdorff`] is within
    /// [`DraftOptions::tolerance`](super::DraftOptions::tolerance): false when the
    /// refinement stopped at
    /// [`DraftOptions::max_refinements`](super::DraftOptions::max_refinements), or when no
    /// anchor set it tried could be solved, before reaching it. Always true for user
    /// points.
    pub within_tolerance: bool,
    /// No curve through the piece's anchors could be solved, even with the piece cut in
    /// parts ([`draft`](super::draft), step 7): `path` is the original's segments
    /// unchanged, `anchors` are its ends, and `spline` only the straight chord between
    /// them.
    pub fallback: bool,
    /// The solver's unknowns at [`Piece::spline`] ([`SolvedState`]), where there is a
    /// solve to reproduce (`None` for a fallback). The κ source keeps it
    /// ([`DraftedGlyph::path_docs`]): the curve systems can have several solutions for the
    /// same anchors, and a draft's refinements are solved from the previous solution, so a
    /// cold solve of the final anchors need not find the drafted curve, or converge at all.
    pub state: Option<SolvedState>,
}

/// A drafted contour.
#[derive(Clone, Debug)]
pub struct DraftedContour {
    /// Its pieces in order (consecutive pieces share their end anchors).
    pub pieces: Vec<Piece>,
    /// The contour as one closed path.
    pub path: BezPath,
    /// The original contour's on-curve points (see [`crate::glyph::on_curve_points`]; 0 for user
    /// points).
    pub original_on_curve: usize,
}

impl DraftedContour {
    /// The number of distinct anchors (shared piece ends counted once).
    pub fn anchor_count(&self) -> usize {
        match self.pieces.as_slice() {
            [p] if p.closed => p.anchors.len(),
            pieces => pieces
                .iter()
                .map(|p| p.anchors.len().saturating_sub(1))
                .sum(),
        }
    }
}

/// A drafted glyph outline.
#[derive(Clone, Debug)]
pub struct DraftedGlyph {
    /// The contours, in the order of the original's subpaths.
    pub contours: Vec<DraftedContour>,
    /// All contours as one path (one closed subpath each).
    pub path: BezPath,
    /// The largest piece Hausdorff distance (None for user points).
    pub hausdorff: Option<f64>,
}

impl DraftedGlyph {
    /// The number of points the designer places: the anchors of all contours.
    pub fn anchor_count(&self) -> usize {
        self.contours.iter().map(DraftedContour::anchor_count).sum()
    }

    /// The on-curve points of the original outline.
    pub fn original_on_curve(&self) -> usize {
        self.contours.iter().map(|c| c.original_on_curve).sum()
    }

    /// The number of segments of the drafted path.
    pub fn segment_count(&self) -> usize {
        self.path.segments().count()
    }

    /// All pieces of all contours.
    pub fn pieces(&self) -> impl Iterator<Item = &Piece> {
        self.contours.iter().flat_map(|c| c.pieces.iter())
    }

    /// Whether the refinement brought every piece within the tolerance (see
    /// [`Piece::within_tolerance`]).
    pub fn within_tolerance(&self) -> bool {
        self.pieces().all(|p| p.within_tolerance)
    }

    /// How many pieces kept the original's segments ([`Piece::fallback`]).
    pub fn fallback_count(&self) -> usize {
        self.pieces().filter(|p| p.fallback).count()
    }
}

#[cfg(feature = "serde")]
impl DraftedGlyph {
    /// The glyph's κ source: one path-tool document ([`PathDoc`](crate::editor::PathDoc))
    /// per contour, closed, its anchors in order with their shapes and tangents. The ends of
    /// the pieces are corners, and the tangent with which a piece arrives at its last anchor
    /// becomes that corner's incoming tangent. A contour drafted as one closed piece has no
    /// corner.
    ///
    /// Each document keeps its pieces' solutions ([`Piece::state`],
    /// [`PathDoc::solution`](crate::editor::PathDoc::solution)), so that it reopens with
    /// the drafted curves.
    ///
    /// This is what `kappa font` writes under the UFO lib key `org.kappa.contours` (as
    /// JSON), and what the editor and the Python filter solve back into the outline.
    pub fn path_docs(&self, scheme: crate::Scheme) -> Vec<crate::editor::PathDoc> {
        use crate::editor::{EditPoint, PathDoc};
        self.contours
            .iter()
            .map(|c| {
                let mut points: Vec<EditPoint> = Vec::new();
                let single = matches!(c.pieces.as_slice(), [p] if p.closed);
                let tangent = |a: &Anchor| a.tangent.map(|v| [v.x, v.y]);
                // The direction in which the previous piece arrives at the next corner.
                let mut arriving = None;
                for p in &c.pieces {
                    let take = if single {
                        p.anchors.len()
                    } else {
                        p.anchors.len().saturating_sub(1)
                    };
                    for (k, a) in p.anchors.iter().take(take).enumerate() {
                        let corner = !single && (k == 0 || a.kind == AnchorKind::Corner);
                        points.push(EditPoint {
                            x: a.point.x,
                            y: a.point.y,
                            shape: a.a,
                            corner,
                            tangent: tangent(a),
                            tangent_in: if k == 0 { arriving.take() } else { None },
                        });
                    }
                    arriving = p.anchors.last().and_then(tangent);
                }
                // The last piece arrives at the first corner.
                if let (false, Some(first)) = (single, points.first_mut()) {
                    first.tangent_in = arriving;
                }
                // The editor cuts the document into the same pieces, in the same order, when
                // its corners are exactly the pieces' ends.
                let corners = points.iter().filter(|p| p.corner).count();
                let solution = if corners.max(1) == c.pieces.len() {
                    c.pieces.iter().map(|p| p.state.clone()).collect()
                } else {
                    Vec::new()
                };
                PathDoc {
                    points,
                    closed: true,
                    scheme,
                    solution,
                }
            })
            .collect()
    }
}
