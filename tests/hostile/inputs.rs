//! Structured inputs from raw bytes.

use arbitrary::Unstructured;
use kappa::{Point3, Scheme, Shape};
use kurbo::Point;

/// Values that break naive code: NaN, infinities, the largest finite numbers, subnormals,
/// signed zeros.
pub const SPECIALS: [f64; 9] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    1e308,
    -1e308,
    5e-324,
    f64::MIN_POSITIVE,
    0.0,
    -0.0,
];

/// Relative offsets of a near-duplicate point (0: an exact repeat).
pub const NEAR: [f64; 6] = [0.0, 1e-16, 1e-13, 1e-11, 1e-8, 1e-5];

/// A source of structured values; never fails (an exhausted source gives zeros).
pub struct Gen<'a> {
    u: Unstructured<'a>,
}

impl<'a> Gen<'a> {
    /// Values drawn from `data`.
    pub fn new(data: &'a [u8]) -> Gen<'a> {
        Gen {
            u: Unstructured::new(data),
        }
    }

    /// Whether the bytes are used up.
    pub fn is_empty(&self) -> bool {
        self.u.is_empty()
    }

    /// Up to `max` raw bytes.
    pub fn chunk(&mut self, max: usize) -> &'a [u8] {
        let n = self.below(max + 1).min(self.u.len());
        self.u.bytes(n).unwrap_or(&[])
    }

    /// A byte.
    pub fn byte(&mut self) -> u8 {
        self.u.arbitrary().unwrap_or(0)
    }

    /// An integer in `0..n` (0 when `n == 0`).
    pub fn below(&mut self, n: usize) -> usize {
        if n <= 1 {
            return 0;
        }
        self.u.int_in_range(0..=n - 1).unwrap_or(0)
    }

    /// A coin flip.
    pub fn flag(&mut self) -> bool {
        self.byte() & 1 == 1
    }

    /// One of `items`.
    pub fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[self.below(items.len())]
    }

    /// A number in `[-1, 1]`.
    pub fn unit(&mut self) -> f64 {
        let v: u32 = self.u.arbitrary().unwrap_or(0);
        v as f64 / u32::MAX as f64 * 2.0 - 1.0
    }

    /// A number in `[0, 1]`.
    pub fn fraction(&mut self) -> f64 {
        0.5 * (self.unit() + 1.0)
    }

    /// A power of ten from 1e-9 to 1e9.
    pub fn scale(&mut self) -> f64 {
        10f64.powi(self.below(19) as i32 - 9)
    }

    /// A signed number of any scale from 1e-9 to 1e9, and rarely a special value.
    pub fn number(&mut self) -> f64 {
        if self.below(16) == 0 {
            self.pick(&SPECIALS)
        } else {
            self.unit() * self.scale()
        }
    }

    /// A shape parameter: mostly in or near `scheme`'s range, sometimes anything.
    pub fn shape_value(&mut self, scheme: Scheme) -> f64 {
        let (min, max) = scheme.shape_range();
        match self.below(8) {
            0 => self.number(),
            1 => min,
            2 => max,
            3 => max - self.pick(&[1e-15, 1e-9, 1e-4]),
            _ => min + (max.max(min + 0.3) - min) * self.fraction() * 0.999,
        }
    }

    /// A scheme.
    pub fn scheme(&mut self) -> Scheme {
        self.pick(&[Scheme::Kappa, Scheme::EkCubic, Scheme::EkTrig])
    }

    /// Shapes for `n` points of `scheme`: neutral, one global value, or one per point (now and
    /// then of the wrong length).
    pub fn shape(&mut self, scheme: Scheme, n: usize) -> Shape {
        match self.below(4) {
            0 => Shape::Neutral,
            1 => Shape::Global(self.shape_value(scheme)),
            _ => {
                let len = if self.below(16) == 0 {
                    self.below(n + 3)
                } else {
                    n
                };
                Shape::PerPoint((0..len).map(|_| self.shape_value(scheme)).collect())
            }
        }
    }

    /// Up to `max` points in `D` dimensions (see the module docs for the mixture).
    pub fn coords<const D: usize>(&mut self, max: usize) -> Vec<[f64; D]> {
        let n = self.below(max + 1);
        let scale = self.scale();
        let offset: [f64; D] = if self.flag() {
            core::array::from_fn(|_| 0.0)
        } else {
            let s = self.scale();
            core::array::from_fn(|_| self.unit() * s)
        };
        let special = self.below(8) == 0;
        let mut pts: Vec<[f64; D]> = Vec::with_capacity(n);
        for i in 0..n {
            let random = |g: &mut Gen| -> [f64; D] {
                core::array::from_fn(|k| offset[k] + scale * g.unit())
            };
            let p = match self.below(10) {
                // Near-duplicate of the previous point.
                3 if i > 0 => {
                    let eps = self.pick(&NEAR) * scale;
                    let prev = pts[i - 1];
                    core::array::from_fn(|k| prev[k] + eps * self.unit())
                }
                // Collinear continuation of the last two points.
                4 if i > 1 => {
                    let (a, b) = (pts[i - 2], pts[i - 1]);
                    let t = self.pick(&[1.0, 0.5, 2.0, -1.0]);
                    let eps = self.pick(&NEAR) * scale;
                    core::array::from_fn(|k| b[k] + t * (b[k] - a[k]) + eps * self.unit())
                }
                // On a circle (and, in 3D, a helix).
                5 => {
                    let th = self.byte() as f64 / 256.0 * core::f64::consts::TAU;
                    core::array::from_fn(|k| {
                        offset[k]
                            + scale
                                * match k {
                                    0 => th.cos(),
                                    1 => th.sin(),
                                    _ => 0.1 * th,
                                }
                    })
                }
                // A copy of any earlier point (self-intersections, loops).
                6 if i > 0 => pts[self.below(i)],
                // A special value in one coordinate.
                7 if special => {
                    let mut p = random(self);
                    p[self.below(D)] = self.pick(&SPECIALS);
                    p
                }
                _ => random(self),
            };
            pts.push(p);
        }
        pts
    }

    /// Up to `max` 2D points.
    pub fn points(&mut self, max: usize) -> Vec<Point> {
        self.coords::<2>(max)
            .into_iter()
            .map(|[x, y]| Point::new(x, y))
            .collect()
    }

    /// Up to `max` 3D points.
    pub fn points3(&mut self, max: usize) -> Vec<Point3> {
        self.coords::<3>(max)
            .into_iter()
            .map(|[x, y, z]| Point3::new(x, y, z))
            .collect()
    }

    /// An angle: mostly in `(-2π, 2π)`, sometimes large or special.
    pub fn angle(&mut self) -> f64 {
        match self.below(8) {
            0 => self.number(),
            1 => self.pick(&[0.0, core::f64::consts::PI, -core::f64::consts::PI]),
            _ => self.unit() * core::f64::consts::TAU,
        }
    }
}
