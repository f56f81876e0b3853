//! Uniform cubic B-splines through given points, open (relaxed) and closed (periodic), in 2D
//! and 3D, with their exact maximum curvature (seed paper 002). The mathematics, the
//! measurements behind the choices and the input rules are documented on [`BSpline`].

use core::ops::Range;

use kurbo::{
    BezPath, CubicBez, ParamCurveArclen, ParamCurveArea, ParamCurveExtrema, PathEl, Point, Rect,
    Shape,
};

#[cfg(feature = "render")]
mod picture;

use crate::analysis::{CurvatureAnalysis, SpaceBez};
use crate::linalg::{solve_symmetric_toeplitz_into, Lin};
use crate::{Coords, Error, Point3};

/// Two consecutive points closer than this fraction of the drawing size (the larger side of
/// their bounding box) are repeated.
const COINCIDENT: f64 = 1e-12;

/// The control points are kept in the normalized frame too when a coordinate of the centre of
/// the points' bounding box exceeds this many drawing sizes: mapping them to user coordinates
/// and back then loses more than about `(2 · 3/2 + FAR) ε` of the drawing size.
const FAR: f64 = 2.0;

/// The diagonal of the interpolation system `b_{k−1} + 4 b_k + b_{k+1} = 6 s_k`.
const DIAGONAL: f64 = 4.0;

/// The control points lie within this many drawing sizes of the centre of the points'
/// bounding box (3/2, see `interpolate`, plus a margin for rounding).
const CONTROL_REACH: f64 = 1.5 + 1e-9;

/// A uniform cubic B-spline through given points: relaxed (open, zero end curvature) or
/// periodic (closed, C2 everywhere).
///
/// `P` is [`kurbo::Point`] (2D, the default) or [`Point3`] ([`BSpline3`]).
///
/// # Interpolation
///
/// Given points `s_0 … s_n`, the control points `b_0 … b_n` of the uniform cubic B-spline
/// through them solve (seed 002 §2)
///
/// ```text
/// b_{k−1} + 4 b_k + b_{k+1} = 6 s_k
/// ```
///
/// - **relaxed** (open) for `k = 1 … n−1` with `b_0 = s_0`, `b_n = s_n` (Theorem 2.1): the
///   curvature is zero at both ends;
/// - **periodic** (closed) for `k = 0 … n` with indices mod `n + 1` (seed 002 eqs. 8–9,
///   Theorem 2.2): C2 everywhere, `n + 1` segments.
///
/// Segment `k` is the cubic Bézier `s_k, (2b_k + b_{k+1})/3, (b_k + 2b_{k+1})/3, s_{k+1}` on
/// the global parameter interval `[k, k+1]` (seed 002 eqs. 4–5 and 11, with 0-based indices),
/// so the whole curve is parameterized by `t ∈ [0, n]` (open) or `t ∈ [0, n + 1]` (closed)
/// and passes through `s_k` at `t = k`.
///
/// The systems are solved in `O(n)` in a normalized frame (the points' bounding box centred at
/// the origin, largest side 1), so coordinates near the limits of `f64` do not overflow:
/// Thomas' algorithm for the open case and the factorization
/// `(1/α)(I + αS)(I + αS⁻¹)`, `α = 2 − √3`, of the circulant for the closed one. The
/// paper's closed forms, with `β_ℓ = ((2+√3)^{ℓ+1} − (2−√3)^{ℓ+1})/(2√3)`, cost `O(n²)` and
/// are kept only as a test oracle. Measured in `tests/bspline.rs`: while they work they agree
/// with the solver to about 2e-15 of the points' magnitude, but `(2+√3)^{ℓ+1}` overflows `f64`
/// at `ℓ = 538`. With coordinates of size 1 the periodic form is not finite from 539 points
/// on, and the relaxed one is silently wrong at 540 points (a term `β_ℓ/β_{n−1}` becomes 0)
/// and not finite from 541; larger coordinates overflow the sums `Σ β_ℓ s_j` a few points
/// earlier (536 points for coordinates of size 600).
///
/// # Maximum curvature
///
/// [`BSpline::max_curvature`] is the paper's Algorithm 1 for both dimensions, through
/// [`analysis`](crate::analysis): on every segment the real roots of the stationarity
/// polynomial of the curvature (2D: `a·u = 0` and `(v·v)(a′·u) − 3(a·u)(v·a) = 0`, seed 002
/// eqs. 15–16; 3D: seed 002 eq. 13, degree ≤ 7) plus both segment ends are the candidates;
/// the maximum of |κ| is returned with **every** global parameter where it is attained, ties
/// counted within a relative [`BSplineCurvatureMax::TIE_TOLERANCE`] (1e-12): symmetric data
/// has several equal maxima. The value is |κ| re-measured at the reported global parameter
/// (the one [`BSpline::curvature`] sees), so it is attained exactly where it is reported.
/// [`BSpline::curvature`] is Algorithm 2, the curvature at any global parameter.
///
/// **Cusps.** Where `r′ = 0` (to within [`STALL_TOLERANCE`](crate::analysis::STALL_TOLERANCE)
/// of the segment's hodograph) and |κ| grows without bound next to it, the maximum is
/// [`f64::INFINITY`], reported at the cusp parameters (where `curvature` returns 0 by
/// convention). Data force such cusps: a closed spline through `A, B, A, C` (a point
/// repeated two places apart) has `b₀ = b₂` exactly (subtract rows 0 and 2 of the system), so
/// `r′(1) = (b₂ − b₀)/2 = 0` and the curve turns back at `B`; a closed spline that is its own
/// reversal (`s_k = s_{−k}`) folds back at its two fixed points. In floating point `r′` is a
/// few units in the last place there rather than 0, which the stall tolerance absorbs. Near
/// (not exact) cusps have a finite, possibly huge maximum.
///
/// **Precision.** For points far from the origin relative to their extent (the centre of their
/// bounding box more than 2 extents away) the control points are also kept in the normalized
/// frame as solved there, and the curvature is computed from those: mapping the user control
/// points back would round them to the magnitude of the coordinates, which for points 1e-7
/// apart at 1e4, say, is most of their precision, and the two segments at a joint would then
/// disagree on |κ| there. Near the origin the round trip costs a few units in the last place
/// and the extra memory is not spent.
///
/// Running the root finder on every segment costs a few microseconds each, so segments are
/// first screened by cheap bounds (`curvature_bounds`): the curvature at the joints is a lower
/// bound of the maximum, and the Bernstein coefficients of `r′ × r″` over a lower bound of
/// `|r′|³` an upper bound per segment (refined on eight pieces where needed). Segments whose
/// upper bound is below the best value found cannot attain it and are skipped; the result is
/// the same as without screening.
///
/// # Input
///
/// Errors are typed ([`Error`]): too few points (an open spline needs 2, a closed one 3),
/// NaN or infinite coordinates, points whose extent overflows `f64`
/// ([`Error::ExtentOverflow`], also when the control points could: they stay within 1.5
/// extents of the centre of the points' bounding box), and **repeated
/// consecutive points** ([`Error::RepeatedPoint`], within 1e-12 of the drawing size, and the
/// last and first points of a closed spline): with a uniform parameterization a zero chord
/// does not give a corner but a small loop through the repeated point, which is never what
/// the repetition meant. Collinear points are accepted; a closed spline through them runs
/// back and forth along the line.
///
/// # Example
///
/// ```
/// use kappa::BSpline;
/// use kurbo::{ParamCurve, Point};
///
/// let points = [
///     Point::new(0.0, 0.0),
///     Point::new(1.0, 1.0),
///     Point::new(2.0, 0.0),
///     Point::new(3.0, 1.0),
/// ];
/// let open = BSpline::new(&points, false)?;
/// assert_eq!(open.segment_count(), 3);
/// assert_eq!(open.param_range(), 0.0..3.0);
/// assert!((open.eval(2.0) - points[2]).hypot() < 1e-15);
/// // Zero curvature at the ends of a relaxed spline.
/// assert!(open.curvature(0.0).abs() < 1e-12);
/// // The exact kurbo segments.
/// let seg = open.segment(1).unwrap();
/// assert_eq!(seg.eval(1.0), points[2]);
///
/// let max = BSpline::new(&points, true)?.max_curvature();
/// assert!(max.value > 0.0 && !max.params.is_empty());
/// # Ok::<(), kappa::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct BSpline<P = Point> {
    closed: bool,
    /// The interpolated points `s_k`.
    points: Vec<P>,
    /// The control points `b_k`.
    control: Vec<P>,
    /// The control points `b_k` in the normalized frame, as solved there, when the points lie
    /// far from the origin relative to their extent ([`FAR`]); empty otherwise. Mapping the
    /// user control points back to the normalized frame rounds them to the magnitude of the
    /// coordinates, which for such points is much of their precision (most of it for points
    /// 1e-7 apart at 1e4); near the origin it costs a few units in the last place and no
    /// memory.
    local_control: Vec<P>,
    /// Centre of the points' bounding box.
    center: P,
    /// Larger side of the points' bounding box (positive).
    size: f64,
}

/// A uniform cubic B-spline through 3D points; its segments are cubic [`SpaceBez`].
pub type BSpline3 = BSpline<Point3>;

/// The maximum of |κ| over a [`BSpline`] and every global parameter where it is attained.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BSplineCurvatureMax {
    /// The maximum of |κ| (2D curvature is signed; this is its absolute value).
    /// [`f64::INFINITY`] if |κ| is unbounded next to a cusp (`r′ = 0`).
    pub value: f64,
    /// Every global parameter where `|κ| ≥ (1 − TIE_TOLERANCE) · value`, increasing, each
    /// once: in `[0, n]` for an open spline and in `[0, n + 1)` for a closed one (a maximum at
    /// the closing point is reported at 0). At a cusp these are the cusp parameters.
    pub params: Vec<f64>,
}

impl BSplineCurvatureMax {
    /// Relative tolerance within which two values of |κ| count as the same maximum.
    ///
    /// Mirror-symmetric data gives mirror-symmetric splines, whose maxima agree to within a
    /// few units in the last place (measured on the paper's ellipse T5, whose points are mirror
    /// images only up to the rounding of sin and cos: 1.0e-14 relative), far inside this
    /// tolerance.
    pub const TIE_TOLERANCE: f64 = 1e-12;
}

mod sealed {
    use super::*;

    /// Dimension-specific operations of [`BSplinePoint`].
    pub trait Sealed: Copy + core::fmt::Debug + PartialEq {
        /// The exact segment type.
        type Seg: CurvatureAnalysis;

        /// Validate `points`, then replace `control` by the control points (user coordinates)
        /// and `local_control` by the control points in the normalized frame if the points are
        /// [`FAR`] from the origin (else clear it); returns the centre and the size of the
        /// normalized frame. The vectors are untouched on error.
        fn interpolate(
            points: &[Self],
            closed: bool,
            control: &mut Vec<Self>,
            local_control: &mut Vec<Self>,
        ) -> Result<(Self, f64), Error>;

        /// `wa a + wb b`.
        fn combine(a: Self, wa: f64, b: Self, wb: f64) -> Self;

        /// The cubic segment with these control points.
        fn segment(p: [Self; 4]) -> Self::Seg;

        /// Arc length of a segment.
        fn arclen(seg: &Self::Seg, accuracy: f64) -> f64;

        /// `(self − center) / size`.
        fn to_local(self, center: Self, size: f64) -> Self;

        /// A point with every coordinate NaN.
        fn nan() -> Self;

        /// Cheap bounds of |κ| on the cubic with these control points, split into `pieces`
        /// equal parts.
        fn curvature_bounds(p: [Self; 4], pieces: usize) -> CurvatureBounds;
    }
}

/// The point types a [`BSpline`] can interpolate: [`kurbo::Point`] and [`Point3`]. Sealed.
pub trait BSplinePoint: sealed::Sealed {}

impl BSplinePoint for Point {}
impl BSplinePoint for Point3 {}

macro_rules! impl_sealed {
    ($p:ty, $d:literal, $seg:ty, |$s:ident| $make:expr, |$g:ident, $acc:ident| $arclen:expr) => {
        impl sealed::Sealed for $p {
            type Seg = $seg;

            fn interpolate(
                points: &[Self],
                closed: bool,
                control: &mut Vec<Self>,
                local_control: &mut Vec<Self>,
            ) -> Result<(Self, f64), Error> {
                interpolate::<$p, $d>(points, closed, control, local_control)
            }

            #[inline]
            fn combine(a: Self, wa: f64, b: Self, wb: f64) -> Self {
                let (a, b) = (a.coords(), b.coords());
                <$p>::from_coords(core::array::from_fn(|k| wa * a[k] + wb * b[k]))
            }

            #[inline]
            fn segment($s: [Self; 4]) -> $seg {
                $make
            }

            fn arclen($g: &$seg, $acc: f64) -> f64 {
                $arclen
            }

            #[inline]
            fn to_local(self, center: Self, size: f64) -> Self {
                let (p, c) = (self.coords(), center.coords());
                <$p>::from_coords(core::array::from_fn(|k| (p[k] - c[k]) / size))
            }

            fn nan() -> Self {
                <$p>::from_coords([f64::NAN; $d])
            }

            fn curvature_bounds(p: [Self; 4], pieces: usize) -> CurvatureBounds {
                curvature_bounds_split::<$d>(p.map(|q| q.coords()), pieces)
            }
        }
    };
}

impl_sealed!(
    Point,
    2,
    CubicBez,
    |s| CubicBez::new(s[0], s[1], s[2], s[3]),
    |g, accuracy| g.arclen(accuracy)
);
impl_sealed!(
    Point3,
    3,
    SpaceBez,
    |s| SpaceBez::cubic(s[0], s[1], s[2], s[3]),
    |g, accuracy| g.arclen(accuracy)
);

impl Lin for Point {
    const ZERO: Self = Point::ZERO;
    #[inline]
    fn add_scaled(self, o: Self, s: f64) -> Self {
        Point::new(self.x + s * o.x, self.y + s * o.y)
    }
    #[inline]
    fn scaled(self, s: f64) -> Self {
        Point::new(s * self.x, s * self.y)
    }
}

impl Lin for Point3 {
    const ZERO: Self = Point3::ORIGIN;
    #[inline]
    fn add_scaled(self, o: Self, s: f64) -> Self {
        Point3::new(self.x + s * o.x, self.y + s * o.y, self.z + s * o.z)
    }
    #[inline]
    fn scaled(self, s: f64) -> Self {
        Point3::new(s * self.x, s * self.y, s * self.z)
    }
}

/// Relative margin on [`CurvatureBounds::upper`] for rounding: a segment is skipped only if
/// its bound, enlarged by this, is below the maximum found.
const BOUND_MARGIN: f64 = 1e-9;

/// Pieces into which a segment that survives the first pruning is split for tighter bounds.
const BOUND_PIECES: usize = 8;

/// [`CurvatureBounds`] of a cubic split into `pieces` equal parts (|κ| does not depend on the
/// parameterization, so each piece, reparameterized to `[0, 1]`, bounds its part).
///
/// Each piece's hodograph and second derivative come from the segment's own (blossoming the
/// quadratic `r′` over the piece, evaluating the linear `r″` at its ends), not from positions
/// of the piece: the piece's second differences of positions are `1/pieces²` of the segment's
/// while the rounding of positions is not, so on a nearly straight segment they would turn
/// the normal part of `r″` into noise (an end value 10 % above the true |κ| there, taken as
/// attained, once pruned the segment that held the maximum). Computed from the derivatives
/// they are known to a few ε of the segment's `|h|` and `|g|`, the rounding margin the
/// whole segment's bound already carries. The common factors `1/pieces` of `r′` and
/// `1/pieces²` of `r″` are left out: |κ| does not see them.
fn curvature_bounds_split<const D: usize>(p: [[f64; D]; 4], pieces: usize) -> CurvatureBounds {
    let (h, g) = derivative_coefficients(p);
    let margin = margins(&h, &g);
    if pieces <= 1 {
        return bounds_from_derivatives(h, g, margin);
    }
    // r′(u) = Σ B²_i(u) h_i and its blossom r′[u, v]; r″(u) = (1 − u) g₀ + u g₁.
    let blossom = |u: f64, v: f64| -> [f64; D] {
        let (w0, w1, w2) = ((1.0 - u) * (1.0 - v), (1.0 - u) * v + u * (1.0 - v), u * v);
        core::array::from_fn(|k| w0 * h[0][k] + w1 * h[1][k] + w2 * h[2][k])
    };
    let second =
        |u: f64| -> [f64; D] { core::array::from_fn(|k| (1.0 - u) * g[0][k] + u * g[1][k]) };
    let step = 1.0 / pieces as f64;
    let mut out = CurvatureBounds {
        at_ends: 0.0,
        upper: 0.0,
    };
    for j in 0..pieces {
        let u0 = j as f64 * step;
        let u1 = if j + 1 == pieces {
            1.0
        } else {
            (j + 1) as f64 * step
        };
        let hp = [blossom(u0, u0), blossom(u0, u1), blossom(u1, u1)];
        let gp = [second(u0), second(u1)];
        let piece = bounds_from_derivatives(hp, gp, margin);
        out.at_ends = out.at_ends.max(piece.at_ends);
        out.upper = out.upper.max(piece.upper);
    }
    out
}

/// Bounds of |κ| on one cubic segment, from its control points alone.
#[derive(Clone, Copy, Debug)]
pub struct CurvatureBounds {
    /// `max(|κ(0)|, |κ(1)|)`: attained, so a lower bound of the spline's maximum.
    at_ends: f64,
    /// `≥ |κ(t)|` for all `t ∈ [0, 1]` (up to rounding); infinite when `r′` may vanish.
    upper: f64,
}

/// The hodograph `h_i = 3(p_{i+1} − p_i)` and second-derivative coefficients
/// `g_j = 2(h_{j+1} − h_j)` of the cubic with control points `p`.
fn derivative_coefficients<const D: usize>(p: [[f64; D]; 4]) -> ([[f64; D]; 3], [[f64; D]; 2]) {
    let h: [[f64; D]; 3] =
        core::array::from_fn(|i| core::array::from_fn(|k| 3.0 * (p[i + 1][k] - p[i][k])));
    let g: [[f64; D]; 2] =
        core::array::from_fn(|j| core::array::from_fn(|k| 2.0 * (h[j + 1][k] - h[j][k])));
    (h, g)
}

fn dot<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    (0..D).map(|k| a[k] * b[k]).sum::<f64>()
}

/// The allowances of a segment's bounds, from its largest `|h_i|` and `|g_j|`:
/// - the rounding of the cross products `h × g` (a few ε `|h| |g|` each): for a segment
///   collinear to within rounding they are that rounding, and the bound must still hold for
///   the curvature computed from the same control points;
/// - the stall threshold of the analysis, `STALL_TOL` times the largest `|h_i|`: where the
///   lower bound of `|r′|` is below it the analysis may find a stall (and report |κ| = ∞),
///   so the bound must be infinite there too.
fn margins<const D: usize>(h: &[[f64; D]; 3], g: &[[f64; D]; 2]) -> Margins {
    let hmax = h.iter().map(|&v| dot(v, v)).fold(0.0, f64::max).sqrt();
    let gmax = g.iter().map(|&v| dot(v, v)).fold(0.0, f64::max).sqrt();
    Margins {
        cross: 16.0 * f64::EPSILON * hmax * gmax,
        stall: crate::analysis::STALL_TOL * hmax,
    }
}

/// The rounding allowances of [`bounds_from_derivatives`], from the whole segment.
#[derive(Clone, Copy)]
struct Margins {
    /// Added to the bound of `|r′ × r″|`.
    cross: f64,
    /// A lower bound of `|r′|` at or below this gives an infinite bound.
    stall: f64,
}

/// [`CurvatureBounds`] of the cubic whose hodograph has Bernstein coefficients `h` and whose
/// second derivative has `g` (any common scale of `h` and its square for `g`).
///
/// With `r′ = Σ B²_i h_i` and `r″ = Σ B¹_j g_j`, the product `r′ × r″` is the cubic Bernstein
/// polynomial with coefficients `h₀×g₀, (2h₁×g₀ + h₀×g₁)/3, (h₂×g₀ + 2h₁×g₁)/3, h₂×g₁`, so
/// `|r′ × r″|` is at most the largest of their norms (convex hull property), plus
/// `margin.cross` for rounding. `|r′|` is at least `min_i h_i · û` for any unit `û` (the
/// hodograph lies in the convex hull of the `h_i`); the best of `û ∈ {h₀, h₁, h₂, h₀ + h₂}`
/// normalized is taken. Hence `|κ| ≤ max_k |c_k| / (min |r′|)³`, tight to first order in the
/// segment's variation; infinite where `min |r′|` is within `margin.stall`.
fn bounds_from_derivatives<const D: usize>(
    h: [[f64; D]; 3],
    g: [[f64; D]; 2],
    margin: Margins,
) -> CurvatureBounds {
    // |a × b|² = |a|²|b|² − (a·b)² loses accuracy for nearly parallel vectors; the explicit
    // components do not.
    let cross = |a: [f64; D], b: [f64; D]| -> [f64; 3] {
        let c = |v: [f64; D], k: usize| if k < D { v[k] } else { 0.0 };
        [
            c(a, 1) * c(b, 2) - c(a, 2) * c(b, 1),
            c(a, 2) * c(b, 0) - c(a, 0) * c(b, 2),
            c(a, 0) * c(b, 1) - c(a, 1) * c(b, 0),
        ]
    };
    let norm3 = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let c0 = cross(h[0], g[0]);
    let c3 = cross(h[2], g[1]);
    let (h1g0, h0g1, h2g0, h1g1) = (
        cross(h[1], g[0]),
        cross(h[0], g[1]),
        cross(h[2], g[0]),
        cross(h[1], g[1]),
    );
    let c1: [f64; 3] = core::array::from_fn(|k| (2.0 * h1g0[k] + h0g1[k]) / 3.0);
    let c2: [f64; 3] = core::array::from_fn(|k| (h2g0[k] + 2.0 * h1g1[k]) / 3.0);
    let num = norm3(c0).max(norm3(c1)).max(norm3(c2)).max(norm3(c3)) + margin.cross;
    let kappa_end = |c: [f64; 3], v: [f64; D]| {
        let l = dot(v, v).sqrt();
        let k = norm3(c) / (l * l * l);
        if k.is_finite() {
            k
        } else {
            0.0
        }
    };
    let at_ends = kappa_end(c0, h[0]).max(kappa_end(c3, h[2]));
    let sum: [f64; D] = core::array::from_fn(|k| h[0][k] + h[2][k]);
    let mut speed = 0.0f64;
    for u in [h[0], h[1], h[2], sum] {
        let len = dot(u, u).sqrt();
        if len > 0.0 {
            let low = h
                .iter()
                .map(|&hi| dot(hi, u) / len)
                .fold(f64::INFINITY, f64::min);
            speed = speed.max(low);
        }
    }
    let upper = if speed > margin.stall {
        num / (speed * speed * speed)
    } else {
        f64::INFINITY
    };
    CurvatureBounds {
        at_ends,
        upper: if upper.is_nan() { f64::INFINITY } else { upper },
    }
}

/// Validate `points`, solve for the control points in the normalized frame and map them back.
///
/// Four sweeps over the points: bounds, repeated points, and the two of the solver, which
/// reads the right-hand sides straight from the points and writes the control points in user
/// coordinates (the solver's vectors are points of the normalized frame until then). For
/// points [`FAR`] from the origin the solver writes the normalized control points, and a fifth
/// sweep maps them to user coordinates.
fn interpolate<P: Coords<D> + Lin, const D: usize>(
    points: &[P],
    closed: bool,
    control: &mut Vec<P>,
    local_control: &mut Vec<P>,
) -> Result<(P, f64), Error> {
    let m = points.len();
    let (kind, needed) = if closed {
        ("a closed B-spline", 3)
    } else {
        ("an open B-spline", 2)
    };
    if m < needed {
        return Err(Error::TooFewPoints {
            kind,
            needed,
            got: m,
        });
    }
    let mut lo = [f64::INFINITY; D];
    let mut hi = [f64::NEG_INFINITY; D];
    for (index, p) in points.iter().enumerate() {
        let c = p.coords();
        if !c.iter().all(|x| x.is_finite()) {
            return Err(Error::NonFinitePoint { index });
        }
        for k in 0..D {
            lo[k] = lo[k].min(c[k]);
            hi[k] = hi[k].max(c[k]);
        }
    }
    let size = (0..D).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    // In the normalized frame |s_k| ≤ ½ per coordinate, and diagonal dominance gives
    // |b|∞ ≤ (6 · ½ + 2 |b|∞) / 4, i.e. |b|∞ ≤ 3/2: the control points stay within
    // |centre| + 3/2 · size, which must be finite.
    let reach = (0..D).fold(0.0f64, |r, k| {
        r.max((0.5 * lo[k] + 0.5 * hi[k]).abs() + CONTROL_REACH * size)
    });
    if !(size.is_finite() && reach.is_finite()) {
        return Err(Error::ExtentOverflow);
    }
    if size == 0.0 {
        return Err(Error::RepeatedPoint { index: 0, next: 1 });
    }
    // Halves first: (lo + hi) / 2 can overflow where lo/2 + hi/2 does not.
    let center: [f64; D] = core::array::from_fn(|k| 0.5 * lo[k] + 0.5 * hi[k]);
    // A subnormal size has no finite reciprocal: then differences are scaled up by 2⁶⁰⁰
    // (exactly) first, which keeps them far from overflow.
    let pre = if (1.0 / size).is_finite() {
        1.0
    } else {
        2f64.powi(600)
    };
    let inv = 1.0 / (size * pre);
    let local = |p: P| -> [f64; D] {
        let c = p.coords();
        core::array::from_fn(|k| (c[k] - center[k]) * pre * inv)
    };
    let coincident2 = COINCIDENT * COINCIDENT;
    let repeated = |a: [f64; D], b: [f64; D]| {
        (0..D).map(|k| (b[k] - a[k]) * (b[k] - a[k])).sum::<f64>() <= coincident2
    };
    let mut prev = local(points[0]);
    for (i, &p) in points.iter().enumerate().skip(1) {
        let s = local(p);
        if repeated(prev, s) {
            return Err(Error::RepeatedPoint {
                index: i - 1,
                next: i,
            });
        }
        prev = s;
    }
    if closed && repeated(prev, local(points[0])) {
        return Err(Error::RepeatedPoint {
            index: m - 1,
            next: 0,
        });
    }
    // Unknowns: all b_k (closed), or b_1 … b_{n−1} with b_0 = s_0, b_n = s_n moved to the
    // right-hand side (open).
    let (offset, unknowns) = if closed { (0, m) } else { (1, m - 2) };
    let (first, last) = (local(points[0]), local(points[m - 1]));
    let rhs = |i: usize| -> P {
        let mut d = local(points[i + offset]).map(|x| 6.0 * x);
        if !closed {
            for k in 0..D {
                if i == 0 {
                    d[k] -= first[k];
                }
                if i + 1 == unknowns {
                    d[k] -= last[k];
                }
            }
        }
        P::from_coords(d)
    };
    let to_user = |x: P| {
        let c = x.coords();
        P::from_coords(core::array::from_fn(|k| c[k] * size + center[k]))
    };
    let far = center.iter().any(|c| c.abs() > FAR * size);
    local_control.clear();
    control.clear();
    control.reserve(m);
    if far {
        local_control.reserve(m);
        if !closed {
            local_control.push(P::from_coords(first));
        }
        let solved =
            solve_symmetric_toeplitz_into(DIAGONAL, closed, unknowns, rhs, local_control, |x| x);
        debug_assert!(solved, "the diagonal is a valid constant");
        if !closed {
            local_control.push(P::from_coords(last));
        }
        control.extend(local_control.iter().map(|&b| to_user(b)));
        if !closed {
            // The ends are the data points themselves, exactly.
            control[0] = points[0];
            control[m - 1] = points[m - 1];
        }
    } else {
        if !closed {
            control.push(points[0]);
        }
        let solved =
            solve_symmetric_toeplitz_into(DIAGONAL, closed, unknowns, rhs, control, to_user);
        debug_assert!(solved, "the diagonal is a valid constant");
        if !closed {
            control.push(points[m - 1]);
        }
    }
    Ok((P::from_coords(center), size))
}

impl<P: BSplinePoint> BSpline<P> {
    /// The uniform cubic B-spline through `points`: relaxed if `closed` is false, periodic if
    /// it is true. `O(n)`.
    ///
    /// # Errors
    ///
    /// [`Error::TooFewPoints`] (fewer than 2 points open, 3 closed),
    /// [`Error::NonFinitePoint`], [`Error::RepeatedPoint`] (consecutive points within 1e-12
    /// of the drawing size, including last → first when closed) and
    /// [`Error::ExtentOverflow`] (the extent of the points is not a finite `f64`, or the
    /// control points could overflow: a coordinate within 1.5 extents of `±f64::MAX`).
    pub fn new(points: &[P], closed: bool) -> Result<Self, Error> {
        let (mut control, mut local_control) = (Vec::new(), Vec::new());
        let (center, size) = P::interpolate(points, closed, &mut control, &mut local_control)?;
        Ok(BSpline {
            closed,
            points: points.to_vec(),
            control,
            local_control,
            center,
            size,
        })
    }

    /// Re-interpolate new points in place, reusing the spline's memory: the same as
    /// [`new`](Self::new) without allocating when the point count does not grow (for
    /// interactive editing, or many splines in a row). On error the spline is unchanged.
    pub fn set_points(&mut self, points: &[P], closed: bool) -> Result<(), Error> {
        let (center, size) =
            P::interpolate(points, closed, &mut self.control, &mut self.local_control)?;
        self.points.clear();
        self.points.extend_from_slice(points);
        self.closed = closed;
        self.center = center;
        self.size = size;
        Ok(())
    }

    /// The relaxed (open) spline through `points`: `new(points, false)`.
    pub fn relaxed(points: &[P]) -> Result<Self, Error> {
        Self::new(points, false)
    }

    /// The periodic (closed) spline through `points`: `new(points, true)`.
    pub fn periodic(points: &[P]) -> Result<Self, Error> {
        Self::new(points, true)
    }

    /// Whether the spline is closed (periodic).
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// The interpolated points `s_k`; the spline passes through `s_k` at `t = k`.
    pub fn points(&self) -> &[P] {
        &self.points
    }

    /// The B-spline control points `b_k` (as many as points; `b_0 = s_0` and `b_n = s_n` for
    /// an open spline).
    pub fn control_points(&self) -> &[P] {
        &self.control
    }

    /// The number of segments: `n` for `n + 1` points open, `n + 1` closed.
    pub fn segment_count(&self) -> usize {
        if self.closed {
            self.points.len()
        } else {
            self.points.len() - 1
        }
    }

    /// The range of the global parameter: `0..n` open, `0..n+1` closed (the segment count).
    pub fn param_range(&self) -> Range<f64> {
        0.0..self.segment_count() as f64
    }

    /// The four Bézier control points of segment `i`,
    /// `s_i, (2b_i + b_{i+1})/3, (b_i + 2b_{i+1})/3, s_{i+1}` (indices mod the point count
    /// when closed), or `None` if there is no such segment.
    pub fn segment_points(&self, i: usize) -> Option<[P; 4]> {
        if i >= self.segment_count() {
            return None;
        }
        let j = (i + 1) % self.points.len();
        let (b0, b1) = (self.control[i], self.control[j]);
        Some([
            self.points[i],
            P::combine(b0, 2.0 / 3.0, b1, 1.0 / 3.0),
            P::combine(b0, 1.0 / 3.0, b1, 2.0 / 3.0),
            self.points[j],
        ])
    }

    /// Segment `i` in the normalized frame (centre at the origin, drawing size 1), where its
    /// curvature is computed: the curvature in user units is this one's divided by `size`.
    fn local_segment(&self, i: usize) -> P::Seg {
        P::segment(self.local_points(i))
    }

    /// The control points of segment `i` in the normalized frame (the same formula as
    /// [`segment_points`](Self::segment_points)), from the normalized control points when they
    /// are kept ([`FAR`]).
    fn local_points(&self, i: usize) -> [P; 4] {
        let j = (i + 1) % self.points.len();
        let local = |p: P| p.to_local(self.center, self.size);
        let (b0, b1) = if self.local_control.is_empty() {
            (local(self.control[i]), local(self.control[j]))
        } else {
            (self.local_control[i], self.local_control[j])
        };
        [
            local(self.points[i]),
            P::combine(b0, 2.0 / 3.0, b1, 1.0 / 3.0),
            P::combine(b0, 1.0 / 3.0, b1, 2.0 / 3.0),
            local(self.points[j]),
        ]
    }

    /// The segment containing the global parameter `t` and the parameter in `[0, 1]` on it
    /// (seed 002, Algorithm 2 steps 1–5): segment `⌊t⌋`, except that the end `t = n` of an
    /// open spline belongs to the last segment. `t` outside the parameter range is clamped
    /// (open) or wrapped around (closed). NaN maps to segment 0 at NaN.
    pub fn locate(&self, t: f64) -> (usize, f64) {
        let count = self.segment_count();
        let end = count as f64;
        let t = if self.closed {
            let w = t.rem_euclid(end);
            // rem_euclid can round up to `end` itself for tiny negative t.
            if w >= end {
                0.0
            } else {
                w
            }
        } else {
            t.clamp(0.0, end)
        };
        if t.is_nan() {
            return (0, t);
        }
        let i = (t.floor() as usize).min(count - 1);
        (i, t - i as f64)
    }

    /// The point at global parameter `t` (see [`locate`](Self::locate); NaN gives NaN).
    pub fn eval(&self, t: f64) -> P {
        let (i, u) = self.locate(t);
        if u.is_nan() {
            return P::nan();
        }
        let [p0, p1, p2, p3] = self.segment_points(i).expect("located segment");
        let v = 1.0 - u;
        let a = P::combine(p0, v, p1, u);
        let b = P::combine(p1, v, p2, u);
        let c = P::combine(p2, v, p3, u);
        let ab = P::combine(a, v, b, u);
        let bc = P::combine(b, v, c, u);
        P::combine(ab, v, bc, u)
    }

    /// The curvature at global parameter `t` (seed 002, Algorithm 2): signed in 2D (positive
    /// for left turns, `(x′y″ − y′x″)/|r′|³`), `|r′ × r″|/|r′|³` in 3D. Computed in the
    /// normalized frame, so it does not overflow for huge or tiny coordinates. NaN for a NaN
    /// `t`; 0 where `r′ = 0` and on segments whose control points are collinear to within
    /// rounding (straight, see [`analysis`](crate::analysis)).
    pub fn curvature(&self, t: f64) -> f64 {
        self.local_curvature(t) / self.size
    }

    /// The curvature at global parameter `t` in the normalized frame.
    fn local_curvature(&self, t: f64) -> f64 {
        let (i, u) = self.locate(t);
        if u.is_nan() {
            return f64::NAN;
        }
        let seg = self.local_segment(i);
        if crate::analysis::is_straight(&seg) {
            // κ ≡ 0 on a segment straight to within rounding, as its maximum says; the noise
            // of `r′ × r″` over a small `|r′|` (a straight reversal) is not curvature.
            return 0.0;
        }
        CurvatureAnalysis::curvature(&seg, u)
    }

    /// The maximum of |κ| and every global parameter where it is attained (seed 002,
    /// Algorithm 1, through [`CurvatureAnalysis::max_curvature`] on each segment: roots of the
    /// stationarity polynomial and both ends). Ties within
    /// [`BSplineCurvatureMax::TIE_TOLERANCE`] are all reported.
    pub fn max_curvature(&self) -> BSplineCurvatureMax {
        let tie = 1.0 - BSplineCurvatureMax::TIE_TOLERANCE;
        let count = self.segment_count();
        // Cheap bounds first: |κ| at every joint is a lower bound of the maximum, and a
        // segment whose upper bound stays below it cannot attain it. The rest are analysed in
        // decreasing order of their bound, until the bound drops below the best value found.
        //
        // A segment straight to within rounding has κ ≡ 0 (its curvature is 0, see
        // `curvature`): its bound is 0, and the values at the ends of a segment next to one
        // are not counted as attained (at the joint `curvature` sees the straight one).
        let straight: Vec<bool> = (0..count)
            .map(|i| crate::analysis::is_straight(&self.local_segment(i)))
            .collect();
        let next_straight = |i: usize| {
            i + 1 < count && straight[i + 1] || i + 1 == count && self.closed && straight[0]
        };
        let mut bounds: Vec<(usize, f64)> = Vec::with_capacity(count);
        let mut lower = 0.0f64;
        for (i, &flat) in straight.iter().enumerate() {
            if flat {
                bounds.push((i, 0.0));
                continue;
            }
            let b = P::curvature_bounds(self.local_points(i), 1);
            if !next_straight(i) {
                lower = lower.max(b.at_ends);
            }
            bounds.push((i, b.upper));
        }
        // The bounds are exact up to rounding; the margin absorbs it.
        let prunable = |upper: f64, best: f64| upper * (1.0 + BOUND_MARGIN) < best * tie;
        bounds.retain(|b| !prunable(b.1, lower));
        // Tighter bounds (and more attained values) for the segments left, from pieces.
        for b in &mut bounds {
            if straight[b.0] {
                continue;
            }
            let r = P::curvature_bounds(self.local_points(b.0), BOUND_PIECES);
            if !next_straight(b.0) {
                lower = lower.max(r.at_ends);
            }
            b.1 = r.upper;
        }
        bounds.retain(|b| !prunable(b.1, lower));
        bounds.sort_unstable_by(|a, b| b.1.total_cmp(&a.1));
        let mut best = 0.0f64;
        // (global parameter, |κ| there) of the candidates that may still tie with `best`.
        let mut cands: Vec<(f64, f64)> = Vec::new();
        for &(i, upper) in &bounds {
            if prunable(upper, best) {
                break;
            }
            let seg = P::segment(self.local_points(i));
            let m = seg.max_curvature();
            if m.value < best * tie {
                continue;
            }
            for &u in &m.params {
                // The analysis reports parameters within its own (looser) tolerance of the
                // segment's maximum: re-measure each one where it is reported, at the global
                // parameter, so that the value is |κ| there exactly. At a cusp, or where
                // r′ = 0 with a finite limit, the value is the analysis' limit, not the 0 of
                // `curvature`.
                let mut t = i as f64 + u;
                if t > 0.0 && !straight[i] && straight[self.locate(t).0] {
                    // The end of this curved segment at a joint with a straight one, where
                    // `curvature` sees the straight one (0). The curved side's value is
                    // reported at the last parameter before the joint, which `curvature`
                    // evaluates on this segment (a near-cusp of nearly collinear data has
                    // its maximum there; skipping it under-reported the maximum).
                    t = f64::from_bits(t.to_bits() - 1);
                    if straight[self.locate(t).0] {
                        continue;
                    }
                }
                let k = self.local_curvature(t).abs();
                let v = if m.value.is_infinite() || (k == 0.0 && m.value > 0.0) {
                    m.value
                } else {
                    k
                };
                if v > best {
                    best = v;
                    cands.retain(|c| c.1 >= best * tie);
                }
                cands.push((t, v));
            }
        }
        let end = count as f64;
        let mut params: Vec<f64> = cands
            .iter()
            .filter(|c| c.1 >= best * tie)
            .map(|c| if self.closed && c.0 >= end { 0.0 } else { c.0 })
            .collect();
        params.sort_by(f64::total_cmp);
        // A joint is reported by both of its segments, as (i, 1) and (i + 1, 0).
        params.dedup_by(|a, b| (*a - *b).abs() <= PARAM_DEDUP);
        BSplineCurvatureMax {
            value: best / self.size,
            params,
        }
    }

    /// The arc length, to within about `accuracy` per segment. Measured in the normalized
    /// frame, so it does not overflow for huge or tiny coordinates.
    pub fn arclen(&self, accuracy: f64) -> f64 {
        let local_accuracy = accuracy / self.size;
        let local: f64 = (0..self.segment_count())
            .map(|i| P::arclen(&self.local_segment(i), local_accuracy))
            .sum();
        local * self.size
    }
}

/// Global parameters closer than this are the same point of the curve.
const PARAM_DEDUP: f64 = 1e-12;

impl BSpline<Point> {
    /// Segment `i` as an exact kurbo cubic, or `None` if there is no such segment.
    pub fn segment(&self, i: usize) -> Option<CubicBez> {
        self.segment_points(i)
            .map(|[p0, p1, p2, p3]| CubicBez::new(p0, p1, p2, p3))
    }

    /// The segments in order along the curve.
    pub fn segments(&self) -> impl Iterator<Item = CubicBez> + '_ {
        (0..self.segment_count()).filter_map(|i| self.segment(i))
    }

    /// The spline as a kurbo path of exact `CubicBez` segments, closed with `ClosePath` when
    /// the spline is closed.
    pub fn to_bezpath(&self) -> BezPath {
        self.path_elements(0.0).collect()
    }
}

impl BSpline<Point3> {
    /// Segment `i` as an exact cubic [`SpaceBez`], or `None` if there is no such segment.
    pub fn segment(&self, i: usize) -> Option<SpaceBez> {
        self.segment_points(i)
            .map(|[p0, p1, p2, p3]| SpaceBez::cubic(p0, p1, p2, p3))
    }

    /// The segments in order along the curve.
    pub fn segments(&self) -> impl Iterator<Item = SpaceBez> + '_ {
        (0..self.segment_count()).filter_map(|i| self.segment(i))
    }

    /// The spline drawn through `project` as a kurbo path, segment by segment (control point
    /// by control point). Exact when `project` is affine, e.g. an orthographic view.
    pub fn to_bezpath_projected(&self, project: impl Fn(Point3) -> Point) -> BezPath {
        let mut path = BezPath::new();
        for (i, [p0, p1, p2, p3]) in (0..self.segment_count())
            .filter_map(|i| self.segment_points(i))
            .enumerate()
        {
            if i == 0 {
                path.move_to(project(p0));
            }
            path.curve_to(project(p1), project(p2), project(p3));
        }
        if self.closed {
            path.close_path();
        }
        path
    }
}

/// The path elements of a 2D [`BSpline`]: `MoveTo`, one `CurveTo` per segment, and
/// `ClosePath` for a closed spline.
#[derive(Clone, Debug)]
pub struct BSplinePathElements<'a> {
    spline: &'a BSpline<Point>,
    /// The next element: 0 is the `MoveTo`, `i + 1` is segment `i`'s `CurveTo`.
    next: usize,
}

impl Iterator for BSplinePathElements<'_> {
    type Item = PathEl;

    fn next(&mut self) -> Option<PathEl> {
        let count = self.spline.segment_count();
        let k = self.next;
        self.next += 1;
        match k {
            0 => Some(PathEl::MoveTo(self.spline.points[0])),
            k if k <= count => {
                let [_, p1, p2, p3] = self.spline.segment_points(k - 1)?;
                Some(PathEl::CurveTo(p1, p2, p3))
            }
            k if k == count + 1 && self.spline.closed => Some(PathEl::ClosePath),
            _ => {
                self.next = k;
                None
            }
        }
    }
}

/// A 2D spline is a kurbo [`Shape`] made of its exact cubic segments.
impl Shape for BSpline<Point> {
    type PathElementsIter<'iter> = BSplinePathElements<'iter>;

    fn path_elements(&self, _tolerance: f64) -> BSplinePathElements<'_> {
        BSplinePathElements {
            spline: self,
            next: 0,
        }
    }

    /// The signed area, as kurbo's `BezPath::area` of [`to_bezpath`](Self::to_bezpath)
    /// (positive for anticlockwise curves in y-up coordinates).
    fn area(&self) -> f64 {
        self.segments().map(|s| s.signed_area()).sum()
    }

    fn perimeter(&self, accuracy: f64) -> f64 {
        self.arclen(accuracy)
    }

    fn winding(&self, pt: Point) -> i32 {
        self.to_bezpath().winding(pt)
    }

    fn bounding_box(&self) -> Rect {
        self.segments()
            .map(|s| ParamCurveExtrema::bounding_box(&s))
            .reduce(|a, b| a.union(b))
            .unwrap_or_default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// xorshift64*, for reproducible random control points.
    fn rng(state: &mut u64) -> f64 {
        *state ^= *state >> 12;
        *state ^= *state << 25;
        *state ^= *state >> 27;
        (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// |κ| of the cubic at `t`, from its derivatives.
    fn kappa<const D: usize>(p: [[f64; D]; 4], t: f64) -> f64 {
        let s = 1.0 - t;
        let d1: [f64; 3] = core::array::from_fn(|k| {
            if k >= D {
                return 0.0;
            }
            3.0 * (s * s * (p[1][k] - p[0][k])
                + 2.0 * s * t * (p[2][k] - p[1][k])
                + t * t * (p[3][k] - p[2][k]))
        });
        let d2: [f64; 3] = core::array::from_fn(|k| {
            if k >= D {
                return 0.0;
            }
            6.0 * (s * (p[2][k] - 2.0 * p[1][k] + p[0][k])
                + t * (p[3][k] - 2.0 * p[2][k] + p[1][k]))
        });
        let c = [
            d1[1] * d2[2] - d1[2] * d2[1],
            d1[2] * d2[0] - d1[0] * d2[2],
            d1[0] * d2[1] - d1[1] * d2[0],
        ];
        let n = (d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2]).sqrt();
        (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt() / (n * n * n)
    }

    fn check_bounds<const D: usize>(seed: &mut u64) -> (usize, usize) {
        let mut finite = 0;
        let mut tight = 0;
        for _ in 0..2000 {
            let p: [[f64; D]; 4] = core::array::from_fn(|_| core::array::from_fn(|_| rng(seed)));
            let sampled = (0..=2000)
                .map(|j| kappa(p, j as f64 / 2000.0))
                .fold(0.0f64, f64::max);
            let ends = kappa(p, 0.0).max(kappa(p, 1.0));
            for pieces in [1, 8] {
                let b = curvature_bounds_split(p, pieces);
                assert!(
                    b.upper >= sampled * (1.0 - 1e-12),
                    "{p:?}: {} < {sampled}",
                    b.upper
                );
                assert!(b.at_ends <= sampled * (1.0 + 1e-12) && b.at_ends >= ends * (1.0 - 1e-12));
                if pieces == 8 && b.upper.is_finite() {
                    finite += 1;
                    tight += usize::from(b.upper < 2.0 * sampled);
                }
            }
        }
        (finite, tight)
    }

    #[test]
    fn curvature_bounds_bound_sampled_curvature() {
        let mut seed = 0x5eed;
        let (finite, tight) = check_bounds::<2>(&mut seed);
        // Random control points often make loops (no finite bound); where the bound is finite
        // it is usually within a factor 2.
        assert!(finite > 500 && tight > finite / 2, "{finite} {tight}");
        let (finite, tight) = check_bounds::<3>(&mut seed);
        assert!(finite > 500 && tight > finite / 2, "{finite} {tight}");
    }

    #[test]
    fn toeplitz_solver_accepts_points() {
        // The interpolation solves on points directly.
        let pts = [
            Point::new(0.0, 6.0),
            Point::new(6.0, 0.0),
            Point::new(6.0, 6.0),
        ];
        let mut out = Vec::new();
        assert!(solve_symmetric_toeplitz_into(
            4.0,
            true,
            3,
            |i| pts[i],
            &mut out,
            |x| x
        ));
        for i in 0..3 {
            let lhs = out[(i + 2) % 3]
                .add_scaled(out[i], 4.0)
                .add_scaled(out[(i + 1) % 3], 1.0);
            assert!((lhs - pts[i]).hypot() < 1e-14);
        }
    }
}
