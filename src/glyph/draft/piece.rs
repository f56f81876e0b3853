//! One piece drafted: anchors, refinement and the optional passes, cut in parts where it
//! will not solve or strays ([`draft`](super::draft), steps 2 to 7).

use kurbo::{BezPath, ParamCurve, PathSeg};

use super::distance::{two_way, within, Target};
use super::solve::anchors_of;
use super::{Anchor, AnchorKind, Cand, Drafter, Piece, Solved};
use crate::{Error, Spline};

/// How many times a piece that will not solve, or strays, is cut in two ([`draft`](super::draft),
/// step 7).
pub const SPLIT_DEPTH: usize = 3;

/// A piece that keeps the original's segments ([`Piece::fallback`]); `None` for a piece
/// of no length. The chord of a closed piece runs to the middle of its first segment.
fn fallback_piece(segs: &[PathSeg], closed: bool) -> Option<Piece> {
    let (start, end) = (segs.first()?.start(), segs.last()?.end());
    let chord = Spline::kappa(&[start, end], false)
        .or_else(|_| Spline::kappa(&[start, segs[0].eval(0.5)], false))
        .ok()?;
    let mut path = BezPath::from_path_segments(segs.iter().copied());
    if closed {
        path.close_path();
    }
    let anchor = |point| Anchor {
        point,
        kind: AnchorKind::Corner,
        a: 2.0 / 3.0,
        target_curvature: 0.0,
        tangent: None,
    };
    Some(Piece {
        anchors: vec![anchor(start), anchor(end)],
        closed,
        spline: chord,
        path,
        hausdorff: Some(0.0),
        within_tolerance: true,
        fallback: true,
        state: None,
    })
}

/// The drafted piece from its last solve and its two-sided Hausdorff distance.
fn finish(anchors: &[Cand], solved: Solved, closed: bool, hausdorff: f64, tolerance: f64) -> Piece {
    let tangents = solved.tangents.clone();
    let mut out = anchors_of(
        &solved.spline,
        &solved.points,
        AnchorKind::Refined,
        &solved.targets,
    );
    for (i, (a, c)) in out.iter_mut().zip(anchors).enumerate() {
        a.kind = c.kind;
        a.tangent = tangents.get(i).copied().flatten();
    }
    Piece {
        anchors: out,
        closed,
        spline: solved.spline,
        path: solved.path,
        hausdorff: Some(hausdorff),
        within_tolerance: hausdorff <= tolerance,
        fallback: false,
        state: solved.state,
    }
}

impl Drafter<'_> {
    /// [`Drafter::piece`], or where it fails the piece cut in two and each part drafted
    /// the same way, `depth` cuts deep so far; a part that still fails keeps the original
    /// ([`draft`](super::draft), step 7). Where it solves but strays beyond the tolerance,
    /// the parts are drafted too and replace it only if none is a fallback and their worst
    /// Hausdorff distance is below the whole's.
    pub(super) fn piece_or_parts(
        &mut self,
        segs: &[PathSeg],
        closed: bool,
        depth: usize,
    ) -> Vec<Piece> {
        let whole = self.piece(segs, closed).ok();
        if whole.as_ref().is_some_and(|p| p.within_tolerance) {
            return whole.into_iter().collect();
        }
        if depth < SPLIT_DEPTH && segs.len() >= 2 {
            let h = segs.len() / 2;
            let mut out = self.piece_or_parts(&segs[..h], false, depth + 1);
            out.extend(self.piece_or_parts(&segs[h..], false, depth + 1));
            let Some(whole) = whole else {
                return out;
            };
            // A piece that solves but strays: its parts replace it where they are drafted
            // (none keeps the original) and come nearer the original.
            let worst = out.iter().map(|p| p.hausdorff.unwrap_or(f64::INFINITY));
            let worst = worst.fold(0.0, f64::max);
            let better = worst < whole.hausdorff.unwrap_or(f64::INFINITY);
            return if better && !out.iter().any(|p| p.fallback) {
                out
            } else {
                vec![whole]
            };
        }
        if let Some(whole) = whole {
            return vec![whole];
        }
        // Only a piece of no length has no fallback: it has nothing to draw either.
        fallback_piece(segs, closed).into_iter().collect()
    }

    /// Drafts one piece ([`draft`](super::draft), steps 2 and 3).
    fn piece(&mut self, segs: &[PathSeg], closed: bool) -> Result<Piece, Error> {
        let opts = self.options;
        let k = opts.samples.clamp(2, 256);
        let original = Target::new(segs);
        let mut anchors = self.initial_anchors(segs, closed);
        let mut solved = self.solve(segs, closed, &anchors)?;
        let mut added = 0;
        loop {
            let drafted: Vec<PathSeg> = solved.path.segments().collect();
            let spans = self.worst_per_span(segs, &Target::new(&drafted), &anchors, closed, k);
            let budget = opts.max_refinements.saturating_sub(added);
            if spans.iter().all(Option::is_none) || budget == 0 {
                break;
            }
            // None: no anchor set tried could be solved; the piece stays as it is, and
            // `within_tolerance` tells.
            let Some((more, next, n)) = self.refine(
                segs,
                closed,
                &anchors,
                &spans,
                budget,
                solved.state.as_ref(),
            ) else {
                break;
            };
            anchors = more;
            solved = next;
            added += n;
        }
        if within(&original, &solved, k, opts.tolerance) {
            if opts.fair {
                (anchors, solved) = self.fair(segs, closed, &original, k, (anchors, solved));
            }
            if opts.simplify {
                (anchors, solved) = self.simplify(segs, closed, &original, k, (anchors, solved));
            }
        }
        if opts.extremum_tangents {
            let held = self.with_extremum_tangents(segs, closed, &anchors, &original, k, &solved);
            if let Some((more, held)) = held {
                anchors = more;
                solved = held;
            }
        }
        let hausdorff = two_way(&original, &solved, k);
        Ok(finish(&anchors, solved, closed, hausdorff, opts.tolerance))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::glyph::draft::tests::ellipse;
    use crate::glyph::DraftOptions;
    use crate::Solver;

    /// The pieces [`Drafter::piece_or_parts`] makes of `segs` (closed) with a solver capped
    /// at `max_iterations`, after checking that they join end to end around the contour and
    /// that the fallback ones are the original's segments.
    fn parts(segs: &[PathSeg], max_iterations: usize) -> Vec<Piece> {
        let options = DraftOptions::default();
        let mut drafter = Drafter {
            options: &options,
            size: 2000.0,
            solver: Solver::with_options(crate::SolveOptions {
                max_iterations,
                ..crate::SolveOptions::default()
            }),
            tangents: Vec::new(),
            seed: None,
            turn_limit: f64::INFINITY,
        };
        let pieces = drafter.piece_or_parts(segs, true, 0);
        let mut at = segs[0].start();
        for p in &pieces {
            let ps: Vec<PathSeg> = p.path.segments().collect();
            assert!(
                (ps[0].start() - at).hypot() < 1e-9,
                "{at:?} {:?}",
                ps[0].start()
            );
            at = ps.last().unwrap().end();
            if p.fallback {
                assert!(ps.iter().all(|s| segs.contains(s)));
                assert_eq!(p.hausdorff, Some(0.0));
            }
        }
        assert!((at - segs[0].start()).hypot() < 1e-9);
        pieces
    }

    #[test]
    fn a_piece_that_will_not_solve_is_split_then_kept_as_the_original() {
        let outline = kurbo::Affine::skew(0.3, 0.1) * ellipse();
        let segs: Vec<PathSeg> = outline.segments().collect();
        // One iteration does not solve the whole contour: its halves (and their halves)
        // are drafted instead of the glyph being aborted.
        let split = parts(&segs, 1);
        assert!(split.len() > 1 && split.iter().all(|p| !p.fallback && !p.closed));
        // No iteration at all: the parts that need one keep the original, flagged (parts
        // whose anchors are just their ends are straight chords, drafted without one).
        let kept = parts(&segs, 0);
        assert!(kept.len() >= segs.len() / 2);
        let fallback = kept.iter().filter(|p| p.fallback).count();
        assert!(fallback >= 1, "{} parts, {fallback} kept", kept.len());
    }
}
