//! The block Jacobians against finite differences of the residuals.

use super::linear::Var;
use super::*;
use crate::basis::Basis;

fn dense_jacobian<const D: usize, const B: usize>(
    prob: &Problem<D>,
    st: &State<D>,
) -> (Vec<f64>, Vec<f64>) {
    let n = st.t.len();
    let nn = n * B;
    let mut jac = vec![0.0; nn * nn];
    let mut res = vec![0.0; nn];
    for j in 0..n {
        let loc = Workspace::<D, B>::local(prob, st, j);
        let mut scale = [1.0; 2];
        let mut sink = |row: usize, col: Var, v: f64| {
            if let Some(c) = col.index::<D, B>(prob.closed, n, j) {
                jac[(j * B + row) * nn + c] += v;
            }
        };
        let r = Workspace::<D, B>::eval_block::<true, false>(
            prob, j, &loc, &mut scale, &mut 0.0, &mut sink,
        );
        res[j * B..(j + 1) * B].copy_from_slice(&r);
    }
    (jac, res)
}

fn residual<const D: usize, const B: usize>(
    prob: &Problem<D>,
    st: &State<D>,
    scales: &[[f64; 2]],
) -> Vec<f64> {
    let n = st.t.len();
    let mut out = vec![0.0; n * B];
    for j in 0..n {
        let loc = Workspace::<D, B>::local(prob, st, j);
        let mut sc = scales[j];
        let r = Workspace::<D, B>::block::<true>(prob, j, &loc, &mut sc);
        out[j * B..(j + 1) * B].copy_from_slice(&r);
    }
    out
}

fn check<const D: usize, const B: usize>(closed: bool, a: f64, tangents: Vec<Option<Tangent<D>>>) {
    let n = 6;
    let mut seed = 5u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64) / ((1u64 << 53) as f64)
    };
    let p: Vec<[f64; D]> = (0..n)
        .map(|i| {
            let th = i as f64 / n as f64 * std::f64::consts::TAU;
            core::array::from_fn(|k| match k {
                0 => th.cos() + 0.1 * rnd(),
                1 => th.sin() + 0.1 * rnd(),
                _ => 0.3 * rnd(),
            })
        })
        .collect();
    let prob = Problem {
        closed,
        p: p.clone(),
        ghost: [[0.5; D], [-0.5; D]],
        basis: vec![Basis::Cubic(crate::basis::CubicEk::new(a)); n],
        tangents,
    };
    let st = State {
        c: p.iter()
            .map(|q| core::array::from_fn(|k| q[k] * 1.1 + 0.05 * rnd()))
            .collect(),
        lam: (0..n)
            .map(|i| {
                if !closed && i == n - 1 {
                    1.0
                } else {
                    0.3 + 0.4 * rnd()
                }
            })
            .collect(),
        t: (0..n).map(|_| 0.3 + 0.4 * rnd()).collect(),
    };
    let (jac, _) = dense_jacobian::<D, B>(&prob, &st);
    let n_all = n * B;
    let scales: Vec<[f64; 2]> = (0..n)
        .map(|j| {
            let loc = Workspace::<D, B>::local(&prob, &st, j);
            let mut s = [1.0; 2];
            Workspace::<D, B>::block::<false>(&prob, j, &loc, &mut s);
            s
        })
        .collect();
    let h = 1e-6;
    for col in 0..n_all {
        let (blk, k) = (col / B, col % B);
        if !closed && blk == n - 1 && k == D {
            continue;
        }
        let mut plus = st.clone();
        let mut minus = st.clone();
        match k {
            _ if k < D => {
                plus.c[blk][k] += h;
                minus.c[blk][k] -= h;
            }
            _ if k == D => {
                plus.lam[blk] += h;
                minus.lam[blk] -= h;
            }
            _ => {
                plus.t[blk] += h;
                minus.t[blk] -= h;
            }
        }
        let rp = residual::<D, B>(&prob, &plus, &scales);
        let rm = residual::<D, B>(&prob, &minus, &scales);
        for row in 0..n_all {
            if !closed && row == (n - 1) * B + D {
                continue;
            }
            let fd = (rp[row] - rm[row]) / (2.0 * h);
            let an = jac[row * n_all + col];
            assert!(
                (fd - an).abs() <= 1e-6 * (1.0 + fd.abs()),
                "closed={closed} a={a} row {row} col {col}: fd {fd} analytic {an}"
            );
        }
    }
}

#[test]
fn jacobian_matches_finite_differences() {
    for &closed in &[true, false] {
        for &a in &[2.0 / 3.0, 0.8] {
            check::<2, 4>(closed, a, Vec::new());
            check::<3, 5>(closed, a, Vec::new());
        }
    }
}

#[test]
fn tangent_rows_match_finite_differences() {
    let tan = |x: f64, y: f64, at| {
        let n = x.hypot(y);
        Some(Tangent {
            dir: [x / n, y / n],
            at,
        })
    };
    for &a in &[2.0 / 3.0, 0.8] {
        let peak = vec![
            tan(1.0, 0.2, TangentAt::Peak),
            None,
            tan(-0.3, 1.0, TangentAt::Peak),
            None,
            None,
            tan(0.5, -1.0, TangentAt::Peak),
        ];
        check::<2, 4>(true, a, peak);
        let ends = vec![
            tan(1.0, 0.0, TangentAt::Start),
            None,
            tan(0.0, 1.0, TangentAt::Peak),
            None,
            None,
            tan(1.0, -1.0, TangentAt::End),
        ];
        check::<2, 4>(false, a, ends);
    }
}
