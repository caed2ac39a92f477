//! Time the immersion triangulators against n and print a markdown table of
//! medians (own timing loop; run with `cargo run --release --example bench_dp`).
//!
//! Input: a self-overlapping spiral strip (two full turns, overlapping
//! itself) with n vertices. Columns: decision + witness
//! ([`immerse::triangulate`]), Delaunay flips on that witness
//! ([`immerse::improve`]), the max–min DP ([`immerse::triangulate_maxmin`],
//! skipped above `--maxmin-up-to`, default 1000), and the DP tables' memory.
//! `--sizes 500,1000` picks other n; `--shape circle` uses a regular n-gon.

use std::time::Instant;

use immerse::geom::Point;
use immerse::immersion::dp_memory_bytes;
use immerse::quality::maxmin_memory_bytes;
use immerse::{improve, triangulate, triangulate_maxmin};

/// A spiral strip of `n` vertices (n even) turning `turns` times.
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

/// A regular n-gon: convex, so every triangle is valid (the max–min DP's
/// worst case for pruning).
fn circle(n: usize) -> Vec<Point> {
    (0..n)
        .map(|i| {
            let a = i as f64 * std::f64::consts::TAU / n as f64;
            Point::new(a.cos(), a.sin())
        })
        .collect()
}

fn median_secs(runs: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..runs)
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn fmt_ms(s: f64) -> String {
    format!("{:.2} ms", s * 1e3)
}

fn main() {
    let maxmin_up_to: usize = std::env::args()
        .skip_while(|a| a != "--maxmin-up-to")
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1000);
    let sizes: Vec<usize> = std::env::args()
        .skip_while(|a| a != "--sizes")
        .nth(1)
        .map(|s| s.split(',').filter_map(|x| x.parse().ok()).collect())
        .unwrap_or_else(|| vec![100, 250, 500, 1000, 2000]);
    let shape = std::env::args()
        .skip_while(|a| a != "--shape")
        .nth(1)
        .unwrap_or_else(|| "spiral".to_owned());
    println!("shape: {shape}\n");
    println!("| n | decision + witness | Delaunay flips | maxmin DP | DP memory | maxmin memory |");
    println!("|---|---|---|---|---|---|");
    for n in sizes {
        let pts = match shape.as_str() {
            "circle" => circle(n),
            _ => spiral_strip(n, 2.0),
        };
        let runs = if n >= 1000 { 5 } else { 11 };
        let witness = match triangulate(&pts) {
            Ok(imm) => imm,
            Err(e) => {
                println!("| {n} | {e} | | | | |");
                continue;
            }
        };
        let t_dp = median_secs(runs, || {
            std::hint::black_box(triangulate(&pts).ok());
        });
        let t_flip = median_secs(runs, || {
            std::hint::black_box(improve(witness.clone()));
        });
        let t_mm = if n <= maxmin_up_to {
            fmt_ms(median_secs(if n >= 1000 { 3 } else { runs }, || {
                std::hint::black_box(triangulate_maxmin(&pts).ok());
            }))
        } else {
            "skipped".to_owned()
        };
        let del = improve(witness.clone());
        eprintln!(
            "n={n}: min angle witness {:.4}°, delaunay {:.4}°",
            witness.min_angle().to_degrees(),
            del.min_angle().to_degrees()
        );
        println!(
            "| {n} | {} | {} | {} | {:.2} MB | {:.1} MB |",
            fmt_ms(t_dp),
            fmt_ms(t_flip),
            t_mm,
            dp_memory_bytes(n) as f64 / 1e6,
            maxmin_memory_bytes(n) as f64 / 1e6
        );
    }
}
