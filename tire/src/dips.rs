//! The speed dips of the cleat test (Ribaric §8.3, Fig. 8-7: the vertical amplitude drops at
//! 40–50 km/h on the drum; §8.5, Fig. 8-14: at 45–55 km/h on the flat road), predicted from the
//! cleat's enveloping and the loaded tire's vertical mode.
//!
//! # Mechanism
//! Ribaric gives no explanation beyond "the boundary conditions (patch size and pressure
//! distribution) have changed" (§8.5). The one used here is the classical enveloping filter of
//! tire–obstacle models (the "basic function" of Zegelaar's and Schmeitz's enveloping models):
//! the cleat is felt by the tire over a stretch of road `L` around the patch centre, longer
//! than the patch, because the tread next to the patch is less than the cleat height above the
//! ground. The quasi-static change of the vertical spindle force while the cleat passes,
//! `ΔF(x)` (`x` the cleat's distance ahead of the patch centre), is computed from the reduced
//! tire's contact-node flexibility with the spindle height held ([`enveloping_profile`]).
//!
//! At speed `v` this profile is a force pulse `ΔF(−v t)` acting on the loaded tire's vertical
//! mode (frequency `f`, damping ratio `ζ`; [`super::loaded`]): the cleat test's dominant
//! vertical line (BENCHMARKS.md, issue 21: 88–96 % of the line is that one mode at every speed).
//! A mode that follows its quasi-static response, `q̈ + 2ζωq̇ + ω²q = ω² ΔF(t)`, rings down
//! after the pulse with the amplitude (referred to `t = 0`, the cleat at the patch centre)
//!
//! ```text
//!   A(v) = (ω² / ω_d) |∫ ΔF(t) e^{−s t} dt|,   s = −ζω + i ω_d,   ω_d = ω √(1 − ζ²)
//!        = (ω² / (ω_d v)) |∫ ΔF(x) e^{s x / v} dx|                       [N]
//! ```
//!
//! (Duhamel's integral of the free response; undamped, `A = κ |ΔF̂(κ)|` with the wavenumber
//! `κ = ω/v`). `A(v)` vanishes (undamped) or has a minimum (damped) where the pulse's spectrum
//! has a zero at `f`: for a pulse of length `L` and a smooth, half-sine-like shape at
//! `f L / v ≈ 1.5, 2.5, …`, i.e. the dips lie at `v_k ≈ f L / (k + ½)` ([`predict_dips`]).
//! A longer enveloping length or a stiffer vertical mode moves them to higher speeds; the road
//! envelopes the cleat over a longer stretch than the convex drum
//! ([`geometric_envelope_half_length`]), so its dips lie higher, as in Ribaric.
//!
//! Which pulse: the quasi-static profile of the generated tire is a comb of peaks (the cleat
//! meets the 17 mm-spaced node rows one by one) with an M-shaped envelope, and its zeros put
//! the dips 1.7–1.9 times too high; the spindle force of the simulated passage is a single
//! hump over the same stretch, and a half sine over the profile's support
//! ([`PulseShape::HalfSine`]) predicts the sweep's dips (BENCHMARKS.md, "speed dips").
//!
//! The coincidence of the line with harmonics of the wheel rotation is no mechanism for one
//! cleat passage: a single pulse has no periodic excitation whose harmonics could meet the
//! mode, and the rotation frequency `v / 2πR` (1.7–8.5 Hz at 20–100 km/h on this tire) is of
//! the order of the line's half-power bandwidth `2ζf` (4.4 Hz at 76 Hz, ζ = 2.9 %), so some
//! harmonic lies within the line at every speed.

use crate::error::{TireError, invalid};
use crate::ground::{Ground, GroundConfig, GroundKind};
use crate::reduced::ReducedTire;
use crate::spectrum::Spectrum;
use crate::statics::{contact_at, preload, reduced_flexibility};
use mbd_core::validate::{Validate, check};
use serde::Serialize;
use std::f64::consts::PI;

/// Quasi-static vertical and longitudinal spindle force while the cleat passes the patch, the
/// spindle held at its preload height (module docs).
#[derive(Debug, Clone, Serialize)]
pub struct EnvelopingProfile {
    /// Cleat positions ahead of the patch centre \[m\] (ascending, uniform).
    pub cleat_x: Vec<f64>,
    /// Change of the vertical spindle force from the preload `ΔF_y(x)` \[N\].
    pub dfy: Vec<f64>,
    /// Longitudinal spindle force `F_x(x)` \[N\] (frictionless contact: the cleat's slope).
    pub fx: Vec<f64>,
    /// Contact nodes pressed at each position.
    pub active: Vec<usize>,
    /// Preload deflection \[m\].
    pub deflection: f64,
    /// Where the cleat is felt: first and last position with `ΔF_y` above 0.1 % of its peak
    /// \[m\]; their distance is the enveloping length `L`.
    pub support: [f64; 2],
    /// Extent of the contact nodes along `x` \[m\] (the cleat can act only within it, widened
    /// by the cleat radius).
    pub node_span: [f64; 2],
}

impl EnvelopingProfile {
    /// Enveloping length `L` \[m\]: the stretch over which the cleat changes the spindle force.
    pub fn length(&self) -> f64 {
        self.support[1] - self.support[0]
    }

    /// Ring-down amplitude `A(v)` \[N\] of a mode of frequency `f_hz` \[Hz\] and damping ratio
    /// `zeta` that tracks `ΔF_y` quasi-statically, after the cleat passed at `speed` \[m/s\]
    /// (module docs; Duhamel's integral evaluated at the mode's pole, trapezoidal rule in `x`).
    pub fn ring_down_amplitude(&self, f_hz: f64, zeta: f64, speed: f64) -> f64 {
        ring_down_amplitude(&self.cleat_x, &self.dfy, f_hz, zeta, speed)
    }
}

/// Ring-down amplitude of `q̈ + 2ζωq̇ + ω²q = ω² u(t)` after the pulse `u(t) = p(−v t)` given on
/// the positions `x` (`p` in N, positions in m), referred to `t = 0` \[N\] (module docs).
pub fn ring_down_amplitude(x: &[f64], p: &[f64], f_hz: f64, zeta: f64, speed: f64) -> f64 {
    let w = 2.0 * PI * f_hz;
    let wd = w * (1.0 - zeta * zeta).max(0.0).sqrt();
    // t = −x/v: e^{−s t} = e^{s x / v}, s = −ζω + iω_d
    let (sr, si) = (-zeta * w / speed, wd / speed);
    let (mut re, mut im) = (0.0, 0.0);
    for k in 0..x.len().saturating_sub(1) {
        let h = x[k + 1] - x[k];
        for j in [k, k + 1] {
            let e = (sr * x[j]).exp();
            re += 0.5 * h * p[j] * e * (si * x[j]).cos();
            im += 0.5 * h * p[j] * e * (si * x[j]).sin();
        }
    }
    w * w / (wd * speed) * re.hypot(im)
}

/// Half-length \[m\] of the stretch over which the undeformed tire (outer radius `r_tire`,
/// pressed by `deflection` onto the ground) comes within the cleat's height of the ground:
/// the gap between tire and ground at `x` is `x²/(2 R_e) − d` with `1/R_e = 1/R_t + 1/R_d`
/// (drum radius `R_d`; road `R_d = ∞`), so a cleat of height `h` touches the tread for
/// `|x| < √(2 R_e (h + d))` (second-order expansion of both circles; the geometric reference
/// of the enveloping length).
pub fn geometric_envelope_half_length(r_tire: f64, ground: &GroundConfig, deflection: f64) -> f64 {
    let inv = match ground.kind {
        GroundKind::Road => 1.0 / r_tire,
        GroundKind::Drum => 1.0 / r_tire + 1.0 / ground.drum_radius,
    };
    (2.0 / inv * (ground.cleat_radius + deflection)).sqrt()
}

/// The quasi-static enveloping profile of the reduced tire (module docs): the tire preloaded
/// with `load` \[N\] onto `ground` (non-rolling, [`preload`]), the spindle held at that height,
/// and the cleat placed at positions `x` every `step` \[m\] over the contact nodes' extent
/// widened by twice the cleat radius; at each position the frictionless contact problem of
/// the contact nodes (Lagrange multipliers, Ribaric §7.3) is solved with the contact-node
/// flexibility `Y = T_c K_z⁻¹ T_cᵀ`.
///
/// `blocked_below_hz` \[Hz\] > 0 gives the *blocked* profile: the modes of the reduced tire
/// (rim fixed) below that frequency are held at their preload deflection and only the faster
/// ones follow the cleat quasi-statically, i.e. the flexibility is split by the modal sum
/// `Y = Σ_k T_c φ_k φ_kᵀ T_cᵀ / ω_k²` into `Y_slow + Y_fast` (the residual flexibility of the
/// mode-acceleration method) and the contact problem is solved with `Y_fast` from the
/// positions `s_c + Y_slow f^c₀`. This is the force the cleat puts on the slow part of the
/// tire when its passage is short against the periods of those modes; with 0 every mode
/// follows (the quasi-static profile).
pub fn enveloping_profile(
    red: &ReducedTire, ground: &GroundConfig, load: f64, step: f64, blocked_below_hz: f64,
) -> Result<EnvelopingProfile, TireError> {
    check::positive("step", step, "m")?;
    check::non_negative("blocked_below_hz", blocked_below_hz, "Hz")?;
    ground.validate_within("ground")?;
    if !ground.cleat {
        return Err(invalid(
            "ground.cleat",
            "the enveloping profile needs the cleat",
        ));
    }
    if ground.has_obstacles_or_grid() {
        return Err(invalid(
            "ground.obstacles",
            "the enveloping profile is that of the cleat alone (no obstacles or height grid)",
        ));
    }
    let pre = preload(red, ground, load)?;
    let (mut y, _) = reduced_flexibility(red)?;
    let mut shifted = red.contact_positions.clone();
    if blocked_below_hz > 0.0 {
        let modes = fe_model::dense_modes(red.k.as_ref(), red.m.as_ref(), red.n_z())?;
        let nc3 = red.tc.nrows();
        for (k, &f) in modes.frequencies_hz.iter().enumerate() {
            if f >= blocked_below_hz {
                break;
            }
            let u = &red.tc * modes.vectors.col(k);
            let w2 = modes.values[k];
            for i in 0..nc3 {
                for j in 0..nc3 {
                    y[(i, j)] -= u[i] * u[j] / w2;
                }
                // slow part of the preload deflection: Y_slow f^c₀
                let d: f64 = (0..nc3).map(|j| u[i] * u[j] / w2 * pre.patch.f_c[j]).sum();
                shifted[i / 3][i % 3] += d;
            }
        }
    }
    let s_c = &shifted;
    let lo = s_c.iter().map(|s| s[0]).fold(f64::INFINITY, f64::min);
    let hi = s_c.iter().map(|s| s[0]).fold(f64::NEG_INFINITY, f64::max);
    let reach = 2.0 * ground.cleat_radius;
    let n = ((hi - lo + 2.0 * reach) / step).ceil() as usize + 1;
    if n > 1_000_000 {
        return Err(invalid(
            "step",
            format!("{step} m gives {n} cleat positions (at most 1e6)"),
        ));
    }
    let f0: f64 = (0..s_c.len()).map(|i| pre.patch.f_c[3 * i + 2]).sum();
    let (mut xs, mut dfy, mut fx, mut active) = (vec![], vec![], vec![], vec![]);
    for k in 0..n {
        let x = lo - reach + k as f64 * step;
        // the cleat `x` ahead of the patch centre at t = 0 (`Ground::cleat_ahead`)
        let g = Ground::without_grid(ground.clone(), pre.patch.top, 1.0, 0.0, x);
        let (lambda, f_c, _) = contact_at(&y, s_c, &g)?;
        xs.push(x);
        dfy.push((0..s_c.len()).map(|i| f_c[3 * i + 2]).sum::<f64>() - f0);
        fx.push((0..s_c.len()).map(|i| f_c[3 * i]).sum::<f64>());
        active.push(lambda.iter().filter(|&&l| l > 0.0).count());
    }
    let peak = dfy.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let felt: Vec<usize> = (0..n).filter(|&k| dfy[k].abs() > 1e-3 * peak).collect();
    let support = match (felt.first(), felt.last()) {
        (Some(&a), Some(&b)) => [xs[a], xs[b]],
        _ => [0.0, 0.0],
    };
    Ok(EnvelopingProfile {
        cleat_x: xs,
        dfy,
        fx,
        active,
        deflection: pre.patch.deflection,
        support,
        node_span: [lo, hi],
    })
}

/// Predicted ring-down amplitude against speed and its dips.
#[derive(Debug, Clone, Serialize)]
pub struct DipPrediction {
    /// Frequency of the vertical mode \[Hz\].
    pub mode_hz: f64,
    /// Its damping ratio.
    pub zeta: f64,
    /// Speeds \[km/h\].
    pub speeds_kmh: Vec<f64>,
    /// Ring-down amplitude `A(v)` \[N\].
    pub amplitude_n: Vec<f64>,
    /// Speeds of the local minima of `A(v)` \[km/h\].
    pub dips_kmh: Vec<f64>,
}

/// `A(v)` of `profile` for the mode `f_hz` \[Hz\], `zeta` over `speeds_kmh` \[km/h\] and its
/// local minima (module docs).
pub fn predict_dips(
    profile: &EnvelopingProfile, f_hz: f64, zeta: f64, speeds_kmh: &[f64],
) -> Result<DipPrediction, TireError> {
    check::positive("mode frequency", f_hz, "Hz")?;
    check::within("zeta", zeta, 0.0, 0.99, "")?;
    for (i, v) in speeds_kmh.iter().enumerate() {
        check::positive(&format!("speeds_kmh[{i}]"), *v, "km/h")?;
    }
    let amplitude_n: Vec<f64> = speeds_kmh
        .iter()
        .map(|v| profile.ring_down_amplitude(f_hz, zeta, v / 3.6))
        .collect();
    Ok(DipPrediction {
        mode_hz: f_hz,
        zeta,
        speeds_kmh: speeds_kmh.to_vec(),
        dips_kmh: local_minima(speeds_kmh, &amplitude_n),
        amplitude_n,
    })
}

/// The abscissae of the strict interior local minima of `y(x)`.
pub fn local_minima(x: &[f64], y: &[f64]) -> Vec<f64> {
    (1..y.len().min(x.len()).saturating_sub(1))
        .filter(|&i| y[i] < y[i - 1] && y[i] < y[i + 1])
        .map(|i| x[i])
        .collect()
}

/// Amplitude \[N\] of the spectral line near `f_hz` from the energy of the amplitude
/// spectrum within `f_hz ± half_band` \[Hz\]: `√(Σ A_k² / 1.5)`, the Hann window's equivalent
/// noise bandwidth being 1.5 bins, so that a sine of amplitude `A` gives `A` wherever it falls
/// between the bins (Parseval); the peak bin alone scallops by up to 15 % (−1.42 dB) as the
/// line moves across the 3.3 Hz bins of the 0.3 s record. The measured counterpart of `A(v)`.
pub fn line_amplitude(spectrum: &Spectrum, f_hz: f64, half_band: f64) -> f64 {
    let e: f64 = spectrum
        .freq_hz
        .iter()
        .zip(&spectrum.amplitude)
        .filter(|(f, _)| (**f - f_hz).abs() <= half_band)
        .map(|(_, a)| a * a)
        .sum();
    (e / 1.5).sqrt()
}

/// Shape of the force pulse whose spectrum filters the vertical mode in [`ground_dips`].
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum PulseShape {
    /// A half sine over the profile's support `L` (a smooth single hump, the shape of the
    /// enveloping models' basic function; dips at `v ≈ f L / (k + ½)`). Default: it predicts
    /// the sweep's dips of the generated tire (BENCHMARKS.md, "speed dips"), where the spiky
    /// quasi-static profile of the discrete node rows does not.
    HalfSine,
    /// The quasi-static (or blocked) profile itself.
    Profile,
}

impl PulseShape {
    /// The pulse on the profile's positions: the profile, or a half sine of the profile's
    /// peak over its support.
    pub fn pulse(self, p: &EnvelopingProfile) -> Vec<f64> {
        match self {
            Self::Profile => p.dfy.clone(),
            Self::HalfSine => {
                let peak = p.dfy.iter().copied().fold(0.0, f64::max);
                let [a, b] = p.support;
                p.cleat_x
                    .iter()
                    .map(|&x| {
                        if b > a && x >= a && x <= b {
                            peak * (PI * (x - a) / (b - a)).sin()
                        } else {
                            0.0
                        }
                    })
                    .collect()
            }
        }
    }
}

/// Settings of [`ground_dips`].
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct DipConfig {
    /// Spacing of the cleat positions of the enveloping profile \[m\].
    pub profile_step: f64,
    /// Modes of the rim-fixed reduced tire below this frequency are blocked in the profile
    /// ([`enveloping_profile`]) \[Hz\]; 0 = quasi-static profile.
    pub blocked_below_hz: f64,
    /// Pulse shape of the prediction.
    pub pulse: PulseShape,
    /// Speeds of the predicted amplitude curve \[km/h\].
    pub predict_speeds_kmh: Vec<f64>,
    /// Speeds of the cleat sweep \[km/h\] (empty: prediction only).
    pub sweep_speeds_kmh: Vec<f64>,
    /// Half width of the band around the loaded vertical mode in which the sweep's line
    /// amplitude is measured \[Hz\].
    pub line_half_band_hz: f64,
}

impl Default for DipConfig {
    fn default() -> Self {
        Self {
            profile_step: 1e-3,
            blocked_below_hz: 0.0,
            pulse: PulseShape::HalfSine,
            predict_speeds_kmh: (0..=220).map(|k| 10.0 + 0.5 * k as f64).collect(),
            sweep_speeds_kmh: (0..=16).map(|k| 20.0 + 5.0 * k as f64).collect(),
            line_half_band_hz: 12.0,
        }
    }
}

/// Most speeds of a predicted curve or a sweep.
pub const MAX_DIP_SPEEDS: usize = 100_000;

impl Validate for DipConfig {
    /// Positive profile step and band, positive finite speeds (at least three predicted, at
    /// most [`MAX_DIP_SPEEDS`]), ascending.
    fn validate(&self) -> Result<(), mbd_core::validate::InvalidField> {
        check::positive("profile_step", self.profile_step, "m")?;
        check::non_negative("blocked_below_hz", self.blocked_below_hz, "Hz")?;
        check::positive("line_half_band_hz", self.line_half_band_hz, "Hz")?;
        for (name, v, min) in [
            ("predict_speeds_kmh", &self.predict_speeds_kmh, 3),
            ("sweep_speeds_kmh", &self.sweep_speeds_kmh, 0),
        ] {
            check::count(&format!("{name} (length)"), v.len(), min, MAX_DIP_SPEEDS)?;
            for (i, x) in v.iter().enumerate() {
                check::positive(&format!("{name}[{i}]"), *x, "km/h")?;
                if i > 0 && *x <= v[i - 1] {
                    return Err(mbd_core::validate::InvalidField::new(
                        format!("{name}[{i}]"),
                        "speeds must ascend",
                    ));
                }
            }
        }
        Ok(())
    }
}

/// Dips of one ground: the prediction and, with sweep speeds, the measured line amplitude.
#[derive(Debug, Clone, Serialize)]
pub struct GroundDips {
    /// The ground.
    pub ground: GroundKind,
    /// Enveloping profile (module docs).
    pub profile: EnvelopingProfile,
    /// Enveloping length `L` of the profile \[m\].
    pub envelope_length_m: f64,
    /// Twice [`geometric_envelope_half_length`] at the preload deflection \[m\].
    pub geometric_envelope_length_m: f64,
    /// The loaded tire's vertical mode \[Hz\] ([`super::loaded::dominant_vertical_mode`]).
    pub vertical_mode_hz: f64,
    /// Its Rayleigh damping ratio in the rig.
    pub zeta: f64,
    /// Predicted amplitude against speed (of the pulse [`DipConfig::pulse`]) and its dips.
    pub prediction: DipPrediction,
    /// Sweep speeds \[km/h\].
    pub sweep_speeds_kmh: Vec<f64>,
    /// Measured amplitude of the vertical line per sweep speed ([`line_amplitude`]) \[N\].
    pub line_amplitude_n: Vec<f64>,
    /// Local minima of the measured line amplitude \[km/h\].
    pub measured_dips_kmh: Vec<f64>,
}

/// Prediction and measurement of the speed dips on the ground of `rig` (its speed replaced
/// by the sweep speeds): the enveloping profile ([`enveloping_profile`]), the loaded vertical
/// mode at the static preload with its Rayleigh damping ratio, `A(v)` ([`predict_dips`]) and,
/// for each sweep speed, the cleat test ([`super::rig::run_cleat`]) with the amplitude of its
/// vertical line ([`line_amplitude`]). `progress` gets the fraction of sweep runs done.
pub fn ground_dips(
    red: &ReducedTire, rig: &super::rig::RigConfig, cfg: &DipConfig, progress: &mut dyn FnMut(f64),
) -> Result<GroundDips, TireError> {
    cfg.validate_within("dips")?;
    let ground = &rig.ground;
    let profile = enveloping_profile(
        red,
        ground,
        rig.load,
        cfg.profile_step,
        cfg.blocked_below_hz,
    )?;
    let mut plain = ground.clone();
    plain.cleat = false;
    let (_, modes) = super::loaded::loaded_modes_at_preload(red, &plain, rig.load)?;
    let mode = super::loaded::dominant_vertical_mode(&modes)
        .ok_or_else(|| invalid("loaded modes", "no vertical mode of the loaded tire"))?;
    let zeta = rig
        .damping
        .rayleigh(red)?
        .ratio(2.0 * PI * mode.hz)
        .clamp(0.0, 0.99);
    let pulse = EnvelopingProfile {
        dfy: cfg.pulse.pulse(&profile),
        ..profile.clone()
    };
    let prediction = predict_dips(&pulse, mode.hz, zeta, &cfg.predict_speeds_kmh)?;
    let n = cfg.sweep_speeds_kmh.len();
    let mut line_amplitude_n = Vec::with_capacity(n);
    for (k, &v) in cfg.sweep_speeds_kmh.iter().enumerate() {
        let mut r = rig.clone();
        r.speed_kmh = v;
        let res = super::rig::run_cleat(red, &r, &mut |f| progress((k as f64 + f) / n as f64))?;
        let (_, sy) = res.spectra();
        line_amplitude_n.push(line_amplitude(&sy, mode.hz, cfg.line_half_band_hz));
    }
    Ok(GroundDips {
        ground: ground.kind,
        envelope_length_m: profile.length(),
        geometric_envelope_length_m: 2.0
            * geometric_envelope_half_length(red.outer_radius, ground, profile.deflection),
        profile,
        vertical_mode_hz: mode.hz,
        zeta,
        prediction,
        measured_dips_kmh: local_minima(&cfg.sweep_speeds_kmh, &line_amplitude_n),
        sweep_speeds_kmh: cfg.sweep_speeds_kmh.clone(),
        line_amplitude_n,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uniform grid over `[a, b]` with `n` points.
    fn grid(a: f64, b: f64, n: usize) -> Vec<f64> {
        (0..n)
            .map(|k| a + (b - a) * k as f64 / (n - 1) as f64)
            .collect()
    }

    #[test]
    fn rectangular_pulse_has_zeros_at_whole_periods() {
        // Analytical: undamped, A = κ|∫_{−L/2}^{L/2} e^{iκx} dx| = 2|sin(κL/2)|, zero where
        // f L / v = k.
        let (l, f) = (0.2, 75.0);
        let x = grid(-0.1, 0.1, 4001);
        let p = vec![1.0; x.len()];
        for v in [5.0, 12.0, 30.0] {
            let kappa = 2.0 * PI * f / v;
            let want = 2.0 * (kappa * l / 2.0).sin().abs();
            let got = ring_down_amplitude(&x, &p, f, 0.0, v);
            assert!((got - want).abs() < 1e-5, "v = {v}: {got} vs {want}");
        }
        let speeds = grid(5.0, 60.0, 5501); // km/h, 0.01 km/h apart
        let a: Vec<f64> = speeds
            .iter()
            .map(|v| ring_down_amplitude(&x, &p, f, 0.0, v / 3.6))
            .collect();
        let dips = local_minima(&speeds, &a);
        for (k, d) in (1..=5).zip(dips.iter().rev()) {
            let want = 3.6 * f * l / k as f64;
            assert!((d - want).abs() < 0.02, "dip {k}: {d} vs {want} km/h");
        }
    }

    #[test]
    fn half_sine_pulse_has_zeros_at_half_odd_periods() {
        // Analytical: the transform of sin(π(x + L/2)/L) on [−L/2, L/2] vanishes at
        // κL/2π = 3/2, 5/2, ..., so the dips are at v = f L / (k + ½).
        let (l, f) = (0.25, 64.0);
        let x = grid(-l / 2.0, l / 2.0, 4001);
        let p: Vec<f64> = x.iter().map(|x| (PI * (x + l / 2.0) / l).sin()).collect();
        let speeds = grid(10.0, 80.0, 7001);
        let pred = predict_dips(
            &EnvelopingProfile {
                cleat_x: x.clone(),
                dfy: p,
                fx: vec![0.0; x.len()],
                active: vec![0; x.len()],
                deflection: 0.0,
                support: [-l / 2.0, l / 2.0],
                node_span: [-l / 2.0, l / 2.0],
            },
            f,
            0.0,
            &speeds,
        )
        .unwrap();
        let want: Vec<f64> = (1..=3).map(|k| 3.6 * f * l / (k as f64 + 0.5)).collect();
        for w in &want {
            assert!(
                pred.dips_kmh.iter().any(|d| (d - w).abs() < 0.02),
                "no dip near {w} km/h in {:?}",
                pred.dips_kmh
            );
        }
    }

    #[test]
    fn damping_turns_the_zeros_into_minima_and_is_the_duhamel_integral() {
        // Second formulation: Duhamel's integral of the SDOF after the pulse, integrated in
        // time with the exact free response, evaluated as the ring-down amplitude at t = 0.
        let (l, f, zeta, v) = (0.2, 70.0, 0.03, 12.0);
        let x = grid(-l / 2.0, l / 2.0, 2001);
        let p: Vec<f64> = x.iter().map(|x| (PI * (x + l / 2.0) / l).sin()).collect();
        let a = ring_down_amplitude(&x, &p, f, zeta, v);
        // time domain: t = −x/v runs from −L/(2v) to L/(2v)
        let w = 2.0 * PI * f;
        let wd = w * (1.0 - zeta * zeta).sqrt();
        let n = 200_000;
        let (t0, t1) = (-l / (2.0 * v), l / (2.0 * v));
        let dt = (t1 - t0) / n as f64;
        // q(t) = ∫ ω²u(τ) e^{−ζω(t−τ)} sin(ω_d(t−τ))/ω_d dτ; after the pulse
        // q = e^{−ζωt}(C sin ω_d t − S cos ω_d t) with C, S the moments below
        let (mut c, mut s) = (0.0, 0.0);
        for k in 0..n {
            let tau = t0 + (k as f64 + 0.5) * dt;
            let u = (PI * (-v * tau + l / 2.0) / l).sin();
            let e = (zeta * w * tau).exp();
            c += w * w / wd * u * e * (wd * tau).cos() * dt;
            s += w * w / wd * u * e * (wd * tau).sin() * dt;
        }
        let want = c.hypot(s);
        assert!((a - want).abs() < 1e-5 * want, "{a} vs {want}");
        let undamped = ring_down_amplitude(&x, &p, f, 0.0, v);
        assert!(a > 0.0 && (a - undamped).abs() < 0.2 * undamped);
    }

    #[test]
    fn the_road_envelopes_a_longer_stretch_than_the_drum() {
        // Geometry: R_t = 0.52 m, d = 5 mm, h = 10 mm: road √(2·0.52·0.015) = 0.1249 m;
        // drum R_e = 0.52·1.25/1.77 = 0.3672 m: 0.1050 m.
        let mut g = GroundConfig::default();
        let drum = geometric_envelope_half_length(0.52, &g, 0.005);
        g.kind = GroundKind::Road;
        let road = geometric_envelope_half_length(0.52, &g, 0.005);
        assert!((road - 0.1249).abs() < 1e-4 && (drum - 0.1050).abs() < 1e-4);
    }
}
