//! Prints the pacing and the keys of every pair of
//! `curves/motion-pairs.list` (docs/design.md §12): with linear easing at
//! 320 frames, the largest per-frame mean vertex step over the median, the
//! largest per-frame single-vertex step over the median of those, the key
//! count and whether every segment between keys is certified; then the
//! speed ratios at the keys of `immerse animate`'s example sequence.
//!
//! Run with `cargo run --release --example pacing [-- --frames N]`.

use immerse::Curve;
use immerse::morph::{CurveMorphOptions, Tween};
use immerse::sequence::{Key, Sequence, SequenceOptions, Timing, key_speeds};
use std::path::Path;

use testkit::pacing;
use testkit::pairs;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let frames: usize = args
        .iter()
        .position(|a| a == "--frames")
        .and_then(|i| args.get(i + 1))
        .map_or(Ok(320), |f| f.parse())?;
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("curves");
    println!(
        "| pair | n | keys | certified | mean step max/median | largest step max/median | plan ms |"
    );
    println!("|---|---|---|---|---|---|---|");
    let (mut worst_mean, mut worst_max) = (0.0f64, 0.0f64);
    let mut keys_total = 0;
    for (a, b) in pairs::motion_pairs() {
        let ca = Curve::from_path(dir.join(&a))?;
        let cb = Curve::from_path(dir.join(&b))?;
        let start = std::time::Instant::now();
        let tween = Tween::new(&ca.points, &cb.points, &CurveMorphOptions::DEFAULT)?;
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let p = pacing::measure(&tween, frames)?;
        worst_mean = worst_mean.max(p.mean_ratio);
        worst_max = worst_max.max(p.max_ratio);
        keys_total += tween.key_count();
        println!(
            "| {a} → {b} | {} | {} | {} | {:.3} | {:.3} | {ms:.0} |",
            tween.vertex_count(),
            tween.key_count(),
            if tween.is_certified() { "yes" } else { "no" },
            p.mean_ratio,
            p.max_ratio,
        );
    }
    println!(
        "\nworst: mean step {worst_mean:.3} (aim ≤ 1.5), largest step {worst_max:.3} (aim ≤ 2); {keys_total} keys in all"
    );
    // The sequence of the pacing report of `immerse animate`.
    let names = [
        "spiral-strip-540deg-n120.json",
        "blob-n64.json",
        "immersed-disk-n40.json",
        "spiral-strip-540deg-n120.json",
    ];
    let keys: Vec<Key> = names
        .iter()
        .map(|f| Ok(Key::new(*f, Curve::from_path(dir.join(f))?.points)))
        .collect::<Result<_, immerse::curve::CurveError>>()?;
    let seq = Sequence::new(&keys, &[], &SequenceOptions::DEFAULT)?;
    for count in [91, frames] {
        let schedule = seq.schedule(&Timing::new(keys.len()).with_frames(Some(count)))?;
        let morph = seq.frames(&schedule)?;
        let speeds = key_speeds(&morph.frames, &schedule);
        let ratios: Vec<String> = speeds
            .iter()
            .map(|s| format!("key {} {:.3}", s.key, s.ratio))
            .collect();
        println!(
            "animate {} at {count} frames: {} sequence keyframes; speed ratio at {}",
            names.join(" "),
            seq.keyframes().len(),
            ratios.join(", ")
        );
    }
    Ok(())
}
