//! (Cyclic) tridiagonal systems with vector right-hand sides ([`solve_tridiagonal`]): the
//! Thomas algorithm, Sherman–Morrison for the cyclic case, and a pivoted elimination at
//! order 3.

// `!(x > 0.0)` is meant: it is also true for NaN, which must count as a zero pivot.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use super::pivot;

/// Solve the tridiagonal system `a_i x_{i-1} + b_i x_i + c_i x_{i+1} = d_i` (with `a_0` and
/// `c_{n-1}` ignored), or its cyclic version where `a_0` couples to `x_{n-1}` and `c_{n-1}`
/// to `x_0` (Sherman–Morrison). `d` is overwritten with the solution. Returns `false` if a
/// pivot vanishes.
pub(crate) fn solve_tridiagonal<const D: usize>(
    a: &[f64],
    b: &[f64],
    c: &[f64],
    d: &mut [[f64; D]],
    cyclic: bool,
    scratch: &mut TriScratch,
) -> bool {
    let n = d.len();
    if cyclic && n == 3 {
        return cyclic3(a, b, c, d);
    }
    let TriScratch { cp, cp2, u } = scratch;
    // Every multiplier is written before it is read.
    cp.resize(n, 0.0);
    if !cyclic || n < 3 {
        return thomas(a, b, c, d, cp, None);
    }
    // Sherman–Morrison: A = T + u vᵀ with u = (γ, 0, …, 0, c_{n-1}), v = (1, 0, …, 0, a_0/γ).
    let gamma = -b[0];
    let b0 = b[0] - gamma;
    let bn = b[n - 1] - c[n - 1] * a[0] / gamma;
    u.clear();
    u.resize(n, [0.0]);
    u[0] = [gamma];
    u[n - 1] = [c[n - 1]];
    // Solve T z = u and T y = d (long systems side by side: each solve is one chain of
    // divisions).
    let ends = Some((b0, bn));
    let ok = if n >= PARALLEL_TRIDIAGONAL {
        cp2.resize(n, 0.0);
        let (ok_u, ok_d) = crate::parallel::join(
            || thomas(a, b, c, u, cp2, ends),
            || thomas(a, b, c, d, cp, ends),
        );
        ok_u && ok_d
    } else {
        let ok = thomas(a, b, c, u, cp, ends);
        ok & thomas(a, b, c, d, cp, ends)
    };
    if !ok {
        return false;
    }
    let fact_den = 1.0 + u[0][0] + a[0] / gamma * u[n - 1][0];
    if !(fact_den.abs() > 0.0) {
        return false;
    }
    let mut num = [0.0; D];
    for (k, x) in num.iter_mut().enumerate() {
        *x = d[0][k] + a[0] / gamma * d[n - 1][k];
    }
    for (di, &[ui]) in d.iter_mut().zip(u.iter()) {
        for k in 0..D {
            di[k] -= num[k] / fact_den * ui;
        }
    }
    true
}

/// The cyclic system of order 3, a full 3 × 3 matrix (row `i` is `a_i`, `b_i`, `c_i` on the
/// columns `i - 1`, `i`, `i + 1` modulo 3), by Gaussian elimination with partial pivoting:
/// about 230 instructions against 540 for the two Thomas passes and the Sherman–Morrison
/// correction (callgrind). `false` if a pivot vanishes or is not finite.
// Index loops of fixed length: the compiler unrolls them fully (the iterator form measured
// about 8 000 instructions more on the bear drawing).
#[allow(clippy::needless_range_loop)]
fn cyclic3<const D: usize>(a: &[f64], b: &[f64], c: &[f64], d: &mut [[f64; D]]) -> bool {
    let mut m = [[b[0], c[0], a[0]], [a[1], b[1], c[1]], [c[2], a[2], b[2]]];
    let mut x: [[f64; D]; 3] = [d[0], d[1], d[2]];
    for k in 0..3 {
        let below = (k + 1..3).map(|i| (i, m[i][k]));
        let Some(p) = pivot((k, m[k][k]), below) else {
            return false;
        };
        m.swap(k, p);
        x.swap(k, p);
        let inv = 1.0 / m[k][k];
        for i in k + 1..3 {
            let f = m[i][k] * inv;
            for j in k + 1..3 {
                m[i][j] -= f * m[k][j];
            }
            for q in 0..D {
                x[i][q] -= f * x[k][q];
            }
        }
    }
    for k in (0..3).rev() {
        let inv = 1.0 / m[k][k];
        for q in 0..D {
            let mut s = x[k][q];
            for j in k + 1..3 {
                s -= m[k][j] * x[j][q];
            }
            x[k][q] = s * inv;
        }
    }
    d[..3].copy_from_slice(&x);
    true
}

/// Buffers of [`solve_tridiagonal`], reused between solves.
#[derive(Clone, Debug, Default)]
pub(crate) struct TriScratch {
    cp: Vec<f64>,
    /// The multipliers of the second of two solves run side by side.
    cp2: Vec<f64>,
    u: Vec<[f64; 1]>,
}

/// Cyclic tridiagonal systems of this order or more solve their two Thomas passes side by
/// side.
const PARALLEL_TRIDIAGONAL: usize = 2048;

/// Thomas algorithm with vector right-hand sides; `ends` overrides `b_0` and `b_{n-1}`.
fn thomas<const D: usize>(
    a: &[f64],
    b: &[f64],
    c: &[f64],
    d: &mut [[f64; D]],
    cp: &mut [f64],
    ends: Option<(f64, f64)>,
) -> bool {
    let n = d.len();
    let bi = |i: usize| match ends {
        Some((b0, _)) if i == 0 => b0,
        Some((_, bn)) if i == n - 1 => bn,
        _ => b[i],
    };
    let mut den = bi(0);
    if !(den.abs() > 0.0) {
        return false;
    }
    cp[0] = c[0] / den;
    for x in d[0].iter_mut() {
        *x /= den;
    }
    for i in 1..n {
        den = bi(i) - a[i] * cp[i - 1];
        if !(den.abs() > 0.0) {
            return false;
        }
        cp[i] = c[i] / den;
        let prev = d[i - 1];
        for k in 0..D {
            d[i][k] = (d[i][k] - a[i] * prev[k]) / den;
        }
    }
    for i in (0..n - 1).rev() {
        let next = d[i + 1];
        for k in 0..D {
            d[i][k] -= cp[i] * next[k];
        }
    }
    true
}
#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::testing::lcg;
    use crate::linalg::DenseLu;

    #[test]
    fn cyclic_tridiagonal_matches_dense() {
        let mut seed = 3;
        for &n in &[3usize, 4, 9] {
            for &cyclic in &[false, true] {
                let a: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
                let c: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
                let b: Vec<f64> = (0..n).map(|_| 2.5 + lcg(&mut seed)).collect();
                let d: Vec<[f64; 2]> = (0..n).map(|_| [lcg(&mut seed), lcg(&mut seed)]).collect();
                let mut dense = DenseLu::default();
                dense.reset(n);
                for i in 0..n {
                    dense.add(i, i, b[i]);
                    if i > 0 {
                        dense.add(i, i - 1, a[i]);
                    } else if cyclic {
                        dense.add(0, n - 1, a[0]);
                    }
                    if i + 1 < n {
                        dense.add(i, i + 1, c[i]);
                    } else if cyclic {
                        dense.add(n - 1, 0, c[n - 1]);
                    }
                }
                assert!(dense.factor());
                let mut x = d.clone();
                let mut scratch = TriScratch::default();
                assert!(solve_tridiagonal(&a, &b, &c, &mut x, cyclic, &mut scratch));
                for k in 0..2 {
                    let mut col: Vec<f64> = d.iter().map(|v| v[k]).collect();
                    dense.solve(&mut col);
                    for i in 0..n {
                        assert!((x[i][k] - col[i]).abs() < 1e-10, "n={n} cyclic={cyclic}");
                    }
                }
            }
        }
    }

    #[test]
    fn cyclic_order_three_pivots_and_reports_singular() {
        // b_0 = 0: the elimination must pivot (the Thomas passes would divide by it).
        let (a, b, c) = ([0.5, 0.25, 1.0], [0.0, 2.0, 0.5], [1.0, 0.75, 0.25]);
        let want = [[1.0, -2.0], [0.5, 3.0], [-1.5, 0.25]];
        let row = |i: usize, k: usize| {
            a[i] * want[(i + 2) % 3][k] + b[i] * want[i][k] + c[i] * want[(i + 1) % 3][k]
        };
        let mut x: Vec<[f64; 2]> = (0..3).map(|i| [row(i, 0), row(i, 1)]).collect();
        let mut scratch = TriScratch::default();
        assert!(solve_tridiagonal(&a, &b, &c, &mut x, true, &mut scratch));
        for i in 0..3 {
            for k in 0..2 {
                assert!((x[i][k] - want[i][k]).abs() < 1e-14, "{x:?}");
            }
        }
        // Rows summing to zero: the all-ones vector is in the kernel.
        let (a, b, c) = ([1.0, 1.0, 1.0], [-2.0, -2.0, -2.0], [1.0, 1.0, 1.0]);
        let mut x = vec![[1.0, 0.0]; 3];
        assert!(!solve_tridiagonal(&a, &b, &c, &mut x, true, &mut scratch));
        let mut x = vec![[f64::NAN, 0.0]; 3];
        let b = [f64::NAN, 2.0, 2.0];
        assert!(!solve_tridiagonal(&a, &b, &c, &mut x, true, &mut scratch));
    }

    #[test]
    fn long_cyclic_tridiagonal_solves() {
        // Long enough for the two Thomas passes to run side by side: A x = d checked row by
        // row.
        let mut seed = 9;
        let n = PARALLEL_TRIDIAGONAL + 5;
        let a: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
        let c: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
        let b: Vec<f64> = (0..n).map(|_| 2.5 + lcg(&mut seed)).collect();
        let d: Vec<[f64; 2]> = (0..n).map(|_| [lcg(&mut seed), lcg(&mut seed)]).collect();
        let mut x = d.clone();
        let mut scratch = TriScratch::default();
        assert!(solve_tridiagonal(&a, &b, &c, &mut x, true, &mut scratch));
        for i in 0..n {
            let (prev, next) = (x[(i + n - 1) % n], x[(i + 1) % n]);
            for k in 0..2 {
                let row = a[i] * prev[k] + b[i] * x[i][k] + c[i] * next[k];
                assert!(
                    (row - d[i][k]).abs() < 1e-12,
                    "row {i}: {row} vs {}",
                    d[i][k]
                );
            }
        }
    }
}
