//! The string partly wrapped on two pulleys (`flowmbd-string wrap`, `flowmbd.string.wrap`;
//! Ribaric Fig. 4-4, 4-7, (4.10), (4.11), (4.31)–(4.40)), lifting off under a harmonic load:
//! active-set Lagrange contact with event location ([`simulate_contact`]). Configuration,
//! checks, the run, the tables of `history.csv` and `events.csv` and the VTK frame's geometry
//! live here so that the CLI and the Python package return the same numbers.

use crate::contact::{ContactEvent, ContactString, HarmonicLoad, candidates};
use crate::error::FlowError;
use crate::string_study::{
    MAX_STRING_NODES, Regime, check_number, check_scales, check_steps, check_string,
};
use crate::{
    AxialMotion, ContactConfig, DerivativeMethod, PulleyObstacle, StringConfig, StringMesh,
    simulate_contact,
};
use fe_model::io::vtk::PointField;
use fe_model::{Cell, CellKind, Mesh};
use mbd_core::MbdError;
use mbd_core::integrators::State;
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};
use std::ops::ControlFlow;

/// Coordinates of the wrapped string.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Formulation {
    /// Nodal deflections (4.10).
    Nodal,
    /// Craig–Bampton / flowing material (4.11), (4.40).
    CraigBampton,
}

/// Configuration. The string runs between anchors at 0 and `string.length` (both at u = 0) and
/// over two pulleys whose tops lie `top` above the anchors (the default wraps ≈ 5 cm on each).
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct WrapConfig {
    /// String parameters (`length`: anchor to anchor) \[SI\].
    pub string: StringConfig,
    /// Interior FE nodes.
    pub nodes: usize,
    /// Pulleys.
    pub pulleys: Vec<PulleyObstacle>,
    /// Candidate contact nodes: within this distance of a pulley centre \[m\].
    pub candidate_half_width: f64,
    /// Formulation.
    pub formulation: Formulation,
    /// Retained free-node modes (Craig–Bampton only).
    pub free_modes: usize,
    /// Axial speed \[m/s\] (travelling string, (4.40)).
    pub speed: f64,
    /// Harmonic load.
    pub load: HarmonicLoad,
    /// Duration \[s\].
    pub duration: f64,
    /// Output sampling period \[s\].
    pub sample: f64,
    /// Mode-shape derivative operator.
    pub derivative: DerivativeMethod,
    /// Contact and integrator settings.
    pub contact: ContactConfig,
    /// Number of VTK snapshots (`wrap_NNN.vtu`: deformed string, pulleys, contact forces).
    pub vtk_snapshots: usize,
}

impl Default for WrapConfig {
    fn default() -> Self {
        Self {
            string: StringConfig {
                length: 1.2,
                ..StringConfig::default()
            },
            nodes: 119,
            pulleys: vec![
                PulleyObstacle {
                    center_x: 0.1,
                    top: 0.015,
                    radius: 0.25,
                },
                PulleyObstacle {
                    center_x: 1.1,
                    top: 0.015,
                    radius: 0.25,
                },
            ],
            candidate_half_width: 0.08,
            formulation: Formulation::CraigBampton,
            free_modes: 20,
            speed: 0.0,
            load: HarmonicLoad {
                x: 0.6,
                amplitude: 15.0,
                frequency: 20.0,
            },
            duration: 0.3,
            sample: 5e-4,
            derivative: DerivativeMethod::default(),
            contact: ContactConfig::default(),
            vtk_snapshots: 20,
        }
    }
}

/// Most periods of the model's fastest motion in one run, `duration × max(c(n+1)/(πL),
/// load.frequency)` (the FE mesh's highest natural frequency or the load's): Dormand–Prince
/// takes about 40 steps per period at the default tolerances, so 2.5·10⁵ periods are about 10⁷
/// steps; the default run is 385 periods.
pub const MAX_WRAP_PERIODS: f64 = 2.5e5;

/// Most pulleys of the wrapped string.
pub const MAX_WRAP_PULLEYS: usize = 64;

impl mbd_core::config::PartialRules for WrapConfig {}

impl Validate for WrapConfig {
    fn validate(&self) -> Result<(), InvalidField> {
        use mbd_core::validate::check::show;
        check_string(&self.string, "string")?;
        mbd_core::validate::check::size("nodes", self.nodes, 5, MAX_STRING_NODES)?;
        check_scales(&self.string, "string", "speed", self.speed, self.nodes)?;
        mbd_core::validate::check::size("pulleys", self.pulleys.len(), 1, MAX_WRAP_PULLEYS)?;
        for (i, p) in self.pulleys.iter().enumerate() {
            if !(p.radius.is_finite() && p.radius > 0.0) {
                return Err(InvalidField::new(
                    format!("pulleys[{i}].radius"),
                    format!("must be positive, got {}", show(p.radius)),
                ));
            }
            if !(p.center_x > 0.0 && p.center_x < self.string.length) {
                return Err(InvalidField::new(
                    format!("pulleys[{i}].center_x"),
                    "must lie between the anchors",
                ));
            }
            check_number(&format!("pulleys[{i}].top"), p.top, false)?;
            // the string model is one of small deflections (issue 35: top = 1e300 m ran into a
            // step size underflow, exit 1)
            mbd_core::validate::check::within(
                &format!("pulleys[{i}].top"),
                p.top,
                -self.string.length,
                self.string.length,
                "m (within the string's length of its line: small deflections)",
            )?;
            if !(self.candidate_half_width > 0.0 && self.candidate_half_width < p.radius) {
                return Err(InvalidField::new(
                    "candidate_half_width",
                    format!("must be positive and below pulleys[{i}].radius"),
                ));
            }
        }
        check_number("speed", self.speed, false)?;
        let crit = self.string.wave_speed();
        if Regime::of(&self.string, self.speed) != Regime::Subcritical {
            return Err(InvalidField::new(
                "speed",
                format!(
                    "|speed| = {} m/s must be below the critical speed c = √(T/ρA) = {crit:.4} \
                     m/s of this string (above it the travelling string between fixed \
                     supports is no initial-value problem: both waves travel downstream)",
                    show(self.speed.abs())
                ),
            ));
        }
        check_number("load.amplitude", self.load.amplitude, false)?;
        check_number("load.frequency", self.load.frequency, true)?;
        if !(self.load.x > 0.0 && self.load.x < self.string.length) {
            return Err(InvalidField::new("load.x", "must lie between the anchors"));
        }
        if !(self.duration.is_finite() && self.duration > 0.0) {
            return Err(InvalidField::new("duration", "must be positive"));
        }
        if !(self.sample.is_finite() && self.sample > 0.0 && self.sample <= self.duration) {
            return Err(InvalidField::new(
                "sample",
                "must be positive and at most the duration",
            ));
        }
        check_steps("duration", self.duration, self.sample, 1e7, "samples")?;
        let f_top = (crit * (self.nodes + 1) as f64 / (std::f64::consts::PI * self.string.length))
            .max(self.load.frequency);
        check_steps(
            "duration",
            self.duration,
            1.0 / f_top,
            MAX_WRAP_PERIODS,
            "periods of the fastest motion (the FE mesh's highest frequency or the load's)",
        )?;
        mbd_core::validate::check::size("vtk_snapshots", self.vtk_snapshots, 0, 100_000)?;
        if self.formulation == Formulation::CraigBampton && self.free_modes == 0 {
            return Err(InvalidField::new("free_modes", "must be at least 1"));
        }
        if self.formulation == Formulation::CraigBampton && self.free_modes > self.nodes {
            return Err(InvalidField::new(
                "free_modes",
                format!(
                    "must be at most nodes = {}, got {}",
                    self.nodes, self.free_modes
                ),
            ));
        }
        self.contact.validate_within("contact")?;
        Ok(())
    }
}

/// Summary of the run (`summary.json` of `flowmbd-string wrap`).
#[derive(Debug, Clone, Serialize)]
pub struct WrapSummary {
    /// Generalized coordinates.
    pub coordinates: usize,
    /// Candidate contact nodes per pulley.
    pub candidates_per_pulley: Vec<usize>,
    /// Active contact nodes per pulley in static equilibrium.
    pub initial_active_per_pulley: Vec<usize>,
    /// Static contact force per pulley \[N\].
    pub initial_force_per_pulley: Vec<f64>,
    /// Fewest active contact nodes per pulley during the run.
    pub min_active_per_pulley: Vec<usize>,
    /// Lift-off (release) events.
    pub releases: usize,
    /// Re-contact (activation) events.
    pub contacts: usize,
    /// Kinetic energy removed by plastic impacts \[J\].
    pub impact_loss: f64,
    /// Longest free span between the pulleys during the run \[m\].
    pub max_free_span: f64,
    /// Largest |gap| of an active node (constraint drift) \[m\].
    pub max_active_gap: f64,
    /// Integrator steps.
    pub steps: usize,
    /// What the numbers mean ([`WRAP_MEANING`]).
    pub meaning: String,
}

/// What the `summary`'s keys mean (the CLI's `meaning`).
pub const WRAP_MEANING: &str = "A string partly wrapped on two pulleys under a harmonic load (Ribaric (4.10), \
         (4.11), (4.40)): contact nodes lift off and land again as the load shakes the free \
         span. coordinates is the model size; candidates_, initial_active_ and \
         initial_force_per_pulley [N] describe the static wrap; min_active_per_pulley is the \
         fewest nodes in contact during the run; releases and contacts count lift-off and \
         landing events; impact_loss [J] is the kinetic energy removed by the plastic \
         landings; max_free_span [m] the longest free span reached (the wrap shrinks when \
         nodes lift off); max_active_gap [m] the largest gap of a node held in contact \
         (constraint drift, near 0 for a sound integration).";

/// Columns of `history.csv` for `n_pulleys` pulleys: time \[s\], the deflection at the load
/// \[m\], the free span \[m\], the energy \[J\], then per pulley its active contact nodes and
/// its contact force \[N\].
pub fn wrap_history_header(n_pulleys: usize) -> Vec<String> {
    let mut header = vec![
        "t_s".to_string(),
        "midload_deflection_m".into(),
        "free_span_m".into(),
        "energy_J".into(),
    ];
    header.extend((0..n_pulleys).map(|p| format!("pulley{p}_active_count")));
    header.extend((0..n_pulleys).map(|p| format!("pulley{p}_force_N")));
    header
}

/// Columns of `events.csv`.
pub const EVENTS_HEADER: [&str; 5] = [
    "t_s",
    "candidate_index",
    "node_index",
    "activated_flag",
    "impact_loss_J",
];

/// The rows of `events.csv`: time \[s\], candidate, node, 1 for a landing (0 for a lift-off),
/// the impact loss \[J\].
pub fn event_rows(events: &[ContactEvent]) -> impl Iterator<Item = [f64; 5]> + '_ {
    events.iter().map(|e| {
        [
            e.t,
            e.candidate as f64,
            e.node as f64,
            f64::from(u8::from(e.activated)),
            e.impact_loss,
        ]
    })
}

/// What the run shows its observer at every accepted step and event state.
pub struct WrapSample<'a> {
    /// The model with the active set in force.
    pub system: &'a ContactString,
    /// The state.
    pub state: &'a State,
    /// The `history.csv` row ([`wrap_history_header`]) due at this state, if one is due (every
    /// `sample` seconds).
    pub row: Option<&'a [f64]>,
    /// The index of the VTK frame due at this state, if one is due (`vtk_snapshots` over the
    /// run).
    pub frame: Option<usize>,
    /// Interior node positions \[m\].
    pub positions: &'a [f64],
}

/// A finished (or cancelled) run.
#[derive(Debug, Clone)]
pub struct WrapRun {
    /// The summary.
    pub summary: WrapSummary,
    /// The contact switches in time order (`events.csv`, [`event_rows`]).
    pub events: Vec<ContactEvent>,
    /// The `history.csv` rows.
    pub history: Vec<Vec<f64>>,
}

/// A failure of the run that is no bad input (as an [`MbdError::Model`] at time `t`).
fn failed(t: f64, message: String) -> FlowError {
    FlowError::Mbd(MbdError::Model { t, message })
}

/// Run the wrapped string (Ribaric (4.10) nodal or (4.11), (4.40) Craig–Bampton coordinates):
/// its static equilibrium on the pulleys (the initial active set), then the harmonic load for
/// `c.duration` with event location ([`simulate_contact`]). `observer` sees every accepted step
/// ([`WrapSample`], with the history row and the VTK frame when due) and may stop the run
/// (the run so far is returned).
pub fn string_wrap(
    c: &WrapConfig, observer: &mut dyn FnMut(&WrapSample<'_>) -> ControlFlow<()>,
) -> Result<WrapRun, FlowError> {
    let mesh = StringMesh::uniform(c.string, c.nodes)?;
    let cands = candidates(&mesh, &c.pulleys, c.candidate_half_width)?;
    let motion = AxialMotion::Constant { speed: c.speed };
    let mut sys = match c.formulation {
        Formulation::Nodal => {
            ContactString::nodal(&mesh, cands, c.derivative, motion, Some(c.load))
        }
        Formulation::CraigBampton => ContactString::craig_bampton(
            &mesh,
            cands,
            c.free_modes,
            c.derivative,
            motion,
            Some(c.load),
        ),
    }?;
    let np = c.pulleys.len();
    let y0 = sys.static_equilibrium()?;
    let st0 = State::new(0.0, y0.clone(), vec![0.0; y0.len()]);
    let p0 = sys.contact_forces(&st0)?;
    let count = |v: Vec<f64>| v.iter().map(|x| *x as usize).collect::<Vec<usize>>();
    let cand_pp = count(per_pulley(&sys, np, |_| 1.0));
    let act_pp = count(per_pulley(&sys, np, |c| f64::from(u8::from(sys.active[c]))));
    let force_pp = per_pulley(&sys, np, |c| p0[c]);
    let load_node = sys.load.map(|l| l.0).unwrap_or(0);
    let mut next = 0.0;
    let mut min_act = act_pp.clone();
    let mut max_span = free_span(&sys, c.string.length, np);
    let mut max_gap: f64 = 0.0;
    let mut rows: Vec<Vec<f64>> = Vec::new();
    let mut num_err: Option<FlowError> = None;
    let positions = mesh.grid.positions().to_vec();
    let vtk_dt = if c.vtk_snapshots > 0 {
        c.duration / c.vtk_snapshots as f64
    } else {
        f64::INFINITY
    };
    let mut next_vtk = 0.0;
    let mut vtk_count = 0usize;
    let run = simulate_contact(&mut sys, st0, c.duration, &c.contact, |s, st| {
        for (ci, a) in s.active.iter().enumerate() {
            if *a {
                max_gap = max_gap.max(s.gap(ci, &st.q).abs());
            }
        }
        let act: Vec<f64> = per_pulley(s, np, |k| f64::from(u8::from(s.active[k])));
        for p in 0..np {
            min_act[p] = min_act[p].min(act[p] as usize);
        }
        let span = free_span(s, c.string.length, np);
        max_span = max_span.max(span);
        let frame = (st.t + 1e-12 >= next_vtk).then(|| {
            next_vtk += vtk_dt;
            vtk_count += 1;
            vtk_count - 1
        });
        let mut row = None;
        if st.t + 1e-12 >= next {
            next += c.sample;
            let p = s.contact_forces(st).unwrap_or_else(|e| {
                num_err.get_or_insert(failed(st.t, format!("contact forces: {e}")));
                vec![0.0; s.candidates.len()]
            });
            let u = s.deflection(&st.q);
            let mut r = vec![st.t, u[load_node], span, s.energy(&st.q, &st.v, c.speed)];
            r.extend(act.iter());
            r.extend(per_pulley(s, np, |k| p[k]));
            rows.push(r);
            row = rows.last().map(|r| r.as_slice());
        }
        let sample = WrapSample {
            system: s,
            state: st,
            row,
            frame,
            positions: &positions,
        };
        observer(&sample)
    });
    if let Some(e) = num_err {
        return Err(e);
    }
    let run = run?;
    let summary = WrapSummary {
        coordinates: sys.dim(),
        candidates_per_pulley: cand_pp,
        initial_active_per_pulley: act_pp,
        initial_force_per_pulley: force_pp,
        min_active_per_pulley: min_act,
        releases: run.events.iter().filter(|e| !e.activated).count(),
        contacts: run.events.iter().filter(|e| e.activated).count(),
        impact_loss: run.events.iter().map(|e| e.impact_loss).sum(),
        max_free_span: max_span,
        max_active_gap: max_gap,
        steps: run.stats.steps,
        meaning: WRAP_MEANING.to_string(),
    };
    let numbers = summary.initial_force_per_pulley.iter().chain([
        &summary.impact_loss,
        &summary.max_free_span,
        &summary.max_active_gap,
    ]);
    if numbers.into_iter().any(|x| !x.is_finite()) {
        return Err(failed(
            run.state.t,
            format!("the contact simulation gave non-finite results: {summary:?}"),
        ));
    }
    Ok(WrapRun {
        summary,
        events: run.events,
        history: rows,
    })
}

/// The VTK frame of a sample: the deformed string (anchors included, `length` apart \[m\]), the
/// pulley circles, and the point fields `contact_force_N`, `active` and `deflection_m`.
pub fn wrap_frame(
    sample: &WrapSample<'_>, pulleys: &[PulleyObstacle], length: f64,
) -> Result<(Mesh, Vec<PointField>), FlowError> {
    let (sys, st) = (sample.system, sample.state);
    let u = sys.deflection(&st.q);
    let p = sys.contact_forces(st)?;
    let mut force = vec![0.0; u.len()];
    let mut active = vec![0.0; u.len()];
    for (c, k) in sys.candidates.iter().enumerate() {
        force[k.node] = p[c];
        active[k.node] = f64::from(u8::from(sys.active[c]));
    }
    let mut mesh = Mesh::new(1);
    let mut fvals = Vec::new();
    let mut avals = Vec::new();
    let mut uvals = Vec::new();
    let mut push = |mesh: &mut Mesh, x: f64, y: f64, f: f64, a: f64, defl: f64| {
        fvals.push(f);
        avals.push(a);
        uvals.push(defl);
        mesh.add_node([x, y, 0.0])
    };
    let line = |a, b| Cell {
        kind: CellKind::Line,
        nodes: vec![a, b],
    };
    let mut prev = push(&mut mesh, 0.0, 0.0, 0.0, 0.0, 0.0);
    for (j, x) in sample.positions.iter().enumerate() {
        let n = push(&mut mesh, *x, u[j], force[j], active[j], u[j]);
        mesh.cells.push(line(prev, n));
        prev = n;
    }
    let n = push(&mut mesh, length, 0.0, 0.0, 0.0, 0.0);
    mesh.cells.push(line(prev, n));
    for pl in pulleys {
        let segs = 96;
        let cy = pl.top - pl.radius;
        let first = mesh.n_nodes();
        for k in 0..segs {
            let a = 2.0 * std::f64::consts::PI * k as f64 / segs as f64;
            let (x, y) = (pl.center_x + pl.radius * a.cos(), cy + pl.radius * a.sin());
            let id = push(&mut mesh, x, y, 0.0, 0.0, 0.0);
            let next = if k + 1 == segs { first } else { id + 1 };
            mesh.cells.push(line(id, next));
        }
    }
    let field = |name: &str, values| PointField {
        name: name.into(),
        components: 1,
        values,
    };
    let fields = vec![
        field("contact_force_N", fvals),
        field("active", avals),
        field("deflection_m", uvals),
    ];
    Ok((mesh, fields))
}

fn per_pulley(sys: &ContactString, n: usize, f: impl Fn(usize) -> f64) -> Vec<f64> {
    let mut v = vec![0.0; n];
    for (c, k) in sys.candidates.iter().enumerate() {
        v[k.pulley] += f(c);
    }
    v
}

/// Length between the last contact on the first pulley and the first contact on the last pulley
/// (an anchor where a pulley has no contact) \[m\].
fn free_span(sys: &ContactString, length: f64, n_pulleys: usize) -> f64 {
    let right0 = sys
        .candidates
        .iter()
        .enumerate()
        .filter(|(c, k)| sys.active[*c] && k.pulley == 0)
        .map(|(_, k)| k.x)
        .fold(0.0, f64::max);
    let left1 = sys
        .candidates
        .iter()
        .enumerate()
        .filter(|(c, k)| sys.active[*c] && k.pulley + 1 == n_pulleys)
        .map(|(_, k)| k.x)
        .fold(length, f64::min);
    left1 - right0
}
