//! The ANCF belt drive (Kerkkänen ch. 3, [`ancf::belt_drive`]) as a [`DriveModel`] of the
//! speed-loss procedure ([`crate::speed_loss_sweep`]): the same drive as the flowing
//! study (Ribaric Table 6-1, [`BeltDriveConfig`]), meshed as a Lagrangian loop of ANCF belt
//! elements — the high-fidelity reference of issue 8.
//!
//! This module depends only on `ancf`, `flowing`, `fe-model` and `mbd-core` (flowing and ancf
//! are siblings: neither knows the other, the adapter lives in `drives`, above both).
//!
//! # Parameter mapping (Ribaric Table 6-1 → ANCF belt drive)
//!
//! | Ribaric / [`BeltDriveConfig`] | ANCF ([`BeltDriveSpec`]) |
//! |---|---|
//! | driver at (0, 0), driven at (L_c, 0), radii R₁, R₂ | two pulleys inside the loop at the same centres; contact radius `R + p₀` (below) |
//! | EA, EI, ρA | rectangular section of thickness `h = √(12 EI/EA)` (so that `EI/EA = h²/12`) and width `b` ([`AncfConfig::width`]); `E = EA/(b h)`, `ρ = ρA/(b h)`, `α₁ = α₂ = 1` (the belt element's axial stiffness is `α₁EA`, its bending stiffness `α₂EI`, Kerkkänen (3.18)) |
//! | pre-tension T0 on the path of L_c and R (note U8) | unstretched length `L_b = L_path / (1 + T0/EA)` (the flowing model's choice, 1.2117 m for Table 6-1), then corrected by secant steps `L_b ← L_b (1 + (T − T0)/EA)` until the mean span tension `T` of the static solve ([`BeltDrive::initial_state`]) is T0 within 0.1 % (the role of Ribaric §6.4 step 1, "move the pulleys apart until T0"); `T` is the axial force of the belt's material law ([`BeltElement::axial_force`](ancf::BeltElement::axial_force), [`AncfConfig::law`]). The first estimate lands a few per cent off: at rest the axial force on a wrap is the span's less `EI/(2R²)` (beam statics, 5.2 N on Table 6-1), and the contact pressure and penetration follow it |
//! | penalty (6.1) `F_N = L_ele (k₂ δ² + k₁ δ)` per contact node | the same law per unit length, distributed: `f_n = k₂ d² + k₁ d + c_p ḋ` (Kerkkänen (3.20) with the quadratic term), integrated by Gauss quadrature (3.27) |
//! | the mounted belt's line on the path (flowing: contact radius `R + p₀`, `p₀` the penetration under `T0/R`, 72 µm) | the same: pulley radius `R + p₀`, so that the belt centreline sinks by `p₀` onto the path of radius R |
//! | tanh friction (6.2) `μ`, `κ` per node (or the `contact.friction` law) | the same law per unit length ([`BeltConfig::friction_law`](flowing::belt::config::BeltContact::friction_law)) |
//! | Rayleigh damping `αM + βK_e` of the deflection (β on the material rate) | the stiffness-proportional part as Kelvin–Voigt damping of the axial strain rate with the same β ([`BeltSpec::axial_damping`]: axial force `EA(ε + β ε̇)`; without it the driven pulley's torsional vibration against the spans, ≈57 Hz, decayed with ζ ≈ 0.003 and the steady-state detection never triggered); bending undamped; the mass-proportional part `αM` is dropped (on the absolute velocities of a Lagrangian mesh it would brake the moving belt); generalized-α's numerical damping (ρ∞ of the procedure) damps the contact vibrations; penalty damping `c_p` ([`AncfConfig::contact_damping`]) is 0 by default, as in (6.1) |
//! | driven inertia `I` | the free pulley's inertia |
//! | driver speed and load schedules of the procedure | supplied at every evaluation through [`BeltDrive::forces_with`] / [`BeltDrive::force_tangent_with`] |
//!
//! Slip of the tanh law is measured against the surface speed `ω (R + p₀)` at the contact
//! radius (Kerkkänen (3.25), nominal radius); the belt line runs at `R`, so a sticking belt
//! sees a small negative slip `−ω p₀` on both pulleys alike. It cancels in Δω at zero load.

use crate::ancf_run::snapshot;
use crate::model::{BeltData, DriveModel};
use crate::report::{DriveSnapshot, PulleyRole};
use ancf::belt_drive::{
    BeltDrive, BeltDriveSpec, BeltSpec, ContactSpec, InitialOptions, Pulley, PulleyDrive,
    SpeedProfile, TorqueProfile, post,
};
use ancf::{AncfError, BeltLaw};
use fe_model::generate::belt_path::{BeltPath, PathPulley, WrapSide};
use flowing::belt::model::mounting_penetration;
use flowing::belt::{BeltDriveConfig, Schedule};
use mbd_core::MbdError;
use mbd_core::integrators::State;
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};

fn invalid(item: String, reason: String) -> AncfError {
    AncfError::InvalidInput { item, reason }
}

/// Discretisation choices of the ANCF belt that Table 6-1 does not fix.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AncfConfig {
    /// Number of equal belt elements (40: 30 mm elements, about 5 per pulley arc).
    pub elements: usize,
    /// Contact quadrature points per element.
    pub contact_points: usize,
    /// Section width `b` \[m\] (planar model: only `b h` and `b h³` matter, through EA and EI).
    pub width: f64,
    /// Penalty damping `c_p` \[N·s/m²\] (default 0, as in (6.1)). A damped law is discontinuous
    /// where a quadrature point enters or leaves contact (`c_p ḋ ≠ 0` at `d = 0`): with
    /// `c_p = 500` (10 % of critical) Newton cycled at a contact change during the spin-up.
    pub contact_damping: f64,
    /// Generalized-α step \[s\] (replaces the procedure's step for this model).
    pub step: f64,
    /// Reuse tolerance of the elastic tangent (`BeltDrive::with_tangent_refresh`); `0` (exact
    /// tangent) by default: the procedure's Newton tolerance (1e-10 m) is tight, and with the
    /// Table 6-1 belt (EA = 152 kN) a lagging tangent (0.02) stalled Newton at 6e-6 m during
    /// the spin-up.
    pub tangent_refresh: f64,
    /// Material law of the belt ([`BeltLaw`]): `"st_venant_kirchhoff"` (Kerkkänen (3.18), the
    /// default) or `"linear"` (axial force `EA(‖r_x‖ − 1)`, as datasheets and Exudyn's cable).
    /// Span tensions, wrap tensions and the mounted tension are the axial force of this law.
    pub law: BeltLaw,
}

impl Default for AncfConfig {
    fn default() -> Self {
        Self {
            elements: 40,
            contact_points: 5,
            width: 0.02,
            contact_damping: 0.0,
            step: 1e-4,
            tangent_refresh: 0.0,
            law: BeltLaw::StVenantKirchhoff,
        }
    }
}

impl Validate for AncfConfig {
    /// Every field checked; the error names the field (path relative to this struct).
    fn validate(&self) -> Result<(), InvalidField> {
        if self.elements < 8 {
            return Err(InvalidField::new("elements", "must be at least 8"));
        }
        if self.contact_points == 0 || self.contact_points > 20 {
            return Err(InvalidField::new("contact_points", "must lie in 1..=20"));
        }
        for (name, v) in [("width", self.width), ("step", self.step)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(InvalidField::new(
                    name,
                    format!("must be finite and > 0 (got {v})"),
                ));
            }
        }
        if !(self.contact_damping.is_finite() && self.contact_damping >= 0.0) {
            return Err(InvalidField::new(
                "contact_damping",
                format!("must be finite and ≥ 0 (got {})", self.contact_damping),
            ));
        }
        if !(self.tangent_refresh.is_finite() && self.tangent_refresh >= 0.0) {
            return Err(InvalidField::new("tangent_refresh", "must be ≥ 0"));
        }
        Ok(())
    }
}

/// The derived quantities of the mapping (for reports).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AncfMapping {
    /// Penalty penetration under the mounting pressure `T0/R` of the driver and driven pulley \[m\].
    pub penetration: [f64; 2],
    /// Path length over the nominal radii \[m\].
    pub path_length: f64,
    /// Unstretched belt length \[m\] (after the correction to T0).
    pub belt_length: f64,
    /// Mean static span tension of the mounted belt \[N\] (T0 after the correction).
    pub mounted_tension: f64,
    /// Section thickness \[m\].
    pub thickness: f64,
    /// Young's modulus \[Pa\].
    pub young: f64,
    /// Density \[kg/m³\].
    pub density: f64,
    /// Penalty damping \[N·s/m²\].
    pub contact_damping: f64,
}

/// The ANCF drive of `cfg` (see the module documentation for every mapping).
pub fn ancf_spec(
    cfg: &BeltDriveConfig,
    s: &AncfConfig,
) -> Result<(BeltDriveSpec, AncfMapping), AncfError> {
    cfg.validate_within("drive")?;
    s.validate_within("ancf")?;
    let g = &cfg.geometry;
    let b = &cfg.belt;
    let centers = [[0.0, 0.0], [g.center_distance, 0.0]];
    let radii = [g.radius_driver, g.radius_driven];
    let nominal: Vec<PathPulley> = (0..2)
        .map(|k| PathPulley {
            center: centers[k],
            radius: radii[k],
            side: WrapSide::Inside,
        })
        .collect();
    let path_length = BeltPath::new(&nominal)
        .map_err(|e| invalid("drive.geometry".into(), e.to_string()))?
        .length();
    let penetration = [
        mounting_penetration(cfg, radii[0]),
        mounting_penetration(cfg, radii[1]),
    ];
    let belt_length = path_length / (1.0 + b.tension / b.ea);
    let thickness = (12.0 * b.ei / b.ea).sqrt();
    let area = s.width * thickness;
    let young = b.ea / area;
    let density = b.mass_per_length / area;
    let contact_damping = s.contact_damping;
    let pulley = |k: usize, name: &str, drive: PulleyDrive| Pulley {
        name: name.into(),
        center: centers[k],
        radius: radii[k] + penetration[k],
        side: WrapSide::Inside,
        drive,
    };
    let spec = BeltDriveSpec {
        pulleys: vec![
            pulley(
                0,
                "driver",
                PulleyDrive::Speed {
                    speed: SpeedProfile::Constant { omega: 0.0 },
                },
            ),
            pulley(
                1,
                "driven",
                PulleyDrive::Free {
                    inertia: cfg.driven_inertia,
                    load: TorqueProfile::None,
                },
            ),
        ],
        belt: BeltSpec {
            length: belt_length,
            elements: s.elements,
            width: s.width,
            thickness,
            young,
            poisson: 0.3,
            density,
            shear_factor: 5.0 / 6.0,
            alpha1: 1.0,
            alpha2: 1.0,
            gauss_points: 5,
            axial_damping: cfg.damping.beta,
            law: s.law,
        },
        contact: ContactSpec {
            stiffness: cfg.contact.penalty_linear,
            quadratic: cfg.contact.penalty_quadratic,
            damping: contact_damping,
            friction: cfg.contact.friction_law(),
            points: s.contact_points,
        },
    };
    Ok((
        spec,
        AncfMapping {
            penetration,
            path_length,
            belt_length,
            mounted_tension: f64::NAN,
            thickness,
            young,
            density,
            contact_damping,
        },
    ))
}

/// The ANCF belt drive with the procedure's driver-speed and load schedules.
pub struct AncfDrive {
    drive: BeltDrive,
    driver: Schedule,
    load: Schedule,
    driven_dof: usize,
    mapping: AncfMapping,
    belt: BeltData,
}

impl AncfDrive {
    /// Build the ANCF drive of `cfg` with discretisation `s`.
    pub fn new(cfg: &BeltDriveConfig, s: &AncfConfig) -> Result<Self, AncfError> {
        let (mut spec, mut mapping) = ancf_spec(cfg, s)?;
        // secant correction of the unstretched length until the static span tension is T0
        let t0 = cfg.belt.tension;
        let mut drive = BeltDrive::new(spec.clone())?;
        for _ in 0..5 {
            let init = drive.initial_state(&InitialOptions::default())?;
            let spans = post::span_tensions(&drive, &init.q);
            let t = spans.iter().sum::<f64>() / spans.len() as f64;
            mapping.mounted_tension = t;
            if !t.is_finite() || (t - t0).abs() <= 1e-3 * t0 {
                break;
            }
            spec.belt.length *= 1.0 + (t - t0) / cfg.belt.ea;
            mapping.belt_length = spec.belt.length;
            drive = BeltDrive::new(spec.clone())?;
        }
        let drive = drive.with_tangent_refresh(s.tangent_refresh);
        let driven_dof = drive
            .pulley_dof(1)
            .ok_or_else(|| invalid("pulleys".into(), "the driven pulley is not free".into()))?;
        Ok(Self {
            belt: BeltData {
                pretension: t0,
                ea: cfg.belt.ea,
                driven_radius: cfg.geometry.radius_driven,
                friction: drive.spec().contact.friction,
                linearised: false,
            },
            drive,
            driver: Schedule::constant(0.0),
            load: Schedule::constant(0.0),
            driven_dof,
            mapping,
        })
    }

    /// The underlying ANCF drive.
    pub fn drive(&self) -> &BeltDrive {
        &self.drive
    }

    /// The derived parameters of the mapping.
    pub fn mapping(&self) -> &AncfMapping {
        &self.mapping
    }

    fn omegas(&self, t: f64, v: &[f64]) -> [f64; 2] {
        [self.driver.value(t), v[self.driven_dof]]
    }

    fn loads(&self, t: f64) -> [f64; 2] {
        [0.0, self.load.value(t)]
    }
}

/// [`SecondOrderSystem`] of a wrapper of a [`BeltDrive`] (field `drive`) that supplies the
/// pulley speeds `self.omegas(t, v)` \[rad/s\] and load torques `self.loads(t)` \[N·m\] at every
/// evaluation through [`BeltDrive::forces_with`] / [`BeltDrive::force_tangent_with`]
/// (Kerkkänen (2.27), (3.26), (3.27)); shared by the two-pulley and the layout adapters.
macro_rules! scheduled_belt_system {
    ($ty:ty) => {
        impl mbd_core::SecondOrderSystem for $ty {
            fn n_q(&self) -> usize {
                self.drive.n_q()
            }
            fn dof_name(&self, dof: usize) -> String {
                self.drive.dof_name(dof)
            }
            fn mass_is_constant(&self) -> bool {
                true
            }
            fn mass(&self, t: f64, q: &[f64]) -> Result<mbd_core::SysMatrix, mbd_core::MbdError> {
                self.drive.mass(t, q)
            }
            fn forces(
                &self,
                t: f64,
                q: &[f64],
                v: &[f64],
                f: &mut [f64],
                ws: &mut mbd_core::Workspace,
            ) -> Result<(), mbd_core::MbdError> {
                let omegas = self.omegas(t, v);
                let loads = self.loads(t);
                self.drive.forces_with(q, v, &omegas, &loads, f, ws);
                Ok(())
            }
            fn force_tangent(
                &self,
                t: f64,
                q: &[f64],
                v: &[f64],
                ws: &mut mbd_core::Workspace,
            ) -> Result<Option<mbd_core::system::ForceTangent>, mbd_core::MbdError> {
                let omegas = self.omegas(t, v);
                Ok(Some(self.drive.force_tangent_with(q, v, &omegas, ws)))
            }
        }
    };
}
pub(crate) use scheduled_belt_system;

scheduled_belt_system!(AncfDrive);

impl DriveModel for AncfDrive {
    fn driven_speed(&self, v: &[f64]) -> f64 {
        v[self.driven_dof]
    }
    fn driver_speed(&self, t: f64) -> f64 {
        self.driver.value(t)
    }
    /// The static pre-strained equilibrium on the pulleys at rest
    /// ([`BeltDrive::initial_state`]).
    fn initial_state(&self) -> Result<State, MbdError> {
        let init = self
            .drive
            .initial_state(&InitialOptions::default())
            .map_err(|e| MbdError::InvalidInput {
                item: "ANCF belt initial state".into(),
                reason: e.to_string(),
            })?;
        let n = init.q.len();
        Ok(State::new(0.0, init.q, vec![0.0; n]))
    }
    fn set_driver_speed(&mut self, s: Schedule) {
        self.driver = s;
    }
    fn load_mut(&mut self) -> &mut Schedule {
        &mut self.load
    }

    fn belt_data(&self) -> BeltData {
        self.belt
    }

    /// [`crate::ancf_run::snapshot`] with the scheduled driver speed, the driven pulley's
    /// speed coordinate, and the belt-line radii `R` (the contact radii less `p₀`).
    fn snapshot(&self, t: f64, q: &[f64], v: &[f64]) -> Result<DriveSnapshot, MbdError> {
        let radii: Vec<f64> = (0..2)
            .map(|k| self.drive.pulleys()[k].radius - self.mapping.penetration[k])
            .collect();
        Ok(snapshot(
            &self.drive,
            t,
            q,
            v,
            &self.omegas(t, v),
            &[PulleyRole::Driver, PulleyRole::Driven],
            &radii,
        ))
    }

    fn span_transverse(&self, q: &[f64]) -> Result<Vec<f64>, MbdError> {
        Ok(post::span_transverse(&self.drive, q))
    }
}
