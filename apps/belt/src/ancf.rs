//! `flowmbd-belt ancf`: the planar ANCF belt drive of Kerkkänen ch. 3 (library:
//! [`ancf::belt_drive`]; the run and its time loop: [`drives::ancf_run`]). Defaults are Table 3.1 with the driver ramp (3.29) (example 3.3-B);
//! `apps/belt/examples/kerkkanen-3-3-*.toml` hold the other examples.
//!
//! Output folder: `history.csv` (pulley speeds, span mid-point positions, span tensions),
//! `tension.csv` (tension along the belt at the end), `contact.csv` (normal and friction force
//! per unit length and belt–pulley relative velocity at every active contact quadrature point at
//! the end), `relative_velocity.csv` (the relative velocity (3.25) sampled at
//! `output.points_per_element` points per element, which resolves the inlet and exit zones),
//! `wrap.csv` (tension, contact pressure, friction, slip velocity and friction utilisation at
//! every contact quadrature point of every wrap at the end, by angle from the wrap's inlet),
//! the plots of these, and a VTK series of the belt (`vtk/belt_NNNN.vtu` + `belt.vtu.series`,
//! [`flowmbd_cli::VtkSeries`]).
//! `summary.json` adds per pulley the contact, slip and adhesion arcs, slip velocities, hub
//! load and torque, and per span the tension and the transverse vibration amplitude
//! ([`belt::report`]).

use crate::ancf_shell::{
    self, AncfApp, Args, Sampled, finish, sampled_run, time_plot, to_study_error,
};
use crate::wrap_csv;
use ancf::belt_drive::{BeltDrive, post};
use drives::ancf_study::{
    Analysis, AncfStudyConfig, AncfStudySummary, closure_study, dynamic_run, dynamic_setup,
};
use fe_model::io::vtk::{PointField, polyline, write_vtu};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{StudyContext, StudyError, VtkSeries};
use mbd_core::integrators::State;
use std::process::ExitCode;
use std::time::Instant;

/// Configuration of the `ancf` study (defined in `drives`, shared with the Python package).
pub type Config = AncfStudyConfig;
/// Summary of a run (`summary.json`, `--json`).
pub type Summary = AncfStudySummary;

/// The `ancf` study ([`AncfApp`]).
pub(crate) struct AncfStudy;

/// The belt's centreline at `q` as a closed `.vtu` polyline with its tension \[N\].
fn write_vtk(
    drive: &BeltDrive, q: &[f64], per_el: usize, path: &std::path::Path,
) -> Result<(), StudyError> {
    let samples = post::tension_samples(drive, q, per_el);
    let points: Vec<[f64; 3]> = samples
        .iter()
        .map(|s| [s.position[0], s.position[1], 0.0])
        .collect();
    let tension = PointField {
        name: "tension_N".into(),
        components: 1,
        values: samples.iter().map(|s| s.tension).collect(),
    };
    write_vtu(path, &polyline(&points, true), &[tension])
        .map_err(|e| flowmbd_cli::CliError::write(path, e).into())
}

impl AncfStudy {
    fn closure(c: &Config, ctx: &mut StudyContext, start: Instant) -> Result<Summary, StudyError> {
        // the belt is stress-free on the path length (Kerkkänen: 1.276 m on the 1.276273 m path)
        let (drive, r, mut summary) = closure_study(c).map_err(to_study_error)?;
        let samples = post::tension_samples(&drive, &r.q, c.output.points_per_element);
        ctx.out.write_csv(
            "closure.csv",
            &["s_material_m", "x_m", "y_m"],
            samples
                .iter()
                .map(|s| [s.s_material, s.position[0], s.position[1]]),
        )?;
        let q0 = drive.placed_coordinates();
        let init = post::tension_samples(&drive, &q0, c.output.points_per_element);
        let pts = |v: &[post::TensionSample]| {
            let mut p: Vec<(f64, f64)> = v.iter().map(|s| (s.position[0], s.position[1])).collect();
            if let Some(&f) = p.first() {
                p.push(f);
            }
            p
        };
        LinePlot::new("Free belt closure (Kerkkänen 3.3-A)", "x [m]", "y [m]")
            .with(Series::line("initial guess", pts(&init)))
            .with(Series::line("equilibrium", pts(&samples)))
            .save(&ctx.out.path("closure"))?;
        let mut frames = VtkSeries::new("belt", "vtu", 0.0);
        let path = frames.frame(&ctx.out, 0.0)?;
        write_vtk(&drive, &r.q, c.output.points_per_element, &path)?;
        frames.finish(&ctx.out)?;
        summary.run.wall_time_s = start.elapsed().as_secs_f64();
        Ok(summary)
    }

    fn dynamic(c: &Config, ctx: &mut StudyContext, start: Instant) -> Result<Summary, StudyError> {
        let (drive, init) = dynamic_setup(c).map_err(to_study_error)?;
        let spans = post::spans(&drive);
        let mut columns = Vec::new();
        for k in 0..spans.len() {
            columns.push(format!("span{k}_mid_x_m"));
            columns.push(format!("span{k}_mid_y_m"));
        }
        columns.extend((0..spans.len()).map(|k| format!("span{k}_tension_N")));
        let sampled = Sampled {
            label: "ANCF belt drive",
            t_end: c.t_end,
            vtk_interval: c.output.vtk_interval,
            pulleys: drive.pulleys().iter().map(|p| p.name.clone()).collect(),
            columns,
        };
        let mut mids: Vec<Vec<(f64, f64)>> = vec![Vec::new(); spans.len()];
        let mut tens: Vec<Vec<(f64, f64)>> = vec![Vec::new(); spans.len()];
        let row = |s: &State| {
            let mut row: Vec<f64> = (0..drive.pulleys().len())
                .map(|p| drive.pulley_speed(p, s.t, &s.v))
                .collect();
            let m = post::span_midpoints(&drive, &s.q);
            for (k, mp) in m.iter().enumerate() {
                let p = mp.unwrap_or([f64::NAN, f64::NAN]);
                row.push(p[0]);
                row.push(p[1]);
                if p[1].is_finite() {
                    mids[k].push((s.t, p[1]));
                }
            }
            let t = post::span_tensions(&drive, &s.q);
            for (k, v) in t.iter().enumerate() {
                row.push(*v);
                if v.is_finite() {
                    tens[k].push((s.t, *v));
                }
            }
            row
        };
        let per_el = c.output.points_per_element;
        let (end, speeds) = sampled_run(
            ctx,
            sampled,
            &init.q,
            row,
            |s, path| write_vtk(&drive, &s.q, per_el, path),
            |observer| dynamic_run(c, &drive, &init, start, observer),
        )?;
        let s = &end.state;

        // end-of-run distributions
        let samples = post::tension_samples(&drive, &s.q, c.output.points_per_element);
        ctx.out.write_csv(
            "tension.csv",
            &[
                "s_material_m",
                "x_m",
                "y_m",
                "engineering_strain",
                "tension_N",
            ],
            samples.iter().map(|p| {
                [
                    p.s_material,
                    p.position[0],
                    p.position[1],
                    p.strain,
                    p.tension,
                ]
            }),
        )?;
        let recs = drive.contact_records(s.t, &s.q, &s.v);
        ctx.out.write_csv(
            "contact.csv",
            &[
                "pulley_index",
                "s_material_m",
                "arc_m",
                "x_m",
                "y_m",
                "penetration_m",
                "normal_force_N_per_m",
                "friction_force_N_per_m",
                "relative_velocity_m_per_s",
            ],
            recs.iter().map(|r| {
                [
                    r.pulley as f64,
                    r.s_material,
                    post::pulley_arc_coordinate(&drive, r.pulley, r.position),
                    r.position[0],
                    r.position[1],
                    r.penetration,
                    r.normal_force,
                    r.friction_force,
                    r.slip,
                ]
            }),
        )?;

        // the relative velocity sampled densely (the inlet and exit zones are narrower than the
        // spacing of the contact quadrature points)
        let fine = drive.contact_records_sampled(s.t, &s.q, &s.v, c.output.points_per_element);
        ctx.out.write_csv(
            "relative_velocity.csv",
            &[
                "pulley_index",
                "s_material_m",
                "arc_m",
                "penetration_m",
                "relative_velocity_m_per_s",
            ],
            fine.iter().map(|r| {
                [
                    r.pulley as f64,
                    r.s_material,
                    post::pulley_arc_coordinate(&drive, r.pulley, r.position),
                    r.penetration,
                    r.slip,
                ]
            }),
        )?;

        // tension, pressure, friction and slip along every wrap at the end
        let mu = &end.friction_coefficients;
        ctx.out.write_csv(
            "wrap.csv",
            &wrap_csv::COLUMNS,
            end.wrap.iter().map(|w| wrap_csv::row(w, mu[w.pulley])),
        )?;

        // plots
        let names = drive.pulleys().iter().map(|p| p.name.clone());
        time_plot("Pulley speeds", "ω [rad/s]", names.zip(speeds))
            .save(&ctx.out.path("pulley_speeds"))?;
        let spans = |v: Vec<Vec<(f64, f64)>>| {
            v.into_iter()
                .enumerate()
                .map(|(k, m)| (format!("span {k}"), m))
        };
        time_plot("Span mid-points", "y [m]", spans(mids)).save(&ctx.out.path("span_midpoints"))?;
        time_plot("Span tensions", "T [N]", spans(tens)).save(&ctx.out.path("span_tensions"))?;
        LinePlot::new(
            format!("Tension along the belt at t = {:.3} s", s.t),
            "s (material) [m]",
            "T [N]",
        )
        .with(Series::line(
            "tension",
            samples.iter().map(|p| (p.s_material, p.tension)).collect(),
        ))
        .save(&ctx.out.path("tension"))?;
        for (p, pulley) in drive.pulleys().iter().enumerate() {
            let mut on: Vec<_> = recs.iter().filter(|r| r.pulley == p).collect();
            on.sort_by(|a, b| a.s_material.total_cmp(&b.s_material));
            LinePlot::new(
                format!("Contact forces on {} at t = {:.3} s", pulley.name, s.t),
                "s (material) [m]",
                "force per length [N/m]",
            )
            .with(Series::points(
                "normal",
                on.iter().map(|r| (r.s_material, r.normal_force)).collect(),
            ))
            .with(Series::points(
                "friction",
                on.iter()
                    .map(|r| (r.s_material, r.friction_force))
                    .collect(),
            ))
            .save(&ctx.out.path(&format!("contact_{}", pulley.name)))?;
            let mut arc: Vec<(f64, f64)> = fine
                .iter()
                .filter(|r| r.pulley == p)
                .map(|r| (post::pulley_arc_coordinate(&drive, p, r.position), r.slip))
                .collect();
            arc.sort_by(|a, b| a.0.total_cmp(&b.0));
            LinePlot::new(
                format!("Belt–pulley relative velocity on {}", pulley.name),
                "arc from inlet [m]",
                "v_belt − v_pulley [m/s]",
            )
            .with(Series::points("relative velocity", arc))
            .save(&ctx.out.path(&format!("relative_velocity_{}", pulley.name)))?;
        }

        finish(end.summary, |s| &mut s.run, end.failure, start)
    }
}

impl AncfApp for AncfStudy {
    type Config = Config;
    const NAME: &'static str = "ancf";

    fn run(c: &Config, ctx: &mut StudyContext, start: Instant) -> Result<Summary, StudyError> {
        match c.analysis {
            Analysis::StaticClosure => Self::closure(c, ctx, start),
            Analysis::Dynamic => Self::dynamic(c, ctx, start),
        }
    }
}

/// Run the `ancf` study under the app conventions.
pub fn run(args: &Args) -> ExitCode {
    ancf_shell::run::<AncfStudy>(args)
}
