//! Criterion benchmarks of the segment certificate (docs/design.md §13):
//! n versus time for one straight-line segment under a fixed
//! triangulation.
//!
//! Run `cargo bench --bench certify` (filter with e.g. `-- typical/10000`).
//! Input: a spiral strip of 2.5 turns (n = 2m vertices, its zigzag
//! triangulation) and, as the segment's end,
//! - `typical`: the strip curled to 2.52 turns (one frame's step of a morph);
//! - `typical_f32`: the same against the f32 player's margin;
//! - `failing`: curled to 3 turns in one segment, which turns triangles
//!   over: the cost of locating the earliest failure exactly;
//! - `near_degenerate`: turned by π − 10⁻⁹ about the origin, so that at
//!   s = ½ every triangle is within 10⁻¹⁸ of flat and nearly every one goes
//!   to exact arithmetic (the filter's worst case; certified).

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use immerse::Point;
use immerse::certify::{Player, certify_segment};
use std::hint::black_box;

use testkit::shapes::spiral_strip;

fn certify(c: &mut Criterion) {
    let sizes = [100, 1000, 10_000];
    type Case = (&'static str, Player, bool, fn(usize) -> Vec<Point>);
    let cases: [Case; 4] = [
        ("typical", Player::Exact, true, |n| {
            spiral_strip(n / 2, 2.52, 0.3).0
        }),
        ("typical_f32", Player::F32, true, |n| {
            spiral_strip(n / 2, 2.52, 0.3).0
        }),
        ("failing", Player::Exact, false, |n| {
            spiral_strip(n / 2, 3.0, 0.3).0
        }),
        ("near_degenerate", Player::Exact, true, |n| {
            let t = std::f64::consts::PI - 1e-9;
            let (s, co) = t.sin_cos();
            spiral_strip(n / 2, 2.5, 0.3)
                .0
                .iter()
                .map(|p| Point::new(co * p.x - s * p.y, s * p.x + co * p.y))
                .collect()
        }),
    ];
    for (name, player, certified, end) in cases {
        let mut g = c.benchmark_group(format!("certify/{name}"));
        g.sample_size(20);
        for n in sizes {
            let (start, tris) = spiral_strip(n / 2, 2.5, 0.3);
            let end = end(n);
            let report = certify_segment(&start, &end, &tris, player).expect("a motion");
            assert_eq!(
                report.is_certified(),
                certified,
                "{name} {n}: {:?}",
                report.failure
            );
            g.bench_with_input(
                BenchmarkId::from_parameter(n),
                &(start, end, tris),
                |b, (p, q, t)| b.iter(|| black_box(certify_segment(p, q, t, player).ok())),
            );
        }
        g.finish();
    }
}

criterion_group!(benches, certify);
criterion_main!(benches);
