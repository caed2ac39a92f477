//! Measures the morph metrics of docs/design.md §8 on the compatible pairs of
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
//! [`immerse::check`]) gets an n/a row with the defect. The
//! metrics are those of the morph as emitted, so after a fallback they are
//! the `hybrid` frames'. A summary per quality follows (medians under
//! `hybrid`, over all pairs where the quality applies and over the pairs
//! where all three apply).

use std::path::Path;

use immerse::Curve;
use immerse::RootChoice;
use immerse::check;
use immerse::frames::{Frame, metrics};
use immerse::morph::{Compatible, MorphOptions, ThirdVertexPath};
use immerse::{Quality, triangulate_with};

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
    cv: f64,
    share: f64,
    ar: usize,
}

/// Coefficient of variation (standard deviation / mean) of the per-frame
/// area-change norms behind Var. Var scales with the square of the norm of
/// the area vector, which depends on how the triangulation splits the area
/// (on a similarity pair every triangle's area grows by the same factor,
/// yet Var differs between triangulations); CV does not.
fn area_step_cv(frames: &[Frame]) -> f64 {
    let areas: Vec<Vec<f64>> = frames
        .iter()
        .map(|f| {
            f.triangles
                .iter()
                .map(|t| {
                    let [a, b, c] = t.map(|v| f.points[v as usize]);
                    0.5 * (b - a).perp_dot(c - a)
                })
                .collect()
        })
        .collect();
    let steps: Vec<f64> = areas
        .windows(2)
        .map(|w| {
            w[0].iter()
                .zip(&w[1])
                .map(|(a, b)| (b - a).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    let k = steps.len() as f64;
    let mean = steps.iter().sum::<f64>() / k;
    let var = steps.iter().map(|s| (s - mean).powi(2)).sum::<f64>() / k;
    var.sqrt() / mean
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
    let (mut cells, mut fallbacks, mut fell) = (0usize, 0usize, [0usize; 2]);
    println!(
        "{FRAMES} frames per morph; root: disk centre; fan margin {} rad.",
        MorphOptions::DEFAULT.fan_margin
    );
    println!(
        "Columns: AR = area-matrix rank, Var = variance of per-frame area change (areas / source area), \
         CV = its standard deviation / mean, \
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
        println!("| quality | path | AR | Var | CV | min∠ | end∠ | balloon | share | valid |");
        println!("|---|---|---:|---:|---:|---:|---:|---:|---:|---|");
        for q in Quality::ALL {
            let tri = match triangulate_with(&src.points, q) {
                Ok(imm) => imm.triangles,
                Err(e) => {
                    println!("| {q} | all | n/a: source not self-overlapping ({e}) |||||||||");
                    continue;
                }
            };
            if let Err(defect) = check(&dst.points, &tri) {
                println!(
                    "| {q} | all | n/a: T_{q}(source) is not an immersion of the target ({defect}) |||||||||"
                );
                continue;
            }
            let plan = Compatible::new(
                &src.points,
                &dst.points,
                &tri,
                RootChoice::Disk,
                MorphOptions::DEFAULT.fan_margin,
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
                let morph = plan
                    .morph(&times, path)
                    .unwrap_or_else(|e| panic!("{name} {q} {path}: {e}"));
                let m = metrics(&morph.frames);
                assert_eq!(
                    m.valid_frames, m.frames,
                    "{name} {q} {path}: emitted invalid frames"
                );
                cells += 1;
                if morph.fallback {
                    fallbacks += 1;
                    fell[usize::from(path == ThirdVertexPath::RotateSlide)] += 1;
                }
                let valid = if morph.fallback {
                    format!("{own_valid}/{FRAMES} → hybrid")
                } else {
                    format!("{own_valid}/{FRAMES}")
                };
                let ar = m.area_rank.unwrap_or(0);
                let var = m.area_variance.unwrap_or(f64::NAN);
                let share = m.smallest_area_share.unwrap_or(f64::NAN);
                let cv = area_step_cv(&morph.frames);
                println!(
                    "| {q} | {path} | {ar} | {var:.2e} | {cv:.3} | {:.3} | {:.3} | {:.3} | {share:.3} | {valid} |",
                    m.min_angle_deg, m.endpoint_min_angle_deg, m.ballooning
                );
                if path == ThirdVertexPath::Hybrid {
                    hybrid.push(HybridCell {
                        pair: pi,
                        quality: q,
                        min_angle: m.min_angle_deg,
                        var,
                        cv,
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
        "Morphs measured: {cells}; fell back to hybrid: {fallbacks} (linear {}, rotate-slide {}).\n",
        fell[0], fell[1]
    );
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
    println!(
        "| quality | pairs | min∠ | Var | CV | share | AR | pairs (all three) | min∠ (all three) | Var (all three) | CV (all three) |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for q in Quality::ALL {
        let cells: Vec<&HybridCell> = hybrid.iter().filter(|c| c.quality == q).collect();
        let common: Vec<&&HybridCell> = cells
            .iter()
            .filter(|c| all_three.contains(&c.pair))
            .collect();
        println!(
            "| {q} | {} | {:.3} | {:.2e} | {:.3} | {:.3} | {} | {} | {:.3} | {:.2e} | {:.3} |",
            cells.len(),
            median(cells.iter().map(|c| c.min_angle).collect()),
            median(cells.iter().map(|c| c.var).collect()),
            median(cells.iter().map(|c| c.cv).collect()),
            median(cells.iter().map(|c| c.share).collect()),
            median(cells.iter().map(|c| c.ar as f64).collect()),
            common.len(),
            median(common.iter().map(|c| c.min_angle).collect()),
            median(common.iter().map(|c| c.var).collect()),
            median(common.iter().map(|c| c.cv).collect()),
        );
    }
    // Head to head: each two qualities on the pairs where both apply.
    println!("\n### Head to head under `hybrid` (pairs where both qualities apply)\n");
    println!(
        "| qualities | pairs | min∠ | Var | CV | share | min∠ higher / lower | Var lower / higher | CV lower / higher |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    let pairs_of =
        |q: Quality| -> Vec<&HybridCell> { hybrid.iter().filter(|c| c.quality == q).collect() };
    for (qa, qb) in [
        (Quality::Any, Quality::Delaunay),
        (Quality::Any, Quality::MaxMin),
        (Quality::Delaunay, Quality::MaxMin),
    ] {
        let (ca, cb) = (pairs_of(qa), pairs_of(qb));
        let both: Vec<(&HybridCell, &HybridCell)> = ca
            .iter()
            .filter_map(|a| Some((*a, *cb.iter().find(|b| b.pair == a.pair)?)))
            .collect();
        let med = |f: &dyn Fn(&HybridCell) -> f64| {
            (
                median(both.iter().map(|(a, _)| f(a)).collect()),
                median(both.iter().map(|(_, b)| f(b)).collect()),
            )
        };
        let wins = |f: &dyn Fn(&HybridCell) -> f64, higher_better: bool| {
            let (mut w, mut l) = (0, 0);
            for (a, b) in &both {
                let (x, y) = (f(a), f(b));
                let rel = (x - y).abs() / x.abs().max(y.abs()).max(1e-300);
                if rel < 1e-3 {
                    continue;
                }
                if (x > y) == higher_better {
                    w += 1;
                } else {
                    l += 1;
                }
            }
            format!("{w} / {l}")
        };
        let (ma, mb) = med(&|c| c.min_angle);
        let (va, vb) = med(&|c| c.var);
        let (cva, cvb) = med(&|c| c.cv);
        let (sa, sb) = med(&|c| c.share);
        println!(
            "| {qa} vs {qb} | {} | {ma:.3} vs {mb:.3} | {va:.2e} vs {vb:.2e} | {cva:.3} vs {cvb:.3} | {sa:.3} vs {sb:.3} | {} | {} | {} |",
            both.len(),
            wins(&|c| c.min_angle, true),
            wins(&|c| c.var, false),
            wins(&|c| c.cv, false),
        );
    }
    println!(
        "\n(win counts are for the first quality of each row; differences below 0.1% count as ties)"
    );
}
