//! Many curves solved cold in one call: the curves of a drawing, the contours of a glyph.
//!
//! Each curve is an independent system, so a batch spreads them over the threads of
//! rayon's pool (feature `parallel`): the calling thread and the pool's other threads take
//! the next unsolved curve, the largest first, until none is left. Every thread has a
//! [`SolverN`] of its own, kept by the [`BatchSolverN`] across calls, so repeated batches
//! allocate little more than their results. A curve's result does not depend on the thread
//! that solved it or on what that thread solved before: a cold solve starts from its input
//! alone, and the batch returns exactly what [`SolverN::solve`] returns for each curve.
//!
//! Small batches (fewer than [`MIN_PARALLEL_SEGMENTS`] segments in all) stay on the
//! calling thread: waking another thread can cost a few microseconds, about one small
//! curve's solve.

use core::sync::atomic::{AtomicUsize, Ordering};

use crate::error::Error;
use crate::parallel;
use crate::spline::{Coords, Scheme, Shape, SolveOptions, SolverN, Spline};

/// Batches with fewer segments than this in all are solved on the calling thread alone.
pub const MIN_PARALLEL_SEGMENTS: usize = 16;

/// One curve of a batch: its input points, whether it is closed, and its shape parameters
/// (as for [`SolverN::solve`]).
#[derive(Clone, Copy, Debug)]
pub struct BatchCurve<'a, P> {
    /// The input points.
    pub points: &'a [P],
    /// Closed (a loop through every point) or open (first and last points are the ends).
    pub closed: bool,
    /// The shape parameters.
    pub shape: &'a Shape,
}

impl<'a, P> BatchCurve<'a, P> {
    /// A curve of the batch.
    pub fn new(points: &'a [P], closed: bool, shape: &'a Shape) -> Self {
        BatchCurve {
            points,
            closed,
            shape,
        }
    }

    /// The segments its solve has (one per point of a closed curve, one per interior point
    /// of an open one): the measure the batch orders and splits the work by.
    fn segments(&self) -> usize {
        if self.closed {
            self.points.len()
        } else {
            self.points.len().saturating_sub(2)
        }
    }
}

/// Solves batches of curves cold, on the threads of rayon's pool (feature `parallel`,
/// `rayon::current_num_threads()` of them) or on the calling thread alone.
///
/// Use the aliases [`BatchSolver`] (2D) and [`BatchSolver3`] (3D).
///
/// ```
/// use kappa::{BatchCurve, BatchSolver, Scheme, Shape};
/// use kurbo::Point;
///
/// let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(Point::from);
/// let arc = [(0.0, 2.0), (1.0, 3.0), (2.0, 2.0)].map(Point::from);
/// let shape = Shape::Neutral;
/// let curves = [
///     BatchCurve::new(&square, true, &shape),
///     BatchCurve::new(&arc, false, &shape),
/// ];
/// let mut batch = BatchSolver::new();
/// let splines = batch.solve(&curves, Scheme::Kappa);
/// assert_eq!(splines.len(), 2);
/// assert_eq!(splines[0].as_ref().unwrap().segments().len(), 4);
/// assert_eq!(splines[1].as_ref().unwrap().segments().len(), 1);
/// ```
#[derive(Clone, Debug)]
pub struct BatchSolverN<P, const D: usize, const B: usize> {
    options: SolveOptions,
    /// One solver and one result list per thread; the first is the calling thread's.
    workers: Vec<Worker<P, D, B>>,
    /// The curves' indices, largest first.
    order: Vec<usize>,
}

/// What one thread of a batch keeps: its solver and the results it produced.
#[derive(Clone, Debug)]
struct Worker<P, const D: usize, const B: usize> {
    solver: SolverN<P, D, B>,
    done: Vec<(usize, Result<Spline<P>, Error>)>,
}

/// The 2D batch solver.
pub type BatchSolver = BatchSolverN<kurbo::Point, 2, 4>;
/// The 3D batch solver.
pub type BatchSolver3 = BatchSolverN<crate::Point3, 3, 5>;

impl<P, const D: usize, const B: usize> Default for BatchSolverN<P, D, B>
where
    P: Coords<D> + Send + Sync,
{
    fn default() -> Self {
        Self::new()
    }
}

impl<P, const D: usize, const B: usize> BatchSolverN<P, D, B>
where
    P: Coords<D> + Send + Sync,
{
    /// A batch solver with default options.
    pub fn new() -> Self {
        Self::with_options(SolveOptions::default())
    }

    /// A batch solver with the given options (for every curve).
    pub fn with_options(options: SolveOptions) -> Self {
        BatchSolverN {
            options,
            workers: Vec::new(),
            order: Vec::new(),
        }
    }

    /// The options.
    pub fn options(&self) -> SolveOptions {
        self.options
    }

    /// How many threads a batch of `curves` would be spread over.
    pub fn threads_for(&self, curves: &[BatchCurve<'_, P>]) -> usize {
        let segments: usize = curves.iter().map(BatchCurve::segments).sum();
        if segments < MIN_PARALLEL_SEGMENTS {
            1
        } else {
            parallel::threads().min(curves.len()).max(1)
        }
    }

    /// Solve every curve from scratch with `scheme`; the results come in the order of
    /// `curves`, each exactly what [`SolverN::solve`] returns for that curve (its errors
    /// included: a bad curve does not stop the others).
    pub fn solve(
        &mut self,
        curves: &[BatchCurve<'_, P>],
        scheme: Scheme,
    ) -> Vec<Result<Spline<P>, Error>> {
        let threads = self.threads_for(curves);
        while self.workers.len() < threads {
            self.workers.push(Worker {
                solver: SolverN::with_options(self.options),
                done: Vec::new(),
            });
        }
        // Largest first, so that the last curves taken are small and the threads finish
        // together (ties keep the input order).
        self.order.clear();
        self.order.extend(0..curves.len());
        self.order
            .sort_by_key(|&i| core::cmp::Reverse(curves[i].segments()));
        let next = AtomicUsize::new(0);
        let order = &self.order;
        parallel::each_worker(&mut self.workers[..threads], |w| {
            w.done.clear();
            loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                let Some(&i) = order.get(k) else {
                    break;
                };
                let c = &curves[i];
                let spline = w.solver.solve(c.points, c.closed, scheme, c.shape);
                w.done.push((i, spline));
            }
        });
        let mut out: Vec<Option<Result<Spline<P>, Error>>> =
            (0..curves.len()).map(|_| None).collect();
        for w in &mut self.workers[..threads] {
            for (i, r) in w.done.drain(..) {
                out[i] = Some(r);
            }
        }
        // Every index was taken by exactly one thread.
        out.into_iter().flatten().collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::Point;

    fn ring(n: usize, r: f64, cx: f64) -> Vec<Point> {
        (0..n)
            .map(|i| {
                let th = i as f64 / n as f64 * core::f64::consts::TAU;
                let rr = if i % 2 == 0 { r } else { 0.8 * r };
                Point::new(cx + rr * th.cos(), rr * th.sin())
            })
            .collect()
    }

    #[test]
    fn batch_matches_one_solve_per_curve_in_input_order() {
        let curves: Vec<(Vec<Point>, bool)> = (3..12)
            .map(|n| (ring(n, 10.0 + n as f64, 30.0 * n as f64), n % 3 != 0))
            .collect();
        let shape = Shape::Global(0.8);
        let batch: Vec<_> = curves
            .iter()
            .map(|(p, c)| BatchCurve::new(p, *c, &shape))
            .collect();
        let mut solver = BatchSolver::new();
        for scheme in [Scheme::Kappa, Scheme::EkCubic] {
            let got = solver.solve(&batch, scheme);
            assert_eq!(got.len(), curves.len());
            for ((p, c), g) in curves.iter().zip(&got) {
                let want = crate::Solver::new().solve(p, *c, scheme, &shape);
                assert_eq!(g, &want);
            }
        }
    }

    #[test]
    fn a_bad_curve_gets_its_error_and_the_others_are_solved() {
        let good = ring(8, 10.0, 0.0);
        let bad = vec![
            Point::new(0.0, 0.0),
            Point::new(f64::NAN, 1.0),
            Point::new(2.0, 0.0),
        ];
        let shape = Shape::Neutral;
        let batch = [
            BatchCurve::new(&good, true, &shape),
            BatchCurve::new(&bad, true, &shape),
            BatchCurve::new(&good, false, &shape),
            BatchCurve::new(&good, true, &shape),
        ];
        let got = BatchSolver::new().solve(&batch, Scheme::Kappa);
        assert!(got[0].is_ok() && got[2].is_ok() && got[3].is_ok());
        assert!(
            matches!(got[1], Err(Error::NonFinitePoint { index: 1 })),
            "{:?}",
            got[1]
        );
        assert_eq!(got[0], got[3]);
    }

    #[test]
    fn small_and_empty_batches_stay_on_the_calling_thread() {
        let tri = ring(3, 1.0, 0.0);
        let shape = Shape::Neutral;
        let solver = BatchSolver::new();
        assert_eq!(solver.threads_for(&[]), 1);
        assert_eq!(
            solver.threads_for(&[BatchCurve::new(&tri, true, &shape)]),
            1
        );
        assert!(BatchSolver::new().solve(&[], Scheme::Kappa).is_empty());
    }
}
