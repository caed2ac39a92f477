//! # immerse
//!
//! Tween closed curves that may cross themselves, so that every in-between
//! is again the boundary of an immersed disk.
//!
//! A closed polygon with turning number +1 is *self-overlapping* when it is
//! the boundary of an immersed disk: a disk mapped into the plane so that it
//! may overlap itself but is never folded or turned inside out. immerse
//! reads such curves, decides self-overlap exactly, triangulates the disk
//! and morphs it triangle by triangle.
//!
//! ## Pipeline
//!
//! ```text
//! curve file ──> curve (parse, clean, orient) ──> immersion (DP triangulation)
//!   ──> quality ──> tree ──> correspond ──> morph ──> frames
//! ```
//!
//! Every stage uses [`geom`] for positions and exact predicates; [`geom`]
//! and [`input`] (capped file reading) re-export the `immerse-base` crate,
//! which `immerse-mesh` shares.
//!
//! Between frames, players move every vertex on a straight line;
//! [`certify`] decides exactly whether such a segment stays an immersed
//! disk for every s (docs/design.md §13), with margins for players that
//! interpolate in `f64` or `f32`.
//!
//! ## Features
//!
//! - `cli` (default): the `immerse` command-line tool and its rendering,
//!   progress and argument-parsing dependencies. Without it the library has
//!   no rendering or CLI dependency.
//!
//! ## Example
//!
//! ```
//! use immerse::curve::Curve;
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! // A square given clockwise is reversed to counter-clockwise on reading.
//! let curve = Curve::from_json_str("[[0,0],[0,1],[1,1],[1,0]]", "square.json")?;
//! assert!(curve.reversed);
//! assert_eq!(curve.points.len(), 4);
//! # Ok(())
//! # }
//! ```
//!
//! ## Mesh family
//!
//! Morphs of compatible planar tilings (docs/design.md §9) are a product of
//! their own, the `immerse-mesh` crate of this workspace; the `immerse`
//! binary's `mesh-morph` command runs them.
#![deny(rustdoc::broken_intra_doc_links)]

pub mod certify;
pub mod correspond;
pub mod curve;
pub mod drawing;
pub mod error;
pub mod flip;
pub mod frames;
pub mod geom;
pub mod immersion;
pub mod input;
pub mod morph;
pub mod quality;
pub mod sequence;
pub mod tree;

pub use curve::Curve;
pub use error::{Error, Result};
pub use geom::Point;
pub use immersion::{Immersion, ImmersionDefect, NotSelfOverlapping, triangulate};
pub use quality::{Quality, improve, triangulate_maxmin, triangulate_with};
