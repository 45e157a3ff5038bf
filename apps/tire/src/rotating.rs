//! `flowmbd-tire rotating-modes`: complex modes of the rolling tire in the ground-fixed frame at
//! several speeds ([`tire::rotating_study`]): the flowing-material gyroscopic and convective
//! terms of Ribaric (7.17) split each circumferential order `n` into a forward and a backward
//! wave. Free tire (rim fixed) and loaded tire (rolling preload's patch held); Campbell
//! diagrams, a CSV of every mode and the forward/backward splits.

use crate::common::{run_reduced, tire_err};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, Study, StudyContext, StudyError, set_given};
use tire::rotating_study::{
    ROTATING_COLUMNS, RotatingStudyConfig as Config, RotatingSummary as Summary, SplitOut,
    rotating_rows, run_rotating,
};
use tire::{SpeedModes, WaveDirection};

/// Command-line arguments.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Speeds [km/h], comma separated (overrides `speeds_kmh`), e.g. `--speeds 0,30,60,90,120`.
    #[arg(long, value_delimiter = ',')]
    speeds: Option<Vec<f64>>,
    /// Highest damped frequency reported [Hz] (overrides `max_hz`).
    #[arg(long)]
    max_hz: Option<f64>,
}

fn campbell(
    runs: &[SpeedModes], splits: &[SplitOut], loaded: bool, stem: &std::path::Path,
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

impl Study for Args {
    type Config = Config;
    type Summary = Summary;
    const NAME: &'static str = "rotating-modes";

    fn apply_overrides(&self, c: &mut Config) {
        set_given(&mut c.speeds_kmh, self.speeds.clone());
        set_given(&mut c.max_hz, self.max_hz);
    }

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let (_, (summary, runs)) = run_reduced(
            ctx,
            &c.tire,
            c.speeds_kmh.len(),
            "rotating modes",
            |red, bar| run_rotating(red, c, bar).map_err(tire_err),
        )?;
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
