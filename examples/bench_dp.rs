//! Time the immersion triangulators against n and print a markdown table of
//! medians (own timing loop; run with `cargo run --release --example bench_dp`).
//!
//! Input: a self-overlapping spiral strip (two full turns, overlapping
//! itself) with n vertices. Columns: decision + witness
//! ([`immerse::triangulate`]), Delaunay flips on that witness
//! ([`immerse::improve`]), the max–min DP ([`immerse::triangulate_maxmin`],
//! skipped above `--maxmin-up-to`, default 1000), and the DP tables' memory.
//! `--sizes 500,1000` picks other n; `--shape circle` uses a regular n-gon.
//!
//! `--scale --cli PATH [--baseline OLD] [--baseline-up-to N]` instead times
//! the command line at scale: `PATH check` on a spiral strip and on a blob
//! (the stress generators' star-shaped curve) of 1,000 to 20,000 points,
//! and `PATH triangulate --quality maxmin` at 1,000 to 4,000, each as a
//! child process (wall time, median of 3, one run past 10 s; peak resident
//! memory from `/usr/bin/time` when present), beside the same runs of an
//! earlier binary `OLD` up to `N` points (default 10,000), with the growth
//! exponent of each column fitted by least squares on log t against log n
//! (n ≥ 2,000).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use immerse::geom::Point;
use immerse::{Quality, improve, triangulate, triangulate_maxmin};

use testkit::stress as harness;

use testkit::shapes;

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

/// The star-shaped blob of the stress generators (simple, nearly convex),
/// with a fixed seed.
fn blob(n: usize) -> Vec<Point> {
    harness::blob(&mut testkit::Rng::stream(7, n as u64), n)
}

fn arg(name: &str) -> Option<String> {
    std::env::args().skip_while(|a| a != name).nth(1)
}

/// A timed child run: wall seconds, peak resident kilobytes (when
/// `/usr/bin/time` is there to tell) and whether the command refused the
/// input up front (the max–min candidate limit).
#[derive(Clone, Copy)]
struct Run {
    secs: f64,
    kb: Option<u64>,
    refused: bool,
}

/// One timed child run; panics on any failure but a refusal.
fn run_once(cli: &Path, args: &[&str]) -> Run {
    let time = Path::new("/usr/bin/time");
    let stats = tempfile::NamedTempFile::new().expect("temporary file");
    let mut cmd = if time.exists() {
        let mut c = Command::new(time);
        c.arg("-f").arg("%M").arg("-o").arg(stats.path()).arg(cli);
        c
    } else {
        Command::new(cli)
    };
    cmd.args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped());
    let s = Instant::now();
    let out = cmd.output().expect("run the command line");
    let secs = s.elapsed().as_secs_f64();
    let stderr = String::from_utf8_lossy(&out.stderr);
    let refused = !out.status.success() && stderr.contains("candidate triangles");
    assert!(
        out.status.success() || refused,
        "{} {args:?}: {}: {stderr}",
        cli.display(),
        out.status
    );
    let kb = std::fs::read_to_string(stats.path())
        .ok()
        .and_then(|t| t.trim().lines().find_map(|l| l.trim().parse().ok()));
    Run { secs, kb, refused }
}

/// Median wall time and largest peak memory of up to 3 runs (1 when the
/// first takes more than 10 s).
fn run_median(cli: &Path, args: &[&str]) -> Run {
    let mut times = Vec::new();
    let mut peak = None;
    let mut refused = false;
    for _ in 0..3 {
        let r = run_once(cli, args);
        times.push(r.secs);
        peak = peak.max(r.kb);
        refused |= r.refused;
        if r.secs > 10.0 {
            break;
        }
    }
    times.sort_by(f64::total_cmp);
    Run {
        secs: times[times.len() / 2],
        kb: peak,
        refused,
    }
}

/// Least-squares slope of log t against log n, over n ≥ 2,000 (below,
/// process start-up weighs too much).
fn growth(points: &[(usize, f64)]) -> Option<f64> {
    let points: Vec<(usize, f64)> = points.iter().copied().filter(|p| p.0 >= 2000).collect();
    if points.len() < 2 {
        return None;
    }
    let xy: Vec<(f64, f64)> = points
        .iter()
        .map(|&(n, t)| ((n as f64).ln(), t.ln()))
        .collect();
    let m = xy.len() as f64;
    let (sx, sy) = xy.iter().fold((0.0, 0.0), |(a, b), &(x, y)| (a + x, b + y));
    let (mx, my) = (sx / m, sy / m);
    let num: f64 = xy.iter().map(|&(x, y)| (x - mx) * (y - my)).sum();
    let den: f64 = xy.iter().map(|&(x, _)| (x - mx) * (x - mx)).sum();
    Some(num / den)
}

fn fmt_run(r: Option<Run>) -> (String, String) {
    match r {
        None => ("not run".to_owned(), String::new()),
        Some(Run { secs, kb, refused }) => (
            if refused {
                format!("refused in {secs:.2} s")
            } else {
                format!("{secs:.2} s")
            },
            kb.map_or_else(
                || "?".to_owned(),
                |kb| format!("{:.0} MB", kb as f64 / 1024.0),
            ),
        ),
    }
}

fn fmt_growth(g: Option<f64>) -> String {
    g.map_or_else(|| "–".to_owned(), |g| format!("n^{g:.2}"))
}

/// The `--scale` table (module docs).
fn scale() {
    let cli = PathBuf::from(arg("--cli").unwrap_or_else(|| "target/release/immerse".to_owned()));
    let baseline = arg("--baseline").map(PathBuf::from);
    let up_to: usize = arg("--baseline-up-to")
        .and_then(|s| s.parse().ok())
        .unwrap_or(10_000);
    let dir = tempfile::tempdir().expect("temporary folder");
    let curve = |shape: &str, n: usize| {
        let pts = if shape == "blob" {
            blob(n)
        } else {
            shapes::wide_spiral(n, 2.0)
        };
        let path = dir.path().join(format!("{shape}-{n}.json"));
        std::fs::write(&path, harness::curve_json(shape, &pts)).expect("write the curve");
        path
    };
    let jobs: [(&str, &[&str], &[usize]); 2] = [
        ("check", &["check"], &[1000, 2000, 5000, 10_000, 20_000]),
        (
            "triangulate --quality maxmin",
            &["triangulate", "--quality", "maxmin"],
            &[1000, 2000, 4000],
        ),
    ];
    for (title, args, sizes) in jobs {
        println!(
            "`immerse {title}` (wall time, median of 3 or one run past 10 s; peak resident memory)\n"
        );
        println!("| curve | n | before | before memory | after | after memory | DP tables |");
        println!("|---|---|---|---|---|---|---|");
        for shape in ["spiral", "blob"] {
            let (mut before, mut after) = (Vec::new(), Vec::new());
            for &n in sizes {
                let path = curve(shape, n);
                let file = path.to_str().expect("a UTF-8 path");
                let all: Vec<&str> = args.iter().copied().chain([file]).collect();
                let old = baseline
                    .as_deref()
                    .filter(|_| n <= up_to)
                    .map(|b| run_median(b, &all));
                let new = run_median(&cli, &all);
                // A refusal is not a time of the job: left out of the fit.
                if let Some(r) = old.filter(|r| !r.refused) {
                    before.push((n, r.secs));
                }
                if !new.refused {
                    after.push((n, new.secs));
                }
                let (bt, bm) = fmt_run(old);
                let (at, am) = fmt_run(Some(new));
                let tables = if title == "check" {
                    Quality::Any.table_bytes(n)
                } else {
                    Quality::MaxMin.table_bytes(n)
                };
                println!(
                    "| {shape} | {n} | {bt} | {bm} | {at} | {am} | {:.0} MB |",
                    tables as f64 / 1e6
                );
            }
            println!(
                "| {shape} | growth | {} | | {} | | |",
                fmt_growth(growth(&before)),
                fmt_growth(growth(&after))
            );
        }
        println!();
    }
}

fn main() {
    if std::env::args().any(|a| a == "--scale") {
        scale();
        return;
    }
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
            _ => shapes::wide_spiral(n, 2.0),
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
            Quality::Any.table_bytes(n) as f64 / 1e6,
            Quality::MaxMin.table_bytes(n) as f64 / 1e6
        );
    }
}
