//! A drafted glyph's κ source reopens as drafted: its documents, read back from JSON into
//! the editor, give the drafted curves without a solver iteration, whichever way the
//! drafting reached them.
#![cfg(all(feature = "font", feature = "serde"))]

use std::path::Path;

use kappa::editor::{Editor, PathDoc};
use kappa::glyph::{draft, hausdorff, DraftOptions, DraftShape, FontOutlines};
use kappa::Scheme;

fn font(name: &str) -> Vec<u8> {
    std::fs::read(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/fonts")
            .join(name),
    )
    .unwrap()
}

/// Drafts `chars` of `file` with the defaults for its em, reopens every contour's κ source
/// after a JSON round trip, and checks the reopened curve against the drafted one.
fn reopens(file: &str, chars: &str, scheme: Scheme) {
    let data = font(file);
    let outlines = FontOutlines::parse(&data).unwrap();
    let upem = outlines.units_per_em();
    let opts = DraftOptions::for_units_per_em(upem).with_scheme(scheme, DraftShape::Auto);
    let mut saved = 0;
    let mut pieces = 0;
    for ch in chars.chars() {
        let g = outlines.glyph(ch).unwrap();
        let drafted = draft(&g.path, &opts).unwrap();
        let docs = drafted.path_docs(scheme);
        assert_eq!(docs.len(), drafted.contours.len(), "{ch}");
        for (doc, contour) in docs.into_iter().zip(&drafted.contours) {
            let text = serde_json::to_string(&doc).unwrap();
            let back: PathDoc = serde_json::from_str(&text).unwrap();
            assert_eq!(back, doc, "{ch}: the JSON round trip keeps the document");
            saved += back.solution.iter().filter(|s| s.is_some()).count();
            // A straight piece (two anchors) has no unknowns to keep, nor a fallback one.
            pieces += contour
                .pieces
                .iter()
                .filter(|p| !p.fallback && (p.closed || p.anchors.len() > 2))
                .count();
            let (editor, change) = Editor::from_doc(back);
            assert!(editor.errors().is_empty(), "{ch}: {:?}", editor.errors());
            assert_eq!(change.iterations, 0, "{ch}: reopening iterates");
            let d = hausdorff(&editor.to_bezpath(), &contour.path, 64);
            // εκ-trig curves are drawn fitted (the draft's within `tolerance / 20`).
            let within = match scheme {
                Scheme::EkTrig => opts.tolerance / 10.0,
                _ => 1e-6 * upem,
            };
            assert!(d < within, "{ch}: reopened {d} units away");
        }
    }
    // Every other piece keeps the solution it was drafted with, also where the auto shape's
    // last re-solve failed and its answer is an earlier one.
    assert_eq!(saved, pieces, "{saved} of {pieces} pieces kept a solution");
}

#[test]
fn drafted_kappa_sources_reopen_as_drafted() {
    reopens("DejaVuSans.ttf", "aegsBRS&@3", Scheme::Kappa);
    reopens("EBGaramond12-Regular-subset.otf", "NGRx", Scheme::Kappa);
}

#[test]
fn drafted_ek_sources_reopen_as_drafted() {
    reopens("DejaVuSans.ttf", "aeS", Scheme::EkCubic);
    reopens("DejaVuSans.ttf", "oS", Scheme::EkTrig);
}
