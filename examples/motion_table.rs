//! Measures motion on the pairs of `curves/motion-pairs.list`: for each
//! pair, the detour (mean vertex path length over the straight-line
//! distance under the best cyclic shift; 1 = straight lines), the unwind
//! (least total absolute turning of a frame over the smaller end's; below
//! 1 = overlaps undone and redone), flips, fallbacks and wall time, on the
//! 40 frames a morph writes; and, untimed, the other measures of
//! docs/design.md §7c: the largest single-vertex step at 40, 320 and 2,560
//! frames (continuity), and at 320 frames the longest edge, the area
//! range, the smallest angle (each ÷ the ends') and the
//! as-rigid-as-possible distortion.
//!
//! Each row also gives the winding reference: the detour of the natural
//! winding motion between the same end frames (see [`winding_reference`]).
//!
//! Run with `cargo run --release --example motion_table [-- OPTION...]`
//! where options are `--path P`, `--correspondence C`, `--intermediate I`
//! with the CLI's values, and `--reps K` (timing repetitions, median);
//! `--by-option` prints a table for each option changed alone from the
//! defaults (and the earlier defaults) and a summary of them all
//! (docs/motion-by-option.md).

use immerse::Curve;
use immerse::frames::{metrics, view_measures};
use immerse::morph::{
    Correspondence, CurveMorphOptions, Intermediate, MorphOptions, ThirdVertexPath, Tween,
};
use std::path::Path;
use std::time::Instant;
use testkit::morph_pair;

use testkit::pairs;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let reps: usize = flag(&args, "--reps").map_or(Ok(1), |r| r.parse())?;
    if !args.iter().any(|a| a == "--by-option") {
        let timing_only = args.iter().any(|a| a == "--timing-only");
        let summary = table(&options_of(&args)?, reps, timing_only)?;
        if timing_only {
            println!(
                "\n{} pairs: total time {:.0} ms",
                summary.pairs, summary.total_ms
            );
        } else {
            println!("\n{}", summary.line());
        }
        return Ok(());
    }
    // Every option changed alone from the defaults, then the earlier
    // defaults: a table per option and a summary table at the end.
    let sets: [&[&str]; 15] = [
        &[],
        &["--path", "straight"],
        &["--correspondence", "outline"],
        &["--correspondence", "corners"],
        &["--correspondence", "min-flips"],
        &["--correspondence", "pivot"],
        &["--correspondence", "shape"],
        &["--correspondence", "identity"],
        &["--path", "hybrid"],
        &["--path", "polar"],
        &["--path", "angle"],
        &["--path", "rotate-slide"],
        &["--path", "linear"],
        &["--intermediate", "disk"],
        &["--path", "hybrid", "--correspondence", "min-flips"],
    ];
    let mut rows = Vec::new();
    for set in sets {
        let label = if set.is_empty() {
            "defaults".to_string()
        } else {
            format!("`{}`", set.join(" "))
        };
        let owned: Vec<String> = set.iter().map(|s| s.to_string()).collect();
        println!("## {label}\n");
        let s = table(&options_of(&owned)?, reps, false)?;
        println!("\n{}\n", s.line());
        rows.push(format!(
            "| {label} | {:.2} | {:.2} | {:.2} | {} |",
            s.median, s.max, s.min_unwind, s.below
        ));
    }
    println!("## Summary\n");
    println!("| option | detour median | detour max | unwind min | pairs with unwind < 0.9 |");
    println!("|---|---|---|---|---|");
    for r in rows {
        println!("{r}");
    }
    Ok(())
}

/// The value after `name` in `args`.
fn flag(args: &[String], name: &str) -> Option<String> {
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .cloned()
}

/// The morph options that `args` (the CLI's `--path`, `--correspondence`
/// and `--intermediate`) set on the defaults.
fn options_of(args: &[String]) -> Result<CurveMorphOptions, Box<dyn std::error::Error>> {
    let mut options = CurveMorphOptions::DEFAULT;
    if let Some(p) = flag(args, "--path") {
        let path: ThirdVertexPath = p.parse()?;
        options = options.with_morph(MorphOptions::DEFAULT.with_path(path));
    }
    if let Some(c) = flag(args, "--correspondence") {
        let rule = Correspondence::ALL
            .into_iter()
            .find(|r| r.as_str() == c)
            .ok_or_else(|| format!("unknown correspondence {c}"))?;
        options = options.with_correspondence(rule);
    }
    if let Some(i) = flag(args, "--intermediate") {
        options = options.with_intermediate(match i.as_str() {
            "disk" => Intermediate::Disk,
            _ => Intermediate::Target,
        });
    }
    Ok(options)
}

/// One table's summary.
struct Summary {
    pairs: usize,
    median: f64,
    max: f64,
    min_unwind: f64,
    below: usize,
    total_ms: f64,
}

impl Summary {
    fn line(&self) -> String {
        format!(
            "{} pairs: detour median {:.2}, max {:.2}; unwind min {:.2} ({} below 0.9); total time {:.0} ms",
            self.pairs, self.median, self.max, self.min_unwind, self.below, self.total_ms
        )
    }
}

/// Prints the per-pair table for `options` (each morph timed `reps`
/// times, the median kept) and returns its summary.
fn table(
    options: &CurveMorphOptions,
    reps: usize,
    timing_only: bool,
) -> Result<Summary, Box<dyn std::error::Error>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("curves");
    let fractions: Vec<f64> = (0..40).map(|i| f64::from(i) / 39.0).collect();
    if timing_only {
        println!("| pair | n | time (ms) |\n|---|---|---|");
    } else {
        println!(
            "| pair | n | detour | winding reference | unwind | largest step 40 / 320 / 2,560 | edge | area | angle | distortion | flips | path | fallbacks | valid | time (ms) |"
        );
        println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    }
    let (mut detours, mut unwinds, mut total_ms) = (Vec::new(), Vec::new(), 0.0);
    let mut timed = 0;
    for (a, b) in pairs::motion_pairs() {
        let ca = Curve::from_path(dir.join(&a))?;
        let cb = Curve::from_path(dir.join(&b))?;
        let mut times = Vec::new();
        let mut result = None;
        for _ in 0..reps.max(1) {
            let start = Instant::now();
            let r = morph_pair(&ca.points, &cb.points, &fractions, options);
            times.push(start.elapsed().as_secs_f64() * 1e3);
            result = Some(r);
        }
        times.sort_by(f64::total_cmp);
        let ms = times[times.len() / 2];
        total_ms += ms;
        match result.expect("at least one repetition") {
            Ok((report, _)) if timing_only => {
                timed += 1;
                println!("| {a} → {b} | {} | {ms:.1} |", report.n);
            }
            Ok((report, morph)) => {
                let m = metrics(&morph.frames);
                let (steps, view) = view_of(&ca.points, &cb.points, options);
                detours.push(m.detour);
                unwinds.push(m.unwind);
                println!(
                    "| {a} → {b} | {} | {:.2} | {:.2} | {:.2} | {steps} | {view} | {} | {} | {} | {}/{} | {ms:.1} |",
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
            Err(e) => println!("| {a} → {b} | | | | | | | | | | | | error: {e} | | {ms:.1} |"),
        }
    }
    detours.sort_by(f64::total_cmp);
    Ok(Summary {
        pairs: if timing_only { timed } else { detours.len() },
        median: detours.get(detours.len() / 2).copied().unwrap_or(f64::NAN),
        max: detours.last().copied().unwrap_or(f64::NAN),
        min_unwind: unwinds.iter().copied().fold(f64::INFINITY, f64::min),
        below: unwinds.iter().filter(|&&u| u < 0.9).count(),
        total_ms,
    })
}

/// The measures of docs/design.md §7c beyond detour and unwind, untimed:
/// the largest single-vertex step (fraction of the diagonal) at 40, 320
/// and 2,560 frames, marked "jump" where it does not shrink 4× (or stay
/// under 1 %) from one count to the next; and at 320 frames the longest
/// edge ÷ the ends', the area range ÷ the ends', the smallest angle ÷ the
/// ends' and the as-rigid-as-possible distortion, as table cells.
fn view_of(
    a: &[immerse::Point],
    b: &[immerse::Point],
    options: &CurveMorphOptions,
) -> (String, String) {
    let none = || ("".to_string(), " | | | ".to_string());
    let Ok(tween) = Tween::new(a, b, options) else {
        return none();
    };
    let mut steps = [0.0; 3];
    let mut at_320 = None;
    for (i, count) in [40usize, 320, 2560].into_iter().enumerate() {
        let f: Vec<f64> = (0..count).map(|k| k as f64 / (count - 1) as f64).collect();
        let Some(v) = tween.morph(&f).ok().and_then(|m| view_measures(&m.frames)) else {
            return none();
        };
        steps[i] = v.max_step;
        if count == 320 {
            at_320 = Some(v);
        }
    }
    let ok = |x: f64, y: f64| y <= x / 4.0 || y < 0.01;
    let jump = if ok(steps[0], steps[1]) && ok(steps[1], steps[2]) {
        ""
    } else {
        " jump"
    };
    let v = at_320.expect("320 frames measured");
    (
        format!("{:.4} / {:.4} / {:.4}{jump}", steps[0], steps[1], steps[2]),
        format!(
            "{:.2} | {:.2}–{:.2} | {:.2} | {:.2}",
            v.edge_ratio, v.area_low, v.area_high, v.angle_ratio, v.distortion
        ),
    )
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
