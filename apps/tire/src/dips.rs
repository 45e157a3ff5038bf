//! `flowmbd-tire dips`: the speed dips of the cleat test (Ribaric §8.3/§8.5: 40–50 km/h on
//! the drum, 45–55 km/h on the road), predicted from the cleat's quasi-static enveloping
//! profile and the loaded vertical mode (`tire::dips`) and measured by a cleat sweep,
//! on the drum and on the flat road ([`tire::dips_study`]).

use crate::common::{RigFlags, ground_named, rig_err, run_reduced};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, Study, StudyContext, StudyError, set_given};
use tire::dips_study::{
    DipsStudyConfig as Config, DipsSummary as Summary, PREDICTION_COLUMNS, PROFILE_COLUMNS,
    SWEEP_COLUMNS, prediction_rows, profile_rows, run_dips, sweep_rows,
};
use tire::{GroundKind, PulseShape};

/// Command-line arguments.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub common: CommonArgs,
    #[command(flatten)]
    rig: RigFlags,
    /// Prediction only: no cleat sweep (overrides `dips.sweep_speeds_kmh` with none).
    #[arg(long)]
    no_sweep: bool,
    /// Only this ground (`drum` or `road`; default both).
    #[arg(long, value_parser = ["drum", "road"])]
    only: Option<String>,
    /// Pulse shape of the prediction: `half_sine` over the profile's support (default) or
    /// the `profile` itself (overrides `dips.pulse`).
    #[arg(long, value_parser = ["half_sine", "profile"])]
    pulse: Option<String>,
    /// Block the modes below this frequency in the enveloping profile (overrides
    /// `dips.blocked_below_hz`; 0 = quasi-static profile).
    #[arg(long)]
    blocked_below_hz: Option<f64>,
}

/// Ribaric's dip band \[km/h\] (§8.5: drum 40–50, road 45–55).
fn ribaric_band(k: GroundKind) -> (f64, f64) {
    match k {
        GroundKind::Drum => (40.0, 50.0),
        GroundKind::Road => (45.0, 55.0),
    }
}

impl Study for Args {
    type Config = Config;
    type Summary = Summary;
    const NAME: &'static str = "dips";

    fn apply_overrides(&self, c: &mut Config) {
        self.rig.apply(&mut c.tire, &mut c.rig);
        if self.no_sweep {
            c.dips.sweep_speeds_kmh.clear();
        }
        if let Some(p) = &self.pulse {
            c.dips.pulse = if p == "profile" {
                PulseShape::Profile
            } else {
                PulseShape::HalfSine
            };
        }
        set_given(&mut c.dips.blocked_below_hz, self.blocked_below_hz);
        if let Some(g) = &self.only {
            c.grounds = vec![ground_named(g)];
        }
    }

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let (_, (summary, out)) =
            run_reduced(ctx, &c.tire, c.grounds.len(), "dips", |red, bar| {
                run_dips(red, c, bar).map_err(|f| match rig_err(f.error) {
                    StudyError::Numerical { message, .. } => StudyError::Numerical {
                        message: format!("{}: {message}", f.ground.name()),
                        partial: None,
                    },
                    other => other,
                })
            })?;
        let mut profile_plot = LinePlot::new(
            "Quasi-static vertical force change while the cleat passes (spindle held)",
            "cleat ahead of the patch centre x [m]",
            "dFy [N]",
        );
        let mut amp_plot = LinePlot::new(
            "Vertical line against speed: predicted ring-down / sweep (each / its maximum)",
            "v [km/h]",
            "relative amplitude",
        );
        for d in &out {
            let n = d.ground.name();
            let p = &d.profile;
            ctx.out.write_csv(
                &format!("profile_{n}.csv"),
                &PROFILE_COLUMNS,
                profile_rows(d),
            )?;
            let pr = &d.prediction;
            ctx.out.write_csv(
                &format!("prediction_{n}.csv"),
                &PREDICTION_COLUMNS,
                prediction_rows(d),
            )?;
            if !d.sweep_speeds_kmh.is_empty() {
                ctx.out
                    .write_csv(&format!("sweep_{n}.csv"), &SWEEP_COLUMNS, sweep_rows(d))?;
            }
            profile_plot = profile_plot.with(Series::line(
                n,
                p.cleat_x
                    .iter()
                    .copied()
                    .zip(p.dfy.iter().copied())
                    .collect(),
            ));
            let rel = |a: &[f64]| {
                let m = a.iter().copied().fold(0.0, f64::max).max(f64::MIN_POSITIVE);
                a.iter().map(|x| x / m).collect::<Vec<_>>()
            };
            amp_plot = amp_plot.with(Series::line(
                format!(
                    "{n}: predicted, {:.1} Hz, L = {:.3} m",
                    d.vertical_mode_hz, d.envelope_length_m
                ),
                pr.speeds_kmh
                    .iter()
                    .copied()
                    .zip(rel(&pr.amplitude_n))
                    .collect(),
            ));
            if !d.sweep_speeds_kmh.is_empty() {
                amp_plot = amp_plot.with(Series::points(
                    format!("{n}: sweep"),
                    d.sweep_speeds_kmh
                        .iter()
                        .copied()
                        .zip(rel(&d.line_amplitude_n))
                        .collect(),
                ));
            }
            let (a, b) = ribaric_band(d.ground);
            amp_plot = amp_plot.with_band(format!("Ribaric {n} dip"), a, b);
        }
        profile_plot.save(&ctx.out.path("profile"))?;
        amp_plot.save(&ctx.out.path("amplitude_vs_speed"))?;
        Ok(summary)
    }
}
