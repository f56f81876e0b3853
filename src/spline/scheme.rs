//! The curve families ([`Scheme`]) and their shape parameters ([`Shape`]).

use crate::basis::{Basis, CubicEk, TrigEk};

/// The family of segments a curve is built from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
pub enum Scheme {
    /// κ-curves (Yan et al. 2017): quadratic Bézier segments, curvature peaks at the points.
    #[default]
    Kappa,
    /// εκ-curves with the constrained cubic Bernstein segment (seed 000 §3): a shape
    /// parameter `a ∈ [2/3, 1)` per point; larger `a` gives a sharper curvature peak.
    EkCubic,
    /// εκ-curves with the constrained quadratic trigonometric segment (seed 000 §4): a
    /// shape parameter `a ∈ [1/2, 1)` per point, rounder than [`Scheme::EkCubic`] at the
    /// same `a`. Not polynomial: [`Spline::to_bezpath`](super::Spline::to_bezpath) fits
    /// cubics to it.
    ///
    /// For `a` below about 0.61 and gentle turns the stationary point placed at an input
    /// point is a curvature *minimum* (see
    /// [`Segment::extremum`](super::Segment::extremum)); the default shape
    /// ([`Scheme::neutral_shape`]) is [`EK_TRIG_DEFAULT_SHAPE`], which keeps maxima.
    EkTrig,
}

/// The default shape parameter of [`Scheme::EkTrig`]. A symmetric segment's stationary
/// point is a curvature minimum below `a ≈ 0.6104` (for a gentle 1° turn; less for sharper
/// turns), and asymmetric segments need more: on the built-in drawings, 9 of their points
/// sit at minima with `a = 0.65` and none with `a = 0.7`.
pub const EK_TRIG_DEFAULT_SHAPE: f64 = 0.7;

impl Scheme {
    /// The shape parameter of [`Shape::Neutral`]: `2/3` for κ and εκ-cubic (the εκ cubic is
    /// then the κ quadratic), [`EK_TRIG_DEFAULT_SHAPE`] for εκ-trig.
    pub const fn neutral_shape(self) -> f64 {
        match self {
            Scheme::Kappa | Scheme::EkCubic => 2.0 / 3.0,
            Scheme::EkTrig => EK_TRIG_DEFAULT_SHAPE,
        }
    }

    /// The admissible shape range `[min, max)`.
    pub const fn shape_range(self) -> (f64, f64) {
        match self {
            Scheme::Kappa => (2.0 / 3.0, 2.0 / 3.0),
            Scheme::EkCubic => (2.0 / 3.0, 1.0),
            Scheme::EkTrig => (0.5, 1.0),
        }
    }

    /// The degree of the output segments: 2 for κ (quadratic Bézier) and εκ-trig
    /// (quadratic trigonometric), 3 for εκ-cubic.
    pub const fn degree(self) -> usize {
        match self {
            Scheme::Kappa | Scheme::EkTrig => 2,
            Scheme::EkCubic => 3,
        }
    }

    /// Whether the segments are polynomial, so that
    /// [`Spline::to_bezpath`](super::Spline::to_bezpath) is exact.
    pub const fn is_polynomial(self) -> bool {
        !matches!(self, Scheme::EkTrig)
    }

    /// The solver's segment family for shape `a`.
    pub(super) fn basis(self, a: f64) -> Basis {
        match self {
            Scheme::Kappa | Scheme::EkCubic => Basis::Cubic(CubicEk::new(a)),
            Scheme::EkTrig => Basis::Trig(TrigEk::new(a)),
        }
    }
}

/// Shape parameters of εκ-curves.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Shape {
    /// The scheme's neutral value ([`Scheme::neutral_shape`]).
    #[default]
    Neutral,
    /// One value for every point.
    Global(f64),
    /// One value per input point (for open curves the first and last are ignored).
    PerPoint(Vec<f64>),
}

impl From<f64> for Shape {
    fn from(a: f64) -> Shape {
        Shape::Global(a)
    }
}
