//! `modes`: damped natural frequencies of the analytical and the flowing-material models
//! (configuration, summary and computation in [`flowing::string_study`]).

use crate::common::{ModelArgs, SpeedArg, study_error};
use flowing::string_study::{ModesConfig, ModesSummary, string_modes};
use flowmbd_cli::{CommonArgs, Study, StudyContext, StudyError};

/// The `modes` study: its command line.
#[derive(clap::Args, Debug)]
pub struct ModesStudy {
    #[command(flatten)]
    pub speed: SpeedArg,
    #[command(flatten)]
    pub model: ModelArgs,
    #[command(flatten)]
    pub common: CommonArgs,
}

impl Study for ModesStudy {
    type Config = ModesConfig;
    type Summary = ModesSummary;
    const NAME: &'static str = "modes";

    fn apply_overrides(&self, c: &mut ModesConfig) {
        self.speed.apply(&mut c.speed);
        self.model.apply(&mut c.nodes, &mut c.modes);
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
            &["n", "analytical_Hz", "flowing_Hz", "exact_Hz"],
            rows,
        )?;
        // every growing eigenvalue of either model: reproduced by the second discretisation
        // (truncation_flag 0) or truncation-dependent (1); check_rate 0: the check does not grow
        let rows: Vec<[f64; 6]> = [
            (
                0.0,
                &summary.analytical_growth,
                &summary.analytical_truncation_growth,
            ),
            (
                1.0,
                &summary.flowing_growth,
                &summary.flowing_truncation_growth,
            ),
        ]
        .into_iter()
        .flat_map(|(code, kept, trunc)| {
            kept.iter()
                .map(move |g| {
                    [
                        code,
                        0.0,
                        g.rate_per_s,
                        g.frequency_hz,
                        g.rate_per_s,
                        g.frequency_hz,
                    ]
                })
                .chain(trunc.iter().map(move |g| {
                    [
                        code,
                        1.0,
                        g.rate_per_s,
                        g.frequency_hz,
                        g.check_rate_per_s,
                        g.check_frequency_hz,
                    ]
                }))
        })
        .collect();
        if !rows.is_empty() {
            // model_code: 0 Galerkin (4.29), 1 flowing material (4.20)
            ctx.out.write_csv(
                "growth.csv",
                &[
                    "model_code",
                    "truncation_flag",
                    "rate_1_per_s",
                    "frequency_Hz",
                    "check_rate_1_per_s",
                    "check_frequency_Hz",
                ],
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
