//! The travelling-string modes study of Ribaric §4.2.3: damped natural frequencies of the
//! analytical Galerkin model (4.24)–(4.29) and of the discrete flowing-material model (4.20)
//! at one axial speed. The configuration, its checks and the summary are what
//! `flowmbd-string modes` reads and writes, shared with the Python package
//! (`flowmbd.string.modes`); the model-building helpers are shared by every string study.
//!
//! # Above the critical speed
//!
//! Ribaric §4.2.3 and the seed note's STR-5 call the string unstable for `|v| > c`
//! (`c = √(T/ρA)`); that is what the truncated models show, not what the string does. Its
//! exact eigenvalues are `λ_n = iπn(c² − v²)/(cL)` at every speed (Wickert & Mote 1990; see
//! [`StringConfig::exact_moving_frequency_hz`]), purely imaginary also for `|v| > c`: in the
//! characteristic time `τ = t + v x/(c² − v²)` the equation (4.23)
//! `u_tt + 2v u_xt + (v² − c²) u_xx = 0` becomes the fixed string
//! `u_ττ = ((c² − v²)/c)² u_xx` with the same ends `u(0) = u(L) = 0` (the mixed derivative
//! cancels; the coefficient of `u_ττ` is `c²/(c² − v²)`), whose energy is conserved: the
//! travelling string between fixed guides is neutrally stable on both sides of `c`. At
//! `|v| = c` the transverse stiffness `T − ρAv²` vanishes, every `λ_n` is 0 and any static
//! load deflects the string without bound: divergence, the one instability of this model.
//!
//! The discretisations are not at fault in the way one might suspect: the Galerkin matrix `A`
//! of (4.28) is skew (to round-off) and `B = (c² − v²)(nπ/L)²` exactly diagonal, and with the
//! FE-consistent derivatives `ΨᵀMΨ_,x` is skew and `ΨᵀMΨ_,xx = −Λ/c²` (tests in `flowing` and
//! `tests/`). Above `c` the stiffness `B` (resp. `(1 − v²/c²)Λ`) is negative definite, and a
//! gyroscopic system with a negative definite stiffness of odd dimension always has a real
//! positive eigenvalue (Kelvin–Tait–Chetaev: `det B < 0`, `det(λ²I + λA + B) → +∞`); for any
//! dimension the truncations carry growing pairs whose rates rise without bound as the
//! truncation is refined (Galerkin at 45 m/s: 272, 402, 559, 740 1/s for 20, 40, 80, 160
//! terms). In physical time both waves travel downstream when `|v| > c` (speeds `v ± c`), so
//! the fixed–fixed string is no initial-value problem there (the downstream guide cannot act
//! on the span, the upstream one would need two conditions); its resolvent grows
//! exponentially in the right half plane and every truncation finds eigenvalues there. The
//! truncations' neutral eigenvalues, meanwhile, converge to the exact `λ_n` (tests below).
//!
//! The study therefore reports the exact frequencies at every speed, classifies every growing
//! eigenvalue of a model by a second discretisation (refined, or coarsened at the ceilings;
//! [`classify_growth`]): growth that is not reproduced within
//! [`GROWTH_CHECK_TOLERANCE`] is listed as truncation-dependent (`*_truncation_growth`) and
//! does not make `unstable`; growth that is reproduced does. `unstable` is also set at the
//! critical speed (divergence).

use crate::error::FlowError;
use crate::{
    AxialMotion, DerivativeMethod, FlowingString, GalerkinString, StringConfig, StringMesh,
};
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// Checks the string parameters (finite and positive, with a finite positive wave speed; a
/// slender string: the side `√area` of its cross-section below its length), naming the field
/// `prefix.name`.
pub fn check_string(p: &StringConfig, prefix: &str) -> Result<(), InvalidField> {
    for (name, v) in [
        ("length", p.length),
        ("density", p.density),
        ("area", p.area),
        ("tension", p.tension),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(InvalidField::new(
                format!("{prefix}.{name}"),
                format!("must be a positive number, got {}", check::show(v)),
            ));
        }
    }
    // issue 35: area = 1e300 m² was refused as a speed above the critical one
    if p.area.sqrt() >= p.length {
        return Err(InvalidField::new(
            format!("{prefix}.area"),
            format!(
                "{} m² is not the cross-section of a string {} m long (its side √area must be \
                 below the length: the string model is a slender line)",
                check::show(p.area),
                check::show(p.length)
            ),
        ));
    }
    let (mu, c) = (p.mu(), p.wave_speed());
    if !(mu.is_normal() && c.is_normal()) {
        return Err(InvalidField::new(
            format!("{prefix}.density"),
            format!(
                "density × area = {} kg/m and tension {} N give the wave speed √(T/ρA) = {} \
                 m/s, outside the range of f64 arithmetic",
                check::show(mu),
                check::show(p.tension),
                check::show(c)
            ),
        ));
    }
    Ok(())
}

/// Largest and smallest angular frequency scale \[rad/s\] a string model may have: beyond them
/// the squares in its matrices (`(nπv/L)²`, `4T/(μh²)`) leave f64's range or its round-off.
pub const FREQUENCY_SCALE_RANGE: (f64, f64) = (1e-100, 1e100);

/// Checks that a string model with up to `dofs` modes or nodes at `speed` \[m/s\] stays within
/// [`FREQUENCY_SCALE_RANGE`]: `max(c, |v|)·π·(dofs + 1)/L` and `cπ/L` (an absurd length or
/// speed would otherwise give infinite or zero matrices and non-finite results). The refusal
/// names `speed_field` when the speed sets the top scale, else `prefix.length`.
pub fn check_scales(
    p: &StringConfig, prefix: &str, speed_field: &str, speed: f64, dofs: usize,
) -> Result<(), InvalidField> {
    let c = p.wave_speed();
    let top = c.max(speed.abs()) * std::f64::consts::PI * (dofs as f64 + 1.0) / p.length;
    let low = c * std::f64::consts::PI / p.length;
    let (lo, hi) = FREQUENCY_SCALE_RANGE;
    if !(top <= hi && low >= lo) {
        let field = if speed.abs() > c && top > hi {
            speed_field.to_string()
        } else {
            format!("{prefix}.length")
        };
        return Err(InvalidField::new(
            field,
            format!(
                "length {} m, wave speed {} m/s and speed {} m/s give model frequencies from \
                 {} to {} rad/s, outside [{lo:e}, {hi:e}] rad/s",
                check::show(p.length),
                check::show(c),
                check::show(speed),
                check::show(low),
                check::show(top)
            ),
        ));
    }
    Ok(())
}

/// Checks that `v` is finite (and non-negative if `non_negative`).
pub fn check_number(field: &str, v: f64, non_negative: bool) -> Result<(), InvalidField> {
    if !v.is_finite() || (non_negative && v < 0.0) {
        return Err(InvalidField::new(
            field,
            format!(
                "must be a finite{} number, got {}",
                if non_negative { " non-negative" } else { "" },
                check::show(v)
            ),
        ));
    }
    Ok(())
}

/// Most interior nodes of a string model: its mass and stiffness matrices and the modal
/// eigen problem are dense (`nodes²` entries, `O(nodes³)` work: about a second at 2000), so
/// larger counts are refused before anything is allocated (`--nodes 1e9` aborted on the
/// allocation, issue 20). Ribaric's string has 99.
pub const MAX_STRING_NODES: usize = 2000;

/// Most sine terms of the Galerkin model (4.24) (dense `2N × 2N` state matrix, as
/// [`MAX_STRING_NODES`]).
pub const MAX_GALERKIN_TERMS: usize = 2000;

/// Checks `3 ≤ nodes ≤` [`MAX_STRING_NODES`] and `1 ≤ modes ≤ nodes`.
pub fn check_nodes_modes(nodes: usize, modes: usize) -> Result<(), InvalidField> {
    if nodes < 3 {
        return Err(InvalidField::new(
            "nodes",
            format!("needs at least 3 interior nodes, got {nodes}"),
        ));
    }
    check::size("nodes", nodes, 3, MAX_STRING_NODES)?;
    if modes == 0 || modes > nodes {
        return Err(InvalidField::new(
            "modes",
            format!("must be between 1 and nodes = {nodes}, got {modes}"),
        ));
    }
    Ok(())
}

/// Checks that `duration / step` (both \[s\], positive) is at most `max` steps or samples, naming
/// `field` (the run's length is bounded before it starts).
pub fn check_steps(
    field: &str, duration: f64, step: f64, max: f64, what: &str,
) -> Result<(), InvalidField> {
    let n = duration / step;
    let max = mbd_core::validate::limits::ceiling(max);
    if n > max {
        return Err(InvalidField::new(
            field,
            format!(
                "{} s in steps of {} s is {n:.3e} {what}, more than the {max:e} a run may take{}",
                check::show(duration),
                check::show(step),
                mbd_core::validate::limits::raise_hint()
            ),
        ));
    }
    Ok(())
}

/// The string mesh of `nodes` interior nodes (Ribaric (4.1)) and its flowing-material model
/// (4.20) with `modes` modes at the constant axial speed `speed` \[m/s\].
pub fn flowing_model(
    p: StringConfig, nodes: usize, modes: usize, method: DerivativeMethod, speed: f64,
) -> Result<(StringMesh, FlowingString), FlowError> {
    let mesh = StringMesh::uniform(p, nodes)?;
    let basis = mesh.modes(modes)?;
    let sys = FlowingString::new(
        &mesh.mass_sys(),
        basis,
        &[mesh.flow_line()],
        method,
        AxialMotion::Constant { speed },
    )?;
    Ok((mesh, sys))
}

/// Speed regime of the travelling string: below, at or above its critical speed
/// `c = √(T/ρA)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Regime {
    /// `|v| < c`: frequencies `n(c² − v²)/(2cL)`, neutrally stable.
    Subcritical,
    /// `|v| = c` within [`CRITICAL_SPEED_TOLERANCE`]: no transverse stiffness, every
    /// frequency 0, divergence.
    Critical,
    /// `|v| > c`: frequencies `n(v² − c²)/(2cL)`, neutrally stable (module docs).
    Supercritical,
}

/// Relative distance `||v| − c|/c` within which a speed is the critical speed: there the
/// stiffness `(1 − v²/c²)` is round-off of the input (2·10⁻⁹ relative) and the exact
/// frequencies are 0.
pub const CRITICAL_SPEED_TOLERANCE: f64 = 1e-9;

impl Regime {
    /// The regime of string `p` at `speed` \[m/s\].
    pub fn of(p: &StringConfig, speed: f64) -> Self {
        let c = p.wave_speed();
        let r = (speed.abs() - c) / c;
        if r.abs() <= CRITICAL_SPEED_TOLERANCE {
            Regime::Critical
        } else if r < 0.0 {
            Regime::Subcritical
        } else {
            Regime::Supercritical
        }
    }
}

/// A growing solution of a linear model: an eigenvalue `λ` with `Re λ > 0`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Growth {
    /// Growth rate `Re λ` \[1/s\] (the amplitude grows as `e^{rate·t}`).
    pub rate_per_s: f64,
    /// Frequency `Im λ/2π` \[Hz\] (0: divergence, a non-oscillating growth; > 0: flutter).
    pub frequency_hz: f64,
}

impl Growth {
    fn eigenvalue(&self) -> num_complex::Complex<f64> {
        num_complex::Complex::new(
            self.rate_per_s,
            2.0 * std::f64::consts::PI * self.frequency_hz,
        )
    }
}

/// A growing eigenvalue of a truncated model that a second discretisation does not reproduce
/// (a truncation artefact, not an instability of the string; [`classify_growth`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TruncationGrowth {
    /// Growth rate `Re λ` of the model as configured \[1/s\].
    pub rate_per_s: f64,
    /// Its frequency `Im λ/2π` \[Hz\].
    pub frequency_hz: f64,
    /// Growth rate of the nearest growing eigenvalue of the second discretisation \[1/s\]
    /// (0: it has none).
    pub check_rate_per_s: f64,
    /// Frequency of that eigenvalue \[Hz\] (0 when there is none).
    pub check_frequency_hz: f64,
}

/// Largest relative distance `|λ − λ'|/max(|λ|, |λ'|)` between a growing eigenvalue of a model
/// and the nearest growing eigenvalue of its second discretisation for the growth to count as
/// reproduced (10 %: above the critical speed the truncation artefacts move by 24–50 % per
/// doubling of the Galerkin terms up to the 2000-term ceiling, while a converged eigenvalue
/// moves by far less than 1 %).
pub const GROWTH_CHECK_TOLERANCE: f64 = 0.1;

/// Splits the growing eigenvalues `model` of a discretised model by those `check` of a second
/// discretisation (more or fewer terms, nodes, modes): `(reproduced, truncation-dependent)`.
/// A growing eigenvalue is reproduced when `check` has one within [`GROWTH_CHECK_TOLERANCE`]
/// (relative distance in the complex plane); otherwise its growth depends on the truncation.
pub fn classify_growth(model: &[Growth], check: &[Growth]) -> (Vec<Growth>, Vec<TruncationGrowth>) {
    let mut reproduced = Vec::new();
    let mut artefacts = Vec::new();
    for g in model {
        let l = g.eigenvalue();
        let nearest = check.iter().min_by(|a, b| {
            (a.eigenvalue() - l)
                .norm()
                .total_cmp(&(b.eigenvalue() - l).norm())
        });
        match nearest {
            Some(h)
                if (h.eigenvalue() - l).norm()
                    <= GROWTH_CHECK_TOLERANCE * l.norm().max(h.eigenvalue().norm()) =>
            {
                reproduced.push(*g)
            }
            _ => artefacts.push(TruncationGrowth {
                rate_per_s: g.rate_per_s,
                frequency_hz: g.frequency_hz,
                check_rate_per_s: nearest.map_or(0.0, |h| h.rate_per_s),
                check_frequency_hz: nearest.map_or(0.0, |h| h.frequency_hz),
            }),
        }
    }
    (reproduced, artefacts)
}

/// Sine terms of the Galerkin model that checks the growth of a model with `terms`: twice as
/// many within [`MAX_GALERKIN_TERMS`], else half as many (at least 1; the check never costs
/// more than the documented ceiling).
pub fn check_terms(terms: usize) -> usize {
    if 2 * terms <= MAX_GALERKIN_TERMS {
        2 * terms
    } else {
        (terms / 2).max(1)
    }
}

/// `(nodes, modes)` of the flowing-material model that checks the growth of one with `nodes`
/// interior nodes and `modes` modes: the mesh halved (`2·nodes + 1`: every old node kept) and
/// twice the modes within [`MAX_STRING_NODES`], else the mesh coarsened
/// (`(nodes − 1)/2`, at least 3) with half the modes.
pub fn check_mesh(nodes: usize, modes: usize) -> (usize, usize) {
    if 2 * nodes < MAX_STRING_NODES {
        let n = 2 * nodes + 1;
        (n, (2 * modes).min(n))
    } else {
        let n = ((nodes - 1) / 2).max(3);
        (n, (modes / 2).clamp(1, n))
    }
}

/// The eigenvalues of a discretised model at one speed: its neutral frequencies and its
/// growing solutions.
#[derive(Debug, Clone, PartialEq)]
pub struct Spectrum {
    /// Frequencies `Im λ/2π` \[Hz\] of the oscillating eigenvalues that neither grow nor decay,
    /// ascending ([`crate::StateEigen::neutral_frequencies_hz`]).
    pub neutral_hz: Vec<f64>,
    /// Growing solutions, fastest first ([`crate::StateEigen::growth_rates`]).
    pub growth: Vec<Growth>,
    /// Largest eigenvalue modulus `|λ|` \[1/s\] (what bounds an explicit integrator's step).
    pub max_modulus: f64,
}

impl Spectrum {
    fn of(e: &crate::gyroscopic::StateEigen) -> Self {
        Self {
            neutral_hz: e.neutral_frequencies_hz(),
            growth: e
                .growth_rates()
                .into_iter()
                .map(|(rate_per_s, frequency_hz)| Growth {
                    rate_per_s,
                    frequency_hz,
                })
                .collect(),
            max_modulus: e.values.iter().fold(0.0f64, |a, z| a.max(z.norm())),
        }
    }
}

/// Eigen analysis of the Galerkin model (4.29) with `terms` sine terms at `speed` \[m/s\].
pub fn galerkin_spectrum(p: StringConfig, speed: f64, terms: usize) -> Result<Spectrum, FlowError> {
    let e = GalerkinString::new(p, speed, terms)?
        .system()
        .state_eigen()?;
    Ok(Spectrum::of(&e))
}

/// Eigen analysis of the flowing-material model (4.20) frozen at `speed` \[m/s\].
pub fn flowing_spectrum(sys: &FlowingString, speed: f64) -> Result<Spectrum, FlowError> {
    Ok(Spectrum::of(&sys.frozen(speed, 0.0).state_eigen()?))
}

/// Configuration of the modes study (defaults: Ribaric 4.2.3 string at 20 m/s, 99 nodes,
/// 20 modes).
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct ModesConfig {
    /// String parameters.
    pub string: StringConfig,
    /// Axial speed \[m/s\].
    pub speed: f64,
    /// Interior FE nodes (Ribaric (4.1)).
    pub nodes: usize,
    /// Retained modes of the flowing-material model (4.20).
    pub modes: usize,
    /// Sine terms of the Galerkin model (4.24).
    pub galerkin_terms: usize,
    /// Number of frequencies reported per model (at most the larger model's size).
    pub report: usize,
    /// Mode-shape derivative operator (Ribaric App. A).
    pub derivative: DerivativeMethod,
}

impl Default for ModesConfig {
    fn default() -> Self {
        Self {
            string: StringConfig::default(),
            speed: 20.0,
            nodes: 99,
            modes: 20,
            galerkin_terms: 40,
            report: 10,
            derivative: DerivativeMethod::default(),
        }
    }
}

impl mbd_core::config::PartialRules for ModesConfig {}

impl Validate for ModesConfig {
    fn validate(&self) -> Result<(), InvalidField> {
        check_string(&self.string, "string")?;
        check_number("speed", self.speed, false)?;
        check_nodes_modes(self.nodes, self.modes)?;
        check::size("galerkin_terms", self.galerkin_terms, 1, MAX_GALERKIN_TERMS)?;
        // the second discretisations of the growth check are at most twice as fine
        check_scales(
            &self.string,
            "string",
            "speed",
            self.speed,
            2 * self.nodes.max(self.galerkin_terms) + 1,
        )?;
        let most = self.galerkin_terms.max(self.modes);
        if self.report == 0 || self.report > most {
            return Err(InvalidField::new(
                "report",
                format!(
                    "must be between 1 and the larger model's size max(galerkin_terms, modes) \
                     = {most}, got {}",
                    self.report
                ),
            ));
        }
        Ok(())
    }
}

/// Sizes of the second discretisations that checked the models' growth ([`classify_growth`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct GrowthCheck {
    /// Sine terms of the second Galerkin model (`None`: the Galerkin model did not grow).
    pub galerkin_terms: Option<usize>,
    /// Interior nodes of the second flowing-material model (`None`: it did not grow).
    pub nodes: Option<usize>,
    /// Retained modes of the second flowing-material model.
    pub modes: Option<usize>,
}

/// Relative deviation from the exact travelling-string frequencies above which the modes
/// study warns that its models are not converged (5 %: the 99-node mesh alone is within
/// 3.1 % of the exact 10th frequency up to v = 0.97 c with a full basis).
pub const CONVERGENCE_TOLERANCE: f64 = 0.05;

/// Summary of the modes study (`summary.json`).
#[derive(Debug, Clone, Serialize)]
pub struct ModesSummary {
    /// Axial speed \[m/s\].
    pub speed: f64,
    /// Critical speed `c = √(T/ρA)` \[m/s\].
    pub critical_speed: f64,
    /// Below, at or above the critical speed.
    pub regime: Regime,
    /// Neutral frequencies of the Galerkin model (4.29) \[Hz\], ascending (the eigenvalues on
    /// the imaginary axis; growing or decaying pairs are not natural frequencies).
    pub analytical_hz: Vec<f64>,
    /// Neutral frequencies of the flowing-material model (4.20) \[Hz\], ascending (likewise).
    pub flowing_hz: Vec<f64>,
    /// The exact frequencies of the travelling string between fixed guides,
    /// `f_n = n|c² − v²|/(2cL)` \[Hz\] (Wickert & Mote 1990; Ribaric (4.29) converges to them
    /// on both sides of `c`; all 0 at `|v| = c`), as many as reported.
    pub exact_hz: Vec<f64>,
    /// Whether the string has a growing or diverging solution: at the critical speed
    /// (divergence), or where a model's growth is reproduced by a second discretisation
    /// (`analytical_growth`, `flowing_growth`). Truncation-dependent growth does not count.
    pub unstable: bool,
    /// Growing solutions of the Galerkin model that its second discretisation reproduces,
    /// fastest first (at most `report`).
    pub analytical_growth: Vec<Growth>,
    /// Growing solutions of the flowing-material model that its second discretisation
    /// reproduces, fastest first (at most `report`).
    pub flowing_growth: Vec<Growth>,
    /// Growing eigenvalues of the truncated Galerkin model that the second discretisation does
    /// not reproduce: truncation artefacts, with the check's nearest rate (at most `report`).
    pub analytical_truncation_growth: Vec<TruncationGrowth>,
    /// Likewise for the flowing-material model.
    pub flowing_truncation_growth: Vec<TruncationGrowth>,
    /// Sizes of the second discretisations (present when a model grew).
    pub growth_check: Option<GrowthCheck>,
    /// Largest relative deviation of `analytical_hz` from `exact_hz` (`None` at the critical
    /// speed, where the exact frequencies are 0).
    pub analytical_max_rel_error: Option<f64>,
    /// Largest relative deviation of `flowing_hz` from `exact_hz` (`None` at the critical
    /// speed).
    pub flowing_max_rel_error: Option<f64>,
    /// What the numbers cannot be trusted for: divergence, truncation-dependent growth,
    /// frequencies not converged (the app prints these on stderr).
    pub warnings: Vec<String>,
    /// What the numbers mean.
    pub meaning: String,
}

/// `(index, relative error)` of the worst of `f` against `exact` (over their common length).
fn worst(f: &[f64], exact: &[f64]) -> Option<(usize, f64)> {
    f.iter()
        .zip(exact)
        .map(|(a, b)| (a - b).abs() / b.abs())
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

/// `rate (check rate)` list of truncation growth for a warning.
fn rates(g: &[TruncationGrowth]) -> String {
    g.iter()
        .take(3)
        .map(|t| format!("{:.0} → {:.0}", t.rate_per_s, t.check_rate_per_s))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Run the modes study on a validated configuration: the first `c.report` neutral
/// frequencies of the Galerkin model (4.29) and of the flowing-material model (4.20), the
/// exact ones, the models' growing solutions split by a second discretisation into reproduced
/// and truncation-dependent ones ([`classify_growth`]), and warnings where the models'
/// frequencies are not converged (compared with the exact `f_n = n|c² − v²|/(2cL)`; the
/// flowing model is solved once more with twice the modes to say whether more modes help).
pub fn string_modes(c: &ModesConfig) -> Result<ModesSummary, FlowError> {
    let crit = c.string.wave_speed();
    let regime = Regime::of(&c.string, c.speed);
    let a = galerkin_spectrum(c.string, c.speed, c.galerkin_terms)?;
    let (_, sys) = flowing_model(c.string, c.nodes, c.modes, c.derivative, c.speed)?;
    let f = flowing_spectrum(&sys, c.speed)?;
    let mut check: Option<GrowthCheck> = None;
    let (mut a_growth, mut a_trunc) = if a.growth.is_empty() {
        (Vec::new(), Vec::new())
    } else {
        let terms = check_terms(c.galerkin_terms);
        let other = galerkin_spectrum(c.string, c.speed, terms)?;
        check
            .get_or_insert_with(GrowthCheck::default)
            .galerkin_terms = Some(terms);
        classify_growth(&a.growth, &other.growth)
    };
    let (mut f_growth, mut f_trunc) = if f.growth.is_empty() {
        (Vec::new(), Vec::new())
    } else {
        let (nodes, modes) = check_mesh(c.nodes, c.modes);
        let (_, other) = flowing_model(c.string, nodes, modes, c.derivative, c.speed)?;
        let other = flowing_spectrum(&other, c.speed)?;
        let g = check.get_or_insert_with(GrowthCheck::default);
        (g.nodes, g.modes) = (Some(nodes), Some(modes));
        classify_growth(&f.growth, &other.growth)
    };
    for g in [&mut a_growth, &mut f_growth] {
        g.truncate(c.report);
    }
    for g in [&mut a_trunc, &mut f_trunc] {
        g.truncate(c.report);
    }
    let (mut analytical, mut flowing) = (a.neutral_hz, f.neutral_hz);
    analytical.truncate(c.report);
    flowing.truncate(c.report);
    let unstable = regime == Regime::Critical || !(a_growth.is_empty() && f_growth.is_empty());
    let exact: Vec<f64> = (1..=c.report)
        .map(|n| c.string.exact_moving_frequency_hz(n, c.speed))
        .collect();
    let mut warnings = Vec::new();
    if regime == Regime::Critical {
        warnings.push(format!(
            "the axial speed {} m/s is the critical speed c = √(T/ρA) = {crit:.6} m/s: the \
             tension no longer stiffens the string (T − ρAv² = 0), every exact frequency is 0 \
             Hz and a static load deflects it without bound (divergence: unstable); the \
             models' frequencies here come from the Coriolis coupling alone and do not \
             converge to 0",
            c.speed
        ));
    }
    if !(a_growth.is_empty() && f_growth.is_empty()) {
        let operator = if regime == Regime::Subcritical
            && !matches!(c.derivative, DerivativeMethod::Consistent(_))
            && a_growth.is_empty()
        {
            " (below the critical speed the string and its FE-consistent model are stable: \
             this growth comes from the derivative operator, Ribaric App. A, notes STR-6)"
        } else {
            ""
        };
        warnings.push(format!(
            "growth that a second discretisation reproduces (analytical_growth, \
             flowing_growth; sizes in growth_check): the model is unstable at {} m/s{operator}",
            c.speed
        ));
    }
    if !(a_trunc.is_empty() && f_trunc.is_empty()) {
        let mut what = Vec::new();
        if !a_trunc.is_empty() {
            what.push(format!(
                "Galerkin {} → {} terms: {} 1/s",
                c.galerkin_terms,
                check.and_then(|g| g.galerkin_terms).unwrap_or(0),
                rates(&a_trunc)
            ));
        }
        if !f_trunc.is_empty() {
            what.push(format!(
                "flowing {} nodes/{} modes → {}/{}: {} 1/s",
                c.nodes,
                c.modes,
                check.and_then(|g| g.nodes).unwrap_or(0),
                check.and_then(|g| g.modes).unwrap_or(0),
                rates(&f_trunc)
            ));
        }
        warnings.push(format!(
            "the truncated models have growing eigenvalues whose rates depend on the \
             truncation ({}): truncation artefacts, listed in *_truncation_growth, not an \
             instability of the string{}",
            what.join("; "),
            if regime == Regime::Supercritical {
                format!(
                    " (above the critical speed c = {crit:.4} m/s the string between fixed \
                     guides is neutrally stable with the frequencies exact_hz, but it is no \
                     initial-value problem in physical time: both waves travel downstream, \
                     and a time integration of these models is not valid)"
                )
            } else {
                String::new()
            }
        ));
    }
    let converged = regime != Regime::Critical;
    let f_worst = worst(&flowing, &exact).filter(|_| converged);
    if let Some((n, err)) = f_worst
        && err > CONVERGENCE_TOLERANCE
    {
        let more = (2 * c.modes).min(c.nodes);
        let hint = if more > c.modes {
            let (_, sys2) = flowing_model(c.string, c.nodes, more, c.derivative, c.speed)?;
            let f2 = flowing_spectrum(&sys2, c.speed)?.neutral_hz;
            match worst(&f2[..f2.len().min(c.report)], &exact) {
                Some((_, e2)) => format!(
                    "; with modes = {more} the worst of the first {} is {:.1} % off",
                    c.report,
                    100.0 * e2
                ),
                None => String::new(),
            }
        } else {
            String::new()
        };
        warnings.push(format!(
            "flowing_hz[{n}] (mode {}) is {:.1} % off the exact travelling-string frequency \
             n|c² − v²|/(2cL) = {:.4} Hz: {} retained modes do not converge at v/c = {:.3} \
             (near and above the critical speed the moving string's modes are far from the \
             fixed string's; raise `modes`, and `nodes` for the higher frequencies){hint}",
            n + 1,
            100.0 * err,
            exact[n],
            c.modes,
            c.speed.abs() / crit
        ));
    }
    let a_worst = worst(&analytical, &exact).filter(|_| converged);
    if let Some((n, err)) = a_worst
        && err > CONVERGENCE_TOLERANCE
    {
        warnings.push(format!(
            "analytical_hz[{n}] (mode {}) is {:.1} % off the exact frequency {:.4} Hz: raise \
             `galerkin_terms` ({} now)",
            n + 1,
            100.0 * err,
            exact[n],
            c.galerkin_terms
        ));
    }
    Ok(ModesSummary {
        speed: c.speed,
        critical_speed: crit,
        regime,
        analytical_hz: analytical,
        flowing_hz: flowing,
        exact_hz: exact,
        unstable,
        analytical_growth: a_growth,
        flowing_growth: f_growth,
        analytical_truncation_growth: a_trunc,
        flowing_truncation_growth: f_trunc,
        growth_check: check,
        analytical_max_rel_error: a_worst.map(|w| w.1),
        flowing_max_rel_error: f_worst.map(|w| w.1),
        warnings,
        meaning: MODES_MEANING.to_string(),
    })
}

/// The modes study's "what the numbers mean" paragraph (`meaning` in the summary).
pub const MODES_MEANING: &str = "Natural frequencies of a string of length L, tension T and \
mass per length rho*A travelling at the axial speed v between two fixed guides (Ribaric \
ch. 4): analytical_hz from the Galerkin model (4.29), flowing_hz from the discrete \
flowing-material model (4.20) (the neutral eigenvalues of each, ascending), exact_hz from the \
closed form f_n = n|c^2 - v^2|/(2cL) with the wave speed c = sqrt(T/(rho*A)) = critical_speed \
(Wickert & Mote 1990). The axial motion lowers every frequency (Coriolis coupling of the \
modes) until all reach 0 Hz at v = c (regime \"critical\": no transverse stiffness, \
divergence, unstable = true); above c (regime \"supercritical\") they rise again as \
n(v^2 - c^2)/(2cL) and the string stays neutrally stable. unstable is true at c and where a \
model's growing solution (rate in 1/s: the amplitude grows as e^(rate*t); frequency 0 Hz is \
divergence, > 0 Hz flutter) is reproduced by a second discretisation (growth_check: twice the \
Galerkin terms, or half the FE spacing with twice the modes; coarser at the size ceilings): \
those are listed in analytical_growth / flowing_growth. Growing eigenvalues whose rate \
changes with the truncation are truncation artefacts of the discrete models, listed with the \
second discretisation's rate in analytical_truncation_growth / flowing_truncation_growth and \
not counted as instability (above c every truncation has them, with rates that rise without \
bound as it is refined). analytical_ and flowing_max_rel_error are the largest deviations \
from exact_hz; near and above c the modal basis (the fixed string's modes) converges slowly \
and a warning says when more modes or nodes are needed. The app's frequencies.csv lists the \
three side by side (NaN where a model has fewer neutral frequencies than report) and \
growth.csv every growing eigenvalue (truncation_flag 1: truncation-dependent; check_rate 0: \
the second discretisation does not grow).";

#[cfg(test)]
mod tests {
    use super::*;

    // at rest the Galerkin and flowing frequencies approach the exact string's n·c/(2L)
    // (analytical, Ribaric (4.30) at v = 0)
    #[test]
    fn frequencies_at_rest_match_the_exact_string() {
        let c = ModesConfig {
            speed: 0.0,
            report: 3,
            ..Default::default()
        };
        c.validate().unwrap();
        let s = string_modes(&c).unwrap();
        for n in 1..=3 {
            let exact = c.string.exact_moving_frequency_hz(n, 0.0);
            assert!((s.analytical_hz[n - 1] - exact).abs() < 1e-6 * exact);
            assert!((s.flowing_hz[n - 1] - exact).abs() < 1e-2 * exact);
        }
    }

    /// `n|c² − v²|/(2cL)` for the default string, written out independently of
    /// `StringConfig::exact_moving_frequency_hz` (c from T/(ρA) directly).
    fn closed_form(n: usize, v: f64) -> f64 {
        let c2 = 1000.0 / (7850.0 * 7.854e-5);
        n as f64 * (c2 - v * v).abs() / (2.0 * c2.sqrt())
    }

    fn max_rel_err(f: &[f64], v: f64, count: usize) -> f64 {
        (0..count)
            .map(|i| (f[i] - closed_form(i + 1, v)).abs() / closed_form(i + 1, v))
            .fold(0.0, f64::max)
    }

    // issue 34 item 9: above c = 40.27 m/s (41, 45, 60 m/s) the string between fixed guides is
    // neutrally stable with f_n = n(v² − c²)/(2cL) (Wickert & Mote 1990; module docs: the
    // characteristic time turns (4.23) into a fixed string); the models' growing eigenvalues
    // change by more than 10 % under refinement and are listed as truncation growth, not as
    // instability. Below c nothing grows (the undamped gyroscopic system with positive
    // stiffness has its eigenvalues on the imaginary axis).
    #[test]
    fn supercritical_speeds_are_neutral_and_truncation_growth_is_labelled() {
        for v in [41.0, 45.0, 60.0] {
            let c = ModesConfig {
                speed: v,
                ..Default::default()
            };
            let s = string_modes(&c).unwrap();
            assert_eq!(s.regime, Regime::Supercritical);
            assert!(!s.unstable, "{v} m/s: {:?}", s.warnings);
            assert!(s.analytical_growth.is_empty() && s.flowing_growth.is_empty());
            for g in s
                .analytical_truncation_growth
                .iter()
                .chain(&s.flowing_truncation_growth)
            {
                assert!(g.rate_per_s > 0.0);
                // the refined model grows faster: the rate is not converged
                assert!(g.check_rate_per_s > 1.1 * g.rate_per_s, "{v}: {g:?}");
            }
            assert!(!s.analytical_truncation_growth.is_empty());
            assert!(!s.flowing_truncation_growth.is_empty());
            assert_eq!(
                s.growth_check,
                Some(GrowthCheck {
                    galerkin_terms: Some(80),
                    nodes: Some(199),
                    modes: Some(40)
                })
            );
            for (n, f) in s.exact_hz.iter().enumerate() {
                assert!((f - closed_form(n + 1, v)).abs() < 1e-12 * f, "{v}: {f}");
            }
            // the Galerkin model's neutral frequencies are the exact ones (40 terms: 0.2 %)
            assert!(max_rel_err(&s.analytical_hz, v, 8) < 2e-3, "{v}: {s:?}");
            assert!(
                s.warnings
                    .iter()
                    .any(|w| w.contains("truncation artefacts"))
            );
        }
        for v in [0.0, 20.0, 39.0, -30.0] {
            let s = string_modes(&ModesConfig {
                speed: v,
                ..Default::default()
            })
            .unwrap();
            assert_eq!(s.regime, Regime::Subcritical);
            assert!(!s.unstable, "{v} m/s: {:?}", s.flowing_growth);
            assert!(s.flowing_truncation_growth.is_empty() && s.growth_check.is_none());
        }
    }

    // issue 34 item 9: the Galerkin model's neutral frequencies converge to the exact
    // n(v² − c²)/(2cL) above c as the terms double (20 … 160), while its largest growth rate
    // rises without bound (272, 402, 559, 740 1/s: truncation artefacts); reference: the
    // closed form (Wickert & Mote 1990)
    #[test]
    fn galerkin_converges_to_the_exact_frequencies_above_the_critical_speed() {
        let p = StringConfig::default();
        let v = 45.0;
        let mut errs = Vec::new();
        let mut top = Vec::new();
        for terms in [20, 40, 80, 160] {
            let s = galerkin_spectrum(p, v, terms).unwrap();
            errs.push(max_rel_err(&s.neutral_hz, v, 8));
            top.push(s.growth[0].rate_per_s);
        }
        for w in errs.windows(2) {
            assert!(w[1] < w[0], "{errs:?}");
        }
        assert!(errs[3] < 2e-4, "{errs:?}");
        for w in top.windows(2) {
            assert!(w[1] > 1.2 * w[0], "{top:?}");
        }
    }

    // issue 34 item 9: the suspected causes of the spurious growth are absent at 45 m/s. The
    // Galerkin A of (4.28) is skew and B = (c² − v²)(nπ/L)² exactly diagonal; the
    // flowing model's G = 2vΨᵀMΨ_,x is skew and K = (1 − v²/c²)Λ (FE-consistent operators,
    // notes §2.1). Reference: these closed forms; the growth is the truncation's (module docs)
    #[test]
    fn discretisations_stay_exactly_gyroscopic_above_the_critical_speed() {
        let p = StringConfig::default();
        let (v, c2) = (45.0, p.wave_speed().powi(2));
        let g = GalerkinString::new(p, v, 21).unwrap().system();
        let (_, sys) = flowing_model(p, 99, 21, DerivativeMethod::default(), v).unwrap();
        let f = sys.frozen(v, 0.0);
        for i in 0..21 {
            for j in 0..21 {
                // skew to round-off (each entry of (4.28) is evaluated on its own)
                let a = g.gyro[(i, j)];
                assert!((a + g.gyro[(j, i)]).abs() <= 1e-14 * a.abs(), "{i} {j}");
                let b = if i == j {
                    (c2 - v * v) * (std::f64::consts::PI * (i + 1) as f64).powi(2)
                } else {
                    0.0
                };
                assert!((g.stiffness[(i, j)] - b).abs() <= 1e-12 * b.abs());
                assert!((f.gyro[(i, j)] + f.gyro[(j, i)]).abs() < 1e-9, "{i} {j}");
                let k = if i == j {
                    (1.0 - v * v / c2) * sys.basis.lambda[i]
                } else {
                    0.0
                };
                assert!(
                    (f.stiffness[(i, j)] - k).abs() < 1e-8 * sys.basis.lambda[20],
                    "{i} {j}"
                );
            }
        }
        // 21 negative stiffnesses: an odd count, so a real growing eigenvalue
        // (Kelvin–Tait–Chetaev), in both models
        for s in [
            galerkin_spectrum(p, v, 21).unwrap(),
            flowing_spectrum(&sys, v).unwrap(),
        ] {
            assert!(
                s.growth.iter().any(|g| g.frequency_hz == 0.0),
                "{:?}",
                s.growth
            );
        }
    }

    // issue 34 item 9: the flowing-material model's neutral frequencies converge to the exact
    // supercritical ones as the mesh and the basis are refined together (FE error ~ h²);
    // reference: the closed form n(v² − c²)/(2cL)
    #[test]
    fn flowing_model_converges_to_the_exact_frequencies_above_the_critical_speed() {
        let p = StringConfig::default();
        for v in [45.0, 60.0] {
            let errs: Vec<f64> = [(99, 20), (199, 40), (399, 80)]
                .iter()
                .map(|&(n, k)| {
                    let (_, sys) = flowing_model(p, n, k, DerivativeMethod::default(), v).unwrap();
                    max_rel_err(&flowing_spectrum(&sys, v).unwrap().neutral_hz, v, 5)
                })
                .collect();
            for w in errs.windows(2) {
                assert!(w[1] < 0.5 * w[0], "{v}: {errs:?}");
            }
            assert!(errs[2] < 2e-3, "{v}: {errs:?}");
        }
    }

    // issue 34 item 9: at v = c the stiffness T − ρAv² vanishes: every exact frequency is 0
    // (closed form) and the string diverges, which the summary flags (unstable, regime
    // critical); relative errors against 0 Hz are not reported
    #[test]
    fn critical_speed_is_divergence() {
        let p = StringConfig::default();
        let s = string_modes(&ModesConfig {
            speed: p.wave_speed(),
            ..Default::default()
        })
        .unwrap();
        assert_eq!(s.regime, Regime::Critical);
        assert!(s.unstable);
        assert!(s.exact_hz.iter().all(|f| *f == 0.0) && s.exact_hz.len() == 10);
        assert!(s.flowing_max_rel_error.is_none() && s.analytical_max_rel_error.is_none());
        assert!(s.warnings[0].contains("divergence"), "{:?}", s.warnings);
        // one part in 10⁸ away from c the string is off-critical again, with tiny frequencies
        let s = string_modes(&ModesConfig {
            speed: p.wave_speed() * (1.0 + 1e-8),
            report: 3,
            ..Default::default()
        })
        .unwrap();
        assert_eq!(s.regime, Regime::Supercritical);
        assert!(!s.unstable);
        // c² − v² = −2·10⁻⁸ c²: the two forms agree to the cancellation's 10⁻⁸ relative
        let want = closed_form(1, p.wave_speed() * (1.0 + 1e-8));
        assert!(
            want > 0.0 && (s.exact_hz[0] - want).abs() < 1e-6 * want,
            "{:?}",
            s.exact_hz
        );
    }

    // definition of the growth check: a growing eigenvalue that the second discretisation
    // reproduces within 10 % is kept as growth, one that moves further is truncation growth
    // and carries the nearest check eigenvalue (or 0 when the check does not grow)
    #[test]
    fn growth_is_classified_by_the_second_discretisation() {
        let g = |rate_per_s, frequency_hz| Growth {
            rate_per_s,
            frequency_hz,
        };
        let (kept, art) = classify_growth(
            &[g(100.0, 0.0), g(300.0, 20.0), g(50.0, 3.0)],
            &[g(101.0, 0.0), g(450.0, 22.0)],
        );
        assert_eq!(kept, vec![g(100.0, 0.0)]);
        assert_eq!(art.len(), 2);
        assert_eq!(
            (art[0].check_rate_per_s, art[0].check_frequency_hz),
            (450.0, 22.0)
        );
        // 50 + 18.8i is nearest to 101 + 0i, 47 % away
        assert_eq!(art[1].check_rate_per_s, 101.0);
        let (kept, art) = classify_growth(&[g(10.0, 1.0)], &[]);
        assert!(kept.is_empty() && art[0].check_rate_per_s == 0.0);
        assert_eq!(check_terms(40), 80);
        assert_eq!(check_terms(1500), 750);
        assert_eq!(check_mesh(99, 20), (199, 40));
        assert_eq!(check_mesh(99, 99), (199, 198));
        assert_eq!(check_mesh(1500, 1500), (749, 749));
    }

    // issue 20: at 39 m/s the default 20 modes leave the 10th frequency 21.6 % off the exact
    // f_n = n(c² − v²)/(2cL) (Wickert & Mote 1990), and the summary warns; 40 modes converge
    // to the mesh's own error (3.1 %, measured with all 99 modes), and the warning says so.
    // At 20 m/s nothing is off by more than 1 % and nothing is warned.
    #[test]
    fn unconverged_frequencies_near_critical_speed_are_warned() {
        let c = ModesConfig {
            speed: 39.0,
            ..Default::default()
        };
        let s = string_modes(&c).unwrap();
        let crit = c.string.wave_speed();
        for (n, f) in s.exact_hz.iter().enumerate() {
            let want = (n + 1) as f64 * crit * (1.0 - 39.0 * 39.0 / (crit * crit)) / 2.0;
            assert!((f - want).abs() < 1e-12 * want);
        }
        let err = s.flowing_max_rel_error.unwrap();
        assert!(err > 0.2 && err < 0.3, "{err}");
        let w = s.warnings.join(" | ");
        assert!(
            w.contains("mode 10") && w.contains("with modes = 40"),
            "{w}"
        );
        // the hint's figure: 40 modes bring the 10th frequency within 5 %
        let s40 = string_modes(&ModesConfig { modes: 40, ..c }).unwrap();
        assert!(s40.flowing_max_rel_error.unwrap() < CONVERGENCE_TOLERANCE);
        assert!(s40.warnings.is_empty(), "{:?}", s40.warnings);
        let s20 = string_modes(&ModesConfig::default()).unwrap();
        assert!(s20.flowing_max_rel_error.unwrap() < 0.01);
        assert!(s20.warnings.is_empty());
    }

    // the messages name the field (definition of the checks); issue 35: `report` and the
    // model's frequency scale are bounded before anything is allocated
    #[test]
    fn bad_nodes_report_and_scales_are_named() {
        let bad = |c: ModesConfig| c.validate().unwrap_err().field;
        let d = ModesConfig::default;
        assert_eq!(bad(ModesConfig { nodes: 2, ..d() }), "nodes");
        assert_eq!(bad(ModesConfig { report: 41, ..d() }), "report");
        assert_eq!(
            bad(ModesConfig {
                report: usize::MAX,
                ..d()
            }),
            "report"
        );
        let tiny = StringConfig {
            length: 1e-300,
            ..StringConfig::default()
        };
        // a 1e-300 m string: refused by its length or by the area that no longer fits it
        // (area below length², issue 35)
        let f = bad(ModesConfig {
            string: tiny,
            ..d()
        });
        assert!(f == "string.length" || f == "string.area", "{f}");
        assert_eq!(
            bad(ModesConfig {
                speed: 1e200,
                ..d()
            }),
            "speed"
        );
        let light = StringConfig {
            density: 1e-200,
            area: 1e-200,
            ..StringConfig::default()
        };
        assert_eq!(
            bad(ModesConfig {
                string: light,
                ..d()
            }),
            "string.density"
        );
        assert!(ModesConfig { report: 40, ..d() }.validate().is_ok());
    }
}
