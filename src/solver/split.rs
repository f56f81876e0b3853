//! Long curves cut in two halves and a border ([`Split`]), worked on side by side.

use super::tuning::split::SPLIT_MIN_BLOCKS;
use crate::parallel::join;

/// The length from which curves are cut ([`SPLIT_MIN_BLOCKS`]; the unit tests lower it to
/// cut short curves).
#[cfg(not(test))]
pub(super) fn split_min() -> usize {
    SPLIT_MIN_BLOCKS
}

#[cfg(test)]
thread_local! {
    pub(super) static SPLIT_MIN: core::cell::Cell<usize> = const { core::cell::Cell::new(SPLIT_MIN_BLOCKS) };
}

#[cfg(test)]
pub(super) fn split_min() -> usize {
    SPLIT_MIN.with(|c| c.get())
}

/// How the blocks of a long curve are cut: the first half `0..m`, a separator of two blocks
/// `m..m + 2`, the second half `m + 2..end`, and the tail `end..n` (the two blocks that
/// close a closed curve; empty for an open one). The blocks of a half touch only their own
/// half and the border (separator and tail), so the halves are worked on side by side.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Split {
    m: usize,
    end: usize,
    n: usize,
}

impl Split {
    /// The cut of `n` blocks, if the curve is long enough to be cut.
    pub(super) fn of(closed: bool, n: usize) -> Option<Split> {
        (n >= split_min().max(8)).then(|| Split {
            m: n / 2,
            end: if closed { n - 2 } else { n },
            n,
        })
    }

    /// Where the block ranges of [`ranges`](Self::ranges) meet.
    pub(super) fn cuts(&self) -> [usize; 3] {
        [self.m, self.m + 2, self.end]
    }

    /// The block ranges: first half, separator, second half, tail.
    pub(super) fn ranges(&self) -> [core::ops::Range<usize>; 4] {
        [
            0..self.m,
            self.m..self.m + 2,
            self.m + 2..self.end,
            self.end..self.n,
        ]
    }

    /// `f` on each of the four pieces of work (first half, separator, second half, tail):
    /// the halves side by side, then the border pieces; the results in the pieces' order.
    pub(super) fn each<T: Send, R: Send>(pieces: [T; 4], f: impl Fn(T) -> R + Sync) -> [R; 4] {
        let [p0, p1, p2, p3] = pieces;
        let (r0, r2) = join(|| f(p0), || f(p2));
        let r1 = f(p1);
        let r3 = f(p3);
        [r0, r1, r2, r3]
    }
}

/// `s` cut at `cuts` (ascending) into four pieces.
pub(super) fn split4<T>(s: &mut [T], [a, b, c]: [usize; 3]) -> [&mut [T]; 4] {
    let (s0, rest) = s.split_at_mut(a);
    let (s1, rest) = rest.split_at_mut(b - a);
    let (s2, s3) = rest.split_at_mut(c - b);
    [s0, s1, s2, s3]
}
