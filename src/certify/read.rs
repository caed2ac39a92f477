//! Reading animations to certify: immerse's morph and animate JSON, Lottie
//! files and animated SVG (docs/design.md §13, "What `certify` covers").
//!
//! Every animated outline becomes an [`AnimatedPath`]: its keys (time,
//! points, and the triangulation when the file has one) and how each
//! segment between two keys is played ([`Play`]). Coordinates of the
//! y-down formats (Lottie, SVG) are mirrored to y up; the vertex order of
//! every key is reversed when the first key turns clockwise, so every
//! shape is read counter-clockwise as immerse draws them. Neither changes
//! whether a shape is an immersed disk.

use crate::geom::Point;
use crate::geom::polygon::{Turning, turning_number};

/// Largest file read (bytes).
pub const MAX_ANIMATION_BYTES: usize = 256 << 20;

/// What the file was read as.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Format {
    /// `immerse morph --json` or `immerse animate --json`, its
    /// `"keyframes"` list.
    ImmerseKeyframes,
    /// `immerse morph --json` or `immerse animate --json`, its `"frames"`
    /// list (no `"keyframes"`).
    ImmerseFrames,
    /// A Lottie animation (its shape layers' animated paths).
    Lottie,
    /// An SVG with `<animate attributeName="d">` on a path.
    AnimatedSvg,
}

/// How a segment between two keys is played.
#[derive(Clone, Debug, PartialEq)]
pub enum Play {
    /// Straight lines at constant speed.
    Linear,
    /// Straight lines, eased in time without leaving [0, 1] (a cubic
    /// Bézier easing with both control values in [0, 1]): the same shapes
    /// as linear, at other times.
    Eased,
    /// The first key holds until the next one replaces it: no motion.
    Hold,
    /// Not a straight-line motion between the two keys, or not one
    /// certify covers; the reason.
    NotCovered(String),
}

/// One key read from a file.
#[derive(Clone, Debug, PartialEq)]
pub struct ReadKey {
    /// Its time (frames for Lottie, seconds or fractions otherwise).
    pub t: f64,
    /// Its shape (y up).
    pub points: Vec<Point>,
    /// Its triangulation, when the file gives one.
    pub triangles: Option<Vec<[u32; 3]>>,
}

/// An animated outline.
#[derive(Clone, Debug, PartialEq)]
pub struct AnimatedPath {
    /// Where it is in the file (layer and shape names).
    pub name: String,
    /// The keys, in time order.
    pub keys: Vec<ReadKey>,
    /// How each segment (key i to key i + 1) is played.
    pub play: Vec<Play>,
    /// True when the vertex order was reversed (the first key was
    /// clockwise).
    pub reversed: bool,
}

/// The animated outlines of a file.
#[derive(Clone, Debug, PartialEq)]
pub struct Animation {
    /// What the file was read as.
    pub format: Format,
    /// The animated outlines.
    pub paths: Vec<AnimatedPath>,
    /// What the file has that is not certified (static shapes, other
    /// animated properties), one line each.
    pub skipped: Vec<String>,
}

/// A file that cannot be read as an animation.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ReadError {
    /// Larger than [`MAX_ANIMATION_BYTES`].
    #[error("{path}: too large ({size} bytes; the limit is {limit} bytes)")]
    TooLarge {
        /// The file.
        path: String,
        /// Its size.
        size: usize,
        /// The limit.
        limit: usize,
    },
    /// Not JSON or SVG of a known kind, or malformed.
    #[error("{path}: {what}")]
    Bad {
        /// The file.
        path: String,
        /// What is wrong and what to do.
        what: String,
    },
}

fn bad(path: &str, what: impl Into<String>) -> ReadError {
    ReadError::Bad {
        path: path.to_string(),
        what: what.into(),
    }
}

/// Reads an animation from `bytes`; `label` names it in errors. JSON with
/// `"frames"` or `"keyframes"` is immerse's, JSON with `"layers"` Lottie,
/// XML an animated SVG.
///
/// # Errors
///
/// [`ReadError`] for a file too large, not of a known kind, malformed, or
/// without any animated outline.
pub fn read_animation(bytes: &[u8], label: &str) -> Result<Animation, ReadError> {
    if bytes.len() > MAX_ANIMATION_BYTES {
        return Err(ReadError::TooLarge {
            path: label.into(),
            size: bytes.len(),
            limit: MAX_ANIMATION_BYTES,
        });
    }
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let first = bytes.iter().find(|b| !b.is_ascii_whitespace());
    let mut anim = match first {
        Some(b'{') => read_json(bytes, label)?,
        Some(b'<') => read_svg(bytes, label)?,
        _ => {
            return Err(bad(
                label,
                "not an animation certify reads: give immerse's morph/animate JSON, a Lottie file (.json) or an animated SVG",
            ));
        }
    };
    if anim.paths.is_empty() {
        let what = match anim.format {
            Format::Lottie => {
                "no animated path: certify reads the keyframed paths (\"sh\" items with \"a\": 1) of shape layers"
            }
            Format::AnimatedSvg => "no <animate attributeName=\"d\"> on a <path>",
            _ => "no frames",
        };
        return Err(bad(label, what));
    }
    for path in &mut anim.paths {
        orient(path);
    }
    Ok(anim)
}

/// Counter-clockwise from the first key on (module docs).
fn orient(path: &mut AnimatedPath) {
    let Some(first) = path.keys.first() else {
        return;
    };
    if path.keys.iter().any(|k| k.triangles.is_some()) || first.points.len() < 3 {
        return;
    }
    if turning_number(&first.points) == Turning::Number(-1) {
        path.reversed = true;
        for k in &mut path.keys {
            k.points.reverse();
        }
    }
}

#[derive(serde::Deserialize)]
struct JsonFrame {
    t: f64,
    points: Vec<[f64; 2]>,
    #[serde(default)]
    triangles: Option<Vec<[u32; 3]>>,
}

fn read_json(bytes: &[u8], label: &str) -> Result<Animation, ReadError> {
    let value: serde_json::Value =
        serde_json::from_slice(bytes).map_err(|e| bad(label, format!("not valid JSON ({e})")))?;
    if value.get("layers").is_some() {
        return read_lottie(&value, label);
    }
    let (list, format) = match (value.get("keyframes"), value.get("frames")) {
        (Some(k), _) if k.as_array().is_some_and(|a| !a.is_empty()) => {
            (k, Format::ImmerseKeyframes)
        }
        (_, Some(f)) => (f, Format::ImmerseFrames),
        _ => {
            return Err(bad(
                label,
                "JSON without \"frames\", \"keyframes\" or \"layers\": certify reads immerse's morph/animate JSON or a Lottie file",
            ));
        }
    };
    let frames: Vec<JsonFrame> = serde_json::from_value(list.clone()).map_err(|e| {
        bad(
            label,
            format!(
                "the frames are not [{{\"t\", \"points\": [[x, y], …], \"triangles\"}}, …] ({e})"
            ),
        )
    })?;
    let keys: Vec<ReadKey> = frames
        .into_iter()
        .map(|f| ReadKey {
            t: f.t,
            points: f.points.iter().map(|&[x, y]| Point::new(x, y)).collect(),
            triangles: f.triangles,
        })
        .collect();
    let play = vec![Play::Linear; keys.len().saturating_sub(1)];
    Ok(Animation {
        format,
        paths: vec![AnimatedPath {
            name: if format == Format::ImmerseKeyframes {
                "keyframes".into()
            } else {
                "frames".into()
            },
            keys,
            play,
            reversed: false,
        }],
        skipped: Vec::new(),
    })
}

/// A number or the first number of an array (Lottie writes both).
fn first_number(v: &serde_json::Value) -> Option<f64> {
    v.as_f64().or_else(|| {
        v.as_array()
            .and_then(|a| a.first())
            .and_then(serde_json::Value::as_f64)
    })
}

/// Every number of a value that is a number or an array of numbers.
fn numbers(v: &serde_json::Value) -> Vec<f64> {
    match v {
        serde_json::Value::Array(a) => a.iter().filter_map(serde_json::Value::as_f64).collect(),
        _ => v.as_f64().into_iter().collect(),
    }
}

/// A Lottie path value `{"c", "v", "i", "o"}` (or a one-element array of
/// it) as y-up points; `Err` says why it is not a closed polygon.
fn lottie_shape(v: &serde_json::Value) -> Result<Vec<Point>, String> {
    let v = match v {
        serde_json::Value::Array(a) if a.len() == 1 => &a[0],
        _ => v,
    };
    let verts = v
        .get("v")
        .and_then(serde_json::Value::as_array)
        .ok_or("a path value without \"v\" (vertices)")?;
    let mut pts = Vec::with_capacity(verts.len());
    for (k, p) in verts.iter().enumerate() {
        let xy = numbers(p);
        let [x, y] = xy[..] else {
            return Err(format!("vertex {k} is not [x, y]"));
        };
        if !(x.is_finite() && y.is_finite()) {
            return Err(format!("vertex {k} is not finite"));
        }
        pts.push(Point::new(x, -y));
    }
    if v.get("c").and_then(serde_json::Value::as_bool) == Some(false) {
        return Err("the path is open (\"c\": false); certify covers closed outlines".into());
    }
    for key in ["i", "o"] {
        if let Some(t) = v.get(key).and_then(serde_json::Value::as_array) {
            if let Some(k) = t.iter().position(|p| numbers(p).iter().any(|&x| x != 0.0)) {
                return Err(format!(
                    "vertex {k} has a non-zero {} tangent: the outline is curved, not a polygon",
                    if key == "i" { "in" } else { "out" }
                ));
            }
        }
    }
    Ok(pts)
}

/// How a Lottie keyframe plays to the next: from its `h`, `o` and the
/// next's `i` (or its own `i`, as written by most exporters).
fn lottie_play(key: &serde_json::Value) -> Play {
    if first_number(key.get("h").unwrap_or(&serde_json::Value::Null)) == Some(1.0) {
        return Play::Hold;
    }
    let (Some(o), Some(i)) = (key.get("o"), key.get("i")) else {
        return Play::Linear;
    };
    let get = |v: &serde_json::Value, c: &str| v.get(c).map(numbers).unwrap_or_default();
    let (ox, oy, ix, iy) = (get(o, "x"), get(o, "y"), get(i, "x"), get(i, "y"));
    if ox.is_empty() || oy.is_empty() || ix.is_empty() || iy.is_empty() {
        return Play::Linear;
    }
    if ox == oy && ix == iy {
        return Play::Linear;
    }
    if oy.iter().chain(&iy).all(|y| (0.0..=1.0).contains(y)) {
        Play::Eased
    } else {
        Play::NotCovered(
            "its easing's control values leave [0, 1], so it may overshoot the keys; the shapes beyond them are not certified".into(),
        )
    }
}

fn read_lottie(root: &serde_json::Value, label: &str) -> Result<Animation, ReadError> {
    let layers = root
        .get("layers")
        .and_then(serde_json::Value::as_array)
        .ok_or_else(|| bad(label, "\"layers\" is not a list"))?;
    let mut anim = Animation {
        format: Format::Lottie,
        paths: Vec::new(),
        skipped: Vec::new(),
    };
    for (li, layer) in layers.iter().enumerate() {
        let lname = layer
            .get("nm")
            .and_then(serde_json::Value::as_str)
            .map_or_else(|| format!("layer {li}"), |n| format!("layer {li} '{n}'"));
        if layer.get("ty").and_then(serde_json::Value::as_i64) != Some(4) {
            continue;
        }
        let mut stack: Vec<(String, &serde_json::Value)> = Vec::new();
        if let Some(shapes) = layer.get("shapes").and_then(serde_json::Value::as_array) {
            for (k, s) in shapes.iter().enumerate().rev() {
                stack.push((format!("{lname}, shape {k}"), s));
            }
        }
        while let Some((name, item)) = stack.pop() {
            let name = match item.get("nm").and_then(serde_json::Value::as_str) {
                Some(n) => format!("{name} '{n}'"),
                None => name,
            };
            match item.get("ty").and_then(serde_json::Value::as_str) {
                Some("gr") => {
                    if let Some(items) = item.get("it").and_then(serde_json::Value::as_array) {
                        for (k, s) in items.iter().enumerate().rev() {
                            stack.push((format!("{name}, item {k}"), s));
                        }
                    }
                }
                Some("sh") => {
                    let ks = item.get("ks").unwrap_or(&serde_json::Value::Null);
                    if first_number(ks.get("a").unwrap_or(&serde_json::Value::Null)) != Some(1.0) {
                        anim.skipped
                            .push(format!("{name}: a static path (no motion)"));
                        continue;
                    }
                    anim.paths.push(lottie_path(&name, ks, label)?);
                }
                _ => {}
            }
        }
    }
    Ok(anim)
}

fn lottie_path(name: &str, ks: &serde_json::Value, label: &str) -> Result<AnimatedPath, ReadError> {
    let frames = ks
        .get("k")
        .and_then(serde_json::Value::as_array)
        .ok_or_else(|| {
            bad(
                label,
                format!("{name}: \"ks\".\"k\" is not a list of keyframes"),
            )
        })?;
    let mut keys: Vec<ReadKey> = Vec::new();
    let mut play = Vec::new();
    let mut not_covered: Option<String> = None;
    let mut pending_end: Option<&serde_json::Value> = None;
    for (k, key) in frames.iter().enumerate() {
        let t = key
            .get("t")
            .and_then(serde_json::Value::as_f64)
            .filter(|t| t.is_finite())
            .ok_or_else(|| bad(label, format!("{name}: keyframe {k} has no time \"t\"")))?;
        // Its shape: "s", or (old files) the previous keyframe's "e".
        let Some(shape) = key.get("s").or(pending_end) else {
            continue;
        };
        let points = match lottie_shape(shape) {
            Ok(p) => p,
            Err(why) => {
                not_covered.get_or_insert(format!("keyframe {k}: {why}"));
                Vec::new()
            }
        };
        if !keys.is_empty() {
            let prev: &serde_json::Value = &frames[k - 1];
            play.push(lottie_play(prev));
        }
        keys.push(ReadKey {
            t,
            points,
            triangles: None,
        });
        pending_end = key.get("e");
    }
    if keys.is_empty() {
        return Err(bad(
            label,
            format!("{name}: no keyframe has a shape (\"s\")"),
        ));
    }
    if let Some(why) = not_covered {
        // Curved or open outlines: nothing of this path is certified.
        let n = keys.len();
        for p in &mut play {
            *p = Play::NotCovered(why.clone());
        }
        for k in &mut keys {
            k.points.clear();
        }
        if n == 1 {
            return Err(bad(label, format!("{name}: {why}")));
        }
    }
    Ok(AnimatedPath {
        name: name.to_string(),
        keys,
        play,
        reversed: false,
    })
}

/// A polygon from SVG path data (y mirrored to up); `Err` says why it is
/// not one closed polygon.
fn svg_polygon(d: &str) -> Result<Vec<Point>, String> {
    use svgtypes::PathSegment as S;
    let mut pts: Vec<Point> = Vec::new();
    let (mut cur, mut start) = (Point::ZERO, Point::ZERO);
    let mut moves = 0;
    let mut closed = false;
    for seg in svgtypes::PathParser::from(d) {
        let seg = seg.map_err(|e| format!("bad path data ({e})"))?;
        if closed && !matches!(seg, S::ClosePath { .. }) {
            return Err("more than one subpath; certify covers one closed polygon per path".into());
        }
        let next = match seg {
            S::MoveTo { abs, x, y } => {
                moves += 1;
                if moves > 1 {
                    return Err(
                        "more than one subpath; certify covers one closed polygon per path".into(),
                    );
                }
                let p = if abs {
                    Point::new(x, y)
                } else {
                    cur + Point::new(x, y)
                };
                start = p;
                Some(p)
            }
            S::LineTo { abs, x, y } => Some(if abs {
                Point::new(x, y)
            } else {
                cur + Point::new(x, y)
            }),
            S::HorizontalLineTo { abs, x } => {
                Some(Point::new(if abs { x } else { cur.x + x }, cur.y))
            }
            S::VerticalLineTo { abs, y } => {
                Some(Point::new(cur.x, if abs { y } else { cur.y + y }))
            }
            S::ClosePath { .. } => {
                closed = true;
                cur = start;
                None
            }
            _ => {
                return Err(
                    "a curved segment (C, S, Q, T or A): the outline is not a polygon".into(),
                );
            }
        };
        if let Some(p) = next {
            if !(p.x.is_finite() && p.y.is_finite()) {
                return Err("a coordinate is not finite".into());
            }
            pts.push(p);
            cur = p;
        }
    }
    if !closed {
        return Err("the path is not closed (no Z)".into());
    }
    if pts.len() > 1 && pts.last() == pts.first() {
        pts.pop();
    }
    Ok(pts.into_iter().map(|p| Point::new(p.x, -p.y)).collect())
}

fn read_svg(bytes: &[u8], label: &str) -> Result<Animation, ReadError> {
    let text = std::str::from_utf8(bytes).map_err(|_| bad(label, "not UTF-8 text"))?;
    let opts = roxmltree::ParsingOptions {
        allow_dtd: false,
        ..roxmltree::ParsingOptions::default()
    };
    let doc = roxmltree::Document::parse_with_options(text, opts)
        .map_err(|e| bad(label, format!("not well-formed XML ({e})")))?;
    let mut anim = Animation {
        format: Format::AnimatedSvg,
        paths: Vec::new(),
        skipped: Vec::new(),
    };
    for (k, node) in doc
        .descendants()
        .filter(|n| n.tag_name().name() == "animate" && n.attribute("attributeName") == Some("d"))
        .enumerate()
    {
        let parent = node.parent_element();
        let name = parent.and_then(|p| p.attribute("id")).map_or_else(
            || format!("animation {k}"),
            |id| format!("animation {k} of path '{id}'"),
        );
        if parent.is_none_or(|p| p.tag_name().name() != "path") {
            anim.skipped.push(format!("{name}: not on a <path>"));
            continue;
        }
        let values: Vec<&str> = match (
            node.attribute("values"),
            node.attribute("from"),
            node.attribute("to"),
        ) {
            (Some(v), _, _) => v
                .split(';')
                .map(str::trim)
                .filter(|s| !s.is_empty())
                .collect(),
            (None, Some(f), Some(t)) => vec![f, t],
            _ => {
                return Err(bad(
                    label,
                    format!("{name}: no \"values\" (or \"from\" and \"to\")"),
                ));
            }
        };
        if values.len() < 2 {
            return Err(bad(label, format!("{name}: fewer than two values")));
        }
        let times: Vec<f64> = match node.attribute("keyTimes") {
            Some(kt) => {
                let t: Vec<f64> = kt
                    .split(';')
                    .map(str::trim)
                    .filter(|s| !s.is_empty())
                    .map(|s| {
                        s.parse::<f64>().map_err(|_| {
                            bad(label, format!("{name}: keyTimes '{s}' is not a number"))
                        })
                    })
                    .collect::<Result<_, _>>()?;
                if t.len() != values.len() {
                    return Err(bad(
                        label,
                        format!("{name}: {} keyTimes for {} values", t.len(), values.len()),
                    ));
                }
                t
            }
            None => (0..values.len())
                .map(|i| i as f64 / (values.len() - 1) as f64)
                .collect(),
        };
        let calc = node.attribute("calcMode").unwrap_or("linear");
        let splines: Vec<Vec<f64>> = node
            .attribute("keySplines")
            .map(|s| {
                s.split(';')
                    .map(|q| {
                        q.split(|c: char| c == ',' || c.is_whitespace())
                            .filter(|x| !x.is_empty())
                            .filter_map(|x| x.parse().ok())
                            .collect()
                    })
                    .filter(|v: &Vec<f64>| !v.is_empty())
                    .collect()
            })
            .unwrap_or_default();
        let mut keys = Vec::with_capacity(values.len());
        let mut why: Option<String> = None;
        for (i, (d, &t)) in values.iter().zip(&times).enumerate() {
            let points = svg_polygon(d).unwrap_or_else(|e| {
                why.get_or_insert(format!("value {i}: {e}"));
                Vec::new()
            });
            keys.push(ReadKey {
                t,
                points,
                triangles: None,
            });
        }
        let play = (0..values.len() - 1)
            .map(|i| {
                if let Some(w) = &why {
                    return Play::NotCovered(w.clone());
                }
                match calc {
                    "linear" => Play::Linear,
                    "discrete" => Play::Hold,
                    "spline" => match splines.get(i).map(Vec::as_slice) {
                        Some(&[x1, y1, x2, y2]) if x1 == y1 && x2 == y2 => Play::Linear,
                        Some(&[_, y1, _, y2])
                            if (0.0..=1.0).contains(&y1) && (0.0..=1.0).contains(&y2) =>
                        {
                            Play::Eased
                        }
                        Some(&[_, _, _, _]) => Play::NotCovered(
                            "its keySpline leaves [0, 1], so it may overshoot".into(),
                        ),
                        _ => Play::NotCovered("calcMode spline without a keySpline for it".into()),
                    },
                    other => Play::NotCovered(format!(
                        "calcMode \"{other}\" (certify covers linear, spline and discrete)"
                    )),
                }
            })
            .collect();
        anim.paths.push(AnimatedPath {
            name,
            keys,
            play,
            reversed: false,
        });
    }
    Ok(anim)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn svg_polygons_are_read_and_mirrored() {
        let p = svg_polygon("M0 0L10 0 10 10h-10Z").unwrap();
        assert_eq!(
            p,
            vec![
                Point::new(0.0, 0.0),
                Point::new(10.0, 0.0),
                Point::new(10.0, -10.0),
                Point::new(0.0, -10.0)
            ]
        );
        assert!(svg_polygon("M0 0L1 0L1 1").is_err());
        assert!(svg_polygon("M0 0C1 0 1 1 0 1Z").is_err());
        assert!(svg_polygon("M0 0L1 0L1 1ZM5 5L6 5L6 6Z").is_err());
    }

    #[test]
    fn lottie_easing_is_classified() {
        let v = |s: &str| serde_json::from_str::<serde_json::Value>(s).unwrap();
        assert_eq!(
            lottie_play(&v(r#"{"i":{"x":1,"y":1},"o":{"x":0,"y":0}}"#)),
            Play::Linear
        );
        assert_eq!(
            lottie_play(&v(r#"{"i":{"x":[0.58],"y":[1]},"o":{"x":[0.42],"y":[0]}}"#)),
            Play::Eased
        );
        assert!(matches!(
            lottie_play(&v(r#"{"i":{"x":0.3,"y":1.4},"o":{"x":0.4,"y":0}}"#)),
            Play::NotCovered(_)
        ));
        assert_eq!(lottie_play(&v(r#"{"h":1}"#)), Play::Hold);
    }
}
