//! Jobs: the work a request makes the server do, and what bounds it.
//!
//! Every check, morph and download is a job. A job first takes one of
//! `--max-jobs` slots ([`Slots`]), waiting for a free one, then runs on a
//! blocking thread ([`run`]) that stops when its client leaves or its time
//! (`--job-timeout`, the wait for the slot included) is up ([`Stop`]): a
//! GIF stops at its next frame and a chained morph at its next frame, while
//! planning a morph and writing an SVG or Lottie run to their end. The slot
//! goes with the work, so work that outlives its request still counts until
//! it really ends, and then with the response body until the last byte is
//! sent. Finished morphs are kept for their URLs under a memory budget,
//! oldest dropped first ([`Store`]), and named by 128 random bits
//! ([`JobId`]), so no other page can guess a job's URL.

use super::http::ApiError;
use crate::commands::keyed::{self, Played};
use bytes::Bytes;
use clap::ValueEnum;
use immerse::curve::{CurveError, Format};
use immerse::drawing::{
    Drawing, DrawingError, DrawingFrame, DrawingTween, DrawingTweenError, MatchMode, Matching,
    ShapeKeys, match_shapes,
};
use immerse::frames::{Fallback, Morph};
use immerse::morph::{
    Correspondence, Counts, CurveMorphError, CurveMorphOptions, Intermediate, Keyframe,
    ThirdVertexPath, Tween,
};
use immerse::sequence::{Key, Sequence, SequenceError, SequenceOptions};
use immerse::{Curve, Point, Quality};
use immerse_render as render;
use serde::Deserialize;
use std::collections::{HashMap, VecDeque};
use std::fmt;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use tokio::sync::{OwnedSemaphorePermit, Semaphore};

/// A job's name in its URLs: 128 bits from the operating system's random
/// source, written as 32 hexadecimal digits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) struct JobId(u128);

impl JobId {
    /// A fresh random id.
    pub(super) fn random() -> Result<JobId, ApiError> {
        let mut bytes = [0_u8; 16];
        getrandom::fill(&mut bytes)
            .map_err(|e| ApiError::new(500, format!("no random numbers for a job id: {e}")))?;
        Ok(JobId(u128::from_le_bytes(bytes)))
    }

    /// Parses the 32 hexadecimal digits of a URL.
    pub(super) fn parse(s: &str) -> Option<JobId> {
        if s.len() != 32 || !s.bytes().all(|b| b.is_ascii_hexdigit()) {
            return None;
        }
        u128::from_str_radix(s, 16).ok().map(JobId)
    }
}

impl fmt::Display for JobId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:032x}", self.0)
    }
}

/// The job slots: at most `--max-jobs` jobs hold one at once.
pub(super) struct Slots {
    semaphore: Arc<Semaphore>,
    max: usize,
    timeout: Duration,
}

/// A taken slot, given back when dropped.
pub(super) type Slot = OwnedSemaphorePermit;

impl Slots {
    pub(super) fn new(max: usize, timeout: Duration) -> Slots {
        Slots {
            semaphore: Arc::new(Semaphore::new(max)),
            max,
            timeout,
        }
    }

    /// The time limit of every job.
    pub(super) fn timeout(&self) -> Duration {
        self.timeout
    }

    /// Waits (in order of arrival) for a free slot until `deadline`; HTTP
    /// 503 when none comes free in time.
    pub(super) async fn take(&self, deadline: Instant) -> Result<Slot, ApiError> {
        let wait = Arc::clone(&self.semaphore).acquire_owned();
        match tokio::time::timeout_at(deadline.into(), wait).await {
            Ok(Ok(slot)) => Ok(slot),
            _ => Err(ApiError::new(
                503,
                format!(
                    "all {} job slot(s) stayed busy for {} s, this server's job time limit; try again when a job has finished",
                    self.max,
                    self.timeout.as_secs()
                ),
            )),
        }
    }
}

/// When a job's work should stop: its client left (the request's future
/// was dropped) or its deadline passed.
#[derive(Clone)]
pub(super) struct Stop {
    cancelled: Arc<AtomicBool>,
    deadline: Instant,
}

impl Stop {
    fn new(deadline: Instant) -> Stop {
        Stop {
            cancelled: Arc::new(AtomicBool::new(false)),
            deadline,
        }
    }

    /// True when the work should end now.
    pub(super) fn now(&self) -> bool {
        self.cancelled.load(Ordering::Relaxed) || Instant::now() >= self.deadline
    }

    fn cancel(&self) {
        self.cancelled.store(true, Ordering::Relaxed);
    }
}

/// Cancels a [`Stop`] when dropped: held by the request's future, which
/// the server drops when the client closes its connection.
struct CancelOnDrop(Stop);

impl Drop for CancelOnDrop {
    fn drop(&mut self) {
        self.0.cancel();
    }
}

/// Runs `work` on a blocking thread with `slot`, until `deadline`.
///
/// The slot stays with the work: when the deadline passes (HTTP 503) or
/// the request is dropped, `work` is told through its [`Stop`] and keeps
/// the slot until it returns. On success the slot comes back with the
/// result, to be held while the answer is sent.
pub(super) async fn run<T, F>(
    slot: Slot,
    deadline: Instant,
    limit: Duration,
    work: F,
) -> Result<(T, Slot), ApiError>
where
    T: Send + 'static,
    F: FnOnce(&Stop) -> Result<T, ApiError> + Send + 'static,
{
    let stop = Stop::new(deadline);
    let cancel = CancelOnDrop(stop.clone());
    let task = tokio::task::spawn_blocking(move || {
        let result = work(&stop);
        result.map(|value| (value, slot))
    });
    let result = match tokio::time::timeout_at(deadline.into(), task).await {
        Ok(Ok(result)) => result,
        Ok(Err(e)) => Err(ApiError::new(
            500,
            format!("the job stopped unexpectedly ({e}); this is a bug in immerse"),
        )),
        Err(_) => Err(too_long(limit)),
    };
    drop(cancel);
    result
}

/// HTTP 503 for a job past its time limit.
pub(super) fn too_long(limit: Duration) -> ApiError {
    ApiError::new(
        503,
        format!(
            "the job took longer than {} s, this server's limit; try fewer frames, fewer points or a smaller size",
            limit.as_secs()
        ),
    )
}

/// Finished morphs, kept for their URLs within a memory budget.
pub(super) struct Store {
    budget: usize,
    inner: Mutex<StoreInner>,
}

#[derive(Default)]
struct StoreInner {
    order: VecDeque<JobId>,
    map: HashMap<JobId, Arc<Job>>,
    bytes: usize,
}

impl Store {
    pub(super) fn new(budget: usize) -> Store {
        Store {
            budget,
            inner: Mutex::new(StoreInner::default()),
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, StoreInner> {
        self.inner.lock().unwrap_or_else(|p| p.into_inner())
    }

    pub(super) fn get(&self, id: JobId) -> Option<Arc<Job>> {
        self.lock().map.get(&id).cloned()
    }

    /// Keeps `job`, dropping the oldest jobs until all fit the budget; a
    /// job larger than the whole budget is refused (HTTP 413).
    pub(super) fn keep(&self, job: Job) -> Result<Arc<Job>, ApiError> {
        if job.bytes > self.budget {
            return Err(ApiError::new(
                413,
                format!(
                    "the morph takes {} MiB, more than the {} MiB this server keeps for morphs (--job-memory); use fewer frames or fewer points",
                    job.bytes.div_ceil(1 << 20),
                    self.budget >> 20
                ),
            ));
        }
        let job = Arc::new(job);
        let mut store = self.lock();
        while store.bytes + job.bytes > self.budget {
            let Some(old) = store.order.pop_front() else {
                break;
            };
            if let Some(j) = store.map.remove(&old) {
                store.bytes -= j.bytes;
            }
        }
        store.order.push_back(job.id);
        store.bytes += job.bytes;
        store.map.insert(job.id, Arc::clone(&job));
        Ok(job)
    }

    /// Jobs kept and the bytes they take.
    #[cfg(test)]
    fn usage(&self) -> (usize, usize) {
        let store = self.lock();
        (store.map.len(), store.bytes)
    }
}

/// A finished morph, kept for its frame and download URLs.
pub(super) struct Job {
    pub(super) id: JobId,
    pub(super) frames: Vec<render::Frame>,
    view: render::View,
    style: render::Style,
    pub(super) fps: f64,
    looping: render::Loop,
    /// The morph as `immerse morph --json` writes it.
    morph_json: Bytes,
    /// The keys its Lottie and SVG write (docs/design.md §12).
    played: Played,
    /// What the job takes in memory (an estimate from its sizes).
    bytes: usize,
    /// Frames of the GIF being rendered: done, and in all (0 when none is).
    pub(super) gif_done: AtomicUsize,
    pub(super) gif_total: AtomicUsize,
}

impl Job {
    /// The morph as `immerse morph --json` writes it.
    pub(super) fn morph_json(&self) -> Bytes {
        self.morph_json.clone()
    }

    /// The view its frames and downloads are drawn in: pixels per unit and
    /// the pixel position of the origin.
    pub(super) fn view(&self) -> [f64; 3] {
        let [tx, ty] = self.view.to_pixel([0.0, 0.0]);
        [self.view.scale(), tx, ty]
    }

    /// A finished morph: its rendered `frames` and, for a morph of curves,
    /// its certified `keys` (none for a drawing's).
    pub(super) fn new(
        id: JobId,
        frames: Vec<render::Frame>,
        plan: &Plan,
        morph_json: Bytes,
        keys: &[Keyframe],
    ) -> Job {
        let played = Played::new(keys, &plan.times, plan.looping, plan.eased);
        let key_bytes: usize = played
            .keys
            .iter()
            .map(|k| k.points.len() * 16 + k.triangles.len() * 12 + 64)
            .sum();
        let view = render::View::fit(&frames, &plan.style);
        let frame_bytes: usize = frames
            .iter()
            .map(|f| {
                std::mem::size_of::<render::Frame>()
                    + f.points.len() * 16
                    + f.triangles.len() * 12
                    + f.outline.len() * 4
                    + f.layers
                        .iter()
                        .map(|l| std::mem::size_of::<render::Layer>() + l.outline.len() * 4)
                        .sum::<usize>()
            })
            .sum();
        Job {
            id,
            bytes: frame_bytes + key_bytes + morph_json.len() + 1024,
            frames,
            view,
            style: plan.style.clone(),
            fps: plan.fps,
            looping: plan.looping,
            morph_json,
            played,
            gif_done: AtomicUsize::new(0),
            gif_total: AtomicUsize::new(0),
        }
    }
}

/// What the server's morphs and checks may be given.
#[derive(Clone, Copy, Debug)]
pub(super) struct ShapeLimits {
    pub(super) max_points: usize,
    pub(super) max_frames: usize,
    pub(super) max_curves: usize,
    pub(super) max_side: u32,
    /// Every morph's key tolerance (`--key-tolerance`).
    pub(super) key_tolerance: f64,
}

/// `POST /api/morph`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MorphRequest {
    /// Two or more curves, `[[x, y], ...]` each, y up; morphed in order ...
    #[serde(default)]
    curves: Vec<Vec<[f64; 2]>>,
    /// ... or two drawings, each in the library's drawing JSON
    /// (`{"name", "shapes": [{"id", "points", "fill", ...}]}`).
    drawings: Option<Vec<serde_json::Value>>,
    /// How the shapes of two drawings are paired (`--match`).
    #[serde(rename = "match")]
    match_mode: Option<String>,
    /// A number, checked to be whole here (serde's message for 2.5 would
    /// name a Rust type).
    frames: Option<f64>,
    path: Option<String>,
    quality: Option<String>,
    counts: Option<String>,
    intermediate: Option<String>,
    correspondence: Option<String>,
    easing: Option<String>,
    size: Option<[f64; 2]>,
    fps: Option<f64>,
    #[serde(default)]
    wireframe: bool,
    #[serde(default)]
    onion: bool,
    #[serde(rename = "loop")]
    looping: Option<String>,
}

/// Frames of a morph when the request does not say.
pub(super) const DEFAULT_FRAMES: usize = 60;
/// Frame rate when the request does not say.
pub(super) const DEFAULT_FPS: f64 = 30.0;
/// Image side when the request does not say (the page's canvas).
pub(super) const DEFAULT_SIDE: u32 = 600;
/// Most shapes of one drawing in the playground: pairing them costs the
/// cube of their number, and every pair is a morph.
pub(super) const MAX_SHAPES: usize = 64;
/// Smallest image side.
pub(super) const MIN_SIDE: u32 = 16;

/// A CLI value name (`--path hybrid` etc.) for an option.
fn value<T: ValueEnum>(field: &str, given: Option<&str>, default: T) -> Result<T, ApiError> {
    match given {
        None => Ok(default),
        Some(s) => T::from_str(s, true).map_err(|_| {
            let names: Vec<String> = T::value_variants()
                .iter()
                .filter_map(|v| v.to_possible_value().map(|p| p.get_name().to_string()))
                .collect();
            ApiError::bad(format!(
                "\"{field}\": '{s}' is not one of {}",
                names.join(", ")
            ))
        }),
    }
}

/// A whole number in `lo..=hi`, or HTTP 400 naming `field`.
fn whole(field: &str, v: f64, lo: u64, hi: u64, unit: &str) -> Result<u64, ApiError> {
    if v.fract() == 0.0 && v >= lo as f64 && v <= hi as f64 {
        Ok(v as u64)
    } else {
        Err(ApiError::bad(format!(
            "\"{field}\": {v} is not a whole number from {lo} to {hi}{unit}"
        )))
    }
}

/// What a morph job morphs.
pub(super) enum Input {
    /// Two or more curves, in order.
    Curves(Vec<Curve>),
    /// Two drawings, their shapes paired by the mode.
    Drawings(Box<[Drawing; 2]>, MatchMode),
}

/// Everything a morph job needs, checked.
pub(super) struct Plan {
    pub(super) input: Input,
    times: Vec<f64>,
    /// The easing is not linear: every frame is a key of the Lottie and
    /// SVG too.
    eased: bool,
    options: CurveMorphOptions,
    pub(super) style: render::Style,
    pub(super) fps: f64,
    looping: render::Loop,
}

pub(super) fn plan(req: MorphRequest, limits: &ShapeLimits) -> Result<Plan, ApiError> {
    if req.drawings.is_some() && !req.curves.is_empty() {
        return Err(ApiError::bad(
            "give either \"curves\" or \"drawings\", not both",
        ));
    }
    if req.drawings.is_none() && req.match_mode.is_some() {
        return Err(ApiError::bad(
            "\"match\" pairs the shapes of two \"drawings\"; curves need none",
        ));
    }
    if req.drawings.is_none() && (req.curves.len() < 2 || req.curves.len() > limits.max_curves) {
        return Err(ApiError::bad(format!(
            "\"curves\" holds {} curve(s); give from 2 to {}",
            req.curves.len(),
            limits.max_curves
        )));
    }
    let frames = whole(
        "frames",
        req.frames.unwrap_or(DEFAULT_FRAMES as f64),
        2,
        limits.max_frames as u64,
        "",
    )? as usize;
    let side = f64::from(DEFAULT_SIDE);
    let [w, h] = req.size.unwrap_or([side, side]);
    let pixels = |v: f64| {
        whole(
            "size",
            v,
            u64::from(MIN_SIDE),
            u64::from(limits.max_side),
            " pixels a side",
        )
        .map(|v| v as u32)
    };
    let (w, h) = (pixels(w)?, pixels(h)?);
    let fps = req.fps.unwrap_or(DEFAULT_FPS);
    if let Some(message) = crate::commands::fps_error("\"fps\":", fps) {
        return Err(ApiError::bad(message));
    }
    let easing_text = req.easing.as_deref().unwrap_or("linear");
    let easing: render::Easing = easing_text
        .parse()
        .map_err(|e: render::RenderError| ApiError::bad(format!("\"easing\": {e}")))?;
    let times = render::frame_times(frames, &easing);
    // An easing that overshoots asks for frames outside the morph: refused
    // as the command line refuses it.
    if let Some((index, t)) = times
        .iter()
        .enumerate()
        .find(|(_, t)| !(0.0..=1.0).contains(*t))
    {
        return Err(ApiError::bad(format!(
            "\"easing\": {easing_text}: frame fraction {t} (at position {index}) is not a number in [0, 1]"
        )));
    }
    let looping: render::Loop = req
        .looping
        .as_deref()
        .unwrap_or("loop")
        .parse()
        .map_err(|e: render::RenderError| ApiError::bad(format!("\"loop\": {e}")))?;
    let path = value("path", req.path.as_deref(), ThirdVertexPath::Rigid)?;
    let quality = value("quality", req.quality.as_deref(), Quality::Delaunay)?;
    let counts = value("counts", req.counts.as_deref(), Counts::Insert)?;
    let intermediate = value(
        "intermediate",
        req.intermediate.as_deref(),
        Intermediate::Target,
    )?;
    let correspondence = value(
        "correspondence",
        req.correspondence.as_deref(),
        Correspondence::Best,
    )?;
    // The same options as `immerse morph` builds from its arguments.
    let options = crate::commands::morph::PlanFlags {
        path,
        correspondence,
        quality,
        counts,
        intermediate,
        key_tolerance: limits.key_tolerance,
    }
    .options()
    .map_err(|e| ApiError::bad(e.trim_start_matches("--").to_string()))?;
    let input = match req.drawings {
        Some(drawings) => {
            let mode = value("match", req.match_mode.as_deref(), MatchMode::Auto)?;
            Input::Drawings(drawings_from(drawings, limits)?, mode)
        }
        None => Input::Curves(curves_from(req.curves, limits.max_points)?),
    };
    let style = render::Style::DEFAULT
        .with_size(w, h)
        .with_wireframe(req.wireframe)
        .with_onion_skin(req.onion);
    Ok(Plan {
        input,
        times,
        eased: easing != render::Easing::Linear,
        options,
        style,
        fps,
        looping,
    })
}

/// HTTP 413 for a curve of `n` points.
pub(super) fn too_many_points(name: &str, n: usize, max: usize) -> ApiError {
    ApiError::new(
        413,
        format!(
            "{name} has {n} points; the playground accepts at most {max} per curve (simplify it, or use the immerse command line)"
        ),
    )
}

/// Curves as sent: `[[x, y], ...]`, at most `max_points` each.
pub(super) fn curves_from(
    raw: Vec<Vec<[f64; 2]>>,
    max_points: usize,
) -> Result<Vec<Curve>, ApiError> {
    let mut out = Vec::with_capacity(raw.len());
    for (i, pts) in raw.into_iter().enumerate() {
        let label = format!("curve {}", i + 1);
        if pts.len() > max_points {
            return Err(too_many_points(&label, pts.len(), max_points));
        }
        let points = pts.into_iter().map(|[x, y]| Point::new(x, y)).collect();
        out.push(Curve::from_points(&label, points).map_err(|e| ApiError::bad(e.to_string()))?);
    }
    Ok(out)
}

/// Reads a drawing sent as text (`format` as a curve file's extension:
/// `svg`, `json`, ...) with the library's reader, within the playground's
/// limits: at most [`MAX_SHAPES`] shapes and `max_points` points in all
/// (what one curve may hold).
/// Holes and unreadable shapes are HTTP 400 with the library's message.
pub(super) fn read_drawing(
    bytes: &[u8],
    format: Format,
    label: &str,
    name: &str,
    limits: &ShapeLimits,
) -> Result<Drawing, ApiError> {
    let drawing = Drawing::from_bytes(bytes, format, label, name).map_err(|e| {
        let status = if matches!(e, DrawingError::Curve(CurveError::TooLarge { .. })) {
            413
        } else {
            400
        };
        ApiError::new(status, e.to_string())
    })?;
    if drawing.single_curve {
        // One curve: checked as a curve is.
        return Ok(drawing);
    }
    if drawing.shapes.len() > MAX_SHAPES {
        return Err(ApiError::new(
            413,
            format!(
                "{label} has {} shapes; the playground accepts at most {MAX_SHAPES} per drawing (use the immerse command line)",
                drawing.shapes.len()
            ),
        ));
    }
    // A frame of a drawing holds all its shapes' points: as many as one
    // curve's at most, so that its frames take what a curve's take.
    let total: usize = drawing.shapes.iter().map(|s| s.points.len()).sum();
    if total > limits.max_points {
        return Err(ApiError::new(
            413,
            format!(
                "{label}: its shapes have {total} points in all; the playground accepts at most {} per drawing, as per curve (simplify it, or use the immerse command line)",
                limits.max_points
            ),
        ));
    }
    Ok(drawing)
}

/// The two drawings of a morph, each given as the library's drawing JSON,
/// every shape self-overlapping (else HTTP 400 naming it).
fn drawings_from(
    raw: Vec<serde_json::Value>,
    limits: &ShapeLimits,
) -> Result<Box<[Drawing; 2]>, ApiError> {
    let [a, b]: [serde_json::Value; 2] = raw.try_into().map_err(|raw: Vec<_>| {
        ApiError::bad(format!(
            "\"drawings\" holds {} drawing(s); give exactly 2",
            raw.len()
        ))
    })?;
    let read = |k: usize, value: serde_json::Value| -> Result<Drawing, ApiError> {
        let label = format!("drawing {k}");
        let name = value
            .get("name")
            .and_then(serde_json::Value::as_str)
            .unwrap_or(&label)
            .to_string();
        let bytes =
            serde_json::to_vec(&value).map_err(|e| ApiError::bad(format!("{label}: {e}")))?;
        let drawing = read_drawing(&bytes, Format::Json, &label, &name, limits)?;
        drawing
            .require_self_overlapping(&label)
            .map_err(|e| ApiError::bad(e.to_string()))?;
        Ok(drawing)
    };
    Ok(Box::new([read(1, a)?, read(2, b)?]))
}

/// Runs the morph of two drawings: every matched pair of shapes as a
/// [`Tween`], unmatched shapes growing or shrinking (`immerse morph` on
/// drawings), a verified frame at each of the plan's times. Frames stop
/// when `stop` says so; planning runs to its end.
pub(super) fn compute_drawings(
    plan: &Plan,
    drawings: &[Drawing; 2],
    mode: MatchMode,
    stop: &Stop,
) -> Result<(Vec<DrawingFrame>, Matching, Vec<ShapeKeys>), ApiError> {
    let [a, b] = drawings;
    let matching = match_shapes(a, b, mode);
    let tween = DrawingTween::new(a, b, &matching, &plan.options).map_err(|e| match e {
        DrawingTweenError::NotSelfOverlapping { .. }
        | DrawingTweenError::Pair {
            source: CurveMorphError::NotSelfOverlapping { .. },
            ..
        } => ApiError::bad(e.to_string()),
        other => ApiError::new(500, format!("the morph failed: {other}")),
    })?;
    let keys = tween
        .shape_keys()
        .map_err(|e| ApiError::new(500, format!("the morph failed: {e}")))?;
    let mut frames = Vec::with_capacity(plan.times.len());
    for &t in &plan.times {
        if stop.now() {
            return Err(ApiError::new(503, "the morph was stopped"));
        }
        frames.push(
            tween
                .frame(t)
                .map_err(|e| ApiError::new(500, format!("the morph failed: {e}")))?,
        );
    }
    Ok((frames, matching, keys))
}

/// Runs the morph of a plan, with its keys: with two curves one [`Tween`],
/// whose frames are exactly those of `immerse morph` with the same options;
/// with more a [`Sequence`] (vertex counts equalised once across all
/// curves, vertex numbers carried along the chain), its frames at the
/// eased times of the whole chain on the sequence's pace axis, so the
/// frames meet exactly at each key. Frames stop when `stop` says so;
/// planning runs to its end.
pub(super) fn compute(
    plan: &Plan,
    curves: &[Curve],
    stop: &Stop,
) -> Result<(Morph, Vec<Keyframe>), ApiError> {
    let stopped = || ApiError::new(503, "the morph was stopped");
    let fail = |e: immerse::morph::MorphError| ApiError::new(500, format!("the morph failed: {e}"));
    if curves.len() == 2 {
        let tween = Tween::new(&curves[0].points, &curves[1].points, &plan.options).map_err(
            |e| match e {
                CurveMorphError::NotSelfOverlapping { side, reason } => {
                    let k = match side {
                        immerse::morph::Side::Source => 1,
                        immerse::morph::Side::Target => 2,
                    };
                    ApiError::bad(format!("curve {k} is not self-overlapping: {reason}"))
                }
                other => ApiError::new(500, format!("the morph failed: {other}")),
            },
        )?;
        if stop.now() {
            return Err(stopped());
        }
        let morph = tween.morph(&plan.times).map_err(fail)?;
        return Ok((morph, tween.keyframes()));
    }
    let keys: Vec<Key> = curves
        .iter()
        .map(|c| Key::new(c.name.clone(), c.points.clone()))
        .collect();
    let seq = Sequence::new(
        &keys,
        &[],
        &SequenceOptions::DEFAULT.with_morph(plan.options),
    )
    .map_err(|e| match e {
        SequenceError::NotSelfOverlapping { key, reason, .. } => {
            ApiError::bad(format!("curve {key} is not self-overlapping: {reason}"))
        }
        other => ApiError::new(500, format!("the morph failed: {other}")),
    })?;
    let lengths = seq.path_lengths();
    let total: f64 = lengths.iter().sum();
    let segments = lengths.len();
    let shares: Vec<f64> = if total > 0.0 && total.is_finite() {
        lengths.iter().map(|l| l / total).collect()
    } else {
        vec![1.0 / segments as f64; segments]
    };
    let mut starts = Vec::with_capacity(segments);
    let mut acc = 0.0;
    for s in &shares {
        starts.push(acc);
        acc += s;
    }
    let mut paths: Vec<ThirdVertexPath> = Vec::new();
    let mut fallbacks: Vec<Fallback> = Vec::new();
    for i in 0..segments {
        let t = seq.tween(i);
        for p in &t.report().paths {
            if !paths.contains(p) {
                paths.push(*p);
            }
        }
        fallbacks.extend(t.report().fallbacks.iter().map(|f| {
            Fallback::new(
                &format!("curves {} to {}: {}", i + 1, i + 2, f.what),
                &f.why,
            )
        }));
    }
    let mut frames = Vec::with_capacity(plan.times.len());
    for &u in &plan.times {
        if stop.now() {
            return Err(stopped());
        }
        // The last segment whose share starts at or before u (the end of
        // a segment is the start of the next: the same curve).
        let k = starts
            .iter()
            .rposition(|&s| s <= u && u > 0.0)
            .unwrap_or(0)
            .min(segments - 1);
        let local = if u >= 1.0 && k == segments - 1 {
            1.0
        } else if shares[k] > 0.0 {
            ((u - starts[k]) / shares[k]).clamp(0.0, 1.0)
        } else {
            1.0
        };
        let mut f = seq.frame(k, local).map_err(fail)?;
        f.t = u;
        frames.push(f);
    }
    let morph = Morph::new(paths, fallbacks, frames);
    Ok((morph, seq.keyframes()))
}

/// A file of a job: its content type, bytes and download name.
pub(super) struct File {
    pub(super) content_type: &'static str,
    pub(super) bytes: Bytes,
    pub(super) name: String,
}

/// Which file of a job a URL names (`frame/K.png`, `morph.gif`, ...),
/// decided before the job takes a slot.
pub(super) enum Want {
    Frame(usize),
    Gif,
    Svg,
    Lottie,
    Json,
}

impl Want {
    /// The file `what` names, or HTTP 404 (HTTP 400 for a GIF of a morph
    /// whose rate a GIF cannot play, as the command line refuses it).
    pub(super) fn parse(job: &Job, what: &str) -> Result<Want, ApiError> {
        if let Some(k) = what
            .strip_prefix("frame/")
            .and_then(|f| f.strip_suffix(".png"))
        {
            let n = job.frames.len();
            return k
                .parse()
                .ok()
                .filter(|&k| k < n)
                .map(Want::Frame)
                .ok_or_else(|| {
                    ApiError::new(404, format!("no frame {k}: frames are 0 to {}", n - 1))
                });
        }
        match what {
            "morph.gif" => {
                render::check_gif_fps(job.fps)
                    .map_err(|e| ApiError::bad(format!("\"fps\": {e}")))?;
                Ok(Want::Gif)
            }
            "morph.svg" => Ok(Want::Svg),
            "morph.lottie.json" => Ok(Want::Lottie),
            "morph.json" => Ok(Want::Json),
            _ => Err(ApiError::new(
                404,
                format!(
                    "no such file of a job: '{what}'; use frame/K.png, morph.gif, morph.svg, morph.lottie.json or morph.json"
                ),
            )),
        }
    }
}

/// The file a download saves as: `immerse-morph.gif`,
/// `immerse-frame-0002.png` (numbered as `immerse morph -o DIR` numbers
/// its frames).
pub(super) fn download_name(want: &Want, frames: usize) -> String {
    match *want {
        Want::Frame(k) => format!(
            "immerse-{}",
            render::frame_file_name(k, frames, "png").replace('_', "-")
        ),
        Want::Gif => "immerse-morph.gif".to_string(),
        Want::Svg => "immerse-morph.svg".to_string(),
        Want::Lottie => "immerse-morph.lottie.json".to_string(),
        Want::Json => "immerse-morph.json".to_string(),
    }
}

/// Makes a file of a job: on a blocking thread, since rendering takes
/// time. A GIF reports its progress in the job and stops when `stop` says.
pub(super) fn make(job: &Job, want: &Want, stop: &Stop) -> Result<File, ApiError> {
    let render_err = |e: render::RenderError| match e {
        render::RenderError::Cancelled => ApiError::new(503, "the job was stopped"),
        e => ApiError::new(500, format!("{e:#}")),
    };
    let name = download_name(want, job.frames.len());
    let file = |content_type, bytes: Vec<u8>| File {
        content_type,
        bytes: Bytes::from(bytes),
        name: name.clone(),
    };
    Ok(match *want {
        Want::Frame(k) => {
            let n = job.frames.len();
            let ghosts: Vec<&render::Frame> = if job.style.onion_skin && n > 1 {
                vec![&job.frames[0], &job.frames[n - 1]]
            } else {
                Vec::new()
            };
            let pixmap = render::render(&job.frames[k], &job.view, &job.style, &ghosts)
                .map_err(render_err)?;
            file(
                "image/png",
                render::encode_png(&pixmap).map_err(render_err)?,
            )
        }
        Want::Gif => {
            let played = job.looping.sequence(job.frames.len()).len();
            job.gif_done.store(0, Ordering::Relaxed);
            job.gif_total.store(played, Ordering::Relaxed);
            let gif = render::encode_gif(
                &job.frames,
                &job.style,
                job.fps,
                job.looping,
                &render::Output::DEFAULT,
                &|done| {
                    job.gif_done.store(done, Ordering::Relaxed);
                    !stop.now()
                },
            );
            job.gif_total.store(0, Ordering::Relaxed);
            file("image/gif", gif.map_err(render_err)?)
        }
        Want::Svg => file("image/svg+xml", keyed_file(job, keyed::Kind::AnimatedSvg)?),
        Want::Lottie => file("application/json", keyed_file(job, keyed::Kind::Lottie)?),
        Want::Json => File {
            content_type: "application/json",
            bytes: job.morph_json.clone(),
            name,
        },
    })
}

/// The job's Lottie or animated SVG from its keys, certified as written
/// (as `immerse morph -o` writes it); a drawing's, which has no keys, from
/// its frames, one styled shape group per shape (as `immerse morph -o`
/// writes a drawing's).
fn keyed_file(job: &Job, kind: keyed::Kind) -> Result<Vec<u8>, ApiError> {
    if job.played.keys.is_empty() {
        let written = match kind {
            keyed::Kind::Lottie => render::lottie(&job.frames, &job.style, job.fps, job.looping),
            keyed::Kind::AnimatedSvg => {
                render::animated_svg(&job.frames, &job.style, job.fps, job.looping)
            }
        };
        return written
            .map(String::into_bytes)
            .map_err(|e| ApiError::new(500, format!("{e:#}")));
    }
    let doc = keyed::Document {
        kind,
        view: job.view,
        style: &job.style,
        fps: job.fps,
        looping: job.looping,
    };
    keyed::write(doc, &job.played)
        .map(|w| w.text.into_bytes())
        .map_err(|e| ApiError::new(500, format!("{e:#}")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn job_ids_are_random_and_read_back() {
        let a = JobId::random().unwrap();
        let b = JobId::random().unwrap();
        assert_ne!(a, b);
        let text = a.to_string();
        assert_eq!(text.len(), 32);
        assert_eq!(JobId::parse(&text), Some(a));
        assert_eq!(JobId::parse("1"), None);
        assert_eq!(JobId::parse(&format!("{text}0")), None);
        assert_eq!(JobId::parse(&"g".repeat(32)), None);
        assert_eq!(JobId::parse("+0000000000000000000000000000001"), None);
    }

    fn job(bytes: usize) -> Job {
        Job {
            id: JobId::random().unwrap(),
            frames: Vec::new(),
            view: render::View::from_bounds([0.0, 0.0], [1.0, 1.0], &render::Style::DEFAULT),
            style: render::Style::DEFAULT,
            fps: DEFAULT_FPS,
            looping: render::Loop::Loop,
            morph_json: Bytes::new(),
            played: Played {
                keys: Vec::new(),
                frames: 0,
            },
            bytes,
            gif_done: AtomicUsize::new(0),
            gif_total: AtomicUsize::new(0),
        }
    }

    #[test]
    fn the_store_drops_the_oldest_jobs_to_stay_in_its_budget() {
        let store = Store::new(1000);
        let ids: Vec<JobId> = (0..5).map(|_| store.keep(job(300)).unwrap().id).collect();
        // Three of 300 bytes fit in 1000; the two oldest went.
        assert_eq!(store.usage(), (3, 900));
        assert!(store.get(ids[0]).is_none() && store.get(ids[1]).is_none());
        assert!(ids[2..].iter().all(|&id| store.get(id).is_some()));
        // One job of 1000 bytes takes the whole budget.
        let big = store.keep(job(1000)).unwrap().id;
        assert_eq!(store.usage(), (1, 1000));
        assert!(store.get(big).is_some());
        let e = store.keep(job(1001)).err().unwrap();
        assert_eq!(e.status, 413);
        assert_eq!(store.usage(), (1, 1000));
    }

    #[test]
    fn download_names_follow_the_cli_numbering() {
        assert_eq!(download_name(&Want::Frame(2), 24), "immerse-frame-0002.png");
        assert_eq!(download_name(&Want::Gif, 24), "immerse-morph.gif");
    }
}
