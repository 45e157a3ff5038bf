//! The studies of `flowmbd-beam`: configuration (defaults = Kerkkänen's cases), overrides,
//! and output. The computations live in `flowmbd_cases::ancf_beams` and `flowmbd_cases::ancf_dynamics`.

use ancf::AncfError;
use ancf::beam_mesh::BeamElementKind;
use fe_model::io::vtk::{polyline, write_vtu};
use flowmbd_cases::ancf_beams::{self as studies, GroundContactCase, StaticBeamCase};
use flowmbd_cases::ancf_dynamics::{self as dynamics, PendulumCase, Sample, SpinningCase};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, InputError, Study, StudyContext, StudyError, Validate, set_given};
use mbd_core::validate::plausible::Checks;
use serde::{Deserialize, Serialize};
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
fn study_error(e: AncfError) -> StudyError {
    match e {
        AncfError::InvalidInput { item, reason } => {
            StudyError::Input(InputError::new(item, reason))
        }
        other => StudyError::numerical(other),
    }
}

/// Run a time integration from 0 to `t_end` with step `h` \[s\] behind a progress bar
/// labelled `label`, keeping every `every`-th step so that about `samples` samples are kept:
/// `run(every, bar)` is the library call (the pendulum's and the spinning beam's histories).
///
/// `run` gets the progress callback to hand to the library loop: it moves the bar and answers
/// `Break` once SIGINT/SIGTERM arrived, so the loop stops and the samples so far are kept.
fn sampled_history(
    ctx: &StudyContext, label: &str, t_end: f64, h: f64, samples: f64,
    run: impl FnOnce(usize, &mut dyn FnMut(f64) -> ControlFlow<()>) -> Result<Vec<Sample>, AncfError>,
) -> Result<Vec<Sample>, StudyError> {
    let bar = ctx.progress(1.0, label);
    let every = ((t_end / h) / samples).ceil().max(1.0) as usize;
    let s = run(every, &mut |f| ctx.tick(&bar, f)).map_err(study_error)?;
    bar.finish();
    Ok(s)
}

/// The plausibility checks of a summary as the study's error (skipped when the run was
/// interrupted: its summary is partial and marked so).
fn plausible<T: Serialize>(
    ctx: &StudyContext, summary: T, checks: impl FnOnce(&mut Checks),
) -> Result<T, StudyError> {
    if ctx.cancel.is_cancelled() {
        return Ok(summary);
    }
    let mut c = Checks::new();
    checks(&mut c);
    c.result()
        .map_err(|e| StudyError::implausible(e, &summary))?;
    Ok(summary)
}

/// Write `history.csv`: time \[s\], tip position \[m\], then the study's `N` columns
/// `columns` with the values `values(sample)`.
fn write_history<const N: usize>(
    ctx: &StudyContext, s: &[Sample], columns: [&str; N], values: impl Fn(&Sample) -> [f64; N],
) -> Result<(), StudyError> {
    let mut header = vec!["t_s", "tip_x_m", "tip_y_m"];
    header.extend(columns);
    ctx.out.write_csv(
        "history.csv",
        &header,
        s.iter().map(|x| {
            let mut row = vec![x.t, x.tip[0], x.tip[1]];
            row.extend(values(x));
            row
        }),
    )?;
    Ok(())
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

/// Summary of `simply-supported`.
#[derive(Debug, Serialize)]
pub struct DeflectionSummary {
    /// Vertical position of the mid-point \[mm\] (Kerkkänen Tables 2.1/2.2).
    pub midpoint_deflection_mm: f64,
}

impl Study for SimplySupported {
    type Config = StaticBeamCase;
    type Summary = DeflectionSummary;
    const NAME: &'static str = "simply-supported";
    const MEANING: &'static str = "The simply supported ANCF beam of Kerkkanen 2.4 under a 1000 N mid-point load: \
         midpoint_deflection_mm is the vertical position of the mid-point [mm], compared in \
         Kerkkanen Tables 2.1/2.2 with the Euler-Bernoulli and Timoshenko values; the \
         proposed element converges to them with the number of elements, the Omar-Shabana \
         element locks (is too stiff) for thick beams.";

    fn apply_overrides(&self, c: &mut StaticBeamCase) {
        set_given(&mut c.element, self.element.map(Into::into));
        set_given(&mut c.nu, self.nu);
        set_given(&mut c.elements, self.elements);
    }

    fn run(
        &self, c: &StaticBeamCase, ctx: &mut StudyContext,
    ) -> Result<DeflectionSummary, StudyError> {
        if !c.elements.is_multiple_of(2) {
            return Err(
                InputError::new("elements", format!("must be even, got {}", c.elements)).into(),
            );
        }
        let d = studies::simply_supported_deflection(c).map_err(study_error)?;
        plausible(
            ctx,
            DeflectionSummary {
                midpoint_deflection_mm: d * 1e3,
            },
            |k| {
                // the mid-point of a pinned beam cannot move further than its half length
                k.magnitude_at_most(
                    "midpoint_deflection_mm",
                    d * 1e3,
                    0.5 * c.length * 1e3,
                    "half the beam's length [mm]",
                );
            },
        )
    }
}

/// Cantilever configuration: Table 2.3 (Model 1: h = 0.1 m, ν = 0.3) by default.
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct CantileverConfig {
    /// Beam data.
    pub beam: StaticBeamCase,
    /// Segments per element of the deformed-shape output.
    pub shape_segments: usize,
}

impl Default for CantileverConfig {
    fn default() -> Self {
        let mut beam = StaticBeamCase::kerkkanen(BeamElementKind::Proposed, 8, 0.3, 0.1);
        beam.increments = 10;
        Self {
            beam,
            shape_segments: 8,
        }
    }
}

impl flowmbd_cli::PartialRules for CantileverConfig {}

impl Validate for CantileverConfig {
    fn validate(&self) -> Result<(), InputError> {
        self.beam.validate_within("beam")?;
        mbd_core::validate::check::size("shape_segments", self.shape_segments, 1, 10_000)
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

/// Summary of `cantilever`.
#[derive(Debug, Serialize)]
pub struct TipSummary {
    /// Tip position (x, y) \[m\] (Kerkkänen Tables 2.3/2.4).
    pub tip: [f64; 2],
}

impl Study for Cantilever {
    type Config = CantileverConfig;
    type Summary = TipSummary;
    const NAME: &'static str = "cantilever";
    const MEANING: &'static str = "The large-deflection cantilever of Kerkkanen 2.4 under the tip force -5e8 h^3 N: tip \
         is the deformed tip position (x, y) [m] (Kerkkanen Tables 2.3/2.4), compared with \
         the converged reference of the thesis; the beam bends far beyond the linear range, \
         so the tip moves inwards (x < L) as well as down.";

    fn apply_overrides(&self, c: &mut CantileverConfig) {
        set_given(&mut c.beam.element, self.element.map(Into::into));
        set_given(&mut c.beam.height, self.h);
        set_given(&mut c.beam.nu, self.nu);
        set_given(&mut c.beam.elements, self.elements);
    }

    fn run(&self, c: &CantileverConfig, ctx: &mut StudyContext) -> Result<TipSummary, StudyError> {
        let case = c.beam;
        let line = studies::cantilever_centreline(&case, c.shape_segments).map_err(study_error)?;
        let tip = *line
            .last()
            .ok_or_else(|| StudyError::numerical("empty centreline"))?;
        ctx.out.write_csv(
            "shape.csv",
            &["x_m", "y_m"],
            line.iter().map(|p| [p[0], p[1]]),
        )?;
        let points: Vec<[f64; 3]> = line.iter().map(|p| [p[0], p[1], 0.0]).collect();
        let path = ctx.out.path("shape.vtu");
        write_vtu(&path, &polyline(&points, false), &[]).map_err(|e| {
            StudyError::Cli(flowmbd_cli::CliError::Write {
                path: path.clone(),
                message: e.to_string(),
            })
        })?;
        LinePlot::new("Deformed cantilever (Kerkkänen Fig. 2.4)", "x [m]", "y [m]")
            .with(Series::line(
                "centreline",
                line.iter().map(|p| (p[0], p[1])).collect(),
            ))
            .save(&ctx.out.path("shape"))?;
        let length = c.beam.length;
        plausible(ctx, TipSummary { tip }, |k| {
            // a clamped beam's tip stays within its length (with stretch: twice) of the clamp
            k.all_finite("tip", &tip).magnitude_at_most(
                "tip",
                tip[0].hypot(tip[1]),
                2.0 * length,
                "twice the beam's length",
            );
        })
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

/// Summary of `pendulum`.
#[derive(Debug, Serialize)]
pub struct PendulumSummary {
    /// Number of elements.
    pub elements: usize,
    /// Largest deviation of `T + U + V` from its initial value \[J\] (thesis: 0.62e-4 J).
    pub max_energy_deviation_j: f64,
    /// Lowest tip height \[m\].
    pub min_tip_y_m: f64,
    /// Tip position at the end \[m\].
    pub final_tip: [f64; 2],
    /// Largest kinetic energy \[J\].
    pub max_kinetic_j: f64,
}

impl Study for Pendulum {
    type Config = PendulumCase;
    type Summary = PendulumSummary;
    const NAME: &'static str = "pendulum";
    const MEANING: &'static str = "The falling flexible pendulum of Kerkkanen Figs. 2.6/2.7, pinned at one end and \
         released horizontally under gravity. max_energy_deviation_j is the largest deviation \
         of the total energy T + U + V from its initial value [J] (the thesis reports 0.62e-4 \
         J): the energy balance of the time integration; min_tip_y_m is the lowest tip \
         position [m], max_kinetic_j the largest kinetic energy [J], final_tip the tip \
         position at the end [m].";

    fn apply_overrides(&self, c: &mut PendulumCase) {
        set_given(&mut c.elements, self.count.elements);
    }

    fn run(&self, c: &PendulumCase, ctx: &mut StudyContext) -> Result<PendulumSummary, StudyError> {
        let case = *c;
        let s = sampled_history(
            ctx,
            "pendulum",
            case.t_end,
            case.h,
            2000.0,
            |every, tick| dynamics::pendulum(&case, every, tick),
        )?;
        write_history(
            ctx,
            &s,
            ["kinetic_J", "strain_J", "potential_J", "total_J"],
            |x| {
                [
                    x.energy.kinetic,
                    x.energy.strain,
                    x.energy.potential,
                    x.energy.total,
                ]
            },
        )?;
        LinePlot::new(
            "Pendulum tip vertical position (Kerkkänen Fig. 2.6)",
            "t [s]",
            "tip y [m]",
        )
        .with(Series::line(
            format!("{} elements", case.elements),
            series(&s, |x| x.tip[1]),
        ))
        .save(&ctx.out.path("tip"))?;
        LinePlot::new(
            "Pendulum energies (Kerkkänen Fig. 2.7)",
            "t [s]",
            "energy [J]",
        )
        .with(Series::line("kinetic", series(&s, |x| x.energy.kinetic)))
        .with(Series::line("strain", series(&s, |x| x.energy.strain)))
        .with(Series::line(
            "potential",
            series(&s, |x| x.energy.potential),
        ))
        .with(Series::line("total", series(&s, |x| x.energy.total)))
        .save(&ctx.out.path("energy"))?;
        let last = s
            .last()
            .ok_or_else(|| StudyError::numerical("no samples"))?;
        let summary = PendulumSummary {
            elements: case.elements,
            max_energy_deviation_j: dynamics::energy_drift(&s),
            min_tip_y_m: s.iter().map(|x| x.tip[1]).fold(f64::INFINITY, f64::min),
            final_tip: last.tip,
            max_kinetic_j: s.iter().map(|x| x.energy.kinetic).fold(0.0, f64::max),
        };
        let (tip, min_y, ke) = (last.tip, summary.min_tip_y_m, summary.max_kinetic_j);
        plausible(ctx, summary, |k| {
            // the tip of a pendulum pinned at the origin stays within twice its length
            k.magnitude_at_most(
                "final_tip",
                tip[0].hypot(tip[1]),
                2.0 * case.length,
                "twice the pendulum's length",
            )
            .magnitude_at_most(
                "min_tip_y_m",
                min_y,
                2.0 * case.length,
                "twice the pendulum's length",
            )
            .non_negative("max_kinetic_j", ke, "a kinetic energy");
        })
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

/// Summary of `spinning`.
#[derive(Debug, Serialize)]
pub struct SpinningSummary {
    /// Mean axial extension over the last 10 % of the run \[m\].
    pub steady_extension_m: f64,
    /// Kerkkänen (2.37) evaluated with the configuration's data \[m\].
    pub analytical_extension_m: f64,
    /// Value printed in the thesis \[m\].
    pub printed_extension_m: f64,
    /// Relative difference to the printed value \[-\].
    pub relative_error: f64,
    /// Largest tip offset from the rigid shadow beam \[m\].
    pub max_tip_offset_m: f64,
}

impl Study for Spinning {
    type Config = SpinningCase;
    type Summary = SpinningSummary;
    const NAME: &'static str = "spinning";
    const MEANING: &'static str = "The spinning beam of Kerkkanen Figs. 2.10/2.11: the hub spins up to omega and the \
         beam stretches under the centrifugal load. steady_extension_m is the mean axial \
         extension of the tip over the last 10 % of the run [m], analytical_extension_m the \
         closed form (2.37) with the configuration's data and printed_extension_m the value \
         printed in the thesis; relative_error compares the first two; max_tip_offset_m is \
         the largest transverse tip deflection [m] (small: the spin-up excites little \
         bending).";

    fn apply_overrides(&self, c: &mut SpinningCase) {
        set_given(&mut c.elements, self.count.elements);
    }

    fn run(&self, c: &SpinningCase, ctx: &mut StudyContext) -> Result<SpinningSummary, StudyError> {
        let case = *c;
        let s = sampled_history(
            ctx,
            "spinning beam",
            case.t_end,
            case.h,
            4000.0,
            |every, tick| dynamics::spinning(&case, every, tick),
        )?;
        write_history(
            ctx,
            &s,
            ["axial_extension_m", "tip_offset_m", "kinetic_J", "strain_J"],
            |x| [x.value, x.value2, x.energy.kinetic, x.energy.strain],
        )?;
        LinePlot::new(
            "Tip offset from the rigid shadow beam (Kerkkänen Fig. 2.10)",
            "t [s]",
            "offset [m]",
        )
        .with(Series::line("flexible − rigid", series(&s, |x| x.value2)))
        .save(&ctx.out.path("tip_offset"))?;
        let exact = dynamics::spinning_extension(case.length, case.density, case.young, case.omega);
        LinePlot::new(
            "Axial extension (Kerkkänen Fig. 2.11)",
            "t [s]",
            "extension [m]",
        )
        .with(Series::line("ANCF", series(&s, |x| x.value)))
        .with(Series::line(
            "(2.37)",
            vec![(0.0, exact), (case.t_end, exact)],
        ))
        .save(&ctx.out.path("extension"))?;
        let t0 = 0.9 * case.t_end;
        let tail: Vec<f64> = s.iter().filter(|x| x.t >= t0).map(|x| x.value).collect();
        let steady = tail.iter().sum::<f64>() / tail.len().max(1) as f64;
        let printed = 1.09545e-4;
        let summary = SpinningSummary {
            steady_extension_m: steady,
            analytical_extension_m: exact,
            printed_extension_m: printed,
            relative_error: (steady - printed) / printed,
            max_tip_offset_m: s.iter().map(|x| x.value2.abs()).fold(0.0, f64::max),
        };
        let offset = summary.max_tip_offset_m;
        plausible(ctx, summary, |k| {
            // a spinning bar stretches (positive extension), by less than its own length
            k.non_negative("analytical_extension_m", exact, "a centrifugal extension")
                .magnitude_at_most(
                    "analytical_extension_m",
                    exact,
                    case.length,
                    "the beam's length",
                )
                .magnitude_at_most(
                    "steady_extension_m",
                    steady,
                    case.length,
                    "the beam's length",
                )
                .magnitude_at_most("max_tip_offset_m", offset, case.length, "the beam's length");
        })
    }
}

/// Ground-contact configuration (newtype over the library case; default: proposed element,
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

/// Summary of `ground-contact`.
#[derive(Debug, Serialize)]
pub struct GroundContactSummary {
    /// Line load `q` \[N/m\] and Euler–Bernoulli critical load `q*` \[N/m\].
    pub line_load: f64,
    pub critical_load: f64,
    /// Total contact force \[N\] and its Euler–Bernoulli value.
    pub total_force: f64,
    pub euler_bernoulli_total_force: f64,
    /// First node in contact \[m\] and the Euler–Bernoulli start of the contact zone.
    pub first_contact_x: Option<f64>,
    pub euler_bernoulli_contact_start: f64,
}

impl Study for GroundContact {
    type Config = GroundContactCase;
    type Summary = GroundContactSummary;
    const NAME: &'static str = "ground-contact";
    const MEANING: &'static str = "A cantilever pressed onto rigid ground by a line load q = load_factor q* with \
         unilateral Lagrange contact at the nodes: line_load and critical_load [N/m] (q*, the \
         load at which the tip of an Euler-Bernoulli beam just touches); total_force [N] is \
         the sum of the contact forces and first_contact_x [m] where the contact zone starts, \
         compared with the Euler-Bernoulli closed forms euler_bernoulli_total_force and \
         euler_bernoulli_contact_start (for q > q* the beam lies flat from a = (72 EI g0 / \
         q)^(1/4) to the tip).";

    fn apply_overrides(&self, c: &mut GroundContactCase) {
        set_given(&mut c.element, self.mesh.element.map(Into::into));
        set_given(&mut c.elements, self.mesh.count.elements);
        set_given(&mut c.load_factor, self.load_factor);
    }

    fn run(
        &self, c: &GroundContactCase, ctx: &mut StudyContext,
    ) -> Result<GroundContactSummary, StudyError> {
        let r = studies::ground_contact(c).map_err(study_error)?;
        ctx.out.write_csv(
            "contact.csv",
            &["x_m", "y_m", "contact_force_N"],
            r.positions
                .iter()
                .zip(&r.forces)
                .map(|(p, f)| [p[0], p[1], *f]),
        )?;
        LinePlot::new("Contact forces on the ground", "x [m]", "force [N]")
            .with(Series::line(
                "nodal contact force",
                r.positions
                    .iter()
                    .zip(&r.forces)
                    .map(|(p, f)| (p[0], *f))
                    .collect(),
            ))
            .save(&ctx.out.path("contact"))?;
        let forces = r.forces.clone();
        let summary = GroundContactSummary {
            line_load: r.line_load,
            critical_load: r.critical_load,
            total_force: r.total_force,
            euler_bernoulli_total_force: r.euler_bernoulli_total_force,
            first_contact_x: r.first_contact_x,
            euler_bernoulli_contact_start: r.euler_bernoulli_contact_start,
        };
        let total = summary.total_force;
        plausible(ctx, summary, |k| {
            // the ground only pushes: unilateral contact forces are compressive
            k.all_non_negative("contact_force_N", &forces, "a contact force")
                .non_negative("total_force", total, "a contact force");
        })
    }
}
