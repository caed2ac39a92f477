//! Morphing one curve into another whose triangulation differs: staged
//! edge flips on the way to an intermediate (docs/design.md §7, §7a). This is
//! the one staged driver; the intermediate and the flip order are its
//! parameters.
//!
//! A *leg* is a compatible morph from the current shape toward an
//! intermediate under the current triangulation. The leg is walked in
//! steps of [`LEG_STEP`]; every step is checked exactly, and at every step
//! the flips whose gate passes are applied (both new triangles valid and
//! their smallest angle at least min(the old pair's, a floor)). After a
//! flip the next leg starts from the current shape under the new
//! triangulation. Once the triangulation is valid on the other curve, a
//! last leg goes there.
//!
//! - **Target** intermediate (the default): the other curve measured with
//!   the current triangulation and made valid (see `target.rs`); a flip
//!   is any diagonal whose flip strictly lowers its crossings with the
//!   goal triangulation, largest gain first. If the target is reached with
//!   flips left, the triangles around the blocked flips take the disk's
//!   angles once (a local unblock); after that the disk finishes the job.
//! - **Disk** intermediate (Mukherjee & Gopi §6.2): a convex disk with the
//!   curve's area; flips follow the insertion sequence of
//!   [`crate::flip::sequence::flip_sequence`]. At the disk every flip is valid, so
//!   the procedure always finishes.
//!
//! Recovery instead of stopping: a leg whose sampled frame fails the exact
//! check is walked again with the next guaranteed path; a target shape
//! that cannot be laid out or that no path reaches hands over to the disk;
//! every such step is recorded as a [`Fallback`].
//!
//! The second stage of a curve morph, above `crate::propagate` (each leg
//! is one of its compatible morphs) and below `crate::morph` (which plans
//! the sides and places their keys, and re-exports [`Fallback`] and
//! [`Intermediate`]).

mod off_path;
pub(crate) mod target;

use crate::flip::canonical;
use crate::flip::sequence::{Flip, FlipTriangulation, flip_sequence, gate};
use crate::geom::Point;
use crate::geom::polygon::{min_triangle_angle as min_angle, signed_area};
use crate::immersion::{CheckedTriangles, check, check_triangles};
use crate::propagate::MorphError;
use crate::propagate::compatible::PlanSeed;
use crate::propagate::compatible::{Compatible, CompatibleError, area_and_centroid};
use crate::propagate::paths::ThirdVertexPath;
use crate::staged::target::{Candidates, TargetAngles, target_shape};
use crate::tree::{DualTree, RootChoice, disk_positions};

/// One recovery: what was done instead of what was asked, and why.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Fallback {
    /// What was done, e.g. "used the hybrid path for the last leg".
    pub what: String,
    /// Why, e.g. the defect of the frame that failed the exact check.
    pub why: String,
}

impl Fallback {
    /// A fallback from its two parts.
    pub fn new(what: &str, why: &str) -> Fallback {
        Fallback {
            what: what.to_string(),
            why: why.to_string(),
        }
    }
}

impl std::fmt::Display for Fallback {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.what, self.why)
    }
}

/// The intermediate that staged flips happen on the way to. With the `cli`
/// feature it is the command line's `--intermediate` (each variant's first
/// doc paragraph is its help there).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Intermediate {
    /// A valid shape that looks like the other curve: overlaps extend instead
    /// of unwinding.
    ///
    /// docs/design.md §7a.
    #[default]
    Target,
    /// A convex disk with the curve's area (Mukherjee & Gopi's route).
    ///
    /// Mukherjee & Gopi §6.2, docs/design.md §7.
    Disk,
}

impl Intermediate {
    /// The CLI name.
    pub fn as_str(self) -> &'static str {
        match self {
            Intermediate::Target => "target",
            Intermediate::Disk => "disk",
        }
    }
}

/// A shape held by several owners: a key of one leg is the start of the
/// next and of its plan's seed ([`LegPlan::release`]), and a route of
/// hundreds of legs would otherwise hold each three times.
pub(crate) type Shape = std::sync::Arc<[Point]>;

/// Step of the walk along one leg, in the leg's own parameter.
pub(crate) const LEG_STEP: f64 = 1.0 / 32.0;

/// One stretch of the path: a compatible morph under a fixed
/// triangulation, used for its local parameter in `[0, s_end]`, with the
/// samples it was checked at and the cumulative largest vertex move at
/// each (the frame timing).
#[derive(Clone, Debug)]
pub(crate) struct Leg {
    pub(crate) plan: LegPlan,
    pub(crate) path: ThirdVertexPath,
    /// Local parameters of the checked samples, from 0 to `s_end`;
    /// once the keys are placed, of the keys (non-decreasing: keys off
    /// the path can share one, [`Leg::certify_off_path`]).
    pub(crate) samples: Vec<f64>,
    /// Cumulative largest vertex move at each sample (0 at the first).
    pub(crate) travel: Vec<f64>,
    /// The positions at each sample: the leg's keys. Between two keys the
    /// animation moves every vertex in a straight line
    /// ([`Leg::refine_keys`] makes them dense enough).
    pub(crate) keys: Vec<Shape>,
    /// Per segment between consecutive keys: whether the straight-line
    /// motion is certified an immersion for every s in exact arithmetic
    /// (`crate::certify`); set by [`Leg::refine_keys`].
    pub(crate) certified: Vec<bool>,
    /// Per segment between consecutive keys: the triangulation
    /// [`Leg::repair_keys`] flipped to where the leg's own left the
    /// segment uncertified (`None`, or missing, for the leg's own).
    pub(crate) repaired: Vec<Option<Vec<[u32; 3]>>>,
    /// The mean over vertices of the distance each travels over the
    /// samples (the numerator of the detour).
    pub(crate) mean_travel: f64,
    /// The least total absolute turning over the samples and the smaller
    /// of the leg's ends' (the unwind of §7b), where measured (last legs).
    pub(crate) least_turning: f64,
    pub(crate) end_turning: f64,
}

/// A leg's plan: kept while the leg is walked, then only what it is built
/// from ([`LegPlan::release`]); built again, bit for bit the same, where
/// it is used (its keys are placed, a frame is recovered on it). A flip
/// route of some thousands of flips walks hundreds of legs, and a plan
/// takes about three times the memory of its seed.
#[derive(Clone, Debug)]
pub(crate) struct LegPlan {
    plan: std::sync::OnceLock<Compatible>,
    seed: Option<PlanSeed>,
}

impl LegPlan {
    fn new(plan: Compatible) -> LegPlan {
        LegPlan {
            plan: std::sync::OnceLock::from(plan),
            seed: None,
        }
    }

    /// Drops the plan, keeping its seed (the one it was built again from,
    /// if it was; else one taken from it that holds a shape of `held` in
    /// place of equal points, [`Compatible::seed_sharing`]).
    pub(crate) fn release(&mut self, held: &[&Shape]) {
        if let Some(plan) = self.plan.take() {
            match &mut self.seed {
                Some(seed) => seed.note_rigid_guide(&plan),
                None => self.seed = Some(plan.seed_sharing(held)),
            }
        }
    }

    /// Reads a plan's input from the seed of a released plan that has not
    /// been built again (without building it), else from the plan.
    fn read<'a, T>(
        &'a self,
        from_seed: impl FnOnce(&'a PlanSeed) -> T,
        from_plan: impl FnOnce(&'a Compatible) -> T,
    ) -> T {
        match (self.plan.get(), &self.seed) {
            (None, Some(seed)) => from_seed(seed),
            _ => from_plan(self),
        }
    }

    /// [`Compatible::triangles`], without building a released plan.
    pub(crate) fn triangles(&self) -> &[[u32; 3]] {
        self.read(PlanSeed::triangles, Compatible::triangles)
    }

    /// [`Compatible::target`], without building a released plan.
    pub(crate) fn target(&self) -> &[Point] {
        self.read(PlanSeed::target, Compatible::target)
    }

    /// [`Compatible::fan_margin`], without building a released plan.
    pub(crate) fn fan_margin(&self) -> f64 {
        self.read(PlanSeed::fan_margin, Compatible::fan_margin)
    }

    /// [`Compatible::has_rigid_guide`], without building a released plan.
    pub(crate) fn has_rigid_guide(&self) -> bool {
        self.read(PlanSeed::has_rigid_guide, Compatible::has_rigid_guide)
    }
}

impl std::ops::Deref for LegPlan {
    type Target = Compatible;

    fn deref(&self) -> &Compatible {
        self.plan.get_or_init(|| {
            self.seed
                .as_ref()
                .expect("a released plan keeps its seed")
                .build()
                .expect("a plan's seed builds it again")
        })
    }
}

impl Leg {
    /// A leg with only its start sample.
    fn start(plan: Compatible, path: ThirdVertexPath) -> Leg {
        let first = Shape::from(plan.source());
        Leg::start_at(plan, path, first)
    }

    /// [`Leg::start`] from `first`, the plan's source itself (held, not
    /// copied).
    fn start_at(plan: Compatible, path: ThirdVertexPath, first: Shape) -> Leg {
        debug_assert!(
            *first == *plan.source(),
            "a leg starts at its plan's source"
        );
        Leg {
            plan: LegPlan::new(plan),
            path,
            samples: vec![0.0],
            travel: vec![0.0],
            keys: vec![first],
            certified: Vec::new(),
            repaired: Vec::new(),
            mean_travel: 0.0,
            least_turning: 0.0,
            end_turning: 0.0,
        }
    }

    /// Whether the leg keeps the overlaps of its ends: its least total
    /// absolute turning is at least 0.9 of the smaller end's (§7b's
    /// unwind).
    fn keeps_overlaps(&self) -> bool {
        self.least_turning >= 0.9 * self.end_turning
    }

    /// Whether this finished last leg is better than `other`: less
    /// travel wins, unless it unwinds overlaps the other keeps.
    fn beats(&self, other: &Leg) -> bool {
        match (self.keeps_overlaps(), other.keeps_overlaps()) {
            (true, false) => true,
            (false, true) => false,
            _ => self.mean_travel < other.mean_travel,
        }
    }

    /// Whether this partly sampled last leg can no longer beat the
    /// finished `other` however it goes on, `ahead` being at least the
    /// travel it still has to go: its travel only grows and its least
    /// turning only falls.
    fn cannot_beat(&self, other: &Leg, ahead: f64) -> bool {
        let travels_more = self.mean_travel + ahead >= other.mean_travel;
        if other.keeps_overlaps() {
            travels_more || !self.keeps_overlaps()
        } else {
            travels_more && !self.keeps_overlaps()
        }
    }

    fn plan_path(&self) -> ThirdVertexPath {
        self.path
    }

    /// The leg's end parameter.
    pub(crate) fn s_end(&self) -> f64 {
        self.samples.last().copied().unwrap_or(0.0)
    }

    /// The leg's total travel.
    pub(crate) fn length(&self) -> f64 {
        self.travel.last().copied().unwrap_or(0.0)
    }

    /// Adds keys until the straight segment between every two consecutive
    /// keys keeps within `tol` of the path at its midpoint (each vertex),
    /// keeps the path's total area there within [`KEY_AREA_TOLERANCE`], and
    /// is certified an immersion for every s in exact arithmetic
    /// (`crate::certify`, docs/design.md §13); then sets the travel table
    /// from the keys: the largest vertex move of each segment, so that
    /// frames placed at equal steps of travel move the fastest vertex at a
    /// constant speed. A segment is split down to [`MIN_KEY_STEP`] of the
    /// leg and at most [`MAX_KEY_SPLITS`] times per checked sample. Where no
    /// point of the path inside a segment passes the exact check (the
    /// layout's rounding turns a thin triangle over for a stretch between
    /// two checked samples), the segment follows instead the straight path
    /// planned between its two keys on the same triangulation (a bridge),
    /// split and certified in the same way. Segments left uncertified are
    /// marked in [`Leg::certified`] (frames on them are checked exactly,
    /// with the bridge and the path as recovery). Returns the number of
    /// bridges; `None` when `strict` and a segment is left uncertified
    /// that no flip of its triangulation certifies
    /// (`crate::certify::flip_to_certify`): the keys then stop there (a
    /// plan tried only for keys that are all certified is dropped at
    /// once, [`crate::morph::Tween::new`]).
    pub(crate) fn refine_keys(&mut self, tol: f64, strict: bool) -> Option<usize> {
        let old_samples = std::mem::take(&mut self.samples);
        let old_keys = std::mem::take(&mut self.keys);
        let out = self.keys_along(&old_samples, &old_keys, tol, strict, &|s| {
            self.plan.positions(s, self.path)
        });
        let KeyOut {
            samples,
            keys,
            certified,
            bridges,
            aborted,
            ..
        } = out;
        self.samples = samples;
        self.keys = keys;
        self.set_travel();
        self.certified = certified;
        self.repaired.clear();
        (!aborted).then_some(bridges)
    }

    /// Sets the travel table from the keys: the cumulative largest vertex
    /// move of the segments between them.
    fn set_travel(&mut self) {
        let mut travel = Vec::with_capacity(self.keys.len());
        travel.push(0.0);
        for w in self.keys.windows(2) {
            let step = moves(&w[0], &w[1]).0;
            travel.push(travel.last().copied().unwrap_or(0.0) + step);
        }
        self.travel = travel;
    }

    /// The triangulation of the segment from key `k` to the next: the
    /// leg's, or the one [`Leg::repair_keys`] flipped to.
    pub(crate) fn segment_triangles(&self, k: usize) -> &[[u32; 3]] {
        match self.repaired.get(k) {
            Some(Some(t)) => t,
            _ => self.plan.triangles(),
        }
    }

    /// Repairs each segment that the leg's triangulation leaves
    /// uncertified, where it can, by giving the segment a triangulation of
    /// its own, flipped from the leg's until the segment is certified
    /// (`crate::certify::flip_to_certify`: a nearly collinear triangle at
    /// both keys has an area the rounding of their coordinates decides,
    /// and another triangulation may not need it). The keys stay where
    /// they are; those where the triangulation changes are flip keys,
    /// valid under both. Returns how many segments were repaired.
    pub(crate) fn repair_keys(&mut self) -> usize {
        use rayon::prelude::*;
        if self.certified.iter().all(|&c| c) {
            return 0;
        }
        let tris = self.plan.triangles();
        let repaired: Vec<Option<Vec<[u32; 3]>>> = self
            .certified
            .par_iter()
            .enumerate()
            .map(|(k, &c)| {
                let (a, b) = (&self.keys[k], &self.keys[k + 1]);
                (!c).then(|| {
                    crate::certify::flip_to_certify(a, b, tris, crate::certify::Player::Exact)
                })?
            })
            .collect();
        let count = repaired.iter().flatten().count();
        for (c, r) in self.certified.iter_mut().zip(&repaired) {
            *c |= r.is_some();
        }
        self.repaired = repaired;
        count
    }

    /// Certifies each segment still uncertified after
    /// [`Leg::repair_keys`], where it can, by keys off the leg's path
    /// (`off_path`: a bridge split in its own parameter, or the failing
    /// feature enlarged first), each within `tol` of the segment's chord.
    /// The new keys take parameters evenly spaced inside the segment's
    /// (non-decreasing).
    /// Returns how many segments were certified so.
    pub(crate) fn certify_off_path(&mut self, tol: f64) -> (usize, usize) {
        use rayon::prelude::*;
        if self.certified.iter().all(|&c| c) {
            return (0, 0);
        }
        let (tris, margin) = (self.plan.triangles(), self.plan.fan_margin());
        // The searches that fail spend one budget for the leg, in the
        // order of its segments, a batch searched side by side at a time.
        let budget = off_path::Budget::new();
        let open: Vec<usize> = (0..self.certified.len())
            .filter(|&k| !self.certified[k])
            .collect();
        // Per segment certified so: its new keys and their parameters.
        type Found = (usize, Vec<(f64, Vec<Point>)>);
        let mut found: Vec<Found> = Vec::new();
        for batch in open.chunks(off_path::SEARCH_BATCH) {
            if budget.is_spent() {
                break;
            }
            let searched: Vec<_> = batch
                .par_iter()
                .map(|&k| {
                    let (a, b) = (&self.keys[k], &self.keys[k + 1]);
                    off_path::search(a, b, tris, margin, tol)
                })
                .collect();
            for (&k, result) in batch.iter().zip(searched) {
                let Some(inner) = budget.count(result) else {
                    continue;
                };
                // Parameters spaced evenly inside the segment's, in order
                // (some equal where the segment spans fewer doubles than
                // it gets keys: frames are timed by the keys' moves, and
                // the parameter only places the path's recovery).
                let params = even_params(self.samples[k], self.samples[k + 1], inner.len());
                found.push((k, params.into_iter().zip(inner).collect()));
            }
        }
        if found.is_empty() {
            let across = self.certify_across_keys(tol, &budget);
            return (across, across);
        }
        let count = found.len();
        let segments = self.certified.len();
        let (mut samples, mut keys) = (Vec::new(), Vec::new());
        let (mut certified, mut repaired) = (Vec::new(), Vec::new());
        let old_keys = std::mem::take(&mut self.keys);
        let mut found = found.into_iter().peekable();
        for (k, key) in old_keys.into_iter().enumerate() {
            samples.push(self.samples[k]);
            keys.push(key);
            if k == segments {
                break;
            }
            if let Some((_, inner)) = found.next_if(|(j, _)| *j == k) {
                for (s, p) in inner {
                    certified.push(true);
                    repaired.push(None);
                    samples.push(s);
                    keys.push(p.into());
                }
                certified.push(true);
                repaired.push(None);
            } else {
                certified.push(self.certified[k]);
                repaired.push(self.repaired.get(k).cloned().flatten());
            }
        }
        self.samples = samples;
        self.keys = keys;
        self.certified = certified;
        self.repaired = repaired;
        self.set_travel();
        let across = self.certify_across_keys(tol, &budget);
        (count + across, across)
    }

    /// Certifies each segment that keys off the path leave uncertified, where
    /// it can, by a bridge across it and up to [`MAX_KEYS_ACROSS`] keys
    /// beside it (nearest spans first, the earlier side first): where the
    /// failure sits at a key (a triangle nearly flat there, which the
    /// straight motion from it turns over at once), a bridge that does not
    /// pass through that key may hold. The keys skipped must lie within
    /// `tol` of the wider chord, and so must the bridge's. Returns how many
    /// segments were certified so.
    fn certify_across_keys(&mut self, tol: f64, budget: &off_path::Budget) -> usize {
        if self.certified.iter().all(|&c| c) {
            return 0;
        }
        let (tris, margin) = (self.plan.triangles(), self.plan.fan_margin());
        self.repaired.resize(self.certified.len(), None);
        let mut count = 0;
        let mut k = 0;
        while k < self.certified.len() {
            if self.certified[k] {
                k += 1;
                continue;
            }
            let keys = &self.keys;
            let spans = (1..=MAX_KEYS_ACROSS).flat_map(|wide| {
                (0..=wide).rev().filter_map(move |before| {
                    let lo = k.checked_sub(before)?;
                    let hi = k + 1 + (wide - before);
                    (hi < keys.len()).then_some((lo, hi))
                })
            });
            let repaired = &self.repaired;
            let found = spans
                .filter(|&(lo, hi)| {
                    (lo..hi).all(|j| repaired[j].is_none())
                        && keys[lo + 1..hi]
                            .iter()
                            .all(|p| off_path::near_chord(&keys[lo], &keys[hi], tol, p))
                })
                .take_while(|_| !budget.is_spent())
                .find_map(|(lo, hi)| {
                    let inner =
                        budget.count(off_path::search(&keys[lo], &keys[hi], tris, margin, tol))?;
                    Some((lo, hi, inner))
                });
            let Some((lo, hi, inner)) = found else {
                k += 1;
                continue;
            };
            let samples = even_params(self.samples[lo], self.samples[hi], inner.len());
            let added = inner.len();
            self.samples.splice(lo + 1..hi, samples);
            self.keys
                .splice(lo + 1..hi, inner.into_iter().map(Shape::from));
            self.certified
                .splice(lo..hi, std::iter::repeat_n(true, added + 1));
            self.repaired
                .splice(lo..hi, std::iter::repeat_n(None, added + 1));
            count += 1;
            k = lo + added + 1;
        }
        if count > 0 {
            self.set_travel();
        }
        count
    }

    /// The keys of [`Leg::refine_keys`] from the checked samples
    /// `old_samples` (parameters) and `old_keys` (shapes) of the leg's
    /// `path` (its positions at a parameter).
    fn keys_along(
        &self,
        old_samples: &[f64],
        old_keys: &[Shape],
        tol: f64,
        strict: bool,
        path: &dyn Fn(f64) -> Vec<Point>,
    ) -> KeyOut {
        let tris = self.plan.triangles().to_vec();
        let tris = CheckedTriangles::new(old_keys[0].len(), &tris);
        let mut out = KeyOut {
            samples: vec![old_samples[0]],
            keys: vec![old_keys[0].clone()],
            certified: Vec::with_capacity(old_samples.len()),
            bridges: 0,
            budget: MAX_KEY_SPLITS.saturating_mul(old_samples.len()),
            cert_budget: MAX_KEY_SPLITS.saturating_mul(old_samples.len()),
            strict,
            aborted: false,
        };
        let total_area = area_and_centroid(&old_keys[0], tris.triangles()).0.abs();
        for i in 1..old_samples.len() {
            if out.aborted {
                break;
            }
            let (a, b) = (
                (old_samples[i - 1], &old_keys[i - 1][..]),
                (old_samples[i], &old_keys[i][..]),
            );
            // A segment whose neighbours show the path bending far less
            // than `tol` there, whose chord keeps the area and which is
            // certified is kept without laying out the path's midpoint.
            let bend = [
                i.checked_sub(2).map(|h| (h, i - 1, i)),
                (i + 1 < old_samples.len()).then_some((i - 1, i, i + 1)),
            ]
            .into_iter()
            .flatten()
            .map(|(h, j, k)| {
                let (s, p) = (old_samples, old_keys);
                midpoint_bend((s[h], &p[h]), (s[j], &p[j]), (s[k], &p[k]), (a.0, b.0))
            })
            .fold(None, |m: Option<f64>, x| Some(m.map_or(x, |m| m.max(x))));
            let smooth = bend.is_some_and(|d| d <= 0.5 * tol)
                && chord_area_loss(a.1, b.1).abs() <= 0.5 * KEY_AREA_TOLERANCE * total_area;
            if smooth
                && crate::certify::segment_holds(a.1, b.1, &tris, crate::certify::Player::Exact)
            {
                out.push(b, true);
                continue;
            }
            self.split(a, b, &tris, tol, &mut out, path, false);
        }
        out
    }

    /// The plan of a bridge from `a` to `b`, two valid shapes of this leg
    /// (keys): a compatible morph between them on the leg's
    /// triangulation, whose straight path runs from one to the other
    /// close to the chord (within the area range of its own ends: held to
    /// the leg's, its fitted area left the chord's where the chord's
    /// strays, and frames jumped between the two). Used where the leg's
    /// own path fails the exact check between two keys; `None` where a
    /// shape is not valid.
    pub(crate) fn bridge(&self, a: &[Point], b: &[Point]) -> Option<Compatible> {
        let tris = self.plan.triangles();
        Compatible::new(a, b, tris, RootChoice::Disk, self.plan.fan_margin()).ok()
    }

    /// Appends the keys of the segment from `a` to `b` (without `a`'s),
    /// splitting it at its midpoint while the path strays from the segment
    /// by more than `tol` there, loses area along it, or the segment is not
    /// certified.
    #[allow(
        clippy::too_many_arguments,
        reason = "the segment, its triangulation, the tolerance, the output and the path followed"
    )]
    fn split(
        &self,
        a: (f64, &[Point]),
        b: (f64, &[Point]),
        checked: &CheckedTriangles<'_>,
        tol: f64,
        out: &mut KeyOut,
        path: &dyn Fn(f64) -> Vec<Point>,
        bridged: bool,
    ) {
        if out.aborted {
            return;
        }
        let tris = checked.triangles();
        let certified =
            || crate::certify::segment_holds(a.1, b.1, checked, crate::certify::Player::Exact);
        // Following the path closely (position and area) and certifying
        // the segment draw on separate budgets, so that a stretch the path
        // is hard to follow on (a strip thinner than its moves) cannot use
        // up the splits another stretch needs to be certified.
        let follow = out.budget > 0;
        if b.0 - a.0 > MIN_KEY_STEP && (follow || out.cert_budget > 0) {
            if !follow && certified() {
                out.push(b, true);
                return;
            }
            // The path's midpoint, or where that fails the exact check (a
            // thin triangle turned over in the layout's rounding), another
            // point of the path inside the segment.
            let inside = SPLIT_AT.iter().find_map(|&f| {
                let sm = a.0 + f * (b.0 - a.0);
                if sm <= a.0 || sm >= b.0 {
                    return None;
                }
                let pm = path(sm);
                check_triangles(&pm, tris).is_ok().then_some((sm, pm))
            });
            if let Some((sm, pm)) = inside {
                let strays = || {
                    pm.iter()
                        .zip(a.1.iter().zip(b.1))
                        .any(|(m, (p, q))| (*m - (*p + *q) * 0.5).length() > tol)
                };
                // The straight segment also keeps the path's total area
                // (a thin strip turning can lose much of its area along a
                // chord that keeps within `tol`).
                let shrinks = || {
                    let mid: Vec<Point> =
                        a.1.iter().zip(b.1).map(|(p, q)| p.lerp(*q, 0.5)).collect();
                    let (on_path, on_chord) = (
                        area_and_centroid(&pm, tris).0,
                        area_and_centroid(&mid, tris).0,
                    );
                    (on_chord - on_path).abs() > KEY_AREA_TOLERANCE * on_path.abs()
                };
                let split = if follow && (strays() || shrinks()) {
                    out.budget -= 1;
                    true
                } else if !follow || !certified() {
                    // (Without the follow budget, the segment was found
                    // uncertified above.)
                    if out.cert_budget == 0 {
                        out.push_uncertified(a.1, b, tris);
                        return;
                    }
                    out.cert_budget -= 1;
                    true
                } else {
                    false
                };
                if split {
                    self.split(a, (sm, &pm), checked, tol, out, path, bridged);
                    self.split((sm, &pm), b, checked, tol, out, path, bridged);
                    return;
                }
                out.push(b, true);
                return;
            }
            // No point of the path inside the segment passes the exact
            // check (thin triangles turned over by the layout's rounding
            // for a stretch): the segment follows the straight path from
            // key to key instead, planned on the leg's triangulation
            // between the two keys (both valid), which keeps close to
            // the chord and is split and certified in the same way.
            if !bridged && let Some(bridge) = self.bridge(a.1, b.1) {
                out.bridges += 1;
                let (s0, s1) = (a.0, b.0);
                let along =
                    |s: f64| bridge.positions((s - s0) / (s1 - s0), ThirdVertexPath::Straight);
                // A bridge draws on the leg's budgets, at most as many
                // splits of each as one checked sample has.
                let (budget, cert_budget) = (out.budget, out.cert_budget);
                out.budget = budget.min(MAX_KEY_SPLITS);
                out.cert_budget = cert_budget.min(MAX_KEY_SPLITS);
                let (lent, cert_lent) = (out.budget, out.cert_budget);
                self.split(a, b, checked, tol, out, &along, true);
                out.budget = budget - (lent - out.budget);
                out.cert_budget = cert_budget - (cert_lent - out.cert_budget);
                return;
            }
        }
        if certified() {
            out.push(b, true);
        } else {
            out.push_uncertified(a.1, b, tris);
        }
    }
}

/// An estimate of how far the path strays from the chord over `seg` (a
/// parameter interval between two of the three keys `h`, `j`, `k`): the
/// middle key's distance from the chord of the outer two gives the path's
/// second derivative (a parabola through the three), and the chord of an
/// interval of length `l` strays `l²|p''|/8` at its midpoint.
fn midpoint_bend(
    h: (f64, &[Point]),
    j: (f64, &[Point]),
    k: (f64, &[Point]),
    seg: (f64, f64),
) -> f64 {
    let (h1, h2) = (j.0 - h.0, k.0 - j.0);
    if !(h1 > 0.0 && h2 > 0.0) {
        return f64::INFINITY;
    }
    let w = h1 / (h1 + h2);
    let d =
        h.1.iter()
            .zip(j.1)
            .zip(k.1)
            .map(|((p, q), r)| (*q - p.lerp(*r, w)).length())
            .fold(0.0f64, f64::max);
    // d = h1·h2·|p''|/2 for a parabola.
    let second = 2.0 * d / (h1 * h2);
    let l = seg.1 - seg.0;
    l * l * second / 8.0
}

/// How much total area the chord from `a` to `b` loses at its midpoint
/// against the mean of its ends' areas: a straight-line motion's signed
/// area is quadratic in s, and its quadratic coefficient is the signed
/// area of the polygon of moves `b − a`, a quarter of which is lost at
/// s = ½.
fn chord_area_loss(a: &[Point], b: &[Point]) -> f64 {
    let n = a.len();
    let d = |i: usize| b[i] - a[i];
    0.25 * 0.5 * (0..n).map(|i| d(i).perp_dot(d((i + 1) % n))).sum::<f64>()
}

/// The keys [`Leg::refine_keys`] builds, and its counters.
struct KeyOut {
    samples: Vec<f64>,
    keys: Vec<Shape>,
    /// Per segment: certified for every s in exact arithmetic.
    certified: Vec<bool>,
    /// Segments that follow the straight path between their keys instead
    /// of the leg's path (no point of it inside passed the exact check).
    bridges: usize,
    /// Splits left to follow the path (position and area).
    budget: usize,
    /// Splits left to certify segments.
    cert_budget: usize,
    /// Whether a segment left uncertified that no flip certifies ends the
    /// keys ([`Leg::refine_keys`]), and whether one did.
    strict: bool,
    aborted: bool,
}

impl KeyOut {
    /// Appends the key `b` (parameter, shape), ending a segment that is
    /// `certified` or not.
    fn push(&mut self, b: (f64, &[Point]), certified: bool) {
        self.certified.push(certified);
        self.samples.push(b.0);
        self.keys.push(b.1.into());
    }

    /// Appends the key `b` ending an uncertified segment from `a` under
    /// `tris`; when strict, ends the keys unless a flip of the
    /// triangulation certifies the segment (as [`Leg::repair_keys`] would).
    fn push_uncertified(&mut self, a: &[Point], b: (f64, &[Point]), tris: &[[u32; 3]]) {
        if self.strict
            && crate::certify::flip_to_certify(a, b.1, tris, crate::certify::Player::Exact)
                .is_none()
        {
            self.aborted = true;
        }
        self.push(b, false);
    }
}

/// The farthest index in `good..count` that `joins` accepts, from `good`
/// (accepted): tried at doubling steps, then at the last index where no
/// step was refused, then by bisection between the last accepted and the
/// first refused. `joins` need not be monotone; the answer is one it
/// accepts (or `good`). O(log k) calls for an answer k indices on.
pub(crate) fn farthest_join(
    mut good: usize,
    count: usize,
    mut joins: impl FnMut(usize) -> bool,
) -> usize {
    let mut step = 1usize;
    let mut bad = count;
    while good + step < count {
        if joins(good + step) {
            good += step;
            step *= 2;
        } else {
            bad = good + step;
            break;
        }
    }
    if bad == count && good + 1 < count && joins(count - 1) {
        good = count - 1;
    }
    let mut hi = bad.min(count);
    while hi > good + 1 {
        let mid = good + (hi - good) / 2;
        if joins(mid) {
            good = mid;
        } else {
            hi = mid;
        }
    }
    good
}

/// How much the total area of a straight segment's midpoint may differ
/// from the path's there, relative to the path's (1 %).
pub(crate) const KEY_AREA_TOLERANCE: f64 = 0.01;

/// Most splits of a leg's segments per checked sample: a bound on the
/// work and the keys where a path cannot be followed closely (a segment
/// left unsplit is still checked at every frame).
const MAX_KEY_SPLITS: usize = 64;

/// `count` parameters spaced evenly strictly inside (`s0`, `s1`), in
/// order and never decreasing (some equal where the span holds fewer
/// doubles than that): those of keys off the path.
fn even_params(s0: f64, s1: f64, count: usize) -> Vec<f64> {
    let parts = count as f64 + 1.0;
    let mut last = s0;
    (1..=count)
        .map(|i| {
            last = (s0 + (s1 - s0) * (i as f64 / parts)).clamp(last, s1);
            last
        })
        .collect()
}

/// Most keys a bridge across an uncertified segment may skip beside it
/// ([`Leg::certify_across_keys`]).
const MAX_KEYS_ACROSS: usize = 3;

/// Where [`Leg::split`] splits a segment, in order of preference: its
/// midpoint, then other points where the path's midpoint fails the exact
/// check.
const SPLIT_AT: [f64; 7] = [0.5, 0.25, 0.75, 0.375, 0.625, 0.125, 0.875];

/// Finest split of a segment between keys, in the leg's own parameter.
const MIN_KEY_STEP: f64 = 1.0 / (1u64 << 44) as f64;

/// A staged path from one curve to another (in the first curve's labels).
#[derive(Clone, Debug)]
pub(crate) struct Staged {
    pub(crate) legs: Vec<Leg>,
    /// Where the other triangulation was reached: on the disk route the
    /// fraction of the way to the disk (0 when no flip was needed); on the
    /// target route the number of legs toward a target.
    pub u_star: f64,
    /// Flips applied.
    pub flips: usize,
    /// Local unblocks used (target route).
    pub unblocks: usize,
    /// True when the disk was used (always for the disk route; a fallback
    /// for the target route).
    pub used_disk: bool,
    /// Everything that did not go as asked, in order.
    pub fallbacks: Vec<Fallback>,
    /// Triangles whose third vertex the layout moved by the exact
    /// orientation test, over every checked sample.
    pub repairs: usize,
}

/// The disk of docs/design.md §7: vertices on a circle spaced in proportion to
/// the curve's edge lengths (with a floor, so that no two coincide), with
/// the curve's area (as the polygon it forms) and area centroid.
pub(crate) fn disk_for(points: &[Point], area: f64, centroid: Point) -> Vec<Point> {
    let unit = disk_positions(points);
    let a_unit = signed_area(&unit);
    let c_unit = crate::geom::polygon::area_centroid(&unit);
    let scale = (area / a_unit).sqrt();
    unit.into_iter()
        .map(|p| centroid + (p - c_unit) * scale)
        .collect()
}

/// Which flips come next.
enum FlipOrder {
    /// The insertion sequence of Mukherjee & Gopi §6.2, in order (the disk
    /// route).
    Sequence { flips: Vec<Flip>, next: usize },
    /// Any diagonal whose flip lowers its crossings with the goal, largest
    /// gain first (the target route).
    Gain(Candidates),
}

impl FlipOrder {
    fn sequence(cur: &FlipTriangulation, goal: &[[u32; 3]]) -> FlipOrder {
        FlipOrder::Sequence {
            flips: flip_sequence(cur.vertex_count(), cur.triangles(), goal),
            next: 0,
        }
    }

    fn is_done(&self) -> bool {
        match self {
            FlipOrder::Sequence { flips, next } => *next >= flips.len(),
            FlipOrder::Gain(c) => c.is_empty(),
        }
    }

    /// Applies every flip acceptable in shape `p` (all that remain when
    /// `force`); returns how many.
    fn batch(
        &mut self,
        cur: &mut FlipTriangulation,
        p: &[Point],
        floor: f64,
        force: bool,
    ) -> usize {
        match self {
            FlipOrder::Sequence { flips, next } => {
                let mut applied = 0;
                while *next < flips.len() {
                    let f = flips[*next].from;
                    let Some((quad, _)) = cur.quad(f.0, f.1) else {
                        // Out of step with the sequence: recompute it.
                        break;
                    };
                    if !(force || gate(p, quad, floor).is_some()) {
                        break;
                    }
                    cur.flip(f.0, f.1);
                    *next += 1;
                    applied += 1;
                }
                applied
            }
            FlipOrder::Gain(c) => c.batch(cur, p, floor),
        }
    }

    /// The quads of the flips waiting to be applied.
    fn waiting(&self, cur: &FlipTriangulation) -> Vec<[u32; 4]> {
        match self {
            FlipOrder::Sequence { flips, next } => flips
                .get(*next)
                .and_then(|f| cur.quad(f.from.0, f.from.1))
                .map(|q| vec![q.0])
                .unwrap_or_default(),
            FlipOrder::Gain(c) => c.quads(),
        }
    }
}

/// The inputs of one side of the morph.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SideInput<'a> {
    /// This side's curve and triangulation.
    pub(crate) s: &'a [Point],
    pub(crate) t_start: &'a [[u32; 3]],
    /// The other curve (in this side's labels) and its triangulation.
    pub(crate) other: &'a [Point],
    pub(crate) t_other: &'a [[u32; 3]],
    /// The path of the legs toward intermediates and of the last leg.
    pub(crate) leg_path: ThirdVertexPath,
    pub(crate) final_path: ThirdVertexPath,
    /// Whether the last leg races other paths against `final_path`
    /// ([`crate::morph::MorphOptions`]).
    pub(crate) rivals: bool,
    pub(crate) root: RootChoice,
    pub(crate) margin: f64,
    pub(crate) intermediate: Intermediate,
    /// The gate's angle floor on the target route.
    pub(crate) floor: f64,
    /// The largest vertex move allowed between checked samples (samples
    /// are refined until it holds).
    pub(crate) max_step: f64,
    /// The side is given up (built as `None`) as soon as the mean travel
    /// of its vertices passes this limit: a plan already made, or the
    /// leading side of this plan, travels less.
    pub(crate) limit: Limit<'a>,
}

/// How far a side's vertices may travel before it is given up: a fixed
/// bound (a plan made before) and, for the side that follows in the race
/// of one plan's two sides, the leading side's travel once it finished.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Limit<'a> {
    pub(crate) fixed: f64,
    /// The leading side's travel once it finished (f64 bits; infinite
    /// before).
    pub(crate) rival: Option<&'a std::sync::atomic::AtomicU64>,
    /// For the leading side, the following side's reach once it finished
    /// (f64 bits; infinite before): the largest travel at which it went
    /// on, at least its travel. The lead is given up at the start of a leg
    /// or between samples once the travel it must at least end with (its
    /// legs so far and the straight way from the leg's start to the other
    /// curve) passes it: it would lose, and the follower decided
    /// everything as it would have under the lead's finished travel. Not
    /// a limit of [`Peak`]: what it gives up, building the lead alone
    /// gives up too, or loses.
    pub(crate) reach: Option<&'a std::sync::atomic::AtomicU64>,
}

impl Limit<'_> {
    /// The limit `fixed` alone (infinite: none).
    pub(crate) fn fixed(fixed: f64) -> Limit<'static> {
        Limit {
            fixed,
            rival: None,
            reach: None,
        }
    }

    /// What a side at `x` that has travelled `travelled` must travel at
    /// least in all, whatever way it goes on to `other` (where every way
    /// ends): `None` where no reach is consulted ([`Limit::reach`]).
    fn least_travel(&self, travelled: f64, x: &[Point], other: &[Point]) -> Option<f64> {
        self.reach
            .map(|_| travelled + moves(x, other).1 * AHEAD_COUNTED)
    }

    /// Whether a side that must travel at least `least` in all
    /// ([`Limit::least_travel`]) is past the other side's reach.
    fn past_reach(&self, least: Option<f64>) -> bool {
        match (self.reach, least) {
            (Some(r), Some(least)) => {
                least > f64::from_bits(r.load(std::sync::atomic::Ordering::Relaxed))
            }
            _ => false,
        }
    }

    /// Whether the limit can be finite: a fixed bound, or a rival.
    fn can_fall(&self) -> bool {
        self.fixed < f64::INFINITY || self.rival.is_some()
    }

    /// The limit now (it only falls, and never below its final value).
    fn get(&self) -> f64 {
        let rival = self.rival.map_or(f64::INFINITY, |r| {
            f64::from_bits(r.load(std::sync::atomic::Ordering::Relaxed))
        });
        self.fixed.min(rival)
    }
}

/// What a side's building saw of its limit: the largest travel at which
/// it consulted the limit, and the largest at which it went on (was not
/// given up), on the legs toward intermediates and on the last leg. A
/// side that went on only at travels within a limit `L` decided
/// everything as it would have under `L` from the start; one that went on
/// past `L` on a leg toward an intermediate would have been given up
/// under `L` (every look before was within it).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Peak {
    pub(crate) consulted: f64,
    pub(crate) went_on_walking: f64,
    pub(crate) went_on_last: f64,
}

impl Peak {
    /// Consults `limit` at travel `partial` on the last leg or on a leg
    /// toward an intermediate: whether the side passes it.
    fn passes(&mut self, partial: f64, limit: &Limit<'_>, last: bool) -> bool {
        self.consulted = self.consulted.max(partial);
        let passes = partial > limit.get();
        if !passes {
            let went_on = if last {
                &mut self.went_on_last
            } else {
                &mut self.went_on_walking
            };
            *went_on = went_on.max(partial);
        }
        passes
    }

    /// Counts what `other` saw on the last leg as seen by this side.
    fn count(&mut self, other: &Peak) {
        self.consulted = self.consulted.max(other.consulted);
        self.went_on_last = self.went_on_last.max(other.went_on_last);
    }
}

impl SideInput<'_> {
    /// A leg's plan from `x` to `end` under the triangulation of `tree`,
    /// keeping the whole morph's area range (straight path).
    fn plan(
        &self,
        x: &[Point],
        end: &[Point],
        tree: &DualTree,
    ) -> Result<Compatible, CompatibleError> {
        let a0 = area_and_centroid(self.s, self.t_start).0;
        let a1 = area_and_centroid(self.other, self.t_other).0;
        Ok(
            Compatible::on_tree(x, end, tree, self.root.into(), self.margin)?
                .with_area_range(a0, a1),
        )
    }
}

/// The guaranteed paths to try after `first`, in order.
pub(crate) fn recovery_paths(first: ThirdVertexPath) -> Vec<ThirdVertexPath> {
    let mut v = vec![first];
    for p in [
        ThirdVertexPath::Hybrid,
        ThirdVertexPath::Straight,
        ThirdVertexPath::Polar,
        ThirdVertexPath::Angle,
    ] {
        if !v.contains(&p) {
            v.push(p);
        }
    }
    v
}

/// What the route is heading for.
enum Mode {
    Target,
    Disk { disk: Vec<Point>, floor: f64 },
}

/// How a walk along one leg ended.
enum Walk {
    /// The leg, the flips applied at its end, and the shape there.
    Done(Box<Leg>, usize, Shape),
    /// No guaranteed path could be set up or checked toward this end.
    Failed(String),
    /// The vertices travelled farther than [`SideInput::limit`].
    GaveUp,
}

impl Staged {
    /// Builds the staged path of one side; `None` when its vertices
    /// travel farther than [`SideInput::limit`] (it was given up there).
    /// Beside the outcome, what it saw of its limit ([`Peak`]): a side
    /// that failed having consulted the limit only within a limit `L`
    /// would have failed under `L` too.
    ///
    /// # Errors
    ///
    /// [`MorphError`] when even the disk route cannot finish (a bug).
    pub(crate) fn build(inp: &SideInput<'_>) -> (Result<Option<Staged>, MorphError>, Peak) {
        let mut peak = Peak::default();
        let outcome = Self::build_tracked(inp, &mut peak);
        (outcome, peak)
    }

    fn build_tracked(inp: &SideInput<'_>, peak: &mut Peak) -> Result<Option<Staged>, MorphError> {
        let n = inp.s.len();
        let goal_tris: &[[u32; 3]] = if check(inp.other, inp.t_start).is_ok() {
            inp.t_start
        } else {
            inp.t_other
        };
        let goal = FlipTriangulation::new(n, goal_tris).diagonals();
        let mut cur = FlipTriangulation::new(n, inp.t_start);
        let mut st = Staged {
            legs: Vec::new(),
            u_star: 0.0,
            flips: 0,
            unblocks: 0,
            used_disk: false,
            fallbacks: Vec::new(),
            repairs: 0,
        };
        let mut x = Shape::from(inp.s);
        // The end every leg toward an intermediate is guided at, held once
        // by all their released plans.
        let other_shared: std::sync::Arc<[Point]> = std::sync::Arc::from(inp.other);
        let (area, centroid) = area_and_centroid(inp.s, inp.t_start);
        let reference_disk = disk_for(inp.s, area, centroid);
        let mut target_angles = TargetAngles::default();
        let mut mode = Mode::Target;
        let mut order = FlipOrder::Gain(Candidates::new(&cur, &goal));
        if inp.intermediate == Intermediate::Disk {
            (mode, order) = Self::to_disk(&x, &cur, goal_tris);
            st.used_disk = true;
        }
        let mut remaining = 1.0; // the disk route's distance left to the disk
        let mut blocked: Vec<bool> = Vec::new();
        if let Mode::Target = mode {
            st.flips += order.batch(&mut cur, &x, inp.floor, false);
        }
        while !order.is_done() {
            // One dual tree per leg, for the target and the leg's plan.
            let tree = DualTree::new(n, cur.triangles()).map_err(CompatibleError::from)?;
            let (end, floor) = match &mode {
                Mode::Target => match target_shape(
                    &tree,
                    inp.other,
                    &reference_disk,
                    &blocked,
                    &mut target_angles,
                ) {
                    Some(t) => (t, inp.floor),
                    None => {
                        st.fallbacks.push(Fallback::new(
                            "finished through the disk",
                            "the target-shaped intermediate could not be laid out as an immersion",
                        ));
                        (mode, order) = Self::to_disk(&x, &cur, goal_tris);
                        st.used_disk = true;
                        continue;
                    }
                },
                Mode::Disk { disk, floor } => (disk.clone(), *floor),
            };
            let at_disk = matches!(mode, Mode::Disk { .. });
            let walked = walk(
                inp, &x, &end, &tree, &mut cur, &mut order, floor, at_disk, &mut st, peak,
            )?;
            let (mut leg, applied, end_shape) = match walked {
                Walk::Done(leg, applied, end_shape) => (*leg, applied, end_shape),
                Walk::GaveUp => return Ok(None),
                Walk::Failed(why) if !at_disk => {
                    st.fallbacks
                        .push(Fallback::new("finished through the disk", &why));
                    (mode, order) = Self::to_disk(&x, &cur, goal_tris);
                    st.used_disk = true;
                    continue;
                }
                Walk::Failed(why) => {
                    return Err(MorphError::InvalidFrame {
                        t: 0.0,
                        path: inp.leg_path,
                        defect: format!("the disk route could not continue: {why}"),
                    });
                }
            };
            if at_disk {
                remaining *= 1.0 - leg.s_end();
            }
            x = end_shape;
            st.flips += applied;
            if leg.s_end() > 0.0 {
                leg.plan.release(&[&leg.keys[0], &other_shared]);
                st.legs.push(leg);
            }
            if applied > 0 {
                blocked.clear();
                continue;
            }
            // The intermediate is reached with flips left.
            if at_disk {
                // At the disk every flip is valid (convex position).
                st.flips += order.batch(&mut cur, &x, 0.0, true);
                continue;
            }
            if blocked.is_empty() {
                st.unblocks += 1;
                blocked = vec![false; cur.triangles().len()];
                for q in order.waiting(&cur) {
                    for t in [[q[0], q[1], q[2]], [q[2], q[3], q[0]]] {
                        let t = canonical(t);
                        if let Some(i) = cur.triangles().iter().position(|&c| c == t) {
                            blocked[i] = true;
                        }
                    }
                }
            } else {
                st.fallbacks.push(Fallback::new(
                    "finished through the disk",
                    "the target-shaped intermediate was reached with flips left, even after a local unblock",
                ));
                (mode, order) = Self::to_disk(&x, &cur, goal_tris);
                st.used_disk = true;
            }
        }
        st.u_star = if st.used_disk && inp.intermediate == Intermediate::Disk {
            if st.flips == 0 { 0.0 } else { 1.0 - remaining }
        } else {
            st.legs.len() as f64
        };
        // The last leg, to the other curve.
        let Some(last) = last_leg(inp, &x, cur.triangles(), &mut st, peak)? else {
            return Ok(None);
        };
        st.legs.push(last);
        for (k, leg) in st.legs.iter().enumerate() {
            let rigid = leg.plan.has_rigid_guide();
            if let Some(f) = guide_fallback(rigid, leg.path, &format!("leg {}", k + 1)) {
                st.fallbacks.push(f);
            }
        }
        Ok(Some(st))
    }

    /// Switches to the disk route from shape `x`.
    fn to_disk(x: &[Point], cur: &FlipTriangulation, goal: &[[u32; 3]]) -> (Mode, FlipOrder) {
        let (area, centroid) = area_and_centroid(x, cur.triangles());
        let disk = disk_for(x, area, centroid);
        let floor = 0.5 * min_angle(&disk, cur.triangles()).min(min_angle(&disk, goal));
        (Mode::Disk { disk, floor }, FlipOrder::sequence(cur, goal))
    }

    /// The mean over vertices of the distance each travels along the whole
    /// path (over the checked samples).
    pub(crate) fn mean_travel(&self) -> f64 {
        self.legs.iter().map(|l| l.mean_travel).sum()
    }
}

/// Walks one leg from `x` toward `end` under `cur` (whose dual tree is
/// `tree`), trying the guaranteed paths in turn until every sample passes
/// the exact check; applies the flips at the first sample where some pass
/// the gate (all remaining ones are left for the caller at the disk).
#[allow(
    clippy::too_many_arguments,
    reason = "the state of the route at the start of a leg"
)]
fn walk(
    inp: &SideInput<'_>,
    x: &Shape,
    end: &[Point],
    tree: &DualTree,
    cur: &mut FlipTriangulation,
    order: &mut FlipOrder,
    floor: f64,
    at_disk: bool,
    st: &mut Staged,
    peak: &mut Peak,
) -> Result<Walk, MorphError> {
    let mut why = String::new();
    let travelled = st.mean_travel();
    let least = inp.limit.least_travel(travelled, x, inp.other);
    for (attempt, path) in recovery_paths(inp.leg_path).into_iter().enumerate() {
        let plan = match inp.plan(x, end, tree) {
            // Toward a target-shaped intermediate, head for the other curve
            // itself (its projection is the intermediate where they differ).
            Ok(plan) if !at_disk => plan.with_guide(inp.other),
            Ok(plan) => plan,
            Err(e @ CompatibleError::NotCcw { .. }) => {
                return Ok(Walk::Failed(format!("the intermediate is not valid ({e})")));
            }
            Err(e) => return Err(e.into()),
        };
        let mut leg = Leg::start_at(plan, path, Shape::clone(x));
        let mut prev = Shape::clone(x);
        let mut repairs = 0;
        let mut k = 1usize;
        let outcome = loop {
            if inp.limit.past_reach(least) {
                return Ok(Walk::GaveUp);
            }
            let s = (k as f64 * LEG_STEP).min(1.0);
            let (p, r) = leg.plan.positions_counted(s, path);
            repairs += r;
            let p = match record(
                &mut leg,
                cur.triangles(),
                inp.max_step,
                &prev,
                s,
                p,
                &mut repairs,
            ) {
                Ok(p) => p,
                Err(e) => break Err(e),
            };
            // Every vertex still has at least the straight way to the
            // other curve to go, where the side ends (the mean of those
            // distances bounds the travel ahead): a side that cannot finish
            // within the limit is given up here, not legs later. Only where
            // the limit can be finite, whatever the timing.
            let ahead = if inp.limit.can_fall() {
                moves(&p, inp.other).1 * AHEAD_COUNTED
            } else {
                0.0
            };
            if peak.passes(travelled + leg.mean_travel + ahead, &inp.limit, false) {
                return Ok(Walk::GaveUp);
            }
            let applied = if s < 1.0 || !at_disk {
                order.batch(cur, &p, floor, false)
            } else {
                0
            };
            if applied > 0 || s >= 1.0 {
                break Ok((applied, p));
            }
            prev = p;
            k += 1;
        };
        match outcome {
            Ok((applied, end_shape)) => {
                st.repairs += repairs;
                if attempt > 0 {
                    st.fallbacks.push(Fallback::new(
                        &format!("used the {path} path for a leg"),
                        &why,
                    ));
                }
                return Ok(Walk::Done(Box::new(leg), applied, end_shape));
            }
            Err(w) => why = w,
        }
    }
    Ok(Walk::Failed(why))
}

/// The last leg, from `x` to the other curve under `tris` (valid on both),
/// with the requested path, or the guaranteed ones in turn when a sample
/// fails the exact check; `None` when the side's vertices travel farther
/// than [`SideInput::limit`] along it.
fn last_leg(
    inp: &SideInput<'_>,
    x: &[Point],
    tris: &[[u32; 3]],
    st: &mut Staged,
    peak: &mut Peak,
) -> Result<Option<Leg>, MorphError> {
    // The travel before this leg, against the side's limit.
    let base = st.mean_travel();
    if inp
        .limit
        .past_reach(inp.limit.least_travel(base, x, inp.other))
    {
        return Ok(None);
    }
    let tree = DualTree::new(x.len(), tris).map_err(CompatibleError::from)?;
    let plan = inp.plan(x, inp.other, &tree)?;
    let mut why = String::new();
    // The straight path competes with the hybrid and the polar ones on the
    // last leg: a winding or unwinding that straight lines cut across is
    // often shorter along them. The one whose vertices travel least is
    // kept, unless it unwinds overlaps another keeps (`Leg::beats`); each
    // rival is given up as soon as it cannot win, and the polar path is
    // tried only where the straight leg did not win over the hybrid one.
    let rigid = inp.final_path == ThirdVertexPath::Rigid && inp.rivals;
    let mut candidates = if rigid {
        // Straight first: it usually travels least, and the rigid rival is
        // then given up as soon as it cannot win (same choice, less work).
        vec![
            ThirdVertexPath::Straight,
            ThirdVertexPath::Rigid,
            ThirdVertexPath::Polar,
            ThirdVertexPath::Hybrid,
            ThirdVertexPath::Angle,
        ]
    } else {
        recovery_paths(inp.final_path)
    };
    let compete = inp.rivals && (inp.final_path == ThirdVertexPath::Straight || rigid);
    let last_rival = ThirdVertexPath::Polar;
    let mut best: Option<(Leg, usize)> = None;
    // The first path when it passed the limit before a rival was tried.
    let mut passed: Option<ThirdVertexPath> = None;
    // Why the requested path failed the exact check, if it did.
    let mut first_failed: Option<String> = None;
    // What the first path saw of the limit, kept apart from `peak` until
    // it is known whether it counts (`Excuse`).
    let mut first_peak = Peak::default();
    let mut excuse = Excuse::default();
    for (i, path) in candidates.drain(..).enumerate() {
        let rival = best.as_ref().map(|(b, _)| b);
        // The polar path is for windings that straight lines cut across;
        // where the straight leg beat its rival (hybrid, or rigid) there is
        // none.
        if compete
            && path == ThirdVertexPath::Polar
            && rival.is_some_and(|r| r.plan_path() == ThirdVertexPath::Straight)
        {
            break;
        }
        // Whether another rival follows this one.
        let more = compete && path != last_rival;
        // A rival that passes the limit travels more than the kept leg:
        // it can still win only if it keeps overlaps the kept leg undoes,
        // and then the side travels past the limit anyway. So the limit
        // holds unless the kept leg unwinds.
        let seen = if i == 0 { &mut first_peak } else { &mut *peak };
        let lim = match rival {
            Some(r) if !r.keeps_overlaps() => None,
            _ => Some((&inp.limit, seen)),
        };
        let sampled = sample_leg(
            plan.clone(),
            path,
            x,
            tris,
            inp.max_step,
            rival,
            (base, lim),
        );
        if i == 0 {
            excuse.first_finished = matches!(sampled, Ok(Sampled::Done(..)));
            excuse.first_had_rivals = more;
        }
        match sampled {
            Ok(Sampled::CannotBeat) => {
                if !more {
                    break;
                }
            }
            Ok(Sampled::PassedLimit) => {
                if best.is_some() {
                    // The kept leg keeps overlaps and travels less.
                    if !more {
                        break;
                    }
                    continue;
                }
                if !compete || passed.is_some() {
                    // Every path this side could end with travels past
                    // the limit: the paths after these two (`polar`,
                    // `hybrid`, `angle`) are not tried. Where they win
                    // on travel they jump on thin strips (the `angle`
                    // path: 7 jumps in 2,000 stress pairs of seed
                    // 0xbee5, against none).
                    peak.count(&first_peak);
                    return Ok(None);
                }
                passed = Some(path);
            }
            Ok(Sampled::Done(leg, repairs, most)) => {
                let leg = *leg;
                if let Some(first) = passed.take() {
                    // The first path passed the limit, this one did not:
                    // this one wins unless it unwinds overlaps the first
                    // keeps, which only the whole first path can tell.
                    if !leg.keeps_overlaps()
                        && let Ok(Sampled::Done(f, ..)) = sample_leg(
                            plan.clone(),
                            first,
                            x,
                            tris,
                            inp.max_step,
                            None,
                            (base, None),
                        )
                        && f.beats(&leg)
                    {
                        peak.count(&first_peak);
                        return Ok(None);
                    }
                    best = Some((leg, repairs));
                    excuse.best = i;
                } else if best.as_ref().is_none_or(|(b, _)| leg.beats(b)) {
                    best = Some((leg, repairs));
                    excuse.best = i;
                }
                if i == 1 {
                    excuse.second_most = most;
                }
                if !more {
                    break;
                }
            }
            Err(w) => {
                if path == inp.final_path {
                    first_failed = Some(w.clone());
                }
                why = w;
            }
        }
    }
    if excuse.holds() {
        // The first path's travels give way to the second's.
        first_peak.went_on_last = excuse.second_most;
    }
    peak.count(&first_peak);
    if let (Some(w), Some((leg, _))) = (&first_failed, &best) {
        st.fallbacks.push(Fallback::new(
            &format!("used the {} path for the last leg", leg.plan_path()),
            w,
        ));
    }
    match best {
        Some((leg, repairs)) => {
            st.repairs += repairs;
            Ok(Some(leg))
        }
        None if passed.is_some() => Ok(None),
        None => Err(MorphError::InvalidFrame {
            t: 1.0,
            path: inp.final_path,
            defect: why,
        }),
    }
}

/// The report that `path` on a plan, for `what` (e.g. "leg 2"), was
/// guided by the straight guide instead of the as-rigid-as-possible one
/// (the plan's [`Compatible::has_rigid_guide`] is `has_rigid_guide`).
pub(crate) fn guide_fallback(
    has_rigid_guide: bool,
    path: ThirdVertexPath,
    what: &str,
) -> Option<Fallback> {
    (path == ThirdVertexPath::Rigid && !has_rigid_guide).then(|| {
        Fallback::new(
            &format!("guided the rigid path of {what} by the straight guide"),
            "the as-rigid-as-possible system cannot be solved accurately in double precision \
             here (thin triangles far apart in size); its rounding would shake the frames",
        )
    })
}

/// Where the first path of a last leg did not count toward the side's
/// [`Peak`] (what decides whether the follower is built again under the
/// lead's travel, and the follower's reach that can give the lead up):
/// the first path (no rival, so the limit alone could stop it) finished,
/// the second path then beat it and stayed kept to the end. Under any
/// limit `L` at least the side's recorded peak, the last leg then keeps
/// the same leg: the first path either stays under `L` (everything as
/// here) or passes it and is set aside; the second path, sampled then
/// without a rival, gives the same samples (it finished here, so its
/// rival never stopped it), stays under `L` (its largest partial travel,
/// `second_most`, is counted in the peak) and is kept, since the first
/// does not beat it (it lost to it here, and [`Leg::beats`] is
/// asymmetric); every path after it sees the same rival as here.
#[derive(Default)]
struct Excuse {
    /// The first path finished (it neither failed nor passed the limit).
    first_finished: bool,
    /// Rivals follow the first path (a passed first path is set aside,
    /// not the end of the side).
    first_had_rivals: bool,
    /// The index of the path kept last.
    best: usize,
    /// The second path's largest partial travel, as the limit would see
    /// it (the travel before the leg, its own, and the straight way
    /// ahead).
    second_most: f64,
}

impl Excuse {
    fn holds(&self) -> bool {
        self.first_finished && self.first_had_rivals && self.best == 1
    }
}

/// How sampling a leg ended.
enum Sampled {
    /// Every sample passed the exact check: the leg, its repairs and its
    /// largest partial travel as the limit would see it (see
    /// [`sample_leg`]), whether or not the limit was consulted.
    Done(Box<Leg>, usize, f64),
    /// It can no longer beat the rival.
    CannotBeat,
    /// Its vertices travelled farther than the limit.
    PassedLimit,
}

/// Samples the whole of a leg with `path`, checking every sample exactly;
/// stops as soon as it cannot beat `rival` any more (its travel only
/// grows, by at least the mean straight distance from each vertex to its
/// end, and its least turning only falls) or, with `limit` = (the side's
/// limit, the travel before this leg, the side's peak), the side's mean
/// vertex travel must pass the limit (by the same bound). `watch` is the
/// travel before this leg and, where the side's limit holds here, the
/// limit and the peak that records what the leg saw of it.
fn sample_leg(
    plan: Compatible,
    path: ThirdVertexPath,
    x: &[Point],
    tris: &[[u32; 3]],
    max_step: f64,
    rival: Option<&Leg>,
    watch: (f64, Option<(&Limit<'_>, &mut Peak)>),
) -> Result<Sampled, String> {
    let (base, mut limit) = watch;
    let mut most = f64::NEG_INFINITY;
    let steps = (1.0 / LEG_STEP).round() as usize;
    let mut leg = Leg::start(plan, path);
    let mut prev = Shape::clone(&leg.keys[0]);
    let mut repairs = 0;
    let turning = crate::geom::polygon::total_absolute_turning;
    leg.end_turning = turning(x).min(turning(leg.plan.target()));
    leg.least_turning = turning(x);
    for k in 1..=steps {
        let s = k as f64 / steps as f64;
        let (p, r) = leg.plan.positions_counted(s, path);
        repairs += r;
        prev = record(&mut leg, tris, max_step, &prev, s, p, &mut repairs)?;
        leg.least_turning = leg.least_turning.min(turning(&prev));
        // Every vertex still has at least the straight way to its end to
        // go (the mean of those distances bounds the travel ahead).
        let ahead = if s < 1.0 {
            moves(&prev, leg.plan.target()).1
        } else {
            0.0
        };
        if rival.is_some_and(|b| leg.cannot_beat(b, ahead)) {
            return Ok(Sampled::CannotBeat);
        }
        let partial = base + leg.mean_travel + ahead;
        most = most.max(partial);
        if let Some((lim, peak)) = limit.as_mut()
            && peak.passes(partial, lim, true)
        {
            return Ok(Sampled::PassedLimit);
        }
    }
    Ok(Sampled::Done(Box::new(leg), repairs, most))
}

/// The share of the straight way still to go that a side on a leg toward
/// an intermediate counts against its limit ([`walk`]): a millionth is
/// left out for the rounding of the travel's sums.
const AHEAD_COUNTED: f64 = 1.0 - 1e-6;

/// Finest refinement of a leg's samples, in its own parameter.
const MIN_SAMPLE_STEP: f64 = 1.0 / 4096.0;

/// Checks the sample `p` at `s` exactly and appends it to the leg, after
/// first inserting (checked) samples halfway back toward the previous one
/// wherever some vertex would move more than `max_step` between samples,
/// so that the timing table never hides a fast stretch and every stretch
/// of the path is checked finely. Returns `p`.
#[allow(
    clippy::too_many_arguments,
    reason = "the leg, its triangulation and the two samples"
)]
fn record(
    leg: &mut Leg,
    tris: &[[u32; 3]],
    max_step: f64,
    prev: &[Point],
    s: f64,
    p: Vec<Point>,
    repairs: &mut usize,
) -> Result<Shape, String> {
    let path = leg.plan_path();
    if let Err(defect) = check_triangles(&p, tris) {
        return Err(format!(
            "the {path} path gave an invalid frame at s = {s} ({defect})"
        ));
    }
    let s_prev = leg.s_end();
    let (step, mean) = moves(prev, &p);
    if step > max_step && s - s_prev > MIN_SAMPLE_STEP {
        let sm = 0.5 * (s_prev + s);
        let (pm, r) = leg.plan.positions_counted(sm, path);
        *repairs += r;
        let pm = record(leg, tris, max_step, prev, sm, pm, repairs)?;
        return record(leg, tris, max_step, &pm, s, p, repairs);
    }
    leg.samples.push(s);
    leg.travel.push(leg.length() + step);
    let p = Shape::from(p);
    leg.keys.push(Shape::clone(&p));
    leg.mean_travel += mean;
    Ok(p)
}

/// The largest and the mean distance the vertices move between `a` and
/// `b`.
pub(crate) fn moves(a: &[Point], b: &[Point]) -> (f64, f64) {
    let (mut max, mut sum) = (0.0f64, 0.0);
    for (p, q) in a.iter().zip(b) {
        let d = (*p - *q).length();
        max = max.max(d);
        sum += d;
    }
    (max, sum / a.len().max(1) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::propagate::compatible::tests::spiral_strip;
    use crate::quality::{Quality, triangulate_with};

    /// A triangle whose `linear` path (not a guaranteed one) turns it
    /// over for a stretch: the probe of the keys' bridge.
    fn folding_triangle() -> (Vec<Point>, Vec<Point>, Vec<[u32; 3]>) {
        let p = Point::new;
        (
            vec![p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0)],
            vec![p(0.0, 0.0), p(-1.0, 0.9), p(0.9, -1.0)],
            vec![[0, 1, 2]],
        )
    }

    /// Where no point of a leg's path between two keys passes the exact
    /// check, the keys there follow a bridge (the straight path planned
    /// between the two keys) and are certified, where the straight
    /// segment between those keys turns the triangle over. The path here
    /// is the vertices' straight lines, which turn the folding triangle
    /// clockwise for s in (0.345, 0.909).
    #[test]
    fn keys_bridge_a_stretch_where_the_path_fails_the_exact_check() {
        let (a, b, tris) = folding_triangle();
        let chord =
            |s: f64| -> Vec<Point> { a.iter().zip(&b).map(|(p, q)| p.lerp(*q, s)).collect() };
        assert!(check_triangles(&chord(0.5), &tris).is_err());
        let plan = Compatible::new(&a, &b, &tris, RootChoice::Disk, 0.0).unwrap();
        let leg = Leg::start(plan, ThirdVertexPath::Straight);
        let ends = [Shape::from(&a[..]), Shape::from(&b[..])];
        let out = leg.keys_along(&[0.0, 1.0], &ends, 0.01, false, &chord);
        assert!(out.bridges >= 1, "no bridge");
        assert_eq!(out.keys.first().map(|k| &k[..]), Some(&a[..]));
        assert_eq!(out.keys.last().map(|k| &k[..]), Some(&b[..]));
        assert!(
            out.samples.windows(2).all(|w| w[0] < w[1]),
            "{:?}",
            out.samples
        );
        for (k, key) in out.keys.iter().enumerate() {
            assert!(check_triangles(key, &tris).is_ok(), "key {k} is not valid");
        }
        // Every segment is certified, by the certifier's own report and
        // independently: its signed area, a quadratic in s, checked at
        // its ends, its midpoint and its vertex.
        assert!(out.certified.iter().all(|&c| c), "{:?}", out.certified);
        for w in out.keys.windows(2) {
            let area = |s: f64| {
                let p: Vec<Point> = w[0]
                    .iter()
                    .zip(w[1].iter())
                    .map(|(p, q)| p.lerp(*q, s))
                    .collect();
                (p[1] - p[0]).perp_dot(p[2] - p[0])
            };
            let (c0, c1, cm) = (area(0.0), area(1.0), area(0.5));
            // c(s) = c0 (1 - s)^2 + 2 m s (1 - s) + c1 s^2.
            let m = 2.0 * cm - 0.5 * (c0 + c1);
            let vertex = (c0 - m) / (c0 - 2.0 * m + c1);
            let lowest = if (0.0..=1.0).contains(&vertex) {
                area(vertex)
            } else {
                c0.min(c1)
            };
            assert!(lowest > 0.0, "a segment turns the triangle over ({lowest})");
        }
    }

    #[test]
    fn the_disk_has_the_curve_area_and_centroid() {
        let (s, tris) = spiral_strip(20, 1.3, 0.2);
        let (area, c) = area_and_centroid(&s, &tris);
        let d = disk_for(&s, area, c);
        assert!((signed_area(&d) - area).abs() < 1e-12 * area);
        assert!((crate::geom::polygon::area_centroid(&d) - c).length() < 1e-12);
    }

    /// The side from `a` to `b`, given up (`None`) once its travel passes
    /// `limit`.
    fn side(
        a: &[Point],
        b: &[Point],
        ta: &[[u32; 3]],
        tb: &[[u32; 3]],
        intermediate: Intermediate,
        limit: f64,
    ) -> Option<Staged> {
        Staged::build(&SideInput {
            s: a,
            t_start: ta,
            other: b,
            t_other: tb,
            leg_path: ThirdVertexPath::Hybrid,
            final_path: ThirdVertexPath::Hybrid,
            rivals: true,
            root: RootChoice::Disk,
            margin: 0.05,
            intermediate,
            floor: 0.25 * min_angle(a, ta).min(min_angle(b, tb)),
            max_step: 0.05,
            limit: Limit::fixed(limit),
        })
        .0
        .unwrap()
    }

    /// Two spirals and their Delaunay-quality triangulations, the second
    /// relabelled by a shift so that the first's triangulation folds on
    /// it.
    fn incompatible_spirals() -> [(Vec<Point>, Vec<[u32; 3]>); 2] {
        let (a, _) = spiral_strip(16, 1.4, 0.25);
        let (b, _) = spiral_strip(16, 0.6, 0.25);
        let b: Vec<Point> = (0..b.len()).map(|i| b[(i + 5) % b.len()]).collect();
        let ta = triangulate_with(&a, Quality::Delaunay).unwrap().triangles;
        let tb = triangulate_with(&b, Quality::Delaunay).unwrap().triangles;
        [(a, ta), (b, tb)]
    }

    #[test]
    fn both_routes_between_incompatible_spirals_end_at_the_other_curve() {
        let [(a, ta), (b, tb)] = incompatible_spirals();
        assert!(check(&b, &ta).is_err());
        for route in [Intermediate::Disk, Intermediate::Target] {
            let st = side(&a, &b, &ta, &tb, route, f64::INFINITY).unwrap();
            assert!(st.flips > 0);
            let last = st.legs.last().unwrap();
            assert_eq!(last.plan.positions(1.0, last.path), b);
            assert_eq!(st.legs[0].plan.source(), &a[..]);
            // Consecutive legs join.
            for w in st.legs.windows(2) {
                let end = w[0].plan.positions(w[0].s_end(), w[0].path);
                assert_eq!(w[1].plan.source(), &end[..]);
            }
            assert_eq!(route == Intermediate::Disk, st.used_disk, "{route:?}");
        }
    }

    /// What a racing side counts against its limit at each sample of a
    /// leg toward an intermediate (its travel so far plus the straight way
    /// its vertices still have to go to the other curve, less a millionth
    /// of that) never passes the travel the side finishes with; so a side
    /// built under a limit equal to that travel is not given up and is the
    /// same side, and one under a limit just below it is given up.
    #[test]
    fn a_side_is_given_up_only_where_it_could_not_finish_within_its_limit() {
        let [(a, ta), (b, tb)] = incompatible_spirals();
        for (s, o, ts, to) in [(&a, &b, &ta, &tb), (&b, &a, &tb, &ta)] {
            let st = side(s, o, ts, to, Intermediate::Target, f64::INFINITY).unwrap();
            let total = st.mean_travel();
            assert!(st.legs.len() > 1, "no leg toward an intermediate");
            let mut travelled = 0.0;
            let mut largest = 0.0f64;
            for leg in &st.legs {
                let mut on_leg = 0.0;
                for w in leg.keys.windows(2) {
                    on_leg += moves(&w[0], &w[1]).1;
                    let ahead = moves(&w[1], o).1 * AHEAD_COUNTED;
                    largest = largest.max(travelled + on_leg + ahead);
                }
                travelled += leg.mean_travel;
            }
            assert!(
                largest <= total,
                "counted {largest} against a final travel of {total}"
            );
            let under = |limit: f64| side(s, o, ts, to, Intermediate::Target, limit);
            let kept = under(total).expect("given up within its own travel");
            assert_eq!(kept.mean_travel().to_bits(), total.to_bits());
            assert_eq!(kept.legs.len(), st.legs.len());
            assert!(
                under(total * (1.0 - 1e-9)).is_none(),
                "not given up below its travel"
            );
        }
    }
}
