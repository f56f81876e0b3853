//! G2 curves through points from G2 Hermite intrinsic segments.

use kurbo::{CubicBez, ParamCurve, ParamCurveDeriv, Point};

use super::hermite::reduce_angle;
use super::{Hermite, IntrinsicSeg, Profile, Turning};
use crate::analysis::CurvatureAnalysis;
use crate::fit::{fit, FitOptions, Fitted};
use crate::{Error, Spline};

/// Tangent samples per εκ segment piece when measuring how far the estimate turns between
/// two points.
const TURN_SAMPLES: usize = 32;

/// Options of [`IntrinsicSpline::new`].
#[derive(Clone, Debug, PartialEq)]
pub struct SplineOptions {
    /// Degree of the curvature function of every segment (at least 3). Default 5.
    pub degree: usize,
    /// If a span has no solution of `degree`, try up to this degree (in steps of 2).
    /// Default 9.
    pub max_degree: usize,
    /// Shape parameter `a ∈ [2/3, 1)` of the εκ-curve that estimates missing tangents and
    /// curvatures. Default 2/3 (the κ-like neutral shape).
    pub shape: f64,
    /// Tangent angles at the points (radians); `None` estimates them. A given angle fixes
    /// the direction only: between two points the curve turns the short way round.
    pub angles: Option<Vec<f64>>,
    /// Curvatures at the points; `None` estimates them.
    pub curvatures: Option<Vec<f64>>,
}

impl Default for SplineOptions {
    fn default() -> SplineOptions {
        SplineOptions {
            degree: 5,
            max_degree: 9,
            shape: 2.0 / 3.0,
            angles: None,
            curvatures: None,
        }
    }
}

/// A G2 curve through points made of intrinsic segments, one per span between consecutive
/// points: each is the G2 Hermite segment ([`Hermite::solve`], unknowns `κ_1`, `κ_{n−1}`,
/// linear interpolation between) meeting the tangent angle and curvature given or estimated
/// at both of its points. Joints are G2 by construction, and the curvature of each span is a
/// polynomial in arc length that the designer can inspect ([`IntrinsicSeg::inflections`],
/// [`IntrinsicSeg::is_monotone`]).
///
/// Missing tangents and curvatures are read off the cubic εκ-curve ([`Spline::ek_cubic`])
/// through the same points, and the turning of each span is the εκ-curve's (so that loops and
/// sharp bends keep their winding).
#[derive(Clone, Debug, PartialEq)]
pub struct IntrinsicSpline {
    segments: Vec<IntrinsicSeg>,
    closed: bool,
}

impl IntrinsicSpline {
    /// The curve through `points` (closed: back to the first point).
    ///
    /// # Errors
    ///
    /// The εκ solver's errors (too few, non-finite or repeated points, collinear closed
    /// input, a bad shape), [`Error::InvalidOption`] for a degree below 3 or given angle or
    /// curvature lists of the wrong length, and [`Error::NoHermiteSolution`] (or
    /// [`Error::NotConverged`], the Hermite solver's cap) when a span has no solution up to
    /// `max_degree`.
    pub fn new(
        points: &[Point],
        closed: bool,
        options: &SplineOptions,
    ) -> Result<IntrinsicSpline, Error> {
        if options.degree < 3 {
            return Err(Error::InvalidOption(
                "the degree of an intrinsic spline must be at least 3",
            ));
        }
        let count = points.len();
        for list in [&options.angles, &options.curvatures].into_iter().flatten() {
            if list.len() != count {
                return Err(Error::InvalidOption(
                    "give one tangent angle and curvature per point",
                ));
            }
        }
        let estimate = Spline::ek_cubic(points, closed, options.shape)?;
        let frames = frames(&estimate, points.len(), closed);
        let spans = if closed { count } else { count - 1 };
        let mut segments = Vec::with_capacity(spans);
        for i in 0..spans {
            let j = (i + 1) % count;
            let (a0, k0, _) = frames[i];
            let (a1, k1, turn) = frames[j];
            let mut h = Hermite::g2(points[i], a0, k0, points[j], a1, k1);
            // The estimate's winding between the two points, unless angles were given.
            match &options.angles {
                Some(angles) => {
                    h.start.angle = angles[i];
                    h.end.angle = angles[j];
                }
                None => {
                    h.end.angle = a0 + turn;
                    h = h.with_turning(Turning::AsGiven);
                }
            }
            if let Some(k) = &options.curvatures {
                h.start.curvature = Some(k[i]);
                h.end.curvature = Some(k[j]);
            }
            segments.push(solve_span(&h, options)?);
        }
        Ok(IntrinsicSpline { segments, closed })
    }

    /// The segments, one per span, in order.
    pub fn segments(&self) -> &[IntrinsicSeg] {
        &self.segments
    }

    /// Whether the curve is closed.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// Cubic Béziers within a tolerance of the curve, through [`crate::fit::fit`].
    pub fn to_bezpath(&self, options: &FitOptions) -> Result<Fitted, Error> {
        fit(&self.segments, self.closed, options)
    }
}

/// Solves one span with the options' degree, raising it by 2 up to `max_degree` on failure.
fn solve_span(h: &Hermite, options: &SplineOptions) -> Result<IntrinsicSeg, Error> {
    let mut degree = options.degree;
    loop {
        match h.solve(&Profile::free(degree)) {
            Ok(seg) => return Ok(seg),
            Err(Error::NoHermiteSolution { .. } | Error::NotConverged { .. })
                if degree + 2 <= options.max_degree =>
            {
                degree += 2;
            }
            Err(e) => return Err(e),
        }
    }
}

/// For each point: the εκ-curve's tangent angle and curvature there, and how far its tangent
/// turns from the previous point to this one (0 for the first point of an open curve).
fn frames(estimate: &Spline, count: usize, closed: bool) -> Vec<(f64, f64, f64)> {
    let segs: Vec<CubicBez> = estimate
        .segments()
        .iter()
        .map(|s| s.to_path_seg().to_cubic())
        .collect();
    // Where each point lies: (segment, t). Closed: segment i at t_max. Open: the start of
    // the first segment, interior point i on segment i − 1 at t_max, the end of the last.
    let at: Vec<(usize, f64)> = (0..count)
        .map(|i| {
            if closed {
                (i, estimate.segments()[i].t_max)
            } else if i == 0 {
                (0, 0.0)
            } else if i == count - 1 {
                (segs.len() - 1, 1.0)
            } else {
                (i - 1, estimate.segments()[i - 1].t_max)
            }
        })
        .collect();
    let angle = |s: usize, t: f64| {
        let d = segs[s].deriv().eval(t).to_vec2();
        d.y.atan2(d.x)
    };
    let mut out = Vec::with_capacity(count);
    let mut unwrapped = 0.0;
    for (i, &(s, t)) in at.iter().enumerate() {
        let a = angle(s, t);
        let k = CurvatureAnalysis::curvature(&segs[s], t);
        let turn = if i == 0 && !closed {
            0.0
        } else {
            let (ps, pt) = at[(i + count - 1) % count];
            turning_between(&segs, ps, pt, s, t)
        };
        if i == 0 {
            unwrapped = a;
        } else {
            unwrapped += turn;
        }
        out.push((unwrapped, k, turn));
    }
    out
}

/// How far the tangent turns along the εκ-curve from `(s0, t0)` to `(s1, t1)` (the next
/// point), by summing reduced angle steps between dense samples.
fn turning_between(segs: &[CubicBez], s0: usize, t0: f64, s1: usize, t1: f64) -> f64 {
    let n = segs.len();
    let mut pieces = Vec::new();
    if s0 == s1 && t1 >= t0 {
        pieces.push((s0, t0, t1));
    } else {
        pieces.push((s0, t0, 1.0));
        let mut s = (s0 + 1) % n;
        while s != s1 {
            pieces.push((s, 0.0, 1.0));
            s = (s + 1) % n;
        }
        pieces.push((s1, 0.0, t1));
    }
    let mut total = 0.0;
    let mut prev: Option<f64> = None;
    for (s, a, b) in pieces {
        for k in 0..=TURN_SAMPLES {
            let t = a + (b - a) * k as f64 / TURN_SAMPLES as f64;
            let d = segs[s].deriv().eval(t).to_vec2();
            if d.hypot2() == 0.0 {
                continue;
            }
            let ang = d.y.atan2(d.x);
            if let Some(p) = prev {
                total += reduce_angle(ang - p);
            }
            prev = Some(ang);
        }
    }
    total
}
