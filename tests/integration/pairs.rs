//! The compatible pairs of `curves/pairs/` (written by
//! `cargo run --release --example make_pairs`): under the guaranteed paths
//! every frame is an immersion, the end frames are the inputs and the total
//! area stays within the fitted paths' range (0.81 of the smaller endpoint's
//! area to 1.13 of the larger's, `AREA_RANGE`).

use immerse::Curve;
use immerse::check;
use immerse::frames::Frame;
use immerse::morph::{Compatible, MorphError, MorphOptions, ThirdVertexPath};
use immerse::{Quality, triangulate_with};

use crate::util::curves_dir;

/// The total-area range of the fitted paths, as fractions of the smaller
/// and the larger endpoint's area (the library's `STRAIGHT_AREA_RANGE`).
const AREA_RANGE: (f64, f64) = (0.81, 1.13);

/// (name, source, target) of every pair.
fn pairs() -> Vec<(String, Curve, Curve)> {
    let dir = curves_dir().join("pairs");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| {
            let f = e.ok()?.file_name().into_string().ok()?;
            Some(f.strip_suffix(".source.json")?.to_string())
        })
        .collect();
    names.sort();
    names
        .into_iter()
        .map(|name| {
            let read = |side: &str| {
                Curve::from_path(dir.join(format!("{name}.{side}.json")))
                    .unwrap_or_else(|e| panic!("{e}"))
            };
            let (src, dst) = (read("source"), read("target"));
            (name, src, dst)
        })
        .collect()
}

#[test]
fn pairs_are_compatible_and_self_overlapping() {
    let all = pairs();
    assert!(
        all.len() >= 6,
        "expected at least 6 pairs, found {}",
        all.len()
    );
    for (name, src, dst) in &all {
        assert_eq!(src.len(), dst.len(), "{name}");
        assert!(!dst.reversed, "{name}: target should be counter-clockwise");
        assert!(
            triangulate_with(&dst.points, Quality::Delaunay).is_ok(),
            "{name}: target not self-overlapping"
        );
        // Some quality's source triangulation is an immersion of the target.
        assert!(
            Quality::ALL.into_iter().any(|q| {
                let t = triangulate_with(&src.points, q).unwrap();
                check(&dst.points, &t.triangles).is_ok()
            }),
            "{name}: no source triangulation is valid on the target"
        );
    }
}

#[test]
fn guaranteed_paths_give_immersions_between_the_pairs() {
    let times: Vec<f64> = (0..200).map(|i| f64::from(i) / 199.0).collect();
    for (name, src, dst) in pairs() {
        // The first quality (Delaunay first) whose source triangulation is
        // valid on the target.
        let tri = [Quality::Delaunay, Quality::MaxMin, Quality::Any]
            .into_iter()
            .map(|q| triangulate_with(&src.points, q).unwrap().triangles)
            .find(|t| check(&dst.points, t).is_ok())
            .unwrap_or_else(|| panic!("{name}: no compatible triangulation"));
        let a0 = Frame {
            t: 0.0,
            points: src.points.clone(),
            triangles: tri.clone(),
        }
        .total_area();
        let a1 = Frame {
            t: 1.0,
            points: dst.points.clone(),
            triangles: tri.clone(),
        }
        .total_area();
        let (lo, hi) = (a0.min(a1) * AREA_RANGE.0, a0.max(a1) * AREA_RANGE.1);
        for path in [ThirdVertexPath::Hybrid, ThirdVertexPath::Angle] {
            let o = MorphOptions::DEFAULT;
            let m = Compatible::new(&src.points, &dst.points, &tri, o.root, o.fan_margin)
                .map_err(MorphError::from)
                .and_then(|plan| plan.morph(&times, path))
                .unwrap_or_else(|e| panic!("{name} {path}: {e}"));
            assert_eq!(m.paths, [path], "{name}");
            assert!(!m.fallback, "{name} {path}");
            assert_eq!(m.frames.len(), 200);
            for f in &m.frames {
                assert!(f.is_immersion(), "{name} {path} t={}: {:?}", f.t, f.check());
                let area = f.total_area();
                assert!(
                    area >= lo * (1.0 - 1e-9) && area <= hi * (1.0 + 1e-9),
                    "{name} {path} t={}: area {area} outside [{lo}, {hi}]",
                    f.t
                );
            }
            assert_eq!(m.frames[0].points, src.points, "{name} {path}: frame 0");
            assert_eq!(
                m.frames[199].points, dst.points,
                "{name} {path}: last frame"
            );
        }
    }
}
