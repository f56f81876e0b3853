//! Drafted outlines written with their anchors as the on-curve nodes.
//!
//! A drafted curve is made of segments that run from joint to joint and pass through their
//! anchor at the peak parameter `t_i`, so the curve's own Bézier nodes are the joints, not
//! the points the designer placed. For a font, the nodes should be the anchors: the span
//! between two consecutive anchors (the end of one segment and the start of the next,
//! joined with G2) becomes one cubic, fitted where it is not one Bézier already.

use core::ops::Range;

use kurbo::{
    fit_to_bezpath, fit_to_cubic, BezPath, CubicBez, CurveFitSample, ParamCurve, ParamCurveFit,
    ParamCurveNearest, PathSeg, Point, Vec2,
};

use super::{AnchorKind, DraftedGlyph, Piece};
use crate::trig::TrigBez;
use crate::{Scheme, Segment};

/// The largest angle (radians) by which the tangent at an extremum anchor is turned to the
/// nearest axis (1°… 5° off is typical of a drafted curve through a point where the original
/// is horizontal or vertical).
const SNAP_ANGLE: f64 = 5.0 * core::f64::consts::PI / 180.0;

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
}

/// The drafted glyph with its anchors as nodes: each span between consecutive anchors is one
/// cubic (exact where the span is one polynomial segment, otherwise kurbo's `fit_to_cubic`
/// within half the piece's room — below — or `accuracy` font units if that is more, and
/// kurbo's `fit_to_bezpath` within `accuracy` where one cubic is not enough). At an anchor the
/// drafting placed at an extremum of the original ([`AnchorKind::Extremum`]) whose tangent is
/// within 5° of horizontal or vertical, both handles are turned onto that axis (lengths
/// kept), as a designer would set them, and a curve that meets a straight segment within 10°
/// of tangent is made tangent to it (the drafting solves the curve between straight
/// segments with free ends); each only where the changed curve stays within `tolerance` of
/// `original` (the outline that was drafted), or moves from the draft by no more than the
/// piece's room (`tolerance` less the piece's Hausdorff distance, at least `accuracy`).
/// Pieces that kept the original's segments ([`Piece::fallback`]) are copied.
///
/// **What holds at a node whose tangent was set.** The curve still passes through the
/// anchor (the node is the anchor) and is G1 there (both handles on one line, checked in
/// `tests/glyph.rs`), but the change comes after the solve: the two sides' |κ| at the node
/// no longer agree (no G2), and the anchor is no longer exactly the curvature peak of its
/// span. Elsewhere the written curve is the draft within `max_error`. (Constraining the
/// tangent inside the solve, which would keep G2 by giving up the peak condition, is not
/// built.)
pub fn anchor_outline(
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
    };
    for contour in &drafted.contours {
        // Each piece's curves (cubics and lines), and which of their start nodes are
        // extremum anchors.
        let mut curves: Vec<(PathSeg, bool)> = Vec::new();
        let mut sources: Vec<Option<(Span, f64)>> = Vec::new();
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
            match *c {
                PathSeg::Line(l) => out.path.line_to(l.p1),
                PathSeg::Quad(q) => out.path.quad_to(q.p1, q.p2),
                PathSeg::Cubic(c) => out.path.curve_to(c.p1, c.p2, c.p3),
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
    sources: &mut Vec<Option<(Span, f64)>>,
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
        let span = Span { parts };
        let fitted = span.to_cubics(accuracy, (0.5 * room).max(accuracy));
        if fitted.len() > 1 {
            out.split_spans += 1;
        }
        out.max_error = out.max_error.max(span.distance(&fitted));
        for (i, c) in fitted.into_iter().enumerate() {
            curves.push((PathSeg::Cubic(c), extremum && i == 0));
            sources.push((i == 0).then(|| (span.clone(), room)));
        }
    }
}

/// Turns the tangent at each flagged node onto the nearest axis where it is within
/// [`SNAP_ANGLE`] and the two curves meeting there stay within their room of their spans
/// (a curve not fitted to one whole span is not moved).
fn snap_extrema(
    curves: &mut [(PathSeg, bool)],
    sources: &[Option<(Span, f64)>],
    budget: &Budget<'_>,
    out: &mut NodeOutline,
) {
    let n = curves.len();
    for i in 0..n {
        if !curves[i].1 {
            continue;
        }
        let prev = (i + n - 1) % n;
        let (PathSeg::Cubic(before), PathSeg::Cubic(after)) = (curves[prev].0, curves[i].0) else {
            continue;
        };
        let (h_in, h_out) = (before.p2 - before.p3, after.p1 - after.p0);
        if h_out.hypot2() == 0.0 || h_in.hypot2() == 0.0 {
            continue;
        }
        let angle = h_out.angle();
        let axis = (angle / core::f64::consts::FRAC_PI_2).round() * core::f64::consts::FRAC_PI_2;
        let off = angle - axis;
        if off.abs() > SNAP_ANGLE || off == 0.0 {
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
        let new_after = CubicBez::new(node, node + dir * h_out.hypot(), after.p2, after.p3);
        let new_before = CubicBez::new(before.p0, before.p1, node - dir * h_in.hypot(), node);
        let moved = |c: &CubicBez, k: usize| budget.accept(c, k, sources);
        if let (Some(a), Some(b)) = (moved(&new_after, i), moved(&new_before, prev)) {
            curves[prev].0 = PathSeg::Cubic(new_before);
            curves[i].0 = PathSeg::Cubic(new_after);
            out.max_error = out.max_error.max(a).max(b);
            out.snapped += 1;
        }
    }
}

/// The largest angle (radians) between a straight segment and the curve leaving it that is
/// taken for a smooth join and made tangent: corners turn by more than 15° (where the
/// drafting cuts contours).
const SMOOTH_JOIN_ANGLE: f64 = 10.0 * core::f64::consts::PI / 180.0;

/// Makes each curve that meets a straight segment at a near-smooth join (within
/// [`SMOOTH_JOIN_ANGLE`]) leave it tangent to the line: the drafting cuts contours at straight
/// segments and solves the curve between them with free ends, so a smooth line-to-curve
/// join of the original comes out with a small kink. The handle at the join is turned onto
/// the line's direction (length kept) where [`Budget::accept`] accepts the change.
fn smooth_line_joins(
    curves: &mut [(PathSeg, bool)],
    sources: &[Option<(Span, f64)>],
    budget: &Budget<'_>,
    out: &mut NodeOutline,
) {
    let n = curves.len();
    let within = |c: &CubicBez, k: usize| budget.accept(c, k, sources);
    for i in 0..n {
        let next = (i + 1) % n;
        // A line, then a curve: the curve's first handle along the line.
        if let (PathSeg::Line(l), PathSeg::Cubic(c)) = (curves[i].0, curves[next].0) {
            let dir = l.p1 - l.p0;
            let h = c.p1 - c.p0;
            if let Some(len) = turn_within(dir, h) {
                let fixed = CubicBez::new(c.p0, c.p0 + dir * (len / dir.hypot()), c.p2, c.p3);
                if let Some(d) = within(&fixed, next) {
                    curves[next].0 = PathSeg::Cubic(fixed);
                    out.max_error = out.max_error.max(d);
                }
            }
        }
        // A curve, then a line: the curve's last handle along the line.
        if let (PathSeg::Cubic(c), PathSeg::Line(l)) = (curves[i].0, curves[next].0) {
            let dir = l.p1 - l.p0;
            let h = c.p3 - c.p2;
            if let Some(len) = turn_within(dir, h) {
                let fixed = CubicBez::new(c.p0, c.p1, c.p3 - dir * (len / dir.hypot()), c.p3);
                if let Some(d) = within(&fixed, i) {
                    curves[i].0 = PathSeg::Cubic(fixed);
                    out.max_error = out.max_error.max(d);
                }
            }
        }
    }
}

/// The length of handle `h` if it turns from direction `dir` by a nonzero angle of at most
/// [`SMOOTH_JOIN_ANGLE`].
fn turn_within(dir: Vec2, h: Vec2) -> Option<f64> {
    let (ld, lh) = (dir.hypot(), h.hypot());
    if ld == 0.0 || lh == 0.0 {
        return None;
    }
    let angle = dir.cross(h).atan2(dir.dot(h)).abs();
    (angle > 0.0 && angle <= SMOOTH_JOIN_ANGLE).then_some(lh)
}

/// How far a curve turned at a node may move: within its room of the drafted span (see
/// [`anchor_outline`]), or anywhere within the tolerance of the original outline (sampled).
struct Budget<'a> {
    original: &'a [PathSeg],
    tolerance: f64,
}

impl Budget<'_> {
    /// The distance of curve `k`, changed to `c`, from its drafted span, if the change is
    /// acceptable: `c` is fitted to one whole span, and stays within the span's room of it
    /// or within the tolerance of the original.
    fn accept(&self, c: &CubicBez, k: usize, sources: &[Option<(Span, f64)>]) -> Option<f64> {
        let n = sources.len();
        let whole = sources
            .get(k + 1)
            .map_or(true, |next| next.is_some() || k + 1 == n);
        let (span, room) = sources[k].as_ref().filter(|_| whole)?;
        let d = span.distance(&[*c]);
        if d <= *room || self.near_original(c) {
            Some(d)
        } else {
            None
        }
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

/// The curve between two anchors: one or two parts, parameter `u ∈ [0, 1]` spread evenly
/// over them.
#[derive(Clone, Debug)]
struct Span {
    parts: Vec<Part>,
}

impl Span {
    /// The part and its local parameter at `u`; at a boundary, the part after it for
    /// `sign > 0` and the one before for `sign < 0`.
    fn locate(&self, u: f64, sign: f64) -> (&Part, f64, f64) {
        let k = self.parts.len() as f64;
        let x = (u.clamp(0.0, 1.0) * k).min(k);
        let mut i = x.floor();
        if (x == i && sign < 0.0 && i > 0.0) || i >= k {
            i -= 1.0;
        }
        let part = &self.parts[i as usize];
        let w = part.range.end - part.range.start;
        (part, part.range.start + w * (x - i), w * k)
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
        let k = self.parts.len() as f64;
        let mut total = (0.0, 0.0, 0.0);
        let mut lo = range.start;
        while lo < range.end {
            let hi = (((lo * k).floor() + 1.0) / k).min(range.end);
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
