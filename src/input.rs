//! Reading input files through a size cap, from the `immerse-base` crate
//! that `immerse-mesh` shares (the same items as `immerse_base::input`).
//!
//! Every curve file goes through [`read_capped`] (see
//! [`crate::Curve::from_path`]), as do the command line's timelines and
//! the tilings of `immerse-mesh`.

#[doc(inline)]
pub use immerse_base::input::*;
