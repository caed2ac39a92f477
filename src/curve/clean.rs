//! Cleaning and orientation: range checks, duplicate removal, degeneracy
//! checks and reversal of clockwise curves.

use super::{Curve, CurveError};
use crate::geom::polygon::{Turning, turning_number};
use crate::geom::{Orientation, Point, orient};

/// Largest coordinate magnitude accepted. Products of four coordinates in
/// the in-circle predicate stay far below `f64::MAX` (≈ 1.8e308), as in
/// spade's `MAX_ALLOWED_VALUE` (its bound is 2^201 for the same reason);
/// 1e30 is a round bound with room to spare that no drawing approaches.
pub const MAX_COORDINATE: f64 = 1e30;

/// Smallest non-zero coordinate magnitude accepted. Below it the error
/// terms of the adaptive predicates could underflow (spade rejects values
/// below 2^-142 for the same reason); 1e-30 leaves room to spare.
pub const MIN_COORDINATE: f64 = 1e-30;

/// Most points accepted in one curve (after reading, before cleaning).
pub const MAX_POINTS: usize = 200_000;

pub(crate) fn build(
    name: String,
    raw: Vec<(Point, usize)>,
    lines: bool,
    label: &str,
) -> Result<Curve, CurveError> {
    if raw.len() > MAX_POINTS {
        return Err(CurveError::TooLarge {
            path: label.to_string(),
            what: format!("{} points", raw.len()),
            limit: format!("{MAX_POINTS} points"),
        });
    }
    for (index, &(p, place)) in raw.iter().enumerate() {
        let place = if lines {
            format!("line {place}")
        } else {
            "counting from 0".to_string()
        };
        if !p.is_finite() {
            return Err(CurveError::NonFinite {
                path: label.to_string(),
                index,
                place,
            });
        }
        for v in [p.x, p.y] {
            let a = v.abs();
            if a > MAX_COORDINATE || (a != 0.0 && a < MIN_COORDINATE) {
                return Err(CurveError::OutOfRange {
                    path: label.to_string(),
                    index,
                    place,
                    value: v,
                    min: MIN_COORDINATE,
                    max: MAX_COORDINATE,
                });
            }
        }
    }
    let total = raw.len();
    let mut points: Vec<Point> = Vec::with_capacity(total);
    // The cleaned vertex each point as read became (before reversal).
    let mut source_vertex: Vec<usize> = Vec::with_capacity(total);
    for (p, _) in raw {
        if points.last() != Some(&p) {
            points.push(p);
        }
        source_vertex.push(points.len() - 1);
    }
    while points.len() > 1 && points.first() == points.last() {
        // A closing point equal to the first: the points it absorbed are
        // the first vertex.
        let last = points.len() - 1;
        points.pop();
        for v in source_vertex.iter_mut().filter(|v| **v == last) {
            *v = 0;
        }
    }
    let dropped = total - points.len();
    let mut distinct = points.clone();
    distinct.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    distinct.dedup();
    if distinct.len() < 3 {
        return Err(CurveError::TooFewPoints {
            path: label.to_string(),
            distinct: distinct.len(),
        });
    }
    let (a, b) = (distinct[0], distinct[1]);
    if points
        .iter()
        .all(|&p| orient(a, b, p) == Orientation::Collinear)
    {
        return Err(CurveError::ZeroArea {
            path: label.to_string(),
            count: points.len(),
        });
    }
    let turning_as_given = turning_number(&points);
    let reversed = turning_as_given == Turning::Number(-1);
    if reversed {
        points[1..].reverse();
        let n = points.len();
        for v in &mut source_vertex {
            *v = (n - *v) % n;
        }
    }
    Ok(Curve {
        name,
        points,
        reversed,
        turning_as_given,
        dropped,
        source_vertex,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn raw(xy: &[(f64, f64)]) -> Vec<(Point, usize)> {
        xy.iter()
            .enumerate()
            .map(|(i, &(x, y))| (Point::new(x, y), i + 1))
            .collect()
    }

    /// [`build`] of the points `xy` (not lines of a text file), named
    /// `name` in the curve and in messages.
    fn build_as(name: &str, xy: &[(f64, f64)]) -> Result<Curve, CurveError> {
        build(name.into(), raw(xy), false, name)
    }

    #[test]
    fn drops_closing_and_consecutive_duplicates() {
        let c = build_as(
            "sq",
            &[(0., 0.), (1., 0.), (1., 0.), (1., 1.), (0., 1.), (0., 0.)],
        )
        .unwrap();
        assert_eq!(c.points.len(), 4);
        assert_eq!(c.dropped, 2);
        assert!(!c.reversed);
    }

    #[test]
    fn reverses_clockwise_keeping_the_first_point() {
        let c = build_as("cw", &[(0., 0.), (0., 1.), (1., 1.), (1., 0.)]).unwrap();
        assert!(c.reversed);
        assert_eq!(c.turning_as_given, Turning::Number(-1));
        assert_eq!(c.points[0], Point::new(0., 0.));
        assert_eq!(c.points[1], Point::new(1., 0.));
        assert_eq!(c.turning_number(), Some(1));
    }

    #[test]
    fn source_points_map_to_their_cleaned_vertices() {
        // Repeated points, a closing point, and a reversal.
        let raw_pts = [
            (0., 0.),
            (0., 1.),
            (0., 1.),
            (1., 1.),
            (1., 0.),
            (0., 0.),
            (0., 0.),
        ];
        let c = build_as("cw", &raw_pts).unwrap();
        assert!(c.reversed);
        assert_eq!(c.source_vertex.len(), 7);
        for (r, &(x, y)) in raw_pts.iter().enumerate() {
            assert_eq!(c.points[c.source_vertex[r]], Point::new(x, y), "point {r}");
        }
        assert_eq!(c.source_vertex, vec![0, 3, 3, 2, 1, 0, 0]);
    }

    #[test]
    fn rejects_degenerate_curves() {
        let e = build_as("x", &[(0., 0.), (1., 1.), (0., 0.)]).unwrap_err();
        assert!(
            matches!(e, CurveError::TooFewPoints { distinct: 2, .. }),
            "{e}"
        );
        let e = build_as("x", &[(0., 0.), (1., 1.), (3., 3.), (2., 2.)]).unwrap_err();
        assert!(matches!(e, CurveError::ZeroArea { .. }), "{e}");
        let e = build_as("x", &[(0., 0.), (1., f64::NAN), (3., 3.)]).unwrap_err();
        assert!(matches!(e, CurveError::NonFinite { index: 1, .. }), "{e}");
        let e = build_as("x", &[(0., 0.), (1., 1e40), (3., 3.)]).unwrap_err();
        assert!(matches!(e, CurveError::OutOfRange { index: 1, .. }), "{e}");
    }

    #[test]
    fn out_of_range_names_the_line_or_the_index() {
        let pts = raw(&[(0., 0.), (1., 0.), (1e40, 1.)]);
        let e = build("x".into(), pts, true, "t.txt").unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.txt: point 2 (line 3) has a coordinate of magnitude 1e40, outside [1e-30, 1e30]; rescale the curve"
        );
        let pts = raw(&[(0., 0.), (f64::INFINITY, 0.), (1., 1.)]);
        let e = build("x".into(), pts, false, "p.json").unwrap_err();
        assert_eq!(
            e.to_string(),
            "p.json: point 1 (counting from 0) has a non-finite coordinate; give finite numbers"
        );
    }
}
