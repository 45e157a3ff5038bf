//! `flowmbd-tire pressure`: the preloaded patch on the drum (R = 1.25 m) and on a flat road
//! (Ribaric Fig. 8-12, 4448 N): contact-node forces and patch extent.

use crate::common::{TireSource, TireSourceExt, tire_err};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, InputError, Study, StudyContext, StudyError, Validate, run_study};
use serde::{Deserialize, Serialize};
use std::process::ExitCode;
use tire::{GroundConfig, GroundKind, preload};

/// Configuration.
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// The tire.
    pub tire: TireSource,
    /// Vertical load \[N\].
    pub load: f64,
    /// Drum radius \[m\].
    pub drum_radius: f64,
}

impl Default for Config {
    fn default() -> Self {
        Self {
            tire: TireSource::default(),
            load: 4448.2,
            drum_radius: 1.25,
        }
    }
}

impl flowmbd_cli::PartialRules for Config {}

impl Validate for Config {
    fn validate(&self) -> Result<(), InputError> {
        self.tire.validate_within("tire")?;
        if !(self.load > 0.0 && self.load.is_finite()) {
            return Err(InputError::new("load", "must be positive"));
        }
        if !(self.drum_radius > 0.0 && self.drum_radius.is_finite()) {
            return Err(InputError::new("drum_radius", "must be positive"));
        }
        Ok(())
    }
}

/// Patch statistics of one ground.
#[derive(Debug, Serialize)]
pub struct Patch {
    /// Deflection \[m\].
    pub deflection_m: f64,
    /// Nodes in contact.
    pub nodes_in_contact: usize,
    /// Largest node force \[N\].
    pub peak_node_force_n: f64,
    /// Longitudinal patch length (extent of the contacting nodes) \[m\].
    pub length_m: f64,
}

/// Summary.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// On the drum.
    pub drum: Patch,
    /// On the flat road.
    pub road: Patch,
}

struct Pressure;

impl Study for Pressure {
    type Config = Config;
    type Summary = Summary;
    const APP: &'static str = "tire";
    const NAME: &'static str = "pressure";

    fn meaning(&self) -> &'static str {
        "The preloaded contact patch on the drum and on the flat road (Ribaric Fig. 8-12): \
         per ground the deflection [m] of the tire under the load, the contact nodes in \
         contact, the largest node force [N] and the patch length [m] along the rolling \
         direction. The node forces in patch_*.csv add up to the load; the convex drum needs \
         a larger deflection and gives a shorter patch with higher peak forces than the road."
    }

    fn config_notes(&self, c: &Config) -> String {
        crate::common::import_notes(&c.tire)
    }

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let red = c.tire.reduced(ctx.quiet)?;
        let mut out = Vec::new();
        let mut plot = LinePlot::new(
            format!(
                "Contact-node forces at {:.0} N (drum R = {} m vs flat road)",
                c.load, c.drum_radius
            ),
            "x [m] (longitudinal position in the patch)",
            "node force [N]",
        );
        for kind in [GroundKind::Drum, GroundKind::Road] {
            let g = GroundConfig {
                kind,
                drum_radius: c.drum_radius,
                cleat: false,
                ..GroundConfig::default()
            };
            let p = preload(&red, &g, c.load).map_err(tire_err)?;
            let name = match kind {
                GroundKind::Drum => "drum",
                GroundKind::Road => "road",
            };
            ctx.out.write_csv(
                &format!("patch_{name}.csv"),
                &["x_m", "y_m", "z_m", "force_N"],
                red.contact_positions
                    .iter()
                    .zip(&p.patch.lambda)
                    .map(|(s, l)| vec![s[0], s[1], s[2], *l]),
            )?;
            plot = plot.with(Series::points(
                name,
                red.contact_positions
                    .iter()
                    .zip(&p.patch.lambda)
                    .filter(|(_, l)| **l > 0.0)
                    .map(|(s, l)| (s[0], *l))
                    .collect(),
            ));
            let xs: Vec<f64> = red
                .contact_positions
                .iter()
                .zip(&p.patch.lambda)
                .filter(|(_, l)| **l > 0.0)
                .map(|(s, _)| s[0])
                .collect();
            let len = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max)
                - xs.iter().copied().fold(f64::INFINITY, f64::min);
            out.push(Patch {
                deflection_m: p.patch.deflection,
                nodes_in_contact: xs.len(),
                peak_node_force_n: p.patch.lambda.iter().copied().fold(0.0, f64::max),
                length_m: if xs.is_empty() { 0.0 } else { len },
            });
        }
        plot.save(&ctx.out.path("patch_forces"))?;
        let road = out
            .pop()
            .ok_or_else(|| StudyError::numerical("no road patch"))?;
        let drum = out
            .pop()
            .ok_or_else(|| StudyError::numerical("no drum patch"))?;
        Ok(Summary { drum, road })
    }
}

/// Run the study.
pub fn run(args: &CommonArgs) -> ExitCode {
    run_study(&Pressure, args)
}
