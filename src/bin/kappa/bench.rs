//! `kappa bench`: time the solver on the built-in benchmark set and print median timings.

use std::f64::consts::TAU;
use std::hint::black_box;
use std::process::ExitCode;
use std::time::Instant;

use clap::Args;
use kappa::{BatchCurve, BatchSolver, Scheme, Shape, SolveOptions, Solver, Spline};
use kurbo::{Point, Vec2};
use serde::Serialize;

use crate::builtin::{self, DESIGNER_DRAWING};
use crate::curve::SchemeName;
use crate::failure::{self, Failure, Result};

/// The εκ shape parameter of the drawing benchmarks.
const EK_SHAPE: f64 = 0.85;
/// The schemes (and εκ shape) each drawing is timed with, in the order of the rows.
const DRAWING_SCHEMES: [(Scheme, Option<f64>); 2] =
    [(Scheme::Kappa, None), (Scheme::EkCubic, Some(EK_SHAPE))];
/// Points of the small star loop (warm and cold cases).
const SMALL_LOOP: usize = 50;
/// The input point moved in the warm case, and by how much.
const MOVED_POINT: usize = 10;
const MOVE_BY: Vec2 = Vec2::new(0.8, -0.5);
/// Points of the large star loop.
const LARGE_LOOP: usize = 100_000;
/// Repetitions of the large case at most (it takes a while).
const LARGE_REPEAT: usize = 3;
/// Microseconds per second.
const MICROS_PER_SECOND: f64 = 1e6;
/// The names of the cases that are not drawings.
const WARM_CASE: &str = "warm_move_one_point_50";
const COLD_CASE: &str = "cold_50";
const LARGE_CASE: &str = "ek_cubic_closed_100000";
/// Every case, for `--case`.
const CASES: [&str; 13] = [
    "bear",
    "bird",
    "deer",
    "dinosaur",
    "elephant",
    "plane",
    "pumpkin",
    "rabbit",
    "rose",
    DESIGNER_DRAWING,
    WARM_CASE,
    COLD_CASE,
    LARGE_CASE,
];

/// Time the solver on the built-in benchmark set.
#[derive(Debug, Args)]
#[command(
    long_about = "Time the solver on the built-in benchmark set and print a JSON array of \
        median timings in microseconds, one object per case:\n  \
        {\"case\": \"bear\", \"scheme\": \"kappa\", \"shape\": 0.85 (ek-cubic only), \
        \"curves\": 28, \"points\": 96, \"threads\": 1, \"repeat\": 31, \"median_us\": 12.3, \"iterations\": 150, \"converged\": true}\n\n\
        Cases: each drawing of the εκ paper (bear, bird, deer, dinosaur, elephant, plane, \
        pumpkin, rabbit, rose) and the designer drawing (a wave, a symmetric S, a curl on \
        whole pixels, straight runs) solved cold, curve by curve on one thread, as a κ-curve and \
        as an εκ-curve with a = 0.85 (median_us: all curves together; iterations: their \
        sum), then the same as one batch spread over the threads of the pool (\"threads\"; \
        RAYON_NUM_THREADS sets the pool's size); \
        warm_move_one_point_50: re-solving a 50-point κ star loop (radii alternating 100 and \
        90) after point 10 moved by (0.8, -0.5), from the previous solution, and re-solving \
        after moving it back (median_us: per re-solve, half the time of the pair; \
        iterations: of the pair); cold_50: the same loop solved from scratch; \
        ek_cubic_closed_100000: a 100 000-point star loop as an εκ-curve with a = 0.85, cold, \
        at most 3 repetitions.\n\n\
        Every solve accepts an unconverged result (iteration cap hit) so that the table is \
        always complete; \"converged\" is false in a row where any solve fell short.\n\n\
        Build with --release for meaningful numbers.",
    after_help = "Examples:\n  kappa bench\n  kappa bench --repeat 101 > timings.json\n  \
        kappa bench --case bear --case warm_move_one_point_50"
)]
pub struct BenchArgs {
    /// Repetitions per case (the median is reported).
    #[arg(long, value_name = "N", default_value_t = 31,
          value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    repeat: u32,
    /// Run only this case (repeatable; default: all).
    #[arg(long = "case", value_name = "CASE",
          value_parser = clap::builder::PossibleValuesParser::new(CASES))]
    cases: Vec<String>,
}

/// One row of the output table.
#[derive(Debug, Serialize)]
struct Row {
    case: String,
    scheme: SchemeName,
    #[serde(skip_serializing_if = "Option::is_none")]
    shape: Option<f64>,
    curves: usize,
    points: usize,
    /// Threads the curves were spread over (1: one after the other on one thread).
    threads: usize,
    repeat: usize,
    median_us: f64,
    iterations: usize,
    converged: bool,
}

/// What one timed run reports: iterations used and whether every solve converged.
#[derive(Clone, Copy, Debug)]
struct RunInfo {
    iterations: usize,
    converged: bool,
}

impl RunInfo {
    fn of(spline: &Spline) -> RunInfo {
        RunInfo {
            iterations: spline.iterations(),
            converged: spline.converged(),
        }
    }

    /// The iterations of several solves together, and whether all converged; the first
    /// error if any failed.
    fn total(
        splines: impl IntoIterator<Item = std::result::Result<Spline, kappa::Error>>,
    ) -> std::result::Result<RunInfo, kappa::Error> {
        let mut info = RunInfo {
            iterations: 0,
            converged: true,
        };
        for spline in splines {
            let spline = black_box(spline?);
            info.iterations += spline.iterations();
            info.converged &= spline.converged();
        }
        Ok(info)
    }
}

/// The timing of a case.
struct Timing {
    threads: usize,
    repeat: usize,
    median_us: f64,
    iterations: usize,
    converged: bool,
}

/// Runs `kappa bench`.
pub fn run(args: &BenchArgs) -> Result<ExitCode> {
    let repeat = args.repeat as usize;
    let wanted = |case: &str| args.cases.is_empty() || args.cases.iter().any(|c| c == case);
    let mut solver = Solver::with_options(SolveOptions {
        accept_unconverged: true,
        ..SolveOptions::default()
    });
    let mut batcher = BatchSolver::with_options(solver.options());
    let mut rows = Vec::new();
    for name in builtin::bench_drawings().filter(|n| wanted(n)) {
        let design = builtin::load(name)?;
        let curves: Vec<(Vec<Point>, bool)> = design
            .curves
            .iter()
            .map(|c| (c.kurbo_points(), c.is_closed()))
            .collect();
        let points = curves.iter().map(|(p, _)| p.len()).sum();
        for (scheme, shape) in DRAWING_SCHEMES {
            let shape_arg = shape.map_or(Shape::Neutral, Shape::Global);
            let timing = measure(repeat, || {
                RunInfo::total(
                    curves
                        .iter()
                        .map(|(pts, closed)| solver.solve(pts, *closed, scheme, &shape_arg)),
                )
            })
            .map_err(|f| f.context(name))?;
            rows.push(row(name, scheme, shape, curves.len(), points, timing));
        }
        // The same curves as one batch, spread over the threads of the pool.
        for (scheme, shape) in DRAWING_SCHEMES {
            let shape_arg = shape.map_or(Shape::Neutral, Shape::Global);
            let batch: Vec<BatchCurve<'_, Point>> = curves
                .iter()
                .map(|(pts, closed)| BatchCurve::new(pts, *closed, &shape_arg))
                .collect();
            let threads = batcher.threads_for(&batch);
            let mut timing = measure(repeat, || RunInfo::total(batcher.solve(&batch, scheme)))
                .map_err(|f| f.context(name))?;
            timing.threads = threads;
            rows.push(row(name, scheme, shape, curves.len(), points, timing));
        }
    }

    let small = star_loop(SMALL_LOOP);
    let mut moved = small.clone();
    moved[MOVED_POINT] += MOVE_BY;
    if wanted(WARM_CASE) {
        solver
            .solve(&small, true, Scheme::Kappa, &Shape::Neutral)
            .map_err(|e| Failure::new(format!("{WARM_CASE}: {e}")))?;
        // One timed run moves the point and moves it back: the two re-solves differ (the
        // stored factors are exact at one end only), and a median over alternating single
        // re-solves would land on the edge of one of the two clusters.
        let mut timing = measure(repeat, || {
            let there = RunInfo::of(&black_box(solver.resolve(&moved)?));
            let back = RunInfo::of(&black_box(solver.resolve(&small)?));
            Ok(RunInfo {
                iterations: there.iterations + back.iterations,
                converged: there.converged && back.converged,
            })
        })
        .map_err(|f| f.context(WARM_CASE))?;
        timing.median_us = (timing.median_us * 0.5 * 1e3).round() / 1e3;
        rows.push(row(WARM_CASE, Scheme::Kappa, None, 1, SMALL_LOOP, timing));
    }
    if wanted(COLD_CASE) {
        let timing = measure(repeat, || {
            let spline = solver.solve(&moved, true, Scheme::Kappa, &Shape::Neutral)?;
            Ok(RunInfo::of(&black_box(spline)))
        })
        .map_err(|f| f.context(COLD_CASE))?;
        rows.push(row(COLD_CASE, Scheme::Kappa, None, 1, SMALL_LOOP, timing));
    }
    if wanted(LARGE_CASE) {
        let large = star_loop(LARGE_LOOP);
        let shape = Shape::Global(EK_SHAPE);
        let timing = measure(repeat.min(LARGE_REPEAT), || {
            let spline = solver.solve(&large, true, Scheme::EkCubic, &shape)?;
            Ok(RunInfo::of(&black_box(spline)))
        })
        .map_err(|f| f.context(LARGE_CASE))?;
        rows.push(row(
            LARGE_CASE,
            Scheme::EkCubic,
            Some(EK_SHAPE),
            1,
            LARGE_LOOP,
            timing,
        ));
    }

    failure::print_stdout(&table(&rows)?)?;
    Ok(ExitCode::SUCCESS)
}

/// Runs `f` `repeat` times (after one untimed warm-up run when repeating more than once) and
/// returns the median time in µs, the median iteration count, and whether every run
/// converged.
fn measure(
    repeat: usize,
    mut f: impl FnMut() -> std::result::Result<RunInfo, kappa::Error>,
) -> Result<Timing> {
    let mut converged = true;
    if repeat > 1 {
        converged &= f().map_err(Failure::new)?.converged;
    }
    let mut times = Vec::with_capacity(repeat);
    let mut iterations = Vec::with_capacity(repeat);
    for _ in 0..repeat {
        let start = Instant::now();
        let info = f().map_err(Failure::new)?;
        times.push(start.elapsed().as_secs_f64() * MICROS_PER_SECOND);
        iterations.push(info.iterations);
        converged &= info.converged;
    }
    times.sort_by(f64::total_cmp);
    iterations.sort_unstable();
    let mid = repeat / 2;
    let median_us = if repeat % 2 == 1 {
        times[mid]
    } else {
        0.5 * (times[mid - 1] + times[mid])
    };
    Ok(Timing {
        threads: 1,
        repeat,
        // Nanosecond resolution is all `Instant` offers.
        median_us: (median_us * 1e3).round() / 1e3,
        iterations: iterations[mid],
        converged,
    })
}

/// A row of the table.
fn row(
    case: &str,
    scheme: Scheme,
    shape: Option<f64>,
    curves: usize,
    points: usize,
    timing: Timing,
) -> Row {
    Row {
        case: case.to_owned(),
        scheme: SchemeName::of(scheme),
        shape,
        curves,
        points,
        threads: timing.threads,
        repeat: timing.repeat,
        median_us: timing.median_us,
        iterations: timing.iterations,
        converged: timing.converged,
    }
}

/// `n` points of a closed star loop, radii alternating 100 and 90, θ = 2πi/n (a jagged
/// outline, the kind that makes the classic loop oscillate).
fn star_loop(n: usize) -> Vec<Point> {
    (0..n)
        .map(|i| {
            let th = i as f64 / n as f64 * TAU;
            let r = if i % 2 == 0 { 100.0 } else { 90.0 };
            Point::new(r * th.cos(), r * th.sin())
        })
        .collect()
}

/// The rows as a JSON array, one object per line.
fn table(rows: &[Row]) -> Result<String> {
    let mut out = String::from("[\n");
    for (i, row) in rows.iter().enumerate() {
        let json = serde_json::to_string(row)
            .map_err(|e| Failure::new(format!("cannot write JSON: {e}")))?;
        out.push_str("  ");
        out.push_str(&json);
        out.push_str(if i + 1 < rows.len() { ",\n" } else { "\n" });
    }
    out.push_str("]\n");
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_cases_start_with_the_paper_drawings() {
        use crate::builtin::PAPER_DRAWINGS;
        assert_eq!(CASES[..PAPER_DRAWINGS.len()], PAPER_DRAWINGS);
    }

    #[test]
    fn bench_star_loop_is_closed_and_distinct() {
        let pts = star_loop(SMALL_LOOP);
        assert_eq!(pts.len(), SMALL_LOOP);
        assert!((pts[0] - Point::new(100.0, 0.0)).hypot() < 1e-12);
    }
}
