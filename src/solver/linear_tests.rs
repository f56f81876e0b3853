//! The condensed, structured and split solves of a Newton step against dense ones.

use super::linear::Var;
use super::*;
use crate::basis::Basis;
use crate::linalg::DenseLu;

/// The Newton system assembled into the banded/bordered solver gives the same step as a
/// dense LU of the same entries.
fn check<const D: usize, const B: usize>(closed: bool, n: usize) {
    check_with::<D, B>(closed, n, Vec::new());
}

fn check_with<const D: usize, const B: usize>(
    closed: bool,
    n: usize,
    tangents: Vec<Option<Tangent<D>>>,
) {
    let p: Vec<[f64; D]> = (0..n)
        .map(|i| {
            let th = i as f64 / n as f64 * std::f64::consts::TAU;
            core::array::from_fn(|k| match k {
                0 => th.cos() * (1.0 + 0.2 * (3.0 * th).sin()),
                1 => th.sin(),
                _ => 0.2 * (2.0 * th).cos(),
            })
        })
        .collect();
    let prob = Problem {
        closed,
        p: p.clone(),
        ghost: [[1.5; D], [-1.5; D]],
        basis: vec![Basis::Cubic(crate::basis::CubicEk::new(0.7)); n],
        tangents,
    };
    let mut ws = Workspace::<D, B>::default();
    ws.cold_start(&prob);
    ws.classic_iteration(&prob, true);
    ws.size_buffers(n);
    ws.lin.reset(closed, n, B - 1);
    ws.assemble(&prob, 1e-12);
    // The full Newton system, dense.
    let nn = n * B;
    // (The rows as `eval_block` has them: `assemble` may order a block's rows otherwise,
    // which leaves the step as it is.)
    let mut dense = DenseLu::default();
    dense.reset(nn);
    let mut full = Vec::with_capacity(nn);
    for j in 0..n {
        let loc = Workspace::<D, B>::local(&prob, &ws.state, j);
        let mut scale = [1.0; 2];
        let mut sink = |row: usize, col: Var, v: f64| {
            if let Some(c) = col.index::<D, B>(closed, n, j) {
                dense.add(j * B + row, c, v);
            }
        };
        let r = Workspace::<D, B>::eval_block::<true, false>(
            &prob, j, &loc, &mut scale, &mut 0.0, &mut sink,
        );
        full.extend(r.iter().map(|v| -v));
    }
    assert!(dense.factor());
    dense.solve(&mut full);
    // The condensed system through the banded / bordered / small dense solver.
    assert!(ws.lin.factor());
    assert!(ws.condensed_step());
    for (a, b) in ws.step.iter().zip(&full) {
        assert!(
            (a - b).abs() <= 1e-8 * (1.0 + b.abs()),
            "closed={closed} n={n}: {a} vs {b}"
        );
    }
}

#[test]
fn condensed_step_with_tangents() {
    for (closed, n) in [(true, 7), (false, 7), (true, 40), (false, 40)] {
        let mut tangents = vec![None; n];
        let at = |end| if closed { TangentAt::Peak } else { end };
        tangents[0] = Some(Tangent {
            dir: [0.6, 0.8],
            at: at(TangentAt::Start),
        });
        tangents[3] = Some(Tangent {
            dir: [-1.0, 0.0],
            at: TangentAt::Peak,
        });
        tangents[n - 1] = Some(Tangent {
            dir: [0.0, -1.0],
            at: at(TangentAt::End),
        });
        check_with::<2, 4>(closed, n, tangents);
    }
}

/// After an accepted Newton step, the residual rescaled from the line search's
/// measure equals the one evaluated with the factorization's row scales, bit for bit.
fn check_refreeze<const D: usize, const B: usize>(closed: bool, n: usize, basis: Basis) {
    let p: Vec<[f64; D]> = (0..n)
        .map(|i| {
            let th = i as f64 / n as f64 * std::f64::consts::TAU;
            // Jagged and without symmetry (a symmetric start can be a solution).
            let r = if i % 2 == 0 { 1.0 } else { 0.8 } + 0.1 * (3.0 * th + 0.5).sin();
            core::array::from_fn(|k| match k {
                0 => r * th.cos(),
                1 => r * th.sin(),
                _ => 0.1 * (2.0 * th).cos(),
            })
        })
        .collect();
    let prob = Problem {
        closed,
        p,
        ghost: [[1.5; D], [-1.5; D]],
        basis: vec![basis; n],
        tangents: Vec::new(),
    };
    let tol = 1e-12;
    let mut ws = Workspace::<D, B>::default();
    ws.cold_start(&prob);
    ws.trial.clone_from(&ws.state);
    ws.size_buffers(n);
    for _ in 0..3 {
        ws.classic_iteration(&prob, true);
    }
    let mut accepted = 0;
    for _ in 0..3 {
        ws.lin.reset(closed, n, B - 1);
        let phi = ws.assemble(&prob, tol);
        ws.fact_scale.clone_from(&ws.scale);
        if ws.max_residual() <= tol || !ws.newton_step(&prob, phi, tol) {
            break;
        }
        accepted += 1;
        let fast = ws.refreeze();
        let (res, check) = (ws.res.clone(), ws.check.clone());
        let slow = ws.residual_frozen(&prob, tol, false);
        assert_eq!(fast.to_bits(), slow.to_bits(), "closed={closed} n={n}");
        for (a, b) in res.iter().flatten().zip(ws.res.iter().flatten()) {
            assert_eq!(a.to_bits(), b.to_bits(), "closed={closed} n={n}");
        }
        for (a, b) in check.iter().flatten().zip(ws.check.iter().flatten()) {
            assert_eq!(a.to_bits(), b.to_bits(), "closed={closed} n={n}");
        }
    }
    assert!(
        accepted > 0,
        "closed={closed} n={n}: no Newton step to check"
    );
}

#[test]
fn refrozen_residual_matches_a_frozen_evaluation() {
    let cubic = Basis::Cubic(crate::basis::CubicEk::new(0.8));
    for basis in [Basis::QUADRATIC, cubic] {
        for &n in &[3, 4, 5, 9, 17] {
            check_refreeze::<2, 4>(true, n, basis);
            check_refreeze::<2, 4>(false, n, basis);
            check_refreeze::<3, 5>(true, n, basis);
        }
    }
}

#[test]
fn structured_solve_matches_dense() {
    for &n in &[17, 9, 6, 5, 4, 3] {
        check::<2, 4>(false, n);
        check::<3, 5>(false, n);
        check::<2, 4>(true, n);
        check::<3, 5>(true, n);
    }
}

/// Runs `f` with curves of `min` blocks or more cut in two halves.
fn with_split_min<R>(min: usize, f: impl FnOnce() -> R) -> R {
    let old = super::split::SPLIT_MIN.with(|c| c.replace(min));
    let r = f();
    super::split::SPLIT_MIN.with(|c| c.set(old));
    r
}

#[test]
fn split_solve_matches_dense() {
    // The halves, the separator and the tail of a cut curve (classic iteration, Jacobian
    // assembly, condensed solve, recovery of δt) against the dense Newton system.
    with_split_min(8, || {
        for &n in &[8, 9, 10, 17, 31] {
            check::<2, 4>(false, n);
            check::<3, 5>(false, n);
            check::<2, 4>(true, n);
            check::<3, 5>(true, n);
        }
    });
}

#[test]
fn split_solves_match_whole_ones() {
    // Whole solves of curves cut in two halves converge to the same curves as uncut.
    for closed in [true, false] {
        for (basis, n) in [
            (Basis::QUADRATIC, 40),
            (Basis::Cubic(crate::basis::CubicEk::new(0.85)), 41),
        ] {
            let p: Vec<[f64; 2]> = (0..n)
                .map(|i| {
                    let th = i as f64 / n as f64 * std::f64::consts::TAU;
                    let r = if i % 2 == 0 { 1.0 } else { 0.9 };
                    [r * th.cos(), r * th.sin()]
                })
                .collect();
            let prob = Problem {
                closed,
                p,
                ghost: [[1.2, -0.1], [1.2, 0.1]],
                basis: vec![basis; n],
                tangents: Vec::new(),
            };
            let set = Settings {
                tolerance: 1e-12,
                max_iterations: 200,
                newton_chords: true,
            };
            let solve = || {
                let mut ws = Workspace::<2, 4>::default();
                let mut scratch = Problem {
                    closed,
                    p: vec![],
                    ghost: [[0.0; 2]; 2],
                    basis: vec![],
                    tangents: Vec::new(),
                };
                let out = ws.solve_cold(&prob, &set, &mut scratch);
                (out, ws.state)
            };
            let (whole, a) = solve();
            let (cut, b) = with_split_min(8, solve);
            assert!(whole.converged && cut.converged, "{closed} {n}");
            for (x, y) in a.c.iter().zip(&b.c) {
                assert!(
                    (x[0] - y[0]).abs() + (x[1] - y[1]).abs() < 1e-10,
                    "{closed} {n}"
                );
            }
            for (x, y) in a.t.iter().zip(&b.t) {
                assert!((x - y).abs() < 1e-8, "{closed} {n}: {x} vs {y}");
            }
        }
    }
}
