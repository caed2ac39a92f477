//! The dual tree of an immersion triangulation, its spine, pivot and root.
//!
//! An immersion triangulation has no interior vertices, so its dual graph (one
//! node per triangle, one edge per shared diagonal) is a tree (Mukherjee & Gopi
//! §5, §6.1; docs/design.md §4). This module is index-only: positions enter
//! only in [`root_triangle`], which needs the curve's edge lengths to place the
//! disk image.
//!
//! The spine, pivot and root follow Mukherjee & Gopi, *Tweening Boundary
//! Curves of Non-simple Immersions of a Disk*.
//!
//! petgraph types stay inside this module; [`DualTree`] wraps them.

mod spine;

pub use spine::Spine;

use crate::geom::Point;
use petgraph::graph::{NodeIndex, UnGraph};
use rustc_hash::FxHashMap;
use std::collections::VecDeque;

/// Why a triangle list does not form the dual tree of a polygon
/// triangulation.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum TreeError {
    /// The triangle count is not n − 2.
    #[error("{triangles} triangles for a {n}-gon; a triangulation has n - 2")]
    Count {
        /// Polygon vertices.
        n: usize,
        /// Triangles given.
        triangles: usize,
    },
    /// A diagonal is shared by more than two triangles, or the dual graph
    /// is not connected.
    #[error("the triangles do not form a triangulated disk (dual graph is not a tree)")]
    NotATree,
}

/// The dual tree of a triangulated n-gon.
#[derive(Clone, Debug)]
pub(crate) struct DualTree {
    graph: UnGraph<u32, [u32; 2]>,
    triangles: Vec<[u32; 3]>,
    n: usize,
}

/// Which triangle roots the propagation of a morph.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum RootChoice {
    /// The triangle closest to the centre of the disk image of the
    /// triangulation (Mukherjee & Gopi §5).
    #[default]
    Disk,
}

/// A dual tree rooted at one triangle: breadth-first order, parents and
/// base edges.
#[derive(Clone, Debug)]
pub(crate) struct Rooted {
    /// The root triangle.
    pub root: usize,
    /// Triangles in breadth-first order from the root (parents first).
    pub order: Vec<usize>,
    /// Parent of each triangle (`None` for the root).
    pub parent: Vec<Option<usize>>,
    /// For each non-root triangle, its base: the edge shared with its
    /// parent, as `[x, y]` in the triangle's own counter-clockwise order;
    /// the third vertex follows `y`. For the root, its first edge.
    pub base: Vec<[u32; 2]>,
    /// For each triangle, its third vertex (the corner not on the base).
    pub third: Vec<u32>,
}

impl DualTree {
    /// Builds the dual tree of `triangles`, a triangulation of the abstract
    /// `n`-gon (each triangle's corners in cyclic polygon order).
    ///
    /// # Errors
    ///
    /// [`TreeError`] when the count is wrong or the dual graph is not a
    /// tree.
    pub(crate) fn new(n: usize, triangles: &[[u32; 3]]) -> Result<DualTree, TreeError> {
        if n < 3 || triangles.len() != n - 2 {
            return Err(TreeError::Count {
                n,
                triangles: triangles.len(),
            });
        }
        let mut graph = UnGraph::with_capacity(triangles.len(), triangles.len());
        for t in 0..triangles.len() {
            graph.add_node(t as u32);
        }
        let mut owner: FxHashMap<(u32, u32), usize> =
            FxHashMap::with_capacity_and_hasher(3 * n, Default::default());
        let mut boundary_seen = vec![false; n];
        for (t, tri) in triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                if a as usize >= n || b as usize >= n {
                    return Err(TreeError::NotATree);
                }
                let key = (a.min(b), a.max(b));
                let boundary = (key.1 - key.0) as usize == 1 || (key.1 - key.0) as usize == n - 1;
                if boundary {
                    // Boundary edge (i, i + 1) is identified by i.
                    let i = if key.1 - key.0 == 1 { key.0 } else { key.1 } as usize;
                    if std::mem::replace(&mut boundary_seen[i], true) {
                        return Err(TreeError::NotATree);
                    }
                    continue;
                }
                match owner.remove(&key) {
                    Some(other) => {
                        graph.add_edge(NodeIndex::new(other), NodeIndex::new(t), [key.0, key.1]);
                    }
                    None => {
                        owner.insert(key, t);
                    }
                }
            }
        }
        if !owner.is_empty()
            || graph.edge_count() != triangles.len() - 1
            || boundary_seen.contains(&false)
        {
            return Err(TreeError::NotATree);
        }
        let tree = DualTree {
            graph,
            triangles: triangles.to_vec(),
            n,
        };
        if tree.rooted(0).order.len() != triangles.len() {
            return Err(TreeError::NotATree);
        }
        Ok(tree)
    }

    /// Number of polygon vertices.
    pub(crate) fn vertex_count(&self) -> usize {
        self.n
    }

    /// The triangles (nodes of the tree).
    pub(crate) fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// Number of neighbours of triangle `t` (1 leaf, 2 path, 3 internal).
    pub(crate) fn degree(&self, t: usize) -> usize {
        self.graph.neighbors(NodeIndex::new(t)).count()
    }

    /// Neighbouring triangles of `t` with the shared diagonal.
    pub(crate) fn neighbours(&self, t: usize) -> Vec<(usize, [u32; 2])> {
        self.neighbour_iter(t).collect()
    }

    /// [`DualTree::neighbours`] without collecting them (the traversals).
    fn neighbour_iter(&self, t: usize) -> impl Iterator<Item = (usize, [u32; 2])> + '_ {
        self.graph.edges(NodeIndex::new(t)).map(move |e| {
            use petgraph::visit::EdgeRef;
            let other = if e.source().index() == t {
                e.target().index()
            } else {
                e.source().index()
            };
            (other, *e.weight())
        })
    }

    /// Hop distances from `from` to every triangle.
    pub(crate) fn distances(&self, from: usize) -> Vec<usize> {
        let mut dist = vec![usize::MAX; self.triangles.len()];
        let mut queue = VecDeque::from([from]);
        dist[from] = 0;
        while let Some(t) = queue.pop_front() {
            for (u, _) in self.neighbour_iter(t) {
                if dist[u] == usize::MAX {
                    dist[u] = dist[t] + 1;
                    queue.push_back(u);
                }
            }
        }
        dist
    }

    /// The centre of the tree: the middle of a longest path (ties to the
    /// smaller index).
    pub(crate) fn centre(&self) -> usize {
        let d0 = self.distances(0);
        let a = argmax(&d0);
        let da = self.distances(a);
        let b = argmax(&da);
        let db = self.distances(b);
        let len = da[b];
        (0..self.triangles.len())
            .filter(|&t| da[t] + db[t] == len)
            .min_by_key(|&t| (da[t].max(db[t]), t))
            .unwrap_or(0)
    }

    /// Roots the tree at triangle `root`.
    pub(crate) fn rooted(&self, root: usize) -> Rooted {
        let m = self.triangles.len();
        let mut parent = vec![None; m];
        let mut seen = vec![false; m];
        let mut order = Vec::with_capacity(m);
        let mut base = vec![[0u32; 2]; m];
        let mut third = vec![0u32; m];
        let r = self.triangles[root];
        base[root] = [r[0], r[1]];
        third[root] = r[2];
        seen[root] = true;
        let mut queue = VecDeque::from([root]);
        while let Some(t) = queue.pop_front() {
            order.push(t);
            for (u, [a, b]) in self.neighbour_iter(t) {
                if seen[u] {
                    continue;
                }
                seen[u] = true;
                parent[u] = Some(t);
                let tri = self.triangles[u];
                // The base in u's counter-clockwise order: the corner pair
                // (tri[k], tri[k+1]) that is {a, b}.
                for k in 0..3 {
                    let (x, y) = (tri[k], tri[(k + 1) % 3]);
                    if (x == a && y == b) || (x == b && y == a) {
                        base[u] = [x, y];
                        third[u] = tri[(k + 2) % 3];
                    }
                }
                queue.push_back(u);
            }
        }
        Rooted {
            root,
            order,
            parent,
            base,
            third,
        }
    }

    /// The spine and pivot (Mukherjee & Gopi §6.1). `points` (the curve) break
    /// the choice between the two spine ends: the end triangle with the larger
    /// area becomes the pivot triangle.
    pub(crate) fn spine(&self, points: &[Point]) -> Spine {
        spine::spine(self, points)
    }
}

fn argmax(v: &[usize]) -> usize {
    let mut best = 0;
    for (i, &x) in v.iter().enumerate() {
        if x > v[best] {
            best = i;
        }
    }
    best
}

/// Where a plan's propagation starts: as a [`RootChoice`] says, or at a
/// given triangle (a bridge of the staged route roots its plan at the
/// feature it carries, so that the layout's rounding there is relative to
/// the feature's size, not to the distance from the disk's centre).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Root {
    /// As the choice says.
    Choice(RootChoice),
    /// This triangle (an index into the triangulation).
    Triangle(usize),
}

impl From<RootChoice> for Root {
    fn from(choice: RootChoice) -> Root {
        Root::Choice(choice)
    }
}

/// The root triangle for propagation.
///
/// [`RootChoice::Disk`]: place the vertices on a circle at angles
/// proportional to the curve's cumulative edge length (the disk image of
/// the triangulation) and take the triangle whose centroid is closest to
/// the centre. [`Root::Triangle`]: that triangle, where it is one.
pub(crate) fn root_triangle(tree: &DualTree, points: &[Point], root: Root) -> usize {
    match root {
        Root::Triangle(t) if t < tree.triangles().len() => t,
        Root::Triangle(_) | Root::Choice(RootChoice::Disk) => {
            let disk = disk_positions(points);
            let mut best = (f64::INFINITY, 0);
            for (t, tri) in tree.triangles().iter().enumerate() {
                let c =
                    (disk[tri[0] as usize] + disk[tri[1] as usize] + disk[tri[2] as usize]) / 3.0;
                let d = c.length_squared();
                if d < best.0 {
                    best = (d, t);
                }
            }
            best.1
        }
    }
}

/// Unit-circle positions of the vertices, spaced in proportion to the
/// curve's edge lengths (vertex 0 at angle 0, counter-clockwise), each edge
/// given at least 1/(4n) of the circle so that no two positions coincide
/// however short an edge is.
pub(crate) fn disk_positions(points: &[Point]) -> Vec<Point> {
    let n = points.len();
    let raw: Vec<f64> = (0..n)
        .map(|i| (points[(i + 1) % n] - points[i]).length())
        .collect();
    let perimeter: f64 = raw.iter().sum();
    let floor = perimeter / (4.0 * n as f64);
    let lengths: Vec<f64> = raw.iter().map(|&l| l.max(floor)).collect();
    let total: f64 = lengths.iter().sum();
    let mut acc = 0.0;
    let mut out = Vec::with_capacity(n);
    for len in lengths {
        let a = std::f64::consts::TAU * acc / total;
        out.push(Point::new(a.cos(), a.sin()));
        acc += len;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::points;

    /// Fan triangulation of an n-gon from vertex 0.
    pub(crate) fn fan(n: u32) -> Vec<[u32; 3]> {
        (1..n - 1).map(|i| [0, i, i + 1]).collect()
    }

    #[test]
    fn disk_positions_never_coincide_even_for_a_tiny_edge() {
        // A square with one edge 1e-13 of the perimeter: spacing by edge
        // length alone rounds its two disk points together.
        let pts = points([(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.0, 4e-13)]);
        let d = disk_positions(&pts);
        for i in 0..d.len() {
            for j in i + 1..d.len() {
                assert_ne!(d[i], d[j], "{i} {j}");
            }
        }
        // Every fan triangle of the disk is exactly counter-clockwise.
        for t in fan(d.len() as u32) {
            let [a, b, c] = t.map(|v| d[v as usize]);
            assert!(crate::geom::orient(a, b, c).is_ccw(), "{t:?}");
        }
    }

    #[test]
    fn fan_is_a_path() {
        let t = DualTree::new(6, &fan(6)).unwrap();
        let leaves: Vec<usize> = (0..4).filter(|&i| t.degree(i) <= 1).collect();
        assert_eq!(leaves, vec![0, 3]);
        assert_eq!(
            (0..4).map(|i| t.degree(i)).collect::<Vec<_>>(),
            vec![1, 2, 2, 1]
        );
        let r = t.rooted(1);
        assert_eq!(r.order.len(), 4);
        assert_eq!(r.parent[0], Some(1));
        // Triangle [0,1,2] meets [0,2,3] along 0-2; in its own CCW order the
        // base is (2, 0) and the third vertex 1.
        assert_eq!(r.base[0], [2, 0]);
        assert_eq!(r.third[0], 1);
    }

    #[test]
    fn rejects_non_trees() {
        assert!(matches!(
            DualTree::new(5, &fan(4)),
            Err(TreeError::Count { .. })
        ));
        // Two copies of the same triangle in a 4-gon.
        assert_eq!(
            DualTree::new(4, &[[0, 1, 2], [0, 1, 2]]).unwrap_err(),
            TreeError::NotATree
        );
    }

    #[test]
    fn centre_of_a_path() {
        let t = DualTree::new(9, &fan(9)).unwrap();
        assert_eq!(t.centre(), 3);
    }
}
