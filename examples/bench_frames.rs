//! Frame generation speed: vertices × frames per second for the
//! compatible propagation morph (every path) and for the incompatible
//! morph end to end. Prints a markdown table of medians.
//!
//! Run with `cargo run --release --example bench_frames`.

use immerse::RootChoice;
use immerse::morph::{Compatible, CurveMorphOptions, ThirdVertexPath};
use std::time::Instant;
use testkit::morph_pair;

use testkit::shapes::spiral_strip;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Seconds per frame of `frames` making `count` frames: the median of 5
/// runs.
fn per_frame(count: usize, mut frames: impl FnMut()) -> f64 {
    let runs: Vec<f64> = (0..5)
        .map(|_| {
            let start = Instant::now();
            frames();
            start.elapsed().as_secs_f64() / count as f64
        })
        .collect();
    median(runs)
}

/// Seconds per frame of `plan.morph` at `times` (median of 5 runs), on
/// the cores of the calling pool; the morph must keep `path`.
fn checked_frames(plan: &Compatible, times: &[f64], path: ThirdVertexPath) -> f64 {
    per_frame(times.len(), || {
        let morph = plan.morph(times, path).expect("a checked morph");
        assert!(!morph.fallback, "{path}: {:?}", morph.fallbacks);
        std::hint::black_box(&morph);
    })
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("## Compatible morph: frames per second (median of 5 runs of 200 frames)\n");
    println!(
        "| vertices | path | ms per frame | frames/s | ms per frame, checked | frames/s, checked | target |"
    );
    println!("|---|---|---|---|---|---|---|");
    let one_core = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let times: Vec<f64> = (1..=200).map(|i| i as f64 / 201.0).collect();
    for n in [1_000usize, 10_000] {
        let (a, tris) = spiral_strip(n / 2, 1.6, 0.05);
        let (b, _) = spiral_strip(n / 2, 0.6, 0.05);
        let plan = Compatible::new(&a, &b, &tris, RootChoice::Disk, 0.05)?;
        for path in ThirdVertexPath::ALL {
            // The positions alone, and the frames as `Compatible::morph`
            // computes them for a caller: each checked exactly (the
            // triangulation's combinatorics once, every frame's triangles
            // and fans), here on one core.
            let positions = || {
                per_frame(times.len(), || {
                    let mut sink = 0.0;
                    for &t in &times {
                        sink += plan.positions(t, path)[n / 2].x;
                    }
                    std::hint::black_box(sink);
                })
            };
            let (s, c) = (
                positions(),
                one_core.install(|| checked_frames(&plan, &times, path)),
            );
            let target = if n == 10_000 {
                "> 1,000 frames/s with the check"
            } else {
                ""
            };
            println!(
                "| {n} | {path} | {:.3} | {:.0} | {:.3} | {:.0} | {target} |",
                s * 1e3,
                1.0 / s,
                c * 1e3,
                1.0 / c
            );
        }
    }
    println!(
        "\n## Checked frames on both cores (as `Compatible::morph` computes them; median of 5 runs of 200 frames)\n"
    );
    println!("| vertices | path | ms per frame | frames/s | target |");
    println!("|---|---|---|---|---|");
    {
        let n = 10_000;
        let (a, tris) = spiral_strip(n / 2, 1.6, 0.05);
        let (b, _) = spiral_strip(n / 2, 0.6, 0.05);
        let plan = Compatible::new(&a, &b, &tris, RootChoice::Disk, 0.05)?;
        for path in ThirdVertexPath::ALL {
            let s = checked_frames(&plan, &times, path);
            println!(
                "| {n} | {path} | {:.3} | {:.0} | > 1,000 frames/s |",
                s * 1e3,
                1.0 / s
            );
        }
    }
    println!(
        "\n## End to end (`Tween::new` and `Tween::morph`: triangulation + both sides + 60 checked frames; median of 3)\n"
    );
    println!("| vertices | time (ms) |");
    println!("|---|---|");
    for m in [25usize, 50, 100, 200] {
        let (a, _) = spiral_strip(m, 1.4, 0.3);
        let (b, _) = spiral_strip(m, 0.7, 0.3);
        let fr: Vec<f64> = (0..60).map(|i| i as f64 / 59.0).collect();
        let runs: Vec<f64> = (0..3)
            .map(|_| {
                let start = Instant::now();
                let out = morph_pair(&a, &b, &fr, &CurveMorphOptions::DEFAULT);
                std::hint::black_box(out.is_ok());
                start.elapsed().as_secs_f64()
            })
            .collect();
        println!("| {} | {:.1} |", 2 * m, median(runs) * 1e3);
    }
    Ok(())
}
