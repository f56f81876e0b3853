//! Gauss–Legendre rules for the integrals of intrinsic curves, and the spectral integration
//! matrix that gives indefinite integrals at the nodes of a rule.
//!
//! The position integrand `(cos θ, sin θ)` oscillates at the rate the curve turns. A rule is
//! chosen from a bound `T ≥ max_τ |dθ/dτ|` (for a Bézier curvature function,
//! `L · max|κ_i|` by the convex hull property): one 16-point piece while `T ≤ ½`, else
//! 24-point pieces each turning by at most [`PIECE_TURN`]. Measured on random angle
//! polynomials of degree up to 11 (the worst are alternating control curvatures), the error
//! relative to the length is below 1e-14 for one 16-point piece at `T = ½` and 3e-15 for a
//! 24-point piece at `T = 8` (the unit test `quadrature_accuracy` repeats the measurement).

use std::sync::OnceLock;

use kurbo::common::{GAUSS_LEGENDRE_COEFFS_16, GAUSS_LEGENDRE_COEFFS_24};

/// The largest turning of one 24-point piece.
pub const PIECE_TURN: f64 = 6.0;

/// The largest turning bound for which one 16-point piece is used.
const SMALL_TURN: f64 = 0.5;

/// The largest number of pieces of a rule (a bound of 6e5 radians, far beyond
/// [`super::MAX_TURNING`]).
const MAX_PIECES: f64 = 1e5;

/// A composite Gauss–Legendre rule on `[0, 1]`: `pieces` equal pieces with the same
/// `(weight, abscissa)` table on `[−1, 1]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Rule {
    /// Number of equal pieces.
    pub pieces: usize,
    /// The `(weight, abscissa)` table.
    pub coeffs: &'static [(f64, f64)],
}

impl Rule {
    /// The rule for a turning bound `bound`; for a rational function with weights `w`, at
    /// least `2 ⌈log₂ ρ⌉` pieces, `ρ = max w / min w` (its curvature varies faster as the
    /// weights spread).
    pub fn new(bound: f64, weights: Option<&[f64]>) -> Rule {
        let mut pieces = 1.0;
        let mut coeffs = GAUSS_LEGENDRE_COEFFS_16;
        if bound > SMALL_TURN || weights.is_some() {
            coeffs = GAUSS_LEGENDRE_COEFFS_24;
            pieces = (bound / PIECE_TURN).ceil().max(1.0);
        }
        if let Some(w) = weights {
            let (lo, hi) = w.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &w| {
                (lo.min(w), hi.max(w))
            });
            // log₂ of the ratio as a difference: `hi / lo` overflows for subnormal weights.
            pieces = pieces.max(2.0 * (hi.log2() - lo.log2()).ceil());
        }
        Rule {
            pieces: pieces.min(MAX_PIECES) as usize,
            coeffs,
        }
    }

    /// The number of nodes.
    pub fn len(&self) -> usize {
        self.pieces * self.coeffs.len()
    }

    /// The spectral integration matrix of the rule's table (see [`integration_matrix`]).
    pub fn matrix(&self) -> &'static [f64] {
        integration_matrix(self.coeffs)
    }
}

/// The spectral integration matrix `S` of a Gauss–Legendre table with nodes `x_k` and weights
/// `w_k` (row-major, `m × m`): `S[k][j] = ∫_{−1}^{x_k} ℓ_j(x) dx` for the Lagrange basis `ℓ_j`
/// on the nodes, so that `Σ_j S[k][j] f(x_j) ≈ ∫_{−1}^{x_k} f` (exact for polynomials of degree
/// below `m`). With the Legendre expansion `ℓ_j = w_j Σ_{i<m} (i + ½) P_i(x_j) P_i` (exact by
/// the rule's own orthogonality) and `∫_{−1}^{x} P_i = (P_{i+1}(x) − P_{i−1}(x)) / (2i + 1)`:
///
/// ```text
/// S[k][j] = w_j [ ½ (x_k + 1) + ½ Σ_{i=1}^{m−1} P_i(x_j) (P_{i+1}(x_k) − P_{i−1}(x_k)) ].
/// ```
///
/// Only the 16- and 24-point tables are used; their matrices are computed once.
pub(crate) fn integration_matrix(coeffs: &'static [(f64, f64)]) -> &'static [f64] {
    static M16: OnceLock<Vec<f64>> = OnceLock::new();
    static M24: OnceLock<Vec<f64>> = OnceLock::new();
    let cell = if coeffs.len() == 16 { &M16 } else { &M24 };
    cell.get_or_init(|| build_matrix(coeffs))
}

/// Legendre polynomials `P_0(x)..P_{m}(x)` by the three-term recurrence.
fn legendre(x: f64, m: usize) -> Vec<f64> {
    let mut p = Vec::with_capacity(m + 1);
    p.push(1.0);
    if m >= 1 {
        p.push(x);
    }
    for i in 1..m {
        let next = ((2 * i + 1) as f64 * x * p[i] - i as f64 * p[i - 1]) / (i + 1) as f64;
        p.push(next);
    }
    p
}

fn build_matrix(coeffs: &[(f64, f64)]) -> Vec<f64> {
    let m = coeffs.len();
    let polys: Vec<Vec<f64>> = coeffs.iter().map(|&(_, x)| legendre(x, m)).collect();
    let mut s = vec![0.0; m * m];
    for k in 0..m {
        let xk = coeffs[k].1;
        let pk = &polys[k];
        for j in 0..m {
            let pj = &polys[j];
            let mut v = 0.5 * (xk + 1.0);
            for i in 1..m {
                v += 0.5 * pj[i] * (pk[i + 1] - pk[i - 1]);
            }
            s[k * m + j] = coeffs[j].0 * v;
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integration_matrix_is_exact_for_polynomials() {
        for coeffs in [GAUSS_LEGENDRE_COEFFS_16, GAUSS_LEGENDRE_COEFFS_24] {
            let s = integration_matrix(coeffs);
            let m = coeffs.len();
            // f(x) = x^d for d < m: ∫_{−1}^{x} = (x^{d+1} − (−1)^{d+1}) / (d + 1).
            for d in [0, 1, 5, m - 1] {
                for k in 0..m {
                    let xk = coeffs[k].1;
                    let approx: f64 = (0..m)
                        .map(|j| s[k * m + j] * coeffs[j].1.powi(d as i32))
                        .sum();
                    let exact =
                        (xk.powi(d as i32 + 1) - (-1f64).powi(d as i32 + 1)) / (d + 1) as f64;
                    assert!((approx - exact).abs() < 1e-13, "m {m} d {d} k {k}");
                }
            }
        }
    }

    /// The accuracy claim of the module docs: `∫_0^1 e^{iθ}` for random angle polynomials of
    /// degree up to 11 turning by at most `T`, against 64 pieces of 32 points.
    #[test]
    fn quadrature_accuracy() {
        use super::super::bernstein::{antiderivative, eval};
        let integrate = |theta: &[f64], rule: Rule| -> (f64, f64) {
            let h = 1.0 / rule.pieces as f64;
            let (mut x, mut y) = (0.0, 0.0);
            for p in 0..rule.pieces {
                let mid = (p as f64 + 0.5) * h;
                for &(w, xi) in rule.coeffs {
                    let (s, c) = eval(theta, mid + 0.5 * h * xi).sin_cos();
                    x += w * c * 0.5 * h;
                    y += w * s * 0.5 * h;
                }
            }
            (x, y)
        };
        let reference = Rule {
            pieces: 64,
            coeffs: kurbo::common::GAUSS_LEGENDRE_COEFFS_32,
        };
        let mut seed: u64 = 12345;
        let mut rnd = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for bound in [0.5, 1.0, 3.0, 6.0, 12.0, 30.0] {
            for case in 0..100 {
                let n = 1 + case % 11;
                let a: Vec<f64> = if case % 3 == 0 {
                    (0..=n)
                        .map(|i| if i % 2 == 0 { bound } else { -bound })
                        .collect()
                } else {
                    (0..=n).map(|_| bound * (2.0 * rnd() - 1.0)).collect()
                };
                let mut theta = Vec::new();
                antiderivative(&a, &mut theta);
                let (rx, ry) = integrate(&theta, reference);
                let (x, y) = integrate(&theta, Rule::new(bound, None));
                assert!(
                    (x - rx).hypot(y - ry) < 1e-13,
                    "bound {bound} case {case}: {:e}",
                    (x - rx).hypot(y - ry)
                );
            }
        }
    }
}
