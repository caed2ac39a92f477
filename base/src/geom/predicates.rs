//! Exact geometric predicates.
//!
//! Every orientation, in-circle and angle-order decision in immerse is made
//! here, with Shewchuk's adaptive-precision predicates (the `robust` crate),
//! so the answer is the sign of the exact determinant of the `f64` inputs.
//! Convention: [`orient`]`(a, b, c)` is [`Orientation::CounterClockwise`]
//! when `c` lies strictly to the left of the directed line `a → b` (y up).
//!
//! Angles are never compared through `atan2`. The counter-clockwise angle
//! φ ∈ [0, 2π) of a direction relative to a reference direction is ordered
//! by its half-plane class (on the reference ray, strictly left, on the
//! opposite ray, strictly right) and, inside one class, by the sign of a
//! cross product — which is again an orientation of three input points.

use super::Point;
use robust::Coord;

/// The side on which a third point lies relative to a directed line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Orientation {
    /// Strictly to the left (a counter-clockwise turn).
    CounterClockwise,
    /// Strictly to the right (a clockwise turn).
    Clockwise,
    /// Exactly on the line.
    Collinear,
}

impl Orientation {
    /// True for [`Orientation::CounterClockwise`].
    pub fn is_ccw(self) -> bool {
        self == Orientation::CounterClockwise
    }

    /// True for [`Orientation::Clockwise`].
    pub fn is_cw(self) -> bool {
        self == Orientation::Clockwise
    }

    /// The sign as an integer: +1 counter-clockwise, −1 clockwise, 0 collinear.
    pub fn signum(self) -> i32 {
        match self {
            Orientation::CounterClockwise => 1,
            Orientation::Clockwise => -1,
            Orientation::Collinear => 0,
        }
    }

    fn from_det(det: f64) -> Self {
        if det > 0.0 {
            Orientation::CounterClockwise
        } else if det < 0.0 {
            Orientation::Clockwise
        } else {
            Orientation::Collinear
        }
    }
}

#[inline]
fn coord(p: Point) -> Coord<f64> {
    Coord { x: p.x, y: p.y }
}

/// Exact orientation of `c` relative to the directed line `a → b`.
///
/// # Examples
///
/// ```
/// use immerse_base::geom::{orient, Orientation, Point};
/// let o = orient(Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(0.0, 1.0));
/// assert_eq!(o, Orientation::CounterClockwise);
/// ```
#[inline]
pub fn orient(a: Point, b: Point, c: Point) -> Orientation {
    Orientation::from_det(robust::orient2d(coord(a), coord(b), coord(c)))
}

/// Exact in-circle test: true when `d` lies strictly inside the circle
/// through `a`, `b`, `c`, which must be counter-clockwise.
#[inline]
pub fn in_circle(a: Point, b: Point, c: Point, d: Point) -> bool {
    robust::incircle(coord(a), coord(b), coord(c), coord(d)) > 0.0
}

/// Half-plane class of the direction `x − v` relative to the reference
/// direction `r − v`: 0 on the reference ray, 1 strictly left, 2 on the
/// opposite ray, 3 strictly right. `None` when `x == v` (no direction).
///
/// The class orders angles: a smaller class means a smaller
/// counter-clockwise angle φ ∈ [0, 2π) from the reference direction.
#[inline]
pub(crate) fn half_plane_class(v: Point, r: Point, x: Point) -> Option<u8> {
    if x == v {
        return None;
    }
    match orient(v, r, x) {
        Orientation::CounterClockwise => Some(1),
        Orientation::Clockwise => Some(3),
        Orientation::Collinear => {
            // x − v is parallel to r − v; the sign of their dot product is
            // read off exactly from coordinate comparisons along an axis on
            // which r − v is not zero.
            let same = if r.x != v.x {
                (r.x > v.x) == (x.x > v.x)
            } else {
                (r.y > v.y) == (x.y > v.y)
            };
            Some(if same { 0 } else { 2 })
        }
    }
}

/// Exact fan-angle order: true when φ_v(u) < φ_v(w), where φ_v(x) is the
/// counter-clockwise angle in [0, 2π) from the direction `r − v` to `x − v`.
///
/// In the immersion test `r` is the next polygon vertex after `v`. Returns
/// false when `u` or `w` coincides with `v` (no angle is defined) or when
/// the two angles are equal.
///
/// # Examples
///
/// ```
/// use immerse_base::geom::{is_fan_order_less, Point};
/// let v = Point::new(0.0, 0.0);
/// let r = Point::new(1.0, 0.0);
/// let up = Point::new(0.0, 1.0);
/// let down = Point::new(0.0, -1.0);
/// assert!(is_fan_order_less(v, r, up, down)); // 90° < 270°
/// assert!(!is_fan_order_less(v, r, down, up));
/// ```
#[inline]
pub fn is_fan_order_less(v: Point, r: Point, u: Point, w: Point) -> bool {
    let (Some(cu), Some(cw)) = (half_plane_class(v, r, u), half_plane_class(v, r, w)) else {
        return false;
    };
    if cu != cw {
        return cu < cw;
    }
    match cu {
        // Same open half-plane: u before w iff w is left of v → u.
        1 | 3 => orient(v, u, w).is_ccw(),
        // Same ray: equal angles.
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    #[test]
    fn orient_is_exact_near_degeneracy() {
        // Points nearly collinear: a float determinant gets the sign wrong
        // for some of these; the exact predicate is consistent under the
        // cyclic permutation of its arguments.
        let a = p(0.5, 0.5);
        let b = p(12.0, 12.0);
        let mut x: f64 = 0.5;
        for _ in 0..64 {
            x = f64::from_bits(x.to_bits() + 1);
            let c = p(x, 0.5 + 1e-17);
            assert_eq!(orient(a, b, c), orient(b, c, a));
            assert_eq!(orient(a, b, c), orient(c, a, b));
            assert_eq!(orient(a, b, c).signum(), -orient(b, a, c).signum());
        }
        assert_eq!(
            orient(p(0.0, 0.0), p(1.0, 1.0), p(3.0, 3.0)),
            Orientation::Collinear
        );
    }

    #[test]
    fn fan_order_matches_atan2_on_a_grid() {
        let v = p(0.0, 0.0);
        let r = p(2.0, 1.0);
        let angle = |x: Point| {
            let base = (r - v).to_angle();
            let a = (x - v).to_angle() - base;
            a.rem_euclid(std::f64::consts::TAU)
        };
        let pts: Vec<Point> = (-3..=3)
            .flat_map(|i| (-3..=3).map(move |j| p(i as f64, j as f64)))
            .filter(|&x| x != v)
            .collect();
        for &u in &pts {
            for &w in &pts {
                let (au, aw) = (angle(u), angle(w));
                // Skip pairs whose float angles are too close to call; the
                // exact predicate is the reference, atan2 only a cross-check.
                if (au - aw).abs() < 1e-12 {
                    assert!(!is_fan_order_less(v, r, u, w) || orient(v, u, w).is_ccw());
                    continue;
                }
                assert_eq!(is_fan_order_less(v, r, u, w), au < aw, "u={u} w={w}");
            }
        }
    }

    #[test]
    fn in_circle_unit_circle() {
        let (a, b, c) = (p(1.0, 0.0), p(0.0, 1.0), p(-1.0, 0.0));
        assert!(in_circle(a, b, c, p(0.0, 0.0)));
        assert!(!in_circle(a, b, c, p(0.0, -1.0))); // on the circle
        assert!(!in_circle(a, b, c, p(2.0, 2.0)));
    }
}
