//! SVG output: one document per frame, or one animated document (SMIL).
//!
//! Coordinates are written in pixels through the shared [`View`], rounded to
//! 1/100 pixel.
//!
//! *Per-frame SVG* draws each triangle (and face) as its own path with fill
//! opacity [`Style::layer_alpha`], so a spot covered k times is composited k
//! times and gets opacity `1 - (1 - a)^k`, the same shading as the PNG
//! output (renderers may show faint seams along shared edges).
//!
//! *Animated SVG* animates the outline path with one
//! `<animate attributeName="d">`. One path cannot show coverage depth
//! directly: with `nonzero` a doubly covered spot looks like a singly
//! covered one, with `evenodd` it looks like a hole. So the animated path
//! (defined once and reused with `<use>`) is filled twice, translucently:
//! once with `nonzero` (every covered spot) and once more through a mask
//! that keeps only the spots of even winding number (`nonzero` minus
//! `evenodd`). The overlap of an immersed disk, winding number 2, is
//! therefore darker, matching the raster shading for depths 1 and 2
//! (depth 3 shades like 1).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::output::{check_fps, onion, write_sequence};
use crate::{Frame, Keys, Loop, Output, RenderError, Rgba, Style, View, write_atomic};

/// The `id` of the background rectangle of every SVG written here.
pub const BACKGROUND_ID: &str = "immerse-background";

/// The `id` of the outline path (the curve) of every SVG written here;
/// immerse reads this path when it reads such a drawing back.
pub const OUTLINE_ID: &str = "immerse-outline";

/// A number with at most two decimals and no trailing zeros.
fn num(out: &mut String, v: f64) {
    let r = (v * 100.0).round() / 100.0;
    // Avoid "-0".
    let r = if r == 0.0 { 0.0 } else { r };
    let _ = write!(out, "{r}");
}

/// Pixel coordinates of every point, `None` for non-finite ones.
fn pixel_points(frame: &Frame, view: &View) -> Vec<Option<[f64; 2]>> {
    frame
        .points
        .iter()
        .map(|&p| {
            let q = view.to_pixel(p);
            (q[0].is_finite() && q[1].is_finite()).then_some(q)
        })
        .collect()
}

/// Path data of a polyline (closed if `close`) through `idx`, skipping
/// non-finite points; empty if fewer than two remain.
fn path_data(idx: &[u32], pts: &[Option<[f64; 2]>], close: bool) -> String {
    let corners: Vec<[f64; 2]> = idx
        .iter()
        .filter_map(|&i| pts.get(i as usize).copied().flatten())
        .collect();
    let mut d = String::new();
    if corners.len() < 2 {
        return d;
    }
    for (k, p) in corners.iter().enumerate() {
        d.push(if k == 0 { 'M' } else { 'L' });
        num(&mut d, p[0]);
        d.push(' ');
        num(&mut d, p[1]);
    }
    if close {
        d.push('Z');
    }
    d
}

/// Path data of a closed loop; empty if any corner is non-finite.
fn polygon_data(idx: &[u32], pts: &[Option<[f64; 2]>]) -> String {
    if idx
        .iter()
        .any(|&i| pts.get(i as usize).copied().flatten().is_none())
    {
        return String::new();
    }
    path_data(idx, pts, true)
}

fn color_attr(out: &mut String, attr: &str, c: Rgba) {
    let _ = write!(out, " {attr}=\"{}\"", c.hex_rgb());
    if c.a != 255 {
        let _ = write!(out, " {attr}-opacity=\"{:.3}\"", c.opacity());
    }
}

fn stroke_attrs(out: &mut String, c: Rgba, width: f32) {
    out.push_str(" fill=\"none\"");
    color_attr(out, "stroke", c);
    let _ = write!(
        out,
        " stroke-width=\"{width}\" stroke-linejoin=\"round\" stroke-linecap=\"round\""
    );
}

fn header(out: &mut String, style: &Style) {
    let (w, h) = (style.width, style.height);
    let _ = writeln!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" \
         width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">"
    );
    // Marked, so that immerse reading the drawing back skips it.
    let _ = write!(
        out,
        "<rect id=\"{BACKGROUND_ID}\" width=\"100%\" height=\"100%\""
    );
    color_attr(out, "fill", style.background);
    out.push_str("/>\n");
}

fn layer_alpha(style: &Style) -> f64 {
    style.depth_opacity(1.0)
}

/// Ghost outlines (or edges) of the onion frames.
fn onion_paths(out: &mut String, onion: &[&Frame], view: &View, style: &Style) {
    for ghost in onion {
        let pts = pixel_points(ghost, view);
        let d = if ghost.outline.is_empty() {
            edges_data(ghost, &pts)
        } else {
            path_data(&ghost.outline, &pts, true)
        };
        if !d.is_empty() {
            let _ = write!(out, "<path d=\"{d}\"");
            stroke_attrs(out, style.onion_color, 1.0);
            out.push_str("/>\n");
        }
    }
}

fn edges_data(frame: &Frame, pts: &[Option<[f64; 2]>]) -> String {
    let mut d = String::new();
    for t in &frame.triangles {
        d.push_str(&polygon_data(t, pts));
    }
    for f in &frame.faces {
        d.push_str(&polygon_data(f, pts));
    }
    d
}

/// One frame as a standalone SVG document, drawn in the same layers as
/// [`render`](crate::render): background, fill (one translucent path per
/// triangle or face, so overlap shows as depth), onion ghosts, wireframe,
/// outline, spine, markers. Primitives touching a non-finite point are
/// skipped.
///
/// # Examples
///
/// ```
/// use immerse_render::{svg_frame, Frame, Style, View};
///
/// let frame = Frame::from_triangles(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], vec![[0, 1, 2]]);
/// let style = Style::DEFAULT;
/// let view = View::fit(std::slice::from_ref(&frame), &style);
/// let svg = svg_frame(&frame, &view, &style, &[])?;
/// assert!(svg.starts_with("<svg"));
/// # Ok::<(), immerse_render::RenderError>(())
/// ```
///
/// # Errors
///
/// [`RenderError::EmptyImage`] for a zero size, [`RenderError::BadIndex`]
/// for an out-of-range index.
pub fn svg_frame(
    frame: &Frame,
    view: &View,
    style: &Style,
    onion: &[&Frame],
) -> Result<String, RenderError> {
    style.check_size()?;
    frame.check_indices()?;
    for ghost in onion {
        ghost.check_indices()?;
    }
    let pts = pixel_points(frame, view);
    let mut out = String::with_capacity(128 + 64 * frame.triangles.len());
    header(&mut out, style);

    let _ = writeln!(
        out,
        "<g fill=\"{}\" fill-opacity=\"{:.3}\" stroke=\"none\">",
        style.fill.hex_rgb(),
        layer_alpha(style)
    );
    let solid = frame.triangles.is_empty() && frame.faces.is_empty();
    let loops = frame
        .triangles
        .iter()
        .map(|t| &t[..])
        .chain(frame.faces.iter().map(|f| &f[..]))
        .chain(solid.then_some(&frame.outline[..]));
    for l in loops {
        let d = polygon_data(l, &pts);
        if !d.is_empty() {
            let _ = writeln!(out, "<path d=\"{d}\"/>");
        }
    }
    out.push_str("</g>\n");
    for layer in &frame.layers {
        let d = path_data(&layer.outline, &pts, true);
        if d.is_empty() {
            continue;
        }
        let paint = |c: Option<crate::Rgba>| {
            c.map_or(("none".to_string(), 1.0), |c| {
                (c.hex_rgb(), f64::from(c.a) / 255.0)
            })
        };
        let (fill, fill_alpha) = paint(layer.fill);
        let (stroke, stroke_alpha) = paint(layer.stroke);
        let _ = writeln!(
            out,
            "<path d=\"{d}\" fill=\"{fill}\" fill-opacity=\"{:.3}\" fill-rule=\"{}\" stroke=\"{stroke}\" stroke-opacity=\"{:.3}\" stroke-width=\"{:.3}\" stroke-linejoin=\"round\" opacity=\"{:.3}\"/>",
            fill_alpha,
            if layer.evenodd { "evenodd" } else { "nonzero" },
            stroke_alpha,
            layer.stroke_width * view.scale(),
            layer.opacity.clamp(0.0, 1.0),
        );
    }

    onion_paths(&mut out, onion, view, style);

    if style.wireframe && style.wireframe_width > 0.0 {
        let d = edges_data(frame, &pts);
        if !d.is_empty() {
            let _ = write!(out, "<path d=\"{d}\"");
            stroke_attrs(&mut out, style.wireframe_color, style.wireframe_width);
            out.push_str("/>\n");
        }
    }
    if style.outline_width > 0.0 {
        let d = path_data(&frame.outline, &pts, true);
        if !d.is_empty() {
            let _ = write!(out, "<path id=\"{OUTLINE_ID}\" d=\"{d}\"");
            stroke_attrs(&mut out, style.outline, style.outline_width);
            out.push_str("/>\n");
        }
    }
    if style.spine && !frame.spine.is_empty() {
        let centres: Vec<_> = frame
            .spine
            .iter()
            .map(|&t| {
                let q = view.to_pixel(frame.centroid(t));
                (q[0].is_finite() && q[1].is_finite()).then_some(q)
            })
            .collect();
        let idx: Vec<u32> = (0..centres.len() as u32).collect();
        let d = path_data(&idx, &centres, false);
        if !d.is_empty() {
            let _ = write!(out, "<path d=\"{d}\"");
            stroke_attrs(
                &mut out,
                style.spine_color,
                (style.outline_width * 0.75).max(1.0),
            );
            out.push_str("/>\n");
        }
    }
    if style.markers && style.marker_radius > 0.0 {
        for &m in &frame.markers {
            let [x, y] = view.to_pixel(m);
            if x.is_finite() && y.is_finite() {
                out.push_str("<circle cx=\"");
                num(&mut out, x);
                out.push_str("\" cy=\"");
                num(&mut out, y);
                let _ = write!(out, "\" r=\"{}\"", style.marker_radius);
                color_attr(&mut out, "fill", style.marker_color);
                color_attr(&mut out, "stroke", style.outline);
                out.push_str("/>\n");
            }
        }
    }
    out.push_str("</svg>\n");
    Ok(out)
}

/// Writes every frame as `dir/frame_0000.svg`, ... with one shared
/// [`View`], like [`write_png_sequence`](crate::write_png_sequence).
///
/// # Errors
///
/// As [`write_png_sequence`](crate::write_png_sequence).
pub fn write_svg_sequence(
    frames: &[Frame],
    dir: &Path,
    style: &Style,
    opts: &Output,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Vec<PathBuf>, RenderError> {
    let ghosts = onion(frames, style);
    write_sequence(frames, dir, style, opts, progress, "svg", |f, view| {
        svg_frame(f, view, style, &ghosts).map(String::into_bytes)
    })
}

/// An animated SVG of every played frame ([`Loop::sequence`]) as a key
/// ([`animated_svg_keys`], full precision), `(frames - 1) / fps` seconds
/// long.
///
/// # Errors
///
/// As [`animated_svg_keys`].
pub fn animated_svg(
    frames: &[Frame],
    style: &Style,
    fps: f64,
    looping: Loop,
) -> Result<String, RenderError> {
    if frames.is_empty() {
        return Err(RenderError::NoFrames);
    }
    if !frames[0].layers.is_empty() {
        return animated_layers(frames, style, fps, looping);
    }
    let played: Vec<Frame> = looping
        .sequence(frames.len())
        .into_iter()
        .map(|i| frames[i].clone())
        .collect();
    let times: Vec<f64> = (0..played.len()).map(|i| i as f64).collect();
    let keys = Keys {
        shapes: &played,
        times: &times,
        frames: played.len(),
        view: View::fit(frames, style),
        digits: None,
    };
    animated_svg_keys(&keys, style, fps, looping)
}

/// One SVG document whose outline path is animated by an
/// `<animate attributeName="d">` holding exactly the shapes of `keys`:
/// `values` are their outlines (pixels of `keys.view`, written with
/// `keys.digits` decimals or in full precision), `keyTimes` their times
/// over the last frame, `calcMode="linear"`, `(frames - 1) / fps` seconds
/// long, repeated unless `looping` is [`Loop::Once`] (the keys are in
/// played order already). How overlap is shown is described in the
/// module docs of this file: the path is filled `nonzero` plus once more
/// where the winding number is even, so the doubly covered region is
/// darker. With onion skin on, the first and last keys are static ghosts.
/// Triangles, wireframe, spine and markers are not drawn.
///
/// # Errors
///
/// [`RenderError::NoFrames`], [`RenderError::KeyTime`],
/// [`RenderError::BadFps`], a size error, [`RenderError::OutlineMismatch`]
/// unless every key has an outline of the same non-zero length,
/// [`RenderError::InFrame`] for a bad index or a non-finite outline point
/// (reported as [`RenderError::NonFinitePoint`]).
pub fn animated_svg_keys(
    keys: &Keys<'_>,
    style: &Style,
    fps: f64,
    looping: Loop,
) -> Result<String, RenderError> {
    keys.check()?;
    check_fps(fps)?;
    style.check_size()?;
    let expected = keys.shapes[0].outline.len();
    for (i, f) in keys.shapes.iter().enumerate() {
        if f.outline.len() != expected {
            return Err(RenderError::OutlineMismatch {
                frame: i,
                expected,
                found: f.outline.len(),
            });
        }
    }
    let mut shapes = Vec::with_capacity(keys.shapes.len());
    for i in 0..keys.shapes.len() {
        shapes.push(outline_data(&keys.pixel_outline(i)?));
    }
    let last = (keys.frames.max(2) - 1) as f64;
    let dur = last / fps;
    let key_times = smil_key_times(keys.times, last);
    let (values, key_times) = if shapes.len() == 1 {
        ([shapes[0].as_str(); 2].join(";"), "0;1".to_string())
    } else {
        (shapes.join(";"), key_times.join(";"))
    };
    let repeat = if looping == Loop::Once {
        "1"
    } else {
        "indefinite"
    };

    let mut out = String::new();
    header(&mut out, style);
    let (w, h) = (style.width, style.height);
    let _ = write!(
        out,
        "<defs>\n<path id=\"{OUTLINE_ID}\" d=\"{}\">\n<animate attributeName=\"d\" dur=\"{dur}s\" \
         repeatCount=\"{repeat}\" fill=\"freeze\" calcMode=\"linear\" keyTimes=\"{key_times}\" values=\"{values}\"/>\n</path>\n\
         <mask id=\"even\" maskUnits=\"userSpaceOnUse\" x=\"0\" y=\"0\" width=\"{w}\" height=\"{h}\">\n\
         <use xlink:href=\"#{OUTLINE_ID}\" fill=\"white\" fill-rule=\"nonzero\"/>\n\
         <use xlink:href=\"#{OUTLINE_ID}\" fill=\"black\" fill-rule=\"evenodd\"/>\n</mask>\n</defs>\n",
        shapes[0],
    );
    let fill = format!(
        "fill=\"{}\" fill-opacity=\"{:.3}\" stroke=\"none\"",
        style.fill.hex_rgb(),
        layer_alpha(style)
    );
    let _ = writeln!(
        out,
        "<use xlink:href=\"#{OUTLINE_ID}\" {fill} fill-rule=\"nonzero\"/>"
    );
    let _ = writeln!(
        out,
        "<use xlink:href=\"#{OUTLINE_ID}\" {fill} fill-rule=\"nonzero\" mask=\"url(#even)\"/>"
    );
    onion_paths(&mut out, &onion(keys.shapes, style), &keys.view, style);
    if style.outline_width > 0.0 {
        let _ = write!(out, "<use xlink:href=\"#{OUTLINE_ID}\"");
        stroke_attrs(&mut out, style.outline, style.outline_width);
        out.push_str("/>\n");
    }
    out.push_str("</svg>\n");
    Ok(out)
}

/// An animated SVG of a drawing's frames (each with the same layers, of
/// the same outline lengths): every played frame a key of every shape
/// ([`animated_svg_drawing`], full precision).
fn animated_layers(
    frames: &[Frame],
    style: &Style,
    fps: f64,
    looping: Loop,
) -> Result<String, RenderError> {
    let view = View::fit(frames, style);
    with_layer_keys(frames, looping, view, |keys| {
        animated_svg_drawing(keys, style, fps, looping)
    })
}

/// Calls `write` with the drawing of `frames`' layers as one scene whose
/// every played frame is a key of every shape.
pub(crate) fn with_layer_keys(
    frames: &[Frame],
    looping: Loop,
    view: View,
    write: impl FnOnce(&crate::DrawingKeys<'_>) -> Result<String, RenderError>,
) -> Result<String, RenderError> {
    let first = &frames[0];
    for (i, f) in frames.iter().enumerate() {
        f.check_indices().map_err(|e| e.in_frame(i))?;
        if f.layers.len() != first.layers.len() {
            return Err(RenderError::OutlineMismatch {
                frame: i,
                expected: first.layers.len(),
                found: f.layers.len(),
            });
        }
    }
    let played: Vec<&Frame> = looping
        .sequence(frames.len())
        .into_iter()
        .map(|i| &frames[i])
        .collect();
    let times: Vec<f64> = (0..played.len()).map(|i| i as f64).collect();
    let shapes: Vec<Vec<Frame>> = (0..first.layers.len())
        .map(|k| {
            played
                .iter()
                .map(|f| Frame {
                    points: f.points.clone(),
                    outline: f.layers[k].outline.clone(),
                    ..Frame::default()
                })
                .collect()
        })
        .collect();
    let paints: Vec<Vec<crate::Paint>> = (0..first.layers.len())
        .map(|k| played.iter().map(|f| f.layers[k].paint()).collect())
        .collect();
    let tracks: Vec<crate::Track<'_>> = (0..first.layers.len())
        .map(|k| crate::Track {
            shapes: &shapes[k],
            times: &times,
            paints: &paints[k],
            paint_times: &times,
            evenodd: first.layers[k].evenodd,
        })
        .collect();
    let scenes = [crate::Scene {
        start: 0.0,
        tracks: &tracks,
    }];
    write(&crate::DrawingKeys {
        scenes: &scenes,
        frames: played.len(),
        view,
        digits: None,
    })
}

/// `values[k]` at `times[k]` over an animation whose last frame is
/// `last`, as SMIL's `keyTimes` and `values`; keys inside a run of equal
/// values are left out.
fn smil_values(times: &[f64], values: &[String], last: f64) -> (String, String) {
    let n = values.len();
    if n == 1 {
        return ("0;1".to_string(), format!("{0};{0}", values[0]));
    }
    let kept: Vec<usize> = (0..n)
        .filter(|&k| {
            k == 0 || k + 1 == n || values[k] != values[k - 1] || values[k] != values[k + 1]
        })
        .collect();
    let kept_times: Vec<f64> = kept.iter().map(|&k| times[k]).collect();
    let key_times = smil_key_times(&kept_times, last);
    let vals: Vec<&str> = kept.iter().map(|&k| values[k].as_str()).collect();
    (key_times.join(";"), vals.join(";"))
}

/// One SVG document playing a keyed drawing: every scene a group shown
/// from its start to the next scene's, holding one path per track,
/// bottom first, whose `d` is animated through exactly the track's keys
/// (`keyTimes` their times over the last frame, `calcMode="linear"`,
/// pixels of `keys.view` with `keys.digits` decimals, as
/// [`animated_svg_keys`] writes them), and whose fill, stroke, stroke
/// width and opacity are animated through its paints. `(frames - 1) / fps`
/// seconds long, repeated unless `looping` is [`Loop::Once`].
///
/// # Errors
///
/// As [`crate::lottie_drawing`], and [`RenderError::OutlineMismatch`]
/// unless every key of a track has an outline of the same length.
pub fn animated_svg_drawing(
    keys: &crate::DrawingKeys<'_>,
    style: &Style,
    fps: f64,
    looping: Loop,
) -> Result<String, RenderError> {
    keys.check()?;
    check_fps(fps)?;
    style.check_size()?;
    let last = (keys.frames.max(2) - 1) as f64;
    let dur = last / fps;
    let repeat = if looping == Loop::Once {
        "1"
    } else {
        "indefinite"
    };
    let colour = |c: Option<Rgba>| c.map_or_else(|| "none".to_string(), Rgba::hex_rgb);
    let scale = keys.view.scale();
    let mut out = String::new();
    header(&mut out, style);
    for (si, scene) in keys.scenes.iter().enumerate() {
        if keys.scenes.len() == 1 {
            out.push_str("<g>\n");
        } else {
            // Shown from its start to the next scene's.
            let end = keys.scenes.get(si + 1).map(|n| n.start / last);
            let start = scene.start / last;
            let (times, values) = match (si, end) {
                (0, Some(e)) => (format!("0;{e}"), "visible;hidden"),
                (_, Some(e)) => (format!("0;{start};{e}"), "hidden;visible;hidden"),
                (_, None) => (format!("0;{start}"), "hidden;visible"),
            };
            let _ = writeln!(
                out,
                "<g visibility=\"{}\">\n<animate attributeName=\"visibility\" dur=\"{dur}s\" repeatCount=\"{repeat}\" fill=\"freeze\" calcMode=\"discrete\" keyTimes=\"{times}\" values=\"{values}\"/>",
                if si == 0 { "visible" } else { "hidden" }
            );
        }
        for track in scene.tracks {
            let one = keys.keys(track);
            let expected = track.shapes[0].outline.len();
            let mut ds = Vec::with_capacity(track.shapes.len());
            for (i, f) in track.shapes.iter().enumerate() {
                if f.outline.len() != expected {
                    return Err(RenderError::OutlineMismatch {
                        frame: i,
                        expected,
                        found: f.outline.len(),
                    });
                }
                ds.push(outline_data(&one.pixel_outline(i)?));
            }
            let p0 = &track.paints[0];
            let _ = writeln!(
                out,
                "<path d=\"{}\" fill=\"{}\" fill-rule=\"{}\" stroke=\"{}\" stroke-linejoin=\"round\">",
                ds[0],
                colour(p0.fill),
                if track.evenodd { "evenodd" } else { "nonzero" },
                colour(p0.stroke),
            );
            let animate = |out: &mut String, attr: &str, times: &[f64], v: &[String]| {
                let (key_times, values) = smil_values(times, v, last);
                let _ = writeln!(
                    out,
                    "<animate attributeName=\"{attr}\" dur=\"{dur}s\" repeatCount=\"{repeat}\" fill=\"freeze\" calcMode=\"linear\" keyTimes=\"{key_times}\" values=\"{values}\"/>",
                );
            };
            // Every key of the outline is written, equal or not: the
            // certified keys exactly.
            let key_times = smil_key_times(track.times, last);
            let (key_times, values) = if ds.len() == 1 {
                ("0;1".to_string(), format!("{0};{0}", ds[0]))
            } else {
                (key_times.join(";"), ds.join(";"))
            };
            let _ = writeln!(
                out,
                "<animate attributeName=\"d\" dur=\"{dur}s\" repeatCount=\"{repeat}\" fill=\"freeze\" calcMode=\"linear\" keyTimes=\"{key_times}\" values=\"{values}\"/>",
            );
            let t = track.paint_times;
            let paints = |f: &dyn Fn(&crate::Paint) -> String| -> Vec<String> {
                track.paints.iter().map(f).collect()
            };
            animate(&mut out, "fill", t, &paints(&|p| colour(p.fill)));
            animate(&mut out, "stroke", t, &paints(&|p| colour(p.stroke)));
            animate(
                &mut out,
                "stroke-width",
                t,
                &paints(&|p| format!("{:.3}", p.stroke_width * scale)),
            );
            animate(
                &mut out,
                "opacity",
                t,
                &paints(&|p| format!("{:.3}", p.opacity.clamp(0.0, 1.0))),
            );
            out.push_str("</path>\n");
        }
        out.push_str("</g>\n");
    }
    out.push_str("</svg>\n");
    Ok(out)
}

/// Closed path data through pixel points written in full (they are
/// rounded already).
fn outline_data(pts: &[[f64; 2]]) -> String {
    let mut d = String::new();
    for (k, p) in pts.iter().enumerate() {
        d.push(if k == 0 { 'M' } else { 'L' });
        let _ = write!(d, "{} {}", p[0], p[1]);
    }
    d.push('Z');
    d
}

/// Writes [`animated_svg`] to `path` with [`write_atomic`].
///
/// # Errors
///
/// As [`animated_svg`] and [`write_atomic`]; an existing `path` is refused
/// without `opts.force` before anything is computed.
pub fn write_animated_svg(
    frames: &[Frame],
    path: &Path,
    style: &Style,
    fps: f64,
    looping: Loop,
    opts: &Output,
) -> Result<(), RenderError> {
    crate::check_output_file(path, opts.force)?;
    let svg = animated_svg(frames, style, fps, looping)?;
    write_atomic(path, svg.as_bytes(), opts.force)
}

/// SMIL `keyTimes` for keys at frame times `times` (strictly increasing,
/// the first 0) of an animation whose last frame is `last`: each time over
/// `last`, the last one exactly 1 (the ends exactly 0 and 1, as SMIL
/// asks), strictly increasing. Keys a few units in the last place apart
/// in frame position can share a quotient; each is then moved to the next
/// double past the previous one (then below the following one, towards
/// 1), so that every key keeps its own time.
fn smil_key_times(times: &[f64], last: f64) -> Vec<String> {
    let n = times.len();
    let mut x: Vec<f64> = times
        .iter()
        .enumerate()
        .map(|(i, &t)| if i + 1 == n { 1.0 } else { t / last })
        .collect();
    // On [0, 1] the next double up (down) is the next (previous) bit pattern.
    for i in 1..n.saturating_sub(1) {
        if x[i] <= x[i - 1] {
            x[i] = f64::from_bits(x[i - 1].to_bits() + 1);
        }
    }
    for i in (1..n.saturating_sub(1)).rev() {
        if x[i] >= x[i + 1] {
            x[i] = f64::from_bits(x[i + 1].to_bits() - 1);
        }
    }
    x.iter().map(|x| format!("{x}")).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short() {
        let mut s = String::new();
        for v in [1.0, 2.5, -0.001, 1.23456] {
            num(&mut s, v);
            s.push(' ');
        }
        assert_eq!(s, "1 2.5 0 1.23 ");
    }

    /// Keys one unit in the last place apart in frame position keep
    /// strictly increasing key times after the division by the last frame
    /// (the quotients of several of them round to one double), the ends
    /// exactly 0 and 1.
    #[test]
    fn key_times_strictly_increase_where_quotients_round_together() {
        // Frame positions near 63.9 are 2⁻⁴⁷ apart; over 100, their
        // quotients near 0.639 are 2⁻⁵³ apart, and 2⁻⁴⁷ / 100 is less.
        let last = 100.0;
        let mut times = vec![0.0, 30.0];
        let mut t = 63.9f64;
        for _ in 0..40 {
            times.push(t);
            t = f64::from_bits(t.to_bits() + 1);
        }
        times.push(last);
        let naive: Vec<f64> = times.iter().map(|t| t / last).collect();
        assert!(
            naive[2..times.len() - 1].windows(2).any(|w| w[0] >= w[1]),
            "the case must have quotients that round together"
        );
        let got: Vec<f64> = smil_key_times(&times, last)
            .iter()
            .map(|s| s.parse().unwrap())
            .collect();
        assert_eq!(got.len(), times.len());
        assert_eq!((got[0], got[times.len() - 1]), (0.0, 1.0));
        assert!(got.windows(2).all(|w| w[0] < w[1]), "{got:?}");
        for (g, n) in got.iter().zip(&naive).take(times.len() - 1) {
            assert!((g - n).abs() <= 64.0 * f64::EPSILON, "{g} against {n}");
        }
    }
}
