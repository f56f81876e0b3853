//! Blending functions of the three-control-point segments used by κ- and εκ-curves.
//!
//! Every segment of these schemes is a curve `C(t) = w0(t) Q0 + w1(t) Q1 + w2(t) Q2` with
//! `w0 + w1 + w2 = 1`, so it can be written `C(t) = Q1 - w0(t) r + w2(t) s` with
//! `r = Q1 - Q0`, `s = Q2 - Q1`. Its derivatives are `C' = A r + B s` with `A = -w0'`,
//! `B = w2'`, and `C' × C'' = h(t) (r × s)` with `h = A B' - A' B`: the segment is planar,
//! and its curvature is `κ(t) = |h(t)| |r × s| / |C'(t)|³` (signed in 2D by `r × s`).
//!
//! The curvature is stationary where `h' N - 3 h P = 0`, with `N = C'·C'`, `P = C'·C''`.
//! Expanding `N` and `P` in `r·r`, `r·s`, `s·s` gives the form used by the solver:
//! `c_rr(t) r·r + c_rs(t) r·s + c_ss(t) s·s = 0` — free of the triangle area, so it stays
//! well defined for straight segments.

/// A family of segments described by `w0` and `w2` (see the module docs).
pub(crate) trait SegmentBasis: Copy {
    /// `[w0, w2]` and their derivatives of order 1 to 4 at `t`.
    fn weights(&self, t: f64) -> [[f64; 2]; 5];

    /// The coefficient `k` of the end curvature `κ(1) = k Δ(Q0, Q1, Q2) / |Q2 - Q1|³`
    /// (and, by symmetry, `κ(0) = k Δ / |Q1 - Q0|³`).
    fn end_coefficient(&self) -> f64 {
        end_coefficient_from_weights(self)
    }
}

/// [`SegmentBasis::end_coefficient`] from the weights at `t = 1`.
fn end_coefficient_from_weights(basis: &impl SegmentBasis) -> f64 {
    // κ(1) = |h(1)| 2Δ / (B(1)³ |s|³), and A(1) = 0 so h(1) = -A'(1) B(1).
    let w1 = basis.weights(1.0);
    let a1 = w1[2][0]; // A'(1) = -w0''(1)
    let b1 = w1[1][1]; // B(1) = w2'(1)
    2.0 * a1.abs() / (b1 * b1)
}

/// The constrained cubic of εκ-curves (seed 000 eq. 1):
/// `C(t) = (1-t)³Q0 + 3(1-t)²t[(1-a)Q0 + aQ1] + 3(1-t)t²[aQ1 + (1-a)Q2] + t³Q2`,
/// with `2/3 ≤ a < 1`; `a = 2/3` is exactly the quadratic Bézier of κ-curves.
///
/// In terms of `b = 2 - 3a`, `w0(t) = (1-t)²(1 + b t)` and `w2(t) = w0(1-t)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct CubicEk {
    b: f64,
    /// The shape parameter as given (kept so that it round-trips exactly).
    a: f64,
    /// The end coefficient, from the weights (the solver reads it for every joint).
    k: f64,
}

impl CubicEk {
    /// The quadratic segment of κ-curves (`a = 2/3`).
    pub(crate) const QUADRATIC: CubicEk = CubicEk {
        b: 0.0,
        a: 2.0 / 3.0,
        // 2 |w0''(1)| / w2'(1)² = 2 · 2 / 2², exactly.
        k: 1.0,
    };

    /// The segment with shape parameter `a` (`a = 2/3` maps exactly to [`CubicEk::QUADRATIC`]).
    pub(crate) fn new(a: f64) -> CubicEk {
        if a == 2.0 / 3.0 {
            CubicEk::QUADRATIC
        } else {
            let mut c = CubicEk {
                b: 2.0 - 3.0 * a,
                a,
                k: 0.0,
            };
            c.k = end_coefficient_from_weights(&c);
            c
        }
    }

    /// The shape parameter `a`.
    pub(crate) fn a(&self) -> f64 {
        self.a
    }

    /// `w0` and its derivatives of order 1 to 4.
    #[inline]
    fn w0(&self, t: f64) -> [f64; 5] {
        // w0 = 1 + (b-2) t + (1-2b) t² + b t³
        let b = self.b;
        let (c1, c2, c3) = (b - 2.0, 1.0 - 2.0 * b, b);
        [
            1.0 + t * (c1 + t * (c2 + t * c3)),
            c1 + t * (2.0 * c2 + t * 3.0 * c3),
            2.0 * c2 + 6.0 * c3 * t,
            6.0 * c3,
            0.0,
        ]
    }
}

impl SegmentBasis for CubicEk {
    #[inline]
    fn weights(&self, t: f64) -> [[f64; 2]; 5] {
        let f = self.w0(t);
        let g = self.w0(1.0 - t);
        [
            [f[0], g[0]],
            [f[1], -g[1]],
            [f[2], g[2]],
            [f[3], -g[3]],
            [f[4], g[4]],
        ]
    }

    #[inline]
    fn end_coefficient(&self) -> f64 {
        self.k
    }
}

/// The constrained quadratic trigonometric segment of εκ-curves (seed 000 eq. 17):
/// `C(t) = u²Q0 + 2uv[(1-a)Q0 + aQ1] + 2uw[(1-a)(Q0+Q2) + 2aQ1] + 2vw[aQ1 + (1-a)Q2] + w²Q2`
/// with `S = sin(πt/2)`, `C = cos(πt/2)`, `u = 1-S`, `v = S+C-1`, `w = 1-C` and
/// `1/2 ≤ a < 1`; `a = 1/2` is the linear trigonometric curve of eq. 18.
///
/// Collecting the weights of `Q0` and `Q2` (with `v + w = S`, `u + v = C`) and writing
/// `b = 1 - 2a`: `w0(t) = (1-S)(1 + bS)`, `w2(t) = (1-C)(1 + bC) = w0(1-t)`. This is the
/// trigonometric cubic Bernstein-like basis of seed 000 eq. 29 with `α = 2a`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TrigEk {
    b: f64,
    /// The shape parameter as given (kept so that it round-trips exactly).
    a: f64,
}

impl TrigEk {
    /// The segment with shape parameter `a`.
    pub(crate) fn new(a: f64) -> TrigEk {
        TrigEk {
            b: 1.0 - 2.0 * a,
            a,
        }
    }

    /// `f(x) = (1-x)(1+bx)` composed with `x(t)`, and its `t`-derivatives of order 1 to 4,
    /// given `x(t)` and its four derivatives.
    #[inline]
    fn compose(&self, x: [f64; 5]) -> [f64; 5] {
        let b = self.b;
        // f = 1 + (b-1)x - b x², f_x = (b-1) - 2bx, f_xx = -2b.
        let fx = (b - 1.0) - 2.0 * b * x[0];
        let fxx = -2.0 * b;
        [
            1.0 + x[0] * ((b - 1.0) - b * x[0]),
            fx * x[1],
            fxx * x[1] * x[1] + fx * x[2],
            3.0 * fxx * x[1] * x[2] + fx * x[3],
            fxx * (3.0 * x[2] * x[2] + 4.0 * x[1] * x[3]) + fx * x[4],
        ]
    }
}

impl SegmentBasis for TrigEk {
    #[inline]
    fn weights(&self, t: f64) -> [[f64; 2]; 5] {
        let w = core::f64::consts::FRAC_PI_2;
        let (s, c) = (w * t).sin_cos();
        let (w2, w3, w4) = (w * w, w * w * w, w * w * w * w);
        // Derivatives of S = sin(ωt) and C = cos(ωt).
        let ds = [s, w * c, -w2 * s, -w3 * c, w4 * s];
        let dc = [c, -w * s, -w2 * c, w3 * s, w4 * c];
        let f = self.compose(ds);
        let g = self.compose(dc);
        core::array::from_fn(|k| [f[k], g[k]])
    }

    fn end_coefficient(&self) -> f64 {
        // κ(1) = ((1-a)/a²) Δ / |Q2-Q1|³ (seed 000 eq. 26; the tests check it against the
        // weights).
        (1.0 - self.a) / (self.a * self.a)
    }
}

/// The segment family of one block of the solver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Basis {
    /// Constrained cubic Bernstein (κ-curves are its `a = 2/3` member).
    Cubic(CubicEk),
    /// Constrained quadratic trigonometric.
    Trig(TrigEk),
}

impl Basis {
    /// The quadratic Bézier of κ-curves.
    pub(crate) const QUADRATIC: Basis = Basis::Cubic(CubicEk::QUADRATIC);

    /// The shape parameter `a`.
    pub(crate) fn a(&self) -> f64 {
        match self {
            Basis::Cubic(b) => b.a(),
            Basis::Trig(b) => b.a,
        }
    }

    /// The member of the same family with shape parameter `a`.
    pub(crate) fn with_a(&self, a: f64) -> Basis {
        match self {
            Basis::Cubic(_) => Basis::Cubic(CubicEk::new(a)),
            Basis::Trig(_) => Basis::Trig(TrigEk::new(a)),
        }
    }
}

impl SegmentBasis for Basis {
    #[inline]
    fn weights(&self, t: f64) -> [[f64; 2]; 5] {
        match self {
            Basis::Cubic(b) => b.weights(t),
            Basis::Trig(b) => b.weights(t),
        }
    }

    #[inline]
    fn end_coefficient(&self) -> f64 {
        match self {
            Basis::Cubic(b) => b.end_coefficient(),
            Basis::Trig(b) => b.end_coefficient(),
        }
    }
}

/// What kind of curvature extremum a segment has at its peak parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Extremum {
    /// |κ| is locally maximal there (the schemes' intent).
    Max,
    /// |κ| is locally minimal there: the stationary point the scheme placed at the input
    /// point is a curvature minimum (εκ-trig with small `a` and gentle turns).
    Min,
    /// |κ| is locally maximal at the point, which sits at a segment end (`t_max` 0 or 1),
    /// but the segment's |κ| is higher inside: the point is not the segment's curvature
    /// peak. εκ-trig solutions with the peak pushed to an end can be like this (measured on
    /// 3 000 random star loops at `a` in 0.65–0.75: 232 of 1 287 end peaks, the interior
    /// |κ| up to 78 % higher); see [`Segment::extremum`](crate::Segment::extremum).
    EndOnly,
    /// The segment has collapsed onto its input point, which is an inflection of the curve:
    /// the neighbouring segments meet there, tangent to each other (G1), with curvatures of
    /// opposite signs. This is the limit of the curve as the point approaches the line
    /// through its neighbours on a curve symmetric about it (a symmetric S or wave); see
    /// [`Segment::is_collapsed`](crate::Segment::is_collapsed).
    Inflection,
}

/// Peak parameters closer than this to 0 or 1 are classified as at the segment end.
const END_SLACK: f64 = 1e-9;

/// Classifies the stationary point of `|κ|` at `t` of the segment `Q1 - w0 r + w2 s`.
///
/// With `h = A B' - A' B` (module docs), `|κ| = |h| |r × s| / N^{3/2}` and
/// `d|κ|/dt = sgn(h) |r × s| g / N^{5/2}`, `g = c_rr r·r + c_rs r·s + c_ss s·s`. Inside
/// `(0, 1)` the point is a maximum when `sgn(h) g' ≤ 0`; at `t = 0` (`t = 1`) it is a
/// maximum when `|κ|` does not increase into the segment (does not decrease towards the end).
pub(crate) fn classify<B: SegmentBasis>(basis: &B, rr: f64, rs: f64, ss: f64, t: f64) -> Extremum {
    let w = basis.weights(t);
    let st = Stationarity::new(&w);
    let h = (-w[1][0]) * w[2][1] - (-w[2][0]) * w[1][1];
    let sign = if h < 0.0 { -1.0 } else { 1.0 };
    let g = sign * (st.c[0] * rr + st.c[1] * rs + st.c[2] * ss);
    let dg = sign * (st.dc[0] * rr + st.dc[1] * rs + st.dc[2] * ss);
    // Slack for rounding in g, whose terms are of the size of |r|², |s|².
    let slack =
        1e-9 * (st.c[0].abs() * rr.abs() + st.c[1].abs() * rs.abs() + st.c[2].abs() * ss.abs());
    // Peak parameters within rounding of an end count as that end.
    let max = if t <= END_SLACK {
        g <= slack
    } else if t >= 1.0 - END_SLACK {
        g >= -slack
    } else {
        dg <= 0.0
    };
    if max {
        Extremum::Max
    } else {
        Extremum::Min
    }
}

/// Coefficients of the stationarity condition `c_rr r·r + c_rs r·s + c_ss s·s` and of its
/// `t`-derivative, from the basis weights (see the module docs).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Stationarity {
    /// `[c_rr, c_rs, c_ss]`.
    pub c: [f64; 3],
    /// `d/dt [c_rr, c_rs, c_ss]`.
    pub dc: [f64; 3],
}

impl Stationarity {
    /// Evaluate from `weights(t)`.
    #[inline]
    pub(crate) fn new(w: &[[f64; 2]; 5]) -> Stationarity {
        // A^(k) = -w0^(k+1), B^(k) = w2^(k+1)
        let a = [-w[1][0], -w[2][0], -w[3][0], -w[4][0]];
        let b = [w[1][1], w[2][1], w[3][1], w[4][1]];
        let h = a[0] * b[1] - a[1] * b[0];
        let h1 = a[0] * b[2] - a[2] * b[0];
        let h2 = a[1] * b[2] + a[0] * b[3] - a[3] * b[0] - a[2] * b[1];
        let c_rr = h1 * a[0] * a[0] - 3.0 * h * a[0] * a[1];
        let c_ss = h1 * b[0] * b[0] - 3.0 * h * b[0] * b[1];
        let c_rs = 2.0 * h1 * a[0] * b[0] - 3.0 * h * (a[0] * b[1] + a[1] * b[0]);
        let d_rr = h2 * a[0] * a[0] - h1 * a[0] * a[1] - 3.0 * h * (a[1] * a[1] + a[0] * a[2]);
        let d_ss = h2 * b[0] * b[0] - h1 * b[0] * b[1] - 3.0 * h * (b[1] * b[1] + b[0] * b[2]);
        let d_rs = 2.0 * h2 * a[0] * b[0]
            - h1 * (a[1] * b[0] + a[0] * b[1])
            - 3.0 * h * (2.0 * a[1] * b[1] + a[0] * b[2] + a[2] * b[0]);
        Stationarity {
            c: [c_rr, c_rs, c_ss],
            dc: [d_rr, d_rs, d_ss],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn assert_near(a: f64, b: f64, tol: f64) {
        assert!((a - b).abs() <= tol, "{a} vs {b}");
    }

    #[test]
    fn cubic_ek_weights_match_bernstein_form() {
        for &a in &[2.0 / 3.0, 0.75, 0.9, 0.99] {
            let basis = CubicEk::new(a);
            for i in 0..=20 {
                let t = i as f64 / 20.0;
                let u = 1.0 - t;
                let w0 = u * u * u + 3.0 * u * u * t * (1.0 - a);
                let w2 = t * t * t + 3.0 * u * t * t * (1.0 - a);
                let w = basis.weights(t);
                assert_near(w[0][0], w0, 1e-15);
                assert_near(w[0][1], w2, 1e-15);
            }
        }
    }

    /// The weights' derivatives of order 1 to 4 match central differences of the order below.
    fn assert_weight_derivatives(basis: impl SegmentBasis, tol: f64) {
        let h = 1e-6;
        for i in 1..10 {
            let t = i as f64 / 10.0;
            let (lo, mid, hi) = (basis.weights(t - h), basis.weights(t), basis.weights(t + h));
            for k in 0..4 {
                for j in 0..2 {
                    let fd = (hi[k][j] - lo[k][j]) / (2.0 * h);
                    assert_near(mid[k + 1][j], fd, tol);
                }
            }
            let (slo, shi) = (Stationarity::new(&lo), Stationarity::new(&hi));
            let smid = Stationarity::new(&mid);
            for k in 0..3 {
                assert_near(smid.dc[k], (shi.c[k] - slo.c[k]) / (2.0 * h), 1e-5);
            }
        }
    }

    #[test]
    fn cubic_ek_derivatives_match_finite_differences() {
        assert_weight_derivatives(CubicEk::new(0.8), 1e-7);
    }

    #[test]
    fn quadratic_end_coefficient_is_one_and_cubic_matches_paper() {
        assert_near(CubicEk::QUADRATIC.end_coefficient(), 1.0, 1e-15);
        // The stored coefficient is exactly the one the weights give.
        for a in [2.0 / 3.0, 0.7, 0.8, 0.95, 0.999] {
            let b = CubicEk::new(a);
            assert_eq!(b.end_coefficient(), end_coefficient_from_weights(&b));
        }
        // seed 000 eq. 8: κ(1) = (4/3)(1-a)Δ / (a²|Q2-Q1|³)
        for &a in &[0.7, 0.8, 0.95] {
            let k = CubicEk::new(a).end_coefficient();
            assert_near(k, 4.0 / 3.0 * (1.0 - a) / (a * a), 1e-14);
        }
    }

    #[test]
    fn quadratic_stationarity_is_the_vertex_condition() {
        // For the quadratic, c_rr rr + c_rs rs + c_ss ss = -48 (t |r-s|² - <r, r-s>).
        let (rr, rs, ss) = (2.0, 0.3, 1.5);
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            let st = Stationarity::new(&CubicEk::QUADRATIC.weights(t));
            let f = st.c[0] * rr + st.c[1] * rs + st.c[2] * ss;
            let expected = -48.0 * (t * (rr - 2.0 * rs + ss) - (rr - rs));
            assert_near(f, expected, 1e-12);
            let df = st.dc[0] * rr + st.dc[1] * rs + st.dc[2] * ss;
            assert_near(df, -48.0 * (rr - 2.0 * rs + ss), 1e-12);
        }
    }

    #[test]
    fn trig_weights_match_the_blending_form() {
        // Seed 000 eq. 17: w0 = u² + 2(1-a)(uv + uw), w2 = w² + 2(1-a)(uw + vw).
        for &a in &[0.5, 0.6, 0.75, 0.9] {
            let basis = TrigEk::new(a);
            for i in 0..=20 {
                let t = i as f64 / 20.0;
                let (s, c) = (core::f64::consts::FRAC_PI_2 * t).sin_cos();
                let (u, v, w) = (1.0 - s, s + c - 1.0, 1.0 - c);
                let w0 = u * u + 2.0 * (1.0 - a) * (u * v + u * w);
                let w2 = w * w + 2.0 * (1.0 - a) * (u * w + v * w);
                let got = basis.weights(t);
                assert_near(got[0][0], w0, 1e-15);
                assert_near(got[0][1], w2, 1e-15);
            }
        }
    }

    #[test]
    fn trig_derivatives_match_finite_differences() {
        assert_weight_derivatives(TrigEk::new(0.7), 1e-6);
    }

    /// The generic end coefficient computed from the weights.
    #[derive(Clone, Copy)]
    struct FromWeights(TrigEk);

    impl SegmentBasis for FromWeights {
        fn weights(&self, t: f64) -> [[f64; 2]; 5] {
            self.0.weights(t)
        }
    }

    #[test]
    fn trig_end_coefficient_matches_weights_and_paper() {
        // Seed 000 eq. 26: κ(1) = ((1-a)/a²) Δ / |Q2 - Q1|³.
        for &a in &[0.5, 0.55, 0.7, 0.9, 0.99] {
            let basis = TrigEk::new(a);
            assert_near(
                FromWeights(basis).end_coefficient(),
                basis.end_coefficient(),
                1e-12,
            );
            assert_near(basis.end_coefficient(), (1.0 - a) / (a * a), 1e-15);
        }
    }

    #[test]
    fn classify_symmetric_segments() {
        // A symmetric segment (|r| = |s|) is stationary at t = 1/2. The cubic is a maximum
        // there for every a ≥ 2/3; the trigonometric segment is a minimum for a near 1/2 and
        // gentle turns, and a maximum for large a (thresholds: tests/trig.rs).
        for deg in [1.0f64, 30.0, 60.0, 89.0, 120.0] {
            let th = deg.to_radians();
            let (rr, rs, ss) = (1.0, th.cos(), 1.0);
            for a in [2.0 / 3.0, 0.7, 0.9] {
                assert_eq!(classify(&CubicEk::new(a), rr, rs, ss, 0.5), Extremum::Max);
            }
            assert_eq!(classify(&TrigEk::new(0.9), rr, rs, ss, 0.5), Extremum::Max);
            if deg < 90.0 {
                assert_eq!(classify(&TrigEk::new(0.5), rr, rs, ss, 0.5), Extremum::Min);
            }
        }
    }

    #[test]
    fn stationarity_derivative_matches_finite_differences() {
        let basis = CubicEk::new(0.85);
        let h = 1e-6;
        for i in 1..10 {
            let t = i as f64 / 10.0;
            let lo = Stationarity::new(&basis.weights(t - h));
            let hi = Stationarity::new(&basis.weights(t + h));
            let mid = Stationarity::new(&basis.weights(t));
            for k in 0..3 {
                assert_near(mid.dc[k], (hi.c[k] - lo.c[k]) / (2.0 * h), 1e-6);
            }
        }
    }
}
