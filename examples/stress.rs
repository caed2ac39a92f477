//! The long stress run: random pairs of self-overlapping
//! curves from the generators of `testkit/src/stress.rs` (thin wedges and
//! strips, collinear runs, very short edges, spirals, loops, glued disks at
//! scales 1e-6..1e6), morphed under random options; every frame is checked
//! exactly. Prints the count, the failures (by category, generator and
//! option), the run time and pairs per second; exits with 1 when any pair
//! failed.
//!
//! ```text
//! cargo run --release --example stress -- [--pairs N] [--seed S] [--start I]
//!     [--show K] [--timeout S] [--shrink] [--max-shrink K] [--save DIR] [--csv FILE]
//! cargo run --release --example stress -- --pair I [--seed S] [--shrink] [--save DIR]
//! cargo run --release --example stress -- --replay FILE...
//! ```
//!
//! - `--pairs N` (default 10000), `--seed S` (decimal or 0x-hex; default
//!   the test's seed), `--start I`: run pairs I..I+N of that seed, on all
//!   cores (rayon; set `RAYON_NUM_THREADS` to change).
//! - `--timeout S`: end the run with exit code 3 when one pair runs longer
//!   than S seconds (default 300), naming the pair.
//! - `--show K`: print the first K failing pairs as JSON (default 5).
//! - `--shrink`: shrink the first failure of each category (at most
//!   `--max-shrink`, default 10) by dropping points and frames while it
//!   keeps failing the same way, and print the shrunk pairs as JSON;
//!   `--save DIR` also writes them there as regression files
//!   (`tests/stress-regressions/` is replayed by the test
//!   `stress_regressions_all_morph`).
//! - `--pair I`: run one pair and print it with its result; with
//!   `--dump DIR`, also write its curves as `DIR/pairI-source.json` and
//!   `DIR/pairI-target.json` for `immerse morph`.
//! - `--gallery DIR`: write 4 curves of each generator as JSON files (to
//!   look at them with `immerse triangulate FILE -o FILE.png`).
//! - `--csv FILE`: write one line per pair (index, generators, options,
//!   n, milliseconds, failure category) for analysis.
//! - `--replay FILE...`: run regression files.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;

use harness::{DEFAULT_SEED, Failure, Pair, normalise, pair, run_pair, run_pairs, shrink};
use testkit::stress as harness;

struct Args {
    pairs: u64,
    seed: u64,
    start: u64,
    show: usize,
    shrink: bool,
    max_shrink: usize,
    timeout: f64,
    save: Option<PathBuf>,
    one: Option<u64>,
    dump: Option<PathBuf>,
    gallery: Option<PathBuf>,
    csv: Option<PathBuf>,
    replay: Vec<PathBuf>,
}

/// CPU seconds (user + system) this process has used so far, from
/// /proc/self/stat (Linux; `None` elsewhere). Wall time on a shared
/// machine says little; CPU time says what the run costs.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the command name (which is in parentheses).
    let rest = &stat[stat.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks: f64 = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
    // USER_HZ is 100 on every Linux this runs on.
    Some(ticks / 100.0)
}

fn parse_u64(s: &str) -> Result<u64, String> {
    match s.strip_prefix("0x") {
        Some(h) => u64::from_str_radix(h, 16),
        None => s.parse(),
    }
    .map_err(|e| format!("'{s}': {e}"))
}

fn parse_args() -> Result<Args, String> {
    let mut a = Args {
        pairs: 10_000,
        seed: DEFAULT_SEED,
        start: 0,
        show: 5,
        shrink: false,
        max_shrink: 10,
        timeout: 300.0,
        save: None,
        one: None,
        dump: None,
        gallery: None,
        csv: None,
        replay: Vec::new(),
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{arg} needs a value"));
        match arg.as_str() {
            "--pairs" => a.pairs = parse_u64(&value()?)?,
            "--seed" => a.seed = parse_u64(&value()?)?,
            "--start" => a.start = parse_u64(&value()?)?,
            "--show" => a.show = parse_u64(&value()?)? as usize,
            "--max-shrink" => a.max_shrink = parse_u64(&value()?)? as usize,
            "--timeout" => a.timeout = parse_u64(&value()?)? as f64,
            "--save" => a.save = Some(PathBuf::from(value()?)),
            "--pair" => a.one = Some(parse_u64(&value()?)?),
            "--dump" => a.dump = Some(PathBuf::from(value()?)),
            "--gallery" => a.gallery = Some(PathBuf::from(value()?)),
            "--csv" => a.csv = Some(PathBuf::from(value()?)),
            "--shrink" => a.shrink = true,
            "--replay" => {
                a.replay.extend(it.by_ref().map(PathBuf::from));
                if a.replay.is_empty() {
                    return Err("--replay needs files".into());
                }
            }
            "-h" | "--help" => {
                println!("see the doc comment of examples/stress.rs");
                std::process::exit(0);
            }
            other => return Err(format!("unknown argument '{other}'")),
        }
    }
    Ok(a)
}

/// A file name for a shrunk failure.
fn file_name(p: &Pair, f: &Failure) -> String {
    let g = |i: usize| p.generators[i].map_or("x", |g| g.as_str());
    let kind: String = normalise(&f.message)
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect::<String>()
        .split('-')
        .filter(|w| !w.is_empty())
        .take(6)
        .collect::<Vec<_>>()
        .join("-");
    let seed = p.seed.map_or(String::new(), |s| format!("-s{s:x}"));
    format!("pair{}{seed}-{}-{}-{kind}.json", p.index, g(0), g(1))
}

fn shrink_and_report(p: &Pair, f: &Failure, save: Option<&Path>) {
    let t = Instant::now();
    let (small, sf) = shrink(p, f, 3000);
    eprintln!(
        "shrunk {} from {}+{} to {}+{} points, {} to {} frames in {:.1} s",
        p.name(),
        p.source.len(),
        p.target.len(),
        small.source.len(),
        small.target.len(),
        p.options.frames,
        small.options.frames,
        t.elapsed().as_secs_f64()
    );
    let json = small.to_file_text(Some(&sf.message));
    println!("SHRUNK {}: {}\n{json}", small.name(), sf.message);
    if let Some(dir) = save {
        std::fs::create_dir_all(dir).unwrap();
        let path = dir.join(file_name(&small, &sf));
        std::fs::write(&path, json).unwrap();
        eprintln!("wrote {}", path.display());
    }
}

fn main() {
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("stress: {e}");
            std::process::exit(2);
        }
    };
    // Panics inside the library are caught and reported per pair; keep the
    // default hook's backtrace noise out of the run's output.
    std::panic::set_hook(Box::new(|_| {}));

    if !args.replay.is_empty() {
        let mut failed = 0;
        for path in &args.replay {
            let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{e}"));
            let p = Pair::from_json(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            match run_pair(&p) {
                Ok(o) => println!(
                    "ok   {} (n = {}, shift {})",
                    path.display(),
                    o.n,
                    o.report.shift
                ),
                Err(f) => {
                    failed += 1;
                    println!("FAIL {}: {}", path.display(), f.message);
                }
            }
        }
        println!("{failed} of {} regression pairs failed", args.replay.len());
        std::process::exit(i32::from(failed > 0));
    }

    if let Some(dir) = &args.gallery {
        std::fs::create_dir_all(dir).unwrap();
        let mut rng = testkit::Rng::stream(args.seed, 0x9a11e7);
        for g in harness::Generator::ALL {
            for k in 0..4 {
                let (p, _) = harness::generate(&mut rng, g);
                let p = p.expect("a curve");
                let path = dir.join(format!("{}-{k}.json", g.as_str()));
                std::fs::write(&path, harness::curve_json(g.as_str(), &p)).unwrap();
                println!("{} ({} points)", path.display(), p.len());
            }
        }
        return;
    }

    if let Some(i) = args.one {
        let p = pair(args.seed, i);
        if let Some(dir) = &args.dump {
            std::fs::create_dir_all(dir).unwrap();
            for (side, pts) in [("source", &p.source), ("target", &p.target)] {
                let path = dir.join(format!("pair{i}-{side}.json"));
                std::fs::write(&path, harness::curve_json(side, pts)).unwrap();
                eprintln!("wrote {}", path.display());
            }
        }
        let t = Instant::now();
        let r = run_pair(&p);
        let ms = t.elapsed().as_secs_f64() * 1e3;
        println!("{} ({:.1} ms): {}", p.name(), ms, p.options.label());
        match &r {
            Ok(o) => println!(
                "ok: n = {}, shift {}, {:?}",
                o.n, o.report.shift, o.report.used
            ),
            Err(f) => println!("FAIL: {}", f.message),
        }
        println!(
            "{}",
            p.to_json(r.as_ref().err().map(|f| f.message.as_str()))
        );
        if let (Err(f), true) = (&r, args.shrink) {
            shrink_and_report(&p, f, args.save.as_deref());
        }
        std::process::exit(i32::from(r.is_err()));
    }

    let done = AtomicU64::new(0);
    let failed = AtomicU64::new(0);
    let start = Instant::now();
    let step = (args.pairs / 10).max(1);
    // Watchdog: a pair still running after --timeout seconds ends the run
    // (exit 3) with its index, so a hang fails CI instead of stalling it.
    let running: Arc<Mutex<BTreeMap<u64, Instant>>> = Arc::default();
    {
        let running = Arc::clone(&running);
        let (seed, timeout) = (args.seed, args.timeout);
        std::thread::spawn(move || {
            loop {
                std::thread::sleep(std::time::Duration::from_secs(5));
                let stuck: Vec<(u64, f64)> = running
                    .lock()
                    .map(|m| {
                        m.iter()
                            .map(|(&i, t)| (i, t.elapsed().as_secs_f64()))
                            .filter(|&(_, s)| s > timeout)
                            .collect()
                    })
                    .unwrap_or_default();
                if let Some(&(i, secs)) = stuck.first() {
                    println!(
                        "TIMEOUT: pair {i} has run for {secs:.0} s (--timeout {timeout}); reproduce with\n  cargo run --release --example stress -- --seed {seed:#x} --pair {i}"
                    );
                    println!("{}", pair(seed, i).to_json(Some("timeout")));
                    std::process::exit(3);
                }
            }
        });
    }
    let summary = run_pairs(args.seed, args.start, args.pairs, &|i, r| {
        let Ok(mut map) = running.lock() else { return };
        let Some(r) = r else {
            map.insert(i, Instant::now());
            return;
        };
        map.remove(&i);
        drop(map);
        if r.is_err() {
            failed.fetch_add(1, Ordering::Relaxed);
        }
        let k = done.fetch_add(1, Ordering::Relaxed) + 1;
        if k % step == 0 {
            eprintln!(
                "  {k} / {} pairs, {} failed, {:.0} s",
                args.pairs,
                failed.load(Ordering::Relaxed),
                start.elapsed().as_secs_f64()
            );
        }
    });
    let secs = start.elapsed().as_secs_f64();
    if let Some(path) = &args.csv {
        let mut out = String::from(
            "pair,source,target,n,quality,counts,intermediate,correspondence,frames,ms,failure\n",
        );
        for r in &summary.rows {
            let g = |i: usize| r.generators[i].map_or("?", |g| g.as_str());
            let o = &r.options;
            out += &format!(
                "{},{},{},{},{},{},{},{},{},{:.3},\"{}\"\n",
                r.index,
                g(0),
                g(1),
                r.n,
                o.quality,
                harness::counts_name(o.counts),
                o.intermediate.as_str(),
                o.correspondence.as_str(),
                o.frames,
                r.seconds * 1e3,
                r.failed.as_deref().unwrap_or("").replace('"', "'")
            );
        }
        std::fs::write(path, out).unwrap();
    }
    print!("{}", summary.report(args.show));
    let t = summary.sorted_seconds();
    let pct = |q: f64| t[((t.len() - 1) as f64 * q).round() as usize] * 1e3;
    let passing: Vec<f64> = summary
        .rows
        .iter()
        .filter(|r| r.failed.is_none())
        .map(|r| r.seconds)
        .collect();
    if !passing.is_empty() {
        println!(
            "per-pair time of passing pairs (ms, one core): mean {:.1} over {} pairs",
            passing.iter().sum::<f64>() / passing.len() as f64 * 1e3,
            passing.len()
        );
    }
    let slowest = summary
        .rows
        .iter()
        .max_by(|a, b| a.seconds.total_cmp(&b.seconds))
        .map_or(0, |r| r.index);
    println!(
        "per-pair time (ms, one core): mean {:.1}, median {:.1}, p90 {:.1}, p99 {:.1}, max {:.1} (pair {slowest})",
        t.iter().sum::<f64>() / t.len().max(1) as f64 * 1e3,
        pct(0.5),
        pct(0.9),
        pct(0.99),
        pct(1.0)
    );
    if let Some(cpu) = cpu_seconds() {
        println!(
            "CPU time: {cpu:.1} s ({:.1} ms per pair); on 2 idle cores about {:.0} s of wall time",
            cpu / summary.total().max(1) as f64 * 1e3,
            cpu / 2.0
        );
    }
    println!(
        "stress: seed {:#x}, pairs {}..{}: {} pairs, {} failed, {:.1} s, {:.1} pairs/s on {} threads",
        args.seed,
        args.start,
        args.start + args.pairs,
        summary.total(),
        summary.failures.len(),
        secs,
        summary.total() as f64 / secs,
        rayon::current_num_threads()
    );
    if args.shrink {
        // The first failure of each category, shrunk in parallel.
        use rayon::prelude::*;
        let mut seen = BTreeSet::new();
        let firsts: Vec<&(Pair, Failure)> = summary
            .failures
            .iter()
            .filter(|(_, f)| seen.insert(f.category.clone()))
            .take(args.max_shrink)
            .collect();
        firsts
            .par_iter()
            .for_each(|(p, f)| shrink_and_report(p, f, args.save.as_deref()));
    }
    std::process::exit(i32::from(!summary.failures.is_empty()));
}
