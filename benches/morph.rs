//! Criterion benchmarks of frame generation: one frame of the compatible
//! propagation morph per path at n = 1,000 and 10,000 vertices, and the
//! end-to-end curve morph (triangulation, both flip sides, 60 checked
//! frames) at n = 100 and 400, and one frame of a planned `Tween` (layout
//! and exact check) at n = 500 and 2000.
//!
//! Run `cargo bench --bench morph` (filter with e.g. `-- frame/hybrid` or
//! `-- tween`).

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use immerse::RootChoice;
use immerse::morph::{Compatible, CurveMorphOptions, ThirdVertexPath, Tween};
use std::hint::black_box;

use testkit::shapes::spiral_strip;

fn frames(c: &mut Criterion) {
    let mut g = c.benchmark_group("frame");
    for n in [1_000usize, 10_000] {
        let (a, tris) = spiral_strip(n / 2, 1.6, 0.05);
        let (b, _) = spiral_strip(n / 2, 0.6, 0.05);
        let plan = Compatible::new(&a, &b, &tris, RootChoice::Disk, 0.05).expect("valid pair");
        for path in ThirdVertexPath::ALL {
            g.bench_with_input(BenchmarkId::new(path.as_str(), n), &plan, |bench, plan| {
                bench.iter(|| black_box(plan.positions(0.37, path)))
            });
        }
    }
    g.finish();
    let mut g = c.benchmark_group("curves");
    g.sample_size(10);
    for m in [50usize, 200] {
        let (a, _) = spiral_strip(m, 1.4, 0.3);
        let (b, _) = spiral_strip(m, 0.7, 0.3);
        let fr: Vec<f64> = (0..60).map(|i| f64::from(i) / 59.0).collect();
        g.bench_function(BenchmarkId::from_parameter(2 * m), |bench| {
            bench.iter(|| {
                let tween = Tween::new(&a, &b, &CurveMorphOptions::DEFAULT);
                black_box(tween.is_ok_and(|t| t.morph(&fr).is_ok()))
            })
        });
    }
    g.finish();
    // One frame of a planned (staged) tween: the pair needs flips, so the
    // frames cross legs; t steps through the travel.
    let mut g = c.benchmark_group("tween");
    g.sample_size(20);
    for n in [500usize, 2000] {
        let (a, _) = spiral_strip(n / 2, 1.4, 0.3);
        let (b, _) = spiral_strip(n / 2, 0.7, 0.3);
        let tween = Tween::new(&a, &b, &CurveMorphOptions::DEFAULT).expect("a valid pair");
        let mut i = 0u32;
        g.bench_with_input(BenchmarkId::from_parameter(n), &tween, |bench, tween| {
            bench.iter(|| {
                i = (i + 1) % 97;
                black_box(tween.frame(f64::from(i) / 96.0).is_ok())
            })
        });
    }
    g.finish();
}

criterion_group!(benches, frames);
criterion_main!(benches);
