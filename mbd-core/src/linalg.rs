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
//! sparse LU otherwise. The sparse path builds, once per combination of block patterns, the
//! union pattern of `[S Dᵀ; D 0]` with a scatter map from every block's stored entries into it
//! and the symbolic factorisation (fill-reducing ordering); a refactorisation with new values
//! (Newton iterations, time steps of a model with a fixed pattern) is then a scatter of the
//! values and a numeric factorisation into reused storage, without triplets, sorting or
//! allocation.
//!
//! The numeric factorisation is faer's supernodal LU (dense kernels on groups of columns with
//! the same structure) whenever the union pattern has at least [`SUPERNODAL_MIN_DENSITY`]
//! entries per column, i.e. for models whose nodes carry three or more coupled coordinates;
//! sparser patterns leave the choice to faer's flop-count heuristic. See that constant for
//! the measurement behind the rule. With [`KktSolver::banded`] the union pattern is instead
//! reordered into a band with a dense border and factored by the banded LU of module `band`
//! (for closed chains of nodes; faer's sparse LU remains the fallback at a zero pivot or
//! when a test solve shows the banded factors inaccurate, [`BAND_BACKWARD_ERROR_LIMIT`]).

mod band;
mod kernels;
mod rowmajor;

pub use kernels::{axpy_cols, col_slice, lu_solve_in_place};

use crate::{MbdError, SysMatrix};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::matmul::matmul;
use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::lu::{
    LuRef, LuSymbolicParams, NumericLu, SymbolicLu, factorize_symbolic_lu,
};
use faer::sparse::{SparseColMat, SparseColMatRef, SymbolicSparseColMat, Triplet};
use faer::{Accum, Conj, Mat, MatMut, MatRef, Par};

/// `out = a x` for a dense matrix view `a` (`out` of length `a.nrows()`): faer's
/// matrix–vector product on the calling thread. With `a = bᵀ` of a stored `b` it is one
/// dot product per contiguous column of `b`. The one dense product of the integrators'
/// explicit inverse, the split products ([`crate::parallel`]) and the rolling tire.
///
/// For a row-major `a` (rows contiguous) of at most [`ROWMAJOR_MAX_ENTRIES`] entries on a
/// machine where faer uses its AVX2+FMA kernels, the product runs in module `rowmajor`'s
/// kernel: faer's per-row reduction order reproduced exactly (the same bits), three rows per
/// pass sharing the loads of `x`. That is faster while the matrix stays in a core's L2 cache
/// (the mirror half model of the rolling tire, 173 × 344 and 173 × 173: 10–20 % per product,
/// `cargo bench -p mbd-core --bench matvec` with `MATVEC_N=173`); a larger matrix streams from
/// L3 and faer's one-row kernel is as fast or faster (5–8 % at 341 × 682), so it keeps
/// faer's `matmul`.
/// Panics if `x.len() != a.ncols()` or `out.len() != a.nrows()`.
pub fn matvec(a: MatRef<'_, f64>, x: &[f64], out: &mut [f64]) {
    #[cfg(target_arch = "x86_64")]
    if a.col_stride() == 1
        && a.row_stride() > 1
        && a.nrows() > 0
        && a.ncols() > 0
        && a.nrows() * a.ncols() <= ROWMAJOR_MAX_ENTRIES
        && rowmajor::available()
    {
        assert!(
            x.len() == a.ncols() && out.len() == a.nrows(),
            "matvec: {}x{} matrix, x of length {}, out of length {}",
            a.nrows(),
            a.ncols(),
            x.len(),
            out.len()
        );
        // SAFETY: AVX2 and FMA checked; `a` has `out.len()` rows of `x.len()` contiguous
        // entries, row `i` at `a.as_ptr() + i·row_stride` (a valid view)
        unsafe { rowmajor::matvec_rows(a.as_ptr(), a.row_stride() as usize, x, out) };
        return;
    }
    matvec_faer(a, x, out);
}

/// Largest matrix (entries) for the row-major kernel of [`matvec`]: 640 KiB of `f64`, about
/// two thirds of a 1 MiB L2 cache.
pub const ROWMAJOR_MAX_ENTRIES: usize = 80 * 1024;

/// faer's matrix–vector product (`matmul` with one column) on the calling thread.
fn matvec_faer(a: MatRef<'_, f64>, x: &[f64], out: &mut [f64]) {
    let xv = MatRef::from_column_major_slice(x, x.len(), 1);
    let ov = MatMut::from_column_major_slice_mut(out, a.nrows(), 1);
    matmul(ov, Accum::Replace, a, xv, 1.0, Par::Seq);
}

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
                for (w, &xj) in cp.windows(2).zip(x) {
                    let xj = s * xj;
                    for (&i, &v) in ri[w[0]..w[1]].iter().zip(&val[w[0]..w[1]]) {
                        y[i] += v * xj;
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
                let sym = m.symbolic();
                let ri = sym.row_idx();
                let val = m.val();
                for j in 0..m.ncols() {
                    for k in sym.col_range(j) {
                        f(ri[k], j, val[k]);
                    }
                }
            }
        }
    }

    /// The same matrix without the stored zeros of a sparse matrix (a dense one is cloned):
    /// cheaper products with a matrix stored on a wider shared pattern (e.g. a mass matrix
    /// on the pattern of the tangent). Products are unchanged: the dropped terms are exact
    /// zeros.
    pub fn without_zeros(&self) -> SysMatrix {
        match self {
            SysMatrix::Dense(m) => SysMatrix::Dense(m.clone()),
            SysMatrix::Sparse(m) => {
                let mut t = Vec::new();
                self.for_each_entry(|i, j, v| {
                    if v != 0.0 {
                        t.push(Triplet::new(i, j, v));
                    }
                });
                SparseColMat::try_new_from_triplets(m.nrows(), m.ncols(), &t)
                    .map(SysMatrix::Sparse)
                    .unwrap_or_else(|_| self.clone())
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
        nr: usize, nc: usize, entries: &[Triplet<usize, usize, f64>], sparse: bool, t: f64,
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
        blocks: &[(usize, usize, SysMatrix)], mut entries: Vec<Triplet<usize, usize, f64>>,
        nr: usize, nc: usize, sparse: bool, t: f64,
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
    /// Numeric factors in [`SparsePath::numeric`].
    Sparse,
}

/// Stored pattern of one block of the augmented matrix, to recognise a repeated structure.
enum BlockKey {
    Dense {
        nrows: usize,
        ncols: usize,
    },
    Sparse {
        col_ptr: Vec<usize>,
        row_idx: Vec<usize>,
    },
}

impl BlockKey {
    fn of(m: &SysMatrix) -> Self {
        match m {
            SysMatrix::Dense(d) => BlockKey::Dense {
                nrows: d.nrows(),
                ncols: d.ncols(),
            },
            SysMatrix::Sparse(sp) => {
                let sym = sp.symbolic();
                let mut col_ptr = Vec::with_capacity(sym.ncols() + 1);
                let mut row_idx = Vec::new();
                col_ptr.push(0);
                for j in 0..sym.ncols() {
                    row_idx.extend_from_slice(&sym.row_idx()[sym.col_range(j)]);
                    col_ptr.push(row_idx.len());
                }
                BlockKey::Sparse { col_ptr, row_idx }
            }
        }
    }

    fn matches(&self, m: &SysMatrix) -> bool {
        match (self, m) {
            (BlockKey::Dense { nrows, ncols }, SysMatrix::Dense(d)) => {
                *nrows == d.nrows() && *ncols == d.ncols()
            }
            (BlockKey::Sparse { col_ptr, row_idx }, SysMatrix::Sparse(sp)) => {
                let sym = sp.symbolic();
                let ri = sym.row_idx();
                if col_ptr.len() != sym.ncols() + 1 {
                    return false;
                }
                match compact_storage(sp.as_ref()) {
                    // the same column pointers (the key's start at 0) make the same column
                    // ranges: one comparison of the whole row index array decides for all
                    // columns
                    Some(nnz) => sym.col_ptr() == &col_ptr[..] && ri[..nnz] == row_idx[..],
                    None => (0..sym.ncols())
                        .all(|j| ri[sym.col_range(j)] == row_idx[col_ptr[j]..col_ptr[j + 1]]),
                }
            }
            _ => false,
        }
    }
}

/// The number of stored entries `nnz` of `m` when its storage is compact: column pointers
/// from 0 and no per-column counts, so that the entries of column `j` are
/// `col_ptr[j]..col_ptr[j + 1]` and [`SysMatrix::for_each_entry`] visits the values
/// `val[..nnz]` in their storage order.
fn compact_storage(m: SparseColMatRef<'_, usize, f64>) -> Option<usize> {
    let sym = m.symbolic();
    let cp = sym.col_ptr();
    (sym.col_nnz().is_none() && cp.first() == Some(&0)).then(|| cp[sym.ncols()])
}

/// `vals[map[k]] += s · v` for the stored entries `v` of `b` in [`SysMatrix::for_each_entry`]
/// order (`map` has one position per entry). A compact sparse block ([`compact_storage`]) is
/// read as one slice of values beside its map: the same entries in the same order, the same
/// bits, without the per-column ranges.
fn scatter_scaled(vals: &mut [f64], s: f64, b: &SysMatrix, map: &[usize]) {
    if let SysMatrix::Sparse(sp) = b
        && let Some(nnz) = compact_storage(sp.as_ref())
    {
        for (v, &p) in sp.val()[..nnz].iter().zip(&map[..nnz]) {
            vals[p] += s * v;
        }
        return;
    }
    let mut k = 0;
    b.for_each_entry(|_, _, v| {
        vals[map[k]] += s * v;
        k += 1;
    });
}

/// `vals[map[k]] += Σ sₖ vₖ` over the blocks (those with `sₖ ≠ 0`, in their order) when they
/// are all compact sparse blocks ([`compact_storage`]) stored on one pattern whose entries go
/// to `map`; returns `false` (nothing done) otherwise. One pass instead of one per block: the
/// map sends a block's entries to distinct positions, so each position receives the same
/// additions in the same (block) order as from [`scatter_scaled`] block after block: the same
/// bits.
fn scatter_shared(vals: &mut [f64], blocks: &[ScaledBlock<'_>], map: &[usize]) -> bool {
    let Some(terms) = shared_terms(blocks, map) else {
        return false;
    };
    match terms.as_slice() {
        [] => {}
        [(s0, v0), (s1, v1), (s2, v2)] => {
            for (k, &p) in map.iter().enumerate() {
                let mut a = vals[p];
                a += s0 * v0[k];
                a += s1 * v1[k];
                a += s2 * v2[k];
                vals[p] = a;
            }
        }
        _ => {
            for (k, &p) in map.iter().enumerate() {
                let mut a = vals[p];
                for (s, v) in &terms {
                    a += s * v[k];
                }
                vals[p] = a;
            }
        }
    }
    true
}

/// The terms `(sₖ, values of Aₖ)` of [`scatter_shared`] (the blocks with `sₖ ≠ 0`), when every
/// block is compact sparse storage ([`compact_storage`]) with one entry per position of `map`.
fn shared_terms<'a>(blocks: &[ScaledBlock<'a>], map: &[usize]) -> Option<Vec<(f64, &'a [f64])>> {
    let mut terms: Vec<(f64, &[f64])> = Vec::with_capacity(blocks.len());
    for (s, b) in blocks {
        let SysMatrix::Sparse(sp) = b else {
            return None;
        };
        let nnz = compact_storage(sp.as_ref())?;
        if nnz != map.len() {
            return None;
        }
        if *s != 0.0 {
            terms.push((*s, &sp.val()[..nnz]));
        }
    }
    Some(terms)
}

/// The values `vals` of a [`SparsePath`]'s pattern: `Σ sₖ Aₖ` through the blocks' maps
/// (`shared_map`: one map for all, [`scatter_shared`]) and `D`, `Dᵀ` through `d_map`.
fn fill_vals(
    vals: &mut [f64], shared_map: bool, maps: &[Vec<usize>], d_map: &[(usize, usize)],
    blocks: &[ScaledBlock<'_>], d: Option<&SysMatrix>,
) {
    vals.fill(0.0);
    if !(shared_map && scatter_shared(vals, blocks, &maps[0])) {
        for ((s, b), map) in blocks.iter().zip(maps) {
            if *s == 0.0 {
                continue;
            }
            scatter_scaled(vals, *s, b, map);
        }
    }
    if let Some(d) = d {
        let mut k = 0;
        d.for_each_entry(|_, _, v| {
            let (a, b) = d_map[k];
            vals[a] += v;
            vals[b] += v;
            k += 1;
        });
    }
}

/// The sparse path: union pattern, scatter maps, symbolic and numeric factors, scratch.
struct SparsePath {
    /// Patterns of the blocks (and of `D`, last) this path was built for.
    keys: Vec<BlockKey>,
    /// Dimension `n + n_c`.
    dim: usize,
    symbolic_pattern: SymbolicSparseColMat<usize>,
    /// Per block, the position in `vals` of each stored entry (column-major order of the
    /// block's storage; every entry of a dense block).
    maps: Vec<Vec<usize>>,
    /// Whether every block has the first block's map (the blocks share one pattern, as the
    /// mass, damping and stiffness of a model assembled on one pattern do): the scatter then
    /// sums the blocks entry by entry in one pass ([`scatter_shared`]).
    shared_map: bool,
    /// Positions of `D` (rows `n..`) and `Dᵀ` (columns `n..`) entries, in `D`'s storage order.
    d_map: Vec<(usize, usize)>,
    vals: Vec<f64>,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    /// Scratch of the numeric factorisation.
    factor_mem: MemBuffer,
    /// Scratch of the one-column solves of [`KktSolver::solve`] (`&mut self`; taken out while
    /// a solve runs). Several columns ([`KktSolver::solve_columns`]) allocate their own.
    solve_mem: Option<MemBuffer>,
    /// Whether the banded LU was requested when this path was built.
    banded_requested: bool,
    /// The banded-plus-border LU ([`KktSolver::banded`]) when requested and the reordered
    /// pattern is a band.
    band: Option<band::BandLu>,
    /// The further band plans (the next one last), taken in turn when the current plan's
    /// factors fail the backward-error check ([`BAND_BACKWARD_ERROR_LIMIT`]); when none is
    /// left the pattern keeps faer's LU.
    band_plans: Vec<band::BandPlan>,
    /// Whether the last numeric factorisation is the banded one (else faer's).
    band_active: bool,
    /// Backward errors measured so far (accepted ones; [`KktSolver::banded_checks`]).
    band_checks: usize,
    /// Permuted right-hand side of the banded one-column solves.
    band_work: Vec<f64>,
}

/// The compressed-column (CSC) pattern of the row lists `cols` (one per column, in any order,
/// repeats allowed): `(col_ptr, row_idx)`, `col_ptr` of length `cols.len() + 1`, each column's
/// rows ascending and distinct. The one pattern builder of the sparse assemblies (the KKT
/// solver here, ANCF's element assembly).
pub fn csc_pattern(mut cols: Vec<Vec<usize>>) -> (Vec<usize>, Vec<usize>) {
    let mut col_ptr = Vec::with_capacity(cols.len() + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0);
    for c in &mut cols {
        c.sort_unstable();
        c.dedup();
        row_idx.extend_from_slice(c);
        col_ptr.push(row_idx.len());
    }
    (col_ptr, row_idx)
}

/// Index into the value array of the stored entry `(r, c)` of the pattern
/// `(col_ptr, row_idx)` ([`csc_pattern`]); the entry must be stored (else the column's first).
pub fn csc_position(col_ptr: &[usize], row_idx: &[usize], r: usize, c: usize) -> usize {
    let col = &row_idx[col_ptr[c]..col_ptr[c + 1]];
    col_ptr[c] + col.binary_search(&r).unwrap_or(0)
}

impl SparsePath {
    /// Union pattern of `[Σ Aₖ, Dᵀ; D, 0]` plus the diagonal, maps and symbolic factorisation.
    fn build(
        blocks: &[ScaledBlock<'_>], d: Option<&SysMatrix>, n: usize, n_c: usize, t: f64,
        banded: bool,
    ) -> Result<Self, MbdError> {
        let dim = n + n_c;
        let mut cols: Vec<Vec<usize>> = (0..dim).map(|j| vec![j]).collect();
        let mut push_all = |m: &SysMatrix, off_r: usize, off_c: usize, transpose: bool| {
            m.for_each_entry(|i, j, _| {
                let (r, c) = if transpose {
                    (j + off_c, i + off_r)
                } else {
                    (i + off_r, j + off_c)
                };
                cols[c].push(r);
            })
        };
        for (_, b) in blocks {
            push_all(b, 0, 0, false);
        }
        if let Some(d) = d {
            push_all(d, n, 0, false);
            push_all(d, n, 0, true);
        }
        let (col_ptr, row_idx) = csc_pattern(cols);
        let pos = |r: usize, c: usize| -> usize { csc_position(&col_ptr, &row_idx, r, c) };
        let maps: Vec<Vec<usize>> = blocks
            .iter()
            .map(|(_, b)| {
                let mut m = Vec::new();
                b.for_each_entry(|i, j, _| m.push(pos(i, j)));
                m
            })
            .collect();
        let mut d_map = Vec::new();
        if let Some(d) = d {
            d.for_each_entry(|i, j, _| d_map.push((pos(n + i, j), pos(j, n + i))));
        }
        let nnz = row_idx.len();
        let mut band_plans: Vec<band::BandPlan> = if banded {
            band::BandPlan::candidates(dim, &col_ptr, &row_idx)
                .into_iter()
                // a band as wide as half the matrix is a dense matrix in band storage
                .filter(|p| {
                    let (kl, ku) = p.bandwidths();
                    2 * (kl + ku + 1) <= dim
                })
                .rev()
                .collect()
        } else {
            Vec::new()
        };
        let band = band_plans.pop().map(band::BandLu::new);
        let symbolic_pattern = SymbolicSparseColMat::new_checked(dim, dim, col_ptr, None, row_idx);
        let params = LuSymbolicParams {
            supernodal_flop_ratio_threshold: lu_variant(nnz, dim),
            ..Default::default()
        };
        let symbolic = factorize_symbolic_lu(symbolic_pattern.as_ref(), params).map_err(|e| {
            MbdError::Singular {
                t,
                detail: format!("symbolic LU failed: {e:?}"),
            }
        })?;
        let factor_mem = MemBuffer::new(
            symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()),
        );
        let solve_mem = Some(MemBuffer::new(
            symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
        ));
        let mut keys: Vec<BlockKey> = blocks.iter().map(|(_, b)| BlockKey::of(b)).collect();
        if let Some(d) = d {
            keys.push(BlockKey::of(d));
        }
        Ok(Self {
            keys,
            dim,
            symbolic_pattern,
            shared_map: maps.iter().all(|m| *m == maps[0]),
            maps,
            d_map,
            vals: vec![0.0; nnz],
            symbolic,
            numeric: NumericLu::new(),
            factor_mem,
            solve_mem,
            banded_requested: banded,
            band,
            band_plans,
            band_active: false,
            band_checks: 0,
            band_work: vec![0.0; dim],
        })
    }

    /// Whether the blocks have the patterns this path was built for.
    fn matches(
        &self, blocks: &[ScaledBlock<'_>], d: Option<&SysMatrix>, dim: usize, banded: bool,
    ) -> bool {
        let nk = blocks.len() + usize::from(d.is_some());
        self.dim == dim
            && self.banded_requested == banded
            && self.keys.len() == nk
            && blocks
                .iter()
                .zip(&self.keys)
                .all(|((_, b), k)| k.matches(b))
            && d.is_none_or(|d| self.keys.last().is_some_and(|k| k.matches(d)))
    }

    /// Scatters `Σ sₖ Aₖ` and `D` into the values and factors them numerically; returns the
    /// number of banded factorisations rejected by the backward-error check on the way.
    ///
    /// Blocks that share one pattern (and no `D`) go straight into the band's arrays
    /// (`BandLu::load_shared`, the same bits); the pattern's values are then filled only when
    /// the backward error is measured or faer's LU takes over.
    fn factor(
        &mut self, blocks: &[ScaledBlock<'_>], d: Option<&SysMatrix>, t: f64,
    ) -> Result<usize, MbdError> {
        let non_finite = || MbdError::NonFinite {
            what: "system matrix (mass, tangent or constraint Jacobian)".into(),
            t,
        };
        let no_d = d.is_none_or(|d| d.nrows() == 0);
        let direct = match (&mut self.band, self.shared_map && no_d) {
            (Some(band), true) => match shared_terms(blocks, &self.maps[0]) {
                Some(terms) => {
                    let pat = self.symbolic_pattern.as_ref();
                    band.load_shared(pat.col_ptr(), pat.row_idx(), &terms, &self.maps[0])
                }
                None => None,
            },
            _ => None,
        };
        // the pattern's values, filled once when first needed
        let (shared_map, maps, d_map) = (self.shared_map, &self.maps, &self.d_map);
        let mut vals_filled = false;
        let mut ensure_vals = |vals: &mut Vec<f64>| {
            if !vals_filled {
                fill_vals(vals, shared_map, maps, d_map, blocks, d);
                vals_filled = true;
            }
        };
        match direct {
            Some(true) => {}
            // a value that is not finite, as the check of the pattern's values below
            Some(false) => return Err(non_finite()),
            None => {
                ensure_vals(&mut self.vals);
                if self.vals.iter().any(|v| !v.is_finite()) {
                    return Err(non_finite());
                }
            }
        }
        let mut loaded = direct.is_some();
        self.band_active = false;
        let mut rejected = 0;
        while self.band.is_some() {
            let pat = self.symbolic_pattern.as_ref();
            if !loaded {
                ensure_vals(&mut self.vals);
                if let Some(band) = self.band.as_mut() {
                    band.load(pat.col_ptr(), pat.row_idx(), &self.vals);
                }
            }
            let Some(band) = self.band.as_mut() else {
                break;
            };
            // a zero pivot of the band (pivoting confined to it) falls back to faer's LU for
            // this factorisation
            if band.factor_loaded().is_err() {
                break;
            }
            // measured unless the factors grew as little as a measured one's
            let measured = band.check_needed();
            if measured {
                ensure_vals(&mut self.vals);
            }
            let Some(band) = self.band.as_mut() else {
                break;
            };
            if !measured
                || band.backward_error(pat.col_ptr(), pat.row_idx(), &self.vals)
                    <= BAND_BACKWARD_ERROR_LIMIT
            {
                band.verdict(measured);
                self.band_checks += usize::from(measured);
                self.band_active = true;
                return Ok(rejected);
            }
            // inaccurate factors: the next plan for this pattern from now on (else faer's LU)
            rejected += 1;
            self.band = self.band_plans.pop().map(band::BandLu::new);
            loaded = false;
        }
        ensure_vals(&mut self.vals);
        let a = SparseColMatRef::new(self.symbolic_pattern.as_ref(), &self.vals);
        self.symbolic
            .factorize_numeric_lu(
                &mut self.numeric,
                a,
                Par::Seq,
                MemStack::new(&mut self.factor_mem),
                Default::default(),
            )
            .map(|_| rejected)
            .map_err(|e| MbdError::Singular {
                t,
                detail: format!("sparse LU of the augmented matrix failed: {e:?}"),
            })
    }

    /// Solves in place with the scratch `mem` (sized for one column) when given and `rhs` has
    /// one column, with a scratch allocated here otherwise.
    fn solve_in_place(&self, mut rhs: MatMut<'_, f64>, mem: Option<&mut MemBuffer>) {
        if let (true, Some(band)) = (self.band_active, &self.band) {
            let mut col = vec![0.0; self.dim];
            let mut work = vec![0.0; self.dim];
            for c in 0..rhs.ncols() {
                for (i, x) in col.iter_mut().enumerate() {
                    *x = rhs[(i, c)];
                }
                band.solve(&mut col, &mut work);
                for (i, x) in col.iter().enumerate() {
                    rhs[(i, c)] = *x;
                }
            }
            return;
        }
        let lu = LuRef::new_unchecked(&self.symbolic, &self.numeric);
        let ncols = rhs.ncols();
        match mem {
            Some(mem) if ncols == 1 => {
                lu.solve_in_place_with_conj(Conj::No, rhs, Par::Seq, MemStack::new(mem))
            }
            _ => {
                let mut mem =
                    MemBuffer::new(self.symbolic.solve_in_place_scratch::<f64>(ncols, Par::Seq));
                lu.solve_in_place_with_conj(Conj::No, rhs, Par::Seq, MemStack::new(&mut mem))
            }
        }
    }
}

/// Entries per column of the union pattern from which [`KktSolver`] always takes faer's
/// supernodal sparse LU \[-\].
///
/// faer's own choice (`SupernodalThreshold::AUTO`: supernodal when the estimated flops per
/// stored entry of `L + U` exceed 40) picks the simplicial (column-by-column) LU for the
/// block-banded patterns of beam, belt and plate models, whose nodes carry 3–12 coupled
/// coordinates. Measured with faer 0.24.4 (2026-11-26, numeric factorisation of cyclic
/// block-tridiagonal patterns, `b` coordinates per node; BENCHMARKS.md, "Against Exudyn"):
/// `b = 3`, 300 unknowns: simplicial 76 µs, supernodal 61 µs; `b = 6`,
/// 120: 79 / 38 µs; `b = 6`, 600: 556 / 238 µs; `b = 6`, 2 400: 1 552 / 867 µs; `b = 12`, 600:
/// 1 050 / 338 µs; the planar ANCF belt of Kerkkänen Table 3.1 (121 unknowns, 2 401 entries):
/// 107 / 79 µs. With `b = 2` (6 entries per column) the simplicial LU is the faster one
/// (1 000 unknowns: 144 / 184 µs), so sparser patterns keep faer's heuristic. `b = 3` gives 9
/// entries per column.
pub const SUPERNODAL_MIN_DENSITY: f64 = 8.0;

/// The LU variant for a union pattern of `nnz` entries in `dim` columns
/// ([`SUPERNODAL_MIN_DENSITY`]).
fn lu_variant(nnz: usize, dim: usize) -> SupernodalThreshold {
    if dim > 0 && nnz as f64 >= SUPERNODAL_MIN_DENSITY * dim as f64 {
        SupernodalThreshold::FORCE_SUPERNODAL
    } else {
        SupernodalThreshold::AUTO
    }
}

/// Factoriser/solver of the augmented matrix `[S Dᵀ; D 0]` (Ribaric (2.16), Lin (2.27)).
///
/// `S = Σ sₖ Aₖ` is given as a list of scaled blocks (mass, damping and stiffness in the
/// generalized-α iteration matrix). The sparse path reuses its union pattern, scatter maps and
/// symbolic LU while the blocks' patterns are unchanged; [`KktSolver::symbolic_factorizations`]
/// counts how often it had to be rebuilt.
pub struct KktSolver {
    factor: Option<Factor>,
    sparse: Option<SparsePath>,
    n: usize,
    n_c: usize,
    /// Number of numeric factorisations performed.
    pub factorizations: usize,
    /// Number of symbolic (sparse) analyses performed.
    pub symbolic_factorizations: usize,
    /// Factor sparse systems with the banded-plus-border LU (module `band`): the union
    /// pattern is reordered by reverse Cuthill–McKee after moving coordinates with more than
    /// four times the average number of couplings (at most 1/16 of them) to a dense border,
    /// and factored by a banded LU with partial pivoting within the band (LAPACK dgbtf2) and
    /// the dense LU of the border's Schur complement. Used when the band spans at most half
    /// the matrix; a zero pivot falls back to faer's sparse LU, and factors whose test solve
    /// has a backward error above [`BAND_BACKWARD_ERROR_LIMIT`] move the pattern to its next
    /// band plan or to faer's LU. Default `false`.
    pub banded: bool,
    /// Number of numeric factorisations done by the banded LU.
    pub banded_factorizations: usize,
    /// Number of banded factorisations rejected by the backward-error check
    /// ([`BAND_BACKWARD_ERROR_LIMIT`]); each rejection moves the pattern to its next band
    /// plan or, after the last, to faer's sparse LU for good.
    pub banded_rejections: usize,
    /// Number of banded factorisations accepted after their backward error was measured by a
    /// test solve (`BandLu::backward_error`; the rejected ones are
    /// [`KktSolver::banded_rejections`]). A factorisation whose element growth is at most twice
    /// that of the last measured and accepted one takes its verdict without a test solve, at
    /// most 16 in a row (`BandLu::check_needed`).
    pub banded_checks: usize,
}

impl Default for KktSolver {
    fn default() -> Self {
        Self::new()
    }
}

/// Largest accepted normwise relative backward error of the banded LU \[-\], measured after a
/// banded factorisation by one test solve (module `band`, `BandLu::backward_error`) unless its
/// element growth is at most twice that of the last measured one, at most 16 in a row
/// (`BandLu::check_needed`, [`KktSolver::banded_checks`]).
///
/// Partial pivoting over the whole matrix (faer's LU) gives a small multiple of the unit
/// roundoff (2.2e-16) on the Newton matrices of the belt models; the banded LU pivots only
/// within its band and its border. The plan that cuts a closed chain at one node (6bd31ba)
/// solved the plate belt's Newton matrix to a residual of 24 against a right-hand side of 0.5,
/// which tripled the plate's Newton iterations per step (issue 37, bisected). A factorisation
/// above this limit is discarded and the pattern moves to its next band plan, then to faer's
/// LU. The margin to roundoff (six orders) keeps ill-conditioned but stable factors.
pub const BAND_BACKWARD_ERROR_LIMIT: f64 = 1e-10;

/// Relative pivot threshold below which a dense factorisation is reported as singular.
const PIVOT_TOL: f64 = 1e-13;

impl KktSolver {
    /// An empty solver (nothing factored yet).
    pub fn new() -> Self {
        Self {
            factor: None,
            sparse: None,
            n: 0,
            n_c: 0,
            factorizations: 0,
            symbolic_factorizations: 0,
            banded: false,
            banded_factorizations: 0,
            banded_rejections: 0,
            banded_checks: 0,
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
        &mut self, blocks: &[ScaledBlock<'_>], d: Option<&SysMatrix>, t: f64,
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
            if !self
                .sparse
                .as_ref()
                .is_some_and(|p| p.matches(blocks, d, dim, self.banded))
            {
                self.sparse = None;
                self.sparse = Some(SparsePath::build(blocks, d, n, n_c, t, self.banded)?);
                self.symbolic_factorizations += 1;
            }
            let path = self.sparse.as_mut().ok_or_else(|| MbdError::Model {
                t,
                message: "missing sparse assembly".into(),
            })?;
            let checks = path.band_checks;
            self.banded_rejections += path.factor(blocks, d, t)?;
            self.banded_checks += path.band_checks - checks;
            if path.band_active {
                self.banded_factorizations += 1;
            }
            self.factor = Some(Factor::Sparse);
        }
        self.factorizations += 1;
        Ok(())
    }

    /// Solves for several right-hand sides at once: the columns of `rhs` (`(n + n_c) × k`) hold
    /// `[b; c]` on input and `[x; μ]` on output (e.g. the explicit inverse from the identity);
    /// the sparse path allocates the solve scratch for `k` columns.
    pub fn solve_columns(&self, rhs: faer::MatMut<'_, f64>, t: f64) -> Result<(), MbdError> {
        self.solve_with(rhs, t, None)
    }

    /// [`solve_columns`](Self::solve_columns) with the one-column scratch `mem` of the sparse
    /// path.
    fn solve_with(
        &self, mut rhs: faer::MatMut<'_, f64>, t: f64, mem: Option<&mut MemBuffer>,
    ) -> Result<(), MbdError> {
        let dim = self.n + self.n_c;
        if rhs.nrows() != dim {
            return Err(MbdError::Model {
                t,
                message: format!("right-hand side has {} rows, expected {dim}", rhs.nrows()),
            });
        }
        match (&self.factor, &self.sparse) {
            (Some(Factor::Dense(lu)), _) => lu.solve_in_place(rhs.as_mut()),
            (Some(Factor::Sparse), Some(path)) => path.solve_in_place(rhs.as_mut(), mem),
            _ => {
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
    /// `n + n_c`) and `[x; μ]` on output. `&mut self`: the sparse path solves with the
    /// solver's own scratch (allocated with the symbolic factorisation), so repeated solves
    /// do not allocate.
    pub fn solve(&mut self, rhs: &mut [f64], t: f64) -> Result<(), MbdError> {
        let dim = self.n + self.n_c;
        if rhs.len() != dim {
            return Err(MbdError::Model {
                t,
                message: format!("right-hand side has length {}, expected {dim}", rhs.len()),
            });
        }
        if let (Some(Factor::Sparse), Some(p)) = (&self.factor, self.sparse.as_mut())
            && p.band_active
            && let Some(band) = &p.band
        {
            band.solve(rhs, &mut p.band_work);
            if rhs.iter().any(|v| !v.is_finite()) {
                return Err(MbdError::Singular {
                    t,
                    detail: "augmented matrix is singular (non-finite solution)".into(),
                });
            }
            return Ok(());
        }
        let mut mem = self.sparse.as_mut().and_then(|p| p.solve_mem.take());
        let solved = self.solve_with(
            MatMut::from_column_major_slice_mut(rhs, dim, 1),
            t,
            mem.as_mut(),
        );
        if let Some(p) = self.sparse.as_mut() {
            p.solve_mem = mem;
        }
        solved
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The scatter of a compact sparse block as one slice of values ([`scatter_scaled`]) adds
    /// the same terms in the same order as the entry-by-entry loop over
    /// [`SysMatrix::for_each_entry`] it replaced (reference: that loop, `==` on the bits of
    /// every accumulated value, on top of values already there), and a block with per-column
    /// counts keeps the loop.
    #[test]
    fn slice_scatter_is_the_entrywise_scatter_bit_for_bit() {
        let n = 9;
        let mut t = Vec::new();
        for j in 0..n {
            for i in [j, (j + 1) % n, (j + 4) % n] {
                t.push(Triplet::new(
                    i,
                    j,
                    ((i * 13 + j * 7) as f64 * 0.41).sin() / 3.0,
                ));
            }
        }
        let b = SysMatrix::Sparse(SparseColMat::try_new_from_triplets(n, n, &t).expect("valid"));
        let SysMatrix::Sparse(sp) = &b else {
            unreachable!()
        };
        assert!(compact_storage(sp.as_ref()).is_some());
        let mut count = 0;
        b.for_each_entry(|_, _, _| count += 1);
        // an arbitrary map with repeats, as blocks of a union pattern overlap
        let map: Vec<usize> = (0..count).map(|k| (k * 5) % 17).collect();
        let start: Vec<f64> = (0..17).map(|k| (k as f64 * 0.7).cos()).collect();
        let s = 0.3;
        let mut reference = start.clone();
        let mut k = 0;
        b.for_each_entry(|_, _, v| {
            reference[map[k]] += s * v;
            k += 1;
        });
        let mut got = start.clone();
        scatter_scaled(&mut got, s, &b, &map);
        assert!(
            got.iter()
                .zip(&reference)
                .all(|(a, r)| a.to_bits() == r.to_bits())
        );
        // the dense path is the loop itself
        let d = SysMatrix::Dense(sp.to_dense());
        let mut k = 0;
        let mut reference = start.clone();
        let map: Vec<usize> = (0..n * n).map(|k| (k * 5) % 17).collect();
        d.for_each_entry(|_, _, v| {
            reference[map[k]] += s * v;
            k += 1;
        });
        let mut got = start;
        scatter_scaled(&mut got, s, &d, &map);
        assert_eq!(got, reference);
    }

    /// Blocks on one pattern summed in one pass ([`scatter_shared`]) give the bits of the
    /// block-after-block scatter (reference: [`scatter_scaled`] per block, itself checked
    /// against the entry-by-entry loop above), for three blocks (the unrolled case), four
    /// (the loop) and with a zero scale skipped; a dense block is declined.
    #[test]
    fn one_pass_scatter_of_shared_blocks_is_the_blockwise_scatter_bit_for_bit() {
        let n = 11;
        let block = |seed: f64| {
            let mut t = Vec::new();
            for j in 0..n {
                for i in [j, (j + 2) % n, (j + 5) % n] {
                    t.push(Triplet::new(
                        i,
                        j,
                        ((i * 13 + j * 7) as f64 * seed).sin() * 1e3,
                    ));
                }
            }
            SysMatrix::Sparse(SparseColMat::try_new_from_triplets(n, n, &t).expect("valid"))
        };
        let (m, c, k, kc) = (block(0.41), block(0.77), block(1.3), block(2.9));
        let mut nnz = 0;
        m.for_each_entry(|_, _, _| nnz += 1);
        // distinct positions in a larger union, as the union pattern with D's rows gives
        let map: Vec<usize> = (0..nnz).map(|e| e + e / 3).collect();
        let len = map.last().map_or(0, |p| p + 1);
        for blocks in [
            vec![(1.0, &m), (0.37, &c), (123.4, &k)],
            vec![(1.0, &m), (0.37, &c), (123.4, &k), (123.4, &kc)],
            vec![(1.0, &m), (0.0, &c), (123.4, &k), (-7.5, &kc)],
        ] {
            let mut reference = vec![0.0; len];
            for (s, b) in &blocks {
                if *s != 0.0 {
                    scatter_scaled(&mut reference, *s, b, &map);
                }
            }
            let mut got = vec![0.0; len];
            assert!(scatter_shared(&mut got, &blocks, &map));
            assert!(
                got.iter()
                    .zip(&reference)
                    .all(|(a, r)| a.to_bits() == r.to_bits())
            );
        }
        let d = SysMatrix::Dense(m.to_dense());
        let mut got = vec![0.0; len];
        assert!(!scatter_shared(&mut got, &[(1.0, &d)], &map));
    }
}
