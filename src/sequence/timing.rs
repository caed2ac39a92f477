//! Where the frames of a sequence fall: keys at whole frame numbers,
//! holds as repeated frames, and the frames in between placed by vertex
//! travel so the speed carries through a key.
//!
//! Time is counted in frames at [`Timing::fps`]. Key `j` has a frame
//! number F_j; it holds for h_j extra frames; segment `j` then takes s_j
//! frame steps to key `j + 1` (F_{j+1} = F_j + h_j + s_j). A segment's s_j
//! is fixed by a `duration`, or by the `time`s of the keys around it;
//! otherwise it is *free*. Between two keys whose frame numbers are known
//! (the first key, keys with a `time`, keys reached through fixed
//! durations, and the last key when the total frame count is given), the
//! free segments share the remaining steps in proportion to their travel
//! ([`crate::morph::Tween::path_length`]), divided by a relative speed
//! that makes the speed continuous where one free segment meets the
//! next: segment `j + 1` starts as fast as segment `j` ends, counting the
//! easing's slope at each end (1 for linear). A key with a hold, a time,
//! or an easing that stops there (slope below 0.05) starts the
//! chain afresh. Steps are whole numbers, handed out one at a time to the
//! segment that is currently fastest (the largest travel per step), so
//! the speeds stay as even as whole steps allow. Without a total, a run
//! of free segments at the end lasts [`DEFAULT_SECONDS_PER_SEGMENT`] per
//! segment.
//!
//! Within segment `j`, step `k` of s_j is at travel fraction
//! `easing(k / s_j)` of that segment's tween.

use super::SequenceError;
use crate::frames::Frame;
use std::sync::Arc;

/// An easing slope below this at a segment's end counts as a stop.
pub(crate) const STOP_SLOPE: f64 = 0.05;

/// Seconds per segment of a run of free segments whose end no time,
/// duration or total fixes.
pub(crate) const DEFAULT_SECONDS_PER_SEGMENT: f64 = 2.0;

/// The frame step, as a share of a segment's pace, over which its speed
/// at a key is first measured (see [`crate::morph::Tween::end_rates`]).
pub(crate) const RATE_WINDOW: f64 = 0.02;

/// Most frames a sequence may have.
pub(crate) const MAX_FRAMES: usize = 100_000;

/// An easing function x ↦ y on [0, 1] with y(0) = 0 and y(1) = 1: the
/// timing of one segment. The library has no easing curves of its own
/// (the CLI passes CSS easings); [`Ease::LINEAR`] is the identity.
#[derive(Clone, Default)]
pub struct Ease(Option<Arc<dyn Fn(f64) -> f64 + Send + Sync>>);

impl Ease {
    /// Constant speed.
    pub const LINEAR: Ease = Ease(None);

    /// An easing from a function (it should map 0 to 0 and 1 to 1).
    pub fn new(f: impl Fn(f64) -> f64 + Send + Sync + 'static) -> Ease {
        Ease(Some(Arc::new(f)))
    }

    /// The eased value of `x` ∈ [0, 1].
    pub(crate) fn apply(&self, x: f64) -> f64 {
        match &self.0 {
            None => x,
            Some(f) => f(x),
        }
    }

    /// True for [`Ease::LINEAR`].
    pub fn is_linear(&self) -> bool {
        self.0.is_none()
    }

    /// The slope at x = 0 and at x = 1 (1 and 1 for linear), by a
    /// one-sided difference.
    pub(crate) fn end_slopes(&self) -> (f64, f64) {
        if self.is_linear() {
            return (1.0, 1.0);
        }
        let d = 1e-4;
        let s0 = (self.apply(d) - self.apply(0.0)) / d;
        let s1 = (self.apply(1.0) - self.apply(1.0 - d)) / d;
        let ok = |s: f64| if s.is_finite() { s.max(0.0) } else { 1.0 };
        (ok(s0), ok(s1))
    }
}

impl std::fmt::Debug for Ease {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.is_linear() {
            "Ease::LINEAR"
        } else {
            "Ease(fn)"
        })
    }
}

/// The timing of one key and of the segment that leaves it.
#[derive(Clone, Debug, Default)]
pub struct KeyTiming {
    /// When the key is reached, in seconds from the first key (which is
    /// at 0).
    pub time: Option<f64>,
    /// Seconds the key is held (repeated frames) before the next segment
    /// starts.
    pub hold: f64,
    /// Seconds the segment leaving this key takes (not on the last key).
    pub duration: Option<f64>,
    /// Easing of the segment leaving this key.
    pub easing: Ease,
}

/// The timing of a whole sequence.
#[derive(Clone, Debug)]
pub struct Timing {
    /// Frames per second (above 0, at most 1000).
    pub fps: f64,
    /// Frames in all, holds included; `None` lets times, durations and
    /// the default of 2 s per segment decide.
    pub frames: Option<usize>,
    /// One per key.
    pub keys: Vec<KeyTiming>,
}

impl Timing {
    /// Linear, free timing for `keys` keys at 30 frames per second.
    pub fn new(keys: usize) -> Timing {
        Timing {
            fps: 30.0,
            frames: None,
            keys: vec![KeyTiming::default(); keys],
        }
    }
}

crate::options::setters! {
    Timing {
        /// Sets the total frame count.
        fn with_frames(frames: Option<usize>);
        /// Sets the frame rate.
        fn with_fps(fps: f64);
    }
}

/// One output frame: a segment and the travel fraction of its tween.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// The segment (key `segment` to key `segment + 1`).
    pub segment: usize,
    /// Travel fraction of that segment's tween, in [0, 1].
    pub t: f64,
}

/// Where every frame of a sequence falls.
#[derive(Clone, Debug, PartialEq)]
pub struct Schedule {
    /// One per frame.
    pub samples: Vec<Sample>,
    /// The frame number of each key (its first frame when it holds).
    pub key_frames: Vec<usize>,
    /// Extra frames each key is held.
    pub holds: Vec<usize>,
    /// Frame steps of each segment.
    pub steps: Vec<usize>,
    /// Frames per second.
    pub fps: f64,
    /// For each key, why the speed is not meant to be continuous there
    /// (`None` where it is; always `Some` for the first and last key).
    pub breaks: Vec<Option<String>>,
}

/// The speed on both sides of a key: the largest vertex move of the
/// frame step just before it and just after it (after its hold).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct KeySpeed {
    /// The key, counting from 1.
    pub key: usize,
    /// Its frame number.
    pub frame: usize,
    /// Largest vertex move of the step into the key.
    pub before: f64,
    /// Largest vertex move of the step out of it.
    pub after: f64,
    /// The larger over the smaller (1 = continuous; infinite when one
    /// side stands still).
    pub ratio: f64,
    /// Why the speed is not meant to be continuous here, if it is not.
    pub not_continuous: Option<String>,
}

/// The speed ratio at every key between the first and the last.
pub fn key_speeds(frames: &[Frame], schedule: &Schedule) -> Vec<KeySpeed> {
    let step = |i: usize| -> f64 {
        match (frames.get(i), frames.get(i + 1)) {
            (Some(a), Some(b)) => a
                .points
                .iter()
                .zip(&b.points)
                .map(|(p, q)| (*q - *p).length())
                .fold(0.0, f64::max),
            _ => 0.0,
        }
    };
    let keys = schedule.key_frames.len();
    (1..keys.saturating_sub(1))
        .map(|j| {
            let f = schedule.key_frames[j];
            let before = if f > 0 { step(f - 1) } else { 0.0 };
            let after = step(f + schedule.holds[j]);
            let (lo, hi) = (before.min(after), before.max(after));
            let ratio = if hi == 0.0 {
                1.0
            } else if lo == 0.0 {
                f64::INFINITY
            } else {
                hi / lo
            };
            KeySpeed {
                key: j + 1,
                frame: f,
                before,
                after,
                ratio,
                not_continuous: schedule.breaks[j].clone(),
            }
        })
        .collect()
}

fn key_label(names: &[String], j: usize) -> String {
    format!("key {} ({})", j + 1, names[j])
}

fn frames_of(seconds: f64, fps: f64) -> usize {
    (seconds * fps).round() as usize
}

/// Places the frames for segments of pace `lengths`, whose largest vertex
/// moves per unit of pace at their start and end are `rates` (1 where
/// unknown).
/// Places the frames of a sequence of `lengths.len()` segments whose
/// travels ([`crate::morph::Tween::path_length`] or the like) are
/// `lengths`, with the speed at a key taken as even on both sides (rate 1);
/// `names` name the keys in errors. What [`super::Sequence::schedule`]
/// does for curves, for sequences made of other motions (drawings).
///
/// # Errors
///
/// [`SequenceError::Timing`] naming the key or setting that cannot be
/// met.
pub fn schedule_lengths(
    lengths: &[f64],
    timing: &Timing,
    names: &[String],
) -> Result<Schedule, SequenceError> {
    schedule(lengths, &[], timing, names)
}

pub(super) fn schedule(
    lengths: &[f64],
    rates: &[(f64, f64)],
    timing: &Timing,
    names: &[String],
) -> Result<Schedule, SequenceError> {
    let err = |m: String| SequenceError::Timing(m);
    let m = lengths.len() + 1;
    let fps = timing.fps;
    if !(fps.is_finite() && fps > 0.0 && fps <= 1000.0) {
        return Err(err(format!(
            "fps {fps} is not a rate above 0 and at most 1000 frames per second"
        )));
    }
    if timing.keys.len() != m {
        return Err(err(format!(
            "timing given for {} keys, but the sequence has {m}",
            timing.keys.len()
        )));
    }
    let limit_seconds = MAX_FRAMES as f64 / fps;
    for (j, k) in timing.keys.iter().enumerate() {
        let who = key_label(names, j);
        if !(k.hold.is_finite() && k.hold >= 0.0) {
            return Err(err(format!(
                "{who}: hold {} is not a number of seconds of at least 0",
                k.hold
            )));
        }
        if k.hold > limit_seconds {
            return Err(err(format!(
                "{who}: hold {} s is more than {MAX_FRAMES} frames at {fps} fps; give a shorter hold",
                k.hold
            )));
        }
        if let Some(d) = k.duration {
            if j == m - 1 {
                return Err(err(format!(
                    "{who}: the last key has no segment after it, so a duration {d} means nothing; remove it"
                )));
            }
            if !(d.is_finite() && d > 0.0) {
                return Err(err(format!(
                    "{who}: duration {d} is not a number of seconds above 0"
                )));
            }
            if d > limit_seconds {
                return Err(err(format!(
                    "{who}: duration {d} s is more than {MAX_FRAMES} frames at {fps} fps; give a shorter duration"
                )));
            }
        }
        if let Some(t) = k.time {
            if !(t.is_finite() && t >= 0.0) {
                return Err(err(format!(
                    "{who}: time {t} is not a number of seconds of at least 0"
                )));
            }
            if t > limit_seconds {
                return Err(err(format!(
                    "{who}: time {t} s is more than {MAX_FRAMES} frames at {fps} fps; give an earlier time"
                )));
            }
            if j == 0 && t != 0.0 {
                return Err(err(format!(
                    "{who}: the first key is at time 0, not {t}; give times from the first key"
                )));
            }
            if j > 0 && timing.keys[j - 1].duration.is_some() {
                return Err(err(format!(
                    "{who}: its time and a duration on the key before it ({}) both time the segment between them; give one of them",
                    key_label(names, j - 1)
                )));
            }
        }
    }
    let holds: Vec<usize> = timing.keys.iter().map(|k| frames_of(k.hold, fps)).collect();
    let fixed: Vec<Option<usize>> = timing.keys[..m - 1]
        .iter()
        .map(|k| k.duration.map(|d| frames_of(d, fps).max(1)))
        .collect();
    let slopes: Vec<(f64, f64)> = timing.keys[..m - 1]
        .iter()
        .map(|k| k.easing.end_slopes())
        .collect();
    // Known key frame numbers.
    let mut known: Vec<Option<usize>> = timing
        .keys
        .iter()
        .map(|k| k.time.map(|t| frames_of(t, fps)))
        .collect();
    known[0] = Some(0);
    for j in 0..m - 1 {
        if let (Some(f), Some(s)) = (known[j], fixed[j]) {
            known[j + 1] = Some(f + holds[j] + s);
        }
    }
    if let Some(total) = timing.frames {
        if !(2..=MAX_FRAMES).contains(&total) {
            return Err(err(format!(
                "{total} frames: give from 2 to {MAX_FRAMES} frames"
            )));
        }
        let end = (total - 1).checked_sub(holds[m - 1]);
        match (known[m - 1], end) {
            (Some(f), Some(e)) if f != e => {
                return Err(err(format!(
                    "{total} frames do not fit the timing: {} is at frame {f}, so the sequence has {} frames; leave out the frame count or change the times",
                    key_label(names, m - 1),
                    f + holds[m - 1] + 1
                )));
            }
            (_, None) => {
                return Err(err(format!(
                    "{total} frames are fewer than the last key's hold of {} frames",
                    holds[m - 1]
                )));
            }
            (_, Some(e)) => known[m - 1] = Some(e),
        }
    }
    // The end of a trailing run of unknown keys.
    if known[m - 1].is_none() {
        let a = (0..m).rev().find(|&j| known[j].is_some()).unwrap_or(0);
        let base = known[a].unwrap_or(0);
        let mut end = base;
        for j in a..m - 1 {
            end += holds[j]
                + fixed[j].unwrap_or_else(|| frames_of(DEFAULT_SECONDS_PER_SEGMENT, fps).max(1));
        }
        known[m - 1] = Some(end);
    }
    // Relative speed of each free segment: continuity where free segments
    // meet at a key with no hold, time or stopping easing.
    let mut breaks: Vec<Option<String>> = vec![None; m];
    breaks[0] = Some("first key".to_string());
    breaks[m - 1] = Some("last key".to_string());
    for j in 1..m - 1 {
        let why = if timing.keys[j].time.is_some() {
            Some("its time is given".to_string())
        } else if holds[j] > 0 {
            Some(format!("it holds for {} frames", holds[j]))
        } else if fixed[j - 1].is_some() || fixed[j].is_some() {
            Some("a segment next to it has a duration".to_string())
        } else if slopes[j - 1].1 < STOP_SLOPE {
            Some("the easing into it stops there".to_string())
        } else if slopes[j].0 < STOP_SLOPE {
            Some("the easing out of it starts from rest".to_string())
        } else if lengths[j - 1] <= 0.0 || lengths[j] <= 0.0 {
            Some("a segment next to it does not move".to_string())
        } else {
            None
        };
        breaks[j] = why;
    }
    // The fastest vertex leaves key j as fast as it arrives: pace per
    // step times the easing's slope times the segment's rate there.
    let rate = |j: usize, end: bool| -> f64 {
        let r = rates.get(j).map_or(1.0, |r| if end { r.1 } else { r.0 });
        if r.is_finite() && r > 0.0 { r } else { 1.0 }
    };
    let mut speed = vec![1.0f64; m - 1];
    for j in 1..m - 1 {
        if breaks[j].is_none() {
            speed[j] = (speed[j - 1] * slopes[j - 1].1 * rate(j - 1, true)
                / (slopes[j].0 * rate(j, false)))
            .clamp(1e-3, 1e3);
        }
    }
    // Steps per segment, run by run.
    let mut steps: Vec<usize> = vec![0; m - 1];
    let mut a = 0;
    while a < m - 1 {
        let b = (a + 1..m).find(|&j| known[j].is_some()).unwrap_or(m - 1);
        let (fa, fb) = (known[a].unwrap_or(0), known[b].unwrap_or(0));
        let used: usize = (a..b).map(|j| holds[j] + fixed[j].unwrap_or(0)).sum();
        let free: Vec<usize> = (a..b).filter(|&j| fixed[j].is_none()).collect();
        for j in a..b {
            if let Some(s) = fixed[j] {
                steps[j] = s;
            }
        }
        let budget = fb.checked_sub(fa + used);
        match budget {
            Some(budget) if budget >= free.len() => {
                if free.is_empty() {
                    if budget != 0 {
                        return Err(err(format!(
                            "{}: its time does not match the durations before it; give one or the other",
                            key_label(names, b)
                        )));
                    }
                } else {
                    let weights: Vec<f64> = free.iter().map(|&j| lengths[j] / speed[j]).collect();
                    for (&j, s) in free.iter().zip(share(&weights, budget)) {
                        steps[j] = s;
                    }
                }
            }
            _ => {
                return Err(err(format!(
                    "{}: at frame {fb} it leaves too few frames after {} at frame {fa} for {} segment(s) of at least one step and their holds; give it a later time or a higher fps",
                    key_label(names, b),
                    key_label(names, a),
                    b - a
                )));
            }
        }
        a = b;
    }
    // The frames.
    let total: usize = steps.iter().sum::<usize>() + holds.iter().sum::<usize>() + 1;
    if total > MAX_FRAMES {
        return Err(err(format!(
            "the timing needs {total} frames, more than {MAX_FRAMES}; give shorter times or a lower fps"
        )));
    }
    let mut samples = Vec::with_capacity(total);
    let mut key_frames = Vec::with_capacity(m);
    for j in 0..m - 1 {
        key_frames.push(samples.len());
        let key = Sample { segment: j, t: 0.0 };
        samples.extend(std::iter::repeat_n(key, holds[j] + 1));
        let e = &timing.keys[j].easing;
        for k in 1..steps[j] {
            let x = k as f64 / steps[j] as f64;
            let t = e.apply(x);
            samples.push(Sample {
                segment: j,
                t: if t.is_finite() { t.clamp(0.0, 1.0) } else { x },
            });
        }
    }
    key_frames.push(samples.len());
    let last = Sample {
        segment: m - 2,
        t: 1.0,
    };
    samples.extend(std::iter::repeat_n(last, holds[m - 1] + 1));
    Ok(Schedule {
        samples,
        key_frames,
        holds,
        steps,
        fps,
        breaks,
    })
}

/// Splits `budget` whole steps among segments of weights `w` (travel ÷
/// relative speed), at least one each, always giving the next step to
/// the segment with the largest weight per step (D'Hondt): the largest
/// speed is as small as whole steps allow.
fn share(w: &[f64], budget: usize) -> Vec<usize> {
    let left = budget - w.len();
    if w.iter().all(|&x| x <= 0.0 || !x.is_finite()) {
        // Nothing moves: spread evenly.
        let mut s = vec![1usize; w.len()];
        for i in 0..left {
            s[i % w.len()] += 1;
        }
        return s;
    }
    crate::correspond::apportion(w, left)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(m: usize) -> Vec<String> {
        (0..m).map(|j| format!("k{}", j + 1)).collect()
    }

    #[test]
    fn free_segments_share_frames_by_travel() {
        let t = Timing::new(4).with_frames(Some(61));
        let s = schedule(&[1.0, 2.0, 3.0], &[], &t, &names(4)).unwrap();
        assert_eq!(s.samples.len(), 61);
        assert_eq!(s.steps, vec![10, 20, 30]);
        assert_eq!(s.key_frames, vec![0, 10, 30, 60]);
        assert_eq!(s.samples[30], Sample { segment: 2, t: 0.0 });
        assert_eq!(s.samples[60], Sample { segment: 2, t: 1.0 });
        assert!(s.breaks[1].is_none() && s.breaks[2].is_none());
    }

    #[test]
    fn holds_times_and_durations() {
        let mut t = Timing::new(4).with_fps(10.0);
        t.keys[1].hold = 0.5;
        t.keys[1].duration = Some(1.0);
        t.keys[3].time = Some(6.0);
        let s = schedule(&[1.0, 1.0, 1.0], &[], &t, &names(4)).unwrap();
        // Key 4 is at frame 60; key 2 holds 5 frames and segment 2 takes
        // 10: segments 1 and 3 share the other 45 by travel.
        assert_eq!(s.steps[1], 10);
        assert_eq!(s.holds[1], 5);
        assert_eq!(s.steps[0] + s.steps[2], 45);
        assert_eq!(s.samples.len(), 61);
        assert_eq!(*s.key_frames.last().unwrap(), 60);
        assert!(s.breaks[1].as_deref().unwrap().contains("holds"));
    }

    #[test]
    fn bad_timings_name_the_key() {
        let mut t = Timing::new(3);
        t.keys[1].duration = Some(-1.0);
        let e = schedule(&[1.0, 1.0], &[], &t, &names(3)).unwrap_err();
        assert_eq!(
            e.to_string(),
            "key 2 (k2): duration -1 is not a number of seconds above 0"
        );
        let mut t = Timing::new(3);
        t.keys[2].time = Some(0.01);
        let e = schedule(&[1.0, 1.0], &[], &t, &names(3)).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("key 3 (k3): at frame 0 it leaves too few frames"),
            "{e}"
        );
    }

    #[test]
    fn easing_slopes_chain_the_speeds() {
        // Segment 1 eases out (ends fast), segment 2 is linear: segment 2
        // takes the speed segment 1 ends with.
        let mut t = Timing::new(3).with_frames(Some(201));
        t.keys[0].easing = Ease::new(|x: f64| 1.0 - (1.0 - x) * (1.0 - x)); // slope 2 at 0, 0 at 1
        t.keys[1].easing = Ease::new(|x: f64| x * x); // slope 0 at 0
        let s = schedule(&[1.0, 1.0], &[], &t, &names(3)).unwrap();
        assert!(s.breaks[1].is_some());
        let mut t = Timing::new(3).with_frames(Some(201));
        t.keys[0].easing = Ease::new(|x: f64| x * x); // ends at slope 2
        let s = schedule(&[1.0, 1.0], &[], &t, &names(3)).unwrap();
        assert!(s.breaks[1].is_none());
        // Speed at the end of 1: 2 / s0; at the start of 2: 1 / s1.
        let (a, b) = (2.0 / s.steps[0] as f64, 1.0 / s.steps[1] as f64);
        assert!((a / b - 1.0).abs() < 0.02, "{a} {b} {:?}", s.steps);
    }
}
