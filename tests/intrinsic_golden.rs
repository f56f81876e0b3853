//! Golden images of the intrinsic curves: seed 003's Fig. 2 (one G1 problem, six curvature
//! profiles, with combs) and Fig. 4 (the viable region of monotone G2 segments for degrees 3,
//! 5 and 10).
//!
//! Re-bless with `KAPPA_BLESS=1 cargo test --all-features --test intrinsic_golden` after an
//! intended change, and look at the new PNGs before committing.
#![cfg(feature = "render")]

use kappa::intrinsic::picture::{variety_figure, viable_figure};
use kappa::render::golden::{check_golden, Tolerance};
use kappa::render::Pixmap;
use std::path::Path;

fn check(name: &str, image: &Pixmap) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/golden/{name}.png"));
    if let Err(e) = check_golden(&path, image, Tolerance::DEFAULT) {
        panic!("{e}");
    }
}

#[test]
fn golden_intrinsic_variety_fig2() {
    check("intrinsic-variety", &variety_figure(200).unwrap());
}

#[test]
fn golden_intrinsic_viable_fig4() {
    check("intrinsic-viable", &viable_figure(240, 41).unwrap());
}
