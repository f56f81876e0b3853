//! Coordinates: user point types as coordinate arrays ([`Coords`]), and the normalized
//! frame the solver works in.

use kurbo::Point;

use crate::Point3;

/// Affine map from user coordinates to the normalized frame (drawing size 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Frame<const D: usize> {
    pub(super) center: [f64; D],
    pub(super) size: f64,
}

impl<const D: usize> Frame<D> {
    pub(super) fn new(points: &[[f64; D]]) -> Frame<D> {
        let mut lo = [f64::INFINITY; D];
        let mut hi = [f64::NEG_INFINITY; D];
        for p in points {
            for k in 0..D {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let size = (0..D).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        Frame {
            // Halves first: (lo + hi) / 2 can overflow where lo/2 + hi/2 does not.
            center: core::array::from_fn(|k| 0.5 * lo[k] + 0.5 * hi[k]),
            size: if size > 0.0 { size } else { 1.0 },
        }
    }

    pub(super) fn to_local(self, p: [f64; D]) -> [f64; D] {
        core::array::from_fn(|k| (p[k] - self.center[k]) / self.size)
    }

    pub(super) fn to_user(self, p: [f64; D]) -> [f64; D] {
        core::array::from_fn(|k| p[k] * self.size + self.center[k])
    }
}

/// Conversion between user point types and coordinate arrays.
pub trait Coords<const D: usize>: Copy {
    /// The coordinates.
    fn coords(self) -> [f64; D];
    /// The point with these coordinates.
    fn from_coords(c: [f64; D]) -> Self;
}

impl Coords<2> for Point {
    fn coords(self) -> [f64; 2] {
        [self.x, self.y]
    }
    fn from_coords(c: [f64; 2]) -> Self {
        Point::new(c[0], c[1])
    }
}

impl Coords<3> for Point3 {
    fn coords(self) -> [f64; 3] {
        [self.x, self.y, self.z]
    }
    fn from_coords(c: [f64; 3]) -> Self {
        Point3::new(c[0], c[1], c[2])
    }
}
