//! How a pulley turns: prescribed speed, or free with an inertia against a load torque and a
//! viscous damper (an accessory, an idler). Speeds and torques are counted in the belt's
//! **travel sense** ([`crate::pulley`]): a positive speed moves the pulley's surface with the
//! belt; a load torque opposes that sense (Kerkkänen (3.26): "opposing torque of the driven
//! accessories").
//!
//! A free pulley's equation, in every belt model:
//!
//! ```text
//!   J ω̇ = τ_belt − M_load(t) − c ω        (τ_belt the belt's contact torque, travel sense)
//! ```

use crate::decoupler::Decoupler;
use crate::signal::Signal;
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// How a pulley turns (module documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Motion {
    /// Speed prescribed \[rad/s\] in the travel sense (a crankshaft, a test-rig driver); no
    /// coordinate of its own.
    Speed {
        /// Speed history \[rad/s\].
        speed: Signal,
    },
    /// Free, with moment of inertia `inertia` about its axle \[kg m²\], against the load
    /// torque `torque` \[N m\] (opposing the travel sense; negative drives the belt) and a
    /// viscous damper `damping` \[N m s/rad\] (an accessory).
    Load {
        /// Moment of inertia \[kg m²\].
        inertia: f64,
        /// Load torque history \[N m\].
        torque: Signal,
        /// Viscous rotational damping `c` \[N m s/rad\] (bearing and accessory losses).
        #[serde(default)]
        damping: f64,
        /// A decoupler between the pulley and the accessory ([`Decoupler`]; none: the
        /// accessory is rigid on the pulley). With one, `inertia`, `torque` and `damping` are
        /// the accessory's and the pulley hub has [`Decoupler::pulley_inertia`].
        #[serde(default, skip_serializing_if = "Option::is_none")]
        decoupler: Option<Decoupler>,
    },
    /// Free with inertia and no load (an idler), optionally with a viscous damper.
    Idler {
        /// Moment of inertia \[kg m²\].
        inertia: f64,
        /// Viscous rotational damping `c` \[N m s/rad\].
        #[serde(default)]
        damping: f64,
    },
}

/// Role of a pulley in a drive's reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Role {
    /// Speed-driven (the driver).
    Driver,
    /// Free with a load torque (a driven accessory).
    Driven,
    /// Free without load.
    Idler,
}

impl Motion {
    /// A free pulley with inertia \[kg m²\] and a load torque \[N m\], undamped.
    pub fn load(inertia: f64, torque: Signal) -> Self {
        Motion::Load {
            inertia,
            torque,
            damping: 0.0,
            decoupler: None,
        }
    }

    /// The decoupler of a loaded pulley (`None`: none, or not a loaded pulley).
    pub fn decoupler(&self) -> Option<&Decoupler> {
        match self {
            Motion::Load { decoupler, .. } => decoupler.as_ref(),
            _ => None,
        }
    }

    /// Moment of inertia \[kg m²\] on the pulley's own rotation coordinate: the hub's
    /// [`Decoupler::pulley_inertia`] behind a decoupler, else [`Self::inertia`] (`None`:
    /// speed-driven).
    pub fn pulley_inertia(&self) -> Option<f64> {
        match self.decoupler() {
            Some(d) => Some(d.pulley_inertia),
            None => self.inertia(),
        }
    }

    /// An undamped idler with inertia \[kg m²\].
    pub fn idler(inertia: f64) -> Self {
        Motion::Idler {
            inertia,
            damping: 0.0,
        }
    }

    /// A speed-driven pulley.
    pub fn speed(speed: Signal) -> Self {
        Motion::Speed { speed }
    }

    /// Whether the pulley has its own rotation coordinate (not speed-driven).
    pub fn is_free(&self) -> bool {
        !matches!(self, Motion::Speed { .. })
    }

    /// The role in reports: speed → driver, load → driven, idler → idler.
    pub fn role(&self) -> Role {
        match self {
            Motion::Speed { .. } => Role::Driver,
            Motion::Load { .. } => Role::Driven,
            Motion::Idler { .. } => Role::Idler,
        }
    }

    /// Moment of inertia \[kg m²\] of a free pulley, the accessory's behind a decoupler
    /// (`None`: speed-driven).
    pub fn inertia(&self) -> Option<f64> {
        match self {
            Motion::Speed { .. } => None,
            Motion::Load { inertia, .. } | Motion::Idler { inertia, .. } => Some(*inertia),
        }
    }

    /// Viscous damping \[N m s/rad\] (0 for a speed-driven pulley).
    pub fn damping(&self) -> f64 {
        match self {
            Motion::Speed { .. } => 0.0,
            Motion::Load { damping, .. } | Motion::Idler { damping, .. } => *damping,
        }
    }

    /// Prescribed speed \[rad/s\] at `t` (`None`: free).
    pub fn prescribed_speed(&self, t: f64) -> Option<f64> {
        match self {
            Motion::Speed { speed } => Some(speed.value(t)),
            _ => None,
        }
    }

    /// Load torque \[N m\] at `t` (0 for idlers and speed-driven pulleys).
    pub fn load_torque(&self, t: f64) -> f64 {
        match self {
            Motion::Load { torque, .. } => torque.value(t),
            _ => 0.0,
        }
    }

    /// Torque on a free pulley other than the belt's \[N m\], travel sense, at speed `omega`
    /// \[rad/s\]: `−M_load(t) − c ω`, and its derivative with respect to `ω` (module
    /// documentation). Behind a decoupler this is the torque on the accessory at its speed
    /// `omega` (the pulley feels it only through the spring: [`Decoupler::forces`]; in a
    /// steady state, engaged, the two speeds and torques are equal).
    pub fn applied_torque(&self, t: f64, omega: f64) -> (f64, f64) {
        let c = self.damping();
        (-self.load_torque(t) - c * omega, -c)
    }

    /// The same motion at rest: speed zero, or free with its inertia and damping but no load
    /// (for the static equilibrium of the mounted belt).
    pub fn at_rest(&self) -> Self {
        match self {
            Motion::Speed { .. } => Motion::speed(Signal::constant(0.0)),
            Motion::Load {
                inertia,
                damping,
                decoupler,
                ..
            } => Motion::Load {
                inertia: *inertia,
                torque: Signal::constant(0.0),
                damping: *damping,
                decoupler: *decoupler,
            },
            m @ Motion::Idler { .. } => m.clone(),
        }
    }

    /// The signal of a speed-driven pulley or a loaded one.
    pub fn signal(&self) -> Option<&Signal> {
        match self {
            Motion::Speed { speed } => Some(speed),
            Motion::Load { torque, .. } => Some(torque),
            Motion::Idler { .. } => None,
        }
    }

    /// Mutable [`Self::signal`].
    pub fn signal_mut(&mut self) -> Option<&mut Signal> {
        match self {
            Motion::Speed { speed } => Some(speed),
            Motion::Load { torque, .. } => Some(torque),
            Motion::Idler { .. } => None,
        }
    }
}

impl Validate for Motion {
    /// The error names the field relative to the motion (`inertia`, `torque.knots[1]`, …).
    fn validate(&self) -> Result<(), InvalidField> {
        match self {
            Motion::Speed { speed } => speed.validate_within("speed"),
            Motion::Load {
                inertia,
                torque,
                damping,
                decoupler,
            } => {
                check::positive("inertia", *inertia, "kg m²")?;
                check::non_negative("damping", *damping, "N m s/rad")?;
                if let Some(d) = decoupler {
                    d.validate_within("decoupler")?;
                }
                torque.validate_within("torque")
            }
            Motion::Idler { inertia, damping } => {
                check::positive("inertia", *inertia, "kg m²")?;
                check::non_negative("damping", *damping, "N m s/rad")
            }
        }
    }
}
