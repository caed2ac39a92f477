//! Equal vertex counts: inserting vertices on edges (original vertices
//! stay exactly where they are) or resampling by arc length.

use crate::geom::Point;

/// Inserts `extra` vertices on the curve's edges, each time splitting the
/// currently longest edge (in its current subdivision) evenly, and returns
/// the new polygon with, for each of its vertices, the index of the
/// original vertex it is (`Some`) or `None` for an inserted one.
///
/// Original vertices keep their exact coordinates; inserted ones lie on
/// the original edges.
pub fn insert_vertices(points: &[Point], extra: usize) -> (Vec<Point>, Vec<Option<usize>>) {
    let n = points.len();
    let lengths: Vec<f64> = (0..n)
        .map(|i| (points[(i + 1) % n] - points[i]).length())
        .collect();
    // Number of pieces each original edge is cut into.
    let pieces = apportion(&lengths, extra);
    let mut out = Vec::with_capacity(n + extra);
    let mut origin = Vec::with_capacity(n + extra);
    for i in 0..n {
        let (a, b) = (points[i], points[(i + 1) % n]);
        out.push(a);
        origin.push(Some(i));
        for k in 1..pieces[i] {
            out.push(a.lerp(b, k as f64 / pieces[i] as f64));
            origin.push(None);
        }
    }
    (out, origin)
}

/// Brings two curves to the same vertex count by inserting vertices on
/// the edges of the one with fewer ([`insert_vertices`]).
pub fn equalize(a: &[Point], b: &[Point]) -> (Vec<Point>, Vec<Point>) {
    match a.len().cmp(&b.len()) {
        std::cmp::Ordering::Less => (insert_vertices(a, b.len() - a.len()).0, b.to_vec()),
        std::cmp::Ordering::Greater => (a.to_vec(), insert_vertices(b, a.len() - b.len()).0),
        std::cmp::Ordering::Equal => (a.to_vec(), b.to_vec()),
    }
}

/// `m` points evenly spaced by arc length along the closed curve, starting
/// at its first vertex. Original vertices are not kept.
pub fn resample_arc_length(points: &[Point], m: usize) -> Vec<Point> {
    let n = points.len();
    let lengths: Vec<f64> = (0..n)
        .map(|i| (points[(i + 1) % n] - points[i]).length())
        .collect();
    let total: f64 = lengths.iter().sum();
    let mut out = Vec::with_capacity(m);
    let (mut edge, mut start) = (0usize, 0.0f64);
    for k in 0..m {
        let s = total * k as f64 / m as f64;
        while edge + 1 < n && start + lengths[edge] < s {
            start += lengths[edge];
            edge += 1;
        }
        let f = if lengths[edge] > 0.0 {
            ((s - start) / lengths[edge]).clamp(0.0, 1.0)
        } else {
            0.0
        };
        out.push(points[edge].lerp(points[(edge + 1) % n], f));
    }
    out
}

/// Splits `extra` whole units among items of weights `w`, on top of one
/// each ([`apportion_among`] over every item). Edges cut into pieces by
/// length ([`insert_vertices`]) and a sequence's frames shared among its
/// segments by travel are both this.
pub(crate) fn apportion(w: &[f64], extra: usize) -> Vec<usize> {
    let mut units = vec![1usize; w.len()];
    let all: Vec<usize> = (0..w.len()).collect();
    apportion_among(w, &mut units, &all, extra);
    units
}

/// Adds `extra` whole units to `units` at the items `among` (each with at
/// least one unit already), always giving the next unit to the item with
/// the largest weight per unit `w[i] / units[i]` (D'Hondt; ties to the
/// lower index): the largest weight per unit is as small as whole units
/// allow.
pub(crate) fn apportion_among(w: &[f64], units: &mut [usize], among: &[usize], extra: usize) {
    use std::cmp::Reverse;
    let mut heap: std::collections::BinaryHeap<(Weight, Reverse<usize>)> = among
        .iter()
        .map(|&i| (Weight(w[i] / units[i] as f64), Reverse(i)))
        .collect();
    for _ in 0..extra {
        let Some((_, Reverse(i))) = heap.pop() else {
            break;
        };
        units[i] += 1;
        heap.push((Weight(w[i] / units[i] as f64), Reverse(i)));
    }
}

/// A weight ordered totally (`f64::total_cmp`), for the heap.
#[derive(Clone, Copy)]
struct Weight(f64);
impl PartialEq for Weight {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other).is_eq()
    }
}
impl Eq for Weight {}
impl PartialOrd for Weight {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Weight {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Orientation, orient};
    use crate::testing::{points, unit_square};

    #[test]
    fn inserted_vertices_lie_on_edges_and_originals_stay() {
        let sq = points([(0.0, 0.0), (4.0, 0.0), (4.0, 1.0), (0.0, 1.0)]);
        let (out, origin) = insert_vertices(&sq, 5);
        assert_eq!(out.len(), 9);
        for (i, o) in origin.iter().enumerate() {
            if let Some(j) = o {
                assert_eq!(out[i], sq[*j]);
            }
        }
        // The long edges (length 4) take the new vertices first.
        assert_eq!(origin.iter().filter(|o| o.is_none()).count(), 5);
        for (i, p) in out.iter().enumerate() {
            if origin[i].is_none() {
                let prev = (0..i).rev().find(|&j| origin[j].is_some()).unwrap();
                let e = origin[prev].unwrap();
                assert_eq!(orient(sq[e], sq[(e + 1) % 4], *p), Orientation::Collinear);
            }
        }
    }

    #[test]
    fn arc_length_resampling_is_even() {
        let sq = unit_square();
        let r = resample_arc_length(&sq, 8);
        assert_eq!(r.len(), 8);
        for i in 0..8 {
            let d = (r[(i + 1) % 8] - r[i]).length();
            assert!((d - 0.5).abs() < 1e-12, "{d}");
        }
    }
}
