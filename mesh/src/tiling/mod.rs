//! Planar tilings: points plus convex faces (triangles the common case).
//!
//! A [`Tiling`] is the pair `(U, G)` of Floater & Gotsman, *How to Morph
//! Tilings Injectively*, Definition 2.1: a point sequence and a list of faces,
//! each a counter-clockwise list of vertex indices, such that (1) every face is
//! a strictly convex polygon, (2) two faces meet in nothing, a common vertex or
//! a common edge, and (3) the faces cover the convex hull of the points.
//!
//! Reading ([`read`]) accepts Wavefront OBJ and JSON. Validation
//! ([`validate`]) decides Definition 2.1 exactly with
//! [`immerse_base::geom::predicates`]: instead of testing every pair of faces for
//! overlap (quadratic), it checks that the faces form a combinatorial disk,
//! that every face is strictly convex and counter-clockwise, that the faces
//! around every vertex wind around it exactly once, and that the boundary is
//! a convex polygon; a locally injective, orientation-preserving piecewise
//! linear map of a disk with a simple boundary is globally injective, so
//! this is equivalent and linear in the size of the tiling.
//!
//! Deviation: the boundary may have straight (collinear) corners, as in a
//! rectangular grid, while every face must be strictly convex as in the
//! paper's definition of a convex polygon.

pub mod read;
pub mod validate;

use immerse_base::geom::Point;
use std::path::PathBuf;

/// Largest number of vertices a tiling may have: bounds memory and time on
/// untrusted input.
pub const MAX_VERTICES: usize = 2_000_000;

/// Largest tiling file read, in bytes (256 MiB: room for
/// [`MAX_VERTICES`] vertices and their faces as OBJ or JSON text).
pub const MAX_FILE_BYTES: u64 = 256 << 20;

/// Largest absolute coordinate accepted (2^100): the exact tests of
/// [`crate::mesh_morph::check_linear`] multiply up to four coordinate
/// differences, which must neither overflow nor lose their exactness.
pub const MAX_COORDINATE: f64 = 1.267_650_600_228_229_4e30;

/// A planar tiling: points and convex counter-clockwise faces over them.
///
/// Built only through [`Tiling::new`], [`Tiling::from_path`],
/// [`Tiling::from_json_str`] or [`Tiling::from_obj_str`], all of which
/// validate it against Floater & Gotsman Definition 2.1.
///
/// # Examples
///
/// ```
/// use immerse_mesh::tiling::Tiling;
/// # fn main() -> Result<(), immerse_mesh::tiling::TilingError> {
/// let t = Tiling::from_json_str(
///     r#"{"points": [[0,0],[1,0],[1,1],[0,1]], "faces": [[0,1,2],[0,2,3]]}"#,
/// )?;
/// assert_eq!(t.faces.len(), 2);
/// # Ok(())
/// # }
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Tiling {
    /// Vertex positions.
    pub points: Vec<Point>,
    /// Faces, each a counter-clockwise list of indices into `points`.
    pub faces: Vec<Vec<u32>>,
}

impl Tiling {
    /// Validates `points` and `faces` (Floater & Gotsman Definition 2.1) and
    /// builds a tiling.
    ///
    /// # Errors
    ///
    /// A [`TilingError`] naming the first offending face or vertex.
    pub fn new(points: Vec<Point>, faces: Vec<Vec<u32>>) -> Result<Tiling, TilingError> {
        let tiling = Tiling { points, faces };
        validate::validate(&tiling)?;
        Ok(tiling)
    }

    /// Number of vertices.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True when the tiling has no vertices (never for a validated tiling).
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The edge neighbours of every vertex in counter-clockwise order; for a
    /// boundary vertex from the next boundary vertex round to the previous
    /// one. Empty when the faces do not form a disk.
    pub fn neighbours(&self) -> Vec<Vec<u32>> {
        validate::Topology::build(&self.faces, self.points.len())
            .map(|t| t.fan)
            .unwrap_or_default()
    }

    /// Indices of the boundary vertices in counter-clockwise order.
    pub fn boundary(&self) -> Vec<u32> {
        validate::Topology::build(&self.faces, self.points.len())
            .map(|t| t.boundary.clone())
            .unwrap_or_default()
    }
}

/// Why a tiling could not be read or is not a tiling (Floater & Gotsman
/// Definition 2.1).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum TilingError {
    /// The file could not be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
    /// The file is longer than [`MAX_FILE_BYTES`].
    #[error("{path}: too large ({size}; the limit is {limit} bytes)")]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its length, or "more than N bytes" for data read through the
        /// cap (a device, FIFO or pipe).
        size: String,
        /// The limit.
        limit: u64,
    },
    /// A problem inside a named file.
    #[error("{path}: {source}")]
    InFile {
        /// The file.
        path: PathBuf,
        /// The problem.
        #[source]
        source: Box<TilingError>,
    },
    /// The JSON text is malformed or lacks `points`/`faces`.
    #[error(
        "bad json at line {line}, column {column}: {message} (hint: expected {{\"points\": [[x,y],...], \"faces\": [[i,j,k],...]}} with 0-based indices)"
    )]
    Json {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// An OBJ line could not be parsed.
    #[error("bad obj line {line}: {message}")]
    Obj {
        /// 1-based line.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// More vertices than [`MAX_VERTICES`].
    #[error("too many vertices: {count} (at most {max} are accepted)")]
    TooManyVertices {
        /// Vertices given.
        count: usize,
        /// The limit.
        max: usize,
    },
    /// No points or no faces.
    #[error(
        "empty tiling: {points} points and {faces} faces (hint: a tiling needs at least one face)"
    )]
    Empty {
        /// Points given.
        points: usize,
        /// Faces given.
        faces: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate")]
    NonFinite {
        /// The vertex (0-based).
        vertex: usize,
    },
    /// A coordinate exceeds [`MAX_COORDINATE`] in magnitude.
    #[error("vertex {vertex} has a coordinate beyond ±{max:e} (hint: rescale the input)")]
    CoordinateTooLarge {
        /// The vertex (0-based).
        vertex: usize,
        /// The limit.
        max: f64,
    },
    /// A face has fewer than three vertices.
    #[error("face {face} has {len} vertices (hint: a face needs at least 3)")]
    FaceTooSmall {
        /// The face (0-based).
        face: usize,
        /// Its vertex count.
        len: usize,
    },
    /// A face names a vertex that does not exist.
    #[error(
        "face {face} names vertex {index}, but there are only {vertices} vertices (hint: indices are 0-based in json, 1-based in obj)"
    )]
    IndexOutOfRange {
        /// The face (0-based).
        face: usize,
        /// The bad index (0-based).
        index: i64,
        /// Vertices in the tiling.
        vertices: usize,
    },
    /// A face lists the same vertex twice.
    #[error("face {face} lists vertex {vertex} twice")]
    RepeatedVertex {
        /// The face (0-based).
        face: usize,
        /// The vertex (0-based).
        vertex: u32,
    },
    /// A face is not strictly convex and counter-clockwise at a vertex.
    #[error(
        "face {face} is not strictly convex and counter-clockwise at vertex {vertex} (hint: list each face's vertices counter-clockwise, y up, without straight corners)"
    )]
    FaceNotConvex {
        /// The face (0-based).
        face: usize,
        /// The vertex (0-based).
        vertex: u32,
    },
    /// A face turns left everywhere but winds around more than once.
    #[error(
        "face {face} winds {winding} times around its interior (hint: a face must be a simple convex polygon)"
    )]
    FaceWinds {
        /// The face (0-based).
        face: usize,
        /// Its winding number.
        winding: usize,
    },
    /// A directed edge occurs in two faces: orientations disagree or more
    /// than two faces share the edge.
    #[error(
        "face {face} repeats the directed edge {from} -> {to} of another face (hint: all faces counter-clockwise, and an edge is shared by at most two faces)"
    )]
    InconsistentEdge {
        /// The face (0-based).
        face: usize,
        /// Edge start.
        from: u32,
        /// Edge end.
        to: u32,
    },
    /// A vertex belongs to no face.
    #[error("vertex {vertex} belongs to no face")]
    UnusedVertex {
        /// The vertex (0-based).
        vertex: u32,
    },
    /// The faces around a vertex do not form a single fan.
    #[error(
        "the faces around vertex {vertex} do not form one fan (hint: the tiling must be a disk without pinched vertices)"
    )]
    NonManifoldVertex {
        /// The vertex (0-based).
        vertex: u32,
    },
    /// The faces do not form a topological disk.
    #[error(
        "the faces do not form a disk: {boundary_loops} boundary loops, euler characteristic {euler}"
    )]
    NotADisk {
        /// Number of boundary cycles.
        boundary_loops: usize,
        /// V − E + F.
        euler: i64,
    },
    /// The faces around a vertex overlap (they wind around it more than once).
    #[error("the faces around vertex {vertex} overlap (they turn {winding} times around it)")]
    Overlap {
        /// The vertex (0-based).
        vertex: u32,
        /// Turns of the fan.
        winding: usize,
    },
    /// The boundary polygon is not convex at a vertex (Definition 2.1 (3)).
    #[error(
        "the boundary is not convex at vertex {vertex} (hint: the faces must cover their convex hull)"
    )]
    BoundaryNotConvex {
        /// The vertex (0-based).
        vertex: u32,
    },
}

/// A pair of compatible triangulated `n × n` grids on the unit square with
/// `(n − 2)²` interior vertices, for benchmarks and demos: the source has
/// its interior vertices jittered by up to 0.15 of the spacing
/// (deterministic in `seed`), the target is the plain grid twisted about
/// the centre by up to 2.2 radians (an area-preserving twist, so the
/// target is valid at any resolution). Their linear morph is typically
/// invalid; the convex-combination morph is valid.
///
/// # Panics
///
/// When `n < 3` (no interior vertex) or `n² > MAX_VERTICES`.
pub fn grid_pair(n: usize, seed: u64) -> (Tiling, Tiling) {
    assert!(
        n >= 3 && n * n <= MAX_VERTICES,
        "grid size {n} out of range"
    );
    let h = 1.0 / (n - 1) as f64;
    let mut state = seed ^ 0x9E37_79B9_7F4A_7C15;
    let mut rand = move || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut a = Vec::with_capacity(n * n);
    let mut b = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let p = Point::new(i as f64 * h, j as f64 * h);
            if i == 0 || j == 0 || i == n - 1 || j == n - 1 {
                a.push(p);
                b.push(p);
                continue;
            }
            a.push(p + 0.15 * h * Point::new(2.0 * rand() - 1.0, 2.0 * rand() - 1.0));
            let d = p - Point::new(0.5, 0.5);
            let fall = (1.0 - d.length() / 0.5).max(0.0);
            let ang = 2.2 * fall * fall;
            b.push(Point::new(0.5, 0.5) + Point::from_angle(ang).rotate(d));
        }
    }
    let mut faces = Vec::with_capacity(2 * (n - 1) * (n - 1));
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let v = (j * n + i) as u32;
            let (r, u, ru) = (v + 1, v + n as u32, v + n as u32 + 1);
            faces.push(vec![v, r, ru]);
            faces.push(vec![v, ru, u]);
        }
    }
    (
        Tiling {
            points: a,
            faces: faces.clone(),
        },
        Tiling { points: b, faces },
    )
}
