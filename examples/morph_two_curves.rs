//! The shortest path through the library: read two curves, morph one into
//! the other, check every frame, write the frames as JSON.
//!
//! Run with `cargo run --release --example morph_two_curves [-- OUT.json]`
//! (default `morph.json` in the current folder; an existing file is
//! replaced).

use immerse::Curve;
use immerse::morph::{CurveMorphOptions, Tween};
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let curves = Path::new(env!("CARGO_MANIFEST_DIR")).join("curves");
    let a = Curve::from_path(curves.join("ribbon-curl.svg"))?;
    let b = Curve::from_path(curves.join("tail-loop.svg"))?;
    let fractions: Vec<f64> = (0..=30).map(|i| f64::from(i) / 30.0).collect();
    let tween = Tween::new(&a.points, &b.points, &CurveMorphOptions::DEFAULT)?;
    let morph = tween.morph(&fractions)?;
    let report = tween.report();
    assert!(morph.frames.iter().all(|f| f.is_immersion()));
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "morph.json".to_string());
    std::fs::write(&out, serde_json::to_string(&morph)?)?;
    println!(
        "{} frames of {} vertices ({} flips), every one an immersed disk; wrote {out}",
        morph.frames.len(),
        report.n,
        report.flips
    );
    Ok(())
}
