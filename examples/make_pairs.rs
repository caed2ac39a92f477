//! Writes the compatible curve pairs of `curves/pairs/` (deterministic,
//! fixed seed): `cargo run --release --example make_pairs`.
//!
//! Each pair is two files, `NAME.source.json` and `NAME.target.json`
//! (`{"name": ..., "points": [[x, y], ...]}`, y up, counter-clockwise),
//! with vertex i of the source matched to vertex i of the target. The
//! source is a curve of `curves/` as immerse reads it (cleaned, oriented,
//! SVG flattened and flipped). Two kinds of target:
//!
//! - **similarity**: the source rotated, scaled and translated;
//! - **deformation**: an immersion triangulation T of the source (Delaunay
//!   for most pairs; the DP witness `any` or `maxmin` for the pairs named
//!   `*-on-any` / `*-on-maxmin`, so that every quality has pairs it applies
//!   to) with every triangle's three
//!   angles multiplied by random factors exp(s·u), u uniform in [−1, 1],
//!   renormalised to sum π, blended toward the source's angles just enough
//!   that every vertex fan sum is at most 2π − min(0.05, (2π − S_src(v))/2)
//!   (S_src(v) the source's fan sum at v), laid out again along the dual
//!   tree with [`immerse::morph::lay_out`] and fitted by a similarity
//!   (least-squares rotation, then √area and area centroid of the source).
//!   T is an immersion of the target by construction.
//!
//! Every written target is checked: it reads back with the same point
//! count, it is self-overlapping (`triangulate_with(.., Delaunay)` succeeds)
//! and T (Delaunay for similarity pairs) passes the exact
//! [`immerse::check`] on it. The run fails otherwise. The table
//! printed lists, per pair, which qualities' source triangulations are
//! immersions of the target.

use std::f64::consts::{PI, TAU};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use immerse::Curve;
use immerse::check;
use immerse::geom::Point;
use immerse::geom::polygon::triangle_angles;
use immerse::morph::{area_and_centroid, lay_out};
use immerse::{Quality, triangulate_with};
use testkit::Rng;

/// Seed of the deformations (xorshift64).
const SEED: u64 = 0x1d2c_3b4a_5968_7788;

/// Fan margin ε of the deformation blend (radians).
const FAN_MARGIN: f64 = 0.05;

/// How a pair's target is made.
enum Kind {
    /// Rotate by `angle` degrees, scale by `scale`, then translate by
    /// (`dx`, `dy`) times the source's bounding-box diagonal.
    Similarity {
        angle: f64,
        scale: f64,
        dx: f64,
        dy: f64,
    },
    /// Random angle factors exp(s·u), u uniform in [−1, 1], applied to the
    /// source's triangulation of quality `on`.
    Deformation { strength: f64, on: Quality },
}

/// The pairs: (pair name, source file in `curves/`, kind).
fn pairs() -> Vec<(&'static str, &'static str, Kind)> {
    use Kind::{Deformation, Similarity};
    vec![
        (
            "blob-similarity",
            "blob-n64.json",
            Similarity {
                angle: 40.0,
                scale: 0.6,
                dx: 0.5,
                dy: -0.2,
            },
        ),
        (
            "spiral-540-similarity",
            "spiral-strip-540deg-n120.json",
            Similarity {
                angle: 120.0,
                scale: 1.8,
                dx: -0.3,
                dy: 0.4,
            },
        ),
        (
            "tail-loop-similarity",
            "tail-loop.svg",
            Similarity {
                angle: -75.0,
                scale: 1.3,
                dx: 0.2,
                dy: 0.2,
            },
        ),
        (
            "blob-deformation",
            "blob-n64.json",
            Deformation {
                strength: 1.5,
                on: Quality::Delaunay,
            },
        ),
        (
            "letter-S-deformation",
            "letter-S-n62.json",
            Deformation {
                strength: 1.5,
                on: Quality::Delaunay,
            },
        ),
        (
            "comb-deformation",
            "comb-8-teeth.json",
            Deformation {
                strength: 1.5,
                on: Quality::Delaunay,
            },
        ),
        (
            "circular-strip-450-deformation",
            "circular-strip-450deg-n60.json",
            Deformation {
                strength: 1.5,
                on: Quality::Delaunay,
            },
        ),
        (
            "spiral-540-deformation",
            "spiral-strip-540deg-n120.json",
            Deformation {
                strength: 1.2,
                on: Quality::Delaunay,
            },
        ),
        (
            "immersed-disk-40-deformation",
            "immersed-disk-n40.json",
            Deformation {
                strength: 1.5,
                on: Quality::Delaunay,
            },
        ),
        (
            "ribbon-curl-deformation",
            "ribbon-curl.svg",
            Deformation {
                strength: 1.5,
                on: Quality::Delaunay,
            },
        ),
        (
            "letter-S-deformation-on-any",
            "letter-S-n62.json",
            Deformation {
                strength: 1.5,
                on: Quality::Any,
            },
        ),
        (
            "circular-strip-450-deformation-on-any",
            "circular-strip-450deg-n60.json",
            Deformation {
                strength: 1.5,
                on: Quality::Any,
            },
        ),
        (
            "comb-deformation-on-maxmin",
            "comb-8-teeth.json",
            Deformation {
                strength: 1.5,
                on: Quality::MaxMin,
            },
        ),
    ]
}

fn bbox_diag(p: &[Point]) -> f64 {
    let (mut lo, mut hi) = (Point::splat(f64::INFINITY), Point::splat(f64::NEG_INFINITY));
    for &q in p {
        lo = lo.min(q);
        hi = hi.max(q);
    }
    (hi - lo).length()
}

/// Fan sums of an angle vector.
fn fan_sums(n: usize, triangles: &[[u32; 3]], angles: &[[f64; 3]]) -> Vec<f64> {
    let mut s = vec![0.0; n];
    for (t, a) in triangles.iter().zip(angles) {
        for k in 0..3 {
            s[t[k] as usize] += a[k];
        }
    }
    s
}

/// The deformed target (see the module docs).
fn deform(src: &[Point], triangles: &[[u32; 3]], strength: f64, rng: &mut Rng) -> Vec<Point> {
    let n = src.len();
    let orig: Vec<[f64; 3]> = triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| src[v as usize]);
            triangle_angles(a, b, c)
        })
        .collect();
    let rnd: Vec<[f64; 3]> = orig
        .iter()
        .map(|a| {
            let f = a.map(|x| x * (strength * (2.0 * rng.unit() - 1.0)).exp());
            let s = f[0] + f[1] + f[2];
            f.map(|x| x * PI / s)
        })
        .collect();
    let (sr, so) = (fan_sums(n, triangles, &rnd), fan_sums(n, triangles, &orig));
    let mut lambda: f64 = 0.0;
    for v in 0..n {
        let cap = TAU - FAN_MARGIN.min((TAU - so[v]) / 2.0);
        if sr[v] > cap {
            lambda = lambda.max((sr[v] - cap) / (sr[v] - so[v]));
        }
    }
    let ang: Vec<[f64; 3]> = rnd
        .iter()
        .zip(&orig)
        .map(|(r, o)| [0, 1, 2].map(|k| (1.0 - lambda) * r[k] + lambda * o[k]))
        .collect();
    let laid = lay_out(n, triangles, &ang).expect("a triangulation of the n-gon");
    fit(&laid, src, triangles)
}

/// The similarity image of `p` whose rotation best matches `to` (least
/// squares about the area centroids) and whose √area and area centroid
/// are `to`'s.
fn fit(p: &[Point], to: &[Point], triangles: &[[u32; 3]]) -> Vec<Point> {
    let (ap, cp) = area_and_centroid(p, triangles);
    let (at, ct) = area_and_centroid(to, triangles);
    // Complex least squares: the a minimising Σ |a·(p − cp) − (q − ct)|².
    let mut num = Point::ZERO;
    for (&x, &y) in p.iter().zip(to) {
        let (u, v) = (x - cp, y - ct);
        // conj(u)·v as a complex number.
        num += Point::new(u.dot(v), u.perp_dot(v));
    }
    let rot = num.normalize_or(Point::X) * (at / ap).sqrt();
    p.iter().map(|&x| rot.rotate(x - cp) + ct).collect()
}

fn similarity(src: &[Point], angle: f64, scale: f64, dx: f64, dy: f64) -> Vec<Point> {
    let d = bbox_diag(src);
    let rot = Point::from_angle(angle.to_radians()) * scale;
    let shift = Point::new(dx, dy) * d;
    src.iter().map(|&p| rot.rotate(p) + shift).collect()
}

fn write_curve(path: &Path, name: &str, points: &[Point]) {
    let mut s = format!("{{\"name\": \"{name}\", \"points\": [\n");
    for (i, p) in points.iter().enumerate() {
        let sep = if i + 1 == points.len() { "" } else { "," };
        writeln!(s, "  [{:?}, {:?}]{sep}", p.x, p.y).unwrap();
    }
    s.push_str("]}\n");
    std::fs::write(path, s).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out_dir: PathBuf = root.join("curves").join("pairs");
    std::fs::create_dir_all(&out_dir).unwrap();
    let mut rng = Rng::xorshift(SEED);
    println!("| pair | source | n | kind | simple (src/dst) | T_q(src) valid on dst |");
    println!("|---|---|---:|---|---|---|");
    for (name, file, kind) in pairs() {
        let curve = Curve::from_path(root.join("curves").join(file))
            .unwrap_or_else(|e| panic!("{file}: {e}"));
        let src = curve.points.clone();
        let on = match kind {
            Kind::Similarity { .. } => Quality::Delaunay,
            Kind::Deformation { on, .. } => on,
        };
        let tri = triangulate_with(&src, on)
            .unwrap_or_else(|e| panic!("{file} is not self-overlapping: {e}"))
            .triangles;
        let (dst, kind_s) = match kind {
            Kind::Similarity {
                angle,
                scale,
                dx,
                dy,
            } => (
                similarity(&src, angle, scale, dx, dy),
                format!("similarity (rotate {angle}°, scale {scale})"),
            ),
            Kind::Deformation { strength, .. } => (
                deform(&src, &tri, strength, &mut rng),
                format!("deformation of T_{on} (s = {strength})"),
            ),
        };
        let src_path = out_dir.join(format!("{name}.source.json"));
        let dst_path = out_dir.join(format!("{name}.target.json"));
        write_curve(&src_path, &format!("{name} source"), &src);
        write_curve(&dst_path, &format!("{name} target"), &dst);
        // Read both back as a user would, and verify.
        let a = Curve::from_path(&src_path).unwrap_or_else(|e| panic!("{e}"));
        let b = Curve::from_path(&dst_path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(a.points, src, "{name}: source changed on reading");
        assert_eq!(b.points, dst, "{name}: target changed on reading");
        assert!(
            triangulate_with(&b.points, Quality::Delaunay).is_ok(),
            "{name}: target is not self-overlapping"
        );
        let ok = check(&b.points, &tri);
        assert!(
            ok.is_ok(),
            "{name}: the source's {on} triangulation fails on the target: {ok:?}"
        );
        println!(
            "| {name} | {file} | {} | {kind_s} | {}/{} | {} |",
            src.len(),
            a.is_simple(),
            b.is_simple(),
            Quality::ALL
                .into_iter()
                .filter(|&q| triangulate_with(&src, q).is_ok_and(|imm| check(
                    &b.points,
                    &imm.triangles
                )
                .is_ok()))
                .map(Quality::as_str)
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
}
