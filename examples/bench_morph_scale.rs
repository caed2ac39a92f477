//! How `immerse morph` scales with the vertex count: the CLI with its
//! default options and 60 frames (written as JSON), on two pairs, at
//! n = 400, 1000, 2000 and 5000 (or `--sizes`). Each row gives the median
//! wall time of `--runs` runs (default 7: the small rows vary by a few
//! milliseconds from run to run), the median CPU time (user +
//! system, all threads: on a machine shared with other jobs the wall time
//! varies far more) and the peak resident memory of the process, and, on
//! the same pair in the same run, flubber's time and
//! memory when `--flubber DIR` names a folder where flubber is installed
//! (`scripts/bench-table.sh --morph-scale` installs it as
//! `scripts/peer-compare.sh` does). A last line fits the growth exponent
//! of the time over n = 1000–5000 (least squares on log–log; n² log n
//! over that range is an exponent of 2.13).
//!
//! The pairs:
//! - spiral ↔ blob: a spiral strip wound 720° (it overlaps itself) and a
//!   star-shaped blob, both with n vertices;
//! - triangle → spiral strip: a triangle (3 vertices, n − 3 inserted on
//!   its edges) into the same spiral.
//!
//! Usage: `cargo build --release --bin immerse --example bench_morph_scale
//! && target/release/examples/bench_morph_scale [--sizes 400,1000]
//! [--runs K] [--immerse PATH] [--baseline PATH] [--flubber DIR]
//! [--keep DIR]`. `--keep` also writes each row's two curves into DIR as
//! `spiral-blob-N-{a,b}.json` and `triangle-spiral-N-{a,b}.json`, to
//! profile one row alone.
//! `--baseline` times a second immerse binary on the same curves in the
//! same run (before/after tables). Peak memory and CPU time are read
//! from `/proc/PID/status` and `/proc/PID/stat` (Linux) while the process
//! runs (the last reading before it exits); elsewhere they are left
//! blank.

use immerse::Point;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use testkit::shapes;

/// A spiral strip of n vertices (n/2 stations, outer edge out, inner edge
/// back) wound `turns` times; its width is more than the radius gained in
/// one turn, so it overlaps itself.
fn spiral(n: usize, turns: f64) -> Vec<Point> {
    shapes::spiral_strip(n / 2, turns, 0.3).0
}

fn triangle() -> Vec<Point> {
    vec![
        Point::new(0.0, 0.0),
        Point::new(4.0, 0.0),
        Point::new(1.0, 3.0),
    ]
}

/// Makes the two curves of a pair at a vertex count.
type Pair = fn(usize) -> (Vec<Point>, Vec<Point>);

fn write_curve(path: &Path, name: &str, p: &[Point]) -> std::io::Result<()> {
    let pts: Vec<[f64; 2]> = p.iter().map(|q| [q.x, q.y]).collect();
    let json = serde_json::json!({ "name": name, "points": pts });
    std::fs::write(path, json.to_string())
}

/// Peak resident memory (VmHWM, bytes) of a running process, if readable.
fn peak_memory(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// CPU time (user + system, seconds) of a running process, if readable.
fn cpu_time(pid: u32) -> Option<f64> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // The fields after the command name (in brackets, may hold spaces).
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let ticks = fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

/// One finished run: wall time, CPU time and peak memory (the last two
/// polled).
struct Run {
    wall: f64,
    cpu: Option<f64>,
    peak: Option<u64>,
}

/// Runs `cmd` to completion.
fn run(cmd: &mut Command) -> Result<Run, String> {
    let start = Instant::now();
    let mut child = cmd
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("{cmd:?}: {e}"))?;
    let (mut peak, mut cpu) = (None, None);
    let status = loop {
        if let Some(m) = peak_memory(child.id()) {
            peak = Some(m);
        }
        if let Some(c) = cpu_time(child.id()) {
            cpu = Some(c);
        }
        match child.try_wait().map_err(|e| e.to_string())? {
            Some(status) => break status,
            None => std::thread::sleep(Duration::from_millis(1)),
        }
    };
    let secs = start.elapsed().as_secs_f64();
    if !status.success() {
        let mut err = String::new();
        if let Some(mut e) = child.stderr.take() {
            use std::io::Read;
            let _ = e.read_to_string(&mut err);
        }
        return Err(format!("{cmd:?} failed: {err}"));
    }
    Ok(Run {
        wall: secs,
        cpu,
        peak,
    })
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Median wall time, median CPU time and largest peak memory of `runs`
/// runs of `cmd`.
fn measure(runs: usize, mut cmd: impl FnMut() -> Command) -> Result<Run, String> {
    let (mut walls, mut cpus) = (Vec::new(), Vec::new());
    let mut peak: Option<u64> = None;
    for _ in 0..runs {
        let r = run(&mut cmd())?;
        walls.push(r.wall);
        cpus.extend(r.cpu);
        peak = peak.max(r.peak);
    }
    Ok(Run {
        wall: median(walls),
        cpu: (!cpus.is_empty()).then(|| median(cpus)),
        peak,
    })
}

fn secs(t: Option<f64>) -> String {
    t.map_or(String::new(), |t| format!("{t:.2} s"))
}

/// Least-squares slope of log t against log n.
fn exponent(points: &[(usize, f64)]) -> Option<f64> {
    if points.len() < 2 {
        return None;
    }
    let xs: Vec<f64> = points.iter().map(|p| (p.0 as f64).ln()).collect();
    let ys: Vec<f64> = points.iter().map(|p| p.1.ln()).collect();
    let k = xs.len() as f64;
    let (mx, my) = (xs.iter().sum::<f64>() / k, ys.iter().sum::<f64>() / k);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    Some(sxy / sxx)
}

/// The target of each pair at each n (a time in seconds).
fn target(n: usize) -> Option<f64> {
    match n {
        400 => Some(0.06),
        2000 => Some(0.5),
        5000 => Some(3.0),
        _ => None,
    }
}

fn mb(m: Option<u64>) -> String {
    m.map_or(String::new(), |b| format!("{:.0} MB", b as f64 / 1e6))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let sizes: Vec<usize> = match value("--sizes") {
        Some(s) => s.split(',').map(str::parse).collect::<Result<_, _>>()?,
        None => vec![400, 1000, 2000, 5000],
    };
    let runs: usize = value("--runs").map_or(Ok(7), |r| r.parse())?;
    let exe_dir = std::env::current_exe()?
        .parent()
        .and_then(Path::parent)
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let immerse = value("--immerse").map_or_else(|| exe_dir.join("immerse"), PathBuf::from);
    if !immerse.is_file() {
        return Err(format!(
            "{} not found: build it with `cargo build --release --bin immerse` or pass --immerse",
            immerse.display()
        )
        .into());
    }
    let baseline = value("--baseline").map(PathBuf::from);
    let flubber = value("--flubber").map(PathBuf::from);
    let keep = value("--keep").map(PathBuf::from);
    if let Some(k) = &keep {
        std::fs::create_dir_all(k)?;
    }
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/peer/flubber_frames.mjs");
    let dir = tempfile::tempdir()?;
    let pairs: [(&str, &str, Pair); 2] = [
        ("spiral ↔ blob", "spiral-blob", |n| {
            (spiral(n, 2.0), shapes::star_blob(n))
        }),
        ("triangle → spiral strip", "triangle-spiral", |n| {
            (triangle(), spiral(n, 2.0))
        }),
    ];
    println!(
        "`immerse morph A B --json OUT` with default options, 60 frames; median wall and CPU time (user + system, all threads) of {runs} runs, peak resident memory; flubber 0.4.2 `interpolate` + 60 evaluations in node (fastest of 3 after a warm-up, in-process), its process's peak memory\n"
    );
    let mut header = "| pair | n | immerse | CPU | memory |".to_string();
    let mut rule = "|---|---|---|---|---|".to_string();
    if baseline.is_some() {
        header += " before | CPU before | memory before |";
        rule += "---|---|---|";
    }
    header += " target | flubber | flubber memory |";
    rule += "---|---|---|";
    println!("{header}\n{rule}");
    let mut fits: Vec<String> = Vec::new();
    for (name, stem, make) in pairs {
        let mut ours = Vec::new();
        let mut ours_cpu = Vec::new();
        let mut theirs = Vec::new();
        for &n in &sizes {
            let (a, b) = make(n);
            let (pa, pb) = (dir.path().join("a.json"), dir.path().join("b.json"));
            write_curve(&pa, "a", &a)?;
            write_curve(&pb, "b", &b)?;
            if let Some(k) = &keep {
                write_curve(&k.join(format!("{stem}-{n}-a.json")), "a", &a)?;
                write_curve(&k.join(format!("{stem}-{n}-b.json")), "b", &b)?;
            }
            let out = dir.path().join("out.json");
            let cmd = |bin: &Path| {
                let mut c = Command::new(bin);
                c.arg("morph")
                    .arg(&pa)
                    .arg(&pb)
                    .args(["--frames", "60", "--quiet", "--force", "--json"])
                    .arg(&out);
                c
            };
            let r = measure(runs, || cmd(&immerse))?;
            ours.push((n, r.wall));
            ours_cpu.extend(r.cpu.map(|c| (n, c)));
            let mut row = format!(
                "| {name} | {n} | {:.3} s | {} | {} |",
                r.wall,
                secs(r.cpu),
                mb(r.peak)
            );
            if let Some(base) = &baseline {
                let b = measure(runs, || cmd(base))?;
                row += &format!(" {:.3} s | {} | {} |", b.wall, secs(b.cpu), mb(b.peak));
            }
            row += &format!(
                " {} |",
                target(n).map_or(String::new(), |s| format!("< {s} s"))
            );
            match &flubber {
                Some(prefix) => {
                    let pdir = dir.path().join("flubber");
                    std::fs::create_dir_all(&pdir)?;
                    let pts = |p: &[Point]| p.iter().map(|q| [q.x, q.y]).collect::<Vec<_>>();
                    let pair = serde_json::json!({
                        "name": name,
                        "from": {"points": pts(&a)},
                        "to": {"points": pts(&b)},
                    });
                    std::fs::write(pdir.join("pair-00.json"), pair.to_string())?;
                    let fm = run(Command::new("node")
                        .arg(&script)
                        .arg(&pdir)
                        .arg(prefix)
                        .args(["false", "60"]))?;
                    let res: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(
                        pdir.join("flubber-00.json"),
                    )?)?;
                    let ms = res["ms"].as_f64().unwrap_or(f64::NAN);
                    theirs.push((n, ms / 1e3));
                    row += &format!(" {:.3} s | {} |", ms / 1e3, mb(fm.peak));
                }
                None => row += " not run | |",
            }
            println!("{row}");
        }
        let fit = |v: &[(usize, f64)]| {
            let big: Vec<(usize, f64)> = v
                .iter()
                .copied()
                .filter(|p| (1000..=5000).contains(&p.0))
                .collect();
            exponent(&big).map_or("n/a".to_string(), |e| format!("{e:.2}"))
        };
        let mut line = format!(
            "{name}: immerse {} (CPU time {})",
            fit(&ours),
            fit(&ours_cpu)
        );
        if !theirs.is_empty() {
            line += &format!(", flubber {}", fit(&theirs));
        }
        fits.push(line);
    }
    println!(
        "\nGrowth exponent of the time over n = 1000–5000 (least squares on log–log; n² log n is 2.13): {}",
        fits.join("; ")
    );
    Ok(())
}
