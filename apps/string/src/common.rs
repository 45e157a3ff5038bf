//! Pieces shared by the studies: error mapping, validation helpers, model building.

use flowing::string_study;
use flowing::{DerivativeMethod, FlowError, FlowingString, StringConfig, StringMesh};
use flowmbd_cli::{InputError, StudyError};

/// Maps library errors to the app's exit-code classes (bad input: 2, numerical: 1).
pub fn study_error(e: FlowError) -> StudyError {
    match e {
        FlowError::InvalidInput { item, reason } => {
            StudyError::Input(InputError::new(item, reason))
        }
        FlowError::MethodNotApplicable { method, reason } => {
            StudyError::Input(InputError::new("derivative", format!("{method}: {reason}")))
        }
        other => StudyError::numerical(other),
    }
}

/// The shared checks, defined with the modes study in `flowing` (one set of messages).
pub use flowing::string_study::{
    MAX_GALERKIN_TERMS, MAX_STRING_NODES, check_nodes_modes, check_number, check_steps,
    check_string,
};

/// The string mesh of `nodes` interior nodes and its flowing-material model with `modes` modes
/// ([`flowing::string_study::flowing_model`]).
pub fn flowing_model(
    p: StringConfig,
    nodes: usize,
    modes: usize,
    method: DerivativeMethod,
    speed: f64,
) -> Result<(StringMesh, FlowingString), StudyError> {
    string_study::flowing_model(p, nodes, modes, method, speed).map_err(study_error)
}

/// Eigen analysis of the Galerkin model: (damped frequencies \[Hz\], max real part \[1/s\]).
pub fn galerkin_frequencies(
    p: StringConfig,
    speed: f64,
    terms: usize,
) -> Result<(Vec<f64>, f64), StudyError> {
    string_study::galerkin_frequencies(p, speed, terms).map_err(study_error)
}

/// Eigen analysis of the flowing model frozen at `speed`.
pub fn flowing_frequencies(sys: &FlowingString, speed: f64) -> Result<(Vec<f64>, f64), StudyError> {
    string_study::flowing_frequencies(sys, speed).map_err(study_error)
}
