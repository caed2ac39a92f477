//! The spine of the dual tree and the pivot vertex (Mukherjee & Gopi §6.1).
//!
//! Leaves have degree 1, path nodes 2, internal nodes 3. Repeatedly remove
//! the leaf closest (in hops) to an internal node together with its path
//! up to that node, until two leaves remain; the path between them is the
//! spine. One spine end is the pivot triangle; its corner not shared with
//! its neighbour is the pivot vertex.

use super::DualTree;
use crate::geom::Point;

/// The spine of a dual tree.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Spine {
    /// Triangles along the spine, from the pivot triangle to the other end.
    pub triangles: Vec<usize>,
    /// The pivot triangle (the first spine triangle).
    pub pivot_triangle: usize,
    /// The pivot vertex: the pivot triangle's corner not shared with its
    /// neighbour on the spine.
    pub pivot_vertex: u32,
    /// The vertex of the other end triangle not shared with its neighbour.
    pub other_end_vertex: u32,
}

pub(super) fn spine(tree: &DualTree, points: &[Point]) -> Spine {
    let m = tree.triangles().len();
    let mut alive = vec![true; m];
    let mut degree: Vec<usize> = (0..m).map(|t| tree.degree(t)).collect();
    loop {
        // For every leaf, the walk to the first internal node.
        let mut best: Option<(usize, Vec<usize>)> = None;
        for leaf in (0..m).filter(|&t| alive[t] && degree[t] == 1) {
            let mut path = vec![leaf];
            let mut prev = usize::MAX;
            let mut cur = leaf;
            let reached = loop {
                let next = tree
                    .neighbours(cur)
                    .into_iter()
                    .map(|(u, _)| u)
                    .find(|&u| alive[u] && u != prev);
                let Some(next) = next else { break false };
                if degree[next] >= 3 {
                    break true;
                }
                path.push(next);
                prev = cur;
                cur = next;
            };
            if reached && best.as_ref().is_none_or(|(_, p)| path.len() < p.len()) {
                best = Some((leaf, path));
            }
        }
        let Some((_, path)) = best else { break };
        let last = *path.last().unwrap_or(&path[0]);
        for &t in &path {
            alive[t] = false;
        }
        for (u, _) in tree.neighbours(last) {
            if alive[u] {
                degree[u] -= 1;
            }
        }
    }
    // What is left is a path: walk it from one end.
    let ends: Vec<usize> = (0..m)
        .filter(|&t| alive[t] && tree.neighbours(t).iter().filter(|(u, _)| alive[*u]).count() <= 1)
        .collect();
    let start = ends.first().copied().unwrap_or(0);
    let mut path = vec![start];
    let mut prev = usize::MAX;
    let mut cur = start;
    while let Some(next) = tree
        .neighbours(cur)
        .into_iter()
        .map(|(u, _)| u)
        .find(|&u| alive[u] && u != prev)
    {
        path.push(next);
        prev = cur;
        cur = next;
    }
    let area = |t: usize| {
        let [a, b, c] = tree.triangles()[t].map(|i| points[i as usize]);
        (b - a).perp_dot(c - a).abs()
    };
    if path.len() > 1 && area(path[path.len() - 1]) > area(path[0]) {
        path.reverse();
    }
    let free_vertex = |end: usize, neighbour: Option<usize>| -> u32 {
        let tri = tree.triangles()[end];
        match neighbour {
            None => tri[0],
            Some(nb) => {
                let other = tree.triangles()[nb];
                tri.into_iter()
                    .find(|v| !other.contains(v))
                    .unwrap_or(tri[0])
            }
        }
    };
    let pivot_triangle = path[0];
    let pivot_vertex = free_vertex(path[0], path.get(1).copied());
    let end = path[path.len() - 1];
    let other_end_vertex = free_vertex(end, path.len().checked_sub(2).map(|i| path[i]));
    Spine {
        triangles: path,
        pivot_triangle,
        pivot_vertex,
        other_end_vertex,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::regular_polygon;

    #[test]
    fn spine_of_a_fan_is_the_whole_path() {
        let tris: Vec<[u32; 3]> = (1..5).map(|i| [0, i, i + 1]).collect();
        let pts: Vec<Point> = (0..6)
            .map(|i| {
                let a = i as f64;
                Point::new(a.cos(), a.sin())
            })
            .collect();
        let tree = DualTree::new(6, &tris).unwrap();
        let s = tree.spine(&pts);
        assert_eq!(s.triangles.len(), 4);
        // The pivot's free corner is not shared with the next triangle.
        let next = tris[s.triangles[1]];
        assert!(!next.contains(&s.pivot_vertex));
    }

    #[test]
    fn spine_prunes_the_shortest_branch() {
        // An 8-gon: central triangle (0,3,6) with branches of 2, 2 and 1
        // triangles; the one-triangle branch (6,7,0) is pruned.
        let tris = vec![
            [0, 3, 6],
            [0, 1, 3],
            [1, 2, 3],
            [3, 4, 6],
            [4, 5, 6],
            [6, 7, 0],
        ];
        let pts = regular_polygon(8);
        let tree = DualTree::new(8, &tris).unwrap();
        let s = tree.spine(&pts);
        assert_eq!(s.triangles.len(), 5, "{s:?}");
        assert!(!s.triangles.contains(&5));
        assert!([2, 4].contains(&s.pivot_triangle));
        // Pivot vertex of an end triangle: 2 for (1,2,3), 5 for (4,5,6).
        assert!([2, 5].contains(&s.pivot_vertex));
        assert_ne!(s.pivot_vertex, s.other_end_vertex);
    }
}
