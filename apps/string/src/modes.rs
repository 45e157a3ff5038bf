//! `modes`: damped natural frequencies of the analytical and the flowing-material models
//! (configuration, summary and computation in [`flowing::string_study`]).

use crate::common::study_error;
use flowing::string_study::{ModesConfig, ModesSummary, string_modes};
use flowmbd_cli::{Study, StudyContext, StudyError};

/// The `modes` study.
pub struct ModesStudy {
    pub speed: Option<f64>,
    pub nodes: Option<usize>,
    pub modes: Option<usize>,
}

impl Study for ModesStudy {
    type Config = ModesConfig;
    type Summary = ModesSummary;
    const APP: &'static str = "string";
    const NAME: &'static str = "modes";

    fn apply_overrides(&self, c: &mut ModesConfig) {
        if let Some(v) = self.speed {
            c.speed = v;
        }
        if let Some(n) = self.nodes {
            c.nodes = n;
        }
        if let Some(k) = self.modes {
            c.modes = k;
        }
    }

    fn run(&self, c: &ModesConfig, ctx: &mut StudyContext) -> Result<ModesSummary, StudyError> {
        let summary = string_modes(c).map_err(study_error)?;
        let (analytical, flowing) = (&summary.analytical_hz, &summary.flowing_hz);
        let exact: Vec<f64> = (1..=c.report)
            .map(|n| c.string.exact_moving_frequency_hz(n, c.speed))
            .collect();
        let rows = (0..c.report).map(|i| {
            [
                (i + 1) as f64,
                analytical.get(i).copied().unwrap_or(f64::NAN),
                flowing.get(i).copied().unwrap_or(f64::NAN),
                exact[i],
            ]
        });
        ctx.out.write_csv(
            "frequencies.csv",
            &["n", "analytical_hz", "flowing_hz", "exact_hz"],
            rows,
        )?;
        Ok(summary)
    }
}
