//! The generic constrained second-order system that all flowmbd models implement.
//!
//! A model provides, at time `t`, positions `q` (length [`SecondOrderSystem::n_q`]) and
//! velocities `v` (length [`SecondOrderSystem::n_v`]):
//!
//! ```text
//!   q̇ = H(q) v                                   (kinematic map, identity for most models)
//!   M(q) v̇ + Dᵀ(q) λ = f(t, q, v)                 (Ribaric (2.16), Lin (2.27))
//!   Φ(t, q) = 0,   D v = ν(t, q),   D v̇ = γ(t, q, v)
//! ```
//!
//! `f` contains applied, elastic, damping and quadratic-velocity forces. Rigid bodies with Euler
//! parameters have `n_q = 7`, `n_v = 6` per body (r, p / ṙ, ω̄); ANCF meshes, reduced flexible
//! bodies and flowing-material models have `q̇ = v`. The integrators of [`crate`] only see this
//! trait, so models of different crates couple in one system by composition.

use crate::{MbdError, Workspace};
use faer::Mat;
use faer::sparse::SparseColMat;

/// A system matrix (mass, tangent stiffness/damping, constraint Jacobian), dense for small
/// models, sparse (CSC) for large ones.
#[derive(Debug, Clone)]
pub enum SysMatrix {
    /// Dense matrix.
    Dense(Mat<f64>),
    /// Sparse compressed-column matrix.
    Sparse(SparseColMat<usize, f64>),
}

impl SysMatrix {
    /// Number of rows.
    pub fn nrows(&self) -> usize {
        match self {
            SysMatrix::Dense(m) => m.nrows(),
            SysMatrix::Sparse(m) => m.nrows(),
        }
    }

    /// Number of columns.
    pub fn ncols(&self) -> usize {
        match self {
            SysMatrix::Dense(m) => m.ncols(),
            SysMatrix::Sparse(m) => m.ncols(),
        }
    }

    /// Dense copy of the matrix.
    pub fn to_dense(&self) -> Mat<f64> {
        match self {
            SysMatrix::Dense(m) => m.clone(),
            SysMatrix::Sparse(m) => m.to_dense(),
        }
    }
}

/// Tangent matrices of the generalized forces: `K_t = -∂f/∂q · H(q)` and `C_t = -∂f/∂v`,
/// both `n_v × n_v` (used by implicit integrators and static solvers).
#[derive(Debug, Clone)]
pub struct ForceTangent {
    /// Tangent stiffness `-∂f/∂q · H` \[N/m or consistent units\].
    pub stiffness: SysMatrix,
    /// Tangent damping `-∂f/∂v` \[N·s/m or consistent units\].
    pub damping: SysMatrix,
}

/// A constrained second-order system (see the module documentation for the equations).
///
/// The hot methods ([`forces`](Self::forces), [`force_tangent`](Self::force_tangent),
/// [`dynamic_residual`](Self::dynamic_residual)) take a [`Workspace`] owned by the caller (the
/// stepper, Newton problem or study, one per model): a model keeps its work buffers and caches
/// there ([`Workspace::get_or_insert_with`]), never in hidden interior-mutable fields.
///
/// Only the sizes, [`mass`](Self::mass) and [`forces`](Self::forces) are required; a model
/// without constraints keeps the default constraint methods, and a model without an analytic
/// tangent returns `None` from [`force_tangent`](Self::force_tangent) so that integrators
/// fall back to finite differences.
pub trait SecondOrderSystem {
    /// Number of position coordinates `q`.
    fn n_q(&self) -> usize;

    /// Number of velocity coordinates `v` (equals `n_q` unless rotations are parametrised
    /// redundantly, e.g. Euler parameters).
    fn n_v(&self) -> usize {
        self.n_q()
    }

    /// Number of (holonomic or rheonomic) constraint equations.
    fn n_c(&self) -> usize {
        0
    }

    /// Kinematic map `q̇ = H(q) v` (Nikravesh: `ṗ = ½ Lᵀ(p) ω̄` for Euler parameters).
    fn position_rate(&self, _q: &[f64], v: &[f64], qdot: &mut [f64]) {
        qdot.copy_from_slice(v);
    }

    /// Restore invariants of `q` after an update (e.g. normalise Euler parameters).
    fn normalize(&self, _q: &mut [f64]) {}

    /// Composition `q_new = q ⊕ Δ` of a position with an increment `Δ` given in velocity
    /// coordinates (length `n_v`), used by the implicit integrators (the Lie-group form of
    /// generalized-α, Brüls, Cardona & Arnold 2012). The default is `q + Δ` when `n_q == n_v`,
    /// and the first-order map `q + H(q) Δ` followed by [`normalize`](Self::normalize)
    /// otherwise; rigid-body models override it with the exact exponential map.
    fn integrate_position(&self, q: &[f64], dq: &[f64], q_new: &mut [f64]) {
        if self.n_q() == self.n_v() {
            for ((o, a), b) in q_new.iter_mut().zip(q).zip(dq) {
                *o = a + b;
            }
        } else {
            self.position_rate(q, dq, q_new);
            for (o, a) in q_new.iter_mut().zip(q) {
                *o += a;
            }
            self.normalize(q_new);
        }
    }

    /// The model's own prediction of a step of size `h` \[s\] from the state `(t, q, v)` with
    /// accelerations `vdot`: the position increment `Δq` (velocity coordinates, as
    /// [`integrate_position`](Self::integrate_position)) written over `dq`, which holds the
    /// integrator's own prediction on entry (a model may keep it for some coordinates).
    /// Returns whether it predicted (default: `false`, `dq` untouched). Only the starting
    /// iterate of the implicit integrators' Newton iteration: the step's solution does not
    /// depend on it (generalized-α with
    /// [`AlphaConfig::model_predictor`](crate::integrators::AlphaConfig::model_predictor)
    /// starts from whichever prediction has the smaller residual). E.g. a Lagrangian belt mesh
    /// in a steady drive: every node moves to where the material ahead of it was, which the
    /// constant-acceleration predictor misses at every wrap entry by `h v²/R` in velocity.
    fn predict_increment(
        &self, _t: f64, _q: &[f64], _v: &[f64], _vdot: &[f64], _h: f64, _dq: &mut [f64],
    ) -> bool {
        false
    }

    /// Largest fraction `α ∈ (0, 1]` of a Newton correction that the model admits in one
    /// iteration of an implicit step (default `1`): the iterate is the state `(t, q, v)` and the
    /// correction moves it by `dq` (velocity coordinates, as
    /// [`integrate_position`](Self::integrate_position)) and `dv` \[units of v\]. Only the
    /// path of the iteration changes, not the equations solved: generalized-α with
    /// [`AlphaConfig::model_correction_limit`](crate::integrators::AlphaConfig::model_correction_limit)
    /// scales the correction by `α` before its line search, and a scaled iteration never
    /// counts as converged. E.g. a regularised friction law whose band of steep slope is
    /// narrow: the transition-aware limit of Castro et al. (2019) stops every contact's slip
    /// velocity from crossing the band in one iteration (`contact::friction::transition_limit`,
    /// the smallest `α` over the contact points).
    fn correction_limit(
        &self, _t: f64, _q: &[f64], _v: &[f64], _dq: &[f64], _dv: &[f64], _ws: &mut Workspace,
    ) -> Result<f64, MbdError> {
        Ok(1.0)
    }

    /// Model-specific validation of a state at time `t` \[s\] (e.g. unit Euler parameters),
    /// called by the integrators on the initial state; sizes and finiteness are checked by the
    /// caller.
    fn check_state(&self, _t: f64, _q: &[f64], _v: &[f64]) -> Result<(), MbdError> {
        Ok(())
    }

    /// Human-readable name of constraint row `row` (used in error messages, e.g. for redundant
    /// constraints).
    fn constraint_name(&self, row: usize) -> String {
        format!("constraint row {row}")
    }

    /// Human-readable name of velocity coordinate `dof` (used in error messages).
    fn dof_name(&self, dof: usize) -> String {
        format!("coordinate {dof}")
    }

    /// Whether [`mass`](Self::mass) is independent of `t` and `q` (lets integrators factor it once).
    fn mass_is_constant(&self) -> bool {
        false
    }

    /// Mass matrix `M(q)` (`n_v × n_v`, symmetric positive (semi)definite).
    fn mass(&self, t: f64, q: &[f64]) -> Result<SysMatrix, MbdError>;

    /// Generalized forces `f(t, q, v)` (length `n_v`), written into `f` (overwrite, not add);
    /// `ws` is the caller's scratch for this model.
    fn forces(
        &self, t: f64, q: &[f64], v: &[f64], f: &mut [f64], ws: &mut Workspace,
    ) -> Result<(), MbdError>;

    /// The dynamic residual `r = M(q) v̇ − f(t, q, v)` (length `n_v`, constraint forces
    /// excluded) of the implicit integrators' equations of motion, written into `r`; `Ok(false)`
    /// (the default) if the model does not provide it, and the integrator then forms `M` and
    /// `f` itself. A model overrides it when one fused product is cheaper than forming `M(q)`
    /// (e.g. a mass with a configuration-dependent coupling, as the rolling tire's `G₁ z θ̈`).
    fn dynamic_residual(
        &self, _t: f64, _q: &[f64], _v: &[f64], _vdot: &[f64], _r: &mut [f64], _ws: &mut Workspace,
    ) -> Result<bool, MbdError> {
        Ok(false)
    }

    /// Analytic tangent of the forces, or `None` to request finite differences; `ws` is the
    /// caller's scratch for this model (the same as for [`forces`](Self::forces)).
    fn force_tangent(
        &self, _t: f64, _q: &[f64], _v: &[f64], _ws: &mut Workspace,
    ) -> Result<Option<ForceTangent>, MbdError> {
        Ok(None)
    }

    /// Tangent of the constraint forces for fixed multipliers, `K_c = ∂(Dᵀ(q) λ)/∂q · H`
    /// (`n_v × n_v`, the "geometric stiffness" of the joints), or `None` to neglect it in the
    /// Newton matrix of the implicit integrators (quasi-Newton).
    fn constraint_force_tangent(
        &self, _t: f64, _q: &[f64], _lambda: &[f64],
    ) -> Result<Option<SysMatrix>, MbdError> {
        Ok(None)
    }

    /// Constraint residual `Φ(t, q)` (length `n_c`).
    fn constraint_residual(&self, _t: f64, _q: &[f64], _phi: &mut [f64]) -> Result<(), MbdError> {
        Ok(())
    }

    /// Constraint Jacobian `D(t, q)` with respect to the velocities (`n_c × n_v`).
    fn constraint_jacobian(&self, _t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        Ok(SysMatrix::Dense(Mat::zeros(0, self.n_v())))
    }

    /// Velocity right-hand side `ν` of `D v = ν` (`-Φ_t` for rheonomic drivers; length `n_c`).
    fn constraint_velocity_rhs(&self, _t: f64, _q: &[f64], nu: &mut [f64]) -> Result<(), MbdError> {
        nu.fill(0.0);
        Ok(())
    }

    /// Acceleration right-hand side `γ` of `D v̇ = γ` (length `n_c`).
    fn constraint_gamma(
        &self, _t: f64, _q: &[f64], _v: &[f64], gamma: &mut [f64],
    ) -> Result<(), MbdError> {
        gamma.fill(0.0);
        Ok(())
    }
}

/// Column `j` of the force tangent by central differences with step `h`: of `K = −∂f/∂q`
/// (`in_q`, perturbing `q` through [`SecondOrderSystem::integrate_position`]) or of
/// `C = −∂f/∂v`, `−(f(x + h e_j) − f(x − h e_j))/(2h)`. The reference the models' analytic
/// [`SecondOrderSystem::force_tangent`] is tested against.
pub fn central_difference_column<S: SecondOrderSystem + ?Sized>(
    sys: &S, (t, q, v): (f64, &[f64], &[f64]), j: usize, h: f64, in_q: bool,
) -> Result<Vec<f64>, MbdError> {
    let n = sys.n_v();
    let mut ws = Workspace::new();
    let mut at = |s: f64| -> Result<Vec<f64>, MbdError> {
        let mut f = vec![0.0; n];
        if in_q {
            let mut e = vec![0.0; n];
            e[j] = s;
            let mut qs = vec![0.0; q.len()];
            sys.integrate_position(q, &e, &mut qs);
            sys.forces(t, &qs, v, &mut f, &mut ws)?;
        } else {
            let mut vs = v.to_vec();
            vs[j] += s;
            sys.forces(t, q, &vs, &mut f, &mut ws)?;
        }
        Ok(f)
    };
    let (fp, fm) = (at(h)?, at(-h)?);
    Ok(fp
        .iter()
        .zip(&fm)
        .map(|(a, b)| -(a - b) / (2.0 * h))
        .collect())
}

/// Dense forward-difference tangent of a model's forces: `K = −∂f/∂q` (perturbing `q` through
/// [`SecondOrderSystem::integrate_position`], so rotations stay on their manifold) and
/// `C = −∂f/∂v`; `2 n_v + 1` force evaluations with the model's workspace `ws`. The fallback
/// of the implicit integrators for models without [`SecondOrderSystem::force_tangent`].
pub fn finite_difference_tangent<S: SecondOrderSystem + ?Sized>(
    sys: &S, t: f64, q: &[f64], v: &[f64], ws: &mut Workspace,
) -> Result<ForceTangent, MbdError> {
    let n = sys.n_v();
    let mut f0 = vec![0.0; n];
    sys.forces(t, q, v, &mut f0, ws)?;
    let mut k = Mat::<f64>::zeros(n, n);
    let mut c = Mat::<f64>::zeros(n, n);
    let mut fp = vec![0.0; n];
    let mut qp = vec![0.0; q.len()];
    let mut vp = v.to_vec();
    let mut e = vec![0.0; n];
    for j in 0..n {
        let eps = 1e-7;
        e[j] = eps;
        sys.integrate_position(q, &e, &mut qp);
        e[j] = 0.0;
        sys.forces(t, &qp, v, &mut fp, ws)?;
        for i in 0..n {
            k[(i, j)] = -(fp[i] - f0[i]) / eps;
        }
        let ev = 1e-7 * (1.0 + v[j].abs());
        vp[j] = v[j] + ev;
        sys.forces(t, q, &vp, &mut fp, ws)?;
        vp[j] = v[j];
        for i in 0..n {
            c[(i, j)] = -(fp[i] - f0[i]) / ev;
        }
    }
    Ok(ForceTangent {
        stiffness: SysMatrix::Dense(k),
        damping: SysMatrix::Dense(c),
    })
}
