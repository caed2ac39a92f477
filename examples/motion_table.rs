//! Measures motion on the pairs of `curves/motion-pairs.list`: for each
//! pair, the detour (mean vertex path length over the straight-line
//! distance under the best cyclic shift; 1 = straight lines), the unwind
//! (least total absolute turning of a frame over the smaller end's; below
//! 1 = overlaps undone and redone), flips, fallbacks and wall time, on the
//! 40 frames a morph writes.
//!
//! Run with `cargo run --release --example motion_table [-- OPTION...]`
//! where options are `--path P`, `--correspondence C`, `--intermediate I`
//! with the CLI's values, and `--reps K` (timing repetitions, median).

use immerse::Curve;
use immerse::frames::metrics;
use immerse::morph::{
    Correspondence, CurveMorphOptions, Intermediate, MorphOptions, ThirdVertexPath, morph_curves,
};
use std::path::Path;
use std::time::Instant;

#[path = "../tests/common/pairs.rs"]
mod pairs;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let mut options = CurveMorphOptions::DEFAULT;
    if let Some(p) = value("--path") {
        let path: ThirdVertexPath = p.parse()?;
        options = options.with_morph(MorphOptions::DEFAULT.with_path(path));
    }
    if let Some(c) = value("--correspondence") {
        let rule = Correspondence::ALL
            .into_iter()
            .find(|r| r.as_str() == c)
            .ok_or_else(|| format!("unknown correspondence {c}"))?;
        options = options.with_correspondence(rule);
    }
    if let Some(i) = value("--intermediate") {
        options = options.with_intermediate(match i.as_str() {
            "disk" => Intermediate::Disk,
            _ => Intermediate::Target,
        });
    }
    let reps: usize = value("--reps").map_or(Ok(1), |r| r.parse())?;
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("curves");
    let fractions: Vec<f64> = (0..40).map(|i| f64::from(i) / 39.0).collect();
    println!(
        "| pair | n | detour | winding reference | unwind | flips | path | fallbacks | valid | time (ms) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let (mut detours, mut unwinds, mut total_ms) = (Vec::new(), Vec::new(), 0.0);
    for (a, b) in pairs::motion_pairs() {
        let ca = Curve::from_path(dir.join(&a))?;
        let cb = Curve::from_path(dir.join(&b))?;
        let mut times = Vec::new();
        let mut result = None;
        for _ in 0..reps.max(1) {
            let start = Instant::now();
            let r = morph_curves(&ca.points, &cb.points, &fractions, &options);
            times.push(start.elapsed().as_secs_f64() * 1e3);
            result = Some(r);
        }
        times.sort_by(f64::total_cmp);
        let ms = times[times.len() / 2];
        total_ms += ms;
        match result.expect("at least one repetition") {
            Ok((report, morph)) => {
                let m = metrics(&morph.frames);
                detours.push(m.detour);
                unwinds.push(m.unwind);
                println!(
                    "| {a} → {b} | {} | {:.2} | {:.2} | {:.2} | {} | {} | {} | {}/{} | {ms:.1} |",
                    report.n,
                    m.detour,
                    winding_reference(&morph.frames, fractions.len()),
                    m.unwind,
                    report.flips,
                    morph.path_name(),
                    morph.fallbacks.len(),
                    m.valid_frames,
                    m.frames,
                );
            }
            Err(e) => println!("| {a} → {b} | | | | | | | error: {e} | | {ms:.1} |"),
        }
    }
    detours.sort_by(f64::total_cmp);
    let median = detours.get(detours.len() / 2).copied().unwrap_or(f64::NAN);
    let max = detours.last().copied().unwrap_or(f64::NAN);
    let min_unwind = unwinds.iter().copied().fold(f64::INFINITY, f64::min);
    let below = unwinds.iter().filter(|&&u| u < 0.9).count();
    println!(
        "\n{} pairs: detour median {median:.2}, max {max:.2}; unwind min {min_unwind:.2} ({below} below 0.9); total time {total_ms:.0} ms",
        detours.len()
    );
    Ok(())
}

/// The detour of the natural winding motion between the same two end
/// frames, with the same vertex matching (`frames` of them, the same
/// measure): each vertex's angle about its frame's vertex mean (unwound
/// along the curve; the last frame's shifted by the whole turns that move
/// the vertices least) and its distance from it interpolated linearly,
/// about the mean interpolated linearly. Not necessarily an immersion: a
/// reference for what winding costs, not a morph.
fn winding_reference(morph: &[immerse::frames::Frame], frames: usize) -> f64 {
    use immerse::Point;
    use std::f64::consts::{PI, TAU};
    let (Some(first), Some(last)) = (morph.first(), morph.last()) else {
        return f64::NAN;
    };
    let (a, b) = (&first.points, &last.points);
    if a.len() != b.len() || a.is_empty() {
        return f64::NAN;
    }
    let mean = |p: &[Point]| p.iter().copied().sum::<Point>() / p.len() as f64;
    let (c0, c1) = (mean(a), mean(b));
    let unwound = |p: &[Point], c: Point| -> Vec<f64> {
        let mut out: Vec<f64> = Vec::with_capacity(p.len());
        for q in p {
            let d = (*q - c).to_angle();
            let next = out
                .last()
                .map_or(d, |&prev| prev + (d - prev + PI).rem_euclid(TAU) - PI);
            out.push(next);
        }
        out
    };
    let (ua, ub) = (unwound(a, c0), unwound(b, c1));
    let weight = |i: usize| (a[i] - c0).length() + (b[i] - c1).length();
    let moved = |k: f64| -> f64 {
        (0..a.len())
            .map(|i| (ub[i] + k * TAU - ua[i]).abs() * weight(i))
            .sum()
    };
    let k = (-8..=8)
        .map(f64::from)
        .min_by(|x, y| moved(*x).total_cmp(&moved(*y)))
        .unwrap_or(0.0);
    let reference: Vec<immerse::frames::Frame> = (0..frames)
        .map(|j| {
            let t = j as f64 / (frames - 1).max(1) as f64;
            let c = c0.lerp(c1, t);
            let points = (0..a.len())
                .map(|i| {
                    let angle = ua[i] + (ub[i] + k * TAU - ua[i]) * t;
                    let r = (a[i] - c0).length() * (1.0 - t) + (b[i] - c1).length() * t;
                    c + Point::from_angle(angle) * r
                })
                .collect();
            immerse::frames::Frame {
                t,
                points,
                triangles: Vec::new(),
            }
        })
        .collect();
    immerse::frames::detour(&reference)
}
