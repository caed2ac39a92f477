//! Property tests (proptest) on random immersed disks.
//!
//! A random immersed disk is built by gluing triangles along a random tree:
//! start with one counter-clockwise triangle; repeatedly pick an edge
//! (a, b) of the current boundary and attach a new triangle (a, c, b),
//! with c placed on the outer side of a→b. The new triangle may overlap
//! earlier ones; the map stays an immersion as long as every triangle is
//! counter-clockwise (decided exactly) and no vertex's fan of angles
//! reaches 2π (a step that would break this is skipped). Every vertex stays
//! on the boundary, so the glued triangles are themselves a triangulation
//! of the boundary polygon by diagonals, all valid: the DP must find one.
//!
//! Each property has a bounded number of cases so that the module runs in
//! a few seconds in release. Failures are shrunk and saved to
//! `tests/regressions/properties.txt`, which proptest replays first on
//! every run (commit that file when it appears).

use immerse::Curve;
use immerse::correspond::{compatible_shift, degree_sequence, shift_triangles};
use immerse::geom::polygon::{Turning, is_simple, triangle_angles, turning_number};
use immerse::geom::{Orientation, Point, orient};
use immerse::{Quality, triangulate_with};
use immerse::{check, is_valid_triangle, triangulate};
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;
use std::f64::consts::TAU;

/// Most triangles glued into one disk.
const MAX_TRIANGLES: usize = 24;

/// Margin below 2π for a vertex's fan of angles (measured in floating
/// point, so the exact validity test cannot disagree with it).
const FAN_MARGIN: f64 = 1e-6;

/// One gluing step: which boundary edge, where along it, how far out.
type Step = (u32, f64, f64);

/// A glued immersed disk: its boundary polygon (counter-clockwise, turning
/// number +1) and the glued triangles as a triangulation of that polygon.
#[derive(Clone, Debug)]
struct Disk {
    points: Vec<Point>,
    triangles: Vec<[u32; 3]>,
}

/// Glues a disk from `steps`; `rotate` picks the boundary vertex that comes
/// first and `scale` multiplies every coordinate.
fn glue(steps: &[Step], rotate: usize, scale: f64) -> Disk {
    let mut pos = vec![
        Point::new(0.0, 0.0),
        Point::new(1.0, 0.0),
        Point::new(0.3, 0.9),
    ];
    let mut fan = vec![0.0; 3];
    for (v, a) in triangle_angles(pos[0], pos[1], pos[2])
        .into_iter()
        .enumerate()
    {
        fan[v] = a;
    }
    let mut tris: Vec<[usize; 3]> = vec![[0, 1, 2]];
    // The boundary as vertex ids in counter-clockwise order.
    let mut boundary: Vec<usize> = vec![0, 1, 2];
    for &(edge, t, h) in steps {
        let i = edge as usize % boundary.len();
        let (a, b) = (boundary[i], boundary[(i + 1) % boundary.len()]);
        let (pa, pb) = (pos[a], pos[b]);
        let d = pb - pa;
        // Outer side of a→b on a counter-clockwise boundary: the right.
        let c = pa + t * d + h * Point::new(d.y, -d.x);
        if orient(pa, c, pb) != Orientation::CounterClockwise {
            continue;
        }
        let [at_a, at_c, at_b] = triangle_angles(pa, c, pb);
        if fan[a] + at_a >= TAU - FAN_MARGIN || fan[b] + at_b >= TAU - FAN_MARGIN {
            continue; // the fan at a or b would wrap: not an immersion
        }
        fan[a] += at_a;
        fan[b] += at_b;
        fan.push(at_c);
        pos.push(c);
        let id = pos.len() - 1;
        tris.push([a, id, b]);
        boundary.insert(i + 1, id);
    }
    let n = boundary.len();
    let first = rotate % n;
    let order: Vec<usize> = (0..n).map(|k| boundary[(first + k) % n]).collect();
    let mut place = vec![0u32; n];
    for (k, &v) in order.iter().enumerate() {
        place[v] = k as u32;
    }
    let points = order.iter().map(|&v| pos[v] * scale).collect();
    let mut triangles: Vec<[u32; 3]> = tris
        .iter()
        .map(|t| {
            let mut s = t.map(|v| place[v]);
            s.sort_unstable();
            s
        })
        .collect();
    triangles.sort_unstable();
    Disk { points, triangles }
}

/// Random gluing steps, boundary rotation and a power-of-ten scale.
fn disks() -> impl Strategy<Value = Disk> {
    (
        prop::collection::vec(
            (any::<u32>(), 0.05f64..0.95, 0.15f64..4.0),
            0..=MAX_TRIANGLES,
        ),
        any::<usize>(),
        -6i32..=6,
    )
        .prop_map(|(steps, rotate, e)| glue(&steps, rotate, 10f64.powi(e)))
}

/// Random polygons: grid points (collinear triples, cusps, repeated
/// vertices) or points in general position.
fn polygons() -> impl Strategy<Value = Vec<Point>> {
    prop_oneof![
        prop::collection::vec((-3i8..=3, -3i8..=3), 3..12).prop_map(|v| v
            .into_iter()
            .map(|(x, y)| Point::new(f64::from(x), f64::from(y)))
            .collect()),
        prop::collection::vec((-1e3f64..1e3, -1e3f64..1e3), 3..30)
            .prop_map(|v| v.into_iter().map(|(x, y)| Point::new(x, y)).collect()),
    ]
}

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "tests/regressions/properties.txt",
        ))),
        // A fixed seed keeps CI deterministic; change it locally to explore.
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x1433_25e0),
        ..ProptestConfig::default()
    }
}

/// The plain interval DP, unfiltered and cell by cell, with the literal
/// validity predicate: is there a triangulation by valid triangles?
fn plain_dp(points: &[Point]) -> bool {
    let n = points.len();
    let mut q = vec![vec![false; n]; n];
    for i in (0..n - 1).rev() {
        q[i][i + 1] = true;
        for j in i + 2..n {
            q[i][j] = (i + 1..j).any(|k| q[i][k] && q[k][j] && is_valid_triangle(points, i, k, j));
        }
    }
    q[0][n - 1]
}

fn rotated<T: Copy>(v: &[T], k: usize) -> Vec<T> {
    let n = v.len();
    (0..n).map(|i| v[(i + k) % n]).collect()
}

proptest! {
    #![proptest_config(config(96))]

    /// The glued triangles are an immersion triangulation of the boundary,
    /// so the DP finds one, and so do the Delaunay and max–min variants.
    #[test]
    fn glued_disks_are_self_overlapping(disk in disks()) {
        prop_assert_eq!(check(&disk.points, &disk.triangles), Ok(()), "the gluing itself");
        prop_assert_eq!(turning_number(&disk.points), Turning::Number(1));
        for q in Quality::ALL {
            let imm = triangulate_with(&disk.points, q);
            prop_assert!(imm.is_ok(), "{q}: {:?} on {:?}", imm, disk.points);
            let imm = imm.unwrap();
            prop_assert_eq!(imm.points.len(), disk.points.len());
            prop_assert_eq!(check(&imm.points, &imm.triangles), Ok(()), "{}", q);
        }
    }

    /// The decision (filtered, parallel, bitset DP) agrees with the plain
    /// DP on random polygons and on glued disks, turned by a rotation so
    /// the chord filter sees every vertex at every place.
    #[test]
    fn the_decision_agrees_with_the_plain_dp(
        points in polygons(),
        disk in disks(),
        k in any::<usize>(),
    ) {
        for p in [points, rotated(&disk.points, k % disk.points.len())] {
            if turning_number(&p) != Turning::Number(1) {
                continue;
            }
            let imm = triangulate(&p);
            prop_assert_eq!(imm.is_ok(), plain_dp(&p), "{:?}", p);
            if let Ok(imm) = imm {
                prop_assert_eq!(check(&imm.points, &imm.triangles), Ok(()));
            }
        }
    }

    /// Reversing a polygon negates its turning number (and a cusp stays a
    /// cusp, at the mirrored vertex).
    #[test]
    fn reversing_negates_the_turning_number(points in polygons(), disk in disks()) {
        for p in [points, disk.points] {
            let mut r = p.clone();
            r.reverse();
            let n = p.len();
            match turning_number(&p) {
                Turning::Number(k) => prop_assert_eq!(turning_number(&r), Turning::Number(-k)),
                Turning::Cusp(_) => prop_assert!(
                    matches!(turning_number(&r), Turning::Cusp(j) if j < n),
                    "{:?}", turning_number(&r)
                ),
            }
        }
    }

    /// Rotating a triangulated polygon rotates its degree sequence;
    /// `compatible_shift` finds a shift that maps one onto the other, and
    /// `shift_triangles` by it recovers the triangulation exactly.
    /// Compatibility of two triangulations does not depend on where either
    /// polygon starts.
    #[test]
    fn compatibility_is_invariant_under_cyclic_shift(
        disk in disks(),
        r in any::<usize>(),
        s in any::<usize>(),
    ) {
        let n = disk.points.len();
        let (r, s) = (r % n, s % n);
        let glued = degree_sequence(n, &disk.triangles);
        prop_assert_eq!(glued.iter().sum::<u32>() as usize, 3 * (n - 2));
        // The same triangulation, vertex v renamed v − r (mod n).
        let renamed = shift_triangles(n, &disk.triangles, r);
        let moved = degree_sequence(n, &renamed);
        prop_assert_eq!(&moved, &rotated(&glued, r));
        let k = compatible_shift(&glued, &moved);
        prop_assert!(k.is_some(), "{:?} vs {:?}", glued, moved);
        let k = k.unwrap();
        for i in 0..n {
            prop_assert_eq!(glued[i], moved[(i + k) % n]);
        }
        let mut back = shift_triangles(n, &renamed, k);
        back.sort_unstable();
        prop_assert_eq!(&back, &disk.triangles);
        // The renamed triangulation fits the rotated polygon.
        let points = rotated(&disk.points, r);
        prop_assert_eq!(check(&points, &renamed), Ok(()));

        // Another triangulation of the same disk: compatible or not, the
        // answer survives rotating either sequence.
        let other = triangulate(&disk.points).expect("a glued disk is self-overlapping");
        let d2 = degree_sequence(n, &other.triangles);
        let answer = compatible_shift(&glued, &d2).is_some();
        prop_assert_eq!(compatible_shift(&rotated(&glued, r), &d2).is_some(), answer);
        prop_assert_eq!(compatible_shift(&glued, &rotated(&d2, s)).is_some(), answer);
        prop_assert_eq!(compatible_shift(&d2, &glued).is_some(), answer);
    }

    /// Writing a curve's points as JSON and reading them back gives the
    /// same points, bit for bit; a clockwise curve comes back reversed with
    /// its first point first.
    #[test]
    fn curve_json_round_trip(disk in disks(), name in "[a-z][a-z0-9 -]{0,12}") {
        let xy: Vec<[f64; 2]> = disk.points.iter().map(|p| [p.x, p.y]).collect();
        let json = serde_json::json!({"name": name, "points": xy}).to_string();
        let c = Curve::from_json_str(&json, "prop.json").unwrap();
        prop_assert_eq!(&c.name, &name);
        prop_assert!(!c.reversed);
        prop_assert_eq!(c.dropped, 0);
        prop_assert_eq!(&c.points, &disk.points, "{}", json);

        let mut cw = xy.clone();
        cw[1..].reverse();
        let bare = serde_json::to_string(&cw).unwrap();
        let c = Curve::from_json_str(&bare, "prop.json").unwrap();
        prop_assert!(c.reversed);
        prop_assert_eq!(c.turning_number_as_given(), Some(-1));
        prop_assert_eq!(&c.points, &disk.points, "{}", bare);
    }
}

/// The generator is worth its name: most disks it makes have a boundary
/// that crosses itself, and they are not tiny.
#[test]
fn glued_disks_are_mostly_self_intersecting() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[7; 32]);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let strategy = (
        prop::collection::vec((any::<u32>(), 0.05f64..0.95, 0.15f64..4.0), MAX_TRIANGLES),
        any::<usize>(),
    );
    let (mut crossing, mut sizes) = (0, 0);
    let total = 200;
    for _ in 0..total {
        let (steps, rotate) = strategy.new_tree(&mut runner).unwrap().current();
        let disk = glue(&steps, rotate, 1.0);
        assert_eq!(check(&disk.points, &disk.triangles), Ok(()));
        crossing += usize::from(!is_simple(&disk.points));
        sizes += disk.points.len();
    }
    assert!(
        crossing * 2 > total,
        "only {crossing} of {total} cross themselves"
    );
    assert!(sizes > total * 15, "mean size {}", sizes / total);
}

/// A disk glued by hand: the second triangle would make the fan at vertex
/// 0 wrap past 2π once more triangles go around it, so those steps are
/// skipped and the result stays an immersion.
#[test]
fn glue_skips_steps_that_would_wrap_a_fan() {
    // Many triangles on the edges at vertex 0 (edge index 0 is (0, new)
    // after each insertion), pushed far out: the fan at 0 fills up.
    let steps: Vec<Step> = (0..40).map(|_| (0, 0.5, 2.0)).collect();
    let disk = glue(&steps, 0, 1.0);
    assert!(disk.points.len() < 42, "some steps were skipped");
    assert_eq!(check(&disk.points, &disk.triangles), Ok(()));
    assert!(triangulate(&disk.points).is_ok());
}

proptest! {
    #![proptest_config(config(32))]

    /// Morphing any two glued disks (different sizes, scales and vertex
    /// counts, mostly self-intersecting): every frame is an immersion by
    /// the exact checker, the ends are the inputs, and morph(B, A) is
    /// morph(A, B) reversed — on both routes.
    #[test]
    fn morphs_between_glued_disks_are_immersions_and_symmetric(
        a in disks(),
        b in disks(),
        disk_route in any::<bool>(),
    ) {
        use immerse::morph::{CurveMorphOptions, Intermediate};
        use testkit::morph_pair;
        let options = CurveMorphOptions::DEFAULT.with_intermediate(if disk_route {
            Intermediate::Disk
        } else {
            Intermediate::Target
        });
        let fr: Vec<f64> = (0..=24).map(|i| f64::from(i) / 24.0).collect();
        let (ra, ab) = morph_pair(&a.points, &b.points, &fr, &options).unwrap();
        let (rb, ba) = morph_pair(&b.points, &a.points, &fr, &options).unwrap();
        for f in &ab.frames {
            prop_assert_eq!(check(&f.points, &f.triangles), Ok(()), "t = {}", f.t);
        }
        // The larger input keeps its vertices; the smaller gets vertices
        // inserted on its edges, so compare the first frame's originals.
        let first = &ab.frames[0].points;
        prop_assert!(a.points.iter().all(|p| first.contains(p)));
        let last = &ab.frames[ab.frames.len() - 1].points;
        prop_assert!(b.points.iter().all(|p| last.contains(p)));
        let (n, k) = (ra.n, ra.shift);
        prop_assert_eq!((k + rb.shift) % n, 0);
        let scale = a.points.iter().chain(&b.points).map(|p| p.abs().max_element()).fold(0.0, f64::max);
        for (j, f) in ab.frames.iter().enumerate() {
            let g = &ba.frames[ab.frames.len() - 1 - j];
            for i in 0..n {
                prop_assert!((f.points[i] - g.points[(i + k) % n]).length() <= 1e-9 * scale);
            }
        }
    }
}
