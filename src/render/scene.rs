//! A scene of layers, written as SVG and rendered with resvg.

use std::fmt::Write as _;

use kurbo::{Affine, BezPath, ParamCurveExtrema, PathEl, Point, Rect, Vec2};
use resvg::tiny_skia::Pixmap;
use resvg::usvg;

use super::label::{text_outline, TextAlign};
use super::{pixmap_new, Color, PointStyle, RenderError, Style, MAX_PIXELS};

/// Coordinates and lengths in the SVG are rounded to `1 / SVG_PRECISION` px.
///
/// A thousandth of a pixel is far below what anti-aliasing can show, keeps
/// the SVG short, and absorbs last-bit differences in the input (from a
/// different libm, say) so that golden images stay stable.
const SVG_PRECISION: f64 = 1000.0;

/// Values at least this large are not rounded: `x * SVG_PRECISION` could
/// overflow, and they are far outside any image anyway.
const ROUNDING_LIMIT: f64 = 1e12;

#[derive(Clone, Debug)]
enum Layer {
    Path {
        path: BezPath,
        style: Style,
        kind: &'static str,
    },
    Points {
        points: Vec<Point>,
        style: PointStyle,
    },
    /// Text outlines, already in pixel coordinates (not moved by the view).
    Label { path: BezPath, color: Color },
}

impl Layer {
    fn kind(&self) -> &'static str {
        match self {
            Layer::Path { kind, .. } => kind,
            Layer::Points { .. } => "points",
            Layer::Label { .. } => "label",
        }
    }

    /// Tight bounds of what the layer draws, ignoring stroke width and dot
    /// radius (the margin is there for those).
    fn bounds(&self) -> Option<Rect> {
        match self {
            Layer::Path { path, .. } => path
                .segments()
                .map(|seg| seg.bounding_box())
                .reduce(|a, b| a.union(b)),
            Layer::Points { points, .. } => points
                .iter()
                .map(|&p| Rect::from_points(p, p))
                .reduce(|a, b| a.union(b)),
            // Labels sit in the image's pixels, not in the drawing.
            Layer::Label { .. } => None,
        }
    }

    fn check(&self, layer: usize) -> Result<(), RenderError> {
        let kind = self.kind();
        let (finite, problem) = match self {
            Layer::Path { path, style, .. } => (path.is_finite(), style.problem()),
            Layer::Points { points, style } => {
                (points.iter().all(|p| p.is_finite()), style.problem())
            }
            Layer::Label { path, .. } => (path.is_finite(), None),
        };
        if !finite {
            return Err(RenderError::NonFinite { layer, kind });
        }
        if let Some(reason) = problem {
            return Err(RenderError::InvalidStyle {
                layer,
                kind,
                reason,
            });
        }
        Ok(())
    }
}

/// A drawing of curves, polygons and points, rendered deterministically to
/// SVG ([`to_svg`](Self::to_svg)) or to pixels ([`render`](Self::render)).
///
/// Layers are drawn in the order they are added, over an opaque white
/// background. Input coordinates are mapped to pixels by a uniform scale and
/// a translation (see [`view_transform`](Self::view_transform)); stroke
/// widths and dot radii are in pixels and do not scale.
///
/// ```
/// use kappa::render::{PointStyle, Scene, Style, Color};
/// use kurbo::{BezPath, Point};
///
/// let mut curve = BezPath::new();
/// curve.move_to((0.0, 0.0));
/// curve.curve_to((30.0, 60.0), (70.0, 60.0), (100.0, 0.0));
/// let points = [Point::new(0.0, 0.0), Point::new(100.0, 0.0)];
/// let scene = Scene::new()
///     .with_size(200, 100)
///     .with_margin(10.0)
///     .curve(&curve)
///     .input_points(&points)
///     .path(&curve, Style::new(Color::RED, 1.0).with_dash(2.0, 2.0));
/// let svg = scene.to_svg()?;
/// assert!(svg.starts_with("<svg"));
/// let pixmap = scene.render()?;
/// assert_eq!((pixmap.width(), pixmap.height()), (200, 100));
/// # Ok::<(), kappa::render::RenderError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Scene {
    width: u32,
    height: u32,
    /// `None` for the default margin.
    margin: Option<f64>,
    view_box: Option<Rect>,
    y_down: bool,
    /// A title drawn centred in a band at the top of the image.
    title: Option<String>,
    layers: Vec<Layer>,
}

impl Default for Scene {
    fn default() -> Self {
        Self::new()
    }
}

impl Scene {
    /// Default image width in pixels.
    pub const DEFAULT_WIDTH: u32 = 800;
    /// Default image height in pixels.
    pub const DEFAULT_HEIGHT: u32 = 600;
    /// Default margin in pixels between the view box and the image edge;
    /// images with a side shorter than `8 × DEFAULT_MARGIN` get a quarter
    /// of their shorter side instead.
    pub const DEFAULT_MARGIN: f64 = 20.0;
    /// Height in pixels of the band a [title](Self::with_title) takes at the top.
    pub const TITLE_BAND: f64 = 22.0;
    /// Size in pixels per em of a title's type.
    pub const TITLE_SIZE: f64 = 14.0;
    /// Baseline of a title, in pixels from the top of the image.
    const TITLE_BASELINE: f64 = 17.0;

    /// An empty 800×600 scene with the default margin (20 px), y down, and
    /// the view box fitted to the content.
    pub fn new() -> Scene {
        Scene {
            width: Self::DEFAULT_WIDTH,
            height: Self::DEFAULT_HEIGHT,
            margin: None,
            view_box: None,
            y_down: true,
            title: None,
            layers: Vec::new(),
        }
    }

    /// Sets the image size in pixels. Both sides must be positive and the
    /// area at most [`MAX_PIXELS`]; this is checked when drawing.
    pub fn with_size(mut self, width_px: u32, height_px: u32) -> Scene {
        self.width = width_px;
        self.height = height_px;
        self
    }

    /// Sets the margin in pixels kept free on every side around the view
    /// box. It must be finite, non-negative and less than half of each side
    /// of the image; this is checked when drawing.
    pub fn with_margin(mut self, margin_px: f64) -> Scene {
        self.margin = Some(margin_px);
        self
    }

    /// Sets the region of the drawing to show, instead of fitting the view
    /// to the content. It is scaled uniformly and centred in the image inside
    /// the margin; content outside it may be clipped.
    pub fn with_view_box(mut self, view_box: Rect) -> Scene {
        self.view_box = Some(view_box);
        self
    }

    /// Chooses the direction of the input's y axis. With `true` (the
    /// default) the input is in y-down pixel-like coordinates: a point with
    /// a larger y is drawn lower in the image. With `false` the y axis points
    /// up, as in mathematics and font units.
    pub fn with_y_down(mut self, y_down: bool) -> Scene {
        self.y_down = y_down;
        self
    }

    /// Gives the image a title: `text` set in [`TITLE_SIZE`](Self::TITLE_SIZE) px type,
    /// centred in a band [`TITLE_BAND`](Self::TITLE_BAND) px tall at the top of the image.
    /// The drawing is fitted into the image below the band (the margin still applies), so a
    /// title never covers it.
    pub fn with_title(mut self, text: &str) -> Scene {
        self.title = Some(text.to_owned());
        self
    }

    /// Adds a text label in `color`, `size_px` pixels per em, with its baseline through the
    /// **pixel** position `at` (y down from the image's top-left corner, whatever the view)
    /// and aligned there as `align` says. It is drawn as glyph outlines of a bundled font
    /// (see [`TextAlign`]), so the SVG has no `<text>` and the pixels need no system font.
    /// Labels do not take part in fitting the view.
    pub fn label(
        mut self,
        text: &str,
        at: Point,
        size_px: f64,
        align: TextAlign,
        color: Color,
    ) -> Scene {
        self.layers.push(Layer::Label {
            path: text_outline(text, at, size_px, align),
            color,
        });
        self
    }

    /// Adds a path layer drawn with `style`.
    pub fn path(mut self, path: &BezPath, style: Style) -> Scene {
        self.layers.push(Layer::Path {
            path: path.clone(),
            style,
            kind: "path",
        });
        self
    }

    /// Adds a layer of dots centred on `points`.
    pub fn points(mut self, points: &[Point], style: PointStyle) -> Scene {
        self.layers.push(Layer::Points {
            points: points.to_vec(),
            style,
        });
        self
    }

    /// Adds the polyline through `points`, closed back to the first point if
    /// `closed` is true. Fewer than two points draw nothing.
    pub fn polygon(mut self, points: &[Point], closed: bool, style: Style) -> Scene {
        let mut path = BezPath::new();
        let mut iter = points.iter();
        if let Some(&first) = iter.next() {
            path.move_to(first);
            for &p in iter {
                path.line_to(p);
            }
            if closed && points.len() > 2 {
                path.close_path();
            }
        }
        self.layers.push(Layer::Path {
            path,
            style,
            kind: "polygon",
        });
        self
    }

    /// Adds a curve in [`Style::CURVE`].
    pub fn curve(self, path: &BezPath) -> Scene {
        self.path(path, Style::CURVE)
    }

    /// Adds input (interpolated) points in [`PointStyle::INPUT`].
    pub fn input_points(self, points: &[Point]) -> Scene {
        self.points(points, PointStyle::INPUT)
    }

    /// Adds a control polygon in [`Style::CONTROL_POLYGON`] with its vertices
    /// as dots in [`PointStyle::CONTROL`].
    pub fn control_polygon(self, points: &[Point], closed: bool) -> Scene {
        self.polygon(points, closed, Style::CONTROL_POLYGON)
            .points(points, PointStyle::CONTROL)
    }

    /// Adds a curvature comb in the thin [`Style::COMB`]. The comb is an
    /// ordinary path, usually one `MoveTo`/`LineTo` pair per tooth, possibly
    /// followed by the polyline through the tooth tips.
    pub fn comb(self, comb: &BezPath) -> Scene {
        self.path(comb, Style::COMB)
    }

    /// The image size in pixels, `(width, height)`.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The map from drawing coordinates to pixel coordinates (y down, origin
    /// at the top-left corner of the image).
    ///
    /// It scales uniformly so that the view box (explicit, or else the tight
    /// bounding box of all layers, stroke widths and dot radii excluded)
    /// fills the image minus the margin in at least one direction, and
    /// centres it. With [`with_y_down(false)`](Self::with_y_down) it also
    /// flips y. A fitted view box with one zero side is fitted on the other
    /// side; a single point, or an empty scene, is drawn at scale 1.
    ///
    /// # Errors
    ///
    /// [`RenderError::InvalidSize`], [`RenderError::InvalidMargin`],
    /// [`RenderError::InvalidViewBox`], and, when the view box is fitted to
    /// the content, [`RenderError::NonFinite`] and
    /// [`RenderError::InvalidStyle`] for bad layers.
    pub fn view_transform(&self) -> Result<Affine, RenderError> {
        self.check_size()?;
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        let m = self
            .margin
            .unwrap_or_else(|| Self::DEFAULT_MARGIN.min(0.25 * w.min(h)));
        let band = self.title_band();
        let avail = Vec2::new(w - 2.0 * m, h - band - 2.0 * m);
        if !(m.is_finite() && m >= 0.0 && avail.x > 0.0 && avail.y > 0.0) {
            return Err(RenderError::InvalidMargin {
                margin: m,
                width: self.width,
                height: self.height,
            });
        }
        let view = match self.view_box {
            Some(rect) => {
                let rect = rect.abs();
                if !(rect.is_finite() && rect.width() > 0.0 && rect.height() > 0.0) {
                    return Err(RenderError::InvalidViewBox { view_box: rect });
                }
                Some(rect)
            }
            None => {
                self.check_layers()?;
                self.content_bounds()
            }
        };
        let Some(view) = view else {
            // Nothing to fit: keep drawing coordinates as pixels.
            return Ok(if self.y_down {
                Affine::IDENTITY
            } else {
                Affine::new([1.0, 0.0, 0.0, -1.0, 0.0, h])
            });
        };
        let size = view.size();
        if !(size.width.is_finite() && size.height.is_finite()) {
            return Err(RenderError::InvalidViewBox { view_box: view });
        }
        let scale_x = avail.x / size.width;
        let scale_y = avail.y / size.height;
        let mut scale = match (size.width > 0.0, size.height > 0.0) {
            (true, true) => scale_x.min(scale_y),
            (true, false) => scale_x,
            (false, true) => scale_y,
            (false, false) => 1.0,
        };
        if !scale.is_finite() {
            // A side so small that avail / side overflows: treat as a point.
            scale = 1.0;
        }
        let flip = if self.y_down { scale } else { -scale };
        let centre = view.center();
        Ok(Affine::translate((0.5 * w, 0.5 * (h + band)))
            * Affine::scale_non_uniform(scale, flip)
            * Affine::translate(-centre.to_vec2()))
    }

    /// Writes the scene as a standalone SVG document: a `viewBox` equal to
    /// the pixel size, a white background `rect`, then one `path` per path
    /// or polygon layer and one `circle` per point, all in pixel
    /// coordinates.
    ///
    /// The output depends only on the scene: numbers are rounded to 1/1000
    /// px and written in Rust's shortest round-trip decimal form, so the
    /// same scene gives the same bytes on every platform. Layers that draw
    /// nothing (empty paths, no visible paint) are left out.
    ///
    /// # Errors
    ///
    /// Everything [`view_transform`](Self::view_transform) reports, plus
    /// [`RenderError::NonFinite`] and [`RenderError::InvalidStyle`] for bad
    /// layers.
    pub fn to_svg(&self) -> Result<String, RenderError> {
        self.check_layers()?;
        let transform = self.view_transform()?;
        let (w, h) = (self.width, self.height);
        let mut svg = String::new();
        // Writing to a String cannot fail.
        let _ = writeln!(
            svg,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
        );
        let _ = writeln!(
            svg,
            r##"<rect x="0" y="0" width="{w}" height="{h}" fill="#ffffff"/>"##
        );
        for (index, layer) in self.layers.iter().enumerate() {
            let out_of_range = RenderError::NonFinite {
                layer: index,
                kind: layer.kind(),
            };
            match layer {
                Layer::Path { path, style, .. } => {
                    let mut path = path.clone();
                    path.apply_affine(transform);
                    round_path(&mut path);
                    if !path.is_finite() {
                        return Err(out_of_range);
                    }
                    write_path(&mut svg, &path, style);
                }
                Layer::Points { points, style } => {
                    for &p in points {
                        let p = round_point(transform * p);
                        if !p.is_finite() {
                            return Err(out_of_range);
                        }
                        write_circle(&mut svg, p, style);
                    }
                }
                Layer::Label { path, color } => write_label(&mut svg, path, *color),
            }
        }
        if let Some(title) = &self.title {
            let at = Point::new(0.5 * f64::from(w), Self::TITLE_BASELINE);
            let path = text_outline(title, at, Self::TITLE_SIZE, TextAlign::Middle);
            write_label(&mut svg, &path, Color::BLACK);
        }
        svg.push_str("</svg>\n");
        Ok(svg)
    }

    /// Renders the scene: [`to_svg`](Self::to_svg), parsed by
    /// `usvg::Tree::from_str` with default options and drawn by
    /// `resvg::render` onto an opaque white pixmap of the scene's size. The
    /// pixels are exactly what the SVG shows, and identical on every x86-64
    /// machine (tiny-skia chooses its SIMD code at compile time; do not build
    /// with `-C target-cpu=native` if images must match references made
    /// elsewhere).
    ///
    /// # Errors
    ///
    /// Everything [`to_svg`](Self::to_svg) reports, and
    /// [`RenderError::Svg`] if usvg rejects the document (for example, more
    /// than a million points).
    pub fn render(&self) -> Result<Pixmap, RenderError> {
        let svg = self.to_svg()?;
        let tree = usvg::Tree::from_str(&svg, &usvg::Options::default())?;
        let mut pixmap = pixmap_new(u64::from(self.width), u64::from(self.height))?;
        pixmap.fill(resvg::tiny_skia::Color::WHITE);
        resvg::render(
            &tree,
            resvg::tiny_skia::Transform::identity(),
            &mut pixmap.as_mut(),
        );
        Ok(pixmap)
    }

    /// [`render`](Self::render)s the scene and encodes it as PNG bytes.
    ///
    /// # Errors
    ///
    /// Everything [`render`](Self::render) reports, and
    /// [`RenderError::PngEncode`].
    pub fn render_png(&self) -> Result<Vec<u8>, RenderError> {
        self.render()?
            .encode_png()
            .map_err(|e| RenderError::PngEncode(Box::new(e)))
    }

    /// The height of the title band: [`TITLE_BAND`](Self::TITLE_BAND) with a title, else 0.
    fn title_band(&self) -> f64 {
        if self.title.is_some() {
            Self::TITLE_BAND
        } else {
            0.0
        }
    }

    fn check_size(&self) -> Result<(), RenderError> {
        let (w, h) = (u64::from(self.width), u64::from(self.height));
        if w == 0 || h == 0 || w * h > MAX_PIXELS {
            return Err(RenderError::InvalidSize {
                width: w,
                height: h,
            });
        }
        Ok(())
    }

    fn check_layers(&self) -> Result<(), RenderError> {
        for (index, layer) in self.layers.iter().enumerate() {
            layer.check(index)?;
        }
        Ok(())
    }

    /// Union of the layers' bounds; layers must be finite.
    fn content_bounds(&self) -> Option<Rect> {
        self.layers
            .iter()
            .filter_map(Layer::bounds)
            .reduce(|a, b| a.union(b))
    }
}

/// Rounds to `1 / SVG_PRECISION` and turns `-0` into `0`.
fn round(x: f64) -> f64 {
    if x.abs() < ROUNDING_LIMIT {
        (x * SVG_PRECISION).round() / SVG_PRECISION + 0.0
    } else {
        x + 0.0
    }
}

fn round_point(p: Point) -> Point {
    Point::new(round(p.x), round(p.y))
}

fn round_el(el: PathEl) -> PathEl {
    match el {
        PathEl::MoveTo(p) => PathEl::MoveTo(round_point(p)),
        PathEl::LineTo(p) => PathEl::LineTo(round_point(p)),
        PathEl::QuadTo(p1, p2) => PathEl::QuadTo(round_point(p1), round_point(p2)),
        PathEl::CurveTo(p1, p2, p3) => {
            PathEl::CurveTo(round_point(p1), round_point(p2), round_point(p3))
        }
        PathEl::ClosePath => PathEl::ClosePath,
    }
}

/// Rounds every coordinate of `path` to `1 / SVG_PRECISION`.
fn round_path(path: &mut BezPath) {
    for el in path.elements_mut() {
        *el = round_el(*el);
    }
}

/// Writes a label's outline (pixel coordinates), rounded, filled with `color`.
fn write_label(svg: &mut String, path: &BezPath, color: Color) {
    let mut path = path.clone();
    round_path(&mut path);
    write_path(svg, &path, &Style::filled(color));
}

/// Writes a rounded number in shortest round-trip form.
fn num(x: f64) -> String {
    format!("{}", round(x))
}

fn write_path(svg: &mut String, path: &BezPath, style: &Style) {
    let stroke = style.stroke.filter(|c| c.a > 0 && style.stroke_width > 0.0);
    let fill = style.fill.filter(|c| c.a > 0);
    if path.segments().next().is_none() || (stroke.is_none() && fill.is_none()) {
        return;
    }
    let _ = write!(svg, r#"<path d="{}""#, path.to_svg());
    write_fill(svg, fill);
    if let Some(c) = stroke {
        let _ = write!(
            svg,
            r#" stroke="{c}" stroke-width="{}" stroke-linejoin="round" stroke-linecap="round""#,
            num(style.stroke_width)
        );
        if c.a < 255 {
            let _ = write!(svg, r#" stroke-opacity="{}""#, c.opacity());
        }
        if let Some([on, off]) = style.dash {
            let _ = write!(svg, r#" stroke-dasharray="{} {}""#, num(on), num(off));
        }
    }
    svg.push_str("/>\n");
}

/// The `fill` (and `fill-opacity`) attributes of an element.
fn write_fill(svg: &mut String, fill: Option<Color>) {
    match fill {
        Some(c) => {
            let _ = write!(svg, r#" fill="{c}""#);
            if c.a < 255 {
                let _ = write!(svg, r#" fill-opacity="{}""#, c.opacity());
            }
        }
        None => svg.push_str(r#" fill="none""#),
    }
}

fn write_circle(svg: &mut String, p: Point, style: &PointStyle) {
    let fill = Some(style.color).filter(|c| c.a > 0);
    let outline = style.outline.filter(|c| c.a > 0);
    if style.radius <= 0.0 || (fill.is_none() && outline.is_none()) {
        return;
    }
    let _ = write!(
        svg,
        r#"<circle cx="{}" cy="{}" r="{}""#,
        num(p.x),
        num(p.y),
        num(style.radius)
    );
    write_fill(svg, fill);
    if let Some(c) = outline {
        let _ = write!(
            svg,
            r#" stroke="{c}" stroke-width="{}""#,
            num(PointStyle::OUTLINE_WIDTH)
        );
        if c.a < 255 {
            let _ = write!(svg, r#" stroke-opacity="{}""#, c.opacity());
        }
    }
    svg.push_str("/>\n");
}
