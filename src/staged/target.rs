//! A target-shaped intermediate instead of the disk (docs/design.md §7a): the
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
//! of docs/design.md §7 finishes the job, so the procedure always ends.

use crate::flip::sequence::FlipTriangulation;
use crate::flip::sequence::gate;
use crate::geom::Point;
use crate::geom::polygon::triangle_angles;
use crate::immersion::check_triangles;
use crate::propagate::compatible::lay_out_rooted;
use crate::propagate::layout::{self, fit_similarity, lerp3};
use crate::tree::DualTree;
use std::f64::consts::{PI, TAU};

/// Smallest measured angle kept when building the target (δ ≈ 1°).
pub(crate) const TARGET_MIN_ANGLE: f64 = PI / 180.0;

/// Margin ε kept below 2π in every fan of the target (radians).
pub(crate) const TARGET_FAN_MARGIN: f64 = 0.05;

/// The corner angles of each triangle on the disk and on the other curve,
/// kept from one target to the next: a flip replaces two triangles in
/// place, so only the triangles that changed are measured again.
#[derive(Default)]
pub(crate) struct TargetAngles {
    tris: Vec<[u32; 3]>,
    disk: Vec<[f64; 3]>,
    other: Vec<[f64; 3]>,
}

impl TargetAngles {
    /// Brings the angles up to date with `tris`.
    fn update(&mut self, tris: &[[u32; 3]], disk: &[Point], other: &[Point]) {
        let measure = |p: &[Point], t: [u32; 3]| {
            let [a, b, c] = t.map(|v| p[v as usize]);
            triangle_angles(a, b, c)
        };
        if self.tris.len() != tris.len() {
            *self = TargetAngles::default();
        }
        for (i, &t) in tris.iter().enumerate() {
            if self.tris.get(i) == Some(&t) {
                continue;
            }
            if i >= self.tris.len() {
                self.tris.push(t);
                self.disk.push(measure(disk, t));
                self.other.push(measure(other, t));
            } else {
                self.tris[i] = t;
                self.disk[i] = measure(disk, t);
                self.other[i] = measure(other, t);
            }
        }
    }
}

/// The target D*: the other curve measured with the triangulation of
/// `tree`, made valid, laid out and fitted to it. `blocked` triangles take
/// the disk's angles. `angles` keeps the measurements between calls with
/// the same disk and other curve.
pub(crate) fn target_shape(
    tree: &DualTree,
    other: &[Point],
    disk: &[Point],
    blocked: &[bool],
    angles: &mut TargetAngles,
) -> Option<Vec<Point>> {
    let n = other.len();
    let tris = tree.triangles();
    angles.update(tris, disk, other);
    let disk_angles = &angles.disk;
    let measured: Vec<[f64; 3]> = (0..tris.len())
        .map(|i| {
            if blocked.get(i).copied().unwrap_or(false) {
                return disk_angles[i];
            }
            let m = angles.other[i]
                .map(|x| if x.is_finite() { x } else { PI / 3.0 })
                .map(|x| x.clamp(TARGET_MIN_ANGLE, PI - TARGET_MIN_ANGLE));
            let s = m[0] + m[1] + m[2];
            m.map(|x| x * PI / s)
        })
        .collect();
    let corners: Vec<[usize; 3]> = tris.iter().map(|t| t.map(|v| v as usize)).collect();
    let sm = layout::fan_sums(n, &corners, &measured);
    let sd = layout::fan_sums(n, &corners, disk_angles);
    let mut lambda = layout::fan_blend(&sm, &sd, |_| TAU - TARGET_FAN_MARGIN);
    let rooted = tree.rooted(tree.centre());
    // Rounding in the layout can spoil a nearly degenerate target; blend
    // further toward the disk until the exact check passes. `tris` is a
    // triangulation of the n-gon (its dual tree exists), so the
    // geometric half of the check is the whole check.
    for _ in 0..8 {
        let l = lambda.clamp(0.0, 1.0);
        let ang: Vec<[f64; 3]> = measured
            .iter()
            .zip(disk_angles)
            .map(|(m, d)| lerp3(*m, *d, l))
            .collect();
        let laid = lay_out_rooted(&rooted, tris, &ang);
        let fit = fit_similarity(&laid, other);
        let fitted = match_area(laid.iter().map(|&p| fit.apply(p)).collect(), other);
        if fitted.iter().all(|p| p.is_finite()) && check_triangles(&fitted, tris).is_ok() {
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

/// A candidate flip: the diagonal, its quad and the crossings it removes.
#[derive(Clone, Copy, Debug)]
struct Candidate {
    from: (u32, u32),
    quad: [u32; 4],
    gain: i64,
}

/// The flips that strictly lower their diagonal's crossings with the goal,
/// kept up to date flip by flip: a flip changes only the quads of its own
/// four sides and the new diagonal, so only those are recomputed instead of
/// every diagonal. The current diagonals' crossing counts with the goal are
/// remembered (a flipped-in diagonal's is its predecessor's less the gain),
/// so a refresh counts one chord (O(log² n)), the one it would flip to.
pub(crate) struct Candidates {
    /// The candidates by diagonal (hashed: the order they are applied in
    /// is fixed by sorting, with the diagonal as the last key).
    by_diagonal: rustc_hash::FxHashMap<(u32, u32), Candidate>,
    /// The goal's diagonals, sorted.
    goal: Vec<(u32, u32)>,
    /// Crossing counts against the goal.
    crossings: crate::flip::sequence::CrossingCounter,
    /// Crossing counts of the current diagonals not in the goal, as far as
    /// counted.
    counted: rustc_hash::FxHashMap<(u32, u32), usize>,
    /// The candidates (re)made by the flips since the last pass of a batch.
    refreshed: Vec<(u32, u32)>,
}

impl Candidates {
    pub(crate) fn new(cur: &FlipTriangulation, goal: &[(u32, u32)]) -> Candidates {
        let mut c = Candidates {
            by_diagonal: rustc_hash::FxHashMap::default(),
            goal: goal.to_vec(),
            crossings: crate::flip::sequence::CrossingCounter::new(goal),
            counted: rustc_hash::FxHashMap::default(),
            refreshed: Vec::new(),
        };
        for d in cur.diagonals() {
            c.refresh_one(cur, d);
        }
        c
    }

    fn refresh_one(&mut self, cur: &FlipTriangulation, d: (u32, u32)) {
        let d = (d.0.min(d.1), d.0.max(d.1));
        self.by_diagonal.remove(&d);
        let goal = &self.goal;
        if goal.binary_search(&d).is_ok() {
            return;
        }
        let Some((quad, _)) = cur.quad(d.0, d.1) else {
            return;
        };
        let new = (quad[1].min(quad[3]), quad[1].max(quad[3]));
        let gain = self.count(d) as i64 - self.crossings.count(new) as i64;
        if gain > 0 {
            self.refreshed.push(d);
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

    /// The crossings of the current diagonal `d` (`d.0 < d.1`) with the
    /// goal.
    fn count(&mut self, d: (u32, u32)) -> usize {
        let crossings = &self.crossings;
        *self.counted.entry(d).or_insert_with(|| crossings.count(d))
    }

    /// Applies the flip of `c` to `cur` and updates the affected entries.
    fn flip(&mut self, cur: &mut FlipTriangulation, c: Candidate) {
        cur.flip(c.from.0, c.from.1);
        let [a, b, cc, d] = c.quad;
        if let Some(before) = self.counted.remove(&c.from) {
            let after = before as i64 - c.gain;
            self.counted.insert((b.min(d), b.max(d)), after as usize);
        }
        for e in [c.from, (b, d), (a, b), (b, cc), (cc, d), (d, a)] {
            self.refresh_one(cur, e);
        }
    }

    fn iter(&self) -> impl Iterator<Item = &Candidate> {
        self.by_diagonal.values()
    }

    /// True when no flip lowers the crossings: the goal is reached (in
    /// convex position some flip always lowers them otherwise).
    pub(crate) fn is_empty(&self) -> bool {
        self.by_diagonal.is_empty()
    }

    /// The quads of the waiting flips.
    pub(crate) fn quads(&self) -> Vec<[u32; 4]> {
        self.iter().map(|c| c.quad).collect()
    }

    /// Applies acceptable flips at shape `p` (largest gain first, then the
    /// best new minimum angle, then the smaller diagonal) until none is
    /// left; returns how many. Each pass gates the candidates and applies
    /// those that pass in that order, gating each again just before (an
    /// earlier flip of the pass may have changed its quad); flips made
    /// possible by the pass wait for the next pass. The first pass gates
    /// every candidate; a later one only those a flip of the pass before
    /// refreshed, as every other one failed the gate then and, with the
    /// same quad in the same shape, fails it again.
    pub(crate) fn batch(&mut self, cur: &mut FlipTriangulation, p: &[Point], floor: f64) -> usize {
        let mut applied = 0;
        let mut first = true;
        loop {
            let gated = |c: &Candidate| gate(p, c.quad, floor).map(|m| (*c, m));
            let mut ready: Vec<(Candidate, f64)> = if first {
                self.iter().filter_map(gated).collect()
            } else {
                let mut refreshed = std::mem::take(&mut self.refreshed);
                refreshed.sort_unstable();
                refreshed.dedup();
                refreshed
                    .iter()
                    .filter_map(|d| self.by_diagonal.get(d))
                    .filter_map(gated)
                    .collect()
            };
            first = false;
            self.refreshed.clear();
            if ready.is_empty() {
                return applied;
            }
            ready.sort_by(|(c1, m1), (c2, m2)| {
                c2.gain
                    .cmp(&c1.gain)
                    .then(m2.total_cmp(m1))
                    .then(c1.from.cmp(&c2.from))
            });
            for (c, _) in ready {
                // Still a candidate with the same quad, and still acceptable?
                let current = self.by_diagonal.get(&c.from).copied();
                let Some(now) = current else { continue };
                if now.quad != c.quad || gate(p, now.quad, floor).is_none() {
                    continue;
                }
                self.flip(cur, now);
                applied += 1;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::propagate::compatible::area_and_centroid;
    use crate::propagate::compatible::tests::spiral_strip;
    use crate::quality::{Quality, triangulate_with};

    #[test]
    fn the_target_is_valid_and_is_the_other_curve_where_the_triangulation_fits_it() {
        let (a, _) = spiral_strip(18, 1.5, 0.25);
        let (b, _) = spiral_strip(18, 0.7, 0.25);
        let ta = triangulate_with(&a, Quality::Delaunay).unwrap().triangles;
        let tb = triangulate_with(&b, Quality::Delaunay).unwrap().triangles;
        let (area, c) = area_and_centroid(&a, &ta);
        let disk = crate::staged::disk_for(&a, area, c);
        // A's triangulation on B: some triangles are inverted there; the
        // target is an immersion anyway.
        let mut angles = TargetAngles::default();
        let t = target_shape(
            &DualTree::new(a.len(), &ta).unwrap(),
            &b,
            &disk,
            &[],
            &mut angles,
        )
        .unwrap();
        assert!(crate::immersion::check(&t, &ta).is_ok());
        // B's own triangulation (angles above the clamp): B itself.
        assert!(crate::geom::polygon::min_triangle_angle(&b, &tb) > TARGET_MIN_ANGLE);
        let t = target_shape(
            &DualTree::new(b.len(), &tb).unwrap(),
            &b,
            &disk,
            &[],
            &mut TargetAngles::default(),
        )
        .unwrap();
        let diag = crate::propagate::compatible::tests::bbox_diag(&b);
        for (p, q) in t.iter().zip(&b) {
            assert!((*p - *q).length() < 1e-9 * diag);
        }
    }
}
