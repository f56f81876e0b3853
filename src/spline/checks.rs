//! Checks of a solve's input: repeated and collinear points, points in order along a
//! line, and the shape parameters.

use super::{Scheme, Shape};
use crate::Error;

/// The relative size below which two consecutive points count as repeated, and below which
/// the spread of a closed curve's points off their best line counts as collinear.
pub(super) const COINCIDENT: f64 = 1e-12;

/// Two consecutive points closer than this many `f64::EPSILON`s times their largest
/// coordinate magnitude (4 to 8 units in the last place) also count as repeated: their
/// difference is rounding noise of their own coordinates (a pair one ulp apart has one of
/// eight directions), so no curve through them means anything, and a drawing a few hundred
/// ulps wide cannot hold its own control points (found by fuzzing: peaks at such pairs
/// moved by up to 100 % of |κ| when the same solution was written in user coordinates).
/// Scale-invariant: it depends on where the points are, not on the units.
pub(super) const ULP_COINCIDENT: f64 = 4.0;

/// The input points that get a segment: all of a closed curve, the interior ones of an open
/// curve (`m ≥ 2`).
pub(super) fn block_range(closed: bool, m: usize) -> core::ops::Range<usize> {
    if closed {
        0..m
    } else {
        1..m - 1
    }
}

/// Whether points on one line come in strictly monotone order along it.
pub(super) fn monotone_along_line<const D: usize>(p: &[[f64; D]]) -> bool {
    // Along the line from the first point to the farthest one: the last point may coincide
    // with the first (a loop that doubles back), and then gives no direction.
    let d2 = |q: &[f64; D]| (0..D).map(|k| (q[k] - p[0][k]).powi(2)).sum::<f64>();
    let far = p
        .iter()
        .fold(p[0], |best, q| if d2(q) > d2(&best) { *q } else { best });
    let dir: [f64; D] = core::array::from_fn(|k| far[k] - p[0][k]);
    let along = |q: &[f64; D]| (0..D).map(|k| (q[k] - p[0][k]) * dir[k]).sum::<f64>();
    p.windows(2).all(|w| along(&w[1]) > along(&w[0]))
}

/// Whether two points coincide to within the rounding of their own coordinates:
/// `|a − b| ≤ ULP_COINCIDENT · ε · max |coordinate|` (see [`ULP_COINCIDENT`]).
pub(super) fn within_rounding<const D: usize>(a: [f64; D], b: [f64; D]) -> bool {
    let mag = a.iter().chain(&b).fold(0.0f64, |m, v| m.max(v.abs()));
    if mag == 0.0 {
        return true;
    }
    // In units of the magnitude (squares of tiny differences underflow), halves first (the
    // difference of finite points can overflow).
    let d = (0..D)
        .map(|k| ((0.5 * a[k] - 0.5 * b[k]) / mag).powi(2))
        .sum::<f64>()
        .sqrt();
    d <= 0.5 * ULP_COINCIDENT * f64::EPSILON
}

/// Whether all points lie on one line (relative to the drawing size 1).
pub(super) fn collinear<const D: usize>(p: &[[f64; D]]) -> bool {
    // Farthest point from p0, then the largest distance from the line through both.
    let far = p
        .iter()
        .map(|q| (0..D).map(|k| (q[k] - p[0][k]).powi(2)).sum::<f64>())
        .enumerate()
        .fold(
            (0, 0.0),
            |best, (i, d)| if d > best.1 { (i, d) } else { best },
        );
    let dir: [f64; D] = core::array::from_fn(|k| p[far.0][k] - p[0][k]);
    let len2 = far.1;
    if len2 <= 0.0 {
        return true;
    }
    p.iter().all(|q| {
        let v: [f64; D] = core::array::from_fn(|k| q[k] - p[0][k]);
        let along = (0..D).map(|k| v[k] * dir[k]).sum::<f64>() / len2;
        let off2 = (0..D).map(|k| (v[k] - along * dir[k]).powi(2)).sum::<f64>();
        off2.sqrt() <= COINCIDENT
    })
}

/// The shape parameter of point `i` of `shape` (validated by [`check_shapes`]).
pub(super) fn shape_at(scheme: Scheme, shape: &Shape, i: usize) -> f64 {
    match shape {
        Shape::Neutral => scheme.neutral_shape(),
        Shape::Global(a) => *a,
        Shape::PerPoint(v) => v[i],
    }
}

/// Validate the shape parameters of `m` points (read back by [`shape_at`], with no copy).
pub(super) fn check_shapes(scheme: Scheme, shape: &Shape, m: usize) -> Result<(), Error> {
    let (min, max) = scheme.shape_range();
    // A uniform shape is checked once (as the first point's).
    let count = match shape {
        Shape::PerPoint(v) if v.len() != m => {
            return Err(Error::ShapeCount {
                expected: m,
                got: v.len(),
            })
        }
        Shape::PerPoint(_) => m,
        Shape::Neutral | Shape::Global(_) => m.min(1),
    };
    for index in 0..count {
        let value = shape_at(scheme, shape, index);
        if scheme == Scheme::Kappa && value != min {
            return Err(Error::InvalidOption(
                "the kappa scheme has no shape parameter (use ek-cubic)",
            ));
        }
        if scheme != Scheme::Kappa && !(value >= min && value < max) {
            return Err(Error::ShapeOutOfRange {
                index,
                value,
                min,
                max,
            });
        }
    }
    Ok(())
}
