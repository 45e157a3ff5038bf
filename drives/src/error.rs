//! Errors of the drive layer: the model crates' typed errors, passed through unchanged.

use thiserror::Error;

/// Failure to build or run a drive model.
#[derive(Debug, Error)]
pub enum DriveError {
    /// The flowing or nodal belt (`flowing`) rejected its input or failed.
    #[error(transparent)]
    Flowing(#[from] flowing::FlowError),
    /// The ANCF belt drive (`ancf`) rejected its input or failed.
    #[error(transparent)]
    Ancf(#[from] ancf::AncfError),
    /// An analytical model rejected its input (the message names the field).
    #[error("{0}")]
    Invalid(String),
    /// An analytical model has no solution at the requested operating point.
    #[error("{0}")]
    Numerical(String),
}
