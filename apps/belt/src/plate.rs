//! `flowmbd-belt plate`: the three-dimensional plate-belt drive of Kerkkänen ch. 4 (library:
//! [`ancf::plate::belt_drive`]; the run, summary and distributions: [`drives::plate_study`];
//! the analytical comparison: [`drives::bechtel_steady`]). Defaults are Model 2 of Table 4.1;
//! `apps/belt/examples/kerkkanen-4-6-model1.toml` and `-model2.toml` hold both models.
//!
//! Output folder: `history.csv` (pulley speeds, driven contact torque, load, span tensions by
//! the three strain measures and membrane forces), `tension.csv` (strain, tension by the three
//! measures, speed and area ratio along the strain line at the end), `analytical.csv`
//! (Bechtel's full and capstan models along the path), `contact.csv` (pressure, friction and
//! slip along the force line at the end), the plots of Kerkkänen Figs 4.10–4.18
//! (`pulley_speeds`, `tension`, `speed`, `area_ratio`, `friction_driven`, `normal_driven`) and
//! a VTK series of the belt surface (`vtk/belt_NNNN.vtu` + `belt.vtu.series`).

use ancf::plate::StrainMeasure;
use ancf::plate::belt_drive::PlateBeltDrive;
use ancf::plate::belt_drive::post::{pulley_torques, span_states, surface_grid};
use drives::ancf_run::Due;
use drives::bechtel_steady::SteadyPoint;
use drives::plate_study::{
    PlateStudyConfig, PlateStudySummary, plate_distributions, plate_run, plate_setup,
};
use fe_model::io::vtk::{PointField, write_vtu};
use fe_model::{Cell, CellKind, Mesh};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{Study, StudyContext, StudyError, VtkSeries, run_study};
use mbd_core::integrators::State;
use std::process::ExitCode;
use std::time::Instant;

/// Command-line arguments of the `plate` study (those of `ancf`).
pub type Args = crate::ancf::Args;

/// Configuration of the `plate` study (defined in `drives`, shared with the Python package).
pub type Config = PlateStudyConfig;
/// Summary of a run (`summary.json`, `--json`).
pub type Summary = PlateStudySummary;

struct PlateStudy {
    t_end: Option<f64>,
}

/// The belt surface at `(q, v)` as a `.vtu` file of quadrilaterals (4 per element) with the
/// tension (by `measure`) and velocity fields.
fn write_surface(
    drive: &PlateBeltDrive,
    s: &State,
    measure: StrainMeasure,
    path: &std::path::Path,
) -> Result<(), StudyError> {
    let g = surface_grid(drive, &s.q, &s.v, 4, measure);
    let mut mesh = Mesh::new(3);
    for p in &g.points {
        mesh.add_node(*p);
    }
    for quad in &g.quads {
        mesh.cells.push(Cell {
            kind: CellKind::Quad,
            nodes: quad.to_vec(),
        });
    }
    let fields = [
        PointField {
            name: format!("tension_{}_N", measure.name()),
            components: 1,
            values: g.tension.clone(),
        },
        PointField {
            name: "velocity_m_per_s".into(),
            components: 3,
            values: g.velocity.iter().flatten().copied().collect(),
        },
    ];
    write_vtu(path, &mesh, &fields).map_err(|e| {
        StudyError::Cli(flowmbd_cli::CliError::Write {
            path: path.to_path_buf(),
            message: e.to_string(),
        })
    })
}

fn analytical_series(
    a: &[SteadyPoint],
    name: &str,
    f: impl Fn(&SteadyPoint) -> f64,
) -> Option<Series> {
    (!a.is_empty()).then(|| Series::line(name, a.iter().map(|p| (p.s, f(p))).collect()))
}

impl PlateStudy {
    fn dynamic(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let start = Instant::now();
        let (drive, init) = plate_setup(c).map_err(crate::ancf::to_study_error)?;
        let (_, driven) = drives::ancf_run::roles(&drive);
        let names: Vec<String> = drive.pulleys().iter().map(|p| p.name.clone()).collect();
        let mut header: Vec<String> = vec!["t_s".into()];
        for n in &names {
            header.push(format!("omega_{n}_rad_per_s"));
        }
        header.push("torque_driven_N_m".into());
        header.push("load_driven_N_m".into());
        let nspans = drive.path().pulleys().len();
        for k in 0..nspans {
            for m in StrainMeasure::ALL {
                header.push(format!("span{k}_tension_{}_N", m.name()));
            }
            header.push(format!("span{k}_membrane_force_N"));
        }
        let hdr: Vec<&str> = header.iter().map(|s| s.as_str()).collect();
        let mut csv = ctx.out.csv("history.csv", &hdr)?;
        let mut frames = VtkSeries::new("belt", "vtu", c.output.vtk_interval);
        let np = names.len();
        let mut speeds: Vec<Vec<(f64, f64)>> = vec![Vec::new(); np];

        let record = |s: &State,
                      csv: &mut flowmbd_cli::output::CsvSink,
                      speeds: &mut Vec<Vec<(f64, f64)>>|
         -> Result<(), StudyError> {
            let mut row = vec![s.t];
            for (p, sp) in speeds.iter_mut().enumerate() {
                let w = drive.pulley_speed(p, s.t, &s.v);
                row.push(w);
                sp.push((s.t, w));
            }
            match driven {
                Some(p) => {
                    row.push(pulley_torques(&drive, s.t, &s.q, &s.v)[p]);
                    row.push(drive.load_torque(p, s.t));
                }
                None => row.extend([f64::NAN, f64::NAN]),
            }
            for st in span_states(&drive, &s.q, &s.v) {
                row.extend(st.tension);
                row.push(st.membrane_force);
            }
            csv.row(&row)?;
            Ok(())
        };

        let s0 = State::new(0.0, init.q.clone(), vec![0.0; init.q.len()]);
        record(&s0, &mut csv, &mut speeds)?;
        let path = frames.frame(&ctx.out, 0.0)?;
        write_surface(&drive, &s0, c.output.strain_measure, &path)?;

        let progress = ctx.progress(c.t_end, "plate belt drive");
        let out = &ctx.out;
        let end = plate_run(
            c,
            &drive,
            &init,
            start,
            |s, due: Due| -> Result<(), StudyError> {
                if due.history {
                    record(s, &mut csv, &mut speeds)?;
                }
                if due.frame {
                    let path = frames.frame(out, s.t)?;
                    write_surface(&drive, s, c.output.strain_measure, &path)?;
                }
                progress.set(s.t);
                Ok(())
            },
        )?;
        progress.finish();
        csv.finish()?;
        let s = &end.state;
        frames.finish(&ctx.out)?;

        // distributions at the end (Figs 4.11–4.18)
        let d = plate_distributions(c, &drive, s);
        ctx.out.write_csv(
            "tension.csv",
            &[
                "s_path_m",
                "s_material_m",
                "x_m",
                "y_m",
                "z_m",
                "green_strain",
                "true_strain",
                "almansi_strain",
                "tension_green_N",
                "tension_true_N",
                "tension_almansi_N",
                "speed_m_per_s",
                "area_ratio",
            ],
            d.belt.iter().map(|p| {
                let b = &p.sample;
                [
                    p.s_path,
                    p.s_material,
                    b.position[0],
                    b.position[1],
                    b.position[2],
                    b.strain[0],
                    b.strain[1],
                    b.strain[2],
                    b.tension[0],
                    b.tension[1],
                    b.tension[2],
                    b.speed,
                    b.area_ratio,
                ]
            }),
        )?;
        let [full, capstan] = &d.analytical;
        if !full.is_empty() {
            ctx.out.write_csv(
                "analytical.csv",
                &[
                    "s_m",
                    "tension_N",
                    "speed_m_per_s",
                    "normal_N_per_m",
                    "friction_N_per_m",
                    "capstan_tension_N",
                    "capstan_speed_m_per_s",
                    "capstan_normal_N_per_m",
                    "capstan_friction_N_per_m",
                ],
                full.iter().enumerate().map(|(i, p)| {
                    let q = capstan.get(i);
                    [
                        p.s,
                        p.tension,
                        p.speed,
                        p.normal,
                        p.friction,
                        q.map_or(f64::NAN, |q| q.tension),
                        q.map_or(f64::NAN, |q| q.speed),
                        q.map_or(f64::NAN, |q| q.normal),
                        q.map_or(f64::NAN, |q| q.friction),
                    ]
                }),
            )?;
        }
        ctx.out.write_csv(
            "contact.csv",
            &[
                "pulley_index",
                "s_path_m",
                "s_material_m",
                "y_material_m",
                "x_m",
                "y_m",
                "z_m",
                "penetration_m",
                "pressure_Pa",
                "friction_circumferential_Pa",
                "friction_axial_Pa",
                "slip_circumferential_m_per_s",
                "slip_axial_m_per_s",
            ],
            d.contact.iter().map(|p| {
                let r = &p.record;
                [
                    r.pulley as f64,
                    p.s_path,
                    r.s_material,
                    r.y,
                    r.position[0],
                    r.position[1],
                    r.position[2],
                    r.penetration,
                    r.pressure,
                    r.friction[0],
                    r.friction[1],
                    r.slip[0],
                    r.slip[1],
                ]
            }),
        )?;

        // plots
        let mut pl = LinePlot::new(
            "Pulley speeds (Kerkkänen Figs 4.10, 4.16)",
            "t [s]",
            "ω [rad/s]",
        );
        for (p, sp) in speeds.into_iter().enumerate() {
            pl = pl.with(Series::line(names[p].clone(), sp));
        }
        pl.save(&ctx.out.path("pulley_speeds"))?;

        let mut pl = LinePlot::new(
            format!(
                "Tension along the belt at t = {:.3} s (Figs 4.11, 4.12)",
                s.t
            ),
            "s (path, from the driver exit) [m]",
            "T [N]",
        );
        for m in StrainMeasure::ALL {
            pl = pl.with(Series::line(
                format!("FE, {} strain", m.name()),
                d.belt
                    .iter()
                    .map(|p| (p.s_path, p.sample.tension_by(m)))
                    .collect(),
            ));
        }
        for (a, name) in [(full, "analytical"), (capstan, "analytical, capstan")] {
            if let Some(se) = analytical_series(a, name, |p| p.tension) {
                pl = pl.with(se);
            }
        }
        pl.save(&ctx.out.path("tension"))?;

        let mut pl = LinePlot::new(
            format!("Belt speed at t = {:.3} s (Figs 4.14, 4.15)", s.t),
            "s (path, from the driver exit) [m]",
            "v [m/s]",
        )
        .with(Series::line(
            "FE",
            d.belt.iter().map(|p| (p.s_path, p.sample.speed)).collect(),
        ));
        if let Some(se) = analytical_series(full, "analytical", |p| p.speed) {
            pl = pl.with(se);
        }
        pl.save(&ctx.out.path("speed"))?;

        LinePlot::new(
            format!("Area ratio √det(JᵀJ) at t = {:.3} s (Fig. 4.13)", s.t),
            "s (path, from the driver exit) [m]",
            "area ratio [-]",
        )
        .with(Series::line(
            "FE",
            d.belt
                .iter()
                .map(|p| (p.s_path, p.sample.area_ratio))
                .collect(),
        ))
        .save(&ctx.out.path("area_ratio"))?;

        // contact forces on the driven pulley: FE per unit area on the force line, analytical
        // per unit length divided by the belt width
        if let Some(p) = driven {
            let w = c.drive.belt.width;
            let on: Vec<_> = d.contact.iter().filter(|r| r.record.pulley == p).collect();
            let arc = |a: &SteadyPoint| {
                matches!(
                    a.zone,
                    drives::bechtel_steady::Zone::DrivenStick
                        | drives::bechtel_steady::Zone::DrivenSlip
                )
            };
            for (stem, title, fe, an) in [
                (
                    "friction_driven",
                    "Friction on the belt, driven pulley (Fig. 4.17)",
                    Box::new(|r: &drives::plate_study::FeContactPoint| r.record.friction[0])
                        as Box<dyn Fn(&drives::plate_study::FeContactPoint) -> f64>,
                    Box::new(|a: &SteadyPoint| a.friction) as Box<dyn Fn(&SteadyPoint) -> f64>,
                ),
                (
                    "normal_driven",
                    "Normal force, driven pulley (Fig. 4.18)",
                    Box::new(|r: &drives::plate_study::FeContactPoint| r.record.pressure),
                    Box::new(|a: &SteadyPoint| a.normal),
                ),
            ] {
                let mut pl = LinePlot::new(
                    format!("{title} at t = {:.3} s", s.t),
                    "s (path, from the driver exit) [m]",
                    "force per area [N/m²]",
                )
                .with(Series::points(
                    "FE",
                    on.iter().map(|r| (r.s_path, fe(r))).collect(),
                ));
                for (a, name) in [(full, "analytical"), (capstan, "analytical, capstan")] {
                    let pts: Vec<(f64, f64)> = a
                        .iter()
                        .filter(|x| arc(x))
                        .map(|x| (x.s, an(x) / w))
                        .collect();
                    if !pts.is_empty() {
                        pl = pl.with(Series::line(name, pts));
                    }
                }
                pl.save(&ctx.out.path(stem))?;
            }
        }

        let mut summary = end.summary;
        summary.run.wall_time_s = start.elapsed().as_secs_f64();
        crate::ancf::finish(summary, end.failure)
    }
}

impl Study for PlateStudy {
    type Config = Config;
    type Summary = Summary;
    const NAME: &'static str = "plate";
    const MEANING: &'static str = drives::plate_study::PLATE_MEANING;

    fn apply_overrides(&self, c: &mut Config) {
        if let Some(t) = self.t_end {
            c.t_end = t;
        }
    }

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        self.dynamic(c, ctx)
    }
}

/// Run the `plate` study under the app conventions.
pub fn run(args: &Args) -> ExitCode {
    run_study(crate::APP, &PlateStudy { t_end: args.t_end }, &args.common)
}
