//! Rasterising one frame with tiny-skia, and PNG encoding.
//!
//! Fill is drawn by *coverage counting*: every triangle (and face) adds a
//! fixed amount [`LAYER_STEP`] to the alpha channel of a scratch pixmap with
//! [`BlendMode::Plus`], so afterwards each pixel holds how many layers cover
//! it (fractions at anti-aliased edges). A lookup table then maps that depth
//! to the fill colour at opacity `1 - (1 - a)^depth` over the background.
//! Unlike stacking translucent triangles, this leaves no seams along shared
//! interior edges.

use tiny_skia::{
    BlendMode, FillRule, LineCap, LineJoin, Paint, Path, PathBuilder, Pixmap, PremultipliedColorU8,
    Stroke, Transform,
};

use crate::{Frame, RenderError, Rgba, Style, View};

/// Alpha added per covering layer in the scratch pixmap: depths up to
/// `255 / 32 ≈ 8` are told apart; deeper spots shade like depth 8 (with the
/// default layer alpha that is already 99 % opaque).
const LAYER_STEP: u8 = 32;

/// Draws `frame` as seen through `view`, with the `onion` frames as faint
/// ghost outlines underneath its outline.
///
/// Layers, bottom to top: background, fill shaded by overlap depth, onion
/// ghosts, wireframe, outline, spine, markers. A frame with an outline but no
/// triangles or faces is filled as its outline with the nonzero rule (one
/// layer deep).
///
/// # Examples
///
/// ```
/// use immerse_render::{render, Frame, Style, View};
///
/// let frame = Frame::from_triangles(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], vec![[0, 1, 2]]);
/// let style = Style::DEFAULT.with_size(64, 64);
/// let view = View::fit(std::slice::from_ref(&frame), &style);
/// let pixmap = render(&frame, &view, &style, &[])?;
/// assert_eq!((pixmap.width(), pixmap.height()), (64, 64));
/// # Ok::<(), immerse_render::RenderError>(())
/// ```
///
/// # Errors
///
/// [`RenderError::EmptyImage`] for a zero width or height,
/// [`RenderError::ImageTooLarge`] when the pixel buffer cannot be allocated,
/// [`RenderError::BadIndex`] for an out-of-range index in `frame` or an
/// onion frame.
pub fn render(
    frame: &Frame,
    view: &View,
    style: &Style,
    onion: &[&Frame],
) -> Result<Pixmap, RenderError> {
    style.check_size()?;
    frame.check_indices()?;
    for ghost in onion {
        ghost.check_indices()?;
    }
    let too_large = || RenderError::ImageTooLarge {
        width: style.width,
        height: style.height,
        reason: "the pixel buffer cannot be allocated",
    };
    let mut pixmap = Pixmap::new(style.width, style.height).ok_or_else(too_large)?;
    pixmap.fill(style.background.to_skia());

    let pts: Vec<Option<(f32, f32)>> = frame.points.iter().map(|&p| view.to_pixel_f32(p)).collect();

    draw_fill(&mut pixmap, frame, &pts, style).ok_or_else(too_large)?;
    draw_layers(&mut pixmap, frame, &pts, view, style);

    let mut paint = Paint {
        anti_alias: style.anti_alias,
        ..Paint::default()
    };
    let round = |width: f32| Stroke {
        width,
        line_join: LineJoin::Round,
        line_cap: LineCap::Round,
        ..Stroke::default()
    };
    let id = Transform::identity();

    for ghost in onion {
        let gpts: Vec<_> = ghost.points.iter().map(|&p| view.to_pixel_f32(p)).collect();
        let path = if ghost.outline.is_empty() {
            edges_path(ghost, &gpts)
        } else {
            loop_path(&ghost.outline, &gpts, true)
        };
        if let Some(path) = path {
            paint.set_color(style.onion_color.to_skia());
            pixmap.stroke_path(&path, &paint, &round(1.0), id, None);
        }
    }

    if style.wireframe && style.wireframe_width > 0.0 {
        if let Some(path) = edges_path(frame, &pts) {
            paint.set_color(style.wireframe_color.to_skia());
            pixmap.stroke_path(&path, &paint, &round(style.wireframe_width), id, None);
        }
    }

    if style.outline_width > 0.0 {
        if let Some(path) = loop_path(&frame.outline, &pts, true) {
            paint.set_color(style.outline.to_skia());
            pixmap.stroke_path(&path, &paint, &round(style.outline_width), id, None);
        }
    }

    if style.spine && !frame.spine.is_empty() {
        let centres: Vec<_> = frame
            .spine
            .iter()
            .map(|&t| view.to_pixel_f32(frame.centroid(t)))
            .collect();
        let idx: Vec<u32> = (0..centres.len() as u32).collect();
        if let Some(path) = loop_path(&idx, &centres, false) {
            paint.set_color(style.spine_color.to_skia());
            let width = (style.outline_width * 0.75).max(1.0);
            pixmap.stroke_path(&path, &paint, &round(width), id, None);
        }
    }

    if style.markers && style.marker_radius > 0.0 {
        let mut pb = PathBuilder::new();
        for &m in &frame.markers {
            if let Some((x, y)) = view.to_pixel_f32(m) {
                pb.push_circle(x, y, style.marker_radius);
            }
        }
        if let Some(path) = pb.finish() {
            paint.set_color(style.marker_color.to_skia());
            pixmap.fill_path(&path, &paint, FillRule::Winding, id, None);
            paint.set_color(style.outline.to_skia());
            pixmap.stroke_path(&path, &paint, &round(1.0), id, None);
        }
    }
    Ok(pixmap)
}

/// Coverage-counts the triangles and faces, then shades `pixmap` by depth.
/// `None` only if the scratch pixmap cannot be allocated.
/// Paints a drawing's shapes, bottom first, each with its own style.
fn draw_layers(
    pixmap: &mut Pixmap,
    frame: &Frame,
    pts: &[Option<(f32, f32)>],
    view: &View,
    style: &Style,
) {
    let id = Transform::identity();
    for layer in &frame.layers {
        let Some(path) = loop_path(&layer.outline, pts, true) else {
            continue;
        };
        let alpha = |c: crate::Rgba| {
            let a = (f64::from(c.a) * layer.opacity.clamp(0.0, 1.0)).round() as u8;
            tiny_skia::Color::from_rgba8(c.r, c.g, c.b, a)
        };
        let mut paint = Paint {
            anti_alias: style.anti_alias,
            ..Paint::default()
        };
        if let Some(fill) = layer.fill {
            paint.set_color(alpha(fill));
            let rule = if layer.evenodd {
                FillRule::EvenOdd
            } else {
                FillRule::Winding
            };
            pixmap.fill_path(&path, &paint, rule, id, None);
        }
        let width = (layer.stroke_width * view.scale()) as f32;
        if let Some(stroke) = layer.stroke
            && width > 0.0
        {
            paint.set_color(alpha(stroke));
            let stroke = Stroke {
                width,
                line_join: LineJoin::Round,
                line_cap: LineCap::Round,
                ..Stroke::default()
            };
            pixmap.stroke_path(&path, &paint, &stroke, id, None);
        }
    }
}

fn draw_fill(
    pixmap: &mut Pixmap,
    frame: &Frame,
    pts: &[Option<(f32, f32)>],
    style: &Style,
) -> Option<()> {
    let mut count = Pixmap::new(pixmap.width(), pixmap.height())?;
    let mut paint = Paint {
        anti_alias: style.anti_alias,
        blend_mode: BlendMode::Plus,
        ..Paint::default()
    };
    paint.set_color_rgba8(0, 0, 0, LAYER_STEP);
    let id = Transform::identity();
    let mut any = false;
    let mut fill = |path: Option<Path>| {
        if let Some(path) = path {
            count.fill_path(&path, &paint, FillRule::Winding, id, None);
            any = true;
        }
    };
    for t in &frame.triangles {
        fill(loop_path(t, pts, true));
    }
    for f in &frame.faces {
        fill(loop_path(f, pts, true));
    }
    if frame.triangles.is_empty() && frame.faces.is_empty() {
        fill(loop_path(&frame.outline, pts, true));
    }
    if !any {
        return Some(());
    }

    let lut = depth_lut(style);
    for (dst, c) in pixmap.pixels_mut().iter_mut().zip(count.pixels()) {
        let v = c.alpha();
        if v != 0 {
            *dst = over(lut[usize::from(v)], *dst);
        }
    }
    Some(())
}

/// Premultiplied fill colour for every scratch alpha value.
fn depth_lut(style: &Style) -> [PremultipliedColorU8; 256] {
    let Rgba { r, g, b, .. } = style.fill;
    std::array::from_fn(|v| {
        let o = style.depth_opacity(v as f64 / f64::from(LAYER_STEP));
        let a = (o * 255.0).round().clamp(0.0, 255.0) as u8;
        let pm = |c: u8| ((f64::from(c) * o).round() as u8).min(a);
        PremultipliedColorU8::from_rgba(pm(r), pm(g), pm(b), a)
            .unwrap_or(PremultipliedColorU8::TRANSPARENT)
    })
}

/// Source-over of premultiplied colours.
fn over(src: PremultipliedColorU8, dst: PremultipliedColorU8) -> PremultipliedColorU8 {
    let inv = 255 - u16::from(src.alpha());
    let mix = |s: u8, d: u8| s.saturating_add(div255(u16::from(d) * inv));
    let a = mix(src.alpha(), dst.alpha());
    let c = |s: u8, d: u8| mix(s, d).min(a);
    PremultipliedColorU8::from_rgba(
        c(src.red(), dst.red()),
        c(src.green(), dst.green()),
        c(src.blue(), dst.blue()),
        a,
    )
    .unwrap_or(dst)
}

fn div255(v: u16) -> u8 {
    (((u32::from(v) + 128) * 257) >> 16) as u8
}

/// A polyline (closed if `close`) through `idx`, skipping non-finite points.
/// `None` when fewer than two points remain.
fn loop_path(idx: &[u32], pts: &[Option<(f32, f32)>], close: bool) -> Option<Path> {
    let mut pb = PathBuilder::with_capacity(idx.len() + 1, idx.len());
    let mut n = 0;
    for (x, y) in idx
        .iter()
        .filter_map(|&i| pts.get(i as usize).copied().flatten())
    {
        if n == 0 {
            pb.move_to(x, y);
        } else {
            pb.line_to(x, y);
        }
        n += 1;
    }
    if n < 2 {
        return None;
    }
    if close {
        pb.close();
    }
    pb.finish()
}

/// All triangle and face edges as one path of closed loops; a triangle with
/// a non-finite corner is skipped.
fn edges_path(frame: &Frame, pts: &[Option<(f32, f32)>]) -> Option<Path> {
    let mut pb = PathBuilder::with_capacity(frame.triangles.len() * 4, frame.triangles.len() * 3);
    let loops = frame
        .triangles
        .iter()
        .map(|t| &t[..])
        .chain(frame.faces.iter().map(|f| &f[..]));
    'outer: for l in loops {
        let mut corners = Vec::with_capacity(l.len());
        for &i in l {
            match pts.get(i as usize).copied().flatten() {
                Some(p) => corners.push(p),
                None => continue 'outer,
            }
        }
        if let Some((&(x, y), rest)) = corners.split_first() {
            pb.move_to(x, y);
            for &(x, y) in rest {
                pb.line_to(x, y);
            }
            pb.close();
        }
    }
    pb.finish()
}

/// Encodes `pixmap` as an 8-bit RGBA PNG (fast compression).
///
/// # Errors
///
/// [`RenderError::Png`] if the encoder fails.
pub fn encode_png(pixmap: &Pixmap) -> Result<Vec<u8>, RenderError> {
    let opaque = pixmap.pixels().iter().all(|p| p.alpha() == 255);
    let data: Vec<u8> = if opaque {
        // Premultiplied equals straight for opaque pixels; drop alpha.
        pixmap
            .pixels()
            .iter()
            .flat_map(|p| [p.red(), p.green(), p.blue()])
            .collect()
    } else {
        pixmap
            .pixels()
            .iter()
            .flat_map(|p| {
                let c = p.demultiply();
                [c.red(), c.green(), c.blue(), c.alpha()]
            })
            .collect()
    };
    let mut out = Vec::with_capacity(data.len() / 8);
    let mut enc = png::Encoder::new(&mut out, pixmap.width(), pixmap.height());
    enc.set_color(if opaque {
        png::ColorType::Rgb
    } else {
        png::ColorType::Rgba
    });
    enc.set_depth(png::BitDepth::Eight);
    enc.set_compression(png::Compression::Fast);
    let mut writer = enc.write_header().map_err(RenderError::Png)?;
    writer.write_image_data(&data).map_err(RenderError::Png)?;
    writer.finish().map_err(RenderError::Png)?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn div255_is_exact_rounding() {
        for v in 0..=255u16 * 255 {
            assert_eq!(u16::from(div255(v)), (v + 127) / 255, "{v}");
        }
    }

    #[test]
    fn lut_darkens_with_depth() {
        let lut = depth_lut(&Style::DEFAULT);
        assert_eq!(lut[0].alpha(), 0);
        let one = lut[usize::from(LAYER_STEP)].alpha();
        let two = lut[2 * usize::from(LAYER_STEP)].alpha();
        assert!(two > one && one > 0);
    }
}
