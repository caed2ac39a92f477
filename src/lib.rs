//! # immerse
//!
//! Tween closed curves that may cross themselves, so that every in-between
//! is again the boundary of an immersed disk.
#![deny(rustdoc::broken_intra_doc_links)]

pub mod geom;
pub mod immersion;
pub mod quality;

pub use geom::Point;
pub use immersion::{Immersion, ImmersionDefect, NotSelfOverlapping, triangulate};
pub use quality::{Quality, improve, triangulate_maxmin, triangulate_with};
