//! What a belt-drive engineer reads off a running drive, for any model and any number of
//! pulleys: span tensions, the tension, contact pressure and friction along every wrap, the
//! adhesion and slip arcs per pulley, the slip (creep) velocity, hub loads and the torque each
//! pulley receives.
//!
//! A model ([`crate::DriveModel::snapshot`]) hands over a [`DriveSnapshot`]: the contact points
//! of every wrap ([`WrapPoint`]: belt nodes of the flowing and nodal belts, contact quadrature
//! points of the ANCF belt, each with the angular width it stands for), the pulleys' hub loads
//! and torques and the span tensions. [`DriveReport::new`] turns it into per-pulley and
//! per-span results with one set of definitions for all models:
//!
//! * **friction utilisation** `u = |f|/(μ p)` at a point (`f` friction, `p` pressure, both per
//!   unit length, `μ` the law's coefficient [`FrictionLaw::coefficient`]);
//! * **contact arc**: from the first to the last point in contact; each point stands for the
//!   angular cell halfway to its neighbours;
//! * **slip arc** `φ_slip = ∫ u dθ` over the contact arc: the arc over which a Coulomb belt
//!   slides (`u = 1`) to build the same tension ratio, with adhesion (`u = 0`) elsewhere. For a
//!   string on a pulley (`p = T/R`, `dT = ±f R dθ`) the tension ratio across the wrap is
//!   `T_in/T_out = e^{±μ φ_slip}`: Euler–Eytelwein on the slip arc. With Coulomb friction it is
//!   the classical active arc (Grashof); with a regularised law (Ribaric's tanh (6.2),
//!   κ = 40 s/m) the friction carries the load at creep speeds of a few mm/s, partly utilised
//!   over the whole wrap, and `φ_slip` is the Coulomb-equivalent arc;
//! * **adhesion arc**: contact arc minus slip arc;
//! * **saturated arc**: the part of the contact arc where the friction is within
//!   `1 − `[`SLIP_UTILISATION`] of saturation: where the belt visibly slides;
//! * **gross slip** ([`DriveReport::gross_slip`]): the slip arc covers the whole wrap (the
//!   adhesion arc is below [`GROSS_SLIP_ADHESION`] of it): the friction is used up and any
//!   more load makes the pulley slide as a whole.

use contact::friction::FrictionLaw;
use serde::Serialize;

/// Friction utilisation `|f|/(μ p)` from which a contact point counts as saturated (on the
/// saturated arc). For the tanh law (6.2) this is a slip speed of `atanh(0.95)/κ` (4.6 cm/s at
/// κ = 40 s/m), ten times the belt's elastic creep at Table 6-1's rated load.
pub const SLIP_UTILISATION: f64 = 0.95;

/// A wrap whose adhesion arc is shorter than this fraction of its contact arc slides as a whole
/// (gross slip): its mean friction utilisation exceeds 95 %, so the tension ratio it holds is
/// within 5 % (in the exponent) of Euler–Eytelwein's `e^{μ φ}` over the whole contact arc.
pub const GROSS_SLIP_ADHESION: f64 = 0.05;

/// Role of a pulley in the drive.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum PulleyRole {
    /// Speed-driven (the driver).
    Driver,
    /// Free with a load torque (a driven accessory).
    Driven,
    /// Free without load.
    Idler,
}

/// One contact point on a wrap.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WrapPoint {
    /// Pulley index.
    pub pulley: usize,
    /// Angle from the inlet of the wrap in the travel direction \[rad\]
    /// ([`fe_model::generate::belt_path::BeltPath::angle_from_inlet`]).
    pub angle: f64,
    /// Belt length the point's force densities stand for \[m\] (tributary length of a node,
    /// quadrature weight times element length of a contact point).
    pub length: f64,
    /// Belt tension at the point \[N\].
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
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PulleyState {
    /// Name (`driver`, `driven`, or the configured name).
    pub name: String,
    /// Role.
    pub role: PulleyRole,
    /// Radius of the belt line \[m\].
    pub radius: f64,
    /// Speed in the travel sense \[rad/s\].
    pub omega: f64,
    /// Force of the belt on the pulley (hub load) \[N\].
    pub hub_load: [f64; 2],
    /// Torque of the belt's contact forces on the pulley in its travel sense \[N·m\] (negative
    /// on a driver: the pulley drives the belt).
    pub torque: f64,
}

/// A span's state in a snapshot.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpanState {
    /// Pulley the span leaves.
    pub from: usize,
    /// Pulley the span reaches.
    pub to: usize,
    /// Tension (mean over the middle half of the span) \[N\].
    pub tension: f64,
    /// Transverse displacement of the span's mid-point from the undeformed span line,
    /// positive to the left of the travel direction \[m\].
    pub transverse: f64,
}

/// What a model reports at one state `(t, q, v)` ([`crate::DriveModel::snapshot`]).
#[derive(Debug, Clone, PartialEq)]
pub struct DriveSnapshot {
    /// Time \[s\].
    pub time: f64,
    /// Pulleys in travel order.
    pub pulleys: Vec<PulleyState>,
    /// Spans in travel order (span `k` leaves pulley `k`).
    pub spans: Vec<SpanState>,
    /// Every contact point in contact (positive pressure).
    pub wrap: Vec<WrapPoint>,
}

/// Per-pulley results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PulleyReport {
    /// Name.
    pub name: String,
    /// Role.
    pub role: PulleyRole,
    /// Speed \[rad/s\].
    pub omega: f64,
    /// Contact arc: from the first to the last point in contact \[rad\].
    pub contact_arc_rad: f64,
    /// Slip arc `∫ |f|/(μ p) dθ` over the contact arc \[rad\] (module documentation).
    pub slip_arc_rad: f64,
    /// Adhesion arc: contact arc minus slip arc \[rad\].
    pub adhesion_arc_rad: f64,
    /// Saturated arc: where the utilisation reaches [`SLIP_UTILISATION`] \[rad\].
    pub saturated_arc_rad: f64,
    /// Largest slip (creep) speed over the contact arc \[m/s\].
    pub slip_velocity_max: f64,
    /// Mean slip velocity over the contact arc (weighted by width), signed \[m/s\].
    pub slip_velocity_mean: f64,
    /// Power lost to sliding on this pulley, `−∫ f v_slip ds` \[W\].
    pub sliding_power_w: f64,
    /// Force of the belt on the pulley (hub load) \[N\].
    pub hub_load: [f64; 2],
    /// Magnitude of the hub load \[N\] (of the mean force for a window mean).
    pub hub_load_magnitude: f64,
    /// Torque the belt exerts on the pulley in its travel sense \[N·m\].
    pub torque: f64,
    /// Tension of the span running onto the pulley \[N\].
    pub tension_in: f64,
    /// Tension of the span leaving the pulley \[N\].
    pub tension_out: f64,
}

/// Per-span results.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpanReport {
    /// Pulley the span leaves.
    pub from: usize,
    /// Pulley the span reaches.
    pub to: usize,
    /// Tension \[N\].
    pub tension: f64,
    /// Transverse displacement of the mid-point at the snapshot \[m\].
    pub transverse: f64,
    /// Transverse vibration amplitude of the mid-point, half the peak-to-peak over the
    /// observation window \[m\] (`NaN` when not observed).
    pub vibration_amplitude: f64,
}

/// The belt's force on one pulley (a summary entry).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HubLoad {
    /// Pulley name.
    pub name: String,
    /// Force of the belt on the pulley (x, y) \[N\].
    pub force: [f64; 2],
    /// Its magnitude \[N\].
    pub magnitude: f64,
}

/// The report of one state: every pulley and span.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DriveReport {
    /// Time of the snapshot \[s\].
    pub time: f64,
    /// Pulleys in travel order.
    pub pulleys: Vec<PulleyReport>,
    /// Spans in travel order.
    pub spans: Vec<SpanReport>,
}

impl DriveReport {
    /// The report of `snap` with the friction coefficient `mu` of the contact law.
    pub fn new(snap: &DriveSnapshot, mu: f64) -> Self {
        let spans: Vec<SpanReport> = snap
            .spans
            .iter()
            .map(|s| SpanReport {
                from: s.from,
                to: s.to,
                tension: s.tension,
                transverse: s.transverse,
                vibration_amplitude: f64::NAN,
            })
            .collect();
        let pulleys = snap
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
                let span_t = |f: &dyn Fn(&SpanState) -> bool| {
                    snap.spans
                        .iter()
                        .find(|s| f(s))
                        .map_or(f64::NAN, |s| s.tension)
                };
                PulleyReport {
                    name: p.name.clone(),
                    role: p.role,
                    omega: p.omega,
                    contact_arc_rad: arc,
                    slip_arc_rad: slip_arc,
                    adhesion_arc_rad: arc - slip_arc,
                    saturated_arc_rad: saturated,
                    slip_velocity_max: vmax,
                    slip_velocity_mean: if arc > 0.0 { vsum / arc } else { 0.0 },
                    sliding_power_w: power,
                    hub_load: p.hub_load,
                    hub_load_magnitude: p.hub_load[0].hypot(p.hub_load[1]),
                    torque: p.torque,
                    tension_in: span_t(&|s| s.to == k),
                    tension_out: span_t(&|s| s.from == k),
                }
            })
            .collect();
        Self {
            time: snap.time,
            pulleys,
            spans,
        }
    }

    /// The mean of `reports` (same drive, at least one): every number averaged, the time of
    /// the last. A steady state of a rotating mesh (nodal, ANCF) carries the ripple of its
    /// element passing: its results are window means, like its speed loss.
    pub fn mean(reports: &[DriveReport]) -> Option<DriveReport> {
        let last = reports.last()?;
        let n = reports.len() as f64;
        let avg = |f: &dyn Fn(&DriveReport) -> f64| reports.iter().map(f).sum::<f64>() / n;
        let pulleys = (0..last.pulleys.len())
            .map(|k| {
                let p = |f: fn(&PulleyReport) -> f64| avg(&|r: &DriveReport| f(&r.pulleys[k]));
                PulleyReport {
                    name: last.pulleys[k].name.clone(),
                    role: last.pulleys[k].role,
                    omega: p(|q| q.omega),
                    contact_arc_rad: p(|q| q.contact_arc_rad),
                    slip_arc_rad: p(|q| q.slip_arc_rad),
                    adhesion_arc_rad: p(|q| q.adhesion_arc_rad),
                    saturated_arc_rad: p(|q| q.saturated_arc_rad),
                    slip_velocity_max: p(|q| q.slip_velocity_max),
                    slip_velocity_mean: p(|q| q.slip_velocity_mean),
                    sliding_power_w: p(|q| q.sliding_power_w),
                    hub_load: [p(|q| q.hub_load[0]), p(|q| q.hub_load[1])],
                    hub_load_magnitude: p(|q| q.hub_load_magnitude),
                    torque: p(|q| q.torque),
                    tension_in: p(|q| q.tension_in),
                    tension_out: p(|q| q.tension_out),
                }
            })
            .collect();
        let spans = (0..last.spans.len())
            .map(|k| {
                let s = |f: fn(&SpanReport) -> f64| avg(&|r: &DriveReport| f(&r.spans[k]));
                SpanReport {
                    from: last.spans[k].from,
                    to: last.spans[k].to,
                    tension: s(|q| q.tension),
                    transverse: s(|q| q.transverse),
                    vibration_amplitude: last.spans[k].vibration_amplitude,
                }
            })
            .collect();
        Some(DriveReport {
            time: last.time,
            pulleys,
            spans,
        })
    }

    /// The first pulley (travel order) whose adhesion arc has shrunk below
    /// [`GROSS_SLIP_ADHESION`] of its contact arc: the friction is used up over its whole
    /// wrap and the belt slides on it (gross slip). `None` while every wrap keeps an adhesion
    /// arc.
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
                force: q.hub_load,
                magnitude: q.hub_load_magnitude,
            })
            .collect()
    }

    /// Slip arc \[rad\] of the first pulley with `role` (`NaN` if there is none).
    pub fn slip_arc(&self, role: PulleyRole) -> f64 {
        self.find(role)
            .map_or(f64::NAN, |k| self.pulleys[k].slip_arc_rad)
    }

    /// Index of the first pulley with `role`.
    pub fn find(&self, role: PulleyRole) -> Option<usize> {
        self.pulleys.iter().position(|p| p.role == role)
    }

    /// Tension of the tight span (running onto the driver) \[N\].
    pub fn tension_tight(&self) -> f64 {
        self.find(PulleyRole::Driver)
            .map_or(f64::NAN, |d| self.pulleys[d].tension_in)
    }

    /// Tension of the slack span (leaving the driver) \[N\].
    pub fn tension_slack(&self) -> f64 {
        self.find(PulleyRole::Driver)
            .map_or(f64::NAN, |d| self.pulleys[d].tension_out)
    }
}

/// Slip speed \[m/s\] at which the friction law's force reaches the fraction `eta` of `μ|f_n|`
/// (the sliding branch of the law): `atanh(η)/κ` for the tanh law (6.2). Found by doubling from
/// 1 µm/s and bisection; infinite if the law never reaches it below 100 m/s (e.g. a Stribeck
/// law whose kinetic coefficient is below `η μ_s`).
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
    let mut lo = 0.0;
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if reached(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

#[cfg(test)]
mod tests {
    use super::*;
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

    // A string on a pulley with saturated friction on the last 2 rad of a π wrap (Coulomb slip
    // arc) and none before: the report finds slip arc 2 rad (also the saturated arc), adhesion
    // π − 2, and the tension ratio it was built with, e^{μ·2} (Euler–Eytelwein).
    #[test]
    fn arcs_of_a_capstan_wrap() {
        let (mu, r, t_out) = (0.5, 0.1, 100.0);
        let n = 2001;
        let pi = std::f64::consts::PI;
        let dphi = pi / (n - 1) as f64;
        let phi_slip = 2.0;
        let mut wrap = Vec::new();
        for i in 0..n {
            let phi = i as f64 * dphi;
            // tension falls from the inlet value over the slip arc at the end of the wrap
            let slipping = phi > pi - phi_slip;
            let tension = if slipping {
                t_out * (mu * (pi - phi)).exp()
            } else {
                t_out * (mu * phi_slip).exp()
            };
            wrap.push(WrapPoint {
                pulley: 0,
                angle: phi,
                length: dphi * r,
                tension,
                pressure: tension / r,
                friction: if slipping { mu * tension / r } else { 0.0 },
                slip: if slipping { -0.1 } else { 0.0 },
            });
        }
        let t_in = wrap[0].tension;
        let snap = DriveSnapshot {
            time: 0.0,
            pulleys: vec![PulleyState {
                name: "driven".into(),
                role: PulleyRole::Driven,
                radius: r,
                omega: 10.0,
                hub_load: [0.0, 0.0],
                torque: 0.0,
            }],
            spans: vec![SpanState {
                from: 0,
                to: 0,
                tension: t_in,
                transverse: 0.0,
            }],
            wrap,
        };
        let rep = DriveReport::new(&snap, mu);
        let p = &rep.pulleys[0];
        assert!((p.contact_arc_rad - pi).abs() < 1e-12);
        assert!(
            (p.slip_arc_rad - phi_slip).abs() < 2.0 * dphi,
            "{}",
            p.slip_arc_rad
        );
        assert!((p.saturated_arc_rad - phi_slip).abs() < 2.0 * dphi);
        assert!((p.adhesion_arc_rad - (pi - phi_slip)).abs() < 2.0 * dphi);
        let ratio = t_in / t_out;
        assert!((ratio.ln() / mu - p.slip_arc_rad).abs() < 2.0 * dphi);
        assert_eq!(rep.gross_slip(), None);
        // sliding power: −∫ f v ds = μ v ∫ p R dφ over the slip arc = 0.1 (T_in − T_out)
        let expect = 0.1 * (t_in - t_out);
        assert!(
            (p.sliding_power_w / expect - 1.0).abs() < 2e-3,
            "{}",
            p.sliding_power_w
        );
    }
}
