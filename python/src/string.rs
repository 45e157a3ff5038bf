//! `flowmbd.string`: the travelling-string modes study of Ribaric §4.2.3 through
//! [`flowing::string_study`] (the same as `flowmbd-string modes`).

use crate::{input_error, numerical_error, read_config, to_json};
use flowing::FlowError;
use flowing::string_study::{ModesConfig, string_modes as run};
use mbd_core::{InvalidField, Validate};
use pyo3::prelude::*;

/// Damped natural frequencies of the Galerkin (4.29) and flowing-material (4.20) models;
/// returns the JSON text of the summary. `speed`, `nodes`, `modes` replace the configuration's
/// fields (like the CLI's flags).
#[pyfunction]
#[pyo3(signature = (config=None, speed=None, nodes=None, modes=None))]
pub fn string_modes(
    py: Python<'_>,
    config: Option<&str>,
    speed: Option<f64>,
    nodes: Option<usize>,
    modes: Option<usize>,
) -> PyResult<String> {
    let mut c: ModesConfig = read_config(config)?;
    if let Some(v) = speed {
        c.speed = v;
    }
    if let Some(n) = nodes {
        c.nodes = n;
    }
    if let Some(k) = modes {
        c.modes = k;
    }
    c.validate().map_err(input_error)?;
    match py.detach(|| run(&c)) {
        Ok(summary) => to_json(&summary),
        // the classification of the app (apps/string/src/common.rs: study_error)
        Err(FlowError::InvalidInput { item, reason }) => {
            Err(input_error(InvalidField::new(item, reason)))
        }
        Err(FlowError::MethodNotApplicable { method, reason }) => Err(input_error(
            InvalidField::new("derivative", format!("{method}: {reason}")),
        )),
        Err(e) => Err(numerical_error(py, e.to_string(), None)),
    }
}
