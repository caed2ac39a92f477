//! JSON curves: `{"name": "...", "points": [[x, y], ...]}` or a bare array.

use super::{CurveError, RawCurve};
use crate::geom::Point;
use serde_json::Value;

const SHAPE: &str = r#"expected {"points": [[x, y], ...]} or a bare array of [x, y] pairs"#;

pub(crate) fn parse(bytes: &[u8], label: &str) -> Result<RawCurve, CurveError> {
    let err = |line, column, message: String| CurveError::Json {
        path: label.to_string(),
        line,
        column,
        message,
    };
    let shape = |message: String| CurveError::JsonShape {
        path: label.to_string(),
        message,
    };
    let value: Value = serde_json::from_slice(bytes).map_err(|e| {
        let msg = e.to_string();
        // serde_json appends " at line L column C"; we report those apart.
        let msg = msg.split(" at line ").next().unwrap_or(&msg).to_string();
        err(e.line(), e.column(), format!("invalid JSON: {msg}"))
    })?;
    let (name, points) = match &value {
        Value::Array(items) => (None, items),
        Value::Object(map) => {
            let name = map.get("name").and_then(Value::as_str).map(str::to_string);
            match map.get("points") {
                Some(Value::Array(items)) => (name, items),
                Some(_) => return Err(shape(format!("\"points\" is not an array; {SHAPE}"))),
                None => return Err(shape(format!("no \"points\" field; {SHAPE}"))),
            }
        }
        _ => return Err(shape(SHAPE.to_string())),
    };
    let mut out = Vec::with_capacity(points.len());
    for (i, item) in points.iter().enumerate() {
        let pair = item.as_array().filter(|a| a.len() == 2);
        let xy = pair.and_then(|a| Some((a[0].as_f64()?, a[1].as_f64()?)));
        let Some((x, y)) = xy else {
            let mut shown = item.to_string();
            if shown.len() > 40 {
                shown = format!("{}…", shown.chars().take(40).collect::<String>());
            }
            return Err(shape(format!(
                "point {i} is {shown}, not an [x, y] pair of numbers; {SHAPE}"
            )));
        };
        out.push((Point::new(x, y), i));
    }
    Ok(RawCurve { name, points: out })
}
