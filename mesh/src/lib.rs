//! # immerse-mesh
//!
//! Morph compatible planar tilings so that every in-between is again a
//! tiling (docs/design.md §9).
//!
//! Two tilings are *compatible* when they share their faces: the same
//! vertex count and the same faces in the same order. A tiling is read and
//! validated exactly by [`tiling`], its interior vertices are written as
//! convex combinations of their neighbours by [`coords`], and
//! [`mesh_morph::mesh_morph`] morphs it with the guaranteed-injective
//! convex-combination methods of Floater & Gotsman and Surazhsky & Gotsman
//! (convex, intrinsic, power, local), or linearly;
//! [`mesh_morph::check_linear`] decides exactly whether the linear morph is
//! valid.
//!
//! ## Pipeline
//!
//! ```text
//! tiling file ──> tiling (read, validate exactly) ──> coords (barycentric weights)
//!   ──> mesh_morph (linear | convex | intrinsic | power | local), through solve
//!   ──> MeshFrame (points + exact `valid` flag)
//! ```
//!
//! Positions and exact orientation predicates come from
//! [`immerse_base::geom`], tiling files are read through
//! [`immerse_base::input::read_capped`]; the sparse systems of the convex
//! combination methods are solved by a private module on `faer`'s sparse
//! LU and a multigrid-preconditioned iteration.
//!
//! ## Example
//!
//! ```
//! use immerse_mesh::mesh_morph::{mesh_morph, MeshMorphOptions, Method};
//! use immerse_mesh::tiling::grid_pair;
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let (a, b) = grid_pair(8, 1);
//! let frames = mesh_morph(&a, &b, Method::Convex, &[0.0, 0.5, 1.0], &MeshMorphOptions::DEFAULT)?;
//! assert!(frames.iter().all(|f| f.valid));
//! # Ok(())
//! # }
//! ```
#![deny(rustdoc::broken_intra_doc_links)]

pub mod coords;
pub mod mesh_morph;
mod solve;
pub mod tiling;
