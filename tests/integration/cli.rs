//! The CLI through the real binary: facts on good curves, and every class
//! of bad input gives exit code 2 and exactly one documented stderr line
//! naming the file (the rows of docs/bad-input.md name these tests).

use crate::util::{LAST_LEG_RIVALS, assert_stderr, curve, immerse, immerse_in, stderr, stdout};

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
    let p = p.to_str().unwrap();
    assert_stderr(
        None,
        &["check", p],
        2,
        &format!(
            "immerse: {p}: only 2 distinct point(s) after dropping repeated points; a curve needs at least 3"
        ),
    );
}

#[test]
fn nan_coordinate_names_the_line() {
    let p = curve("degenerate-nan.txt");
    let p = p.to_str().unwrap();
    assert_stderr(
        None,
        &["check", p],
        2,
        &format!("immerse: {p}:4: non-finite coordinate in 'nan 1'; give finite numbers"),
    );
}

#[test]
fn infinite_coordinate_and_out_of_range() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("inf.txt"), "0 0\n1 0\ninf 1\n").unwrap();
    assert_stderr(
        Some(dir.path()),
        &["check", "inf.txt"],
        2,
        "immerse: inf.txt:3: non-finite coordinate in 'inf 1'; give finite numbers",
    );
    std::fs::write(dir.path().join("big.json"), "[[0,0],[1,0],[1e300,1]]").unwrap();
    assert_stderr(
        Some(dir.path()),
        &["check", "big.json"],
        2,
        "immerse: big.json: point 2 (counting from 0) has a coordinate of magnitude 1e300, outside [1e-30, 1e30]; rescale the curve",
    );
}

#[test]
fn zero_area() {
    let p = curve("degenerate-collinear.json");
    let p = p.to_str().unwrap();
    assert_stderr(
        None,
        &["check", p],
        2,
        &format!(
            "immerse: {p}: all 6 points lie on one line (zero area); a curve must enclose a region"
        ),
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
    assert_stderr(
        Some(dir.path()),
        &["check", "open.svg"],
        2,
        "immerse: open.svg: no closed shape found; draw a closed path (ending in Z), polygon, rect, circle or ellipse",
    );
}

#[test]
fn unknown_extension() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("curve.dat"), "0 0\n1 0\n0 1\n").unwrap();
    assert_stderr(
        Some(dir.path()),
        &["check", "curve.dat"],
        2,
        "immerse: curve.dat: unknown curve format 'dat'; use .json (points array), .txt (x y per line) or .svg",
    );
}

#[test]
fn missing_file() {
    assert_stderr(
        None,
        &["check", "no/such/curve.json"],
        2,
        "immerse: cannot read no/such/curve.json (check the path and permissions): No such file or directory (os error 2)",
    );
}

#[test]
fn unreadable_inputs() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("folder.json")).unwrap();
    assert_stderr(
        Some(dir.path()),
        &["check", "folder.json"],
        2,
        "immerse: folder.json is a folder, not a curve file; name a .json, .txt or .svg file",
    );
    std::fs::write(
        dir.path().join("broken.json"),
        "{\"points\": [[0, 0], [1,\n",
    )
    .unwrap();
    assert_stderr(
        Some(dir.path()),
        &["check", "broken.json"],
        2,
        "immerse: broken.json:2:1: invalid JSON: EOF while parsing a value",
    );
    std::fs::write(
        dir.path().join("shape.json"),
        r#"{"points": [[0, 0], [1], [2, 2]]}"#,
    )
    .unwrap();
    assert_stderr(
        Some(dir.path()),
        &["check", "shape.json"],
        2,
        r#"immerse: shape.json: point 1 is [1], not an [x, y] pair of numbers; expected {"points": [[x, y], ...]} or a bare array of [x, y] pairs"#,
    );
    std::fs::write(dir.path().join("bin.txt"), [0xff, 0xfe, b'\n']).unwrap();
    assert_stderr(
        Some(dir.path()),
        &["check", "bin.txt"],
        2,
        "immerse: bin.txt:1: not UTF-8 text; save the file as plain text",
    );
    std::fs::write(dir.path().join("bad.svg"), "<svg").unwrap();
    assert_stderr(
        Some(dir.path()),
        &["check", "bad.svg"],
        2,
        "immerse: bad.svg: not a readable SVG: SVG data parsing failed cause the document does not have a root node",
    );
}

#[test]
fn usage_errors_exit_2() {
    let out = immerse(&["check"]);
    assert_eq!(out.status.code(), Some(2));
    let out = immerse(&["frobnicate"]);
    assert_eq!(out.status.code(), Some(2));
}

/// The experimental paths and correspondences are refused in a default
/// build (exit 2, before any file is read), naming the offered values,
/// and `--help` lists only the offered ones; every offered one morphs.
#[test]
#[cfg(not(feature = "experimental"))]
fn experimental_options_are_refused_naming_the_offered_ones() {
    let (a, b) = (curve("triangle.json"), curve("square.json"));
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    for (flag, value, offered) in [
        ("--path", "polar", "rigid, hybrid, straight"),
        ("--path", "rotate-slide", "rigid, hybrid, straight"),
        ("--correspondence", "identity", "corners, min-flips, best"),
        ("--correspondence", "outline", "corners, min-flips, best"),
    ] {
        for command in ["morph", "animate"] {
            let out = immerse(&[command, a, b, flag, value]);
            assert_eq!(out.status.code(), Some(2), "{command} {flag} {value}");
            let e = stderr(&out);
            assert!(
                e.contains(&format!("'{value}' is experimental")) && e.contains(offered),
                "{command} {flag} {value}: {e}"
            );
        }
    }
    let help = String::from_utf8_lossy(&immerse(&["morph", "--help"]).stdout).into_owned();
    for hidden in [
        "- polar",
        "- angle",
        "- rotate-slide",
        "- linear",
        "- pivot",
        "- identity",
    ] {
        assert!(!help.contains(hidden), "--help lists {hidden}");
    }
    for shown in [
        "- rigid",
        "- straight",
        "- hybrid",
        "- corners",
        "- min-flips",
        "- best",
    ] {
        assert!(help.contains(shown), "--help misses {shown}");
    }
    for (flag, value) in [
        ("--path", "rigid"),
        ("--path", "straight"),
        ("--path", "hybrid"),
        ("--correspondence", "corners"),
        ("--correspondence", "min-flips"),
    ] {
        let out = immerse(&["morph", a, b, flag, value]);
        assert_eq!(
            out.status.code(),
            Some(0),
            "{flag} {value}: {}",
            stderr(&out)
        );
    }
}

#[test]
fn morph_writes_verified_json_frames() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (
        curve("letter-E.json"),
        curve("spiral-strip-400deg-n30.json"),
    );
    let args = [
        "morph",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "--frames",
        "12",
        "--json",
        "m.json",
    ];
    let out = immerse_in(dir.path(), &args);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("m.json")).unwrap()).unwrap();
    // The default path; the last leg may take another path where its
    // vertices travel less ("rigid+straight").
    let path = v["path"].as_str().unwrap();
    assert!(
        path.split('+').all(|p| LAST_LEG_RIVALS.contains(&p)) && path.starts_with("rigid"),
        "{path}"
    );
    assert_eq!(v["fallback"], false);
    assert_eq!(v["fallbacks"].as_array().map(Vec::len), Some(0));
    let frames = v["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 12);
    let n = frames[0]["points"].as_array().unwrap().len();
    for f in frames {
        let pts: Vec<immerse::Point> = f["points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| immerse::Point::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
            .collect();
        let tris: Vec<[u32; 3]> = serde_json::from_value(f["triangles"].clone()).unwrap();
        assert_eq!(pts.len(), n);
        assert!(immerse::check(&pts, &tris).is_ok(), "t = {}", f["t"]);
    }
    // The motion measures, recomputed here from the frames written: the
    // mean path over the least mean end-to-end distance (any cyclic
    // shift), and the least total absolute turning over the ends' least.
    let points = |f: &serde_json::Value| -> Vec<(f64, f64)> {
        f["points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
            .collect()
    };
    let all: Vec<Vec<(f64, f64)>> = frames.iter().map(points).collect();
    let dist = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).hypot(a.1 - b.1);
    let path: f64 = all
        .windows(2)
        .map(|w| (0..n).map(|i| dist(w[0][i], w[1][i])).sum::<f64>())
        .sum();
    let (first, last) = (&all[0], &all[all.len() - 1]);
    let straight = (0..n)
        .map(|k| {
            (0..n)
                .map(|i| dist(first[i], last[(i + k) % n]))
                .sum::<f64>()
        })
        .fold(f64::INFINITY, f64::min);
    let turning = |p: &[(f64, f64)]| -> f64 {
        (0..n)
            .map(|i| {
                let (a, b, c) = (p[(i + n - 1) % n], p[i], p[(i + 1) % n]);
                let (u, v) = ((b.0 - a.0, b.1 - a.1), (c.0 - b.0, c.1 - b.1));
                (u.0 * v.1 - u.1 * v.0).atan2(u.0 * v.0 + u.1 * v.1).abs()
            })
            .sum()
    };
    let least = all.iter().map(|p| turning(p)).fold(f64::INFINITY, f64::min);
    let ends = turning(first).min(turning(last));
    let detour = v["motion"]["detour"].as_f64().unwrap();
    let unwind = v["motion"]["unwind"].as_f64().unwrap();
    assert!((detour - path / straight).abs() < 1e-9 * detour, "{detour}");
    assert!((unwind - least / ends).abs() < 1e-9, "{unwind}");
    assert!(
        (1.0..3.0).contains(&detour) && unwind >= 0.9,
        "{detour} {unwind}"
    );
    // --metrics prints the same measures.
    let out = immerse_in(
        dir.path(),
        &[
            "morph",
            a.to_str().unwrap(),
            b.to_str().unwrap(),
            "--frames",
            "12",
            "--metrics",
        ],
    );
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        text.contains(&format!("detour               {detour:.2} ("))
            && text.contains(&format!("unwind               {unwind:.2} (")),
        "{text}"
    );
    // A second run refuses to overwrite the file without --force.
    let again = immerse_in(dir.path(), &args);
    assert_eq!(again.status.code(), Some(2));
    assert!(
        stderr(&again).contains("m.json already exists; pass --force"),
        "{}",
        stderr(&again)
    );
    let mut forced = args.to_vec();
    forced.push("--force");
    assert_eq!(immerse_in(dir.path(), &forced).status.code(), Some(0));
}

#[test]
fn morph_with_a_curve_that_is_not_self_overlapping_exits_1() {
    let (a, b) = (curve("letter-E.json"), curve("figure-eight-n64.json"));
    let out = immerse(&["morph", a.to_str().unwrap(), b.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(err.contains("figure-eight-n64.json: the target curve is not self-overlapping: turning number is 0, not 1"), "{err}");
}

#[test]
fn demo_runs_twice_and_never_touches_foreign_files() {
    let dir = tempfile::tempdir().unwrap();
    let args = ["demo", "--frames", "6", "--size", "64x64", "-q"];
    for _ in 0..2 {
        let out = immerse_in(dir.path(), &args);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    }
    let demo = dir.path().join("immerse-demo");
    assert!(demo.join("demo.gif").is_file());
    assert!(demo.join("frame_0005.png").is_file());
    std::fs::write(demo.join("notes.txt"), "mine").unwrap();
    let out = immerse_in(dir.path(), &args);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("holds files the demo did not write"));
    assert_eq!(
        std::fs::read_to_string(demo.join("notes.txt")).unwrap(),
        "mine"
    );
}

#[test]
fn check_says_why_a_curve_is_not_self_overlapping() {
    let p = curve("turning-one-not-self-overlapping-n9.json");
    let out = immerse(&["check", p.to_str().unwrap(), "--json"]);
    assert_eq!(out.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["self_overlapping"], false);
    assert_eq!(v["turning_number"], 1);
    assert_eq!(
        v["reason"],
        "no triangulation of the disk by valid triangles exists"
    );
}

fn mesh(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("meshes")
        .join(name)
}

#[test]
fn mesh_morph_reports_the_linear_fold_and_the_convex_morph_stays_valid() {
    let (a, b) = (mesh("fg_4_3_a.json"), mesh("fg_4_3_b.json"));
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    let out = immerse(&["mesh-morph", a, b, "--check-linear"]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stdout(&out).contains("the linear morph is not valid"),
        "{}",
        stdout(&out)
    );
    let frames = |method: &str| -> Vec<serde_json::Value> {
        let out = immerse(&[
            "mesh-morph",
            a,
            b,
            "--method",
            method,
            "--frames",
            "41",
            "--json",
            "-",
            "-q",
        ]);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["method"], method);
        v["frames"].as_array().unwrap().clone()
    };
    // The linear morph degenerates at t = 1/2 (frame 20 of 41), and only there.
    let linear = frames("linear");
    let invalid: Vec<f64> = linear
        .iter()
        .filter(|f| f["valid"] == false)
        .map(|f| f["t"].as_f64().unwrap())
        .collect();
    assert_eq!(invalid, vec![0.5]);
    for method in ["convex", "intrinsic", "power", "local"] {
        let fs = frames(method);
        assert_eq!(fs.len(), 41);
        assert!(fs.iter().all(|f| f["valid"] == true), "{method}");
        assert!(fs[0]["faces"].is_array());
    }
}

#[test]
fn mesh_morph_check_linear_accepts_a_valid_linear_morph() {
    // A tiling morphed into itself moves nothing: the linear morph is valid.
    let a = mesh("grid6_a.obj");
    let a = a.to_str().unwrap();
    let out = immerse(&["mesh-morph", a, a, "--check-linear"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        stdout(&out).starts_with("the linear morph is valid"),
        "{}",
        stdout(&out)
    );
}

#[test]
fn curves_too_large_for_the_dp_are_refused_with_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let n = 20_001;
    write_polygon(&dir.path().join("big.json"), n);
    let out = immerse_in(dir.path(), &["check", "big.json"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("big.json: 20001 points is more than the 20000"),
        "{}",
        stderr(&out)
    );
    // The max–min DP has its own, lower limit.
    let m = 4_001;
    write_polygon(&dir.path().join("mid.json"), m);
    let out = immerse_in(
        dir.path(),
        &["triangulate", "mid.json", "--quality", "maxmin"],
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("4001 points is more than the 4000"),
        "{}",
        stderr(&out)
    );
    // Within the point limit, a nearly convex curve whose max–min DP would
    // weigh too many candidate triangles is refused before the DP runs.
    let m = 3000;
    write_polygon(&dir.path().join("busy.json"), m);
    let out = immerse_in(
        dir.path(),
        &["triangulate", "busy.json", "--quality", "maxmin"],
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("busy.json: this curve needs ")
            && stderr(&out).contains(
                " candidate triangles for the max–min triangulation; the limit is 1,500,000,000 \
                 (about 10 s on 2 cores); use --quality delaunay"
            ),
        "{}",
        stderr(&out)
    );
}

#[test]
fn morph_refuses_more_frame_points_than_it_keeps_in_memory() {
    let dir = tempfile::tempdir().unwrap();
    let pts: Vec<[f64; 2]> = (0..600)
        .map(|i| {
            let a = std::f64::consts::TAU * f64::from(i) / 600.0;
            [a.cos(), a.sin()]
        })
        .collect();
    std::fs::write(
        dir.path().join("c.json"),
        serde_json::to_string(&pts).unwrap(),
    )
    .unwrap();
    let out = immerse_in(
        dir.path(),
        &["morph", "c.json", "c.json", "--frames", "100000"],
    );
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        stderr(&out).trim_end(),
        "immerse: 100000 frames of 600 points is more than 50000000 points in all; ask for fewer --frames"
    );
}

#[test]
fn triangulate_json_has_the_design_fields_and_a_valid_triangulation() {
    let p = curve("spiral-strip-540deg-n120-clockwise.json");
    for quality in ["any", "delaunay", "maxmin"] {
        let out = immerse(&[
            "triangulate",
            p.to_str().unwrap(),
            "--json",
            "--quality",
            quality,
        ]);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let pts: Vec<immerse::Point> = v["points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|q| immerse::Point::new(q[0].as_f64().unwrap(), q[1].as_f64().unwrap()))
            .collect();
        let tris: Vec<[u32; 3]> = serde_json::from_value(v["triangles"].clone()).unwrap();
        assert_eq!(pts.len(), 120);
        assert_eq!(tris.len(), 118);
        // Oriented order (the file is clockwise) and every triangle CCW.
        assert_eq!(v["reversed"], true);
        assert_eq!(
            immerse::geom::polygon::turning_number(&pts),
            immerse::geom::polygon::Turning::Number(1)
        );
        assert!(immerse::check(&pts, &tris).is_ok(), "{quality}");
        // The spine runs between two leaves; the pivot vertex is a corner
        // of its first triangle; the root is a triangle.
        let spine: Vec<usize> = serde_json::from_value(v["spine"].clone()).unwrap();
        assert!(spine.len() >= 2);
        let pivot = v["pivot_vertex"].as_u64().unwrap() as u32;
        assert!(tris[spine[0]].contains(&pivot));
        assert!((v["root_triangle"].as_u64().unwrap() as usize) < tris.len());
    }
}

/// Writes a regular `m`-gon (a convex curve) as a JSON point list.
fn write_polygon(path: &std::path::Path, m: usize) {
    let pts: Vec<[f64; 2]> = (0..m)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / m as f64;
            [a.cos(), a.sin()]
        })
        .collect();
    std::fs::write(path, serde_json::to_string(&pts).unwrap()).unwrap();
}

/// Every input is read through its size cap: a curve, timeline or mesh
/// file that is a link to `/dev/zero` stops at the cap with exit 2, where
/// a length check alone would read without end; a FIFO that a writer
/// fills after the command has started is read whole.
#[cfg(unix)]
#[test]
fn inputs_are_read_through_a_cap_devices_and_fifos_included() {
    use std::os::unix::fs::symlink;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for name in [
        "zero.json",
        "zero.svg",
        "zero.txt",
        "timeline.json",
        "mesh.obj",
    ] {
        symlink("/dev/zero", d.join(name)).unwrap();
    }
    let curve_cap = immerse::curve::MAX_FILE_BYTES;
    for name in ["zero.json", "zero.svg", "zero.txt"] {
        assert_stderr(
            Some(d),
            &["check", name],
            2,
            &format!(
                "immerse: {name}: too large (more than {curve_cap} bytes; the limit is {curve_cap} bytes); simplify the curve first"
            ),
        );
    }
    assert_stderr(
        Some(d),
        &["animate", "--timeline", "timeline.json"],
        2,
        "immerse: timeline.json: too large (more than 16777216 bytes; the limit is 16777216 bytes)",
    );
    let mesh_cap = immerse_mesh::tiling::MAX_FILE_BYTES;
    assert_stderr(
        Some(d),
        &["mesh-morph", "mesh.obj", "mesh.obj", "--check-linear"],
        2,
        &format!(
            "immerse: mesh.obj: too large (more than {mesh_cap} bytes; the limit is {mesh_cap} bytes)"
        ),
    );

    // A FIFO: the command waits for a writer, then reads to the end.
    let fifo = d.join("later.json");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("mkfifo runs");
    assert!(made.success());
    let reader = std::process::Command::new(env!("CARGO_BIN_EXE_immerse"))
        .args(["check", fifo.to_str().unwrap(), "--json"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(300));
    let square = std::fs::read(curve("triangle.json")).unwrap();
    std::fs::write(&fifo, &square).unwrap();
    let out = reader.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["self_overlapping"], true);
}
