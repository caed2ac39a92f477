//! A morph planned once, asked for frames at any t (docs/design.md §12).
//!
//! [`Tween::new`] does all the planning of [`super::morph_curves`]: equal
//! counts, triangulations, correspondence, both staged sides and the
//! choice between them, every leg walked and checked exactly at its
//! samples, and the timing table (cumulative largest vertex move over the
//! samples). [`Tween::frame`] then costs one layout and one exact check,
//! O(n), and gives the same frame for the same t however it is called.

use super::curves::{CurveMorphError, CurveMorphOptions, MorphReport, Side, plan};
use super::staged::{Leg, recovery_paths};
use super::{MorphError, Staged, ThirdVertexPath};
use crate::correspond::shift_triangles;
use crate::frames::{Fallback, Frame, Morph};
use crate::geom::Point;
use crate::immersion::check_triangles;

/// How far the straight segment between two keys may stray from the
/// planned path at its midpoint, as a fraction of the larger end's
/// bounding-box diagonal (0.25 %).
pub(crate) const KEY_TOLERANCE: f64 = 0.0025;

/// The unwind below which a rigid morph is raced by the straight one
/// ([`Tween::new`]): the gate of docs/design.md §7c.
const KEPT_TURNING: f64 = 0.9;

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
    /// Travel at the start of each leg, and in all.
    offsets: Vec<f64>,
    total: f64,
    report: MorphReport,
}

impl Tween {
    /// Plans the morph of curve `a` into curve `b` (both oriented, turning
    /// number +1), as [`super::morph_curves`] does.
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
        let tween = Self::planned(a, b, options)?;
        // The rigid path interpolates each triangle's rotation, so a corner
        // that turns one way on one curve and the other way on the other
        // passes through straight; where that undoes the overlaps both
        // curves have (unwind below KEPT_TURNING over the keys,
        // docs/design.md §7c), the straight path is planned too and kept
        // if it keeps that turning without its vertices travelling more
        // than RACE_TRAVEL times as far. One choice per morph: the motion
        // stays continuous.
        if options.morph.path == ThirdVertexPath::Rigid {
            let unwind = tween.key_unwind();
            if unwind < KEPT_TURNING {
                let straight =
                    options.with_morph(options.morph.with_path(ThirdVertexPath::Straight));
                if let Ok(other) = Self::planned(a, b, &straight)
                    && other.key_unwind() >= KEPT_TURNING
                    && other.staged.mean_travel() <= RACE_TRAVEL * tween.staged.mean_travel()
                {
                    return Ok(other);
                }
            }
        }
        Ok(tween)
    }

    /// The least total absolute turning over the keys of the side used,
    /// divided by the smaller of its two ends' (the unwind of §7c on the
    /// keys).
    fn key_unwind(&self) -> f64 {
        let turning = crate::frames::total_absolute_turning;
        let legs = &self.staged.legs;
        let (Some(first), Some(last)) = (
            legs.first().and_then(|l| l.keys.first()),
            legs.last().and_then(|l| l.keys.last()),
        ) else {
            return 1.0;
        };
        let ends = turning(first).min(turning(last));
        let least = legs
            .iter()
            .flat_map(|l| &l.keys)
            .map(|k| turning(k))
            .fold(f64::INFINITY, f64::min);
        if ends > 0.0 { least / ends } else { 1.0 }
    }

    /// Plans the morph with exactly the options given.
    fn planned(
        a: &[Point],
        b: &[Point],
        options: &CurveMorphOptions,
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
                super::Intermediate::Disk => super::Intermediate::Target,
                super::Intermediate::Target => super::Intermediate::Disk,
            };
            let maxmin = crate::Quality::MaxMin;
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
            let min_flips = super::Correspondence::MinFlips;
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
                    return Tween::finish(p.a.len(), s, &retry, fallbacks);
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
        Tween::finish(n, sides, options, fallbacks)
    }

    fn finish(
        n: usize,
        sides: super::curves::Sides,
        options: &CurveMorphOptions,
        mut fallbacks: Vec<Fallback>,
    ) -> Result<Tween, CurveMorphError> {
        let star = |s: &super::curves::SideResult| match s {
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
        let diagonal = {
            let d = crate::geom::polygon::bbox_diagonal;
            let first = staged.legs.first().and_then(|l| l.keys.first());
            let last = staged.legs.last().and_then(|l| l.keys.last());
            first.map_or(0.0, |p| d(p)).max(last.map_or(0.0, |p| d(p)))
        };
        {
            use rayon::prelude::*;
            let tol = KEY_TOLERANCE * diagonal;
            staged.legs.par_iter_mut().for_each(|leg| {
                leg.refine_keys(tol);
            });
        }
        fallbacks.extend(staged.fallbacks.iter().cloned());
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
                &format!("used the {} path", crate::frames::path_names(&paths)),
                &format!(
                    "the {} path is not guaranteed, so the legs through intermediates use the hybrid path",
                    options.morph.path
                ),
            ));
        }
        let mut offsets = Vec::with_capacity(staged.legs.len());
        let mut total = 0.0;
        for leg in &staged.legs {
            offsets.push(total);
            total += leg.length();
        }
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

    /// Total travel: the sum over the checked samples of the largest
    /// vertex move (the unit of the frame timing).
    pub fn path_length(&self) -> f64 {
        self.total
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
        let (k, w) = leg.key_at(d - self.offsets[i]);
        (leg, k, w)
    }

    /// The frame at fraction `t` ∈ [0, 1] of the total vertex travel
    /// (0 = the source, exactly; 1 = the target, exactly), checked
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
    pub fn frame_with_fallback(&self, t: f64) -> Result<(Frame, Option<Fallback>), MorphError> {
        if !(0.0..=1.0).contains(&t) {
            return Err(MorphError::Fraction(t));
        }
        let f = if self.reversed { 1.0 - t } else { t };
        let (leg, k, w) = self.locate(f);
        let tris = leg.plan.triangles();
        // The animation: every vertex on a straight line between two keys.
        let keys = &leg.keys;
        let between = |k: usize| -> Vec<Point> {
            let a = &keys[k];
            let Some(b) = keys.get(k + 1) else {
                return a.clone();
            };
            if w <= 0.0 {
                a.clone()
            } else if w >= 1.0 {
                b.clone()
            } else {
                a.iter().zip(b).map(|(p, q)| p.lerp(*q, w)).collect()
            }
        };
        let interpolated = between(k);
        // Frames are checked exactly; where the straight segment fails (a
        // segment the keys could not certify), the path itself is used.
        let checked = check_triangles(&interpolated, tris).map(|()| interpolated);
        let (points, fallback) = match checked {
            Ok(points) => (points, None),
            Err(defect) => {
                // The segment between the keys is not an immersion here:
                // the path itself at this t, with the guaranteed paths in
                // turn.
                let samples = &leg.samples;
                let s = match samples.get(k + 1) {
                    Some(&s1) => samples[k] + w * (s1 - samples[k]),
                    None => samples[k],
                };
                let mut first_defect = None;
                let mut found = None;
                for path in recovery_paths(leg.path) {
                    let p = leg.plan.positions(s, path);
                    match check_triangles(&p, tris) {
                        Ok(()) => {
                            found = Some((p, path));
                            break;
                        }
                        Err(e) => {
                            first_defect.get_or_insert((path, e));
                        }
                    }
                }
                let Some((points, path)) = found else {
                    let (path, e) = first_defect.unwrap_or((leg.path, defect));
                    return Err(MorphError::InvalidFrame {
                        t,
                        path,
                        defect: e.to_string(),
                    });
                };
                let what = if path == leg.path {
                    format!("used the {path} path itself for the frame at t = {t}")
                } else {
                    format!("used the {path} path for the frame at t = {t}")
                };
                let why = match first_defect {
                    Some((p, e)) => format!(
                        "the straight segment between two keys was not an immersion there ({defect}), nor the {p} path ({e})"
                    ),
                    None => format!(
                        "the straight segment between two keys was not an immersion there ({defect})"
                    ),
                };
                (points, Some(Fallback::new(&what, &why)))
            }
        };
        let frame = if self.reversed {
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
        };
        Ok((frame, fallback))
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
        Ok(Morph {
            paths,
            fallback: !fallbacks.is_empty(),
            fallbacks,
            frames,
        })
    }
}
