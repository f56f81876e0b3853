//! The first anchors of a piece: its ends, the on-curve extrema and the curvature peaks
//! of the original, thinned to the minimum spacing ([`draft`](super::draft), step 2).

use kurbo::{ParamCurve, ParamCurveExtrema, PathSeg, Point};

use super::{eval_at, AnchorKind, Cand, Drafter};
use crate::analysis::CurvatureAnalysis;

/// A curvature peak becomes an anchor only if its |κ| is at least this many times the lowest
/// |κ| between it and a higher peak (or the piece end) on both sides.
pub const PEAK_PROMINENCE: f64 = 2.0;

/// A curvature peak becomes an anchor only if its radius of curvature is below this fraction
/// of the outline's size (gentle bends are left to the extrema and the refinement).
pub const PEAK_MAX_RADIUS: f64 = 0.5;

/// A joint tangent this close to horizontal or vertical (sine of the angle) makes the joint
/// an on-curve extremum.
const EXTREMUM_SLOPE: f64 = 0.02;

/// The spacing of extremum anchors, as a fraction of
/// [`DraftOptions::min_spacing`](super::DraftOptions::min_spacing)
/// ([`draft`](super::draft), step 1).
const EXTREMUM_SPACING: f64 = 0.25;

/// The longest chord, in minimum spacings, of a piece that gets a middle anchor
/// (`fillet_anchor`). Measured on the alphabet of EB Garamond (κ, TTF and UFO): 0.5 left
/// kinks of 4°–12° at the `h`, `p` and `M` where a gently curved piece meets lines (6 smooth
/// joins over 0.5° in the UFO); 1 left the `M` (2); 2 left the 136-unit flank at the top of
/// `h`'s stem when the UFO is drafted alone, at the full tolerance (1); 3 leaves none. Without
/// a bound the tip of `seven` gets anchors 2 units apart and a curve segment under 2 units in
/// the TTF.
const FILLET_MAX_CHORD: f64 = 3.0;

impl Drafter<'_> {
    /// Ends, extrema and curvature peaks, thinned to the minimum spacing.
    pub(super) fn initial_anchors(&self, segs: &[PathSeg], closed: bool) -> Vec<Cand> {
        let n = segs.len();
        let mut cands: Vec<Cand> = Vec::new();
        if !closed {
            cands.push(Cand {
                s: 0.0,
                kind: AnchorKind::Corner,
            });
            cands.push(Cand {
                s: n as f64,
                kind: AnchorKind::Corner,
            });
        }
        if !(n == 1 && matches!(segs[0], PathSeg::Line(_))) {
            self.extrema(segs, closed, &mut cands);
            self.peaks(segs, closed, &mut cands);
        }
        // Thin out: corners first, then extrema, then peaks.
        let rank = |k: AnchorKind| match k {
            AnchorKind::Corner => 0,
            AnchorKind::Extremum => 1,
            _ => 2,
        };
        cands.sort_by(|a, b| rank(a.kind).cmp(&rank(b.kind)).then(a.s.total_cmp(&b.s)));
        let mut kept: Vec<(Cand, Point)> = Vec::new();
        for c in cands {
            let p = eval_at(segs, c.s);
            // Extrema are where a designer puts nodes: they keep a closer spacing.
            let spacing = if c.kind == AnchorKind::Extremum {
                EXTREMUM_SPACING * self.options.min_spacing
            } else {
                self.options.min_spacing
            };
            let far = kept
                .iter()
                .all(|(_, q)| (p - *q).hypot() >= spacing.max(f64::MIN_POSITIVE));
            if c.kind == AnchorKind::Corner || far {
                kept.push((c, p));
            }
        }
        let mut out: Vec<Cand> = kept.into_iter().map(|(c, _)| c).collect();
        out.sort_by(|a, b| a.s.total_cmp(&b.s));
        if !closed && out.len() == 2 {
            out.extend(self.fillet_anchor(segs));
            out.sort_by(|a, b| a.s.total_cmp(&b.s));
        }
        if closed && out.len() < 3 {
            // A closed curve needs three points. Without any: three evenly spread; else the
            // largest gap between them gets points at its thirds (not in its middle, which
            // is often the curvature minimum between two peaks).
            let n = n as f64;
            let (a, gap) = if out.is_empty() {
                (0.0, n)
            } else {
                (0..out.len())
                    .map(|i| {
                        let next = out.get(i + 1).map_or(out[0].s + n, |c| c.s);
                        (out[i].s, next - out[i].s)
                    })
                    .max_by(|x, y| x.1.total_cmp(&y.1))
                    .unwrap_or((0.0, n))
            };
            let fill: &[f64] = if out.is_empty() {
                &[0.0, 1.0 / 3.0, 2.0 / 3.0]
            } else {
                &[1.0 / 3.0, 2.0 / 3.0]
            };
            for f in fill {
                out.push(Cand {
                    s: (a + f * gap) % n,
                    kind: AnchorKind::Refined,
                });
            }
            out.sort_by(|a, b| a.s.total_cmp(&b.s));
        }
        out
    }

    /// The middle anchor of a short curved piece that would otherwise keep only its two
    /// ends, and so be drafted as a straight line: a fillet, where a crossbar meets a stem,
    /// or a gently curved flank between two lines (the shoulder of EB Garamond's `h`, the
    /// right foot of its `M`). A κ-curve through two points is their chord, and such a piece
    /// is often within the tolerance of its chord, so the refinement would leave it straight,
    /// with a corner at each end where the original's joins are smooth (EB Garamond's `H` and
    /// `4`: corners of 24°–84°; `h` and `M`: 12° and 4° where a line meets a line). With the
    /// anchor halfway along it the draft is the quadratic through the ends that peaks there,
    /// whose end tangents are near the original's (on a quarter circle, 5.4° off: the
    /// parabola through the ends with its vertex at the middle has its control point at
    /// `(√2 − ½) r` along the diagonal), and the node outline turns them onto the lines.
    /// `None` for a piece with a chord over [`FILLET_MAX_CHORD`] minimum spacings or under
    /// twice the tolerance (the two curve segments would be shorter than a font checker's 2
    /// units), or that keeps within a tenth of the tolerance of its chord.
    fn fillet_anchor(&self, segs: &[PathSeg]) -> Option<Cand> {
        const SAMPLES: usize = 64;
        let n = segs.len() as f64;
        let (a, b) = (segs.first()?.start(), segs.last()?.end());
        let tol = self.options.tolerance;
        let chord = (b - a).hypot();
        if !(chord >= 2.0 * tol && chord <= FILLET_MAX_CHORD * self.options.min_spacing) {
            return None;
        }
        let s_at = |k: usize| n * k as f64 / SAMPLES as f64;
        let pts: Vec<Point> = (0..=SAMPLES).map(|k| eval_at(segs, s_at(k))).collect();
        let bulge = pts
            .iter()
            .map(|p| (*p - a).cross(b - a).abs() / chord)
            .fold(0.0, f64::max);
        if bulge < 0.1 * tol {
            return None;
        }
        let mut length = vec![0.0f64; SAMPLES + 1];
        for k in 1..=SAMPLES {
            length[k] = length[k - 1] + (pts[k] - pts[k - 1]).hypot();
        }
        let k = (1..SAMPLES).find(|&k| length[k] >= 0.5 * length[SAMPLES])?;
        Some(Cand {
            s: s_at(k),
            kind: AnchorKind::Peak,
        })
    }

    /// The chord of an open piece short enough to be a fillet: at most half the
    /// [`DraftOptions::min_spacing`](super::DraftOptions::min_spacing), end to end.
    pub(super) fn fillet_chord(&self, segs: &[PathSeg]) -> Option<f64> {
        let chord = (segs.last()?.end() - segs.first()?.start()).hypot();
        (chord <= 0.5 * self.options.min_spacing).then_some(chord)
    }

    fn extrema(&self, segs: &[PathSeg], closed: bool, cands: &mut Vec<Cand>) {
        for (i, seg) in segs.iter().enumerate() {
            if matches!(seg, PathSeg::Line(_)) {
                continue;
            }
            for t in seg.extrema() {
                cands.push(Cand {
                    s: i as f64 + t,
                    kind: AnchorKind::Extremum,
                });
            }
            if i > 0 || closed {
                let d = seg.eval(1e-6) - seg.eval(0.0);
                let len = d.hypot();
                if len > 0.0
                    && (d.x.abs() < EXTREMUM_SLOPE * len || d.y.abs() < EXTREMUM_SLOPE * len)
                {
                    cands.push(Cand {
                        s: i as f64,
                        kind: AnchorKind::Extremum,
                    });
                }
            }
        }
    }

    fn peaks(&self, segs: &[PathSeg], closed: bool, cands: &mut Vec<Cand>) {
        let n = segs.len();
        let maxima: Vec<(f64, f64)> = segs
            .iter()
            .map(|seg| {
                let m = seg.max_curvature();
                let t = m.params.first().copied().unwrap_or(0.5);
                if m.value.is_finite() {
                    (m.value, t)
                } else {
                    (0.0, t)
                }
            })
            .collect();
        let value = |j: isize| -> Option<f64> {
            if closed {
                Some(maxima[j.rem_euclid(n as isize) as usize].0)
            } else if j >= 0 && (j as usize) < n {
                Some(maxima[j as usize].0)
            } else {
                None
            }
        };
        for (i, &(v, t)) in maxima.iter().enumerate() {
            if v <= 0.0 || v * PEAK_MAX_RADIUS * self.size < 1.0 {
                continue;
            }
            // Lowest value on each side before a higher peak (of equal peaks the later wins).
            let mut lows = [f64::INFINITY; 2];
            let mut tie = false;
            for (side, step) in [(0usize, -1isize), (1, 1)] {
                let mut j = i as isize + step;
                let mut steps = 1;
                while let Some(w) = value(j) {
                    if w > v || (w == v && step < 0) || steps >= n {
                        tie |= w == v && step < 0 && steps < n;
                        break;
                    }
                    lows[side] = lows[side].min(w);
                    j += step;
                    steps += 1;
                }
            }
            if tie {
                continue;
            }
            let low = lows
                .iter()
                .copied()
                .filter(|l| l.is_finite())
                .fold(f64::NEG_INFINITY, f64::max);
            if low.is_finite() && v >= PEAK_PROMINENCE * low {
                cands.push(Cand {
                    s: i as f64 + t,
                    kind: AnchorKind::Peak,
                });
            }
        }
    }
}
