//! The timeline file of `immerse animate --timeline` (docs/timeline.md):
//! JSON listing the keys with their curve files, times or durations,
//! holds, easings and shape hints. Every error names the file, the key
//! (counting from 1) and the field or hint, on one line.

use immerse::curve::SvgShapes;
use immerse_base::input::ReadError;
use immerse_render as render;
use serde_json::{Map, Value};
use std::path::{Path, PathBuf};

/// A hinted point as the file gives it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum HintSpec {
    /// The key file's own point index (counting from 0, before cleaning).
    Index(usize),
    /// A position, snapped to the nearest point of the curve.
    Position(f64, f64),
    /// A fraction of the curve's length from its first point, in the
    /// file's drawing order.
    Fraction(f64),
}

/// One key of the file.
#[derive(Clone, Debug)]
pub(crate) struct KeySpec {
    /// The curve file, relative to the timeline's folder.
    pub(crate) curve: PathBuf,
    /// The curve as the file names it (for messages).
    pub(crate) curve_text: String,
    /// Which shape of a multi-shape SVG (counting from 1).
    pub(crate) shape: Option<usize>,
    pub(crate) time: Option<f64>,
    pub(crate) duration: Option<f64>,
    pub(crate) hold: Option<f64>,
    pub(crate) easing: Option<render::Easing>,
    pub(crate) hints: Vec<(String, HintSpec)>,
}

impl KeySpec {
    pub(crate) fn plain(curve: PathBuf, shape: Option<usize>) -> KeySpec {
        KeySpec {
            curve_text: curve.display().to_string(),
            curve,
            shape,
            time: None,
            duration: None,
            hold: None,
            easing: None,
            hints: Vec::new(),
        }
    }
}

/// A parsed timeline file.
#[derive(Clone, Debug)]
pub(crate) struct Timeline {
    pub(crate) fps: Option<f64>,
    pub(crate) frames: Option<usize>,
    pub(crate) looping: Option<render::Loop>,
    pub(crate) svg_keys: Option<SvgShapes>,
    /// Keys listed one by one; `None` when "keys" names one SVG drawing.
    pub(crate) keys: Vec<KeySpec>,
    /// "keys": "drawing.svg": every shape of the drawing is a key.
    pub(crate) drawing: Option<PathBuf>,
}

/// Most bytes a timeline file may have.
const MAX_TIMELINE_BYTES: u64 = 16 << 20;

const TOP_FIELDS: &str = "fps, frames, loop, svg_keys, keys";
const KEY_FIELDS: &str = "curve, shape, time, duration, hold, easing, hints";

pub(crate) fn parse_svg_keys(s: &str) -> Option<SvgShapes> {
    match s {
        "auto" => Some(SvgShapes::Auto),
        "shapes" => Some(SvgShapes::Shapes),
        "groups" | "layers" => Some(SvgShapes::Groups),
        _ => None,
    }
}

/// Reads a timeline file. Errors are one line without the file name (the
/// caller adds it).
pub(crate) fn read(path: &Path) -> anyhow::Result<Timeline> {
    // Read through the cap: a device, FIFO or pipe stops at the limit.
    let bytes =
        immerse_base::input::read_capped(path, MAX_TIMELINE_BYTES).map_err(|e| match e {
            ReadError::IsDirectory => anyhow::anyhow!(
                "{} is a folder, not a timeline file; name a .json file",
                path.display()
            ),
            ReadError::Io(e) => anyhow::anyhow!(
                "cannot read {} (check the path and permissions): {e}",
                path.display()
            ),
            e => anyhow::anyhow!("{}: {e}", path.display()),
        })?;
    let dir = path.parent().unwrap_or(Path::new(""));
    parse(&bytes, dir).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))
}

/// Parses timeline JSON; curve paths are taken relative to `dir`.
pub(crate) fn parse(bytes: &[u8], dir: &Path) -> Result<Timeline, String> {
    let value: Value = serde_json::from_slice(bytes).map_err(|e| {
        let what = e.to_string();
        let what = what.split(" at line ").next().unwrap_or(&what).to_string();
        format!("{}:{}: invalid JSON: {what}", e.line(), e.column())
    })?;
    let Value::Object(top) = value else {
        return Err("expected an object with a \"keys\" array (see docs/timeline.md)".to_string());
    };
    unknown_fields(&top, TOP_FIELDS, "")?;
    let fps = number(&top, "fps", "")?;
    let frames = match top.get("frames") {
        None | Some(Value::Null) => None,
        Some(v) => Some(
            v.as_u64()
                .filter(|&f| (2..=100_000).contains(&f))
                .ok_or_else(|| {
                    format!("\"frames\" is {v}, not a whole number of frames from 2 to 100000")
                })? as usize,
        ),
    };
    let looping = match top.get("loop") {
        None | Some(Value::Null) => None,
        Some(Value::String(s)) => Some(s.parse::<render::Loop>().map_err(|_| {
            format!("\"loop\" is \"{s}\"; expected \"once\", \"loop\" or \"ping-pong\"")
        })?),
        Some(v) => {
            return Err(format!(
                "\"loop\" is {v}; expected \"once\", \"loop\" or \"ping-pong\""
            ));
        }
    };
    let svg_keys = match top.get("svg_keys") {
        None | Some(Value::Null) => None,
        Some(v) => Some(v.as_str().and_then(parse_svg_keys).ok_or_else(|| {
            format!("\"svg_keys\" is {v}; expected \"auto\", \"shapes\" or \"groups\"")
        })?),
    };
    let (keys, drawing) = match top.get("keys") {
        None => return Err("no \"keys\"; list the keys (see docs/timeline.md)".to_string()),
        Some(Value::String(s)) => (Vec::new(), Some(dir.join(s))),
        Some(Value::Array(list)) => {
            let keys = list
                .iter()
                .enumerate()
                .map(|(i, v)| key(v, i + 1, dir))
                .collect::<Result<Vec<_>, _>>()?;
            (keys, None)
        }
        Some(v) => {
            return Err(format!(
                "\"keys\" is {}, not a list of keys or the name of an SVG drawing",
                short(v)
            ));
        }
    };
    if drawing.is_none() && keys.len() < 2 {
        return Err(format!(
            "{} key given; a sequence needs at least 2 keys",
            keys.len()
        ));
    }
    Ok(Timeline {
        fps,
        frames,
        looping,
        svg_keys,
        keys,
        drawing,
    })
}

fn short(v: &Value) -> String {
    let s = v.to_string();
    if s.chars().count() > 40 {
        format!("{}…", s.chars().take(40).collect::<String>())
    } else {
        s
    }
}

fn unknown_fields(obj: &Map<String, Value>, known: &str, at: &str) -> Result<(), String> {
    let names: Vec<&str> = known.split(", ").collect();
    match obj.keys().find(|k| !names.contains(&k.as_str())) {
        Some(k) => Err(format!("{at}unknown field '{k}'; expected {known}")),
        None => Ok(()),
    }
}

fn number(obj: &Map<String, Value>, field: &str, at: &str) -> Result<Option<f64>, String> {
    match obj.get(field) {
        None | Some(Value::Null) => Ok(None),
        Some(Value::Number(x)) => Ok(x.as_f64()),
        Some(v) => Err(format!("{at}\"{field}\" is {}, not a number", short(v))),
    }
}

fn key(v: &Value, k: usize, dir: &Path) -> Result<KeySpec, String> {
    let at = format!("key {k}: ");
    let obj = match v {
        Value::String(s) => return Ok(KeySpec::plain(dir.join(s), None)),
        Value::Object(o) => o,
        _ => {
            return Err(format!(
                "{at}{} is not a key; give {{\"curve\": \"file\", ...}} or a file name",
                short(v)
            ));
        }
    };
    unknown_fields(obj, KEY_FIELDS, &at)?;
    let curve_text = match obj.get("curve") {
        Some(Value::String(s)) => s.clone(),
        None => return Err(format!("{at}no \"curve\"; name the key's curve file")),
        Some(v) => {
            return Err(format!("{at}\"curve\" is {}, not a file name", short(v)));
        }
    };
    let shape = match obj.get("shape") {
        None | Some(Value::Null) => None,
        Some(v) => Some(v.as_u64().filter(|&s| s >= 1).ok_or_else(|| {
            format!(
                "{at}\"shape\" is {}, not a shape number (counting from 1)",
                short(v)
            )
        })? as usize),
    };
    let easing = match obj.get("easing") {
        None | Some(Value::Null) => None,
        Some(Value::String(s)) => Some(
            s.parse::<render::Easing>()
                .map_err(|e| format!("{at}{e}"))?,
        ),
        Some(v) => {
            return Err(format!(
                "{at}\"easing\" is {}, not an easing name such as \"ease-in-out\"",
                short(v)
            ));
        }
    };
    let hints = match obj.get("hints") {
        None | Some(Value::Null) => Vec::new(),
        Some(Value::Object(h)) => h
            .iter()
            .map(|(name, v)| Ok((name.clone(), hint(name, v, &at)?)))
            .collect::<Result<Vec<_>, String>>()?,
        Some(v) => {
            return Err(format!(
                "{at}\"hints\" is {}, not an object of named points such as {{\"a\": 12, \"b\": [1.5, 2]}}",
                short(v)
            ));
        }
    };
    Ok(KeySpec {
        curve: dir.join(&curve_text),
        curve_text,
        shape,
        time: number(obj, "time", &at)?,
        duration: number(obj, "duration", &at)?,
        hold: number(obj, "hold", &at)?,
        easing,
        hints,
    })
}

fn hint(name: &str, v: &Value, at: &str) -> Result<HintSpec, String> {
    let bad = || {
        format!(
            "{at}hint '{name}' is {}; give a point index (12), a position ([x, y]) or {{\"fraction\": f}}",
            short(v)
        )
    };
    let finite = |x: &Value| x.as_f64().filter(|f| f.is_finite());
    match v {
        Value::Number(x) => x
            .as_u64()
            .map(|i| HintSpec::Index(i as usize))
            .ok_or_else(bad),
        Value::Array(xy) => match xy.as_slice() {
            [x, y] => match (finite(x), finite(y)) {
                (Some(x), Some(y)) => Ok(HintSpec::Position(x, y)),
                _ => Err(bad()),
            },
            _ => Err(bad()),
        },
        Value::Object(o) => {
            if o.len() != 1 {
                return Err(bad());
            }
            match (o.get("index"), o.get("at"), o.get("fraction")) {
                (Some(i), _, _) => hint(name, i, at).and_then(|h| match h {
                    HintSpec::Index(_) => Ok(h),
                    _ => Err(bad()),
                }),
                (_, Some(p), _) => hint(name, p, at).and_then(|h| match h {
                    HintSpec::Position(..) => Ok(h),
                    _ => Err(bad()),
                }),
                (_, _, Some(f)) => match finite(f) {
                    Some(f) if (0.0..=1.0).contains(&f) => Ok(HintSpec::Fraction(f)),
                    _ => Err(format!(
                        "{at}hint '{name}': fraction {} is not a number in [0, 1]",
                        short(f)
                    )),
                },
                _ => Err(bad()),
            }
        }
        _ => Err(bad()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_full_timeline_parses() {
        let t = parse(
            br#"{"fps": 24, "frames": 97, "loop": "ping-pong", "keys": [
                {"curve": "a.json", "hold": 0.5, "easing": "ease-in", "hints": {"a": 3, "b": [1, 2], "c": {"fraction": 0.25}}},
                "b.svg",
                {"curve": "c.svg", "shape": 2, "time": 3}
            ]}"#,
            Path::new("dir"),
        )
        .unwrap();
        assert_eq!(t.fps, Some(24.0));
        assert_eq!(t.frames, Some(97));
        assert_eq!(t.looping, Some(render::Loop::PingPong));
        assert_eq!(t.keys.len(), 3);
        assert_eq!(t.keys[0].curve, Path::new("dir").join("a.json"));
        assert_eq!(
            t.keys[0].hints,
            vec![
                ("a".to_string(), HintSpec::Index(3)),
                ("b".to_string(), HintSpec::Position(1.0, 2.0)),
                ("c".to_string(), HintSpec::Fraction(0.25)),
            ]
        );
        assert_eq!(t.keys[2].shape, Some(2));
        assert_eq!(t.keys[2].time, Some(3.0));
    }

    #[test]
    fn bad_timelines_say_what_is_wrong() {
        let e = |s: &str| parse(s.as_bytes(), Path::new("")).unwrap_err();
        assert_eq!(
            e(r#"{"keys": ["a.json"]}"#),
            "1 key given; a sequence needs at least 2 keys"
        );
        assert_eq!(
            e(r#"{"keys": ["a.json", {"curve": "b.json", "durration": 1}]}"#),
            "key 2: unknown field 'durration'; expected curve, shape, time, duration, hold, easing, hints"
        );
        assert_eq!(
            e(r#"{"keys": ["a.json", {"curve": "b.json", "hints": {"a": -1}}]}"#),
            "key 2: hint 'a' is -1; give a point index (12), a position ([x, y]) or {\"fraction\": f}"
        );
        assert_eq!(
            e("{\"keys\": [\n"),
            "2:0: invalid JSON: EOF while parsing a list"
        );
        assert_eq!(
            e(r#"{"keys": ["a.json", {"hold": 1}]}"#),
            "key 2: no \"curve\"; name the key's curve file"
        );
    }
}
