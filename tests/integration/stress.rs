//! Stress pairs: random pairs of self-overlapping
//! curves — thin wedges and strips (height down to 1e-9 of the length),
//! collinear runs, edges down to 1e-12 of the perimeter, scales 1e-6 to
//! 1e6 — morphed with every `--quality`, `--counts`, intermediate and
//! correspondence; every frame must pass the exact immersion check and the
//! end frames must be the inputs.
//!
//! The generators and the pair driver live in `testkit/src/stress.rs`,
//! shared with the long run (`cargo run --release --example stress --
//! --pairs 10000`). The short run here is
//! [`stress_short_random_pairs_all_morph`]; shrunk failures found by the
//! long run are kept in `tests/stress-regressions/` and replayed by
//! [`stress_regressions_all_morph`].

use testkit::Rng;
use testkit::stress as harness;

use harness::{
    DEFAULT_SEED, Generator, Pair, generate, pair, read_curve, regression_files, run_pair,
    run_pairs, thinnest_degrees,
};
use immerse::geom::polygon::is_simple;
use immerse::geom::{Orientation, Point, orient};

/// Pairs of the short run: a few seconds in release on 2 cores; fewer in
/// the debug-profile pass, where the library's debug assertions run.
const SHORT_PAIRS: u64 = if cfg!(debug_assertions) { 24 } else { 240 };

/// Curves drawn per generator by the generator test (enough that each
/// generator's extremes show up for any seed).
const PER_GENERATOR: usize = 40;

fn perimeter(p: &[Point]) -> f64 {
    (0..p.len())
        .map(|i| (p[(i + 1) % p.len()] - p[i]).length())
        .sum()
}

fn shortest_edge(p: &[Point]) -> f64 {
    (0..p.len())
        .map(|i| (p[(i + 1) % p.len()] - p[i]).length())
        .fold(f64::INFINITY, f64::min)
}

fn extent(p: &[Point]) -> f64 {
    let (lo, hi) = testkit::shapes::bounds(p);
    (hi - lo).max_element()
}

/// Area over squared diameter: about 1e-9 for a strip of height 1e-9 of
/// its length.
fn thinness(p: &[Point]) -> f64 {
    let area = immerse::geom::polygon::signed_area(p).abs();
    area / (extent(p) * extent(p))
}

/// The generators make what they promise: genuinely self-overlapping
/// curves (read back as files are), rarely discarded, at every scale from
/// 1e-6 to 1e6, with the advertised thinness, short edges, collinear runs,
/// crossings and sizes.
#[test]
fn stress_generators_make_self_overlapping_curves() {
    let mut rng = Rng::stream(DEFAULT_SEED, 0xcafe);
    let mut total_discards = 0usize;
    let mut total = 0usize;
    for g in Generator::ALL {
        let mut discards = 0;
        let mut curves = Vec::new();
        for _ in 0..PER_GENERATOR {
            let (p, d) = generate(&mut rng, g);
            discards += d.len();
            curves.push(p.unwrap_or_else(|| panic!("{}: 40 discards in a row: {d:?}", g.as_str())));
        }
        total_discards += discards;
        total += discards + curves.len();
        assert!(
            discards * 5 <= PER_GENERATOR,
            "{}: {discards} discards for {PER_GENERATOR} curves",
            g.as_str()
        );
        for p in &curves {
            // Already read and triangulated by the generator; once more
            // here, as a user's file.
            assert_eq!(read_curve("again", p).as_ref(), Ok(p), "{}", g.as_str());
            assert!(
                p.len() >= 3 && p.len() <= 202,
                "{}: {} points",
                g.as_str(),
                p.len()
            );
        }
        let sizes: Vec<f64> = curves.iter().map(|p| extent(p)).collect();
        let (lo, hi) = sizes
            .iter()
            .fold((f64::INFINITY, 0f64), |(l, h), &s| (l.min(s), h.max(s)));
        assert!(
            lo < 1e-3 && hi > 1e3,
            "{}: sizes only from {lo:e} to {hi:e}",
            g.as_str()
        );
        let min_of =
            |f: &dyn Fn(&[Point]) -> f64| curves.iter().map(|p| f(p)).fold(f64::INFINITY, f64::min);
        let any = |f: &dyn Fn(&[Point]) -> bool| curves.iter().any(|p| f(p));
        match g {
            Generator::Wedge => {
                assert!(min_of(&thinness) < 1e-8, "{}", min_of(&thinness));
                assert!(any(&|p| p.len() == 3));
                assert!(any(&|p| p.len() > 20));
            }
            Generator::Strip | Generator::ThinSpiral | Generator::ThinCurl => {
                // Thinness is width/length times length²/extent² (up to
                // about 30 for a long curled strip): 1e-7 needs a width
                // below about 1e-7 of the length, a quarter of the draws.
                assert!(
                    min_of(&thinness) < 1e-7,
                    "{}: {}",
                    g.as_str(),
                    min_of(&thinness)
                );
            }
            Generator::GluedThin => {
                assert!(
                    min_of(&|p| thinnest_degrees(p)) < 1e-5,
                    "{}",
                    min_of(&|p| thinnest_degrees(p))
                );
            }
            Generator::ShortEdge => {
                let r = min_of(&|p| shortest_edge(p) / perimeter(p));
                assert!(r < 1e-11, "shortest edge only {r:e} of the perimeter");
            }
            Generator::Collinear => {
                let collinear_triples = |p: &[Point]| {
                    let n = p.len();
                    (0..n)
                        .filter(|&i| {
                            orient(p[i], p[(i + 1) % n], p[(i + 2) % n]) == Orientation::Collinear
                        })
                        .count()
                };
                assert!(
                    curves.iter().filter(|p| collinear_triples(p) >= 2).count() * 2 > curves.len(),
                    "most collinear curves have exactly collinear runs"
                );
            }
            Generator::Spiral | Generator::Curl | Generator::Glued => {
                let crossing = curves.iter().filter(|p| !is_simple(p)).count();
                assert!(
                    crossing * 3 > curves.len(),
                    "{}: only {crossing} cross themselves",
                    g.as_str()
                );
            }
            Generator::Blob => assert!(curves.iter().all(|p| is_simple(p))),
        }
        if matches!(g, Generator::ThinSpiral | Generator::ThinCurl) {
            assert!(
                any(&|p| !is_simple(p)),
                "{}: none crosses itself",
                g.as_str()
            );
        }
    }
    assert!(
        total_discards * 20 <= total,
        "{total_discards} of {total} generated curves discarded"
    );
}

/// A pair depends on the seed and its index only.
#[test]
fn stress_pairs_are_reproducible_from_their_index() {
    let a = pair(DEFAULT_SEED, 12345);
    let _ = pair(DEFAULT_SEED, 7);
    let b = pair(DEFAULT_SEED, 12345);
    assert_eq!(a.source, b.source);
    assert_eq!(a.target, b.target);
    assert_eq!(a.options, b.options);
    assert_ne!(pair(DEFAULT_SEED + 1, 12345).source, a.source);
}

/// The regression-file form reads back to the same pair, bit for bit.
#[test]
fn stress_pair_json_round_trip() {
    for i in 0..20 {
        let p = pair(DEFAULT_SEED, i);
        let text = p.to_json(Some("message")).to_string();
        let q = Pair::from_json(&text).unwrap();
        assert_eq!(p.source, q.source, "pair {i}");
        assert_eq!(p.target, q.target, "pair {i}");
        assert_eq!(p.options, q.options, "pair {i}");
        assert_eq!(p.generators, q.generators, "pair {i}");
        assert_eq!(p.seed, q.seed, "pair {i}");
    }
}

/// THE SHORT STRESS RUN: random pairs from every
/// generator under every option; every pair must morph, every frame must
/// pass the exact check and the end frames must be the inputs. All
/// failures are collected and printed (with the pairs as JSON, ready for
/// `tests/stress-regressions/`) before the test fails.
///
/// Reproduce or shrink a failure with
/// `cargo run --release --example stress -- --pair INDEX --shrink`.
#[test]
fn stress_short_random_pairs_all_morph() {
    let start = std::time::Instant::now();
    let summary = run_pairs(DEFAULT_SEED, 0, SHORT_PAIRS, &|_, _| {});
    let secs = start.elapsed().as_secs_f64();
    eprintln!(
        "stress (short): {} pairs in {secs:.1} s; {}",
        summary.total(),
        summary.headline()
    );
    assert!(
        summary.discard_rate() < 0.05,
        "{:.1}% of generated curves discarded",
        100.0 * summary.discard_rate()
    );
    assert!(
        summary.failures.is_empty(),
        "stress (short): {} of {} pairs failed (seed {DEFAULT_SEED:#x})\n{}",
        summary.failures.len(),
        summary.total(),
        summary.report(12)
    );
}

/// Every shrunk failure kept in `tests/stress-regressions/` morphs, with
/// every frame exactly valid and the end frames the inputs.
#[test]
fn stress_regressions_all_morph() {
    let files = regression_files();
    assert!(!files.is_empty(), "tests/stress-regressions/ holds no case");
    let mut failures = Vec::new();
    for (path, p) in &files {
        let name = path.file_name().unwrap().to_string_lossy();
        match p {
            Err(e) => failures.push(format!("{name}: unreadable: {e}")),
            Ok(p) => {
                if let Err(f) = run_pair(p) {
                    failures.push(format!("{name}: {} ({})", f.message, p.options.label()));
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} regression pairs failed:\n{}",
        failures.len(),
        files.len(),
        failures.join("\n")
    );
}
