//! A target-shaped intermediate instead of the disk (DESIGN.md §7a): the
//! overlaps of a curve extend toward the other curve instead of unwinding
//! into a disk and winding up again.
//!
//! For a fixed triangulation T the valid angle vectors (angles > 0,
//! triangle sums π, fan sums < 2π) form a convex set, and every point of it
//! lays out to an immersion. The disk is one such point; the one used here
//! looks like the other curve:
//! 1. measure the other curve with T (corner angles, absolute where a
//!    triangle is inverted there);
//! 2. clamp each angle to [δ, π − δ] and rescale each triangle to sum π;
//! 3. blend toward the disk's angles just enough that every fan sum is at
//!    most 2π − ε (a closed-form λ);
//! 4. lay it out from the tree centre and fit it to the other curve by a
//!    similarity: the target D*.
//!
//! The current shape morphs toward D* (`hybrid`, valid for every t). At
//! each sample the diagonals not in the goal triangulation whose flip
//! strictly lowers their number of crossings with it are candidates
//! (largest gain first, then the best new minimum angle); one is applied
//! when both new triangles are valid and their minimum angle is at least
//! min(the old pair's, ¼ of the inputs' minimum angle). After each batch
//! of flips the target is measured again with the new triangulation. The
//! total crossing count strictly falls, so this ends. If D* is reached
//! with flips left, the triangles around the blocked flips take the disk's
//! angles (a local unblock); if that is not enough either, the disk route
//! of DESIGN.md §7 finishes the job, so the procedure always ends.

use super::flips::{FlipTriangulation, crosses};
use super::incompatible::{Leg, Staged, disk_for, gate, stage};
use super::{Compatible, MorphError, ThirdVertexPath, area_and_centroid, lay_out_rooted};
use crate::geom::Point;
use crate::geom::polygon::triangle_angles;
use crate::immersion::check;
use crate::tree::{DualTree, RootChoice};
use std::f64::consts::{PI, TAU};

/// Smallest measured angle kept when building the target (δ ≈ 1°).
pub const TARGET_MIN_ANGLE: f64 = PI / 180.0;

/// Margin ε kept below 2π in every fan of the target (radians).
pub const TARGET_FAN_MARGIN: f64 = 0.05;

/// Sampling step along one leg toward the target.
const LEG_STEP: f64 = 1.0 / 200.0;

fn canonical(t: [u32; 3]) -> [u32; 3] {
    super::flips::canonical(t)
}

/// The target D*: the other curve measured with `tris`, made valid, laid
/// out and fitted to it. `blocked` triangles take the disk's angles.
fn target_shape(
    tris: &[[u32; 3]],
    other: &[Point],
    disk: &[Point],
    blocked: &[bool],
) -> Option<Vec<Point>> {
    let n = other.len();
    let disk_angles: Vec<[f64; 3]> = tris
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| disk[v as usize]);
            triangle_angles(a, b, c)
        })
        .collect();
    let measured: Vec<[f64; 3]> = tris
        .iter()
        .enumerate()
        .map(|(i, t)| {
            if blocked.get(i).copied().unwrap_or(false) {
                return disk_angles[i];
            }
            let [a, b, c] = t.map(|v| other[v as usize]);
            let m = triangle_angles(a, b, c)
                .map(|x| if x.is_finite() { x } else { PI / 3.0 })
                .map(|x| x.clamp(TARGET_MIN_ANGLE, PI - TARGET_MIN_ANGLE));
            let s = m[0] + m[1] + m[2];
            m.map(|x| x * PI / s)
        })
        .collect();
    let fan = |ang: &[[f64; 3]]| {
        let mut s = vec![0.0; n];
        for (t, a) in tris.iter().zip(ang) {
            for k in 0..3 {
                s[t[k] as usize] += a[k];
            }
        }
        s
    };
    let (sm, sd) = (fan(&measured), fan(&disk_angles));
    let cap = TAU - TARGET_FAN_MARGIN;
    let mut lambda: f64 = 0.0;
    for v in 0..n {
        if sm[v] > cap && sm[v] > sd[v] {
            lambda = lambda.max((sm[v] - cap) / (sm[v] - sd[v]));
        }
    }
    let tree = DualTree::new(n, tris).ok()?;
    let rooted = tree.rooted(tree.centre());
    // Rounding in the layout can spoil a nearly degenerate target; blend
    // further toward the disk until the exact check passes.
    for _ in 0..8 {
        let l = lambda.clamp(0.0, 1.0);
        let ang: Vec<[f64; 3]> = measured
            .iter()
            .zip(&disk_angles)
            .map(|(m, d)| [0, 1, 2].map(|k| m[k] + (d[k] - m[k]) * l))
            .collect();
        let laid = lay_out_rooted(&rooted, tris, &ang);
        let fitted = match_area(fit_similarity(&laid, other), other);
        if fitted.iter().all(|p| p.is_finite()) && check(&fitted, tris).is_ok() {
            return Some(fitted);
        }
        lambda = 0.5 * (1.0 + lambda);
    }
    None
}

/// Scales `p` about its area centroid so that its area equals `q`'s and
/// moves that centroid onto `q`'s, so that morphing toward it keeps the
/// total area within the inputs' range.
fn match_area(p: Vec<Point>, q: &[Point]) -> Vec<Point> {
    use crate::geom::polygon::{area_centroid, signed_area};
    let (ap, aq) = (signed_area(&p), signed_area(q));
    if !(ap > 0.0 && aq > 0.0) {
        return p;
    }
    let (cp, cq) = (area_centroid(&p), area_centroid(q));
    let k = (aq / ap).sqrt();
    p.into_iter().map(|x| cq + (x - cp) * k).collect()
}

/// The similarity (rotation, uniform scale, translation) that best maps
/// `p` onto `q` in the least-squares sense, applied to `p`.
pub(crate) fn fit_similarity(p: &[Point], q: &[Point]) -> Vec<Point> {
    let n = p.len() as f64;
    let (cp, cq) = (
        p.iter().copied().sum::<Point>() / n,
        q.iter().copied().sum::<Point>() / n,
    );
    // As complex numbers: a = Σ conj(p̃) q̃ / Σ |p̃|².
    let (mut re, mut im, mut den) = (0.0, 0.0, 0.0);
    for (a, b) in p.iter().zip(q) {
        let (x, y) = (*a - cp, *b - cq);
        re += x.dot(y);
        im += x.perp_dot(y);
        den += x.length_squared();
    }
    if den == 0.0 {
        return p.to_vec();
    }
    let a = Point::new(re / den, im / den);
    p.iter().map(|&x| cq + a.rotate(x - cp)).collect()
}

/// A candidate flip: the diagonal, its quad and the crossings it removes.
#[derive(Clone, Copy, Debug)]
struct Candidate {
    from: (u32, u32),
    quad: [u32; 4],
    gain: i64,
}

/// The flips that strictly lower their diagonal's crossings with the goal,
/// kept up to date flip by flip: a flip changes only the quads of its own
/// four sides and the new diagonal, so only those are recomputed (O(n) each
/// for the crossing counts) instead of every diagonal.
struct Candidates {
    by_diagonal: std::collections::BTreeMap<(u32, u32), Candidate>,
}

impl Candidates {
    fn new(cur: &FlipTriangulation, goal: &[(u32, u32)]) -> Candidates {
        let mut c = Candidates {
            by_diagonal: std::collections::BTreeMap::new(),
        };
        for d in cur.diagonals() {
            c.refresh_one(cur, goal, d);
        }
        c
    }

    fn refresh_one(&mut self, cur: &FlipTriangulation, goal: &[(u32, u32)], d: (u32, u32)) {
        let d = (d.0.min(d.1), d.0.max(d.1));
        self.by_diagonal.remove(&d);
        if goal.binary_search(&d).is_ok() {
            return;
        }
        let Some((quad, _)) = cur.quad(d.0, d.1) else {
            return;
        };
        let count = |c: (u32, u32)| goal.iter().filter(|&&g| crosses(g, c)).count() as i64;
        let new = (quad[1].min(quad[3]), quad[1].max(quad[3]));
        let gain = count(d) - count(new);
        if gain > 0 {
            self.by_diagonal.insert(
                d,
                Candidate {
                    from: d,
                    quad,
                    gain,
                },
            );
        }
    }

    /// Applies the flip of `c` to `cur` and updates the affected entries.
    fn flip(&mut self, cur: &mut FlipTriangulation, goal: &[(u32, u32)], c: Candidate) {
        cur.flip(c.from.0, c.from.1);
        let [a, b, cc, d] = c.quad;
        for e in [c.from, (b, d), (a, b), (b, cc), (cc, d), (d, a)] {
            self.refresh_one(cur, goal, e);
        }
    }

    fn iter(&self) -> impl Iterator<Item = &Candidate> {
        self.by_diagonal.values()
    }
}

/// Applies acceptable flips at shape `p` until none is left; returns how
/// many.
fn batch(
    cur: &mut FlipTriangulation,
    cands: &mut Candidates,
    goal: &[(u32, u32)],
    p: &[Point],
    floor: f64,
) -> usize {
    let mut applied = 0;
    loop {
        let best = cands
            .iter()
            .filter_map(|c| gate(p, c.quad, floor).map(|m| (*c, m)))
            .max_by(|(c1, m1), (c2, m2)| c1.gain.cmp(&c2.gain).then(m1.total_cmp(m2)));
        let Some((c, _)) = best else {
            return applied;
        };
        cands.flip(cur, goal, c);
        applied += 1;
    }
}

/// Builds the target-route path from `s` (triangulated by `t_start`) to
/// `other` (triangulated by `t_goal`, same labels). `floor` is the gate's
/// angle floor (¼ of the inputs' minimum angle).
#[allow(
    clippy::too_many_arguments,
    reason = "one call site; the parameters are the route's inputs"
)]
pub(crate) fn stage_target(
    s: &[Point],
    t_start: &[[u32; 3]],
    other: &[Point],
    t_goal: &[[u32; 3]],
    final_path: ThirdVertexPath,
    root: RootChoice,
    margin: f64,
    floor: f64,
) -> Result<Staged, MorphError> {
    let n = s.len();
    let (area, centroid) = area_and_centroid(s, t_start);
    let disk = disk_for(s, area, centroid);
    let goal = FlipTriangulation::new(n, t_goal).diagonals();
    let mut cur = FlipTriangulation::new(n, t_start);
    let mut x = s.to_vec();
    let mut u = 0.0f64;
    let mut legs: Vec<Leg> = Vec::new();
    let (mut flips, mut unblocks, mut retargets) = (0usize, 0usize, 0usize);
    let mut blocked: Vec<bool> = Vec::new();
    let mut cands = Candidates::new(&cur, &goal);
    // Flips acceptable in the input shape itself.
    flips += batch(&mut cur, &mut cands, &goal, &x, floor);
    while cur.diagonals() != goal {
        let target = target_shape(cur.triangles(), other, &disk, &blocked);
        let plan = match target {
            Some(t) => Compatible::new(&x, &t, cur.triangles(), root, margin).ok(),
            None => None,
        };
        let Some(plan) = plan else {
            return disk_fallback(
                s, legs, x, u, &cur, other, t_goal, final_path, root, margin, flips, unblocks,
            );
        };
        retargets += 1;
        let mut k = 1usize;
        let moved = loop {
            let sh = (k as f64 * LEG_STEP).min(1.0);
            let p = plan.positions(sh, ThirdVertexPath::Hybrid);
            let applied = batch(&mut cur, &mut cands, &goal, &p, floor);
            if applied > 0 || sh >= 1.0 {
                legs.push(Leg {
                    plan,
                    path: ThirdVertexPath::Hybrid,
                    s_end: sh,
                    u0: u,
                    u1: u + sh,
                });
                u += sh;
                x = p;
                flips += applied;
                break applied > 0;
            }
            k += 1;
        };
        if moved {
            blocked.clear();
            continue;
        }
        // D* reached with flips left: unblock locally once, then the disk.
        if !blocked.is_empty() {
            return disk_fallback(
                s, legs, x, u, &cur, other, t_goal, final_path, root, margin, flips, unblocks,
            );
        }
        unblocks += 1;
        blocked = vec![false; cur.triangles().len()];
        for c in cands.iter() {
            for [a, b, cc] in [
                [c.quad[0], c.quad[1], c.quad[2]],
                [c.quad[2], c.quad[3], c.quad[0]],
            ] {
                let t = canonical([a, b, cc]);
                if let Some(i) = cur.triangles().iter().position(|&q| q == t) {
                    blocked[i] = true;
                }
            }
        }
    }
    legs.push(Leg {
        plan: Compatible::new(&x, other, cur.triangles(), root, margin)?,
        path: final_path,
        s_end: 1.0,
        u0: u,
        u1: u + 1.0,
    });
    Ok(Staged {
        legs,
        u_star: retargets as f64,
        flips,
        unblocks,
        used_disk: false,
    })
}

/// Finishes with the disk route from the current shape and triangulation.
#[allow(
    clippy::too_many_arguments,
    reason = "the state of the route at the hand-over"
)]
fn disk_fallback(
    _s: &[Point],
    mut legs: Vec<Leg>,
    x: Vec<Point>,
    u: f64,
    cur: &FlipTriangulation,
    other: &[Point],
    t_goal: &[[u32; 3]],
    final_path: ThirdVertexPath,
    root: RootChoice,
    margin: f64,
    flips: usize,
    unblocks: usize,
) -> Result<Staged, MorphError> {
    let rest = stage(&x, cur.triangles(), other, t_goal, final_path, root, margin)?;
    let retargets = legs.len();
    for mut leg in rest.legs {
        leg.u0 += u;
        leg.u1 += u;
        legs.push(leg);
    }
    Ok(Staged {
        legs,
        u_star: retargets as f64 + rest.u_star,
        flips: flips + rest.flips,
        unblocks,
        used_disk: true,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::morph::compatible::tests::spiral_strip;
    use crate::quality::{Quality, triangulate_with};

    #[test]
    fn similarity_fit_recovers_a_similarity() {
        let p = vec![
            Point::new(0.0, 0.0),
            Point::new(2.0, 0.0),
            Point::new(1.0, 3.0),
        ];
        let a = Point::new(0.6, -1.7);
        let q: Vec<Point> = p
            .iter()
            .map(|&x| a.rotate(x) + Point::new(5.0, -2.0))
            .collect();
        let f = fit_similarity(&p, &q);
        for (x, y) in f.iter().zip(&q) {
            assert!((*x - *y).length() < 1e-12);
        }
    }

    #[test]
    fn target_route_between_spirals_is_valid_and_ends_without_the_disk() {
        let (a, _) = spiral_strip(18, 1.5, 0.25);
        let (b, _) = spiral_strip(18, 0.7, 0.25);
        let ta = triangulate_with(&a, Quality::Delaunay).unwrap().triangles;
        let tb = triangulate_with(&b, Quality::Delaunay).unwrap().triangles;
        let floor = 0.25
            * crate::geom::polygon::min_triangle_angle(&a, &ta)
                .min(crate::geom::polygon::min_triangle_angle(&b, &tb));
        let mut staged = stage_target(
            &a,
            &ta,
            &b,
            &tb,
            ThirdVertexPath::Hybrid,
            RootChoice::Disk,
            0.05,
            floor,
        )
        .unwrap();
        let fr: Vec<f64> = (0..=400).map(|i| i as f64 / 400.0).collect();
        let (frames, _) = staged.frames(&fr).unwrap();
        assert_eq!(frames[0].points, a);
        assert_eq!(frames[400].points, b);
        assert!(frames.iter().all(|f| f.is_immersion()));
    }
}
