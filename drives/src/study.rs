//! The belt models a study can run on one drive ([`ModelKind`]), their settings
//! ([`ModelSettings`]), and the speed-loss study of Ribaric §6.4–6.5 (Figs. 6-6, 6-7): one case
//! per driver speed, each the procedure of [`crate::speed_loss`] on a fresh model, with
//! Bechtel's line (6.3) at the same torques.

use crate::analytical::{bechtel, euler_eytelwein_capacity};
use crate::ancf_model::{AncfBelt, AncfConfig, AncfMapping};
use crate::error::DriveError;
use crate::speed_loss::speed_loss_sweep;
use crate::speed_loss::{Sample, SpeedLossConfig, SpeedLossPoint, SweepFailure, SweepStats};
use belt::{BeltModel, Drive};
use flowing::belt::{AxialForce, BeltMesh, FlowingBelt, FlowingSettings, NodalBelt};
use mbd_core::SecondOrderSystem;
use mbd_core::integrators::State;
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// Belt model of a study.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema, Default,
)]
#[serde(rename_all = "lowercase")]
pub enum ModelKind {
    /// Flowing-material modal model with a stationary mesh (Ribaric (5.14)).
    #[default]
    Flowing,
    /// ANCF belt elements in a rotating (Lagrangian) mesh, Kerkkänen ch. 3 (the geometrically
    /// exact reference; [`crate::ancf_model`]).
    Ancf,
    /// Nodal model with a rotating (Lagrangian) mesh (Ribaric (5.7)): the reference the
    /// flowing form replaces; needs a fine uniform mesh ([`NodalConfig::mesh`]).
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
/// longer averaging window over its element-passing ripple.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct NodalConfig {
    /// Mesh of the rotating loop (default: 5.6 mm everywhere, 216 elements on Table 6-1).
    pub mesh: BeltMesh,
    /// Averaging window of the speed-loss procedure \[s\]: the interval between the two means
    /// its steady test compares; the means themselves span the fewest whole loop passages that
    /// cover a window (the mesh travels with the material,
    /// [`crate::speed_loss::averaging_steps`]).
    pub window: f64,
    /// Steady-state tolerance between consecutive windows of the speed-loss procedure
    /// \[rad/s\].
    pub tolerance: f64,
    /// The elements' axial force (default: co-rotated).
    pub axial_force: AxialForce,
}

impl Default for NodalConfig {
    /// 5.625 mm on the spans (80 per 450 mm span), 5.61 mm on the wraps (28 per half-wrap of
    /// Table 6-1); 0.1 s windows, 10⁻³ rad/s.
    fn default() -> Self {
        Self {
            mesh: BeltMesh {
                span_element: 0.005625,
                arc_element: 0.00561,
                contact_margin_nodes: 1,
            },
            window: 0.1,
            tolerance: 1e-3,
            axial_force: AxialForce::CoRotated,
        }
    }
}

impl Validate for NodalConfig {
    fn validate(&self) -> Result<(), InvalidField> {
        self.mesh.validate_within("mesh")?;
        check::within("window", self.window, 1e-6, 100.0, "s")?;
        check::within("tolerance", self.tolerance, 1e-12, 1e3, "rad/s")
    }
}

/// Each model's discretisation settings (one table per model in a study's configuration).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema, Default)]
#[serde(default, deny_unknown_fields)]
pub struct ModelSettings {
    /// The flowing-material model's loop and reduction.
    pub flowing: FlowingSettings,
    /// The nodal model's loop (and its speed-loss window).
    pub nodal: NodalConfig,
    /// The ANCF belt's discretisation and step.
    pub ancf: AncfConfig,
}

impl Validate for ModelSettings {
    fn validate(&self) -> Result<(), InvalidField> {
        self.flowing.validate_within("flowing")?;
        self.nodal.validate_within("nodal")?;
        self.ancf.validate_within("ancf")
    }
}

/// A belt model built for a drive: one of the three kinds.
pub enum AnyModel {
    /// The flowing-material belt (Ribaric (5.14)).
    Flowing(Box<FlowingBelt>),
    /// The rotating-mesh nodal belt (Ribaric (5.7)).
    Nodal(Box<NodalBelt>),
    /// The ANCF belt (Kerkkänen ch. 3).
    Ancf(Box<AncfBelt>),
}

/// Run a generic function on the model inside an [`AnyModel`].
#[macro_export]
macro_rules! with_model {
    ($any:expr, |$m:ident| $body:expr) => {
        match $any {
            $crate::study::AnyModel::Flowing($m) => $body,
            $crate::study::AnyModel::Nodal($m) => $body,
            $crate::study::AnyModel::Ancf($m) => $body,
        }
    };
}

impl AnyModel {
    /// Build the model `kind` of `drive` with its settings from `settings`.
    pub fn new(
        kind: ModelKind, drive: &Drive, settings: &ModelSettings,
    ) -> Result<Self, DriveError> {
        Ok(match kind {
            ModelKind::Flowing => {
                AnyModel::Flowing(Box::new(FlowingBelt::new(drive, &settings.flowing)?))
            }
            ModelKind::Nodal => AnyModel::Nodal(Box::new(
                NodalBelt::new(drive, &settings.nodal.mesh)?
                    .with_axial_force(settings.nodal.axial_force),
            )),
            ModelKind::Ancf => AnyModel::Ancf(Box::new(AncfBelt::new(drive, &settings.ancf)?)),
        })
    }

    /// Number of coordinates of the model.
    pub fn coordinates(&self) -> usize {
        with_model!(self, |m| m.n_q())
    }

    /// The derived parameters of the drive → ANCF mapping (ANCF model only).
    pub fn ancf_mapping(&self) -> Option<&AncfMapping> {
        match self {
            AnyModel::Ancf(a) => Some(a.mapping()),
            _ => None,
        }
    }
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
    /// Euler–Eytelwein capacity of the drive at this speed \[N m\]
    /// ([`crate::euler_eytelwein_capacity`]; `NaN` for drives other than two pulleys).
    pub capacity: f64,
    /// Coefficient μ of the friction law on each pulley's wrap, travel order
    /// ([`belt::Drive::wrap_friction_coefficients`]: `μ/sin(β/2)` on the grooved pulleys of a
    /// multi-ribbed belt; the utilisation of the wrap points).
    pub friction_coefficients: Vec<f64>,
    /// Integration statistics.
    pub stats: SweepStats,
}

/// The procedure's settings for the model `kind`: the nodal model's window and tolerance, the
/// ANCF belt's own step.
pub fn procedure_for(
    kind: ModelKind, procedure: &SpeedLossConfig, settings: &ModelSettings,
) -> SpeedLossConfig {
    let mut p = procedure.clone();
    match kind {
        ModelKind::Nodal => {
            p.window = settings.nodal.window;
            p.tolerance = settings.nodal.tolerance;
        }
        ModelKind::Ancf => p.step = settings.ancf.step,
        ModelKind::Flowing => {}
    }
    p
}

/// Run the speed-loss procedure ([`speed_loss_sweep`]) on `model` with `settings` (already
/// adapted to the model: [`procedure_for`]), with Bechtel's line and the capacity of its drive
/// at the same torques. `observer` sees every step.
pub fn speed_loss_case(
    model: &mut AnyModel, settings: &SpeedLossConfig, observer: impl FnMut(&State, Sample),
) -> Result<SpeedLossCase, SweepFailure> {
    let (points, stats) = with_model!(model, |m| speed_loss_sweep(m.as_mut(), settings, observer))?;
    let drive = with_model!(model, |m| m.drive().clone());
    Ok(SpeedLossCase {
        omega_driver: settings.omega_driver,
        capacity: euler_eytelwein_capacity(&drive, settings.omega_driver),
        friction_coefficients: drive.wrap_friction_coefficients(),
        analytical: points
            .iter()
            .map(|p| bechtel(&drive, p.torque, settings.omega_driver))
            .collect(),
        points,
        stats,
    })
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

    // the nodal procedure takes its window and tolerance from the nodal options, the ANCF one
    // its step; the flowing one keeps the procedure as given (definition of the study)
    #[test]
    fn each_model_gets_its_procedure_settings() {
        let (p, s) = (SpeedLossConfig::default(), ModelSettings::default());
        assert_eq!(procedure_for(ModelKind::Flowing, &p, &s), p);
        let n = procedure_for(ModelKind::Nodal, &p, &s);
        assert_eq!((n.window, n.tolerance), (s.nodal.window, s.nodal.tolerance));
        assert_eq!(procedure_for(ModelKind::Ancf, &p, &s).step, s.ancf.step);
    }

    // the nodal default mesh is Table 6-1's former 80 per span and 28 per wrap
    #[test]
    fn nodal_default_mesh_counts() {
        let d = crate::table_6_1::drive();
        let counts = NodalConfig::default().mesh.counts(d.path());
        assert_eq!(counts, vec![80, 28, 80, 28]);
        assert_eq!(
            FlowingSettings::default().mesh.counts(d.path()),
            vec![10, 18, 10, 18]
        );
    }
}
