//! Criterion benchmarks of the immersion triangulators: n versus time for
//! the decision DP with witness, the Delaunay flips and the max–min DP.
//!
//! Run `cargo bench --bench immersion` (filter with e.g. `-- dp/1000`).
//! Input: a self-overlapping spiral strip of two turns with n vertices.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use immerse::geom::Point;
use immerse::{improve, triangulate, triangulate_maxmin};
use std::hint::black_box;

fn spiral_strip(n: usize, turns: f64) -> Vec<Point> {
    let half = n / 2;
    let at = |i: usize, r0: f64| {
        let a = i as f64 / (half - 1) as f64 * turns * std::f64::consts::TAU;
        let r = r0 + 0.25 * a;
        Point::new(r * a.cos(), r * a.sin())
    };
    let mut pts: Vec<Point> = (0..half).map(|i| at(i, 2.0)).collect();
    pts.extend((0..half).rev().map(|i| at(i, 1.0)));
    pts
}

fn immersion(c: &mut Criterion) {
    let mut g = c.benchmark_group("dp");
    g.sample_size(10);
    for n in [100, 250, 500, 1000, 2000] {
        let pts = spiral_strip(n, 2.0);
        g.bench_with_input(BenchmarkId::from_parameter(n), &pts, |b, pts| {
            b.iter(|| black_box(triangulate(pts).ok()))
        });
    }
    g.finish();

    let mut g = c.benchmark_group("delaunay_flips");
    g.sample_size(10);
    for n in [100, 250, 500, 1000, 2000] {
        let Ok(witness) = triangulate(&spiral_strip(n, 2.0)) else {
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
        let pts = spiral_strip(n, 2.0);
        g.bench_with_input(BenchmarkId::from_parameter(n), &pts, |b, pts| {
            b.iter(|| black_box(triangulate_maxmin(pts).ok()))
        });
    }
    g.finish();
}

criterion_group!(benches, immersion);
criterion_main!(benches);
