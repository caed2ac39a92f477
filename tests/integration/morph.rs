//! Morphs between pairs of reference curves: every frame an immersion
//! (checked again here with the exact checker), endpoints reproduce the
//! inputs, no jumps, area within the endpoints' range, and
//! morph(A, B) = morph(B, A) reversed.

use crate::util::curve;
use immerse::Curve;
use immerse::check;
use immerse::frames::Frame;
use immerse::geom::Point;
use immerse::morph::{CurveMorphOptions, Tween};
use testkit::morph_pair;

use pairs::reference_pairs;
use testkit::pairs;

fn load(name: &str) -> Curve {
    Curve::from_path(curve(name)).unwrap_or_else(|e| panic!("{e}"))
}

fn fractions(k: usize) -> Vec<f64> {
    (0..k).map(|i| i as f64 / (k - 1) as f64).collect()
}

fn diag(points: &[Point]) -> f64 {
    immerse::geom::polygon::bbox_diagonal(points)
}

fn area(f: &Frame) -> f64 {
    f.total_area()
}

/// `frame` holds `curve`'s vertices in cyclic order starting at `shift`,
/// every other vertex lying on the edge between the originals
/// around it.
fn reproduces(frame: &[Point], curve: &[Point], shift: usize) {
    let n = frame.len();
    let m = curve.len();
    let mut j = 0;
    let mut last_original = None;
    for i in 0..n {
        let p = frame[(i + shift) % n];
        if j < m && p == curve[j] {
            last_original = Some(j);
            j += 1;
        } else {
            let a = last_original.map_or(curve[m - 1], |k| curve[k]);
            let b = curve[j % m];
            // Inserted at a + t (b - a), rounded to f64: on the edge to
            // within rounding.
            let e = b - a;
            let off = e.perp_dot(p - a).abs() / e.length();
            assert!(
                off <= 1e-12 * e.length(),
                "inserted vertex {i} is {off} off its edge"
            );
            let t = (p - a).dot(e) / e.length_squared();
            assert!(t > 0.0 && t < 1.0, "inserted vertex {i} outside its edge");
        }
    }
    assert_eq!(j, m, "only {j} of {m} original vertices found in order");
}

#[test]
fn reference_pairs_morph_with_every_frame_an_immersion() {
    let pairs = reference_pairs();
    assert!(pairs.len() >= 20);
    let options = CurveMorphOptions::DEFAULT;
    for (sa, sb) in &pairs {
        let (sa, sb) = (sa.as_str(), sb.as_str());
        let (a, b) = (load(sa), load(sb));
        // 40 displacement-timed frames.
        let (report, m40) = morph_pair(&a.points, &b.points, &fractions(40), &options)
            .unwrap_or_else(|e| panic!("{sa} -> {sb}: {e}"));
        assert_eq!(m40.frames.len(), 40);
        for f in &m40.frames {
            assert_eq!(f.points.len(), report.n);
            if let Err(e) = check(&f.points, &f.triangles) {
                panic!("{sa} -> {sb} at t = {}: {e}", f.t);
            }
        }
        reproduces(&m40.frames[0].points, &a.points, 0);
        // The last frame is the target, re-indexed by the shift.
        let last = &m40.frames[39].points;
        let n = last.len();
        let unshifted: Vec<Point> = (0..n).map(|i| last[(i + n - report.shift) % n]).collect();
        reproduces(&unshifted, &b.points, 0);
        // No jumps: a vertex moves at most a quarter of the diagonal.
        let d = diag(&a.points).max(diag(&b.points));
        for w in m40.frames.windows(2) {
            let step = w[0]
                .points
                .iter()
                .zip(&w[1].points)
                .map(|(p, q)| (*p - *q).length())
                .fold(0.0, f64::max);
            assert!(
                step <= 0.25 * d,
                "{sa} -> {sb}: a vertex moved {step} (diagonal {d})"
            );
        }
        // No collapse or ballooning: the fitted paths may shrink like the
        // linear morph, but the total area stays within half the smaller
        // and twice the larger endpoint's (STRAIGHT_AREA_RANGE).
        let (a0, a1) = (area(&m40.frames[0]), area(&m40.frames[39]));
        let (lo, hi) = (a0.min(a1), a0.max(a1));
        for f in &m40.frames {
            let x = area(f);
            assert!(
                x >= lo * 0.5 * (1.0 - 1e-9) && x <= hi * 2.0 * (1.0 + 1e-9),
                "{sa} -> {sb}: area {x} outside [{lo}/2, 2·{hi}] at t = {}",
                f.t
            );
        }
        // 400 dense values.
        let (_, m400) = morph_pair(&a.points, &b.points, &fractions(400), &options).unwrap();
        for f in &m400.frames {
            assert!(
                check(&f.points, &f.triangles).is_ok(),
                "{sa} -> {sb} dense t = {}",
                f.t
            );
        }
    }
}

#[test]
fn the_hybrid_route_keeps_the_total_area_in_the_fitted_range() {
    use immerse::morph::{MorphOptions, ThirdVertexPath};
    /// The library's `STRAIGHT_AREA_RANGE`.
    const AREA_RANGE: (f64, f64) = (0.81, 1.13);
    let options = CurveMorphOptions::DEFAULT
        .with_morph(MorphOptions::DEFAULT.with_path(ThirdVertexPath::Hybrid));
    for (sa, sb) in &reference_pairs() {
        let (a, b) = (load(sa), load(sb));
        let (_, m) = morph_pair(&a.points, &b.points, &fractions(40), &options)
            .unwrap_or_else(|e| panic!("{sa} -> {sb}: {e}"));
        let (a0, a1) = (area(&m.frames[0]), area(&m.frames[39]));
        // The range of every fitted path (STRAIGHT_AREA_RANGE); frames
        // interpolate keys whose chords keep the path's total area within
        // 1 % (docs/design.md §7c), and the range leaves room for that
        // inside the motion gate [0.8, 1.15].
        let (lo, hi) = (a0.min(a1) * AREA_RANGE.0, a0.max(a1) * AREA_RANGE.1);
        for f in &m.frames {
            let x = area(f);
            assert!(
                x >= lo * (1.0 - 0.01) && x <= hi * (1.0 + 0.01),
                "{sa} -> {sb}: area {x} outside [{lo}, {hi}] at t = {}",
                f.t
            );
        }
    }
}

#[test]
fn morph_backwards_is_the_same_sequence_reversed() {
    let options = CurveMorphOptions::DEFAULT;
    for (sa, sb) in &reference_pairs() {
        let (sa, sb) = (sa.as_str(), sb.as_str());
        let (a, b) = (load(sa), load(sb));
        let fr = fractions(41);
        let (ra, ab) = morph_pair(&a.points, &b.points, &fr, &options).unwrap();
        let (rb, ba) = morph_pair(&b.points, &a.points, &fr, &options).unwrap();
        // NaN for a side that was not finished, in both directions.
        let bits = |x: f64, y: f64| (x.to_bits(), y.to_bits());
        assert_eq!(
            bits(ra.u_star, ra.v_star),
            bits(rb.v_star, rb.u_star),
            "{sa} {sb}: {ra:?} {rb:?}"
        );
        assert_eq!(ra.flips, rb.flips);
        let n = ra.n;
        let k = ra.shift;
        assert_eq!(
            (k + rb.shift) % n,
            0,
            "{sa} {sb}: shifts {k} and {}",
            rb.shift
        );
        let tol = 1e-9 * diag(&a.points).max(diag(&b.points));
        let last = ab.frames.len() - 1;
        for (j, f) in ab.frames.iter().enumerate() {
            let g = &ba.frames[last - j];
            for i in 0..n {
                let (p, q) = (f.points[i], g.points[(i + k) % n]);
                assert!(
                    (p - q).length() <= tol,
                    "{sa} {sb}: frame {j} vertex {i}: {p} vs {q}"
                );
            }
        }
    }
}

#[test]
fn the_disk_route_is_valid_and_symmetric_too() {
    use immerse::morph::Intermediate;
    let options = CurveMorphOptions::DEFAULT.with_intermediate(Intermediate::Disk);
    for (sa, sb) in &reference_pairs() {
        let (sa, sb) = (sa.as_str(), sb.as_str());
        let (a, b) = (load(sa), load(sb));
        let (ra, ab) = morph_pair(&a.points, &b.points, &fractions(400), &options).unwrap();
        assert!(ra.used_disk);
        for f in &ab.frames {
            assert!(
                check(&f.points, &f.triangles).is_ok(),
                "{sa} -> {sb} t = {}",
                f.t
            );
        }
        let (_, ba) = morph_pair(&b.points, &a.points, &fractions(400), &options).unwrap();
        let (n, k) = (ra.n, ra.shift);
        let tol = 1e-9 * diag(&a.points).max(diag(&b.points));
        for (j, f) in ab.frames.iter().enumerate() {
            let g = &ba.frames[ab.frames.len() - 1 - j];
            for i in 0..n {
                assert!(
                    (f.points[i] - g.points[(i + k) % n]).length() <= tol,
                    "{sa} {sb}"
                );
            }
        }
    }
}

#[test]
fn the_target_route_needs_no_disk_on_the_reference_pairs() {
    let options = CurveMorphOptions::DEFAULT;
    let mut disk = Vec::new();
    for (sa, sb) in reference_pairs() {
        let (a, b) = (load(&sa), load(&sb));
        let (r, _) = morph_pair(&a.points, &b.points, &fractions(10), &options).unwrap();
        if r.used_disk {
            disk.push((sa, sb));
        }
    }
    assert!(disk.is_empty(), "needed the disk: {disk:?}");
}

#[test]
fn the_best_correspondence_is_symmetric() {
    use immerse::morph::Correspondence;
    let best = CurveMorphOptions::DEFAULT.with_correspondence(Correspondence::Best);
    let fr = fractions(21);
    for (sa, sb) in reference_pairs().into_iter().take(8) {
        let (a, b) = (load(&sa), load(&sb));
        let (ra, ab) = morph_pair(&a.points, &b.points, &fr, &best).unwrap();
        let (rb, ba) = morph_pair(&b.points, &a.points, &fr, &best).unwrap();
        assert_eq!((ra.shift + rb.shift) % ra.n, 0, "{sa} {sb}");
        let (n, k) = (ra.n, ra.shift);
        for (j, f) in ab.frames.iter().enumerate() {
            let g = &ba.frames[ab.frames.len() - 1 - j];
            for i in 0..n {
                assert!(
                    (f.points[i] - g.points[(i + k) % n]).length() < 1e-9,
                    "{sa} {sb}"
                );
            }
            assert!(f.is_immersion());
        }
    }
}

/// The measures of docs/design.md §7c for one pair at the default
/// options: the largest single-vertex step at 40, 320 and 2,560 frames,
/// and the other view measures, detour and unwind at 320 frames. Every
/// frame is checked exactly on the way (`Tween::morph`).
fn view_of(a: &str, b: &str) -> ([f64; 3], immerse::frames::ViewMeasures, f64, f64) {
    use immerse::frames::{detour, unwind, view_measures};
    let (ca, cb) = (load(a), load(b));
    let tween = Tween::new(&ca.points, &cb.points, &CurveMorphOptions::DEFAULT)
        .unwrap_or_else(|e| panic!("{a} → {b}: {e}"));
    let mut steps = [0.0; 3];
    let mut at_320 = None;
    for (i, count) in [40, 320, 2560].into_iter().enumerate() {
        let morph = tween
            .morph(&fractions(count))
            .unwrap_or_else(|e| panic!("{a} → {b}: {e}"));
        assert!(
            morph.fallbacks.is_empty(),
            "{a} → {b}: {:?}",
            morph.fallbacks
        );
        let v = view_measures(&morph.frames).expect("a constant vertex count");
        steps[i] = v.max_step;
        if count == 320 {
            at_320 = Some((v, detour(&morph.frames), unwind(&morph.frames)));
        }
    }
    let (v, d, u) = at_320.expect("320 frames measured");
    (steps, v, d, u)
}

/// Continuity (docs/design.md §7c): a continuous motion's largest
/// single-vertex step shrinks in proportion to the frame count, a jump
/// does not. From 40 to 320 frames and from 320 to 2,560 it must shrink
/// at least 4× or stay under 1 % of the diagonal.
fn assert_continuous(name: &str, steps: [f64; 3]) {
    let ok = |a: f64, b: f64| b <= a / 4.0 || b < 0.01;
    assert!(
        ok(steps[0], steps[1]) && ok(steps[1], steps[2]),
        "{name}: largest step {:.4} / {:.4} / {:.4} of the diagonal at 40 / 320 / 2,560 frames",
        steps[0],
        steps[1],
        steps[2]
    );
}

/// The per-pair gates of docs/design.md §7c on `a` → `b`: continuous, no
/// spike, no collapse or ballooning, unwind at least 0.9, detour at most
/// 3. Returns the detour and the angle ratio.
fn assert_pair_gates(name: &str, a: &str, b: &str) -> (f64, f64) {
    let (steps, v, detour, unwind) = view_of(a, b);
    assert_continuous(name, steps);
    assert!(
        v.edge_ratio <= 2.0,
        "{name}: edge ratio {:.2}",
        v.edge_ratio
    );
    assert!(
        v.area_low >= 0.8 && v.area_high <= 1.15,
        "{name}: area [{:.3}, {:.3}]",
        v.area_low,
        v.area_high
    );
    assert!(unwind >= 0.9, "{name}: unwind {unwind:.3} < 0.9");
    assert!(detour <= 3.0, "{name}: detour {detour:.2} > 3");
    (detour, v.angle_ratio)
}

/// The gates of [`assert_pair_gates`] on every pair of `list` (every
/// fourth in the debug profile), and over the pairs the median detour at
/// most 1.5 and the median angle ratio at least 0.5. Returns how many
/// pairs were morphed.
fn assert_set_gates(list: Vec<(String, String)>) -> usize {
    let stride = if cfg!(debug_assertions) { 4 } else { 1 };
    let (mut detours, mut angles) = (Vec::new(), Vec::new());
    for (a, b) in list.into_iter().step_by(stride) {
        let (detour, angle) = assert_pair_gates(&format!("{a} → {b}"), &a, &b);
        detours.push(detour);
        angles.push(angle);
    }
    let count = detours.len() * stride;
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let (d, g) = (median(detours), median(angles));
    assert!(d <= 1.5, "median detour {d:.2}");
    assert!(g >= 0.5, "median angle ratio {g:.2}");
    count
}

/// Motion on the pairs of `curves/motion-pairs.list` with the default
/// options (docs/motion.md): every gate of docs/design.md §7c at once on
/// every pair. Continuous (the largest step shrinks with the frame count),
/// no spike (no edge past 2× the ends' longest), no collapse or
/// ballooning (total area within [0.8 × the smaller end, 1.15 × the
/// larger]), no undoing of overlaps (unwind ≥ 0.9), no pair's detour past
/// 3; over the pairs the median detour at most 1.5 and the median angle
/// ratio at least 0.5. In the debug profile every fourth pair.
#[test]
fn motion_meets_its_goal_on_the_motion_pairs() {
    let count = assert_set_gates(pairs::motion_pairs());
    assert!(count >= 20, "{count} motion pairs");
}

/// The same gates on `curves/reference-pairs.list`, every pair held to
/// unwind 0.9. An annulus sector against a coarse curl kept 0.89 when
/// matched by outline (its cap fell in the middle of the curl's outer
/// edge); matched cap to cap by the corners rule's wide window it keeps
/// 1.00 (docs/motion.md). A letter E against a 5-point star kept 0.80
/// with the correspondence that travels least (the E's inner corners turn
/// against the star's points, and every path straightens them on the
/// way); the min-flips correspondence, raced in where the kept plan
/// unwinds, keeps 0.92.
#[test]
fn motion_meets_its_goal_on_the_reference_pairs() {
    assert_set_gates(reference_pairs());
}

/// The two sides of a plan race on the target route (each is given up
/// once it travels farther than the other finished), so which side is
/// given up depends on the cores; what is kept must not. One core, two
/// and three give the same report and the same frames, bit for bit.
#[test]
fn the_result_does_not_depend_on_the_number_of_cores() {
    let options = CurveMorphOptions::DEFAULT;
    let fr = fractions(21);
    let on = |threads: usize, a: &[Point], b: &[Point]| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let (report, m) = pool.install(|| morph_pair(a, b, &fr, &options)).unwrap();
        let frames: Vec<Vec<(u64, u64)>> = m
            .frames
            .iter()
            .map(|f| {
                f.points
                    .iter()
                    .map(|p| (p.x.to_bits(), p.y.to_bits()))
                    .collect()
            })
            .collect();
        (format!("{report:?}"), frames)
    };
    for (sa, sb) in &reference_pairs() {
        let (a, b) = (load(sa), load(sb));
        let one = on(1, &a.points, &b.points);
        for threads in [2, 3] {
            let other = on(threads, &a.points, &b.points);
            assert_eq!(one.0, other.0, "{sa} -> {sb}: report on {threads} threads");
            assert!(
                one.1 == other.1,
                "{sa} -> {sb}: frames on {threads} threads"
            );
        }
    }
}

/// The corners rule pairs the strips' edges piece by piece: spiral strips
/// wound 720° and 1080° then share a triangulation (no flip) and every
/// frame is an immersion; swapping the curves pairs the same vertices.
/// Curves whose corners do not match up fall back to the outline rule,
/// and say so.
#[test]
fn the_corners_rule_matches_strip_edges_and_says_when_it_cannot() {
    use immerse::morph::Correspondence;
    let options = CurveMorphOptions::DEFAULT.with_correspondence(Correspondence::Corners);
    let (a, b) = (
        load("spiral-strip-720deg-n200.json"),
        load("spiral-strip-1080deg-n400.json"),
    );
    let (report, m) = morph_pair(&a.points, &b.points, &fractions(21), &options).unwrap();
    assert_eq!(report.flips, 0, "{report:?}");
    assert!(report.fallbacks.is_empty(), "{:?}", report.fallbacks);
    for f in &m.frames {
        assert!(check(&f.points, &f.triangles).is_ok(), "t = {}", f.t);
    }
    let (back, _) = morph_pair(&b.points, &a.points, &fractions(21), &options).unwrap();
    assert_eq!((report.shift + back.shift) % report.n, 0);
    let (t, s) = (load("triangle.json"), load("square.json"));
    let (report, m) = morph_pair(&t.points, &s.points, &fractions(11), &options).unwrap();
    assert!(
        report
            .fallbacks
            .iter()
            .any(|f| f.what.contains("outline rule") && f.why.contains("corners")),
        "{:?}",
        report.fallbacks
    );
    assert!(
        m.frames
            .iter()
            .all(|f| check(&f.points, &f.triangles).is_ok())
    );
}

/// A morph leaves its first curve and reaches its last continuously, even
/// where a triangle is thin down to rounding (the stress generators'
/// collinear runs: angles of 10⁻¹⁵ rad). The angle rule once floored
/// single angles at 10⁻¹², which moved such a triangle's third vertex
/// along its base: the frames next to an end sat a tenth of the diagonal
/// away from it. Frames 10⁻¹⁰ from either end now lie within 10⁻⁶ of the
/// diagonal of it.
#[test]
fn a_morph_meets_its_ends_continuously_through_triangles_thin_to_rounding() {
    for index in [24, 1452, 1547] {
        let p = testkit::stress::pair(0x2026b, index);
        let tween = Tween::new(&p.source, &p.target, &CurveMorphOptions::DEFAULT)
            .unwrap_or_else(|e| panic!("stress pair {index}: {e}"));
        let d = diag(&p.source).max(diag(&p.target));
        for (end, near) in [(0.0, 1e-10), (1.0, 1.0 - 1e-10)] {
            let (a, b) = (tween.frame(end).unwrap(), tween.frame(near).unwrap());
            let gap = a
                .points
                .iter()
                .zip(&b.points)
                .map(|(p, q)| p.distance(*q))
                .fold(0.0, f64::max);
            assert!(
                gap <= 1e-6 * d,
                "stress pair {index}: the frame at t = {near} lies {gap:.3e} from the one at t = {end} (diagonal {d:.3e})"
            );
        }
    }
}

/// The straight path through triangles whose angle rule is thin: the
/// stress generators' collinear runs and short edges (stress pairs 77,
/// 341 and 1014 of seed 0x2026b, where the defaults take `straight`). Its
/// floor step once blended such a triangle toward the rule's angles by an
/// amount decided by rounding, so its third vertex switched between two
/// places along its base from frame to frame; now the largest step
/// shrinks with the frame count (docs/design.md §7c).
#[test]
fn the_straight_path_is_continuous_where_the_angle_rule_is_thin() {
    continuous_on_stress_pairs(0x2026b, &[77, 341, 1014]);
}

/// The rigid guide's least-squares solve meets its ends only up to
/// rounding, which thin strips make large: the path then jumped onto its
/// snapped end over the last 10⁻¹³ of its parameter. What the solve misses
/// at each end is now spread over t, and stress pairs 403, 750 and 1451
/// of seed 0x2026b (thin strips and wedges, where the defaults take
/// `rigid`) are continuous.
#[test]
fn the_rigid_path_is_continuous_where_its_solve_misses_the_ends() {
    continuous_on_stress_pairs(0x2026b, &[403, 750, 1451]);
}

/// Where a path is at the limit of double-precision rounding (wedges,
/// glued and thin strips, thin curls), its keys and frames once left it:
/// a frame whose interpolation the rounding turned over was taken from
/// another path at that t alone, and a path midpoint that failed the exact
/// check left its segment uncertified. Now frames keep to their segment
/// and their path (nudged at most 2⁻²⁰ of the segment), segments are split
/// elsewhere where the midpoint fails, and merged keys are certified with
/// the margin of double-precision interpolation. Stress pairs 538, 902,
/// 918, 1288 and 1965 of seed 0x2026b jumped under one or another of
/// these and are continuous.
#[test]
fn frames_keep_to_their_path_where_its_rounding_turns_thin_triangles_over() {
    continuous_on_stress_pairs(0x2026b, &[538, 902, 918, 1288, 1965]);
}

/// The min-flips correspondence is raced in where the plan kept unwinds,
/// but only where its keys are certified wherever the first plan's are:
/// on stress pair 1135 of seed 0x2026b (thin spiral → thin spiral) it
/// keeps the turning but leaves segments uncertified, and the morph
/// jumped there.
#[test]
fn the_correspondence_race_keeps_the_motion_continuous() {
    continuous_on_stress_pairs(0x2026b, &[1135]);
}

/// The as-rigid-as-possible guide is a least-squares solve whose
/// elimination, on thin triangles far apart in size, cancels all but 10⁻⁹
/// to 10⁻¹⁵ of some diagonal entries: solved once in double precision, its
/// rounding changed from one t to the next by up to 2 % of the diagonal
/// (stress pair 616 of seed 0x2026b), and every frame laid out from it
/// shook. Stress pairs 335, 616, 985, 1257 and 1951 jumped at 2,560
/// frames; the refined solve (or, where it cannot converge, the straight
/// guide, reported) keeps them continuous.
#[test]
fn the_rigid_guide_is_continuous_where_its_solve_cancels() {
    continuous_on_stress_pairs(0x2026b, &[335, 616, 985, 1257, 1951]);
    // Where the refined solve cannot converge, the straight guide stands
    // in, and the report says so.
    for index in [335, 1257] {
        let p = testkit::stress::pair(0x2026b, index);
        let tween = Tween::new(&p.source, &p.target, &CurveMorphOptions::DEFAULT).unwrap();
        assert!(
            tween
                .report()
                .fallbacks
                .iter()
                .any(|f| f.what.contains("rigid path") && f.what.contains("straight guide")),
            "stress pair {index}: {:?}",
            tween.report().fallbacks
        );
    }
}

/// The morph kept must not depend on the cores. The two sides of a plan
/// are built side by side, one on each core; on stress pair 552 of seed
/// 0xbee5 (strip → thin spiral) the target's last leg gave its side up
/// once two of its paths passed the limit that the source's finished
/// travel set, a limit that fell at a time that depended on scheduling:
/// the source's side was kept on one thread (its `rigid` path jumped, the
/// largest step 0.0279 of the diagonal at 320 frames and still 0.0201 at
/// 2,560) and, in most runs, the target's on two.
#[test]
fn the_morph_is_the_same_on_any_number_of_cores() {
    let p = testkit::stress::pair(0xbee5, 552);
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool");
        pool.install(|| Tween::new(&p.source, &p.target, &CurveMorphOptions::DEFAULT).unwrap())
    };
    let (one, two) = (on(1), on(2));
    let what = |t: &Tween| {
        let r = t.report();
        (r.used, r.shift, r.paths.clone(), r.fallbacks.clone())
    };
    assert_eq!(what(&one), what(&two), "the plans on one thread and on two");
    let frames = |t: &Tween| {
        let frames = t.morph(&fractions(40)).unwrap().frames;
        frames.into_iter().map(|f| f.points).collect::<Vec<_>>()
    };
    assert!(
        frames(&one) == frames(&two),
        "the frames on one thread and on two differ"
    );
    let steps = [40, 320, 2560].map(|count| {
        let morph = two.morph(&fractions(count)).unwrap();
        immerse::frames::view_measures(&morph.frames)
            .expect("a constant vertex count")
            .max_step
    });
    assert_continuous("stress pair 552 of seed 0xbee5", steps);
}

/// A frame that its key segment fails comes from the segment's bridge
/// (the straight path planned between its two keys, as close to the
/// chord as validity allows) before the leg's own path. Where the keys
/// could not follow the path (their splitting budget spent), a frame on
/// the chord and the next one on the path lay far apart: on stress pair
/// 253 of seed 0x2026b (thin curl → wedge, the `polar` path) a vertex
/// moved 15 % of the diagonal between two frames 1/2,560 apart.
#[test]
fn frames_a_segment_fails_come_from_its_bridge_before_the_path() {
    continuous_on_stress_pairs(0x2026b, &[253]);
}

/// Continuity (as [`assert_continuous`]) of the default morph of the
/// given stress pairs of `seed`.
fn continuous_on_stress_pairs(seed: u64, indices: &[u64]) {
    for &index in indices {
        let p = testkit::stress::pair(seed, index);
        let tween = Tween::new(&p.source, &p.target, &CurveMorphOptions::DEFAULT)
            .unwrap_or_else(|e| panic!("stress pair {index}: {e}"));
        let mut steps = [0.0; 3];
        for (i, count) in [40, 320, 2560].into_iter().enumerate() {
            let morph = tween.morph(&fractions(count)).unwrap();
            steps[i] = immerse::frames::view_measures(&morph.frames)
                .expect("a constant vertex count")
                .max_step;
        }
        assert_continuous(&format!("stress pair {index}"), steps);
    }
}
