//! `kappa gallery`: render the gallery (the figures of the README and docs/).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use kappa::gallery::{
    design_scene, paper_scenes, variant_figure, FIGURE_GAP, PAPER_VARIANTS, TRIG_VARIANTS,
};
use kappa::glyph::{word_figure, DraftOptions, DraftShape, FontOutlines, FIGURE_WORD};
use kappa::render::{hstack, Pixmap};
use kappa::space::{views_figure, View};
use kappa::{BSpline, BSpline3, Point3, Scheme, SpaceCurve, SpaceOptions, Vec3};
use kurbo::Point;

use crate::builtin::{self, DESIGNER_DRAWING, PAPER_DRAWINGS};
use crate::failure::{self, Failure, Result};

/// The drawings shown with all four variants.
const FIGURE_DRAWINGS: [&str; 4] = ["bear", "elephant", "bird", DESIGNER_DRAWING];
/// The drawings shown in the layout of the paper's Fig. 11 (κ, εκ-cubic, εκ-trig).
const TRIG_DRAWINGS: [&str; 2] = ["eps-ClosedEkcurveKTM1", "rose"];
/// Side of each panel of the Fig. 11 layout, in pixels.
const TRIG_PANEL: u32 = 300;
/// Side of each panel of the paper figures, in pixels.
const FIGURE_PANEL: u32 = 360;
/// Side of each panel of the overview of all drawings, in pixels.
const OVERVIEW_PANEL: u32 = 300;
/// Side of each panel of the κ-space curve figures (four views side by side), in pixels.
const SPACE_PANEL: u32 = 300;
/// Side of each panel of the intrinsic-curve figures, in pixels.
const INTRINSIC_PANEL: u32 = 260;
/// Samples per axis of the viable-region figure.
const VIABLE_SAMPLES: usize = 61;
/// Panels per row of the overview.
const OVERVIEW_COLUMNS: usize = 3;
/// Size in pixels of the glyph figure (the golden image `tests/golden/glyph-sample.png`).
const GLYPH_FIGURE_SIZE: (u32, u32) = (1200, 1000);
/// The vendored font of the glyph figure (DejaVu Sans, Bitstream Vera licence:
/// `tests/fonts/DejaVuSans-LICENSE.txt`).
const GLYPH_FONT: &[u8] = include_bytes!("../../../tests/fonts/DejaVuSans.ttf");
/// A cubic (CFF) font for the second glyph figure (EB Garamond 12, a Latin-1 subset; OFL).
const CUBIC_FONT: &[u8] = include_bytes!("../../../tests/fonts/EBGaramond12-Regular-subset.otf");

/// Render the gallery (PNG figures and SVG panels).
#[derive(Debug, Args)]
#[command(
    long_about = "Render the gallery into DIR (created if needed):\n  \
        <name>.png          bear, elephant, bird and designer (a wave and a symmetric S \
        with inflections through points, a curl on whole pixels, straight runs) as a \
        κ-curve and as εκ-curves with \
        a = 0.75, 0.85, 0.95 side by side\n  \
        <name>-<variant>.svg  one SVG per panel (variants kappa, ek-0.75, ek-0.85, ek-0.95)\n  \
        <name>-trig.png     eps-ClosedEkcurveKTM1 and rose as in the paper's Fig. 11: κ, \
        εκ-cubic with a = 0.75, 0.9 and εκ-trig with a = 0.55, 0.6, 0.75, 0.9\n  \
        drawings.png        all nine drawings of the εκ paper as κ-curves, in a 3 × 3 grid\n  \
        intrinsic-variety.png  one G1 problem met by six curvature profiles (intrinsic curves)\n  \
        intrinsic-viable.png   end curvatures admitting a monotone G2 segment, degrees 3, 5, 10\n  \
        space-helix.png, space-trefoil.png  κ-space curves from the top, front, side and \
        isometrically\n  \
        bsplines.png        uniform cubic B-splines of the B-spline paper (T4, and the trefoil \
        E3 in an orthographic view) with their maximum curvature marked\n  \
        glyph-sample.png    \"Sample\" in DejaVu Sans: the original outlines with their \
        curvature combs and on-curve points (implied ones hollow), then drafted as \
        κ-curves and as auto-shaped εκ-cubic curves with combs and anchors\n\
        Prints the files written, one per line.",
    after_help = "Examples:\n  kappa gallery\n  kappa gallery --out docs/gallery"
)]
pub struct GalleryArgs {
    /// Output directory.
    #[arg(long, value_name = "DIR", default_value = "gallery")]
    out: PathBuf,
}

/// Runs `kappa gallery`.
pub fn run(args: &GalleryArgs) -> Result<ExitCode> {
    let dir = &args.out;
    std::fs::create_dir_all(dir)
        .map_err(|e| Failure::new(format!("cannot create {}: {e}", dir.display())))?;
    for name in FIGURE_DRAWINGS {
        let design = builtin::load(name)?;
        let scenes = paper_scenes(&design, FIGURE_PANEL)
            .map_err(|e| Failure::new(format!("{name}: {e}")))?;
        let mut images = Vec::with_capacity(scenes.len());
        for ((scheme, a), scene) in PAPER_VARIANTS.into_iter().zip(&scenes) {
            let svg = scene
                .to_svg()
                .map_err(|e| Failure::new(format!("{name}: {e}")))?;
            let path = dir.join(format!("{name}-{}.svg", variant_name(scheme, a)));
            failure::write_file(&path, svg.as_bytes())?;
            announce(&path)?;
            images.push(
                scene
                    .render()
                    .map_err(|e| Failure::new(format!("{name}: {e}")))?,
            );
        }
        // The same picture as `kappa::gallery::paper_figure`, from the scenes drawn above.
        let figure =
            hstack(&images, FIGURE_GAP).map_err(|e| Failure::new(format!("{name}: {e}")))?;
        write_png(&dir.join(format!("{name}.png")), &figure)?;
    }
    for name in TRIG_DRAWINGS {
        let design = builtin::load(name)?;
        let figure = variant_figure(&design, &TRIG_VARIANTS, TRIG_PANEL)
            .map_err(|e| Failure::new(format!("{name}: {e}")))?;
        write_png(&dir.join(format!("{name}-trig.png")), &figure)?;
    }
    let mut rows = Vec::new();
    for names in PAPER_DRAWINGS.chunks(OVERVIEW_COLUMNS) {
        let mut panels = Vec::with_capacity(names.len());
        for name in names {
            let design = builtin::load(name)?;
            let scene = design_scene(
                &design,
                Scheme::Kappa,
                2.0 / 3.0,
                OVERVIEW_PANEL,
                OVERVIEW_PANEL,
                None,
            )
            .map_err(|e| Failure::new(format!("{name}: {e}")))?
            .with_title(name);
            panels.push(
                scene
                    .render()
                    .map_err(|e| Failure::new(format!("{name}: {e}")))?,
            );
        }
        rows.push(hstack(&panels, FIGURE_GAP).map_err(Failure::new)?);
    }
    write_png(&dir.join("drawings.png"), &vstack(&rows, FIGURE_GAP)?)?;
    for (name, points, closed) in space_inputs() {
        let curve = SpaceCurve::new(&points, closed, &SpaceOptions::default())
            .map_err(|e| Failure::new(format!("{name}: {e}")))?;
        let figure =
            views_figure(&curve, SPACE_PANEL).map_err(|e| Failure::new(format!("{name}: {e}")))?;
        write_png(&dir.join(format!("{name}.png")), &figure)?;
    }
    let variety =
        kappa::intrinsic::picture::variety_figure(INTRINSIC_PANEL).map_err(Failure::new)?;
    write_png(&dir.join("intrinsic-variety.png"), &variety)?;
    let viable = kappa::intrinsic::picture::viable_figure(INTRINSIC_PANEL, VIABLE_SAMPLES)
        .map_err(Failure::new)?;
    write_png(&dir.join("intrinsic-viable.png"), &viable)?;
    write_png(&dir.join("bsplines.png"), &bsplines()?)?;
    write_png(&dir.join("glyph-sample.png"), &glyph_figure(GLYPH_FONT)?)?;
    write_png(&dir.join("glyph-garamond.png"), &glyph_figure(CUBIC_FONT)?)?;
    Ok(ExitCode::SUCCESS)
}

/// "Sample" from a vendored font: original, κ draft, auto-shaped εκ-cubic draft.
fn glyph_figure(data: &[u8]) -> Result<Pixmap> {
    let font = FontOutlines::parse(data).map_err(Failure::new)?;
    let kappa = DraftOptions::for_units_per_em(font.units_per_em());
    let ek = kappa.clone().with_scheme(Scheme::EkCubic, DraftShape::Auto);
    let (width, height) = GLYPH_FIGURE_SIZE;
    word_figure(&font, FIGURE_WORD, &[kappa, ek], width, height)
        .map_err(|e| Failure::new(format!("glyph figure: {e}")))?
        .render()
        .map_err(|e| Failure::new(format!("glyph figure: {e}")))
}

/// The B-spline paper's (seed 002 §4) symmetric closed curve T4.
const BSPLINE_T4: [(f64, f64); 9] = [
    (1.0, 4.0),
    (0.6, 2.0),
    (2.0, 0.4),
    (3.4, 1.0),
    (2.6, 2.8),
    (2.2, 2.4),
    (4.0, 1.6),
    (4.6, 3.0),
    (3.0, 4.4),
];

/// The parameters at which the paper's E3 samples its trefoil knot.
const BSPLINE_E3_T: [f64; 11] = [0.0, 0.4, 1.0, 1.5, 2.0, 2.5, 3.2, 3.9, 4.5, 5.1, 5.8];

/// T4 and the trefoil E3 as periodic B-splines, side by side, maxima marked; E3 seen from
/// azimuth −60°, elevation 55° (as its golden image).
fn bsplines() -> Result<Pixmap> {
    let t4: Vec<Point> = BSPLINE_T4.iter().map(|&p| p.into()).collect();
    let e3: Vec<Point3> = BSPLINE_E3_T
        .iter()
        .map(|&t: &f64| {
            let r = 1.0 + 0.3 * (3.0 * t).cos();
            Point3::new(
                r * (2.0 * t).cos(),
                r * (2.0 * t).sin(),
                0.35 * (3.0 * t).sin(),
            )
        })
        .collect();
    let (a, e) = ((-60f64).to_radians(), 55f64.to_radians());
    let toward = Vec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin());
    let view = View::looking(-toward, Vec3::new(0.0, 0.0, 1.0)).map_err(Failure::new)?;
    let scenes = [
        BSpline::periodic(&t4)
            .map_err(Failure::new)?
            .scene(FIGURE_PANEL, FIGURE_PANEL)
            .with_title("T4, closed"),
        BSpline3::periodic(&e3)
            .map_err(Failure::new)?
            .scene(view, FIGURE_PANEL, FIGURE_PANEL)
            .with_title("E3 trefoil, closed"),
    ];
    let images = scenes
        .iter()
        .map(|s| s.render().map_err(Failure::new))
        .collect::<Result<Vec<_>>>()?;
    hstack(&images, FIGURE_GAP).map_err(Failure::new)
}

/// The κ-space curves of the gallery: points on a helix (open) and on a trefoil knot
/// (closed), the inputs of the golden images `tests/golden/space-*.png`.
fn space_inputs() -> [(&'static str, Vec<Point3>, bool); 2] {
    let helix = (0..10)
        .map(|i| {
            let th = 0.9 * i as f64;
            Point3::new(50.0 * th.cos(), 50.0 * th.sin(), 12.0 * th)
        })
        .collect();
    let trefoil = (0..12)
        .map(|i| {
            let t = i as f64 / 12.0 * std::f64::consts::TAU;
            Point3::new(
                30.0 * (t.sin() + 2.0 * (2.0 * t).sin()),
                30.0 * (t.cos() - 2.0 * (2.0 * t).cos()),
                -30.0 * (3.0 * t).sin(),
            )
        })
        .collect();
    [
        ("space-helix", helix, false),
        ("space-trefoil", trefoil, true),
    ]
}

/// The file-name tag of a variant: `kappa` or `ek-<a>`.
fn variant_name(scheme: Scheme, a: f64) -> String {
    match scheme {
        Scheme::Kappa => "kappa".to_owned(),
        Scheme::EkCubic => format!("ek-{a}"),
        Scheme::EkTrig => format!("ek-trig-{a}"),
    }
}

/// Opaque images one above the other, left-aligned, with `gap` white rows between them (the
/// library only stacks horizontally).
fn vstack(images: &[Pixmap], gap: u32) -> Result<Pixmap> {
    let width = images.iter().map(Pixmap::width).max().unwrap_or(0);
    let gaps = gap.saturating_mul(images.len().saturating_sub(1) as u32);
    let height = images
        .iter()
        .map(Pixmap::height)
        .fold(gaps, u32::saturating_add);
    let mut out = Pixmap::new(width, height)
        .ok_or_else(|| Failure::new(format!("cannot make a {width}x{height} image")))?;
    out.fill(resvg::tiny_skia::Color::WHITE);
    let row_bytes = 4 * width as usize;
    let mut y0 = 0usize;
    for image in images {
        let src_row = 4 * image.width() as usize;
        let data = out.data_mut();
        for (y, row) in image.data().chunks_exact(src_row).enumerate() {
            let start = (y0 + y) * row_bytes;
            data[start..start + src_row].copy_from_slice(row);
        }
        y0 += image.height() as usize + gap as usize;
    }
    Ok(out)
}

fn write_png(path: &Path, image: &Pixmap) -> Result<()> {
    let png = image
        .encode_png()
        .map_err(|e| Failure::new(format!("cannot encode {}: {e}", path.display())))?;
    failure::write_file(path, &png)?;
    announce(path)
}

/// Prints the path of a file written.
fn announce(path: &Path) -> Result<()> {
    failure::print_stdout(&format!("{}\n", path.display()))
}
