//! Errors of the library, one enum per stage, gathered in [`Error`].
//!
//! Three kinds are kept apart: bad input (the caller can fix the file or
//! the arguments), a negative answer (for example a curve that is not
//! self-overlapping: a result, not a failure) and a broken internal
//! invariant (a bug in immerse; the message says so).

use crate::curve::CurveError;

/// Any error of the library.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A curve could not be read or is degenerate.
    #[error(transparent)]
    Curve(#[from] CurveError),
}

/// The library's result type.
pub type Result<T, E = Error> = std::result::Result<T, E>;
