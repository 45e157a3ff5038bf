//! The rolling wheel–tire model with flowing material (Ribaric (7.10)–(7.17)) and its time
//! integration with Lagrange-multiplier contact and Coulomb slip friction (§7.3, §8.4.3).
//!
//! # Equations
//! The mesh frame does not spin (seed note U16): the wheel centre is held by the spindle
//! (U22: after the preload the centre is fixed, camber and steer are locked) and spins freely
//! about its axis `η = ŷ` with `θ̇ = ηᵀω` (U17). The absolute acceleration of the material at mesh
//! location `s` is (7.9), (7.14)–(7.16)
//!
//! ```text
//!   d̈ = r̈ + ω̇ × s + ω × (ω × s) + T z̈ + θ̈ T_,θ z + θ̇² T_,θθ z + 2 θ̇ T_,θ ż      (r̈ = 0)
//! ```
//!
//! Rows 3–4 of (7.17) are projected with `Tᵀ` applied to the mass-weighted nodal equations
//! (`M d̈ = f − K δ − C δ̇`), the Galerkin variant of U15 extended to the contact rows (identical
//! to Ribaric's rows when nothing is truncated, and symmetric in M and K):
//!
//! ```text
//!   M_z z̈ + (m_θ + G₁ z) θ̈ + (2θ̇ G₁ + α M_z + β K_z) ż + (K_z + θ̇² G₂ + β θ̇ K₁) z + θ̇² c_s
//!        = T_cᵀ f^c
//!   J θ̈ = τ − ηᵀ K_θ (z + β (ż + θ̇ ... ))                    (row 2 of (7.10): rim moment)
//! ```
//! Rayleigh damping `C = αM + βK` acts with its `βK` part on the material strain rate
//! `δ̇ = T ż + θ̇ T_,θ z` and its `αM` part on the Eulerian rate `T ż` (seed note U10: no drag
//! in the steady state). The spindle force is the force of the tire on the rim,
//! `F = −(K_r δ + β K_r δ̇)` (7.2). Summing the tire's nodal equations over a rigid translation
//! `e` (`K e = 0`) gives the same force from Newton's second law for the tire,
//! `F = Σ fᶜ − eᵀM d̈ − α eᵀM T ż`, which is the default here ([`SpindleForceMethod`]): the
//! two agree when nothing is truncated, but the truncated model satisfies its projected
//! equations only, and the rim form then carries the elastic residual of loads the basis does
//! not represent, chiefly the centrifugal load of rolling (the steady vertical force misses the
//! load by −2.1 % on the default tire at 60 km/h). The momentum form is the force-summation
//! form of reaction recovery, which, like the mode-acceleration method, converges faster with
//! the number of modes than the mode-displacement form (e.g. Craig & Kurdila, *Fundamentals of
//! Structural Dynamics*).
//!
//! # Contact (E15)
//! A contact node `i` at mesh position `xᵢ = sᵢ + (T_c z)ᵢ` is constrained by its gap `gᵢ ≥ 0`
//! (closest point on the drum/road/cleat), with multiplier `λᵢ ≥ 0` along the normal `nᵢ`; the
//! friction force opposes the slip of the material over the ground,
//! `vᵢ = θ̇ η × sᵢ + (T_c ż + θ̇ T_c,θ z)ᵢ − u_ground`: set-valued Coulomb with stick
//! (`|fᵢ| ≤ μλᵢ`, `fᵢ = −μλᵢ v̂_t` when slipping; default) or Ribaric's slip-only regularised
//! `fᵢ = −μλᵢ v_t/√(|v_t|² + ε²)` (U20), or any law of the contact crate, see [`TireFriction`](crate::TireFriction). The penalty option replaces the
//! rigid constraint by a compliance `1/k` on the diagonal of the contact problem.
//!
//! # Integration
//! Generalized-α (Chung–Hulbert, in the form of Arnold and Brüls with pseudo-accelerations;
//! spectral radius ρ∞ = 0.5 by default, ρ∞ = 1 is the trapezoidal Newmark rule) with the
//! contact gaps imposed at the end of each step (index-3), a linearly implicit step. The small
//! high-frequency damping of ρ∞ < 1 removes the period-two chatter of the index-3 contact
//! forces at the patch edges that the trapezoidal rule leaves undamped (and with it the
//! sensitivity of the cleat response to round-off and to the contact tolerance).
//!
//! The step runs on mbd-core's generalized-α stepper ([`AlphaStepper`]) with the tire's smooth
//! equations as a [`SecondOrderSystem`](mbd_core::SecondOrderSystem) ([`TireDynamics`]) and the
//! contact as its [`StepCorrection`](mbd_core::integrators::StepCorrection) ([`TireContact`]),
//! configured by [`RollingConfig::alpha_config`]: a linearly implicit step (one Newton
//! iteration from the predictor `v̇ₙ₊₁ = v̇ₙ`) with the frozen iteration matrix
//! ([`NewtonUpdate::Frozen`](mbd_core::integrators::NewtonUpdate::Frozen)) kept as its explicit inverse. The θ̇-dependent
//! gyroscopic/centrifugal/damping matrices are evaluated at a spin rate frozen until it drifts
//! by more than `spin_tolerance` (then re-formed: cheap). The iteration matrix
//! `S = [J ⋯; m_θ + G₁ z  M + γ'h C_eff + β'h² K_eff]`, with the generalized-α coefficients
//! `(β', γ') = (β, γ)(1 − α_f)/(1 − α_m)` of the end-of-step accelerations
//! ([`RollingConfig::implicit_coefficients`]), is inverted, together with the contact responses
//! `X = S⁻¹[0; T_cᵀ]` and `Y = T_c X_z` of all contact nodes, only when θ̇ drifts by more than
//! `matrix_tolerance` (10 %: once per run at constant speed) or the step size changes (the
//! inverse of the other step size is kept). In between, the one Newton iteration from the
//! predictor `v̇ₙ` applies the difference `(S(θ̇, z) − S_F) v̇ₙ` between the current and the
//! frozen matrix with a lag of one step (the gyroscopic part `2γ'h(θ̇_R − θ̇_S)G₁`, the
//! centrifugal and stiffness-damping parts and the coupling `G₁ (z − z_F) θ̈`). The normal and
//! friction problems are solved together by a semismooth Newton method on the Alart–Curnier
//! equations in the local contact frames (the contact crate's [`contact::solver`]), converged to
//! `contact_tolerance`. The step runs in the mass-normalised modal coordinates of
//! [`ReducedTire::modal`] (an exact change of coordinates, `M = I`, `K` diagonal), so per step
//! the cost is one product with `[G₁ H]` (n × 2 n_z, [`super::dynamics`]), one with `S⁻¹`
//! (n × n), `T_c z` of the nodes that may be near the ground for the candidate search, and work
//! on the candidates only (the local Delassus matrix is a gather from `Y` and `X`, copied once per
//! candidate set and factorisation). Candidates are the
//! nodes whose free gap is below `contact_margin` (plus `h v` in front of the cleat, whose
//! faces approach at the surface speed); [`StepStats::late_contacts`] counts impacts begun
//! within one step.
//!
//! # Mirror symmetry
//! A tire that is symmetric about its mid-plane, started symmetric on the (axially extruded)
//! drum or road (and on any ground that is its own mirror image: transverse obstacles, centred
//! potholes, a grid symmetric in `y`; no camber or slip angle, [`Ground::mirror_symmetric`]),
//! moves symmetrically: with [`RollingConfig::symmetry`] = `auto` (default) the
//! step runs on the half model of [`super::mirror`] — the symmetric modal coordinates (172 of
//! the default tire's 335) and one contact unknown per mirrored pair of contact nodes (52 of
//! 95) — which has the full model's symmetric solution at about a quarter of the matrix data
//! and half the contact problem per step (issue #16: the default cleat run 2.3 times, the
//! 0.05 ms step 2.2 times faster). The contact forces of every node ([`RollingState::lambda`],
//! [`RollingState::friction`]: mirrored onto the images), the spindle force and the input
//! tire's coordinates [`RollingTire::coordinates`] are those of the full model ([`RollingState::z`]
//! holds the simulated, symmetric modal coordinates); [`RollingTire::symmetry`] says which
//! model runs and, for the full one, why.

use crate::contact_step::TireContact;
use crate::dynamics::{PrescribedSpin, TireDynamics};
use crate::error::{TireError, invalid};
use crate::ground::Ground;
use crate::mirror::MirrorHalf;
use crate::reduced::ReducedTire;
use crate::rolling_config::{RollingConfig, SpindleForceMethod, Symmetry};
use crate::stats::StepStats;
use mbd_core::Validate;
use mbd_core::integrators::{AlphaStepper, State, Stepper};
use mbd_core::linalg::matvec;
use mbd_core::validate::check;
use serde::Serialize;

/// State of the rolling tire.
#[derive(Debug, Clone)]
pub struct RollingState {
    /// Time \[s\].
    pub t: f64,
    /// Reduced coordinates `z` of the simulation's tire ([`RollingTire::reduced`]: the modal
    /// coordinates `y`; [`RollingTire::coordinates`] gives the input tire's `z`).
    pub z: Vec<f64>,
    /// Their rates `ż`.
    pub zd: Vec<f64>,
    /// Their accelerations `z̈`.
    pub zdd: Vec<f64>,
    /// The generalized-α pseudo-accelerations `a` of `z` (equal to `z̈` for plain Newmark).
    pub acc: Vec<f64>,
    /// Wheel spin angle θ \[rad\].
    pub theta: f64,
    /// Spin rate θ̇ \[rad/s\].
    pub theta_d: f64,
    /// Spin acceleration θ̈ \[rad/s²\].
    pub theta_dd: f64,
    /// Pseudo-acceleration of θ \[rad/s²\].
    pub theta_acc: f64,
    /// Normal multiplier per contact node \[N\].
    pub lambda: Vec<f64>,
    /// Friction force per contact node (wheel frame) \[N\].
    pub friction: Vec<[f64; 3]>,
    /// Net force of the ground on the tire (normal and friction, wheel frame x, y, z) \[N\].
    pub contact_force: [f64; 3],
}

/// Spindle force of the tire on the wheel, in the output frame of U18.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpindleForce {
    /// Longitudinal `F_x` \[N\].
    pub fx: f64,
    /// Vertical `F_y` (up positive: the carried load) \[N\].
    pub fy: f64,
    /// Lateral (along the wheel axis) \[N\].
    pub fz: f64,
}

/// All six forces and moments on the wheel in the ISO 8855 wheel frame of the rig (x forward
/// in the travel direction, y left along the spin axis, z up; origin at the wheel centre):
/// issue 38, item 1.
///
/// The forces are today's [`SpindleForce`] (by [`RollingConfig::spindle_force`]) in the ISO
/// order: `fx` = [`SpindleForce::fx`], `fy` = the lateral [`SpindleForce::fz`], `fz` = the
/// vertical [`SpindleForce::fy`] (the carried load, positive up). The moments are those of the
/// contact forces about the wheel centre, `M = Σᵢ xᵢ × (λᵢ nᵢ + fᵢ)` over the contact nodes at
/// their deformed positions `xᵢ` (normal multiplier `λᵢ` along the ground normal `nᵢ`, friction
/// force `fᵢ`): the moment of the road on the tire, which in the steady state (constant
/// angular momentum of the flowing tire) is the moment the tire passes to the wheel; in
/// transients (the cleat) the tire's rate of angular momentum, not included, adds to it.
/// `my` includes the moment that balances the drive torque (`my ≈ −drive_torque` plus the
/// rolling-resistance moment in the steady state). `mz` is the aligning moment; the pneumatic
/// trail is `t = −M_z/F_y` (Pacejka, *Tire and Vehicle Dynamics*, §1.2: a side force acting
/// behind the contact centre). Moments about the contact centre (the W-axis system of ISO
/// 8855, the point of the road below the wheel centre at height `h` below it) follow as
/// `M_x − h F_y`, `M_y + h F_x`, `M_z`.
///
/// With a camber angle γ ≠ 0 ([`crate::rig::WheelInputs::camber_deg`]) the forces and moments
/// are given in the W-axis orientation instead (TYDEX/ISO 8855 W-axes: `x_W` the wheel's `x`,
/// `z_W = (0, sin γ, cos γ)` the road normal, `y_W = z_W × x_W = (0, cos γ, −sin γ)` in the
/// road plane), the moments still about the wheel centre: `fz` is then the load along the road
/// normal and `fy` the side force in the road plane. At γ = 0 the two frames coincide.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct WheelLoads {
    /// Longitudinal force `F_x` (forward positive) \[N\].
    pub fx: f64,
    /// Lateral force `F_y` (left positive) \[N\].
    pub fy: f64,
    /// Vertical force `F_z` (up positive: the carried load) \[N\].
    pub fz: f64,
    /// Overturning moment `M_x` about the wheel centre \[N·m\].
    pub mx: f64,
    /// Moment `M_y` about the spin axis at the wheel centre \[N·m\].
    pub my: f64,
    /// Aligning moment `M_z` about the vertical through the wheel centre \[N·m\].
    pub mz: f64,
}

/// The reduced tire rolling on a ground, with the spindle fixed: [`TireDynamics`] stepped by
/// mbd-core's [`AlphaStepper`] with the contact [`TireContact`] as its step correction.
///
/// The step runs in the mass-normalised modal coordinates of [`ReducedTire::modal`] (an exact
/// change of coordinates: `M = I`, `K` diagonal, a third less data per step), so the
/// coordinates of [`RollingTire::state`] are those of [`RollingTire::reduced`];
/// [`RollingTire::coordinates`] maps them back to the input tire's `z`.
pub struct RollingTire<'a> {
    /// The map between the simulation's coordinates and the input tire's, when the simulation
    /// runs in the modal coordinates of [`ReducedTire::modal`].
    modal: Option<(faer::Mat<f64>, faer::Mat<f64>)>,
    cfg: RollingConfig,
    /// Rayleigh α \[1/s\].
    pub alpha: f64,
    /// Rayleigh β \[s\].
    pub beta: f64,
    /// Drive torque about the wheel axis \[N·m\] (0: free-rolling spindle).
    pub drive_torque: f64,
    /// The prescribed spin, if any ([`RollingTire::prescribe_spin`]).
    spin_drive: Option<SpinDrive>,
    /// Reaction torque of the prescribed spin in the last step \[N·m\] (0 without one).
    reaction_torque: f64,
    /// Current state (a copy of the stepper's, with the contact forces; the contact forces
    /// written here before a step are its warm start, e.g. the preload's multipliers).
    pub state: RollingState,
    sys: TireDynamics<'a>,
    stepper: AlphaStepper<TireContact>,
    /// Number of inversions of the iteration matrix so far.
    pub refactors: usize,
    /// Work counters.
    pub stats: StepStats,
    /// Contact nodes pressed onto the cleat in the last step.
    pub cleat_contacts: usize,
    /// The rows of `P`, `P₁`, `P₂` (momentum spindle force) and of `K_r`, `Σ_rim K T_,θ` (rim
    /// force) as contiguous columns (n_z × 15: column `3k + c` is row `c` of matrix `k`), read
    /// once per recorded step.
    force_rows: faer::Mat<f64>,
    /// The worker thread of the split products (`threads ≥ 2`).
    product_worker: Option<std::sync::Arc<mbd_core::parallel::ProductWorker>>,
    symmetry: SymmetryUse,
}

/// The prescribed spin of a [`RollingTire`]: the target rate and the prescription at the
/// present time (the start of the next step's [`PrescribedSpin`]).
#[derive(Debug, Clone, Copy, PartialEq)]
struct SpinDrive {
    /// Target spin rate Ω \[rad/s\] (reached at the end of the next step).
    target: f64,
    /// Prescribed angle at the present time \[rad\].
    angle: f64,
    /// Prescribed rate at the present time \[rad/s\].
    rate: f64,
}

/// Whether a [`RollingTire`] steps the half model of symmetric motion
/// ([`RollingConfig::symmetry`], [`super::mirror`]).
#[derive(Debug, Clone, PartialEq)]
pub enum SymmetryUse {
    /// The half model with these symmetric coordinates and contact-node images.
    Half(MirrorHalf),
    /// The full model, and why (`symmetry = "off"`, or the test that failed).
    Full(String),
}

impl SymmetryUse {
    /// A one-line description, e.g. for a study's summary.
    pub fn describe(&self) -> String {
        match self {
            SymmetryUse::Half(h) => format!(
                "mirror half model: {} of {} coordinates, {} contact unknowns of {} nodes",
                h.kept.len(),
                h.n_full,
                (0..h.partner.len()).filter(|&i| h.weight(i) > 0.0).count(),
                h.partner.len()
            ),
            SymmetryUse::Full(why) => format!("full model ({why})"),
        }
    }
}

/// Largest antisymmetric part of the initial coordinates, relative to their largest value,
/// for which [`RollingTire::new`] starts the half model.
const START_ASYMMETRY: f64 = 1e-6;

/// The symmetric half of the modal tire `tire` if it exists and the initial modal coordinates
/// `y0` are symmetric (their antisymmetric part below [`START_ASYMMETRY`]), else the reason.
fn symmetric_half(tire: &ReducedTire, y0: &[f64]) -> Result<MirrorHalf, String> {
    let half = super::mirror::mirror_half(tire)?;
    let top = y0.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let anti = (0..y0.len())
        .filter(|j| half.kept.binary_search(j).is_err())
        .fold(0.0f64, |a, j| a.max(y0[j].abs()));
    if anti > START_ASYMMETRY * top {
        return Err(format!(
            "the initial state is not mirror-symmetric (antisymmetric part {:.1e} of {top:.1e})",
            anti
        ));
    }
    Ok(half)
}

/// Largest [`super::reduced::ModalTire::deviation`] for which [`RollingTire`] steps in modal
/// coordinates (round-off of the change of coordinates; else the input coordinates).
const MODAL_DEVIATION: f64 = 1e-9;

impl<'a> RollingTire<'a> {
    /// A tire at the preload coordinates `z0`, spinning at `spin` \[rad/s\], with Rayleigh
    /// coefficients `alpha`, `beta`, starting from rest accelerations (`v̇ = 0`: the steady
    /// state, whose contact forces the acceleration equations without contact do not see).
    pub fn new(
        red: &'a ReducedTire, cfg: RollingConfig, ground: Ground, alpha: f64, beta: f64,
        z0: Vec<f64>, spin: f64,
    ) -> Result<Self, TireError> {
        cfg.validate_within("rolling")?;
        ground.cfg.validate_within("ground")?;
        let nz = red.n_z();
        if z0.len() != nz {
            return Err(invalid(
                "initial coordinates",
                format!("{} values for {nz} coordinates", z0.len()),
            ));
        }
        let nc = red.n_contact();
        // the step in mass-normalised modal coordinates (M = I, K diagonal: a third less data
        // per step, issue #16); the input tire's coordinates if the change of coordinates is not
        // exact to round-off (e.g. unsymmetric M or K)
        let modal = red.modal()?;
        let mut symmetry = SymmetryUse::Full("symmetry = \"off\"".into());
        let ground_asymmetry = ground.mirror_symmetric().err();
        let (sys, z0, map) = if modal.deviation <= MODAL_DEVIATION {
            let y0 = (&modal.phi_inv * faer::MatRef::from_column_major_slice(&z0, nz, 1))
                .col(0)
                .iter()
                .copied()
                .collect::<Vec<f64>>();
            let half = match cfg.symmetry {
                Symmetry::Off => None,
                Symmetry::Auto if ground.lateral_speed != 0.0 => {
                    symmetry = SymmetryUse::Full(
                        "the road's lateral velocity (slip angle) breaks the mirror symmetry"
                            .into(),
                    );
                    None
                }
                Symmetry::Auto if ground_asymmetry.is_some() => {
                    symmetry = SymmetryUse::Full(ground_asymmetry.unwrap_or_default());
                    None
                }
                Symmetry::Auto => match symmetric_half(&modal.tire, &y0) {
                    Ok(h) => Some(h),
                    Err(reason) => {
                        symmetry = SymmetryUse::Full(reason);
                        None
                    }
                },
            };
            if let Some(half) = half {
                // the half model: the symmetric modal coordinates only (module `mirror`)
                let tire = super::mirror::half_tire(&modal.tire, &half);
                let k = &half.kept;
                let ys = k.iter().map(|&j| y0[j]).collect();
                let phi = faer::Mat::from_fn(nz, k.len(), |i, j| modal.phi[(i, k[j])]);
                let phi_inv = faer::Mat::from_fn(k.len(), nz, |i, j| modal.phi_inv[(k[i], j)]);
                let sys = TireDynamics::owned(tire, alpha, beta, cfg.wheel_spin_inertia, spin);
                symmetry = SymmetryUse::Half(half);
                (sys, ys, Some((phi, phi_inv)))
            } else {
                let sys =
                    TireDynamics::owned(modal.tire, alpha, beta, cfg.wheel_spin_inertia, spin);
                (sys, y0, Some((modal.phi, modal.phi_inv)))
            }
        } else {
            symmetry = SymmetryUse::Full(
                "the modal change of coordinates is not exact to round-off".into(),
            );
            let sys = TireDynamics::new(red, alpha, beta, cfg.wheel_spin_inertia, spin);
            (sys, z0, None)
        };
        let nz = sys.reduced().n_z();
        // one worker thread shared by the products with [G₁ H] and S⁻¹ (applied one after the
        // other in a step)
        let worker = mbd_core::parallel::ProductWorker::for_threads(cfg.threads);
        let mut sys = sys;
        sys.set_product_worker(worker.clone());
        let product_worker = worker.clone();
        let mut q0 = vec![0.0; nz + 1];
        q0[1..].copy_from_slice(&z0);
        let mut v0 = vec![0.0; nz + 1];
        v0[0] = spin;
        let sim_err = |e: mbd_core::MbdError| TireError::Simulation {
            time: 0.0,
            reason: e.to_string(),
        };
        let mut stepper = AlphaStepper::new(&sys, State::new(0.0, q0, v0), cfg.alpha_config())
            .map_err(sim_err)?
            .with_correction(TireContact::new(
                sys.reduced(),
                cfg.clone(),
                ground,
                match &symmetry {
                    SymmetryUse::Half(h) => Some(h),
                    SymmetryUse::Full(_) => None,
                },
            ));
        stepper.set_product_worker(worker);
        stepper
            .set_initial_acceleration(&vec![0.0; nz + 1])
            .map_err(sim_err)?;
        let sim_red = sys.reduced();
        let force_rows = faer::Mat::from_fn(nz, 15, |j, col| {
            let (k, c) = (col / 3, col % 3);
            [
                &sim_red.p_e,
                &sim_red.p_e1,
                &sim_red.p_e2,
                &sim_red.kr,
                &sim_red.kr1,
            ][k][(c, j)]
        });
        Ok(Self {
            modal: map,
            cfg,
            alpha,
            beta,
            drive_torque: 0.0,
            spin_drive: None,
            reaction_torque: 0.0,
            state: RollingState {
                t: 0.0,
                z: z0,
                zd: vec![0.0; nz],
                zdd: vec![0.0; nz],
                acc: vec![0.0; nz],
                theta: 0.0,
                theta_d: spin,
                theta_dd: 0.0,
                theta_acc: 0.0,
                lambda: vec![0.0; nc],
                friction: vec![[0.0; 3]; nc],
                contact_force: [0.0; 3],
            },
            sys,
            stepper,
            refactors: 0,
            stats: StepStats::default(),
            cleat_contacts: 0,
            force_rows,
            product_worker,
            symmetry,
        })
    }

    /// Change the time step `h` \[s\] for the following steps (e.g. sub-steps through an impact).
    /// The generalized-α scheme takes variable steps as they come; the stepper keeps the
    /// iteration matrix of the previous step size ([`NewtonUpdate::Frozen`](mbd_core::integrators::NewtonUpdate::Frozen)), so switching back
    /// and forth between two step sizes inverts each only once. Errors: `h` not positive.
    pub fn set_time_step(&mut self, h: f64) -> Result<(), TireError> {
        if !(h > 0.0 && h.is_finite()) {
            return Err(invalid("rolling.time_step", format!("{h} is not positive")));
        }
        self.cfg.time_step = h;
        Ok(())
    }

    /// The worker thread of the split products, if [`RollingConfig::threads`] ≥ 2 (e.g. to
    /// add its CPU time to the caller's).
    pub fn product_worker(&self) -> Option<&mbd_core::parallel::ProductWorker> {
        self.product_worker.as_deref()
    }

    /// Settings.
    pub fn config(&self) -> &RollingConfig {
        &self.cfg
    }

    /// The ground.
    pub fn ground(&self) -> &Ground {
        &self.stepper.correction().ground
    }

    /// Continues from `state`, a [`RollingTire::state`] saved earlier from this simulation (or
    /// one of the same tire, configuration and [`RollingTire::symmetry`]): its coordinates are
    /// those of [`RollingTire::reduced`], its contact forces the next step's warm start. With
    /// the generalized-α accelerations it holds, this is the stepper's whole memory
    /// ([`AlphaStepper::resume`]). The next step forms the spin-dependent matrices and the
    /// iteration matrix at the state's spin rate and starts the contact solve from the state's
    /// forces ([`TireContact`] keeps no older history), so the steps after a restart depend on
    /// the state only: a restart in this simulation and one in a fresh simulation step alike.
    /// Against the run that was never stopped they differ by what a re-formed matrix changes
    /// anywhere in a run (the spin-frozen matrices are re-formed after a drift of
    /// `spin_tolerance`/`matrix_tolerance`; the test `tire_restart` measures it). Errors:
    /// lengths other than the simulation's coordinates and contact nodes, values that are not
    /// finite, negative normal forces.
    pub fn set_state(&mut self, state: RollingState) -> Result<(), TireError> {
        let (nz, nc) = (self.sys.reduced().n_z(), self.sys.reduced().n_contact());
        let lengths = [
            ("z", state.z.len(), nz),
            ("zd", state.zd.len(), nz),
            ("zdd", state.zdd.len(), nz),
            ("acc", state.acc.len(), nz),
            ("lambda", state.lambda.len(), nc),
            ("friction", state.friction.len(), nc),
        ];
        for (field, n, want) in lengths {
            if n != want {
                return Err(invalid(
                    format!("state.{field}"),
                    format!("{n} values, the simulation has {want}"),
                ));
            }
        }
        // the shared range checks, on the first offending entry (named `state.<field>[i]`)
        let bad = |x: &[f64], ok: fn(f64) -> bool| x.iter().position(|&v| !ok(v));
        let scalars = [
            ("t", state.t),
            ("theta", state.theta),
            ("theta_d", state.theta_d),
            ("theta_dd", state.theta_dd),
            ("theta_acc", state.theta_acc),
        ];
        for (field, x) in scalars {
            check::finite(&format!("state.{field}"), x)?;
        }
        let friction: Vec<f64> = state.friction.iter().flatten().copied().collect();
        let arrays: [(&str, &[f64]); 7] = [
            ("z", &state.z),
            ("zd", &state.zd),
            ("zdd", &state.zdd),
            ("acc", &state.acc),
            ("friction", &friction),
            ("contact_force", &state.contact_force),
            ("lambda", &state.lambda),
        ];
        for (field, x) in arrays {
            if let Some(i) = bad(x, f64::is_finite) {
                check::finite(&format!("state.{field}[{i}]"), x[i])?;
            }
        }
        // contact pushes only
        if let Some(i) = bad(&state.lambda, |l| l >= 0.0) {
            check::non_negative(&format!("state.lambda[{i}]"), state.lambda[i], "N")?;
        }
        let join = |x: f64, rest: &[f64]| [&[x][..], rest].concat();
        let q = join(state.theta, &state.z);
        let v = join(state.theta_d, &state.zd);
        let vdot = join(state.theta_dd, &state.zdd);
        let a = join(state.theta_acc, &state.acc);
        self.stepper
            .resume(&self.sys, State::new(state.t, q, v), &vdot, &a)
            .map_err(|e| invalid("state", e.to_string()))?;
        self.stepper
            .correction_mut()
            .restart(&state.lambda, &state.friction);
        if let Some(d) = &mut self.spin_drive {
            // the prescription continues from the restored spin
            d.angle = state.theta;
            d.rate = state.theta_d;
        }
        self.state = state;
        Ok(())
    }

    /// Prescribes the wheel's spin rate `Ω` \[rad/s\] for the following steps (`Some`) instead
    /// of driving the spin by the torque [`RollingTire::drive_torque`] (`None`, the default:
    /// the spin is free, issue 38 item 1). The spin is then a kinematic constraint
    /// `θ = θ_p(t)` on the spin coordinate of the shared generalized-α stepper
    /// ([`PrescribedSpin`]; not a second integrator): over each step the rate goes linearly
    /// from its value at the start (at the switch: the present spin rate) to `Ω`, and the
    /// torque that holds it is the reaction [`RollingTire::reaction_torque`] (any
    /// `drive_torque` acts on top of it). Switching the prescription on or off re-sizes the
    /// stepper's constraints ([`AlphaStepper::resize_constraints`]); the next step factors
    /// the iteration matrix again. Errors: `Ω` not finite.
    pub fn prescribe_spin(&mut self, omega: Option<f64>) -> Result<(), TireError> {
        if let Some(w) = omega {
            check::finite("spin_rate", w)?;
        }
        let was = self.spin_drive.is_some();
        self.spin_drive = omega.map(|target| match self.spin_drive {
            Some(d) => SpinDrive { target, ..d },
            None => SpinDrive {
                target,
                angle: self.state.theta,
                rate: self.state.theta_d,
            },
        });
        if was != omega.is_some() {
            self.sys
                .set_prescribed_spin(self.spin_drive.map(|d| PrescribedSpin {
                    t0: self.state.t,
                    theta0: d.angle,
                    omega0: d.rate,
                    omega1: d.target,
                    h: self.cfg.time_step,
                }));
            self.stepper
                .resize_constraints(&self.sys)
                .map_err(|e| invalid("spin_rate", e.to_string()))?;
            self.reaction_torque = 0.0;
        }
        Ok(())
    }

    /// Replaces the ground under the wheel for the following steps: its height `top` (the
    /// wheel centre's height above the road is `−top`), surface speed and lateral velocity
    /// (the wheel centre's velocity over the road, [`Ground`]), e.g. per step from a prescribed
    /// wheel-centre motion (issue 38 item 2, [`crate::motion`]). The contact is position-level
    /// (index 3): a changed height is met at the end of the next step. Errors: an invalid
    /// ground configuration, a non-finite height or speed, and a lateral velocity on the half
    /// model of symmetric motion (which has no lateral coordinates: start with
    /// `rolling.symmetry = "off"` or a non-zero slip angle).
    pub fn set_ground(&mut self, ground: Ground) -> Result<(), TireError> {
        ground.cfg.validate_within("ground")?;
        check::finite("ground.top", ground.top)?;
        check::finite("ground.speed", ground.speed)?;
        check::finite("ground.lateral_speed", ground.lateral_speed)?;
        check::finite("ground.cleat_time", ground.cleat_time)?;
        if ground.lateral_speed != 0.0 && matches!(self.symmetry, SymmetryUse::Half(_)) {
            return Err(invalid(
                "ground.lateral_speed",
                "the half model of symmetric motion is stepped (no lateral motion): start \
                 with rolling.symmetry = \"off\" for a lateral velocity",
            ));
        }
        self.stepper.correction_mut().set_ground(ground);
        Ok(())
    }

    /// Sets the acceleration of the wheel frame (the spindle's rigid translation, wheel frame
    /// x, y, z) \[m/s²\] for the following steps ([`TireDynamics::set_frame_acceleration`]:
    /// the inertial load `−M a` on the tire; the momentum spindle force then also carries
    /// the tire's `−m a`, [`RollingTire::spindle_force`]). Errors: a value that is not finite,
    /// a lateral component on the half model.
    pub fn set_frame_acceleration(&mut self, a: [f64; 3]) -> Result<(), TireError> {
        for (c, x) in ["x", "y", "z"].iter().zip(a) {
            check::finite(&format!("frame_acceleration.{c}"), x)?;
        }
        if a[1] != 0.0 && matches!(self.symmetry, SymmetryUse::Half(_)) {
            return Err(invalid(
                "frame_acceleration.y",
                "the half model of symmetric motion is stepped (no lateral motion): start \
                 with rolling.symmetry = \"off\" for a lateral acceleration",
            ));
        }
        self.sys.set_frame_acceleration(a);
        Ok(())
    }

    /// The prescribed spin rate `Ω` \[rad/s\] ([`RollingTire::prescribe_spin`]), `None` when
    /// the spin is free.
    pub fn prescribed_spin(&self) -> Option<f64> {
        self.spin_drive.map(|d| d.target)
    }

    /// Reaction torque of the prescribed spin about the spin axis +y in the last step \[N·m\]:
    /// the torque the prescribing drive applies to the wheel, `−λ` with the constraint's
    /// multiplier λ ([`PrescribedSpin`]); 0 when the spin is free. In the steady state it
    /// balances the rim moment (Ribaric (7.2)), which is `t (−M_y)` of the contact moment
    /// ([`WheelLoads::my`]) with `t` = [`crate::steady::rim_moment_transfer`] (1 for a
    /// rotation-invariant stiffness, 0.85 on the inflated coarse test tire).
    pub fn reaction_torque(&self) -> f64 {
        self.reaction_torque
    }

    /// The total torque applied to the wheel about +y in the last step \[N·m\]:
    /// [`RollingTire::drive_torque`] plus [`RollingTire::reaction_torque`].
    pub fn spin_torque(&self) -> f64 {
        self.drive_torque + self.reaction_torque
    }

    /// Advance one time step of mbd-core's generalized-α stepper (module documentation): the
    /// spin-dependent matrices are re-formed first if θ̇ has drifted by more than
    /// `spin_tolerance`.
    pub fn step(&mut self) -> Result<(), TireError> {
        let clk = std::time::Instant::now();
        let h = self.cfg.time_step;
        let (_, gn) = self.cfg.implicit_coefficients();
        let (am, af, gn0) = (self.cfg.alpha_m, self.cfg.alpha_f, self.cfg.newmark_gamma);
        // the stepper's predicted spin rate (predictor θ̈ₙ₊₁ = 0)
        let st = &self.state;
        let w_theta = (af * st.theta_dd - am * st.theta_acc) / (1.0 - am);
        let spin_pred = st.theta_d + h * ((1.0 - gn0) * st.theta_acc + gn0 * w_theta);
        let drift = |s: f64, tol: f64| (spin_pred - s).abs() > tol * s.abs().max(1.0);
        // the stepper inverts the iteration matrix again in this step (no inverse of this step
        // size, or θ̇ drifted beyond `matrix_tolerance`, its `DriftTrigger` on the same
        // predicted θ̇): force matrices and S at the predicted spin rate
        let need_s = self
            .stepper
            .frozen_reference(h)
            .is_none_or(|s| drift(s, self.cfg.matrix_tolerance));
        if need_s {
            self.sys.set_spin(spin_pred);
        } else if drift(self.sys.spin(), self.cfg.spin_tolerance) {
            self.sys.set_spin(spin_pred);
            self.stats.force_matrix_updates += 1;
        }
        let spin_s = if need_s {
            spin_pred
        } else {
            self.stepper.frozen_reference(h).unwrap_or(spin_pred)
        };
        let lag = 2.0 * gn * h * (self.sys.spin() - spin_s);
        self.sys.set_lagged(st.theta_dd, &st.z, &st.zdd, lag);
        let c_r = clk.elapsed().as_secs_f64();
        self.sys.drive_torque = self.drive_torque;
        if let Some(d) = self.spin_drive {
            self.sys.set_prescribed_spin(Some(PrescribedSpin {
                t0: self.state.t,
                theta0: d.angle,
                omega0: d.rate,
                omega1: d.target,
                h,
            }));
        }
        let contact = self.stepper.correction_mut();
        contact.lambda.copy_from_slice(&self.state.lambda);
        contact.friction.copy_from_slice(&self.state.friction);
        let t = self.state.t;
        Stepper::step(&mut self.stepper, &self.sys, Some(self.cfg.time_step)).map_err(|e| {
            TireError::Simulation {
                time: t,
                reason: e.to_string(),
            }
        })?;
        let (s, vdot, acc) = (
            self.stepper.state(),
            self.stepper.acceleration(),
            self.stepper.algorithmic_acceleration(),
        );
        let c = self.stepper.correction();
        let st = &mut self.state;
        st.t = s.t;
        st.theta = s.q[0];
        st.z.copy_from_slice(&s.q[1..]);
        st.theta_d = s.v[0];
        st.zd.copy_from_slice(&s.v[1..]);
        st.theta_dd = vdot[0];
        st.zdd.copy_from_slice(&vdot[1..]);
        st.theta_acc = acc[0];
        st.acc.copy_from_slice(&acc[1..]);
        st.lambda.copy_from_slice(&c.lambda);
        st.friction.copy_from_slice(&c.friction);
        st.contact_force = c.contact_force;
        if let (Some(d), Some(p)) = (&mut self.spin_drive, self.sys.prescribed_spin()) {
            d.angle = p.angle(st.t);
            d.rate = d.target;
            self.reaction_torque = -self.stepper.lambda()[0];
        }
        self.cleat_contacts = c.cleat_contacts;
        self.refactors = self.stepper.stats.jacobian_evaluations;
        let own = self.stats;
        self.stats = c.stats;
        self.stats.force_matrix_updates = own.force_matrix_updates;
        self.stats.seconds[2] = own.seconds[2] + c_r;
        let total = own.seconds.iter().sum::<f64>() + clk.elapsed().as_secs_f64();
        self.stats.seconds[0] = total
            - self.stats.seconds[1]
            - self.stats.seconds[2]
            - self.stats.seconds[3]
            - self.stats.seconds[4];
        Ok(())
    }

    /// Spindle force of the tire on the wheel in the current state, by
    /// [`RollingConfig::spindle_force`]: Newton's second law for the tire (default) or the rim
    /// forces of Ribaric (7.2). See the module documentation.
    pub fn spindle_force(&self) -> SpindleForce {
        let f = match self.cfg.spindle_force {
            SpindleForceMethod::Momentum => self.spindle_force_momentum(),
            SpindleForceMethod::Rim => self.spindle_force_rim(),
        };
        SpindleForce {
            fx: f[0],
            fy: f[2],
            fz: f[1],
        }
    }

    /// All six spindle forces and moments in the ISO 8855 wheel frame ([`WheelLoads`]; with
    /// camber in the W-axis orientation): the forces of [`RollingTire::spindle_force`] and the
    /// moments of the contact forces about the wheel centre (deformed positions of the nodes in
    /// contact only).
    pub fn wheel_loads(&self) -> WheelLoads {
        let f = self.spindle_force();
        let red = self.sys.reduced();
        let st = &self.state;
        let mut m = [0.0; 3];
        for (i, &l) in st.lambda.iter().enumerate() {
            let fr = st.friction[i];
            if l == 0.0 && fr == [0.0; 3] {
                continue;
            }
            let s = red.contact_positions[i];
            let mut x = [0.0; 3];
            for (c, xc) in x.iter_mut().enumerate() {
                let row = red.tc.row(3 * i + c);
                let mut d = 0.0;
                for (j, zj) in st.z.iter().enumerate() {
                    d += row[j] * zj;
                }
                *xc = s[c] + d;
            }
            let n = self.ground().query(st.t, x).normal;
            let g = [l * n[0] + fr[0], l * n[1] + fr[1], l * n[2] + fr[2]];
            m[0] += x[1] * g[2] - x[2] * g[1];
            m[1] += x[2] * g[0] - x[0] * g[2];
            m[2] += x[0] * g[1] - x[1] * g[0];
        }
        let gamma = self.ground().camber;
        if gamma == 0.0 {
            return WheelLoads {
                fx: f.fx,
                fy: f.fz,
                fz: f.fy,
                mx: m[0],
                my: m[1],
                mz: m[2],
            };
        }
        // the W-axis orientation: y_W = (0, cos γ, −sin γ), z_W = (0, sin γ, cos γ)
        let (sg, cg) = gamma.sin_cos();
        WheelLoads {
            fx: f.fx,
            fy: cg * f.fz - sg * f.fy,
            fz: sg * f.fz + cg * f.fy,
            mx: m[0],
            my: cg * m[1] - sg * m[2],
            mz: sg * m[1] + cg * m[2],
        }
    }

    /// The rim forces (7.2): `F = −K_r (z + β ż) − β θ̇ K_r,θ z` (wheel frame).
    fn spindle_force_rim(&self) -> [f64; 3] {
        let red = self.sys.reduced();
        let st = &self.state;
        let b = self.beta;
        let mut f = [0.0; 3];
        let rows = &self.force_rows;
        for (c, fc) in f.iter_mut().enumerate() {
            let (kr, kr1) = (rows.col(9 + c), rows.col(12 + c));
            let mut s = 0.0;
            for j in 0..red.n_z() {
                s += kr[j] * (st.z[j] + b * st.zd[j]) + b * st.theta_d * kr1[j] * st.z[j];
            }
            *fc = -s;
        }
        f
    }

    /// Newton's second law for the tire (wheel frame): with the absolute acceleration of the
    /// material (module docs) and the mass-proportional damping force `αM T ż`,
    /// `F = Σ fᶜ − [P z̈ + θ̈ (P₁ z + eᵀM s_,θ) + θ̇² (P₂ z + eᵀM s_,θθ) + 2θ̇ P₁ ż] − α P ż`.
    /// (Summing the tire's nodal equations and using `K e = 0` for the rigid translation `e`
    /// turns the elastic and stiffness-damping forces into the rim forces of (7.2), so both
    /// forms agree for the untruncated model.)
    fn spindle_force_momentum(&self) -> [f64; 3] {
        let red = self.sys.reduced();
        let st = &self.state;
        let (w, w2) = (st.theta_d, st.theta_d * st.theta_d);
        let mut f = [0.0; 3];
        let rows = &self.force_rows;
        for (c, fc) in f.iter_mut().enumerate() {
            let (p, p1, p2) = (rows.col(c), rows.col(3 + c), rows.col(6 + c));
            let mut inertia = st.theta_dd * red.p_s[0][c] + w2 * red.p_s[1][c];
            for j in 0..red.n_z() {
                inertia += p[j] * (st.zdd[j] + self.alpha * st.zd[j])
                    + p1[j] * (st.theta_dd * st.z[j] + 2.0 * w * st.zd[j])
                    + w2 * p2[j] * st.z[j];
            }
            *fc = st.contact_force[c] - inertia;
        }
        // the accelerating spindle frame: the tire's momentum also changes by m a
        let a = self.sys.frame_acceleration();
        if a != [0.0; 3] {
            for (fc, ac) in f.iter_mut().zip(a) {
                *fc -= red.tire_mass * ac;
            }
        }
        f
    }

    /// Deformed contact-node positions `sᵢ + (T_c z)ᵢ` \[m\].
    pub fn contact_positions(&self) -> Vec<[f64; 3]> {
        let red = self.sys.reduced();
        let mut d = vec![0.0; red.tc.nrows()];
        matvec(red.tc.as_ref(), &self.state.z, &mut d);
        red.contact_positions
            .iter()
            .enumerate()
            .map(|(i, s)| [s[0] + d[3 * i], s[1] + d[3 * i + 1], s[2] + d[3 * i + 2]])
            .collect()
    }

    /// The reduced tire the simulation steps: the input tire in the modal coordinates of
    /// [`ReducedTire::modal`] (or the input tire itself, see [`RollingTire::new`]); the
    /// coordinates of [`RollingState`] are its own.
    pub fn reduced(&self) -> &ReducedTire {
        self.sys.reduced()
    }

    /// The input tire's reduced coordinates `z` of the current state (`z = Φ y` when the
    /// simulation runs in modal coordinates `y`).
    pub fn coordinates(&self) -> Vec<f64> {
        match &self.modal {
            Some((phi, _)) => {
                let y = faer::MatRef::from_column_major_slice(&self.state.z, self.state.z.len(), 1);
                (phi * y).col(0).iter().copied().collect()
            }
            None => self.state.z.clone(),
        }
    }

    /// Total normal contact force vector `Σ λᵢ nᵢ`-weighted vertical component \[N\] (the
    /// vertical force the ground exerts, friction excluded).
    pub fn total_normal_force(&self) -> f64 {
        self.state.lambda.iter().sum()
    }

    /// Number of contact nodes in contact.
    pub fn active_count(&self) -> usize {
        self.state.lambda.iter().filter(|&&l| l > 0.0).count()
    }

    /// Whether the half model of symmetric motion is stepped ([`RollingConfig::symmetry`]).
    pub fn symmetry(&self) -> &SymmetryUse {
        &self.symmetry
    }

    /// The spin-row coefficients `[β K_θ; K_θ + β θ̇ K_θ,θ]` of the current spin-dependent matrices
    /// (for diagnostics).
    pub fn spin_row(&self) -> Option<Vec<f64>> {
        Some(self.sys.spin_row())
    }
}
