//! Correspondence between two curves: equal vertex counts and the compatibility
//! of two triangulations (Mukherjee & Gopi §5–6; docs/design.md §5).

mod align;
mod compat;
mod resample;

pub(crate) use align::{align, align_corners};
pub use compat::{compatible_shift, degree_sequence, from_degree_sequence, shift_triangles};
pub(crate) use resample::{apportion, apportion_among};
pub use resample::{equalize, insert_vertices, resample_arc_length};
