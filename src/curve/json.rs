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
        // serde_json gives column 0 at a line break; columns are 1-based.
        err(
            e.line(),
            e.column().max(1),
            super::error::one_line(&format!("invalid JSON: {msg}")),
        )
    })?;
    let (name, points) = match &value {
        Value::Array(items) => (None, items),
        Value::Object(map) => {
            let name = map.get("name").and_then(Value::as_str).map(str::to_string);
            if let (None, Some(Value::Array(shapes))) = (map.get("points"), map.get("shapes")) {
                // A drawing (crate::drawing): one shape is one curve;
                // several are refused, naming them.
                if let [one] = shapes.as_slice()
                    && let Some(points) = one.get("points")
                {
                    let mut raw = parse(points.to_string().as_bytes(), label)?;
                    raw.name = name;
                    return Ok(raw);
                }
                let names: Vec<String> = shapes
                    .iter()
                    .enumerate()
                    .map(|(k, s)| match s.get("id").and_then(Value::as_str) {
                        Some(id) if !id.is_empty() => {
                            format!("shape {} '{}'", k + 1, super::error::one_line(id))
                        }
                        _ => format!("shape {}", k + 1),
                    })
                    .collect();
                return Err(CurveError::SeveralParts {
                    path: label.to_string(),
                    count: names.len(),
                    parts: super::svg::list_names(&names),
                });
            }
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
    Ok(RawCurve {
        name,
        points: out,
        lines: false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regression (property `curve_json_round_trip`, tests/regressions):
    /// serde_json's default float parsing may be one ULP off, so a curve
    /// written by `immerse triangulate --json` read back as a different
    /// curve. The `float_roundtrip` feature makes parsing exact.
    #[test]
    fn coordinates_read_back_bit_for_bit() {
        let xy = [
            [0.0, 0.0],
            [-0.09422795889074179, 0.10480394518765569],
            [-0.19999999999999996, -0.15],
            [0.5, -1.5],
            [10.0, 0.0],
            [3.0, 9.0],
            [std::f64::consts::PI * 1e-7, 2.0f64.sqrt() * 1e25],
        ];
        let text = serde_json::to_string(&xy).unwrap();
        let raw = parse(text.as_bytes(), "rt.json").unwrap();
        for (i, (&[x, y], (p, _))) in xy.iter().zip(&raw.points).enumerate() {
            assert_eq!(
                (p.x.to_bits(), p.y.to_bits()),
                (x.to_bits(), y.to_bits()),
                "point {i}"
            );
        }
    }

    #[test]
    fn coordinates_are_read_correctly_rounded() {
        // Shortest round-trip digits (as Rust, ryu and serde_json write
        // them) that serde_json's default fast float parser reads one ulp
        // off; exact predicates on the curve depend on every bit.
        let (x, y) = (1.292406097716038_f64, -0.049643602872603276_f64);
        let json = format!("[[0, 0], [{x:?}, {y:?}], [1, 1]]");
        let raw = parse(json.as_bytes(), "t.json").unwrap();
        assert_eq!(raw.points[1].0.x.to_bits(), x.to_bits());
        assert_eq!(raw.points[1].0.y.to_bits(), y.to_bits());
        // And everything serde_json writes reads back bit for bit.
        let pts: Vec<[f64; 2]> = (1..500)
            .map(|i| {
                let a = f64::from(i) * 0.7311;
                [a.sin() * 1.7e3 / 3.0, a.cos() / 7.0]
            })
            .collect();
        let text = serde_json::to_string(&pts).unwrap();
        let raw = parse(text.as_bytes(), "t.json").unwrap();
        for (p, q) in raw.points.iter().zip(&pts) {
            assert_eq!([p.0.x.to_bits(), p.0.y.to_bits()], q.map(f64::to_bits));
        }
    }
}
