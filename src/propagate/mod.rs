//! One compatible morph under a fixed triangulation (docs/design.md §6):
//! every triangle's third vertex moves along a path in its base frame
//! (`paths`, the as-rigid-as-possible guide in `rigid`), and the vertices
//! are laid out along the dual tree from a root (`layout`, `compatible`).
//! Also the error of such a morph ([`MorphError`]), which every stage
//! above reports with; `crate::morph` re-exports it.

pub(crate) mod compatible;
pub(crate) mod layout;
pub(crate) mod paths;
pub(crate) mod rigid;

use compatible::CompatibleError;
use paths::ThirdVertexPath;

/// Why a morph failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MorphError {
    /// The pair could not be set up for a compatible morph.
    #[error(transparent)]
    Compatible(#[from] CompatibleError),
    /// A frame of a guaranteed path failed the exact immersion check: a
    /// bug in immerse.
    #[error(
        "frame at t = {t} of the {path} path is not an immersion ({defect}); this is a bug in immerse, please report it with the two curves"
    )]
    InvalidFrame {
        /// The frame's parameter.
        t: f64,
        /// The path that produced it.
        path: ThirdVertexPath,
        /// What the checker found.
        defect: String,
    },
    /// A frame was asked for at a parameter that is not in [0, 1].
    #[error("frame parameter {0} is not a number in [0, 1]")]
    Fraction(f64),
}

impl MorphError {
    /// What went wrong, without the request to report a bug: for a
    /// failure that a recovery then got around (a fallback's reason).
    pub(crate) fn reason(&self) -> String {
        match self {
            MorphError::InvalidFrame { t, path, defect } => {
                format!("frame at t = {t} of the {path} path is not an immersion ({defect})")
            }
            other => other.to_string(),
        }
    }
}
