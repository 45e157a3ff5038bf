//! `flowmbd.string`: the travelling-string modes study of Ribaric §4.2.3 through
//! [`flowing::string_study`] (the same as `flowmbd-string modes`) and the speed sweep through
//! [`flowing::string_sweep`] (`flowmbd-string sweep`), the pluck transient through
//! [`flowing::string_simulate`] (`flowmbd-string simulate`) and the string wrapped on two
//! pulleys through [`flowing::string_wrap`] (`flowmbd-string wrap`).

use crate::{
    WithSeries, columns, input_error, numerical_error, study_config, to_json, with_series,
};
use flowing::FlowError;
use flowing::string_study::{ModesConfig, string_modes as run};
use mbd_core::InvalidField;
use pyo3::prelude::*;

/// Damped natural frequencies of the Galerkin (4.29) and flowing-material (4.20) models;
/// returns the JSON text of the summary. `speed`, `nodes`, `modes` replace the configuration's
/// fields (like the CLI's flags).
#[pyfunction]
#[pyo3(signature = (config=None, speed=None, nodes=None, modes=None))]
pub fn string_modes(
    py: Python<'_>, config: Option<&str>, speed: Option<f64>, nodes: Option<usize>,
    modes: Option<usize>,
) -> PyResult<String> {
    let c = study_config(config, |c: &mut ModesConfig| {
        if let Some(v) = speed {
            c.speed = v;
        }
        if let Some(n) = nodes {
            c.nodes = n;
        }
        if let Some(k) = modes {
            c.modes = k;
        }
    })?;
    match py.detach(|| run(&c)) {
        Ok(summary) => to_json(&summary),
        Err(e) => Err(flow_error(py, e)),
    }
}

/// Bad input (`ValueError`) or a numerical failure (`flowmbd.NumericalError`): the
/// classification of the app (apps/string/src/common.rs: `study_error`).
fn flow_error(py: Python<'_>, e: FlowError) -> PyErr {
    match e {
        FlowError::InvalidInput { item, reason } => input_error(InvalidField::new(item, reason)),
        FlowError::MethodNotApplicable { method, reason } => input_error(InvalidField::new(
            "derivative",
            format!("{method}: {reason}"),
        )),
        e => numerical_error(py, e.to_string(), None),
    }
}

/// The speed sweep ([`flowing::string_sweep::string_sweep`], `flowmbd-string sweep`):
/// frequencies of the Galerkin (4.29), flowing-material (4.20) and exact models from 0 to past
/// the critical speed; returns `(summary JSON text, series)` with the series `{"sweep": the
/// columns of sweep.csv}` (numpy arrays). `nodes`, `modes` replace the configuration's (the
/// CLI's `--nodes`, `--modes`).
#[pyfunction]
#[pyo3(signature = (config=None, nodes=None, modes=None))]
pub fn string_sweep<'py>(
    py: Python<'py>, config: Option<&str>, nodes: Option<usize>, modes: Option<usize>,
) -> PyResult<WithSeries<'py>> {
    use flowing::string_sweep::{SweepConfig, string_sweep as sweep, sweep_header};
    let c = study_config(config, |c: &mut SweepConfig| {
        if let Some(n) = nodes {
            c.nodes = n;
        }
        if let Some(k) = modes {
            c.modes = k;
        }
    })?;
    let mut rows: Vec<Vec<f64>> = Vec::new();
    let summary = py
        .detach(|| {
            sweep(&c, &mut |_, row| {
                rows.push(row.to_vec());
                std::ops::ControlFlow::Continue(())
            })
        })
        .map_err(|e| flow_error(py, e))?;
    let header = sweep_header(c.tracked);
    with_series(py, &summary, [("sweep", columns(&header, &rows))])
}

/// The pluck transient ([`flowing::string_simulate::string_simulate`],
/// `flowmbd-string simulate`; Ribaric Fig. 4-6 right): returns `(summary JSON text, series)`
/// with the series `{"modal_history", "spectra": the columns of modal_history.csv and
/// spectra.csv}` (numpy arrays). `speed` replaces the configuration's (the CLI's `--speed`).
#[pyfunction]
#[pyo3(signature = (config=None, speed=None))]
pub fn string_simulate<'py>(
    py: Python<'py>, config: Option<&str>, speed: Option<f64>,
) -> PyResult<WithSeries<'py>> {
    use flowing::string_simulate::{
        SimulateConfig, history_header, history_rows, spectra_header, spectra_rows,
        string_simulate as simulate,
    };
    let c = study_config(config, |c: &mut SimulateConfig| {
        if let Some(v) = speed {
            c.speed = v;
        }
    })?;
    let r = py
        .detach(|| simulate(&c, &mut |_| std::ops::ControlFlow::Continue(())))
        .map_err(|e| flow_error(py, e))?;
    with_series(
        py,
        &r.summary,
        [
            (
                "modal_history",
                columns(&history_header(c.modes), history_rows(&r.history)),
            ),
            (
                "spectra",
                columns(&spectra_header(c.modes), spectra_rows(&r.spectra)),
            ),
        ],
    )
}

/// The string wrapped on two pulleys under a harmonic load
/// ([`flowing::string_wrap::string_wrap`], `flowmbd-string wrap`; Ribaric (4.10), (4.11),
/// (4.40)): returns `(summary JSON text, series)` with the series `{"history", "events": the
/// columns of history.csv and events.csv}` (numpy arrays; no VTK frames). `speed` replaces the
/// configuration's (the CLI's `--speed`).
#[pyfunction]
#[pyo3(signature = (config=None, speed=None))]
pub fn string_wrap<'py>(
    py: Python<'py>, config: Option<&str>, speed: Option<f64>,
) -> PyResult<WithSeries<'py>> {
    use flowing::string_wrap::{
        EVENTS_HEADER, WrapConfig, event_rows, string_wrap as wrap, wrap_history_header,
    };
    let c = study_config(config, |c: &mut WrapConfig| {
        if let Some(v) = speed {
            c.speed = v;
        }
    })?;
    let r = py
        .detach(|| wrap(&c, &mut |_| std::ops::ControlFlow::Continue(())))
        .map_err(|e| flow_error(py, e))?;
    let history_header = wrap_history_header(c.pulleys.len());
    with_series(
        py,
        &r.summary,
        [
            ("history", columns(&history_header, &r.history)),
            ("events", columns(&EVENTS_HEADER, event_rows(&r.events))),
        ],
    )
}
