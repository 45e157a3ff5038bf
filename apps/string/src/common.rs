//! Pieces shared by the studies: error mapping, validation helpers, model building.

use flowing::string_study::{self, Spectrum};
use flowing::{FlowError, FlowingString};
use flowmbd_cli::{InputError, StudyError};

/// The flowing-material model's discretisation on the command line of the `modes` and `sweep`
/// studies (`--nodes`, `--modes`): each given value replaces the configuration's.
#[derive(clap::Args, Debug, Clone, Copy, Default)]
pub struct ModelArgs {
    /// Interior FE nodes.
    #[arg(long)]
    pub nodes: Option<usize>,
    /// Retained modes of the flowing-material model.
    #[arg(long)]
    pub modes: Option<usize>,
}

impl ModelArgs {
    /// Replace `nodes` and `modes` (a configuration's) by the values given.
    pub fn apply(&self, nodes: &mut usize, modes: &mut usize) {
        if let Some(n) = self.nodes {
            *nodes = n;
        }
        if let Some(k) = self.modes {
            *modes = k;
        }
    }
}

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
    MAX_STRING_NODES, Regime, check_nodes_modes, check_number, check_scales, check_steps,
    check_string,
};

/// Eigen analysis of the flowing model frozen at `speed`
/// ([`flowing::string_study::flowing_spectrum`]).
pub fn flowing_spectrum(sys: &FlowingString, speed: f64) -> Result<Spectrum, StudyError> {
    string_study::flowing_spectrum(sys, speed).map_err(study_error)
}
