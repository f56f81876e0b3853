//! Tests of `kappa font`: a whole font drafted and written back as TrueType and UFO, read
//! back here (ttf-parser, norad) and left in `target/font-check/` for the external
//! validators that `.ci/run` runs on them (OpenType Sanitizer, fontTools, ufoLib2, fontmake:
//! `tests/check_fonts.py`).
#![cfg(feature = "cli")]

mod common;

use std::path::{Path, PathBuf};

use kappa::editor::{Editor, PathDoc};
use kappa::glyph::{hausdorff, FontOutlines, KAPPA_LIB_KEY};
use kurbo::{BezPath, PathEl, Shape};
use serde_json::Value;

fn dejavu() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fonts/DejaVuSans.ttf")
}

fn garamond() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fonts/EBGaramond12-Regular-subset.otf")
}

/// The directory the external validators check.
fn font_check() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/font-check");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `kappa font` and parses its report.
fn font(args: &[&str]) -> Value {
    let out = common::run_kappa(args, "");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Each closed contour of `path` with its signed area (kurbo: positive is counter-clockwise
/// with y up) and whether another contour encloses it an odd number of times (a counter).
fn contour_roles(path: &BezPath) -> Vec<(f64, bool)> {
    let mut subs: Vec<BezPath> = Vec::new();
    for el in path.elements() {
        if matches!(el, PathEl::MoveTo(_)) {
            subs.push(BezPath::new());
        }
        subs.last_mut().unwrap().push(*el);
    }
    subs.iter()
        .enumerate()
        .map(|(i, s)| {
            let probe = kurbo::ParamCurve::eval(&s.segments().next().unwrap(), 0.5);
            let depth = subs
                .iter()
                .enumerate()
                .filter(|&(j, o)| j != i && o.winding(probe) != 0)
                .count();
            (s.area(), depth % 2 == 1)
        })
        .collect()
}

#[test]
fn a_truetype_font_is_drafted_and_written_whole() {
    let dir = font_check();
    let (ttf, ufo) = (dir.join("dejavu-kappa.ttf"), dir.join("dejavu-kappa.ufo"));
    let chars = "aeoBS&@é";
    let src = dejavu();
    let report = font(&[
        "font",
        "--font",
        src.to_str().unwrap(),
        "--chars",
        chars,
        "--family",
        "Kappa Test",
        "--out",
        ttf.to_str().unwrap(),
        "--out",
        ufo.to_str().unwrap(),
    ]);
    let source_bytes = std::fs::read(&src).unwrap();
    let source = FontOutlines::parse(&source_bytes).unwrap();
    let tolerance = report["tolerance"].as_f64().unwrap();
    assert!((tolerance - 0.004 * 2048.0).abs() < 1e-9);
    // A TrueType font is written: the drafts leave room for its quadratics and grid.
    let draft_tolerance = report["draft_tolerance"].as_f64().unwrap();
    assert!((draft_tolerance - (tolerance - 0.5 - 0.5 * 2f64.sqrt())).abs() < 1e-9);
    // é is a composite in DejaVu Sans: its components (e and the accent) are drafted
    // instead, and it stays a composite.
    let glyphs = report["glyphs"].as_array().unwrap();
    let drafted: Vec<u16> = glyphs
        .iter()
        .map(|g| g["glyph_id"].as_u64().unwrap() as u16)
        .collect();
    assert_eq!(report["drafted"].as_u64().unwrap() as usize, glyphs.len());
    assert!(glyphs.len() >= 7, "{report}");
    for g in glyphs {
        assert!(g["within_tolerance"].as_bool().unwrap(), "{g}");
        assert!(!g["fallback"].as_bool().unwrap(), "{g}");
        assert!(g["anchors"].as_u64().unwrap() >= 4, "{g}");
        // The written outline too.
        assert!(g["written_hausdorff"].as_f64().unwrap() <= tolerance, "{g}");
        assert!(g["seconds"].as_f64().unwrap() >= 0.0, "{g}");
    }

    // The TrueType font: the same glyph set, names, character map and advances; drafted
    // glyphs within the tolerance (plus the quadratic conversion and the grid) of the source,
    // outer contours clockwise.
    let bytes = std::fs::read(&ttf).unwrap();
    let out = FontOutlines::parse(&bytes).unwrap();
    assert_eq!(out.glyph_count(), source.glyph_count());
    assert_eq!(out.char_map(), source.char_map());
    for id in 0..source.glyph_count() {
        assert_eq!(out.glyph_name(id), source.glyph_name(id), "glyph {id}");
        assert_eq!(out.advance(id), source.advance(id), "glyph {id}");
    }
    for &id in &drafted {
        let (a, b) = (out.outline(id).unwrap(), source.outline(id).unwrap());
        let d = hausdorff(&a, &b, 64);
        assert!(d <= tolerance + 0.5 + 1.0, "glyph {id}: {d}");
        for (area, counter) in contour_roles(&a) {
            assert!(
                (area < 0.0) != counter,
                "glyph {id}: area {area}, counter {counter}"
            );
        }
    }
    // Undrafted glyphs are the source's, point for point.
    for id in [36u16, 100, 300] {
        if !drafted.contains(&id) {
            assert_eq!(out.outline(id).unwrap(), source.outline(id).unwrap());
        }
    }

    // The UFO: every glyph in order, outer contours counter-clockwise, the κ source of each
    // drafted glyph in its lib, re-solved by the path tool to the drafted outline.
    let ufo_font = norad::Font::load(&ufo).unwrap();
    let layer = ufo_font.default_layer();
    assert_eq!(layer.len(), usize::from(source.glyph_count()));
    let order = ufo_font.lib["public.glyphOrder"].as_array().unwrap();
    assert_eq!(order.len(), usize::from(source.glyph_count()));
    assert_eq!(
        ufo_font.font_info.family_name.as_deref(),
        Some("Kappa Test")
    );
    assert_eq!(
        ufo_font.font_info.units_per_em.map(|u| u.as_f64()),
        Some(2048.0)
    );
    for &id in &drafted {
        let name = source.glyph_name(id).unwrap();
        let glyph = layer.get_glyph(name).unwrap();
        let mut path = BezPath::new();
        for c in &glyph.contours {
            path.extend(c.to_kurbo().unwrap().elements().iter().copied());
            path.close_path();
        }
        for (area, counter) in contour_roles(&path) {
            assert!(
                (area > 0.0) != counter,
                "{name}: area {area}, counter {counter}"
            );
        }
        let text = glyph.lib[KAPPA_LIB_KEY].as_string().unwrap();
        let docs: Vec<PathDoc> = serde_json::from_str(text).unwrap();
        assert_eq!(docs.len(), glyph.contours.len(), "{name}");
        let mut resolved = BezPath::new();
        for doc in docs {
            let (editor, change) = Editor::from_doc(doc);
            assert!(change.errors.is_empty(), "{name}: {:?}", change.errors);
            resolved.extend(editor.to_bezpath().elements().iter().copied());
        }
        // The written outline has the anchors as nodes: within its reported distance of
        // the draft, which the path tool re-solves.
        let g = glyphs.iter().find(|g| g["glyph_id"] == id).unwrap();
        let nodes_error = g["nodes_error"].as_f64().unwrap();
        assert!(nodes_error <= tolerance, "{name}: {nodes_error}");
        let d = hausdorff(&resolved, &path, 64);
        assert!(
            // (Both distances are sampled: 0.1 unit apart at most.)
            d <= nodes_error + 0.1,
            "{name}: re-solved source {d} from the written outline ({nodes_error})"
        );
        // Its on-curve points are the anchors (more where one cubic does not span two).
        let on_curve = glyph
            .contours
            .iter()
            .flat_map(|c| c.points.iter())
            .filter(|p| p.typ != norad::PointType::OffCurve)
            .count();
        let anchors = g["anchors"].as_u64().unwrap() as usize;
        assert!(
            on_curve >= anchors && on_curve <= anchors + anchors / 4,
            "{name}: {on_curve} nodes, {anchors} anchors"
        );
    }
}

#[test]
fn font_errors_are_one_line() {
    let src = dejavu();
    let dir = font_check();
    let ttf = dir.join("never-written.ttf");
    for (args, what) in [
        (vec!["--chars", "a", "--out", "x.otf"], "format"),
        (
            vec!["--chars", "\u{10FFFD}", "--out", ttf.to_str().unwrap()],
            "no glyph",
        ),
        (
            vec!["--tolerance", "-1", "--out", ttf.to_str().unwrap()],
            "tolerance",
        ),
        (
            vec!["--quad-tolerance", "0", "--out", ttf.to_str().unwrap()],
            "quad-tolerance",
        ),
        (
            vec![
                "--scheme",
                "kappa",
                "--shape",
                "0.8",
                "--out",
                ttf.to_str().unwrap(),
            ],
            "shape",
        ),
        (
            vec![
                "--scheme",
                "ek-trig",
                "--shape",
                "0.3",
                "--out",
                ttf.to_str().unwrap(),
            ],
            "outside",
        ),
    ] {
        let mut all = vec!["font", "--font", src.to_str().unwrap()];
        all.extend(args);
        let out = common::run_kappa(&all, "");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{what}: {err}");
        assert!(out.stdout.is_empty(), "{what}");
        assert_eq!(err.trim_end().lines().count(), 1, "{what}: {err}");
        assert!(err.contains(what), "{what}: {err}");
    }
    let scratch = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli-font");
    std::fs::create_dir_all(&scratch).unwrap();
    let not_a_font = scratch.join("not-a-font.bin");
    std::fs::write(&not_a_font, b"not a font at all").unwrap();
    let out = common::run_kappa(
        &[
            "font",
            "--font",
            not_a_font.to_str().unwrap(),
            "--out",
            ttf.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(!ttf.exists());
}

#[test]
fn a_cff_font_becomes_truetype_and_ufo() {
    let dir = font_check();
    let (ttf, ufo) = (
        dir.join("garamond-kappa.ttf"),
        dir.join("garamond-kappa.ufo"),
    );
    let src = garamond();
    let report = font(&[
        "font",
        "--font",
        src.to_str().unwrap(),
        "--chars",
        "aoSg&",
        "--scheme",
        "ek-cubic",
        "--out",
        ttf.to_str().unwrap(),
        "--out",
        ufo.to_str().unwrap(),
    ]);
    assert_eq!(report["drafted"], 5, "{report}");
    let source_bytes = std::fs::read(&src).unwrap();
    let source = FontOutlines::parse(&source_bytes).unwrap();
    let bytes = std::fs::read(&ttf).unwrap();
    let out = FontOutlines::parse(&bytes).unwrap();
    assert_eq!(out.glyph_count(), source.glyph_count());
    assert_eq!(out.char_map(), source.char_map());
    let drafted: Vec<u16> = report["glyphs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|g| g["glyph_id"].as_u64().unwrap() as u16)
        .collect();
    // Every glyph is now TrueType: quadratics on the grid, outer contours clockwise; the
    // glyphs not drafted are the source's cubics within the conversion tolerance, the grid
    // and its smooth-node pass (0.5 + √2/2 + √2/2 units: a control point moved by up to √2
    // moves a quadratic by at most half that; measured, 1.52).
    for id in 0..source.glyph_count() {
        assert_eq!(out.glyph_name(id), source.glyph_name(id));
        assert_eq!(out.advance(id), source.advance(id));
        let a = out.outline(id).unwrap();
        assert!(a.segments().all(|s| !matches!(s, kurbo::PathSeg::Cubic(_))));
        for (area, counter) in contour_roles(&a) {
            assert!(
                (area < 0.0) != counter,
                "glyph {id}: area {area}, counter {counter}"
            );
        }
        if !drafted.contains(&id) && !a.elements().is_empty() {
            let d = hausdorff(&a, &source.outline(id).unwrap(), 64);
            assert!(d <= 0.5 + 2f64.sqrt(), "glyph {id}: {d}");
        }
    }
    let ufo_font = norad::Font::load(&ufo).unwrap();
    assert_eq!(
        ufo_font.default_layer().len(),
        usize::from(source.glyph_count())
    );
}

/// A UFO written alone (no TrueType headroom) holds every glyph it writes within the
/// tolerance, measured on the written outline: drafted at the full tolerance, with the
/// node outline's turns checked one way only, EB Garamond's `three` was written 4.27 units
/// from the source and its `h` 4.03 (tolerance 4).
#[test]
fn a_ufo_written_alone_stays_within_the_tolerance() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/cli-font-ufo");
    std::fs::create_dir_all(&dir).unwrap();
    let ufo = dir.join("garamond-h3.ufo");
    let src = garamond();
    let report = font(&[
        "font",
        "--font",
        src.to_str().unwrap(),
        "--chars",
        "h3",
        "--out",
        ufo.to_str().unwrap(),
    ]);
    let tolerance = report["tolerance"].as_f64().unwrap();
    assert!((tolerance - 4.0).abs() < 1e-9, "{report}");
    for g in report["glyphs"].as_array().unwrap() {
        let written = g["written_hausdorff"].as_f64().unwrap();
        assert!(written > 0.0 && written <= tolerance, "{g}");
    }
    assert_eq!(report["drafted"], 2, "{report}");
}

/// A source without an `OS/2` table (older Mac fonts) gets one made from `hhea`, the glyph
/// boxes and the `cmap`; the written font goes to the external validators like the others.
#[test]
fn a_source_without_os2_gets_one() {
    use write_fonts::read::{FontRef, TableProvider};
    use write_fonts::types::Tag;
    let data = std::fs::read(dejavu()).unwrap();
    let font = FontRef::new(&data).unwrap();
    let mut builder = write_fonts::FontBuilder::new();
    for record in font.table_directory.table_records() {
        if record.tag() != Tag::new(b"OS/2") {
            builder.add_raw(
                record.tag(),
                font.table_data(record.tag()).unwrap().as_bytes(),
            );
        }
    }
    let stripped = builder.build();
    assert!(FontRef::new(&stripped).unwrap().os2().is_err());
    let source = FontOutlines::parse(&stripped).unwrap();
    let mut replaced = std::collections::HashMap::new();
    let id = source.glyph_id('o').unwrap();
    let options = kappa::glyph::DraftOptions::for_units_per_em(2048.0);
    let drafted = kappa::glyph::draft(&source.outline(id).unwrap(), &options).unwrap();
    replaced.insert(id, drafted.path);
    let bytes = kappa::glyph::rebuild_ttf(
        &stripped,
        &replaced,
        &kappa::glyph::RebuildOptions::default(),
    )
    .unwrap();
    let out = FontRef::new(&bytes).unwrap();
    let os2 = out.os2().unwrap();
    assert!(os2.version() >= 4);
    let hhea = out.hhea().unwrap();
    assert_eq!(os2.s_typo_ascender(), hhea.ascender().to_i16());
    let first = source
        .char_map()
        .values()
        .flatten()
        .map(|&c| c as u32)
        .min()
        .unwrap();
    assert_eq!(u32::from(os2.us_first_char_index()), first);
    std::fs::write(font_check().join("no-os2-kappa.ttf"), &bytes).unwrap();
}

/// The alphabet the font-quality targets are measured on.
const ALPHABET: &str = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789&@ß";

/// A TrueType and a CFF font's alphabet drafted with the defaults and written both ways, for
/// the quality check `.ci/run` runs on them (`tests/check_font_quality.py`: extremum nodes,
/// missing extrema, short segments, fidelity, measured independently of kappa). Here: every
/// glyph drafted, none a fallback, and each written outline within 0.004 em of the source
/// by kappa's own report (`written_hausdorff`; a few Garamond drafts miss the tighter
/// tolerance they are held to for TrueType output, docs/glyphs.md).
#[test]
fn the_alphabet_is_drafted_for_the_quality_check() {
    let dir = font_check().join("alphabet");
    std::fs::create_dir_all(&dir).unwrap();
    for (name, src) in [("dejavu", dejavu()), ("garamond", garamond())] {
        let (ttf, ufo) = (
            dir.join(format!("{name}.ttf")),
            dir.join(format!("{name}.ufo")),
        );
        let report = font(&[
            "font",
            "--font",
            src.to_str().unwrap(),
            "--chars",
            ALPHABET,
            "--out",
            ttf.to_str().unwrap(),
            "--out",
            ufo.to_str().unwrap(),
        ]);
        let glyphs = report["glyphs"].as_array().unwrap();
        assert_eq!(glyphs.len(), ALPHABET.chars().count(), "{name}");
        let em = report["units_per_em"].as_f64().unwrap();
        for g in glyphs {
            assert_eq!(g["fallback"], false, "{name}: {g}");
            assert!(
                g["written_hausdorff"].as_f64().unwrap() <= 0.004 * em,
                "{name}: {g}"
            );
        }
    }
}
