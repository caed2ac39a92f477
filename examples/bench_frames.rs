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

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("## Compatible morph: frames per second (median of 5 runs of 200 frames)\n");
    println!(
        "| vertices | path | ms per frame | frames/s | ms per frame, checked | frames/s, checked | target |"
    );
    println!("|---|---|---|---|---|---|---|");
    for n in [1_000usize, 10_000] {
        let (a, tris) = spiral_strip(n / 2, 1.6, 0.05);
        let (b, _) = spiral_strip(n / 2, 0.6, 0.05);
        let plan = Compatible::new(&a, &b, &tris, RootChoice::Disk, 0.05)?;
        for path in ThirdVertexPath::ALL {
            // Without and with the exact check of every frame that `morph`
            // runs before it writes one (`immerse::check`: every
            // triangle valid, and the combinatorics of the triangulation,
            // which the tool checks once per fixed triangulation).
            let time = |checked: bool| {
                let runs: Vec<f64> = (0..5)
                    .map(|_| {
                        let start = Instant::now();
                        let mut sink = 0.0;
                        for i in 1..=200 {
                            let p = plan.positions(i as f64 / 201.0, path);
                            if checked {
                                assert!(immerse::check(&p, &tris).is_ok());
                            }
                            sink += p[n / 2].x;
                        }
                        std::hint::black_box(sink);
                        start.elapsed().as_secs_f64() / 200.0
                    })
                    .collect();
                median(runs)
            };
            let (s, c) = (time(false), time(true));
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
        "\n## Checked frames on both cores (as `Tween::morph` computes them; median of 5 runs of 200 frames)\n"
    );
    println!("| vertices | path | ms per frame | frames/s | target |");
    println!("|---|---|---|---|---|");
    {
        use rayon::prelude::*;
        let n = 10_000;
        let (a, tris) = spiral_strip(n / 2, 1.6, 0.05);
        let (b, _) = spiral_strip(n / 2, 0.6, 0.05);
        let plan = Compatible::new(&a, &b, &tris, RootChoice::Disk, 0.05)?;
        for path in ThirdVertexPath::ALL {
            let runs: Vec<f64> = (0..5)
                .map(|_| {
                    let start = Instant::now();
                    let ok = (1..=200).into_par_iter().all(|i| {
                        let p = plan.positions(i as f64 / 201.0, path);
                        immerse::check(&p, &tris).is_ok()
                    });
                    assert!(ok);
                    start.elapsed().as_secs_f64() / 200.0
                })
                .collect();
            let s = median(runs);
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
