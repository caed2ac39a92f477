//! The CLI through the real binary: facts on good curves, and every class
//! of bad input gives exit code 2 and one stderr line naming the file.

use crate::util::{curve, immerse, immerse_in, stderr, stdout};
use std::path::Path;

/// Asserts exit code 2, a single stderr line, and that it contains each of
/// `needles`.
fn assert_bad_input(args: &[&str], dir: Option<&Path>, needles: &[&str]) {
    let out = match dir {
        Some(d) => immerse_in(d, args),
        None => immerse(args),
    };
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "args {args:?}: stderr {err}");
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "one line expected: {err}"
    );
    assert!(err.starts_with("immerse: "), "{err}");
    for n in needles {
        assert!(err.contains(n), "{err:?} should contain {n:?}");
    }
    assert!(stdout(&out).is_empty(), "no data on stdout for an error");
}

#[test]
fn check_json_prints_the_facts() {
    let path = curve("spiral-strip-540deg-n120-clockwise.json");
    let out = immerse(&["check", path.to_str().unwrap(), "--json"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["points"], 120);
    assert_eq!(v["turning_number"], -1);
    assert_eq!(v["reversed"], true);
    assert_eq!(v["simple"], false);
}

#[test]
fn check_text_output_names_the_facts() {
    let path = curve("degenerate-repeated-points-square.json");
    let out = immerse(&["check", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(
        text.contains("points:         4 (4 repeated point(s) dropped)"),
        "{text}"
    );
    assert!(text.contains("simple:         yes"), "{text}");
}

#[test]
fn too_few_points() {
    let p = curve("degenerate-two-points.json");
    assert_bad_input(
        &["check", p.to_str().unwrap()],
        None,
        &[
            "degenerate-two-points.json",
            "only 2 distinct point(s)",
            "at least 3",
        ],
    );
}

#[test]
fn nan_coordinate_names_the_line() {
    let p = curve("degenerate-nan.txt");
    assert_bad_input(
        &["check", p.to_str().unwrap()],
        None,
        &["degenerate-nan.txt:4:", "non-finite", "finite numbers"],
    );
}

#[test]
fn infinite_coordinate_and_out_of_range() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("inf.txt"), "0 0\n1 0\ninf 1\n").unwrap();
    assert_bad_input(
        &["check", "inf.txt"],
        Some(dir.path()),
        &["inf.txt:3:", "non-finite"],
    );
    std::fs::write(dir.path().join("big.json"), "[[0,0],[1,0],[1e300,1]]").unwrap();
    assert_bad_input(
        &["check", "big.json"],
        Some(dir.path()),
        &["big.json", "point 2", "rescale"],
    );
}

#[test]
fn zero_area() {
    let p = curve("degenerate-collinear.json");
    assert_bad_input(
        &["check", p.to_str().unwrap()],
        None,
        &["degenerate-collinear.json", "zero area"],
    );
}

#[test]
fn svg_with_no_closed_shape() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("open.svg"),
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10"><path d="M0 0 L5 5 L9 1" fill="none" stroke="black"/></svg>"#,
    )
    .unwrap();
    assert_bad_input(
        &["check", "open.svg"],
        Some(dir.path()),
        &["open.svg", "no closed shape", "ending in Z"],
    );
}

#[test]
fn unknown_extension() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("curve.dat"), "0 0\n1 0\n0 1\n").unwrap();
    assert_bad_input(
        &["check", "curve.dat"],
        Some(dir.path()),
        &["curve.dat", "unknown curve format 'dat'", ".json", ".svg"],
    );
}

#[test]
fn missing_file() {
    assert_bad_input(
        &["check", "no/such/curve.json"],
        None,
        &["cannot read no/such/curve.json", "check the path"],
    );
}

#[test]
fn unreadable_inputs() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("folder.json")).unwrap();
    assert_bad_input(
        &["check", "folder.json"],
        Some(dir.path()),
        &["folder.json", "is a folder"],
    );
    std::fs::write(
        dir.path().join("broken.json"),
        "{\"points\": [[0, 0], [1,\n",
    )
    .unwrap();
    assert_bad_input(
        &["check", "broken.json"],
        Some(dir.path()),
        &["broken.json:2:", "invalid JSON"],
    );
    std::fs::write(
        dir.path().join("shape.json"),
        r#"{"points": [[0, 0], [1], [2, 2]]}"#,
    )
    .unwrap();
    assert_bad_input(
        &["check", "shape.json"],
        Some(dir.path()),
        &["shape.json", "point 1", "[x, y]"],
    );
    std::fs::write(dir.path().join("bin.txt"), [0xff, 0xfe, b'\n']).unwrap();
    assert_bad_input(
        &["check", "bin.txt"],
        Some(dir.path()),
        &["bin.txt:1:", "not UTF-8"],
    );
    std::fs::write(dir.path().join("bad.svg"), "<svg").unwrap();
    assert_bad_input(
        &["check", "bad.svg"],
        Some(dir.path()),
        &["bad.svg", "not a readable SVG"],
    );
}

#[test]
fn usage_errors_exit_2() {
    let out = immerse(&["check"]);
    assert_eq!(out.status.code(), Some(2));
    let out = immerse(&["frobnicate"]);
    assert_eq!(out.status.code(), Some(2));
}
