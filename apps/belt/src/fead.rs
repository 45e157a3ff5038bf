//! `flowmbd-belt fead`: a passenger-car front-end accessory drive with an automatic tensioner
//! over an engine-speed sweep (issue 17 item 5). The drive, the model and the sweep live in
//! `drives::fead`; this module reads the configuration, runs it and writes the results.

use drives::ModelKind;
use drives::fead::{FeadConfig, FeadFailureOrInvalid, FeadSummary, run_fead};
use flowmbd_cli::plot::{LinePlot, Series, Style};
use flowmbd_cli::{CommonArgs, Study, StudyContext, StudyError, set_given};

/// Command-line arguments.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Engine speeds [rpm], comma separated (replaces the configured sweep).
    #[arg(long, value_delimiter = ',')]
    pub rpm: Option<Vec<f64>>,
    /// Belt model (replaces `model`; `ancf` is slow: minutes per engine speed).
    #[arg(long, value_parser = crate::speed_loss::model_parser())]
    pub model: Option<ModelKind>,
}

impl Study for Args {
    type Config = FeadConfig;
    type Summary = FeadSummary;
    const NAME: &'static str = "fead";

    fn apply_overrides(&self, c: &mut FeadConfig) {
        set_given(&mut c.engine.speeds_rpm, self.rpm.clone());
        set_given(&mut c.model, self.model);
        // a relative trace file is the configuration file's neighbour (drives::crank_trace)
        if let (Some(t), Some(cfg)) = (&c.engine.trace, &self.common.config) {
            // absolute, so the config.toml written with the results still finds it
            let dir = cfg.parent().unwrap_or(std::path::Path::new(""));
            let dir = std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf());
            c.engine.trace = Some(t.resolved_against(&dir));
        }
    }

    fn run(&self, c: &FeadConfig, ctx: &mut StudyContext) -> Result<FeadSummary, StudyError> {
        // a crank trace is one operating point (drives::fead::EngineConfig::trace)
        let n = if c.engine.trace.is_some() {
            1
        } else {
            c.engine.speeds_rpm.len()
        };
        let progress = ctx.progress(n as f64, &format!("engine speeds ({})", c.model.name()));
        // the bar on a terminal; a line per engine speed otherwise (logs of long ANCF runs)
        let lines = !ctx.quiet && !std::io::IsTerminal::is_terminal(&std::io::stderr());
        let (start, mut seen) = (std::time::Instant::now(), 0usize);
        let result = run_fead(c, |p| {
            progress.set(p.point as f64 + p.t / p.duration);
            if lines && p.point > seen {
                seen = p.point;
                eprintln!(
                    "fead: {} of {n} engine speeds done ({:.0} s)",
                    p.point,
                    start.elapsed().as_secs_f64()
                );
            }
        });
        progress.finish();
        let s = match result {
            Ok(s) => s,
            Err(e) => {
                return Err(match *e {
                    FeadFailureOrInvalid::Invalid(f) => StudyError::Input(f),
                    FeadFailureOrInvalid::Build(b) => StudyError::numerical(b),
                    FeadFailureOrInvalid::Numerical(f) => StudyError::Numerical {
                        message: format!("fead sweep: {}", f.error),
                        partial: serde_json::to_value(&f.partial).ok(),
                    },
                });
            }
        };
        if !ctx.quiet {
            eprintln!("fead: {}", s.model_settings);
            for p in &s.points {
                if let Some(why) = &p.linearisation {
                    eprintln!(
                        "fead: {} rpm is outside the model's range: {why}",
                        p.engine_rpm
                    );
                }
                if let Some(why) = &p.caveat {
                    eprintln!("fead: {} rpm: {why}", p.engine_rpm);
                }
                if let Some(why) = &p.balance {
                    eprintln!("fead: {} rpm: {why}", p.engine_rpm);
                }
                if let Some(name) = &p.gross_slip_pulley {
                    eprintln!(
                        "fead: gross slip at {} rpm on pulley '{name}'",
                        p.engine_rpm
                    );
                }
            }
        }
        write_outputs(ctx, &s)?;
        Ok(s)
    }
}

/// CSV table and plots of the sweep.
fn write_outputs(ctx: &StudyContext, s: &FeadSummary) -> Result<(), StudyError> {
    let Some(first) = s.points.first() else {
        return Ok(());
    };
    let mut header: Vec<String> = vec![
        "engine_speed_rpm".into(),
        "belt_speed_m_per_s".into(),
        "gross_slip_flag".into(),
        "linearisation_valid_flag".into(),
    ];
    // the arm's columns and plot only for a layout with a tensioner (issue 35)
    let has_arm = first.arm_angle.is_some();
    if has_arm {
        header.splice(
            2..2,
            [
                "arm_angle_min_rad".into(),
                "arm_angle_mean_rad".into(),
                "arm_angle_max_rad".into(),
            ],
        );
    }
    for k in 0..first.spans.len() {
        header.push(format!("span{k}_tension_min_N"));
        header.push(format!("span{k}_tension_max_N"));
        header.push(format!("span{k}_frequency1_Hz"));
    }
    for k in 0..first.report.pulleys.len() {
        header.push(format!("pulley{k}_speed_loss_percent"));
        header.push(format!("pulley{k}_torque_N_m"));
        header.push(format!("pulley{k}_hub_load_x_N"));
        header.push(format!("pulley{k}_hub_load_y_N"));
        header.push(format!("pulley{k}_torque_residual_N_m"));
    }
    header.push("torque_residual_ratio".into());
    header.push("power_residual_ratio".into());
    let mut csv = ctx.out.csv("fead_sweep.csv", &header)?;
    for p in &s.points {
        let mut row = vec![p.engine_rpm, p.belt_speed];
        if has_arm {
            let a = p.arm_angle.unwrap_or(drives::fead::Extremes {
                min: f64::NAN,
                mean: f64::NAN,
                max: f64::NAN,
            });
            row.extend([a.min, a.mean, a.max]);
        }
        row.extend([
            f64::from(u8::from(p.gross_slip)),
            f64::from(u8::from(p.linearisation.is_none())),
        ]);
        for sp in &p.spans {
            let f1 = sp.frequency_1_hz.unwrap_or(f64::NAN);
            row.extend([sp.tension.min, sp.tension.max, f1]);
        }
        for (k, pl) in p.report.pulleys.iter().enumerate() {
            row.extend([
                p.speed_loss_percent[k],
                pl.torque_n_m,
                pl.hub_load_n[0],
                pl.hub_load_n[1],
                pl.torque_residual_n_m,
            ]);
        }
        row.push(p.report.balances.torque_residual_rel);
        row.push(p.report.balances.power_residual_rel);
        csv.row(&row)?;
    }
    csv.finish()?;
    // decoupled accessories (belt::decoupler): one row per point and decoupler
    if s.points.iter().any(|p| !p.decouplers.is_empty()) {
        let mut dc = ctx.out.csv(
            "fead_decouplers.csv",
            &[
                "engine_speed_rpm",
                "pulley_index",
                "accessory_speed_min_rad_per_s",
                "accessory_speed_mean_rad_per_s",
                "accessory_speed_max_rad_per_s",
                "spring_torque_min_N_m",
                "spring_torque_mean_N_m",
                "spring_torque_max_N_m",
                "overrunning_ratio",
                "clutch_engaged_at_end_flag",
            ],
        )?;
        for p in &s.points {
            for d in &p.decouplers {
                let k = s.pulleys.iter().position(|n| *n == d.pulley).unwrap_or(0);
                let (a, m) = (&d.accessory_speed, &d.spring_torque);
                dc.row(&[
                    p.engine_rpm,
                    k as f64,
                    a.min,
                    a.mean,
                    a.max,
                    m.min,
                    m.mean,
                    m.max,
                    d.overrunning_fraction.unwrap_or(f64::NAN),
                    match d.clutch_at_end {
                        Some(belt::ClutchState::Engaged) => 1.0,
                        Some(belt::ClutchState::Overrunning) => 0.0,
                        None => f64::NAN,
                    },
                ])?;
            }
        }
        dc.finish()?;
    }
    let rpm: Vec<f64> = s.points.iter().map(|p| p.engine_rpm).collect();
    let series = |name: String, y: Vec<f64>| Series {
        name,
        points: rpm.iter().copied().zip(y).collect(),
        style: Style::LinePoints,
    };
    // tensioner arm motion
    if has_arm {
        let mut arm = LinePlot::new(
            "Tensioner arm angle",
            "engine speed [rpm]",
            "arm angle [deg]",
        );
        let nan = drives::fead::Extremes {
            min: f64::NAN,
            mean: f64::NAN,
            max: f64::NAN,
        };
        for (name, f) in [
            (
                "min",
                (|e: &drives::fead::Extremes| e.min) as fn(&drives::fead::Extremes) -> f64,
            ),
            ("mean", |e| e.mean),
            ("max", |e| e.max),
        ] {
            arm.series.push(series(
                name.into(),
                s.points
                    .iter()
                    .map(|p| f(&p.arm_angle.unwrap_or(nan)).to_degrees())
                    .collect(),
            ));
        }
        arm.save(&ctx.out.path("arm_angle"))?;
    }
    // span tension extremes
    let mut ten = LinePlot::new("Span tension extremes", "engine speed [rpm]", "tension [N]");
    for (k, sp) in first.spans.iter().enumerate() {
        let name = format!("{} → {}", sp.from, sp.to);
        ten.series.push(series(
            format!("{name} min"),
            s.points.iter().map(|p| p.spans[k].tension.min).collect(),
        ));
        ten.series.push(series(
            format!("{name} max"),
            s.points.iter().map(|p| p.spans[k].tension.max).collect(),
        ));
    }
    ten.save(&ctx.out.path("span_tension"))?;
    // slip per pulley
    let mut slip = LinePlot::new(
        "Speed loss against the crank",
        "engine speed [rpm]",
        "1 − ωR/(ω_c R_c) [%]",
    );
    for (k, name) in s.pulleys.iter().enumerate().skip(1) {
        slip.series.push(series(
            name.clone(),
            s.points.iter().map(|p| p.speed_loss_percent[k]).collect(),
        ));
    }
    slip.save(&ctx.out.path("slip"))?;
    // Campbell diagram: span frequencies and engine orders
    let mut camp = LinePlot::new(
        "Campbell diagram: span first transverse frequency and engine orders",
        "engine speed [rpm]",
        "frequency [Hz]",
    );
    for (k, sp) in first.spans.iter().enumerate() {
        camp.series.push(series(
            format!("span {} → {}", sp.from, sp.to),
            s.points
                .iter()
                .map(|p| p.spans[k].frequency_1_hz.unwrap_or(f64::NAN))
                .collect(),
        ));
    }
    for &o in &s.orders {
        camp.series.push(Series::line(
            format!("order {o}"),
            rpm.iter().map(|&r| (r, o * r / 60.0)).collect(),
        ));
    }
    camp.save(&ctx.out.path("campbell"))?;
    Ok(())
}
