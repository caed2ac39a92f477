//! Morphing two curves whose triangulations differ: staged edge flips on
//! the way to a disk (seed 004 §6.2; DESIGN.md §7).
//!
//! Each curve S is morphed toward a disk D (its vertices on a circle,
//! spaced by the curve's edge lengths, with the curve's area and
//! centroid) under its current triangulation, with the guaranteed `hybrid`
//! path. The flips that turn its triangulation into the other curve's are
//! applied in order, each at the first sampled moment when both new
//! triangles are valid in the current shape *and* their minimum angle is
//! at least min(the old pair's, half the disk's minimum angle) — flipping
//! at the first valid moment makes slivers that then open fast. After a
//! flip the morph continues from the current shape under the new
//! triangulation. At the disk every flip is valid, so the procedure always
//! finishes. Once the other triangulation is reached (at u*), the shape is
//! morphed directly to the other curve.
//!
//! Both directions are computed, each in its own curve's vertex labels,
//! and the one that reaches the other triangulation earlier is used
//! (ties go to the lexicographically smaller curve), so that
//! `morph(S1, S2)` is exactly `morph(S2, S1)` reversed. Output frames are
//! placed at equal steps of cumulative maximum vertex displacement.

use super::flips::{Flip, FlipTriangulation, canonical, flip_sequence};
use super::{Compatible, MorphError, ThirdVertexPath};
use crate::frames::Frame;
use crate::geom::Point;
use crate::geom::polygon::min_triangle_angle as min_angle;
use crate::geom::polygon::signed_area;
use crate::immersion::{check, is_valid_triangle};
use crate::tree::{RootChoice, disk_positions};

/// Sampling step of the flip schedule in the global parameter u ∈ [0, 1].
pub const SCHEDULE_STEP: f64 = 1.0 / 400.0;

/// Dense samples per unit of u used to time output frames by displacement.
const DENSE_PER_UNIT: f64 = 256.0;

/// One stretch of the path: a compatible morph under a fixed
/// triangulation, used for its local parameter in `[0, s_end]`.
#[derive(Clone, Debug)]
pub(crate) struct Leg {
    pub(crate) plan: Compatible,
    pub(crate) path: ThirdVertexPath,
    pub(crate) s_end: f64,
    /// Global u at the start and end of the leg (the final leg to the other
    /// curve spans [u*, u* + 1] by convention).
    pub(crate) u0: f64,
    pub(crate) u1: f64,
}

impl Leg {
    fn at(&self, u: f64) -> (Vec<Point>, &[[u32; 3]]) {
        let s = if self.u1 > self.u0 {
            ((u - self.u0) / (self.u1 - self.u0)).clamp(0.0, 1.0) * self.s_end
        } else {
            0.0
        };
        (self.plan.positions(s, self.path), self.plan.triangles())
    }
}

/// A staged path from one curve to another.
#[derive(Clone, Debug)]
pub struct Staged {
    pub(crate) legs: Vec<Leg>,
    /// Where the other triangulation was reached: for the disk route the
    /// disk parameter u ∈ [0, 1]; for the target route the number of
    /// re-targeted legs it took.
    pub u_star: f64,
    /// Flips applied.
    pub flips: usize,
    /// Local unblocks used (target route).
    pub unblocks: usize,
    /// True when the target route had to fall back to the disk.
    pub used_disk: bool,
}

/// The disk of DESIGN.md §7: vertices on a circle spaced in proportion to
/// the curve's edge lengths, with the curve's area (as the polygon it
/// forms) and area centroid.
pub fn disk_for(points: &[Point], area: f64, centroid: Point) -> Vec<Point> {
    let unit = disk_positions(points);
    let a_unit = signed_area(&unit);
    let c_unit = crate::geom::polygon::area_centroid(&unit);
    let scale = (area / a_unit).sqrt();
    unit.into_iter()
        .map(|p| centroid + (p - c_unit) * scale)
        .collect()
}

/// The flip gate of DESIGN.md §7: the flip of the quad `[a, b, c, d]`
/// (diagonal a–c to b–d) may be applied in shape `p` when both new
/// triangles are valid and their minimum angle is at least min(the old
/// pair's, `floor`); returns that minimum angle. With `floor` = 0 only
/// validity is required.
pub(crate) fn gate(p: &[Point], quad: [u32; 4], floor: f64) -> Option<f64> {
    let [a, b, c, d] = quad;
    let new = [canonical([a, b, d]), canonical([b, c, d])];
    let old = [canonical([a, b, c]), canonical([c, d, a])];
    if !new
        .iter()
        .all(|t| is_valid_triangle(p, t[0] as usize, t[1] as usize, t[2] as usize))
    {
        return None;
    }
    let m = min_angle(p, &new);
    (m >= min_angle(p, &old).min(floor)).then_some(m)
}

fn flip_ok(p: &[Point], quad: [u32; 4], floor: f64) -> bool {
    gate(p, quad, floor).is_some()
}

/// Builds the staged path from `s` (triangulated by `t_start`) to `other`
/// (triangulated by `t_goal`, in the same labels).
pub(crate) fn stage(
    s: &[Point],
    t_start: &[[u32; 3]],
    other: &[Point],
    t_goal: &[[u32; 3]],
    final_path: ThirdVertexPath,
    root: RootChoice,
    margin: f64,
) -> Result<Staged, MorphError> {
    let n = s.len();
    let (area, centroid) = super::area_and_centroid(s, t_start);
    let disk = disk_for(s, area, centroid);
    let floor = 0.5 * min_angle(&disk, t_start).min(min_angle(&disk, t_goal));
    let flips: Vec<Flip> = flip_sequence(n, t_start, t_goal);
    let mut cur = FlipTriangulation::new(n, t_start);
    let mut x = s.to_vec();
    let mut u = 0.0f64;
    let mut legs = Vec::new();
    let mut next = 0usize;
    while next < flips.len() {
        let plan = Compatible::new(&x, &disk, cur.triangles(), root, margin)?;
        let u_start = u;
        // Walk forward in u until the next flip passes the gate.
        let mut k = 0usize;
        loop {
            let u_here = (u_start + k as f64 * SCHEDULE_STEP).min(1.0);
            let s_here = if u_start < 1.0 {
                (u_here - u_start) / (1.0 - u_start)
            } else {
                1.0
            };
            let p = plan.positions(s_here, ThirdVertexPath::Hybrid);
            let at_disk = u_here >= 1.0;
            let Flip { from, .. } = flips[next];
            let quad = cur.quad(from.0, from.1).map(|q| q.0);
            let Some(quad) = quad else {
                // Not a diagonal of the current triangulation: the
                // sequence is out of step; a bug.
                return Err(MorphError::InvalidFrame {
                    t: u_here,
                    path: ThirdVertexPath::Hybrid,
                    defect: format!("flip {}-{} is not a diagonal", from.0, from.1),
                });
            };
            if at_disk || flip_ok(&p, quad, floor) {
                legs.push(Leg {
                    plan,
                    path: ThirdVertexPath::Hybrid,
                    s_end: s_here,
                    u0: u_start,
                    u1: u_here,
                });
                x = p;
                u = u_here;
                // Apply this flip and every following one that is already
                // acceptable in the same shape.
                cur.flip(from.0, from.1);
                next += 1;
                while next < flips.len() {
                    let f = flips[next].from;
                    match cur.quad(f.0, f.1) {
                        Some((q, _)) if at_disk || flip_ok(&x, q, floor) => {
                            cur.flip(f.0, f.1);
                            next += 1;
                        }
                        _ => break,
                    }
                }
                break;
            }
            k += 1;
        }
    }
    let u_star = u;
    let plan = Compatible::new(&x, other, cur.triangles(), root, margin)?;
    legs.push(Leg {
        plan,
        path: final_path,
        s_end: 1.0,
        u0: u_star,
        u1: u_star + 1.0,
    });
    Ok(Staged {
        legs,
        u_star,
        flips: flips.len(),
        unblocks: 0,
        used_disk: true,
    })
}

impl Staged {
    /// Builds the staged path from `s` to `other` (same labels), trying
    /// `t_start` on `other` first: when it is valid there no flip is needed.
    ///
    /// # Errors
    ///
    /// [`MorphError`] when a compatible leg cannot be set up (a bug).
    #[allow(
        clippy::too_many_arguments,
        reason = "the inputs of one side of the morph"
    )]
    pub fn new(
        s: &[Point],
        t_start: &[[u32; 3]],
        other: &[Point],
        t_other: &[[u32; 3]],
        final_path: ThirdVertexPath,
        root: RootChoice,
        margin: f64,
        intermediate: super::Intermediate,
        floor: f64,
    ) -> Result<Staged, MorphError> {
        let goal = if check(other, t_start).is_ok() {
            t_start
        } else {
            t_other
        };
        match intermediate {
            super::Intermediate::Disk => stage(s, t_start, other, goal, final_path, root, margin),
            super::Intermediate::Target => super::target::stage_target(
                s, t_start, other, goal, final_path, root, margin, floor,
            ),
        }
    }

    /// The end of the path's parameter range.
    fn u_end(&self) -> f64 {
        self.legs.last().map_or(0.0, |l| l.u1)
    }

    fn leg_at(&self, u: f64) -> &Leg {
        // The last leg whose range starts at or before u; zero-length legs
        // (flips at the same moment) are skipped by taking the last one.
        let mut found = &self.legs[0];
        for leg in &self.legs {
            if leg.u0 <= u {
                found = leg;
            }
        }
        found
    }

    /// Positions and triangulation at global parameter `u`.
    fn at(&self, u: f64) -> (Vec<Point>, Vec<[u32; 3]>) {
        let leg = self.leg_at(u);
        let (p, t) = leg.at(u);
        (p, t.to_vec())
    }

    /// Frames at the given fractions of the total displacement (0 = the
    /// source, 1 = the target), each checked exactly. The unguaranteed
    /// final path, if it fails the check, is replaced by `hybrid` (the
    /// returned flag says so).
    ///
    /// # Errors
    ///
    /// [`MorphError::InvalidFrame`] when a guaranteed path produced an
    /// invalid frame (a bug).
    pub fn frames(&mut self, fractions: &[f64]) -> Result<(Vec<Frame>, bool), MorphError> {
        let mut fallback = false;
        loop {
            let frames = self.sample(fractions);
            match frames
                .iter()
                .find_map(|f| f.check().err().map(|e| (f.t, e)))
            {
                None => return Ok((frames, fallback)),
                Some((t, defect)) => {
                    let last = self.legs.len() - 1;
                    if self.legs[last].path.is_guaranteed() {
                        return Err(MorphError::InvalidFrame {
                            t,
                            path: self.legs[last].path,
                            defect: defect.to_string(),
                        });
                    }
                    self.legs[last].path = ThirdVertexPath::Hybrid;
                    fallback = true;
                }
            }
        }
    }

    /// Total path length: the sum over dense samples of the largest vertex
    /// move.
    pub fn path_length(&self) -> f64 {
        let (_, cum) = self.dense();
        *cum.last().unwrap_or(&0.0)
    }

    /// Dense parameter samples and the cumulative largest vertex move.
    fn dense(&self) -> (Vec<f64>, Vec<f64>) {
        let u_end = self.u_end();
        let mut us: Vec<f64> = self.legs.iter().map(|l| l.u0).collect();
        us.push(u_end);
        let dense = (u_end * DENSE_PER_UNIT).ceil().max(16.0) as usize;
        us.extend((0..=dense).map(|i| u_end * i as f64 / dense as f64));
        us.sort_by(f64::total_cmp);
        us.dedup();
        let mut cum = vec![0.0f64; us.len()];
        let mut prev = self.at(us[0]).0;
        for i in 1..us.len() {
            let cur = self.at(us[i]).0;
            let step = cur
                .iter()
                .zip(&prev)
                .map(|(a, b)| (*a - *b).length())
                .fold(0.0, f64::max);
            cum[i] = cum[i - 1] + step;
            prev = cur;
        }
        (us, cum)
    }

    fn sample(&self, fractions: &[f64]) -> Vec<Frame> {
        let u_end = self.u_end();
        let (us, cum) = self.dense();
        let total = *cum.last().unwrap_or(&0.0);
        fractions
            .iter()
            .map(|&f| {
                let f = f.clamp(0.0, 1.0);
                let u = if f <= 0.0 {
                    0.0
                } else if f >= 1.0 || total <= 0.0 {
                    u_end
                } else {
                    let d = f * total;
                    let i = cum.partition_point(|&c| c < d).clamp(1, us.len() - 1);
                    let (c0, c1) = (cum[i - 1], cum[i]);
                    let w = if c1 > c0 { (d - c0) / (c1 - c0) } else { 0.0 };
                    us[i - 1] + w * (us[i] - us[i - 1])
                };
                let (points, triangles) = self.at(u);
                Frame {
                    t: f,
                    points,
                    triangles,
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::morph::compatible::tests::spiral_strip;
    use crate::quality::{Quality, triangulate_with};

    #[test]
    fn the_disk_has_the_curve_area_and_centroid() {
        let (s, tris) = spiral_strip(20, 1.3, 0.2);
        let (area, c) = crate::morph::area_and_centroid(&s, &tris);
        let d = disk_for(&s, area, c);
        assert!((signed_area(&d) - area).abs() < 1e-12 * area);
        assert!((crate::geom::polygon::area_centroid(&d) - c).length() < 1e-12);
    }

    #[test]
    fn staged_morph_between_incompatible_spirals_is_valid_throughout() {
        let (a, _) = spiral_strip(16, 1.4, 0.25);
        let (b, _) = spiral_strip(16, 0.6, 0.25);
        let ta = triangulate_with(&a, Quality::Delaunay).unwrap().triangles;
        let tb = triangulate_with(&b, Quality::Delaunay).unwrap().triangles;
        let mut staged = Staged::new(
            &a,
            &ta,
            &b,
            &tb,
            ThirdVertexPath::Hybrid,
            RootChoice::Disk,
            0.05,
            crate::morph::Intermediate::Disk,
            0.0,
        )
        .unwrap();
        let fr: Vec<f64> = (0..=400).map(|i| i as f64 / 400.0).collect();
        let (frames, fallback) = staged.frames(&fr).unwrap();
        assert!(!fallback);
        assert_eq!(frames[0].points, a);
        assert_eq!(frames[400].points, b);
        for f in &frames {
            assert!(f.is_immersion(), "t={}", f.t);
        }
    }
}
