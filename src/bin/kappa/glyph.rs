//! `kappa glyph`: draft one glyph of a font as κ/εκ contours, print the draft as JSON and
//! write it as a picture (SVG, PNG), a UFO glyph (`.glif`) or a compiled TrueType font.
//!
//! The JSON output is a stable contract: `{"char", "glyph_id", "units_per_em", "scheme",
//! "shape", "tolerance", "hausdorff", "within_tolerance", "fallback", "anchor_count", "on_curve":
//! {"explicit", "all"}, "segments": {"line", "quad", "cubic"}, "contours": [{"closed",
//! "anchors": [{"point", "kind", "a"}], "pieces", "hausdorff", "segments"}], "out":
//! [{"file", "format", "segments", "exact", "max_error"}]}`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use kappa::glyph::{
    compile_font, contours, draft, to_glif, to_quadratic, word_scene, AnchorKind, DraftOptions,
    DraftShape, DraftedGlyph, FontGlyph, FontOutlines, PlacedGlyph,
};
use kappa::Scheme;
use kurbo::{BezPath, PathEl, PathSeg, Vec2};
use serde::Serialize;

use crate::curve::SchemeName;
use crate::failure::{self, Failure, Result};
use crate::picture;

/// Default tolerance of the TrueType conversion of cubics, in font units: half the `glyf`
/// grid step, below the rounding every point undergoes anyway.
const QUAD_TOLERANCE: f64 = 0.5;

/// Draft one glyph of a font as κ/εκ contours and print the draft as JSON.
#[derive(Debug, Args)]
#[command(
    long_about = "Draft one glyph of a TrueType/OpenType font as κ- or εκ-curves through the \
        points a designer would click (corners, on-curve extrema, curvature peaks, and points \
        added where the draft strays), print the draft as JSON, and write it to the --out \
        files.\n\n\
        Coordinates are font units with y up, as the font stores them. The draft is refined \
        until every piece is within --tolerance of the original (two-sided Hausdorff \
        distance). --fair then mends the anchors where the draft turns the other way than \
        the original (a κ-curve makes every point a curvature peak, so a point on a flat \
        flank gets one by wiggling), and --simplify drops the anchors it can do without.\n\n\
        Output files, by extension (--out may be given several times):\n  \
        .svg, .png  a picture: the original filled in grey, the draft in black with its \
        curvature comb and anchors in red (--size pixels square)\n  \
        .glif       the draft as a UFO glyph (glif format 2; quadratics for κ, cubics for εκ)\n  \
        .ttf        a TrueType font (family \"Kappa Draft\") holding the glyph: κ drafts \
        exactly, cubics converted to quadratics within --quad-tolerance; points are rounded \
        to the integer grid\n\n\
        Output (stdout), one JSON object on one line:\n  \
        {\"char\": \"S\", \"glyph_id\": n, \"units_per_em\": u, \"scheme\": ..., \
        \"shape\": \"neutral\" | \"auto\" | a, \"tolerance\": t, \"hausdorff\": h, \
        \"within_tolerance\": true, \"fallback\": 0, \
        \"anchor_count\": n, \"on_curve\": {\"explicit\": n, \"all\": n}, \
        \"segments\": {\"line\": n, \"quad\": n, \"cubic\": n}, \"contours\": [{\"closed\": true, \
        \"anchors\": [{\"point\": [x, y], \"kind\": \"corner\" | \"extremum\" | \"peak\" | \
        \"refined\", \"a\": a}, ...], \"pieces\": n, \"hausdorff\": h, \"segments\": {...}}, ...], \
        \"out\": [{\"file\": ..., \"format\": ..., \"segments\": {...}, \"exact\": true, \
        \"max_error\": e}, ...]}\n\
        'anchor_count' is the number of points a designer places (shared piece ends once); \
        'on_curve' counts the original's on-curve points without ('explicit') and with \
        ('all') the implied points of TrueType quadratics (a joint exactly midway between its \
        off-curve neighbours counts as implied, stored or not); 'hausdorff' is in font units and \
        'within_tolerance' says whether it is at most 'tolerance' (the refinement may stop \
        short: at 32 added anchors per piece, or when no anchor it tries can be solved); \
        'fallback' counts the pieces that no curve could be solved for, even cut in parts, \
        and that keep the original's segments (the glyph is drafted all the same); \
        each anchor's 'a' is its εκ shape parameter (2/3 for κ-curves and piece ends). \
        'out' lists each file written; for .ttf and .glif, 'segments' counts the exported \
        outline, 'exact' says whether it is the draft without approximation and 'max_error' \
        is the largest measured distance of the conversion (font units).\n\n\
        On any error (unreadable or invalid font, no glyph for the character, a glyph \
        without outline, unknown extension, shape out of range) the exit code is 2, stderr \
        holds one 'kappa: error:' line and stdout stays empty.",
    after_help = "Examples:\n  \
        kappa glyph --font DejaVuSans.ttf --char S --out S.png\n  \
        kappa glyph --font DejaVuSans.ttf --char a --scheme ek-cubic --shape auto --out a.glif --out a.svg\n  \
        kappa glyph --font DejaVuSans.ttf --char e --tolerance 4 --fair --simplify --out e.ttf"
)]
pub struct GlyphArgs {
    /// The TrueType/OpenType font file (the first face of a collection).
    #[arg(long, value_name = "FILE")]
    font: PathBuf,
    /// The character whose glyph to draft.
    #[arg(long = "char", value_name = "C")]
    ch: char,
    /// The curve scheme.
    #[arg(long, value_enum, value_name = "SCHEME", default_value = "kappa")]
    scheme: SchemeName,
    /// The εκ shape parameter: a number (ek-cubic: in [2/3, 1); ek-trig: in [1/2, 1)) for
    /// every anchor, or "auto" to match the original's curvature peak at each anchor
    /// [default: the scheme's neutral shape]. Only for the εκ schemes.
    #[arg(long, value_name = "A|auto", allow_negative_numbers = true)]
    shape: Option<String>,
    /// Largest distance of the draft from the original, in font units [default: 0.004 em].
    #[arg(long, value_name = "UNITS", allow_negative_numbers = true)]
    tolerance: Option<f64>,
    /// Move, drop or split the anchors where the draft turns the other way than the
    /// original (no spurious inflections; two to three times as slow).
    #[arg(long)]
    fair: bool,
    /// Drop every anchor the draft can do without and stay within the tolerance (fewer
    /// points, about four times as slow).
    #[arg(long)]
    simplify: bool,
    /// Largest distance of the TrueType quadratics from cubic drafts, in font units.
    #[arg(long, value_name = "UNITS", default_value_t = QUAD_TOLERANCE,
          allow_negative_numbers = true)]
    quad_tolerance: f64,
    /// Write the draft to FILE (.svg, .png, .glif or .ttf); may be repeated.
    #[arg(long, value_name = "FILE")]
    out: Vec<PathBuf>,
    /// Width and height of the pictures in pixels.
    #[arg(long, value_name = "W", default_value_t = 600,
          value_parser = clap::value_parser!(u32).range(1..=8192))]
    size: u32,
}

/// The output formats, by file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
enum Format {
    Svg,
    Png,
    Glif,
    Ttf,
}

impl Format {
    /// The format of a file name, from its extension (case-insensitive).
    fn of(path: &Path) -> Result<Format> {
        match failure::extension(path).as_deref() {
            Some("svg") => Ok(Format::Svg),
            Some("png") => Ok(Format::Png),
            Some("glif") => Ok(Format::Glif),
            Some("ttf") => Ok(Format::Ttf),
            _ => Err(Failure::new(format!(
                "cannot tell the format of {}: expected the extension .svg, .png, .glif or .ttf",
                path.display()
            ))),
        }
    }
}

/// The `"shape"` of the output: a name or a number.
#[derive(Debug, Serialize)]
#[serde(untagged)]
enum ShapeOutput {
    Name(&'static str),
    Value(f64),
}

/// Segment counts of an outline.
#[derive(Debug, Default, Serialize)]
struct Segments {
    line: usize,
    quad: usize,
    cubic: usize,
}

impl Segments {
    fn of(path: &BezPath) -> Segments {
        let mut s = Segments::default();
        for seg in path.segments() {
            match seg {
                PathSeg::Line(_) => s.line += 1,
                PathSeg::Quad(_) => s.quad += 1,
                PathSeg::Cubic(_) => s.cubic += 1,
            }
        }
        s
    }
}

#[derive(Debug, Serialize)]
struct OnCurve {
    explicit: usize,
    all: usize,
}

#[derive(Debug, Serialize)]
struct AnchorOutput {
    point: [f64; 2],
    kind: &'static str,
    a: f64,
}

#[derive(Debug, Serialize)]
struct ContourOutput {
    closed: bool,
    anchors: Vec<AnchorOutput>,
    pieces: usize,
    hausdorff: f64,
    segments: Segments,
}

#[derive(Debug, Serialize)]
struct FileOutput {
    file: String,
    format: Format,
    #[serde(skip_serializing_if = "Option::is_none")]
    segments: Option<Segments>,
    #[serde(skip_serializing_if = "Option::is_none")]
    exact: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    max_error: Option<f64>,
}

#[derive(Debug, Serialize)]
struct GlyphOutput {
    #[serde(rename = "char")]
    ch: String,
    glyph_id: u16,
    units_per_em: f64,
    scheme: SchemeName,
    shape: ShapeOutput,
    tolerance: f64,
    hausdorff: f64,
    within_tolerance: bool,
    fallback: usize,
    anchor_count: usize,
    on_curve: OnCurve,
    segments: Segments,
    contours: Vec<ContourOutput>,
    out: Vec<FileOutput>,
}

/// Runs `kappa glyph`.
pub fn run(args: &GlyphArgs) -> Result<ExitCode> {
    // Everything that can be checked before the work is checked first.
    let formats = args
        .out
        .iter()
        .map(|p| Format::of(p))
        .collect::<Result<Vec<_>>>()?;
    let scheme = args.scheme.scheme();
    let shape = parse_shape(args.shape.as_deref(), scheme)?;
    let data = std::fs::read(&args.font)
        .map_err(|e| Failure::new(format!("cannot read {}: {e}", args.font.display())))?;
    let font =
        FontOutlines::parse(&data).map_err(|e| Failure::new(e).context(args.font.display()))?;
    let glyph = font.glyph(args.ch).map_err(Failure::new)?;
    if glyph.path.elements().is_empty() {
        return Err(Failure::new(format!(
            "the glyph for {:?} has no outline to draft",
            args.ch
        )));
    }
    let upem = font.units_per_em();
    let mut options = DraftOptions::for_units_per_em(upem).with_scheme(scheme, shape.clone());
    if let Some(t) = args.tolerance {
        options.tolerance = t;
    }
    options.fair = args.fair;
    options.simplify = args.simplify;
    let drafted = draft(&glyph.path, &options).map_err(Failure::new)?;
    let font_glyph = FontGlyph {
        name: glyph_name(args.ch),
        ch: args.ch,
        path: drafted.path.clone(),
        advance: glyph.advance,
    };
    let mut files = Vec::with_capacity(args.out.len());
    for (path, &format) in args.out.iter().zip(&formats) {
        let mut out = FileOutput {
            file: path.display().to_string(),
            format,
            segments: None,
            exact: None,
            max_error: None,
        };
        match format {
            Format::Svg | Format::Png => {
                let placed = [PlacedGlyph {
                    original: &glyph.path,
                    drafted: &drafted,
                    offset: Vec2::ZERO,
                }];
                let scene = word_scene(&placed, upem, args.size, args.size, None);
                let (svg, png) = match format {
                    Format::Svg => (Some(path.as_path()), None),
                    _ => (None, Some(path.as_path())),
                };
                picture::write_pictures(&scene, svg, png)?;
            }
            Format::Glif => {
                let xml = to_glif(&font_glyph).map_err(Failure::new)?;
                failure::write_file(path, xml.as_bytes())?;
                out.segments = Some(Segments::of(&drafted.path));
                out.exact = Some(true);
                out.max_error = Some(0.0);
            }
            Format::Ttf => {
                let quads =
                    to_quadratic(&drafted.path, args.quad_tolerance).map_err(Failure::new)?;
                let em = u16::try_from(upem.round() as i64).map_err(|_| {
                    Failure::new(format!("units per em {upem} do not fit a TrueType font"))
                })?;
                let metric = |v: f64| v.round().clamp(i16::MIN.into(), i16::MAX.into()) as i16;
                let bytes = compile_font(
                    "",
                    em,
                    metric(font.ascender()),
                    metric(font.descender()),
                    &[FontGlyph {
                        path: quads.path.clone(),
                        ..font_glyph.clone()
                    }],
                )
                .map_err(Failure::new)?;
                failure::write_file(path, &bytes)?;
                out.segments = Some(Segments::of(&quads.path));
                out.exact = Some(quads.exact);
                out.max_error = Some(quads.max_error);
            }
        }
        files.push(out);
    }
    let out = output(args, &glyph, upem, &options, &shape, &drafted, files);
    let mut text =
        serde_json::to_string(&out).map_err(|e| Failure::new(format!("cannot write JSON: {e}")))?;
    text.push('\n');
    failure::print_stdout(&text)?;
    Ok(ExitCode::SUCCESS)
}

/// The `--shape` value: none (neutral), `auto`, or a number; only for the εκ schemes (the
/// range is checked by the drafting, as [`kappa::Error::ShapeOutOfRange`]).
pub(crate) fn parse_shape(shape: Option<&str>, scheme: Scheme) -> Result<DraftShape> {
    let Some(text) = shape else {
        return Ok(DraftShape::Neutral);
    };
    if scheme == Scheme::Kappa {
        return Err(Failure::new(
            "--shape applies to the ek-cubic and ek-trig schemes only (κ-curves have none)",
        ));
    }
    if text.eq_ignore_ascii_case("auto") {
        return Ok(DraftShape::Auto);
    }
    text.trim()
        .parse::<f64>()
        .map(DraftShape::Global)
        .map_err(|_| Failure::new(format!("--shape is '{text}', expected a number or 'auto'")))
}

/// The glyph name: the character itself for ASCII letters and digits, else `uniXXXX` (the
/// Adobe Glyph List convention for names without a better one).
fn glyph_name(ch: char) -> String {
    if ch.is_ascii_alphanumeric() {
        ch.to_string()
    } else if (ch as u32) <= 0xFFFF {
        format!("uni{:04X}", ch as u32)
    } else {
        format!("u{:05X}", ch as u32)
    }
}

fn kind_name(kind: AnchorKind) -> &'static str {
    match kind {
        AnchorKind::Corner => "corner",
        AnchorKind::Extremum => "extremum",
        AnchorKind::Peak => "peak",
        AnchorKind::Refined => "refined",
        AnchorKind::User => "user",
    }
}

/// The JSON object of a draft.
fn output(
    args: &GlyphArgs,
    glyph: &kappa::glyph::Glyph,
    upem: f64,
    options: &DraftOptions,
    shape: &DraftShape,
    drafted: &DraftedGlyph,
    out: Vec<FileOutput>,
) -> GlyphOutput {
    let contour_outputs = drafted
        .contours
        .iter()
        .map(|c| {
            // Distinct anchors: consecutive open pieces share their ends.
            let mut anchors: Vec<&kappa::glyph::Anchor> = Vec::new();
            match c.pieces.as_slice() {
                [p] if p.closed => anchors.extend(p.anchors.iter()),
                pieces => {
                    for p in pieces {
                        anchors.extend(p.anchors.iter().take(p.anchors.len().saturating_sub(1)));
                    }
                }
            }
            ContourOutput {
                closed: matches!(c.path.elements().last(), Some(PathEl::ClosePath)),
                anchors: anchors
                    .into_iter()
                    .map(|a| AnchorOutput {
                        point: [a.point.x, a.point.y],
                        kind: kind_name(a.kind),
                        a: a.a,
                    })
                    .collect(),
                pieces: c.pieces.len(),
                hausdorff: c
                    .pieces
                    .iter()
                    .filter_map(|p| p.hausdorff)
                    .fold(0.0, f64::max),
                segments: Segments::of(&c.path),
            }
        })
        .collect();
    let all = contours(&glyph.path)
        .iter()
        .map(|(segs, closed)| segs.len() + usize::from(!closed))
        .sum();
    GlyphOutput {
        ch: args.ch.to_string(),
        glyph_id: glyph.id,
        units_per_em: upem,
        scheme: args.scheme,
        shape: match shape {
            DraftShape::Neutral => ShapeOutput::Name("neutral"),
            DraftShape::Auto => ShapeOutput::Name("auto"),
            DraftShape::Global(a) => ShapeOutput::Value(*a),
        },
        tolerance: options.tolerance,
        hausdorff: drafted.hausdorff.unwrap_or(0.0),
        within_tolerance: drafted.within_tolerance(),
        fallback: drafted.fallback_count(),
        anchor_count: drafted.anchor_count(),
        on_curve: OnCurve {
            explicit: drafted.original_on_curve(),
            all,
        },
        segments: Segments::of(&drafted.path),
        contours: contour_outputs,
        out,
    }
}
