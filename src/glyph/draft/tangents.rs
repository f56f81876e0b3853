//! Extremum tangents: the piece solved again holding the original's axis at its extremum
//! anchors ([`DraftOptions::extremum_tangents`](super::DraftOptions::extremum_tangents)).

use kurbo::{ParamCurve, PathSeg, Vec2};

use super::distance::{within, Target};
use super::refine::seeded;
use super::{locate, AnchorKind, Cand, Drafter, Solved};
use crate::glyph::nodes::turn_angle;

/// The original's unit tangent at `s` (a position along `segs`, as
/// [`eval_at`](super::eval_at) takes it), in its direction of travel: the direction of a
/// chord 1e-6 of a segment long (`None` where that has no length).
fn direction_at(segs: &[PathSeg], s: f64) -> Option<Vec2> {
    let (i, t) = locate(segs, s);
    let (a, b) = if t < 1.0 {
        (segs[i].eval(t), segs[i].eval((t + 1e-6).min(1.0)))
    } else {
        (segs[i].eval(t - 1e-6), segs[i].eval(t))
    };
    let d = b - a;
    let len = d.hypot();
    (len > 0.0 && len.is_finite()).then(|| d / len)
}

/// The axis the original runs along at `s`, in its direction: at an extremum one of its
/// derivative's components is zero, or nearly.
fn axis_tangent(segs: &[PathSeg], s: f64) -> Option<Vec2> {
    let d = direction_at(segs, s)?;
    Some(if d.x.abs() >= d.y.abs() {
        Vec2::new(d.x.signum(), 0.0)
    } else {
        Vec2::new(0.0, d.y.signum())
    })
}

/// The original's unit tangent at `s`, turned onto an axis if within [`AXIS_SNAP`] of it.
fn original_tangent(segs: &[PathSeg], s: f64) -> Option<Vec2> {
    let d = direction_at(segs, s)?;
    let axis = axis_tangent(segs, s)?;
    Some(if d.dot(axis) >= AXIS_SNAP.cos() {
        axis
    } else {
        d
    })
}

/// The iteration budget of a solve holding tangents in [`Drafter::with_extremum_tangents`].
/// Most of those that fail are out of reach and run to the cap: on the 190 glyphs of the EB
/// Garamond subset, with a cap of 300, 3 132 failed (two thirds of the solver's time) and the
/// 3 079 that held took 24 iterations on average, 90 % of them 60 or fewer, the slowest 294.
/// At 150 the alphabets of DejaVu Sans and EB Garamond keep the same extremum nodes, all
/// glyphs within the tolerance, and the subset drafts in 30 % less time; at 100 one
/// Garamond glyph (`three`) strays beyond it, as a held solve had brought one of its pieces
/// back within. (300 was chosen against the default 2 000: the same tangents held, and the
/// drafting as fast as without tangents instead of 3 times slower.)
const TANGENT_ITERATIONS: usize = 150;

/// Where the flanking anchors of a tangent that cannot be held go ([`flanked`]): this
/// fraction of the way from its anchor to each neighbour, in position along the piece.
/// Measured on the alphabets of EB Garamond and DejaVu Sans (TrueType output, κ): a third
/// or a half of the way held the same tangents within 1 %, a fifth a few fewer.
const FLANK: f64 = 1.0 / 3.0;

/// `anchors` with an anchor [`FLANK`] of the way from anchor `j` to each neighbour (on an
/// open piece, only to the neighbours it has), kind [`AnchorKind::Refined`], and for each
/// anchor of the new list the index it had before (`None` for the new ones). `None` if
/// there is no neighbour. `n` is the number of segments of the piece: the positions of a
/// closed one wrap at `n`, so a flank past the last anchor's position goes to the end of
/// the list and one before the first anchor's to its start.
fn flanked(
    n: usize,
    closed: bool,
    anchors: &[Cand],
    j: usize,
) -> Option<(Vec<Cand>, Vec<Option<usize>>)> {
    let m = anchors.len();
    let n = n as f64;
    let s = anchors[j].s;
    let prev = match j {
        0 if closed => Some(anchors[m - 1].s - n),
        0 => None,
        _ => Some(anchors[j - 1].s),
    };
    let next = match anchors.get(j + 1) {
        Some(c) => Some(c.s),
        None if closed => Some(anchors[0].s + n),
        None => None,
    };
    if prev.is_none() && next.is_none() {
        return None;
    }
    let flank = |b: f64| Cand {
        s: s + FLANK * (b - s),
        kind: AnchorKind::Refined,
    };
    let (before, after) = (prev.map(flank), next.map(flank));
    // The new list, each entry with its old index (`None` at a flank).
    let mut out: Vec<(Cand, Option<usize>)> = Vec::with_capacity(m + 2);
    for (i, c) in anchors.iter().enumerate() {
        if i == j {
            out.extend(before.filter(|f| f.s >= 0.0).map(|f| (f, None)));
            out.push((*c, Some(i)));
            out.extend(after.filter(|f| f.s < n).map(|f| (f, None)));
        } else {
            out.push((*c, Some(i)));
        }
    }
    // Flanks of a closed piece that wrap round go to the other end of the list.
    if let Some(f) = after.filter(|f| f.s >= n) {
        out.insert(0, (Cand { s: f.s - n, ..f }, None));
    }
    if let Some(f) = before.filter(|f| f.s < 0.0) {
        out.push((Cand { s: f.s + n, ..f }, None));
    }
    Some(out.into_iter().unzip())
}

/// How much more a curve holding tangents may turn than the original piece or the free
/// curve, whichever turns more (radians, [`turning`]). A held tangent the free curve cannot
/// reach smoothly can be met by a small loop or a back-and-forth at its point, within the
/// tolerance of the original: EB Garamond's `₂` held its base's horizontal at (151, -166) by
/// running back 6 units and on again, 344° more turning than the original and a 180° cusp
/// in the written outline. Going back and on again turns by at least 360° (180° each way),
/// a wiggle by a few degrees. On the alphabets of EB Garamond and DejaVu Sans no held solve
/// kept before is dropped by it; on the whole of EB Garamond, 5 glyphs change, each for the
/// better (one more extremum node, 7 fewer short segments, the cusp gone).
const LOOP_TURN: f64 = core::f64::consts::PI;

/// The total absolute turning of a path (radians): the sum of the angles between successive
/// legs of its control polygons (lines, quadratics and cubics in order; legs of no length
/// skipped), round the closing joint too where `closed`. For a quadratic that is its own
/// turning exactly; for a cubic an upper bound.
fn turning(segs: impl Iterator<Item = PathSeg>, closed: bool) -> f64 {
    let mut legs: Vec<Vec2> = Vec::new();
    for seg in segs {
        let pts: &[kurbo::Point] = match &seg {
            PathSeg::Line(l) => &[l.p0, l.p1],
            PathSeg::Quad(q) => &[q.p0, q.p1, q.p2],
            PathSeg::Cubic(c) => &[c.p0, c.p1, c.p2, c.p3],
        };
        legs.extend(
            pts.windows(2)
                .map(|w| w[1] - w[0])
                .filter(|d| d.hypot2() > 0.0),
        );
    }
    let mut total: f64 = legs.windows(2).filter_map(|w| turn_angle(w[0], w[1])).sum();
    if let (true, Some(&first), Some(&last)) = (closed, legs.first(), legs.last()) {
        total += turn_angle(last, first).unwrap_or(0.0);
    }
    total
}

/// How near an axis (radians) the original's tangent at a piece's end is taken to be on it.
const AXIS_SNAP: f64 = 1.0 * core::f64::consts::PI / 180.0;

impl Drafter<'_> {
    /// The piece solved again with the original's axis held at extremum anchors inside the
    /// piece and, on an open piece, the original's own direction at both ends
    /// ([`DraftOptions::extremum_tangents`](super::DraftOptions::extremum_tangents)), with
    /// its anchors: all of them if that converges and stays within the tolerance, otherwise
    /// as many as can be added one at a time, in order along the piece, with the piece still
    /// converging and within the tolerance. A tangent far from the free curve's may have no
    /// solution (the point would leave its segment), and an open piece's end and the point
    /// next to it cannot both hold one (one segment); such a tangent is tried once more
    /// with two anchors flanking its point ([`flanked`]), kept if that holds it. On the
    /// alphabets of EB Garamond and DejaVu Sans (κ) the flanks took the source's extremum
    /// nodes kept from 736 to 800 of 1 129 and from 279 to 283 of 288, at 7 % more anchors.
    /// Each solve starts from the last one that held (the free curve `free` at first), with
    /// flanking anchors seeded in ([`seeded`]). A solve is not kept where it turns by more
    /// than [`LOOP_TURN`] beyond the original and the free curve. `None` where none can be
    /// held.
    pub(super) fn with_extremum_tangents(
        &mut self,
        segs: &[PathSeg],
        closed: bool,
        anchors: &[Cand],
        original: &Target<'_>,
        k: usize,
        free: &Solved,
    ) -> Option<(Vec<Cand>, Solved)> {
        let m = anchors.len();
        if !closed && m < 3 {
            return None;
        }
        let wanted: Vec<Option<Vec2>> = anchors
            .iter()
            .enumerate()
            .map(|(i, c)| {
                if !closed && (i == 0 || i + 1 == m) {
                    // The original's own direction leaving (entering) the piece.
                    original_tangent(segs, c.s)
                } else if c.kind == AnchorKind::Extremum {
                    axis_tangent(segs, c.s)
                } else {
                    None
                }
            })
            .collect();
        let count = wanted.iter().flatten().count();
        if count == 0 {
            return None;
        }
        let free_turn = turning(free.path.segments(), closed);
        self.turn_limit = turning(segs.iter().copied(), closed).max(free_turn) + LOOP_TURN;
        let free = free.state.as_ref();
        self.seed = free.cloned();
        let all = self.solve_holding(segs, closed, anchors, original, k, &wanted);
        if let Some(all) = all {
            return Some((anchors.to_vec(), all));
        }
        // No flanks on a small open piece (a fillet, see `fillet_anchor`): they would cut it
        // into curve segments of a unit or two; the node outline turns its ends instead.
        let small = !closed && self.fillet_chord(segs).is_some();
        let mut cur = anchors.to_vec();
        let mut want = wanted;
        let mut kept = vec![None; m];
        let mut held: Option<Solved> = None;
        let mut j = 0;
        while j < cur.len() {
            let Some(tan) = want[j] else {
                j += 1;
                continue;
            };
            kept[j] = Some(tan);
            let last = held.as_ref().map_or(free, |h| h.state.as_ref());
            self.seed = last.cloned();
            if let Some(next) = self.solve_holding(segs, closed, &cur, original, k, &kept) {
                held = Some(next);
                j += 1;
                continue;
            }
            kept[j] = None;
            // Out of reach through these anchors: again with two more flanking it, which
            // bring the free curve's direction there nearer the original's.
            let flanks = flanked(segs.len(), closed, &cur, j).filter(|_| !small);
            if let Some((more, slots)) = flanks {
                let pick = |v: &[Option<Vec2>]| -> Vec<Option<Vec2>> {
                    slots.iter().map(|o| o.and_then(|i| v[i])).collect()
                };
                let mut more_kept = pick(&kept);
                let at = slots.iter().position(|o| *o == Some(j)).unwrap_or(j);
                more_kept[at] = Some(tan);
                self.seed = last.map(|st| seeded(st, segs, closed, &cur, &more));
                let next = self.solve_holding(segs, closed, &more, original, k, &more_kept);
                if let Some(next) = next {
                    held = Some(next);
                    want = pick(&want);
                    cur = more;
                    kept = more_kept;
                    j = at;
                }
            }
            j += 1;
        }
        held.map(|s| (cur, s))
    }

    /// The piece solved with `tangents` held, if it converges and stays within the
    /// tolerance; the solve starts from [`Drafter::seed`] where that is set.
    fn solve_holding(
        &mut self,
        segs: &[PathSeg],
        closed: bool,
        anchors: &[Cand],
        original: &Target<'_>,
        k: usize,
        tangents: &[Option<Vec2>],
    ) -> Option<Solved> {
        self.tangents = tangents.to_vec();
        // A capped budget: a set of tangents out of reach fails anyway, and the uncapped
        // cascade would spend the whole default budget finding that out.
        let solved =
            self.with_iteration_cap(TANGENT_ITERATIONS, |d| d.solve(segs, closed, anchors));
        self.tangents.clear();
        solved.ok().filter(|s| {
            turning(s.path.segments(), closed) <= self.turn_limit
                && within(original, s, k, self.options.tolerance)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f64::consts::FRAC_PI_2;

    fn cands(s: &[f64]) -> Vec<Cand> {
        s.iter()
            .map(|&s| Cand {
                s,
                kind: AnchorKind::Extremum,
            })
            .collect()
    }

    fn positions(c: &[Cand]) -> Vec<f64> {
        c.iter().map(|c| c.s).collect()
    }

    #[test]
    fn turning_sums_the_control_polygons_angles() {
        use kurbo::{Line, Point, QuadBez};
        let quad = |a: (f64, f64), b: (f64, f64), c: (f64, f64)| {
            PathSeg::Quad(QuadBez::new(Point::from(a), Point::from(b), Point::from(c)))
        };
        // A quadratic turns by the angle between its legs: 90° here.
        let q = quad((0.0, 0.0), (1.0, 0.0), (1.0, 1.0));
        assert!((turning([q].into_iter(), false) - FRAC_PI_2).abs() < 1e-15);
        // A line on the same heading adds nothing; a corner adds its angle; a control point
        // on an end (a leg of no length) is skipped.
        let on = PathSeg::Line(Line::new((1.0, 1.0), (1.0, 2.0)));
        let back = quad((1.0, 2.0), (1.0, 2.0), (0.0, 2.0));
        let t = turning([q, on, back].into_iter(), false);
        assert!((t - 2.0 * FRAC_PI_2).abs() < 1e-15, "{t}");
        // Closed: round the closing joint too, from (0, 2) heading -x back to (0, 0) heading
        // +x: a square, 2π in all once the closing line is there.
        let close = PathSeg::Line(Line::new((0.0, 2.0), (0.0, 0.0)));
        let t = turning([q, on, back, close].into_iter(), true);
        assert!((t - 4.0 * FRAC_PI_2).abs() < 1e-14, "{t}");
        // Going back and on again along a line turns by 2π, however short the way back.
        let zig = [
            PathSeg::Line(Line::new((0.0, 0.0), (10.0, 0.0))),
            PathSeg::Line(Line::new((10.0, 0.0), (9.0, 0.0))),
            PathSeg::Line(Line::new((9.0, 0.0), (20.0, 0.0))),
        ];
        assert!((turning(zig.into_iter(), false) - 4.0 * FRAC_PI_2).abs() < 1e-15);
    }

    #[test]
    fn flanks_go_a_third_of_the_way_to_each_neighbour() {
        let (out, slots) = flanked(4, false, &cands(&[0.0, 1.5, 3.0, 4.0]), 1).unwrap();
        assert_eq!(positions(&out), [0.0, 1.0, 1.5, 2.0, 3.0, 4.0]);
        assert_eq!(slots, [Some(0), None, Some(1), None, Some(2), Some(3)]);
        assert_eq!(out[1].kind, AnchorKind::Refined);
        // An open piece's end has one neighbour, so one flank.
        let (out, slots) = flanked(4, false, &cands(&[0.0, 1.5, 3.0]), 0).unwrap();
        assert_eq!(positions(&out), [0.0, 0.5, 1.5, 3.0]);
        assert_eq!(slots, [Some(0), None, Some(1), Some(2)]);
        assert!(flanked(4, false, &cands(&[2.0]), 0).is_none());
    }

    #[test]
    fn flanks_of_a_closed_piece_wrap_round() {
        // The first anchor's neighbour before it is the last, one turn back (at 3 - 6).
        let (out, slots) = flanked(6, true, &cands(&[0.0, 1.5, 3.0]), 0).unwrap();
        assert_eq!(positions(&out), [0.0, 0.5, 1.5, 3.0, 5.0]);
        assert_eq!(slots, [Some(0), None, Some(1), Some(2), None]);
        // The last one's neighbour after it is the first, one turn on (at 0.9 + 6).
        let (out, slots) = flanked(6, true, &cands(&[0.9, 3.0, 5.7]), 2).unwrap();
        let s = positions(&out);
        assert!((s[0] - 0.1).abs() < 1e-12, "{s:?}");
        assert_eq!(&s[1..4], [0.9, 3.0, 5.7 - 0.9]);
        assert_eq!(s[4], 5.7);
        assert_eq!(slots, [None, Some(0), Some(1), None, Some(2)]);
    }
}
