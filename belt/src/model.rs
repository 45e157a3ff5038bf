//! The one public belt-model trait: what every belt model of N pulleys (flowing material,
//! rotating-mesh nodal, planar ANCF, ANCF plate) offers the procedures and studies, and from
//! which the one report ([`crate::report::Report`]) is computed for every model.
//!
//! A model is built from a resolved [`Drive`] (and its own discretisation settings) in its
//! own crate; it is a [`SecondOrderSystem`] that every mbd-core stepper runs. Its coordinates
//! are its own; what it reports through this trait is model-independent: pulley speeds in the
//! travel sense, the arm angle, the belt speed, and a [`Snapshot`] of span forces, contact
//! points and pulley loads. Every span force is the axial force the model's belt actually
//! carries ([`ModelTraits::force_measure`]), so one report and one set of balances serve all.

use crate::decoupler::DecouplerState;
use crate::layout::Drive;
use crate::motion::Motion;
use crate::path::LineOfAction;
use crate::signal::Signal;
use mbd_core::integrators::State;
use mbd_core::validate::InvalidField;
use mbd_core::{MbdError, SecondOrderSystem};
use serde::Serialize;

/// One contact point on a wrap.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WrapPoint {
    /// Pulley index.
    pub pulley: usize,
    /// Angle from the inlet of the wrap in the travel direction \[rad\]
    /// ([`crate::path::BeltPath::angle_from_inlet`]).
    pub angle: f64,
    /// Belt length the point's force densities stand for \[m\] (tributary length of a node,
    /// quadrature weight times element length of a contact point).
    pub length: f64,
    /// Axial force in the belt at the point \[N\] (the model's force measure).
    pub tension: f64,
    /// Contact pressure (normal force per unit belt length) \[N/m\].
    pub pressure: f64,
    /// Friction force per unit belt length on the belt, positive in the travel direction
    /// \[N/m\].
    pub friction: f64,
    /// Slip velocity, belt minus pulley surface speed in the travel direction \[m/s\].
    pub slip: f64,
}

impl WrapPoint {
    /// Friction utilisation `|f|/(μ p)` with the law's coefficient `mu` (0 where the pressure
    /// or `mu` vanishes).
    pub fn utilisation(&self, mu: f64) -> f64 {
        if self.pressure > 0.0 && mu > 0.0 {
            self.friction.abs() / (mu * self.pressure)
        } else {
            0.0
        }
    }
}

/// A pulley's state in a snapshot.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PulleyState {
    /// Speed in the travel sense \[rad/s\].
    pub omega: f64,
    /// Force of the belt on the pulley (hub load) \[N\].
    pub hub_load: [f64; 2],
    /// Torque of the belt's contact forces on the pulley in its travel sense \[N m\] (negative
    /// on a driver: the pulley drives the belt).
    pub torque: f64,
    /// Velocity of the pulley's centre \[m/s\] (a tensioner's idler; zero for fixed centres).
    pub center_velocity: [f64; 2],
    /// Position of the pulley's centre \[m\] (a tensioner's idler where its arm has turned it;
    /// the layout's centre for fixed centres): the point about which the report takes the
    /// spans' moments ([`crate::report`]).
    pub center: [f64; 2],
}

/// A span's state in a snapshot.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpanState {
    /// Pulley the span leaves.
    pub from: usize,
    /// Pulley the span reaches.
    pub to: usize,
    /// Axial force over the middle half of the span (the model's force measure) \[N\].
    pub tension: f64,
    /// Transverse displacement of the span's mid-point from the undeformed span line,
    /// positive to the left of the travel direction \[m\].
    pub transverse: f64,
    /// The line the span's force acts along (the flowing, nodal and plate models: the
    /// least-squares line through the deformed belt over the span's middle half,
    /// [`crate::SpanLine::line_of_action`]; the ANCF belt: the line of its section force,
    /// `ancf::belt_drive::BeltDrive::span_force_lines`); `None` where the model gives no points
    /// there (the report then takes the undeformed span line).
    pub line: Option<LineOfAction>,
    /// The momentum the moving belt carries through the span's middle, `ṁ v` \[N\] along its
    /// line (`ṁ` the mass flow \[kg/s\], `v` the material velocity), where the model states it
    /// (`None`: not evaluated; the report then takes the balance as quasi-static). A pulley's
    /// contact torque balances the moments of the section forces at the middles of its two
    /// spans less the angular momentum the belt carries out through them (module
    /// [`crate::report`]); with equal levers in and out the two fluxes cancel.
    pub momentum_flux: Option<(f64, LineOfAction)>,
}

/// What a model reports at one state `(t, q, v)` ([`BeltModel::snapshot`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    /// Time \[s\].
    pub time: f64,
    /// Pulleys in travel order.
    pub pulleys: Vec<PulleyState>,
    /// Spans in travel order (span `k` leaves pulley `k`).
    pub spans: Vec<SpanState>,
    /// Every contact point in contact (positive pressure).
    pub wrap: Vec<WrapPoint>,
    /// Power dissipated by the belt's own damping at this state \[W\] (material damping,
    /// penalty damping; `None` where the model does not evaluate it).
    pub belt_dissipation: Option<f64>,
}

/// What the procedures need to know about a model beyond its drive.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ModelTraits {
    /// Short name (`flowing`, `nodal`, `ancf`, `plate`).
    pub name: &'static str,
    /// Whether the model is linearised about the mounted tension (stiffness `K_e + K_g(T0)`,
    /// force `T0 + EA Δl/l`: the flowing and nodal belts, Ribaric (5.5)): its results hold only
    /// while the spans stay taut and the strain near the mounted one.
    pub linearised: bool,
    /// The axial force the model reports in its spans and wraps, in words (with the law).
    pub force_measure: &'static str,
    /// Whether the model's contact slip follows the strain its elements carry, so that its speed
    /// loss near Coulomb friction is the elastic creep (Grashof): `false` for the flowing belt
    /// with Ribaric's contact rates (`flowing::belt::ContactVelocity::Ribaric`, 31 % below the
    /// closed form on Table 6-1's default mesh), whose speed-loss points then carry a caveat
    /// when the friction law is sharper than the creep.
    pub near_coulomb_creep: bool,
    /// The known cause of the model's balance residuals where they miss
    /// [`crate::BALANCE_TOLERANCE`], in words with what removes it (`None`: none known; the
    /// flowing belt with the path-referenced bending of Ribaric (5.5)).
    pub balance_defect: Option<&'static str>,
}

/// A belt-drive model of N pulleys (module documentation).
pub trait BeltModel: SecondOrderSystem {
    /// The resolved drive the model was built from (geometry, belt, mounting).
    fn drive(&self) -> &Drive;

    /// Name, linearisation and force measure.
    fn traits(&self) -> ModelTraits;

    /// Consistent state at rest: the mounted belt's static equilibrium at `t = 0`, zero
    /// velocities.
    fn initial_state(&self) -> Result<State, MbdError>;

    /// The motion of pulley `k` as the model runs it (`None`: no such pulley).
    fn motion(&self, k: usize) -> Option<&Motion>;

    /// Mutable [`Self::motion`]. A motion's kind must not change between speed-driven and
    /// free, nor its decoupler come or go (the coordinates depend on them); use
    /// [`Self::set_signal`].
    fn motion_mut(&mut self, k: usize) -> Option<&mut Motion>;

    /// Travel-sense speed of pulley `k` \[rad/s\] at `(t, v)`.
    fn pulley_speed(&self, k: usize, t: f64, v: &[f64]) -> f64;

    /// Tensioner arm angle `θ` \[rad\] at `q` (`None`: no tensioner).
    fn arm_angle(&self, q: &[f64]) -> Option<f64>;

    /// Belt speed \[m/s\]: the material speed along the path (mean over the loop for a
    /// Lagrangian mesh).
    fn belt_speed(&self, q: &[f64], v: &[f64]) -> f64;

    /// Length of the belt elements that travel with the material \[m\]: a Lagrangian mesh
    /// (the ANCF and nodal belts) carries its elements and contact points through the wraps at
    /// the belt speed `v`, so a step `h` moves them `v h` along the path, and a node entering
    /// a wrap changes its acceleration by `v²/R` within the step (the procedures limit `v h` to
    /// a fraction of this length, e.g. the FEAD study's `run.max_travel`). `None` (the default)
    /// for a stationary (Eulerian) mesh, the flowing belt's (Ribaric (5.10): the material
    /// moves through the mesh, whose nodes stay in place).
    fn material_element(&self) -> Option<f64> {
        None
    }

    /// The drive's state at `(t, q, v)` for the report.
    fn snapshot(&self, t: f64, q: &[f64], v: &[f64]) -> Result<Snapshot, MbdError>;

    /// [`Self::snapshot`] for a [`crate::Report`] only ([`crate::Report::new`] reads the wrap
    /// points' pressure, friction, slip and length, not their `tension`): a model may leave
    /// the wrap points' `tension` `NaN` where recovering it is costly (the ANCF belt's
    /// section-force recovery, a fine contact integral per wrap point). Everything else is
    /// [`Self::snapshot`]'s, to the bit. Default: [`Self::snapshot`].
    fn report_snapshot(&self, t: f64, q: &[f64], v: &[f64]) -> Result<Snapshot, MbdError> {
        self.snapshot(t, q, v)
    }

    /// The drive's report at `(t, q, v)`: [`crate::Report::new`] of [`Self::report_snapshot`]
    /// (the one path of every study's report-only samples).
    fn report_at(&self, t: f64, q: &[f64], v: &[f64]) -> Result<crate::Report, MbdError> {
        Ok(crate::Report::new(
            self.drive(),
            &self.report_snapshot(t, q, v)?,
        ))
    }

    /// Transverse displacement of each span's mid-point \[m\] (sampled every step for the
    /// vibration amplitude; spans in travel order).
    fn span_transverse(&self, q: &[f64]) -> Result<Vec<f64>, MbdError>;

    /// The decoupler of pulley `k` at `(q, v)` ([`crate::decoupler`]: accessory speed, spring
    /// and clutch torques, clutch state; `None`: no decoupler on that pulley, or a model
    /// without decouplers).
    fn decoupler_state(&self, _k: usize, _q: &[f64], _v: &[f64]) -> Option<DecouplerState> {
        None
    }

    /// Replace pulley `k`'s signal: the speed of a speed-driven pulley, the load torque of a
    /// free one (an idler becomes a loaded pulley with the same inertia and damping).
    ///
    /// # Errors
    /// `k` is not a pulley of the drive, or the signal is invalid.
    fn set_signal(&mut self, k: usize, signal: Signal) -> Result<(), InvalidField> {
        use mbd_core::validate::Validate;
        let field = format!("pulleys[{k}].motion");
        signal.validate_within(&field)?;
        let n = self.drive().pulleys().len();
        let m = self.motion_mut(k).ok_or_else(|| {
            InvalidField::new("pulleys", format!("no pulley {k} (the drive has {n})"))
        })?;
        match m {
            Motion::Speed { speed } => *speed = signal,
            Motion::Load { torque, .. } => *torque = signal,
            Motion::Idler { inertia, damping } => {
                *m = Motion::Load {
                    inertia: *inertia,
                    torque: signal,
                    damping: *damping,
                    decoupler: None,
                }
            }
        }
        Ok(())
    }
}
