//! Export of space curves: exact JSON (feature `serde`) and sampled OBJ polylines.

use core::fmt::Write as _;

use crate::analysis::SpaceBez;
use crate::{Error, Point3};

use super::SpaceCurve;

/// The deepest bisection of a segment when flattening for [`SpaceCurve::to_obj`]:
/// at most 2¹⁶ lines per segment.
const FLATTEN_MAX_DEPTH: usize = 16;

impl SpaceCurve {
    /// The curve as a polyline within `tolerance` of it: each segment is bisected until all
    /// its control points lie within `tolerance` of the chord, which bounds the distance of
    /// the curve itself (it lies in the convex hull of its control points). The points are
    /// in order along the curve, the first and last ones shared by closed curves only once.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidOption`] for a tolerance that is not positive and finite.
    pub fn flatten(&self, tolerance: f64) -> Result<Vec<Point3>, Error> {
        if !(tolerance > 0.0 && tolerance.is_finite()) {
            return Err(Error::InvalidOption(
                "the polyline tolerance must be positive and finite",
            ));
        }
        let mut out = Vec::new();
        if let Some(first) = self.segments().first() {
            out.push(first.start());
        }
        for s in self.segments() {
            flatten_rec(s, tolerance, 0, &mut out);
        }
        if self.is_closed() && out.len() > 1 {
            out.pop();
        }
        Ok(out)
    }

    /// A Wavefront OBJ file of the [`flatten`](Self::flatten)ed curve: a comment, one `v x y z`
    /// line per point and one polyline element `l 1 2 … n` (ending with `1` again for closed
    /// curves), which 3D tools (Blender, Rhino, MeshLab) read as a curve. Numbers are written
    /// in Rust's shortest round-trip form.
    ///
    /// # Errors
    ///
    /// As for [`flatten`](Self::flatten).
    pub fn to_obj(&self, tolerance: f64) -> Result<String, Error> {
        let pts = self.flatten(tolerance)?;
        let mut out = String::new();
        let _ = writeln!(
            out,
            "# kappa space curve: {} segments, polyline within {tolerance} of the curve",
            self.segments().len()
        );
        for p in &pts {
            let _ = writeln!(out, "v {} {} {}", p.x, p.y, p.z);
        }
        out.push('l');
        for i in 1..=pts.len() {
            let _ = write!(out, " {i}");
        }
        if self.is_closed() && !pts.is_empty() {
            out.push_str(" 1");
        }
        out.push('\n');
        Ok(out)
    }
}

/// Appends the end points of a polyline for `s` within `tolerance` (its start is already in
/// `out`).
fn flatten_rec(s: &SpaceBez, tolerance: f64, depth: usize, out: &mut Vec<Point3>) {
    let pts = s.control_points();
    let (a, b) = (s.start(), s.end());
    let flat = pts[1..pts.len() - 1]
        .iter()
        .all(|&p| distance_to_chord(p, a, b) <= tolerance);
    if flat || depth >= FLATTEN_MAX_DEPTH {
        out.push(b);
        return;
    }
    let (l, r) = s.subdivide();
    flatten_rec(&l, tolerance, depth + 1, out);
    flatten_rec(&r, tolerance, depth + 1, out);
}

/// The distance from `p` to the segment `a b`.
fn distance_to_chord(p: Point3, a: Point3, b: Point3) -> f64 {
    let ab = b - a;
    let len2 = ab.hypot2();
    let s = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * s)
}

#[cfg(feature = "serde")]
mod json {
    use serde::Serialize;

    use super::SpaceCurve;
    use crate::Error;

    /// One segment of the JSON form.
    #[derive(Serialize)]
    struct SegmentJson {
        degree: usize,
        points: Vec<[f64; 3]>,
    }

    /// One joint of the JSON form.
    #[derive(Serialize)]
    struct JointJson {
        curvature_vector_gap: f64,
    }

    /// The JSON form of a space curve.
    #[derive(Serialize)]
    struct CurveJson {
        segments: Vec<SegmentJson>,
        t_max: Vec<f64>,
        joints: Vec<JointJson>,
    }

    impl SpaceCurve {
        /// The curve as one line of JSON:
        ///
        /// ```text
        /// {"segments": [{"degree": 2 | 4, "points": [[x, y, z], …]}, …],
        ///  "t_max": [u, …], "joints": [{"curvature_vector_gap": e}, …]}
        /// ```
        ///
        /// `segments` are the exact Bézier segments in order along the curve (3 or 5 control
        /// points); `t_max` holds, per point with a peak ([`point_params`]), its curve
        /// parameter `u = segment + t`; `joints` holds, per joint of the chain
        /// ([`continuity`] order), the relative curvature-vector gap of
        /// [`curvature_vector_gaps`]. Numbers are written exactly (shortest round-trip form).
        ///
        /// [`point_params`]: SpaceCurve::point_params
        /// [`continuity`]: SpaceCurve::continuity
        /// [`curvature_vector_gaps`]: SpaceCurve::curvature_vector_gaps
        ///
        /// # Errors
        ///
        /// [`Error::NonFiniteCurve`] if a number is not finite (JSON cannot hold it).
        pub fn to_json(&self) -> Result<String, Error> {
            let segments: Vec<SegmentJson> = self
                .segments()
                .iter()
                .map(|s| SegmentJson {
                    degree: s.degree(),
                    points: s.control_points().iter().map(|&p| p.into()).collect(),
                })
                .collect();
            for (segment, s) in segments.iter().enumerate() {
                if !s.points.iter().flatten().all(|v| v.is_finite()) {
                    return Err(Error::NonFiniteCurve { segment });
                }
            }
            let value = CurveJson {
                segments,
                t_max: self
                    .point_params()
                    .iter()
                    .map(|&(i, t)| i as f64 + t)
                    .collect(),
                joints: self
                    .curvature_vector_gaps()
                    .into_iter()
                    .map(|e| JointJson {
                        curvature_vector_gap: e,
                    })
                    .collect(),
            };
            serde_json::to_string(&value).map_err(|_| Error::NonFiniteCurve { segment: 0 })
        }
    }
}
