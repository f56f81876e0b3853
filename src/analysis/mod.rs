//! Curvature analysis of Bézier segments of degree 1–4, in 2D and 3D.
//!
//! Every curve scheme of this crate produces Bézier segments; this module measures them:
//! curvature and curvature vector at a parameter, all curvature extrema of a segment, the
//! maximum of |κ| over a segment or a whole path together with *every* parameter where it is
//! attained (seed paper 002, Algorithm 1), the continuity (gap, tangent angle, curvature jump)
//! at the joints of a path, and curvature combs for display.
//!
//! # Sign convention
//!
//! **In 2D the curvature is signed, positive for left turns** (anticlockwise in y-up
//! coordinates, clockwise on screen in y-down coordinates), as in the papers:
//!
//! ```text
//! κ(t) = (x′y″ − y′x″) / |r′|³ = (r′ × r″) / |r′|³
//! ```
//!
//! This is the **opposite** of kurbo's [`ParamCurveCurvature::curvature`], which computes
//! `(r″ × r′) / |r′|³`: for the `QuadBez` (0,0), (1,0), (1,1) at t = ½ kurbo gives −√2 and this
//! module gives +√2.
//!
//! In 3D the curvature is unsigned, `κ = |r′ × r″| / |r′|³ ≥ 0`.
//!
//! In both cases the *curvature vector* is `k = r′ × (r″ × r′) / |r′|⁴ = (r″|r′|² − r′(r′·r″)) / |r′|⁴`:
//! it has length |κ| and points towards the centre of curvature. In 2D `k = κ n` with the left
//! normal `n = (−y′, x′)/|r′|`.
//!
//! # Degenerate segments
//!
//! Nothing here returns NaN or panics on finite input.
//! - Where `r′(t) = 0` (to within [`STALL_TOLERANCE`] of the size of the hodograph), the tangent
//!   is undefined and [`CurvatureAnalysis::curvature`] returns 0.0 and
//!   [`CurvatureAnalysis::curvature_vector`] the zero vector.
//! - A segment whose control points all coincide, or are collinear to within rounding, is
//!   straight: κ ≡ 0, no extrema, maximum 0.
//! - Next to a cusp (r′ = 0 on a curve that is not straight there, e.g. the cubic
//!   (0,0), (1,1), (0,1), (1,0) at t = ½, or a cubic whose first two control points coincide, at
//!   t = 0) |κ| is unbounded: [`CurvatureAnalysis::max_curvature`] reports
//!   [`f64::INFINITY`] at that parameter.
//!
//! # Example
//!
//! ```
//! use kappa::analysis::CurvatureAnalysis;
//! use kurbo::QuadBez;
//!
//! // The parabola y = x², x in [-1, 1]: maximum curvature 2 at its vertex.
//! let q = QuadBez::new((-1.0, 1.0), (0.0, -1.0), (1.0, 1.0));
//! let max = q.max_curvature();
//! assert!((max.value - 2.0).abs() < 1e-12);
//! assert_eq!(max.params.len(), 1);
//! assert!((max.params[0] - 0.5).abs() < 1e-12);
//! // It turns left: the curvature is positive.
//! assert!(q.curvature(0.25) > 0.0);
//! ```
//!
//! [`ParamCurveCurvature::curvature`]: kurbo::ParamCurveCurvature::curvature

mod bez;
pub(crate) use bez::STALL_TOL;
mod comb;
mod continuity;
mod quartic;
mod space;

use kurbo::{BezPath, CubicBez, Line, PathEl, PathSeg, Point, QuadBez, Vec2};

use crate::Vec3;
use bez::{Bez, Sealed};

pub use comb::{comb_from_samples, curvature_comb};
pub use continuity::{continuity, path_continuity, segments_continuity, Continuity, PathJoint};
pub use quartic::QuarticBez;
pub use space::SpaceBez;

/// Relative tolerance with which a maximum counts as attained: every candidate parameter where
/// `|κ| ≥ (1 − ATTAINED_TOLERANCE) · max` is reported.
pub const ATTAINED_TOLERANCE: f64 = 1e-9;

/// Where `|r′(t)| ≤ STALL_TOLERANCE · max_i |n (p_{i+1} − p_i)|` the tangent is taken as
/// undefined (a stall of the parameterization): the curvature is reported as 0 there.
pub const STALL_TOLERANCE: f64 = bez::STALL_TOL;

/// The maximum of |κ| over one segment, `t ∈ [0, 1]`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CurvatureMax {
    /// The maximum of |κ|. [`f64::INFINITY`] when |κ| is unbounded next to a cusp.
    pub value: f64,
    /// Every parameter in `[0, 1]` where the maximum is attained (within
    /// [`ATTAINED_TOLERANCE`]), in increasing order. The candidates are the interior extrema,
    /// the cusps and both ends; for a straight segment (κ ≡ 0, attained everywhere) this is
    /// `[0, 1]`. At a cusp (`value` infinite) it holds the cusp parameters, where
    /// [`CurvatureAnalysis::curvature`] itself returns 0 by convention.
    pub params: Vec<f64>,
}

/// The maximum of |κ| over a sequence of segments (a path or a spline).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PathCurvatureMax {
    /// The maximum of |κ| over all segments; 0 for a path without segments.
    pub value: f64,
    /// Every `(segment_index, t)` where it is attained (within [`ATTAINED_TOLERANCE`]), in
    /// order. Segment indices are those of [`BezPath::segments`]. A joint can appear twice, as
    /// `(i, 1.0)` and `(i + 1, 0.0)`.
    pub params: Vec<(usize, f64)>,
}

/// Curvature of Bézier segments of degree 1–4.
///
/// Implemented for kurbo's [`Line`], [`QuadBez`], [`CubicBez`] and [`PathSeg`] and for this
/// module's [`QuarticBez`] (2D: signed curvature, [`Vec2`] curvature vectors) and [`SpaceBez`]
/// (3D: unsigned curvature, [`Vec3`] curvature vectors). See the [module docs](self) for the
/// sign convention. This trait is sealed.
pub trait CurvatureAnalysis: Sealed {
    /// The type of curvature vectors: [`Vec2`] in 2D, [`Vec3`] in 3D.
    type Vector;

    /// The curvature at `t`.
    ///
    /// 2D: signed, `κ = (x′y″ − y′x″)/|r′|³`, positive for left (anticlockwise in y-up) turns —
    /// the opposite sign of kurbo's `ParamCurveCurvature`. 3D: `κ = |r′ × r″|/|r′|³ ≥ 0`.
    ///
    /// Returns 0.0 where `r′(t) = 0` (see [`STALL_TOLERANCE`]): the limit is undefined or infinite
    /// there.
    ///
    /// If kurbo's `ParamCurveCurvature` is in scope too, the call is ambiguous: write
    /// `CurvatureAnalysis::curvature(&seg, t)`.
    fn curvature(&self, t: f64) -> f64 {
        self.to_bez().curvature(t)
    }

    /// The curvature vector at `t`: `r′ × (r″ × r′)/|r′|⁴`, of length |κ|, pointing to the centre
    /// of curvature (zero where κ = 0 or `r′(t) = 0`).
    fn curvature_vector(&self, t: f64) -> Self::Vector;

    /// All parameters in `(0, 1)` where `|κ|` has a local extremum, in increasing order.
    ///
    /// These are the sign changes of `d(κ²)/dt`, found as polynomial roots:
    ///
    /// - 2D: the roots of `(r′×r‴)(r′·r′) − 3(r′×r″)(r′·r″)` (`= |r′|⁵ dκ/dt`; degree ≤ 9 for
    ///   quartics, 5 for cubics, 1 for quadratics) — local maxima and minima of the signed κ —
    ///   **and** the inflections, the sign changes of `r′×r″` (κ = 0, minima of |κ|).
    /// - 3D (seed paper 002 eq. 13): the roots of `G′N − 3GN′` with `N = |r′|²`,
    ///   `G = |r′×r″|²` (degree ≤ 13 for quartics, 7 for cubics), which include any zero of κ of a
    ///   planar piece.
    ///
    /// Roots are polished with Newton steps on the unexpanded function (measured: within 1e-14 of
    /// a sign change of the exact function on random quartics); near a near-cusp the
    /// polynomials are re-expanded about it so that tiny values stay accurate. Stationary points
    /// without a sign change (double roots) are not extrema and are generally not reported.
    /// Empty for straight segments. Cusps (`r′ = 0`) are not included: see
    /// [`max_curvature`](Self::max_curvature).
    fn curvature_extrema(&self) -> Vec<f64> {
        self.to_bez().extrema().as_slice().to_vec()
    }

    /// The maximum of |κ| over `t ∈ [0, 1]` and every parameter where it is attained (seed paper
    /// 002, Algorithm 1): the candidates are `t = 0`, `t = 1`, the stationary points of
    /// [`curvature_extrema`](Self::curvature_extrema) and the cusps (`r′ = 0`), where the value
    /// is [`f64::INFINITY`] if |κ| grows without bound nearby.
    fn max_curvature(&self) -> CurvatureMax {
        self.to_bez().max_curvature()
    }
}

fn vec2(v: Vec3) -> Vec2 {
    Vec2::new(v.x, v.y)
}

macro_rules! impl_planar {
    ($ty:ty, |$s:ident| $pts:expr) => {
        impl Sealed for $ty {
            fn to_bez(&self) -> Bez {
                let $s = self;
                Bez::planar(&$pts)
            }
        }

        impl CurvatureAnalysis for $ty {
            type Vector = Vec2;

            fn curvature_vector(&self, t: f64) -> Vec2 {
                vec2(self.to_bez().curvature_vector(t))
            }
        }
    };
}

impl_planar!(Line, |s| [s.p0, s.p1]);
impl_planar!(QuadBez, |s| [s.p0, s.p1, s.p2]);
impl_planar!(CubicBez, |s| [s.p0, s.p1, s.p2, s.p3]);
impl_planar!(QuarticBez, |s| [s.p0, s.p1, s.p2, s.p3, s.p4]);

impl Sealed for PathSeg {
    fn to_bez(&self) -> Bez {
        match self {
            PathSeg::Line(l) => l.to_bez(),
            PathSeg::Quad(q) => q.to_bez(),
            PathSeg::Cubic(c) => c.to_bez(),
        }
    }
}

impl CurvatureAnalysis for PathSeg {
    type Vector = Vec2;

    fn curvature_vector(&self, t: f64) -> Vec2 {
        vec2(self.to_bez().curvature_vector(t))
    }
}

impl Sealed for SpaceBez {
    fn to_bez(&self) -> Bez {
        Bez::spatial(self.control_points())
    }
}

impl CurvatureAnalysis for SpaceBez {
    type Vector = Vec3;

    fn curvature_vector(&self, t: f64) -> Vec3 {
        self.to_bez().curvature_vector(t)
    }
}

/// Is `seg` straight to within rounding (control points coincident or collinear, see the
/// [module docs](self))? Then its curvature is 0 by convention, and
/// [`CurvatureAnalysis::max_curvature`] reports 0; `curvature` itself returns the rounding
/// noise of `r′ × r″`, which next to a reversal of direction (`|r′|` small) can be large.
pub(crate) fn is_straight<C: CurvatureAnalysis>(seg: &C) -> bool {
    seg.to_bez().is_straight()
}

/// The maximum of |κ| over all segments of a path, with every `(segment_index, t)` where it is
/// attained. Segment indices are those of [`BezPath::segments`] (closing lines included).
///
/// ```
/// use kappa::analysis::path_max_curvature;
/// use kurbo::BezPath;
///
/// let mut path = BezPath::new();
/// path.move_to((0.0, 0.0));
/// path.line_to((1.0, 0.0));
/// path.quad_to((2.0, 0.0), (2.0, 1.0));
/// let max = path_max_curvature(&path);
/// assert_eq!(max.params.len(), 1);
/// assert_eq!(max.params[0].0, 1);
/// ```
pub fn path_max_curvature(path: &BezPath) -> PathCurvatureMax {
    max_over(
        subpaths(path)
            .into_iter()
            .flat_map(|sp| sp.segs.into_iter().map(|(i, s)| (i, s.to_bez()))),
    )
}

/// The maximum of |κ| over a sequence of segments (for example the 3D segments of a spline),
/// with every `(index into segments, t)` where it is attained.
pub fn segments_max_curvature<C: CurvatureAnalysis>(segments: &[C]) -> PathCurvatureMax {
    max_over(segments.iter().enumerate().map(|(i, s)| (i, s.to_bez())))
}

fn max_over(segs: impl Iterator<Item = (usize, Bez)>) -> PathCurvatureMax {
    let per_seg: Vec<(usize, CurvatureMax)> = segs.map(|(i, b)| (i, b.max_curvature())).collect();
    let value = per_seg.iter().fold(0.0f64, |m, (_, c)| m.max(c.value));
    let threshold = value * (1.0 - ATTAINED_TOLERANCE);
    let mut params = Vec::new();
    for (i, m) in &per_seg {
        if m.value >= threshold {
            let b_params = m.params.iter().map(|&t| (*i, t));
            params.extend(b_params);
        }
    }
    PathCurvatureMax { value, params }
}

/// One subpath of a [`BezPath`]: its segments with their [`BezPath::segments`] indices.
pub(crate) struct Subpath {
    pub(crate) segs: Vec<(usize, PathSeg)>,
    /// Ended with `ClosePath`.
    pub(crate) closed: bool,
}

/// Split a path into subpaths, numbering segments exactly as [`BezPath::segments`] does (a
/// `ClosePath` adds a closing line unless the subpath already ends at its start). Unlike
/// `segments`, a leading `ClosePath` is skipped instead of panicking.
pub(crate) fn subpaths(path: &BezPath) -> Vec<Subpath> {
    let mut out = Vec::new();
    let mut cur = Subpath {
        segs: Vec::new(),
        closed: false,
    };
    let mut start_last: Option<(Point, Point)> = None;
    let mut index = 0;
    let flush = |cur: &mut Subpath, out: &mut Vec<Subpath>, closed: bool| {
        let segs = std::mem::take(&mut cur.segs);
        if !segs.is_empty() {
            out.push(Subpath { segs, closed });
        }
    };
    for &el in path.elements() {
        let first = match el {
            PathEl::MoveTo(p) | PathEl::LineTo(p) | PathEl::QuadTo(_, p) => p,
            PathEl::CurveTo(_, _, p) => p,
            PathEl::ClosePath => match start_last {
                Some((s, _)) => s,
                None => continue,
            },
        };
        let (start, last) = start_last.get_or_insert((first, first));
        let seg = match el {
            PathEl::MoveTo(p) => {
                flush(&mut cur, &mut out, false);
                *start = p;
                *last = p;
                continue;
            }
            PathEl::LineTo(p) => PathSeg::Line(Line::new(std::mem::replace(last, p), p)),
            PathEl::QuadTo(p1, p2) => {
                PathSeg::Quad(QuadBez::new(std::mem::replace(last, p2), p1, p2))
            }
            PathEl::CurveTo(p1, p2, p3) => {
                PathSeg::Cubic(CubicBez::new(std::mem::replace(last, p3), p1, p2, p3))
            }
            PathEl::ClosePath => {
                if *last != *start {
                    let s = *start;
                    cur.segs.push((
                        index,
                        PathSeg::Line(Line::new(std::mem::replace(last, s), s)),
                    ));
                    index += 1;
                }
                flush(&mut cur, &mut out, true);
                continue;
            }
        };
        cur.segs.push((index, seg));
        index += 1;
    }
    flush(&mut cur, &mut out, false);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::{ParamCurve, ParamCurveCurvature};

    fn assert_near(a: f64, b: f64, tol: f64) {
        assert!((a - b).abs() <= tol, "{a} vs {b} (tol {tol})");
    }

    #[test]
    fn quadbez_sign_is_left_positive_and_opposite_to_kurbo() {
        let q = QuadBez::new((0.0, 0.0), (1.0, 0.0), (1.0, 1.0));
        assert_near(CurvatureAnalysis::curvature(&q, 0.5), 2f64.sqrt(), 1e-14);
        for t in [0.1, 0.5, 0.9] {
            let ours = CurvatureAnalysis::curvature(&q, t);
            let kurbos = ParamCurveCurvature::curvature(&q, t);
            assert_near(ours, -kurbos, 1e-12);
        }
        // Mirror in the x axis: a right turn.
        let m = QuadBez::new((0.0, 0.0), (1.0, 0.0), (1.0, -1.0));
        assert_near(CurvatureAnalysis::curvature(&m, 0.5), -(2f64.sqrt()), 1e-14);
    }

    #[test]
    fn quadbez_curvature_vector_points_to_centre() {
        let q = QuadBez::new((0.0, 0.0), (1.0, 0.0), (1.0, 1.0));
        let k = q.curvature_vector(0.5);
        // Left turn heading (1, 1)/√2: the centre lies to the upper left.
        assert!(k.x < 0.0 && k.y > 0.0, "{k:?}");
        assert_near(k.hypot(), 2f64.sqrt(), 1e-14);
    }

    #[test]
    fn line_has_no_curvature() {
        let l = Line::new((0.0, 0.0), (3.0, 4.0));
        assert_eq!(CurvatureAnalysis::curvature(&l, 0.3), 0.0);
        assert!(l.curvature_extrema().is_empty());
        let m = l.max_curvature();
        assert_eq!(m.value, 0.0);
        assert_eq!(m.params, [0.0, 1.0]);
    }

    #[test]
    fn pathseg_matches_inner_segment() {
        let c = CubicBez::new((0.0, 0.0), (1.0, 2.0), (3.0, -1.0), (4.0, 1.0));
        let s = PathSeg::Cubic(c);
        assert_eq!(
            CurvatureAnalysis::curvature(&s, 0.3),
            CurvatureAnalysis::curvature(&c, 0.3)
        );
        assert_eq!(s.curvature_extrema(), c.curvature_extrema());
        assert_eq!(s.max_curvature(), c.max_curvature());
    }

    #[test]
    fn cubicbez_extrema_are_stationary_or_inflections() {
        let c = CubicBez::new((0.0, 0.0), (1.0, 2.0), (3.0, -1.0), (4.0, 1.0));
        let ex = c.curvature_extrema();
        assert!(!ex.is_empty());
        let h = 1e-6;
        for &t in &ex {
            let k = CurvatureAnalysis::curvature(&c, t);
            let dk = (CurvatureAnalysis::curvature(&c, t + h)
                - CurvatureAnalysis::curvature(&c, t - h))
                / (2.0 * h);
            assert!(k.abs() < 1e-9 || dk.abs() < 1e-5, "t={t} k={k} dk={dk}");
        }
    }

    #[test]
    fn subpaths_number_segments_like_kurbo() {
        let mut p = BezPath::new();
        p.move_to((0.0, 0.0));
        p.line_to((1.0, 0.0));
        p.quad_to((2.0, 0.0), (2.0, 1.0));
        p.close_path();
        p.move_to((5.0, 5.0));
        p.curve_to((6.0, 5.0), (6.0, 6.0), (5.0, 6.0));
        p.line_to((5.0, 5.0));
        p.close_path();
        let sps = subpaths(&p);
        assert_eq!(sps.len(), 2);
        assert!(sps[0].closed && sps[1].closed);
        let ours: Vec<PathSeg> = sps
            .iter()
            .flat_map(|s| s.segs.iter().map(|x| x.1))
            .collect();
        let kurbos: Vec<PathSeg> = p.segments().collect();
        assert_eq!(ours, kurbos);
        let idx: Vec<usize> = sps
            .iter()
            .flat_map(|s| s.segs.iter().map(|x| x.0))
            .collect();
        assert_eq!(idx, (0..kurbos.len()).collect::<Vec<_>>());
        assert_eq!(sps[0].segs.len(), 3); // closing line added
        assert_eq!(sps[1].segs.len(), 2); // already closed: no closing line
    }

    #[test]
    fn subpaths_leading_closepath_does_not_panic() {
        // `Extend` does not check the MoveTo invariant, so such paths can exist.
        let mut p = BezPath::new();
        p.extend([PathEl::ClosePath, PathEl::LineTo((1.0, 1.0).into())]);
        let sps = subpaths(&p);
        assert_eq!(sps.len(), 1);
        assert_eq!(sps[0].segs[0].1.start(), Point::new(1.0, 1.0));
    }
}
