//! The one model shell of the ANCF belt drives: an ANCF discretisation of a resolved drive
//! ([`belt::Drive`]), mounted (its static state solved), as a [`belt::BeltModel`] and a
//! [`SecondOrderSystem`] (issue 33: the planar belt of Kerkkänen ch. 3,
//! [`crate::belt_drive::AncfBelt`], and the plate belt of ch. 4,
//! [`crate::plate::belt_drive::PlateBelt`], are the same shell around the same drive).
//!
//! The drive is one over the dimension, [`AncfBeltDrive`]: its description ([`DriveSpec`]),
//! the path, the pulleys' coordinates, the system matrices' pattern and mass, the accessors
//! and what the shell asks of it ([`AncfDrive`]) are written once; what differs between the
//! discretisations — the elements, the mounted state's type, the reported quantities
//! (snapshot, belt speed, span offsets, the tensioner arm) — is the extension point
//! [`DriveKind`]. The pulleys' motions and speeds, the equations of motion and the initial
//! state are the shell's.

mod drive;
mod equations;
pub(crate) mod pulleys;
mod resting;
mod spec;

pub(crate) use equations::ancf_equations;

pub use drive::{AncfBeltDrive, DriveKind};
pub use pulleys::{MAX_PULLEYS, PulleyCoordinates, validate_pulleys};
pub use resting::InitialOptions;
pub(crate) use resting::{Linearisation, RestingBelt, solve_resting};
pub use spec::DriveSpec;

use belt::{BeltModel, Drive, ModelTraits, Motion, Snapshot};
use mbd_core::integrators::State;
use mbd_core::{MbdError, SecondOrderSystem};

/// Refuse a drive with a decoupler ([`belt::decoupler`]) for the ANCF discretisation `model`
/// (`"ancf"`, `"plate"`): their pulleys are single rigid bodies without the spring, carrier
/// and accessory coordinates of (D1)–(D3). The error names the field
/// (`pulleys[k].motion.decoupler`) and the models that do support it (flowing, nodal).
pub fn refuse_decouplers(drive: &Drive, model: &str) -> Result<(), crate::AncfError> {
    match drive
        .pulleys()
        .iter()
        .position(|p| p.motion.decoupler().is_some())
    {
        Some(k) => Err(crate::error::invalid(
            format!("pulleys[{k}].motion.decoupler"),
            format!(
                "the {model} belt model has no decoupler (spring, one-way clutch): use the \
                 flowing or nodal model"
            ),
        )),
        None => Ok(()),
    }
}

/// What both ANCF discretisations take from a resolved drive (the mapping tables of
/// [`crate::belt_drive::belt_model`] and [`crate::plate::belt_drive::belt_model`]): a
/// rectangular section of width `b` and thickness `h = √(12 EI/EA)` with `E = EA/(b h)` and
/// `ρ = ρA/(b h)`, and the pulleys at the contact radius `R + p₀`, `p₀` the penalty
/// penetration under the mounting pressure `T0/R`
/// ([`belt::BeltContact::mounting_penetration`]), so that the belt centreline sinks by `p₀`
/// onto the path of radius `R`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct MappedDrive {
    /// The pulleys with their contact radii.
    pub pulleys: Vec<belt::Pulley>,
    /// `p₀` of each pulley \[m\].
    pub penetration: Vec<f64>,
    /// Section thickness `h` \[m\].
    pub thickness: f64,
    /// Young's modulus `E` \[Pa\].
    pub young: f64,
    /// Density `ρ` \[kg/m³\].
    pub density: f64,
}

impl MappedDrive {
    /// The mapping of `drive` with the section width `width` \[m\].
    pub fn of(drive: &Drive, width: f64) -> Self {
        let b = drive.belt();
        let t0 = drive.tension();
        let thickness = (12.0 * b.ei / b.ea).sqrt();
        let area = width * thickness;
        let penetration: Vec<f64> = drive
            .pulleys()
            .iter()
            .map(|p| drive.contact().mounting_penetration(t0, p.radius))
            .collect();
        let pulleys = drive
            .pulleys()
            .iter()
            .zip(&penetration)
            .map(|(p, &p0)| belt::Pulley {
                radius: p.radius + p0,
                ..p.clone()
            })
            .collect();
        Self {
            pulleys,
            penetration,
            thickness,
            young: b.ea / area,
            density: b.mass_per_length / area,
        }
    }
}

/// An ANCF belt drive that [`MountedBelt`] wraps (module documentation): its equations of
/// motion ([`SecondOrderSystem`]) and what a [`BeltModel`] reports of it; implemented once,
/// for [`AncfBeltDrive`] of every [`DriveKind`].
pub trait AncfDrive: SecondOrderSystem {
    /// The mounted static state.
    type Initial;
    /// The derived parameters of the drive → discretisation mapping (for reports).
    type Mapping;

    /// What the model is ([`BeltModel::traits`]).
    fn model_traits(&self) -> ModelTraits;
    /// The coordinates of the mounted static state.
    fn initial_q(initial: &Self::Initial) -> &[f64];
    /// The drive's pulleys (travel order).
    fn drive_pulleys(&self) -> &[belt::Pulley];
    /// The belt's path over the pulleys (its spans and wraps).
    fn drive_path(&self) -> &belt::BeltPath;
    /// Which pulleys have an angle coordinate.
    fn pulley_coordinates(&self) -> &PulleyCoordinates;
    /// How pulley `k` turns, to change it.
    fn pulley_motion_mut(&mut self, k: usize) -> Option<&mut Motion>;
    /// How pulley `k` turns.
    fn pulley_motion(&self, k: usize) -> Option<&Motion> {
        self.drive_pulleys().get(k).map(|p| &p.motion)
    }
    /// Speed of pulley `k` in its travel sense \[rad/s\] ([`PulleyCoordinates::speed`]).
    fn travel_speed(&self, k: usize, t: f64, v: &[f64]) -> f64 {
        self.pulley_coordinates()
            .speed(self.drive_pulleys(), k, t, v)
    }
    /// Tensioner arm angle \[rad\] (`None`: no arm).
    fn arm_angle_at(&self, q: &[f64]) -> Option<f64>;
    /// Mean belt speed along the centreline \[m/s\].
    fn mean_belt_speed(&self, q: &[f64], v: &[f64]) -> f64;
    /// Pulleys, spans and wrap points at the state ([`BeltModel::snapshot`]).
    fn snapshot_at(&self, t: f64, q: &[f64], v: &[f64]) -> Result<Snapshot, MbdError>;
    /// [`Self::snapshot_at`] without the wrap points' recovered tension
    /// ([`BeltModel::report_snapshot`]). Default: [`Self::snapshot_at`].
    fn report_snapshot_at(&self, t: f64, q: &[f64], v: &[f64]) -> Result<Snapshot, MbdError> {
        self.snapshot_at(t, q, v)
    }
    /// Transverse offset of each span's middle from its line \[m\].
    fn span_offsets(&self, q: &[f64]) -> Result<Vec<f64>, MbdError>;
    /// Number of belt elements along the belt.
    fn belt_elements(&self) -> usize;
}

/// A mounted ANCF belt of a drive (module documentation).
pub struct MountedBelt<D: AncfDrive> {
    drive: D,
    layout: Drive,
    initial: D::Initial,
    mapping: D::Mapping,
}

impl<D: AncfDrive> MountedBelt<D> {
    /// The shell around the discretisation `drive` of `layout` mounted at `initial`.
    pub(crate) fn from_parts(
        drive: D, layout: &Drive, initial: D::Initial, mapping: D::Mapping,
    ) -> Self {
        Self {
            drive,
            layout: layout.clone(),
            initial,
            mapping,
        }
    }

    /// The underlying ANCF drive.
    pub fn belt_drive(&self) -> &D {
        &self.drive
    }

    /// The derived parameters of the mapping.
    pub fn mapping(&self) -> &D::Mapping {
        &self.mapping
    }

    /// The mounted static state.
    pub fn initial(&self) -> &D::Initial {
        &self.initial
    }

    /// Static arm angle of the tensioner \[rad\] (`None`: no tensioner).
    pub fn static_arm_angle(&self) -> Option<f64> {
        self.drive.arm_angle_at(D::initial_q(&self.initial))
    }
}

impl<D: AncfDrive> SecondOrderSystem for MountedBelt<D> {
    mbd_core::forward_dynamics!(drive);
}

impl<D: AncfDrive> BeltModel for MountedBelt<D> {
    fn drive(&self) -> &Drive {
        &self.layout
    }

    fn traits(&self) -> ModelTraits {
        self.drive.model_traits()
    }

    /// The belt's equal elements (the planar belt's beam elements, Kerkkänen (3.1); the plate
    /// belt's elements along the belt, (4.1)): the mounted belt length over their number.
    fn material_element(&self) -> Option<f64> {
        Some(self.layout.belt_length() / self.drive.belt_elements().max(1) as f64)
    }

    /// The mounted static state, at rest.
    fn initial_state(&self) -> Result<State, MbdError> {
        let q = D::initial_q(&self.initial).to_vec();
        let n = q.len();
        Ok(State::new(0.0, q, vec![0.0; n]))
    }

    fn motion(&self, k: usize) -> Option<&Motion> {
        self.drive.pulley_motion(k)
    }

    fn motion_mut(&mut self, k: usize) -> Option<&mut Motion> {
        self.drive.pulley_motion_mut(k)
    }

    fn pulley_speed(&self, k: usize, t: f64, v: &[f64]) -> f64 {
        self.drive.travel_speed(k, t, v)
    }

    fn arm_angle(&self, q: &[f64]) -> Option<f64> {
        self.drive.arm_angle_at(q)
    }

    fn belt_speed(&self, q: &[f64], v: &[f64]) -> f64 {
        self.drive.mean_belt_speed(q, v)
    }

    fn snapshot(&self, t: f64, q: &[f64], v: &[f64]) -> Result<Snapshot, MbdError> {
        self.drive.snapshot_at(t, q, v)
    }

    fn report_snapshot(&self, t: f64, q: &[f64], v: &[f64]) -> Result<Snapshot, MbdError> {
        self.drive.report_snapshot_at(t, q, v)
    }

    fn span_transverse(&self, q: &[f64]) -> Result<Vec<f64>, MbdError> {
        self.drive.span_offsets(q)
    }
}
