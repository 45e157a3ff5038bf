//! Pieces shared by the studies: error mapping, validation helpers, model building.

use flowing::{AxialMotion, DerivativeMethod};
use flowing::{FlowError, FlowingString, GalerkinString, StringConfig, StringMesh};
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

/// Checks the string parameters, naming the offending field.
pub fn check_string(p: &StringConfig, prefix: &str) -> Result<(), InputError> {
    for (name, v) in [
        ("length", p.length),
        ("density", p.density),
        ("area", p.area),
        ("tension", p.tension),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(InputError::new(
                format!("{prefix}.{name}"),
                format!("must be a positive number, got {v}"),
            ));
        }
    }
    Ok(())
}

/// Checks that `v` is finite (and non-negative if `non_negative`).
pub fn check_number(field: &str, v: f64, non_negative: bool) -> Result<(), InputError> {
    if !v.is_finite() || (non_negative && v < 0.0) {
        return Err(InputError::new(
            field,
            format!(
                "must be a finite{} number, got {v}",
                if non_negative { " non-negative" } else { "" }
            ),
        ));
    }
    Ok(())
}

/// Checks `nodes ≥ 3` and `1 ≤ modes ≤ nodes`.
pub fn check_nodes_modes(nodes: usize, modes: usize) -> Result<(), InputError> {
    if nodes < 3 {
        return Err(InputError::new(
            "nodes",
            format!("needs at least 3 interior nodes, got {nodes}"),
        ));
    }
    if modes == 0 || modes > nodes {
        return Err(InputError::new(
            "modes",
            format!("must be between 1 and nodes = {nodes}, got {modes}"),
        ));
    }
    Ok(())
}

/// The string mesh of `nodes` interior nodes and its flowing-material model with `modes` modes.
pub fn flowing_model(
    p: StringConfig,
    nodes: usize,
    modes: usize,
    method: DerivativeMethod,
    speed: f64,
) -> Result<(StringMesh, FlowingString), StudyError> {
    let mesh = StringMesh::uniform(p, nodes).map_err(study_error)?;
    let basis = mesh.modes(modes).map_err(study_error)?;
    let sys = FlowingString::new(
        &mesh.mass_sys(),
        basis,
        &[mesh.flow_line()],
        method,
        AxialMotion::Constant { speed },
    )
    .map_err(study_error)?;
    Ok((mesh, sys))
}

/// Eigen analysis of the Galerkin model: (damped frequencies \[Hz\], max real part \[1/s\]).
pub fn galerkin_frequencies(
    p: StringConfig,
    speed: f64,
    terms: usize,
) -> Result<(Vec<f64>, f64), StudyError> {
    let g = GalerkinString::new(p, speed, terms).map_err(study_error)?;
    let e = g.system().state_eigen().map_err(study_error)?;
    Ok((e.damped_frequencies_hz(), e.max_real_part()))
}

/// Eigen analysis of the flowing model frozen at `speed`.
pub fn flowing_frequencies(sys: &FlowingString, speed: f64) -> Result<(Vec<f64>, f64), StudyError> {
    let e = sys.frozen(speed, 0.0).state_eigen().map_err(study_error)?;
    Ok((e.damped_frequencies_hz(), e.max_real_part()))
}
