//! Deterministic drawings of curves as SVG and PNG, and golden-image tests.
//!
//! Enabled by the `render` feature. A [`Scene`] collects layers — curves
//! ([`Scene::curve`]), input points, control polygons, curvature combs, or any
//! [`BezPath`](kurbo::BezPath) / point set with a [`Style`] or
//! [`PointStyle`] — fits them into the image and writes a standalone SVG
//! ([`Scene::to_svg`]). [`Scene::render`] rasterizes exactly that SVG with
//! resvg onto an opaque white [`Pixmap`], and [`hstack`] puts several
//! renders side by side.
//!
//! # Determinism
//!
//! The SVG text depends only on the scene (numbers are rounded to 1/1000 px
//! and printed in shortest form), and resvg/tiny-skia rasterize it with
//! integer and `f32` code whose SIMD path is chosen at compile time, so the
//! pixels are identical on every x86-64 machine built without
//! `-C target-cpu=native`. resvg is built without its `text` feature, and
//! scenes contain no text, so no system fonts are involved. Other
//! architectures (aarch64 with NEON) may differ in anti-aliased edge pixels
//! by a level or two, which the default [`Tolerance`](golden::Tolerance) of
//! one level per channel partly absorbs.
//!
//! # Golden images
//!
//! [`golden::check_golden`] compares a render with a reference PNG kept in
//! the repository:
//!
//! ```no_run
//! use kappa::render::{golden, Scene};
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! # let curve = kurbo::BezPath::new();
//! let pixmap = Scene::new().curve(&curve).render()?;
//! golden::check_golden(
//!     std::path::Path::new("tests/golden/my_curve.png"),
//!     &pixmap,
//!     golden::Tolerance::default(),
//! )?;
//! # Ok(())
//! # }
//! ```
//!
//! 1. The first time, the reference does not exist and the check fails with
//!    a message saying how to create it: run the tests with the environment
//!    variable `KAPPA_BLESS=1` ([`golden::BLESS_ENV`]), e.g.
//!    `KAPPA_BLESS=1 cargo test --features render`. Look at the new PNG
//!    before committing it.
//! 2. Later runs load the reference and [`golden::compare`] it with the new
//!    render. Two pixels are equal when no channel differs by more than
//!    [`Tolerance::channel`](golden::Tolerance::channel) (default 1); the
//!    check passes when at most
//!    [`Tolerance::max_bad_pixels`](golden::Tolerance::max_bad_pixels)
//!    (default 0) pixels differ and the sizes match.
//! 3. On failure, an `expected | diff | actual` image is written to
//!    `$CARGO_TARGET_DIR/golden-failures/<name>.png` (`target/` when the
//!    variable is unset), and the error names it along with the counts. In
//!    the diff panel, red pixels differ by more than the tolerance, orange
//!    ones by less, magenta ones exist in only one image, and the rest is a
//!    faded copy of the expected image.
//! 4. When a change is intended, re-run with `KAPPA_BLESS=1` to overwrite
//!    the references (files whose pixels are unchanged are not rewritten),
//!    and review the PNG diff in version control.

mod error;
pub mod golden;
mod label;
mod scene;
mod style;

pub use error::RenderError;
pub use label::TextAlign;
pub use resvg::tiny_skia::Pixmap;
pub use scene::Scene;
pub use style::{Color, PointStyle, Style};

/// Largest number of pixels in any image this module allocates (a scene, a
/// stack, a diff): 2²⁶ = 67,108,864, i.e. 256 MiB of RGBA. Larger requests
/// fail with [`RenderError::InvalidSize`] instead of exhausting memory.
pub const MAX_PIXELS: u64 = 1 << 26;

/// Width in pixels of the grey bars between the panels of a diff image.
const DIFF_GAP: u32 = 4;

/// A transparent pixmap of the given size, checked against [`MAX_PIXELS`].
fn pixmap_new(width: u64, height: u64) -> Result<Pixmap, RenderError> {
    let invalid = RenderError::InvalidSize { width, height };
    if width == 0 || height == 0 || width.saturating_mul(height) > MAX_PIXELS {
        return Err(invalid);
    }
    let (Ok(w), Ok(h)) = (u32::try_from(width), u32::try_from(height)) else {
        return Err(invalid);
    };
    Pixmap::new(w, h).ok_or(invalid)
}

/// Places `images` side by side, top-aligned, left to right, with `gap_px`
/// pixels between neighbours, on an opaque white background. Translucent
/// pixels are composited over white, so the result is opaque.
///
/// The result is `Σ width + gap_px × (n − 1)` wide and as tall as the
/// tallest image. This is how a gallery shows variants of one drawing.
///
/// # Errors
///
/// [`RenderError::NoImages`] for an empty slice, and
/// [`RenderError::InvalidSize`] if the result would exceed [`MAX_PIXELS`].
pub fn hstack(images: &[Pixmap], gap_px: u32) -> Result<Pixmap, RenderError> {
    let refs: Vec<&Pixmap> = images.iter().collect();
    stack(&refs, gap_px, Color::WHITE)
}

/// [`hstack`] over references, with an opaque `background` colour.
fn stack(images: &[&Pixmap], gap: u32, background: Color) -> Result<Pixmap, RenderError> {
    if images.is_empty() {
        return Err(RenderError::NoImages);
    }
    let gaps = u64::from(gap) * (images.len() as u64 - 1);
    let width = images
        .iter()
        .map(|p| u64::from(p.width()))
        .fold(gaps, u64::saturating_add);
    let height = images.iter().map(|p| p.height()).max().unwrap_or(0);
    let mut out = pixmap_new(width, u64::from(height))?;
    let bg = [background.r, background.g, background.b, 255];
    for px in out.data_mut().chunks_exact_mut(4) {
        px.copy_from_slice(&bg);
    }
    let mut x = 0usize;
    for image in images {
        blit_over(&mut out, image, x, bg);
        x += image.width() as usize + gap as usize;
    }
    Ok(out)
}

/// Composites `src` (premultiplied RGBA) at column `x0`, row 0 of `dst`, over
/// the opaque background colour `bg`: `out = src + bg × (1 − α)`, rounded.
/// Opaque pixels are copied exactly.
fn blit_over(dst: &mut Pixmap, src: &Pixmap, x0: usize, bg: [u8; 4]) {
    let dst_w = dst.width() as usize;
    let src_w = src.width() as usize;
    let data = dst.data_mut();
    for (y, row) in src.data().chunks_exact(4 * src_w).enumerate() {
        let start = 4 * (y * dst_w + x0);
        let out = &mut data[start..start + 4 * src_w];
        for (o, s) in out.chunks_exact_mut(4).zip(row.chunks_exact(4)) {
            let inv = 255 - u32::from(s[3]);
            for c in 0..3 {
                o[c] = (u32::from(s[c]) + div255(u32::from(bg[c]) * inv)) as u8;
            }
            o[3] = 255;
        }
    }
}

/// `x / 255` rounded to nearest, for `x ≤ 255 × 255`.
fn div255(x: u32) -> u32 {
    (x + 127) / 255
}
