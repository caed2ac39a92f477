//! Hostile local traffic against `immerse serve` (loopback only, bounded
//! in count and time: about a minute in all). Run by `.ci/run`:
//!
//! ```sh
//! cargo test --release --test hostile -- --nocapture
//! ```
//!
//! Each attack gets a fresh server with the default limits, started with
//! the usual limit of 1024 open files, while a prober asks `GET /` every
//! 100 ms and the server's resident memory is sampled every 20 ms. For
//! every attack the test asserts that `GET /` keeps answering within 2 s,
//! that the server is alive at the end, and that its RSS stays under
//! [`RSS_BOUND`]; it prints a table of what it measured.
//!
//! `IMMERSE_BIN=path` measures another build of the binary instead (for
//! the table of docs/serve-hardening.md) and only reports.

#![allow(
    unreachable_pub,
    reason = "items of a test binary are reachable only inside it"
)]

use std::io::{Read, Write};
use std::net::TcpStream;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use testkit::serve::{Server, rss_of};

/// The most resident memory the server may use under any attack here:
/// the stored-morph budget (`--job-memory`, 128 MiB by default), the work
/// of the two jobs that may run at once (packing a morph of 5,000 points
/// and 240 frames takes about 140 MB: its frames, their JSON, 68 MB, and
/// the frames kept for rendering), and room for the allocator. The largest
/// peaks measured are 337 to 409 MiB (usvg reading two 2 MB SVGs at once).
const RSS_BOUND: u64 = 512 << 20;

/// How long `GET /` may take while the server is under attack.
const PROBE_LIMIT: Duration = Duration::from_secs(2);

/// The open-file limit the server runs with.
const NOFILE: u32 = 1024;

fn binary() -> (String, bool) {
    match std::env::var("IMMERSE_BIN") {
        Ok(b) if !b.is_empty() => (b, false),
        _ => (env!("CARGO_BIN_EXE_immerse").to_string(), true),
    }
}

/// Starts the server under the open-file limit.
fn start(bin: &str) -> Server {
    Server::start_limited(bin, NOFILE, &[])
}

/// What one attack did, and how the server fared.
#[derive(Default)]
struct Outcome {
    attack: String,
    /// What the attacking requests got, summarised.
    answers: String,
    probes: u64,
    probe_failures: u64,
    slowest_probe: Duration,
    peak_rss: u64,
    alive: bool,
}

/// Asks `GET /` every 100 ms and samples the RSS every 20 ms, until
/// stopped.
struct Watch {
    stop: Arc<AtomicBool>,
    probes: Arc<AtomicU64>,
    failures: Arc<AtomicU64>,
    slowest: Arc<AtomicU64>,
    peak: Arc<AtomicU64>,
    threads: Vec<std::thread::JoinHandle<()>>,
}

impl Watch {
    fn start(port: u16, pid: u32) -> Watch {
        let stop = Arc::new(AtomicBool::new(false));
        let probes = Arc::new(AtomicU64::new(0));
        let failures = Arc::new(AtomicU64::new(0));
        let slowest = Arc::new(AtomicU64::new(0));
        let peak = Arc::new(AtomicU64::new(0));
        let mut threads = Vec::new();
        {
            let (stop, probes, failures, slowest) = (
                Arc::clone(&stop),
                Arc::clone(&probes),
                Arc::clone(&failures),
                Arc::clone(&slowest),
            );
            threads.push(std::thread::spawn(move || {
                while !stop.load(Ordering::SeqCst) {
                    let t = Instant::now();
                    let ok = probe(port);
                    let took = t.elapsed();
                    probes.fetch_add(1, Ordering::SeqCst);
                    if !ok || took > PROBE_LIMIT {
                        failures.fetch_add(1, Ordering::SeqCst);
                    }
                    slowest.fetch_max(took.as_micros() as u64, Ordering::SeqCst);
                    std::thread::sleep(Duration::from_millis(100).saturating_sub(took));
                }
            }));
        }
        {
            let (stop, peak) = (Arc::clone(&stop), Arc::clone(&peak));
            threads.push(std::thread::spawn(move || {
                while !stop.load(Ordering::SeqCst) {
                    if let Some(rss) = rss_of(pid) {
                        peak.fetch_max(rss, Ordering::SeqCst);
                    }
                    std::thread::sleep(Duration::from_millis(20));
                }
            }));
        }
        Watch {
            stop,
            probes,
            failures,
            slowest,
            peak,
            threads,
        }
    }

    fn finish(self, attack: &str, answers: String, server: &mut Server) -> Outcome {
        // One last probe after the attack.
        let t = Instant::now();
        let last_ok = probe(server.port) && t.elapsed() <= PROBE_LIMIT;
        self.stop.store(true, Ordering::SeqCst);
        for t in self.threads {
            let _ = t.join();
        }
        Outcome {
            attack: attack.to_string(),
            answers,
            probes: self.probes.load(Ordering::SeqCst) + 1,
            probe_failures: self.failures.load(Ordering::SeqCst) + u64::from(!last_ok),
            slowest_probe: Duration::from_micros(self.slowest.load(Ordering::SeqCst))
                .max(t.elapsed()),
            peak_rss: self.peak.load(Ordering::SeqCst),
            alive: server.alive(),
        }
    }
}

/// `GET /` on a new connection: true when a whole 200 answer came within
/// [`PROBE_LIMIT`].
fn probe(port: u16) -> bool {
    let Ok(mut s) = TcpStream::connect_timeout(&([127, 0, 0, 1], port).into(), PROBE_LIMIT) else {
        return false;
    };
    let _ = s.set_read_timeout(Some(PROBE_LIMIT));
    let _ = s.set_write_timeout(Some(PROBE_LIMIT));
    let head = format!("GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\n\r\n");
    if s.write_all(head.as_bytes()).is_err() {
        return false;
    }
    let mut out = Vec::new();
    let _ = s.read_to_end(&mut out);
    out.starts_with(b"HTTP/1.1 200") && out.windows(7).any(|w| w == b"</html>")
}

/// Counts of what a set of connections got: `404×3, no answer×2`.
#[derive(Default)]
struct Tally(Mutex<std::collections::BTreeMap<String, usize>>);

impl Tally {
    fn add(&self, what: impl Into<String>) {
        *self.0.lock().unwrap().entry(what.into()).or_default() += 1;
    }

    fn text(&self) -> String {
        let m = self.0.lock().unwrap();
        if m.is_empty() {
            return "none".to_string();
        }
        m.iter()
            .map(|(k, n)| format!("{k}×{n}"))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// The status of an answer on `s` within `wait`, "closed" when the server
/// closed without one, or "no answer" when nothing came.
fn answer(s: &mut TcpStream, wait: Duration) -> String {
    let _ = s.set_read_timeout(Some(wait));
    let mut buf = [0_u8; 64];
    match s.read(&mut buf) {
        Ok(0) => "closed".to_string(),
        Ok(n) => {
            let text = String::from_utf8_lossy(&buf[..n]).to_string();
            text.split(' ').nth(1).unwrap_or("?").to_string()
        }
        Err(e)
            if matches!(
                e.kind(),
                std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
            ) =>
        {
            "no answer".to_string()
        }
        Err(_) => "reset".to_string(),
    }
}

fn connect(port: u16) -> Option<TcpStream> {
    TcpStream::connect_timeout(&([127, 0, 0, 1], port).into(), Duration::from_secs(2)).ok()
}

/// The points of a curve file of `curves/`.
fn points_of(name: &str) -> serde_json::Value {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("curves")
        .join(name);
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    v.get("points").cloned().unwrap_or(v)
}

fn ellipse(n: usize, rx: f64, ry: f64, wobble: f64) -> Vec<[f64; 2]> {
    (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            [rx * a.cos() + wobble * (3.0 * a).cos(), ry * a.sin()]
        })
        .collect()
}

/// A morph job through the API: its answer (or None when refused).
fn morph(port: u16, body: &serde_json::Value) -> Option<serde_json::Value> {
    let text = body.to_string();
    let head = format!(
        "POST /api/morph HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
        text.len()
    );
    let mut s = connect(port)?;
    s.set_read_timeout(Some(Duration::from_secs(60))).ok()?;
    s.write_all(head.as_bytes()).ok()?;
    s.write_all(text.as_bytes()).ok()?;
    let mut out = Vec::new();
    let _ = s.read_to_end(&mut out);
    let (status, _, body) = testkit::serve::parse_response(&out);
    (status == 200).then(|| serde_json::from_slice(&body).ok())?
}

fn request_head(port: u16, method: &str, path: &str, extra: &str) -> String {
    format!("{method} {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n{extra}\r\n")
}

/// 600 connections that never send a byte, held 3 s.
fn idle_connections(port: u16) -> String {
    let conns: Vec<TcpStream> = (0..600).filter_map(|_| connect(port)).collect();
    std::thread::sleep(Duration::from_secs(3));
    let tally = Tally::default();
    tally.add(format!("connected of 600: {}; then", conns.len()));
    for mut c in conns {
        tally.add(answer(&mut c, Duration::from_millis(1)));
    }
    tally.text()
}

/// 600 POSTs announcing a body over 1 GiB and sending none, held open.
fn huge_content_length(port: u16) -> String {
    let head = request_head(
        port,
        "POST",
        "/api/check",
        "Content-Type: application/json\r\nContent-Length: 2147483648\r\n",
    );
    let mut conns = Vec::new();
    for _ in 0..600 {
        if let Some(mut c) = connect(port)
            && c.write_all(head.as_bytes()).is_ok()
        {
            conns.push(c);
        }
    }
    std::thread::sleep(Duration::from_secs(2));
    let tally = Tally::default();
    for mut c in conns {
        tally.add(answer(&mut c, Duration::from_millis(20)));
    }
    tally.text()
}

/// 64 POSTs whose bodies come one byte every 250 ms, for 5 s: 32 announce
/// 100,000 bytes, 32 announce 3,000,000 (over the body limit).
fn slow_bodies(port: u16) -> String {
    let mut conns: Vec<TcpStream> = (0..64)
        .filter_map(|i| {
            let length = if i % 2 == 0 { 100_000 } else { 3_000_000 };
            let head = request_head(
                port,
                "POST",
                "/api/check",
                &format!("Content-Type: application/json\r\nContent-Length: {length}\r\n"),
            );
            let mut c = connect(port)?;
            c.write_all(head.as_bytes()).ok()?;
            Some(c)
        })
        .collect();
    let t = Instant::now();
    while t.elapsed() < Duration::from_secs(5) {
        for c in &mut conns {
            let _ = c.write_all(b" ");
        }
        std::thread::sleep(Duration::from_millis(250));
    }
    let tally = Tally::default();
    for mut c in conns {
        tally.add(answer(&mut c, Duration::from_millis(20)));
    }
    tally.text()
}

/// 8 connections each sending a request head without end, 50 MiB each at
/// most (400 MiB in all), until the server stops reading: four as one
/// header line that never ends, four as ever more header lines.
fn header_flood(port: u16) -> String {
    let tally = Arc::new(Tally::default());
    let sent = Arc::new(AtomicU64::new(0));
    let threads: Vec<_> = (0..8)
        .map(|i| {
            let (tally, sent) = (Arc::clone(&tally), Arc::clone(&sent));
            std::thread::spawn(move || {
                let Some(mut c) = connect(port) else {
                    tally.add("refused");
                    return;
                };
                let _ = c.set_write_timeout(Some(Duration::from_secs(2)));
                let start = format!("GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nX-Flood: ");
                let block = if i % 2 == 0 {
                    "f".repeat(64 << 10)
                } else {
                    format!("f\r\nX-Flood: {}", "f".repeat(100)).repeat(560)
                };
                let mut total = 0_u64;
                let t = Instant::now();
                if c.write_all(start.as_bytes()).is_ok() {
                    while total < 50 << 20 && t.elapsed() < Duration::from_secs(8) {
                        match c.write(block.as_bytes()) {
                            Ok(n) if n > 0 => total += n as u64,
                            _ => break,
                        }
                    }
                }
                sent.fetch_add(total, Ordering::SeqCst);
                tally.add(answer(&mut c, Duration::from_millis(200)));
            })
        })
        .collect();
    for t in threads {
        let _ = t.join();
    }
    format!(
        "{} ({} MiB sent)",
        tally.text(),
        sent.load(Ordering::SeqCst) >> 20
    )
}

/// 200 POSTs announcing 1,000,000 bytes and sending 20, held 4 s.
fn lying_content_length(port: u16) -> String {
    let head = request_head(
        port,
        "POST",
        "/api/morph",
        "Content-Type: application/json\r\nContent-Length: 1000000\r\n",
    );
    let conns: Vec<TcpStream> = (0..200)
        .filter_map(|_| {
            let mut c = connect(port)?;
            c.write_all(head.as_bytes()).ok()?;
            c.write_all(b"{\"curves\": [[[0, 0],").ok()?;
            Some(c)
        })
        .collect();
    std::thread::sleep(Duration::from_secs(4));
    let tally = Tally::default();
    for mut c in conns {
        tally.add(answer(&mut c, Duration::from_millis(20)));
    }
    tally.text()
}

/// Downloads that are abandoned or never read. First 8 downloads of the
/// 68 MB JSON of a 5,000-point, 240-frame morph that are never read, held
/// open 4 s; then 24 downloads of a GIF that takes half a minute (240
/// frames of 2048²) and of its SVG, closed as soon as they are sent; then
/// a check, which must find a job slot.
fn abandoned_downloads(port: u16) -> String {
    let big = serde_json::json!({
        "curves": [ellipse(5000, 300.0, 200.0, 0.0), ellipse(5000, 200.0, 300.0, 20.0)],
        "frames": 240,
    });
    let slow = serde_json::json!({
        "curves": [points_of("spiral-strip-400deg-n30.json"), points_of("curl-strip-n10.json")],
        "frames": 240, "size": [2048, 2048],
    });
    let (Some(big), Some(slow)) = (morph(port, &big), morph(port, &slow)) else {
        return "the morphs were refused".to_string();
    };
    let tally = Tally::default();
    let path = big["urls"]["json"].as_str().unwrap().to_string();
    let stalled: Vec<TcpStream> = (0..8)
        .filter_map(|_| {
            let mut c = connect(port)?;
            c.write_all(request_head(port, "GET", &path, "").as_bytes())
                .ok()?;
            Some(c)
        })
        .collect();
    std::thread::sleep(Duration::from_secs(4));
    // Read from all of them before closing any: a closed one gives its
    // slot to the next.
    let mut stalled = stalled;
    for c in &mut stalled {
        let mut one = [0_u8; 12];
        let _ = c.set_read_timeout(Some(Duration::from_millis(1)));
        match c.read(&mut one) {
            Ok(n) if n >= 12 => tally.add(format!(
                "unread JSON: {}",
                String::from_utf8_lossy(&one[9..12])
            )),
            _ => tally.add("unread JSON: nothing yet"),
        }
    }
    drop(stalled);
    for (url, n) in [("gif", 16), ("svg", 8)] {
        let path = slow["urls"][url].as_str().unwrap().to_string();
        let head = request_head(port, "GET", &path, "");
        for _ in 0..n {
            if let Some(mut c) = connect(port) {
                let _ = c.write_all(head.as_bytes());
            }
        }
    }
    std::thread::sleep(Duration::from_millis(500));
    let t = Instant::now();
    let check = serde_json::json!({"points": points_of("curl-strip-n10.json")}).to_string();
    let head = format!(
        "POST /api/check HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
        check.len()
    );
    let status = connect(port).map(|mut c| {
        let _ = c.write_all(head.as_bytes());
        let _ = c.write_all(check.as_bytes());
        answer(&mut c, Duration::from_secs(30))
    });
    tally.add(format!(
        "then a check: {} in {:.1} s",
        status.unwrap_or_else(|| "refused".into()),
        t.elapsed().as_secs_f64()
    ));
    tally.text()
}

/// 32 checks at once of a 2 MB SVG path of arcs.
fn svg_of_arcs(port: u16) -> String {
    let mut d = String::from("M0 0");
    while d.len() < 2_000_000 {
        d.push_str(" a9 9 0 1 1 1 0");
    }
    d.push_str(" Z");
    let svg = format!("<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"{d}\"/></svg>");
    let body = serde_json::json!({"data": svg, "format": "svg", "name": "arcs.svg"}).to_string();
    let head = format!(
        "POST /api/check HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
        body.len()
    );
    let tally = Arc::new(Tally::default());
    let body = Arc::new(body);
    let threads: Vec<_> = (0..32)
        .map(|_| {
            let (tally, body, head) = (Arc::clone(&tally), Arc::clone(&body), head.clone());
            std::thread::spawn(move || {
                let Some(mut c) = connect(port) else {
                    tally.add("refused");
                    return;
                };
                let _ = c.write_all(head.as_bytes());
                let _ = c.write_all(body.as_bytes());
                tally.add(answer(&mut c, Duration::from_secs(60)));
            })
        })
        .collect();
    for t in threads {
        let _ = t.join();
    }
    tally.text()
}

/// 16 morphs at once of two drawings of 64 shapes (the most the
/// playground takes) of 78 points each (4,992 points: a drawing holds at
/// most as many as a curve), 240 frames: every pair a morph, and the
/// pairing of 64 × 64 shapes.
fn drawing_morphs(port: u16) -> String {
    let drawing = |rx: f64, ry: f64| {
        let shapes: Vec<serde_json::Value> = (0..64)
            .map(|k| {
                let (cx, cy) = (f64::from(k % 8) * 700.0, f64::from(k / 8) * 700.0);
                let points: Vec<[f64; 2]> = ellipse(78, rx, ry, 10.0)
                    .into_iter()
                    .map(|[x, y]| {
                        [
                            ((x + cx) * 10.0).round() / 10.0,
                            ((y + cy) * 10.0).round() / 10.0,
                        ]
                    })
                    .collect();
                serde_json::json!({"id": format!("s{k}"), "points": points, "fill": "#3d7cc9"})
            })
            .collect();
        serde_json::json!({ "shapes": shapes })
    };
    let body = serde_json::json!({
        "drawings": [drawing(300.0, 200.0), drawing(200.0, 300.0)],
        "frames": 240,
    });
    let tally = Arc::new(Tally::default());
    let body = Arc::new(body);
    let threads: Vec<_> = (0..16)
        .map(|_| {
            let (tally, body) = (Arc::clone(&tally), Arc::clone(&body));
            std::thread::spawn(move || {
                tally.add(if morph(port, &body).is_some() {
                    "200"
                } else {
                    "refused"
                });
            })
        })
        .collect();
    for t in threads {
        let _ = t.join();
    }
    tally.text()
}

/// 10 morphs of two 5,000-point curves with 240 frames, one after the
/// other (each answer is 68 MB of JSON, and each is kept as a job).
fn stored_jobs(port: u16) -> String {
    let body = serde_json::json!({
        "curves": [ellipse(5000, 300.0, 200.0, 0.0), ellipse(5000, 200.0, 300.0, 20.0)],
        "frames": 240,
    });
    let tally = Tally::default();
    for _ in 0..10 {
        tally.add(if morph(port, &body).is_some() {
            "200"
        } else {
            "refused"
        });
    }
    tally.text()
}

/// 32 downloads at once of the animated SVG of a 5,000-point,
/// 240-frame morph, read slowly.
fn many_downloads(port: u16) -> String {
    let body = serde_json::json!({
        "curves": [ellipse(5000, 300.0, 200.0, 0.0), ellipse(5000, 200.0, 300.0, 20.0)],
        "frames": 240,
    });
    let Some(job) = morph(port, &body) else {
        return "the morph was refused".to_string();
    };
    let path = job["urls"]["svg"].as_str().unwrap().to_string();
    let tally = Arc::new(Tally::default());
    let threads: Vec<_> = (0..32)
        .map(|_| {
            let (tally, path) = (Arc::clone(&tally), path.clone());
            std::thread::spawn(move || {
                let Some(mut c) = connect(port) else {
                    tally.add("refused");
                    return;
                };
                let _ = c.write_all(
                    request_head(port, "GET", &path, "Connection: close\r\n").as_bytes(),
                );
                let _ = c.set_read_timeout(Some(Duration::from_secs(60)));
                let mut buf = vec![0_u8; 1 << 16];
                let mut head = Vec::new();
                loop {
                    match c.read(&mut buf) {
                        Ok(0) | Err(_) => break,
                        Ok(n) => {
                            if head.len() < 12 {
                                head.extend_from_slice(&buf[..n.min(12)]);
                            }
                            std::thread::sleep(Duration::from_millis(2));
                        }
                    }
                }
                tally.add(if head.len() >= 12 {
                    String::from_utf8_lossy(&head[9..12]).to_string()
                } else {
                    "closed".to_string()
                });
            })
        })
        .collect();
    for t in threads {
        let _ = t.join();
    }
    tally.text()
}

type Attack = fn(u16) -> String;

#[test]
fn hostile_local_traffic() {
    let (bin, assert) = binary();
    let attacks: [(&str, Attack); 10] = [
        ("600 idle connections", idle_connections),
        ("600 bodies announced at 2 GiB", huge_content_length),
        ("64 slow bodies", slow_bodies),
        ("header flood, 8 × 50 MiB", header_flood),
        ("200 lying Content-Lengths", lying_content_length),
        ("8 unread and 24 abandoned downloads", abandoned_downloads),
        ("32 checks of a 2 MB SVG of arcs", svg_of_arcs),
        ("10 stored morphs of 68 MB", stored_jobs),
        ("32 slow downloads of a 5,000-point SVG", many_downloads),
        ("16 morphs of two 64-shape drawings", drawing_morphs),
    ];
    let started = Instant::now();
    let mut outcomes = Vec::new();
    for (name, attack) in attacks {
        let mut server = start(&bin);
        let watch = Watch::start(server.port, server.child.id());
        let answers = attack(server.port);
        outcomes.push(watch.finish(name, answers, &mut server));
    }
    println!(
        "\n| attack | answers to the attack | GET / during it (slowest) | peak RSS | survived |"
    );
    println!("|---|---|---|---|---|");
    for o in &outcomes {
        println!(
            "| {} | {} | {} of {} in time ({:.2} s) | {} MiB | {} |",
            o.attack,
            o.answers,
            o.probes - o.probe_failures,
            o.probes,
            o.slowest_probe.as_secs_f64(),
            o.peak_rss >> 20,
            if o.alive { "yes" } else { "no" },
        );
    }
    println!(
        "\n{bin}: {} attacks in {:.0} s",
        outcomes.len(),
        started.elapsed().as_secs_f64()
    );
    if !assert {
        return;
    }
    for o in &outcomes {
        assert!(o.alive, "{}: the server died", o.attack);
        assert_eq!(
            o.probe_failures, 0,
            "{}: GET / failed or took over 2 s ({} of {} probes; slowest {:?})",
            o.attack, o.probe_failures, o.probes, o.slowest_probe
        );
        assert!(
            o.peak_rss < RSS_BOUND,
            "{}: RSS reached {} MiB, over the bound of {} MiB",
            o.attack,
            o.peak_rss >> 20,
            RSS_BOUND >> 20
        );
    }
    // No connection is closed to make room before its request could be
    // read (the server's grace): every announced 2 GiB body gets its 413.
    let huge = &outcomes[1];
    assert_eq!(
        (huge.attack.as_str(), huge.answers.as_str()),
        ("600 bodies announced at 2 GiB", "413×600"),
        "a connection was closed before its request was read"
    );
}
