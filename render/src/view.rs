//! [`View`]: the fixed world-to-pixel mapping of an animation.

use crate::{Frame, Style};

/// A uniform scale plus translation from world coordinates (y up) to pixel
/// coordinates (y down).
///
/// Compute it once for a whole animation with [`View::fit`], so that every
/// frame uses the same mapping and nothing jitters.
///
/// # Examples
///
/// ```
/// use immerse_render::{Frame, Style, View};
///
/// let a = Frame::from_triangles(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], vec![[0, 1, 2]]);
/// let style = Style::DEFAULT.with_size(100, 100).with_padding(10.0);
/// let view = View::fit(&[a], &style);
/// assert_eq!(view.to_pixel([0.0, 0.0]), [10.0, 90.0]);
/// assert_eq!(view.to_pixel([1.0, 1.0]), [90.0, 10.0]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    scale: f64,
    tx: f64,
    ty: f64,
}

impl View {
    /// The view that fits the bounding box of every finite point and marker
    /// of all `frames` into the style's image, inside its padding, centred,
    /// with the aspect ratio preserved and y flipped.
    ///
    /// Degenerate input still gives a usable view: with no finite point the
    /// box `[-1, 1]²` is used, and a single point is centred.
    pub fn fit(frames: &[Frame], style: &Style) -> View {
        let mut min = [f64::INFINITY; 2];
        let mut max = [f64::NEG_INFINITY; 2];
        for p in frames.iter().flat_map(Frame::finite_positions) {
            for k in 0..2 {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
            }
        }
        if min[0] > max[0] {
            min = [-1.0; 2];
            max = [1.0; 2];
        }
        View::from_bounds(min, max, style)
    }

    /// The view that fits the box `min..max` (world coordinates) into the
    /// style's image, as [`View::fit`] does.
    pub fn from_bounds(min: [f64; 2], max: [f64; 2], style: &Style) -> View {
        let (w, h) = (f64::from(style.width), f64::from(style.height));
        let pad = if style.padding.is_finite() {
            style.padding.max(0.0)
        } else {
            0.0
        };
        // Keep at least one pixel to draw into, whatever the padding.
        let avail = [(w - 2.0 * pad).max(1.0), (h - 2.0 * pad).max(1.0)];
        let ext = [max[0] - min[0], max[1] - min[1]];
        let mut scale = f64::INFINITY;
        for k in 0..2 {
            if ext[k] > 0.0 {
                scale = scale.min(avail[k] / ext[k]);
            }
        }
        if !scale.is_finite() || scale <= 0.0 {
            // A single point (or an overflowing extent): any scale will do.
            scale = if ext[0].is_finite() && ext[1].is_finite() {
                1.0
            } else {
                f64::MIN_POSITIVE
            };
        }
        let centre = [min[0] / 2.0 + max[0] / 2.0, min[1] / 2.0 + max[1] / 2.0];
        View {
            scale,
            tx: w / 2.0 - scale * centre[0],
            ty: h / 2.0 + scale * centre[1],
        }
    }

    /// Pixel position of world point `p` (x right, y down).
    pub fn to_pixel(self, p: [f64; 2]) -> [f64; 2] {
        [self.tx + self.scale * p[0], self.ty - self.scale * p[1]]
    }

    /// Pixels per world unit.
    pub fn scale(self) -> f64 {
        self.scale
    }

    /// Pixel position of `p` as `f32`, or `None` when it is not finite or so
    /// far outside the image that the rasteriser should not see it.
    pub(crate) fn to_pixel_f32(self, p: [f64; 2]) -> Option<(f32, f32)> {
        /// Beyond this many pixels f32 coordinates lose sub-pixel precision;
        /// such points are far off-screen anyway.
        const LIMIT: f64 = 1.0e7;
        let [x, y] = self.to_pixel(p);
        (x.abs() <= LIMIT && y.abs() <= LIMIT).then_some((x as f32, y as f32))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degenerate_inputs_give_finite_views() {
        let s = Style::DEFAULT;
        for frames in [
            vec![],
            vec![Frame {
                points: vec![[f64::NAN, 0.0]],
                ..Frame::default()
            }],
            vec![Frame {
                points: vec![[3.0, 4.0]],
                ..Frame::default()
            }],
            vec![Frame {
                points: vec![[-f64::MAX, 0.0], [f64::MAX, 1.0]],
                ..Frame::default()
            }],
        ] {
            let v = View::fit(&frames, &s);
            assert!(v.scale.is_finite() && v.tx.is_finite() && v.ty.is_finite());
        }
    }
}
