//! # immerse
//!
//! Tween closed curves that may cross themselves, so that every in-between
//! is again the boundary of an immersed disk.
//!
//! ## Mesh family
//!
//! Compatible planar tilings (DESIGN.md §9) are read and validated by
//! [`tiling`], their interior vertices written as convex combinations by
//! [`coords`], and morphed by [`mesh_morph::mesh_morph`] with the
//! guaranteed-injective convex-combination methods of Floater & Gotsman,
//! Surazhsky & Gotsman (convex, intrinsic, power, local), or linearly;
//! [`mesh_morph::check_linear`] decides exactly whether the linear morph
//! is valid.
//!
//! ```
//! use immerse::mesh_morph::{mesh_morph, MeshMorphOptions, Method};
//! use immerse::tiling::grid_pair;
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let (a, b) = grid_pair(8, 1);
//! let frames = mesh_morph(&a, &b, Method::Convex, &[0.0, 0.5, 1.0], &MeshMorphOptions::DEFAULT)?;
//! assert!(frames.iter().all(|f| f.valid));
//! # Ok(())
//! # }
//! ```
#![deny(rustdoc::broken_intra_doc_links)]

pub mod geom;

pub use geom::Point;
pub mod coords;
pub mod mesh_morph;
mod solve;
pub mod tiling;
