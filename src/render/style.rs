//! Colours and drawing styles for [`Scene`](super::Scene) layers.

use std::fmt;

/// An sRGB colour with straight (not premultiplied) 8-bit alpha.
///
/// `Display` writes the SVG form `#rrggbb`; the alpha is written separately
/// as an opacity attribute.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Color {
    /// Red.
    pub r: u8,
    /// Green.
    pub g: u8,
    /// Blue.
    pub b: u8,
    /// Alpha: 0 is transparent, 255 is opaque.
    pub a: u8,
}

impl Color {
    /// Opaque black.
    pub const BLACK: Color = Color::rgb(0, 0, 0);
    /// Opaque white.
    pub const WHITE: Color = Color::rgb(255, 255, 255);
    /// Mid grey, `#7f7f7f`.
    pub const GRAY: Color = Color::rgb(127, 127, 127);
    /// Light grey, `#c7c7c7`.
    pub const LIGHT_GRAY: Color = Color::rgb(199, 199, 199);
    /// Red, `#d62728` (the matplotlib "tab10" palette, like the colours below).
    pub const RED: Color = Color::rgb(214, 39, 40);
    /// Green, `#2ca02c`.
    pub const GREEN: Color = Color::rgb(44, 160, 44);
    /// Blue, `#1f77b4`.
    pub const BLUE: Color = Color::rgb(31, 119, 180);
    /// Orange, `#ff7f0e`.
    pub const ORANGE: Color = Color::rgb(255, 127, 14);
    /// Purple, `#9467bd`.
    pub const PURPLE: Color = Color::rgb(148, 103, 189);
    /// Fully transparent black; draws nothing.
    pub const TRANSPARENT: Color = Color::rgba(0, 0, 0, 0);

    /// An opaque colour.
    pub const fn rgb(r: u8, g: u8, b: u8) -> Color {
        Color { r, g, b, a: 255 }
    }

    /// A colour with straight alpha.
    pub const fn rgba(r: u8, g: u8, b: u8, a: u8) -> Color {
        Color { r, g, b, a }
    }

    /// The same colour with alpha `a`.
    pub const fn with_alpha(self, a: u8) -> Color {
        Color { a, ..self }
    }

    /// The SVG opacity, `a / 255`, written with four decimals.
    pub(crate) fn opacity(self) -> String {
        format!("{:.4}", f64::from(self.a) / 255.0)
    }
}

impl fmt::Display for Color {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{:02x}{:02x}{:02x}", self.r, self.g, self.b)
    }
}

/// How a path or polygon layer is drawn. All lengths are in output pixels and
/// do not change with the view scale.
///
/// Strokes use round joins and round caps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Style {
    /// Stroke colour; `None` draws no outline.
    pub stroke: Option<Color>,
    /// Stroke width in pixels; must be finite and non-negative (0 draws no
    /// outline).
    pub stroke_width: f64,
    /// Fill colour (non-zero winding rule; open subpaths are filled as if
    /// closed, as in SVG); `None` leaves the inside empty.
    pub fill: Option<Color>,
    /// Dash pattern `[on, off]` in pixels; `None` draws a solid line. Both
    /// lengths must be finite and non-negative with a positive sum.
    pub dash: Option<[f64; 2]>,
}

impl Style {
    /// Style of [`Scene::curve`](super::Scene::curve): black, 2 px.
    pub const CURVE: Style = Style::new(Color::BLACK, 2.0);
    /// Style of [`Scene::control_polygon`](super::Scene::control_polygon):
    /// grey, 1 px, dashed 4 on 3 off.
    pub const CONTROL_POLYGON: Style = Style::new(Color::GRAY, 1.0).with_dash(4.0, 3.0);
    /// Style of [`Scene::comb`](super::Scene::comb): translucent blue, 0.75 px.
    pub const COMB: Style = Style::new(Color::BLUE.with_alpha(200), 0.75);

    /// A solid stroke of `color`, `width` pixels wide, with no fill.
    pub const fn new(color: Color, width: f64) -> Style {
        Style {
            stroke: Some(color),
            stroke_width: width,
            fill: None,
            dash: None,
        }
    }

    /// A fill of `color` with no stroke.
    pub const fn filled(color: Color) -> Style {
        Style {
            stroke: None,
            stroke_width: 0.0,
            fill: Some(color),
            dash: None,
        }
    }

    /// The same style with a fill colour.
    pub const fn with_fill(mut self, color: Color) -> Style {
        self.fill = Some(color);
        self
    }

    /// The same style with the stroke width set to `width` pixels.
    pub const fn with_stroke_width(mut self, width: f64) -> Style {
        self.stroke_width = width;
        self
    }

    /// The same style with a dash pattern of `on` pixels drawn and `off`
    /// pixels skipped.
    pub const fn with_dash(mut self, on: f64, off: f64) -> Style {
        self.dash = Some([on, off]);
        self
    }

    /// Why this style cannot be drawn, if it cannot.
    pub(crate) fn problem(&self) -> Option<&'static str> {
        if !(self.stroke_width.is_finite() && self.stroke_width >= 0.0) {
            return Some("stroke width must be finite and non-negative");
        }
        if let Some([on, off]) = self.dash {
            if !(on.is_finite() && off.is_finite() && on >= 0.0 && off >= 0.0 && on + off > 0.0) {
                return Some("dash lengths must be finite, non-negative and not both zero");
            }
        }
        None
    }
}

/// How a point layer is drawn: a filled dot, optionally outlined by a 1 px
/// circle. The radius is in output pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointStyle {
    /// Dot radius in pixels; must be finite and non-negative.
    pub radius: f64,
    /// Fill colour of the dot (use [`Color::TRANSPARENT`] for a hollow dot).
    pub color: Color,
    /// Colour of a 1 px outline centred on the dot's edge; `None` for no
    /// outline.
    pub outline: Option<Color>,
}

impl PointStyle {
    /// Width in pixels of the optional outline.
    pub const OUTLINE_WIDTH: f64 = 1.0;
    /// Style of [`Scene::input_points`](super::Scene::input_points): red dots
    /// of radius 4 px.
    pub const INPUT: PointStyle = PointStyle::new(4.0, Color::RED);
    /// Style of the vertices drawn by
    /// [`Scene::control_polygon`](super::Scene::control_polygon): grey dots
    /// of radius 2.5 px.
    pub const CONTROL: PointStyle = PointStyle::new(2.5, Color::GRAY);

    /// Filled dots of `radius` pixels in `color`, without outline.
    pub const fn new(radius: f64, color: Color) -> PointStyle {
        PointStyle {
            radius,
            color,
            outline: None,
        }
    }

    /// The same style with a 1 px outline of `color`.
    pub const fn with_outline(mut self, color: Color) -> PointStyle {
        self.outline = Some(color);
        self
    }

    /// Why this style cannot be drawn, if it cannot.
    pub(crate) fn problem(&self) -> Option<&'static str> {
        if !(self.radius.is_finite() && self.radius >= 0.0) {
            return Some("point radius must be finite and non-negative");
        }
        None
    }
}
