//! A running `immerse serve --port 0` and a minimal HTTP/1.1 client on
//! loopback, for the tests of the server (tests/integration/web.rs) and
//! its hostile-traffic test (tests/hostile.rs).

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

/// A running `immerse serve --port 0`, killed when dropped.
pub struct Server {
    /// The server's process.
    pub child: Child,
    /// The loopback port it printed.
    pub port: u16,
}

impl Server {
    /// Starts the binary at `bin` with `extra` arguments; stderr is kept
    /// in a pipe only when `stderr` is set (else discarded).
    pub fn start_with(bin: &str, extra: &[&str], stderr: bool) -> Server {
        let mut command = Command::new(bin);
        command.args(["serve", "--port", "0"]).args(extra);
        Server::spawn(command, stderr)
    }

    /// Starts the binary at `bin` with at most `nofile` open files (the
    /// shell's `ulimit -n`; the server replaces the shell).
    pub fn start_limited(bin: &str, nofile: u32, extra: &[&str]) -> Server {
        let mut command = Command::new("sh");
        command
            .args([
                "-c",
                &format!("ulimit -n {nofile} && exec \"$@\""),
                "sh",
                bin,
            ])
            .args(["serve", "--port", "0"])
            .args(extra);
        Server::spawn(command, false)
    }

    fn spawn(mut command: Command, stderr: bool) -> Server {
        let mut child = command
            .stdout(Stdio::piped())
            .stderr(if stderr {
                Stdio::piped()
            } else {
                Stdio::null()
            })
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

    /// The request head of `method path`, with this server's Host,
    /// `Connection: close` and, for a body, its JSON type and length.
    pub fn head(&self, method: &str, path: &str, body_len: Option<usize>) -> String {
        let mut head = format!(
            "{method} {path} HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nConnection: close\r\n",
            self.port
        );
        if let Some(n) = body_len {
            head.push_str(&format!(
                "Content-Type: application/json\r\nContent-Length: {n}\r\n"
            ));
        }
        head.push_str("\r\n");
        head
    }

    /// Sends one request; returns (status, body).
    pub fn request(&self, method: &str, path: &str, body: Option<&[u8]>) -> (u16, Vec<u8>) {
        let head = self.head(method, path, body.map(<[u8]>::len));
        let (status, _, body) = raw_request(self.port, head.as_bytes(), body.unwrap_or_default());
        (status, body)
    }

    /// `GET path`; returns (status, body).
    pub fn get(&self, path: &str) -> (u16, Vec<u8>) {
        self.request("GET", path, None)
    }

    /// `POST path` with a JSON body; returns (status, the answer's JSON).
    /// Panics when the answer is not JSON.
    pub fn post(&self, path: &str, json: &serde_json::Value) -> (u16, serde_json::Value) {
        let (status, body) = self.request("POST", path, Some(json.to_string().as_bytes()));
        let value = serde_json::from_slice(&body).unwrap_or_else(|e| {
            panic!("{path}: not JSON ({e}): {}", String::from_utf8_lossy(&body))
        });
        (status, value)
    }

    /// The server's resident memory in bytes (Linux: /proc), or None once
    /// it has exited.
    pub fn rss(&self) -> Option<u64> {
        rss_of(self.child.id())
    }

    /// True while the process runs.
    pub fn alive(&mut self) -> bool {
        matches!(self.child.try_wait(), Ok(None))
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The resident memory in bytes of process `pid` (Linux: /proc), or None
/// once it has exited.
pub fn rss_of(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let kb: u64 = status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))?
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .ok()?;
    Some(kb * 1024)
}

/// Sends `head` and `body` on a new connection and reads the whole
/// answer: (status, head, body), with a chunked body decoded.
pub fn raw_request(port: u16, head: &[u8], body: &[u8]) -> (u16, String, Vec<u8>) {
    let mut s = TcpStream::connect(("127.0.0.1", port)).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(120))).unwrap();
    s.write_all(head).unwrap();
    // The server may answer (413) and close before reading a large body.
    let _ = s.write_all(body);
    read_response(&mut s)
}

/// Reads an answer to its end (the connection closes after it).
pub fn read_response(s: &mut TcpStream) -> (u16, String, Vec<u8>) {
    let mut out = Vec::new();
    let _ = s.read_to_end(&mut out);
    parse_response(&out)
}

/// Splits a whole answer into (status, head, body).
pub fn parse_response(out: &[u8]) -> (u16, String, Vec<u8>) {
    let text_end = out
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .unwrap_or_else(|| panic!("no HTTP response: {:?}", String::from_utf8_lossy(out)));
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
    (status, head, body)
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

/// The `"error"` of a JSON error answer.
pub fn error_of(v: &serde_json::Value) -> &str {
    v["error"]
        .as_str()
        .unwrap_or_else(|| panic!("no error field: {v}"))
}
