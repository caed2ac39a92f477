//! Equal vertex counts across all keys, with hinted points at the same
//! vertex number in consecutive keys.
//!
//! Each key first gets its hinted points as vertices (its *mandatory*
//! vertices: the originals and the hint points). Consecutive keys joined
//! by hints form a *group*; within a group, key `s + 1` is laid out from
//! key `s`: the hints of segment `s` cut both curves into arcs, the arc of
//! key `s` between two hints holds some number of vertices, and key
//! `s + 1` must hold exactly as many in its matching arc — its mandatory
//! ones plus vertices inserted on the arc's longest edges. When an arc of
//! key `s + 1` has more mandatory vertices than key `s`'s arc holds, the
//! missing vertices are inserted into key `s`'s arc for good (a *forced*
//! insertion, which the next pass carries back toward the group's first
//! key) and the pass starts again. Forced insertions only grow and are
//! bounded by the mandatory counts, so this ends. Keys outside groups get
//! vertices on their longest edges, as a two-curve morph does. Every key
//! ends with the same count n, the largest any group needs.

use super::{HintAt, HintVertex, Key, SequenceError};
use crate::geom::Point;

/// The keys with equal counts. Within a group of hinted segments the
/// vertex numbers already agree at the hints; between groups, the
/// segments' tweens choose the shift.
pub(super) struct Aligned {
    pub(super) n: usize,
    pub(super) keys: Vec<Vec<Point>>,
    pub(super) originals: Vec<Vec<Option<usize>>>,
    pub(super) hints: Vec<HintVertex>,
}

/// Where a hint sits, once found on its key.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Place {
    Vertex(usize),
    /// On edge `e` (from vertex e to e + 1) at parameter `u` ∈ (0, 1).
    Edge(usize, f64, Point),
}

/// A key with its hint points inserted.
struct Pinned {
    points: Vec<Point>,
    original: Vec<Option<usize>>,
}

/// Per-key state of the layout.
struct Work {
    m: usize,
    len: Vec<f64>,
    forced: Vec<usize>,
    counts: Vec<usize>,
    rot: usize,
}

fn diagonal(points: &[Point]) -> f64 {
    let (mut lo, mut hi) = (points[0], points[0]);
    for &p in points {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    (hi - lo).length()
}

/// A hinted point this close to a vertex (as a fraction of the key's
/// bounding-box diagonal) is that vertex: a vertex inserted closer would
/// only make a sliver.
pub(crate) const HINT_SNAP: f64 = 1e-3;

/// The place at parameter `u` of edge `e`, snapped to a vertex when it
/// lies within `snap` of one.
fn on_edge(points: &[Point], e: usize, u: f64, snap: f64) -> Place {
    let n = points.len();
    let (a, b) = (points[e], points[(e + 1) % n]);
    if u <= 0.0 {
        return Place::Vertex(e);
    }
    if u >= 1.0 {
        return Place::Vertex((e + 1) % n);
    }
    let q = a.lerp(b, u);
    if (q - a).length() <= snap {
        Place::Vertex(e)
    } else if (q - b).length() <= snap {
        Place::Vertex((e + 1) % n)
    } else {
        Place::Edge(e, u, q)
    }
}

fn resolve(points: &[Point], at: HintAt, tolerance: f64) -> Result<Place, String> {
    let n = points.len();
    let diag = diagonal(points);
    let snap = HINT_SNAP * diag;
    match at {
        HintAt::Vertex(i) => {
            if i < n {
                Ok(Place::Vertex(i))
            } else {
                Err(format!(
                    "vertex {i} does not exist; the key has {n} vertices (0 to {})",
                    n - 1
                ))
            }
        }
        HintAt::Fraction(f) => {
            if !(0.0..=1.0).contains(&f) {
                return Err(format!(
                    "fraction {f} is not in [0, 1]; give the fraction of the curve's length from its first point"
                ));
            }
            let lengths: Vec<f64> = (0..n)
                .map(|i| (points[(i + 1) % n] - points[i]).length())
                .collect();
            let total: f64 = lengths.iter().sum();
            let s = f * total;
            if f >= 1.0 {
                return Ok(Place::Vertex(0));
            }
            let mut start = 0.0;
            for (e, &l) in lengths.iter().enumerate() {
                if s < start + l {
                    return Ok(on_edge(points, e, (s - start) / l, snap));
                }
                start += l;
            }
            Ok(Place::Vertex(0))
        }
        HintAt::Point(p) => {
            if !p.is_finite() {
                return Err(format!("[{}, {}] is not a finite point", p.x, p.y));
            }
            if let Some(i) = points.iter().position(|&q| q == p) {
                return Ok(Place::Vertex(i));
            }
            let mut best = (f64::INFINITY, 0usize, 0.0f64);
            for e in 0..n {
                let (a, b) = (points[e], points[(e + 1) % n]);
                let ab = b - a;
                let l2 = ab.length_squared();
                let u = if l2 > 0.0 {
                    ((p - a).dot(ab) / l2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let d = (p - a.lerp(b, u)).length();
                if d < best.0 {
                    best = (d, e, u);
                }
            }
            let (d, e, u) = best;
            let limit = tolerance * diag;
            if d > limit {
                return Err(format!(
                    "the point [{}, {}] is {d:.4} from the curve, more than {}% of its size; give a point on the curve, a vertex index or a fraction",
                    p.x,
                    p.y,
                    tolerance * 100.0
                ));
            }
            Ok(on_edge(points, e, u, snap))
        }
    }
}

/// Inserts `places` into the key; returns the pinned key and, for each
/// place, its vertex in it.
fn pin(points: &[Point], places: &[Place]) -> (Pinned, Vec<usize>) {
    let n = points.len();
    let mut on: Vec<Vec<(f64, Point)>> = vec![Vec::new(); n];
    for p in places {
        if let Place::Edge(e, u, q) = *p {
            on[e].push((u, q));
        }
    }
    for list in &mut on {
        list.sort_by(|a, b| a.0.total_cmp(&b.0));
        list.dedup_by(|a, b| a.1 == b.1);
    }
    let mut out = Pinned {
        points: Vec::with_capacity(n + places.len()),
        original: Vec::with_capacity(n + places.len()),
    };
    let mut index_of_vertex = vec![0usize; n];
    for e in 0..n {
        index_of_vertex[e] = out.points.len();
        out.points.push(points[e]);
        out.original.push(Some(e));
        for &(_, q) in &on[e] {
            out.points.push(q);
            out.original.push(None);
        }
    }
    let vertex = places
        .iter()
        .map(|p| match *p {
            Place::Vertex(i) => index_of_vertex[i],
            Place::Edge(e, _, q) => {
                let k = on[e].iter().position(|x| x.1 == q).unwrap_or(0);
                index_of_vertex[e] + 1 + k
            }
        })
        .collect();
    (out, vertex)
}

/// Inserts `k` vertices on `edges`, each time splitting the edge whose
/// pieces are currently longest (as `correspond::insert_vertices` does:
/// the same apportionment, [`crate::correspond::apportion_among`], of
/// pieces, one more than the vertices inserted).
fn distribute(len: &[f64], counts: &mut [usize], edges: &[usize], k: usize) {
    if k == 0 {
        return;
    }
    let mut pieces: Vec<usize> = counts.iter().map(|c| c + 1).collect();
    crate::correspond::apportion_among(len, &mut pieces, edges, k);
    for &e in edges {
        counts[e] = pieces[e] - 1;
    }
}

/// Position of each mandatory vertex among all vertices.
fn prefix(counts: &[usize]) -> Vec<usize> {
    let mut out = Vec::with_capacity(counts.len());
    let mut acc = 0;
    for (v, c) in counts.iter().enumerate() {
        out.push(v + acc);
        acc += c;
    }
    out
}

/// The edges of the arc from mandatory vertex `from` up to (not
/// including) `to`, or the whole curve from `from` when `whole`.
fn arc(m: usize, from: usize, to: usize, whole: bool) -> Vec<usize> {
    let count = if whole { m } else { (to + m - from) % m };
    (0..count).map(|k| (from + k) % m).collect()
}

/// One layout pass over a group (keys `w[0..]`, segment hints `hints[s]`
/// joining `w[s]` and `w[s + 1]` as (vertex on s, vertex on s + 1)).
/// `Err` after adding a forced insertion: run again.
fn pass(w: &mut [Work], hints: &[Vec<(usize, usize)>], n: &mut usize) -> Result<(), ()> {
    let first = &mut w[0];
    let forced: usize = first.forced.iter().sum();
    *n = (*n).max(first.m + forced);
    first.counts.clone_from(&first.forced);
    let all: Vec<usize> = (0..first.m).collect();
    distribute(&first.len, &mut first.counts, &all, *n - first.m - forced);
    first.rot = 0;
    let n = *n;
    for (s, hs) in hints.iter().enumerate() {
        let pre = prefix(&w[s].counts);
        let rot = w[s].rot;
        let label = |v: usize| (pre[v] + n - rot) % n;
        let mut order: Vec<(usize, usize, usize)> =
            hs.iter().map(|&(a, b)| (label(a), a, b)).collect();
        order.sort_unstable();
        let h_count = order.len();
        let whole = h_count == 1;
        let (m0, m1) = (w[s].m, w[s + 1].m);
        let mut counts1 = w[s + 1].forced.clone();
        for h in 0..h_count {
            let (la, a, b) = order[h];
            let (la2, a2, b2) = order[(h + 1) % h_count];
            let avail = if whole { n } else { (la2 + n - la) % n };
            let edges1 = arc(m1, b, b2, whole);
            let need = edges1.len() + edges1.iter().map(|&e| w[s + 1].forced[e]).sum::<usize>();
            if avail < need {
                let edges0 = arc(m0, a, a2, whole);
                let k = &w[s];
                let e = edges0
                    .iter()
                    .copied()
                    .max_by(|&x, &y| {
                        let (px, py) = (
                            k.len[x] / (k.counts[x] + 1) as f64,
                            k.len[y] / (k.counts[y] + 1) as f64,
                        );
                        px.total_cmp(&py).then(y.cmp(&x))
                    })
                    .unwrap_or(a);
                w[s].forced[e] += need - avail;
                return Err(());
            }
            distribute(&w[s + 1].len, &mut counts1, &edges1, avail - need);
        }
        let pre1 = prefix(&counts1);
        w[s + 1].rot = (pre1[order[0].2] + n - order[0].0) % n;
        w[s + 1].counts = counts1;
    }
    Ok(())
}

fn hint_error(keys: &[Key], k: usize, hint: &str, reason: String) -> SequenceError {
    SequenceError::Hint {
        key: k + 1,
        name: keys[k].name.clone(),
        hint: hint.to_string(),
        reason,
    }
}

pub(super) fn align(
    keys: &[Key],
    hints: &[super::Hint],
    tolerance: f64,
) -> Result<Aligned, SequenceError> {
    let m = keys.len();
    let segments = m - 1;
    // Find every hint on its keys.
    let mut places: Vec<Vec<Place>> = vec![Vec::new(); m];
    let mut found: Vec<(usize, usize)> = Vec::with_capacity(hints.len());
    for h in hints {
        if h.segment >= segments {
            let k = h.segment.min(m - 1);
            return Err(hint_error(
                keys,
                k,
                &h.name,
                format!(
                    "it joins key {} and key {}, but the sequence has {m} keys",
                    h.segment + 1,
                    h.segment + 2
                ),
            ));
        }
        for (k, at) in [(h.segment, h.from), (h.segment + 1, h.to)] {
            let p = resolve(&keys[k].points, at, tolerance)
                .map_err(|reason| hint_error(keys, k, &h.name, reason))?;
            places[k].push(p);
        }
        found.push((places[h.segment].len() - 1, places[h.segment + 1].len() - 1));
    }
    let mut pinned = Vec::with_capacity(m);
    let mut vertex_of: Vec<Vec<usize>> = Vec::with_capacity(m);
    for (k, key) in keys.iter().enumerate() {
        let (p, v) = pin(&key.points, &places[k]);
        pinned.push(p);
        vertex_of.push(v);
    }
    // Each segment's hints as (vertex on key s, vertex on key s + 1).
    let mut seg: Vec<Vec<(usize, usize)>> = vec![Vec::new(); segments];
    let mut seg_names: Vec<Vec<&str>> = vec![Vec::new(); segments];
    for (h, &(pa, pb)) in hints.iter().zip(&found) {
        let s = h.segment;
        let (a, b) = (vertex_of[s][pa], vertex_of[s + 1][pb]);
        for (k, v, other) in [(s, a, 0), (s + 1, b, 1)] {
            if let Some(i) = seg[s]
                .iter()
                .position(|p| if other == 0 { p.0 == v } else { p.1 == v })
            {
                return Err(hint_error(
                    keys,
                    k,
                    &h.name,
                    format!(
                        "it is the same point of this key as hint '{}'; give each hint its own point",
                        seg_names[s][i]
                    ),
                ));
            }
        }
        seg[s].push((a, b));
        seg_names[s].push(&h.name);
    }
    // Cyclic order: along key s + 1 the hints must come in the order they
    // come along key s.
    for s in 0..segments {
        let hs = &seg[s];
        if hs.len() < 3 {
            continue;
        }
        let mut by_a: Vec<usize> = (0..hs.len()).collect();
        by_a.sort_by_key(|&i| hs[i].0);
        let m1 = pinned[s + 1].points.len();
        let b0 = hs[by_a[0]].1;
        let rel = |i: usize| (hs[i].1 + m1 - b0) % m1;
        for w in 1..by_a.len() {
            if rel(by_a[w]) < rel(by_a[w - 1]) {
                let mut by_b: Vec<usize> = (0..hs.len()).collect();
                by_b.sort_by_key(|&i| rel(i));
                let names = |ord: &[usize]| {
                    ord.iter()
                        .map(|&i| seg_names[s][i])
                        .collect::<Vec<_>>()
                        .join(", ")
                };
                return Err(hint_error(
                    keys,
                    s + 1,
                    seg_names[s][by_a[w]],
                    format!(
                        "out of cyclic order: along key {} ({}) the hints run {}, along this key {}; give the hints in the same order along both curves",
                        s + 1,
                        keys[s].name,
                        names(&by_a),
                        names(&by_b)
                    ),
                ));
            }
        }
    }
    // Lay out.
    let mut work: Vec<Work> = pinned
        .iter()
        .map(|p| {
            let mm = p.points.len();
            Work {
                m: mm,
                len: (0..mm)
                    .map(|i| (p.points[(i + 1) % mm] - p.points[i]).length())
                    .collect(),
                forced: vec![0; mm],
                counts: vec![0; mm],
                rot: 0,
            }
        })
        .collect();
    // Groups: maximal runs of hinted segments, as (first key, last key);
    // a key in no group is a run of one key.
    let mut groups: Vec<(usize, usize)> = Vec::new();
    let mut k = 0;
    while k < m {
        let mut end = k;
        while end < segments && !seg[end].is_empty() {
            end += 1;
        }
        groups.push((k, end));
        k = end + 1;
    }
    let mut n = work.iter().map(|w| w.m).max().unwrap_or(3);
    loop {
        let mut grew = false;
        for &(lo, hi) in &groups {
            let mut size = n;
            let mut guard = 0usize;
            while pass(&mut work[lo..=hi], &seg[lo..hi], &mut size).is_err() {
                guard += 1;
                if guard > 10_000_000 {
                    return Err(SequenceError::Timing(
                        "the hinted vertex counts could not be equalised (a bug in immerse)"
                            .to_string(),
                    ));
                }
            }
            if size > n {
                n = size;
                grew = true;
            }
        }
        if !grew {
            break;
        }
    }
    // Build the keys.
    let mut out_keys = Vec::with_capacity(m);
    let mut originals = Vec::with_capacity(m);
    for (p, w) in pinned.iter().zip(&work) {
        let mut pts = Vec::with_capacity(n);
        let mut orig = Vec::with_capacity(n);
        for e in 0..w.m {
            let (a, b) = (p.points[e], p.points[(e + 1) % w.m]);
            pts.push(a);
            orig.push(p.original[e]);
            let pieces = w.counts[e] + 1;
            for i in 1..pieces {
                pts.push(a.lerp(b, i as f64 / pieces as f64));
                orig.push(None);
            }
        }
        debug_assert_eq!(pts.len(), n);
        out_keys.push((0..n).map(|i| pts[(i + w.rot) % n]).collect::<Vec<_>>());
        originals.push((0..n).map(|i| orig[(i + w.rot) % n]).collect::<Vec<_>>());
    }
    let mut vertices = Vec::with_capacity(hints.len());
    for (h, &(pa, pb)) in hints.iter().zip(&found) {
        let s = h.segment;
        let (a, b) = (vertex_of[s][pa], vertex_of[s + 1][pb]);
        let label = |k: usize, v: usize| (prefix(&work[k].counts)[v] + n - work[k].rot) % n;
        let vertex = label(s, a);
        debug_assert_eq!(vertex, label(s + 1, b), "hint {}", h.name);
        vertices.push(HintVertex {
            name: h.name.clone(),
            segment: s,
            vertex,
            from: pinned[s].points[a],
            to: pinned[s + 1].points[b],
        });
    }
    Ok(Aligned {
        n,
        keys: out_keys,
        originals,
        hints: vertices,
    })
}

#[cfg(test)]
mod tests {
    use super::super::Hint;
    use super::*;

    fn square(size: f64, n_side: usize) -> Vec<Point> {
        let mut out = Vec::new();
        let c = [
            Point::new(0.0, 0.0),
            Point::new(size, 0.0),
            Point::new(size, size),
            Point::new(0.0, size),
        ];
        for i in 0..4 {
            for k in 0..n_side {
                out.push(c[i].lerp(c[(i + 1) % 4], k as f64 / n_side as f64));
            }
        }
        out
    }

    #[test]
    fn hinted_points_share_vertex_numbers_and_originals_stay() {
        // Three keys of different counts with hints that force arcs of
        // very different sizes.
        let keys = vec![
            Key::new("a", square(1.0, 1)),
            Key::new("b", square(2.0, 5)),
            Key::new("c", square(3.0, 2)),
        ];
        let hints = vec![
            Hint {
                name: "p".into(),
                segment: 0,
                from: HintAt::Vertex(0),
                to: HintAt::Vertex(1),
            },
            Hint {
                name: "q".into(),
                segment: 0,
                from: HintAt::Point(Point::new(0.5, 0.0)),
                to: HintAt::Vertex(19),
            },
            Hint {
                name: "r".into(),
                segment: 1,
                from: HintAt::Fraction(0.5),
                to: HintAt::Vertex(3),
            },
        ];
        let al = align(&keys, &hints, 0.02).unwrap();
        assert!(al.keys.iter().all(|k| k.len() == al.n));
        for h in &al.hints {
            assert_eq!(al.keys[h.segment][h.vertex], h.from, "{}", h.name);
            assert_eq!(al.keys[h.segment + 1][h.vertex], h.to, "{}", h.name);
        }
        for (k, key) in keys.iter().enumerate() {
            for (v, o) in al.originals[k].iter().enumerate() {
                if let Some(i) = o {
                    assert_eq!(al.keys[k][v], key.points[*i]);
                }
            }
            let kept = al.originals[k].iter().flatten().count();
            assert_eq!(kept, key.points.len());
        }
    }

    #[test]
    fn out_of_order_and_shared_hints_are_refused() {
        let keys = vec![Key::new("a", square(1.0, 2)), Key::new("b", square(1.0, 2))];
        let h = |name: &str, a: usize, b: usize| Hint {
            name: name.into(),
            segment: 0,
            from: HintAt::Vertex(a),
            to: HintAt::Vertex(b),
        };
        let e = align(&keys, &[h("a", 0, 0), h("b", 2, 4), h("c", 4, 2)], 0.02)
            .err()
            .unwrap();
        assert!(
            e.to_string()
                .starts_with("key 2 (b): hint 'c': out of cyclic order"),
            "{e}"
        );
        let e = align(&keys, &[h("a", 0, 0), h("b", 0, 3)], 0.02)
            .err()
            .unwrap();
        assert_eq!(
            e.to_string(),
            "key 1 (a): hint 'b': it is the same point of this key as hint 'a'; give each hint its own point"
        );
        let far = Hint {
            name: "z".into(),
            segment: 0,
            from: HintAt::Point(Point::new(0.5, 0.5)),
            to: HintAt::Vertex(0),
        };
        let e = align(&keys, &[far], 0.02).err().unwrap();
        assert!(e.to_string().contains("from the curve"), "{e}");
    }
}
