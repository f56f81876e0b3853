//! G1 and G2 Hermite interpolation by one intrinsic segment (seed 003 §4).
//!
//! # Method
//!
//! The data are moved to a normalized frame: start at (0, 0), end at (1, 0); the tangent
//! angles become `φ₀`, `φ₁` relative to the chord and curvatures are multiplied by the chord
//! length `d` (a similarity scales curvatures by `1/σ`, seed 003 §4.2). The unknowns are
//! written without dimension: `A_i = L κ_i`, so that the tangent angle
//! `θ(τ) = φ₀ + Σ A_i M_i(τ)`, `M_i(τ) = ∫_0^τ B_i^n` (or `∫_0^τ w_i B_i^n / Σ w_j B_j^n`),
//! does not depend on `L` by itself. Every control curvature is an affine function of the two
//! unknowns `a`, `b` (the solved ones, the linearly interpolated ones, the ones tied to
//! another, the given ones and, for G2, the end curvatures), so
//! `A_i = α_i a′ + β_i b′ + γ_i L` with `a′ = L a`, `b′ = L b` is **linear** in
//! `u = (a′, b′, L)`. The three equations
//!
//! ```text
//! Σ A_i M_i(1) = δ          (end angle; linear in u)
//! L ∫_0^1 cos θ = 1          (end point)
//! L ∫_0^1 sin θ = 0
//! ```
//!
//! are solved by Newton's method with the exact Jacobian (the derivatives of `θ` with
//! respect to `u` are the functions `Σ α_i M_i`, `Σ β_i M_i`, `Σ γ_i M_i`, integrated in the
//! same quadrature pass as the residual) and a backtracking line search that keeps `L > 0`.
//! Nothing divides by the net turning `δ`, so S-curves (`δ = 0`) and straight lines solve like
//! any other data — unlike seed 003's `L = θ_d (n + 1) / Σ κ_i` (eq. 9).
//!
//! The start is the G1 clothoid of the same data (degree 1, [`super::clothoid`]), which is an
//! exact solution of the *linear* profile of any degree. When Newton's method from there does
//! not reach the requested profile, a homotopy takes over: the profile is blended from the
//! linear one (λ = 0) to the requested one (λ = 1) — interior control curvatures, weights and
//! G2 end curvatures alike — with Newton's method at each step, steps halved on failure. If
//! the steps become too small the data are taken to have no solution in the family and
//! [`Error::NoHermiteSolution`] is returned; every returned segment is checked to meet the
//! end conditions.

use kurbo::{ParamCurve, Point};

use super::bernstein;
use super::clothoid;
use super::quad::Rule;
use super::segment::{check_weights, IntrinsicSeg, MAX_TURNING};
use crate::{Error, SolveOptions};

/// Quadrature nodes per unit of the iteration cap ([`Hermite::solve_with`]): a solve
/// evaluates at most `max_iterations × NODES_PER_ITERATION` nodes. A Newton iteration of a
/// typical problem evaluates a few hundred (one 24-point piece per 6 radians of turning), so
/// the cap is rarely the limit below turnings of hundreds of radians.
pub const NODES_PER_ITERATION: usize = 2048;

/// The iteration cap of [`Hermite::solve`] (the curve solver's default,
/// [`SolveOptions::max_iterations`], is larger): a solve that cannot converge ends within
/// about 0.1 s on one core.
pub const HERMITE_ITERATIONS: usize = 2000;

/// The work of tabulating one quadrature node, in evaluations of a node of the residual.
const TABLE_COST: usize = 4;

/// Newton iterations per solve.
const NEWTON_ITERATIONS: usize = 40;
/// Newton stops when the residual (position relative to the chord, angle in radians) is
/// below this.
const RESIDUAL_TOLERANCE: f64 = 1e-13;
/// A residual that stagnates (no step reduces it) is accepted below this.
const STAGNATION_TOLERANCE: f64 = 1e-11;
/// The largest change of any `A_i = L κ_i` (radians of turning) in one Newton step.
const MAX_STEP_TURNING: f64 = 1.0;
/// Halvings of the line search.
const LINE_SEARCH_STEPS: usize = 30;
/// The homotopy gives up when its step in λ falls below this.
const MIN_HOMOTOPY_STEP: f64 = 1.0 / 4096.0;
/// The largest total turning `|θ_d|` (radians, about 160 turns) a Hermite problem may ask
/// for ([`Turning::AsGiven`] takes any angles literally). The quadrature grows with the
/// turning, and the clothoid search scans around its guess: a turning of 10⁷ radians took
/// minutes before this bound (found by the `hermite` fuzz target).
const MAX_HERMITE_TURNING: f64 = 1e3;
/// The returned segment must meet the end conditions to this (relative to the chord).
pub const END_TOLERANCE: f64 = 1e-10;

/// How the total turning `θ_d` between the end tangents is chosen: the angles fix it only up
/// to multiples of 2π.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Turning {
    /// Both tangent angles are taken relative to the chord and reduced to `(−π, π]`, and
    /// `θ_d = φ₁ − φ₀ ∈ (−2π, 2π)`: the curve turns the short way round, as a clothoid of
    /// Bertolazzi & Frego does. The default.
    #[default]
    Nearest,
    /// `θ_d = θ₁ − θ₀` exactly as given: add 2π to the end angle for one more anticlockwise
    /// turn.
    AsGiven,
}

/// One end of a Hermite problem: a point, a tangent angle and, for G2, a curvature.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HermiteEnd {
    /// The point.
    pub point: Point,
    /// The tangent angle in radians, anticlockwise from +x (in y-up coordinates).
    pub angle: f64,
    /// The curvature (positive for left turns), for G2 data.
    pub curvature: Option<f64>,
}

/// G1 or G2 Hermite data: two ends with points, tangent angles and (G2) curvatures.
///
/// [`Hermite::solve`] finds the segment of a given curvature [`Profile`] that meets them.
///
/// ```
/// use kappa::intrinsic::{Hermite, Profile};
/// use kurbo::{ParamCurve, Point};
///
/// // G1 data and degree 1: the clothoid, curvature linear in arc length.
/// let g1 = Hermite::g1(Point::new(0.0, 0.0), 0.3, Point::new(10.0, 4.0), 1.6);
/// let clothoid = g1.solve(&Profile::clothoid())?;
/// assert_eq!(clothoid.degree(), 1);
/// assert!(g1.end_error(&clothoid) < 1e-10);
///
/// // G2 data: the end curvatures are the first and last control curvatures.
/// let g2 = Hermite::g2(Point::new(0.0, 0.0), 0.3, -0.1, Point::new(10.0, 4.0), 1.6, 0.3);
/// let quintic = g2.solve(&Profile::free(5))?;
/// let k = quintic.curvatures();
/// assert_eq!(k.len(), 6);
/// assert!((k[0] + 0.1).abs() < 1e-9 && (k[5] - 0.3).abs() < 1e-9);
/// assert!((quintic.end() - g2.end.point).hypot() < 1e-9);
/// # Ok::<(), kappa::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hermite {
    /// The start.
    pub start: HermiteEnd,
    /// The end.
    pub end: HermiteEnd,
    /// How the angles fix the total turning.
    pub turning: Turning,
}

/// How one control curvature of a [`Profile`] is determined.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Control {
    /// Chosen by the solver: the two unknowns (`κ_0`, `κ_n` for G1; `κ_1`, `κ_{n−1}` for G2)
    /// and, elsewhere, linear interpolation between them (by index). For G2 the end entries
    /// are the end curvatures and must be `Free`.
    Free,
    /// This value (a curvature in the units of the data).
    Given(f64),
    /// Equal to the control curvature with this index (which must not itself be `Same`).
    Same(usize),
}

/// The curvature profile of a Hermite segment: how each control curvature is determined, and
/// optional weights for a rational curvature function.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    /// One entry per control curvature `κ_0..κ_n`; the degree is `len − 1`.
    pub controls: Vec<Control>,
    /// Positive weights, one per control curvature, for a rational function.
    pub weights: Option<Vec<f64>>,
}

impl Profile {
    /// Degree `n` with every control curvature [`Control::Free`]: for G1 a clothoid (degree
    /// elevated), for G2 the unknowns `κ_1`, `κ_{n−1}` with linear interpolation between.
    pub fn free(degree: usize) -> Profile {
        Profile {
            controls: vec![Control::Free; degree + 1],
            weights: None,
        }
    }

    /// The clothoid: degree 1.
    pub fn clothoid() -> Profile {
        Profile::free(1)
    }

    /// A profile with these controls and no weights.
    pub fn new(controls: Vec<Control>) -> Profile {
        Profile {
            controls,
            weights: None,
        }
    }

    /// The same profile with weights (a rational curvature function).
    pub fn with_weights(mut self, weights: Vec<f64>) -> Profile {
        self.weights = Some(weights);
        self
    }

    /// The degree `n` (0 for an empty profile, which no problem accepts).
    pub fn degree(&self) -> usize {
        self.controls.len().saturating_sub(1)
    }
}

impl Hermite {
    /// G1 data: points and tangent angles, [`Turning::Nearest`].
    pub fn g1(start: Point, start_angle: f64, end: Point, end_angle: f64) -> Hermite {
        Hermite {
            start: HermiteEnd {
                point: start,
                angle: start_angle,
                curvature: None,
            },
            end: HermiteEnd {
                point: end,
                angle: end_angle,
                curvature: None,
            },
            turning: Turning::Nearest,
        }
    }

    /// G2 data: points, tangent angles and curvatures, [`Turning::Nearest`].
    pub fn g2(
        start: Point,
        start_angle: f64,
        start_curvature: f64,
        end: Point,
        end_angle: f64,
        end_curvature: f64,
    ) -> Hermite {
        let mut h = Hermite::g1(start, start_angle, end, end_angle);
        h.start.curvature = Some(start_curvature);
        h.end.curvature = Some(end_curvature);
        h
    }

    /// The same data with another [`Turning`].
    pub fn with_turning(mut self, turning: Turning) -> Hermite {
        self.turning = turning;
        self
    }

    /// Whether these are G2 data (both curvatures given).
    pub fn is_g2(&self) -> bool {
        self.start.curvature.is_some() && self.end.curvature.is_some()
    }

    /// The total turning `θ_d` a solution has, per [`Hermite::turning`].
    pub fn turning_angle(&self) -> f64 {
        let chord = self.end.point - self.start.point;
        let psi = chord.y.atan2(chord.x);
        let phi0 = reduce_angle(self.start.angle - psi);
        match self.turning {
            Turning::Nearest => reduce_angle(self.end.angle - psi) - phi0,
            Turning::AsGiven => self.end.angle - self.start.angle,
        }
    }

    /// The largest violation of the end conditions by `seg`, relative to the chord length
    /// `d`: `|P(0) − P₀| / d`, `|P(1) − P₁| / d`, the start and end angle errors (radians,
    /// against `θ₀` and `θ₀ + θ_d`) and, for G2 data, `d |κ(0) − κ₀|` and `d |κ(1) − κ₁|`.
    pub fn end_error(&self, seg: &IntrinsicSeg) -> f64 {
        let d = (self.end.point - self.start.point).hypot();
        let mut e = ((seg.start() - self.start.point).hypot() / d)
            .max((seg.end() - self.end.point).hypot() / d)
            .max((seg.start_angle() - self.start.angle).abs())
            .max((seg.end_angle() - self.start.angle - self.turning_angle()).abs());
        if let (Some(k0), Some(k1)) = (self.start.curvature, self.end.curvature) {
            e = e
                .max(d * (seg.curvature_at(0.0) - k0).abs())
                .max(d * (seg.curvature_at(1.0) - k1).abs());
        }
        e
    }

    /// The segment with curvature profile `profile` that meets these data.
    ///
    /// G1 data: unknowns `κ_0` and `κ_n`; degree 1, or any degree with every control
    /// [`Control::Free`] and no weights, is the clothoid of Bertolazzi & Frego (2015).
    /// G2 data: `κ_0`, `κ_n` are the end curvatures, unknowns `κ_1` and `κ_{n−1}`, `n ≥ 3`.
    ///
    /// # Errors
    ///
    /// [`Error::NonFinitePoint`] / [`Error::RepeatedPoint`] for non-finite or coincident end
    /// points; [`Error::InvalidOption`] for non-finite angles or curvatures, only one end
    /// curvature, a degree too low for the data (G1: 1, G2: 3), a [`Control::Given`] or
    /// [`Control::Same`] where the solver chooses, a bad [`Control::Same`] index, or bad
    /// weights; [`Error::NoHermiteSolution`] when no curve of the profile meets the data;
    /// [`Error::NotConverged`] when the default work cap of [`HERMITE_ITERATIONS`]
    /// runs out (see [`solve_with`](Self::solve_with)).
    pub fn solve(&self, profile: &Profile) -> Result<IntrinsicSeg, Error> {
        self.solve_with(
            profile,
            &SolveOptions {
                max_iterations: HERMITE_ITERATIONS,
                ..SolveOptions::default()
            },
        )
    }

    /// [`solve`](Self::solve) with an iteration cap: `options.max_iterations` (the other
    /// fields are not used; the Newton tolerance is fixed).
    ///
    /// The cap counts Newton iterations over every attempt (the direct one and each step of
    /// the homotopy), and it also bounds the work: every evaluation of the residual
    /// integrates `θ` with a quadrature whose size grows with the turning (and with the
    /// spread of the weights of a rational profile), so a solve evaluates at most
    /// `max_iterations ×` [`NODES_PER_ITERATION`] quadrature nodes in all, line-search steps
    /// and tables included. The time of a solve is therefore proportional to the cap (at
    /// most about 0.1 s for the default [`HERMITE_ITERATIONS`] on one core).
    ///
    /// # Errors
    ///
    /// As [`solve`](Self::solve); [`Error::NotConverged`] with the Newton iterations done and
    /// the smallest residual reached (position relative to the chord, angle in radians) when
    /// the cap runs out — typically a homotopy that follows the solutions out to turnings
    /// of thousands of radians, or weights spread over hundreds of orders of magnitude.
    pub fn solve_with(
        &self,
        profile: &Profile,
        options: &SolveOptions,
    ) -> Result<IntrinsicSeg, Error> {
        let problem = Problem::new(self, profile)?;
        let u = problem.solve(options.max_iterations)?;
        let seg = problem.segment(&u)?;
        let error = self.end_error(&seg);
        if error.is_nan() || error > END_TOLERANCE {
            return Err(Error::NoHermiteSolution {
                reason: "the solution found misses the end conditions",
            });
        }
        Ok(seg)
    }
}

/// `a` reduced to `(−π, π]`.
pub(crate) fn reduce_angle(a: f64) -> f64 {
    use core::f64::consts::{PI, TAU};
    let r = a - TAU * (a / TAU).round();
    if r <= -PI {
        r + TAU
    } else if r > PI {
        r - TAU
    } else {
        r
    }
}

/// Affine rows `κ_i = α_i a + β_i b + γ_i` (normalized frame) of a profile.
#[derive(Clone, Debug, PartialEq)]
struct Rows {
    alpha: Vec<f64>,
    beta: Vec<f64>,
    gamma: Vec<f64>,
    weights: Option<Vec<f64>>,
}

impl Rows {
    fn blend(start: &Rows, target: &Rows, lambda: f64) -> Rows {
        let mix = |a: &[f64], b: &[f64]| -> Vec<f64> {
            a.iter().zip(b).map(|(x, y)| x + lambda * (y - x)).collect()
        };
        let weights = target.weights.as_ref().map(|w| {
            let ones = vec![1.0; w.len()];
            mix(&ones, w)
        });
        Rows {
            alpha: mix(&start.alpha, &target.alpha),
            beta: mix(&start.beta, &target.beta),
            gamma: mix(&start.gamma, &target.gamma),
            weights,
        }
    }

    /// `A_i = α_i a′ + β_i b′ + γ_i L`.
    fn scaled(&self, u: &[f64; 3], out: &mut Vec<f64>) {
        out.clear();
        out.extend(
            (0..self.alpha.len())
                .map(|i| self.alpha[i] * u[0] + self.beta[i] * u[1] + self.gamma[i] * u[2]),
        );
    }
}

/// A Hermite problem in the normalized frame.
struct Problem {
    /// Start point, chord length and direction of the data.
    origin: Point,
    chord: f64,
    start_angle: f64,
    phi0: f64,
    delta: f64,
    /// The unknowns' indices.
    ia: usize,
    ib: usize,
    /// The requested profile.
    target: Rows,
    /// The requested profile is the clothoid itself.
    is_clothoid: bool,
}

impl Problem {
    fn new(h: &Hermite, profile: &Profile) -> Result<Problem, Error> {
        let (p0, p1) = (h.start.point, h.end.point);
        if !p0.is_finite() {
            return Err(Error::NonFinitePoint { index: 0 });
        }
        if !p1.is_finite() {
            return Err(Error::NonFinitePoint { index: 1 });
        }
        let chord_vec = p1 - p0;
        let chord = chord_vec.hypot();
        if !chord.is_finite() {
            return Err(Error::ExtentOverflow);
        }
        let scale = p0.to_vec2().hypot().max(p1.to_vec2().hypot());
        if chord <= 1e-12 * scale || chord == 0.0 {
            return Err(Error::RepeatedPoint { index: 0, next: 1 });
        }
        if !(h.start.angle.is_finite() && h.end.angle.is_finite()) {
            return Err(Error::InvalidOption("tangent angles must be finite"));
        }
        let g2 = match (h.start.curvature, h.end.curvature) {
            (None, None) => None,
            (Some(k0), Some(k1)) if k0.is_finite() && k1.is_finite() => Some((k0, k1)),
            (Some(_), Some(_)) => {
                return Err(Error::InvalidOption("end curvatures must be finite"));
            }
            _ => {
                return Err(Error::InvalidOption(
                    "G2 data need both end curvatures (or neither, for G1)",
                ));
            }
        };
        let n = profile.degree();
        if profile.controls.is_empty() || n < if g2.is_some() { 3 } else { 1 } {
            return Err(Error::InvalidOption(
                "the degree must be at least 1 for G1 data and 3 for G2 data",
            ));
        }
        if let Some(w) = &profile.weights {
            check_weights(w, n + 1)?;
        }
        let psi = chord_vec.y.atan2(chord_vec.x);
        let phi0 = reduce_angle(h.start.angle - psi);
        let delta = h.turning_angle();
        if delta.is_nan() || delta.abs() > MAX_HERMITE_TURNING {
            return Err(Error::NoHermiteSolution {
                reason: "the total turning exceeds a thousand radians",
            });
        }
        let (ia, ib) = if g2.is_some() { (1, n - 1) } else { (0, n) };
        let target = target_rows(
            profile,
            ia,
            ib,
            g2.map(|(a, b)| (a * chord, b * chord)),
            chord,
        )?;
        let mut problem = Problem {
            origin: p0,
            chord,
            start_angle: h.start.angle,
            phi0,
            delta,
            ia,
            ib,
            target,
            is_clothoid: false,
        };
        problem.is_clothoid = g2.is_none()
            && profile.weights.is_none()
            && problem.linear(clothoid::Clothoid::default()) == problem.target;
        Ok(problem)
    }

    /// The linear profile through the clothoid `c`'s curvature function: the unknowns, linear
    /// interpolation between them and, for G2, the clothoid's end curvatures at the ends.
    fn linear(&self, c: clothoid::Clothoid) -> Rows {
        let n = self.target.alpha.len() - 1;
        let (ia, ib) = (self.ia, self.ib);
        let mut linear = Rows {
            alpha: vec![0.0; n + 1],
            beta: vec![0.0; n + 1],
            gamma: vec![0.0; n + 1],
            weights: None,
        };
        for i in 0..=n {
            if i < ia || i > ib {
                linear.gamma[i] = c.at(i as f64 / n as f64);
            } else {
                let s = (i - ia) as f64 / (ib - ia) as f64;
                linear.alpha[i] = 1.0 - s;
                linear.beta[i] = s;
            }
        }
        linear
    }

    /// The unknowns `(L κ(ia/n), L κ(ib/n), L)` of the clothoid `c` in the linear profile.
    fn clothoid_start(&self, c: clothoid::Clothoid) -> [f64; 3] {
        let n = (self.target.alpha.len() - 1) as f64;
        [
            c.length * c.at(self.ia as f64 / n),
            c.length * c.at(self.ib as f64 / n),
            c.length,
        ]
    }

    fn solve(&self, max_iterations: usize) -> Result<[f64; 3], Error> {
        let no_clothoid = Error::NoHermiteSolution {
            reason: "no clothoid meets the G1 data, so the solver has no start",
        };
        if self.is_clothoid {
            let c = clothoid::solve(self.phi0, self.delta).ok_or(no_clothoid)?;
            return Ok(self.clothoid_start(c));
        }
        // Newton's method on the requested profile, from the clothoid of Bertolazzi &
        // Frego's initial guess (it meets the end angles, not quite the end point).
        let mut work = Work {
            budget: max_iterations.saturating_mul(NODES_PER_ITERATION),
            max_iterations,
            ..Work::default()
        };
        if let Some(c) = clothoid::approximate(self.phi0, self.delta) {
            let start = self.clothoid_start(c);
            if let Some(u) = newton(&self.target, self.phi0, self.delta, start, &mut work) {
                return Ok(u);
            }
            if work.exhausted() {
                return Err(self.not_converged(&work, work.last));
            }
        }
        // Homotopy from the linear profile (solved by the clothoid) to the target.
        let c = clothoid::solve(self.phi0, self.delta).ok_or(no_clothoid)?;
        let linear = self.linear(c);
        let (mut lambda, mut u) = (0.0, self.clothoid_start(c));
        let mut prev: Option<(f64, [f64; 3])> = None;
        let mut step: f64 = 0.25;
        while lambda < 1.0 {
            let next = (lambda + step).min(1.0);
            // Secant predictor along the path.
            let guess = match prev {
                Some((l0, u0)) if lambda > l0 => {
                    let f = (next - lambda) / (lambda - l0);
                    [
                        u[0] + f * (u[0] - u0[0]),
                        u[1] + f * (u[1] - u0[1]),
                        (u[2] + f * (u[2] - u0[2])).max(0.5 * u[2]),
                    ]
                }
                _ => u,
            };
            let rows = Rows::blend(&linear, &self.target, next);
            let solved = newton(&rows, self.phi0, self.delta, guess, &mut work)
                .or_else(|| newton(&rows, self.phi0, self.delta, u, &mut work));
            if work.exhausted() {
                return Err(self.not_converged(&work, u));
            }
            match solved {
                Some(v) => {
                    prev = Some((lambda, u));
                    lambda = next;
                    u = v;
                    step = (2.0 * step).min(1.0);
                }
                None => {
                    step *= 0.5;
                    if step < MIN_HOMOTOPY_STEP {
                        return Err(Error::NoHermiteSolution {
                            reason: "the continuation from the clothoid stalls (the data are \
                                     outside the profile's reach)",
                        });
                    }
                }
            }
        }
        Ok(u)
    }

    /// [`Error::NotConverged`] after the work cap ran out, with the Newton iterations done
    /// and the residual of the requested profile at `u` (the last point reached on the way).
    fn not_converged(&self, work: &Work, u: [f64; 3]) -> Error {
        // One more evaluation, allowed an eighth of the cap (else the residual is reported
        // as infinite: the point is too far out to be worth integrating).
        let mut w = Work {
            budget: work.budget / 8,
            max_iterations: 1,
            ..Work::default()
        };
        self.target.scaled(&u, &mut w.scaled);
        let bound = w.scaled.iter().fold(0.0f64, |m, a| m.max(a.abs()));
        let residual = if bound <= MAX_TURNING
            && u.iter().all(|x| x.is_finite())
            && w.ensure(
                &self.target,
                Rule::new(bound, self.target.weights.as_deref()),
            ) {
            norm(&w.residual(self.phi0, self.delta, &u).0)
        } else {
            f64::INFINITY
        };
        Error::NotConverged {
            iterations: work.iterations,
            residual: if residual.is_nan() {
                f64::INFINITY
            } else {
                residual
            },
        }
    }

    /// The segment in the data's frame for the unknowns `u`.
    fn segment(&self, u: &[f64; 3]) -> Result<IntrinsicSeg, Error> {
        let mut a = Vec::new();
        self.target.scaled(u, &mut a);
        let l = u[2];
        let curvatures: Vec<f64> = a.iter().map(|ai| ai / (l * self.chord)).collect();
        IntrinsicSeg::build(
            self.origin,
            self.start_angle,
            l * self.chord,
            curvatures,
            self.target.weights.clone(),
        )
    }
}

/// The rows of the requested profile (normalized curvatures: given values times the chord).
fn target_rows(
    profile: &Profile,
    ia: usize,
    ib: usize,
    ends: Option<(f64, f64)>,
    chord: f64,
) -> Result<Rows, Error> {
    let n = profile.degree();
    let mut rows = Rows {
        alpha: vec![0.0; n + 1],
        beta: vec![0.0; n + 1],
        gamma: vec![0.0; n + 1],
        weights: profile.weights.clone(),
    };
    for (i, c) in profile.controls.iter().enumerate() {
        let solver_owned = i == ia || i == ib || (ends.is_some() && (i == 0 || i == n));
        if solver_owned && *c != Control::Free {
            return Err(Error::InvalidOption(
                "the solved control curvatures (and, for G2, the end ones) must be Free",
            ));
        }
        let (alpha, beta, gamma) = match *c {
            _ if i == ia => (1.0, 0.0, 0.0),
            _ if i == ib => (0.0, 1.0, 0.0),
            _ if ends.is_some() && i == 0 => (0.0, 0.0, ends.map_or(0.0, |e| e.0)),
            _ if ends.is_some() && i == n => (0.0, 0.0, ends.map_or(0.0, |e| e.1)),
            Control::Free => {
                let s = (i - ia) as f64 / (ib - ia) as f64;
                (1.0 - s, s, 0.0)
            }
            Control::Given(v) if v.is_finite() => (0.0, 0.0, v * chord),
            Control::Given(_) => {
                return Err(Error::InvalidOption(
                    "given control curvatures must be finite",
                ));
            }
            Control::Same(_) => (0.0, 0.0, 0.0),
        };
        rows.alpha[i] = alpha;
        rows.beta[i] = beta;
        rows.gamma[i] = gamma;
    }
    for (i, c) in profile.controls.iter().enumerate() {
        if let Control::Same(j) = *c {
            if j > n || matches!(profile.controls[j], Control::Same(_)) {
                return Err(Error::InvalidOption(
                    "Same(j) must name a control curvature that is not itself Same",
                ));
            }
            rows.alpha[i] = rows.alpha[j];
            rows.beta[i] = rows.beta[j];
            rows.gamma[i] = rows.gamma[j];
        }
    }
    Ok(rows)
}

/// Quadrature table of a profile: for each node its weight and the three direction
/// functions `Σ α_i M_i(τ)`, `Σ β_i M_i(τ)`, `Σ γ_i M_i(τ)`; their values at `τ = 1`.
#[derive(Default)]
struct Work {
    nodes: Vec<[f64; 4]>,
    at_end: [f64; 3],
    rule: Option<Rule>,
    scaled: Vec<f64>,
    /// Scratch: the polynomial antiderivatives, or the weighted numerators.
    anti: [Vec<f64>; 3],
    /// The work cap: quadrature nodes that may still be evaluated in all.
    budget: usize,
    /// Quadrature nodes evaluated so far (residuals and tables).
    spent: usize,
    /// Newton iterations so far, and their cap.
    iterations: usize,
    max_iterations: usize,
    /// The last point Newton's method accepted.
    last: [f64; 3],
}

impl Work {
    /// Whether the work cap has run out.
    fn exhausted(&self) -> bool {
        self.spent > self.budget || self.iterations >= self.max_iterations
    }

    /// Makes sure the table of `rows` is at least as fine as `rule` (and not needlessly
    /// finer): re-tabulates when it is not. `false` (and the cap marked as run out) when the
    /// table and one residual with it would overrun the work cap.
    fn ensure(&mut self, rows: &Rows, rule: Rule) -> bool {
        if let Some(have) = self.rule {
            let fine_enough = have.coeffs.len() >= rule.coeffs.len() && have.pieces >= rule.pieces;
            if fine_enough && have.len() <= 4 * rule.len() {
                return true;
            }
        }
        let cost = (TABLE_COST + 1).saturating_mul(rule.len());
        if self.spent.saturating_add(cost) > self.budget {
            self.spent = self.budget.saturating_add(1);
            self.rule = None;
            return false;
        }
        self.tabulate(rows, rule);
        true
    }

    /// Tabulates the direction functions of `rows` with `rule`.
    fn tabulate(&mut self, rows: &Rows, rule: Rule) {
        self.rule = Some(rule);
        // A table costs a few times a residual per node (Bernstein numerators and, for
        // weights, the spectral integration matrix): measured about 3.5 times.
        self.spent = self.spent.saturating_add(TABLE_COST * rule.len());
        self.nodes.clear();
        self.nodes.reserve(rule.len());
        let h = 1.0 / rule.pieces as f64;
        let dirs = [&rows.alpha, &rows.beta, &rows.gamma];
        match &rows.weights {
            None => {
                for (d, anti) in dirs.iter().zip(self.anti.iter_mut()) {
                    bernstein::antiderivative(d, anti);
                }
                for p in 0..rule.pieces {
                    let mid = (p as f64 + 0.5) * h;
                    for &(wi, xi) in rule.coeffs {
                        let t = mid + 0.5 * h * xi;
                        self.nodes.push([
                            wi * 0.5 * h,
                            bernstein::eval(&self.anti[0], t),
                            bernstein::eval(&self.anti[1], t),
                            bernstein::eval(&self.anti[2], t),
                        ]);
                    }
                }
                for k in 0..3 {
                    self.at_end[k] = *self.anti[k].last().unwrap_or(&0.0);
                }
            }
            Some(w) => {
                // M_d(τ) = ∫_0^τ Σ d_i w_i B_i / Σ w_i B_i: the integrands at the nodes of each
                // piece, indefinite integrals at the nodes from the spectral matrix.
                for (d, num) in dirs.iter().zip(self.anti.iter_mut()) {
                    num.clear();
                    num.extend(d.iter().zip(w).map(|(d, w)| d * w));
                }
                let s = rule.matrix();
                let m = rule.coeffs.len();
                let mut f = [[0.0; 3]; 24];
                let mut base = [0.0; 3];
                for p in 0..rule.pieces {
                    let mid = (p as f64 + 0.5) * h;
                    for (fj, &(_, xj)) in f.iter_mut().zip(rule.coeffs) {
                        let t = mid + 0.5 * h * xj;
                        let den = bernstein::eval(w, t);
                        for (v, num) in fj.iter_mut().zip(&self.anti) {
                            *v = bernstein::eval(num, t) / den;
                        }
                    }
                    for (k, &(wk, _)) in rule.coeffs.iter().enumerate() {
                        let row = &s[k * m..(k + 1) * m];
                        let mut node = [wk * 0.5 * h, base[0], base[1], base[2]];
                        for (sj, fj) in row.iter().zip(&f[..m]) {
                            for d in 0..3 {
                                node[d + 1] += 0.5 * h * sj * fj[d];
                            }
                        }
                        self.nodes.push(node);
                    }
                    for (&(wj, _), fj) in rule.coeffs.iter().zip(&f[..m]) {
                        for d in 0..3 {
                            base[d] += 0.5 * h * wj * fj[d];
                        }
                    }
                }
                self.at_end = base;
            }
        }
    }

    /// Residual and Jacobian at `u`: `e = [Σ A_i M_i(1) − δ, L X − 1, L Y]`.
    fn residual(&mut self, phi0: f64, delta: f64, u: &[f64; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
        self.spent = self.spent.saturating_add(self.nodes.len());
        let (mut x, mut y) = (0.0, 0.0);
        let (mut dx, mut dy) = ([0.0; 3], [0.0; 3]);
        for node in &self.nodes {
            let th = phi0 + u[0] * node[1] + u[1] * node[2] + u[2] * node[3];
            let (s, c) = th.sin_cos();
            let (ws, wc) = (node[0] * s, node[0] * c);
            x += wc;
            y += ws;
            for k in 0..3 {
                dx[k] -= ws * node[k + 1];
                dy[k] += wc * node[k + 1];
            }
        }
        let l = u[2];
        let e0 = u[0] * self.at_end[0] + u[1] * self.at_end[1] + u[2] * self.at_end[2] - delta;
        let e = [e0, l * x - 1.0, l * y];
        let j = [
            self.at_end,
            [l * dx[0], l * dx[1], x + l * dx[2]],
            [l * dy[0], l * dy[1], y + l * dy[2]],
        ];
        (e, j)
    }
}

fn norm(e: &[f64; 3]) -> f64 {
    (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt()
}

/// Solves `J x = −e` by Gaussian elimination with partial pivoting; `None` if singular.
fn solve3(mut j: [[f64; 3]; 3], e: [f64; 3]) -> Option<[f64; 3]> {
    let mut b = [-e[0], -e[1], -e[2]];
    for col in 0..3 {
        let piv = (col..3).max_by(|&r, &s| j[r][col].abs().total_cmp(&j[s][col].abs()))?;
        if j[piv][col].abs() <= 1e-300 || j[piv][col].is_nan() {
            return None;
        }
        j.swap(col, piv);
        b.swap(col, piv);
        for r in col + 1..3 {
            let f = j[r][col] / j[col][col];
            let pivot_row = j[col];
            for (x, p) in j[r].iter_mut().zip(pivot_row).skip(col) {
                *x -= f * p;
            }
            b[r] -= f * b[col];
        }
    }
    let mut x = [0.0; 3];
    for r in (0..3).rev() {
        let mut s = b[r];
        for c in r + 1..3 {
            s -= j[r][c] * x[c];
        }
        x[r] = s / j[r][r];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Newton's method with backtracking for the profile `rows` from `u`; `None` when it fails.
fn newton(
    rows: &Rows,
    phi0: f64,
    delta: f64,
    mut u: [f64; 3],
    work: &mut Work,
) -> Option<[f64; 3]> {
    let pieces_for = |u: &[f64; 3], work: &mut Work| -> Option<()> {
        rows.scaled(u, &mut work.scaled);
        let bound = work.scaled.iter().fold(0.0f64, |m, a| m.max(a.abs()));
        if bound.is_nan() || bound > MAX_TURNING {
            return None;
        }
        work.ensure(rows, Rule::new(bound, rows.weights.as_deref()))
            .then_some(())
    };
    work.rule = None;
    work.last = u;
    pieces_for(&u, work)?;
    let (mut e, mut j) = work.residual(phi0, delta, &u);
    let mut r = norm(&e);
    for _ in 0..NEWTON_ITERATIONS {
        if r <= RESIDUAL_TOLERANCE {
            return Some(u);
        }
        if work.exhausted() {
            return None;
        }
        work.iterations += 1;
        let step = solve3(j, e)?;
        // Trust region: no control curvature's turning changes by more than
        // MAX_STEP_TURNING and L by no more than half, so that Newton's method moves to a
        // nearby solution instead of jumping to one that winds differently.
        rows.scaled(&step, &mut work.scaled);
        let turn = work.scaled.iter().fold(0.0f64, |m, a| m.max(a.abs()));
        let mut t: f64 = 1.0;
        if turn > MAX_STEP_TURNING {
            t = t.min(MAX_STEP_TURNING / turn);
        }
        if step[2].abs() > 0.5 * u[2] {
            t = t.min(0.5 * u[2] / step[2].abs());
        }
        let mut accepted = false;
        for _ in 0..LINE_SEARCH_STEPS {
            if work.exhausted() {
                return None;
            }
            let v = [u[0] + t * step[0], u[1] + t * step[1], u[2] + t * step[2]];
            if v[2] > 0.0 && v.iter().all(|x| x.is_finite()) && pieces_for(&v, work).is_some() {
                let (e2, j2) = work.residual(phi0, delta, &v);
                let r2 = norm(&e2);
                if r2 < (1.0 - 1e-4 * t) * r {
                    u = v;
                    work.last = v;
                    e = e2;
                    j = j2;
                    r = r2;
                    accepted = true;
                    break;
                }
            }
            t *= 0.5;
        }
        if !accepted {
            return (r <= STAGNATION_TOLERANCE).then_some(u);
        }
    }
    (r <= STAGNATION_TOLERANCE).then_some(u)
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f64::consts::PI;

    #[test]
    fn reduce_angle_range() {
        assert_eq!(reduce_angle(PI), PI);
        assert_eq!(reduce_angle(-PI), PI);
        assert!((reduce_angle(3.0 * PI + 0.1) - (-PI + 0.1)).abs() < 1e-12);
        assert!((reduce_angle(-0.5) + 0.5).abs() < 1e-15);
    }

    #[test]
    fn hermite_g1_cubic_profiles() {
        let h = Hermite::g1(Point::ZERO, 0.3, Point::new(2.0, 1.0), 1.2);
        let profiles = [
            Profile::free(1),
            Profile::free(3),
            Profile::new(vec![
                Control::Free,
                Control::Same(0),
                Control::Same(0),
                Control::Free,
            ]),
            Profile::new(vec![
                Control::Free,
                Control::Same(3),
                Control::Same(3),
                Control::Free,
            ]),
            Profile::new(vec![
                Control::Free,
                Control::Same(0),
                Control::Same(3),
                Control::Free,
            ]),
            Profile::new(vec![
                Control::Free,
                Control::Given(2.0),
                Control::Given(-1.0),
                Control::Free,
            ]),
            Profile::free(3).with_weights(vec![1.0, 3.0, 0.5, 1.0]),
        ];
        for p in &profiles {
            let seg = h.solve(p).unwrap_or_else(|e| panic!("{p:?}: {e}"));
            assert!(h.end_error(&seg) < 1e-10, "{p:?}: {}", h.end_error(&seg));
        }
    }

    #[test]
    fn hermite_g2_cubic() {
        let h = Hermite::g2(Point::ZERO, 0.0, 0.5, Point::new(1.0, 0.6), 1.2, 2.0);
        let seg = h.solve(&Profile::free(3)).unwrap();
        assert!(h.end_error(&seg) < 1e-10);
    }
}
