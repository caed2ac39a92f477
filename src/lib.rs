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
//! re-exports the `immerse-base` crate's (with `input`, its capped file
//! reading), which `immerse-mesh` shares.
//!
//! Between frames, players move every vertex on a straight line;
//! [`certify`] decides exactly whether such a segment stays an immersed
//! disk for every s (docs/design.md §13), with margins for players that
//! interpolate in `f64` or `f32`.
//!
//! ## Features
//!
//! - `cli` (default): the `immerse` command-line tool and its rendering,
//!   progress and argument-parsing dependencies; the option enums
//!   (`Quality`, `morph::ThirdVertexPath`, `morph::Correspondence`, ...)
//!   derive `clap::ValueEnum`, so the command line parses them directly.
//!   Without it the library has no rendering or CLI dependency.
//!
//! ## The front door
//!
//! [`Tween`] morphs two keys, [`Sequence`] many; both plan once and then
//! give their certified keyframes (the animation is their piecewise-linear
//! interpolation, every segment certified exactly, docs/design.md §13)
//! and verified frames at any t:
//!
//! ```
//! use immerse::{CurveMorphOptions, Key, Point, Sequence, SequenceOptions, Tween};
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(x, y)| Point::new(x, y));
//! let diamond = [(0.5, -0.2), (1.2, 0.5), (0.5, 1.2), (-0.2, 0.5)].map(|(x, y)| Point::new(x, y));
//! let tween = Tween::new(&square, &diamond, &CurveMorphOptions::DEFAULT)?;
//! assert!(tween.is_certified());
//! let keys = tween.keyframes();
//! assert!(keys.len() >= 2 && keys[0].t == 0.0 && keys[keys.len() - 1].t == 1.0);
//! assert!(tween.frame(0.5)?.is_immersion());
//!
//! let chain = [Key::new("a", square.to_vec()), Key::new("b", diamond.to_vec()), Key::new("c", square.to_vec())];
//! let sequence = Sequence::new(&chain, &[], &SequenceOptions::DEFAULT)?;
//! assert_eq!(sequence.key_count(), 3);
//! # Ok(())
//! # }
//! ```
//!
//! Two curves that already share a triangulation (a compatible pair, the
//! seed papers' setting) are morphed without planning by
//! [`morph::Compatible::new`] and [`morph::Compatible::morph`].
//!
//! ## Reading a curve
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
mod error;
mod flip;
pub mod frames;
pub mod geom;
mod immersion;
pub mod morph;
mod options;
mod propagate;
mod quality;
pub mod sequence;
mod staged;
#[cfg(test)]
mod testing;
mod tree;

pub use curve::Curve;
pub use error::{Error, Result};
pub use geom::Point;
pub use immersion::{
    Immersion, ImmersionDefect, NotSelfOverlapping, check, common_triangulation, is_valid_triangle,
    triangulate,
};
pub use morph::{CurveMorphOptions, Keyframe, Tween};
pub use quality::{
    Quality, UnknownQuality, improve, triangulate_maxmin, triangulate_with,
    triangulate_with_progress,
};
pub use sequence::{Key, Sequence, SequenceOptions};
pub use tree::{RootChoice, Spine, TreeError};
