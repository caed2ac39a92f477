//! Text curves: one `x y` pair per line, separated by whitespace or a
//! comma; `#` starts a comment; blank lines are skipped.

use super::error::one_line;
use super::{CurveError, RawCurve};
use crate::geom::Point;

pub(crate) fn parse(bytes: &[u8], label: &str) -> Result<RawCurve, CurveError> {
    let text = std::str::from_utf8(bytes).map_err(|e| CurveError::Text {
        path: label.to_string(),
        line: 1 + bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count(),
        message: "not UTF-8 text; save the file as plain text".to_string(),
    })?;
    let mut points = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let content = line.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let fields: Vec<&str> = content
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|f| !f.is_empty())
            .collect();
        let bad = |message: String| CurveError::Text {
            path: label.to_string(),
            line: i + 1,
            message: one_line(&message),
        };
        if fields.len() != 2 {
            return Err(bad(format!(
                "expected two numbers 'x y', found {} field(s) in '{content}'",
                fields.len()
            )));
        }
        let num = |f: &str| {
            f.parse::<f64>()
                .map_err(|_| bad(format!("'{f}' is not a number (in '{content}')")))
        };
        let p = Point::new(num(fields[0])?, num(fields[1])?);
        if !p.is_finite() {
            return Err(bad(format!(
                "non-finite coordinate in '{content}'; give finite numbers"
            )));
        }
        points.push((p, i + 1));
    }
    Ok(RawCurve {
        name: None,
        points,
        lines: true,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_commas_and_blank_lines() {
        let r = parse(b"# hexagon\n0 0\n1,0 # right\n\n 1 , 1\n", "t").unwrap();
        let pts: Vec<Point> = r.points.iter().map(|p| p.0).collect();
        assert_eq!(
            pts,
            vec![Point::new(0., 0.), Point::new(1., 0.), Point::new(1., 1.)]
        );
        assert_eq!(r.points[2].1, 5);
    }

    /// Regression (fuzz target `curve_text` hardening): a carriage return
    /// or tab inside a line is escaped, so the message stays on one line.
    #[test]
    fn control_characters_are_escaped_in_messages() {
        let e = parse(b"0 0\n1\r2\t3\n", "t.txt").unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.txt:2: expected two numbers 'x y', found 3 field(s) in '1\\r2\\t3'"
        );
    }

    #[test]
    fn errors_name_the_line() {
        let e = parse(b"0 0\n1 2 3\n", "t.txt").unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.txt:2: expected two numbers 'x y', found 3 field(s) in '1 2 3'"
        );
        let e = parse(b"0 0\nnan 1\n", "t.txt").unwrap_err();
        assert!(e.to_string().starts_with("t.txt:2: non-finite"), "{e}");
    }
}
