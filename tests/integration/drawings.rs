//! Drawings: many styled shapes per file (docs/design.md §2a).

use crate::util::curve;
use immerse::Curve;
use immerse::curve::{CurveError, Format};
use immerse::drawing::{Color, Drawing, DrawingError, FillRule, winding_number};

fn svg(body: &str) -> Vec<u8> {
    format!(r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 200 200">{body}</svg>"#)
        .into_bytes()
}

fn read(body: &str) -> Result<Drawing, DrawingError> {
    Drawing::from_bytes(&svg(body), Format::Svg, "d.svg", "d")
}

fn hex(h: &str) -> Option<Color> {
    Some(Color::parse_hex(h).unwrap())
}

#[test]
fn svg_shapes_keep_order_ids_styles_and_transforms() {
    let d = read(
        r##"<rect id="back" x="0" y="0" width="100" height="50" fill="#ff0000"/>
        <g transform="translate(10 20)" opacity="0.5">
          <circle id="eye" cx="30" cy="30" r="10" fill="#00ff00" fill-opacity="0.5" stroke="#0000ff" stroke-width="3"/>
          <path id="pair" d="M 60 60 L 80 60 L 80 80 Z M 100 60 L 120 60 L 120 80 Z" fill="#123456" fill-rule="evenodd"/>
        </g>
        <path d="M 0 100 L 20 100" stroke="black" fill="none"/>"##,
    )
    .unwrap();
    let ids: Vec<&str> = d.shapes.iter().map(|s| s.id.as_str()).collect();
    assert_eq!(ids, ["back", "eye", "pair.1", "pair.2"]);
    assert_eq!(d.shapes[0].style.fill, hex("#ff0000"));
    assert_eq!(d.shapes[0].style.stroke, None);
    assert_eq!(d.shapes[0].style.opacity, 1.0);
    let eye = &d.shapes[1];
    assert_eq!(eye.style.fill, hex("#00ff00"));
    assert_eq!(eye.style.stroke, hex("#0000ff"));
    assert_eq!(eye.style.stroke_width, 3.0);
    assert!(
        (eye.style.opacity - 0.25).abs() < 1e-6,
        "group × fill opacity"
    );
    // The transform is applied (y flipped): the circle's centre is at
    // (40, -50).
    let c = immerse::geom::polygon::area_centroid(&eye.points);
    assert!(
        (c.x - 40.0).abs() < 0.05 && (c.y + 50.0).abs() < 0.05,
        "{c:?}"
    );
    assert_eq!(d.shapes[2].style.fill_rule, FillRule::Evenodd);
    assert_eq!(d.shapes[2].points.len(), 3);
    assert_eq!(d.shapes[3].label, "shape 4 (path 'pair' subpath 2)");
    assert_eq!(
        d.notices,
        ["path 4: an open stroke-only path is a line, not a shape; left out"]
    );
}

#[test]
fn gradients_are_flattened_with_a_notice() {
    let d = read(
        r##"<defs><linearGradient id="g"><stop offset="0" stop-color="#000000"/><stop offset="1" stop-color="#ffffff"/></linearGradient></defs>
        <rect id="r" width="10" height="10" fill="url(#g)"/>"##,
    )
    .unwrap();
    let fill = d.shapes[0].style.fill.unwrap();
    // The OKLab mean of black and white: lightness 0.5.
    assert_eq!(fill, Color::from_oklab([0.5, 0.0, 0.0]));
    assert_eq!(
        d.notices,
        [format!(
            "path 'r': fill gradient flattened to the solid colour {}",
            fill.hex()
        )]
    );
}

#[test]
fn only_open_strokes_is_refused() {
    let e = read(r#"<path id="l" d="M 0 0 L 10 10" stroke="black" fill="none"/>"#).unwrap_err();
    assert_eq!(
        e.to_string(),
        "d.svg: no closed shape found (open stroke-only paths left out: path 'l'); draw closed, filled paths"
    );
}

const SQUARE_CCW: &str = "M 0 0 L 0 100 L 100 100 L 100 0 Z";

#[test]
fn holes_are_refused_naming_the_subpath() {
    // SVG is y down: this outer square is counter-clockwise once y is
    // flipped; the inner one is drawn the other way.
    let nonzero = read(&format!(
        r#"<path id="ring" d="{SQUARE_CCW} M 30 30 L 70 30 L 70 70 L 30 70 Z"/>"#
    ))
    .unwrap_err();
    assert!(matches!(nonzero, DrawingError::Hole { .. }), "{nonzero}");
    assert_eq!(
        nonzero.to_string(),
        "d.svg: shape 2 (path 'ring' subpath 2) is a hole in shape 1 (path 'ring' subpath 1) (under the nonzero fill rule it cuts a region out of it); holes are not supported yet: draw the parts as separate shapes"
    );
    // Same orientation: nonzero paints the inner square twice (no hole),
    // even-odd cuts it out.
    let same = format!(r#"{SQUARE_CCW} M 30 30 L 30 70 L 70 70 L 70 30 Z"#);
    let d = read(&format!(r#"<path d="{same}"/>"#)).unwrap();
    assert_eq!(d.shapes.len(), 2);
    let e = read(&format!(r#"<path d="{same}" fill-rule="evenodd"/>"#)).unwrap_err();
    assert!(e.to_string().contains("is a hole in shape 1"), "{e}");
    assert!(e.to_string().contains("evenodd"), "{e}");
    // Two squares that only overlap: even-odd leaves their lens unpainted,
    // which separate shapes would paint.
    let lens = read(
        r#"<path d="M 0 0 L 0 50 L 50 50 L 50 0 Z M 25 25 L 25 90 L 90 90 L 90 25 Z" fill-rule="evenodd"/>"#,
    )
    .unwrap_err();
    assert!(lens.to_string().contains("is a hole"), "{lens}");
    // Separate elements never cut each other: they are painted apart.
    let d = read(&format!(
        r#"<path d="{SQUARE_CCW}"/><path d="M 30 30 L 70 30 L 70 70 L 30 70 Z" fill="white"/>"#
    ))
    .unwrap();
    assert_eq!(d.shapes.len(), 2);
}

/// Under nonzero, a subpath drawn the other way inside a region a
/// self-overlapping outer shape covers twice cuts nothing (the sum stays
/// 1): it is a shape of its own. Inside a region covered once it is a
/// hole.
#[test]
fn reversed_subpath_in_a_doubly_covered_region_is_not_a_hole() {
    let outer = Curve::from_path(curve("spiral-strip-400deg-n30.json")).unwrap();
    let (lo, hi) = outer
        .points
        .iter()
        .fold((outer.points[0], outer.points[0]), |(l, h), &p| {
            (l.min(p), h.max(p))
        });
    let size = (hi - lo).length();
    let r = size * 0.01;
    // A small square (of half-side r) whose corners and centre all have
    // winding number w.
    let find = |w: i64| {
        (1..100)
            .flat_map(|i| (1..100).map(move |j| (i, j)))
            .map(|(i, j)| {
                immerse::Point::new(
                    lo.x + (hi.x - lo.x) * f64::from(i) / 100.0,
                    lo.y + (hi.y - lo.y) * f64::from(j) / 100.0,
                )
            })
            .find(|&c| {
                [
                    (0.0, 0.0),
                    (r, r),
                    (-r, r),
                    (r, -r),
                    (-r, -r),
                    (0.0, 2.0 * r),
                    (2.0 * r, 0.0),
                    (0.0, -2.0 * r),
                    (-2.0 * r, 0.0),
                ]
                .iter()
                .all(|&(dx, dy)| {
                    winding_number(&outer.points, c + immerse::Point::new(dx, dy)) == Some(w)
                })
            })
            .unwrap()
    };
    // SVG path data (y down) of the outer curve and of a square at c that
    // is clockwise once y is flipped back up.
    let path = |pts: &[immerse::Point]| {
        let mut d = String::new();
        for (k, p) in pts.iter().enumerate() {
            d.push_str(&format!(
                "{} {} {} ",
                if k == 0 { "M" } else { "L" },
                p.x,
                -p.y
            ));
        }
        d + "Z "
    };
    let square_cw = |c: immerse::Point| {
        let q = |dx: f64, dy: f64| c + immerse::Point::new(dx * r, dy * r);
        path(&[q(-1.0, -1.0), q(-1.0, 1.0), q(1.0, 1.0), q(1.0, -1.0)])
    };
    let outer_d = path(&outer.points);
    let twice = find(2);
    let d = read(&format!(r#"<path d="{outer_d}{}"/>"#, square_cw(twice))).unwrap();
    assert_eq!(d.shapes.len(), 2);
    assert!(d.shapes[1].reversed, "the clockwise square is reversed");
    assert!(d.require_self_overlapping("d.svg").is_ok());
    let once = find(1);
    let e = read(&format!(r#"<path d="{outer_d}{}"/>"#, square_cw(once))).unwrap_err();
    assert!(
        e.to_string()
            .contains("shape 2 (path 1 subpath 2) is a hole in shape 1 (path 1 subpath 1)"),
        "{e}"
    );
}

#[test]
fn every_shape_must_be_self_overlapping() {
    let d = read(
        r#"<rect width="10" height="10"/><path id="eight" d="M 0 0 L 10 10 L 10 0 L 0 10 Z"/>"#,
    )
    .unwrap();
    let e = d.require_self_overlapping("d.svg").unwrap_err();
    assert!(
        e.to_string()
            .starts_with("d.svg: shape 2 (path 'eight') is not self-overlapping ("),
        "{e}"
    );
}

#[test]
fn json_drawings_read_with_defaults_and_refuse_bad_fields() {
    let json = br##"{"shapes": [
        {"id": "a", "points": [[0,0],[1,0],[0,1]], "fill": "#abc", "opacity": 0.5},
        {"points": [[0,0],[0,2],[2,2],[2,0]], "fill": null, "stroke": "#102030", "stroke_width": 2, "fill_rule": "evenodd"}
    ]}"##;
    let d = Drawing::from_bytes(json, Format::Json, "d.json", "d").unwrap();
    assert_eq!(d.shapes.len(), 2);
    assert_eq!(d.shapes[0].style.fill, hex("#aabbcc"));
    assert_eq!(d.shapes[0].style.opacity, 0.5);
    assert_eq!(d.shapes[1].style.fill, None);
    assert_eq!(d.shapes[1].style.stroke, hex("#102030"));
    assert_eq!(d.shapes[1].style.fill_rule, FillRule::Evenodd);
    assert!(d.shapes[1].reversed, "given clockwise");
    let bad = br#"{"shapes": [{"id": "x", "points": [[0,0],[1,0],[0,1]], "opacity": 2}]}"#;
    let e = Drawing::from_bytes(bad, Format::Json, "d.json", "d").unwrap_err();
    assert!(
        e.to_string()
            .starts_with("d.json (shape 1 'x'): \"opacity\" must be a number in [0, 1]"),
        "{e}"
    );
    let dup = br#"{"shapes": [{"id": "x", "points": [[0,0],[1,0],[0,1]]}, {"id": "x", "points": [[0,0],[1,0],[0,1]]}]}"#;
    let e = Drawing::from_bytes(dup, Format::Json, "d.json", "d").unwrap_err();
    assert_eq!(
        e.to_string(),
        "d.json: shapes 1 and 2 share the id 'x'; give every shape its own id"
    );
    let flat = br#"{"shapes": [{"id": "f", "points": [[0,0],[1,0],[2,0]]}]}"#;
    let e = Drawing::from_bytes(flat, Format::Json, "d.json", "d").unwrap_err();
    assert!(
        e.to_string()
            .starts_with("d.json (shape 1 'f'): all 3 points"),
        "{e}"
    );
    // A plain curve is a drawing of one shape.
    let one = Drawing::read_path(curve("square.json")).unwrap();
    assert!(one.single_curve && one.shapes.len() == 1);
}

/// Where one curve is expected, a file of several parts is refused naming
/// them; a drawing of one shape is that curve.
#[test]
fn curve_readers_refuse_several_parts() {
    let two = svg(
        r#"<rect id="a" width="10" height="10"/><path d="M 20 0 L 30 0 L 30 10 Z M 40 0 L 50 0 L 50 10 Z"/>"#,
    );
    let e = Curve::from_bytes(&two, Format::Svg, "two.svg", "two").unwrap_err();
    assert!(
        matches!(e, CurveError::SeveralParts { count: 3, .. }),
        "{e}"
    );
    assert_eq!(
        e.to_string(),
        "two.svg: 3 closed shapes (path 'a', path 2 subpath 1, path 2 subpath 2), not one curve; read it as a drawing (`immerse check`, `immerse morph`) or keep one shape"
    );
    let json = br#"{"shapes": [{"id": "a", "points": [[0,0],[1,0],[0,1]]}, {"points": [[0,0],[1,0],[0,1]]}]}"#;
    let e = Curve::from_bytes(json, Format::Json, "two.json", "two").unwrap_err();
    assert_eq!(
        e.to_string(),
        "two.json: 2 closed shapes (shape 1 'a', shape 2), not one curve; read it as a drawing (`immerse check`, `immerse morph`) or keep one shape"
    );
    let one = br#"{"shapes": [{"id": "a", "points": [[0,0],[1,0],[0,1]]}]}"#;
    assert_eq!(
        Curve::from_bytes(one, Format::Json, "one.json", "one")
            .unwrap()
            .len(),
        3
    );
}

const TWO_SHAPES: &str = r##"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100"><rect id="body" x="0" y="0" width="40" height="40" fill="#3366cc"/><path id="eight" d="M 50 50 L 60 60 L 60 50 L 50 60 Z" fill="red"/></svg>"##;

/// `check` answers a drawing shape by shape; `triangulate` and a key of
/// `animate`, which need one curve, refuse it naming its parts.
#[test]
fn commands_never_read_one_part_of_a_drawing() {
    use crate::util::{immerse_in, stderr, stdout};
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("two.svg"), TWO_SHAPES).unwrap();
    std::fs::write(
        d.path().join("good.svg"),
        TWO_SHAPES.replace(
            "M 50 50 L 60 60 L 60 50 L 50 60 Z",
            "M 50 50 L 60 50 L 60 60 Z",
        ),
    )
    .unwrap();
    let out = immerse_in(d.path(), &["check", "two.svg"]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert_eq!(
        stdout(&out),
        "two.svg: a drawing of 2 shapes: 1 of 2 not self-overlapping\n  \
         shape 1 (path 'body'): self-overlapping, 4 points, clockwise as given (reversed)\n  \
         shape 2 (path 'eight'): not self-overlapping (turning number is 0, not 1), 4 points\n"
    );
    let out = immerse_in(d.path(), &["check", "good.svg", "--json=r.json"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let r: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.path().join("r.json")).unwrap()).unwrap();
    assert_eq!(r["self_overlapping"], true);
    assert_eq!(r["shapes"].as_array().unwrap().len(), 2);
    assert_eq!(r["shapes"][1]["id"], "eight");
    assert_eq!(r["shapes"][1]["points"], 3);
    let refusal = "two.svg: 2 closed shapes (path 'body', path 'eight'), not one curve; read it as a drawing (`immerse check`, `immerse morph`) or keep one shape";
    let out = immerse_in(d.path(), &["triangulate", "two.svg"]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(stderr(&out), format!("immerse: {refusal}\n"));
    let square = curve("square.json");
    let out = immerse_in(
        d.path(),
        &[
            "animate",
            square.to_str().unwrap(),
            "two.svg",
            "-o",
            "a.gif",
        ],
    );
    // animate reads it as a drawing key, whose every shape must be
    // self-overlapping.
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains(
            "two.svg: shape 2 (path 'eight') is not self-overlapping (turning number is 0, not 1)"
        ),
        "{}",
        stderr(&out)
    );
    // A hole is bad input for check too.
    std::fs::write(
        d.path().join("ring.svg"),
        format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="{SQUARE_CCW} M 30 30 L 70 30 L 70 70 L 30 70 Z"/></svg>"#
        ),
    )
    .unwrap();
    let out = immerse_in(d.path(), &["check", "ring.svg"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("shape 2 (path 1 subpath 2) is a hole in shape 1"),
        "{}",
        stderr(&out)
    );
}

/// Three shapes and the same three moved a little, listed in another
/// order: by id and by auto the right pairs, by order the listed ones.
/// The source's fourth shape, far off, has no partner.
fn shuffled() -> (Drawing, Drawing) {
    let a = read(
        r#"<rect id="sq" x="10" y="10" width="30" height="30"/>
        <polygon id="tri" points="80,40 110,40 95,10"/>
        <circle id="dot" cx="160" cy="25" r="15"/>
        <rect id="far" x="170" y="170" width="20" height="10"/>"#,
    )
    .unwrap();
    let b = read(
        r#"<circle id="dot" cx="165" cy="30" r="14"/>
        <rect id="sq" x="15" y="12" width="28" height="32"/>
        <polygon id="tri" points="82,42 112,44 96,12"/>"#,
    )
    .unwrap();
    (a, b)
}

#[test]
fn matching_by_id_order_and_auto() {
    use immerse::drawing::{MatchMode, match_shapes};
    let (a, b) = shuffled();
    let by_id = match_shapes(&a, &b, MatchMode::Id);
    assert_eq!(by_id.pairs, [(0, 1), (1, 2), (2, 0)]);
    assert_eq!(by_id.vanishing, [3]);
    assert!(by_id.appearing.is_empty());
    let by_order = match_shapes(&a, &b, MatchMode::Order);
    assert_eq!(by_order.pairs, [(0, 0), (1, 1), (2, 2)]);
    assert_eq!(by_order.vanishing, [3]);
    let auto = match_shapes(&a, &b, MatchMode::Auto);
    assert_eq!(auto.pairs, by_id.pairs, "{auto:?}");
    assert_eq!(auto.vanishing, [3]);
    // The right pairs cost less than the listed ones.
    let total = |m: &immerse::drawing::Matching| m.costs.iter().sum::<f64>();
    assert!(total(&auto) < total(&by_order));
    // Swapped, the far shape appears instead.
    let back = match_shapes(&b, &a, MatchMode::Auto);
    assert_eq!(back.pairs, [(0, 2), (1, 0), (2, 1)]);
    assert_eq!(back.appearing, [3]);
}

/// Every shape of every frame is an immersed disk (the independent
/// checker); the ends are the drawings; a vanishing shape shrinks by a
/// similarity to a copy scaled by 0.02 (design §2b) and fades out, an appearing one
/// the reverse.
#[test]
fn drawing_tween_frames_are_immersions_with_growing_and_fading_shapes() {
    use immerse::drawing::{DrawingTween, MatchMode, ShapeRole, match_shapes};
    // The documented scale of the copy an unmatched shape grows from.
    const GROWN_SCALE: f64 = 0.02;
    use immerse::morph::CurveMorphOptions;
    let (a, b) = shuffled();
    for (src, dst) in [(&a, &b), (&b, &a)] {
        let m = match_shapes(src, dst, MatchMode::Auto);
        let tween = DrawingTween::new(src, dst, &m, &CurveMorphOptions::DEFAULT).unwrap();
        assert_eq!(tween.shape_count(), 4);
        for k in 0..=10 {
            let t = f64::from(k) / 10.0;
            let f = tween.frame(t).unwrap();
            for s in &f.shapes {
                immerse::check(&s.points, &s.triangles).unwrap();
                let other = match s.role {
                    ShapeRole::Vanishing => 1.0 - t,
                    ShapeRole::Appearing => t,
                    ShapeRole::Matched => 1.0,
                };
                assert!((s.style.opacity - other).abs() < 1e-12, "{t} {:?}", s.role);
            }
        }
        let (first, last) = (tween.frame(0.0).unwrap(), tween.frame(1.0).unwrap());
        let lone = first
            .shapes
            .iter()
            .position(|s| s.role != ShapeRole::Matched)
            .unwrap();
        assert_eq!(first.shapes[lone].id, "far");
        let area = |p: &[immerse::Point]| immerse::geom::polygon::signed_area(p);
        let ratio = area(&last.shapes[lone].points) / area(&first.shapes[lone].points);
        let expected = if first.shapes[lone].role == ShapeRole::Vanishing {
            GROWN_SCALE * GROWN_SCALE
        } else {
            1.0 / (GROWN_SCALE * GROWN_SCALE)
        };
        assert!((ratio / expected - 1.0).abs() < 1e-9, "{ratio}");
        // Matched shapes end as the target's shapes, styles included.
        for s in last.shapes.iter().filter(|s| s.role == ShapeRole::Matched) {
            let target = dst.shapes.iter().find(|t| t.id == s.id).unwrap();
            assert_eq!(s.style, target.style);
        }
    }
}

/// `immerse morph` on drawings: the matching in the summary and the JSON,
/// every shape of every JSON frame an immersed disk, styles carried into
/// the SVG frames, the animated SVG and the Lottie file.
#[test]
fn morph_drawings_reports_matching_and_draws_every_shape_with_its_style() {
    use crate::util::{immerse_in, stderr};
    let d = tempfile::tempdir().unwrap();
    let a = curve("drawings/creature-a.svg");
    let b = curve("drawings/creature-b.svg");
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    let out = immerse_in(
        d.path(),
        &[
            "morph",
            a,
            b,
            "--frames",
            "5",
            "--match",
            "id",
            "--json=m.json",
            "-o",
            "f",
            "--format",
            "svg",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        stderr(&out).contains(
            "matching (id): 'body' → 'body', 'shell' → 'shell', 'eye' → 'eye', 'horn' vanishes, 'hat' appears"
        ),
        "{}",
        stderr(&out)
    );
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.path().join("m.json")).unwrap()).unwrap();
    assert_eq!(json["matching"]["mode"], "id");
    assert_eq!(json["matching"]["vanishing"], serde_json::json!([2]));
    assert_eq!(json["matching"]["appearing"], serde_json::json!([3]));
    let frames = json["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 5);
    for f in frames {
        let shapes = f["shapes"].as_array().unwrap();
        assert_eq!(shapes.len(), 5);
        for s in shapes {
            let points: Vec<immerse::Point> = s["points"]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| immerse::Point::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
                .collect();
            let triangles: Vec<[u32; 3]> = serde_json::from_value(s["triangles"].clone()).unwrap();
            immerse::check(&points, &triangles).unwrap();
        }
    }
    // The first SVG frame paints the source's shapes in order with their
    // colours; the last the target's.
    let first = std::fs::read_to_string(d.path().join("f/frame_0000.svg")).unwrap();
    let fills: Vec<&str> = first
        .match_indices(" fill=\"#")
        .map(|(i, _)| &first[i + 7..i + 14])
        .collect();
    assert!(
        fills.ends_with(&["#f2cc8f", "#e07a5f", "#f2cc8f", "#3d405b", "#f2cc8f"]),
        "{fills:?}"
    );
    let last = std::fs::read_to_string(d.path().join("f/frame_0004.svg")).unwrap();
    assert!(
        last.contains("fill=\"#81b29a\""),
        "the target body's colour"
    );
    assert!(
        last.contains("stroke=\"#f4f1de\""),
        "the target shell's stroke"
    );
    // The animated SVG: one path per shape, its outline, colours and
    // opacity animated from the source's to the target's.
    let out = immerse_in(
        d.path(),
        &[
            "morph", a, b, "--frames", "4", "--match", "id", "-o", "a.svg",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let svg = std::fs::read_to_string(d.path().join("a.svg")).unwrap();
    assert_eq!(svg.matches("<path ").count(), 5);
    assert_eq!(svg.matches("attributeName=\"d\"").count(), 5);
    let body_fill = svg.find("attributeName=\"fill\"").unwrap();
    let values = &svg[body_fill..body_fill + svg[body_fill..].find("/>").unwrap()];
    assert!(
        values.contains("values=\"#f2cc8f;") && values.ends_with(";#81b29a\""),
        "{values}"
    );
    assert!(
        svg.contains("values=\"1.000;0.667;0.333;0.000\""),
        "the horn fades out: {svg}"
    );
    // Lottie: one layer of the shapes, one shape group per shape (top
    // first) with its own fill and stroke, then the background layer; the
    // body's fill runs to the target's.
    let out = immerse_in(
        d.path(),
        &[
            "morph", a, b, "--frames", "4", "--match", "id", "-o", "a.json", "--format", "lottie",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let lottie: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.path().join("a.json")).unwrap()).unwrap();
    let groups = lottie["layers"][0]["shapes"].as_array().unwrap();
    assert_eq!(lottie["layers"][1]["nm"], "Background");
    let names: Vec<&str> = groups.iter().map(|g| g["nm"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        ["Shape 5", "Shape 4", "Shape 3", "Shape 2", "Shape 1",]
    );
    let body = groups[4]["it"].as_array().unwrap();
    let fill = body.iter().find(|i| i["ty"] == "fl").unwrap();
    let keys = fill["c"]["k"].as_array().unwrap();
    let rgb = |v: &serde_json::Value| {
        let c = v["s"].as_array().unwrap();
        [0, 1, 2].map(|i| (c[i].as_f64().unwrap() * 255.0).round() as u8)
    };
    assert_eq!(rgb(&keys[0]), [0xf2, 0xcc, 0x8f]);
    assert_eq!(rgb(keys.last().unwrap()), [0x81, 0xb2, 0x9a]);
    assert!(body.iter().any(|i| i["ty"] == "st"), "the body is stroked");
}

/// JSON drawing of `shapes` (id, points).
fn json_drawing(shapes: &[(String, Vec<immerse::Point>)]) -> Drawing {
    let items: Vec<serde_json::Value> = shapes
        .iter()
        .map(|(id, pts)| {
            serde_json::json!({"id": id, "points": pts.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>()})
        })
        .collect();
    let text = serde_json::json!({ "shapes": items }).to_string();
    Drawing::from_bytes(text.as_bytes(), Format::Json, "p.json", "p").unwrap()
}

proptest::proptest! {
    #![proptest_config(proptest::test_runner::Config {
        cases: 48,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x2a_d7a3),
        failure_persistence: None,
        ..proptest::test_runner::Config::default()
    })]

    /// Shapes of different outlines set apart, then each moved by less
    /// than a tenth of the spacing, scaled by at most 10% and the list
    /// shuffled: auto matching pairs every shape with its own moved copy.
    #[test]
    fn auto_matching_finds_moved_shuffled_shapes(
        count in 2usize..6,
        moves in proptest::collection::vec((-1.0f64..1.0, -1.0f64..1.0, 0.9f64..1.1), 6),
        order in proptest::strategy::Strategy::prop_shuffle(proptest::sample::subsequence((0..6).collect::<Vec<usize>>(), 6)),
    ) {
        use proptest::prelude::*;
        use immerse::Point;
        use immerse::drawing::{MatchMode, match_shapes};
        // Regular k-gons (k = 3..8) on a row 100 apart, radius 20.
        let shape = |k: usize, centre: Point, scale: f64| -> Vec<Point> {
            (0..k + 3)
                .map(|i| {
                    let a = std::f64::consts::TAU * i as f64 / (k + 3) as f64;
                    centre + scale * 20.0 * Point::new(a.cos(), a.sin())
                })
                .collect()
        };
        let a: Vec<(String, Vec<Point>)> = (0..count)
            .map(|k| (format!("s{k}"), shape(k, Point::new(100.0 * k as f64, 0.0), 1.0)))
            .collect();
        let b: Vec<(String, Vec<Point>)> = order
            .iter()
            .filter(|&&k| k < count)
            .map(|&k| {
                let (dx, dy, s) = moves[k];
                let c = Point::new(100.0 * k as f64 + 10.0 * dx, 10.0 * dy);
                (format!("s{k}"), shape(k, c, s))
            })
            .collect();
        let (da, db) = (json_drawing(&a), json_drawing(&b));
        let auto = match_shapes(&da, &db, MatchMode::Auto);
        let by_id = match_shapes(&da, &db, MatchMode::Id);
        prop_assert_eq!(&auto.pairs, &by_id.pairs);
        prop_assert_eq!(auto.pairs.len(), count);
        prop_assert!(auto.vanishing.is_empty() && auto.appearing.is_empty());
    }
}

/// An independent reading of a written animation: every animated outline
/// as its keys (y up, counter-clockwise), in the file's order.
fn outlines_of(text: &str) -> Vec<Vec<Vec<immerse::Point>>> {
    use immerse::Point;
    let ccw = |mut keys: Vec<Vec<Point>>| {
        let area: f64 = {
            let p = &keys[0];
            (0..p.len())
                .map(|i| {
                    let (a, b) = (p[i], p[(i + 1) % p.len()]);
                    a.x * b.y - b.x * a.y
                })
                .sum()
        };
        if area < 0.0 {
            for k in &mut keys {
                k.reverse();
            }
        }
        keys
    };
    let mut out = Vec::new();
    if text.trim_start().starts_with('{') {
        let doc: serde_json::Value = serde_json::from_str(text).unwrap();
        for layer in doc["layers"].as_array().unwrap() {
            for group in layer["shapes"].as_array().unwrap() {
                for item in group["it"].as_array().unwrap() {
                    if item["ty"] != "sh" || item["ks"]["a"] != 1 {
                        continue;
                    }
                    let keys: Vec<Vec<Point>> = item["ks"]["k"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|k| {
                            k["s"][0]["v"]
                                .as_array()
                                .unwrap()
                                .iter()
                                .map(|p| {
                                    Point::new(p[0].as_f64().unwrap(), -p[1].as_f64().unwrap())
                                })
                                .collect()
                        })
                        .collect();
                    out.push(ccw(keys));
                }
            }
        }
    } else {
        for anim in text.split("<animate attributeName=\"d\"").skip(1) {
            let values = anim.split("values=\"").nth(1).unwrap();
            let values = &values[..values.find('"').unwrap()];
            let keys: Vec<Vec<Point>> = values
                .split(';')
                .map(|d| {
                    d.trim_end_matches('Z')
                        .split(['M', 'L'])
                        .filter(|s| !s.is_empty())
                        .map(|xy| {
                            let mut it = xy.split(' ').map(|v| v.parse::<f64>().unwrap());
                            let (x, y) = (it.next().unwrap(), it.next().unwrap());
                            Point::new(x, -y)
                        })
                        .collect()
                })
                .collect();
            out.push(ccw(keys));
        }
    }
    out
}

/// Certifies every segment of every outline for `player`: the start
/// key's triangulation, re-triangulating where it stops holding.
fn certify_all(outlines: &[Vec<Vec<immerse::Point>>], player: immerse::certify::Player) -> usize {
    use immerse::certify::{MotionOptions, Verdict, certify_motion};
    let mut segments = 0;
    for (o, keys) in outlines.iter().enumerate() {
        for (i, w) in keys.windows(2).enumerate() {
            let tris = immerse::triangulate(&w[0])
                .unwrap_or_else(|e| panic!("outline {o} key {i} is not self-overlapping: {e}"))
                .triangles;
            let r = certify_motion(&w[0], &w[1], &[&tris], player, MotionOptions::default());
            assert_eq!(r.verdict, Verdict::Certified, "outline {o} segment {i}");
            segments += 1;
        }
    }
    segments
}

/// The drawing Lottie and animated SVG are written from every shape's
/// certified keys: read back here, every segment of every shape is
/// certified; the Lottie groups are in stacking order with each shape's
/// paint in its own group (no overlap-depth fill over the shapes below);
/// the styles run from the source's to the target's.
#[test]
fn drawing_lottie_and_animated_svg_certify_shape_by_shape() {
    use crate::util::{immerse_in, stderr};
    use immerse::certify::Player;
    let d = tempfile::tempdir().unwrap();
    let a = curve("drawings/creature-a.svg");
    let b = curve("drawings/creature-b.svg");
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    let out = immerse_in(
        d.path(),
        &[
            "morph",
            a,
            b,
            "--match",
            "id",
            "-o",
            "m.lottie.json",
            "--json=m.json",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.path().join("m.json")).unwrap()).unwrap();
    let shapes = json["shapes"].as_array().unwrap();
    let ids: Vec<&str> = shapes.iter().map(|s| s["id"].as_str().unwrap()).collect();
    assert_eq!(ids, ["body", "shell", "horn", "eye", "hat"]);
    let mut key_counts = Vec::new();
    for s in shapes {
        let keys = s["keyframes"].as_array().unwrap();
        assert_eq!(s["key_count"].as_u64(), Some(keys.len() as u64));
        assert!(keys.len() >= 2);
        key_counts.push(keys.len());
    }
    // Growing and shrinking shapes are scalings: two keys.
    assert_eq!(key_counts[2], 2);
    assert_eq!(key_counts[4], 2);
    let text = std::fs::read_to_string(d.path().join("m.lottie.json")).unwrap();
    let outlines = outlines_of(&text);
    assert_eq!(outlines.len(), 5);
    // Lottie lists the shapes top first: the keys of each are the shape's.
    for (o, k) in outlines.iter().zip(key_counts.iter().rev()) {
        assert_eq!(o.len(), *k);
    }
    assert!(certify_all(&outlines, Player::F32) >= 5);
    let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    let layers = doc["layers"].as_array().unwrap();
    assert_eq!(layers.len(), 2, "the shapes and the background");
    let groups = layers[0]["shapes"].as_array().unwrap();
    let background = &layers[1]["shapes"][0]["it"];
    assert_eq!(background[0]["ty"], "rc");
    let rgb = |v: &serde_json::Value| {
        let c = if v["a"] == 1 {
            v["k"][0]["s"].clone()
        } else {
            v["k"].clone()
        };
        let c = c.as_array().unwrap().clone();
        Color {
            r: (c[0].as_f64().unwrap() * 255.0).round() as u8,
            g: (c[1].as_f64().unwrap() * 255.0).round() as u8,
            b: (c[2].as_f64().unwrap() * 255.0).round() as u8,
        }
    };
    let src = Drawing::from_path(a).unwrap();
    let dst = Drawing::from_path(b).unwrap();
    // Stacking order: bottom (listed last) to top; each group holds one
    // outline and paints only it, with the shape's own colour.
    let mut bottom_up: Vec<&serde_json::Value> = groups.iter().collect();
    bottom_up.reverse();
    for (g, id) in bottom_up.iter().zip(&ids) {
        let items = g["it"].as_array().unwrap();
        assert_eq!(items.iter().filter(|i| i["ty"] == "sh").count(), 1);
        let fills: Vec<&serde_json::Value> = items.iter().filter(|i| i["ty"] == "fl").collect();
        assert!(fills.len() <= 1, "no depth layer over the shapes below");
        let shape = src
            .shapes
            .iter()
            .find(|s| s.id == *id)
            .or_else(|| dst.shapes.iter().find(|s| s.id == *id))
            .unwrap();
        if let Some(f) = fills.first() {
            assert_eq!(Some(rgb(&f["c"])), shape.style.fill, "{id}");
        }
    }
    // The body's colour runs from the source's to the target's.
    let body = bottom_up[0]["it"].as_array().unwrap();
    let fill = body.iter().find(|i| i["ty"] == "fl").unwrap();
    let last = fill["c"]["k"].as_array().unwrap().last().unwrap();
    let c = last["s"].as_array().unwrap();
    let target = dst.shapes[0].style.fill.unwrap();
    assert_eq!((c[0].as_f64().unwrap() * 255.0).round() as u8, target.r);
    // The animated SVG: the same keys, bottom first, certified for f64.
    let out = immerse_in(d.path(), &["morph", a, b, "--match", "id", "-o", "m.svg"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = std::fs::read_to_string(d.path().join("m.svg")).unwrap();
    let outlines = outlines_of(&text);
    assert_eq!(
        outlines.iter().map(Vec::len).collect::<Vec<_>>(),
        key_counts
    );
    certify_all(&outlines, Player::F64);
    assert!(text.contains("calcMode=\"linear\" keyTimes=\"0;"));
    assert!(
        stderr(&out).contains("keys per shape: 'body' "),
        "{}",
        stderr(&out)
    );
}

/// `animate` over three drawings: every shape of every frame an immersed
/// disk; the Lottie of the whole sequence certified shape by shape.
#[test]
fn animate_takes_drawings_as_keys() {
    use crate::util::{immerse_in, stderr};
    let d = tempfile::tempdir().unwrap();
    let a = curve("drawings/creature-a.svg");
    let b = curve("drawings/creature-b.svg");
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    let out = immerse_in(
        d.path(),
        &[
            "animate",
            a,
            b,
            a,
            "--match",
            "id",
            "--frames",
            "40",
            "--json=s.json",
            "-o",
            "s.lottie.json",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let out = immerse_in(
        d.path(),
        &[
            "animate", a, b, a, "--match", "id", "--frames", "40", "-o", "f", "--format", "svg",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.path().join("s.json")).unwrap()).unwrap();
    let frames = json["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 40);
    for (i, f) in frames.iter().enumerate() {
        let shapes = f["shapes"].as_array().unwrap();
        assert_eq!(shapes.len(), 5, "frame {i}");
        for s in shapes {
            let points: Vec<immerse::Point> = s["points"]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| immerse::Point::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
                .collect();
            let triangles: Vec<[u32; 3]> = serde_json::from_value(s["triangles"].clone()).unwrap();
            immerse::check(&points, &triangles)
                .unwrap_or_else(|e| panic!("frame {i} shape {}: {e}", s["id"]));
        }
    }
    assert_eq!(json["segments"].as_array().unwrap().len(), 2);
    assert_eq!(json["keys"][1]["shapes"], 4);
    // The first and last frames are the first key's drawing.
    let first = frames[0]["shapes"].as_array().unwrap();
    let last = frames[39]["shapes"].as_array().unwrap();
    assert_eq!(first[0]["fill"], "#f2cc8f");
    assert_eq!(last[0]["fill"], "#f2cc8f");
    let svg = std::fs::read_to_string(d.path().join("f/frame_0020.svg")).unwrap();
    assert!(
        svg.contains("fill=\"#81b29a\""),
        "the middle key's body colour"
    );
    let text = std::fs::read_to_string(d.path().join("s.lottie.json")).unwrap();
    let outlines = outlines_of(&text);
    assert_eq!(outlines.len(), 10, "five shapes in each of two segments");
    certify_all(&outlines, immerse::certify::Player::F32);
    let out = immerse_in(d.path(), &["certify", "s.lottie.json"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
}

/// One SVG whose groups hold several shapes: every group is a drawing
/// key, read whole; a hole in a key is refused naming the subpath.
#[test]
fn group_keys_read_as_drawings_and_holes_are_refused() {
    use crate::util::{immerse_in, stderr};
    let d = tempfile::tempdir().unwrap();
    let keys = r##"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 300 100">
<g id="one"><rect id="big" x="10" y="10" width="60" height="60" fill="#112233"/><circle id="dot" cx="40" cy="85" r="8" fill="#aa0000"/></g>
<g id="two"><rect id="big" x="110" y="20" width="80" height="40" fill="#334455"/><circle id="dot" cx="150" cy="85" r="10" fill="#00aa00"/></g>
<g id="three"><rect id="big" x="210" y="10" width="50" height="70" fill="#556677"/></g>
</svg>"##;
    std::fs::write(d.path().join("keys.svg"), keys).unwrap();
    let groups = Drawing::groups_from_path(d.path().join("keys.svg")).unwrap();
    assert_eq!(
        groups.iter().map(Drawing::len).collect::<Vec<_>>(),
        [2, 2, 1]
    );
    assert_eq!(groups[0].name, "group 'one'");
    assert_eq!(groups[1].shapes[1].style.fill, hex("#00aa00"));
    let out = immerse_in(
        d.path(),
        &[
            "animate",
            "keys.svg",
            "--frames",
            "20",
            "--json=k.json",
            "-o",
            "k.svg",
            "--format",
            "animated-svg",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.path().join("k.json")).unwrap()).unwrap();
    let frames = json["frames"].as_array().unwrap();
    assert_eq!(frames[0]["shapes"].as_array().unwrap().len(), 2);
    assert_eq!(frames[0]["shapes"][1]["fill"], "#aa0000");
    // The dot shrinks away in the second segment.
    let end = frames.last().unwrap()["shapes"].as_array().unwrap();
    assert_eq!(end.len(), 2);
    assert_eq!(end[1]["role"], "vanishing");
    assert_eq!(end[1]["opacity"], 0.0);
    let text = std::fs::read_to_string(d.path().join("k.svg")).unwrap();
    certify_all(&outlines_of(&text), immerse::certify::Player::F64);

    // A hole in a key: exit 2, naming the subpath.
    std::fs::write(
        d.path().join("ring.svg"),
        svg(&format!(
            r#"<path id="ring" d="{SQUARE_CCW} M 30 30 L 70 30 L 70 70 L 30 70 Z"/><circle cx="150" cy="150" r="20"/>"#
        )),
    )
    .unwrap();
    let b = curve("drawings/creature-b.svg");
    let out = immerse_in(
        d.path(),
        &["animate", "ring.svg", b.to_str().unwrap(), "-o", "r.gif"],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("shape 2 (path 'ring' subpath 2) is a hole in shape 1"),
        "{}",
        stderr(&out)
    );
    assert!(!d.path().join("r.gif").exists());
}
