//! The studies of `flowmbd-beam`: command lines and output files. Configurations, runs,
//! summaries and checks live in `flowmbd_cases::beam_study` (shared with Python), the models in
//! `flowmbd_cases::ancf_beams` and `flowmbd_cases::ancf_dynamics`.

use ancf::beam_mesh::BeamElementKind;
use fe_model::io::vtk::{polyline, write_vtu};
use flowmbd_cases::ancf_beams::{GroundContactCase, StaticBeamCase};
use flowmbd_cases::ancf_dynamics::{PendulumCase, Sample, SpinningCase};
use flowmbd_cases::beam_study::{
    self as study, BeamStudyError, CantileverConfig, DeflectionSummary, GroundContactSummary,
    History, HistoryRun, PendulumSummary, SpinningSummary, TipSummary,
};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, Study, StudyContext, StudyError, set_given};
use mbd_core::validate::plausible::Implausible;
use serde::Serialize;
use std::ops::ControlFlow;

/// Element choice on the command line.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum ElementArg {
    /// Kerkkänen's proposed 8-DOF linear shear-deformable element.
    Proposed,
    /// The Omar–Shabana 12-DOF element.
    OmarShabana,
}

impl From<ElementArg> for BeamElementKind {
    fn from(e: ElementArg) -> Self {
        match e {
            ElementArg::Proposed => BeamElementKind::Proposed,
            ElementArg::OmarShabana => BeamElementKind::OmarShabana,
        }
    }
}

/// The number of elements on the command line (`--elements`).
#[derive(clap::Args, Debug)]
pub struct ElementCount {
    /// Number of elements.
    #[arg(long)]
    pub elements: Option<usize>,
}

/// The element type and number on the command line (`--element`, `--elements`).
#[derive(clap::Args, Debug)]
pub struct Mesh {
    /// Element type.
    #[arg(long, value_enum)]
    pub element: Option<ElementArg>,
    #[command(flatten)]
    pub count: ElementCount,
}

/// Library errors: invalid input → exit code 2, anything else → numerical failure (exit 1).
fn study_error(e: BeamStudyError) -> StudyError {
    match e {
        BeamStudyError::Input(e) => StudyError::Input(e),
        other => StudyError::numerical(other),
    }
}

/// The summary, or its plausibility failure (`check`) as the study's error (skipped when the
/// run was interrupted: its summary is partial and marked so).
fn plausible<T: Serialize>(
    ctx: &StudyContext, summary: T, check: impl FnOnce(&T) -> Result<(), Implausible>,
) -> Result<T, StudyError> {
    if !ctx.cancel.is_cancelled() {
        check(&summary).map_err(|e| StudyError::implausible(e, &summary))?;
    }
    Ok(summary)
}

/// Run a dynamic study (`run` gets the progress callback: it moves a bar labelled `label` and
/// answers `Break` once SIGINT/SIGTERM arrived, keeping the samples so far) and write its
/// `history.csv`.
fn history_run<S: History>(
    ctx: &StudyContext, label: &str,
    run: impl FnOnce(&mut dyn FnMut(f64) -> ControlFlow<()>) -> Result<HistoryRun<S>, BeamStudyError>,
) -> Result<HistoryRun<S>, StudyError> {
    let bar = ctx.progress(1.0, label);
    let r = run(&mut |f| ctx.tick(&bar, f)).map_err(study_error)?;
    bar.finish();
    ctx.out
        .write_csv("history.csv", &S::COLUMNS, r.history_rows())?;
    Ok(r)
}

/// The plot series `(t, value(sample))` of a history.
fn series(s: &[Sample], value: impl Fn(&Sample) -> f64) -> Vec<(f64, f64)> {
    s.iter().map(|x| (x.t, value(x))).collect()
}

/// `simply-supported`: Table 2.1 (ν = 0) by default.
#[derive(clap::Args, Debug)]
pub struct SimplySupported {
    /// Element type.
    #[arg(long, value_enum)]
    pub element: Option<ElementArg>,
    /// Poisson's ratio.
    #[arg(long)]
    pub nu: Option<f64>,
    /// Number of elements (even).
    #[arg(long)]
    pub elements: Option<usize>,
    #[command(flatten)]
    pub common: CommonArgs,
}

impl Study for SimplySupported {
    type Config = StaticBeamCase;
    type Summary = DeflectionSummary;
    const NAME: &'static str = "simply-supported";

    fn apply_overrides(&self, c: &mut StaticBeamCase) {
        set_given(&mut c.element, self.element.map(Into::into));
        set_given(&mut c.nu, self.nu);
        set_given(&mut c.elements, self.elements);
    }

    fn run(
        &self, c: &StaticBeamCase, ctx: &mut StudyContext,
    ) -> Result<DeflectionSummary, StudyError> {
        let summary = study::simply_supported(c).map_err(study_error)?;
        plausible(ctx, summary, |s| s.check(c))
    }
}

/// `cantilever`.
#[derive(clap::Args, Debug)]
pub struct Cantilever {
    /// Element type.
    #[arg(long, value_enum)]
    pub element: Option<ElementArg>,
    /// Section height h [m].
    #[arg(long)]
    pub h: Option<f64>,
    /// Poisson's ratio.
    #[arg(long)]
    pub nu: Option<f64>,
    /// Number of elements.
    #[arg(long)]
    pub elements: Option<usize>,
    #[command(flatten)]
    pub common: CommonArgs,
}

impl Study for Cantilever {
    type Config = CantileverConfig;
    type Summary = TipSummary;
    const NAME: &'static str = "cantilever";

    fn apply_overrides(&self, c: &mut CantileverConfig) {
        set_given(&mut c.beam.element, self.element.map(Into::into));
        set_given(&mut c.beam.height, self.h);
        set_given(&mut c.beam.nu, self.nu);
        set_given(&mut c.beam.elements, self.elements);
    }

    fn run(&self, c: &CantileverConfig, ctx: &mut StudyContext) -> Result<TipSummary, StudyError> {
        let run = study::cantilever(c).map_err(study_error)?;
        let line = &run.centreline;
        ctx.out
            .write_csv("shape.csv", &study::SHAPE_COLUMNS, line.iter().copied())?;
        let points: Vec<[f64; 3]> = line.iter().map(|p| [p[0], p[1], 0.0]).collect();
        let path = ctx.out.path("shape.vtu");
        write_vtu(&path, &polyline(&points, false), &[])
            .map_err(|e| flowmbd_cli::CliError::write(&path, e))?;
        LinePlot::new("Deformed cantilever (Kerkkänen Fig. 2.4)", "x [m]", "y [m]")
            .with(Series::line(
                "centreline",
                line.iter().map(|p| (p[0], p[1])).collect(),
            ))
            .save(&ctx.out.path("shape"))?;
        plausible(ctx, run.summary, |s| s.check(c))
    }
}

/// `pendulum`.
#[derive(clap::Args, Debug)]
pub struct Pendulum {
    #[command(flatten)]
    pub count: ElementCount,
    #[command(flatten)]
    pub common: CommonArgs,
}

impl Study for Pendulum {
    type Config = PendulumCase;
    type Summary = PendulumSummary;
    const NAME: &'static str = "pendulum";

    fn apply_overrides(&self, c: &mut PendulumCase) {
        set_given(&mut c.elements, self.count.elements);
    }

    fn run(&self, c: &PendulumCase, ctx: &mut StudyContext) -> Result<PendulumSummary, StudyError> {
        let run = history_run(ctx, "pendulum", |tick| study::pendulum(c, tick))?;
        let s = &run.samples;
        LinePlot::new(
            "Pendulum tip vertical position (Kerkkänen Fig. 2.6)",
            "t [s]",
            "tip y [m]",
        )
        .with(Series::line(
            format!("{} elements", c.elements),
            series(s, |x| x.tip[1]),
        ))
        .save(&ctx.out.path("tip"))?;
        LinePlot::new(
            "Pendulum energies (Kerkkänen Fig. 2.7)",
            "t [s]",
            "energy [J]",
        )
        .with(Series::line("kinetic", series(s, |x| x.energy.kinetic)))
        .with(Series::line("strain", series(s, |x| x.energy.strain)))
        .with(Series::line("potential", series(s, |x| x.energy.potential)))
        .with(Series::line("total", series(s, |x| x.energy.total)))
        .save(&ctx.out.path("energy"))?;
        plausible(ctx, run.summary, |s| s.check(c))
    }
}

/// `spinning`.
#[derive(clap::Args, Debug)]
pub struct Spinning {
    #[command(flatten)]
    pub count: ElementCount,
    #[command(flatten)]
    pub common: CommonArgs,
}

impl Study for Spinning {
    type Config = SpinningCase;
    type Summary = SpinningSummary;
    const NAME: &'static str = "spinning";

    fn apply_overrides(&self, c: &mut SpinningCase) {
        set_given(&mut c.elements, self.count.elements);
    }

    fn run(&self, c: &SpinningCase, ctx: &mut StudyContext) -> Result<SpinningSummary, StudyError> {
        let run = history_run(ctx, "spinning beam", |tick| study::spinning(c, tick))?;
        let s = &run.samples;
        LinePlot::new(
            "Tip offset from the rigid shadow beam (Kerkkänen Fig. 2.10)",
            "t [s]",
            "offset [m]",
        )
        .with(Series::line("flexible − rigid", series(s, |x| x.value2)))
        .save(&ctx.out.path("tip_offset"))?;
        let exact = run.summary.analytical_extension_m;
        LinePlot::new(
            "Axial extension (Kerkkänen Fig. 2.11)",
            "t [s]",
            "extension [m]",
        )
        .with(Series::line("ANCF", series(s, |x| x.value)))
        .with(Series::line("(2.37)", vec![(0.0, exact), (c.t_end, exact)]))
        .save(&ctx.out.path("extension"))?;
        plausible(ctx, run.summary, |s| s.check(c))
    }
}

/// `ground-contact`.
#[derive(clap::Args, Debug)]
pub struct GroundContact {
    #[command(flatten)]
    pub mesh: Mesh,
    /// Line load as a multiple f of the critical load q* = 72 EI g₀/L⁴.
    #[arg(long)]
    pub load_factor: Option<f64>,
    #[command(flatten)]
    pub common: CommonArgs,
}

impl Study for GroundContact {
    type Config = GroundContactCase;
    type Summary = GroundContactSummary;
    const NAME: &'static str = "ground-contact";

    fn apply_overrides(&self, c: &mut GroundContactCase) {
        set_given(&mut c.element, self.mesh.element.map(Into::into));
        set_given(&mut c.elements, self.mesh.count.elements);
        set_given(&mut c.load_factor, self.load_factor);
    }

    fn run(
        &self, c: &GroundContactCase, ctx: &mut StudyContext,
    ) -> Result<GroundContactSummary, StudyError> {
        let run = study::ground_contact(c).map_err(study_error)?;
        let rows = run.contact_rows();
        ctx.out
            .write_csv("contact.csv", &study::CONTACT_COLUMNS, rows.iter().copied())?;
        LinePlot::new("Contact forces on the ground", "x [m]", "force [N]")
            .with(Series::line(
                "nodal contact force",
                rows.iter().map(|r| (r[0], r[2])).collect(),
            ))
            .save(&ctx.out.path("contact"))?;
        if !ctx.cancel.is_cancelled() {
            run.check()
                .map_err(|e| StudyError::implausible(e, &run.summary))?;
        }
        Ok(run.summary)
    }
}
