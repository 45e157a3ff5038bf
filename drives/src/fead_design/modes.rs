//! Modes of the drive about an operating point: the linearised rotational model and the
//! transverse span modes.
//!
//! # Rotational model (Hwang, Perkins, Ulsoy & Meckstroth 1994; Beikmann, Perkins & Ulsoy 1996)
//!
//! Coordinates `q`: the rotation `θ_k` \[rad\] (travel sense) of every free pulley and, with a
//! tensioner, its arm angle `θ_a` \[rad\]; the speed-driven pulley is held (`θ = 0`: the crank's
//! inertia is large). Span `k`, from pulley `i` to pulley `j` with unit direction `d_k`, is an
//! axial spring of stiffness `k_k = 1/(L_k/EA_t + c_{w,i})` \[N/m\] (`EA_t = dN/dλ` at the
//! span's tension, [`belt::Section::tangent_stiffness`]; `L_k` the span length; `c_{w,i}` the
//! compliance of the slip arc of pulley `i`, below) on the stretch
//!
//! ```text
//!   e_k = r_j θ_j − r_i θ_i + d_k · (u_j − u_i),     u_t = c'(θ_a) δθ_a  (the idler on the arm)
//! ```
//!
//! so `K = Σ_k k_k b_k b_kᵀ + (k_t + k_g) e_a e_aᵀ` with `b_k = ∂e_k/∂q`, `k_t` the arm's spring
//! rate and `k_g = −∂M_belt/∂θ_a` at fixed span tensions (the geometric stiffness of the belt's
//! pull on the arm: its direction and lever turn with the arm; central difference of
//! [`super::statics::belt_moment`]). `M = diag(J_k, J_arm)`. A decoupled accessory
//! ([`belt::decoupler`]) adds its own coordinate after the pulleys': the pulley hub `J_p` and the
//! accessory `J_a` (plus the carrier `J_r`, the clutch taken as engaged) joined by the spring's
//! `k` in `K`. The eigenpairs of `K φ = ω² M φ`
//! come from the workspace's dense generalized symmetric solver ([`fe_model::dense_modes`]).
//!
//! **Wrap compliance** ([`WrapModel::Creep`], the default; derived below): the belt is held
//! on each wrap's adhesion arc and free on its slip arc, so span `k` leaving pulley `i` is in
//! series with the compliance `c_{w,i}` of the belt on `i`'s slip arc:
//! `k_k = 1/(L_k/EA_t + c_{w,i})`. [`WrapModel::Held`] holds the belt on the whole wrap
//! (`c_w = 0`, the model of Hwang et al. 1994), for comparison.
//!
//! **Not modelled**: the compliance of the adhesion arcs (rigid in creep theory; a regularised
//! friction law such as the flowing model's `tanh` has creep there), the belt's mass, damping,
//! the transport of stretch by the moving belt (terms `v δλ`), and the spans' transverse
//! motion (see below). For a two-pulley drive with the driver held and no load this gives
//! exactly `f = √(2 k r²/J)/(2π)`, `k = EA/L`. Each omission adds compliance or mass, so the
//! frequencies are upper bounds of a model that had them (Rayleigh's principle).
//! Measurements against the flowing belt model's free ring-down: `drives/tests/fead_sweep.rs`.
//!
//! # Wrap compliance (linearised creep theory)
//!
//! The steady wrap is Euler's creep theory (Grashof; Johnson, *Contact Mechanics* §8.6;
//! Firbank 1970, Int. J. Mech. Sci. 12; [`super::statics`], step 2): the belt enters pulley `i`
//! and sticks over the adhesion arc `[0, φ_a]` with the stretch of the span running on, then
//! slides over the slip arc `[φ_a, φ]` at the exit, where the friction per length is saturated,
//! `μ p` with the pressure `p = (T − T_c)/r`, and
//!
//! ```text
//!   d(T − T_c)/dψ = σ μ (T − T_c)      (σ = +1 where the belt gains tension, a driven
//!                                       pulley; σ = −1 on the driver)
//! ```
//!
//! The linearisation about it is derived here (the steady theory is the cited one's; the
//! perturbation is this module's). A small vibration about the steady state leaves the slip
//! arc sliding in the same sense (its sliding speed, the creep speed `v |λ(ψ) − λ_in|/λ_in`,
//! exceeds the vibration's but in a neighbourhood of the arc's start that shrinks with the
//! amplitude), so its friction stays saturated and changes only with the
//! pressure, `δf = μ δp = μ δT/r`: the perturbation obeys the same capstan law,
//! `dδT/dψ = σ μ δT`, and with the exit tension `T_out + δT_out` (the span leaving the wrap)
//!
//! ```text
//!   δT(ψ) = δT_out (T(ψ) − T_c)/(T_out − T_c)        on the slip arc.
//! ```
//!
//! The end of the slip arc moves to meet the adhesion arc's tension; that changes the profile
//! over a first-order length by a first-order amount, so no belt moves to first order. The
//! adhesion arc moves with the pulley. The span from the exit of `i` to the inlet of `j` then
//! receives, by the belt's material balance on the wrap (flux `F = V/λ`, continuity
//! `∂_t(1/λ) + ∂_s F = 0`), `r_i δθ_i` from the pulley plus the extension of the slip arc
//! `∫ δλ r dψ`, and gives `r_j δθ_j` to the adhesion arc of `j`. With `λ ≈ 1` as in the span
//! springs and the transport terms `v δλ` dropped (as Hwang et al. drop them for the spans):
//!
//! ```text
//!   L_k δT_k/EA_t = e_k − ∫_slip δλ r dψ = e_k − c_{w,i} δT_k
//!   c_{w,i} = ∫_slip r dψ (T(ψ) − T_c)/((T_out − T_c) EA_t(T(ψ)))      [m/N]
//! ```
//!
//! ([`super::statics::WrapState::exit_compliance`]): the span and the slip arc it leaves are
//! springs in series. For the linear law, `∫_slip (T − T_c) dψ = |T_out − T_in|/μ` gives
//!
//! ```text
//!   EA c_w = r |T_out − T_in| / (μ (T_out − T_c))
//!          = r (1 − e^{−μ φ_s})/μ    on a driven pulley (T_out the tighter side)
//!          = r (e^{μ φ_s} − 1)/μ     on the driver (T_out the slacker side)
//! ```
//!
//! a length of belt proportional to the torque the pulley carries, zero without load, `→ r φ_s`
//! as `μ φ_s → 0`. (The estimate `r (1 − e^{−μ φ_s})/μ` of the issue 36 diagnosis is the driven
//! pulleys' and falls short on the driver by the factor `e^{μ φ_s}`.) The compliance does not
//! depend on frequency (quasi-static capstan on the arc: the belt's inertia there is
//! neglected). On a two-pulley drive, driver held, driven pulley `(J, r)` on spans of length
//! `L`: `f = √((k_0 + k_1) r²/J)/(2π)` with `k_0 = EA/(L + EA c_{w,driver})` (slack span) and
//! `k_1 = EA/(L + EA c_{w,driven})` (tight span).
//!
//! # Transverse span modes
//!
//! Each span is a travelling string of length `L`, tension `T` (the total axial force, the
//! centrifugal part included) and speed `v` between fixed ends (Wickert & Mote 1990):
//! `f_n = n (c² − v²)/(2 L c)`, `c = √(T/ρA)` ([`flowing::params::StringConfig::exact_moving_frequency_hz`]).
//! The spans next to the tensioner's idler end on a moving centre: their transverse motion
//! couples with the arm's rotation (Beikmann, Perkins & Ulsoy 1996), which this formula does
//! not hold; those spans are flagged, and more strongly when their frequency lies near a mode
//! in which the arm takes part. The coupled solution is [`super::coupled`].

use super::statics::{Geometry, SteadyState, belt_moment};
use belt::Drive;
use faer::Mat;
use serde::{Deserialize, Serialize};

/// How the rotational model holds the belt on the wraps (module documentation).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum WrapModel {
    /// Held on the adhesion arcs, free on the slip arcs (creep theory): each span in series
    /// with the compliance of the slip arc it leaves,
    /// [`super::statics::WrapState::exit_compliance`].
    #[default]
    Creep,
    /// Held on the whole wrap: the spans are the only springs (Hwang et al. 1994; an upper
    /// bound of the creep model's frequencies).
    Held,
}

impl WrapModel {
    /// Its name in the configuration (`"creep"`, `"held"`).
    pub fn name(self) -> &'static str {
        match self {
            WrapModel::Creep => "creep",
            WrapModel::Held => "held",
        }
    }
}

/// Arm angle step of the geometric stiffness's central difference \[rad\].
const ARM_STEP: f64 = 1e-6;

/// The linearised rotational model (module documentation).
#[derive(Debug, Clone)]
pub struct RotationalModel {
    /// Name of every coordinate (pulley names; `"tensioner arm"`).
    pub names: Vec<String>,
    /// Stiffness `K` \[N m/rad\].
    pub stiffness: Mat<f64>,
    /// Mass `M` \[kg m²\].
    pub mass: Mat<f64>,
    /// Geometric stiffness of the belt's pull on the arm `k_g` \[N m/rad\] (`None`: no arm).
    pub arm_geometric_stiffness: Option<f64>,
    /// How the belt is held on the wraps.
    pub wrap: WrapModel,
    /// Compliance of the slip arc each span leaves, `c_w` \[m/N\] (span order; zero for
    /// [`WrapModel::Held`]).
    pub wrap_compliance: Vec<f64>,
    /// Axial stiffness of every span in series with that slip arc,
    /// `1/(L/EA_t + c_w)` \[N/m\] (span order).
    pub span_stiffness: Vec<f64>,
}

/// One rotational mode.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RotationalMode {
    /// Natural frequency \[Hz\].
    pub frequency_hz: f64,
    /// The coordinate with the largest share of the modal kinetic energy `J_i φ_i²`.
    pub dominant: String,
    /// Share of the modal kinetic energy of every coordinate (sums to 1), in the order of
    /// [`RotationalModel::names`].
    pub energy_share: Vec<f64>,
    /// Mode shape scaled to a largest entry of +1 \[rad/rad\].
    pub shape: Vec<f64>,
}

/// A span's transverse natural frequencies.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpanModes {
    /// Pulley the span leaves.
    pub from: String,
    /// Pulley the span reaches.
    pub to: String,
    /// Frequencies of the harmonics `n = 1, 2, …` \[Hz\] (`None` at or above the critical
    /// speed `v ≥ c`).
    pub frequencies_hz: Vec<Option<f64>>,
    /// Whether the span ends on the tensioner's idler: its transverse motion couples with the
    /// arm's rotation (Beikmann, Perkins & Ulsoy 1996; module documentation).
    pub coupled_through_arm: bool,
}

/// Build the rotational model of `drive` about the steady state `s` with the belt held on the
/// adhesion arcs only ([`WrapModel::Creep`], module documentation).
pub fn rotational_model(drive: &Drive, s: &SteadyState) -> RotationalModel {
    rotational_model_with(drive, s, WrapModel::Creep)
}

/// Build the rotational model of `drive` about the steady state `s` holding the belt on the
/// wraps as `wrap` says (module documentation).
pub fn rotational_model_with(drive: &Drive, s: &SteadyState, wrap: WrapModel) -> RotationalModel {
    let pulleys = s.geometry.path.pulleys();
    let n = pulleys.len();
    let section = drive.belt();
    // coordinate of every free pulley
    let mut index = vec![None; n];
    let mut names = Vec::new();
    let mut inertia = Vec::new();
    for (k, p) in pulleys.iter().enumerate() {
        if let Some(j) = p.motion.pulley_inertia() {
            index[k] = Some(names.len());
            names.push(p.name.clone());
            inertia.push(j);
        }
    }
    // a decoupled accessory: its own coordinate on the spring k (clutch engaged: the carrier
    // turns with the accessory, J_r + J_a; belt::decoupler)
    let mut springs = Vec::new();
    for (k, p) in pulleys.iter().enumerate() {
        if let (Some(d), Some(ja), Some(ip)) = (p.motion.decoupler(), p.motion.inertia(), index[k])
        {
            springs.push((ip, names.len(), d.stiffness));
            names.push(format!("{} accessory", p.name));
            inertia.push(ja + if d.clutch { d.carrier_inertia } else { 0.0 });
        }
    }
    let arm = drive.arm().zip(s.arm_angle);
    let arm_dof = arm.map(|_| {
        names.push("tensioner arm".into());
        names.len() - 1
    });
    if let Some((a, _)) = arm {
        inertia.push(a.tensioner.inertia);
    }
    let m = names.len();
    let mut stiffness = Mat::<f64>::zeros(m, m);
    // idler centre velocity per arm rate c'(θ)
    let dc = arm.map(|(a, th)| (a.tensioner.pulley, a.tensioner.center(a.length, th).1));
    let mut wrap_compliance = Vec::with_capacity(s.geometry.spans.len());
    let mut span_stiffness = Vec::with_capacity(s.geometry.spans.len());
    for sp in &s.geometry.spans {
        let (i, j) = (sp.from, sp.to);
        let cw = match wrap {
            WrapModel::Creep => {
                s.wraps[i].exit_compliance(pulleys[i].radius, s.centrifugal, section)
            }
            WrapModel::Held => 0.0,
        };
        let k = 1.0 / (sp.length / section.tangent_stiffness(s.tensions[i]) + cw);
        wrap_compliance.push(cw);
        span_stiffness.push(k);
        let mut b = vec![0.0; m];
        if let Some(c) = index[j] {
            b[c] += pulleys[j].radius;
        }
        if let Some(c) = index[i] {
            b[c] -= pulleys[i].radius;
        }
        if let (Some((t, v)), Some(a)) = (dc, arm_dof) {
            let along = sp.direction[0] * v[0] + sp.direction[1] * v[1];
            if j == t {
                b[a] += along;
            }
            if i == t {
                b[a] -= along;
            }
        }
        for r in 0..m {
            for c in 0..m {
                stiffness[(r, c)] += k * b[r] * b[c];
            }
        }
    }
    for (ip, ia, k) in springs {
        stiffness[(ip, ip)] += k;
        stiffness[(ia, ia)] += k;
        stiffness[(ip, ia)] -= k;
        stiffness[(ia, ip)] -= k;
    }
    let mut kg = None;
    if let (Some((a, th)), Some(ad)) = (arm, arm_dof) {
        let spec = a.tensioner;
        let moment = |theta: f64| {
            Geometry::at(drive, Some(theta)).map_or(f64::NAN, |g| {
                belt_moment(&g, &spec, &s.tensions, s.centrifugal)
            })
        };
        let g = -(moment(th + ARM_STEP) - moment(th - ARM_STEP)) / (2.0 * ARM_STEP);
        let g = if g.is_finite() { g } else { 0.0 };
        stiffness[(ad, ad)] += spec.stiffness + g;
        kg = Some(g);
    }
    let mass = Mat::from_fn(m, m, |r, c| if r == c { inertia[r] } else { 0.0 });
    RotationalModel {
        names,
        stiffness,
        mass,
        arm_geometric_stiffness: kg,
        wrap,
        wrap_compliance,
        span_stiffness,
    }
}

impl RotationalModel {
    /// All its modes, ascending ([`fe_model::dense_modes`]).
    ///
    /// # Errors
    /// The eigen solver's ([`fe_model::FeError`]): a stiffness that is not positive
    /// semi-definite (an arm whose belt pull outweighs its spring), non-finite entries.
    pub fn modes(&self) -> Result<Vec<RotationalMode>, fe_model::FeError> {
        let m = self.names.len();
        if m == 0 {
            return Ok(Vec::new());
        }
        let modes = fe_model::dense_modes(self.stiffness.as_ref(), self.mass.as_ref(), m)?;
        Ok((0..modes.values.len())
            .map(|c| {
                let phi: Vec<f64> = (0..m).map(|r| modes.vectors[(r, c)]).collect();
                let e: Vec<f64> = (0..m)
                    .map(|r| self.mass[(r, r)] * phi[r] * phi[r])
                    .collect();
                let total: f64 = e.iter().sum();
                let share: Vec<f64> = e.iter().map(|x| x / total).collect();
                let dom = (0..m)
                    .max_by(|&a, &b| share[a].total_cmp(&share[b]))
                    .unwrap_or(0);
                let big = (0..m)
                    .max_by(|&a, &b| phi[a].abs().total_cmp(&phi[b].abs()))
                    .unwrap_or(0);
                let scale = phi[big];
                RotationalMode {
                    frequency_hz: modes.frequencies_hz[c],
                    dominant: self.names[dom].clone(),
                    energy_share: share,
                    shape: phi.iter().map(|x| x / scale).collect(),
                }
            })
            .collect())
    }
}

/// Transverse frequencies of every span of the steady state `s` for the harmonics
/// `1..=harmonics` (module documentation).
pub fn span_modes(drive: &Drive, s: &SteadyState, harmonics: usize) -> Vec<SpanModes> {
    let names = drive.names();
    let rho = drive.belt().mass_per_length;
    let v = s.loading.belt_speed;
    let idler = drive.arm().map(|a| a.tensioner.pulley);
    s.geometry
        .spans
        .iter()
        .map(|sp| {
            let t = s.tensions[sp.from];
            let string = flowing::params::StringConfig {
                length: sp.length,
                density: rho,
                area: 1.0,
                tension: t,
            };
            let sub = t > 0.0 && v * v < t / rho;
            SpanModes {
                from: names[sp.from].clone(),
                to: names[sp.to].clone(),
                frequencies_hz: (1..=harmonics)
                    .map(|h| sub.then(|| string.exact_moving_frequency_hz(h, v)))
                    .collect(),
                coupled_through_arm: idler.is_some_and(|k| sp.from == k || sp.to == k),
            }
        })
        .collect()
}
