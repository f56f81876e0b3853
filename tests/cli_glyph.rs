//! Tests of `kappa glyph`: its JSON contract against the library's draft, every output format
//! written and read back (SVG parsed by usvg, PNG decoded, glif read by norad, TTF read by
//! ttf-parser), and its errors. They run the built binary.
#![cfg(feature = "cli")]

mod common;

use std::path::{Path, PathBuf};
use std::process::Output;

use kappa::glyph::{
    draft, from_glif, quantize, to_quadratic, DraftOptions, DraftShape, DraftedGlyph, FontOutlines,
};
use kappa::Scheme;
use kurbo::{ParamCurve, ParamCurveNearest, PathSeg, Point};
use serde_json::Value;

fn font_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fonts/DejaVuSans.ttf")
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("cli-glyph")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn kappa(args: &[&str]) -> Output {
    common::run_kappa(args, "")
}

/// Runs `kappa glyph` on the vendored font with `args` and parses stdout as JSON.
fn glyph_json(args: &[&str]) -> Value {
    let font = font_path();
    let mut all = vec!["glyph", "--font", font.to_str().unwrap()];
    all.extend_from_slice(args);
    let out = kappa(&all);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "kappa {all:?} failed: {err}");
    assert!(err.is_empty(), "{err}");
    serde_json::from_str(&String::from_utf8(out.stdout).unwrap()).expect("stdout is JSON")
}

/// The library's draft of `ch` with the same options as the CLI.
fn library_draft(
    ch: char,
    scheme: Scheme,
    shape: DraftShape,
) -> (kappa::glyph::Glyph, DraftedGlyph) {
    let data = std::fs::read(font_path()).unwrap();
    let font = FontOutlines::parse(&data).unwrap();
    let g = font.glyph(ch).unwrap();
    let options = DraftOptions::for_units_per_em(font.units_per_em()).with_scheme(scheme, shape);
    let d = draft(&g.path, &options).unwrap();
    (g, d)
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("{v} is not a number"))
}

fn n(v: &Value) -> usize {
    v.as_u64().unwrap_or_else(|| panic!("{v} is not a count")) as usize
}

/// Distance from `p` to the outline.
fn distance(path: &kurbo::BezPath, p: Point) -> f64 {
    path.segments()
        .map(|s: PathSeg| s.nearest(p, 1e-12).distance_sq)
        .fold(f64::INFINITY, f64::min)
        .sqrt()
}

/// Checks the JSON against the library's draft: the same anchors with their `a`, Hausdorff
/// distance and segment counts; anchors on the original outline.
fn check_against_library(v: &Value, ch: char, scheme: Scheme, shape: DraftShape) {
    let (g, d) = library_draft(ch, scheme, shape);
    assert_eq!(v["char"], Value::String(ch.to_string()));
    assert_eq!(f(&v["units_per_em"]), 2048.0);
    let tol = f(&v["tolerance"]);
    assert!((tol - 0.004 * 2048.0).abs() < 1e-12);
    let h = f(&v["hausdorff"]);
    assert!(h <= tol, "Hausdorff {h} above the tolerance {tol}");
    assert_eq!(h, d.hausdorff.unwrap());
    assert_eq!(v["within_tolerance"], Value::Bool(true));
    assert_eq!(n(&v["fallback"]), d.fallback_count());
    assert_eq!(n(&v["anchor_count"]), d.anchor_count());
    assert_eq!(n(&v["on_curve"]["explicit"]), d.original_on_curve());
    // With the implied points: one on-curve point per segment of a closed contour.
    assert_eq!(n(&v["on_curve"]["all"]), g.path.segments().count());
    let contours = v["contours"].as_array().unwrap();
    assert_eq!(contours.len(), d.contours.len());
    let mut listed = 0;
    let mut segs = [0usize; 3];
    for (c, dc) in contours.iter().zip(&d.contours) {
        assert_eq!(c["closed"], Value::Bool(true));
        assert_eq!(n(&c["pieces"]), dc.pieces.len());
        assert!(f(&c["hausdorff"]) <= h);
        let anchors = c["anchors"].as_array().unwrap();
        assert_eq!(anchors.len(), dc.anchor_count());
        listed += anchors.len();
        // The listed anchors are the pieces' anchors, shared ends once, in order.
        let lib: Vec<&kappa::glyph::Anchor> = dc
            .pieces
            .iter()
            .flat_map(|p| {
                let take = if p.closed {
                    p.anchors.len()
                } else {
                    p.anchors.len() - 1
                };
                p.anchors.iter().take(take)
            })
            .collect();
        for (a, la) in anchors.iter().zip(lib) {
            let p = a["point"].as_array().unwrap();
            let p = Point::new(f(&p[0]), f(&p[1]));
            assert_eq!(p, la.point);
            assert_eq!(f(&a["a"]), la.a);
            assert!(distance(&g.path, p) < 1e-6, "anchor {p:?} off the outline");
            let kind = a["kind"].as_str().unwrap();
            assert!(
                ["corner", "extremum", "peak", "refined"].contains(&kind),
                "{kind}"
            );
        }
        for (k, name) in ["line", "quad", "cubic"].iter().enumerate() {
            segs[k] += n(&c["segments"][name]);
        }
    }
    assert_eq!(listed, n(&v["anchor_count"]));
    for (k, name) in ["line", "quad", "cubic"].iter().enumerate() {
        assert_eq!(n(&v["segments"][name]), segs[k]);
    }
    assert_eq!(segs.iter().sum::<usize>(), d.segment_count());
}

#[test]
fn glyph_cli_kappa_all_formats() {
    let dir = scratch("kappa");
    let files: Vec<PathBuf> = ["S.svg", "S.png", "S.glif", "S.ttf"]
        .iter()
        .map(|f| dir.join(f))
        .collect();
    let mut args = vec!["--char", "S"];
    for file in &files {
        args.push("--out");
        args.push(file.to_str().unwrap());
    }
    let v = glyph_json(&args);
    let keys: Vec<&str> = v.as_object().unwrap().keys().map(|k| k.as_str()).collect();
    assert_eq!(
        keys,
        [
            "anchor_count",
            "char",
            "contours",
            "fallback",
            "glyph_id",
            "hausdorff",
            "on_curve",
            "out",
            "scheme",
            "segments",
            "shape",
            "tolerance",
            "units_per_em",
            "within_tolerance"
        ]
    );
    assert_eq!(v["scheme"], Value::String("kappa".into()));
    assert_eq!(v["shape"], Value::String("neutral".into()));
    check_against_library(&v, 'S', Scheme::Kappa, DraftShape::Neutral);
    // κ-curves are quadratics and lines only.
    assert_eq!(n(&v["segments"]["cubic"]), 0);
    let (g, d) = library_draft('S', Scheme::Kappa, DraftShape::Neutral);

    let out = v["out"].as_array().unwrap();
    assert_eq!(out.len(), 4);
    for (o, (file, format)) in out
        .iter()
        .zip(files.iter().zip(["svg", "png", "glif", "ttf"]))
    {
        assert_eq!(o["file"].as_str().unwrap(), file.to_str().unwrap());
        assert_eq!(o["format"].as_str().unwrap(), format);
    }
    // SVG: a document usvg reads.
    let svg = std::fs::read_to_string(&files[0]).unwrap();
    let tree = resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default()).unwrap();
    assert_eq!(tree.size().width(), 600.0);
    // PNG: decodes, at the default size, and is not blank.
    let png = kappa::render::golden::load_png(&files[1]).unwrap();
    assert_eq!((png.width(), png.height()), (600, 600));
    let dark = png
        .pixels()
        .iter()
        .filter(|p| p.red() < 64 && p.green() < 64 && p.blue() < 64)
        .count();
    assert!(dark > 1000, "only {dark} dark pixels");
    // glif: norad reads it, and its outline is the draft's.
    let xml = std::fs::read_to_string(&files[2]).unwrap();
    let glyph = norad::Glyph::parse_raw(xml.as_bytes()).unwrap();
    assert_eq!(glyph.name().as_str(), "S");
    assert_eq!(glyph.codepoints.iter().next(), Some('S'));
    assert_eq!(glyph.width, g.advance);
    assert_eq!(glyph.contours.len(), d.contours.len());
    let back = from_glif(&xml).unwrap();
    let (sa, sb): (Vec<PathSeg>, Vec<PathSeg>) =
        (d.path.segments().collect(), back.segments().collect());
    assert_eq!(sa.len(), sb.len());
    assert_eq!(o_segments(&out[2]), sa.len());
    for p in sa.iter().map(|s| s.start()) {
        assert!(distance(&back, p) < 1e-9);
    }
    assert_eq!(kurbo::Shape::area(&back), kurbo::Shape::area(&d.path));
    // TTF: ttf-parser reads it; the glyph is the draft on the integer grid, element for
    // element (exact for κ).
    assert_eq!(out[3]["exact"], Value::Bool(true));
    assert_eq!(f(&out[3]["max_error"]), 0.0);
    let bytes = std::fs::read(&files[3]).unwrap();
    let face = ttf_parser::Face::parse(&bytes, 0).unwrap();
    assert_eq!(face.units_per_em(), 2048);
    let font = FontOutlines::parse(&bytes).unwrap();
    let read = font.glyph('S').unwrap();
    assert_eq!(read.path.elements(), quantize(&d.path).elements());
    assert_eq!(read.advance, g.advance);
}

fn o_segments(o: &Value) -> usize {
    ["line", "quad", "cubic"]
        .iter()
        .map(|k| n(&o["segments"][k]))
        .sum()
}

/// εκ-cubic with the auto shape: the same draft as the library, per-point shapes reported;
/// the TTF holds the cubics converted to quadratics within --quad-tolerance.
#[test]
fn glyph_cli_ek_cubic_auto() {
    let dir = scratch("ek-cubic");
    let ttf = dir.join("a.ttf");
    let glif = dir.join("a.glif");
    let v = glyph_json(&[
        "--char",
        "a",
        "--scheme",
        "ek-cubic",
        "--shape",
        "auto",
        "--quad-tolerance",
        "0.25",
        "--out",
        ttf.to_str().unwrap(),
        "--out",
        glif.to_str().unwrap(),
    ]);
    assert_eq!(v["scheme"], Value::String("ek-cubic".into()));
    assert_eq!(v["shape"], Value::String("auto".into()));
    check_against_library(&v, 'a', Scheme::EkCubic, DraftShape::Auto);
    assert!(n(&v["segments"]["cubic"]) > 0);
    // Some anchor got a sharper shape than the κ-like 2/3.
    let sharper = v["contours"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|c| c["anchors"].as_array().unwrap())
        .filter(|a| f(&a["a"]) > 2.0 / 3.0 + 1e-6)
        .count();
    assert!(sharper > 0);
    let (_, d) = library_draft('a', Scheme::EkCubic, DraftShape::Auto);
    let quads = to_quadratic(&d.path, 0.25).unwrap();
    let out = &v["out"][0];
    assert_eq!(out["exact"], Value::Bool(false));
    assert_eq!(f(&out["max_error"]), quads.max_error);
    assert!(quads.max_error <= 0.25);
    assert_eq!(n(&out["segments"]["cubic"]), 0);
    let bytes = std::fs::read(&ttf).unwrap();
    let font = FontOutlines::parse(&bytes).unwrap();
    assert_eq!(
        font.glyph('a').unwrap().path.elements(),
        quantize(&quads.path).elements()
    );
    // The glif keeps the cubics exactly.
    let back = from_glif(&std::fs::read_to_string(&glif).unwrap()).unwrap();
    assert_eq!(v["out"][1]["exact"], Value::Bool(true));
    assert_eq!(
        back.segments()
            .filter(|s| matches!(s, PathSeg::Cubic(_)))
            .count(),
        n(&v["segments"]["cubic"])
    );
}

/// εκ-trig with one shape for every anchor: every interior anchor of a curved piece carries
/// it.
#[test]
fn glyph_cli_ek_trig_global_shape() {
    let v = glyph_json(&["--char", "e", "--scheme", "ek-trig", "--shape", "0.8"]);
    assert_eq!(v["shape"], Value::from(0.8));
    assert!(v["out"].as_array().unwrap().is_empty());
    check_against_library(&v, 'e', Scheme::EkTrig, DraftShape::Global(0.8));
    let shapes: Vec<f64> = v["contours"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|c| c["anchors"].as_array().unwrap())
        .map(|a| f(&a["a"]))
        .collect();
    assert!(shapes.contains(&0.8));
    assert!(shapes.iter().all(|&a| a == 0.8 || a == 2.0 / 3.0));
}

/// A looser tolerance is honoured and gives no more anchors; --simplify keeps the bound
/// with no more anchors.
#[test]
fn glyph_cli_tolerance_and_simplify() {
    let fine = glyph_json(&["--char", "o"]);
    let coarse = glyph_json(&["--char", "o", "--tolerance", "20"]);
    assert_eq!(f(&coarse["tolerance"]), 20.0);
    assert!(f(&coarse["hausdorff"]) <= 20.0);
    assert_eq!(coarse["within_tolerance"], Value::Bool(true));
    assert!(n(&coarse["anchor_count"]) <= n(&fine["anchor_count"]));
    let full = glyph_json(&["--char", "a"]);
    let simple = glyph_json(&["--char", "a", "--simplify"]);
    assert_eq!(simple["within_tolerance"], Value::Bool(true));
    assert!(f(&simple["hausdorff"]) <= f(&simple["tolerance"]));
    assert!(n(&simple["anchor_count"]) <= n(&full["anchor_count"]));
    let mut options = DraftOptions::for_units_per_em(2048.0);
    options.simplify = true;
    let data = std::fs::read(font_path()).unwrap();
    let font = FontOutlines::parse(&data).unwrap();
    let d = draft(&font.glyph('a').unwrap().path, &options).unwrap();
    assert_eq!(n(&simple["anchor_count"]), d.anchor_count());
    // --fair: the library's fair draft, anchor for anchor.
    let fair = glyph_json(&["--char", "p", "--fair"]);
    options.simplify = false;
    options.fair = true;
    let d = draft(&font.glyph('p').unwrap().path, &options).unwrap();
    assert_eq!(n(&fair["anchor_count"]), d.anchor_count());
    assert_eq!(f(&fair["hausdorff"]), d.hausdorff.unwrap());
    assert_eq!(fair["within_tolerance"], Value::Bool(true));
}

/// Runs a failing command: exit 2, one `kappa: error:` line, nothing on stdout.
fn fails(args: &[&str]) -> String {
    let out = kappa(args);
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(out.stdout.is_empty(), "{args:?}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("kappa: error: "), "{err}");
    err
}

#[test]
fn glyph_cli_errors() {
    let dir = scratch("errors");
    let font = font_path();
    let font = font.to_str().unwrap();
    let not_font = dir.join("not-a-font.ttf");
    std::fs::write(&not_font, "not a font").unwrap();
    let err = fails(&["glyph", "--font", not_font.to_str().unwrap(), "--char", "S"]);
    assert!(err.contains("cannot parse the font"), "{err}");
    let missing = dir.join("missing.ttf");
    let err = fails(&["glyph", "--font", missing.to_str().unwrap(), "--char", "S"]);
    assert!(err.contains("cannot read"), "{err}");
    let err = fails(&["glyph", "--font", font, "--char", "\u{E000}"]);
    assert!(err.contains("no glyph for"), "{err}");
    let err = fails(&["glyph", "--font", font, "--char", " "]);
    assert!(err.contains("no outline"), "{err}");
    // An unknown extension fails before anything is written.
    let pdf = dir.join("S.pdf");
    let svg = dir.join("S.svg");
    let err = fails(&[
        "glyph",
        "--font",
        font,
        "--char",
        "S",
        "--out",
        svg.to_str().unwrap(),
        "--out",
        pdf.to_str().unwrap(),
    ]);
    assert!(err.contains("S.pdf") && err.contains(".glif"), "{err}");
    assert!(!svg.exists() && !pdf.exists());
    let err = fails(&["glyph", "--font", font, "--char", "S", "--out", "noext"]);
    assert!(err.contains("cannot tell the format"), "{err}");
    let err = fails(&[
        "glyph", "--font", font, "--char", "S", "--scheme", "ek-cubic", "--shape", "1.5",
    ]);
    assert!(
        err.contains("shape parameter") && err.contains("outside"),
        "{err}"
    );
    let err = fails(&[
        "glyph", "--font", font, "--char", "S", "--scheme", "ek-trig", "--shape", "0.3",
    ]);
    assert!(err.contains("outside [0.5, 1)"), "{err}");
    let err = fails(&[
        "glyph", "--font", font, "--char", "S", "--scheme", "ek-cubic", "--shape", "sharp",
    ]);
    assert!(err.contains("expected a number or 'auto'"), "{err}");
    let err = fails(&["glyph", "--font", font, "--char", "S", "--shape", "0.8"]);
    assert!(err.contains("ek-cubic and ek-trig"), "{err}");
    for t in ["0", "-3", "NaN"] {
        let err = fails(&["glyph", "--font", font, "--char", "S", "--tolerance", t]);
        assert!(err.contains("tolerance"), "{t}: {err}");
    }
    let err = fails(&[
        "glyph",
        "--font",
        font,
        "--char",
        "S",
        "--quad-tolerance",
        "0",
        "--out",
        dir.join("q.ttf").to_str().unwrap(),
    ]);
    assert!(err.contains("quadratic tolerance"), "{err}");
    // Usage errors: two characters, no font.
    fails(&["glyph", "--font", font, "--char", "ab"]);
    fails(&["glyph", "--char", "S"]);
    // A directory that does not exist cannot be written.
    let err = fails(&[
        "glyph",
        "--font",
        font,
        "--char",
        "l",
        "--out",
        dir.join("no/such/dir/l.glif").to_str().unwrap(),
    ]);
    assert!(err.contains("cannot write"), "{err}");
}
