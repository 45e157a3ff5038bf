//! The steady solution of a belt drive at one operating point, without time stepping: span
//! tensions from the pulley torques, the tension level from the belt length (and the
//! tensioner arm's moment balance), the wraps' adhesion and slip arcs by creep theory, hub
//! loads and slip margins.
//!
//! # Equations
//!
//! Speeds and torques in the belt's travel sense ([`belt::pulley`], [`belt::motion`]). Span `k`
//! leaves pulley `k` and reaches pulley `k + 1`; `T_k` \[N\] is its (total) axial force, `m = ρA`
//! \[kg/m\] the belt's mass per length, `v` \[m/s\] the belt speed and `T_c = m v²` the
//! centrifugal tension.
//!
//! 1. **Pulley torques.** A free pulley `k` at its steady speed `ω_k = v/r_k` carries
//!    `Q_k = M_load + c_k ω_k` \[N m\] ([`belt::Motion::applied_torque`]: load torque plus the
//!    viscous damper); the belt delivers it as `(T_k − T_{k−1}) r_k = Q_k`, so the loop is
//!    traversed from a reference span with `T_k = T_{k−1} + Q_k/r_k`. The one speed-driven
//!    pulley (the driver) closes the loop: its jump is `−Σ Q_j/r_j`, its torque
//!    `−r_0 Σ Q_j/r_j` (it supplies the power `Σ Q_j ω_j`).
//! 2. **Wraps (creep theory, Grashof; Johnson, *Contact Mechanics* §8.6).** The belt enters a
//!    wrap of angle `φ` and sticks (adhesion arc, tension `T_in`), and slides over the slip arc
//!    at the exit, where the quasi-static tension `T − T_c` changes by the Euler–Eytelwein
//!    factor: `(T_out − T_c)/(T_in − T_c) = e^{±μ φ_s}`, so
//!    `φ_s = |ln((T_out − T_c)/(T_in − T_c))|/μ`, `φ_a = φ − φ_s`. The pressure on the pulley
//!    is `(T − T_c)/r` per unit length (the belt's centripetal acceleration takes `m v²`), so
//!    gross slip sets in when `φ_s > φ`: the wrap's capacity is
//!    `(T_tight − T_slack)_max = (T_slack − T_c)(e^{μφ} − 1)` \[N\] with the slack side as it
//!    is, and the **slip margin** is `(T_tight − T_slack)_max r / |Q|`.
//! 3. **Hub loads.** The belt's force on pulley `k` is
//!    `F_k = (T_out − T_c) d_out − (T_in − T_c) d_in` \[N\] (`d` the spans' unit travel
//!    directions), the vector sum of the two span pulls less the centrifugal part carried by
//!    the belt itself on the wrap.
//! 4. **Belt length.** The unstretched belt length `L_b` (of the mounted drive,
//!    [`belt::Drive::belt_length`]) is conserved: `Σ_k L_k/λ(T_k) + Σ_wraps ∫ r dψ/λ(T(ψ)) = L_b`
//!    with `λ(T)` the material law's stretch ([`belt::Section::stretch`]; adhesion arcs at
//!    `T_in`, slip arcs along the exponential, Simpson's rule). For the linear law and small
//!    strain this is the mean-tension model `Σ (T_i − T_0) L_i/EA = 0`. Without a tensioner the
//!    path is fixed and this one equation sets the tension level `T_ref` (monotone: the
//!    Illinois root finder, [`mbd_core::roots::illinois`]); the total span tension then stays
//!    near the installation tension and the centrifugal tension lowers the pressure `T − T_c`.
//! 5. **Tensioner.** With an arm at angle `θ` the idler's centre is `c(θ)` and the path, span
//!    lengths and wraps follow; at each `θ` step 4 gives `T_ref(θ)`, and the arm balances when
//!    `M_s(θ) + (c − p) × F_idler(θ) = 0` ([`belt::tensioner`]), a second Illinois root over
//!    the arm's travel. The spring then sets `T − T_c` at the idler: the centrifugal tension
//!    adds to every span. No root in the travel: the arm rests on the stop it is pushed to,
//!    and the drive is solved as a fixed-centre drive there (flagged).

use crate::fead_design::DesignIssue;
use belt::{BeltPath, Drive, Motion, Pulley, Section, SpanLine, Tensioner, tensioner::cross};
use mbd_core::roots::illinois;

/// Simpson intervals along a slip arc (the tension changes by a few per cent along it: the
/// rule is exact to ~1e-10 of the arc's length).
const SIMPSON_INTERVALS: usize = 16;

/// Geometry of the drive with the tensioner's arm at one angle.
#[derive(Debug, Clone)]
pub struct Geometry {
    /// The belt path.
    pub path: BeltPath,
    /// Spans in travel order.
    pub spans: Vec<SpanLine>,
    /// Wrap angles \[rad\].
    pub wraps: Vec<f64>,
}

impl Geometry {
    /// The geometry of `pulleys` (`None`: no open-belt path over them).
    pub fn of(pulleys: &[Pulley]) -> Option<Self> {
        let path = BeltPath::new(pulleys).ok()?;
        let spans = path.spans();
        let wraps = (0..pulleys.len())
            .map(|k| path.wrap_angle(k).unwrap_or(0.0))
            .collect();
        Some(Self { path, spans, wraps })
    }

    /// The geometry of `drive` with its tensioner arm at `theta` \[rad\] (the mounted geometry
    /// when `theta` is `None` or there is no tensioner).
    pub fn at(drive: &Drive, theta: Option<f64>) -> Option<Self> {
        let mut pulleys = drive.pulleys().to_vec();
        if let (Some(arm), Some(th)) = (drive.arm(), theta) {
            pulleys[arm.tensioner.pulley].center = arm.tensioner.center(arm.length, th).0;
        }
        Self::of(&pulleys)
    }
}

/// What the loads are at one operating point.
#[derive(Debug, Clone)]
pub struct Loading {
    /// Belt speed `v` \[m/s\].
    pub belt_speed: f64,
    /// Speed of every pulley `ω_k = v/r_k` \[rad/s\] (travel sense, no creep).
    pub speeds: Vec<f64>,
    /// Torque carried by every pulley in the travel sense \[N m\]: `Q_k` on free pulleys, the
    /// closing torque `−r_d Σ Q_j/r_j` on the driver.
    pub torques: Vec<f64>,
    /// Index of the speed-driven pulley.
    pub driver: usize,
}

impl Loading {
    /// The steady loads of `drive` with its driver (the one speed-driven pulley) turning at
    /// `driver_speed` \[rad/s\]: each free pulley's load torque at its final value (the mean
    /// part of its signal, [`belt::Signal::final_value`]) plus its damper at `ω_k = v/r_k`
    /// (module documentation, step 1).
    pub fn steady(drive: &Drive, driver: usize, driver_speed: f64) -> Self {
        let pulleys = drive.pulleys();
        let v = driver_speed * pulleys[driver].radius;
        let speeds: Vec<f64> = pulleys.iter().map(|p| v / p.radius).collect();
        let mut torques: Vec<f64> = pulleys
            .iter()
            .zip(&speeds)
            .map(|(p, &w)| match &p.motion {
                Motion::Speed { .. } => 0.0,
                Motion::Load {
                    torque, damping, ..
                } => torque.final_value() + damping * w,
                Motion::Idler { damping, .. } => damping * w,
            })
            .collect();
        let jump: f64 = pulleys
            .iter()
            .zip(&torques)
            .enumerate()
            .filter(|(k, _)| *k != driver)
            .map(|(_, (p, q))| q / p.radius)
            .sum();
        torques[driver] = -jump * pulleys[driver].radius;
        Self {
            belt_speed: v,
            speeds,
            torques,
            driver,
        }
    }

    /// Tension of every span relative to span `reference` \[N\] (module documentation, step 1):
    /// `D_k = D_{k−1} + Q_k/r_k`, `D_reference = 0`.
    pub fn offsets(&self, radii: &[f64], reference: usize) -> Vec<f64> {
        let n = radii.len();
        let mut d = vec![0.0; n];
        for s in 1..n {
            let k = (reference + s) % n;
            let prev = (k + n - 1) % n;
            d[k] = d[prev] + self.torques[k] / radii[k];
        }
        d
    }
}

/// One wrap by creep theory (module documentation, step 2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WrapState {
    /// Tension entering \[N\].
    pub tension_in: f64,
    /// Tension leaving \[N\].
    pub tension_out: f64,
    /// Wrap angle `φ` \[rad\].
    pub wrap: f64,
    /// Slip arc `φ_s` \[rad\], at most `φ`.
    pub slip_arc: f64,
    /// Euler–Eytelwein ratio the torque requires, `max/min` of `T − T_c` at the two ends
    /// (`∞` when a side carries no quasi-static tension).
    pub required_ratio: f64,
    /// Ratio the wrap can hold, `e^{μ φ}`.
    pub available_ratio: f64,
}

impl WrapState {
    /// The wrap of angle `wrap` \[rad\] between `tension_in` and `tension_out` \[N\] with the
    /// centrifugal tension `tc` \[N\] and friction coefficient `mu`.
    pub fn new(tension_in: f64, tension_out: f64, wrap: f64, tc: f64, mu: f64) -> Self {
        let (a, b) = (tension_in - tc, tension_out - tc);
        let (lo, hi) = (a.min(b), a.max(b));
        let required_ratio = if lo > 0.0 { hi / lo } else { f64::INFINITY };
        let slip_arc = (required_ratio.ln() / mu).min(wrap);
        Self {
            tension_in,
            tension_out,
            wrap,
            slip_arc,
            required_ratio,
            available_ratio: (mu * wrap).exp(),
        }
    }

    /// Whether the wrap slides as a whole (`φ_s` would exceed `φ`).
    pub fn gross_slip(&self) -> bool {
        self.required_ratio > self.available_ratio
    }

    /// Tension at angle `psi` \[rad\] from the inlet: `T_in` over the adhesion arc, then the
    /// exponential of the slip arc towards `T_out`.
    pub fn tension_at(&self, psi: f64, tc: f64) -> f64 {
        let adhesion = self.wrap - self.slip_arc;
        if psi <= adhesion || self.slip_arc <= 0.0 {
            return self.tension_in;
        }
        let (a, b) = (self.tension_in - tc, self.tension_out - tc);
        if a <= 0.0 || b <= 0.0 {
            // a side without pressure: linear between the ends (gross slip, flagged)
            let f = (psi - adhesion) / self.slip_arc;
            return self.tension_in + f * (self.tension_out - self.tension_in);
        }
        // Euler–Eytelwein on the slip arc (under gross slip the profile that reaches T_out
        // over the whole wrap: the length integral of a flagged state)
        let rate = (b / a).ln() / self.slip_arc;
        tc + a * (rate * (psi - adhesion)).exp()
    }

    /// Compliance of the belt on the slip arc to a change of the exit tension \[m/N\]: the
    /// extension `∫ δλ r dψ` of the belt on the slip arc per `δT_out`, for a pulley of radius
    /// `r` \[m\] ([`super::modes`], "Wrap compliance"):
    ///
    /// ```text
    ///   c_w = ∫_slip r dψ (T(ψ) − T_c)/((T_out − T_c) EA_t(T(ψ)))
    /// ```
    ///
    /// (Simpson's rule on the slip arc's profile [`Self::tension_at`], `EA_t` the section's
    /// tangent stiffness [`Section::tangent_stiffness`]). For the linear law it is the closed
    /// form `r |T_out − T_in| / (μ EA (T_out − T_c))`. Zero without a slip arc. A wrap with a
    /// side without quasi-static tension (a flagged state, [`Self::required_ratio`] `∞`) has
    /// no friction to hold a perturbation: it is taken uniform on the slip arc.
    pub fn exit_compliance(&self, r: f64, tc: f64, section: &Section) -> f64 {
        if self.slip_arc <= 0.0 {
            return 0.0;
        }
        let adhesion = self.wrap - self.slip_arc;
        let b = self.tension_out - tc;
        let pressure = self.tension_in > tc && b > 0.0;
        let n = SIMPSON_INTERVALS;
        let h = self.slip_arc / n as f64;
        let mut s = 0.0;
        for i in 0..=n {
            let w = crate::analytical::simpson_weight(i, n);
            let t = self.tension_at(adhesion + i as f64 * h, tc);
            let share = if pressure { (t - tc) / b } else { 1.0 };
            s += w * share / section.tangent_stiffness(t);
        }
        r * s * h / 3.0
    }

    /// Unstretched length of the belt on the wrap \[m\] for a pulley of radius `r` \[m\]:
    /// `∫ r dψ / λ(T(ψ))` (adhesion arc exact, slip arc by Simpson's rule).
    pub fn unstretched(&self, r: f64, tc: f64, section: &Section) -> f64 {
        let adhesion = self.wrap - self.slip_arc;
        let mut len = r * adhesion / section.stretch(self.tension_in);
        if self.slip_arc > 0.0 {
            let n = SIMPSON_INTERVALS;
            let h = self.slip_arc / n as f64;
            let mut s = 0.0;
            for i in 0..=n {
                let w = crate::analytical::simpson_weight(i, n);
                let psi = adhesion + i as f64 * h;
                s += w / section.stretch(self.tension_at(psi, tc));
            }
            len += r * s * h / 3.0;
        }
        len
    }
}

/// The steady state of the drive at one operating point (module documentation).
#[derive(Debug, Clone)]
pub struct SteadyState {
    /// Geometry at the solved arm angle.
    pub geometry: Geometry,
    /// Tensioner arm angle \[rad\] (`None`: no tensioner).
    pub arm_angle: Option<f64>,
    /// The arm rests on a stop: `Some(stop angle)` when the moment balance has no root in the
    /// travel.
    pub arm_on_stop: Option<f64>,
    /// Span tensions `T_k` \[N\] (total axial force, centrifugal part included).
    pub tensions: Vec<f64>,
    /// Centrifugal tension `T_c = m v²` \[N\].
    pub centrifugal: f64,
    /// Friction coefficient of every wrap.
    pub mu: Vec<f64>,
    /// Wraps by creep theory, one per pulley.
    pub wraps: Vec<WrapState>,
    /// The loads solved for.
    pub loading: Loading,
    /// Whether the belt length cannot be closed with every span under quasi-static tension
    /// (the belt is too long for the load: the slackest span is at `T = T_c`).
    pub slack: bool,
}

/// The one speed-driven pulley of `drive` (`None`: none or several).
pub fn single_driver(drive: &Drive) -> Option<usize> {
    let drivers: Vec<usize> = drive
        .pulleys()
        .iter()
        .enumerate()
        .filter(|(_, p)| !p.is_free())
        .map(|(k, _)| k)
        .collect();
    (drivers.len() == 1).then(|| drivers[0])
}

/// The unstretched length of the belt over `geo` with span tensions `t` \[N\] (module
/// documentation, step 4).
fn unstretched_length(geo: &Geometry, t: &[f64], tc: f64, mu: &[f64], section: &Section) -> f64 {
    let n = t.len();
    let radii: Vec<f64> = geo.path.pulleys().iter().map(|p| p.radius).collect();
    let spans: f64 = geo
        .spans
        .iter()
        .map(|s| s.length / section.stretch(t[s.from]))
        .sum();
    let wraps: f64 = (0..n)
        .map(|k| {
            WrapState::new(t[(k + n - 1) % n], t[k], geo.wraps[k], tc, mu[k])
                .unstretched(radii[k], tc, section)
        })
        .sum();
    spans + wraps
}

/// The tension level `T_ref` of the reference span that closes the belt length `lb` \[m\] on
/// the geometry `geo` with offsets `d` \[N\] (module documentation, step 4), and whether the
/// belt is too long to keep every span's quasi-static tension positive (then the slackest
/// span is returned at `T_c`).
fn close_length(
    geo: &Geometry, d: &[f64], tc: f64, mu: &[f64], section: &Section, lb: f64, scale: f64,
) -> (f64, bool) {
    let tensions = |tref: f64| -> Vec<f64> { d.iter().map(|x| tref + x).collect() };
    let f = |tref: f64| unstretched_length(geo, &tensions(tref), tc, mu, section) - lb;
    let dmin = d.iter().copied().fold(f64::INFINITY, f64::min);
    let lo = tc - dmin;
    let lo = lo + 1e-12 * scale.max(lo.abs());
    let flo = f(lo);
    if flo <= 0.0 {
        return (lo, true);
    }
    let mut hi = lo + scale.max(1.0);
    let mut fhi = f(hi);
    let mut n = 0;
    while fhi > 0.0 && n < 80 {
        hi = lo + 2.0 * (hi - lo);
        fhi = f(hi);
        n += 1;
    }
    (illinois(f, lo, hi, flo, fhi, 1e-12 * hi.abs()), false)
}

/// Moment \[N m\] about the pivot of the belt's force on the tensioner's idler, `(c − p) × F`,
/// with the span tensions `t` on the geometry `geo` (module documentation, steps 3 and 5).
pub fn belt_moment(geo: &Geometry, spec: &Tensioner, t: &[f64], tc: f64) -> f64 {
    let k = spec.pulley;
    let n = t.len();
    let f = hub_force(geo, k, t[(k + n - 1) % n], t[k], tc);
    let c = geo.path.pulleys()[k].center;
    cross([c[0] - spec.pivot[0], c[1] - spec.pivot[1]], f)
}

/// The belt's force on pulley `k` \[N\]: `(T_out − T_c) d_out − (T_in − T_c) d_in`.
pub fn hub_force(geo: &Geometry, k: usize, t_in: f64, t_out: f64, tc: f64) -> [f64; 2] {
    let n = geo.spans.len();
    let d_in = geo.spans[(k + n - 1) % n].direction;
    let d_out = geo.spans[k].direction;
    let (a, b) = (t_in - tc, t_out - tc);
    [b * d_out[0] - a * d_in[0], b * d_out[1] - a * d_in[1]]
}

/// Solve the steady state of `drive` under `loading` with the friction coefficient of every
/// wrap `mu` (module documentation). Issues found on the way (the arm on a stop, a slack
/// span) are pushed to `issues` by the caller from the returned flags.
pub fn solve(drive: &Drive, loading: Loading, mu: Vec<f64>) -> SteadyState {
    let section = *drive.belt();
    let lb = drive.belt_length();
    let radii: Vec<f64> = drive.pulleys().iter().map(|p| p.radius).collect();
    let n = radii.len();
    let tc = section.mass_per_length * loading.belt_speed * loading.belt_speed;
    let scale = drive.tension()
        + loading
            .torques
            .iter()
            .zip(&radii)
            .map(|(q, r)| (q / r).abs())
            .sum::<f64>();
    let finish = |geometry: Geometry,
                  arm_angle: Option<f64>,
                  arm_on_stop: Option<f64>,
                  tref: f64,
                  d: &[f64],
                  slack: bool,
                  loading: Loading| {
        let tensions: Vec<f64> = d.iter().map(|x| tref + x).collect();
        let wraps = (0..n)
            .map(|k| {
                WrapState::new(
                    tensions[(k + n - 1) % n],
                    tensions[k],
                    geometry.wraps[k],
                    tc,
                    mu[k],
                )
            })
            .collect();
        SteadyState {
            geometry,
            arm_angle,
            arm_on_stop,
            tensions,
            centrifugal: tc,
            mu: mu.clone(),
            wraps,
            loading,
            slack,
        }
    };
    match drive.arm() {
        None => {
            let d = loading.offsets(&radii, 0);
            let geo = Geometry::at(drive, None).expect("the mounted drive has a path");
            let (tref, slack) = close_length(&geo, &d, tc, &mu, &section, lb, scale);
            finish(geo, None, None, tref, &d, slack, loading)
        }
        Some(arm) => {
            let spec = arm.tensioner;
            // the reference span runs onto the idler
            let d = loading.offsets(&radii, (spec.pulley + n - 1) % n);
            let at = |theta: f64| -> Option<(Geometry, f64, bool)> {
                let geo = Geometry::at(drive, Some(theta))?;
                let (tref, slack) = close_length(&geo, &d, tc, &mu, &section, lb, scale);
                Some((geo, tref, slack))
            };
            let g = |theta: f64| -> f64 {
                let belt = at(theta).map_or(0.0, |(geo, tref, _)| {
                    let t: Vec<f64> = d.iter().map(|x| tref + x).collect();
                    belt_moment(&geo, &spec, &t, tc)
                });
                spec.spring_moment(theta).0 + belt
            };
            let [lo, hi] = spec.travel;
            let (glo, ghi) = (g(lo), g(hi));
            let (theta, stop) = if glo * ghi <= 0.0 {
                (illinois(g, lo, hi, glo, ghi, 1e-13), None)
            } else if glo > 0.0 {
                // counter-clockwise moment over the whole travel: on the upper stop
                (hi, Some(hi))
            } else {
                (lo, Some(lo))
            };
            match at(theta) {
                Some((geo, tref, slack)) => {
                    finish(geo, Some(theta), stop, tref, &d, slack, loading)
                }
                None => {
                    // no path at the stop: keep the mounted geometry (flagged by the stop)
                    let geo = Geometry::at(drive, None).expect("the mounted drive has a path");
                    let (tref, slack) = close_length(&geo, &d, tc, &mu, &section, lb, scale);
                    finish(geo, Some(arm.angle), Some(theta), tref, &d, slack, loading)
                }
            }
        }
    }
}

/// The issues of a solved state that do not depend on the study's settings: the arm on a
/// stop, a slack span, gross slip.
pub fn state_issues(drive: &Drive, s: &SteadyState, engine_rpm: f64) -> Vec<DesignIssue> {
    let names = drive.names();
    let mut out = Vec::new();
    if let Some(stop) = s.arm_on_stop {
        out.push(DesignIssue::ArmOnStop {
            engine_rpm,
            stop_deg: stop.to_degrees(),
        });
    }
    if s.slack {
        let n = s.tensions.len();
        let k = (0..n)
            .min_by(|&a, &b| s.tensions[a].total_cmp(&s.tensions[b]))
            .unwrap_or(0);
        out.push(DesignIssue::SlackSpan {
            engine_rpm,
            from: names[k].clone(),
            to: names[(k + 1) % n].clone(),
            tension_n: s.tensions[k],
            centrifugal_n: s.centrifugal,
        });
    }
    for (k, w) in s.wraps.iter().enumerate() {
        if w.gross_slip() && !s.slack {
            out.push(DesignIssue::GrossSlip {
                engine_rpm,
                pulley: names[k].clone(),
                required_ratio: w.required_ratio,
                available_ratio: w.available_ratio,
            });
        }
    }
    out
}
