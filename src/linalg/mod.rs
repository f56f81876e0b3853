//! Small direct solvers: banded and dense LU with partial pivoting, a bordered solve for
//! cyclic (wrap-around) banded systems, and (cyclic) tridiagonal systems with vector
//! right-hand sides. All buffers are owned by the structs and reused between solves.
//!
//! - [`band`]: banded LU ([`BandLu`]);
//! - [`dense`]: dense LU ([`DenseLu`]);
//! - [`bordered`]: a banded system with a small dense border ([`BorderedLu`]);
//! - [`split`]: a banded system cut in two halves by a separator ([`SplitLu`]);
//! - [`tridiagonal`]: (cyclic) tridiagonal systems ([`solve_tridiagonal`]);
//! - [`toeplitz`]: symmetric Toeplitz tridiagonal systems, streamed
//!   ([`solve_symmetric_toeplitz_into`]).

mod band;
mod bordered;
mod dense;
mod split;
mod toeplitz;
mod tridiagonal;

pub(crate) use band::BandLu;
pub(crate) use bordered::BorderedLu;
pub(crate) use dense::DenseLu;
pub(crate) use split::SplitLu;
pub(crate) use toeplitz::{solve_symmetric_toeplitz_into, Lin};
pub(crate) use tridiagonal::{solve_tridiagonal, TriScratch};

/// Partial pivoting: the index of the candidate of largest magnitude (the first of equals,
/// `first` winning ties), or `None` if that magnitude is zero or not finite.
#[inline(always)]
fn pivot(first: (usize, f64), rest: impl Iterator<Item = (usize, f64)>) -> Option<usize> {
    let (mut p, mut best) = (first.0, first.1.abs());
    for (i, v) in rest {
        let v = v.abs();
        if v > best {
            best = v;
            p = i;
        }
    }
    (best > 0.0 && best.is_finite()).then_some(p)
}

/// Helpers shared by the solvers' tests.
#[cfg(test)]
mod testing {
    use super::DenseLu;

    /// `solve` and the dense LU give the same solution for `rhs`.
    pub(super) fn assert_same_solution(
        mut solve: impl FnMut(&mut [f64]),
        dense: &DenseLu,
        rhs: &[f64],
    ) {
        let (mut x1, mut x2) = (rhs.to_vec(), rhs.to_vec());
        solve(&mut x1);
        dense.solve(&mut x2);
        for (a, b) in x1.iter().zip(&x2) {
            assert!((a - b).abs() < 1e-9 * (1.0 + b.abs()), "{a} vs {b}");
        }
    }

    /// A deterministic pseudo-random sequence for tests.
    pub(super) fn lcg(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((*seed >> 11) as f64) / ((1u64 << 53) as f64) - 0.5
    }
}
