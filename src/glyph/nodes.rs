//! Drafted outlines written with their anchors as the on-curve nodes.
//!
//! A drafted curve is made of segments that run from joint to joint and pass through their
//! anchor at the peak parameter `t_i`, so the curve's own Bézier nodes are the joints, not
//! the points the designer placed. For a font, the nodes should be the anchors: the span
//! between two consecutive anchors (the end of one segment and the start of the next,
//! joined with G2) becomes one cubic, fitted where it is not one Bézier already.

use core::ops::Range;

use kurbo::{
    fit_to_bezpath, fit_to_cubic, BezPath, CubicBez, CurveFitSample, ParamCurve, ParamCurveDeriv,
    ParamCurveFit, ParamCurveNearest, PathSeg, Point, Vec2,
};

use super::{AnchorKind, DraftedGlyph, Piece};
use crate::analysis::continuity;
use crate::trig::TrigBez;
use crate::{Scheme, Segment};

/// The largest angle (radians) by which the tangent at an extremum anchor is turned to the
/// nearest axis. Where the solver holds the axis (`DraftOptions::extremum_tangents`) there
/// is nothing to turn; where it could not, the drafted tangent is typically 1°… 25° off (on
/// EB Garamond's alphabet, 13 % of the extremum nodes were 5°… 25° off; turning up to 25°
/// kept 93–94 % of them on their axis, against 73 % at 5°). The turn is taken only where
/// the outline stays within the tolerance.
const SNAP_ANGLE: f64 = 25.0 * core::f64::consts::PI / 180.0;

/// The outline with the anchors as nodes (see the module docs), and what it cost.
#[derive(Clone, Debug)]
pub struct NodeOutline {
    /// Lines and cubics, one closed subpath per contour, on-curve points at the anchors
    /// (and, where one cubic was not within `accuracy` of a span, at the extra nodes of the
    /// fit).
    pub path: BezPath,
    /// The largest distance measured from the drafted curve to the written one (sampled
    /// both ways, font units).
    pub max_error: f64,
    /// Spans that needed more than one cubic.
    pub split_spans: usize,
    /// Extremum anchors whose tangent was turned to the axis.
    pub snapped: usize,
    /// Nodes added where a curve passed a horizontal or vertical extremum between two
    /// nodes (see [`anchor_outline`]).
    pub extrema_added: usize,
    /// The Hausdorff distance between the written outline and the original (both ways,
    /// [`WRITTEN_SAMPLES`] samples per segment, font units: [`hausdorff`](super::hausdorff)).
    pub hausdorff: f64,
}

/// Samples per segment of [`NodeOutline::hausdorff`].
pub const WRITTEN_SAMPLES: usize = 32;

/// The part of the tolerance that drafts written as a UFO leave for their written outline
/// (`kappa font` and the Python package's `draft_glyph` draft at `(1 − WRITTEN_HEADROOM)` of
/// the tolerance when no TrueType font is written): the drafts' Hausdorff distance is
/// sampled, and [`anchor_outline`]'s cubic fits add up to its `accuracy`. Drafted at the full
/// tolerance, EB Garamond's `h` (3.96 units drafted, against 4) was written 4.03 units from
/// its source, and 63 of the alphabet's 65 glyphs within 0.004 em.
pub const WRITTEN_HEADROOM: f64 = 0.05;

/// How many times [`anchor_outline`] tightens the budget of its turns when the written
/// outline strays beyond the tolerance.
const TIGHTENINGS: usize = 3;

/// The drafted glyph with its anchors as nodes: each span between consecutive anchors is one
/// cubic (exact where the span is one polynomial segment, otherwise kurbo's `fit_to_cubic`
/// within half the piece's room — below — or `accuracy` font units if that is more, and
/// kurbo's `fit_to_bezpath` within `accuracy` where one cubic is not enough). At an anchor the
/// drafting placed at an extremum of the original ([`AnchorKind::Extremum`]) whose tangent is
/// within 25° of horizontal or vertical, both handles are turned onto that axis (lengths
/// kept, or else both handle lengths of each side refitted to its curve), as a designer
/// would set them, and a curve that meets a straight segment within 10°
/// of tangent is made tangent to it (the drafting solves the curve between straight
/// segments with free ends); each only where the changed curve stays within `tolerance` of
/// `original` (the outline that was drafted), or moves from the draft by no more than the
/// piece's room (`tolerance` less the piece's Hausdorff distance, at least `accuracy`).
/// Pieces that kept the original's segments ([`Piece::fallback`]) are copied. Last, a curve
/// that passes a horizontal or vertical extremum between its nodes (bulging past its end
/// points by more than 5 · `accuracy`) is cut there exactly, where both parts keep a chord
/// of at least 20 · `accuracy` ([`NodeOutline::extrema_added`]): the outline is unchanged,
/// G2 at the new node, whose handles lie on the axis — no segment misses an extremum, as
/// font checkers (fontbakery) want.
///
/// **What holds at a node whose tangent was set.** The curve still passes through the
/// anchor (the node is the anchor) and is G1 there (both handles on one line, checked in
/// `tests/glyph.rs`), but the change comes after the solve: the two sides' |κ| at the node
/// no longer agree (no G2), and the anchor is no longer exactly the curvature peak of its
/// span. Elsewhere the written curve is the draft within `max_error`. (Constraining the
/// tangent inside the solve, which would keep G2 by giving up the peak condition, is not
/// built.)
///
/// **Within the tolerance, both ways.** The turns are checked one way (samples of the turned
/// curve near the original), so together they can leave part of the original further than
/// `tolerance` from the written outline (EB Garamond's `three` at 4.27 units, `h` at 4.03,
/// against a tolerance of 4). The written outline's Hausdorff distance from `original` is
/// measured ([`NodeOutline::hausdorff`]); where it exceeds `tolerance` the outline is written
/// again with the turns' budget lowered by the excess (and by `accuracy`), up to three times,
/// and the nearest outline is kept.
pub fn anchor_outline(
    drafted: &DraftedGlyph,
    original: &BezPath,
    accuracy: f64,
    tolerance: f64,
) -> NodeOutline {
    let mut budget = tolerance;
    let mut best: Option<NodeOutline> = None;
    for _ in 0..=TIGHTENINGS {
        let mut out = nodes_within(drafted, original, accuracy, budget);
        out.hausdorff = super::hausdorff(&out.path, original, WRITTEN_SAMPLES);
        let excess = out.hausdorff - tolerance;
        if best.as_ref().map_or(true, |b| out.hausdorff < b.hausdorff) {
            best = Some(out);
        }
        // (Also stops on a NaN distance.)
        if excess.is_nan() || excess <= 0.0 {
            break;
        }
        budget -= excess + accuracy;
        if budget.is_nan() || budget <= 0.0 {
            break;
        }
    }
    best.expect("one outline is always written")
}

/// [`anchor_outline`] with the turns' budget `tolerance`, unmeasured.
fn nodes_within(
    drafted: &DraftedGlyph,
    original: &BezPath,
    accuracy: f64,
    tolerance: f64,
) -> NodeOutline {
    let original: Vec<PathSeg> = original.segments().collect();
    let budget = Budget {
        original: &original,
        tolerance,
    };
    let mut out = NodeOutline {
        path: BezPath::new(),
        max_error: 0.0,
        split_spans: 0,
        snapped: 0,
        extrema_added: 0,
        hausdorff: 0.0,
    };
    for contour in &drafted.contours {
        // Each piece's curves (cubics and lines), and which of their start nodes are
        // extremum anchors.
        let mut curves: Vec<(PathSeg, bool)> = Vec::new();
        let mut sources: Vec<Option<SpanSource>> = Vec::new();
        for piece in &contour.pieces {
            let room = piece
                .hausdorff
                .map_or(accuracy, |h| (tolerance - h).max(accuracy));
            piece_curves(piece, (accuracy, room), &mut curves, &mut sources, &mut out);
        }
        if curves.is_empty() {
            continue;
        }
        snap_extrema(&mut curves, &sources, &budget, &mut out);
        smooth_line_joins(&mut curves, &sources, &budget, &mut out);
        out.path.move_to(curves[0].0.start());
        for (c, _) in &curves {
            for part in split_at_extrema(*c, accuracy, &mut out.extrema_added) {
                match part {
                    PathSeg::Line(l) => out.path.line_to(l.p1),
                    PathSeg::Quad(q) => out.path.quad_to(q.p1, q.p2),
                    PathSeg::Cubic(c) => out.path.curve_to(c.p1, c.p2, c.p3),
                }
            }
        }
        out.path.close_path();
    }
    out
}

/// The curves of one piece, appended to `curves` with a flag for an extremum anchor at
/// each curve's start, and the span each came from (`None`: copied).
fn piece_curves(
    piece: &Piece,
    (accuracy, room): (f64, f64),
    curves: &mut Vec<(PathSeg, bool)>,
    sources: &mut Vec<Option<SpanSource>>,
    out: &mut NodeOutline,
) {
    let segs = piece.spline.segments();
    let m = piece.anchors.len();
    if piece.fallback || m < 2 || (!piece.closed && m == 2) || segs.is_empty() {
        for seg in piece.path.segments() {
            curves.push((seg, false));
            sources.push(None);
        }
        return;
    }
    let n = segs.len();
    let part = |j: usize, r: Range<f64>| Part {
        curve: SegCurve::of(&segs[j]),
        range: r,
    };
    // The spans in order, and the anchor each starts at.
    let mut spans: Vec<(Vec<Part>, usize)> = Vec::new();
    if piece.closed {
        for j in 0..n {
            let k = (j + 1) % n;
            spans.push((
                vec![part(j, segs[j].t_max..1.0), part(k, 0.0..segs[k].t_max)],
                j,
            ));
        }
    } else {
        spans.push((vec![part(0, 0.0..segs[0].t_max)], 0));
        for j in 0..n - 1 {
            spans.push((
                vec![
                    part(j, segs[j].t_max..1.0),
                    part(j + 1, 0.0..segs[j + 1].t_max),
                ],
                j + 1,
            ));
        }
        spans.push((vec![part(n - 1, segs[n - 1].t_max..1.0)], n));
    }
    for (parts, anchor) in spans {
        let parts: Vec<Part> = parts.into_iter().filter(|p| !p.is_point()).collect();
        if parts.is_empty() {
            continue;
        }
        let extremum = piece
            .anchors
            .get(anchor)
            .is_some_and(|a| a.kind == AnchorKind::Extremum);
        let span = Span::new(parts);
        let fitted = span.to_cubics(accuracy, (0.5 * room).max(accuracy));
        if fitted.len() > 1 {
            out.split_spans += 1;
        }
        out.max_error = out.max_error.max(span.distance(&fitted));
        let (first, len) = (curves.len(), fitted.len());
        for (i, c) in fitted.into_iter().enumerate() {
            curves.push((PathSeg::Cubic(c), extremum && i == 0));
            sources.push(Some(SpanSource {
                span: span.clone(),
                room,
                first,
                len,
            }));
        }
    }
}

/// The angle (radians) within which the original's tangent at a node counts as horizontal
/// or vertical (1°, as font checkers count extremum nodes).
const AXIS_ANGLE: f64 = core::f64::consts::PI / 180.0;

/// A curve that passes an extremum in x or y between its end points by more than this
/// many `accuracy` is cut there (0.5 unit of a 1000-unit em at the default accuracy).
const EXTREMUM_BULGE: f64 = 5.0;

/// A cut at an extremum leaves parts whose chords are at least this many `accuracy` long
/// (2 units of a 1000-unit em at the default accuracy): no short segments.
const EXTREMUM_MIN_PART: f64 = 20.0;

/// The curve cut at its extrema in x and y (kurbo's `extrema`) where it bulges past the
/// interval of its end points by more than [`EXTREMUM_BULGE`] · `accuracy` and every part
/// keeps a chord of at least [`EXTREMUM_MIN_PART`] · `accuracy`. The parts are exact
/// subsegments, so the curve is unchanged (and stays G2 at the new node); at the new node
/// the derivative's x or y is zero, so the node's handles are horizontal or vertical, as a
/// font's extremum nodes are.
fn split_at_extrema(seg: PathSeg, accuracy: f64, added: &mut usize) -> Vec<PathSeg> {
    use kurbo::ParamCurveExtrema;
    let (p0, p1) = (seg.start(), seg.end());
    let bulge = |t: f64| {
        let p = seg.eval(t);
        let over = |v: f64, a: f64, b: f64| (a.min(b) - v).max(v - a.max(b)).max(0.0);
        over(p.x, p0.x, p1.x).max(over(p.y, p0.y, p1.y))
    };
    let min_part = EXTREMUM_MIN_PART * accuracy;
    let mut cuts: Vec<f64> = Vec::new();
    for t in seg.extrema() {
        if !(t > 0.0 && t < 1.0) || bulge(t) <= EXTREMUM_BULGE * accuracy {
            continue;
        }
        let p = seg.eval(t);
        let last = cuts.last().map_or(p0, |&c| seg.eval(c));
        if (p - last).hypot() >= min_part && (p1 - p).hypot() >= min_part {
            cuts.push(t);
        }
    }
    if cuts.is_empty() {
        return vec![seg];
    }
    *added += cuts.len();
    let mut parts: Vec<PathSeg> = Vec::with_capacity(cuts.len() + 1);
    let mut from = 0.0;
    for &t in cuts.iter().chain(core::iter::once(&1.0)) {
        let mut part = seg.subsegment(from..t);
        if let Some(prev) = parts.last_mut() {
            // The handles at the cut on the axis exactly (they are within rounding of it).
            let node = part.start();
            let d = match seg {
                PathSeg::Cubic(c) => c.deriv().eval(from).to_vec2(),
                PathSeg::Quad(q) => q.deriv().eval(from).to_vec2(),
                PathSeg::Line(l) => l.p1 - l.p0,
            };
            let vertical = d.x.abs() < d.y.abs();
            let put = |p: &mut Point| {
                if vertical {
                    p.x = node.x;
                } else {
                    p.y = node.y;
                }
            };
            match (prev, &mut part) {
                (PathSeg::Cubic(a), PathSeg::Cubic(b)) => {
                    put(&mut a.p2);
                    put(&mut b.p1);
                }
                (PathSeg::Quad(a), PathSeg::Quad(b)) => {
                    put(&mut a.p1);
                    put(&mut b.p1);
                }
                _ => {}
            }
        }
        parts.push(part);
        from = t;
    }
    parts
}

/// Turns the tangent at each flagged node onto the nearest axis where it is within
/// [`SNAP_ANGLE`] and the two curves meeting there stay within their room of their spans
/// ([`Budget::accept`]).
fn snap_extrema(
    curves: &mut [(PathSeg, bool)],
    sources: &[Option<SpanSource>],
    budget: &Budget<'_>,
    out: &mut NodeOutline,
) {
    let n = curves.len();
    for i in 0..n {
        let prev = (i + n - 1) % n;
        let (PathSeg::Cubic(before), PathSeg::Cubic(after)) = (curves[prev].0, curves[i].0) else {
            continue;
        };
        if !(curves[i].1 || budget.axis_on_original(after.p0)) {
            continue;
        }
        let (h_in, h_out) = (before.p2 - before.p3, after.p1 - after.p0);
        if h_out.hypot2() == 0.0 || h_in.hypot2() == 0.0 {
            continue;
        }
        let angle = h_out.angle();
        let axis = (angle / core::f64::consts::FRAC_PI_2).round() * core::f64::consts::FRAC_PI_2;
        let off = angle - axis;
        // The arriving handle's turn from the same axis: one of the two may be on it already
        // (a piece cut at the node, which held its tangent on one side only).
        let off_in = {
            let a = (-h_in).angle() - axis;
            (a + core::f64::consts::PI).rem_euclid(core::f64::consts::TAU) - core::f64::consts::PI
        };
        if off.abs() > SNAP_ANGLE || off_in.abs() > SNAP_ANGLE || (off == 0.0 && off_in == 0.0) {
            continue;
        }
        // The axis direction, exactly.
        let dir = match ((axis / core::f64::consts::FRAC_PI_2).round() as i64).rem_euclid(4) {
            0 => Vec2::new(1.0, 0.0),
            1 => Vec2::new(0.0, 1.0),
            2 => Vec2::new(-1.0, 0.0),
            _ => Vec2::new(0.0, -1.0),
        };
        // One node for both curves (their ends may differ in the last bits).
        let node = after.p0;
        let before = CubicBez { p3: node, ..before };
        if let (Some((a, da)), Some((b, db))) = (
            budget.turn_or_refit(&after, i, Some(dir), None, curves, sources),
            budget.turn_or_refit(&before, prev, None, Some(-dir), curves, sources),
        ) {
            curves[prev].0 = PathSeg::Cubic(b);
            curves[i].0 = PathSeg::Cubic(a);
            out.max_error = out.max_error.max(da).max(db);
            out.snapped += 1;
        }
    }
}

/// The cubic with `c`'s end points whose handles leave `p0` along the unit vector `d0` and
/// arrive at `p3` from the unit vector `d1` (`p2 = p3 + L₁·d1`), with the two lengths that
/// fit `c` best in the least-squares sense at 16 equal parameter steps (a linear problem:
/// `B(t) − (b₀ + b₁) p0 − (b₂ + b₃) p3 = b₁ L₀ d0 + b₂ L₁ d1`, Bernstein weights `bᵢ`).
/// None when the fit wants a handle of negative or no length, or the directions are
/// parallel.
fn fit_handle_lengths(c: &CubicBez, d0: Vec2, d1: Vec2) -> Option<CubicBez> {
    const STEPS: usize = 16;
    let (mut a00, mut a01, mut a11, mut r0, mut r1) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let dd = d0.dot(d1);
    for i in 1..STEPS {
        let t = i as f64 / STEPS as f64;
        let mt = 1.0 - t;
        let (b0, b1, b2, b3) = (mt * mt * mt, 3.0 * mt * mt * t, 3.0 * mt * t * t, t * t * t);
        let r = c.eval(t).to_vec2() - c.p0.to_vec2() * (b0 + b1) - c.p3.to_vec2() * (b2 + b3);
        a00 += b1 * b1;
        a01 += b1 * b2 * dd;
        a11 += b2 * b2;
        r0 += b1 * d0.dot(r);
        r1 += b2 * d1.dot(r);
    }
    let det = a00 * a11 - a01 * a01;
    if det.is_nan() || det.abs() <= 1e-12 * a00 * a11 {
        return None;
    }
    let l0 = (r0 * a11 - r1 * a01) / det;
    let l1 = (a00 * r1 - a01 * r0) / det;
    (l0 > 0.0 && l1 > 0.0 && l0.is_finite() && l1.is_finite())
        .then(|| CubicBez::new(c.p0, c.p0 + d0 * l0, c.p3 + d1 * l1, c.p3))
}

/// The largest angle (radians) between a straight segment and the curve leaving it that is
/// taken for a smooth join and made tangent: corners turn by more than 15° (where the
/// drafting cuts contours).
const SMOOTH_JOIN_ANGLE: f64 = 10.0 * core::f64::consts::PI / 180.0;

/// The largest angle by which a handle is turned onto a line where the original's join is
/// smooth ([`Budget::smooth_on_original`]): the three-anchor drafts of EB Garamond's small
/// fillets meet their lines at 46°–63°. The turn is also bounded by [`Budget::accept`], and
/// an asymmetric fillet's turned curve keeps both handles pointing forward.
const FILLET_JOIN_ANGLE: f64 = 70.0 * core::f64::consts::PI / 180.0;

/// Makes each curve that meets a straight segment at a near-smooth join (within
/// [`SMOOTH_JOIN_ANGLE`]) leave it tangent to the line: the drafting cuts contours at straight
/// segments and solves the curve between them with free ends, so a smooth line-to-curve
/// join of the original comes out with a small kink. The handle at the join is turned onto
/// the line's direction (length kept) where [`Budget::accept`] accepts the change.
fn smooth_line_joins(
    curves: &mut [(PathSeg, bool)],
    sources: &[Option<SpanSource>],
    budget: &Budget<'_>,
    out: &mut NodeOutline,
) {
    let n = curves.len();
    for i in 0..n {
        let next = (i + 1) % n;
        // A line, then a curve: the curve's first handle along the line.
        if let (PathSeg::Line(l), PathSeg::Cubic(c)) = (curves[i].0, curves[next].0) {
            let dir = l.p1 - l.p0;
            let h = c.p1 - c.p0;
            if turn_within(dir, h).is_some() || budget.smooth_on_original(c.p0, dir, h) {
                let u = dir / dir.hypot();
                if let Some((f, d)) = budget.turn_or_refit(&c, next, Some(u), None, curves, sources)
                {
                    curves[next].0 = PathSeg::Cubic(f);
                    out.max_error = out.max_error.max(d);
                }
            }
        }
        // A curve, then a line: the curve's last handle along the line.
        if let (PathSeg::Cubic(c), PathSeg::Line(l)) = (curves[i].0, curves[next].0) {
            let dir = l.p1 - l.p0;
            let h = c.p3 - c.p2;
            if turn_within(dir, h).is_some() || budget.smooth_on_original(c.p3, dir, h) {
                let u = dir / dir.hypot();
                if let Some((f, d)) = budget.turn_or_refit(&c, i, None, Some(-u), curves, sources) {
                    curves[i].0 = PathSeg::Cubic(f);
                    out.max_error = out.max_error.max(d);
                }
            }
        }
    }
}

/// The length of handle `h` if it turns from direction `dir` by a nonzero angle of at most
/// [`SMOOTH_JOIN_ANGLE`].
fn turn_within(dir: Vec2, h: Vec2) -> Option<f64> {
    turn_angle(dir, h)
        .filter(|&a| a > 0.0 && a <= SMOOTH_JOIN_ANGLE)
        .map(|_| h.hypot())
}

/// The angle in `[0, π]` from direction `dir` to handle `h`; `None` if either is zero.
pub(super) fn turn_angle(dir: Vec2, h: Vec2) -> Option<f64> {
    (dir.hypot() > 0.0 && h.hypot() > 0.0).then(|| dir.cross(h).atan2(dir.dot(h)).abs())
}

/// How far a curve turned at a node may move: within its room of the drafted span (see
/// [`anchor_outline`]), or anywhere within the tolerance of the original outline (sampled).
struct Budget<'a> {
    original: &'a [PathSeg],
    tolerance: f64,
}

impl Budget<'_> {
    /// The distance of curve `k`, changed to `c`, from its drafted span (with the span's
    /// other cubics as they are), if the change is acceptable: curve `k` comes from a span
    /// (not copied, not a line), and `c` stays within the span's room of it or within the
    /// tolerance of the original.
    fn accept(
        &self,
        c: &CubicBez,
        k: usize,
        curves: &[(PathSeg, bool)],
        sources: &[Option<SpanSource>],
    ) -> Option<f64> {
        let s = sources[k].as_ref()?;
        let mut cubics = Vec::with_capacity(s.len);
        for (m, curve) in curves.iter().enumerate().skip(s.first).take(s.len) {
            cubics.push(match curve.0 {
                _ if m == k => *c,
                PathSeg::Cubic(x) => x,
                _ => return None,
            });
        }
        let d = s.span.distance(&cubics);
        if d <= s.room || self.near_original(c) {
            Some(d)
        } else {
            None
        }
    }

    /// Curve `k` (`old`) with its start handle along the unit vector `start` and/or its end
    /// handle along `end` (`p2 = p3 + L·end`), if [`Budget::accept`] takes it: first with the
    /// handles' lengths kept, else with both lengths refitted ([`fit_handle_lengths`]). The
    /// changed curve and its distance from the draft.
    fn turn_or_refit(
        &self,
        old: &CubicBez,
        k: usize,
        start: Option<Vec2>,
        end: Option<Vec2>,
        curves: &[(PathSeg, bool)],
        sources: &[Option<SpanSource>],
    ) -> Option<(CubicBez, f64)> {
        let mut turned = *old;
        if let Some(d) = start {
            turned.p1 = old.p0 + d * (old.p1 - old.p0).hypot();
        }
        if let Some(d) = end {
            turned.p2 = old.p3 + d * (old.p2 - old.p3).hypot();
        }
        let accept = |c: CubicBez| self.accept(&c, k, curves, sources).map(|d| (c, d));
        accept(turned).or_else(|| {
            let d0 = start.unwrap_or_else(|| (old.p1 - old.p0).normalize());
            let d1 = end.unwrap_or_else(|| (old.p2 - old.p3).normalize());
            fit_handle_lengths(old, d0, d1).and_then(accept)
        })
    }

    /// Whether the original outline passes through `p` (within 1e-6 of the tolerance) with a
    /// horizontal or vertical tangent (within [`AXIS_ANGLE`]): a node there is an extremum
    /// node of the original, whichever kind of anchor the drafting made it.
    fn axis_on_original(&self, p: Point) -> bool {
        let near = 1e-6 * self.tolerance;
        self.original.iter().any(|s| {
            let hit = s.nearest(p, 1e-9);
            if hit.distance_sq > near * near {
                return false;
            }
            let d = match s {
                PathSeg::Line(l) => l.p1 - l.p0,
                PathSeg::Quad(q) => q.deriv().eval(hit.t).to_vec2(),
                PathSeg::Cubic(c) => c.deriv().eval(hit.t).to_vec2(),
            };
            let a = d.angle().rem_euclid(core::f64::consts::FRAC_PI_2);
            d.hypot2() > 0.0 && a.min(core::f64::consts::FRAC_PI_2 - a) <= AXIS_ANGLE
        })
    }

    /// Whether the original outline has a smooth join at `p` (within 1e-6 of the
    /// tolerance) with a curve leaving or reaching it along `dir` (within [`AXIS_ANGLE`]),
    /// and the drafted handle `h` (pointing the way the outline runs, as `dir` does) is within
    /// [`FILLET_JOIN_ANGLE`] of `dir`: a line-to-curve join the designer made smooth, which
    /// the draft meets at more than [`SMOOTH_JOIN_ANGLE`] (a small fillet between a stem and
    /// a crossbar, drafted through three anchors, meets its lines at up to 63°).
    fn smooth_on_original(&self, p: Point, dir: Vec2, h: Vec2) -> bool {
        if !turn_angle(dir, h).is_some_and(|a| a <= FILLET_JOIN_ANGLE) {
            return false;
        }
        let near = 1e-6 * self.tolerance;
        // The line, arriving at `p` and leaving it, against each curve of the original that
        // leaves or reaches `p` (the joint's tangent angle as `continuity` measures it).
        let arriving = PathSeg::Line(kurbo::Line::new(p - dir, p));
        let leaving = PathSeg::Line(kurbo::Line::new(p, p + dir));
        let smooth = |a: &PathSeg, b: &PathSeg| continuity(a, b).tangent_angle <= AXIS_ANGLE;
        self.original
            .iter()
            .filter(|s| !matches!(s, PathSeg::Line(_)))
            .any(|s| {
                ((s.start() - p).hypot() <= near && smooth(&arriving, s))
                    || ((s.end() - p).hypot() <= near && smooth(s, &leaving))
            })
    }

    /// Whether every sample of `c` is within the tolerance of the original outline.
    fn near_original(&self, c: &CubicBez) -> bool {
        const SAMPLES: usize = 24;
        !self.original.is_empty()
            && (0..=SAMPLES).all(|i| {
                let p = c.eval(i as f64 / SAMPLES as f64);
                self.original
                    .iter()
                    .any(|s| s.nearest(p, 1e-6).distance_sq <= self.tolerance * self.tolerance)
            })
    }
}

/// The span a written cubic was fitted to: its room (see [`anchor_outline`]) and the
/// `len` cubics from index `first` that were fitted to it together.
#[derive(Clone, Debug)]
struct SpanSource {
    span: Span,
    room: f64,
    first: usize,
    len: usize,
}

/// One segment of a drafted curve, evaluable with derivatives.
#[derive(Clone, Debug)]
enum SegCurve {
    Poly(PathSeg),
    Trig(TrigBez),
}

impl SegCurve {
    fn of(seg: &Segment<Point>) -> SegCurve {
        if seg.scheme == Scheme::EkTrig {
            SegCurve::Trig(seg.to_trig())
        } else {
            SegCurve::Poly(seg.to_path_seg())
        }
    }

    fn point_deriv(&self, t: f64) -> (Point, Vec2) {
        match self {
            SegCurve::Poly(s) => {
                let (p, d, _) = crate::spline::path_seg_derivs(s, t);
                (p, d)
            }
            SegCurve::Trig(c) => {
                let (p, d, _) = c.eval_derivs(t);
                (p, d)
            }
        }
    }
}

/// A parameter range of a segment.
#[derive(Clone, Debug)]
struct Part {
    curve: SegCurve,
    range: Range<f64>,
}

impl Part {
    /// Whether the part has no extent (a collapsed segment, or a peak at the segment end).
    fn is_point(&self) -> bool {
        let (a, _) = self.curve.point_deriv(self.range.start);
        let (b, _) = self.curve.point_deriv(self.range.end);
        let (m, _) = self
            .curve
            .point_deriv(0.5 * (self.range.start + self.range.end));
        self.range.end - self.range.start <= 1e-12 || (a == b && a == m)
    }
}

/// The curve between two anchors: one or two parts, parameter `u ∈ [0, 1]` spread over them
/// in proportion to their lengths (`bounds[i]..bounds[i + 1]` is part `i`'s share). Spread
/// evenly, a part of a unit or two next to an anchor (a peak near its segment's end) took
/// half the parameter range, and kurbo's fit, which halves the range where one cubic does
/// not do, cut the span at the parts' joint: a curve segment under 2 units in the written
/// outline.
#[derive(Clone, Debug)]
struct Span {
    parts: Vec<Part>,
    bounds: Vec<f64>,
}

impl Span {
    /// The span of `parts`, with their shares of the parameter by length (16 chords each; a
    /// part gets at least 1e-6 of the range).
    fn new(parts: Vec<Part>) -> Span {
        const CHORDS: usize = 16;
        let lengths: Vec<f64> = parts
            .iter()
            .map(|part| {
                let (a, b) = (part.range.start, part.range.end);
                let at = |i: usize| {
                    part.curve
                        .point_deriv(a + (b - a) * i as f64 / CHORDS as f64)
                        .0
                };
                (1..=CHORDS)
                    .map(|i| (at(i) - at(i - 1)).hypot())
                    .sum::<f64>()
            })
            .collect();
        let total: f64 = lengths.iter().sum();
        let k = parts.len() as f64;
        let mut bounds = vec![0.0];
        let mut acc = 0.0;
        for len in &lengths {
            let share = if total > 0.0 && total.is_finite() {
                (len / total).max(1e-6)
            } else {
                1.0 / k
            };
            acc += share;
            bounds.push(acc);
        }
        for b in bounds.iter_mut() {
            *b /= acc;
        }
        Span { parts, bounds }
    }

    /// The part and its local parameter at `u`, with the parameter speed's factor; at a
    /// boundary, the part after it for `sign > 0` and the one before for `sign < 0`.
    fn locate(&self, u: f64, sign: f64) -> (&Part, f64, f64) {
        let k = self.parts.len();
        let u = u.clamp(0.0, 1.0);
        let mut i = (0..k).rfind(|&i| self.bounds[i] <= u).unwrap_or(0);
        if u == self.bounds[i] && sign < 0.0 && i > 0 {
            i -= 1;
        }
        let (lo, hi) = (self.bounds[i], self.bounds[i + 1]);
        let part = &self.parts[i];
        let w = part.range.end - part.range.start;
        let x = ((u - lo) / (hi - lo)).clamp(0.0, 1.0);
        (part, part.range.start + w * x, w / (hi - lo))
    }

    fn eval(&self, u: f64, sign: f64) -> (Point, Vec2) {
        let (part, t, scale) = self.locate(u, sign);
        let (p, d) = part.curve.point_deriv(t);
        (p, d * scale)
    }

    /// One cubic if exact or within `one` (the span's share of the tolerance), else kurbo's
    /// fit within `accuracy`.
    fn to_cubics(&self, accuracy: f64, one: f64) -> Vec<CubicBez> {
        if let [Part {
            curve: SegCurve::Poly(seg),
            range,
        }] = self.parts.as_slice()
        {
            return vec![crate::fit::to_cubic(seg.subsegment(range.clone()))];
        }
        if let Some((c, err2)) = fit_to_cubic(self, 0.0..1.0, one) {
            if err2.sqrt() <= one {
                return vec![c];
            }
        }
        let mut out = Vec::new();
        crate::fit::push_cubics(&fit_to_bezpath(self, accuracy), &mut out);
        out
    }

    /// The largest distance between the span and `cubics` (sampled both ways).
    fn distance(&self, cubics: &[CubicBez]) -> f64 {
        const SAMPLES: usize = 24;
        let mut d: f64 = 0.0;
        for i in 0..=SAMPLES {
            let p = self.eval(i as f64 / SAMPLES as f64, 1.0).0;
            let near = cubics
                .iter()
                .map(|c| c.nearest(p, 1e-9).distance_sq)
                .fold(f64::INFINITY, f64::min);
            d = d.max(near.sqrt());
        }
        for c in cubics {
            for i in 0..=SAMPLES {
                let q = c.eval(i as f64 / SAMPLES as f64);
                let near = self
                    .parts
                    .iter()
                    .map(|part| nearest_on_part(part, q))
                    .fold(f64::INFINITY, f64::min);
                d = d.max(near);
            }
        }
        d
    }
}

/// The distance from `q` to a part (dense sampling, then a golden-section refinement).
fn nearest_on_part(part: &Part, q: Point) -> f64 {
    const N: usize = 32;
    let (a, b) = (part.range.start, part.range.end);
    let dist = |t: f64| (part.curve.point_deriv(t).0 - q).hypot();
    let mut best = (f64::INFINITY, a);
    for i in 0..=N {
        let t = a + (b - a) * i as f64 / N as f64;
        let d = dist(t);
        if d < best.0 {
            best = (d, t);
        }
    }
    let h = (b - a) / N as f64;
    let (mut lo, mut hi) = ((best.1 - h).max(a), (best.1 + h).min(b));
    for _ in 0..40 {
        let m1 = lo + 0.382 * (hi - lo);
        let m2 = lo + 0.618 * (hi - lo);
        if dist(m1) < dist(m2) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    best.0.min(dist(0.5 * (lo + hi)))
}

impl ParamCurveFit for Span {
    fn sample_pt_tangent(&self, t: f64, sign: f64) -> CurveFitSample {
        let (p, tangent) = self.eval(t, sign);
        CurveFitSample { p, tangent }
    }

    fn sample_pt_deriv(&self, t: f64) -> (Point, Vec2) {
        self.eval(t, 1.0)
    }

    fn break_cusp(&self, _: Range<f64>) -> Option<f64> {
        None
    }

    /// kurbo's Gauss–Legendre quadrature, on each part separately: the parameter speed
    /// jumps where the parts meet, which one quadrature over the whole range would not
    /// integrate accurately (and the fit would then miss).
    fn moment_integrals(&self, range: Range<f64>) -> (f64, f64, f64) {
        let mut total = (0.0, 0.0, 0.0);
        let mut lo = range.start;
        while lo < range.end {
            let next = self.bounds.iter().copied().find(|&b| b > lo).unwrap_or(1.0);
            let hi = next.min(range.end);
            if hi <= lo {
                break;
            }
            let (t0, dt) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            for &(wi, xi) in kurbo::common::GAUSS_LEGENDRE_COEFFS_16 {
                let (p, d) = self.eval(t0 + xi * dt, 1.0);
                let a = wi * d.x * p.y * dt;
                total.0 += a;
                total.1 += p.x * a;
                total.2 += p.y * a;
            }
            lo = hi;
        }
        total
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_span_with_a_short_part_is_not_cut_at_the_parts_joint() {
        // The last unit of one quadratic, then a long bend of another, meeting at a
        // curvature jump (as an anchor whose peak lies near its segment's end gives): fitted
        // within a tight accuracy, no cubic of the fit is shorter than 2 units.
        let a = kurbo::QuadBez::new((0.0, 0.0), (50.0, 50.0), (100.0, 0.0));
        let t = 1.0 - 1.0 / a.p1.distance(a.p2) / 2.0;
        let b = kurbo::QuadBez::new((100.0, 0.0), (150.0, -50.0), (160.0, 40.0));
        let span = Span::new(vec![
            Part {
                curve: SegCurve::Poly(PathSeg::Quad(a)),
                range: t..1.0,
            },
            Part {
                curve: SegCurve::Poly(PathSeg::Quad(b)),
                range: 0.0..1.0,
            },
        ]);
        assert!((span.eval(0.0, 1.0).0 - a.eval(t)).hypot() < 1e-12);
        assert!((span.eval(1.0, -1.0).0 - b.p2).hypot() < 1e-12);
        let cubics = span.to_cubics(0.01, 0.01);
        assert!(cubics.len() > 1);
        for c in &cubics {
            assert!((c.p3 - c.p0).hypot() >= 2.0, "{c:?}");
        }
        assert!(span.distance(&cubics) < 0.05);
    }

    #[test]
    fn a_bulging_curve_is_cut_exactly_at_its_extremum() {
        // A bowl from (0, 100) down through its bottom near y = 25 and up to (200, 100).
        let c = CubicBez::new((0.0, 100.0), (50.0, 0.0), (150.0, 0.0), (200.0, 100.0));
        let mut added = 0;
        let parts = split_at_extrema(PathSeg::Cubic(c), 0.1, &mut added);
        assert_eq!((parts.len(), added), (2, 1));
        let (PathSeg::Cubic(a), PathSeg::Cubic(b)) = (parts[0], parts[1]) else {
            panic!("{parts:?}");
        };
        // The node is the bottom, its handles horizontal exactly, the curve unchanged.
        assert!((a.p3 - Point::new(100.0, 25.0)).hypot() < 1e-12);
        assert_eq!((a.p2.y, b.p1.y), (a.p3.y, b.p0.y));
        for i in 0..=16 {
            let t = f64::from(i) / 16.0;
            let (pa, pb) = (a.eval(t), b.eval(t));
            let (qa, qb) = (c.eval(t / 2.0), c.eval(0.5 + t / 2.0));
            assert!((pa - qa).hypot() < 1e-9 && (pb - qb).hypot() < 1e-9);
        }
        // A curve that stays between its ends, or bulges by less than 5 · accuracy, or whose
        // extremum is within 20 · accuracy of an end, is left alone.
        let flat = CubicBez::new((0.0, 0.0), (50.0, 10.0), (150.0, 90.0), (200.0, 100.0));
        let small = CubicBez::new((0.0, 10.0), (30.0, 9.4), (170.0, 9.4), (200.0, 10.0));
        let near_end = CubicBez::new((0.0, 0.0), (0.0, -3.0), (100.0, 50.0), (200.0, 100.0));
        for c in [flat, small, near_end] {
            let parts = split_at_extrema(PathSeg::Cubic(c), 0.1, &mut added);
            assert_eq!(parts, vec![PathSeg::Cubic(c)]);
        }
        assert_eq!(added, 1);
    }

    #[test]
    fn handle_lengths_fit_a_cubic_with_its_own_directions_exactly() {
        let c = CubicBez::new((0.0, 0.0), (30.0, 40.0), (120.0, 60.0), (150.0, 10.0));
        let fit = fit_handle_lengths(&c, (c.p1 - c.p0).normalize(), (c.p2 - c.p3).normalize());
        let fit = fit.unwrap();
        for (p, q) in [(fit.p1, c.p1), (fit.p2, c.p2)] {
            assert!((p - q).hypot() < 1e-9, "{p:?} {q:?}");
        }
        // A direction turned by 10° at the start: still the nearest such cubic, whose
        // handle leaves along the new direction.
        let d0 = Vec2::from_angle((c.p1 - c.p0).angle() + 10f64.to_radians());
        let turned = fit_handle_lengths(&c, d0, (c.p2 - c.p3).normalize()).unwrap();
        assert!((turned.p1 - turned.p0).normalize().cross(d0).abs() < 1e-12);
        let worst = (0..=32)
            .map(|i| (turned.eval(f64::from(i) / 32.0) - c.eval(f64::from(i) / 32.0)).hypot())
            .fold(0.0, f64::max);
        assert!(worst > 0.0 && worst < 10.0, "{worst}");
        // Directions pointing away from the curve want negative lengths: no fit.
        assert!(
            fit_handle_lengths(&c, -(c.p1 - c.p0).normalize(), -(c.p2 - c.p3).normalize())
                .is_none()
        );
    }
}
