//! The speed-loss study of Ribaric §6.4–6.5 (Figs. 6-6, 6-7) for a chosen belt model: one case
//! per driver speed, each the procedure of [`crate::speed_loss`] on a fresh model, with
//! Bechtel's line (6.3) at the same torques. The app only reads the configuration, calls
//! [`SpeedLossModel::new`] and [`SpeedLossModel::sweep`] per speed, and writes the results.

use crate::analytical::{bechtel, euler_eytelwein_capacity};
use crate::ancf_drive_model::{AncfConfig, AncfDrive, AncfMapping};
use crate::error::DriveError;
use crate::speed_loss::speed_loss_sweep;
use crate::speed_loss::{Sample, SpeedLossConfig, SpeedLossPoint, SweepFailure, SweepStats};
use contact::friction::FrictionLaw;
use flowing::belt::config::BeltMesh;
use flowing::belt::nodal::NodalBelt;
use flowing::belt::{BeltDriveConfig, BeltFe, FlowingBelt, Schedule};
use mbd_core::SecondOrderSystem;
use mbd_core::integrators::State;
use serde::{Deserialize, Serialize};

/// Belt model used for the study.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum ModelKind {
    /// Flowing-material modal model with a stationary mesh (Ribaric (5.14)).
    #[default]
    Flowing,
    /// ANCF belt elements in a rotating (Lagrangian) mesh, Kerkkänen ch. 3 (the high-fidelity
    /// reference; [`crate::ancf_drive_model`]).
    Ancf,
    /// Nodal model with a rotating (Lagrangian) mesh (Ribaric (5.7)): the reference the
    /// flowing form replaces; needs a fine uniform mesh ([`NodalConfig::mesh`]) to be accurate.
    Nodal,
}

impl ModelKind {
    /// Every model, in the order of the command-line help.
    pub const ALL: [ModelKind; 3] = [ModelKind::Flowing, ModelKind::Ancf, ModelKind::Nodal];

    /// The lower-case name used in configuration files, on the command line and in plots.
    pub fn name(self) -> &'static str {
        match self {
            ModelKind::Flowing => "flowing",
            ModelKind::Nodal => "nodal",
            ModelKind::Ancf => "ancf",
        }
    }
}

impl std::str::FromStr for ModelKind {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        ModelKind::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| format!("unknown belt model `{s}` (flowing, ancf or nodal)"))
    }
}

/// What the rotating-mesh model needs to reach an accurate steady state: a fine uniform loop
/// (its elements travel over the pulleys, so short arc elements alone do not help) and a
/// longer averaging window over its element-passing ripple. With the defaults its Δω agrees
/// with the flowing model's within 2 % (tests/tests/flowing_belt_nodal.rs); on the
/// 56-element flowing mesh its polygonal ripple (±1 rad/s) prevents any steady state.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct NodalConfig {
    /// Mesh of the rotating loop (default: uniform, 216 elements of 5.6 mm).
    pub mesh: BeltMesh,
    /// Averaging window \[s\].
    pub window: f64,
    /// Steady-state tolerance between consecutive windows \[rad/s\].
    pub tolerance: f64,
}

impl Default for NodalConfig {
    fn default() -> Self {
        Self {
            mesh: BeltMesh {
                span_elements: 80,
                arc_elements: 28,
                contact_margin_nodes: 1,
            },
            window: 0.1,
            tolerance: 1e-3,
        }
    }
}

/// The drive and the procedure of the case at driver speed `omega` \[rad/s\]: `procedure` with
/// `omega_driver = omega`; for the nodal model, its mesh, window and tolerance from `nodal`.
pub fn case_inputs(
    model: ModelKind,
    drive: &BeltDriveConfig,
    procedure: &SpeedLossConfig,
    nodal: &NodalConfig,
    omega: f64,
) -> (BeltDriveConfig, SpeedLossConfig) {
    let mut settings = SpeedLossConfig {
        omega_driver: omega,
        ..procedure.clone()
    };
    let mut drive = *drive;
    if model == ModelKind::Nodal {
        drive.mesh = nodal.mesh;
        settings.window = nodal.window;
        settings.tolerance = nodal.tolerance;
    }
    (drive, settings)
}

/// One driver speed's result.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeedLossCase {
    /// Driver speed \[rad/s\].
    pub omega_driver: f64,
    /// Steady points.
    pub points: Vec<SpeedLossPoint>,
    /// Bechtel's Δω (6.3) at the same torques \[rad/s\].
    pub analytical: Vec<f64>,
    /// Euler–Eytelwein capacity of the drive at this speed \[N·m\]
    /// ([`crate::euler_eytelwein_capacity`]).
    pub capacity: f64,
    /// Coefficient μ of the belt–pulley friction law.
    pub friction_coefficient: f64,
    /// Integration statistics.
    pub stats: SweepStats,
}

/// A belt model built for the speed-loss procedure.
pub enum SpeedLossModel {
    /// The flowing-material belt (Ribaric (5.14)).
    Flowing(Box<FlowingBelt>),
    /// The rotating-mesh nodal belt (Ribaric (5.7)).
    Nodal(Box<NodalBelt>),
    /// The ANCF belt drive (Kerkkänen ch. 3) with its own generalized-α step \[s\]
    /// ([`AncfConfig::step`], which replaces the procedure's).
    Ancf {
        /// The adapted drive.
        drive: Box<AncfDrive>,
        /// Generalized-α step \[s\].
        step: f64,
    },
}

impl SpeedLossModel {
    /// Build `kind` for the drive `drive` (Table 6-1 fields); `ancf` is read by the ANCF model
    /// only.
    pub fn new(
        kind: ModelKind,
        drive: &BeltDriveConfig,
        ancf: &AncfConfig,
    ) -> Result<Self, DriveError> {
        let (driver, load) = (Schedule::constant(0.0), Schedule::constant(0.0));
        Ok(match kind {
            ModelKind::Flowing => SpeedLossModel::Flowing(Box::new(FlowingBelt::new(
                BeltFe::new(drive)?,
                driver,
                load,
            )?)),
            ModelKind::Nodal => {
                SpeedLossModel::Nodal(Box::new(NodalBelt::new(BeltFe::new(drive)?, driver, load)?))
            }
            ModelKind::Ancf => SpeedLossModel::Ancf {
                drive: Box::new(AncfDrive::new(drive, ancf)?),
                step: ancf.step,
            },
        })
    }

    /// Number of coordinates: modal + belt + pulley (flowing), nodal + belt + pulley (nodal),
    /// or the ANCF drive's coordinates.
    pub fn coordinates(&self) -> usize {
        match self {
            SpeedLossModel::Flowing(b) => b.n_modes() + 2,
            SpeedLossModel::Nodal(b) => b.n_nodal() + 2,
            SpeedLossModel::Ancf { drive, .. } => drive.drive().n_q(),
        }
    }

    /// Whether the first velocity is the belt speed \[m/s\] (flowing and nodal models).
    pub fn has_belt_speed(&self) -> bool {
        !matches!(self, SpeedLossModel::Ancf { .. })
    }

    /// The derived parameters of the Table 6-1 → ANCF mapping (ANCF model only).
    pub fn ancf_mapping(&self) -> Option<&AncfMapping> {
        match self {
            SpeedLossModel::Ancf { drive, .. } => Some(drive.mapping()),
            _ => None,
        }
    }

    /// Run the procedure ([`speed_loss_sweep`]) with `settings` (the ANCF model's own step
    /// replaces `settings.step`) and Bechtel's line for the drive `drive` at the same torques.
    /// `observer` sees every step.
    pub fn sweep(
        &mut self,
        drive: &BeltDriveConfig,
        settings: &SpeedLossConfig,
        observer: impl FnMut(&State, Sample),
    ) -> Result<SpeedLossCase, SweepFailure> {
        let (points, stats) = match self {
            SpeedLossModel::Flowing(b) => speed_loss_sweep(b.as_mut(), settings, observer),
            SpeedLossModel::Nodal(b) => speed_loss_sweep(b.as_mut(), settings, observer),
            SpeedLossModel::Ancf { drive, step } => {
                let settings = SpeedLossConfig {
                    step: *step,
                    ..settings.clone()
                };
                speed_loss_sweep(drive.as_mut(), &settings, observer)
            }
        }?;
        Ok(SpeedLossCase {
            omega_driver: settings.omega_driver,
            capacity: euler_eytelwein_capacity(drive, settings.omega_driver),
            friction_coefficient: drive.contact.friction_law().coefficient(),
            analytical: points
                .iter()
                .map(|p| bechtel(drive, p.torque, settings.omega_driver))
                .collect(),
            points,
            stats,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // names round-trip through FromStr (the command line) and serde (configuration files)
    #[test]
    fn model_names_parse_back() {
        for m in ModelKind::ALL {
            assert_eq!(m.name().parse::<ModelKind>(), Ok(m));
            assert_eq!(
                serde_json::to_string(&m).unwrap(),
                format!("\"{}\"", m.name())
            );
        }
        assert!("tire".parse::<ModelKind>().is_err());
    }

    // the nodal case takes its mesh, window and tolerance from the nodal options; the others
    // keep the drive and procedure as given (definition of the study)
    #[test]
    fn case_inputs_apply_the_nodal_options_to_the_nodal_model_only() {
        let (d, p, n) = (
            BeltDriveConfig::default(),
            SpeedLossConfig::default(),
            NodalConfig::default(),
        );
        let (d1, s1) = case_inputs(ModelKind::Flowing, &d, &p, &n, 22.6);
        assert_eq!(d1, d);
        assert_eq!(s1.omega_driver, 22.6);
        assert_eq!(s1.window, p.window);
        let (d2, s2) = case_inputs(ModelKind::Nodal, &d, &p, &n, 22.6);
        assert_eq!(d2.mesh, n.mesh);
        assert_eq!((s2.window, s2.tolerance), (n.window, n.tolerance));
    }
}
