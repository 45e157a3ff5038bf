//! Typed errors of the reduction layer.

use thiserror::Error;

/// Errors raised while building, applying, saving or loading a reduction.
///
/// Every message names what was wrong and where (matrix, DOF, node, field, file).
#[derive(Debug, Error)]
pub enum ReductionError {
    /// A matrix has the wrong shape.
    #[error("{what}: expected a {expected} matrix, got {rows}x{cols}")]
    Shape {
        /// Which matrix (e.g. `mass matrix`).
        what: String,
        /// Expected shape in words (e.g. `10x10`).
        expected: String,
        /// Actual number of rows.
        rows: usize,
        /// Actual number of columns.
        cols: usize,
    },
    /// A DOF or node index is out of range, repeated, or otherwise invalid.
    #[error("invalid {what}: {reason}")]
    InvalidDofs {
        /// Which set (e.g. `boundary DOF set`).
        what: String,
        /// Why it is rejected.
        reason: String,
    },
    /// A parameter is invalid (number of modes, tolerance, ...).
    #[error("invalid parameter {name}: {reason}")]
    InvalidParameter {
        /// Parameter name.
        name: String,
        /// Why it is rejected.
        reason: String,
    },
    /// A matrix that must be positive definite is not (e.g. `K_ii` with too few boundary DOFs).
    #[error("{what} is not positive definite: {hint}")]
    NotPositiveDefinite {
        /// Which matrix.
        what: String,
        /// What to check.
        hint: String,
    },
    /// A linear solve or eigen solve failed.
    #[error("numerical failure in {what}: {detail}")]
    Numerical {
        /// Which step.
        what: String,
        /// Details.
        detail: String,
    },
    /// Reading or writing a reduced-model file failed.
    #[error("file {path}: {reason}")]
    File {
        /// File path.
        path: String,
        /// What went wrong (I/O error, parse error with line/column, version mismatch).
        reason: String,
    },
}

/// Shorthand result type of the crate.
pub type Result<T> = std::result::Result<T, ReductionError>;
