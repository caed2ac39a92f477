//! Which shape of one drawing becomes which shape of another
//! (docs/design.md §2b).

use super::{Drawing, Shape};
use crate::geom::Point;
use crate::geom::polygon::{area_centroid, signed_area};

/// How shapes are paired. With the `cli` feature it is the command line's
/// `--match` (each variant's first doc paragraph is its help there).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum MatchMode {
    /// The same id; shapes without a partner appear or vanish.
    ///
    /// Only non-empty ids pair.
    Id,
    /// The k-th shape with the k-th.
    ///
    /// The extra shapes of the longer drawing appear or vanish.
    Order,
    /// The least total cost of position, size and outline.
    ///
    /// The optimal assignment, where leaving a shape unmatched costs 1
    /// (the cost of a shape's own size).
    #[default]
    Auto,
}

/// What leaving one shape without a partner costs in [`MatchMode::Auto`]:
/// a pair whose cost is above twice this is split into a vanishing and
/// an appearing shape.
pub(crate) const UNMATCHED_COST: f64 = 1.0;

/// Weight of the size term (|ln| of the ratio of the square roots of the
/// areas) in a pair's cost.
const SIZE_WEIGHT: f64 = 0.5;

/// Weight of the outline term (mean distance of the normalised outlines,
/// best rotation of the start) in a pair's cost.
const OUTLINE_WEIGHT: f64 = 0.5;

/// Points each outline is resampled to for the outline term.
const OUTLINE_SAMPLES: usize = 32;

/// Costs are rounded to integers in these units for the exact assignment.
const COST_UNITS: f64 = 1e6;

/// The pairing of two drawings' shapes.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Matching {
    /// The mode that made it.
    pub mode: MatchMode,
    /// Pairs `(source shape, target shape)`, by index, in the source's
    /// order.
    pub pairs: Vec<(usize, usize)>,
    /// The cost of each pair (position + size + outline, see
    /// docs/design.md §2b), in the order of `pairs`.
    pub costs: Vec<f64>,
    /// Source shapes without a partner: they shrink and fade out.
    pub vanishing: Vec<usize>,
    /// Target shapes without a partner: they grow and fade in.
    pub appearing: Vec<usize>,
}

/// Pairs the shapes of `a` with those of `b` by `mode`.
pub fn match_shapes(a: &Drawing, b: &Drawing, mode: MatchMode) -> Matching {
    let scale = drawing_scale(a, b);
    let fa: Vec<Features> = a.shapes.iter().map(|s| Features::of(s, scale)).collect();
    let fb: Vec<Features> = b.shapes.iter().map(|s| Features::of(s, scale)).collect();
    let mut pairs: Vec<(usize, usize)> = match mode {
        MatchMode::Id => a
            .shapes
            .iter()
            .enumerate()
            .filter(|(_, s)| !s.id.is_empty())
            .filter_map(|(i, s)| b.shapes.iter().position(|t| t.id == s.id).map(|j| (i, j)))
            .collect(),
        MatchMode::Order => (0..a.len().min(b.len())).map(|k| (k, k)).collect(),
        MatchMode::Auto => assign(&fa, &fb),
    };
    pairs.sort_unstable();
    let costs = pairs.iter().map(|&(i, j)| fa[i].cost(&fb[j])).collect();
    let vanishing = (0..a.len())
        .filter(|i| !pairs.iter().any(|p| p.0 == *i))
        .collect();
    let appearing = (0..b.len())
        .filter(|j| !pairs.iter().any(|p| p.1 == *j))
        .collect();
    Matching {
        mode,
        pairs,
        costs,
        vanishing,
        appearing,
    }
}

/// The least-cost assignment, each shape matched or left alone at
/// 1 (`UNMATCHED_COST`): Kuhn–Munkres on the square matrix of size
/// `na + nb` whose extra rows and columns stand for "no partner".
fn assign(fa: &[Features], fb: &[Features]) -> Vec<(usize, usize)> {
    let (na, nb) = (fa.len(), fb.len());
    let n = na + nb;
    if na == 0 || nb == 0 {
        return Vec::new();
    }
    let units = |c: f64| (c * COST_UNITS).round() as i64;
    let alone = units(UNMATCHED_COST);
    // A dummy row or column for another shape: never chosen.
    let forbidden = alone.saturating_mul(1_000_000);
    let cost = |i: usize, j: usize| match (i < na, j < nb) {
        (true, true) => units(fa[i].cost(&fb[j])),
        // Source i unmatched (only its own dummy column), target j
        // unmatched (only its own dummy row), or two dummies.
        (true, false) if j - nb == i => alone,
        (false, true) if i - na == j => alone,
        (false, false) => 0,
        _ => forbidden,
    };
    // kuhn_munkres maximises.
    let w: Vec<i64> = (0..n)
        .flat_map(|i| (0..n).map(move |j| -cost(i, j)))
        .collect();
    let Ok(matrix) = pathfinding::matrix::Matrix::from_vec(n, n, w) else {
        return Vec::new();
    };
    let (_, columns) = pathfinding::kuhn_munkres::kuhn_munkres(&matrix);
    columns
        .into_iter()
        .enumerate()
        .take(na)
        .filter(|&(_, j)| j < nb)
        .collect()
}

/// The diagonal of the bounding box of both drawings: costs are measured
/// in it, so they do not depend on the drawings' units.
fn drawing_scale(a: &Drawing, b: &Drawing) -> f64 {
    let mut pts = a.shapes.iter().chain(&b.shapes).flat_map(|s| &s.points);
    let Some(&first) = pts.next() else {
        return 1.0;
    };
    let (lo, hi) = pts.fold((first, first), |(l, h), &p| (l.min(p), h.max(p)));
    let d = (hi - lo).length();
    if d > 0.0 { d } else { 1.0 }
}

/// What a pair's cost compares.
struct Features {
    /// Area centroid, over the drawings' scale.
    centroid: Point,
    /// Square root of the area, over the drawings' scale.
    size: f64,
    /// The outline resampled by arc length, centred and scaled to unit
    /// root-mean-square radius.
    outline: Vec<Point>,
}

impl Features {
    fn of(shape: &Shape, scale: f64) -> Features {
        let c = area_centroid(&shape.points);
        let size = signed_area(&shape.points).abs().sqrt() / scale;
        let samples = resample(&shape.points, OUTLINE_SAMPLES);
        let rms = (samples
            .iter()
            .map(|p| (*p - c).length_squared())
            .sum::<f64>()
            / samples.len() as f64)
            .sqrt();
        let rms = if rms > 0.0 { rms } else { 1.0 };
        Features {
            centroid: c / scale,
            size,
            outline: samples.iter().map(|p| (*p - c) / rms).collect(),
        }
    }

    /// Position + size + outline (docs/design.md §2b).
    fn cost(&self, other: &Features) -> f64 {
        let position = (self.centroid - other.centroid).length();
        let size = if self.size > 0.0 && other.size > 0.0 {
            (self.size / other.size).ln().abs()
        } else {
            0.0
        };
        let m = self.outline.len();
        let outline = (0..m)
            .map(|shift| {
                (0..m)
                    .map(|k| (self.outline[k] - other.outline[(k + shift) % m]).length())
                    .sum::<f64>()
                    / m as f64
            })
            .fold(f64::INFINITY, f64::min);
        position + SIZE_WEIGHT * size + OUTLINE_WEIGHT * outline
    }
}

/// `m` points at equal arc length along the closed polygon, from its first
/// vertex.
fn resample(points: &[Point], m: usize) -> Vec<Point> {
    let n = points.len();
    let edge = |i: usize| (points[i], points[(i + 1) % n]);
    let total: f64 = (0..n).map(|i| (edge(i).1 - edge(i).0).length()).sum();
    if total <= 0.0 {
        return vec![points[0]; m];
    }
    let mut out = Vec::with_capacity(m);
    let (mut i, mut walked) = (0, 0.0);
    for k in 0..m {
        let target = total * k as f64 / m as f64;
        while i < n - 1 && walked + (edge(i).1 - edge(i).0).length() < target {
            walked += (edge(i).1 - edge(i).0).length();
            i += 1;
        }
        let (a, b) = edge(i);
        let len = (b - a).length();
        let f = if len > 0.0 {
            ((target - walked) / len).clamp(0.0, 1.0)
        } else {
            0.0
        };
        out.push(a + f * (b - a));
    }
    out
}
