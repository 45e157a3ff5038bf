//! `flowmbd.tire.Simulation`: the reduced tire rolling on the rig, stepped in time from Python
//! (issue 39 item 6): started as the cleat test starts it ([`tire::start_rolling`]: the
//! rolling preload, the cleat reaching the patch centre at `rig.settle_time`) and advanced by
//! the cleat test's own step ([`tire::rig_step`]), so that a stepped run reproduces
//! `flowmbd.tire.cleat` step by step.

use crate::stepping::MAX_STEPS_PER_CALL;
use crate::study_config;
use crate::tire::{PyReducedTire, reduced_or, tire_error};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::Arc;
use tire::study::{FORCE_COLUMNS, force_row};
use tire::{
    CleatStudyConfig, ReducedTire, RigConfig, RollingState, RollingTire, TireError, rig_step,
    start_rolling,
};

self_cell::self_cell!(
    /// The rolling tire with the reduced tire it borrows.
    struct Rolling {
        owner: Arc<ReducedTire>,
        #[not_covariant]
        dependent: RollingTire,
    }
);

/// The rolling tire of the cleat rig and its configuration.
#[pyclass(name = "TireSimulation", module = "flowmbd.tire", unsendable)]
pub struct PyTireSimulation {
    rolling: Rolling,
    rig: RigConfig,
}

impl PyTireSimulation {
    fn steps(&mut self, py: Python<'_>, n: usize) -> PyResult<()> {
        let rig = &self.rig;
        self.rolling.with_dependent_mut(|_, sim| {
            for _ in 0..n {
                if let Err(e) = rig_step(sim, rig) {
                    let t = sim.state.t;
                    return Err(tire_error(py, e, Some(serde_json::json!({ "t": t }))));
                }
            }
            Ok(())
        })
    }

    fn t(&self) -> f64 {
        self.rolling.with_dependent(|_, sim| sim.state.t)
    }
}

#[pymethods]
impl PyTireSimulation {
    /// Reduce `config.tire` (or take `tire`), preload it rolling on the rig of `config.rig`
    /// (JSON text of a cleat-study dict over the defaults) and start it there.
    #[new]
    #[pyo3(signature = (config=None, tire=None))]
    fn new(
        py: Python<'_>, config: Option<&str>, tire: Option<PyRef<'_, PyReducedTire>>,
    ) -> PyResult<Self> {
        let c: CleatStudyConfig = study_config(config, |_: &mut CleatStudyConfig| {})?;
        let red = reduced_or(py, tire, &c.tire)?;
        let rig = c.rig.clone();
        let rolling = py
            .detach(|| Rolling::try_new(red, |red| start_rolling(red, &rig).map(|start| start.sim)))
            .map_err(|e: TireError| tire_error(py, e, None))?;
        Ok(Self { rolling, rig })
    }

    /// Time \[s\] (the cleat reaches the patch centre at `settle_time`).
    #[getter(t)]
    fn time(&self) -> f64 {
        self.t()
    }

    /// The rig's `settle_time` \[s\]: the time of the cleat hit.
    #[getter]
    fn settle_time(&self) -> f64 {
        self.rig.settle_time
    }

    /// The rig's step `rolling.time_step` \[s\] (sub-stepped during the impact).
    #[getter]
    fn step_size(&self) -> f64 {
        self.rig.rolling.time_step
    }

    /// Spin rate θ̇ \[rad/s\].
    #[getter]
    fn spin(&self) -> f64 {
        self.rolling.with_dependent(|_, sim| sim.state.theta_d)
    }

    /// Drive torque about the wheel axis \[N·m\] (0: free rolling).
    #[getter]
    fn drive_torque(&self) -> f64 {
        self.rolling.with_dependent(|_, sim| sim.drive_torque)
    }

    /// Set the drive torque \[N·m\] for the following steps.
    #[setter]
    fn set_drive_torque(&mut self, torque: f64) -> PyResult<()> {
        if !torque.is_finite() {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "drive_torque: must be finite, got {torque}"
            )));
        }
        self.rolling
            .with_dependent_mut(|_, sim| sim.drive_torque = torque);
        Ok(())
    }

    /// Prescribe the spin rate `rate` \[rad/s\] for the following steps, or free the spin
    /// (`None`, the start: driven by `drive_torque`): [`RollingTire::prescribe_spin`], a
    /// kinematic constraint on the spin coordinate of the stepper, the rate going linearly to
    /// `rate` over the next step. Errors: `rate` not finite (`ValueError` naming `rate`).
    #[pyo3(signature = (rate=None))]
    fn prescribe_spin(&mut self, py: Python<'_>, rate: Option<f64>) -> PyResult<()> {
        if let Some(r) = rate
            && !r.is_finite()
        {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "rate: must be finite, got {r}"
            )));
        }
        self.rolling
            .with_dependent_mut(|_, sim| sim.prescribe_spin(rate))
            .map_err(|e| tire_error(py, e, None))
    }

    /// The prescribed spin rate \[rad/s\], `None` when the spin is free
    /// ([`RollingTire::prescribed_spin`]).
    #[getter]
    fn prescribed_spin(&self) -> Option<f64> {
        self.rolling.with_dependent(|_, sim| sim.prescribed_spin())
    }

    /// Reaction torque of the prescribed spin about the spin axis +y in the last step \[N·m\]
    /// (0 when the spin is free; [`RollingTire::reaction_torque`]).
    #[getter]
    fn reaction_torque(&self) -> f64 {
        self.rolling.with_dependent(|_, sim| sim.reaction_torque())
    }

    /// Total torque on the wheel about +y in the last step \[N·m\]: the drive torque plus the
    /// reaction torque ([`RollingTire::spin_torque`]).
    #[getter]
    fn spin_torque(&self) -> f64 {
        self.rolling.with_dependent(|_, sim| sim.spin_torque())
    }

    /// The reduced coordinates `z` of the input tire (numpy copy).
    #[getter]
    fn coordinates<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.rolling
            .with_dependent(|_, sim| sim.coordinates())
            .into_pyarray(py)
    }

    /// Normal force per contact node \[N\] (numpy copy).
    #[getter]
    fn normal_forces<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.rolling
            .with_dependent(|_, sim| sim.state.lambda.clone())
            .into_pyarray(py)
    }

    /// Contact-node positions in the wheel frame \[m\] (n × 3, numpy).
    #[getter]
    fn contact_positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let p = self
            .rolling
            .with_dependent(|_, sim| sim.contact_positions());
        Array2::from_shape_fn((p.len(), 3), |(i, j)| p[i][j]).into_pyarray(py)
    }

    /// The cleat test's force row of the present state (its `forces` series' columns: time
    /// from the hit `t_s` \[s\], `fx_N`, `fy_N` (vertical), `f_lateral_N` \[N\],
    /// `spin_rad_per_s`, `active_nodes_count`, `normal_sum_N` \[N\], `mx_N_m`, `my_N_m`,
    /// `mz_N_m` \[N·m\]).
    fn forces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let row = self
            .rolling
            .with_dependent(|_, sim| force_row(sim, self.rig.settle_time));
        let d = PyDict::new(py);
        for (k, x) in FORCE_COLUMNS.iter().zip(row) {
            d.set_item(*k, x)?;
        }
        Ok(d)
    }

    /// The state (`tire::RollingState`, copies) as a dict: `t` \[s\], the simulation's reduced
    /// coordinates `z`, `zd`, `zdd` and the generalized-α pseudo-accelerations `acc`, the spin
    /// angle `theta` \[rad\], `theta_d` \[rad/s\], `theta_dd`, `theta_acc` \[rad/s²\], the
    /// normal force per contact node `lambda` \[N\], the friction force per node `friction`
    /// (n × 3) \[N\] and the net contact force `contact_force` (3) \[N\].
    fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = self.rolling.with_dependent(|_, sim| sim.state.clone());
        let d = PyDict::new(py);
        d.set_item("t", s.t)?;
        for (k, v) in [("z", s.z), ("zd", s.zd), ("zdd", s.zdd), ("acc", s.acc)] {
            d.set_item(k, v.into_pyarray(py))?;
        }
        for (k, v) in [
            ("theta", s.theta),
            ("theta_d", s.theta_d),
            ("theta_dd", s.theta_dd),
            ("theta_acc", s.theta_acc),
        ] {
            d.set_item(k, v)?;
        }
        d.set_item("lambda", s.lambda.into_pyarray(py))?;
        let f = &s.friction;
        d.set_item(
            "friction",
            Array2::from_shape_fn((f.len(), 3), |(i, j)| f[i][j]).into_pyarray(py),
        )?;
        d.set_item("contact_force", s.contact_force.to_vec().into_pyarray(py))?;
        Ok(d)
    }

    /// Continue from a state of [`Self::state`] (a dict with its keys, float64 arrays), e.g.
    /// one saved earlier (`tire::RollingTire::set_state`).
    fn set_state(&mut self, py: Python<'_>, state: &Bound<'_, PyDict>) -> PyResult<()> {
        let get = |k: &str| -> PyResult<Bound<'_, PyAny>> {
            state.get_item(k)?.ok_or_else(|| {
                pyo3::exceptions::PyValueError::new_err(format!("state: missing key '{k}'"))
            })
        };
        let num = |k: &str| -> PyResult<f64> { get(k)?.extract() };
        let vec = |k: &str| -> PyResult<Vec<f64>> {
            Ok(get(k)?
                .extract::<PyReadonlyArray1<'_, f64>>()?
                .as_array()
                .to_vec())
        };
        let friction = get("friction")?.extract::<PyReadonlyArray2<'_, f64>>()?;
        let friction = friction.as_array();
        if friction.ncols() != 3 {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "state.friction: {} columns, must be 3 (x, y, z per contact node)",
                friction.ncols()
            )));
        }
        let contact_force = vec("contact_force")?;
        let contact_force: [f64; 3] = contact_force.as_slice().try_into().map_err(|_| {
            pyo3::exceptions::PyValueError::new_err(format!(
                "state.contact_force: {} values, must be 3",
                contact_force.len()
            ))
        })?;
        let s = RollingState {
            t: num("t")?,
            z: vec("z")?,
            zd: vec("zd")?,
            zdd: vec("zdd")?,
            acc: vec("acc")?,
            theta: num("theta")?,
            theta_d: num("theta_d")?,
            theta_dd: num("theta_dd")?,
            theta_acc: num("theta_acc")?,
            lambda: vec("lambda")?,
            friction: friction
                .rows()
                .into_iter()
                .map(|r| [r[0], r[1], r[2]])
                .collect(),
            contact_force,
        };
        self.rolling
            .with_dependent_mut(|_, sim| sim.set_state(s))
            .map_err(|e| tire_error(py, e, None))
    }

    /// Take `n` rig steps; a failed step raises `flowmbd.NumericalError` (`partial`: the time
    /// reached).
    fn step(&mut self, py: Python<'_>, n: usize) -> PyResult<()> {
        if n as f64 > MAX_STEPS_PER_CALL {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "n: {n} steps in one call, more than {MAX_STEPS_PER_CALL:e}"
            )));
        }
        self.steps(py, n)
    }

    /// Step until `t_end` \[s\].
    fn run_to(&mut self, py: Python<'_>, t_end: f64) -> PyResult<()> {
        let h = self.rig.rolling.time_step;
        let left = ((t_end - self.t()) / h).round();
        if !left.is_finite() || left > MAX_STEPS_PER_CALL {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "t_end: {t_end} s is {left:e} steps of {h} s away, more than \
                 {MAX_STEPS_PER_CALL:e} in one call"
            )));
        }
        while self.t() < t_end - 0.5 * h {
            self.steps(py, 1)?;
        }
        Ok(())
    }
}
