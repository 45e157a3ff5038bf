//! Sturm-sequence count: the number of eigenvalues of `K φ = λ M φ` below a cut `c` equals the
//! number of negative pivots of `L D Lᵀ = P (K − c M) Pᵀ` (Sylvester's law of inertia; Bathe,
//! *Finite Element Procedures* §11.4.3). Used to prove that no mode below the cut was missed.

use super::factor::{Analysis, shifted};
use crate::FeError;
use faer::sparse::SparseColMatRef;

/// Number of eigenvalues of `K φ = λ M φ` strictly below `cut` \[rad²/s²\].
///
/// `analysis` must be the symbolic analysis of the union pattern of K and M (see
/// [`super::factor::shifted`]); pass `None` to analyse here.
pub fn sturm_count(
    k: SparseColMatRef<'_, usize, f64>, m: SparseColMatRef<'_, usize, f64>, cut: f64,
    analysis: Option<&Analysis>,
) -> Result<usize, FeError> {
    if !cut.is_finite() {
        return Err(FeError::param("sturm cut", cut, "must be finite"));
    }
    let a = shifted(k, m, cut)?;
    let owned;
    let an = match analysis {
        Some(a) => a,
        None => {
            owned = Analysis::new(a.as_ref())?;
            &owned
        }
    };
    an.negative_pivots(a.as_ref())
}
