//! Outlines onto the TrueType integer grid: rounding that keeps implied on-curve points
//! implied and smooth nodes smooth.

use kurbo::{BezPath, PathEl, Point, Vec2};

/// The turn, in radians, below which a node on the grid counts as aligned (0.1°): the
/// smooth-node pass then takes the smallest moves.
const SMOOTH_TURN: f64 = 0.1 * core::f64::consts::PI / 180.0;

/// The turn, in radians, above which a join looks kinked (0.5°): the smooth-node pass
/// moves a node itself only where its control points alone leave more, and only to less.
const SMOOTH_NODE: f64 = 0.5 * core::f64::consts::PI / 180.0;

/// How much more, in radians, the smooth-node pass may turn a corner at the far end of a
/// segment it moves (1°).
const CORNER_SLACK: f64 = core::f64::consts::PI / 180.0;

/// Curve segments on the grid shorter than this (chord, font units) are not made by the
/// smooth-node pass.
const SHORT_CHORD: f64 = 2.0;

/// The sine of the turn below which a node of the outline before rounding counts as
/// smooth (the drafted outlines' smooth nodes turn by rounding errors only).
const SMOOTH_SINE: f64 = 1e-2;

/// The outline on the TrueType integer grid. A `glyf` table stores integer font units, so
/// this is exactly what a compiled font holds.
///
/// - **Rounding.** Every point is rounded to the nearest integer, halves up (`⌊x + ½⌋`,
///   the OpenType rounding of write-fonts' `OtRound`), which moves it by at most `√2 / 2`.
/// - **Implied on-curve points stay implied.** An on-curve point midway between the control
///   points of the two quadratics it joins (the joints of a quadratic spline, such as
///   [`to_quadratic`](super::to_quadratic) makes of a cubic) is put midway between the
///   *rounded* control points, half a unit off the grid where their sum is odd. `glyf` does
///   not store such a point: write-fonts leaves it implied and a reader puts it back at the
///   midpoint, so the spline stays G1 there. Rounded on its own, the point would be stored,
///   and turned: on an EB Garamond alphabet drafted with κ-curves, 3 507 of 6 207 written
///   nodes turned by 0.5°–30°.
/// - **Smooth nodes stay smooth.** At a stored on-curve point that is smooth before
///   rounding (its incoming and outgoing directions within a sine of 1e-2), rounding the
///   points on either side turns the join by about `0.5 / h` radians for handles of `h`
///   units: up to 26° for the 1–3 unit handles of small fillets. First, every such node
///   that rounding left smooth (an extremum with its handles on the axis) holds its control
///   points on their line through it. Then each other one moves its control points by up
///   to a unit per coordinate from their rounded positions (a held one only along its
///   axis, or not at all), and the node itself likewise where one of its segments is a
///   quadratic and the control points alone leave it turned by more than 0.5°: to the
///   positions nearest the unrounded ones among those that turn the least (turns below
///   0.1° counting as one), if that is less than rounding alone, without turning the
///   smooth nodes at the far ends of its segments more (corners by at most 1° more) or
///   making a curve segment shorter than 2 units. A line's far end never moves. On that
///   alphabet, the smooth source joins the TrueType font turns by more than 0.5° went from
///   62 to 16, with every glyph still within 0.004 em.
/// - A quadratic whose control point lands on one of its end points is a straight line and
///   is written as one (a tiny quadratic that rounds so would otherwise stay a curve segment
///   of a unit or two); its ends are then rounded on their own.
///
/// So control points move by at most `3√2 / 2` units, and a quadratic by at most `√2`: the
/// rounding's `√2 / 2`, and half of a control point's move of up to `√2` after it. A stored
/// on-curve point moves by at most `√2 / 2` across its tangent. Cubics are rounded point by
/// point.
pub fn quantize(path: &BezPath) -> BezPath {
    let mut out = BezPath::new();
    let mut contour: Vec<PathEl> = Vec::new();
    for el in path.elements() {
        if matches!(el, PathEl::MoveTo(_)) && !contour.is_empty() {
            quantize_contour(&contour, &mut out);
            contour.clear();
        }
        contour.push(*el);
        if matches!(el, PathEl::ClosePath) {
            quantize_contour(&contour, &mut out);
            contour.clear();
        }
    }
    if !contour.is_empty() {
        quantize_contour(&contour, &mut out);
    }
    out
}

/// `⌊x + ½⌋` per coordinate.
fn round(p: Point) -> Point {
    Point::new((p.x + 0.5).floor(), (p.y + 0.5).floor())
}

/// One contour of [`quantize`]: `els` starts with a `MoveTo` (or continues the previous
/// contour's end) and ends with at most one `ClosePath`.
fn quantize_contour(els: &[PathEl], out: &mut BezPath) {
    let (start, body) = match els.first() {
        Some(PathEl::MoveTo(p)) => (Some(*p), &els[1..]),
        _ => (None, els),
    };
    let closed = matches!(body.last(), Some(PathEl::ClosePath));
    let body = if closed {
        &body[..body.len() - 1]
    } else {
        body
    };
    let segs: Vec<(Option<Point>, Point)> = body
        .iter()
        .filter_map(|el| match *el {
            PathEl::LineTo(p) => Some((None, p)),
            PathEl::QuadTo(a, p) => Some((Some(a), p)),
            _ => None,
        })
        .collect();
    if segs.len() != body.len() {
        // Cubics or stray elements: every point rounded on its own.
        for el in els {
            out.push(match *el {
                PathEl::MoveTo(p) => PathEl::MoveTo(round(p)),
                PathEl::LineTo(p) => PathEl::LineTo(round(p)),
                PathEl::QuadTo(a, b) => PathEl::QuadTo(round(a), round(b)),
                PathEl::CurveTo(a, b, c) => PathEl::CurveTo(round(a), round(b), round(c)),
                PathEl::ClosePath => PathEl::ClosePath,
            });
        }
        return;
    }
    let mut g = Grid::new(start, segs, closed);
    g.make_lines();
    g.align_smooth_nodes();
    g.write(out);
}

/// A contour of lines and quadratics being put on the grid.
struct Grid {
    /// The contour's start point, unrounded (`None`: it continues the previous contour).
    start: Option<Point>,
    /// Per segment: its control point (quadratics) and end point, unrounded.
    segs: Vec<(Option<Point>, Point)>,
    closed: bool,
    /// The last segment ends at the start point of a closed contour.
    wraps: bool,
    /// Per segment: its control point on the grid.
    rc: Vec<Option<Point>>,
    /// Per segment: whether its end point is implied (midway between the control points).
    implied: Vec<bool>,
    /// Per segment: a quadratic written as a line.
    line: Vec<bool>,
    /// Per segment: its stored end point where the smooth-node pass moved it.
    moved: Vec<Option<Point>>,
}

/// A candidate of the smooth-node pass: its turn beyond [`SMOOTH_TURN`], its cost, its
/// control points and node.
#[derive(Clone, Copy)]
struct Candidate {
    excess: f64,
    cost: f64,
    a: Option<Point>,
    b: Option<Point>,
    node: Point,
}

/// What earlier smooth nodes allow of a control point in the smooth-node pass.
#[derive(Clone, Copy, PartialEq)]
enum Hold {
    /// Any move of up to one unit per coordinate.
    Free,
    /// Moves of up to one unit along this axis only (a node with its handles on it).
    Along(Vec2),
    /// None.
    Fixed,
}

impl Hold {
    /// Another node holds the control point towards `d` (from the node to the point).
    fn and(self, d: Vec2) -> Hold {
        let axis = if d.x == 0.0 && d.y != 0.0 {
            Some(Vec2::new(0.0, 1.0))
        } else if d.y == 0.0 && d.x != 0.0 {
            Some(Vec2::new(1.0, 0.0))
        } else {
            None
        };
        match (self, axis) {
            (Hold::Free, Some(w)) => Hold::Along(w),
            (Hold::Along(v), Some(w)) if v == w => Hold::Along(v),
            _ => Hold::Fixed,
        }
    }

    /// The moves allowed.
    fn moves(self) -> Vec<Vec2> {
        match self {
            Hold::Free => (-1..=1)
                .flat_map(|x| (-1..=1).map(move |y| Vec2::new(f64::from(x), f64::from(y))))
                .collect(),
            Hold::Along(w) => (-1..=1).map(|m| f64::from(m) * w).collect(),
            Hold::Fixed => vec![Vec2::ZERO],
        }
    }
}

impl Grid {
    fn new(start: Option<Point>, segs: Vec<(Option<Point>, Point)>, closed: bool) -> Self {
        let n = segs.len();
        let wraps = closed && n > 0 && start.is_some_and(|s| segs[n - 1].1 == s);
        let rc = segs.iter().map(|(a, _)| a.map(round)).collect();
        let mut g = Grid {
            start,
            segs,
            closed,
            wraps,
            rc,
            implied: vec![false; n],
            line: vec![false; n],
            moved: vec![None; n],
        };
        g.implied = (0..n)
            .map(|i| {
                let (Some(a), Some(j)) = (g.segs[i].0, g.next(i)) else {
                    return false;
                };
                let Some(b) = g.segs[j].0 else {
                    return false;
                };
                let m = a.midpoint(b);
                let near = (m - g.segs[i].1).hypot() <= 1e-9 * (1.0 + m.to_vec2().hypot());
                near && g.rc[i] != g.rc[j]
            })
            .collect();
        g
    }

    fn n(&self) -> usize {
        self.segs.len()
    }

    /// The segment after segment `i`, around a closed contour.
    fn next(&self, i: usize) -> Option<usize> {
        if i + 1 < self.n() {
            Some(i + 1)
        } else if self.wraps {
            Some(0)
        } else {
            None
        }
    }

    /// The segment before segment `i`, around a closed contour.
    fn prev(&self, i: usize) -> Option<usize> {
        if i > 0 {
            Some(i - 1)
        } else if self.wraps {
            Some(self.n() - 1)
        } else {
            None
        }
    }

    /// The control point of segment `i` as written (`None` for a line).
    fn control(&self, i: usize) -> Option<Point> {
        self.rc[i].filter(|_| !self.line[i])
    }

    /// The end point of segment `i` on the grid (or implied).
    fn end(&self, i: usize) -> Point {
        match (self.implied[i], self.next(i)) {
            (true, Some(j)) => self.rc[i]
                .unwrap_or_default()
                .midpoint(self.rc[j].unwrap_or_default()),
            _ => self.moved[i].unwrap_or_else(|| round(self.segs[i].1)),
        }
    }

    /// The start point of segment `i` on the grid.
    fn start_of(&self, i: usize) -> Point {
        match self.prev(i) {
            Some(p) => self.end(p),
            None => self.start.map_or(Point::ZERO, round),
        }
    }

    /// Whether quadratic `i` is degenerate on the grid: its control point on an end, or on
    /// the next control point across an implied end.
    fn degenerate(&self, i: usize) -> bool {
        let Some(a) = self.control(i) else {
            return false;
        };
        let across = self.implied[i] && self.next(i).is_some_and(|j| self.rc[j] == Some(a));
        a == self.start_of(i) || a == self.end(i) || across
    }

    /// A quadratic whose control point lands on one of its ends becomes a line, and a line's
    /// ends are not implied; repeated until nothing changes (each pass turns one more
    /// quadratic into a line at least).
    fn make_lines(&mut self) {
        loop {
            let mut changed = false;
            for i in 0..self.n() {
                if self.control(i).is_some() && self.degenerate(i) {
                    self.line[i] = true;
                    self.implied[i] = false;
                    if let Some(p) = self.prev(i) {
                        self.implied[p] = false;
                    }
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
    }

    /// The smooth-node pass of [`quantize`]: first every smooth node that rounding left
    /// smooth (such as an extremum with its handles on the axis) holds its control points
    /// (to their line through it: an axis, or fixed), then the others are aligned in turn,
    /// each holding its control points for the next.
    fn align_smooth_nodes(&mut self) {
        let n = self.n();
        let mut hold = vec![Hold::Free; n];
        let mut todo = Vec::new();
        for i in 0..n {
            let Some(j) = self.next(i) else {
                continue;
            };
            if self.implied[i] || !self.smooth_before_rounding(i, j) {
                continue;
            }
            if turn(self.incoming(i), self.end(i), self.outgoing(j)) == 0.0 {
                self.hold_controls(&mut hold, i, j);
            } else {
                todo.push((i, j));
            }
        }
        for (i, j) in todo {
            self.align(&hold, i, j);
            self.hold_controls(&mut hold, i, j);
        }
    }

    /// The controls of the node between segments `i` and `j`, held to their line through it.
    fn hold_controls(&self, hold: &mut [Hold], i: usize, j: usize) {
        let node = self.end(i);
        for k in [i, j] {
            if let Some(c) = self.control(k) {
                hold[k] = hold[k].and(c - node);
            }
        }
    }

    /// Aligns the stored smooth node between segments `i` and `j`: its control points moved
    /// as `hold` allows, and the node itself by up to a unit per coordinate where one of its
    /// segments is a quadratic and that is needed to turn by less than [`SMOOTH_NODE`]
    /// (a move kept only if it does; across the node's tangent it stays within the `√2 / 2`
    /// of rounding), to the positions nearest the unrounded ones (the node's move across its
    /// tangent weighing 17 times) among those that turn the least (all turns below
    /// [`SMOOTH_TURN`] counting as one), if that is [`SMOOTH_TURN`] less than rounding
    /// alone. No move turns the stored smooth nodes at the segments' far ends more (corners
    /// by at most [`CORNER_SLACK`] more), or makes a curve segment shorter than
    /// [`SHORT_CHORD`] that was not before rounding.
    fn align(&mut self, hold: &[Hold], i: usize, j: usize) {
        let moves = |k: usize, g: &Self| match g.control(k) {
            Some(_) => hold[k].moves(),
            None => vec![Vec2::ZERO],
        };
        let (ma, mb) = (moves(i, self), moves(j, self));
        let node_moves = if self.control(i).is_some() || self.control(j).is_some() {
            Hold::Free.moves()
        } else {
            Vec::new()
        };
        let before = turn(self.incoming(i), self.end(i), self.outgoing(j));
        let (a0, b0, n0) = (self.rc[i], self.rc[j], self.end(i));
        // The stored nodes at the far ends of the two segments turn no more than before if
        // they were smooth, and by at most `CORNER_SLACK` more if they are corners.
        let (far_in, far_out) = (self.prev(i).filter(|&p| !self.implied[p]), self.next(j));
        let far_out = far_out.filter(|_| !self.implied[j]);
        let slack = |a: Option<usize>, b: Option<usize>| match (a, b) {
            (Some(a), Some(b)) if !self.smooth_before_rounding(a, b) => CORNER_SLACK,
            _ => 1e-12,
        };
        let slack = (slack(far_in, Some(i)), slack(Some(j), far_out));
        let far = |g: &Self| {
            let at = |a: usize, b: usize| turn(g.incoming(a), g.end(a), g.outgoing(b));
            (far_in.map(|p| at(p, i)), far_out.map(|q| at(j, q)))
        };
        let far0 = far(self);
        let worse = |now: (Option<f64>, Option<f64>)| {
            let w = |x: Option<f64>, y: Option<f64>, slack: f64| match (x, y) {
                (Some(x), Some(y)) => x > y + slack,
                _ => false,
            };
            w(now.0, far0.0, slack.0) || w(now.1, far0.1, slack.1)
        };
        // The unit normal of the node's tangent before rounding.
        let normal = {
            let from = self.segs[i].0.or(self.start_unrounded(i));
            let u = self.segs[i].1 - from.unwrap_or_default();
            Vec2::new(-u.y, u.x) / u.hypot()
        };
        let cost = |g: &Self| {
            let d = |k: usize| match (g.rc[k], g.segs[k].0) {
                (Some(p), Some(q)) => (p - q).hypot2(),
                _ => 0.0,
            };
            let m = g.end(i) - g.segs[i].1;
            d(i) + d(j) + m.hypot2() + 16.0 * m.dot(normal).powi(2)
        };
        let mut best: Option<Candidate> = None;
        // The node moves only where its control points alone leave a visible turn, and
        // only to a join that looks smooth.
        let visible = SMOOTH_NODE - SMOOTH_TURN;
        for (phase, dn) in core::iter::once(Vec2::ZERO)
            .chain(node_moves.into_iter().filter(|d| *d != Vec2::ZERO))
            .enumerate()
        {
            if phase == 1 && best.is_some_and(|c| c.excess <= visible) {
                break;
            }
            let kept = best;
            // (Across the tangent, the node moves no more than rounding may move it.)
            let across = ((n0 + dn) - self.segs[i].1).dot(normal).abs();
            if across > core::f64::consts::FRAC_1_SQRT_2 {
                continue;
            }
            self.moved[i] = Some(n0 + dn);
            for da in &ma {
                self.rc[i] = a0.map(|p| p + *da);
                for db in &mb {
                    self.rc[j] = b0.map(|p| p + *db);
                    if self.around_degenerate(i, j) || worse(far(self)) {
                        continue;
                    }
                    let t = turn(self.incoming(i), self.end(i), self.outgoing(j));
                    // (Turns below `SMOOTH_TURN` look smooth: they compare by cost.)
                    let key = ((t - SMOOTH_TURN).max(0.0), cost(self));
                    if best.map_or(true, |c: Candidate| key < (c.excess, c.cost)) {
                        best = Some(Candidate {
                            excess: key.0,
                            cost: key.1,
                            a: self.rc[i],
                            b: self.rc[j],
                            node: n0 + dn,
                        });
                    }
                }
            }
            if phase > 0 && best.is_some_and(|c| c.excess > visible) {
                best = kept;
            }
        }
        match best {
            Some(c) if c.excess + SMOOTH_TURN < before => {
                self.rc[i] = c.a;
                self.rc[j] = c.b;
                self.moved[i] = Some(c.node);
            }
            _ => {
                self.rc[i] = a0;
                self.rc[j] = b0;
                self.moved[i] = Some(n0);
            }
        }
    }

    /// Whether the node between segments `i` and `j` is stored and smooth before rounding.
    fn smooth_before_rounding(&self, i: usize, j: usize) -> bool {
        let node = self.segs[i].1;
        let Some(from) = self.start_unrounded(i) else {
            return false;
        };
        let u = node - self.segs[i].0.unwrap_or(from);
        let v = self.segs[j].0.unwrap_or(self.segs[j].1) - node;
        let (lu, lv) = (u.hypot(), v.hypot());
        lu > 0.0 && lv > 0.0 && u.dot(v) > 0.0 && u.cross(v).abs() <= SMOOTH_SINE * lu * lv
    }

    /// The point a node at the end of segment `i` is reached from on the grid.
    fn incoming(&self, i: usize) -> Point {
        self.control(i).unwrap_or_else(|| self.start_of(i))
    }

    /// The point a node at the start of segment `j` leaves towards on the grid.
    fn outgoing(&self, j: usize) -> Point {
        self.control(j).unwrap_or_else(|| self.end(j))
    }

    /// Whether moving the control points of segments `i` and `j` made one of the
    /// quadratics next to them degenerate.
    fn around_degenerate(&self, i: usize, j: usize) -> bool {
        let mut near = vec![i, j];
        near.extend(self.prev(i));
        near.extend(self.next(j));
        near.iter().any(|&k| {
            let short = self.control(k).is_some()
                && (self.end(k) - self.start_of(k)).hypot() < SHORT_CHORD
                && (self.segs[k].1 - self.start_unrounded(k).unwrap_or_default()).hypot()
                    >= SHORT_CHORD;
            self.degenerate(k) || short
        })
    }

    /// The start point of segment `i` before rounding (`None` for the first segment of a
    /// contour that continues the previous one).
    fn start_unrounded(&self, i: usize) -> Option<Point> {
        match self.prev(i) {
            Some(p) => Some(self.segs[p].1),
            None => self.start,
        }
    }

    fn write(&self, out: &mut BezPath) {
        if self.start.is_some() {
            out.push(PathEl::MoveTo(self.start_of(0)));
        }
        for i in 0..self.n() {
            let p = self.end(i);
            out.push(match self.control(i) {
                Some(a) => PathEl::QuadTo(a, p),
                None => PathEl::LineTo(p),
            });
        }
        if self.closed {
            out.push(PathEl::ClosePath);
        }
    }
}

/// The angle, in radians, between `node - a` and `b - node` (π where one is zero).
fn turn(a: Point, node: Point, b: Point) -> f64 {
    super::nodes::turn_angle(node - a, b - node).unwrap_or(core::f64::consts::PI)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn implied_points_stay_midway() {
        // A quadratic spline of two pieces whose joint rounds off the midpoint.
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.quad_to((10.4, 20.4), (15.45, 20.2));
        p.quad_to((20.5, 20.0), (30.0, 0.0));
        p.close_path();
        let q = quantize(&p);
        let els = q.elements();
        let PathEl::QuadTo(a, m) = els[1] else {
            panic!("{els:?}")
        };
        let PathEl::QuadTo(b, _) = els[2] else {
            panic!("{els:?}")
        };
        assert_eq!((a, b), (Point::new(10.0, 20.0), Point::new(21.0, 20.0)));
        assert_eq!(m, a.midpoint(b));
        assert_eq!(m, Point::new(15.5, 20.0));
    }

    #[test]
    fn a_smooth_node_with_short_handles_stays_smooth() {
        // A smooth node at (46, 265) whose handles are 3.4 and 1.5 units long: rounded
        // alone, the join turns by 18.4°.
        let mut p = BezPath::new();
        p.move_to((0.0, 200.0));
        p.quad_to((49.2, 263.9), (46.0, 265.0));
        p.quad_to((44.6, 265.48125), (0.0, 300.0));
        p.close_path();
        let before = turn(
            Point::new(49.0, 264.0),
            Point::new(46.0, 265.0),
            Point::new(45.0, 265.0),
        );
        assert!(before.to_degrees() > 18.0);
        let q = quantize(&p);
        let els = q.elements();
        let (PathEl::QuadTo(a, m), PathEl::QuadTo(b, _)) = (els[1], els[2]) else {
            panic!("{els:?}")
        };
        assert_eq!(m, Point::new(46.0, 265.0));
        assert_eq!((m - a).cross(b - m), 0.0, "{a:?} {b:?}");
        assert!((m - a).dot(b - m) > 0.0);
        // Within one unit of the rounded control points.
        assert!((a - Point::new(49.0, 264.0)).hypot() <= 2f64.sqrt());
        assert!((b - Point::new(45.0, 265.0)).hypot() <= 2f64.sqrt());
    }

    #[test]
    fn a_smooth_join_of_a_line_and_a_curve_stays_smooth() {
        // A line from a corner at the origin into a smooth join with a quadratic whose
        // handle is 3.5 units long, along the line: rounded alone, the join turns by 8.1°.
        let node = Point::new(30.45, 10.45);
        let d = node.to_vec2().normalize();
        let handle = node + d * 3.5;
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.line_to(node);
        p.quad_to(handle, Point::new(60.0, 0.0));
        p.close_path();
        let rounded = turn(Point::ZERO, round(node), round(handle));
        assert!(rounded.to_degrees() > 0.5, "{}", rounded.to_degrees());
        let q = quantize(&p);
        let els = q.elements();
        let (PathEl::LineTo(m), PathEl::QuadTo(b, _)) = (els[1], els[2]) else {
            panic!("{els:?}")
        };
        let after = turn(Point::ZERO, m, b);
        assert!(after.to_degrees() < 0.5, "{}", after.to_degrees());
        // The node stays within rounding of its place across the line.
        let normal = Vec2::new(-d.y, d.x);
        assert!((m - node).dot(normal).abs() <= core::f64::consts::FRAC_1_SQRT_2);
        assert!((m - round(node)).hypot() <= 2f64.sqrt());
        assert!((b - round(handle)).hypot() <= 2f64.sqrt());
    }

    #[test]
    fn a_quadratic_onto_its_end_becomes_a_line() {
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.quad_to((0.3, 0.2), (10.0, 0.0));
        p.line_to((10.0, 10.0));
        p.close_path();
        let q = quantize(&p);
        assert!(matches!(q.elements()[1], PathEl::LineTo(_)), "{q:?}");
    }
}
