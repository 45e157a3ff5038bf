//! Reductions of large sparse models: static (constraint) modes from **one** sparse Cholesky
//! factorization of `K_ii` reused for every boundary DOF (Lin (6.3)), Galerkin projection with
//! sparse products, and Craig–Bampton with fe-model's sparse shift-invert eigen solver
//! (Lin (6.19)–(6.25)).

use crate::basis::{Basis, Column, Method};
use crate::error::{ReductionError, Result};
use crate::partition::DofPartition;
use crate::reduced::ReducedModel;
use faer::linalg::solvers::Solve;
use faer::sparse::SparseColMatRef;
use faer::sparse::linalg::matmul::sparse_dense_matmul;
use faer::{Accum, Mat, Par, Side};
use serde::Serialize;
use std::time::Instant;

fn fe_err(what: &str) -> impl Fn(fe_model::FeError) -> ReductionError + '_ {
    move |e| ReductionError::Numerical {
        what: what.to_string(),
        detail: e.to_string(),
    }
}

fn check_sparse(what: &str, a: SparseColMatRef<'_, usize, f64>, n: usize) -> Result<()> {
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

/// Static modes `Ψs = −K_ii⁻¹ K_ib` (Lin (6.3)) of a sparse `K`: one sparse Cholesky
/// factorization of `K_ii` (AMD ordering, faer), solved for all `n_b` right-hand sides at once.
/// Returns the dense `n_i × n_b` block (interior rows in ascending DOF order).
pub fn static_modes_sparse(
    k: SparseColMatRef<'_, usize, f64>,
    part: &DofPartition,
) -> Result<Mat<f64>> {
    check_sparse("stiffness matrix K", k, part.n())?;
    let kii = fe_model::sparse::submatrix(k, part.interior(), part.interior())
        .map_err(fe_err("K_ii extraction"))?;
    let kib = fe_model::sparse::submatrix(k, part.interior(), part.boundary())
        .map_err(fe_err("K_ib extraction"))?;
    let llt = kii
        .sp_cholesky(Side::Lower)
        .map_err(|_| ReductionError::NotPositiveDefinite {
            what: "interior stiffness K_ii".into(),
            hint: "the boundary set must restrain every rigid-body motion".into(),
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

/// `Ψᵀ A Ψ` for sparse `A` and dense `Ψ` (symmetrised).
pub fn project_sparse(a: SparseColMatRef<'_, usize, f64>, psi: &Mat<f64>) -> Mat<f64> {
    let mut ap = Mat::<f64>::zeros(a.nrows(), psi.ncols());
    sparse_dense_matmul(
        ap.as_mut(),
        Accum::Replace,
        a,
        psi.as_ref(),
        1.0,
        Par::rayon(0),
    );
    let r = psi.transpose() * &ap;
    crate::linalg::symmetrize(&r)
}

/// Projects sparse `K`, `M` onto `basis` into a [`ReducedModel`].
pub fn reduced_model_sparse(
    basis: Basis,
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
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

/// Guyan basis `[I; Ψs]` of a sparse model (natural row order).
pub fn guyan_sparse(k: SparseColMatRef<'_, usize, f64>, part: &DofPartition) -> Result<Basis> {
    let ps = static_modes_sparse(k, part)?;
    Ok(assemble(part, Method::Guyan, &ps, None, &[]))
}

fn assemble(
    part: &DofPartition,
    method: Method,
    ps: &Mat<f64>,
    phi: Option<&Mat<f64>>,
    lam: &[f64],
) -> Basis {
    let b = part.boundary();
    let ii = part.interior();
    let nb = b.len();
    let nk = lam.len();
    let mut psi = Mat::<f64>::zeros(part.n(), nb + nk);
    let mut columns = Vec::with_capacity(nb + nk);
    for (c, &d) in b.iter().enumerate() {
        psi[(d, c)] = 1.0;
        for (r, &di) in ii.iter().enumerate() {
            psi[(di, c)] = ps[(r, c)];
        }
        columns.push(Column::Boundary { dof: d });
    }
    if let Some(phi) = phi {
        for j in 0..nk {
            for (r, &di) in ii.iter().enumerate() {
                psi[(di, nb + j)] = phi[(r, j)];
            }
            columns.push(Column::Mode {
                index: j,
                eigenvalue: lam[j],
            });
        }
    }
    Basis {
        method,
        psi,
        columns,
    }
}
/// Timings of a sparse Craig–Bampton reduction \[s\].
#[derive(Debug, Clone, Serialize)]
pub struct SparseCbReport {
    /// Full DOFs.
    pub n: usize,
    /// Boundary DOFs.
    pub n_boundary: usize,
    /// Kept fixed-interface modes.
    pub n_modes: usize,
    /// Static modes (one Cholesky of `K_ii` + `n_b` solves).
    pub static_modes_s: f64,
    /// Fixed-interface modes (sparse shift-invert Lanczos).
    pub normal_modes_s: f64,
    /// Galerkin projection of K and M.
    pub projection_s: f64,
}

/// Craig–Bampton `Ψ = [I 0; Ψs Ψn^k]` (Lin (6.19)) of a large sparse model: static modes from
/// one sparse factorization of `K_ii`, the `n_modes` lowest fixed-interface modes from
/// [`fe_model::eigen::sparse_modes`], then the projection.
pub fn craig_bampton_sparse(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    part: &DofPartition,
    n_modes: usize,
    dofs_per_node: usize,
) -> Result<(ReducedModel, SparseCbReport)> {
    check_sparse("mass matrix M", m, part.n())?;
    let t0 = Instant::now();
    let ps = static_modes_sparse(k, part)?;
    let t1 = Instant::now();
    let (lam, phi) = if n_modes == 0 {
        (Vec::new(), Mat::zeros(part.interior().len(), 0))
    } else {
        let kii = fe_model::sparse::submatrix(k, part.interior(), part.interior())
            .map_err(fe_err("K_ii extraction"))?;
        let mii = fe_model::sparse::submatrix(m, part.interior(), part.interior())
            .map_err(fe_err("M_ii extraction"))?;
        let (modes, _) = fe_model::eigen::sparse_modes(
            kii.as_ref(),
            mii.as_ref(),
            n_modes,
            &fe_model::eigen::SparseEigenOptions::default(),
        )
        .map_err(fe_err("fixed-interface eigen solve"))?;
        let take = n_modes.min(modes.values.len());
        (
            modes.values[..take].to_vec(),
            modes.vectors.subcols(0, take).to_owned(),
        )
    };
    let t2 = Instant::now();
    let basis = assemble(part, Method::CraigBampton, &ps, Some(&phi), &lam);
    let red = reduced_model_sparse(basis, k, m, dofs_per_node)?;
    let t3 = Instant::now();
    Ok((
        red,
        SparseCbReport {
            n: part.n(),
            n_boundary: part.boundary().len(),
            n_modes: lam.len(),
            static_modes_s: (t1 - t0).as_secs_f64(),
            normal_modes_s: (t2 - t1).as_secs_f64(),
            projection_s: (t3 - t2).as_secs_f64(),
        },
    ))
}
