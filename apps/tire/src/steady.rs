//! `flowmbd-tire steady`: steady-state force and moment characteristics of the rolling tire on
//! a flat (or height-grid) road (issue 38): side force `F_y(α)`, aligning moment `M_z(α)`,
//! cornering stiffness and pneumatic trail over a slip-angle sweep, `F_x(κ)` over a drive/brake
//! torque sweep, camber thrust `F_y(γ)` and `M_x(γ)` over a camber sweep ([`tire::steady`]).

use crate::common::{run_reduced, tire_err};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, Study, StudyContext, StudyError, set_given};
use tire::steady::{STEADY_COLUMNS, steady_row};
use tire::{SteadyStudyConfig as Config, SteadySummary as Summary, run_steady, steady_summary};

/// Command-line arguments.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Coulomb friction coefficient (overrides `rig.rolling.friction`).
    #[arg(long)]
    friction: Option<f64>,
    /// Speed [km/h] (overrides `rig.speed_kmh`).
    #[arg(long)]
    speed: Option<f64>,
}

impl Study for Args {
    type Config = Config;
    type Summary = Summary;
    const NAME: &'static str = "steady";

    fn apply_overrides(&self, c: &mut Config) {
        set_given(&mut c.rig.rolling.friction, self.friction);
        set_given(&mut c.rig.speed_kmh, self.speed);
    }

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let (red, r) = run_reduced(ctx, &c.tire, 1, "steady sweep", |red, bar| {
            run_steady(red, c, bar).map_err(tire_err)
        })?;
        let mut s = steady_summary(c, &r);
        ctx.out.write_csv(
            "points.csv",
            &STEADY_COLUMNS,
            s.points.iter().map(|p| steady_row(p).to_vec()),
        )?;
        // F_y(α) and M_z(α) with the free-rolling point, in the order of α
        let mut by_alpha: Vec<(f64, f64, f64)> = std::iter::once(&r.free_rolling)
            .chain(&r.slip)
            .map(|p| (p.slip_angle_deg, p.loads.fy, p.loads.mz))
            .collect();
        by_alpha.sort_by(|a, b| a.0.total_cmp(&b.0));
        LinePlot::new("Side force against slip angle", "alpha [deg]", "Fy [N]")
            .with(Series::line(
                "Fy",
                by_alpha.iter().map(|p| (p.0, p.1)).collect(),
            ))
            .save(&ctx.out.path("fy_alpha"))?;
        LinePlot::new(
            "Aligning moment against slip angle",
            "alpha [deg]",
            "Mz [N m]",
        )
        .with(Series::line(
            "Mz",
            by_alpha.iter().map(|p| (p.0, p.2)).collect(),
        ))
        .save(&ctx.out.path("mz_alpha"))?;
        // F_x(κ): the torque points (κ reached through the wheel's inertia) and the
        // prescribed-spin points (κ set), each with the free-rolling point
        let by_kappa = |pts: &[tire::SteadyPoint]| {
            let mut v: Vec<(f64, f64)> = std::iter::once(&r.free_rolling)
                .chain(pts)
                .map(|p| (p.kappa, p.loads.fx))
                .collect();
            v.sort_by(|a, b| a.0.total_cmp(&b.0));
            v
        };
        let mut fx = LinePlot::new(
            "Longitudinal force against longitudinal slip",
            "kappa [-]",
            "Fx [N]",
        );
        for (name, pts) in [
            ("Fx, drive torque", &r.torque),
            ("Fx, prescribed spin", &r.prescribed),
        ] {
            if !pts.is_empty() || (r.torque.is_empty() && r.prescribed.is_empty()) {
                fx = fx.with(Series::line(name, by_kappa(pts)));
            }
        }
        fx.save(&ctx.out.path("fx_kappa"))?;
        if !r.camber.is_empty() {
            // F_y(γ) and M_x(γ) (W-axis orientation) with the free-rolling point
            let mut by_gamma: Vec<(f64, f64, f64)> = std::iter::once(&r.free_rolling)
                .chain(&r.camber)
                .map(|p| (p.camber_deg, p.loads.fy, p.loads.mx))
                .collect();
            by_gamma.sort_by(|a, b| a.0.total_cmp(&b.0));
            LinePlot::new(
                "Camber thrust and overturning moment against camber angle (W-axis)",
                "gamma [deg]",
                "Fy [N], Mx [N m]",
            )
            .with(Series::line(
                "Fy",
                by_gamma.iter().map(|p| (p.0, p.1)).collect(),
            ))
            .with(Series::line(
                "Mx",
                by_gamma.iter().map(|p| (p.0, p.2)).collect(),
            ))
            .save(&ctx.out.path("fy_gamma"))?;
        }
        if let Some(m) = s.magic_formula.as_mut() {
            write_fit(m, &r, &red, c, ctx)?;
        }
        Ok(s)
    }
}

/// Write `tire.tir` and the data-with-fit plots of the Magic Formula fit of the summary, and
/// put the file's path into it.
fn write_fit(
    m: &mut tire::magic_formula::MfSummary, r: &tire::SteadyResult, red: &tire::ReducedTire,
    c: &Config, ctx: &mut StudyContext,
) -> Result<(), StudyError> {
    let fit = m.fit;
    let text = tire::steady_tir(&fit, red, c);
    let path = ctx.out.write_text("tire.tir", &text)?;
    m.tir = Some(path.display().to_string());
    // data points and fitted curves (the fit sampled finely over the data's range)
    let l = &fit.lateral;
    let lateral = |load: fn(&tire::WheelLoads) -> f64| -> Vec<(f64, f64)> {
        std::iter::once(&r.free_rolling)
            .chain(&r.slip)
            .map(|p| (p.slip_angle_deg, load(&p.loads)))
            .collect()
    };
    fit_plot(
        ctx,
        "mf_fy_alpha",
        ("Side force", "alpha [deg]", "Fy [N]", "Fy"),
        lateral(|w| w.fy),
        |a| l.fy.eval(a.to_radians().tan()),
    )?;
    fit_plot(
        ctx,
        "mf_mz_alpha",
        ("Aligning moment", "alpha [deg]", "Mz [N m]", "Mz"),
        lateral(|w| w.mz),
        |a| tire::magic_formula::aligning_moment(&l.fy, &l.trail, a.to_radians()),
    )?;
    if let Some(x) = &fit.longitudinal {
        let data = std::iter::once(&r.free_rolling)
            .chain(&r.torque)
            .chain(&r.prescribed)
            .map(|p| (p.kappa, p.loads.fx))
            .collect();
        fit_plot(
            ctx,
            "mf_fx_kappa",
            ("Longitudinal force", "kappa [-]", "Fx [N]", "Fx"),
            data,
            |k| x.fx.eval(k),
        )?;
    }
    Ok(())
}

/// Plot `file`: the simulated `data` as points and the fitted `curve` sampled at 201 points over
/// the data's range; `labels` = (title, x axis, y axis, quantity).
fn fit_plot(
    ctx: &mut StudyContext, file: &str, labels: (&str, &str, &str, &str), data: Vec<(f64, f64)>,
    curve: impl Fn(f64) -> f64,
) -> Result<(), StudyError> {
    let (title, xl, yl, q) = labels;
    let (lo, hi) = data
        .iter()
        .fold((f64::MAX, f64::MIN), |a, p| (a.0.min(p.0), a.1.max(p.0)));
    let line = (0..=200)
        .map(|i| lo + (hi - lo) * i as f64 / 200.0)
        .map(|x| (x, curve(x)))
        .collect();
    LinePlot::new(format!("{title}: data and Magic Formula fit"), xl, yl)
        .with(Series::points(format!("{q} (simulation)"), data))
        .with(Series::line(format!("{q} (MF fit)"), line))
        .save(&ctx.out.path(file))?;
    Ok(())
}
