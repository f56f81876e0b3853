//! Drafting: a glyph outline rebuilt as κ- or εκ-curves through the points a designer would
//! click (the method is documented on [`draft`]).
//!
//! The parts: [`options`] and the results ([`drafted`]); the first anchors ([`anchors`]);
//! a piece drafted ([`piece`]), solved ([`solve`]), refined ([`refine`]), faired and
//! simplified ([`fair`]), with extremum tangents ([`tangents`]) and the auto shape
//! ([`auto_shape`]); the measurements ([`distance`]).

use kurbo::{BezPath, ParamCurve, PathEl, PathSeg, Point, Vec2};

use crate::analysis::{continuity, CurvatureAnalysis};
use crate::{Error, Scheme, Shape, SolvedState, Solver, Spline};

mod anchors;
mod auto_shape;
mod distance;
mod drafted;
mod fair;
mod options;
mod piece;
mod refine;
mod solve;
mod tangents;

pub use anchors::{PEAK_MAX_RADIUS, PEAK_PROMINENCE};
pub use auto_shape::{
    AUTO_MAX_SHAPE, AUTO_MIN_TRIG_SHAPE, AUTO_RELATIVE_TOLERANCE, AUTO_SECANT_STEPS,
};
pub use distance::hausdorff;
pub use drafted::{Anchor, AnchorKind, DraftedContour, DraftedGlyph, Piece};
pub use options::{DraftOptions, DraftShape};
pub use piece::SPLIT_DEPTH;

use solve::{anchors_of, spline_path};

/// Drafts a glyph outline: anchors where a designer would click, a κ/εκ curve through them,
/// refined until within the tolerance.
///
/// # Method
///
/// 1. **Pieces.** Each contour is cut at its *corners* — joints whose tangent turns by more
///    than [`DraftOptions::corner_angle`] (measured with [`crate::analysis::continuity`]) —
///    and at both ends of every straight segment, which stays a straight line. The cuts
///    split the contour into open pieces whose end points are the corners, so corners stay
///    sharp; a contour without cuts (the counter of an `o`) is one closed piece.
/// 2. **Anchors.** On each curved piece the designer's points are, in this order of
///    preference: the piece ends; the on-curve *extrema* (tangent horizontal or vertical,
///    from kurbo's `ParamCurveExtrema` and at the joints); and the *curvature peaks* — local
///    maxima of the segments' largest |κ| ([`CurvatureAnalysis::max_curvature`]) with a
///    prominence of at least [`PEAK_PROMINENCE`] over the lowest |κ| on the way to a higher
///    peak (or the piece end) on either side. A candidate closer than
///    [`DraftOptions::min_spacing`] to one already taken is dropped. A curved open piece
///    left with its two ends only and with a chord of at most three minimum spacings — a
///    small fillet between a stem and a crossbar, a gentle flank between two lines — gets a
///    third anchor halfway along it, so that it is not drafted as its chord (see
///    `fillet_anchor`).
/// 3. **Refinement.** The piece is solved through its anchors and measured: for each span
///    between consecutive anchors, the original sample furthest from the drafted curve. The
///    worst sample of every span further than [`DraftOptions::tolerance`] becomes a new
///    anchor — all at once, except that of two neighbouring spans only the worse one gets
///    one (an anchor also pulls the curve next to it) — and the piece is solved again, at
///    most [`DraftOptions::max_refinements`] anchors per piece. Should the new anchor set
///    not be solvable, the round tries only the worst sample, then other places in each
///    straying span (its middle and quarters); if none of these solves either, the
///    refinement stops there and [`Piece::within_tolerance`] says whether the piece is
///    within the tolerance anyway. Each set is first solved from the last solution, the
///    added anchors seeded in straight (at most 400 iterations), and only if no set solves
///    that way from scratch: a cold solve of many dense anchors is where the solver fails
///    most (on EB Garamond's `N`, 75 of 139 solves failed and took 3.5 of its 3.9 s; with
///    the warm starts the glyph takes 0.5 s). Most samples are settled without a nearest-point search:
///    a point of the draft near the last nearest point, found by two Newton steps, is
///    within the tolerance already.
/// 4. **Fairing** ([`DraftOptions::fair`], off by default): a κ-curve makes every point a
///    peak of |κ|, so an anchor at a curvature *minimum* of the original — the flank of a
///    bowl, where designers put their extrema — gets its peak by turning the other way, with
///    an inflection on either side, within the tolerance but visible in the comb (the κ
///    drafts of the 52 letters of DejaVu Sans have 77 such inflections, the εκ-cubic auto
///    ones 68, the originals' curved pieces none). For each such anchor the piece is solved
///    with it moved halfway to either neighbour, without it, or with two anchors halfway to
///    its neighbours instead; the first that stays within the tolerance with fewer of them
///    is kept. It leaves 2 of the 77 inflections, at two to three times the drafting time.
/// 5. **Simplification** ([`DraftOptions::simplify`], off by default): each anchor that is
///    not a corner, in order along the piece, is dropped if the piece solved without it
///    stays within the tolerance (and, when fairing, does not turn the wrong way at more
///    anchors). It saves about 5 % of the anchors of DejaVu Sans's letters, up to 15 % on
///    some glyphs, at about four times the drafting time.
/// 6. **Auto shape** ([`DraftShape::Auto`], εκ schemes): the peak |κ| of an εκ segment at
///    its point grows monotonically with the shape parameter `a` (seed 000 §3), so each
///    `a_i` is chosen so that the drafted peak at anchor `i` matches the original's |κ|
///    there: one solve at the lowest `a` (at the scheme's neutral `a` should that system
///    not be solvable), one at `a + 0.1` for the points that fall short, then up to
///    [`AUTO_SECANT_STEPS`] per-point secant steps on `ln |κ|` against `a`, each a warm
///    [`Solver::resolve_shapes`]. Points whose κ-curve peak already exceeds the original
///    keep the lowest `a`; `a` stays in `[2/3, 0.98]` (εκ-cubic) or `[0.62, 0.98]`
///    (εκ-trig, where lower `a` can turn the peak into a minimum).
/// 7. **A piece that will not solve** does not abort the glyph: it is cut in two at its
///    middle joint (a closed piece into two open halves) and each part drafted, to
///    [`SPLIT_DEPTH`] levels; a part that still fails keeps the original's segments,
///    flagged ([`Piece::fallback`], [`DraftedGlyph::fallback_count`]). **A piece that
///    solves but strays** beyond the tolerance is cut the same way, and its parts replace
///    it only when none of them is a fallback and their worst Hausdorff distance is below
///    the whole piece's.
///
/// The reported **Hausdorff distance** is taken piece by piece, both ways, on
/// [`DraftOptions::samples`] samples per segment with exact nearest points: the original
/// piece against its own drafted piece, which bounds the Hausdorff distance of the whole
/// outlines from above (up to the sampling).
///
/// # Errors
///
/// [`Error::InvalidOption`] or [`Error::ShapeOutOfRange`] for unusable options, and
/// [`Error::NonFinitePoint`] for an outline with a NaN or infinite coordinate. A piece the
/// solver cannot solve is not an error (step 7).
pub fn draft(outline: &BezPath, options: &DraftOptions) -> Result<DraftedGlyph, Error> {
    options.validate()?;
    for (index, el) in outline.elements().iter().enumerate() {
        let finite = match *el {
            PathEl::MoveTo(p) | PathEl::LineTo(p) => p.is_finite(),
            PathEl::QuadTo(a, p) => a.is_finite() && p.is_finite(),
            PathEl::CurveTo(a, b, p) => a.is_finite() && b.is_finite() && p.is_finite(),
            PathEl::ClosePath => true,
        };
        if !finite {
            return Err(Error::NonFinitePoint { index });
        }
    }
    let size = {
        let b = kurbo::Shape::bounding_box(outline);
        b.width().max(b.height())
    };
    let mut drafter = Drafter {
        options,
        size,
        solver: Solver::new(),
        tangents: Vec::new(),
        seed: None,
        turn_limit: f64::INFINITY,
    };
    let mut contours = Vec::new();
    let mut hausdorff = 0.0f64;
    for (segs, closed) in super::contours(outline) {
        if segs.is_empty() {
            continue;
        }
        let original_on_curve = super::on_curve_points_of(&segs, closed);
        let mut pieces = Vec::new();
        for (range, piece_closed) in split_pieces(&segs, closed, options.corner_angle) {
            let piece_segs: Vec<PathSeg> = range.iter().map(|&i| segs[i]).collect();
            for piece in drafter.piece_or_parts(&piece_segs, piece_closed, 0) {
                hausdorff = hausdorff.max(piece.hausdorff.unwrap_or(0.0));
                pieces.push(piece);
            }
        }
        let path = join_pieces(&pieces, closed);
        contours.push(DraftedContour {
            pieces,
            path,
            original_on_curve,
        });
    }
    let mut path = BezPath::new();
    for c in &contours {
        path.extend(c.path.elements().iter().copied());
    }
    Ok(DraftedGlyph {
        contours,
        path,
        hausdorff: Some(hausdorff),
    })
}

/// The direct route: contours through user-given points (each `(points, closed)`), with
/// per-contour shapes (`None`: `shape`). Each contour is one piece; no Hausdorff distance.
///
/// # Errors
///
/// The solver's errors for unusable points or shapes.
pub fn draft_points(
    contours: &[(Vec<Point>, bool)],
    scheme: Scheme,
    shape: &Shape,
    shapes: &[Option<Vec<f64>>],
) -> Result<DraftedGlyph, Error> {
    let mut solver = Solver::new();
    let mut out = Vec::with_capacity(contours.len());
    for (i, (points, closed)) in contours.iter().enumerate() {
        let shape = match shapes.get(i) {
            Some(Some(a)) if scheme != Scheme::Kappa => Shape::PerPoint(a.clone()),
            _ => shape.clone(),
        };
        let spline = solver.solve(points, *closed, scheme, &shape)?;
        let state = solver.state();
        let anchors = anchors_of(&spline, points, AnchorKind::User, &[]);
        let path = spline_path(&spline, None);
        let piece = Piece {
            anchors,
            closed: *closed,
            spline,
            path: path.clone(),
            hausdorff: None,
            within_tolerance: true,
            fallback: false,
            state,
        };
        out.push(DraftedContour {
            pieces: vec![piece],
            path,
            original_on_curve: 0,
        });
    }
    let mut path = BezPath::new();
    for c in &out {
        path.extend(c.path.elements().iter().copied());
    }
    Ok(DraftedGlyph {
        contours: out,
        path,
        hausdorff: None,
    })
}

struct Drafter<'o> {
    options: &'o DraftOptions,
    size: f64,
    solver: Solver,
    /// The tangents the next solves hold, by anchor (empty: none).
    tangents: Vec<Option<Vec2>>,
    /// A start for the next solve (taken by it): the last solution with the anchors a
    /// refinement adds seeded in ([`refine::seeded`]).
    seed: Option<SolvedState>,
    /// The most a solve holding tangents may turn (radians), set for each piece by
    /// [`Drafter::with_extremum_tangents`].
    turn_limit: f64,
}

/// A candidate anchor: position along the piece and kind.
#[derive(Clone, Copy, Debug)]
struct Cand {
    s: f64,
    kind: AnchorKind,
}

/// A piece solved through its anchors.
struct Solved {
    spline: Spline,
    points: Vec<Point>,
    targets: Vec<f64>,
    path: BezPath,
    /// The tangents held, by anchor (empty: none).
    tangents: Vec<Option<Vec2>>,
    /// The solver's unknowns at the solution, where it keeps them.
    state: Option<SolvedState>,
}

/// The point of a piece at position `s` (segment index + t).
fn eval_at(segs: &[PathSeg], s: f64) -> Point {
    let (i, t) = locate(segs, s);
    segs[i].eval(t)
}

/// The segment and parameter of position `s` along `segs` (clamped to them).
fn locate(segs: &[PathSeg], s: f64) -> (usize, f64) {
    let i = (s.floor().max(0.0) as usize).min(segs.len() - 1);
    (i, (s - i as f64).clamp(0.0, 1.0))
}

/// |κ| of a piece at position `s`; at a joint, the mean of both sides.
fn abs_curvature_at(segs: &[PathSeg], s: f64, closed: bool) -> f64 {
    curvature_at(segs, s, closed, f64::abs)
}

/// κ of a piece at position `s`, `f` applied to each side; at a joint, the mean of both
/// sides.
fn curvature_at(segs: &[PathSeg], s: f64, closed: bool, f: fn(f64) -> f64) -> f64 {
    let n = segs.len();
    let i = (s.floor().max(0.0) as usize).min(n - 1);
    let t = (s - i as f64).clamp(0.0, 1.0);
    let here = f(CurvatureAnalysis::curvature(&segs[i], t));
    let other = if t < 1e-9 && (i > 0 || closed) {
        Some(f(CurvatureAnalysis::curvature(&segs[(i + n - 1) % n], 1.0)))
    } else if t > 1.0 - 1e-9 && (i + 1 < n || closed) {
        Some(f(CurvatureAnalysis::curvature(&segs[(i + 1) % n], 0.0)))
    } else {
        None
    };
    other.map_or(here, |o| 0.5 * (here + o))
}

/// The pieces of a contour: ranges of segment indices (in order, possibly wrapping) and
/// whether the piece is closed.
fn split_pieces(segs: &[PathSeg], closed: bool, corner_angle: f64) -> Vec<(Vec<usize>, bool)> {
    let n = segs.len();
    let is_line = |i: usize| matches!(segs[i], PathSeg::Line(_));
    // Joint j is the start of segment j.
    let cut = |j: usize| -> bool {
        let prev = (j + n - 1) % n;
        is_line(j)
            || is_line(prev)
            || continuity(&segs[prev], &segs[j]).tangent_angle > corner_angle
    };
    let mut cuts: Vec<usize> = if closed {
        (0..n).filter(|&j| cut(j)).collect()
    } else {
        (1..n).filter(|&j| cut(j)).collect()
    };
    if closed && cuts.is_empty() {
        return vec![((0..n).collect(), true)];
    }
    if !closed {
        cuts.insert(0, 0);
    }
    let mut pieces = Vec::with_capacity(cuts.len());
    for (k, &start) in cuts.iter().enumerate() {
        let end = match cuts.get(k + 1) {
            Some(&e) => e,
            None if closed => cuts[0] + n,
            None => n,
        };
        pieces.push(((start..end).map(|i| i % n).collect(), false));
    }
    pieces
}

/// The drafted contour path from its pieces: the first piece's start, then every piece's
/// segments, closed for a closed contour.
fn join_pieces(pieces: &[Piece], closed: bool) -> BezPath {
    let mut path = BezPath::new();
    for piece in pieces {
        for (i, el) in piece.path.elements().iter().enumerate() {
            match el {
                kurbo::PathEl::MoveTo(_) if i > 0 || !path.elements().is_empty() => {}
                kurbo::PathEl::ClosePath => {}
                el => path.push(*el),
            }
        }
    }
    if closed && !path.elements().is_empty() {
        path.close_path();
    }
    path
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An ellipse of semi-axes 1000 and 300 as eight quadratics (the font way).
    pub(super) fn ellipse() -> BezPath {
        let mut path = BezPath::new();
        let n = 8;
        let at = |i: usize, r: f64| {
            let th = i as f64 / n as f64 * core::f64::consts::TAU;
            Point::new(1000.0 * r * th.cos(), 300.0 * r * th.sin())
        };
        // Off-curve points at the tangent intersections: radius 1/cos(π/8) at half steps.
        let r = 1.0 / (core::f64::consts::PI / n as f64).cos();
        path.move_to(at(0, 1.0));
        for i in 0..n {
            let th = (i as f64 + 0.5) / n as f64 * core::f64::consts::TAU;
            let c = Point::new(1000.0 * r * th.cos(), 300.0 * r * th.sin());
            path.quad_to(c, at((i + 1) % n, 1.0));
        }
        path.close_path();
        path
    }

    /// Tolerance of the ellipse tests (0.4 % of its width, as 0.004 em for a glyph).
    const ELLIPSE_TOLERANCE: f64 = 8.0;

    #[test]
    fn draft_refines_until_within_tolerance() {
        let mut options = DraftOptions {
            tolerance: ELLIPSE_TOLERANCE,
            ..DraftOptions::default()
        };
        let d = draft(&ellipse(), &options).unwrap();
        assert!(d.within_tolerance());
        let h = d.hausdorff.unwrap();
        assert!(h <= ELLIPSE_TOLERANCE, "{h}");
        assert!(d
            .pieces()
            .any(|p| p.anchors.iter().any(|a| a.kind == AnchorKind::Refined)));
        // Measured independently, on other samples.
        let whole = hausdorff(&ellipse(), &d.path, 64);
        assert!(whole <= h + 0.05, "{whole} vs {h}");
        // Without refinements the piece stays outside the tolerance, and says so.
        options.max_refinements = 0;
        let d = draft(&ellipse(), &options).unwrap();
        assert!(d.hausdorff.unwrap() > ELLIPSE_TOLERANCE);
        assert!(!d.within_tolerance());
        assert!(d
            .pieces()
            .all(|p| p.anchors.iter().all(|a| a.kind != AnchorKind::Refined)));
    }

    #[test]
    fn draft_simplify_keeps_the_bound_with_fewer_points() {
        let mut options = DraftOptions {
            tolerance: ELLIPSE_TOLERANCE,
            ..DraftOptions::default()
        };
        let full = draft(&ellipse(), &options).unwrap();
        options.simplify = true;
        let simple = draft(&ellipse(), &options).unwrap();
        assert!(simple.within_tolerance());
        assert!(simple.hausdorff.unwrap() <= ELLIPSE_TOLERANCE);
        assert!(simple.anchor_count() <= full.anchor_count());
        let whole = hausdorff(&ellipse(), &simple.path, 64);
        assert!(whole <= ELLIPSE_TOLERANCE + 0.05, "{whole}");
        // No anchor left can go: without it the curve cannot be solved or breaks the bound.
        let piece = simple.pieces().next().unwrap();
        let points: Vec<Point> = piece.anchors.iter().map(|a| a.point).collect();
        for j in 0..points.len() {
            let mut fewer = points.clone();
            fewer.remove(j);
            if let Ok(spline) = Solver::new().solve(&fewer, true, Scheme::Kappa, &Shape::Neutral) {
                let h = hausdorff(&ellipse(), &spline.to_bezpath(), 16);
                assert!(h > ELLIPSE_TOLERANCE, "anchor {j} could go: {h}");
            }
        }
    }
}
