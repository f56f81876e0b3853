//! Distances between outlines: nearest points with pruning and a hint, the Hausdorff
//! distance, and how far a solved piece strays from the original.

use core::cell::Cell;

use kurbo::{BezPath, ParamCurve, ParamCurveDeriv, ParamCurveNearest, PathSeg, Point, Rect, Vec2};

use super::Solved;

/// The Hausdorff distance between two outlines, on `samples` samples per segment of each
/// (clamped to 2..=256) with exact nearest points on the other: `max(sup_a d(·, b),
/// sup_b d(·, a))` over the samples. Segments whose points all coincide (a contour of one
/// point, which draws nothing: DejaVu Sans's `u` has one) are left out. 0 for two empty
/// paths; infinite if exactly one is empty.
pub fn hausdorff(a: &BezPath, b: &BezPath, samples: usize) -> f64 {
    let drawn = |s: &PathSeg| match *s {
        PathSeg::Line(l) => l.p0 != l.p1,
        PathSeg::Quad(q) => !(q.p0 == q.p1 && q.p1 == q.p2),
        PathSeg::Cubic(c) => !(c.p0 == c.p1 && c.p1 == c.p2 && c.p2 == c.p3),
    };
    let sa: Vec<PathSeg> = a.segments().filter(drawn).collect();
    let sb: Vec<PathSeg> = b.segments().filter(drawn).collect();
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
pub(super) struct Target<'a> {
    segs: &'a [PathSeg],
    boxes: Vec<Rect>,
    /// Where the last query found its nearest point (segment, t): consecutive samples have
    /// nearby nearest points, so this is where the next query looks first.
    hint: Cell<(usize, f64)>,
}

impl<'a> Target<'a> {
    pub(super) fn new(segs: &'a [PathSeg]) -> Target<'a> {
        let boxes = segs.iter().map(control_box).collect();
        Target {
            segs,
            boxes,
            hint: Cell::new((0, 0.0)),
        }
    }

    /// The squared distance from `p` to a point of the hinted segment: `HINT_STEPS` Newton
    /// steps on `(B(t) − p) · B′(t) = 0` from the hinted `t` (an upper bound of the squared
    /// distance to the target whatever the steps do).
    fn hinted(&self, p: Point) -> f64 {
        let (i, mut t) = self.hint.get();
        let Some(seg) = self.segs.get(i) else {
            return f64::INFINITY;
        };
        for _ in 0..HINT_STEPS {
            let (q, d1, d2) = derivs(seg, t);
            let r = q - p;
            let slope = d1.hypot2() + r.dot(d2);
            if slope.is_nan() || slope <= 0.0 {
                break;
            }
            t = (t - r.dot(d1) / slope).clamp(0.0, 1.0);
        }
        self.hint.set((i, t));
        (seg.eval(t) - p).hypot2()
    }

    /// The distance from `p` to the nearest segment.
    pub(super) fn distance(&self, p: Point) -> f64 {
        // The hinted point bounds the distance, so that far segments are pruned at once.
        let mut best = self.hinted(p);
        let mut found = self.hint.get();
        for (i, (seg, b)) in self.segs.iter().zip(&self.boxes).enumerate() {
            let dx = (b.x0 - p.x).max(p.x - b.x1).max(0.0);
            let dy = (b.y0 - p.y).max(p.y - b.y1).max(0.0);
            if dx * dx + dy * dy >= best {
                continue;
            }
            let near = seg.nearest(p, 1e-9);
            if near.distance_sq < best {
                best = near.distance_sq;
                found = (i, near.t);
            }
        }
        self.hint.set(found);
        best.sqrt()
    }

    /// Whether the distance from `p` to the nearest segment exceeds `floor`: settled by the
    /// hinted point when it is within `floor`, else by exact nearest points segment by
    /// segment up to the first within `floor`.
    pub(super) fn distance_above(&self, p: Point, floor: f64) -> bool {
        let f2 = floor * floor;
        if self.hinted(p) <= f2 {
            return false;
        }
        for (i, (seg, b)) in self.segs.iter().zip(&self.boxes).enumerate() {
            let dx = (b.x0 - p.x).max(p.x - b.x1).max(0.0);
            let dy = (b.y0 - p.y).max(p.y - b.y1).max(0.0);
            if dx * dx + dy * dy > f2 {
                continue;
            }
            let near = seg.nearest(p, 1e-9);
            if near.distance_sq <= f2 {
                self.hint.set((i, near.t));
                return false;
            }
        }
        true
    }

    /// Whether a sample of `segs` (those of [`Target::deviation`]) is further than `floor`
    /// from this target (stops at the first).
    fn exceeds(&self, segs: &[PathSeg], k: usize, floor: f64) -> bool {
        segs.iter().enumerate().any(|(i, seg)| {
            let last = usize::from(i + 1 == segs.len());
            (0..k + last).any(|j| self.distance_above(seg.eval(j as f64 / k as f64), floor))
        })
    }

    /// The largest distance of a sample of `segs` (`k` per segment and the last end point)
    /// to this target, and where it is (segment index + t). Samples that cannot beat the
    /// largest distance so far are settled by [`Target::distance_above`] alone.
    fn deviation(&self, segs: &[PathSeg], k: usize) -> (f64, f64) {
        let mut worst = (0.0, 0.0);
        for (i, seg) in segs.iter().enumerate() {
            let last = usize::from(i + 1 == segs.len());
            for j in 0..k + last {
                let t = j as f64 / k as f64;
                let p = seg.eval(t);
                if self.distance_above(p, worst.0) {
                    let d = self.distance(p);
                    if d > worst.0 {
                        worst = (d, i as f64 + t);
                    }
                }
            }
        }
        worst
    }
}

/// Newton steps of the projection onto the hinted segment (see [`Target::distance_above`]).
const HINT_STEPS: usize = 2;

/// A segment's point and first two derivatives at `t`.
fn derivs(seg: &PathSeg, t: f64) -> (Point, Vec2, Vec2) {
    match *seg {
        PathSeg::Line(l) => (l.eval(t), l.p1 - l.p0, Vec2::ZERO),
        PathSeg::Quad(q) => {
            let d = q.deriv();
            (q.eval(t), d.eval(t).to_vec2(), d.deriv().eval(t).to_vec2())
        }
        PathSeg::Cubic(c) => {
            let d = c.deriv();
            (c.eval(t), d.eval(t).to_vec2(), d.deriv().eval(t).to_vec2())
        }
    }
}

fn control_box(seg: &PathSeg) -> Rect {
    match *seg {
        PathSeg::Line(l) => Rect::from_points(l.p0, l.p1),
        PathSeg::Quad(q) => Rect::from_points(q.p0, q.p1).union_pt(q.p2),
        PathSeg::Cubic(c) => Rect::from_points(c.p0, c.p1).union_pt(c.p2).union_pt(c.p3),
    }
}

/// Whether a solved piece is within `tolerance` of the original both ways, on the samples of
/// [`two_way`] (stops at the first sample beyond).
pub(super) fn within(original: &Target<'_>, solved: &Solved, k: usize, tolerance: f64) -> bool {
    let drafted: Vec<PathSeg> = solved.path.segments().collect();
    !Target::new(&drafted).exceeds(original.segs, k, tolerance)
        && !original.exceeds(&drafted, k, tolerance)
}

/// The two-sided Hausdorff distance of a solved piece to the original, on `k` samples per
/// segment of each.
pub(super) fn two_way(original: &Target<'_>, solved: &Solved, k: usize) -> f64 {
    let drafted: Vec<PathSeg> = solved.path.segments().collect();
    let there = Target::new(&drafted).deviation(original.segs, k).0;
    let back = original.deviation(&drafted, k).0;
    there.max(back)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::glyph::draft::tests::ellipse;

    /// The hinted distance queries agree with exact nearest points.
    #[test]
    fn target_hint_is_exact() {
        let segs: Vec<PathSeg> = ellipse().segments().collect();
        let target = Target::new(&segs);
        for i in 0..200 {
            let th = i as f64 * 0.0731;
            let p = Point::new(1050.0 * th.cos(), 280.0 * th.sin() + 3.0 * (7.0 * th).sin());
            let exact = segs
                .iter()
                .map(|s| s.nearest(p, 1e-12).distance_sq)
                .fold(f64::INFINITY, f64::min)
                .sqrt();
            assert!((target.distance(p) - exact).abs() < 1e-6);
            for floor in [0.5 * exact, 0.999 * exact, 1.001 * exact, 2.0 * exact] {
                assert_eq!(
                    target.distance_above(p, floor),
                    exact > floor,
                    "{floor} {exact}"
                );
            }
        }
    }
}
