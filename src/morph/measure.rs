//! The measures of motion a viewer sees (docs/design.md §7b, §7c) on a
//! frame sequence: detour, unwind and the view measures (continuity,
//! spikes, area, angles, distortion). The planner holds a route to them
//! ([`crate::morph::Tween`]), and a morph's JSON carries its detour and
//! unwind; [`crate::frames`] re-exports them beside the metrics of §8.

use crate::geom::Point;
use crate::geom::polygon::total_absolute_turning;
use crate::morph::Frame;

/// The detour of a frame sequence: the mean over vertices of the path
/// length a vertex travels through the frames, divided by the mean
/// straight-line distance between the first and last frames under the
/// best cyclic shift of the last frame's vertices (the shift that makes
/// that mean smallest). 1.0 is straight lines; 1.0 also when nothing
/// moves. O(n²) for the shift search at worst (shifts that cannot win are
/// abandoned early).
pub fn detour(frames: &[Frame]) -> f64 {
    let (Some(first), Some(last)) = (frames.first(), frames.last()) else {
        return 1.0;
    };
    let n = first.points.len();
    if n == 0 || frames.iter().any(|f| f.points.len() != n) {
        return f64::NAN;
    }
    let travelled = travelled(frames);
    // The least sum over shifts. Shift 0 (the frames' own matching, most
    // often the least) first; then every shift on all cores, each summed
    // in vertex order without a remainder per term, and abandoned once
    // its partial sum passes the least found by its worker (its terms are
    // never negative), so the result is the full minimum.
    let (f, l) = (&first.points, &last.points);
    let shift_sum = |k: usize, bound: f64| -> f64 {
        let mut sum = 0.0;
        let pieces = [(&f[..n - k], &l[k..]), (&f[n - k..], &l[..k])];
        for (fs, ls) in pieces {
            for (fc, lc) in fs.chunks(64).zip(ls.chunks(64)) {
                for (p, q) in fc.iter().zip(lc) {
                    sum += (*q - *p).length();
                }
                if sum >= bound {
                    return sum;
                }
            }
        }
        sum
    };
    let at_zero = shift_sum(0, f64::INFINITY);
    use rayon::prelude::*;
    let straight = (1..n)
        .into_par_iter()
        .fold(|| at_zero, |best, k| best.min(shift_sum(k, best)))
        .reduce(|| at_zero, f64::min);
    if straight <= 0.0 {
        return if travelled <= 0.0 { 1.0 } else { f64::INFINITY };
    }
    travelled / straight
}

/// The summed length of every vertex's path through the frames (frames
/// of one vertex count).
fn travelled(frames: &[Frame]) -> f64 {
    frames
        .windows(2)
        .map(|w| {
            w[0].points
                .iter()
                .zip(&w[1].points)
                .map(|(a, b)| (*a - *b).length())
                .sum::<f64>()
        })
        .sum()
}

/// The unwind of a frame sequence: the smallest total absolute turning of
/// any frame divided by the smaller of the two end frames' totals. Below
/// 1 means overlaps were undone and redone.
pub fn unwind(frames: &[Frame]) -> f64 {
    let (Some(first), Some(last)) = (frames.first(), frames.last()) else {
        return 1.0;
    };
    let ends = total_absolute_turning(&first.points).min(total_absolute_turning(&last.points));
    let least = frames
        .iter()
        .map(|f| total_absolute_turning(&f.points))
        .fold(f64::INFINITY, f64::min);
    if ends <= 0.0 { 1.0 } else { least / ends }
}

/// The measures of motion a viewer sees (docs/design.md §7c), on a frame
/// sequence with a constant vertex count. Each is taken over the frames as
/// given, so it depends on how many there are: the continuity measure is
/// compared between counts (a continuous motion's largest step shrinks in
/// proportion to the frame count), the others are meant at 320 frames.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ViewMeasures {
    /// Largest move of a single vertex between consecutive frames, as a
    /// fraction of the larger end's bounding-box diagonal.
    pub max_step: f64,
    /// Longest curve edge over the frames ÷ the longest curve edge of the
    /// two end frames (spikes: above 1 means an edge grew past both ends').
    pub edge_ratio: f64,
    /// Smallest total area over the frames ÷ the smaller end's (collapse).
    pub area_low: f64,
    /// Largest total area over the frames ÷ the larger end's (ballooning).
    pub area_high: f64,
    /// Smallest triangle angle over the frames ÷ the smallest of the two
    /// end frames (slivers: below 1 means thinner than the ends).
    pub angle_ratio: f64,
    /// As-rigid-as-possible distortion: per triangle of each frame, the
    /// ratio of the larger to the smaller singular value of the affine map
    /// from the same three vertices at the nearer end frame; their
    /// geometric mean over the triangles, then the largest over frames (1 =
    /// every triangle moved rigidly or scaled evenly).
    pub distortion: f64,
}

/// The [`ViewMeasures`] of `frames`; `None` when there are fewer than two
/// frames or the vertex count changes.
pub fn view_measures(frames: &[Frame]) -> Option<ViewMeasures> {
    let (first, last) = (frames.first()?, frames.last()?);
    let n = first.points.len();
    if frames.len() < 2 || n < 3 || frames.iter().any(|f| f.points.len() != n) {
        return None;
    }
    let diagonal = |p: &[Point]| {
        let lo = p
            .iter()
            .copied()
            .fold(Point::splat(f64::INFINITY), Point::min);
        let hi = p
            .iter()
            .copied()
            .fold(Point::splat(f64::NEG_INFINITY), Point::max);
        (hi - lo).length()
    };
    let diag = diagonal(&first.points).max(diagonal(&last.points));
    let max_step = frames
        .windows(2)
        .flat_map(|w| w[0].points.iter().zip(&w[1].points))
        .map(|(p, q)| (*p - *q).length())
        .fold(0.0, f64::max)
        / diag;
    let longest_edge = |p: &[Point]| {
        (0..n)
            .map(|i| (p[(i + 1) % n] - p[i]).length())
            .fold(0.0, f64::max)
    };
    let end_edge = longest_edge(&first.points).max(longest_edge(&last.points));
    let edge_ratio = frames
        .iter()
        .map(|f| longest_edge(&f.points))
        .fold(0.0, f64::max)
        / end_edge;
    let areas: Vec<f64> = frames.iter().map(Frame::total_area).collect();
    let (a0, a1) = (areas[0], areas[areas.len() - 1]);
    let area_low = areas.iter().copied().fold(f64::INFINITY, f64::min) / a0.min(a1);
    let area_high = areas.iter().copied().fold(f64::NEG_INFINITY, f64::max) / a0.max(a1);
    let end_angle = first.min_angle().min(last.min_angle());
    let angle_ratio = frames
        .iter()
        .map(Frame::min_angle)
        .fold(f64::INFINITY, f64::min)
        / end_angle;
    let (t0, t1) = (first.t, last.t);
    let distortion = frames
        .iter()
        .map(|f| {
            let near = if (f.t - t0).abs() <= (t1 - f.t).abs() {
                first
            } else {
                last
            };
            let ratios: Vec<f64> = f
                .triangles
                .iter()
                .filter_map(|t| {
                    let [a, b, c] = t.map(|v| near.points[v as usize]);
                    let [x, y, z] = t.map(|v| f.points[v as usize]);
                    stretch_ratio([b - a, c - a], [y - x, z - x])
                })
                .collect();
            if ratios.is_empty() {
                1.0
            } else {
                (ratios.iter().map(|r| r.ln()).sum::<f64>() / ratios.len() as f64).exp()
            }
        })
        .fold(1.0, f64::max);
    Some(ViewMeasures {
        max_step,
        edge_ratio,
        area_low,
        area_high,
        angle_ratio,
        distortion,
    })
}

/// The ratio of the larger to the smaller singular value of the linear map
/// taking the edge vectors `from` to `to`; `None` where `from` is
/// degenerate or the map is singular.
fn stretch_ratio(from: [Point; 2], to: [Point; 2]) -> Option<f64> {
    let det = from[0].perp_dot(from[1]);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    // M = T F⁻¹ with F = [from0 from1], T = [to0 to1] (columns).
    let inv = [
        [from[1].y / det, -from[1].x / det],
        [-from[0].y / det, from[0].x / det],
    ];
    let m = [
        [
            to[0].x * inv[0][0] + to[1].x * inv[1][0],
            to[0].x * inv[0][1] + to[1].x * inv[1][1],
        ],
        [
            to[0].y * inv[0][0] + to[1].y * inv[1][0],
            to[0].y * inv[0][1] + to[1].y * inv[1][1],
        ],
    ];
    // Singular values of a 2×2 matrix from its Frobenius norm and
    // determinant: σ₁² + σ₂² = ‖M‖², σ₁σ₂ = |det M|.
    let fro = m[0][0].powi(2) + m[0][1].powi(2) + m[1][0].powi(2) + m[1][1].powi(2);
    let d = (m[0][0] * m[1][1] - m[0][1] * m[1][0]).abs();
    let root = (fro * fro - 4.0 * d * d).max(0.0).sqrt();
    let (s1, s2) = (
        ((fro + root) / 2.0).sqrt(),
        ((fro - root) / 2.0).max(0.0).sqrt(),
    );
    (s2 > 0.0 && s1.is_finite()).then(|| s1 / s2)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The detour's shift search abandons shifts early; it must find the
    /// same least sum as summing every shift in full: random point sets
    /// (some with the least shift far from 0) against the definition.
    #[test]
    fn detour_equals_its_definition() {
        let mut state = 0x9e3779b97f4a7c15_u64;
        let mut next = || testkit::rng::unit_from_bits(testkit::rng::xorshift64(&mut state));
        for case in 0..200 {
            let n = 1 + (next() * 40.0) as usize;
            let a: Vec<Point> = (0..n).map(|_| Point::new(next(), next())).collect();
            let turn = (next() * n as f64) as usize;
            let b: Vec<Point> = (0..n)
                .map(|i| a[(i + turn) % n] + Point::new(next(), next()) * 0.1 + Point::X)
                .collect();
            let mid: Vec<Point> = a.iter().zip(&b).map(|(p, q)| p.lerp(*q, 0.5)).collect();
            let frames: Vec<Frame> = [a.clone(), mid, b.clone()]
                .into_iter()
                .enumerate()
                .map(|(k, points)| Frame {
                    t: k as f64 / 2.0,
                    points,
                    triangles: Vec::new(),
                })
                .collect();
            let least = (0..n)
                .map(|k| {
                    (0..n)
                        .map(|i| (b[(i + k) % n] - a[i]).length())
                        .sum::<f64>()
                })
                .fold(f64::INFINITY, f64::min);
            assert_eq!(detour(&frames), travelled(&frames) / least, "case {case}");
        }
    }
}
