//! The render crate's synthetic morph, shared by its benchmark and
//! `examples/bench_render.rs` (feature `render`).
//!
//! A 500-vertex star-shaped polygon, ear-clipped once (498 triangles), is
//! interpolated towards a twisted copy of itself: each vertex turns by an
//! angle that grows with its radius, so in-between frames curl and their
//! triangles overlap.

use immerse_render::Frame;

/// The star polygon with `n` vertices, counter-clockwise.
pub fn star(n: usize) -> Vec<[f64; 2]> {
    (0..n)
        .map(|i| {
            let t = i as f64 / n as f64 * std::f64::consts::TAU;
            let r = 1.0 + 0.3 * (7.0 * t).sin();
            [r * t.cos(), r * t.sin()]
        })
        .collect()
}

fn cross(o: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
}

/// Ear clipping of a simple counter-clockwise polygon: `n - 2` triangles.
pub fn ear_clip(p: &[[f64; 2]]) -> Vec<[u32; 3]> {
    let mut idx: Vec<usize> = (0..p.len()).collect();
    let mut tris = Vec::with_capacity(p.len().saturating_sub(2));
    let mut i = 0;
    let mut stall = 0;
    while idx.len() > 3 && stall <= idx.len() {
        let m = idx.len();
        let (a, b, c) = (idx[(i + m - 1) % m], idx[i % m], idx[(i + 1) % m]);
        let convex = cross(p[a], p[b], p[c]) > 0.0;
        let empty = convex
            && idx.iter().all(|&k| {
                k == a
                    || k == b
                    || k == c
                    || !(cross(p[a], p[b], p[k]) >= 0.0
                        && cross(p[b], p[c], p[k]) >= 0.0
                        && cross(p[c], p[a], p[k]) >= 0.0)
            });
        if empty {
            tris.push([a as u32, b as u32, c as u32]);
            idx.remove(i % m);
            stall = 0;
        } else {
            i += 1;
            stall += 1;
        }
        i %= idx.len();
    }
    if let [a, b, c] = idx[..] {
        tris.push([a as u32, b as u32, c as u32]);
    }
    tris
}

/// `frames` frames morphing the `n`-vertex star into its twisted copy.
pub fn morph(n: usize, frames: usize) -> Vec<Frame> {
    let src = star(n);
    let tris = ear_clip(&src);
    let dst: Vec<[f64; 2]> = src
        .iter()
        .map(|&[x, y]| {
            let r = x.hypot(y);
            let a = 0.6 + 2.2 * r * r;
            let (s, c) = a.sin_cos();
            [c * x - s * y + 0.3, s * x + c * y]
        })
        .collect();
    (0..frames)
        .map(|f| {
            let t = f as f64 / (frames.max(2) - 1) as f64;
            let points = src
                .iter()
                .zip(&dst)
                .map(|(a, b)| [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])])
                .collect();
            let mut frame = Frame::from_triangles(points, tris.clone());
            frame.spine = (0..tris.len() as u32).step_by(50).collect();
            frame.markers = vec![frame.points[0]];
            frame
        })
        .collect()
}
