//! [`Style`] and [`Rgba`]: how frames look.

use std::fmt;
use std::str::FromStr;

use crate::RenderError;

/// An 8-bit colour with straight (not premultiplied) alpha.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Rgba {
    /// Red.
    pub r: u8,
    /// Green.
    pub g: u8,
    /// Blue.
    pub b: u8,
    /// Alpha: 0 transparent, 255 opaque.
    pub a: u8,
}

impl Rgba {
    /// An opaque colour.
    pub const fn rgb(r: u8, g: u8, b: u8) -> Rgba {
        Rgba { r, g, b, a: 255 }
    }

    /// A colour with alpha.
    pub const fn new(r: u8, g: u8, b: u8, a: u8) -> Rgba {
        Rgba { r, g, b, a }
    }

    /// The same colour with alpha `a`.
    pub const fn with_alpha(self, a: u8) -> Rgba {
        Rgba { a, ..self }
    }

    pub(crate) fn to_skia(self) -> tiny_skia::Color {
        tiny_skia::Color::from_rgba8(self.r, self.g, self.b, self.a)
    }

    /// `#rrggbb` for SVG, the alpha goes into a separate opacity attribute.
    pub(crate) fn hex_rgb(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.r, self.g, self.b)
    }

    pub(crate) fn opacity(self) -> f64 {
        f64::from(self.a) / 255.0
    }
}

/// Formats as `#rrggbb`, or `#rrggbbaa` when not opaque.
impl fmt::Display for Rgba {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.hex_rgb())?;
        if self.a != 255 {
            write!(f, "{:02x}", self.a)?;
        }
        Ok(())
    }
}

/// Parses `#rrggbb` or `#rrggbbaa` (the `#` is optional).
impl FromStr for Rgba {
    type Err = RenderError;

    fn from_str(s: &str) -> Result<Rgba, RenderError> {
        let bad = || RenderError::BadColor { input: s.into() };
        let hex = s.trim().trim_start_matches('#');
        if !(hex.len() == 6 || hex.len() == 8) || !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
            return Err(bad());
        }
        let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).map_err(|_| bad());
        let a = if hex.len() == 8 { byte(6)? } else { 255 };
        Ok(Rgba::new(byte(0)?, byte(2)?, byte(4)?, a))
    }
}

/// How a frame is drawn: size, colours, line widths and which layers appear.
///
/// Build it from [`Style::DEFAULT`] with the `with_*` methods.
///
/// # Examples
///
/// ```
/// use immerse_render::{Rgba, Style};
///
/// let style = Style::DEFAULT
///     .with_size(256, 128)
///     .with_wireframe(false)
///     .with_fill(Rgba::rgb(200, 80, 40));
/// assert_eq!(style.width, 256);
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Style {
    /// Image width in pixels. Default: `512`.
    pub width: u32,
    /// Image height in pixels. Default: `512`.
    pub height: u32,
    /// Empty margin around the geometry, in pixels. Default: `16.0`.
    pub padding: f64,
    /// Background colour. Default: `#fbfaf7` (warm white).
    pub background: Rgba,
    /// Fill colour of triangles and faces; its alpha is ignored (see
    /// [`layer_alpha`](Style::layer_alpha)). Default: `#3d7cc9` (blue).
    pub fill: Rgba,
    /// Opacity of one layer of fill. A spot covered k times gets opacity
    /// `1 - (1 - layer_alpha)^k`, so overlap depth is visible; clamped to
    /// `[0, 1]`. Default: `0.45`.
    pub layer_alpha: f32,
    /// Outline colour. Default: `#1d2b3a` (dark slate).
    pub outline: Rgba,
    /// Outline stroke width in pixels; `0` hides the outline. Default: `2.0`.
    pub outline_width: f32,
    /// Whether triangle and face edges are drawn. Default: `true`.
    pub wireframe: bool,
    /// Wireframe colour. Default: `#1d2b3a` at alpha 90.
    pub wireframe_color: Rgba,
    /// Wireframe stroke width in pixels. Default: `0.75`.
    pub wireframe_width: f32,
    /// Whether [`Frame::spine`](crate::Frame::spine) is drawn. Default: `true`.
    pub spine: bool,
    /// Spine colour. Default: `#d1495b` (red).
    pub spine_color: Rgba,
    /// Whether [`Frame::markers`](crate::Frame::markers) are drawn. Default: `true`.
    pub markers: bool,
    /// Marker colour. Default: `#edae49` (amber).
    pub marker_color: Rgba,
    /// Marker dot radius in pixels. Default: `4.0`.
    pub marker_radius: f32,
    /// Whether sequence writers draw the first and last frame as faint
    /// ghost outlines behind every frame (onion skin). Default: `true`.
    pub onion_skin: bool,
    /// Colour of onion-skin ghosts. Default: `#1d2b3a` at alpha 60.
    pub onion_color: Rgba,
    /// Whether edges are anti-aliased. Default: `true`.
    pub anti_alias: bool,
}

impl Style {
    /// The default style.
    pub const DEFAULT: Style = Style {
        width: 512,
        height: 512,
        padding: 16.0,
        background: Rgba::rgb(0xfb, 0xfa, 0xf7),
        fill: Rgba::rgb(0x3d, 0x7c, 0xc9),
        layer_alpha: 0.45,
        outline: Rgba::rgb(0x1d, 0x2b, 0x3a),
        outline_width: 2.0,
        wireframe: true,
        wireframe_color: Rgba::new(0x1d, 0x2b, 0x3a, 90),
        wireframe_width: 0.75,
        spine: true,
        spine_color: Rgba::rgb(0xd1, 0x49, 0x5b),
        markers: true,
        marker_color: Rgba::rgb(0xed, 0xae, 0x49),
        marker_radius: 4.0,
        onion_skin: true,
        onion_color: Rgba::new(0x1d, 0x2b, 0x3a, 60),
        anti_alias: true,
    };

    /// Sets the image size in pixels.
    pub fn with_size(mut self, width: u32, height: u32) -> Style {
        self.width = width;
        self.height = height;
        self
    }

    /// Sets the padding in pixels.
    pub fn with_padding(mut self, padding: f64) -> Style {
        self.padding = padding;
        self
    }

    /// Sets the background colour.
    pub fn with_background(mut self, color: Rgba) -> Style {
        self.background = color;
        self
    }

    /// Sets the fill colour.
    pub fn with_fill(mut self, color: Rgba) -> Style {
        self.fill = color;
        self
    }

    /// Sets the opacity of one layer of fill.
    pub fn with_layer_alpha(mut self, alpha: f32) -> Style {
        self.layer_alpha = alpha;
        self
    }

    /// Sets the outline colour and width (`0` hides it).
    pub fn with_outline(mut self, color: Rgba, width: f32) -> Style {
        self.outline = color;
        self.outline_width = width;
        self
    }

    /// Turns the wireframe on or off.
    pub fn with_wireframe(mut self, on: bool) -> Style {
        self.wireframe = on;
        self
    }

    /// Sets the wireframe colour and width.
    pub fn with_wireframe_style(mut self, color: Rgba, width: f32) -> Style {
        self.wireframe_color = color;
        self.wireframe_width = width;
        self
    }

    /// Turns the spine on or off.
    pub fn with_spine(mut self, on: bool) -> Style {
        self.spine = on;
        self
    }

    /// Sets the spine colour.
    pub fn with_spine_color(mut self, color: Rgba) -> Style {
        self.spine_color = color;
        self
    }

    /// Turns markers on or off.
    pub fn with_markers(mut self, on: bool) -> Style {
        self.markers = on;
        self
    }

    /// Sets the marker colour and radius.
    pub fn with_marker_style(mut self, color: Rgba, radius: f32) -> Style {
        self.marker_color = color;
        self.marker_radius = radius;
        self
    }

    /// Turns the onion skin on or off.
    pub fn with_onion_skin(mut self, on: bool) -> Style {
        self.onion_skin = on;
        self
    }

    /// Sets the onion-skin colour.
    pub fn with_onion_color(mut self, color: Rgba) -> Style {
        self.onion_color = color;
        self
    }

    /// Turns anti-aliasing on or off.
    pub fn with_anti_alias(mut self, on: bool) -> Style {
        self.anti_alias = on;
        self
    }

    /// The fill opacity of a spot covered `depth` times (fractional depths
    /// come from anti-aliased edges).
    pub fn depth_opacity(&self, depth: f64) -> f64 {
        let a = f64::from(self.layer_alpha);
        let a = if a.is_nan() { 0.0 } else { a.clamp(0.0, 1.0) };
        1.0 - (1.0 - a).powf(depth.max(0.0))
    }

    /// The longest side, in pixels, of an image that is rendered.
    pub const MAX_SIDE: u32 = 8192;

    /// The largest image, in pixels, that is rendered: 8192 × 8192. Each
    /// frame needs two RGBA buffers of this size (512 MiB at the limit), and
    /// allocating more could abort the process instead of failing.
    pub const MAX_PIXELS: u64 = 1 << 26;

    pub(crate) fn check_size(&self) -> Result<(), RenderError> {
        if self.width == 0 || self.height == 0 {
            return Err(RenderError::EmptyImage {
                width: self.width,
                height: self.height,
            });
        }
        if self.width > Style::MAX_SIDE
            || self.height > Style::MAX_SIDE
            || u64::from(self.width) * u64::from(self.height) > Style::MAX_PIXELS
        {
            return Err(RenderError::ImageTooLarge {
                width: self.width,
                height: self.height,
                reason: "images are at most 8192 pixels a side",
            });
        }
        Ok(())
    }
}

impl Default for Style {
    fn default() -> Style {
        Style::DEFAULT
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_parse_and_print() {
        let c: Rgba = "#3d7cc9".parse().unwrap();
        assert_eq!(c, Rgba::rgb(0x3d, 0x7c, 0xc9));
        assert_eq!(c.to_string(), "#3d7cc9");
        let c: Rgba = "11223344".parse().unwrap();
        assert_eq!(c.to_string(), "#11223344");
        for bad in ["", "#12345", "#gg0000", "#1234567", "#ÿÿÿ"] {
            assert!(bad.parse::<Rgba>().is_err(), "{bad}");
        }
    }

    #[test]
    fn depth_opacity_grows() {
        let s = Style::DEFAULT;
        assert_eq!(s.depth_opacity(0.0), 0.0);
        assert!(s.depth_opacity(2.0) > s.depth_opacity(1.0));
        assert!(s.with_layer_alpha(f32::NAN).depth_opacity(3.0) == 0.0);
    }
}
