//! `immerse serve` through the real binary and a minimal HTTP client on
//! loopback (no node, no browser: those are in tests/browser/; the
//! hostile-traffic test is tests/hostile.rs), and `immerse morph --format
//! lottie`.

use crate::util::{curve, immerse, stderr};
use std::io::Write;
use std::net::TcpStream;
use std::process::Command;
use std::time::{Duration, Instant};

use testkit::serve::{Server, error_of, raw_request, read_response};

/// `immerse serve --port 0` of this package's binary with `extra`
/// arguments, stderr discarded.
fn start(extra: &[&str]) -> Server {
    Server::start_with(env!("CARGO_BIN_EXE_immerse"), extra, false)
}

/// The points of a curve file of `curves/` (JSON files only).
fn points_of(name: &str) -> serde_json::Value {
    let text = std::fs::read_to_string(curve(name)).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v.get("points").cloned().unwrap_or(v)
}

/// A small pair whose morph is quick at any size.
fn pair() -> [serde_json::Value; 2] {
    [
        points_of("spiral-strip-400deg-n30.json"),
        points_of("curl-strip-n10.json"),
    ]
}

/// A job whose GIF takes half a minute or more: 240 frames of 2048².
fn slow_gif_job(server: &Server) -> serde_json::Value {
    let [a, b] = pair();
    let (status, reply) = server.post(
        "/api/morph",
        &serde_json::json!({"curves": [a, b], "frames": 240, "size": [2048, 2048]}),
    );
    assert_eq!(status, 200, "{reply}");
    reply
}

/// Opens a connection and sends `head` (and `body`), leaving it open.
fn send(port: u16, head: &str, body: &[u8]) -> TcpStream {
    let mut s = TcpStream::connect(("127.0.0.1", port)).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(120))).unwrap();
    s.write_all(head.as_bytes()).unwrap();
    s.write_all(body).unwrap();
    s
}

#[test]
fn serve_morphs_like_the_cli_and_serves_the_page() {
    let server = start(&[]);
    let (status, page) = server.get("/");
    assert_eq!(status, 200);
    assert!(String::from_utf8_lossy(&page).contains("immerse playground"));
    // HEAD: the page's headers and length, no body.
    let head = server.head("HEAD", "/", None);
    let (status, head, body) = raw_request(server.port, head.as_bytes(), b"");
    assert_eq!(status, 200);
    assert!(body.is_empty());
    assert!(
        head.to_ascii_lowercase()
            .contains(&format!("content-length: {}", page.len())),
        "{head}"
    );
    let (status, limits) = server.get("/api/limits");
    assert_eq!(status, 200);
    let limits: serde_json::Value = serde_json::from_slice(&limits).unwrap();
    assert_eq!(limits["max_points"], 5000);
    assert_eq!(limits["max_frames"], 240);
    assert_eq!(limits["max_connections"], 128);
    let (status, refs) = server.get("/api/curves");
    assert_eq!(status, 200);
    let refs: serde_json::Value = serde_json::from_slice(&refs).unwrap();
    let refs = refs["curves"].as_array().unwrap().clone();
    assert!(refs.len() >= 8);
    // Each reference curve's tag is the verdict of /api/check on it.
    for r in &refs {
        let (status, check) =
            server.post("/api/check", &serde_json::json!({"points": r["points"]}));
        assert_eq!(status, 200, "{check}");
        assert_eq!(
            check["self_overlapping"], r["self_overlapping"],
            "{}",
            r["name"]
        );
    }

    let (a, b) = ("spiral-strip-400deg-n30.json", "curl-strip-n10.json");
    let (status, reply) = server.post(
        "/api/morph",
        &serde_json::json!({"curves": [points_of(a), points_of(b)], "frames": 7, "size": [200, 150]}),
    );
    assert_eq!(status, 200, "{reply}");
    assert_eq!(reply["frames"], 7);
    // A job id is 128 random bits, and the URLs name it.
    let id = reply["id"].as_str().unwrap();
    assert_eq!(id.len(), 32);
    assert!(id.bytes().all(|c| c.is_ascii_hexdigit()));
    assert!(reply["urls"]["gif"].as_str().unwrap().contains(id));
    // The frames are those of `immerse morph --json` for the same curves.
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("m.json");
    let out = immerse(&[
        "morph",
        curve(a).to_str().unwrap(),
        curve(b).to_str().unwrap(),
        "--frames",
        "7",
        "--json",
        json.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let cli: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(reply["morph"], cli);

    // Frames and downloads of the job.
    let frame = reply["urls"]["frame"].as_str().unwrap().replace("{k}", "3");
    let (status, png) = server.get(&frame);
    assert_eq!(status, 200);
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let head = server.head("GET", &format!("{frame}?download=1"), None);
    let (_, head, _) = raw_request(server.port, head.as_bytes(), b"");
    assert!(
        head.contains("attachment; filename=\"immerse-frame-0003.png\""),
        "{head}"
    );
    let (status, lottie) = server.get(reply["urls"]["lottie"].as_str().unwrap());
    assert_eq!(status, 200);
    let lottie: serde_json::Value = serde_json::from_slice(&lottie).unwrap();
    assert_eq!(lottie["w"], 200);
    assert_eq!(lottie["layers"].as_array().unwrap().len(), 1);
    let (status, gif) = server.get(reply["urls"]["gif"].as_str().unwrap());
    assert_eq!(status, 200);
    assert_eq!(&gif[..6], b"GIF89a");
    let (status, progress) = server.get(reply["urls"]["progress"].as_str().unwrap());
    assert_eq!(status, 200);
    assert_eq!(
        serde_json::from_slice::<serde_json::Value>(&progress).unwrap(),
        serde_json::json!({"gif": null})
    );
    let (status, svg) = server.get(reply["urls"]["svg"].as_str().unwrap());
    assert_eq!(status, 200);
    let svg = String::from_utf8_lossy(&svg).to_string();
    assert!(svg.starts_with("<svg") || svg.starts_with("<?xml"));
    let (status, morph) = server.get(reply["urls"]["json"].as_str().unwrap());
    assert_eq!(status, 200);
    assert_eq!(
        serde_json::from_slice::<serde_json::Value>(&morph).unwrap(),
        cli
    );
    let (status, _) = server.get(&reply["urls"]["frame"].as_str().unwrap().replace("{k}", "7"));
    assert_eq!(status, 404);
    // Ids are not counted: neither a small number nor a near miss is a job.
    assert_eq!(server.get("/api/jobs/1/morph.gif").0, 404);
    let mut near = id.to_string();
    near.replace_range(31.., if id.ends_with('0') { "1" } else { "0" });
    assert_eq!(server.get(&format!("/api/jobs/{near}/morph.gif")).0, 404);
    assert_eq!(server.get("/etc/passwd").0, 404);

    // Three curves: a chain through the middle one.
    let (status, reply) = server.post(
        "/api/morph",
        &serde_json::json!({"curves": [points_of(a), points_of(b), points_of(a)], "frames": 9}),
    );
    assert_eq!(status, 200, "{reply}");
    let frames = reply["morph"]["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 9);
    // Every frame has one vertex count, and vertex i runs on across the
    // middle key: the frames are continuous there (no jump of a vertex
    // much larger than between other frames).
    let n = frames[0]["points"].as_array().unwrap().len();
    assert!(
        frames
            .iter()
            .all(|f| f["points"].as_array().unwrap().len() == n)
    );
    let step = |f: &serde_json::Value, g: &serde_json::Value| {
        let (p, q) = (
            f["points"].as_array().unwrap(),
            g["points"].as_array().unwrap(),
        );
        p.iter()
            .zip(q)
            .map(|(a, b)| {
                let d = |k: usize| a[k].as_f64().unwrap() - b[k].as_f64().unwrap();
                d(0).hypot(d(1))
            })
            .fold(0.0_f64, f64::max)
    };
    let steps: Vec<f64> = frames.windows(2).map(|w| step(&w[0], &w[1])).collect();
    let mean = steps.iter().sum::<f64>() / steps.len() as f64;
    assert!(steps.iter().all(|&s| s < 3.0 * mean), "{steps:?}");
    // It ends on the first curve, vertex for vertex up to a relabelling.
    let sorted = |v: &serde_json::Value| {
        let mut p: Vec<String> = v
            .as_array()
            .unwrap()
            .iter()
            .map(|q| q.to_string())
            .collect();
        p.sort();
        p
    };
    assert_eq!(sorted(&frames[0]["points"]), sorted(&frames[8]["points"]));
    let (status, svg) = server.get(reply["urls"]["svg"].as_str().unwrap());
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&svg));

    // Checking curves: drawn points, and the text of an SVG file.
    let (status, check) = server.post("/api/check", &serde_json::json!({"points": points_of(a)}));
    assert_eq!(status, 200, "{check}");
    assert_eq!(check["self_overlapping"], true);
    assert_eq!(check["triangles"].as_array().unwrap().len(), 28);
    let svg = std::fs::read_to_string(curve("figure-eight.svg")).unwrap();
    let (status, check) = server.post(
        "/api/check",
        &serde_json::json!({"data": svg, "format": "svg", "name": "figure-eight.svg"}),
    );
    assert_eq!(status, 200, "{check}");
    assert_eq!(check["self_overlapping"], false);
    assert_eq!(check["turning_number"], 0);
    assert_eq!(check["reason"], "turning number is 0, not 1");
}

#[test]
fn serve_bounds_requests_with_json_errors() {
    let server = start(&[]);
    let [a, b] = pair();
    let port = server.port;

    // 400: bad JSON, bad values, a curve that is not self-overlapping.
    let (status, body) = server.request("POST", "/api/morph", Some(b"{\"curves\": ["));
    assert_eq!(status, 400);
    let v: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert!(error_of(&v).starts_with("bad request JSON: "), "{v}");
    for (field, value, message) in [
        (
            "frames",
            serde_json::json!(241),
            "\"frames\": 241 is not a whole number from 2 to 240",
        ),
        (
            "frames",
            serde_json::json!(2.5),
            "\"frames\": 2.5 is not a whole number from 2 to 240",
        ),
        (
            "size",
            serde_json::json!([600.5, 600]),
            "\"size\": 600.5 is not a whole number from 16 to 2048 pixels a side",
        ),
        (
            "fps",
            serde_json::json!(0),
            "\"fps\": 0 is not a rate from 0.1 to 1000 frames per second",
        ),
        (
            "fps",
            serde_json::json!(1e-300),
            "\"fps\": 1e-300 is not a rate from 0.1 to 1000 frames per second",
        ),
    ] {
        let mut body = serde_json::json!({"curves": [a, b]});
        body[field] = value;
        let (status, v) = server.post("/api/morph", &body);
        assert_eq!(status, 400, "{v}");
        assert_eq!(error_of(&v), message);
    }
    let (status, v) = server.post("/api/morph", &serde_json::json!({"curves": [a]}));
    assert_eq!(status, 400);
    assert_eq!(
        error_of(&v),
        "\"curves\" holds 1 curve(s); give from 2 to 8"
    );
    let (status, v) = server.post(
        "/api/morph",
        &serde_json::json!({"curves": [a, b], "path": "wobbly"}),
    );
    assert_eq!(status, 400);
    assert!(
        error_of(&v).starts_with("\"path\": 'wobbly' is not one of rigid, hybrid, straight"),
        "{v}"
    );
    let (status, v) = server.post(
        "/api/morph",
        &serde_json::json!({"curves": [a, b], "colour": 1}),
    );
    assert_eq!(status, 400);
    assert!(error_of(&v).contains("unknown field `colour`"), "{v}");
    let eight = points_of("turning-one-not-self-overlapping-n9.json");
    let (status, v) = server.post("/api/morph", &serde_json::json!({"curves": [a, eight]}));
    assert_eq!(status, 400);
    assert!(
        error_of(&v).starts_with("curve 2 is not self-overlapping: "),
        "{v}"
    );
    let (status, v) = server.post(
        "/api/check",
        &serde_json::json!({"points": [[0, 0], [1, 1]]}),
    );
    assert_eq!(status, 400);
    assert!(error_of(&v).contains("at least 3"), "{v}");
    // A file's error names the file once.
    let (status, v) = server.post(
        "/api/check",
        &serde_json::json!({"data": "<svg", "format": "svg", "name": "bad.svg"}),
    );
    assert_eq!(status, 400);
    assert!(error_of(&v).starts_with("bad.svg: "), "{v}");
    assert_eq!(error_of(&v).matches("bad.svg").count(), 1, "{v}");

    // A GIF plays at most 50 fps: refused as the command line refuses it.
    let (status, reply) = server.post(
        "/api/morph",
        &serde_json::json!({"curves": [a, b], "frames": 3, "fps": 60}),
    );
    assert_eq!(status, 200, "{reply}");
    let (status, body) = server.get(reply["urls"]["gif"].as_str().unwrap());
    assert_eq!(status, 400);
    let v: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert!(
        error_of(&v).starts_with("\"fps\": a gif plays at most 50 frames per second"),
        "{v}"
    );
    assert_eq!(server.get(reply["urls"]["svg"].as_str().unwrap()).0, 200);

    // 413: too many points (as sent, and read from a file's text), too
    // large a body (announced, and streamed in chunks).
    let many: Vec<[f64; 2]> = (0..5001)
        .map(|i| {
            let t = i as f64 / 5001.0 * std::f64::consts::TAU;
            [t.cos(), t.sin()]
        })
        .collect();
    let (status, v) = server.post("/api/morph", &serde_json::json!({"curves": [a, many]}));
    assert_eq!(status, 413);
    assert!(
        error_of(&v).starts_with("curve 2 has 5001 points; the playground accepts at most 5000"),
        "{v}"
    );
    let text: String = (0..200_001).map(|i| format!("{i} {}\n", i % 7)).collect();
    let (status, v) = server.post(
        "/api/check",
        &serde_json::json!({"data": text, "format": "txt", "name": "many.txt"}),
    );
    assert_eq!(status, 413, "{v}");
    assert!(
        error_of(&v).starts_with("many.txt: too large (200001 points"),
        "{v}"
    );
    let big = vec![b' '; 3 << 20];
    let (status, body) = server.request("POST", "/api/morph", Some(&big));
    assert_eq!(status, 413);
    let v: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(
        error_of(&v),
        "the request body is 3145728 bytes; the limit is 2097152 bytes (2 MiB)"
    );
    let chunk = vec![b' '; 1 << 20];
    let mut chunked = Vec::new();
    for _ in 0..3 {
        chunked.extend_from_slice(format!("{:x}\r\n", chunk.len()).as_bytes());
        chunked.extend_from_slice(&chunk);
        chunked.extend_from_slice(b"\r\n");
    }
    chunked.extend_from_slice(b"0\r\n\r\n");
    let head = format!(
        "POST /api/check HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\nContent-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n"
    );
    let (status, _, body) = raw_request(port, head.as_bytes(), &chunked);
    assert_eq!(status, 413, "{}", String::from_utf8_lossy(&body));
    let v: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(
        error_of(&v),
        "the request body is more than 2097152 bytes; the limit is 2097152 bytes (2 MiB)"
    );

    // 415 (also for a type that only starts like JSON) and 405.
    for media in ["text/plain", "application/jsonx"] {
        let head = format!(
            "POST /api/morph HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\nContent-Type: {media}\r\nContent-Length: 2\r\n\r\n"
        );
        assert_eq!(raw_request(port, head.as_bytes(), b"{}").0, 415, "{media}");
    }
    let (status, body) = server.get("/api/morph");
    assert_eq!(status, 405);
    let v: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(error_of(&v), "/api/morph takes POST, not GET");

    // 403: another Host (DNS rebinding) on every route; a POST from a
    // page of another site, by its Origin or its Sec-Fetch-Site; 400
    // without a Host.
    for path in ["/", "/api/limits"] {
        let head = format!(
            "GET {path} HTTP/1.1\r\nHost: evil.example:{port}\r\nConnection: close\r\n\r\n"
        );
        assert_eq!(raw_request(port, head.as_bytes(), b"").0, 403, "{path}");
    }
    let body = serde_json::json!({"points": a}).to_string();
    for (header, expect) in [
        ("Origin: http://evil.example".to_string(), 403),
        (
            format!("Origin: http://localhost:{}", port.wrapping_add(1)),
            403,
        ),
        ("Sec-Fetch-Site: cross-site".to_string(), 403),
        ("Sec-Fetch-Site: same-site".to_string(), 403),
        (format!("Origin: http://127.0.0.1:{port}"), 200),
        (
            format!("Origin: http://localhost:{port}\r\nSec-Fetch-Site: same-origin"),
            200,
        ),
    ] {
        let head = format!(
            "POST /api/check HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\n{header}\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
            body.len()
        );
        let (status, _, reply) = raw_request(port, head.as_bytes(), body.as_bytes());
        assert_eq!(
            status,
            expect,
            "{header}: {}",
            String::from_utf8_lossy(&reply)
        );
    }
    let (status, _, _) = raw_request(port, b"GET / HTTP/1.0\r\n\r\n", b"");
    assert_eq!(status, 400);

    // The head is bounded: 431 past --max-header-bytes; a request line of
    // another HTTP version is answered (400), not left hanging.
    let head = format!(
        "GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nX-Filler: {}\r\n\r\n",
        "a".repeat(20_000)
    );
    assert_eq!(raw_request(port, head.as_bytes(), b"").0, 431);
    let head = format!("GET / HTTP/2.0\r\nHost: 127.0.0.1:{port}\r\n\r\n");
    assert_eq!(raw_request(port, head.as_bytes(), b"").0, 400);
}

/// One job slot: a request waits for it, in order, until its time is up
/// (503); a body that does not come in time gets 408; other requests are
/// answered meanwhile. No test hook: a POST whose body has not arrived
/// holds the slot.
#[test]
fn serve_waits_for_job_slots_within_the_time_limits() {
    let server = start(&[
        "--max-jobs",
        "1",
        "--job-timeout",
        "2",
        "--body-timeout",
        "3",
    ]);
    let port = server.port;
    let body = serde_json::json!({"points": pair()[0]}).to_string();
    let head = server.head("POST", "/api/check", Some(body.len()));
    // A takes the slot and sends half its body.
    let half = body.len() / 2;
    let mut a = send(port, &head, &body.as_bytes()[..half]);
    std::thread::sleep(Duration::from_millis(300));
    // B waits for the slot, then gives up after the job time limit.
    let t = Instant::now();
    let (status, v) = server.post("/api/check", &serde_json::json!({"points": pair()[1]}));
    let waited = t.elapsed();
    assert_eq!(status, 503, "{v}");
    assert_eq!(
        error_of(&v),
        "all 1 job slot(s) stayed busy for 2 s, this server's job time limit; try again when a job has finished"
    );
    assert!(
        waited >= Duration::from_millis(1900) && waited < Duration::from_secs(4),
        "{waited:?}"
    );
    // Meanwhile everything else is answered at once.
    let t = Instant::now();
    assert_eq!(server.get("/api/limits").0, 200);
    assert_eq!(server.get("/").0, 200);
    assert!(t.elapsed() < Duration::from_secs(1), "{:?}", t.elapsed());
    // A's body arrives: A is answered.
    a.write_all(&body.as_bytes()[half..]).unwrap();
    let (status, _, reply) = read_response(&mut a);
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&reply));
    // A body that never completes: 408 after --body-timeout.
    let mut c = send(port, &head, &body.as_bytes()[..half]);
    let t = Instant::now();
    let (status, _, reply) = read_response(&mut c);
    assert_eq!(status, 408, "{}", String::from_utf8_lossy(&reply));
    let v: serde_json::Value = serde_json::from_slice(&reply).unwrap();
    assert_eq!(
        error_of(&v),
        "the request body did not arrive within 3 s, this server's limit"
    );
    assert!(t.elapsed() < Duration::from_secs(5), "{:?}", t.elapsed());
    // And the slot is free again.
    assert_eq!(
        server
            .post("/api/check", &serde_json::json!({"points": pair()[1]}))
            .0,
        200
    );
}

/// A GIF past the job time limit is stopped (503) and one whose client
/// leaves is stopped too: in both cases its slot is free within moments,
/// where the whole GIF would take half a minute.
#[test]
fn serve_stops_renders_past_their_time_or_without_a_client() {
    let server = start(&["--max-jobs", "1", "--job-timeout", "2"]);
    let job = slow_gif_job(&server);
    let gif = job["urls"]["gif"].as_str().unwrap();
    let t = Instant::now();
    let (status, body) = server.get(gif);
    assert_eq!(status, 503, "{}", String::from_utf8_lossy(&body));
    let v: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert!(
        error_of(&v).starts_with("the job took longer than 2 s, this server's limit"),
        "{v}"
    );
    assert!(t.elapsed() < Duration::from_secs(4), "{:?}", t.elapsed());
    // The stopped render gives its slot back within moments (it notices
    // the stop between frames): a check is answered within 5 s of the 503
    // (20 s in the debug profile, where a frame takes several times as
    // long and the whole GIF minutes).
    let moments = Duration::from_secs(if cfg!(debug_assertions) { 20 } else { 5 });
    let check = serde_json::json!({"points": pair()[0]});
    let t = Instant::now();
    loop {
        let status = server.post("/api/check", &check).0;
        if status == 200 {
            break;
        }
        assert_eq!(status, 503, "a check while the slot is taken");
        assert!(
            t.elapsed() < moments,
            "the stopped GIF held its slot for {:?}",
            t.elapsed()
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    drop(server);

    let server = start(&["--max-jobs", "1", "--job-timeout", "120"]);
    let job = slow_gif_job(&server);
    let gif = job["urls"]["gif"].as_str().unwrap();
    let client = send(server.port, &server.head("GET", gif, None), b"");
    // The render is under way: its progress shows.
    let t = Instant::now();
    loop {
        let (_, p) = server.get(job["urls"]["progress"].as_str().unwrap());
        let p: serde_json::Value = serde_json::from_slice(&p).unwrap();
        if p["gif"]["total"] == 240 {
            break;
        }
        assert!(t.elapsed() < Duration::from_secs(10), "no progress: {p}");
        std::thread::sleep(Duration::from_millis(50));
    }
    drop(client);
    let t = Instant::now();
    assert_eq!(server.post("/api/check", &check).0, 200);
    assert!(
        t.elapsed() < moments,
        "the abandoned GIF held its slot for {:?}",
        t.elapsed()
    );
}

/// Ctrl-C stops accepting at once and lets the request in flight finish
/// (the drain), then the server exits 0.
#[cfg(unix)]
#[test]
fn serve_drains_on_ctrl_c() {
    let mut server = start(&[]);
    let port = server.port;
    let body = serde_json::json!({"points": pair()[0]}).to_string();
    let head = server.head("POST", "/api/check", Some(body.len()));
    let half = body.len() / 2;
    let mut a = send(port, &head, &body.as_bytes()[..half]);
    // A connection without a request, as a browser keeps one spare.
    let _spare = TcpStream::connect(("127.0.0.1", port)).unwrap();
    std::thread::sleep(Duration::from_millis(300));
    let pid = server.child.id().to_string();
    assert!(
        Command::new("kill")
            .args(["-INT", &pid])
            .status()
            .unwrap()
            .success()
    );
    // New connections are refused once the listener is closed.
    let t = Instant::now();
    while TcpStream::connect(("127.0.0.1", port)).is_ok() {
        assert!(
            t.elapsed() < Duration::from_secs(5),
            "still accepting after Ctrl-C"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(server.alive(), "exited with a request in flight");
    a.write_all(&body.as_bytes()[half..]).unwrap();
    let (status, _, reply) = read_response(&mut a);
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&reply));
    let t = Instant::now();
    loop {
        if let Some(status) = server.child.try_wait().unwrap() {
            assert_eq!(status.code(), Some(0), "exit status after Ctrl-C: {status}");
            break;
        }
        // Well within the drain's 5 s: the spare connection does not hold it.
        assert!(
            t.elapsed() < Duration::from_secs(3),
            "serve did not stop after the drain"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// The page takes its option lists from `GET /api/options`, which offers
/// exactly the paths and correspondence rules the library offers in this
/// build and the command line's values, and the server morphs with each
/// of them; an experimental one is refused with 400 naming the offered.
#[test]
fn the_options_offer_every_path_and_rule_and_the_server_takes_them() {
    let server = start(&[]);
    let (status, options) = server.get("/api/options");
    assert_eq!(status, 200);
    let options: serde_json::Value = serde_json::from_slice(&options).unwrap();
    let names = |key: &str| -> Vec<String> {
        options[key]["values"]
            .as_array()
            .unwrap_or_else(|| panic!("no {key}: {options}"))
            .iter()
            .map(|v| v["name"].as_str().unwrap().to_string())
            .collect()
    };
    let sorted = |mut v: Vec<String>| {
        v.sort();
        v
    };
    let paths = names("path");
    let mut want: Vec<String> = immerse::morph::ThirdVertexPath::offered()
        .iter()
        .map(|p| p.as_str().to_string())
        .collect();
    want.sort();
    assert_eq!(sorted(paths.clone()), want);
    let rules = names("correspondence");
    let mut want: Vec<String> = immerse::morph::Correspondence::offered()
        .iter()
        .map(|r| r.as_str().to_string())
        .collect();
    want.sort();
    assert_eq!(sorted(rules.clone()), want);
    assert_eq!(options["fps"]["min"], 0.1);
    assert_eq!(options["fps"]["max"], 1000.0);
    assert_eq!(options["fps"]["gif_max"], 50.0);
    assert_eq!(options["frames"]["max"], 240);
    assert!(names("easing").contains(&"cubic-bezier".to_string()));
    // The page has no list of its own.
    let page = String::from_utf8(server.get("/").1).unwrap();
    assert!(
        !page.contains("<option>rotate-slide"),
        "the page repeats a list"
    );
    let curves = [
        points_of("letter-E.json"),
        points_of("spiral-strip-400deg-n30.json"),
    ];
    let mut tried = Vec::new();
    for key in [
        "path",
        "correspondence",
        "intermediate",
        "quality",
        "counts",
        "easing",
        "loop",
    ] {
        for v in names(key) {
            let value = if v == "cubic-bezier" {
                "cubic-bezier(0.2,0.8,0.6,1.1)".to_string()
            } else {
                v.clone()
            };
            let body = serde_json::json!({"curves": curves, "frames": 4, key: value});
            let (status, reply) = server.post("/api/morph", &body);
            assert_eq!(status, 200, "{key} {v}: {reply}");
            tried.push(format!("{key}={v}"));
        }
    }
    assert!(tried.len() >= 16, "{tried:?}");
    if !cfg!(feature = "experimental") {
        for (key, value) in [("path", "polar"), ("correspondence", "identity")] {
            let body = serde_json::json!({"curves": curves, "frames": 4, key: value});
            let (status, reply) = server.post("/api/morph", &body);
            assert_eq!(status, 400, "{key} {value}: {reply}");
            assert!(reply.to_string().contains("experimental"), "{reply}");
        }
    }
}

/// The shapes of a drawing as `POST /api/check` reads them, in the
/// library's drawing JSON.
fn checked_drawing(server: &Server, file: &str) -> serde_json::Value {
    let text = std::fs::read_to_string(curve(&format!("drawings/{file}"))).unwrap();
    let (status, k) = server.post(
        "/api/check",
        &serde_json::json!({"data": text, "format": "svg", "name": file}),
    );
    assert_eq!(status, 200, "{k}");
    assert_eq!(k["kind"], "drawing");
    let shapes: Vec<serde_json::Value> = k["shapes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            let mut s = s.clone();
            let m = s.as_object_mut().unwrap();
            for extra in ["self_overlapping", "reason", "triangles"] {
                m.remove(extra);
            }
            s
        })
        .collect();
    serde_json::json!({"name": k["name"], "shapes": shapes})
}

/// Drawings through the server: read, matched and morphed as `immerse
/// morph` does them, their files served, and their limits kept.
#[test]
fn serve_morphs_drawings_like_the_cli_within_its_limits() {
    let server = start(&[]);
    let a = checked_drawing(&server, "creature-a.svg");
    let b = checked_drawing(&server, "creature-b.svg");
    assert_eq!(a["shapes"].as_array().unwrap().len(), 4);
    let dir = tempfile::tempdir().unwrap();
    let (pa, pb) = (dir.path().join("a.json"), dir.path().join("b.json"));
    std::fs::write(&pa, a.to_string()).unwrap();
    std::fs::write(&pb, b.to_string()).unwrap();
    for mode in ["id", "order", "auto"] {
        let (status, reply) = server.post(
            "/api/morph",
            &serde_json::json!({"drawings": [a, b], "match": mode, "frames": 5}),
        );
        assert_eq!(status, 200, "{mode}: {reply}");
        assert_eq!(reply["kind"], "drawings");
        assert!(
            reply["matching"]
                .as_str()
                .unwrap()
                .starts_with(&format!("matching ({mode}): ")),
            "{reply}"
        );
        // The frames and matching are the command line's on the same
        // drawings (notices aside: the files are named differently).
        let json = dir.path().join(format!("{mode}.json"));
        let (json_s, pa_s, pb_s) = (
            json.to_str().unwrap(),
            pa.to_str().unwrap(),
            pb.to_str().unwrap(),
        );
        let out = immerse(&[
            "morph", "--match", mode, "--frames", "5", "--quiet", "--json", json_s, pa_s, pb_s,
        ]);
        assert!(out.status.success(), "{}", stderr(&out));
        let cli: serde_json::Value =
            serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
        assert_eq!(reply["morph"]["matching"], cli["matching"], "{mode}");
        assert_eq!(reply["morph"]["frames"], cli["frames"], "{mode}");
        for file in ["morph.svg", "morph.lottie.json", "morph.gif", "frame/4.png"] {
            let url = reply["urls"]["json"]
                .as_str()
                .unwrap()
                .replace("morph.json", file);
            let (status, body) = server.get(&url);
            assert_eq!(status, 200, "{file}");
            assert!(body.len() > 100, "{file}");
        }
    }
    // Bad drawing requests: each a 4xx with a message naming what to do.
    let hole = "<svg xmlns=\"http://www.w3.org/2000/svg\"><path fill-rule=\"evenodd\" d=\"M0 0 L100 0 L100 100 L0 100 Z M20 20 L80 20 L80 80 L20 80 Z\"/></svg>";
    let (status, reply) = server.post(
        "/api/check",
        &serde_json::json!({"data": hole, "format": "svg", "name": "ring.svg"}),
    );
    assert_eq!(status, 400);
    assert!(error_of(&reply).contains("is a hole in"), "{reply}");
    let square =
        |x: f64| serde_json::json!({"points": [[x, 0], [x + 1.0, 0], [x + 1.0, 1], [x, 1]]});
    let many = serde_json::json!({"shapes": (0..65).map(|k| square(2.0 * f64::from(k))).collect::<Vec<_>>()});
    let eight = serde_json::json!({"shapes": [{"points": points_of("figure-eight-n64.json")}]});
    for (body, want_status, want) in [
        (
            serde_json::json!({"drawings": [a, b, a]}),
            400,
            "give exactly 2",
        ),
        (
            serde_json::json!({"drawings": [a, b], "curves": pair()}),
            400,
            "not both",
        ),
        (
            serde_json::json!({"curves": pair(), "match": "auto"}),
            400,
            "\"match\" pairs the shapes",
        ),
        (
            serde_json::json!({"drawings": [a, b], "match": "size"}),
            400,
            "'size' is not one of id, order, auto",
        ),
        (
            serde_json::json!({"drawings": [a, many]}),
            413,
            "at most 64 per drawing",
        ),
        (
            serde_json::json!({"drawings": [a, eight]}),
            400,
            "is not self-overlapping",
        ),
        (
            serde_json::json!({"drawings": [a, {"shapes": 3}]}),
            400,
            "\"shapes\" is not an array",
        ),
    ] {
        let (status, reply) = server.post("/api/morph", &body);
        assert_eq!(status, want_status, "{reply}");
        assert!(error_of(&reply).contains(want), "{want}: {reply}");
    }
    let (_, options) = server.get("/api/options");
    let options: serde_json::Value = serde_json::from_slice(&options).unwrap();
    assert_eq!(options["max_shapes"], 64);
    assert_eq!(options["match"]["default"], "auto");
}

#[test]
fn morph_writes_lottie() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (
        curve("spiral-strip-400deg-n30.json"),
        curve("curl-strip-n10.json"),
    );
    for (args, file) in [
        (vec!["--format", "lottie"], "m.json"),
        (vec![], "m.lottie.json"),
    ] {
        let out_path = dir.path().join(file);
        let mut cmd = vec![
            "morph",
            a.to_str().unwrap(),
            b.to_str().unwrap(),
            "--frames",
            "20",
            "--fps",
            "24",
            "--size",
            "320x240",
            "-o",
            out_path.to_str().unwrap(),
        ];
        cmd.extend(args);
        let out = immerse(&cmd);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&out_path).unwrap()).unwrap();
        assert_eq!(v["fr"], 24.0);
        assert_eq!((v["w"].as_u64(), v["h"].as_u64()), (Some(320), Some(240)));
        assert_eq!(v["op"], 20);
        let layers = v["layers"].as_array().unwrap();
        assert_eq!(layers.len(), 1);
        let curve_group = &layers[0]["shapes"][0]["it"];
        assert_eq!(curve_group[0]["ty"], "sh");
        let fills: Vec<_> = curve_group
            .as_array()
            .unwrap()
            .iter()
            .filter(|i| i["ty"] == "fl")
            .collect();
        assert_eq!(fills.last().unwrap()["r"], 1, "the curve is filled nonzero");
    }
}
