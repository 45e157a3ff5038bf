//! `flowmbd.beam`: the ANCF beam studies of Kerkkänen (2006) §2.4 through
//! [`flowmbd_cases::beam_study`] (the same as `flowmbd-beam simply-supported`, `cantilever`,
//! `pendulum`, `spinning` and `ground-contact`).

use crate::{
    WithSeries, columns, input_error, numerical_error, study_config, to_json, with_series,
};
use ancf::beam_mesh::BeamElementKind;
use flowmbd_cases::ancf_beams::{GroundContactCase, StaticBeamCase};
use flowmbd_cases::ancf_dynamics::{PendulumCase, SpinningCase};
use flowmbd_cases::beam_study::{
    self as study, BeamStudyError, CantileverConfig, History, HistoryRun,
};
use mbd_core::InvalidField;
use mbd_core::validate::plausible::Implausible;
use pyo3::prelude::*;
use std::ops::ControlFlow;

/// Bad input (`ValueError` naming the field) or a numerical failure
/// (`flowmbd.NumericalError`): the classification of the app (`flowmbd-beam`'s `study_error`).
fn beam_error(py: Python<'_>, e: BeamStudyError) -> PyErr {
    match e {
        BeamStudyError::Input(field) => input_error(field),
        other => numerical_error(py, other.to_string(), None),
    }
}

/// The summary's plausibility `check` as `flowmbd.NumericalError` with the summary attached as
/// partial result (the app's `implausible result FIELD`, exit code 1).
fn plausible<S: serde::Serialize>(
    py: Python<'_>, summary: &S, check: Result<(), Implausible>,
) -> PyResult<()> {
    check.map_err(|e| numerical_error(py, e.to_string(), serde_json::to_value(summary).ok()))
}

/// The element type named `name` (`"proposed"` or `"omar-shabana"`, the CLI's `--element`).
fn element_kind(name: Option<&str>) -> PyResult<Option<BeamElementKind>> {
    name.map(|n| {
        serde_json::from_value(serde_json::Value::String(n.to_string())).map_err(|_| {
            input_error(InvalidField::new(
                "element",
                format!("expected \"proposed\" or \"omar-shabana\", got {n:?}"),
            ))
        })
    })
    .transpose()
}

/// Replace `*field` by `value` when given (a keyword override, like the CLI's flags).
fn set<T>(field: &mut T, value: Option<T>) {
    if let Some(v) = value {
        *field = v;
    }
}

/// Progress of a library run from Python: never stops (Ctrl-C is handled by Python after the
/// call returns).
fn go_on(_: f64) -> ControlFlow<()> {
    ControlFlow::Continue(())
}

/// The simply supported beam under a 1000 N mid-point load (Kerkkänen Tables 2.1/2.2,
/// [`study::simply_supported`]); returns the JSON text of the summary. `element`, `nu`,
/// `elements` replace the configuration's fields (the CLI's flags).
#[pyfunction]
#[pyo3(signature = (config=None, element=None, nu=None, elements=None))]
pub fn beam_simply_supported(
    py: Python<'_>, config: Option<&str>, element: Option<&str>, nu: Option<f64>,
    elements: Option<usize>,
) -> PyResult<String> {
    let element = element_kind(element)?;
    let c = study_config(config, |c: &mut StaticBeamCase| {
        set(&mut c.element, element);
        set(&mut c.nu, nu);
        set(&mut c.elements, elements);
    })?;
    let summary = py
        .detach(|| study::simply_supported(&c))
        .map_err(|e| beam_error(py, e))?;
    plausible(py, &summary, summary.check(&c))?;
    to_json(&summary)
}

/// The large-deflection cantilever (Kerkkänen Tables 2.3/2.4, [`study::cantilever`]): returns
/// `(summary JSON text, {"shape": the columns of shape.csv})`. `element`, `h` \[m\], `nu`,
/// `elements` replace the beam's fields (the CLI's flags).
#[pyfunction]
#[pyo3(signature = (config=None, element=None, h=None, nu=None, elements=None))]
pub fn beam_cantilever<'py>(
    py: Python<'py>, config: Option<&str>, element: Option<&str>, h: Option<f64>, nu: Option<f64>,
    elements: Option<usize>,
) -> PyResult<WithSeries<'py>> {
    let element = element_kind(element)?;
    let c = study_config(config, |c: &mut CantileverConfig| {
        set(&mut c.beam.element, element);
        set(&mut c.beam.height, h);
        set(&mut c.beam.nu, nu);
        set(&mut c.beam.elements, elements);
    })?;
    let run = py
        .detach(|| study::cantilever(&c))
        .map_err(|e| beam_error(py, e))?;
    plausible(py, &run.summary, run.summary.check(&c))?;
    let shape = columns(&study::SHAPE_COLUMNS, &run.centreline);
    with_series(py, &run.summary, [("shape", shape)])
}

/// A dynamic study's result from Python: its plausibility `check`, then
/// `(summary JSON text, {"history": the columns of history.csv})`.
fn with_history<'py, S: History + serde::Serialize>(
    py: Python<'py>, run: Result<HistoryRun<S>, BeamStudyError>,
    check: impl FnOnce(&S) -> Result<(), Implausible>,
) -> PyResult<WithSeries<'py>> {
    let run = run.map_err(|e| beam_error(py, e))?;
    plausible(py, &run.summary, check(&run.summary))?;
    let history = columns(&S::COLUMNS, run.history_rows());
    with_series(py, &run.summary, [("history", history)])
}

/// The falling flexible pendulum (Kerkkänen Figs 2.6/2.7, [`study::pendulum`]): returns
/// `(summary JSON text, {"history": the columns of history.csv})`. `elements` replaces the
/// configuration's (the CLI's `--elements`).
#[pyfunction]
#[pyo3(signature = (config=None, elements=None))]
pub fn beam_pendulum<'py>(
    py: Python<'py>, config: Option<&str>, elements: Option<usize>,
) -> PyResult<WithSeries<'py>> {
    let c = study_config(config, |c: &mut PendulumCase| {
        set(&mut c.elements, elements)
    })?;
    let run = py.detach(|| study::pendulum(&c, go_on));
    with_history(py, run, |s| s.check(&c))
}

/// The spinning beam (Kerkkänen Figs 2.10/2.11, (2.37), [`study::spinning`]): returns
/// `(summary JSON text, {"history": the columns of history.csv})`. `elements` replaces the
/// configuration's (the CLI's `--elements`).
#[pyfunction]
#[pyo3(signature = (config=None, elements=None))]
pub fn beam_spinning<'py>(
    py: Python<'py>, config: Option<&str>, elements: Option<usize>,
) -> PyResult<WithSeries<'py>> {
    let c = study_config(config, |c: &mut SpinningCase| {
        set(&mut c.elements, elements)
    })?;
    let run = py.detach(|| study::spinning(&c, go_on));
    with_history(py, run, |s| s.check(&c))
}

/// The cantilever on rigid ground by unilateral Lagrange contact ([`study::ground_contact`]):
/// returns `(summary JSON text, {"contact": the columns of contact.csv})`. `element`,
/// `elements`, `load_factor` replace the configuration's (the CLI's flags).
#[pyfunction]
#[pyo3(signature = (config=None, element=None, elements=None, load_factor=None))]
pub fn beam_ground_contact<'py>(
    py: Python<'py>, config: Option<&str>, element: Option<&str>, elements: Option<usize>,
    load_factor: Option<f64>,
) -> PyResult<WithSeries<'py>> {
    let element = element_kind(element)?;
    let c = study_config(config, |c: &mut GroundContactCase| {
        set(&mut c.element, element);
        set(&mut c.elements, elements);
        set(&mut c.load_factor, load_factor);
    })?;
    let run = py
        .detach(|| study::ground_contact(&c))
        .map_err(|e| beam_error(py, e))?;
    plausible(py, &run.summary, run.check())?;
    let contact = columns(&study::CONTACT_COLUMNS, run.contact_rows());
    with_series(py, &run.summary, [("contact", contact)])
}
