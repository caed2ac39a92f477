//! Keyframe sequences and the Tween: the Tween gives the frames `morph`
//! gives, alone or in a batch; sequences over the reference curves are
//! immersions frame by frame with the keys' original vertices exact,
//! hints honoured, and the speed carried through unheld keys; the
//! `animate` command's outputs and its bad inputs (docs/bad-input.md).

use crate::util::{LAST_LEG_RIVALS, assert_stderr, curve, immerse, immerse_in, stderr, stdout};
use immerse::Curve;
use immerse::Point;
use immerse::frames::Frame;
use immerse::morph::{CurveMorphOptions, Tween};
use immerse::sequence::{Ease, Hint, HintAt, Key, Sequence, SequenceOptions, Timing, key_speeds};
use testkit::morph_pair;

fn load(name: &str) -> Curve {
    Curve::from_path(curve(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn key(name: &str) -> Key {
    Key::new(name, load(name).points)
}

fn same_frame(a: &Frame, b: &Frame, what: &str) {
    assert_eq!(a.points.len(), b.points.len(), "{what}");
    for (p, q) in a.points.iter().zip(&b.points) {
        assert!(
            p.x.to_bits() == q.x.to_bits() && p.y.to_bits() == q.y.to_bits(),
            "{what}: {p} != {q}"
        );
    }
    assert_eq!(a.triangles, b.triangles, "{what}");
}

const PAIRS: [(&str, &str); 5] = [
    (
        "spiral-strip-400deg-n30.json",
        "circular-strip-450deg-n60.json",
    ),
    ("ribbon-curl.svg", "tail-loop.svg"),
    ("letter-E.json", "star-5-points.json"),
    ("curl-strip-n10.json", "spiral-strip-400deg-n30.json"),
    (
        "immersed-disk-n80.json",
        "spiral-strip-540deg-n120-clockwise.json",
    ),
];

/// A Tween planned again gives bit for bit the same frames, and a frame at
/// t is the same asked alone, in a batch, or in another order.
#[test]
fn tween_frames_are_the_same_planned_again_alone_or_in_a_batch() {
    let ts: Vec<f64> = (0..=24).map(|i| f64::from(i) / 24.0).collect();
    for (sa, sb) in PAIRS {
        let (a, b) = (load(sa), load(sb));
        let tween = Tween::new(&a.points, &b.points, &CurveMorphOptions::DEFAULT).unwrap();
        let (report, batch) =
            morph_pair(&a.points, &b.points, &ts, &CurveMorphOptions::DEFAULT).unwrap();
        assert_eq!(report.shift, tween.report().shift, "{sa} -> {sb}");
        assert_eq!(batch.frames.len(), ts.len());
        let own = tween.morph(&ts).unwrap();
        for (i, &t) in ts.iter().enumerate().rev() {
            let alone = tween.frame(t).unwrap();
            same_frame(&alone, &batch.frames[i], &format!("{sa} -> {sb} at {t}"));
            same_frame(
                &alone,
                &own.frames[i],
                &format!("{sa} -> {sb} own batch at {t}"),
            );
        }
        // The same t twice in one batch, and out of order.
        let shuffled = [0.7, 0.2, 0.7, 1.0, 0.0];
        let m = tween.morph(&shuffled).unwrap();
        same_frame(&m.frames[0], &m.frames[2], "repeated t");
        same_frame(&m.frames[1], &tween.frame(0.2).unwrap(), "t = 0.2");
        // The ends are the curves.
        assert_eq!(tween.frame(0.0).unwrap().points.len(), tween.vertex_count());
    }
}

/// `immerse morph --json` writes the Tween's frames (JSON numbers read back
/// bit for bit).
#[test]
fn tween_frames_are_the_morph_commands_frames() {
    let (sa, sb) = ("ribbon-curl.svg", "tail-loop.svg");
    let out = immerse(&[
        "morph",
        curve(sa).to_str().unwrap(),
        curve(sb).to_str().unwrap(),
        "--frames",
        "13",
        "--json",
        "-",
        "-q",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let frames = v["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 13);
    let tween = Tween::new(
        &load(sa).points,
        &load(sb).points,
        &CurveMorphOptions::DEFAULT,
    )
    .unwrap();
    for (i, f) in frames.iter().enumerate() {
        let t = f["t"].as_f64().unwrap();
        assert_eq!(t, i as f64 / 12.0);
        let mine = tween.frame(t).unwrap();
        let pts: Vec<Point> = f["points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| Point::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
            .collect();
        let tris: Vec<[u32; 3]> = serde_json::from_value(f["triangles"].clone()).unwrap();
        same_frame(
            &mine,
            &Frame {
                t,
                points: pts,
                triangles: tris,
            },
            &format!("frame {i}"),
        );
    }
}

/// The largest vertex move between two frames.
fn step(a: &Frame, b: &Frame) -> f64 {
    a.points
        .iter()
        .zip(&b.points)
        .map(|(p, q)| (*q - *p).length())
        .fold(0.0, f64::max)
}

/// Checks a planned sequence's frames: every one an immersion by the
/// independent checker, constant vertex count, the keys at their frame
/// numbers with every original vertex exact; returns the speed ratios at
/// the keys.
fn check_sequence(keys: &[Key], seq: &Sequence, frames: usize) -> Vec<f64> {
    let schedule = seq
        .schedule(&Timing::new(keys.len()).with_frames(Some(frames)))
        .unwrap();
    let morph = seq.frames(&schedule).unwrap();
    assert_eq!(morph.frames.len(), frames);
    let n = seq.vertex_count();
    for (i, f) in morph.frames.iter().enumerate() {
        assert_eq!(f.points.len(), n);
        if let Err(e) = immerse::check(&f.points, &f.triangles) {
            panic!("frame {i}: {e}");
        }
    }
    for (j, k) in keys.iter().enumerate() {
        let f = &morph.frames[schedule.key_frames[j]];
        assert_eq!(f.points, seq.key_points(j), "key {}", j + 1);
        let originals = seq.original_vertices(j);
        let mut seen = vec![false; k.points.len()];
        for (v, o) in originals.iter().enumerate() {
            if let Some(i) = *o {
                assert_eq!(f.points[v], k.points[i], "key {} vertex {i}", j + 1);
                seen[i] = true;
            }
        }
        assert!(
            seen.iter().all(|&s| s),
            "key {}: every original vertex",
            j + 1
        );
    }
    // Frame t grows along the travel.
    for w in morph.frames.windows(2) {
        assert!(w[1].t >= w[0].t);
    }
    let speeds = key_speeds(&morph.frames, &schedule);
    assert_eq!(speeds.len(), keys.len() - 2);
    for s in &speeds {
        let f = s.frame;
        assert_eq!(s.before, step(&morph.frames[f - 1], &morph.frames[f]));
        assert!(s.not_continuous.is_none(), "{s:?}");
    }
    speeds.iter().map(|s| s.ratio).collect()
}

#[test]
fn three_key_sequence_over_reference_curves() {
    let keys = vec![
        key("spiral-strip-400deg-n30.json"),
        key("circular-strip-450deg-n60.json"),
        key("curl-strip-n10.json"),
    ];
    let seq = Sequence::new(&keys, &[], &SequenceOptions::DEFAULT).unwrap();
    assert_eq!(seq.vertex_count(), 60);
    let ratios = check_sequence(&keys, &seq, 121);
    eprintln!("3-key speed ratios: {ratios:?}");
    assert!(ratios.iter().all(|&r| r <= 1.25), "{ratios:?}");
}

#[test]
fn five_key_sequence_over_reference_curves() {
    let keys = vec![
        key("ribbon-curl.svg"),
        key("tail-loop.svg"),
        key("folded-ribbon.svg"),
        key("ring-wrap-400deg.svg"),
        key("ribbon-curl.svg"),
    ];
    let seq = Sequence::new(&keys, &[], &SequenceOptions::DEFAULT).unwrap();
    assert_eq!(seq.vertex_count(), 200);
    let ratios = check_sequence(&keys, &seq, 161);
    eprintln!("5-key speed ratios: {ratios:?}");
    assert!(ratios.iter().all(|&r| r <= 1.25), "{ratios:?}");
}

/// Hints by index, position and fraction: the hinted vertex of one key
/// lands on its partner in the next, to 1e-12 of the curves' size.
#[test]
fn hints_are_honoured_exactly() {
    let keys = vec![
        key("spiral-strip-540deg-n120.json"),
        key("spiral-strip-capped-450deg-n92.json"),
        key("annulus-sector-300deg-n40.json"),
    ];
    // A point between two vertices of key 2, by position.
    let (p, q) = (keys[1].points[60], keys[1].points[61]);
    let between = p.lerp(q, 0.37);
    let hints = vec![
        Hint {
            name: "a".into(),
            segment: 0,
            from: HintAt::Vertex(0),
            to: HintAt::Vertex(45),
        },
        Hint {
            name: "b".into(),
            segment: 0,
            from: HintAt::Vertex(60),
            to: HintAt::Point(between),
        },
        Hint {
            name: "c".into(),
            segment: 0,
            from: HintAt::Fraction(0.75),
            to: HintAt::Vertex(80),
        },
        Hint {
            name: "d".into(),
            segment: 1,
            from: HintAt::Point(between),
            to: HintAt::Vertex(5),
        },
        Hint {
            name: "e".into(),
            segment: 1,
            from: HintAt::Vertex(0),
            to: HintAt::Fraction(0.5),
        },
    ];
    let seq = Sequence::new(&keys, &hints, &SequenceOptions::DEFAULT).unwrap();
    let schedule = seq.schedule(&Timing::new(3).with_frames(Some(81))).unwrap();
    let morph = seq.frames(&schedule).unwrap();
    assert!(morph.frames.iter().all(Frame::is_immersion));
    let size = |pts: &[Point]| {
        let (mut lo, mut hi) = (pts[0], pts[0]);
        for &p in pts {
            lo = lo.min(p);
            hi = hi.max(p);
        }
        (hi - lo).length()
    };
    assert_eq!(seq.hints().len(), hints.len());
    for h in seq.hints() {
        let s = h.segment;
        let start = &morph.frames[schedule.key_frames[s]];
        let end = &morph.frames[schedule.key_frames[s + 1]];
        let tol = 1e-12 * size(&end.points).max(size(&start.points));
        assert!(
            (start.points[h.vertex] - h.from).length() <= tol,
            "{}",
            h.name
        );
        assert!((end.points[h.vertex] - h.to).length() <= tol, "{}", h.name);
        // In fact exactly: the tween's ends are its keys.
        assert_eq!(start.points[h.vertex], h.from, "{}", h.name);
        assert_eq!(end.points[h.vertex], h.to, "{}", h.name);
        // The hint's own point: on the curve where it was given.
        let given = hints.iter().find(|g| g.name == h.name).unwrap();
        for (at, point, k) in [(given.from, h.from, s), (given.to, h.to, s + 1)] {
            match at {
                HintAt::Vertex(i) => assert_eq!(point, keys[k].points[i]),
                HintAt::Point(x) => assert!((point - x).length() <= tol, "{}", h.name),
                HintAt::Fraction(_) => {}
            }
        }
    }
    // Both "b" and "d" pin the same point of key 2: one vertex.
    let b = seq.hints().iter().find(|h| h.name == "b").unwrap();
    let d = seq.hints().iter().find(|h| h.name == "d").unwrap();
    assert_eq!(b.vertex, d.vertex);
}

/// A hold repeats the key; an easing that stops at a key is reported as
/// such; linear keys carry the speed.
#[test]
fn holds_and_stopping_easings_break_continuity_where_asked() {
    let keys = vec![
        key("spiral-strip-400deg-n30.json"),
        key("circular-strip-450deg-n60.json"),
        key("curl-strip-n10.json"),
        key("spiral-strip-400deg-n30.json"),
    ];
    let seq = Sequence::new(&keys, &[], &SequenceOptions::DEFAULT).unwrap();
    let mut timing = Timing::new(4).with_frames(Some(100));
    timing.keys[1].hold = 0.2; // 6 frames at 30 fps
    timing.keys[2].easing = Ease::new(|x: f64| x * x); // starts from rest
    let schedule = seq.schedule(&timing).unwrap();
    assert_eq!(schedule.samples.len(), 100);
    assert_eq!(schedule.holds[1], 6);
    let morph = seq.frames(&schedule).unwrap();
    let f = schedule.key_frames[1];
    for i in f..=f + 6 {
        assert_eq!(morph.frames[i].points, morph.frames[f].points);
    }
    let speeds = key_speeds(&morph.frames, &schedule);
    assert!(
        speeds[0]
            .not_continuous
            .as_deref()
            .unwrap()
            .contains("holds")
    );
    assert!(
        speeds[1]
            .not_continuous
            .as_deref()
            .unwrap()
            .contains("rest")
    );
    assert!(speeds[1].ratio > 3.0, "{:?}", speeds[1]);
}

// ---- the animate command ----

#[test]
fn animate_writes_every_frame_with_keys_at_their_frame_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let files = [
        "spiral-strip-400deg-n30.json",
        "circular-strip-450deg-n60.json",
        "curl-strip-n10.json",
    ];
    for f in files {
        std::fs::copy(curve(f), dir.path().join(f)).unwrap();
    }
    let out = immerse_in(
        dir.path(),
        &[
            "animate",
            files[0],
            files[1],
            files[2],
            "--frames",
            "61",
            "--json",
            "seq.json",
            "-o",
            "seq.gif",
            "-o",
            "sheet.png",
            "-o",
            "frames",
            "--size",
            "120x120",
            "-q",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(
        text.contains("3 keys, 60 vertices each, 61 frames at 30 fps"),
        "{text}"
    );
    assert!(
        text.contains("key 2 (circular-strip-450deg-n60.json) at frame"),
        "{text}"
    );
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("seq.json")).unwrap())
            .unwrap();
    // The default path (the last legs may take a rival where it travels
    // less).
    let path = v["path"].as_str().unwrap();
    assert!(
        path.split('+').all(|p| LAST_LEG_RIVALS.contains(&p)) && path.starts_with("rigid"),
        "{path}"
    );
    let frames = v["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 61);
    let keys = v["keys"].as_array().unwrap();
    assert_eq!(keys.len(), 3);
    assert_eq!(keys[0]["frame"], 0);
    assert_eq!(keys[2]["frame"], 60);
    // Key 2's frame holds its curve's points (all of them, in order).
    let k2 = load(files[1]);
    let f = &frames[keys[1]["frame"].as_u64().unwrap() as usize]["points"];
    let pts: Vec<Point> = f
        .as_array()
        .unwrap()
        .iter()
        .map(|p| Point::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
        .collect();
    for p in &k2.points {
        assert!(pts.contains(p));
    }
    assert!(v["speeds"][0]["ratio"].as_f64().unwrap() <= 1.25);
    assert!(dir.path().join("seq.gif").is_file());
    assert!(dir.path().join("sheet.png").is_file());
    assert!(dir.path().join("frames/frame_0060.png").is_file());
    assert!(!dir.path().join("frames/frame_0061.png").exists());
}

fn write(dir: &std::path::Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap();
}

/// A timeline folder with three keys.
fn timeline_dir() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for f in [
        "spiral-strip-400deg-n30.json",
        "circular-strip-450deg-n60.json",
        "curl-strip-n10.json",
    ] {
        std::fs::copy(curve(f), dir.path().join(f)).unwrap();
    }
    dir
}

#[test]
fn animate_timeline_with_hints_holds_and_easing() {
    let dir = timeline_dir();
    write(
        dir.path(),
        "seq.json",
        r#"{"fps": 20, "loop": "ping-pong", "keys": [
            {"curve": "spiral-strip-400deg-n30.json", "hints": {"a": 0, "b": {"fraction": 0.5}}},
            {"curve": "circular-strip-450deg-n60.json", "hold": 0.25, "easing": "ease-out", "hints": {"a": 10, "b": 40, "c": 20}},
            {"curve": "curl-strip-n10.json", "time": 4, "hints": {"c": 3}}
        ]}"#,
    );
    let out = immerse_in(
        dir.path(),
        &["animate", "--timeline", "seq.json", "--json", "out.json"],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("out.json")).unwrap())
            .unwrap();
    let frames = v["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 81, "4 s at 20 fps");
    assert_eq!(v["keys"][1]["hold"], 5);
    assert_eq!(v["keys"][2]["frame"], 80);
    let k2 = load("circular-strip-450deg-n60.json");
    let f = v["keys"][1]["frame"].as_u64().unwrap() as usize;
    // Hint a: key 1's point 0 reaches key 2's point 10 at key 2's frame.
    let k1 = load("spiral-strip-400deg-n30.json");
    let at = |frame: usize, p: Point| -> Option<usize> {
        frames[frame]["points"]
            .as_array()
            .unwrap()
            .iter()
            .position(|q| q[0].as_f64() == Some(p.x) && q[1].as_f64() == Some(p.y))
    };
    let va = at(0, k1.points[0]).unwrap();
    assert_eq!(at(f, k2.points[10]), Some(va));
}

#[test]
fn animate_bad_inputs_exit_2_with_one_line() {
    let dir = timeline_dir();
    let d = Some(dir.path());
    let keys = r#""circular-strip-450deg-n60.json", "curl-strip-n10.json""#;
    // One key only.
    assert_stderr(
        d,
        &["animate", "curl-strip-n10.json"],
        2,
        "immerse: 1 key given; a sequence needs at least 2 keys: name two or more curve files, one SVG drawing with a shape per key, or --timeline FILE",
    );
    write(
        dir.path(),
        "one.json",
        r#"{"keys": ["curl-strip-n10.json"]}"#,
    );
    assert_stderr(
        d,
        &["animate", "--timeline", "one.json"],
        2,
        "immerse: one.json: 1 key given; a sequence needs at least 2 keys",
    );
    // A missing key file.
    write(
        dir.path(),
        "missing.json",
        &format!(r#"{{"keys": [{keys}, "nowhere.json"]}}"#),
    );
    assert_stderr(
        d,
        &["animate", "--timeline", "missing.json"],
        2,
        "immerse: missing.json: key 3: cannot read nowhere.json (check the path and permissions): No such file or directory (os error 2)",
    );
    // A negative duration.
    write(
        dir.path(),
        "negative.json",
        r#"{"keys": ["circular-strip-450deg-n60.json", {"curve": "curl-strip-n10.json", "duration": -1}, "spiral-strip-400deg-n30.json"]}"#,
    );
    assert_stderr(
        d,
        &["animate", "--timeline", "negative.json"],
        2,
        "immerse: negative.json: key 2 (curl-strip-n10.json): duration -1 is not a number of seconds above 0",
    );
    // Hints: an index out of range, out of cyclic order, without partner,
    // off the curve.
    write(
        dir.path(),
        "range.json",
        r#"{"keys": [{"curve": "circular-strip-450deg-n60.json", "hints": {"a": 60}}, {"curve": "curl-strip-n10.json", "hints": {"a": 0}}]}"#,
    );
    assert_stderr(
        d,
        &["animate", "--timeline", "range.json"],
        2,
        "immerse: range.json: key 1 (circular-strip-450deg-n60.json): hint 'a': point 60 does not exist; the file has 60 points (0 to 59)",
    );
    write(
        dir.path(),
        "order.json",
        r#"{"keys": [{"curve": "circular-strip-450deg-n60.json", "hints": {"a": 0, "b": 20, "c": 40}}, {"curve": "curl-strip-n10.json", "hints": {"a": 0, "b": 6, "c": 3}}]}"#,
    );
    assert_stderr(
        d,
        &["animate", "--timeline", "order.json"],
        2,
        "immerse: order.json: key 2 (curl-strip-n10.json): hint 'c': out of cyclic order: along key 1 (circular-strip-450deg-n60.json) the hints run a, b, c, along this key a, c, b; give the hints in the same order along both curves",
    );
    write(
        dir.path(),
        "partner.json",
        r#"{"keys": [{"curve": "circular-strip-450deg-n60.json", "hints": {"a": 0}}, "curl-strip-n10.json"]}"#,
    );
    assert_stderr(
        d,
        &["animate", "--timeline", "partner.json"],
        2,
        "immerse: partner.json: key 1 (circular-strip-450deg-n60.json): hint 'a' has no partner; name it on key 2 too (hints pair points of consecutive keys by name)",
    );
    write(
        dir.path(),
        "off.json",
        r#"{"keys": [{"curve": "circular-strip-450deg-n60.json", "hints": {"a": [100, 100]}}, {"curve": "curl-strip-n10.json", "hints": {"a": 0}}]}"#,
    );
    let out = immerse_in(dir.path(), &["animate", "--timeline", "off.json"]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(
        err.starts_with(
            "immerse: off.json: key 1 (circular-strip-450deg-n60.json): hint 'a': the point [100, 100] is "
        ) && err.ends_with(
            "from the curve, more than 2% of its size; give a point on the curve, a vertex index or a fraction\n"
        ) && err.lines().count() == 1,
        "{err}"
    );
}

/// One SVG drawing as the keys: its layers (top-level groups), or each
/// closed shape.
#[test]
fn svg_drawings_give_their_layers_or_shapes_as_keys() {
    use immerse::curve::SvgShapes;
    let layers =
        Curve::all_from_svg_path(curve("sequence/ribbon-loops.svg"), SvgShapes::Auto).unwrap();
    let names: Vec<&str> = layers.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "ribbon-loops group 'ribbon'",
            "ribbon-loops group 'tail'",
            "ribbon-loops group 'two-loops'",
            "ribbon-loops group 'ribbon-again'"
        ]
    );
    // Each layer is its own drawing, moved: the same points up to the
    // translation.
    let ribbon = load("ribbon-curl.svg");
    assert_eq!(layers[0].len(), ribbon.len());
    assert_eq!(layers[0].points, layers[3].points);
    let svg = br#"<svg xmlns="http://www.w3.org/2000/svg">
        <path d="M 0 0 L 10 0 L 10 10 Z M 20 0 L 30 0 L 30 10 Z"/>
        <g><rect x="0" y="20" width="5" height="5"/><rect x="10" y="20" width="5" height="5"/></g>
        <polyline points="0 40 5 40 5 45"/>
    </svg>"#;
    let shapes = Curve::all_from_svg_bytes(svg, "s.svg", "s", SvgShapes::Shapes).unwrap();
    assert_eq!(
        shapes.len(),
        4,
        "two subpaths and two rects; the open polyline is skipped"
    );
    assert_eq!(shapes[1].points.len(), 3);
    // Only one top-level group: auto falls back to shapes.
    let auto = Curve::all_from_svg_bytes(svg, "s.svg", "s", SvgShapes::Auto).unwrap();
    assert_eq!(auto.len(), 4);
    // A group of two closed shapes is a drawing, not one key: refused,
    // naming its parts, never read as its first part.
    let e = Curve::all_from_svg_bytes(svg, "s.svg", "s", SvgShapes::Groups).unwrap_err();
    assert_eq!(
        e.to_string(),
        "s.svg (group 2): 2 closed shapes (path 1, path 2), not one curve; read it as a drawing (`immerse check`, `immerse morph`) or keep one shape"
    );
    let one = br#"<svg xmlns="http://www.w3.org/2000/svg">
        <g id="a"><rect x="0" y="20" width="5" height="5"/></g>
        <g id="b"><rect x="10" y="20" width="5" height="5"/><polyline points="0 40 5 40 5 45"/></g>
    </svg>"#;
    let groups = Curve::all_from_svg_bytes(one, "s.svg", "s", SvgShapes::Groups).unwrap();
    assert_eq!(groups.len(), 2);
    assert_eq!(groups[1].name, "s group 'b'");
    let e = Curve::all_from_svg_bytes(
        br#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L 1 0 L 2 0 Z"/></svg>"#,
        "flat.svg",
        "flat",
        SvgShapes::Shapes,
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "flat.svg (shape 1): all 3 points lie on one line (zero area); a curve must enclose a region"
    );
}

/// The example of the README: `animate` on the timeline in
/// curves/sequence, with hints at both ends of each stroke honoured and
/// the speed carried through the two unheld keys.
#[test]
fn the_example_sequence_honours_its_hints_and_keeps_its_speed() {
    let timeline = curve("sequence/ribbon-loops.json");
    let out = immerse(&[
        "animate",
        "--timeline",
        timeline.to_str().unwrap(),
        "--json",
        "-",
        "-q",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let frames = v["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 157, "6 s at 24 fps and a 0.5 s hold");
    let keys = v["keys"].as_array().unwrap();
    assert_eq!(keys[3]["frame"], 144);
    assert_eq!(keys[3]["hold"], 12);
    let point = |f: usize, i: usize| {
        let p = &frames[f]["points"][i];
        Point::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap())
    };
    let spec: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&timeline).unwrap()).unwrap();
    let n = frames[0]["points"].as_array().unwrap().len();
    for name in ["a", "b"] {
        // The vertex at hint `name` on key 1 is at it on every key
        // (snapped to the curve's vertex within 0.1% of its size).
        let at = |k: usize| {
            let h = &spec["keys"][k]["hints"][name];
            Point::new(h[0].as_f64().unwrap(), h[1].as_f64().unwrap())
        };
        let f0 = keys[0]["frame"].as_u64().unwrap() as usize;
        let v0 = (0..n)
            .min_by(|&i, &j| {
                (point(f0, i) - at(0))
                    .length()
                    .total_cmp(&(point(f0, j) - at(0)).length())
            })
            .unwrap();
        for (k, key) in keys.iter().enumerate() {
            let f = key["frame"].as_u64().unwrap() as usize;
            let d = (point(f, v0) - at(k)).length();
            assert!(d < 0.5, "hint {name} on key {}: {d} away", k + 1);
        }
    }
    for s in v["speeds"].as_array().unwrap() {
        assert!(s["not_continuous"].is_null(), "{s}");
        assert!(s["ratio"].as_f64().unwrap() <= 1.25, "{s}");
    }
}

/// Every other bad timeline or `animate` option: exit 2 (exit 1 for a key
/// that is not self-overlapping) and one line naming the file, the key and
/// the field (docs/bad-input.md).
#[test]
fn animate_timeline_errors_name_the_key_and_the_field() {
    let dir = timeline_dir();
    std::fs::copy(
        curve("figure-eight-n64.json"),
        dir.path().join("eight.json"),
    )
    .unwrap();
    std::fs::copy(curve("letter-C.svg"), dir.path().join("c.svg")).unwrap();
    let d = Some(dir.path());
    let cases: [(&str, &str, i32, &str); 11] = [
        (
            "field.json",
            r#"{"keys": ["curl-strip-n10.json", {"curve": "circular-strip-450deg-n60.json", "durration": 1}]}"#,
            2,
            "key 2: unknown field 'durration'; expected curve, shape, time, duration, hold, easing, hints",
        ),
        (
            "shape.json",
            r#"{"keys": ["curl-strip-n10.json", {"curve": "c.svg", "shape": 2}]}"#,
            2,
            "key 2: shape 2 does not exist; c.svg has 1 shape(s) as keys",
        ),
        (
            "both.json",
            r#"{"keys": [{"curve": "curl-strip-n10.json", "duration": 1}, {"curve": "circular-strip-450deg-n60.json", "time": 2}]}"#,
            2,
            "key 2 (circular-strip-450deg-n60.json): its time and a duration on the key before it (key 1 (curl-strip-n10.json)) both time the segment between them; give one of them",
        ),
        (
            "last.json",
            r#"{"keys": ["curl-strip-n10.json", {"curve": "circular-strip-450deg-n60.json", "duration": 1}]}"#,
            2,
            "key 2 (circular-strip-450deg-n60.json): the last key has no segment after it, so a duration 1 means nothing; remove it",
        ),
        (
            "early.json",
            r#"{"keys": ["curl-strip-n10.json", {"curve": "circular-strip-450deg-n60.json", "time": 0.01}]}"#,
            2,
            "key 2 (circular-strip-450deg-n60.json): at frame 0 it leaves too few frames after key 1 (curl-strip-n10.json) at frame 0 for 1 segment(s) of at least one step and their holds; give it a later time or a higher fps",
        ),
        (
            "count.json",
            r#"{"frames": 10, "keys": ["curl-strip-n10.json", {"curve": "circular-strip-450deg-n60.json", "time": 1}]}"#,
            2,
            "10 frames do not fit the timing: key 2 (circular-strip-450deg-n60.json) is at frame 30, so the sequence has 31 frames; leave out the frame count or change the times",
        ),
        (
            "hold.json",
            r#"{"keys": ["curl-strip-n10.json", {"curve": "circular-strip-450deg-n60.json", "hold": -0.5}]}"#,
            2,
            "key 2 (circular-strip-450deg-n60.json): hold -0.5 is not a number of seconds of at least 0",
        ),
        (
            "easing.json",
            r#"{"keys": ["curl-strip-n10.json", {"curve": "circular-strip-450deg-n60.json", "easing": "bounce"}]}"#,
            2,
            "key 2: invalid easing 'bounce': unknown name; expected linear, ease, ease-in, ease-out, ease-in-out or cubic-bezier(x1,y1,x2,y2) with x1 and x2 in [0,1]",
        ),
        (
            "fps.json",
            r#"{"fps": 0.001, "keys": ["curl-strip-n10.json", "circular-strip-450deg-n60.json"]}"#,
            2,
            "\"fps\" 0.001 is not a rate from 0.1 to 1000 frames per second",
        ),
        (
            "drawing.json",
            r#"{"keys": "c.svg"}"#,
            2,
            "c.svg: 1 closed shape found; a sequence needs at least 2 keys: draw each key as its own shape, group or layer",
        ),
        (
            "eight.json.timeline",
            r#"{"keys": ["curl-strip-n10.json", "eight.json"]}"#,
            1,
            "key 2 (eight.json) is not self-overlapping: turning number is 0, not 1",
        ),
    ];
    for (file, text, code, message) in cases {
        write(dir.path(), file, text);
        assert_stderr(
            d,
            &["animate", "--timeline", file, "-q"],
            code,
            &format!("immerse: {file}: {message}"),
        );
    }
    write(dir.path(), "bad.json", "{\"keys\": [\n");
    assert_stderr(
        d,
        &["animate", "--timeline", "bad.json"],
        2,
        "immerse: bad.json: 2:0: invalid JSON: EOF while parsing a list",
    );
    assert_stderr(
        d,
        &["animate", "--timeline", "nowhere.json"],
        2,
        "immerse: cannot read nowhere.json (check the path and permissions): No such file or directory (os error 2)",
    );
    let two = [
        "animate",
        "curl-strip-n10.json",
        "circular-strip-450deg-n60.json",
    ];
    for (flag, value, message) in [
        (
            "--hold",
            "-1",
            "--hold -1 is not a number of seconds of at least 0",
        ),
        (
            "--fps",
            "0",
            "--fps 0 is not a rate from 0.1 to 1000 frames per second",
        ),
    ] {
        let mut args = two.to_vec();
        args.extend([flag, value]);
        assert_stderr(d, &args, 2, &format!("immerse: {message}"));
    }
    let mut args = two.to_vec();
    args.extend(["--json", "out.json"]);
    write(dir.path(), "out.json", "{}");
    assert_stderr(
        d,
        &args,
        2,
        "immerse: output file out.json already exists; pass --force to overwrite it",
    );
}
