//! The κ-space curve: a chain of exact quadratic and quartic Bézier segments in 3D.

use crate::analysis::{
    segments_continuity, segments_max_curvature, CurvatureAnalysis, PathCurvatureMax, PathJoint,
    SpaceBez,
};
use crate::{Error, Point3, Scheme, Shape, Solver3, Spline3, Vec3};

use super::replace::{self, GammaPrime, Quad};
use super::{Gamma, PeakAtJoint, Replace, SpaceOptions, MIN_REPLACED};

/// A G2 space curve through 3D points: the quadratic κ-curve with a quartic at every joint
/// (seed 004). See the [module docs](super).
///
/// ```
/// use kappa::space::{SpaceCurve, SpaceOptions};
/// use kappa::Point3;
///
/// let helix: Vec<Point3> = (0..8)
///     .map(|i| {
///         let th = 0.9 * i as f64;
///         Point3::new(50.0 * th.cos(), 50.0 * th.sin(), 12.0 * th)
///     })
///     .collect();
/// let curve = SpaceCurve::new(&helix, false, &SpaceOptions::default())?;
/// // G2: the curvature vectors agree at every joint (relative gap).
/// assert!(curve.curvature_vector_gaps().iter().all(|&g| g < 1e-9));
/// // Every interior point lies on the curve, at the parameter of its |κ| peak.
/// assert!(curve.missed_points().is_empty());
/// for (&(segment, t), p) in curve.point_params().iter().zip(&helix[1..]) {
///     assert!(curve.segments()[segment].eval(t).distance(*p) < 1e-9);
/// }
/// # Ok::<(), kappa::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct SpaceCurve {
    closed: bool,
    segments: Vec<SpaceBez>,
    pieces: Vec<Piece>,
    joints: Vec<Joint>,
    /// Per κ-segment: the output segment and parameter of its input point.
    peaks: Vec<(usize, f64)>,
    /// Input points given up at joints ([`PeakAtJoint::Replace`]): κ-segment and distance.
    missed: Vec<(usize, f64)>,
    /// Chain joints (index of the segment before them) where the κ-curve's joint is kept.
    kept: Vec<usize>,
    /// The κ-curve the replacement started from.
    base: Spline3,
}

/// What an output segment of a [`SpaceCurve`] is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Piece {
    /// The piece `t ∈ [start, end]` of the κ-curve's quadratic segment `source`.
    Quadratic {
        /// Index into the κ-curve's segments ([`SpaceCurve::spline`]).
        source: usize,
        /// Start parameter on that segment.
        start: f64,
        /// End parameter on that segment.
        end: f64,
    },
    /// The quartic replacing joint `joint` (an index into [`SpaceCurve::joints`]).
    Quartic {
        /// Index into [`SpaceCurve::joints`].
        joint: usize,
    },
}

/// A joint of the κ-curve, between its segments `before` and `before + 1` (modulo the
/// segment count for the closing joint of a closed curve).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Joint {
    /// Index of the κ-segment ending at the joint.
    pub before: usize,
    /// The κ-curve's joint ratio: the joint is `(1−λ) c_{i,1} + λ c_{i+1,1}` (seed 004 eq. 7).
    pub lambda: f64,
    /// Start of the replaced piece on segment `before`, after cutting at that segment's input
    /// point (at `t = ½` if the point was given up, see [`PeakAtJoint`]); 1 for a kept joint.
    pub t1: f64,
    /// End of the replaced piece on segment `before + 1`, cut likewise; 0 for a kept joint.
    pub t2: f64,
    /// The replacement, or `None` where the joint was kept: no replacement was asked for, an
    /// input point sits at the joint and [`PeakAtJoint::Keep`] was chosen, or a quadratic
    /// stalls at the joint (`λ ∈ {0, 1}`, no quartic exists).
    pub quartic: Option<JointQuartic>,
}

/// The quartic at a joint (seed 004 eqs. 11–18).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointQuartic {
    /// Index of the quartic in [`SpaceCurve::segments`].
    pub segment: usize,
    /// `γ`: `Q2 = (1−γ) c_{i,1} + γ c_{i+1,1}` (eq. 14).
    pub gamma: f64,
    /// `λ′`, the joint ratio on the replaced pieces (eq. 15).
    pub lambda_prime: f64,
    /// `γ′`: `Q2 = (1−γ′) B + γ′ C` (eq. 16).
    pub gamma_prime: f64,
    /// `a′`: `Q1 = (1−a′) Q0 + a′ B` (eq. 17).
    pub a: f64,
    /// `b′`: `Q3 = (1−b′) C + b′ Q4` (eq. 18).
    pub b: f64,
}

/// An interior curvature extremum of a replacement quartic: the extremum the quartic adds
/// to the curve (seed 004 §3.2, Fig. 7).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuarticExtremum {
    /// Index into [`SpaceCurve::joints`].
    pub joint: usize,
    /// Index of the quartic in [`SpaceCurve::segments`].
    pub segment: usize,
    /// Parameter on the quartic, in `(0, 1)`.
    pub t: f64,
    /// The curvature there.
    pub curvature: f64,
}

impl SpaceCurve {
    /// The κ-space curve through `points`: a κ-curve from [`Solver3`] with the options'
    /// [`SolveOptions`](crate::SolveOptions), then [`SpaceCurve::from_spline`].
    ///
    /// # Errors
    ///
    /// Everything [`Solver3::solve`](crate::SolverN::solve) reports (too few points, NaN,
    /// repeated points, collinear closed input, non-convergence) and the option errors of
    /// [`SpaceCurve::from_spline`].
    pub fn new(
        points: &[Point3],
        closed: bool,
        options: &SpaceOptions,
    ) -> Result<SpaceCurve, Error> {
        validate_replace(options.replace)?;
        let spline = Solver3::with_options(options.solve).solve(
            points,
            closed,
            Scheme::Kappa,
            &Shape::Neutral,
        )?;
        let mut curve = SpaceCurve::from_spline(spline, options)?;
        if !closed && points.len() == 2 {
            // Two points make one straight segment with no input point inside it, so no
            // point has a peak (its segment's `t_max` is just the midpoint).
            curve.peaks.clear();
        }
        Ok(curve)
    }

    /// The κ-space curve made from a solved 3D κ-curve (for example from a [`Solver3`] kept
    /// for warm re-solves).
    ///
    /// # Errors
    ///
    /// [`Error::InvalidOption`] for an εκ-curve (the replacement needs quadratics), for a
    /// [`Replace::Partial`] outside `0 ≤ t1 ≤ 1 − MIN_REPLACED`, `MIN_REPLACED ≤ t2 ≤ 1`
    /// ([`MIN_REPLACED`](super::MIN_REPLACED)), and for a
    /// [`Gamma::PerJoint`] list whose length is not the number of joints;
    /// [`Error::GammaOutOfRange`] for a `γ` outside its joint's interval.
    pub fn from_spline(spline: Spline3, options: &SpaceOptions) -> Result<SpaceCurve, Error> {
        if spline.scheme() != Scheme::Kappa {
            return Err(Error::InvalidOption(
                "space curves are built from kappa curves (quadratic segments)",
            ));
        }
        validate_replace(options.replace)?;
        let quads: Vec<Quad> = spline.segments().iter().map(|s| s.q).collect();
        let t_max: Vec<f64> = spline.segments().iter().map(|s| s.t_max).collect();
        let n = quads.len();
        let closed = spline.is_closed();
        let joint_count = if closed { n } else { n.saturating_sub(1) };
        if let Gamma::PerJoint(list) = &options.gamma {
            if list.len() != joint_count {
                return Err(Error::InvalidOption(
                    "the gamma list needs one value per joint",
                ));
            }
        }
        let (t1_req, t2_req) = match options.replace {
            Replace::None => (1.0, 0.0),
            Replace::Partial { t1, t2 } => (t1, t2),
        };
        // Per κ-segment the parameter that separates the ranges of its two joints: the input
        // point, unless it sits at a replaced joint (see `at_joint`).
        let has_left = |j: usize| closed || j > 0;
        let has_right = |j: usize| j < joint_count;
        let mut split = t_max.clone();
        let mut given_up = Vec::new();
        let mut kept = vec![false; joint_count];
        if options.replace != Replace::None {
            for j in 0..n {
                let at_start = has_left(j) && at_joint(t_max[j], t2_req);
                let at_end = has_right(j) && at_joint(1.0 - t_max[j], 1.0 - t1_req);
                if !(at_start || at_end) {
                    continue;
                }
                match options.at_joint {
                    PeakAtJoint::Replace => {
                        split[j] = 0.5;
                        given_up.push(j);
                    }
                    PeakAtJoint::Keep => {
                        if at_start {
                            kept[(j + n - 1) % n] = true;
                        }
                        if at_end {
                            kept[j] = true;
                        }
                    }
                }
            }
        }
        // Per κ-segment the ends of the piece left between its two joints' ranges; a piece
        // shorter than `MIN_REPLACED` is absorbed (both quartics meet at the split point):
        // its curvature, from control points that nearly coincide, would be rounding.
        let piece_ends = |k: usize| -> (f64, f64) {
            let (lo, hi) = (t2_req.min(split[k]), t1_req.max(split[k]));
            if has_left(k) && has_right(k) && hi - lo < MIN_REPLACED {
                (split[k], split[k])
            } else {
                (lo, hi)
            }
        };
        // Per joint: the replaced ranges, cut at the split points, and the quartic.
        let mut joints = Vec::with_capacity(joint_count);
        let mut quartics: Vec<Option<[Point3; 5]>> = Vec::with_capacity(joint_count);
        for j in 0..joint_count {
            let next = (j + 1) % n;
            let (left, right) = (&quads[j], &quads[next]);
            let lambda = joint_lambda(left, right);
            let (t1, t2) = if kept[j] {
                (1.0, 0.0)
            } else {
                (piece_ends(j).1, piece_ends(next).0)
            };
            let mut joint = Joint {
                before: j,
                lambda,
                t1,
                t2,
                quartic: None,
            };
            let mut points = None;
            if t1 < 1.0 && t2 > 0.0 {
                let gp = match &options.gamma {
                    Gamma::Lambda => Some(GammaPrime::Lambda),
                    Gamma::Optimized => {
                        replace::optimal_gamma_prime(left, right, t1, t2).map(GammaPrime::Value)
                    }
                    Gamma::PerJoint(list) => {
                        let value = list[j];
                        let (min, max) = replace::gamma_range(lambda, t1, t2);
                        if !(value > min && value < max) {
                            return Err(Error::GammaOutOfRange {
                                joint: j,
                                value,
                                min,
                                max,
                            });
                        }
                        Some(GammaPrime::Value(replace::gamma_prime(
                            value, lambda, t1, t2,
                        )))
                    }
                };
                if let Some((q, rep)) = gp.and_then(|g| replace::quartic(left, right, t1, t2, g)) {
                    joint.quartic = Some(JointQuartic {
                        segment: 0,
                        gamma: match gp {
                            Some(GammaPrime::Lambda) => lambda,
                            _ => replace::gamma_from_prime(rep.gamma_prime, lambda, t1, t2),
                        },
                        lambda_prime: rep.lambda_prime,
                        gamma_prime: rep.gamma_prime,
                        a: rep.a,
                        b: rep.b,
                    });
                    points = Some(q);
                }
            }
            if points.is_none() {
                // Kept joint: the quadratics run to it.
                joint.t1 = 1.0;
                joint.t2 = 0.0;
            }
            joints.push(joint);
            quartics.push(points);
        }
        // The chain: per κ-segment its remaining piece, then the quartic of the joint after it.
        let mut segments = Vec::with_capacity(n + joint_count);
        let mut pieces = Vec::with_capacity(n + joint_count);
        let mut peaks = Vec::with_capacity(n);
        let mut kept_chain = Vec::new();
        for j in 0..n {
            let prev = if closed {
                Some((j + n - 1) % n)
            } else {
                j.checked_sub(1)
            };
            let start = prev.map_or(0.0, |p| joints[p].t2);
            let end = if j < joint_count { joints[j].t1 } else { 1.0 };
            if end > start {
                let mut piece = replace::quad_piece(&quads[j], start, end);
                // Share the quartics' end points exactly.
                if let Some(q) = prev.and_then(|p| quartics[p]) {
                    piece[0] = q[4];
                }
                if let Some(q) = quartics.get(j).copied().flatten() {
                    piece[2] = q[0];
                }
                if start == 0.0 {
                    piece[0] = quads[j][0];
                }
                if end == 1.0 {
                    piece[2] = quads[j][2];
                }
                peaks.push((segments.len(), (t_max[j] - start) / (end - start)));
                segments.push(SpaceBez::quad(piece[0], piece[1], piece[2]));
                pieces.push(Piece::Quadratic {
                    source: j,
                    start,
                    end,
                });
            } else if quartics.get(j).copied().flatten().is_some() {
                // Both neighbours replaced up to the input point: it starts the next quartic.
                peaks.push((segments.len(), 0.0));
            } else {
                // The peak sits at the very end of the segment (t_max = 1) and the joint
                // after it was kept: it ends the quartic before it, placed below.
                peaks.push((usize::MAX, 1.0));
            }
            if let Some(q) = quartics.get(j).copied().flatten() {
                if let Some(jq) = &mut joints[j].quartic {
                    jq.segment = segments.len();
                }
                segments.push(SpaceBez::quartic(q[0], q[1], q[2], q[3], q[4]));
                pieces.push(Piece::Quartic { joint: j });
            } else if j < joint_count {
                // A kept joint: it ends the last segment so far (for the first joint of a
                // closed curve whose quadratic the quartic before it took whole, the last
                // segment of the chain, fixed below).
                kept_chain.push(segments.len().wrapping_sub(1));
            }
        }
        for k in &mut kept_chain {
            if *k == usize::MAX {
                *k = segments.len() - 1;
            }
        }
        kept_chain.sort_unstable();
        // Points given up: the nearest point of the quartic that replaced them.
        let mut missed = Vec::with_capacity(given_up.len());
        for &j in &given_up {
            let p = replace::quad_eval(&quads[j], t_max[j]);
            // Where the point is now: on its own quadratic piece, if the joint it sits at
            // turned out to be kept (no quartic exists there).
            let (seg, t) = peaks[j];
            let here = if seg == usize::MAX || !(0.0..=1.0).contains(&t) {
                f64::INFINITY
            } else {
                segments[seg].eval(t).distance(p)
            };
            let mut best = (usize::MAX, 0.0, here);
            let prev = if closed {
                Some((j + n - 1) % n)
            } else {
                j.checked_sub(1)
            };
            for joint in [prev, (j < joint_count).then_some(j)].into_iter().flatten() {
                if let Some(q) = joints[joint].quartic {
                    let (t, d) = nearest(&segments[q.segment], p);
                    if d < best.2 {
                        best = (q.segment, t, d);
                    }
                }
            }
            if best.0 != usize::MAX {
                peaks[j] = (best.0, best.1);
                missed.push((j, best.2));
            }
        }
        for (j, peak) in peaks.iter_mut().enumerate() {
            if peak.0 == usize::MAX {
                let prev = (j + n - 1) % n;
                peak.0 = joints
                    .get(prev)
                    .and_then(|p| p.quartic)
                    .map_or(0, |q| q.segment);
            }
        }
        Ok(SpaceCurve {
            closed,
            segments,
            pieces,
            joints,
            peaks,
            missed,
            kept: kept_chain,
            base: spline,
        })
    }

    /// Whether the curve is closed.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// The segments in order along the curve: quadratics (degree 2, pieces of the κ-curve)
    /// and quartics (degree 4, one per replaced joint). A closed curve's last segment ends
    /// where its first starts.
    pub fn segments(&self) -> &[SpaceBez] {
        &self.segments
    }

    /// What each segment is, in the order of [`segments`](Self::segments).
    pub fn pieces(&self) -> &[Piece] {
        &self.pieces
    }

    /// The joints of the κ-curve and their replacements.
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// The κ-curve the replacement started from.
    pub fn spline(&self) -> &Spline3 {
        &self.base
    }

    /// Where the input points are: `(segment, t)` per κ-segment, i.e. per input point of a
    /// closed curve and per interior input point of an open one. The curve's |κ| peaks there
    /// on the quadratic piece holding the point (for a point given up at a joint, see
    /// [`missed_points`](Self::missed_points), it is the nearest point of the curve).
    pub fn point_params(&self) -> &[(usize, f64)] {
        &self.peaks
    }

    /// The input points that were given up ([`PeakAtJoint::Replace`]): per such point its
    /// κ-segment index and its distance from the curve, whose nearest point
    /// [`point_params`](Self::point_params) then gives. Empty when every point is
    /// interpolated.
    pub fn missed_points(&self) -> &[(usize, f64)] {
        &self.missed
    }

    /// The joints of the chain where the κ-curve's own joint is kept (no replacement was
    /// asked for, [`PeakAtJoint::Keep`] kept an input point there, or a quadratic stalls at
    /// it): each as the index of the segment before it, as in the `before` of
    /// [`continuity`](Self::continuity). These joints are G1 with equal |κ| but not G2 (the
    /// curvature vectors lie in the two quadratics' planes); every other joint is G2.
    pub fn kept_joints(&self) -> &[usize] {
        &self.kept
    }

    /// The number of segments, `n`: the curve's parameter `u` runs over `[0, n]`.
    pub fn len(&self) -> usize {
        self.segments.len()
    }

    /// Whether the curve has no segments (never true for a solved curve).
    pub fn is_empty(&self) -> bool {
        self.segments.is_empty()
    }

    /// The segment and its own parameter at the curve parameter `u ∈ [0, n]` (clamped).
    pub fn locate(&self, u: f64) -> (usize, f64) {
        let n = self.segments.len();
        if n == 0 {
            return (0, 0.0);
        }
        let u = if u.is_nan() {
            0.0
        } else {
            u.clamp(0.0, n as f64)
        };
        let i = (u.floor() as usize).min(n - 1);
        (i, u - i as f64)
    }

    fn at(&self, u: f64) -> (&SpaceBez, f64) {
        let (i, t) = self.locate(u);
        (&self.segments[i], t)
    }

    /// The point at `u`.
    pub fn eval(&self, u: f64) -> Point3 {
        let (s, t) = self.at(u);
        s.eval(t)
    }

    /// The first derivative `r′(u)`.
    pub fn deriv(&self, u: f64) -> Vec3 {
        let (s, t) = self.at(u);
        s.deriv().eval(t).to_vec3()
    }

    /// The second derivative `r″(u)`.
    pub fn deriv2(&self, u: f64) -> Vec3 {
        let (s, t) = self.at(u);
        s.deriv().deriv().eval(t).to_vec3()
    }

    /// The curvature `|r′ × r″| / |r′|³` at `u`.
    pub fn curvature(&self, u: f64) -> f64 {
        let (s, t) = self.at(u);
        CurvatureAnalysis::curvature(s, t)
    }

    /// The curvature vector at `u` (length κ, towards the centre of curvature).
    pub fn curvature_vector(&self, u: f64) -> Vec3 {
        let (s, t) = self.at(u);
        s.curvature_vector(t)
    }

    /// The torsion at `u` ([`SpaceBez::torsion`]): 0 on the quadratics, which are planar.
    pub fn torsion(&self, u: f64) -> f64 {
        let (s, t) = self.at(u);
        s.torsion(t)
    }

    /// The arc length of the whole curve, to within `accuracy` (absolute).
    pub fn arclen(&self, accuracy: f64) -> f64 {
        let per = accuracy / self.segments.len().max(1) as f64;
        self.segments.iter().map(|s| s.arclen(per)).sum()
    }

    /// The continuity at every joint of the chain (the closing joint included for closed
    /// curves), measured by [`crate::analysis`].
    pub fn continuity(&self) -> Vec<PathJoint> {
        segments_continuity(&self.segments, self.closed)
    }

    /// The relative curvature-vector gap at every joint of the chain, in the order of
    /// [`continuity`](Self::continuity): `|k_a(1) − k_b(0)| / max(|k_a(1)|, |k_b(0)|)`
    /// (0 where both curvatures are 0).
    pub fn curvature_vector_gaps(&self) -> Vec<f64> {
        self.continuity()
            .iter()
            .map(|j| {
                let ka = CurvatureAnalysis::curvature(&self.segments[j.before], 1.0);
                let kb = CurvatureAnalysis::curvature(&self.segments[j.after], 0.0);
                let scale = ka.max(kb);
                if scale > 0.0 {
                    j.continuity.curvature_vector_diff / scale
                } else {
                    // Straight on both sides: what is left of the vectors is rounding.
                    0.0
                }
            })
            .collect()
    }

    /// The maximum curvature over the whole curve and every `(segment, t)` where it is
    /// attained.
    pub fn max_curvature(&self) -> PathCurvatureMax {
        segments_max_curvature(&self.segments)
    }

    /// The interior curvature extrema of every replacement quartic, in order: the extrema
    /// the replacement adds (seed 004 Fig. 7).
    pub fn quartic_extrema(&self) -> Vec<QuarticExtremum> {
        let mut out = Vec::new();
        for (joint, j) in self.joints.iter().enumerate() {
            if let Some(q) = &j.quartic {
                let s = &self.segments[q.segment];
                for t in s.curvature_extrema() {
                    out.push(QuarticExtremum {
                        joint,
                        segment: q.segment,
                        t,
                        curvature: CurvatureAnalysis::curvature(s, t),
                    });
                }
            }
        }
        out
    }

    /// The input points with a peak, as the curve evaluates them at
    /// [`point_params`](Self::point_params).
    pub fn peak_points(&self) -> Vec<Point3> {
        self.peaks
            .iter()
            .map(|&(i, t)| self.segments[i].eval(t))
            .collect()
    }

    /// The start and end points of the curve (equal for closed curves).
    pub fn ends(&self) -> (Point3, Point3) {
        match (self.segments.first(), self.segments.last()) {
            (Some(a), Some(b)) => (a.start(), b.end()),
            _ => (Point3::ORIGIN, Point3::ORIGIN),
        }
    }
}

/// Is an input point at parameter distance `dist` from a joint *at* that joint, for a
/// requested replacement of length `requested` on that side? Yes when it is closer than
/// [`PEAK_AT_JOINT`] × the requested length (at most the default 0.01): a quartic cut there
/// would have a side too short for its curvature to be accurate (the curvature-vector gap grows
/// like `1/side²`; measured 5e-12 at side 0.01 and 5e-10 at 0.001 on the trefoil).
fn at_joint(dist: f64, requested: f64) -> bool {
    requested > 0.0 && dist < PEAK_AT_JOINT * requested.min(DEFAULT_FRACTION)
}

/// See [`at_joint`].
const PEAK_AT_JOINT: f64 = 0.1;
/// The paper's replacement parameter (seed 004 §5).
const DEFAULT_FRACTION: f64 = 0.01;
/// Samples of the coarse search in [`nearest`].
const NEAREST_SAMPLES: usize = 64;
/// Golden-section steps of [`nearest`] (the bracket shrinks to about 1e-12 of a sample step).
const NEAREST_ITERATIONS: usize = 60;

/// The parameter of the point of `s` nearest to `p`, and the distance: the best of
/// [`NEAREST_SAMPLES`] samples refined by golden-section search.
fn nearest(s: &SpaceBez, p: Point3) -> (f64, f64) {
    let d = |t: f64| s.eval(t).distance(p);
    let step = 1.0 / NEAREST_SAMPLES as f64;
    let (mut best_t, mut best_d) = (0.0, f64::INFINITY);
    for i in 0..=NEAREST_SAMPLES {
        let t = i as f64 * step;
        let v = d(t);
        if v < best_d {
            (best_t, best_d) = (t, v);
        }
    }
    let (mut a, mut b) = ((best_t - step).max(0.0), (best_t + step).min(1.0));
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..NEAREST_ITERATIONS {
        let c = b - ratio * (b - a);
        let e = a + ratio * (b - a);
        if d(c) < d(e) {
            b = e;
        } else {
            a = c;
        }
    }
    let t = 0.5 * (a + b);
    if d(t) < best_d {
        (t, d(t))
    } else {
        (best_t, best_d)
    }
}

/// The κ-curve's joint ratio from the control points: the joint `left[2]` as the fraction
/// of the way from `left[1]` to `right[1]`.
fn joint_lambda(left: &Quad, right: &Quad) -> f64 {
    let d = right[1] - left[1];
    let d2 = d.hypot2();
    if d2 > 0.0 {
        (left[2] - left[1]).dot(d) / d2
    } else {
        0.5
    }
}

/// Checks a [`Replace`] against the documented range: `0 ≤ t1 ≤ 1 − MIN_REPLACED`,
/// `MIN_REPLACED ≤ t2 ≤ 1` (see [`MIN_REPLACED`](super::MIN_REPLACED)).
fn validate_replace(replace: Replace) -> Result<(), Error> {
    match replace {
        Replace::None => Ok(()),
        Replace::Partial { t1, t2 } => {
            if t1 >= 0.0 && 1.0 - t1 >= MIN_REPLACED && (MIN_REPLACED..=1.0).contains(&t2) {
                Ok(())
            } else {
                Err(Error::InvalidOption(
                    "the replaced range needs 0 <= t1 <= 1 - 1e-3 and 1e-3 <= t2 <= 1",
                ))
            }
        }
    }
}
