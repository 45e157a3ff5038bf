//! The pluck transient of the travelling string (`flowmbd-string simulate`,
//! `flowmbd.string.simulate`; Ribaric Fig. 4-6 right): the flowing-material model (4.20)
//! plucked into a triangle and integrated in time (RK4), the amplitude spectra of its modal
//! coordinates and their peaks (the axial motion couples the modes, so each coordinate
//! vibrates at several natural frequencies). Configuration, checks, the run and the tables of
//! `modal_history.csv` and `spectra.csv` live here so that the CLI and the Python package
//! return the same numbers.

use crate::error::{FlowError, invalid};
use crate::spectrum::{Spectrum, amplitude_spectrum};
use crate::string_study::{
    Regime, check_nodes_modes, check_number, check_scales, check_steps, check_string,
    flowing_model, flowing_spectrum,
};
use crate::travelling::{TimeHistory, simulate_rk4, triangular_pluck};
use crate::{DerivativeMethod, StringConfig};
use mbd_core::MbdError;
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};
use std::ops::ControlFlow;

/// Triangular pluck (initial deflection, zero velocity).
#[derive(Debug, Clone, Copy, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Pluck {
    /// Position of the peak \[m\].
    pub x: f64,
    /// Peak deflection \[m\].
    pub amplitude: f64,
}

/// Configuration (defaults: notes §2.1 time-domain check: v = 20 m/s, n = 99, 10 modes, pluck
/// 1 mm at 0.3 m, 4 s).
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct SimulateConfig {
    /// String parameters.
    pub string: StringConfig,
    /// Axial speed \[m/s\].
    pub speed: f64,
    /// Interior FE nodes.
    pub nodes: usize,
    /// Retained modes.
    pub modes: usize,
    /// Initial pluck.
    pub pluck: Pluck,
    /// Duration \[s\].
    pub duration: f64,
    /// RK4 step \[s\].
    pub step: f64,
    /// Keep every n-th step (sampling period = step · sample_every).
    pub sample_every: usize,
    /// Spectral peaks below this fraction of the largest amplitude are ignored \[-\].
    pub peak_threshold: f64,
    /// Mode-shape derivative operator.
    pub derivative: DerivativeMethod,
}

impl Default for SimulateConfig {
    fn default() -> Self {
        Self {
            string: StringConfig::default(),
            speed: 20.0,
            nodes: 99,
            modes: 10,
            pluck: Pluck {
                x: 0.3,
                amplitude: 1e-3,
            },
            duration: 4.0,
            step: 5e-5,
            sample_every: 20,
            peak_threshold: 0.05,
            derivative: DerivativeMethod::default(),
        }
    }
}

/// Most values of the recorded history, `samples × modes` (positions and velocities are kept
/// for every sample: 2·10⁷ values, 320 MB; the default run records 4·10⁴).
pub const MAX_HISTORY_VALUES: f64 = 1e7;

/// Most RK4 work, `steps × modes²` (one modal force evaluation is `modes²` multiply-adds, four
/// per step: 10¹¹ is a few minutes; the default run is 8·10⁶).
pub const MAX_RK4_WORK: f64 = 1e11;

/// RK4's stability limit on the imaginary axis, `|hλ| ≤ 2√2`.
pub const RK4_STABILITY_LIMIT: f64 = 2.0 * std::f64::consts::SQRT_2;

impl mbd_core::config::PartialRules for SimulateConfig {}

impl Validate for SimulateConfig {
    /// The string, a subcritical speed, nodes and modes, the number scales, the pluck inside the
    /// string and small against it, positive duration and step, at least 8 samples and at most
    /// [`MAX_HISTORY_VALUES`] recorded values and [`MAX_RK4_WORK`] of RK4 work.
    fn validate(&self) -> Result<(), InvalidField> {
        check_string(&self.string, "string")?;
        check_number("speed", self.speed, false)?;
        check_nodes_modes(self.nodes, self.modes)?;
        check_scales(&self.string, "string", "speed", self.speed, self.nodes)?;
        // issue 35: above the critical speed the fixed–fixed string is no initial-value problem
        // (both waves travel downstream) and every truncation grows spuriously (issue 34,
        // flowing::string_study module docs); at it the stiffness vanishes
        let crit = self.string.wave_speed();
        if Regime::of(&self.string, self.speed) != Regime::Subcritical {
            return Err(InvalidField::new(
                "speed",
                format!(
                    "|speed| = {} m/s is at or above the critical speed c = √(T/ρA) = {crit:.4} \
                     m/s of this string (tension {} N): the pluck transient of the string \
                     between fixed guides exists only below c (above it both waves travel \
                     downstream and the truncated model grows without bound); `modes` gives \
                     the frequencies n|c² − v²|/(2cL) at any speed",
                    mbd_core::validate::check::show(self.speed.abs()),
                    mbd_core::validate::check::show(self.string.tension)
                ),
            ));
        }
        if !(self.pluck.x > 0.0 && self.pluck.x < self.string.length) {
            return Err(InvalidField::new(
                "pluck.x",
                format!("must lie strictly inside (0, length), got {}", self.pluck.x),
            ));
        }
        check_number("pluck.amplitude", self.pluck.amplitude, false)?;
        if self.pluck.amplitude.abs() > self.string.length {
            return Err(InvalidField::new(
                "pluck.amplitude",
                format!(
                    "|{}| m exceeds the string's length {} m (the linear string model needs a \
                     deflection small against its length)",
                    mbd_core::validate::check::show(self.pluck.amplitude),
                    mbd_core::validate::check::show(self.string.length)
                ),
            ));
        }
        if !(self.duration.is_finite() && self.duration > 0.0) {
            return Err(InvalidField::new("duration", "must be positive"));
        }
        if !(self.step.is_finite() && self.step > 0.0 && self.step < self.duration) {
            return Err(InvalidField::new(
                "step",
                "must be positive and below the duration",
            ));
        }
        if self.sample_every == 0 {
            return Err(InvalidField::new("sample_every", "must be at least 1"));
        }
        if !(self.peak_threshold > 0.0 && self.peak_threshold < 1.0) {
            return Err(InvalidField::new("peak_threshold", "must lie in (0, 1)"));
        }
        // RK4 steps of the run (each a few matrix-vector products of the modal size)
        check_steps("duration", self.duration, self.step, 1e8, "RK4 steps")?;
        let period = self.step * self.sample_every as f64;
        if (self.duration / period) < 8.0 {
            return Err(InvalidField::new("duration", "gives fewer than 8 samples"));
        }
        let k = self.modes as f64;
        check_steps(
            "duration",
            self.duration * k,
            period,
            MAX_HISTORY_VALUES,
            "recorded values (samples × modes)",
        )?;
        check_steps(
            "duration",
            self.duration * k * k,
            self.step,
            MAX_RK4_WORK,
            "units of RK4 work (steps × modes²)",
        )?;
        Ok(())
    }
}

/// Spectral peaks of one modal coordinate.
#[derive(Debug, Clone, Serialize)]
pub struct ModePeaks {
    /// Mode number (1-based).
    pub mode: usize,
    /// Peak frequencies \[Hz\], interpolated between the bins
    /// (`flowing::spectrum::Spectrum::peaks`).
    pub peaks_hz: Vec<f64>,
}

/// Summary of the pluck transient (`summary.json`).
#[derive(Debug, Clone, Serialize)]
pub struct SimulateSummary {
    /// Axial speed \[m/s\].
    pub speed: f64,
    /// Damped frequencies of the model (eigenvalues) \[Hz\].
    pub model_hz: Vec<f64>,
    /// Exact moving-string frequencies n(c²−v²)/(2cL) \[Hz\].
    pub exact_hz: Vec<f64>,
    /// Frequency resolution of the spectra \[Hz\].
    pub resolution_hz: f64,
    /// Peaks of every modal coordinate.
    pub peaks: Vec<ModePeaks>,
    /// Relative drift of the conserved energy-like invariant H over the run.
    pub hamiltonian_drift: f64,
    /// What the numbers mean ([`SIMULATE_MEANING`]).
    pub meaning: String,
}

/// The transient's "what the numbers mean" paragraph (`meaning` in `summary.json`).
pub const SIMULATE_MEANING: &str = "The travelling string (Ribaric Fig. 4-6 right) plucked into a triangle and let go: \
         the flowing-material model (4.20) integrated in time (RK4). history.csv holds the \
         modal coordinates z_i [sqrt(kg) m, mass-normalised modes], spectra.csv their \
         amplitude spectra. model_hz are the model's natural frequencies (eigenvalues) and \
         exact_hz the travelling string's n(c^2 - v^2)/(2cL) [Hz]; peaks lists the spectral \
         peaks of every coordinate: because the axial motion couples the modes (Coriolis \
         term), each coordinate vibrates at several of these frequencies, not one. \
         resolution_hz is the spectra's bin width (the peaks are interpolated between the \
         bins); hamiltonian_drift is the relative drift of \
         the conserved energy-like invariant H over the run, a check of the time integration \
         (near 0).";

/// The pluck transient: the summary, the sampled modal history and each coordinate's spectrum.
#[derive(Debug)]
pub struct SimulateResult {
    /// The summary.
    pub summary: SimulateSummary,
    /// Sample times \[s\] and modal coordinates `z` \[√kg·m\] (velocities too).
    pub history: TimeHistory,
    /// Amplitude spectrum of each modal coordinate (common frequencies).
    pub spectra: Vec<Spectrum>,
}

/// A failure of the run that is no bad input (as an [`MbdError::Model`] at time `t`).
fn failed(t: f64, message: String) -> FlowError {
    FlowError::Mbd(MbdError::Model { t, message })
}

/// Run the pluck transient: the flowing model frozen at `c.speed`, refused when it grows below
/// the critical speed (a non-FE-consistent derivative operator, notes STR-6) or when `c.step`
/// is beyond RK4's stability limit `2√2/|λ|max`; the triangular pluck projected on the modes
/// and integrated by RK4 ([`simulate_rk4`]; `tick` sees the time at every kept sample and may
/// stop the run); the Hann-windowed spectra of the modal coordinates with their peaks above
/// `c.peak_threshold` of the largest; the drift of the energy-like invariant `H`.
pub fn string_simulate(
    c: &SimulateConfig, tick: &mut dyn FnMut(f64) -> ControlFlow<()>,
) -> Result<SimulateResult, FlowError> {
    let (mesh, sys) = flowing_model(c.string, c.nodes, c.modes, c.derivative, c.speed)?;
    let spectrum = flowing_spectrum(&sys, c.speed)?;
    // below c the FE-consistent model cannot grow (its energy is positive definite);
    // another derivative operator can (notes STR-6), and then its response is an artefact
    if let Some(g) = spectrum.growth.first() {
        return Err(invalid(
            "derivative",
            format!(
                "the model with this derivative operator grows at {:.4e} 1/s ({:.4} Hz) \
                 although the string is below its critical speed: the operator is not \
                 FE-consistent (Ribaric App. A, notes STR-6) and the response would grow \
                 without bound; use Consistent or fewer modes",
                g.rate_per_s, g.frequency_hz
            ),
        ));
    }
    let h_max = RK4_STABILITY_LIMIT / spectrum.max_modulus;
    if c.step > h_max {
        return Err(invalid(
            "step",
            format!(
                "{} s is beyond RK4's stability limit 2√2/|λ|max = {} s for this model \
                 (|λ|max = {:.4e} 1/s with {} modes)",
                mbd_core::validate::check::show(c.step),
                mbd_core::validate::check::show(h_max),
                spectrum.max_modulus,
                c.modes
            ),
        ));
    }
    let model_hz = spectrum.neutral_hz;
    let u0 = triangular_pluck(
        mesh.grid.positions(),
        0.0,
        c.string.length,
        c.pluck.x,
        c.pluck.amplitude,
    )?;
    let z0 = sys.project(&u0)?;
    let k = c.modes;
    let hist = simulate_rk4(
        &sys,
        z0.clone(),
        vec![0.0; k],
        c.duration,
        c.step,
        c.sample_every,
        tick,
    )?;
    if hist.t.len() < 8 {
        // interrupted before the spectra have samples to work on
        return Err(failed(
            hist.t.last().copied().unwrap_or(0.0),
            format!("only {} samples computed", hist.t.len()),
        ));
    }
    if let Some((t, _)) = hist
        .t
        .iter()
        .zip(hist.q.iter().zip(&hist.v))
        .find(|(_, (q, v))| q.iter().chain(v.iter()).any(|x| !x.is_finite()))
    {
        return Err(failed(*t, "the modal response is not finite".to_string()));
    }
    let dt = c.step * c.sample_every as f64;
    let mut spectra = Vec::new();
    let mut peaks = Vec::new();
    for m in 0..k {
        let sig: Vec<f64> = hist.q.iter().map(|q| q[m]).collect();
        let s = amplitude_spectrum(&sig, dt, 1)?;
        peaks.push(ModePeaks {
            mode: m + 1,
            peaks_hz: s.peaks(c.peak_threshold).into_iter().map(|p| p.0).collect(),
        });
        spectra.push(s);
    }
    let h0 = sys.hamiltonian(&z0, &vec![0.0; k], c.speed);
    let last = hist.q.len() - 1;
    let h1 = sys.hamiltonian(&hist.q[last], &hist.v[last], c.speed);
    let drift = if h0 != 0.0 { (h1 - h0) / h0 } else { 0.0 };
    if !drift.is_finite() {
        return Err(failed(
            hist.t[last],
            format!("the energy-like invariant H is not finite (H(0) = {h0:e}, H(end) = {h1:e})"),
        ));
    }
    let summary = SimulateSummary {
        speed: c.speed,
        exact_hz: (1..=k)
            .map(|n| c.string.exact_moving_frequency_hz(n, c.speed))
            .collect(),
        model_hz,
        resolution_hz: spectra[0].frequencies.get(1).copied().unwrap_or(f64::NAN),
        peaks,
        hamiltonian_drift: drift,
        meaning: SIMULATE_MEANING.to_string(),
    };
    Ok(SimulateResult {
        summary,
        history: hist,
        spectra,
    })
}

/// Header of `modal_history.csv`: `t_s`, then `z<i>_sqrt_kg_m` for the `modes` coordinates.
pub fn history_header(modes: usize) -> Vec<String> {
    let mut header = vec!["t_s".to_string()];
    header.extend((1..=modes).map(|i| format!("z{i}_sqrt_kg_m")));
    header
}

/// Rows of `modal_history.csv`: time \[s\], modal coordinates \[√kg·m\].
pub fn history_rows(h: &TimeHistory) -> Vec<Vec<f64>> {
    h.t.iter()
        .zip(&h.q)
        .map(|(t, q)| std::iter::once(*t).chain(q.iter().copied()).collect())
        .collect()
}

/// Header of `spectra.csv`: `f_Hz`, then `amp_z<i>_sqrt_kg_m` for the `modes` coordinates.
pub fn spectra_header(modes: usize) -> Vec<String> {
    let mut header = vec!["f_Hz".to_string()];
    header.extend((1..=modes).map(|i| format!("amp_z{i}_sqrt_kg_m")));
    header
}

/// Rows of `spectra.csv`: frequency \[Hz\], amplitude of each coordinate \[√kg·m\].
pub fn spectra_rows(spectra: &[Spectrum]) -> Vec<Vec<f64>> {
    let nf = spectra.first().map_or(0, |s| s.frequencies.len());
    (0..nf)
        .map(|i| {
            std::iter::once(spectra[0].frequencies[i])
                .chain(spectra.iter().map(|s| s.amplitudes[i]))
                .collect()
        })
        .collect()
}
