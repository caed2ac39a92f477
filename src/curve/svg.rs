//! SVG curves, parsed with `usvg` (which turns `rect`, `circle`, `ellipse`,
//! `polygon` and `path` elements into paths and resolves transforms).
//!
//! The curve is the first closed subpath in document order: a subpath that
//! ends with `Z`, or whose last point equals its first. Its control points
//! are mapped by the element's absolute transform, Béziers are flattened
//! to [`SVG_FLATTEN_TOLERANCE`] times the diagonal of the subpath's control
//! polygon bounds, and y is negated (SVG is y down, immerse is y up).

use super::error::one_line;
use super::{CurveError, RawCurve};
use crate::geom::Point;

/// Flattening tolerance for Bézier segments, relative to the diagonal of
/// the shape's bounding box: the flattened polyline stays within this
/// fraction of the diagonal of the true curve (0.1%).
pub const SVG_FLATTEN_TOLERANCE: f64 = 1e-3;

/// Upper bound on the segments one Bézier is split into, so that a
/// malformed file cannot ask for unbounded work.
const MAX_SEGMENTS_PER_CURVE: usize = 256;

#[derive(Clone, Copy)]
enum Seg {
    Line(Point),
    Quad(Point, Point),
    Cubic(Point, Point, Point),
}

pub(crate) fn parse(bytes: &[u8], label: &str) -> Result<RawCurve, CurveError> {
    let tree =
        usvg::Tree::from_data(bytes, &usvg::Options::default()).map_err(|e| CurveError::Svg {
            path: label.to_string(),
            message: one_line(&e.to_string()),
        })?;
    let mut found = None;
    find_closed(tree.root(), &mut found);
    let Some((start, segs)) = found else {
        return Err(CurveError::NoClosedShape {
            path: label.to_string(),
        });
    };
    let (mut lo, mut hi) = (start, start);
    for s in &segs {
        let pts: &[Point] = match s {
            Seg::Line(a) => &[*a],
            Seg::Quad(a, b) => &[*a, *b],
            Seg::Cubic(a, b, c) => &[*a, *b, *c],
        };
        for &p in pts {
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    let tol = (SVG_FLATTEN_TOLERANCE * (hi - lo).length()).max(f64::MIN_POSITIVE);
    let mut points = vec![start];
    let mut cur = start;
    for s in segs {
        match s {
            Seg::Line(p) => points.push(p),
            Seg::Quad(c, p) => {
                let dd = (cur - 2.0 * c + p).length();
                let n = segments_for(0.25 * dd, tol);
                for i in 1..=n {
                    let t = i as f64 / n as f64;
                    let u = 1.0 - t;
                    points.push(u * u * cur + 2.0 * u * t * c + t * t * p);
                }
            }
            Seg::Cubic(c1, c2, p) => {
                let dd = (cur - 2.0 * c1 + c2)
                    .length()
                    .max((c1 - 2.0 * c2 + p).length());
                let n = segments_for(0.75 * dd, tol);
                for i in 1..=n {
                    let t = i as f64 / n as f64;
                    let u = 1.0 - t;
                    points.push(
                        u * u * u * cur
                            + 3.0 * u * u * t * c1
                            + 3.0 * u * t * t * c2
                            + t * t * t * p,
                    );
                }
            }
        }
        cur = *points.last().unwrap_or(&cur);
    }
    // Flip y: SVG is y down.
    let points = points
        .into_iter()
        .enumerate()
        .map(|(i, p)| (Point::new(p.x, -p.y), i))
        .collect();
    Ok(RawCurve {
        name: None,
        points,
        lines: false,
    })
}

/// Segments needed so that a Bézier whose second differences are bounded
/// by `m / (scale factor already applied)` deviates by at most `tol` from
/// its chords: n = ⌈√(m / tol)⌉ (Wang's bound).
fn segments_for(m: f64, tol: f64) -> usize {
    let n = (m / tol).sqrt().ceil();
    if n.is_finite() {
        (n as usize).clamp(1, MAX_SEGMENTS_PER_CURVE)
    } else {
        MAX_SEGMENTS_PER_CURVE
    }
}

fn find_closed(group: &usvg::Group, found: &mut Option<(Point, Vec<Seg>)>) {
    for node in group.children() {
        if found.is_some() {
            return;
        }
        match node {
            usvg::Node::Group(g) => find_closed(g, found),
            usvg::Node::Path(path) => {
                let ts = path.abs_transform();
                let map = |p: usvg::tiny_skia_path::Point| {
                    let (x, y) = (f64::from(p.x), f64::from(p.y));
                    Point::new(
                        f64::from(ts.sx) * x + f64::from(ts.kx) * y + f64::from(ts.tx),
                        f64::from(ts.ky) * x + f64::from(ts.sy) * y + f64::from(ts.ty),
                    )
                };
                let mut start: Option<Point> = None;
                let mut segs: Vec<Seg> = Vec::new();
                let mut last = Point::ZERO;
                for seg in path.data().segments() {
                    use usvg::tiny_skia_path::PathSegment as S;
                    match seg {
                        S::MoveTo(p) => {
                            // An open subpath ends here; a closed one would
                            // have returned already.
                            if let Some(s) = start
                                && !segs.is_empty()
                                && last == s
                            {
                                *found = Some((s, segs));
                                return;
                            }
                            start = Some(map(p));
                            last = map(p);
                            segs.clear();
                        }
                        S::LineTo(p) => {
                            last = map(p);
                            segs.push(Seg::Line(last));
                        }
                        S::QuadTo(c, p) => {
                            last = map(p);
                            segs.push(Seg::Quad(map(c), last));
                        }
                        S::CubicTo(c1, c2, p) => {
                            last = map(p);
                            segs.push(Seg::Cubic(map(c1), map(c2), last));
                        }
                        S::Close => {
                            if let Some(s) = start
                                && !segs.is_empty()
                            {
                                *found = Some((s, segs));
                                return;
                            }
                        }
                    }
                }
                if let Some(s) = start
                    && !segs.is_empty()
                    && last == s
                {
                    *found = Some((s, segs));
                    return;
                }
            }
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regression (fuzz target `curve_svg`, seed
    /// `fuzz/seeds/curve_svg/regression-newline-in-parser-message.svg`):
    /// the XML parser quotes the offending character, here a line break,
    /// which split the CLI's one-line error in two.
    #[test]
    fn parser_messages_stay_on_one_line() {
        let data =
            b"<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M0 0 L1 0 L0 1 Z\"/\n</svg>";
        let e = parse(data, "s.svg").unwrap_err();
        let msg = e.to_string();
        assert!(matches!(e, CurveError::Svg { .. }), "{msg}");
        assert!(!msg.contains('\n'), "{msg:?}");
        assert!(msg.contains("\\n"), "the character is shown escaped: {msg}");
        let crash =
            include_bytes!("../../fuzz/seeds/curve_svg/regression-newline-in-parser-message.svg");
        let msg = parse(crash, "c.svg").unwrap_err().to_string();
        assert!(!msg.chars().any(char::is_control), "{msg:?}");
    }
}
