//! `flowmbd.reduce`: clamped normal modes, the partitioned Craig–Bampton reduction
//! (Lin (6.3), (6.11), (6.19)–(6.25)) and Eitelberg's reduction (Lin §6.6.4) of sparse mass and stiffness matrices, through
//! [`reduction::sparse`] (the engine of `flowmbd-reduce` and the tire reduction). Matrices come
//! in as coordinate triplets (scipy.sparse `tocoo()`, duplicates summed) and go out as numpy
//! arrays.

use crate::numerical_error;
use faer::Mat;
use faer::sparse::{SparseColMat, Triplet};
use fe_model::eigen::SparseEigenOptions;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use reduction::eitelberg_model::EitelbergModel;
use reduction::sparse::{CraigBamptonOptions, craig_bampton_sparse, fixed_interface_modes_sparse};
use reduction::{DofPartition, ReductionError};

/// A sparse `n × n` matrix from triplets, named `name` in errors (indices in range, values
/// finite, the three arrays of equal length).
fn sparse(
    name: &str, n: usize, rows: PyReadonlyArray1<'_, i64>, cols: PyReadonlyArray1<'_, i64>,
    vals: PyReadonlyArray1<'_, f64>,
) -> PyResult<SparseColMat<usize, f64>> {
    let (r, c, v) = (rows.as_slice()?, cols.as_slice()?, vals.as_slice()?);
    if r.len() != c.len() || r.len() != v.len() {
        return Err(PyValueError::new_err(format!(
            "{name}: row, column and value arrays differ in length"
        )));
    }
    let mut t = Vec::with_capacity(v.len());
    for k in 0..v.len() {
        let (i, j, x) = (r[k], c[k], v[k]);
        if i < 0 || j < 0 || i as usize >= n || j as usize >= n {
            return Err(PyValueError::new_err(format!(
                "{name}: entry ({i}, {j}) is outside the {n}x{n} matrix"
            )));
        }
        if !x.is_finite() {
            return Err(PyValueError::new_err(format!(
                "{name}[{i},{j}] = {x} is not finite"
            )));
        }
        t.push(Triplet::new(i as usize, j as usize, x));
    }
    let a = SparseColMat::try_new_from_triplets(n, n, &t)
        .map_err(|e| PyValueError::new_err(format!("{name}: {e:?}")))?;
    // a stiffness or mass matrix is symmetric (issue 35: a non-symmetric K was reduced)
    fe_model::plausibility::check_symmetric(name, a.as_ref())
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(a)
}

/// Bad input (shape, DOF sets, parameters, a singular `K_ii`) raises `ValueError`; a failed
/// solve raises `flowmbd.NumericalError`.
fn reduction_error(py: Python<'_>, e: ReductionError) -> PyErr {
    match e {
        ReductionError::Numerical { .. } => numerical_error(py, e.to_string(), None),
        other => PyValueError::new_err(other.to_string()),
    }
}

/// Run `solve` with the GIL released; its error mapped by [`reduction_error`].
fn detached<T: Send>(
    py: Python<'_>, solve: impl FnOnce() -> Result<T, ReductionError> + Send,
) -> PyResult<T> {
    py.detach(solve).map_err(|e| reduction_error(py, e))
}

/// The mass and stiffness matrices `(M, K)` (`n × n`) from their triplets ([`sparse`]).
fn mass_stiffness(
    n: usize, m: Triplets<'_>, k: Triplets<'_>,
) -> PyResult<(SparseColMat<usize, f64>, SparseColMat<usize, f64>)> {
    Ok((
        sparse("M", n, m.0, m.1, m.2)?,
        sparse("K", n, k.0, k.1, k.2)?,
    ))
}

fn to_numpy<'py>(py: Python<'py>, a: &Mat<f64>) -> Matrix<'py> {
    Array2::from_shape_fn((a.nrows(), a.ncols()), |(i, j)| a[(i, j)]).into_pyarray(py)
}

type Triplets<'py> = (
    PyReadonlyArray1<'py, i64>,
    PyReadonlyArray1<'py, i64>,
    PyReadonlyArray1<'py, f64>,
);

/// A matrix handed to Python (numpy).
type Matrix<'py> = Bound<'py, PyArray2<f64>>;

/// A vector handed to Python (numpy).
type Vector<'py> = Bound<'py, PyArray1<f64>>;

/// `(eigenvalues, frequencies, vectors)` of [`modes`].
type ModesOut<'py> = (Vec<f64>, Vec<f64>, Matrix<'py>);

/// `(M_r, K_r, Ψ, frequencies)` of [`craig_bampton`].
type CbOut<'py> = (Matrix<'py>, Matrix<'py>, Matrix<'py>, Vector<'py>);

/// The lowest `count` modes of `K φ = λ M φ` with the `fixed` DOFs clamped (Lin (6.11) with an
/// empty boundary set): `(eigenvalues [rad²/s²], frequencies [Hz], n × count M-normalised
/// vectors with zero rows at the fixed DOFs)`.
#[pyfunction]
pub fn modes<'py>(
    py: Python<'py>, n: usize, m: Triplets<'py>, k: Triplets<'py>, count: usize, fixed: Vec<usize>,
) -> PyResult<ModesOut<'py>> {
    let (m, k) = mass_stiffness(n, m, k)?;
    let part = DofPartition::new(n, &[], &fixed).map_err(|e| reduction_error(py, e))?;
    // fewer modes than asked would come back silently (issue 35)
    if count > part.interior().len() {
        return Err(PyValueError::new_err(format!(
            "count: {count} modes asked, but the model has only {} free DOFs ({n} DOFs, {} fixed)",
            part.interior().len(),
            part.fixed().len()
        )));
    }
    let (modes, _) = detached(py, || {
        fixed_interface_modes_sparse(
            k.as_ref(),
            m.as_ref(),
            &part,
            count,
            &SparseEigenOptions::default(),
        )
    })?;
    if modes.values.len() < count {
        return Err(numerical_error(
            py,
            format!(
                "count: {count} modes asked, the eigen solver found {}",
                modes.values.len()
            ),
            None,
        ));
    }
    let interior = part.interior();
    let mut full = Mat::<f64>::zeros(n, modes.values.len());
    for (r, &dof) in interior.iter().enumerate() {
        for j in 0..modes.values.len() {
            full[(dof, j)] = modes.vectors[(r, j)];
        }
    }
    Ok((modes.values, modes.frequencies_hz, to_numpy(py, &full)))
}

/// Craig–Bampton reduction (Lin (6.19)–(6.25)) keeping the `boundary` DOFs and `n_modes`
/// fixed-interface modes: `(M_r, K_r, Ψ, natural frequencies of the reduced model [Hz])`.
#[pyfunction]
pub fn craig_bampton<'py>(
    py: Python<'py>, n: usize, m: Triplets<'py>, k: Triplets<'py>, boundary: Vec<usize>,
    n_modes: usize,
) -> PyResult<CbOut<'py>> {
    let (m, k) = mass_stiffness(n, m, k)?;
    let part =
        DofPartition::from_boundary_dofs(n, &boundary).map_err(|e| reduction_error(py, e))?;
    let opts = CraigBamptonOptions::with_modes(n_modes);
    let (red, hz) = detached(py, || {
        let (red, _) = craig_bampton_sparse(k.as_ref(), m.as_ref(), &part, &opts, 1)?;
        let hz = red.natural_frequencies_hz()?;
        Ok((red, hz))
    })?;
    Ok((
        to_numpy(py, &red.mass),
        to_numpy(py, &red.stiffness),
        to_numpy(py, &red.psi),
        hz.into_pyarray(py),
    ))
}

/// `(M⁻¹K on the boundary, A_r, B_r, C_r, natural frequencies [Hz])` of [`eitelberg`].
type EitelbergOut<'py> = (
    Matrix<'py>,
    Matrix<'py>,
    Matrix<'py>,
    Matrix<'py>,
    Vector<'py>,
);

/// Eitelberg's reduction of the structure onto the `boundary` DOFs with the `fixed` DOFs
/// clamped (Lin §6.6.4, [`reduction::eitelberg_model::EitelbergModel`]; dense, at most
/// [`reduction::eitelberg_model::EITELBERG_LIMIT`] unclamped DOFs).
#[pyfunction]
pub fn eitelberg<'py>(
    py: Python<'py>, n: usize, m: Triplets<'py>, k: Triplets<'py>, boundary: Vec<usize>,
    fixed: Vec<usize>,
) -> PyResult<EitelbergOut<'py>> {
    let (m, k) = mass_stiffness(n, m, k)?;
    let part = DofPartition::new(n, &boundary, &fixed).map_err(|e| reduction_error(py, e))?;
    let (red, hz) = detached(py, || {
        let red = EitelbergModel::reduce_sparse(k.as_ref(), m.as_ref(), &part)?;
        let hz = red.natural_frequencies_hz()?;
        Ok((red, hz))
    })?;
    Ok((
        to_numpy(py, &red.minv_k),
        to_numpy(py, &red.reduction.a_r),
        to_numpy(py, &red.reduction.b_r),
        to_numpy(py, &red.reduction.c_r),
        hz.into_pyarray(py),
    ))
}

/// The `flowmbd-reduce lin-beam` study (Lin ch. 6.2, 6.3, 7.1, 8.5 on the Appendix A beam,
/// [`flowmbd_cases::lin::beam_study::lin_beam`]): returns `(summary JSON text, {"profiles",
/// "frequencies": the columns of profiles.csv and frequencies.csv})`.
#[pyfunction]
#[pyo3(signature = (config=None))]
pub fn lin_beam<'py>(py: Python<'py>, config: Option<&str>) -> PyResult<crate::WithSeries<'py>> {
    use flowmbd_cases::lin::beam_study::{
        FREQUENCY_COLUMNS, LinBeamStudyConfig, PROFILE_COLUMNS, lin_beam as run,
    };
    let c: LinBeamStudyConfig = crate::study_config(config, |_| {})?;
    let r = detached(py, || run(&c))?;
    crate::with_series(
        py,
        &r.summary,
        [
            (
                "profiles",
                crate::columns(&PROFILE_COLUMNS, r.profile_rows()),
            ),
            (
                "frequencies",
                crate::columns(&FREQUENCY_COLUMNS, r.frequency_rows()),
            ),
        ],
    )
}

/// The `flowmbd-reduce lin-slab` study (Lin §7.2 simulations 1–3 on the Appendix B slab,
/// [`flowmbd_cases::lin::slab_study::lin_slab`]): returns `(summary JSON text, series)` with
/// the series `{"<sim>_node8"` per completed simulation, and `"sim3_tables"`,
/// `"sim3_source_node8"` when simulation 3 ran`}`, the columns of the CSV files of the same
/// names (the CLI has no flags of its own: everything is in `config`).
#[pyfunction]
#[pyo3(signature = (config=None))]
pub fn lin_slab<'py>(py: Python<'py>, config: Option<&str>) -> PyResult<crate::WithSeries<'py>> {
    use flowmbd_cases::lin::slab_study::{
        LinSlabConfig, LinSlabError, SIM3_SOURCE_COLUMNS, lin_slab as run, sim3_source_rows,
        sim3_tables_header, sim3_tables_rows,
    };
    let c: LinSlabConfig = crate::study_config(config, |_| {})?;
    let r = py
        .detach(|| run(&c, |_| std::ops::ControlFlow::Continue(())))
        .map_err(|e| match e {
            LinSlabError::Input(field) => crate::input_error(field),
            LinSlabError::Numerical {
                source,
                partial_statics_m,
            } => numerical_error(
                py,
                source.to_string(),
                partial_statics_m.and_then(|p| serde_json::to_value(p).ok()),
            ),
        })?;
    let mut series: Vec<(String, crate::Columns)> = r
        .simulations
        .iter()
        .map(|s| {
            let name = format!("{}_node8", s.name);
            (name, crate::columns(&s.node8_header(), s.node8_rows()))
        })
        .collect();
    if let Some(src) = &r.sim3_source {
        series.push((
            "sim3_tables".into(),
            crate::columns(&sim3_tables_header(), sim3_tables_rows(src)),
        ));
        series.push((
            "sim3_source_node8".into(),
            crate::columns(&SIM3_SOURCE_COLUMNS, sim3_source_rows(src)),
        ));
    }
    crate::with_series(py, &r.summary, series)
}

/// Coordinate triplets `(rows, cols, values)` of a sparse matrix as numpy arrays.
type TripletsOut<'py> = (
    Bound<'py, PyArray1<usize>>,
    Bound<'py, PyArray1<usize>>,
    Vector<'py>,
);

fn triplets_out<'py>(py: Python<'py>, a: &SparseColMat<usize, f64>) -> TripletsOut<'py> {
    let (mut r, mut c, mut v) = (Vec::new(), Vec::new(), Vec::new());
    for (i, j, x) in fe_model::sparse::triplets(a.as_ref()) {
        r.push(i);
        c.push(j);
        v.push(x);
    }
    (r.into_pyarray(py), c.into_pyarray(py), v.into_pyarray(py))
}

/// `(summary JSON text, nodes (n × 3) [m], K triplets [N/m], M triplets [kg], {node set: node
/// indices})` of [`tire_mesh`].
type TireMeshOut<'py> = (
    String,
    Matrix<'py>,
    TripletsOut<'py>,
    TripletsOut<'py>,
    Bound<'py, pyo3::types::PyDict>,
);

/// The `flowmbd-reduce tire-mesh` study ([`fe_model::generate::tire_mesh::tire_mesh`]): the
/// generated truck-tire carcass with K (inflation geometric stiffness when
/// `geometric_stiffness`) and M (`mass`: consistent or lumped) on all DOFs; what the CLI
/// writes as `mesh.json`, `K.mtx`, `M.mtx` and `node_sets.json` comes back as arrays.
#[pyfunction]
#[pyo3(signature = (config=None))]
pub fn tire_mesh<'py>(py: Python<'py>, config: Option<&str>) -> PyResult<TireMeshOut<'py>> {
    use fe_model::generate::tire_mesh::{TireMeshConfig, TireMeshError, tire_mesh as run};
    let c: TireMeshConfig = crate::study_config(config, |_| {})?;
    let r = py.detach(|| run(&c)).map_err(|e| match e {
        TireMeshError::Generate(e) => {
            crate::input_error(mbd_core::InvalidField::new("tire", e.to_string()))
        }
        e @ TireMeshError::Assembly(_) => numerical_error(py, e.to_string(), None),
    })?;
    let mesh = &r.tire.model.mesh;
    let nodes = Array2::from_shape_fn((mesh.nodes.len(), 3), |(i, j)| mesh.nodes[i][j]);
    let sets = pyo3::types::PyDict::new(py);
    for (name, ids) in &mesh.node_sets {
        sets.set_item(name, ids.clone().into_pyarray(py))?;
    }
    Ok((
        crate::to_json(&r.summary)?,
        nodes.into_pyarray(py),
        triplets_out(py, &r.k),
        triplets_out(py, &r.m),
        sets,
    ))
}
