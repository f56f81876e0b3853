//! Golden images of the εκ paper's figures (Figs. 6, 8, 9): the bird, the bear and the
//! elephant as κ-curves beside εκ-curves with a = 0.75, 0.85, 0.95, with curvature combs;
//! and its Fig. 11 layout (κ, εκ-cubic 0.75 and 0.9, εκ-trig 0.55, 0.6, 0.75 and 0.9) for
//! two drawings.
//!
//! References live in `tests/golden/`; re-bless with `KAPPA_BLESS=1 cargo test --all-features
//! --test golden_figures` after an intended change, and look at the new PNGs before committing.
//! On a mismatch, `target/golden-failures/<name>.png` shows expected | diff | actual.

use kappa::gallery::{paper_figure, variant_figure, TRIG_VARIANTS};
use kappa::render::golden::{check_golden, Tolerance};
use kappa::{builtin_design, Design};
use std::path::Path;

fn figure(name: &str) {
    let design = Design::from_json(builtin_design(name).unwrap()).unwrap();
    let image = paper_figure(&design, 300).unwrap();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/golden/fig-{name}.png"));
    if let Err(e) = check_golden(&path, &image, Tolerance::DEFAULT) {
        panic!("{e}");
    }
}

#[test]
fn golden_bear_fig8() {
    figure("bear");
}

#[test]
fn golden_elephant_fig9() {
    figure("elephant");
}

#[test]
fn golden_bird_fig6() {
    figure("bird");
}

fn trig_figure(name: &str) {
    let design = Design::from_json(builtin_design(name).unwrap()).unwrap();
    let image = variant_figure(&design, &TRIG_VARIANTS, 200).unwrap();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/golden/trig-{name}.png"));
    if let Err(e) = check_golden(&path, &image, Tolerance::DEFAULT) {
        panic!("{e}");
    }
}

#[test]
fn golden_trig_closed() {
    trig_figure("eps-ClosedEkcurveKTM1");
}

#[test]
fn golden_trig_rose() {
    trig_figure("rose");
}
