//! `flowmbd-belt speed-loss`: angular speed loss Δω = ω₁ − ω₂ of the two-pulley drive of
//! Ribaric Table 6-1 against the load torque, at the driver speeds of Figs. 6-6 and 6-7, with
//! Bechtel's analytical line (6.3). The models, the procedure and the study live in `drives`;
//! this module reads the configuration, calls [`SpeedLossModel`] per driver speed and writes
//! the results.

use clap::builder::{PossibleValuesParser, TypedValueParser};
use drives::ancf_drive_model::AncfConfig;
use drives::speed_loss::{Sample, SweepStats};
use drives::study::case_inputs;
use drives::{DriveError, ModelKind, NodalConfig, SpeedLossCase, SpeedLossModel};
use drives::{SpeedLossConfig, speed_loss::SweepFailure};
use flowing::belt::BeltDriveConfig;
use flowmbd_cli::plot::{LinePlot, Series, Style};
use flowmbd_cli::{CommonArgs, InputError, Study, StudyContext, StudyError, Validate, run_study};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::process::ExitCode;
use std::sync::atomic::{AtomicUsize, Ordering};

fn model_parser() -> impl TypedValueParser<Value = ModelKind> {
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

/// Study configuration.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// Belt model.
    pub model: ModelKind,
    /// Driver speeds \[rad/s\] (Figs. 6-6 and 6-7: 62.8 and 22.6).
    pub omegas: Vec<f64>,
    /// The drive (Table 6-1).
    pub drive: BeltDriveConfig,
    /// The procedure (torques, ramps, steady-state detection, integrator). Its `omega_driver`
    /// is replaced by each entry of `omegas`.
    pub procedure: SpeedLossConfig,
    /// Write every n-th integration step to the history CSV files.
    pub history_every: usize,
    /// Discretisation of the ANCF belt (`model = "ancf"` only).
    pub ancf: AncfConfig,
    /// Settings used instead of `drive.mesh` and the procedure's steady-state window when
    /// `model = "nodal"`.
    pub nodal: NodalConfig,
}

impl Default for Config {
    fn default() -> Self {
        Self {
            model: ModelKind::Flowing,
            omegas: vec![62.8, 22.6],
            drive: BeltDriveConfig::default(),
            procedure: SpeedLossConfig::default(),
            history_every: 20,
            ancf: Default::default(),
            nodal: NodalConfig::default(),
        }
    }
}

impl Validate for Config {
    fn validate(&self) -> Result<(), InputError> {
        if self.omegas.is_empty() {
            return Err(InputError::new("omegas", "give at least one driver speed"));
        }
        if let Some(i) = self
            .omegas
            .iter()
            .position(|w| !(w.is_finite() && *w > 0.0))
        {
            return Err(InputError::new(
                format!("omegas[{i}]"),
                "must be finite and > 0 [rad/s]",
            ));
        }
        if self.history_every == 0 {
            return Err(InputError::new("history_every", "must be at least 1"));
        }
        self.drive.validate_within("drive")?;
        self.ancf.validate_within("ancf")?;
        if self.model == ModelKind::Nodal {
            BeltDriveConfig {
                mesh: self.nodal.mesh,
                ..self.drive
            }
            .validate_within("nodal")?;
            SpeedLossConfig {
                window: self.nodal.window,
                tolerance: self.nodal.tolerance,
                ..self.procedure.clone()
            }
            .validate_within("nodal")?;
        }
        self.procedure.validate_within("procedure")
    }
}

/// One driver speed's result.
#[derive(Debug, Clone, Serialize)]
pub struct Case {
    /// Driver speed \[rad/s\].
    pub omega_driver: f64,
    /// Steady points.
    pub points: Vec<Point>,
    /// Bechtel's Δω (6.3) at the same torques \[rad/s\].
    pub analytical: Vec<f64>,
    /// Integration statistics.
    pub stats: SweepStats,
    /// Wall time of this case \[s\].
    pub wall_time_s: f64,
}

/// One point of the summary.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Point {
    /// Load torque \[N m\].
    pub torque: f64,
    /// Steady speed loss \[rad/s\].
    pub delta_omega: f64,
}

/// Summary: the first speed's case at the top level (the `--omega` contract), all cases below.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// Driver speed of the first case \[rad/s\].
    pub omega_driver: f64,
    /// Model.
    pub model: ModelKind,
    /// Points of the first case.
    pub points: Vec<Point>,
    /// Analytical Δω of the first case \[rad/s\].
    pub analytical: Vec<f64>,
    /// Every driver speed.
    pub cases: Vec<Case>,
    /// Number of coordinates of the model (modal + belt + pulley for the flowing model,
    /// nodal + belt + pulley for the nodal model).
    pub modal_coordinates: usize,
    /// Total wall time \[s\].
    pub wall_time_s: f64,
}

struct SpeedLoss {
    args: Args,
}

fn drive_error(e: DriveError) -> StudyError {
    match e {
        DriveError::Ancf(ancf::AncfError::InvalidInput { item, reason }) => {
            StudyError::Input(InputError::new(format!("ancf: {item}"), reason))
        }
        DriveError::Ancf(other) => StudyError::numerical(other),
        DriveError::Flowing(e) => StudyError::numerical(e),
    }
}

fn sweep_error(omega: f64, f: SweepFailure) -> StudyError {
    StudyError::Numerical {
        message: format!("ω₁ = {omega} rad/s: {}", f.error),
        partial: Some(serde_json::json!({
            "omega_driver": omega,
            "points": f.points,
        })),
    }
}

/// One driver speed: build the model, write the ANCF mapping (if any) and the history CSV
/// while [`SpeedLossModel::sweep`] runs. `(case, number of coordinates)`.
fn run_case(
    c: &Config,
    omega: f64,
    ctx: &StudyContext,
    done: &AtomicUsize,
    report: &(dyn Fn(usize) + Sync),
) -> Result<(Case, usize), StudyError> {
    let (drive, settings) = case_inputs(c.model, &c.drive, &c.procedure, &c.nodal, omega);
    let mut model = SpeedLossModel::new(c.model, &drive, &c.ancf).map_err(drive_error)?;
    if let Some(mapping) = model.ancf_mapping() {
        // the derived parameters of the Table 6-1 → ANCF mapping, for the record
        ctx.out
            .write_json(&format!("ancf_mapping_omega_{omega:.1}.json"), mapping)?;
    }
    let start = std::time::Instant::now();
    let name = format!("history_omega_{omega:.1}.csv");
    // the flowing and nodal models carry the belt speed as their first velocity
    let columns = [
        "t",
        "omega_driver",
        "omega_driven",
        "load_torque",
        "belt_speed",
    ];
    let n_col = if model.has_belt_speed() { 5 } else { 4 };
    let mut csv = ctx.out.csv(&name, &columns[..n_col])?;
    let mut io_err = None;
    let mut k = 0usize;
    let mut found = 0usize;
    let every = c.history_every;
    let result = model.sweep(&drive, &settings, |st, s: Sample| {
        k += 1;
        let row = [s.t, s.omega_driver, s.omega_driven, s.load, st.v[0]];
        if k.is_multiple_of(every)
            && let Err(e) = csv.row(&row[..n_col])
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
    let case: SpeedLossCase = result.map_err(|f| sweep_error(omega, f))?;
    // the last point ends the sweep, after the last observer call
    let extra = case.points.len().saturating_sub(found);
    report(done.fetch_add(extra, Ordering::Relaxed) + extra);
    Ok((
        Case {
            omega_driver: case.omega_driver,
            points: case
                .points
                .iter()
                .map(|p| Point {
                    torque: p.torque,
                    delta_omega: p.delta_omega,
                })
                .collect(),
            analytical: case.analytical,
            stats: case.stats,
            wall_time_s: start.elapsed().as_secs_f64(),
        },
        model.coordinates(),
    ))
}

impl Study for SpeedLoss {
    type Config = Config;
    type Summary = Summary;
    const APP: &'static str = "belt";
    const NAME: &'static str = "speed-loss";

    fn apply_overrides(&self, c: &mut Config) {
        if let Some(w) = self.args.omega {
            c.omegas = vec![w];
        }
        if let Some(t) = &self.args.torques {
            c.procedure.torques = t.clone();
        }
        if let Some(m) = self.args.model {
            c.model = m;
        }
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
                "omega_driver",
                "torque",
                "delta_omega",
                "delta_omega_analytical",
            ],
        )?;
        let mut plot = LinePlot::new(
            "Angular speed loss (Ribaric Table 6-1, T0 = 310 N)",
            "load torque [N m]",
            "Δω = ω₁ − ω₂ [rad/s]",
        );
        for case in &cases {
            for (p, a) in case.points.iter().zip(&case.analytical) {
                table.row(&[case.omega_driver, p.torque, p.delta_omega, *a])?;
            }
            plot.series.push(Series {
                name: format!("{}, ω₁ = {} rad/s", c.model.name(), case.omega_driver),
                points: case
                    .points
                    .iter()
                    .map(|p| (p.torque, p.delta_omega))
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
        plot.save(&ctx.out.path("speed_loss"))?;
        let first = &cases[0];
        Ok(Summary {
            omega_driver: first.omega_driver,
            model: c.model,
            points: first.points.clone(),
            analytical: first.analytical.clone(),
            modal_coordinates: modes,
            cases,
            wall_time_s: start.elapsed().as_secs_f64(),
        })
    }
}

/// Run the study under the app conventions.
pub fn run(args: &Args) -> ExitCode {
    run_study(&SpeedLoss { args: args.clone() }, &args.common)
}
