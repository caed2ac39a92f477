//! Exact validation of Floater & Gotsman Definition 2.1, and the tiling's
//! topology.
//!
//! The test is local, and linear in the size of the input:
//! 1. the faces form a connected combinatorial disk (every directed edge in
//!    at most one face, one fan of faces around every vertex, one boundary
//!    cycle, Euler characteristic 1);
//! 2. every face is strictly convex and counter-clockwise: every corner is
//!    a strict left turn ([`orient`]) and its edge directions turn around
//!    exactly once;
//! 3. the faces around an interior vertex turn around it exactly once, and
//!    those around a boundary vertex less than once;
//! 4. the boundary cycle is convex: no right turns, straight corners only
//!    strictly between their neighbours, one turn in all.
//!
//! A locally injective orientation-preserving piecewise linear map of a
//! disk whose boundary is a simple closed curve is a homeomorphism onto the
//! region bounded by that curve, so 1–4 are equivalent to conditions (1)–(3)
//! of Definition 2.1. Turns are counted exactly: a direction is "upper" when
//! its point is above the origin point (or level and to the right), which
//! compares coordinates only, and each step turns by less than π.

use super::{MAX_COORDINATE, MAX_VERTICES, Tiling, TilingError};
use immerse_base::geom::{Orientation, Point, orient};
use std::collections::HashMap;

/// Index-only structure of a tiling: boundary cycle and the fan of
/// neighbours around every vertex.
#[derive(Clone, Debug)]
pub(crate) struct Topology {
    /// Boundary vertices, counter-clockwise.
    pub(crate) boundary: Vec<u32>,
    /// True for boundary vertices.
    pub(crate) is_boundary: Vec<bool>,
    /// Edge neighbours of every vertex in counter-clockwise order. For a
    /// boundary vertex the fan runs from the next boundary vertex to the
    /// previous one.
    pub(crate) fan: Vec<Vec<u32>>,
}

impl Topology {
    /// Builds the topology, checking that the faces form a disk.
    /// Indices must already be in range and distinct within each face.
    pub(crate) fn build(faces: &[Vec<u32>], n: usize) -> Result<Topology, TilingError> {
        let key = |a: u32, b: u32| (u64::from(a) << 32) | u64::from(b);
        let mut edges: HashMap<u64, usize> = HashMap::new();
        let mut half_edges = 0usize;
        for (f, face) in faces.iter().enumerate() {
            for k in 0..face.len() {
                let (a, b) = (face[k], face[(k + 1) % face.len()]);
                if a as usize >= n || b as usize >= n {
                    return Err(TilingError::IndexOutOfRange {
                        face: f,
                        index: i64::from(a.max(b)),
                        vertices: n,
                    });
                }
                if edges.insert(key(a, b), f).is_some() {
                    return Err(TilingError::InconsistentEdge {
                        face: f,
                        from: a,
                        to: b,
                    });
                }
                half_edges += 1;
            }
        }
        // Corners per vertex: (next, prev), counter-clockwise from next to prev.
        let mut corners: Vec<Vec<(u32, u32)>> = vec![Vec::new(); n];
        for face in faces {
            let m = face.len();
            for k in 0..m {
                corners[face[k] as usize].push((face[(k + 1) % m], face[(k + m - 1) % m]));
            }
        }
        let mut fan = vec![Vec::new(); n];
        let mut is_boundary = vec![false; n];
        let mut bnext = vec![u32::MAX; n];
        let mut boundary_edges = 0usize;
        for v in 0..n {
            let vc = &corners[v];
            if vc.is_empty() {
                return Err(TilingError::UnusedVertex { vertex: v as u32 });
            }
            let vv = v as u32;
            let starts: Vec<usize> = (0..vc.len())
                .filter(|&c| !edges.contains_key(&key(vc[c].0, vv)))
                .collect();
            let nonmanifold = || TilingError::NonManifoldVertex { vertex: vv };
            let f = &mut fan[v];
            match starts.len() {
                0 => {
                    let mut c = 0usize;
                    for _ in 0..vc.len() {
                        f.push(vc[c].0);
                        let prev = vc[c].1;
                        match vc.iter().position(|&(nx, _)| nx == prev) {
                            Some(next_c) => c = next_c,
                            None => return Err(nonmanifold()),
                        }
                    }
                    if c != 0 {
                        return Err(nonmanifold());
                    }
                }
                1 => {
                    is_boundary[v] = true;
                    boundary_edges += 1;
                    let mut c = starts[0];
                    bnext[v] = vc[c].0;
                    f.push(vc[c].0);
                    for step in 0..vc.len() {
                        let prev = vc[c].1;
                        f.push(prev);
                        match vc.iter().position(|&(nx, _)| nx == prev) {
                            Some(next_c) if step + 1 < vc.len() => c = next_c,
                            Some(_) => return Err(nonmanifold()),
                            None if step + 1 == vc.len() => {}
                            None => return Err(nonmanifold()),
                        }
                    }
                }
                _ => return Err(nonmanifold()),
            }
        }
        // Boundary cycles.
        let mut seen = vec![false; n];
        let mut loops = 0usize;
        let mut boundary = Vec::new();
        for v in 0..n {
            if !is_boundary[v] || seen[v] {
                continue;
            }
            loops += 1;
            let mut cur = v;
            while !seen[cur] {
                seen[cur] = true;
                if loops == 1 {
                    boundary.push(cur as u32);
                }
                cur = bnext[cur] as usize;
                if cur >= n || !is_boundary[cur] {
                    return Err(TilingError::NonManifoldVertex { vertex: v as u32 });
                }
            }
        }
        let e = (half_edges + boundary_edges) / 2;
        let euler = n as i64 - e as i64 + faces.len() as i64;
        if loops != 1 || euler != 1 {
            return Err(TilingError::NotADisk {
                boundary_loops: loops,
                euler,
            });
        }
        // Connectivity.
        let mut reached = vec![false; n];
        let mut stack = vec![0usize];
        reached[0] = true;
        let mut count = 1;
        while let Some(v) = stack.pop() {
            for &w in &fan[v] {
                if !reached[w as usize] {
                    reached[w as usize] = true;
                    count += 1;
                    stack.push(w as usize);
                }
            }
        }
        if count != n {
            return Err(TilingError::NotADisk {
                boundary_loops: loops,
                euler,
            });
        }
        Ok(Topology {
            boundary,
            is_boundary,
            fan,
        })
    }

    /// Interior vertices in increasing order.
    pub(crate) fn interior(&self) -> Vec<u32> {
        (0..self.is_boundary.len() as u32)
            .filter(|&v| !self.is_boundary[v as usize])
            .collect()
    }
}

/// True when the direction from `o` to `p` is "upper": `p` above `o`, or
/// level and to the right. Compares coordinates only, so it is exact.
fn is_upper(o: Point, p: Point) -> bool {
    p.y > o.y || (p.y == o.y && p.x > o.x)
}

/// Number of class changes (upper/lower) along a cyclic sequence of
/// directions; twice the number of turns when every step is a left turn of
/// less than π.
fn class_changes(classes: impl Iterator<Item = bool> + Clone, closed: bool) -> usize {
    let v: Vec<bool> = classes.collect();
    let mut changes = v.windows(2).filter(|w| w[0] != w[1]).count();
    if closed && v.len() > 1 && v[0] != v[v.len() - 1] {
        changes += 1;
    }
    changes
}

/// Checks coordinates, sizes and indices; everything before topology.
pub(crate) fn validate_input(points: &[Point], faces: &[Vec<u32>]) -> Result<(), TilingError> {
    if points.len() > MAX_VERTICES {
        return Err(TilingError::TooManyVertices {
            count: points.len(),
            max: MAX_VERTICES,
        });
    }
    if points.is_empty() || faces.is_empty() {
        return Err(TilingError::Empty {
            points: points.len(),
            faces: faces.len(),
        });
    }
    for (i, p) in points.iter().enumerate() {
        if !p.is_finite() {
            return Err(TilingError::NonFinite { vertex: i });
        }
        if p.x.abs() > MAX_COORDINATE || p.y.abs() > MAX_COORDINATE {
            return Err(TilingError::CoordinateTooLarge {
                vertex: i,
                max: MAX_COORDINATE,
            });
        }
    }
    for (f, face) in faces.iter().enumerate() {
        if face.len() < 3 {
            return Err(TilingError::FaceTooSmall {
                face: f,
                len: face.len(),
            });
        }
        for &i in face {
            if i as usize >= points.len() {
                return Err(TilingError::IndexOutOfRange {
                    face: f,
                    index: i64::from(i),
                    vertices: points.len(),
                });
            }
        }
        let mut sorted = face.clone();
        sorted.sort_unstable();
        if let Some(w) = sorted.windows(2).find(|w| w[0] == w[1]) {
            return Err(TilingError::RepeatedVertex {
                face: f,
                vertex: w[0],
            });
        }
    }
    Ok(())
}

/// True when every face of `faces` is strictly convex and counter-clockwise
/// at `points` (exact). This is the per-frame validity of a morph.
pub(crate) fn faces_strictly_convex(points: &[Point], faces: &[Vec<u32>]) -> bool {
    faces
        .iter()
        .enumerate()
        .all(|(f, _)| check_face(points, faces, f).is_ok())
}

fn check_face(points: &[Point], faces: &[Vec<u32>], f: usize) -> Result<(), TilingError> {
    let face = &faces[f];
    let m = face.len();
    let p = |k: usize| points[face[k % m] as usize];
    for (k, &vertex) in face.iter().enumerate() {
        if orient(p(k + m - 1), p(k), p(k + 1)) != Orientation::CounterClockwise {
            return Err(TilingError::FaceNotConvex { face: f, vertex });
        }
    }
    let changes = class_changes((0..m).map(|k| is_upper(p(k), p(k + 1))), true);
    if changes != 2 {
        return Err(TilingError::FaceWinds {
            face: f,
            winding: changes / 2,
        });
    }
    Ok(())
}

/// Validates a tiling against Floater & Gotsman Definition 2.1 and returns its
/// topology.
pub(crate) fn validate_topology(tiling: &Tiling) -> Result<Topology, TilingError> {
    let points = &tiling.points;
    validate_input(points, &tiling.faces)?;
    for f in 0..tiling.faces.len() {
        check_face(points, &tiling.faces, f)?;
    }
    let topo = Topology::build(&tiling.faces, points.len())?;
    // Fans: every step is a left turn of less than π (a face corner), so
    // class changes count half turns.
    for (v, fan) in topo.fan.iter().enumerate() {
        let o = points[v];
        let changes = class_changes(
            fan.iter().map(|&w| is_upper(o, points[w as usize])),
            !topo.is_boundary[v],
        );
        let ok = if topo.is_boundary[v] {
            changes <= 1
        } else {
            changes == 2
        };
        if !ok {
            return Err(TilingError::Overlap {
                vertex: v as u32,
                winding: changes.div_ceil(2),
            });
        }
    }
    // Boundary convexity.
    let b = &topo.boundary;
    let m = b.len();
    let bp = |k: usize| points[b[k % m] as usize];
    for (k, &vertex) in b.iter().enumerate() {
        let (u, v, w) = (bp(k + m - 1), bp(k), bp(k + 1));
        let bad = match orient(u, v, w) {
            Orientation::CounterClockwise => false,
            Orientation::Clockwise => true,
            Orientation::Collinear => {
                let lt = |a: Point, c: Point| (a.x, a.y) < (c.x, c.y);
                !((lt(u, v) && lt(v, w)) || (lt(w, v) && lt(v, u)))
            }
        };
        if bad {
            return Err(TilingError::BoundaryNotConvex { vertex });
        }
    }
    let changes = class_changes((0..m).map(|k| is_upper(bp(k), bp(k + 1))), true);
    if changes != 2 {
        return Err(TilingError::BoundaryNotConvex { vertex: b[0] });
    }
    Ok(topo)
}

/// Validates a tiling against Floater & Gotsman Definition 2.1.
///
/// # Errors
///
/// The first problem found, as a [`TilingError`] naming the face or vertex.
pub fn validate(tiling: &Tiling) -> Result<(), TilingError> {
    validate_topology(tiling).map(|_| ())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square_pair() -> (Vec<Point>, Vec<Vec<u32>>) {
        (
            vec![
                Point::new(0.0, 0.0),
                Point::new(1.0, 0.0),
                Point::new(1.0, 1.0),
                Point::new(0.0, 1.0),
                Point::new(0.5, 0.5),
            ],
            vec![vec![0, 1, 4], vec![1, 2, 4], vec![2, 3, 4], vec![3, 0, 4]],
        )
    }

    #[test]
    fn accepts_fan_and_builds_topology() {
        let (p, f) = square_pair();
        let t = Tiling::new(p, f).unwrap();
        let topo = validate_topology(&t).unwrap();
        assert_eq!(topo.boundary.len(), 4);
        assert_eq!(topo.fan[4], vec![0, 1, 2, 3]);
        assert_eq!(topo.interior(), vec![4]);
    }

    #[test]
    fn rejects_clockwise_face() {
        let (p, mut f) = square_pair();
        f[1] = vec![1, 4, 2];
        assert!(Tiling::new(p, f).is_err());
    }

    #[test]
    fn rejects_folded_vertex() {
        let (mut p, f) = square_pair();
        p[4] = Point::new(1.5, 0.5);
        assert!(Tiling::new(p, f).is_err());
    }
}
