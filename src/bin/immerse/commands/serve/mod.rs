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
//!   `.../morph.lottie.json`, `.../morph.json`: renderings of a job, and
//!   `.../progress` while its GIF renders;
//! - `GET /api/options` (the option lists and defaults the page offers),
//!   `GET /api/curves` (reference curves), `GET /api/limits`.
//!
//! The server runs on tokio: [`http`] holds the connections and the
//! checks every request passes, [`jobs`] bounds and runs the work, [`api`]
//! holds the routes. Every resource a client can make it spend is bounded
//! by a limit of `immerse serve --help` (docs/design.md §12). The server
//! never reads or writes a file: curves arrive in request bodies, the page
//! and the reference curves are compiled in.

mod api;
mod http;
mod jobs;

use crate::Outcome;
use crate::args::ServeArgs;
use crate::output;
use std::sync::Arc;
use std::time::Duration;

/// Connections the kernel queues for the accept loop. A burst beyond the
/// queue is not refused but retried by the client's kernel a second later,
/// so the queue is longer than a burst of hostile connections, whose
/// surplus the server then closes at once.
const LISTEN_QUEUE: i32 = 1024;

/// A non-blocking listener on loopback (the port is taken now, so a taken
/// port is a plain error), with a queue of [`LISTEN_QUEUE`].
fn listen(port: u16) -> std::io::Result<std::net::TcpListener> {
    use socket2::{Domain, Socket, Type};
    let socket = Socket::new(Domain::IPV4, Type::STREAM, None)?;
    // As the standard library does: a restarted server may take its port
    // back while old connections linger in TIME_WAIT.
    #[cfg(unix)]
    socket.set_reuse_address(true)?;
    socket.bind(&std::net::SocketAddr::from(([127, 0, 0, 1], port)).into())?;
    socket.listen(LISTEN_QUEUE)?;
    socket.set_nonblocking(true)?;
    Ok(socket.into())
}

pub(crate) fn run(args: &ServeArgs) -> anyhow::Result<Outcome> {
    let limits = &args.limits;
    // Bound before the runtime starts, so a taken port is a plain error.
    let listener = listen(args.port)
        .map_err(|e| anyhow::anyhow!("cannot listen on 127.0.0.1:{}: {e}", args.port))?;
    let port = listener.local_addr()?.port();
    let max_body = limits.max_body_bytes as usize;
    // The outer time limit of any request: its body and its job, with a
    // margin (each has its own, tighter limit).
    let request_timeout =
        Duration::from_secs(limits.body_timeout + limits.job_timeout + REQUEST_MARGIN_SECS);
    let guard = Arc::new(http::Guard::new(port, max_body, request_timeout));
    let state = Arc::new(api::State::new(limits, args.key_tolerance, guard)?);
    let app = api::app(state, request_timeout, max_body);
    let server = http::Server::new(http::ConnLimits {
        max_connections: limits.max_connections as usize,
        header_timeout: Duration::from_secs(limits.header_timeout),
        max_header_bytes: limits.max_header_bytes as usize,
        max_headers: limits.max_headers as usize,
        write_timeout: Duration::from_secs(limits.write_timeout),
    });
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        // Jobs run on blocking threads, at most one per job slot (work
        // that outlives its request keeps its slot).
        .max_blocking_threads(limits.max_jobs as usize + 1)
        .thread_name("immerse-serve")
        .enable_all()
        .build()?;

    // Ctrl-C, SIGTERM and SIGHUP stop accepting and let the requests in
    // flight finish (the CLI's handler calls this instead of exiting); a
    // second one exits at once.
    let (stop_tx, stop_rx) = tokio::sync::watch::channel(false);
    let stop_tx = Arc::new(stop_tx);
    let on_stop = Arc::clone(&stop_tx);
    let hooked = crate::ON_INTERRUPT.set(Box::new(move || {
        if on_stop.send_replace(true) {
            std::process::exit(crate::INTERRUPTED);
        }
    }));
    if hooked.is_err() {
        output::note("Ctrl-C stops the server at once (no drain)");
    }

    let url = format!("http://127.0.0.1:{port}/");
    output::print(&url)?;
    output::note(&format!(
        "serving the playground at {url} (127.0.0.1 only); press Ctrl-C to stop"
    ));
    if args.open {
        open_browser(&url);
    }

    let drain = Duration::from_secs(limits.drain_timeout);
    runtime.block_on(async {
        let listener = tokio::net::TcpListener::from_std(listener)?;
        Arc::clone(&server).serve(listener, app, stop_rx).await;
        let open = server.live();
        if open > 0 {
            output::note(&format!(
                "stopping: finishing {open} connection(s), at most {} s",
                drain.as_secs()
            ));
        }
        if tokio::time::timeout(drain, server.drained()).await.is_err() {
            output::note(&format!(
                "{} connection(s) still open after {} s; closing them",
                server.live(),
                drain.as_secs()
            ));
        }
        anyhow::Ok(())
    })?;
    // Jobs that outlived their requests end with the process.
    runtime.shutdown_timeout(Duration::from_millis(100));
    output::note("stopped");
    Ok(Outcome::Success)
}

/// Seconds added to a request's body and job limits for its outer limit.
const REQUEST_MARGIN_SECS: u64 = 5;

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
