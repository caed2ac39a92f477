//! Shared helpers: fixture paths, labels, and running the real binary.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Paths a morph's summary may name at the default options: the default
/// `rigid`, and the rivals its last leg may take where they travel less
/// (docs/design.md §7b).
pub const LAST_LEG_RIVALS: [&str; 5] = ["rigid", "straight", "polar", "hybrid", "angle"];

/// The project's `curves/` folder.
pub fn curves_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("curves")
}

/// Path of a curve in `curves/`.
pub fn curve(name: &str) -> PathBuf {
    curves_dir().join(name)
}

/// One entry of `curves/MANIFEST.json`.
#[derive(Debug, Clone)]
pub struct Label {
    pub file: String,
    /// `Some(true|false)`, or `None` for "invalid".
    pub self_overlapping: Option<bool>,
    pub simple: Option<bool>,
    pub n_clean: Option<usize>,
    pub turning_number: Option<i64>,
    pub reversed: bool,
}

/// The labels of the reference curves.
pub fn labels() -> Vec<Label> {
    let text = std::fs::read_to_string(curves_dir().join("MANIFEST.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let files = v["files"].as_object().unwrap();
    let mut out: Vec<Label> = files
        .iter()
        .map(|(file, e)| Label {
            file: file.clone(),
            self_overlapping: e["self_overlapping"].as_bool(),
            simple: e["simple"].as_bool(),
            n_clean: e["n_clean"].as_u64().map(|n| n as usize),
            turning_number: e["turning_number"].as_i64(),
            reversed: e["orientation"].as_str() == Some("reversed"),
        })
        .collect();
    out.sort_by(|a, b| a.file.cmp(&b.file));
    out
}

/// Runs the `immerse` binary with `args` in `dir`.
pub fn immerse_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_immerse"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the immerse binary runs")
}

/// Runs the `immerse` binary with `args` in the project folder.
pub fn immerse(args: &[&str]) -> Output {
    immerse_in(Path::new(env!("CARGO_MANIFEST_DIR")), args)
}

/// stderr as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// stdout as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Runs `immerse args` (in `dir`, else the project folder) and asserts the
/// exit code and that stderr is exactly `expected` plus a newline. A bad
/// input (code 2) also leaves stdout empty.
pub fn assert_stderr(dir: Option<&Path>, args: &[&str], code: i32, expected: &str) -> Output {
    let out = match dir {
        Some(d) => immerse_in(d, args),
        None => immerse(args),
    };
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(code), "args {args:?}: stderr {err}");
    assert_eq!(err, format!("{expected}\n"), "args {args:?}");
    if code == 2 {
        assert!(stdout(&out).is_empty(), "no data on stdout for an error");
    }
    out
}

/// `certify_keys` on a morph's keyframes, each segment under its first
/// key's triangulation, with the library's own certificate.
pub fn certify_keyframes(
    keys: &[immerse::morph::Keyframe],
    player: immerse::certify::Player,
) -> immerse::certify::KeysReport {
    let list: Vec<immerse::certify::Key<'_>> = keys
        .iter()
        .map(|k| immerse::certify::Key {
            t: k.t,
            points: &k.points,
            triangles: &k.triangles,
        })
        .collect();
    immerse::certify::certify_keys(&list, player).unwrap()
}
