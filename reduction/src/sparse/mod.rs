//! Reductions of large sparse models: static (constraint) modes from **one** sparse Cholesky
//! factorization of `K_ii` reused for every boundary DOF (Lin (6.3)), Galerkin projection with
//! sparse products, and the partitioned Craig–Bampton ([`craig_bampton`]: fixed / boundary /
//! interior DOFs, fe-model's sparse shift-invert eigen solver, Lin (6.19)–(6.25)).

pub mod craig_bampton;

pub use craig_bampton::{
    CraigBamptonModes, CraigBamptonOptions, SparseCbReport, craig_bampton_modes,
    craig_bampton_sparse, fixed_interface_modes_sparse,
};

use crate::basis::{Basis, Method};
use crate::error::{ReductionError, Result};
use crate::partition::DofPartition;
use crate::reduced::ReducedModel;
use faer::linalg::solvers::Solve;
use faer::sparse::SparseColMatRef;
use faer::{Mat, Side};

pub(crate) fn fe_err(what: &str) -> impl Fn(fe_model::FeError) -> ReductionError + '_ {
    move |e| ReductionError::Numerical {
        what: what.to_string(),
        detail: e.to_string(),
    }
}

pub(crate) fn check_sparse(what: &str, a: SparseColMatRef<'_, usize, f64>, n: usize) -> Result<()> {
    if a.nrows() != n || a.ncols() != n {
        return Err(ReductionError::Shape {
            what: what.into(),
            expected: format!("{n}x{n}"),
            rows: a.nrows(),
            cols: a.ncols(),
        });
    }
    for j in 0..n {
        if let Some(v) = a.val_of_col(j).iter().find(|v| !v.is_finite()) {
            return Err(ReductionError::Numerical {
                what: what.into(),
                detail: format!("column {j} holds the non-finite value {v}"),
            });
        }
    }
    Ok(())
}

/// `K[rows, cols]` of a sparse matrix, with the block named in errors.
pub(crate) fn block(
    a: SparseColMatRef<'_, usize, f64>, rows: &[usize], cols: &[usize], what: &str,
) -> Result<faer::sparse::SparseColMat<usize, f64>> {
    fe_model::sparse::submatrix(a, rows, cols).map_err(fe_err(what))
}

/// `Ψs = −K_ii⁻¹ K_ib` from the extracted blocks: one sparse Cholesky of `K_ii` (AMD ordering,
/// faer) solved for all `n_b` right-hand sides at once.
pub(crate) fn static_modes_of_blocks(
    kii: SparseColMatRef<'_, usize, f64>, kib: SparseColMatRef<'_, usize, f64>,
) -> Result<Mat<f64>> {
    if kii.nrows() == 0 {
        return Ok(Mat::zeros(0, kib.ncols()));
    }
    let llt = kii
        .sp_cholesky(Side::Lower)
        .map_err(|_| ReductionError::NotPositiveDefinite {
            what: "interior stiffness K_ii".into(),
            hint: "the boundary and fixed sets must restrain every rigid-body motion".into(),
        })?;
    let mut x = kib.to_dense();
    llt.solve_in_place(x.as_mut());
    for j in 0..x.ncols() {
        for i in 0..x.nrows() {
            x[(i, j)] = -x[(i, j)];
        }
    }
    crate::linalg::check_finite("static modes", x.as_ref())?;
    Ok(x)
}

/// Static modes `Ψs = −K_ii⁻¹ K_ib` (Lin (6.3)) of a sparse `K`: one sparse Cholesky
/// factorization of `K_ii` (AMD ordering, faer), solved for all `n_b` right-hand sides at once.
/// Fixed DOFs of `part` are clamped (they belong to neither block). Returns the dense
/// `n_i × n_b` block (interior rows in ascending DOF order).
pub fn static_modes_sparse(
    k: SparseColMatRef<'_, usize, f64>, part: &DofPartition,
) -> Result<Mat<f64>> {
    check_sparse("stiffness matrix K", k, part.n())?;
    let kii = block(k, part.interior(), part.interior(), "K_ii extraction")?;
    let kib = block(k, part.interior(), part.boundary(), "K_ib extraction")?;
    static_modes_of_blocks(kii.as_ref(), kib.as_ref())
}

/// `Ψᵀ A Ψ` for sparse `A` and dense `Ψ` (symmetrised).
pub fn project_sparse(a: SparseColMatRef<'_, usize, f64>, psi: &Mat<f64>) -> Mat<f64> {
    let ap = fe_model::sparse::sparse_times_dense(a, psi.as_ref());
    let r = psi.transpose() * &ap;
    crate::linalg::symmetrize(&r)
}

/// Projects sparse `K`, `M` onto `basis` into a [`ReducedModel`].
pub fn reduced_model_sparse(
    basis: Basis, k: SparseColMatRef<'_, usize, f64>, m: SparseColMatRef<'_, usize, f64>,
    dofs_per_node: usize,
) -> Result<ReducedModel> {
    let n = basis.psi.nrows();
    check_sparse("stiffness matrix K", k, n)?;
    check_sparse("mass matrix M", m, n)?;
    if dofs_per_node == 0 || !n.is_multiple_of(dofs_per_node) {
        return Err(ReductionError::InvalidParameter {
            name: "dofs_per_node".into(),
            reason: format!("{dofs_per_node} does not divide the number of DOFs {n}"),
        });
    }
    Ok(ReducedModel {
        method: basis.method,
        dofs_per_node,
        mass: project_sparse(m, &basis.psi),
        stiffness: project_sparse(k, &basis.psi),
        damping: None,
        columns: basis.columns,
        psi: basis.psi,
    })
}

/// Guyan basis `[I; Ψs]` of a sparse model (natural row order, fixed rows zero).
pub fn guyan_sparse(k: SparseColMatRef<'_, usize, f64>, part: &DofPartition) -> Result<Basis> {
    let ps = static_modes_sparse(k, part)?;
    Ok(crate::basis::assemble(
        part,
        Method::Guyan,
        Some(&ps),
        None,
        &[],
        &[],
    ))
}
