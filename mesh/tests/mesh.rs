//! Mesh family: tilings, barycentric coordinates and mesh morphs, checked
//! against the worked examples of Floater & Gotsman and Surazhsky & Gotsman.

use immerse_base::geom::{Point, orient};
use immerse_mesh::coords::{Weights, star_weights};
use immerse_mesh::mesh_morph::{
    LinearCheck, MeshFrame, MeshMorphOptions, Method, check_linear, check_star_linear, mesh_morph,
    power_choice,
};
use immerse_mesh::tiling::{Tiling, TilingError};
use std::path::{Path, PathBuf};
use testkit::Rng;

/// The workspace's sample tilings (`meshes/`, beside this crate's folder).
fn meshes() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../meshes")
}

fn mesh(name: &str) -> Tiling {
    let path = meshes().join(name);
    Tiling::from_path(&path).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn times(n: usize) -> Vec<f64> {
    (0..n).map(|k| k as f64 / (n - 1) as f64).collect()
}

/// Largest distance between corresponding points, relative to the extent.
fn rel_diff(a: &[Point], b: &[Point]) -> f64 {
    let scale = a
        .iter()
        .map(|p| p.abs().max_element())
        .fold(1e-300, f64::max);
    a.iter()
        .zip(b)
        .map(|(p, q)| (*p - *q).length())
        .fold(0.0, f64::max)
        / scale
}

const PAIRS: [(&str, &str); 5] = [
    ("fg_4_3_a.json", "fg_4_3_b.json"),
    ("fg_rotated9_a.json", "fg_rotated9_b.json"),
    ("grid6_a.obj", "grid6_b.obj"),
    ("quads5_a.json", "quads5_b.json"),
    ("square5_a.json", "rotated5_b.json"),
];

#[test]
fn every_sample_mesh_is_a_tiling() {
    let dir = meshes();
    let mut count = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path: PathBuf = entry.unwrap().path();
        if matches!(
            path.extension().and_then(|e| e.to_str()),
            Some("json" | "obj")
        ) {
            Tiling::from_path(&path).unwrap_or_else(|e| panic!("{e}"));
            count += 1;
        }
    }
    assert!(count >= 10);
    // OBJ and JSON of the same tiling agree.
    assert_eq!(mesh("fg_4_3_a.obj"), mesh("fg_4_3_a.json"));
}

#[test]
fn weights_are_positive_partitions_that_reproduce_the_vertex() {
    for (a, b) in PAIRS {
        for t in [mesh(a), mesh(b)] {
            let fans = t.neighbours();
            let boundary = t.boundary();
            for (v, fan) in fans.iter().enumerate() {
                if boundary.contains(&(v as u32)) {
                    continue;
                }
                let p = t.points[v];
                let ring: Vec<Point> = fan.iter().map(|&w| t.points[w as usize]).collect();
                for kind in Weights::ALL {
                    let l = star_weights(kind, p, &ring);
                    assert!(l.iter().all(|&x| x > 0.0), "{a} {kind:?} vertex {v}");
                    let s: f64 = l.iter().sum();
                    assert!((s - 1.0).abs() < 1e-12);
                    if kind != Weights::Uniform {
                        let q: Point = ring.iter().zip(&l).map(|(&q, &w)| q * w).sum();
                        let scale = ring.iter().map(|r| (*r - p).length()).fold(0.0, f64::max);
                        assert!((q - p).length() <= 1e-12 * scale, "{a} {kind:?} vertex {v}");
                    }
                }
            }
        }
    }
}

fn all_valid(frames: &[MeshFrame]) -> bool {
    frames.iter().all(|f| f.valid)
}

#[test]
fn example_4_3_linear_degenerates_convex_does_not() {
    let (a, b) = (mesh("fg_4_3_a.json"), mesh("fg_4_3_b.json"));
    let opts = MeshMorphOptions::DEFAULT;
    let lin = mesh_morph(&a, &b, Method::Linear, &[0.5], &opts).unwrap();
    // Lemma 4.3: u1(1/2) = u2(1/2).
    assert_eq!(lin[0].points[0], lin[0].points[1]);
    assert!(!lin[0].valid);
    match check_linear(&a, &b) {
        LinearCheck::Degenerates { t_from, t_to, .. } => {
            assert!(t_from <= 0.5 && 0.5 <= t_to, "{t_from} {t_to}")
        }
        other => panic!("{other:?}"),
    }
    for weights in [Weights::Floater, Weights::MeanValue] {
        let o = opts.clone().with_weights(weights);
        for method in [Method::Convex, Method::Intrinsic, Method::Local] {
            let frames = mesh_morph(&a, &b, method, &times(200), &o).unwrap();
            assert!(all_valid(&frames), "{method} {weights:?}");
        }
    }
}

#[test]
fn rotated_triangulation_linear_degenerates_convex_does_not() {
    let (a, b) = (mesh("fg_rotated9_a.json"), mesh("fg_rotated9_b.json"));
    let opts = MeshMorphOptions::DEFAULT;
    let lin = mesh_morph(&a, &b, Method::Linear, &[0.5], &opts).unwrap();
    let half = &lin[0].points;
    let bad = a.faces.iter().any(|f| {
        !orient(
            half[f[0] as usize],
            half[f[1] as usize],
            half[f[2] as usize],
        )
        .is_ccw()
    });
    assert!(bad && !lin[0].valid);
    assert!(!check_linear(&a, &b).is_valid());
    for method in [Method::Convex, Method::Intrinsic, Method::Local] {
        let frames = mesh_morph(&a, &b, method, &times(200), &opts).unwrap();
        assert!(all_valid(&frames), "{method}");
    }
    let local = mesh_morph(
        &a,
        &b,
        Method::Local,
        &times(50),
        &opts.clone().with_area_improvement(true),
    )
    .unwrap();
    assert!(all_valid(&local));
}

#[test]
fn endpoints_reproduce_the_inputs() {
    for (na, nb) in PAIRS {
        let (a, b) = (mesh(na), mesh(nb));
        for weights in [Weights::Floater, Weights::MeanValue] {
            let opts = MeshMorphOptions::DEFAULT
                .with_weights(weights)
                .with_max_power(8)
                .with_validity_samples(8)
                .with_fraction_steps(2);
            for method in Method::ALL {
                let f = mesh_morph(&a, &b, method, &[0.0, 1.0], &opts)
                    .unwrap_or_else(|e| panic!("{na} {method}: {e}"));
                assert!(
                    rel_diff(&f[0].points, &a.points) < 1e-9,
                    "{na} {method} t=0"
                );
                assert!(
                    rel_diff(&f[1].points, &b.points) < 1e-9,
                    "{na} {method} t=1"
                );
                assert!(f[0].valid && f[1].valid);
            }
        }
    }
}

#[test]
fn power_one_is_convex_and_search_finds_a_valid_power() {
    let (a, b) = (mesh("fg_rotated9_a.json"), mesh("fg_rotated9_b.json"));
    let ts = times(21);
    let opts = MeshMorphOptions::DEFAULT;
    let convex = mesh_morph(&a, &b, Method::Convex, &ts, &opts).unwrap();
    let power = mesh_morph(
        &a,
        &b,
        Method::Power,
        &ts,
        &opts.clone().with_power(Some(1)),
    )
    .unwrap();
    for (c, p) in convex.iter().zip(&power) {
        assert!(rel_diff(&c.points, &p.points) < 1e-9);
    }
    let choice = power_choice(&a, &b, &ts, &opts).unwrap();
    assert!(choice.m >= 1);
    let searched = mesh_morph(&a, &b, Method::Power, &ts, &opts).unwrap();
    assert!(all_valid(&searched));
}

#[test]
fn power_approaches_linear_when_linear_is_valid() {
    let a = mesh("grid6_a.obj");
    let mut pts = a.points.clone();
    pts[14] += Point::new(0.01, -0.005);
    let b = Tiling::new(pts, a.faces.clone()).unwrap();
    assert!(check_linear(&a, &b).is_valid());
    let ts = times(9);
    let opts = MeshMorphOptions::DEFAULT.with_max_power(16);
    assert_eq!(power_choice(&a, &b, &ts, &opts).unwrap().m, 16);
    let lin = mesh_morph(&a, &b, Method::Linear, &ts, &opts).unwrap();
    // Local is linear-reducible (Surazhsky & Gotsman *Controllable Morphing*
    // Theorem 4.1).
    let local = mesh_morph(&a, &b, Method::Local, &ts, &opts).unwrap();
    for (l, m) in lin.iter().zip(&local) {
        assert!(rel_diff(&l.points, &m.points) < 1e-9);
    }
}

#[test]
fn appendix_a_agrees_with_dense_sampling_on_random_stars() {
    let mut rng = Rng::xorshift_star(0x5eed_1234_abcd_0001);
    let star = |rng: &mut Rng, d: usize| -> (Point, Vec<Point>) {
        // Valid star: sorted angles with gaps below π.
        loop {
            let mut ang: Vec<f64> = (0..d)
                .map(|_| rng.range(0.0, std::f64::consts::TAU))
                .collect();
            ang.sort_by(f64::total_cmp);
            let ok = (0..d).all(|j| {
                let next = if j + 1 < d {
                    ang[j + 1]
                } else {
                    ang[0] + std::f64::consts::TAU
                };
                next - ang[j] < 3.0
            });
            if ok {
                let c = Point::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
                let ring = ang
                    .iter()
                    .map(|&a| c + rng.range(0.3, 2.0) * Point::new(a.cos(), a.sin()))
                    .collect();
                return (c, ring);
            }
        }
    };
    let samples = 4000;
    let (mut valid, mut invalid) = (0, 0);
    for _ in 0..400 {
        let d = 3 + (rng.unit() * 5.0) as usize;
        let (c0, r0) = star(&mut rng, d);
        let (c1, r1) = star(&mut rng, d);
        let exact = check_star_linear(c0, &r0, c1, &r1);
        let sampled_bad = (0..=samples).find_map(|k| {
            let t = k as f64 / samples as f64;
            let c = c0.lerp(c1, t);
            (0..d).find_map(|j| {
                let k2 = (j + 1) % d;
                let o = orient(c, r0[j].lerp(r1[j], t), r0[k2].lerp(r1[k2], t));
                (!o.is_ccw()).then_some((j, t))
            })
        });
        match (exact, sampled_bad) {
            (Ok(()), None) => valid += 1,
            (Err((_, from, to)), Some((_, t))) => {
                invalid += 1;
                assert!(from <= to + 1e-12);
                let _ = t;
            }
            (Ok(()), Some(bad)) => panic!("exact says valid, sampling fails at {bad:?}"),
            (Err((j, from, to)), None) => {
                // Only a failure narrower than the sampling step may be missed.
                assert!(
                    to - from < 2.0 / samples as f64,
                    "sector {j} fails on [{from}, {to}]"
                );
            }
        }
    }
    assert!(
        valid > 20 && invalid > 20,
        "{valid} valid, {invalid} invalid"
    );
}

/// The polar boundary morph (Floater & Gotsman, "How to morph tilings
/// injectively", §6) as seen in the frames: about the centre that moves
/// linearly between the two boundaries' vertex centroids, each boundary
/// vertex's distance and (unwrapped) angle change linearly in t. Moving
/// the boundary vertices on straight lines gives neither; the test
/// measures by how much, so that it tells the two apart.
#[test]
fn different_boundaries_use_the_polar_boundary_morph() {
    let (a, b) = (mesh("square5_a.json"), mesh("rotated5_b.json"));
    let boundary = a.boundary();
    assert!(boundary.len() >= 3);
    let centre = |t: &Tiling| {
        boundary
            .iter()
            .map(|&v| t.points[v as usize])
            .sum::<Point>()
            / boundary.len() as f64
    };
    let (ca, cb) = (centre(&a), centre(&b));
    let centre_at = |t: f64| ca.lerp(cb, t);
    let ts = times(40);
    // Distance of vertex v from the moving centre at time t, against the
    // linear interpolation of its two end distances (relative error).
    let radius_error = |points: &[Point], v: u32, t: f64| {
        let (ra, rb) = (
            (a.points[v as usize] - ca).length(),
            (b.points[v as usize] - cb).length(),
        );
        let want = (1.0 - t) * ra + t * rb;
        ((points[v as usize] - centre_at(t)).length() - want).abs() / want
    };
    // The straight-line boundary misses the radius property by far.
    let straight_miss = ts
        .iter()
        .flat_map(|&t| {
            let points: Vec<Point> = a
                .points
                .iter()
                .zip(&b.points)
                .map(|(p, q)| p.lerp(*q, t))
                .collect();
            boundary
                .iter()
                .map(|&v| radius_error(&points, v, t))
                .collect::<Vec<_>>()
        })
        .fold(0.0, f64::max);
    assert!(straight_miss > 0.05, "{straight_miss}");
    for method in [Method::Convex, Method::Intrinsic, Method::Local] {
        let frames = mesh_morph(&a, &b, method, &ts, &MeshMorphOptions::DEFAULT).unwrap();
        assert!(all_valid(&frames), "{method}");
        assert!(rel_diff(&frames[0].points, &a.points) < 1e-12, "{method}");
        assert!(
            rel_diff(&frames[ts.len() - 1].points, &b.points) < 1e-12,
            "{method}"
        );
        for &v in &boundary {
            // The angle about the moving centre, unwrapped along the frames
            // (consecutive frames turn by far less than half a turn).
            let mut angle = vec![0.0];
            for w in frames.windows(2) {
                let p = w[0].points[v as usize] - centre_at(w[0].t);
                let q = w[1].points[v as usize] - centre_at(w[1].t);
                angle.push(angle[angle.len() - 1] + p.perp_dot(q).atan2(p.dot(q)));
            }
            let total = angle[angle.len() - 1];
            assert!(total.abs() > 0.1, "{method}: vertex {v} turns by {total}");
            for (f, frame) in frames.iter().enumerate() {
                let e = radius_error(&frame.points, v, frame.t);
                assert!(
                    e < 1e-9,
                    "{method}: vertex {v} at t = {}: radius off by {e}",
                    frame.t
                );
                let drift = (angle[f] - frame.t * total).abs();
                assert!(
                    drift < 1e-9,
                    "{method}: vertex {v} at t = {}: angle off by {drift}",
                    frame.t
                );
            }
        }
    }
}

#[test]
fn morph_through_an_intermediate_tiling() {
    let (a, b) = (mesh("fg_rotated9_a.json"), mesh("fg_rotated9_b.json"));
    let mid = mesh_morph(&a, &b, Method::Local, &[0.5], &MeshMorphOptions::DEFAULT).unwrap();
    let m = Tiling::new(mid[0].points.clone(), a.faces.clone()).unwrap();
    for method in [Method::Convex, Method::Intrinsic] {
        let opts = MeshMorphOptions::DEFAULT.with_intermediate(Some(m.clone()), 0.4);
        let ts = times(101);
        let frames = mesh_morph(&a, &b, method, &ts, &opts).unwrap();
        assert!(all_valid(&frames), "{method}");
        let at = mesh_morph(&a, &b, method, &[0.4], &opts).unwrap();
        assert!(rel_diff(&at[0].points, &m.points) < 1e-9, "{method}");
    }
    let opts = MeshMorphOptions::DEFAULT.with_intermediate(Some(m), 0.4);
    assert!(mesh_morph(&a, &b, Method::Local, &[0.5], &opts).is_err());
}

#[test]
fn bad_inputs_are_errors_not_panics() {
    let a = mesh("fg_4_3_a.json");
    let q = mesh("quads5_a.json");
    assert!(mesh_morph(&a, &q, Method::Convex, &[0.5], &MeshMorphOptions::DEFAULT).is_err());
    assert!(
        mesh_morph(
            &a,
            &a,
            Method::Convex,
            &[f64::NAN],
            &MeshMorphOptions::DEFAULT
        )
        .is_err()
    );
    assert!(mesh_morph(&a, &a, Method::Convex, &[1.5], &MeshMorphOptions::DEFAULT).is_err());
    assert!(matches!(check_linear(&a, &q), LinearCheck::Incompatible(_)));
    for text in [
        "",
        "v 0 0\n",
        "v nan 0\nv 1 0\nv 0 1\nf 1 2 3\n",
        "v inf 0\nv 1 0\nv 0 1\nf 1 2 3\n",
        "v 0 0\nv 1 0\nv 0 1\nf 1 2 99999999999\n",
        "v 0 0\nv 1 0\nv 0 1\nf 1 2\n",
        "v 0 0\nv 1 0\nv 0 1\nf 1 2 3\nf 1 2 3\n",
        "v 0 0\nv 1 0\nv 0 1\nv 5 5\nf 1 2 3\n",
        "v 0 0\nv 1 0\nv 0 1\nf 1 3 2\n",
        "v 0 0\nv 1 0\nv 2 0\nf 1 2 3\n",
        "f 1 2 3\n",
        "v 1e300 0\nv 1 0\nv 0 1\nf 1 2 3\n",
    ] {
        assert!(Tiling::from_obj_str(text).is_err(), "{text:?}");
    }
    for text in [
        "",
        "{}",
        "[]",
        r#"{"points": [], "faces": []}"#,
        r#"{"points": [[0,0],[1,0],[0,1]], "faces": [[0,1,-1]]}"#,
        r#"{"points": [[0,0],[1,0],[0,1]], "faces": [[0,1,7]]}"#,
        r#"{"points": [[0,0],[1,0],[0,1]], "faces": [[0,1,2,0]]}"#,
        r#"{"points": [[0,0],[1,0]], "faces": [[0,1]]}"#,
    ] {
        assert!(Tiling::from_json_str(text).is_err(), "{text:?}");
    }
}

#[test]
fn reader_errors_name_the_face_and_file() {
    // Face 1 is clockwise.
    let text = r#"{"points": [[0,0],[1,0],[1,1],[0,1]], "faces": [[0,1,2],[0,3,2]]}"#;
    let err = Tiling::from_json_str(text).unwrap_err();
    let msg = err.to_string();
    assert!(
        matches!(
            err,
            TilingError::FaceNotConvex { face: 1, .. }
                | TilingError::InconsistentEdge { face: 1, .. }
        ),
        "{msg}"
    );
    assert!(msg.contains("face 1") && msg.contains("hint"), "{msg}");
    let err = Tiling::from_obj_str("v 0 0\nv 1 0\nv 0 1\nf 1 2 3\nf 1 2 4\n").unwrap_err();
    assert!(err.to_string().contains("face 1"), "{err}");
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.obj");
    std::fs::write(&path, "v 0 0\nv 1 0\nv 0 1\nf 1 3 2\n").unwrap();
    let msg = Tiling::from_path(&path).unwrap_err().to_string();
    assert!(msg.contains("bad.obj") && msg.contains("face 0"), "{msg}");
    let msg = Tiling::from_path(&dir.path().join("missing.json"))
        .unwrap_err()
        .to_string();
    assert!(msg.contains("missing.json"), "{msg}");
}

#[test]
fn method_names_round_trip() {
    for m in Method::ALL {
        assert_eq!(m.as_str().parse::<Method>().unwrap(), m);
    }
    assert_eq!(MeshMorphOptions::default(), MeshMorphOptions::DEFAULT);
}

#[test]
fn tilings_without_interior_vertices_morph() {
    let a = Tiling::from_json_str(r#"{"points": [[0,0],[1,0],[1,1],[0,1]], "faces": [[0,1,2,3]]}"#)
        .unwrap();
    let b = Tiling::from_json_str(r#"{"points": [[0,0],[2,0],[2,1],[0,1]], "faces": [[0,1,2,3]]}"#)
        .unwrap();
    for method in Method::ALL {
        let f = mesh_morph(&a, &b, method, &times(5), &MeshMorphOptions::DEFAULT).unwrap();
        assert!(all_valid(&f), "{method}");
        assert!(rel_diff(&f[4].points, &b.points) < 1e-12, "{method}");
    }
    assert!(check_linear(&a, &b).is_valid());
}
