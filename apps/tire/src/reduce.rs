//! `flowmbd-tire reduce`: generate the tire, reduce it (Ribaric §8.2) and save the reduced-tire
//! file; the stage times are the benchmark record of the 60 000-DOF reduction.

use crate::common::{TireSource, TireSourceExt, tire_err};
use flowmbd_cli::{InputError, Study, StudyContext, StudyError, Validate};
use serde::{Deserialize, Serialize};
use std::time::Instant;
use tire::ReductionTimings;

/// Configuration.
#[derive(Debug, Clone, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// The tire (the reduced file is always recomputed and written).
    pub tire: TireSource,
}

impl flowmbd_cli::PartialRules for Config {}

impl Validate for Config {
    fn validate(&self) -> Result<(), InputError> {
        self.tire.validate_within("tire")
    }
}

/// Summary.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// FE DOFs.
    pub fe_dof: usize,
    /// Wheel–tire DOF after reduction (6 + n_f + 3 n_c).
    pub dof: usize,
    /// Kept free-node modes.
    pub free_modes: usize,
    /// Contact nodes.
    pub contact_nodes: usize,
    /// Highest kept free-node mode \[Hz\].
    pub free_mode_max_hz: f64,
    /// Highest contact-node mode \[Hz\].
    pub contact_mode_max_hz: f64,
    /// Tire mass \[kg\].
    pub tire_mass_kg: f64,
    /// Mesh generation and assembly \[s\].
    pub assembly_s: f64,
    /// Reduction stage times \[s\].
    pub timings: ReductionTimings,
    /// Saved file.
    pub file: String,
}

/// The study.
pub struct Reduce;

impl Study for Reduce {
    type Config = Config;
    type Summary = Summary;
    const NAME: &'static str = "reduce";
    const MEANING: &'static str = "The reduction of Ribaric 8.2: the FE tire (fe_dof DOFs) reduced to dof coordinates \
         (6 wheel DOFs, 3 per contact node, free_modes free-node modes) and saved to file. \
         free_mode_max_hz and contact_mode_max_hz are the highest kept free-node and \
         contact-node modes [Hz] (the band the reduced tire resolves); tire_mass_kg is the \
         tire's mass; the timings [s] are the stages of the reduction (modes, static modes, \
         derivatives, projection).";

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let t = Instant::now();
        let fe = c.tire.fe_model_or_err()?;
        let assembly_s = t.elapsed().as_secs_f64();
        let (red, timings) = c.tire.reduce_fe(&fe).map_err(tire_err)?;
        let path = match c.tire.reduced_path().map_err(tire_err)? {
            Some(p) => p,
            None => ctx.out.path("reduced-tire.json"),
        };
        // (a temporary file renamed onto `path` when complete, `ReducedTire::save`)
        red.save(&path).map_err(tire_err)?;
        let file = path.display().to_string();
        ctx.out.write_csv(
            "free_modes.csv",
            &["mode", "f_Hz"],
            red.free_mode_hz
                .iter()
                .enumerate()
                .map(|(i, f)| vec![(i + 1) as f64, *f]),
        )?;
        Ok(Summary {
            fe_dof: fe.n_dofs(),
            dof: red.dof(),
            free_modes: red.n_free_modes,
            contact_nodes: red.n_contact(),
            free_mode_max_hz: red.free_mode_hz.last().copied().unwrap_or(0.0),
            contact_mode_max_hz: red.contact_mode_hz.last().copied().unwrap_or(0.0),
            tire_mass_kg: red.tire_mass,
            assembly_s,
            timings,
            file,
        })
    }
}
