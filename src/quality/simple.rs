//! Simple polygons: their constrained Delaunay triangulation, by spade in
//! O(n log n), instead of the O(n³/64) DP followed by flips. For a simple
//! counter-clockwise polygon the immersed Delaunay triangulation *is* the
//! constrained Delaunay triangulation of its inside (docs/design.md §3),
//! so the result is the same; the exact checker confirms it before it is
//! used, and the caller falls back to the DP otherwise.

use crate::geom::Point;
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

/// The inside triangles of the constrained Delaunay triangulation of the
/// simple polygon `points` (corners sorted, so in cyclic order), or `None`
/// when spade refuses a point or the result is not an immersion
/// triangulation of the polygon.
pub(crate) fn cdt(points: &[Point]) -> Option<Vec<[u32; 3]>> {
    let n = points.len();
    let mut cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::new();
    let mut handles = Vec::with_capacity(n);
    for p in points {
        handles.push(cdt.insert(Point2::new(p.x, p.y)).ok()?);
    }
    if cdt.num_vertices() != n {
        return None; // two points merged
    }
    let mut index = vec![u32::MAX; n];
    for (i, h) in handles.iter().enumerate() {
        index[h.index()] = i as u32;
    }
    for i in 0..n {
        if !cdt.can_add_constraint(handles[i], handles[(i + 1) % n]) {
            return None;
        }
        cdt.add_constraint(handles[i], handles[(i + 1) % n]);
    }
    // The inside: faces left of each polygon edge (i → i + 1), flooded
    // without crossing a constraint.
    let mut inside = vec![false; cdt.num_inner_faces() + 1];
    let mut queue = Vec::new();
    for edge in cdt.directed_edges() {
        let (from, to) = (
            index[edge.from().fix().index()],
            index[edge.to().fix().index()],
        );
        if (from + 1) % n as u32 == to {
            if let Some(face) = edge.face().as_inner() {
                if !inside[face.fix().index()] {
                    inside[face.fix().index()] = true;
                    queue.push(face.fix());
                }
            }
        }
    }
    while let Some(f) = queue.pop() {
        for e in cdt.face(f).adjacent_edges() {
            if cdt.is_constraint_edge(e.as_undirected().fix()) {
                continue;
            }
            if let Some(g) = e.rev().face().as_inner() {
                if !inside[g.fix().index()] {
                    inside[g.fix().index()] = true;
                    queue.push(g.fix());
                }
            }
        }
    }
    let mut tris: Vec<[u32; 3]> = cdt
        .inner_faces()
        .filter(|f| inside[f.fix().index()])
        .map(|f| {
            let mut t = f.vertices().map(|v| index[v.fix().index()]);
            t.sort_unstable();
            t
        })
        .collect();
    tris.sort_unstable();
    crate::immersion::check(points, &tris).ok()?;
    Some(tris)
}
