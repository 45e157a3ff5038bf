//! A belt model stepped in time: build a model from a drive, step it, read and set its state,
//! observe it, and read the one report ([`belt::Report`]) at any state. The procedures of this
//! crate use the same stepping (mbd-core's generalized-α stepper, a failed step subdivided
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

use crate::speed_loss::STEP_SUBDIVISIONS;
use crate::study::AnyModel;
use belt::{BeltModel, Report};
use contact::friction::FrictionLaw;
use mbd_core::MbdError;
use mbd_core::integrators::{AlphaConfig, AlphaStepper, GeneralizedAlpha, State, Stepper};

/// A belt model and its generalized-α stepper (module documentation).
pub struct BeltSimulation<M: BeltModel> {
    model: M,
    stepper: AlphaStepper,
    alpha: AlphaConfig,
}

impl<M: BeltModel> BeltSimulation<M> {
    /// Start `model` from its mounted static state ([`BeltModel::initial_state`]) with the
    /// generalized-α settings `alpha` (its step `alpha.h` \[s\] is the simulation's step; a
    /// failed step is subdivided at least [`STEP_SUBDIVISIONS`] levels).
    pub fn new(model: M, alpha: AlphaConfig) -> Result<Self, MbdError> {
        let alpha = AlphaConfig {
            subdivisions: alpha.subdivisions.max(STEP_SUBDIVISIONS),
            ..alpha
        };
        let s0 = model.initial_state()?;
        let stepper = GeneralizedAlpha::new(alpha).stepper(&model, s0)?;
        Ok(Self {
            model,
            stepper,
            alpha,
        })
    }

    /// One step (split into halves up to [`AlphaConfig::subdivisions`] levels when Newton
    /// fails); the new state.
    pub fn step(&mut self) -> Result<&State, MbdError> {
        self.stepper.step(&self.model, Some(self.alpha.h))?;
        Ok(self.stepper.state())
    }

    /// Step until `t_end` \[s\], `observer` seeing the model and every new state.
    pub fn run_to(
        &mut self,
        t_end: f64,
        mut observer: impl FnMut(&M, &State),
    ) -> Result<(), MbdError> {
        while self.stepper.state().t < t_end - 0.5 * self.alpha.h {
            self.step()?;
            observer(&self.model, self.stepper.state());
        }
        Ok(())
    }

    /// The current state.
    pub fn state(&self) -> &State {
        self.stepper.state()
    }

    /// Restart from `state` (same model and step).
    pub fn set_state(&mut self, state: State) -> Result<(), MbdError> {
        self.stepper = GeneralizedAlpha::new(self.alpha).stepper(&self.model, state)?;
        Ok(())
    }

    /// The model.
    pub fn model(&self) -> &M {
        &self.model
    }

    /// The model, to change its pulleys' signals between steps ([`BeltModel::set_signal`]).
    pub fn model_mut(&mut self) -> &mut M {
        &mut self.model
    }

    /// The report of the current state ([`Report::new`]).
    pub fn report(&self) -> Result<Report, MbdError> {
        let s = self.stepper.state();
        let snap = self.model.snapshot(s.t, &s.q, &s.v)?;
        let mu = self.model.drive().contact().friction.coefficient();
        Ok(Report::new(self.model.drive(), &snap, mu))
    }
}

impl AnyModel {
    /// Run the model from its mounted state to `t_end` \[s\] with steps `h` \[s\] (mbd-core's
    /// generalized-α defaults otherwise; the ANCF belt with its own Newton settings) and return
    /// the report of the last state.
    pub fn simulate(self, t_end: f64, h: f64) -> Result<Report, MbdError> {
        let alpha = |ancf: bool| {
            if ancf {
                ancf::belt_drive::SimulationConfig {
                    h,
                    ..Default::default()
                }
                .alpha_params()
            } else {
                AlphaConfig {
                    h,
                    newton_line_search: true,
                    ..Default::default()
                }
            }
        };
        let is_ancf = matches!(self, AnyModel::Ancf(_));
        crate::with_model!(self, |m| {
            let mut sim = BeltSimulation::new(*m, alpha(is_ancf))?;
            sim.run_to(t_end, |_, _| {})?;
            sim.report()
        })
    }
}
