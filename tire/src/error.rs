//! Typed errors of the reduced FE tire.

use thiserror::Error;

/// Errors of the tire model, its reduction, the rig and the reduced-tire file format.
///
/// Every message names the offending item (node, set, field, file, time) so that an app can
/// print it as a one-line diagnostic.
#[derive(Debug, Error)]
pub enum TireError {
    /// A parameter or input array is invalid.
    #[error("invalid tire input for {item}: {reason}")]
    Invalid {
        /// What was wrong (e.g. `contact nodes`).
        item: String,
        /// Why it is rejected.
        reason: String,
    },
    /// A factorisation or eigen decomposition failed.
    #[error("linear algebra failure in {what}: {reason}")]
    LinearAlgebra {
        /// Which computation.
        what: String,
        /// Solver message.
        reason: String,
    },
    /// The time integration failed (e.g. the contact problem has no solution).
    #[error("tire simulation failed at t = {time:.6} s: {reason}")]
    Simulation {
        /// Simulated time \[s\].
        time: f64,
        /// What happened.
        reason: String,
    },
    /// A reduced-tire file could not be read or written.
    #[error("reduced tire file {path}: {reason}")]
    File {
        /// File path.
        path: String,
        /// What was wrong.
        reason: String,
    },
    /// A file of an imported tire ([`super::ImportFiles`]) is unreadable or malformed:
    /// `field` is the import field naming it (`stiffness`, `nodes`, ...), `reason` starts with
    /// the file (and line).
    #[error("import.{field}: {reason}")]
    Import {
        /// The field of [`super::ImportFiles`] that names the file.
        field: &'static str,
        /// What is wrong, with the file and line.
        reason: String,
    },
    /// An imported tire that reads well but fails one of the checks of the easy mistakes
    /// ([`super::ImportCheckError`]: a diagonal or disconnected K, a patch set off the tread):
    /// `field` is the import field naming the file the check blames.
    #[error("import.{field}: {check}")]
    ImportCheck {
        /// The field of [`super::ImportFiles`] that names the file.
        field: &'static str,
        /// The failed check, with the file (and line) and the numbers that fail it.
        #[source]
        check: crate::import::ImportCheckError,
    },
    /// Error of the finite-element layer.
    #[error(transparent)]
    Fe(#[from] fe_model::FeError),
    /// Error of the flowing-material layer (derivative operators).
    #[error(transparent)]
    Flow(#[from] flowing::FlowError),
    /// Error of the reduction layer (partitioned Craig–Bampton: static and free-node modes).
    #[error(transparent)]
    Reduction(#[from] reduction::ReductionError),
}

impl From<mbd_core::InvalidField> for TireError {
    fn from(e: mbd_core::InvalidField) -> Self {
        invalid(e.field, e.reason)
    }
}

/// Shorthand for a [`TireError::Invalid`].
pub(crate) fn invalid(item: impl Into<String>, reason: impl Into<String>) -> TireError {
    TireError::Invalid {
        item: item.into(),
        reason: reason.into(),
    }
}

/// Shorthand for a [`TireError::LinearAlgebra`].
pub(crate) fn linalg(what: impl Into<String>, reason: impl std::fmt::Debug) -> TireError {
    TireError::LinearAlgebra {
        what: what.into(),
        reason: format!("{reason:?}"),
    }
}
