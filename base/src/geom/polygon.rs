//! Measures of closed polygons: signed area, area centroid, exact turning
//! number and an exact simplicity test.

use super::Point;
use super::predicates::{Orientation, half_plane_class, orient};

/// Twice the signed area of the closed polygon (positive when
/// counter-clockwise). Coordinates are shifted to the first vertex before
/// the shoelace sum to reduce cancellation.
pub fn signed_area(points: &[Point]) -> f64 {
    let Some(&o) = points.first() else {
        return 0.0;
    };
    let n = points.len();
    let mut sum = 0.0;
    for i in 1..n.saturating_sub(1) {
        sum += (points[i] - o).perp_dot(points[i + 1] - o);
    }
    0.5 * sum
}

/// The area centroid of the closed polygon (signed; overlapping parts count
/// with their winding number). Falls back to the vertex mean when the
/// signed area is zero.
pub fn area_centroid(points: &[Point]) -> Point {
    let Some(&o) = points.first() else {
        return Point::ZERO;
    };
    let n = points.len();
    let (mut a2, mut c) = (0.0, Point::ZERO);
    for i in 1..n.saturating_sub(1) {
        let (p, q) = (points[i] - o, points[i + 1] - o);
        let cross = p.perp_dot(q);
        a2 += cross;
        c += (p + q) * cross;
    }
    if a2 == 0.0 {
        return points.iter().copied().sum::<Point>() / n as f64;
    }
    o + c / (3.0 * a2)
}

/// Outcome of [`turning_number`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Turning {
    /// The tangent direction turns `k` full times counter-clockwise.
    Number(i64),
    /// The curve reverses direction at this vertex (a cusp: the turn there
    /// is exactly ±π), so the turning number is undefined.
    Cusp(usize),
}

/// Exact turning number of a closed polygon without consecutive duplicate
/// vertices.
///
/// Counts the signed passes of the edge direction through the +x direction:
/// each vertex turns by less than π one way or the other (the sign is the
/// exact orientation of the three points), and whether the turn passes the
/// reference direction is decided by half-plane classes and that same sign.
pub fn turning_number(points: &[Point]) -> Turning {
    let n = points.len();
    let origin = Point::ZERO;
    let east = Point::X;
    // Direction class of edge i relative to +x, and the ordering inside a
    // class via the orientation of consecutive edges.
    let mut k: i64 = 0;
    for i in 0..n {
        let (a, b, c) = (points[(i + n - 1) % n], points[i], points[(i + 1) % n]);
        let turn = orient(a, b, c);
        let ca = half_plane_class(origin, east, b - a);
        let cb = half_plane_class(origin, east, c - b);
        let (Some(ca), Some(cb)) = (ca, cb) else {
            // Consecutive duplicates are removed by cleaning; a zero edge
            // here has no direction. Treat as a cusp at this vertex.
            return Turning::Cusp(i);
        };
        // φ(d) for d = edge direction. A counter-clockwise turn (less than
        // π) passes the +x ray iff the angle falls; a clockwise one iff it
        // rises. Inside one open half-plane class the order of the two
        // directions is the sign of the turn itself, so only a change of
        // class can wrap. Arriving on the ray counts, leaving it does not.
        match turn {
            Orientation::CounterClockwise => k += i64::from(cb < ca),
            Orientation::Clockwise => k -= i64::from(cb > ca),
            Orientation::Collinear => {
                if ca != cb {
                    // Straight on keeps the class; a reversal is a cusp.
                    return Turning::Cusp(i);
                }
            }
        }
    }
    Turning::Number(k)
}

/// Do the closed segments `a–b` and `c–d` share at least one point? Exact.
#[inline]
pub(crate) fn segments_touch(a: Point, b: Point, c: Point, d: Point) -> bool {
    let o1 = orient(a, b, c);
    let o2 = orient(a, b, d);
    let o3 = orient(c, d, a);
    let o4 = orient(c, d, b);
    if o1 != o2 && o3 != o4 {
        return true;
    }
    let on = |p: Point, q: Point, r: Point| {
        // r on the closed segment p–q, given the three are collinear.
        r.x >= p.x.min(q.x) && r.x <= p.x.max(q.x) && r.y >= p.y.min(q.y) && r.y <= p.y.max(q.y)
    };
    (o1 == Orientation::Collinear && on(a, b, c))
        || (o2 == Orientation::Collinear && on(a, b, d))
        || (o3 == Orientation::Collinear && on(c, d, a))
        || (o4 == Orientation::Collinear && on(c, d, b))
}

/// The first pair of edges `(i, j)` (edge i joins vertex i to i + 1) that
/// touch where they should not, or `None` when the polygon is simple.
///
/// Adjacent edges may share only their common vertex; other edges may not
/// touch at all. Edges are swept in order of their left end so only pairs
/// whose x-ranges overlap are tested exactly.
pub fn first_self_intersection(points: &[Point]) -> Option<(usize, usize)> {
    let n = points.len();
    if n < 3 {
        return None;
    }
    let seg = |i: usize| (points[i], points[(i + 1) % n]);
    let mut order: Vec<usize> = (0..n).collect();
    let min_x = |i: usize| {
        let (a, b) = seg(i);
        a.x.min(b.x)
    };
    order.sort_by(|&i, &j| min_x(i).total_cmp(&min_x(j)));
    let mut active: Vec<usize> = Vec::new();
    let mut best: Option<(usize, usize)> = None;
    for &i in &order {
        let (a, b) = seg(i);
        let lo = a.x.min(b.x);
        active.retain(|&j| {
            let (c, d) = seg(j);
            c.x.max(d.x) >= lo
        });
        for &j in &active {
            let (c, d) = seg(j);
            let (lo_y, hi_y) = (a.y.min(b.y), a.y.max(b.y));
            if c.y.max(d.y) < lo_y || c.y.min(d.y) > hi_y {
                continue;
            }
            let bad = if (i + 1) % n == j || (j + 1) % n == i {
                // Adjacent: share vertex s; bad when they overlap along a
                // line (the far end of one lies on the other).
                let (s, p, q) = if (i + 1) % n == j {
                    (b, a, d)
                } else {
                    (a, b, c)
                };
                orient(p, s, q) == Orientation::Collinear && half_plane_class(s, p, q) == Some(0)
            } else {
                segments_touch(a, b, c, d)
            };
            if bad {
                let pair = (i.min(j), i.max(j));
                if best.is_none_or(|b| pair < b) {
                    best = Some(pair);
                }
            }
        }
        active.push(i);
    }
    best
}

/// True when the polygon has no self-intersection (see
/// [`first_self_intersection`]).
pub fn is_simple(points: &[Point]) -> bool {
    first_self_intersection(points).is_none()
}

/// The three interior angles (radians) of the triangle `a, b, c`, at `a`,
/// `b` and `c`. Measurement only: never used for a decision.
#[inline]
pub fn triangle_angles(a: Point, b: Point, c: Point) -> [f64; 3] {
    let ang = |p: Point, q: Point, r: Point| {
        let (u, v) = (q - p, r - p);
        u.perp_dot(v).abs().atan2(u.dot(v))
    };
    [ang(a, b, c), ang(b, c, a), ang(c, a, b)]
}

/// sin² of the smallest angle of the triangle `a, b, c` (a measurement).
#[inline]
pub fn sin2_min_angle(a: Point, b: Point, c: Point) -> f64 {
    let (ab, bc, ca) = (b - a, c - b, a - c);
    let (x, y, z) = (
        ab.length_squared(),
        bc.length_squared(),
        ca.length_squared(),
    );
    let cross = ab.perp_dot(c - a);
    let big = x.max(y).max(z);
    let mid = if big == x {
        y.max(z)
    } else if big == y {
        x.max(z)
    } else {
        x.max(y)
    };
    let denom = big * mid;
    if denom > 0.0 {
        (cross * cross / denom).min(1.0)
    } else {
        0.0
    }
}

/// The sine of the smallest interior angle of the triangle `a, b, c`
/// (the smallest angle is at most π/3, so its sine orders triangles as the
/// angle does), without trigonometry: the least of |cross| / (|u| |v|)
/// over the corners (the obtuse corner's sine is never smaller). 0 for a
/// degenerate triangle. Measurement only.
#[inline]
pub fn min_angle_sine(a: Point, b: Point, c: Point) -> f64 {
    let (ab, bc, ca) = (b - a, c - b, a - c);
    let cross = ab.perp_dot(bc).abs();
    let (lab, lbc, lca) = (ab.length(), bc.length(), ca.length());
    let den = (lab * lbc).max(lbc * lca).max(lca * lab);
    if den > 0.0 && cross.is_finite() {
        cross / den
    } else {
        0.0
    }
}

/// A total order on point lists by their coordinates' bit patterns: the
/// tie-break that makes pairwise choices independent of argument order
/// (`lex_key(a) < lex_key(b)` picks the same curve either way round).
pub fn lex_key(points: &[Point]) -> Vec<u64> {
    points
        .iter()
        .flat_map(|q| [q.x.to_bits(), q.y.to_bits()])
        .collect()
}

/// The length of the diagonal of the axis-aligned bounding box of `points`
/// (0 for none). Measurement only.
pub fn bbox_diagonal(points: &[Point]) -> f64 {
    if points.is_empty() {
        return 0.0;
    }
    let lo = points
        .iter()
        .copied()
        .fold(Point::splat(f64::INFINITY), Point::min);
    let hi = points
        .iter()
        .copied()
        .fold(Point::splat(f64::NEG_INFINITY), Point::max);
    (hi - lo).length()
}

/// Total absolute turning of a closed polygon: the sum over vertices of
/// the absolute exterior (turning) angle, radians. Measurement only.
pub fn total_absolute_turning(points: &[Point]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|i| {
            let a = points[(i + n - 1) % n];
            let b = points[i];
            let c = points[(i + 1) % n];
            let (u, v) = (b - a, c - b);
            u.perp_dot(v).atan2(u.dot(v)).abs()
        })
        .sum()
}

/// The smallest interior angle (radians) over the triangles `tris` of
/// `points`; +∞ when there are none. Measurement only.
pub fn min_triangle_angle(points: &[Point], tris: &[[u32; 3]]) -> f64 {
    tris.iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| points[v as usize]);
            let [x, y, z] = triangle_angles(a, b, c);
            x.min(y).min(z)
        })
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly(xy: &[(f64, f64)]) -> Vec<Point> {
        xy.iter().map(|&(x, y)| Point::new(x, y)).collect()
    }

    fn float_turning(points: &[Point]) -> i64 {
        let n = points.len();
        let mut total = 0.0;
        for i in 0..n {
            let d0 = points[i] - points[(i + n - 1) % n];
            let d1 = points[(i + 1) % n] - points[i];
            total += d0.perp_dot(d1).atan2(d0.dot(d1));
        }
        (total / std::f64::consts::TAU).round() as i64
    }

    #[test]
    fn square_and_reversed_square() {
        let sq = poly(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]);
        assert_eq!(turning_number(&sq), Turning::Number(1));
        let mut rev = sq.clone();
        rev.reverse();
        assert_eq!(turning_number(&rev), Turning::Number(-1));
        assert_eq!(signed_area(&sq), 1.0);
        assert!(is_simple(&sq));
        assert_eq!(area_centroid(&sq), Point::new(0.5, 0.5));
    }

    #[test]
    fn circle_twice_has_turning_two() {
        let pts: Vec<Point> = (0..40)
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU * 2.0 / 40.0 + 0.1;
                Point::new(a.cos(), a.sin())
            })
            .collect();
        // Goes round twice through the same 20 positions: not simple.
        assert_eq!(turning_number(&pts), Turning::Number(2));
        assert!(!is_simple(&pts));
    }

    #[test]
    fn exact_turning_agrees_with_float_sum_on_random_polygons() {
        let mut s: u64 = 0x9e3779b97f4a7c15;
        let mut rnd = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..2000 {
            let n = 3 + (rnd() * 12.0) as usize;
            let pts: Vec<Point> = (0..n).map(|_| Point::new(rnd(), rnd())).collect();
            match turning_number(&pts) {
                Turning::Number(k) => assert_eq!(k, float_turning(&pts), "{pts:?}"),
                Turning::Cusp(_) => {}
            }
            let mut rev = pts.clone();
            rev.reverse();
            if let (Turning::Number(a), Turning::Number(b)) =
                (turning_number(&pts), turning_number(&rev))
            {
                assert_eq!(a, -b);
            }
        }
    }

    #[test]
    fn figure_eight_is_not_simple_and_turns_zero() {
        let pts = poly(&[(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0)]);
        assert_eq!(turning_number(&pts), Turning::Number(0));
        assert_eq!(first_self_intersection(&pts), Some((0, 2)));
    }

    #[test]
    fn cusp_is_reported() {
        let pts = poly(&[(0.0, 0.0), (2.0, 0.0), (1.0, 0.0), (1.0, 1.0)]);
        assert!(matches!(turning_number(&pts), Turning::Cusp(_)));
        assert!(!is_simple(&pts));
    }
}
