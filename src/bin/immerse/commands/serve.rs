//! `immerse serve`: the playground page and its JSON API on 127.0.0.1.
//!
//! One self-contained page (`web/index.html`, embedded at build time) and a
//! small JSON API, documented in the README ("Playground"):
//!
//! - `POST /api/morph`: curves and options in, the verified morph out (the
//!   same frames and JSON as `immerse morph --json`), kept as a job whose
//!   frames and animations are then fetched by URL;
//! - `POST /api/check`: one curve (points, or the text of a JSON, text or
//!   SVG file) in, its facts out, as `immerse check --json`, plus its
//!   triangulation when it is self-overlapping;
//! - `GET /api/jobs/ID/frame/K.png`, `.../morph.gif`, `.../morph.svg`,
//!   `.../morph.lottie.json`, `.../morph.json`: renderings of a job;
//! - `GET /api/curves` (reference curves), `GET /api/limits`.
//!
//! Every request runs on its own thread (at most [`MAX_CONNECTIONS`]);
//! morphs, checks and GIFs also take one of `--max-jobs` job slots (HTTP
//! 429 when none is free) and a morph runs on a worker thread that the
//! request waits for at most `--job-timeout` seconds (HTTP 503 after). The
//! server never reads or writes a file: curves arrive in request bodies,
//! the page and the reference curves are compiled in.

use crate::Outcome;
use crate::args::{CorrespondenceArg, CountsArg, IntermediateArg, PathArg, QualityArg, ServeArgs};
use crate::output;
use clap::ValueEnum;
use immerse::correspond::{insert_vertices, resample_arc_length, shift_triangles};
use immerse::curve::Format;
use immerse::frames::{Fallback, Morph};
use immerse::geom::polygon;
use immerse::morph::{
    Correspondence, Counts, CurveMorphError, CurveMorphOptions, Intermediate, MorphOptions,
    ThirdVertexPath, Tween,
};
use immerse::{Curve, Point, Quality};
use immerse_render as render;
use serde::Deserialize;
use std::collections::{HashMap, VecDeque};
use std::io::Read;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, mpsc};
use std::time::{Duration, Instant};
use tiny_http::{Header, Method, Request, Response, Server};

/// The page, embedded so that the server needs no file and no network.
const PAGE: &str = include_str!("../../../../web/index.html");

/// Largest request body, in bytes (2 MiB); larger bodies get HTTP 413.
pub(crate) const MAX_BODY_BYTES: usize = 2 << 20;
/// Most points in one curve (as sent, before cleaning); more get HTTP 413.
pub(crate) const MAX_POINTS: usize = 5_000;
/// Most frames of one morph; more get HTTP 400.
pub(crate) const MAX_FRAMES: usize = 240;
/// Most curves (keyframes) in one morph request.
pub(crate) const MAX_CURVES: usize = 8;
/// Largest image side, in pixels.
pub(crate) const MAX_SIDE: u32 = 2048;
/// Most requests handled at once; more get HTTP 503 at once.
pub(crate) const MAX_CONNECTIONS: usize = 32;
/// A body declared longer than this is not answered: tiny_http 0.12
/// discards an unread body by allocating a buffer of its remaining declared
/// length, which for an absurd `Content-Length` would abort the process.
/// Such a request is dropped unanswered instead (its connection stays open
/// until the server stops). Bodies up to this size get HTTP 413.
const MAX_DECLARED_BODY: usize = 1 << 30;
/// Finished morphs kept for their frame and download URLs (oldest dropped).
pub(crate) const MAX_STORED_JOBS: usize = 16;

/// Reference curves offered by the page: (name, format, file contents).
const REFERENCE: &[(&str, Format, &[u8])] = &[
    (
        "ribbon-curl",
        Format::Svg,
        include_bytes!("../../../../curves/ribbon-curl.svg"),
    ),
    (
        "tail-loop",
        Format::Svg,
        include_bytes!("../../../../curves/tail-loop.svg"),
    ),
    (
        "folded-ribbon",
        Format::Svg,
        include_bytes!("../../../../curves/folded-ribbon.svg"),
    ),
    (
        "ring-wrap-400deg",
        Format::Svg,
        include_bytes!("../../../../curves/ring-wrap-400deg.svg"),
    ),
    (
        "letter-S",
        Format::Json,
        include_bytes!("../../../../curves/letter-S-n62.json"),
    ),
    (
        "spiral-strip-400deg",
        Format::Json,
        include_bytes!("../../../../curves/spiral-strip-400deg-n30.json"),
    ),
    (
        "curl-strip",
        Format::Json,
        include_bytes!("../../../../curves/curl-strip-n10.json"),
    ),
    (
        "limacon-inner-loop",
        Format::Json,
        include_bytes!("../../../../curves/limacon-inner-loop-n80.json"),
    ),
    (
        "figure-eight (not self-overlapping)",
        Format::Svg,
        include_bytes!("../../../../curves/figure-eight.svg"),
    ),
    (
        "circle-twice (not self-overlapping)",
        Format::Json,
        include_bytes!("../../../../curves/circle-twice-n40.json"),
    ),
];

pub(crate) fn run(args: &ServeArgs) -> anyhow::Result<Outcome> {
    let server = Server::http(("127.0.0.1", args.port))
        .map_err(|e| anyhow::anyhow!("cannot listen on 127.0.0.1:{}: {e}", args.port))?;
    let addr = server
        .server_addr()
        .to_ip()
        .ok_or_else(|| anyhow::anyhow!("the server has no IP address"))?;
    let state = Arc::new(State::new(args, addr.port())?);
    let url = format!("http://127.0.0.1:{}/", addr.port());

    // Ctrl-C (and SIGTERM) stop the accept loop below. When the process
    // already has a handler (the CLI's own), that one stays in charge.
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    if let Err(e) = ctrlc::try_set_handler(move || flag.store(true, Ordering::SeqCst)) {
        if !matches!(e, ctrlc::Error::MultipleHandlers) {
            output::note(&format!("cannot install the Ctrl-C handler: {e}"));
        }
    }

    output::print(&url)?;
    output::note(&format!(
        "serving the playground at {url} (127.0.0.1 only); press Ctrl-C to stop"
    ));
    if args.open {
        open_browser(&url);
    }

    while !stop.load(Ordering::SeqCst) {
        let request = match server.recv_timeout(Duration::from_millis(200)) {
            Ok(Some(r)) => r,
            Ok(None) => continue,
            Err(e) => {
                output::note(&format!("stopped accepting connections: {e}"));
                break;
            }
        };
        if request.body_length().is_some_and(|n| n > MAX_DECLARED_BODY) {
            std::mem::forget(request);
            continue;
        }
        if state.connections.fetch_add(1, Ordering::SeqCst) >= MAX_CONNECTIONS {
            state.connections.fetch_sub(1, Ordering::SeqCst);
            let _ = request.respond(error_response(&ApiError::new(
                503,
                format!("the server is handling {MAX_CONNECTIONS} requests; try again shortly"),
            )));
            continue;
        }
        let st = Arc::clone(&state);
        let spawned = std::thread::Builder::new()
            .name("immerse-http".into())
            .spawn(move || {
                handle(&st, request);
                st.connections.fetch_sub(1, Ordering::SeqCst);
            });
        if spawned.is_err() {
            state.connections.fetch_sub(1, Ordering::SeqCst);
        }
    }
    // Let requests in flight finish (briefly); workers of abandoned jobs
    // end with the process.
    let deadline = Instant::now() + Duration::from_secs(5);
    while state.connections.load(Ordering::SeqCst) > 0 && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(20));
    }
    drop(server);
    output::note("stopped");
    Ok(Outcome::Success)
}

/// Opens `url` with the platform's opener; a failure is only a notice.
fn open_browser(url: &str) {
    let mut cmd = if cfg!(target_os = "macos") {
        std::process::Command::new("open")
    } else if cfg!(windows) {
        let mut c = std::process::Command::new("cmd");
        c.args(["/C", "start", ""]);
        c
    } else {
        std::process::Command::new("xdg-open")
    };
    let opened = cmd
        .arg(url)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn();
    if let Err(e) = opened {
        output::note(&format!("cannot open a browser ({e}); open {url} yourself"));
    }
}

/// What the server shares between requests.
struct State {
    port: u16,
    max_jobs: usize,
    jobs_running: AtomicUsize,
    connections: AtomicUsize,
    timeout: Duration,
    delay: Duration,
    next_id: AtomicU64,
    store: Mutex<JobStore>,
    /// `GET /api/curves`, built once.
    reference_json: String,
}

impl State {
    fn new(args: &ServeArgs, port: u16) -> anyhow::Result<State> {
        let mut curves = Vec::new();
        for &(name, format, bytes) in REFERENCE {
            let c = Curve::from_bytes(bytes, format, name, name)?;
            curves.push(serde_json::json!({
                "name": name,
                "points": c.points.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
            }));
        }
        Ok(State {
            port,
            max_jobs: args.max_jobs as usize,
            jobs_running: AtomicUsize::new(0),
            connections: AtomicUsize::new(0),
            timeout: Duration::from_secs(args.job_timeout),
            delay: Duration::from_millis(args.job_delay_ms),
            next_id: AtomicU64::new(1),
            store: Mutex::new(JobStore::default()),
            reference_json: serde_json::to_string(&serde_json::json!({ "curves": curves }))?,
        })
    }

    /// A job slot, or HTTP 429 when all are taken.
    fn slot(self: &Arc<State>) -> Result<Slot, ApiError> {
        let taken = self
            .jobs_running
            .fetch_update(Ordering::SeqCst, Ordering::SeqCst, |n| {
                (n < self.max_jobs).then_some(n + 1)
            });
        match taken {
            Ok(_) => Ok(Slot(Arc::clone(self))),
            Err(_) => Err(ApiError::new(
                429,
                format!(
                    "{} job(s) are already running, the most this server runs at once; try again when one has finished",
                    self.max_jobs
                ),
            )),
        }
    }

    fn job(&self, id: u64) -> Option<Arc<Job>> {
        let store = self.store.lock().unwrap_or_else(|p| p.into_inner());
        store.map.get(&id).cloned()
    }

    fn keep(&self, job: Job) -> Arc<Job> {
        let job = Arc::new(job);
        let mut store = self.store.lock().unwrap_or_else(|p| p.into_inner());
        store.order.push_back(job.id);
        store.map.insert(job.id, Arc::clone(&job));
        while store.order.len() > MAX_STORED_JOBS {
            if let Some(old) = store.order.pop_front() {
                store.map.remove(&old);
            }
        }
        job
    }
}

/// A taken job slot, given back when dropped (also by an abandoned worker).
struct Slot(Arc<State>);

impl Drop for Slot {
    fn drop(&mut self) {
        self.0.jobs_running.fetch_sub(1, Ordering::SeqCst);
    }
}

#[derive(Default)]
struct JobStore {
    order: VecDeque<u64>,
    map: HashMap<u64, Arc<Job>>,
}

/// A finished morph, kept for its frame and download URLs.
struct Job {
    id: u64,
    frames: Vec<render::Frame>,
    view: render::View,
    style: render::Style,
    fps: f64,
    looping: render::Loop,
    /// The morph as `immerse morph --json` writes it.
    morph_json: String,
}

/// An error answer: HTTP status and a message for `{"error": ...}`.
#[derive(Debug)]
struct ApiError {
    status: u16,
    message: String,
}

impl ApiError {
    fn new(status: u16, message: impl Into<String>) -> ApiError {
        ApiError {
            status,
            message: message.into(),
        }
    }

    fn bad(message: impl Into<String>) -> ApiError {
        ApiError::new(400, message)
    }
}

/// A successful answer.
struct Reply {
    content_type: &'static str,
    body: Vec<u8>,
    /// A file name: sent as an attachment.
    download: Option<String>,
}

impl Reply {
    fn json(text: String) -> Reply {
        Reply {
            content_type: "application/json",
            body: text.into_bytes(),
            download: None,
        }
    }
}

fn header(name: &str, value: &str) -> Header {
    Header::from_bytes(name.as_bytes(), value.as_bytes()).expect("ASCII header")
}

fn error_response(e: &ApiError) -> Response<std::io::Cursor<Vec<u8>>> {
    let body = serde_json::json!({ "error": e.message }).to_string();
    Response::from_data(body)
        .with_status_code(e.status)
        .with_header(header("Content-Type", "application/json"))
        .with_header(header("Cache-Control", "no-store"))
}

/// Answers one request (on its own thread).
fn handle(state: &Arc<State>, mut request: Request) {
    let result = route(state, &mut request);
    let response = match result {
        Ok(reply) => {
            let mut r = Response::from_data(reply.body)
                .with_header(header("Content-Type", reply.content_type))
                .with_header(header("Cache-Control", "no-store"))
                .with_header(header("X-Content-Type-Options", "nosniff"));
            if let Some(name) = reply.download {
                r = r.with_header(header(
                    "Content-Disposition",
                    &format!("attachment; filename=\"{name}\""),
                ));
            }
            r
        }
        Err(e) => error_response(&e),
    };
    let _ = request.respond(response);
}

fn route(state: &Arc<State>, request: &mut Request) -> Result<Reply, ApiError> {
    check_host(state, request)?;
    let url = request.url().to_string();
    let (path, query) = url.split_once('?').unwrap_or((&url, ""));
    let method = request.method().clone();
    match (&method, path) {
        (Method::Get, "/" | "/index.html") => Ok(Reply {
            content_type: "text/html; charset=utf-8",
            body: PAGE.as_bytes().to_vec(),
            download: None,
        }),
        (Method::Get, "/favicon.ico") => Ok(Reply {
            content_type: "image/svg+xml",
            body: FAVICON.as_bytes().to_vec(),
            download: None,
        }),
        (Method::Get, "/api/limits") => Ok(Reply::json(limits_json(state))),
        (Method::Get, "/api/curves") => Ok(Reply::json(state.reference_json.clone())),
        (Method::Post, "/api/check") => {
            let body = read_json_body(request)?;
            check_curve(state, &body)
        }
        (Method::Post, "/api/morph") => {
            let body = read_json_body(request)?;
            morph(state, &body)
        }
        (Method::Get, p) if p.starts_with("/api/jobs/") => job_file(state, p, query),
        (_, "/api/check" | "/api/morph") => Err(ApiError::new(405, format!("{path} takes POST"))),
        _ => Err(ApiError::new(404, format!("no such page: {path}"))),
    }
}

/// A tiny icon so the browser's automatic request finds something.
const FAVICON: &str = "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 16 16\"><path d=\"M2 8C2 2 14 2 14 8S6 14 6 8 10 4 10 8\" fill=\"#3d7cc9\" fill-opacity=\".6\" stroke=\"#1d2b3a\"/></svg>";

/// Refuses requests whose `Host` is not this server on loopback (DNS
/// rebinding: a web page cannot reach the API under another name).
fn check_host(state: &State, request: &Request) -> Result<(), ApiError> {
    let Some(host) = request
        .headers()
        .iter()
        .find(|h| h.field.equiv("Host"))
        .map(|h| h.value.as_str().to_ascii_lowercase())
    else {
        return Ok(());
    };
    let port = state.port;
    let ok = [
        format!("127.0.0.1:{port}"),
        format!("localhost:{port}"),
        format!("[::1]:{port}"),
    ];
    if ok.contains(&host) || (port == 80 && ["127.0.0.1", "localhost"].contains(&host.as_str())) {
        Ok(())
    } else {
        Err(ApiError::new(
            403,
            format!("host '{host}' is not this server; use http://127.0.0.1:{port}/"),
        ))
    }
}

fn limits_json(state: &State) -> String {
    serde_json::json!({
        "max_body_bytes": MAX_BODY_BYTES,
        "max_points": MAX_POINTS,
        "max_frames": MAX_FRAMES,
        "max_curves": MAX_CURVES,
        "max_side": MAX_SIDE,
        "max_jobs": state.max_jobs,
        "job_timeout_seconds": state.timeout.as_secs(),
    })
    .to_string()
}

/// The body of a JSON POST, at most [`MAX_BODY_BYTES`].
fn read_json_body(request: &mut Request) -> Result<Vec<u8>, ApiError> {
    let json = request
        .headers()
        .iter()
        .find(|h| h.field.equiv("Content-Type"))
        .is_some_and(|h| {
            h.value
                .as_str()
                .to_ascii_lowercase()
                .starts_with("application/json")
        });
    if !json {
        return Err(ApiError::new(
            415,
            "send the request body as JSON with Content-Type: application/json",
        ));
    }
    let too_large = |n: &str| {
        ApiError::new(
            413,
            format!("the request body is {n} bytes; the limit is {MAX_BODY_BYTES} bytes (2 MiB)"),
        )
    };
    if let Some(n) = request.body_length()
        && n > MAX_BODY_BYTES
    {
        return Err(too_large(&n.to_string()));
    }
    let mut body = Vec::new();
    request
        .as_reader()
        .take(MAX_BODY_BYTES as u64 + 1)
        .read_to_end(&mut body)
        .map_err(|e| ApiError::bad(format!("cannot read the request body: {e}")))?;
    if body.len() > MAX_BODY_BYTES {
        return Err(too_large("more than"));
    }
    Ok(body)
}

/// Parses JSON, with the line and column of a syntax or shape error.
fn parse_json<'a, T: Deserialize<'a>>(body: &'a [u8]) -> Result<T, ApiError> {
    serde_json::from_slice(body).map_err(|e| ApiError::bad(format!("bad request JSON: {e}")))
}

/// Curves as sent: `[[x, y], ...]`, at most [`MAX_POINTS`] each.
fn curves_from(raw: Vec<Vec<[f64; 2]>>) -> Result<Vec<Curve>, ApiError> {
    let mut out = Vec::with_capacity(raw.len());
    for (i, pts) in raw.into_iter().enumerate() {
        if pts.len() > MAX_POINTS {
            return Err(ApiError::new(
                413,
                format!(
                    "curve {} has {} points; the playground accepts at most {MAX_POINTS} per curve (simplify it, or use the immerse command line)",
                    i + 1,
                    pts.len()
                ),
            ));
        }
        let label = format!("curve {}", i + 1);
        let points = pts.into_iter().map(|[x, y]| Point::new(x, y)).collect();
        out.push(Curve::from_points(&label, points).map_err(|e| ApiError::bad(e.to_string()))?);
    }
    Ok(out)
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

fn check_curve(state: &Arc<State>, body: &[u8]) -> Result<Reply, ApiError> {
    let req: CheckRequest = parse_json(body)?;
    let name = req.name.unwrap_or_else(|| "curve".to_string());
    let curve = match (req.points, req.data) {
        (Some(points), None) => curves_from(vec![points])?.remove(0),
        (None, Some(data)) => {
            let ext = req.format.as_deref().unwrap_or("json").to_ascii_lowercase();
            let format = Format::from_extension(&ext).ok_or_else(|| {
                ApiError::bad(format!(
                    "unknown curve format '{ext}'; use json, txt (x y per line) or svg"
                ))
            })?;
            let stem = name.rsplit_once('.').map_or(name.as_str(), |(s, _)| s);
            let c = Curve::from_bytes(data.as_bytes(), format, &name, stem)
                .map_err(|e| ApiError::bad(e.to_string()))?;
            if c.len() > MAX_POINTS {
                return Err(ApiError::new(
                    413,
                    format!(
                        "{name} has {} points; the playground accepts at most {MAX_POINTS} per curve (simplify it, or use the immerse command line)",
                        c.len()
                    ),
                ));
            }
            c
        }
        _ => {
            return Err(ApiError::bad(
                "give either \"points\" or \"data\" (the text of a .json, .txt or .svg curve file)",
            ));
        }
    };
    let _slot = state.slot()?;
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
    Ok(Reply::json(report.to_string()))
}

/// `POST /api/morph`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MorphRequest {
    /// Two or more curves, `[[x, y], ...]` each, y up; morphed in order.
    curves: Vec<Vec<[f64; 2]>>,
    #[serde(default = "default_frames")]
    frames: usize,
    path: Option<String>,
    quality: Option<String>,
    counts: Option<String>,
    intermediate: Option<String>,
    correspondence: Option<String>,
    easing: Option<String>,
    size: Option<[u32; 2]>,
    fps: Option<f64>,
    #[serde(default)]
    wireframe: bool,
    #[serde(default)]
    onion: bool,
    #[serde(rename = "loop")]
    looping: Option<String>,
}

fn default_frames() -> usize {
    60
}

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

/// Everything a morph job needs, checked.
struct Plan {
    curves: Vec<Curve>,
    times: Vec<f64>,
    options: CurveMorphOptions,
    style: render::Style,
    fps: f64,
    looping: render::Loop,
}

fn plan(req: MorphRequest) -> Result<Plan, ApiError> {
    if req.curves.len() < 2 || req.curves.len() > MAX_CURVES {
        return Err(ApiError::bad(format!(
            "\"curves\" holds {} curve(s); give from 2 to {MAX_CURVES}",
            req.curves.len()
        )));
    }
    if !(2..=MAX_FRAMES).contains(&req.frames) {
        return Err(ApiError::bad(format!(
            "\"frames\": {} is not from 2 to {MAX_FRAMES}",
            req.frames
        )));
    }
    let [w, h] = req.size.unwrap_or([600, 600]);
    if !(16..=MAX_SIDE).contains(&w) || !(16..=MAX_SIDE).contains(&h) {
        return Err(ApiError::bad(format!(
            "\"size\": [{w}, {h}] is not from 16 to {MAX_SIDE} pixels a side"
        )));
    }
    let fps = req.fps.unwrap_or(30.0);
    if !(fps.is_finite() && fps > 0.0 && fps <= 120.0) {
        return Err(ApiError::bad(format!(
            "\"fps\": {fps} is not a rate above 0 and at most 120"
        )));
    }
    let easing: render::Easing = req
        .easing
        .as_deref()
        .unwrap_or("linear")
        .parse()
        .map_err(|e: render::RenderError| ApiError::bad(format!("\"easing\": {e}")))?;
    let looping: render::Loop = req
        .looping
        .as_deref()
        .unwrap_or("loop")
        .parse()
        .map_err(|e: render::RenderError| ApiError::bad(format!("\"loop\": {e}")))?;
    let path: PathArg = value("path", req.path.as_deref(), PathArg::Straight)?;
    let quality: QualityArg = value("quality", req.quality.as_deref(), QualityArg::Delaunay)?;
    let counts: CountsArg = value("counts", req.counts.as_deref(), CountsArg::Insert)?;
    let intermediate: IntermediateArg = value(
        "intermediate",
        req.intermediate.as_deref(),
        IntermediateArg::Target,
    )?;
    let correspondence: CorrespondenceArg = value(
        "correspondence",
        req.correspondence.as_deref(),
        CorrespondenceArg::Best,
    )?;
    // The same options as `immerse morph` builds from its arguments.
    let options = CurveMorphOptions::DEFAULT
        .with_quality(Quality::from(quality))
        .with_counts(match counts {
            CountsArg::Insert => Counts::Insert,
            CountsArg::Resample => Counts::Resample,
        })
        .with_correspondence(Correspondence::from(correspondence))
        .with_intermediate(match intermediate {
            IntermediateArg::Target => Intermediate::Target,
            IntermediateArg::Disk => Intermediate::Disk,
        })
        .with_morph(MorphOptions::DEFAULT.with_path(ThirdVertexPath::from(path)));
    let curves = curves_from(req.curves)?;
    let style = render::Style::DEFAULT
        .with_size(w, h)
        .with_wireframe(req.wireframe)
        .with_onion_skin(req.onion);
    Ok(Plan {
        curves,
        times: render::frame_times(req.frames, &easing),
        options,
        style,
        fps,
        looping,
    })
}

/// Runs the morph of a plan: one [`Tween`] per consecutive pair; with two
/// curves the frames are exactly those of `immerse morph` with the same
/// options. With more, every curve is first brought to the largest vertex
/// count (as `counts` says), each pair's frames are relabelled so that
/// vertex `i` runs on where the previous pair left it, and the eased times
/// run across the whole chain, each pair getting a share proportional to
/// its vertex travel: every frame has the same vertex count and the frames
/// meet exactly at each key.
fn compute(plan: &Plan) -> Result<Morph, ApiError> {
    let n = plan.curves.iter().map(Curve::len).max().unwrap_or(0);
    let keys: Vec<Vec<Point>> = if plan.curves.len() == 2 {
        plan.curves.iter().map(|c| c.points.clone()).collect()
    } else {
        plan.curves
            .iter()
            .map(|c| match plan.options.counts {
                Counts::Resample => resample_arc_length(&c.points, n),
                _ => insert_vertices(&c.points, n - c.len()).0,
            })
            .collect()
    };
    let mut tweens = Vec::with_capacity(keys.len() - 1);
    for (i, pair) in keys.windows(2).enumerate() {
        let tween = Tween::new(&pair[0], &pair[1], &plan.options).map_err(|e| match e {
            CurveMorphError::NotSelfOverlapping { side, reason } => {
                let k = match side {
                    immerse::morph::Side::Source => i + 1,
                    immerse::morph::Side::Target => i + 2,
                };
                ApiError::bad(format!("curve {k} is not self-overlapping: {reason}"))
            }
            other => ApiError::new(500, format!("the morph failed: {other}")),
        })?;
        tweens.push(tween);
    }
    let fail = |e: immerse::morph::MorphError| ApiError::new(500, format!("the morph failed: {e}"));
    if tweens.len() == 1 {
        return tweens[0].morph(&plan.times).map_err(fail);
    }
    let lengths: Vec<f64> = tweens.iter().map(Tween::path_length).collect();
    let total: f64 = lengths.iter().sum();
    let shares: Vec<f64> = if total > 0.0 && total.is_finite() {
        lengths.iter().map(|l| l / total).collect()
    } else {
        vec![1.0 / tweens.len() as f64; tweens.len()]
    };
    let mut starts = Vec::with_capacity(shares.len());
    let mut acc = 0.0;
    for s in &shares {
        starts.push(acc);
        acc += s;
    }
    // Pair k starts where pair k-1 ended: its vertex i is the chain's
    // vertex i - offset[k].
    let mut offsets = Vec::with_capacity(tweens.len());
    let mut offset = 0;
    for t in &tweens {
        offsets.push(offset);
        if t.vertex_count() > 0 {
            offset = (offset + t.report().shift) % t.vertex_count();
        }
    }
    let mut paths: Vec<ThirdVertexPath> = Vec::new();
    let mut fallbacks: Vec<Fallback> = Vec::new();
    for (i, t) in tweens.iter().enumerate() {
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
        // The last pair whose share starts at or before u (the end of a
        // pair is the start of the next: the same curve).
        let k = starts
            .iter()
            .rposition(|&s| s <= u && u > 0.0)
            .unwrap_or(0)
            .min(tweens.len() - 1);
        let local = if u >= 1.0 && k == tweens.len() - 1 {
            1.0
        } else if shares[k] > 0.0 {
            ((u - starts[k]) / shares[k]).clamp(0.0, 1.0)
        } else {
            1.0
        };
        let f = tweens[k].frame(local).map_err(fail)?;
        let m = f.points.len();
        // Chain vertex i is vertex i + offset of this pair.
        let c = offsets[k] % m.max(1);
        frames.push(immerse::frames::Frame {
            t: u,
            points: (0..m).map(|i| f.points[(i + c) % m]).collect(),
            triangles: shift_triangles(m, &f.triangles, c),
        });
    }
    Ok(Morph {
        paths,
        fallback: !fallbacks.is_empty(),
        fallbacks,
        frames,
    })
}

fn morph(state: &Arc<State>, body: &[u8]) -> Result<Reply, ApiError> {
    let req: MorphRequest = parse_json(body)?;
    let plan = plan(req)?;
    let slot = state.slot()?;
    let started = Instant::now();
    let (tx, rx) = mpsc::channel();
    let delay = state.delay;
    // The worker owns the slot: a job abandoned after the time limit
    // still counts until it really ends.
    let worker = std::thread::Builder::new()
        .name("immerse-job".into())
        .spawn(move || {
            let _slot = slot;
            if !delay.is_zero() {
                std::thread::sleep(delay);
            }
            let result = compute(&plan).map(|m| (m, plan));
            let _ = tx.send(result);
        });
    if worker.is_err() {
        return Err(ApiError::new(
            503,
            "cannot start a worker thread; try again",
        ));
    }
    let (morph, plan) = match rx.recv_timeout(state.timeout) {
        Ok(result) => result?,
        Err(mpsc::RecvTimeoutError::Timeout) => {
            return Err(ApiError::new(
                503,
                format!(
                    "the morph took longer than {} s, this server's limit; try curves with fewer points",
                    state.timeout.as_secs()
                ),
            ));
        }
        Err(mpsc::RecvTimeoutError::Disconnected) => {
            return Err(ApiError::new(500, "the morph worker stopped unexpectedly"));
        }
    };
    let elapsed = started.elapsed();
    let morph_json =
        serde_json::to_string(&morph).map_err(|e| ApiError::new(500, e.to_string()))?;
    let frames = super::render_frames(&morph.frames);
    let view = render::View::fit(&frames, &plan.style);
    let id = state.next_id.fetch_add(1, Ordering::SeqCst);
    let counts: Vec<usize> = {
        let mut c: Vec<usize> = morph.frames.iter().map(|f| f.points.len()).collect();
        c.dedup();
        c
    };
    let summary = serde_json::json!({
        "id": id,
        "curves": plan.curves.len(),
        "frames": morph.frames.len(),
        "vertices": counts,
        "path": morph.path_name(),
        "fallback": morph.fallback,
        "fallbacks": morph.fallbacks,
        "milliseconds": (elapsed.as_secs_f64() * 1e4).round() / 10.0,
        "size": [plan.style.width, plan.style.height],
        "fps": plan.fps,
        "urls": {
            "frame": format!("/api/jobs/{id}/frame/{{k}}.png"),
            "gif": format!("/api/jobs/{id}/morph.gif"),
            "svg": format!("/api/jobs/{id}/morph.svg"),
            "lottie": format!("/api/jobs/{id}/morph.lottie.json"),
            "json": format!("/api/jobs/{id}/morph.json"),
        },
    });
    let mut text = summary.to_string();
    // Append the morph itself, exactly as `immerse morph --json` writes it.
    text.pop();
    text.push_str(",\"morph\":");
    text.push_str(&morph_json);
    text.push('}');
    state.keep(Job {
        id,
        frames,
        view,
        style: plan.style,
        fps: plan.fps,
        looping: plan.looping,
        morph_json,
    });
    Ok(Reply::json(text))
}

/// `GET /api/jobs/ID/...`.
fn job_file(state: &Arc<State>, path: &str, query: &str) -> Result<Reply, ApiError> {
    let rest = &path["/api/jobs/".len()..];
    let (id, what) = rest.split_once('/').unwrap_or((rest, ""));
    let job = id
        .parse::<u64>()
        .ok()
        .and_then(|id| state.job(id))
        .ok_or_else(|| {
            ApiError::new(
                404,
                format!(
                    "no morph job {id} on this server (only the last {MAX_STORED_JOBS} are kept); run the morph again"
                ),
            )
        })?;
    let render_err = |e: render::RenderError| ApiError::new(500, format!("{e:#}"));
    let download = query.split('&').any(|q| q == "download=1");
    if let Some(k) = what
        .strip_prefix("frame/")
        .and_then(|f| f.strip_suffix(".png"))
    {
        let n = job.frames.len();
        let k: usize = k.parse().ok().filter(|&k| k < n).ok_or_else(|| {
            ApiError::new(404, format!("no frame {k}: frames are 0 to {}", n - 1))
        })?;
        let ghosts: Vec<&render::Frame> = if job.style.onion_skin && n > 1 {
            vec![&job.frames[0], &job.frames[n - 1]]
        } else {
            Vec::new()
        };
        let pixmap =
            render::render(&job.frames[k], &job.view, &job.style, &ghosts).map_err(render_err)?;
        return Ok(Reply {
            content_type: "image/png",
            body: render::encode_png(&pixmap).map_err(render_err)?,
            download: download.then(|| render::frame_file_name(k, n, "png")),
        });
    }
    let (content_type, body, name) = match what {
        "morph.json" => (
            "application/json",
            job.morph_json.clone().into_bytes(),
            "morph.json",
        ),
        "morph.svg" => (
            "image/svg+xml",
            render::animated_svg(&job.frames, &job.style, job.fps, job.looping)
                .map_err(render_err)?
                .into_bytes(),
            "morph.svg",
        ),
        "morph.lottie.json" => (
            "application/json",
            render::lottie(&job.frames, &job.style, job.fps, job.looping)
                .map_err(render_err)?
                .into_bytes(),
            "morph.lottie.json",
        ),
        "morph.gif" => {
            let _slot = state.slot()?;
            let gif = render::encode_gif(
                &job.frames,
                &job.style,
                job.fps.min(50.0),
                job.looping,
                &render::Output::DEFAULT,
                &|_| {},
            )
            .map_err(render_err)?;
            ("image/gif", gif, "morph.gif")
        }
        _ => {
            return Err(ApiError::new(
                404,
                format!(
                    "no such file of a job: '{what}'; use frame/K.png, morph.gif, morph.svg, morph.lottie.json or morph.json"
                ),
            ));
        }
    };
    Ok(Reply {
        content_type,
        body,
        download: download.then(|| format!("immerse-{name}")),
    })
}
