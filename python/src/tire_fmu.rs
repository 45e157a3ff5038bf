//! `flowmbd.tire.CoSimulation` and `flowmbd.tire.build_fmu` (issue 38 items 2, 4 and 6): the
//! rolling tire driven by its wheel-centre motion ([`tire::motion::CoSimulation`], the same
//! implementation as the FMU's) and the FMU packaging ([`flowmbd_tire_fmu::write_fmu`]).

use crate::study_config;
use crate::tire::{PyReducedTire, reduced_or, tire_error};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use std::sync::Arc;
use tire::motion::{CoSimulation, WheelMotion};
use tire::{CleatStudyConfig, ReducedTire, TireError};

self_cell::self_cell!(
    /// The co-simulation with the reduced tire it borrows.
    struct Running {
        owner: Arc<ReducedTire>,
        #[not_covariant]
        dependent: CoSimulation,
    }
);

fn motion_dict<'py>(py: Python<'py>, m: &WheelMotion) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("height", m.height)?;
    d.set_item("velocity", m.velocity.to_vec())?;
    d.set_item("yaw", m.yaw)?;
    d.set_item("camber", m.camber)?;
    d.set_item("spin_rate", m.spin_rate)?;
    Ok(d)
}

/// The tire driven by its wheel-centre motion.
#[pyclass(name = "TireCoSimulation", module = "flowmbd.tire", unsendable)]
pub struct PyTireCoSimulation {
    running: Running,
}

#[pymethods]
impl PyTireCoSimulation {
    /// Start on the rig of `config` (JSON of a cleat-study dict over the defaults) with the
    /// motion `motion` (JSON of a `WheelMotion`; `None`: the rig's steady start).
    #[new]
    #[pyo3(signature = (config=None, tire=None, motion=None))]
    fn new(
        py: Python<'_>, config: Option<&str>, tire: Option<PyRef<'_, PyReducedTire>>,
        motion: Option<&str>,
    ) -> PyResult<Self> {
        let c: CleatStudyConfig = study_config(config, |_: &mut CleatStudyConfig| {})?;
        let red = reduced_or(py, tire, &c.tire)?;
        let m: Option<WheelMotion> = motion
            .map(|t| {
                serde_json::from_str(t)
                    .map_err(|e| pyo3::exceptions::PyValueError::new_err(format!("motion: {e}")))
            })
            .transpose()?;
        let rig = c.rig.clone();
        let running = py
            .detach(|| {
                Running::try_new(red, |red| {
                    let m = match m {
                        Some(m) => m,
                        None => CoSimulation::rig_start(red, &rig)?,
                    };
                    CoSimulation::start(red, &rig, &m)
                })
            })
            .map_err(|e: TireError| tire_error(py, e, None))?;
        Ok(Self { running })
    }

    /// Time \[s\].
    #[getter]
    fn t(&self) -> f64 {
        self.running.with_dependent(|_, cs| cs.time())
    }

    /// The inputs of the last communication point (a dict of `WheelMotion`).
    fn motion<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let m = self.running.with_dependent(|_, cs| *cs.motion());
        motion_dict(py, &m)
    }

    /// One communication step of `h` \[s\] with the motion `motion` (JSON of a `WheelMotion`)
    /// held; returns the loads (`fx`, `fy`, `fz` \[N\], `mx`, `my`, `mz` \[N·m\], ISO 8855 wheel
    /// frame) and `spin_torque` \[N·m\].
    fn do_step<'py>(
        &mut self, py: Python<'py>, h: f64, motion: &str,
    ) -> PyResult<Bound<'py, PyDict>> {
        let m: WheelMotion = serde_json::from_str(motion)
            .map_err(|e| pyo3::exceptions::PyValueError::new_err(format!("motion: {e}")))?;
        let r = self
            .running
            .with_dependent_mut(|_, cs| cs.do_step(h, &m).map(|l| (l, cs.sim.spin_torque())));
        let (l, tau) = r.map_err(|e| tire_error(py, e, None))?;
        let d = PyDict::new(py);
        for (k, v) in [
            ("fx", l.fx),
            ("fy", l.fy),
            ("fz", l.fz),
            ("mx", l.mx),
            ("my", l.my),
            ("mz", l.mz),
            ("spin_torque", tau),
        ] {
            d.set_item(k, v)?;
        }
        Ok(d)
    }
}

/// Write the FMU of the tire of `config` (or `tire`) on its rig to `out`, with the shared
/// library `library` (the compiled `flowmbd_tire_fmu` cdylib) as its binary; returns the
/// start motion (the inputs' start values) as a dict.
#[pyfunction]
#[pyo3(signature = (out, library, config=None, tire=None))]
pub fn tire_build_fmu<'py>(
    py: Python<'py>, out: PathBuf, library: PathBuf, config: Option<&str>,
    tire: Option<PyRef<'_, PyReducedTire>>,
) -> PyResult<Bound<'py, PyDict>> {
    let c: CleatStudyConfig = study_config(config, |_: &mut CleatStudyConfig| {})?;
    let red = reduced_or(py, tire, &c.tire)?;
    let m = py
        .detach(|| flowmbd_tire_fmu::write_fmu(&library, &red, &c.rig, &out))
        .map_err(|e| match e {
            flowmbd_tire_fmu::FmuError::Tire(t) => tire_error(py, t, None),
            other => pyo3::exceptions::PyOSError::new_err(other.to_string()),
        })?;
    motion_dict(py, &m)
}
