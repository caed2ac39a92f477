//! A shape's paint: colours, stroke width, opacity, fill rule, and their
//! interpolation (colour in OKLab).

use serde::{Serialize, Serializer};

/// An sRGB colour, 8 bits per channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Color {
    /// Red.
    pub r: u8,
    /// Green.
    pub g: u8,
    /// Blue.
    pub b: u8,
}

impl Color {
    /// Black.
    pub(crate) const BLACK: Color = Color { r: 0, g: 0, b: 0 };

    /// `#rrggbb`.
    pub fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.r, self.g, self.b)
    }

    /// Reads `#rgb` or `#rrggbb` (case-insensitive).
    pub fn parse_hex(text: &str) -> Option<Color> {
        let h = text.strip_prefix('#')?;
        let digit = |c: u8| (c as char).to_digit(16).map(|d| d as u8);
        let b = h.as_bytes();
        match b.len() {
            3 => Some(Color {
                r: digit(b[0])? * 17,
                g: digit(b[1])? * 17,
                b: digit(b[2])? * 17,
            }),
            6 => Some(Color {
                r: digit(b[0])? * 16 + digit(b[1])?,
                g: digit(b[2])? * 16 + digit(b[3])?,
                b: digit(b[4])? * 16 + digit(b[5])?,
            }),
            _ => None,
        }
    }

    /// The colour in OKLab (Björn Ottosson, "A perceptual color space for
    /// image processing").
    pub(crate) fn to_oklab(self) -> [f64; 3] {
        let lin = |c: u8| {
            let c = f64::from(c) / 255.0;
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        };
        let (r, g, b) = (lin(self.r), lin(self.g), lin(self.b));
        let l = (0.412_221_470_8 * r + 0.536_332_536_3 * g + 0.051_445_992_9 * b).cbrt();
        let m = (0.211_903_498_2 * r + 0.680_699_545_1 * g + 0.107_396_956_6 * b).cbrt();
        let s = (0.088_302_461_9 * r + 0.281_718_837_6 * g + 0.629_978_700_5 * b).cbrt();
        [
            0.210_454_255_3 * l + 0.793_617_785 * m - 0.004_072_046_8 * s,
            1.977_998_495_1 * l - 2.428_592_205 * m + 0.450_593_709_9 * s,
            0.025_904_037_1 * l + 0.782_771_766_2 * m - 0.808_675_766 * s,
        ]
    }

    /// The sRGB colour of an OKLab triple, clamped to the gamut.
    pub fn from_oklab([ll, a, b]: [f64; 3]) -> Color {
        let l = (ll + 0.396_337_777_4 * a + 0.215_803_757_3 * b).powi(3);
        let m = (ll - 0.105_561_345_8 * a - 0.063_854_172_8 * b).powi(3);
        let s = (ll - 0.089_484_177_5 * a - 1.291_485_548 * b).powi(3);
        let r = 4.076_741_662_1 * l - 3.307_711_591_3 * m + 0.230_969_929_2 * s;
        let g = -1.268_438_004_6 * l + 2.609_757_401_1 * m - 0.341_319_396_5 * s;
        let bl = -0.004_196_086_3 * l - 0.703_418_614_7 * m + 1.707_614_701 * s;
        let enc = |c: f64| {
            let c = c.clamp(0.0, 1.0);
            let v = if c <= 0.003_130_8 {
                12.92 * c
            } else {
                1.055 * c.powf(1.0 / 2.4) - 0.055
            };
            (v * 255.0).round().clamp(0.0, 255.0) as u8
        };
        Color {
            r: enc(r),
            g: enc(g),
            b: enc(bl),
        }
    }

    /// The colour at `t` between `self` (t = 0) and `other` (t = 1), on a
    /// straight line in OKLab.
    pub(crate) fn lerp(self, other: Color, t: f64) -> Color {
        if t <= 0.0 {
            return self;
        }
        if t >= 1.0 {
            return other;
        }
        let (a, b) = (self.to_oklab(), other.to_oklab());
        Color::from_oklab([
            a[0] + t * (b[0] - a[0]),
            a[1] + t * (b[1] - a[1]),
            a[2] + t * (b[2] - a[2]),
        ])
    }
}

impl Serialize for Color {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.hex())
    }
}

/// How a shape's interior is decided where it overlaps itself (SVG's
/// `fill-rule`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum FillRule {
    /// Painted where the winding number is not zero (SVG's default).
    #[default]
    Nonzero,
    /// Painted where the winding number is odd.
    Evenodd,
}

impl FillRule {
    /// True when a point of winding number `w` is painted.
    pub(crate) fn paints(self, w: i64) -> bool {
        match self {
            FillRule::Nonzero => w != 0,
            FillRule::Evenodd => w % 2 != 0,
        }
    }
}

impl std::fmt::Display for FillRule {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            FillRule::Nonzero => "nonzero",
            FillRule::Evenodd => "evenodd",
        })
    }
}

/// A shape's paint.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Style {
    /// Fill colour; `None` when the shape is not filled.
    pub fill: Option<Color>,
    /// Stroke colour; `None` when the shape is not stroked.
    pub stroke: Option<Color>,
    /// Stroke width, in the drawing's units.
    pub stroke_width: f64,
    /// Opacity in [0, 1] (the element's, its groups' and its paint's
    /// opacities multiplied).
    pub opacity: f64,
    /// The fill rule.
    pub fill_rule: FillRule,
}

impl Default for Style {
    /// Filled black, no stroke (SVG's defaults), stroke width 1, opaque.
    fn default() -> Style {
        Style {
            fill: Some(Color::BLACK),
            stroke: None,
            stroke_width: 1.0,
            opacity: 1.0,
            fill_rule: FillRule::Nonzero,
        }
    }
}

impl Style {
    /// The style at `t` between `self` (t ≤ 0, exactly) and `other`
    /// (t ≥ 1, exactly): colours on a straight line in OKLab, opacity
    /// linearly. A colour on one side only is kept as it is in between
    /// (a stroke's width then grows from or shrinks to zero). The stroke
    /// width is linear; the fill rule is the source's until the end.
    pub(crate) fn lerp(&self, other: &Style, t: f64) -> Style {
        if t <= 0.0 {
            return *self;
        }
        if t >= 1.0 {
            return *other;
        }
        let colour = |a: Option<Color>, b: Option<Color>| match (a, b) {
            (Some(a), Some(b)) => Some(a.lerp(b, t)),
            (Some(a), None) => Some(a),
            (None, Some(b)) => Some(b),
            (None, None) => None,
        };
        let width = |a: &Style| {
            if a.stroke.is_some() {
                a.stroke_width
            } else {
                0.0
            }
        };
        Style {
            fill: colour(self.fill, other.fill),
            stroke: colour(self.stroke, other.stroke),
            stroke_width: width(self) + t * (width(other) - width(self)),
            opacity: self.opacity + t * (other.opacity - self.opacity),
            fill_rule: self.fill_rule,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn oklab_round_trips_every_grey_and_primaries() {
        for v in 0..=255_u8 {
            let c = Color { r: v, g: v, b: v };
            assert_eq!(Color::from_oklab(c.to_oklab()), c);
        }
        for c in ["#ff0000", "#00ff00", "#0000ff", "#123456", "#fedcba"] {
            let c = Color::parse_hex(c).unwrap();
            assert_eq!(Color::from_oklab(c.to_oklab()), c);
        }
        // White has lightness 1 and no chroma.
        let w = Color::parse_hex("#fff").unwrap().to_oklab();
        assert!((w[0] - 1.0).abs() < 1e-6 && w[1].abs() < 1e-6 && w[2].abs() < 1e-6);
    }

    #[test]
    fn colour_ends_are_exact_and_the_middle_is_perceptual() {
        let (a, b) = (Color::BLACK, Color::parse_hex("#ffffff").unwrap());
        assert_eq!(a.lerp(b, 0.0), a);
        assert_eq!(a.lerp(b, 1.0), b);
        // Half way in OKLab lightness is far lighter than sRGB's #808080
        // is in linear light: L = 0.5 gives sRGB ≈ 99.
        let mid = a.lerp(b, 0.5);
        assert!(mid.r == mid.g && mid.g == mid.b, "{mid:?}");
        assert!((95..=103).contains(&mid.r), "{mid:?}");
    }
}
