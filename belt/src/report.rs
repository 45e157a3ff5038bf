//! What a belt-drive engineer reads off a running drive, for every model and any number of
//! pulleys: span forces, the force, contact pressure and friction along every wrap, adhesion
//! and slip arcs, slip (creep) velocity, hub loads, the torque and power each pulley receives,
//! and the balances that hold them together. Computed here, once, from a model's
//! [`Snapshot`] ([`crate::model::BeltModel::snapshot`]) and its [`Drive`].
//!
//! Definitions (one set for all models):
//!
//! * **friction utilisation** `u = |f|/(μ p)` at a point (`f` friction, `p` pressure, both per
//!   unit length, `μ` the coefficient of the law on that pulley's wrap,
//!   [`FrictionLaw::coefficient`] of [`Drive::wrap_friction_law`]: `μ/sin(β/2)` on the grooved
//!   pulleys of a multi-ribbed belt);
//! * **contact arc**: from the first to the last point in contact; each point stands for the
//!   angular cell halfway to its neighbours;
//! * **slip arc** `φ_slip = ∫ u dθ` over the contact arc: the arc over which a Coulomb belt
//!   slides (`u = 1`) to build the same tension ratio, with adhesion (`u = 0`) elsewhere. For a
//!   string on a pulley (`p = T/R`, `dT = ±f R dθ`) the force ratio across the wrap is
//!   `T_in/T_out = e^{±μ φ_slip}`: Euler–Eytelwein on the slip arc (Grashof's active arc for
//!   Coulomb friction; the Coulomb-equivalent arc for a regularised law);
//! * **adhesion arc**: contact arc minus slip arc; **saturated arc**: where `u ≥`
//!   [`SLIP_UTILISATION`];
//! * **gross slip** ([`Report::gross_slip`]): the adhesion arc is below
//!   [`GROSS_SLIP_ADHESION`] of the contact arc: the wrap slides as a whole;
//! * **torque balance** per pulley: the belt's contact torque `τ` (travel sense) against the
//!   moment `T_out ℓ_out − T_in ℓ_in` of the forces of the spans leaving and reaching it about
//!   its centre, `ℓ` the lever of each span's line of action ([`SpanState::line`],
//!   [`crate::LineOfAction::lever`]; the belt-line radius `R` on the undeformed path, `R` also
//!   where a model gives no line), less the angular momentum the moving belt carries out
//!   through the two sections where the model states it ([`SpanState::momentum_flux`]: the
//!   ANCF, flowing and nodal belts; [`span_momentum_fluxes`]): moment balance of the belt from the middle of one span over the wrap to the
//!   middle of the next (a steady wrap: the belt's inertia on the wrap enters only while its
//!   speed changes). A deformed belt's spans do not leave the pulleys
//!   along the undeformed tangents: on Table 6-1 at 10 N m the flowing model's tight span acts
//!   0.10 mm and 0.16 mm outside `R` at the driver and the driven pulley; `(T_out − T_in) R`
//!   missed the contact torques by 0.43 % and 0.75 % there, the lines of action by 0.24 % and
//!   0.19 % (issue 34). The residual is stated absolutely and relative to the largest pulley
//!   torque of the drive;
//! * **power balance** of the belt: the power the pulleys put into the belt,
//!   `−Σ (τ ω + F_hub · ċ)` (drivers positive, accessories negative, a tensioner idler's moving
//!   centre included), against the sliding losses `−∫ f v_slip ds` and the belt's own damping
//!   ([`Snapshot::belt_dissipation`]); at one instant the difference is the rate of change of
//!   the belt's energy, over whole periods of a steady state zero ([`Report::mean`]).

use crate::layout::Drive;
use crate::model::{Snapshot, SpanState, WrapPoint};
use crate::motion::Role;
use crate::path::{BeltPath, LineOfAction};
use contact::friction::FrictionLaw;
use serde::Serialize;

/// Friction utilisation `|f|/(μ p)` from which a contact point counts as saturated. For the
/// tanh law (6.2) this is a slip speed of `atanh(0.95)/κ` (4.6 cm/s at κ = 40 s/m).
pub const SLIP_UTILISATION: f64 = 0.95;

/// A wrap whose adhesion arc is shorter than this fraction of its contact arc slides as a
/// whole (gross slip): its mean friction utilisation exceeds 95 %.
pub const GROSS_SLIP_ADHESION: f64 = 0.05;

/// Per-pulley results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PulleyReport {
    /// Name.
    pub name: String,
    /// Role.
    pub role: Role,
    /// Speed in the travel sense \[rad/s\].
    pub omega: f64,
    /// Contact arc \[rad\].
    pub contact_arc_rad: f64,
    /// Slip arc `∫ |f|/(μ p) dθ` \[rad\] (module documentation).
    pub slip_arc_rad: f64,
    /// Adhesion arc: contact arc minus slip arc \[rad\].
    pub adhesion_arc_rad: f64,
    /// Saturated arc: where the utilisation reaches [`SLIP_UTILISATION`] \[rad\].
    pub saturated_arc_rad: f64,
    /// Largest slip (creep) speed over the contact arc \[m/s\].
    pub slip_velocity_max_m_s: f64,
    /// Mean slip velocity over the contact arc (weighted by angle), signed \[m/s\].
    pub slip_velocity_mean_m_s: f64,
    /// Power lost to sliding on this pulley, `−∫ f v_slip ds` \[W\].
    pub sliding_power_w: f64,
    /// Force of the belt on the pulley (hub load) \[N\].
    pub hub_load_n: [f64; 2],
    /// Magnitude of the hub load \[N\] (of the mean force for a window mean).
    pub hub_load_magnitude_n: f64,
    /// Torque the belt exerts on the pulley in its travel sense \[N m\].
    pub torque_n_m: f64,
    /// Power the belt delivers to the pulley, `τ ω + F_hub · ċ` \[W\] (negative on a driver).
    pub power_w: f64,
    /// Force of the span running onto the pulley \[N\].
    pub tension_in_n: f64,
    /// Force of the span leaving the pulley \[N\].
    pub tension_out_n: f64,
    /// `T_out ℓ_out − T_in ℓ_in`: the moment of the span forces about the pulley's centre,
    /// `ℓ` the lever of each span's line of action, less the moment of the momentum flux
    /// where the model states it (module documentation) \[N m\].
    pub span_torque_n_m: f64,
    /// Torque balance residual `τ − (T_out ℓ_out − T_in ℓ_in)` \[N m\].
    pub torque_residual_n_m: f64,
}

/// Per-span results.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpanReport {
    /// Pulley the span leaves.
    pub from: usize,
    /// Pulley the span reaches.
    pub to: usize,
    /// Axial force \[N\] (the model's force measure).
    pub tension_n: f64,
    /// Transverse displacement of the mid-point \[m\].
    pub transverse_m: f64,
    /// Transverse vibration amplitude of the mid-point, half the peak-to-peak over an
    /// observation window \[m\] (`None` when not observed).
    pub vibration_amplitude_m: Option<f64>,
}

/// The balances of one report (module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Balances {
    /// Largest torque-balance residual over the pulleys relative to the largest pulley torque
    /// \[-\].
    pub torque_residual_rel: f64,
    /// Power into the belt from the pulleys `−Σ (τ ω + F_hub · ċ)` \[W\].
    pub power_in_w: f64,
    /// Sliding losses over all wraps \[W\].
    pub sliding_w: f64,
    /// Dissipation in the belt's own damping \[W\] (`null`: not evaluated by the model).
    pub belt_damping_w: Option<f64>,
    /// Power residual `power_in − sliding − belt_damping` \[W\] (the rate of change of the
    /// belt's energy; zero on average over whole periods of a steady state).
    pub power_residual_w: f64,
    /// Power residual relative to the power the drivers deliver \[-\].
    pub power_residual_rel: f64,
    /// Power the speed-driven pulleys deliver to the belt \[W\].
    pub driver_power_w: f64,
}

/// Largest relative torque and power residual \[-\] at which a report's balances hold: 0.5 %,
/// the bound of issue 34 item 2, which the ANCF and nodal belts keep on Table 6-1, the
/// Pechstein–Gerstmayr drive and the default FEAD drive (`flowmbd-validation`
/// `belt_balances`).
pub const BALANCE_TOLERANCE: f64 = 5e-3;

impl Balances {
    /// The residuals beyond `bound` \[-\] (e.g. [`BALANCE_TOLERANCE`]), as
    /// "torque residual +0.72 %, power residual −1.88 % (bound 0.5 %)", or `None` when both
    /// are within it: the torque residual relative to the largest pulley torque, the power
    /// residual relative to the drivers' power (a NaN residual counts as beyond). A model
    /// whose forces on the pulleys are carried by its reported spans and which neither creates
    /// nor loses energy keeps both near zero at a steady state (module documentation).
    pub fn beyond(&self, bound: f64) -> Option<String> {
        let miss = |what: &str, r: f64| {
            (r.abs() > bound || r.is_nan()).then(|| format!("{what} {:+.2} %", 100.0 * r))
        };
        let misses: Vec<String> = [
            miss("torque residual", self.torque_residual_rel),
            miss("power residual", self.power_residual_rel),
        ]
        .into_iter()
        .flatten()
        .collect();
        (!misses.is_empty()).then(|| format!("{} (bound {} %)", misses.join(", "), 100.0 * bound))
    }
}

/// The report of one state, or the mean of a window of states ([`Report::mean`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Time of the snapshot (of the last one for a mean) \[s\].
    pub time_s: f64,
    /// Pulleys in travel order.
    pub pulleys: Vec<PulleyReport>,
    /// Spans in travel order.
    pub spans: Vec<SpanReport>,
    /// Torque and power balances.
    pub balances: Balances,
}

/// The belt's force on one pulley (a summary entry).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HubLoad {
    /// Pulley name.
    pub name: String,
    /// Force of the belt on the pulley (x, y) \[N\].
    pub force_n: [f64; 2],
    /// Its magnitude \[N\].
    pub magnitude_n: f64,
}

/// Arcs, slip and sliding power of the points `on` of one wrap (sorted by angle).
fn wrap_arcs(on: &[&WrapPoint], mu: f64) -> [f64; 6] {
    let n = on.len();
    let (mut arc, mut slip_arc, mut saturated) = (0.0, 0.0, 0.0);
    let (mut vmax, mut vsum, mut power) = (0.0f64, 0.0, 0.0);
    for (i, w) in on.iter().enumerate() {
        // angular cell: halfway to the neighbours, ending at the first and last point
        let lo = if i == 0 {
            w.angle
        } else {
            0.5 * (on[i - 1].angle + w.angle)
        };
        let hi = if i + 1 == n {
            w.angle
        } else {
            0.5 * (w.angle + on[i + 1].angle)
        };
        let cell = hi - lo;
        let u = w.utilisation(mu);
        arc += cell;
        slip_arc += u.min(1.0) * cell;
        if u >= SLIP_UTILISATION {
            saturated += cell;
        }
        vmax = vmax.max(w.slip.abs());
        vsum += w.slip * cell;
        power -= w.friction * w.slip * w.length;
    }
    let vmean = if arc > 0.0 { vsum / arc } else { 0.0 };
    [arc, slip_arc, saturated, vmax, vmean, power]
}

impl Report {
    /// The report of `snap` of a model of `drive`, with the friction coefficient of each
    /// pulley's wrap ([`Drive::wrap_friction_coefficients`]: `μ/sin(β/2)` on the grooved
    /// pulleys of a multi-ribbed belt, the law the models contact that pulley with).
    pub fn new(drive: &Drive, snap: &Snapshot) -> Self {
        Self::of(drive.pulleys(), snap, &drive.wrap_friction_coefficients())
    }

    /// The report of `snap` of a belt running over `pulleys` (names, roles and belt-line radii
    /// taken from them), with the friction coefficient `mu[k]` of the law on pulley `k`'s wrap
    /// (travel order; one per pulley).
    ///
    /// # Panics
    /// `mu` has fewer entries than `snap` has pulleys.
    pub fn of(pulleys: &[crate::pulley::Pulley], snap: &Snapshot, mu: &[f64]) -> Self {
        let names: Vec<String> = pulleys.iter().map(|p| p.name.clone()).collect();
        let roles: Vec<Role> = pulleys.iter().map(|p| p.motion.role()).collect();
        let radius: Vec<f64> = pulleys.iter().map(|p| p.radius).collect();
        let turn: Vec<f64> = pulleys.iter().map(|p| p.side.turn()).collect();
        let spans: Vec<SpanReport> = snap
            .spans
            .iter()
            .map(|s| SpanReport {
                from: s.from,
                to: s.to,
                tension_n: s.tension,
                transverse_m: s.transverse,
                vibration_amplitude_m: None,
            })
            .collect();
        // (force, its moment less that of the momentum flux) about pulley k of the span
        // matching `f`
        let span_t = |f: &dyn Fn(&SpanState) -> bool, k: usize| {
            snap.spans
                .iter()
                .find(|s| f(s))
                .map_or((f64::NAN, f64::NAN), |s| {
                    let c = snap.pulleys[k].center;
                    let lever = s.line.map_or(radius[k], |l| l.lever(c, turn[k]));
                    let flux = s
                        .momentum_flux
                        .map_or(0.0, |(m, l)| m * l.lever(c, turn[k]));
                    (s.tension, s.tension * lever - flux)
                })
        };
        let pulleys: Vec<PulleyReport> = snap
            .pulleys
            .iter()
            .enumerate()
            .map(|(k, p)| {
                let mut on: Vec<&WrapPoint> = snap
                    .wrap
                    .iter()
                    .filter(|w| w.pulley == k && w.pressure > 0.0)
                    .collect();
                on.sort_by(|a, b| a.angle.total_cmp(&b.angle));
                let [arc, slip_arc, saturated, vmax, vmean, sliding] = wrap_arcs(&on, mu[k]);
                let ((t_in, m_in), (t_out, m_out)) =
                    (span_t(&|s| s.to == k, k), span_t(&|s| s.from == k, k));
                let span_torque = m_out - m_in;
                PulleyReport {
                    name: names[k].clone(),
                    role: roles[k],
                    omega: p.omega,
                    contact_arc_rad: arc,
                    slip_arc_rad: slip_arc,
                    adhesion_arc_rad: arc - slip_arc,
                    saturated_arc_rad: saturated,
                    slip_velocity_max_m_s: vmax,
                    slip_velocity_mean_m_s: vmean,
                    sliding_power_w: sliding,
                    hub_load_n: p.hub_load,
                    hub_load_magnitude_n: p.hub_load[0].hypot(p.hub_load[1]),
                    torque_n_m: p.torque,
                    power_w: p.torque * p.omega
                        + p.hub_load[0] * p.center_velocity[0]
                        + p.hub_load[1] * p.center_velocity[1],
                    tension_in_n: t_in,
                    tension_out_n: t_out,
                    span_torque_n_m: span_torque,
                    torque_residual_n_m: p.torque - span_torque,
                }
            })
            .collect();
        let balances = Self::balances(&pulleys, snap.belt_dissipation);
        Self {
            time_s: snap.time,
            pulleys,
            spans,
            balances,
        }
    }

    fn balances(pulleys: &[PulleyReport], belt_damping: Option<f64>) -> Balances {
        let scale = pulleys
            .iter()
            .map(|p| p.torque_n_m.abs())
            .fold(0.0, f64::max);
        let torque_residual_rel = pulleys
            .iter()
            .map(|p| p.torque_residual_n_m.abs())
            .fold(0.0, f64::max)
            / scale;
        let power_in: f64 = -pulleys.iter().map(|p| p.power_w).sum::<f64>();
        let sliding: f64 = pulleys.iter().map(|p| p.sliding_power_w).sum();
        let driver: f64 = -pulleys
            .iter()
            .filter(|p| p.role == Role::Driver)
            .map(|p| p.power_w)
            .sum::<f64>();
        let damping = belt_damping.unwrap_or(0.0);
        let residual = power_in - sliding - damping;
        Balances {
            torque_residual_rel,
            power_in_w: power_in,
            sliding_w: sliding,
            belt_damping_w: belt_damping,
            power_residual_w: residual,
            power_residual_rel: residual / driver.abs(),
            driver_power_w: driver,
        }
    }

    /// The mean of `reports` (same drive, at least one): every number averaged, the time of
    /// the last; the balances recomputed from the averaged terms. A steady state of a rotating
    /// mesh (nodal, ANCF) carries the ripple of its element passing: its results are window
    /// means; averaged over whole periods the power residual (the change of the belt's energy)
    /// vanishes.
    pub fn mean(reports: &[Report]) -> Option<Report> {
        let last = reports.last()?;
        let n = reports.len() as f64;
        let avg = |f: &dyn Fn(&Report) -> f64| reports.iter().map(f).sum::<f64>() / n;
        let pulleys: Vec<PulleyReport> = (0..last.pulleys.len())
            .map(|k| {
                let p = |f: fn(&PulleyReport) -> f64| avg(&|r: &Report| f(&r.pulleys[k]));
                let hub = [p(|q| q.hub_load_n[0]), p(|q| q.hub_load_n[1])];
                PulleyReport {
                    name: last.pulleys[k].name.clone(),
                    role: last.pulleys[k].role,
                    omega: p(|q| q.omega),
                    contact_arc_rad: p(|q| q.contact_arc_rad),
                    slip_arc_rad: p(|q| q.slip_arc_rad),
                    adhesion_arc_rad: p(|q| q.adhesion_arc_rad),
                    saturated_arc_rad: p(|q| q.saturated_arc_rad),
                    slip_velocity_max_m_s: p(|q| q.slip_velocity_max_m_s),
                    slip_velocity_mean_m_s: p(|q| q.slip_velocity_mean_m_s),
                    sliding_power_w: p(|q| q.sliding_power_w),
                    hub_load_n: hub,
                    hub_load_magnitude_n: hub[0].hypot(hub[1]),
                    torque_n_m: p(|q| q.torque_n_m),
                    power_w: p(|q| q.power_w),
                    tension_in_n: p(|q| q.tension_in_n),
                    tension_out_n: p(|q| q.tension_out_n),
                    span_torque_n_m: p(|q| q.span_torque_n_m),
                    torque_residual_n_m: p(|q| q.torque_residual_n_m),
                }
            })
            .collect();
        let spans = (0..last.spans.len())
            .map(|k| {
                let s = |f: fn(&SpanReport) -> f64| avg(&|r: &Report| f(&r.spans[k]));
                SpanReport {
                    from: last.spans[k].from,
                    to: last.spans[k].to,
                    tension_n: s(|q| q.tension_n),
                    transverse_m: s(|q| q.transverse_m),
                    vibration_amplitude_m: last.spans[k].vibration_amplitude_m,
                }
            })
            .collect();
        // the mean where every report has it
        let belt_damping = reports
            .iter()
            .map(|r| r.balances.belt_damping_w)
            .sum::<Option<f64>>()
            .map(|s| s / n);
        let balances = Self::balances(&pulleys, belt_damping);
        Some(Report {
            time_s: last.time_s,
            pulleys,
            spans,
            balances,
        })
    }

    /// The first pulley (travel order) whose adhesion arc has shrunk below
    /// [`GROSS_SLIP_ADHESION`] of its contact arc (gross slip). `None` while every wrap keeps
    /// an adhesion arc.
    pub fn gross_slip(&self) -> Option<usize> {
        self.pulleys.iter().position(|p| {
            p.contact_arc_rad > 0.0 && p.adhesion_arc_rad < GROSS_SLIP_ADHESION * p.contact_arc_rad
        })
    }

    /// The hub load of every pulley, in travel order.
    pub fn hub_loads(&self) -> Vec<HubLoad> {
        self.pulleys
            .iter()
            .map(|q| HubLoad {
                name: q.name.clone(),
                force_n: q.hub_load_n,
                magnitude_n: q.hub_load_magnitude_n,
            })
            .collect()
    }

    /// Index of the first pulley with `role`.
    pub fn find(&self, role: Role) -> Option<usize> {
        self.pulleys.iter().position(|p| p.role == role)
    }

    /// Slip arc \[rad\] of the first pulley with `role` (`NaN` if there is none).
    pub fn slip_arc(&self, role: Role) -> f64 {
        self.find(role)
            .map_or(f64::NAN, |k| self.pulleys[k].slip_arc_rad)
    }

    /// Force of the tight span (running onto the first driver) \[N\].
    pub fn tension_tight(&self) -> f64 {
        self.find(Role::Driver)
            .map_or(f64::NAN, |d| self.pulleys[d].tension_in_n)
    }

    /// Force of the slack span (leaving the first driver) \[N\].
    pub fn tension_slack(&self) -> f64 {
        self.find(Role::Driver)
            .map_or(f64::NAN, |d| self.pulleys[d].tension_out_n)
    }
}

/// Force and transverse mid-point displacement of every span of `path` for a belt whose
/// deformed nodes are `nodes` (closed polyline) and whose element `i → i+1` carries
/// `forces[i]` \[N\]: the mean force of the elements over the middle half of the span that run
/// without a break from its bisector ([`crate::path::SpanLine::middle_run`]: not the elements
/// of another span that passes within the band), the polyline's crossing of the span's
/// bisector and the line of action through its nodes over the middle half
/// ([`BeltPath::lines_of_action`]).
pub fn span_states(path: &BeltPath, nodes: &[[f64; 2]], forces: &[f64]) -> Vec<SpanState> {
    let spans = path.spans();
    let sum: Vec<(f64, usize)> = spans
        .iter()
        .map(|sp| {
            let run = sp.middle_run(nodes);
            (run.iter().map(|&i| forces[i]).sum(), run.len())
        })
        .collect();
    spans
        .iter()
        .zip(span_offsets(path, nodes))
        .zip(sum)
        .zip(path.lines_of_action(nodes))
        .map(|(((sp, transverse), (t, k)), line)| SpanState {
            from: sp.from,
            to: sp.to,
            tension: if k == 0 { f64::NAN } else { t / k as f64 },
            transverse,
            line,
            momentum_flux: None,
        })
        .collect()
}

/// The momentum flux of every span of `path` ([`SpanState::momentum_flux`]) from the
/// momentum `flux[i]` = `ṁ_i V_i` \[N\] the belt carries through a section fixed in space at
/// node `i` of the deformed closed polyline `nodes` (`ṁ` the mass flow \[kg/s\], `V` the
/// material velocity \[m/s\]): the resultant and moment `Σ p × φ` of the fluxes at both ends of
/// the elements over the span's middle half ([`crate::path::SpanLine::middle_run`], the same
/// sections as [`span_states`]), averaged, and their line
/// ([`LineOfAction::of_resultant`]). `None` where the span has no such elements.
pub fn span_momentum_fluxes(
    path: &BeltPath, nodes: &[[f64; 2]], flux: &[[f64; 2]],
) -> Vec<Option<(f64, LineOfAction)>> {
    let n = nodes.len();
    path.spans()
        .iter()
        .map(|sp| {
            let run = sp.middle_run(nodes);
            if run.is_empty() {
                return None;
            }
            let (mut f, mut m) = ([0.0; 2], 0.0);
            for &e in &run {
                for i in [e, (e + 1) % n] {
                    let (p, phi) = (nodes[i], flux[i]);
                    f[0] += phi[0];
                    f[1] += phi[1];
                    m += p[0] * phi[1] - p[1] * phi[0];
                }
            }
            let k = 2.0 * run.len() as f64;
            LineOfAction::of_resultant([f[0] / k, f[1] / k], m / k, sp.direction)
        })
        .collect()
}

/// Transverse displacement \[m\] of the mid-point of every span of `path` for the deformed
/// closed polyline `nodes` ([`SpanState::transverse`]).
pub fn span_offsets(path: &BeltPath, nodes: &[[f64; 2]]) -> Vec<f64> {
    path.spans()
        .iter()
        .map(|sp| {
            sp.bisector_crossing(nodes)
                .map_or(f64::NAN, |p| sp.local(p).1)
        })
        .collect()
}

/// Slip speed \[m/s\] at which the friction law's force reaches the fraction `eta` of `μ|f_n|`
/// (the sliding branch of the law): `atanh(η)/κ` for the tanh law (6.2). Found by doubling from
/// 1 µm/s and bisection; infinite if the law never reaches it below 100 m/s.
pub fn sliding_speed(law: &impl FrictionLaw, eta: f64) -> f64 {
    let mu = law.coefficient();
    if mu <= 0.0 {
        return f64::INFINITY;
    }
    let reached = |v: f64| law.friction(v, 1.0).force.abs() >= eta * mu;
    let mut hi = 1e-6;
    while !reached(hi) {
        hi *= 2.0;
        if hi > 100.0 {
            return f64::INFINITY;
        }
    }
    mbd_core::roots::bisect(0.0, hi, reached, mbd_core::roots::Stop::iterations(60)).1
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::Layout;
    use crate::model::{PulleyState, SpanState};
    use crate::section::Section;
    use crate::signal::Signal;
    use contact::friction::CoulombTanh;

    // the tanh law (6.2) reaches η μ at atanh(η)/κ (definition of the law)
    #[test]
    fn sliding_speed_of_the_tanh_law() {
        let law = CoulombTanh {
            mu: 1.2,
            kappa: 40.0,
        };
        let v = sliding_speed(&law, 0.95);
        assert!((v - 0.95f64.atanh() / 40.0).abs() < 1e-12, "{v}");
    }

    /// A string on the driven pulley of a two-pulley drive: saturated friction on the last
    /// `phi_slip` of a π wrap (Coulomb slip arc) and none before; spans, pulley torques and
    /// hub loads of the string's statics.
    ///
    /// The drive's contact law is the tanh law with `mu`, or with `ribs` (wedge angle) the law
    /// whose grooved wraps hold `mu`: `μ = mu · sin(β/2)`.
    fn capstan_snapshot(mu: f64, phi_slip: f64, ribs: Option<f64>) -> (Drive, Snapshot, f64, f64) {
        let (r, t_out) = (0.05, 100.0);
        let mut layout = Layout::two_pulley(
            0.45,
            r,
            r,
            Signal::constant(10.0),
            0.01,
            Signal::constant(1.0),
            Section::default(),
            300.0,
        );
        layout.belt.ribs = ribs.map(|b| crate::Ribs {
            count: 6,
            wedge_angle: b,
        });
        layout.contact.friction = contact::friction::FrictionSpec::Tanh {
            mu: mu * ribs.map_or(1.0, |b| (0.5 * b).sin()),
            kappa: 40.0,
        };
        let drive = layout.resolve().unwrap();
        let n = 2001;
        let pi = std::f64::consts::PI;
        let dphi = pi / (n - 1) as f64;
        let t_in = t_out * (mu * phi_slip).exp();
        let mut wrap = Vec::new();
        for i in 0..n {
            let phi = i as f64 * dphi;
            // the force rises from the inlet (slack) over the slip arc at the end of the wrap
            let slipping = phi > pi - phi_slip;
            let tension = if slipping {
                t_out * (mu * (phi - (pi - phi_slip))).exp()
            } else {
                t_out
            };
            wrap.push(WrapPoint {
                pulley: 1,
                angle: phi,
                length: dphi * r,
                tension,
                pressure: tension / r,
                friction: if slipping { mu * tension / r } else { 0.0 },
                slip: if slipping { -0.1 } else { 0.0 },
            });
        }
        // driven pulley: slack span in, tight span out; τ = (T_out − T_in) R on the driven,
        // the opposite on the driver
        let torque = (t_in - t_out) * r;
        let pulley = |omega: f64, torque: f64, hub: f64| PulleyState {
            omega,
            hub_load: [hub, 0.0],
            torque,
            center_velocity: [0.0; 2],
            center: [0.0; 2],
        };
        let snap = Snapshot {
            time: 0.0,
            pulleys: vec![
                pulley(10.0, -torque, t_in + t_out),
                pulley(10.0, torque, -(t_in + t_out)),
            ],
            spans: vec![
                SpanState {
                    from: 0,
                    to: 1,
                    tension: t_out,
                    transverse: 0.0,
                    line: None,
                    momentum_flux: None,
                },
                SpanState {
                    from: 1,
                    to: 0,
                    tension: t_in,
                    transverse: 0.0,
                    line: None,
                    momentum_flux: None,
                },
            ],
            wrap,
            belt_dissipation: Some(0.0),
        };
        (drive, snap, t_in, t_out)
    }

    // Euler–Eytelwein on the slip arc: a string with saturated friction over the last 2 rad
    // of a π wrap builds the force ratio e^{μ·2}; the report finds slip arc 2 rad (also the
    // saturated arc), adhesion π − 2, and the sliding power −∫ f v ds = 0.1 (T_in − T_out).
    // The string's statics close the balances: τ = (T_out − T_in) R on each pulley (torque
    // residual 0), and the power the driver puts in is the driven pulley's (power residual the
    // sliding loss, which this snapshot's wrap carries and its pulleys do not).
    #[test]
    fn arcs_and_balances_of_a_capstan_wrap() {
        let (mu, phi_slip) = (0.5, 2.0);
        let (drive, snap, t_in, t_out) = capstan_snapshot(mu, phi_slip, None);
        let rep = Report::new(&drive, &snap);
        let p = &rep.pulleys[1];
        let (pi, dphi) = (std::f64::consts::PI, std::f64::consts::PI / 2000.0);
        assert!((p.contact_arc_rad - pi).abs() < 1e-12);
        assert!(
            (p.slip_arc_rad - phi_slip).abs() < 2.0 * dphi,
            "{}",
            p.slip_arc_rad
        );
        assert!((p.saturated_arc_rad - phi_slip).abs() < 2.0 * dphi);
        assert!((p.adhesion_arc_rad - (pi - phi_slip)).abs() < 2.0 * dphi);
        assert!(((t_in / t_out).ln() / mu - p.slip_arc_rad).abs() < 2.0 * dphi);
        assert_eq!(rep.gross_slip(), None);
        let expect = 0.1 * (t_in - t_out);
        assert!(
            (p.sliding_power_w / expect - 1.0).abs() < 2e-3,
            "{}",
            p.sliding_power_w
        );
        // torque balance closes on both pulleys
        for q in &rep.pulleys {
            assert!(
                q.torque_residual_n_m.abs() < 1e-9 * q.torque_n_m.abs(),
                "{q:?}"
            );
        }
        assert!(rep.balances.torque_residual_rel < 1e-12);
        assert_eq!(rep.tension_tight(), t_in);
        assert_eq!(rep.tension_slack(), t_out);
        // power: the driver gives τ ω, the driven pulley takes it; the belt's balance is short
        // by the sliding power of the wrap
        let b = rep.balances;
        assert!((b.driver_power_w - (t_in - t_out) * 0.05 * 10.0).abs() < 1e-9);
        assert!(b.power_in_w.abs() < 1e-9);
        assert!((b.power_residual_w + p.sliding_power_w).abs() < 1e-9);
        // a window mean of two equal reports is the report
        let m = Report::mean(&[rep.clone(), rep.clone()]).unwrap();
        assert_eq!(m.pulleys[1].slip_arc_rad, rep.pulleys[1].slip_arc_rad);
    }

    // Balances::beyond names what misses the bound and nothing else. Reference: the
    // capstan wrap above, whose torque balance closes to 1e-12 and whose power balance is
    // short by exactly the wrap's sliding power (the snapshot's pulleys carry no sliding).
    #[test]
    fn the_balance_issue_names_each_residual_beyond_the_bound() {
        let (drive, snap, _, _) = capstan_snapshot(0.5, 2.0, None);
        let b = Report::new(&drive, &snap).balances;
        let rel = b.power_residual_rel;
        assert!(rel < -BALANCE_TOLERANCE, "{b:?}");
        let why = b
            .beyond(BALANCE_TOLERANCE)
            .expect("the power residual is beyond the bound");
        assert!(
            why.contains(&format!("power residual {:+.2} %", 100.0 * rel)),
            "{why}"
        );
        assert!(!why.contains("torque"), "{why}");
        let within = Balances {
            power_residual_rel: 0.9 * BALANCE_TOLERANCE,
            torque_residual_rel: -0.9 * BALANCE_TOLERANCE,
            ..b
        };
        assert_eq!(within.beyond(BALANCE_TOLERANCE), None);
        let torque = Balances {
            torque_residual_rel: 1.1 * BALANCE_TOLERANCE,
            ..within
        };
        let why = torque.beyond(BALANCE_TOLERANCE).unwrap();
        assert!(
            why.contains("torque residual +0.55 %") && !why.contains("power"),
            "{why}"
        );
        let nan = Balances {
            power_residual_rel: f64::NAN,
            ..within
        };
        assert!(nan.beyond(BALANCE_TOLERANCE).is_some());
        // a wider bound takes the capstan's power residual in
        assert_eq!(b.beyond(1.1 * rel.abs()), None);
    }

    // Angular momentum balance of the steady belt between the middles of two spans (module
    // documentation): the contact torque is the moment of the section forces less that of the
    // momentum carried out, `ṁv` along each span. With the momentum of the span leaving the
    // driven pulley on a line offset by d outward (lever R + d about both pulleys, a common
    // external tangent) and the other on the undeformed tangent (lever R), the driven pulley
    // transmits Φ d less than (T_in − T_out) R and the driver Φ d more; the report closes both
    // balances with the fluxes and misses them by Φ d without.
    #[test]
    fn momentum_flux_enters_the_torque_balance_through_its_levers() {
        let (drive, mut snap, _, _) = capstan_snapshot(0.5, 2.0, None);
        let (phi, d) = (20.0, 1e-3);
        let spans = drive.path().spans();
        let line = |k: usize, off: f64| {
            let sp = spans.iter().find(|s| s.from == k).unwrap();
            let e = sp.direction;
            // the pulleys are wrapped clockwise: their centres lie right of the travel
            let left = [-e[1], e[0]];
            crate::LineOfAction {
                point: [sp.start[0] + off * left[0], sp.start[1] + off * left[1]],
                direction: e,
            }
        };
        for s in &mut snap.spans {
            let off = if s.from == 1 { d } else { 0.0 };
            s.momentum_flux = Some((phi, line(s.from, off)));
        }
        snap.pulleys[1].torque -= phi * d;
        snap.pulleys[0].torque += phi * d;
        let rep = Report::new(&drive, &snap);
        for q in &rep.pulleys {
            assert!(q.torque_residual_n_m.abs() < 1e-9, "{q:?}");
        }
        for s in &mut snap.spans {
            s.momentum_flux = None;
        }
        let rep = Report::new(&drive, &snap);
        for q in &rep.pulleys {
            assert!(
                (q.torque_residual_n_m.abs() - phi * d).abs() < 1e-9,
                "{q:?}"
            );
        }
    }

    // a wrap without adhesion is gross slip (definition: adhesion arc below 5 % of the contact
    // arc)
    #[test]
    fn a_fully_sliding_wrap_is_gross_slip() {
        let (drive, snap, _, _) = capstan_snapshot(0.5, std::f64::consts::PI, None);
        let rep = Report::new(&drive, &snap);
        assert_eq!(rep.gross_slip(), Some(1));
    }

    // Ribs: the report measures a grooved wrap's utilisation against μ/sin(β/2) (Johnson
    // §8.6), the μ of the law the models contact it with. A string saturated over the last
    // 1.5 rad with μ' = 0.9 builds e^{0.9·1.5} (Euler–Eytelwein with μ'): the report of the
    // ribbed drive (contact law μ = 0.9 sin 20°) finds slip arc 1.5 rad = ln(T_in/T_out)/μ',
    // and a sliding point's utilisation 1 (against the flat μ it would be 1/sin 20° = 2.92).
    #[test]
    fn a_ribbed_wrap_is_measured_against_its_wedge_coefficient() {
        let (mu_eff, phi_slip, beta) = (0.9, 1.5, 40f64.to_radians());
        let (drive, snap, t_in, t_out) = capstan_snapshot(mu_eff, phi_slip, Some(beta));
        let mu = drive.wrap_friction_coefficients();
        assert!((mu[1] - mu_eff).abs() < 1e-12, "{mu:?}");
        let rep = Report::new(&drive, &snap);
        let p = &rep.pulleys[1];
        let dphi = std::f64::consts::PI / 2000.0;
        assert!(
            (p.slip_arc_rad - phi_slip).abs() < 2.0 * dphi,
            "{}",
            p.slip_arc_rad
        );
        assert!(((t_in / t_out).ln() / mu_eff - p.slip_arc_rad).abs() < 2.0 * dphi);
        assert_eq!(rep.gross_slip(), None);
        let last = snap.wrap.last().unwrap();
        assert!((last.utilisation(mu[1]) - 1.0).abs() < 1e-12);
        assert!((mu[0] - mu_eff).abs() < 1e-12, "both wraps grooved");
    }
}
