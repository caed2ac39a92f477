//! Outputs a user can trust: where bytes go (stdout, special
//! files, links), checks before any work, no partial output on an
//! interrupt, no stale frames, one rule for `-o`, contact-sheet grids, one
//! `--json [FILE]` convention, clear messages, and immerse's own SVG read
//! back. Every test runs the real binary in a temporary folder.

use crate::util::{assert_stderr, curve, immerse_in, stderr, stdout};
use std::path::Path;

/// The reference triangle, as an absolute path.
fn tri() -> String {
    curve("triangle.json").to_str().unwrap().to_string()
}

/// The entries of `dir` whose names start with `.immerse-` (temporary
/// files and folders).
fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".immerse-"))
        .collect()
}

/// Sorted file names in `dir`.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

// ---- item 1: stdout, special files and symbolic links ----------------------

/// `--json /dev/stdout` was refused ("exists; pass --force"), steering users
/// into `--force`, which then renamed a file over the device.
#[test]
fn json_to_dev_stdout_or_dash_prints_on_stdout() {
    let d = tempfile::tempdir().unwrap();
    let t = tri();
    for target in ["/dev/stdout", "-"] {
        let out = immerse_in(
            d.path(),
            &["morph", &t, &t, "--frames", "3", "--json", target, "-q"],
        );
        assert_eq!(out.status.code(), Some(0), "{target}: {}", stderr(&out));
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["frames"].as_array().unwrap().len(), 3, "{target}");
    }
    assert!(names(d.path()).is_empty(), "nothing written to the folder");
}

/// With `--force` a special file (here a FIFO, as /dev/null is for root)
/// was replaced by a regular file, and a symbolic link by the file instead
/// of the file it points to.
#[cfg(unix)]
#[test]
fn force_writes_through_special_files_and_follows_links() {
    use std::os::unix::fs::FileTypeExt;
    let d = tempfile::tempdir().unwrap();
    let t = tri();
    let fifo = d.path().join("pipe.json");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(made.success());
    let (tx, rx) = std::sync::mpsc::channel();
    let reader_path = fifo.clone();
    std::thread::spawn(move || {
        let _ = tx.send(std::fs::read(reader_path));
    });
    let out = immerse_in(
        d.path(),
        &[
            "morph",
            &t,
            &t,
            "--frames",
            "2",
            "--json",
            "pipe.json",
            "--force",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        std::fs::symlink_metadata(&fifo)
            .unwrap()
            .file_type()
            .is_fifo(),
        "the FIFO is still a FIFO"
    );
    let read = rx
        .recv_timeout(std::time::Duration::from_secs(30))
        .expect("the reader got the data")
        .unwrap();
    let v: serde_json::Value = serde_json::from_slice(&read).unwrap();
    assert_eq!(v["frames"].as_array().unwrap().len(), 2);

    // A link is followed: the file it points to is replaced, the link stays.
    std::fs::write(d.path().join("real.json"), "old").unwrap();
    std::os::unix::fs::symlink("real.json", d.path().join("link.json")).unwrap();
    assert_stderr(
        Some(d.path()),
        &["morph", &t, &t, "--frames", "2", "--json", "link.json"],
        2,
        "immerse: output file link.json already exists; pass --force to overwrite it",
    );
    let out = immerse_in(
        d.path(),
        &[
            "morph",
            &t,
            &t,
            "--frames",
            "2",
            "--json",
            "link.json",
            "--force",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let link = std::fs::symlink_metadata(d.path().join("link.json")).unwrap();
    assert!(link.file_type().is_symlink(), "the link is still a link");
    let real = std::fs::read_to_string(d.path().join("real.json")).unwrap();
    assert!(real.starts_with('{'), "{real}");
    // A special file needs no --force (nothing is replaced).
    let out = immerse_in(d.path(), &["check", &t, "--json=/dev/null"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(temporaries(d.path()).is_empty());
}

// ---- item 2: every output is checked before any work -----------------------

/// An existing `-o` file, a missing output folder or a contact sheet too
/// large was found only after the morph was computed. Each is now refused
/// before the curves are even read (here: a missing curve file, which
/// would otherwise be the error).
#[test]
fn outputs_are_checked_before_any_work() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("exists.gif"), "keep").unwrap();
    std::fs::write(d.path().join("plain"), "a file").unwrap();
    let dp = Some(d.path());
    let m = "missing.json";
    assert_stderr(
        dp,
        &["morph", m, m, "-o", "exists.gif"],
        2,
        "immerse: output file exists.gif already exists; pass --force to overwrite it",
    );
    assert_stderr(
        dp,
        &["morph", m, m, "-o", "nodir/anim.gif"],
        2,
        "immerse: cannot write nodir/anim.gif: there is no folder nodir; create it first",
    );
    assert_stderr(
        dp,
        &["morph", m, m, "-o", "nodir/frames"],
        2,
        "immerse: cannot write nodir/frames: there is no folder nodir; create it first",
    );
    assert_stderr(
        dp,
        &["morph", m, m, "--json", "plain/m.json"],
        2,
        "immerse: cannot write plain/m.json: there is no folder plain; create it first",
    );
    assert_stderr(
        dp,
        &["morph", m, m, "--frames", "2000", "-o", "sheet.png"],
        2,
        "immerse: a contact sheet of 2000 frames in 45 columns would be 27000x27000 pixels, over the limit of 67108864 pixels; use fewer frames or a smaller size",
    );
    assert_stderr(
        dp,
        &["triangulate", m, "-o", "exists.gif"],
        2,
        "immerse: exists.gif: unknown image type; name a .png or .svg file",
    );
    assert_stderr(
        dp,
        &["check", m, "--json=nodir/c.json"],
        2,
        "immerse: cannot write nodir/c.json: there is no folder nodir; create it first",
    );
    assert_eq!(std::fs::read(d.path().join("exists.gif")).unwrap(), b"keep");
    assert!(temporaries(d.path()).is_empty());
}

/// An unwritable folder is found up front too, and the message names the
/// output, never a temporary file. (As root, permissions do not stop
/// writes; /proc refuses new files to everyone.)
#[cfg(target_os = "linux")]
#[test]
fn unwritable_folders_are_found_first_and_no_temporary_name_shows() {
    let d = tempfile::tempdir().unwrap();
    let out = immerse_in(
        d.path(),
        &[
            "morph",
            "missing.json",
            "missing.json",
            "-o",
            "/proc/anim.gif",
        ],
    );
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.starts_with("immerse: cannot write /proc/anim.gif: "),
        "{err}"
    );
    assert!(!err.contains(".immerse-") && !err.contains(".tmp"), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
}

// ---- item 3: an interrupt leaves no partial output -------------------------

/// Runs `args` in `dir`, waits until a temporary output appears, sends
/// SIGINT and returns the exit status.
#[cfg(unix)]
fn interrupt_when_writing(dir: &Path, args: &[&str]) -> std::process::ExitStatus {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_immerse"))
        .args(args)
        .current_dir(dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    while temporaries(dir).is_empty() {
        assert!(
            child.try_wait().unwrap().is_none(),
            "finished before it could be interrupted"
        );
        assert!(start.elapsed().as_secs() < 120, "no temporary output seen");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let killed = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("immerse: interrupted"), "{err}");
    out.status
}

/// Ctrl-C during a PNG sequence left a partial folder, during a GIF (or a
/// large --json) a hidden `.immerse-*.tmp` file. Now both are removed and
/// the exit code is 130.
#[cfg(unix)]
#[test]
fn an_interrupt_removes_partial_outputs_and_exits_130() {
    let t = tri();
    let d = tempfile::tempdir().unwrap();
    let status = interrupt_when_writing(
        d.path(),
        &[
            "morph",
            &t,
            &t,
            "--frames",
            "3000",
            "--size",
            "1200x1200",
            "-o",
            "frames",
        ],
    );
    assert_eq!(status.code(), Some(130));
    assert!(names(d.path()).is_empty(), "{:?}", names(d.path()));

    // Into an existing folder (--force): the old frames stay as they were.
    let d = tempfile::tempdir().unwrap();
    let kept = d.path().join("kept");
    std::fs::create_dir(&kept).unwrap();
    std::fs::write(kept.join("frame_0000.png"), "old").unwrap();
    let status = interrupt_when_writing(
        &kept,
        &[
            "morph",
            &t,
            &t,
            "--frames",
            "3000",
            "--size",
            "1200x1200",
            "-o",
            ".",
            "--force",
        ],
    );
    assert_eq!(status.code(), Some(130));
    assert_eq!(names(&kept), ["frame_0000.png"]);
    assert_eq!(std::fs::read(kept.join("frame_0000.png")).unwrap(), b"old");

    let d = tempfile::tempdir().unwrap();
    let status = interrupt_when_writing(
        d.path(),
        &[
            "morph", &t, &t, "--frames", "3000", "--size", "800x800", "-o", "anim.gif",
        ],
    );
    assert_eq!(status.code(), Some(130));
    assert!(names(d.path()).is_empty(), "{:?}", names(d.path()));
}

// ---- item 4: no stale frames -----------------------------------------------

/// `demo -o d`, then `demo -o d --frames 3`, left the higher-numbered frames
/// of the first run (which ffmpeg then picks up); so did `morph -o frames
/// --force` with fewer frames.
#[test]
fn fewer_frames_leave_no_stale_frames() {
    let d = tempfile::tempdir().unwrap();
    let demo = |frames: &str| {
        let out = immerse_in(
            d.path(),
            &[
                "demo", "-o", "show", "--frames", frames, "--size", "32x32", "-q",
            ],
        );
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    };
    demo("6");
    demo("3");
    assert_eq!(
        names(&d.path().join("show")),
        [
            ".immerse-demo",
            "demo.gif",
            "frame_0000.png",
            "frame_0001.png",
            "frame_0002.png"
        ]
    );
    let t = tri();
    let morph = |frames: &str| {
        immerse_in(
            d.path(),
            &[
                "morph", &t, &t, "--frames", frames, "--size", "32x32", "-o", "f", "--force",
            ],
        )
    };
    assert_eq!(morph("5").status.code(), Some(0));
    std::fs::write(d.path().join("f/notes.txt"), "mine").unwrap();
    assert_eq!(morph("2").status.code(), Some(0));
    assert_eq!(
        names(&d.path().join("f")),
        ["frame_0000.png", "frame_0001.png", "notes.txt"]
    );
    assert!(temporaries(d.path()).is_empty());
}

// ---- item 5: one rule for -o -----------------------------------------------

/// An unknown extension (`anim.mp4`, `out.jpg`) or `-` silently became a
/// folder of PNG frames.
#[test]
fn one_rule_for_image_outputs() {
    let d = tempfile::tempdir().unwrap();
    let t = tri();
    let dp = Some(d.path());
    let formats = "name a .gif, .svg (animated), .png (contact sheet) or .lottie.json file, or a folder (no extension, or ending in /) for PNG frames";
    for (out, ext) in [("anim.mp4", "mp4"), ("out.jpg", "jpg")] {
        assert_stderr(
            dp,
            &["morph", &t, &t, "--frames", "2", "-o", out],
            2,
            &format!("immerse: -o {out}: unknown image type '.{ext}'; {formats}"),
        );
    }
    assert_stderr(
        dp,
        &["morph", &t, &t, "--frames", "2", "-o", "-"],
        2,
        "immerse: -o -: standard output takes one file; add --format gif, animated-svg, sheet or lottie",
    );
    assert_stderr(
        dp,
        &[
            "morph", &t, &t, "--frames", "2", "-o", "x.png", "--format", "gif",
        ],
        2,
        "immerse: -o x.png: --format gif writes a .gif file, not .png; name the file .gif",
    );
    assert_stderr(
        dp,
        &[
            "morph", &t, &t, "--frames", "2", "-o", "x.png", "--format", "png",
        ],
        2,
        "immerse: -o x.png: --format png writes a folder of frames; name a folder without an extension (or ending in /)",
    );
    assert_stderr(
        dp,
        &["mesh-morph", "a.obj", "b.obj", "-o", "anim.mp4"],
        2,
        &format!("immerse: -o anim.mp4: unknown image type '.mp4'; {formats}"),
    );
    assert!(names(d.path()).is_empty(), "{:?}", names(d.path()));
    // `-` with a single-file format is standard output.
    let out = immerse_in(
        d.path(),
        &[
            "morph", &t, &t, "--frames", "2", "--size", "16x16", "-o", "-", "--format", "gif",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(out.stdout.starts_with(b"GIF89a"));
    // Folders: no extension, or a trailing slash.
    for dir in ["plain", "dotted.d/"] {
        let out = immerse_in(
            d.path(),
            &[
                "morph", &t, &t, "--frames", "2", "--size", "16x16", "-o", dir,
            ],
        );
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        assert_eq!(
            names(&d.path().join(dir)),
            ["frame_0000.png", "frame_0001.png"]
        );
    }
}

// ---- item 6: contact sheets are grids ---------------------------------------

/// The contact sheet was one row (60 frames at 600 px: 36,000 × 600).
#[test]
fn contact_sheets_are_grids() {
    let d = tempfile::tempdir().unwrap();
    let t = tri();
    let size = |name: &str| {
        let decoder = png::Decoder::new(std::io::BufReader::new(
            std::fs::File::open(d.path().join(name)).unwrap(),
        ));
        let reader = decoder.read_info().unwrap();
        (reader.info().width, reader.info().height)
    };
    let args = ["morph", &t, &t, "--frames", "60", "--size", "20x10", "-o"];
    let out = immerse_in(d.path(), &[&args[..], &["sheet.png"]].concat());
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(size("sheet.png"), (160, 80));
    let out = immerse_in(
        d.path(),
        &[&args[..], &["cols.png", "--columns", "5"]].concat(),
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(size("cols.png"), (100, 120));
    assert_stderr(
        Some(d.path()),
        &[&args[..], &["anim.gif", "--columns", "5"]].concat(),
        2,
        "immerse: --columns lays out a contact sheet; add --format sheet or name a .png file",
    );
    // --size stops where the renderer stops.
    let out = immerse_in(d.path(), &["morph", &t, &t, "--size", "16384x16384"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("'16384' in '16384x16384' is not a size from 1 to 8192"),
        "{}",
        stderr(&out)
    );
}

// ---- item 7: messages ------------------------------------------------------

/// A UTF-8 byte order mark gave "'0' is not a number" or "invalid JSON".
#[test]
fn a_byte_order_mark_is_accepted() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("bom.txt"), "\u{feff}0 0\n1 0\n0 1\n").unwrap();
    std::fs::write(d.path().join("bom.json"), "\u{feff}[[0,0],[1,0],[0,1]]").unwrap();
    std::fs::write(
        d.path().join("bom.svg"),
        "\u{feff}<svg xmlns=\"http://www.w3.org/2000/svg\"><polygon points=\"0,0 0,1 1,0\"/></svg>",
    )
    .unwrap();
    for f in ["bom.txt", "bom.json", "bom.svg"] {
        let out = immerse_in(d.path(), &["check", f]);
        assert_eq!(out.status.code(), Some(0), "{f}: {}", stderr(&out));
        assert!(stdout(&out).contains("points:         3"), "{f}");
    }
}

/// An SVG whose transform puts coordinates out of range said "no closed
/// shape found".
#[test]
fn svg_coordinates_out_of_range_after_a_transform_are_named() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(
        d.path().join("huge.svg"),
        r#"<svg xmlns="http://www.w3.org/2000/svg"><g transform="scale(1e39)"><polygon points="0,0 1,0 0,1"/></g></svg>"#,
    )
    .unwrap();
    assert_stderr(
        Some(d.path()),
        &["check", "huge.svg"],
        2,
        "immerse: huge.svg: the shape's coordinates are not finite or too large after its transforms are applied; rescale the drawing",
    );
}

/// Every SVG rect and circle (drawn clockwise on screen, as SVG does)
/// triggered the "drawn clockwise; reversed" notice; a reversal that is the
/// format's convention is not news. Other formats still get it.
#[test]
fn no_reversal_notice_for_svg_shapes() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(
        d.path().join("rect.svg"),
        r#"<svg xmlns="http://www.w3.org/2000/svg"><rect x="0" y="0" width="4" height="3"/></svg>"#,
    )
    .unwrap();
    std::fs::write(
        d.path().join("circle.svg"),
        r#"<svg xmlns="http://www.w3.org/2000/svg"><circle cx="0" cy="0" r="2"/></svg>"#,
    )
    .unwrap();
    let out = immerse_in(
        d.path(),
        &["morph", "rect.svg", "circle.svg", "--frames", "2"],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(
        stderr(&out),
        "immerse: 2 keyframes (every segment between them certified), 2 frames computed and verified; pass --json FILE or -o PATH to keep them\n"
    );
    let cw = curve("spiral-strip-540deg-n120-clockwise.json");
    let out = immerse_in(
        d.path(),
        &["morph", cw.to_str().unwrap(), "rect.svg", "--frames", "2"],
    );
    assert!(
        stderr(&out).contains("is drawn clockwise; reversed it"),
        "{}",
        stderr(&out)
    );
}

/// `demo -o existing-file --force` failed with "File exists (os error 17)".
#[test]
fn demo_into_a_file_says_what_to_do() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("taken"), "mine").unwrap();
    for force in [false, true] {
        let mut args = vec!["demo", "-o", "taken", "-q"];
        if force {
            args.push("--force");
        }
        assert_stderr(
            Some(d.path()),
            &args,
            2,
            "immerse: taken exists and is not a folder; choose another -o",
        );
    }
    assert_eq!(std::fs::read(d.path().join("taken")).unwrap(), b"mine");
}

/// `mesh-morph` printed the cause of its error twice.
#[test]
fn mesh_morph_errors_are_said_once() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("bad.json"), "{").unwrap();
    let out = immerse_in(d.path(), &["mesh-morph", "bad.json", "bad.json"]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert_eq!(err.lines().count(), 1, "{err}");
    let body = err.trim_end().trim_start_matches("immerse: ");
    // No clause appears twice.
    let parts: Vec<&str> = body.split(": ").collect();
    for (i, p) in parts.iter().enumerate() {
        assert!(!parts[i + 1..].contains(p), "repeated '{p}' in {err}");
    }
}

/// GIF frame rates above 50 fps were silently capped at 50.
#[test]
fn gif_rates_above_50_fps_are_refused() {
    let d = tempfile::tempdir().unwrap();
    assert_stderr(
        Some(d.path()),
        &[
            "morph",
            "missing.json",
            "missing.json",
            "-o",
            "a.gif",
            "--fps",
            "60",
        ],
        2,
        "immerse: --fps 60: a gif plays at most 50 frames per second (its frame delays are whole hundredths of a second, and browsers slow down delays under 2), not 60; ask for 50 or fewer, or write png frames or an animated svg",
    );
    assert!(names(d.path()).is_empty());
}

/// Two raw points were "a cusp at point 0".
#[test]
fn two_points_are_degenerate_not_a_cusp() {
    use immerse::{NotSelfOverlapping, triangulate};
    let two = [immerse::Point::new(0.0, 0.0), immerse::Point::new(1.0, 0.0)];
    let e = triangulate(&two).unwrap_err();
    assert_eq!(e, NotSelfOverlapping::Degenerate);
    assert!(!e.is_answer());
    assert_eq!(
        e.to_string(),
        "the points lie on one line (fewer than 3 points, or zero area), so they bound no disk; give at least 3 points that enclose a region"
    );
    let line: Vec<_> = (0..5)
        .map(|i| immerse::Point::new(f64::from(i), 0.0))
        .collect();
    assert_eq!(
        triangulate(&line).unwrap_err(),
        NotSelfOverlapping::Degenerate
    );
}

// ---- item 8: one --json convention -----------------------------------------

/// `--json` was a flag printing to stdout in `check` and `triangulate` but
/// took a file in `morph` and `mesh-morph`. Now every command takes
/// `--json[=FILE]`: bare (or `-`, /dev/stdout) prints on stdout; the old
/// forms still work.
#[test]
fn one_json_convention() {
    let d = tempfile::tempdir().unwrap();
    let t = tri();
    let dp = Some(d.path());
    let json = |args: &[&str]| -> serde_json::Value {
        let out = immerse_in(d.path(), args);
        assert_eq!(out.status.code(), Some(0), "{args:?}: {}", stderr(&out));
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let read = |name: &str| -> serde_json::Value {
        serde_json::from_slice(&std::fs::read(d.path().join(name)).unwrap()).unwrap()
    };
    // check: old bare flag (before or after the curve), and a file.
    assert_eq!(json(&["check", "--json", &t])["points"], 3);
    assert_eq!(json(&["check", &t, "--json"])["points"], 3);
    let out = immerse_in(d.path(), &["check", &t, "--json=c.json"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(
        stdout(&out).contains("self-overlapping"),
        "the text report still prints"
    );
    assert_eq!(read("c.json")["self_overlapping"], true);
    assert_stderr(
        dp,
        &["check", &t, "--json=c.json"],
        2,
        "immerse: output file c.json already exists; pass --force to overwrite it",
    );
    assert_eq!(
        immerse_in(d.path(), &["check", &t, "--json=c.json", "--force"])
            .status
            .code(),
        Some(0)
    );
    // triangulate likewise.
    assert_eq!(
        json(&["triangulate", &t, "--json"])["triangles"]
            .as_array()
            .unwrap()
            .len(),
        1
    );
    let out = immerse_in(d.path(), &["triangulate", &t, "--json=t.json"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(read("t.json")["points"].as_array().unwrap().len(), 3);
    // morph and mesh-morph: a file after a space (old), bare = stdout.
    assert_eq!(
        json(&["morph", &t, &t, "--frames", "2", "--json"])["frames"]
            .as_array()
            .unwrap()
            .len(),
        2
    );
    let (a, b) = (
        Path::new(env!("CARGO_MANIFEST_DIR")).join("meshes/fg_4_3_a.json"),
        Path::new(env!("CARGO_MANIFEST_DIR")).join("meshes/fg_4_3_b.json"),
    );
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    assert_eq!(
        json(&["mesh-morph", a, b, "--frames", "3", "-q", "--json"])["frames"]
            .as_array()
            .unwrap()
            .len(),
        3
    );
    // Two outputs on stdout are refused.
    assert_stderr(
        dp,
        &["morph", &t, &t, "--json", "--metrics"],
        2,
        "immerse: --json and --metrics would both print to standard output; send one of them to a file",
    );
}

// ---- the SVG immerse writes reads back as its curve ------------------------

/// The SVG that immerse writes read back as its background rectangle.
#[test]
fn immerse_svg_reads_back_as_the_curve() {
    let d = tempfile::tempdir().unwrap();
    let spiral = curve("spiral-strip-400deg-n30.json");
    let spiral = spiral.to_str().unwrap();
    let out = immerse_in(d.path(), &["triangulate", spiral, "-o", "t.svg"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let out = immerse_in(
        d.path(),
        &["morph", spiral, spiral, "--frames", "2", "-o", "anim.svg"],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let out = immerse_in(
        d.path(),
        &[
            "morph", spiral, spiral, "--frames", "2", "-o", "frames", "--format", "svg",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let original = immerse::Curve::from_path(spiral).unwrap();
    for svg in ["t.svg", "anim.svg", "frames/frame_0000.svg"] {
        let back = immerse::Curve::from_path(d.path().join(svg)).unwrap();
        assert_eq!(back.len(), original.len(), "{svg}");
        assert_eq!(back.turning_number(), Some(1), "{svg}");
        // The same shape up to the drawing's scale: compare the bounding
        // boxes' aspect ratios.
        let aspect = |c: &immerse::Curve| {
            let (mut lo, mut hi) = (c.points[0], c.points[0]);
            for &p in &c.points {
                lo = lo.min(p);
                hi = hi.max(p);
            }
            (hi.x - lo.x) / (hi.y - lo.y)
        };
        assert!(
            (aspect(&back) / aspect(&original) - 1.0).abs() < 0.01,
            "{svg}"
        );
        let out = immerse_in(d.path(), &["check", svg]);
        assert_eq!(out.status.code(), Some(0), "{svg}: {}", stderr(&out));
    }
    assert_eq!(immerse_render::OUTLINE_ID, "immerse-outline");
    assert_eq!(immerse_render::BACKGROUND_ID, "immerse-background");
}
