//! Glyph drafting benchmarks: draft and export all 52 ASCII letters of the vendored DejaVu
//! Sans (import excluded), as κ-curves (export: TrueType quadratics, exact) and as auto-shaped
//! εκ-cubic curves (export: quadratics within 0.5 font units); κ-curves with the fairing and
//! with the simplification pass; and the compiled test font. A whole CFF font: every glyph
//! of the vendored EB Garamond subset (190 drawn glyphs) drafted as κ-curves, written with
//! the anchors as nodes and rebuilt as a TrueType font (what `kappa font` does).
//!
//! Run with `cargo bench --all-features --bench glyph`.

use criterion::{criterion_group, criterion_main, Criterion};
use kappa::glyph::{
    anchor_outline, compile_font, draft, drawn_glyph_ids, rebuild_ttf, to_quadratic, DraftOptions,
    DraftShape, FontGlyph, FontOutlines, RebuildOptions,
};
use kappa::Scheme;
use std::collections::HashMap;
use std::hint::black_box;

fn letters() -> Vec<(char, kurbo::BezPath, f64)> {
    let data = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fonts/DejaVuSans.ttf"
    ))
    .unwrap();
    let font = FontOutlines::parse(&data).unwrap();
    ('A'..='Z')
        .chain('a'..='z')
        .map(|ch| {
            let g = font.glyph(ch).unwrap();
            (ch, g.path, g.advance)
        })
        .collect()
}

fn draft_export(letters: &[(char, kurbo::BezPath, f64)], options: &DraftOptions) -> Vec<FontGlyph> {
    letters
        .iter()
        .map(|(ch, path, advance)| {
            let d = draft(path, options).unwrap();
            FontGlyph {
                name: ch.to_string(),
                ch: *ch,
                path: to_quadratic(&d.path, 0.5).unwrap().path,
                advance: *advance,
            }
        })
        .collect()
}

fn glyphs(c: &mut Criterion) {
    let letters = letters();
    let mut g = c.benchmark_group("glyph_52_letters");
    g.sample_size(10);
    for (label, scheme, shape, fair, simplify) in [
        ("kappa", Scheme::Kappa, DraftShape::Neutral, false, false),
        (
            "ek_cubic_auto",
            Scheme::EkCubic,
            DraftShape::Auto,
            false,
            false,
        ),
        (
            "kappa_fair",
            Scheme::Kappa,
            DraftShape::Neutral,
            true,
            false,
        ),
        (
            "kappa_simplify",
            Scheme::Kappa,
            DraftShape::Neutral,
            false,
            true,
        ),
    ] {
        let mut options = DraftOptions::for_units_per_em(2048.0).with_scheme(scheme, shape);
        options.fair = fair;
        options.simplify = simplify;
        g.bench_function(format!("draft_export_{label}"), |b| {
            b.iter(|| black_box(draft_export(black_box(&letters), &options)))
        });
    }
    let done = draft_export(&letters, &DraftOptions::for_units_per_em(2048.0));
    g.bench_function("compile_font_kappa", |b| {
        b.iter(|| black_box(compile_font("", 2048, 1901, -483, black_box(&done)).unwrap()))
    });
    g.finish();
}

/// Every drawn glyph of a CFF font drafted, written with its anchors as nodes, and the font
/// rebuilt as TrueType.
fn whole_font(c: &mut Criterion) {
    let data = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fonts/EBGaramond12-Regular-subset.otf"
    ))
    .unwrap();
    let mut g = c.benchmark_group("font");
    g.sample_size(10);
    g.bench_function("garamond_subset_kappa_ttf", |b| {
        b.iter(|| {
            let font = FontOutlines::parse(&data).unwrap();
            let options = DraftOptions::for_units_per_em(font.units_per_em());
            let mut replaced = HashMap::new();
            for id in drawn_glyph_ids(&data).unwrap() {
                let outline = font.outline(id).unwrap();
                if let Ok(d) = draft(&outline, &options) {
                    let nodes = anchor_outline(&d, &outline, 0.1, options.tolerance);
                    replaced.insert(id, nodes.path);
                }
            }
            black_box(rebuild_ttf(&data, &replaced, &RebuildOptions::default()).unwrap())
        })
    });
    g.finish();
}

criterion_group!(benches, glyphs, whole_font);
criterion_main!(benches);
