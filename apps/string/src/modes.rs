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

    fn results_must_be_finite(&self) -> bool {
        true
    }

    fn meaning(&self) -> &'static str {
        flowing::string_study::MODES_MEANING
    }

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
        let rows = (0..c.report).map(|i| {
            [
                (i + 1) as f64,
                analytical.get(i).copied().unwrap_or(f64::NAN),
                flowing.get(i).copied().unwrap_or(f64::NAN),
                summary.exact_hz.get(i).copied().unwrap_or(f64::NAN),
            ]
        });
        ctx.out.write_csv(
            "frequencies.csv",
            &["n", "analytical_hz", "flowing_hz", "exact_hz"],
            rows,
        )?;
        if !summary.flowing_growth.is_empty() || !summary.analytical_growth.is_empty() {
            let rows = summary
                .analytical_growth
                .iter()
                .map(|g| [0.0, g.rate_per_s, g.frequency_hz])
                .chain(
                    summary
                        .flowing_growth
                        .iter()
                        .map(|g| [1.0, g.rate_per_s, g.frequency_hz]),
                );
            // model_code: 0 Galerkin (4.29), 1 flowing material (4.20)
            ctx.out.write_csv(
                "growth.csv",
                &["model_code", "rate_1_s", "frequency_hz"],
                rows,
            )?;
        }
        if !ctx.quiet {
            for w in &summary.warnings {
                eprintln!("warning: {w}");
            }
        }
        Ok(summary)
    }
}
