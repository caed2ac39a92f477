//! Better immersion triangulations than the DP's arbitrary witness.
//!
//! DP witnesses are very thin (minimum angles of 0.0005°–0.1° are typical).
//! Two remedies, both producing triangulations that pass
//! [`crate::immersion::check`]:
//!
//! - [`improve`]: immersed Delaunay edge flips, the method of Mukherjee &
//!   Gopi, *Tweening Boundary Curves of Non-simple Immersions of a Disk* (§4,
//!   Algorithm 1).
//! - [`triangulate_maxmin`]: the interval DP maximising the minimum angle
//!   exactly over all valid triangulations (docs/design.md §3), O(n³).
//!
//! A simple polygon takes a short cut for `delaunay`: its
//! constrained Delaunay triangulation (spade, O(n log n)) is the immersed
//! Delaunay triangulation, checked exactly before use.
//!
//! [`Quality`] names the choice (`any`, `delaunay`, `maxmin` on the command
//! line) and [`triangulate_with`] dispatches on it. Guaranteed order of the
//! minimum angles: `maxmin ≥ delaunay ≥ any` (flips only raise the sorted
//! angle vector; the DP is optimal).

mod optimal;
mod simple;

pub use crate::flip::delaunay::improve;
pub(crate) use crate::flip::delaunay::improve_common;

use std::fmt;
use std::str::FromStr;

use crate::geom::Point;
use crate::immersion::{Immersion, NotSelfOverlapping, precheck, triangulate_progress};

/// Which immersion triangulation to compute. With the `cli` feature it is
/// the command line's `--quality` (each variant's first doc paragraph is
/// its help there).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Quality {
    /// The dynamic program's witness: any valid triangulation (thin).
    ///
    /// The fastest.
    Any,
    /// The witness improved by immersed Delaunay edge flips.
    ///
    /// See [`improve`].
    #[default]
    Delaunay,
    /// The valid triangulation maximising the minimum angle (slower; at most
    /// 4,000 points and 1.5 billion candidate triangles, about 10 s: nearly
    /// convex curves past about 2,500 points are refused).
    ///
    /// See [`triangulate_maxmin`].
    #[cfg_attr(feature = "cli", value(name = "maxmin"))]
    MaxMin,
}

impl Quality {
    /// Every variant, in CLI order.
    pub const ALL: [Quality; 3] = [Quality::Any, Quality::Delaunay, Quality::MaxMin];

    /// The command-line value: `any`, `delaunay` or `maxmin`.
    pub fn as_str(self) -> &'static str {
        match self {
            Quality::Any => "any",
            Quality::Delaunay => "delaunay",
            Quality::MaxMin => "maxmin",
        }
    }

    /// Bytes of the DP tables that [`triangulate_with`] keeps for `n`
    /// points at this quality: the decision DP's (n²/2 bytes) for
    /// [`Quality::Any`] and [`Quality::Delaunay`], and the max–min DP's
    /// (about 18n² bytes more: the halves of its tables it touches) for
    /// [`Quality::MaxMin`].
    pub fn table_bytes(self, n: usize) -> usize {
        match self {
            Quality::Any | Quality::Delaunay => crate::immersion::dp_memory_bytes(n),
            Quality::MaxMin => optimal::memory_bytes(n),
        }
    }
}

impl fmt::Display for Quality {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A string that names no [`Quality`].
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown triangulation quality '{0}', expected any, delaunay or maxmin")]
pub struct UnknownQuality(pub String);

impl FromStr for Quality {
    type Err = UnknownQuality;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Quality::ALL
            .into_iter()
            .find(|q| q.as_str() == s)
            .ok_or_else(|| UnknownQuality(s.to_owned()))
    }
}

/// The valid triangulation that maximises the minimum angle; among exact
/// ties, the one with the largest sum over triangles of sin² of the
/// triangle's minimum angle, then the smallest apex index (see the
/// `optimal` module docs). O(n³) time, about 18n² bytes of tables.
///
/// # Errors
///
/// As [`crate::immersion::triangulate`]; also
/// [`NotSelfOverlapping::TooManyPoints`] over 4,000 points and
/// [`NotSelfOverlapping::TooManyCandidates`] over
/// 1.5 × 10⁹ candidate triangles (refused before the DP).
pub fn triangulate_maxmin(points: &[Point]) -> Result<Immersion, NotSelfOverlapping> {
    triangulate_with_progress(points, Quality::MaxMin, &mut |_| {})
}

/// Triangulate with the chosen [`Quality`].
///
/// # Examples
///
/// ```
/// use immerse::geom::Point;
/// use immerse::{triangulate_with, Quality};
/// let hex: Vec<Point> = (0..6)
///     .map(|i| {
///         let a = i as f64 * std::f64::consts::TAU / 6.0;
///         Point::new(a.cos(), a.sin())
///     })
///     .collect();
/// for q in Quality::ALL {
///     assert!(triangulate_with(&hex, q)?.is_immersion());
/// }
/// # Ok::<(), immerse::NotSelfOverlapping>(())
/// ```
///
/// # Errors
///
/// As [`crate::immersion::triangulate`].
pub fn triangulate_with(points: &[Point], q: Quality) -> Result<Immersion, NotSelfOverlapping> {
    triangulate_with_progress(points, q, &mut |_| {})
}

/// [`triangulate_with`] with a progress callback receiving the fraction of
/// the work done, in [0, 1].
///
/// # Errors
///
/// As [`crate::immersion::triangulate`].
pub fn triangulate_with_progress(
    points: &[Point],
    q: Quality,
    progress: &mut dyn FnMut(f64),
) -> Result<Immersion, NotSelfOverlapping> {
    // A simple polygon's Delaunay triangulation is its constrained
    // Delaunay triangulation: O(n log n) instead of the DP (checked exactly
    // inside; the DP is the fallback). `any` keeps meaning the DP's witness.
    if q == Quality::Delaunay {
        precheck(points)?;
        if crate::geom::polygon::is_simple(points)
            && let Some(triangles) = simple::cdt(points)
        {
            progress(1.0);
            return Ok(Immersion {
                points: points.to_vec(),
                triangles,
            });
        }
    }
    match q {
        Quality::Any => triangulate_progress(points, progress),
        Quality::Delaunay => triangulate_progress(points, progress).map(improve),
        Quality::MaxMin => {
            precheck(points)?;
            if points.len() > MAX_MAXMIN_POINTS {
                return Err(NotSelfOverlapping::TooManyPoints {
                    n: points.len(),
                    limit: MAX_MAXMIN_POINTS,
                });
            }
            let triangles = optimal::maxmin(points, MAX_MAXMIN_CANDIDATES, progress)?;
            Ok(Immersion {
                points: points.to_vec(),
                triangles,
            })
        }
    }
}

/// Most points the max–min-angle DP accepts: it keeps about 18n² bytes
/// of tables (288 MB at this limit).
pub(crate) const MAX_MAXMIN_POINTS: usize = 4_000;

/// Most candidate triangles `(i, k, j)` (apexes of feasible sub-polygons,
/// counted from the decision table before the max–min DP starts) that the
/// max–min DP accepts: about 10 s on 2 cores for a nearly convex curve,
/// where nearly every candidate is measured. A spiral strip of 4,000
/// points needs far fewer; a nearly convex blob of 2,000 fits, one of
/// 3,000 does not.
pub(crate) const MAX_MAXMIN_CANDIDATES: u64 = 1_500_000_000;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quality_names_round_trip() {
        for q in Quality::ALL {
            assert_eq!(q.as_str().parse::<Quality>(), Ok(q));
            assert_eq!(q.to_string(), q.as_str());
        }
        assert!("best".parse::<Quality>().is_err());
    }
}
