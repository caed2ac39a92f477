//! Time per frame of a planned [`Tween`] (one layout and one exact check)
//! at n = 500 and 2000 vertices, and what the planning costs once.
//! Prints a markdown table of medians.
//!
//! Run with `cargo run --release --example bench_tween` (optionally the
//! vertex counts: `-- 500 2000 4000`).
//!
//! Two pairs: two spiral strips (1.4 and 0.7 turns) whose triangulations
//! are compatible, so the tween is one leg; and the drawings
//! `curves/ribbon-curl.svg` → `curves/tail-loop.svg` with vertices
//! inserted on their edges up to n, whose triangulations differ, so the
//! tween is staged (legs through target-shaped intermediates with flips
//! between them). The frames are spread over the whole travel, so every
//! leg is visited.

use immerse::correspond::insert_vertices;
use immerse::morph::{CurveMorphOptions, Tween};
use immerse::{Curve, Point};
use std::hint::black_box;
use std::time::Instant;

use testkit::shapes::spiral_strip;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse())
        .collect::<Result<_, _>>()?;
    let sizes = if sizes.is_empty() {
        vec![500, 2000]
    } else {
        sizes
    };
    println!(
        "## Tween: time per frame (median of 5 runs over 100 frames spread over the travel)\n"
    );
    println!("| pair | vertices | planning (s) | flips | ms per frame | frames/s |");
    println!("|---|---|---|---|---|---|");
    let ribbon = Curve::from_path("curves/ribbon-curl.svg")?.points;
    let tail = Curve::from_path("curves/tail-loop.svg")?.points;
    let pairs = sizes.iter().flat_map(|&n| {
        let spirals = (
            "spiral strips",
            n,
            spiral_strip(n / 2, 1.4, 0.3).0,
            spiral_strip(n / 2, 0.7, 0.3).0,
        );
        let up = |p: &[Point]| insert_vertices(p, n.saturating_sub(p.len())).0;
        let drawings = ("ribbon → tail", n, up(&ribbon), up(&tail));
        [spirals, drawings]
    });
    for (what, n, a, b) in pairs {
        let start = Instant::now();
        let tween = Tween::new(&a, &b, &CurveMorphOptions::DEFAULT)?;
        let planning = start.elapsed().as_secs_f64();
        let frames = 100;
        let runs: Vec<f64> = (0..5)
            .map(|run| {
                let start = Instant::now();
                for i in 0..frames {
                    // A different t each run, so nothing is reused.
                    let t = (i as f64 + 0.1 * run as f64) / frames as f64;
                    black_box(tween.frame(t).expect("a valid frame"));
                }
                start.elapsed().as_secs_f64() / frames as f64
            })
            .collect();
        let per = median(runs);
        println!(
            "| {what} | {n} | {planning:.3} | {} | {:.3} | {:.0} |",
            tween.report().flips,
            per * 1e3,
            1.0 / per
        );
    }
    Ok(())
}
