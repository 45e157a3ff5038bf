//! The five studies of `flowmbd-beam` (Kerkkänen 2006, §2.4): configurations, runs,
//! summaries (the content of `summary.json`, with their `meaning` paragraph), plausibility
//! checks and CSV series. Shared by the app (which parses, calls and writes files and plots)
//! and the Python package (`flowmbd.beam`). The models are those of [`crate::ancf_beams`] and
//! [`crate::ancf_dynamics`].
//!
//! * [`simply_supported`]: mid-point deflection, Kerkkänen Tables 2.1/2.2;
//! * [`cantilever`]: large-deflection tip, Tables 2.3/2.4;
//! * [`pendulum`]: falling flexible pendulum, Figs 2.6/2.7;
//! * [`spinning`]: spinning beam, Figs 2.10/2.11 and (2.37);
//! * [`ground_contact`]: cantilever on rigid ground against Euler–Bernoulli.

use crate::ancf_beams::{self as beams, GroundContactCase, GroundContactResult, StaticBeamCase};
use crate::ancf_dynamics::{self as dynamics, PendulumCase, Sample, SpinningCase};
use ancf::AncfError;
use ancf::beam_mesh::BeamElementKind;
use mbd_core::validate::plausible::{Checks, Implausible};
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};
use std::ops::ControlFlow;

/// Failure of a beam study.
#[derive(Debug, thiserror::Error)]
pub enum BeamStudyError {
    /// Unusable input: the field and why (the app's exit code 2, `ValueError` in Python).
    #[error("{0}")]
    Input(InvalidField),
    /// The computation failed (exit code 1, `flowmbd.NumericalError` in Python).
    #[error("{0}")]
    Numerical(AncfError),
    /// The run produced no output to summarise (`what` names it).
    #[error("{0}")]
    Empty(&'static str),
}

impl From<AncfError> for BeamStudyError {
    /// The ANCF crate's `InvalidInput` is bad input; every other error is numerical.
    fn from(e: AncfError) -> Self {
        match e {
            AncfError::InvalidInput { item, reason } => {
                Self::Input(InvalidField::new(item, reason))
            }
            other => Self::Numerical(other),
        }
    }
}

/// The `meaning` of the `simply-supported` summary.
pub const SIMPLY_SUPPORTED_MEANING: &str = "The simply supported ANCF beam of Kerkkanen 2.4 under a 1000 N mid-point load: \
     midpoint_deflection_mm is the vertical position of the mid-point [mm], compared in \
     Kerkkanen Tables 2.1/2.2 with the Euler-Bernoulli and Timoshenko values; the \
     proposed element converges to them with the number of elements, the Omar-Shabana \
     element locks (is too stiff) for thick beams.";

/// Summary of `simply-supported` (Kerkkänen Tables 2.1/2.2).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DeflectionSummary {
    /// Vertical position of the mid-point \[mm\] (Kerkkänen Tables 2.1/2.2).
    pub midpoint_deflection_mm: f64,
    /// What the numbers mean ([`SIMPLY_SUPPORTED_MEANING`]).
    pub meaning: String,
}

/// The simply supported beam of `case` under a −1000 N mid-point load (Kerkkänen §2.4,
/// Tables 2.1/2.2; [`beams::simply_supported_deflection`]). The number of elements must be
/// even (a node at the mid-point).
pub fn simply_supported(case: &StaticBeamCase) -> Result<DeflectionSummary, BeamStudyError> {
    if !case.elements.is_multiple_of(2) {
        return Err(BeamStudyError::Input(InvalidField::new(
            "elements",
            format!("must be even, got {}", case.elements),
        )));
    }
    let d = beams::simply_supported_deflection(case)?;
    Ok(DeflectionSummary {
        midpoint_deflection_mm: d * 1e3,
        meaning: SIMPLY_SUPPORTED_MEANING.to_string(),
    })
}

impl DeflectionSummary {
    /// The mid-point of a pinned beam cannot move further than half the beam's length.
    pub fn check(&self, case: &StaticBeamCase) -> Result<(), Implausible> {
        Checks::new()
            .magnitude_at_most(
                "midpoint_deflection_mm",
                self.midpoint_deflection_mm,
                0.5 * case.length * 1e3,
                "half the beam's length [mm]",
            )
            .result()
    }
}

/// Cantilever configuration: Kerkkänen Table 2.3 (Model 1: h = 0.1 m, ν = 0.3) by default.
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

impl mbd_core::config::PartialRules for CantileverConfig {}

impl Validate for CantileverConfig {
    /// The beam ([`StaticBeamCase`]'s checks under `beam.`) and `1 ≤ shape_segments ≤ 10⁴`.
    fn validate(&self) -> Result<(), InvalidField> {
        self.beam.validate_within("beam")?;
        check::size("shape_segments", self.shape_segments, 1, 10_000)
    }
}

/// The `meaning` of the `cantilever` summary.
pub const CANTILEVER_MEANING: &str = "The large-deflection cantilever of Kerkkanen 2.4 under the tip force -5e8 h^3 N: tip \
     is the deformed tip position (x, y) [m] (Kerkkanen Tables 2.3/2.4), compared with \
     the converged reference of the thesis; the beam bends far beyond the linear range, \
     so the tip moves inwards (x < L) as well as down.";

/// Summary of `cantilever` (Kerkkänen Tables 2.3/2.4).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TipSummary {
    /// Tip position (x, y) \[m\] (Kerkkänen Tables 2.3/2.4).
    pub tip: [f64; 2],
    /// What the numbers mean ([`CANTILEVER_MEANING`]).
    pub meaning: String,
}

impl TipSummary {
    /// A clamped beam's tip stays within twice its length of the clamp (with stretch).
    pub fn check(&self, c: &CantileverConfig) -> Result<(), Implausible> {
        let tip = self.tip;
        Checks::new()
            .all_finite("tip", &tip)
            .magnitude_at_most(
                "tip",
                tip[0].hypot(tip[1]),
                2.0 * c.beam.length,
                "twice the beam's length",
            )
            .result()
    }
}

/// Columns of `shape.csv`: the deformed centreline (x, y) \[m\].
pub const SHAPE_COLUMNS: [&str; 2] = ["x_m", "y_m"];

/// Result of [`cantilever`]: the summary and the deformed centreline.
#[derive(Debug, Clone, PartialEq)]
pub struct CantileverRun {
    /// The summary.
    pub summary: TipSummary,
    /// Deformed centreline points (x, y) \[m\], root first, `shape_segments` per element (the
    /// rows of `shape.csv`, [`SHAPE_COLUMNS`]).
    pub centreline: Vec<[f64; 2]>,
}

/// The cantilever of `c` under the tip force `−5·10⁸ h³` N (Kerkkänen §2.4, Tables 2.3/2.4;
/// [`beams::cantilever_centreline`]).
pub fn cantilever(c: &CantileverConfig) -> Result<CantileverRun, BeamStudyError> {
    let centreline = beams::cantilever_centreline(&c.beam, c.shape_segments)?;
    let tip = *centreline
        .last()
        .ok_or(BeamStudyError::Empty("empty centreline"))?;
    Ok(CantileverRun {
        summary: TipSummary {
            tip,
            meaning: CANTILEVER_MEANING.to_string(),
        },
        centreline,
    })
}

/// Samples kept of the pendulum's history (about; every `n`-th step, [`sample_every`]).
pub const PENDULUM_SAMPLES: f64 = 2000.0;

/// Samples kept of the spinning beam's history (about).
pub const SPINNING_SAMPLES: f64 = 4000.0;

/// Keep every `n`-th step of a run from 0 to `t_end` with step `h` \[s\] so that about
/// `samples` samples are kept (at least every step).
pub fn sample_every(t_end: f64, h: f64, samples: f64) -> usize {
    ((t_end / h) / samples).ceil().max(1.0) as usize
}

/// The `meaning` of the `pendulum` summary.
pub const PENDULUM_MEANING: &str = "The falling flexible pendulum of Kerkkanen Figs. 2.6/2.7, pinned at one end and \
     released horizontally under gravity. max_energy_deviation_j is the largest deviation \
     of the total energy T + U + V from its initial value [J] (the thesis reports 0.62e-4 \
     J): the energy balance of the time integration; min_tip_y_m is the lowest tip \
     position [m], max_kinetic_j the largest kinetic energy [J], final_tip the tip \
     position at the end [m].";

/// Summary of `pendulum` (Kerkkänen Figs 2.6/2.7).
#[derive(Debug, Clone, PartialEq, Serialize)]
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
    /// What the numbers mean ([`PENDULUM_MEANING`]).
    pub meaning: String,
}

impl PendulumSummary {
    /// The tip of a pendulum pinned at the origin stays within twice its length; kinetic
    /// energy is not negative.
    pub fn check(&self, case: &PendulumCase) -> Result<(), Implausible> {
        let tip = self.final_tip;
        Checks::new()
            .magnitude_at_most(
                "final_tip",
                tip[0].hypot(tip[1]),
                2.0 * case.length,
                "twice the pendulum's length",
            )
            .magnitude_at_most(
                "min_tip_y_m",
                self.min_tip_y_m,
                2.0 * case.length,
                "twice the pendulum's length",
            )
            .non_negative("max_kinetic_j", self.max_kinetic_j, "a kinetic energy")
            .result()
    }
}

/// A dynamic study's summary with the layout of its `history.csv` (the pendulum's and the
/// spinning beam's).
pub trait History {
    /// Columns of `history.csv`.
    const COLUMNS: [&'static str; 7];
    /// The row of `history.csv` of one sample.
    fn row(x: &Sample) -> [f64; 7];
}

impl History for PendulumSummary {
    /// Time \[s\], tip position \[m\], kinetic, strain, potential and total energy \[J\]
    /// (Kerkkänen Figs 2.6/2.7).
    const COLUMNS: [&'static str; 7] = [
        "t_s",
        "tip_x_m",
        "tip_y_m",
        "kinetic_J",
        "strain_J",
        "potential_J",
        "total_J",
    ];

    fn row(x: &Sample) -> [f64; 7] {
        let e = &x.energy;
        [
            x.t,
            x.tip[0],
            x.tip[1],
            e.kinetic,
            e.strain,
            e.potential,
            e.total,
        ]
    }
}

/// Result of a dynamic study ([`pendulum`], [`spinning`]): the summary and the sampled
/// history.
#[derive(Debug, Clone, PartialEq)]
pub struct HistoryRun<S> {
    /// The summary.
    pub summary: S,
    /// The kept samples of the run (about [`PENDULUM_SAMPLES`] or [`SPINNING_SAMPLES`]).
    pub samples: Vec<Sample>,
}

impl<S: History> HistoryRun<S> {
    /// The rows of `history.csv` ([`History::COLUMNS`]).
    pub fn history_rows(&self) -> Vec<[f64; 7]> {
        self.samples.iter().map(S::row).collect()
    }
}

/// The falling flexible pendulum of `case` (Kerkkänen §2.4, Figs 2.6/2.7;
/// [`dynamics::pendulum`]), about [`PENDULUM_SAMPLES`] samples kept. `progress` gets the
/// fraction done; a `Break` stops the run there, the summary then covers the samples so far.
pub fn pendulum(
    case: &PendulumCase, progress: impl FnMut(f64) -> ControlFlow<()>,
) -> Result<HistoryRun<PendulumSummary>, BeamStudyError> {
    let every = sample_every(case.t_end, case.h, PENDULUM_SAMPLES);
    let samples = dynamics::pendulum(case, every, progress)?;
    let last = samples.last().ok_or(BeamStudyError::Empty("no samples"))?;
    let summary = PendulumSummary {
        elements: case.elements,
        max_energy_deviation_j: dynamics::energy_drift(&samples),
        min_tip_y_m: samples
            .iter()
            .map(|x| x.tip[1])
            .fold(f64::INFINITY, f64::min),
        final_tip: last.tip,
        max_kinetic_j: samples.iter().map(|x| x.energy.kinetic).fold(0.0, f64::max),
        meaning: PENDULUM_MEANING.to_string(),
    };
    Ok(HistoryRun { summary, samples })
}

/// Axial extension of the spinning beam printed in Kerkkänen §2.4 (Fig. 2.11) \[m\].
pub const PRINTED_EXTENSION_M: f64 = 1.09545e-4;

/// The `meaning` of the `spinning` summary.
pub const SPINNING_MEANING: &str = "The spinning beam of Kerkkanen Figs. 2.10/2.11: the hub spins up to omega and the \
     beam stretches under the centrifugal load. steady_extension_m is the mean axial \
     extension of the tip over the last 10 % of the run [m], analytical_extension_m the \
     closed form (2.37) with the configuration's data and printed_extension_m the value \
     printed in the thesis; relative_error compares the first two; max_tip_offset_m is \
     the largest transverse tip deflection [m] (small: the spin-up excites little \
     bending).";

/// Summary of `spinning` (Kerkkänen Figs 2.10/2.11, (2.37)).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpinningSummary {
    /// Mean axial extension over the last 10 % of the run \[m\].
    pub steady_extension_m: f64,
    /// Kerkkänen (2.37) evaluated with the configuration's data \[m\].
    pub analytical_extension_m: f64,
    /// Value printed in the thesis \[m\] ([`PRINTED_EXTENSION_M`]).
    pub printed_extension_m: f64,
    /// Relative difference of the steady extension to the printed value \[-\].
    pub relative_error: f64,
    /// Largest tip offset from the rigid shadow beam \[m\].
    pub max_tip_offset_m: f64,
    /// What the numbers mean ([`SPINNING_MEANING`]).
    pub meaning: String,
}

impl SpinningSummary {
    /// A spinning bar stretches (positive extension), by less than its own length, and its tip
    /// stays within its length of the rigid shadow beam.
    pub fn check(&self, case: &SpinningCase) -> Result<(), Implausible> {
        let (exact, l) = (self.analytical_extension_m, case.length);
        Checks::new()
            .non_negative("analytical_extension_m", exact, "a centrifugal extension")
            .magnitude_at_most("analytical_extension_m", exact, l, "the beam's length")
            .magnitude_at_most(
                "steady_extension_m",
                self.steady_extension_m,
                l,
                "the beam's length",
            )
            .magnitude_at_most(
                "max_tip_offset_m",
                self.max_tip_offset_m,
                l,
                "the beam's length",
            )
            .result()
    }
}

impl History for SpinningSummary {
    /// Time \[s\], tip position \[m\], axial extension \[m\], tip offset from the rigid shadow
    /// beam \[m\], kinetic and strain energy \[J\] (Kerkkänen Figs 2.10/2.11).
    const COLUMNS: [&'static str; 7] = [
        "t_s",
        "tip_x_m",
        "tip_y_m",
        "axial_extension_m",
        "tip_offset_m",
        "kinetic_J",
        "strain_J",
    ];

    fn row(x: &Sample) -> [f64; 7] {
        [
            x.t,
            x.tip[0],
            x.tip[1],
            x.value,
            x.value2,
            x.energy.kinetic,
            x.energy.strain,
        ]
    }
}

/// The spinning beam of `case` (Kerkkänen §2.4, Figs 2.10/2.11; [`dynamics::spinning`]),
/// about [`SPINNING_SAMPLES`] samples kept; the steady extension is the mean over the last
/// 10 % of the run, compared with (2.37) ([`dynamics::spinning_extension`]). `progress` as
/// for [`pendulum`].
pub fn spinning(
    case: &SpinningCase, progress: impl FnMut(f64) -> ControlFlow<()>,
) -> Result<HistoryRun<SpinningSummary>, BeamStudyError> {
    let every = sample_every(case.t_end, case.h, SPINNING_SAMPLES);
    let samples = dynamics::spinning(case, every, progress)?;
    let exact = dynamics::spinning_extension(case.length, case.density, case.young, case.omega);
    let t0 = 0.9 * case.t_end;
    let tail: Vec<f64> = samples
        .iter()
        .filter(|x| x.t >= t0)
        .map(|x| x.value)
        .collect();
    let steady = tail.iter().sum::<f64>() / tail.len().max(1) as f64;
    let summary = SpinningSummary {
        steady_extension_m: steady,
        analytical_extension_m: exact,
        printed_extension_m: PRINTED_EXTENSION_M,
        relative_error: (steady - PRINTED_EXTENSION_M) / PRINTED_EXTENSION_M,
        max_tip_offset_m: samples.iter().map(|x| x.value2.abs()).fold(0.0, f64::max),
        meaning: SPINNING_MEANING.to_string(),
    };
    Ok(HistoryRun { summary, samples })
}

/// The `meaning` of the `ground-contact` summary.
pub const GROUND_CONTACT_MEANING: &str = "A cantilever pressed onto rigid ground by a line load q = load_factor q* with \
     unilateral Lagrange contact at the nodes: line_load and critical_load [N/m] (q*, the \
     load at which the tip of an Euler-Bernoulli beam just touches); total_force [N] is \
     the sum of the contact forces and first_contact_x [m] where the contact zone starts, \
     compared with the Euler-Bernoulli closed forms euler_bernoulli_total_force and \
     euler_bernoulli_contact_start (for q > q* the beam lies flat from a = (72 EI g0 / \
     q)^(1/4) to the tip).";

/// Summary of `ground-contact` (the Euler–Bernoulli references of [`GroundContactCase`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GroundContactSummary {
    /// Line load `q` \[N/m\].
    pub line_load: f64,
    /// Euler–Bernoulli critical load `q* = 72 EI g₀/L⁴` \[N/m\].
    pub critical_load: f64,
    /// Total contact force \[N\].
    pub total_force: f64,
    /// Euler–Bernoulli total contact force \[N\].
    pub euler_bernoulli_total_force: f64,
    /// Reference position of the first node in contact \[m\] (`None`: no contact).
    pub first_contact_x: Option<f64>,
    /// Euler–Bernoulli start of the contact zone \[m\].
    pub euler_bernoulli_contact_start: f64,
    /// What the numbers mean ([`GROUND_CONTACT_MEANING`]).
    pub meaning: String,
}

/// Columns of `contact.csv`: node position (x, y) \[m\] and its contact force \[N\].
pub const CONTACT_COLUMNS: [&str; 3] = ["x_m", "y_m", "contact_force_N"];

/// Result of [`ground_contact`]: the summary and the nodal result.
#[derive(Debug, Clone, PartialEq)]
pub struct GroundContactRun {
    /// The summary.
    pub summary: GroundContactSummary,
    /// Deformed node positions and nodal contact forces.
    pub result: GroundContactResult,
}

impl GroundContactRun {
    /// The rows of `contact.csv` ([`CONTACT_COLUMNS`]), root first.
    pub fn contact_rows(&self) -> Vec<[f64; 3]> {
        let r = &self.result;
        r.positions
            .iter()
            .zip(&r.forces)
            .map(|(p, f)| [p[0], p[1], *f])
            .collect()
    }

    /// The ground only pushes: unilateral contact forces are compressive (non-negative).
    pub fn check(&self) -> Result<(), Implausible> {
        Checks::new()
            .all_non_negative("contact_force_N", &self.result.forces, "a contact force")
            .non_negative("total_force", self.summary.total_force, "a contact force")
            .result()
    }
}

/// The cantilever of `case` on rigid ground ([`beams::ground_contact`]).
pub fn ground_contact(case: &GroundContactCase) -> Result<GroundContactRun, BeamStudyError> {
    let r = beams::ground_contact(case)?;
    let summary = GroundContactSummary {
        line_load: r.line_load,
        critical_load: r.critical_load,
        total_force: r.total_force,
        euler_bernoulli_total_force: r.euler_bernoulli_total_force,
        first_contact_x: r.first_contact_x,
        euler_bernoulli_contact_start: r.euler_bernoulli_contact_start,
        meaning: GROUND_CONTACT_MEANING.to_string(),
    };
    Ok(GroundContactRun { summary, result: r })
}
