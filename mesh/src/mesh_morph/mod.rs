//! Morphing compatible planar tilings (docs/design.md §9).
//!
//! Papers: Floater & Gotsman, *How to Morph Tilings Injectively*; Surazhsky &
//! Gotsman, *Intrinsic Morphing of Compatible Triangulations* (cited as
//! *Intrinsic Morphing*) and *Controllable Morphing of Compatible Planar
//! Triangulations* (cited as *Controllable Morphing*).
//!
//! [`mesh_morph`] turns two [`Tiling`]s with the same faces into one
//! [`MeshFrame`] per requested time, in three steps:
//!
//! 1. **Set-up** (`Problem`): both tilings are validated, their faces
//!    compared, the interior vertices numbered, and, where the boundaries
//!    differ, the boundary motion prepared.
//! 2. **Positions at t**: the boundary is placed, then the method gives the
//!    interior. [`Method::Linear`] moves every vertex on a straight line
//!    (Floater & Gotsman eq. 4.1). Every other method writes each interior
//!    vertex as a convex combination `x_i = Σ_j λ_ij(t) x_j` of its edge
//!    neighbours and solves `x_i − Σ_j λ_ij(t) x_j = Σ_{j∈B} λ_ij(t) x_j(t)`
//!    for the interior (Floater & Gotsman eq. 5.3, by the private `solve`
//!    module). Strictly positive weights and a convex boundary give a valid
//!    tiling (Tutte; Floater); the methods differ in how `λ(t)` is made.
//! 3. **Check**: every frame's `valid` flag is decided exactly (every face
//!    strictly convex and counter-clockwise), whatever the method promises.
//!
//! The weights of each method:
//!
//! * [`Method::Convex`]: `λ_ij(t) = (1 − t) λ_ij⁰ + t λ_ij¹`, the weights of
//!   [`MeshMorphOptions::weights`] interpolated (Floater & Gotsman §5).
//! * [`Method::Intrinsic`]: the sector angles and edge lengths of each star
//!   are interpolated and put into the mean value formula (Surazhsky &
//!   Gotsman *Intrinsic Morphing* eq. 6 in eq. 2);
//!   [`MeshMorphOptions::weights`] is not used.
//! * [`Method::Power`] (`power.rs`): the stochastic neighbourhood matrix
//!   `M = [[A, B], [0, I]]` of each tiling is raised to a power `m`, and
//!   `x = M(t) x` with `M(t) = (1 − t) M₀^m + t M₁^m` (Surazhsky & Gotsman
//!   *Controllable Morphing* §3.3). `m = 1` is `convex`; as `m` grows the
//!   morph tends to the linear one and is no longer guaranteed valid, so the
//!   largest valid `m` is searched (doubling, then bisection), then the
//!   largest `d ∈ [0, 1]` for which `(1 − d)·M(t; m) + d·M(t; m + 1)` stays
//!   valid (bisection; this blend of powers `m` and `m + 1` is how eq. 14 of
//!   *Controllable Morphing* is implemented). A candidate is valid when
//!   every frame at the requested times and at
//!   [`MeshMorphOptions::validity_samples`] evenly spaced ones is valid
//!   (checked exactly; the paper leaves the sampling open).
//! * [`Method::Local`] (`local.rs`): every star (an interior vertex with its
//!   neighbours, centred at the origin) is morphed on its own: linearly when
//!   [`check_star_linear`] (*Controllable Morphing* Appendix A) says the
//!   star's linear morph stays valid, otherwise by interpolating its
//!   neighbours' polar coordinates (*Controllable Morphing* §4, §4.1); the
//!   centre's weights in the morphed star are row `i` of `A(t)`. With
//!   [`MeshMorphOptions::area_improvement`] every sector's radial edges are
//!   rescaled so that its area evolves linearly, keeping the ratio of the
//!   linearly interpolated edge lengths, and each edge takes the mean of its
//!   two sectors' lengths (*Controllable Morphing* §4.3, eq. 24); the
//!   angles are kept, so validity is too.
//!
//! Two more things shape the path of the methods that solve:
//!
//! * [`MeshMorphOptions::intermediate`] (`convex` and `intrinsic`): a tiling
//!   `T_m` to pass through at `t_m` (*Controllable Morphing* §3.4). Each
//!   weight (for `intrinsic`, each angle and length) follows a monotone
//!   piecewise cubic Hermite interpolant (Fritsch–Butland slopes) through its
//!   values at 0, `t_m` and 1, and the rows are renormalised. The paper uses
//!   piecewise Bézier curves; monotone pieces serve the same end, since they
//!   stay between their end values: weights stay positive, so the morph
//!   stays valid, and it is C¹.
//! * Different boundaries (Floater & Gotsman §6): each boundary vertex
//!   interpolates its polar coordinates about the moving barycentre of the
//!   boundary vertices, so both boundaries must be star-shaped about their
//!   barycentre (checked exactly). The boundaries in between need not be
//!   convex, so validity is not guaranteed there; each frame's `valid` flag
//!   says.
//!
//! [`check_linear`] (`exact.rs`) decides exactly whether the linear morph
//! is valid, without sampling: the Appendix A test of *Controllable
//! Morphing* (Theorem 4.1) on every face corner.

mod exact;
mod local;
mod power;

pub use power::{MAX_POWER, MAX_POWER_ENTRIES, MAX_SAMPLES, PowerChoice, power_choice};

use crate::coords::{self, Weights};
use crate::solve::SparseSolver;
use crate::tiling::validate::{Topology, faces_strictly_convex, validate_topology};
use crate::tiling::{Tiling, TilingError};
use immerse_base::geom::{Orientation, Point, orient};

/// How the vertices travel; the names are the CLI values. With the `cli`
/// feature it is the command line's `--method` (each variant's first doc
/// paragraph is its help there).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Method {
    /// Straight-line vertex paths (may fold; reported per frame).
    ///
    /// At constant speed (`linear`).
    Linear,
    /// Interpolate barycentric weights and solve (Floater–Gotsman).
    ///
    /// Convex combination weights (`convex`, Floater & Gotsman).
    Convex,
    /// Interpolate angles and edge lengths in the mean value formula.
    ///
    /// Mean value coordinates (`intrinsic`, Surazhsky & Gotsman *Intrinsic
    /// Morphing*).
    Intrinsic,
    /// Neighbourhood matrices to the largest valid power (closer to linear).
    ///
    /// `power`, Surazhsky & Gotsman *Controllable Morphing* §3.3.
    Power,
    /// Linear where each star allows it, polar averaging elsewhere.
    ///
    /// Star by star (`local`, Surazhsky & Gotsman *Controllable Morphing*
    /// §4.1).
    Local,
}

impl Method {
    /// Every method, in CLI order.
    pub const ALL: [Method; 5] = [
        Method::Linear,
        Method::Convex,
        Method::Intrinsic,
        Method::Power,
        Method::Local,
    ];

    /// The CLI value: `linear`, `convex`, `intrinsic`, `power` or `local`.
    pub fn as_str(self) -> &'static str {
        match self {
            Method::Linear => "linear",
            Method::Convex => "convex",
            Method::Intrinsic => "intrinsic",
            Method::Power => "power",
            Method::Local => "local",
        }
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::str::FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Method, String> {
        Method::ALL
            .into_iter()
            .find(|m| m.as_str() == s)
            .ok_or_else(|| {
                format!("unknown method {s:?} (expected linear|convex|intrinsic|power|local)")
            })
    }
}

/// Options of [`mesh_morph`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct MeshMorphOptions {
    /// Barycentric coordinates for `convex`, `power` and `local`.
    /// [`Weights::Uniform`] does not reproduce the vertices, so with it the
    /// end frames are the Tutte drawings, not the inputs. Default:
    /// [`Weights::MeanValue`].
    pub weights: Weights,
    /// A fixed power `m ≥ 1` for `power` (no search, fraction
    /// [`MeshMorphOptions::power_fraction`]); `None` searches the largest
    /// valid one. Default: `None`.
    pub power: Option<u32>,
    /// Upper limit of the power search (at most [`MAX_POWER`]). Default: 64.
    pub max_power: u32,
    /// Fractional part `d ∈ [0, 1)` used with a fixed
    /// [`MeshMorphOptions::power`]. Default: 0.
    pub power_fraction: f64,
    /// Bisection steps of the fractional refinement after the power search;
    /// 0 turns it off. Default: 8.
    pub fraction_steps: u32,
    /// Evenly spaced times, besides the requested ones, at which a `power`
    /// candidate must be valid (at most [`MAX_SAMPLES`]). Default: 32.
    pub validity_samples: usize,
    /// `local` only: improve the evolution of triangle areas
    /// (Surazhsky & Gotsman *Controllable Morphing* §4.3). Default: `false`.
    pub area_improvement: bool,
    /// A compatible tiling with the same boundary to pass through (`convex` and
    /// `intrinsic`; Surazhsky & Gotsman *Controllable Morphing* §3.4). Default:
    /// `None`.
    pub intermediate: Option<Tiling>,
    /// When to pass through [`MeshMorphOptions::intermediate`], in (0, 1).
    /// Default: 0.5.
    pub intermediate_t: f64,
}

impl MeshMorphOptions {
    /// The defaults.
    pub const DEFAULT: MeshMorphOptions = MeshMorphOptions {
        weights: Weights::MeanValue,
        power: None,
        max_power: 64,
        power_fraction: 0.0,
        fraction_steps: 8,
        validity_samples: 32,
        area_improvement: false,
        intermediate: None,
        intermediate_t: 0.5,
    };

    /// Sets [`MeshMorphOptions::weights`].
    pub fn with_weights(mut self, weights: Weights) -> Self {
        self.weights = weights;
        self
    }

    /// Sets [`MeshMorphOptions::power`].
    pub fn with_power(mut self, power: Option<u32>) -> Self {
        self.power = power;
        self
    }

    /// Sets [`MeshMorphOptions::max_power`].
    pub fn with_max_power(mut self, max_power: u32) -> Self {
        self.max_power = max_power;
        self
    }

    /// Sets [`MeshMorphOptions::power_fraction`].
    pub fn with_power_fraction(mut self, d: f64) -> Self {
        self.power_fraction = d;
        self
    }

    /// Sets [`MeshMorphOptions::fraction_steps`].
    pub fn with_fraction_steps(mut self, steps: u32) -> Self {
        self.fraction_steps = steps;
        self
    }

    /// Sets [`MeshMorphOptions::validity_samples`].
    pub fn with_validity_samples(mut self, samples: usize) -> Self {
        self.validity_samples = samples;
        self
    }

    /// Sets [`MeshMorphOptions::area_improvement`].
    pub fn with_area_improvement(mut self, on: bool) -> Self {
        self.area_improvement = on;
        self
    }

    /// Sets [`MeshMorphOptions::intermediate`] and
    /// [`MeshMorphOptions::intermediate_t`].
    pub fn with_intermediate(mut self, tiling: Option<Tiling>, t: f64) -> Self {
        self.intermediate = tiling;
        self.intermediate_t = t;
        self
    }
}

impl Default for MeshMorphOptions {
    fn default() -> Self {
        MeshMorphOptions::DEFAULT
    }
}

/// One frame of a mesh morph.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshFrame {
    /// Time in [0, 1].
    pub t: f64,
    /// Vertex positions; the faces are those of the input.
    pub points: Vec<Point>,
    /// True when every face is strictly convex and counter-clockwise,
    /// decided exactly.
    pub valid: bool,
}

/// Why a mesh morph could not be computed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MeshMorphError {
    /// An input is not a tiling.
    #[error("{which} tiling: {source}")]
    Tiling {
        /// `source`, `target` or `intermediate`.
        which: &'static str,
        /// The problem.
        #[source]
        source: TilingError,
    },
    /// The tilings do not share their faces.
    #[error(
        "the {which} tiling is not compatible with the source: {reason} (hint: same vertex count and the same faces in the same order)"
    )]
    Incompatible {
        /// `target` or `intermediate`.
        which: &'static str,
        /// What differs.
        reason: String,
    },
    /// The boundaries differ and one is not star-shaped about its barycentre
    /// (Floater & Gotsman §6).
    #[error(
        "the boundaries differ and the {which} boundary is not star-shaped about its barycentre at vertex {vertex}"
    )]
    BoundaryNotStarShaped {
        /// `source` or `target`.
        which: &'static str,
        /// A boundary vertex where it fails.
        vertex: u32,
    },
    /// The intermediate tiling needs identical boundaries and `convex` or
    /// `intrinsic`.
    #[error("an intermediate tiling {reason}")]
    Intermediate {
        /// What is wrong.
        reason: String,
    },
    /// A requested time is not a number in [0, 1].
    #[error("time {t} (index {index}) is not in [0, 1]")]
    BadTime {
        /// Index in `times`.
        index: usize,
        /// The value.
        t: f64,
    },
    /// An option is out of range.
    #[error("bad option: {0}")]
    BadOption(String),
    /// The sparse solver failed: a bug, since the systems are non-singular.
    #[error("sparse solve failed ({0}); this is a bug, please report it")]
    Solver(String),
}

/// Result of [`check_linear`].
#[derive(Clone, Debug, PartialEq)]
pub enum LinearCheck {
    /// Every face stays strictly convex and counter-clockwise for all
    /// t ∈ [0, 1].
    Valid,
    /// The sector `(vertex, a, b)` (a corner of a face) degenerates; `vertex`
    /// is the smallest such vertex index and `[t_from, t_to]` approximates
    /// the first sub-interval of [0, 1] where its area is not positive.
    Degenerates {
        /// Centre of the failing star.
        vertex: u32,
        /// First neighbour of the sector (counter-clockwise).
        a: u32,
        /// Second neighbour of the sector.
        b: u32,
        /// Start of the failing interval.
        t_from: f64,
        /// End of the failing interval.
        t_to: f64,
    },
    /// The inputs are not compatible tilings.
    Incompatible(String),
}

impl LinearCheck {
    /// True for [`LinearCheck::Valid`].
    pub fn is_valid(&self) -> bool {
        matches!(self, LinearCheck::Valid)
    }
}

/// Decides exactly whether the linear morph from `a` to `b` is valid: the
/// Surazhsky & Gotsman *Controllable Morphing* Appendix A test on every star
/// (Theorem 4.1), extended to every face corner so it also covers polygonal
/// faces and moving boundaries.
///
/// # Examples
///
/// ```
/// use immerse_mesh::mesh_morph::check_linear;
/// use immerse_mesh::tiling::Tiling;
/// # fn main() -> Result<(), immerse_mesh::tiling::TilingError> {
/// let faces = r#""faces": [[0,1,4],[1,2,4],[2,3,4],[3,0,4]]"#;
/// let a = Tiling::from_json_str(&format!(r#"{{"points": [[0,0],[1,0],[1,1],[0,1],[0.3,0.3]], {faces}}}"#))?;
/// let b = Tiling::from_json_str(&format!(r#"{{"points": [[0,0],[1,0],[1,1],[0,1],[0.7,0.6]], {faces}}}"#))?;
/// assert!(check_linear(&a, &b).is_valid());
/// # Ok(())
/// # }
/// ```
pub fn check_linear(a: &Tiling, b: &Tiling) -> LinearCheck {
    let topo = match validate_topology(a) {
        Ok(t) => t,
        Err(e) => return LinearCheck::Incompatible(format!("source: {e}")),
    };
    if let Err(e) = validate_topology(b) {
        return LinearCheck::Incompatible(format!("target: {e}"));
    }
    if let Err(reason) = compatible(a, b) {
        return LinearCheck::Incompatible(reason);
    }
    for (v, fan) in topo.fan.iter().enumerate() {
        let k = fan.len();
        let sectors = if topo.is_boundary[v] { k - 1 } else { k };
        for s in 0..sectors {
            let (x, y) = (fan[s] as usize, fan[(s + 1) % k] as usize);
            let p0 = [a.points[v], a.points[x], a.points[y]];
            let p1 = [b.points[v], b.points[x], b.points[y]];
            if let Err((t_from, t_to)) = exact::triangle_stays_ccw(p0, p1) {
                return LinearCheck::Degenerates {
                    vertex: v as u32,
                    a: x as u32,
                    b: y as u32,
                    t_from,
                    t_to,
                };
            }
        }
    }
    LinearCheck::Valid
}

/// Decides exactly whether the star with centre `c` and counter-clockwise ring
/// `ring` stays valid (every sector strictly counter-clockwise) while all its
/// vertices move linearly from time 0 to time 1 (Surazhsky & Gotsman
/// *Controllable Morphing* Appendix A). Returns the first failing sector index
/// `j` (between ring vertices `j` and `j + 1`) and an approximate failing
/// interval.
///
/// # Errors
///
/// `Err((j, t_from, t_to))` when sector `j` degenerates.
pub fn check_star_linear(
    c0: Point,
    ring0: &[Point],
    c1: Point,
    ring1: &[Point],
) -> Result<(), (usize, f64, f64)> {
    let d = ring0.len().min(ring1.len());
    for j in 0..d {
        let k = (j + 1) % d;
        exact::triangle_stays_ccw([c0, ring0[j], ring0[k]], [c1, ring1[j], ring1[k]])
            .map_err(|(a, b)| (j, a, b))?;
    }
    Ok(())
}

/// Checks that `b` has the same vertex count and faces as `a`.
fn compatible(a: &Tiling, b: &Tiling) -> Result<(), String> {
    if a.points.len() != b.points.len() {
        return Err(format!(
            "{} vertices versus {}",
            a.points.len(),
            b.points.len()
        ));
    }
    if a.faces.len() != b.faces.len() {
        return Err(format!("{} faces versus {}", a.faces.len(), b.faces.len()));
    }
    if let Some(f) = (0..a.faces.len()).find(|&f| a.faces[f] != b.faces[f]) {
        return Err(format!("face {f} differs"));
    }
    Ok(())
}

/// Shared set-up of a morph: topology, interior numbering, boundary motion.
pub(crate) struct Problem<'a> {
    pub(crate) a: &'a Tiling,
    pub(crate) b: &'a Tiling,
    pub(crate) topo: Topology,
    /// Interior vertices in increasing order.
    pub(crate) interior: Vec<u32>,
    /// Vertex → interior index, or `u32::MAX` for boundary vertices.
    pub(crate) index: Vec<u32>,
    boundary_motion: Option<PolarBoundary>,
}

/// Polar-coordinate boundary morph of Floater & Gotsman §6.
struct PolarBoundary {
    centre: [Point; 2],
    radius: [Vec<f64>; 2],
    angle: [Vec<f64>; 2],
}

impl PolarBoundary {
    fn new(topo: &Topology, a: &Tiling, b: &Tiling) -> Result<PolarBoundary, MeshMorphError> {
        let mut centre = [Point::ZERO; 2];
        let mut radius = [Vec::new(), Vec::new()];
        let mut angle = [Vec::new(), Vec::new()];
        for (k, (t, which)) in [(a, "source"), (b, "target")].into_iter().enumerate() {
            let pts: Vec<Point> = topo
                .boundary
                .iter()
                .map(|&v| t.points[v as usize])
                .collect();
            let n = pts.len();
            let c = pts.iter().sum::<Point>() / n as f64;
            let mut turns = 0usize;
            for i in 0..n {
                let (p, q) = (pts[i], pts[(i + 1) % n]);
                if orient(c, p, q) != Orientation::CounterClockwise {
                    return Err(MeshMorphError::BoundaryNotStarShaped {
                        which,
                        vertex: topo.boundary[i],
                    });
                }
                let up = |x: Point| x.y > c.y || (x.y == c.y && x.x > c.x);
                if !up(p) && up(q) {
                    turns += 1;
                }
            }
            if turns != 1 {
                return Err(MeshMorphError::BoundaryNotStarShaped {
                    which,
                    vertex: topo.boundary[0],
                });
            }
            let rel: Vec<Point> = pts.iter().map(|&p| p - c).collect();
            let first = rel[0].y.atan2(rel[0].x).rem_euclid(std::f64::consts::TAU);
            let mut th = vec![first];
            for i in 1..n {
                let step = rel[i - 1].perp_dot(rel[i]).atan2(rel[i - 1].dot(rel[i]));
                th.push(th[i - 1] + step);
            }
            centre[k] = c;
            radius[k] = rel.iter().map(|r| r.length()).collect();
            angle[k] = th;
        }
        Ok(PolarBoundary {
            centre,
            radius,
            angle,
        })
    }

    fn at(&self, t: f64, boundary: &[u32], out: &mut [Point]) {
        let c = self.centre[0].lerp(self.centre[1], t);
        for (i, &v) in boundary.iter().enumerate() {
            let r = lerp(self.radius[0][i], self.radius[1][i], t);
            let th = lerp(self.angle[0][i], self.angle[1][i], t);
            out[v as usize] = c + r * Point::new(th.cos(), th.sin());
        }
    }
}

pub(crate) fn lerp(a: f64, b: f64, t: f64) -> f64 {
    (1.0 - t) * a + t * b
}

impl<'a> Problem<'a> {
    fn new(a: &'a Tiling, b: &'a Tiling, polar: bool) -> Result<Problem<'a>, MeshMorphError> {
        let topo = validate_topology(a).map_err(|source| MeshMorphError::Tiling {
            which: "source",
            source,
        })?;
        validate_topology(b).map_err(|source| MeshMorphError::Tiling {
            which: "target",
            source,
        })?;
        compatible(a, b).map_err(|reason| MeshMorphError::Incompatible {
            which: "target",
            reason,
        })?;
        let interior = topo.interior();
        let mut index = vec![u32::MAX; a.points.len()];
        for (k, &v) in interior.iter().enumerate() {
            index[v as usize] = k as u32;
        }
        let same = topo
            .boundary
            .iter()
            .all(|&v| a.points[v as usize] == b.points[v as usize]);
        let boundary_motion = if same || !polar {
            None
        } else {
            Some(PolarBoundary::new(&topo, a, b)?)
        };
        Ok(Problem {
            a,
            b,
            topo,
            interior,
            index,
            boundary_motion,
        })
    }

    /// True when the boundary is fixed.
    pub(crate) fn same_boundary(&self) -> bool {
        self.boundary_motion.is_none()
    }

    /// Positions at time `t` with the boundary placed and the interior
    /// copied from the source (to be overwritten).
    pub(crate) fn boundary_at(&self, t: f64) -> Vec<Point> {
        let mut pts = self.a.points.clone();
        if let Some(m) = &self.boundary_motion {
            m.at(t, &self.topo.boundary, &mut pts);
        }
        pts
    }

    /// Ring positions of vertex `v` in `points`.
    pub(crate) fn ring(&self, v: u32, points: &[Point]) -> Vec<Point> {
        self.topo.fan[v as usize]
            .iter()
            .map(|&w| points[w as usize])
            .collect()
    }

    /// The solver for weight rows aligned with the fans.
    pub(crate) fn weight_solver(&self) -> Result<SparseSolver, MeshMorphError> {
        let rows: Vec<Vec<u32>> = self
            .interior
            .iter()
            .enumerate()
            .map(|(k, &v)| {
                let mut r = vec![k as u32];
                r.extend(
                    self.topo.fan[v as usize]
                        .iter()
                        .map(|&w| self.index[w as usize])
                        .filter(|&i| i != u32::MAX),
                );
                r
            })
            .collect();
        SparseSolver::new(&rows).map_err(MeshMorphError::Solver)
    }

    /// Solves for the interior given one weight row per interior vertex
    /// (aligned with its fan); `points` holds the boundary and receives the
    /// interior.
    pub(crate) fn solve_weights(
        &self,
        solver: &mut SparseSolver,
        weights: &[Vec<f64>],
        points: &mut [Point],
    ) -> Result<(), MeshMorphError> {
        let mut values = Vec::new();
        let mut rhs = vec![Point::ZERO; self.interior.len()];
        for (k, &v) in self.interior.iter().enumerate() {
            values.push(1.0);
            for (&w, &l) in self.topo.fan[v as usize].iter().zip(&weights[k]) {
                let i = self.index[w as usize];
                if i == u32::MAX {
                    rhs[k] += l * points[w as usize];
                } else {
                    values.push(-l);
                }
            }
        }
        debug_assert_eq!(solver.len(), rhs.len());
        solver
            .solve(&values, &mut rhs)
            .map_err(MeshMorphError::Solver)?;
        for (k, &v) in self.interior.iter().enumerate() {
            points[v as usize] = rhs[k];
        }
        Ok(())
    }

    /// Weight rows of every interior vertex of `t`.
    pub(crate) fn weights_of(&self, tiling: &Tiling, kind: Weights) -> Vec<Vec<f64>> {
        self.interior
            .iter()
            .map(|&v| kind.of(tiling.points[v as usize], &self.ring(v, &tiling.points)))
            .collect()
    }

    /// Sector angles and edge lengths of every interior star of `t`.
    fn angles_of(&self, tiling: &Tiling) -> Vec<(Vec<f64>, Vec<f64>)> {
        self.interior
            .iter()
            .map(|&v| coords::star_angles(tiling.points[v as usize], &self.ring(v, &tiling.points)))
            .collect()
    }

    pub(crate) fn frame(&self, t: f64, points: Vec<Point>) -> MeshFrame {
        let valid = faces_strictly_convex(&points, &self.a.faces);
        MeshFrame { t, points, valid }
    }
}

/// Monotone cubic Hermite interpolation through `(0, v0)`, `(tm, vm)`,
/// `(1, v1)` (Fritsch–Butland slopes): each piece stays between its end
/// values.
pub(crate) fn interpolate3(v0: f64, vm: f64, v1: f64, tm: f64, t: f64) -> f64 {
    let (h0, h1) = (tm, 1.0 - tm);
    let (d0, d1) = ((vm - v0) / h0, (v1 - vm) / h1);
    let mid = if d0 * d1 <= 0.0 {
        0.0
    } else {
        let (w1, w2) = (2.0 * h1 + h0, h1 + 2.0 * h0);
        (w1 + w2) / (w1 / d0 + w2 / d1)
    };
    let hermite = |x0: f64, x1: f64, y0: f64, y1: f64, m0: f64, m1: f64, x: f64| {
        let h = x1 - x0;
        let s = (x - x0) / h;
        let (s2, s3) = (s * s, s * s * s);
        (2.0 * s3 - 3.0 * s2 + 1.0) * y0
            + (s3 - 2.0 * s2 + s) * h * m0
            + (-2.0 * s3 + 3.0 * s2) * y1
            + (s3 - s2) * h * m1
    };
    if t <= tm {
        hermite(0.0, tm, v0, vm, d0, mid, t)
    } else {
        hermite(tm, 1.0, vm, v1, mid, d1, t)
    }
}

/// Morphs tiling `a` into the compatible tiling `b` with `method`, one frame
/// per entry of `times`.
///
/// # Examples
///
/// ```
/// use immerse_mesh::mesh_morph::{mesh_morph, Method, MeshMorphOptions};
/// use immerse_mesh::tiling::Tiling;
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let faces = r#""faces": [[0,1,4],[1,2,4],[2,3,4],[3,0,4]]"#;
/// let a = Tiling::from_json_str(&format!(r#"{{"points": [[0,0],[1,0],[1,1],[0,1],[0.3,0.3]], {faces}}}"#))?;
/// let b = Tiling::from_json_str(&format!(r#"{{"points": [[0,0],[1,0],[1,1],[0,1],[0.7,0.6]], {faces}}}"#))?;
/// let frames = mesh_morph(&a, &b, Method::Convex, &[0.0, 0.5, 1.0], &MeshMorphOptions::DEFAULT)?;
/// assert!(frames.iter().all(|f| f.valid));
/// assert!((frames[2].points[4] - b.points[4]).length() < 1e-12);
/// # Ok(())
/// # }
/// ```
///
/// # Errors
///
/// [`MeshMorphError`] when an input is not a tiling, the tilings are not
/// compatible, the boundaries differ and one is not star-shaped about its
/// barycentre (not for `linear`), a time is outside [0, 1], or an option is
/// out of range.
pub fn mesh_morph(
    a: &Tiling,
    b: &Tiling,
    method: Method,
    times: &[f64],
    opts: &MeshMorphOptions,
) -> Result<Vec<MeshFrame>, MeshMorphError> {
    if let Some((index, &t)) = times
        .iter()
        .enumerate()
        .find(|(_, t)| !(0.0..=1.0).contains(*t))
    {
        return Err(MeshMorphError::BadTime { index, t });
    }
    let problem = Problem::new(a, b, method != Method::Linear)?;
    let mid = match &opts.intermediate {
        None => None,
        Some(m) => {
            if !matches!(method, Method::Convex | Method::Intrinsic) {
                return Err(MeshMorphError::Intermediate {
                    reason: format!("works with convex and intrinsic, not {method}"),
                });
            }
            if !(opts.intermediate_t > 0.0 && opts.intermediate_t < 1.0) {
                return Err(MeshMorphError::Intermediate {
                    reason: format!("time {} is not in (0, 1)", opts.intermediate_t),
                });
            }
            validate_topology(m).map_err(|source| MeshMorphError::Tiling {
                which: "intermediate",
                source,
            })?;
            compatible(a, m).map_err(|reason| MeshMorphError::Incompatible {
                which: "intermediate",
                reason,
            })?;
            let same = problem.same_boundary()
                && problem
                    .topo
                    .boundary
                    .iter()
                    .all(|&v| m.points[v as usize] == a.points[v as usize]);
            if !same {
                return Err(MeshMorphError::Intermediate {
                    reason: "needs the same boundary as the source and the target".into(),
                });
            }
            Some((m, opts.intermediate_t))
        }
    };
    match method {
        Method::Linear => Ok(times
            .iter()
            .map(|&t| {
                let pts = a
                    .points
                    .iter()
                    .zip(&b.points)
                    .map(|(p, q)| p.lerp(*q, t))
                    .collect();
                problem.frame(t, pts)
            })
            .collect()),
        Method::Convex => {
            let mut solver = problem.weight_solver()?;
            let w0 = problem.weights_of(a, opts.weights);
            let w1 = problem.weights_of(b, opts.weights);
            let wm = mid.map(|(m, tm)| (problem.weights_of(m, opts.weights), tm));
            times
                .iter()
                .map(|&t| {
                    let rows: Vec<Vec<f64>> = (0..w0.len())
                        .map(|k| {
                            let row: Vec<f64> = match &wm {
                                None => w0[k]
                                    .iter()
                                    .zip(&w1[k])
                                    .map(|(x, y)| lerp(*x, *y, t))
                                    .collect(),
                                Some((wm, tm)) => (0..w0[k].len())
                                    .map(|j| interpolate3(w0[k][j], wm[k][j], w1[k][j], *tm, t))
                                    .collect(),
                            };
                            let s: f64 = row.iter().sum();
                            row.iter().map(|x| x / s).collect()
                        })
                        .collect();
                    let mut pts = problem.boundary_at(t);
                    problem.solve_weights(&mut solver, &rows, &mut pts)?;
                    Ok(problem.frame(t, pts))
                })
                .collect()
        }
        Method::Intrinsic => {
            let mut solver = problem.weight_solver()?;
            let s0 = problem.angles_of(a);
            let s1 = problem.angles_of(b);
            let sm = mid.map(|(m, tm)| (problem.angles_of(m), tm));
            times
                .iter()
                .map(|&t| {
                    let rows: Vec<Vec<f64>> = (0..s0.len())
                        .map(|k| {
                            let mix = |x: &[f64], y: &[f64], z: Option<&[f64]>| -> Vec<f64> {
                                (0..x.len())
                                    .map(|j| match (z, &sm) {
                                        (Some(z), Some((_, tm))) => {
                                            interpolate3(x[j], z[j], y[j], *tm, t)
                                        }
                                        _ => lerp(x[j], y[j], t),
                                    })
                                    .collect()
                            };
                            let zm = sm.as_ref().map(|(s, _)| &s[k]);
                            let angles = mix(&s0[k].0, &s1[k].0, zm.map(|z| z.0.as_slice()));
                            let lengths = mix(&s0[k].1, &s1[k].1, zm.map(|z| z.1.as_slice()));
                            coords::mean_value_from_angles(&angles, &lengths)
                        })
                        .collect();
                    let mut pts = problem.boundary_at(t);
                    problem.solve_weights(&mut solver, &rows, &mut pts)?;
                    Ok(problem.frame(t, pts))
                })
                .collect()
        }
        Method::Power => power::morph(&problem, times, opts),
        Method::Local => local::morph(&problem, times, opts),
    }
}
