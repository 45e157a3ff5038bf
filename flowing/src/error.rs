//! Typed errors of the flowing-material layer.

use thiserror::Error;

/// Errors raised while building flow grids, derivative operators and flowing-material models.
///
/// Every message names the offending item (grid, node, field, mode) so that an app can print it
/// as a one-line diagnostic.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FlowError {
    /// A parameter or input array is invalid.
    #[error("invalid input for {item}: {reason}")]
    InvalidInput {
        /// What was wrong (e.g. `flow grid: node 3 position`).
        item: String,
        /// Why it is rejected.
        reason: String,
    },
    /// A derivative method cannot be used on this grid (e.g. FFT on a non-uniform grid).
    #[error("derivative method {method} cannot be used here: {reason}")]
    MethodNotApplicable {
        /// The method's name.
        method: &'static str,
        /// Why not.
        reason: String,
    },
    /// A dense factorisation or eigen decomposition failed.
    #[error("linear algebra failure in {what}: {reason}")]
    LinearAlgebra {
        /// Which computation.
        what: String,
        /// Solver message.
        reason: String,
    },
    /// An error of the multibody layer (integrator, model).
    #[error(transparent)]
    Mbd(#[from] mbd_core::MbdError),
}

/// Shorthand for an [`FlowError::InvalidInput`].
pub(crate) fn invalid(item: impl Into<String>, reason: impl Into<String>) -> FlowError {
    FlowError::InvalidInput {
        item: item.into(),
        reason: reason.into(),
    }
}

impl From<fe_model::FeError> for FlowError {
    fn from(e: fe_model::FeError) -> Self {
        FlowError::InvalidInput {
            item: "finite-element model".into(),
            reason: e.to_string(),
        }
    }
}

impl From<mbd_core::InvalidField> for FlowError {
    fn from(e: mbd_core::InvalidField) -> Self {
        FlowError::InvalidInput {
            item: e.field,
            reason: e.reason,
        }
    }
}
