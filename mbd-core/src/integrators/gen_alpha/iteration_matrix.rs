//! The factored iteration matrix of [`AlphaStepper`](super::AlphaStepper): the augmented
//! matrix `[S Dᵀ; D 0]` of Arnold & Brüls (2007) (`S = M + (γ'/β') C_t + K_t/β'`, module
//! [`gen_alpha`](super)), as an LU factorisation or, with
//! [`AlphaConfig::explicit_inverse`](super::AlphaConfig::explicit_inverse), as the explicit inverse (stored transposed, so that
//! a solve is one product over contiguous rows).
//!
//! The explicit inverse pays `O(n³)` once per factorisation and makes every solve a
//! matrix–vector product (no pivoting, no allocation): the choice for small dense models
//! stepped with a frozen matrix ([`NewtonUpdate::Frozen`](super::NewtonUpdate::Frozen)), whose
//! step correction needs many solves (e.g. the contact responses `S⁻¹ Jᵀ` of all contact
//! points of the rolling tire).

use crate::linalg::{KktSolver, ScaledBlock, matvec};
use crate::parallel::{ProductWorker, SplitProduct};
use crate::{MbdError, SysMatrix};
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatMut, MatRef, Par};
use std::sync::Arc;

/// One factorisation of the iteration matrix with the data of the frozen-matrix policy.
pub(crate) struct IterationMatrix {
    pub(crate) kkt: KktSolver,
    /// `(S⁻¹)ᵀ` of the augmented matrix when the inverse is explicit.
    inverse_t: Option<Mat<f64>>,
    /// The product with the explicit inverse, split between two threads when the stepper has
    /// a [`ProductWorker`].
    product: Option<SplitProduct>,
    /// Step size \[s\] of the factorisation.
    pub(crate) h: f64,
    /// Velocity of the drift-trigger coordinate at the factorisation.
    pub(crate) v_ref: f64,
    /// Identity of the factorisation (the stepper's factorisation count when it was made).
    pub(crate) id: usize,
}

impl IterationMatrix {
    pub(crate) fn new() -> Self {
        Self {
            kkt: KktSolver::new(),
            inverse_t: None,
            product: None,
            h: 0.0,
            v_ref: 0.0,
            id: 0,
        }
    }

    pub(crate) fn is_factored(&self) -> bool {
        self.kkt.is_factored()
    }

    /// Drops the factorisation (the next step factors again).
    pub(crate) fn invalidate(&mut self) {
        self.kkt.invalidate();
        self.inverse_t = None;
    }

    /// Factors `[Σ sₖ Aₖ, Dᵀ; D, 0]` (and inverts it when `explicit`, its products then split
    /// with `worker`, if any).
    pub(crate) fn factor(
        &mut self, blocks: &[ScaledBlock<'_>], d: Option<&SysMatrix>, t: f64, explicit: bool,
        worker: Option<&Arc<ProductWorker>>,
    ) -> Result<(), MbdError> {
        self.inverse_t = None;
        self.kkt.factor(blocks, d, t)?;
        if explicit {
            let dim = blocks.first().map_or(0, |b| b.1.nrows()) + d.map_or(0, |d| d.nrows());
            let mut inv = Mat::<f64>::identity(dim, dim);
            self.kkt.solve_columns(inv.as_mut(), t)?;
            let inv_t = inv.transpose().to_owned();
            let same_worker = match (self.product.as_ref(), worker) {
                (Some(p), w) => p.is_split() == w.is_some(),
                (None, _) => false,
            };
            if !same_worker {
                self.product = Some(SplitProduct::new(worker.cloned()));
            }
            if let Some(p) = self.product.as_mut() {
                p.set(inv_t.as_ref());
            }
            self.inverse_t = Some(inv_t);
        }
        Ok(())
    }

    /// Solves in place: `rhs = [b; c]` on input, `[x; μ]` on output; `scratch` (same length)
    /// receives the product with the explicit inverse.
    pub(crate) fn solve(
        &mut self, rhs: &mut [f64], scratch: &mut [f64], t: f64,
    ) -> Result<(), MbdError> {
        match &self.inverse_t {
            Some(inv_t) => {
                if rhs.len() != inv_t.nrows() || scratch.len() != rhs.len() {
                    return Err(MbdError::Model {
                        t,
                        message: format!(
                            "right-hand side has length {} (scratch {}), expected {}",
                            rhs.len(),
                            scratch.len(),
                            inv_t.nrows()
                        ),
                    });
                }
                match &self.product {
                    Some(p) => p.apply(inv_t.as_ref(), rhs, scratch),
                    None => matvec(inv_t.as_ref().transpose(), rhs, scratch),
                }
                rhs.copy_from_slice(scratch);
                if rhs.iter().any(|v| !v.is_finite()) {
                    return Err(MbdError::Singular {
                        t,
                        detail: "augmented matrix is singular (non-finite solution)".into(),
                    });
                }
                Ok(())
            }
            None => self.kkt.solve(rhs, t),
        }
    }

    /// `out = [S Dᵀ; D 0]⁻¹ [f; 0]` for the columns of `f` (`n_v × k`); `out` is
    /// `(n_v + n_c) × k`.
    pub(crate) fn solve_columns(
        &self, f: MatRef<'_, f64>, mut out: MatMut<'_, f64>, t: f64,
    ) -> Result<(), MbdError> {
        let n = f.nrows();
        if out.ncols() != f.ncols() || out.nrows() < n {
            return Err(MbdError::Model {
                t,
                message: format!(
                    "solve of {}x{} columns into {}x{}",
                    f.nrows(),
                    f.ncols(),
                    out.nrows(),
                    out.ncols()
                ),
            });
        }
        match &self.inverse_t {
            Some(inv_t) => {
                let inv = inv_t.as_ref().transpose();
                matmul(
                    out.as_mut(),
                    Accum::Replace,
                    inv.subcols(0, n),
                    f,
                    1.0,
                    Par::Seq,
                );
                Ok(())
            }
            None => {
                out.as_mut().fill(0.0);
                out.as_mut().subrows_mut(0, n).copy_from(f);
                self.kkt.solve_columns(out, t)
            }
        }
    }
}
