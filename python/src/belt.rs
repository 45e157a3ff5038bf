//! `flowmbd.belt`: the speed-loss study of Ribaric §6.4–6.5 (Figs. 6-6, 6-7) through
//! [`drives::speed_loss_study::run_case`], with the configuration and summary of
//! [`drives::speed_loss_study`] (the same as `flowmbd-belt speed-loss`), and the ANCF drive of
//! Kerkkänen ch. 3 through [`drives::ancf_study`] (the same as `flowmbd-belt ancf`), and the
//! plate-belt drive of Kerkkänen ch. 4 through [`drives::plate_study`] (the same as
//! `flowmbd-belt plate`), the FEAD sweep (`flowmbd-belt fead`) and its steady design
//! (`flowmbd-belt design`).

use crate::{
    WithSeries, input_error, numerical_error, read_config, study_config, to_json, with_series,
};
use drives::ancf_run::StudyEnd;
use drives::ancf_study::{Analysis, AncfStudyConfig, closure_study, dynamic_run, dynamic_setup};
use drives::fead::{FeadConfig, FeadFailureOrInvalid, run_fead};
use drives::fead_design::{DesignConfig, run_design};
use drives::plate_study::{PlateStudyConfig, plate_run, plate_setup};
use drives::speed_loss_study::{CaseFailure, SummaryCase, SummaryPoint, run_case};
use drives::{ModelKind, SpeedLossStudyConfig, SpeedLossSummary};
use mbd_core::{InvalidField, Validate};
use pyo3::prelude::*;
use std::time::Instant;

/// Why a run stopped: bad input or a numerical failure with partial results.
enum Failure {
    Input(InvalidField),
    Numerical(String, Option<serde_json::Value>),
}

/// Run every driver speed of `c` (validated) in the configured order.
fn run(c: &SpeedLossStudyConfig) -> Result<SpeedLossSummary, Failure> {
    let start = Instant::now();
    let mut cases = Vec::with_capacity(c.omegas.len());
    let mut coordinates = 0;
    for &omega in &c.omegas {
        let t0 = Instant::now();
        let (case, n, _) = run_case(c, omega, |_, _| {}).map_err(|f| match f {
            CaseFailure::Input(field) => Failure::Input(field),
            CaseFailure::Build(e) => Failure::Numerical(e.to_string(), None),
            CaseFailure::Sweep(f) => Failure::Numerical(
                format!("ω₁ = {omega} rad/s: {}", f.error),
                Some(serde_json::json!({
                    "omega_driver": omega,
                    "points": f.points.iter().map(SummaryPoint::new).collect::<Vec<_>>(),
                })),
            ),
        })?;
        coordinates = n;
        cases.push(SummaryCase::new(case, t0.elapsed().as_secs_f64()));
    }
    Ok(SpeedLossSummary::new(
        c.model,
        cases,
        coordinates,
        start.elapsed().as_secs_f64(),
    ))
}

/// Speed loss against load torque; returns the JSON text of the summary. `omega`, `torques`
/// and `model` replace `omegas`, `procedure.torques` and `model` of the configuration (like
/// the CLI's `--omega`, `--torques`, `--model`).
#[pyfunction]
#[pyo3(signature = (config=None, omega=None, torques=None, model=None))]
pub fn speed_loss(
    py: Python<'_>, config: Option<&str>, omega: Option<f64>, torques: Option<Vec<f64>>,
    model: Option<&str>,
) -> PyResult<String> {
    let mut c: SpeedLossStudyConfig = read_config(config)?;
    if let Some(w) = omega {
        c.omegas = vec![w];
    }
    if let Some(t) = torques {
        c.procedure.torques = t;
    }
    if let Some(m) = model {
        c.model = m
            .parse::<ModelKind>()
            .map_err(|reason| input_error(InvalidField::new("model", reason)))?;
    }
    c.validate().map_err(input_error)?;
    match py.detach(|| run(&c)) {
        Ok(summary) => to_json(&summary),
        Err(Failure::Input(field)) => Err(input_error(field)),
        Err(Failure::Numerical(message, partial)) => Err(numerical_error(py, message, partial)),
    }
}

/// The ANCF drive's failures as the app classifies them (`apps/belt/src/ancf.rs`): rejected
/// input names `drive: <item>`.
fn ancf_error(py: Python<'_>, e: ::ancf::AncfError) -> PyErr {
    match e {
        ::ancf::AncfError::InvalidInput { item, reason } => {
            input_error(InvalidField::new(format!("drive: {item}"), reason))
        }
        other => numerical_error(py, other.to_string(), None),
    }
}

/// A dynamic run of either ANCF drive (`run`, outside the GIL) as the JSON text of its
/// summary, or the failure that stopped it with the summary as its partial result.
fn drive_study<S, H>(
    py: Python<'_>, run: impl Send + FnOnce() -> Result<StudyEnd<S, H>, ::ancf::AncfError>,
) -> PyResult<String>
where
    S: serde::Serialize + Send,
    H: Send,
{
    let end = py.detach(run).map_err(|e| ancf_error(py, e))?;
    summary_or_failure(py, end.failure, &end.summary)
}

/// The planar ANCF belt drive of Kerkkänen ch. 3 (defaults: example 3.3-B, Table 3.1);
/// returns the JSON text of the summary. `t_end` replaces the configuration's end time (the
/// CLI's `--t-end`).
#[pyfunction]
#[pyo3(signature = (config=None, t_end=None))]
pub fn ancf(py: Python<'_>, config: Option<&str>, t_end: Option<f64>) -> PyResult<String> {
    let c = study_config(config, |c: &mut AncfStudyConfig| {
        if let Some(t) = t_end {
            c.t_end = t;
        }
    })?;
    match c.analysis {
        Analysis::StaticClosure => {
            let result = py.detach(|| closure_study(&c));
            let (_, _, summary) = result.map_err(|e| ancf_error(py, e))?;
            to_json(&summary)
        }
        Analysis::Dynamic => {
            let start = Instant::now();
            drive_study(py, || {
                let (drive, init) = dynamic_setup(&c)?;
                dynamic_run(&c, &drive, &init, start, |_, _| Ok(()))
            })
        }
    }
}

/// The three-dimensional plate-belt drive of Kerkkänen ch. 4 (defaults: Model 2 of Table 4.1);
/// returns the JSON text of the summary. `t_end` replaces the configuration's end time (the
/// CLI's `--t-end`).
#[pyfunction]
#[pyo3(signature = (config=None, t_end=None))]
pub fn plate(py: Python<'_>, config: Option<&str>, t_end: Option<f64>) -> PyResult<String> {
    let c = study_config(config, |c: &mut PlateStudyConfig| {
        if let Some(t) = t_end {
            c.t_end = t;
        }
    })?;
    let start = Instant::now();
    drive_study(py, || {
        let (drive, init) = plate_setup(&c)?;
        plate_run(&c, &drive, &init, start, |_, _| Ok(()))
    })
}

/// The front-end accessory drive with an automatic tensioner over an engine-speed sweep
/// (`drives::fead`, issue 17 item 5; defaults: the six-pulley passenger-car drive); returns the
/// JSON text of the summary. `rpm` replaces the configured engine speeds \[rpm\] (the CLI's
/// `--rpm`).
#[pyfunction]
#[pyo3(signature = (config=None, rpm=None))]
pub fn fead(py: Python<'_>, config: Option<&str>, rpm: Option<Vec<f64>>) -> PyResult<String> {
    let c = study_config(config, |c: &mut FeadConfig| {
        if let Some(r) = rpm {
            c.engine.speeds_rpm = r;
        }
    })?;
    match py.detach(|| run_fead(&c, |_| {})) {
        Ok(summary) => to_json(&summary),
        Err(e) => Err(match *e {
            FeadFailureOrInvalid::Invalid(f) => input_error(f),
            FeadFailureOrInvalid::Build(b) => numerical_error(py, b.to_string(), None),
            FeadFailureOrInvalid::Numerical(f) => numerical_error(
                py,
                format!("fead sweep: {}", f.error),
                serde_json::to_value(&f.partial).ok(),
            ),
        }),
    }
}

/// The steady FEAD design without time stepping (`drives::fead_design`, issue 36; defaults:
/// the `fead` study's drive and engine): span tensions, tensioner arm, slip arcs, hub loads and
/// slip margins per engine speed, rotational and span modes, the Campbell diagram and the
/// findings; returns the JSON text of the summary (the same as `flowmbd-belt design --json`).
/// `rpm` replaces the configured engine speeds \[rpm\].
#[pyfunction]
#[pyo3(signature = (config=None, rpm=None))]
pub fn design(py: Python<'_>, config: Option<&str>, rpm: Option<Vec<f64>>) -> PyResult<String> {
    let c = study_config(config, |c: &mut DesignConfig| {
        if let Some(r) = rpm {
            c.engine.speeds_rpm = r;
        }
    })?;
    let summary = py.detach(|| run_design(&c)).map_err(input_error)?;
    to_json(&summary)
}

/// The JSON text of `summary`, or the integration failure with the summary as its partial
/// result (the apps' exit-1 convention).
fn summary_or_failure<S: serde::Serialize>(
    py: Python<'_>, failure: Option<String>, summary: &S,
) -> PyResult<String> {
    match failure {
        None => to_json(summary),
        Some(msg) => Err(numerical_error(
            py,
            format!("integration failed: {msg}"),
            serde_json::to_value(summary).ok(),
        )),
    }
}

/// The rotating vs non-rotating belt demonstration of Ribaric §6.2, Fig. 6-3
/// ([`drives::wave::run_wave_study`], `flowmbd-belt wave`): returns `(summary JSON text,
/// series)` with the series `{"wave": the columns of wave.csv}` (numpy arrays). `speed`
/// \[m/s\] and `t_end` \[s\] replace `wave.belt_speed` and `wave.t_end` (the CLI's `--speed`,
/// `--t-end`).
#[pyfunction]
#[pyo3(signature = (config=None, speed=None, t_end=None))]
pub fn wave<'py>(
    py: Python<'py>, config: Option<&str>, speed: Option<f64>, t_end: Option<f64>,
) -> PyResult<WithSeries<'py>> {
    use drives::wave::{WAVE_CSV_HEADER, WaveStudyConfig, run_wave_study, wave_csv_rows};
    let c = study_config(config, |c: &mut WaveStudyConfig| {
        if let Some(v) = speed {
            c.wave.belt_speed = v;
        }
        if let Some(t) = t_end {
            c.wave.t_end = t;
        }
    })?;
    let study = py
        .detach(|| run_wave_study(&c, |_| {}))
        .map_err(|e| match e {
            flowing::FlowError::InvalidInput { item, reason } => {
                input_error(InvalidField::new(item, reason))
            }
            other => numerical_error(py, other.to_string(), None),
        })?;
    let rows = wave_csv_rows(&study.rest, &study.running);
    with_series(
        py,
        &study.summary,
        [("wave", crate::columns(&WAVE_CSV_HEADER, &rows))],
    )
}

/// The rigid slider-crank demonstration
/// ([`flowmbd_cases::slider_crank_study::slider_crank_demo`], `flowmbd-belt demo`): returns
/// `(summary JSON text, series)` with the series `{"history": the columns of history.csv}`
/// (numpy arrays). `t_end` \[s\] replaces the configuration's (the CLI's `--t-end`).
#[pyfunction]
#[pyo3(signature = (config=None, t_end=None))]
pub fn demo<'py>(
    py: Python<'py>, config: Option<&str>, t_end: Option<f64>,
) -> PyResult<WithSeries<'py>> {
    use flowmbd_cases::slider_crank_study::{DEMO_HISTORY_HEADER, DemoConfig, slider_crank_demo};
    let c = study_config(config, |c: &mut DemoConfig| {
        if let Some(t) = t_end {
            c.t_end = t;
        }
    })?;
    let mut rows: Vec<[f64; 4]> = Vec::new();
    let summary = py
        .detach(|| slider_crank_demo(&c, &mut |r| rows.push(*r)))
        .map_err(|e| numerical_error(py, e.to_string(), None))?;
    with_series(
        py,
        &summary,
        [("history", crate::columns(&DEMO_HISTORY_HEADER, &rows))],
    )
}
