//! The error type of rendering and PNG input/output.

use std::path::PathBuf;

use super::MAX_PIXELS;

/// An error from building, rendering, encoding or loading an image.
///
/// Nothing in [`render`](super) panics on bad input: invalid scenes, bad
/// files and oversized images all end up here.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// An image would have a zero side or more than [`MAX_PIXELS`] pixels.
    #[error(
        "invalid image size {width}x{height} px: both sides must be positive \
         and the area at most {MAX_PIXELS} pixels"
    )]
    InvalidSize {
        /// Requested width in pixels.
        width: u64,
        /// Requested height in pixels.
        height: u64,
    },
    /// The margin is negative, not finite, or leaves no room for drawing.
    #[error(
        "invalid margin {margin} px: it must be finite, non-negative and \
         smaller than half of each side of the {width}x{height} px image"
    )]
    InvalidMargin {
        /// The margin in pixels.
        margin: f64,
        /// Image width in pixels.
        width: u32,
        /// Image height in pixels.
        height: u32,
    },
    /// The explicit view box, or the bounds of the content when the view box
    /// is fitted, is not finite or has no positive side.
    #[error(
        "invalid view box ({}, {})-({}, {}): it must be finite and have a \
         positive width or height (an explicit view box needs both)",
        view_box.x0, view_box.y0, view_box.x1, view_box.y1
    )]
    InvalidViewBox {
        /// The offending rectangle, in drawing coordinates.
        view_box: kurbo::Rect,
    },
    /// A layer has a NaN or infinite coordinate, or one that overflows when
    /// mapped to pixels.
    #[error("layer {layer} ({kind}) has a non-finite coordinate (NaN, infinite or out of range)")]
    NonFinite {
        /// Index of the layer, in the order the layers were added.
        layer: usize,
        /// Kind of layer: `"path"`, `"polygon"` or `"points"`.
        kind: &'static str,
    },
    /// A layer's style cannot be drawn (negative width, NaN radius, ...).
    #[error("layer {layer} ({kind}) has an invalid style: {reason}")]
    InvalidStyle {
        /// Index of the layer, in the order the layers were added.
        layer: usize,
        /// Kind of layer: `"path"`, `"polygon"` or `"points"`.
        kind: &'static str,
        /// What is wrong.
        reason: &'static str,
    },
    /// [`hstack`](super::hstack) was given no images.
    #[error("no images to stack")]
    NoImages,
    /// usvg rejected the generated SVG (for example, more than a million
    /// elements).
    #[error("usvg rejected the generated SVG: {0}")]
    Svg(#[from] resvg::usvg::Error),
    /// A file could not be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// A file is not a PNG that tiny-skia can decode (8-bit or less per
    /// channel, not indexed with more than 8 bits...).
    #[error("{path} is not a readable PNG: {source}")]
    PngDecode {
        /// The file.
        path: PathBuf,
        /// The decoder's error.
        #[source]
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// PNG encoding failed.
    #[error("cannot encode PNG: {0}")]
    PngEncode(#[source] Box<dyn std::error::Error + Send + Sync>),
}
