//! Barycentric coordinates of a point inside a star-shaped polygon.
//!
//! For an interior vertex `p` of a tiling with edge neighbours
//! `q_1, …, q_d` in counter-clockwise order, `p` lies strictly inside the
//! kernel of the polygon `(q_1, …, q_d)` (every sector angle is in (0, π)).
//! Each function here returns `λ_1, …, λ_d > 0` with `Σ λ_j = 1` and
//! `Σ λ_j q_j = p` (Floater & Gotsman eq. 5.4):
//!
//! * [`Weights::Floater`]: Floater's averaged weights, Floater & Gotsman §5
//!   eq. 5.5. For each `k` the line through `q_k` and `p` meets the opposite
//!   edge `[q_i, q_{i+1})`; the barycentric coordinates of `p` in the triangle
//!   `(q_k, q_i, q_{i+1})` are averaged over `k`. The edge is found with exact
//!   orientations ([`orient`]); the coordinates are area ratios in floats.
//! * [`Weights::MeanValue`]: mean value coordinates, Surazhsky & Gotsman
//!   *Intrinsic Morphing* eq. 2: `w_j = (tan(α_{j−1}/2) + tan(α_j/2)) / ℓ_j`,
//!   `λ_j = w_j / Σ w`, where `α_j` is the angle at `p` between `q_j` and
//!   `q_{j+1}` and `ℓ_j = |q_j − p|`.
//! * [`Weights::Uniform`]: Tutte's barycentric mapping, `λ_j = 1/d`. These do
//!   not reproduce `p`; they only give a valid drawing (Tutte 1963).
//!
//! Papers: Floater & Gotsman, *How to Morph Tilings Injectively*; Surazhsky &
//! Gotsman, *Intrinsic Morphing of Compatible Triangulations*
//! (docs/design.md §9).

use immerse_base::geom::{Orientation, Point, orient};

/// Which barycentric coordinates represent an interior vertex. With the
/// `cli` feature it is the command line's `--weights`, variants in its
/// order (each variant's first doc paragraph is its help there).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Weights {
    /// Mean value coordinates (Floater 2003).
    ///
    /// As in Surazhsky & Gotsman *Intrinsic Morphing* eq. 2.
    #[default]
    MeanValue,
    /// Floater's averaged shape-preserving weights.
    ///
    /// Floater & Gotsman eq. 5.5.
    Floater,
    /// Uniform (Tutte) weights; end frames become Tutte drawings.
    ///
    /// `1/d`: they do not reproduce the vertex.
    Uniform,
}

impl Weights {
    /// All choices, in CLI order.
    pub const ALL: [Weights; 3] = [Weights::MeanValue, Weights::Floater, Weights::Uniform];

    /// The name used on the command line: `floater`, `mean-value`, `uniform`.
    pub fn as_str(self) -> &'static str {
        match self {
            Weights::Floater => "floater",
            Weights::MeanValue => "mean-value",
            Weights::Uniform => "uniform",
        }
    }

    /// Coordinates of `p` with respect to `ring` (see [`star_weights`]).
    pub fn of(self, p: Point, ring: &[Point]) -> Vec<f64> {
        star_weights(self, p, ring)
    }
}

/// Coordinates of `p` with respect to the counter-clockwise `ring` of its
/// neighbours, of the chosen kind.
///
/// `p` must lie strictly inside the kernel of `ring` (every consecutive
/// triple `p, q_j, q_{j+1}` counter-clockwise); otherwise the result is
/// unspecified but finite where possible.
pub fn star_weights(kind: Weights, p: Point, ring: &[Point]) -> Vec<f64> {
    match kind {
        Weights::Floater => floater_weights(p, ring),
        Weights::MeanValue => mean_value_weights(p, ring),
        Weights::Uniform => uniform_weights(ring.len()),
    }
}

/// Uniform weights `1/d`.
pub fn uniform_weights(d: usize) -> Vec<f64> {
    vec![1.0 / d.max(1) as f64; d]
}

/// Sector angles `α_j` (at `p`, from `q_j` to `q_{j+1}`) and edge lengths
/// `ℓ_j = |q_j − p|` of a star, the ingredients of Surazhsky & Gotsman
/// *Intrinsic Morphing* eq. 2.
pub fn star_angles(p: Point, ring: &[Point]) -> (Vec<f64>, Vec<f64>) {
    let d = ring.len();
    let rel: Vec<Point> = ring.iter().map(|&q| q - p).collect();
    let angles = (0..d)
        .map(|j| {
            let (a, b) = (rel[j], rel[(j + 1) % d]);
            a.perp_dot(b).atan2(a.dot(b))
        })
        .collect();
    let lengths = rel.iter().map(|r| r.length()).collect();
    (angles, lengths)
}

/// Mean value coordinates from sector angles and edge lengths (Surazhsky &
/// Gotsman *Intrinsic Morphing* eq. 2); `angles[j]` lies between neighbours `j`
/// and `j + 1`.
pub fn mean_value_from_angles(angles: &[f64], lengths: &[f64]) -> Vec<f64> {
    let d = angles.len();
    let tans: Vec<f64> = angles.iter().map(|a| (a * 0.5).tan()).collect();
    let w: Vec<f64> = (0..d)
        .map(|j| (tans[(j + d - 1) % d] + tans[j]) / lengths[j])
        .collect();
    let s: f64 = w.iter().sum();
    w.iter().map(|x| x / s).collect()
}

/// Mean value coordinates of `p` in the star `ring` (Surazhsky & Gotsman
/// *Intrinsic Morphing* eq. 2).
pub fn mean_value_weights(p: Point, ring: &[Point]) -> Vec<f64> {
    let (angles, lengths) = star_angles(p, ring);
    mean_value_from_angles(&angles, &lengths)
}

/// Floater's averaged weights of `p` in the star `ring` (Floater & Gotsman
/// eq. 5.5).
pub fn floater_weights(p: Point, ring: &[Point]) -> Vec<f64> {
    let d = ring.len();
    let mut lambda = vec![0.0; d];
    for k in 0..d {
        // The edge [q_i, q_{i+1}) hit by the ray from q_k through p: the
        // direction p − q_k is at or after q_i and strictly before q_{i+1}.
        let hit = (0..d).find(|&i| {
            let i1 = (i + 1) % d;
            i != k
                && i1 != k
                && orient(p, ring[i], ring[k]) != Orientation::CounterClockwise
                && orient(p, ring[k], ring[i1]) == Orientation::Clockwise
        });
        let Some(i) = hit else {
            return mean_value_weights(p, ring);
        };
        let i1 = (i + 1) % d;
        let (a, b, c) = (ring[k] - p, ring[i] - p, ring[i1] - p);
        let (ta, tb, tc) = (b.perp_dot(c), c.perp_dot(a), a.perp_dot(b).max(0.0));
        let s = ta + tb + tc;
        lambda[k] += ta / s;
        lambda[i] += tb / s;
        lambda[i1] += tc / s;
    }
    lambda.iter().map(|l| l / d as f64).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reproduce_regular_star() {
        let ring: Vec<Point> = (0..5)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 5.0;
                Point::new(a.cos() * (1.0 + 0.3 * k as f64), a.sin())
            })
            .collect();
        let p = Point::new(0.1, -0.05);
        for kind in [Weights::Floater, Weights::MeanValue] {
            let l = star_weights(kind, p, &ring);
            assert!(l.iter().all(|&x| x > 0.0));
            let s: f64 = l.iter().sum();
            assert!((s - 1.0).abs() < 1e-14);
            let q: Point = ring.iter().zip(&l).map(|(&q, &w)| q * w).sum();
            assert!((q - p).length() < 1e-13, "{kind:?}");
        }
    }
}
