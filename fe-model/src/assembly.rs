//! Sparse assembly of element matrices into faer [`SparseColMat`] (CSC, both triangles stored).
//!
//! The sparsity pattern is built once from the element DOF lists
//! ([`SymbolicSparseColMat::try_new_from_indices`], duplicates summed); every later assembly
//! (K, M, K_G, or a refill after a parameter change) only recomputes the element matrices —
//! in parallel over elements with rayon for large meshes — and scatters the values through the
//! stored argsort. Element matrices are symmetrised on the way, so the global matrices are
//! exactly (bitwise) symmetric.

use crate::FeError;
use crate::element::{Element, MatrixKind};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat};
use rayon::prelude::*;

/// Element count above which element matrices are computed in parallel.
const PARALLEL_THRESHOLD: usize = 256;

/// A reusable assembly pattern for a fixed list of elements.
#[derive(Debug, Clone)]
pub struct Assembler {
    n_dofs: usize,
    symbolic: SymbolicSparseColMat<usize>,
    argsort: Argsort<usize>,
    /// Start of each element's values in the flat value array.
    offsets: Vec<usize>,
    /// For each stored entry (i, j): the position of (j, i) (the pattern is symmetric).
    mirror: Vec<usize>,
}

impl Assembler {
    /// Build the pattern of an `n_dofs × n_dofs` matrix for `elements`.
    ///
    /// Errors if an element refers to a DOF ≥ `n_dofs`.
    pub fn new(n_dofs: usize, elements: &[Box<dyn Element>]) -> Result<Self, FeError> {
        let mut offsets = Vec::with_capacity(elements.len() + 1);
        let mut total = 0usize;
        for (e, el) in elements.iter().enumerate() {
            offsets.push(total);
            for &d in el.dofs() {
                if d >= n_dofs {
                    return Err(FeError::Element {
                        element: e,
                        reason: format!("DOF {d} out of range (model has {n_dofs} DOFs)"),
                    });
                }
            }
            total += el.dofs().len() * el.dofs().len();
        }
        offsets.push(total);
        let mut pairs = Vec::with_capacity(total);
        for el in elements {
            let d = el.dofs();
            for &c in d {
                for &r in d {
                    pairs.push(Pair::new(r, c));
                }
            }
        }
        let (symbolic, argsort) =
            SymbolicSparseColMat::try_new_from_indices(n_dofs, n_dofs, &pairs)
                .map_err(|e| FeError::Sparse(format!("assembly pattern: {e:?}")))?;
        let cp = symbolic.col_ptr();
        let ri = symbolic.row_idx();
        let mut mirror = vec![0usize; ri.len()];
        for j in 0..n_dofs {
            for p in cp[j]..cp[j + 1] {
                let i = ri[p];
                let col_i = &ri[cp[i]..cp[i + 1]];
                let q = col_i.binary_search(&j).map_err(|_| {
                    FeError::Sparse(format!("assembly pattern not symmetric at ({i}, {j})"))
                })?;
                mirror[p] = cp[i] + q;
            }
        }
        Ok(Self {
            n_dofs,
            symbolic,
            argsort,
            offsets,
            mirror,
        })
    }

    /// Number of DOFs (rows = columns).
    pub fn n_dofs(&self) -> usize {
        self.n_dofs
    }

    /// The sparsity pattern.
    pub fn symbolic(&self) -> &SymbolicSparseColMat<usize> {
        &self.symbolic
    }

    /// Assemble the global matrix of `kind` for the same `elements` that built the pattern.
    /// Elements without a matrix of that kind (e.g. no geometric stiffness) contribute zeros.
    pub fn assemble(
        &self, elements: &[Box<dyn Element>], kind: MatrixKind,
    ) -> Result<SparseColMat<usize, f64>, FeError> {
        if elements.len() + 1 != self.offsets.len() {
            return Err(FeError::Dimension {
                context: "Assembler::assemble element count".into(),
                expected: self.offsets.len() - 1,
                got: elements.len(),
            });
        }
        let total = *self.offsets.last().unwrap_or(&0);
        let mut values = vec![0.0; total];
        // split the flat value array into one slice per element
        let mut slices = Vec::with_capacity(elements.len());
        let mut rest: &mut [f64] = &mut values;
        for w in self.offsets.windows(2) {
            let (a, b) = rest.split_at_mut(w[1] - w[0]);
            slices.push(a);
            rest = b;
        }
        let fill = |(el, out): (&dyn Element, &mut &mut [f64])| -> Result<(), usize> {
            let nd = el.dofs().len();
            if let Some(m) = el.matrix(kind) {
                if m.nrows() != nd || m.ncols() != nd {
                    return Err(nd);
                }
                // symmetrised, so that the global matrix is bitwise symmetric (a(i,j) and
                // a(j,i) are then sums of identical terms in identical order)
                for c in 0..nd {
                    for r in 0..nd {
                        out[c * nd + r] = 0.5 * (m[(r, c)] + m[(c, r)]);
                    }
                }
            }
            Ok(())
        };
        let check = |res: Result<(), usize>, e: usize| {
            res.map_err(|nd| FeError::Element {
                element: e,
                reason: format!("element matrix is not {nd}×{nd}"),
            })
        };
        if elements.len() >= PARALLEL_THRESHOLD {
            elements
                .par_iter()
                .zip(slices.par_iter_mut())
                .enumerate()
                .try_for_each(|(e, (el, out))| check(fill((el.as_ref(), out)), e))?;
        } else {
            for (e, (el, out)) in elements.iter().zip(slices.iter_mut()).enumerate() {
                check(fill((el.as_ref(), out)), e)?;
            }
        }
        let mut a = SparseColMat::new_from_argsort(self.symbolic.clone(), &self.argsort, &values)
            .map_err(|e| FeError::Sparse(format!("assembly values: {e:?}")))?;
        // duplicates may be summed in a different order for (i, j) and (j, i): make the result
        // bitwise symmetric
        let v = a.val_mut();
        for (p, &q) in self.mirror.iter().enumerate() {
            if p < q {
                let s = 0.5 * (v[p] + v[q]);
                v[p] = s;
                v[q] = s;
            }
        }
        Ok(a)
    }
}

/// One-shot assembly: build the pattern and assemble `kind`.
pub fn assemble(
    n_dofs: usize, elements: &[Box<dyn Element>], kind: MatrixKind,
) -> Result<SparseColMat<usize, f64>, FeError> {
    Assembler::new(n_dofs, elements)?.assemble(elements, kind)
}
