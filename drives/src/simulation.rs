//! A belt model stepped in time: build a model from a drive, step it, read and set its state,
//! observe it, and read the one report ([`belt::Report`]) at any state. The procedures of this
//! crate step their models through it ([`crate::speed_loss_sweep`], [`crate::fead::run_fead`]:
//! mbd-core's generalized-α stepper, a failed step subdivided
//! [`crate::speed_loss::STEP_SUBDIVISIONS`] levels, [`AlphaConfig::subdivisions`]).
//!
//! ```
//! use drives::belt::{Layout, Motion, Pulley, Section, Signal, Tensioner, WrapSide};
//! use drives::{AnyModel, ModelKind, ModelSettings};
//! // crank ramped to 40 rad/s, alternator loaded with 1.5 N m, back-side idler on an arm
//! let crank = Motion::speed(Signal::schedule(vec![(0.0, 0.0), (0.02, 40.0)]));
//! let pulleys = vec![
//!     Pulley::new("crank", [0.0, 0.0], 0.06, WrapSide::Inside, crank),
//!     Pulley::new("alternator", [0.3, 0.05], 0.03, WrapSide::Inside, Motion::load(2e-3, Signal::constant(1.5))),
//!     Pulley::new("idler", [0.15, -0.035], 0.03, WrapSide::Outside, Motion::idler(1e-4)),
//! ];
//! let mut layout = Layout::new(pulleys, Section::default(), 300.0);
//! // arm 60 mm long, pivot right of the idler, the spring pushing the idler into the belt
//! layout.tensioner = Some(Tensioner::new(2, [0.21, -0.035], 40.0, -25.0, std::f64::consts::PI));
//! let drive = layout.resolve()?;
//! let mut settings = ModelSettings::default();
//! settings.ancf.elements = 60;
//! for kind in [ModelKind::Flowing, ModelKind::Nodal, ModelKind::Ancf] {
//!     let report = AnyModel::new(kind, &drive, &settings)?.simulate(0.03, 2.5e-4)?;
//!     assert_eq!(report.pulleys.len(), 3);
//!     assert!(report.spans.iter().all(|s| s.tension_n > 0.0), "{kind:?}");
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::DriveError;
use crate::ancf_model::AncfBelt;
use crate::speed_loss::{BELT_LINE_SEARCH_TRIALS, BELT_NEWTON_ITERATIONS, STEP_SUBDIVISIONS};
use crate::study::{AnyModel, ModelKind, ModelSettings};
use crate::with_model;
use belt::{BeltModel, Layout, Motion, Report, Signal};
use contact::friction::FrictionLaw;
use flowing::belt::{FlowingBelt, NodalBelt};
use mbd_core::integrators::{AlphaConfig, AlphaStepper, GeneralizedAlpha, State, Stats, Stepper};
use mbd_core::validate::{InvalidField, Validate, check};
use mbd_core::{MbdError, SecondOrderSystem};
use serde::{Deserialize, Serialize};
use std::borrow::BorrowMut;
use std::marker::PhantomData;
use thiserror::Error;

/// A belt model and its generalized-α stepper (module documentation). The model is owned
/// (`B = M`) or borrowed (`B = &mut M`: the procedures step the model their caller built).
pub struct BeltSimulation<M: BeltModel, B: BorrowMut<M> = M> {
    model: B,
    stepper: AlphaStepper,
    alpha: AlphaConfig,
    /// The counters of the steppers before the last restart ([`Self::set_state`]).
    earlier: Stats,
    _model: PhantomData<fn() -> M>,
}

impl<M: BeltModel, B: BorrowMut<M>> BeltSimulation<M, B> {
    /// Start `model` from its mounted static state ([`BeltModel::initial_state`]) with the
    /// generalized-α settings `alpha` (its step `alpha.h` \[s\] is the simulation's step; a
    /// failed step is subdivided at least [`STEP_SUBDIVISIONS`] levels).
    pub fn new(model: B, alpha: AlphaConfig) -> Result<Self, MbdError> {
        let s0 = model.borrow().initial_state()?;
        Self::from_state(model, alpha, s0)
    }

    /// Start `model` from `state` (as [`Self::new`] otherwise).
    pub fn from_state(model: B, alpha: AlphaConfig, state: State) -> Result<Self, MbdError> {
        let alpha = AlphaConfig {
            subdivisions: alpha.subdivisions.max(STEP_SUBDIVISIONS),
            ..alpha
        };
        let stepper = GeneralizedAlpha::new(alpha).stepper(model.borrow(), state)?;
        Ok(Self {
            model,
            stepper,
            alpha,
            earlier: Stats::default(),
            _model: PhantomData,
        })
    }

    /// One step (split into halves up to [`AlphaConfig::subdivisions`] levels when Newton
    /// fails); the new state.
    pub fn step(&mut self) -> Result<&State, MbdError> {
        self.stepper.step(self.model.borrow(), Some(self.alpha.h))?;
        Ok(self.stepper.state())
    }

    /// Step until `t_end` \[s\], `observer` seeing the model and every new state.
    pub fn run_to(
        &mut self, t_end: f64, mut observer: impl FnMut(&M, &State),
    ) -> Result<(), MbdError> {
        while self.stepper.state().t < t_end - 0.5 * self.alpha.h {
            self.step()?;
            observer(self.model.borrow(), self.stepper.state());
        }
        Ok(())
    }

    /// The current state.
    pub fn state(&self) -> &State {
        self.stepper.state()
    }

    /// The step \[s\] (a failed step is subdivided, the next one tries this size again).
    pub fn step_size(&self) -> f64 {
        self.alpha.h
    }

    /// Restart from `state` (same model and step; the work counters carry on).
    pub fn set_state(&mut self, state: State) -> Result<(), MbdError> {
        let stepper = GeneralizedAlpha::new(self.alpha).stepper(self.model.borrow(), state)?;
        let done = std::mem::replace(&mut self.stepper, stepper);
        self.earlier.accumulate(&done.stats);
        Ok(())
    }

    /// The work since the start: steps, Newton iterations, factorisations (over restarts).
    pub fn stats(&self) -> Stats {
        let mut s = self.earlier;
        s.accumulate(&self.stepper.stats);
        s
    }

    /// The model.
    pub fn model(&self) -> &M {
        self.model.borrow()
    }

    /// The model, to change its pulleys' signals between steps ([`BeltModel::set_signal`]).
    pub fn model_mut(&mut self) -> &mut M {
        self.model.borrow_mut()
    }

    /// The report of the current state ([`Report::new`]).
    pub fn report(&self) -> Result<Report, MbdError> {
        let s = self.stepper.state();
        self.model().report_at(s.t, &s.q, &s.v)
    }
}

/// The generalized-α settings a belt model of `kind` is stepped with at the step `h` \[s\]:
/// mbd-core's defaults with a line search of [`BELT_LINE_SEARCH_TRIALS`] trials,
/// [`BELT_NEWTON_ITERATIONS`] iterations and the models' transition-aware limit on Newton
/// corrections ([`AlphaConfig::model_correction_limit`]: the friction's slip velocities do
/// not cross its steep band in one iteration, Castro et al. 2019) (flowing and nodal), the
/// ANCF belt with its own Newton settings
/// ([`ancf::belt_drive::SimulationConfig::alpha_params`]), its velocities resolved to the
/// friction law's transition width `width` \[m/s\]
/// ([`ancf::belt_drive::SimulationConfig::resolving`]; `None`: a law without a steep band).
pub fn alpha_for(kind: ModelKind, h: f64, width: Option<f64>) -> AlphaConfig {
    match kind {
        ModelKind::Ancf => ancf::belt_drive::SimulationConfig {
            h,
            ..Default::default()
        }
        .resolving(width)
        .alpha_params(),
        ModelKind::Flowing | ModelKind::Nodal => AlphaConfig {
            h,
            newton_line_search: true,
            newton_line_search_trials: BELT_LINE_SEARCH_TRIALS,
            max_newton_iterations: BELT_NEWTON_ITERATIONS,
            model_correction_limit: true,
            ..Default::default()
        },
    }
}

impl AnyModel {
    /// The kind of the model inside.
    pub fn kind(&self) -> ModelKind {
        match self {
            AnyModel::Flowing(_) => ModelKind::Flowing,
            AnyModel::Nodal(_) => ModelKind::Nodal,
            AnyModel::Ancf(_) => ModelKind::Ancf,
        }
    }

    /// The model stepped from its mounted state with steps `h` \[s\] ([`alpha_for`]).
    pub fn into_simulation(self, h: f64) -> Result<AnySimulation, MbdError> {
        let width = with_model!(&self, |m| m.drive().contact().friction.transition_width());
        let alpha = alpha_for(self.kind(), h, width);
        Ok(match self {
            AnyModel::Flowing(m) => {
                AnySimulation::Flowing(Box::new(BeltSimulation::new(*m, alpha)?))
            }
            AnyModel::Nodal(m) => AnySimulation::Nodal(Box::new(BeltSimulation::new(*m, alpha)?)),
            AnyModel::Ancf(m) => AnySimulation::Ancf(Box::new(BeltSimulation::new(*m, alpha)?)),
        })
    }

    /// Run the model from its mounted state to `t_end` \[s\] with steps `h` \[s\]
    /// ([`alpha_for`]) and return the report of the last state.
    pub fn simulate(self, t_end: f64, h: f64) -> Result<Report, MbdError> {
        let mut sim = self.into_simulation(h)?;
        sim.run_to(t_end, |_| {})?;
        sim.report()
    }
}

/// A [`BeltSimulation`] of any of the three belt models, chosen at run time (the Python
/// `flowmbd.belt.Simulation`): the same stepping, state and report whatever the model.
pub enum AnySimulation {
    /// The flowing-material belt (Ribaric (5.14)).
    Flowing(Box<BeltSimulation<FlowingBelt>>),
    /// The rotating-mesh nodal belt (Ribaric (5.7)).
    Nodal(Box<BeltSimulation<NodalBelt>>),
    /// The ANCF belt (Kerkkänen ch. 3).
    Ancf(Box<BeltSimulation<AncfBelt>>),
}

/// Run `$body` on the [`BeltSimulation`] inside an [`AnySimulation`].
macro_rules! with_sim {
    ($any:expr, |$s:ident| $body:expr) => {
        match $any {
            AnySimulation::Flowing($s) => $body,
            AnySimulation::Nodal($s) => $body,
            AnySimulation::Ancf($s) => $body,
        }
    };
}

impl AnySimulation {
    /// Build the model of `config` and start it from its mounted static state.
    ///
    /// # Errors
    /// The configuration is invalid ([`DriveSimulationConfig::validate`], the layout's
    /// [`Layout::resolve`]) or the model cannot be built or mounted.
    pub fn new(config: &DriveSimulationConfig) -> Result<Self, SimulationBuildError> {
        config.validate()?;
        let drive = config.drive.resolve().map_err(|e| e.within("drive"))?;
        let model = AnyModel::new(config.model, &drive, &config.models)?;
        Ok(model.into_simulation(config.step)?)
    }

    /// The kind of the model.
    pub fn kind(&self) -> ModelKind {
        match self {
            AnySimulation::Flowing(_) => ModelKind::Flowing,
            AnySimulation::Nodal(_) => ModelKind::Nodal,
            AnySimulation::Ancf(_) => ModelKind::Ancf,
        }
    }

    /// One step ([`BeltSimulation::step`]); the new state.
    pub fn step(&mut self) -> Result<&State, MbdError> {
        with_sim!(self, |s| s.step())
    }

    /// Step until `t_end` \[s\], `observer` seeing every new state.
    pub fn run_to(&mut self, t_end: f64, mut observer: impl FnMut(&State)) -> Result<(), MbdError> {
        with_sim!(self, |s| s.run_to(t_end, |_, st| observer(st)))
    }

    /// The step \[s\] ([`BeltSimulation::step_size`]).
    pub fn step_size(&self) -> f64 {
        with_sim!(self, |s| s.step_size())
    }

    /// The current state (time \[s\], coordinates, velocities).
    pub fn state(&self) -> &State {
        with_sim!(self, |s| s.state())
    }

    /// Restart from `state` (same model and step).
    ///
    /// # Errors
    /// `state` does not have the model's sizes, or the stepper cannot start from it.
    pub fn set_state(&mut self, state: State) -> Result<(), MbdError> {
        let n = self.coordinates();
        if state.q.len() != n || state.v.len() != n {
            return Err(MbdError::InvalidInput {
                item: "state".into(),
                reason: format!(
                    "the model has {n} coordinates, got q of {} and v of {}",
                    state.q.len(),
                    state.v.len()
                ),
            });
        }
        with_sim!(self, |s| s.set_state(state))
    }

    /// The report of the current state ([`BeltSimulation::report`]).
    pub fn report(&self) -> Result<Report, MbdError> {
        with_sim!(self, |s| s.report())
    }

    /// Number of coordinates.
    pub fn coordinates(&self) -> usize {
        with_sim!(self, |s| s.model().n_q())
    }

    /// The name of coordinate `dof`.
    pub fn coordinate_name(&self, dof: usize) -> String {
        with_sim!(self, |s| s.model().dof_name(dof))
    }

    /// The pulleys' speeds in the travel sense at the current state \[rad/s\].
    pub fn pulley_speeds(&self) -> Vec<f64> {
        with_sim!(self, |s| {
            let st = s.state();
            (0..s.model().drive().pulleys().len())
                .map(|k| s.model().pulley_speed(k, st.t, &st.v))
                .collect()
        })
    }

    /// The belt's speed along its path at the current state \[m/s\].
    pub fn belt_speed(&self) -> f64 {
        with_sim!(self, |s| {
            let st = s.state();
            s.model().belt_speed(&st.q, &st.v)
        })
    }

    /// The tensioner arm's angle at the current state \[rad\] (`None` without a tensioner).
    pub fn arm_angle(&self) -> Option<f64> {
        with_sim!(self, |s| s.model().arm_angle(&s.state().q))
    }

    /// Replace the signal of pulley `k` from now on: the speed of a driver, the load torque
    /// of an accessory (an idler becomes a loaded pulley) ([`BeltModel::set_signal`]).
    ///
    /// # Errors
    /// `k` is not a pulley of the drive, or the signal is invalid.
    pub fn set_signal(&mut self, k: usize, signal: Signal) -> Result<(), InvalidField> {
        with_sim!(self, |s| s.model_mut().set_signal(k, signal))
    }

    /// The motion of pulley `k` (`None` if there is no such pulley).
    pub fn motion(&self, k: usize) -> Option<Motion> {
        with_sim!(self, |s| s.model().motion(k).cloned())
    }
}

/// Why a [`DriveSimulationConfig`] did not become an [`AnySimulation`].
#[derive(Debug, Error)]
pub enum SimulationBuildError {
    /// A field of the configuration is invalid (the message names it).
    #[error(transparent)]
    Input(#[from] InvalidField),
    /// The belt model rejected the drive or could not be built.
    #[error(transparent)]
    Model(#[from] DriveError),
    /// The mounted static state or the stepper's start failed.
    #[error("mounting the belt: {0}")]
    Mount(#[from] MbdError),
}

/// Limits on a stepped drive's step \[s\].
const STEP_RANGE: (f64, f64) = (1e-8, 0.1);

/// A belt drive to step in time ([`AnySimulation::new`]; the Python `flowmbd.belt.Simulation`).
/// The defaults are Ribaric's Table 6-1 drive (§6.4) run as its speed-loss procedure runs it:
/// the driver ramped to 62.8 rad/s in 0.3 s, then the driven pulley's load ramped to 10 N m in
/// 0.1 s, the flowing model with a step of 0.25 ms.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct DriveSimulationConfig {
    /// The belt model: `flowing` (Ribaric (5.14)), `nodal` (Ribaric (5.7)) or `ancf`
    /// (Kerkkänen ch. 3).
    pub model: ModelKind,
    /// The drive: pulleys with their motions, tensioner, belt section, mounting, contact.
    pub drive: Layout,
    /// Time step \[s\] (the ANCF belt's Newton settings are its own, [`alpha_for`]).
    pub step: f64,
    /// Each model's discretisation (`models.flowing`, `models.nodal`, `models.ancf`).
    pub models: ModelSettings,
}

impl Default for DriveSimulationConfig {
    fn default() -> Self {
        let mut drive = Layout::table_6_1();
        drive.pulleys[0].motion = Motion::speed(Signal::schedule(vec![(0.0, 0.0), (0.3, 62.8)]));
        drive.pulleys[1].motion = Motion::load(
            0.013,
            Signal::schedule(vec![(0.0, 0.0), (0.3, 0.0), (0.4, 10.0)]),
        );
        Self {
            model: ModelKind::Flowing,
            drive,
            step: 2.5e-4,
            models: ModelSettings::default(),
        }
    }
}

impl Validate for DriveSimulationConfig {
    /// The step within [1e-8, 0.1] s and the models' settings (the layout is checked when it
    /// is resolved, [`Layout::resolve`]).
    fn validate(&self) -> Result<(), InvalidField> {
        check::within("step", self.step, STEP_RANGE.0, STEP_RANGE.1, "s")?;
        self.models.validate_within("models")
    }
}

impl mbd_core::config::PartialRules for DriveSimulationConfig {
    const DROPPED_BY: &'static [(&'static str, &'static str)] = belt::PARTIAL_RULES;
}
