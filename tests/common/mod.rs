//! Helpers shared by the integration tests.
#![allow(dead_code)]

use kappa::{builtin_design, Design};
use kurbo::{ParamCurve, ParamCurveDeriv, PathSeg, Point};

mod walks;
// (Re-exported for the tests that use them; not every test does.)
#[allow(unused_imports)]
pub use walks::{grid_walks, pixel_samples, Lcg};

/// Every curve with at least three points of the nine drawings of the εκ paper:
/// `(drawing, index, points, closed)`.
pub fn paper_curves() -> Vec<(String, usize, Vec<Point>, bool, f64)> {
    let mut out = Vec::new();
    for name in [
        "bear", "bird", "deer", "dinosaur", "elephant", "plane", "pumpkin", "rabbit", "rose",
    ] {
        let d = Design::from_json(builtin_design(name).unwrap()).unwrap();
        let size = d.size();
        for (i, c) in d.curves.iter().enumerate() {
            if c.points.len() >= 3 {
                out.push((name.to_string(), i, c.kurbo_points(), c.is_closed(), size));
            }
        }
    }
    out
}

/// First and second derivative of a segment at `t`.
pub fn derivs(seg: &PathSeg, t: f64) -> (kurbo::Vec2, kurbo::Vec2) {
    match seg {
        PathSeg::Line(l) => (l.deriv().eval(t).to_vec2(), kurbo::Vec2::ZERO),
        PathSeg::Quad(q) => (
            q.deriv().eval(t).to_vec2(),
            q.deriv().deriv().eval(t).to_vec2(),
        ),
        PathSeg::Cubic(c) => (
            c.deriv().eval(t).to_vec2(),
            c.deriv().deriv().eval(t).to_vec2(),
        ),
    }
}

/// Signed curvature, positive for left turns (x′y″ − y′x″)/|r′|³.
pub fn curvature(seg: &PathSeg, t: f64) -> f64 {
    let (d1, d2) = derivs(seg, t);
    d1.cross(d2) / d1.hypot().powi(3)
}

/// A first-order bound on how far κ = (r′ × r″)/|r′|³ moves when `r′` moves by at most `e1`
/// and `r″` by at most `e2`: `(e1|r″| + e2|r′|)/|r′|³ + 3|κ|e1/|r′|`.
pub fn kappa_perturbation(d1: kurbo::Vec2, d2: kurbo::Vec2, e1: f64, e2: f64) -> f64 {
    let s1 = d1.hypot();
    let k = d1.cross(d2) / s1.powi(3);
    (e1 * d2.hypot() + e2 * s1) / s1.powi(3) + 3.0 * k.abs() * e1 / s1
}

/// A few units in the last place of the largest coordinate of `points`: how far two
/// roundings of one control point (the solver's and a curve form's) can differ.
pub fn coordinate_rounding(points: &[Point]) -> f64 {
    let coord = points
        .iter()
        .fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
    4.0 * f64::EPSILON * coord
}

/// A bound on how far |κ(t)| of `seg` moves when each control point moves by
/// [`coordinate_rounding`]: for a cubic `|δr′| ≤ 6e` and `|δr″| ≤ 24e` (less for lower
/// degrees). It matters only for segments far smaller than their distance from the origin
/// (a collapsed segment of εκ).
pub fn curvature_rounding(seg: &PathSeg, t: f64) -> f64 {
    let pts: Vec<Point> = match seg {
        PathSeg::Line(l) => vec![l.p0, l.p1],
        PathSeg::Quad(q) => vec![q.p0, q.p1, q.p2],
        PathSeg::Cubic(c) => vec![c.p0, c.p1, c.p2, c.p3],
    };
    let e = coordinate_rounding(&pts);
    let (d1, d2) = derivs(seg, t);
    kappa_perturbation(d1, d2, 6.0 * e, 24.0 * e)
}

/// Unit tangent.
pub fn tangent(seg: &PathSeg, t: f64) -> kurbo::Vec2 {
    let (d1, _) = derivs(seg, t);
    d1 / d1.hypot()
}

/// The parameter of the largest |κ| on a dense grid refined by golden-section search.
pub fn sampled_peak(seg: &PathSeg) -> (f64, f64) {
    let n = 2000;
    let (mut best_t, mut best) = (0.0, -1.0);
    for i in 0..=n {
        let t = i as f64 / n as f64;
        let k = curvature(seg, t).abs();
        if k > best {
            best = k;
            best_t = t;
        }
    }
    let (mut lo, mut hi) = (
        (best_t - 1.0 / n as f64).max(0.0),
        (best_t + 1.0 / n as f64).min(1.0),
    );
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..80 {
        let a = hi - g * (hi - lo);
        let b = lo + g * (hi - lo);
        if curvature(seg, a).abs() > curvature(seg, b).abs() {
            hi = b;
        } else {
            lo = a;
        }
    }
    let t = 0.5 * (lo + hi);
    (t, curvature(seg, t).abs())
}

/// Distance between two points.
pub fn dist(a: Point, b: Point) -> f64 {
    (a - b).hypot()
}

/// A segment's start point.
pub fn start(seg: &PathSeg) -> Point {
    seg.eval(0.0)
}

impl Lcg {
    /// A random star polygon of `n` points (see [`star_polygon`]): for each point a jitter
    /// and a radius in [0.35, 1], drawn in that order, at scale 100.
    pub fn star(&mut self, n: usize) -> Vec<Point> {
        let raw: Vec<(f64, f64)> = (0..n)
            .map(|_| (self.next(), 0.35 + 0.65 * self.next()))
            .collect();
        star_polygon(&raw, 100.0, 0.0)
    }
}

/// A star-shaped polygon from `(jitter, radius)` pairs: the pairs sorted by jitter, point `i`
/// at angle `(i + 0.6 jitter) / n` of a turn and that radius times `scale`, shifted by
/// `(shift, -shift)`.
pub fn star_polygon(raw: &[(f64, f64)], scale: f64, shift: f64) -> Vec<Point> {
    let mut v = raw.to_vec();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    let n = v.len();
    v.iter()
        .enumerate()
        .map(|(i, &(jitter, r))| {
            let th = (i as f64 + 0.6 * jitter) / n as f64 * std::f64::consts::TAU;
            Point::new(shift + scale * r * th.cos(), -shift + scale * r * th.sin())
        })
        .collect()
}

/// The maximizer of `f` on `[lo, hi]` by golden-section search (100 steps).
pub fn golden_max(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> f64 {
    let (mut a, mut b) = (lo, hi);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..100 {
        let (x1, x2) = (b - g * (b - a), a + g * (b - a));
        if f(x1) > f(x2) {
            b = x2;
        } else {
            a = x1;
        }
    }
    0.5 * (a + b)
}

/// Runs the built `kappa` binary with `args`, feeding `stdin`.
#[cfg(feature = "cli")]
pub fn run_kappa(args: &[&str], stdin: &str) -> std::process::Output {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_kappa"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the kappa binary runs");
    // The tool may exit before reading stdin (argument errors); ignore a broken pipe.
    let _ = child.stdin.take().unwrap().write_all(stdin.as_bytes());
    child.wait_with_output().unwrap()
}

/// The joints of a curve as `(j, k)`: segment `j` ends where segment `k` starts, stepping
/// over segments collapsed onto their input point (an inflection through the point: the
/// segments on either side meet there, tangent, with equal |κ|).
pub fn joints_across_collapsed(
    segs: &[kappa::Segment<Point>],
    closed: bool,
) -> Vec<(usize, usize)> {
    let n = segs.len();
    let live: Vec<usize> = (0..n).filter(|&j| !segs[j].is_collapsed()).collect();
    let mut out: Vec<(usize, usize)> = live.windows(2).map(|w| (w[0], w[1])).collect();
    if closed && live.len() >= 2 {
        out.push((live[live.len() - 1], live[0]));
    }
    out
}

/// The size of a drawing: the larger side of its points' bounding box.
pub fn drawing_size(points: &[Point]) -> f64 {
    let r = points
        .iter()
        .fold(kurbo::Rect::from_points(points[0], points[0]), |r, &p| {
            r.union_pt(p)
        });
    r.width().max(r.height())
}
