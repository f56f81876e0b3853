//! The built-in drawings, by name.

use kappa::{builtin_design, Design, BUILTIN_DESIGNS};

use crate::failure::{Failure, Result};

/// The nine drawings of the εκ paper, in the order of [`BUILTIN_DESIGNS`].
pub const PAPER_DRAWINGS: [&str; 9] = [
    "bear", "bird", "deer", "dinosaur", "elephant", "plane", "pumpkin", "rabbit", "rose",
];

/// The first shapes a designer clicks (a wave and a symmetric S with inflections through
/// points, a curl on whole pixels, straight runs): solved, drawn and timed beside the
/// paper's drawings.
pub const DESIGNER_DRAWING: &str = "designer";

/// The drawings `kappa bench` times: the paper's, then the designer's.
pub fn bench_drawings() -> impl Iterator<Item = &'static str> {
    PAPER_DRAWINGS.into_iter().chain([DESIGNER_DRAWING])
}

/// The built-in drawing `name`, parsed.
pub fn load(name: &str) -> Result<Design> {
    let text = builtin_design(name).ok_or_else(|| {
        let names: Vec<&str> = BUILTIN_DESIGNS.iter().map(|(n, _)| *n).collect();
        Failure::new(format!(
            "no built-in drawing named '{name}' (available: {})",
            names.join(", ")
        ))
    })?;
    Design::from_json(text)
        .map_err(|e| Failure::new(format!("built-in drawing '{name}' is invalid: {e}")))
}
