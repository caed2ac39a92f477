//! The bad-input catalogue (docs/bad-input.md): every row not already
//! backed by a test in `cli.rs` is backed here, through the real binary,
//! with the exact stderr text and exit code.

use crate::util::{assert_stderr, curve, stdout};
use std::path::Path;

/// A temporary folder holding `files` (name, contents).
fn dir_with(files: &[(&str, &[u8])]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (name, data) in files {
        let path = dir.path().join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, data).unwrap();
    }
    dir
}

const SHAPE: &str = r#"expected {"points": [[x, y], ...]} or a bare array of [x, y] pairs"#;

#[test]
fn json_of_the_wrong_shape() {
    let d = dir_with(&[
        ("nopoints.json", br#"{"name": "x"}"#),
        ("notarray.json", br#"{"points": 5}"#),
        ("scalar.json", b"42"),
    ]);
    let d = Some(d.path());
    assert_stderr(
        d,
        &["check", "nopoints.json"],
        2,
        &format!("immerse: nopoints.json: no \"points\" field; {SHAPE}"),
    );
    assert_stderr(
        d,
        &["check", "notarray.json"],
        2,
        &format!("immerse: notarray.json: \"points\" is not an array; {SHAPE}"),
    );
    assert_stderr(
        d,
        &["check", "scalar.json"],
        2,
        &format!("immerse: scalar.json: {SHAPE}"),
    );
}

#[test]
fn text_lines_that_are_not_pairs() {
    let d = dir_with(&[
        ("fields.txt", b"0 0\n1 2 3\n"),
        ("word.csv", b"0, 0\nabc, 1\n"),
    ]);
    let d = Some(d.path());
    assert_stderr(
        d,
        &["check", "fields.txt"],
        2,
        "immerse: fields.txt:2: expected two numbers 'x y', found 3 field(s) in '1 2 3'",
    );
    assert_stderr(
        d,
        &["check", "word.csv"],
        2,
        "immerse: word.csv:2: 'abc' is not a number (in 'abc, 1')",
    );
}

#[test]
fn json_cannot_spell_nan_or_infinity() {
    let d = dir_with(&[
        ("nan.json", b"[[0,0],[1,0],[NaN,1]]"),
        ("huge.json", b"[[0,0],[1,0],[1e999,1]]"),
    ]);
    let d = Some(d.path());
    assert_stderr(
        d,
        &["check", "nan.json"],
        2,
        "immerse: nan.json:1:15: invalid JSON: expected value",
    );
    assert_stderr(
        d,
        &["check", "huge.json"],
        2,
        "immerse: huge.json:1:19: invalid JSON: number out of range",
    );
}

#[test]
fn out_of_range_in_text_names_the_line_and_tiny_values_count() {
    let d = dir_with(&[
        ("big.txt", b"0 0\n1 0\n1e40 1\n"),
        ("tiny.json", b"[[0,0],[1,0],[1e-40,1]]"),
    ]);
    let d = Some(d.path());
    assert_stderr(
        d,
        &["check", "big.txt"],
        2,
        "immerse: big.txt: point 2 (line 3) has a coordinate of magnitude 1e40, outside [1e-30, 1e30]; rescale the curve",
    );
    assert_stderr(
        d,
        &["check", "tiny.json"],
        2,
        "immerse: tiny.json: point 2 (counting from 0) has a coordinate of magnitude 1e-40, outside [1e-30, 1e30]; rescale the curve",
    );
}

#[test]
fn too_large_file_and_too_many_points() {
    let d = tempfile::tempdir().unwrap();
    // A sparse file one byte over the limit: refused before it is read.
    let f = std::fs::File::create(d.path().join("big.json")).unwrap();
    f.set_len(immerse::curve::MAX_FILE_BYTES + 1).unwrap();
    drop(f);
    let n = immerse::curve::MAX_POINTS + 1;
    let text: String = (0..n).map(|i| format!("{} {}\n", i % 7, i % 3)).collect();
    std::fs::write(d.path().join("many.txt"), text).unwrap();
    let d = Some(d.path());
    assert_stderr(
        d,
        &["check", "big.json"],
        2,
        "immerse: big.json: too large (67108865 bytes; the limit is 67108864 bytes); simplify the curve first",
    );
    assert_stderr(
        d,
        &["check", "many.txt"],
        2,
        "immerse: many.txt: too large (200001 points; the limit is 200000 points); simplify the curve first",
    );
}

/// Bad input is refused the same way by every command that reads curves.
#[test]
fn triangulate_and_morph_refuse_bad_curves_too() {
    let d = dir_with(&[("two.json", b"[[0,0],[1,1],[0,0]]")]);
    let tri = curve("triangle.json");
    let tri = tri.to_str().unwrap();
    let msg = "immerse: two.json: only 2 distinct point(s) after dropping repeated points; a curve needs at least 3";
    let d = Some(d.path());
    assert_stderr(d, &["triangulate", "two.json"], 2, msg);
    assert_stderr(d, &["morph", tri, "two.json", "--frames", "2"], 2, msg);
    assert_stderr(d, &["morph", "two.json", tri, "--frames", "2"], 2, msg);
}

/// Clap's usage errors: exit 2, the whole message as clap prints it.
#[test]
fn usage_errors() {
    let tri = curve("triangle.json");
    let tri = tri.to_str().unwrap();
    let more = "\n\nFor more information, try '--help'.";
    let cases: &[(&[&str], String)] = &[
        (
            &["check"],
            format!(
                "error: the following required arguments were not provided:\n  <CURVE>\n\nUsage: immerse check <CURVE>{more}"
            ),
        ),
        (
            &["xyzzy"],
            format!("error: unrecognized subcommand 'xyzzy'\n\nUsage: immerse <COMMAND>{more}"),
        ),
        (
            &["check", tri, "--bogus"],
            format!(
                "error: unexpected argument '--bogus' found\n\n  tip: to pass '--bogus' as a value, use '-- --bogus'\n\nUsage: immerse check <CURVE>{more}"
            ),
        ),
        (
            &["triangulate", tri, "--quality", "best"],
            format!(
                "error: invalid value 'best' for '--quality <QUALITY>'\n  [possible values: any, delaunay, maxmin]{more}"
            ),
        ),
        (
            &["morph", tri, tri, "--frames", "1"],
            format!(
                "error: invalid value '1' for '--frames <FRAMES>': 1 is not in 2..=100000{more}"
            ),
        ),
        (
            &["morph", tri, tri, "--fps", "abc"],
            format!("error: invalid value 'abc' for '--fps <FPS>': invalid float literal{more}"),
        ),
        (
            &["triangulate", tri, "--size", "0x5"],
            format!(
                "error: invalid value '0x5' for '--size <WxH>': '0' in '0x5' is not a size from 1 to 8192{more}"
            ),
        ),
        (
            &["triangulate", tri, "--size", "12"],
            format!(
                "error: invalid value '12' for '--size <WxH>': '12' is not WIDTHxHEIGHT, e.g. 800x600{more}"
            ),
        ),
        (
            &["morph", tri, tri, "--size", "99999x1"],
            format!(
                "error: invalid value '99999x1' for '--size <WxH>': '99999' in '99999x1' is not a size from 1 to 8192{more}"
            ),
        ),
    ];
    for (args, expected) in cases {
        assert_stderr(None, args, 2, expected);
    }
}

/// Option values that parse but mean nothing: exit 2, one line.
#[test]
fn bad_easing_fps_and_image_type() {
    let tri = curve("triangle.json");
    let tri = tri.to_str().unwrap();
    let expected_easing = "expected linear, ease, ease-in, ease-out, ease-in-out or cubic-bezier(x1,y1,x2,y2) with x1 and x2 in [0,1]";
    assert_stderr(
        None,
        &["morph", tri, tri, "--easing", "wobble"],
        2,
        &format!(
            "immerse: --easing 'wobble': invalid easing 'wobble': unknown name; {expected_easing}"
        ),
    );
    assert_stderr(
        None,
        &["morph", tri, tri, "--easing", "cubic-bezier(1,2)"],
        2,
        &format!(
            "immerse: --easing 'cubic-bezier(1,2)': invalid easing 'cubic-bezier(1,2)': needs 4 numbers, found 2; {expected_easing}"
        ),
    );
    for (fps, shown) in [
        ("0", "0"),
        ("-3", "-3"),
        ("0.05", "0.05"),
        ("1e-300", "1e-300"),
        ("1001", "1001"),
        ("1e9", "1000000000"),
        ("NaN", "NaN"),
    ] {
        for command in ["morph", "mesh-morph"] {
            assert_stderr(
                None,
                &[command, tri, tri, &format!("--fps={fps}")],
                2,
                &format!("immerse: --fps {shown} is not a rate from 0.1 to 1000 frames per second"),
            );
        }
    }
    let d = tempfile::tempdir().unwrap();
    assert_stderr(
        Some(d.path()),
        &["triangulate", tri, "-o", "out.gif"],
        2,
        "immerse: out.gif: unknown image type; name a .png or .svg file",
    );
    assert!(!d.path().join("out.gif").exists());
}

/// Existing outputs are never overwritten without --force (exit 2), and
/// are left as they were.
#[test]
fn existing_outputs_need_force() {
    let tri = curve("triangle.json");
    let tri = tri.to_str().unwrap();
    let d = dir_with(&[
        ("out.png", b"keep"),
        ("morph.json", b"keep"),
        ("anim.gif", b"keep"),
        ("full/x", b""),
    ]);
    let p = d.path();
    let dp = Some(p);
    assert_stderr(
        dp,
        &["triangulate", tri, "-o", "out.png"],
        2,
        "immerse: output file out.png already exists; pass --force to overwrite it",
    );
    assert_stderr(
        dp,
        &["morph", tri, tri, "--frames", "2", "--json", "morph.json"],
        2,
        "immerse: output file morph.json already exists; pass --force to overwrite it",
    );
    assert_stderr(
        dp,
        &["morph", tri, tri, "--frames", "2", "-o", "anim.gif"],
        2,
        "immerse: output file anim.gif already exists; pass --force to overwrite it",
    );
    assert_stderr(
        dp,
        &["morph", tri, tri, "--frames", "2", "-o", "full"],
        2,
        "immerse: output folder full is not empty; pass --force to write into it",
    );
    for f in ["out.png", "morph.json", "anim.gif"] {
        assert_eq!(std::fs::read(p.join(f)).unwrap(), b"keep", "{f} untouched");
    }
    // With --force the same command succeeds.
    let out = crate::util::immerse_in(p, &["triangulate", tri, "-o", "out.png", "--force"]);
    assert_eq!(out.status.code(), Some(0));
    assert_ne!(std::fs::read(p.join("out.png")).unwrap(), b"keep");
}

/// A curve that is not self-overlapping is an answer, not an error: exit 1
/// with the reason on stderr (and `check`'s report on stdout).
#[test]
fn not_self_overlapping_is_exit_1() {
    let eight = curve("figure-eight-n64.json");
    let eight = eight.to_str().unwrap();
    let nine = curve("turning-one-not-self-overlapping-n9.json");
    let nine = nine.to_str().unwrap();
    let tri = curve("triangle.json");
    let tri = tri.to_str().unwrap();
    let root = Some(Path::new(env!("CARGO_MANIFEST_DIR")));
    assert_stderr(
        root,
        &["triangulate", eight],
        1,
        &format!("immerse: {eight}: not self-overlapping: turning number is 0, not 1"),
    );
    assert_stderr(
        root,
        &["triangulate", nine],
        1,
        &format!(
            "immerse: {nine}: not self-overlapping: no triangulation of the disk by valid triangles exists"
        ),
    );
    assert_stderr(
        root,
        &["morph", eight, tri, "--frames", "2"],
        1,
        &format!(
            "immerse: {eight}: the source curve is not self-overlapping: turning number is 0, not 1"
        ),
    );
    assert_stderr(
        root,
        &["morph", tri, nine, "--frames", "2"],
        1,
        &format!(
            "immerse: {nine}: the target curve is not self-overlapping: no triangulation of the disk by valid triangles exists"
        ),
    );
    let out = crate::util::immerse(&["check", eight]);
    assert_eq!(out.status.code(), Some(1));
    assert!(out.stderr.is_empty());
    assert_eq!(
        stdout(&out).lines().next(),
        Some(format!("{eight}: not self-overlapping (turning number is 0, not 1)").as_str())
    );
}

/// SVG input that would make the parser do unbounded work is refused
/// before parsing (found by the `curve_svg` fuzz target).
#[test]
fn svg_path_numbers_too_large_and_svgz() {
    let d = dir_with(&[
        (
            "arc.svg",
            b"<svg xmlns=\"http://www.w3.org/2000/svg\">\n<path d=\"M 80 -60 A 100 5e47 0 1 0 80 60 Z\"/></svg>",
        ),
        ("zipped.svg", &[0x1f, 0x8b, 8, 0, 0, 0, 0, 0]),
    ]);
    let d = Some(d.path());
    assert_stderr(
        d,
        &["check", "arc.svg"],
        2,
        "immerse: arc.svg:2: path data has a number of magnitude 5e47, over the limit 1e12 for SVG path data; rescale the drawing",
    );
    assert_stderr(
        d,
        &["check", "zipped.svg"],
        2,
        "immerse: zipped.svg: not a readable SVG: compressed SVG (svgz) is not supported; decompress it first",
    );
}
