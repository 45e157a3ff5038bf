//! Linear-algebra helpers on [`SysMatrix`] and the augmented (KKT) solver.
//!
//! The augmented matrix of Ribaric (2.16) / Lin (2.27),
//!
//! ```text
//!   [ S   Dᵀ ] [ x ]   [ b ]
//!   [ D   0  ] [ μ ] = [ c ]
//! ```
//!
//! is factored densely (faer partial-pivoting LU) when every block is dense, and with faer's
//! sparse LU otherwise. The sparse path keeps the symbolic factorisation and reuses it as long
//! as the sparsity pattern of the assembled matrix does not change (Newton iterations, time
//! steps of a model with a fixed pattern).

use crate::{MbdError, SysMatrix};
use faer::Mat;
use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat, Triplet};

impl SysMatrix {
    /// `y = A x` (overwrites `y`).
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        self.mul_vec_add(1.0, x, y);
    }

    /// `y += s · A x`.
    pub fn mul_vec_add(&self, s: f64, x: &[f64], y: &mut [f64]) {
        match self {
            SysMatrix::Dense(m) => {
                for j in 0..m.ncols() {
                    let xj = s * x[j];
                    if xj == 0.0 {
                        continue;
                    }
                    let col = m.col(j);
                    for i in 0..m.nrows() {
                        y[i] += col[i] * xj;
                    }
                }
            }
            SysMatrix::Sparse(m) => {
                let cp = m.symbolic().col_ptr();
                let ri = m.symbolic().row_idx();
                let val = m.val();
                for j in 0..m.ncols() {
                    let xj = s * x[j];
                    for k in cp[j]..cp[j + 1] {
                        y[ri[k]] += val[k] * xj;
                    }
                }
            }
        }
    }

    /// `y += s · Aᵀ x`.
    pub fn tmul_vec_add(&self, s: f64, x: &[f64], y: &mut [f64]) {
        match self {
            SysMatrix::Dense(m) => {
                for j in 0..m.ncols() {
                    let col = m.col(j);
                    let mut acc = 0.0;
                    for i in 0..m.nrows() {
                        acc += col[i] * x[i];
                    }
                    y[j] += s * acc;
                }
            }
            SysMatrix::Sparse(m) => {
                let cp = m.symbolic().col_ptr();
                let ri = m.symbolic().row_idx();
                let val = m.val();
                for j in 0..m.ncols() {
                    let mut acc = 0.0;
                    for k in cp[j]..cp[j + 1] {
                        acc += val[k] * x[ri[k]];
                    }
                    y[j] += s * acc;
                }
            }
        }
    }

    /// Calls `f(row, col, value)` for every stored entry (every entry of a dense matrix, zeros
    /// included, so that the pattern does not depend on the values).
    pub fn for_each_entry(&self, mut f: impl FnMut(usize, usize, f64)) {
        match self {
            SysMatrix::Dense(m) => {
                for j in 0..m.ncols() {
                    for i in 0..m.nrows() {
                        f(i, j, m[(i, j)]);
                    }
                }
            }
            SysMatrix::Sparse(m) => {
                let cp = m.symbolic().col_ptr();
                let ri = m.symbolic().row_idx();
                let val = m.val();
                for j in 0..m.ncols() {
                    for k in cp[j]..cp[j + 1] {
                        f(ri[k], j, val[k]);
                    }
                }
            }
        }
    }

    /// Whether the matrix is stored sparsely.
    pub fn is_sparse(&self) -> bool {
        matches!(self, SysMatrix::Sparse(_))
    }

    /// Whether every stored entry is finite.
    pub fn all_finite(&self) -> bool {
        let mut ok = true;
        self.for_each_entry(|_, _, v| ok &= v.is_finite());
        ok
    }

    /// An `nr × nc` matrix from `entries` (duplicates summed), sparse when `sparse`, dense
    /// otherwise; `t` \[s\] names the time of a failed sparse assembly.
    pub fn from_triplets(
        nr: usize,
        nc: usize,
        entries: &[Triplet<usize, usize, f64>],
        sparse: bool,
        t: f64,
    ) -> Result<SysMatrix, MbdError> {
        if sparse {
            SparseColMat::try_new_from_triplets(nr, nc, entries)
                .map(SysMatrix::Sparse)
                .map_err(|e| MbdError::Model {
                    t,
                    message: format!("sparse assembly failed: {e:?}"),
                })
        } else {
            let mut m = Mat::<f64>::zeros(nr, nc);
            for tr in entries {
                m[(tr.row, tr.col)] += tr.val;
            }
            Ok(SysMatrix::Dense(m))
        }
    }

    /// Assembles `blocks` (each `(row offset, column offset, block)`) and the single `entries`
    /// into an `nr × nc` matrix (overlaps summed): the assembly of stacked constraint rows and
    /// block-diagonal composites. Sparse when `sparse` or any block is sparse (dense blocks
    /// then contribute every entry, zeros included), dense otherwise.
    pub fn assemble(
        blocks: &[(usize, usize, SysMatrix)],
        mut entries: Vec<Triplet<usize, usize, f64>>,
        nr: usize,
        nc: usize,
        sparse: bool,
        t: f64,
    ) -> Result<SysMatrix, MbdError> {
        if sparse || blocks.iter().any(|b| b.2.is_sparse()) {
            for (r0, c0, b) in blocks {
                b.for_each_entry(|i, j, v| entries.push(Triplet::new(r0 + i, c0 + j, v)));
            }
            Self::from_triplets(nr, nc, &entries, true, t)
        } else {
            let mut m = Mat::<f64>::zeros(nr, nc);
            for (r0, c0, b) in blocks {
                b.for_each_entry(|i, j, v| m[(r0 + i, c0 + j)] += v);
            }
            for tr in entries {
                m[(tr.row, tr.col)] += tr.val;
            }
            Ok(SysMatrix::Dense(m))
        }
    }
}

/// A term `scale · A` of the (1,1) block `S` of the augmented matrix.
pub type ScaledBlock<'a> = (f64, &'a SysMatrix);

/// The factored augmented matrix.
enum Factor {
    Dense(PartialPivLu<f64>),
    Sparse(Lu<usize, f64>),
}

/// Cached assembly order (triplet indices → CSC) of the last sparse matrix.
struct AssemblyCache {
    indices: Vec<(usize, usize)>,
    symbolic: SymbolicSparseColMat<usize>,
    argsort: Argsort<usize>,
}

/// Cached sparse symbolic analysis together with the pattern it was computed for.
struct SymbolicCache {
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    symbolic: SymbolicLu<usize>,
}

/// Factoriser/solver of the augmented matrix `[S Dᵀ; D 0]` (Ribaric (2.16), Lin (2.27)).
///
/// `S = Σ sₖ Aₖ` is given as a list of scaled blocks (mass, damping and stiffness in the
/// generalized-α iteration matrix). The sparse path reuses its symbolic LU while the pattern
/// is unchanged; [`KktSolver::symbolic_factorizations`] counts how often it had to be redone.
pub struct KktSolver {
    factor: Option<Factor>,
    cache: Option<SymbolicCache>,
    assembly: Option<AssemblyCache>,
    n: usize,
    n_c: usize,
    /// Number of numeric factorisations performed.
    pub factorizations: usize,
    /// Number of symbolic (sparse) analyses performed.
    pub symbolic_factorizations: usize,
}

impl Default for KktSolver {
    fn default() -> Self {
        Self::new()
    }
}

/// Relative pivot threshold below which a dense factorisation is reported as singular.
const PIVOT_TOL: f64 = 1e-13;

impl KktSolver {
    /// An empty solver (nothing factored yet).
    pub fn new() -> Self {
        Self {
            factor: None,
            cache: None,
            assembly: None,
            n: 0,
            n_c: 0,
            factorizations: 0,
            symbolic_factorizations: 0,
        }
    }

    /// Whether a factorisation is available for [`solve`](Self::solve).
    pub fn is_factored(&self) -> bool {
        self.factor.is_some()
    }

    /// Drops the numeric factorisation (the symbolic analysis is kept).
    pub fn invalidate(&mut self) {
        self.factor = None;
    }

    /// Assembles and factors `[Σ sₖ Aₖ, Dᵀ; D, 0]`. `d` may be `None` or have zero rows for an
    /// unconstrained system. `t` is only used in error messages.
    pub fn factor(
        &mut self,
        blocks: &[ScaledBlock<'_>],
        d: Option<&SysMatrix>,
        t: f64,
    ) -> Result<(), MbdError> {
        self.factor = None;
        let n = blocks.first().map(|b| b.1.nrows()).unwrap_or(0);
        let n_c = d.map(|d| d.nrows()).unwrap_or(0);
        for (_, b) in blocks {
            if b.nrows() != n || b.ncols() != n {
                return Err(MbdError::Model {
                    t,
                    message: format!(
                        "system matrix block is {}x{}, expected {n}x{n}",
                        b.nrows(),
                        b.ncols()
                    ),
                });
            }
        }
        if let Some(d) = d
            && n_c > 0
            && d.ncols() != n
        {
            return Err(MbdError::Model {
                t,
                message: format!(
                    "constraint Jacobian is {}x{}, expected {n_c}x{n}",
                    d.nrows(),
                    d.ncols()
                ),
            });
        }
        let any_sparse = blocks.iter().any(|b| b.1.is_sparse()) || d.is_some_and(|d| d.is_sparse());
        let dim = n + n_c;
        self.n = n;
        self.n_c = n_c;
        if !any_sparse {
            let mut a = Mat::<f64>::zeros(dim, dim);
            for (s, b) in blocks {
                if *s == 0.0 {
                    continue;
                }
                if let SysMatrix::Dense(m) = b {
                    for j in 0..n {
                        for i in 0..n {
                            a[(i, j)] += s * m[(i, j)];
                        }
                    }
                }
            }
            if let Some(SysMatrix::Dense(dm)) = d {
                for i in 0..n_c {
                    for j in 0..n {
                        let v = dm[(i, j)];
                        a[(n + i, j)] = v;
                        a[(j, n + i)] = v;
                    }
                }
            }
            if !a.as_ref().is_all_finite() {
                return Err(MbdError::NonFinite {
                    what: "system matrix (mass, tangent or constraint Jacobian)".into(),
                    t,
                });
            }
            let lu = a.partial_piv_lu();
            let u = lu.U();
            let mut umax = 0.0f64;
            let mut umin = f64::INFINITY;
            for i in 0..dim {
                let v = u[(i, i)].abs();
                umax = umax.max(v);
                umin = umin.min(v);
            }
            if dim > 0 && (umin <= PIVOT_TOL * umax || !umin.is_finite()) {
                return Err(MbdError::Singular {
                    t,
                    detail: format!(
                        "augmented matrix of size {dim} is singular (pivot ratio {:.3e})",
                        if umax > 0.0 { umin / umax } else { 0.0 }
                    ),
                });
            }
            self.factor = Some(Factor::Dense(lu));
        } else {
            let mut trip: Vec<Triplet<usize, usize, f64>> = Vec::new();
            for (s, b) in blocks {
                b.for_each_entry(|i, j, v| trip.push(Triplet::new(i, j, s * v)));
            }
            if let Some(d) = d {
                d.for_each_entry(|i, j, v| {
                    trip.push(Triplet::new(n + i, j, v));
                    trip.push(Triplet::new(j, n + i, v));
                });
            }
            // explicit diagonal so that the pattern always contains it
            for i in 0..dim {
                trip.push(Triplet::new(i, i, 0.0));
            }
            if trip.iter().any(|t| !t.val.is_finite()) {
                return Err(MbdError::NonFinite {
                    what: "system matrix (mass, tangent or constraint Jacobian)".into(),
                    t,
                });
            }
            let a = self.assemble(dim, &trip, t)?;
            let same = self.cache.as_ref().is_some_and(|c| {
                c.col_ptr == a.symbolic().col_ptr() && c.row_idx == a.symbolic().row_idx()
            });
            if !same {
                let symbolic =
                    SymbolicLu::try_new(a.symbolic()).map_err(|e| MbdError::Singular {
                        t,
                        detail: format!("symbolic LU failed: {e:?}"),
                    })?;
                self.symbolic_factorizations += 1;
                self.cache = Some(SymbolicCache {
                    col_ptr: a.symbolic().col_ptr().to_vec(),
                    row_idx: a.symbolic().row_idx().to_vec(),
                    symbolic,
                });
            }
            let sym = self
                .cache
                .as_ref()
                .map(|c| c.symbolic.clone())
                .ok_or_else(|| MbdError::Model {
                    t,
                    message: "missing symbolic factorisation".into(),
                })?;
            let lu =
                Lu::try_new_with_symbolic(sym, a.as_ref()).map_err(|e| MbdError::Singular {
                    t,
                    detail: format!("sparse LU of the augmented matrix failed: {e:?}"),
                })?;
            self.factor = Some(Factor::Sparse(lu));
        }
        self.factorizations += 1;
        Ok(())
    }

    /// CSC matrix from triplets, reusing the sorting of the previous call when the triplet
    /// indices are identical (same model, new values).
    fn assemble(
        &mut self,
        dim: usize,
        trip: &[Triplet<usize, usize, f64>],
        t: f64,
    ) -> Result<SparseColMat<usize, f64>, MbdError> {
        let err = |e: String| MbdError::Model {
            t,
            message: format!("sparse assembly failed: {e}"),
        };
        let same = self.assembly.as_ref().is_some_and(|c| {
            c.symbolic.nrows() == dim
                && c.indices.len() == trip.len()
                && c.indices
                    .iter()
                    .zip(trip)
                    .all(|(&(r, cc), tr)| r == tr.row && cc == tr.col)
        });
        if !same {
            let pairs: Vec<Pair<usize, usize>> =
                trip.iter().map(|tr| Pair::new(tr.row, tr.col)).collect();
            let (symbolic, argsort) = SymbolicSparseColMat::try_new_from_indices(dim, dim, &pairs)
                .map_err(|e| err(format!("{e:?}")))?;
            self.assembly = Some(AssemblyCache {
                indices: trip.iter().map(|tr| (tr.row, tr.col)).collect(),
                symbolic,
                argsort,
            });
        }
        let c = self
            .assembly
            .as_ref()
            .ok_or_else(|| err("missing assembly cache".into()))?;
        let vals: Vec<f64> = trip.iter().map(|tr| tr.val).collect();
        SparseColMat::new_from_argsort(c.symbolic.clone(), &c.argsort, &vals)
            .map_err(|e| err(format!("{e:?}")))
    }

    /// Solves for several right-hand sides at once: the columns of `rhs` (`(n + n_c) × k`) hold
    /// `[b; c]` on input and `[x; μ]` on output (e.g. the explicit inverse from the identity).
    pub fn solve_columns(&self, mut rhs: faer::MatMut<'_, f64>, t: f64) -> Result<(), MbdError> {
        let dim = self.n + self.n_c;
        if rhs.nrows() != dim {
            return Err(MbdError::Model {
                t,
                message: format!("right-hand side has {} rows, expected {dim}", rhs.nrows()),
            });
        }
        match &self.factor {
            Some(Factor::Dense(lu)) => lu.solve_in_place(rhs.as_mut()),
            Some(Factor::Sparse(lu)) => lu.solve_in_place(rhs.as_mut()),
            None => {
                return Err(MbdError::Model {
                    t,
                    message: "augmented matrix was not factored".into(),
                });
            }
        }
        if !rhs.as_ref().is_all_finite() {
            return Err(MbdError::Singular {
                t,
                detail: "augmented matrix is singular (non-finite solution)".into(),
            });
        }
        Ok(())
    }

    /// Solves with the current factorisation: `rhs` holds `[b; c]` on input (length
    /// `n + n_c`) and `[x; μ]` on output.
    pub fn solve(&self, rhs: &mut [f64], t: f64) -> Result<(), MbdError> {
        let dim = self.n + self.n_c;
        if rhs.len() != dim {
            return Err(MbdError::Model {
                t,
                message: format!("right-hand side has length {}, expected {dim}", rhs.len()),
            });
        }
        let mut b = Mat::<f64>::from_fn(dim, 1, |i, _| rhs[i]);
        self.solve_columns(b.as_mut(), t)?;
        for (i, r) in rhs.iter_mut().enumerate() {
            *r = b[(i, 0)];
        }
        Ok(())
    }
}

/// Rows of the constraint Jacobian `D` (`n_c × n_v`) that are linearly dependent on the rows
/// before them (modified Gram–Schmidt with relative tolerance `tol`); used to name redundant
/// constraints in [`MbdError::Singular`].
pub fn dependent_rows(d: &SysMatrix, tol: f64) -> Vec<usize> {
    let dm = d.to_dense();
    let (m, n) = (dm.nrows(), dm.ncols());
    let mut basis: Vec<Vec<f64>> = Vec::new();
    let mut dep = Vec::new();
    for i in 0..m {
        let mut r: Vec<f64> = (0..n).map(|j| dm[(i, j)]).collect();
        let norm0 = r.iter().map(|x| x * x).sum::<f64>().sqrt();
        for b in &basis {
            let c: f64 = r.iter().zip(b).map(|(x, y)| x * y).sum();
            for (x, y) in r.iter_mut().zip(b) {
                *x -= c * y;
            }
        }
        let norm = r.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm <= tol * norm0.max(1e-300) || norm0 == 0.0 {
            dep.push(i);
        } else {
            r.iter_mut().for_each(|x| *x /= norm);
            basis.push(r);
        }
    }
    dep
}
