//! Correspondence by what the user sees: the two outlines matched by arc
//! length, up to a similarity (docs/design.md §7b).
//!
//! Each curve's vertices get their position along the outline as a
//! fraction of its perimeter. For every candidate vertex `k` of the curve
//! with more vertices that could match the other's vertex 0, the other
//! curve's vertices are assigned, in order, to the nearest positions of the
//! first (an increasing assignment), the missing vertices are inserted on
//! its edges at the first curve's relative positions (its own vertices
//! stay exactly where they are), and the pair is scored by how far matched vertices are once both
//! outlines are centred and scaled to unit size (a turn is not forgiven:
//! the user sees it). The best candidate wins.

use crate::geom::Point;
use rayon::prelude::*;

/// Most candidate shifts scored in full; more vertices are first scored on
/// every `stride`-th shift and refined around the best.
const COARSE_SHIFTS: usize = 256;

/// Most vertices used to score one candidate.
const SCORE_SAMPLES: usize = 512;

/// The two curves brought to the same vertex count with their vertices
/// matched by arc length: `(a', b', shift)` where vertex `i` of `a'`
/// matches vertex `(i + shift) % n` of `b'`. The curve with fewer vertices
/// gets vertices inserted on its edges; original vertices stay exact and in
/// order. Symmetric: `align(b, a)` pairs the same vertices.
pub(crate) fn align(a: &[Point], b: &[Point]) -> (Vec<Point>, Vec<Point>, usize) {
    if small_second(a, b) {
        back(align_small_to_large(b, a))
    } else {
        align_small_to_large(a, b)
    }
}

/// Two curves with equal counts and the shift that pairs them.
type Pairing = (Vec<Point>, Vec<Point>, usize);

/// Whether `b` is the curve that gets insertions: the one with fewer
/// vertices, ties going by coordinates so that both argument orders agree.
fn small_second(a: &[Point], b: &[Point]) -> bool {
    let lex = crate::geom::polygon::lex_key;
    match a.len().cmp(&b.len()) {
        std::cmp::Ordering::Less => false,
        std::cmp::Ordering::Greater => true,
        std::cmp::Ordering::Equal => lex(a) > lex(b),
    }
}

/// The pairing `(b2, a2, k)` of `(b, a)` as one of `(a, b)`: `b2[i]`
/// matches `a2[(i + k) % n]`, so `a2[j]` matches `b2[(j + n − k) % n]`.
fn back((b2, a2, k): Pairing) -> Pairing {
    let n = a2.len();
    (a2, b2, (n - k) % n)
}

/// A vertex where the outline turns by at least this much (either way) is
/// a corner: 60°.
const CORNER_TURN: f64 = std::f64::consts::FRAC_PI_3;

/// A stretch of outline this short (as a share of the perimeter) that
/// turns by at least [`ROUNDED_TURN`] is a rounded corner, such as a
/// ribbon's rounded cap: 3%.
const ROUNDED_SPAN: f64 = 0.03;

/// The span tried when no rounded corners within [`ROUNDED_SPAN`] match
/// up: 10%, so that a window centred on one corner of a square cap reaches
/// the other where the cap is up to 5% of the perimeter (a strip about ten
/// times as long as it is wide). Tried second, so that a thin ribbon's
/// folds (a half turn over a few percent) do not join its caps.
const WIDE_ROUNDED_SPAN: f64 = 0.10;

/// Least turning of a rounded corner within [`ROUNDED_SPAN`]: 160°, so
/// that a wide loop of the outline (a ribbon's fold) is not one.
const ROUNDED_TURN: f64 = 8.0 * std::f64::consts::PI / 9.0;

/// Most corners matched: past this an outline has no few features that
/// stand out.
const MOST_CORNERS: usize = 16;

/// [`align`] with the corners matched: when both curves have the same
/// number of corners (between 2 and 16; a corner turns by 60° or more),
/// each corner of one is matched to a corner of the other turning the same
/// way, in order, and the arc length between consecutive corners is
/// matched piece by piece (so a strip's long and short edges, or a
/// letter's strokes, correspond whatever their share of the perimeter).
/// Where the sharp corners do not match up, rounded corners are tried the
/// same way: stretches of at most 3% of the perimeter turning by 160° or
/// more, such as the rounded caps of a drawn ribbon, each placed at the
/// middle of its turning; where those do not match up either, stretches of
/// at most 10% (the square caps of a strip as wide as a twentieth of its
/// perimeter).
/// Of the cyclic matchings of the corners the one that stretches the
/// pieces between corners least wins (the sum of |ln| of the ratios of
/// their shares of the perimeter, to a tenth), then the best score as in
/// [`align`]. `None` when neither kind of corner matches up.
/// Symmetric, as [`align`].
pub(crate) fn align_corners(a: &[Point], b: &[Point]) -> Option<Pairing> {
    let (a, b, swap) = if small_second(a, b) {
        (b, a, true)
    } else {
        (a, b, false)
    };
    let (alpha, beta) = (positions(a), positions(b));
    let match_up =
        |ca: &[(f64, f64)], cb: &[(f64, f64)]| corners_small_to_large(a, b, &alpha, &beta, ca, cb);
    let sharp = match_up(&corners(a, &alpha), &corners(b, &beta));
    let rounded = |span: f64| {
        match_up(
            &rounded_corners(a, &alpha, span),
            &rounded_corners(b, &beta, span),
        )
    };
    let found = sharp
        .or_else(|| rounded(ROUNDED_SPAN))
        .or_else(|| rounded(WIDE_ROUNDED_SPAN));
    if swap { found.map(back) } else { found }
}

/// The exterior angle of `p` at each vertex, signed (left turns positive).
fn turns(p: &[Point]) -> Vec<f64> {
    let n = p.len();
    (0..n)
        .map(|i| {
            let (u, v) = (p[i] - p[(i + n - 1) % n], p[(i + 1) % n] - p[i]);
            u.perp_dot(v).atan2(u.dot(v))
        })
        .collect()
}

/// The corners of `p` (module docs) as (fraction of the perimeter, signed
/// turning); `at` holds each vertex's fraction ([`positions`]).
fn corners(p: &[Point], at: &[f64]) -> Vec<(f64, f64)> {
    turns(p)
        .into_iter()
        .enumerate()
        .filter(|&(_, turn)| turn.abs() >= CORNER_TURN)
        .map(|(i, turn)| (at[i], turn))
        .collect()
}

/// The rounded corners of `p` as (fraction of the perimeter, signed
/// turning): each maximal run of vertices around which the outline turns
/// by at least [`ROUNDED_TURN`] one way within `span` of the perimeter,
/// centred on the vertex (half the span either side), is one
/// corner, placed where half of the run's vertices' own turning is done. A
/// curve whose turning is that strong everywhere has none.
fn rounded_corners(p: &[Point], at: &[f64], span: f64) -> Vec<(f64, f64)> {
    let n = p.len();
    if n < 3 {
        return Vec::new();
    }
    let turn = turns(p);
    // Window sums around each vertex by two pointers over the outline
    // unwrapped three times: index j is vertex j − n (mod n), at position
    // at[j % n] + j / n − 1, so the window [lo, hi) stays in range.
    let half = span / 2.0;
    let mut window = vec![0.0; n];
    let (mut lo, mut hi, mut sum) = (0usize, 0usize, 0.0);
    let upos = |j: usize| at[j % n] + (j / n) as f64 - 1.0;
    let uturn = |j: usize| turn[j % n];
    for (i, w) in window.iter_mut().enumerate() {
        let centre = at[i];
        while hi < 3 * n && upos(hi) <= centre + half {
            sum += uturn(hi);
            hi += 1;
        }
        while upos(lo) < centre - half {
            sum -= uturn(lo);
            lo += 1;
        }
        *w = sum;
    }
    let strong = |i: usize| window[i].abs() >= ROUNDED_TURN;
    if (0..n).all(strong) {
        return Vec::new();
    }
    // Runs of strong vertices turning the same way, read from a vertex
    // that ends a run.
    let start = (0..n).find(|&i| !strong(i)).unwrap_or(0);
    let mut out = Vec::new();
    let mut i = 0;
    while i < n {
        let v = (start + i) % n;
        if !strong(v) {
            i += 1;
            continue;
        }
        let sign = window[v] > 0.0;
        let mut run = vec![v];
        i += 1;
        while i < n {
            let u = (start + i) % n;
            if !strong(u) || (window[u] > 0.0) != sign {
                break;
            }
            run.push(u);
            i += 1;
        }
        // Where half of the run's turning (the vertices' own) is done.
        let total: f64 = run.iter().map(|&u| turn[u]).sum();
        let mut done = 0.0;
        let mut place = at[run[0]];
        for &u in &run {
            done += turn[u];
            if done.abs() >= total.abs() / 2.0 {
                place = at[u];
                break;
            }
        }
        let most = run.iter().map(|&u| window[u].abs()).fold(0.0, f64::max);
        out.push((place, if sign { most } else { -most }));
    }
    out.sort_by(|x, y| x.0.total_cmp(&y.0));
    out
}

/// [`align_corners`] with `small` (m vertices) against `large` (n ≥ m),
/// given their vertices' fractions of the perimeter ([`positions`]) and
/// the corners of each as (fraction of the perimeter, signed turn).
fn corners_small_to_large(
    small: &[Point],
    large: &[Point],
    alpha: &[f64],
    beta: &[f64],
    ca: &[(f64, f64)],
    cb: &[(f64, f64)],
) -> Option<(Vec<Point>, Vec<Point>, usize)> {
    let f = ca.len();
    if f < 2 || f != cb.len() || f > MOST_CORNERS {
        return None;
    }
    let n = large.len();
    let xs: Vec<f64> = ca.iter().map(|&(x, _)| x).collect();
    let mut best: Option<(f64, f64, Vec<Point>, usize)> = None;
    for r in 0..f {
        let matched = |i: usize| cb[(i + r) % f];
        if (0..f).any(|i| (ca[i].1 > 0.0) != (matched(i).1 > 0.0)) {
            continue;
        }
        // The corners' places on the large curve, unwrapped to increase.
        let mut ys: Vec<f64> = (0..f).map(|i| matched(i).0).collect();
        for i in 1..f {
            while ys[i] <= ys[i - 1] {
                ys[i] += 1.0;
            }
        }
        // The piecewise-linear map of small's fractions onto large's,
        // through the matched corners (period 1 on both sides), unwrapped
        // so that it increases from small's vertex 0 on.
        let warp = |x: f64| -> f64 {
            let (x, lift) = if x < xs[0] { (x + 1.0, 1.0) } else { (x, 0.0) };
            let i = xs.partition_point(|&v| v <= x).max(1) - 1;
            let (x0, y0) = (xs[i], ys[i]);
            let (x1, y1) = if i + 1 < f {
                (xs[i + 1], ys[i + 1])
            } else {
                (xs[0] + 1.0, ys[0] + 1.0)
            };
            y0 + (x - x0) / (x1 - x0) * (y1 - y0) - lift
        };
        let w: Vec<f64> = alpha.iter().map(|&x| warp(x)).collect();
        // Large's vertex nearest to where small's vertex 0 lands.
        let w0 = w[0].rem_euclid(1.0);
        let cyclic = |d: f64| (d + 0.5).rem_euclid(1.0) - 0.5;
        let k = (0..n)
            .min_by(|&i, &j| {
                cyclic(beta[i] - w0)
                    .abs()
                    .total_cmp(&cyclic(beta[j] - w0).abs())
            })
            .unwrap_or(0);
        let d0 = cyclic(w0 - beta[k]);
        let rel: Vec<f64> = w
            .iter()
            .map(|&x| (x - w[0] + d0).clamp(0.0, 1.0 - f64::EPSILON))
            .collect();
        // How much the matching stretches the pieces between corners: the
        // sum of |ln| of each piece's share of the perimeter on one curve
        // over its share on the other. A strip's long edge matched to a cap
        // stretches a lot; the score only breaks near-ties.
        let stretch: f64 = (0..f)
            .map(|i| {
                let next = (i + 1) % f;
                let on_small = (xs[next] - xs[i]).rem_euclid(1.0);
                let on_large = if next == 0 {
                    ys[0] + 1.0 - ys[i]
                } else {
                    ys[next] - ys[i]
                };
                (on_small.max(f64::MIN_POSITIVE) / on_large.max(f64::MIN_POSITIVE))
                    .ln()
                    .abs()
            })
            .sum();
        let padded = pad(small, &rel, beta, k);
        if !(0..n).all(|i| padded[i] != padded[(i + 1) % n]) {
            continue;
        }
        let score = residual(&padded, large, k);
        let better = best.as_ref().is_none_or(|b| {
            // Stretch first (to a tenth), then the outline score.
            let (s0, s1) = ((stretch * 10.0).round(), (b.0 * 10.0).round());
            s0 < s1 || (s0 == s1 && score < b.1)
        });
        if better {
            best = Some((stretch, score, padded, k));
        }
    }
    let (_, _, padded, k) = best?;
    Some((padded, large.to_vec(), k))
}

/// Fractions of the perimeter at each vertex, from vertex 0.
fn positions(p: &[Point]) -> Vec<f64> {
    let n = p.len();
    let mut acc = 0.0;
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        out.push(acc);
        acc += (p[(i + 1) % n] - p[i]).length();
    }
    if acc > 0.0 {
        for x in &mut out {
            *x /= acc;
        }
    }
    out
}

/// `small` (m vertices) against `large` (n ≥ m): returns the padded
/// `small`, `large` unchanged, and the shift.
fn align_small_to_large(small: &[Point], large: &[Point]) -> (Vec<Point>, Vec<Point>, usize) {
    let (m, n) = (small.len(), large.len());
    let alpha = positions(small);
    let beta = positions(large);
    let score = |k: usize| -> f64 {
        let padded = pad(small, &alpha, &beta, k);
        residual(&padded, large, k)
    };
    let stride = n.div_ceil(COARSE_SHIFTS).max(1);
    // Scored side by side, then the first least score in order.
    let coarse: Vec<(usize, f64)> = (0..n)
        .step_by(stride)
        .collect::<Vec<_>>()
        .par_iter()
        .map(|&k| (k, score(k)))
        .collect();
    let mut best = (f64::INFINITY, 0usize);
    for (k, s) in coarse {
        if s < best.0 {
            best = (s, k);
        }
    }
    if stride > 1 {
        let centre = best.1;
        for d in 1..stride {
            for k in [(centre + d) % n, (centre + n - d) % n] {
                let s = score(k);
                if s < best.0 || (s == best.0 && k < best.1) {
                    best = (s, k);
                }
            }
        }
    }
    let k = best.1;
    debug_assert!(m <= n);
    let padded = pad(small, &alpha, &beta, k);
    let distinct = (0..n).all(|i| padded[i] != padded[(i + 1) % n]);
    if distinct {
        return (padded, large.to_vec(), k);
    }
    // Edges too short to hold the aligned points: split the longest edges
    // instead, and match by the same score.
    let padded = super::insert_vertices(small, n - m).0;
    let k = (0..n)
        .min_by(|&i, &j| residual(&padded, large, i).total_cmp(&residual(&padded, large, j)))
        .unwrap_or(0);
    (padded, large.to_vec(), k)
}

/// `small` with vertices inserted so that, with `large` read from vertex
/// `k`, vertex `i` of each sits at about the same fraction of its
/// perimeter.
fn pad(small: &[Point], alpha: &[f64], beta: &[f64], k: usize) -> Vec<Point> {
    let (m, n) = (small.len(), beta.len());
    // Positions of large's vertices read from k, relative to vertex k.
    let rel = |j: usize| (beta[(j + k) % n] - beta[k]).rem_euclid(1.0);
    // Increasing assignment of small's vertices to large's indices.
    let mut slot = Vec::with_capacity(m);
    let mut prev: Option<usize> = None;
    for (i, &a) in alpha.iter().enumerate() {
        let lo = prev.map_or(0, |p| p + 1);
        let hi = n - (m - i);
        // Nearest index by binary search on the increasing rel(j).
        let (mut l, mut h) = (lo, hi);
        while l < h {
            let mid = (l + h) / 2;
            if rel(mid) < a { l = mid + 1 } else { h = mid }
        }
        let mut j = l.min(hi);
        if j > lo && (a - rel(j - 1)).abs() <= (rel(j) - a).abs() {
            j -= 1;
        }
        let j = if i == 0 { 0 } else { j.clamp(lo, hi) };
        slot.push(j);
        prev = Some(j);
    }
    let mut out = Vec::with_capacity(n);
    for i in 0..m {
        let (p, q) = (small[i], small[(i + 1) % m]);
        let j0 = slot[i];
        let j1 = if i + 1 < m { slot[i + 1] } else { n };
        let (r0, r1) = (rel(j0), if i + 1 < m { rel(j1) } else { 1.0 });
        out.push(p);
        let start = out.len();
        for j in j0 + 1..j1 {
            let f = if r1 > r0 {
                (rel(j) - r0) / (r1 - r0)
            } else {
                0.0
            };
            // Keep clear of the edge's ends, where the sides of a thin
            // wedge are within rounding of each other: at least 1% of the
            // even spacing from either end (the bounds grow with j, so the
            // order is kept).
            let even = (j - j0) as f64 / (j1 - j0) as f64;
            let f = f.clamp(0.01 * even, 1.0 - 0.01 * (1.0 - even));
            out.push(p.lerp(q, f));
        }
        // Inserted points must be distinct from each other and from the
        // edge's ends; where rounding merges them, space them evenly.
        let distinct = |pts: &[Point]| {
            std::iter::once(p)
                .chain(pts.iter().copied())
                .chain(std::iter::once(q))
                .collect::<Vec<_>>()
                .windows(2)
                .all(|w| w[0] != w[1])
        };
        if !distinct(&out[start..]) {
            let count = j1 - j0;
            for (idx, j) in (j0 + 1..j1).enumerate() {
                out[start + idx] = p.lerp(q, (j - j0) as f64 / count as f64);
            }
        }
    }
    out
}

/// How far `a` (vertex `i`) is from `b` (vertex `(i + k) % n`) once both
/// are centred and scaled to unit size, without turning either: the mean
/// squared distance between matched vertices (0 for the same shape in the
/// same pose). A turn is not forgiven because the user sees it: a vertex
/// matched across the shape must travel across it.
fn residual(a: &[Point], b: &[Point], k: usize) -> f64 {
    let n = a.len();
    let step = n.div_ceil(SCORE_SAMPLES).max(1);
    let idx = (0..n).step_by(step);
    let count = idx.clone().count() as f64;
    let (mut ca, mut cb) = (Point::ZERO, Point::ZERO);
    for i in idx.clone() {
        ca += a[i];
        cb += b[(i + k) % n];
    }
    ca /= count;
    cb /= count;
    let (mut na, mut nb) = (0.0, 0.0);
    for i in idx.clone() {
        na += (a[i] - ca).length_squared();
        nb += (b[(i + k) % n] - cb).length_squared();
    }
    if na <= 0.0 || nb <= 0.0 {
        return f64::INFINITY;
    }
    let (sa, sb) = ((count / na).sqrt(), (count / nb).sqrt());
    idx.map(|i| ((a[i] - ca) * sa - (b[(i + k) % n] - cb) * sb).length_squared())
        .sum::<f64>()
        / count
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{points, unit_square};

    /// The vertices of `p` that are sharp corners.
    fn corner_vertices(p: &[Point]) -> Vec<usize> {
        let turn = turns(p);
        (0..p.len())
            .filter(|&i| turn[i].abs() >= CORNER_TURN)
            .collect()
    }

    fn circle(n: usize, phase: f64, r: f64) -> Vec<Point> {
        (0..n)
            .map(|i| Point::from_angle(phase + std::f64::consts::TAU * i as f64 / n as f64) * r)
            .collect()
    }

    /// A strip along an arc of `turn` radians (its centre line from angle
    /// 0), `m` stations per long edge: outer edge out, inner edge back, so
    /// it has four corners (two at each cap).
    fn arc_strip(m: usize, turn: f64, width: f64) -> Vec<Point> {
        let at = |i: usize, r: f64| Point::from_angle(turn * i as f64 / (m - 1) as f64) * r;
        let outer = (0..m).map(|i| at(i, 1.0 + width / 2.0));
        let inner = (0..m).rev().map(|i| at(i, 1.0 - width / 2.0));
        outer.chain(inner).collect()
    }

    #[test]
    fn corners_match_corners_and_the_pieces_between_them() {
        // Long edges of 20 and 60 stations: the caps are at different
        // shares of the perimeter on the two strips.
        let a = arc_strip(20, 4.0, 0.3);
        let b = arc_strip(60, 6.0, 0.5);
        assert_eq!(corner_vertices(&a).len(), 4);
        assert_eq!(corner_vertices(&b).len(), 4);
        let (a2, b2, k) = align_corners(&a, &b).expect("the corners match up");
        let n = b.len();
        assert_eq!((a2.len(), b2.len()), (n, n));
        assert_eq!(b2, b);
        // The originals stay, in order.
        let originals: Vec<Point> = a2.iter().copied().filter(|p| a.contains(p)).collect();
        assert_eq!(originals, a);
        // Every corner of a lands on a corner of b, outer edge on outer
        // edge: vertex 0 (the outer edge's start) on b's vertex 0.
        for i in corner_vertices(&a) {
            let at = a2.iter().position(|p| *p == a[i]).unwrap();
            let j = (at + k) % n;
            assert!(
                corner_vertices(&b).contains(&j),
                "corner {i} of a on {j} of b"
            );
        }
        assert_eq!(k, 0);
        // Symmetric: the other order pairs the same vertices.
        let (b3, a3, k3) = align_corners(&b, &a).unwrap();
        assert_eq!((b3, a3), (b2, a2));
        assert_eq!((k + k3) % n, 0);
        // The outline rule, by perimeter share alone, puts a's caps
        // elsewhere on b.
        let (o2, _, ko) = align(&a, &b);
        let cap = o2.iter().position(|p| *p == a[20]).unwrap();
        assert!(!corner_vertices(&b).contains(&((cap + ko) % n)));
    }

    #[test]
    fn curves_whose_corners_differ_have_no_corner_match() {
        let triangle = points([(0.0, 0.0), (4.0, 0.0), (1.0, 3.0)]);
        let square = unit_square();
        assert!(align_corners(&triangle, &square).is_none());
        // A circle has no corner at all.
        assert!(align_corners(&circle(40, 0.0, 1.0), &circle(50, 0.0, 1.0)).is_none());
    }

    /// [`arc_strip`] with each cap rounded: a half circle of `cap`
    /// stations across the ends instead of two sharp corners.
    fn rounded_arc_strip(m: usize, turn: f64, width: f64, cap: usize) -> Vec<Point> {
        let at = |i: usize, r: f64| Point::from_angle(turn * i as f64 / (m - 1) as f64) * r;
        // Around the centre line's end at `angle`: from `from` (a unit
        // vector across the strip) through `bulge` (along it) to −`from`.
        let half = |angle: f64, start: bool| {
            let centre = Point::from_angle(angle);
            let tangent = Point::new(-centre.y, centre.x);
            let (from, bulge) = if start {
                (-centre, -tangent)
            } else {
                (centre, tangent)
            };
            (1..cap).map(move |j| {
                let s = std::f64::consts::PI * j as f64 / cap as f64;
                centre + (from * s.cos() + bulge * s.sin()) * (width / 2.0)
            })
        };
        let outer = (0..m).map(|i| at(i, 1.0 + width / 2.0));
        let end_cap = half(turn, false);
        let inner = (0..m).rev().map(|i| at(i, 1.0 - width / 2.0));
        let start_cap = half(0.0, true);
        outer.chain(end_cap).chain(inner).chain(start_cap).collect()
    }

    #[test]
    fn rounded_caps_are_corners_where_sharp_corners_are_missing() {
        // Two rounded strips wound 400° and 700°: no sharp corner, one
        // rounded cap at each end, turning left by about a half turn.
        let a = rounded_arc_strip(40, 7.0, 0.25, 8);
        let b = rounded_arc_strip(90, 12.2, 0.3, 10);
        for p in [&a, &b] {
            assert!(corner_vertices(p).is_empty());
            let caps = rounded_corners(p, &positions(p), ROUNDED_SPAN);
            assert_eq!(caps.len(), 2, "{caps:?}");
            assert!(
                caps.iter()
                    .all(|c| c.1 > 0.0 && c.1 < 1.5 * std::f64::consts::PI)
            );
        }
        let (a2, b2, k) = align_corners(&a, &b).expect("the caps match up");
        let n = b.len();
        assert_eq!(b2, b);
        // Each end of a's outer edge lands on the same end of b's.
        let start = a2.iter().position(|p| *p == a[0]).unwrap();
        let end = a2.iter().position(|p| *p == a[39]).unwrap();
        assert!(
            (start + k) % n <= 1 || (start + k) % n >= n - 1,
            "start on {}",
            (start + k) % n
        );
        assert!(
            ((end + k) % n).abs_diff(89) <= 3,
            "end on {}",
            (end + k) % n
        );
        // A sharp-cornered strip keeps matching by its sharp corners, and
        // a circle (turning evenly) has no rounded corner.
        assert!(
            rounded_corners(
                &circle(30, 0.0, 1.0),
                &positions(&circle(30, 0.0, 1.0)),
                ROUNDED_SPAN
            )
            .is_empty()
        );
        let sharp = arc_strip(20, 4.0, 0.3);
        assert!(align_corners(&sharp, &arc_strip(60, 6.0, 0.5)).is_some());
        // One rounded cap against two: no match.
        let loop_ = circle(64, 0.0, 1.0);
        assert!(align_corners(&loop_, &b).is_none());
    }

    #[test]
    fn the_drawn_ribbons_have_two_rounded_caps() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("curves");
        for name in ["ribbon-curl.svg", "folded-ribbon.svg"] {
            let c = crate::curve::Curve::from_path(dir.join(name)).unwrap();
            let at = positions(&c.points);
            assert!(corners(&c.points, &at).is_empty(), "{name}");
            let caps = rounded_corners(&c.points, &at, ROUNDED_SPAN);
            assert_eq!(caps.len(), 2, "{name}: {caps:?}");
        }
    }

    #[test]
    fn strips_with_wide_square_caps_match_end_to_end() {
        // A 300° annulus sector (caps 4% of its perimeter) and a coarse
        // 470° curl (caps 4.4%), both wound counter-clockwise: no sharp
        // corners match (4 against 9), no cap is within 3% of either
        // perimeter, and within 10% each has its two caps.
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("curves");
        let load = |name: &str| {
            crate::curve::Curve::from_path(dir.join(name))
                .unwrap()
                .points
        };
        let (a, b) = (
            load("annulus-sector-300deg-n40.json"),
            load("curl-strip-n10.json"),
        );
        for p in [&a, &b] {
            let at = positions(p);
            assert!(rounded_corners(p, &at, ROUNDED_SPAN).is_empty());
            let caps = rounded_corners(p, &at, WIDE_ROUNDED_SPAN);
            assert_eq!(caps.len(), 2, "{caps:?}");
        }
        let (a2, b2, k) = align_corners(&a, &b).expect("the wide caps match up");
        let n = a2.len();
        // Each corner of the sector's caps (its outer arc's ends at
        // vertices 0 and 19, its inner arc's at 20 and 39) lands on the
        // same corner of the curl's (outer ends 0 and 4, inner 5 and 9).
        for (i, j) in [(0, 0), (19, 4), (20, 5), (39, 9)] {
            let on = (a2.iter().position(|p| *p == a[i]).unwrap() + k) % n;
            let want = b2.iter().position(|p| *p == b[j]).unwrap();
            assert!(
                on.abs_diff(want).min(n - on.abs_diff(want)) <= 1,
                "sector vertex {i} on {on}, curl vertex {j} at {want}"
            );
        }
    }

    #[test]
    fn originals_stay_and_similar_outlines_match_where_they_should() {
        // A 12-gon and a turned, scaled 36-gon: every 12-gon vertex should
        // land on the 36-gon vertex at the same angle (up to the turn).
        let a = circle(12, 0.0, 1.0);
        let b = circle(36, 0.3, 2.0);
        let (a2, b2, k) = align(&a, &b);
        assert_eq!((a2.len(), b2.len()), (36, 36));
        assert_eq!(b2, b);
        let originals: Vec<Point> = a2.iter().copied().filter(|p| a.contains(p)).collect();
        assert_eq!(originals, a);
        // Vertex 0 of a sits at index 0 and matches a vertex of b.
        assert_eq!(a2[0], a[0]);
        assert!(k < 36);
        // Symmetric: the other order pairs the same vertices.
        let (b3, a3, k3) = align(&b, &a);
        assert_eq!((b3, a3), (b2, a2.clone()));
        assert_eq!((k + k3) % 36, 0);
    }
}
