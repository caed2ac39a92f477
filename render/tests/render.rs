//! Integration tests: pixels, file formats, SVG structure and output safety.

use std::path::Path;

use immerse_render::{
    Easing, Frame, Loop, Output, RenderError, Rgba, Style, View, animated_svg, check_output_dir,
    encode_png, frame_times, render, svg_frame, write_animated_svg, write_atomic, write_gif,
    write_png_sequence, write_svg_sequence,
};

/// Two overlapping right triangles: `[0,4]²` corner and the same shifted by (1,1).
fn overlapping() -> Frame {
    Frame {
        points: vec![
            [0.0, 0.0],
            [4.0, 0.0],
            [0.0, 4.0],
            [1.0, 1.0],
            [5.0, 1.0],
            [1.0, 5.0],
        ],
        triangles: vec![[0, 1, 2], [3, 4, 5]],
        ..Frame::default()
    }
}

/// A square morphing into a rotated square, `n` frames.
fn squares(n: usize) -> Vec<Frame> {
    (0..n)
        .map(|i| {
            let a = i as f64 / (n.max(2) - 1) as f64 * std::f64::consts::FRAC_PI_4;
            let points = (0..4)
                .map(|k| {
                    let t = a + k as f64 * std::f64::consts::FRAC_PI_2;
                    [t.cos(), t.sin()]
                })
                .collect();
            Frame::from_triangles(points, vec![[0, 1, 2], [0, 2, 3]])
        })
        .collect()
}

fn plain_style() -> Style {
    Style::DEFAULT
        .with_size(100, 100)
        .with_wireframe(false)
        .with_outline(Rgba::rgb(0, 0, 0), 0.0)
}

fn pixel(p: &immerse_render::tiny_skia::Pixmap, view: &View, at: [f64; 2]) -> [u8; 4] {
    let [x, y] = view.to_pixel(at);
    let c = p.pixel(x as u32, y as u32).unwrap();
    [c.red(), c.green(), c.blue(), c.alpha()]
}

fn luma(c: [u8; 4]) -> u32 {
    u32::from(c[0]) + u32::from(c[1]) + u32::from(c[2])
}

#[test]
fn pixel_probes_show_fill_background_and_depth() {
    let frame = overlapping();
    for aa in [true, false] {
        let style = plain_style().with_anti_alias(aa);
        let view = View::fit(std::slice::from_ref(&frame), &style);
        let p = render(&frame, &view, &style, &[]).unwrap();
        let bg = style.background;
        // Background far away (a corner pixel is padding).
        let corner = p.pixel(1, 1).unwrap();
        assert_eq!(
            [corner.red(), corner.green(), corner.blue()],
            [bg.r, bg.g, bg.b]
        );
        let once = pixel(&p, &view, [0.4, 3.0]);
        let twice = pixel(&p, &view, [1.5, 1.5]);
        let outside = pixel(&p, &view, [4.5, 4.5]);
        assert_eq!(outside[..3], [bg.r, bg.g, bg.b]);
        assert!(luma(once) < luma(outside), "{once:?} vs {outside:?}");
        assert!(luma(twice) < luma(once), "{twice:?} vs {once:?}");
        // Depth shading follows 1 - (1 - a)^k.
        let expect = |k: f64| {
            let o = style.depth_opacity(k);
            (f64::from(bg.r) * (1.0 - o) + f64::from(style.fill.r) * o).round()
        };
        assert!((f64::from(once[0]) - expect(1.0)).abs() <= 2.0);
        assert!((f64::from(twice[0]) - expect(2.0)).abs() <= 2.0);
    }
}

#[test]
fn shared_edges_leave_no_seam() {
    // A square split into two triangles: the diagonal must not be lighter.
    let frame = &squares(1)[0];
    let style = plain_style().with_size(200, 200);
    let view = View::fit(std::slice::from_ref(frame), &style);
    let p = render(frame, &view, &style, &[]).unwrap();
    let inside = pixel(&p, &view, [0.3, 0.0]);
    for k in -5..=5 {
        let t = f64::from(k) / 10.0;
        // Points on the diagonal from vertex 0 (1,0) to vertex 2 (-1,0).
        let c = pixel(&p, &view, [t, 0.0]);
        assert!(c[0].abs_diff(inside[0]) <= 3, "{c:?} vs {inside:?}");
    }
}

#[test]
fn view_is_fixed_and_flips_y() {
    let frames = squares(5);
    let style = Style::DEFAULT;
    let view = View::fit(&frames, &style);
    for f in &frames {
        // Fitting from the whole slice, whichever frame we draw.
        assert_eq!(View::fit(&frames, &style), view);
        let _ = f;
    }
    let low = view.to_pixel([0.0, 0.0]);
    let high = view.to_pixel([0.0, 1.0]);
    assert!(high[1] < low[1], "larger y must be higher in the image");
    // Everything lies inside the padded image.
    for f in &frames {
        for &p in &f.points {
            let [x, y] = view.to_pixel(p);
            let pad = style.padding - 1e-9;
            assert!(x >= pad && x <= f64::from(style.width) - pad);
            assert!(y >= pad && y <= f64::from(style.height) - pad);
        }
    }
}

#[test]
fn bad_input_errors_instead_of_panicking() {
    let frame = overlapping();
    let view = View::fit(std::slice::from_ref(&frame), &Style::DEFAULT);
    assert!(matches!(
        render(&frame, &view, &Style::DEFAULT.with_size(0, 10), &[]),
        Err(RenderError::EmptyImage { .. })
    ));
    assert!(matches!(
        render(
            &frame,
            &view,
            &Style::DEFAULT.with_size(1 << 20, 1 << 20),
            &[]
        ),
        Err(RenderError::ImageTooLarge { .. })
    ));
    let mut bad = frame.clone();
    bad.outline = vec![0, 9];
    assert!(matches!(
        render(&bad, &view, &Style::DEFAULT, &[]),
        Err(RenderError::BadIndex { .. })
    ));
    // NaN and huge coordinates are skipped, empty frames draw the background.
    let mut weird = frame.clone();
    weird.points[0] = [f64::NAN, 0.0];
    weird.points[4] = [1e300, -1e300];
    weird.markers = vec![[f64::INFINITY, 0.0], [1.0, 1.0]];
    weird.spine = vec![0, 1];
    weird.outline = vec![0, 1, 2, 3, 4, 5];
    for f in [weird, Frame::default()] {
        let view = View::fit(std::slice::from_ref(&f), &Style::DEFAULT);
        render(&f, &view, &Style::DEFAULT, &[&f]).unwrap();
        svg_frame(&f, &view, &Style::DEFAULT, &[&f]).unwrap();
    }
}

#[test]
fn png_sequence_decodes_with_the_right_size() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("frames");
    let frames = squares(3);
    let style = Style::DEFAULT.with_size(64, 48);
    let count = std::sync::atomic::AtomicUsize::new(0);
    let paths = write_png_sequence(&frames, &out, &style, &Output::DEFAULT, &|_| {
        count.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    })
    .unwrap();
    assert_eq!(count.into_inner(), 3);
    let names: Vec<_> = paths
        .iter()
        .map(|p| p.file_name().unwrap().to_str().unwrap().to_owned())
        .collect();
    assert_eq!(
        names,
        ["frame_0000.png", "frame_0001.png", "frame_0002.png"]
    );
    for p in &paths {
        let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(p).unwrap()));
        let reader = decoder.read_info().unwrap();
        assert_eq!((reader.info().width, reader.info().height), (64, 48));
    }
    assert_no_temp_files(&out);
    // An ordinary folder's permissions, not a temporary folder's 0700.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let plain = dir.path().join("plain");
        std::fs::create_dir(&plain).unwrap();
        let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode(&out), mode(&plain));
    }

    // The folder is not empty now: refused without force, fine with it.
    let err = write_png_sequence(&frames, &out, &style, &Output::DEFAULT, &|_| {}).unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.contains("not empty") && msg.contains("--force"),
        "{msg}"
    );
    assert!(msg.contains(&out.display().to_string()), "{msg}");
    write_png_sequence(
        &frames,
        &out,
        &style,
        &Output::DEFAULT.with_force(true),
        &|_| {},
    )
    .unwrap();
}

#[test]
fn encoded_png_keeps_transparency() {
    let frame = overlapping();
    let style = plain_style().with_background(Rgba::new(0, 0, 0, 0));
    let view = View::fit(std::slice::from_ref(&frame), &style);
    let bytes = encode_png(&render(&frame, &view, &style, &[]).unwrap()).unwrap();
    let reader = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .unwrap();
    assert_eq!(reader.info().color_type, png::ColorType::Rgba);
}

fn gif_frames(path: &Path) -> (usize, u16, u16, Vec<u16>) {
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::RGBA);
    let mut d = opts.read_info(std::fs::File::open(path).unwrap()).unwrap();
    let (w, h) = (d.width(), d.height());
    let mut delays = Vec::new();
    while let Some(f) = d.read_next_frame().unwrap() {
        delays.push(f.delay);
    }
    (delays.len(), w, h, delays)
}

#[test]
fn gif_decodes_with_the_right_frame_count() {
    let dir = tempfile::tempdir().unwrap();
    let frames = squares(20);
    let style = Style::DEFAULT.with_size(40, 30);
    for (looping, expect) in [(Loop::Once, 20), (Loop::Loop, 20), (Loop::PingPong, 38)] {
        let path = dir.path().join(format!("{looping}.gif"));
        let done = std::sync::atomic::AtomicUsize::new(0);
        write_gif(
            &frames,
            &path,
            &style,
            25.0,
            looping,
            &Output::DEFAULT,
            &|n| {
                done.fetch_max(n, std::sync::atomic::Ordering::Relaxed);
            },
        )
        .unwrap();
        let (n, w, h, delays) = gif_frames(&path);
        assert_eq!((n, w, h), (expect, 40, 30), "{looping}");
        assert!(delays.iter().all(|&d| d == 4));
        assert_eq!(done.into_inner(), expect);
        // Refused without force.
        assert!(matches!(
            write_gif(
                &frames,
                &path,
                &style,
                25.0,
                looping,
                &Output::DEFAULT,
                &|_| {}
            ),
            Err(RenderError::FileExists { .. })
        ));
    }
    let path = dir.path().join("x.gif");
    assert!(matches!(
        write_gif(
            &frames,
            &path,
            &style,
            0.0,
            Loop::Loop,
            &Output::DEFAULT,
            &|_| {}
        ),
        Err(RenderError::BadFps { .. })
    ));
    assert!(matches!(
        write_gif(
            &[],
            &path,
            &style,
            10.0,
            Loop::Loop,
            &Output::DEFAULT,
            &|_| {}
        ),
        Err(RenderError::NoFrames)
    ));
    assert!(matches!(
        write_gif(
            &frames,
            &path,
            &style.clone().with_size(70_000, 2),
            10.0,
            Loop::Loop,
            &Output::DEFAULT,
            &|_| {}
        ),
        Err(RenderError::ImageTooLarge { .. })
    ));
    assert!(!path.exists());
    assert_no_temp_files(dir.path());
}

/// The subpaths of SVG path data made of `M`, `L` and `Z` commands: the
/// corners of each and whether it is closed.
fn subpaths(d: &str) -> Vec<(Vec<[f64; 2]>, bool)> {
    let mut out: Vec<(Vec<[f64; 2]>, bool)> = Vec::new();
    let mut rest = d.trim();
    while let Some(c) = rest.chars().next() {
        rest = &rest[1..];
        let end = rest.find(['M', 'L', 'Z']).unwrap_or(rest.len());
        let args: Vec<f64> = rest[..end]
            .split_whitespace()
            .map(|v| v.parse().unwrap_or_else(|e| panic!("{v:?} in {d:?}: {e}")))
            .collect();
        rest = &rest[end..];
        match c {
            'M' => out.push((Vec::new(), false)),
            'Z' => {
                out.last_mut().expect("Z after M").1 = true;
                continue;
            }
            'L' => assert!(!out.is_empty(), "L before M in {d:?}"),
            _ => panic!("command {c} in {d:?}"),
        }
        assert_eq!(args.len(), 2, "{d:?}");
        out.last_mut().unwrap().0.push([args[0], args[1]]);
    }
    out
}

/// `#rrggbb` of a colour.
fn hex(c: Rgba) -> String {
    format!("#{:02x}{:02x}{:02x}", c.r, c.g, c.b)
}

/// Asserts that the written corners are the pixel positions of `want`
/// to the written precision (1/100 pixel, rounded).
fn assert_corners(got: &[[f64; 2]], want: &[[f64; 2]], view: &View, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: {got:?}");
    for (g, w) in got.iter().zip(want) {
        let p = view.to_pixel(*w);
        assert!(
            (g[0] - p[0]).abs() <= 0.005 + 1e-9 && (g[1] - p[1]).abs() <= 0.005 + 1e-9,
            "{what}: written {g:?}, frame point {w:?} at pixel {p:?}"
        );
    }
}

/// The per-frame SVG files hold, layer by layer, what each frame is: the
/// size and background, one translucent fill path per triangle through the
/// frame's own points (mapped by the sequence's shared view), the onion
/// ghosts of the first and last frames, the wireframe, the outline, and
/// the spine and markers only where the frame has them.
#[test]
fn svg_frames_write_each_frames_geometry_and_colours() {
    let dir = tempfile::tempdir().unwrap();
    let style = Style::DEFAULT;
    let mut frames = squares(4);
    frames[1].spine = vec![0, 1];
    frames[1].markers = vec![[0.0, 0.0]];
    let paths = write_svg_sequence(&frames, dir.path(), &style, &Output::DEFAULT, &|_| {}).unwrap();
    assert_eq!(paths.len(), 4);
    let view = View::fit(&frames, &style);
    let corners_of = |f: &Frame, idx: &[u32]| -> Vec<[f64; 2]> {
        idx.iter().map(|&i| f.points[i as usize]).collect()
    };
    for (k, (p, frame)) in paths.iter().zip(&frames).enumerate() {
        assert_eq!(
            p.file_name().unwrap().to_string_lossy(),
            format!("frame_{k:04}.svg")
        );
        let text = std::fs::read_to_string(p).unwrap();
        let doc = roxmltree::Document::parse(&text).unwrap();
        let root = doc.root_element();
        assert_eq!(root.tag_name().name(), "svg");
        let (w, h) = (style.width, style.height);
        assert_eq!(root.attribute("width"), Some(&*w.to_string()));
        assert_eq!(root.attribute("height"), Some(&*h.to_string()));
        assert_eq!(root.attribute("viewBox"), Some(&*format!("0 0 {w} {h}")));
        let children: Vec<_> = root.children().filter(|n| n.is_element()).collect();

        // Background.
        assert!(children[0].has_tag_name("rect"), "frame {k}");
        assert_eq!(children[0].attribute("fill"), Some(&*hex(style.background)));

        // Fill: one translucent path per triangle, in order.
        let g = children[1];
        assert!(g.has_tag_name("g"), "frame {k}");
        assert_eq!(g.attribute("fill"), Some(&*hex(style.fill)));
        let alpha: f64 = g.attribute("fill-opacity").unwrap().parse().unwrap();
        assert!((alpha - style.depth_opacity(1.0)).abs() <= 5e-4, "{alpha}");
        let fills: Vec<_> = g.children().filter(|n| n.is_element()).collect();
        assert_eq!(fills.len(), frame.triangles.len(), "frame {k}");
        for (t, path) in frame.triangles.iter().zip(&fills) {
            let sub = subpaths(path.attribute("d").unwrap());
            assert_eq!(sub.len(), 1);
            assert!(sub[0].1, "a triangle is closed");
            assert_corners(&sub[0].0, &corners_of(frame, t), &view, "fill");
        }

        // Strokes after the fill, in drawing order: two onion ghosts
        // (outlines of the first and last frames), the wireframe, the
        // outline, then the spine where the frame has one.
        let strokes: Vec<_> = children[2..]
            .iter()
            .filter(|n| n.has_tag_name("path"))
            .collect();
        let spine = !frame.spine.is_empty();
        assert_eq!(strokes.len(), 4 + usize::from(spine), "frame {k}");
        for s in &strokes {
            assert_eq!(s.attribute("fill"), Some("none"));
        }
        for (s, ghost) in strokes[..2].iter().zip([&frames[0], &frames[3]]) {
            assert_eq!(s.attribute("stroke"), Some(&*hex(style.onion_color)));
            let sub = subpaths(s.attribute("d").unwrap());
            assert_eq!(sub.len(), 1);
            assert_corners(
                &sub[0].0,
                &corners_of(ghost, &ghost.outline),
                &view,
                "onion",
            );
        }
        let wire = strokes[2];
        assert_eq!(wire.attribute("stroke"), Some(&*hex(style.wireframe_color)));
        assert_eq!(
            wire.attribute("stroke-width"),
            Some(&*style.wireframe_width.to_string())
        );
        let sub = subpaths(wire.attribute("d").unwrap());
        assert_eq!(sub.len(), frame.triangles.len());
        for (t, (c, closed)) in frame.triangles.iter().zip(&sub) {
            assert!(closed);
            assert_corners(c, &corners_of(frame, t), &view, "wireframe");
        }
        let outline = strokes[3];
        assert_eq!(outline.attribute("id"), Some(immerse_render::OUTLINE_ID));
        assert_eq!(outline.attribute("stroke"), Some(&*hex(style.outline)));
        let sub = subpaths(outline.attribute("d").unwrap());
        assert_eq!(sub.len(), 1);
        assert!(sub[0].1);
        assert_corners(
            &sub[0].0,
            &corners_of(frame, &frame.outline),
            &view,
            "outline",
        );
        if spine {
            let s = strokes[4];
            assert_eq!(s.attribute("stroke"), Some(&*hex(style.spine_color)));
            let centroid = |t: u32| {
                let c = corners_of(frame, &frame.triangles[t as usize]);
                [
                    (c[0][0] + c[1][0] + c[2][0]) / 3.0,
                    (c[0][1] + c[1][1] + c[2][1]) / 3.0,
                ]
            };
            let want: Vec<[f64; 2]> = frame.spine.iter().map(|&t| centroid(t)).collect();
            let sub = subpaths(s.attribute("d").unwrap());
            assert_eq!(sub.len(), 1);
            assert!(!sub[0].1, "the spine is open");
            assert_corners(&sub[0].0, &want, &view, "spine");
        }

        // Markers: one circle each, where the frame has them.
        let circles: Vec<_> = children
            .iter()
            .filter(|n| n.has_tag_name("circle"))
            .collect();
        assert_eq!(circles.len(), frame.markers.len(), "frame {k}");
        for (c, m) in circles.iter().zip(&frame.markers) {
            let at = [
                c.attribute("cx").unwrap().parse::<f64>().unwrap(),
                c.attribute("cy").unwrap().parse::<f64>().unwrap(),
            ];
            assert_corners(&[at], &[*m], &view, "marker");
            assert_eq!(c.attribute("fill"), Some(&*hex(style.marker_color)));
            assert_eq!(c.attribute("r"), Some(&*style.marker_radius.to_string()));
        }
    }
}

#[test]
fn animated_svg_has_one_animate_with_a_value_per_frame() {
    let frames = squares(7);
    for (looping, expect) in [(Loop::Once, 7), (Loop::Loop, 7), (Loop::PingPong, 12)] {
        let text = animated_svg(&frames, &Style::DEFAULT, 12.0, looping).unwrap();
        let doc = roxmltree::Document::parse(&text).unwrap();
        let animates: Vec<_> = doc
            .descendants()
            .filter(|n| n.has_tag_name("animate"))
            .collect();
        assert_eq!(animates.len(), 1);
        let a = animates[0];
        assert_eq!(a.attribute("attributeName"), Some("d"));
        let values = a.attribute("values").unwrap();
        assert_eq!(values.split(';').count(), expect);
        assert_eq!(
            a.attribute("dur"),
            Some(&*format!("{}s", (expect - 1) as f64 / 12.0))
        );
        let repeat = if looping == Loop::Once {
            "1"
        } else {
            "indefinite"
        };
        assert_eq!(a.attribute("repeatCount"), Some(repeat));
    }

    // Outlines must match in length.
    let mut bad = squares(3);
    bad[2].outline.pop();
    assert!(matches!(
        animated_svg(&bad, &Style::DEFAULT, 12.0, Loop::Loop),
        Err(RenderError::OutlineMismatch { frame: 2, .. })
    ));
    let mut nan = squares(3);
    nan[1].points[2] = [f64::NAN, 0.0];
    let err = animated_svg(&nan, &Style::DEFAULT, 12.0, Loop::Loop).unwrap_err();
    assert!(
        matches!(err, RenderError::InFrame { frame: 1, .. }),
        "{err}"
    );

    // Written atomically, refused when present.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("anim.svg");
    write_animated_svg(
        &frames,
        &path,
        &Style::DEFAULT,
        12.0,
        Loop::Loop,
        &Output::DEFAULT,
    )
    .unwrap();
    assert!(
        write_animated_svg(
            &frames,
            &path,
            &Style::DEFAULT,
            12.0,
            Loop::Loop,
            &Output::DEFAULT
        )
        .is_err()
    );
    assert_no_temp_files(dir.path());
}

#[test]
fn animated_svg_renders_with_usvg() {
    // usvg ignores the animation but must accept the document (use, mask).
    let text = animated_svg(&squares(3), &Style::DEFAULT, 10.0, Loop::Loop).unwrap();
    usvg::Tree::from_str(&text, &usvg::Options::default()).unwrap();
    let frame = overlapping();
    let view = View::fit(std::slice::from_ref(&frame), &Style::DEFAULT);
    let text = svg_frame(&frame, &view, &Style::DEFAULT, &[]).unwrap();
    usvg::Tree::from_str(&text, &usvg::Options::default()).unwrap();
}

fn assert_no_temp_files(dir: &Path) {
    for e in std::fs::read_dir(dir).unwrap() {
        let name = e.unwrap().file_name();
        let name = name.to_string_lossy();
        assert!(!name.starts_with(".immerse-"), "left behind: {name}");
    }
}

#[test]
fn write_atomic_refuses_then_replaces() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("a.png");
    write_atomic(&path, b"first", false).unwrap();
    let err = write_atomic(&path, b"second", false).unwrap_err();
    assert!(matches!(err, RenderError::FileExists { .. }));
    assert!(err.to_string().contains("--force"));
    assert_eq!(std::fs::read(&path).unwrap(), b"first");
    write_atomic(&path, b"second", true).unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), b"second");
    // A missing folder is an error naming it, with nothing left behind.
    let missing = dir.path().join("no/such/dir/x.png");
    let err = write_atomic(&missing, b"x", false).unwrap_err();
    assert!(matches!(err, RenderError::NoFolder { .. }), "{err}");
    assert_no_temp_files(dir.path());
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(names.len(), 1);
    // Same permissions as an ordinary new file, not a temp file's 0600.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let plain = dir.path().join("plain");
        std::fs::write(&plain, b"x").unwrap();
        let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode(&path), mode(&plain));
    }
}

#[test]
fn output_dir_rules() {
    let dir = tempfile::tempdir().unwrap();
    let fresh = dir.path().join("a");
    check_output_dir(&fresh, false).unwrap();
    assert!(!fresh.exists(), "a check creates nothing");
    // The parent must exist.
    let deep = dir.path().join("no/such");
    assert_eq!(
        check_output_dir(&deep, false).unwrap_err().to_string(),
        format!(
            "cannot write {}: there is no folder {}; create it first",
            deep.display(),
            dir.path().join("no").display()
        )
    );
    std::fs::create_dir(&fresh).unwrap();
    check_output_dir(&fresh, false).unwrap(); // empty is fine
    std::fs::write(fresh.join("keep.txt"), "x").unwrap();
    let err = check_output_dir(&fresh, false).unwrap_err();
    assert_eq!(
        err.to_string(),
        format!(
            "output folder {} is not empty; pass --force to write into it",
            fresh.display()
        )
    );
    check_output_dir(&fresh, true).unwrap();
    assert!(fresh.join("keep.txt").exists());
    let file = fresh.join("keep.txt");
    assert!(matches!(
        check_output_dir(&file, true),
        Err(RenderError::NotADir { .. })
    ));
    assert_no_temp_files(dir.path());
}

/// Regression: a shorter sequence written into a frame
/// folder left the frames of an earlier, longer run behind.
#[test]
fn a_shorter_sequence_removes_stale_frames_but_nothing_else() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("frames");
    let style = Style::DEFAULT.with_size(16, 16);
    write_png_sequence(&squares(5), &out, &style, &Output::DEFAULT, &|_| {}).unwrap();
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    std::fs::write(out.join("frame_0009.svg"), "other format").unwrap();
    let forced = Output::DEFAULT.with_force(true);
    write_png_sequence(&squares(2), &out, &style, &forced, &|_| {}).unwrap();
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "frame_0000.png",
            "frame_0001.png",
            "frame_0009.svg",
            "notes.txt"
        ]
    );
    assert_no_temp_files(dir.path());
}

/// A failed sequence (here: a frame with a bad index) leaves no folder and
/// no temporary folder behind.
#[test]
fn a_failed_sequence_leaves_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("frames");
    let mut frames = squares(3);
    frames[2].triangles.push([0, 1, 99]);
    let err =
        write_png_sequence(&frames, &out, &Style::DEFAULT, &Output::DEFAULT, &|_| {}).unwrap_err();
    assert!(matches!(err, RenderError::InFrame { .. }), "{err}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// Regression: with force, a symbolic link was replaced
/// by a regular file and a special file renamed over.
#[cfg(unix)]
#[test]
fn links_are_followed_and_special_files_written_through() {
    let dir = tempfile::tempdir().unwrap();
    let real = dir.path().join("real.txt");
    let link = dir.path().join("link.txt");
    std::fs::write(&real, "old").unwrap();
    std::os::unix::fs::symlink("real.txt", &link).unwrap();
    assert!(matches!(
        write_atomic(&link, b"new", false),
        Err(RenderError::FileExists { .. })
    ));
    write_atomic(&link, b"new", true).unwrap();
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(std::fs::read(&real).unwrap(), b"new");
    // A dangling link: the file is created where it points.
    let dangling = dir.path().join("dangling.txt");
    std::os::unix::fs::symlink("target.txt", &dangling).unwrap();
    write_atomic(&dangling, b"made", false).unwrap();
    assert_eq!(
        std::fs::read(dir.path().join("target.txt")).unwrap(),
        b"made"
    );
    // /dev/null is a special file, written through (never written to here:
    // a regression would replace the machine's /dev/null; the CLI test
    // writes through a FIFO instead).
    assert_eq!(
        immerse_render::resolve_output(Path::new("/dev/null")).unwrap(),
        immerse_render::Destination::Special("/dev/null".into())
    );
    assert_eq!(
        immerse_render::resolve_output(Path::new("/dev/stdout")).unwrap(),
        immerse_render::Destination::Stdout
    );
    // A folder is not a file.
    assert!(matches!(
        write_atomic(dir.path(), b"x", true),
        Err(RenderError::IsADir { .. })
    ));
    assert_no_temp_files(dir.path());
}

#[test]
fn easing_properties() {
    for e in [
        Easing::Linear,
        Easing::EaseIn,
        Easing::EaseOut,
        Easing::EaseInOut,
    ] {
        assert_eq!(e.apply(0.0), 0.0);
        assert_eq!(e.apply(1.0), 1.0);
        let t = frame_times(50, &e);
        assert!(t.windows(2).all(|w| w[0] <= w[1]), "{e}");
    }
    let lin = "cubic-bezier(0,0,1,1)".parse::<Easing>().unwrap();
    for t in frame_times(11, &lin)
        .iter()
        .zip(frame_times(11, &Easing::Linear))
    {
        assert!((t.0 - t.1).abs() < 1e-9);
    }
    let err = "cubic-bezier(1.2,0,1,1)".parse::<Easing>().unwrap_err();
    assert!(
        err.to_string().contains("x1 and x2 must lie in [0,1]"),
        "{err}"
    );
}

#[test]
fn contact_sheet_places_each_frame_in_its_cell() {
    let frames = squares(5);
    let style = plain_style();
    let sheet = immerse_render::contact_sheet(&frames, &style, 3).unwrap();
    // Three columns, two rows of 100 × 100 cells.
    assert_eq!((sheet.width(), sheet.height()), (300, 200));
    // Each cell matches the frame rendered alone with the shared view.
    let view = View::fit(&frames, &style);
    for (i, f) in frames.iter().enumerate() {
        let alone = render(f, &view, &style, &[]).unwrap();
        let (cx, cy) = ((i % 3) as u32 * 100, (i / 3) as u32 * 100);
        for (x, y) in [(50, 50), (10, 10), (90, 50)] {
            let a = alone.pixel(x, y).unwrap();
            let b = sheet.pixel(cx + x, cy + y).unwrap();
            assert_eq!(a, b, "frame {i} at ({x}, {y})");
        }
    }
    // Without a column count the grid is nearly square: 5 frames in 3 columns.
    let auto = immerse_render::contact_sheet(&frames, &style, 0).unwrap();
    assert_eq!((auto.width(), auto.height()), (300, 200));
    assert_eq!(immerse_render::contact_sheet_columns(60, 0), 8);
    assert_eq!(immerse_render::contact_sheet_columns(3, 10), 3);
    // The size is known (and checked) before anything is rendered.
    let big = Style::DEFAULT.with_size(600, 600);
    assert_eq!(
        immerse_render::contact_sheet_size(2000, &big, 0)
            .unwrap_err()
            .to_string(),
        "a contact sheet of 2000 frames in 45 columns would be 27000x27000 pixels, over the limit of 67108864 pixels; use fewer frames or a smaller size"
    );
    // The empty sixth cell stays transparent.
    assert_eq!(sheet.pixel(250, 150).unwrap().alpha(), 0);
    assert!(matches!(
        immerse_render::contact_sheet(&[], &style, 3),
        Err(RenderError::NoFrames)
    ));
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sheet.png");
    immerse_render::write_contact_sheet(&frames, &path, &style, 0, &Output::DEFAULT).unwrap();
    let again = immerse_render::write_contact_sheet(&frames, &path, &style, 0, &Output::DEFAULT);
    assert!(matches!(again, Err(RenderError::FileExists { .. })));
}
