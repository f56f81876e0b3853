//! The classic local/global iteration (seed 000 Algorithm 1) that starts Newton, and the
//! extrapolation of its last steps.

use super::peak::{peak_parameter, EndTerms};
use super::problem::{Problem, State};
use super::residual::JointTerms;
use super::split::{split4, Split};
use super::tuning::classic::EXTRAPOLATE_COSINE;
use super::tuning::newton::NEWTON_CHORD_MIN_BLOCKS;
use super::tuning::peak::{LONG_START_PEAK_T_TOLERANCE, START_PEAK_T_TOLERANCE};
use super::workspace::Workspace;
use super::{lerp, LAMBDA_MIN};
use crate::basis::SegmentBasis;
use crate::linalg::solve_tridiagonal;

impl<const D: usize, const B: usize> Workspace<D, B> {
    /// One iteration of the classic local/global loop (seed 000 Algorithm 1), generalized
    /// to the basis: λ from the G2 formula, `t` by a bracketed root solve of the peak
    /// condition with `c_j` eliminated (to the looser start tolerance with `start`), then the
    /// (cyclic) tridiagonal system for the `c_j`.
    pub(crate) fn classic_iteration(&mut self, prob: &Problem<D>, start: bool) {
        let n = self.n();
        let start = start.then_some(if n < NEWTON_CHORD_MIN_BLOCKS {
            START_PEAK_T_TOLERANCE
        } else {
            LONG_START_PEAK_T_TOLERANCE
        });
        for a in self.tri.iter_mut() {
            a.resize(n, 0.0);
        }
        self.tri_d.resize(n, [0.0; D]);
        let split = Split::of(prob.closed, n);
        // λ (Jacobi style: from the previous λ's), into `trial.lam`.
        let st = &self.state;
        match split {
            None => Self::ratios_from(prob, st, 0, &mut self.trial.lam),
            Some(split) => {
                let [l0, l1, l2, l3] = split4(&mut self.trial.lam, split.cuts());
                let [j0, j1, j2, j3] = split.ranges().map(|r| r.start);
                let pieces = [(j0, l0), (j1, l1), (j2, l2), (j3, l3)];
                Split::each(pieces, |(j, l)| Self::ratios_from(prob, st, j, l));
            }
        }
        for j in 0..n {
            if prob.closed || j + 1 < n {
                self.state.lam[j] = self.trial.lam[j];
            }
        }
        // t, and the coefficients of the linear system; `t` into `trial.t`.
        let st = &self.state;
        let [a, b, c] = &mut self.tri;
        match split {
            None => {
                let out = (&mut self.trial.t[..], &mut a[..], &mut b[..], &mut c[..]);
                Self::peaks_from(prob, st, 0, &mut self.ends, start, out, &mut self.tri_d);
            }
            Some(split) => {
                let cuts = split.cuts();
                let [t0, t1, t2, t3] = split4(&mut self.trial.t, cuts);
                let [a0, a1, a2, a3] = split4(a, cuts);
                let [b0, b1, b2, b3] = split4(b, cuts);
                let [c0, c1, c2, c3] = split4(c, cuts);
                let [d0, d1, d2, d3] = split4(&mut self.tri_d, cuts);
                let [j0, j1, j2, j3] = split.ranges().map(|r| r.start);
                // The end terms are a function of the basis: each piece keeps its own copy
                // of the cache, and the first half's is kept.
                let [mut e0, mut e1, mut e2, mut e3] = [self.ends; 4];
                let pieces = [
                    (j0, &mut e0, (t0, a0, b0, c0), d0),
                    (j1, &mut e1, (t1, a1, b1, c1), d1),
                    (j2, &mut e2, (t2, a2, b2, c2), d2),
                    (j3, &mut e3, (t3, a3, b3, c3), d3),
                ];
                Split::each(pieces, |(j, ends, out, d)| {
                    Self::peaks_from(prob, st, j, ends, start, out, d)
                });
                self.ends = e0;
            }
        }
        core::mem::swap(&mut self.state.t, &mut self.trial.t);
        let [a, b, c] = &self.tri;
        if solve_tridiagonal(a, b, c, &mut self.tri_d, prob.closed, &mut self.scratch)
            && self.tri_d.iter().all(|v| v.iter().all(|x| x.is_finite()))
        {
            self.state.c.copy_from_slice(&self.tri_d);
        }
    }

    /// The classic loop's `λ` of the blocks `j0..j0 + lam.len()` into `lam` (an open curve's
    /// last one is left as it is).
    fn ratios_from(prob: &Problem<D>, st: &State<D>, j0: usize, lam: &mut [f64]) {
        let n = st.t.len();
        let mut carry = None;
        for (i, out) in lam.iter_mut().enumerate() {
            let j = j0 + i;
            if !prob.closed && j == n - 1 {
                continue;
            }
            let l = Self::local(prob, st, j);
            let jt = JointTerms::new(prob, j, &l, &mut carry);
            let (a, b) = (jt.x.sqrt(), jt.y.sqrt());
            let lam = a / (a + b);
            *out = if lam.is_finite() {
                lam.clamp(LAMBDA_MIN, 1.0 - LAMBDA_MIN)
            } else {
                0.5
            };
        }
    }

    /// The classic loop's peak parameters `t` of the blocks `j0..j0 + t.len()` (into `t`)
    /// and their rows of the tridiagonal system for the control points (`a`, `b`, `c`, `d`).
    #[allow(clippy::type_complexity)]
    fn peaks_from(
        prob: &Problem<D>,
        st: &State<D>,
        j0: usize,
        ends: &mut Option<EndTerms>,
        start: Option<f64>,
        (t, a, b, c): (&mut [f64], &mut [f64], &mut [f64], &mut [f64]),
        d: &mut [[f64; D]],
    ) {
        let n = st.t.len();
        let rows = t.iter_mut().zip(a).zip(b).zip(c).zip(d).enumerate();
        for (i, ((((t, a), b), c), d)) in rows {
            let j = j0 + i;
            let l = Self::local(prob, st, j);
            // The segment's ends (as `State::segment` has them) from the gathered block.
            let (q0, q2) = (lerp(l.cm, l.c0, l.lm), lerp(l.c0, l.c1, l.l0));
            let basis = prob.basis[j];
            *t = peak_parameter(basis, ends, q0, q2, prob.p[j], l.t, start);
            let w = basis.weights(*t);
            let (w0, w2) = (w[0][0], w[0][1]);
            let mut dj = prob.p[j];
            let aj = w0 * (1.0 - l.lm);
            let cj = w2 * l.l0;
            *a = aj;
            *b = 1.0 - aj - cj;
            *c = cj;
            if !prob.closed {
                if j == 0 {
                    dj = core::array::from_fn(|k| dj[k] - aj * prob.ghost[0][k]);
                }
                if j == n - 1 {
                    dj = core::array::from_fn(|k| dj[k] - cj * prob.ghost[1][k]);
                }
            }
            *d = dj;
        }
    }

    /// Record the unknowns before one of the last two classic iterations for
    /// [`extrapolate`](Self::extrapolate): before the second to last (`first`), the
    /// iterate; before the last, also the step from it.
    pub(super) fn record_iterate(&mut self, first: bool) {
        let [prev, step] = &mut self.extra;
        let st = &self.state;
        let n = st.t.len();
        if first {
            prev.resize(n * B, 0.0);
            step.resize(n * B, 0.0);
        }
        // (The first call's step, from whatever `prev` held, is overwritten by the second:
        // one loop for both measured fewer instructions than a separate copy.)
        let blocks = prev.chunks_exact_mut(B).zip(step.chunks_exact_mut(B));
        for (j, (p, f)) in blocks.enumerate() {
            let x = Self::unknowns(st, j);
            for k in 0..B {
                f[k] = x[k] - p[k];
                p[k] = x[k];
            }
        }
    }

    /// The unknowns of block `j`: `c_j`, `λ_j`, `t_j`.
    #[inline(always)]
    fn unknowns(st: &State<D>, j: usize) -> [f64; B] {
        let (c, lam, t) = (st.c[j], st.lam[j], st.t[j]);
        core::array::from_fn(|k| match k {
            k if k < D => c[k],
            k if k == D => lam,
            _ => t,
        })
    }

    /// Extrapolate the last two classic steps `f₁`, `f₂` (Anderson acceleration of depth
    /// one, or a secant step along the iteration): `x ← x − γ f₂` with `γ` minimizing
    /// `|f₂ − γ (f₂ − f₁)|`. Where the classic loop contracts each step by a near-constant
    /// factor `ρ` (about 0.15 on the bear's three-point curves), `γ = ρ / (ρ − 1)` jumps to
    /// the limit of that geometric sequence, and Newton starts at a residual some twenty
    /// times smaller. `λ` and `t` are kept in their ranges.
    pub(super) fn extrapolate(&mut self, prob: &Problem<D>) {
        let [prev, f1] = &self.extra;
        let st = &mut self.state;
        let n = st.t.len();
        if prev.len() != n * B || f1.len() != n * B {
            return;
        }
        let (mut a11, mut a12, mut a22) = (0.0, 0.0, 0.0);
        for (j, (p, f1)) in prev.chunks_exact(B).zip(f1.chunks_exact(B)).enumerate() {
            let x = Self::unknowns(st, j);
            for k in 0..B {
                let f2 = x[k] - p[k];
                a11 += f1[k] * f1[k];
                a12 += f1[k] * f2;
                a22 += f2 * f2;
            }
        }
        // γ = f₂·(f₂ − f₁) / |f₂ − f₁|².
        let gamma = (a22 - a12) / (a11 - 2.0 * a12 + a22);
        // Only where the two steps are near parallel (cosine ≥ EXTRAPOLATE_COSINE: one mode
        // dominates, as in a geometric sequence) and contract by ρ ≤ 4/9 (γ ≥ -0.8). On the
        // bear's stiff curves, whose steps turn (cosines 0.6–0.8), extrapolating cost
        // iterations; so did a six-point εκ curve contracting by ρ ≈ 0.49 (42 iterations
        // instead of 12).
        if !(a12 >= EXTRAPOLATE_COSINE * (a11 * a22).sqrt() && (-0.8..=0.0).contains(&gamma)) {
            return;
        }
        for (j, p) in prev.chunks_exact(B).enumerate() {
            let x = Self::unknowns(st, j);
            let y: [f64; B] = core::array::from_fn(|k| x[k] - gamma * (x[k] - p[k]));
            st.c[j] = core::array::from_fn(|k| y[k]);
            if prob.closed || j + 1 < n {
                st.lam[j] = y[D].clamp(LAMBDA_MIN, 1.0 - LAMBDA_MIN);
            }
            st.t[j] = y[D + 1].clamp(0.0, 1.0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::basis::Basis;

    #[test]
    fn extrapolation_finds_the_limit_of_a_geometric_sequence_and_skips_turning_steps() {
        // Iterates x_k = x* + ρ^k v (one mode): the extrapolation from x_1, x_2, x_3 lands
        // on x*. Steps that turn (two modes of opposite sign) are left alone.
        let n = 3;
        let prob = Problem {
            closed: true,
            p: vec![[0.0; 2]; n],
            ghost: [[0.0; 2]; 2],
            basis: vec![Basis::QUADRATIC; n],
            tangents: Vec::new(),
        };
        let star = State {
            c: vec![[0.3, -0.2], [1.0, 0.5], [-0.4, 0.9]],
            lam: vec![0.4, 0.55, 0.6],
            t: vec![0.45, 0.5, 0.52],
        };
        let v = [[0.02, 0.01], [-0.03, 0.02], [0.01, -0.02]];
        let vl = [0.01, -0.02, 0.015];
        let vt = [-0.01, 0.02, 0.01];
        let iterate = |k: i32, rho: f64, turn: bool| {
            let mut st = star.clone();
            for j in 0..n {
                // A second mode of opposite sign on the first block when turning.
                let w = rho.powi(k)
                    + if turn && j == 0 {
                        0.9f64.powi(k) * (-1f64).powi(k)
                    } else {
                        0.0
                    };
                st.c[j] = core::array::from_fn(|d| star.c[j][d] + w * v[j][d]);
                st.lam[j] = star.lam[j] + w * vl[j];
                st.t[j] = star.t[j] + w * vt[j];
            }
            st
        };
        for (rho, turn, lands) in [(0.15, false, true), (0.3, false, true), (0.15, true, false)] {
            let mut ws = Workspace::<2, 4> {
                state: iterate(1, rho, turn),
                ..Default::default()
            };
            ws.record_iterate(true);
            ws.state = iterate(2, rho, turn);
            ws.record_iterate(false);
            ws.state = iterate(3, rho, turn);
            let before = ws.state.clone();
            ws.extrapolate(&prob);
            let err = |st: &State<2>| {
                (0..n)
                    .map(|j| {
                        let dc = (0..2).map(|d| (st.c[j][d] - star.c[j][d]).abs());
                        dc.fold((st.lam[j] - star.lam[j]).abs(), f64::max)
                            .max((st.t[j] - star.t[j]).abs())
                    })
                    .fold(0.0, f64::max)
            };
            if lands {
                assert!(err(&ws.state) < 1e-14, "ρ = {rho}: {}", err(&ws.state));
            } else {
                assert_eq!(ws.state.c, before.c, "turning steps are not extrapolated");
                assert_eq!(ws.state.lam, before.lam);
            }
        }
    }
}
