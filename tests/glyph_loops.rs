//! A held tangent is not met by a loop: drafted with the original's axis held at its
//! extremum anchors, no κ segment of EB Garamond's `₂` runs back on itself.
#![cfg(feature = "font")]

use std::path::Path;

use kappa::glyph::{draft, DraftOptions, FontOutlines};

#[test]
fn a_held_extremum_tangent_does_not_loop() {
    let data = std::fs::read(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fonts/EBGaramond12-Regular.otf"),
    )
    .unwrap();
    let font = FontOutlines::parse(&data).unwrap();
    let glyph = font.glyph('₂').unwrap();
    let mut options = DraftOptions::for_units_per_em(font.units_per_em());
    options.extremum_tangents = true;
    // The tolerance `kappa font` drafts to for TrueType output (4 units, less the
    // quadratic conversion's 0.5 and half a grid diagonal).
    options.tolerance = 4.0 - 0.5 - 0.5 * core::f64::consts::SQRT_2;
    let drafted = draft(&glyph.path, &options).unwrap();
    assert!(drafted.within_tolerance(), "{:?}", drafted.hausdorff);
    let mut worst: f64 = 0.0;
    for contour in &drafted.contours {
        for piece in &contour.pieces {
            for seg in piece.spline.segments() {
                let (a, b) = (seg.q[1] - seg.q[0], seg.q[2] - seg.q[1]);
                if a.hypot2() > 0.0 && b.hypot2() > 0.0 {
                    worst = worst.max(a.cross(b).atan2(a.dot(b)).abs().to_degrees());
                }
            }
        }
    }
    // Held at (151, -166) by running back 6 units and on again, two segments had turned by
    // 172° each; the glyph's tightest real turn in one segment is far less.
    assert!(worst < 150.0, "a segment turns by {worst}°");
}
