//! `kappa bspline`: the uniform cubic B-spline through points (2D or 3D, open or closed), its
//! Bézier segments, its maximum curvature and its length, as JSON.
//!
//! The JSON formats are a stable contract:
//!
//! - input: `{"points": [[x, y], …] or [[x, y, z], …], "closed"?: bool}`, no other fields;
//! - output: `{"control_points": [[…], …], "segments": [{"points": [4 points]}, …],
//!   "max_curvature": {"value": κ, "params": [t, …], "points": [[…], …]}, "length": L}`.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use kappa::input::{BSplineInput, BSplinePoints, InputLimits, DEFAULT_MAX_POINTS};
use kappa::render::Scene;
use kappa::space::{View, VIEWS};
use kappa::{BSpline, BSpline3, BSplineCurvatureMax, BSplinePoint};
use serde::Serialize;

use crate::failure::{self, Failure, Result};

/// Arc-length accuracy, relative to the drawing size (per segment).
const LENGTH_ACCURACY: f64 = 1e-10;

/// Interpolate points with a uniform cubic B-spline and print it as JSON.
#[derive(Debug, Args)]
#[command(
    long_about = "Interpolate points with a uniform cubic B-spline (relaxed when open: zero \
        curvature at both ends; periodic when closed: C2 everywhere) and print its control \
        points, Bézier segments, maximum curvature and length as JSON.\n\n\
        Input (stdin, or --input FILE), one JSON object:\n  \
        {\"points\": [[x, y], ...] or [[x, y, z], ...], \"closed\": true}\n\
        All points have 2 coordinates or all have 3. 'closed' defaults to true (as for \
        'kappa curve'); other fields are rejected. An open spline needs 2 points, a closed one \
        3; consecutive points must differ.\n\n\
        Output (stdout), one JSON object on one line:\n  \
        {\"control_points\": [[...], ...], \"segments\": [{\"points\": [p0, p1, p2, p3]}, ...], \
        \"max_curvature\": {\"value\": k, \"params\": [t, ...], \"points\": [[...], ...]}, \
        \"length\": L}\n\
        Segment i is the cubic Bézier from point i to point i+1 on the global parameter \
        interval [i, i+1]; 'params' are global parameters (in [0, n] open, [0, n+1) closed \
        for n+1 points) where the maximum |curvature| 'value' is attained, every one of them \
        (ties within 1e-12 relative), and 'points' the curve points there. 'value' is null if \
        the curvature is unbounded (a cusp). 'length' is the arc length.\n\n\
        --svg/--png draw the curve, its control polygon, the points and the maxima (in y-up \
        coordinates; 2D curves with a curvature comb, 3D curves in the orthographic --view).\n\n\
        On any error the exit code is 2, stderr holds one 'kappa: error:' line and stdout \
        stays empty.",
    after_help = "Examples:\n  \
        echo '{\"points\": [[0,0],[1,1],[2,0],[3,1]], \"closed\": false}' | kappa bspline\n  \
        echo '{\"points\": [[1,0,0],[0,1,0.5],[-1,0,0],[0,-1,-0.5]]}' | kappa bspline --png knot.png\n  \
        kappa bspline --input points.json --svg spline.svg --size 800"
)]
pub struct BSplineArgs {
    /// Read the JSON input from FILE instead of stdin.
    #[arg(long, value_name = "FILE")]
    input: Option<PathBuf>,
    /// Also write an SVG picture to FILE.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    /// Also write a PNG picture to FILE.
    #[arg(long, value_name = "FILE")]
    png: Option<PathBuf>,
    /// Width and height of the pictures in pixels.
    #[arg(long, value_name = "W", default_value_t = 600,
          value_parser = clap::value_parser!(u32).range(1..=8192))]
    size: u32,
    /// The most points the input may have; larger inputs are rejected while they are read.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_POINTS)]
    max_points: usize,
    /// 3D pictures: the orthographic view (as for `kappa space`).
    #[arg(long, value_name = "VIEW", default_value = "isometric",
          value_parser = clap::builder::PossibleValuesParser::new(VIEWS.map(|v| v.0)))]
    view: String,
}

/// The output; `P` is `[f64; 2]` or `[f64; 3]`.
#[derive(Debug, Serialize)]
struct Output<P> {
    control_points: Vec<P>,
    segments: Vec<SegmentOutput<P>>,
    max_curvature: MaxOutput<P>,
    length: f64,
}

#[derive(Debug, Serialize)]
struct SegmentOutput<P> {
    points: [P; 4],
}

#[derive(Debug, Serialize)]
struct MaxOutput<P> {
    /// `None` (JSON null) when unbounded.
    value: Option<f64>,
    params: Vec<f64>,
    points: Vec<P>,
}

/// Runs `kappa bspline`.
pub fn run(args: &BSplineArgs) -> Result<ExitCode> {
    let text = match &args.input {
        Some(path) => failure::read_text(path)?,
        None => failure::read_stdin()?,
    };
    let limits = InputLimits {
        max_points: args.max_points,
    };
    let input = BSplineInput::from_json(&text, &limits).map_err(Failure::new)?;
    let closed = input.closed;
    let (json, scene) = match input.points {
        BSplinePoints::Plane(pts) => {
            let s = BSpline::new(&pts, closed).map_err(Failure::new)?;
            let json = to_json(&output(&s, |p| [p.x, p.y])?)?;
            (
                json,
                wants_picture(args).then(|| s.scene(args.size, args.size)),
            )
        }
        BSplinePoints::Space(pts) => {
            let s = BSpline3::new(&pts, closed).map_err(Failure::new)?;
            let json = to_json(&output(&s, |p| [p.x, p.y, p.z])?)?;
            let view = VIEWS
                .iter()
                .find(|v| v.0 == args.view)
                .map_or(View::ISOMETRIC, |v| v.1);
            (
                json,
                wants_picture(args).then(|| s.scene(view, args.size, args.size)),
            )
        }
    };
    if let Some(scene) = scene {
        write_pictures(args, &scene)?;
    }
    failure::print_stdout(&json)?;
    Ok(ExitCode::SUCCESS)
}

fn wants_picture(args: &BSplineArgs) -> bool {
    args.svg.is_some() || args.png.is_some()
}

fn write_pictures(args: &BSplineArgs, scene: &Scene) -> Result<()> {
    crate::picture::write_pictures(scene, args.svg.as_deref(), args.png.as_deref())
}

/// The output object of a spline, with `coords` giving the JSON form of a point.
fn output<P: BSplinePoint, C: AsRef<[f64]>>(
    s: &BSpline<P>,
    coords: impl Fn(P) -> C,
) -> Result<Output<C>> {
    let segments = (0..s.segment_count())
        .filter_map(|i| s.segment_points(i))
        .map(|p| SegmentOutput {
            points: p.map(&coords),
        })
        .collect();
    let BSplineCurvatureMax { value, params } = s.max_curvature();
    let points = params.iter().map(|&t| coords(s.eval(t))).collect();
    let input: Vec<C> = s.points().iter().map(|&p| coords(p)).collect();
    let size = drawing_size(&input);
    let length = s.arclen(LENGTH_ACCURACY * size);
    if !length.is_finite() {
        return Err(Failure::new("the length of the curve overflows"));
    }
    Ok(Output {
        control_points: s.control_points().iter().map(|&p| coords(p)).collect(),
        segments,
        max_curvature: MaxOutput {
            value: value.is_finite().then_some(value),
            params,
            points,
        },
        length,
    })
}

/// The larger side of the bounding box of the points.
fn drawing_size<C: AsRef<[f64]>>(points: &[C]) -> f64 {
    let dim = points.first().map_or(0, |p| p.as_ref().len());
    (0..dim)
        .map(|k| {
            let (lo, hi) = points
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                    (lo.min(p.as_ref()[k]), hi.max(p.as_ref()[k]))
                });
            hi - lo
        })
        .fold(0.0, f64::max)
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
    use BSplinePoints as Points;

    /// The library's parser with the default limits, as the tool calls it.
    fn parse(text: &str) -> Result<(Points, bool)> {
        let input = BSplineInput::from_json(text, &InputLimits::default()).map_err(Failure::new)?;
        Ok((input.points, input.closed))
    }

    #[test]
    fn bspline_input_dimensions_and_defaults() {
        let (p, closed) = parse(r#"{"points": [[0, 0], [1, 0], [0, 1]]}"#).unwrap();
        assert!(closed && matches!(p, Points::Plane(ref v) if v.len() == 3));
        let (p, closed) = parse(r#"{"points": [[0, 0, 1], [1, 0, 2]], "closed": false}"#).unwrap();
        assert!(!closed && matches!(p, Points::Space(ref v) if v.len() == 2));
        assert!(parse(r#"{"points": [[0, 0], [1, 0, 2]]}"#).is_err());
        assert!(parse(r#"{"points": [[0, 0, 0, 0]]}"#).is_err());
        assert!(parse(r#"{"points": [[0, null]]}"#).is_err());
        assert!(parse(r#"{"points": [], "closd": true}"#).is_err());
    }
}
