//! Drawings in JSON: `{"shapes": [{"id", "points", "fill", "stroke",
//! "stroke_width", "opacity", "fill_rule"}]}`.

use super::style::{Color, FillRule, Style};
use super::{Drawing, DrawingError, Shape};
use crate::curve::{Curve, CurveError, Format};
use serde_json::Value;

const SHAPE: &str = r##"expected {"shapes": [{"id": "...", "points": [[x, y], ...], "fill": "#rrggbb" or null, "stroke": "#rrggbb" or null, "stroke_width": w, "opacity": o, "fill_rule": "nonzero" or "evenodd"}, ...]}"##;

/// True when the data is a JSON object with a `shapes` field.
pub(super) fn is_drawing(bytes: &[u8]) -> bool {
    // Only the top level is looked at; the full parse reports errors.
    matches!(serde_json::from_slice::<Value>(bytes), Ok(Value::Object(m)) if m.contains_key("shapes"))
}

pub(super) fn read(bytes: &[u8], label: &str, name: &str) -> Result<Drawing, DrawingError> {
    let shape_err = |message: String| {
        DrawingError::Curve(CurveError::JsonShape {
            path: label.to_string(),
            message,
        })
    };
    let value: Value = serde_json::from_slice(bytes).map_err(|e| {
        shape_err(format!(
            "invalid JSON at line {} column {}: {e}",
            e.line(),
            e.column()
        ))
    })?;
    let Some(Value::Array(items)) = value.get("shapes") else {
        return Err(shape_err(format!("\"shapes\" is not an array; {SHAPE}")));
    };
    let name = value
        .get("name")
        .and_then(Value::as_str)
        .unwrap_or(name)
        .to_string();
    let mut shapes: Vec<Shape> = Vec::with_capacity(items.len());
    for (k, item) in items.iter().enumerate() {
        let Value::Object(map) = item else {
            return Err(shape_err(format!(
                "shape {} is not an object; {SHAPE}",
                k + 1
            )));
        };
        let id = match map.get("id") {
            None | Some(Value::Null) => String::new(),
            Some(Value::String(s)) => s.clone(),
            Some(v) => v.to_string(),
        };
        let shape_label = if id.is_empty() {
            format!("shape {}", k + 1)
        } else {
            format!("shape {} '{}'", k + 1, crate::curve::error_one_line(&id))
        };
        let at = format!("{label} ({shape_label})");
        let field_err = |field: &str, want: &str| {
            DrawingError::Curve(CurveError::JsonShape {
                path: at.clone(),
                message: format!("\"{field}\" must be {want}; {SHAPE}"),
            })
        };
        let colour = |field: &str, default: Option<Color>| match map.get(field) {
            None => Ok(default),
            Some(Value::Null) => Ok(None),
            Some(Value::String(s)) if s == "none" => Ok(None),
            Some(Value::String(s)) => Color::parse_hex(s)
                .map(Some)
                .ok_or_else(|| field_err(field, "a colour \"#rrggbb\" or \"#rgb\", or null")),
            Some(_) => Err(field_err(
                field,
                "a colour \"#rrggbb\" or \"#rgb\", or null",
            )),
        };
        let number = |field: &str, default: f64, ok: &dyn Fn(f64) -> bool, want: &str| match map
            .get(field)
        {
            None => Ok(default),
            Some(v) => v
                .as_f64()
                .filter(|x| ok(*x))
                .ok_or_else(|| field_err(field, want)),
        };
        let style = Style {
            fill: colour("fill", Some(Color::BLACK))?,
            stroke: colour("stroke", None)?,
            stroke_width: number(
                "stroke_width",
                1.0,
                &|x| x.is_finite() && x >= 0.0,
                "a number ≥ 0",
            )?,
            opacity: number(
                "opacity",
                1.0,
                &|x| (0.0..=1.0).contains(&x),
                "a number in [0, 1]",
            )?,
            fill_rule: match map.get("fill_rule").and_then(Value::as_str) {
                None if map.get("fill_rule").is_none() => FillRule::Nonzero,
                Some("nonzero") => FillRule::Nonzero,
                Some("evenodd") => FillRule::Evenodd,
                _ => return Err(field_err("fill_rule", "\"nonzero\" or \"evenodd\"")),
            },
        };
        let Some(points) = map.get("points") else {
            return Err(field_err("points", "an array of [x, y] pairs"));
        };
        let curve = Curve::from_bytes(points.to_string().as_bytes(), Format::Json, &at, &name)?;
        if !id.is_empty()
            && let Some(first) = shapes.iter().position(|s| s.id == id)
        {
            return Err(DrawingError::DuplicateId {
                path: label.to_string(),
                id,
                first: first + 1,
                second: k + 1,
            });
        }
        shapes.push(Shape::new(id, shape_label, curve, style));
    }
    if shapes.is_empty() {
        return Err(DrawingError::Empty {
            path: label.to_string(),
            why: "\"shapes\" is empty".to_string(),
        });
    }
    Ok(Drawing {
        name,
        single_curve: false,
        shapes,
        notices: Vec::new(),
    })
}
