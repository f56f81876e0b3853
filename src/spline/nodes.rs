//! The curve with nodes at its input points and its joints, in a structure fixed by the
//! input's topology ([`Spline::to_node_bezpath`]): what point-compatible font masters need.

use kurbo::{BezPath, ParamCurve, PathSeg, Point};

use super::{Scheme, Segment, Spline};

/// Cubics per part of an εκ-trig segment in [`Spline::to_node_bezpath`] (a part runs from a
/// joint to the segment's input point, or from there to the next joint). Each is the cubic
/// Hermite interpolant of the part's ends and derivatives, so its error falls about as the
/// fourth power of the part's parameter length. Measured on the paper drawings
/// (`tests/nodes.rs`, the distance at corresponding parameters, which bounds the distance
/// between the curves): 4.6e-4 of the drawing size with 2, 1.1e-4 with 3, 3.6e-5 with 4. At
/// 2 a glyph 1000 units tall is within half a unit, well inside `kappa font`'s drafting
/// tolerance (4 units).
pub const TRIG_NODE_CUBICS: usize = 2;

impl Spline<Point> {
    /// The curve as a kurbo path whose on-curve nodes are every input point and every joint:
    /// each segment is split at its peak parameter `t_max`, where it passes through its input
    /// point.
    ///
    /// The structure depends only on the number of points and whether the curve is closed:
    ///
    /// - a closed curve through `n` points starts at point 0 and has `2n` parts (from each
    ///   point to the next joint and from there to the next point);
    /// - an open curve through `m ≥ 3` points has `2(m - 2)` parts from its first point to
    ///   its last (through 2 points, its straight segment split at the middle: 2 parts).
    ///
    /// κ parts are quadratics and εκ-cubic parts cubics, both exact (subsegments of the
    /// curve's own segments); an εκ-trig part is [`TRIG_NODE_CUBICS`] cubic Hermite
    /// interpolants of the curve. A part of no length (a peak at its segment's end, or a
    /// segment collapsed onto its point at an inflection) is kept, as a curve whose points
    /// coincide. So two curves through the same number of points, open or closed alike,
    /// give paths with the same elements in the same order whatever their positions and
    /// shapes: font masters drawn from them interpolate (where [`Spline::to_bezpath`] drops
    /// collapsed segments and fits εκ-trig curves with as many cubics as each one needs).
    ///
    /// ```
    /// use kappa::Spline;
    /// use kurbo::{PathEl, Point};
    ///
    /// let a = [(0.0, 0.0), (100.0, 10.0), (120.0, 90.0), (20.0, 110.0)].map(Point::from);
    /// let b = [(0.0, 0.0), (140.0, -20.0), (100.0, 80.0), (10.0, 140.0)].map(Point::from);
    /// let (pa, pb) = (Spline::kappa(&a, true)?.to_node_bezpath(), Spline::kappa(&b, true)?.to_node_bezpath());
    /// assert_eq!(pa.elements().len(), 2 * 4 + 2); // move, 8 quadratics, close
    /// let kinds = |p: &kurbo::BezPath| p.elements().iter().map(core::mem::discriminant).collect::<Vec<_>>();
    /// assert_eq!(kinds(&pa), kinds(&pb));
    /// // Every input point is a node.
    /// for q in a {
    ///     assert!(pa.elements().iter().any(|el| el.end_point().is_some_and(|e| (e - q).hypot() < 1e-9)));
    /// }
    /// # Ok::<(), kappa::Error>(())
    /// ```
    pub fn to_node_bezpath(&self) -> BezPath {
        let segs = &self.segments;
        let mut path = BezPath::new();
        let n = segs.len();
        if n == 0 {
            return path;
        }
        if self.closed {
            path.move_to(segs[0].eval(segs[0].t_max));
            for j in 0..n {
                let next = &segs[(j + 1) % n];
                part(&mut path, &segs[j], segs[j].t_max, 1.0);
                part(&mut path, next, 0.0, next.t_max);
            }
            path.close_path();
        } else {
            path.move_to(segs[0].eval(0.0));
            part(&mut path, &segs[0], 0.0, segs[0].t_max);
            for j in 0..n - 1 {
                part(&mut path, &segs[j], segs[j].t_max, 1.0);
                part(&mut path, &segs[j + 1], 0.0, segs[j + 1].t_max);
            }
            part(&mut path, &segs[n - 1], segs[n - 1].t_max, 1.0);
        }
        path
    }
}

/// Appends segment `seg` from `t0` to `t1` (see [`Spline::to_node_bezpath`]).
fn part(path: &mut BezPath, seg: &Segment<Point>, t0: f64, t1: f64) {
    if seg.scheme != Scheme::EkTrig {
        match seg.to_path_seg().subsegment(t0..t1) {
            PathSeg::Quad(q) => path.quad_to(q.p1, q.p2),
            PathSeg::Cubic(c) => path.curve_to(c.p1, c.p2, c.p3),
            PathSeg::Line(l) => path.line_to(l.p1),
        }
        return;
    }
    for i in 0..TRIG_NODE_CUBICS {
        let a = t0 + (t1 - t0) * i as f64 / TRIG_NODE_CUBICS as f64;
        let b = t0 + (t1 - t0) * (i + 1) as f64 / TRIG_NODE_CUBICS as f64;
        let h = (b - a) / 3.0;
        let (p0, p3) = (seg.eval(a), seg.eval(b));
        path.curve_to(p0 + seg.derivative(a) * h, p3 - seg.derivative(b) * h, p3);
    }
}
