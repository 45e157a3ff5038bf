//! `flowmbd-belt design`: the FEAD's steady design without time stepping (issue 36): span
//! tensions, the tensioner arm, slip arcs, hub loads and slip margins at every engine speed,
//! the drive's rotational and span modes and its Campbell diagram, with warnings and errors
//! before any time stepping. The computation lives in `drives::fead_design`; this module reads
//! the configuration (the `fead` study's `[drive]` and `[engine]` tables plus `[design]`),
//! runs it and writes the results.
//!
//! Output folder: `design_points.csv` (per engine speed), `design_spans.csv` and
//! `design_pulleys.csv` (one row per engine speed and span or pulley, travel order),
//! `rotational_modes.csv`, `coupled_modes.csv` (the spans' transverse motion coupled with the
//! rotational model through the tensioner arm, `drives::fead_design::coupled`), `campbell.csv`
//! (every curve on the grid), `crossings.csv`, and the plots `hub_loads.png/svg` (polar plot:
//! every pulley's hub-load vector in the (F_x, F_y) plane over the engine speeds, equal axis
//! scales), `slip_margins.png/svg` and `campbell.png/svg` (the coupled modes and the engine
//! orders with their crossings; legend beside the chart).

use drives::fead_design::{DesignConfig, DesignPoint, DesignSummary, Severity, run_design};
use flowmbd_cli::plot::{Legend, LinePlot, Series, Style};
use flowmbd_cli::{CommonArgs, Study, StudyContext, StudyError, set_given};

/// Command-line arguments.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Engine speeds [rpm], comma separated (replaces the configured operating points).
    #[arg(long, value_delimiter = ',')]
    pub rpm: Option<Vec<f64>>,
}

impl Study for Args {
    type Config = DesignConfig;
    type Summary = DesignSummary;
    const NAME: &'static str = "design";

    fn apply_overrides(&self, c: &mut DesignConfig) {
        set_given(&mut c.engine.speeds_rpm, self.rpm.clone());
    }

    fn run(&self, c: &DesignConfig, ctx: &mut StudyContext) -> Result<DesignSummary, StudyError> {
        let s = run_design(c).map_err(StudyError::Input)?;
        if !ctx.quiet {
            for f in &s.findings {
                let tag = match f.severity {
                    Severity::Error => "error",
                    Severity::Warning => "warning",
                };
                eprintln!("design: {tag}: {}", f.message);
            }
        }
        write_outputs(ctx, &s, c.design.slip_margin_warning)?;
        Ok(s)
    }
}

/// Write `name`: the engine speed, the columns `fixed` and `extra`; a row per engine speed and
/// element of `items(point)` (travel order) holding the speed and `row(point, index, element)`.
fn per_speed_csv<T>(
    ctx: &StudyContext, name: &str, fixed: &[&str], extra: impl Iterator<Item = String>,
    s: &DesignSummary, items: impl Fn(&DesignPoint) -> &[T],
    row: impl Fn(&DesignPoint, usize, &T) -> Vec<f64>,
) -> Result<(), StudyError> {
    let header: Vec<String> = std::iter::once("engine_speed_rpm")
        .chain(fixed.iter().copied())
        .map(str::to_string)
        .chain(extra)
        .collect();
    let (items, row) = (&items, &row);
    let rows = s.points.iter().flat_map(|p| {
        items(p).iter().enumerate().map(move |(i, x)| {
            let mut r = vec![p.engine_rpm];
            r.extend(row(p, i, x));
            r
        })
    });
    ctx.out.write_csv(name, &header, rows)?;
    Ok(())
}

/// CSV tables and plots.
fn write_outputs(ctx: &StudyContext, s: &DesignSummary, warning: f64) -> Result<(), StudyError> {
    let flag = |b: bool| f64::from(u8::from(b));
    let opt = |x: Option<f64>| x.unwrap_or(f64::NAN);
    // per engine speed
    let mut csv = ctx.out.csv(
        "design_points.csv",
        &[
            "engine_speed_rpm",
            "belt_speed_m_per_s",
            "centrifugal_tension_N",
            "belt_elongation_m",
            "arm_angle_deg",
            "arm_swing_deg",
            "arm_stop_margin_deg",
            "arm_spring_moment_N_m",
            "idler_force_N",
            "arm_on_stop_flag",
        ],
    )?;
    for p in &s.points {
        let a = p.arm.as_ref();
        csv.row(&[
            p.engine_rpm,
            p.belt_speed_m_per_s,
            p.centrifugal_tension_n,
            p.belt_elongation_m,
            opt(a.map(|a| a.angle_deg)),
            opt(a.map(|a| a.swing_deg)),
            opt(a.map(|a| a.stop_margin_deg)),
            opt(a.map(|a| a.spring_moment_n_m)),
            opt(a.map(|a| a.idler_force_magnitude_n)),
            flag(a.is_some_and(|a| a.on_stop)),
        ])?;
    }
    csv.finish()?;
    // spans
    let harmonics = s
        .points
        .first()
        .and_then(|p| p.spans.first())
        .map_or(0, |sp| sp.modes.frequencies_hz.len());
    per_speed_csv(
        ctx,
        "design_spans.csv",
        &[
            "span_index",
            "length_m",
            "tension_N",
            "effective_tension_N",
            "tight_flag",
            "stiffness_N_per_m",
            "wrap_compliance_m_per_N",
            "series_stiffness_N_per_m",
            "coupled_through_arm_flag",
        ],
        (1..=harmonics).map(|n| format!("frequency{n}_Hz")),
        s,
        |p| &p.spans[..],
        |_, k, sp| {
            let mut row = vec![
                k as f64,
                sp.length_m,
                sp.tension_n,
                sp.effective_tension_n,
                flag(sp.side == "tight"),
                sp.stiffness_n_per_m,
                sp.wrap_compliance_m_per_n,
                sp.series_stiffness_n_per_m,
                flag(sp.modes.coupled_through_arm),
            ];
            row.extend(sp.modes.frequencies_hz.iter().map(|f| opt(*f)));
            row
        },
    )?;
    per_speed_csv(
        ctx,
        "design_pulleys.csv",
        &[
            "pulley_index",
            "wrap_deg",
            "speed_rad_per_s",
            "torque_N_m",
            "tension_in_N",
            "tension_out_N",
            "friction_coefficient_ratio",
            "adhesion_arc_deg",
            "slip_arc_deg",
            "capacity_N_m",
            "slip_margin_ratio",
            "hub_load_x_N",
            "hub_load_y_N",
            "hub_load_N",
            "hub_load_direction_deg",
        ],
        std::iter::empty(),
        s,
        |p| &p.pulleys[..],
        |_, k, pl| {
            vec![
                k as f64,
                pl.wrap_deg,
                pl.speed_rad_per_s,
                pl.torque_n_m,
                pl.tension_in_n,
                pl.tension_out_n,
                pl.friction_coefficient,
                pl.adhesion_arc_deg,
                pl.slip_arc_deg,
                pl.capacity_n_m,
                opt(pl.slip_margin),
                pl.hub_load_n[0],
                pl.hub_load_n[1],
                pl.hub_load_magnitude_n,
                pl.hub_load_direction_deg,
            ]
        },
    )?;
    // rotational modes
    let dofs = s.points.first().map_or(0, |p| p.rotational_dofs.len());
    per_speed_csv(
        ctx,
        "rotational_modes.csv",
        &["mode", "frequency_Hz"],
        (0..dofs).map(|i| format!("dof{i}_energy_share")),
        s,
        |p| &p.rotational_modes[..],
        |_, i, m| {
            let mut row = vec![(i + 1) as f64, m.frequency_hz];
            row.extend(m.energy_share.iter().copied());
            row
        },
    )?;
    // coupled modes
    let parts = s.points.first().map_or(0, |p| p.coupled_parts.len());
    per_speed_csv(
        ctx,
        "coupled_modes.csv",
        &["mode", "frequency_Hz", "dominant_part_index"],
        (0..parts).map(|i| format!("part{i}_energy_share")),
        s,
        |p| &p.coupled_modes[..],
        |p, i, m| {
            let dom = p
                .coupled_parts
                .iter()
                .position(|x| *x == m.dominant)
                .map_or(f64::NAN, |k| k as f64);
            let mut row = vec![(i + 1) as f64, m.frequency_hz, dom];
            row.extend(m.energy_share.iter().copied());
            row
        },
    )?;
    // Campbell diagram and crossings
    let c = &s.campbell;
    let mut header: Vec<String> = vec!["engine_speed_rpm".into()];
    header.extend((0..c.curves.len()).map(|i| format!("curve{i}_Hz")));
    let mut csv = ctx.out.csv("campbell.csv", &header)?;
    for (i, &r) in c.engine_rpm.iter().enumerate() {
        let mut row = vec![r];
        row.extend(c.curves.iter().map(|cv| opt(cv.frequencies_hz[i])));
        csv.row(&row)?;
    }
    csv.finish()?;
    let mut csv = ctx.out.csv(
        "crossings.csv",
        &[
            "curve_index",
            "engine_order_ratio",
            "engine_speed_rpm",
            "frequency_Hz",
        ],
    )?;
    for x in &c.crossings {
        let idx = c
            .curves
            .iter()
            .position(|cv| cv.name == x.curve)
            .unwrap_or(0);
        csv.row(&[idx as f64, x.order, x.engine_rpm, x.frequency_hz])?;
    }
    csv.finish()?;
    hub_polar(s).save(&ctx.out.path("hub_loads"))?;
    slip_margin_bars(s, warning).save(&ctx.out.path("slip_margins"))?;
    // the coupled modes (rotational and transverse together; the separate models' curves are
    // in campbell.csv), the orders and their crossings, the legend beside the chart
    let mut camp = LinePlot::new(
        "Campbell diagram: coupled modes, engine orders",
        "engine speed [rpm]",
        "frequency [Hz]",
    )
    .with_legend(Legend::Outside);
    for cv in c.curves.iter().filter(|cv| cv.kind == "coupled") {
        camp.series.push(Series::line(
            cv.name.clone(),
            c.engine_rpm
                .iter()
                .zip(&cv.frequencies_hz)
                .filter_map(|(&r, f)| f.map(|f| (r, f)))
                .collect(),
        ));
    }
    for &o in &c.orders {
        camp.series.push(Series::line(
            format!("order {o}"),
            c.engine_rpm.iter().map(|&r| (r, o * r / 60.0)).collect(),
        ));
    }
    let coupled: Vec<(f64, f64)> = c
        .crossings
        .iter()
        .filter(|x| x.curve.starts_with("coupled mode"))
        .map(|x| (x.engine_rpm, x.frequency_hz))
        .collect();
    if !coupled.is_empty() {
        camp.series.push(Series::points("crossings", coupled));
    }
    camp.save(&ctx.out.path("campbell"))?;
    Ok(())
}

/// Polar plot of the hub loads (`drives::fead_design`: the belt's force on each pulley): per
/// pulley one curve (one colour) from the origin to its first speed's force vector `(F_x, F_y)`,
/// then through the vectors of the other engine speeds in order, equal scales on both axes so that
/// directions and magnitudes read true.
fn hub_polar(s: &DesignSummary) -> LinePlot {
    let speeds: Vec<String> = s
        .points
        .iter()
        .map(|p| format!("{}", p.engine_rpm))
        .collect();
    let mut hub = LinePlot::new(
        format!(
            "Hub loads (force of the belt on each pulley) at {} rpm",
            speeds.join(", ")
        ),
        "F_x [N]",
        "F_y [N]",
    )
    .with_equal_axes()
    .with_legend(Legend::Outside);
    for (k, name) in s.pulleys.iter().enumerate() {
        let pts: Vec<(f64, f64)> = s
            .points
            .iter()
            .map(|p| (p.pulleys[k].hub_load_n[0], p.pulleys[k].hub_load_n[1]))
            .collect();
        // one colour per pulley: the ray from the origin to the first speed's vector, then
        // the curve through the others
        let mut line = vec![(0.0, 0.0)];
        line.extend(pts);
        hub.series.push(Series {
            name: name.clone(),
            points: line,
            style: Style::LinePoints,
        });
    }
    hub.series
        .push(Series::points("origin (no load)", vec![(0.0, 0.0)]));
    hub
}

/// Bar chart of the slip margins (capacity over torque, `drives::fead_design`) per pulley:
/// one bar outline per engine speed, side by side at each pulley's index, and the warning
/// threshold `warning` as a line. Pulleys without a margin (no torque) have no bar.
fn slip_margin_bars(s: &DesignSummary, warning: f64) -> LinePlot {
    let names: Vec<String> = s
        .pulleys
        .iter()
        .enumerate()
        .map(|(k, n)| format!("{k} {n}"))
        .collect();
    let mut plot = LinePlot::new(
        "Slip margins (capacity / torque)",
        format!("pulley ({})", names.join(", ")),
        "slip margin [-]",
    );
    let n = s.points.len().max(1) as f64;
    let width = 0.8 / n;
    for (i, p) in s.points.iter().enumerate() {
        let mut outline = vec![(-0.5, 0.0)];
        for (k, pl) in p.pulleys.iter().enumerate() {
            let Some(m) = pl.slip_margin.filter(|m| m.is_finite()) else {
                continue;
            };
            let x0 = k as f64 - 0.4 + i as f64 * width;
            outline.extend([(x0, 0.0), (x0, m), (x0 + width, m), (x0 + width, 0.0)]);
        }
        outline.push((s.pulleys.len() as f64 - 0.5, 0.0));
        plot.series
            .push(Series::line(format!("{} rpm", p.engine_rpm), outline));
    }
    plot.series.push(Series {
        name: format!("warning below {warning}"),
        points: vec![(-0.5, warning), (s.pulleys.len() as f64 - 0.5, warning)],
        style: Style::Line,
    });
    plot
}
