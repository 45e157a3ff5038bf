//! Implicit generalized-α integrator in the index-3 form of Arnold & Brüls (2007).
//!
//! Equations at `t_{n+1}` (unknowns `v̇_{n+1}`, `λ_{n+1}`):
//!
//! ```text
//!   M(q) v̇ + Dᵀ(q) λ − f(t, q, v) = 0,     Φ(t, q) = 0
//!   q_{n+1} = q_n ⊕ Δq,   Δq = h v_n + h² (½ − β) a_n + h² β a_{n+1}
//!   v_{n+1} = v_n + h (1 − γ) a_n + h γ a_{n+1}
//!   (1 − α_m) a_{n+1} + α_m a_n = (1 − α_f) v̇_{n+1} + α_f v̇_n
//! ```
//!
//! with the Chung–Hulbert parameters `α_m = (2ρ∞ − 1)/(ρ∞ + 1)`, `α_f = ρ∞/(ρ∞ + 1)`,
//! `γ = ½ + α_f − α_m`, `β = ¼ (γ + ½)²`. `⊕` is
//! [`SecondOrderSystem::integrate_position`] (the Lie-group form of Brüls, Cardona & Arnold
//! (2012) for rotations). Newton iterations on the position correction `Δx` use the scaled
//! iteration matrix
//!
//! ```text
//!   [ M + (γ'/β') C_t + K_t/β'   Dᵀ ] [ Δx     ]   [ −r/β' ]
//!   [ D                          0  ] [ Δλ/β'  ] = [ −Φ    ],
//!   β' = (1 − α_m) / (h² β (1 − α_f)),   γ' = γ / (h β),
//! ```
//!
//! which stays well conditioned as `h → 0` (the scaling of Arnold & Brüls / Bottasso et al.).
//! The iteration runs on the workspace's Newton solver [`crate::newton::solve`] (problem in
//! the private `newton` submodule).

use super::accel::{AccelSolver, Stabilization};
use super::{
    AlphaCorrection, NoCorrection, Solution, State, Stats, StepCorrection, Stepper, check_step,
    impl_integrator, integrate_stepper,
};
use crate::newton::{
    self, LineSearch, NewtonError, NewtonOptions, NewtonProblem, NewtonWorkspace, Tolerances,
};
use crate::{MbdError, SecondOrderSystem, SysMatrix, Workspace};
use faer::Mat;

pub(crate) mod iteration_matrix;
mod newton_step;
pub(crate) use iteration_matrix::IterationMatrix;
use newton_step::StepProblem;

/// How the Newton matrix is obtained.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum JacobianMode {
    /// `M`, the model's [`SecondOrderSystem::force_tangent`] (finite differences of the forces
    /// if the model has none), [`SecondOrderSystem::constraint_force_tangent`] (neglected if
    /// `None`) and `D`. `∂(M v̇)/∂q` is neglected; sparse matrices stay sparse.
    Analytic,
    /// Dense forward differences of the complete residual (mass, constraint forces, forces and
    /// constraints): exact Newton matrix, `n_v` residual evaluations per update.
    FiniteDifference,
}

/// When the Newton matrix is re-evaluated and re-factored.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum NewtonUpdate {
    /// Full Newton: every iteration.
    EveryIteration,
    /// Modified Newton: once per step (falls back to full Newton if a step fails).
    EveryStep,
    /// Frozen iteration matrix: factored once and kept across steps; re-factored when the step
    /// size changes (the factorisation of the previous step size is kept as a spare, so that
    /// alternating between two step sizes factors each once), when the
    /// [`AlphaConfig::refactor_drift`] trigger fires, when the caller asks
    /// ([`AlphaStepper::refactor`]) and after a step that failed with it (the step is then
    /// retaken with full Newton). Exact for linear models with constant matrices; for weakly
    /// nonlinear ones a chord (W-) method whose Newton iterations converge linearly.
    Frozen,
}

/// Re-factor trigger of [`NewtonUpdate::Frozen`]: the predicted velocity `v_j` of one
/// coordinate `j` has drifted from its value `v_j,F` at the factorisation,
/// `|v_j − v_j,F| > tolerance · max(|v_j,F|, 1)` (e.g. the spin rate of a rotating model whose
/// gyroscopic matrices scale with it).
#[derive(
    Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields)]
pub struct DriftTrigger {
    /// Velocity coordinate `j` watched.
    pub dof: usize,
    /// Relative drift that triggers a factorisation.
    pub tolerance: f64,
}

/// Explicit generalized-α coefficients `(α_m, α_f, β, γ)` (Chung & Hulbert 1993), e.g. plain
/// Newmark with `α_m = α_f = 0`; [`AlphaConfig::rho_inf`] is then unused.
#[derive(
    Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields)]
pub struct AlphaCoefficients {
    /// Weight α_m of the algorithmic acceleration, in (−1, 1).
    pub alpha_m: f64,
    /// Weight α_f of the true acceleration, in (−1, 1).
    pub alpha_f: f64,
    /// Newmark β (positive).
    pub beta: f64,
    /// Newmark γ (positive).
    pub gamma: f64,
}

impl crate::Validate for AlphaCoefficients {
    /// `|α_m|, |α_f| < 1`, `0 < β ≤ 1` and `½ ≤ γ ≤ 3/2`: the ranges of β and γ spanned by
    /// the generalized-α schemes of Chung & Hulbert (1993) with ρ∞ ∈ \[0, 1\]
    /// (`γ = ½ − α_m + α_f`, `β = (γ + ½)²/4`: ρ∞ = 1 gives β = ¼, γ = ½; ρ∞ = 0 gives β = 1,
    /// γ = 3/2). γ < ½ amplifies every mode (negative numerical damping); β beyond 1 adds
    /// period error of order β (ω h)² and no damping that ρ∞ = 0 does not already give
    /// (β = 10⁹ "ran" the tire to the end with a meaningless answer, issue 20). β below
    /// `(γ + ½)²/4` is accepted: only conditionally stable, and a step too large for it fails
    /// as a numerical error, not as bad input.
    fn validate(&self) -> Result<(), crate::InvalidField> {
        use crate::validate::check;
        for (name, v) in [("alpha_m", self.alpha_m), ("alpha_f", self.alpha_f)] {
            if !(v.is_finite() && v.abs() < 1.0) {
                return Err(check::reject(name, "in (-1, 1)", v));
            }
        }
        if !(self.beta.is_finite() && self.beta > 0.0 && self.beta <= 1.0) {
            return Err(check::reject(
                "beta",
                "in (0, 1] (the generalized-alpha family spans 1/4 to 1)",
                self.beta,
            ));
        }
        check::within("gamma", self.gamma, 0.5, 1.5, "")
    }
}

/// Parameters of the generalized-α integrator.
#[derive(
    Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields, default)]
pub struct AlphaConfig {
    /// Spectral radius at infinite frequency ρ∞ ∈ \[0, 1\] (1: no numerical damping).
    pub rho_inf: f64,
    /// Nominal step size \[s\].
    pub h: f64,
    /// Absolute Newton tolerance on the position correction `‖Δx‖∞` \[m or rad\].
    pub newton_atol: f64,
    /// Relative Newton tolerance (times `‖Δq‖∞` of the step).
    pub newton_rtol: f64,
    /// Tolerance on the velocity correction `γ' ‖Δx‖∞` \[m/s or rad/s\] (`γ' = γ/(β h)`: the
    /// position correction `Δx` moves the velocities by `γ' Δx`, Arnold & Brüls 2007; module
    /// documentation). The iteration then converges only when its correction also moves the
    /// velocities by less than this: the position test's bound is
    /// [`Self::newton_atol_at`]. `None` (the default): the position test alone, which admits
    /// velocity changes of `γ' newton_atol` in the last iteration (5 µm at `h` = 0.25 ms and
    /// ρ∞ = 0.8: 40 mm/s). A regularised friction law resolves slip velocities only to its
    /// transition width (`contact::friction::FrictionLaw::transition_width`); a model stepped
    /// with a loose position tolerance and a sharper law gets friction forces off by up to
    /// `μ f_n` at a converged step.
    pub newton_vtol: Option<f64>,
    /// Maximum Newton iterations per step.
    pub max_newton_iterations: usize,
    /// Newton-matrix source.
    pub jacobian: JacobianMode,
    /// Newton-matrix update strategy.
    pub update: NewtonUpdate,
    /// Maximum number of step halvings after a failed Newton iteration in
    /// [`Stepper::step_until`] / [`Stepper::advance_to`] (the step continues from the time
    /// reached and grows back by doubling).
    pub max_halvings: usize,
    /// Subdivision levels of a step of prescribed size ([`Stepper::step`] with `Some(h)`)
    /// whose Newton iteration fails: it is retaken as two steps of `h/2`, each of which may
    /// be split again, up to this many levels, so that the step still ends on `t + h` (a
    /// caller's fixed time grid is kept; each split counts in [`Stats::halvings`] and
    /// [`Stats::rejected_steps`]). `0`: the failure is returned. The rotating-mesh belt
    /// model (`flowing::belt::nodal::NodalBelt`) needs it when a coarse element lands on a
    /// pulley; the belt procedures of `drives` use 4 levels.
    pub subdivisions: usize,
    /// Project the velocities onto `D v = ν` after each step (the index-3 form satisfies the
    /// constraints at position level only).
    pub project_velocities: bool,
    /// Explicit coefficients instead of those of `rho_inf`.
    pub coefficients: Option<AlphaCoefficients>,
    /// Linearly implicit step: one Newton iteration from the predictor, accepted without a
    /// convergence test (exact for linear models with the exact iteration matrix; with
    /// [`NewtonUpdate::Frozen`] a linearly implicit W-method whose matrix error enters as the
    /// defect `(S(xₙ) − S_F) v̇ₙ` of the predictor, a lag of one step).
    pub linearly_implicit: bool,
    /// Predict `v̇ₙ₊₁ = 0` instead of `v̇ₙ` (the unknown of a linearly implicit step is then
    /// the end-of-step acceleration itself, as in Newmark's acceleration form; the predictor
    /// does not change the step of a linear model with the exact matrix, but with a frozen one
    /// the matrix error no longer enters through `v̇ₙ`).
    pub zero_predictor: bool,
    /// Keep the iteration matrix as its explicit inverse (module `iteration_matrix`): solves
    /// become matrix–vector products; for small dense models.
    pub explicit_inverse: bool,
    /// Factor a sparse iteration matrix with the banded-plus-border LU of
    /// [`KktSolver::banded`](crate::linalg::KktSolver::banded) (reverse Cuthill–McKee band,
    /// densely coupled coordinates as a border): for closed chains of nodes such as the ANCF
    /// belt, whose 121 × 121 matrix it factors ≈ 2.7× and solves ≈ 2.5× faster than the
    /// supernodal sparse LU (BENCHMARKS.md, "ancf: belt drive").
    pub banded_lu: bool,
    /// Re-factor trigger of [`NewtonUpdate::Frozen`] (`None`: only step-size changes, failures
    /// and [`AlphaStepper::refactor`]).
    pub refactor_drift: Option<DriftTrigger>,
    /// Contraction trigger of [`NewtonUpdate::Frozen`] and [`NewtonUpdate::EveryStep`]: when a
    /// correction solved with the kept factorisation exceeds this fraction of the previous
    /// correction of the step, the iteration matrix is re-evaluated and re-factored at the
    /// current iterate and the correction recomputed with it (`None`: never; the modified
    /// Newton of Exudyn's implicit solvers uses 0.5). With a frozen matrix a chord iteration
    /// converges linearly at the rate of the matrix error; the trigger renews the matrix as
    /// soon as that rate is poor (after contact or friction states changed) and keeps it
    /// while it is good.
    pub refactor_contraction: Option<f64>,
    /// Treatment of a Newton iteration whose corrections stop contracting
    /// ([`crate::newton::Stall`]: Armijo backtracking on the residual norm after the first
    /// stall, early exit after repeated stalls; the step is then retaken as after any Newton
    /// failure, halved or with full Newton after a failure with a kept matrix). At a
    /// saturating friction law (slope ν_s inside, 0 outside) the corrections can jump between
    /// the two flat branches forever, a two-cycle of constant size that the step would
    /// otherwise have to be halved to escape. The residual of an accepted line-search trial is
    /// reused by the next iteration. `None`: plain Newton up to `max_newton_iterations`.
    pub newton_stall: Option<crate::newton::Stall>,
    /// Armijo backtracking on the residual norm in every Newton iteration
    /// ([`crate::newton::LineSearch`] with the trial steps of
    /// [`Self::newton_line_search_trials`] and the full step when none decreases `‖r‖`): a
    /// globalised Newton that does not cycle at the kinks of
    /// piecewise-smooth forces. The residual of an accepted trial is reused by the next
    /// iteration, so an accepted full step costs nothing extra.
    pub newton_line_search: bool,
    /// Trial steps of the line search of [`Self::newton_line_search`]: `1, ½, …, 2^{1−n}`,
    /// then the full step when none decreases `‖r‖` (≥ 1; default 5). A sharp regularised
    /// friction law (`μ tanh(v_t/v_s)` with `v_s` = 0.05 mm/s on a belt) needs deeper
    /// backtracking: its Newton correction moves the slip velocity by orders of magnitude more
    /// than `v_s`, and after five halvings the full step throws the iterate onto the opposite
    /// saturated branch (the belt procedures of `drives` use 13, BENCHMARKS.md "friction
    /// regularisation").
    pub newton_line_search_trials: usize,
    /// Offer every step's Newton iteration the model's own prediction
    /// ([`SecondOrderSystem::predict_increment`]) besides the constant-acceleration predictor
    /// `v̇ₙ₊₁ = v̇ₙ`, and start from the one whose residual `‖[M v̇ + Dᵀλ − f; Φ]‖₂` is
    /// smaller (one residual evaluation more per step when the model predicts). The model's
    /// increment `Δq̂` moves the whole unknown along the Newmark relations of the update,
    /// `v ← v + γ' (Δq̂ − Δq)`, `v̇ ← v̇ + β' (Δq̂ − Δq)`, as a Newton correction would: only
    /// the starting iterate changes, not the equations solved.
    pub model_predictor: bool,
    /// Largest Newton correction `‖Δx‖∞` taken in one iteration (a trust region,
    /// [`crate::newton::NewtonOptions::max_step`]: a longer correction is scaled down to it
    /// before the line search; an iteration converges only on an unscaled correction), in the
    /// position coordinates' units (`None`: unlimited). Where contact points enter and leave
    /// their contact within a step, the Newton matrix at the predictor can miss the forces by
    /// orders of magnitude: on the default FEAD drive at 3500 rpm the ANCF belt's first
    /// corrections reached 2–20 cm in a step that moves the belt 7 mm, and the line search
    /// then spent up to 25 iterations reining them in (BENCHMARKS.md, issue 37 item 4).
    pub newton_max_step: Option<f64>,
    /// Ask the model for the largest fraction of each Newton correction it admits
    /// ([`SecondOrderSystem::correction_limit`], with the iterate's `q = qₙ ⊕ Δq`, `v` and
    /// the correction's `Δq`, `Δv = γ' Δq`) and scale the correction to it before the line
    /// search; a scaled iteration never counts as converged. Only the path of the iteration
    /// changes, not the equations solved. E.g. the transition-aware limit of a sharp
    /// regularised friction law (Castro et al. 2019), whose Newton corrections otherwise move
    /// slip velocities across the law's steep band onto the opposite flat branch.
    pub model_correction_limit: bool,
}

impl Default for AlphaConfig {
    fn default() -> Self {
        Self {
            rho_inf: 0.8,
            h: 1e-3,
            newton_atol: 1e-10,
            newton_rtol: 1e-8,
            newton_vtol: None,
            max_newton_iterations: 20,
            jacobian: JacobianMode::Analytic,
            update: NewtonUpdate::EveryIteration,
            max_halvings: 8,
            subdivisions: 0,
            project_velocities: false,
            coefficients: None,
            linearly_implicit: false,
            zero_predictor: false,
            explicit_inverse: false,
            banded_lu: false,
            refactor_drift: None,
            refactor_contraction: None,
            newton_stall: None,
            newton_line_search: false,
            newton_line_search_trials: 5,
            model_predictor: false,
            newton_max_step: None,
            model_correction_limit: false,
        }
    }
}

/// The four generalized-α coefficients `(α_m, α_f, β, γ)` from ρ∞ (Chung & Hulbert 1993).
pub fn alpha_coefficients(rho_inf: f64) -> (f64, f64, f64, f64) {
    let r = rho_inf;
    let am = (2.0 * r - 1.0) / (r + 1.0);
    let af = r / (r + 1.0);
    let g = 0.5 + af - am;
    let b = 0.25 * (g + 0.5) * (g + 0.5);
    (am, af, b, g)
}

impl AlphaConfig {
    /// The absolute tolerance of the position test at the velocity factor `gp` = `γ' = γ/(β h)`
    /// \[1/s\] of a step: `newton_atol`, tightened to `newton_vtol / γ'` when
    /// [`Self::newton_vtol`] is set and smaller.
    pub fn newton_atol_at(&self, gp: f64) -> f64 {
        match self.newton_vtol {
            Some(vtol) if gp > 0.0 => self.newton_atol.min(vtol / gp),
            _ => self.newton_atol,
        }
    }

    /// `(α_m, α_f, β, γ)`: [`coefficients`](Self::coefficients) if set, else those of
    /// `rho_inf` ([`alpha_coefficients`]).
    pub fn alpha_coefficients(&self) -> (f64, f64, f64, f64) {
        match self.coefficients {
            Some(c) => (c.alpha_m, c.alpha_f, c.beta, c.gamma),
            None => alpha_coefficients(self.rho_inf),
        }
    }
}

/// Generalized-α integrator (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GeneralizedAlpha {
    /// Parameters.
    pub params: AlphaConfig,
}

impl GeneralizedAlpha {
    /// Integrator with the given parameters.
    pub fn new(params: AlphaConfig) -> Self {
        Self { params }
    }

    /// A stepper started at `state0` (consistent initial accelerations and multipliers from the
    /// index-1 equations).
    pub fn stepper<S: SecondOrderSystem + ?Sized>(
        &self, sys: &S, state0: State,
    ) -> Result<AlphaStepper, MbdError> {
        AlphaStepper::new(sys, state0, self.params)
    }

    /// A stepper started at `state0` that applies `correction` after every step's Newton
    /// iteration (nonsmooth contact, module [`correction`](super::StepCorrection)).
    pub fn stepper_with<S: SecondOrderSystem + ?Sized, C: StepCorrection<S>>(
        &self, sys: &S, state0: State, correction: C,
    ) -> Result<AlphaStepper<C>, MbdError> {
        Ok(AlphaStepper::new(sys, state0, self.params)?.with_correction(correction))
    }

    /// Integrates from `state0` to `t_end` \[s\] with the nominal step `params.h` (the last step
    /// is shortened; failed Newton iterations halve the step). `observer` sees the initial state
    /// and every accepted step.
    pub fn integrate<S: SecondOrderSystem + ?Sized, R: super::Proceed>(
        &self, sys: &S, state0: State, t_end: f64, observer: impl FnMut(&State) -> R,
    ) -> Result<Solution, MbdError> {
        integrate_stepper(self.stepper(sys, state0)?, sys, t_end, observer)
    }
}

impl_integrator!(GeneralizedAlpha);

/// Per-step vectors of [`AlphaStepper`], allocated once.
#[derive(Default)]
struct Work {
    /// Newton unknown `[Δq; v_{n+1}; v̇_{n+1}; λ_{n+1}]`.
    x: Vec<f64>,
    v1: Vec<f64>,
    q1: Vec<f64>,
    rhs: Vec<f64>,
    f: Vec<f64>,
    /// Residual, correction and updated unknown of the linearly implicit step.
    r: Vec<f64>,
    dx: Vec<f64>,
    x_new: Vec<f64>,
    /// Last residual evaluated by a line-search trial and its unknowns.
    cache_x: Vec<f64>,
    cache_r: Vec<f64>,
    newton: NewtonWorkspace,
}

impl Work {
    fn new(nq: usize, n: usize, nc: usize) -> Self {
        Self {
            x: vec![0.0; 3 * n + nc],
            v1: vec![0.0; n],
            q1: vec![0.0; nq],
            rhs: vec![0.0; n + nc],
            f: vec![0.0; n],
            r: vec![0.0; n + nc],
            dx: vec![0.0; n + nc],
            x_new: vec![0.0; 3 * n + nc],
            cache_x: vec![0.0; 3 * n + nc],
            cache_r: vec![0.0; n + nc],
            newton: NewtonWorkspace::new(),
        }
    }
}

/// Stepping object of the generalized-α integrator: holds the state, the accelerations
/// `v̇`, the algorithmic accelerations `a`, the multipliers `λ`, the statistics, the factored
/// iteration matrix, the per-step workspaces and a [`StepCorrection`] `C` applied after the
/// Newton iteration of every step (nonsmooth contact; [`NoCorrection`] by default).
pub struct AlphaStepper<C = NoCorrection> {
    /// Parameters.
    pub params: AlphaConfig,
    state: State,
    vdot: Vec<f64>,
    a: Vec<f64>,
    lambda: Vec<f64>,
    /// Statistics so far.
    pub stats: Stats,
    matrix: IterationMatrix,
    /// The factorisation of the previous step size ([`NewtonUpdate::Frozen`]).
    spare: Option<IterationMatrix>,
    /// Solve scratch of the explicit inverse (`n_v + n_c`).
    scratch: Vec<f64>,
    mass_cache: Option<SysMatrix>,
    /// `mass_cache` without its stored zeros, for the products `M v̇` of the residual.
    mass_product: Option<SysMatrix>,
    work: Work,
    /// The model's scratch ([`SecondOrderSystem::forces`], kept for the stepper's lifetime).
    ws: Workspace,
    /// Current step of [`Stepper::step_until`] (halved after Newton failures).
    h_cur: f64,
    halvings: usize,
    correction: C,
    /// The worker thread of the explicit inverse's products ([`AlphaStepper::set_product_worker`]).
    worker: Option<std::sync::Arc<crate::parallel::ProductWorker>>,
}

impl AlphaStepper<NoCorrection> {
    /// Starts at `state0`; `v̇₀` and `λ₀` solve the index-1 equations, `a₀ = v̇₀`.
    pub fn new<S: SecondOrderSystem + ?Sized>(
        sys: &S, state0: State, params: AlphaConfig,
    ) -> Result<Self, MbdError> {
        check_step(params.h, "generalized-alpha step h")?;
        if let Some(c) = params.coefficients {
            crate::Validate::validate(&c).map_err(|e| MbdError::InvalidInput {
                item: format!("generalized-alpha coefficients: {}", e.field),
                reason: e.reason,
            })?;
        } else if !(0.0..=1.0).contains(&params.rho_inf) {
            return Err(MbdError::InvalidInput {
                item: "generalized-alpha rho_inf".into(),
                reason: format!("must lie in [0, 1], got {}", params.rho_inf),
            });
        }
        if params.max_newton_iterations == 0 {
            return Err(MbdError::InvalidInput {
                item: "generalized-alpha max_newton_iterations".into(),
                reason: "must be at least 1".into(),
            });
        }
        state0.check(sys)?;
        let mut stats = Stats::default();
        let mut vdot = vec![0.0; sys.n_v()];
        let mut lambda = vec![0.0; sys.n_c()];
        let mut accel = AccelSolver::default();
        accel.solve(
            sys,
            state0.t,
            &state0.q,
            &state0.v,
            &Stabilization::default(),
            &mut stats,
            &mut vdot,
            &mut lambda,
        )?;
        let a = vdot.clone();
        Ok(Self {
            params,
            state: state0,
            vdot,
            a,
            lambda,
            stats,
            matrix: IterationMatrix::new(),
            spare: None,
            scratch: vec![0.0; sys.n_v() + sys.n_c()],
            mass_cache: None,
            mass_product: None,
            work: Work::new(sys.n_q(), sys.n_v(), sys.n_c()),
            ws: std::mem::take(&mut accel.ws),
            h_cur: params.h,
            halvings: 0,
            correction: NoCorrection,
            worker: None,
        })
    }
}

impl<C> AlphaStepper<C> {
    /// The same stepper with the step correction `correction` (applied from the next step on).
    pub fn with_correction<C2>(self, correction: C2) -> AlphaStepper<C2> {
        AlphaStepper {
            params: self.params,
            state: self.state,
            vdot: self.vdot,
            a: self.a,
            lambda: self.lambda,
            stats: self.stats,
            matrix: self.matrix,
            spare: self.spare,
            scratch: self.scratch,
            mass_cache: self.mass_cache,
            mass_product: self.mass_product,
            work: self.work,
            ws: self.ws,
            h_cur: self.h_cur,
            halvings: self.halvings,
            correction,
            worker: self.worker,
        }
    }

    /// Splits the products with the explicit inverse of the iteration matrix
    /// ([`AlphaConfig::explicit_inverse`]) between the calling thread and `worker` (`None`: one
    /// thread), from the next factorisation on; the results are the same bit for bit
    /// ([`crate::parallel`]).
    pub fn set_product_worker(
        &mut self, worker: Option<std::sync::Arc<crate::parallel::ProductWorker>>,
    ) {
        self.worker = worker;
    }

    /// The model's workspace this stepper passes to its hot methods (e.g. to read
    /// statistics a model keeps there).
    pub fn workspace(&self) -> &Workspace {
        &self.ws
    }

    /// The step correction.
    pub fn correction(&self) -> &C {
        &self.correction
    }

    /// The step correction (mutable, e.g. to change its data between steps).
    pub fn correction_mut(&mut self) -> &mut C {
        &mut self.correction
    }

    /// Current state.
    pub fn state(&self) -> &State {
        &self.state
    }

    /// Current accelerations `v̇`.
    pub fn acceleration(&self) -> &[f64] {
        &self.vdot
    }

    /// Current algorithmic (pseudo-) accelerations `a` of the update formulas.
    pub fn algorithmic_acceleration(&self) -> &[f64] {
        &self.a
    }

    /// Replaces the start accelerations `v̇₀ = a₀` (default: the index-1 equations), e.g. by
    /// those of a known steady state whose contact forces the smooth equations do not see.
    /// Only before the first step; errors on a length other than `n_v`.
    pub fn set_initial_acceleration(&mut self, vdot: &[f64]) -> Result<(), MbdError> {
        if vdot.len() != self.vdot.len() || self.stats.steps > 0 {
            return Err(MbdError::InvalidInput {
                item: "generalized-alpha initial acceleration".into(),
                reason: format!(
                    "{} values for n_v = {} (only before the first step; {} steps taken)",
                    vdot.len(),
                    self.vdot.len(),
                    self.stats.steps
                ),
            });
        }
        self.vdot.copy_from_slice(vdot);
        self.a.copy_from_slice(vdot);
        Ok(())
    }

    /// Continues from a state saved earlier from this stepper (or one of the same model):
    /// `state`, its accelerations `v̇` ([`AlphaStepper::acceleration`]) and algorithmic
    /// accelerations `a` ([`AlphaStepper::algorithmic_acceleration`]), which together are the
    /// generalized-α scheme's whole memory (Arnold & Brüls 2007, (8)–(10)). The factorisations
    /// are dropped (the next step factors at the resumed state, so that a resumed run does
    /// not depend on where this stepper was before: with [`NewtonUpdate::Frozen`] a kept
    /// factorisation would); the statistics are kept. Errors: a length other than
    /// `n_q`/`n_v`, or a value that is not finite.
    pub fn resume<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S, state: State, vdot: &[f64], a: &[f64],
    ) -> Result<(), MbdError> {
        state.check(sys)?;
        for (what, x) in [("acceleration", vdot), ("algorithmic acceleration", a)] {
            if x.len() != self.vdot.len() {
                return Err(MbdError::InvalidInput {
                    item: format!("generalized-alpha {what}"),
                    reason: format!("{} values for n_v = {}", x.len(), self.vdot.len()),
                });
            }
            if x.iter().any(|v| !v.is_finite()) {
                return Err(MbdError::NonFinite {
                    what: format!("generalized-alpha {what}"),
                    t: state.t,
                });
            }
        }
        self.vdot.copy_from_slice(vdot);
        self.a.copy_from_slice(a);
        self.state = state;
        self.matrix.invalidate();
        self.spare = None;
        Ok(())
    }

    /// Continues after the model's number of constraint equations changed between steps (a
    /// rheonomic constraint switched on or off, e.g. a prescribed coordinate): the multipliers,
    /// the per-step vectors and the iteration matrix are re-sized to `sys.n_c()`; the state,
    /// `v̇`, `a` and the statistics are kept. The new multipliers start at 0 (only the predictor
    /// of the next Newton iteration: λ enters the step equations linearly) and the next step
    /// factors the augmented matrix again. Errors: a model with another number of coordinates
    /// or velocities.
    pub fn resize_constraints<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S,
    ) -> Result<(), MbdError> {
        let (nq, n, nc) = (sys.n_q(), sys.n_v(), sys.n_c());
        if nq != self.state.q.len() || n != self.vdot.len() {
            return Err(MbdError::InvalidInput {
                item: "generalized-alpha constraints".into(),
                reason: format!(
                    "the model has n_q = {nq}, n_v = {n}; the stepper {} and {}",
                    self.state.q.len(),
                    self.vdot.len()
                ),
            });
        }
        self.lambda = vec![0.0; nc];
        self.work = Work::new(nq, n, nc);
        self.scratch = vec![0.0; n + nc];
        self.matrix = IterationMatrix::new();
        self.spare = None;
        Ok(())
    }

    /// Current Lagrange multipliers `λ` (generalized reactions `−Dᵀλ`).
    pub fn lambda(&self) -> &[f64] {
        &self.lambda
    }

    /// Symbolic sparse analyses performed so far (sparse models).
    pub fn symbolic_factorizations(&self) -> usize {
        self.matrix.kkt.symbolic_factorizations
            + self
                .spare
                .as_ref()
                .map_or(0, |m| m.kkt.symbolic_factorizations)
    }

    /// Drops the current factored iteration matrix: the next step factors again (the
    /// caller's re-factor trigger of [`NewtonUpdate::Frozen`], e.g. after changing the model's
    /// matrices; the spare of the other step size is kept).
    pub fn refactor(&mut self) {
        self.matrix.invalidate();
    }

    /// [`NewtonUpdate::Frozen`]: the velocity of the [`AlphaConfig::refactor_drift`] coordinate
    /// at the factorisation kept for the step size `h` \[s\] (current or spare), `None` if
    /// none is kept (the next step of size `h` factors).
    pub fn frozen_reference(&self, h: f64) -> Option<f64> {
        [Some(&self.matrix), self.spare.as_ref()]
            .into_iter()
            .flatten()
            .find(|m| m.is_factored() && m.h == h)
            .map(|m| m.v_ref)
    }

    /// One step of exactly `h` \[s\], split into halves after a Newton failure up to
    /// [`AlphaConfig::subdivisions`] levels (recursively, ending on `t + h`). On failure the
    /// state is that reached by the sub-steps already accepted.
    fn step_subdivided<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S, h: f64, levels: usize,
    ) -> Result<(), MbdError>
    where
        C: StepCorrection<S>,
    {
        let t1 = self.state.t + h;
        match self.step_to(sys, h, t1) {
            Err(MbdError::NoConvergence { .. }) if levels > 0 => {
                self.stats.rejected_steps += 1;
                self.stats.halvings += 1;
                self.step_subdivided(sys, 0.5 * h, levels - 1)?;
                self.step_subdivided(sys, 0.5 * h, levels - 1)
            }
            other => other,
        }
    }

    /// One step of size `h` ending at `t1 ≈ t + h` (`t1` exactly, so that stop times are hit).
    fn step_to<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S, h: f64, t1: f64,
    ) -> Result<(), MbdError>
    where
        C: StepCorrection<S>,
    {
        check_step(h, "generalized-alpha step h")?;
        let p = self.params;
        let mut w = std::mem::take(&mut self.work);
        let mut r = self.step_impl(sys, h, t1, p.update, &mut w);
        if let Err(MbdError::NoConvergence { .. }) = r
            && matches!(p.update, NewtonUpdate::EveryStep | NewtonUpdate::Frozen)
        {
            self.stats.rejected_steps += 1;
            r = self.step_impl(sys, h, t1, NewtonUpdate::EveryIteration, &mut w);
        }
        self.work = w;
        r
    }

    fn step_impl<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S, h: f64, t1: f64, update: NewtonUpdate, w: &mut Work,
    ) -> Result<(), MbdError>
    where
        C: StepCorrection<S>,
    {
        let p = self.params;
        let (am, af, beta, gamma) = p.alpha_coefficients();
        let n = sys.n_v();
        let nc = sys.n_c();
        let bp = (1.0 - am) / (h * h * beta * (1.0 - af));
        let gp = gamma / (h * beta);
        let Work {
            x,
            v1: v1_state,
            q1,
            rhs,
            f,
            r: r_lin,
            dx: dx_lin,
            x_new: x_lin,
            cache_x,
            cache_r,
            newton: newton_ws,
        } = w;

        // predictor: v̇_{n+1} = v̇_n, λ_{n+1} = λ_n
        {
            let (dq, rest) = x.split_at_mut(n);
            let (v1, rest) = rest.split_at_mut(n);
            let (vdot1, lam1) = rest.split_at_mut(n);
            if p.zero_predictor {
                vdot1.iter_mut().for_each(|x| *x = 0.0);
            } else {
                vdot1.copy_from_slice(&self.vdot);
            }
            lam1.copy_from_slice(&self.lambda);
            for i in 0..n {
                let a1 = (af * self.vdot[i] - am * self.a[i] + (1.0 - af) * vdot1[i]) / (1.0 - am);
                dq[i] = h * self.state.v[i] + h * h * ((0.5 - beta) * self.a[i] + beta * a1);
                v1[i] = self.state.v[i] + h * ((1.0 - gamma) * self.a[i] + gamma * a1);
            }
        }

        let mut cached = false;
        if p.model_predictor {
            cached = self.model_prediction(
                sys,
                (h, t1, bp, gp),
                x,
                q1,
                f,
                r_lin,
                x_lin,
                dx_lin,
                cache_x,
                cache_r,
            )?;
        }
        if update == NewtonUpdate::Frozen {
            self.select_frozen_matrix(h, &x[n..2 * n]);
        }
        let opts = NewtonOptions {
            max_iterations: p.max_newton_iterations,
            tolerances: Tolerances::mixed(p.newton_atol_at(gp), p.newton_rtol),
            stall: p.newton_stall,
            line_search: p.newton_line_search.then_some(LineSearch {
                max_trials: p.newton_line_search_trials,
                ..Default::default()
            }),
            max_step: p.newton_max_step.unwrap_or(f64::INFINITY),
            ..Default::default()
        };
        let mut problem = StepProblem {
            stepper: self,
            sys,
            t1,
            h,
            bp,
            gp,
            update,
            q1,
            f,
            trial: rhs,
            it: 0,
            reuse: false,
            prev_norm: f64::INFINITY,
            cache_x,
            cache_r,
            cached,
        };
        let solved = if p.linearly_implicit {
            // one iteration from the predictor, no convergence test
            problem
                .linearize(x, 1.0, r_lin)
                .and_then(|()| problem.solve(r_lin, dx_lin))
                .and_then(|()| problem.update(x, dx_lin, x_lin))
                .map(|()| x.copy_from_slice(x_lin))
                .map_err(NewtonError::Problem)
        } else {
            newton::solve(&mut problem, x, &opts, newton_ws).map(|_| ())
        };
        let iterations = problem.it;
        match solved {
            Ok(()) => {}
            // a singular Newton matrix at an iterate past the step's first one is a Newton
            // failure like a non-finite one (below): the iterate, not the model at the step's
            // start, is singular, and the caller halves the step. On the flowing belt's
            // energy-consistent formulation at 3500 rpm from rest (0.125 ms) the line search
            // stalled at an iterate whose crank wrap had lifted off (5 of 24 nodes in contact,
            // 2.6 mm penetration, slip −8.9 m/s) and whose Newton matrix was singular there,
            // though the mass part and the matrix at every accepted state were regular
            // (BENCHMARKS.md, "An energy-consistent flowing belt"). The matrix at the first
            // iterate (the predictor) keeps its `Singular` error: it is the model's.
            Err(NewtonError::Problem(MbdError::Singular { .. })) if iterations > 1 => {
                return Err(MbdError::NoConvergence {
                    t: t1,
                    iterations,
                    residual: f64::NAN,
                });
            }
            Err(NewtonError::Problem(e)) => return Err(e),
            // the step is halved by the caller
            Err(NewtonError::NoConvergence {
                iterations,
                correction,
                ..
            }) => {
                return Err(MbdError::NoConvergence {
                    t: t1,
                    iterations,
                    residual: correction,
                });
            }
            Err(NewtonError::NonFinite {
                what, iteration, ..
            }) => {
                return Err(MbdError::NoConvergence {
                    t: t1,
                    iterations: iteration,
                    residual: if what == "correction" {
                        f64::INFINITY
                    } else {
                        f64::NAN
                    },
                });
            }
            Err(e) => return Err(e.into_mbd(t1)),
        }
        let (dq, rest) = x.split_at_mut(n);
        let (v1, rest) = rest.split_at_mut(n);
        let (vdot1, lam1) = rest.split_at_mut(n);
        sys.integrate_position(&self.state.q, dq, q1);
        // nonsmooth correction with the factored iteration matrix
        {
            let integrate =
                |q: &[f64], d: &[f64], out: &mut [f64]| sys.integrate_position(q, d, out);
            let factor_id = self.matrix.id;
            let mut ctx = AlphaCorrection {
                h,
                beta_prime: bp,
                gamma_prime: gp,
                start: &self.state,
                t1,
                dq,
                q: q1,
                v: v1,
                vdot: vdot1,
                lambda: lam1,
                matrix: &mut self.matrix,
                rhs,
                scratch: &mut self.scratch,
                integrate_position: &integrate,
                factorizations: self.stats.factorizations,
                factor_id,
            };
            self.correction.correct(sys, &mut ctx)?;
        }
        v1_state.copy_from_slice(v1);
        let v1 = v1_state;
        // accept
        sys.normalize(q1);
        let mut new_state = State::new(t1, std::mem::take(q1), std::mem::take(v1));
        let checked = if p.project_velocities && nc > 0 {
            super::accel::project_velocities(sys, &mut new_state)
        } else {
            Ok(())
        }
        .and_then(|()| new_state.check(sys));
        if let Err(e) = checked {
            *q1 = new_state.q;
            *v1 = new_state.v;
            return Err(e);
        }
        for i in 0..n {
            self.a[i] = (af * self.vdot[i] - am * self.a[i] + (1.0 - af) * vdot1[i]) / (1.0 - am);
        }
        let old = std::mem::replace(&mut self.state, new_state);
        *q1 = old.q;
        *v1 = old.v;
        self.vdot.copy_from_slice(vdot1);
        self.lambda.copy_from_slice(lam1);
        self.stats.steps += 1;
        Ok(())
    }

    /// `r = M v̇ + Dᵀλ − f`, `φ = Φ(t, q)`.
    #[allow(clippy::too_many_arguments)]
    fn residual<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S, t: f64, q: &[f64], v: &[f64], vdot: &[f64], lam: &[f64], r: &mut [f64],
        phi: &mut [f64], f: &mut [f64],
    ) -> Result<(), MbdError> {
        self.stats.force_evaluations += 1;
        if sys.dynamic_residual(t, q, v, vdot, r, &mut self.ws)? {
            if let Some(i) = r.iter().position(|x| !x.is_finite()) {
                return Err(MbdError::NonFinite {
                    what: format!("dynamic residual of {}", sys.dof_name(i)),
                    t,
                });
            }
        } else {
            sys.forces(t, q, v, f, &mut self.ws)?;
            if let Some(i) = f.iter().position(|x| !x.is_finite()) {
                return Err(MbdError::NonFinite {
                    what: format!("force on {}", sys.dof_name(i)),
                    t,
                });
            }
            if sys.mass_is_constant() {
                if self.mass_cache.is_none() {
                    self.mass_cache = Some(sys.mass(t, q)?);
                }
                if self.mass_product.is_none() {
                    self.mass_product = self.mass_cache.as_ref().map(SysMatrix::without_zeros);
                }
                if let Some(m) = &self.mass_product {
                    m.mul_vec(vdot, r);
                }
            } else {
                sys.mass(t, q)?.mul_vec(vdot, r);
            }
            for (ri, fi) in r.iter_mut().zip(f.iter()) {
                *ri -= fi;
            }
        }
        if !phi.is_empty() {
            let d = sys.constraint_jacobian(t, q)?;
            d.tmul_vec_add(1.0, lam, r);
            sys.constraint_residual(t, q, phi)?;
        }
        Ok(())
    }

    /// [`AlphaConfig::model_predictor`]: replaces the predicted unknown `x` by the model's
    /// prediction ([`SecondOrderSystem::predict_increment`], moved along the Newmark
    /// relations) when its residual is smaller. Returns whether `cache_x`/`cache_r` hold the
    /// residual at the chosen `x` (the first Newton iteration then reuses it).
    #[allow(clippy::too_many_arguments)] // the step's coefficients and the work vectors
    fn model_prediction<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S, (h, t1, bp, gp): (f64, f64, f64, f64), x: &mut [f64], q1: &mut [f64],
        f: &mut [f64], r_std: &mut [f64], x_alt: &mut [f64], dq_alt: &mut [f64],
        cache_x: &mut [f64], cache_r: &mut [f64],
    ) -> Result<bool, MbdError> {
        let n = sys.n_v();
        let dq_alt = &mut dq_alt[..n];
        dq_alt.copy_from_slice(&x[..n]);
        let (t, q, v) = (self.state.t, &self.state.q, &self.state.v);
        if !sys.predict_increment(t, q, v, &self.vdot, h, dq_alt) {
            return Ok(false);
        }
        x_alt.copy_from_slice(x);
        for (i, &dq) in dq_alt.iter().enumerate() {
            let d = dq - x[i];
            x_alt[i] = dq;
            x_alt[n + i] += gp * d;
            x_alt[2 * n + i] += bp * d;
        }
        let norm = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>().sqrt();
        let mut eval = |st: &mut Self, xx: &[f64], r: &mut [f64]| -> Result<f64, MbdError> {
            let (dq, rest) = xx.split_at(n);
            let (v1, rest) = rest.split_at(n);
            let (vdot1, lam1) = rest.split_at(n);
            sys.integrate_position(&st.state.q, dq, q1);
            let (rr, phi) = r.split_at_mut(n);
            st.residual(sys, t1, q1, v1, vdot1, lam1, rr, phi, f)?;
            Ok(norm(r))
        };
        let standard = eval(self, x, r_std)?;
        // a prediction whose residual is not finite is not taken
        let alternative = eval(self, x_alt, cache_r).unwrap_or(f64::INFINITY);
        if alternative < standard {
            x.copy_from_slice(x_alt);
            self.stats.model_predictions += 1;
        } else {
            cache_r.copy_from_slice(r_std);
        }
        cache_x.copy_from_slice(x);
        Ok(true)
    }

    /// [`NewtonUpdate::Frozen`]: keeps the factored matrix unless the step size `h` \[s\]
    /// changed (then swaps in the spare of that size, or keeps the current one as the spare)
    /// or the drift trigger fires on the predicted velocities `v1`.
    fn select_frozen_matrix(&mut self, h: f64, v1: &[f64]) {
        if self.matrix.is_factored() && self.matrix.h != h {
            if self
                .spare
                .as_ref()
                .is_some_and(|m| m.is_factored() && m.h == h)
            {
                if let Some(spare) = self.spare.as_mut() {
                    std::mem::swap(&mut self.matrix, spare);
                }
            } else {
                // a step of another size (an output time's shortened step, a halving): factor
                // it on the spare's symbolic analysis (the pattern does not change with `h`),
                // so that the band plan and the symbolic LU are not redone at every such step
                let mut fresh = self.spare.take().unwrap_or_else(IterationMatrix::new);
                fresh.invalidate();
                let old = std::mem::replace(&mut self.matrix, fresh);
                self.spare = Some(old);
            }
        }
        if let Some(trig) = self.params.refactor_drift
            && self.matrix.is_factored()
            && let Some(&v) = v1.get(trig.dof)
        {
            let v_ref = self.matrix.v_ref;
            if (v - v_ref).abs() > trig.tolerance * v_ref.abs().max(1.0) {
                self.matrix.invalidate();
            }
        }
    }

    fn mass<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S, t: f64, q: &[f64],
    ) -> Result<SysMatrix, MbdError> {
        if sys.mass_is_constant() {
            if let Some(m) = &self.mass_cache {
                return Ok(m.clone());
            }
            let m = sys.mass(t, q)?;
            self.mass_cache = Some(m.clone());
            Ok(m)
        } else {
            sys.mass(t, q)
        }
    }

    /// Evaluates and factors the Newton matrix ([`Self::newton_matrix_factor`]) and counts the
    /// banded factorisations and rejections of the KKT solver ([`Stats::banded_factorizations`]).
    #[allow(clippy::too_many_arguments)]
    fn newton_matrix<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S, t: f64, q: &[f64], v: &[f64], vdot: &[f64], lam: &[f64], r0: &[f64],
        phi0: &[f64], bp: f64, gp: f64, h: f64, f: &mut [f64],
    ) -> Result<(), MbdError> {
        let kkt = &self.matrix.kkt;
        let before = (
            kkt.banded_factorizations,
            kkt.banded_rejections,
            kkt.banded_checks,
        );
        let out = self.newton_matrix_factor(sys, t, q, v, vdot, lam, r0, phi0, bp, gp, h, f);
        let kkt = &self.matrix.kkt;
        self.stats.banded_factorizations += kkt.banded_factorizations.saturating_sub(before.0);
        self.stats.banded_rejections += kkt.banded_rejections.saturating_sub(before.1);
        self.stats.banded_checks += kkt.banded_checks.saturating_sub(before.2);
        out
    }

    /// The body of [`Self::newton_matrix`].
    #[allow(clippy::too_many_arguments)]
    fn newton_matrix_factor<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S, t: f64, q: &[f64], v: &[f64], vdot: &[f64], lam: &[f64], r0: &[f64],
        phi0: &[f64], bp: f64, gp: f64, h: f64, f: &mut [f64],
    ) -> Result<(), MbdError> {
        let n = sys.n_v();
        let nc = sys.n_c();
        self.stats.jacobian_evaluations += 1;
        self.stats.factorizations += 1;
        let explicit = self.params.explicit_inverse;
        self.matrix.kkt.banded = self.params.banded_lu;
        self.matrix.h = h;
        self.matrix.id = self.stats.factorizations;
        self.matrix.v_ref = self
            .params
            .refactor_drift
            .and_then(|d| v.get(d.dof).copied())
            .unwrap_or(0.0);
        match self.params.jacobian {
            JacobianMode::Analytic => {
                // a constant mass is lent out of its cache for the factorisation (no copy)
                let m = match self.mass_cache.take() {
                    Some(m) if sys.mass_is_constant() => m,
                    _ => self.mass(sys, t, q)?,
                };
                let out = self.analytic_newton_matrix(sys, t, q, v, lam, bp, gp, &m, explicit);
                if sys.mass_is_constant() {
                    self.mass_cache = Some(m);
                }
                out
            }
            JacobianMode::FiniteDifference => {
                // column j: perturb the Newton unknown Δx_j by ε:
                //   q → q ⊕ ε e_j, v → v + γ' ε e_j, v̇ → v̇ + β' ε e_j
                let mut s = Mat::<f64>::zeros(n, n);
                let mut dmat = Mat::<f64>::zeros(nc, n);
                let mut qp = vec![0.0; q.len()];
                let mut vp = v.to_vec();
                let mut ap = vdot.to_vec();
                let mut rp = vec![0.0; n];
                let mut php = vec![0.0; nc];
                let mut e = vec![0.0; n];
                for j in 0..n {
                    let eps = 1e-7 * (1.0 + v[j].abs() / gp.max(1e-300)).min(1e3);
                    e[j] = eps;
                    sys.integrate_position(q, &e, &mut qp);
                    e[j] = 0.0;
                    vp[j] = v[j] + gp * eps;
                    ap[j] = vdot[j] + bp * eps;
                    self.residual(sys, t, &qp, &vp, &ap, lam, &mut rp, &mut php, f)?;
                    vp[j] = v[j];
                    ap[j] = vdot[j];
                    for i in 0..n {
                        s[(i, j)] = (rp[i] - r0[i]) / (eps * bp);
                    }
                    for i in 0..nc {
                        dmat[(i, j)] = (php[i] - phi0[i]) / eps;
                    }
                }
                let sm = SysMatrix::Dense(s);
                let dm = SysMatrix::Dense(dmat);
                self.matrix.factor(
                    &[(1.0, &sm)],
                    if nc > 0 { Some(&dm) } else { None },
                    t,
                    explicit,
                    self.worker.as_ref(),
                )
            }
        }
    }

    /// The analytic Newton matrix `M + γ'/β' C + 1/β' (K + K_c)` with the mass `m`, factored
    /// with the constraint Jacobian ([`Self::newton_matrix_factor`]).
    #[allow(clippy::too_many_arguments)]
    fn analytic_newton_matrix<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S, t: f64, q: &[f64], v: &[f64], lam: &[f64], bp: f64, gp: f64,
        m: &SysMatrix, explicit: bool,
    ) -> Result<(), MbdError> {
        let nc = sys.n_c();
        let d = if nc > 0 {
            Some(sys.constraint_jacobian(t, q)?)
        } else {
            None
        };
        let tangent = match sys.force_tangent(t, q, v, &mut self.ws)? {
            Some(tg) => (tg.stiffness, tg.damping),
            None => self.fd_force_tangent(sys, t, q, v)?,
        };
        let kc = if nc > 0 {
            sys.constraint_force_tangent(t, q, lam)?
        } else {
            None
        };
        let mut blocks = vec![(1.0, m), (gp / bp, &tangent.1), (1.0 / bp, &tangent.0)];
        if let Some(kc) = &kc {
            blocks.push((1.0 / bp, kc));
        }
        self.matrix
            .factor(&blocks, d.as_ref(), t, explicit, self.worker.as_ref())
    }

    /// Forward-difference tangent `K = −∂f/∂q` (through `⊕`), `C = −∂f/∂v` (dense).
    fn fd_force_tangent<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S, t: f64, q: &[f64], v: &[f64],
    ) -> Result<(SysMatrix, SysMatrix), MbdError> {
        let tan = crate::system::finite_difference_tangent(sys, t, q, v, &mut self.ws)?;
        self.stats.force_evaluations += 2 * sys.n_v() + 1;
        Ok((tan.stiffness, tan.damping))
    }
}

impl<S: SecondOrderSystem + ?Sized, C: StepCorrection<S>> Stepper<S> for AlphaStepper<C> {
    fn state(&self) -> &State {
        &self.state
    }

    fn stats(&self) -> &Stats {
        &self.stats
    }

    /// A step of `h` (default: the nominal step), subdivided after Newton failures
    /// ([`AlphaConfig::subdivisions`]); on a failure without subdivision the state is
    /// unchanged.
    fn step(&mut self, sys: &S, h: Option<f64>) -> Result<(), MbdError> {
        self.step_subdivided(sys, h.unwrap_or(self.params.h), self.params.subdivisions)
    }

    /// Nominal step (shortened to end on `t_stop`), halved after a Newton failure (up to
    /// `max_halvings` times) and doubled back after each accepted step.
    fn step_until(&mut self, sys: &S, t_stop: f64) -> Result<bool, MbdError> {
        let h0 = self.params.h;
        if self.state.t >= t_stop - 1e-12 * h0 {
            return Ok(false);
        }
        loop {
            let rem = t_stop - self.state.t;
            let h = self.h_cur;
            let (hs, t1) = if rem <= h * (1.0 + 1e-8) {
                (rem, t_stop)
            } else {
                (h, self.state.t + h)
            };
            match self.step_to(sys, hs, t1) {
                Ok(()) => {
                    if self.halvings > 0 {
                        self.halvings -= 1;
                        self.h_cur *= 2.0;
                    }
                    return Ok(true);
                }
                Err(MbdError::NoConvergence { .. }) if self.halvings < self.params.max_halvings => {
                    self.stats.rejected_steps += 1;
                    self.stats.halvings += 1;
                    self.halvings += 1;
                    self.h_cur *= 0.5;
                }
                Err(e) => return Err(e),
            }
        }
    }

    /// Every call starts from the nominal step.
    fn advance_to(
        &mut self, sys: &S, t_stop: f64, observer: &mut dyn super::Observer,
    ) -> Result<(), MbdError> {
        self.h_cur = self.params.h;
        self.halvings = 0;
        while Stepper::step_until(self, sys, t_stop)? {
            observer.observe(&self.state, &self.stats);
            if observer.stop_requested() {
                break;
            }
        }
        Ok(())
    }
}
