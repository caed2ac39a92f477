//! Peer comparison against flubber (npm) and a plain linear interpolation:
//! the fraction of in-between frames that are still self-overlapping,
//! judged by immerse's own exact checker, and the wall time of each.
//!
//! Normally driven by `scripts/peer-compare.sh`, which runs, in order:
//!
//! - `cargo run --release --example peer_check -- export DIR`: writes
//!   `DIR/pair-NN.json` for each pair, `{"name", "from": {"points"},
//!   "to": {"points"}}`, with the cleaned, oriented (counter-clockwise,
//!   y up) points immerse reads from `curves/` (SVGs included);
//! - `node scripts/peer/flubber_frames.mjs DIR`: writes
//!   `DIR/flubber-NN.json`, `{"frames": [[[x, y], ...], ...], "ms"}`;
//! - `cargo run --release --example peer_check -- DIR`: judges flubber's
//!   frames, builds and judges the linear interpolation and immerse's
//!   morph at the same [`FRAMES`] values of t, and prints a markdown table.
//!
//! A frame counts as self-overlapping when [`immerse::Curve::from_points`]
//! cleans it (an error counts as not self-overlapping) and
//! [`immerse::triangulate`] finds an immersed disk for the
//! cleaned points. Cleaning reverses a clockwise frame, so a frame that is
//! self-overlapping only after reversal (turned inside out relative to the
//! source) is counted separately as *flipped*.

use immerse::Curve;
use immerse::Point;
use immerse::correspond::equalize;
use immerse::morph::CurveMorphOptions;
use immerse::{NotSelfOverlapping, triangulate};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::time::Instant;
use testkit::morph_pair;

/// Frames per pair, at t = i / (FRAMES − 1).
const FRAMES: usize = 41;

/// Timed repetitions per method; the table shows the fastest.
const REPEATS: usize = 3;

use testkit::pairs::reference_pairs;

#[derive(Serialize, Deserialize)]
struct Ring {
    points: Vec<[f64; 2]>,
}

#[derive(Serialize, Deserialize)]
struct Pair {
    name: String,
    from: Ring,
    to: Ring,
}

#[derive(Deserialize)]
struct FlubberFrames {
    frames: Vec<Vec<[f64; 2]>>,
    ms: f64,
}

fn to_ring(points: &[Point]) -> Ring {
    Ring {
        points: points.iter().map(|p| [p.x, p.y]).collect(),
    }
}

fn to_points(ring: &[[f64; 2]]) -> Vec<Point> {
    ring.iter().map(|&[x, y]| Point::new(x, y)).collect()
}

/// What the exact checker says about one frame.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Verdict {
    /// Self-overlapping with the source's orientation.
    SelfOverlapping,
    /// Self-overlapping only after cleaning reversed it: turned inside out.
    Flipped,
    /// Not self-overlapping: turning number 1, but no immersed disk.
    NoDisk,
    /// Not self-overlapping: cleaning failed, a cusp, or a turning
    /// number other than ±1.
    No,
}

fn judge(points: Vec<Point>, source_reversed: bool) -> Verdict {
    let Ok(curve) = Curve::from_points("frame", points) else {
        return Verdict::No;
    };
    match triangulate(&curve.points) {
        Err(NotSelfOverlapping::NoValidTriangulation) => return Verdict::NoDisk,
        Err(_) => return Verdict::No,
        Ok(_) => {}
    }
    if curve.reversed != source_reversed {
        Verdict::Flipped
    } else {
        Verdict::SelfOverlapping
    }
}

/// Counts of self-overlapping and flipped frames.
#[derive(Default)]
struct Tally {
    ok: usize,
    flipped: usize,
    no_disk: usize,
    frames: usize,
}

impl Tally {
    fn of(frames: impl IntoIterator<Item = Vec<Point>>, source_reversed: bool) -> Tally {
        let mut t = Tally::default();
        for f in frames {
            t.frames += 1;
            match judge(f, source_reversed) {
                Verdict::SelfOverlapping => t.ok += 1,
                Verdict::Flipped => {
                    t.ok += 1;
                    t.flipped += 1;
                }
                Verdict::NoDisk => t.no_disk += 1,
                Verdict::No => {}
            }
        }
        t
    }

    fn cell(&self) -> String {
        let pct = 100.0 * self.ok as f64 / self.frames.max(1) as f64;
        if self.flipped > 0 {
            format!(
                "{}/{} ({pct:.0}%; {} flipped)",
                self.ok, self.frames, self.flipped
            )
        } else {
            format!("{}/{} ({pct:.0}%)", self.ok, self.frames)
        }
    }
}

fn fractions() -> Vec<f64> {
    (0..FRAMES)
        .map(|i| i as f64 / (FRAMES - 1) as f64)
        .collect()
}

/// Vertex i ↔ i after [`equal_counts`] with [`Counts::Insert`], positions
/// (1 − t) a + t b.
fn linear(a: &[Point], b: &[Point], ts: &[f64]) -> Vec<Vec<Point>> {
    let (a, b) = equalize(a, b);
    ts.iter()
        .map(|&t| {
            a.iter()
                .zip(&b)
                .map(|(p, q)| *p * (1.0 - t) + *q * t)
                .collect()
        })
        .collect()
}

/// Runs `f` [`REPEATS`] times; the last result and the fastest time in ms.
fn timed<T>(mut f: impl FnMut() -> T) -> (T, f64) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..REPEATS {
        let start = Instant::now();
        let r = f();
        best = best.min(start.elapsed().as_secs_f64() * 1e3);
        out = Some(r);
    }
    (out.expect("REPEATS > 0"), best)
}

fn pair_path(dir: &Path, i: usize) -> PathBuf {
    dir.join(format!("pair-{i:02}.json"))
}

fn export(dir: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let curves = Path::new(env!("CARGO_MANIFEST_DIR")).join("curves");
    std::fs::create_dir_all(dir)?;
    let pairs = reference_pairs();
    for (i, (a, b)) in pairs.iter().enumerate() {
        let ca = Curve::from_path(curves.join(a))?;
        let cb = Curve::from_path(curves.join(b))?;
        let pair = Pair {
            name: format!("{a} → {b}"),
            from: to_ring(&ca.points),
            to: to_ring(&cb.points),
        };
        std::fs::write(pair_path(dir, i), serde_json::to_string(&pair)?)?;
    }
    eprintln!("wrote {} pairs to {}", pairs.len(), dir.display());
    Ok(())
}

fn compare(dir: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let ts = fractions();
    println!(
        "| pair | n | flubber n | flubber self-overlapping | linear self-overlapping | immerse self-overlapping | flubber ms | linear ms | immerse ms |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    let (mut sum_f, mut sum_l, mut sum_i) = (Tally::default(), Tally::default(), Tally::default());
    let (mut ms_f, mut ms_l, mut ms_i) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0.. {
        let path = pair_path(dir, i);
        if !path.exists() {
            break;
        }
        let pair: Pair = serde_json::from_str(&std::fs::read_to_string(&path)?)?;
        let fl_path = dir.join(format!("flubber-{i:02}.json"));
        let fl: FlubberFrames = serde_json::from_str(
            &std::fs::read_to_string(&fl_path)
                .map_err(|e| format!("{}: {e}", fl_path.display()))?,
        )?;
        if fl.frames.len() != FRAMES {
            return Err(format!(
                "{}: {} frames, expected {FRAMES}",
                fl_path.display(),
                fl.frames.len()
            )
            .into());
        }
        let a = to_points(&pair.from.points);
        let b = to_points(&pair.to.points);
        // The exported points are already cleaned and oriented; cleaning
        // them again must not reverse them.
        let source_reversed = Curve::from_points("source", a.clone())?.reversed;
        let flubber_n = fl.frames[0].len();
        for end in [0, FRAMES - 1] {
            if matches!(
                judge(to_points(&fl.frames[end]), source_reversed),
                Verdict::No | Verdict::NoDisk
            ) {
                eprintln!(
                    "{}: flubber's frame {end} is not self-overlapping",
                    pair.name
                );
            }
        }
        let tf = Tally::of(fl.frames.iter().map(|f| to_points(f)), source_reversed);
        let (lin, lin_ms) = timed(|| linear(&a, &b, &ts));
        let n = lin[0].len();
        let tl = Tally::of(lin, source_reversed);
        let (morph, imm_ms) = timed(|| morph_pair(&a, &b, &ts, &CurveMorphOptions::DEFAULT));
        let (_, morph) = morph.map_err(|e| format!("{}: {e}", pair.name))?;
        let ti = Tally::of(morph.frames.into_iter().map(|f| f.points), source_reversed);
        if ti.ok != ti.frames || ti.flipped != 0 {
            return Err(format!("{}: immerse produced a frame that fails", pair.name).into());
        }
        println!(
            "| {} | {n} | {flubber_n} | {} | {} | {} | {:.2} | {:.3} | {:.1} |",
            pair.name,
            tf.cell(),
            tl.cell(),
            ti.cell(),
            fl.ms,
            lin_ms,
            imm_ms
        );
        for (sum, t) in [(&mut sum_f, tf), (&mut sum_l, tl), (&mut sum_i, ti)] {
            sum.ok += t.ok;
            sum.flipped += t.flipped;
            sum.no_disk += t.no_disk;
            sum.frames += t.frames;
        }
        ms_f.push(fl.ms);
        ms_l.push(lin_ms);
        ms_i.push(imm_ms);
    }
    if ms_f.is_empty() {
        return Err(format!("no pair-NN.json in {}", dir.display()).into());
    }
    println!(
        "| **all {} pairs** (times: median) | | | {} | {} | {} | {:.2} | {:.3} | {:.1} |",
        ms_f.len(),
        sum_f.cell(),
        sum_l.cell(),
        sum_i.cell(),
        median(ms_f),
        median(ms_l),
        median(ms_i)
    );
    println!();
    println!(
        "| method | self-overlapping | not: turning number 1, no immersed disk | not: turning number ≠ 1, cusp or degenerate |"
    );
    println!("|---|---|---|---|");
    for (name, t) in [("flubber", sum_f), ("linear", sum_l), ("immerse", sum_i)] {
        println!(
            "| {name} | {} | {} | {} |",
            t.ok,
            t.no_disk,
            t.frames - t.ok - t.no_disk
        );
    }
    Ok(())
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.as_slice() {
        [cmd, dir] if cmd == "export" => export(Path::new(dir)),
        [dir] => compare(Path::new(dir)),
        _ => Err("usage: peer_check export DIR | peer_check DIR".into()),
    }
}
