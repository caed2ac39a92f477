//! The measures of motion a viewer sees (docs/design.md §7c) on three sets
//! of pairs: continuity (the largest single-vertex step at 40, 320 and
//! 2,560 frames), spikes (longest edge), area range, angle ratio,
//! as-rigid-as-possible distortion, detour and unwind (at 320 frames).
//!
//! ```text
//! cargo run --release --example motion_view -- [--set motion|reference|stress]
//!     [--seed S] [--start I] [--pairs N] [--path P] [--correspondence C] [--rows] [--failures]
//!     [--classify]
//! ```
//!
//! `--set stress` draws pairs `I..I+N` of the stress generators with seed
//! `S` and morphs them at the default options. `--rows` prints one row per
//! pair; `--failures` only the pairs that miss a gate. `--classify` gives
//! every key segment left uncertified to `certify::certify_motion` (the
//! search of `immerse certify`: any triangulations, piece by piece, up to
//! 64) and counts those it finds invalid, certifies and leaves undecided.

use immerse::frames::{Frame, detour, unwind, view_measures};
use immerse::morph::{CurveMorphOptions, MorphOptions, ThirdVertexPath, Tween};
use rayon::prelude::*;
use std::time::Instant;

use testkit::pairs;
use testkit::stress as harness;

/// One pair's measures.
#[derive(Clone, Debug)]
struct Row {
    name: String,
    n: usize,
    steps: [f64; 3],
    edge: f64,
    area: (f64, f64),
    angle: f64,
    distortion: f64,
    detour: f64,
    unwind: f64,
    ms: f64,
    path: String,
    /// Key segments, and those the certificate (docs/design.md §13)
    /// rejects when re-run on the keys as `Tween::keyframes` gives them.
    segments: usize,
    uncertified: usize,
    /// With `--classify`: the uncertified segments that
    /// `certify::certify_motion` (any triangulations, piece by piece)
    /// finds invalid, certifies, and leaves undecided.
    classified: [usize; 3],
    error: Option<String>,
}

impl Row {
    /// Whether the largest step shrinks at least 4× (or stays under 1 % of
    /// the diagonal) from 40 to 320 and from 320 to 2,560 frames.
    fn continuous(&self) -> bool {
        let ok = |a: f64, b: f64| b <= a / 4.0 || b < 0.01;
        ok(self.steps[0], self.steps[1]) && ok(self.steps[1], self.steps[2])
    }
    fn misses(&self) -> Vec<&'static str> {
        let mut m = Vec::new();
        if self.error.is_some() {
            m.push("error");
            return m;
        }
        if !self.continuous() {
            m.push("jump");
        }
        if self.edge > 2.0 {
            m.push("spike");
        }
        if self.area.0 < 0.8 {
            m.push("collapse");
        }
        if self.area.1 > 1.15 {
            m.push("balloon");
        }
        if self.detour > 3.0 {
            m.push("detour");
        }
        if self.unwind < 0.9 {
            m.push("unwind");
        }
        if self.uncertified > 0 {
            m.push("uncertified");
        }
        m
    }
}

fn fractions(k: usize) -> Vec<f64> {
    (0..k).map(|i| i as f64 / (k - 1) as f64).collect()
}

fn measure(
    name: String,
    a: &[immerse::Point],
    b: &[immerse::Point],
    options: &CurveMorphOptions,
    classify: bool,
) -> Row {
    let start = Instant::now();
    let mut row = Row {
        name,
        n: 0,
        steps: [f64::NAN; 3],
        edge: f64::NAN,
        area: (f64::NAN, f64::NAN),
        angle: f64::NAN,
        distortion: f64::NAN,
        detour: f64::NAN,
        unwind: f64::NAN,
        ms: 0.0,
        path: String::new(),
        segments: 0,
        uncertified: 0,
        classified: [0; 3],
        error: None,
    };
    let tween = match Tween::new(a, b, options) {
        Ok(t) => t,
        Err(e) => {
            row.error = Some(e.to_string());
            return row;
        }
    };
    row.ms = start.elapsed().as_secs_f64() * 1e3;
    row.n = tween.vertex_count();
    row.path = tween
        .report()
        .paths
        .iter()
        .map(|p| p.as_str())
        .collect::<Vec<_>>()
        .join("+");
    // Every key segment certified again, exactly, from the keys as
    // written (the triangulation of the segment is the first key's; a
    // flip key carries the one that follows).
    let keys = tween.keyframes();
    for w in keys.windows(2) {
        row.segments += 1;
        let certified = immerse::certify::certify_segment(
            &w[0].points,
            &w[1].points,
            &w[0].triangles,
            immerse::certify::Player::Exact,
        )
        .is_ok_and(|r| r.is_certified());
        if !certified {
            row.uncertified += 1;
            if classify {
                use immerse::certify::{MotionOptions, Verdict, certify_motion};
                let report = certify_motion(
                    &w[0].points,
                    &w[1].points,
                    &[&w[0].triangles, &w[1].triangles],
                    immerse::certify::Player::Exact,
                    MotionOptions { max_pieces: 64 },
                );
                row.classified[match report.verdict {
                    Verdict::Invalid { .. } => 0,
                    Verdict::Certified => 1,
                    Verdict::Undecided { .. } => 2,
                }] += 1;
            }
        }
    }
    let frames = |k: usize| -> Result<Vec<Frame>, String> {
        tween
            .morph(&fractions(k))
            .map(|m| m.frames)
            .map_err(|e| e.to_string())
    };
    for (i, k) in [40, 320, 2560].into_iter().enumerate() {
        match frames(k) {
            Ok(f) => {
                let Some(v) = view_measures(&f) else {
                    row.error = Some("no measures".into());
                    return row;
                };
                row.steps[i] = v.max_step;
                if k == 320 {
                    row.edge = v.edge_ratio;
                    row.area = (v.area_low, v.area_high);
                    row.angle = v.angle_ratio;
                    row.distortion = v.distortion;
                    row.detour = detour(&f);
                    row.unwind = unwind(&f);
                }
            }
            Err(e) => {
                row.error = Some(e);
                return row;
            }
        }
    }
    row
}

fn flag(args: &[String], name: &str) -> Option<String> {
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .cloned()
}

fn parse_u64(s: &str) -> u64 {
    match s.strip_prefix("0x") {
        Some(h) => u64::from_str_radix(h, 16).expect("a hex number"),
        None => s.parse().expect("a number"),
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.retain(|x| x.is_finite());
    v.sort_by(f64::total_cmp);
    if v.is_empty() {
        return f64::NAN;
    }
    v[v.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let set = flag(&args, "--set").unwrap_or_else(|| "motion".into());
    let classify = args.iter().any(|a| a == "--classify");
    let mut options = CurveMorphOptions::DEFAULT;
    if let Some(p) = flag(&args, "--path") {
        let path: ThirdVertexPath = p.parse().expect("a path name");
        options = options.with_morph(MorphOptions::DEFAULT.with_path(path));
    }
    if let Some(c) = flag(&args, "--correspondence") {
        use immerse::morph::Correspondence as C;
        let rule = match c.as_str() {
            "best" => C::Best,
            "identity" => C::Identity,
            "pivot" => C::Pivot,
            "min-flips" => C::MinFlips,
            "shape" => C::Shape,
            "outline" => C::Outline,
            "corners" => C::Corners,
            other => panic!("unknown correspondence {other}"),
        };
        options = options.with_correspondence(rule);
    }
    let start = Instant::now();
    let rows: Vec<Row> = match set.as_str() {
        "motion" | "reference" => pairs::read_set(&set)
            .unwrap_or_default()
            .into_iter()
            .map(|(name, a, b)| measure(name, &a, &b, &options, classify))
            .collect(),
        "stress" => {
            let seed = flag(&args, "--seed").map_or(0x5eed_2024, |s| parse_u64(&s));
            let first = flag(&args, "--start").map_or(0, |s| parse_u64(&s));
            let count = flag(&args, "--pairs").map_or(100, |s| parse_u64(&s));
            let done = std::sync::atomic::AtomicUsize::new(0);
            (first..first + count)
                .into_par_iter()
                .map(|i| {
                    let p = harness::pair(seed, i);
                    let g = |g: Option<harness::Generator>| g.map_or("?", |g| g.as_str());
                    let row = measure(
                        format!("{i} {} → {}", g(p.generators[0]), g(p.generators[1])),
                        &p.source,
                        &p.target,
                        &options,
                        classify,
                    );
                    let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                    if k % 50 == 0 {
                        eprintln!("{k}/{count} pairs, {:.0} s", start.elapsed().as_secs_f64());
                    }
                    row
                })
                .collect()
        }
        other => panic!("unknown set {other}"),
    };
    let show_rows = args.iter().any(|a| a == "--rows");
    let only_failures = args.iter().any(|a| a == "--failures");
    if show_rows || only_failures {
        println!(
            "| pair | n | step 40 | step 320 | step 2560 | edge | area low | area high | angle | distortion | detour | unwind | ms | path | misses |"
        );
        println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
        for r in &rows {
            let misses = r.misses();
            if only_failures && misses.is_empty() {
                continue;
            }
            println!(
                "| {} | {} | {:.4} | {:.4} | {:.4} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.0} | {} | {} |",
                r.name,
                r.n,
                r.steps[0],
                r.steps[1],
                r.steps[2],
                r.edge,
                r.area.0,
                r.area.1,
                r.angle,
                r.distortion,
                r.detour,
                r.unwind,
                r.ms,
                r.path,
                r.error.clone().unwrap_or_else(|| misses.join(" "))
            );
        }
    }
    let ok: Vec<&Row> = rows.iter().filter(|r| r.error.is_none()).collect();
    let count = |m: &str| rows.iter().filter(|r| r.misses().contains(&m)).count();
    let fold = |f: &dyn Fn(&Row) -> f64, init: f64, g: fn(f64, f64) -> f64| {
        ok.iter().map(|r| f(r)).fold(init, g)
    };
    println!(
        "{set}: {} pairs ({} errors); jumps {}; edge max {:.2} (> 2: {}); area [{:.2}, {:.2}] (collapse {}, balloon {}); angle ratio median {:.2}; distortion median {:.2} max {:.2}; detour median {:.2} max {:.2} (> 3: {}); unwind min {:.2} (< 0.9: {}); key segments {} ({} uncertified, on {} pairs); planning {:.0} ms in all; wall {:.0} s",
        rows.len(),
        count("error"),
        count("jump"),
        fold(&|r| r.edge, 0.0, f64::max),
        count("spike"),
        fold(&|r| r.area.0, f64::INFINITY, f64::min),
        fold(&|r| r.area.1, 0.0, f64::max),
        count("collapse"),
        count("balloon"),
        median(ok.iter().map(|r| r.angle).collect()),
        median(ok.iter().map(|r| r.distortion).collect()),
        fold(&|r| r.distortion, 0.0, f64::max),
        median(ok.iter().map(|r| r.detour).collect()),
        fold(&|r| r.detour, 0.0, f64::max),
        count("detour"),
        fold(&|r| r.unwind, f64::INFINITY, f64::min),
        count("unwind"),
        ok.iter().map(|r| r.segments).sum::<usize>(),
        ok.iter().map(|r| r.uncertified).sum::<usize>(),
        count("uncertified"),
        ok.iter().map(|r| r.ms).sum::<f64>(),
        start.elapsed().as_secs_f64()
    );
    if classify {
        let sum = |k: usize| ok.iter().map(|r| r.classified[k]).sum::<usize>();
        println!(
            "uncertified segments through certify_motion (up to 64 pieces): {} invalid, {} certified piece by piece, {} undecided",
            sum(0),
            sum(1),
            sum(2)
        );
    }
}
