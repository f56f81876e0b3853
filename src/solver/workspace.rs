//! The solver's reusable [`Workspace`]: the unknowns, a trial copy for the line search and
//! the buffers of the Newton steps, and the starts of a solve.

use super::condense::Condensed;
use super::linear::Linear;
use super::peak::EndTerms;
use super::problem::{Problem, State};
use super::residual::Raw;
use super::window::{Edit, Window};
use crate::linalg::TriScratch;

/// Reusable solver state: the unknowns, a trial copy for the line search, and all buffers.
/// After the first solve of a given size nothing is allocated.
#[derive(Clone, Debug, Default)]
pub(crate) struct Workspace<const D: usize, const B: usize> {
    pub state: State<D>,
    pub(super) trial: State<D>,
    pub(super) res: Vec<[f64; B]>,
    /// The residuals measured by the convergence test (`res`, with the G2 row replaced by
    /// the relative |κ| mismatch).
    pub(super) check: Vec<[f64; B]>,
    pub(super) scale: Vec<[f64; 2]>,
    /// `res`, `check` and `scale` of the trial state of the line search: swapped in with it
    /// when it is accepted, so that a step landing within the tolerance is recognized
    /// without assembling the Jacobian there.
    pub(super) trial_res: Vec<[f64; B]>,
    pub(super) trial_check: Vec<[f64; B]>,
    pub(super) trial_scale: Vec<[f64; 2]>,
    /// What the line search measured of its trial state besides `trial_res` (curves cut in
    /// no halves), and of the state it was swapped in as: see [`Workspace::refreeze`].
    pub(super) trial_raw: Vec<Raw>,
    pub(super) raw: Vec<Raw>,
    pub(super) step: Vec<f64>,
    /// Right-hand side and solution of the condensed system (`B - 1` unknowns per block).
    pub(super) reduced: Vec<f64>,
    /// Per block, what eliminating `t_j` left behind (see [`Condensed`]).
    pub(super) cond: Vec<Condensed<B>>,
    pub(super) lin: Linear,
    /// What `lin` holds (for chord steps), and the row scales it was assembled with.
    pub(super) lin_state: LinState,
    pub(super) fact_scale: Vec<[f64; 2]>,
    pub(super) tri: [Vec<f64>; 3],
    pub(super) tri_d: Vec<[f64; D]>,
    /// The extrapolation of the classic loop ([`Workspace::extrapolate`]): the unknowns
    /// before the last classic iteration and the step of the one before, `B` per block.
    pub(super) extra: [Vec<f64>; 2],
    pub(super) scratch: TriScratch,
    /// The end terms of the last basis the classic loop met (a function of the basis
    /// alone, so they stay valid from one iteration and solve to the next).
    pub(super) ends: Option<EndTerms>,
    /// The window of local re-solves ([`window`](super::window)) and the edit the next warm re-solve
    /// follows.
    pub(super) window: Window<B>,
    pub(super) edit: Option<Edit>,
}

/// What the linear system holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) enum LinState {
    /// Nothing usable.
    #[default]
    Empty,
    /// The Jacobian of the current state, not yet factored.
    Assembled,
    /// Factors of an earlier state than the current one, too old for a warm start: the
    /// next warm re-solve assembles its own.
    Stale,
    /// The factors of a Jacobian of this problem's structure.
    Factored,
}

impl<const D: usize, const B: usize> Workspace<D, B> {
    const CHECK: () = assert!(B == D + 2, "block size must be D + 2");

    /// Number of unknown blocks.
    pub(super) fn n(&self) -> usize {
        self.state.t.len()
    }

    /// Allocate for `n` blocks and set the cold start: `c = p`, `λ = ½`, `t = ½`.
    pub(crate) fn cold_start(&mut self, prob: &Problem<D>) {
        #[allow(clippy::let_unit_value)]
        let _ = Self::CHECK;
        self.window.measured = false;
        let n = prob.p.len();
        let st = &mut self.state;
        st.c.clear();
        st.c.extend_from_slice(&prob.p);
        st.lam.clear();
        st.lam.resize(n, 0.5);
        if !prob.closed {
            st.lam[n - 1] = 1.0;
        }
        st.t.clear();
        st.t.resize(n, 0.5);
        self.trial.clone_from(&self.state);
        self.lin_state = LinState::Empty;
        self.window.invalidate();
    }

    /// Allocate for `prob` and start from the given unknowns (in the normalized frame), as
    /// if a solve had just ended there: the next solve starts warm from them. `false`, with
    /// a cold start instead, if they do not fit `prob` (another count, a value out of its
    /// range or not finite).
    pub(crate) fn start_at(
        &mut self,
        prob: &Problem<D>,
        c: &[[f64; D]],
        lam: &[f64],
        t: &[f64],
    ) -> bool {
        self.cold_start(prob);
        let n = prob.p.len();
        let fits = c.len() == n
            && lam.len() == n
            && t.len() == n
            && c.iter().flatten().all(|x| x.is_finite())
            && lam.iter().all(|l| (0.0..=1.0).contains(l))
            && t.iter().all(|t| (0.0..=1.0).contains(t))
            && (prob.closed || lam[n - 1] == 1.0);
        if fits {
            let st = &mut self.state;
            st.c.copy_from_slice(c);
            st.lam.copy_from_slice(lam);
            st.t.copy_from_slice(t);
            self.trial.clone_from(&self.state);
        }
        self.edit = None;
        fits
    }

    /// Before a warm re-solve changes the problem: if the stored factors are stale, assemble
    /// the Jacobian at the current state, the solution of `prob` (it does not depend on the
    /// target points, only on the unknowns).
    pub(crate) fn refresh_jacobian(&mut self, prob: &Problem<D>, tol: f64) {
        let n = self.n();
        if self.lin_state == LinState::Stale && prob.p.len() == n && self.res.len() == n {
            self.lin.reset(prob.closed, n, B - 1);
            self.assemble(prob, tol);
            self.fact_scale.clone_from(&self.scale);
            self.lin_state = LinState::Assembled;
        }
    }

    /// Forget the stored factorization (the problem's structure or shapes changed).
    pub(crate) fn invalidate(&mut self) {
        self.lin_state = LinState::Empty;
        self.window.invalidate();
    }

    /// The edit the next warm re-solve follows (`None`: points moved all over, or not at
    /// all); `rescaled` if the normalization changed scale, which the window's linearization
    /// does not carry over; `reframed` if it changed at all, which moves every control point.
    pub(crate) fn set_edit(&mut self, edit: Option<Edit>, rescaled: bool, reframed: bool) {
        self.edit = edit;
        if rescaled {
            self.window.invalidate();
        }
        if reframed {
            // Every control point moved in the normalized frame.
            self.window.measured = false;
        }
    }

    /// Size the per-block buffers of the Newton steps for `n` blocks (no-op once sized).
    pub(super) fn size_buffers(&mut self, n: usize) {
        self.res.resize(n, [0.0; B]);
        self.check.resize(n, [0.0; B]);
        self.scale.resize(n, [1.0; 2]);
        self.trial_res.resize(n, [0.0; B]);
        self.trial_check.resize(n, [0.0; B]);
        self.trial_scale.resize(n, [1.0; 2]);
        self.trial_raw.resize_with(n, Raw::default);
        self.raw.resize_with(n, Raw::default);
        self.step.resize(n * B, 0.0);
        self.cond.resize_with(n, Condensed::default);
    }

    /// Exchange the residual buffers (`res`, `check`, `scale`) with the trial ones.
    pub(super) fn swap_trial_residuals(&mut self) {
        core::mem::swap(&mut self.res, &mut self.trial_res);
        core::mem::swap(&mut self.check, &mut self.trial_check);
        core::mem::swap(&mut self.scale, &mut self.trial_scale);
        core::mem::swap(&mut self.raw, &mut self.trial_raw);
    }
}
