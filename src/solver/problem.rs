//! The data of a solve and its unknowns: [`Problem`] and [`State`], with the [`Settings`] and
//! [`Outcome`] of a solve.

use super::tangent::Tangent;
use super::{lerp, wrap};
use crate::basis::Basis;

/// The data of one solve: targets, shapes and topology, in normalized coordinates.
#[derive(Clone, Debug)]
pub(crate) struct Problem<const D: usize> {
    /// Closed curve (cyclic indices) or open (ghost ends).
    pub closed: bool,
    /// The points the segments must peak at, one per unknown block.
    pub p: Vec<[f64; D]>,
    /// Open curves: the first and last input points.
    pub ghost: [[f64; D]; 2],
    /// The segment basis of each block.
    pub basis: Vec<Basis>,
    /// A prescribed tangent per block (empty: none anywhere; see [`Tangent`]).
    pub tangents: Vec<Option<Tangent<D>>>,
}

/// The unknowns.
#[derive(Debug, Default)]
pub(crate) struct State<const D: usize> {
    pub c: Vec<[f64; D]>,
    pub lam: Vec<f64>,
    pub t: Vec<f64>,
}

impl<const D: usize> Clone for State<D> {
    fn clone(&self) -> Self {
        State {
            c: self.c.clone(),
            lam: self.lam.clone(),
            t: self.t.clone(),
        }
    }

    /// Copies into the existing buffers (the derived `clone_from` would allocate new ones):
    /// the solver copies states between iterations.
    fn clone_from(&mut self, source: &Self) {
        self.c.clone_from(&source.c);
        self.lam.clone_from(&source.lam);
        self.t.clone_from(&source.t);
    }
}

impl<const D: usize> State<D> {
    /// The middle control point `c_i`, `i` taken cyclically for closed curves; for open ones
    /// `c_{-1}` and `c_n` are the first and last input points.
    #[inline]
    pub(crate) fn control(&self, prob: &Problem<D>, i: isize) -> [f64; D] {
        let n = self.t.len();
        if prob.closed {
            self.c[wrap(i, n)]
        } else if i < 0 {
            prob.ghost[0]
        } else if i as usize >= n {
            prob.ghost[1]
        } else {
            self.c[i as usize]
        }
    }

    /// The joint ratio `λ_i`, `i` taken cyclically for closed curves; for open ones
    /// `λ_{-1} = 0` and `λ_{n-1} = λ_n = 1` (the ends are the input points).
    #[inline]
    pub(crate) fn ratio(&self, prob: &Problem<D>, i: isize) -> f64 {
        let n = self.t.len();
        if prob.closed {
            self.lam[wrap(i, n)]
        } else if i < 0 {
            0.0
        } else if i as usize >= n {
            1.0
        } else {
            self.lam[i as usize]
        }
    }

    /// The three defining points of segment `j`: `c_{j,0} = lerp(c_{j-1}, c_j, λ_{j-1})`,
    /// `c_j`, `c_{j,2} = lerp(c_j, c_{j+1}, λ_j)` (seed 000 eq. 7).
    #[inline]
    pub(crate) fn segment(&self, prob: &Problem<D>, j: usize) -> [[f64; D]; 3] {
        let j = j as isize;
        let c = self.control(prob, j);
        [
            lerp(self.control(prob, j - 1), c, self.ratio(prob, j - 1)),
            c,
            lerp(c, self.control(prob, j + 1), self.ratio(prob, j)),
        ]
    }
}

/// Solver options in normalized units.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Settings {
    pub tolerance: f64,
    pub max_iterations: usize,
    /// Follow each Newton step with chord steps while they contract well (cold solves of
    /// long curves gain most; warm re-solves do their own chord steps first).
    pub newton_chords: bool,
}

/// What a solve reports.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Outcome {
    pub iterations: usize,
    pub newton_steps: usize,
    pub converged: bool,
    pub residual: f64,
}
