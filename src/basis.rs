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
        // κ(1) = |h(1)| 2Δ / (B(1)³ |s|³), and A(1) = 0 so h(1) = -A'(1) B(1).
        let w1 = self.weights(1.0);
        let a1 = w1[2][0]; // A'(1) = -w0''(1)
        let b1 = w1[1][1]; // B(1) = w2'(1)
        2.0 * a1.abs() / (b1 * b1)
    }
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
}

impl CubicEk {
    /// The quadratic segment of κ-curves (`a = 2/3`).
    pub(crate) const QUADRATIC: CubicEk = CubicEk {
        b: 0.0,
        a: 2.0 / 3.0,
    };

    /// The segment with shape parameter `a` (`a = 2/3` maps exactly to [`CubicEk::QUADRATIC`]).
    pub(crate) fn new(a: f64) -> CubicEk {
        if a == 2.0 / 3.0 {
            CubicEk::QUADRATIC
        } else {
            CubicEk {
                b: 2.0 - 3.0 * a,
                a,
            }
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

    #[test]
    fn cubic_ek_derivatives_match_finite_differences() {
        let basis = CubicEk::new(0.8);
        let h = 1e-6;
        for i in 1..10 {
            let t = i as f64 / 10.0;
            let (lo, mid, hi) = (basis.weights(t - h), basis.weights(t), basis.weights(t + h));
            for k in 0..4 {
                for j in 0..2 {
                    let fd = (hi[k][j] - lo[k][j]) / (2.0 * h);
                    assert_near(mid[k + 1][j], fd, 1e-7);
                }
            }
        }
    }

    #[test]
    fn quadratic_end_coefficient_is_one_and_cubic_matches_paper() {
        assert_near(CubicEk::QUADRATIC.end_coefficient(), 1.0, 1e-15);
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
