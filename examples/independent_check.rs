//! Every key segment of a set of morphs, checked by the independent exact
//! checker (`testkit::exact_check`, rational arithmetic, no code shared
//! with `immerse::certify`) and by the certificate, for the closing figures
//! of the certified-keyframes work (docs/design.md §13). A long run, not a
//! test: the checker's rational arithmetic takes milliseconds a segment.
//!
//! ```text
//! cargo run --release --example independent_check -- --set motion
//! cargo run --release --example independent_check -- --set reference
//! cargo run --release --example independent_check -- --set stress --seed 0xbee5 --pairs 200 [--start 0] [--every 1]
//! ```
//!
//! `--every N` checks every Nth segment of each morph (and always its
//! first and last); the certificate takes every one. Prints one line per
//! morph that either rejects, and the totals.

use immerse::certify::{Player, certify_segment};
use immerse::morph::{CurveMorphOptions, Tween};
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;
use testkit::exact_check::first_invalid;
use testkit::{pairs, stress};

/// What one morph's key segments got.
#[derive(Default)]
struct Tally {
    segments: usize,
    checked: usize,
    /// Segments the independent checker rejects.
    rejected: Vec<usize>,
    /// Segments the certificate does not certify.
    uncertified: Vec<usize>,
    /// Seconds in the independent checker.
    seconds: f64,
}

fn check(a: &[immerse::Point], b: &[immerse::Point], every: usize) -> Result<Tally, String> {
    let tween = Tween::new(a, b, &CurveMorphOptions::DEFAULT).map_err(|e| e.to_string())?;
    let keys = tween.keyframes();
    let last = keys.len().saturating_sub(2);
    let mut tally = Tally {
        segments: keys.len().saturating_sub(1),
        ..Tally::default()
    };
    for (k, w) in keys.windows(2).enumerate() {
        let certified = certify_segment(&w[0].points, &w[1].points, &w[0].triangles, Player::Exact)
            .is_ok_and(|r| r.is_certified());
        if !certified {
            tally.uncertified.push(k);
        }
        if k % every == 0 || k == last {
            let started = Instant::now();
            let bad = first_invalid(&w[0].points, &w[1].points, &w[0].triangles);
            tally.seconds += started.elapsed().as_secs_f64();
            tally.checked += 1;
            if bad.is_some() {
                tally.rejected.push(k);
            }
        }
    }
    Ok(tally)
}

fn flag(args: &[String], name: &str) -> Option<String> {
    let i = args.iter().position(|a| a == name)?;
    args.get(i + 1).cloned()
}

fn number(s: &str) -> u64 {
    match s.strip_prefix("0x") {
        Some(hex) => u64::from_str_radix(hex, 16).expect("a hexadecimal number"),
        None => s.parse().expect("a number"),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let set = flag(&args, "--set").unwrap_or_else(|| "motion".into());
    let every = flag(&args, "--every").map_or(1, |s| number(&s).max(1) as usize);
    let list: Vec<pairs::CurvePair> = match set.as_str() {
        "motion" | "reference" => pairs::read_set(&set).unwrap_or_default(),
        "stress" => {
            let seed = flag(&args, "--seed").map_or(0xbee5, |s| number(&s));
            let first = flag(&args, "--start").map_or(0, |s| number(&s));
            let count = flag(&args, "--pairs").map_or(100, |s| number(&s));
            (first..first + count)
                .map(|i| {
                    let p = stress::pair(seed, i);
                    (format!("stress {seed:#x} pair {i}"), p.source, p.target)
                })
                .collect()
        }
        other => panic!("unknown set {other}: motion, reference or stress"),
    };
    let started = Instant::now();
    let done = AtomicUsize::new(0);
    let total = list.len();
    let results: Vec<(String, Result<Tally, String>)> = list
        .into_par_iter()
        .map(|(name, a, b)| {
            let r = check(&a, &b, every);
            let k = done.fetch_add(1, Ordering::Relaxed) + 1;
            if k % 25 == 0 {
                eprintln!(
                    "{k}/{total} morphs, {:.0} s",
                    started.elapsed().as_secs_f64()
                );
            }
            (name, r)
        })
        .collect();
    let (mut segments, mut checked, mut rejected, mut uncertified, mut errors) = (0, 0, 0, 0, 0);
    let mut seconds = 0.0;
    for (name, r) in &results {
        match r {
            Err(e) => {
                errors += 1;
                println!("{name}: no morph: {e}");
            }
            Ok(t) => {
                segments += t.segments;
                checked += t.checked;
                rejected += t.rejected.len();
                uncertified += t.uncertified.len();
                seconds += t.seconds;
                if !t.rejected.is_empty() || !t.uncertified.is_empty() {
                    println!(
                        "{name}: rejected by the checker {:?}, not certified {:?}",
                        t.rejected, t.uncertified
                    );
                }
            }
        }
    }
    println!(
        "{set}: {} morphs ({errors} without a morph); key segments {segments}, certified {}, \
         checked independently {checked} (every {every}), rejected {rejected}; \
         checker {seconds:.0} s in all, wall {:.0} s",
        results.len(),
        segments - uncertified,
        started.elapsed().as_secs_f64()
    );
}
