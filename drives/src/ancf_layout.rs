//! The ANCF belt drive (Kerkkänen ch. 3, [`ancf::belt_drive`]) on any layout (issue 17 item 4):
//! the same TOML layout as the flowing model ([`LayoutConfig`]: N pulleys speed-driven by a
//! [`Signal`], free with an inertia and a load torque, or idlers; grooved or back side; the
//! belt's unstretched length given or computed from the target pre-tension; an optional
//! automatic tensioner, [`mbd_core::tensioner`]) meshed as a Lagrangian loop of ANCF belt
//! elements.
//!
//! The parameter mapping is the one of the two-pulley drive ([`crate::ancf_drive_model`]):
//! section `h = √(12 EI/EA)` of width [`AncfConfig::width`], contact radius `R + p₀` (`p₀` the
//! penalty penetration under the mounting pressure `T0/R`), the layout's friction law and
//! penalty, Kelvin–Voigt axial damping with the Rayleigh `β`.
//!
//! Mounting ([`AncfLayoutDrive::new`]):
//!
//! * **belt length.** Given (`belt_length`), it is used as is. Otherwise the belt starts at
//!   `L_b = L_path / (1 + T0/EA)` (the layout's [`LayoutConfig::resolve`], `L_path` over the
//!   nominal radii, with a tensioner at the hand-statics arm angle) and is corrected by secant
//!   steps `L_b ← L_b (1 + (T̄ − T0)/EA)` until the mean static span tension `T̄` of the ANCF
//!   belt ([`BeltDrive::initial_state`], Kerkkänen (2.20), (3.20) at rest) is `T0` within
//!   [`TENSION_TOLERANCE`] (the belt element's bending–stretching coupling on the arcs,
//!   Kerkkänen (3.18), puts the first estimate a few per cent off);
//! * **tensioner.** The arm is a coordinate of the drive ([`BeltDrive::with_tensioner`]); the
//!   static solve holds it at the hand-statics angle while the belt length is corrected, then
//!   releases it: secant iterations on the arm angle `θ` until the arm's moment balance
//!   `M_s(θ) + (c − p) × F_hub = 0` (F_hub from the ANCF contact forces) holds to
//!   [`ARM_ANGLE_TOLERANCE`].
//!
//! Pulley speeds and loads are the layout's [`Signal`]s, supplied at every evaluation through
//! [`BeltDrive::forces_with`] / [`BeltDrive::force_tangent_with`]. The drive is a
//! [`DriveModel`] (driver: pulley 0, driven: the first loaded pulley), so the speed-loss
//! procedure and the FEAD study ([`crate::fead`], `model = "ancf"`) run it on the shared
//! generalized-α stepper.

use crate::ancf_drive_model::AncfConfig;
use crate::ancf_run::snapshot;
use crate::layout::{LayoutConfig, MotionSpec, ResolvedLayout};
use crate::model::{BeltData, DriveModel};
use crate::report::{DriveSnapshot, PulleyRole};
use crate::{DriveError, Schedule};
use ancf::belt_drive::{
    BeltDrive, BeltDriveSpec, BeltSpec, ContactSpec, InitialOptions, InitialState, Pulley,
    PulleyDrive, SpeedProfile, TorqueProfile, post,
};
use flowing::belt::Signal;
use flowing::belt::model::mounting_penetration;
use mbd_core::integrators::State;
use mbd_core::validate::Validate;
use mbd_core::{MbdError, Workspace};

/// Relative tolerance of the mounted mean span tension against the target `T0` \[-\].
pub const TENSION_TOLERANCE: f64 = 1e-3;
/// Tolerance of the static arm angle \[rad\].
pub const ARM_ANGLE_TOLERANCE: f64 = 1e-7;

/// The ANCF drive of a layout with its pulley signals (see the module documentation).
pub struct AncfLayoutDrive {
    drive: BeltDrive,
    motions: Vec<MotionSpec>,
    resolved: ResolvedLayout,
    penetration: Vec<f64>,
    initial: InitialState,
    target_tension: f64,
    ea: f64,
    friction: contact::friction::FrictionSpec,
}

fn bad(e: impl std::fmt::Display) -> DriveError {
    DriveError::Invalid(e.to_string())
}

impl LayoutConfig {
    /// The ANCF belt-drive spec of the layout (module documentation): pulleys at the resolved
    /// centres (a tensioner's idler at its hand-statics arm angle) with contact radii
    /// `R + p₀`, the belt at the unstretched length `L_path/(1 + T/EA)` of the resolved
    /// tension `T` (before the ANCF correction), and the penetrations `p₀` \[m\].
    pub fn ancf_spec(
        &self,
        s: &AncfConfig,
    ) -> Result<(BeltDriveSpec, ResolvedLayout, Vec<f64>), DriveError> {
        self.validate().map_err(bad)?;
        s.validate_within("ancf").map_err(bad)?;
        let res = self.resolve().map_err(bad)?;
        let bcfg = self.belt_config(res.tension);
        let b = &self.belt;
        let thickness = (12.0 * b.ei / b.ea).sqrt();
        let area = s.width * thickness;
        let centers: Vec<[f64; 2]> = res.path.pulleys().iter().map(|p| p.center).collect();
        let penetration: Vec<f64> = self
            .pulleys
            .iter()
            .map(|p| mounting_penetration(&bcfg, p.radius))
            .collect();
        let pulleys = self
            .pulleys
            .iter()
            .enumerate()
            .map(|(k, p)| Pulley {
                name: p.name.clone(),
                center: centers[k],
                radius: p.radius + penetration[k],
                side: p.side,
                drive: match &p.motion {
                    // the signals are supplied at every evaluation (AncfLayoutDrive)
                    MotionSpec::Speed { .. } => PulleyDrive::Speed {
                        speed: SpeedProfile::Constant { omega: 0.0 },
                    },
                    MotionSpec::Load { inertia, .. } | MotionSpec::Idler { inertia } => {
                        PulleyDrive::Free {
                            inertia: *inertia,
                            load: TorqueProfile::None,
                        }
                    }
                },
            })
            .collect();
        let spec = BeltDriveSpec {
            pulleys,
            belt: BeltSpec {
                length: res.belt_length,
                elements: s.elements,
                width: s.width,
                thickness,
                young: b.ea / area,
                poisson: 0.3,
                density: b.mass_per_length / area,
                shear_factor: 5.0 / 6.0,
                alpha1: 1.0,
                alpha2: 1.0,
                gauss_points: 5,
                axial_damping: self.damping.beta,
                law: s.law,
            },
            contact: ContactSpec {
                stiffness: self.contact.penalty_linear,
                quadratic: self.contact.penalty_quadratic,
                damping: s.contact_damping,
                friction: self.friction_law(),
                points: s.contact_points,
            },
        };
        Ok((spec, res, penetration))
    }

    /// The mounted ANCF drive of the layout ([`AncfLayoutDrive::new`]).
    pub fn ancf_model(&self, s: &AncfConfig) -> Result<AncfLayoutDrive, DriveError> {
        AncfLayoutDrive::new(self, s)
    }
}

/// Mean of the finite span tensions \[N\].
fn mean_span_tension(drive: &BeltDrive, q: &[f64]) -> f64 {
    let t: Vec<f64> = post::span_tensions(drive, q)
        .into_iter()
        .filter(|t| t.is_finite())
        .collect();
    t.iter().sum::<f64>() / t.len().max(1) as f64
}

impl AncfLayoutDrive {
    /// Build and mount the ANCF drive of `cfg` with the discretisation `s` (module
    /// documentation: belt length correction, then the tensioner's static arm angle).
    pub fn new(cfg: &LayoutConfig, s: &AncfConfig) -> Result<Self, DriveError> {
        let (mut spec, resolved, penetration) = cfg.ancf_spec(s)?;
        let build = |spec: &BeltDriveSpec| -> Result<BeltDrive, DriveError> {
            let d = match cfg.tensioner {
                Some(t) => BeltDrive::with_tensioner(spec.clone(), t)?,
                None => BeltDrive::new(spec.clone())?,
            };
            Ok(d.with_tangent_refresh(s.tangent_refresh))
        };
        let opts = InitialOptions::default();
        let t0 = resolved.tension;
        let ea = cfg.belt.ea;
        let mut drive = build(&spec)?;
        let mut init = drive.initial_state(&opts)?;
        if cfg.belt_length.is_none() {
            for _ in 0..8 {
                let t = mean_span_tension(&drive, &init.q);
                if !t.is_finite() || (t - t0).abs() <= TENSION_TOLERANCE * t0 {
                    break;
                }
                spec.belt.length *= 1.0 + (t - t0) / ea;
                drive = build(&spec)?;
                init = drive.initial_state(&opts)?;
            }
        }
        if let Some(a) = drive.arm().copied() {
            // secant on the arm's static moment balance, the belt re-solved at each angle
            let residual = |q: &[f64]| -> f64 {
                let n = q.len();
                let mut f = vec![0.0; n];
                let omegas = vec![0.0; drive.pulleys().len()];
                drive.forces_with(
                    q,
                    &vec![0.0; n],
                    &omegas,
                    &omegas,
                    &mut f,
                    &mut Workspace::new(),
                );
                f[a.dof]
            };
            let (mut th0, mut g0) = (init.q[a.dof], residual(&init.q));
            // first trial: the spring's stiffness alone as the slope
            let mut th1 = th0 + g0 / a.spec.stiffness;
            let mut converged = false;
            for _ in 0..40 {
                let mut q = init.q.clone();
                q[a.dof] = th1;
                init = drive.initial_state_from(q, &opts)?;
                let g1 = residual(&init.q);
                if (th1 - th0).abs() <= ARM_ANGLE_TOLERANCE {
                    converged = true;
                    break;
                }
                let slope = (g1 - g0) / (th1 - th0);
                if !(slope.is_finite() && slope != 0.0) {
                    break;
                }
                (th0, g0) = (th1, g1);
                th1 -= g1 / slope;
            }
            if !converged || !a.spec.within_travel(init.q[a.dof]) {
                return Err(DriveError::Invalid(format!(
                    "tensioner: outside its travel: the ANCF belt's arm of pulley '{}' finds no static angle in [{:.3}, {:.3}] rad (last {:.4} rad)",
                    cfg.pulleys[a.spec.pulley].name,
                    a.spec.travel[0],
                    a.spec.travel[1],
                    init.q[a.dof]
                )));
            }
        }
        Ok(Self {
            drive,
            motions: cfg.pulleys.iter().map(|p| p.motion.clone()).collect(),
            resolved,
            penetration,
            initial: init,
            target_tension: t0,
            ea,
            friction: cfg.friction_law(),
        })
    }

    /// The underlying ANCF drive.
    pub fn drive(&self) -> &BeltDrive {
        &self.drive
    }

    /// The layout resolved by hand statics ([`LayoutConfig::resolve`]).
    pub fn resolved(&self) -> &ResolvedLayout {
        &self.resolved
    }

    /// The mounted static state (pulleys at rest, arm at its static angle).
    pub fn initial(&self) -> &InitialState {
        &self.initial
    }

    /// Mean static span tension of the mounted belt \[N\].
    pub fn mounted_tension(&self) -> f64 {
        mean_span_tension(&self.drive, &self.initial.q)
    }

    /// The target (or, with a given belt length, the hand-statics) pre-tension \[N\].
    pub fn target_tension(&self) -> f64 {
        self.target_tension
    }

    /// Unstretched belt length after the mounting correction \[m\].
    pub fn belt_length(&self) -> f64 {
        self.drive.spec().belt.length
    }

    /// Static arm angle of the tensioner in the ANCF belt \[rad\] (`None`: no tensioner).
    pub fn static_arm_angle(&self) -> Option<f64> {
        self.drive.arm().map(|a| self.initial.q[a.dof])
    }

    /// The mounted state as an integrator state at `t = 0` (zero velocities).
    pub fn initial_state(&self) -> State {
        let n = self.initial.q.len();
        State::new(0.0, self.initial.q.clone(), vec![0.0; n])
    }

    /// Travel-sense speeds \[rad/s\] of every pulley at `(t, v)`.
    pub fn omegas(&self, t: f64, v: &[f64]) -> Vec<f64> {
        self.motions
            .iter()
            .enumerate()
            .map(|(k, m)| match (m, self.drive.pulley_dof(k)) {
                (MotionSpec::Speed { speed }, _) => speed.value(t),
                (_, Some(j)) => v[j],
                _ => 0.0,
            })
            .collect()
    }

    fn loads(&self, t: f64) -> Vec<f64> {
        self.motions
            .iter()
            .map(|m| match m {
                MotionSpec::Load { torque, .. } => torque.value(t),
                _ => 0.0,
            })
            .collect()
    }

    /// Role of every pulley (speed: driver, load: driven, idler).
    pub fn roles(&self) -> Vec<PulleyRole> {
        self.motions
            .iter()
            .map(|m| match m {
                MotionSpec::Speed { .. } => PulleyRole::Driver,
                MotionSpec::Load { .. } => PulleyRole::Driven,
                MotionSpec::Idler { .. } => PulleyRole::Idler,
            })
            .collect()
    }

    /// The report snapshot ([`crate::report`]) at `(t, q, v)` with the belt-line radii `R`.
    pub fn snapshot(&self, t: f64, q: &[f64], v: &[f64]) -> DriveSnapshot {
        let radii: Vec<f64> = (0..self.motions.len())
            .map(|k| self.drive.pulleys()[k].radius - self.penetration[k])
            .collect();
        snapshot(
            &self.drive,
            t,
            q,
            v,
            &self.omegas(t, v),
            &self.roles(),
            &radii,
        )
    }

    /// The pulley motions (their signals may be replaced between runs: the FEAD sweep sets the
    /// crank's speed per engine speed).
    pub fn motions_mut(&mut self) -> &mut [MotionSpec] {
        &mut self.motions
    }

    /// Tensioner arm angle `θ` \[rad\] at `q` (`None`: no tensioner).
    pub fn arm_angle(&self, q: &[f64]) -> Option<f64> {
        self.drive.arm().map(|a| q[a.dof])
    }

    /// Mean belt speed \[m/s\] ([`post::belt_speed`]).
    pub fn belt_speed(&self, q: &[f64], v: &[f64]) -> f64 {
        post::belt_speed(&self.drive, q, v)
    }

    /// Index of the driven pulley of the speed-loss procedure: the first loaded pulley, else
    /// the first idler, else the last pulley.
    fn driven_pulley(&self) -> usize {
        let first = |f: fn(&MotionSpec) -> bool| self.motions.iter().position(f);
        first(|m| matches!(m, MotionSpec::Load { .. }))
            .or_else(|| first(|m| matches!(m, MotionSpec::Idler { .. })))
            .unwrap_or(self.motions.len() - 1)
    }

    /// The pulley signals (for reports).
    pub fn signal(&self, k: usize) -> Option<&Signal> {
        match self.motions.get(k)? {
            MotionSpec::Speed { speed } => Some(speed),
            MotionSpec::Load { torque, .. } => Some(torque),
            MotionSpec::Idler { .. } => None,
        }
    }
}

crate::ancf_drive_model::scheduled_belt_system!(AncfLayoutDrive);

/// The ANCF layout drive in the speed-loss procedure and the FEAD study: pulley 0 is the
/// driver, the first loaded pulley ([`MotionSpec::Load`]) the driven one.
impl DriveModel for AncfLayoutDrive {
    /// Travel-sense speed of the driven pulley \[rad/s\] (`NaN` without a free driven pulley).
    fn driven_speed(&self, v: &[f64]) -> f64 {
        self.drive
            .pulley_dof(self.driven_pulley())
            .map_or(f64::NAN, |j| v[j])
    }

    /// Pulley 0's prescribed speed (`NaN` when pulley 0 is not speed-driven).
    fn driver_speed(&self, t: f64) -> f64 {
        match &self.motions[0] {
            MotionSpec::Speed { speed } => speed.value(t),
            _ => f64::NAN,
        }
    }

    /// The mounted static state ([`AncfLayoutDrive::new`]: belt length and arm angle solved).
    fn initial_state(&self) -> Result<State, MbdError> {
        Ok(AncfLayoutDrive::initial_state(self))
    }

    /// Pulley 0's speed (kept when pulley 0 is not speed-driven).
    fn set_driver_speed(&mut self, s: Schedule) {
        if let MotionSpec::Speed { speed } = &mut self.motions[0] {
            *speed = s.into();
        }
    }

    /// The driven pulley's load schedule (an idler chosen as the driven pulley is given a
    /// load: it becomes [`MotionSpec::Load`] with its inertia).
    ///
    /// # Panics
    /// If every pulley is speed-driven (no pulley can carry a load; the FEAD study never asks).
    fn load_mut(&mut self) -> &mut Schedule {
        let k = self.driven_pulley();
        if let MotionSpec::Idler { inertia } = self.motions[k] {
            self.motions[k] = MotionSpec::Load {
                inertia,
                torque: Signal::constant(0.0),
            };
        }
        match &mut self.motions[k] {
            MotionSpec::Load { torque, .. } => &mut torque.schedule,
            _ => panic!("the ANCF layout drive has no free pulley to load"),
        }
    }

    /// Target pre-tension, `EA`, the driven pulley's belt-line radius and the friction law;
    /// not linearised (the ANCF belt is geometrically exact, Kerkkänen (3.18)).
    fn belt_data(&self) -> BeltData {
        let k = self.driven_pulley();
        BeltData {
            pretension: self.target_tension,
            ea: self.ea,
            driven_radius: self.drive.pulleys()[k].radius - self.penetration[k],
            friction: self.friction,
            linearised: false,
        }
    }

    fn snapshot(&self, t: f64, q: &[f64], v: &[f64]) -> Result<crate::DriveSnapshot, MbdError> {
        Ok(AncfLayoutDrive::snapshot(self, t, q, v))
    }

    fn span_transverse(&self, q: &[f64]) -> Result<Vec<f64>, MbdError> {
        Ok(post::span_transverse(&self.drive, q))
    }
}
