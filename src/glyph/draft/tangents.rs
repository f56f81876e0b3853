//! Extremum tangents: the piece solved again holding the original's axis at its extremum
//! anchors ([`DraftOptions::extremum_tangents`](super::DraftOptions::extremum_tangents)).

use kurbo::{ParamCurve, PathSeg, Vec2};

use super::distance::{within, Target};
use super::{locate, AnchorKind, Cand, Drafter, Solved};

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

/// The iteration budget of a solve holding tangents in [`Drafter::with_extremum_tangents`]
/// (measured on the alphabets of DejaVu Sans and EB Garamond: the same tangents held as
/// with the default 2 000, and the drafting as fast as without tangents instead of 3
/// times slower).
const TANGENT_ITERATIONS: usize = 300;

/// How near an axis (radians) the original's tangent at a piece's end is taken to be on it.
const AXIS_SNAP: f64 = 1.0 * core::f64::consts::PI / 180.0;

impl Drafter<'_> {
    /// The piece solved again with the original's axis held at extremum anchors inside the
    /// piece and, on an open piece, the original's own direction at both ends
    /// ([`DraftOptions::extremum_tangents`](super::DraftOptions::extremum_tangents)): all
    /// of them if that converges and stays within the tolerance, otherwise as many as can
    /// be added one at a time, in order along the piece, with the piece still converging
    /// and within the tolerance (a tangent far from the free curve's may have no solution:
    /// the point would leave its segment). `None` where none can be held.
    pub(super) fn with_extremum_tangents(
        &mut self,
        segs: &[PathSeg],
        closed: bool,
        anchors: &[Cand],
        original: &Target<'_>,
        k: usize,
    ) -> Option<Solved> {
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
        let mut held = self.solve_holding(segs, closed, anchors, original, k, &wanted);
        if held.is_some() || count == 1 {
            return held;
        }
        let mut kept = vec![None; m];
        for (i, tan) in wanted.iter().enumerate() {
            if tan.is_none() {
                continue;
            }
            kept[i] = *tan;
            match self.solve_holding(segs, closed, anchors, original, k, &kept) {
                Some(next) => held = Some(next),
                None => kept[i] = None,
            }
        }
        held
    }

    /// The piece solved with `tangents` held, if it converges and stays within the
    /// tolerance.
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
        let options = self.solver.options();
        self.solver.set_options(crate::SolveOptions {
            max_iterations: options.max_iterations.min(TANGENT_ITERATIONS),
            ..options
        });
        let solved = self.solve(segs, closed, anchors);
        self.solver.set_options(options);
        self.tangents.clear();
        solved
            .ok()
            .filter(|s| within(original, s, k, self.options.tolerance))
    }
}
