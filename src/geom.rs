//! Plane geometry: the point type, the exact predicates and polygon
//! measures, from the `immerse-base` crate that `immerse-mesh` shares
//! (the same items as `immerse_base::geom`).
//!
//! Positions are constructed in `f64` ([`Point`] is `glam::DVec2`); every
//! decision (orientation, in-circle, angle order) goes through
//! [`predicates`], the only module that calls the `robust` crate.

#[doc(inline)]
pub use immerse_base::geom::*;
