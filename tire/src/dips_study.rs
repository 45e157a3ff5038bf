//! The speed-dips study (`flowmbd-tire dips`, `flowmbd.tire.dips`; Ribaric §8.3/§8.5: dips at
//! 40–50 km/h on the drum, 45–55 km/h on the road): per ground the cleat's quasi-static
//! enveloping profile, the loaded vertical mode, the predicted ring-down amplitude against
//! speed and the measured line amplitude of a cleat sweep ([`ground_dips`]). Configuration,
//! summary and the tables of the CSV files live here so that the CLI and the Python package
//! return the same numbers.

use crate::dips::{DipConfig, GroundDips, ground_dips};
use crate::error::TireError;
use crate::ground::GroundKind;
use crate::reduced::ReducedTire;
use crate::rig::RigConfig;
use crate::source::TireSource;
use crate::study::validate_rig;
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};

/// Configuration of the speed-dips study.
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct DipsStudyConfig {
    /// The tire.
    pub tire: TireSource,
    /// The rig (its ground kind and speed are replaced by each ground and sweep speed).
    pub rig: RigConfig,
    /// Profile, prediction and sweep settings.
    pub dips: DipConfig,
    /// Grounds studied.
    pub grounds: Vec<GroundKind>,
}

impl Default for DipsStudyConfig {
    fn default() -> Self {
        Self {
            tire: TireSource::default(),
            rig: RigConfig::default(),
            dips: DipConfig::default(),
            grounds: vec![GroundKind::Drum, GroundKind::Road],
        }
    }
}

impl mbd_core::config::PartialRules for DipsStudyConfig {}

impl Validate for DipsStudyConfig {
    /// The tire, the rig ([`validate_rig`]) with its cleat on, the dip settings (`dips.…`) and
    /// at least one ground.
    fn validate(&self) -> Result<(), InvalidField> {
        self.tire.validate()?;
        validate_rig(&self.rig)?;
        if !self.rig.ground.cleat {
            return Err(InvalidField::new(
                "rig.ground.cleat",
                "the dips need the cleat",
            ));
        }
        if !self.rig.ground.obstacles.is_empty() {
            return Err(InvalidField::new(
                "rig.ground.obstacles",
                "the dips are those of the cleat alone: no further obstacles",
            ));
        }
        if !self.rig.ground.grid_file.is_empty() {
            return Err(InvalidField::new(
                "rig.ground.grid_file",
                "the dips are those of the cleat on the plain drum or road: no height grid",
            ));
        }
        if self.rig.wheel.camber_deg != 0.0 {
            return Err(InvalidField::new(
                "rig.wheel.camber_deg",
                "the dips' quasi-static profile is that of the upright wheel: must be 0",
            ));
        }
        self.dips.validate_within("dips")?;
        if self.grounds.is_empty() {
            return Err(InvalidField::new("grounds", "is empty"));
        }
        Ok(())
    }
}

/// Summary of one ground.
#[derive(Debug, Serialize)]
pub struct GroundSummary {
    /// Ground.
    pub ground: GroundKind,
    /// Preload deflection \[m\].
    pub deflection_m: f64,
    /// Enveloping length of the model's profile \[m\].
    pub envelope_length_m: f64,
    /// Enveloping length of the undeformed tire's geometry \[m\].
    pub geometric_envelope_length_m: f64,
    /// Extent of the contact nodes along x \[m\].
    pub contact_node_span_m: [f64; 2],
    /// Peak quasi-static vertical force change \[N\].
    pub profile_peak_n: f64,
    /// Loaded vertical mode \[Hz\].
    pub vertical_mode_hz: f64,
    /// Its damping ratio.
    pub zeta: f64,
    /// Predicted dips \[km/h\].
    pub predicted_dips_kmh: Vec<f64>,
    /// Measured dips of the sweep \[km/h\].
    pub measured_dips_kmh: Vec<f64>,
    /// Measured line amplitude per sweep speed \[N\].
    pub line_amplitude_n: Vec<f64>,
    /// Sweep speeds \[km/h\].
    pub sweep_speeds_kmh: Vec<f64>,
}

impl From<&GroundDips> for GroundSummary {
    fn from(d: &GroundDips) -> Self {
        let p = &d.profile;
        Self {
            ground: d.ground,
            deflection_m: p.deflection,
            envelope_length_m: d.envelope_length_m,
            geometric_envelope_length_m: d.geometric_envelope_length_m,
            contact_node_span_m: p.node_span,
            profile_peak_n: p.dfy.iter().copied().fold(0.0, f64::max),
            vertical_mode_hz: d.vertical_mode_hz,
            zeta: d.zeta,
            predicted_dips_kmh: d.prediction.dips_kmh.clone(),
            measured_dips_kmh: d.measured_dips_kmh.clone(),
            line_amplitude_n: d.line_amplitude_n.clone(),
            sweep_speeds_kmh: d.sweep_speeds_kmh.clone(),
        }
    }
}

/// Summary of the speed-dips study (`summary.json`).
#[derive(Debug, Serialize)]
pub struct DipsSummary {
    /// Per ground.
    pub grounds: Vec<GroundSummary>,
    /// What the numbers mean ([`DIPS_MEANING`]).
    pub meaning: String,
}

/// The dips study's "what the numbers mean" paragraph (`meaning` in `summary.json`).
pub const DIPS_MEANING: &str = "The speed dips of the cleat test (Ribaric: 40-50 km/h on the drum, 45-55 km/h on the \
     road). Per ground: the quasi-static change of the vertical spindle force while the \
     cleat passes (profile_<ground>.csv; its extent is the enveloping length [m], against \
     the undeformed tire's geometric one), the loaded vertical mode [Hz] and its damping \
     ratio, the predicted ring-down amplitude of that mode after the cleat against speed \
     for a pulse over the enveloping length (dips.pulse: a half sine by default, or the \
     profile itself; prediction_<ground>.csv, dips where the pulse's spectrum has a zero \
     at the mode: v_k ~ f L/(k+1/2) for the half sine) and the measured amplitude of the vertical line in a cleat sweep \
     (sweep_<ground>.csv) with its local minima.";

/// A dips study that failed on `ground`.
#[derive(Debug)]
pub struct DipsFailure {
    /// The ground that failed.
    pub ground: GroundKind,
    /// Its error.
    pub error: TireError,
}

/// Run [`ground_dips`] on every ground of `c.grounds` (the rig's ground kind replaced);
/// `progress` gets the fraction done (0–1). Returns the summary and each ground's profile,
/// prediction and sweep (the tables of [`profile_rows`], [`prediction_rows`], [`sweep_rows`]).
pub fn run_dips(
    red: &ReducedTire, c: &DipsStudyConfig, progress: &mut dyn FnMut(f64),
) -> Result<(DipsSummary, Vec<GroundDips>), Box<DipsFailure>> {
    let n = c.grounds.len().max(1) as f64;
    let mut out: Vec<GroundDips> = Vec::new();
    for (k, &g) in c.grounds.iter().enumerate() {
        let mut rig = c.rig.clone();
        rig.ground.kind = g;
        let d = ground_dips(red, &rig, &c.dips, &mut |f| progress((k as f64 + f) / n))
            .map_err(|error| Box::new(DipsFailure { ground: g, error }))?;
        out.push(d);
    }
    let summary = DipsSummary {
        grounds: out.iter().map(GroundSummary::from).collect(),
        meaning: DIPS_MEANING.to_string(),
    };
    Ok((summary, out))
}

/// Columns of `profile_<ground>.csv` ([`profile_rows`]).
pub const PROFILE_COLUMNS: [&str; 4] = ["cleat_x_m", "dfy_N", "fx_N", "active_nodes_count"];

/// The enveloping profile's rows: cleat position \[m\], `ΔF_y` \[N\], `F_x` \[N\], pressed nodes.
pub fn profile_rows(d: &GroundDips) -> Vec<[f64; 4]> {
    let p = &d.profile;
    (0..p.cleat_x.len())
        .map(|i| [p.cleat_x[i], p.dfy[i], p.fx[i], p.active[i] as f64])
        .collect()
}

/// Columns of `prediction_<ground>.csv` ([`prediction_rows`]).
pub const PREDICTION_COLUMNS: [&str; 2] = ["speed_km_per_h", "amplitude_N"];

/// The predicted ring-down amplitude's rows: speed \[km/h\], amplitude \[N\].
pub fn prediction_rows(d: &GroundDips) -> Vec<[f64; 2]> {
    let pr = &d.prediction;
    pr.speeds_kmh
        .iter()
        .zip(&pr.amplitude_n)
        .map(|(v, a)| [*v, *a])
        .collect()
}

/// Columns of `sweep_<ground>.csv` ([`sweep_rows`]; written only when the sweep has speeds).
pub const SWEEP_COLUMNS: [&str; 2] = ["speed_km_per_h", "line_amplitude_N"];

/// The measured line amplitude's rows: speed \[km/h\], amplitude \[N\].
pub fn sweep_rows(d: &GroundDips) -> Vec<[f64; 2]> {
    d.sweep_speeds_kmh
        .iter()
        .zip(&d.line_amplitude_n)
        .map(|(v, a)| [*v, *a])
        .collect()
}
