//! # immerse
//!
//! Tween closed curves that may cross themselves, so that every in-between
//! is again the boundary of an immersed disk.
#![deny(rustdoc::broken_intra_doc_links)]

pub mod geom;

pub use geom::Point;
pub mod coords;
pub mod mesh_morph;
mod solve;
pub mod tiling;
