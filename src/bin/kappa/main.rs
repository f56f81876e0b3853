//! `kappa`: the command-line tool over the `kappa` library.
//!
//! Each subcommand lives in its own module; this file only parses the command line, runs the
//! subcommand and turns failures into exit code 2 with one `kappa: error: …` line on stderr.

mod bench;
mod bspline;
mod builtin;
mod curve;
mod diff;
mod failure;
mod font;
mod gallery;
mod glyph;
mod hermite;
mod picture;
mod space;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

use failure::EXIT_ERROR;

/// Curves with controlled curvature: κ-curves and εκ-curves from the command line.
#[derive(Debug, Parser)]
#[command(
    name = "kappa",
    version,
    about = "Curves with controlled curvature: κ-curves and εκ-curves from the command line",
    long_about = "Curves with controlled curvature: κ-curves and εκ-curves from the command line.\n\n\
        Every error ends the program with exit code 2 and exactly one line on stderr \
        starting with 'kappa: error:'; nothing is then written to stdout.",
    after_help = "Examples:\n  \
        echo '{\"points\": [[0,0],[100,0],[50,80]]}' | kappa curve\n  \
        echo '{\"points\": [[0,0,0],[1,2,1],[3,1,0]], \"closed\": false}' | kappa bspline\n  \
        kappa curve --builtin bear --scheme ek-cubic --shape 0.85 --png bear.png\n  \
        kappa diff expected.png actual.png --out diff.png\n  \
        kappa bench --repeat 11\n  \
        echo '{\"points\": [[0,0,0],[100,0,30],[100,100,0],[0,100,30]]}' | kappa space\n  \
        kappa gallery --out gallery\n  \
        kappa glyph --font DejaVuSans.ttf --char S --scheme ek-cubic --shape auto --out S.png\n  \
        echo '{\"start\": {\"point\": [0,0], \"angle\": 0}, \"end\": {\"point\": [10,4], \"angle\": 1.2}, \"degree\": 3}' | kappa hermite"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    Curve(curve::CurveArgs),
    Bspline(bspline::BSplineArgs),
    Diff(diff::DiffArgs),
    Bench(bench::BenchArgs),
    Gallery(gallery::GalleryArgs),
    Space(space::SpaceArgs),
    Hermite(hermite::HermiteArgs),
    Glyph(glyph::GlyphArgs),
    Font(font::FontArgs),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return failure::usage_error(e),
    };
    failure::install_panic_hook();
    let result = std::panic::catch_unwind(|| match &cli.command {
        Command::Curve(args) => curve::run(args),
        Command::Bspline(args) => bspline::run(args),
        Command::Diff(args) => diff::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Gallery(args) => gallery::run(args),
        Command::Space(args) => space::run(args),
        Command::Hermite(args) => hermite::run(args),
        Command::Glyph(args) => glyph::run(args),
        Command::Font(args) => font::run(args),
    });
    match result {
        Ok(Ok(code)) => code,
        Ok(Err(failure)) => failure.report(),
        // The panic hook has already printed the one-line message.
        Err(_) => ExitCode::from(EXIT_ERROR),
    }
}

#[cfg(test)]
mod tests {
    use super::Cli;

    #[test]
    fn cli_definition_is_consistent() {
        <Cli as clap::CommandFactory>::command().debug_assert();
    }
}
