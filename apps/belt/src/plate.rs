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

use crate::ancf_shell::{
    self, AncfApp, Args, Sampled, finish, sampled_run, time_plot, to_study_error,
};
use ancf::plate::StrainMeasure;
use ancf::plate::belt_drive::PlateBeltDrive;
use ancf::plate::belt_drive::post::{pulley_torques, span_states, surface_grid};
use drives::bechtel_steady::SteadyPoint;
use drives::plate_study::{
    PlateStudyConfig, PlateStudySummary, plate_distributions, plate_run, plate_setup,
};
use fe_model::io::vtk::{PointField, write_vtu};
use fe_model::{Cell, CellKind, Mesh};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{StudyContext, StudyError};
use mbd_core::integrators::State;
use std::process::ExitCode;
use std::time::Instant;

/// Configuration of the `plate` study (defined in `drives`, shared with the Python package).
pub type Config = PlateStudyConfig;
/// Summary of a run (`summary.json`, `--json`).
pub type Summary = PlateStudySummary;

/// The `plate` study ([`AncfApp`]).
pub(crate) struct PlateStudy;

/// The belt surface at `(q, v)` as a `.vtu` file of quadrilaterals (4 per element) with the
/// tension (by `measure`) and velocity fields.
fn write_surface(
    drive: &PlateBeltDrive, s: &State, measure: StrainMeasure, path: &std::path::Path,
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
    write_vtu(path, &mesh, &fields).map_err(|e| flowmbd_cli::CliError::write(path, e).into())
}

fn analytical_series(
    a: &[SteadyPoint], name: &str, f: impl Fn(&SteadyPoint) -> f64,
) -> Option<Series> {
    (!a.is_empty()).then(|| Series::line(name, a.iter().map(|p| (p.s, f(p))).collect()))
}

impl AncfApp for PlateStudy {
    type Config = Config;
    const NAME: &'static str = "plate";

    fn run(c: &Config, ctx: &mut StudyContext, start: Instant) -> Result<Summary, StudyError> {
        let (drive, init) = plate_setup(c).map_err(to_study_error)?;
        let (_, driven) = drives::ancf_run::roles(&drive);
        let names: Vec<String> = drive.pulleys().iter().map(|p| p.name.clone()).collect();
        let mut columns = vec!["torque_driven_N_m".to_string(), "load_driven_N_m".into()];
        for k in 0..drive.path().pulleys().len() {
            for m in StrainMeasure::ALL {
                columns.push(format!("span{k}_tension_{}_N", m.name()));
            }
            columns.push(format!("span{k}_membrane_force_N"));
        }
        let sampled = Sampled {
            label: "plate belt drive",
            t_end: c.t_end,
            vtk_interval: c.output.vtk_interval,
            pulleys: names.clone(),
            columns,
        };
        let row = |s: &State| {
            let mut row: Vec<f64> = (0..names.len())
                .map(|p| drive.pulley_speed(p, s.t, &s.v))
                .collect();
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
            row
        };
        let measure = c.output.strain_measure;
        let (end, speeds) = sampled_run(
            ctx,
            sampled,
            &init.q,
            row,
            |s, path| write_surface(&drive, s, measure, path),
            |observer| plate_run(c, &drive, &init, start, observer),
        )?;
        let s = &end.state;

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
        let title = "Pulley speeds (Kerkkänen Figs 4.10, 4.16)";
        time_plot(title, "ω [rad/s]", names.into_iter().zip(speeds))
            .save(&ctx.out.path("pulley_speeds"))?;

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

        finish(end.summary, |s| &mut s.run, end.failure, start)
    }
}

/// Run the `plate` study under the app conventions.
pub fn run(args: &Args) -> ExitCode {
    ancf_shell::run::<PlateStudy>(args)
}
