//! Frames of a morph and the quality metrics of docs/design.md §8 (Mukherjee & Gopi §7,
//! Table 1); the motion measures of §7b and §7c, which the planner uses
//! too, live in the morph's room and are re-exported here.

pub use crate::morph::measure::{ViewMeasures, detour, unwind, view_measures};
use crate::morph::output::Motion;
pub(crate) use crate::morph::output::ser_points;
pub use crate::morph::{Fallback, Frame, Morph};

/// A morph in JSON, with the motion measures of its frames (written here,
/// above the morph's types and its measures). The measures are computed
/// on the first write and kept in the morph.
impl serde::Serialize for Morph {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let finite = |x: f64| x.is_finite().then_some(x);
        let motion = self.motion.get_or_init(|| Motion {
            detour: finite(detour(&self.frames)),
            unwind: finite(unwind(&self.frames)),
        });
        let mut m = s.serialize_struct("Morph", 5)?;
        m.serialize_field("path", &self.path_name())?;
        m.serialize_field("fallback", &self.fallback)?;
        m.serialize_field("fallbacks", &self.fallbacks)?;
        m.serialize_field("motion", &motion)?;
        m.serialize_field("frames", &self.frames)?;
        m.end()
    }
}

/// Quality metrics of a frame sequence (docs/design.md §8).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Metrics {
    /// Numerical rank of the triangle-area matrix (rows triangles, columns
    /// frames), tolerance 10⁻⁶ × the largest singular value;
    /// `None` when the triangulation changes between frames.
    pub area_rank: Option<usize>,
    /// Variance over frames of the norm of the per-frame change in
    /// triangle areas, areas divided by the source's total area; `None`
    /// when the triangulation changes.
    pub area_variance: Option<f64>,
    /// Smallest triangle angle over all frames, degrees.
    pub min_angle_deg: f64,
    /// Smallest triangle angle of the two end frames, degrees.
    pub endpoint_min_angle_deg: f64,
    /// Largest total area over the frames divided by the larger endpoint's.
    pub ballooning: f64,
    /// Over triangles, the smallest ratio of a triangle's least area over
    /// the morph to the smaller of its endpoint areas (1 means no internal
    /// collapse); `None` when the triangulation changes.
    pub smallest_area_share: Option<f64>,
    /// Mean vertex path length over the frames divided by the mean
    /// straight-line distance between the first and last frames under the
    /// best cyclic shift of the last frame's vertices ([`detour`]): 1 is
    /// straight lines; a needless spin or unwind shows as a large value.
    pub detour: f64,
    /// Smallest total absolute turning of any frame divided by the smaller
    /// of the two end frames' ([`unwind`]): below 1 means overlaps were
    /// undone and redone.
    pub unwind: f64,
    /// Frames that pass the exact immersion check.
    pub valid_frames: usize,
    /// All frames.
    pub frames: usize,
}

/// Relative tolerance of the numerical rank: singular values below
/// 1e-6 × the largest are treated as zero (docs/design.md §8). Areas carry
/// relative rounding errors near 1e-16 per operation, far below it.
pub(crate) const RANK_TOLERANCE: f64 = 1e-6;

/// Computes the metrics of a frame sequence.
pub fn metrics(frames: &[Frame]) -> Metrics {
    let valid_frames = frames.iter().filter(|f| f.is_immersion()).count();
    let min_angle = frames
        .iter()
        .map(Frame::min_angle)
        .fold(f64::INFINITY, f64::min);
    let end_min = match (frames.first(), frames.last()) {
        (Some(a), Some(b)) => a.min_angle().min(b.min_angle()),
        _ => f64::NAN,
    };
    let totals: Vec<f64> = frames.iter().map(Frame::total_area).collect();
    let end_max = match (totals.first(), totals.last()) {
        (Some(a), Some(b)) => a.max(*b),
        _ => f64::NAN,
    };
    let ballooning = totals.iter().copied().fold(f64::NEG_INFINITY, f64::max) / end_max;
    let fixed = frames.windows(2).all(|w| w[0].triangles == w[1].triangles);
    let (mut area_rank, mut area_variance, mut share) = (None, None, None);
    if fixed && !frames.is_empty() {
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
        area_rank = Some(numerical_rank(&areas, RANK_TOLERANCE));
        let norm = totals[0].abs().max(f64::MIN_POSITIVE);
        let steps: Vec<f64> = areas
            .windows(2)
            .map(|w| {
                w[0].iter()
                    .zip(&w[1])
                    .map(|(a, b)| ((b - a) / norm).powi(2))
                    .sum::<f64>()
                    .sqrt()
            })
            .collect();
        if !steps.is_empty() {
            let mean = steps.iter().sum::<f64>() / steps.len() as f64;
            area_variance =
                Some(steps.iter().map(|s| (s - mean).powi(2)).sum::<f64>() / steps.len() as f64);
        }
        let m = areas[0].len();
        let last = areas.len() - 1;
        let mut best = f64::INFINITY;
        for i in 0..m {
            let lo = areas[0][i].min(areas[last][i]);
            let least = areas.iter().map(|a| a[i]).fold(f64::INFINITY, f64::min);
            if lo > 0.0 {
                best = best.min(least / lo);
            }
        }
        share = Some(best);
    }
    Metrics {
        area_rank,
        area_variance,
        min_angle_deg: min_angle.to_degrees(),
        endpoint_min_angle_deg: end_min.to_degrees(),
        ballooning,
        smallest_area_share: share,
        detour: detour(frames),
        unwind: unwind(frames),
        valid_frames,
        frames: frames.len(),
    }
}

/// Numerical rank of the matrix whose columns are `cols`, by one-sided
/// Jacobi SVD (accurate for small singular values, unlike the Gram
/// matrix): the number of singular values above `tol` × the largest.
pub(crate) fn numerical_rank(cols: &[Vec<f64>], tol: f64) -> usize {
    let mut a: Vec<Vec<f64>> = cols.to_vec();
    let k = a.len();
    if k == 0 {
        return 0;
    }
    for _sweep in 0..60 {
        let mut rotated = false;
        for p in 0..k {
            for q in p + 1..k {
                let (alpha, beta, gamma) = {
                    let (x, y) = (&a[p], &a[q]);
                    (
                        x.iter().map(|v| v * v).sum::<f64>(),
                        y.iter().map(|v| v * v).sum::<f64>(),
                        x.iter().zip(y).map(|(u, v)| u * v).sum::<f64>(),
                    )
                };
                if gamma.abs() <= 1e-15 * (alpha * beta).sqrt() || gamma == 0.0 {
                    continue;
                }
                rotated = true;
                let zeta = (beta - alpha) / (2.0 * gamma);
                let t = zeta.signum() / (zeta.abs() + (1.0 + zeta * zeta).sqrt());
                let t = if zeta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (1.0 + t * t).sqrt();
                let s = c * t;
                let (left, right) = a.split_at_mut(q);
                let (x, y) = (&mut left[p], &mut right[0]);
                for (u, v) in x.iter_mut().zip(y.iter_mut()) {
                    let (uu, vv) = (*u, *v);
                    *u = c * uu - s * vv;
                    *v = s * uu + c * vv;
                }
            }
        }
        if !rotated {
            break;
        }
    }
    let sv: Vec<f64> = a
        .iter()
        .map(|c| c.iter().map(|v| v * v).sum::<f64>().sqrt())
        .collect();
    let max = sv.iter().copied().fold(0.0, f64::max);
    if max == 0.0 {
        return 0;
    }
    sv.iter().filter(|&&s| s > tol * max).count()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point;

    /// A morph's JSON carries the detour and unwind of its frames,
    /// computed on the first write and kept: a second write gives the same
    /// text without searching again (frames changed after the first write
    /// do not change it), and the kept measures do not make two morphs
    /// unequal.
    #[test]
    fn morph_json_keeps_its_motion_measures() {
        let square = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)];
        let frames: Vec<Frame> = (0..5)
            .map(|k| {
                let t = k as f64 / 4.0;
                let spin = Point::from_angle(t);
                Frame {
                    t,
                    points: square
                        .iter()
                        .map(|&(x, y)| spin.rotate(Point::new(x, y)) * (1.0 + t))
                        .collect(),
                    triangles: vec![[0, 1, 2], [0, 2, 3]],
                }
            })
            .collect();
        let morph = Morph::new(Vec::new(), Vec::new(), frames.clone());
        let unwritten = morph.clone();
        let first = serde_json::to_value(&morph).unwrap();
        assert_eq!(first["motion"]["detour"], detour(&frames));
        assert_eq!(first["motion"]["unwind"], unwind(&frames));
        assert!(detour(&frames) > 1.0, "the spin is a detour");
        assert_eq!(morph, unwritten);
        let mut moved = morph.clone();
        moved.frames[2].points[0] += Point::new(5.0, 0.0);
        assert_ne!(detour(&moved.frames), detour(&frames));
        let again = serde_json::to_value(&moved).unwrap();
        assert_eq!(again["motion"], first["motion"]);
        assert_eq!(
            serde_json::to_string(&morph).unwrap(),
            serde_json::to_string(&unwritten).unwrap()
        );
    }

    #[test]
    fn rank_of_known_matrices() {
        let c1 = vec![1.0, 2.0, 3.0, 4.0];
        let c2 = vec![2.0, 4.0, 6.0, 8.0];
        let c3 = vec![0.0, 1.0, 0.0, 1.0];
        assert_eq!(numerical_rank(&[c1.clone(), c2.clone()], 1e-6), 1);
        assert_eq!(numerical_rank(&[c1.clone(), c2, c3.clone()], 1e-6), 2);
        let c4: Vec<f64> = c1.iter().zip(&c3).map(|(a, b)| a + 1e-9 * b).collect();
        assert_eq!(numerical_rank(&[c1.clone(), c4.clone()], 1e-6), 1);
        assert_eq!(numerical_rank(&[c1, c4], 1e-12), 2);
    }
}
