//! Glyph drafting from the vendored DejaVu Sans: import, drafting bounds, auto shape, TrueType
//! quadratics, the compiled-font round trip, UFO, tessellation against direct rendering, and
//! golden pictures.
#![cfg(all(feature = "font", feature = "tessellate", feature = "render"))]

use std::path::{Path, PathBuf};

use kappa::analysis::CurvatureAnalysis;
use kappa::glyph::{
    anchor_outline, compile_font, draft, fill_mesh, from_glif, hausdorff, is_quadratic,
    on_curve_points, on_curve_split, quantize, stroke_mesh, to_glif, to_quadratic, to_svg,
    word_figure, word_scene, AnchorKind, DraftOptions, DraftShape, DraftedGlyph, FontGlyph,
    FontOutlines, Mesh, PlacedGlyph, AUTO_MAX_SHAPE, FIGURE_WORD,
};
use kappa::render::golden::{check_golden, Tolerance};
use kappa::{Error, Scheme};
use kurbo::{Affine, BezPath, ParamCurve, ParamCurveArea, ParamCurveNearest, PathEl, Point, Vec2};
use resvg::tiny_skia;

const WORD: &str = "Sample";

fn font_data() -> Vec<u8> {
    std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fonts/DejaVuSans.ttf")).unwrap()
}

fn garamond_data() -> Vec<u8> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::read(dir.join("tests/fonts/EBGaramond12-Regular-subset.otf")).unwrap()
}

fn options(scheme: Scheme, shape: DraftShape) -> DraftOptions {
    DraftOptions::for_units_per_em(2048.0).with_scheme(scheme, shape)
}

fn drafted_word(scheme: Scheme, shape: DraftShape) -> Vec<(kappa::glyph::Glyph, DraftedGlyph)> {
    let data = font_data();
    let font = FontOutlines::parse(&data).unwrap();
    let opts = options(scheme, shape);
    WORD.chars()
        .map(|ch| {
            let g = font.glyph(ch).unwrap();
            let d = draft(&g.path, &opts).unwrap();
            (g, d)
        })
        .collect()
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn glyph_import_font_units_y_up() {
    let data = font_data();
    let font = FontOutlines::parse(&data).unwrap();
    assert_eq!(font.units_per_em(), 2048.0);
    let l = font.glyph('l').unwrap();
    // DejaVu's 'l' is one rectangle: 4 on-curve points, above the baseline (y up).
    assert_eq!(on_curve_points(&l.path), 4);
    let b = kurbo::Shape::bounding_box(&l.path);
    assert!(b.y0 >= 0.0 && b.y1 > 1400.0, "{b:?}");
    let p = font.glyph('p').unwrap();
    // The descender goes below the baseline.
    assert!(kurbo::Shape::bounding_box(&p.path).y0 < -300.0);
    assert!(l.advance > 0.0);
    // Every contour is closed and ends where it starts.
    for (segs, closed) in kappa::glyph::contours(&p.path) {
        assert!(closed);
        assert!((segs[0].start() - segs.last().unwrap().end()).hypot() < 1e-12);
    }
    assert_eq!(
        font.glyph('\u{E000}').unwrap_err(),
        Error::MissingGlyph { ch: '\u{E000}' }
    );
    assert!(matches!(
        FontOutlines::parse(b"not a font"),
        Err(Error::Font(_))
    ));
    // A space has no outline.
    assert!(font.glyph(' ').unwrap().path.elements().is_empty());
}

/// Every scheme and shape rule of the drafts: κ, and εκ-cubic and εκ-trig with their
/// neutral shape, one global shape and the auto shape.
const ALL_SCHEMES: [(Scheme, DraftShape); 7] = [
    (Scheme::Kappa, DraftShape::Neutral),
    (Scheme::EkCubic, DraftShape::Neutral),
    (Scheme::EkCubic, DraftShape::Global(0.85)),
    (Scheme::EkCubic, DraftShape::Auto),
    (Scheme::EkTrig, DraftShape::Neutral),
    (Scheme::EkTrig, DraftShape::Global(0.8)),
    (Scheme::EkTrig, DraftShape::Auto),
];

/// Hausdorff bound, anchors on the original, corners kept, for every glyph of the word in
/// every scheme.
#[test]
fn glyph_draft_sample_within_bound() {
    for (scheme, shape) in ALL_SCHEMES {
        let tol = options(scheme, shape.clone()).tolerance;
        for (g, d) in drafted_word(scheme, shape.clone()) {
            let h = d.hausdorff.unwrap();
            assert!(
                h <= tol,
                "{scheme:?} {shape:?} {}: Hausdorff {h} > {tol}",
                g.ch
            );
            assert!(d.within_tolerance());
            // The reported piecewise distance bounds the outline's Hausdorff distance, measured
            // independently on 4x the samples (up to the sampling step).
            let whole = hausdorff(&g.path, &d.path, 64);
            assert!(whole <= h + 0.5, "{}: {whole} vs {h}", g.ch);
            let original: Vec<kurbo::PathSeg> = g.path.segments().collect();
            for piece in d.pieces() {
                for a in &piece.anchors {
                    let dist = original
                        .iter()
                        .map(|s| s.nearest(a.point, 1e-12).distance_sq)
                        .fold(f64::INFINITY, f64::min)
                        .sqrt();
                    assert!(dist < 1e-6, "anchor off the original by {dist}");
                }
                // Open pieces start and end on their corner anchors (corners stay sharp).
                if !piece.closed {
                    let first = piece.anchors.first().unwrap();
                    let last = piece.anchors.last().unwrap();
                    assert_eq!(first.kind, AnchorKind::Corner);
                    assert_eq!(last.kind, AnchorKind::Corner);
                    let segs: Vec<_> = piece.path.segments().collect();
                    assert!((segs[0].start() - first.point).hypot() < 1e-9);
                    assert!((segs.last().unwrap().end() - last.point).hypot() < 1e-9);
                }
                // The κ/εκ curve passes through every anchor: exactly, and the fitted path
                // of an εκ-trig curve within its fitting tolerance (tolerance / 20).
                let fit = if scheme == Scheme::EkTrig {
                    tol / 20.0
                } else {
                    0.0
                };
                for a in &piece.anchors {
                    let exact = piece
                        .spline
                        .segments()
                        .iter()
                        .map(|s| (s.eval(s.t_max) - a.point).hypot())
                        .fold(f64::INFINITY, f64::min);
                    if piece.anchors.len() > 2 && (piece.closed || a.kind != AnchorKind::Corner) {
                        assert!(exact < 1e-6, "curve misses its anchor by {exact}");
                    }
                    let d = piece
                        .path
                        .segments()
                        .map(|s| s.nearest(a.point, 1e-12).distance_sq)
                        .fold(f64::INFINITY, f64::min)
                        .sqrt();
                    assert!(d < fit + 1e-6, "path misses its anchor by {d}");
                }
            }
            assert!(d.anchor_count() >= 4 && d.original_on_curve() >= 4);
        }
    }
}

/// Curvature sign changes along the curved parts of an outline (16 samples per segment; a
/// line, where κ = 0, starts a new count).
fn inflections(path: &BezPath) -> usize {
    let mut count = 0;
    for (segs, _) in kappa::glyph::contours(path) {
        let mut last = 0.0f64;
        for seg in &segs {
            if matches!(seg, kurbo::PathSeg::Line(_)) {
                last = 0.0;
                continue;
            }
            for j in 0..=16 {
                let k = CurvatureAnalysis::curvature(seg, j as f64 / 16.0);
                if k.abs() < 1e-7 {
                    continue;
                }
                if last * k < 0.0 {
                    count += 1;
                }
                last = k;
            }
        }
    }
    count
}

/// Fairing: the drafts of the word turn the way the original turns, within the bound; the
/// plain drafts do not (anchors at flank extrema become |κ| peaks of the other sign).
#[test]
fn glyph_fair_sample() {
    for (scheme, shape) in [
        (Scheme::Kappa, DraftShape::Neutral),
        (Scheme::EkCubic, DraftShape::Auto),
        (Scheme::EkTrig, DraftShape::Auto),
    ] {
        let mut fair = options(scheme, shape.clone());
        fair.fair = true;
        let (mut plain, mut faired) = (0, 0);
        for (g, d) in drafted_word(scheme, shape.clone()) {
            let f = draft(&g.path, &fair).unwrap();
            let h = f.hausdorff.unwrap();
            assert!(h <= fair.tolerance && f.within_tolerance(), "{}: {h}", g.ch);
            let original = inflections(&g.path);
            assert_eq!(inflections(&f.path), original, "{scheme:?} {}", g.ch);
            plain += inflections(&d.path) - original;
            // The drafted curvature at each anchor has the original's sign there.
            let segs: Vec<kurbo::PathSeg> = g.path.segments().collect();
            for piece in f.pieces() {
                let off = usize::from(!piece.closed);
                let m = piece.anchors.len();
                for (i, a) in piece.anchors.iter().enumerate() {
                    if !piece.closed && (m <= 2 || i == 0 || i + 1 == m) {
                        continue;
                    }
                    let seg = piece.spline.segments()[i - off];
                    let (ko, _) = segs
                        .iter()
                        .map(|s| {
                            let n = s.nearest(a.point, 1e-12);
                            (CurvatureAnalysis::curvature(s, n.t), n.distance_sq)
                        })
                        .min_by(|x, y| x.1.total_cmp(&y.1))
                        .unwrap();
                    if ko.abs() > 1e-6 {
                        assert!(seg.curvature(seg.t_max) * ko > 0.0, "{}: {a:?}", g.ch);
                        faired += 1;
                    }
                }
            }
        }
        assert!(faired > 50, "{faired}");
        if scheme != Scheme::EkTrig {
            assert!(
                plain > 0,
                "{scheme:?}: the plain drafts have no spurious inflections"
            );
        }
    }
}

/// The simplification keeps every glyph of the word within the bound with no more anchors,
/// and fewer in all.
#[test]
fn glyph_simplify_sample() {
    for (scheme, shape) in [
        (Scheme::Kappa, DraftShape::Neutral),
        (Scheme::EkCubic, DraftShape::Auto),
    ] {
        let mut simple = options(scheme, shape.clone());
        simple.simplify = true;
        let data = font_data();
        let font = FontOutlines::parse(&data).unwrap();
        let (mut before, mut after) = (0, 0);
        for (g, d) in drafted_word(scheme, shape.clone()) {
            let s = draft(&g.path, &simple).unwrap();
            let h = s.hausdorff.unwrap();
            assert!(
                h <= simple.tolerance && s.within_tolerance(),
                "{}: {h}",
                g.ch
            );
            assert!(hausdorff(&font.glyph(g.ch).unwrap().path, &s.path, 64) <= h + 0.5);
            assert!(s.anchor_count() <= d.anchor_count(), "{}", g.ch);
            before += d.anchor_count();
            after += s.anchor_count();
        }
        assert!(after < before, "{scheme:?}: {after} vs {before}");
    }
}

/// Auto shape: where the shape is not clamped, the drafted peak |κ| matches the original's.
#[test]
fn glyph_auto_shape_matches_peaks() {
    let mut matched = 0;
    let mut free = 0;
    for (_, d) in drafted_word(Scheme::EkCubic, DraftShape::Auto) {
        for piece in d.pieces() {
            let segs = piece.spline.segments();
            let off = usize::from(!piece.closed);
            for (i, a) in piece.anchors.iter().enumerate() {
                let Some(seg) = i.checked_sub(off).and_then(|j| segs.get(j)) else {
                    continue;
                };
                if !piece.closed && (i == 0 || i + 1 == piece.anchors.len()) {
                    continue;
                }
                let peak = seg.curvature(seg.t_max).abs();
                if a.a > 2.0 / 3.0 + 1e-9 && a.a < AUTO_MAX_SHAPE - 1e-9 {
                    free += 1;
                    if (peak / a.target_curvature).ln().abs() <= 0.05 {
                        matched += 1;
                    }
                } else if a.a <= 2.0 / 3.0 + 1e-9 {
                    // Clamped low: the κ-curve peak alone already reaches the target (within
                    // the 2 % stopping rule), or a neighbour's sharpening pushed it there.
                    assert!(seg.a <= 2.0 / 3.0 + 1e-9);
                }
            }
        }
    }
    assert!(free > 5, "only {free} anchors with a free shape");
    assert!(
        matched * 10 >= free * 9,
        "{matched} of {free} free anchors match their peak within 5 %"
    );
}

/// The εκ peak at a point grows with a (the premise of the auto shape).
#[test]
fn glyph_ek_peak_grows_with_shape() {
    let pts = [
        Point::new(0.0, 0.0),
        Point::new(100.0, 10.0),
        Point::new(120.0, 90.0),
        Point::new(20.0, 110.0),
    ];
    for scheme in [Scheme::EkCubic, Scheme::EkTrig] {
        let mut last = 0.0;
        for a in [0.7, 0.75, 0.8, 0.85, 0.9, 0.95] {
            let s = kappa::Solver::new()
                .solve(&pts, true, scheme, &kappa::Shape::Global(a))
                .unwrap();
            let seg = s.segments()[1];
            let k = seg.curvature(seg.t_max).abs();
            assert!(k > last, "{scheme:?} a = {a}: {k} <= {last}");
            last = k;
        }
    }
}

#[test]
fn glyph_quadratic_export() {
    // κ: exact (the same elements).
    for (_, d) in drafted_word(Scheme::Kappa, DraftShape::Neutral) {
        let q = to_quadratic(&d.path, 0.5).unwrap();
        assert!(q.exact && q.max_error == 0.0);
        assert_eq!(q.path.elements(), d.path.elements());
        assert!(is_quadratic(&q.path));
    }
    // εκ-cubic: within the stated tolerance, checked on the whole outline.
    for (g, d) in drafted_word(Scheme::EkCubic, DraftShape::Auto) {
        for tol in [1.0, 0.25] {
            let q = to_quadratic(&d.path, tol).unwrap();
            assert!(!q.exact || is_quadratic(&d.path));
            assert!(is_quadratic(&q.path));
            assert!(q.max_error <= tol, "{}: {} > {tol}", g.ch, q.max_error);
            let h = hausdorff(&d.path, &q.path, 32);
            assert!(h <= tol * 1.05, "{}: Hausdorff {h} > {tol}", g.ch);
        }
    }
    assert!(matches!(
        to_quadratic(&BezPath::new(), f64::NAN),
        Err(Error::InvalidOption(_))
    ));
}

fn font_glyphs(word: &[(kappa::glyph::Glyph, DraftedGlyph)]) -> Vec<FontGlyph> {
    word.iter()
        .map(|(g, d)| FontGlyph {
            name: g.ch.to_string(),
            ch: g.ch,
            path: to_quadratic(&d.path, 0.5).unwrap().path,
            advance: g.advance,
        })
        .collect()
}

/// The acceptance round trip: κ-drafted glyphs in a TrueType font read back by ttf-parser
/// are the drafted paths on the integer grid, element for element.
#[test]
fn glyph_font_round_trip() {
    for (scheme, shape) in [
        (Scheme::Kappa, DraftShape::Neutral),
        (Scheme::EkCubic, DraftShape::Auto),
    ] {
        let word = drafted_word(scheme, shape);
        let glyphs = font_glyphs(&word);
        let bytes = compile_font("", 2048, 1901, -483, &glyphs).unwrap();
        let face = ttf_parser::Face::parse(&bytes, 0).unwrap();
        let t = face.tables();
        assert!(t.glyf.is_some() && t.hhea.number_of_metrics > 0);
        assert!(t.cmap.is_some() && t.hmtx.is_some() && t.name.is_some() && t.post.is_some());
        assert_eq!(t.maxp.number_of_glyphs.get(), glyphs.len() as u16 + 1);
        assert_eq!(face.units_per_em(), 2048);
        let family = face
            .names()
            .into_iter()
            .find(|n| n.name_id == ttf_parser::name_id::FAMILY)
            .and_then(|n| n.to_string())
            .unwrap();
        assert_eq!(family, kappa::glyph::FONT_FAMILY);
        let font = FontOutlines::parse(&bytes).unwrap();
        for g in &glyphs {
            let back = font.glyph(g.ch).unwrap();
            let expected = quantize(&g.path);
            assert_eq!(back.path.elements(), expected.elements(), "{}", g.ch);
            assert_eq!(back.advance, g.advance.round());
            // The grid moves no on-curve point by more than 3√2/2 units (rounding, then a
            // unit per coordinate for a smooth node, or the mean of two control points'
            // moves for an implied one), and most by at most √2/2 (rounding alone).
            let mut rounded = 0;
            let mut all = 0;
            for (a, b) in g.path.elements().iter().zip(expected.elements()) {
                if let (Some(p), Some(q)) = (a.end_point(), b.end_point()) {
                    let d = (p - q).hypot();
                    assert!(d <= 1.5 * 2f64.sqrt() + 1e-12, "{}: {d}", g.ch);
                    rounded += usize::from(d <= 0.5f64.sqrt() + 1e-12);
                    all += 1;
                }
            }
            assert!(rounded * 10 >= all * 9, "{}: {rounded}/{all}", g.ch);
        }
    }
    let mut cubic = BezPath::new();
    cubic.move_to((0.0, 0.0));
    cubic.curve_to((10.0, 10.0), (20.0, 10.0), (30.0, 0.0));
    cubic.close_path();
    let bad = FontGlyph {
        name: "x".into(),
        ch: 'x',
        path: cubic,
        advance: 10.0,
    };
    assert!(matches!(
        compile_font("", 1000, 800, -200, &[bad]),
        Err(Error::Font(_))
    ));
}

#[test]
fn glyph_ufo_round_trip() {
    let word = drafted_word(Scheme::EkCubic, DraftShape::Auto);
    for (g, d) in &word {
        let fg = FontGlyph {
            name: g.ch.to_string(),
            ch: g.ch,
            path: d.path.clone(),
            advance: g.advance,
        };
        let xml = to_glif(&fg).unwrap();
        assert!(
            xml.contains("<glyph") && xml.contains("type=\"line\""),
            "{xml}"
        );
        let back = from_glif(&xml).unwrap();
        // Same contours; each closed contour starts at its own first on-curve point.
        let a = kappa::glyph::contours(&d.path);
        let b = kappa::glyph::contours(&back);
        assert_eq!(a.len(), b.len());
        for ((sa, ca), (sb, cb)) in a.iter().zip(&b) {
            assert_eq!(ca, cb);
            assert_eq!(sa.len(), sb.len(), "{}", g.ch);
            for (x, y) in sa.iter().zip(sb) {
                for t in [0.0, 0.3, 0.7, 1.0] {
                    assert!((x.eval(t) - y.eval(t)).hypot() < 1e-9);
                }
            }
        }
    }
    let dir = scratch("glyph-ufo").join("Draft.ufo");
    let glyphs = font_glyphs(&word);
    kappa::glyph::write_ufo(&dir, "Kappa Draft", 2048.0, &glyphs).unwrap();
    let font = norad::Font::load(&dir).unwrap();
    assert_eq!(font.default_layer().len(), glyphs.len());
    assert_eq!(
        font.font_info.units_per_em.map(|u| u.as_f64()),
        Some(2048.0)
    );
    let s = font.default_layer().get_glyph("S").unwrap();
    assert_eq!(s.codepoints.iter().next(), Some('S'));
    assert!(!s.contours.is_empty());
    // The optional external check with Python's fontTools/ufoLib2, when installed.
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/ufo_check.py");
    match std::process::Command::new("python3")
        .arg(&script)
        .arg(&dir)
        .output()
    {
        Ok(out) if out.status.code() == Some(0) => {
            let text = String::from_utf8_lossy(&out.stdout);
            assert!(text.contains("glyphs 6"), "{text}");
        }
        // Exit 77: the Python readers are not installed here; skipped.
        Ok(out) if out.status.code() == Some(77) => {}
        Ok(out) => panic!("ufo check failed: {}", String::from_utf8_lossy(&out.stderr)),
        Err(_) => {}
    }
}

#[test]
fn glyph_svg_export() {
    let word = drafted_word(Scheme::Kappa, DraftShape::Neutral);
    let svg = to_svg(&word[0].1.path, 20.0);
    assert!(svg.starts_with("<svg") && svg.contains("scale(1 -1)"));
    assert!(svg.contains(" Q"));
    let tree = resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default()).unwrap();
    assert!(tree.size().width() > 1000.0);
}

/// Binary coverage masks of a fill: `paths` filled with the non-zero rule, no anti-aliasing.
fn mask(paths: &[tiny_skia::Path], size: u32, transform: tiny_skia::Transform) -> Vec<bool> {
    let mut pixmap = tiny_skia::Pixmap::new(size, size).unwrap();
    let mut paint = tiny_skia::Paint::default();
    paint.set_color_rgba8(0, 0, 0, 255);
    paint.anti_alias = false;
    for p in paths {
        pixmap.fill_path(p, &paint, tiny_skia::FillRule::Winding, transform, None);
    }
    pixmap.pixels().iter().map(|p| p.alpha() > 127).collect()
}

/// The path for tiny-skia, its curves flattened by kurbo within `tolerance`: tiny-skia's own
/// curve edges stray by a good fraction of a pixel, which alone costs about 0.5 % IoU at
/// 512 px; a polygon this fine renders the exact outline to within 0.01 px.
fn skia_path(path: &BezPath, tolerance: f64) -> tiny_skia::Path {
    let mut flat = BezPath::new();
    kurbo::flatten(path.iter(), tolerance, |el| flat.push(el));
    let mut pb = tiny_skia::PathBuilder::new();
    for el in flat.elements() {
        match *el {
            PathEl::MoveTo(p) => pb.move_to(p.x as f32, p.y as f32),
            PathEl::LineTo(p) => pb.line_to(p.x as f32, p.y as f32),
            PathEl::QuadTo(a, p) => pb.quad_to(a.x as f32, a.y as f32, p.x as f32, p.y as f32),
            PathEl::CurveTo(a, b, p) => pb.cubic_to(
                a.x as f32, a.y as f32, b.x as f32, b.y as f32, p.x as f32, p.y as f32,
            ),
            PathEl::ClosePath => pb.close(),
        }
    }
    pb.finish().unwrap()
}

/// The mesh's triangles as one path (all counter-clockwise, so non-zero is their union).
fn mesh_path(mesh: &Mesh) -> tiny_skia::Path {
    let mut pb = tiny_skia::PathBuilder::new();
    for [a, b, c] in mesh.triangles() {
        pb.move_to(a.x as f32, a.y as f32);
        pb.line_to(b.x as f32, b.y as f32);
        pb.line_to(c.x as f32, c.y as f32);
        pb.close();
    }
    pb.finish().unwrap()
}

fn iou(a: &[bool], b: &[bool]) -> f64 {
    let inter = a.iter().zip(b).filter(|(x, y)| **x && **y).count();
    let union = a.iter().zip(b).filter(|(x, y)| **x || **y).count();
    inter as f64 / union.max(1) as f64
}

/// Tessellated fill and stroke agree with tiny-skia's direct rendering of the path
/// (IoU ≥ 0.995 at 512 px) for every drafted glyph of the gallery word; vertex and
/// triangle counts are snapshot-tested.
#[test]
fn glyph_tessellation_matches_direct_rendering() {
    const SIZE: u32 = 512;
    // Flattening tolerance in font units: 0.01 px at this scale.
    const TOLERANCE: f64 = 0.05;
    let mut snapshot = String::new();
    for (scheme, shape) in [
        (Scheme::Kappa, DraftShape::Neutral),
        (Scheme::EkCubic, DraftShape::Auto),
    ] {
        for (g, d) in drafted_word(scheme, shape) {
            // The glyph's em box, y flipped, onto 512 px.
            let s = SIZE as f64 / 2400.0;
            let transform = tiny_skia::Transform::from_row(
                s as f32,
                0.0,
                0.0,
                -s as f32,
                (0.05 * SIZE as f64) as f32,
                (SIZE as f64 * 0.8) as f32,
            );
            let fill = fill_mesh(&d.path, TOLERANCE).unwrap();
            let direct = mask(&[skia_path(&d.path, TOLERANCE)], SIZE, transform);
            let meshed = mask(&[mesh_path(&fill)], SIZE, transform);
            let v = iou(&direct, &meshed);
            assert!(v >= 0.995, "{scheme:?} {} fill IoU {v}", g.ch);
            // Area: the mesh covers the outline's area (non-zero; no overlapping contours).
            let area: f64 = kurbo::Shape::area(&d.path).abs();
            assert!((fill.area() - area).abs() <= 0.01 * area, "{}", g.ch);
            let width = 40.0;
            let stroke = stroke_mesh(&d.path, width, TOLERANCE).unwrap();
            let stroker = tiny_skia::Stroke {
                width: width as f32,
                line_join: tiny_skia::LineJoin::Round,
                line_cap: tiny_skia::LineCap::Round,
                ..Default::default()
            };
            let outline = skia_path(&d.path, TOLERANCE).stroke(&stroker, 1.0).unwrap();
            let direct = mask(&[outline], SIZE, transform);
            let meshed = mask(&[mesh_path(&stroke)], SIZE, transform);
            let v = iou(&direct, &meshed);
            assert!(v >= 0.995, "{scheme:?} {} stroke IoU {v}", g.ch);
            snapshot.push_str(&format!(
                "{scheme:?} {} fill {} vertices {} triangles, stroke {} vertices {} triangles\n",
                g.ch,
                fill.vertices.len(),
                fill.triangle_count(),
                stroke.vertices.len(),
                stroke.triangle_count()
            ));
        }
    }
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/snapshots/glyph-meshes.txt");
    if kappa::render::golden::bless_requested() || !path.exists() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, &snapshot).unwrap();
    }
    let expected = std::fs::read_to_string(&path).unwrap();
    assert_eq!(
        snapshot, expected,
        "mesh counts changed; re-bless with KAPPA_BLESS=1 after checking"
    );
    assert!(matches!(
        fill_mesh(&BezPath::new(), 0.0),
        Err(Error::InvalidOption(_))
    ));
    let mut nan = BezPath::new();
    nan.move_to((f64::NAN, 0.0));
    nan.line_to((1.0, 1.0));
    assert!(matches!(
        stroke_mesh(&nan, 1.0, 0.1),
        Err(Error::NonFinitePoint { .. })
    ));
}

#[test]
fn glyph_bad_input_is_typed() {
    let mut nan = BezPath::new();
    nan.move_to((0.0, 0.0));
    nan.quad_to((f64::NAN, 1.0), (2.0, 0.0));
    nan.close_path();
    let opts = DraftOptions::default();
    assert!(matches!(
        draft(&nan, &opts),
        Err(Error::NonFinitePoint { .. })
    ));
    let mut bad = opts.clone();
    bad.tolerance = 0.0;
    assert!(matches!(
        draft(&BezPath::new(), &bad),
        Err(Error::InvalidOption(_))
    ));
    let bad = opts.with_scheme(Scheme::EkCubic, DraftShape::Global(1.5));
    assert!(matches!(
        draft(&BezPath::new(), &bad),
        Err(Error::ShapeOutOfRange { .. })
    ));
    // An empty outline drafts to nothing.
    let empty = draft(&BezPath::new(), &DraftOptions::default()).unwrap();
    assert_eq!(empty.anchor_count(), 0);
}

/// Drafting commutes with translation (the anchors move with the outline).
#[test]
fn glyph_draft_translation_invariant() {
    let data = font_data();
    let font = FontOutlines::parse(&data).unwrap();
    let g = font.glyph('e').unwrap();
    let opts = options(Scheme::Kappa, DraftShape::Neutral);
    let a = draft(&g.path, &opts).unwrap();
    let shift = Vec2::new(1000.0, -500.0);
    let b = draft(&(Affine::translate(shift) * g.path.clone()), &opts).unwrap();
    assert_eq!(a.anchor_count(), b.anchor_count());
    for (pa, pb) in a.pieces().zip(b.pieces()) {
        for (x, y) in pa.anchors.iter().zip(&pb.anchors) {
            assert!((x.point + shift - y.point).hypot() < 1e-6);
        }
    }
}

fn golden(name: &str, scheme: Scheme, shape: DraftShape) {
    let word = drafted_word(scheme, shape);
    let mut x = 0.0;
    let placed: Vec<PlacedGlyph<'_>> = word
        .iter()
        .map(|(g, d)| {
            let p = PlacedGlyph {
                original: &g.path,
                drafted: d,
                offset: Vec2::new(x, 0.0),
            };
            x += g.advance;
            p
        })
        .collect();
    let image = word_scene(&placed, 2048.0, 1200, 320, None)
        .render()
        .unwrap();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/golden/{name}.png"));
    if let Err(e) = check_golden(&path, &image, Tolerance::DEFAULT) {
        panic!("{e}");
    }
}

#[test]
fn golden_glyph_sample_kappa() {
    golden("glyph-sample-kappa", Scheme::Kappa, DraftShape::Neutral);
}

#[test]
fn golden_glyph_sample_ek_auto() {
    golden("glyph-sample-ek-auto", Scheme::EkCubic, DraftShape::Auto);
}

/// The gallery figure (`kappa gallery` writes the same as `glyph-sample.png`): "Sample"
/// original, κ-drafted and auto-shaped εκ-cubic, 1200 × 1000 px.
#[test]
fn golden_glyph_sample_figure() {
    let data = font_data();
    let font = FontOutlines::parse(&data).unwrap();
    let kappa = options(Scheme::Kappa, DraftShape::Neutral);
    let ek = options(Scheme::EkCubic, DraftShape::Auto);
    let scene = word_figure(&font, FIGURE_WORD, &[kappa, ek], 1200, 1000).unwrap();
    let image = scene.render().unwrap();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden/glyph-sample.png");
    if let Err(e) = check_golden(&path, &image, Tolerance::DEFAULT) {
        panic!("{e}");
    }
    // The SVG of the same scene is a document usvg reads.
    let svg = scene.to_svg().unwrap();
    resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default()).unwrap();
    assert!(matches!(
        word_figure(&font, "S\u{E000}", &[], 100, 100),
        Err(Error::MissingGlyph { .. })
    ));
}

/// The same figure from a cubic (CFF) font, EB Garamond 12 (`kappa gallery` writes it as
/// `glyph-garamond.png`): its cubic originals with their combs, κ and auto-shaped εκ-cubic
/// drafts.
#[test]
fn golden_glyph_garamond_figure() {
    let data = garamond_data();
    let font = FontOutlines::parse(&data).unwrap();
    let kappa = DraftOptions::for_units_per_em(font.units_per_em());
    let ek = kappa.clone().with_scheme(Scheme::EkCubic, DraftShape::Auto);
    let scene = word_figure(&font, FIGURE_WORD, &[kappa, ek], 1200, 1000).unwrap();
    let image = scene.render().unwrap();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden/glyph-garamond.png");
    if let Err(e) = check_golden(&path, &image, Tolerance::DEFAULT) {
        panic!("{e}");
    }
}

/// A piece that solves but stays outside the tolerance after its refinements is cut in
/// parts, which come within it: EB Garamond's `N` (its diagonal meeting the right stem)
/// strayed by 9.8 units at the default 4 (0.004 em).
#[test]
fn glyph_straying_piece_is_cut_in_parts() {
    let data = garamond_data();
    let font = FontOutlines::parse(&data).unwrap();
    let (ch, tolerance) = ('N', 4.0);
    let g = font.glyph(ch).unwrap();
    let opts = DraftOptions {
        tolerance,
        ..DraftOptions::for_units_per_em(font.units_per_em())
    };
    let d = draft(&g.path, &opts).unwrap();
    assert!(d.within_tolerance(), "{ch}: {:?}", d.hausdorff);
    assert_eq!(d.fallback_count(), 0, "{ch}");
    // Measured independently on 4x the samples, up to the sampling step.
    let whole = hausdorff(&g.path, &d.path, 64);
    assert!(whole <= tolerance + 0.5, "{ch}: {whole}");
    // The parts join end to end: the drafted contours stay closed and G0.
    for c in &d.contours {
        for (p, q) in c.pieces.iter().zip(c.pieces.iter().cycle().skip(1)) {
            let (end, start) = (p.path.segments().last(), q.path.segments().next());
            let gap = (end.unwrap().end() - start.unwrap().start()).hypot();
            assert!(gap < 1e-9, "{ch}: pieces {gap} apart");
        }
    }
}

/// The on-curve points split into stored and implied ones: DejaVu's 'o' stores few and
/// implies the rest; the counts agree with `on_curve_points`.
#[test]
fn glyph_on_curve_split() {
    let data = font_data();
    let font = FontOutlines::parse(&data).unwrap();
    for ch in WORD.chars().chain(['o']) {
        let path = font.glyph(ch).unwrap().path;
        let (stored, implied) = on_curve_split(&path);
        assert_eq!(stored.len(), on_curve_points(&path), "{ch}");
        assert_eq!(
            stored.len() + implied.len(),
            path.segments().count(),
            "{ch}"
        );
        // Every implied point is the midpoint of the off-curve points around it.
        for p in &implied {
            let found = kappa::glyph::contours(&path).iter().any(|(segs, _)| {
                let n = segs.len();
                (0..n).any(|j| match (segs[j], segs[(j + 1) % n]) {
                    (kurbo::PathSeg::Quad(a), kurbo::PathSeg::Quad(b)) => {
                        a.p2 == *p && (a.p1.midpoint(b.p1) - *p).hypot() < 1e-9
                    }
                    _ => false,
                })
            });
            assert!(found, "{ch}: {p:?} is not implied");
        }
    }
    let o = font.glyph('o').unwrap().path;
    assert!(!on_curve_split(&o).1.is_empty());
}

/// Curvature sign sanity for imported outlines: TrueType outer contours run clockwise (y up),
/// so the outline of 'l' turns right (negative κ) at its corners' neighbours — checked on a
/// curved glyph: the outer bowl of 'o' has negative curvature.
#[test]
fn glyph_outer_contours_clockwise() {
    let data = font_data();
    let font = FontOutlines::parse(&data).unwrap();
    let o = font.glyph('o').unwrap();
    let contours = kappa::glyph::contours(&o.path);
    let outer = contours
        .iter()
        .max_by(|a, b| {
            let area =
                |s: &Vec<kurbo::PathSeg>| s.iter().map(|x| x.signed_area()).sum::<f64>().abs();
            area(&a.0).total_cmp(&area(&b.0))
        })
        .unwrap();
    let k: f64 = outer
        .0
        .iter()
        .map(|s| CurvatureAnalysis::curvature(s, 0.5))
        .sum();
    assert!(k < 0.0);
}

/// The written outline has the anchors as its nodes: every anchor is an on-curve point, one
/// cubic spans each pair of consecutive anchors, the outline stays within the reported
/// distance of the draft (and so within the tolerance of the original), and the tangent at
/// each snapped extremum anchor is horizontal or vertical.
#[test]
fn anchor_outline_puts_nodes_at_the_anchors() {
    let data = font_data();
    let font = FontOutlines::parse(&data).unwrap();
    for scheme in [Scheme::Kappa, Scheme::EkCubic, Scheme::EkTrig] {
        let shape = if scheme == Scheme::Kappa {
            DraftShape::Neutral
        } else {
            DraftShape::Auto
        };
        let options = options(scheme, shape);
        for ch in "aeoSB@".chars() {
            let glyph = font.glyph(ch).unwrap();
            let drafted = draft(&glyph.path, &options).unwrap();
            let nodes = anchor_outline(&drafted, &glyph.path, 0.2, options.tolerance);
            let on: Vec<kurbo::Point> = nodes
                .path
                .elements()
                .iter()
                .filter_map(|e| match e {
                    kurbo::PathEl::ClosePath => None,
                    e => e.end_point(),
                })
                .collect();
            for a in drafted.pieces().flat_map(|p| p.anchors.iter()) {
                let d = on
                    .iter()
                    .map(|p| (*p - a.point).hypot())
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    d < 1e-6,
                    "{scheme:?} {ch}: anchor {:?} not a node ({d})",
                    a.point
                );
            }
            // (One span of the εκ-trig `@` takes two cubics.)
            assert!(
                nodes.split_spans <= 1,
                "{scheme:?} {ch}: {}",
                nodes.split_spans
            );
            let extra = on.len() - drafted.anchor_count();
            assert!(
                extra <= drafted.contours.len() + 2 * nodes.split_spans + nodes.extrema_added,
                "{scheme:?} {ch}: {extra} extra nodes"
            );
            // No curve passes an extremum between its nodes by more than 5 × the accuracy
            // (1 unit here), unless cutting it there would leave a part shorter than 20 ×.
            for seg in nodes.path.segments() {
                use kurbo::{ParamCurve, ParamCurveExtrema};
                let (p0, p1) = (seg.start(), seg.end());
                for t in seg.extrema() {
                    let p = seg.eval(t);
                    let over = |v: f64, a: f64, b: f64| (a.min(b) - v).max(v - a.max(b));
                    let bulge = over(p.x, p0.x, p1.x).max(over(p.y, p0.y, p1.y));
                    let short = (p - p0).hypot().min((p1 - p).hypot()) < 20.0 * 0.2;
                    assert!(
                        bulge <= 1.0 || short,
                        "{scheme:?} {ch}: bulge {bulge} at {p:?}"
                    );
                }
            }
            assert!(
                nodes.max_error <= options.tolerance,
                "{scheme:?} {ch}: {}",
                nodes.max_error
            );
            let d = hausdorff(&nodes.path, &glyph.path, 64);
            assert!(
                d <= options.tolerance + 1e-6,
                "{scheme:?} {ch}: {d} from the original"
            );
            assert!(nodes.snapped > 0, "{scheme:?} {ch}");
            // Snapped tangents: at extremum anchors, cubic handles on an axis.
            let mut axis = 0;
            let segs: Vec<kurbo::PathSeg> = nodes.path.segments().collect();
            for s in &segs {
                if let kurbo::PathSeg::Cubic(c) = s {
                    let h = c.p1 - c.p0;
                    if h.x == 0.0 || h.y == 0.0 {
                        axis += 1;
                    }
                }
            }
            // G1 at every node between two cubics whose outgoing handle is on an axis: the
            // incoming handle is on the same line.
            for w in segs.windows(2) {
                if let (kurbo::PathSeg::Cubic(a), kurbo::PathSeg::Cubic(b)) = (w[0], w[1]) {
                    let (h_in, h_out) = (a.p3 - a.p2, b.p1 - b.p0);
                    if (h_out.x == 0.0) != (h_out.y == 0.0) && h_in.hypot() > 0.0 {
                        assert!(
                            h_in.cross(h_out).abs() <= 1e-9 * h_in.hypot() * h_out.hypot(),
                            "{scheme:?} {ch}: handles {h_in:?} {h_out:?} not on one line"
                        );
                    }
                }
            }
            assert!(
                axis >= nodes.snapped,
                "{scheme:?} {ch}: {axis} < {}",
                nodes.snapped
            );
        }
    }
}

/// Smooth line-to-curve joins: where a drafted curve meets a straight segment within 10°,
/// the written outline makes it tangent to the line unless that moves the curve beyond the
/// tolerance.
#[test]
fn anchor_outline_makes_line_joins_tangent() {
    let data = font_data();
    let font = FontOutlines::parse(&data).unwrap();
    let options = options(Scheme::Kappa, DraftShape::Neutral);
    let (mut tangent, mut kinked) = (0, 0);
    for ch in ('a'..='z').chain('A'..='Z') {
        let glyph = font.glyph(ch).unwrap();
        let drafted = draft(&glyph.path, &options).unwrap();
        let nodes = anchor_outline(&drafted, &glyph.path, 0.2, options.tolerance);
        let segs: Vec<kurbo::PathSeg> = nodes.path.segments().collect();
        for w in segs.windows(2) {
            let (a, b) = match (w[0], w[1]) {
                (kurbo::PathSeg::Line(l), kurbo::PathSeg::Cubic(c)) => (l.p1 - l.p0, c.p1 - c.p0),
                (kurbo::PathSeg::Cubic(c), kurbo::PathSeg::Line(l)) => (c.p3 - c.p2, l.p1 - l.p0),
                _ => continue,
            };
            let turn = a.cross(b).atan2(a.dot(b)).abs();
            if turn < 1e-9 {
                tangent += 1;
            } else if turn <= 10f64.to_radians() {
                kinked += 1;
            }
        }
        // (DejaVu keeps one-point contours as anchors in some glyphs, `u` among them; the
        // drafts leave them out.)
        let d = hausdorff(&nodes.path, &without_points(&glyph.path), 64);
        assert!(d <= options.tolerance + 1e-6, "{ch}: {d}");
    }
    // Measured: 31 made tangent, 36 left with a kink of up to 10°, where turning the handle
    // alone would take the curve beyond the tolerance (the drafting does not solve with a
    // tangent at its piece ends).
    assert!(
        tangent >= 28 && kinked <= 40,
        "{tangent} tangent, {kinked} kinked"
    );
}

/// A small fillet between a stem and a crossbar (a quarter circle of radius 20 in a
/// 2048-unit em: its chord is within the tolerance of the arc, and shorter than the minimum
/// spacing of anchors) stays a curve, and the written outline meets both lines smoothly
/// (within 0.5°); it was drafted as a straight line with a 45° corner at each end.
#[test]
fn small_fillets_stay_smooth() {
    let options = options(Scheme::Kappa, DraftShape::Neutral);
    let k = 0.5522847498 * 20.0;
    let mut path = BezPath::new();
    path.move_to((0.0, 0.0));
    path.line_to((400.0, 0.0));
    path.line_to((400.0, 100.0));
    path.line_to((120.0, 100.0));
    path.curve_to((120.0 - k, 100.0), (100.0, 120.0 - k), (100.0, 120.0));
    path.line_to((100.0, 700.0));
    path.line_to((0.0, 700.0));
    path.close_path();
    let drafted = draft(&path, &options).unwrap();
    let nodes = anchor_outline(&drafted, &path, 0.2, options.tolerance);
    let segs: Vec<kurbo::PathSeg> = nodes.path.segments().collect();
    let n = segs.len();
    let (start, end) = (Point::new(120.0, 100.0), Point::new(100.0, 120.0));
    let mut curves = 0;
    for (i, seg) in segs.iter().enumerate() {
        let next = segs[(i + 1) % n];
        let p = seg.end();
        if (p - start).hypot() > 1e-6 && (p - end).hypot() > 1e-6 {
            continue;
        }
        let tin = match *seg {
            kurbo::PathSeg::Line(l) => l.p1 - l.p0,
            kurbo::PathSeg::Quad(q) => q.p2 - q.p1,
            kurbo::PathSeg::Cubic(c) => c.p3 - c.p2,
        };
        let tout = match next {
            kurbo::PathSeg::Line(l) => l.p1 - l.p0,
            kurbo::PathSeg::Quad(q) => q.p1 - q.p0,
            kurbo::PathSeg::Cubic(c) => c.p1 - c.p0,
        };
        let turn = tin.cross(tout).atan2(tin.dot(tout)).abs();
        assert!(
            turn < 0.5f64.to_radians(),
            "{p:?}: turns {}°",
            turn.to_degrees()
        );
        curves += usize::from(!matches!(next, kurbo::PathSeg::Line(_)));
    }
    // The fillet's first curve leaves `start`; the line leaves `end`.
    assert_eq!(curves, 1, "{:?}", nodes.path.to_svg());
    let d = hausdorff(&nodes.path, &path, 64);
    assert!(d <= options.tolerance, "{d}");
}

/// EB Garamond's smooth joins stay smooth in the written outline (within 0.5°), as
/// `kappa font` writes a UFO: where a gently curved piece meets lines (the shoulder of `h`,
/// the bowl of `p`, the foot of `M`: drafted as their chords, with kinks of 4°–12°, until
/// they got a middle anchor) and where two pieces meet at an extremum node with one side on
/// the axis already (`three`, `five`: 2°–4°).
#[test]
fn garamond_smooth_joins_stay_smooth() {
    let data = garamond_data();
    let font = FontOutlines::parse(&data).unwrap();
    let mut options = DraftOptions::for_units_per_em(font.units_per_em());
    options.extremum_tangents = true;
    let turn = |a: Vec2, b: Vec2| a.cross(b).atan2(a.dot(b)).abs();
    let (tin, tout) = (
        |s: &kurbo::PathSeg| match *s {
            kurbo::PathSeg::Line(l) => l.p1 - l.p0,
            kurbo::PathSeg::Quad(q) => q.p2 - q.p1,
            kurbo::PathSeg::Cubic(c) => c.p3 - c.p2,
        },
        |s: &kurbo::PathSeg| match *s {
            kurbo::PathSeg::Line(l) => l.p1 - l.p0,
            kurbo::PathSeg::Quad(q) => q.p1 - q.p0,
            kurbo::PathSeg::Cubic(c) => c.p1 - c.p0,
        },
    );
    // The joins of a closed outline: (point, incoming direction, outgoing direction).
    let joins = |path: &kurbo::BezPath| -> Vec<(Point, Vec2, Vec2)> {
        kappa::glyph::contours(path)
            .into_iter()
            .flat_map(|(segs, _)| {
                let n = segs.len();
                (0..n)
                    .map(|i| (segs[i].end(), tin(&segs[i]), tout(&segs[(i + 1) % n])))
                    .collect::<Vec<_>>()
            })
            .collect()
    };
    let mut checked = 0;
    for ch in ['h', 'p', 'M', '3', '5'] {
        let glyph = font.glyph(ch).unwrap();
        let drafted = draft(&glyph.path, &options).unwrap();
        let nodes = anchor_outline(&drafted, &glyph.path, 0.1, options.tolerance);
        let written = joins(&nodes.path);
        for (p, a, b) in joins(&glyph.path) {
            if a.hypot2() == 0.0 || b.hypot2() == 0.0 || turn(a, b) >= 0.5f64.to_radians() {
                continue;
            }
            // The written node at the source's smooth join, if there is one.
            let Some(&(_, u, v)) = written.iter().find(|(q, _, _)| (*q - p).hypot() <= 1e-6) else {
                continue;
            };
            checked += 1;
            let t = turn(u, v).to_degrees();
            assert!(t < 0.5, "{ch} at {p:?}: turns {t}°");
        }
    }
    // Measured: 89 of the five glyphs' smooth joins are nodes of the written outline.
    assert!(checked >= 80, "{checked} joins checked");
}

/// The outline without its one-point contours.
fn without_points(path: &kurbo::BezPath) -> kurbo::BezPath {
    let mut out = kurbo::BezPath::new();
    let mut sub: Vec<kurbo::PathEl> = Vec::new();
    let flush = |sub: &mut Vec<kurbo::PathEl>, out: &mut kurbo::BezPath| {
        let b = kurbo::Shape::bounding_box(&kurbo::BezPath::from_vec(sub.clone()));
        if b.width() > 0.0 || b.height() > 0.0 {
            out.extend(sub.iter().copied());
        }
        sub.clear();
    };
    for el in path.elements() {
        if matches!(el, kurbo::PathEl::MoveTo(_)) && !sub.is_empty() {
            flush(&mut sub, &mut out);
        }
        sub.push(*el);
    }
    if !sub.is_empty() {
        flush(&mut sub, &mut out);
    }
    out
}

/// Extremum anchors hold the original's axis as their tangent in the solve
/// (`DraftOptions::extremum_tangents`): where an anchor reports a tangent, the drafted curve
/// runs along it at the anchor (within 1e-8 rad), and most extremum anchors of the word get
/// one; without the option none does.
#[test]
fn glyph_extremum_anchors_hold_their_axis() {
    for (scheme, shape) in [
        (Scheme::Kappa, DraftShape::Neutral),
        (Scheme::EkCubic, DraftShape::Global(0.8)),
    ] {
        let (mut extrema, mut held) = (0, 0);
        let data = font_data();
        let font = FontOutlines::parse(&data).unwrap();
        let mut opts = options(scheme, shape.clone());
        opts.extremum_tangents = true;
        for ch in WORD.chars() {
            let drafted = draft(&font.glyph(ch).unwrap().path, &opts).unwrap();
            for piece in drafted.pieces().filter(|p| !p.fallback) {
                let segs = piece.spline.segments();
                let m = piece.anchors.len();
                for (i, a) in piece.anchors.iter().enumerate() {
                    extrema += usize::from(a.kind == AnchorKind::Extremum);
                    let Some(tan) = a.tangent else { continue };
                    held += usize::from(a.kind == AnchorKind::Extremum);
                    let d = match (piece.closed, i) {
                        (true, _) => segs[i].derivative(segs[i].t_max),
                        (false, 0) => segs[0].derivative(0.0),
                        (false, i) if i + 1 == m => segs[segs.len() - 1].derivative(1.0),
                        (false, i) => segs[i - 1].derivative(segs[i - 1].t_max),
                    };
                    let angle = tan.cross(d).atan2(tan.dot(d));
                    assert!(angle.abs() <= 1e-8, "{scheme:?}: off by {angle} rad");
                    if a.kind == AnchorKind::Extremum {
                        assert!(tan.x == 0.0 || tan.y == 0.0, "{scheme:?}: {tan:?}");
                    }
                }
            }
        }
        // Measured: κ 18 of 30, εκ-cubic 0.8 similar; the others' axes are too far from
        // the free curve's for a solution through the same anchors.
        println!("{scheme:?}: {held} of {extrema} extremum anchors hold their axis");
        assert!(held * 2 >= extrema, "{scheme:?}: {held} of {extrema}");
        let plain = draft(&font.glyph('o').unwrap().path, &options(scheme, shape)).unwrap();
        assert!(plain
            .pieces()
            .all(|p| p.anchors.iter().all(|a| a.tangent.is_none())));
    }
}
