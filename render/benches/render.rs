//! Criterion benchmarks of the rasteriser and encoders on the synthetic
//! 500-vertex morph (`testkit::synth`).
//!
//! ```text
//! cargo bench -p immerse-render --bench render [-- FILTER]
//! ```

use testkit::synth;

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use immerse_render::{Loop, Output, Style, View, animated_svg, encode_png, render, svg_frame};

fn bench(c: &mut Criterion) {
    let frames = synth::morph(500, 120);
    let mid = &frames[60];
    let ghosts = [&frames[0], &frames[119]];

    let mut group = c.benchmark_group("render");
    group.sample_size(20);
    for size in [256u32, 512, 1024] {
        let style = Style::DEFAULT.with_size(size, size);
        let view = View::fit(&frames, &style);
        group.bench_with_input(BenchmarkId::from_parameter(size), &size, |b, _| {
            b.iter(|| render(black_box(mid), &view, &style, &ghosts).expect("render"));
        });
    }
    group.finish();

    let style = Style::DEFAULT.with_size(1024, 1024);
    let view = View::fit(&frames, &style);
    let pixmap = render(mid, &view, &style, &ghosts).expect("render");
    let mut group = c.benchmark_group("encode");
    group.sample_size(20);
    group.bench_function("png_1024", |b| b.iter(|| encode_png(black_box(&pixmap))));
    group.bench_function("svg_frame", |b| {
        b.iter(|| svg_frame(black_box(mid), &view, &style, &ghosts))
    });
    group.bench_function("animated_svg_120", |b| {
        b.iter(|| animated_svg(black_box(&frames), &style, 30.0, Loop::PingPong))
    });
    group.finish();

    // The whole 120-frame PNG sequence, as the CLI writes it.
    let mut group = c.benchmark_group("sequence");
    group.sample_size(10);
    let dir = tempfile::tempdir().expect("temp dir");
    let opts = Output::DEFAULT.with_force(true);
    group.bench_function("png_120x1024", |b| {
        b.iter(|| {
            immerse_render::write_png_sequence(&frames, dir.path(), &style, &opts, &|_| {})
                .expect("write")
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
