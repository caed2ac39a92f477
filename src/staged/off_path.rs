//! Keys off the path (docs/design.md §12, "Keys off the path"): for a
//! segment between two keys that no key taken from the leg's path
//! certifies, and no flip of its triangulation either.
//!
//! Such a segment is short in the leg's parameter (split down to its
//! finest step) and holds a feature the keys' doubles barely carry: a
//! needle whose short edge is a few units in the last place, or a shape
//! that grows by many times its size within the finest step. Two routes,
//! each certified exactly segment by segment, so that trying them costs
//! time but never validity:
//!
//! 1. **A bridge.** A compatible morph planned between the two keys on the
//!    leg's triangulation (both are valid), whose straight path (else its
//!    hybrid, else its rigid one) is split in its own parameter, far finer
//!    than the leg's finest step, until every segment is certified.
//! 2. **The feature enlarged.** The vertices around the failing triangle
//!    (or fan) that lie far closer to each other than to any other vertex
//!    are scaled up about one of them by a power of two, at both keys: the
//!    scaling is exact in doubles (checked), so the straight motion from a
//!    key to its enlarged copy is a pure scaling of that cluster and keeps
//!    its triangles' orientation for every s. The bridge is then planned
//!    between the enlarged keys, where the feature is many units in the
//!    last place wide. The enlargement stays within a tenth of the key
//!    tolerance.
//!
//! Every key added stays within the key tolerance of the chord it
//! replaces.

use crate::certify::{Defect, Player, certify_segment, segment_holds};
use crate::geom::Point;
use crate::immersion::{CheckedTriangles, check_triangles};
use crate::propagate::compatible::Compatible;
use crate::propagate::paths::ThirdVertexPath;
use crate::tree::{DualTree, Root, RootChoice};

/// Deepest split of a bridge, in its own parameter (a bridge spans one
/// segment of the leg, itself down to 2⁻⁴⁴ of the leg).
const MAX_DEPTH: u32 = 24;

/// Most keys a bridge may add to one segment: both routes are tried with
/// the first bound, then again with the second (a needle 4·10⁻⁵ wide that
/// moves 27 units, stress pair 1552, keeps 5,225), so that a segment a
/// smaller bridge certifies keeps the fewer keys it needs.
const MAX_KEYS: [usize; 2] = [1 << 12, 1 << 14];

/// Most exact segment certificates the search for one segment's keys may
/// take, over both routes and both key bounds: past it the segment is left
/// uncertified (its frames are still checked exactly). On the CI's 2,000
/// stress pairs the largest search takes 49,817; on 2,000 pairs of seed
/// 0xbee5, 383,438 (pair 1552: a needle 4·10⁻⁵ wide moved 27 units,
/// about 5,000 keys on one segment).
pub(crate) const MAX_WORK: usize = 1 << 19;

/// Most certificates one leg's searches that fail may take in all, in the
/// order of its segments: past it the leg's segments left are not
/// searched (a leg whose searches keep failing is given up after two at
/// least; searches that succeed are not counted, however many).
pub(crate) const MAX_FAILED_WORK: usize = 1 << 20;

/// Segments searched side by side, a batch at a time, so that where the
/// searches stop never depends on the number of cores.
pub(crate) const SEARCH_BATCH: usize = 8;

/// The certificates a leg's failed searches may still take
/// ([`MAX_FAILED_WORK`]).
pub(crate) struct Budget(std::cell::Cell<usize>);

impl Budget {
    pub(crate) fn new() -> Budget {
        Budget(std::cell::Cell::new(MAX_FAILED_WORK))
    }

    /// Whether the failed searches have taken it all.
    pub(crate) fn is_spent(&self) -> bool {
        self.0.get() == 0
    }

    /// Counts a search's result: the certificates it took are spent when
    /// it failed.
    pub(crate) fn count<T>(&self, searched: (Option<T>, usize)) -> Option<T> {
        let (keys, work) = searched;
        if keys.is_none() {
            self.0.set(self.0.get().saturating_sub(work));
        }
        keys
    }
}

/// [`off_path_keys`] within [`MAX_WORK`] certificates, and how many it
/// took.
pub(crate) fn search(
    a: &[Point],
    b: &[Point],
    tris: &[[u32; 3]],
    fan_margin: f64,
    tol: f64,
) -> (Option<Vec<Vec<Point>>>, usize) {
    let work = std::cell::Cell::new(MAX_WORK);
    let keys = off_path_keys(a, b, tris, fan_margin, tol, &work);
    (keys, MAX_WORK - work.get())
}

/// Most clusters tried around one failure, smallest first.
const MAX_CLUSTERS: usize = 3;

/// How much closer a cluster's vertices are to each other than to the
/// nearest other vertex, at the least.
const CLUSTER_GAP: f64 = 8.0;

/// The keys strictly between `a` and `b` (two valid shapes under `tris`,
/// the ends of a segment that is not certified) such that every straight
/// segment from `a` through them to `b` is certified for every s in exact
/// arithmetic, each within `tol` of the chord from `a` to `b`; `None`
/// where neither route finds them within `work` certificates (what is
/// left of it is left in it).
fn off_path_keys(
    a: &[Point],
    b: &[Point],
    tris: &[[u32; 3]],
    fan_margin: f64,
    tol: f64,
    work: &std::cell::Cell<usize>,
) -> Option<Vec<Vec<Point>>> {
    let checked = CheckedTriangles::new(a.len(), tris);
    let gap = Gap {
        a,
        b,
        tris: &checked,
        fan_margin,
        tol,
        work,
    };
    let inner = MAX_KEYS
        .into_iter()
        .find_map(|most| gap.bridged(most).or_else(|| gap.enlarged(most)))?;
    Some(gap.fewest(inner))
}

/// A segment to bridge: two valid shapes under one triangulation, the
/// fan margin its plans lay out with, how far its new keys may stray
/// from its chord, and the certificates the search may still take
/// ([`MAX_WORK`]).
#[derive(Clone, Copy)]
struct Gap<'a> {
    a: &'a [Point],
    b: &'a [Point],
    tris: &'a CheckedTriangles<'a>,
    fan_margin: f64,
    tol: f64,
    work: &'a std::cell::Cell<usize>,
}

impl Gap<'_> {
    /// [`segment_holds`] from `a` to `b` as one unit of the search's
    /// work; `None` once the work is spent.
    fn holds(&self, a: &[Point], b: &[Point]) -> Option<bool> {
        let left = self.work.get().checked_sub(1)?;
        self.work.set(left);
        Some(segment_holds(a, b, self.tris, Player::Exact))
    }

    /// The keys of `inner` that a greedy pass from `a` keeps: from each
    /// kept key, the farthest later one (`farthest_join`: doubling, then
    /// bisection) whose straight segment from it is certified, so that a
    /// bridge split at midpoints keeps only the keys it needs. Every
    /// segment between kept keys is certified; each kept key keeps within
    /// the tolerance of its chord, and so does every point between two of
    /// them (the distance to a segment is convex).
    fn fewest(&self, inner: Vec<Vec<Point>>) -> Vec<Vec<Point>> {
        let last = inner.len() + 1;
        let at = |i: usize| -> &[Point] {
            match i {
                0 => self.a,
                i if i == last => self.b,
                i => &inner[i - 1],
            }
        };
        let holds = |i: usize, j: usize| segment_holds(at(i), at(j), self.tris, Player::Exact);
        let mut kept = Vec::new();
        let mut i = 0;
        while i < last {
            // i + 1 holds: the split certified it.
            let good = super::farthest_join(i + 1, last + 1, |j| holds(i, j));
            if good < last {
                kept.push(good);
            }
            i = good;
        }
        let mut inner: Vec<Option<Vec<Point>>> = inner.into_iter().map(Some).collect();
        kept.into_iter()
            .filter_map(|k| inner[k - 1].take())
            .collect()
    }

    /// Whether every vertex of `p` lies within the tolerance of its own
    /// straight segment from `a` to `b`.
    fn near(&self, p: &[Point]) -> bool {
        near_chord(self.a, self.b, self.tol, p)
    }

    /// Route 1: the interior keys along the straight path of a compatible
    /// morph from `a` to `b`, split at midpoints until every segment is
    /// certified, each within the tolerance of the chord (the chord's
    /// fraction is the bridge's parameter). Planned from `a`, and only
    /// where that fails from `b` (the layout's rounding differs).
    fn bridged(&self, most: usize) -> Option<Vec<Vec<Point>>> {
        // Rooted at the failing feature, the layout's rounding there is
        // relative to the feature's own size.
        let mut feature: Option<Option<usize>> = None;
        for paths in [&BRIDGE_PATHS[..], &LAST_BRIDGE_PATHS[..]] {
            if let Some(keys) = self.bridged_from(None, paths, most) {
                return Some(keys);
            }
            let root = *feature.get_or_insert_with(|| self.failing_triangle());
            if let Some(keys) = root.and_then(|t| self.bridged_from(Some(t), paths, most)) {
                return Some(keys);
            }
        }
        None
    }

    /// The triangle where the straight motion from `a` to `b` first fails
    /// (for a fan, a triangle of it).
    fn failing_triangle(&self) -> Option<usize> {
        let failure = certify_segment(self.a, self.b, self.tris.triangles(), Player::Exact)
            .ok()?
            .failure?;
        match failure.defect {
            Defect::Triangle { index, .. } => Some(index),
            Defect::Fan { vertex } => self
                .tris
                .triangles()
                .iter()
                .position(|t| t.contains(&(vertex as u32))),
            Defect::Start(_) => None,
        }
    }

    /// [`Gap::bridged`] along `paths`, with plans rooted as
    /// [`RootChoice::Disk`] says, or at triangle `root`, adding at most
    /// `most` keys.
    fn bridged_from(
        &self,
        root: Option<usize>,
        paths: &[ThirdVertexPath],
        most: usize,
    ) -> Option<Vec<Vec<Point>>> {
        let tree = DualTree::new(self.a.len(), self.tris.triangles()).ok()?;
        let root = root.map_or(Root::Choice(RootChoice::Disk), Root::Triangle);
        for back in [false, true] {
            let (from, to) = if back {
                (self.b, self.a)
            } else {
                (self.a, self.b)
            };
            let plan = Compatible::on_tree(from, to, &tree, root, self.fan_margin);
            let Ok(plan) = plan else {
                continue;
            };
            for &p in paths {
                let path = |u: f64| plan.positions(if back { 1.0 - u } else { u }, p);
                let mut keys = Vec::new();
                let mut budget = most;
                let split = Split {
                    path: &path,
                    gap: self,
                };
                if split.run(
                    (0.0, self.a),
                    (1.0, self.b),
                    MAX_DEPTH,
                    &mut keys,
                    &mut budget,
                ) {
                    return Some(keys);
                }
            }
        }
        None
    }

    /// Route 2: the cluster around the segment's first failure enlarged
    /// at both keys, and the bridge between the enlarged keys; the
    /// interior keys are the enlarged `a`, the bridge's keys and the
    /// enlarged `b`.
    fn enlarged(&self, most: usize) -> Option<Vec<Vec<Point>>> {
        let (a, b) = (self.a, self.b);
        let failure = certify_segment(a, b, self.tris.triangles(), Player::Exact)
            .ok()?
            .failure?;
        let corners: Vec<usize> = match failure.defect {
            Defect::Triangle { corners, .. } => corners.iter().map(|&c| c as usize).collect(),
            Defect::Fan { vertex } => vec![vertex],
            Defect::Start(_) => return None,
        };
        // The feature's size: its corners' largest distance at either key.
        let size = corners
            .iter()
            .flat_map(|&i| corners.iter().map(move |&j| (i, j)))
            .map(|(i, j)| (a[i] - a[j]).length().max((b[i] - b[j]).length()))
            .fold(0.0f64, f64::max);
        corners
            .iter()
            .find_map(|&centre| self.enlarged_about(centre, size, most))
    }

    /// Route 2 about the corner `centre` of a failing feature of `size`.
    fn enlarged_about(&self, centre: usize, size: f64, most: usize) -> Option<Vec<Vec<Point>>> {
        let (a, b, checked) = (self.a, self.b, self.tris);
        let tris = checked.triangles();
        // Every vertex by its larger distance from the centre at the two keys.
        let mut by_distance: Vec<(f64, usize)> = (0..a.len())
            .map(|i| {
                let d = (a[i] - a[centre]).length().max((b[i] - b[centre]).length());
                (d, i)
            })
            .collect();
        by_distance.sort_by(|x, y| x.0.total_cmp(&y.0));
        let cuts = (0..by_distance.len().saturating_sub(1)).filter(|&j| {
            let r = by_distance[j].0.max(size);
            by_distance[j].0 >= size && by_distance[j + 1].0 > CLUSTER_GAP * r
        });
        for j in cuts.take(MAX_CLUSTERS) {
            let radius = by_distance[j].0.max(size);
            if radius.is_nan() || radius <= 0.0 {
                continue;
            }
            let gap = by_distance[j + 1].0;
            let cluster: Vec<usize> = by_distance[..=j].iter().map(|&(_, i)| i).collect();
            // The scale: a power of two keeping the cluster well inside its
            // gap and its moves within a tenth of the tolerance.
            let largest = (gap / (4.0 * radius)).min(0.1 * self.tol / radius);
            if largest.is_nan() || largest < 2.0 {
                continue;
            }
            let mut exponent = largest.log2().floor() as i32;
            while exponent >= 1 {
                let scale = 2f64.powi(exponent);
                exponent -= 2;
                let (Some(ea), Some(eb)) = (
                    scaled(a, &cluster, centre, scale),
                    scaled(b, &cluster, centre, scale),
                ) else {
                    continue;
                };
                if check_triangles(&ea, tris).is_err() || check_triangles(&eb, tris).is_err() {
                    continue;
                }
                let ends = match self.holds(a, &ea)? {
                    true => self.holds(&eb, b)?,
                    false => false,
                };
                if !ends {
                    continue;
                }
                let inside = Gap {
                    a: &ea,
                    b: &eb,
                    tol: self.tol - scale * radius,
                    ..*self
                };
                if let Some(mut inner) = inside.bridged(most) {
                    inner.insert(0, ea);
                    inner.push(eb);
                    return Some(inner);
                }
            }
        }
        None
    }
}

/// Whether every vertex of `p` lies within `tol` of its own straight
/// segment from `a` to `b`.
pub(crate) fn near_chord(a: &[Point], b: &[Point], tol: f64, p: &[Point]) -> bool {
    p.iter().zip(a.iter().zip(b)).all(|(x, (a, b))| {
        let d = *b - *a;
        let len2 = d.length_squared();
        let w = if len2 > 0.0 {
            ((*x - *a).dot(d) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (*x - a.lerp(*b, w)).length() <= tol
    })
}

/// The bridge's paths, in order: the straightest first, then the two
/// that lay the shape out from angles, whose layout a rounding turns
/// over elsewhere.
const BRIDGE_PATHS: [ThirdVertexPath; 3] = [
    ThirdVertexPath::Straight,
    ThirdVertexPath::Hybrid,
    ThirdVertexPath::Rigid,
];

/// The bridge's paths where none of [`BRIDGE_PATHS`] holds, from either
/// root: the two that interpolate each triangle's angles and scale
/// without a guide, so that a feature whose straight path draws its
/// vertices together is not pinched.
const LAST_BRIDGE_PATHS: [ThirdVertexPath; 2] = [ThirdVertexPath::Angle, ThirdVertexPath::Polar];

/// A bridge being split.
struct Split<'a> {
    path: &'a dyn Fn(f64) -> Vec<Point>,
    gap: &'a Gap<'a>,
}

impl Split<'_> {
    /// Appends to `keys` the keys strictly between `a` and `b` (parameter,
    /// shape); false where the segment cannot be certified within the
    /// depth and the budget.
    fn run(
        &self,
        a: (f64, &[Point]),
        b: (f64, &[Point]),
        depth: u32,
        keys: &mut Vec<Vec<Point>>,
        budget: &mut usize,
    ) -> bool {
        let tris = self.gap.tris;
        match self.gap.holds(a.1, b.1) {
            Some(true) => return true,
            Some(false) => {}
            None => return false,
        }
        if depth == 0 || *budget == 0 {
            return false;
        }
        *budget -= 1;
        let um = 0.5 * (a.0 + b.0);
        let m = (self.path)(um);
        if check_triangles(&m, tris.triangles()).is_err() || !self.gap.near(&m) {
            return false;
        }
        if !self.run(a, (um, &m), depth - 1, keys, budget) {
            return false;
        }
        keys.push(m.clone());
        self.run((um, &m), b, depth - 1, keys, budget)
    }
}

/// `p` with the vertices of `cluster` scaled by `scale` (a power of two)
/// about vertex `centre`; `None` unless every step is exact in doubles (so
/// the straight motion from `p` to the result scales the cluster exactly).
fn scaled(p: &[Point], cluster: &[usize], centre: usize, scale: f64) -> Option<Vec<Point>> {
    let c = p[centre];
    let mut q = p.to_vec();
    for &i in cluster {
        let mut x = [0.0; 2];
        for (axis, out) in x.iter_mut().enumerate() {
            let d = exact_sum(p[i][axis], -c[axis])?;
            let far = d * scale;
            if !far.is_finite() || far / scale != d {
                return None;
            }
            *out = exact_sum(c[axis], far)?;
        }
        q[i] = Point::new(x[0], x[1]);
    }
    Some(q)
}

/// `a + b` where it is exact in doubles (Knuth's two-sum has no error
/// term), else `None`.
fn exact_sum(a: f64, b: f64) -> Option<f64> {
    let s = a + b;
    let bb = s - a;
    let err = (a - (s - bb)) + (b - bb);
    (s.is_finite() && err == 0.0).then_some(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A search takes at most [`MAX_WORK`] certificates, and a leg's
    /// budget counts only the searches that fail: a square turned half a
    /// turn in one straight segment (every vertex through the centre at
    /// s = ½) has no keys within a hundredth of its chord, and every route
    /// fails at its first split; a square moved along its chord needs no
    /// key at all.
    #[test]
    fn failed_searches_spend_the_budget_and_stop_at_it() {
        let a: Vec<Point> = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
            .map(|(x, y)| Point::new(x, y))
            .to_vec();
        let turned: Vec<Point> = a.iter().map(|p| Point::new(1.0 - p.x, 1.0 - p.y)).collect();
        let moved: Vec<Point> = a.iter().map(|p| Point::new(p.x + 3.0, p.y)).collect();
        let tris = [[0, 1, 2], [0, 2, 3]];
        let (keys, work) = search(&a, &turned, &tris, 0.05, 0.01);
        assert!(keys.is_none() && work > 1 && work < MAX_WORK, "{work}");
        let budget = Budget::new();
        assert_eq!(
            budget.count(search(&a, &moved, &tris, 0.05, 0.01)),
            Some(Vec::new())
        );
        assert_eq!(
            budget.0.get(),
            MAX_FAILED_WORK,
            "a search that succeeds is not counted"
        );
        assert_eq!(budget.count((None::<()>, work)), None);
        assert_eq!(budget.0.get(), MAX_FAILED_WORK - work);
        assert!(!budget.is_spent());
        budget.count((None::<()>, MAX_FAILED_WORK));
        assert!(
            budget.is_spent(),
            "a failure past what is left spends it all"
        );
    }

    /// A cluster scaled by a power of two keeps every offset from its
    /// centre exactly (so the straight motion to it is a pure scaling);
    /// where the scaled vertex cannot be held exactly, nothing is scaled.
    #[test]
    fn a_cluster_is_scaled_exactly_or_not_at_all() {
        let c = Point::new(0.3, 0.7);
        let ulp = f64::EPSILON / 2.0;
        let p = vec![
            c,
            Point::new(0.3 + 3.0 * ulp, 0.7),
            Point::new(0.3, 0.7 + 5.0 * ulp),
            Point::new(2.0, -1.0),
        ];
        let q = scaled(&p, &[0, 1, 2], 0, 1024.0).expect("exact");
        for i in 0..3 {
            assert_eq!(q[i] - c, (p[i] - c) * 1024.0, "vertex {i}");
            assert!(q[i] != p[i] || i == 0);
        }
        assert_eq!(q[3], p[3], "a vertex outside the cluster stays");
        // 1 + 2⁻⁵² and 1 + 2⁻⁵¹ are one unit in the last place apart; scaled
        // by 2⁵³ that unit is 2, and 3 + 2⁻⁵² is not a double.
        let one = 1.0 + f64::EPSILON;
        let p = vec![Point::new(one, 0.0), Point::new(one + f64::EPSILON, 0.0)];
        assert_eq!(scaled(&p, &[0, 1], 0, 2f64.powi(53)), None);
        assert_eq!(exact_sum(1.0, f64::EPSILON / 4.0), None);
        assert_eq!(exact_sum(1.0, f64::EPSILON), Some(1.0 + f64::EPSILON));
    }
}
