//! Times the convex-combination mesh morph on grid pairs and prints a
//! markdown table. Run with `cargo run --release --example bench_mesh`.
//!
//! Per-frame time is `(T(11 frames) − T(1 frame)) / 10`: the set-up
//! (validation, weights, symbolic analysis of the sparse LU) is paid once,
//! every further frame refactors numerically and solves.

use immerse::mesh_morph::{MeshMorphOptions, Method, mesh_morph};
use immerse::tiling::{Tiling, grid_pair};
use std::time::Instant;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn time(a: &Tiling, b: &Tiling, method: Method, frames: usize) -> f64 {
    let ts: Vec<f64> = (0..frames).map(|k| (k as f64 + 0.5) / frames as f64).collect();
    let start = Instant::now();
    let out = mesh_morph(a, b, method, &ts, &MeshMorphOptions::DEFAULT).expect("morph");
    let dt = start.elapsed().as_secs_f64();
    assert!(out.iter().all(|f| f.valid) || method == Method::Linear);
    dt
}

fn main() {
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|s| s.parse().ok())
        .collect();
    let sizes = if sizes.is_empty() { vec![102, 318] } else { sizes };
    println!("| grid | interior vertices | method | set-up + 1 frame (s) | per extra frame (s) |");
    println!("|---|---|---|---|---|");
    for n in sizes {
        let (a, b) = grid_pair(n, 1);
        let t = Tiling::new(a.points.clone(), a.faces.clone()).expect("valid source");
        let _ = Tiling::new(b.points.clone(), b.faces.clone()).expect("valid target");
        for method in [Method::Convex, Method::Intrinsic, Method::Local] {
            let one = median((0..3).map(|_| time(&t, &b, method, 1)).collect());
            let eleven = median((0..3).map(|_| time(&t, &b, method, 11)).collect());
            println!(
                "| {n}×{n} | {} | {} | {:.3} | {:.4} |",
                (n - 2) * (n - 2),
                method,
                one,
                (eleven - one) / 10.0
            );
        }
    }
}
