//! Fairing and simplification ([`draft`](super::draft), steps 4 and 5): the anchors where
//! the draft turns the other way than the original are mended, and those the piece does not
//! need are dropped.

use kurbo::PathSeg;

use super::distance::{within, Target};
use super::{curvature_at, AnchorKind, Cand, Drafter, Solved};

/// The anchors (corners and open ends excepted) where the drafted curvature has the other
/// sign than the original's.
fn flipped(segs: &[PathSeg], closed: bool, anchors: &[Cand], solved: &Solved) -> Vec<usize> {
    let m = anchors.len();
    let off = usize::from(!closed);
    let drafted = solved.spline.segments();
    (0..m)
        .filter(|&i| {
            let interior = closed || (m > 2 && i > 0 && i + 1 < m);
            let Some(seg) = i.checked_sub(off).and_then(|j| drafted.get(j)) else {
                return false;
            };
            interior
                && anchors[i].kind != AnchorKind::Corner
                && seg.curvature(seg.t_max) * curvature_at(segs, anchors[i].s, closed, |k| k) < 0.0
        })
        .collect()
}

fn flipped_count(segs: &[PathSeg], closed: bool, anchors: &[Cand], solved: &Solved) -> usize {
    flipped(segs, closed, anchors, solved).len()
}

impl Drafter<'_> {
    /// The fairing pass ([`draft`](super::draft), step 4): while an anchor has a drafted
    /// curvature of the other sign than the original's there, the piece is solved in turn
    /// with it moved halfway to its previous or next neighbour, without it, and with two
    /// anchors halfway to its neighbours instead; the first that stays within the tolerance
    /// with fewer such anchors is kept. An anchor none of these fixes is left alone.
    pub(super) fn fair(
        &mut self,
        segs: &[PathSeg],
        closed: bool,
        original: &Target<'_>,
        k: usize,
        (mut anchors, mut solved): (Vec<Cand>, Solved),
    ) -> (Vec<Cand>, Solved) {
        let n = segs.len() as f64;
        let wrap = |x: f64| if closed { x.rem_euclid(n) } else { x };
        let mut kept: Vec<f64> = Vec::new();
        loop {
            let flipped = flipped(segs, closed, &anchors, &solved);
            let Some(&i) = flipped.iter().find(|&&i| !kept.contains(&anchors[i].s)) else {
                break;
            };
            let m = anchors.len();
            let s0 = anchors[i].s;
            let prev = if i > 0 {
                anchors[i - 1].s
            } else {
                anchors[m - 1].s - n
            };
            let next = anchors.get(i + 1).map_or(anchors[0].s + n, |c| c.s);
            let d = 0.5 * (s0 - prev).min(next - s0);
            let mut without = anchors.clone();
            without.remove(i);
            let refined = |s: f64| Cand {
                s: wrap(s),
                kind: AnchorKind::Refined,
            };
            // Moves first (they fix most), then without it, then two instead.
            let tries = [
                vec![refined(s0 - d)],
                vec![refined(s0 + d)],
                vec![],
                vec![refined(s0 - d), refined(s0 + d)],
            ];
            let mut fixed = false;
            for extra in tries {
                let mut trial = without.clone();
                trial.extend(extra);
                trial.sort_by(|a, b| a.s.total_cmp(&b.s));
                if closed && trial.len() < 3 {
                    continue;
                }
                let Ok(next) = self.solve(segs, closed, &trial) else {
                    continue;
                };
                if within(original, &next, k, self.options.tolerance)
                    && flipped_count(segs, closed, &trial, &next) < flipped.len()
                {
                    anchors = trial;
                    solved = next;
                    fixed = true;
                    break;
                }
            }
            if !fixed {
                kept.push(s0);
            }
        }
        (anchors, solved)
    }

    /// The simplification pass ([`draft`](super::draft), step 5): each anchor that is not a
    /// corner, in order along the piece, is dropped if the piece solved without it stays
    /// within the tolerance (two-sided, as reported).
    pub(super) fn simplify(
        &mut self,
        segs: &[PathSeg],
        closed: bool,
        original: &Target<'_>,
        k: usize,
        (mut anchors, mut solved): (Vec<Cand>, Solved),
    ) -> (Vec<Cand>, Solved) {
        let mut j = 0;
        while j < anchors.len() {
            if closed && anchors.len() <= 3 {
                break;
            }
            if anchors[j].kind == AnchorKind::Corner {
                j += 1;
                continue;
            }
            let mut fewer = anchors.clone();
            fewer.remove(j);
            let fair = |next: &Solved, fewer: &[Cand]| {
                !self.options.fair
                    || flipped_count(segs, closed, fewer, next)
                        <= flipped_count(segs, closed, &anchors, &solved)
            };
            match self.solve(segs, closed, &fewer) {
                Ok(next)
                    if within(original, &next, k, self.options.tolerance)
                        && fair(&next, &fewer) =>
                {
                    anchors = fewer;
                    solved = next;
                }
                _ => j += 1,
            }
        }
        (anchors, solved)
    }
}
