//! Connections and the checks every request passes, whatever it asks.
//!
//! - [`Server::serve`] accepts connections on tokio and serves each with
//!   hyper's HTTP/1.1 connection, which bounds the request head's size
//!   (`--max-header-bytes`, `--max-headers`: HTTP 431) and the time to send
//!   it (`--header-timeout`, also how long an idle connection stays open).
//!   Writes to a client that stopped reading end the connection after
//!   `--write-timeout` (tokio-io-timeout). At most `--max-connections` are
//!   open: a new one closes the oldest connection that is not working on a
//!   request (one without a request, or whose request still waits for a
//!   job slot or its body), else is answered HTTP 503 at once.
//! - [`guard`] runs first for every request: the `Host` must name this
//!   server on loopback (DNS rebinding), a `POST` whose `Origin` is another
//!   site's is refused, and so is any API request whose `Sec-Fetch-Site`
//!   says another site sent it. Every error answer, including those of the
//!   layers below it (tower-http's request time limit and body limit),
//!   becomes `{"error": "..."}`.
//! - [`require_json`], [`read_body`] and [`parse_json`] take a POST's
//!   JSON body, within `--body-timeout`.

use axum::body::Body;
use axum::extract::{Request, State};
use axum::http::{HeaderMap, HeaderValue, Method, StatusCode, header};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use bytes::Bytes;
use http_body::{Frame, SizeHint};
use http_body_util::BodyExt;
use hyper::body::Incoming;
use hyper_util::rt::{TokioIo, TokioTimer};
use std::collections::{BTreeMap, VecDeque};
use std::convert::Infallible;
use std::pin::Pin;
use std::sync::atomic::{AtomicBool, AtomicU8, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll};
use std::time::{Duration, Instant};
use tokio::io::AsyncWriteExt;
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::{Notify, Semaphore, watch};
use tower::{Service, ServiceExt};

/// An error answer: HTTP status and a message for `{"error": ...}`.
#[derive(Debug)]
pub(super) struct ApiError {
    pub(super) status: u16,
    pub(super) message: String,
}

impl ApiError {
    pub(super) fn new(status: u16, message: impl Into<String>) -> ApiError {
        ApiError {
            status,
            message: message.into(),
        }
    }

    pub(super) fn bad(message: impl Into<String>) -> ApiError {
        ApiError::new(400, message)
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let status = StatusCode::from_u16(self.status).unwrap_or(StatusCode::INTERNAL_SERVER_ERROR);
        let body = serde_json::json!({ "error": self.message }).to_string();
        let mut r = (
            status,
            [
                (header::CONTENT_TYPE, HeaderValue::from_static(JSON)),
                (header::CONTENT_LENGTH, HeaderValue::from(body.len())),
            ],
            body,
        )
            .into_response();
        if status == StatusCode::SERVICE_UNAVAILABLE {
            r.headers_mut()
                .insert(header::RETRY_AFTER, HeaderValue::from_static("1"));
        }
        r
    }
}

const JSON: &str = "application/json";

/// A body sent as the chunks it is made of (a morph's answer is its
/// summary and then the morph JSON that its job keeps, without a copy),
/// each cut into frames of at most [`FRAME_BYTES`]: hyper asks for the
/// next frame only once it has written the last, so the body, and what it
/// holds, lasts until the answer is nearly all sent.
struct Chunks(VecDeque<Bytes>);

/// Largest frame of a [`Chunks`] body.
const FRAME_BYTES: usize = 64 << 10;

impl http_body::Body for Chunks {
    type Data = Bytes;
    type Error = Infallible;

    fn poll_frame(
        mut self: Pin<&mut Self>,
        _: &mut Context<'_>,
    ) -> Poll<Option<Result<Frame<Bytes>, Infallible>>> {
        let frame = match self.0.front_mut() {
            None => None,
            Some(first) if first.len() > FRAME_BYTES => Some(first.split_to(FRAME_BYTES)),
            Some(_) => self.0.pop_front(),
        };
        Poll::Ready(frame.map(|b| Ok(Frame::data(b))))
    }

    fn is_end_stream(&self) -> bool {
        self.0.is_empty()
    }

    fn size_hint(&self) -> SizeHint {
        SizeHint::with_exact(self.0.iter().map(|b| b.len() as u64).sum())
    }
}

/// A successful answer of `chunks` (one after another), keeping `hold` (a
/// job slot, the job itself) until its last byte is sent or the connection
/// ends; a download when `name` is given.
pub(super) fn reply(
    content_type: &'static str,
    chunks: Vec<Bytes>,
    name: Option<&str>,
    hold: impl Send + 'static,
) -> Response {
    let len: usize = chunks.iter().map(Bytes::len).sum();
    let body = Chunks(chunks.into()).map_frame(move |frame| {
        let _ = &hold;
        frame
    });
    let mut r = Response::new(Body::new(body));
    let h = r.headers_mut();
    h.insert(header::CONTENT_TYPE, HeaderValue::from_static(content_type));
    h.insert(header::CONTENT_LENGTH, HeaderValue::from(len));
    if let Some(name) = name
        && let Ok(v) = HeaderValue::from_str(&format!("attachment; filename=\"{name}\""))
    {
        h.insert(header::CONTENT_DISPOSITION, v);
    }
    r
}

/// The connection limits (`immerse serve --help`, "Limits").
#[derive(Clone, Copy, Debug)]
pub(super) struct ConnLimits {
    pub(super) max_connections: usize,
    pub(super) header_timeout: Duration,
    pub(super) max_header_bytes: usize,
    pub(super) max_headers: usize,
    pub(super) write_timeout: Duration,
}

/// What a connection is doing, for choosing which one to close when all
/// are taken.
const IDLE: u8 = 0;
const WAITING: u8 = 1;
const WORKING: u8 = 2;

/// How long a new connection has to send its request before it may be
/// closed to make room for another: on loopback a request follows its
/// connection within milliseconds.
const FRESH: Duration = Duration::from_millis(200);

/// Most connections accepted and waiting for a slot at once (while every
/// connection that could be closed is younger than [`FRESH`]); beyond
/// them, the oldest is closed once it is [`GRACE`] old.
const MAX_ENTERING: usize = 64;

/// The least time an admitted connection has before it may be closed to
/// make room, even when [`MAX_ENTERING`] are waiting: until the oldest is
/// that old, the accept loop waits (the kernel's listen queue holds the
/// new connections meanwhile). Without it, a burst of connections
/// accepted faster than their requests are read closed each new one
/// before its request was read: a well-formed `GET /` arriving inside a
/// burst of 600 connections was reset in 6 bursts of 80.
const GRACE: Duration = Duration::from_millis(20);

/// One open connection.
struct Conn {
    /// When it was admitted.
    since: Instant,
    phase: AtomicU8,
    close: Notify,
    /// Closed at once (to make room), not after its request (the drain).
    kill: AtomicBool,
}

/// A request's handle on its connection's phase (a request extension):
/// a job marks itself waiting until it holds its slot and its body.
#[derive(Clone)]
pub(super) struct Phase(Arc<Conn>);

impl Phase {
    /// The request waits for a job slot or for its body: the connection
    /// may be dropped to make room for another.
    pub(super) fn waiting(&self) {
        self.0.phase.store(WAITING, Ordering::SeqCst);
    }

    /// The request holds a slot: its connection is kept.
    pub(super) fn working(&self) {
        self.0.phase.store(WORKING, Ordering::SeqCst);
    }
}

/// Sets its connection idle when dropped (with the response body).
struct Busy(Arc<Conn>);

impl Drop for Busy {
    fn drop(&mut self) {
        self.0.phase.store(IDLE, Ordering::SeqCst);
    }
}

/// The open connections, oldest first.
#[derive(Default)]
struct Registry {
    next: u64,
    open: BTreeMap<u64, Arc<Conn>>,
}

/// Accepts and serves connections within [`ConnLimits`].
pub(super) struct Server {
    limits: ConnLimits,
    registry: Mutex<Registry>,
    /// Connection tasks running (a closed one until it has ended).
    live: AtomicUsize,
    ended: Notify,
    /// Refusals being written at once (beyond them, connections are
    /// closed without an answer).
    refusals: Arc<Semaphore>,
    /// Accepted connections waiting for a slot.
    entering: Arc<Semaphore>,
    /// Set when the server stops accepting.
    stopping: AtomicBool,
}

/// Whether a connection may be registered now.
enum Entry {
    Admitted(u64, Arc<Conn>),
    /// Every connection is working on a request.
    Full,
    /// The server has stopped accepting (the connection waited).
    Stopped,
    /// Every connection that could be closed is new: ask again after this
    /// long, or when a connection ends.
    Wait(Duration),
}

/// Most HTTP 503 refusals written at once when every connection is busy.
const MAX_REFUSALS: usize = 32;

impl Conn {
    fn new() -> Conn {
        Conn {
            since: Instant::now(),
            phase: AtomicU8::new(IDLE),
            close: Notify::new(),
            kill: AtomicBool::new(false),
        }
    }
}

impl Server {
    pub(super) fn new(limits: ConnLimits) -> Arc<Server> {
        Arc::new(Server {
            limits,
            registry: Mutex::new(Registry::default()),
            live: AtomicUsize::new(0),
            ended: Notify::new(),
            refusals: Arc::new(Semaphore::new(MAX_REFUSALS)),
            entering: Arc::new(Semaphore::new(MAX_ENTERING)),
            stopping: AtomicBool::new(false),
        })
    }

    fn registry(&self) -> std::sync::MutexGuard<'_, Registry> {
        self.registry.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Serves `app` on `listener` until `stop` turns true, then closes the
    /// connections without a request and lets the others finish theirs.
    pub(super) async fn serve<S>(
        self: Arc<Self>,
        listener: TcpListener,
        app: S,
        mut stop: watch::Receiver<bool>,
    ) where
        S: Service<Request, Response = Response, Error = Infallible> + Clone + Send + 'static,
        S::Future: Send + 'static,
    {
        let mut noted = false;
        loop {
            let accepted = tokio::select! {
                _ = stop.wait_for(|&s| s) => break,
                a = listener.accept() => a,
            };
            match accepted {
                Ok((stream, _)) => {
                    noted = false;
                    self.admit(stream, app.clone()).await;
                    // Lets the connections already admitted run, and the
                    // I/O driver be polled, before the next is admitted: in
                    // a burst of connections, a client that sent its
                    // request at once could otherwise still count as idle,
                    // the oldest, once the burst has filled every slot, and
                    // be closed to make room.
                    tokio::task::yield_now().await;
                }
                Err(e) => {
                    // Out of file handles (or another passing failure):
                    // wait for connections to end and accept again.
                    if !noted {
                        crate::output::note(&format!(
                            "cannot accept a connection ({e}); trying again"
                        ));
                        noted = true;
                    }
                    tokio::time::sleep(Duration::from_millis(50)).await;
                }
            }
        }
        drop(listener);
        // Connections without a request close now (a browser keeps spare
        // ones open); the others finish their request first.
        let reg = self.registry();
        self.stopping.store(true, Ordering::SeqCst);
        for conn in reg.open.values() {
            if conn.phase.load(Ordering::SeqCst) == IDLE {
                conn.kill.store(true, Ordering::SeqCst);
            }
            conn.close.notify_one();
        }
    }

    /// Connection tasks still running.
    pub(super) fn live(&self) -> usize {
        self.live.load(Ordering::SeqCst)
    }

    /// Waits until no connection task runs.
    pub(super) async fn drained(&self) {
        loop {
            let ended = self.ended.notified();
            if self.live() == 0 {
                return;
            }
            ended.await;
        }
    }

    /// Registers a new connection when there is room, or when the oldest
    /// connection not working on a request (idle, or waiting for a job
    /// slot or its body) can be closed to make room. Age, not the phase,
    /// decides, so a new connection that has not yet sent its request is
    /// the last to go; and none is closed before it has had [`FRESH`] to
    /// send it, unless `force`, and even then not before [`GRACE`].
    fn enter(&self, force: bool) -> Entry {
        let mut reg = self.registry();
        // Under the registry's lock, which the shutdown takes to close the
        // connections without a request, so none is admitted past it.
        if self.stopping.load(Ordering::SeqCst) {
            return Entry::Stopped;
        }
        if reg.open.len() >= self.limits.max_connections {
            let victim = reg
                .open
                .iter()
                .find(|(_, c)| c.phase.load(Ordering::SeqCst) != WORKING)
                .map(|(&id, c)| (id, c.since.elapsed()));
            let Some((victim, age)) = victim else {
                return Entry::Full;
            };
            let least = if force { GRACE } else { FRESH };
            if age < least {
                return Entry::Wait(least - age);
            }
            // Closed at once: it has no request (or one still waiting),
            // and hyper would keep a connection that has not finished its
            // first request open until it does.
            if let Some(c) = reg.open.remove(&victim) {
                c.kill.store(true, Ordering::SeqCst);
                c.close.notify_one();
            }
        }
        let id = reg.next;
        reg.next += 1;
        let conn = Arc::new(Conn::new());
        reg.open.insert(id, Arc::clone(&conn));
        self.live.fetch_add(1, Ordering::SeqCst);
        Entry::Admitted(id, conn)
    }

    /// Registers a new connection and serves it ([`enter`](Self::enter)),
    /// or refuses it when every connection is working. Where every
    /// connection that could be closed is new, it waits for a slot in a
    /// task of its own, so the accept loop goes on (a stalled loop would
    /// fill the listen queue, and new connections would wait seconds for
    /// the kernel to retry them); when [`MAX_ENTERING`] already wait, the
    /// oldest connection is closed to make room once it is [`GRACE`] old,
    /// and the accept loop waits until then.
    async fn admit<S>(self: &Arc<Self>, stream: TcpStream, app: S)
    where
        S: Service<Request, Response = Response, Error = Infallible> + Clone + Send + 'static,
        S::Future: Send + 'static,
    {
        let _ = stream.set_nodelay(true);
        let entry = match self.enter(false) {
            Entry::Wait(wait) => match Arc::clone(&self.entering).try_acquire_owned() {
                Ok(permit) => {
                    let server = Arc::clone(self);
                    tokio::spawn(async move {
                        let entry = server.enter_after(wait, false).await;
                        drop(permit);
                        server.run(entry, stream, app).await;
                    });
                    return;
                }
                Err(_) => match self.enter(true) {
                    Entry::Wait(wait) => self.enter_after(wait, true).await,
                    entry => entry,
                },
            },
            entry => entry,
        };
        let server = Arc::clone(self);
        tokio::spawn(async move { server.run(entry, stream, app).await });
    }

    /// [`enter`](Self::enter) again each time a connection ends or `wait`
    /// has passed, until it no longer says to wait.
    async fn enter_after(&self, mut wait: Duration, force: bool) -> Entry {
        loop {
            let ended = self.ended.notified();
            let _ = tokio::time::timeout(wait, ended).await;
            match self.enter(force) {
                Entry::Wait(w) => wait = w,
                entry => return entry,
            }
        }
    }

    /// Serves an admitted connection until it ends, or refuses it.
    async fn run<S>(self: Arc<Self>, entry: Entry, stream: TcpStream, app: S)
    where
        S: Service<Request, Response = Response, Error = Infallible> + Clone + Send + 'static,
        S::Future: Send + 'static,
    {
        let (id, conn) = match entry {
            Entry::Admitted(id, conn) => (id, conn),
            Entry::Full => return self.refuse(stream),
            Entry::Stopped | Entry::Wait(_) => return,
        };
        self.connection(stream, app, &conn).await;
        self.registry().open.remove(&id);
        self.live.fetch_sub(1, Ordering::SeqCst);
        self.ended.notify_waiters();
    }

    /// Answers HTTP 503 without reading the request, and closes.
    fn refuse(&self, mut stream: TcpStream) {
        let Ok(permit) = Arc::clone(&self.refusals).try_acquire_owned() else {
            return;
        };
        let max = self.limits.max_connections;
        tokio::spawn(async move {
            let body = serde_json::json!({
                "error": format!("the server has {max} connections open, its limit, and all are busy; try again shortly")
            })
            .to_string();
            let head = format!(
                "HTTP/1.1 503 Service Unavailable\r\ncontent-type: {JSON}\r\ncontent-length: {}\r\nretry-after: 1\r\ncache-control: no-store\r\nconnection: close\r\n\r\n",
                body.len()
            );
            let write = async {
                stream.write_all(head.as_bytes()).await?;
                stream.write_all(body.as_bytes()).await?;
                stream.shutdown().await
            };
            let _ = tokio::time::timeout(Duration::from_secs(2), write).await;
            drop(permit);
        });
    }

    /// Serves one connection until it ends or is closed.
    async fn connection<S>(&self, stream: TcpStream, app: S, conn: &Arc<Conn>)
    where
        S: Service<Request, Response = Response, Error = Infallible> + Clone + Send + 'static,
        S::Future: Send + 'static,
    {
        let mut io = tokio_io_timeout::TimeoutStream::new(stream);
        io.set_write_timeout(Some(self.limits.write_timeout));
        let io = TokioIo::new(Box::pin(io));
        let shared = Arc::clone(conn);
        let service = hyper::service::service_fn(move |req: hyper::Request<Incoming>| {
            shared.phase.store(WORKING, Ordering::SeqCst);
            let busy = Busy(Arc::clone(&shared));
            let mut req = req.map(Body::new);
            req.extensions_mut().insert(Phase(Arc::clone(&shared)));
            let app = app.clone();
            async move {
                let Ok(res) = app.oneshot(req).await;
                // The connection is busy until the body is sent.
                Ok::<_, Infallible>(res.map(|b| {
                    Body::new(b.map_frame(move |frame| {
                        let _ = &busy;
                        frame
                    }))
                }))
            }
        });
        let mut builder = hyper::server::conn::http1::Builder::new();
        builder
            .timer(TokioTimer::new())
            .header_read_timeout(self.limits.header_timeout)
            .max_header_size(self.limits.max_header_bytes)
            .max_headers(self.limits.max_headers)
            .max_buf_size((64 << 10).max(self.limits.max_header_bytes + 1024))
            .keep_alive(true);
        let served = builder.serve_connection(io, service);
        tokio::pin!(served);
        tokio::select! {
            _ = served.as_mut() => return,
            () = conn.close.notified() => {}
        }
        if conn.kill.load(Ordering::SeqCst) {
            return;
        }
        served.as_mut().graceful_shutdown();
        let _ = served.await;
    }
}

/// What [`guard`] checks and how it words the answers of the layers below.
pub(super) struct Guard {
    hosts: Vec<String>,
    origins: Vec<String>,
    url: String,
    max_body: usize,
    request_timeout: Duration,
}

impl Guard {
    pub(super) fn new(port: u16, max_body: usize, request_timeout: Duration) -> Guard {
        let names = ["127.0.0.1", "localhost", "[::1]"];
        let mut hosts: Vec<String> = names.iter().map(|n| format!("{n}:{port}")).collect();
        if port == 80 {
            hosts.extend(names.iter().map(|n| n.to_string()));
        }
        let origins = hosts.iter().map(|h| format!("http://{h}")).collect();
        Guard {
            hosts,
            origins,
            url: format!("http://127.0.0.1:{port}/"),
            max_body,
            request_timeout,
        }
    }

    fn check(&self, req: &Request) -> Result<(), ApiError> {
        let headers = req.headers();
        let text = |name: &str| {
            headers
                .get(name)
                .map(|v| v.to_str().unwrap_or("(not text)"))
        };
        let Some(host) = text(header::HOST.as_str()) else {
            return Err(ApiError::bad(format!(
                "the request has no Host header; use {}",
                self.url
            )));
        };
        if !self.hosts.iter().any(|h| h.eq_ignore_ascii_case(host)) {
            return Err(ApiError::new(
                403,
                format!("host '{host}' is not this server; use {}", self.url),
            ));
        }
        let api = req.uri().path().starts_with("/api/");
        let changes = !matches!(*req.method(), Method::GET | Method::HEAD);
        if let Some(site) = text(SEC_FETCH_SITE)
            && (api || changes)
            && !matches!(site, "same-origin" | "none")
        {
            return Err(ApiError::new(
                403,
                format!(
                    "a request sent by a page of another site ({site}) is refused; use the page at {}",
                    self.url
                ),
            ));
        }
        if changes
            && let Some(origin) = text(header::ORIGIN.as_str())
            && !self.origins.iter().any(|o| o.eq_ignore_ascii_case(origin))
        {
            return Err(ApiError::new(
                403,
                format!(
                    "a page of another site ({origin}) may not send requests to this server; use the page at {}",
                    self.url
                ),
            ));
        }
        Ok(())
    }

    /// The body-limit message: `declared` is the announced length.
    pub(super) fn too_large(&self, declared: Option<u64>) -> ApiError {
        let max = self.max_body;
        let mib = if max % (1 << 20) == 0 {
            format!(" ({} MiB)", max >> 20)
        } else {
            String::new()
        };
        let size = match declared {
            Some(n) if n > max as u64 => format!("{n} bytes"),
            _ => format!("more than {max} bytes"),
        };
        ApiError::new(
            413,
            format!("the request body is {size}; the limit is {max} bytes{mib}"),
        )
    }
}

/// The header that says which site a browser request comes from (`http`
/// has no constant for it).
const SEC_FETCH_SITE: &str = "sec-fetch-site";

/// The outermost layer: checks every request ([`Guard`]), turns the plain
/// error answers of the layers below into JSON, and adds the headers every
/// answer carries.
pub(super) async fn guard(State(g): State<Arc<Guard>>, req: Request, next: Next) -> Response {
    let declared = content_length(req.headers());
    let mut res = match g.check(&req) {
        Ok(()) => next.run(req).await,
        Err(e) => e.into_response(),
    };
    let status = res.status();
    let is_json = res
        .headers()
        .get(header::CONTENT_TYPE)
        .is_some_and(|v| v.as_bytes().starts_with(JSON.as_bytes()));
    if (status.is_client_error() || status.is_server_error()) && !is_json {
        let e = match status {
            StatusCode::PAYLOAD_TOO_LARGE => g.too_large(declared),
            StatusCode::REQUEST_TIMEOUT => ApiError::new(
                408,
                format!(
                    "the request took longer than {} s, this server's limit",
                    g.request_timeout.as_secs()
                ),
            ),
            s => ApiError::new(s.as_u16(), format!("HTTP {s}")),
        };
        res = e.into_response();
    }
    let html = res
        .headers()
        .get(header::CONTENT_TYPE)
        .is_some_and(|v| v.as_bytes().starts_with(b"text/html"));
    let h = res.headers_mut();
    for (name, value) in [
        (header::CACHE_CONTROL, "no-store"),
        (header::X_CONTENT_TYPE_OPTIONS, "nosniff"),
        (header::REFERRER_POLICY, "no-referrer"),
        (header::X_FRAME_OPTIONS, "DENY"),
    ] {
        h.insert(name, HeaderValue::from_static(value));
    }
    // Other sites may not read the API's answers, even as images.
    h.insert(
        "cross-origin-resource-policy",
        HeaderValue::from_static("same-origin"),
    );
    if html {
        h.insert(header::CONTENT_SECURITY_POLICY, HeaderValue::from_static(
            "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; img-src 'self' blob: data:; connect-src 'self'; frame-ancestors 'none'; base-uri 'none'; form-action 'none'",
        ));
    }
    res
}

fn content_length(headers: &HeaderMap) -> Option<u64> {
    headers
        .get(header::CONTENT_LENGTH)?
        .to_str()
        .ok()?
        .trim()
        .parse()
        .ok()
}

/// HTTP 415 unless the request says its body is JSON
/// (`application/json`, with or without parameters).
pub(super) fn require_json(headers: &HeaderMap) -> Result<(), ApiError> {
    let json = headers
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.split(';').next())
        .is_some_and(|media| media.trim().eq_ignore_ascii_case(JSON));
    if json {
        Ok(())
    } else {
        Err(ApiError::new(
            415,
            "send the request body as JSON with Content-Type: application/json",
        ))
    }
}

/// Reads a request body within `timeout` (HTTP 408), at most the body
/// limit that [`tower_http::limit::RequestBodyLimitLayer`] enforces while
/// it is read (HTTP 413).
pub(super) async fn read_body(
    body: Body,
    timeout: Duration,
    guard: &Guard,
) -> Result<Bytes, ApiError> {
    match tokio::time::timeout(timeout, body.collect()).await {
        Err(_) => Err(ApiError::new(
            408,
            format!(
                "the request body did not arrive within {} s, this server's limit",
                timeout.as_secs()
            ),
        )),
        Ok(Err(e)) => {
            let mut cause: Option<&(dyn std::error::Error + 'static)> = Some(&e);
            while let Some(c) = cause {
                if c.is::<http_body_util::LengthLimitError>() {
                    return Err(guard.too_large(None));
                }
                cause = c.source();
            }
            Err(ApiError::bad(format!("cannot read the request body: {e}")))
        }
        Ok(Ok(collected)) => Ok(collected.to_bytes()),
    }
}

/// Parses JSON, with the line and column of a syntax or shape error.
pub(super) fn parse_json<'a, T: serde::Deserialize<'a>>(body: &'a [u8]) -> Result<T, ApiError> {
    serde_json::from_slice(body).map_err(|e| ApiError::bad(format!("bad request JSON: {e}")))
}
