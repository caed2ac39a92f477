//! Mesh morph benchmarks (docs/design.md §11): the convex-combination morph on
//! generated grid pairs ([`grid_pair`]) with a fixed square boundary.
//!
//! `convex/1` times set-up plus one frame, `convex/11` set-up plus eleven;
//! the per-frame cost after the symbolic analysis is reused is their
//! difference divided by ten (see `benches/README.md`).

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use immerse_mesh::mesh_morph::{MeshMorphOptions, Method, mesh_morph};
use immerse_mesh::tiling::{Tiling, grid_pair};
use std::hint::black_box;

fn pair(n: usize) -> (Tiling, Tiling) {
    let (a, b) = grid_pair(n, 1);
    (
        Tiling::new(a.points, a.faces).expect("valid source"),
        Tiling::new(b.points, b.faces).expect("valid target"),
    )
}

fn convex(c: &mut Criterion) {
    let mut group = c.benchmark_group("convex");
    group.sample_size(10);
    for n in [52usize, 102, 318] {
        let (a, b) = pair(n);
        let interior = (n - 2) * (n - 2);
        for frames in [1usize, 11] {
            let ts: Vec<f64> = (0..frames)
                .map(|k| k as f64 / (frames.max(2) - 1) as f64)
                .collect();
            group.bench_with_input(
                BenchmarkId::new(format!("{frames}"), interior),
                &ts,
                |bench, ts| {
                    bench.iter(|| {
                        black_box(
                            mesh_morph(&a, &b, Method::Convex, ts, &MeshMorphOptions::DEFAULT)
                                .expect("morph"),
                        )
                    })
                },
            );
        }
    }
    group.finish();
}

criterion_group!(benches, convex);
criterion_main!(benches);
