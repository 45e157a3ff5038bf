//! Time integration of a belt drive with mbd-core's integrators: implicit generalized-α with
//! the analytic Jacobian (the production path) or explicit RK4 at a fixed step (the reference
//! for the cost comparison of the benchmark).

use super::model::BeltDrive;
use crate::error::{AncfError, invalid};
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha, JacobianMode, NewtonUpdate, Rk4};
use mbd_core::integrators::{Solution, State};
use mbd_core::newton::Stall;
use serde::{Deserialize, Serialize};

/// Which integrator runs the drive.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum IntegratorKind {
    /// Implicit generalized-α (Chung–Hulbert) with the analytic tangent.
    GeneralizedAlpha,
    /// Explicit fixed-step RK4 (needs a step below the stability limit, ~1e-6 s for Table 3.1).
    Rk4,
}

/// Integration options.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SimulationConfig {
    /// Integrator.
    pub integrator: IntegratorKind,
    /// Step size \[s\] (default 2.5e-4 s, four steps per 1 ms output interval: with the
    /// default ρ∞ and tolerance the driven speed of Table 3.1 is then within 2.7e-3 rad/s
    /// (E = 1e8 Pa) and 5.1e-3 rad/s (E = 1e9 Pa) of the h = 2.5e-5 s solution, see
    /// BENCHMARKS.md).
    pub h: f64,
    /// Generalized-α spectral radius at infinite frequency ρ∞ \[-\] (default 0.8: at h = 2.5e-4 s
    /// and E = 1e9 Pa the driven speed is 5.1e-3 rad/s off the h = 2.5e-5 s solution,
    /// against 7.8e-3 rad/s with the stronger numerical damping of ρ∞ = 0.6; ρ∞ = 1 is not
    /// more accurate and needs 1.6× the Newton iterations).
    pub rho_inf: f64,
    /// Newton tolerance on the position correction \[m\] (default 5e-6 m: below the ~10⁻⁵ m
    /// contact penetrations and of the order of the step's own discretisation error; the
    /// driven speed of Table 3.1 moves by less than 1e-4 rad/s against 1e-6 m, while twice the
    /// tolerance, 1e-5 m, lets Newton settle on another friction branch in the ramp at
    /// E = 1e8 Pa, 1.6e-2 rad/s off; loose enough that Newton does not cycle between the
    /// branches of the piecewise-linear friction law).
    pub newton_atol: f64,
    /// Newton tolerance on the velocity correction \[m/s\] (mbd-core
    /// `AlphaConfig::newton_vtol`): with it a step converges only when its last correction also
    /// moves the velocities by less than this. `None` (the default): [`Self::newton_atol`]
    /// alone, which lets the last correction move velocities by `γ/(β h)` times 5 µm, 40 mm/s
    /// at the default step and ρ∞: of the order of the transition width of Ribaric's
    /// κ = 40 s/m law (25 mm/s), but 80–130 times that of the layouts' default `tanh_slip` law
    /// at 0.3–0.5 mm/s. Set it from the friction law with [`Self::resolving`].
    pub newton_vtol: Option<f64>,
    /// Maximum Newton iterations per step.
    pub max_newton_iterations: usize,
    /// When the Newton matrix is re-factored: `every_iteration` (full Newton), `every_step`
    /// or `frozen` (kept across steps, the default: a chord iteration whose matrix is renewed
    /// by `refactor_contraction`).
    pub newton_update: NewtonUpdate,
    /// `every_step` and `frozen`: re-factor at the current iterate when a correction exceeds
    /// this fraction of the previous one \[-\] (mbd-core `AlphaConfig::refactor_contraction`).
    /// Default 0.8: on the Table 3.1 drive after the speed ramp (E = 1e9 Pa, h = 2.5e-4 s)
    /// 0.6, 0.7, 0.8, 0.85, 0.9 gave 0.58, 0.48, 0.35, 0.30, 0.27 factorisations and 4.0, 4.3,
    /// 4.7, 5.1, 5.5 Newton iterations per step, the least CPU time at 0.8–0.85 (at E = 1e8 Pa
    /// flat from 0.6 to 0.8, rising beyond; BENCHMARKS.md, "Against Exudyn").
    pub refactor_contraction: f64,
    /// Armijo backtracking on the residual norm in every Newton iteration (mbd-core
    /// `AlphaConfig::newton_line_search`): without it Newton cycles at the kink of the
    /// creep-rate friction law (Kerkkänen Fig. 3.3) in a few per cent of the steps, which are
    /// then halved.
    pub line_search: bool,
    /// Offer each step's Newton iteration the belt convected along itself
    /// ([`BeltDrive::convected_increment`]) as its starting iterate when its residual is
    /// smaller than the constant-acceleration predictor's (mbd-core
    /// `AlphaConfig::model_predictor`). A node entering a wrap at belt speed `v` changes its
    /// acceleration by `v²/R` within the step, which the constant-acceleration predictor
    /// misses by about `γ h v²/R` in velocity (≈ 3 m/s on the 28 mm alternator at 3500 rpm of
    /// the default FEAD drive, against the friction law's 25 mm/s, `1/κ`). Default `false`:
    /// on the default ANCF FEAD sweep (BENCHMARKS.md, issue 37 item 4) it cut the
    /// factorisations at 2500 and 3500 rpm by 28 % and 52 % but doubled and tripled them at
    /// 1500 and 800 rpm (a smaller starting residual is not a shorter Newton iteration
    /// there), 25 % fewer in all, for no saving in CPU time. Together with
    /// [`Self::max_correction`] it pays: the FEAD study sets both (0.81 of the sweep's CPU on
    /// the idle machine).
    pub convected_predictor: bool,
    /// Largest Newton correction per iteration \[m; the slope coordinates' correction in the
    /// same number\] (mbd-core `AlphaConfig::newton_max_step`, a trust region; `None`:
    /// unlimited, the default). Where the belt carries contact points into and out of the
    /// wraps within a step, the Newton matrix at the predictor can miss the contact and
    /// friction forces by orders of magnitude: the first corrections of the default FEAD
    /// drive's ANCF belt at 3500 rpm reached 2–20 cm in steps that move the belt 7 mm, and the
    /// line search spent most of the step's 25 iterations reining them in (BENCHMARKS.md,
    /// issue 37 item 4). The FEAD study sets 1 mm.
    pub max_correction: Option<f64>,
    /// Scale every Newton correction by the transition-aware limit of the contact points'
    /// slip velocities ([`BeltDrive::transition_limit`], Castro et al. 2019; mbd-core
    /// `AlphaConfig::model_correction_limit`): no point crosses the friction law's steep band
    /// in one iteration. Only laws with a band (tanh) are limited. With the limit the stall
    /// detection is off: while the limit holds the full corrections need not contract (the
    /// iterate moves by a fraction of each), which the stall test reads as a stall and halves
    /// the step. Default `false`; the FEAD study sets it (BENCHMARKS.md, issue 37 item 4: on
    /// the 3500 rpm point from rest 11.2 Newton iterations and 5.8 factorisations a step
    /// against 20.5 and 11.0 with the 1 mm trust region, 2 rejected steps against 2930).
    pub correction_limit: bool,
}

impl Default for SimulationConfig {
    fn default() -> Self {
        Self {
            integrator: IntegratorKind::GeneralizedAlpha,
            h: 2.5e-4,
            rho_inf: 0.8,
            newton_atol: 5e-6,
            newton_vtol: None,
            max_newton_iterations: 25,
            newton_update: NewtonUpdate::Frozen,
            refactor_contraction: 0.8,
            line_search: true,
            convected_predictor: false,
            max_correction: None,
            correction_limit: false,
        }
    }
}

/// Smallest spectral radius at infinity `ρ∞` of the ANCF belt drive's generalized-α
/// (Chung & Hulbert 1993) accepted from input \[-\].
pub const RHO_INF_MIN: f64 = 0.1;

/// The ANCF belt's Newton velocity tolerance per transition width of its friction law \[-\]
/// ([`SimulationConfig::resolving`]): 4. Measured on the three-pulley example without its
/// friction table at 1500 rpm (`tanh_slip`, BENCHMARKS.md, issue 34 item 2), torque / power
/// residual: at 0.5 mm/s the 5 µm position test alone (velocity corrections up to 40 mm/s, 80
/// widths) 0.63 / −0.05 %, 1, 4 widths 0.04 / 0.43 % and 0.02 / 0.39 %; at 0.3 mm/s the
/// position test alone +3.06 / −3.11 %, position tests of 0.5 and 0.1 µm (13 and 2.6 widths at
/// the 0.25 ms step) and 1 width 0.02–0.03 / 0.37–0.47 %. The speed losses move by under 0.5 %.
/// Four widths cost 1.24 times the position test's CPU there, one width 1.38 times.
pub const VTOL_PER_TRANSITION_WIDTH: f64 = 4.0;

impl SimulationConfig {
    /// These settings with [`Self::newton_vtol`] at [`VTOL_PER_TRANSITION_WIDTH`] times the
    /// friction law's transition width `width` \[m/s\]
    /// (`contact::friction::FrictionLaw::transition_width`; `None`, a law without a steep band:
    /// unchanged). Where the position test is the tighter one (mbd-core
    /// `AlphaConfig::newton_atol_at`) it stays in force.
    pub fn resolving(self, width: Option<f64>) -> Self {
        match width.filter(|w| w.is_finite() && *w > 0.0) {
            Some(w) => Self {
                newton_vtol: Some(VTOL_PER_TRANSITION_WIDTH * w),
                ..self
            },
            None => self,
        }
    }

    /// Check the parameters; the error names the field.
    pub fn validate(&self) -> Result<(), AncfError> {
        if !(self.h.is_finite() && self.h > 0.0) {
            return Err(invalid(
                "integrator.h",
                format!("must be > 0 s, got {}", self.h),
            ));
        }
        // ρ∞ → 0 is the fully annihilating end of Chung–Hulbert (α_m → −1); issue 35 found the
        // ANCF run ending in NaN there, so input is held to [RHO_INF_MIN, 1] (Kerkkänen uses 0.8)
        if !(RHO_INF_MIN..=1.0).contains(&self.rho_inf) {
            return Err(invalid(
                "integrator.rho_inf",
                format!(
                    "must lie in [{RHO_INF_MIN}, 1], got {}",
                    mbd_core::validate::check::show(self.rho_inf)
                ),
            ));
        }
        if !(self.newton_atol.is_finite() && self.newton_atol > 0.0) {
            return Err(invalid(
                "integrator.newton_atol",
                format!("must be > 0, got {}", self.newton_atol),
            ));
        }
        if let Some(v) = self.newton_vtol
            && !(v.is_finite() && v > 0.0)
        {
            return Err(invalid(
                "integrator.newton_vtol",
                format!("must be > 0 m/s, got {v}"),
            ));
        }
        if self.max_newton_iterations == 0 {
            return Err(invalid("integrator.max_newton_iterations", "must be ≥ 1"));
        }
        if let Some(m) = self.max_correction
            && !(m.is_finite() && m > 0.0)
        {
            return Err(invalid(
                "integrator.max_correction",
                format!("must be > 0 m, got {m}"),
            ));
        }
        if !(self.refactor_contraction > 0.0 && self.refactor_contraction < 1.0) {
            return Err(invalid(
                "integrator.refactor_contraction",
                format!("must lie in (0, 1), got {}", self.refactor_contraction),
            ));
        }
        Ok(())
    }

    /// The generalized-α parameters: analytic Jacobian, the configured Newton-matrix policy,
    /// line search, and an early exit after three corrections in a row that do not contract
    /// by 10 % (the step is then halved instead of iterating to `max_newton_iterations`;
    /// not with [`Self::correction_limit`], which it turns on).
    pub fn alpha_params(&self) -> AlphaConfig {
        AlphaConfig {
            rho_inf: self.rho_inf,
            h: self.h,
            newton_atol: self.newton_atol,
            newton_rtol: 1e-8,
            newton_vtol: self.newton_vtol,
            max_newton_iterations: self.max_newton_iterations,
            jacobian: JacobianMode::Analytic,
            update: self.newton_update,
            refactor_contraction: Some(self.refactor_contraction),
            newton_line_search: self.line_search,
            newton_stall: (!self.correction_limit).then_some(Stall {
                ratio: 0.9,
                iterations: 3,
                backtrack: false,
            }),
            max_halvings: 10,
            project_velocities: false,
            banded_lu: true,
            model_predictor: self.convected_predictor,
            newton_max_step: self.max_correction,
            model_correction_limit: self.correction_limit,
            ..AlphaConfig::default()
        }
    }
}

/// Integrate `drive` from rest at `q0` (t = 0) to `t_end` \[s\]; `observer` sees every accepted
/// step.
pub fn simulate(
    drive: &BeltDrive, q0: &[f64], t_end: f64, opts: &SimulationConfig,
    observer: impl FnMut(&State),
) -> Result<Solution, AncfError> {
    opts.validate()?;
    if !(t_end.is_finite() && t_end >= 0.0) {
        return Err(invalid("t_end", format!("must be ≥ 0 s, got {t_end}")));
    }
    let state = State::new(0.0, q0.to_vec(), vec![0.0; q0.len()]);
    let sol = match opts.integrator {
        IntegratorKind::GeneralizedAlpha => {
            GeneralizedAlpha::new(opts.alpha_params()).integrate(drive, state, t_end, observer)
        }
        IntegratorKind::Rk4 => Rk4::new(opts.h).integrate(drive, state, t_end, observer),
    }?;
    Ok(sol)
}

/// The explicit RK4 step limit of a belt-drive state, from the eigenvalues of the linearised
/// first-order system.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ExplicitStepLimit {
    /// Largest step \[s\] for which `|R(hλ)| ≤ 1` for every eigenvalue `λ` with `Re λ ≤ 0`,
    /// `R(z) = 1 + z + z²/2 + z³/6 + z⁴/24` the RK4 amplification factor.
    pub h_max: f64,
    /// The eigenvalue that sets the limit \[1/s\].
    pub limiting: [f64; 2],
    /// Largest `|Im λ|`, the highest (damped) eigenfrequency \[rad/s\].
    pub omega_max: f64,
    /// Most negative `Re λ` \[1/s\] (e.g. the creep-rate friction's `ν_s/ρA`).
    pub decay_max: f64,
    /// `2√2/ω_max` \[s\]: the RK4 limit of the undamped highest mode (imaginary-axis limit).
    pub h_imaginary: f64,
    /// `2.785/|Re λ|_max` \[s\]: the RK4 limit of the fastest decay (real-axis limit).
    pub h_real: f64,
}

/// RK4 amplification factor `|R(z)|`, `R(z) = Σ_{k≤4} z^k/k!`.
fn rk4_amplification(re: f64, im: f64) -> f64 {
    // Horner in complex arithmetic: R = 1 + z(1 + z/2(1 + z/3(1 + z/4)))
    let mul = |a: (f64, f64), b: (f64, f64)| (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0);
    let mut r = (1.0, 0.0);
    for k in [4.0, 3.0, 2.0, 1.0] {
        let zr = mul((re / k, im / k), r);
        r = (1.0 + zr.0, zr.1);
    }
    r.0.hypot(r.1)
}

/// Largest `h` with `|R(hλ)| ≤ 1` along the ray of `λ` (`Re λ ≤ 0`, `λ ≠ 0`).
fn rk4_ray_limit(re: f64, im: f64) -> f64 {
    let m = re.hypot(im);
    // RK4's stability region lies within |z| < 3: scan, then bisect the first exit
    let n = 600;
    let mut lo = 0.0;
    let mut hi = f64::NAN;
    for k in 1..=n {
        let h = 3.0 * k as f64 / (n as f64 * m);
        if rk4_amplification(h * re, h * im) > 1.0 + 1e-12 {
            hi = h;
            break;
        }
        lo = h;
    }
    if hi.is_nan() {
        return f64::INFINITY;
    }
    mbd_core::roots::bisect(
        lo,
        hi,
        |h| rk4_amplification(h * re, h * im) > 1.0 + 1e-12,
        mbd_core::roots::Stop::iterations(60),
    )
    .0
}

impl BeltDrive {
    /// The RK4 step limit at the state `(t, q, v)`: eigenvalues `λ` of the linearised
    /// first-order system `[δq̇; δv̇] = [0, I; −M⁻¹K, −M⁻¹C] [δq; δv]` with the analytic tangent
    /// `K = −∂f/∂q`, `C = −∂f/∂v` (dense, `2 n_q` eigenvalues), and the largest step keeping
    /// every decaying or oscillating mode inside RK4's stability region. Eigenvalues with
    /// `Re λ > 0` (physical instabilities) and `|λ| < 1e-6` (rigid motions) set no limit.
    pub fn rk4_step_limit(
        &self, t: f64, q: &[f64], v: &[f64],
    ) -> Result<ExplicitStepLimit, AncfError> {
        use faer::Mat;
        use faer::prelude::Solve;
        use mbd_core::SecondOrderSystem;
        let n = self.n_q();
        let num = |e: mbd_core::MbdError| AncfError::NonFinite {
            what: format!("linearised belt drive at t = {t} s: {e}"),
        };
        let m = self.mass(t, q).map_err(num)?.to_dense();
        let tg = self
            .force_tangent(t, q, v, &mut mbd_core::Workspace::new())
            .map_err(num)?
            .ok_or_else(|| AncfError::NonFinite {
                what: "belt drive tangent".into(),
            })?;
        let k = tg.stiffness.to_dense();
        let c = tg.damping.to_dense();
        let lu = m.partial_piv_lu();
        let mk = lu.solve(&k);
        let mc = lu.solve(&c);
        let a = Mat::<f64>::from_fn(2 * n, 2 * n, |i, j| match (i < n, j < n) {
            (true, true) => 0.0,
            (true, false) => {
                if j - n == i {
                    1.0
                } else {
                    0.0
                }
            }
            (false, true) => -mk[(i - n, j)],
            (false, false) => -mc[(i - n, j - n)],
        });
        let ev = a.eigenvalues().map_err(|e| AncfError::Singular {
            load_factor: 1.0,
            detail: format!("eigenvalues of the linearised belt drive: {e:?}"),
        })?;
        let mut out = ExplicitStepLimit {
            h_max: f64::INFINITY,
            limiting: [0.0, 0.0],
            omega_max: 0.0,
            decay_max: 0.0,
            h_imaginary: f64::INFINITY,
            h_real: f64::INFINITY,
        };
        for z in &ev {
            let (re, im) = (z.re, z.im);
            if !(re.is_finite() && im.is_finite()) {
                return Err(AncfError::NonFinite {
                    what: "eigenvalue of the linearised belt drive".into(),
                });
            }
            if re > 0.0 || re.hypot(im) < 1e-6 {
                continue;
            }
            out.omega_max = out.omega_max.max(im.abs());
            out.decay_max = out.decay_max.max(-re);
            let h = rk4_ray_limit(re, im);
            if h < out.h_max {
                out.h_max = h;
                out.limiting = [re, im];
            }
        }
        out.h_imaginary = 2.0 * std::f64::consts::SQRT_2 / out.omega_max;
        out.h_real = 2.785 / out.decay_max;
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: the RK4 stability interval on the negative real axis ends at z = −2.7853 and
    // on the imaginary axis at |z| = 2√2 (Hairer–Wanner, Solving ODEs II, §IV.2).
    #[test]
    fn rk4_stability_limits_on_the_axes() {
        assert!((rk4_ray_limit(-1.0, 0.0) - 2.785_293).abs() < 1e-5);
        assert!((rk4_ray_limit(-1e-300, 1.0) - 2.0 * std::f64::consts::SQRT_2).abs() < 1e-6);
        assert!((rk4_amplification(-1.0, 0.0) - 0.375).abs() < 1e-15);
    }
}
