//! Stress pairs: seeded generators of self-overlapping
//! curves, the pair driver that morphs two of them and checks every frame
//! exactly, the regression-file format and a small shrinker.
//!
//! One copy, shared by the integration tests (`tests/integration/stress.rs`),
//! the long-run driver (`examples/stress.rs`) and the examples that draw
//! stress curves (`motion_view`, `bench_dp`).
//!
//! Everything is reproducible from `(seed, pair index)` alone: pair `i`
//! draws from its own random stream ([`Rng::stream`]), so pairs can be run
//! in any order, in parallel, or one at a time.
//!
//! Every generated curve goes through the same reading path as a user's
//! file: its points are written as JSON and read back with
//! [`Curve::from_json_str`] (range checks, duplicate removal, orientation),
//! and it is kept only when [`immerse::triangulate`] says it is
//! self-overlapping. Outputs that are not are counted as discards.

use crate::Rng;
use crate::shapes::bounds;
use immerse::Curve;
use immerse::Quality;
use immerse::geom::Point;
use immerse::geom::polygon::triangle_angles;
use immerse::geom::{Orientation, orient};
use immerse::morph::{Correspondence, Counts, CurveMorphOptions, Intermediate, MorphReport};
use immerse::triangulate;
use std::f64::consts::{PI, TAU};
use std::fmt::Write as _;

/// The default seed of the stress runs (the short test and the long run).
pub const DEFAULT_SEED: u64 = 0x1717_5eed;

/// Largest curve the generators aim for (after cleaning a curve can only
/// get smaller).
pub const MAX_SIZE: usize = 200;

/// The max–min-angle triangulation is O(n³): pairs with more vertices
/// than this (after equalising counts) use `any` or `delaunay` instead.
pub const MAX_MAXMIN_SIZE: usize = 150;

/// Folder of shrunk failing pairs that `stress_regressions_all_morph`
/// replays, relative to the package root.
pub const REGRESSION_DIR: &str = "tests/stress-regressions";

// ---------------------------------------------------------------------
// Random numbers

/// A size from 3 to [`MAX_SIZE`], log-uniform (small curves are common,
/// large ones appear often enough).
pub fn size(rng: &mut Rng) -> usize {
    let lo = 3f64.ln();
    let hi = (MAX_SIZE as f64 + 1.0).ln();
    (rng.range(lo, hi).exp().floor() as usize).clamp(3, MAX_SIZE)
}

// ---------------------------------------------------------------------
// Generators

/// A family of self-overlapping curves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Generator {
    /// A thin triangle: height 1e-9..1e-3 of its length, apex anywhere
    /// above (or beyond) the base; sometimes with points on its edges.
    Wedge,
    /// A thin straight strip: height 1e-9..1e-1 of its length, points at
    /// random stations on both long sides.
    Strip,
    /// A thin strip curled along a spiral, wrapping 10°–1200°, width
    /// 1e-9..1e-3 of its length; consecutive wraps often overlap.
    ThinSpiral,
    /// A thin strip along a centreline that curls 200°–1080° and crosses
    /// itself (a cursive loop), width 1e-9..1e-3 of its length.
    ThinCurl,
    /// A random immersed disk on an integer grid with runs of exactly
    /// collinear points inserted on its edges (lattice points), often under
    /// an exact transform that keeps them collinear.
    Collinear,
    /// An ordinary curve (blob, spiral, curl or glued disk) with one corner
    /// cut by an edge of 1e-12..1e-6 of the perimeter.
    ShortEdge,
    /// A star-shaped blob (simple).
    Blob,
    /// A spiral strip of ordinary width wrapping 200°–1080°.
    Spiral,
    /// A limaçon-like loop: a thick strip whose centreline curls
    /// 200°–1080° and crosses itself.
    Curl,
    /// A random immersed disk glued from triangles along a random tree.
    Glued,
    /// A glued immersed disk of slivers (heights 1e-9..1e-2 of the edge).
    GluedThin,
}

impl Generator {
    /// Every generator.
    pub const ALL: [Generator; 11] = [
        Generator::Wedge,
        Generator::Strip,
        Generator::ThinSpiral,
        Generator::ThinCurl,
        Generator::Collinear,
        Generator::ShortEdge,
        Generator::Blob,
        Generator::Spiral,
        Generator::Curl,
        Generator::Glued,
        Generator::GluedThin,
    ];

    /// A short name.
    pub fn as_str(self) -> &'static str {
        match self {
            Generator::Wedge => "wedge",
            Generator::Strip => "strip",
            Generator::ThinSpiral => "thin-spiral",
            Generator::ThinCurl => "thin-curl",
            Generator::Collinear => "collinear",
            Generator::ShortEdge => "short-edge",
            Generator::Blob => "blob",
            Generator::Spiral => "spiral",
            Generator::Curl => "curl",
            Generator::Glued => "glued",
            Generator::GluedThin => "glued-thin",
        }
    }

    /// The generator of this name.
    pub fn from_name(name: &str) -> Option<Generator> {
        Generator::ALL.into_iter().find(|g| g.as_str() == name)
    }

    /// Raw points (before the random transform) of about `n` points.
    fn raw(self, rng: &mut Rng, n: usize) -> Raw {
        match self {
            Generator::Wedge => wedge(rng, n),
            Generator::Strip => strip(rng, n),
            Generator::ThinSpiral => {
                let w = rng.pow10(-9.0, -3.0);
                spiral(rng, n, (10.0, 1200.0), Width::OfLength(w))
            }
            Generator::ThinCurl => {
                let w = rng.pow10(-9.0, -3.0);
                curl(rng, n, (200.0, 1080.0), Width::OfLength(w))
            }
            Generator::Collinear => collinear(rng, n),
            Generator::ShortEdge => short_edge(rng, n),
            Generator::Blob => Raw::plain(blob(rng, n)),
            Generator::Spiral => {
                let w = rng.range(0.02, 0.35);
                spiral(rng, n, (200.0, 1080.0), Width::OfRadius(w))
            }
            Generator::Curl => {
                let w = rng.range(0.05, 0.95);
                curl(rng, n, (200.0, 1080.0), Width::OfRadius(w))
            }
            Generator::Glued => Raw::plain(glued(rng, n, false)),
            Generator::GluedThin => Raw::plain(glued(rng, n, true)),
        }
    }
}

fn rng_turn(rng: &mut Rng, lo_deg: f64, hi_deg: f64) -> f64 {
    rng.range(lo_deg, hi_deg).to_radians()
}

/// A generator's points and whether they lie on an integer grid (so that an
/// exact transform keeps their collinear runs exactly collinear).
struct Raw {
    points: Vec<Point>,
    grid: bool,
}

impl Raw {
    fn plain(points: Vec<Point>) -> Raw {
        Raw {
            points,
            grid: false,
        }
    }
}

/// Inserts `k` points at random positions on random edges of the closed
/// polygon (by `lerp`, so exactly on axis-parallel edges, within rounding
/// on the others).
fn insert_on_edges(rng: &mut Rng, p: &[Point], k: usize) -> Vec<Point> {
    let n = p.len();
    let mut per_edge: Vec<Vec<f64>> = vec![Vec::new(); n];
    for _ in 0..k {
        let e = rng.int(0, n - 1);
        per_edge[e].push(rng.range(0.001, 0.999));
    }
    let mut out = Vec::with_capacity(n + k);
    for (i, ts) in per_edge.iter_mut().enumerate() {
        ts.sort_by(f64::total_cmp);
        out.push(p[i]);
        let (a, b) = (p[i], p[(i + 1) % n]);
        out.extend(ts.iter().map(|&t| a.lerp(b, t)));
    }
    out
}

/// A thin triangle of length 1 and height 1e-9..1e-3, the apex above the
/// base or beyond either end of it (an obtuse sliver); with probability
/// 0.6 more points on its edges.
fn wedge(rng: &mut Rng, n: usize) -> Raw {
    let h = rng.pow10(-9.0, -3.0);
    let t = rng.range(-0.4, 1.4);
    let tri = [Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(t, h)];
    let points = if rng.chance(0.4) || n <= 3 {
        tri.to_vec()
    } else {
        insert_on_edges(rng, &tri, n - 3)
    };
    Raw::plain(points)
}

/// A thin rectangle of length 1 and height 1e-9..1e-1 with points at
/// random stations along both long sides (exactly collinear before the
/// transform).
fn strip(rng: &mut Rng, n: usize) -> Raw {
    let h = rng.pow10(-9.0, -1.0);
    let n = n.max(4);
    let bottom = rng.int(2, n - 2);
    let top = n - bottom;
    let stations = |rng: &mut Rng, k: usize| -> Vec<f64> {
        let mut x: Vec<f64> = (0..k.saturating_sub(2))
            .map(|_| rng.range(0.0, 1.0))
            .collect();
        x.extend([0.0, 1.0]);
        x.sort_by(f64::total_cmp);
        x.dedup();
        x
    };
    let mut points: Vec<Point> = stations(rng, bottom)
        .into_iter()
        .map(|x| Point::new(x, 0.0))
        .collect();
    // The top side, right to left; its ends may overhang a little.
    let (l, r) = if rng.chance(0.5) {
        (0.0, 1.0)
    } else {
        (rng.range(-0.01, 0.01), 1.0 + rng.range(-0.01, 0.01))
    };
    points.extend(
        stations(rng, top)
            .into_iter()
            .rev()
            .map(|x| Point::new(l + x * (r - l), h)),
    );
    Raw::plain(points)
}

/// How wide a strip is.
#[derive(Clone, Copy)]
enum Width {
    /// A fraction of the centreline's length.
    OfLength(f64),
    /// A fraction of the smallest safe width (twice the smallest radius of
    /// curvature of the centreline).
    OfRadius(f64),
}

/// Closes a strip around a centreline given as stations `c` with unit
/// normals `nrm`: the right side forward, the left side back.
fn strip_around(c: &[Point], nrm: &[Point], w: f64) -> Vec<Point> {
    let half = 0.5 * w;
    let mut out: Vec<Point> = c.iter().zip(nrm).map(|(&p, &v)| p - half * v).collect();
    out.extend(c.iter().zip(nrm).rev().map(|(&p, &v)| p + half * v));
    out
}

/// A strip around the spiral r(φ) = 1 + g φ / 2π, φ ∈ [0, θ]: with
/// |g| below the width the wraps overlap (the curve crosses itself);
/// sometimes g is larger and the spiral is simple.
fn spiral(rng: &mut Rng, n: usize, turn_deg: (f64, f64), width: Width) -> Raw {
    let theta = rng_turn(rng, turn_deg.0, turn_deg.1);
    // At most 40° per station, and at least two stations per side.
    let min_stations = (theta / 40f64.to_radians()).ceil() as usize + 2;
    let m = (n / 2).max(min_stations).min(MAX_SIZE / 2);
    let turns = theta / TAU;
    let len_est = theta; // radius about 1
    let w = match width {
        Width::OfLength(f) => f * len_est,
        Width::OfRadius(f) => f,
    };
    let mut g = if rng.chance(0.7) {
        w * rng.range(-1.5, 1.5)
    } else {
        rng.range(-0.3, 0.3) / turns.max(1.0)
    };
    // Keep the inner side well away from the centre.
    if 1.0 + g * turns - 0.5 * w < 0.3 {
        g = g.abs();
    }
    let stations: Vec<f64> = (0..m).map(|i| theta * i as f64 / (m - 1) as f64).collect();
    let mut c = Vec::with_capacity(m);
    let mut nrm = Vec::with_capacity(m);
    for &phi in &stations {
        let r = 1.0 + g * phi / TAU;
        let (s, co) = phi.sin_cos();
        c.push(Point::new(r * co, r * s));
        // Left of the direction of travel (counter-clockwise): inward.
        nrm.push(Point::new(-co, -s));
    }
    Raw::plain(strip_around(&c, &nrm, w))
}

/// A strip around a centreline whose direction turns by θ along a smooth
/// bump of curvature in the middle (straight lead-in and lead-out), so the
/// centreline curls and crosses itself, like a limaçon's inner loop.
fn curl(rng: &mut Rng, n: usize, turn_deg: (f64, f64), width: Width) -> Raw {
    let theta = rng_turn(rng, turn_deg.0, turn_deg.1);
    let min_stations = (theta / 30f64.to_radians()).ceil() as usize + 4;
    let m = (n / 2).max(min_stations).min(MAX_SIZE / 2);
    let a = rng.range(0.05, 0.35);
    let b = rng.range(0.65, 0.95);
    let sign = if rng.chance(0.5) { 1.0 } else { -1.0 };
    // Turning angle φ(s) = sign θ S((s − a)/(b − a)), S the cubic
    // smoothstep; max |φ'| = 1.5 θ / (b − a) over a centreline of length 1.
    let phi = |s: f64| {
        let u = ((s - a) / (b - a)).clamp(0.0, 1.0);
        sign * theta * u * u * (3.0 - 2.0 * u)
    };
    let min_radius = (b - a) / (1.5 * theta);
    let w = match width {
        Width::OfLength(f) => f.min(min_radius),
        Width::OfRadius(f) => f * 2.0 * min_radius,
    };
    // Stations: uniform in s, integrated finely by the midpoint rule.
    let sub = 64;
    let mut c = Vec::with_capacity(m);
    let mut nrm = Vec::with_capacity(m);
    let mut pos = Point::ZERO;
    let ds = 1.0 / ((m - 1) * sub) as f64;
    for i in 0..m {
        if i > 0 {
            for k in 0..sub {
                let s = ((i - 1) * sub + k) as f64 * ds + 0.5 * ds;
                let (sn, cs) = phi(s).sin_cos();
                pos += ds * Point::new(cs, sn);
            }
        }
        let (sn, cs) = phi(i as f64 / (m - 1) as f64).sin_cos();
        c.push(pos);
        nrm.push(Point::new(-sn, cs));
    }
    Raw::plain(strip_around(&c, &nrm, w))
}

/// A star-shaped blob: r(φ) = 1 + Σ a_k cos(kφ + p_k) at jittered angles.
pub fn blob(rng: &mut Rng, n: usize) -> Vec<Point> {
    let harmonics: Vec<(f64, f64, f64)> = (2..=6)
        .map(|k| {
            let k = k as f64;
            (k, rng.range(0.0, 0.3 / k), rng.range(0.0, TAU))
        })
        .collect();
    let mut angles: Vec<f64> = (0..n)
        .map(|i| (i as f64 + rng.range(-0.45, 0.45)) * TAU / n as f64)
        .collect();
    angles.sort_by(f64::total_cmp);
    angles
        .into_iter()
        .map(|phi| {
            let r = 1.0
                + harmonics
                    .iter()
                    .map(|&(k, a, p)| a * (k * phi + p).cos())
                    .sum::<f64>();
            Point::new(r * phi.cos(), r * phi.sin())
        })
        .collect()
}

/// Margin below 2π of a glued vertex's fan (measured in floating point,
/// so the exact test cannot disagree).
const FAN_MARGIN: f64 = 1e-6;

/// A random immersed disk: starting from one counter-clockwise triangle,
/// repeatedly glue a triangle (a, c, b) on the outer side of a boundary
/// edge a→b (overlaps allowed), skipping a step that would make a fan wrap.
/// With `thin`, the glued triangles are slivers. `snap` rounds every new
/// vertex to the integer grid (before its exact orientation test).
fn glue(rng: &mut Rng, n: usize, thin: bool, snap: Option<f64>) -> Vec<Point> {
    let h0 = if thin { rng.pow10(-9.0, -2.0) } else { 0.9 };
    let unit = snap.unwrap_or(1.0);
    let mut pos = vec![
        Point::new(0.0, 0.0),
        Point::new(unit, 0.0),
        Point::new((0.3 * unit).round_if(snap), (h0 * unit).round_if(snap)),
    ];
    if orient(pos[0], pos[1], pos[2]) != Orientation::CounterClockwise {
        pos[2] = Point::new(0.0, unit);
    }
    let mut fan: Vec<f64> = triangle_angles(pos[0], pos[1], pos[2]).to_vec();
    let mut boundary: Vec<usize> = vec![0, 1, 2];
    let mut tries = 0;
    while boundary.len() < n && tries < 4 * n + 20 {
        tries += 1;
        let i = rng.int(0, boundary.len() - 1);
        let (a, b) = (boundary[i], boundary[(i + 1) % boundary.len()]);
        let (pa, pb) = (pos[a], pos[b]);
        let d = pb - pa;
        let t = rng.range(0.05, 0.95);
        // Mostly moderate heights: tall ones make every later triangle
        // glued on their sides larger still.
        let h = if thin {
            rng.pow10(-9.0, -2.0)
        } else if rng.chance(0.85) {
            rng.range(0.15, 1.5)
        } else {
            rng.range(1.5, 4.0)
        };
        let mut c = pa + t * d + h * Point::new(d.y, -d.x);
        if snap.is_some() {
            c = c.round();
        }
        // Grid coordinates stay far below 2^53 (exact integers).
        let cap = if snap.is_some() { 2f64.powi(40) } else { 1e12 };
        if !c.is_finite() || c.abs().max_element() > cap {
            continue;
        }
        if orient(pa, c, pb) != Orientation::CounterClockwise {
            continue;
        }
        let [at_a, at_c, at_b] = triangle_angles(pa, c, pb);
        if fan[a] + at_a >= TAU - FAN_MARGIN || fan[b] + at_b >= TAU - FAN_MARGIN {
            continue;
        }
        fan[a] += at_a;
        fan[b] += at_b;
        fan.push(at_c);
        pos.push(c);
        boundary.insert(i + 1, pos.len() - 1);
    }
    boundary.into_iter().map(|v| pos[v]).collect()
}

trait RoundIf {
    fn round_if(self, snap: Option<f64>) -> f64;
}

impl RoundIf for f64 {
    fn round_if(self, snap: Option<f64>) -> f64 {
        if snap.is_some() { self.round() } else { self }
    }
}

fn glued(rng: &mut Rng, n: usize, thin: bool) -> Vec<Point> {
    glue(rng, n, thin, None)
}

/// A glued disk on an integer grid (coordinates up to about 2^20), with
/// runs of lattice points inserted on some edges: exactly collinear.
fn collinear(rng: &mut Rng, n: usize) -> Raw {
    let base_n = rng.int(3, (n / 2).max(3));
    let unit = f64::from(rng.pick(&[12u32, 60, 360]));
    let base = glue(rng, base_n, false, Some(unit));
    let budget = n.saturating_sub(base.len());
    let m = base.len();
    let mut out = Vec::with_capacity(n);
    let mut left = budget;
    for i in 0..m {
        let (a, b) = (base[i], base[(i + 1) % m]);
        out.push(a);
        let d = b - a;
        let g = gcd(d.x.abs() as u64, d.y.abs() as u64);
        if g < 2 || left == 0 || rng.chance(0.3) {
            continue;
        }
        // A run of up to `left` of the g − 1 lattice points inside the edge.
        let k = rng.int(1, ((g - 1) as usize).min(left).min(12));
        let mut picks: Vec<u64> = (0..k).map(|_| 1 + rng.next_u64() % (g - 1)).collect();
        picks.sort_unstable();
        picks.dedup();
        left -= picks.len();
        let step = d / g as f64;
        out.extend(picks.into_iter().map(|j| a + step * j as f64));
    }
    Raw {
        points: out,
        grid: true,
    }
}

fn gcd(mut a: u64, mut b: u64) -> u64 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

/// An ordinary curve with one corner cut by a very short edge (1e-12..1e-6
/// of the perimeter): the new point is the corner moved by ε along a
/// direction between the incoming and outgoing edges (sometimes exactly
/// along the outgoing edge).
fn short_edge(rng: &mut Rng, n: usize) -> Raw {
    let base_n = n.saturating_sub(1).max(3);
    let base = match rng.int(0, 3) {
        0 => blob(rng, base_n),
        1 => glued(rng, base_n, false),
        2 => spiral(rng, base_n, (200.0, 720.0), Width::OfRadius(0.2)).points,
        _ => curl(rng, base_n, (200.0, 720.0), Width::OfRadius(0.5)).points,
    };
    let m = base.len();
    let perimeter: f64 = (0..m).map(|i| (base[(i + 1) % m] - base[i]).length()).sum();
    let eps = rng.pow10(-12.0, -6.0) * perimeter;
    let v = rng.int(0, m - 1);
    let (a, p, b) = (base[(v + m - 1) % m], base[v], base[(v + 1) % m]);
    let d_in = (p - a).normalize_or_zero();
    let d_out = (b - p).normalize_or_zero();
    let u = if rng.chance(0.25) {
        d_out
    } else {
        let turn = d_in.perp_dot(d_out).atan2(d_in.dot(d_out));
        let alpha = rng.range(0.0, 1.0);
        Point::from_angle(alpha * turn).rotate(d_in)
    };
    let mut points = base;
    points.insert(v + 1, p + eps * u);
    Raw::plain(points)
}

// ---------------------------------------------------------------------
// Transform and validation

/// Where the generated curve sits: rotation, mirror, scale, translation.
fn transform(rng: &mut Rng, raw: Raw) -> Vec<Point> {
    let mut p = raw.points;
    // The bounding box, to scale and place the curve by its size.
    let (lo, hi) = bounds(&p);
    let exact = raw.grid || rng.chance(0.2);
    let mirror = rng.chance(0.25);
    if exact {
        // Quarter turns, a power-of-two scale and a translation on the
        // scaled grid: every coordinate stays exact, so collinear runs stay
        // exactly collinear.
        let size = (hi - lo).max_element();
        let e = rng.range(-20.0, 20.0).round() as i32 - size.log2().ceil() as i32;
        let s = 2f64.powi(e);
        let q = rng.int(0, 3);
        let shift = Point::new(
            (rng.range(-16.0, 16.0) * size).round(),
            (rng.range(-16.0, 16.0) * size).round(),
        );
        for v in &mut p {
            let mut w = *v;
            for _ in 0..q {
                w = w.perp();
            }
            if mirror {
                w.x = -w.x;
            }
            *v = (w + shift) * s;
        }
    } else {
        let c = 0.5 * (lo + hi);
        let size = (hi - lo).max_element();
        let s = rng.pow10(-6.0, 6.0) / size;
        let rot = Point::from_angle(rng.range(0.0, TAU));
        let shift = if rng.chance(0.2) {
            Point::ZERO
        } else {
            Point::new(rng.range(-10.0, 10.0), rng.range(-10.0, 10.0))
        };
        for v in &mut p {
            let mut w = rot.rotate(*v - c);
            if mirror {
                w.x = -w.x;
            }
            *v = w * s + shift * (s * size);
        }
    }
    // The reader refuses non-zero magnitudes below 1e-30.
    for v in &mut p {
        for x in [&mut v.x, &mut v.y] {
            if x.abs() < 1e-30 {
                *x = 0.0;
            }
        }
    }
    let k = rng.int(0, p.len() - 1);
    p.rotate_left(k);
    p
}

/// The points as a user's JSON curve file.
pub fn curve_json(name: &str, points: &[Point]) -> String {
    let xy: Vec<[f64; 2]> = points.iter().map(|p| [p.x, p.y]).collect();
    serde_json::json!({ "name": name, "points": xy }).to_string()
}

/// Reads points as a user's file would be read (cleaning, range checks,
/// orientation) and keeps them only when they are self-overlapping.
pub fn read_curve(name: &str, points: &[Point]) -> Result<Vec<Point>, String> {
    let curve = Curve::from_json_str(&curve_json(name, points), "stress.json")
        .map_err(|e| e.to_string())?;
    triangulate(&curve.points).map_err(|e| e.to_string())?;
    Ok(curve.points)
}

/// Why a generator's output was discarded.
#[derive(Clone, Debug)]
pub struct Discard {
    /// The generator.
    pub generator: Generator,
    /// The reader's or the triangulator's message.
    pub reason: String,
}

/// A generated, cleaned, oriented, self-overlapping curve.
#[derive(Clone, Debug)]
pub struct Generated {
    /// Which family.
    pub generator: Generator,
    /// The points, as read back.
    pub points: Vec<Point>,
    /// Outputs thrown away before this one (by any generator).
    pub discards: Vec<Discard>,
}

/// Draws one curve of family `generator`: retries (counting discards)
/// until one is self-overlapping; `None` after 40 failed attempts.
pub fn generate(rng: &mut Rng, generator: Generator) -> (Option<Vec<Point>>, Vec<Discard>) {
    let mut discards = Vec::new();
    for _ in 0..40 {
        let n = size(rng);
        let raw = generator.raw(rng, n);
        let points = transform(rng, raw);
        match read_curve(generator.as_str(), &points) {
            Ok(p) => return (Some(p), discards),
            Err(reason) => discards.push(Discard { generator, reason }),
        }
    }
    (None, discards)
}

/// Draws one curve from a random family.
pub fn draw_curve(rng: &mut Rng) -> Generated {
    let mut all = Vec::new();
    loop {
        let generator = rng.pick(&Generator::ALL);
        let (points, discards) = generate(rng, generator);
        all.extend(discards);
        if let Some(points) = points {
            return Generated {
                generator,
                points,
                discards: all,
            };
        }
    }
}

// ---------------------------------------------------------------------
// Pairs

/// The options of one pair, by their command-line names.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairOptions {
    /// `--quality`.
    pub quality: Quality,
    /// `--counts`.
    pub counts: Counts,
    /// `--intermediate`.
    pub intermediate: Intermediate,
    /// `--correspondence`.
    pub correspondence: Correspondence,
    /// Number of frames, evenly spaced in [0, 1] (at least 2).
    pub frames: usize,
}

/// `--counts` name.
pub fn counts_name(c: Counts) -> &'static str {
    match c {
        Counts::Insert => "insert",
        Counts::Resample => "resample",
    }
}

impl PairOptions {
    /// The library options.
    pub fn curve_options(&self) -> CurveMorphOptions {
        CurveMorphOptions::DEFAULT
            .with_quality(self.quality)
            .with_counts(self.counts)
            .with_intermediate(self.intermediate)
            .with_correspondence(self.correspondence)
    }

    /// The frame parameters.
    pub fn fractions(&self) -> Vec<f64> {
        let k = self.frames.max(2);
        (0..k).map(|i| i as f64 / (k - 1) as f64).collect()
    }

    /// As JSON.
    pub fn to_json(self) -> serde_json::Value {
        serde_json::json!({
            "quality": self.quality.as_str(),
            "counts": counts_name(self.counts),
            "intermediate": self.intermediate.as_str(),
            "correspondence": self.correspondence.as_str(),
            "frames": self.frames,
        })
    }

    /// From JSON (as [`PairOptions::to_json`] writes).
    pub fn from_json(v: &serde_json::Value) -> Result<PairOptions, String> {
        let s = |k: &str| {
            v[k].as_str()
                .ok_or_else(|| format!("options.{k}: expected a string"))
        };
        let quality: Quality = s("quality")?.parse().map_err(|e| format!("{e}"))?;
        let counts = match s("counts")? {
            "insert" => Counts::Insert,
            "resample" => Counts::Resample,
            other => return Err(format!("unknown counts '{other}'")),
        };
        let intermediate = match s("intermediate")? {
            "target" => Intermediate::Target,
            "disk" => Intermediate::Disk,
            other => return Err(format!("unknown intermediate '{other}'")),
        };
        let name = s("correspondence")?;
        let correspondence = Correspondence::ALL
            .into_iter()
            .find(|c| c.as_str() == name)
            .ok_or_else(|| format!("unknown correspondence '{name}'"))?;
        let frames = v["frames"]
            .as_u64()
            .ok_or("options.frames: expected a number")? as usize;
        Ok(PairOptions {
            quality,
            counts,
            intermediate,
            correspondence,
            frames,
        })
    }

    /// One line for humans.
    pub fn label(&self) -> String {
        format!(
            "--quality {} --counts {} --intermediate {} --correspondence {} --frames {}",
            self.quality,
            counts_name(self.counts),
            self.intermediate.as_str(),
            self.correspondence.as_str(),
            self.frames
        )
    }
}

/// One stress pair: two curves and the options to morph them with.
#[derive(Clone, Debug)]
pub struct Pair {
    /// Seed of the run (`None` for a pair read from a file).
    pub seed: Option<u64>,
    /// Index of the pair in its run.
    pub index: u64,
    /// Families of source and target (`None` when unknown).
    pub generators: [Option<Generator>; 2],
    /// The source curve (cleaned, oriented).
    pub source: Vec<Point>,
    /// The target curve (cleaned, oriented).
    pub target: Vec<Point>,
    /// The options.
    pub options: PairOptions,
    /// Generator outputs discarded while drawing this pair.
    pub discards: Vec<Discard>,
}

/// Pair `index` of the run with `seed`.
pub fn pair(seed: u64, index: u64) -> Pair {
    let mut rng = Rng::stream(seed, index);
    let a = draw_curve(&mut rng);
    let b = draw_curve(&mut rng);
    let n = a.points.len().max(b.points.len());
    let quality = if n <= MAX_MAXMIN_SIZE {
        rng.pick(&Quality::ALL)
    } else {
        rng.pick(&[Quality::Any, Quality::Delaunay])
    };
    let options = PairOptions {
        quality,
        counts: rng.pick(&[Counts::Insert, Counts::Resample]),
        intermediate: rng.pick(&[Intermediate::Target, Intermediate::Disk]),
        correspondence: rng.pick(&Correspondence::ALL),
        frames: rng.int(20, 40),
    };
    let mut discards = a.discards;
    discards.extend(b.discards);
    Pair {
        seed: Some(seed),
        index,
        generators: [Some(a.generator), Some(b.generator)],
        source: a.points,
        target: b.points,
        options,
        discards,
    }
}

fn points_json(p: &[Point]) -> serde_json::Value {
    serde_json::Value::from(p.iter().map(|q| vec![q.x, q.y]).collect::<Vec<_>>())
}

fn points_from_json(v: &serde_json::Value, what: &str) -> Result<Vec<Point>, String> {
    let arr = v
        .as_array()
        .ok_or_else(|| format!("{what}: expected an array of [x, y]"))?;
    arr.iter()
        .map(|xy| match (xy[0].as_f64(), xy[1].as_f64()) {
            (Some(x), Some(y)) => Ok(Point::new(x, y)),
            _ => Err(format!("{what}: expected [x, y] pairs")),
        })
        .collect()
}

impl Pair {
    /// Which pair this is, for messages.
    pub fn name(&self) -> String {
        let g = |g: Option<Generator>| g.map_or("?", Generator::as_str);
        match self.seed {
            Some(seed) => format!(
                "pair {} (seed {seed:#x}, {} -> {})",
                self.index,
                g(self.generators[0]),
                g(self.generators[1])
            ),
            None => format!(
                "pair {} ({} -> {})",
                self.index,
                g(self.generators[0]),
                g(self.generators[1])
            ),
        }
    }

    /// The regression-file form: everything needed to replay the pair.
    pub fn to_json(&self, error: Option<&str>) -> serde_json::Value {
        let g = |g: Option<Generator>| g.map(Generator::as_str);
        serde_json::json!({
            "seed": self.seed.map(|s| format!("{s:#x}")),
            "pair": self.index,
            "generators": [g(self.generators[0]), g(self.generators[1])],
            "error": error,
            "options": self.options.to_json(),
            "source": points_json(&self.source),
            "target": points_json(&self.target),
        })
    }

    /// The regression-file text: [`Pair::to_json`] with one point per line.
    pub fn to_file_text(&self, error: Option<&str>) -> String {
        let v = self.to_json(error);
        let mut s = String::from("{\n");
        for key in ["seed", "pair", "generators", "error", "options"] {
            let _ = writeln!(s, "  \"{key}\": {},", v[key]);
        }
        for (key, pts, end) in [("source", &self.source, ","), ("target", &self.target, "")] {
            let _ = writeln!(s, "  \"{key}\": [");
            for (i, p) in pts.iter().enumerate() {
                let comma = if i + 1 < pts.len() { "," } else { "" };
                let _ = writeln!(s, "    {}{comma}", serde_json::json!([p.x, p.y]));
            }
            let _ = writeln!(s, "  ]{end}");
        }
        s.push_str("}\n");
        s
    }

    /// Reads the form [`Pair::to_json`] writes. The curves are read again
    /// as user files are (cleaning, orientation).
    pub fn from_json(text: &str) -> Result<Pair, String> {
        let v: serde_json::Value = serde_json::from_str(text).map_err(|e| e.to_string())?;
        let seed = match v["seed"].as_str() {
            Some(s) => Some(
                u64::from_str_radix(s.trim_start_matches("0x"), 16)
                    .map_err(|e| format!("seed: {e}"))?,
            ),
            None => None,
        };
        let gen_at = |i: usize| v["generators"][i].as_str().and_then(Generator::from_name);
        let read = |key: &str| -> Result<Vec<Point>, String> {
            let p = points_from_json(&v[key], key)?;
            let c = Curve::from_json_str(&curve_json(key, &p), key).map_err(|e| e.to_string())?;
            Ok(c.points)
        };
        Ok(Pair {
            seed,
            index: v["pair"].as_u64().unwrap_or(0),
            generators: [gen_at(0), gen_at(1)],
            source: read("source")?,
            target: read("target")?,
            options: PairOptions::from_json(&v["options"])?,
            discards: Vec::new(),
        })
    }
}

// ---------------------------------------------------------------------
// Running a pair

/// What went wrong with a pair.
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    /// A short class of the failure: the message with its numbers replaced
    /// by `#`, so that failures of one kind group together.
    pub category: String,
    /// The full message.
    pub message: String,
}

impl Failure {
    fn new(kind: &str, message: String) -> Failure {
        Failure {
            category: format!("{kind}: {}", normalise(&message)),
            message: format!("{kind}: {message}"),
        }
    }
}

/// The message with every number (and every run of digits inside a word)
/// replaced by `#` and long lists cut, for grouping.
pub fn normalise(message: &str) -> String {
    let mut out = String::new();
    let mut chars = message.chars().peekable();
    while let Some(c) = chars.next() {
        let minus = c == '-'
            && chars.peek().is_some_and(char::is_ascii_digit)
            && !out.ends_with(char::is_alphanumeric);
        if c.is_ascii_digit() || minus {
            // The rest of the number: digits, a point, an exponent.
            while let Some(&d) = chars.peek() {
                if d.is_ascii_alphanumeric() || matches!(d, '.' | '-' | '+') {
                    chars.next();
                } else {
                    break;
                }
            }
            out.push('#');
        } else {
            out.push(c);
        }
    }
    if out.chars().count() > 160 {
        out = out.chars().take(160).collect::<String>() + "…";
    }
    out
}

/// What a passing pair reports.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// Vertices after equalising counts.
    pub n: usize,
    /// The library's report.
    pub report: MorphReport,
}

/// Why `frame` does not run along the closed polyline `outline` in order
/// from its vertex 0 (every point within 1e-9 of the outline's size of it,
/// at non-decreasing arc length), or `None`.
fn off_outline(frame: &[Point], outline: &[Point]) -> Option<String> {
    let m = outline.len();
    let size = outline
        .iter()
        .map(|p| (*p - outline[0]).length())
        .fold(0.0, f64::max);
    let tol = 1e-9 * size.max(f64::MIN_POSITIVE);
    if frame[0] != outline[0] {
        return Some(format!("vertex 0 is {:?}, not {:?}", frame[0], outline[0]));
    }
    // Walk the outline's edges forward as the frame's points go along.
    let mut edge = 0usize;
    for (i, &p) in frame.iter().enumerate().skip(1) {
        let mut found = false;
        for _ in 0..=m {
            let (u, v) = (outline[edge], outline[(edge + 1) % m]);
            let e = v - u;
            let t = if e.length_squared() > 0.0 {
                ((p - u).dot(e) / e.length_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            if (u + e * t - p).length() <= tol {
                found = true;
                break;
            }
            edge += 1;
            if edge >= m {
                break;
            }
        }
        if !found {
            return Some(format!("vertex {i} {p:?} is not on the outline in order"));
        }
    }
    None
}

/// `frame` holds `original`'s vertices, exactly, in cyclic order starting
/// at `start` (other vertices may sit between them).
fn holds_in_order(frame: &[Point], original: &[Point], start: usize) -> bool {
    let n = frame.len();
    let mut j = 0;
    for i in 0..n {
        if j < original.len() && frame[(start + i) % n] == original[j] {
            j += 1;
        }
    }
    j == original.len()
}

/// The text of a panic payload.
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "(non-string panic payload)".to_string()
    }
}

/// Morphs the pair and checks it: `morph_pair` returns Ok, there is one
/// frame per fraction, every frame passes the exact immersion check, the
/// first frame is the source after count equalisation (with insertion, the
/// source's own vertices appear exactly, in cyclic order, from vertex 0)
/// and the last is the target after count equalisation, shifted by the
/// reported correspondence. A panic is caught and reported as a failure.
pub fn run_pair(pair: &Pair) -> Result<Outcome, Failure> {
    let options = pair.options.curve_options();
    let fractions = pair.options.fractions();
    let (a, b) = (&pair.source, &pair.target);
    let result = std::panic::catch_unwind(|| crate::morph_pair(a, b, &fractions, &options));
    let (report, morph) = match result {
        Err(payload) => return Err(Failure::new("panic", panic_message(payload.as_ref()))),
        Ok(Err(e)) => return Err(Failure::new("error", e.to_string())),
        Ok(Ok(x)) => x,
    };
    let n = a.len().max(b.len());
    if morph.frames.len() != fractions.len() {
        return Err(Failure::new(
            "frame count",
            format!(
                "{} frames for {} fractions",
                morph.frames.len(),
                fractions.len()
            ),
        ));
    }
    if report.n != n || report.shift >= n {
        return Err(Failure::new(
            "report",
            format!("n = {} shift = {} for {n} vertices", report.n, report.shift),
        ));
    }
    for (j, f) in morph.frames.iter().enumerate() {
        if f.points.len() != n {
            return Err(Failure::new(
                "frame size",
                format!("frame {j} has {} points, not {n}", f.points.len()),
            ));
        }
        if let Err(defect) = f.check() {
            return Err(Failure::new(
                "invalid frame returned",
                format!("frame {j} (t = {}): {defect}", f.t),
            ));
        }
    }
    // The ends are the inputs after count equalisation, whatever way the
    // vertices were added: with insertion (asked for, or the fallback of
    // resampling) every original vertex is there exactly and in order; in
    // every case every vertex lies on the input's outline, in order along
    // it.
    let inserted = pair.options.counts == Counts::Insert
        || report
            .fallbacks
            .iter()
            .any(|f| f.what.contains("inserted vertices instead of resampling"));
    let k = report.shift;
    let first = &morph.frames[0].points;
    let last = &morph.frames[morph.frames.len() - 1].points;
    let last_from_b: Vec<Point> = (0..n).map(|i| last[(i + n - k) % n]).collect();
    for (frame, input, which) in [
        (&first[..], &a[..], "first frame is not the source"),
        (&last_from_b[..], &b[..], "last frame is not the target"),
    ] {
        if inserted && !holds_in_order(frame, input, 0) {
            return Err(Failure::new(
                which,
                "the input's vertices are not all there in order".to_string(),
            ));
        }
        if let Some(why) = off_outline(frame, input) {
            return Err(Failure::new(which, why));
        }
    }
    Ok(Outcome { n, report })
}

// ---------------------------------------------------------------------
// Running many pairs

/// One pair's result, without its curves.
#[derive(Clone, Debug)]
pub struct Row {
    /// The pair's index.
    pub index: u64,
    /// Families of source and target.
    pub generators: [Option<Generator>; 2],
    /// Its options.
    pub options: PairOptions,
    /// Vertices of the larger curve.
    pub n: usize,
    /// Wall time of the morph and its checks, in seconds.
    pub seconds: f64,
    /// The failure's category, if it failed.
    pub failed: Option<String>,
}

/// The result of a run.
#[derive(Debug, Default)]
pub struct Summary {
    /// Every pair, in index order.
    pub rows: Vec<Row>,
    /// The failing pairs and why, in index order.
    pub failures: Vec<(Pair, Failure)>,
    /// Generator outputs kept and discarded, by generator.
    pub generated: std::collections::BTreeMap<Generator, (usize, usize)>,
    /// Discard reasons (normalised) and how often.
    pub discard_reasons: std::collections::BTreeMap<String, usize>,
}

/// A table of failures over totals, grouped by `key`.
fn tally(rows: &[Row], title: &str, key: impl Fn(&Row) -> Vec<String>) -> String {
    let mut all: std::collections::BTreeMap<String, (usize, usize)> = Default::default();
    for r in rows {
        for k in key(r) {
            let e = all.entry(k).or_default();
            e.1 += 1;
            e.0 += usize::from(r.failed.is_some());
        }
    }
    let mut s = format!("failures by {title}:\n");
    for (k, (f, t)) in all {
        let _ = writeln!(
            s,
            "  {k:<22} {f:6} / {t:<6} ({:.1}%)",
            100.0 * f as f64 / t.max(1) as f64
        );
    }
    s
}

impl Summary {
    /// One line: failures, pairs, discards.
    pub fn headline(&self) -> String {
        format!(
            "{} of {} pairs failed; {:.2}% of generated curves discarded",
            self.failures.len(),
            self.total(),
            100.0 * self.discard_rate()
        )
    }

    /// Pairs run.
    pub fn total(&self) -> usize {
        self.rows.len()
    }

    /// Discarded outputs over all outputs.
    pub fn discard_rate(&self) -> f64 {
        let (kept, dropped) = self
            .generated
            .values()
            .fold((0, 0), |(k, d), &(a, b)| (k + a, d + b));
        dropped as f64 / (kept + dropped).max(1) as f64
    }

    /// Per-pair wall times, sorted.
    pub fn sorted_seconds(&self) -> Vec<f64> {
        let mut t: Vec<f64> = self.rows.iter().map(|r| r.seconds).collect();
        t.sort_by(f64::total_cmp);
        t
    }

    /// A report: counts, discards, failures by category, generator and
    /// option, and (up to `show`) failing pairs as JSON.
    pub fn report(&self, show: usize) -> String {
        use std::collections::BTreeMap;
        let mut s = String::new();
        // Every failure on one line (the index reproduces it), the first
        // `show` also as JSON.
        for (k, (p, f)) in self.failures.iter().enumerate() {
            let _ = writeln!(
                s,
                "FAIL {}: {} [{}]",
                p.name(),
                f.message,
                p.options.label()
            );
            if k < show {
                let _ = writeln!(s, "  {}", p.to_json(Some(&f.message)));
            }
        }
        if self.failures.len() > show {
            let _ = writeln!(
                s,
                "({} failing pairs not shown as JSON; `cargo run --release --example stress -- --pair I [--shrink]` prints one)",
                self.failures.len() - show
            );
        }
        let _ = writeln!(s, "{}", self.headline());
        let _ = writeln!(s, "generated curves by generator (kept / discarded):");
        for (g, (k, d)) in &self.generated {
            let _ = writeln!(s, "  {:<22} {k:6} / {d}", g.as_str());
        }
        if !self.discard_reasons.is_empty() {
            let _ = writeln!(s, "discard reasons:");
            for (r, k) in &self.discard_reasons {
                let _ = writeln!(s, "  {k:6}  {r}");
            }
        }
        let mut by_cat: BTreeMap<&str, usize> = BTreeMap::new();
        for (_, f) in &self.failures {
            *by_cat.entry(&f.category).or_default() += 1;
        }
        let mut cats: Vec<_> = by_cat.into_iter().collect();
        cats.sort_by(|x, y| y.1.cmp(&x.1).then(x.0.cmp(y.0)));
        let _ = writeln!(s, "failures by category:");
        for (c, k) in &cats {
            let _ = writeln!(s, "  {k:6}  {c}");
        }
        let g = |g: Option<Generator>| g.map_or("?", Generator::as_str).to_string();
        s += &tally(
            &self.rows,
            "generator (a pair counts once for each of its two curves' families)",
            |r| {
                let mut v = vec![g(r.generators[0]), g(r.generators[1])];
                v.dedup();
                v
            },
        );
        s += &tally(&self.rows, "quality", |r| {
            vec![r.options.quality.to_string()]
        });
        s += &tally(&self.rows, "counts", |r| {
            vec![counts_name(r.options.counts).to_string()]
        });
        s += &tally(&self.rows, "intermediate", |r| {
            vec![r.options.intermediate.as_str().to_string()]
        });
        s += &tally(&self.rows, "correspondence", |r| {
            vec![r.options.correspondence.as_str().to_string()]
        });
        s += &tally(&self.rows, "size (larger curve)", |r| {
            let b = match r.n {
                0..=9 => "n < 10",
                10..=49 => "10 <= n < 50",
                50..=99 => "50 <= n < 100",
                _ => "n >= 100",
            };
            vec![b.to_string()]
        });
        s += &self.matrix();
        s += &self.categories_by_generator();
        s
    }
}

impl Summary {
    /// Failures over totals for every generator (either curve of the pair)
    /// against every combination of `--counts` and `--intermediate`.
    pub fn matrix(&self) -> String {
        let combos = [
            (Counts::Insert, Intermediate::Target),
            (Counts::Insert, Intermediate::Disk),
            (Counts::Resample, Intermediate::Target),
            (Counts::Resample, Intermediate::Disk),
        ];
        let mut s =
            String::from("failures by generator and --counts/--intermediate (failed/total):\n");
        let _ = write!(s, "  {:<14}", "");
        for (c, i) in combos {
            let _ = write!(s, " {:>17}", format!("{}/{}", counts_name(c), i.as_str()));
        }
        s.push('\n');
        for g in Generator::ALL {
            let _ = write!(s, "  {:<14}", g.as_str());
            for (c, i) in combos {
                let (mut f, mut t) = (0, 0);
                for r in &self.rows {
                    if r.generators.contains(&Some(g))
                        && r.options.counts == c
                        && r.options.intermediate == i
                    {
                        t += 1;
                        f += usize::from(r.failed.is_some());
                    }
                }
                let _ = write!(s, " {:>17}", format!("{f}/{t}"));
            }
            s.push('\n');
        }
        s
    }

    /// For each failure category, how many failing pairs involve each
    /// generator.
    pub fn categories_by_generator(&self) -> String {
        use std::collections::BTreeMap;
        let mut m: BTreeMap<&str, BTreeMap<&str, usize>> = BTreeMap::new();
        for r in &self.rows {
            if let Some(c) = &r.failed {
                let mut gens: Vec<&str> = r
                    .generators
                    .iter()
                    .map(|g| g.map_or("?", Generator::as_str))
                    .collect();
                gens.dedup();
                for g in gens {
                    *m.entry(c.as_str()).or_default().entry(g).or_default() += 1;
                }
            }
        }
        let mut s = String::from("generators involved, by failure category:\n");
        for (c, gens) in m {
            let mut gens: Vec<_> = gens.into_iter().collect();
            gens.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(b.0)));
            let list: Vec<String> = gens.iter().map(|(g, k)| format!("{g} {k}")).collect();
            let _ = writeln!(s, "  {c}\n      {}", list.join(", "));
        }
        s
    }
}

/// Called with a pair's index when it starts (`None`) and ends (its
/// result).
pub type Progress<'a> = dyn Fn(u64, Option<&Result<Outcome, Failure>>) + Sync + 'a;

/// Runs pairs `start..start + count` of the run with `seed`, in parallel
/// (rayon), and collects every failure. `each` is called when a pair
/// starts (with `None`) and when it ends (for progress and watchdogs).
pub fn run_pairs(seed: u64, start: u64, count: u64, each: &Progress<'_>) -> Summary {
    use rayon::prelude::*;
    let results: Vec<(Pair, Result<Outcome, Failure>, f64)> = (start..start + count)
        .into_par_iter()
        .map(|i| {
            each(i, None);
            let p = pair(seed, i);
            let t = std::time::Instant::now();
            let r = run_pair(&p);
            each(i, Some(&r));
            (p, r, t.elapsed().as_secs_f64())
        })
        .collect();
    let mut summary = Summary::default();
    for (p, r, seconds) in results {
        for g in p.generators.iter().flatten() {
            summary.generated.entry(*g).or_default().0 += 1;
        }
        for d in &p.discards {
            summary.generated.entry(d.generator).or_default().1 += 1;
            *summary
                .discard_reasons
                .entry(format!(
                    "{}: {}",
                    d.generator.as_str(),
                    normalise(&d.reason)
                ))
                .or_default() += 1;
        }
        summary.rows.push(Row {
            index: p.index,
            generators: p.generators,
            options: p.options,
            n: p.source.len().max(p.target.len()),
            seconds,
            failed: r.as_ref().err().map(|f| f.category.clone()),
        });
        if let Err(f) = r {
            summary.failures.push((p, f));
        }
    }
    summary
}

// ---------------------------------------------------------------------
// Shrinking

/// Shrinks a failing pair while it keeps failing with the same category:
/// fewer frames first, then fewer points on either curve (dropping runs of
/// points, halving the run length down to single points), keeping only
/// candidates that are still self-overlapping curves as read from a file.
/// `budget` bounds the number of trial morphs.
pub fn shrink(pair: &Pair, failure: &Failure, budget: usize) -> (Pair, Failure) {
    let mut best = pair.clone();
    let mut best_failure = failure.clone();
    let trials = std::cell::Cell::new(0usize);
    let attempt = |cand: &Pair| -> Option<Failure> {
        trials.set(trials.get() + 1);
        match run_pair(cand) {
            Err(f) if f.category == failure.category => Some(f),
            _ => None,
        }
    };
    for frames in [2, 3, 5, 9] {
        if frames >= best.options.frames {
            break;
        }
        let mut cand = best.clone();
        cand.options.frames = frames;
        if let Some(f) = attempt(&cand) {
            best = cand;
            best_failure = f;
            break;
        }
    }
    // Simpler options, when the failure stays: the cheapest quality and a
    // single-morph correspondence.
    for quality in [Quality::Any, Quality::Delaunay] {
        if best.options.quality == quality {
            break;
        }
        let mut cand = best.clone();
        cand.options.quality = quality;
        if let Some(f) = attempt(&cand) {
            best = cand;
            best_failure = f;
            break;
        }
    }
    if best.options.correspondence == Correspondence::Best {
        for rule in [
            Correspondence::Identity,
            Correspondence::MinFlips,
            Correspondence::Pivot,
            Correspondence::Shape,
        ] {
            let mut cand = best.clone();
            cand.options.correspondence = rule;
            if let Some(f) = attempt(&cand) {
                best = cand;
                best_failure = f;
                break;
            }
        }
    }
    let side_len = |p: &Pair, side: usize| {
        if side == 0 {
            p.source.len()
        } else {
            p.target.len()
        }
    };
    loop {
        let before = (best.source.len(), best.target.len());
        for side in 0..2 {
            let mut chunk = (side_len(&best, side) / 2).max(1);
            loop {
                let mut start = 0;
                while start < side_len(&best, side) && trials.get() < budget {
                    let cur = if side == 0 {
                        &best.source
                    } else {
                        &best.target
                    };
                    let end = (start + chunk).min(cur.len());
                    if cur.len() - (end - start) < 3 {
                        start += chunk;
                        continue;
                    }
                    let mut p = cur[..start].to_vec();
                    p.extend_from_slice(&cur[end..]);
                    let Ok(p) = read_curve("shrink", &p) else {
                        start += chunk;
                        continue;
                    };
                    let mut cand = best.clone();
                    if side == 0 {
                        cand.source = p;
                    } else {
                        cand.target = p;
                    }
                    match attempt(&cand) {
                        Some(f) => {
                            best = cand;
                            best_failure = f;
                        }
                        None => start += chunk,
                    }
                }
                if chunk == 1 || trials.get() >= budget {
                    break;
                }
                chunk /= 2;
            }
            // Strips lose validity when one side loses a point alone:
            // drop a point together with its nearest non-neighbour (across
            // the strip).
            let mut i = 0;
            while i < side_len(&best, side) && trials.get() < budget {
                let cur = if side == 0 {
                    &best.source
                } else {
                    &best.target
                };
                let n = cur.len();
                if n <= 4 {
                    break;
                }
                let j = (0..n)
                    .filter(|&j| j != i && j != (i + 1) % n && j != (i + n - 1) % n)
                    .min_by(|&a, &b| {
                        (cur[a] - cur[i])
                            .length_squared()
                            .total_cmp(&(cur[b] - cur[i]).length_squared())
                    });
                let Some(j) = j else { break };
                let p: Vec<Point> = (0..n)
                    .filter(|&k| k != i && k != j)
                    .map(|k| cur[k])
                    .collect();
                let mut accepted = false;
                if let Ok(p) = read_curve("shrink", &p) {
                    let mut cand = best.clone();
                    if side == 0 {
                        cand.source = p;
                    } else {
                        cand.target = p;
                    }
                    if let Some(f) = attempt(&cand) {
                        best = cand;
                        best_failure = f;
                        accepted = true;
                    }
                }
                if !accepted {
                    i += 1;
                }
            }
        }
        if (best.source.len(), best.target.len()) == before || trials.get() >= budget {
            break;
        }
    }
    // Shorter coordinates: round each curve to a grid of 10^-k of its size
    // for the smallest k that keeps it self-overlapping and failing.
    for side in 0..2 {
        for k in [2, 3, 4, 6, 8, 10, 12] {
            if trials.get() >= budget {
                break;
            }
            let cur = if side == 0 {
                &best.source
            } else {
                &best.target
            };
            let (lo, hi) = bounds(cur);
            // To a power of ten, through decimal text, so that the rounded
            // coordinates print short.
            let e = ((hi - lo).max_element().log10().floor() as i32) - k;
            let round = |x: f64| -> f64 {
                format!("{}e{e}", (x / 10f64.powi(e)).round() as i64)
                    .parse()
                    .unwrap_or(x)
            };
            let rounded: Vec<Point> = cur
                .iter()
                .map(|p| Point::new(round(p.x), round(p.y)))
                .collect();
            let Ok(rounded) = read_curve("shrink", &rounded) else {
                continue;
            };
            let mut cand = best.clone();
            if side == 0 {
                cand.source = rounded;
            } else {
                cand.target = rounded;
            }
            if let Some(f) = attempt(&cand) {
                best = cand;
                best_failure = f;
                break;
            }
        }
    }
    (best, best_failure)
}

/// The regression files (path, pair) in [`REGRESSION_DIR`], sorted by name.
pub fn regression_files() -> Vec<(std::path::PathBuf, Result<Pair, String>)> {
    let dir = crate::workspace_root().join(REGRESSION_DIR);
    let mut files: Vec<std::path::PathBuf> = std::fs::read_dir(&dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "json"))
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).map_err(|e| e.to_string());
            let pair = text.and_then(|t| Pair::from_json(&t));
            (path, pair)
        })
        .collect()
}

/// The angle, in degrees, of the thinnest triangle corner a curve's
/// triangulation has (a measure of how thin a generated curve is).
pub fn thinnest_degrees(points: &[Point]) -> f64 {
    triangulate(points)
        .map(|t| t.min_angle() * 180.0 / PI)
        .unwrap_or(f64::NAN)
}
