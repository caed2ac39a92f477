//! # immerse-base
//!
//! What both immerse products stand on: the curve library `immerse` and the
//! mesh family `immerse-mesh` take their positions, exact predicates and
//! file reading from here, and from nowhere else.
//!
//! - [`geom`]: the point type, the exact orientation, in-circle and
//!   fan-angle predicates (the only caller of the `robust` crate) and
//!   polygon measures (docs/design.md §3).
//! - [`input`]: reading an input file through a size cap, so that no file,
//!   device or pipe is read past its limit (the limits: docs/design.md §2).
//!
//! `immerse` re-exports both modules, so `immerse::geom` and
//! `immerse::input` name the same items.
//!
//! ```
//! use immerse_base::geom::{Orientation, Point, orient};
//! let turn = orient(Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(0.0, 1.0));
//! assert_eq!(turn, Orientation::CounterClockwise);
//! ```
#![deny(rustdoc::broken_intra_doc_links)]

pub mod geom;
pub mod input;
