//! Prints a markdown table of the incompatible morph on pairs of reference
//! curves: flips, u*, v*, the minimum angle over the morph against the
//! inputs', path length, ballooning and wall time, for each route and
//! correspondence rule.
//!
//! Run with `cargo run --release --example morph_pairs [-- WORD...]`
//! where words pick correspondence rules (pivot, min-flips, shape,
//! identity) and intermediates (target, disk); default: all of each.

use immerse::Curve;
use immerse::frames::metrics;
use immerse::morph::{Correspondence, CurveMorphOptions, Intermediate};
use std::path::Path;
use std::time::Instant;
use testkit::morph_pair;

use testkit::pairs::reference_pairs;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let picked = |name: &str, all: &[&str]| {
        !args.iter().any(|a| all.contains(&a.as_str())) || args.iter().any(|a| a == name)
    };
    let rule_names: Vec<&str> = Correspondence::ALL.iter().map(|r| r.as_str()).collect();
    let rules: Vec<Correspondence> = Correspondence::ALL
        .into_iter()
        .filter(|r| picked(r.as_str(), &rule_names))
        .collect();
    let routes: Vec<Intermediate> = [Intermediate::Target, Intermediate::Disk]
        .into_iter()
        .filter(|r| picked(r.as_str(), &["target", "disk"]))
        .collect();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("curves");
    let fractions: Vec<f64> = (0..=100).map(|i| f64::from(i) / 100.0).collect();
    println!(
        "| pair | n | route | rule | flips | u* | v* | disk | min angle (°) | inputs' (°) | path length | ballooning | time (ms) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let mut summary: Vec<Summary> = Vec::new();
    for &route in &routes {
        for &rule in &rules {
            let (mut angles, mut flips, mut lengths, mut times) =
                (Vec::new(), Vec::new(), Vec::new(), Vec::new());
            let mut disks = 0;
            for (a, b) in &reference_pairs() {
                let ca = Curve::from_path(dir.join(a))?;
                let cb = Curve::from_path(dir.join(b))?;
                let options = CurveMorphOptions::DEFAULT
                    .with_correspondence(rule)
                    .with_intermediate(route);
                let start = Instant::now();
                let (report, morph) = morph_pair(&ca.points, &cb.points, &fractions, &options)?;
                let ms = start.elapsed().as_secs_f64() * 1e3;
                let m = metrics(&morph.frames);
                // Path length: summed largest vertex move per frame, in units
                // of the larger input's bounding-box diagonal.
                let diag = |p: &[immerse::Point]| {
                    let lo = p
                        .iter()
                        .copied()
                        .fold(immerse::Point::splat(f64::INFINITY), immerse::Point::min);
                    let hi = p.iter().copied().fold(
                        immerse::Point::splat(f64::NEG_INFINITY),
                        immerse::Point::max,
                    );
                    (hi - lo).length()
                };
                let d = diag(&ca.points).max(diag(&cb.points));
                let length: f64 = morph
                    .frames
                    .windows(2)
                    .map(|w| {
                        w[0].points
                            .iter()
                            .zip(&w[1].points)
                            .map(|(p, q)| (*p - *q).length())
                            .fold(0.0, f64::max)
                    })
                    .sum::<f64>()
                    / d;
                println!(
                    "| {a} → {b} | {} | {} | {} | {} | {:.3} | {:.3} | {} | {:.3} | {:.3} | {:.2} | {:.3} | {:.1} |",
                    report.n,
                    route.as_str(),
                    rule.as_str(),
                    report.flips,
                    report.u_star,
                    report.v_star,
                    if report.used_disk { "yes" } else { "no" },
                    m.min_angle_deg,
                    m.endpoint_min_angle_deg,
                    length,
                    m.ballooning,
                    ms
                );
                angles.push(m.min_angle_deg);
                flips.push(report.flips as f64);
                lengths.push(length);
                times.push(ms);
                disks += usize::from(report.used_disk);
            }
            summary.push((
                format!("{} / {}", route.as_str(), rule.as_str()),
                angles,
                flips,
                lengths,
                times,
                disks,
            ));
        }
    }
    println!();
    println!(
        "| route / rule | pairs that used the disk | median min angle (°) | median flips | median path length | median time (ms) |"
    );
    println!("|---|---|---|---|---|---|");
    for (name, angles, flips, lengths, times, disks) in summary {
        println!(
            "| {name} | {disks}/{} | {:.3} | {:.0} | {:.2} | {:.1} |",
            angles.len(),
            median(angles),
            median(flips),
            median(lengths),
            median(times)
        );
    }
    Ok(())
}

/// One route and rule: name, per-pair min angles, flips, path lengths,
/// times, and how many pairs used the disk.
type Summary = (String, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, usize);

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}
