//! The modes study (`flowmbd-tire modes`, `flowmbd.tire.modes`): eigenfrequencies of the tire
//! with the rim fixed, full FE model ([`full_frequencies_hz`], sparse shift-invert) against the
//! reduced model (the validation of the reduction, Ribaric §8.2), and the modes of the loaded
//! tire (reduced, preloaded patch held on the ground, wheel fixed; [`loaded_modes_at_preload`])
//! with their effective spindle masses: the vertical in-plane mode the cleat test should show
//! (§8.3). Configuration, summary and the rows of `modes.csv` and `loaded_modes.csv` live here
//! so that the CLI and the Python package return the same numbers.

use crate::error::TireError;
use crate::ground::GroundConfig;
use crate::loaded::{
    LoadedMode, dominant_longitudinal_mode, dominant_vertical_mode, held_nodes,
    loaded_modes_at_preload,
};
use crate::mesh::TireFe;
use crate::reduce::full_frequencies_hz;
use crate::reduced::ReducedTire;
use crate::source::TireSource;
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};

/// Upper end of the band in which the reduction's error is reported \[Hz\] (the band Ribaric
/// keeps).
pub const ERROR_BAND_HZ: f64 = 240.0;

/// Configuration of the modes study.
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct ModesStudyConfig {
    /// The tire.
    pub tire: TireSource,
    /// Number of modes compared.
    pub count: usize,
    /// Ground of the loaded tire (drum R = 1.25 m by default; the cleat is not used).
    pub ground: GroundConfig,
    /// Vertical load of the loaded tire \[N\] (1000 lb, Ribaric §8.3).
    pub load: f64,
}

impl Default for ModesStudyConfig {
    fn default() -> Self {
        Self {
            tire: TireSource::default(),
            count: 30,
            ground: GroundConfig::default(),
            load: 4448.2,
        }
    }
}

impl mbd_core::config::PartialRules for ModesStudyConfig {}

impl Validate for ModesStudyConfig {
    /// A positive count and load, the ground and the tire.
    fn validate(&self) -> Result<(), InvalidField> {
        if self.count == 0 {
            return Err(InvalidField::new("count", "must be positive"));
        }
        if !(self.load > 0.0 && self.load.is_finite()) {
            return Err(InvalidField::new("load", "must be positive"));
        }
        self.ground.validate_within("ground")?;
        self.tire.validate_within("tire")
    }
}

/// Summary of the modes study (`summary.json`).
#[derive(Debug, Serialize)]
pub struct ModesSummary {
    /// Full FE frequencies \[Hz\].
    pub full_hz: Vec<f64>,
    /// Reduced frequencies \[Hz\].
    pub reduced_hz: Vec<f64>,
    /// Largest relative error below [`ERROR_BAND_HZ`].
    pub max_rel_error_below_240hz: f64,
    /// Contact nodes held in the loaded tire (positive preload multiplier).
    pub loaded_held_nodes: usize,
    /// Frequencies of the loaded tire \[Hz\] (the first `count`).
    pub loaded_hz: Vec<f64>,
    /// The loaded tire's vertical in-plane mode: largest effective vertical spindle mass \[Hz\].
    pub loaded_vertical_mode_hz: Option<f64>,
    /// Its effective vertical spindle mass \[kg\].
    pub loaded_vertical_mass_kg: Option<f64>,
    /// The loaded mode with the largest effective longitudinal spindle mass \[Hz\].
    pub loaded_longitudinal_mode_hz: Option<f64>,
    /// What the numbers mean ([`MODES_MEANING`]).
    pub meaning: String,
}

/// The modes study's "what the numbers mean" paragraph (`meaning` in `summary.json`).
pub const MODES_MEANING: &str = "Natural frequencies of the tire with the rim fixed: full_hz of the full FE model and \
     reduced_hz of the reduced model (Ribaric 8.2: contact-node modes, free-node modes \
     and static modes); max_rel_error_below_240hz is the reduced model's largest relative \
     error in the band Ribaric keeps (the reduction is Rayleigh-Ritz, so reduced >= \
     full). loaded_hz are the frequencies of the tire pressed onto the ground by the \
     preload (its loaded_held_nodes contact nodes held); loaded_vertical_mode_hz and \
     loaded_longitudinal_mode_hz are the loaded modes with the largest effective vertical \
     and longitudinal spindle mass [kg]: the modes that carry the cleat test's F_y and \
     F_x lines.";

/// Run the study on the FE tire `fe` and its reduction `red`: the first `c.count` full and
/// reduced frequencies with the rim fixed, then the loaded modes at the static preload of
/// `c.load` on `c.ground`. Returns the summary and every loaded mode (the rows of
/// [`loaded_rows`]).
pub fn run_modes(
    fe: &TireFe, red: &ReducedTire, c: &ModesStudyConfig,
) -> Result<(ModesSummary, Vec<LoadedMode>), TireError> {
    let full = full_frequencies_hz(fe, c.count)?;
    let mut reduced = red.frequencies_hz()?;
    reduced.truncate(full.len());
    let err = full
        .iter()
        .zip(&reduced)
        .filter(|(f, _)| **f < ERROR_BAND_HZ)
        .map(|(f, r)| (r - f).abs() / f)
        .fold(0.0, f64::max);
    let (pre, loaded) = loaded_modes_at_preload(red, &c.ground, c.load)?;
    let vertical = dominant_vertical_mode(&loaded);
    let summary = ModesSummary {
        loaded_held_nodes: held_nodes(&pre.patch).len(),
        loaded_hz: loaded.iter().take(c.count).map(|m| m.hz).collect(),
        loaded_vertical_mode_hz: vertical.map(|m| m.hz),
        loaded_vertical_mass_kg: vertical.map(|m| m.vertical_mass.abs()),
        loaded_longitudinal_mode_hz: dominant_longitudinal_mode(&loaded).map(|m| m.hz),
        full_hz: full,
        reduced_hz: reduced,
        max_rel_error_below_240hz: err,
        meaning: MODES_MEANING.to_string(),
    };
    Ok((summary, loaded))
}

/// Columns of `modes.csv` ([`modes_rows`]).
pub const MODES_COLUMNS: [&str; 3] = ["mode", "full_Hz", "reduced_Hz"];

/// Rows of `modes.csv`: mode number (from 1), full and reduced frequency \[Hz\].
pub fn modes_rows(s: &ModesSummary) -> Vec<[f64; 3]> {
    s.full_hz
        .iter()
        .zip(&s.reduced_hz)
        .enumerate()
        .map(|(i, (f, r))| [(i + 1) as f64, *f, *r])
        .collect()
}

/// Columns of `loaded_modes.csv` ([`loaded_rows`]).
pub const LOADED_COLUMNS: [&str; 7] = [
    "mode",
    "f_Hz",
    "spindle_fx_N_per_sqrt_kg",
    "spindle_fy_N_per_sqrt_kg",
    "spindle_lateral_N_per_sqrt_kg",
    "vertical_mass_kg",
    "longitudinal_mass_kg",
];

/// Rows of `loaded_modes.csv`: mode number (from 1), frequency \[Hz\], spindle force of the
/// mass-normalised mode \[N/√kg\], effective vertical and longitudinal spindle mass \[kg\].
pub fn loaded_rows(loaded: &[LoadedMode]) -> Vec<[f64; 7]> {
    loaded
        .iter()
        .enumerate()
        .map(|(i, m)| {
            [
                (i + 1) as f64,
                m.hz,
                m.spindle[0],
                m.spindle[1],
                m.spindle[2],
                m.vertical_mass,
                m.longitudinal_mass,
            ]
        })
        .collect()
}
