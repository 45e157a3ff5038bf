//! The one ANCF belt drive over the dimension (issue 33 item 2): [`AncfBeltDrive`] holds what
//! the planar drive (Kerkkänen ch. 3, [`crate::belt_drive::BeltDrive`]) and the plate drive
//! (ch. 4, [`crate::plate::belt_drive::PlateBeltDrive`]) share — the drive description
//! ([`DriveSpec`]), the belt's path over the pulleys, the pulleys' coordinates, the sparsity
//! pattern of the system matrices and the constant mass (2.26) with the pulleys' inertias
//! (3.26) — around the discretisation `K` ([`DriveKind`]: the elements, the contact, what the
//! drive reports).

use super::{AncfDrive, DriveSpec, PulleyCoordinates};
use crate::sparse::Pattern;
use belt::{BeltPath, ModelTraits, Motion, Pulley, Snapshot};
use mbd_core::{MbdError, SecondOrderSystem};

/// What differs between the ANCF belt drives (module documentation): the belt and contact
/// parameters of the [`DriveSpec`], the mounted state, the mapping from a [`belt::Drive`] and
/// what the drive reports as a [`belt::BeltModel`]. The fields of the discretisation are the
/// implementing type's (the drive's `kind`).
pub trait DriveKind: Sized {
    /// The belt's parameters.
    type Belt;
    /// The contact's parameters.
    type Contact;
    /// The mounted static state.
    type Initial;
    /// The derived parameters of the drive → discretisation mapping (for reports).
    type Mapping;
    /// The drive's name in debug output.
    const NAME: &'static str;
    /// What the model is ([`belt::BeltModel::traits`]).
    const TRAITS: ModelTraits;

    /// Number of belt elements.
    fn elements(&self) -> usize;
    /// Number of belt coordinates.
    fn belt_coordinates(&self) -> usize;
    /// The belt coordinates of each element, in element order.
    fn element_dofs(&self) -> Vec<Vec<Option<usize>>>;
    /// The mass matrix of element `e` (Kerkkänen (2.26)), column-major.
    fn element_mass(&self, e: usize) -> Vec<f64>;
    /// The coordinates of the mounted static state.
    fn initial_q(initial: &Self::Initial) -> &[f64];
    /// Tensioner arm angle \[rad\] of `d` at `q` (`None`: no arm).
    fn arm_angle_at(d: &AncfBeltDrive<Self>, q: &[f64]) -> Option<f64>;
    /// Mean belt speed along the centreline of `d` \[m/s\].
    fn mean_belt_speed(d: &AncfBeltDrive<Self>, q: &[f64], v: &[f64]) -> f64;
    /// Pulleys, spans and wrap points of `d` at the state ([`belt::BeltModel::snapshot`]).
    fn snapshot_at(
        d: &AncfBeltDrive<Self>, t: f64, q: &[f64], v: &[f64],
    ) -> Result<Snapshot, MbdError>;
    /// [`Self::snapshot_at`] without the wrap points' recovered tension
    /// ([`belt::BeltModel::report_snapshot`]). Default: [`Self::snapshot_at`].
    fn report_snapshot_at(
        d: &AncfBeltDrive<Self>, t: f64, q: &[f64], v: &[f64],
    ) -> Result<Snapshot, MbdError> {
        Self::snapshot_at(d, t, q, v)
    }
    /// Transverse offset of each span's middle from its line \[m\].
    fn span_offsets(d: &AncfBeltDrive<Self>, q: &[f64]) -> Result<Vec<f64>, MbdError>;
}

/// An ANCF belt drive (module documentation): coordinates `q = [e; θ; …]`, the belt's
/// `e` first, then the free pulleys' travel-sense angles `θ` in pulley order, then the
/// discretisation's own (the planar drive's tensioner arm).
pub struct AncfBeltDrive<K: DriveKind> {
    pub(crate) spec: DriveSpec<K::Belt, K::Contact>,
    pub(crate) path: BeltPath,
    /// Number of belt coordinates.
    pub(crate) n_belt: usize,
    pub(crate) pulley_dofs: PulleyCoordinates,
    pub(crate) pattern: Pattern,
    pub(crate) mass_values: Vec<f64>,
    /// The discretisation.
    pub(crate) kind: K,
}

impl<K: DriveKind> std::fmt::Debug for AncfBeltDrive<K>
where
    Self: SecondOrderSystem,
{
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct(K::NAME)
            .field("elements", &self.kind.elements())
            .field("pulleys", &self.spec.pulleys.len())
            .field("n_q", &self.n_q())
            .finish()
    }
}

impl<K: DriveKind> AncfBeltDrive<K> {
    /// The drive of `spec` over `path` discretised by `kind`, with `extra_inertias.len()`
    /// coordinates of the discretisation's own after the free pulleys' (with their inertias):
    /// the pulleys' coordinates numbered after the belt's; the pattern of the system matrices
    /// with one group per element (in order) and then each element with the free pulleys' and
    /// the extra coordinates (the coupling of the contact); the constant mass values: each
    /// element's mass matrix (Kerkkänen (2.26)), the free pulleys' inertias (3.26) and the
    /// extra inertias.
    pub(crate) fn assemble(
        spec: DriveSpec<K::Belt, K::Contact>, path: BeltPath, kind: K, extra_inertias: &[f64],
    ) -> Self {
        let n_belt = kind.belt_coordinates();
        let pulley_dofs = PulleyCoordinates::new(&spec.pulleys, n_belt);
        let n_free = pulley_dofs.count();
        let n = n_belt + n_free + extra_inertias.len();
        let element_dofs = kind.element_dofs();
        let coupling: Vec<Vec<Option<usize>>> = element_dofs
            .iter()
            .map(|g| {
                let mut g = g.clone();
                g.extend((n_belt..n).map(Some));
                g
            })
            .collect();
        let n_el = element_dofs.len();
        let mut groups = element_dofs;
        groups.extend(coupling);
        let pattern = Pattern::new(n, &groups);
        let mut mass_values = pattern.zeros();
        for e in 0..n_el {
            pattern.add_element(&mut mass_values, e, &kind.element_mass(e), 1.0);
        }
        super::pulleys::add_inertias(&pulley_dofs, &spec.pulleys, &pattern, &mut mass_values);
        for (k, inertia) in extra_inertias.iter().enumerate() {
            mass_values[pattern.diagonal_position(n_belt + n_free + k)] += inertia;
        }
        Self {
            spec,
            path,
            n_belt,
            pulley_dofs,
            pattern,
            mass_values,
            kind,
        }
    }

    /// The description the drive was built from.
    pub fn spec(&self) -> &DriveSpec<K::Belt, K::Contact> {
        &self.spec
    }
    /// The undeformed path of the belt over the pulleys (initial centres).
    pub fn path(&self) -> &BeltPath {
        &self.path
    }
    /// The pulleys in travel order.
    pub fn pulleys(&self) -> &[Pulley] {
        &self.spec.pulleys
    }
    /// The motion of pulley `p` ([`DriveSpec::motion_mut`]: its signals may be replaced
    /// between runs, its kind and inertia must stay).
    pub fn motion_mut(&mut self, p: usize) -> Option<&mut Motion> {
        self.spec.motion_mut(p)
    }
    /// Number of belt coordinates.
    pub fn n_belt(&self) -> usize {
        self.n_belt
    }
    /// The pulleys' angle coordinates.
    pub fn pulley_dofs(&self) -> &PulleyCoordinates {
        &self.pulley_dofs
    }
    /// Coordinate index of pulley `p`'s angle, if it is free.
    pub fn pulley_dof(&self, p: usize) -> Option<usize> {
        self.pulley_dofs.dof(p)
    }
    /// Assembly pattern of the system matrices (built once).
    pub fn pattern(&self) -> &Pattern {
        &self.pattern
    }
    /// Travel-sense angular speed of pulley `p` at `(t, v)` \[rad/s\]: the prescribed history
    /// for driven pulleys, the velocity coordinate for free ones.
    pub fn pulley_speed(&self, p: usize, t: f64, v: &[f64]) -> f64 {
        self.pulley_dofs.speed(&self.spec.pulleys, p, t, v)
    }
    /// [`Self::pulley_speed`] of every pulley \[rad/s\].
    pub(crate) fn speeds(&self, t: f64, v: &[f64]) -> Vec<f64> {
        self.pulley_dofs.speeds(&self.spec.pulleys, t, v)
    }
    /// Load torque on pulley `p` at `t` \[N·m\] (0 for speed-driven pulleys and idlers).
    pub fn load_torque(&self, p: usize, t: f64) -> f64 {
        self.spec.pulleys[p].motion.load_torque(t)
    }
    /// Velocities of the free pulleys rolling with a belt at `speed` \[m/s\] (`θ̇ = V/R`)
    /// written into `v`.
    pub(crate) fn roll_pulleys(&self, speed: f64, v: &mut [f64]) {
        for (p, j) in self.pulley_dofs.free() {
            v[j] = speed / self.spec.pulleys[p].radius;
        }
    }
}

/// Coordinates: the belt's, the free pulleys' angles and the discretisation's own.
impl<K: DriveKind> AncfDrive for AncfBeltDrive<K>
where
    Self: SecondOrderSystem,
{
    type Initial = K::Initial;
    type Mapping = K::Mapping;

    fn model_traits(&self) -> ModelTraits {
        K::TRAITS
    }
    fn initial_q(initial: &K::Initial) -> &[f64] {
        K::initial_q(initial)
    }
    fn drive_pulleys(&self) -> &[Pulley] {
        self.pulleys()
    }
    fn drive_path(&self) -> &BeltPath {
        self.path()
    }
    fn pulley_coordinates(&self) -> &PulleyCoordinates {
        &self.pulley_dofs
    }
    fn pulley_motion_mut(&mut self, k: usize) -> Option<&mut Motion> {
        self.motion_mut(k)
    }
    fn arm_angle_at(&self, q: &[f64]) -> Option<f64> {
        K::arm_angle_at(self, q)
    }
    fn mean_belt_speed(&self, q: &[f64], v: &[f64]) -> f64 {
        K::mean_belt_speed(self, q, v)
    }
    fn snapshot_at(&self, t: f64, q: &[f64], v: &[f64]) -> Result<Snapshot, MbdError> {
        K::snapshot_at(self, t, q, v)
    }
    fn report_snapshot_at(&self, t: f64, q: &[f64], v: &[f64]) -> Result<Snapshot, MbdError> {
        K::report_snapshot_at(self, t, q, v)
    }
    fn span_offsets(&self, q: &[f64]) -> Result<Vec<f64>, MbdError> {
        K::span_offsets(self, q)
    }
    fn belt_elements(&self) -> usize {
        self.kind.elements()
    }
}
