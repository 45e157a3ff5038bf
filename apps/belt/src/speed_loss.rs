//! `flowmbd-belt speed-loss`: angular speed loss Δω = ω₁ − ω₂ of the two-pulley drive of
//! Ribaric Table 6-1 against the load torque, at the driver speeds of Figs. 6-6 and 6-7, with
//! Bechtel's analytical line (6.3). The models, the procedure and the study live in `drives`;
//! this module reads the configuration, calls [`run_case`] per driver speed and writes the
//! results.

use crate::wrap_csv;
use clap::builder::{PossibleValuesParser, TypedValueParser};
use drives::speed_loss::{Sample, SweepFailure};
use drives::speed_loss_study::{
    CaseFailure, SpeedLossStudyConfig, SummaryCase as Case, SummaryPoint, run_case as study_case,
};
use drives::{ModelKind, SpeedLossCase, SpeedLossSummary as Summary};
use flowmbd_cli::plot::{LinePlot, Series, Style};
use flowmbd_cli::{CommonArgs, Study, StudyContext, StudyError, set_given};
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

pub(crate) fn model_parser() -> impl TypedValueParser<Value = ModelKind> {
    PossibleValuesParser::new(ModelKind::ALL.map(ModelKind::name)).map(|s| {
        // the possible values are exactly the names FromStr accepts
        s.parse::<ModelKind>().unwrap_or_default()
    })
}

/// Command-line arguments.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Driver speed [rad/s] (replaces the configured list of speeds).
    #[arg(long)]
    pub omega: Option<f64>,
    /// Load torques [N m], comma separated (e.g. 0,5,10).
    #[arg(long, value_delimiter = ',')]
    pub torques: Option<Vec<f64>>,
    /// Belt model.
    #[arg(long, value_parser = model_parser())]
    pub model: Option<ModelKind>,
}

/// Study configuration (defined in `drives`, shared with the Python package).
pub type Config = SpeedLossStudyConfig;

fn sweep_error(omega: f64, f: SweepFailure) -> StudyError {
    StudyError::Numerical {
        message: format!("ω₁ = {omega} rad/s: {}", f.error),
        partial: Some(serde_json::json!({
            "omega_driver": omega,
            "points": f.points.iter().map(SummaryPoint::new).collect::<Vec<_>>(),
        })),
    }
}

/// The contact points of every wrap at every operating point of `case` (`wrap_omega_*.csv`).
fn write_wrap(ctx: &StudyContext, case: &SpeedLossCase) -> Result<(), StudyError> {
    let header: Vec<&str> = std::iter::once("torque_N_m")
        .chain(wrap_csv::COLUMNS)
        .collect();
    let mut csv = ctx
        .out
        .csv(&format!("wrap_omega_{:.1}.csv", case.omega_driver), &header)?;
    for p in &case.points {
        for w in &p.wrap {
            let mu = case.friction_coefficients[w.pulley];
            csv.row(&[&[p.torque][..], &wrap_csv::row(w, mu)].concat())?;
        }
    }
    csv.finish()?;
    Ok(())
}

/// Say on stderr where friction could not hold the load and where the linearised models stop
/// holding (the points are results; the study goes on).
fn report_slips(model: ModelKind, case: &SpeedLossCase) {
    for p in &case.points {
        if let Some(g) = &p.gross_slip {
            eprintln!(
                "flowmbd-belt speed-loss: {} belt, ω₁ = {} rad/s, load {} N m: gross slip at \
                 pulley '{}' (index {}) at t = {:.4} s: {}",
                model.name(),
                case.omega_driver,
                p.torque,
                g.name,
                g.pulley,
                g.time,
                g.criterion
            );
        }
        if let Some(why) = &p.linearisation {
            eprintln!(
                "flowmbd-belt speed-loss: {} belt, ω₁ = {} rad/s, load {} N m: results not \
                 reported, the linearisation about T0 does not hold: {why}",
                model.name(),
                case.omega_driver,
                p.torque
            );
        }
        if let Some(why) = &p.caveat {
            eprintln!(
                "flowmbd-belt speed-loss: {} belt, ω₁ = {} rad/s, load {} N m: {why}",
                model.name(),
                case.omega_driver,
                p.torque
            );
        }
        if let Some(why) = &p.balance {
            eprintln!(
                "flowmbd-belt speed-loss: {} belt, ω₁ = {} rad/s, load {} N m: {why}",
                model.name(),
                case.omega_driver,
                p.torque
            );
        }
    }
}

/// One driver speed: run the study's case ([`study_case`]) writing the history CSV, then the
/// ANCF mapping (if any) and the wrap distributions. `(case, number of coordinates)`.
fn run_case(
    c: &Config, omega: f64, ctx: &StudyContext, done: &AtomicUsize, report: &(dyn Fn(usize) + Sync),
) -> Result<(Case, usize), StudyError> {
    let start = std::time::Instant::now();
    let name = format!("history_omega_{omega:.1}.csv");
    let columns = [
        "t_s",
        "omega_driver_rad_per_s",
        "omega_driven_rad_per_s",
        "load_torque_N_m",
        "belt_speed_m_per_s",
    ];
    let mut csv = ctx.out.csv(&name, &columns)?;
    let mut io_err = None;
    let mut k = 0usize;
    let mut found = 0usize;
    let every = c.history_every;
    let result = study_case(c, omega, |_st, s: Sample| {
        k += 1;
        let row = [s.t, s.omega_driver, s.omega_driven, s.load, s.belt_speed];
        if k.is_multiple_of(every)
            && let Err(e) = csv.row(&row)
        {
            io_err.get_or_insert(e);
        }
        if s.points > found {
            found = s.points;
            report(done.fetch_add(1, Ordering::Relaxed) + 1);
        }
    });
    csv.flush()?;
    if let Some(e) = io_err {
        return Err(e.into());
    }
    let (case, coordinates, mapping) = result.map_err(|f| match f {
        CaseFailure::Input(field) => StudyError::Input(field),
        CaseFailure::Build(e) => StudyError::numerical(e),
        CaseFailure::Sweep(f) => sweep_error(omega, f),
    })?;
    if let Some(mapping) = mapping {
        // the derived parameters of the drive → ANCF mapping, for the record
        ctx.out
            .write_json(&format!("ancf_mapping_omega_{omega:.1}.json"), &mapping)?;
    }
    write_wrap(ctx, &case)?;
    report_slips(c.model, &case);
    // the last point ends the sweep, after the last observer call
    let extra = case.points.len().saturating_sub(found);
    report(done.fetch_add(extra, Ordering::Relaxed) + extra);
    Ok((Case::new(case, start.elapsed().as_secs_f64()), coordinates))
}

impl Study for Args {
    type Config = Config;
    type Summary = Summary;
    const NAME: &'static str = "speed-loss";

    /// Per driver speed and load: Δω, Bechtel's Δω (6.3), the span tensions, and the torque
    /// and power balance residuals (or why a point has no numbers).
    fn result_table(&self, s: &Summary) -> Option<String> {
        Some(result_table(s))
    }

    fn apply_overrides(&self, c: &mut Config) {
        if let Some(w) = self.omega {
            c.omegas = vec![w];
        }
        set_given(&mut c.procedure.torques, self.torques.clone());
        set_given(&mut c.model, self.model);
    }

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let start = std::time::Instant::now();
        let total = c.omegas.len() * c.procedure.torques.len();
        let progress = ctx.progress(total as f64, "speed loss");
        let done = AtomicUsize::new(0);
        let report = |n: usize| progress.set(n as f64);
        let ctx_ref: &StudyContext = ctx;
        // one case per speed, in parallel; rayon keeps the configured order of speeds
        let results: Vec<Result<(Case, usize), StudyError>> = c
            .omegas
            .par_iter()
            .map(|&w| run_case(c, w, ctx_ref, &done, &report))
            .collect();
        progress.finish();
        let mut cases = Vec::new();
        let mut modes = 0;
        for r in results {
            let (case, m) = r?;
            modes = m;
            cases.push(case);
        }
        let mut table = ctx.out.csv(
            "speed_loss.csv",
            &[
                "omega_driver_rad_per_s",
                "torque_N_m",
                "delta_omega_rad_per_s",
                "delta_omega_bechtel_rad_per_s",
            ],
        )?;
        let mut plot = LinePlot::new(
            "Angular speed loss (Ribaric Table 6-1, T0 = 310 N)",
            "load torque [N m]",
            "Δω = ω₁ − ω₂ [rad/s]",
        );
        let mut ops = ctx.out.csv(
            "operating_points.csv",
            &[
                "omega_driver_rad_per_s",
                "torque_N_m",
                "delta_omega_rad_per_s",
                "tension_tight_N",
                "tension_slack_N",
                "gross_slip_flag",
                "slip_arc_driver_rad",
                "slip_arc_driven_rad",
                "adhesion_arc_driver_rad",
                "adhesion_arc_driven_rad",
                "slip_velocity_max_driven_m_per_s",
                "hub_load_driver_x_N",
                "hub_load_driver_y_N",
                "hub_load_driven_x_N",
                "hub_load_driven_y_N",
                "torque_driver_N_m",
                "torque_driven_N_m",
                "span0_vibration_amplitude_m",
                "span1_vibration_amplitude_m",
                "linearisation_valid_flag",
            ],
        )?;
        let nan = f64::NAN;
        for case in &cases {
            for (p, a) in case.points.iter().zip(&case.analytical) {
                table.row(&[
                    case.omega_driver,
                    p.torque,
                    p.delta_omega.unwrap_or(nan),
                    *a,
                ])?;
                let pl = |k: usize| p.pulleys.as_ref().and_then(|v| v.get(k));
                let sp = |k: usize| {
                    p.spans
                        .as_ref()
                        .and_then(|v| v.get(k))
                        .and_then(|s| s.vibration_amplitude_m)
                        .unwrap_or(nan)
                };
                ops.row(&[
                    case.omega_driver,
                    p.torque,
                    p.delta_omega.unwrap_or(nan),
                    p.tension_tight.unwrap_or(nan),
                    p.tension_slack.unwrap_or(nan),
                    f64::from(u8::from(p.gross_slip)),
                    p.slip_arc_driver_rad.unwrap_or(nan),
                    p.slip_arc_driven_rad.unwrap_or(nan),
                    pl(0).map_or(nan, |q| q.adhesion_arc_rad),
                    pl(1).map_or(nan, |q| q.adhesion_arc_rad),
                    pl(1).map_or(nan, |q| q.slip_velocity_max_m_s),
                    pl(0).map_or(nan, |q| q.hub_load_n[0]),
                    pl(0).map_or(nan, |q| q.hub_load_n[1]),
                    pl(1).map_or(nan, |q| q.hub_load_n[0]),
                    pl(1).map_or(nan, |q| q.hub_load_n[1]),
                    pl(0).map_or(nan, |q| q.torque_n_m),
                    pl(1).map_or(nan, |q| q.torque_n_m),
                    sp(0),
                    sp(1),
                    f64::from(u8::from(p.linearisation_valid)),
                ])?;
            }
            let shown = |p: &&SummaryPoint| p.delta_omega.is_some();
            plot.series.push(Series {
                name: format!("{}, ω₁ = {} rad/s", c.model.name(), case.omega_driver),
                points: case
                    .points
                    .iter()
                    .filter(shown)
                    .map(|p| (p.torque, p.delta_omega.unwrap_or(nan)))
                    .collect(),
                style: Style::LinePoints,
            });
            plot.series.push(Series::line(
                format!("Bechtel (6.3), ω₁ = {} rad/s", case.omega_driver),
                case.points
                    .iter()
                    .zip(&case.analytical)
                    .map(|(p, a)| (p.torque, *a))
                    .collect(),
            ));
        }
        table.finish()?;
        ops.finish()?;
        plot.save(&ctx.out.path("speed_loss"))?;
        Ok(Summary::new(
            c.model,
            cases,
            modes,
            start.elapsed().as_secs_f64(),
        ))
    }
}

/// The table [`Study::result_table`] prints.
fn result_table(s: &Summary) -> String {
    use std::fmt::Write;
    let mut t = format!(
        "speed loss, {} belt ({} driver speed{})\n{:>9} {:>8} {:>11} {:>11} {:>9} {:>9} {:>10} {:>10}\n",
        s.model.name(),
        s.cases.len(),
        if s.cases.len() == 1 { "" } else { "s" },
        "ω₁ rad/s",
        "M N m",
        "Δω rad/s",
        "Bechtel",
        "T₁ N",
        "T₂ N",
        "torque bal",
        "power bal",
    );
    let num = |x: Option<f64>, prec: usize| x.map_or("-".to_string(), |v| format!("{v:.prec$}"));
    for c in &s.cases {
        for (k, p) in c.points.iter().enumerate() {
            // relative residuals of an unloaded drive divide by nothing: not printed
            let rel = |x: f64| {
                if p.torque == 0.0 {
                    "-".to_string()
                } else {
                    format!("{:.2}%", 100.0 * x)
                }
            };
            let _ = write!(
                t,
                "{:>9.1} {:>8.2} {:>11} {:>11} {:>9} {:>9} {:>10} {:>10}",
                c.omega_driver,
                p.torque,
                num(p.delta_omega, 5),
                num(c.analytical.get(k).copied(), 5),
                num(p.tension_tight, 1),
                num(p.tension_slack, 1),
                rel(p.balances.torque_residual_rel),
                rel(p.balances.power_residual_rel),
            );
            if p.gross_slip {
                t.push_str("  gross slip");
            } else if let Some(why) = &p.linearisation {
                let _ = write!(t, "  not valid: {why}");
            }
            t.push('\n');
        }
    }
    t
}
