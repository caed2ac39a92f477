//! Pacing measures of a tween's evenly paced frames (docs/design.md §12),
//! shared by the pacing test and `examples/pacing.rs`.

use immerse::morph::Tween;

/// The spread of the per-frame steps of `frames` evenly paced frames.
pub struct Pacing {
    /// Largest per-frame mean vertex step over the median of those.
    pub mean_ratio: f64,
    /// Largest per-frame single-vertex step over the median of those.
    pub max_ratio: f64,
}

/// Measures the frames at `i / (frames - 1)`, linear easing.
pub fn measure(tween: &Tween, frames: usize) -> Result<Pacing, immerse::morph::MorphError> {
    let ts: Vec<f64> = (0..frames)
        .map(|i| i as f64 / (frames - 1) as f64)
        .collect();
    let morph = tween.morph(&ts)?;
    let (mut means, mut maxes) = (Vec::new(), Vec::new());
    for w in morph.frames.windows(2) {
        let (mut sum, mut max) = (0.0f64, 0.0f64);
        for (p, q) in w[0].points.iter().zip(&w[1].points) {
            let d = (*q - *p).length();
            sum += d;
            max = max.max(d);
        }
        means.push(sum / w[0].points.len() as f64);
        maxes.push(max);
    }
    let spread = |v: &mut Vec<f64>| -> f64 {
        v.sort_by(f64::total_cmp);
        let median = v[v.len() / 2];
        let top = v[v.len() - 1];
        if median > 0.0 {
            top / median
        } else if top > 0.0 {
            f64::INFINITY
        } else {
            1.0
        }
    };
    Ok(Pacing {
        mean_ratio: spread(&mut means),
        max_ratio: spread(&mut maxes),
    })
}
