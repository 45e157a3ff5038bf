//! Typed errors of the ANCF layer.

use mbd_core::MbdError;
use thiserror::Error;

/// Errors raised while building or solving an ANCF model.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum AncfError {
    /// A model parameter is invalid; `item` names it (e.g. `element 3: length`).
    #[error("invalid input for {item}: {reason}")]
    InvalidInput {
        /// What was wrong (element, node, field).
        item: String,
        /// Why it is rejected.
        reason: String,
    },
    /// The static Newton iteration did not converge.
    #[error(
        "static Newton iteration did not converge at load factor {load_factor} after {iterations} iterations (residual {residual:e} N)"
    )]
    NoConvergence {
        /// Load factor of the failing increment (0..1].
        load_factor: f64,
        /// Iterations performed in that increment.
        iterations: usize,
        /// Last residual norm \[N\].
        residual: f64,
    },
    /// The tangent stiffness could not be factored (mechanism, missing supports).
    #[error("singular tangent stiffness at load factor {load_factor}: {detail}")]
    Singular {
        /// Load factor of the failing increment.
        load_factor: f64,
        /// Details from the factorization.
        detail: String,
    },
    /// The contact active set did not settle within the allowed passes.
    #[error(
        "contact active set did not settle at load factor {load_factor} after {passes} passes (use more load increments)"
    )]
    ActiveSet {
        /// Load factor of the failing increment.
        load_factor: f64,
        /// Active-set passes performed.
        passes: usize,
    },
    /// A state contains NaN or infinity.
    #[error("non-finite value in {what}")]
    NonFinite {
        /// Which quantity.
        what: String,
    },
    /// An error from the multibody layer (integrators).
    #[error(transparent)]
    Mbd(#[from] MbdError),
}

pub(crate) fn invalid(item: impl Into<String>, reason: impl Into<String>) -> AncfError {
    AncfError::InvalidInput {
        item: item.into(),
        reason: reason.into(),
    }
}

/// Reject a parameter that is not finite and strictly positive: the error names `item` and
/// says `must be > 0{unit}, got {value}`, where `unit` is the SI unit with its leading space
/// (`" m"`) or `""` for a dimensionless value.
pub(crate) fn check_positive(
    item: impl Into<String>, value: f64, unit: &str,
) -> Result<(), AncfError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(invalid(item, format!("must be > 0{unit}, got {value}")))
    }
}

impl From<mbd_core::InvalidField> for AncfError {
    fn from(e: mbd_core::InvalidField) -> Self {
        AncfError::InvalidInput {
            item: e.field,
            reason: e.reason,
        }
    }
}
