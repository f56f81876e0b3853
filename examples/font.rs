//! Drafts the letters of "Sample" in the vendored EB Garamond subset (a CFF font) as
//! auto-shaped εκ-cubic curves with the anchors as the nodes, and writes the whole font
//! back as TrueType and as a UFO source: what `kappa font` does, through the library.
//!
//! Run with `cargo run --release --features font --example font [OUT_DIR]` (default
//! `target/font-example`).

use std::collections::HashMap;
use std::path::PathBuf;

use kappa::glyph::{
    anchor_outline, draft, rebuild_ttf, rebuild_ufo, DraftOptions, DraftShape, FontOutlines,
    RebuildOptions,
};
use kappa::Scheme;

fn main() -> Result<(), kappa::Error> {
    let io = |e: std::io::Error| kappa::Error::Font(e.to_string());
    let data = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fonts/EBGaramond12-Regular-subset.otf"
    ))
    .map_err(io)?;
    let font = FontOutlines::parse(&data)?;
    let options = DraftOptions::for_units_per_em(font.units_per_em())
        .with_scheme(Scheme::EkCubic, DraftShape::Auto);
    let mut replaced = HashMap::new();
    for ch in "Sample".chars() {
        let id = font.glyph_id(ch).ok_or(kappa::Error::MissingGlyph { ch })?;
        let outline = font.outline(id)?;
        let drafted = draft(&outline, &options)?;
        // The anchors become the nodes, extremum tangents horizontal or vertical.
        let nodes = anchor_outline(&drafted, &outline, 0.1, options.tolerance);
        println!(
            "{ch}: {} anchors, Hausdorff {:.2} units, {} tangents set, written within {:.2} of the draft",
            drafted.anchor_count(),
            drafted.hausdorff.unwrap_or(0.0),
            nodes.snapped,
            nodes.max_error
        );
        replaced.insert(id, nodes.path);
    }
    let dir = std::env::args()
        .nth(1)
        .map_or_else(|| PathBuf::from("target/font-example"), PathBuf::from);
    std::fs::create_dir_all(&dir).map_err(io)?;
    let rebuild = RebuildOptions {
        family: "Kappa Example".into(),
        ..RebuildOptions::default()
    };
    let ttf = rebuild_ttf(&data, &replaced, &rebuild)?;
    std::fs::write(dir.join("example.ttf"), ttf).map_err(io)?;
    rebuild_ufo(
        &data,
        &replaced,
        &HashMap::new(),
        &rebuild,
        &dir.join("example.ufo"),
    )?;
    println!("wrote {}", dir.display());
    Ok(())
}
