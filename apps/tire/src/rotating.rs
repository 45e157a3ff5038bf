//! `flowmbd-tire rotating-modes`: complex modes of the rolling tire in the ground-fixed frame at
//! several speeds ([`tire::rotating_study`]): the flowing-material gyroscopic and convective
//! terms of Ribaric (7.17) split each circumferential order `n` into a forward and a backward
//! wave. Free tire (rim fixed) and loaded tire (rolling preload's patch held); Campbell
//! diagrams, a CSV of every mode and the forward/backward splits.

use crate::common::{TireSourceExt, tire_err};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, Study, StudyContext, StudyError, run_study};
use std::process::ExitCode;
use tire::rotating_study::{
    ROTATING_COLUMNS, ROTATING_MEANING, RotatingStudyConfig as Config, RotatingSummary as Summary,
    SplitOut, rotating_rows, run_rotating,
};
use tire::{SpeedModes, WaveDirection};

/// Command-line arguments.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: CommonArgs,
    /// Speeds [km/h], comma separated (overrides `speeds_kmh`), e.g. `--speeds 0,30,60,90,120`.
    #[allow(rustdoc::broken_intra_doc_links)]
    #[arg(long, value_delimiter = ',')]
    speeds: Option<Vec<f64>>,
    /// Highest damped frequency reported [Hz] (overrides `max_hz`).
    #[allow(rustdoc::broken_intra_doc_links)]
    #[arg(long)]
    max_hz: Option<f64>,
}

struct Rotating {
    speeds: Option<Vec<f64>>,
    max_hz: Option<f64>,
}

fn campbell(
    runs: &[SpeedModes],
    splits: &[SplitOut],
    loaded: bool,
    stem: &std::path::Path,
) -> Result<(), StudyError> {
    let mut plot = LinePlot::new(
        if loaded {
            "Campbell diagram, loaded tire (patch held), ground frame"
        } else {
            "Campbell diagram, free tire (rim fixed), ground frame"
        },
        "speed [km/h]",
        "f [Hz]",
    );
    for (name, d) in [
        ("forward", WaveDirection::Forward),
        ("backward", WaveDirection::Backward),
        ("standing", WaveDirection::Standing),
    ] {
        let pts: Vec<(f64, f64)> = runs
            .iter()
            .flat_map(|r| {
                let modes = if loaded { &r.loaded } else { &r.free };
                modes
                    .iter()
                    .filter(move |m| m.direction == d)
                    .map(move |m| (r.speed_kmh, m.hz))
            })
            .collect();
        plot = plot.with(Series::points(name, pts));
    }
    if !loaded {
        for s in splits.iter().filter(|s| s.plane == "in_plane" && s.n <= 5) {
            for (which, v) in [("fwd", &s.forward_hz), ("bwd", &s.backward_hz)] {
                let pts: Vec<(f64, f64)> = runs
                    .iter()
                    .zip(v)
                    .filter_map(|(r, f)| f.map(|f| (r.speed_kmh, f)))
                    .collect();
                plot = plot.with(Series::line(format!("n={} in-plane {which}", s.n), pts));
            }
        }
    }
    plot.save(stem)?;
    Ok(())
}

impl Study for Rotating {
    type Config = Config;
    type Summary = Summary;
    const APP: &'static str = "tire";
    const NAME: &'static str = "rotating-modes";

    fn meaning(&self) -> &'static str {
        ROTATING_MEANING
    }

    fn config_notes(&self, c: &Config) -> String {
        crate::common::import_notes(&c.tire)
    }

    fn apply_overrides(&self, c: &mut Config) {
        if let Some(s) = &self.speeds {
            c.speeds_kmh = s.clone();
        }
        if let Some(f) = self.max_hz {
            c.max_hz = f;
        }
    }

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let red = c.tire.reduced(ctx.quiet)?;
        let n = c.speeds_kmh.len() as f64;
        let bar = ctx.progress(n, "rotating modes");
        let (summary, runs) = run_rotating(&red, c, &mut |f| bar.set(f * n)).map_err(tire_err)?;
        bar.finish();
        ctx.out.write_csv(
            "rotating_modes.csv",
            &ROTATING_COLUMNS,
            rotating_rows(&summary),
        )?;
        campbell(
            &runs,
            &summary.splits,
            false,
            &ctx.out.path("campbell_free"),
        )?;
        campbell(
            &runs,
            &summary.splits,
            true,
            &ctx.out.path("campbell_loaded"),
        )?;
        Ok(summary)
    }
}

/// Run the study.
pub fn run(args: &Args) -> ExitCode {
    run_study(
        &Rotating {
            speeds: args.speeds.clone(),
            max_hz: args.max_hz,
        },
        &args.common,
    )
}
