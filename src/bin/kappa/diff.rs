//! `kappa diff`: compare two PNG images pixel by pixel.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use kappa::render::golden::{compare, diff_image_with, load_png, Tolerance};

use crate::failure::{self, Failure, Result};

/// Exit code when the images differ.
const EXIT_DIFFERENT: u8 = 1;

/// Compare two PNG images pixel by pixel.
#[derive(Debug, Args)]
#[command(
    long_about = "Compare two PNG images pixel by pixel and print a one-line summary \
        (bad pixel count, largest channel difference).\n\n\
        Two pixels are equal when no channel differs by more than --channel; the images match \
        when they have the same size and at most --max-bad-pixels pixels differ.\n\n\
        Exit code: 0 if the images match, 1 if they differ, 2 on errors (missing or \
        unreadable file).",
    after_help = "Examples:\n  \
        kappa diff expected.png actual.png\n  \
        kappa diff expected.png actual.png --channel 2 --max-bad-pixels 10 --out diff.png"
)]
pub struct DiffArgs {
    /// The expected image.
    expected: PathBuf,
    /// The actual image.
    actual: PathBuf,
    /// Largest difference of a channel (0-255) for which two pixels still count as equal.
    #[arg(long, value_name = "N", default_value_t = Tolerance::DEFAULT.channel)]
    channel: u8,
    /// Number of differing pixels still accepted as a match.
    #[arg(long, value_name = "N", default_value_t = Tolerance::DEFAULT.max_bad_pixels)]
    max_bad_pixels: usize,
    /// When the images differ, write an "expected | diff | actual" image to FILE (red: differs
    /// by more than --channel, orange: by less, magenta: present in one image only).
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
}

/// Runs `kappa diff`.
pub fn run(args: &DiffArgs) -> Result<ExitCode> {
    let load = |path: &PathBuf| load_png(path).map_err(Failure::new);
    let expected = load(&args.expected)?;
    let actual = load(&args.actual)?;
    let tol = Tolerance::new(args.channel, args.max_bad_pixels);
    let comparison = compare(&expected, &actual, tol);
    if comparison.passed() {
        failure::print_stdout(&format!("match: {comparison}\n"))?;
        return Ok(ExitCode::SUCCESS);
    }
    let mut line = format!("differ: {comparison}");
    if let Some(path) = &args.out {
        let image = diff_image_with(&expected, &actual, tol)
            .map_err(|e| Failure::new(format!("cannot make the diff image: {e}")))?;
        let png = image
            .encode_png()
            .map_err(|e| Failure::new(format!("cannot encode the diff image: {e}")))?;
        failure::write_file(path, &png)?;
        line.push_str(&format!(
            "; expected | diff | actual written to {}",
            path.display()
        ));
    }
    line.push('\n');
    failure::print_stdout(&line)?;
    Ok(ExitCode::from(EXIT_DIFFERENT))
}
