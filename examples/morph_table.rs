//! Measures the morph metrics of DESIGN.md §8 on the compatible pairs of
//! `curves/pairs/` and prints markdown tables:
//! `cargo run --release --example morph_table`.
//!
//! For every pair × triangulation quality (`any`, `delaunay`, `maxmin`,
//! computed on the source) × third-vertex path (`linear`, `rotate-slide`,
//! `angle`, `hybrid`), 101 frames at t = i/100: AR (area-matrix rank), Var
//! (variance of the per-frame area change, areas over the source's total),
//! the minimum triangle angle over the morph, ballooning (largest total
//! area over the larger endpoint's), the smallest triangle-area share and
//! the valid frames of the requested path before any fallback. A quality
//! whose source triangulation is not an immersion of the target (exact
//! [`immerse::immersion::check`]) gets an n/a row with the defect. The
//! metrics are those of the morph as emitted, so after a fallback they are
//! the `hybrid` frames'. A summary per quality follows (medians under
//! `hybrid`, over all pairs where the quality applies and over the pairs
//! where all three apply).

use std::path::Path;

use immerse::Curve;
use immerse::frames::{Frame, metrics};
use immerse::immersion::check;
use immerse::morph::{Compatible, DEFAULT_FAN_MARGIN, ThirdVertexPath, morph_with};
use immerse::quality::{Quality, triangulate_with};
use immerse::tree::RootChoice;

/// Frames per morph.
const FRAMES: usize = 101;

/// Paths in table order.
const PATHS: [ThirdVertexPath; 4] = [
    ThirdVertexPath::Linear,
    ThirdVertexPath::RotateSlide,
    ThirdVertexPath::Angle,
    ThirdVertexPath::Hybrid,
];

/// One hybrid measurement kept for the summary.
struct HybridCell {
    pair: usize,
    quality: Quality,
    min_angle: f64,
    var: f64,
    share: f64,
    ar: usize,
}

fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        0.5 * (v[m - 1] + v[m])
    }
}

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("curves/pairs");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| {
            let f = e.ok()?.file_name().into_string().ok()?;
            Some(f.strip_suffix(".source.json")?.to_string())
        })
        .collect();
    names.sort();
    let times: Vec<f64> = (0..FRAMES)
        .map(|i| i as f64 / (FRAMES - 1) as f64)
        .collect();
    let mut hybrid: Vec<HybridCell> = Vec::new();
    println!("{FRAMES} frames per morph; root: disk centre; fan margin {DEFAULT_FAN_MARGIN} rad.");
    println!(
        "Columns: AR = area-matrix rank, Var = variance of per-frame area change (areas / source area), \
         min∠ = minimum triangle angle over the morph (degrees), end∠ = the endpoints' minimum, \
         balloon = max total area / larger endpoint's, share = smallest triangle-area share, \
         valid = frames of the requested path that pass the exact check (→ hybrid: fell back).\n"
    );
    for (pi, name) in names.iter().enumerate() {
        let src = Curve::from_path(dir.join(format!("{name}.source.json")))
            .unwrap_or_else(|e| panic!("{e}"));
        let dst = Curve::from_path(dir.join(format!("{name}.target.json")))
            .unwrap_or_else(|e| panic!("{e}"));
        println!(
            "### {name} (n = {}, simple {}/{})\n",
            src.len(),
            src.is_simple(),
            dst.is_simple()
        );
        println!("| quality | path | AR | Var | min∠ | end∠ | balloon | share | valid |");
        println!("|---|---|---:|---:|---:|---:|---:|---:|---|");
        for q in Quality::ALL {
            let tri = match triangulate_with(&src.points, q) {
                Ok(imm) => imm.triangles,
                Err(e) => {
                    println!("| {q} | all | n/a: source not self-overlapping ({e}) ||||||||");
                    continue;
                }
            };
            if let Err(defect) = check(&dst.points, &tri) {
                println!(
                    "| {q} | all | n/a: T_{q}(source) is not an immersion of the target ({defect}) ||||||||"
                );
                continue;
            }
            let plan = Compatible::new(
                &src.points,
                &dst.points,
                &tri,
                RootChoice::Disk,
                DEFAULT_FAN_MARGIN,
            )
            .unwrap_or_else(|e| panic!("{name} {q}: {e}"));
            for path in PATHS {
                // Validity of the requested path's own frames.
                let own_valid = times
                    .iter()
                    .filter(|&&t| {
                        Frame {
                            t,
                            points: plan.positions(t, path),
                            triangles: tri.clone(),
                        }
                        .is_immersion()
                    })
                    .count();
                let morph = morph_with(&plan, &times, path)
                    .unwrap_or_else(|e| panic!("{name} {q} {path}: {e}"));
                let m = metrics(&morph.frames);
                assert_eq!(m.valid_frames, m.frames, "{name} {q} {path}: emitted invalid frames");
                let valid = if morph.fallback {
                    format!("{own_valid}/{FRAMES} → hybrid")
                } else {
                    format!("{own_valid}/{FRAMES}")
                };
                let ar = m.area_rank.unwrap_or(0);
                let var = m.area_variance.unwrap_or(f64::NAN);
                let share = m.smallest_area_share.unwrap_or(f64::NAN);
                println!(
                    "| {q} | {path} | {ar} | {var:.2e} | {:.3} | {:.3} | {:.3} | {share:.3} | {valid} |",
                    m.min_angle_deg, m.endpoint_min_angle_deg, m.ballooning
                );
                if path == ThirdVertexPath::Hybrid {
                    hybrid.push(HybridCell {
                        pair: pi,
                        quality: q,
                        min_angle: m.min_angle_deg,
                        var,
                        share,
                        ar,
                    });
                }
            }
        }
        println!();
    }
    // Summary per quality under hybrid.
    let all_three: Vec<usize> = (0..names.len())
        .filter(|&p| hybrid.iter().filter(|c| c.pair == p).count() == Quality::ALL.len())
        .collect();
    println!("### Summary: medians per quality under `hybrid`\n");
    println!(
        "Pairs where all three qualities apply: {} of {} ({}).\n",
        all_three.len(),
        names.len(),
        all_three
            .iter()
            .map(|&p| names[p].as_str())
            .collect::<Vec<_>>()
            .join(", ")
    );
    println!("| quality | pairs | median min∠ | median Var | median share | median AR | pairs (all three) | median min∠ (all three) | median Var (all three) |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for q in Quality::ALL {
        let cells: Vec<&HybridCell> = hybrid.iter().filter(|c| c.quality == q).collect();
        let common: Vec<&&HybridCell> =
            cells.iter().filter(|c| all_three.contains(&c.pair)).collect();
        println!(
            "| {q} | {} | {:.3} | {:.2e} | {:.3} | {} | {} | {:.3} | {:.2e} |",
            cells.len(),
            median(cells.iter().map(|c| c.min_angle).collect()),
            median(cells.iter().map(|c| c.var).collect()),
            median(cells.iter().map(|c| c.share).collect()),
            median(cells.iter().map(|c| c.ar as f64).collect()),
            common.len(),
            median(common.iter().map(|c| c.min_angle).collect()),
            median(common.iter().map(|c| c.var).collect()),
        );
    }
}
