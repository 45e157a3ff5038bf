//! Typed errors of the fe-model crate.

use thiserror::Error;

/// Errors of model building, assembly, exchange and eigen solution.
///
/// Every message says what was wrong and where (file, line, element, DOF).
#[derive(Debug, Error)]
pub enum FeError {
    /// Two matrices (or a matrix and a vector) have incompatible shapes.
    #[error("dimension mismatch in {context}: expected {expected}, got {got}")]
    Dimension {
        /// Where the mismatch was found.
        context: String,
        /// Expected size.
        expected: usize,
        /// Actual size.
        got: usize,
    },
    /// A parameter is outside its valid range.
    #[error("invalid parameter `{name}` = {value}: {reason}")]
    InvalidParameter {
        /// Parameter (field) name.
        name: String,
        /// Offending value.
        value: f64,
        /// Why it is invalid.
        reason: String,
    },
    /// An element refers to something invalid (degenerate geometry, unknown node, ...).
    #[error("element {element}: {reason}")]
    Element {
        /// Element index.
        element: usize,
        /// What is wrong.
        reason: String,
    },
    /// A DOF or node index is out of range.
    #[error("{context}: index {index} out of range (size {size})")]
    Index {
        /// Where the index was used.
        context: String,
        /// Offending index.
        index: usize,
        /// Valid size.
        size: usize,
    },
    /// A matrix that must be symmetric positive definite is not (Cholesky failed).
    #[error("matrix `{name}` is not positive definite{detail}")]
    NotPositiveDefinite {
        /// Matrix name (e.g. "M", "K - sigma M").
        name: String,
        /// Extra information (e.g. the shift).
        detail: String,
    },
    /// An eigen solver did not converge or failed a safeguard check.
    #[error("eigen solver: {0}")]
    Eigen(String),
    /// Error while parsing an exchange file, with the 1-based line number.
    #[error("{file}:{line}: {reason}")]
    Parse {
        /// File name (or "<input>").
        file: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// I/O error with the file it concerns.
    #[error("{file}: {source}")]
    Io {
        /// File name.
        file: String,
        /// Underlying error.
        #[source]
        source: std::io::Error,
    },
    /// A named item (node set, field, ...) does not exist.
    #[error("unknown {what} `{name}` (known: {known})")]
    Unknown {
        /// Kind of item.
        what: String,
        /// Requested name.
        name: String,
        /// Known names.
        known: String,
    },
    /// A faer sparse structure could not be created.
    #[error("sparse matrix creation failed in {0}")]
    Sparse(String),
}

impl FeError {
    /// Shorthand for [`FeError::InvalidParameter`].
    pub fn param(name: &str, value: f64, reason: &str) -> Self {
        FeError::InvalidParameter {
            name: name.to_string(),
            value,
            reason: reason.to_string(),
        }
    }

    /// Check that a parameter is finite and strictly positive.
    pub fn check_positive(name: &str, value: f64) -> Result<f64, Self> {
        if value.is_finite() && value > 0.0 {
            Ok(value)
        } else {
            Err(Self::param(name, value, "must be finite and > 0"))
        }
    }

    /// Check that a parameter is finite and non-negative.
    pub fn check_non_negative(name: &str, value: f64) -> Result<f64, Self> {
        if value.is_finite() && value >= 0.0 {
            Ok(value)
        } else {
            Err(Self::param(name, value, "must be finite and >= 0"))
        }
    }
}
