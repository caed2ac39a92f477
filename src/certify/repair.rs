//! Flipping a segment's triangulation until the segment is certified.
//!
//! A triangle whose corners are nearly collinear at both ends of a segment
//! (a vertex on a straight side, a strip thinner than its rounding) has an
//! area that the rounding of the keys' coordinates decides: the straight
//! motion between two such keys can turn it over however close the keys
//! are. Another triangulation of the same shapes may not need that
//! triangle at all. [`flip_to_certify`] looks for one by flipping the
//! diagonals of the triangle that fails, one at a time; a triangulation
//! it returns is certified on the whole segment, so it is valid at both
//! keys, which become flip keys (docs/design.md §13).

use super::{Defect, Player, certify_segment};
use crate::flip::FlipTriangulation;
use crate::geom::Point;
use crate::immersion::dp::is_ccw;

/// Most flips tried for one segment: a bound on the work (each costs one
/// certification of the segment, O(n)).
const MAX_REPAIR_FLIPS: usize = 16;

/// A triangulation under which the straight-line motion from `start` to
/// `end` is certified for every s against `player`, reached from
/// `triangles` (certified at s = 0 or not) by at most [`MAX_REPAIR_FLIPS`]
/// flips, each of a diagonal of the triangle that fails first; `None` when
/// none is found. Of a failing triangle's diagonals, the flip whose two
/// new triangles are counter-clockwise at both ends and least thin there
/// is taken; a diagonal once flipped away is not brought back.
pub(crate) fn flip_to_certify(
    start: &[Point],
    end: &[Point],
    triangles: &[[u32; 3]],
    player: Player,
) -> Option<Vec<[u32; 3]>> {
    let n = start.len();
    if n < 4 || end.len() != n {
        return None;
    }
    let mut t = FlipTriangulation::new(n, triangles);
    let mut removed: Vec<(u32, u32)> = Vec::new();
    for _ in 0..=MAX_REPAIR_FLIPS {
        let report = certify_segment(start, end, t.triangles(), player).ok()?;
        let Some(failure) = report.failure else {
            return Some(t.triangles().to_vec());
        };
        let Defect::Triangle { corners, .. } = failure.defect else {
            return None;
        };
        let [a, b, c] = corners;
        let best = [(a, b), (b, c), (a, c)]
            .into_iter()
            .filter(|&(x, y)| !removed.contains(&(x.min(y), x.max(y))))
            .filter_map(|(x, y)| {
                let ([p, q, r, s], _) = t.quad(x, y)?;
                // Flipped: (p, q, s) and (q, r, s), corners increasing.
                let new = [[p, q, s], [q, r, s]].map(crate::flip::canonical);
                let ccw = |pts: &[Point]| {
                    new.iter()
                        .all(|&[i, j, k]| is_ccw(pts, i as usize, j as usize, k as usize))
                };
                (ccw(start) && ccw(end)).then(|| {
                    let fat = new
                        .iter()
                        .flat_map(|&tri| [fatness(start, tri), fatness(end, tri)])
                        .fold(f64::INFINITY, f64::min);
                    (fat, x, y)
                })
            })
            .max_by(|l, r| l.0.total_cmp(&r.0));
        let (_, x, y) = best?;
        let flip = t.flip(x, y)?;
        removed.push(flip.from);
    }
    None
}

/// How far from collinear the triangle `tri` is in `points`: its doubled
/// area over its longest side squared (a scale-free measure, 0 for a
/// degenerate triangle), in floating point (a preference only; validity
/// is decided exactly).
fn fatness(points: &[Point], [i, j, k]: [u32; 3]) -> f64 {
    let (a, b, c) = (points[i as usize], points[j as usize], points[k as usize]);
    let area = (b - a).perp_dot(c - a).abs();
    let longest = (b - a)
        .length_squared()
        .max((c - b).length_squared())
        .max((a - c).length_squared());
    if longest > 0.0 { area / longest } else { 0.0 }
}
