//! A piece solved through its anchors, and the anchors and path of a solved curve.

use kurbo::{BezPath, PathSeg, Point};

use super::{abs_curvature_at, eval_at, Anchor, AnchorKind, Cand, DraftShape, Drafter, Solved};
use crate::fit::{FitMethod, FitOptions, FitTolerance};
use crate::{Error, Scheme, Shape, Spline};

/// The iteration budget of a solve started from a seed ([`Drafter::seed`]).
const SEEDED_ITERATIONS: usize = 400;

impl Drafter<'_> {
    /// Solves a piece through the anchors with the options' scheme and shape; returns the
    /// spline, its points and the original's |κ| at each.
    pub(super) fn solve(
        &mut self,
        segs: &[PathSeg],
        closed: bool,
        anchors: &[Cand],
    ) -> Result<Solved, Error> {
        let points: Vec<Point> = anchors.iter().map(|c| eval_at(segs, c.s)).collect();
        let targets: Vec<f64> = anchors
            .iter()
            .map(|c| abs_curvature_at(segs, c.s, closed))
            .collect();
        let scheme = self.options.scheme;
        let interior = closed || points.len() > 2;
        // The solver's unknowns at the spline returned: the auto shape's last re-solve may
        // have failed, and its answer is then an earlier one.
        let (spline, state) = match (&self.options.shape, scheme) {
            (DraftShape::Auto, s) if interior && s != Scheme::Kappa => {
                self.auto_shape(&points, closed, &targets)?
            }
            (shape, s) => {
                let shape = match shape {
                    DraftShape::Global(a) if s != Scheme::Kappa => Shape::Global(*a),
                    _ => Shape::Neutral,
                };
                let spline = self.solve_points(&points, closed, &shape)?;
                (spline, self.solver.state())
            }
        };
        let path = if !closed && points.len() == 2 {
            // A straight piece: one line, whatever the scheme.
            let mut line = BezPath::new();
            line.move_to(points[0]);
            line.line_to(points[1]);
            line
        } else {
            spline_path(&spline, Some(self.options.tolerance / 20.0))
        };
        Ok(Solved {
            spline,
            points,
            targets,
            path,
            tangents: self.tangents.clone(),
            state,
        })
    }

    /// A solve through `points` with the options' scheme, holding [`Drafter::tangents`]
    /// where there are any.
    pub(super) fn solve_points(
        &mut self,
        points: &[Point],
        closed: bool,
        shape: &Shape,
    ) -> Result<Spline, Error> {
        let scheme = self.options.scheme;
        let seed = self.seed.take();
        let cap = if seed.is_some() {
            SEEDED_ITERATIONS
        } else {
            usize::MAX
        };
        self.with_iteration_cap(cap, |d| match (&seed, d.tangents.is_empty()) {
            (None, true) => d.solver.solve(points, closed, scheme, shape),
            (None, false) => {
                d.solver
                    .solve_with_tangents(points, closed, scheme, shape, &d.tangents)
            }
            (Some(seed), true) => d.solver.solve_from(points, closed, scheme, shape, seed),
            (Some(seed), false) => {
                d.solver
                    .solve_with_tangents_from(points, closed, scheme, shape, &d.tangents, seed)
            }
        })
    }

    /// Runs `f` with the solver's iteration budget lowered to `cap` (if it is higher), then
    /// gives the solver its options back.
    pub(super) fn with_iteration_cap<R>(
        &mut self,
        cap: usize,
        f: impl FnOnce(&mut Self) -> R,
    ) -> R {
        let options = self.solver.options();
        self.solver.set_options(crate::SolveOptions {
            max_iterations: options.max_iterations.min(cap),
            ..options
        });
        let r = f(self);
        self.solver.set_options(options);
        r
    }
}

/// The path of a solved piece: exact for the polynomial schemes, Hermite-fitted cubics
/// within `tolerance` (default: 1e-4 of the size) for εκ-trig.
pub(super) fn spline_path(spline: &Spline, tolerance: Option<f64>) -> BezPath {
    if spline.scheme().is_polynomial() {
        return spline.to_bezpath();
    }
    let options = FitOptions {
        tolerance: tolerance.map_or(FitTolerance::Relative(1e-4), FitTolerance::Absolute),
        method: FitMethod::Hermite,
        check_samples: 0,
    };
    spline.fit(&options).map(|f| f.path).unwrap_or_default()
}

/// Anchors of a solved curve through `points`: the shape of each point's segment.
pub(super) fn anchors_of(
    spline: &Spline,
    points: &[Point],
    kind: AnchorKind,
    targets: &[f64],
) -> Vec<Anchor> {
    let off = usize::from(!spline.is_closed());
    let segs = spline.segments();
    points
        .iter()
        .enumerate()
        .map(|(i, &point)| {
            let a = i
                .checked_sub(off)
                .and_then(|j| segs.get(j))
                .filter(|_| points.len() > 2 || spline.is_closed())
                .map_or(2.0 / 3.0, |s| s.a);
            Anchor {
                point,
                kind,
                a,
                target_curvature: targets.get(i).copied().unwrap_or(0.0),
                tangent: None,
            }
        })
        .collect()
}
