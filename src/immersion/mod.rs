//! Immersion triangulation: decide whether a closed polygon bounds an
//! immersed disk (is *self-overlapping*) and triangulate that disk.
//!
//! Provenance: Mukherjee & Gopi, *Tweening Boundary Curves of Non-simple
//! Immersions of a Disk* §4, which takes the triangulation from Shor and Van
//! Wyk, *Detecting and Decomposing Self-Overlapping Curves* (its ref. \[24\]);
//! the exact, bitset form is docs/design.md §3. A polygon with turning number
//! +1 is self-overlapping iff the abstract n-gon has a triangulation by
//! diagonals whose n − 2 triangles are all *valid* ([`is_valid_triangle`]:
//! strictly counter-clockwise, no vertex fan wraps).
//!
//! [`triangulate`] returns an arbitrary such triangulation (the DP witness;
//! typically very thin triangles). [`crate::quality`] improves it by
//! Delaunay flips or computes the max–min-angle one.
//!
//! Complexity: O(n³/64) word operations in the worst case (far fewer in
//! practice, see `dp`) and O(n²) exact predicates, in parallel; memory about
//! n²/2 bytes ([`dp_memory_bytes`]: 0.5 MB at n = 1000, 200 MB at
//! n = 20,000). Every
//! decision is exact (`geom::predicates`); only [`Immersion::min_angle`]
//! measures in floating point.
//!
//! # Examples
//!
//! ```
//! use immerse::geom::Point;
//! use immerse::triangulate;
//! let square = [Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(1.0, 1.0), Point::new(0.0, 1.0)];
//! let imm = triangulate(&square)?;
//! assert_eq!(imm.triangles.len(), 2);
//! assert!(imm.is_immersion());
//! # Ok::<(), immerse::NotSelfOverlapping>(())
//! ```

mod check;
pub(crate) mod dp;
pub(crate) mod valid;

pub(crate) use check::check_triangles;
pub(crate) use check::{CheckedTriangles, check_structure};
pub use check::{ImmersionDefect, check};
pub use valid::is_valid_triangle;

use crate::curve::{MAX_COORDINATE, MIN_COORDINATE};
use crate::geom::Point;
use crate::geom::polygon::{Turning, triangle_angles, turning_number};
use crate::tree::{DualTree, RootChoice, Spine, TreeError, root_triangle};

/// A triangulated immersed disk: the boundary polygon and n − 2 triangles.
///
/// Each triangle `[a, b, c]` has `a < b < c`, so its corners are in cyclic
/// polygon order; every triangle is valid, hence counter-clockwise.
#[derive(Clone, Debug, PartialEq)]
pub struct Immersion {
    /// The boundary polygon, in order (turning number +1).
    pub points: Vec<Point>,
    /// The triangles, as indices into `points`.
    pub triangles: Vec<[u32; 3]>,
}

impl Immersion {
    /// The smallest interior angle over all triangles, in radians
    /// (a measurement in floating point; +∞ when there are no triangles).
    pub fn min_angle(&self) -> f64 {
        self.triangles
            .iter()
            .map(|&[a, b, c]| {
                let p = |v: u32| self.points.get(v as usize).copied().unwrap_or(Point::ZERO);
                let [x, y, z] = triangle_angles(p(a), p(b), p(c));
                x.min(y).min(z)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// True when [`check`] finds no defect.
    pub fn is_immersion(&self) -> bool {
        check(&self.points, &self.triangles).is_ok()
    }

    /// The spine of the triangulation's dual tree, with its pivot triangle
    /// and pivot vertex (docs/design.md §4; Mukherjee & Gopi §6.1).
    ///
    /// # Errors
    ///
    /// [`TreeError`] when the triangles are not a triangulation of the
    /// polygon (never for an immersion this crate triangulated).
    pub fn spine(&self) -> Result<Spine, TreeError> {
        Ok(DualTree::new(self.points.len(), &self.triangles)?.spine(&self.points))
    }

    /// The triangle that roots a morph's propagation along the dual tree
    /// (docs/design.md §4; Mukherjee & Gopi §5).
    ///
    /// # Errors
    ///
    /// As [`Immersion::spine`].
    pub fn root_triangle(&self, choice: RootChoice) -> Result<usize, TreeError> {
        let tree = DualTree::new(self.points.len(), &self.triangles)?;
        Ok(root_triangle(&tree, &self.points, choice.into()))
    }
}

/// Why a polygon does not bound an immersed disk.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum NotSelfOverlapping {
    /// The turning number is not +1. (A turning number of −1 means the
    /// polygon is clockwise: the caller orients, this module never reverses.)
    #[error("turning number is {0}, not 1")]
    TurningNumber(i64),
    /// The polygon reverses direction (or has a zero-length edge) at this
    /// vertex, so its turning number is undefined.
    #[error("the curve reverses direction at point {0} (a cusp), so it has no turning number")]
    Cusp(usize),
    /// Fewer than 3 points, or all points on one line: the polygon encloses
    /// no area, so it bounds no disk (and has no turning number). A
    /// [`crate::Curve`] is never degenerate.
    #[error(
        "the points lie on one line (fewer than 3 points, or zero area), so they bound no disk; give at least 3 points that enclose a region"
    )]
    Degenerate,
    /// The turning number is +1 but no triangulation by valid triangles
    /// exists.
    #[error("no triangulation of the disk by valid triangles exists")]
    NoValidTriangulation,
    /// A coordinate of this point is NaN, infinite, or of a magnitude
    /// outside [`MIN_COORDINATE`, `MAX_COORDINATE`] (zero is fine), where
    /// the exact predicates could overflow or underflow, so no answer could
    /// be trusted. A [`crate::Curve`] never has such points.
    #[error(
        "point {0} has a coordinate that is not finite or outside the range [1e-30, 1e30] where the predicates are exact; rescale the points"
    )]
    OutOfRange(usize),
    /// More points than the dynamic program accepts (its tables take
    /// O(n²) memory and its time grows as n³); simplify the curve.
    #[error(
        "{n} points is more than the {limit} this triangulation accepts (memory grows as n², time as n³); simplify the curve"
    )]
    TooManyPoints {
        /// Points given.
        n: usize,
        /// The limit of the triangulator asked.
        limit: usize,
    },
    /// The max–min-angle DP would weigh more candidate triangles than it
    /// accepts (its time grows with them, up to n³/6 on a nearly convex
    /// curve); refused before it starts. Use the Delaunay quality, or
    /// simplify the curve.
    #[error(
        "this curve needs {} candidate triangles for the max–min triangulation; the limit is {} (about 10 s on 2 cores); use --quality delaunay or simplify the curve",
        thousands(*candidates),
        thousands(*limit)
    )]
    TooManyCandidates {
        /// Candidate triangles `(i, k, j)` over the feasible sub-polygons.
        candidates: u64,
        /// `MAX_MAXMIN_CANDIDATES` (1.5 × 10⁹).
        limit: u64,
    },
}

impl NotSelfOverlapping {
    /// True when this is an answer about the curve (it is not
    /// self-overlapping); false when no answer could be computed (points
    /// out of range, too many points), which is bad input.
    pub fn is_answer(&self) -> bool {
        !matches!(
            self,
            NotSelfOverlapping::OutOfRange(_)
                | NotSelfOverlapping::TooManyPoints { .. }
                | NotSelfOverlapping::TooManyCandidates { .. }
                | NotSelfOverlapping::Degenerate
        )
    }
}

/// `x` with commas between groups of three digits.
fn thousands(x: u64) -> String {
    let digits = x.to_string();
    let mut out = String::with_capacity(digits.len() * 4 / 3);
    for (at, c) in digits.chars().enumerate() {
        if at > 0 && (digits.len() - at) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// Most points the decision DP accepts: its four n × n bit tables take
/// n²/2 bytes (200 MB at this limit) and its time grows as n³/64 at worst.
pub(crate) const MAX_DP_POINTS: usize = 20_000;

/// Check the preconditions shared by every triangulator: at least 3 points,
/// every coordinate in the predicates' exact range, and turning number
/// exactly +1.
pub(crate) fn precheck(points: &[Point]) -> Result<(), NotSelfOverlapping> {
    if points.len() < 3 {
        return Err(NotSelfOverlapping::Degenerate);
    }
    if points.len() > MAX_DP_POINTS {
        return Err(NotSelfOverlapping::TooManyPoints {
            n: points.len(),
            limit: MAX_DP_POINTS,
        });
    }
    let in_range = |v: f64| v == 0.0 || (MIN_COORDINATE..=MAX_COORDINATE).contains(&v.abs());
    if let Some(i) = points
        .iter()
        .position(|p| !(in_range(p.x) && in_range(p.y)))
    {
        return Err(NotSelfOverlapping::OutOfRange(i));
    }
    // All on one line (a polygon of two points, or of inserted points on a
    // segment): no area, and not a cusp of a real curve.
    let a = points[0];
    let flat = match points.iter().find(|&&p| p != a) {
        None => true,
        Some(&b) => points
            .iter()
            .all(|&p| crate::geom::orient(a, b, p) == crate::geom::Orientation::Collinear),
    };
    if flat {
        return Err(NotSelfOverlapping::Degenerate);
    }
    match turning_number(points) {
        Turning::Number(1) => Ok(()),
        Turning::Number(k) => Err(NotSelfOverlapping::TurningNumber(k)),
        Turning::Cusp(i) => Err(NotSelfOverlapping::Cusp(i)),
    }
}

/// Triangulate the immersed disk bounded by `points`, or say why there is
/// none. Returns the DP's witness: some valid triangulation, not a good one
/// (see [`crate::triangulate_with`]).
///
/// Any point list is accepted. The turning number is checked first and
/// must be +1: a clockwise polygon is rejected with
/// [`NotSelfOverlapping::TurningNumber`]`(-1)`, never reversed here.
///
/// # Errors
///
/// [`NotSelfOverlapping`]: fewer than 3 points or all on one line
/// ([`NotSelfOverlapping::Degenerate`]), no valid triangulation
/// ([`NotSelfOverlapping::NoValidTriangulation`]), a turning number other
/// than 1, a cusp, or a coordinate outside the exact range
/// ([`NotSelfOverlapping::OutOfRange`]).
pub fn triangulate(points: &[Point]) -> Result<Immersion, NotSelfOverlapping> {
    triangulate_progress(points, &mut |_| {})
}

/// [`triangulate`] with a progress callback that receives the fraction of
/// the work done, in [0, 1].
///
/// # Errors
///
/// As [`triangulate`].
pub(crate) fn triangulate_progress(
    points: &[Point],
    progress: &mut dyn FnMut(f64),
) -> Result<Immersion, NotSelfOverlapping> {
    precheck(points)?;
    let table = dp::decide(points, progress);
    let triangles = dp::witness(points, &table);
    debug_assert_eq!(
        triangles.is_some(),
        table.get(0, points.len() - 1),
        "the witness search disagrees with the decision table: a bug"
    );
    let mut triangles = triangles.ok_or(NotSelfOverlapping::NoValidTriangulation)?;
    triangles.sort_unstable();
    Ok(Immersion {
        points: points.to_vec(),
        triangles,
    })
}

/// A triangulation that is an immersion triangulation of every curve in
/// `curves` at once (same number of points; point `v` of each curve
/// corresponds), or `None` when there is none. Curves with a common
/// triangulation morph into each other without a single edge flip: the
/// compatible morph of docs/design.md §5 applies directly.
///
/// The decision DP of the first curve with each chord filtered by every
/// curve's fan cones and each apex tested on every curve: the cost of about
/// one decision per curve, exact predicates throughout.
///
/// ```
/// use immerse::Point;
/// use immerse::{common_triangulation, Immersion};
/// let square = [Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(1.0, 1.0), Point::new(0.0, 1.0)];
/// // A dart (vertex 3 is reflex): only the diagonal 1–3 is inside it.
/// let dart = [Point::new(0.0, 0.0), Point::new(2.0, -2.0), Point::new(4.0, 0.0), Point::new(2.0, -1.0)];
/// let t = common_triangulation(&[&square, &dart]).expect("a common triangulation");
/// assert_eq!(t, vec![[0, 1, 3], [1, 2, 3]]);
/// for curve in [&square[..], &dart[..]] {
///     assert!(Immersion { points: curve.to_vec(), triangles: t.clone() }.is_immersion());
/// }
/// ```
pub fn common_triangulation(curves: &[&[Point]]) -> Option<Vec<[u32; 3]>> {
    let n = curves.first()?.len();
    if curves.iter().any(|c| c.len() != n || precheck(c).is_err()) {
        return None;
    }
    common_triangulation_with(curves, curves.iter().map(|c| CurveMasks::new(c)).collect())
}

/// The half-plane masks of a curve, for [`common_triangulation_with`]:
/// computed once, relabelled cheaply.
#[derive(Clone, Debug)]
pub(crate) struct CurveMasks(valid::HalfPlanes);

impl CurveMasks {
    pub(crate) fn new(points: &[Point]) -> Self {
        CurveMasks(valid::HalfPlanes::new(points))
    }

    /// The masks of `points[(v + shift) % n]` as vertex `v`.
    pub(crate) fn rotated(&self, shift: usize) -> Self {
        CurveMasks(self.0.rotated(shift))
    }
}

/// [`common_triangulation`] with each curve's masks given (`masks[i]` of
/// `curves[i]`).
pub(crate) fn common_triangulation_with(
    curves: &[&[Point]],
    masks: Vec<CurveMasks>,
) -> Option<Vec<[u32; 3]>> {
    let n = curves.first()?.len();
    if curves.iter().any(|c| c.len() != n || precheck(c).is_err()) {
        return None;
    }
    let planes = masks.into_iter().map(|m| m.0).collect();
    let table = dp::decide_common_with(curves, planes, &dp::ANY, &mut |_| {});
    let mut triangles = dp::witness_common(curves, &table, &dp::ANY)?;
    triangles.sort_unstable();
    Some(triangles)
}

/// Bytes of working memory the decision DP uses for `n` points (reported by
/// the benchmarks).
pub(crate) fn dp_memory_bytes(n: usize) -> usize {
    let words = n.div_ceil(64).max(1);
    let summary = words.div_ceil(64);
    // Q rows, Q columns, half-plane masks and their transpose; the two
    // summaries; the bad-vertex row; a box of four f64 per word of points.
    (4 * n * words + 2 * n * summary + words) * 8 + n.div_ceil(64) * 32
}

#[cfg(test)]
mod tests {
    #[test]
    fn thousands_are_grouped() {
        assert_eq!(super::thousands(0), "0");
        assert_eq!(super::thousands(999), "999");
        assert_eq!(super::thousands(1000), "1,000");
        assert_eq!(super::thousands(7_671_151_536), "7,671,151,536");
    }
    use super::*;
    use crate::testing::{grid_rounds, unit_rng};

    /// Exhaustive: does any triangulation of 0..n use only valid triangles?
    fn brute(points: &[Point], i: usize, j: usize) -> bool {
        brute_common(&[points], i, j)
    }

    #[test]
    fn dp_agrees_with_recursion_including_degenerate_inputs() {
        let (pos, neg) = grid_rounds(11, 3000, (3, 8.0), (3, 3.0), |n, point| {
            let pts: Vec<Point> = (0..n).map(|_| point()).collect();
            let table = dp::decide(&pts, &mut |_| {});
            let expect = brute(&pts, 0, n - 1);
            assert_eq!(table.get(0, n - 1), expect, "{pts:?}");
            let w = dp::witness(&pts, &table);
            assert_eq!(w.is_some(), expect);
            let Some(mut t) = w else {
                return Some(false);
            };
            t.sort_unstable();
            assert_eq!(check(&pts, &t), Ok(()), "{pts:?}");
            Some(true)
        });
        assert!(pos > 200 && neg > 200, "{pos} {neg}");
    }

    /// Exhaustive: a triangulation of 0..n valid on every curve?
    fn brute_common(curves: &[&[Point]], i: usize, j: usize) -> bool {
        if j == i + 1 {
            return true;
        }
        (i + 1..j).any(|k| {
            curves.iter().all(|c| is_valid_triangle(c, i, k, j))
                && brute_common(curves, i, k)
                && brute_common(curves, k, j)
        })
    }

    #[test]
    fn common_triangulation_agrees_with_exhaustive_search() {
        let (pos, neg) = grid_rounds(29, 20000, (4, 7.0), (3, 3.0), |n, point| {
            let mut curve = || -> Vec<Point> { (0..n).map(|_| point()).collect() };
            let (a, b) = (curve(), curve());
            // Only pairs where each curve alone is an immersed disk ask the
            // common question (others are refused before the DP).
            if !brute(&a, 0, n - 1)
                || !brute(&b, 0, n - 1)
                || precheck(&a).is_err()
                || precheck(&b).is_err()
            {
                return None;
            }
            let curves = [&a[..], &b[..]];
            let expect = brute_common(&curves, 0, n - 1);
            let got = common_triangulation(&curves);
            assert_eq!(got.is_some(), expect, "{a:?} {b:?}");
            let Some(t) = got else {
                return Some(false);
            };
            assert_eq!(check(&a, &t), Ok(()), "{a:?}");
            assert_eq!(check(&b, &t), Ok(()), "{b:?}");
            Some(true)
        });
        assert!(pos > 20 && neg > 20, "{pos} {neg}");
    }

    #[test]
    fn every_cell_agrees_with_a_naive_dp_across_words() {
        // A noisy spiral strip with n > 128: many true and false cells, rows
        // and columns spanning several words.
        let mut r = unit_rng(3);
        let n = 140;
        let half = n / 2;
        let at = |i: usize, r0: f64| {
            let a = i as f64 / (half - 1) as f64 * 9.0;
            Point::new((r0 + 0.3 * a) * a.cos(), (r0 + 0.3 * a) * a.sin())
        };
        let mut pts: Vec<Point> = (0..half).map(|i| at(i, 2.0)).collect();
        pts.extend((0..half).rev().map(|i| at(i, 1.0)));
        for p in &mut pts {
            *p += Point::new(r() - 0.5, r() - 0.5) * 0.2;
        }
        let table = dp::decide(&pts, &mut |_| {});
        let mut q = vec![vec![false; n]; n];
        let (mut yes, mut no) = (0, 0);
        for i in (0..n - 1).rev() {
            q[i][i + 1] = true;
            for j in i + 2..n {
                q[i][j] = table.may_be_diagonal(i, j)
                    && (i + 1..j).any(|k| q[i][k] && q[k][j] && is_valid_triangle(&pts, i, k, j));
                assert_eq!(table.get(i, j), q[i][j], "cell ({i}, {j})");
                assert_eq!(table.cols.get(j, i), q[i][j], "cell ({i}, {j})");
                if q[i][j] { yes += 1 } else { no += 1 }
            }
        }
        assert!(yes > 500 && no > 500, "{yes} {no}");
    }

    #[test]
    fn no_panic_on_strange_input() {
        let nan = Point::new(f64::NAN, 0.0);
        let inf = Point::new(f64::INFINITY, 1.0);
        let o = Point::ZERO;
        let x = Point::X;
        for pts in [
            vec![],
            vec![o],
            vec![o, x],
            vec![o, o, o],
            vec![o, x, nan, inf],
            vec![nan, nan, nan, nan],
            vec![o, x, Point::new(2.0, 0.0)],
        ] {
            let _ = triangulate(&pts);
        }
        assert_eq!(
            triangulate(&[o, x, Point::new(0.0, -1.0)]),
            Err(NotSelfOverlapping::TurningNumber(-1))
        );
    }

    /// Regression (fuzz target `check_points`, seed
    /// `fuzz/seeds/check_points/regression-out-of-range`): with a
    /// coordinate of 8e303 the predicates overflow, and the DP accepted a
    /// triangle that the independent check refused. Such input is now
    /// refused as out of range; the same triangle at a sane scale is fine.
    #[test]
    fn out_of_range_coordinates_are_refused() {
        let pts = [
            Point::new(-8.235879855805179e303, -5.267939904436367e178),
            Point::new(2e-323, 0.0),
            Point::ZERO,
        ];
        assert_eq!(triangulate(&pts), Err(NotSelfOverlapping::OutOfRange(0)));
        let mut pts = pts;
        pts[0] = Point::new(-8.0, -5.0);
        assert_eq!(triangulate(&pts), Err(NotSelfOverlapping::OutOfRange(1)));
        pts[1] = Point::new(1e-30, 0.0);
        let imm = triangulate(&pts).unwrap();
        assert_eq!(check(&imm.points, &imm.triangles), Ok(()));
        assert_eq!(
            triangulate(&[Point::X, Point::new(1.0, 1e31), Point::Y]),
            Err(NotSelfOverlapping::OutOfRange(1))
        );
    }
}
