//! # flowmbd-python
//!
//! The native part (`flowmbd._native`) of the `flowmbd` Python package: thin pyo3 wrappers
//! over the library crates (`drives`, `flowing`, `reduction`, `fe-model`, the paper cases of
//! `flowmbd-cases`; the reduced tire as the class `ReducedTire`). Configurations come
//! in as JSON text of the Python dicts (the same keys as the TOML files) and are read into the
//! study's configuration struct, checked with the same [`mbd_core::Validate`] as the apps (so
//! bad input raises `ValueError` with the CLI's `field: reason` message) and run with the GIL
//! released. Study results go back as the JSON text of the study's summary (the content of its
//! `summary.json`); the Python layer turns number series into numpy arrays. Matrices cross as
//! numpy arrays (rust-numpy).
//!
//! The crate is a workspace member built as `cdylib` (by maturin) and `rlib` (so that
//! `cargo test --workspace` and `cargo clippy --workspace` build it like any crate; pyo3 only
//! drops the libpython link when maturin sets `PYO3_BUILD_EXTENSION_MODULE`).

use mbd_core::InvalidField;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use serde::de::DeserializeOwned;

mod beam;
mod belt;
mod reduce;
mod stepping;
mod string;
mod tire;
mod tire_fmu;
mod tire_stepping;

/// `ValueError` carrying the CLI's one-line message for a rejected field (`field: reason`).
pub(crate) fn input_error(e: InvalidField) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// `flowmbd.NumericalError(message, partial)` (defined in `flowmbd/_errors.py`) with the results
/// computed before the failure attached as JSON text (the `partial` of the CLI's
/// `summary.json`).
pub(crate) fn numerical_error(
    py: Python<'_>, message: String, partial: Option<serde_json::Value>,
) -> PyErr {
    let partial = partial.map(|p| p.to_string());
    match py
        .import("flowmbd._errors")
        .and_then(|m| m.getattr("NumericalError"))
        .and_then(|cls| cls.call1((message, partial)))
    {
        Ok(err) => PyErr::from_value(err),
        Err(e) => e,
    }
}

/// The configuration `C`: its defaults, or the JSON object `json` read deeply over them as the
/// CLI reads a TOML file ([`mbd_core::config::from_partial`]: tables merged at every depth,
/// arrays and scalars replaced; unknown keys and wrong types raise `ValueError` naming the
/// dictionary path, e.g. `config["drive"]["pulleys"][0]["radius"]`). Not yet validated.
pub(crate) fn read_config<C>(json: Option<&str>) -> PyResult<C>
where
    C: DeserializeOwned + serde::Serialize + Default + mbd_core::config::PartialRules,
{
    let Some(text) = json else {
        return Ok(C::default());
    };
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| PyValueError::new_err(format!("config: {e}")))?;
    let table = match toml::Value::try_from(&value) {
        Ok(toml::Value::Table(t)) => t,
        Ok(_) => return Err(PyValueError::new_err("config: expected a dict")),
        // TOML has no null: a None somewhere in the dict
        Err(e) => {
            return Err(PyValueError::new_err(format!(
                "config: {e} (None is not a value; leave the key out for its default)"
            )));
        }
    };
    mbd_core::config::from_partial(table).map_err(|e| {
        let mut at = String::from("config");
        for step in e.steps() {
            match step {
                mbd_core::config::PathStep::Key(k) => at.push_str(&format!("[{k:?}]")),
                mbd_core::config::PathStep::Index(i) => at.push_str(&format!("[{i}]")),
            }
        }
        PyValueError::new_err(format!("{at}: {}", e.message))
    })
}

/// A study's configuration `C` as the CLI's `run_study` makes it: read from `json`
/// ([`read_config`]), changed by `overrides` (the keyword arguments that replace keys, like the
/// CLI's flags), then validated once (bad input raises `ValueError` naming the field).
pub(crate) fn study_config<C>(json: Option<&str>, overrides: impl FnOnce(&mut C)) -> PyResult<C>
where
    C: DeserializeOwned
        + serde::Serialize
        + Default
        + mbd_core::config::PartialRules
        + mbd_core::Validate,
{
    let mut c: C = read_config(json)?;
    overrides(&mut c);
    c.validate().map_err(input_error)?;
    Ok(c)
}

/// JSON text of a summary (infallible for the plain summary structs).
pub(crate) fn to_json<S: serde::Serialize>(summary: &S) -> PyResult<String> {
    serde_json::to_string(summary)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))
}

/// The series of a CSV file: its header and columns (collected with the GIL released, then
/// handed to Python by [`Columns::into_py`]).
pub(crate) struct Columns(Vec<(String, Vec<f64>)>);

/// The columns of the CSV with `header` (names as `&str` or `String`) and `rows` (as the app
/// writes it).
pub(crate) fn columns<R: AsRef<[f64]>, S: AsRef<str>>(
    header: &[S], rows: impl IntoIterator<Item = R>,
) -> Columns {
    let mut cols: Vec<Vec<f64>> = vec![Vec::new(); header.len()];
    for row in rows {
        for (col, x) in cols.iter_mut().zip(row.as_ref()) {
            col.push(*x);
        }
    }
    Columns(
        header
            .iter()
            .map(|h| h.as_ref().to_string())
            .zip(cols)
            .collect(),
    )
}

/// What a study with series returns to Python: the JSON text of its summary and the dict
/// `{name: {column: numpy array}}` of its series.
pub(crate) type WithSeries<'py> = (String, Bound<'py, pyo3::types::PyDict>);

/// `summary` as JSON text ([`to_json`]) with its `series`, each named by the CSV file the app
/// writes ([`WithSeries`]).
pub(crate) fn with_series<'py, S: serde::Serialize, K: AsRef<str>>(
    py: Python<'py>, summary: &S, series: impl IntoIterator<Item = (K, Columns)>,
) -> PyResult<WithSeries<'py>> {
    let d = pyo3::types::PyDict::new(py);
    for (name, cols) in series {
        d.set_item(name.as_ref(), cols.into_py(py)?)?;
    }
    Ok((to_json(summary)?, d))
}

impl Columns {
    /// A dict `{column: numpy array}` in the CSV's column order.
    pub(crate) fn into_py(self, py: Python<'_>) -> PyResult<Bound<'_, pyo3::types::PyDict>> {
        use numpy::IntoPyArray;
        let d = pyo3::types::PyDict::new(py);
        for (name, col) in self.0 {
            d.set_item(name, col.into_pyarray(py))?;
        }
        Ok(d)
    }
}

/// The native module `flowmbd._native`.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(belt::speed_loss, m)?)?;
    m.add_function(wrap_pyfunction!(belt::ancf, m)?)?;
    m.add_function(wrap_pyfunction!(belt::plate, m)?)?;
    m.add_function(wrap_pyfunction!(belt::fead, m)?)?;
    m.add_function(wrap_pyfunction!(belt::design, m)?)?;
    m.add_function(wrap_pyfunction!(belt::wave, m)?)?;
    m.add_function(wrap_pyfunction!(belt::demo, m)?)?;
    m.add_class::<stepping::PyBeltSimulation>()?;
    m.add_class::<tire_stepping::PyTireSimulation>()?;
    m.add_class::<tire_fmu::PyTireCoSimulation>()?;
    m.add_function(wrap_pyfunction!(tire_fmu::tire_build_fmu, m)?)?;
    m.add_function(wrap_pyfunction!(string::string_modes, m)?)?;
    m.add_function(wrap_pyfunction!(string::string_sweep, m)?)?;
    m.add_function(wrap_pyfunction!(string::string_simulate, m)?)?;
    m.add_function(wrap_pyfunction!(string::string_wrap, m)?)?;
    m.add_function(wrap_pyfunction!(reduce::modes, m)?)?;
    m.add_function(wrap_pyfunction!(reduce::craig_bampton, m)?)?;
    m.add_function(wrap_pyfunction!(reduce::eitelberg, m)?)?;
    m.add_function(wrap_pyfunction!(reduce::lin_beam, m)?)?;
    m.add_function(wrap_pyfunction!(reduce::lin_slab, m)?)?;
    m.add_function(wrap_pyfunction!(reduce::tire_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(beam::beam_simply_supported, m)?)?;
    m.add_function(wrap_pyfunction!(beam::beam_cantilever, m)?)?;
    m.add_function(wrap_pyfunction!(beam::beam_pendulum, m)?)?;
    m.add_function(wrap_pyfunction!(beam::beam_spinning, m)?)?;
    m.add_function(wrap_pyfunction!(beam::beam_ground_contact, m)?)?;
    m.add_class::<tire::PyReducedTire>()?;
    m.add_function(wrap_pyfunction!(tire::tire_generate, m)?)?;
    m.add_function(wrap_pyfunction!(tire::tire_import, m)?)?;
    m.add_function(wrap_pyfunction!(tire::tire_reduce, m)?)?;
    m.add_function(wrap_pyfunction!(tire::tire_cleat, m)?)?;
    m.add_function(wrap_pyfunction!(tire::tire_steady, m)?)?;
    m.add_function(wrap_pyfunction!(tire::tire_rotating_modes, m)?)?;
    m.add_function(wrap_pyfunction!(tire::tire_sweep, m)?)?;
    m.add_function(wrap_pyfunction!(tire::tire_dips, m)?)?;
    m.add_function(wrap_pyfunction!(tire::tire_pressure, m)?)?;
    m.add_function(wrap_pyfunction!(tire::tire_modes, m)?)?;
    m.add("CLEAT_FORCE_COLUMNS", ::tire::study::FORCE_COLUMNS.to_vec())?;
    m.add(
        "CLEAT_SPECTRUM_COLUMNS",
        ::tire::study::SPECTRUM_COLUMNS.to_vec(),
    )?;
    Ok(())
}
