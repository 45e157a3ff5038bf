//! `flowmbd.belt.Simulation`: a belt drive stepped in time from Python (issue 39 item 6), a
//! thin class over [`drives::AnySimulation`] (the library's stepping: the same model, stepper
//! and report as the studies). The configuration is [`drives::DriveSimulationConfig`] (a
//! layout, the model kind, the step), read deeply over its defaults like every study's.

use crate::{input_error, numerical_error, read_config, to_json};
use drives::belt::Signal;
use drives::{AnySimulation, DriveSimulationConfig, SimulationBuildError};
use mbd_core::MbdError;
use mbd_core::integrators::State;
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// Most steps one call may take (a run longer than this is a loop of calls; the bound keeps
/// a typo such as `t_end = 1e9` from hanging the interpreter without a way to stop it).
pub(crate) const MAX_STEPS_PER_CALL: f64 = 1e8;

/// A stepping failure: `flowmbd.NumericalError` with the state reached as `partial`.
fn step_error(py: Python<'_>, e: MbdError, state: &State) -> PyErr {
    numerical_error(
        py,
        format!("step failed at t = {} s: {e}", state.t),
        Some(serde_json::json!({ "t": state.t })),
    )
}

/// A belt drive and its generalized-α stepper (`drives::AnySimulation`).
#[pyclass(name = "BeltSimulation", module = "flowmbd.belt", unsendable)]
pub struct PyBeltSimulation {
    inner: AnySimulation,
}

#[pymethods]
impl PyBeltSimulation {
    /// Build the model of `config` (JSON text of a `DriveSimulationConfig` dict, merged over
    /// the defaults; `None`: the defaults) and mount it at rest.
    #[new]
    #[pyo3(signature = (config=None))]
    fn new(py: Python<'_>, config: Option<&str>) -> PyResult<Self> {
        let c: DriveSimulationConfig = read_config(config)?;
        match AnySimulation::new(&c) {
            Ok(inner) => Ok(Self { inner }),
            Err(SimulationBuildError::Input(field)) => Err(input_error(field)),
            Err(SimulationBuildError::Model(e)) => Err(PyValueError::new_err(e.to_string())),
            Err(e @ SimulationBuildError::Mount(_)) => {
                Err(numerical_error(py, e.to_string(), None))
            }
        }
    }

    /// The model kind (`flowing`, `nodal`, `ancf`).
    #[getter]
    fn model(&self) -> &'static str {
        self.inner.kind().name()
    }

    /// The step \[s\].
    #[getter]
    fn step_size(&self) -> f64 {
        self.inner.step_size()
    }

    /// Time \[s\].
    #[getter]
    fn t(&self) -> f64 {
        self.inner.state().t
    }

    /// The coordinates `q` (a numpy copy; names in `coordinate_names`).
    #[getter]
    fn q<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.state().q.clone().into_pyarray(py)
    }

    /// The velocities `v` (a numpy copy).
    #[getter]
    fn v<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.state().v.clone().into_pyarray(py)
    }

    /// The name of every coordinate.
    #[getter]
    fn coordinate_names(&self) -> Vec<String> {
        (0..self.inner.coordinates())
            .map(|i| self.inner.coordinate_name(i))
            .collect()
    }

    /// Pulley speeds in the travel sense \[rad/s\], in the layout's order.
    #[getter]
    fn pulley_speeds<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.pulley_speeds().into_pyarray(py)
    }

    /// Belt speed along its path \[m/s\].
    #[getter]
    fn belt_speed(&self) -> f64 {
        self.inner.belt_speed()
    }

    /// Tensioner arm angle \[rad\] (`None` without a tensioner).
    #[getter]
    fn arm_angle(&self) -> Option<f64> {
        self.inner.arm_angle()
    }

    /// Take `n` steps (a failed step is subdivided; a step that still fails raises
    /// `flowmbd.NumericalError` and leaves the last good state).
    #[pyo3(signature = (n=1))]
    fn step(&mut self, py: Python<'_>, n: usize) -> PyResult<()> {
        if n as f64 > MAX_STEPS_PER_CALL {
            return Err(PyValueError::new_err(format!(
                "n: {n} steps in one call is more than {MAX_STEPS_PER_CALL:e}"
            )));
        }
        for _ in 0..n {
            if let Err(e) = self.inner.step() {
                return Err(step_error(py, e, self.inner.state()));
            }
        }
        Ok(())
    }

    /// Step until `t_end` \[s\].
    fn run_to(&mut self, py: Python<'_>, t_end: f64) -> PyResult<()> {
        let t = self.inner.state().t;
        if !t_end.is_finite() {
            return Err(PyValueError::new_err("t_end: must be finite [s]"));
        }
        if t_end > t && (t_end - t) / self.inner.step_size() > MAX_STEPS_PER_CALL {
            return Err(PyValueError::new_err(format!(
                "t_end: {t_end} s is more than {MAX_STEPS_PER_CALL:e} steps ahead"
            )));
        }
        let r = self.inner.run_to(t_end, |_| {});
        r.map_err(|e| step_error(py, e, self.inner.state()))
    }

    /// Restart from the state `(t, q, v)` (same model and step), e.g. one saved earlier.
    fn set_state(
        &mut self, t: f64, q: PyReadonlyArray1<'_, f64>, v: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<()> {
        let (q, v) = (q.as_slice()?.to_vec(), v.as_slice()?.to_vec());
        if !t.is_finite() || q.iter().chain(&v).any(|x| !x.is_finite()) {
            return Err(PyValueError::new_err("state: t, q and v must be finite"));
        }
        self.inner
            .set_state(State::new(t, q, v))
            .map_err(|e| PyValueError::new_err(e.to_string()))
    }

    /// Replace the signal of pulley `k` from now on (JSON text of a signal dict as in a
    /// layout, e.g. `{"kind": "constant", "value": 10.0}`): a driver's speed \[rad/s\], an
    /// accessory's load torque \[N m\].
    fn set_signal(&mut self, k: usize, signal: &str) -> PyResult<()> {
        let s: Signal = serde_json::from_str(signal)
            .map_err(|e| PyValueError::new_err(format!("signal: {e}")))?;
        self.inner.set_signal(k, s).map_err(input_error)
    }

    /// The report of the current state (JSON text of `belt::Report`: spans, wraps, slip arcs,
    /// hub loads, torque and power balances).
    fn report(&self, py: Python<'_>) -> PyResult<String> {
        match self.inner.report() {
            Ok(r) => to_json(&r),
            Err(e) => Err(numerical_error(py, e.to_string(), None)),
        }
    }
}
