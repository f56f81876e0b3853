//! Drafting: a glyph outline rebuilt as κ- or εκ-curves through the points a designer would
//! click.
//!
//! # Method
//!
//! 1. **Pieces.** Each contour is cut at its *corners* — joints whose tangent turns by more
//!    than [`DraftOptions::corner_angle`] (measured with [`crate::analysis::continuity`]) —
//!    and at both ends of every straight segment, which stays a straight line. The cuts
//!    split the contour into open pieces whose end points are the corners, so corners stay
//!    sharp; a contour without cuts (the counter of an `o`) is one closed piece.
//! 2. **Anchors.** On each curved piece the designer's points are, in this order of
//!    preference: the piece ends; the on-curve *extrema* (tangent horizontal or vertical,
//!    from kurbo's `ParamCurveExtrema` and at the joints); and the *curvature peaks* — local
//!    maxima of the segments' largest |κ| ([`CurvatureAnalysis::max_curvature`]) with a
//!    prominence of at least [`PEAK_PROMINENCE`] over the lowest |κ| on the way to a higher
//!    peak (or the piece end) on either side. A candidate closer than
//!    [`DraftOptions::min_spacing`] to one already taken is dropped.
//! 3. **Refinement.** The piece is solved through its anchors; while its deviation from the
//!    original (largest distance of an original sample to the drafted curve) exceeds
//!    [`DraftOptions::tolerance`], the worst original sample becomes a new anchor (at most
//!    [`DraftOptions::max_refinements`] times per piece).
//! 4. **Auto shape** ([`DraftShape::Auto`], εκ schemes): the peak |κ| of an εκ segment at
//!    its point grows monotonically with the shape parameter `a` (seed 000 §3), so each
//!    `a_i` is chosen so that the drafted peak at anchor `i` matches the original's |κ|
//!    there: one solve at the lowest `a`, one at `a + 0.1` for the points that fall short,
//!    then up to [`AUTO_SECANT_STEPS`] per-point secant steps on `ln |κ|` against `a`, each a
//!    warm [`Solver::resolve_shapes`]. Points whose κ-curve peak already exceeds the
//!    original keep the lowest `a`; `a` stays in `[2/3, 0.98]` (εκ-cubic) or `[0.62, 0.98]`
//!    (εκ-trig, where lower `a` can turn the peak into a minimum).
//!
//! The reported **Hausdorff distance** is taken piece by piece, both ways, on
//! [`DraftOptions::samples`] samples per segment with exact nearest points: the original
//! piece against its own drafted piece, which bounds the Hausdorff distance of the whole
//! outlines from above (up to the sampling).

use kurbo::{BezPath, ParamCurve, ParamCurveExtrema, ParamCurveNearest, PathSeg, Point, Rect};

use crate::analysis::{continuity, CurvatureAnalysis};
use crate::fit::{FitMethod, FitOptions, FitTolerance};
use crate::{Error, Scheme, Shape, Solver, Spline};

/// A curvature peak becomes an anchor only if its |κ| is at least this many times the lowest
/// |κ| between it and a higher peak (or the piece end) on both sides.
pub const PEAK_PROMINENCE: f64 = 2.0;
/// A curvature peak becomes an anchor only if its radius of curvature is below this fraction
/// of the outline's size (gentle bends are left to the extrema and the refinement).
pub const PEAK_MAX_RADIUS: f64 = 0.5;
/// Secant steps of the auto shape after its two start-up solves.
pub const AUTO_SECANT_STEPS: usize = 4;
/// The auto shape stops when every drafted peak is within this relative error of its target.
pub const AUTO_RELATIVE_TOLERANCE: f64 = 0.02;
/// The largest shape parameter the auto shape uses (the peak grows without bound as `a → 1`).
pub const AUTO_MAX_SHAPE: f64 = 0.98;
/// The smallest εκ-trig shape parameter the auto shape uses.
pub const AUTO_MIN_TRIG_SHAPE: f64 = 0.62;
/// A joint tangent this close to horizontal or vertical (sine of the angle) makes the joint
/// an on-curve extremum.
const EXTREMUM_SLOPE: f64 = 0.02;

/// How the εκ shape parameters of a draft are chosen.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum DraftShape {
    /// The scheme's neutral shape ([`Scheme::neutral_shape`]).
    #[default]
    Neutral,
    /// One `a` for every anchor.
    Global(f64),
    /// Per anchor, matching the original's curvature peak (see the module docs).
    Auto,
}

/// Options of [`draft`]. Lengths are in the outline's units (font units).
#[derive(Clone, Debug, PartialEq)]
pub struct DraftOptions {
    /// The curve scheme.
    pub scheme: Scheme,
    /// The εκ shape parameters (ignored for [`Scheme::Kappa`]).
    pub shape: DraftShape,
    /// Refine a piece until its deviation from the original is at most this.
    pub tolerance: f64,
    /// Anchors closer than this to an anchor already taken are dropped (corners excepted).
    pub min_spacing: f64,
    /// A joint turning by more than this angle (radians) is a corner.
    pub corner_angle: f64,
    /// Samples per segment for the deviation and Hausdorff measurements (clamped to 2..=256).
    pub samples: usize,
    /// At most this many anchors are added per piece by the refinement.
    pub max_refinements: usize,
}

impl Default for DraftOptions {
    /// The options for a 1000-unit em: see [`DraftOptions::for_units_per_em`].
    fn default() -> DraftOptions {
        DraftOptions::for_units_per_em(1000.0)
    }
}

impl DraftOptions {
    /// κ-curve options scaled to a font's em: tolerance `0.004 em` (8 units at 2048),
    /// minimum spacing `0.03 em`, corners above 15°, 16 samples per segment, at most 8
    /// refinements per piece.
    pub fn for_units_per_em(units_per_em: f64) -> DraftOptions {
        DraftOptions {
            scheme: Scheme::Kappa,
            shape: DraftShape::Neutral,
            tolerance: 0.004 * units_per_em,
            min_spacing: 0.06 * units_per_em,
            corner_angle: 15f64.to_radians(),
            samples: 16,
            max_refinements: 8,
        }
    }

    /// The same options with another scheme and shape.
    pub fn with_scheme(mut self, scheme: Scheme, shape: DraftShape) -> DraftOptions {
        self.scheme = scheme;
        self.shape = shape;
        self
    }

    fn validate(&self) -> Result<(), Error> {
        if !(self.tolerance.is_finite() && self.tolerance > 0.0) {
            return Err(Error::InvalidOption(
                "draft tolerance must be finite and positive",
            ));
        }
        if !(self.min_spacing.is_finite() && self.min_spacing >= 0.0) {
            return Err(Error::InvalidOption(
                "draft minimum spacing must be finite and non-negative",
            ));
        }
        if !(self.corner_angle.is_finite() && self.corner_angle > 0.0) {
            return Err(Error::InvalidOption(
                "corner angle must be finite and positive",
            ));
        }
        if let DraftShape::Global(a) = self.shape {
            let (min, max) = self.scheme.shape_range();
            if self.scheme != Scheme::Kappa && !(a >= min && a < max) {
                return Err(Error::ShapeOutOfRange {
                    index: 0,
                    value: a,
                    min,
                    max,
                });
            }
        }
        Ok(())
    }
}

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
}

/// A drafted contour.
#[derive(Clone, Debug)]
pub struct DraftedContour {
    /// Its pieces in order (consecutive pieces share their end anchors).
    pub pieces: Vec<Piece>,
    /// The contour as one closed path.
    pub path: BezPath,
    /// The original contour's on-curve points (see [`super::on_curve_points`]; 0 for user
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
}

/// Drafts a glyph outline (see the [module docs](self)).
///
/// # Errors
///
/// [`Error::InvalidOption`] or [`Error::ShapeOutOfRange`] for unusable options,
/// [`Error::NonFinitePoint`] for an outline with a NaN or infinite coordinate, and the
/// solver's errors if a piece cannot be solved.
pub fn draft(outline: &BezPath, options: &DraftOptions) -> Result<DraftedGlyph, Error> {
    options.validate()?;
    for (index, el) in outline.elements().iter().enumerate() {
        if el.end_point().is_some_and(|p| !p.is_finite()) {
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
            let piece = drafter.piece(&piece_segs, piece_closed)?;
            hausdorff = hausdorff.max(piece.hausdorff.unwrap_or(0.0));
            pieces.push(piece);
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
        let anchors = anchors_of(&spline, points, AnchorKind::User, &[]);
        let path = spline_path(&spline, None);
        let piece = Piece {
            anchors,
            closed: *closed,
            spline,
            path: path.clone(),
            hausdorff: None,
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

/// The Hausdorff distance between two outlines, on `samples` samples per segment of each
/// (clamped to 2..=256) with exact nearest points on the other: `max(sup_a d(·, b),
/// sup_b d(·, a))` over the samples. 0 for two empty paths; infinite if exactly one is empty.
pub fn hausdorff(a: &BezPath, b: &BezPath, samples: usize) -> f64 {
    let sa: Vec<PathSeg> = a.segments().collect();
    let sb: Vec<PathSeg> = b.segments().collect();
    match (sa.is_empty(), sb.is_empty()) {
        (true, true) => return 0.0,
        (true, false) | (false, true) => return f64::INFINITY,
        _ => {}
    }
    let ta = Target::new(&sa);
    let tb = Target::new(&sb);
    let k = samples.clamp(2, 256);
    tb.deviation(&sa, k).0.max(ta.deviation(&sb, k).0)
}

/// Segments with their control boxes, for nearest-point queries with pruning.
struct Target<'a> {
    segs: &'a [PathSeg],
    boxes: Vec<Rect>,
}

impl<'a> Target<'a> {
    fn new(segs: &'a [PathSeg]) -> Target<'a> {
        let boxes = segs.iter().map(control_box).collect();
        Target { segs, boxes }
    }

    /// The distance from `p` to the nearest segment.
    fn distance(&self, p: Point) -> f64 {
        let mut best = f64::INFINITY;
        for (seg, b) in self.segs.iter().zip(&self.boxes) {
            let dx = (b.x0 - p.x).max(p.x - b.x1).max(0.0);
            let dy = (b.y0 - p.y).max(p.y - b.y1).max(0.0);
            if dx * dx + dy * dy >= best {
                continue;
            }
            best = best.min(seg.nearest(p, 1e-9).distance_sq);
        }
        best.sqrt()
    }

    /// Whether the distance from `p` to the nearest segment exceeds `floor` (stops at the
    /// first segment within `floor`).
    fn distance_above(&self, p: Point, floor: f64) -> bool {
        let f2 = floor * floor;
        for (seg, b) in self.segs.iter().zip(&self.boxes) {
            let dx = (b.x0 - p.x).max(p.x - b.x1).max(0.0);
            let dy = (b.y0 - p.y).max(p.y - b.y1).max(0.0);
            if dx * dx + dy * dy > f2 {
                continue;
            }
            if seg.nearest(p, 1e-9).distance_sq <= f2 {
                return false;
            }
        }
        true
    }

    /// The largest distance of a sample of `segs` (`k` per segment and the last end point)
    /// to this target, and where it is (segment index + t).
    fn deviation(&self, segs: &[PathSeg], k: usize) -> (f64, f64) {
        let mut worst = (0.0, 0.0);
        for (i, seg) in segs.iter().enumerate() {
            let last = usize::from(i + 1 == segs.len());
            for j in 0..k + last {
                let t = j as f64 / k as f64;
                let d = self.distance(seg.eval(t));
                if d > worst.0 {
                    worst = (d, i as f64 + t);
                }
            }
        }
        worst
    }
}

fn control_box(seg: &PathSeg) -> Rect {
    match *seg {
        PathSeg::Line(l) => Rect::from_points(l.p0, l.p1),
        PathSeg::Quad(q) => Rect::from_points(q.p0, q.p1).union_pt(q.p2),
        PathSeg::Cubic(c) => Rect::from_points(c.p0, c.p1).union_pt(c.p2).union_pt(c.p3),
    }
}

/// The point of a piece at position `s` (segment index + t).
fn eval_at(segs: &[PathSeg], s: f64) -> Point {
    let n = segs.len();
    let i = (s.floor().max(0.0) as usize).min(n - 1);
    segs[i].eval((s - i as f64).clamp(0.0, 1.0))
}

/// |κ| of a piece at position `s`; at a joint, the mean of both sides.
fn abs_curvature_at(segs: &[PathSeg], s: f64, closed: bool) -> f64 {
    let n = segs.len();
    let i = (s.floor().max(0.0) as usize).min(n - 1);
    let t = (s - i as f64).clamp(0.0, 1.0);
    let here = CurvatureAnalysis::curvature(&segs[i], t).abs();
    let other = if t < 1e-9 && (i > 0 || closed) {
        Some(CurvatureAnalysis::curvature(&segs[(i + n - 1) % n], 1.0).abs())
    } else if t > 1.0 - 1e-9 && (i + 1 < n || closed) {
        Some(CurvatureAnalysis::curvature(&segs[(i + 1) % n], 0.0).abs())
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

/// The path of a solved piece: exact for the polynomial schemes, Hermite-fitted cubics
/// within `tolerance` (default: 1e-4 of the size) for εκ-trig.
fn spline_path(spline: &Spline, tolerance: Option<f64>) -> BezPath {
    if spline.scheme().is_polynomial() {
        return spline.to_bezpath();
    }
    let options = FitOptions {
        tolerance: tolerance.map_or(FitTolerance::Relative(1e-4), FitTolerance::Absolute),
        method: FitMethod::Hermite,
        check_samples: 0,
    };
    spline.fit(&options).map(|f| f.path).unwrap_or_default()
}

/// Anchors of a solved curve through `points`: the shape of each point's segment.
fn anchors_of(spline: &Spline, points: &[Point], kind: AnchorKind, targets: &[f64]) -> Vec<Anchor> {
    let off = usize::from(!spline.is_closed());
    let segs = spline.segments();
    points
        .iter()
        .enumerate()
        .map(|(i, &point)| {
            let a = i
                .checked_sub(off)
                .and_then(|j| segs.get(j))
                .filter(|_| points.len() > 2 || spline.is_closed())
                .map_or(2.0 / 3.0, |s| s.a);
            Anchor {
                point,
                kind,
                a,
                target_curvature: targets.get(i).copied().unwrap_or(0.0),
            }
        })
        .collect()
}

/// A piece solved through its anchors.
struct Solved {
    spline: Spline,
    points: Vec<Point>,
    targets: Vec<f64>,
    path: BezPath,
}

/// The drafted piece from its last solve, with its two-sided Hausdorff distance.
fn finish(
    original: &Target<'_>,
    anchors: &[Cand],
    solved: Solved,
    closed: bool,
    k: usize,
) -> Piece {
    let drafted: Vec<PathSeg> = solved.path.segments().collect();
    let there = Target::new(&drafted).deviation(original.segs, k).0;
    let back = original.deviation(&drafted, k).0;
    let mut out = anchors_of(
        &solved.spline,
        &solved.points,
        AnchorKind::Refined,
        &solved.targets,
    );
    for (a, c) in out.iter_mut().zip(anchors) {
        a.kind = c.kind;
    }
    Piece {
        anchors: out,
        closed,
        spline: solved.spline,
        path: solved.path,
        hausdorff: Some(there.max(back)),
    }
}

struct Drafter<'o> {
    options: &'o DraftOptions,
    size: f64,
    solver: Solver,
}

/// A candidate anchor: position along the piece and kind.
#[derive(Clone, Copy, Debug)]
struct Cand {
    s: f64,
    kind: AnchorKind,
}

impl Drafter<'_> {
    fn piece(&mut self, segs: &[PathSeg], closed: bool) -> Result<Piece, Error> {
        let opts = self.options;
        let mut anchors = self.initial_anchors(segs, closed);
        let k = opts.samples.clamp(2, 256);
        let original = Target::new(segs);
        let mut refinements = 0;
        // The last solved state, kept in case a refined anchor set cannot be solved.
        let mut last: Option<(Vec<Cand>, Solved)> = None;
        loop {
            let solved = match self.solve(segs, closed, &anchors) {
                Ok(s) => s,
                Err(e) => match last.take() {
                    // The refinement made the system unsolvable: keep the previous draft.
                    Some((prev, solved)) => {
                        return Ok(finish(&original, &prev, solved, closed, k));
                    }
                    None => return Err(e),
                },
            };
            let drafted: Vec<PathSeg> = solved.path.segments().collect();
            let target = Target::new(&drafted);
            let insert = if refinements < opts.max_refinements {
                self.worst_new_anchor(segs, &target, &anchors, k)
            } else {
                None
            };
            match insert {
                Some(s) => {
                    last = Some((anchors.clone(), solved));
                    anchors.push(Cand {
                        s,
                        kind: AnchorKind::Refined,
                    });
                    anchors.sort_by(|a, b| a.s.total_cmp(&b.s));
                    refinements += 1;
                }
                None => return Ok(finish(&original, &anchors, solved, closed, k)),
            }
        }
    }

    /// Ends, extrema and curvature peaks, thinned to the minimum spacing.
    fn initial_anchors(&self, segs: &[PathSeg], closed: bool) -> Vec<Cand> {
        let n = segs.len();
        let mut cands: Vec<Cand> = Vec::new();
        if !closed {
            cands.push(Cand {
                s: 0.0,
                kind: AnchorKind::Corner,
            });
            cands.push(Cand {
                s: n as f64,
                kind: AnchorKind::Corner,
            });
        }
        if !(n == 1 && matches!(segs[0], PathSeg::Line(_))) {
            self.extrema(segs, closed, &mut cands);
            self.peaks(segs, closed, &mut cands);
        }
        // Thin out: corners first, then extrema, then peaks.
        let rank = |k: AnchorKind| match k {
            AnchorKind::Corner => 0,
            AnchorKind::Extremum => 1,
            _ => 2,
        };
        cands.sort_by(|a, b| rank(a.kind).cmp(&rank(b.kind)).then(a.s.total_cmp(&b.s)));
        let mut kept: Vec<(Cand, Point)> = Vec::new();
        for c in cands {
            let p = eval_at(segs, c.s);
            let far = kept
                .iter()
                .all(|(_, q)| (p - *q).hypot() >= self.options.min_spacing.max(f64::MIN_POSITIVE));
            if c.kind == AnchorKind::Corner || far {
                kept.push((c, p));
            }
        }
        let mut out: Vec<Cand> = kept.into_iter().map(|(c, _)| c).collect();
        out.sort_by(|a, b| a.s.total_cmp(&b.s));
        if closed && out.len() < 3 {
            // A closed curve needs three points: spread the missing ones evenly.
            let s0 = out.first().map_or(0.0, |c| c.s);
            let m = 3 - out.len();
            for j in 1..=m {
                let s = (s0 + n as f64 * j as f64 / (m + 1) as f64) % n as f64;
                out.push(Cand {
                    s,
                    kind: AnchorKind::Refined,
                });
            }
            out.sort_by(|a, b| a.s.total_cmp(&b.s));
        }
        out
    }

    fn extrema(&self, segs: &[PathSeg], closed: bool, cands: &mut Vec<Cand>) {
        for (i, seg) in segs.iter().enumerate() {
            if matches!(seg, PathSeg::Line(_)) {
                continue;
            }
            for t in seg.extrema() {
                cands.push(Cand {
                    s: i as f64 + t,
                    kind: AnchorKind::Extremum,
                });
            }
            if i > 0 || closed {
                let d = seg.eval(1e-6) - seg.eval(0.0);
                let len = d.hypot();
                if len > 0.0
                    && (d.x.abs() < EXTREMUM_SLOPE * len || d.y.abs() < EXTREMUM_SLOPE * len)
                {
                    cands.push(Cand {
                        s: i as f64,
                        kind: AnchorKind::Extremum,
                    });
                }
            }
        }
    }

    fn peaks(&self, segs: &[PathSeg], closed: bool, cands: &mut Vec<Cand>) {
        let n = segs.len();
        let maxima: Vec<(f64, f64)> = segs
            .iter()
            .map(|seg| {
                let m = seg.max_curvature();
                let t = m.params.first().copied().unwrap_or(0.5);
                if m.value.is_finite() {
                    (m.value, t)
                } else {
                    (0.0, t)
                }
            })
            .collect();
        let value = |j: isize| -> Option<f64> {
            if closed {
                Some(maxima[j.rem_euclid(n as isize) as usize].0)
            } else if j >= 0 && (j as usize) < n {
                Some(maxima[j as usize].0)
            } else {
                None
            }
        };
        for (i, &(v, t)) in maxima.iter().enumerate() {
            if v <= 0.0 || v * PEAK_MAX_RADIUS * self.size < 1.0 {
                continue;
            }
            // Lowest value on each side before a higher peak (of equal peaks the later wins).
            let mut lows = [f64::INFINITY; 2];
            let mut tie = false;
            for (side, step) in [(0usize, -1isize), (1, 1)] {
                let mut j = i as isize + step;
                let mut steps = 1;
                while let Some(w) = value(j) {
                    if w > v || (w == v && step < 0) || steps >= n {
                        tie |= w == v && step < 0 && steps < n;
                        break;
                    }
                    lows[side] = lows[side].min(w);
                    j += step;
                    steps += 1;
                }
            }
            if tie {
                continue;
            }
            let low = lows
                .iter()
                .copied()
                .filter(|l| l.is_finite())
                .fold(f64::NEG_INFINITY, f64::max);
            if low.is_finite() && v >= PEAK_PROMINENCE * low {
                cands.push(Cand {
                    s: i as f64 + t,
                    kind: AnchorKind::Peak,
                });
            }
        }
    }

    /// The original sample furthest from the draft (if further than the tolerance) that is not
    /// too close to an anchor: one pass over `k` samples per segment, midway between the
    /// measurement samples of [`Target::deviation`] (which would sit on anchors at joints).
    fn worst_new_anchor(
        &self,
        segs: &[PathSeg],
        drafted: &Target<'_>,
        anchors: &[Cand],
        k: usize,
    ) -> Option<f64> {
        let points: Vec<Point> = anchors.iter().map(|c| eval_at(segs, c.s)).collect();
        let gap = 0.25 * self.options.min_spacing;
        let mut best: Option<(f64, f64)> = None;
        for (i, seg) in segs.iter().enumerate() {
            for j in 0..k {
                let t = (j as f64 + 0.5) / k as f64;
                let p = seg.eval(t);
                // Cheap rejections first: too close to an anchor, or no better than the best.
                if points.iter().any(|q| (p - *q).hypot() < gap) {
                    continue;
                }
                let floor = best.map_or(self.options.tolerance, |(bd, _)| bd);
                if drafted.distance_above(p, floor) {
                    best = Some((drafted.distance(p), i as f64 + t));
                }
            }
        }
        best.map(|(_, s)| s)
    }

    /// Solves a piece through the anchors with the options' scheme and shape; returns the
    /// spline, its points and the original's |κ| at each.
    fn solve(&mut self, segs: &[PathSeg], closed: bool, anchors: &[Cand]) -> Result<Solved, Error> {
        let points: Vec<Point> = anchors.iter().map(|c| eval_at(segs, c.s)).collect();
        let targets: Vec<f64> = anchors
            .iter()
            .map(|c| abs_curvature_at(segs, c.s, closed))
            .collect();
        let scheme = self.options.scheme;
        let interior = closed || points.len() > 2;
        let spline = match (&self.options.shape, scheme) {
            (_, Scheme::Kappa) => self
                .solver
                .solve(&points, closed, scheme, &Shape::Neutral)?,
            (DraftShape::Auto, _) if interior => self.auto_shape(&points, closed, &targets)?,
            (DraftShape::Global(a), _) => {
                self.solver
                    .solve(&points, closed, scheme, &Shape::Global(*a))?
            }
            _ => self
                .solver
                .solve(&points, closed, scheme, &Shape::Neutral)?,
        };
        let path = if !closed && points.len() == 2 {
            // A straight piece: one line, whatever the scheme.
            let mut line = BezPath::new();
            line.move_to(points[0]);
            line.line_to(points[1]);
            line
        } else {
            spline_path(&spline, Some(self.options.tolerance / 20.0))
        };
        Ok(Solved {
            spline,
            points,
            targets,
            path,
        })
    }

    /// The auto shape (module docs, step 4).
    fn auto_shape(
        &mut self,
        points: &[Point],
        closed: bool,
        targets: &[f64],
    ) -> Result<Spline, Error> {
        let scheme = self.options.scheme;
        let lo = match scheme {
            Scheme::EkTrig => AUTO_MIN_TRIG_SHAPE,
            _ => 2.0 / 3.0,
        };
        let m = points.len();
        let off = usize::from(!closed);
        // Peak |κ| of each point (None for the ends of an open curve).
        let peaks = |spline: &Spline| -> Vec<Option<f64>> {
            (0..m)
                .map(|i| {
                    i.checked_sub(off)
                        .and_then(|j| spline.segments().get(j))
                        .filter(|_| closed || (i > 0 && i + 1 < m))
                        .map(|s| s.curvature(s.t_max).abs())
                })
                .collect()
        };
        let mut a0 = vec![lo; m];
        let s0 = self
            .solver
            .solve(points, closed, scheme, &Shape::PerPoint(a0.clone()))?;
        let mut k0 = peaks(&s0);
        let mut a1: Vec<f64> = (0..m)
            .map(|i| match k0[i] {
                Some(k) if k < targets[i] => (lo + 0.1).min(AUTO_MAX_SHAPE),
                _ => lo,
            })
            .collect();
        if a1 == a0 {
            return Ok(s0);
        }
        let mut s1 = match self
            .solver
            .resolve_shapes(scheme, &Shape::PerPoint(a1.clone()))
        {
            Ok(s) => s,
            Err(_) => return Ok(s0),
        };
        for _ in 0..AUTO_SECANT_STEPS {
            let k1 = peaks(&s1);
            let mut a2 = a1.clone();
            let mut done = true;
            for i in 0..m {
                let (Some(ka), Some(kb)) = (k0[i], k1[i]) else {
                    continue;
                };
                let target = targets[i];
                if !(target > 0.0 && ka > 0.0 && kb > 0.0) {
                    continue;
                }
                let err = target.ln() - kb.ln();
                if err.abs() <= AUTO_RELATIVE_TOLERANCE
                    || (a1[i] <= lo && err < 0.0)
                    || (a1[i] >= AUTO_MAX_SHAPE && err > 0.0)
                {
                    continue;
                }
                let da = a1[i] - a0[i];
                let dk = kb.ln() - ka.ln();
                let step = if da != 0.0 && dk > 0.0 {
                    err * da / dk
                } else {
                    0.05 * err.signum()
                };
                a2[i] = (a1[i] + step.clamp(-0.15, 0.15)).clamp(lo, AUTO_MAX_SHAPE);
                if a2[i] != a1[i] {
                    done = false;
                }
            }
            if done {
                break;
            }
            match self
                .solver
                .resolve_shapes(scheme, &Shape::PerPoint(a2.clone()))
            {
                Ok(s2) => {
                    a0 = core::mem::replace(&mut a1, a2);
                    s1 = s2;
                    k0 = k1;
                }
                Err(_) => break,
            }
        }
        Ok(s1)
    }
}
