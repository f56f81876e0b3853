//! `kappa font`: draft the glyphs of a whole font as κ/εκ contours and write the font
//! back as TrueType and/or UFO, with a JSON report.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::Args;
use kappa::glyph::{
    anchor_outline, draft, drawn_glyph_ids, rebuild_ttf, rebuild_ufo, DraftOptions, DraftShape,
    DraftedGlyph, FontOutlines, NodeOutline, RebuildOptions,
};
use kappa::Scheme;
use kurbo::BezPath;
use serde::Serialize;

use crate::curve::SchemeName;
use crate::failure::{self, Failure, Result};
use crate::glyph::parse_shape;

/// How closely the written outline, with the anchors as nodes, follows the draft (em).
const NODE_ACCURACY: f64 = 1e-4;

/// Draft the glyphs of a whole font and write it back as TrueType and/or UFO.
#[derive(Debug, Args)]
#[command(
    long_about = "Draft the glyphs of a TrueType/OpenType font (TrueType or CFF outlines) as κ- \
        or εκ-curves, as `kappa glyph` drafts one, and write the whole font back: every other \
        glyph as the source has it (composites stay composites), the glyph names, character \
        map, advance widths and vertical metrics kept.\n\n\
        Output files, by extension (--out may be given several times):\n  \
        .ttf  TrueType: quadratics on the integer grid (cubic drafts converted within \
        --quad-tolerance), outer contours clockwise; head, hhea, maxp, OS/2 (version 4), \
        name, post (format 2) recomputed, layout tables kept\n  \
        .ufo  a UFO 3 source: the drafted outlines exactly, as cubics (κ quadratics raised \
        to the cubics that trace them), outer contours counter-clockwise; each drafted glyph keeps its κ source in \
        its lib under org.kappa.contours (a JSON list of path-tool documents)\n\n\
        The written on-curve points are the anchors: each span between two anchors is one \
        cubic, fitted where it is not one Bézier already ('nodes_error' in the report), and \
        the tangent at an anchor on an extremum of the original is set horizontal or \
        vertical where that keeps the curve within the tolerance ('snapped'); a curve that \
        passes a horizontal or vertical extremum between two nodes gets a node there.\n\n\
        The new font's family is --family (default \"Kappa Draft\"): a modified font may not \
        use its source's Reserved Font Names.\n\n\
        Output (stdout), one JSON object on one line: {\"font\": file, \"units_per_em\": u, \
        \"scheme\": ..., \"tolerance\": t, \"draft_tolerance\": d, \"glyphs\": [{\"name\", \"char\", \"glyph_id\", \
        \"hausdorff\", \"within_tolerance\", \"anchors\", \"fallback\", \"nodes_error\", \"snapped\", \"written_hausdorff\", \"seconds\"}, ...], \"drafted\": n, \
        \"within_tolerance\": n, \"fallback_glyphs\": n, \"seconds\": s, \"out\": [{\"file\", \
        \"format\"}]}. 'char' is null for a glyph no character maps to. The drafts are held to \
        'draft_tolerance': --tolerance, less --quad-tolerance and half a grid diagonal when a \
        .ttf is written (its quadratics and integer grid must stay within --tolerance too; \
        at most half of it), else less 5 % (for the written outline's fits); \
        'within_tolerance' and 'hausdorff' are the draft's, \
        'written_hausdorff' that of the written outline before the grid.\n\n\
        On any error (unreadable font, a character the font lacks, unknown extension, bad \
        option) the exit code is 2, stderr holds one 'kappa: error:' line and stdout stays \
        empty.",
    after_help = "Examples:\n  \
        kappa font --font DejaVuSans.ttf --chars abc --out draft.ttf --out draft.ufo\n  \
        kappa font --font EBGaramond.otf --scheme ek-cubic --family \"My Draft\" --out draft.ufo"
)]
pub struct FontArgs {
    /// The TrueType/OpenType font file (the first face of a collection).
    #[arg(long, value_name = "FILE")]
    font: PathBuf,
    /// Draft the glyphs of these characters [default: every glyph with contours].
    #[arg(long, value_name = "STRING")]
    chars: Option<String>,
    /// The curve scheme.
    #[arg(long, value_enum, value_name = "SCHEME", default_value = "kappa")]
    scheme: SchemeName,
    /// The εκ shape parameter: a number, or "auto" (as for `kappa glyph`).
    #[arg(long, value_name = "A|auto", allow_negative_numbers = true)]
    shape: Option<String>,
    /// Largest distance of a draft from its glyph, in font units [default: 0.004 em].
    #[arg(long, value_name = "UNITS", allow_negative_numbers = true)]
    tolerance: Option<f64>,
    /// Largest distance of the TrueType quadratics from cubic drafts, in font units.
    #[arg(
        long,
        value_name = "UNITS",
        default_value_t = 0.5,
        allow_negative_numbers = true
    )]
    quad_tolerance: f64,
    /// Do not hold the original's axis as the tangent at extremum nodes, nor its direction
    /// at the ends of pieces, in the solve (by default they are held: G2 there, the node no
    /// longer a curvature peak; the UFO's κ sources record them).
    #[arg(long)]
    no_extremum_tangents: bool,
    /// The family name of the written font.
    #[arg(long, value_name = "NAME", default_value = "")]
    family: String,
    /// Write the font to FILE (.ttf or .ufo); may be repeated.
    #[arg(long, value_name = "FILE", required = true)]
    out: Vec<PathBuf>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
enum Format {
    Ttf,
    Ufo,
}

impl Format {
    fn of(path: &Path) -> Result<Format> {
        match failure::extension(path).as_deref() {
            Some("ttf") => Ok(Format::Ttf),
            Some("ufo") => Ok(Format::Ufo),
            _ => Err(Failure::new(format!(
                "cannot tell the format of {}: expected the extension .ttf or .ufo",
                path.display()
            ))),
        }
    }
}

#[derive(Debug, Serialize)]
struct GlyphReport {
    name: String,
    #[serde(rename = "char")]
    ch: Option<String>,
    glyph_id: u16,
    hausdorff: f64,
    within_tolerance: bool,
    anchors: usize,
    fallback: bool,
    /// Largest distance of the written outline (anchors as nodes) from the draft.
    nodes_error: f64,
    /// Extremum anchors whose tangent was set horizontal or vertical.
    snapped: usize,
    /// The Hausdorff distance of the written outline (before the TrueType grid) to the glyph.
    written_hausdorff: f64,
    /// The time this glyph took (draft and written outline).
    seconds: f64,
}

#[derive(Debug, Serialize)]
struct FileReport {
    file: String,
    format: Format,
}

#[derive(Debug, Serialize)]
struct Report {
    font: String,
    units_per_em: f64,
    scheme: SchemeName,
    tolerance: f64,
    draft_tolerance: f64,
    glyphs: Vec<GlyphReport>,
    drafted: usize,
    within_tolerance: usize,
    fallback_glyphs: usize,
    seconds: f64,
    out: Vec<FileReport>,
}

/// Runs `kappa font`.
pub fn run(args: &FontArgs) -> Result<ExitCode> {
    let start = Instant::now();
    let formats = args
        .out
        .iter()
        .map(|p| Format::of(p))
        .collect::<Result<Vec<_>>>()?;
    if !(args.quad_tolerance.is_finite() && args.quad_tolerance > 0.0) {
        return Err(Failure::new("--quad-tolerance must be a positive number"));
    }
    let scheme = args.scheme.scheme();
    let shape = parse_shape(args.shape.as_deref(), scheme)?;
    // Checked here: a shape out of range would otherwise fail every glyph's draft.
    if let DraftShape::Global(a) = shape {
        let (min, max) = scheme.shape_range();
        if !(a >= min && a < max) {
            return Err(Failure::new(format!(
                "--shape {a} is outside [{min}, {max}) for this scheme"
            )));
        }
    }
    let data = std::fs::read(&args.font)
        .map_err(|e| Failure::new(format!("cannot read {}: {e}", args.font.display())))?;
    let font =
        FontOutlines::parse(&data).map_err(|e| Failure::new(e).context(args.font.display()))?;
    let upem = font.units_per_em();
    let mut options = DraftOptions::for_units_per_em(upem).with_scheme(scheme, shape);
    options.extremum_tangents = !args.no_extremum_tangents;
    if let Some(t) = args.tolerance {
        if !(t.is_finite() && t > 0.0) {
            return Err(Failure::new("--tolerance must be a positive number"));
        }
        options.tolerance = t;
    }
    // The written fonts are held to the tolerance: the drafts leave room for the written
    // outline's fits and for the sampling of their own measure (`WRITTEN_HEADROOM`), and a
    // TrueType font also converts cubics to quadratics and rounds every point to the grid.
    let tolerance = options.tolerance;
    let headroom = if formats.contains(&Format::Ttf) {
        args.quad_tolerance + 0.5 * core::f64::consts::SQRT_2
    } else {
        kappa::glyph::WRITTEN_HEADROOM * tolerance
    };
    options.tolerance = (tolerance - headroom).max(0.5 * tolerance);
    let chars = font.char_map();
    let drawn = drawn_glyph_ids(&data).map_err(|e| Failure::new(e).context(args.font.display()))?;
    let ids: Vec<u16> = match &args.chars {
        None => drawn,
        Some(text) => {
            let mut ids = Vec::new();
            for ch in text.chars() {
                let id = font
                    .glyph_id(ch)
                    .ok_or_else(|| Failure::new(format!("the font has no glyph for {ch:?}")))?;
                // A composite follows its components: draft those.
                if drawn.binary_search(&id).is_ok() && !ids.contains(&id) {
                    ids.push(id);
                }
            }
            ids
        }
    };
    let names: Vec<String> = (0..font.glyph_count())
        .map(|id| {
            font.glyph_name(id)
                .map_or_else(|| format!("glyph{id:05}"), str::to_owned)
        })
        .collect();
    let mut replaced: HashMap<u16, BezPath> = HashMap::new();
    let mut sources: HashMap<u16, String> = HashMap::new();
    let mut glyphs = Vec::with_capacity(ids.len());
    // The drafts, on every core (each glyph on its own).
    type Drafted = (Option<(DraftedGlyph, NodeOutline, f64)>, f64);
    let drafts = map_glyphs(&ids, |id| -> Result<Drafted> {
        let start = Instant::now();
        let outline = font.outline(id).map_err(Failure::new)?;
        let drafted = draft(&outline, &options).ok().map(|d| {
            let nodes = anchor_outline(&d, &outline, NODE_ACCURACY * upem, options.tolerance);
            let written = nodes.hausdorff;
            (d, nodes, written)
        });
        Ok((drafted, start.elapsed().as_secs_f64()))
    });
    for (&id, drafted) in ids.iter().zip(drafts) {
        let (drafted, seconds) = drafted?;
        let d = drafted.as_ref().map(|(d, _, _)| d);
        let mut report = GlyphReport {
            name: names[usize::from(id)].clone(),
            ch: chars
                .get(&id)
                .and_then(|c| c.first())
                .map(|c| c.to_string()),
            glyph_id: id,
            hausdorff: d.and_then(|d| d.hausdorff).unwrap_or(0.0),
            within_tolerance: d.is_some_and(DraftedGlyph::within_tolerance),
            anchors: d.map_or(0, DraftedGlyph::anchor_count),
            // A glyph that could not be drafted is kept as the source has it, flagged.
            fallback: d.map_or(true, |d| d.fallback_count() > 0),
            nodes_error: 0.0,
            snapped: 0,
            written_hausdorff: 0.0,
            seconds,
        };
        if let Some((d, nodes, written)) = drafted {
            report.nodes_error = nodes.max_error;
            report.snapped = nodes.snapped;
            report.written_hausdorff = written;
            if formats.contains(&Format::Ufo) {
                sources.insert(id, kappa_source(&d, scheme)?);
            }
            replaced.insert(id, nodes.path);
        }
        glyphs.push(report);
    }
    let timestamp = std::env::var("SOURCE_DATE_EPOCH")
        .ok()
        .and_then(|v| v.parse::<i64>().ok())
        .unwrap_or_else(|| {
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.as_secs() as i64)
        });
    let rebuild = RebuildOptions {
        family: args.family.clone(),
        quad_tolerance: args.quad_tolerance,
        timestamp,
    };
    let mut out = Vec::with_capacity(args.out.len());
    for (path, &format) in args.out.iter().zip(&formats) {
        match format {
            Format::Ttf => {
                let bytes = rebuild_ttf(&data, &replaced, &rebuild).map_err(Failure::new)?;
                failure::write_file(path, &bytes)?;
            }
            Format::Ufo => {
                rebuild_ufo(&data, &replaced, &sources, &rebuild, path).map_err(Failure::new)?;
            }
        }
        out.push(FileReport {
            file: path.display().to_string(),
            format,
        });
    }
    let report = Report {
        font: args.font.display().to_string(),
        units_per_em: upem,
        scheme: args.scheme,
        tolerance,
        draft_tolerance: options.tolerance,
        drafted: glyphs.len(),
        within_tolerance: glyphs.iter().filter(|g| g.within_tolerance).count(),
        fallback_glyphs: glyphs.iter().filter(|g| g.fallback).count(),
        glyphs,
        seconds: start.elapsed().as_secs_f64(),
        out,
    };
    let mut text = serde_json::to_string(&report)
        .map_err(|e| Failure::new(format!("cannot write JSON: {e}")))?;
    text.push('\n');
    failure::print_stdout(&text)?;
    Ok(ExitCode::SUCCESS)
}

/// `f` of every glyph id, in order: on rayon's pool with the `parallel` feature.
fn map_glyphs<T: Send>(ids: &[u16], f: impl Fn(u16) -> T + Sync) -> Vec<T> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        ids.par_iter().map(|&id| f(id)).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        ids.iter().map(|&id| f(id)).collect()
    }
}

/// The κ source of a drafted glyph ([`DraftedGlyph::path_docs`]), as JSON.
fn kappa_source(drafted: &DraftedGlyph, scheme: Scheme) -> Result<String> {
    serde_json::to_string(&drafted.path_docs(scheme))
        .map_err(|e| Failure::new(format!("cannot write JSON: {e}")))
}
