//! `immerse serve` through the real binary and a minimal HTTP client on
//! loopback (no node, no browser: those are in tests/browser/), and
//! `immerse morph --format lottie`.

use crate::util::{curve, immerse, stderr};
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// A running `immerse serve --port 0`, killed when dropped.
struct Server {
    child: Child,
    port: u16,
}

impl Server {
    fn start(extra: &[&str]) -> Server {
        let mut child = Command::new(env!("CARGO_BIN_EXE_immerse"))
            .args(["serve", "--port", "0"])
            .args(extra)
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("immerse serve starts");
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap())
            .read_line(&mut line)
            .unwrap();
        let port = line
            .trim()
            .strip_prefix("http://127.0.0.1:")
            .and_then(|r| r.strip_suffix('/'))
            .and_then(|p| p.parse().ok())
            .unwrap_or_else(|| panic!("no URL on stdout: {line:?}"));
        Server { child, port }
    }

    /// Sends one request; returns (status, body).
    fn request(&self, method: &str, path: &str, body: Option<&[u8]>) -> (u16, Vec<u8>) {
        let mut head = format!(
            "{method} {path} HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nConnection: close\r\n",
            self.port
        );
        if let Some(b) = body {
            head.push_str(&format!(
                "Content-Type: application/json\r\nContent-Length: {}\r\n",
                b.len()
            ));
        }
        head.push_str("\r\n");
        raw_request(self.port, head.as_bytes(), body.unwrap_or_default())
    }

    fn get(&self, path: &str) -> (u16, Vec<u8>) {
        self.request("GET", path, None)
    }

    fn post(&self, path: &str, json: &serde_json::Value) -> (u16, serde_json::Value) {
        let (status, body) = self.request("POST", path, Some(json.to_string().as_bytes()));
        let value = serde_json::from_slice(&body).unwrap_or_else(|e| {
            panic!("{path}: not JSON ({e}): {}", String::from_utf8_lossy(&body))
        });
        (status, value)
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn raw_request(port: u16, head: &[u8], body: &[u8]) -> (u16, Vec<u8>) {
    let mut s = TcpStream::connect(("127.0.0.1", port)).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
    s.write_all(head).unwrap();
    // The server may answer (413) and close before reading a large body.
    let _ = s.write_all(body);
    let mut out = Vec::new();
    let _ = s.read_to_end(&mut out);
    let text_end = out
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .unwrap_or_else(|| panic!("no HTTP response: {:?}", String::from_utf8_lossy(&out)));
    let head = String::from_utf8_lossy(&out[..text_end]).to_string();
    let status = head
        .split(' ')
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or_else(|| panic!("bad status line: {head}"));
    let mut body = out[text_end + 4..].to_vec();
    if head
        .to_ascii_lowercase()
        .contains("transfer-encoding: chunked")
    {
        body = dechunk(&body);
    }
    (status, body)
}

fn dechunk(mut data: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    loop {
        let Some(eol) = data.windows(2).position(|w| w == b"\r\n") else {
            return out;
        };
        let size =
            usize::from_str_radix(String::from_utf8_lossy(&data[..eol]).trim(), 16).unwrap_or(0);
        if size == 0 {
            return out;
        }
        out.extend_from_slice(&data[eol + 2..eol + 2 + size]);
        data = &data[eol + 4 + size..];
    }
}

/// The points of a curve file of `curves/` (JSON files only).
fn points_of(name: &str) -> serde_json::Value {
    let text = std::fs::read_to_string(curve(name)).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v.get("points").cloned().unwrap_or(v)
}

fn error_of(v: &serde_json::Value) -> &str {
    v["error"]
        .as_str()
        .unwrap_or_else(|| panic!("no error field: {v}"))
}

#[test]
fn serve_morphs_like_the_cli_and_serves_the_page() {
    let server = Server::start(&[]);
    let (status, page) = server.get("/");
    assert_eq!(status, 200);
    assert!(String::from_utf8_lossy(&page).contains("immerse playground"));
    let (status, limits) = server.get("/api/limits");
    assert_eq!(status, 200);
    let limits: serde_json::Value = serde_json::from_slice(&limits).unwrap();
    assert_eq!(limits["max_points"], 5000);
    assert_eq!(limits["max_frames"], 240);
    let (status, refs) = server.get("/api/curves");
    assert_eq!(status, 200);
    let refs: serde_json::Value = serde_json::from_slice(&refs).unwrap();
    assert!(refs["curves"].as_array().unwrap().len() >= 8);

    let (a, b) = ("spiral-strip-400deg-n30.json", "curl-strip-n10.json");
    let (status, reply) = server.post(
        "/api/morph",
        &serde_json::json!({"curves": [points_of(a), points_of(b)], "frames": 7, "size": [200, 150]}),
    );
    assert_eq!(status, 200, "{reply}");
    assert_eq!(reply["frames"], 7);
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
    let (status, lottie) = server.get(reply["urls"]["lottie"].as_str().unwrap());
    assert_eq!(status, 200);
    let lottie: serde_json::Value = serde_json::from_slice(&lottie).unwrap();
    assert_eq!(lottie["w"], 200);
    assert_eq!(lottie["layers"].as_array().unwrap().len(), 1);
    let (status, gif) = server.get(reply["urls"]["gif"].as_str().unwrap());
    assert_eq!(status, 200);
    assert_eq!(&gif[..6], b"GIF89a");
    let (status, svg) = server.get(reply["urls"]["svg"].as_str().unwrap());
    assert_eq!(status, 200);
    assert!(
        String::from_utf8_lossy(&svg).starts_with("<svg")
            || String::from_utf8_lossy(&svg).starts_with("<?xml")
    );
    let (status, morph) = server.get(reply["urls"]["json"].as_str().unwrap());
    assert_eq!(status, 200);
    assert_eq!(
        serde_json::from_slice::<serde_json::Value>(&morph).unwrap(),
        cli
    );
    let (status, _) = server.get(&reply["urls"]["frame"].as_str().unwrap().replace("{k}", "7"));
    assert_eq!(status, 404);
    assert_eq!(server.get("/api/jobs/999/morph.gif").0, 404);
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
    let server = Server::start(&["--max-jobs", "1", "--job-delay-ms", "3000"]);
    let a = points_of("spiral-strip-400deg-n30.json");
    let b = points_of("curl-strip-n10.json");
    let ok = serde_json::json!({"curves": [a, b], "frames": 3});

    // 400: bad JSON, bad values, a curve that is not self-overlapping.
    let (status, body) = server.request("POST", "/api/morph", Some(b"{\"curves\": ["));
    assert_eq!(status, 400);
    let v: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert!(error_of(&v).starts_with("bad request JSON: "), "{v}");
    let (status, v) = server.post(
        "/api/morph",
        &serde_json::json!({"curves": [a, b], "frames": 241}),
    );
    assert_eq!(status, 400);
    assert_eq!(error_of(&v), "\"frames\": 241 is not from 2 to 240");
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
        error_of(&v).starts_with("\"path\": 'wobbly' is not one of hybrid, straight"),
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

    // 413: too many points, too large a body.
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
    let big = vec![b' '; 3 << 20];
    let (status, body) = server.request("POST", "/api/morph", Some(&big));
    assert_eq!(status, 413);
    let v: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert!(error_of(&v).contains("the limit is 2097152 bytes"), "{v}");

    // 415 and 405.
    let head = format!(
        "POST /api/morph HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nConnection: close\r\nContent-Type: text/plain\r\nContent-Length: 2\r\n\r\n",
        server.port
    );
    assert_eq!(raw_request(server.port, head.as_bytes(), b"{}").0, 415);
    assert_eq!(server.get("/api/morph").0, 405);
    // 403 for another Host (DNS rebinding).
    let head = "GET / HTTP/1.1\r\nHost: evil.example:80\r\nConnection: close\r\n\r\n";
    assert_eq!(raw_request(server.port, head.as_bytes(), b"").0, 403);

    // 429: one job at a time here; a second is refused while the first
    // runs, and the server keeps answering other requests meanwhile.
    let port = server.port;
    let body = ok.to_string();
    let first = std::thread::spawn(move || {
        let head = format!(
            "POST /api/morph HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
            body.len()
        );
        raw_request(port, head.as_bytes(), body.as_bytes())
    });
    std::thread::sleep(Duration::from_millis(1000));
    let (status, v) = server.post("/api/morph", &ok);
    assert_eq!(status, 429, "{v}");
    assert!(
        error_of(&v).starts_with("1 job(s) are already running"),
        "{v}"
    );
    let t = Instant::now();
    assert_eq!(server.get("/api/limits").0, 200);
    assert!(
        t.elapsed() < Duration::from_millis(1500),
        "a running morph blocked a request"
    );
    let (status, body) = first.join().unwrap();
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
}

#[test]
fn serve_times_out_long_jobs_and_stops_on_ctrl_c() {
    let mut server = Server::start(&["--job-timeout", "1", "--job-delay-ms", "1500"]);
    let a = points_of("spiral-strip-400deg-n30.json");
    let b = points_of("curl-strip-n10.json");
    let (status, v) = server.post(
        "/api/morph",
        &serde_json::json!({"curves": [a, b], "frames": 3}),
    );
    assert_eq!(status, 503);
    assert!(
        error_of(&v).starts_with("the morph took longer than 1 s"),
        "{v}"
    );
    #[cfg(unix)]
    {
        let pid = server.child.id().to_string();
        let killed = Command::new("kill").args(["-INT", &pid]).status().unwrap();
        assert!(killed.success());
        let t = Instant::now();
        loop {
            if let Some(status) = server.child.try_wait().unwrap() {
                assert!(
                    status.success() || status.code() == Some(130),
                    "exit status after Ctrl-C: {status}"
                );
                break;
            }
            assert!(
                t.elapsed() < Duration::from_secs(10),
                "serve did not stop on Ctrl-C"
            );
            std::thread::sleep(Duration::from_millis(50));
        }
        assert!(TcpStream::connect(("127.0.0.1", server.port)).is_err());
    }
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

/// The playground's option lists offer exactly the library's paths and
/// correspondence rules (a rule added to one and not the other is caught
/// here), and the server morphs with each path and rule the page offers.
#[test]
fn the_page_offers_every_path_and_rule_and_the_server_takes_them() {
    let page = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("web/index.html"),
    )
    .unwrap();
    let options = |id: &str| -> Vec<String> {
        let start = page
            .find(&format!("<select id=\"{id}\">"))
            .unwrap_or_else(|| panic!("no select {id}"));
        let end = start + page[start..].find("</select>").unwrap();
        page[start..end]
            .split("<option>")
            .skip(1)
            .map(|o| o.split('<').next().unwrap().to_string())
            .collect()
    };
    // The page's list for `id`, checked against the library's names.
    let offered = |id: &str, names: &[&str]| -> Vec<String> {
        let got = options(id);
        let mut sorted = got.clone();
        sorted.sort();
        let mut want: Vec<String> = names.iter().map(|n| n.to_string()).collect();
        want.sort();
        assert_eq!(sorted, want, "{id}");
        got
    };
    let paths = offered(
        "opt-path",
        &immerse::morph::ThirdVertexPath::ALL.map(|p| p.as_str()),
    );
    let rules = offered(
        "opt-correspondence",
        &immerse::morph::Correspondence::ALL.map(|r| r.as_str()),
    );
    let server = Server::start(&[]);
    let curves = [
        points_of("letter-E.json"),
        points_of("spiral-strip-400deg-n30.json"),
    ];
    for (key, values) in [("path", &paths), ("correspondence", &rules)] {
        for v in values.iter() {
            let body = serde_json::json!({"curves": curves, "frames": 4, key: v});
            let (status, reply) =
                server.request("POST", "/api/morph", Some(body.to_string().as_bytes()));
            assert_eq!(
                status,
                200,
                "{key} {v}: {}",
                String::from_utf8_lossy(&reply)
            );
        }
    }
}
