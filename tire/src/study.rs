//! The tire studies' configuration pieces and results shared by `flowmbd-tire` and the Python
//! package (`flowmbd.tire`): the cleat test of §8.3 at one speed
//! ([`CleatStudyConfig`], [`CleatSummary`]) and the classification of [`TireError`]s into bad
//! input and numerical failures. Kept here so that both front ends accept the same keys, reject
//! the same fields with the same messages and return the same numbers.

use crate::error::TireError;
use crate::lines::{LineMode, SpindleComponent, line_modes};
use crate::loaded::held_nodes;
use crate::reduced::ReducedTire;
use crate::rig::{RigConfig, RigResult, Sample};
use crate::rolling::RollingTire;
use crate::rotating::RotatingOptions;
use crate::source::TireSource;
use crate::spectrum::{LINE_BAND_HZ, PEAK_BAND_HZ, Spectrum};
use crate::stats::StepStats;
use fe_model::FeError;
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// Whether a tire error is bad input: `Ok` with the offending field (paths from the root of a
/// study configuration whose tire table is `tire`: `tire.import.mass`, `tire.generator.…`,
/// `tire.reduced_file …`), `Err` with the error itself for a numerical failure.
pub fn tire_input_error(e: TireError) -> Result<InvalidField, TireError> {
    match e {
        TireError::Invalid { item, reason } => Ok(InvalidField::new(item, reason)),
        TireError::Import { field, reason } => {
            Ok(InvalidField::new(format!("tire.import.{field}"), reason))
        }
        TireError::ImportCheck { field, check } => Ok(InvalidField::new(
            format!("tire.import.{field}"),
            check.to_string(),
        )),
        TireError::File { path, reason } => Ok(InvalidField::new(
            format!("tire.reduced_file `{path}`"),
            reason,
        )),
        // configuration and matrix-file errors of the FE layer are bad input
        TireError::Fe(FeError::Invalid(f)) => Ok(f.within("tire.generator")),
        TireError::Fe(e @ FeError::InvalidParameter { .. }) => {
            Ok(InvalidField::new("tire.generator", e.to_string()))
        }
        TireError::Fe(
            e @ (FeError::Matrix { .. } | FeError::Io { .. } | FeError::Parse { .. }),
        ) => Ok(InvalidField::new("tire.import", e.to_string())),
        other => Err(other),
    }
}

/// [`tire_input_error`] for an error of the rig (cleat test): the rig's invalid items are named
/// by their configuration path (`rig.damping.mode1`, not `damping.mode1`).
pub fn rig_input_error(e: TireError) -> Result<InvalidField, TireError> {
    match e {
        TireError::Invalid { item, reason } => Ok(InvalidField::new(format!("rig.{item}"), reason)),
        other => tire_input_error(other),
    }
}

/// Configuration of the cleat test at one speed (`flowmbd-tire cleat`, `flowmbd.tire.cleat`).
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct CleatStudyConfig {
    /// The tire.
    pub tire: TireSource,
    /// The rig.
    pub rig: RigConfig,
    /// Write a VTK (`.vtu`) snapshot of the deformed contact patch every this many simulated
    /// seconds \[s\] (0 = none; the first after the first step) into `vtk/` (`flowmbd-tire` only).
    /// Simulated time, not steps, so that a finer `rig.rolling.time_step` does not multiply
    /// the files (default 5 ms: 140 frames of the default 0.7 s run).
    pub vtk_interval: f64,
    /// Write a VTK (`.vtu`) snapshot of the whole deforming tire (every ring at the
    /// reduction's visualisation stations, as closed polylines, with the displacement field)
    /// every this many simulated seconds \[s\] (0 = none) into `vtk/` (needs a reduced tire made
    /// with `tire.reduction.viz_stations > 0`; `flowmbd-tire` only; default 10 ms).
    pub vtk_tire_interval: f64,
    /// Cleat phases: run the test this many times with the cleat arriving `j/cleat_phases` of
    /// an impact step later (`j = 0, 1, …`; [`RigConfig::with_cleat_phase`]) and report the
    /// mean and spread of the dominant lines' rms over the runs ([`PhaseSpread`]; 1 = one
    /// run, no spread). The histories, spectra and VTK files are those of phase 0; the other
    /// phases run in parallel.
    pub cleat_phases: usize,
}

/// Most cleat phases of one study ([`CleatStudyConfig::cleat_phases`]).
pub const MAX_CLEAT_PHASES: usize = 64;

impl Default for CleatStudyConfig {
    fn default() -> Self {
        Self {
            tire: TireSource::default(),
            rig: RigConfig::default(),
            vtk_interval: 0.005,
            vtk_tire_interval: 0.01,
            cleat_phases: 1,
        }
    }
}

impl mbd_core::config::PartialRules for CleatStudyConfig {}

impl Validate for CleatStudyConfig {
    fn validate(&self) -> Result<(), InvalidField> {
        self.tire.validate_within("tire")?;
        check::non_negative("vtk_interval", self.vtk_interval, "s")?;
        check::non_negative("vtk_tire_interval", self.vtk_tire_interval, "s")?;
        check::size("cleat_phases", self.cleat_phases, 1, MAX_CLEAT_PHASES)?;
        validate_rig(&self.rig)
    }
}

/// The dominant lines' rms over the cleat's sampling phases (module docs of
/// [`RigConfig::with_cleat_phase`]: single runs scatter with the phase of the node hits on the
/// step grid; the mean over phases is the converging measure).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PhaseSpread {
    /// Runs (phase `j` arrives `j/phases` of an impact step later).
    pub phases: usize,
    /// Mean of `fy_band_rms_n` over the phases \[N\].
    pub fy_band_rms_mean_n: f64,
    /// Sample standard deviation of `fy_band_rms_n` over the phases \[N\].
    pub fy_band_rms_sd_n: f64,
    /// Mean of `fx_band_rms_n` over the phases \[N\].
    pub fx_band_rms_mean_n: f64,
    /// Sample standard deviation of `fx_band_rms_n` over the phases \[N\].
    pub fx_band_rms_sd_n: f64,
    /// `fy_band_rms_n` of each phase \[N\].
    pub fy_band_rms_n: Vec<f64>,
    /// `fx_band_rms_n` of each phase \[N\].
    pub fx_band_rms_n: Vec<f64>,
}

/// Mean and sample standard deviation (`n − 1`; 0 for one value).
fn mean_sd(x: &[f64]) -> (f64, f64) {
    let n = x.len().max(1) as f64;
    let mean = x.iter().sum::<f64>() / n;
    let ss = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>();
    (
        mean,
        if x.len() > 1 {
            (ss / (n - 1.0)).sqrt()
        } else {
            0.0
        },
    )
}

impl PhaseSpread {
    /// The spread of the summaries of phases `0, 1, …` (in that order).
    pub fn of(summaries: &[&CleatSummary]) -> Self {
        let fy: Vec<f64> = summaries.iter().map(|s| s.fy_band_rms_n).collect();
        let fx: Vec<f64> = summaries.iter().map(|s| s.fx_band_rms_n).collect();
        let (fy_m, fy_s) = mean_sd(&fy);
        let (fx_m, fx_s) = mean_sd(&fx);
        Self {
            phases: summaries.len(),
            fy_band_rms_mean_n: fy_m,
            fy_band_rms_sd_n: fy_s,
            fx_band_rms_mean_n: fx_m,
            fx_band_rms_sd_n: fx_s,
            fy_band_rms_n: fy,
            fx_band_rms_n: fx,
        }
    }
}

/// The spread of the cleat test of `rig` over `phases` sampling phases
/// ([`RigConfig::with_cleat_phase`] with fractions `j/phases`): `first` is the summary of the
/// caller's own run (phase 0, the one whose histories are written), phases `1 … phases − 1`
/// run in parallel (rayon), each summarised by [`summarize`]; `progress` receives the fraction
/// of these runs done. `phases = 1` runs nothing.
pub fn phase_spread(
    red: &ReducedTire, rig: &RigConfig, phases: usize, first: &CleatSummary,
    progress: &(dyn Fn(f64) + Sync),
) -> Result<PhaseSpread, TireError> {
    use rayon::prelude::*;
    let done = std::sync::atomic::AtomicUsize::new(0);
    let others = phases.saturating_sub(1);
    let rest = (1..phases)
        .into_par_iter()
        .map(|j| {
            let mut cfg = rig.with_cleat_phase(j as f64 / phases as f64);
            // the phases fill the cores themselves: no product worker per phase (the results
            // do not depend on it, `RollingConfig::threads`)
            cfg.rolling.threads = 1;
            let r = super::rig::run_cleat(red, &cfg, &mut |_| {})?;
            let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            progress(k as f64 / others as f64);
            Ok(summarize(&r))
        })
        .collect::<Result<Vec<CleatSummary>, TireError>>()?;
    let all: Vec<&CleatSummary> = std::iter::once(first).chain(&rest).collect();
    Ok(PhaseSpread::of(&all))
}

/// Validate rig settings: the library's checks ([`RigConfig`]'s `Validate` and
/// [`RigConfig::validate_spectrum`], what the study's spectra need), fields named by their
/// configuration path (`rig.…`).
pub fn validate_rig(rig: &RigConfig) -> Result<(), InvalidField> {
    rig.validate_within("rig")?;
    rig.validate_spectrum().map_err(|e| e.within("rig"))
}

/// Summary of a cleat test (the `summary.json` of `flowmbd-tire cleat`; the JSON keys
/// first).
#[derive(Debug, Serialize)]
pub struct CleatSummary {
    /// Speed \[km/h\].
    pub speed_kmh: f64,
    /// Wheel–tire DOF.
    pub dof: usize,
    /// The model stepped: the mirror half model of symmetric motion (the same solution at
    /// about a quarter of the work per step) or the full model and why
    /// ([`super::RollingConfig::symmetry`]).
    pub symmetry: String,
    /// Dominant frequency of the vertical force \[Hz\]: the largest line of its spectrum in
    /// [`PEAK_BAND_HZ`], interpolated between the bins ([`Spectrum::interpolated_peak`]).
    pub fy_peak_hz: f64,
    /// Dominant frequency of the longitudinal force \[Hz\], likewise.
    pub fx_peak_hz: f64,
    /// Frequency resolution of the record after the hit \[Hz\]: the spectra's bin spacing
    /// `1/(N Δt)` (3.33 Hz for 0.3 s), from which `fy_peak_hz` and `fx_peak_hz` are
    /// interpolated.
    pub peak_resolution_hz: f64,
    /// RMS of the vertical force fluctuation after the hit \[N\].
    pub fy_rms: f64,
    /// RMS of the longitudinal force fluctuation after the hit \[N\].
    pub fx_rms: f64,
    /// RMS of the vertical force's dominant line \[N\]: [`Spectrum::band_rms`] over
    /// `fy_peak_hz ± LINE_BAND_HZ` (10 Hz; [`super::spectrum::LINE_BAND_HZ`]), the measure by
    /// which a time step's accuracy is judged against the converged step (BENCHMARKS.md).
    pub fy_band_rms_n: f64,
    /// RMS of the longitudinal force's dominant line \[N\]: over `fx_peak_hz ± LINE_BAND_HZ`.
    pub fx_band_rms_n: f64,
    /// Wall time of the time integration \[s\].
    pub wall_time_s: f64,
    /// Wall time per simulated second.
    pub wall_per_simulated_s: f64,
    /// CPU time of the integration per simulated second (independent of the machine load).
    pub cpu_per_simulated_s: Option<f64>,
    /// Preload deflection \[m\].
    pub preload_deflection_m: f64,
    /// Mean vertical spindle force of the steadily rolling tire before the cleat \[N\].
    pub fy_mean_before_n: f64,
    /// Mean longitudinal spindle force before the cleat (rolling resistance) \[N\].
    pub fx_mean_before_n: f64,
    /// Mean moments of the contact forces about the wheel centre before the cleat, ISO 8855
    /// wheel frame (x forward, y left, z up): overturning `M_x` \[N·m\].
    pub mx_mean_before_n_m: f64,
    /// Mean `M_y` about the spin axis before the cleat (rolling-resistance moment) \[N·m\].
    pub my_mean_before_n_m: f64,
    /// Mean aligning moment `M_z` before the cleat \[N·m\].
    pub mz_mean_before_n_m: f64,
    /// Preload \[N\].
    pub load_n: f64,
    /// Camber angle γ \[deg\] (`rig.wheel.camber_deg`).
    pub camber_deg: f64,
    /// The frame of the forces and moments (`forces.csv`, the means before the cleat): the ISO
    /// 8855 wheel frame, or with camber the W-axis orientation (z along the road normal);
    /// moments about the wheel centre.
    pub load_frame: String,
    /// Rayleigh α \[1/s\], β \[s\].
    pub rayleigh: [f64; 2],
    /// Time steps and refactorisations of the iteration matrix.
    pub steps: usize,
    /// Refactorisations (spin-rate drift).
    pub refactors: usize,
    /// Work counters of the integration.
    pub stats: StepStats,
    /// Frequency of the loaded tire's vertical in-plane mode \[Hz\] (largest effective vertical
    /// spindle mass, wheel fixed, preloaded patch held; [`super::loaded`]): the reference for
    /// `fy_peak_hz`.
    pub loaded_vertical_mode_hz: Option<f64>,
    /// Frequency of the loaded tire's mode with the largest effective longitudinal spindle
    /// mass \[Hz\].
    pub loaded_longitudinal_mode_hz: Option<f64>,
    /// The mode that carries the `F_x` line (`fx_peak_hz`): the complex mode of the loaded
    /// tire rolling at the test speed (rolling preload's patch held, rig damping;
    /// [`super::lines`]) with the largest participation in the longitudinal spindle force's
    /// response to longitudinal ground motion at the line frequency (`cleat` only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fx_line_mode: Option<LineMode>,
    /// The mode that carries the `F_y` line (`fy_peak_hz`), likewise for vertical motion.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fy_line_mode: Option<LineMode>,
    /// The dominant lines over the cleat's sampling phases (`cleat_phases` > 1 only): mean
    /// and spread of `fy_band_rms_n`, `fx_band_rms_n` ([`PhaseSpread`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub phases: Option<PhaseSpread>,
    /// What the numbers mean ([`CLEAT_MEANING`]; empty, and not written, in the runs of a
    /// speed sweep).
    #[serde(skip_serializing_if = "String::is_empty")]
    pub meaning: String,
}

/// The cleat study's "what the numbers mean" paragraph (`meaning` in `summary.json`).
pub const CLEAT_MEANING: &str = "The cleat test of Ribaric 8.3: the preloaded tire rolls at speed_kmh over a \
         semicircular cleat on the drum (or road; or over the configured obstacles and height-grid \
         road, rig.ground) and the spindle forces are recorded (in load_frame: with a camber \
         angle the W-axis orientation, z along the road normal). \
         fy_peak_hz and fx_peak_hz are the frequencies of the largest spectral peaks of the \
         vertical and longitudinal force after the hit (sought in 10-500 Hz, interpolated \
         between the bins of the record's spectrum, whose spacing is peak_resolution_hz) and \
         fy_band_rms_n, fx_band_rms_n the rms of these lines (spectrum within 10 Hz of the \
         peak) [N]: the loaded tire's vertical and longitudinal modes rolling at that speed \
         (loaded_vertical_mode_hz, fx_line_mode and fy_line_mode name the modes that carry \
         them); fy_rms and fx_rms are the force fluctuations [N]; fy_mean_before_n equals the \
         load when the rolling tire is in equilibrium and fx_mean_before_n is the rolling \
         resistance [N]; preload_deflection_m is the static deflection. wall_ and \
         cpu_per_simulated_s say how fast the model runs (1 = real time); symmetry says \
         whether the mirror half model of the symmetric motion ran (the same solution at a \
         fraction of the cost) or the full model and why. The line amplitudes \
         of one run carry a scatter of about 3 % (standard deviation) from the phase of the \
         cleat's hits on the discrete contact nodes relative to the time steps; with \
         cleat_phases > 1 the test is repeated at shifted phases and phases gives the mean and \
         spread (the converging measure).";

/// The loaded mode at the rolling speed that carries the `component` line at `hz`
/// ([`line_modes`]: largest participation); `None` when that solve fails (the run's results do
/// not depend on it).
pub fn line_mode(
    red: &ReducedTire, r: &RigResult, component: SpindleComponent, hz: f64,
) -> Option<LineMode> {
    let opt = RotatingOptions {
        spin: r.samples.first()?.spin,
        alpha: r.rayleigh.alpha,
        beta: r.rayleigh.beta,
        max_hz: 1e3,
    };
    line_modes(red, &held_nodes(&r.preload), &opt, component, hz)
        .ok()?
        .into_iter()
        .next()
}

/// The frame of a run's forces and moments at the camber angle `camber_deg` \[deg\]
/// ([`crate::rolling::WheelLoads`]).
pub fn load_frame(camber_deg: f64) -> String {
    if camber_deg == 0.0 {
        "ISO 8855 wheel frame (x forward, y left, z up), moments about the wheel centre".into()
    } else {
        format!(
            "W-axis orientation at camber {} deg (x forward, z along the road normal, y in the \
             road plane), moments about the wheel centre",
            check::show(camber_deg)
        )
    }
}

/// Summary of a rig result (without the line modes: [`cleat_summary`] adds them).
pub fn summarize(r: &RigResult) -> CleatSummary {
    let band = PEAK_BAND_HZ;
    let (sx, sy) = r.spectra();
    let (rx, ry) = r.rms();
    // the steadily rolling tire: the last 50 ms before the first node touches the cleat (the
    // cleat enters the patch (L/2 + r)/v before it reaches the patch centre at t = 0)
    let before = r.mean_before_cleat(0.05).unwrap_or((0.0, 0.0));
    let moments = r.mean_moments_before_cleat(0.05).unwrap_or([0.0; 3]);
    let fy_peak_hz = sy.interpolated_peak(band[0], band[1]).map_or(0.0, |p| p.0);
    let fx_peak_hz = sx.interpolated_peak(band[0], band[1]).map_or(0.0, |p| p.0);
    // the line's rms over the band about the peak bin (the band's bins are the same as before
    // the peak was interpolated)
    let line = |s: &Spectrum| {
        let f = s.peak(band[0], band[1]).map_or(0.0, |p| p.0);
        s.band_rms(f - LINE_BAND_HZ, f + LINE_BAND_HZ)
    };
    CleatSummary {
        speed_kmh: r.speed_kmh,
        dof: r.dof,
        symmetry: r.symmetry.clone(),
        fy_peak_hz,
        fx_peak_hz,
        peak_resolution_hz: sy.resolution_hz(),
        fy_rms: ry,
        fx_rms: rx,
        fy_band_rms_n: line(&sy),
        fx_band_rms_n: line(&sx),
        wall_time_s: r.wall_time_s,
        wall_per_simulated_s: r.wall_time_s / r.simulated_s.max(1e-12),
        cpu_per_simulated_s: r.cpu_time_s.map(|c| c / r.simulated_s.max(1e-12)),
        preload_deflection_m: r.preload.deflection,
        fy_mean_before_n: before.1,
        fx_mean_before_n: before.0,
        mx_mean_before_n_m: moments[0],
        my_mean_before_n_m: moments[1],
        mz_mean_before_n_m: moments[2],
        load_n: r.load,
        camber_deg: r.camber_deg,
        load_frame: load_frame(r.camber_deg),
        rayleigh: [r.rayleigh.alpha, r.rayleigh.beta],
        steps: r.samples.len(),
        refactors: r.refactors,
        stats: r.stats,
        loaded_vertical_mode_hz: r.loaded_vertical_mode.as_ref().map(|m| m.hz),
        loaded_longitudinal_mode_hz: r.loaded_longitudinal_mode.as_ref().map(|m| m.hz),
        fx_line_mode: None,
        fy_line_mode: None,
        phases: None,
        meaning: String::new(),
    }
}

/// The cleat study's summary of a rig result: [`summarize`] with the modes that carry the
/// `F_x` and `F_y` lines ([`line_mode`]) and its [`CLEAT_MEANING`].
pub fn cleat_summary(red: &ReducedTire, r: &RigResult) -> CleatSummary {
    let mut s = summarize(r);
    s.meaning = CLEAT_MEANING.to_string();
    s.fx_line_mode = line_mode(red, r, SpindleComponent::Longitudinal, s.fx_peak_hz);
    s.fy_line_mode = line_mode(red, r, SpindleComponent::Vertical, s.fy_peak_hz);
    s
}

/// Columns of the cleat test's force history (`forces.csv` of `flowmbd-tire cleat`, the
/// `forces` of `flowmbd.tire.cleat`): time from the cleat hit \[s\], the spindle forces
/// `F_x`, `F_y`, `F_lateral` \[N\], the spin rate \[rad/s\], the active contact nodes and
/// their total normal force \[N\], and the moments `M_x`, `M_y`, `M_z` of the contact forces
/// about the wheel centre \[N·m\] in the ISO 8855 wheel frame (x forward, y left, z up;
/// [`crate::rolling::WheelLoads`]; with a camber angle in the W-axis orientation, z along the
/// road normal: [`CleatSummary::load_frame`]). (The force columns keep their names: `fy_N` is the
/// vertical force, ISO `F_z`, and `f_lateral_N` the lateral one, ISO `F_y`.)
pub const FORCE_COLUMNS: [&str; 10] = [
    "t_s",
    "fx_N",
    "fy_N",
    "f_lateral_N",
    "spin_rad_per_s",
    "active_nodes_count",
    "normal_sum_N",
    "mx_N_m",
    "my_N_m",
    "mz_N_m",
];

/// Columns of the cleat test's amplitude spectra after the hit (`spectra.csv` of
/// `flowmbd-tire cleat`, the `spectra` of `flowmbd.tire.cleat`): frequency \[Hz\] and the
/// amplitudes of `F_x` and `F_y` \[N\] ([`RigResult::spectra`]).
pub const SPECTRUM_COLUMNS: [&str; 3] = ["f_Hz", "fx_amp_N", "fy_amp_N"];

/// The [`SPECTRUM_COLUMNS`] rows of the spectra `(sx, sy)` of `F_x` and `F_y` of a rig result
/// ([`RigResult::spectra`]).
pub fn spectrum_rows(sx: &Spectrum, sy: &Spectrum) -> impl Iterator<Item = [f64; 3]> {
    (0..sx.freq_hz.len()).map(|k| [sx.freq_hz[k], sx.amplitude[k], sy.amplitude[k]])
}

/// The [`FORCE_COLUMNS`] row of the rolling tire after a step (a run's observer; `settle` is
/// the rig's `settle_time`, so that the cleat hits at `t = 0`): the same numbers as the step's
/// [`Sample`].
pub fn force_row(sim: &RollingTire, settle: f64) -> [f64; 10] {
    let f = sim.wheel_loads();
    [
        sim.state.t - settle,
        f.fx,
        f.fz,
        f.fy,
        sim.state.theta_d,
        sim.active_count() as f64,
        sim.total_normal_force(),
        f.mx,
        f.my,
        f.mz,
    ]
}

/// The [`FORCE_COLUMNS`] row of a recorded sample.
pub fn sample_row(s: &Sample) -> [f64; 10] {
    [
        s.t,
        s.fx,
        s.fy,
        s.fz,
        s.spin,
        s.active as f64,
        s.normal_sum,
        s.mx,
        s.my,
        s.mz,
    ]
}
