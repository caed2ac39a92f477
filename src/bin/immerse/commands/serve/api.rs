//! The routes: the page, its option lists and limits, the reference
//! curves, checking a curve, morphing, and the files of a morph job
//! (README, "Playground", "HTTP API").

use super::http::{self, ApiError, Guard, Phase};
use super::jobs::{self, Job, JobId, ShapeLimits, Slots, Store, Want};
use crate::args::ServeLimits;
use axum::Router;
use axum::extract::{Path, Request, State as With};
use axum::http::{Method, StatusCode, Uri};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use bytes::Bytes;
use clap::ValueEnum;
use immerse::curve::{CurveError, Format};
use immerse::drawing::{Drawing, MatchMode};
use immerse::geom::polygon;
use immerse::morph::{Correspondence, Counts, Intermediate, ThirdVertexPath};
use immerse::{Curve, Quality};
use immerse_render as render;
use serde::Deserialize;
use std::convert::Infallible;
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};
use tower::ServiceBuilder;
use tower::util::BoxCloneSyncService;
use tower_http::limit::RequestBodyLimitLayer;
use tower_http::timeout::TimeoutLayer;

/// The page, embedded so that the server needs no file and no network.
const PAGE: &str = include_str!("../../../../../web/index.html");

/// A tiny icon so the browser's automatic request finds something.
const FAVICON: &str = "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 16 16\"><path d=\"M2 8C2 2 14 2 14 8S6 14 6 8 10 4 10 8\" fill=\"#3d7cc9\" fill-opacity=\".6\" stroke=\"#1d2b3a\"/></svg>";

/// Reference curves offered by the page: (name, format, file contents).
const REFERENCE: &[(&str, Format, &[u8])] = &[
    (
        "ribbon-curl",
        Format::Svg,
        include_bytes!("../../../../../curves/ribbon-curl.svg"),
    ),
    (
        "tail-loop",
        Format::Svg,
        include_bytes!("../../../../../curves/tail-loop.svg"),
    ),
    (
        "folded-ribbon",
        Format::Svg,
        include_bytes!("../../../../../curves/folded-ribbon.svg"),
    ),
    (
        "ring-wrap-400deg",
        Format::Svg,
        include_bytes!("../../../../../curves/ring-wrap-400deg.svg"),
    ),
    (
        "letter-S",
        Format::Json,
        include_bytes!("../../../../../curves/letter-S-n62.json"),
    ),
    (
        "spiral-strip-400deg",
        Format::Json,
        include_bytes!("../../../../../curves/spiral-strip-400deg-n30.json"),
    ),
    (
        "curl-strip",
        Format::Json,
        include_bytes!("../../../../../curves/curl-strip-n10.json"),
    ),
    (
        "limacon-inner-loop",
        Format::Json,
        include_bytes!("../../../../../curves/limacon-inner-loop-n80.json"),
    ),
    (
        "figure-eight",
        Format::Svg,
        include_bytes!("../../../../../curves/figure-eight.svg"),
    ),
    (
        "circle-twice",
        Format::Json,
        include_bytes!("../../../../../curves/circle-twice-n40.json"),
    ),
];

/// The pair the page loads at start (the pair of `immerse demo`).
const EXAMPLE: [&str; 2] = ["ribbon-curl", "tail-loop"];

/// What the routes share.
pub(super) struct State {
    guard: Arc<Guard>,
    slots: Slots,
    store: Store,
    shapes: ShapeLimits,
    body_timeout: Duration,
    /// `GET /api/limits`, `/api/options` and `/api/curves`, built once.
    limits_json: Bytes,
    options_json: Bytes,
    curves_json: Bytes,
}

impl State {
    pub(super) fn new(
        limits: &ServeLimits,
        key_tolerance: f64,
        guard: Arc<Guard>,
    ) -> anyhow::Result<State> {
        let shapes = ShapeLimits {
            max_points: limits.max_points as usize,
            max_frames: limits.max_frames as usize,
            max_curves: limits.max_curves as usize,
            max_side: limits.max_side,
            key_tolerance,
        };
        let job_timeout = Duration::from_secs(limits.job_timeout);
        Ok(State {
            guard,
            slots: Slots::new(limits.max_jobs as usize, job_timeout),
            store: Store::new((limits.job_memory as usize) << 20),
            shapes,
            body_timeout: Duration::from_secs(limits.body_timeout),
            limits_json: Bytes::from(limits_json(limits).to_string()),
            options_json: Bytes::from(options_json(&shapes).to_string()),
            curves_json: Bytes::from(curves_json()?.to_string()),
        })
    }
}

/// The whole service: the routes under the layers that every request
/// passes, outermost first: [`http::guard`], the body limit (while
/// reading; at once for an announced length) and the request time limit.
pub(super) fn app(
    state: Arc<State>,
    request_timeout: Duration,
    max_body: usize,
) -> BoxCloneSyncService<Request, Response, Infallible> {
    let guard = Arc::clone(&state.guard);
    let router = Router::new()
        .route("/", get(page))
        .route("/index.html", get(page))
        .route("/favicon.ico", get(favicon))
        .route("/api/limits", get(limits))
        .route("/api/options", get(options))
        .route("/api/curves", get(curves))
        .route("/api/check", post(check))
        .route("/api/morph", post(morph))
        .route("/api/jobs/{id}/{*file}", get(job_file))
        .fallback(not_found)
        .method_not_allowed_fallback(wrong_method)
        .with_state(state);
    let service = ServiceBuilder::new()
        .layer(axum::middleware::from_fn_with_state(guard, http::guard))
        .layer(RequestBodyLimitLayer::new(max_body))
        .layer(TimeoutLayer::with_status_code(
            StatusCode::REQUEST_TIMEOUT,
            request_timeout,
        ))
        .service(router);
    BoxCloneSyncService::new(service)
}

fn json(bytes: &Bytes) -> Response {
    http::reply("application/json", vec![bytes.clone()], None, ())
}

async fn page() -> Response {
    http::reply(
        "text/html; charset=utf-8",
        vec![Bytes::from_static(PAGE.as_bytes())],
        None,
        (),
    )
}

async fn favicon() -> Response {
    http::reply(
        "image/svg+xml",
        vec![Bytes::from_static(FAVICON.as_bytes())],
        None,
        (),
    )
}

async fn limits(With(st): With<Arc<State>>) -> Response {
    json(&st.limits_json)
}

async fn options(With(st): With<Arc<State>>) -> Response {
    json(&st.options_json)
}

async fn curves(With(st): With<Arc<State>>) -> Response {
    json(&st.curves_json)
}

async fn not_found(uri: Uri) -> Response {
    ApiError::new(404, format!("no such page: {}", uri.path())).into_response()
}

async fn wrong_method(method: Method, uri: Uri) -> Response {
    let path = uri.path();
    let takes = if matches!(path, "/api/check" | "/api/morph") {
        "POST"
    } else {
        "GET or HEAD"
    };
    ApiError::new(405, format!("{path} takes {takes}, not {method}")).into_response()
}

/// The limits, as `GET /api/limits` gives them.
fn limits_json(l: &ServeLimits) -> serde_json::Value {
    serde_json::json!({
        "max_body_bytes": l.max_body_bytes,
        "max_points": l.max_points,
        "max_frames": l.max_frames,
        "max_curves": l.max_curves,
        "max_side": l.max_side,
        "max_jobs": l.max_jobs,
        "job_timeout_seconds": l.job_timeout,
        "job_memory_bytes": l.job_memory << 20,
        "max_connections": l.max_connections,
        "header_timeout_seconds": l.header_timeout,
        "max_header_bytes": l.max_header_bytes,
        "max_headers": l.max_headers,
        "body_timeout_seconds": l.body_timeout,
        "write_timeout_seconds": l.write_timeout,
        "drain_timeout_seconds": l.drain_timeout,
    })
}

/// The values of one option of the command line, with their help.
fn choices<T: ValueEnum>(default: &T) -> serde_json::Value {
    let name = |v: &T| v.to_possible_value().map(|p| p.get_name().to_string());
    let values: Vec<serde_json::Value> = T::value_variants()
        .iter()
        .filter_map(|v| {
            // Hidden values (the experimental ones of this build) are not
            // offered.
            let p = v.to_possible_value().filter(|p| !p.is_hide_set())?;
            Some(serde_json::json!({
                "name": p.get_name(),
                "help": p.get_help().map(ToString::to_string),
            }))
        })
        .collect();
    serde_json::json!({ "default": name(default), "values": values })
}

/// `GET /api/options`: what the page offers, from the definitions the
/// command line and the server use, so that the page repeats none.
fn options_json(shapes: &ShapeLimits) -> serde_json::Value {
    let easings: Vec<serde_json::Value> = render::Easing::NAMES
        .iter()
        .map(|n| serde_json::json!({ "name": n, "help": null }))
        .chain(std::iter::once(serde_json::json!({
            "name": "cubic-bezier",
            "help": "cubic-bezier(x1,y1,x2,y2) as in CSS, x1 and x2 from 0 to 1",
        })))
        .collect();
    let loops: Vec<serde_json::Value> = render::Loop::ALL
        .iter()
        .map(|l| serde_json::json!({ "name": l.to_string(), "help": null }))
        .collect();
    serde_json::json!({
        "path": choices(&ThirdVertexPath::Rigid),
        "intermediate": choices(&Intermediate::Target),
        "correspondence": choices(&Correspondence::Best),
        "quality": choices(&Quality::Delaunay),
        "counts": choices(&Counts::Insert),
        "match": choices(&MatchMode::Auto),
        "easing": { "default": "linear", "values": easings },
        "loop": { "default": render::Loop::Loop.to_string(), "values": loops },
        "frames": { "default": jobs::DEFAULT_FRAMES, "min": 2, "max": shapes.max_frames },
        "fps": {
            "default": jobs::DEFAULT_FPS,
            "min": render::MIN_FPS,
            "max": render::MAX_FPS,
            "gif_max": render::GIF_MAX_FPS,
        },
        "size": {
            "default": [jobs::DEFAULT_SIDE, jobs::DEFAULT_SIDE],
            "min": jobs::MIN_SIDE,
            "max": shapes.max_side,
        },
        "max_points": shapes.max_points,
        "max_curves": shapes.max_curves,
        "max_shapes": jobs::MAX_SHAPES,
    })
}

/// `GET /api/curves`: the reference curves, each checked once here, and
/// the pair loaded at start.
fn curves_json() -> anyhow::Result<serde_json::Value> {
    let mut curves = Vec::new();
    for &(name, format, bytes) in REFERENCE {
        let c = Curve::from_bytes(bytes, format, name, name)?;
        let ok = immerse::triangulate_with(&c.points, Quality::Delaunay).is_ok();
        curves.push(serde_json::json!({
            "name": name,
            "self_overlapping": ok,
            "points": c.points.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
        }));
    }
    Ok(serde_json::json!({ "curves": curves, "example": EXAMPLE }))
}

/// The phase handle of a request's connection (absent only in tests that
/// call the router without a connection).
fn phase(req: &Request) -> Option<Phase> {
    req.extensions().get::<Phase>().cloned()
}

/// The start of every POST job: checks the content type, waits for a
/// slot, then reads the body (in that order: a body is only read, and
/// held in memory, by a job that may run).
async fn start_post(st: &State, req: Request) -> Result<(Bytes, jobs::Slot, Instant), ApiError> {
    http::require_json(req.headers())?;
    let phase = phase(&req);
    if let Some(p) = &phase {
        p.waiting();
    }
    let deadline = Instant::now() + st.slots.timeout();
    let slot = st.slots.take(deadline).await?;
    // The body has its own time limit, not counted in the job's.
    let reading = Instant::now();
    let body = http::read_body(req.into_body(), st.body_timeout, &st.guard).await?;
    if let Some(p) = &phase {
        p.working();
    }
    Ok((body, slot, deadline + reading.elapsed()))
}

async fn check(With(st): With<Arc<State>>, req: Request) -> Response {
    let answer = async {
        let (body, slot, deadline) = start_post(&st, req).await?;
        let shapes = st.shapes;
        let (report, slot) = jobs::run(slot, deadline, st.slots.timeout(), move |_| {
            check_curve(&body, &shapes)
        })
        .await?;
        Ok::<_, ApiError>(http::reply("application/json", vec![report], None, slot))
    };
    answer.await.unwrap_or_else(IntoResponse::into_response)
}

/// `POST /api/check`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CheckRequest {
    /// Points `[[x, y], ...]` (y up) ...
    points: Option<Vec<[f64; 2]>>,
    /// ... or the text of a curve file ...
    data: Option<String>,
    /// ... in this format: `json`, `text` (also `txt`, `xy`, `csv`) or `svg`.
    format: Option<String>,
    /// A name for messages (e.g. the file name).
    name: Option<String>,
}

/// Reads and checks one curve (on a job's thread: an SVG's parse and the
/// triangulation take time). The text of a file with several closed
/// shapes (an SVG, or a drawing's JSON) is a drawing: its shapes, each
/// with its style and verdict (holes refused with the library's message).
fn check_curve(body: &[u8], shapes: &ShapeLimits) -> Result<Bytes, ApiError> {
    let max_points = shapes.max_points;
    let req: CheckRequest = http::parse_json(body)?;
    let name = req.name.unwrap_or_else(|| "curve".to_string());
    let curve = match (req.points, req.data) {
        (Some(points), None) => jobs::curves_from(vec![points], max_points)?.remove(0),
        (None, Some(data)) => {
            let ext = req.format.as_deref().unwrap_or("json").to_ascii_lowercase();
            let format = Format::from_extension(if ext == "text" { "txt" } else { &ext })
                .ok_or_else(|| {
                    ApiError::bad(format!(
                        "unknown curve format '{ext}'; use json, txt (x y per line) or svg"
                    ))
                })?;
            let stem = name.rsplit_once('.').map_or(name.as_str(), |(s, _)| s);
            if matches!(format, Format::Svg | Format::Json) {
                let drawing = jobs::read_drawing(data.as_bytes(), format, &name, stem, shapes)?;
                if !drawing.single_curve {
                    return Ok(Bytes::from(drawing_report(&drawing).to_string()));
                }
            }
            let c = Curve::from_bytes(data.as_bytes(), format, &name, stem).map_err(|e| {
                let status = if matches!(e, CurveError::TooLarge { .. }) {
                    413
                } else {
                    400
                };
                ApiError::new(status, e.to_string())
            })?;
            if c.len() > max_points {
                return Err(jobs::too_many_points(&name, c.len(), max_points));
            }
            c
        }
        _ => {
            return Err(ApiError::bad(
                "give either \"points\" or \"data\" (the text of a .json, .txt or .svg curve file)",
            ));
        }
    };
    let verdict = immerse::triangulate_with(&curve.points, Quality::Delaunay);
    if let Err(e) = &verdict
        && !e.is_answer()
    {
        return Err(ApiError::bad(format!("{name}: {e}")));
    }
    let report = serde_json::json!({
        "name": curve.name,
        "points": curve.points.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
        "point_count": curve.len(),
        "dropped": curve.dropped,
        "turning_number": curve.turning_number_as_given(),
        "simple": polygon::first_self_intersection(&curve.points).is_none(),
        "reversed": curve.reversed,
        "self_overlapping": verdict.is_ok(),
        "reason": verdict.as_ref().err().map(ToString::to_string),
        "triangles": verdict.as_ref().ok().map(|im| im.triangles.clone()),
    });
    Ok(Bytes::from(report.to_string()))
}

/// `POST /api/check` on a drawing: every shape with its style (as the
/// library's drawing JSON has it), whether it is self-overlapping and its
/// triangulation when it is.
fn drawing_report(drawing: &Drawing) -> serde_json::Value {
    let shapes: Vec<serde_json::Value> = drawing
        .shapes
        .iter()
        .zip(drawing.triangulate())
        .map(|(shape, verdict)| {
            let mut v = serde_json::to_value(shape).unwrap_or_default();
            if let Some(m) = v.as_object_mut() {
                m.insert("self_overlapping".into(), verdict.is_ok().into());
                m.insert(
                    "reason".into(),
                    verdict.as_ref().err().map(ToString::to_string).into(),
                );
                m.insert(
                    "triangles".into(),
                    serde_json::to_value(verdict.as_ref().ok().map(|im| &im.triangles))
                        .unwrap_or_default(),
                );
            }
            v
        })
        .collect();
    serde_json::json!({
        "kind": "drawing",
        "name": drawing.name,
        "shape_count": drawing.shapes.len(),
        "point_count": drawing.shapes.iter().map(|s| s.points.len()).sum::<usize>(),
        "self_overlapping": shapes.iter().all(|s| s["self_overlapping"] == true),
        "notices": drawing.notices,
        "shapes": shapes,
    })
}

async fn morph(With(st): With<Arc<State>>, req: Request) -> Response {
    let answer = async {
        let (body, slot, deadline) = start_post(&st, req).await?;
        let shapes = st.shapes;
        let ((reply, job), slot) = jobs::run(slot, deadline, st.slots.timeout(), move |stop| {
            run_morph(&body, &shapes, stop)
        })
        .await?;
        let job = st.store.keep(job)?;
        Ok::<_, ApiError>(http::reply("application/json", reply, None, (slot, job)))
    };
    answer.await.unwrap_or_else(IntoResponse::into_response)
}

/// Plans, runs and packs a morph (on a job's thread): the answer and the
/// job to keep.
fn run_morph(
    body: &[u8],
    shapes: &ShapeLimits,
    stop: &jobs::Stop,
) -> Result<(Vec<Bytes>, Job), ApiError> {
    let req: jobs::MorphRequest = http::parse_json(body)?;
    let plan = jobs::plan(req, shapes)?;
    match &plan.input {
        jobs::Input::Curves(curves) => morph_curves(&plan, curves, stop),
        jobs::Input::Drawings(drawings, mode) => morph_drawings(&plan, drawings, *mode, stop),
    }
}

/// The links to a job's files.
fn job_urls(id: JobId) -> serde_json::Value {
    let base = format!("/api/jobs/{id}");
    serde_json::json!({
        "frame": format!("{base}/frame/{{k}}.png"),
        "gif": format!("{base}/morph.gif"),
        "svg": format!("{base}/morph.svg"),
        "lottie": format!("{base}/morph.lottie.json"),
        "json": format!("{base}/morph.json"),
        "progress": format!("{base}/progress"),
    })
}

/// The answer: the summary, then the morph itself exactly as `immerse
/// morph --json` writes it (the bytes the job keeps, not a copy).
fn answer(summary: &serde_json::Value, morph_json: &Bytes) -> Vec<Bytes> {
    let mut head = summary.to_string();
    head.pop();
    head.push_str(",\"morph\":");
    vec![
        Bytes::from(head),
        morph_json.clone(),
        Bytes::from_static(b"}"),
    ]
}

/// A finished job's [`answer`]: its `summary` with what every job
/// reports (id, time taken, image size, view, frame rate and links).
fn finished(
    mut summary: serde_json::Value,
    elapsed: std::time::Duration,
    plan: &jobs::Plan,
    job: &Job,
) -> Vec<Bytes> {
    let id = job.id;
    let common = serde_json::json!({
        "id": id.to_string(),
        "milliseconds": (elapsed.as_secs_f64() * 1e4).round() / 10.0,
        "size": [plan.style.width, plan.style.height],
        "view": job.view(),
        "fps": plan.fps,
        "urls": job_urls(id),
    });
    if let (Some(fields), serde_json::Value::Object(common)) = (summary.as_object_mut(), common) {
        fields.extend(common);
    }
    answer(&summary, &job.morph_json())
}

/// A morph of curves: its summary and frames, and its certified keys,
/// which the page plays (docs/design.md §12 and §13).
fn morph_curves(
    plan: &jobs::Plan,
    curves: &[Curve],
    stop: &jobs::Stop,
) -> Result<(Vec<Bytes>, Job), ApiError> {
    let started = Instant::now();
    let (morph, keys) = jobs::compute(plan, curves, stop)?;
    let elapsed = started.elapsed();
    let morph_json = exact_json(&crate::commands::morph::WithKeys::new(&morph, &keys))?;
    let id = JobId::random()?;
    let counts: Vec<usize> = {
        let mut c: Vec<usize> = morph.frames.iter().map(|f| f.points.len()).collect();
        c.dedup();
        c
    };
    let frames = crate::commands::render_frames(&morph.frames);
    let frame_count = morph.frames.len();
    let (path, fallback) = (morph.path_name(), morph.fallback);
    let fallbacks = serde_json::to_value(&morph.fallbacks)
        .map_err(|e| ApiError::new(500, format!("cannot write the morph: {e}")))?;
    drop(morph);
    let job = Job::new(id, frames, plan, morph_json, &keys);
    let summary = serde_json::json!({
        "kind": "curves",
        "curves": curves.len(),
        "frames": frame_count,
        "key_count": keys.len(),
        "vertices": counts,
        "path": path,
        "fallback": fallback,
        "fallbacks": fallbacks,
    });
    Ok((finished(summary, elapsed, plan, &job), job))
}

/// A morph of two drawings: its summary (with the matching in words) and
/// its frames, every shape of every frame verified, as `immerse morph
/// --json` writes them for drawings.
fn morph_drawings(
    plan: &jobs::Plan,
    drawings: &[Drawing; 2],
    mode: MatchMode,
    stop: &jobs::Stop,
) -> Result<(Vec<Bytes>, Job), ApiError> {
    use crate::commands::drawing_morph;
    let started = Instant::now();
    let (frames, matching, keys) = jobs::compute_drawings(plan, drawings, mode, stop)?;
    let elapsed = started.elapsed();
    let [a, b] = drawings;
    let notices: Vec<String> = [a, b]
        .iter()
        .enumerate()
        .flat_map(|(k, d)| {
            d.notices
                .iter()
                .map(move |n| format!("drawing {}: {n}", k + 1))
        })
        .collect();
    let morph_json = exact_json(&drawing_morph::DrawingMorphJson {
        matching: drawing_morph::report(a, b, &matching),
        notices,
        shapes: &keys,
        frames: &frames,
    })?;
    let id = JobId::random()?;
    let rendered: Vec<render::Frame> = frames.iter().map(drawing_morph::render_frame).collect();
    let shapes = frames.first().map_or(0, |f| f.shapes.len());
    let frame_count = frames.len();
    drop(frames);
    let job = Job::new(id, rendered, plan, morph_json, &[]);
    let summary = serde_json::json!({
        "kind": "drawings",
        "shapes": shapes,
        "matching": drawing_morph::summary(a, b, &matching),
        "frames": frame_count,
    });
    Ok((finished(summary, elapsed, plan, &job), job))
}

/// `value` as JSON in a buffer of exactly its length: it is measured
/// first, since a growing buffer may end up to twice the length, and the
/// job keeps these bytes (they count in --job-memory).
fn exact_json<T: serde::Serialize>(value: &T) -> Result<Bytes, ApiError> {
    struct Count(usize);
    impl std::io::Write for Count {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            self.0 += buf.len();
            Ok(buf.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    let failed = |e: serde_json::Error| ApiError::new(500, format!("cannot write the morph: {e}"));
    let mut count = Count(0);
    serde_json::to_writer(&mut count, value).map_err(failed)?;
    let mut bytes = Vec::with_capacity(count.0);
    serde_json::to_writer(&mut bytes, value).map_err(failed)?;
    Ok(Bytes::from(bytes))
}

/// `GET /api/jobs/ID/FILE`: a frame or download of a job (one job slot
/// each), or `progress` (the GIF being rendered; no slot).
async fn job_file(
    With(st): With<Arc<State>>,
    Path((id, file)): Path<(String, String)>,
    req: Request,
) -> Response {
    let download = req
        .uri()
        .query()
        .is_some_and(|q| q.split('&').any(|p| p == "download=1"));
    let phase = phase(&req);
    drop(req);
    let answer = async {
        let job = JobId::parse(&id)
            .and_then(|id| st.store.get(id))
            .ok_or_else(|| {
                ApiError::new(
                    404,
                    format!(
                        "no morph job {id} on this server (the oldest are dropped to keep within --job-memory); run the morph again"
                    ),
                )
            })?;
        if file == "progress" {
            let total = job.gif_total.load(Ordering::Relaxed);
            let gif = (total > 0).then(|| {
                serde_json::json!({ "done": job.gif_done.load(Ordering::Relaxed), "total": total })
            });
            let text = serde_json::json!({ "gif": gif }).to_string();
            let text = vec![Bytes::from(text)];
            return Ok(http::reply("application/json", text, None, ()));
        }
        let want = Want::parse(&job, &file)?;
        if let Some(p) = &phase {
            p.waiting();
        }
        let deadline = Instant::now() + st.slots.timeout();
        let slot = st.slots.take(deadline).await?;
        if let Some(p) = &phase {
            p.working();
        }
        let keep = Arc::clone(&job);
        let (made, slot) = jobs::run(slot, deadline, st.slots.timeout(), move |stop| {
            jobs::make(&keep, &want, stop)
        })
        .await?;
        let name = download.then_some(made.name.as_str());
        Ok::<_, ApiError>(http::reply(
            made.content_type,
            vec![made.bytes.clone()],
            name,
            (slot, job),
        ))
    };
    answer.await.unwrap_or_else(IntoResponse::into_response)
}
