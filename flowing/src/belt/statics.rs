//! Static equilibrium of the belt models on resting pulleys: a dense Newton problem for the
//! shared [`mbd_core::newton`] solver, used by [`super::FlowingBelt::static_equilibrium`] and
//! [`super::nodal::NodalBelt::static_equilibrium`].

use faer::Mat;
use faer::linalg::solvers::{PartialPivLu, Solve};
use mbd_core::MbdError;
use mbd_core::newton::{
    self, NewtonError, NewtonOptions, NewtonProblem, NewtonWorkspace, Tolerances,
};

/// `R(x) = 0` with a dense tangent: `eval(x, r)` fills `R` (`dim` entries, the first `n_x`
/// belonging to the unknowns `x`, the rest to constraint rows whose multipliers are solved
/// for directly and not accumulated) and returns `J = ∂R/∂(x, λ)` (`dim × dim`).
struct Dense<F> {
    eval: F,
    n_x: usize,
    dim: usize,
    lu: Option<PartialPivLu<f64>>,
}

impl<F> NewtonProblem for Dense<F>
where
    F: FnMut(&[f64], &mut [f64]) -> Result<Mat<f64>, MbdError>,
{
    type Error = MbdError;

    fn tangent_dim(&self) -> usize {
        self.dim
    }

    fn linearize(&mut self, x: &[f64], _load: f64, r: &mut [f64]) -> Result<(), MbdError> {
        let j = (self.eval)(x, r)?;
        self.lu = Some(j.partial_piv_lu());
        Ok(())
    }

    fn solve(&mut self, r: &[f64], dx: &mut [f64]) -> Result<(), MbdError> {
        let lu = self.lu.as_ref().ok_or_else(|| MbdError::Model {
            t: 0.0,
            message: "belt static equilibrium: no tangent factored".into(),
        })?;
        let d = lu.solve(Mat::from_fn(self.dim, 1, |i, _| -r[i]));
        for (i, v) in dx.iter_mut().enumerate() {
            *v = d[(i, 0)];
        }
        Ok(())
    }

    /// `‖R‖∞` over the force rows.
    fn residual_norm(&self, r: &[f64]) -> f64 {
        newton::max_abs(&r[..self.n_x])
    }

    /// `‖Δx‖∞` over the unknowns (not the multipliers).
    fn correction_norm(&self, dx: &[f64]) -> f64 {
        newton::max_abs(&dx[..self.n_x])
    }
}

/// Full-step Newton from `x = 0` until `‖Δx‖∞ ≤ 10⁻¹³` or `‖R‖∞ < 10⁻⁹` (the latter from
/// iteration `residual_from` on), at most 50 iterations; `what` names the model in errors.
/// Returns `x` (`n_x` entries).
pub(crate) fn dense_equilibrium<F>(
    what: &str, n_x: usize, dim: usize, residual_from: usize, eval: F,
) -> Result<Vec<f64>, MbdError>
where
    F: FnMut(&[f64], &mut [f64]) -> Result<Mat<f64>, MbdError>,
{
    let mut problem = Dense {
        eval,
        n_x,
        dim,
        lu: None,
    };
    let opts = NewtonOptions {
        max_iterations: 50,
        tolerances: Tolerances {
            residual_from_iteration: residual_from,
            ..Tolerances::absolute(1e-13).or_residual(1e-9)
        },
        ..Default::default()
    };
    let mut x = vec![0.0; n_x];
    match newton::solve(&mut problem, &mut x, &opts, &mut NewtonWorkspace::new()) {
        Ok(_) => Ok(x),
        Err(NewtonError::NonFinite {
            what: "correction", ..
        }) => Err(MbdError::Singular {
            t: 0.0,
            detail: format!("{what} static equilibrium: singular tangent"),
        }),
        Err(e) => Err(e.into_mbd(0.0)),
    }
}
