//! A planar curve segment defined by its curvature: an explicit (rational) Bézier function of
//! arc length (seed 003 §3).

use core::ops::Range;

use kurbo::{
    BezPath, CurveFitSample, ParamCurve, ParamCurveArclen, ParamCurveCurvature, ParamCurveDeriv,
    ParamCurveFit, Point, Vec2,
};

use super::bernstein;
use super::quad::Rule;
use super::roots::sign_changes;
use crate::fit::{fit, FitOptions, Fitted};
use crate::Error;

/// The largest `L · max|κ_i|` (an upper bound of the total turning, in radians) a segment
/// may have: about 16 000 turns, and as many quadrature pieces per 2π.
pub const MAX_TURNING: f64 = 1e5;

/// A planar curve whose signed curvature is an explicit Bézier function of arc length
/// (seed 003 eq. 1–2).
///
/// With arc length `L`, `τ = s / L ∈ [0, 1]` and control curvatures `κ_0..κ_n`, the curvature
/// at arc length `s` is `κ(s) = K(s / L)` with
///
/// ```text
/// K(τ) = Σ B_i^n(τ) κ_i                       (polynomial)
/// K(τ) = Σ B_i^n(τ) w_i κ_i / Σ B_i^n(τ) w_i  (rational, weights w_i > 0)
/// ```
///
/// in the crate's sign convention (positive for left turns). The tangent angle is
/// `θ(τ) = θ_0 + L ∫_0^τ K`; for the polynomial case that is a Bernstein polynomial of degree
/// `n + 1` with coefficients `θ_0 + L/(n+1) Σ_{i<j} κ_i` (seed 003 eq. 7–8), evaluated in
/// closed form; for the rational case it is integrated by Gauss–Legendre quadrature. The
/// position `P(τ) = P_0 + L ∫_0^τ (cos θ, sin θ)` (seed 003 eq. 5) is integrated with
/// Gauss–Legendre rules (24 points on pieces over which the tangent turns by at most
/// [`super::PIECE_TURN`], 16 for a curve turning less than half a radian), accurate to about
/// 1e-13 of the
/// length; positions at the piece boundaries are cached, so one evaluation is a single rule.
/// For a rational function the angle at the nodes comes from the rule's spectral
/// integration matrix (exact for polynomials of degree below the rule's size).
///
/// The curve parameter of the kurbo traits is `t = τ = s / L`: the parameterization is by
/// arc length, the speed is `L` everywhere.
///
/// # kurbo traits and the curvature sign
///
/// [`ParamCurve`] (with exact [`ParamCurve::subsegment`]: the restricted curvature function is
/// again a Bézier function), [`ParamCurveArclen`] (exact: `L |t₁ − t₀|`), [`ParamCurveDeriv`]
/// and [`ParamCurveFit`] (so [`crate::fit::fit`] turns segments into a `BezPath`).
/// [`ParamCurveCurvature::curvature`] keeps **kurbo's sign**, i.e. it returns `−K(t)`;
/// [`IntrinsicSeg::curvature_at`] returns the crate's (the papers') `K(t)`.
#[derive(Clone, Debug, PartialEq)]
pub struct IntrinsicSeg {
    start: Point,
    angle: f64,
    length: f64,
    curvatures: Vec<f64>,
    weights: Option<Vec<f64>>,
    /// Polynomial: Bernstein coefficients of `θ(τ) − θ_0`, degree `n + 1`. Rational: empty.
    theta: Vec<f64>,
    /// Rational: `w_i κ_i`. Polynomial: empty.
    weighted: Vec<f64>,
    /// Position and tangent angle at `τ = p / N`, `p = 0..=N`.
    knots: Vec<(Point, f64)>,
    /// The quadrature rule (N pieces).
    rule: Rule,
}

impl IntrinsicSeg {
    /// A segment with polynomial curvature `K(τ) = Σ B_i^n(τ) κ_i` (degree `n =
    /// curvatures.len() − 1`; one control curvature is a circular arc) of arc length `length`
    /// from `start`, leaving it at angle `angle` (radians, anticlockwise from +x in y-up).
    ///
    /// # Errors
    ///
    /// [`Error::NonFinitePoint`] for a non-finite start, [`Error::InvalidOption`] for a
    /// non-finite angle, curvature or length, a negative length, no control curvatures, or a
    /// turning bound `L · max|κ_i|` above [`MAX_TURNING`].
    pub fn new(
        start: Point,
        angle: f64,
        length: f64,
        curvatures: &[f64],
    ) -> Result<IntrinsicSeg, Error> {
        IntrinsicSeg::build(start, angle, length, curvatures.to_vec(), None)
    }

    /// A segment with rational curvature `K(τ) = Σ B_i^n w_i κ_i / Σ B_i^n w_i` (seed 003
    /// eq. 2). Weights must be finite and positive, one per control curvature.
    ///
    /// # Errors
    ///
    /// As [`IntrinsicSeg::new`], and [`Error::InvalidOption`] for weights that are not
    /// positive and finite or whose count differs from the curvatures'.
    pub fn rational(
        start: Point,
        angle: f64,
        length: f64,
        curvatures: &[f64],
        weights: &[f64],
    ) -> Result<IntrinsicSeg, Error> {
        IntrinsicSeg::build(
            start,
            angle,
            length,
            curvatures.to_vec(),
            Some(weights.to_vec()),
        )
    }

    pub(crate) fn build(
        start: Point,
        angle: f64,
        length: f64,
        curvatures: Vec<f64>,
        weights: Option<Vec<f64>>,
    ) -> Result<IntrinsicSeg, Error> {
        if !start.is_finite() {
            return Err(Error::NonFinitePoint { index: 0 });
        }
        if !angle.is_finite() {
            return Err(Error::InvalidOption("the start angle must be finite"));
        }
        if !(length.is_finite() && length >= 0.0) {
            return Err(Error::InvalidOption(
                "the arc length must be finite and not negative",
            ));
        }
        if curvatures.is_empty() {
            return Err(Error::InvalidOption(
                "at least one control curvature is needed",
            ));
        }
        if !curvatures.iter().all(|k| k.is_finite()) {
            return Err(Error::InvalidOption("control curvatures must be finite"));
        }
        if let Some(w) = &weights {
            check_weights(w, curvatures.len())?;
        }
        let bound = length * curvatures.iter().fold(0.0f64, |m, k| m.max(k.abs()));
        if bound.is_nan() || bound > MAX_TURNING {
            return Err(Error::InvalidOption(
                "the curvature times the length exceeds the turning limit (1e5 radians)",
            ));
        }
        let mut seg = IntrinsicSeg {
            start,
            angle,
            length,
            curvatures,
            weights,
            theta: Vec::new(),
            weighted: Vec::new(),
            knots: Vec::new(),
            rule: Rule::new(0.0, None),
        };
        seg.cache(bound);
        Ok(seg)
    }

    /// Fills the closed-form angle coefficients and the knot positions.
    fn cache(&mut self, bound: f64) {
        match &self.weights {
            None => {
                bernstein::antiderivative(&self.curvatures, &mut self.theta);
                for c in &mut self.theta {
                    *c *= self.length;
                }
            }
            Some(w) => {
                self.weighted = self.curvatures.iter().zip(w).map(|(k, w)| k * w).collect();
            }
        }
        self.rule = Rule::new(bound, self.weights.as_deref());
        let pieces = self.rule.pieces;
        self.knots.clear();
        self.knots.reserve(pieces + 1);
        self.knots.push((self.start, self.angle));
        let h = 1.0 / pieces as f64;
        for p in 0..pieces {
            let a = p as f64 * h;
            let b = if p + 1 == pieces { 1.0 } else { a + h };
            let (pa, _) = self.knots[p];
            let (chord, tb) = self.piece_integral(p, a, b);
            self.knots.push((pa + chord, tb));
        }
    }

    /// The degree `n` of the curvature function.
    pub fn degree(&self) -> usize {
        self.curvatures.len() - 1
    }

    /// The control curvatures `κ_0..κ_n` (per unit length, the crate's sign).
    pub fn curvatures(&self) -> &[f64] {
        &self.curvatures
    }

    /// The weights of a rational curvature function, `None` for a polynomial one.
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// The arc length `L`.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The tangent angle at the start, `θ_0` (radians).
    pub fn start_angle(&self) -> f64 {
        self.angle
    }

    /// The tangent angle at the end, `θ_0 + θ_d`, not reduced modulo 2π.
    pub fn end_angle(&self) -> f64 {
        self.knots.last().map_or(self.angle, |k| k.1)
    }

    /// The total turning `θ_d = L ∫_0^1 K` (seed 003 eq. 8: `L` times the mean control
    /// curvature for the polynomial case).
    pub fn turning(&self) -> f64 {
        self.end_angle() - self.angle
    }

    /// The signed curvature `K(t)` at `t = s / L` in the crate's sign convention (positive
    /// for left turns). kurbo's [`ParamCurveCurvature::curvature`] returns `−K(t)`.
    pub fn curvature_at(&self, t: f64) -> f64 {
        match &self.weights {
            None => bernstein::eval(&self.curvatures, t),
            Some(w) => rational(&self.weighted, w, t),
        }
    }

    /// The derivative of the curvature with respect to arc length, `dκ/ds = K′(t) / L`
    /// (infinite sign-carrying values are avoided: 0 for a zero-length segment).
    pub fn curvature_deriv_at(&self, t: f64) -> f64 {
        if self.length == 0.0 {
            return 0.0;
        }
        let mut d = Vec::new();
        let dk = match &self.weights {
            None => {
                bernstein::derivative(&self.curvatures, &mut d);
                bernstein::eval(&d, t)
            }
            Some(w) => {
                bernstein::rational_derivative_numerator(&self.curvatures, w, &mut d);
                let g = bernstein::eval(w, t);
                bernstein::eval(&d, t) / (g * g)
            }
        };
        dk / self.length
    }

    /// The tangent angle `θ(t)` (radians, continuous along the curve, not reduced).
    pub fn angle_at(&self, t: f64) -> f64 {
        if self.theta.is_empty() {
            let (p, a) = self.piece_of(t);
            let (mid, half) = (0.5 * (a + t), 0.5 * (t - a));
            let w = self.weights.as_deref().unwrap_or(&[]);
            let sum: f64 = (self.rule.coeffs.iter())
                .map(|&(wi, xi)| wi * rational(&self.weighted, w, mid + half * xi))
                .sum();
            self.knots[p].1 + self.length * half * sum
        } else {
            self.angle + bernstein::eval(&self.theta, t)
        }
    }

    /// The unit tangent `(cos θ(t), sin θ(t))`.
    pub fn tangent_at(&self, t: f64) -> Vec2 {
        Vec2::from_angle(self.angle_at(t))
    }

    /// The parameters in `(0, 1)` where the curvature changes sign: the inflection points
    /// (roots of `K`, or of its numerator `Σ B_i^n w_i κ_i` for a rational function; seed
    /// 003 §5), found by Bernstein root isolation. Points where `K` touches zero without
    /// changing sign are not inflections.
    pub fn inflections(&self) -> Vec<f64> {
        let mut out = Vec::new();
        match &self.weights {
            None => sign_changes(&self.curvatures, &mut out),
            Some(_) => sign_changes(&self.weighted, &mut out),
        }
        out
    }

    /// The parameters in `(0, 1)` where `dκ/ds` changes sign: the curvature extrema (roots
    /// of `K′`, of degree `n − 1`; for a rational function the roots of the numerator
    /// `f′g − fg′`, of degree `2n − 2`, seed 003 eq. 11).
    pub fn curvature_extrema(&self) -> Vec<f64> {
        let mut d = Vec::new();
        match &self.weights {
            None => bernstein::derivative(&self.curvatures, &mut d),
            Some(w) => bernstein::rational_derivative_numerator(&self.curvatures, w, &mut d),
        }
        let mut out = Vec::new();
        sign_changes(&d, &mut out);
        out
    }

    /// Whether the curvature varies monotonically (never increases and never decreases along
    /// the same segment): `dκ/ds` does not change sign in `(0, 1)` (seed 003 §5). A constant
    /// curvature is monotone.
    pub fn is_monotone(&self) -> bool {
        self.curvature_extrema().is_empty()
    }

    /// Cubic Béziers within a tolerance of the curve, through the crate's fitting adapter
    /// ([`crate::fit::fit`]), which also measures the distance reached.
    pub fn to_bezpath(&self, options: &FitOptions) -> Result<Fitted, Error> {
        fit(core::slice::from_ref(self), false, options)
    }

    /// A curvature comb from the exact curvature: `samples` teeth at uniform arc length
    /// (both ends included), each from `P(t)` to `P(t) − scale · K(t) · n(t)` with `n` the left
    /// normal — pointing away from the centre of curvature, `scale · |K|` long, as
    /// [`crate::analysis::curvature_comb`] draws them — followed by the polyline through the
    /// tips. Fewer than two samples or a non-finite scale give an empty path.
    pub fn curvature_comb(&self, scale: f64, samples: usize) -> BezPath {
        let mut out = BezPath::new();
        if samples < 2 || !scale.is_finite() {
            return out;
        }
        let teeth: Vec<(Point, Point)> = (0..samples)
            .map(|j| {
                let t = j as f64 / (samples - 1) as f64;
                let p = self.eval(t);
                let n = self.tangent_at(t).turn_90();
                (p, p - scale * self.curvature_at(t) * n)
            })
            .collect();
        for (j, &(base, tip)) in teeth.iter().enumerate() {
            out.move_to(base);
            out.line_to(tip);
            if let Some(&(_, next)) = teeth.get(j + 1) {
                out.line_to(next);
            }
        }
        out
    }

    /// The largest `|K|` over the segment: at the ends and the curvature extrema.
    pub fn max_abs_curvature(&self) -> f64 {
        self.curvature_extrema()
            .into_iter()
            .chain([0.0, 1.0])
            .map(|t| self.curvature_at(t).abs())
            .fold(0.0, f64::max)
    }

    /// The knot index `p` of the piece holding `t` (clamped to the segment) and its start.
    fn piece_of(&self, t: f64) -> (usize, f64) {
        let pieces = self.knots.len() - 1;
        let p = ((t * pieces as f64).floor().max(0.0) as usize).min(pieces - 1);
        (p, p as f64 / pieces as f64)
    }

    /// `(L ∫_a^t (cos θ, sin θ), θ(t))` by the segment's rule on `[a, t]`, `a` the start
    /// of piece `p`. For a rational function the angles at the nodes are
    /// `θ(a) + L ∫_a^{u_k} K_R`, from the spectral integration matrix.
    fn piece_integral(&self, p: usize, a: f64, t: f64) -> (Vec2, f64) {
        let (mid, half) = (0.5 * (a + t), 0.5 * (t - a));
        let coeffs = self.rule.coeffs;
        let m = coeffs.len();
        let mut sum = Vec2::ZERO;
        if self.theta.is_empty() {
            let w = self.weights.as_deref().unwrap_or(&[]);
            let mut f = [0.0; MAX_RULE];
            for (fj, &(_, xj)) in f.iter_mut().zip(coeffs) {
                *fj = rational(&self.weighted, w, mid + half * xj);
            }
            let s = self.rule.matrix();
            let theta_a = self.knots[p].1;
            let scale = self.length * half;
            let mut total = 0.0;
            for (k, &(wk, _)) in coeffs.iter().enumerate() {
                let row = &s[k * m..(k + 1) * m];
                let integral: f64 = row.iter().zip(&f[..m]).map(|(s, f)| s * f).sum();
                let (sn, cs) = (theta_a + scale * integral).sin_cos();
                sum += wk * Vec2::new(cs, sn);
                total += wk * f[k];
            }
            (sum * (half * self.length), theta_a + scale * total)
        } else {
            for &(wi, xi) in coeffs {
                let th = self.angle + bernstein::eval(&self.theta, mid + half * xi);
                let (s, c) = th.sin_cos();
                sum += wi * Vec2::new(c, s);
            }
            let end = self.angle + bernstein::eval(&self.theta, t);
            (sum * (half * self.length), end)
        }
    }
}

/// The largest table of a [`Rule`].
const MAX_RULE: usize = 24;

/// `K_R(τ) = Σ B_i w_i κ_i / Σ B_i w_i`, given `w_i κ_i` and `w_i`.
fn rational(weighted: &[f64], w: &[f64], t: f64) -> f64 {
    bernstein::eval(weighted, t) / bernstein::eval(w, t)
}

/// Checks weights: finite, positive, one per control curvature.
pub(crate) fn check_weights(w: &[f64], count: usize) -> Result<(), Error> {
    if w.len() != count {
        return Err(Error::InvalidOption(
            "there must be one weight per control curvature",
        ));
    }
    if !w.iter().all(|w| w.is_finite() && *w > 0.0) {
        return Err(Error::InvalidOption("weights must be finite and positive"));
    }
    Ok(())
}

impl ParamCurve for IntrinsicSeg {
    /// `P(t) = P_0 + L ∫_0^t (cos θ, sin θ)`: the cached position at the start of `t`'s
    /// piece plus one 16-point Gauss–Legendre rule.
    fn eval(&self, t: f64) -> Point {
        let (p, a) = self.piece_of(t);
        self.knots[p].0 + self.piece_integral(p, a, t).0
    }

    /// The curve on `range`, exactly: the curvature function restricted by de Casteljau
    /// subdivision (of `w_i κ_i` and `w_i` for a rational one), length `L |t₁ − t₀|`, start
    /// point and angle at `t₀`. A reversed range gives the reversed curve (angle + π,
    /// curvature negated).
    fn subsegment(&self, range: Range<f64>) -> IntrinsicSeg {
        let (t0, t1) = (range.start, range.end);
        let (lo, hi) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
        let reversed = t1 < t0;
        let (mut k, w) = match &self.weights {
            None => {
                let mut k = self.curvatures.clone();
                bernstein::restrict(&mut k, lo, hi);
                (k, None)
            }
            Some(w) => {
                let mut num = self.weighted.clone();
                let mut den = w.clone();
                bernstein::restrict(&mut num, lo, hi);
                bernstein::restrict(&mut den, lo, hi);
                let k = num.iter().zip(&den).map(|(n, d)| n / d).collect();
                (k, Some(den))
            }
        };
        let mut angle = self.angle_at(t0);
        if reversed {
            k.reverse();
            for v in &mut k {
                *v = -*v;
            }
            angle += core::f64::consts::PI;
        }
        let w = match (w, reversed) {
            (Some(mut w), true) => {
                w.reverse();
                Some(w)
            }
            (w, _) => w,
        };
        let length = self.length * (hi - lo);
        let bound = length * k.iter().fold(0.0f64, |m, v: &f64| m.max(v.abs()));
        let mut seg = IntrinsicSeg {
            start: self.eval(t0),
            angle,
            length,
            curvatures: k,
            weights: w,
            theta: Vec::new(),
            weighted: Vec::new(),
            knots: Vec::new(),
            rule: Rule::new(0.0, None),
        };
        seg.cache(bound);
        seg
    }

    fn start(&self) -> Point {
        self.start
    }

    fn end(&self) -> Point {
        self.knots.last().map_or(self.start, |k| k.0)
    }
}

impl ParamCurveArclen for IntrinsicSeg {
    /// Exactly `L`: the curve is parameterized by arc length.
    fn arclen(&self, _accuracy: f64) -> f64 {
        self.length
    }

    /// Exactly `s / L`, clamped to `[0, 1]`.
    fn inv_arclen(&self, arclen: f64, _accuracy: f64) -> f64 {
        if self.length > 0.0 {
            (arclen / self.length).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }
}

/// The derivative `dP/dt = L (cos θ, sin θ)` of an [`IntrinsicSeg`] on a parameter range,
/// as a kurbo curve (a vector returned as a `Point`).
#[derive(Clone, Debug, PartialEq)]
pub struct IntrinsicDeriv {
    seg: IntrinsicSeg,
    range: Range<f64>,
}

/// The second derivative `d²P/dt² = L² K (−sin θ, cos θ)` of an [`IntrinsicSeg`] on a parameter
/// range, scaled by `scale` (the chain-rule factor of a restricted first derivative).
#[derive(Clone, Debug, PartialEq)]
pub struct IntrinsicDeriv2 {
    seg: IntrinsicSeg,
    range: Range<f64>,
    scale: f64,
}

fn lerp_range(range: &Range<f64>, u: f64) -> f64 {
    range.start + u * (range.end - range.start)
}

fn compose(outer: &Range<f64>, inner: Range<f64>) -> Range<f64> {
    lerp_range(outer, inner.start)..lerp_range(outer, inner.end)
}

impl ParamCurve for IntrinsicDeriv {
    fn eval(&self, u: f64) -> Point {
        let t = lerp_range(&self.range, u);
        (self.seg.length * self.seg.tangent_at(t)).to_point()
    }

    fn subsegment(&self, range: Range<f64>) -> IntrinsicDeriv {
        IntrinsicDeriv {
            seg: self.seg.clone(),
            range: compose(&self.range, range),
        }
    }
}

impl ParamCurveDeriv for IntrinsicDeriv {
    type DerivResult = IntrinsicDeriv2;

    fn deriv(&self) -> IntrinsicDeriv2 {
        IntrinsicDeriv2 {
            seg: self.seg.clone(),
            range: self.range.clone(),
            scale: self.range.end - self.range.start,
        }
    }
}

impl ParamCurve for IntrinsicDeriv2 {
    fn eval(&self, u: f64) -> Point {
        let t = lerp_range(&self.range, u);
        let l = self.seg.length;
        let n = self.seg.tangent_at(t).turn_90();
        (self.scale * l * l * self.seg.curvature_at(t) * n).to_point()
    }

    fn subsegment(&self, range: Range<f64>) -> IntrinsicDeriv2 {
        IntrinsicDeriv2 {
            seg: self.seg.clone(),
            range: compose(&self.range, range),
            scale: self.scale,
        }
    }
}

impl ParamCurveDeriv for IntrinsicSeg {
    type DerivResult = IntrinsicDeriv;

    fn deriv(&self) -> IntrinsicDeriv {
        IntrinsicDeriv {
            seg: self.clone(),
            range: 0.0..1.0,
        }
    }
}

impl ParamCurveCurvature for IntrinsicSeg {
    /// kurbo's sign: `−K(t)` (negative for left turns). Use
    /// [`IntrinsicSeg::curvature_at`] for the crate's sign.
    fn curvature(&self, t: f64) -> f64 {
        -self.curvature_at(t)
    }
}

impl ParamCurveFit for IntrinsicSeg {
    fn sample_pt_tangent(&self, t: f64, _sign: f64) -> CurveFitSample {
        let (p, tangent) = self.sample_pt_deriv(t);
        CurveFitSample { p, tangent }
    }

    fn sample_pt_deriv(&self, t: f64) -> (Point, Vec2) {
        (self.eval(t), self.length * self.tangent_at(t))
    }

    /// None: the speed is `L` everywhere, so there are no cusps.
    fn break_cusp(&self, _range: Range<f64>) -> Option<f64> {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f64::consts::{FRAC_PI_2, PI};

    #[test]
    fn intrinsic_circle_is_exact() {
        // Constant curvature 1 over a length π/2: a quarter of the unit circle around (0, 1).
        let seg = IntrinsicSeg::new(Point::ZERO, 0.0, FRAC_PI_2, &[1.0, 1.0, 1.0]).unwrap();
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            let a = t * FRAC_PI_2;
            let exact = Point::new(a.sin(), 1.0 - a.cos());
            assert!((seg.eval(t) - exact).hypot() < 1e-15, "{t}");
        }
        assert!((seg.end_angle() - FRAC_PI_2).abs() < 1e-15);
        assert!((seg.turning() - FRAC_PI_2).abs() < 1e-15);
        assert!(seg.is_monotone());
        assert!(seg.inflections().is_empty());
    }

    #[test]
    fn intrinsic_line() {
        let seg = IntrinsicSeg::new(Point::new(1.0, 2.0), PI / 6.0, 2.0, &[0.0, 0.0]).unwrap();
        let end = seg.end();
        assert!((end - Point::new(1.0 + 3f64.sqrt(), 3.0)).hypot() < 1e-15);
        assert_eq!(seg.arclen(1e-9), 2.0);
        assert_eq!(seg.inv_arclen(0.5, 1e-9), 0.25);
    }

    #[test]
    fn intrinsic_quadrature_converges() {
        // Degree-5 curvature functions turning several times, polynomial and rational:
        // compare the cached end point with a rule on 8× as many pieces.
        let k = [3.0, -7.0, 11.0, 2.0, -5.0, 9.0];
        let w = [1.0, 0.2, 3.0, 1.5, 0.4, 2.0];
        for seg in [
            IntrinsicSeg::new(Point::ZERO, 0.3, 4.0, &k).unwrap(),
            IntrinsicSeg::rational(Point::ZERO, 0.3, 4.0, &k, &w).unwrap(),
        ] {
            let fine = 8 * (seg.knots.len() - 1);
            let mut p = Vec2::ZERO;
            for q in 0..fine {
                let (a, b) = (q as f64 / fine as f64, (q + 1) as f64 / fine as f64);
                let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
                for &(wi, xi) in kurbo::common::GAUSS_LEGENDRE_COEFFS_32 {
                    let th = seg.angle_at(mid + half * xi);
                    p += wi * half * Vec2::from_angle(th);
                }
            }
            let p = (p * seg.length()).to_point();
            let err = (p - seg.end()).hypot();
            assert!(err < 1e-13 * seg.length(), "{err:e}");
            for t in [0.1, 0.45, 0.8] {
                let sub = seg.subsegment(0.0..t);
                assert!((sub.end() - seg.eval(t)).hypot() < 1e-13 * seg.length());
            }
        }
    }

    #[test]
    fn intrinsic_subsegment_is_exact() {
        let k = [0.5, -2.0, 1.5, 3.0];
        let seg = IntrinsicSeg::new(Point::new(0.2, -0.1), 0.7, 3.0, &k).unwrap();
        let sub = seg.subsegment(0.3..0.8);
        assert!((sub.length() - 1.5).abs() < 1e-15);
        for i in 0..=8 {
            let u = i as f64 / 8.0;
            let t = 0.3 + 0.5 * u;
            assert!((sub.eval(u) - seg.eval(t)).hypot() < 1e-13);
            assert!((sub.curvature_at(u) - seg.curvature_at(t)).abs() < 1e-13);
        }
        // Reversed: same points backwards, curvature negated.
        let rev = seg.subsegment(0.8..0.3);
        for i in 0..=8 {
            let u = i as f64 / 8.0;
            let t = 0.8 - 0.5 * u;
            assert!((rev.eval(u) - seg.eval(t)).hypot() < 1e-13);
            assert!((rev.curvature_at(u) + seg.curvature_at(t)).abs() < 1e-13);
        }
        let w = [1.0, 3.0, 0.5, 2.0];
        let rat = IntrinsicSeg::rational(Point::ZERO, 0.0, 2.0, &k, &w).unwrap();
        let sub = rat.subsegment(0.1..0.6);
        for i in 0..=8 {
            let u = i as f64 / 8.0;
            let t = 0.1 + 0.5 * u;
            assert!((sub.eval(u) - rat.eval(t)).hypot() < 1e-13);
            assert!((sub.curvature_at(u) - rat.curvature_at(t)).abs() < 1e-12);
        }
    }

    #[test]
    fn intrinsic_kurbo_curvature_sign() {
        // A left turn: the crate's curvature is positive, kurbo's negative, and kurbo's
        // default formula on the derivatives agrees with the override.
        let seg = IntrinsicSeg::new(Point::ZERO, 0.0, 1.0, &[1.0, 2.0]).unwrap();
        let t = 0.4;
        assert!((seg.curvature_at(t) - 1.4).abs() < 1e-15);
        assert!((ParamCurveCurvature::curvature(&seg, t) + 1.4).abs() < 1e-15);
        let d = seg.deriv();
        let d2 = d.deriv();
        let (v, a) = (d.eval(t).to_vec2(), d2.eval(t).to_vec2());
        assert!((a.cross(v) / v.hypot().powi(3) + 1.4).abs() < 1e-14);
        // Derivative curves against finite differences, also restricted.
        let h = 1e-6;
        let fd = (seg.eval(t + h) - seg.eval(t - h)) / (2.0 * h);
        assert!((d.eval(t).to_vec2() - fd).hypot() < 1e-8);
        let ds = d.subsegment(0.2..0.6);
        let fd2 = (ds.eval(0.5 + h).to_vec2() - ds.eval(0.5 - h).to_vec2()) / (2.0 * h);
        assert!((ds.deriv().eval(0.5).to_vec2() - fd2).hypot() < 1e-7);
    }

    #[test]
    fn intrinsic_bad_input_is_typed() {
        assert!(IntrinsicSeg::new(Point::ZERO, 0.0, 1.0, &[]).is_err());
        assert!(IntrinsicSeg::new(Point::ZERO, f64::NAN, 1.0, &[1.0]).is_err());
        assert!(IntrinsicSeg::new(Point::ZERO, 0.0, -1.0, &[1.0]).is_err());
        assert!(IntrinsicSeg::new(Point::ZERO, 0.0, 1.0, &[f64::INFINITY]).is_err());
        assert!(IntrinsicSeg::new(Point::ZERO, 0.0, 1e6, &[1.0]).is_err());
        assert_eq!(
            IntrinsicSeg::new(Point::new(f64::NAN, 0.0), 0.0, 1.0, &[1.0]),
            Err(Error::NonFinitePoint { index: 0 })
        );
        assert!(IntrinsicSeg::rational(Point::ZERO, 0.0, 1.0, &[1.0, 2.0], &[1.0]).is_err());
        assert!(IntrinsicSeg::rational(Point::ZERO, 0.0, 1.0, &[1.0, 2.0], &[1.0, 0.0]).is_err());
        // Zero length is a point.
        let p = IntrinsicSeg::new(Point::new(1.0, 1.0), 0.0, 0.0, &[5.0]).unwrap();
        assert_eq!(p.end(), Point::new(1.0, 1.0));
    }
}
