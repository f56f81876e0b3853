//! `kappa curve`: solve one curve (JSON on stdin or `--input`) or a drawing (`--design`,
//! `--builtin`) and print the Bézier segments as JSON.
//!
//! The JSON formats are a stable contract:
//!
//! - input: `{"points": [[x, y], …], "closed"?: bool, "scheme"?: "kappa" | "ek-cubic",
//!   "shape"?: a | [a₀, …]}`, no other fields;
//! - output: `{"scheme", "closed", "iterations", "converged", "segments": [{"degree",
//!   "points", "t_max"}], "svg_path"}`, or `{"name", "curves": [<that object>, …]}` for a
//!   drawing.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{ArgGroup, Args, ValueEnum};
use kappa::fit::FitOptions;
use kappa::input::{CurveInput, InputLimits, DEFAULT_MAX_POINTS};
use kappa::{Design, Extremum, Scheme, Shape, SolveOptions, Solver, Spline};
use kurbo::Point;
use serde::{Deserialize, Serialize};

use crate::builtin;
use crate::failure::{self, Failure, Result};
use crate::picture;

/// Solve a curve, or every curve of a drawing, and print the segments as JSON.
#[derive(Debug, Args)]
#[command(
    long_about = "Solve a curve, or every curve of a drawing, and print its Bézier segments as JSON.\n\n\
        Input (stdin, or --input FILE), one JSON object:\n  \
        {\"points\": [[x, y], ...], \"closed\": true, \"scheme\": \"kappa\" | \"ek-cubic\" | \"ek-trig\", \
        \"shape\": 0.8 | [a0, a1, ...]}\n\
        'closed' defaults to true, 'scheme' to \"kappa\", 'shape' (ek-cubic: in [2/3, 1), default \
        2/3; ek-trig: in [1/2, 1), default 0.7); other fields are rejected.\n\n\
        Output (stdout), one JSON object on one line:\n  \
        {\"scheme\": ..., \"closed\": ..., \"iterations\": n, \"converged\": true, \
        \"segments\": [{\"degree\": 2 | 3, \"points\": [[x, y], ...], \"t_max\": t, \
        \"extremum\": \"max\" | \"min\" | \"end-only\" | \"inflection\"}, ...], \
        \"svg_path\": \"M...\"}\n\
        Segment 'points' are the Bézier control points (3 for degree 2, 4 for degree 3); the \
        segment passes through its input point at t_max, where |curvature| has a local \
        'extremum' (\"end-only\": a local maximum at a segment end, the segment's |curvature| \
        being higher inside; \"inflection\": the segment has collapsed onto its point, an \
        inflection of the curve). Segments follow the curve: one per input point (closed) or per interior \
        input point (open). ek-trig segments carry \"basis\": \"trig\" and as 'points' the five \
        control points P0..P4 of their quadratic trigonometric curve; their svg_path is fitted \
        (cubics within 1e-4 of the drawing size) and the output adds \
        \"fit\": {\"tolerance\": e, \"max_distance\": d, \"cubics\": [k, ...]}.\n\n\
        With --design FILE or --builtin NAME the input is a drawing \
        ({\"name\": ..., \"curves\": [{\"closed\": ..., \"points\": [...], \"shape\": [...]}]}) \
        and the output is {\"name\": ..., \"curves\": [<one object as above per curve>]}.\n\n\
        On any error the exit code is 2, stderr holds one 'kappa: error:' line and stdout \
        stays empty.",
    after_help = "Examples:\n  \
        echo '{\"points\": [[0,0],[100,0],[50,80]]}' | kappa curve\n  \
        kappa curve --input wave.json --svg wave.svg --png wave.png --size 800\n  \
        echo '{\"points\": [[0,0],[100,0],[50,80]], \"scheme\": \"ek-cubic\", \"shape\": 0.9}' | kappa curve\n  \
        kappa curve --design drawing.json --scheme ek-cubic --shape 0.85\n  \
        kappa curve --builtin bear --png bear.png",
    group(ArgGroup::new("drawing").args(["design", "builtin"]))
)]
pub struct CurveArgs {
    /// Read the curve JSON from FILE instead of stdin.
    #[arg(long, value_name = "FILE", conflicts_with = "drawing")]
    input: Option<PathBuf>,
    /// Solve every curve of the drawing in FILE (the data/designs/*.json format).
    #[arg(long, value_name = "FILE")]
    design: Option<PathBuf>,
    /// Solve every curve of a built-in drawing (bear, bird, deer, dinosaur, elephant, plane,
    /// pumpkin, rabbit, rose, eps-…).
    #[arg(long, value_name = "NAME")]
    builtin: Option<String>,
    /// Scheme for a drawing [default: kappa].
    #[arg(long, value_enum, value_name = "SCHEME", requires = "drawing")]
    scheme: Option<SchemeName>,
    /// Global shape parameter `a` for a drawing (ek-cubic: in [2/3, 1); ek-trig: in
    /// [1/2, 1)). Without it, the εκ schemes use each curve's own "shape" list if it has
    /// one, else their default (2/3, 0.7).
    #[arg(
        long,
        value_name = "A",
        requires = "drawing",
        allow_negative_numbers = true
    )]
    shape: Option<f64>,
    /// Convergence tolerance, relative to the drawing size.
    #[arg(long, value_name = "TOL", default_value_t = SolveOptions::default().tolerance, allow_negative_numbers = true)]
    tolerance: f64,
    /// Iteration cap of the solver.
    #[arg(long, value_name = "N", default_value_t = SolveOptions::default().max_iterations)]
    max_iterations: usize,
    /// Print the best curve found when the iteration cap is hit ("converged": false) instead
    /// of failing.
    #[arg(long)]
    allow_unconverged: bool,
    /// The most points a curve (or a whole drawing) may have; larger inputs are rejected
    /// while they are read, before any solving.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_POINTS)]
    max_points: usize,
    /// Also write an SVG picture (curves, input points, curvature combs) to FILE.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    /// Also write a PNG picture (curves, input points, curvature combs) to FILE.
    #[arg(long, value_name = "FILE")]
    png: Option<PathBuf>,
    /// Width and height of the pictures in pixels.
    #[arg(long, value_name = "W", default_value_t = 600,
          value_parser = clap::value_parser!(u32).range(1..=8192))]
    size: u32,
}

/// The scheme names of the JSON contract and of `--scheme`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum SchemeName {
    /// κ-curves: quadratic Bézier segments.
    Kappa,
    /// Cubic εκ-curves: a shape parameter a ∈ [2/3, 1) per point.
    EkCubic,
    /// Trigonometric εκ-curves: a shape parameter a ∈ [1/2, 1) per point.
    EkTrig,
}

impl SchemeName {
    /// The library's scheme.
    pub fn scheme(self) -> Scheme {
        match self {
            SchemeName::Kappa => Scheme::Kappa,
            SchemeName::EkCubic => Scheme::EkCubic,
            SchemeName::EkTrig => Scheme::EkTrig,
        }
    }

    /// The name for a library scheme.
    pub fn of(scheme: Scheme) -> SchemeName {
        match scheme {
            Scheme::Kappa => SchemeName::Kappa,
            Scheme::EkCubic => SchemeName::EkCubic,
            Scheme::EkTrig => SchemeName::EkTrig,
        }
    }
}

/// One solved curve in the output.
#[derive(Debug, Serialize)]
pub struct CurveOutput {
    scheme: SchemeName,
    closed: bool,
    iterations: usize,
    converged: bool,
    segments: Vec<SegmentOutput>,
    svg_path: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    fit: Option<FitOutput>,
}

/// How the path of a non-polynomial curve was fitted.
#[derive(Debug, Serialize)]
struct FitOutput {
    tolerance: f64,
    max_distance: f64,
    cubics: Vec<usize>,
}

/// One Bézier segment in the output.
#[derive(Debug, Serialize)]
struct SegmentOutput {
    #[serde(skip_serializing_if = "Option::is_none")]
    basis: Option<&'static str>,
    degree: usize,
    points: Vec<[f64; 2]>,
    t_max: f64,
    extremum: &'static str,
}

/// The output of a drawing.
#[derive(Debug, Serialize)]
struct DesignOutput {
    name: String,
    curves: Vec<CurveOutput>,
}

/// A curve to solve: points, closedness, scheme and shapes.
struct Job {
    points: Vec<Point>,
    closed: bool,
    scheme: Scheme,
    shape: Shape,
}

/// Runs `kappa curve`.
pub fn run(args: &CurveArgs) -> Result<ExitCode> {
    let options = SolveOptions {
        tolerance: args.tolerance,
        max_iterations: args.max_iterations,
        accept_unconverged: args.allow_unconverged,
    };
    let mut solver = Solver::with_options(options);
    let drawing = match (&args.design, &args.builtin) {
        (Some(path), _) => {
            let text = failure::read_text(path)?;
            let design = Design::from_json(&text)
                .map_err(|e| Failure::new(format!("invalid drawing in {}: {e}", path.display())))?;
            Some(design)
        }
        (None, Some(name)) => Some(builtin::load(name)?),
        (None, None) => None,
    };
    if let Some(design) = &drawing {
        let total: usize = design.curves.iter().map(|c| c.points.len()).sum();
        if total > args.max_points {
            return Err(Failure::new(format!(
                "the drawing has {total} points, more than the limit of {} (see --max-points)",
                args.max_points
            )));
        }
    }
    let (text, solved) = match drawing {
        Some(design) => {
            let scheme = args.scheme.unwrap_or(SchemeName::Kappa).scheme();
            let jobs = design_jobs(&design, scheme, args.shape)?;
            let mut curves = Vec::with_capacity(jobs.len());
            let mut solved = Vec::with_capacity(jobs.len());
            for (i, job) in jobs.into_iter().enumerate() {
                let spline =
                    solve(&mut solver, &job).map_err(|f| f.context(format!("curve {i}")))?;
                curves.push(curve_output(&spline).map_err(|f| f.context(format!("curve {i}")))?);
                solved.push((spline, job.points));
            }
            let out = DesignOutput {
                name: design.name,
                curves,
            };
            (to_json(&out)?, solved)
        }
        None => {
            let text = match &args.input {
                Some(path) => failure::read_text(path)?,
                None => failure::read_stdin()?,
            };
            let limits = InputLimits {
                max_points: args.max_points,
            };
            let job = parse_curve_with(&text, &limits)?;
            let spline = solve(&mut solver, &job)?;
            let out = curve_output(&spline)?;
            (to_json(&out)?, vec![(spline, job.points)])
        }
    };
    if args.svg.is_some() || args.png.is_some() {
        let scene = picture::scene(&solved, args.size, args.size);
        picture::write_pictures(&scene, args.svg.as_deref(), args.png.as_deref())?;
    }
    failure::print_stdout(&text)?;
    Ok(ExitCode::SUCCESS)
}

/// Parses the single-curve JSON input (through the library's [`CurveInput`], which bounds
/// the number of points while parsing).
fn parse_curve_with(text: &str, limits: &InputLimits) -> Result<Job> {
    let input = CurveInput::from_json(text, limits).map_err(Failure::new)?;
    Ok(Job {
        points: input.points,
        closed: input.closed,
        scheme: input.scheme,
        shape: input.shape,
    })
}

/// [`parse_curve_with`] with the default limits.
#[cfg(test)]
fn parse_curve(text: &str) -> Result<Job> {
    parse_curve_with(text, &InputLimits::default())
}

/// The curves of a drawing to solve with `scheme` and the optional global shape `a`.
fn design_jobs(design: &Design, scheme: Scheme, a: Option<f64>) -> Result<Vec<Job>> {
    if design.curves.is_empty() {
        return Err(Failure::new("the drawing has no curves"));
    }
    Ok(design
        .curves
        .iter()
        .map(|c| {
            let shape = match (a, scheme, &c.shape) {
                (Some(a), _, _) => Shape::Global(a),
                (None, Scheme::EkCubic | Scheme::EkTrig, Some(list)) => {
                    Shape::PerPoint(list.clone())
                }
                _ => Shape::Neutral,
            };
            Job {
                points: c.kurbo_points(),
                closed: c.is_closed(),
                scheme,
                shape,
            }
        })
        .collect())
}

fn solve(solver: &mut Solver, job: &Job) -> Result<Spline> {
    solver
        .solve(&job.points, job.closed, job.scheme, &job.shape)
        .map_err(Failure::new)
}

/// The JSON object of one solved curve; fails on any non-finite number (which JSON cannot
/// hold).
pub fn curve_output(spline: &Spline) -> Result<CurveOutput> {
    let segments: Vec<SegmentOutput> = spline
        .segments()
        .iter()
        .map(|s| SegmentOutput {
            basis: (s.scheme == Scheme::EkTrig).then_some("trig"),
            degree: s.degree,
            points: s.control_points().iter().map(|p| [p.x, p.y]).collect(),
            t_max: s.t_max,
            extremum: match s.extremum() {
                Extremum::Max => "max",
                Extremum::Min => "min",
                Extremum::Inflection => "inflection",
                Extremum::EndOnly => "end-only",
            },
        })
        .collect();
    let finite = segments
        .iter()
        .all(|s| s.t_max.is_finite() && s.points.iter().flatten().all(|v| v.is_finite()));
    if !finite {
        return Err(Failure::new(
            "the solver produced a non-finite curve (try other points or options)",
        ));
    }
    let fit = if spline.scheme().is_polynomial() {
        None
    } else {
        let fitted = spline.fit(&FitOptions::default()).map_err(Failure::new)?;
        Some(FitOutput {
            tolerance: fitted.tolerance,
            max_distance: fitted.max_distance,
            cubics: fitted.cubics,
        })
    };
    Ok(CurveOutput {
        scheme: SchemeName::of(spline.scheme()),
        closed: spline.is_closed(),
        iterations: spline.iterations(),
        converged: spline.converged(),
        segments,
        svg_path: spline.to_svg(),
        fit,
    })
}

/// Compact JSON followed by a newline.
fn to_json<T: Serialize>(value: &T) -> Result<String> {
    let mut text = serde_json::to_string(value)
        .map_err(|e| Failure::new(format!("cannot write JSON: {e}")))?;
    text.push('\n');
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn curve_input_defaults() {
        let job = parse_curve(r#"{"points": [[0, 0], [1, 0], [0, 1]]}"#).unwrap();
        assert!(job.closed);
        assert_eq!(job.scheme, Scheme::Kappa);
        assert_eq!(job.shape, Shape::Neutral);
    }

    #[test]
    fn curve_input_shapes() {
        let job = parse_curve(r#"{"points": [], "scheme": "ek-cubic", "shape": 0.8}"#).unwrap();
        assert_eq!(job.shape, Shape::Global(0.8));
        let job = parse_curve(r#"{"points": [], "shape": [0.7, 0.9]}"#).unwrap();
        assert_eq!(job.shape, Shape::PerPoint(vec![0.7, 0.9]));
        assert!(parse_curve(r#"{"points": [], "shape": "x"}"#).is_err());
        assert!(parse_curve(r#"{"points": [], "shape": [0.7, null]}"#).is_err());
    }

    #[test]
    fn curve_input_rejects_bad_points() {
        assert!(parse_curve(r#"{"points": [[0, null]]}"#).is_err());
        assert!(parse_curve(r#"{"points": [[0, 1, 2]]}"#).is_err());
        assert!(parse_curve(r#"{"points": [], "colsed": true}"#).is_err());
    }
}
