//! The curve readers on real files from `curves/`, checked against the
//! labels in `curves/MANIFEST.json`.

use crate::util::{curve, curves_dir, labels};
use immerse::Curve;
use immerse::curve::CurveError;
use immerse::geom::Point;

#[test]
fn every_labelled_curve_reads_with_its_turning_number_and_simplicity() {
    let labels = labels();
    assert!(labels.len() >= 30, "only {} labels", labels.len());
    let mut checked = 0;
    for l in &labels {
        let result = Curve::from_path(curve(&l.file));
        match (l.self_overlapping, result) {
            (None, Err(_)) => {}
            (None, Ok(c)) => panic!("{} is labelled invalid but read as {c:?}", l.file),
            (Some(_), Err(CurveError::ZeroArea { .. })) if l.turning_number.is_none() => {
                // degenerate-collinear: no turning number, rejected as zero area.
            }
            (Some(_), Err(e)) => panic!("{} failed to read: {e}", l.file),
            (Some(_), Ok(c)) => {
                assert_eq!(Some(c.len()), l.n_clean, "{}", l.file);
                assert_eq!(c.turning_number_as_given(), l.turning_number, "{}", l.file);
                assert_eq!(Some(c.is_simple()), l.simple, "{}", l.file);
                assert_eq!(c.reversed, l.reversed, "{}", l.file);
                if let Some(k) = l.turning_number {
                    let oriented = if k == -1 { 1 } else { k };
                    assert_eq!(c.turning_number(), Some(oriented), "{}", l.file);
                }
                checked += 1;
            }
        }
    }
    assert!(checked >= 28, "only {checked} curves checked");
}

#[test]
fn json_object_and_bare_array_agree() {
    let obj = Curve::from_json_str(
        r#"{"name": "sq", "points": [[0,0],[2,0],[2,2],[0,2]]}"#,
        "a",
    )
    .unwrap();
    let bare = Curve::from_json_str("[[0,0],[2,0],[2,2],[0,2],[0,0]]", "b").unwrap();
    assert_eq!(obj.points, bare.points);
    assert_eq!(obj.name, "sq");
    assert_eq!(bare.dropped, 1);
}

#[test]
fn text_reader_on_the_hexagon_file() {
    let c = Curve::from_path(curve("hexagon-text-format.txt")).unwrap();
    assert_eq!(c.len(), 6);
    assert_eq!(c.name, "hexagon-text-format");
    assert!(c.is_simple());
    assert_eq!(c.turning_number(), Some(1));
}

#[test]
fn svg_files_in_curves_read_as_closed_curves() {
    let mut seen = 0;
    for entry in std::fs::read_dir(curves_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("svg") {
            continue;
        }
        let c = Curve::from_path(&path).unwrap_or_else(|e| panic!("{e}"));
        assert!(c.len() >= 3, "{}", path.display());
        seen += 1;
    }
    assert!(
        seen >= 4,
        "expected the SVG drawings in curves/, found {seen}"
    );
}

fn svg_curve(body: &str) -> Result<Curve, CurveError> {
    let svg = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100" viewBox="0 0 100 100">{body}</svg>"#
    );
    Curve::from_bytes(svg.as_bytes(), immerse::curve::Format::Svg, "t.svg", "t")
}

#[test]
fn svg_rect_with_transform_is_mapped_and_flipped() {
    let c = svg_curve(r#"<rect x="10" y="20" width="30" height="40" transform="translate(5 7)"/>"#)
        .unwrap();
    let (lo, hi) = bounds(&c.points);
    assert_eq!((lo, hi), (Point::new(15.0, -67.0), Point::new(45.0, -27.0)));
    // SVG's y-down clockwise rect becomes counter-clockwise or is reversed;
    // either way the oriented curve turns once counter-clockwise.
    assert_eq!(c.turning_number(), Some(1));
    assert_eq!(c.len(), 4);
}

#[test]
fn svg_rotation_is_applied() {
    let c = svg_curve(r#"<polygon points="0,0 10,0 10,10 0,10" transform="rotate(90)"/>"#).unwrap();
    let (lo, hi) = bounds(&c.points);
    assert!((lo - Point::new(-10.0, -10.0)).length() < 1e-5, "{lo}");
    assert!((hi - Point::new(0.0, 0.0)).length() < 1e-5, "{hi}");
}

#[test]
fn svg_circle_is_flattened_within_tolerance() {
    // The documented tolerance (design §2): the polyline stays within 0.1 %
    // of the shape's bounding-box diagonal of the true curve.
    const FLATTEN_TOLERANCE: f64 = 1e-3;
    let c = svg_curve(r#"<circle cx="50" cy="50" r="40"/>"#).unwrap();
    assert!(c.len() >= 16, "only {} points", c.len());
    let centre = Point::new(50.0, -50.0);
    let diag = (80.0f64 * 80.0 * 2.0).sqrt();
    for (i, &p) in c.points.iter().enumerate() {
        let q = c.points[(i + 1) % c.len()];
        // usvg draws the circle as four cubic arcs, which deviate from the
        // true circle by at most 2.7e-4 of the radius; vertices lie on those
        // arcs and chord midpoints within the flattening tolerance of them.
        let arc_error = 2.8e-4 * 40.0;
        assert!(((p - centre).length() - 40.0).abs() < arc_error);
        let sag = 40.0 - ((p + q) / 2.0 - centre).length();
        assert!(sag <= FLATTEN_TOLERANCE * diag + arc_error, "sag {sag}");
    }
    assert!(c.is_simple());
}

#[test]
fn svg_path_with_beziers_and_ellipse() {
    let c = svg_curve(r#"<path d="M 10 10 C 40 0 60 0 90 10 Q 100 50 90 90 L 10 90 Z"/>"#).unwrap();
    assert!(c.len() > 4);
    assert!(c.is_simple());
    let e = svg_curve(r#"<g transform="scale(2)"><ellipse cx="20" cy="20" rx="10" ry="5"/></g>"#)
        .unwrap();
    let (lo, hi) = bounds(&e.points);
    assert!((hi.x - lo.x - 40.0).abs() < 1e-4 && (hi.y - lo.y - 20.0).abs() < 1e-4);
}

#[test]
fn svg_without_a_closed_shape_is_rejected() {
    let e =
        svg_curve(r#"<polyline points="0,0 10,0 10,10" fill="none" stroke="black"/>"#).unwrap_err();
    assert!(matches!(e, CurveError::NoClosedShape { .. }), "{e}");
    let e = svg_curve("").unwrap_err();
    assert!(matches!(e, CurveError::NoClosedShape { .. }), "{e}");
}

fn bounds(points: &[Point]) -> (Point, Point) {
    points.iter().fold(
        (Point::splat(f64::INFINITY), Point::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    )
}

/// Every row of the table in `curves/README.md` is what the readers and
/// the exact DP compute, and every curve file has a row.
#[test]
fn the_curves_readme_table_is_reproduced() {
    let text = std::fs::read_to_string(curves_dir().join("README.md")).unwrap();
    let mut rows = 0;
    for line in text.lines().filter(|l| l.starts_with("| `")) {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let file = cells[1].trim_matches('`');
        let (so, simple, n, turning) = (cells[2], cells[3], cells[4], cells[5]);
        match Curve::from_path(curve(file)) {
            Err(e) => assert_eq!(so, "invalid", "{file}: {e}"),
            Ok(c) => {
                let verdict = immerse::triangulate(&c.points).is_ok();
                assert_eq!(so, if verdict { "yes" } else { "no" }, "{file}");
                assert_eq!(simple, if c.is_simple() { "yes" } else { "no" }, "{file}");
                assert_eq!(n, c.len().to_string(), "{file}");
                let t = c
                    .turning_number_as_given()
                    .map_or("-".to_string(), |k| k.to_string());
                assert_eq!(turning, t, "{file}");
            }
        }
        rows += 1;
    }
    let files = std::fs::read_dir(curves_dir())
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            name != "MANIFEST.json" && [".json", ".txt", ".svg"].iter().any(|x| name.ends_with(x))
        })
        .count();
    assert_eq!(rows, files, "every curve file has one row");
    assert!(rows >= 25);
}
