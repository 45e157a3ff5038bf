//! The speed sweep of the travelling string (`flowmbd-string sweep`, `flowmbd.string.sweep`;
//! Ribaric ch. 4): the neutral frequencies of the Galerkin model (4.29) and of the
//! flowing-material model (4.20) against the axial speed from 0 to past the critical speed,
//! with the exact `f_n = n|c² − v²|/(2cL)` (Wickert & Mote 1990) and every growing eigenvalue
//! classified by a second discretisation ([`classify_growth`], see [`crate::string_study`]).
//! Configuration, checks, the sweep and the rows of `sweep.csv` live here so that the CLI and
//! the Python package return the same numbers.

use crate::error::FlowError;
use crate::string_study::{
    MAX_GALERKIN_TERMS, Regime, check_mesh, check_nodes_modes, check_scales, check_string,
    check_terms, classify_growth, flowing_model, flowing_spectrum, galerkin_spectrum,
};
use crate::{DerivativeMethod, StringConfig};
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};
use std::ops::ControlFlow;

/// Configuration of the speed sweep (`flowmbd-string sweep`, `flowmbd.string.sweep`).
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct SweepConfig {
    /// String parameters.
    pub string: StringConfig,
    /// Interior FE nodes.
    pub nodes: usize,
    /// Retained modes of the flowing-material model.
    pub modes: usize,
    /// Sine terms of the Galerkin model.
    pub galerkin_terms: usize,
    /// Highest speed as a multiple of the critical speed \[-\].
    pub max_speed_ratio: f64,
    /// Number of speeds (the default avoids hitting v = c exactly, where the stiffness vanishes
    /// and only the gyroscopic eigenvalues remain).
    pub steps: usize,
    /// Frequencies tracked per model.
    pub tracked: usize,
    /// Mode-shape derivative operator.
    pub derivative: DerivativeMethod,
}

impl Default for SweepConfig {
    fn default() -> Self {
        Self {
            string: StringConfig::default(),
            nodes: 99,
            modes: 20,
            galerkin_terms: 40,
            max_speed_ratio: 1.2,
            steps: 50,
            tracked: 5,
            derivative: DerivativeMethod::default(),
        }
    }
}

/// Most eigenvalue work of one sweep, in units of `n³` of the dense non-symmetric eigen solver
/// (about 25 flops each): `steps × 9((2·galerkin_terms)³ + (2·modes)³)`, the models at every
/// speed and, where they grow, their second discretisations (twice the size). 10¹² is about an
/// hour; the default sweep takes 2.6·10⁸.
pub const MAX_SWEEP_EIGEN_WORK: f64 = 1e12;

/// Highest `max_speed_ratio` (the supercritical branch up to 100 c).
pub const MAX_SPEED_RATIO: f64 = 100.0;

impl mbd_core::config::PartialRules for SweepConfig {}

impl Validate for SweepConfig {
    /// The string, nodes and modes, `max_speed_ratio` in (1, [`MAX_SPEED_RATIO`]], 2 to 100 000
    /// steps, 1 to [`MAX_GALERKIN_TERMS`] Galerkin terms, `tracked` within the modes and terms,
    /// the number scales and at most [`MAX_SWEEP_EIGEN_WORK`] of eigen work.
    fn validate(&self) -> Result<(), InvalidField> {
        check_string(&self.string, "string")?;
        check_nodes_modes(self.nodes, self.modes)?;
        if !(self.max_speed_ratio.is_finite()
            && self.max_speed_ratio > 1.0
            && self.max_speed_ratio <= MAX_SPEED_RATIO)
        {
            return Err(InvalidField::new(
                "max_speed_ratio",
                format!(
                    "must exceed 1 (past the critical speed) and be at most {MAX_SPEED_RATIO}, \
                     got {}",
                    mbd_core::validate::check::show(self.max_speed_ratio)
                ),
            ));
        }
        // one Galerkin and one flowing eigen problem per speed
        mbd_core::validate::check::size("steps", self.steps, 2, 100_000)?;
        mbd_core::validate::check::size(
            "galerkin_terms",
            self.galerkin_terms,
            1,
            MAX_GALERKIN_TERMS,
        )?;
        if self.tracked == 0 || self.tracked > self.modes {
            return Err(InvalidField::new(
                "tracked",
                format!("must be between 1 and modes = {}", self.modes),
            ));
        }
        if self.galerkin_terms < self.tracked {
            return Err(InvalidField::new(
                "galerkin_terms",
                "must be at least `tracked`",
            ));
        }
        check_scales(
            &self.string,
            "string",
            "max_speed_ratio",
            self.max_speed_ratio * self.string.wave_speed(),
            2 * self.nodes.max(self.galerkin_terms) + 1,
        )?;
        let cube = |n: usize| (2.0 * n as f64).powi(3);
        let work = self.steps as f64 * 9.0 * (cube(self.galerkin_terms) + cube(self.modes));
        let max = mbd_core::validate::limits::ceiling(MAX_SWEEP_EIGEN_WORK);
        if work > max {
            return Err(InvalidField::new(
                "steps",
                format!(
                    "{} speeds of {} Galerkin terms and {} modes are {work:.3e} units of eigen \
                     work (steps × 9((2·galerkin_terms)³ + (2·modes)³)), more than the {max:e} a \
                     sweep may take{}",
                    self.steps,
                    self.galerkin_terms,
                    self.modes,
                    mbd_core::validate::limits::raise_hint()
                ),
            ));
        }
        Ok(())
    }
}

/// Summary of the speed sweep (`summary.json`).
#[derive(Debug, Clone, Serialize)]
pub struct SweepSummary {
    /// Critical speed \[m/s\].
    pub critical_speed: f64,
    /// Lowest swept speed at which the string is unstable \[m/s\]: the critical speed when a
    /// swept speed hits it (divergence), or growth of a model that its second discretisation
    /// reproduces (`None`: stable at every swept speed).
    pub unstable_from: Option<f64>,
    /// Lowest swept speed at which the truncated Galerkin model has truncation-dependent growth
    /// \[m/s\] (an artefact of the truncation above c, not an instability of the string).
    pub analytical_truncation_growth_from: Option<f64>,
    /// Likewise for the flowing-material model \[m/s\].
    pub flowing_truncation_growth_from: Option<f64>,
    /// Largest relative deviation of the flowing from the exact frequencies below 0.9 c.
    pub max_rel_error_below_0_9c: f64,
    /// Largest relative deviation of the Galerkin model's neutral frequencies from the exact
    /// ones above 1.1 c (the supercritical branch, over the tracked frequencies the model has;
    /// `None` when no swept speed is above 1.1 c).
    pub analytical_max_rel_error_above_1_1c: Option<f64>,
    /// What the numbers mean ([`SWEEP_MEANING`]).
    pub meaning: String,
}

/// The sweep's "what the numbers mean" paragraph (`meaning` in `summary.json`).
pub const SWEEP_MEANING: &str = "Natural frequencies of the travelling string (Ribaric ch. 4) against the axial speed \
         from 0 to max_speed_ratio times the critical speed c = sqrt(T/(rho A)) = \
         critical_speed [m/s] (sweep.csv, sweep.png): the neutral eigenvalues of the Galerkin \
         model (4.29) and of the flowing-material model (4.20), and the exact \
         f_n = n|c^2 - v^2|/(2cL) (Wickert & Mote 1990). Every frequency falls with the speed \
         to 0 Hz at v = c (divergence) and rises again above c, where the string between \
         fixed guides stays neutrally stable. The truncated models have growing eigenvalues \
         above c whose rates rise without bound as the truncation is refined (largest in \
         analytical_ / flowing_max_growth_1_s, 0 when nothing grows): at every speed where a \
         model grows it is solved again with twice the Galerkin terms or half the FE spacing \
         and twice the modes, and growth that this does not reproduce within 10 % is a \
         truncation artefact (analytical_ / flowing_truncation_growth_from, the lowest such \
         speed; shaded on the plot). unstable_from is the lowest speed at which the string \
         itself is unstable (v = c hit exactly, or reproduced growth; string_unstable_flag in \
         sweep.csv; null: stable everywhere). max_rel_error_below_0_9c is the flowing \
         model's largest deviation from the exact frequencies below 0.9 c (near c its modal \
         basis converges slowly), analytical_max_rel_error_above_1_1c the Galerkin model's \
         above 1.1 c. A frequency a model does not have at a speed (its growing pairs took \
         the place) is NaN in sweep.csv.";

/// The header of `sweep.csv`: the speed \[m/s\], the `tracked` Galerkin, flowing and exact
/// frequencies \[Hz\], the largest growth rate of each model \[1/s\] and the string's
/// instability flag.
pub fn sweep_header(tracked: usize) -> Vec<String> {
    let mut header = vec!["speed_m_per_s".to_string()];
    for kind in ["analytical", "flowing", "exact"] {
        for n in 1..=tracked {
            header.push(format!("{kind}_f{n}_Hz"));
        }
    }
    header.push("analytical_max_growth_1_per_s".into());
    header.push("flowing_max_growth_1_per_s".into());
    header.push("string_unstable_flag".into());
    header
}

/// Sweep `c.steps` speeds evenly from 0 to `c.max_speed_ratio` times the critical speed; each
/// row of `sweep.csv` ([`sweep_header`]; NaN for a frequency a model does not have at that
/// speed) goes to `on_row` with its index as soon as it is computed, and
/// [`ControlFlow::Break`] from it stops the sweep (the speeds done make the summary).
pub fn string_sweep(
    c: &SweepConfig, on_row: &mut dyn FnMut(usize, &[f64]) -> ControlFlow<()>,
) -> Result<SweepSummary, FlowError> {
    let crit = c.string.wave_speed();
    let (_, sys) = flowing_model(c.string, c.nodes, c.modes, c.derivative, 0.0)?;
    // the second discretisation of the flowing model, built when it first grows
    let mut sys_check = None;
    let mut unstable_from = None;
    let (mut a_trunc, mut f_trunc) = (None, None);
    let (mut max_err, mut max_err_super) = (0.0f64, None::<f64>);
    for i in 0..c.steps {
        let v = c.max_speed_ratio * crit * i as f64 / (c.steps - 1) as f64;
        let regime = Regime::of(&c.string, v);
        let a = galerkin_spectrum(c.string, v, c.galerkin_terms)?;
        let f = flowing_spectrum(&sys, v)?;
        let mut reproduced = false;
        if !a.growth.is_empty() {
            let check = galerkin_spectrum(c.string, v, check_terms(c.galerkin_terms))?;
            let (kept, trunc) = classify_growth(&a.growth, &check.growth);
            reproduced |= !kept.is_empty();
            if !trunc.is_empty() {
                a_trunc.get_or_insert(v);
            }
        }
        if !f.growth.is_empty() {
            if sys_check.is_none() {
                let (n, k) = check_mesh(c.nodes, c.modes);
                sys_check = Some(flowing_model(c.string, n, k, c.derivative, 0.0)?.1);
            }
            if let Some(s2) = &sys_check {
                let check = flowing_spectrum(s2, v)?;
                let (kept, trunc) = classify_growth(&f.growth, &check.growth);
                reproduced |= !kept.is_empty();
                if !trunc.is_empty() {
                    f_trunc.get_or_insert(v);
                }
            }
        }
        let unstable = regime == Regime::Critical || reproduced;
        if unstable {
            unstable_from.get_or_insert(v);
        }
        let mut row = vec![v];
        for n in 0..c.tracked {
            row.push(a.neutral_hz.get(n).copied().unwrap_or(f64::NAN));
        }
        for n in 0..c.tracked {
            let ex = c.string.exact_moving_frequency_hz(n + 1, v);
            row.push(f.neutral_hz.get(n).copied().unwrap_or(f64::NAN));
            if let Some(x) = f.neutral_hz.get(n)
                && v < 0.9 * crit
            {
                max_err = max_err.max((x - ex).abs() / ex);
            }
            if v > 1.1 * crit
                && let Some(x) = a.neutral_hz.get(n)
            {
                max_err_super = Some(max_err_super.unwrap_or(0.0).max((x - ex).abs() / ex));
            }
        }
        for n in 0..c.tracked {
            row.push(c.string.exact_moving_frequency_hz(n + 1, v));
        }
        row.push(a.growth.first().map_or(0.0, |g| g.rate_per_s));
        row.push(f.growth.first().map_or(0.0, |g| g.rate_per_s));
        row.push(f64::from(u8::from(unstable)));
        if on_row(i, &row).is_break() {
            // interrupted: the speeds swept so far make the summary
            break;
        }
    }
    Ok(SweepSummary {
        critical_speed: crit,
        unstable_from,
        analytical_truncation_growth_from: a_trunc,
        flowing_truncation_growth_from: f_trunc,
        max_rel_error_below_0_9c: max_err,
        analytical_max_rel_error_above_1_1c: max_err_super,
        meaning: SWEEP_MEANING.to_string(),
    })
}
