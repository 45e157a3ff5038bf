//! Typed errors of the multibody layer.

use thiserror::Error;

/// Errors raised while building or integrating a multibody model.
///
/// Every variant names the offending item (body, constraint, field) and, where it applies,
/// the simulation time in seconds.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MbdError {
    /// A model parameter is invalid (non-positive mass, non-unit Euler parameters, ...).
    #[error("invalid input for {item}: {reason}")]
    InvalidInput {
        /// What was wrong (e.g. `body "crank": mass`).
        item: String,
        /// Why it is rejected.
        reason: String,
    },
    /// A state contains NaN or infinity.
    #[error("non-finite value in {what} at t = {t} s")]
    NonFinite {
        /// Which quantity (e.g. `velocity of body "rod"`).
        what: String,
        /// Simulation time \[s\].
        t: f64,
    },
    /// The augmented (KKT) or Newton matrix is singular, e.g. redundant constraints.
    #[error("singular system matrix at t = {t} s: {detail}")]
    Singular {
        /// Simulation time \[s\].
        t: f64,
        /// Which constraints or DOFs are suspected.
        detail: String,
    },
    /// A Newton iteration (implicit integrator, projection, static solve) did not converge.
    #[error(
        "Newton iteration did not converge at t = {t} s after {iterations} iterations (residual {residual:e})"
    )]
    NoConvergence {
        /// Simulation time \[s\].
        t: f64,
        /// Iterations performed.
        iterations: usize,
        /// Last residual norm.
        residual: f64,
    },
    /// The adaptive step size fell below its minimum.
    #[error("step size underflow at t = {t} s (h = {h:e} s)")]
    StepSizeUnderflow {
        /// Simulation time \[s\].
        t: f64,
        /// Rejected step size \[s\].
        h: f64,
    },
    /// Writing output failed.
    #[error("cannot write {path}: {message}")]
    Io {
        /// File path.
        path: String,
        /// Underlying error.
        message: String,
    },
    /// The active set of unilateral constraints did not settle within a step
    /// ([`crate::integrators::ActiveSetStepper`]).
    #[error(
        "active set of the unilateral constraints did not settle in the step from t = {t} s after {retakes} retakes"
    )]
    ActiveSet {
        /// Start time of the step \[s\].
        t: f64,
        /// Retakes of the step.
        retakes: usize,
    },
    /// A model (implementor of [`crate::SecondOrderSystem`]) reported a failure.
    #[error("model error at t = {t} s: {message}")]
    Model {
        /// Simulation time \[s\].
        t: f64,
        /// The model's message.
        message: String,
    },
}

impl From<crate::validate::InvalidField> for MbdError {
    fn from(e: crate::validate::InvalidField) -> Self {
        MbdError::InvalidInput {
            item: e.field,
            reason: e.reason,
        }
    }
}
