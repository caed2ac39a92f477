//! Certified keyframes in every output (docs/design.md §12, §13): the keys
//! of the motion pairs certify, their times increase, the written Lottie
//! and animated SVG certify as written, the JSON's keyframes round trip
//! through `immerse certify`, and the frames are evenly paced.

use crate::util::{curve, curves_dir, immerse, stderr};
use immerse::certify::Player;
use immerse::morph::{CurveMorphOptions, Tween};
use immerse::{Curve, Point};
use testkit::pairs;

use testkit::pacing;

fn tween(a: &str, b: &str, options: &CurveMorphOptions) -> Tween {
    let ca = Curve::from_path(curves_dir().join(a)).unwrap();
    let cb = Curve::from_path(curves_dir().join(b)).unwrap();
    Tween::new(&ca.points, &cb.points, options).unwrap()
}

/// The motion pairs (every third in the debug profile, for time).
fn pairs_to_test() -> Vec<(String, String)> {
    let all = pairs::motion_pairs();
    let step = if cfg!(debug_assertions) { 3 } else { 1 };
    all.into_iter().step_by(step).collect()
}

/// Key times start at 0, end at 1 and strictly increase; every segment
/// between keys is certified for every s by an independent call of the
/// certificate; the keys are the frames at their times.
#[test]
fn keys_of_the_motion_pairs_are_certified_and_increase() {
    for (a, b) in pairs_to_test() {
        let tw = tween(&a, &b, &CurveMorphOptions::DEFAULT);
        let keys = tw.keyframes();
        assert_eq!(keys.len(), tw.key_count(), "{a} → {b}");
        assert_eq!(keys[0].t, 0.0);
        assert_eq!(keys.last().unwrap().t, 1.0);
        assert!(keys.windows(2).all(|w| w[0].t < w[1].t), "{a} → {b}: times");
        let report = crate::util::certify_keyframes(&keys, Player::Exact);
        assert_eq!(
            report.is_certified(),
            tw.is_certified(),
            "{a} → {b}: {:?}",
            report.first_failure()
        );
        // The ends are the curves' frames exactly.
        for k in [&keys[0], keys.last().unwrap()] {
            assert_eq!(tw.frame(k.t).unwrap().points, k.points, "{a} → {b}");
        }
    }
}

/// A straight-line morph that is valid needs two keys.
#[test]
fn a_valid_linear_morph_has_two_keys() {
    let linear = CurveMorphOptions::DEFAULT;
    // A pentagon grown and moved: every vertex moves on a straight line
    // on every path, and every straight-line in-between is a pentagon.
    let a: Vec<Point> = (0..5)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / 5.0;
            Point::new(t.cos(), t.sin())
        })
        .collect();
    let b: Vec<Point> = a
        .iter()
        .map(|p| Point::new(3.0 * p.x + 7.0, 3.0 * p.y - 1.0))
        .collect();
    let tw = Tween::new(&a, &b, &linear).unwrap();
    assert_eq!(tw.key_count(), 2);
    assert!(tw.is_certified());
    let keys = tw.keyframes();
    assert_eq!((keys[0].t, keys[1].t), (0.0, 1.0));
}

/// Even pacing at 320 frames with linear easing: the largest per-frame
/// mean vertex step at most 1.5× the median, the largest single-vertex
/// step at most 2× the median of those.
#[test]
fn frames_are_evenly_paced_on_the_motion_pairs() {
    for (a, b) in pairs_to_test() {
        let tw = tween(&a, &b, &CurveMorphOptions::DEFAULT);
        let p = pacing::measure(&tw, 320).unwrap();
        assert!(p.mean_ratio <= 1.5, "{a} → {b}: mean step {}", p.mean_ratio);
        assert!(
            p.max_ratio <= 2.0,
            "{a} → {b}: largest step {}",
            p.max_ratio
        );
    }
}

/// The key tolerance is validated.
#[test]
fn a_bad_key_tolerance_is_refused() {
    for bad in [0.0, -1.0, 0.2, f64::NAN, f64::INFINITY] {
        let o = CurveMorphOptions::DEFAULT.with_key_tolerance(bad);
        assert!(o.validate().is_err(), "{bad}");
    }
    let out = immerse(&[
        "morph",
        curve("triangle.json").to_str().unwrap(),
        curve("square.json").to_str().unwrap(),
        "--key-tolerance",
        "0.5",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("key tolerance 0.5"),
        "{}",
        stderr(&out)
    );
}

/// Every Lottie and animated SVG `immerse morph` writes for the motion
/// pairs certifies as written (f32 and f64 players), and the JSON's
/// keyframes round trip through `immerse certify`. A Lottie file that
/// cannot be certified for an f32 player is refused, naming the segment,
/// and nothing is written.
#[test]
fn written_files_certify_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let mut refused = Vec::new();
    for (i, (a, b)) in pairs_to_test().into_iter().enumerate() {
        let (ca, cb) = (curve(&a), curve(&b));
        let lottie = dir.path().join(format!("{i}.lottie.json"));
        let svg = dir.path().join(format!("{i}.svg"));
        let json = dir.path().join(format!("{i}.json"));
        let morph = |out: &std::path::Path, extra: &str| {
            immerse(&[
                "morph",
                ca.to_str().unwrap(),
                cb.to_str().unwrap(),
                "--frames",
                "40",
                extra,
                "-o",
                out.to_str().unwrap(),
                "--json",
                json.to_str().unwrap(),
                "--force",
            ])
        };
        // Where the keys themselves leave a segment uncertified (frames
        // there fall back to the path), no written file can certify.
        let certified = tween(&a, &b, &CurveMorphOptions::DEFAULT).is_certified();
        let o = morph(&svg, "--once");
        if !certified {
            assert!(
                o.status.success() || stderr(&o).contains("nothing was written"),
                "{a} → {b}: {}",
                stderr(&o)
            );
            refused.push(format!("{a} → {b} (keys not certified)"));
            continue;
        }
        assert!(o.status.success(), "{a} → {b}: {}", stderr(&o));
        let o = morph(&lottie, "--ping-pong");
        let mut written = vec![(&svg, "f64"), (&json, "exact")];
        if o.status.success() {
            written.push((&lottie, "f32"));
        } else {
            let e = stderr(&o);
            assert!(
                e.contains(
                    "not certified as written, even in full precision, for an f32 player: segment"
                ) && e.contains("nothing was written"),
                "{a} → {b}: {e}"
            );
            assert!(!lottie.exists(), "{a} → {b}: a refused file was written");
            refused.push(format!("{a} → {b}"));
        }
        let value: serde_json::Value =
            serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
        let count = value["key_count"].as_u64().unwrap() as usize;
        assert_eq!(value["keyframes"].as_array().unwrap().len(), count);
        for (file, player) in written {
            let o = immerse(&["certify", file.to_str().unwrap(), "--player", player]);
            assert_eq!(
                o.status.code(),
                Some(0),
                "{a} → {b}: {}: {}",
                file.display(),
                crate::util::stdout(&o)
            );
        }
    }
    eprintln!("refused: {refused:?}");
}

/// Where a vertex's two boundary edges shrink to a few hundredths of a
/// pixel inside a segment and grow again (ribbon curl → folded ribbon,
/// keys 8 → 9 of its Lottie file), the f32 player's margin taken from the
/// edges' lengths at the segment's ends is a hundred times too large, and
/// the Lottie file was refused at every precision. The margin is now taken
/// piece by piece (docs/design.md §13): the file is written, `immerse
/// certify` certifies it for an f32 player, and what an f32 player draws
/// between its keys is self-overlapping (decided by the DP, sharing no
/// code with the certificate).
#[test]
fn the_f32_margin_is_taken_piece_by_piece_where_edges_shrink_inside_a_segment() {
    let dir = tempfile::tempdir().unwrap();
    let lottie = dir.path().join("curl-fold.lottie.json");
    let o = immerse(&[
        "morph",
        curve("ribbon-curl.svg").to_str().unwrap(),
        curve("folded-ribbon.svg").to_str().unwrap(),
        "-o",
        lottie.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = immerse(&["certify", lottie.to_str().unwrap(), "--player", "f32"]);
    assert_eq!(o.status.code(), Some(0), "{}", crate::util::stdout(&o));
    let anim = immerse::certify::read_animation(&std::fs::read(&lottie).unwrap(), "x").unwrap();
    let keys = &anim.paths[0].keys;
    for (i, w) in keys.windows(2).enumerate() {
        for s in [0.125f32, 0.375, 0.625, 0.875] {
            for form in [true, false] {
                let drawn = crate::certify::f32_player(&w[0].points, &w[1].points, s, form);
                assert!(
                    immerse::triangulate(&drawn).is_ok(),
                    "segment {i}, s = {s}: an f32 player draws a shape that is not self-overlapping"
                );
            }
        }
    }
}
