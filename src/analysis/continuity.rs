//! Geometric continuity at the joints of consecutive segments.

use kurbo::BezPath;

use super::bez::{Bez, Sealed};
use super::{subpaths, CurvatureAnalysis};

/// How well two consecutive segments join: the end of `a` (t = 1) against the start of `b`
/// (t = 0). All fields are non-negative; zero everywhere is a G2 joint.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Continuity {
    /// Distance between the end point of `a` and the start point of `b` (G0 when 0).
    pub position_gap: f64,
    /// Angle in radians, in `[0, π]`, between the end tangent of `a` and the start tangent of `b`
    /// (G1 when 0). A tangent is taken from the end point to the nearest *distinct* control
    /// point, so coincident handles do not matter; it is 0 if either segment has all its control
    /// points coincident (no tangent).
    pub tangent_angle: f64,
    /// `| |κ_a(1)| − |κ_b(0)| |`: the jump in the magnitude of the curvature (κ-curves match it
    /// even at inflections).
    pub curvature_diff: f64,
    /// 2D (both segments planar): `|κ_a(1) − κ_b(0)|` with signed curvatures. 3D (either segment
    /// a [`SpaceBez`](super::SpaceBez)): `|k_a(1) − k_b(0)|` with the curvature vectors. For a
    /// G1 joint both are the norm of the jump of the curvature vector (G2 when 0).
    pub curvature_vector_diff: f64,
}

/// The continuity at the joint "end of `a`" → "start of `b`".
///
/// The end curvatures are those of [`CurvatureAnalysis::curvature`], so an end where
/// `r′ = 0` (coincident end control points) contributes 0.
///
/// ```
/// use kappa::analysis::continuity;
/// use kurbo::{CubicBez, ParamCurve};
///
/// let c = CubicBez::new((0.0, 0.0), (1.0, 2.0), (3.0, -1.0), (4.0, 1.0));
/// let (a, b) = c.subdivide();
/// let j = continuity(&a, &b);
/// assert!(j.position_gap < 1e-12 && j.tangent_angle < 1e-12 && j.curvature_diff < 1e-9);
/// ```
pub fn continuity<A: CurvatureAnalysis, B: CurvatureAnalysis>(a: &A, b: &B) -> Continuity {
    joint(&a.to_bez(), &b.to_bez())
}

fn joint(a: &Bez, b: &Bez) -> Continuity {
    let position_gap = (a.end() - b.start()).length();
    let ta = a.end_tangent(true);
    let tb = b.end_tangent(false);
    let tangent_angle = ta.cross(tb).length().atan2(ta.dot(tb));
    let ka = a.curvature(1.0);
    let kb = b.curvature(0.0);
    let curvature_diff = (ka.abs() - kb.abs()).abs();
    let curvature_vector_diff = if a.is_planar() && b.is_planar() {
        (ka - kb).abs()
    } else {
        (a.curvature_vector(1.0) - b.curvature_vector(0.0)).length()
    };
    Continuity {
        position_gap,
        tangent_angle,
        curvature_diff,
        curvature_vector_diff,
    }
}

/// The continuity at one joint of a path or spline.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PathJoint {
    /// Index of the segment that ends at the joint.
    pub before: usize,
    /// Index of the segment that starts at the joint.
    pub after: usize,
    /// The measurements.
    pub continuity: Continuity,
}

/// The continuity at every joint of a path: between consecutive segments of each subpath and,
/// for a subpath ended by `ClosePath`, between its last segment (the closing line, if kurbo adds
/// one) and its first. Segment indices are those of [`BezPath::segments`]. Subpaths that are
/// not closed have no joint between their ends, even if the ends coincide.
pub fn path_continuity(path: &BezPath) -> Vec<PathJoint> {
    let mut out = Vec::new();
    for sp in subpaths(path) {
        let segs: Vec<(usize, Bez)> = sp.segs.iter().map(|(i, s)| (*i, s.to_bez())).collect();
        push_joints(&segs, sp.closed, &mut out);
    }
    out
}

/// The continuity at every joint of a sequence of segments (for example the 3D segments of a
/// spline), with `closed` adding the joint from the last segment to the first.
pub fn segments_continuity<C: CurvatureAnalysis>(segments: &[C], closed: bool) -> Vec<PathJoint> {
    let segs: Vec<(usize, Bez)> = segments.iter().map(|s| s.to_bez()).enumerate().collect();
    let mut out = Vec::new();
    push_joints(&segs, closed, &mut out);
    out
}

fn push_joints(segs: &[(usize, Bez)], closed: bool, out: &mut Vec<PathJoint>) {
    let mut emit = |a: &(usize, Bez), b: &(usize, Bez)| {
        out.push(PathJoint {
            before: a.0,
            after: b.0,
            continuity: joint(&a.1, &b.1),
        });
    };
    for w in segs.windows(2) {
        emit(&w[0], &w[1]);
    }
    if closed {
        if let (Some(last), Some(first)) = (segs.last(), segs.first()) {
            emit(last, first);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::SpaceBez;
    use crate::Point3;
    use kurbo::{CubicBez, Line, QuadBez};

    #[test]
    fn continuity_corner_angle() {
        let a = Line::new((0.0, 0.0), (1.0, 0.0));
        let b = Line::new((1.0, 0.0), (1.0, 1.0));
        let j = continuity(&a, &b);
        assert_eq!(j.position_gap, 0.0);
        assert!((j.tangent_angle - core::f64::consts::FRAC_PI_2).abs() < 1e-15);
        assert_eq!(j.curvature_diff, 0.0);
    }

    #[test]
    fn continuity_degenerate_handle_uses_next_point() {
        // End handle retracted onto the end point: the end tangent is p3 − p1 = (1, 1), 45° from
        // the following line (a zero tangent would give 0).
        let a = CubicBez::new((0.0, 0.0), (1.0, 0.0), (2.0, 1.0), (2.0, 1.0));
        let b = Line::new((2.0, 1.0), (3.0, 1.0));
        let j = continuity(&a, &b);
        assert!(
            (j.tangent_angle - core::f64::consts::FRAC_PI_4).abs() < 1e-15,
            "{j:?}"
        );
        // Both handles retracted at the joint.
        let c = CubicBez::new((2.0, 1.0), (2.0, 1.0), (2.0, 1.0), (2.0, 5.0));
        let j = continuity(&a, &c);
        assert!(
            (j.tangent_angle - core::f64::consts::FRAC_PI_4).abs() < 1e-15,
            "{j:?}"
        );
    }

    #[test]
    fn continuity_inflection_joint_2d() {
        // Two arcs turning opposite ways with equal |κ|: G1, |κ| equal, signed κ differ.
        let a = QuadBez::new((-1.0, 1.0), (-0.5, 0.0), (0.0, 0.0));
        let b = QuadBez::new((0.0, 0.0), (1.0, 0.0), (2.0, -1.0));
        let j = continuity(&a, &b);
        assert!(j.tangent_angle < 1e-15);
        let ka = CurvatureAnalysis::curvature(&a, 1.0);
        let kb = CurvatureAnalysis::curvature(&b, 0.0);
        assert!(ka > 0.0 && kb < 0.0, "{ka} {kb}");
        assert!((j.curvature_vector_diff - (ka - kb)).abs() < 1e-15);
    }

    #[test]
    fn continuity_3d_uses_curvature_vectors() {
        let a = SpaceBez::quad(
            Point3::new(0.0, 0.0, 1.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(2.0, 0.0, 0.0),
        );
        let b = SpaceBez::quad(
            Point3::new(2.0, 0.0, 0.0),
            Point3::new(3.0, 0.0, 0.0),
            Point3::new(4.0, 1.0, 0.0),
        );
        let j = continuity(&a, &b);
        assert!(j.tangent_angle < 1e-15);
        let ka = a.curvature_vector(1.0);
        let kb = b.curvature_vector(0.0);
        assert!((j.curvature_vector_diff - (ka - kb).length()).abs() < 1e-15);
        // Perpendicular curvature vectors of equal length: G1 with equal |κ| but not G2.
        assert!(j.curvature_diff < 1e-12);
        assert!(j.curvature_vector_diff > 0.1);
    }
}
