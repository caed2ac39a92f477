//! Giving a segment a triangulation of its own until it is certified.
//!
//! A triangle whose corners are nearly collinear at both ends of a segment
//! (a vertex on a straight side, a strip thinner than its rounding) has an
//! area that the rounding of the keys' coordinates decides: the straight
//! motion between two such keys can turn it over however close the keys
//! are. Another triangulation of the same shapes may not need that
//! triangle at all. [`flip_to_certify`] looks for one, first by flipping
//! the diagonals of the triangle that fails, one at a time, then by
//! [`certified_triangulation`], which decides exactly whether any
//! triangulation certifies the segment and finds one. A triangulation
//! either returns is certified on the whole segment, so it is valid at
//! both keys, which become flip keys (docs/design.md §13).

use super::{Defect, Holds, Player, Span, certify_segment};
use crate::flip::FlipTriangulation;
use crate::geom::Point;
use crate::immersion::dp::{self, is_ccw};
use crate::immersion::{CheckedTriangles, precheck};

/// Most flips tried for one segment: a bound on the work (each costs one
/// certification of the segment, O(n)).
const MAX_REPAIR_FLIPS: usize = 16;

/// A triangulation under which the straight-line motion from `start` to
/// `end` is certified for every s against `player`: reached from
/// `triangles` (certified at s = 0 or not) by at most [`MAX_REPAIR_FLIPS`]
/// flips, each of a diagonal of the triangle that fails first, so that
/// the segment keeps most of its triangles; else any certified
/// triangulation ([`certified_triangulation`]). `None` when there is none
/// (or the DP is not tried, above its size bound). Of a failing
/// triangle's diagonals, the flip whose two new triangles are
/// counter-clockwise at both ends and least thin there is taken; a
/// diagonal once flipped away is not brought back.
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
    let mut flips = || -> Option<Vec<[u32; 3]>> {
        for _ in 0..=MAX_REPAIR_FLIPS {
            let report = certify_segment(start, end, t.triangles(), player).ok()?;
            let Some(failure) = report.failure else {
                return Some(t.triangles().to_vec());
            };
            let Defect::Triangle { corners, .. } = failure.defect else {
                return None;
            };
            let (x, y) = best_flip(&t, start, end, corners, &removed)?;
            let flip = t.flip(x, y)?;
            removed.push(flip.from);
        }
        None
    };
    flips().or_else(|| certified_triangulation(start, end, player))
}

/// Of the diagonals of the triangle `corners` not in `removed`, the one
/// whose flip gives two triangles counter-clockwise at both ends and
/// least thin there.
fn best_flip(
    t: &FlipTriangulation,
    start: &[Point],
    end: &[Point],
    [a, b, c]: [u32; 3],
    removed: &[(u32, u32)],
) -> Option<(u32, u32)> {
    [(a, b), (b, c), (a, c)]
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
        .max_by(|l, r| l.0.total_cmp(&r.0))
        .map(|(_, x, y)| (x, y))
}

/// Most points for which [`certified_triangulation`] is tried: its DP
/// costs O(n³/64) word operations and a certificate per candidate
/// triangle.
const MAX_SEGMENT_DP_POINTS: usize = 2_000;

/// A triangulation under which the straight-line motion from `start` to
/// `end` is certified for every s against `player`, if any triangulation
/// of the n-gon by diagonals is: the immersion DP of docs/design.md §3 on
/// both ends at once, with a triangle counted only where its doubled area
/// stays above the player's margin on all of [0, 1]. This decides the
/// question exactly: the fans' certificate does not depend on the
/// triangulation (a fan's first and last edges are the curve's), and a
/// triangulation valid at s = 0 whose triangles stay counter-clockwise
/// and whose fans never reach a full turn is valid for every s
/// (docs/design.md §13). `None` where a fan fails, where no triangulation
/// keeps every triangle counter-clockwise, or above 2,000 points (the DP's work grows as n³).
pub fn certified_triangulation(
    start: &[Point],
    end: &[Point],
    player: Player,
) -> Option<Vec<[u32; 3]>> {
    let n = start.len();
    if n < 3 || end.len() != n || n > MAX_SEGMENT_DP_POINTS {
        return None;
    }
    if precheck(start).is_err() || precheck(end).is_err() {
        return None;
    }
    let span = Span::new(start, end, 0.0, 1.0, player);
    let mut exact = 0;
    if (0..n).any(|v| span.fan_fails(v, &mut exact).is_some()) {
        return None;
    }
    let keep =
        |i: usize, k: usize, j: usize| !matches!(span.triangle_holds([i, k, j]), Holds::No(..));
    let curves = [start, end];
    let planes = curves
        .iter()
        .map(|c| crate::immersion::valid::HalfPlanes::new(c))
        .collect();
    let table = dp::decide_common_with(&curves, planes, &keep, &mut |_| {});
    let mut triangles = dp::witness_common(&curves, &table, &keep)?;
    triangles.sort_unstable();
    // The DP's answer is certified by construction; checked once more by
    // the certificate itself.
    let checked = CheckedTriangles::new(n, &triangles);
    super::segment_holds(start, end, &checked, player).then_some(triangles)
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
