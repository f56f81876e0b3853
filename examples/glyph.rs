//! Drafts the letters of "Sample" from the vendored DejaVu Sans as κ-curves and εκ-curves
//! with auto shapes, and prints for each the anchors a designer places against the original's
//! on-curve points and the Hausdorff distance in font units.
//!
//! Run with `cargo run --release --features font --example glyph`.

use kappa::glyph::{draft, DraftOptions, DraftShape, FontOutlines};
use kappa::Scheme;

fn main() -> Result<(), kappa::Error> {
    let data = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fonts/DejaVuSans.ttf"
    ))
    .map_err(|e| kappa::Error::Font(e.to_string()))?;
    let font = FontOutlines::parse(&data)?;
    let mut base = DraftOptions::for_units_per_em(font.units_per_em());
    if let Some(t) = std::env::args().nth(1).and_then(|a| a.parse::<f64>().ok()) {
        base.tolerance = t * font.units_per_em();
    }
    println!(
        "units per em {}, tolerance {} units",
        font.units_per_em(),
        base.tolerance
    );
    for (scheme, shape) in [
        (Scheme::Kappa, DraftShape::Neutral),
        (Scheme::EkCubic, DraftShape::Auto),
        (Scheme::EkTrig, DraftShape::Auto),
    ] {
        println!("{scheme:?} {shape:?}");
        let options = base.clone().with_scheme(scheme, shape.clone());
        let mut word = Vec::new();
        for ch in "Sample".chars() {
            let glyph = font.glyph(ch)?;
            let drafted = draft(&glyph.path, &options)?;
            word.push((glyph.clone(), drafted.clone()));
            println!(
                "  {ch}: {:2} anchors for {:2} on-curve points ({} with implied ones), Hausdorff {:5.2} units, {} segments",
                drafted.anchor_count(),
                drafted.original_on_curve(),
                glyph.path.segments().count(),
                drafted.hausdorff.unwrap_or(f64::NAN),
                drafted.segment_count(),
            );
        }
        #[cfg(feature = "render")]
        {
            let mut x = 0.0;
            let placed: Vec<_> = word
                .iter()
                .map(|(g, d)| {
                    let p = kappa::glyph::PlacedGlyph {
                        original: &g.path,
                        drafted: d,
                        offset: kurbo::Vec2::new(x, 0.0),
                    };
                    x += g.advance;
                    p
                })
                .collect();
            let scene = kappa::glyph::word_scene(&placed, font.units_per_em(), 1600, 420, None);
            let out = std::env::temp_dir().join(format!("glyph-{scheme:?}.png"));
            if let Ok(png) = scene.render_png() {
                let _ = std::fs::write(&out, png);
                println!("  wrote {}", out.display());
            }
        }
        let _ = &word;
    }
    Ok(())
}
