//! Golden-image comparison: check renders against reference PNGs.
//!
//! See the [module docs](super#golden-images) for the workflow. In short:
//! [`check_golden`] compares with a reference file, writes
//! `expected | diff | actual` to `target/golden-failures/` on failure, and
//! (re)writes the reference when the environment variable `KAPPA_BLESS=1`
//! ([`BLESS_ENV`]) is set.
//!
//! Pixels are compared as stored by tiny-skia: premultiplied RGBA. For the
//! opaque images that [`Scene::render`](super::Scene::render) produces this
//! is plain RGBA.

use std::fmt;
use std::path::{Path, PathBuf};

use super::{pixmap_new, stack, Color, Pixmap, RenderError, DIFF_GAP};

/// The environment variable that makes [`check_golden`] write references:
/// `KAPPA_BLESS=1`. Any value other than empty, `0` or `false` counts.
pub const BLESS_ENV: &str = "KAPPA_BLESS";

/// Diff colour of pixels that differ by more than the tolerance.
const BAD: [u8; 4] = [255, 0, 0, 255];
/// Diff colour of pixels that differ, but within the tolerance.
const NEAR: [u8; 4] = [255, 165, 0, 255];
/// Diff colour of pixels that exist in only one image.
const MISSING: [u8; 4] = [255, 0, 255, 255];
/// Colour of the bars between the panels of a diff image.
const GAP_COLOR: Color = Color::rgb(128, 128, 128);

/// How different two images may be and still count as equal.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Tolerance {
    /// Largest absolute difference of any channel (0–255) for which two
    /// pixels still count as equal. Default 1.
    pub channel: u8,
    /// Number of unequal pixels that is still a pass. Default 0.
    pub max_bad_pixels: usize,
}

impl Tolerance {
    /// Pixel-exact: no difference at all.
    pub const EXACT: Tolerance = Tolerance::new(0, 0);
    /// The default: channels may differ by 1, no pixel may differ more.
    pub const DEFAULT: Tolerance = Tolerance::new(1, 0);

    /// A tolerance of `channel` levels per channel and `max_bad_pixels`
    /// unequal pixels.
    pub const fn new(channel: u8, max_bad_pixels: usize) -> Tolerance {
        Tolerance {
            channel,
            max_bad_pixels,
        }
    }
}

impl Default for Tolerance {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The result of [`compare`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Comparison {
    /// Pixels that differ by more than the tolerance, plus, when the sizes
    /// differ, the pixels that exist in only one image (over the bounding
    /// box of both, anchored at the top-left corner).
    pub bad_pixels: usize,
    /// Pixels compared: the area of the bounding box of both images.
    pub total_pixels: usize,
    /// Largest channel difference found (255 when the sizes differ).
    pub max_channel_diff: u8,
    /// `Some(((expected_w, expected_h), (actual_w, actual_h)))` when the
    /// sizes differ.
    pub size_mismatch: Option<((u32, u32), (u32, u32))>,
    /// Smallest rectangle `(x0, y0, x1, y1)` (ends exclusive) holding all
    /// bad pixels, if any.
    pub bad_region: Option<(u32, u32, u32, u32)>,
    /// The tolerance used.
    pub tolerance: Tolerance,
}

impl Comparison {
    /// Whether the images count as equal: same size, and at most
    /// `tolerance.max_bad_pixels` bad pixels.
    pub fn passed(&self) -> bool {
        self.size_mismatch.is_none() && self.bad_pixels <= self.tolerance.max_bad_pixels
    }
}

impl fmt::Display for Comparison {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(((ew, eh), (aw, ah))) = self.size_mismatch {
            write!(f, "size mismatch: expected {ew}x{eh}, actual {aw}x{ah}; ")?;
        }
        write!(
            f,
            "{} of {} pixels differ by more than {} (allowed: {}), max channel difference {}",
            self.bad_pixels,
            self.total_pixels,
            self.tolerance.channel,
            self.tolerance.max_bad_pixels,
            self.max_channel_diff
        )?;
        if let Some((x0, y0, x1, y1)) = self.bad_region {
            write!(f, ", in x {x0}..{x1}, y {y0}..{y1}")?;
        }
        Ok(())
    }
}

/// An error from [`check_golden`].
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GoldenError {
    /// The reference does not exist and blessing was not requested.
    #[error(
        "reference image {path} does not exist; run the test with {BLESS_ENV}=1 \
         to create it (then look at it before committing)"
    )]
    MissingReference {
        /// The reference file.
        path: PathBuf,
    },
    /// The reference exists but cannot be read or decoded.
    #[error("cannot load reference image: {0}")]
    Reference(#[source] RenderError),
    /// The render differs from the reference.
    #[error(
        "golden image mismatch for {path}: {comparison}; {}; if the change is \
         intended, re-run with {BLESS_ENV}=1",
        describe_failure_image(.failure_image)
    )]
    Mismatch {
        /// The reference file.
        path: PathBuf,
        /// The counts (boxed to keep the error small).
        comparison: Box<Comparison>,
        /// Where `expected | diff | actual` was written, if writing worked.
        failure_image: Option<PathBuf>,
    },
    /// The reference could not be written while blessing.
    #[error("cannot write reference image {path}: {source}")]
    Write {
        /// The reference file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// The render could not be encoded as PNG while blessing.
    #[error("cannot encode reference image: {0}")]
    Encode(#[source] RenderError),
}

fn describe_failure_image(path: &Option<PathBuf>) -> String {
    match path {
        Some(path) => format!("expected | diff | actual written to {}", path.display()),
        None => "the expected | diff | actual image could not be written".to_owned(),
    }
}

/// Compares two images pixel by pixel with tolerance `tol`. Never fails:
/// images of different sizes are compared over their overlap, and every
/// pixel present in only one of them is bad.
pub fn compare(expected: &Pixmap, actual: &Pixmap, tol: Tolerance) -> Comparison {
    let (ew, eh) = (expected.width(), expected.height());
    let (aw, ah) = (actual.width(), actual.height());
    let (w, h) = (ew.max(aw), eh.max(ah));
    let mut bad_pixels = 0usize;
    let mut max_channel_diff = 0u8;
    let mut region: Option<(u32, u32, u32, u32)> = None;
    for y in 0..h {
        for x in 0..w {
            let (diff, bad) = match (pixel(expected, x, y), pixel(actual, x, y)) {
                (Some(e), Some(a)) => {
                    let diff = channel_diff(e, a);
                    (diff, diff > tol.channel)
                }
                _ => (u8::MAX, true),
            };
            max_channel_diff = max_channel_diff.max(diff);
            if bad {
                bad_pixels += 1;
                region = Some(match region {
                    None => (x, y, x + 1, y + 1),
                    Some((x0, y0, x1, y1)) => (x0.min(x), y0.min(y), x1.max(x + 1), y1.max(y + 1)),
                });
            }
        }
    }
    Comparison {
        bad_pixels,
        total_pixels: w as usize * h as usize,
        max_channel_diff,
        size_mismatch: ((ew, eh) != (aw, ah)).then_some(((ew, eh), (aw, ah))),
        bad_region: region,
        tolerance: tol,
    }
}

/// The RGBA bytes of pixel `(x, y)`, if inside the image.
fn pixel(image: &Pixmap, x: u32, y: u32) -> Option<[u8; 4]> {
    if x >= image.width() || y >= image.height() {
        return None;
    }
    let i = 4 * (y as usize * image.width() as usize + x as usize);
    let d = image.data();
    Some([d[i], d[i + 1], d[i + 2], d[i + 3]])
}

fn channel_diff(e: [u8; 4], a: [u8; 4]) -> u8 {
    e.iter()
        .zip(a)
        .map(|(&e, a)| e.abs_diff(a))
        .max()
        .unwrap_or(0)
}

/// `expected | diff | actual` side by side, separated by grey bars, marking
/// every differing pixel: [`diff_image_with`] at [`Tolerance::EXACT`].
///
/// # Errors
///
/// [`RenderError::InvalidSize`] if the result would exceed
/// [`MAX_PIXELS`](super::MAX_PIXELS).
pub fn diff_image(expected: &Pixmap, actual: &Pixmap) -> Result<Pixmap, RenderError> {
    diff_image_with(expected, actual, Tolerance::EXACT)
}

/// `expected | diff | actual` side by side, separated by grey bars. The
/// diff panel covers both images (anchored top-left); in it, pixels that
/// differ by more than `tol.channel` are red, pixels that differ by less are
/// orange, pixels present in only one image are magenta, and the rest show
/// the expected image faded to a quarter of its contrast.
///
/// # Errors
///
/// [`RenderError::InvalidSize`] if the result would exceed
/// [`MAX_PIXELS`](super::MAX_PIXELS).
pub fn diff_image_with(
    expected: &Pixmap,
    actual: &Pixmap,
    tol: Tolerance,
) -> Result<Pixmap, RenderError> {
    let w = expected.width().max(actual.width());
    let h = expected.height().max(actual.height());
    let mut diff = pixmap_new(u64::from(w), u64::from(h))?;
    let data = diff.data_mut();
    for y in 0..h {
        for x in 0..w {
            let out = match (pixel(expected, x, y), pixel(actual, x, y)) {
                (Some(e), Some(a)) => match channel_diff(e, a) {
                    0 => faded(e),
                    d if d <= tol.channel => NEAR,
                    _ => BAD,
                },
                _ => MISSING,
            };
            let i = 4 * (y as usize * w as usize + x as usize);
            data[i..i + 4].copy_from_slice(&out);
        }
    }
    stack(&[expected, &diff, actual], DIFF_GAP, GAP_COLOR)
}

/// A premultiplied pixel composited over white and blended 3:1 with white.
fn faded(p: [u8; 4]) -> [u8; 4] {
    let inv = 255 - u32::from(p[3]);
    let mut out = [255u8; 4];
    for c in 0..3 {
        let over_white = u32::from(p[c]) + (255 * inv + 127) / 255;
        out[c] = ((over_white + 3 * 255 + 2) / 4) as u8;
    }
    out
}

/// Loads a PNG file into a premultiplied pixmap.
///
/// # Errors
///
/// [`RenderError::Io`] if the file cannot be read, and
/// [`RenderError::PngDecode`] if it is not a PNG tiny-skia can decode.
pub fn load_png(path: &Path) -> Result<Pixmap, RenderError> {
    let bytes = std::fs::read(path).map_err(|source| RenderError::Io {
        path: path.to_owned(),
        source,
    })?;
    Pixmap::decode_png(&bytes).map_err(|source| RenderError::PngDecode {
        path: path.to_owned(),
        source: Box::new(source),
    })
}

/// Whether [`BLESS_ENV`] asks for references to be written: it is set to
/// anything but empty, `0` or `false`.
pub fn bless_requested() -> bool {
    match std::env::var(BLESS_ENV) {
        Ok(v) => {
            let v = v.trim();
            !(v.is_empty() || v == "0" || v.eq_ignore_ascii_case("false"))
        }
        Err(_) => false,
    }
}

/// The directory failure images go to: `$CARGO_TARGET_DIR/golden-failures`,
/// or `target/golden-failures` (relative to the current directory, which is
/// the package root under `cargo test`) when the variable is unset.
pub fn failure_dir() -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .filter(|v| !v.is_empty())
        .map_or_else(|| PathBuf::from("target"), PathBuf::from);
    target.join("golden-failures")
}

/// Checks `actual` against the reference PNG at `path`, blessing if
/// [`bless_requested`]: [`check_golden_with`]`(path, actual, tol,
/// bless_requested())`.
///
/// # Errors
///
/// See [`check_golden_with`].
pub fn check_golden(path: &Path, actual: &Pixmap, tol: Tolerance) -> Result<(), GoldenError> {
    check_golden_with(path, actual, tol, bless_requested())
}

/// Checks `actual` against the reference PNG at `path`.
///
/// With `bless`, writes `actual` as the reference (creating directories)
/// unless the existing reference has exactly the same pixels, and succeeds.
/// Otherwise compares with [`compare`]; on failure writes
/// [`diff_image_with`] to `<failure_dir()>/<file stem of path>.png` (see
/// [`failure_dir`]).
///
/// # Errors
///
/// - [`GoldenError::MissingReference`] if the reference does not exist (the
///   message says to set `KAPPA_BLESS=1`);
/// - [`GoldenError::Reference`] if it cannot be read or is not a PNG;
/// - [`GoldenError::Mismatch`] if the comparison fails, naming the failure
///   image and the counts;
/// - [`GoldenError::Write`] or [`GoldenError::Encode`] if blessing cannot
///   write the reference.
pub fn check_golden_with(
    path: &Path,
    actual: &Pixmap,
    tol: Tolerance,
    bless: bool,
) -> Result<(), GoldenError> {
    if bless {
        if let Ok(existing) = load_png(path) {
            if compare(&existing, actual, Tolerance::EXACT).passed() {
                return Ok(());
            }
        }
        return write_png(path, actual);
    }
    let expected = match load_png(path) {
        Ok(expected) => expected,
        Err(RenderError::Io { source, .. }) if source.kind() == std::io::ErrorKind::NotFound => {
            return Err(GoldenError::MissingReference {
                path: path.to_owned(),
            })
        }
        Err(e) => return Err(GoldenError::Reference(e)),
    };
    let comparison = compare(&expected, actual, tol);
    if comparison.passed() {
        return Ok(());
    }
    let stem = path
        .file_stem()
        .filter(|s| !s.is_empty())
        .map_or_else(|| "golden".into(), |s| s.to_string_lossy().into_owned());
    let failure = failure_dir().join(format!("{stem}.png"));
    let written = diff_image_with(&expected, actual, tol)
        .ok()
        .and_then(|image| write_png(&failure, &image).ok());
    Err(GoldenError::Mismatch {
        path: path.to_owned(),
        comparison: Box::new(comparison),
        failure_image: written.map(|()| failure),
    })
}

fn write_png(path: &Path, image: &Pixmap) -> Result<(), GoldenError> {
    let bytes = image
        .encode_png()
        .map_err(|e| GoldenError::Encode(RenderError::PngEncode(Box::new(e))))?;
    let write = |source| GoldenError::Write {
        path: path.to_owned(),
        source,
    };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(write)?;
    }
    std::fs::write(path, bytes).map_err(write)
}
