//! The stable fallback for libFuzzer: each target body runs over its seeds
//! (`seeds/TARGET/`, plus the project's `curves/` for the curve readers),
//! then over fixed-seed random bytes and mutations of the seeds. A panic
//! saves the input to `artifacts/TARGET/stable-…` and fails with its hex,
//! ready to become a regression test.
//!
//! `IMMERSE_FUZZ_ITERS` sets the number of generated inputs per target
//! (default 3000) and `IMMERSE_FUZZ_SEED` the generator's seed.

use super::*;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

fn manifest_dir() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn env_u64(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Files of `dir` (sorted), or of `dir` filtered by extension.
fn files(dir: &Path, ext: Option<&str>) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut out: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_file())
        .filter(|p| ext.is_none_or(|x| p.extension().is_some_and(|e| e == x)))
        .collect();
    out.sort();
    out
}

fn run_one(target: &str, body: fn(&[u8]), input: &[u8]) {
    if catch_unwind(AssertUnwindSafe(|| body(input))).is_ok() {
        return;
    }
    let dir = manifest_dir().join("artifacts").join(target);
    let hash = input
        .iter()
        .fold(0xcbf2_9ce4_8422_2325_u64, |h, &b| {
            (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3)
        });
    let path = dir.join(format!("stable-{hash:016x}"));
    let saved = std::fs::create_dir_all(&dir)
        .and_then(|()| std::fs::write(&path, input))
        .map_or_else(|e| format!("(not saved: {e})"), |()| path.display().to_string());
    let hex: String = input.iter().map(|b| format!("{b:02x}")).collect();
    panic!("{target} panicked on {} bytes, saved to {saved}; hex {hex}", input.len());
}

/// Runs `body` over the seeds, then random and mutated inputs.
fn drive(target: &str, body: fn(&[u8]), extra_seeds: &[PathBuf]) -> usize {
    let mut seeds: Vec<Vec<u8>> = files(&manifest_dir().join("seeds").join(target), None)
        .iter()
        .chain(extra_seeds)
        .map(|p| std::fs::read(p).expect("seed readable"))
        .collect();
    seeds.push(Vec::new());
    for s in &seeds {
        run_one(target, body, s);
    }
    let iters = env_u64("IMMERSE_FUZZ_ITERS", 3000);
    let mut rng = Rng::new(env_u64("IMMERSE_FUZZ_SEED", 0x1e55_e5ed));
    for i in 0..iters {
        let input = if i % 4 == 0 {
            let len = rng.below(256);
            (0..len).map(|_| rng.next_u64() as u8).collect()
        } else {
            let seed = &seeds[rng.below(seeds.len())];
            mutate(seed, &mut rng)
        };
        run_one(target, body, &input);
    }
    seeds.len()
}

fn curves(ext: &str) -> Vec<PathBuf> {
    files(&manifest_dir().join("..").join("curves"), Some(ext))
}

#[test]
fn curve_json_stable() {
    let extra = curves("json");
    assert!(extra.len() > 10, "the project's JSON curves are seeds");
    drive("curve_json", curve_json, &extra);
}

#[test]
fn curve_text_stable() {
    let mut extra = curves("txt");
    extra.extend(curves("csv"));
    assert!(!extra.is_empty());
    drive("curve_text", curve_text, &extra);
}

#[test]
fn curve_svg_stable() {
    let extra = curves("svg");
    assert!(extra.len() > 5, "the project's SVG curves are seeds");
    drive("curve_svg", curve_svg, &extra);
}

#[test]
fn check_points_stable() {
    assert!(drive("check_points", check_points, &[]) > 1);
}

/// The driver can fail: a body that panics on some input is caught.
#[test]
fn the_driver_reports_a_panicking_body() {
    fn picky(data: &[u8]) {
        assert!(!data.contains(&b'Z'), "found a Z");
    }
    let caught = catch_unwind(|| drive("picky_selftest", picky, &[]));
    let msg = caught.expect_err("some input contains a Z");
    let msg = msg.downcast_ref::<String>().expect("a formatted message");
    assert!(msg.starts_with("picky_selftest panicked on"), "{msg}");
    let _ = std::fs::remove_dir_all(manifest_dir().join("artifacts").join("picky_selftest"));
}

/// The decoder produces each kind of coordinate and every count.
#[test]
fn points_from_covers_its_modes() {
    assert!(points_from(&[]).is_empty());
    let square = points_from(&[0, 4, 4, 4, 5, 4, 5, 5, 4, 5]);
    assert_eq!(square.len(), 4);
    assert_eq!(square[0], Point::new(0.0, 0.0));
    assert_eq!(square[2], Point::new(1.0, 1.0));
    let raw = points_from(&[2, 3, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff]);
    assert!(raw[0].x.is_nan());
    let near = points_from(&[3, 3, 5, 6, 5, 3]);
    assert_eq!(near[0].x, f64::from_bits(1.0f64.to_bits() + 3));
    assert_eq!(near[0].y, f64::from_bits(1.0f64.to_bits()));
    assert_eq!(points_from(&[1, 200]).len(), 200 % (MAX_FUZZ_POINTS + 1));
}
