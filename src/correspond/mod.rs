//! Correspondence between two curves: equal vertex counts and the
//! compatibility of two triangulations (seed 004 §5–6; DESIGN.md §5).

mod compat;
mod resample;

pub use compat::{compatible_shift, degree_sequence, from_degree_sequence, shift_triangles};
pub use resample::{equalize, insert_vertices, resample_arc_length};
