//! A morph planned once, asked for frames at any t (docs/design.md §12).
//!
//! [`Tween::new`] does all the planning of a curve morph: equal counts,
//! triangulations, correspondence, both staged sides and the choice
//! between them, every leg walked and checked exactly at its samples, the keys (split until every straight segment between two keys
//! is certified, docs/design.md §13) and the pacing table.
//! [`Tween::frame`] then costs a binary search, one linear interpolation
//! between two keys and one exact check, O(n), and gives the same frame
//! for the same t however it is called. [`Tween::keyframes`] lists the
//! keys themselves: the animation is their piecewise-linear
//! interpolation, which is what Lottie, SVG and the playground play.
//!
//! **Pacing.** t is a fraction of the *pace*, summed over the segments
//! between consecutive keys. A segment whose vertices move m on average
//! and M at most has pace `max(m, M / c)`: frames at equal steps of pace
//! move the mean vertex at most one unit per unit of pace and any vertex
//! at most c, and where neither bound binds both speeds are even. The
//! ratio c is chosen per tween, among the segments' own M / m, so that
//! the largest per-frame mean move and the largest per-frame single
//! vertex move stay closest to their medians (within 1.5× and 2×, the
//! aims of docs/design.md §12).

use crate::correspond::shift_triangles;
use crate::geom::Point;
use crate::immersion::check_triangles;
use crate::morph::area_and_centroid;
use crate::morph::plan::{CurveMorphError, CurveMorphOptions, MorphReport, Side, plan};
use crate::morph::{Fallback, Frame, Morph};
use crate::morph::{Intermediate, MorphError, MorphOptions, Staged, ThirdVertexPath};
use crate::staged::{KEY_AREA_TOLERANCE, Leg, moves};
use std::cell::OnceCell;

/// One key of a morph's animation, a [`Frame`] read as a key: the shape at
/// fraction `t` of the pace (0 for the first key, 1 for the last, strictly
/// increasing) and the triangulation of the segment that follows it (for
/// the last key, the one of the segment before it, valid at it). Between
/// two keys every vertex moves on a straight line at constant speed; a
/// flip is one key, written with the triangulation after the flip
/// (docs/design.md §12 and §13).
pub type Keyframe = Frame;

/// The unwind below which a rigid morph is raced by the straight one
/// ([`Tween::new`]): the gate of docs/design.md §7c.
const KEPT_TURNING: f64 = 0.9;

/// The largest detour the defaults allow on any pair (docs/design.md
/// §7b): a plan raced in for its unwind ([`Tween::new`]) must keep to it.
const DETOUR_GATE: f64 = 3.0;

/// The longest edge a motion may reach, over the ends' longest
/// (docs/design.md §7c).
const SPIKE_GATE: f64 = 2.0;

/// The total area range a motion keeps to, against the smaller and the
/// larger end's (docs/design.md §7c).
const AREA_GATE: (f64, f64) = (0.8, 1.15);

/// How much farther the straight morph's vertices may travel than the
/// rigid one's for it to be kept instead ([`Tween::new`]).
const RACE_TRAVEL: f64 = 1.5;

/// A planned morph from one curve to another: a verified frame at any t.
///
/// # Examples
///
/// ```
/// use immerse::Curve;
/// use immerse::morph::{CurveMorphOptions, Tween};
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let a = Curve::from_path("curves/spiral-strip-400deg-n30.json")?;
/// let b = Curve::from_path("curves/curl-strip-n10.json")?;
/// let tween = Tween::new(&a.points, &b.points, &CurveMorphOptions::DEFAULT)?;
/// let middle = tween.frame(0.5)?;
/// assert!(middle.is_immersion());
/// assert_eq!(tween.frame(0.0)?.points.len(), tween.vertex_count());
/// # Ok(())
/// # }
/// ```
#[derive(Clone, Debug)]
pub struct Tween {
    n: usize,
    /// The side used, in its own curve's labels.
    staged: Staged,
    /// True when the target's side is used (frames run backwards on it).
    reversed: bool,
    shift: usize,
    /// Per leg, the cumulative pace at each key (0 at its first key).
    pace: Vec<Vec<f64>>,
    /// Pace at the start of each leg, and in all.
    offsets: Vec<f64>,
    total: f64,
    report: MorphReport,
}

impl Tween {
    /// Plans the morph of curve `a` into curve `b` (both oriented, turning
    /// number +1). Both curves are brought to equal counts and
    /// triangulated; a cyclic shift matches their vertices; each curve is
    /// then staged toward the other's triangulation (docs/design.md §7)
    /// and the side that gets there first is used, so the morph of `b`
    /// into `a` is this one reversed. [`Tween::morph`] then gives frames
    /// at many fractions, [`Tween::frame`] one at a time.
    ///
    /// # Errors
    ///
    /// [`CurveMorphError::NotSelfOverlapping`] when a curve is not
    /// self-overlapping; [`CurveMorphError::Morph`] (a bug) when no route
    /// could be completed, after every recovery.
    pub fn new(
        a: &[Point],
        b: &[Point],
        options: &CurveMorphOptions,
    ) -> Result<Tween, CurveMorphError> {
        options.validate()?;
        let tween = Self::chosen(a, b, options)?;
        if tween.is_certified() {
            return Ok(tween);
        }
        // Where the keys of the plan chosen for its motion cannot all be
        // certified (docs/design.md §13: a path that squeezes thin
        // triangles or small features below what the keys' doubles can
        // hold between two keys), the morph is planned again by other
        // routes, in order, and the first whose keys are all certified and
        // whose motion misses no gate of docs/design.md §7c that the first
        // plan's meets is kept, saying so; where none is, the first plan
        // stays (its frames are still checked exactly).
        let (bad, total) = tween.uncertified_segments();
        let why = format!(
            "the keys of the {} path left {bad} of {total} segments uncertified (a straight segment between two keys was not shown to stay an immersed disk)",
            crate::morph::output::path_names(&tween.report.paths)
        );
        let first = OnceCell::new();
        for (alternative, what) in certifying_routes(options) {
            if let Ok(mut other) = Self::planned(a, b, &alternative, true)
                && other.is_certified()
                && other.moves_no_worse(first.get_or_init(|| tween.motion()))
            {
                other.report.fallbacks.push(Fallback::new(&what, &why));
                return Ok(other);
            }
        }
        // No route qualifies: the first plan stays, and the segments it
        // leaves uncertified are given keys off its path where those
        // certify them (`off_path`).
        let mut tween = tween;
        tween.certify_off_path(options);
        Ok(tween)
    }

    /// Certifies, where it can, each segment left uncertified by keys off
    /// the path ([`Leg::certify_off_path`]), saying so in the report, and
    /// sets the frame timing again from the keys.
    fn certify_off_path(&mut self, options: &CurveMorphOptions) {
        use rayon::prelude::*;
        let tol = key_tolerance(&self.staged, options);
        let counts: Vec<(usize, usize)> = self
            .staged
            .legs
            .par_iter_mut()
            .map(|leg| leg.certify_off_path(tol))
            .collect();
        for (j, (&(count, across), leg)) in counts.iter().zip(&self.staged.legs).enumerate() {
            if count > 0 {
                let across = match across {
                    0 => String::new(),
                    n => format!(
                        " ({n} by a bridge across the {} beside {})",
                        noun(n, "key", "keys"),
                        them(n)
                    ),
                };
                let (segments, them) = (noun(count, "segment", "segments"), them(count));
                self.report.fallbacks.push(Fallback::new(
                    &format!(
                        "certified {count} {segments} of leg {} by keys off its path{across}",
                        j + 1
                    ),
                    &format!(
                        "neither keys taken from the {} path nor a flip of the triangulation certified {them}, and no other route qualified: a feature a few units in the last place wide moves too far between two keys",
                        leg.path
                    ),
                ));
            }
        }
        if counts.iter().any(|&(c, _)| c > 0) {
            (self.pace, self.offsets, self.total) = pace_tables(&self.staged.legs);
        }
    }

    /// The measures of docs/design.md §7c of the motion, from its frames
    /// at 40, 320 and 2,560 evenly spaced times; `None` where the frames
    /// cannot be made.
    fn motion(&self) -> Option<Motion> {
        let frames = |k: usize| -> Option<Vec<Frame>> {
            let t: Vec<f64> = (0..k).map(|i| i as f64 / (k - 1) as f64).collect();
            self.morph(&t).ok().map(|m| m.frames)
        };
        let step = |k: usize| frames(k).and_then(|f| crate::morph::measure::view_measures(&f));
        let (coarse, fine) = (step(40)?.max_step, step(2560)?.max_step);
        let f = frames(320)?;
        let v = crate::morph::measure::view_measures(&f)?;
        // A step that keeps its size as frames are added is a jump.
        let shrinks = |a: f64, b: f64| b <= a / 4.0 || b < 0.01;
        Some(Motion {
            jumps: !(shrinks(coarse, v.max_step) && shrinks(v.max_step, fine)),
            edge: v.edge_ratio,
            area: (v.area_low, v.area_high),
            detour: crate::morph::measure::detour(&f),
            unwind: crate::morph::measure::unwind(&f),
        })
    }

    /// Whether this motion misses none of the gates of docs/design.md
    /// §7c that `first` meets, and where `first` misses one, is no worse
    /// there than it.
    fn moves_no_worse(&self, first: &Option<Motion>) -> bool {
        let (Some(m), Some(f)) = (self.motion(), first) else {
            return first.is_none();
        };
        let keeps = |ok: bool, was_ok: bool, no_worse: bool| ok || (!was_ok && no_worse);
        keeps(!m.jumps, !f.jumps, true)
            && keeps(m.edge <= SPIKE_GATE, f.edge <= SPIKE_GATE, m.edge <= f.edge)
            && keeps(
                m.area.0 >= AREA_GATE.0,
                f.area.0 >= AREA_GATE.0,
                m.area.0 >= f.area.0,
            )
            && keeps(
                m.area.1 <= AREA_GATE.1,
                f.area.1 <= AREA_GATE.1,
                m.area.1 <= f.area.1,
            )
            && keeps(
                m.detour <= DETOUR_GATE,
                f.detour <= DETOUR_GATE,
                m.detour <= f.detour,
            )
            && keeps(
                m.unwind >= KEPT_TURNING,
                f.unwind >= KEPT_TURNING,
                m.unwind >= f.unwind,
            )
    }

    /// The plan chosen for its motion: [`Tween::raced`], and the min-flips
    /// rule raced in where the best correspondence's plan unwinds.
    fn chosen(
        a: &[Point],
        b: &[Point],
        options: &CurveMorphOptions,
    ) -> Result<Tween, CurveMorphError> {
        let (tween, unwind) = Self::raced(a, b, options)?;
        // The best correspondence keeps the plan whose vertices travel
        // least. Where that plan still undoes the overlaps both curves
        // have, the min-flips rule is planned too (it matches corners by
        // the flips they need, so a corner more often keeps its sense) and
        // kept on the same terms as the straight path below.
        // It must not trade the unwind for a detour past its gate, or for
        // segments its keys cannot certify (where frames come from the
        // path itself), which the first plan keeps.
        if options.correspondence == crate::morph::Correspondence::Best && unwind < KEPT_TURNING {
            let min_flips = options.with_correspondence(crate::morph::Correspondence::MinFlips);
            if let Ok((other, other_unwind)) = Self::raced(a, b, &min_flips)
                && other_unwind >= KEPT_TURNING
                && other.staged.mean_travel() <= RACE_TRAVEL * tween.staged.mean_travel()
                && (other.key_detour() <= DETOUR_GATE || tween.key_detour() > DETOUR_GATE)
                && (other.is_certified() || !tween.is_certified())
            {
                return Ok(other);
            }
        }
        Ok(tween)
    }

    /// Plans the morph with the options given and, for the rigid path,
    /// races the straight path against it where it unwinds; with the
    /// [`Tween::key_unwind`] of the morph kept.
    fn raced(
        a: &[Point],
        b: &[Point],
        options: &CurveMorphOptions,
    ) -> Result<(Tween, f64), CurveMorphError> {
        let tween = Self::planned(a, b, options, false)?;
        let unwind = tween.key_unwind();
        // The rigid path interpolates each triangle's rotation, so a corner
        // that turns one way on one curve and the other way on the other
        // passes through straight; where that undoes the overlaps both
        // curves have (unwind below KEPT_TURNING over the keys,
        // docs/design.md §7c), the straight path is planned too and kept
        // if it keeps that turning without its vertices travelling more
        // than RACE_TRAVEL times as far. One choice per morph: the motion
        // stays continuous.
        if options.morph.path == ThirdVertexPath::Rigid && unwind < KEPT_TURNING {
            let straight = options.with_morph(options.morph.with_path(ThirdVertexPath::Straight));
            if let Ok(other) = Self::planned(a, b, &straight, false) {
                let other_unwind = other.key_unwind();
                if other_unwind >= KEPT_TURNING
                    && other.staged.mean_travel() <= RACE_TRAVEL * tween.staged.mean_travel()
                {
                    return Ok((other, other_unwind));
                }
            }
        }
        Ok((tween, unwind))
    }

    /// The detour of §7b on the keys (the polyline every frame lies on).
    fn key_detour(&self) -> f64 {
        let frames: Vec<Frame> = self
            .keyframes()
            .into_iter()
            .map(|k| Frame {
                t: k.t,
                points: k.points,
                triangles: k.triangles,
            })
            .collect();
        crate::morph::measure::detour(&frames)
    }

    /// The least total absolute turning over the keys of the side used
    /// and the midpoints of the segments between them, divided by the
    /// smaller of its two ends' (the unwind of §7c on the keyed motion).
    fn key_unwind(&self) -> f64 {
        let turning = crate::geom::polygon::total_absolute_turning;
        let legs = &self.staged.legs;
        let (Some(first), Some(last)) = (
            legs.first().and_then(|l| l.keys.first()),
            legs.last().and_then(|l| l.keys.last()),
        ) else {
            return 1.0;
        };
        let ends = turning(first).min(turning(last));
        // At the keys and halfway along each segment between them, where a
        // player draws the chord (a corner that straightens between two
        // keys is least turned there). On every core: the least of the
        // same values whatever the order (at 5,000 vertices and 374 keys,
        // 71 ms on one).
        use rayon::prelude::*;
        let least = legs
            .par_iter()
            .flat_map(|l| {
                let halfway = l.keys.par_windows(2).map(|w| {
                    let mid: Vec<Point> = w[0]
                        .iter()
                        .zip(w[1].iter())
                        .map(|(p, q)| p.lerp(*q, 0.5))
                        .collect();
                    turning(&mid)
                });
                l.keys.par_iter().map(|k| turning(k)).chain(halfway)
            })
            .reduce(|| f64::INFINITY, f64::min);
        if ends > 0.0 { least / ends } else { 1.0 }
    }

    /// Plans the morph with exactly the options given; `strict` stops
    /// placing keys at the first segment they cannot certify (the tween is
    /// then not certified, and only good for being dropped).
    fn planned(
        a: &[Point],
        b: &[Point],
        options: &CurveMorphOptions,
        strict: bool,
    ) -> Result<Tween, CurveMorphError> {
        let (prepared, mut sides) = plan(a, b, options)?;
        let mut fallbacks = prepared.fallbacks.clone();
        let n = prepared.a.len();
        // Recovery: a side that failed gives way to the other; if both
        // failed, the max–min-angle triangulations are tried, then the
        // other intermediate (the target shape for the disk, the disk for
        // the target shape), then both changes at once.
        if sides.a.is_err() && sides.b.is_err() {
            let why = match &sides.a {
                Err(e) => e.reason(),
                Ok(_) => String::new(),
            };
            let other = match options.intermediate {
                Intermediate::Disk => Intermediate::Target,
                Intermediate::Target => Intermediate::Disk,
            };
            let maxmin = crate::quality::Quality::MaxMin;
            let mut retries: Vec<(CurveMorphOptions, String)> = Vec::new();
            if options.quality != maxmin {
                retries.push((
                    options.with_quality(maxmin),
                    "used the max–min-angle triangulations".to_string(),
                ));
            }
            retries.push((
                options.with_intermediate(other),
                format!("used the {} intermediate", other.as_str()),
            ));
            if options.quality != maxmin {
                retries.push((
                    options.with_intermediate(other).with_quality(maxmin),
                    format!(
                        "used the {} intermediate and the max–min-angle triangulations",
                        other.as_str()
                    ),
                ));
            }
            let min_flips = crate::morph::Correspondence::MinFlips;
            if options.correspondence != min_flips {
                for intermediate in [options.intermediate, other] {
                    retries.push((
                        options
                            .with_correspondence(min_flips)
                            .with_intermediate(intermediate),
                        format!(
                            "matched the vertices by the min-flips rule and used the {} intermediate",
                            intermediate.as_str()
                        ),
                    ));
                }
                if options.quality != maxmin {
                    for intermediate in [options.intermediate, other] {
                        retries.push((
                            options
                                .with_correspondence(min_flips)
                                .with_intermediate(intermediate)
                                .with_quality(maxmin),
                            format!(
                                "matched the vertices by the min-flips rule and used the {} intermediate and the max–min-angle triangulations",
                                intermediate.as_str()
                            ),
                        ));
                    }
                }
            }
            for (retry, what) in retries {
                let Ok((p, s)) = plan(a, b, &retry) else {
                    continue;
                };
                if s.chosen().is_some() {
                    fallbacks.push(Fallback::new(
                        &what,
                        &format!(
                            "both sides failed with the {} triangulations, the {} intermediate and the {} rule: {why}",
                            options.quality.as_str(),
                            options.intermediate.as_str(),
                            options.correspondence.as_str()
                        ),
                    ));
                    fallbacks.extend(p.fallbacks.iter().cloned());
                    return Tween::finish(p.a.len(), s, &retry, fallbacks, strict);
                }
            }
        }
        if sides.a.is_err() != sides.b.is_err() {
            let (failed, err) = match (&sides.a, &sides.b) {
                (Err(e), _) => (Side::Source, e.reason()),
                (_, Err(e)) => (Side::Target, e.reason()),
                _ => unreachable!("exactly one side failed"),
            };
            fallbacks.push(Fallback::new(
                &format!("used the other side instead of the {failed} side"),
                &err,
            ));
            sides.use_a = sides.a.is_ok();
        }
        Tween::finish(n, sides, options, fallbacks, strict)
    }

    fn finish(
        n: usize,
        sides: crate::morph::plan::Sides,
        options: &CurveMorphOptions,
        mut fallbacks: Vec<Fallback>,
        strict: bool,
    ) -> Result<Tween, CurveMorphError> {
        let star = |s: &crate::morph::plan::SideResult| match s {
            Ok(Some(s)) => s.u_star,
            Ok(None) | Err(_) => f64::NAN,
        };
        let (u_star, v_star) = (star(&sides.a), star(&sides.b));
        let (staged, used) = if sides.use_a {
            (sides.a?, Side::Source)
        } else {
            (sides.b?, Side::Target)
        };
        // A plan is kept only with a finished side, and that is the one
        // it uses.
        let mut staged = staged.ok_or_else(|| MorphError::InvalidFrame {
            t: 0.0,
            path: options.morph.path,
            defect: "the side kept was given up while planning".to_string(),
        })?;
        // The keys: the checked samples, split until every straight
        // segment between two keys keeps close to the path.
        let bridges: Vec<usize> = {
            use rayon::prelude::*;
            let tol = key_tolerance(&staged, options);
            staged
                .legs
                .par_iter_mut()
                .map(|leg| {
                    // (A strict plan left uncertified is dropped: its
                    // keys are not merged or repaired.)
                    let bridges = leg.refine_keys(tol, strict)?;
                    merge_keys(leg, tol);
                    leg.repair_keys();
                    // The keys are placed: the plan is built again only
                    // where a frame on an uncertified segment needs it.
                    leg.plan.release(&[]);
                    Some(bridges)
                })
                .collect::<Vec<_>>()
                .into_iter()
                .map(|b| b.unwrap_or(0))
                .collect()
        };
        fallbacks.extend(staged.fallbacks.iter().cloned());
        for ((j, &count), leg) in bridges.iter().enumerate().zip(&staged.legs) {
            if count > 0 {
                let (stretches, them) = (noun(count, "stretch", "stretches"), them(count));
                fallbacks.push(Fallback::new(
                    &format!(
                        "placed the keys of {count} {stretches} of leg {} on the straight path between two checked samples",
                        j + 1
                    ),
                    &format!(
                        "the {} path is not an immersion anywhere inside {them}: the layout's rounding turns a thin triangle over",
                        leg.path
                    ),
                ));
            }
        }
        let mut paths: Vec<ThirdVertexPath> = Vec::new();
        for leg in &staged.legs {
            if !paths.contains(&leg.path) {
                paths.push(leg.path);
            }
        }
        if !options.morph.path.is_guaranteed() && paths.len() > 1 {
            // Legs toward intermediates use a guaranteed path when an
            // unguaranteed one was asked for: say so.
            fallbacks.push(Fallback::new(
                &format!("used the {} path", crate::morph::output::path_names(&paths)),
                &format!(
                    "the {} path is not guaranteed, so the legs through intermediates use the hybrid path",
                    options.morph.path
                ),
            ));
        }
        let (pace, offsets, total) = pace_tables(&staged.legs);
        let report = MorphReport {
            n,
            shift: sides.k,
            flips: staged.flips,
            u_star,
            v_star,
            used,
            unblocks: staged.unblocks,
            used_disk: staged.used_disk,
            paths,
            fallbacks,
            repairs: staged.repairs,
        };
        Ok(Tween {
            n,
            staged,
            reversed: !sides.use_a,
            shift: sides.k,
            pace,
            offsets,
            total,
            report,
        })
    }

    /// What the planning did: shift, flips, side, paths, fallbacks.
    pub fn report(&self) -> &MorphReport {
        &self.report
    }

    /// Vertices of every frame.
    pub fn vertex_count(&self) -> usize {
        self.n
    }

    /// Total pace: the sum over the segments between keys of
    /// `max(m, M / c)` (module docs), a length; the unit of the frame
    /// timing and of a sequence's sharing of frames.
    pub fn path_length(&self) -> f64 {
        self.total
    }

    /// The number of keys [`Tween::keyframes`] lists (2 for a valid
    /// straight-line morph).
    pub fn key_count(&self) -> usize {
        let legs = &self.staged.legs;
        1 + legs
            .iter()
            .map(|l| l.keys.len().saturating_sub(1))
            .sum::<usize>()
    }

    /// The key segments left uncertified, and all of them.
    fn uncertified_segments(&self) -> (usize, usize) {
        let segments = self.staged.legs.iter().flat_map(|l| &l.certified);
        let total = segments.clone().count();
        (segments.filter(|&&c| !c).count(), total)
    }

    /// Whether every segment between two keys is certified an immersion
    /// for every s in exact arithmetic (docs/design.md §13). Where one is
    /// not, frames on it are checked one by one and fall back to the path.
    pub fn is_certified(&self) -> bool {
        self.staged
            .legs
            .iter()
            .all(|l| l.certified.iter().all(|&c| c))
    }

    /// The keys of the animation, in order of t (module docs,
    /// [`Keyframe`]), in the labels of the frames (the first curve's). A
    /// flip between two legs is written once, with the triangulation of
    /// the segment that follows it. Interpolating two consecutive keys
    /// linearly at fraction w of the way gives the frame at the t that
    /// fraction w of the way between theirs (up to rounding).
    pub fn keyframes(&self) -> Vec<Keyframe> {
        let legs = &self.staged.legs;
        // In the side's order: (fraction, points, triangles of the
        // segment before, triangles of the segment after).
        type SideKey<'a> = (f64, &'a [Point], &'a [[u32; 3]], &'a [[u32; 3]]);
        let mut side: Vec<SideKey<'_>> = Vec::with_capacity(self.key_count());
        let count = self.key_count().max(2);
        for (i, leg) in legs.iter().enumerate() {
            for (k, p) in leg.keys.iter().enumerate() {
                let tris = leg.segment_triangles(k);
                if k == 0 && i > 0 {
                    // The flip key: the previous leg's last key is the
                    // same shape; this one starts the following segment.
                    if let Some(last) = side.last_mut() {
                        last.1 = p;
                        last.3 = tris;
                    }
                    continue;
                }
                let d = self.offsets[i] + self.pace[i][k];
                let f = if self.total > 0.0 {
                    (d / self.total).clamp(0.0, 1.0)
                } else {
                    side.len() as f64 / (count - 1) as f64
                };
                let before = side.last().map_or(tris, |s| s.3);
                side.push((f, p, before, tris));
            }
        }
        if let Some(first) = side.first_mut() {
            first.0 = 0.0;
        }
        if let Some(last) = side.last_mut() {
            last.0 = 1.0;
        }
        let mut keys: Vec<Keyframe> = if self.reversed {
            let (n, k) = (self.n, self.shift);
            side.into_iter()
                .rev()
                .map(|(f, p, before, _)| Keyframe {
                    t: 1.0 - f,
                    points: (0..n).map(|i| p[(i + k) % n]).collect(),
                    triangles: shift_triangles(n, before, k),
                })
                .collect()
        } else {
            side.into_iter()
                .map(|(t, p, _, after)| Keyframe {
                    t,
                    points: p.to_vec(),
                    triangles: after.to_vec(),
                })
                .collect()
        };
        strictly_increasing(&mut keys);
        keys
    }

    /// The largest vertex move per unit of pace over the first frame step
    /// and over the last, for frame steps of `h` (a fraction of the pace):
    /// the largest move from t = 0 to t = h and from 1 − h to 1, over
    /// `h ×` [`Tween::path_length`]. How fast the fastest vertex leaves
    /// and arrives when frames are evenly paced; sequences match these at
    /// their keys. 1 where nothing moves.
    pub(crate) fn end_rates(&self, h: f64) -> (f64, f64) {
        let h = if h.is_finite() {
            h.clamp(1e-9, 1.0)
        } else {
            1.0
        };
        let unit = h * self.total;
        let rate = |a: f64, b: f64| -> f64 {
            match (self.frame(a), self.frame(b)) {
                (Ok(p), Ok(q)) if unit > 0.0 => {
                    let m = moves(&p.points, &q.points).0;
                    if m > 0.0 { m / unit } else { 1.0 }
                }
                _ => 1.0,
            }
        };
        (rate(0.0, h), rate(1.0 - h, 1.0))
    }

    /// The leg, its key interval and the fraction of the way through it
    /// at fraction `f` of the travel of the side used (0 = that side's
    /// curve).
    fn locate(&self, f: f64) -> (&Leg, usize, f64) {
        let legs = &self.staged.legs;
        let last = legs.len() - 1;
        if f >= 1.0 || self.total <= 0.0 && f >= 0.5 {
            let k = legs[last].keys.len().saturating_sub(2);
            return (&legs[last], k, 1.0);
        }
        if f <= 0.0 || self.total <= 0.0 {
            return (&legs[0], 0, 0.0);
        }
        let d = f * self.total;
        // The last leg that starts at or before d.
        let i = self
            .offsets
            .partition_point(|&o| o <= d)
            .clamp(1, legs.len())
            - 1;
        let leg = &legs[i];
        let (k, w) = key_at(&self.pace[i], d - self.offsets[i]);
        (leg, k, w)
    }

    /// The frame at fraction `t` ∈ [0, 1] of the pace (module docs; 0 =
    /// the source, exactly; 1 = the target, exactly), checked
    /// exactly. Vertex `i` is source vertex `i` (after equalising counts);
    /// at t = 1 it is target vertex `i + shift`.
    ///
    /// # Errors
    ///
    /// [`MorphError::Fraction`] for a t outside [0, 1] or NaN;
    /// [`MorphError::InvalidFrame`] (a bug) when no guaranteed path gives
    /// a valid frame at t.
    pub fn frame(&self, t: f64) -> Result<Frame, MorphError> {
        self.frame_with_fallback(t).map(|(f, _)| f)
    }

    /// [`Tween::frame`] with the fallback it took, if any (another path
    /// for this frame), as [`Tween::morph`] collects them.
    ///
    /// # Errors
    ///
    /// As [`Tween::frame`].
    pub(crate) fn frame_with_fallback(
        &self,
        t: f64,
    ) -> Result<(Frame, Option<Fallback>), MorphError> {
        if !(0.0..=1.0).contains(&t) {
            return Err(MorphError::Fraction(t));
        }
        let f = if self.reversed { 1.0 - t } else { t };
        let (leg, k, w) = self.locate(f);
        let tris = leg.segment_triangles(k);
        // The animation: every vertex on a straight line between two keys.
        let keys = &leg.keys;
        let between = |k: usize, w: f64| -> Vec<Point> {
            let a = &keys[k];
            let Some(b) = keys.get(k + 1) else {
                return a.to_vec();
            };
            if w <= 0.0 {
                a.to_vec()
            } else if w >= 1.0 {
                b.to_vec()
            } else {
                a.iter().zip(b.iter()).map(|(p, q)| p.lerp(*q, w)).collect()
            }
        };
        let interpolated = between(k, w);
        // Frames are checked exactly. Where the segment's points fail, in
        // the rounding of the interpolation or on a segment the keys could
        // not certify, the nearest point of the same segment that passes
        // is used if it lies within [`NUDGE_REACH`] of the segment;
        // otherwise the segment's bridge, then the path itself.
        let checked = match check_triangles(&interpolated, tris) {
            Ok(()) => Ok((interpolated, None)),
            Err(defect) => first_passing(nudges(w, NUDGE_REACH), tris, |v| between(k, v))
                .map(|(v, p)| {
                    let what = format!(
                        "took the frame at t = {t} from {v} of the way along its segment between two keys instead of {w}"
                    );
                    let why = format!("the segment's points there were not an immersion ({defect})");
                    (p, Some(Fallback::new(&what, &why)))
                })
                .map_err(|_| defect),
        };
        let (points, fallback) = match checked {
            Ok(found) => found,
            Err(defect) => {
                // The segment between the keys is not an immersion here (a
                // segment the keys could not certify). The frame comes from
                // the segment's bridge: the straight path planned between
                // its two keys (both valid) on the same triangulation,
                // which runs from one to the other as close to the chord
                // as validity allows, so frames on the chord and frames on
                // the bridge meet; where the bridge fails too, from the
                // path itself at this t (within the key tolerance of the
                // chord where the keys could follow it); and last from the
                // nearest point of the segment that passes (its keys do:
                // they are checked samples). A frame never jumps to
                // another path.
                let why = format!(
                    "the straight segment between two keys was not an immersion there ({defect})"
                );
                let near = |v: f64| {
                    if v == w {
                        String::new()
                    } else {
                        format!(", {v} of the way along the segment instead of {w}")
                    }
                };
                let fractions = || std::iter::once(w).chain(nudges(w, NUDGE_REACH));
                let bridge = keys.get(k + 1).and_then(|b| leg.bridge(&keys[k], b));
                let bridged = bridge.map(|br| {
                    first_passing(fractions(), tris, |v| {
                        br.positions(v, ThirdVertexPath::Straight)
                    })
                });
                match bridged {
                    Some(Ok((v, points))) => {
                        let what = format!(
                            "used the straight path between two keys for the frame at t = {t}{}",
                            near(v)
                        );
                        (points, Some(Fallback::new(&what, &why)))
                    }
                    _ => {
                        let why = format!("{why}, nor the straight path between its keys");
                        let samples = &leg.samples;
                        let span = samples.get(k + 1).map_or(0.0, |&s1| s1 - samples[k]);
                        let on_path = first_passing(fractions(), tris, |v| {
                            leg.plan.positions(samples[k] + v * span, leg.path)
                        });
                        match on_path {
                            Ok((v, on_path)) => {
                                let what = format!(
                                    "used the {} path itself for the frame at t = {t}{}",
                                    leg.path,
                                    near(v)
                                );
                                (on_path, Some(Fallback::new(&what, &why)))
                            }
                            Err(e) => {
                                let e = e.map_or_else(String::new, |e| e.to_string());
                                let ends = if w < 0.5 { [0.0, 1.0] } else { [1.0, 0.0] };
                                let Ok((v, points)) =
                                    first_passing(nudges(w, 1.0).chain(ends), tris, |v| {
                                        between(k, v)
                                    })
                                else {
                                    return Err(MorphError::InvalidFrame {
                                        t,
                                        path: leg.path,
                                        defect: e,
                                    });
                                };
                                let what = format!(
                                    "used the nearest valid point of the segment between two keys for the frame at t = {t} ({v} of the way along it instead of {w})"
                                );
                                let why = format!("{why}, nor the {} path ({e})", leg.path);
                                (points, Some(Fallback::new(&what, &why)))
                            }
                        }
                    }
                }
            }
        };
        Ok((self.place(t, points, tris), fallback))
    }

    /// The frame at `t` with `points` under `tris` (the leg's labels), in
    /// the labels of the frames.
    fn place(&self, t: f64, points: Vec<Point>, tris: &[[u32; 3]]) -> Frame {
        if self.reversed {
            let (n, k) = (self.n, self.shift);
            Frame {
                t,
                points: (0..n).map(|i| points[(i + k) % n]).collect(),
                triangles: shift_triangles(n, tris, k),
            }
        } else {
            Frame {
                t,
                points,
                triangles: tris.to_vec(),
            }
        }
    }

    /// Frames at the given fractions of the travel, each checked exactly,
    /// with the report's paths and fallbacks.
    ///
    /// # Errors
    ///
    /// As [`Tween::frame`].
    pub fn morph(&self, fractions: &[f64]) -> Result<Morph, MorphError> {
        let mut fallbacks = self.report.fallbacks.clone();
        let mut paths = self.report.paths.clone();
        let mut frames = Vec::with_capacity(fractions.len());
        // Frames are independent: computed and checked on every core, then
        // taken in order.
        let computed: Vec<Result<(Frame, Option<Fallback>), MorphError>> = {
            use rayon::prelude::*;
            fractions
                .par_iter()
                .map(|&t| self.frame_with_fallback(t))
                .collect()
        };
        for result in computed {
            let (frame, fb) = result?;
            if let Some(fb) = fb {
                fallbacks.push(fb);
                if let Some(p) = ThirdVertexPath::ALL.into_iter().find(|p| {
                    fallbacks
                        .last()
                        .is_some_and(|f| f.what.contains(p.as_str()))
                }) {
                    if !paths.contains(&p) {
                        paths.push(p);
                    }
                }
            }
            frames.push(frame);
        }
        Ok(Morph::new(paths, fallbacks, frames))
    }
}

/// How far along a segment between two keys [`Tween::frame`] looks for a
/// point that passes the exact check, as a fraction of the segment.
const NUDGE_REACH: f64 = 1.0 / (1u64 << 20) as f64;

/// The fractions near `w` ∈ [0, 1] to try for a frame, nearest first: at
/// distances 2⁻⁴⁴, 2⁻⁴², … up to `reach`, on either side, within [0, 1].
/// The measures of docs/design.md §7c that [`Tween::new`] holds a route
/// to ([`Tween::motion`]).
#[derive(Clone, Copy, Debug)]
struct Motion {
    /// Whether the largest single-vertex step fails to shrink with the
    /// frame count.
    jumps: bool,
    /// Longest edge over the ends' longest.
    edge: f64,
    /// Least and most total area over the smaller and the larger end's.
    area: (f64, f64),
    detour: f64,
    unwind: f64,
}

/// The routes [`Tween::new`] tries, in order, where the keys of the plan
/// chosen for its motion cannot all be certified: each guaranteed path
/// alone (without the last leg's race) with the options' correspondence;
/// where that is `best`, the rigid and the straight path with each of its
/// other rules; then those two with the other intermediate, and the rigid
/// path with the max–min-angle triangulations. Each comes with what the
/// report says of it. Each is planned strictly: its keys stop at the
/// first segment no flip certifies, so a route that fails costs little
/// more than its planning (docs/motion.md has what each route certifies
/// on the stress pairs).
fn certifying_routes(options: &CurveMorphOptions) -> Vec<(CurveMorphOptions, String)> {
    use crate::morph::{Correspondence, Intermediate};
    use crate::quality::Quality;
    use ThirdVertexPath::{Hybrid, Rigid, Straight};
    let alone = |route: CurveMorphOptions, path: ThirdVertexPath, said: String| {
        let morph = MorphOptions {
            path,
            rivals: false,
            ..route.morph
        };
        (
            route.with_morph(morph),
            format!("planned the morph again with the {path} path alone{said}"),
        )
    };
    let mut routes: Vec<(CurveMorphOptions, String)> = [Rigid, Straight, Hybrid]
        .into_iter()
        .map(|path| alone(*options, path, String::new()))
        .collect();
    // (The hybrid path certified no pair the others left on 2,000 stress
    // pairs with another rule, intermediate or triangulation, nor the
    // straight one with the max–min triangulations: not tried there.)
    if options.correspondence == Correspondence::Best {
        for rule in [Correspondence::MinFlips, Correspondence::Corners] {
            for path in [Rigid, Straight] {
                let said = format!(", the {} rule", rule.as_str());
                routes.push(alone(options.with_correspondence(rule), path, said));
            }
        }
    }
    let other = match options.intermediate {
        Intermediate::Disk => Intermediate::Target,
        Intermediate::Target => Intermediate::Disk,
    };
    for path in [Rigid, Straight] {
        let said = format!(", the {} intermediate", other.as_str());
        routes.push(alone(options.with_intermediate(other), path, said));
    }
    if options.quality != Quality::MaxMin {
        let said = ", the max–min-angle triangulations".to_string();
        routes.push(alone(options.with_quality(Quality::MaxMin), Rigid, said));
    }
    routes
}

fn nudges(w: f64, reach: f64) -> impl Iterator<Item = f64> {
    (0..)
        .map(|i| (-44.0 + 2.0 * f64::from(i)).exp2())
        .take_while(move |&d| d <= reach)
        .flat_map(move |d| [w - d, w + d])
        .filter(|v| (0.0..=1.0).contains(v))
}

/// The first of the fractions `fractions` whose points `at(v)` pass the
/// exact check on `tris`, with the fraction; else the first defect met
/// (`None` when there was no fraction to try).
fn first_passing(
    fractions: impl Iterator<Item = f64>,
    tris: &[[u32; 3]],
    at: impl Fn(f64) -> Vec<Point>,
) -> Result<(f64, Vec<Point>), Option<crate::immersion::ImmersionDefect>> {
    let mut first = None;
    for v in fractions {
        let p = at(v);
        match check_triangles(&p, tris) {
            Ok(()) => return Ok((v, p)),
            Err(e) => {
                first.get_or_insert(e);
            }
        }
    }
    Err(first)
}

/// The key interval at `d` ∈ [0, last] of the cumulative table `c` and the
/// fraction of the way through it: `(i, w)` for the straight segment from
/// key `i` to key `i + 1`.
fn key_at(c: &[f64], d: f64) -> (usize, f64) {
    if c.len() < 2 || d <= 0.0 {
        return (0, 0.0);
    }
    let i = c.partition_point(|&x| x < d).clamp(1, c.len() - 1);
    let (c0, c1) = (c[i - 1], c[i]);
    let w = if c1 > c0 {
        ((d - c0) / (c1 - c0)).clamp(0.0, 1.0)
    } else {
        1.0
    };
    (i - 1, w)
}

/// The pace tables of `legs` (module docs): per leg, the cumulative pace
/// at each key.
fn pace_tables(legs: &[Leg]) -> (Vec<Vec<f64>>, Vec<f64>, f64) {
    // Mean and largest vertex move of every segment between keys.
    let per_leg: Vec<Vec<(f64, f64)>> = legs
        .iter()
        .map(|l| {
            l.keys
                .windows(2)
                .map(|w| {
                    let (max, mean) = moves(&w[0], &w[1]);
                    (mean, max)
                })
                .collect()
        })
        .collect();
    let all: Vec<(f64, f64)> = per_leg.iter().flatten().copied().collect();
    let c = pace_ratio(&all);
    let tables: Vec<Vec<f64>> = per_leg
        .iter()
        .map(|segs| {
            let mut table = Vec::with_capacity(segs.len() + 1);
            let mut acc = 0.0;
            table.push(acc);
            for &(m, big) in segs {
                acc += pace(m, big, c);
                table.push(acc);
            }
            table
        })
        .collect();
    let mut offsets = Vec::with_capacity(tables.len());
    let mut total = 0.0;
    for t in &tables {
        offsets.push(total);
        total += t.last().copied().unwrap_or(0.0);
    }
    (tables, offsets, total)
}

/// The key tolerance of `options` as a length: its fraction of the larger
/// of the plan's two ends' bounding-box diagonals.
fn key_tolerance(staged: &Staged, options: &CurveMorphOptions) -> f64 {
    let d = crate::geom::polygon::bbox_diagonal;
    let first = staged.legs.first().and_then(|l| l.keys.first());
    let last = staged.legs.last().and_then(|l| l.keys.last());
    let diagonal = first.map_or(0.0, |p| d(p)).max(last.map_or(0.0, |p| d(p)));
    options.key_tolerance * diagonal
}

/// The pace of a segment whose vertices move `mean` on average and `max`
/// at most, for the ratio `c`.
fn pace(mean: f64, max: f64, c: f64) -> f64 {
    mean.max(max / c)
}

/// The ratio c of [`pace`] for segments `(mean, max)`: among the
/// segments' own ratios max / mean, the one whose even frames keep the
/// largest per-frame mean move and largest per-frame single-vertex move
/// closest to their medians (each measured against its aim, 1.5 and 2).
fn pace_ratio(segs: &[(f64, f64)]) -> f64 {
    let moving: Vec<(f64, f64)> = segs
        .iter()
        .copied()
        .filter(|&(m, big)| m > 0.0 && big > 0.0 && m.is_finite() && big.is_finite())
        .collect();
    if moving.is_empty() {
        return 1.0;
    }
    let mut ratios: Vec<f64> = moving.iter().map(|&(m, big)| big / m).collect();
    ratios.sort_by(f64::total_cmp);
    ratios.dedup();
    // At most 64 candidates, spread over the sorted ratios.
    let stride = ratios.len().div_ceil(64).max(1);
    let mut candidates: Vec<f64> = ratios.iter().copied().step_by(stride).collect();
    candidates.push(ratios[ratios.len() - 1]);
    let mut best = (f64::INFINITY, candidates[0]);
    for &c in &candidates {
        let score = pace_score(&moving, c);
        if score < best.0 {
            best = (score, c);
        }
    }
    best.1
}

/// How far the even frames of pace ratio `c` are from the aims: the larger
/// of (largest / median per-frame mean move) / 1.5 and (largest / median
/// per-frame largest vertex move) / 2, medians weighted by the frames each
/// segment gets (its pace).
fn pace_score(segs: &[(f64, f64)], c: f64) -> f64 {
    let mut means = Vec::with_capacity(segs.len());
    let mut maxes = Vec::with_capacity(segs.len());
    for &(m, big) in segs {
        let d = pace(m, big, c);
        means.push((m / d, d));
        maxes.push((big / d, d));
    }
    let spread = |v: &mut Vec<(f64, f64)>| -> f64 {
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        let total: f64 = v.iter().map(|x| x.1).sum();
        let mut acc = 0.0;
        let mut median = v[v.len() - 1].0;
        for &(x, w) in v.iter() {
            acc += w;
            if acc >= 0.5 * total {
                median = x;
                break;
            }
        }
        v[v.len() - 1].0 / median
    };
    (spread(&mut means) / 1.5).max(spread(&mut maxes) / 2.0)
}

/// The keys an output writes when frame `i` shows the animation of `keys`
/// at `times[i]` (a fraction of the pace, as [`Tween::frame`] takes it):
/// each key's `t` becomes the frame, possibly fractional, at which the
/// frames pass it, found linearly between the two frames around it; the
/// first and last frames are keys, and so is every frame that repeats
/// its neighbour's time (a hold) or, with `every_frame`, every frame (for
/// eased or played-back timing, whose speed changes inside a segment).
/// The shapes between two written keys are then the animation's own: a
/// part of one of its straight segments, played at constant speed
/// (docs/design.md §12). Times may go back and forth (a ping-pong or an
/// easing that overshoots); every key crossed is written.
///
/// Returns keys with strictly increasing `t` in frames, each with the
/// triangulation of the animation's segment that the written segment
/// after it lies on. Expects `keys` as [`Tween::keyframes`] gives them
/// and `times` in [0, 1].
pub fn timed_keyframes(keys: &[Keyframe], times: &[f64], every_frame: bool) -> Vec<Keyframe> {
    let (Some(first_key), Some(last_key)) = (keys.first(), keys.last()) else {
        return Vec::new();
    };
    if times.is_empty() {
        return Vec::new();
    }
    // The shape at animation time u, and the segment u lies in (the one
    // after it at a key).
    let segment_of = |u: f64| -> usize {
        keys.partition_point(|k| k.t <= u)
            .saturating_sub(1)
            .min(keys.len().saturating_sub(2))
    };
    let shape_at = |u: f64| -> Vec<Point> {
        if u <= first_key.t {
            return first_key.points.clone();
        }
        if u >= last_key.t {
            return last_key.points.clone();
        }
        let j = segment_of(u);
        let (a, b) = (&keys[j], &keys[j + 1]);
        if u == a.t {
            return a.points.clone();
        }
        let w = if b.t > a.t {
            (u - a.t) / (b.t - a.t)
        } else {
            1.0
        };
        a.points
            .iter()
            .zip(&b.points)
            .map(|(p, q)| p.lerp(*q, w))
            .collect()
    };
    // (frame position, animation time, a key's index when exactly a key)
    let mut out: Vec<(f64, f64, Option<usize>)> = Vec::new();
    let last = times.len() - 1;
    for (i, &u) in times.iter().enumerate() {
        let held = (i > 0 && times[i - 1] == u) || (i < last && times[i + 1] == u);
        if i == 0 || i == last || held || every_frame {
            let exact = keys.iter().position(|k| k.t == u);
            out.push((i as f64, u, exact));
        }
        if let Some(&v) = times.get(i + 1)
            && v != u
        {
            // Keys strictly between u and v, in the order they are met.
            let (lo, hi) = (u.min(v), u.max(v));
            let from = keys.partition_point(|k| k.t <= lo);
            let to = keys.partition_point(|k| k.t < hi);
            let mut crossed: Vec<usize> = (from..to).collect();
            if v < u {
                crossed.reverse();
            }
            for j in crossed {
                let x = i as f64 + (keys[j].t - u) / (v - u);
                if x > i as f64 && x < (i + 1) as f64 {
                    out.push((x, keys[j].t, Some(j)));
                }
            }
        }
    }
    let count = out.len();
    let mut written = (0..count)
        .map(|m| {
            let (x, u, exact) = out[m];
            // The segment the written segment after this key lies on (for
            // the last key, the one before it).
            let (a, b) = if m + 1 < count {
                (u, out[m + 1].1)
            } else if m > 0 {
                (out[m - 1].1, u)
            } else {
                (u, u)
            };
            let seg = if a == b {
                segment_of(a)
            } else {
                segment_of(0.5 * (a + b))
            };
            Keyframe {
                t: x,
                points: exact.map_or_else(|| shape_at(u), |j| keys[j].points.clone()),
                triangles: keys[seg.min(keys.len() - 1)].triangles.clone(),
            }
        })
        .collect::<Vec<_>>();
    // Keys crossed less than the resolution of a frame position apart.
    strictly_increasing(&mut written);
    written
}

/// Makes the keys' times strictly increasing between the first key's and
/// the last's by the fewest units in the last place: where a stretch of
/// keys moves less than the resolution of t (its travel, over the whole
/// travel, below a unit in the last place of t), their times round to one
/// value, and each is moved to the next double above the previous key's
/// (then below the following key's, towards the last). Every key is kept:
/// the segments between them are what is certified.
pub(crate) fn strictly_increasing(keys: &mut [Keyframe]) {
    use crate::certify::exact::{next_down, next_up};
    for k in 1..keys.len().saturating_sub(1) {
        let floor = next_up(keys[k - 1].t);
        keys[k].t = keys[k].t.max(floor);
    }
    for k in (0..keys.len().saturating_sub(1)).rev() {
        let ceiling = next_down(keys[k + 1].t);
        keys[k].t = keys[k].t.min(ceiling);
    }
}

/// How many keys past an uncertified segment [`merge_keys`] looks for a
/// certified chord over it: a bound on the work.
const BRIDGE_REACH: usize = 64;

/// `one` or `many`, as `count` asks (for the report's sentences).
fn noun<'a>(count: usize, one: &'a str, many: &'a str) -> &'a str {
    if count == 1 { one } else { many }
}

/// The pronoun that stands for `count` things: "it" or "them".
fn them(count: usize) -> &'static str {
    noun(count, "it", "them")
}

/// Drops the keys of `leg` that a straight segment does not need: greedily
/// from each kept key, the farthest later key such that the straight
/// segment to it passes within `tol` of every key in between (each vertex,
/// at its own parameter along the leg), keeps their total area within
/// [`KEY_AREA_TOLERANCE`], and is certified an immersion for every s with
/// the margin of double-precision interpolation, as frames are computed
/// (docs/design.md §13). So a straight-line morph keeps
/// its two ends. Farther keys are tried at doubling distances, then by
/// bisection: O(k log k) segment checks for k keys.
fn merge_keys(leg: &mut Leg, tol: f64) {
    let count = leg.keys.len();
    if count < 3 || leg.certified.len() + 1 != count {
        return;
    }
    let tris = leg.plan.triangles().to_vec();
    let view: &Leg = leg;
    let (keys, samples) = (&view.keys, &view.samples);
    let checked = crate::immersion::CheckedTriangles::new(keys[0].len(), &tris);
    // The path halfway between keys k − 1 and k, and the areas there and
    // at each key: computed once, whatever (i, j) asks for them.
    let halfway: Vec<OnceCell<(Vec<Point>, f64)>> = (0..count).map(|_| OnceCell::new()).collect();
    let key_area: Vec<OnceCell<f64>> = (0..count).map(|_| OnceCell::new()).collect();
    let halfway_at = |k: usize| {
        halfway[k].get_or_init(|| {
            let mid = 0.5 * (samples[k - 1] + samples[k]);
            let on = view.plan.positions(mid, view.path);
            let area = area_and_centroid(&on, &tris).0;
            (on, area)
        })
    };
    let area_at = |k: usize| *key_area[k].get_or_init(|| area_and_centroid(&keys[k], &tris).0);
    // Whether the chord from key i to key j passes within the tolerance of
    // `on` (the path at `sk`, of area `on_area`), in position and area.
    let near = |i: usize, j: usize, sk: f64, on: &[Point], on_area: f64| -> bool {
        let (a, b) = (&keys[i], &keys[j]);
        let w = (sk - samples[i]) / (samples[j] - samples[i]);
        let chord = || a.iter().zip(b.iter()).map(|(p, q)| p.lerp(*q, w));
        // (Vertex by vertex, so that a far chord is refused at its first
        // vertex out of reach; the area only for a chord within reach.)
        chord().zip(on).all(|(c, p)| (c - *p).length() <= tol) && {
            let on_chord = area_and_centroid(&chord().collect::<Vec<Point>>(), &tris).0;
            (on_chord - on_area).abs() <= KEY_AREA_TOLERANCE * on_area.abs()
        }
    };
    let joins = |i: usize, j: usize| -> bool {
        let span = samples[j] - samples[i];
        if span.is_nan() || span <= 0.0 {
            return false;
        }
        // Every skipped key, and the path halfway between each two keys.
        let close = (i + 1..j).all(|k| {
            let (on, on_area) = halfway_at(k);
            near(i, j, samples[k], &keys[k], area_at(k))
                && near(i, j, 0.5 * (samples[k - 1] + samples[k]), on, *on_area)
        }) && {
            // And halfway through the last key interval.
            let (on, on_area) = halfway_at(j);
            near(i, j, 0.5 * (samples[j - 1] + samples[j]), on, *on_area)
        };
        close
            && crate::certify::segment_holds(
                &keys[i],
                &keys[j],
                &checked,
                crate::certify::Player::F64,
            )
    };
    let mut kept = vec![0usize];
    let mut i = 0;
    while i + 1 < count {
        // The farthest j with joins(i, j), j = i + 1 always kept. Where
        // the segment to key i + 1 is not certified (the path's samples
        // there are closer than its rounding), a longer chord over it is
        // tried first, at doubling distances up to [`BRIDGE_REACH`] keys.
        let mut first = i + 1;
        if !view.certified[i] {
            let mut reach = 1usize;
            while reach <= BRIDGE_REACH && i + 1 + reach < count {
                if joins(i, i + 1 + reach) {
                    first = i + 1 + reach;
                    break;
                }
                reach *= 2;
            }
        }
        let good = crate::staged::farthest_join(first, count, |j| joins(i, j));
        kept.push(good);
        i = good;
    }
    if kept.len() == count {
        return;
    }
    let certified: Vec<bool> = kept
        .windows(2)
        .map(|w| w[1] > w[0] + 1 || leg.certified[w[0]])
        .collect();
    leg.keys = kept
        .iter()
        .map(|&k| std::mem::take(&mut leg.keys[k]))
        .collect();
    leg.samples = kept.iter().map(|&k| leg.samples[k]).collect();
    leg.certified = certified;
    leg.repaired.clear();
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Keys whose times round to one value are spread over the next
    /// doubles, each by the fewest units in the last place, the ends and
    /// every key kept; times already increasing stay.
    #[test]
    fn equal_key_times_are_spread_by_units_in_the_last_place() {
        let key = |t: f64| Keyframe {
            t,
            points: vec![Point::new(t, 0.0)],
            triangles: Vec::new(),
        };
        let near = 1.0 - 7.5e-11;
        let times = [0.0, 0.5, near, near, near, 1.0, 1.0, 1.0];
        let mut keys: Vec<Keyframe> = times.iter().map(|&t| key(t)).collect();
        strictly_increasing(&mut keys);
        let t: Vec<f64> = keys.iter().map(|k| k.t).collect();
        assert!(t.windows(2).all(|w| w[0] < w[1]), "{t:?}");
        assert_eq!((t[0], t[1], t[2]), (0.0, 0.5, near));
        assert_eq!(t[3], f64::from_bits(near.to_bits() + 1));
        assert_eq!(t[4], f64::from_bits(near.to_bits() + 2));
        assert_eq!(t[7], 1.0);
        assert_eq!(t[6], f64::from_bits(1.0f64.to_bits() - 1));
        assert_eq!(t[5], f64::from_bits(1.0f64.to_bits() - 2));
        assert_eq!(keys.len(), times.len());
    }
}
