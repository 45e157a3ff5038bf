//! Eitelberg's reduction of a user's structure with a boundary and clamped DOFs (Lin §6.6.4,
//! [`crate::eitelberg::eitelberg_structure`]) as a result to write and read: the reduced
//! state-space system and `M_⁻¹K_` on the boundary DOFs, with its natural frequencies (the
//! `flowmbd-reduce reduce --method eitelberg` file and the Python `flowmbd.reduce.eitelberg`).

use crate::eitelberg::{EitelbergReduction, eitelberg_structure};
use crate::error::{ReductionError, Result};
use crate::linalg::eig_to_hz;
use crate::partition::DofPartition;
use faer::sparse::SparseColMatRef;
use faer::{Mat, MatRef};
use std::path::Path;

/// Format name of the file written by [`EitelbergModel::save`].
pub const EITELBERG_FORMAT: &str = "flowmbd-eitelberg";

/// Largest number of unclamped DOFs reduced by Eitelberg's method (dense `M⁻¹` and a
/// Bartels–Stewart Lyapunov solve on `2n` states, O(n³) with a large constant).
pub const EITELBERG_LIMIT: usize = 1000;

/// Eitelberg's reduced structure (module documentation).
#[derive(Debug, Clone)]
pub struct EitelbergModel {
    /// DOFs of the full model.
    pub n_full: usize,
    /// The boundary DOFs of the full model, in the order of the reduced coordinates.
    pub boundary: Vec<usize>,
    /// The clamped DOFs removed before the reduction.
    pub fixed: Vec<usize>,
    /// `M_⁻¹K_` on the boundary DOFs (Lin §6.6.4's printed matrix) \[1/s²\].
    pub minv_k: Mat<f64>,
    /// The reduced state-space system `ξ = {δ_b; δ̇_b}` (Lin (6.37)–(6.38)).
    pub reduction: EitelbergReduction,
}

impl EitelbergModel {
    /// Reduce `M δ̈ + K δ = f` (`n × n`, dense) onto the boundary DOFs of `part`, its fixed
    /// DOFs removed first (Lin (6.42)–(6.45)).
    ///
    /// # Errors
    /// More than [`EITELBERG_LIMIT`] unclamped DOFs, a singular `M`, or a failed solve.
    pub fn reduce(k: MatRef<'_, f64>, m: MatRef<'_, f64>, part: &DofPartition) -> Result<Self> {
        Self::check_size(part)?;
        let free = part.unfixed();
        let mut at = vec![usize::MAX; part.n()];
        for (i, &d) in free.iter().enumerate() {
            at[d] = i;
        }
        let boundary: Vec<usize> = part.boundary().iter().map(|&d| at[d]).collect();
        let sub =
            |a: MatRef<'_, f64>| Mat::from_fn(free.len(), free.len(), |i, j| a[(free[i], free[j])]);
        let (minv_k, reduction) = eitelberg_structure(sub(k).as_ref(), sub(m).as_ref(), &boundary)?;
        Ok(Self {
            n_full: part.n(),
            boundary: part.boundary().to_vec(),
            fixed: part.fixed().to_vec(),
            minv_k,
            reduction,
        })
    }

    /// [`reduce`](Self::reduce) of sparse matrices (made dense: the method is dense).
    ///
    /// # Errors
    /// As [`reduce`](Self::reduce); the size is checked before the dense copies are made.
    pub fn reduce_sparse(
        k: SparseColMatRef<'_, usize, f64>, m: SparseColMatRef<'_, usize, f64>, part: &DofPartition,
    ) -> Result<Self> {
        Self::check_size(part)?;
        Self::reduce(k.to_dense().as_ref(), m.to_dense().as_ref(), part)
    }

    fn check_size(part: &DofPartition) -> Result<()> {
        let free = part.n() - part.fixed().len();
        if free > EITELBERG_LIMIT {
            return Err(ReductionError::InvalidParameter {
                name: "method eitelberg".into(),
                reason: format!(
                    "{free} unclamped DOFs exceed the dense limit of {EITELBERG_LIMIT}; use guyan (the same reduced model, Lin §6.6.4) or cb"
                ),
            });
        }
        Ok(())
    }

    /// Natural frequencies of the reduced structure, `√λ/2π` of the eigenvalues `λ` of
    /// `M_⁻¹K_`, ascending \[Hz\].
    ///
    /// # Errors
    /// The eigenvalue solver fails.
    pub fn natural_frequencies_hz(&self) -> Result<Vec<f64>> {
        let ev = self
            .minv_k
            .eigenvalues()
            .map_err(|e| ReductionError::Numerical {
                what: "eigenvalues of the Eitelberg M⁻¹K".into(),
                detail: format!("{e:?}"),
            })?;
        let mut lam: Vec<f64> = ev.iter().map(|z| z.re).collect();
        lam.sort_by(f64::total_cmp);
        Ok(eig_to_hz(&lam))
    }

    /// The versioned JSON text: `format`, `version`, `n_full`, `boundary`, `fixed`, and the
    /// matrices `minv_k`, `a_r`, `b_r`, `c_r` as lists of rows.
    pub fn to_json(&self) -> Result<String> {
        let rows = |a: &Mat<f64>| -> Vec<Vec<f64>> {
            (0..a.nrows())
                .map(|i| (0..a.ncols()).map(|j| a[(i, j)]).collect())
                .collect()
        };
        serde_json::to_string(&serde_json::json!({
            "format": EITELBERG_FORMAT,
            "version": 1,
            "n_full": self.n_full,
            "boundary": self.boundary,
            "fixed": self.fixed,
            "minv_k": rows(&self.minv_k),
            "a_r": rows(&self.reduction.a_r),
            "b_r": rows(&self.reduction.b_r),
            "c_r": rows(&self.reduction.c_r),
        }))
        .map_err(|e| ReductionError::Numerical {
            what: "Eitelberg model JSON".into(),
            detail: e.to_string(),
        })
    }

    /// Writes [`to_json`](Self::to_json) to `path` (atomically).
    ///
    /// # Errors
    /// The file cannot be written.
    pub fn save(&self, path: &Path) -> Result<()> {
        let text = self.to_json()?;
        fe_model::io::write_atomic(path, text.as_bytes()).map_err(|e| ReductionError::File {
            path: path.display().to_string(),
            reason: e.to_string(),
        })
    }
}
