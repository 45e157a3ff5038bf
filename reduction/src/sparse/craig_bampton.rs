//! Partitioned sparse Craig–Bampton reduction (Craig & Bampton, *Coupling of substructures for
//! dynamic analyses*, AIAA J. 6(7), 1968; Lin (6.19)–(6.25); Ribaric (3.15) and §8.2).
//!
//! The DOFs are split by a [`DofPartition`] into three sets:
//!
//! - **fixed** DOFs (a rim, a clamped face): zero rows in the basis, absent from every block;
//! - **boundary** DOFs `b` (interface, contact nodes): kept as physical coordinates through the
//!   static (constraint) modes `Ψs = −K_ii⁻¹ K_ib` (Lin (6.3)), which reproduce a unit
//!   displacement of each boundary DOF with the other boundary and the fixed DOFs held;
//! - **interior** DOFs `i`: represented by the lowest fixed-interface normal modes
//!   `K_ii φ = λ M_ii φ` (Lin (6.11)), truncated to `n_k`.
//!
//! `Ψ_CB = [I 0; Ψs Ψn^k]` (Lin (6.19)); `Ψ_CBᵀ K Ψ_CB = [K_G 0; 0 Λ^k]` (Lin (6.20)–(6.22)) and
//! `Ψ_CBᵀ M Ψ_CB` has the unit modal block of Lin (6.23)–(6.25). With every interior mode kept the
//! basis spans every deflection with the fixed DOFs held, so the reduced model is exact; with
//! truncation its eigenvalues bound those of the full model from above (Rayleigh–Ritz).
//!
//! `K_ii` is extracted once; its one sparse Cholesky factorization serves all `n_b` static
//! modes, and the interior eigenproblem is solved by fe-model's sparse shift-invert Lanczos
//! with its Sturm-sequence check ([`fe_model::eigen::sparse_modes`]; dense below
//! [`SparseEigenOptions::dense_below`] DOFs).

use super::{block, check_sparse, fe_err, reduced_model_sparse, static_modes_of_blocks};
use crate::basis::{Basis, Method, assemble};
use crate::error::Result;
use crate::partition::DofPartition;
use crate::reduced::ReducedModel;
use faer::Mat;
use faer::sparse::SparseColMatRef;
use fe_model::eigen::{Modes, SparseEigenOptions, SparseEigenReport, sparse_modes};
use serde::Serialize;
use std::time::Instant;

/// Settings of the partitioned Craig–Bampton reduction.
#[derive(Debug, Clone, Default)]
pub struct CraigBamptonOptions {
    /// Kept fixed-interface modes `n_k` (the lowest; more than the interior DOFs = all; 0 = the
    /// Guyan basis, Lin (6.5)).
    pub n_modes: usize,
    /// Options of the interior eigen solve (shift, Krylov subspace, Sturm check, dense limit).
    pub eigen: SparseEigenOptions,
}

impl CraigBamptonOptions {
    /// `n_modes` fixed-interface modes with the default eigen-solver options.
    pub fn with_modes(n_modes: usize) -> Self {
        Self {
            n_modes,
            eigen: SparseEigenOptions::default(),
        }
    }
}

/// Sizes, timings \[s\] and eigen-solver diagnostics of a Craig–Bampton reduction.
#[derive(Debug, Clone, Serialize)]
pub struct SparseCbReport {
    /// Full DOFs.
    pub n: usize,
    /// Fixed (clamped) DOFs.
    pub n_fixed: usize,
    /// Boundary DOFs.
    pub n_boundary: usize,
    /// Kept fixed-interface modes.
    pub n_modes: usize,
    /// Static modes (one Cholesky of `K_ii` + `n_b` solves) \[s\]; computed alongside the
    /// fixed-interface modes, so the two times overlap.
    pub static_modes_s: f64,
    /// Fixed-interface modes (sparse shift-invert Lanczos or dense) \[s\].
    pub normal_modes_s: f64,
    /// Galerkin projection of K and M \[s\] (0 until projected).
    pub projection_s: f64,
    /// Report of the interior eigen solve (`None` when no mode was asked for).
    pub eigen: Option<SparseEigenReport>,
}

/// The two families of Craig–Bampton vectors on the interior DOFs of a [`DofPartition`].
#[derive(Debug, Clone)]
pub struct CraigBamptonModes {
    /// Static (constraint) modes `Ψs = −K_ii⁻¹ K_ib` (Lin (6.3)), `n_i × n_b`: interior rows in
    /// ascending DOF order, columns in boundary order.
    pub static_modes: Mat<f64>,
    /// Fixed-interface modes `K_ii φ = λ M_ii φ` (Lin (6.11)): eigenvalues ascending \[rad²/s²\],
    /// `n_i × n_k` vectors with `ΦᵀM_iiΦ = I`, signed by fe-model's convention.
    pub normal_modes: Modes,
    /// Sizes, timings and eigen diagnostics.
    pub report: SparseCbReport,
}

impl CraigBamptonModes {
    /// `Ψ_CB = [I 0; Ψs Ψn^k]` (Lin (6.19)) on all DOFs in natural row order, fixed rows zero;
    /// columns: the boundary DOFs, then the modes. Without modes this is the Guyan basis
    /// `[I; Ψs]` (Lin (6.5)) and is labelled [`Method::Guyan`].
    pub fn basis(&self, part: &DofPartition) -> Basis {
        let nk = self.normal_modes.values.len();
        let method = if nk == 0 {
            Method::Guyan
        } else {
            Method::CraigBampton
        };
        let kept: Vec<usize> = (0..nk).collect();
        assemble(
            part,
            method,
            Some(&self.static_modes),
            Some(&self.normal_modes.vectors),
            &self.normal_modes.values,
            &kept,
        )
    }
}

/// The lowest `count` modes of `(K_ii, M_ii)` (blocks already extracted).
fn interior_modes(
    kii: SparseColMatRef<'_, usize, f64>, mii: SparseColMatRef<'_, usize, f64>, count: usize,
    opts: &SparseEigenOptions,
) -> Result<(Modes, Option<SparseEigenReport>)> {
    let ni = kii.nrows();
    if count == 0 || ni == 0 {
        let none = Modes {
            values: Vec::new(),
            frequencies_hz: Vec::new(),
            vectors: Mat::zeros(ni, 0),
        };
        return Ok((none, None));
    }
    let (modes, report) = sparse_modes(kii, mii, count.min(ni), opts)
        .map_err(fe_err("fixed-interface eigen solve (K_ii, M_ii)"))?;
    Ok((modes, Some(report)))
}

/// The lowest `count` fixed-interface modes `K_ii φ = λ M_ii φ` (Lin (6.11)) of sparse `K`, `M`:
/// boundary and fixed DOFs held. With an empty boundary set these are the modes of the model
/// clamped at its fixed DOFs. Vectors are `n_i × count` on the interior DOFs (ascending); the
/// report is `None` when `count` is 0.
pub fn fixed_interface_modes_sparse(
    k: SparseColMatRef<'_, usize, f64>, m: SparseColMatRef<'_, usize, f64>, part: &DofPartition,
    count: usize, opts: &SparseEigenOptions,
) -> Result<(Modes, Option<SparseEigenReport>)> {
    check_sparse("stiffness matrix K", k, part.n())?;
    check_sparse("mass matrix M", m, part.n())?;
    let ii = part.interior();
    let kii = block(k, ii, ii, "K_ii extraction")?;
    let mii = block(m, ii, ii, "M_ii extraction")?;
    interior_modes(kii.as_ref(), mii.as_ref(), count, opts)
}

/// Static and fixed-interface modes of the partitioned Craig–Bampton reduction (module
/// documentation): `K_ii` extracted once, one sparse Cholesky of it for all static modes, the
/// lowest `opts.n_modes` interior modes by the sparse shift-invert eigen solver.
pub fn craig_bampton_modes(
    k: SparseColMatRef<'_, usize, f64>, m: SparseColMatRef<'_, usize, f64>, part: &DofPartition,
    opts: &CraigBamptonOptions,
) -> Result<CraigBamptonModes> {
    check_sparse("stiffness matrix K", k, part.n())?;
    check_sparse("mass matrix M", m, part.n())?;
    let (ii, b) = (part.interior(), part.boundary());
    let t0 = Instant::now();
    let kii = block(k, ii, ii, "K_ii extraction")?;
    let kii = kii.as_ref();
    // the two families are independent: computed side by side (the eigen solver's operator is
    // sequential, so the static modes' factorisation and solves use the other core)
    let (static_modes, normal) = rayon::join(
        || {
            let kib = block(k, ii, b, "K_ib extraction")?;
            let s = static_modes_of_blocks(kii, kib.as_ref())?;
            Ok::<_, crate::error::ReductionError>((s, t0.elapsed()))
        },
        || {
            let t1 = Instant::now();
            let mii = block(m, ii, ii, "M_ii extraction")?;
            let r = interior_modes(kii, mii.as_ref(), opts.n_modes, &opts.eigen)?;
            Ok::<_, crate::error::ReductionError>((r, t1.elapsed()))
        },
    );
    let (static_modes, static_s) = static_modes?;
    let ((normal_modes, eigen), normal_s) = normal?;
    let report = SparseCbReport {
        n: part.n(),
        n_fixed: part.fixed().len(),
        n_boundary: b.len(),
        n_modes: normal_modes.values.len(),
        static_modes_s: static_s.as_secs_f64(),
        normal_modes_s: normal_s.as_secs_f64(),
        projection_s: 0.0,
        eigen,
    };
    Ok(CraigBamptonModes {
        static_modes,
        normal_modes,
        report,
    })
}

/// Partitioned Craig–Bampton reduced model of a large sparse model: [`craig_bampton_modes`],
/// the basis `Ψ_CB` ([`CraigBamptonModes::basis`]) and the sparse Galerkin projection
/// `M_r = ΨᵀMΨ`, `K_r = ΨᵀKΨ` (Lin (6.20)–(6.25)).
pub fn craig_bampton_sparse(
    k: SparseColMatRef<'_, usize, f64>, m: SparseColMatRef<'_, usize, f64>, part: &DofPartition,
    opts: &CraigBamptonOptions, dofs_per_node: usize,
) -> Result<(ReducedModel, SparseCbReport)> {
    let modes = craig_bampton_modes(k, m, part, opts)?;
    let t = Instant::now();
    let basis = modes.basis(part);
    let red = reduced_model_sparse(basis, k, m, dofs_per_node)?;
    let mut report = modes.report;
    report.projection_s = t.elapsed().as_secs_f64();
    Ok((red, report))
}
