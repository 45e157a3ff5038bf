//! `flowmbd.tire`: the reduced FE truck tire of Ribaric ch. 7–8. The FE tire generated
//! ([`fe_model::generate::tire`]) or imported (ABAQUS / Matrix Market,
//! [`tire::imported_tire`]), its reduction of §8.2 ([`tire::reduce`]) as a
//! reusable, picklable [`PyReducedTire`], and the cleat test of §8.3 with the configuration and
//! summary of [`tire::study`] (the same as `flowmbd-tire cleat`).

use crate::{
    WithSeries, columns, input_error, numerical_error, read_config, study_config, to_json,
    with_series,
};
use faer::Mat;
use fe_model::generate::TireConfig;
use mbd_core::Validate;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};
use std::sync::Arc;
use tire::study::{FORCE_COLUMNS, force_row, sample_row};
use tire::{
    CleatStudyConfig, ImportFiles, ReducedTire, RigResult, RollingTire, SteadyStudyConfig,
    TireError, TireFe, TireSource, cleat_summary, imported_tire, phase_spread, rig_input_error,
    run_cleat_observed, run_steady, steady_summary, tire_input_error,
};

/// Bad input (`ValueError` with the CLI's `field: reason`) or a numerical failure
/// (`flowmbd.NumericalError` with `partial`), classified like `flowmbd-tire`
/// ([`tire_input_error`]).
pub(crate) fn tire_error(
    py: Python<'_>, e: TireError, partial: Option<serde_json::Value>,
) -> PyErr {
    match tire_input_error(e) {
        Ok(field) => input_error(field),
        Err(other) => numerical_error(py, other.to_string(), partial),
    }
}

/// Errors of reading or writing a reduced tire (not a configuration field): `ValueError` with
/// the library's message (`reduced tire file <path>: <reason>`).
fn file_error(py: Python<'_>, e: TireError) -> PyErr {
    match e {
        TireError::File { .. } => PyValueError::new_err(e.to_string()),
        other => tire_error(py, other, None),
    }
}

fn to_numpy<'py>(py: Python<'py>, a: &Mat<f64>) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((a.nrows(), a.ncols()), |(i, j)| a[(i, j)]).into_pyarray(py)
}

/// Rows of equal length `ncols` as a 2-D numpy array.
fn matrix<'py>(py: Python<'py>, rows: &[Vec<f64>], ncols: usize) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((rows.len(), ncols), |(i, j)| rows[i][j]).into_pyarray(py)
}

fn rows3<'py>(py: Python<'py>, v: &[[f64; 3]]) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((v.len(), 3), |(i, j)| v[i][j]).into_pyarray(py)
}

/// The reduced flowing-material tire of Ribaric §8.2 ([`ReducedTire`]): made once by
/// `flowmbd.tire.reduce` (or loaded from a `flowmbd-tire reduce` file) and passed to the tire
/// studies. Immutable; pickles through its versioned JSON form (bit-identical round trip), so
/// that it can be shipped to Dask workers.
#[pyclass(name = "ReducedTire", module = "flowmbd.tire", frozen)]
pub struct PyReducedTire {
    pub(crate) inner: Arc<ReducedTire>,
}

#[pymethods]
impl PyReducedTire {
    /// `M_z = TᵀMT` \[kg\], a numpy copy.
    #[getter]
    fn m<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        to_numpy(py, &self.inner.m)
    }
    /// `K_z = TᵀKT` \[N/m\], a numpy copy.
    #[getter]
    fn k<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        to_numpy(py, &self.inner.k)
    }
    /// `G₁ = TᵀMT_,θ` \[kg/rad\], a numpy copy.
    #[getter]
    fn g1<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        to_numpy(py, &self.inner.g1)
    }
    /// `G₂ = TᵀMT_,θθ` \[kg/rad²\], a numpy copy.
    #[getter]
    fn g2<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        to_numpy(py, &self.inner.g2)
    }
    /// `K₁ = TᵀKT_,θ` \[N/(m·rad)\], a numpy copy.
    #[getter]
    fn k1<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        to_numpy(py, &self.inner.k1)
    }
    /// Rim force per coordinate `K_r` (3 × n_z) \[N/m\], Ribaric (7.2), a numpy copy.
    #[getter]
    fn kr<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        to_numpy(py, &self.inner.kr)
    }
    /// `Σ_rim K T_,θ` (3 × n_z), a numpy copy.
    #[getter]
    fn kr1<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        to_numpy(py, &self.inner.kr1)
    }
    /// Rim moment per coordinate `K_θ` (3 × n_z) \[N\], Ribaric (7.2), a numpy copy.
    #[getter]
    fn kt<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        to_numpy(py, &self.inner.kt)
    }
    /// `Σ_rim s̃ K T_,θ` (3 × n_z), a numpy copy.
    #[getter]
    fn kt1<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        to_numpy(py, &self.inner.kt1)
    }
    /// Contact-node rows of `T` (3 n_c × n_z), a numpy copy.
    #[getter]
    fn tc<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        to_numpy(py, &self.inner.tc)
    }
    /// Contact-node rows of `T_,θ` (3 n_c × n_z) \[1/rad\], a numpy copy.
    #[getter]
    fn tc_theta<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        to_numpy(py, &self.inner.tc_theta)
    }
    /// Translational momentum per coordinate `P = eᵀM T` (3 × n_z) \[kg\], a numpy copy.
    #[getter]
    fn p_e<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        to_numpy(py, &self.inner.p_e)
    }
    /// `P₁ = eᵀM T_,θ` (3 × n_z) \[kg/rad\], a numpy copy.
    #[getter]
    fn p_e1<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        to_numpy(py, &self.inner.p_e1)
    }
    /// `P₂ = eᵀM T_,θθ` (3 × n_z) \[kg/rad²\], a numpy copy.
    #[getter]
    fn p_e2<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        to_numpy(py, &self.inner.p_e2)
    }
    /// Kept free-node modes `n_f`.
    #[getter]
    fn n_free_modes(&self) -> usize {
        self.inner.n_free_modes
    }
    /// Contact nodes `n_c`.
    #[getter]
    fn n_contact(&self) -> usize {
        self.inner.n_contact()
    }
    /// Tire coordinates `n_z = n_f + 3 n_c`.
    #[getter]
    fn n_z(&self) -> usize {
        self.inner.n_z()
    }
    /// Wheel–tire DOF `6 + n_z`.
    #[getter]
    fn dof(&self) -> usize {
        self.inner.dof()
    }
    /// FE node index of each contact node.
    #[getter]
    fn contact_nodes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<usize>> {
        self.inner.contact_nodes.clone().into_pyarray(py)
    }
    /// Undeformed contact-node positions `s^c` (n_c × 3) \[m\].
    #[getter]
    fn contact_positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        rows3(py, &self.inner.contact_positions)
    }
    /// Frequencies of the kept free-node modes \[Hz\].
    #[getter]
    fn free_mode_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.free_mode_hz.clone().into_pyarray(py)
    }
    /// Frequencies of the contact-node modes \[Hz\].
    #[getter]
    fn contact_mode_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.contact_mode_hz.clone().into_pyarray(py)
    }
    /// `m_θ = TᵀM s_,θ` \[kg·m/rad\].
    #[getter]
    fn m_theta<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.m_theta.clone().into_pyarray(py)
    }
    /// `c_s = TᵀM s_,θθ` \[kg·m/rad²\].
    #[getter]
    fn c_s<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.inner.c_s.clone().into_pyarray(py)
    }
    /// Tire mass without the rim nodes \[kg\].
    #[getter]
    fn tire_mass(&self) -> f64 {
        self.inner.tire_mass
    }
    /// Rim-node mass \[kg\].
    #[getter]
    fn rim_mass(&self) -> f64 {
        self.inner.rim_mass
    }
    /// Rim-node spin inertia \[kg m²\].
    #[getter]
    fn rim_spin_inertia(&self) -> f64 {
        self.inner.rim_spin_inertia
    }
    /// Unloaded outer radius \[m\].
    #[getter]
    fn outer_radius(&self) -> f64 {
        self.inner.outer_radius
    }
    /// What the tire was made from (generator, or the imported files' SHA-256 digests, and
    /// the reduction, JSON).
    #[getter]
    fn source(&self) -> String {
        self.inner.source.clone()
    }
    /// The version of the code that reduced it (package version and source digest).
    #[getter]
    fn code_version(&self) -> String {
        self.inner.code_version.clone()
    }
    /// Eigenfrequencies of the reduced tire, wheel fixed, not rolling \[Hz\].
    fn frequencies_hz<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let red = Arc::clone(&self.inner);
        let f = py
            .detach(move || red.frequencies_hz())
            .map_err(|e| tire_error(py, e, None))?;
        Ok(f.into_pyarray(py))
    }
    /// The versioned JSON text (the `flowmbd-tire reduce` file).
    fn to_json(&self, py: Python<'_>) -> PyResult<String> {
        let red = Arc::clone(&self.inner);
        py.detach(move || red.to_json())
            .map_err(|e| tire_error(py, e, None))
    }
    /// From the versioned JSON text.
    #[staticmethod]
    fn from_json(py: Python<'_>, text: &str) -> PyResult<Self> {
        let red = py
            .detach(|| ReducedTire::from_json(text, "JSON text"))
            .map_err(|e| file_error(py, e))?;
        Ok(Self {
            inner: Arc::new(red),
        })
    }
    /// Save to `path` (the file `flowmbd-tire` reuses as `tire.reduced_file`).
    fn save(&self, py: Python<'_>, path: std::path::PathBuf) -> PyResult<()> {
        let red = Arc::clone(&self.inner);
        py.detach(move || red.save(&path))
            .map_err(|e| file_error(py, e))
    }
    /// Load a saved reduced tire (e.g. written by `flowmbd-tire reduce`): a regular file within
    /// the size ceiling whose checksum holds (`ValueError` otherwise, before reading a device
    /// such as `/dev/zero`).
    #[staticmethod]
    fn load(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Self> {
        let red = py
            .detach(|| ReducedTire::load(&path))
            .map_err(|e| file_error(py, e))?;
        Ok(Self {
            inner: Arc::new(red),
        })
    }
    /// Pickle support: `flowmbd.tire._reduced_tire_from_bytes(<versioned JSON as bytes>)`.
    fn __reduce__<'py>(
        &self, py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyBytes>,))> {
        let text = self.to_json(py)?;
        let f = py
            .import("flowmbd.tire")?
            .getattr("_reduced_tire_from_bytes")?;
        Ok((f, (PyBytes::new(py, text.as_bytes()),)))
    }
    fn __repr__(&self) -> String {
        format!(
            "ReducedTire(contact nodes {}, free-node modes {}, {} wheel-tire DOF, tire mass {:.3} kg)",
            self.inner.n_contact(),
            self.inner.n_free_modes,
            self.inner.dof(),
            self.inner.tire_mass
        )
    }
}

/// The FE tire as arrays: `(nodes n × 3 [m], K triplets (rows, cols, values) [N/m] of the
/// 3n × 3n stiffness with the inflation prestress, lumped mass per DOF [kg], rim nodes,
/// candidate patch nodes)`.
type FeOut<'py> = (
    Bound<'py, PyArray2<f64>>,
    (
        Bound<'py, PyArray1<usize>>,
        Bound<'py, PyArray1<usize>>,
        Bound<'py, PyArray1<f64>>,
    ),
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<usize>>,
    Bound<'py, PyArray1<usize>>,
);

fn fe_out<'py>(py: Python<'py>, fe: TireFe) -> FeOut<'py> {
    let (mut r, mut c, mut v) = (Vec::new(), Vec::new(), Vec::new());
    for (i, j, x) in fe_model::sparse::triplets(fe.stiffness.as_ref()) {
        r.push(i);
        c.push(j);
        v.push(x);
    }
    (
        rows3(py, &fe.nodes),
        (r.into_pyarray(py), c.into_pyarray(py), v.into_pyarray(py)),
        fe.mass.into_pyarray(py),
        fe.rim.into_pyarray(py),
        fe.candidates.into_pyarray(py),
    )
}

/// The generated FE tire ([`fe_model::generate::tire`], `TireSource::fe_model`); `config` is
/// the `[tire.generator]` table as JSON.
#[pyfunction]
#[pyo3(signature = (config=None))]
pub fn tire_generate<'py>(py: Python<'py>, config: Option<&str>) -> PyResult<FeOut<'py>> {
    let generator: TireConfig = read_config(config)?;
    let source = TireSource {
        generator,
        ..TireSource::default()
    };
    source.validate_within("tire").map_err(input_error)?;
    let fe = py
        .detach(|| source.fe_model())
        .map_err(|e| tire_error(py, e, None))?;
    Ok(fe_out(py, fe))
}

/// The imported FE tire ([`imported_tire`]); `config` is the `[tire.import]` table as JSON.
#[pyfunction]
pub fn tire_import<'py>(py: Python<'py>, config: &str) -> PyResult<FeOut<'py>> {
    let files: ImportFiles = serde_json::from_str(config)
        .map_err(|e| PyValueError::new_err(format!("tire.import: {e}")))?;
    let source = TireSource {
        import: Some(files),
        ..TireSource::default()
    };
    source.validate_within("tire").map_err(input_error)?;
    let files = source.import.as_ref().expect("set above");
    let fe = py
        .detach(|| imported_tire(files))
        .map_err(|e| tire_error(py, e, None))?;
    Ok(fe_out(py, fe))
}

/// Reduce the tire described by `config` (the `[tire]` table as JSON: `generator` or
/// `import`, and `reduction`; `reduced_file` is not used) with Ribaric §8.2.
#[pyfunction]
#[pyo3(signature = (config=None))]
pub fn tire_reduce(py: Python<'_>, config: Option<&str>) -> PyResult<PyReducedTire> {
    let source: TireSource = read_config(config)?;
    source.validate_within("tire").map_err(input_error)?;
    let red = py
        .detach(|| {
            let fe = source.fe_model()?;
            source.reduce_fe(&fe).map(|(red, _)| red)
        })
        .map_err(|e| tire_error(py, e, None))?;
    Ok(PyReducedTire {
        inner: Arc::new(red),
    })
}

/// The force history (the columns of `forces.csv`: t [s], F_x, F_y, F_lateral [N], spin
/// [rad/s], active contact nodes, Σ normal force [N], M_x, M_y, M_z [N m]) as 10 columns.
type History = [Vec<f64>; FORCE_COLUMNS.len()];

fn history_of(r: &RigResult) -> History {
    let mut h: History = Default::default();
    for s in &r.samples {
        for (col, x) in h.iter_mut().zip(sample_row(s)) {
            col.push(x);
        }
    }
    h
}

/// The reduced tire `given`, or `source` reduced (GIL released).
pub(crate) fn reduced_or(
    py: Python<'_>, given: Option<PyRef<'_, PyReducedTire>>, source: &TireSource,
) -> PyResult<Arc<ReducedTire>> {
    if let Some(t) = given {
        return Ok(Arc::clone(&t.inner));
    }
    let red = py
        .detach(|| {
            let fe = source.fe_model()?;
            source.reduce_fe(&fe).map(|(red, _)| red)
        })
        .map_err(|e| tire_error(py, e, None))?;
    Ok(Arc::new(red))
}

/// The steady-state study ([`tire::run_steady`], `flowmbd-tire steady`): side force and
/// aligning moment over slip angle, longitudinal force over drive torque, cornering stiffness
/// and pneumatic trail; returns the JSON text of the summary and the MF 6.1 `.tir` text of its
/// Magic Formula fit ([`tire::steady_tir`], the CLI's `tire.tir`; `None` without a fit). `tire`
/// replaces the reduction of `config.tire`.
#[pyfunction]
#[pyo3(signature = (config=None, tire=None))]
pub fn tire_steady(
    py: Python<'_>, config: Option<&str>, tire: Option<PyRef<'_, PyReducedTire>>,
) -> PyResult<(String, Option<String>)> {
    let c: SteadyStudyConfig = study_config(config, |_| {})?;
    let red = reduced_or(py, tire, &c.tire)?;
    let result = py.detach(|| run_steady(&red, &c, &mut |_| {}));
    match result {
        Ok(r) => {
            let s = steady_summary(&c, &r);
            let tir = s
                .magic_formula
                .as_ref()
                .map(|m| tire::steady_tir(&m.fit, &red, &c));
            Ok((to_json(&s)?, tir))
        }
        Err(e) => Err(match rig_input_error(e) {
            Ok(field) => input_error(field),
            Err(other) => numerical_error(py, other.to_string(), None),
        }),
    }
}

/// The cleat test (Ribaric §8.3) at one speed: `(summary JSON text, force history columns,
/// spectra columns (f [Hz], |F_x|, |F_y| [N]))`. `tire` replaces the reduction of
/// `config.tire`; `speed_kmh` replaces `rig.speed_kmh` (the CLI's `--speed`). A numerical
/// failure carries the history up to the failure as `partial`.
#[pyfunction]
#[pyo3(signature = (config=None, speed_kmh=None, tire=None))]
pub fn tire_cleat(
    py: Python<'_>, config: Option<&str>, speed_kmh: Option<f64>,
    tire: Option<PyRef<'_, PyReducedTire>>,
) -> PyResult<(String, History, [Vec<f64>; 3])> {
    let c = study_config(config, |c: &mut CleatStudyConfig| {
        if let Some(v) = speed_kmh {
            c.rig.speed_kmh = v;
        }
    })?;
    let red = reduced_or(py, tire, &c.tire)?;
    let settle = c.rig.settle_time;
    let mut seen: History = Default::default();
    let result = py.detach(|| {
        let mut observer = |_k: usize, sim: &RollingTire| -> Result<(), TireError> {
            for (col, x) in seen.iter_mut().zip(force_row(sim, settle)) {
                col.push(x);
            }
            Ok(())
        };
        let r = run_cleat_observed(&red, &c.rig, &mut |_| {}, &mut observer)?;
        let mut summary = cleat_summary(&red, &r);
        if c.cleat_phases > 1 {
            summary.phases = Some(phase_spread(
                &red,
                &c.rig,
                c.cleat_phases,
                &summary,
                &|_| {},
            )?);
        }
        let (sx, sy) = r.spectra();
        Ok::<_, TireError>((
            summary,
            history_of(&r),
            [sx.freq_hz, sx.amplitude, sy.amplitude],
        ))
    });
    match result {
        Ok((summary, history, spectra)) => Ok((to_json(&summary)?, history, spectra)),
        Err(e) => match rig_input_error(e) {
            Ok(field) => Err(input_error(field)),
            Err(other) => {
                let forces: serde_json::Map<String, serde_json::Value> = FORCE_COLUMNS
                    .iter()
                    .zip(&seen)
                    .map(|(n, col)| (n.to_string(), serde_json::json!(col)))
                    .collect();
                let partial = serde_json::json!({
                    "speed_kmh": c.rig.speed_kmh,
                    "steps_done": seen[0].len(),
                    "t_last_s": seen[0].last().copied().unwrap_or(f64::NAN),
                    "forces": forces,
                });
                Err(numerical_error(py, other.to_string(), Some(partial)))
            }
        },
    }
}

/// The rotating-modes study ([`tire::run_rotating`], `flowmbd-tire rotating-modes`): complex
/// modes of the free and loaded tire rolling at each speed, in the ground frame; returns
/// `(summary JSON text, series)` with the series `{"rotating_modes": {column: numpy array}}`
/// (the columns of `rotating_modes.csv`). `speeds_kmh` replaces `speeds_kmh` (the
/// CLI's `--speeds`); `tire` replaces the reduction of `config.tire`.
#[pyfunction]
#[pyo3(signature = (config=None, speeds_kmh=None, tire=None))]
pub fn tire_rotating_modes<'py>(
    py: Python<'py>, config: Option<&str>, speeds_kmh: Option<Vec<f64>>,
    tire: Option<PyRef<'_, PyReducedTire>>,
) -> PyResult<WithSeries<'py>> {
    use ::tire::rotating_study::{ROTATING_COLUMNS, RotatingStudyConfig, rotating_rows};
    let c = study_config(config, |c: &mut RotatingStudyConfig| {
        if let Some(v) = speeds_kmh {
            c.speeds_kmh = v;
        }
    })?;
    let red = reduced_or(py, tire, &c.tire)?;
    let (summary, _) = py
        .detach(|| ::tire::run_rotating(&red, &c, &mut |_| {}))
        .map_err(|e| tire_error(py, e, None))?;
    let series = columns(&ROTATING_COLUMNS, rotating_rows(&summary));
    with_series(py, &summary, [("rotating_modes", series)])
}

/// The speed sweep of the cleat test ([`tire::run_sweep`], `flowmbd-tire sweep`; Ribaric Figs.
/// 8-7, 8-8, 8-14): returns `(summary JSON text, series)` with the series (numpy arrays)
/// `{"waterfall": columns of waterfall.csv, "spectrum_map": {"speed_km_per_h", "f_Hz",
/// "fx_amp_N", "fy_amp_N" (speeds × frequencies, fx_matrix.csv / fy_matrix.csv)}, "run_series":
/// [per speed {"forces": columns of v<speed>_forces.csv, "spectra": v<speed>_spectra.csv}]}`.
/// `speeds_kmh` replaces `speeds_kmh`; `tire` replaces the reduction of `config.tire`. A
/// numerical failure names the speed and carries the runs done before it as `partial`.
#[pyfunction]
#[pyo3(signature = (config=None, speeds_kmh=None, tire=None))]
pub fn tire_sweep<'py>(
    py: Python<'py>, config: Option<&str>, speeds_kmh: Option<Vec<f64>>,
    tire: Option<PyRef<'_, PyReducedTire>>,
) -> PyResult<WithSeries<'py>> {
    use ::tire::study::{SPECTRUM_COLUMNS, spectrum_rows};
    use ::tire::sweep_study::{SweepStudyConfig, WATERFALL_COLUMNS};
    let c = study_config(config, |c: &mut SweepStudyConfig| {
        if let Some(v) = speeds_kmh {
            c.speeds_kmh = v;
        }
    })?;
    let red = reduced_or(py, tire, &c.tire)?;
    let mut run_series = Vec::new();
    let result = py.detach(|| {
        ::tire::run_sweep(&red, &c, &mut |_| {}, &mut |_, r| {
            let (sx, sy) = r.spectra();
            run_series.push((
                columns(&FORCE_COLUMNS, r.samples.iter().map(sample_row)),
                columns(&SPECTRUM_COLUMNS, spectrum_rows(&sx, &sy)),
            ));
            Ok(())
        })
    });
    match result {
        Ok(s) => {
            let series = PyDict::new(py);
            series.set_item(
                "waterfall",
                columns(&WATERFALL_COLUMNS, &s.waterfall).into_py(py)?,
            )?;
            let map = PyDict::new(py);
            map.set_item("speed_km_per_h", c.speeds_kmh.clone().into_pyarray(py))?;
            map.set_item("f_Hz", s.freq_hz.clone().into_pyarray(py))?;
            map.set_item("fx_amp_N", matrix(py, &s.fx_matrix, s.freq_hz.len()))?;
            map.set_item("fy_amp_N", matrix(py, &s.fy_matrix, s.freq_hz.len()))?;
            series.set_item("spectrum_map", map)?;
            let runs = PyList::empty(py);
            for (forces, spectra) in run_series {
                let d = PyDict::new(py);
                d.set_item("forces", forces.into_py(py)?)?;
                d.set_item("spectra", spectra.into_py(py)?)?;
                runs.append(d)?;
            }
            series.set_item("run_series", runs)?;
            Ok((to_json(&s.summary)?, series))
        }
        Err(f) => Err(match rig_input_error(f.error) {
            Ok(field) => input_error(field),
            Err(other) => numerical_error(
                py,
                format!("at {} km/h: {other}", f.speed_kmh),
                serde_json::to_value(&f.runs).ok(),
            ),
        }),
    }
}

/// The speed-dips study ([`tire::run_dips`], `flowmbd-tire dips`; Ribaric §8.3/§8.5): returns
/// `(summary JSON text, series)` with the series (numpy arrays) `{"profile_<ground>",
/// "prediction_<ground>", "sweep_<ground>" (when the sweep has speeds): the columns of the CSV
/// file of that name}` per ground. `tire` replaces the reduction of `config.tire`.
#[pyfunction]
#[pyo3(signature = (config=None, tire=None))]
pub fn tire_dips<'py>(
    py: Python<'py>, config: Option<&str>, tire: Option<PyRef<'_, PyReducedTire>>,
) -> PyResult<WithSeries<'py>> {
    use ::tire::dips_study::{
        DipsStudyConfig, PREDICTION_COLUMNS, PROFILE_COLUMNS, SWEEP_COLUMNS, prediction_rows,
        profile_rows, sweep_rows,
    };
    let c: DipsStudyConfig = study_config(config, |_| {})?;
    let red = reduced_or(py, tire, &c.tire)?;
    let (summary, grounds) = py
        .detach(|| ::tire::run_dips(&red, &c, &mut |_| {}))
        .map_err(|f| match rig_input_error(f.error) {
            Ok(field) => input_error(field),
            Err(other) => numerical_error(py, format!("{}: {other}", f.ground.name()), None),
        })?;
    let mut series = Vec::new();
    for d in &grounds {
        let n = d.ground.name();
        series.push((
            format!("profile_{n}"),
            columns(&PROFILE_COLUMNS, profile_rows(d)),
        ));
        series.push((
            format!("prediction_{n}"),
            columns(&PREDICTION_COLUMNS, prediction_rows(d)),
        ));
        if !d.sweep_speeds_kmh.is_empty() {
            series.push((format!("sweep_{n}"), columns(&SWEEP_COLUMNS, sweep_rows(d))));
        }
    }
    with_series(py, &summary, series)
}

/// The contact-patch study ([`tire::run_pressure`], `flowmbd-tire pressure`; Ribaric Fig.
/// 8-12): returns `(summary JSON text, series)` with the series `{"patch_drum", "patch_road":
/// the columns of patch_<ground>.csv}` (numpy arrays). `tire` replaces the reduction of
/// `config.tire`.
#[pyfunction]
#[pyo3(signature = (config=None, tire=None))]
pub fn tire_pressure<'py>(
    py: Python<'py>, config: Option<&str>, tire: Option<PyRef<'_, PyReducedTire>>,
) -> PyResult<WithSeries<'py>> {
    use ::tire::pressure_study::{PATCH_COLUMNS, PressureStudyConfig};
    let c: PressureStudyConfig = study_config(config, |_| {})?;
    let red = reduced_or(py, tire, &c.tire)?;
    let (summary, patches) = py
        .detach(|| ::tire::run_pressure(&red, &c))
        .map_err(|e| tire_error(py, e, None))?;
    let series = patches.iter().map(|p| {
        (
            format!("patch_{}", p.ground.name()),
            columns(&PATCH_COLUMNS, &p.rows),
        )
    });
    with_series(py, &summary, series)
}

/// The modes study ([`tire::run_modes`], `flowmbd-tire modes`): full FE against reduced
/// frequencies with the rim fixed, and the loaded modes at the static preload; returns
/// `(summary JSON text, series)` with the series `{"modes", "loaded_modes": the columns of
/// modes.csv and loaded_modes.csv}` (numpy arrays). The FE tire of `config.tire` is built and
/// reduced here (the full model is part of the study, so a prebuilt reduced tire is not taken).
#[pyfunction]
#[pyo3(signature = (config=None))]
pub fn tire_modes<'py>(py: Python<'py>, config: Option<&str>) -> PyResult<WithSeries<'py>> {
    use ::tire::modes_study::{
        LOADED_COLUMNS, MODES_COLUMNS, ModesStudyConfig, loaded_rows, modes_rows,
    };
    let c: ModesStudyConfig = study_config(config, |_| {})?;
    let (summary, loaded) = py
        .detach(|| {
            let fe = c.tire.fe_model()?;
            let (red, _) = c.tire.reduce_fe(&fe)?;
            ::tire::run_modes(&fe, &red, &c)
        })
        .map_err(|e| tire_error(py, e, None))?;
    let series = [
        ("modes", columns(&MODES_COLUMNS, modes_rows(&summary))),
        (
            "loaded_modes",
            columns(&LOADED_COLUMNS, loaded_rows(&loaded)),
        ),
    ];
    with_series(py, &summary, series)
}
