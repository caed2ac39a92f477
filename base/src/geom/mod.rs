//! Plane geometry: the point type, the exact predicates and polygon measures.
//!
//! Positions are constructed in `f64` ([`Point`] is [`glam::DVec2`]); every
//! decision (orientation, in-circle, angle order) goes through
//! [`predicates`], the only module that calls the `robust` crate.

pub mod polygon;
pub mod predicates;

pub use predicates::{Orientation, in_circle, is_fan_order_less, orient};

/// A point or vector in the plane, y up.
pub type Point = glam::DVec2;
