//! Pieces shared by the studies: their command-line flags and the error mapping.

use flowing::FlowError;
use flowmbd_cli::{InputError, StudyError, set_given};

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
        set_given(nodes, self.nodes);
        set_given(modes, self.modes);
    }
}

/// The axial speed on the command line of the `modes`, `simulate` and `wrap` studies
/// (`--speed`): given, it replaces the configuration's.
#[derive(clap::Args, Debug, Clone, Copy, Default)]
pub struct SpeedArg {
    /// Axial speed [m/s].
    #[arg(long)]
    pub speed: Option<f64>,
}

impl SpeedArg {
    /// Replace `speed` (a configuration's) by the value given.
    pub fn apply(&self, speed: &mut f64) {
        set_given(speed, self.speed);
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
