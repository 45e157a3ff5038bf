//! Pulleys of a planar belt drive: rigid circles rotating about fixed centres, either driven
//! by a prescribed speed history or free with an inertia and a load torque (Kerkkänen §3.2,
//! (3.25)–(3.26)).

use super::profile::{SpeedProfile, TorqueProfile};
use fe_model::generate::belt_path::{PathPulley, WrapSide};
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};

/// How a pulley moves.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum PulleyDrive {
    /// Angular speed prescribed by a history (the driver of Kerkkänen (3.29)); no coordinate.
    Speed {
        /// Speed history \[rad/s\] in the travel sense.
        speed: SpeedProfile,
    },
    /// Free rotation about the fixed centre with inertia `I` \[kg·m²\] and a load torque
    /// opposing the rotation, Kerkkänen (3.26); its angle is a coordinate of the system.
    Free {
        /// Mass moment of inertia `I` \[kg·m²\].
        inertia: f64,
        /// Load torque history \[N·m\].
        load: TorqueProfile,
    },
}

/// A pulley: centre \[m\], radius \[m\] (the belt centreline's contact radius: belt thickness is
/// not part of the contact geometry, Kerkkänen §3.2), wrap side and drive.
///
/// Speeds are counted in the **travel sense**: positive when the pulley surface moves with the
/// belt running along the path direction of [`fe_model::generate::belt_path::BeltPath`]
/// (clockwise for pulleys inside the loop, counter-clockwise for back-side idlers).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pulley {
    /// Name used in messages and output files.
    pub name: String,
    /// Centre (x, y) \[m\].
    pub center: [f64; 2],
    /// Radius \[m\].
    pub radius: f64,
    /// Wrap side.
    #[serde(default)]
    pub side: WrapSide,
    /// Drive.
    pub drive: PulleyDrive,
}

impl PulleyDrive {
    /// Whether a pulley with this drive has its own rotation coordinate.
    pub fn is_free(&self) -> bool {
        matches!(self, PulleyDrive::Free { .. })
    }
}

/// `+1` if a positive travel-sense speed of a pulley wrapped on `side` is counter-clockwise,
/// `−1` if clockwise: the belt path runs clockwise around pulleys inside the loop.
pub fn ccw_sign(side: WrapSide) -> f64 {
    match side {
        WrapSide::Inside => -1.0,
        WrapSide::Outside => 1.0,
    }
}

impl Pulley {
    /// The pulley as a circle of the belt path (centre, radius, wrap side), Kerkkänen §3.4.
    pub fn path_pulley(&self) -> PathPulley {
        PathPulley {
            center: self.center,
            radius: self.radius,
            side: self.side,
        }
    }

    /// [`ccw_sign`] of the pulley's wrap side.
    pub fn ccw_sign(&self) -> f64 {
        ccw_sign(self.side)
    }

    /// Whether the pulley has its own rotation coordinate.
    pub fn is_free(&self) -> bool {
        self.drive.is_free()
    }
}

impl Validate for Pulley {
    /// Every field checked; the error names the field (path relative to this struct).
    fn validate(&self) -> Result<(), InvalidField> {
        let f = |x: &str| format!("pulley \"{}\": {x}", self.name);
        if !(self.center[0].is_finite() && self.center[1].is_finite()) {
            return Err(InvalidField::new(f("center"), "must be finite"));
        }
        if !(self.radius.is_finite() && self.radius > 0.0) {
            return Err(InvalidField::new(
                f("radius"),
                format!("must be > 0 m, got {}", self.radius),
            ));
        }
        match &self.drive {
            PulleyDrive::Speed { speed } => {
                speed.validate().map_err(|e| e.within(&f("drive.speed")))
            }
            PulleyDrive::Free { inertia, load } => {
                if !(inertia.is_finite() && *inertia > 0.0) {
                    return Err(InvalidField::new(
                        f("drive.inertia"),
                        format!("must be > 0 kg·m², got {inertia}"),
                    ));
                }
                load.validate().map_err(|e| e.within(&f("drive.load")))
            }
        }
    }
}
