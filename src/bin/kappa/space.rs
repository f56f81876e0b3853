//! `kappa space`: a κ-space curve (G2 in 3D, seed 004) through 3D points, as JSON.
//!
//! The JSON formats are a stable contract:
//!
//! - input: `{"points": [[x, y, z], …], "closed"?: bool, "replace"?: r}`, no other fields;
//! - output: `{"segments": [{"degree": 2 | 4, "points": [[x, y, z], …]}], "t_max": [u, …],
//!   "joints": [{"curvature_vector_gap": e}, …]}` (see `SpaceCurve::to_json`).

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, ValueEnum};
use kappa::input::{InputLimits, SpaceInput, DEFAULT_MAX_POINTS};
use kappa::space::{views_figure, views_scene, Gamma, PeakAtJoint, Replace, VIEWS};
use kappa::{Point3, SolveOptions, SpaceCurve, SpaceOptions};

use crate::failure::{self, Failure, Result};

/// Build a κ-space curve through 3D points and print its Bézier segments as JSON.
#[derive(Debug, Args)]
#[command(
    long_about = "Build a κ-space curve through 3D points: the 3D κ-curve (quadratic segments) \
        with a short piece around every joint replaced by a quartic, so that the curvature \
        vectors agree at every joint (G2 in 3D), the points are still interpolated and |κ| \
        still peaks at them (seed paper 004).\n\n\
        Input (stdin, or --input FILE), one JSON object:\n  \
        {\"points\": [[x, y, z], ...], \"closed\": true, \"replace\": 0.01}\n\
        'closed' defaults to true; 'replace' is the fraction r of the parameter range \
        replaced on each side of every joint (t1 = 1 - r, t2 = r; default 0.01 as in the \
        paper's plug-in; 0 keeps the quadratic joints; 1 replaces whole stretches between \
        points); other fields are rejected.\n\n\
        Output (stdout), one JSON object on one line:\n  \
        {\"segments\": [{\"degree\": 2 | 4, \"points\": [[x, y, z], ...]}, ...], \
        \"t_max\": [u, ...], \"joints\": [{\"curvature_vector_gap\": e}, ...]}\n\
        'segments' are the exact Bézier segments in order along the curve (3 or 5 control \
        points). 't_max' has one entry per point with a peak (every point of a closed \
        curve, the interior points of an open one): its curve parameter u = segment index + \
        parameter on that segment. 'joints' has one entry per joint of the segments (the \
        closing one included for closed curves): |k_a - k_b| / max(|k_a|, |k_b|) with k the \
        curvature vectors at the joint.\n\n\
        On any error the exit code is 2, stderr holds one 'kappa: error:' line and stdout \
        stays empty.",
    after_help = "Examples:\n  \
        echo '{\"points\": [[0,0,0],[100,0,30],[100,100,0],[0,100,30]]}' | kappa space\n  \
        kappa space --input helix.json --png helix.png --obj helix.obj\n  \
        kappa space --input knot.json --gamma optimized --svg knot.svg --view top"
)]
pub struct SpaceArgs {
    /// Read the curve JSON from FILE instead of stdin.
    #[arg(long, value_name = "FILE")]
    input: Option<PathBuf>,
    /// Where each quartic's middle control point goes: γ = λ (the paper's default) or the γ
    /// minimizing the distance to the replaced pieces (the paper's eq. 20).
    #[arg(long, value_enum, default_value_t = GammaName::Lambda)]
    gamma: GammaName,
    /// At a joint where the κ-curve put an input point: replace it anyway (G2; the curve then
    /// passes near the point) or keep the point and the G1 joint.
    #[arg(long, value_enum, default_value_t = AtJointName::Replace)]
    at_joint: AtJointName,
    /// Convergence tolerance of the κ solver, relative to the drawing size.
    #[arg(long, value_name = "TOL", default_value_t = SolveOptions::default().tolerance, allow_negative_numbers = true)]
    tolerance: f64,
    /// Iteration cap of the κ solver.
    #[arg(long, value_name = "N", default_value_t = SolveOptions::default().max_iterations)]
    max_iterations: usize,
    /// The most points the input may have; larger inputs are rejected while they are read.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_POINTS)]
    max_points: usize,
    /// Also write the curve as a Wavefront OBJ polyline to FILE.
    #[arg(long, value_name = "FILE")]
    obj: Option<PathBuf>,
    /// Largest distance of the OBJ polyline from the curve, relative to the curve's size.
    #[arg(
        long,
        value_name = "TOL",
        default_value_t = 1e-4,
        allow_negative_numbers = true
    )]
    obj_tolerance: f64,
    /// Also write a PNG picture to FILE: the curve from the top, front, side and
    /// isometrically, with its curvature comb, side by side.
    #[arg(long, value_name = "FILE")]
    png: Option<PathBuf>,
    /// Also write an SVG picture of one view (--view) to FILE.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    /// The view of the SVG picture.
    #[arg(long, value_enum, default_value_t = ViewName::Isometric)]
    view: ViewName,
    /// Side of each picture panel in pixels.
    #[arg(long, value_name = "W", default_value_t = 400,
          value_parser = clap::value_parser!(u32).range(1..=8192))]
    size: u32,
}

/// `--gamma`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum GammaName {
    /// γ = λ.
    Lambda,
    /// γ minimizing seed 004 eq. 20.
    Optimized,
}

/// `--at-joint`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum AtJointName {
    /// Replace the joint (G2).
    Replace,
    /// Keep the point (G1 there).
    Keep,
}

/// `--view`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum ViewName {
    /// Looking down the z axis.
    Top,
    /// Looking along +y.
    Front,
    /// Looking along −x.
    Side,
    /// Looking along −(1, 1, 1).
    Isometric,
}

/// A parsed job.
#[derive(Debug)]
struct Job {
    points: Vec<Point3>,
    closed: bool,
    replace: f64,
}

/// Runs `kappa space`.
pub fn run(args: &SpaceArgs) -> Result<ExitCode> {
    let text = match &args.input {
        Some(path) => failure::read_text(path)?,
        None => failure::read_stdin()?,
    };
    let job = parse_with(
        &text,
        &InputLimits {
            max_points: args.max_points,
        },
    )?;
    let options = SpaceOptions {
        replace: Replace::fraction(job.replace),
        gamma: match args.gamma {
            GammaName::Lambda => Gamma::Lambda,
            GammaName::Optimized => Gamma::Optimized,
        },
        at_joint: match args.at_joint {
            AtJointName::Replace => PeakAtJoint::Replace,
            AtJointName::Keep => PeakAtJoint::Keep,
        },
        solve: SolveOptions {
            tolerance: args.tolerance,
            max_iterations: args.max_iterations,
            accept_unconverged: false,
        },
    };
    let curve = SpaceCurve::new(&job.points, job.closed, &options).map_err(Failure::new)?;
    let mut json = curve.to_json().map_err(Failure::new)?;
    json.push('\n');
    if let Some(path) = &args.obj {
        let size = size_of(&job.points);
        let obj = curve
            .to_obj(args.obj_tolerance * size)
            .map_err(|e| Failure::new(format!("--obj-tolerance: {e}")))?;
        failure::write_file(path, obj.as_bytes())?;
    }
    if let Some(path) = &args.png {
        let image = views_figure(&curve, args.size)
            .map_err(|e| Failure::new(format!("cannot draw: {e}")))?;
        let png = image
            .encode_png()
            .map_err(|e| Failure::new(format!("cannot encode {}: {e}", path.display())))?;
        failure::write_file(path, &png)?;
    }
    if let Some(path) = &args.svg {
        let view = VIEWS[args.view as usize].1;
        let svg = views_scene(&curve, view, args.size, args.size, None)
            .map_err(|e| Failure::new(format!("cannot draw: {e}")))?
            .to_svg()
            .map_err(|e| Failure::new(format!("cannot draw: {e}")))?;
        failure::write_file(path, svg.as_bytes())?;
    }
    failure::print_stdout(&json)?;
    Ok(ExitCode::SUCCESS)
}

/// Parses the JSON input (through the library's [`SpaceInput`], which bounds the number of
/// points while parsing and checks `replace`).
fn parse_with(text: &str, limits: &InputLimits) -> Result<Job> {
    let input = SpaceInput::from_json(text, limits).map_err(Failure::new)?;
    Ok(Job {
        points: input.points,
        closed: input.closed,
        replace: input.replace,
    })
}

/// [`parse_with`] with the default limits.
#[cfg(test)]
fn parse(text: &str) -> Result<Job> {
    parse_with(text, &InputLimits::default())
}

/// The larger side of the points' bounding box (1 for a single point).
fn size_of(points: &[Point3]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for (k, v) in [p.x, p.y, p.z].into_iter().enumerate() {
            lo[k] = lo[k].min(v);
            hi[k] = hi[k].max(v);
        }
    }
    let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    if size > 0.0 {
        size
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn space_input_defaults_and_errors() {
        let job = parse(r#"{"points": [[0, 0, 0], [1, 0, 0], [0, 1, 1]]}"#).unwrap();
        assert!(job.closed);
        assert_eq!(job.replace, 0.01);
        let job = parse(r#"{"points": [], "closed": false, "replace": 0.2}"#).unwrap();
        assert!(!job.closed);
        assert_eq!(job.replace, 0.2);
        assert!(parse(r#"{"points": [[0, 0]]}"#).is_err());
        assert!(parse(r#"{"points": [[0, 0, null]]}"#).is_err());
        assert!(parse(r#"{"points": [], "gamma": 0.5}"#).is_err());
        assert!(parse(r#"{"points": [], "replace": "a"}"#).is_err());
    }

    #[test]
    fn space_views_match_their_names() {
        for (name, i) in [
            ("top", ViewName::Top),
            ("front", ViewName::Front),
            ("side", ViewName::Side),
            ("isometric", ViewName::Isometric),
        ] {
            assert_eq!(VIEWS[i as usize].0, name);
        }
    }
}
