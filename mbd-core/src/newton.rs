//! The one Newton–Raphson solver of the workspace for nonlinear systems `R(x, μ) = 0`.
//!
//! Every static and quasi-static solve (multibody statics, ANCF statics with load increments,
//! unilateral contact by an active set, belt equilibria) implements [`NewtonProblem`] and calls
//! [`solve`]. One iteration at the load factor `μ` is
//!
//! ```text
//! R = R(x, μ)                         (NewtonProblem::linearize: residual and tangent J = ∂R/∂x)
//! J Δx = −R                           (NewtonProblem::solve: dense, sparse or KKT, any factorisation)
//! Δx ← Δx · min(1, s_max/‖Δx‖)        (damping, NewtonOptions::max_step)
//! Δx ← α Δx, α = 2⁻ᵏ                  (optional Armijo backtracking, LineSearch)
//! x ← x ⊕ Δx                          (NewtonProblem::update: + or a manifold retraction)
//! ```
//!
//! i.e. Newton–Raphson with an Armijo backtracking line search (Nocedal & Wright, *Numerical
//! Optimization*, 2nd ed., Alg. 3.1 with the merit `‖R‖` or a potential `Π` with `∇Π = R`),
//! load stepping `μ = 1/n, 2/n, …, 1` with step cutting on failure (Crisfield, *Non-linear
//! Finite Element Analysis of Solids and Structures* Vol. 1, §9.1), and an optional outer
//! loop in which the problem changes its active set after convergence ([`Settle`]).
//!
//! Modified Newton (a tangent factored once and reused, as in the corrector of an implicit
//! integrator) is a problem whose [`NewtonProblem::linearize`] factors only when it chooses to
//! and whose [`NewtonProblem::solve`] reuses the stored factorisation.
//!
//! The scratch vectors live in a [`NewtonWorkspace`] passed by the caller and reused between
//! iterations, increments and solves.

use thiserror::Error;

/// Result of [`NewtonProblem::settle`], called after Newton converged for an increment.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Settle {
    /// The solution is accepted (e.g. the active set is stable).
    Settled,
    /// The problem changed itself (e.g. activated or released contacts): iterate again at the
    /// same load factor from the current `x`.
    Changed,
}

/// A nonlinear system `R(x, μ) = 0` with a load factor `μ ∈ (0, 1]`: the extension point of
/// the Newton solver.
///
/// `x` has the length given to [`solve`]; the correction `Δx` has [`Self::tangent_dim`]
/// entries (it differs from `x` on a manifold, e.g. Euler parameters) and the residual
/// [`Self::residual_dim`] entries.
pub trait NewtonProblem {
    /// Error of the problem's own evaluations (model or factorisation failures).
    type Error;

    /// Length of the correction `Δx`.
    fn tangent_dim(&self) -> usize;

    /// Length of the residual `R` (default [`Self::tangent_dim`]).
    fn residual_dim(&self) -> usize {
        self.tangent_dim()
    }

    /// Evaluate `R(x, μ)` into `r` and prepare [`Self::solve`]: assemble (and possibly factor)
    /// the tangent `J = ∂R/∂x`, or keep an earlier factorisation (modified Newton).
    fn linearize(&mut self, x: &[f64], load: f64, r: &mut [f64]) -> Result<(), Self::Error>;

    /// Solve `J Δx = −R` with the tangent prepared by the last [`Self::linearize`]; `r` is the
    /// residual it returned.
    fn solve(&mut self, r: &[f64], dx: &mut [f64]) -> Result<(), Self::Error>;

    /// Evaluate `R(x, μ)` only (line-search trial points). The default calls
    /// [`Self::linearize`]; override it when the tangent is expensive.
    fn residual(&mut self, x: &[f64], load: f64, r: &mut [f64]) -> Result<(), Self::Error> {
        self.linearize(x, load, r)
    }

    /// `x_new = x ⊕ Δx` (default `x + Δx`; a problem on a manifold overrides it, and may
    /// reject a non-admissible `x_new` with an error).
    fn update(&mut self, x: &[f64], dx: &[f64], x_new: &mut [f64]) -> Result<(), Self::Error> {
        for ((n, a), d) in x_new.iter_mut().zip(x).zip(dx) {
            *n = a + d;
        }
        Ok(())
    }

    /// Norm of a correction, used for damping and the convergence test (default `‖Δx‖∞`).
    fn correction_norm(&self, dx: &[f64]) -> f64 {
        max_abs(dx)
    }

    /// Size of the unknowns for the relative correction test `‖Δx‖ ≤ tol (1 + scale)`
    /// (default `‖x_old‖∞`, the iterate before the update).
    fn scale(&self, x_old: &[f64], _x_new: &[f64]) -> f64 {
        max_abs(x_old)
    }

    /// Norm of a residual, reported and used by the `‖R‖` merit (default Euclidean).
    fn residual_norm(&self, r: &[f64]) -> f64 {
        r.iter().map(|v| v * v).sum::<f64>().sqrt()
    }

    /// A potential `Π(x, μ)` with `∇Π = R`, if the problem is conservative: the line search
    /// then decreases `Π` (slope `Rᵀ Δx`) instead of `‖R‖`. Default: none.
    fn potential(&mut self, _x: &[f64], _load: f64) -> Result<Option<f64>, Self::Error> {
        Ok(None)
    }

    /// Largest fraction `α ∈ (0, 1]` of the correction `dx` from `x` that the problem admits
    /// in this iteration (default `1`; called after [`Self::solve`], before the line search).
    /// The correction is scaled by `α` like a [`NewtonOptions::max_step`] damping, so an
    /// iteration with `α < 1` never counts as converged. E.g. a step limit that keeps a
    /// regularised friction law's contacts from crossing its steep band in one iteration.
    fn step_limit(&mut self, _x: &[f64], _dx: &[f64]) -> Result<f64, Self::Error> {
        Ok(1.0)
    }

    /// Additional convergence condition checked after the correction test passed (e.g. on
    /// multipliers with their own tolerance). Default: none.
    fn converged(&self, _x_old: &[f64], _x_new: &[f64], _dx: &[f64]) -> bool {
        true
    }

    /// Called after Newton converged at load factor `load`; an active-set problem updates its
    /// set here (and may modify `x`, e.g. zero released multipliers). Default: settled.
    fn settle(&mut self, _x: &mut [f64], _load: f64) -> Result<Settle, Self::Error> {
        Ok(Settle::Settled)
    }
}

/// Convergence test of one iteration: converged when the applied correction satisfies
/// `‖Δx‖ ≤ correction · (1 + ‖x‖)` (relative), `‖Δx‖ ≤ correction + per_scale · ‖x‖` (mixed,
/// e.g. `atol + rtol ‖x‖`) or `‖Δx‖ ≤ correction` (absolute), or when the residual at the start
/// of the iteration satisfies `‖R‖ < residual` from iteration `residual_from_iteration` on.
/// `‖x‖` is [`NewtonProblem::scale`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerances {
    /// Tolerance on the correction \[units of x\] or \[-\] when relative.
    pub correction: f64,
    /// Scale the correction tolerance by `1 + ‖x‖` ([`NewtonProblem::scale`]).
    pub relative: bool,
    /// Relative part of the mixed test `‖Δx‖ ≤ correction + per_scale · ‖x‖` \[-\]; used when
    /// `relative` is false, `0` gives the absolute test.
    pub per_scale: f64,
    /// Residual tolerance \[units of R\]; `0` disables the residual test.
    pub residual: f64,
    /// First iteration (1-based) at which the residual test applies.
    pub residual_from_iteration: usize,
}

impl Tolerances {
    /// The bound of the correction test at the scale `‖x‖` ([`NewtonProblem::scale`]):
    /// `correction (1 + ‖x‖)` (relative), `correction + per_scale ‖x‖` (mixed) or
    /// `correction`.
    pub fn threshold(&self, scale: f64) -> f64 {
        if self.relative {
            self.correction * (1.0 + scale)
        } else if self.per_scale != 0.0 {
            self.correction + self.per_scale * scale
        } else {
            self.correction
        }
    }

    /// `‖Δx‖ ≤ tol`.
    pub fn absolute(tol: f64) -> Self {
        Self {
            correction: tol,
            relative: false,
            per_scale: 0.0,
            residual: 0.0,
            residual_from_iteration: 1,
        }
    }

    /// `‖Δx‖ ≤ tol (1 + ‖x‖)`.
    pub fn relative(tol: f64) -> Self {
        Self {
            relative: true,
            ..Self::absolute(tol)
        }
    }

    /// `‖Δx‖ ≤ atol + rtol ‖x‖`.
    pub fn mixed(atol: f64, rtol: f64) -> Self {
        Self {
            per_scale: rtol,
            ..Self::absolute(atol)
        }
    }

    /// Also accept `‖R‖ < tol` (residual before the correction).
    pub fn or_residual(self, tol: f64) -> Self {
        Self {
            residual: tol,
            ..self
        }
    }
}

/// What the line search does when no trial step is accepted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fallback {
    /// Take the full (undamped) step: Newton may still converge from there.
    FullStep,
    /// Keep the last, smallest trial step.
    LastTrial,
}

/// Armijo backtracking (Nocedal & Wright Alg. 3.1 with contraction 1/2): trial steps
/// `α = 1, 1/2, 1/4, …` (at most `max_trials`) until the merit `φ` satisfies
/// `φ(α) ≤ φ(0) + c₁ α φ'(0) + slack |φ(0)|` or `φ(α) < accept_below`.
///
/// The merit is the potential of [`NewtonProblem::potential`] with `φ'(0) = RᵀΔx` when the
/// problem has one, else `‖R‖` with `φ'(0) = −‖R‖` (so the test reads
/// `‖R(α)‖ ≤ (1 − c₁ α) ‖R(0)‖`). Non-finite trial merits are rejected.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineSearch {
    /// Sufficient-decrease constant `c₁` \[-\].
    pub armijo: f64,
    /// Relative slack on the merit (round-off allowance) \[-\].
    pub slack: f64,
    /// A trial merit below this value is accepted outright (`‖R‖` merit only).
    pub accept_below: f64,
    /// Largest number of trial steps (≥ 1).
    pub max_trials: usize,
    /// Step taken when no trial is accepted.
    pub fallback: Fallback,
}

impl Default for LineSearch {
    fn default() -> Self {
        Self {
            armijo: 1e-4,
            slack: 0.0,
            accept_below: 0.0,
            max_trials: 13,
            fallback: Fallback::FullStep,
        }
    }
}

/// Load stepping: `increments` equal steps of the load factor to 1; a failed increment (no
/// convergence or a non-finite iterate) is halved up to `max_cuts` times in total, restarting
/// from the last converged `x`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LoadStepping {
    /// Number of equal increments (≥ 1).
    pub increments: usize,
    /// Largest number of step cuts.
    pub max_cuts: usize,
}

impl Default for LoadStepping {
    fn default() -> Self {
        Self {
            increments: 1,
            max_cuts: 0,
        }
    }
}

/// Treatment of an iteration that does not contract. An iteration stalls when its Newton
/// correction (before damping or line search) exceeds `ratio` times the previous one. Newton on
/// a piecewise-smooth residual (the kink of a saturating friction or contact law) may cycle
/// between the linearizations of two pieces with corrections of constant size and never
/// converge. With `backtrack`, the iterations after the first stall use the Armijo line
/// search ([`NewtonOptions::line_search`], or [`LineSearch::default`] when that is `None`),
/// which breaks such cycles; after `iterations` consecutive stalls [`solve`] stops with
/// [`NewtonError::NoConvergence`] instead of running to `max_iterations`, so that the caller
/// (e.g. a time stepper that halves the step) can react at once.
#[derive(
    Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields)]
pub struct Stall {
    /// Contraction below which an iteration counts as progress \[-\] (e.g. 0.9).
    pub ratio: f64,
    /// Consecutive stalled iterations that end the iteration (≥ 1).
    pub iterations: usize,
    /// Switch the line search on after the first stall.
    pub backtrack: bool,
}

/// Options of [`solve`]. The default is plain full-step Newton, one increment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonOptions {
    /// Iterations per increment (per active-set pass).
    pub max_iterations: usize,
    /// Convergence test.
    pub tolerances: Tolerances,
    /// Largest correction `‖Δx‖` per iteration (damped Newton); a damped iteration never
    /// counts as converged \[units of x\].
    pub max_step: f64,
    /// Backtracking line search (`None`: full steps). A correction that passes the
    /// convergence test in full is taken without a trial (the iteration ends with it).
    pub line_search: Option<LineSearch>,
    /// Load increments and step cutting.
    pub load: LoadStepping,
    /// Largest number of Newton passes per increment when [`NewtonProblem::settle`] reports
    /// changes.
    pub max_passes: usize,
    /// Early exit of a non-contracting iteration (`None`: run to `max_iterations`).
    pub stall: Option<Stall>,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        Self {
            max_iterations: 50,
            tolerances: Tolerances::absolute(1e-10),
            max_step: f64::INFINITY,
            line_search: None,
            load: LoadStepping::default(),
            max_passes: 100,
            stall: None,
        }
    }
}

/// Convergence record of one load increment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IncrementReport {
    /// Load factor reached \[-\].
    pub load: f64,
    /// Newton iterations (all passes).
    pub iterations: usize,
    /// Newton passes ([`Settle::Changed`] adds one).
    pub passes: usize,
}

/// Result of [`solve`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct NewtonReport {
    /// One record per converged increment, in order.
    pub increments: Vec<IncrementReport>,
    /// Applied correction norm of the last iteration.
    pub correction: f64,
    /// Residual norm at the start of the last iteration.
    pub residual: f64,
    /// Step cuts performed.
    pub cuts: usize,
    /// Whether the last increment converged (false only inside [`NewtonError::NoConvergence`]).
    pub converged: bool,
}

impl NewtonReport {
    /// Total Newton iterations.
    pub fn iterations(&self) -> usize {
        self.increments.iter().map(|i| i.iterations).sum()
    }
}

/// Failure of [`solve`].
#[derive(Debug, Clone, PartialEq, Error)]
pub enum NewtonError<E> {
    /// The problem's own evaluation failed.
    #[error("{0}")]
    Problem(E),
    /// An option is out of range.
    #[error("invalid Newton option {field}: {reason}")]
    InvalidOption {
        /// Option name.
        field: &'static str,
        /// Why it is rejected.
        reason: String,
    },
    /// The residual or the correction is NaN or infinite.
    #[error("non-finite Newton {what} at load factor {load} (iteration {iteration})")]
    NonFinite {
        /// `"residual"` or `"correction"`.
        what: &'static str,
        /// Load factor \[-\].
        load: f64,
        /// Iteration (1-based) within the pass.
        iteration: usize,
    },
    /// `max_iterations` reached without passing the convergence test.
    #[error(
        "Newton did not converge at load factor {load} after {iterations} iterations (residual {residual:e}, correction {correction:e})"
    )]
    NoConvergence {
        /// Load factor \[-\].
        load: f64,
        /// Iterations of the failed pass.
        iterations: usize,
        /// Residual norm at the start of the last iteration.
        residual: f64,
        /// Last applied correction norm.
        correction: f64,
    },
    /// [`NewtonProblem::settle`] still reported changes after `max_passes` passes.
    #[error("active set did not settle at load factor {load} after {passes} passes")]
    NotSettled {
        /// Load factor \[-\].
        load: f64,
        /// Passes performed.
        passes: usize,
    },
}

impl NewtonError<crate::MbdError> {
    /// The multibody error of a failure at time `t` \[s\].
    pub fn into_mbd(self, t: f64) -> crate::MbdError {
        use crate::MbdError;
        match self {
            NewtonError::Problem(e) => e,
            NewtonError::InvalidOption { field, reason } => MbdError::InvalidInput {
                item: format!("Newton option {field}"),
                reason,
            },
            NewtonError::NonFinite { what, .. } => MbdError::NonFinite {
                what: format!("Newton {what}"),
                t,
            },
            NewtonError::NoConvergence {
                iterations,
                residual,
                ..
            } => MbdError::NoConvergence {
                t,
                iterations,
                residual,
            },
            NewtonError::NotSettled { passes, .. } => MbdError::NoConvergence {
                t,
                iterations: passes,
                residual: f64::NAN,
            },
        }
    }
}

/// Scratch vectors of [`solve`], reused between iterations and calls.
#[derive(Debug, Clone, Default)]
pub struct NewtonWorkspace {
    r: Vec<f64>,
    dx: Vec<f64>,
    step: Vec<f64>,
    trial: Vec<f64>,
    r_trial: Vec<f64>,
    start: Vec<f64>,
}

impl NewtonWorkspace {
    /// An empty workspace (sized on first use).
    pub fn new() -> Self {
        Self::default()
    }

    fn resize(&mut self, nx: usize, ndx: usize, nr: usize) {
        self.r.resize(nr, 0.0);
        self.dx.resize(ndx, 0.0);
        self.step.resize(ndx, 0.0);
        self.trial.resize(nx, 0.0);
        self.r_trial.resize(nr, 0.0);
        self.start.resize(nx, 0.0);
    }
}

/// `max |vᵢ|` (0 for an empty slice).
pub fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, x| a.max(x.abs()))
}

/// Solve `R(x, μ) = 0` for the load factors of `opts.load`, starting from and overwriting `x`.
/// See the module documentation for the iteration.
pub fn solve<P: NewtonProblem + ?Sized>(
    problem: &mut P, x: &mut [f64], opts: &NewtonOptions, ws: &mut NewtonWorkspace,
) -> Result<NewtonReport, NewtonError<P::Error>> {
    let n = opts.load.increments;
    if n == 0 {
        return Err(NewtonError::InvalidOption {
            field: "load.increments",
            reason: "must be ≥ 1".into(),
        });
    }
    if let Some(st) = &opts.stall
        && (st.iterations == 0 || st.ratio.is_nan() || st.ratio <= 0.0)
    {
        return Err(NewtonError::InvalidOption {
            field: "stall",
            reason: format!("needs iterations ≥ 1 and ratio > 0, got {st:?}"),
        });
    }
    if opts.max_step.is_nan() || opts.max_step <= 0.0 {
        return Err(NewtonError::InvalidOption {
            field: "max_step",
            reason: format!("must be > 0, got {}", opts.max_step),
        });
    }
    if let Some(ls) = &opts.line_search
        && ls.max_trials == 0
    {
        return Err(NewtonError::InvalidOption {
            field: "line_search.max_trials",
            reason: "must be ≥ 1".into(),
        });
    }
    ws.resize(x.len(), problem.tangent_dim(), problem.residual_dim());
    let mut report = NewtonReport::default();
    // load factor num/den: k/n without cuts, a finer grid after each halving
    let (mut num, mut den) = (0usize, n);
    while num < den {
        let load = (num + 1) as f64 / den as f64;
        if opts.load.max_cuts > report.cuts {
            ws.start.copy_from_slice(x);
        }
        match increment(problem, x, load, opts, ws, &mut report) {
            Ok(inc) => {
                report.increments.push(inc);
                num += 1;
            }
            Err(NewtonError::NoConvergence { .. } | NewtonError::NonFinite { .. })
                if report.cuts < opts.load.max_cuts =>
            {
                x.copy_from_slice(&ws.start);
                report.cuts += 1;
                num *= 2;
                den *= 2;
            }
            Err(e) => return Err(e),
        }
    }
    report.converged = true;
    Ok(report)
}

/// Newton passes at one load factor until converged and settled.
fn increment<P: NewtonProblem + ?Sized>(
    problem: &mut P, x: &mut [f64], load: f64, opts: &NewtonOptions, ws: &mut NewtonWorkspace,
    report: &mut NewtonReport,
) -> Result<IncrementReport, NewtonError<P::Error>> {
    let tol = &opts.tolerances;
    let mut inc = IncrementReport {
        load,
        iterations: 0,
        passes: 0,
    };
    loop {
        inc.passes += 1;
        let mut converged = false;
        let mut it = 0;
        let (mut res, mut corr) = (f64::INFINITY, f64::INFINITY);
        let mut stalled = 0;
        let mut prev_full = f64::INFINITY;
        let mut backtracking = false;
        while it < opts.max_iterations {
            it += 1;
            inc.iterations += 1;
            problem
                .linearize(x, load, &mut ws.r)
                .map_err(NewtonError::Problem)?;
            res = problem.residual_norm(&ws.r);
            if !res.is_finite() {
                return Err(NewtonError::NonFinite {
                    what: "residual",
                    load,
                    iteration: it,
                });
            }
            problem
                .solve(&ws.r, &mut ws.dx)
                .map_err(NewtonError::Problem)?;
            let norm = problem.correction_norm(&ws.dx);
            if let Some(st) = &opts.stall {
                if it > 1 && norm > st.ratio * prev_full {
                    stalled += 1;
                    backtracking |= st.backtrack;
                } else {
                    stalled = 0;
                }
            }
            prev_full = norm;
            let mut damp = if norm > opts.max_step {
                opts.max_step / norm
            } else {
                1.0
            };
            let limit = problem
                .step_limit(x, &ws.dx)
                .map_err(NewtonError::Problem)?;
            if limit < 1.0 && limit > 0.0 {
                damp = damp.min(limit);
            }
            for d in ws.dx.iter_mut() {
                *d *= damp;
            }
            let default_ls = LineSearch::default();
            let ls = opts
                .line_search
                .as_ref()
                .or(backtracking.then_some(&default_ls));
            // A full correction that already passes the correction test ends the iteration
            // whatever its merit: it is taken without a line-search trial, whose residual the
            // finished iteration would not use (one evaluation saved per solve).
            let converged_in_full = ls.is_some() && damp == 1.0 && {
                problem
                    .update(x, &ws.dx, &mut ws.trial)
                    .map_err(NewtonError::Problem)?;
                problem.correction_norm(&ws.dx) <= tol.threshold(problem.scale(x, &ws.trial))
                    && problem.converged(x, &ws.trial, &ws.dx)
            };
            let full = match ls {
                Some(_) if converged_in_full => {
                    ws.step.copy_from_slice(&ws.dx);
                    true
                }
                Some(ls) => line_search(problem, x, load, res, ls, ws)?,
                None => {
                    ws.step.copy_from_slice(&ws.dx);
                    problem
                        .update(x, &ws.step, &mut ws.trial)
                        .map_err(NewtonError::Problem)?;
                    true
                }
            };
            corr = problem.correction_norm(&ws.step);
            if !corr.is_finite() {
                return Err(NewtonError::NonFinite {
                    what: "correction",
                    load,
                    iteration: it,
                });
            }
            let threshold = tol.threshold(problem.scale(x, &ws.trial));
            // a backtracked step (after a stall) is no evidence of convergence
            let test = damp == 1.0
                && (full || !backtracking)
                && (corr <= threshold || (it >= tol.residual_from_iteration && res < tol.residual))
                && problem.converged(x, &ws.trial, &ws.step);
            x.copy_from_slice(&ws.trial);
            if test {
                converged = true;
                break;
            }
            if opts.stall.is_some_and(|st| stalled >= st.iterations) {
                break;
            }
        }
        report.residual = res;
        report.correction = corr;
        if !converged {
            return Err(NewtonError::NoConvergence {
                load,
                iterations: it,
                residual: res,
                correction: corr,
            });
        }
        match problem.settle(x, load).map_err(NewtonError::Problem)? {
            Settle::Settled => return Ok(inc),
            Settle::Changed if inc.passes >= opts.max_passes => {
                return Err(NewtonError::NotSettled {
                    load,
                    passes: inc.passes,
                });
            }
            Settle::Changed => {}
        }
    }
}

/// Armijo backtracking along `ws.dx` from `x`; leaves the accepted step in `ws.step` and the
/// new iterate in `ws.trial`. Returns whether the full step was taken.
fn line_search<P: NewtonProblem + ?Sized>(
    problem: &mut P, x: &[f64], load: f64, res: f64, ls: &LineSearch, ws: &mut NewtonWorkspace,
) -> Result<bool, NewtonError<P::Error>> {
    let err = NewtonError::Problem;
    let potential = problem.potential(x, load).map_err(err)?;
    // φ(0) and the sufficient-decrease bound at α
    let slope = ws.r.iter().zip(&ws.dx).map(|(r, d)| r * d).sum::<f64>();
    let mut alpha = 1.0;
    for trial in 0..ls.max_trials {
        if trial > 0 {
            alpha *= 0.5;
        }
        for (s, d) in ws.step.iter_mut().zip(&ws.dx) {
            *s = alpha * d;
        }
        problem.update(x, &ws.step, &mut ws.trial).map_err(err)?;
        let accept = match potential {
            Some(pi0) => {
                let s0 = -slope;
                let pi = problem
                    .potential(&ws.trial, load)
                    .map_err(err)?
                    .unwrap_or(f64::NAN);
                pi.is_finite() && pi <= pi0 - ls.armijo * alpha * s0 + ls.slack * pi0.abs()
            }
            None => {
                problem
                    .residual(&ws.trial, load, &mut ws.r_trial)
                    .map_err(err)?;
                let r_new = problem.residual_norm(&ws.r_trial);
                r_new.is_finite()
                    && (r_new <= (1.0 - ls.armijo * alpha) * res + ls.slack * res
                        || r_new < ls.accept_below)
            }
        };
        if accept {
            return Ok(trial == 0);
        }
    }
    if ls.fallback == Fallback::FullStep {
        ws.step.copy_from_slice(&ws.dx);
        problem.update(x, &ws.step, &mut ws.trial).map_err(err)?;
        return Ok(true);
    }
    Ok(false)
}

#[cfg(test)]
mod tests;
