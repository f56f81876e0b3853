//! `kappa hermite`: one intrinsic segment (curvature an explicit Bézier function of arc
//! length) meeting G1 or G2 Hermite data, as JSON.
//!
//! The JSON formats are a stable contract:
//!
//! - input: `{"start": {"point": [x, y], "angle": θ, "curvature"?: κ}, "end": {…},
//!   "degree": n, "control_curvatures"?: [...], "weights"?: [...], "turning"?: "nearest" |
//!   "as-given"}` — curvatures at both ends make G2 data, at neither G1;
//! - output: `{"length", "control_curvatures", "weights"?, "end_error", "inflections",
//!   "monotone", "svg_path"}`.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use kappa::fit::FitOptions;
use kappa::input::HermiteInput;
use kappa::intrinsic::{picture, Hermite, IntrinsicSeg, Profile};
use serde::Serialize;

use crate::failure::{self, Failure, Result};

/// Solve a G1 or G2 Hermite problem with one intrinsic segment and print it as JSON.
#[derive(Debug, Args)]
#[command(
    long_about = "Find the curve whose curvature is an explicit Bézier function of arc length \
        (degree n) that meets G1 or G2 Hermite data, and print it as JSON.\n\n\
        Input (stdin, or --input FILE), one JSON object:\n  \
        {\"start\": {\"point\": [x, y], \"angle\": a, \"curvature\": k}, \"end\": {...}, \
        \"degree\": n, \"control_curvatures\": [...], \"weights\": [...], \
        \"turning\": \"nearest\" | \"as-given\"}\n\
        Angles are in radians, anticlockwise from +x (y up); curvatures are positive for left \
        turns. With 'curvature' at both ends the data are G2 (n >= 3; the solver picks \
        control curvatures 1 and n-1), at neither G1 (n >= 1; it picks 0 and n). \
        'control_curvatures' (optional, n + 1 entries): null for 'chosen by the solver' (the \
        solved ones, and linear interpolation between them elsewhere), a number for a given \
        value, {\"same_as\": i} to equal entry i; the solved entries (and for G2 the end \
        ones) must be null. 'weights' (optional, n + 1 positive numbers) make the curvature \
        function rational. 'turning' (default \"nearest\") says how the angles fix the total \
        turning: the short way round, or end angle minus start angle exactly.\n\n\
        Output (stdout), one JSON object on one line:\n  \
        {\"length\": L, \"control_curvatures\": [...], \"weights\": [...], \"end_error\": e, \
        \"inflections\": [t, ...], \"monotone\": true, \"svg_path\": \"M...\"}\n\
        'end_error' is the largest miss of the end conditions relative to the chord; \
        'inflections' are the parameters t = s / L in (0, 1) where the curvature changes \
        sign; 'monotone' says whether the curvature never turns back; 'svg_path' is the curve \
        as cubic Béziers within --tolerance of it. 'weights' appears only for rational input.\n\n\
        On any error (including data no curve of the profile meets) the exit code is 2, \
        stderr holds one 'kappa: error:' line and stdout stays empty.",
    after_help = "Examples:\n  \
        echo '{\"start\": {\"point\": [0,0], \"angle\": 0}, \"end\": {\"point\": [10,4], \"angle\": 1.2}, \"degree\": 1}' | kappa hermite\n  \
        echo '{\"start\": {\"point\": [0,0], \"angle\": 0, \"curvature\": 0.05}, \"end\": {\"point\": [10,4], \"angle\": 1.2, \"curvature\": 0.3}, \"degree\": 5}' | kappa hermite --png s.png"
)]
pub struct HermiteArgs {
    /// Read the JSON from FILE instead of stdin.
    #[arg(long, value_name = "FILE")]
    input: Option<PathBuf>,
    /// Tolerance of the cubic Béziers of 'svg_path', relative to the curve's size.
    #[arg(
        long,
        value_name = "TOL",
        default_value_t = 1e-6,
        allow_negative_numbers = true
    )]
    tolerance: f64,
    /// Also write an SVG picture (curve, curvature comb, inflections, extrema) to FILE.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    /// Also write a PNG picture to FILE.
    #[arg(long, value_name = "FILE")]
    png: Option<PathBuf>,
    /// Width and height of the pictures in pixels.
    #[arg(long, value_name = "W", default_value_t = 600,
          value_parser = clap::value_parser!(u32).range(1..=8192))]
    size: u32,
}

/// The output.
#[derive(Debug, Serialize)]
struct HermiteOutput {
    length: f64,
    control_curvatures: Vec<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    weights: Option<Vec<f64>>,
    end_error: f64,
    inflections: Vec<f64>,
    monotone: bool,
    svg_path: String,
}

/// Runs `kappa hermite`.
pub fn run(args: &HermiteArgs) -> Result<ExitCode> {
    let text = match &args.input {
        Some(path) => failure::read_text(path)?,
        None => failure::read_stdin()?,
    };
    let (hermite, profile) = parse(&text)?;
    let seg = hermite.solve(&profile).map_err(Failure::new)?;
    let fitted = seg
        .to_bezpath(&FitOptions::relative(args.tolerance))
        .map_err(Failure::new)?;
    let out = HermiteOutput {
        length: seg.length(),
        control_curvatures: seg.curvatures().to_vec(),
        weights: seg.weights().map(<[f64]>::to_vec),
        end_error: hermite.end_error(&seg),
        inflections: seg.inflections(),
        monotone: seg.is_monotone(),
        svg_path: kappa::svg_path_data(&fitted.path),
    };
    let mut json =
        serde_json::to_string(&out).map_err(|e| Failure::new(format!("cannot write JSON: {e}")))?;
    json.push('\n');
    if args.svg.is_some() || args.png.is_some() {
        draw(args, &seg, &hermite)?;
    }
    failure::print_stdout(&json)?;
    Ok(ExitCode::SUCCESS)
}

/// Writes the pictures asked for.
fn draw(args: &HermiteArgs, seg: &IntrinsicSeg, hermite: &Hermite) -> Result<()> {
    let points = [hermite.start.point, hermite.end.point];
    let scene = picture::scene(std::slice::from_ref(seg), &points, args.size, args.size)
        .map_err(|e| Failure::new(format!("cannot draw: {e}")))?;
    crate::picture::write_pictures(&scene, args.svg.as_deref(), args.png.as_deref())
}

/// Parses the input into Hermite data and a profile (through the library's
/// [`HermiteInput`], which also bounds the degree and the list lengths).
fn parse(text: &str) -> Result<(Hermite, Profile)> {
    let input = HermiteInput::from_json(text).map_err(Failure::new)?;
    Ok((input.hermite, input.profile))
}

#[cfg(test)]
mod tests {
    use super::*;
    use kappa::intrinsic::{Control, Turning};

    #[test]
    fn hermite_input_parses() {
        let (h, p) = parse(
            r#"{"start": {"point": [0, 0], "angle": 0.5}, "end": {"point": [1, 2], "angle": 1},
                "degree": 3, "control_curvatures": [null, {"same_as": 0}, 2.5, null],
                "turning": "as-given"}"#,
        )
        .unwrap();
        assert!(!h.is_g2());
        assert_eq!(h.turning, Turning::AsGiven);
        assert_eq!(
            p.controls,
            vec![
                Control::Free,
                Control::Same(0),
                Control::Given(2.5),
                Control::Free
            ]
        );
        let (h, p) = parse(
            r#"{"start": {"point": [0, 0], "angle": 0, "curvature": 1},
                "end": {"point": [1, 0], "angle": 0, "curvature": -1}, "degree": 5,
                "weights": [1, 1, 2, 2, 1, 1]}"#,
        )
        .unwrap();
        assert!(h.is_g2());
        assert_eq!(p.degree(), 5);
        assert_eq!(p.weights.unwrap().len(), 6);
    }

    #[test]
    fn hermite_input_rejects() {
        for bad in [
            r#"{"start": {"point": [0, null], "angle": 0}, "end": {"point": [1, 0], "angle": 0}, "degree": 1}"#,
            r#"{"start": {"point": [0, 0], "angle": 0}, "end": {"point": [1, 0], "angle": 0}}"#,
            r#"{"start": {"point": [0, 0], "angle": 0}, "end": {"point": [1, 0], "angle": 0}, "degree": 1, "control_curvatures": [null]}"#,
            r#"{"start": {"point": [0, 0], "angle": 0}, "end": {"point": [1, 0], "angle": 0}, "degree": 1, "extra": 1}"#,
            r#"{"start": {"point": [0, 0], "angle": 0}, "end": {"point": [1, 0], "angle": 0}, "degree": 1, "turning": "left"}"#,
        ] {
            assert!(parse(bad).is_err(), "{bad}");
        }
    }
}
