//! Dormand–Prince 5(4) with error control, 4th-order dense output and event location
//! (Dormand & Prince 1980; dense output and step-size control after Hairer, Nørsett & Wanner,
//! *Solving ODEs I*, II.5 and II.6).

use super::accel::{AccelSolver, Stabilization};
use super::{Solution, State, Stats, Stepper, impl_integrator};
use crate::{MbdError, SecondOrderSystem};

const C: [f64; 7] = [0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [0.2, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// Difference of the 5th- and 4th-order weights.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
/// Dense-output weights (Hairer's `dopri5`, `contd5`).
const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

/// What to do when an event is located.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EventAction {
    /// Stop the integration at the event (the returned state is the state at the event).
    Stop,
    /// Record the event and continue.
    Continue,
}

/// A zero-crossing function `g(state)` whose sign change is located in time (contact,
/// switching). `direction`: `+1` only rising crossings, `-1` only falling ones, `0` both.
pub struct Event<'a> {
    /// Name used in the [`EventRecord`].
    pub name: String,
    /// The switching function.
    pub g: Box<dyn Fn(&State) -> f64 + 'a>,
    /// Crossing direction filter.
    pub direction: i8,
    /// Action at the event.
    pub action: EventAction,
}

impl<'a> Event<'a> {
    /// An event stopping the integration on any crossing of `g`.
    pub fn stop(name: &str, g: impl Fn(&State) -> f64 + 'a) -> Self {
        Self {
            name: name.into(),
            g: Box::new(g),
            direction: 0,
            action: EventAction::Stop,
        }
    }
}

/// A located event.
#[derive(Debug, Clone, PartialEq)]
pub struct EventRecord {
    /// Index of the event in the list passed to the integrator.
    pub index: usize,
    /// Name of the event.
    pub name: String,
    /// Located time \[s\].
    pub t: f64,
    /// State at the event (dense output).
    pub state: State,
}

/// Dormand–Prince 5(4) with error control on `y = (q, v)`.
#[derive(
    Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields, default)]
pub struct DormandPrince {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance (units of `q` and `v`).
    pub atol: f64,
    /// Initial step \[s\] (0: automatic, Hairer's initial-step heuristic).
    pub h0: f64,
    /// Maximum step \[s\] (0: unbounded).
    pub h_max: f64,
    /// Minimum step \[s\] before [`MbdError::StepSizeUnderflow`].
    pub h_min: f64,
    /// Maximum number of steps.
    pub max_steps: usize,
    /// Time tolerance of event location \[s\].
    pub event_tol: f64,
    /// Constraint stabilisation.
    pub stabilization: Stabilization,
}

impl Default for DormandPrince {
    fn default() -> Self {
        Self {
            rtol: 1e-8,
            atol: 1e-10,
            h0: 0.0,
            h_max: 0.0,
            h_min: 1e-14,
            max_steps: 10_000_000,
            event_tol: 1e-13,
            stabilization: Stabilization::default(),
        }
    }
}

impl DormandPrince {
    /// Dormand–Prince with relative and absolute tolerances.
    pub fn new(rtol: f64, atol: f64) -> Self {
        Self {
            rtol,
            atol,
            ..Default::default()
        }
    }

    fn validate(&self) -> Result<(), MbdError> {
        let bad = |item: &str, reason: String| MbdError::InvalidInput {
            item: format!("Dormand-Prince {item}"),
            reason,
        };
        let ok = self.rtol.is_finite()
            && self.atol.is_finite()
            && self.rtol >= 0.0
            && self.atol >= 0.0
            && self.rtol + self.atol > 0.0;
        if !ok {
            return Err(bad(
                "tolerances",
                format!(
                    "rtol = {}, atol = {} must be non-negative, finite and not both zero",
                    self.rtol, self.atol
                ),
            ));
        }
        for (name, v) in [
            ("h0", self.h0),
            ("h_max", self.h_max),
            ("h_min", self.h_min),
            ("event_tol", self.event_tol),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(bad(
                    name,
                    format!("must be finite and non-negative, got {v}"),
                ));
            }
        }
        Ok(())
    }

    /// Integrates without events.
    pub fn integrate<S: SecondOrderSystem + ?Sized, R: super::Proceed>(
        &self, sys: &S, state0: State, t_end: f64, observer: impl FnMut(&State) -> R,
    ) -> Result<Solution, MbdError> {
        self.integrate_with_events(sys, state0, t_end, &[], observer)
    }

    /// Integrates from `state0` to `t_end` \[s\], locating the zero crossings of `events`
    /// (on the dense output, Illinois regula falsi to `event_tol`). `observer` sees the initial
    /// state, every accepted step and every located event.
    pub fn integrate_with_events<S: SecondOrderSystem + ?Sized, R: super::Proceed>(
        &self, sys: &S, state0: State, t_end: f64, events: &[Event<'_>],
        observer: impl FnMut(&State) -> R,
    ) -> Result<Solution, MbdError> {
        self.run(sys, state0, t_end, events, None, observer)
    }

    /// Integrates up to the last of `times` \[s\] (strictly increasing, not before the initial
    /// time) and calls `observer` exactly at these times, from the 4th-order dense output
    /// (Hairer's `contd5`), plus at a stopping event.
    pub fn integrate_dense<S: SecondOrderSystem + ?Sized, R: super::Proceed>(
        &self, sys: &S, state0: State, times: &[f64], events: &[Event<'_>],
        observer: impl FnMut(&State) -> R,
    ) -> Result<Solution, MbdError> {
        let bad = |reason: String| MbdError::InvalidInput {
            item: "Dormand-Prince output times".into(),
            reason,
        };
        let Some(&t_end) = times.last() else {
            return Err(bad("no output time given".into()));
        };
        if times.iter().any(|t| !t.is_finite()) {
            return Err(bad("non-finite output time".into()));
        }
        if let Some(k) = times.windows(2).position(|w| w[1] <= w[0]) {
            return Err(bad(format!(
                "times must increase strictly (entry {})",
                k + 1
            )));
        }
        if times[0] < state0.t {
            return Err(bad(format!(
                "first output time {} s is before the initial time {} s",
                times[0], state0.t
            )));
        }
        self.run(sys, state0, t_end, events, Some(times), observer)
    }

    /// A stepper started at `state0`.
    pub fn stepper<S: SecondOrderSystem + ?Sized>(
        &self, sys: &S, state0: State,
    ) -> Result<DopriStepper, MbdError> {
        DopriStepper::new(sys, state0, *self)
    }

    fn run<S: SecondOrderSystem + ?Sized, R: super::Proceed>(
        &self, sys: &S, state0: State, t_end: f64, events: &[Event<'_>], output: Option<&[f64]>,
        mut observer: impl FnMut(&State) -> R,
    ) -> Result<Solution, MbdError> {
        let mut st = DopriStepper::new(sys, state0, *self)?;
        let state0 = &st.state;
        let mut next_out = 0usize;
        // a `Break` from the observer stops the run after the current step (cancelled)
        let mut go_on = true;
        match output {
            None => go_on = observer(state0).proceed(),
            Some(times) => {
                while next_out < times.len() && times[next_out] <= state0.t {
                    go_on &= observer(&State::new(
                        times[next_out],
                        state0.q.clone(),
                        state0.v.clone(),
                    ))
                    .proceed();
                    next_out += 1;
                }
            }
        }
        let mut records = Vec::new();
        let mut g_prev: Vec<f64> = events.iter().map(|e| (e.g)(state0)).collect();
        let mut stepped = false;
        while go_on && st.attempt(sys, t_end)? {
            stepped = true;
            let (t, t_new) = (st.t_prev, st.t);
            let Some(st_new) = &st.raw_end else {
                unreachable!("an accepted step leaves its end state")
            };
            // events (on the unprojected end state and the dense output)
            let mut first: Option<(usize, f64)> = None;
            let g_new: Vec<f64> = events.iter().map(|e| (e.g)(st_new)).collect();
            for (ie, ev) in events.iter().enumerate() {
                let (g0, g1) = (g_prev[ie], g_new[ie]);
                let crossed = (g0 < 0.0 && g1 >= 0.0 && ev.direction >= 0)
                    || (g0 > 0.0 && g1 <= 0.0 && ev.direction <= 0);
                if !crossed {
                    continue;
                }
                let te = crate::roots::illinois(
                    |tt| (ev.g)(&st.interpolate(sys, tt)),
                    t,
                    t_new,
                    g0,
                    g1,
                    self.event_tol,
                );
                if first.is_none_or(|(_, tf)| te < tf) {
                    first = Some((ie, te));
                }
            }
            if let Some(times) = output {
                let t_stop = first.map(|(_, te)| te).unwrap_or(t_new);
                while next_out < times.len() && times[next_out] <= t_stop {
                    let to = times[next_out];
                    let so = if to == t_new {
                        st_new.clone()
                    } else {
                        st.interpolate(sys, to)
                    };
                    go_on &= observer(&so).proceed();
                    next_out += 1;
                }
            }
            if let Some((ie, te)) = first {
                st.stats.events += 1;
                let se = st.interpolate(sys, te);
                records.push(EventRecord {
                    index: ie,
                    name: events[ie].name.clone(),
                    t: te,
                    state: se.clone(),
                });
                if events[ie].action == EventAction::Stop {
                    observer(&se);
                    return Ok(Solution {
                        state: se,
                        stats: st.stats,
                        events: records,
                    });
                }
            }
            g_prev = g_new;
            st.finish(sys)?;
            if output.is_none() {
                go_on &= observer(&st.state).proceed();
            }
        }
        let mut state = st.state;
        if stepped {
            sys.normalize(&mut state.q);
        }
        Ok(Solution {
            state,
            stats: st.stats,
            events: records,
        })
    }
}

/// Stepping object of [`DormandPrince`]: state, stages, step-size controller, dense-output
/// coefficients of the last accepted step and statistics.
pub struct DopriStepper {
    params: DormandPrince,
    solver: AccelSolver,
    lam: Vec<f64>,
    nq: usize,
    /// Time of `y`.
    t: f64,
    /// `y = (q, v)` of the accepted (normalised, projected) state.
    y: Vec<f64>,
    k: Vec<Vec<f64>>,
    ys: Vec<f64>,
    y1: Vec<f64>,
    /// Dense-output coefficients of the last accepted step (Hairer's `rcont1..5`).
    rc: Vec<Vec<f64>>,
    state: State,
    /// End state of the last accepted step before projection.
    raw_end: Option<State>,
    t_prev: f64,
    h_last: f64,
    /// Proposed next step (`None` before the first step: Hairer's initial-step heuristic).
    h: Option<f64>,
    last_reject: bool,
    attempts: usize,
    /// `k[0]` must be re-evaluated at `y` (the accepted state was normalised or projected).
    k0_stale: bool,
    stats: Stats,
}

/// Error scale `atol + rtol max(|y0ᵢ|, |y1ᵢ|)` (Hairer II.4).
fn scale(p: &DormandPrince, y0: &[f64], y1: &[f64], i: usize) -> f64 {
    p.atol + p.rtol * y0[i].abs().max(y1[i].abs())
}

fn eval_rhs<S: SecondOrderSystem + ?Sized>(
    sys: &S, solver: &mut AccelSolver, lam: &mut [f64], stab: &Stabilization, nq: usize, t: f64,
    y: &[f64], dy: &mut [f64], stats: &mut Stats,
) -> Result<(), MbdError> {
    let (q, v) = y.split_at(nq);
    let (dq, dv) = dy.split_at_mut(nq);
    sys.position_rate(q, v, dq);
    solver.solve(sys, t, q, v, stab, stats, dv, lam)
}

impl DopriStepper {
    /// Current state (also [`Stepper::state`]).
    pub fn state(&self) -> &State {
        &self.state
    }

    /// Statistics so far (also [`Stepper::stats`]).
    pub fn stats(&self) -> &Stats {
        &self.stats
    }

    /// Starts at `state0` (one right-hand-side evaluation).
    pub fn new<S: SecondOrderSystem + ?Sized>(
        sys: &S, state0: State, params: DormandPrince,
    ) -> Result<Self, MbdError> {
        params.validate()?;
        state0.check(sys)?;
        let nq = sys.n_q();
        let ny = nq + sys.n_v();
        let y: Vec<f64> = state0.q.iter().chain(state0.v.iter()).copied().collect();
        let mut st = Self {
            params,
            solver: AccelSolver::default(),
            lam: vec![0.0; sys.n_c()],
            nq,
            t: state0.t,
            y,
            k: vec![vec![0.0; ny]; 7],
            ys: vec![0.0; ny],
            y1: vec![0.0; ny],
            rc: vec![vec![0.0; ny]; 5],
            t_prev: state0.t,
            state: state0,
            raw_end: None,
            h_last: 0.0,
            h: None,
            last_reject: false,
            attempts: 0,
            k0_stale: true,
            stats: Stats::default(),
        };
        st.refresh_k0(sys)?;
        Ok(st)
    }

    fn refresh_k0<S: SecondOrderSystem + ?Sized>(&mut self, sys: &S) -> Result<(), MbdError> {
        if self.k0_stale {
            let stab = self.params.stabilization;
            eval_rhs(
                sys,
                &mut self.solver,
                &mut self.lam,
                &stab,
                self.nq,
                self.t,
                &self.y,
                &mut self.k[0],
                &mut self.stats,
            )?;
            self.k0_stale = false;
        }
        Ok(())
    }

    fn sc(&self, y0: &[f64], y1: &[f64], i: usize) -> f64 {
        scale(&self.params, y0, y1, i)
    }

    /// Initial step (Hairer, Nørsett & Wanner II.4) for a run of length `span` \[s\].
    fn initial_step<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S, span: f64,
    ) -> Result<f64, MbdError> {
        let p = self.params;
        let h_max = if p.h_max > 0.0 { p.h_max } else { span };
        let ny = self.y.len();
        let h = if p.h0 > 0.0 {
            p.h0
        } else {
            let y = &self.y.clone();
            let k0 = self.k[0].clone();
            // RMS norm scaled by the tolerances at y (the norm ‖·‖ of Hairer II.4)
            let norm = |x: &[f64]| {
                (x.iter()
                    .enumerate()
                    .map(|(i, x)| (x / scale(&p, y, y, i)).powi(2))
                    .sum::<f64>()
                    / ny as f64)
                    .sqrt()
            };
            let d0 = norm(y);
            let d1 = norm(&k0);
            let h0 = if d0 < 1e-5 || d1 < 1e-5 {
                1e-6
            } else {
                0.01 * d0 / d1
            };
            let y1: Vec<f64> = y.iter().zip(&k0).map(|(a, b)| a + h0 * b).collect();
            let mut f1 = vec![0.0; ny];
            eval_rhs(
                sys,
                &mut self.solver,
                &mut self.lam,
                &p.stabilization,
                self.nq,
                self.t + h0,
                &y1,
                &mut f1,
                &mut self.stats,
            )?;
            let df: Vec<f64> = f1.iter().zip(&k0).map(|(a, b)| a - b).collect();
            let d2 = norm(&df) / h0;
            let h1 = if d1.max(d2) <= 1e-15 {
                (h0 * 1e-3).max(1e-6)
            } else {
                (0.01 / d1.max(d2)).powf(0.2)
            };
            (100.0 * h0).min(h1)
        };
        Ok(h.min(h_max).min(span))
    }

    /// One accepted step towards `t_end` (error control, dense-output coefficients, next step
    /// size) without the projection and the bookkeeping of [`finish`](Self::finish), so that
    /// events can stop the run at a state before the step's end.
    fn attempt<S: SecondOrderSystem + ?Sized>(
        &mut self, sys: &S, t_end: f64,
    ) -> Result<bool, MbdError> {
        if self.t >= t_end || t_end.is_nan() {
            return Ok(false);
        }
        self.refresh_k0(sys)?;
        let mut h = match self.h {
            Some(h) => h,
            None => self.initial_step(sys, t_end - self.t)?,
        };
        let p = self.params;
        let h_max = if p.h_max > 0.0 {
            p.h_max
        } else {
            f64::INFINITY
        };
        let (nq, ny, t) = (self.nq, self.y.len(), self.t);
        loop {
            if self.attempts >= p.max_steps {
                return Err(MbdError::NoConvergence {
                    t,
                    iterations: self.attempts,
                    residual: h,
                });
            }
            self.attempts += 1;
            let clamped = t + 1.01 * h >= t_end;
            if clamped {
                h = t_end - t;
            }
            if h < p.h_min {
                return Err(MbdError::StepSizeUnderflow { t, h });
            }
            let mut stage_failed = false;
            for s in 1..7 {
                for i in 0..ny {
                    let mut acc = 0.0;
                    for j in 0..s {
                        acc += A[s][j] * self.k[j][i];
                    }
                    self.ys[i] = self.y[i] + h * acc;
                }
                let (_, rest) = self.k.split_at_mut(s);
                let r = eval_rhs(
                    sys,
                    &mut self.solver,
                    &mut self.lam,
                    &p.stabilization,
                    nq,
                    t + C[s] * h,
                    &self.ys,
                    &mut rest[0],
                    &mut self.stats,
                );
                if let Err(e) = r {
                    // a failure inside a step (e.g. NaN from a too-large step) rejects the step
                    if matches!(e, MbdError::NonFinite { .. }) && h > p.h_min {
                        stage_failed = true;
                        break;
                    }
                    return Err(e);
                }
            }
            if stage_failed {
                self.stats.rejected_steps += 1;
                h *= 0.25;
                self.last_reject = true;
                continue;
            }
            // y1 = stage 7 argument (FSAL)
            self.y1.copy_from_slice(&self.ys);
            let mut err = 0.0;
            for i in 0..ny {
                let mut e = 0.0;
                for j in 0..7 {
                    e += E[j] * self.k[j][i];
                }
                let s = self.sc(&self.y, &self.y1, i);
                err += (h * e / s).powi(2);
            }
            let err = (err / ny as f64).sqrt();
            if !err.is_finite() || err > 1.0 {
                self.stats.rejected_steps += 1;
                let fac = if err.is_finite() {
                    (0.9 * err.powf(-0.2)).max(0.2)
                } else {
                    0.1
                };
                h *= fac;
                self.last_reject = true;
                continue;
            }
            // accepted: dense-output coefficients
            let (y, y1, k) = (&self.y, &self.y1, &self.k);
            for i in 0..ny {
                let ydiff = y1[i] - y[i];
                let bspl = h * k[0][i] - ydiff;
                self.rc[0][i] = y[i];
                self.rc[1][i] = ydiff;
                self.rc[2][i] = bspl;
                self.rc[3][i] = ydiff - h * k[6][i] - bspl;
                let mut dd = 0.0;
                for j in 0..7 {
                    dd += D[j] * k[j][i];
                }
                self.rc[4][i] = h * dd;
            }
            // the stop time is hit exactly
            let t_new = if clamped { t_end } else { t + h };
            let mut q = y1[..nq].to_vec();
            sys.normalize(&mut q);
            let st_new = State::new(t_new, q, y1[nq..].to_vec());
            self.stats.steps += 1;
            self.t_prev = t;
            self.h_last = h;
            self.t = t_new;
            self.raw_end = Some(st_new);
            let mut fac = if err > 0.0 {
                0.9 * err.powf(-0.2)
            } else {
                10.0
            };
            fac = fac.clamp(0.2, 10.0);
            if self.last_reject {
                fac = fac.min(1.0);
            }
            self.last_reject = false;
            self.h = Some((h * fac).min(h_max));
            return Ok(true);
        }
    }

    /// Completes the step found by [`attempt`](Self::attempt): projection (if requested),
    /// checks, and the accepted state becomes the start of the next step.
    fn finish<S: SecondOrderSystem + ?Sized>(&mut self, sys: &S) -> Result<(), MbdError> {
        let Some(st_new) = &self.raw_end else {
            return Ok(());
        };
        let p = self.params;
        let nq = self.nq;
        let mut st = st_new.clone();
        let mut changed = st.q[..] != self.y1[..nq];
        if p.stabilization.project {
            self.solver
                .project(sys, &mut st, &p.stabilization, &mut self.stats)?;
            changed = true;
        }
        st.check(sys)?;
        self.y[..nq].copy_from_slice(&st.q);
        self.y[nq..].copy_from_slice(&st.v);
        if changed {
            self.k0_stale = true;
        } else {
            let (k0, k6) = self.k.split_at_mut(6);
            k0[0].copy_from_slice(&k6[0]);
        }
        self.state = st;
        Ok(())
    }

    /// `(q, v)` at `t` \[s\] from the dense output of the last step (normalised positions).
    fn interpolate<S: SecondOrderSystem + ?Sized>(&self, sys: &S, t: f64) -> State {
        let th = (t - self.t_prev) / self.h_last;
        let th1 = 1.0 - th;
        let rc = &self.rc;
        let mut q = Vec::with_capacity(self.nq);
        let mut v = Vec::with_capacity(self.y.len() - self.nq);
        for i in 0..self.y.len() {
            let x =
                rc[0][i] + th * (rc[1][i] + th1 * (rc[2][i] + th * (rc[3][i] + th1 * rc[4][i])));
            if i < self.nq { q.push(x) } else { v.push(x) }
        }
        sys.normalize(&mut q);
        State::new(t, q, v)
    }
}

impl<S: SecondOrderSystem + ?Sized> Stepper<S> for DopriStepper {
    fn state(&self) -> &State {
        &self.state
    }

    fn stats(&self) -> &Stats {
        &self.stats
    }

    fn step(&mut self, sys: &S, h: Option<f64>) -> Result<(), MbdError> {
        let t_stop = match h {
            None => f64::INFINITY,
            Some(h) => {
                super::check_step(h, "Dormand-Prince step")?;
                self.t + h
            }
        };
        self.step_until(sys, t_stop).map(|_| ())
    }

    fn step_until(&mut self, sys: &S, t_stop: f64) -> Result<bool, MbdError> {
        if !self.attempt(sys, t_stop)? {
            return Ok(false);
        }
        self.finish(sys)?;
        Ok(true)
    }

    fn has_dense_output(&self) -> bool {
        true
    }

    fn dense_output(&self, sys: &S, t: f64) -> Option<State> {
        let raw = self.raw_end.as_ref()?;
        if t == raw.t {
            return Some(raw.clone());
        }
        let tol = 1e-12 * self.h_last.abs().max(f64::MIN_POSITIVE);
        if t < self.t_prev - tol || t > raw.t + tol {
            return None;
        }
        Some(self.interpolate(sys, t))
    }
}

impl_integrator!(DormandPrince);
