//! Morphing compatible triangulations by propagation along the dual tree
//! (Mukherjee & Gopi §5; docs/design.md §6).
//!
//! The dual tree is rooted at one triangle. The root's placement is
//! interpolated (rotation angle, stretch from the polar decomposition of
//! the source→target affine map, translation). Every other triangle is
//! placed on its current base, which its parent has already placed; only
//! third vertices move, so the shape is consistent at every t and equals
//! the target at t = 1.
//!
//! Paths that lay triangles out from angles (`straight`, `polar`, `angle`,
//! `hybrid`) are placed by the global fit: the least-squares similarity
//! onto the straight guide, kept to an area range (docs/design.md §6,
//! "Placement"); it is applied at every t, so nothing jumps.

use crate::geom::Point;
use crate::propagate::layout::{self, lerp3};
use crate::propagate::paths::{
    RotateSlide, ThirdVertexPath, base_frame_angles, from_base_frame, to_base_frame,
};
use crate::propagate::rigid::RigidGuide;
use crate::tree::{DualTree, Root, RootChoice, Rooted, root_triangle};
use std::f64::consts::TAU;

/// Default margin ε (radians) kept below 2π in every vertex fan by the
/// hybrid path (docs/design.md §6: about 0.05 rad).
pub(crate) const DEFAULT_FAN_MARGIN: f64 = 0.05;

/// Angle floor (radians) of the straight path: a triangle of the guide
/// thinner than min(this, half its smallest angle in the angle rule) is
/// lifted toward the angle rule (about 0.5°).
pub(crate) const STRAIGHT_MIN_ANGLE: f64 = 0.5 * std::f64::consts::PI / 180.0;

/// The smallest angle of the angle rule (radians) below which the
/// straight path's floor step takes the nearest point of the floor set
/// rather than the rule's angles, and above which it takes the rule's
/// angles; between the two it blends them (0.25° and 1°).
const RULE_THIN: (f64, f64) = (0.25 * 2.0 * STRAIGHT_MIN_ANGLE, 2.0 * STRAIGHT_MIN_ANGLE);

/// The fitted paths (`straight`, `polar`, `angle`, `hybrid`) keep their
/// total area between these multiples of the smaller and the larger
/// endpoint's: a linear interpolation may shrink a little in the middle, as
/// animators expect, but never collapse.
pub(crate) const STRAIGHT_AREA_RANGE: (f64, f64) = (0.81, 1.13);

/// Precomputed data for morphing one compatible pair.
#[derive(Clone, Debug)]
pub struct Compatible {
    src: Vec<Point>,
    dst: Vec<Point>,
    triangles: Vec<[u32; 3]>,
    rooted: Rooted,
    /// The base-frame data of the paths that propagate third vertices
    /// (`linear`, `rotate-slide`, `hybrid`), made when first asked for: the
    /// default path and most legs never need them.
    base_frames: std::sync::OnceLock<BaseFrames>,
    /// Per triangle, angles at (base start, base end, third) in source and
    /// target.
    ang_src: Vec<[f64; 3]>,
    ang_dst: Vec<[f64; 3]>,
    root: RootMotion,
    fan_margin: f64,
    /// Per triangle, its corners as (base start, base end, third).
    corners: Vec<[usize; 3]>,
    /// Where the straight path's guide ends (the target unless
    /// [`Compatible::with_guide`] says otherwise).
    guide_end: Vec<Point>,
    /// The vertex means of the source and of the guide's end, and the
    /// best-fit rotation between them (the guide turns by it).
    guide_frame: ([Point; 2], f64),
    /// The vertex means of source and target and the best-fit rotation
    /// between them: the frame of the guide toward the target itself, which
    /// places the angle-based paths that ignore [`Compatible::with_guide`].
    target_frame: ([Point; 2], f64),
    /// The total area range the fitted paths keep to.
    area_range: (f64, f64),
    /// The polar path's ends, made on first use.
    polar: std::sync::OnceLock<PolarEnds>,
    /// The rigid path's guide, made on first use (`None` where it cannot
    /// be factored, and the straight guide toward the target stands in).
    rigid: std::sync::OnceLock<Option<(RigidGuide, [Vec<Point>; 2])>>,
    /// How the root triangle was chosen (to build the plan again,
    /// [`Compatible::seed`]).
    root_choice: Root,
}

/// What a plan is built from, without what it derives: about a third of
/// its memory. [`PlanSeed::build`] builds the same plan again, bit for bit
/// (every step is deterministic), so the staged route need not keep a
/// plan for each of its many legs while it walks them.
#[derive(Clone, Debug)]
pub(crate) struct PlanSeed {
    /// The source: shared with the leg's first key where released by the
    /// staged route ([`Compatible::seed_sharing`]).
    src: std::sync::Arc<[Point]>,
    dst: Vec<Point>,
    triangles: Vec<[u32; 3]>,
    root_choice: Root,
    fan_margin: f64,
    /// The straight guide's end where it is not the target: shared with
    /// the other seeds of a route whose legs all head for the same curve
    /// ([`Compatible::seed_sharing`]).
    guide_end: Option<std::sync::Arc<[Point]>>,
    area_range: (f64, f64),
    /// Whether the rigid guide was found unusable (the plan reports it,
    /// [`Compatible::has_rigid_guide`]).
    rigid_failed: bool,
}

/// Whether `a` and `b` are the same points bit for bit.
pub(crate) fn same_bits(a: &[Point], b: &[Point]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(p, q)| p.x.to_bits() == q.x.to_bits() && p.y.to_bits() == q.y.to_bits())
}

impl PlanSeed {
    /// The plan's triangulation ([`Compatible::triangles`]).
    pub(crate) fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The plan's target ([`Compatible::target`]).
    pub(crate) fn target(&self) -> &[Point] {
        &self.dst
    }

    /// The plan's fan margin ([`Compatible::fan_margin`]).
    pub(crate) fn fan_margin(&self) -> f64 {
        self.fan_margin
    }

    /// [`Compatible::has_rigid_guide`] of the plan when it was released.
    pub(crate) fn has_rigid_guide(&self) -> bool {
        !self.rigid_failed
    }

    /// Notes what a plan built from this seed found of its rigid guide
    /// (evaluated only where the rigid path is asked for; the same answer
    /// each time it is built).
    pub(crate) fn note_rigid_guide(&mut self, plan: &Compatible) {
        self.rigid_failed |= !plan.has_rigid_guide();
    }

    /// The plan this seed was taken from, built again.
    ///
    /// # Errors
    ///
    /// None for a seed taken from a plan ([`Compatible::seed`]): the plan
    /// was built from the same input by the same steps.
    pub(crate) fn build(&self) -> Result<Compatible, CompatibleError> {
        let tree = DualTree::new(self.src.len(), &self.triangles)?;
        let mut plan = Compatible::on_tree(
            &self.src,
            &self.dst,
            &tree,
            self.root_choice,
            self.fan_margin,
        )?;
        if let Some(end) = &self.guide_end {
            plan = plan.with_guide(end);
        }
        plan.area_range = self.area_range;
        if self.rigid_failed {
            let _ = plan.rigid.set(None);
        }
        Ok(plan)
    }
}

/// The two ends of the polar guide: per vertex, its angle about the
/// source's vertex mean and its distance from it, then the same about the
/// guide end's mean. Angles are unwound along each curve (consecutive
/// vertices differ by less than half a turn), and the end's are shifted by
/// the whole number of turns that moves the vertices least (angle changes
/// weighted by distance from the mean), so a vertex winds the short way
/// round unless the curves wind differently.
#[derive(Clone, Debug)]
struct PolarEnds {
    /// Per vertex: [source angle, source distance, end angle, end distance].
    at: Vec<[f64; 4]>,
}

impl PolarEnds {
    fn new(a: &[Point], b: &[Point], [c0, c1]: [Point; 2]) -> PolarEnds {
        use std::f64::consts::{PI, TAU};
        let unwound = |p: &[Point], c: Point| -> Vec<(f64, f64)> {
            let mut out: Vec<(f64, f64)> = Vec::with_capacity(p.len());
            for &q in p {
                let (d, r) = ((q - c).to_angle(), (q - c).length());
                let angle = match out.last() {
                    None => d,
                    Some(&(prev, _)) => prev + (d - prev + PI).rem_euclid(TAU) - PI,
                };
                out.push((angle, r));
            }
            out
        };
        let (ua, ub) = (unwound(a, c0), unwound(b, c1));
        // The whole turns that move the vertices least: the weighted
        // median of the per-vertex turn counts (cost piecewise linear in
        // the shift), rounded to the nearer of its two neighbours.
        let cost = |k: f64| -> f64 {
            ua.iter()
                .zip(&ub)
                .map(|(&(x, rx), &(y, ry))| (y + k * TAU - x).abs() * (rx + ry))
                .sum()
        };
        let mut counts: Vec<(f64, f64)> = ua
            .iter()
            .zip(&ub)
            .map(|(&(x, rx), &(y, ry))| ((x - y) / TAU, rx + ry))
            .collect();
        counts.sort_by(|p, q| p.0.total_cmp(&q.0));
        let half = counts.iter().map(|c| c.1).sum::<f64>() / 2.0;
        let mut acc = 0.0;
        let mut median = counts.first().map_or(0.0, |c| c.0);
        for &(k, w) in &counts {
            acc += w;
            if acc >= half {
                median = k;
                break;
            }
        }
        let (lo, hi) = (median.floor(), median.ceil());
        let k = if cost(lo) <= cost(hi) { lo } else { hi };
        let at = ua
            .iter()
            .zip(&ub)
            .map(|(&(x, rx), &(y, ry))| [x, rx, y + k * TAU, ry])
            .collect();
        PolarEnds { at }
    }
}

/// Per triangle, the third vertex in base-frame coordinates on the source
/// and on the target, and its rotate-slide plan.
#[derive(Clone, Debug)]
struct BaseFrames {
    local_src: Vec<Point>,
    local_dst: Vec<Point>,
    plans: Vec<RotateSlide>,
}

impl BaseFrames {
    fn new(src: &[Point], dst: &[Point], rooted: &Rooted) -> BaseFrames {
        let m = rooted.third.len();
        let local = |p: &[Point]| -> Vec<Point> {
            (0..m)
                .map(|t| {
                    let [x, y] = rooted.base[t].map(|v| v as usize);
                    to_base_frame(p[x], p[y], p[rooted.third[t] as usize])
                })
                .collect()
        };
        let (local_src, local_dst) = (local(src), local(dst));
        // Rotate-slide pivots: base ends whose edge to the third vertex is a
        // child's base.
        let mut has_child_edge = vec![[false; 2]; m];
        for u in 0..m {
            if let Some(p) = rooted.parent[u] {
                let w = rooted.third[p];
                let [x, y] = rooted.base[p];
                let e = rooted.base[u];
                if e.contains(&w) && e.contains(&x) {
                    has_child_edge[p][0] = true;
                }
                if e.contains(&w) && e.contains(&y) {
                    has_child_edge[p][1] = true;
                }
            }
        }
        let plans = (0..m)
            .map(|t| {
                let mut pivots = Vec::with_capacity(2);
                if has_child_edge[t][0] {
                    pivots.push(Point::ZERO);
                }
                if has_child_edge[t][1] {
                    pivots.push(Point::X);
                }
                RotateSlide::plan(local_src[t], local_dst[t], &pivots)
            })
            .collect();
        BaseFrames {
            local_src,
            local_dst,
            plans,
        }
    }
}

/// The straight path's total area range for ends of areas `a0` and `a1`.
fn straight_area_range(a0: f64, a1: f64) -> (f64, f64) {
    (
        a0.min(a1) * STRAIGHT_AREA_RANGE.0,
        a0.max(a1) * STRAIGHT_AREA_RANGE.1,
    )
}

/// The vertex means of `a` and `b` and the best-fit rotation from `a` to
/// `b` about them.
fn guide_frame(a: &[Point], b: &[Point]) -> ([Point; 2], f64) {
    let mean = |p: &[Point]| p.iter().copied().sum::<Point>() / p.len() as f64;
    let (ma, mb) = (mean(a), mean(b));
    let (mut dot, mut cross) = (0.0, 0.0);
    for (p, q) in a.iter().zip(b) {
        let (u, v) = (*p - ma, *q - mb);
        dot += u.dot(v);
        cross += u.perp_dot(v);
    }
    ([ma, mb], cross.atan2(dot))
}

/// The straight guide from `src` to `end` at `t` in the frame `([c0, c1],
/// turn)` of [`guide_frame`]: `src` and `end` interpolated linearly about
/// their vertex means in a frame turning at a constant rate.
fn linear_guide(
    src: &[Point],
    end: &[Point],
    ([c0, c1], turn): ([Point; 2], f64),
    t: f64,
) -> Vec<Point> {
    let c = c0.lerp(c1, t);
    let spin = Point::from_angle(t * turn);
    let back = Point::from_angle(-turn);
    src.iter()
        .zip(end)
        .map(|(&p, &q)| c + spin.rotate((p - c0) * (1.0 - t) + back.rotate(q - c1) * t))
        .collect()
}

/// The interpolated placement of the root triangle: x(t) = L(t)(p − c_s) +
/// c(t) with L(t) = R(tθ)((1 − t)I + tS), where R(θ)S is the polar
/// decomposition of the affine map from the source root to the target.
#[derive(Clone, Copy, Debug)]
struct RootMotion {
    theta: f64,
    s: [[f64; 2]; 2],
    c_src: Point,
    c_dst: Point,
}

impl RootMotion {
    fn new(src: [Point; 3], dst: [Point; 3]) -> RootMotion {
        let c_src = (src[0] + src[1] + src[2]) / 3.0;
        let c_dst = (dst[0] + dst[1] + dst[2]) / 3.0;
        // L maps (src[1]-src[0], src[2]-src[0]) to the same in dst.
        let (u1, u2) = (src[1] - src[0], src[2] - src[0]);
        let (v1, v2) = (dst[1] - dst[0], dst[2] - dst[0]);
        let det = u1.perp_dot(u2);
        // L = V U^{-1}
        let inv = [[u2.y / det, -u2.x / det], [-u1.y / det, u1.x / det]];
        let l = [
            [
                v1.x * inv[0][0] + v2.x * inv[1][0],
                v1.x * inv[0][1] + v2.x * inv[1][1],
            ],
            [
                v1.y * inv[0][0] + v2.y * inv[1][0],
                v1.y * inv[0][1] + v2.y * inv[1][1],
            ],
        ];
        // Polar decomposition of a 2x2 matrix with positive determinant:
        // the rotation angle is atan2(c - b, a + d).
        let theta = (l[1][0] - l[0][1]).atan2(l[0][0] + l[1][1]);
        let (c, s) = (theta.cos(), theta.sin());
        // S = R^T L
        let sm = [
            [c * l[0][0] + s * l[1][0], c * l[0][1] + s * l[1][1]],
            [-s * l[0][0] + c * l[1][0], -s * l[0][1] + c * l[1][1]],
        ];
        RootMotion {
            theta,
            s: sm,
            c_src,
            c_dst,
        }
    }

    fn place(&self, p: Point, t: f64) -> Point {
        let q = p - self.c_src;
        let m = [
            [(1.0 - t) + t * self.s[0][0], t * self.s[0][1]],
            [t * self.s[1][0], (1.0 - t) + t * self.s[1][1]],
        ];
        let sq = Point::new(m[0][0] * q.x + m[0][1] * q.y, m[1][0] * q.x + m[1][1] * q.y);
        let r = Point::from_angle(t * self.theta).rotate(sq);
        r + self.c_src.lerp(self.c_dst, t)
    }
}

/// Why a compatible morph could not be set up.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CompatibleError {
    /// The two point lists differ in length.
    #[error("the curves have {0} and {1} points; compatible morphing needs equal counts")]
    Counts(usize, usize),
    /// The triangles are not a triangulation of the n-gon.
    #[error(transparent)]
    Tree(#[from] crate::tree::TreeError),
    /// A triangle is not counter-clockwise on one of the curves.
    #[error("triangle {triangle} is not counter-clockwise on the {which} curve")]
    NotCcw {
        /// Index of the triangle.
        triangle: usize,
        /// "source" or "target".
        which: &'static str,
    },
}

impl Compatible {
    /// Prepares the morph from `src` to `dst`, which share the
    /// triangulation `triangles` (corners in cyclic order, counter-clockwise
    /// on both curves).
    ///
    /// # Errors
    ///
    /// [`CompatibleError`] when the counts differ, the triangles are not a
    /// triangulation, or a triangle is not counter-clockwise.
    pub fn new(
        src: &[Point],
        dst: &[Point],
        triangles: &[[u32; 3]],
        root: RootChoice,
        fan_margin: f64,
    ) -> Result<Compatible, CompatibleError> {
        if src.len() != dst.len() {
            return Err(CompatibleError::Counts(src.len(), dst.len()));
        }
        let tree = DualTree::new(src.len(), triangles)?;
        Compatible::on_tree(src, dst, &tree, root.into(), fan_margin)
    }

    /// [`Compatible::new`] with the dual tree of the triangulation already
    /// built (the staged route builds it once per leg and shares it).
    ///
    /// # Errors
    ///
    /// As [`Compatible::new`].
    pub(crate) fn on_tree(
        src: &[Point],
        dst: &[Point],
        tree: &DualTree,
        root: Root,
        fan_margin: f64,
    ) -> Result<Compatible, CompatibleError> {
        if src.len() != dst.len() || src.len() != tree.vertex_count() {
            return Err(CompatibleError::Counts(src.len(), dst.len()));
        }
        let triangles = tree.triangles();
        let root_t = root_triangle(tree, src, root);
        let rooted = tree.rooted(root_t);
        let m = triangles.len();
        let mut ang_src = vec![[0.0; 3]; m];
        let mut ang_dst = vec![[0.0; 3]; m];
        for t in 0..m {
            let [x, y] = rooted.base[t].map(|v| v as usize);
            let w = rooted.third[t] as usize;
            ang_src[t] = corner_angles(src, [x, y, w]).ok_or(CompatibleError::NotCcw {
                triangle: t,
                which: "source",
            })?;
            ang_dst[t] = corner_angles(dst, [x, y, w]).ok_or(CompatibleError::NotCcw {
                triangle: t,
                which: "target",
            })?;
        }
        let rt = triangles[root_t].map(|v| v as usize);
        let root_motion = RootMotion::new(rt.map(|v| src[v]), rt.map(|v| dst[v]));
        let (a_s, _) = area_and_centroid(src, triangles);
        let (a_d, _) = area_and_centroid(dst, triangles);
        let corners: Vec<[usize; 3]> = (0..m)
            .map(|t| {
                let [x, y] = rooted.base[t].map(|v| v as usize);
                [x, y, rooted.third[t] as usize]
            })
            .collect();
        let frame = guide_frame(src, dst);
        Ok(Compatible {
            src: src.to_vec(),
            dst: dst.to_vec(),
            triangles: triangles.to_vec(),
            rooted,
            base_frames: std::sync::OnceLock::new(),
            ang_src,
            ang_dst,
            root: root_motion,
            fan_margin,
            corners,
            guide_end: dst.to_vec(),
            guide_frame: frame,
            target_frame: frame,
            area_range: straight_area_range(a_s, a_d),
            polar: std::sync::OnceLock::new(),
            rigid: std::sync::OnceLock::new(),
            root_choice: root,
        })
    }

    /// Aims the straight path's guide at `end` instead of the target: the
    /// frames then follow the straight line from the source toward `end`,
    /// projected into the valid set of this triangulation with the angle
    /// rule toward the target (which must be valid), and reach the target
    /// only where `end`'s own angles are invalid. The staged route uses it
    /// to head every leg for the other curve while its triangulation still
    /// differs. Other paths ignore it.
    ///
    /// # Panics
    ///
    /// When `end` has another length than the curves (a bug in the caller).
    pub(crate) fn with_guide(mut self, end: &[Point]) -> Compatible {
        assert_eq!(end.len(), self.src.len(), "a guide end of another length");
        self.guide_frame = guide_frame(&self.src, end);
        self.guide_end = end.to_vec();
        self.polar = std::sync::OnceLock::new();
        self
    }

    /// Makes the straight path keep the area range of a whole morph whose
    /// ends have total areas `a0` and `a1` (this plan being one leg of it).
    pub(crate) fn with_area_range(mut self, a0: f64, a1: f64) -> Compatible {
        self.area_range = straight_area_range(a0, a1);
        self
    }

    /// The fan margin the paths keep (see [`Compatible::new`]).
    pub(crate) fn fan_margin(&self) -> f64 {
        self.fan_margin
    }

    /// The shared triangulation.
    pub(crate) fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// The source curve.
    pub(crate) fn source(&self) -> &[Point] {
        &self.src
    }

    /// The target curve.
    pub(crate) fn target(&self) -> &[Point] {
        &self.dst
    }

    /// Vertex positions at `t` along `path`. The ends are snapped: t ≤ 0
    /// gives the source exactly and t ≥ 1 the target.
    pub fn positions(&self, t: f64, path: ThirdVertexPath) -> Vec<Point> {
        self.positions_counted(t, path).0
    }

    /// [`Compatible::positions`] and the number of triangles whose third
    /// vertex the layout had to move by the exact orientation test.
    pub(crate) fn positions_counted(&self, t: f64, path: ThirdVertexPath) -> (Vec<Point>, usize) {
        if t <= 0.0 {
            return (self.src.clone(), 0);
        }
        if t >= 1.0 {
            return (self.dst.clone(), 0);
        }
        match path {
            ThirdVertexPath::Linear | ThirdVertexPath::RotateSlide => (self.propagate(t, path), 0),
            ThirdVertexPath::Angle => {
                let ang: Vec<[f64; 3]> = (0..self.triangles.len())
                    .map(|i| lerp3(self.ang_src[i], self.ang_dst[i], t))
                    .collect();
                self.fitted(&layout::factors(&ang), &self.target_guide(t))
            }
            ThirdVertexPath::Hybrid => {
                let ang = self.hybrid_angles(t);
                self.fitted(&layout::factors(&ang), &self.target_guide(t))
            }
            ThirdVertexPath::Rigid => {
                let guide = self.rigid_guide(t).unwrap_or_else(|| self.target_guide(t));
                let factors = self.projected_factors(t, &guide);
                self.fitted(&factors, &guide)
            }
            ThirdVertexPath::Straight | ThirdVertexPath::Polar => {
                let guide = self.guide(t);
                let polar = (path == ThirdVertexPath::Polar).then(|| self.polar_guide(t));
                let shape = polar.as_deref().unwrap_or(&guide);
                let (ang, kept) = self.straight_angles(t, shape);
                // A triangle that keeps the guide's shape takes its factor
                // from the guide's points (no trigonometry; the layout then
                // reproduces the guide there up to rounding).
                let factors: Vec<Point> = (0..ang.len())
                    .map(|i| {
                        if kept[i] {
                            let [x, y, w] = self.corners[i];
                            to_base_frame(shape[x], shape[y], shape[w])
                        } else {
                            layout::factor(ang[i])
                        }
                    })
                    .collect();
                self.fitted(&factors, &guide)
            }
        }
    }

    /// Lays out `factors` placed by the global fit (docs/design.md §6,
    /// "Placement"):
    /// the least-squares similarity onto the straight guide `guide` (every
    /// vertex counts, not only the root), kept to the area range by
    /// [`Compatible::keep_area`].
    fn fitted(&self, factors: &[Point], guide: &[Point]) -> (Vec<Point>, usize) {
        layout::lay_out_fitted(&self.rooted, factors, |unit| {
            self.keep_area(layout::fit_similarity(unit, guide), unit, guide)
        })
    }

    /// The straight guide at `t`: the end shapes interpolated linearly in a
    /// frame that turns by the best-fit rotation between them (so a shape
    /// and its turned copy rotate instead of collapsing through the
    /// centre). With no rotation between the ends this is the linear
    /// morph. It heads for the guide's end ([`Compatible::with_guide`]).
    fn guide(&self, t: f64) -> Vec<Point> {
        linear_guide(&self.src, &self.guide_end, self.guide_frame, t)
    }

    /// The straight guide toward the target itself, whatever the guide's
    /// end: it places the paths that reach the target's own shape
    /// (`hybrid`, `angle`), so that they arrive where the target is.
    fn target_guide(&self, t: f64) -> Vec<Point> {
        linear_guide(&self.src, &self.dst, self.target_frame, t)
    }

    /// The as-rigid-as-possible guide at `t` (the `rigid` path): every
    /// triangle's rotation and stretch toward the target interpolated
    /// separately and the positions fitted to them ([`RigidGuide`]). It
    /// heads for the target even on a leg whose straight guide heads
    /// elsewhere ([`Compatible::with_guide`]): the target is valid under
    /// this triangulation, where the other curve may not be. `None` where
    /// the system cannot be factored, or its solve cannot be made accurate
    /// ([`RigidGuide::at_checked`]) at the ends or half way: its rounding
    /// would then change from one t to the next and shake every frame.
    fn rigid_guide(&self, t: f64) -> Option<Vec<Point>> {
        let guide = self.rigid.get_or_init(|| {
            let ends: Vec<[Point; 2]> = self
                .triangles
                .iter()
                .map(|tri| {
                    let [a, b, c] = tri.map(|v| self.dst[v as usize]);
                    [b - a, c - a]
                })
                .collect();
            let guide = RigidGuide::new(
                &self.src,
                &self.triangles,
                &ends,
                &self.rooted,
                self.target_frame.0,
            )?;
            // The least-squares solve meets the ends only up to its
            // rounding, which grows with the conditioning of thin
            // triangles; what it misses at each end is spread linearly
            // over t, so that the guide is the source at 0 and the target
            // at 1 exactly as the path is (else the path would jump onto
            // its snapped ends).
            let (start, a) = guide.at_checked(0.0);
            let (end, b) = guide.at_checked(1.0);
            // (Half way only where the solve is refined: elsewhere it is
            // accurate at every t.)
            if !(a && b && (!guide.refines() || guide.at_checked(0.5).1)) {
                return None;
            }
            let miss = |at: Vec<Point>, end: &[Point]| -> Vec<Point> {
                at.iter().zip(end).map(|(g, e)| *e - *g).collect()
            };
            let residual = [miss(start, &self.src), miss(end, &self.dst)];
            Some((guide, residual))
        });
        guide.as_ref().map(|(g, [r0, r1])| {
            let mut p = g.at(t);
            for ((p, a), b) in p.iter_mut().zip(r0).zip(r1) {
                *p += *a * (1.0 - t) + *b * t;
            }
            p
        })
    }

    /// What this plan is built from ([`PlanSeed::build`] builds it
    /// again).
    #[cfg(test)]
    pub(crate) fn seed(&self) -> PlanSeed {
        self.seed_sharing(&[])
    }

    /// [`Compatible::seed`], holding one of `held` instead of a copy of
    /// the source or of the straight guide's end wherever it is the same
    /// points: a leg's plan starts at the leg's first key, and the legs of
    /// one side of a staged route toward its intermediates are all guided
    /// at the other curve; a copy of each per leg is half a seed.
    pub(crate) fn seed_sharing(&self, held: &[&std::sync::Arc<[Point]>]) -> PlanSeed {
        let share = |p: &[Point]| match held.iter().find(|h| same_bits(h, p)) {
            Some(h) => std::sync::Arc::clone(h),
            None => std::sync::Arc::from(p),
        };
        let guide_end = (!same_bits(&self.guide_end, &self.dst)).then(|| share(&self.guide_end));
        PlanSeed {
            src: share(&self.src),
            dst: self.dst.clone(),
            triangles: self.triangles.clone(),
            root_choice: self.root_choice,
            fan_margin: self.fan_margin,
            guide_end,
            area_range: self.area_range,
            rigid_failed: !self.has_rigid_guide(),
        }
    }

    /// False where the `rigid` path, once evaluated, was guided by the
    /// straight guide: the as-rigid-as-possible one could not be factored
    /// or solved accurately ([`Compatible::rigid_guide`]).
    pub(crate) fn has_rigid_guide(&self) -> bool {
        !matches!(self.rigid.get(), Some(None))
    }

    /// The layout factors of the guide `guide` at `t`, projected into the
    /// valid set V(T) (docs/design.md §6): each triangle's third vertex,
    /// in its base frame, is moved to the nearest point where all three of
    /// its angles are at least its floor (half its smallest angle in the
    /// angle rule at t, at most [`STRAIGHT_MIN_ANGLE`]); then every vertex
    /// whose fan would pass 2π − min(ε, (2π − S_c)/2) blends its own
    /// triangles toward the angle rule, and whatever is left is settled by
    /// the global closed form of the hybrid path. The nearest-point step is
    /// a projection onto a convex set, so it never moves a vertex faster
    /// than the guide moves it: the result is as continuous as the guide.
    /// Where the guide is valid with these margins its own factors are
    /// returned.
    fn projected_factors(&self, t: f64, guide: &[Point]) -> Vec<Point> {
        let m = self.triangles.len();
        let rule: Vec<[f64; 3]> = (0..m)
            .map(|i| lerp3(self.ang_src[i], self.ang_dst[i], t))
            .collect();
        let mut factors = Vec::with_capacity(m);
        let mut ang = Vec::with_capacity(m);
        // Angles are estimated ([`estimate_angles`]) and measured only
        // where a fan could reach its cap, so the result is what measuring
        // every one gives.
        let mut rough = vec![false; m];
        for (i, c) in rule.iter().enumerate() {
            let [x, y, w] = self.corners[i];
            let floor = floor_of(*c);
            // A base of length 0 gives no finite coordinates.
            let z = to_base_frame(guide[x], guide[y], guide[w]);
            let z = if z.is_finite() {
                project_to_floor(z, floor)
            } else {
                layout::factor(*c)
            };
            factors.push(z);
            match estimate_angles(z.y, z.x, 1.0 - z.x) {
                Some(est) if z.y >= 0.0 => {
                    rough[i] = true;
                    ang.push(est);
                }
                _ => ang.push(factor_angles(z)),
            }
        }
        let n = self.src.len();
        let s_c = layout::fan_sums(n, &self.corners, &rule);
        let cap = |v: usize| TAU - self.fan_margin.min((TAU - s_c[v]) / 2.0);
        let measured: Vec<Point> = factors.clone();
        let measure = |i: usize| factor_angles(measured[i]);
        // Local: each over-full vertex blends its own fan.
        let s = settle_fans(&self.corners, n, &mut ang, &mut rough, &cap, &measure);
        let local = self.local_blends(&s, &s_c, cap);
        for (i, a) in ang.iter_mut().enumerate() {
            if local[i] > 0.0 {
                *a = lerp3(*a, rule[i], local[i]);
                factors[i] = layout::factor(*a);
            }
        }
        // Global: whatever the local step could not settle.
        let s = settle_fans(&self.corners, n, &mut ang, &mut rough, &cap, &measure);
        let lambda = layout::fan_blend(&s, &s_c, cap);
        if lambda > 0.0 {
            for (i, ((a, c), f)) in ang
                .iter_mut()
                .zip(&rule)
                .zip(factors.iter_mut())
                .enumerate()
            {
                if rough[i] {
                    *a = measure(i);
                }
                *a = lerp3(*a, *c, lambda);
                *f = layout::factor(*a);
            }
        }
        factors
    }

    /// The local step of the fan blend (docs/design.md §6): per triangle,
    /// how far its angles move toward the angle rule so that each vertex
    /// whose fan sum `s` passes its cap comes back to it, the largest such
    /// amount over the triangle's corners (`s_c` the angle rule's sums).
    fn local_blends(&self, s: &[f64], s_c: &[f64], cap: impl Fn(usize) -> f64) -> Vec<f64> {
        let local: Vec<f64> = (0..s.len())
            .map(|v| {
                let c = cap(v);
                if s[v] > c && s[v] > s_c[v] {
                    ((s[v] - c) / (s[v] - s_c[v])).clamp(0.0, 1.0)
                } else {
                    0.0
                }
            })
            .collect();
        self.corners
            .iter()
            .map(|c| c.iter().map(|&v| local[v]).fold(0.0, f64::max))
            .collect()
    }

    /// The polar guide at `t` (the `polar` path): every vertex's angle
    /// about the vertex mean and its distance from it interpolated
    /// linearly between the source and the guide's end, about the mean
    /// interpolated linearly ([`PolarEnds`]).
    fn polar_guide(&self, t: f64) -> Vec<Point> {
        let ends = self
            .polar
            .get_or_init(|| PolarEnds::new(&self.src, &self.guide_end, self.guide_frame.0));
        let [c0, c1] = self.guide_frame.0;
        let c = c0.lerp(c1, t);
        ends.at
            .iter()
            .map(|&[a0, r0, a1, r1]| {
                c + Point::from_angle(a0 + (a1 - a0) * t) * (r0 + (r1 - r0) * t)
            })
            .collect()
    }

    /// The angles of the guide where they are valid, projected into the
    /// valid set where they are not (docs/design.md §7b): a triangle that is
    /// clockwise or thinner than the floor in the guide is blended toward
    /// the angle rule by an amount that grows continuously from 0 (at the
    /// floor) to 1 (inverted by at least the floor); then vertices whose fan
    /// would pass 2π − min(ε, (2π − S_c)/2) blend their triangles toward
    /// the angle rule, locally first and then, if still needed, all
    /// together (the closed form of the hybrid path). Every step keeps the
    /// angles positive with triangle sums π, so the result is valid; it is
    /// continuous in t, and where the guide is valid with margins it is the
    /// guide's own angle vector.
    fn straight_angles(&self, t: f64, guide: &[Point]) -> (Vec<[f64; 3]>, Vec<bool>) {
        let m = self.triangles.len();
        let rule: Vec<[f64; 3]> = (0..m)
            .map(|i| lerp3(self.ang_src[i], self.ang_dst[i], t))
            .collect();
        // The guide's angles of a triangle: two by atan2, the third as the
        // rest of π.
        let measure = |i: usize| -> [f64; 3] {
            let [x, y, w] = self.corners[i];
            let (px, py, pw) = (guide[x], guide[y], guide[w]);
            let (e, f) = (py - px, pw - px);
            let cross = e.perp_dot(f).abs();
            let ax = cross.atan2(e.dot(f));
            let ay = cross.atan2((px - py).dot(pw - py));
            [ax, ay, (std::f64::consts::PI - ax - ay).max(0.0)]
        };
        // Per triangle: the angles, whether they are the guide's own, and
        // whether they are only estimated: a triangle that is clearly kept
        // needs its angles only for fan sums, and only where the estimate
        // cannot tell that the fan stays below its cap are they measured
        // (below), so the result is what measuring every one gives.
        let mut kept = vec![false; m];
        let mut rough = vec![false; m];
        let mut ang: Vec<[f64; 3]> = (0..m)
            .map(|i| {
                let [x, y, w] = self.corners[i];
                let c = rule[i];
                let floor = STRAIGHT_MIN_ANGLE.min(0.5 * c[0].min(c[1]).min(c[2]));
                let (px, py, pw) = (guide[x], guide[y], guide[w]);
                if px == py || px == pw || py == pw || floor <= 0.0 {
                    return c;
                }
                let orientation = crate::geom::orient(px, py, pw);
                if orientation.is_ccw() {
                    let (e, f) = (py - px, pw - px);
                    let cross = e.perp_dot(f).abs();
                    if let Some(est) = estimate_angles(cross, e.dot(f), (px - py).dot(pw - py)) {
                        if est[0].min(est[1]).min(est[2]) - ESTIMATE_SLACK >= floor {
                            kept[i] = true;
                            rough[i] = true;
                            return est;
                        }
                    }
                }
                let measured = measure(i);
                let sign = f64::from(orientation.signum());
                let sigma = sign * measured[0].min(measured[1]).min(measured[2]);
                let mu = ((floor - sigma) / (2.0 * floor)).clamp(0.0, 1.0);
                if mu <= 0.0 {
                    kept[i] = true;
                    return measured;
                }
                let toward_rule = if mu >= 1.0 { c } else { lerp3(measured, c, mu) };
                // Where the angle rule itself is thin (its smallest angle
                // below the full floor), its angles decide a thin
                // triangle's third vertex along its base by their ratio,
                // which moves within a span of t of the order of the
                // angle, and the guide's measured angles there are
                // rounding: the nearest point of the floor set keeps the
                // third vertex where the guide has it along the base
                // instead (continuous in the guide, blind to that
                // rounding). The two are blended by how thin the rule is.
                let beta =
                    ((2.0 * floor - RULE_THIN.0) / (RULE_THIN.1 - RULE_THIN.0)).clamp(0.0, 1.0);
                if beta >= 1.0 {
                    return toward_rule;
                }
                let z = to_base_frame(px, py, pw);
                if !z.is_finite() {
                    return toward_rule;
                }
                let projected = factor_angles(project_to_floor(z, floor));
                if beta <= 0.0 {
                    projected
                } else {
                    lerp3(projected, toward_rule, beta)
                }
            })
            .collect();
        let n = self.src.len();
        let s_c = layout::fan_sums(n, &self.corners, &rule);
        let cap = |v: usize| TAU - self.fan_margin.min((TAU - s_c[v]) / 2.0);
        let settle = |ang: &mut [[f64; 3]], rough: &mut [bool]| {
            settle_fans(&self.corners, n, ang, rough, &cap, &measure)
        };
        // Local: each over-full vertex blends its own fan.
        let s = settle(&mut ang, &mut rough);
        let local = self.local_blends(&s, &s_c, cap);
        for (i, a) in ang.iter_mut().enumerate() {
            if local[i] > 0.0 {
                *a = lerp3(*a, rule[i], local[i]);
                kept[i] = false;
            }
        }
        // Global: whatever the local step could not settle.
        let s = settle(&mut ang, &mut rough);
        let lambda = layout::fan_blend(&s, &s_c, cap);
        if lambda > 0.0 {
            for (i, (a, c)) in ang.iter_mut().zip(&rule).enumerate() {
                if rough[i] {
                    *a = measure(i);
                }
                *a = lerp3(*a, *c, lambda);
            }
            kept.iter_mut().for_each(|k| *k = false);
        }
        (ang, kept)
    }

    /// The fitted paths never collapse or balloon the shape: where the
    /// fitted layout's total area leaves the endpoints' range widened by
    /// [`STRAIGHT_AREA_RANGE`], it is scaled about the guide's vertex mean
    /// back to the nearest end of that range (a no-op where the linear
    /// morph stays in range, so linear stays linear there).
    fn keep_area(
        &self,
        fit: layout::Similarity,
        unit: &[Point],
        guide: &[Point],
    ) -> layout::Similarity {
        let (area_unit, _) = area_and_centroid(unit, &self.triangles);
        let area = area_unit * fit.a.length_squared();
        let (lo, hi) = self.area_range;
        if area.is_nan() || area <= 0.0 || (lo..=hi).contains(&area) {
            return fit;
        }
        let k = (area.clamp(lo, hi) / area).sqrt();
        let n = guide.len() as f64;
        let (cu, cg) = (
            unit.iter().copied().sum::<Point>() / n,
            guide.iter().copied().sum::<Point>() / n,
        );
        let a = fit.a * k;
        layout::Similarity {
            a,
            b: cg - a.rotate(cu),
        }
    }

    /// The base-frame data, made on first use.
    fn base_frames(&self) -> &BaseFrames {
        self.base_frames
            .get_or_init(|| BaseFrames::new(&self.src, &self.dst, &self.rooted))
    }

    fn third_local(&self, tri: usize, t: f64, path: ThirdVertexPath) -> Point {
        let b = self.base_frames();
        match path {
            ThirdVertexPath::RotateSlide => b.plans[tri].at(t),
            _ => b.local_src[tri].lerp(b.local_dst[tri], t),
        }
    }

    /// Direct propagation (linear and rotate-slide paths).
    fn propagate(&self, t: f64, path: ThirdVertexPath) -> Vec<Point> {
        let mut pos = vec![Point::ZERO; self.src.len()];
        let root = self.rooted.root;
        for v in self.triangles[root] {
            pos[v as usize] = self.root.place(self.src[v as usize], t);
        }
        for &tri in &self.rooted.order {
            if tri == root {
                continue;
            }
            let [x, y] = self.rooted.base[tri].map(|v| v as usize);
            let w = self.rooted.third[tri] as usize;
            pos[w] = from_base_frame(pos[x], pos[y], self.third_local(tri, t, path));
        }
        pos
    }

    /// Angles of the rotate-slide frame blended toward the angle rule just
    /// enough that every vertex fan stays at most 2π − min(ε, (2π − S_c)/2).
    fn hybrid_angles(&self, t: f64) -> Vec<[f64; 3]> {
        let m = self.triangles.len();
        let ang_c: Vec<[f64; 3]> = (0..m)
            .map(|i| lerp3(self.ang_src[i], self.ang_dst[i], t))
            .collect();
        // Root: angles of the interpolated affine placement.
        let root = self.rooted.root;
        let [x, y] = self.rooted.base[root].map(|v| v as usize);
        let w = self.rooted.third[root] as usize;
        let root_local = to_base_frame(
            self.root.place(self.src[x], t),
            self.root.place(self.src[y], t),
            self.root.place(self.src[w], t),
        );
        let plans = &self.base_frames().plans;
        let ang_b: Vec<[f64; 3]> = (0..m)
            .map(|i| {
                let c = if i == root {
                    root_local
                } else {
                    plans[i].at(t)
                };
                base_frame_angles(c).unwrap_or(ang_c[i])
            })
            .collect();
        let n = self.src.len();
        let s_b = layout::fan_sums(n, &self.corners, &ang_b);
        let s_c = layout::fan_sums(n, &self.corners, &ang_c);
        let lambda = layout::fan_blend(&s_b, &s_c, |v| {
            TAU - self.fan_margin.min((TAU - s_c[v]) / 2.0)
        });
        (0..m).map(|i| lerp3(ang_b[i], ang_c[i], lambda)).collect()
    }
}

/// The floor of a triangle whose angles in the angle rule are `rule`:
/// half the smallest of them, at most [`STRAIGHT_MIN_ANGLE`].
fn floor_of(rule: [f64; 3]) -> f64 {
    STRAIGHT_MIN_ANGLE.min(0.5 * rule[0].min(rule[1]).min(rule[2]))
}

/// The angles (base start, base end, third) of the triangle whose third
/// vertex has base-frame coordinates `z` (base from 0 to 1), for `z` above
/// the base.
fn factor_angles(z: Point) -> [f64; 3] {
    let ax = z.y.atan2(z.x);
    let ay = z.y.atan2(1.0 - z.x);
    [ax, ay, (std::f64::consts::PI - ax - ay).max(0.0)]
}

/// The nearest point to `z` (a third vertex in base-frame coordinates, the
/// base from 0 to 1) at which all three angles of the triangle are at least
/// `floor` (0 < floor < π/3). That set is convex: the wedge above the two
/// lines from the base ends at angle `floor`, cut by the disc of the
/// circle through both base ends that sees the base at angle `floor`. So
/// the nearest point is unique and moves no faster than `z`.
fn project_to_floor(z: Point, floor: f64) -> Point {
    if floor.is_nan() || floor <= 0.0 {
        return z;
    }
    // Most triangles' floor is the default (their rule's angles are not
    // thin): its cosine and sine are taken once.
    static DEFAULT: std::sync::LazyLock<(f64, f64)> =
        std::sync::LazyLock::new(|| (STRAIGHT_MIN_ANGLE.cos(), STRAIGHT_MIN_ANGLE.sin()));
    let (c, s) = if floor == STRAIGHT_MIN_ANGLE {
        *DEFAULT
    } else {
        (floor.cos(), floor.sin())
    };
    let centre = Point::new(0.5, 0.5 * c / s);
    let radius = 0.5 / s;
    let left = c * z.y - s * z.x >= 0.0;
    let right = c * z.y + s * (z.x - 1.0) >= 0.0;
    let inside = (z - centre).length_squared() <= radius * radius;
    if left && right && inside {
        return z;
    }
    // The boundary: two segments from the wedge's apex to where its sides
    // meet the circle, and the arc between those points.
    let apex = Point::new(0.5, 0.5 * s / c);
    let q1 = Point::new(c, s) * (2.0 * c);
    let q2 = Point::new(1.0, 0.0) + Point::new(-c, s) * (2.0 * c);
    let on_segment = |a: Point, b: Point| -> Point {
        let d = b - a;
        let u = ((z - a).dot(d) / d.length_squared()).clamp(0.0, 1.0);
        a + d * u
    };
    let mut best = on_segment(apex, q1);
    let other = on_segment(apex, q2);
    if (other - z).length_squared() < (best - z).length_squared() {
        best = other;
    }
    // The arc from q1 over the top to q2 (counter-clockwise from q2).
    let r = z - centre;
    let arc = if r.length_squared() > 0.0 {
        let a2 = (q2 - centre).to_angle();
        let a1 = (q1 - centre).to_angle();
        let a = r.to_angle();
        // q1 (on the side from the base's start) lies right of the centre
        // and q2 left: the upper arc runs from a1 over the top to a2
        // counter-clockwise.
        let span = (a2 - a1).rem_euclid(TAU);
        let at = (a - a1).rem_euclid(TAU);
        if at <= span {
            Some(centre + Point::from_angle(a) * radius)
        } else {
            None
        }
    } else {
        None
    };
    if let Some(p) = arc
        && (p - z).length_squared() < (best - z).length_squared()
    {
        best = p;
    }
    best
}

/// Largest error of [`estimate_atan`] (radians), with room to spare: the
/// polynomial of Abramowitz & Stegun 4.4.49 is within 1e-5.
const ATAN_ERROR: f64 = 2e-5;

/// Fan sums of the angles `ang` at the `n` vertices, exact (as if every
/// triangle were measured with `measure`) at every vertex whose fan could
/// reach its `cap`; elsewhere they are below it. Triangles marked `rough`
/// hold estimates ([`estimate_angles`]); those at a vertex that could reach
/// its cap are measured and unmarked.
fn settle_fans(
    corners: &[[usize; 3]],
    n: usize,
    ang: &mut [[f64; 3]],
    rough: &mut [bool],
    cap: &impl Fn(usize) -> f64,
    measure: &impl Fn(usize) -> [f64; 3],
) -> Vec<f64> {
    let s = layout::fan_sums(n, corners, ang);
    let mut slack = vec![0.0; n];
    for (i, c) in corners.iter().enumerate() {
        if rough[i] {
            c.iter().for_each(|&v| slack[v] += ESTIMATE_SLACK);
        }
    }
    let unsure: Vec<bool> = (0..n)
        .map(|v| slack[v] > 0.0 && (s[v] + slack[v] >= cap(v) || s[v].is_nan()))
        .collect();
    let mut changed = false;
    for (i, c) in corners.iter().enumerate() {
        if rough[i] && c.iter().any(|&v| unsure[v]) {
            ang[i] = measure(i);
            rough[i] = false;
            changed = true;
        }
    }
    if changed {
        layout::fan_sums(n, corners, ang)
    } else {
        s
    }
}

/// Largest error of one corner of [`estimate_angles`]: the third angle, π
/// less the other two, carries both their errors.
const ESTIMATE_SLACK: f64 = 3.0 * ATAN_ERROR;

/// arctan(z) for z ∈ [0, 1] within [`ATAN_ERROR`] (Abramowitz & Stegun
/// 4.4.49).
fn estimate_atan(z: f64) -> f64 {
    let z2 = z * z;
    z * (0.999_866 + z2 * (-0.330_299_5 + z2 * (0.180_141 + z2 * (-0.085_133 + z2 * 0.020_835_1))))
}

/// The angle atan2(`y`, `x`) for `y` ≥ 0, within [`ATAN_ERROR`]; `None`
/// where the inputs are not finite or both zero.
fn estimate_angle(y: f64, x: f64) -> Option<f64> {
    let ax = x.abs();
    if !(y.is_finite() && x.is_finite()) || (y == 0.0 && ax == 0.0) {
        return None;
    }
    let a = if ax >= y {
        estimate_atan(y / ax)
    } else {
        std::f64::consts::FRAC_PI_2 - estimate_atan(ax / y)
    };
    Some(if x < 0.0 { std::f64::consts::PI - a } else { a })
}

/// Estimates of a triangle's angles from `cross` = |e × f| and the dot
/// products at its first two corners, each within [`ESTIMATE_SLACK`].
fn estimate_angles(cross: f64, dot_x: f64, dot_y: f64) -> Option<[f64; 3]> {
    let ax = estimate_angle(cross, dot_x)?;
    let ay = estimate_angle(cross, dot_y)?;
    Some([ax, ay, (std::f64::consts::PI - ax - ay).max(0.0)])
}

/// Angles at `x`, `y`, `w` of a triangle that the exact predicate says is
/// counter-clockwise, measured from the points themselves (base-frame
/// coordinates can round a very thin triangle to zero height). Angles that
/// round to zero are lifted to a tiny positive value and the triple is
/// rescaled to sum π; `None` when the triangle is not strictly CCW.
fn corner_angles(p: &[Point], [x, y, w]: [usize; 3]) -> Option<[f64; 3]> {
    let (px, py, pw) = (p[x], p[y], p[w]);
    // One cross product for all three corners, from the exact predicate's
    // adaptive determinant (accurate where the floating-point one cancels;
    // its sign is the exact orientation): a thin triangle's small angles
    // then keep their true ratio, which fixes where its third vertex lies
    // along its base.
    let coord = |q: Point| robust::Coord { x: q.x, y: q.y };
    let cross = robust::orient2d(coord(px), coord(py), coord(pw));
    if cross.is_nan() || cross <= 0.0 {
        return None;
    }
    let at = |a: Point, b: Point, c: Point| cross.atan2((b - a).dot(c - a));
    let a = [at(px, py, pw), at(py, pw, px), at(pw, px, py)];
    let s = a[0] + a[1] + a[2];
    Some(a.map(|v| v * std::f64::consts::PI / s))
}

/// Total area of the triangles (overlaps counted with multiplicity) and
/// their area centroid; coordinates are shifted to the first point to
/// reduce cancellation.
pub fn area_and_centroid(points: &[Point], triangles: &[[u32; 3]]) -> (f64, Point) {
    let o = points.first().copied().unwrap_or(Point::ZERO);
    let (mut area, mut moment) = (0.0, Point::ZERO);
    for t in triangles {
        let [a, b, c] = t.map(|v| points[v as usize] - o);
        let ar = 0.5 * (b - a).perp_dot(c - a);
        area += ar;
        moment += (a + b + c) / 3.0 * ar;
    }
    if area == 0.0 {
        return (0.0, o);
    }
    (area, o + moment / area)
}

/// Lays out a triangulated n-gon from its triangle angles, given per
/// triangle in the order of its corners. The result is unique up to a
/// similarity; here the first triangle's first edge runs from (0, 0) to
/// (1, 0).
///
/// When the angles are positive, each triangle's sum to π and every
/// vertex's fan sum is below 2π, the result is an immersion (docs/design.md
/// §6, the `angle` path).
///
/// # Errors
///
/// [`crate::tree::TreeError`] when `triangles` is not a triangulation of
/// the n-gon.
pub fn lay_out(
    n: usize,
    triangles: &[[u32; 3]],
    angles: &[[f64; 3]],
) -> Result<Vec<Point>, crate::tree::TreeError> {
    let tree = DualTree::new(n, triangles)?;
    Ok(lay_out_rooted(&tree.rooted(0), triangles, angles))
}

/// [`lay_out`] from a given rooting of the dual tree (a root near the
/// tree's centre keeps the propagation depth, and so the rounding, small).
pub(crate) fn lay_out_rooted(
    rooted: &Rooted,
    triangles: &[[u32; 3]],
    angles: &[[f64; 3]],
) -> Vec<Point> {
    let ordered: Vec<[f64; 3]> = (0..triangles.len())
        .map(|tri| {
            let [x, y] = rooted.base[tri];
            [x, y, rooted.third[tri]].map(|v| {
                let k = triangles[tri].iter().position(|&c| c == v).unwrap_or(0);
                angles[tri][k]
            })
        })
        .collect();
    layout::place(rooted, &layout::factors(&ordered), Point::ZERO, Point::X).0
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::morph::{Frame, MorphError};
    use std::f64::consts::PI;

    /// The angle rule keeps a thin triangle's third vertex where it is
    /// along its base: its small angles keep their true ratio however thin
    /// it is (no floor on single angles, no cross product lost to
    /// cancellation), so laying the angles out gives the triangle back.
    #[test]
    fn corner_angles_lay_out_thin_triangles_where_they_are() {
        let mut rng = testkit::Rng::xorshift(0x51_1ce5);
        let mut checked = 0;
        for _ in 0..2000 {
            let x = Point::new(rng.range(-300.0, 300.0), rng.range(-300.0, 300.0));
            let e = Point::from_angle(rng.range(0.0, TAU)) * rng.range(0.5, 50.0);
            let along = rng.range(0.05, 0.95);
            // Heights from 10⁻¹⁶ to 10⁻² of the base, as rounding leaves them.
            let h = 10f64.powf(rng.range(-16.0, -2.0));
            let w = x + e * along + e.perp() * h;
            let p = [x, x + e, w];
            let Some(ang) = corner_angles(&p, [0, 1, 2]) else {
                continue; // rounding put w on the line or below it
            };
            assert!(ang.iter().all(|&a| a > 0.0), "{ang:?}");
            let z = layout::factor(ang);
            let (ex, fx) = (p[1] - p[0], p[2] - p[0]);
            let truth = Point::new(ex.dot(fx), ex.perp_dot(fx)) / ex.length_squared();
            assert!(
                (z.x - truth.x).abs() < 1e-9,
                "height {h}: laid out at {} along the base, the triangle has it at {}",
                z.x,
                truth.x
            );
            checked += 1;
        }
        assert!(checked > 1500, "{checked}");
    }

    #[test]
    fn angle_estimates_stay_within_their_bound() {
        let mut worst: f64 = 0.0;
        for i in 0..=200_000 {
            let phi = std::f64::consts::PI * f64::from(i) / 200_000.0;
            for r in [1e-9, 1.0, 3e7] {
                let (y, x) = ((phi.sin() * r).abs(), phi.cos() * r);
                let est = estimate_angle(y, x).unwrap();
                worst = worst.max((est - y.atan2(x)).abs());
            }
        }
        assert!(worst <= 0.6 * ATAN_ERROR, "{worst}");
        assert_eq!(estimate_angle(0.0, 0.0), None);
        assert_eq!(estimate_angle(f64::NAN, 1.0), None);
    }

    /// The test kit's xorshift64 stream ([`testkit::Rng::xorshift`]) as
    /// the morph tests call it: `Rng(seed)`, and `next()` uniform in
    /// [0, 1).
    pub(crate) struct Rng(pub(crate) u64);
    impl Rng {
        pub(crate) fn next(&mut self) -> f64 {
            testkit::rng::unit_from_bits(testkit::rng::xorshift64(&mut self.0))
        }
    }

    /// A random triangulation of an n-gon (corners in cyclic order).
    pub(crate) fn random_triangulation(n: u32, rng: &mut Rng) -> Vec<[u32; 3]> {
        fn split(i: u32, j: u32, rng: &mut Rng, out: &mut Vec<[u32; 3]>) {
            if j - i < 2 {
                return;
            }
            let k = i + 1 + ((rng.next() * f64::from(j - i - 1)) as u32).min(j - i - 2);
            out.push([i, k, j]);
            split(i, k, rng, out);
            split(k, j, rng, out);
        }
        let mut out = Vec::new();
        split(0, n - 1, rng, &mut out);
        out
    }

    /// Angles of the regular n-gon under `triangles` (a convex disk).
    fn disk_angles(n: usize, triangles: &[[u32; 3]]) -> Vec<[f64; 3]> {
        let pts: Vec<Point> = (0..n)
            .map(|i| Point::from_angle(TAU * i as f64 / n as f64))
            .collect();
        triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| pts[v as usize]);
                crate::geom::polygon::triangle_angles(a, b, c)
            })
            .collect()
    }

    /// A random triangulated polygon: `min + ⌊u·span⌋` vertices (u
    /// uniform in [0, 1)) and a random triangulation of them.
    pub(crate) fn random_polygon(rng: &mut Rng, min: usize, span: f64) -> (usize, Vec<[u32; 3]>) {
        let n = min + (rng.next() * span) as usize;
        (n, random_triangulation(n as u32, rng))
    }

    /// A random compatible pair: a [`random_polygon`] and two random
    /// immersed disks under its triangulation (curl 3).
    pub(crate) fn random_pair(
        rng: &mut Rng,
        min: usize,
        span: f64,
    ) -> (usize, Vec<[u32; 3]>, Vec<Point>, Vec<Point>) {
        random_curled_pair(rng, min, span, 3.0)
    }

    /// [`random_pair`] with the disks' `curl`.
    fn random_curled_pair(
        rng: &mut Rng,
        min: usize,
        span: f64,
        curl: f64,
    ) -> (usize, Vec<[u32; 3]>, Vec<Point>, Vec<Point>) {
        let (n, tris) = random_polygon(rng, min, span);
        let a = random_immersed_disk(n, &tris, curl, rng);
        let b = random_immersed_disk(n, &tris, curl, rng);
        (n, tris, a, b)
    }

    /// A random immersed disk: random angles blended toward the disk's
    /// just enough to keep every fan sum below 2π − margin.
    pub(crate) fn random_immersed_disk(
        n: usize,
        triangles: &[[u32; 3]],
        curl: f64,
        rng: &mut Rng,
    ) -> Vec<Point> {
        let disk = disk_angles(n, triangles);
        // Random factors, and a bias that widens the angles at the vertices
        // of one side of the polygon so that the disk curls (and often
        // overlaps itself) once the fans are capped below 2π.
        let side = (rng.next() * n as f64) as usize;
        let rnd: Vec<[f64; 3]> = disk
            .iter()
            .zip(triangles)
            .map(|(d, t)| {
                let f = [0, 1, 2].map(|k| {
                    let on_side = (t[k] as usize + n - side) % n < n / 2;
                    let bias = if on_side { 1.0 + curl } else { 1.0 };
                    d[k] * bias * (1.0 + curl * (rng.next() - 0.3)).max(0.05)
                });
                let s = f[0] + f[1] + f[2];
                f.map(|x| x * PI / s)
            })
            .collect();
        let corners: Vec<[usize; 3]> = triangles.iter().map(|t| t.map(|v| v as usize)).collect();
        let (sr, sd) = (
            layout::fan_sums(n, &corners, &rnd),
            layout::fan_sums(n, &corners, &disk),
        );
        let lambda = layout::fan_blend(&sr, &sd, |_| TAU - 0.1);
        let ang: Vec<[f64; 3]> = rnd
            .iter()
            .zip(&disk)
            .map(|(r, d)| lerp3(*r, *d, lambda))
            .collect();
        lay_out(n, triangles, &ang).unwrap()
    }

    /// The guaranteed paths on random pairs of immersed disks, simple and
    /// overlapping themselves (at curl 6, 11 of the 60 cases have a side
    /// that overlaps itself; at least a tenth must), rooted at the disk's
    /// centre and at another triangle.
    #[test]
    fn guaranteed_paths_give_immersions_on_random_compatible_pairs() {
        let mut rng = Rng(0x853c49e6748fea9b);
        let mut self_intersecting = 0;
        let cases = 60;
        for case in 0..cases {
            let (n, tris, a, mut b) = random_curled_pair(&mut rng, 5, 40.0, 6.0);
            // A large rotation, a scale and a shift of the target.
            let rot = Point::from_angle(rng.next() * TAU) * (0.3 + 3.0 * rng.next());
            let shift = Point::new(rng.next() * 10.0, rng.next() * 10.0);
            for p in &mut b {
                *p = rot.rotate(*p) + shift;
            }
            if !crate::geom::polygon::is_simple(&a) || !crate::geom::polygon::is_simple(&b) {
                self_intersecting += 1;
            }
            // A root other than the disk's, spread over the cases (the
            // generator's draws stay as they were).
            let drawn = (7 * case + 3) % tris.len();
            let paths = [
                ThirdVertexPath::Angle,
                ThirdVertexPath::Hybrid,
                ThirdVertexPath::Straight,
                ThirdVertexPath::Polar,
            ];
            for (path, root) in paths
                .into_iter()
                .flat_map(|p| [(p, None), (p, Some(drawn))])
            {
                let plan = match root {
                    None => Compatible::new(&a, &b, &tris, RootChoice::Disk, DEFAULT_FAN_MARGIN),
                    Some(t) => Compatible::on_tree(
                        &a,
                        &b,
                        &DualTree::new(a.len(), &tris).unwrap(),
                        Root::Triangle(t),
                        DEFAULT_FAN_MARGIN,
                    ),
                }
                .unwrap();
                assert_eq!(plan.rooted.root, root.unwrap_or(plan.rooted.root));
                let (a0, _) = area_and_centroid(&a, &tris);
                let (a1, _) = area_and_centroid(&b, &tris);
                // Every fitted path keeps the ends' range widened by
                // STRAIGHT_AREA_RANGE.
                let (lo, hi) = (
                    a0.min(a1) * STRAIGHT_AREA_RANGE.0,
                    a0.max(a1) * STRAIGHT_AREA_RANGE.1,
                );
                let mut prev: Option<Vec<Point>> = None;
                for i in 0..=200 {
                    let t = i as f64 / 200.0;
                    let f = Frame {
                        t,
                        points: plan.positions(t, path),
                        triangles: tris.clone(),
                    };
                    assert!(
                        f.is_immersion(),
                        "case {case} {path} t={t}: {:?}",
                        f.check()
                    );
                    let area = f.total_area();
                    assert!(
                        area >= lo * 0.99 && area <= hi * 1.01,
                        "case {case} {path} t={t}: area {area} outside [{lo}, {hi}]"
                    );
                    prev = Some(f.points);
                }
                let last = prev.unwrap();
                assert_eq!(last, b);
                // Near the ends the layout agrees with the inputs.
                let near0 = plan.positions(1e-9, path);
                let near1 = plan.positions(1.0 - 1e-9, path);
                let diag = bbox_diag(&a).max(bbox_diag(&b));
                for i in 0..n {
                    assert!(
                        (near0[i] - a[i]).length() < 1e-6 * diag,
                        "case {case} {path}"
                    );
                    assert!(
                        (near1[i] - b[i]).length() < 1e-6 * diag,
                        "case {case} {path}"
                    );
                }
            }
        }
        assert!(
            self_intersecting * 10 >= cases,
            "only {self_intersecting} of {cases} cases overlap themselves"
        );
    }

    #[test]
    fn unguaranteed_paths_fall_back_when_they_fold() {
        let mut rng = Rng(0xabcdef);
        let times: Vec<f64> = (0..=100).map(|i| i as f64 / 100.0).collect();
        let (mut cases, mut fell) = (0, [0, 0]);
        for _ in 0..200 {
            let (_, tris, a, b) = random_curled_pair(&mut rng, 8, 40.0, 6.0);
            cases += 1;
            for (k, path) in [ThirdVertexPath::Linear, ThirdVertexPath::RotateSlide]
                .into_iter()
                .enumerate()
            {
                let o = crate::morph::MorphOptions::DEFAULT;
                let plan = Compatible::new(&a, &b, &tris, o.root, o.fan_margin).unwrap();
                let m = plan.morph(&times, path).unwrap();
                assert!(m.frames.iter().all(Frame::is_immersion));
                // The frames are checked on every core; the fallback names
                // the first frame in time order that fails (found here one
                // by one with the whole check).
                let first = times
                    .iter()
                    .find(|&&t| crate::immersion::check(&plan.positions(t, path), &tris).is_err());
                match first {
                    Some(t) => {
                        let why = &m.fallbacks[0].why;
                        assert!(why.starts_with(&format!("its frame at t = {t} ")), "{why}");
                        fell[k] += 1;
                    }
                    None => assert!(!m.fallback && m.paths == [path]),
                }
            }
        }
        eprintln!(
            "{cases} cases, fallbacks linear {} rotate-slide {}",
            fell[0], fell[1]
        );
        assert!(fell[0] > 0 && fell[1] > 0, "{fell:?}");
    }

    /// A spiral strip and its zigzag triangulation (the test kit's: outer
    /// edge forward, vertices 0..m; inner edge backward, m..2m).
    pub(crate) use testkit::shapes::spiral_strip;

    #[test]
    fn spirals_unwind_and_wind_with_every_frame_an_immersion() {
        let mut rng = Rng(0xfeed);
        for case in 0..24 {
            let m = 10 + (rng.next() * 40.0) as usize;
            let (t1, t2) = (0.3 + 2.0 * rng.next(), 0.3 + 2.0 * rng.next());
            let (a, tris) = spiral_strip(m, t1, 0.2);
            let (mut b, _) = spiral_strip(m, t2, 0.2);
            let rot = Point::from_angle(rng.next() * TAU) * (0.5 + 2.0 * rng.next());
            for p in &mut b {
                *p = rot.rotate(*p);
            }
            assert!(crate::immersion::check(&a, &tris).is_ok(), "case {case}");
            assert!(crate::immersion::check(&b, &tris).is_ok(), "case {case}");
            let times: Vec<f64> = (0..=200).map(|i| i as f64 / 200.0).collect();
            for path in ThirdVertexPath::ALL {
                let o = crate::morph::MorphOptions::DEFAULT;
                let morph = Compatible::new(&a, &b, &tris, o.root, o.fan_margin)
                    .map_err(MorphError::from)
                    .and_then(|plan| plan.morph(&times, path))
                    .unwrap_or_else(|e| panic!("case {case} {path}: {e}"));
                assert!(morph.frames.iter().all(Frame::is_immersion));
                assert_eq!(morph.frames[0].points, a);
                assert_eq!(morph.frames[200].points, b);
                // Every path's own frames: none of them, the unguaranteed
                // linear and rotate-slide included, folds on these strips
                // and falls back to the hybrid path.
                assert!(!morph.fallback, "case {case} {path} fell back");
                assert_eq!(morph.paths, [path], "case {case}");
            }
        }
    }

    pub(crate) fn bbox_diag(p: &[Point]) -> f64 {
        crate::geom::polygon::bbox_diagonal(p)
    }

    /// The plan of `a` → `b` on `tris`, rooted at the disk's centre with
    /// the default fan margin (the pair must be valid).
    fn disk_plan(a: &[Point], b: &[Point], tris: &[[u32; 3]]) -> Compatible {
        Compatible::new(a, b, tris, RootChoice::Disk, DEFAULT_FAN_MARGIN).expect("a valid pair")
    }

    /// `count` random compatible pairs of 6 to 35 vertices ([`random_pair`]).
    fn disk_pairs(
        rng: &mut Rng,
        count: usize,
    ) -> impl Iterator<Item = (Vec<[u32; 3]>, Vec<Point>, Vec<Point>)> + '_ {
        (0..count).map(move |_| {
            let (_, tris, a, b) = random_pair(rng, 6, 30.0);
            (tris, a, b)
        })
    }

    #[test]
    fn a_plan_built_again_from_its_seed_is_the_same_bit_for_bit() {
        let mut rng = Rng(0x9e1ea5e);
        let mut used = 0;
        for (round, (tris, a, b)) in disk_pairs(&mut rng, 20).enumerate() {
            let mut plan = disk_plan(&a, &b, &tris);
            // What the staged route changes after building: a guide's end
            // (every other pair) and an area range that binds.
            let end: Option<std::sync::Arc<[Point]>> =
                (round % 2 == 0).then(|| a.iter().zip(&b).map(|(p, q)| p.lerp(*q, 0.7)).collect());
            if let Some(end) = &end {
                plan = plan.with_guide(end);
            }
            let (a0, a1) = (
                area_and_centroid(&a, &tris).0,
                area_and_centroid(&b, &tris).0,
            );
            plan = plan.with_area_range(1.5 * a0, 1.5 * a1);
            let paths = [
                ThirdVertexPath::Rigid,
                ThirdVertexPath::Straight,
                ThirdVertexPath::Hybrid,
                ThirdVertexPath::Polar,
            ];
            let ts = [0.0, 0.03125, 0.3, 0.5, 0.77, 1.0];
            let bits = |plan: &Compatible| -> Vec<u64> {
                paths
                    .iter()
                    .flat_map(|&path| ts.iter().map(move |&t| (path, t)))
                    .flat_map(|(path, t)| plan.positions(t, path))
                    .flat_map(|p| [p.x.to_bits(), p.y.to_bits()])
                    .collect()
            };
            let first = bits(&plan);
            let usable = plan.has_rigid_guide();
            used += usize::from(usable);
            // Half the seeds hold their source and the guide's end shared
            // (as a route's legs do), the others copies of their own.
            let start: std::sync::Arc<[Point]> = a.clone().into();
            let mut held = vec![&start];
            held.extend(&end);
            let shares = round % 4 < 2;
            let seed = if shares {
                plan.seed_sharing(&held)
            } else {
                plan.seed()
            };
            assert_eq!(std::sync::Arc::ptr_eq(&seed.src, &start), shares);
            if let (Some(end), Some(held)) = (&end, &seed.guide_end) {
                assert_eq!(std::sync::Arc::ptr_eq(end, held), shares);
            }
            assert_eq!(seed.guide_end.is_some(), end.is_some());
            // Points that differ are never shared.
            let unrelated: std::sync::Arc<[Point]> = b.iter().map(|p| *p * 2.0).collect();
            let apart = plan.seed_sharing(&[&unrelated]);
            assert!(!std::sync::Arc::ptr_eq(&apart.src, &unrelated));
            assert!(
                apart
                    .guide_end
                    .is_none_or(|g| !std::sync::Arc::ptr_eq(&g, &unrelated))
            );
            drop(plan);
            let again = seed.build().unwrap();
            // The rigid guide's verdict is carried before it is used again.
            assert_eq!(again.has_rigid_guide(), usable);
            assert_eq!(seed.has_rigid_guide(), usable);
            assert_eq!(bits(&again), first, "round {round}");
        }
        assert!(used >= 10, "{used} of 20 pairs had a usable rigid guide");
        // A guide found unusable stays so: the plan built again is guided
        // by the straight guide, as the first was, without solving again.
        let (_, tris, a, b) = random_pair(&mut rng, 6, 30.0);
        let plan = disk_plan(&a, &b, &tris);
        plan.rigid.set(None).unwrap();
        let again = plan.seed().build().unwrap();
        assert!(!again.has_rigid_guide());
        for t in [0.25, 0.5] {
            let (p, q) = (
                plan.positions(t, ThirdVertexPath::Rigid),
                again.positions(t, ThirdVertexPath::Rigid),
            );
            assert!(
                p.iter()
                    .zip(&q)
                    .all(|(p, q)| p.to_array().map(f64::to_bits) == q.to_array().map(f64::to_bits))
            );
        }
    }

    #[test]
    fn consecutive_frames_move_continuously() {
        let mut rng = Rng(0x1234567);
        for (tris, a, b) in disk_pairs(&mut rng, 20) {
            let plan = disk_plan(&a, &b, &tris);
            let diag = bbox_diag(&a).max(bbox_diag(&b));
            // Halving the step roughly halves the largest move: no jumps.
            let max_step = |steps: usize, path: ThirdVertexPath| {
                let frames: Vec<Vec<Point>> = (0..=steps)
                    .map(|i| plan.positions(i as f64 / steps as f64, path))
                    .collect();
                frames
                    .windows(2)
                    .map(|w| {
                        w[0].iter()
                            .zip(&w[1])
                            .map(|(p, q)| (*p - *q).length())
                            .fold(0.0, f64::max)
                    })
                    .fold(0.0, f64::max)
            };
            let path = ThirdVertexPath::Hybrid;
            let (coarse, fine) = (max_step(200, path), max_step(400, path));
            assert!(fine < 0.75 * coarse + 1e-9 * diag, "{coarse} -> {fine}");
            assert!(coarse < 0.25 * diag);
            // The straight path can be steep where a triangle of the guide
            // passes through degeneracy (the frame timing spends frames
            // there), but it never jumps: a step of 1e-7 moves nothing far.
            for i in 0..400 {
                let t = i as f64 / 400.0;
                for path in [ThirdVertexPath::Straight, ThirdVertexPath::Polar] {
                    let p = plan.positions(t, path);
                    let q = plan.positions(t + 1e-7, path);
                    let m = p
                        .iter()
                        .zip(&q)
                        .map(|(x, y)| (*x - *y).length())
                        .fold(0.0, f64::max);
                    assert!(m < 1e-3 * diag, "{path} jumps {m} at t = {t}");
                }
            }
        }
    }

    /// `got` measured against the straight guide from `a` to `b` at `t`,
    /// the guide computed here from its definition (the ends interpolated
    /// linearly about their vertex means in a frame turning by their
    /// best-fit rotation): the distance between the two vertex means, and
    /// Σ g·h, Σ g×h and Σ |g|² over the vertices (g the frame, h the
    /// guide, each about its mean). The least-squares similarity onto the
    /// guide keeps the mean (distance 0), needs no further rotation
    /// (Σ g×h = 0 with Σ g·h > 0) and, unscaled, has Σ g·h = Σ |g|².
    fn against_straight_guide(a: &[Point], b: &[Point], t: f64, got: &[Point]) -> [f64; 4] {
        let mean = |p: &[Point]| p.iter().copied().sum::<Point>() / p.len() as f64;
        let (c0, c1) = (mean(a), mean(b));
        let (mut dot, mut cross) = (0.0, 0.0);
        for (p, q) in a.iter().zip(b) {
            dot += (*p - c0).dot(*q - c1);
            cross += (*p - c0).perp_dot(*q - c1);
        }
        let turn = cross.atan2(dot);
        let spin = Point::from_angle(t * turn);
        let c = c0.lerp(c1, t);
        let (mut re, mut im, mut den) = (0.0, 0.0, 0.0);
        for v in 0..a.len() {
            let h = spin
                .rotate((a[v] - c0) * (1.0 - t) + Point::from_angle(-turn).rotate(b[v] - c1) * t);
            let g = got[v] - c;
            re += g.dot(h);
            im += g.perp_dot(h);
            den += g.length_squared();
        }
        [(mean(got) - c).length(), re, im, den]
    }

    /// The global fit, from its definition: on random compatible pairs,
    /// every frame of `angle` and `hybrid` at every t has the vertex mean
    /// of the straight guide toward the target (the means interpolated
    /// linearly), no rotation about it brings the frame closer to that
    /// guide (computed here: the ends interpolated about their means in a
    /// frame turning by their best-fit rotation), and its scale is the
    /// least-squares one unless the area range clamps it.
    #[test]
    fn angle_paths_are_placed_by_the_least_squares_fit_to_the_straight_guide() {
        let mut rng = Rng(0x6a09e667f3bcc908);
        let mut unclamped = 0;
        for (case, (tris, a, b)) in disk_pairs(&mut rng, 30).enumerate() {
            let b: Vec<Point> = b
                .iter()
                .map(|p| Point::from_angle(2.0).rotate(*p) * 1.7 + Point::new(3.0, -1.0))
                .collect();
            let (a0, _) = area_and_centroid(&a, &tris);
            let (a1, _) = area_and_centroid(&b, &tris);
            let (lo, hi) = (
                a0.min(a1) * STRAIGHT_AREA_RANGE.0,
                a0.max(a1) * STRAIGHT_AREA_RANGE.1,
            );
            let plan = disk_plan(&a, &b, &tris);
            let diag = bbox_diag(&a).max(bbox_diag(&b));
            for path in [ThirdVertexPath::Angle, ThirdVertexPath::Hybrid] {
                for i in 1..20 {
                    let t = f64::from(i) / 20.0;
                    let got = plan.positions(t, path);
                    let [off, re, im, den] = against_straight_guide(&a, &b, t, &got);
                    assert!(off < 1e-9 * diag, "case {case} {path} t={t}");
                    assert!(
                        re > 0.0 && im.abs() < 1e-9 * re,
                        "case {case} {path} t={t}: {re} {im}"
                    );
                    // Least squares: the guide's projection on the frame
                    // is the frame itself (re = den), unless the area was
                    // clamped to the range.
                    let (area, _) = area_and_centroid(&got, &tris);
                    let at_bound = (area - lo).abs() < 1e-9 * lo || (area - hi).abs() < 1e-9 * hi;
                    if !at_bound {
                        unclamped += 1;
                        assert!(
                            (re - den).abs() < 1e-9 * den,
                            "case {case} {path} t={t}: scale {re} against {den}"
                        );
                    }
                }
            }
        }
        assert!(unclamped > 500, "{unclamped} unclamped frames");
    }

    /// A shape and its copy turned by θ (|θ| < π) morph along the polar
    /// path by turning rigidly the short way about the vertex mean (which
    /// moves straight): at t, turned by tθ, never a collapse through the
    /// centre nor a spin the long way round.
    #[test]
    fn the_polar_path_turns_a_turned_copy_rigidly_the_short_way() {
        let n = 24u32;
        let a: Vec<Point> = (0..n)
            .map(|i| {
                let u = Point::from_angle(TAU * f64::from(i) / f64::from(n));
                Point::new(1.5 * u.x + 0.2, u.y - 0.1)
            })
            .collect();
        let tris: Vec<[u32; 3]> = (1..n - 1).map(|i| [0, i, i + 1]).collect();
        for theta in [0.3, -2.5, 3.0] {
            let b: Vec<Point> = a
                .iter()
                .map(|p| Point::from_angle(theta).rotate(*p))
                .collect();
            let plan = disk_plan(&a, &b, &tris);
            for t in [0.25, 0.5, 0.75] {
                let got = plan.positions(t, ThirdVertexPath::Polar);
                // About the vertex mean, which moves straight.
                let (c0, c1) = (
                    a.iter().sum::<Point>() / 24.0,
                    b.iter().sum::<Point>() / 24.0,
                );
                for (g, p) in got.iter().zip(&a) {
                    let want = c0.lerp(c1, t) + Point::from_angle(theta * t).rotate(*p - c0);
                    assert!(
                        (*g - want).length() < 1e-9,
                        "θ {theta} t {t}: {g:?} {want:?}"
                    );
                }
            }
        }
    }

    /// Where the polar interpolation is valid with margins, the polar path
    /// has its shape: spiral strips wound 1.2 and 2.1 turns, the second
    /// turned by 0.4 rad, morph with every vertex on its arc about the
    /// vertex means (angle unwound along the curve, shifted by whole turns
    /// to move least, and distance both linear in t), computed here from
    /// the definition, up to the similarity of the global fit: the frame
    /// keeps the straight guide's vertex mean and no rotation brings it
    /// closer to that guide. Every frame an immersion.
    #[test]
    fn the_polar_path_winds_spirals_along_their_arcs() {
        let (a, tris) = spiral_strip(60, 1.2, 0.15);
        let (b0, _) = spiral_strip(60, 2.1, 0.15);
        let b: Vec<Point> = b0
            .iter()
            .map(|p| Point::from_angle(0.4).rotate(*p))
            .collect();
        let mean = |p: &[Point]| p.iter().copied().sum::<Point>() / p.len() as f64;
        let (c0, c1) = (mean(&a), mean(&b));
        let unwound = |p: &[Point], c: Point| -> Vec<f64> {
            let mut out: Vec<f64> = Vec::new();
            for q in p {
                let d = (*q - c).to_angle();
                let next = match out.last() {
                    None => d,
                    Some(&prev) => {
                        let mut x = d;
                        while x - prev > PI {
                            x -= TAU;
                        }
                        while x - prev < -PI {
                            x += TAU;
                        }
                        x
                    }
                };
                out.push(next);
            }
            out
        };
        let (ua, ub) = (unwound(&a, c0), unwound(&b, c1));
        // Whole turns that move least, by trying each.
        let moved = |k: f64| -> f64 {
            (0..a.len())
                .map(|i| {
                    (ub[i] + k * TAU - ua[i]).abs() * ((a[i] - c0).length() + (b[i] - c1).length())
                })
                .sum()
        };
        let k = (-4..=4)
            .map(f64::from)
            .min_by(|x, y| moved(*x).total_cmp(&moved(*y)))
            .unwrap();
        let plan = disk_plan(&a, &b, &tris);
        let diag = bbox_diag(&a).max(bbox_diag(&b));
        let travel = |path: ThirdVertexPath| -> f64 {
            let mut prev = a.clone();
            let mut sum = 0.0;
            for i in 1..=100 {
                let t = f64::from(i) / 100.0;
                let p = plan.positions(t, path);
                assert!(crate::immersion::check(&p, &tris).is_ok(), "{path} t={t}");
                sum += p
                    .iter()
                    .zip(&prev)
                    .map(|(x, y)| (*x - *y).length())
                    .sum::<f64>();
                prev = p;
            }
            sum
        };
        for i in 1..100 {
            let t = f64::from(i) / 100.0;
            let c = c0.lerp(c1, t);
            let got = plan.positions(t, ThirdVertexPath::Polar);
            let want: Vec<Point> = (0..a.len())
                .map(|v| {
                    let ang = ua[v] * (1.0 - t) + (ub[v] + k * TAU) * t;
                    let r = (a[v] - c0).length() * (1.0 - t) + (b[v] - c1).length() * t;
                    c + Point::from_angle(ang) * r
                })
                .collect();
            // The shape is the polar interpolation's: `got` is a
            // similarity image of `want` (z ↦ s·z + u, s complex).
            let (mw, mg) = (mean(&want), mean(&got));
            let (mut num, mut den) = (Point::ZERO, 0.0);
            for (w, g) in want.iter().zip(&got) {
                let (w, g) = (*w - mw, *g - mg);
                num += Point::new(w.dot(g), w.perp_dot(g));
                den += w.length_squared();
            }
            let s = num / den;
            for v in 0..a.len() {
                let image = s.rotate(want[v] - mw) + mg;
                assert!(
                    (got[v] - image).length() < 1e-9 * diag,
                    "t = {t}, vertex {v}: {:?} against {:?}",
                    got[v],
                    image
                );
            }
            // Placed by the global fit onto the straight guide: the same
            // vertex mean, and no rotation would bring it closer.
            let [off, re, im, _] = against_straight_guide(&a, &b, t, &got);
            assert!(off < 1e-9 * diag, "t = {t}");
            assert!(re > 0.0 && im.abs() < 1e-9 * re, "t = {t}: {re} {im}");
        }
        assert!(travel(ThirdVertexPath::Polar) > 0.0);
    }

    /// Where the linear morph is valid with margins, the straight path is
    /// the linear morph: a mild deformation of a random immersed disk
    /// (small enough that no triangle thins below the floor and no fan
    /// nears 2π) is interpolated linearly, vertex by vertex.
    #[test]
    fn the_straight_path_is_the_linear_morph_where_that_is_valid() {
        let mut rng = Rng(0x5742a16);
        let mut checked = 0;
        for _ in 0..40 {
            let (n, tris) = random_polygon(&mut rng, 6, 30.0);
            let a = random_immersed_disk(n, &tris, 1.0, &mut rng);
            let diag = bbox_diag(&a);
            let b: Vec<Point> = a
                .iter()
                .map(|p| *p + Point::new(rng.next() - 0.5, rng.next() - 0.5) * (0.002 * diag))
                .collect();
            // Only pairs whose linear morph keeps margins everywhere.
            let linear =
                |t: f64| -> Vec<Point> { a.iter().zip(&b).map(|(p, q)| p.lerp(*q, t)).collect() };
            let margins = (0..=20).all(|i| {
                let p = linear(i as f64 / 20.0);
                crate::immersion::check(&p, &tris).is_ok()
                    && crate::geom::polygon::min_triangle_angle(&p, &tris) > STRAIGHT_MIN_ANGLE
            });
            if !margins {
                continue;
            }
            let plan = disk_plan(&a, &b, &tris);
            // With the guide's rotation taken out (it is tiny here), the
            // straight frames are the linear ones.
            for i in 1..20 {
                let t = i as f64 / 20.0;
                let got = plan.positions(t, ThirdVertexPath::Straight);
                let guide = plan.guide(t);
                for (g, q) in got.iter().zip(&guide) {
                    assert!((*g - *q).length() < 1e-9 * diag, "t={t}: {g} vs {q}");
                }
                for (g, q) in guide.iter().zip(&linear(t)) {
                    assert!((*g - *q).length() < 1e-2 * diag);
                }
            }
            checked += 1;
        }
        assert!(
            checked >= 10,
            "only {checked} pairs had a valid linear morph"
        );
    }

    /// The projection onto a triangle's floor set is the nearest point of
    /// the set: it lies in the set (every angle at least the floor, up to
    /// rounding), no sampled point of the set's boundary is nearer, and it
    /// moves no more than its argument (1-Lipschitz), so the rigid path
    /// is as continuous as its guide.
    #[test]
    fn the_floor_projection_is_the_nearest_point_and_continuous() {
        let mut rng = Rng(0x5eed_f100);
        for _ in 0..2000 {
            let floor = 0.001 + rng.next() * 0.5;
            let z = Point::new(rng.next() * 6.0 - 2.5, rng.next() * 6.0 - 2.5);
            let p = project_to_floor(z, floor);
            let a = factor_angles(p);
            assert!(
                a.iter().all(|&x| x >= floor - 1e-9) && p.y > 0.0,
                "z {z} floor {floor}: {p} has angles {a:?}"
            );
            if a.iter().all(|&x| x >= floor) && factor_angles(z).iter().all(|&x| x >= floor) {
                continue;
            }
            // The boundary sampled finely: the two walls and the arc.
            let (c, s) = (floor.cos(), floor.sin());
            let apex = Point::new(0.5, 0.5 * s / c);
            let (q1, q2) = (
                Point::new(c, s) * (2.0 * c),
                Point::new(1.0, 0.0) + Point::new(-c, s) * (2.0 * c),
            );
            let centre = Point::new(0.5, 0.5 * c / s);
            let (a1, a2) = ((q1 - centre).to_angle(), (q2 - centre).to_angle());
            let span = (a2 - a1).rem_euclid(TAU);
            let k = 4000;
            let nearest = (0..=k)
                .flat_map(|i| {
                    let u = i as f64 / k as f64;
                    [
                        apex.lerp(q1, u),
                        apex.lerp(q2, u),
                        centre + Point::from_angle(a1 + span * u) * (0.5 / s),
                    ]
                })
                .map(|b| (b - z).length())
                .fold(f64::INFINITY, f64::min);
            let d = (p - z).length();
            assert!(
                d <= nearest + 1e-3 * (1.0 + nearest),
                "z {z} floor {floor}: projection at {d}, boundary at {nearest}"
            );
            let w = z + Point::new(rng.next() - 0.5, rng.next() - 0.5) * 1e-3;
            let moved = (project_to_floor(w, floor) - p).length();
            assert!(
                moved <= (w - z).length() * (1.0 + 1e-6) + 1e-12,
                "z {z} floor {floor}: moved {moved} for {}",
                (w - z).length()
            );
        }
    }

    #[test]
    fn lay_out_reproduces_a_triangulated_polygon() {
        let mut rng = Rng(99);
        let n = 12;
        let tris = random_triangulation(n as u32, &mut rng);
        // A convex polygon: a circle with jittered vertex angles.
        let pts: Vec<Point> = (0..n)
            .map(|i| Point::from_angle(TAU * (i as f64 + 0.4 * rng.next()) / n as f64))
            .collect();
        let ang: Vec<[f64; 3]> = tris
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| pts[v as usize]);
                crate::geom::polygon::triangle_angles(a, b, c)
            })
            .collect();
        let out = lay_out(n, &tris, &ang).unwrap();
        // Same shape up to similarity: compare after mapping edge 0 of the
        // first triangle.
        let [x, y, _] = tris[0].map(|v| v as usize);
        let s = (pts[y] - pts[x]).length();
        let r = Point::from_angle((pts[y] - pts[x]).to_angle()) * s;
        for i in 0..n {
            let q = pts[x] + r.rotate(out[i]);
            assert!((q - pts[i]).length() < 1e-9, "{i}");
        }
    }
}
