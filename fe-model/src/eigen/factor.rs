//! Sparse symmetric factorizations of `A = K − σ M` used by the sparse eigen solver:
//! `P A Pᵀ = L Lᵀ` (shift-invert operator) and `P A Pᵀ = L D Lᵀ` (Sturm count), both with
//! faer's AMD-ordered simplicial/supernodal Cholesky (`faer::sparse::linalg::cholesky`).

use crate::FeError;
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
    factorize_symbolic_cholesky, supernodal::SupernodalLdltRef, supernodal::SupernodalLltRef,
};
use faer::sparse::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_lower_triangular_transpose_in_place,
};
use faer::sparse::{SparseColMat, SparseColMatRef};
use faer::{Conj, MatMut, Par, Side};
use std::sync::Arc;

/// `K − σ M` with the union pattern of K and M (so that every shift gives the same pattern
/// and one symbolic factorization serves all shifts).
pub fn shifted(
    k: SparseColMatRef<'_, usize, f64>, m: SparseColMatRef<'_, usize, f64>, sigma: f64,
) -> Result<SparseColMat<usize, f64>, FeError> {
    super::operator::shifted_merge(k, m, sigma)
}

/// Symbolic Cholesky analysis (AMD ordering) of a symmetric pattern, shareable across shifts.
#[derive(Debug, Clone)]
pub struct Analysis {
    symbolic: Arc<SymbolicCholesky<usize>>,
    par: Par,
}

impl Analysis {
    /// Analyse the pattern of `a` (lower triangle used).
    pub fn new(a: SparseColMatRef<'_, usize, f64>) -> Result<Self, FeError> {
        let symbolic = factorize_symbolic_cholesky(
            a.symbolic(),
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams::default(),
        )
        .map_err(|e| FeError::Sparse(format!("symbolic Cholesky: {e:?}")))?;
        Ok(Self {
            symbolic: Arc::new(symbolic),
            par: Par::rayon(0),
        })
    }

    /// The parallelism of the numeric factorisations ([`Self::llt`], [`Self::negative_pivots`]);
    /// default `Par::rayon(0)`, the threads of rayon's current pool.
    pub fn with_par(self, par: Par) -> Self {
        Self { par, ..self }
    }

    /// Number of stored entries of the factor L.
    pub fn factor_nnz(&self) -> usize {
        self.symbolic.len_val()
    }

    /// Forward and inverse fill-reducing permutation (identity if none).
    pub fn perm(&self) -> (Vec<usize>, Vec<usize>) {
        match self.symbolic.perm() {
            Some(p) => {
                let (f, i) = p.arrays();
                (f.to_vec(), i.to_vec())
            }
            None => {
                let n = self.symbolic.nrows();
                ((0..n).collect(), (0..n).collect())
            }
        }
    }

    /// Numeric `L Lᵀ` of `a` (which must have the analysed pattern). `name` is used in the
    /// error when `a` is not positive definite.
    pub fn llt(&self, a: SparseColMatRef<'_, usize, f64>, name: &str) -> Result<Llt, FeError> {
        let mut values = vec![0.0; self.symbolic.len_val()];
        let par = self.par;
        let mut mem = MemBuffer::new(
            self.symbolic
                .factorize_numeric_llt_scratch::<f64>(par, Default::default()),
        );
        self.symbolic
            .factorize_numeric_llt(
                &mut values,
                a,
                Side::Lower,
                LltRegularization::default(),
                par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .map_err(|e| FeError::NotPositiveDefinite {
                name: name.to_string(),
                detail: {
                    let faer::linalg::solvers::LltError::NonPositivePivot { index } = e;
                    format!(
                        " (non-positive pivot at DOF {}, 1-based)",
                        self.original_dof(index) + 1
                    )
                },
            })?;
        Ok(Llt {
            symbolic: self.symbolic.clone(),
            values,
        })
    }

    /// The original (unpermuted) index of the `j`-th pivot of the factorization.
    fn original_dof(&self, j: usize) -> usize {
        match self.symbolic.perm() {
            Some(p) => p.arrays().0.get(j).copied().unwrap_or(j),
            None => j,
        }
    }

    /// Number of negative pivots of `L D Lᵀ = P a Pᵀ` (Sylvester's law of inertia: the number
    /// of negative eigenvalues of `a`). Errors on a zero pivot.
    pub fn negative_pivots(&self, a: SparseColMatRef<'_, usize, f64>) -> Result<usize, FeError> {
        Ok(self.negative_pivot_dofs(a)?.len())
    }

    /// The DOFs (0-based, original order) whose pivots of `L D Lᵀ = P a Pᵀ` are negative,
    /// ascending; their number is the number of negative eigenvalues of `a` (Sylvester's law
    /// of inertia). Errors on a zero pivot.
    pub fn negative_pivot_dofs(
        &self, a: SparseColMatRef<'_, usize, f64>,
    ) -> Result<Vec<usize>, FeError> {
        let mut values = vec![0.0; self.symbolic.len_val()];
        let par = self.par;
        let mut mem = MemBuffer::new(
            self.symbolic
                .factorize_numeric_ldlt_scratch::<f64>(par, Default::default()),
        );
        self.symbolic
            .factorize_numeric_ldlt(
                &mut values,
                a,
                Side::Lower,
                LdltRegularization::default(),
                par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .map_err(|e| FeError::Eigen(format!("LDLᵀ for the Sturm count failed ({e:?})")))?;
        let mut neg = Vec::new();
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(s) => {
                // D is stored as the first (diagonal) entry of each column of L
                let cp = s.col_ptr();
                for j in 0..s.nrows() {
                    let d = values[cp[j]];
                    if !(d.is_finite() && d != 0.0) {
                        return Err(FeError::Eigen(format!("LDLᵀ: zero pivot in column {j}")));
                    }
                    if d < 0.0 {
                        neg.push(self.original_dof(j));
                    }
                }
            }
            SymbolicCholeskyRaw::Supernodal(s) => {
                let l = SupernodalLdltRef::new(s, &values);
                for sn in 0..s.n_supernodes() {
                    let begin = s.supernode_begin()[sn];
                    let v = l.supernode(sn).val();
                    for i in 0..v.ncols() {
                        let d = v[(i, i)];
                        if !(d.is_finite() && d != 0.0) {
                            return Err(FeError::Eigen(format!(
                                "LDLᵀ: zero pivot in supernode {sn}"
                            )));
                        }
                        if d < 0.0 {
                            neg.push(self.original_dof(begin + i));
                        }
                    }
                }
            }
        }
        neg.sort_unstable();
        Ok(neg)
    }
}

/// Numeric Cholesky factor `P A Pᵀ = L Lᵀ` with separate `L⁻¹` and `L⁻ᵀ` solves.
#[derive(Debug, Clone)]
pub struct Llt {
    symbolic: Arc<SymbolicCholesky<usize>>,
    values: Vec<f64>,
}

impl Llt {
    /// Workspace for the solves with `ncols` right-hand sides.
    pub fn scratch(&self, ncols: usize, par: Par) -> StackReq {
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(_) => StackReq::EMPTY,
            SymbolicCholeskyRaw::Supernodal(s) => s.solve_in_place_scratch::<f64>(ncols, par),
        }
    }

    /// `x ← L⁻¹ x` (x in permuted order).
    pub fn l_solve(&self, x: MatMut<'_, f64>, par: Par, stack: &mut MemStack) {
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(s) => {
                let l = SparseColMatRef::new(s.factor(), &self.values);
                solve_lower_triangular_in_place(l, Conj::No, x, par);
            }
            SymbolicCholeskyRaw::Supernodal(s) => {
                SupernodalLltRef::new(s, &self.values).l_solve_with_conj(Conj::No, x, par, stack);
            }
        }
    }

    /// `x ← L⁻ᵀ x` (x in permuted order).
    pub fn lt_solve(&self, x: MatMut<'_, f64>, par: Par, stack: &mut MemStack) {
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(s) => {
                let l = SparseColMatRef::new(s.factor(), &self.values);
                solve_lower_triangular_transpose_in_place(l, Conj::No, x, par);
            }
            SymbolicCholeskyRaw::Supernodal(s) => {
                SupernodalLltRef::new(s, &self.values).l_transpose_solve_with_conj(
                    Conj::No,
                    x,
                    par,
                    stack,
                );
            }
        }
    }
}
