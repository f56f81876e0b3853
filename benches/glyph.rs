//! Glyph drafting benchmarks: draft and export all 52 ASCII letters of the vendored DejaVu
//! Sans (import excluded), as κ-curves (export: TrueType quadratics, exact) and as auto-shaped
//! εκ-cubic curves (export: quadratics within 0.5 font units); κ-curves with the fairing and
//! with the simplification pass; and the compiled test font.
//!
//! Run with `cargo bench --all-features --bench glyph`.

use criterion::{criterion_group, criterion_main, Criterion};
use kappa::glyph::{
    compile_font, draft, to_quadratic, DraftOptions, DraftShape, FontGlyph, FontOutlines,
};
use kappa::Scheme;
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

criterion_group!(benches, glyphs);
criterion_main!(benches);
