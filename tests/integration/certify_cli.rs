//! `immerse certify`: files written by immerse, hand-made bad motions and
//! bad input, through the real binary.

use crate::util::{curve, immerse, immerse_in};
use serde_json::Value;
use std::path::Path;

fn run(dir: &Path, args: &[&str]) -> (i32, String, String) {
    let out = immerse_in(dir, args);
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn json_report(dir: &Path, file: &str, player: &str) -> (i32, Value) {
    let (code, out, err) = run(dir, &["certify", file, "--player", player, "--json"]);
    assert!(!err.contains("panicked"), "{err}");
    (
        code,
        serde_json::from_str(&out).unwrap_or_else(|e| panic!("{e}: {out} {err}")),
    )
}

#[test]
fn a_morph_written_as_json_lottie_and_animated_svg_is_certified() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (curve("triangle.json"), curve("square.json"));
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    for out in [
        vec![
            "morph",
            a,
            b,
            "--frames",
            "30",
            "--json",
            "m.json",
            "-o",
            "m.lottie.json",
            "-q",
        ],
        vec!["morph", a, b, "--frames", "30", "-o", "m.svg", "-q"],
    ] {
        let o = immerse_in(dir.path(), &out);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    for (file, format) in [
        ("m.json", "immerse-keyframes"),
        ("m.lottie.json", "lottie"),
        ("m.svg", "animated-svg"),
    ] {
        for player in ["exact", "f32"] {
            let (code, r) = json_report(dir.path(), file, player);
            assert_eq!(code, 0, "{file} {player}: {r}");
            assert_eq!(r["answer"], "certified", "{file}");
            assert_eq!(r["format"], format);
            assert_eq!(r["player"], player);
            assert_eq!(r["certified"], r["segments"]);
            assert!(r["segments"].as_u64().unwrap() >= 1);
        }
    }
    // immerse's own keys are certified by their own triangulations.
    let (_, r) = json_report(dir.path(), "m.json", "exact");
    let keys: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("m.json")).unwrap()).unwrap();
    let segments = keys["key_count"].as_u64().unwrap() - 1;
    assert_eq!(r["segments"], segments);
    assert_eq!(r["certified_as_given"], segments);
    // Text report, and --json=FILE.
    let (code, text, _) = run(dir.path(), &["certify", "m.svg"]);
    assert_eq!(code, 0);
    assert!(
        text.contains("certified: an immersed disk at every moment"),
        "{text}"
    );
    let (code, _, _) = run(dir.path(), &["certify", "m.svg", "--json=r.json"]);
    assert_eq!(code, 0);
    let r: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("r.json")).unwrap()).unwrap();
    assert_eq!(r["answer"], "certified");
}

/// A unit square and the same square turned by 180° (each vertex to the
/// opposite corner): every vertex passes the centre at s = ½.
const SQUARE_JSON: &str = r#"{"frames": [
  {"t": 0, "points": [[0,0],[1,0],[1,1],[0,1]], "triangles": [[0,1,2],[0,2,3]]},
  {"t": 1, "points": [[1,1],[0,1],[0,0],[1,0]], "triangles": [[0,1,2],[0,2,3]]}]}"#;

fn lottie(shapes: &[&str], easing: &str, tangent: &str) -> String {
    let keys: Vec<String> = shapes
        .iter()
        .enumerate()
        .map(|(k, v)| {
            let ease = if k + 1 < shapes.len() { easing } else { "" };
            format!(
                r#"{{"t":{},"s":[{{"c":true,"v":{v},"i":[{tangent},[0,0],[0,0],[0,0]],"o":[[0,0],[0,0],[0,0],[0,0]]}}]{ease}}}"#,
                30 * k
            )
        })
        .collect();
    format!(
        r#"{{"v":"5.7.4","fr":30,"ip":0,"op":31,"w":100,"h":100,"layers":[{{"ty":4,"nm":"shape","shapes":[{{"ty":"gr","it":[{{"ty":"sh","ks":{{"a":1,"k":[{}]}}}},{{"ty":"sh","ks":{{"a":0,"k":{{"c":true,"v":[[0,0],[1,0],[1,1]]}}}}}}]}}]}}]}}"#,
        keys.join(",")
    )
}

const LINEAR: &str = r#","i":{"x":1,"y":1},"o":{"x":0,"y":0}"#;
const SQ: &str = "[[0,0],[100,0],[100,100],[0,100]]";
const SQ_HALF: &str = "[[100,100],[0,100],[0,0],[100,0]]";
const SQ_QUARTER: &str = "[[100,0],[100,100],[0,100],[0,0]]";

#[test]
fn the_half_turned_square_is_invalid_in_every_format() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("sq.json"), SQUARE_JSON).unwrap();
    std::fs::write(
        dir.path().join("sq.lottie.json"),
        lottie(&[SQ, SQ_HALF], LINEAR, "[0,0]"),
    )
    .unwrap();
    std::fs::write(
        dir.path().join("sq.svg"),
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100"><path d="M0 0H100V100H0Z"><animate attributeName="d" dur="1s" calcMode="linear" keyTimes="0;1" values="M0 0L100 0L100 100L0 100Z;M100 100L0 100L0 0L100 0Z"/></path></svg>"#,
    )
    .unwrap();
    for file in ["sq.json", "sq.lottie.json", "sq.svg"] {
        for player in ["exact", "f64", "f32"] {
            let (code, r) = json_report(dir.path(), file, player);
            assert_eq!(code, 1, "{file}: {r}");
            assert_eq!(r["answer"], "invalid", "{file}");
            let seg = &r["paths"][0]["segments"][0];
            assert_eq!(seg["answer"], "invalid");
            assert_eq!(seg["invalid_at"]["exact"], "1/2", "{file}: {seg}");
        }
        let (code, text, _) = run(dir.path(), &["certify", file]);
        assert_eq!(code, 1);
        assert!(
            text.contains("not certified: invalid") && text.contains("s = 0.5"),
            "{text}"
        );
    }
    // The static path of the Lottie file is said to be skipped.
    let (_, r) = json_report(dir.path(), "sq.lottie.json", "exact");
    assert!(r["skipped"][0].as_str().unwrap().contains("static"), "{r}");
}

#[test]
fn curved_outlines_and_overshooting_easing_are_not_covered() {
    let dir = tempfile::tempdir().unwrap();
    // A quarter turn is valid; with a curved edge or an overshooting
    // easing it is not a motion certify covers: undecided, exit 1.
    let ok = lottie(&[SQ, SQ_QUARTER], LINEAR, "[0,0]");
    std::fs::write(dir.path().join("ok.json"), &ok).unwrap();
    let (code, r) = json_report(dir.path(), "ok.json", "f32");
    assert_eq!((code, r["answer"].as_str()), (0, Some("certified")), "{r}");
    let eased = lottie(
        &[SQ, SQ_QUARTER],
        r#","i":{"x":[0.58],"y":[1]},"o":{"x":[0.42],"y":[0]}"#,
        "[0,0]",
    );
    std::fs::write(dir.path().join("eased.json"), eased).unwrap();
    let (code, r) = json_report(dir.path(), "eased.json", "exact");
    assert_eq!((code, r["answer"].as_str()), (0, Some("certified")), "{r}");
    assert_eq!(r["paths"][0]["segments"][0]["play"], "eased");
    let over = lottie(
        &[SQ, SQ_QUARTER],
        r#","i":{"x":0.3,"y":1.5},"o":{"x":0.4,"y":0}"#,
        "[0,0]",
    );
    std::fs::write(dir.path().join("over.json"), over).unwrap();
    let (code, r) = json_report(dir.path(), "over.json", "exact");
    assert_eq!((code, r["answer"].as_str()), (1, Some("undecided")), "{r}");
    assert!(
        r["paths"][0]["segments"][0]["reason"]
            .as_str()
            .unwrap()
            .contains("overshoot")
    );
    let curved = lottie(&[SQ, SQ_QUARTER], LINEAR, "[5,3]");
    std::fs::write(dir.path().join("curved.json"), curved).unwrap();
    let (code, r) = json_report(dir.path(), "curved.json", "exact");
    assert_eq!((code, r["answer"].as_str()), (1, Some("undecided")), "{r}");
    assert!(
        r["paths"][0]["segments"][0]["reason"]
            .as_str()
            .unwrap()
            .contains("curved"),
        "{r}"
    );
    let (_, text, _) = run(dir.path(), &["certify", "curved.json"]);
    assert!(
        text.contains("not certified: undecided") && text.contains("curved"),
        "{text}"
    );
}

#[test]
fn bad_input_exits_2_with_a_message() {
    let dir = tempfile::tempdir().unwrap();
    let files = [
        ("empty.json", ""),
        ("words.json", "hello"),
        ("broken.json", "{\"frames\": ["),
        ("other.json", "{\"foo\": 1}"),
        ("noanim.json", r#"{"layers":[{"ty":4,"shapes":[]}]}"#),
        ("badframes.json", r#"{"frames":[{"t":0,"points":"x"}]}"#),
        (
            "plain.svg",
            r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0L1 0L1 1Z"/></svg>"#,
        ),
        ("broken.svg", "<svg><path"),
        (
            "keytimes.svg",
            r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0L1 0L1 1Z"><animate attributeName="d" keyTimes="0;x" values="M0 0L1 0L1 1Z;M0 0L2 0L1 1Z"/></path></svg>"#,
        ),
    ];
    for (name, text) in files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    std::fs::create_dir(dir.path().join("folder")).unwrap();
    let names = files.iter().map(|f| f.0).chain(["folder", "missing.json"]);
    for name in names {
        let (code, out, err) = run(dir.path(), &["certify", name]);
        assert_eq!(code, 2, "{name}: {out} {err}");
        assert!(
            err.starts_with("immerse: ") && err.contains(name),
            "{name}: {err}"
        );
        assert!(!err.contains("panicked"), "{name}: {err}");
    }
    // Points that are not finite or counts that differ: not a motion, an
    // answer (undecided), not a crash.
    std::fs::write(
        dir.path().join("counts.json"),
        r#"{"frames":[{"t":0,"points":[[0,0],[1,0],[0,1]]},{"t":1,"points":[[0,0],[1,0],[1,1],[0,1]]}]}"#,
    )
    .unwrap();
    let (code, r) = json_report(dir.path(), "counts.json", "exact");
    assert_eq!((code, r["answer"].as_str()), (1, Some("undecided")), "{r}");
    let o = immerse(&["certify", "--help"]);
    let help = String::from_utf8_lossy(&o.stdout);
    assert!(
        help.contains("--player") && help.contains("undecided"),
        "{help}"
    );
}
