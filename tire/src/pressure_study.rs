//! The contact-patch study (`flowmbd-tire pressure`, `flowmbd.tire.pressure`; Ribaric Fig.
//! 8-12): the reduced tire preloaded with the vertical load on the drum and on a flat road
//! ([`preload`], static contact with Lagrange multipliers, §7.3), the contact-node forces and
//! the patch extent. Configuration, summary and the rows of `patch_<ground>.csv` live here so
//! that the CLI and the Python package return the same numbers.

use crate::error::TireError;
use crate::ground::{GroundConfig, GroundKind};
use crate::reduced::ReducedTire;
use crate::source::TireSource;
use crate::statics::preload;
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};

/// Configuration of the contact-patch study.
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct PressureStudyConfig {
    /// The tire.
    pub tire: TireSource,
    /// Vertical load \[N\].
    pub load: f64,
    /// Drum radius \[m\].
    pub drum_radius: f64,
}

impl Default for PressureStudyConfig {
    fn default() -> Self {
        Self {
            tire: TireSource::default(),
            load: 4448.2,
            drum_radius: 1.25,
        }
    }
}

impl mbd_core::config::PartialRules for PressureStudyConfig {}

impl Validate for PressureStudyConfig {
    /// The tire, a positive finite load and drum radius.
    fn validate(&self) -> Result<(), InvalidField> {
        self.tire.validate_within("tire")?;
        if !(self.load > 0.0 && self.load.is_finite()) {
            return Err(InvalidField::new("load", "must be positive"));
        }
        if !(self.drum_radius > 0.0 && self.drum_radius.is_finite()) {
            return Err(InvalidField::new("drum_radius", "must be positive"));
        }
        Ok(())
    }
}

/// Patch statistics of one ground.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Patch {
    /// Deflection \[m\].
    pub deflection_m: f64,
    /// Nodes in contact.
    pub nodes_in_contact: usize,
    /// Largest node force \[N\].
    pub peak_node_force_n: f64,
    /// Longitudinal patch length (extent of the contacting nodes) \[m\].
    pub length_m: f64,
}

/// Summary of the contact-patch study (`summary.json`).
#[derive(Debug, Serialize)]
pub struct PressureSummary {
    /// On the drum.
    pub drum: Patch,
    /// On the flat road.
    pub road: Patch,
    /// What the numbers mean ([`pressure_meaning`]).
    pub meaning: String,
}

/// The pressure study's fixed explanation of its numbers (the start of `meaning` in
/// `summary.json`, [`pressure_meaning`]).
pub const PRESSURE_MEANING: &str = "The preloaded contact patch on the drum and on the flat road (Ribaric Fig. 8-12): \
     per ground the deflection [m] of the tire under the load, the contact nodes in \
     contact, the largest node force [N] and the patch length [m] along the rolling \
     direction. The node forces in patch_*.csv add up to the load.";

/// The pressure study's `meaning`: [`PRESSURE_MEANING`], then this run's comparison of the
/// drum with the road (load \[N\], drum radius \[m\]), each direction said as it came out
/// (Ribaric Fig. 8-12: the convex drum needs the larger deflection and gives the shorter patch
/// with the higher peak forces, which a user's tire or drum need not repeat).
pub fn pressure_meaning(load: f64, drum_radius: f64, drum: &Patch, road: &Patch) -> String {
    let more = |a: f64, b: f64, up: &'static str, down: &'static str| {
        if a > b {
            up
        } else if a < b {
            down
        } else {
            "the same"
        }
    };
    format!(
        "{PRESSURE_MEANING} In this run, under {load:.0} N on a drum of radius {drum_radius} m: \
         the drum needs {} deflection ({:.2} mm against {:.2} mm on the road) and gives {} \
         patch ({:.1} mm against {:.1} mm, {} against {} nodes) with {} peak node force \
         ({:.0} N against {:.0} N).",
        more(
            drum.deflection_m,
            road.deflection_m,
            "a larger",
            "a smaller"
        ),
        1e3 * drum.deflection_m,
        1e3 * road.deflection_m,
        more(drum.length_m, road.length_m, "a longer", "a shorter"),
        1e3 * drum.length_m,
        1e3 * road.length_m,
        drum.nodes_in_contact,
        road.nodes_in_contact,
        more(
            drum.peak_node_force_n,
            road.peak_node_force_n,
            "a higher",
            "a lower"
        ),
        drum.peak_node_force_n,
        road.peak_node_force_n,
    )
}

/// Columns of `patch_<ground>.csv`: undeformed contact-node position \[m\] and its normal force
/// \[N\] (0 off the patch).
pub const PATCH_COLUMNS: [&str; 4] = ["x_m", "y_m", "z_m", "force_N"];

/// The patch of one ground: its statistics and one row per contact node ([`PATCH_COLUMNS`]).
#[derive(Debug)]
pub struct GroundPatch {
    /// The ground.
    pub ground: GroundKind,
    /// Its statistics.
    pub patch: Patch,
    /// The rows of `patch_<ground>.csv`.
    pub rows: Vec<[f64; 4]>,
}

/// Preload `red` with `c.load` on the drum (radius `c.drum_radius`) and on the road, without
/// the cleat; the patch length is the extent along x of the nodes with a positive force.
/// Returns the summary and the drum's and the road's patch.
pub fn run_pressure(
    red: &ReducedTire, c: &PressureStudyConfig,
) -> Result<(PressureSummary, [GroundPatch; 2]), TireError> {
    let patch = |kind: GroundKind| -> Result<GroundPatch, TireError> {
        let g = GroundConfig {
            kind,
            drum_radius: c.drum_radius,
            cleat: false,
            ..GroundConfig::default()
        };
        let p = preload(red, &g, c.load)?;
        let rows: Vec<[f64; 4]> = red
            .contact_positions
            .iter()
            .zip(&p.patch.lambda)
            .map(|(s, l)| [s[0], s[1], s[2], *l])
            .collect();
        let xs: Vec<f64> = rows.iter().filter(|r| r[3] > 0.0).map(|r| r[0]).collect();
        let len = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max)
            - xs.iter().copied().fold(f64::INFINITY, f64::min);
        Ok(GroundPatch {
            ground: kind,
            patch: Patch {
                deflection_m: p.patch.deflection,
                nodes_in_contact: xs.len(),
                peak_node_force_n: p.patch.lambda.iter().copied().fold(0.0, f64::max),
                length_m: if xs.is_empty() { 0.0 } else { len },
            },
            rows,
        })
    };
    let drum = patch(GroundKind::Drum)?;
    let road = patch(GroundKind::Road)?;
    let summary = PressureSummary {
        drum: drum.patch,
        road: road.patch,
        meaning: pressure_meaning(c.load, c.drum_radius, &drum.patch, &road.patch),
    };
    Ok((summary, [drum, road]))
}
