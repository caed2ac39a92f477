//! Lottie output: one JSON animation with one shape layer whose path is
//! keyframed, playable by lottie-web and the Lottie players of apps.
//!
//! The document (Lottie schema 5.7) has one shape layer (`ty` 4) holding,
//! top to bottom:
//!
//! 1. the curve group: the animated outline path (`sh`, one closed
//!    polyline with zero tangents), its stroke (`st`, round caps and joins
//!    as in the PNGs), a fill in the background colour with the even-odd
//!    rule (`fl`, `r` 2) and the fill colour with the nonzero rule (`fl`,
//!    `r` 1);
//! 2. with [`Style::onion_skin`], the first and last outlines as faint
//!    static strokes (under the fill, unlike the PNGs, where they are above
//!    it);
//! 3. a background rectangle of the image size.
//!
//! **Overlap depth.** The nonzero fill covers every spot inside the curve,
//! overlaps included, at the opacity of a spot covered *twice* in the PNGs
//! (`1 - (1 - a)²` for layer alpha `a`); the even-odd fill on top lightens
//! the spots of odd winding number back to the colour of a spot covered
//! once. For an immersed disk the winding number is the covering depth, so
//! depths 1 and 2 look exactly as in the PNGs (depth 3 looks like 1, as in
//! the animated SVG), with one path and no masks or mattes. This needs an
//! opaque background, which the background rectangle provides.
//!
//! **Keyframes.** [`lottie_keys`] writes exactly the shapes it is given,
//! at their times (frame positions, possibly fractional), with linear
//! interpolation in between (`"i"` and `"o"` on the diagonal: no easing,
//! no overshoot); coordinates are pixels of the given [`View`] (y down),
//! written with [`Keys::digits`] decimals or in full (`f64`) precision.
//! immerse gives it the keys of a certified animation and certifies the
//! written document before it is kept (docs/design.md §12). Where
//! consecutive keys have different vertex counts (which a path cannot
//! interpolate), the earlier keyframe holds (`h` 1). [`lottie`] writes
//! every frame as a key. Triangles, wireframe, spine and markers are not
//! drawn.

use std::fmt::Write as _;
use std::path::Path;

use crate::output::{check_fps, onion};
use crate::{Frame, Loop, Output, RenderError, Rgba, Style, View, write_atomic};

/// Shapes written as keyframes by [`lottie_keys`] and
/// [`crate::animated_svg_keys`]: `shapes[i]` at frame position
/// `times[i]`, in an animation of `frames` frames (0 to `frames − 1`).
#[derive(Clone, Copy, Debug)]
pub struct Keys<'a> {
    /// The shapes; each one's outline is drawn.
    pub shapes: &'a [Frame],
    /// Their frame positions: finite, strictly increasing, the first 0
    /// and the last `frames − 1`.
    pub times: &'a [f64],
    /// Frames of the whole animation.
    pub frames: usize,
    /// World to pixels.
    pub view: View,
    /// Decimals of every written coordinate; `None` for full `f64`
    /// precision (the shortest decimal that reads back bit for bit).
    pub digits: Option<u32>,
}

impl Keys<'_> {
    /// Checks the shapes and their times.
    pub(crate) fn check(&self) -> Result<(), RenderError> {
        if self.shapes.is_empty() || self.frames == 0 {
            return Err(RenderError::NoFrames);
        }
        let last = self.frames - 1;
        let bad = |key: usize, time: f64| RenderError::KeyTime { key, time, last };
        if self.times.len() != self.shapes.len() {
            return Err(bad(self.times.len().min(self.shapes.len()), f64::NAN));
        }
        for (i, &t) in self.times.iter().enumerate() {
            let after = i == 0 || t > self.times[i - 1];
            if !(t.is_finite() && after && t >= 0.0 && t <= last as f64) {
                return Err(bad(i, t));
            }
        }
        for (i, f) in self.shapes.iter().enumerate() {
            f.check_indices().map_err(|e| e.in_frame(i))?;
            if f.outline.is_empty() {
                return Err(RenderError::EmptyOutline { frame: i });
            }
        }
        Ok(())
    }

    /// The outline of shape `i` in pixels, rounded as written.
    pub(crate) fn pixel_outline(&self, i: usize) -> Result<Vec<[f64; 2]>, RenderError> {
        pixel_outline(&self.shapes[i], &self.view, self.digits).map_err(|e| e.in_frame(i))
    }
}

/// The outline of `f` in pixels, rounded to `digits` decimals.
fn pixel_outline(
    f: &Frame,
    view: &View,
    digits: Option<u32>,
) -> Result<Vec<[f64; 2]>, RenderError> {
    f.outline
        .iter()
        .map(|&k| {
            let [x, y] = view.to_pixel(f.points[k as usize]);
            if x.is_finite() && y.is_finite() {
                Ok([round_to(x, digits), round_to(y, digits)])
            } else {
                Err(RenderError::NonFinitePoint { index: k })
            }
        })
        .collect()
}

/// `v` rounded to `digits` decimals (unchanged for `None`), without `-0`.
pub(crate) fn round_to(v: f64, digits: Option<u32>) -> f64 {
    let r = match digits {
        Some(d) => {
            let scale = 10f64.powi(d.min(15) as i32);
            let r = (v * scale).round() / scale;
            if r.is_finite() { r } else { v }
        }
        None => v,
    };
    if r == 0.0 { 0.0 } else { r }
}

/// A number as written: the shortest decimal that reads back as `v`.
fn num(out: &mut String, v: f64) {
    let v = if v == 0.0 { 0.0 } else { v };
    let _ = write!(out, "{v}");
}

/// A colour as Lottie's `[r, g, b, a]` in 0..1.
fn color(c: Rgba) -> String {
    let f = |v: u8| {
        let mut s = String::new();
        let x = (f64::from(v) / 255.0 * 10_000.0).round() / 10_000.0;
        let _ = write!(s, "{x}");
        s
    };
    format!("[{},{},{},1]", f(c.r), f(c.g), f(c.b))
}

/// An opacity in 0..1 as Lottie's percentage.
fn percent(o: f64) -> String {
    let x = (o.clamp(0.0, 1.0) * 100_000.0).round() / 1000.0;
    format!("{x}")
}

/// The static transform of a group or layer: identity.
const GROUP_TRANSFORM: &str = r#"{"ty":"tr","nm":"Transform","p":{"a":0,"k":[0,0]},"a":{"a":0,"k":[0,0]},"s":{"a":0,"k":[100,100]},"r":{"a":0,"k":0},"o":{"a":0,"k":100},"sk":{"a":0,"k":0},"sa":{"a":0,"k":0}}"#;

/// The closed polyline `pts` as a Lottie path value.
fn path_value(out: &mut String, pts: &[[f64; 2]]) {
    out.push_str("{\"c\":true,\"v\":[");
    for (k, p) in pts.iter().enumerate() {
        if k > 0 {
            out.push(',');
        }
        out.push('[');
        num(out, p[0]);
        out.push(',');
        num(out, p[1]);
        out.push(']');
    }
    let zeros = vec!["[0,0]"; pts.len()].join(",");
    let _ = write!(out, "],\"i\":[{zeros}],\"o\":[{zeros}]}}");
}

/// A stroke item.
fn stroke(c: Rgba, width: f64) -> String {
    let mut w = String::new();
    num(&mut w, width);
    format!(
        "{{\"ty\":\"st\",\"nm\":\"Stroke\",\"c\":{{\"a\":0,\"k\":{}}},\"o\":{{\"a\":0,\"k\":{}}},\"w\":{{\"a\":0,\"k\":{w}}},\"lc\":2,\"lj\":2,\"ml\":4}}",
        color(c),
        percent(f64::from(c.a) / 255.0)
    )
}

/// A fill item with rule `r` (1 nonzero, 2 even-odd).
fn fill(name: &str, c: Rgba, opacity: f64, r: u8) -> String {
    format!(
        "{{\"ty\":\"fl\",\"nm\":\"{name}\",\"c\":{{\"a\":0,\"k\":{}}},\"o\":{{\"a\":0,\"k\":{}}},\"r\":{r}}}",
        color(c),
        percent(opacity)
    )
}

/// One Lottie JSON document animating the outlines of `frames` at `fps`
/// frames per second, `style.width` × `style.height` pixels, in the played
/// order of `looping` ([`Loop::sequence`]): every played frame is a key
/// ([`lottie_keys`], full precision). Lottie players loop by default, so
/// [`Loop::Once`] and [`Loop::Loop`] give the same document.
///
/// # Errors
///
/// As [`lottie_keys`].
pub fn lottie(
    frames: &[Frame],
    style: &Style,
    fps: f64,
    looping: Loop,
) -> Result<String, RenderError> {
    if frames.is_empty() {
        return Err(RenderError::NoFrames);
    }
    if !frames[0].layers.is_empty() {
        return lottie_layers(frames, style, fps, looping);
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
    lottie_keys(&keys, style, fps)
}

/// One Lottie JSON document playing `keys` at `fps` frames per second,
/// `style.width` × `style.height` pixels: one shape layer (module docs)
/// whose path has a keyframe per key at its time, interpolated linearly.
/// With [`Style::onion_skin`], the first and last keys are the ghosts.
///
/// # Errors
///
/// [`RenderError::NoFrames`], [`RenderError::KeyTime`],
/// [`RenderError::BadFps`], a size error, [`RenderError::EmptyOutline`] for
/// a shape without an outline, [`RenderError::InFrame`] for a bad index
/// or a non-finite outline point.
pub fn lottie_keys(keys: &Keys<'_>, style: &Style, fps: f64) -> Result<String, RenderError> {
    keys.check()?;
    check_fps(fps)?;
    style.check_size()?;
    let mut played = Vec::with_capacity(keys.shapes.len());
    for i in 0..keys.shapes.len() {
        played.push(keys.pixel_outline(i)?);
    }
    let total = keys.frames;

    // The animated path.
    let mut shape = String::from("{\"ty\":\"sh\",\"nm\":\"Outline\",\"ks\":");
    path_keys(&mut shape, &played, keys.times);
    shape.push('}');

    // Depth shading with two fills (module docs).
    let once = style.depth_opacity(1.0);
    let twice = style.depth_opacity(2.0);
    let mut curve_items = vec![shape];
    if style.outline_width > 0.0 {
        curve_items.push(stroke(style.outline, f64::from(style.outline_width)));
    }
    if twice > 0.0 {
        let lighten = 1.0 - once / twice;
        if lighten > 0.0 {
            curve_items.push(fill("Depth 1 (even-odd)", style.background, lighten, 2));
        }
        curve_items.push(fill("Fill (nonzero)", style.fill, twice, 1));
    }
    curve_items.push(GROUP_TRANSFORM.to_string());
    let mut groups = vec![format!(
        "{{\"ty\":\"gr\",\"nm\":\"Curve\",\"it\":[{}]}}",
        curve_items.join(",")
    )];

    let ghosts = onion(keys.shapes, style);
    if !ghosts.is_empty() {
        let mut items = Vec::new();
        for (k, g) in ghosts.iter().enumerate() {
            let mut s = format!("{{\"ty\":\"sh\",\"nm\":\"Ghost {k}\",\"ks\":{{\"a\":0,\"k\":");
            path_value(&mut s, &pixel_outline(g, &keys.view, keys.digits)?);
            s.push_str("}}");
            items.push(s);
        }
        items.push(stroke(style.onion_color, 1.0));
        items.push(GROUP_TRANSFORM.to_string());
        groups.push(format!(
            "{{\"ty\":\"gr\",\"nm\":\"Onion skin\",\"it\":[{}]}}",
            items.join(",")
        ));
    }

    let (w, h) = (style.width, style.height);
    groups.push(format!(
        "{{\"ty\":\"gr\",\"nm\":\"Background\",\"it\":[{{\"ty\":\"rc\",\"nm\":\"Rectangle\",\"d\":1,\"p\":{{\"a\":0,\"k\":[{},{}]}},\"s\":{{\"a\":0,\"k\":[{w},{h}]}},\"r\":{{\"a\":0,\"k\":0}}}},{},{}]}}",
        f64::from(w) / 2.0,
        f64::from(h) / 2.0,
        fill("Background", style.background, style.background.opacity(), 1),
        GROUP_TRANSFORM
    ));

    let mut fr = String::new();
    num(&mut fr, fps);
    let layer_ks = r#"{"o":{"a":0,"k":100},"r":{"a":0,"k":0},"p":{"a":0,"k":[0,0,0]},"a":{"a":0,"k":[0,0,0]},"s":{"a":0,"k":[100,100,100]}}"#;
    Ok(format!(
        "{{\"v\":\"5.7.4\",\"nm\":\"immerse\",\"fr\":{fr},\"ip\":0,\"op\":{total},\"w\":{w},\"h\":{h},\"ddd\":0,\"assets\":[],\"layers\":[{{\"ddd\":0,\"ind\":1,\"ty\":4,\"nm\":\"immerse morph\",\"sr\":1,\"ks\":{layer_ks},\"ao\":0,\"ip\":0,\"op\":{total},\"st\":0,\"bm\":0,\"shapes\":[{}]}}],\"markers\":[]}}\n",
        groups.join(",")
    ))
}

/// The keyframes of an outline path: `outlines[k]` at `times[k]`, linear
/// in between; a static value for one key. Where consecutive keys have
/// different vertex counts the earlier one holds.
fn path_keys(out: &mut String, outlines: &[Vec<[f64; 2]>], times: &[f64]) {
    if outlines.len() == 1 {
        out.push_str("{\"a\":0,\"k\":");
        path_value(out, &outlines[0]);
        out.push('}');
        return;
    }
    out.push_str("{\"a\":1,\"k\":[");
    for (k, outline) in outlines.iter().enumerate() {
        if k > 0 {
            out.push(',');
        }
        out.push_str("{\"t\":");
        num(out, times[k]);
        out.push_str(",\"s\":[");
        path_value(out, outline);
        out.push(']');
        if let Some(next) = outlines.get(k + 1) {
            if next.len() != outline.len() {
                out.push_str(",\"h\":1");
            } else {
                out.push_str(",\"i\":{\"x\":1,\"y\":1},\"o\":{\"x\":0,\"y\":0}");
            }
        }
        out.push('}');
    }
    out.push_str("]}");
}

/// An animated property: `values[k]` at `times[k]`, linear in between.
/// Keys inside a run of equal values are left out; one value left is a
/// static property.
fn property(times: &[f64], values: &[String]) -> String {
    let n = values.len();
    let kept: Vec<usize> = (0..n)
        .filter(|&k| {
            k == 0 || k + 1 == n || values[k] != values[k - 1] || values[k] != values[k + 1]
        })
        .collect();
    if kept.len() <= 2 && values.iter().all(|v| *v == values[0]) {
        return format!("{{\"a\":0,\"k\":{}}}", values[0]);
    }
    let keys: Vec<String> = kept
        .iter()
        .enumerate()
        .map(|(j, &k)| {
            let mut t = String::new();
            num(&mut t, times[k]);
            if j + 1 == kept.len() {
                format!("{{\"t\":{t},\"s\":{}}}", values[k])
            } else {
                format!(
                    "{{\"t\":{t},\"s\":{},\"i\":{{\"x\":1,\"y\":1}},\"o\":{{\"x\":0,\"y\":0}}}}",
                    values[k]
                )
            }
        })
        .collect();
    format!("{{\"a\":1,\"k\":[{}]}}", keys.join(","))
}

/// A Lottie document of a drawing's frames (each with the same layers,
/// of the same outline lengths): every played frame a key of every shape
/// ([`lottie_drawing`], full precision).
fn lottie_layers(
    frames: &[Frame],
    style: &Style,
    fps: f64,
    looping: Loop,
) -> Result<String, RenderError> {
    let view = View::fit(frames, style);
    crate::svg::with_layer_keys(frames, looping, view, |keys| {
        lottie_drawing(keys, style, fps)
    })
}

/// One Lottie JSON document playing a keyed drawing at `fps` frames per
/// second, `style.width` × `style.height` pixels.
///
/// Every scene is one shape layer shown from its start to the next
/// scene's (`ip`, `op`); it holds one shape group per track, top first as
/// Lottie lists them (the reverse of the painting order), each with its
/// outline path keyed at the track's times (linear in between, as
/// [`lottie_keys`] writes them), its stroke, its fill with the shape's own
/// fill rule and its opacity keyed at the paint times. A shape's fill
/// paints the shape only: no overlap-depth shading that could cover the
/// shapes below (drawings are painted flat, as in the PNGs). The
/// background rectangle is a layer of its own, under every scene.
///
/// # Errors
///
/// [`RenderError::NoFrames`], [`RenderError::KeyTime`] for a scene or key
/// time out of order or a track not spanning the whole animation,
/// [`RenderError::BadFps`], a size error, [`RenderError::EmptyOutline`],
/// [`RenderError::InFrame`] for a bad index or a non-finite point.
pub fn lottie_drawing(
    keys: &crate::DrawingKeys<'_>,
    style: &Style,
    fps: f64,
) -> Result<String, RenderError> {
    keys.check()?;
    check_fps(fps)?;
    style.check_size()?;
    let total = keys.frames;
    let scale = keys.view.scale();
    let colour = |c: Option<Rgba>| color(c.unwrap_or(style.background));
    let layer_ks = r#"{"o":{"a":0,"k":100},"r":{"a":0,"k":0},"p":{"a":0,"k":[0,0,0]},"a":{"a":0,"k":[0,0,0]},"s":{"a":0,"k":[100,100,100]}}"#;
    let mut layers = Vec::with_capacity(keys.scenes.len() + 1);
    for (si, scene) in keys.scenes.iter().enumerate() {
        let mut groups = Vec::with_capacity(scene.tracks.len());
        for (k, track) in scene.tracks.iter().enumerate().rev() {
            let one = keys.keys(track);
            let mut outlines = Vec::with_capacity(track.shapes.len());
            for i in 0..track.shapes.len() {
                outlines.push(one.pixel_outline(i)?);
            }
            let mut sh = String::from("{\"ty\":\"sh\",\"nm\":\"Outline\",\"ks\":");
            path_keys(&mut sh, &outlines, track.times);
            sh.push('}');
            let mut items = vec![sh];
            let t = track.paint_times;
            let values = |f: &dyn Fn(&crate::Paint) -> String| -> Vec<String> {
                track.paints.iter().map(f).collect()
            };
            if track.paints.iter().any(|p| p.stroke.is_some()) {
                items.push(format!(
                    "{{\"ty\":\"st\",\"nm\":\"Stroke\",\"c\":{},\"o\":{{\"a\":0,\"k\":100}},\"w\":{},\"lc\":2,\"lj\":2,\"ml\":4}}",
                    property(t, &values(&|p| colour(p.stroke))),
                    property(
                        t,
                        &values(&|p| {
                            let w = if p.stroke.is_some() { p.stroke_width * scale } else { 0.0 };
                            let mut s = String::from("[");
                            num(&mut s, (w * 1000.0).round() / 1000.0);
                            s.push(']');
                            s
                        })
                    ),
                ));
            }
            if track.paints.iter().any(|p| p.fill.is_some()) {
                items.push(format!(
                    "{{\"ty\":\"fl\",\"nm\":\"Fill\",\"c\":{},\"o\":{{\"a\":0,\"k\":100}},\"r\":{}}}",
                    property(t, &values(&|p| colour(p.fill))),
                    if track.evenodd { 2 } else { 1 },
                ));
            }
            let opacity = property(t, &values(&|p| format!("[{}]", percent(p.opacity))));
            items.push(format!(
                "{{\"ty\":\"tr\",\"nm\":\"Transform\",\"p\":{{\"a\":0,\"k\":[0,0]}},\"a\":{{\"a\":0,\"k\":[0,0]}},\"s\":{{\"a\":0,\"k\":[100,100]}},\"r\":{{\"a\":0,\"k\":0}},\"o\":{opacity},\"sk\":{{\"a\":0,\"k\":0}},\"sa\":{{\"a\":0,\"k\":0}}}}"
            ));
            groups.push(format!(
                "{{\"ty\":\"gr\",\"nm\":\"Shape {}\",\"it\":[{}]}}",
                k + 1,
                items.join(",")
            ));
        }
        let mut ip = String::new();
        num(&mut ip, scene.start);
        let mut op = String::new();
        num(
            &mut op,
            keys.scenes.get(si + 1).map_or(total as f64, |n| n.start),
        );
        let name = if keys.scenes.len() == 1 {
            "immerse drawing".to_string()
        } else {
            format!("immerse drawing, segment {}", si + 1)
        };
        layers.push(format!(
            "{{\"ddd\":0,\"ind\":{},\"ty\":4,\"nm\":\"{name}\",\"sr\":1,\"ks\":{layer_ks},\"ao\":0,\"ip\":{ip},\"op\":{op},\"st\":0,\"bm\":0,\"shapes\":[{}]}}",
            si + 1,
            groups.join(",")
        ));
    }
    let (w, h) = (style.width, style.height);
    layers.push(format!(
        "{{\"ddd\":0,\"ind\":{},\"ty\":4,\"nm\":\"Background\",\"sr\":1,\"ks\":{layer_ks},\"ao\":0,\"ip\":0,\"op\":{total},\"st\":0,\"bm\":0,\"shapes\":[{{\"ty\":\"gr\",\"nm\":\"Background\",\"it\":[{{\"ty\":\"rc\",\"nm\":\"Rectangle\",\"d\":1,\"p\":{{\"a\":0,\"k\":[{},{}]}},\"s\":{{\"a\":0,\"k\":[{w},{h}]}},\"r\":{{\"a\":0,\"k\":0}}}},{},{}]}}]}}",
        keys.scenes.len() + 1,
        f64::from(w) / 2.0,
        f64::from(h) / 2.0,
        fill("Background", style.background, style.background.opacity(), 1),
        GROUP_TRANSFORM
    ));
    let mut fr = String::new();
    num(&mut fr, fps);
    Ok(format!(
        "{{\"v\":\"5.7.4\",\"nm\":\"immerse\",\"fr\":{fr},\"ip\":0,\"op\":{total},\"w\":{w},\"h\":{h},\"ddd\":0,\"assets\":[],\"layers\":[{}],\"markers\":[]}}\n",
        layers.join(",")
    ))
}

/// Writes [`lottie`] to `path` with [`write_atomic`].
///
/// # Errors
///
/// As [`lottie`] and [`write_atomic`]; an existing `path` is refused
/// without `opts.force` before anything is computed.
pub fn write_lottie(
    frames: &[Frame],
    path: &Path,
    style: &Style,
    fps: f64,
    looping: Loop,
    opts: &Output,
) -> Result<(), RenderError> {
    if !opts.force && std::fs::symlink_metadata(path).is_ok() {
        return Err(RenderError::FileExists { path: path.into() });
    }
    let json = lottie(frames, style, fps, looping)?;
    write_atomic(path, json.as_bytes(), opts.force)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::Value;

    /// A square turning by a quarter turn over `n` frames (vertices move
    /// on arcs, so linear interpolation between far frames is off).
    fn turning_square(n: usize) -> Vec<Frame> {
        (0..n)
            .map(|i| {
                let a = i as f64 / (n - 1) as f64 * std::f64::consts::FRAC_PI_2;
                let points = (0..4)
                    .map(|k| {
                        let t = a + k as f64 * std::f64::consts::FRAC_PI_2;
                        [t.cos(), t.sin()]
                    })
                    .collect();
                Frame::from_triangles(points, vec![[0, 1, 2], [0, 2, 3]])
            })
            .collect()
    }

    fn parse(json: &str) -> Value {
        serde_json::from_str(json).expect("valid JSON")
    }

    #[test]
    fn structure_is_one_shape_layer_with_path_keyframes() {
        let frames = turning_square(31);
        let style = Style::DEFAULT.with_size(320, 200).with_onion_skin(false);
        let doc = parse(&lottie(&frames, &style, 24.0, Loop::Loop).unwrap());
        assert_eq!(doc["fr"], 24.0);
        assert_eq!(
            (doc["w"].as_u64(), doc["h"].as_u64()),
            (Some(320), Some(200))
        );
        assert_eq!(
            (doc["ip"].as_f64(), doc["op"].as_f64()),
            (Some(0.0), Some(31.0))
        );
        let layers = doc["layers"].as_array().unwrap();
        assert_eq!(layers.len(), 1);
        assert_eq!(layers[0]["ty"], 4);
        let groups = layers[0]["shapes"].as_array().unwrap();
        assert_eq!(groups.len(), 2, "curve and background");
        let items = groups[0]["it"].as_array().unwrap();
        let sh = &items[0];
        assert_eq!(sh["ty"], "sh");
        assert_eq!(sh["ks"]["a"], 1);
        let keys = sh["ks"]["k"].as_array().unwrap();
        assert!(keys.len() >= 2);
        assert_eq!(keys[0]["t"], 0);
        assert_eq!(keys.last().unwrap()["t"], 30);
        for k in keys {
            let s = &k["s"][0];
            assert_eq!(s["c"], true);
            let v = s["v"].as_array().unwrap();
            assert_eq!(v.len(), 4);
            assert_eq!(s["i"].as_array().unwrap().len(), 4);
            assert_eq!(s["o"].as_array().unwrap().len(), 4);
        }
        let fills: Vec<&Value> = items.iter().filter(|i| i["ty"] == "fl").collect();
        assert_eq!(fills.len(), 2);
        // The fill of the curve is nonzero (1); the lightening one even-odd (2).
        assert_eq!(fills.last().unwrap()["r"], 1);
        assert_eq!(fills[0]["r"], 2);
        assert!(items.iter().any(|i| i["ty"] == "st"));
        assert_eq!(items.last().unwrap()["ty"], "tr");
        let bg = groups[1]["it"].as_array().unwrap();
        assert_eq!(bg[0]["ty"], "rc");
        assert_eq!(bg[0]["s"]["k"], serde_json::json!([320, 200]));
    }

    /// Exactly the keys given are written, at their (fractional) times,
    /// with the decimals asked for, and linear interpolation.
    #[test]
    fn keys_are_written_at_their_times_with_their_digits() {
        let frames = turning_square(3);
        let style = Style::DEFAULT.with_size(512, 512).with_onion_skin(false);
        let view = View::fit(&frames, &style);
        let times = [0.0, 7.25, 20.0];
        for digits in [Some(2), Some(5), None] {
            let keys = Keys {
                shapes: &frames,
                times: &times,
                frames: 21,
                view,
                digits,
            };
            let doc = parse(&lottie_keys(&keys, &style, 30.0).unwrap());
            assert_eq!(doc["op"], 21);
            let k = doc["layers"][0]["shapes"][0]["it"][0]["ks"]["k"]
                .as_array()
                .unwrap()
                .clone();
            assert_eq!(k.len(), 3);
            for (key, (f, &t)) in k.iter().zip(frames.iter().zip(&times)) {
                assert_eq!(key["t"].as_f64(), Some(t));
                let v = key["s"][0]["v"].as_array().unwrap();
                for (p, &i) in v.iter().zip(&f.outline) {
                    let exact = view.to_pixel(f.points[i as usize]);
                    for c in 0..2 {
                        let written = p[c].as_f64().unwrap();
                        let want = round_to(exact[c], digits);
                        assert_eq!(written, want, "digits {digits:?}");
                    }
                }
            }
            assert_eq!(k[0]["i"]["x"], 1);
            assert_eq!(k[0]["o"]["x"], 0);
        }
        // Times must increase and end at the last frame at most.
        let bad = Keys {
            shapes: &frames,
            times: &[0.0, 3.0, 3.0],
            frames: 21,
            view,
            digits: None,
        };
        assert!(matches!(
            lottie_keys(&bad, &style, 30.0),
            Err(RenderError::KeyTime { key: 2, .. })
        ));
    }

    #[test]
    fn a_change_of_vertex_count_holds() {
        let tri = Frame::from_triangles(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], vec![[0, 1, 2]]);
        let quad = Frame::from_triangles(
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            vec![[0, 1, 2], [0, 2, 3]],
        );
        let frames = vec![tri.clone(), tri, quad.clone(), quad];
        let doc = parse(&lottie(&frames, &Style::DEFAULT, 10.0, Loop::Loop).unwrap());
        let k = &doc["layers"][0]["shapes"][0]["it"][0]["ks"]["k"];
        assert_eq!(k.as_array().unwrap().len(), 4);
        assert_eq!(k[1]["h"], 1);
    }

    #[test]
    fn ping_pong_plays_back_and_bad_input_is_refused() {
        let frames = turning_square(5);
        let style = Style::DEFAULT.with_onion_skin(true);
        let doc = parse(&lottie(&frames, &style, 12.0, Loop::PingPong).unwrap());
        assert_eq!(doc["op"], 8);
        assert_eq!(doc["layers"][0]["shapes"].as_array().unwrap().len(), 3);
        assert!(matches!(
            lottie(&[], &style, 12.0, Loop::Loop),
            Err(RenderError::NoFrames)
        ));
        assert!(matches!(
            lottie(&frames, &style, 0.0, Loop::Loop),
            Err(RenderError::BadFps { .. })
        ));
        let mut bare = frames.clone();
        bare[1].outline.clear();
        assert!(matches!(
            lottie(&bare, &style, 12.0, Loop::Loop),
            Err(RenderError::EmptyOutline { frame: 1 })
        ));
        let mut bad = frames.clone();
        bad[2].points[1] = [f64::NAN, 0.0];
        assert!(matches!(
            lottie(&bad, &style, 12.0, Loop::Loop),
            Err(RenderError::InFrame { frame: 2, .. })
        ));
    }
}
