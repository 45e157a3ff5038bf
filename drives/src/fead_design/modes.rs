//! Modes of the drive about an operating point: the linearised rotational model and the
//! transverse span modes.
//!
//! # Rotational model (Hwang, Perkins, Ulsoy & Meckstroth 1994; Beikmann, Perkins & Ulsoy 1996)
//!
//! Coordinates `q`: the rotation `θ_k` \[rad\] (travel sense) of every free pulley and, with a
//! tensioner, its arm angle `θ_a` \[rad\]; the speed-driven pulley is held (`θ = 0`: the crank's
//! inertia is large). Span `k`, from pulley `i` to pulley `j` with unit direction `d_k`, is an
//! axial spring of stiffness `k_k = EA_t/L_k` \[N/m\] (`EA_t = dN/dλ` at the span's tension,
//! [`belt::Section::tangent_stiffness`]; `L_k` the span length) on the stretch
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
//! **Not modelled**: the belt's compliance and creep on the wraps (the belt is fixed to the
//! pulleys over its wraps: the spans are the only springs), the belt's mass, damping, and the
//! spans' transverse motion (see below). For a two-pulley drive with the driver held this
//! gives exactly `f = √(2 k r²/J)/(2π)`, `k = EA/L`. Each omission adds compliance or mass, so
//! the frequencies are upper bounds of a model that had them (Rayleigh's principle). Against
//! the flowing belt model's free ring-down (`drives/examples/fead_ringdown.rs`,
//! `drives/tests/fead_sweep.rs`): −2 % on a two-pulley drive at κ = 2000 s/m; −14 % for the
//! default FEAD drive's first mode (49.4 Hz predicted, 42.35 Hz at κ = 40 s/m), about a third
//! each from the tanh law's creep on the wraps, the loaded pulleys' slip arcs and the flowing
//! model's discretisation.
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
use serde::Serialize;

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

/// Build the rotational model of `drive` about the steady state `s` (module documentation).
pub fn rotational_model(drive: &Drive, s: &SteadyState) -> RotationalModel {
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
    for sp in &s.geometry.spans {
        let (i, j) = (sp.from, sp.to);
        let k = section.tangent_stiffness(s.tensions[i]) / sp.length;
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
