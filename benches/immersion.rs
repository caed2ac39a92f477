//! Criterion benchmarks of the immersion triangulators: n versus time for
//! the decision DP with witness, the Delaunay flips and the max–min DP.
//!
//! Run `cargo bench --bench immersion` (filter with e.g. `-- dp/1000`).
//! Input: a self-overlapping spiral strip of two turns with n vertices.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use immerse::{improve, triangulate, triangulate_maxmin};
use std::hint::black_box;

use testkit::shapes::wide_spiral;

fn immersion(c: &mut Criterion) {
    let mut g = c.benchmark_group("dp");
    g.sample_size(10);
    for n in [100, 250, 500, 1000, 2000] {
        let pts = wide_spiral(n, 2.0);
        g.bench_with_input(BenchmarkId::from_parameter(n), &pts, |b, pts| {
            b.iter(|| black_box(triangulate(pts).ok()))
        });
    }
    g.finish();

    let mut g = c.benchmark_group("delaunay_flips");
    g.sample_size(10);
    for n in [100, 250, 500, 1000, 2000] {
        let Ok(witness) = triangulate(&wide_spiral(n, 2.0)) else {
            continue;
        };
        g.bench_with_input(BenchmarkId::from_parameter(n), &witness, |b, w| {
            b.iter(|| black_box(improve(w.clone())))
        });
    }
    g.finish();

    let mut g = c.benchmark_group("maxmin");
    g.sample_size(10);
    for n in [100, 250, 500, 1000] {
        let pts = wide_spiral(n, 2.0);
        g.bench_with_input(BenchmarkId::from_parameter(n), &pts, |b, pts| {
            b.iter(|| black_box(triangulate_maxmin(pts).ok()))
        });
    }
    g.finish();
}

criterion_group!(benches, immersion);
criterion_main!(benches);
