//! Times the mesh morphs on generated grid pairs ([`grid_pair`]) and prints
//! a markdown table. Run with
//! `cargo run --release -p immerse-mesh --example bench_mesh`
//! (optionally followed by grid sizes, default `102 318`, i.e. 10,000 and
//! 99,856 interior vertices).
//!
//! Per-frame time is `(T(1 + k frames) − T(1 frame)) / k`: the set-up
//! (validation, weights, the multigrid hierarchy) and the first frame's solve
//! from zero are paid once, every further frame is a warm-started
//! multigrid-preconditioned solve (see `mesh/src/solve.rs`).
//! Frames are evenly spaced over [0, 1], so larger `k` means smaller steps.

use immerse_mesh::mesh_morph::{MeshMorphOptions, Method, mesh_morph};
use immerse_mesh::tiling::{Tiling, grid_pair};
use std::time::Instant;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn time(a: &Tiling, b: &Tiling, method: Method, frames: usize) -> f64 {
    let ts: Vec<f64> = (0..frames)
        .map(|k| k as f64 / (frames.max(2) - 1) as f64)
        .collect();
    let start = Instant::now();
    let out = mesh_morph(a, b, method, &ts, &MeshMorphOptions::DEFAULT).expect("morph");
    let dt = start.elapsed().as_secs_f64();
    assert!(out.iter().all(|f| f.valid), "{method}: invalid frame");
    dt
}

fn main() {
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|s| s.parse().ok())
        .collect();
    let sizes = if sizes.is_empty() {
        vec![102, 318]
    } else {
        sizes
    };
    println!(
        "| interior vertices | method | frames | set-up + first frame (s) | median per further frame (s) |"
    );
    println!("|---|---|---|---|---|");
    for n in sizes {
        let (a, b) = grid_pair(n, 1);
        let a = Tiling::new(a.points, a.faces).expect("valid source");
        let b = Tiling::new(b.points, b.faces).expect("valid target");
        let methods: &[Method] = if n <= 150 {
            &[
                Method::Linear,
                Method::Convex,
                Method::Intrinsic,
                Method::Local,
            ]
        } else {
            &[Method::Convex]
        };
        for &method in methods {
            for extra in [10usize, 40] {
                let reps = if n <= 150 { 3 } else { 1 };
                let one = median((0..reps).map(|_| time(&a, &b, method, 1)).collect());
                let many = median((0..reps).map(|_| time(&a, &b, method, 1 + extra)).collect());
                println!(
                    "| {} | {} | {} | {:.3} | {:.4} |",
                    (n - 2) * (n - 2),
                    method,
                    1 + extra,
                    one,
                    (many - one) / extra as f64
                );
            }
        }
    }
}
