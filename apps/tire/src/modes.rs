//! `flowmbd-tire modes`: eigenfrequencies of the generated tire with the rim fixed, full FE model
//! (sparse shift-invert) against the reduced model (Ribaric §8.2 validation), and the modes of
//! the loaded tire (reduced, preloaded patch held on the ground, wheel fixed) with their
//! effective spindle masses (`tire::loaded`): the vertical in-plane mode the cleat test
//! should show (Ribaric §8.3).

use crate::common::{TireSource, TireSourceExt, tire_err};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, InputError, Study, StudyContext, StudyError, Validate, run_study};
use serde::{Deserialize, Serialize};
use std::process::ExitCode;
use tire::{
    GroundConfig, dominant_longitudinal_mode, dominant_vertical_mode, full_frequencies_hz,
    held_nodes, loaded_modes_at_preload,
};

/// Configuration.
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// The tire.
    pub tire: TireSource,
    /// Number of modes compared.
    pub count: usize,
    /// Ground of the loaded tire (drum R = 1.25 m by default; the cleat is not used).
    pub ground: GroundConfig,
    /// Vertical load of the loaded tire \[N\] (1000 lb, Ribaric §8.3).
    pub load: f64,
}

impl Default for Config {
    fn default() -> Self {
        Self {
            tire: TireSource::default(),
            count: 30,
            ground: GroundConfig::default(),
            load: 4448.2,
        }
    }
}

impl flowmbd_cli::PartialRules for Config {}

impl Validate for Config {
    fn validate(&self) -> Result<(), InputError> {
        if self.count == 0 {
            return Err(InputError::new("count", "must be positive"));
        }
        if !(self.load > 0.0 && self.load.is_finite()) {
            return Err(InputError::new("load", "must be positive"));
        }
        self.ground.validate_within("ground")?;
        self.tire.validate_within("tire")
    }
}

/// Summary.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// Full FE frequencies \[Hz\].
    pub full_hz: Vec<f64>,
    /// Reduced frequencies \[Hz\].
    pub reduced_hz: Vec<f64>,
    /// Largest relative error below 240 Hz.
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
}

struct Modes;

impl Study for Modes {
    type Config = Config;
    type Summary = Summary;
    const APP: &'static str = "tire";
    const NAME: &'static str = "modes";

    fn meaning(&self) -> &'static str {
        "Natural frequencies of the tire with the rim fixed: full_hz of the full FE model and \
         reduced_hz of the reduced model (Ribaric 8.2: contact-node modes, free-node modes \
         and static modes); max_rel_error_below_240hz is the reduced model's largest relative \
         error in the band Ribaric keeps (the reduction is Rayleigh-Ritz, so reduced >= \
         full). loaded_hz are the frequencies of the tire pressed onto the ground by the \
         preload (its loaded_held_nodes contact nodes held); loaded_vertical_mode_hz and \
         loaded_longitudinal_mode_hz are the loaded modes with the largest effective vertical \
         and longitudinal spindle mass [kg]: the modes that carry the cleat test's F_y and \
         F_x lines."
    }

    fn config_notes(&self, c: &Config) -> String {
        crate::common::import_notes(&c.tire)
    }

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let fe = c.tire.fe_model_or_err()?;
        let full = full_frequencies_hz(&fe, c.count).map_err(tire_err)?;
        let red = c.tire.reduced(ctx.quiet)?;
        let mut reduced = red.frequencies_hz().map_err(tire_err)?;
        reduced.truncate(full.len());
        let err = full
            .iter()
            .zip(&reduced)
            .filter(|(f, _)| **f < 240.0)
            .map(|(f, r)| (r - f).abs() / f)
            .fold(0.0, f64::max);
        ctx.out.write_csv(
            "modes.csv",
            &["mode", "full_Hz", "reduced_Hz"],
            full.iter()
                .zip(&reduced)
                .enumerate()
                .map(|(i, (f, r))| vec![(i + 1) as f64, *f, *r]),
        )?;
        let pts = |f: &[f64]| -> Vec<(f64, f64)> {
            f.iter()
                .enumerate()
                .map(|(i, f)| ((i + 1) as f64, *f))
                .collect()
        };
        LinePlot::new(
            "Eigenfrequencies with the rim fixed: full FE vs reduced",
            "mode",
            "f [Hz]",
        )
        .with(Series::points("full FE", pts(&full)))
        .with(Series::points("reduced", pts(&reduced)))
        .save(&ctx.out.path("modes"))?;
        let (pre, loaded) = loaded_modes_at_preload(&red, &c.ground, c.load).map_err(tire_err)?;
        ctx.out.write_csv(
            "loaded_modes.csv",
            &[
                "mode",
                "f_Hz",
                "spindle_fx_N_per_sqrt_kg",
                "spindle_fy_N_per_sqrt_kg",
                "spindle_lateral_N_per_sqrt_kg",
                "vertical_mass_kg",
                "longitudinal_mass_kg",
            ],
            loaded.iter().enumerate().map(|(i, m)| {
                vec![
                    (i + 1) as f64,
                    m.hz,
                    m.spindle[0],
                    m.spindle[1],
                    m.spindle[2],
                    m.vertical_mass,
                    m.longitudinal_mass,
                ]
            }),
        )?;
        let vertical = dominant_vertical_mode(&loaded);
        Ok(Summary {
            full_hz: full,
            reduced_hz: reduced,
            max_rel_error_below_240hz: err,
            loaded_held_nodes: held_nodes(&pre.patch).len(),
            loaded_hz: loaded.iter().take(c.count).map(|m| m.hz).collect(),
            loaded_vertical_mode_hz: vertical.map(|m| m.hz),
            loaded_vertical_mass_kg: vertical.map(|m| m.vertical_mass.abs()),
            loaded_longitudinal_mode_hz: dominant_longitudinal_mode(&loaded).map(|m| m.hz),
        })
    }
}

/// Run the study.
pub fn run(args: &CommonArgs) -> ExitCode {
    run_study(&Modes, args)
}
