//! Holes: a subpath that cuts a region out of another under its element's
//! fill rule (docs/design.md §2a).
//!
//! The subpaths of one element are painted together: a point is painted
//! when the fill rule accepts the sum of their winding numbers. Read as
//! separate shapes, each is painted where the rule accepts its own
//! winding number. A point is *cut* when some subpath alone would paint it
//! but the element does not; the painting of the separate shapes is the
//! element's exactly when no point is cut (every point the element paints
//! has a subpath that paints it alone, under either rule). At a cut point
//! another subpath winds too; of the two, the one of smaller area is the
//! hole of the other.
//!
//! Cut points are looked for at samples: the centroid of every triangle of
//! every subpath's immersion triangulation, and a point on each side of the
//! midpoint of every edge, at a thousandth of the edge's length. Every
//! winding number at a sample is exact; a cut region that holds no sample
//! is not found.

use super::style::FillRule;
use super::winding_number;
use crate::geom::Point;
use crate::geom::polygon::signed_area;
use crate::immersion;

/// The first hole found among the closed subpaths `polys` of one element
/// painted under `rule`: `(hole, outer)` as indices into `polys`. A
/// subpath whose `reversed` flag is set was given the other way round: its
/// winding numbers count negated.
pub(super) fn find(
    polys: &[&[Point]],
    reversed: &[bool],
    rule: FillRule,
) -> Option<(usize, usize)> {
    let boxes: Vec<(Point, Point)> = polys
        .iter()
        .map(|p| {
            p.iter()
                .fold((p[0], p[0]), |(lo, hi), &q| (lo.min(q), hi.max(q)))
        })
        .collect();
    let areas: Vec<f64> = polys.iter().map(|p| signed_area(p).abs()).collect();
    let windings = |q: Point| -> Option<Vec<i64>> {
        polys
            .iter()
            .zip(&boxes)
            .zip(reversed)
            .map(|((p, (lo, hi)), &rev)| {
                if q.x < lo.x || q.x > hi.x || q.y < lo.y || q.y > hi.y {
                    Some(0)
                } else {
                    winding_number(p, q).map(|w| if rev { -w } else { w })
                }
            })
            .collect()
    };
    for (s, poly) in polys.iter().enumerate() {
        for q in samples(poly) {
            let Some(w) = windings(q) else {
                continue;
            };
            let total: i64 = w.iter().sum();
            if rule.paints(total) || !rule.paints(w[s]) {
                continue;
            }
            // Cut: subpath s alone paints q, the element does not. The
            // largest other subpath winding at q cancels it.
            let other = (0..polys.len())
                .filter(|&t| t != s && w[t] != 0)
                .max_by(|&a, &b| areas[a].total_cmp(&areas[b]));
            if let Some(t) = other {
                return Some(if areas[s] <= areas[t] { (s, t) } else { (t, s) });
            }
        }
    }
    None
}

/// Sample points of one subpath: its immersion's triangle centroids (when
/// it has one) and a point each side of every edge's midpoint.
fn samples(poly: &[Point]) -> Vec<Point> {
    let mut out = Vec::new();
    if let Ok(imm) = immersion::triangulate(poly) {
        for &[a, b, c] in &imm.triangles {
            out.push((poly[a as usize] + poly[b as usize] + poly[c as usize]) / 3.0);
        }
    }
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let m = 0.5 * (a + b);
        let d = b - a;
        let n = Point::new(-d.y, d.x) * 1e-3;
        out.push(m + n);
        out.push(m - n);
    }
    out
}
