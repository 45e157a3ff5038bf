//! The `flowmbd-reduce lin-beam` study: Lin (2005) ch. 6.2, 6.3, 7.1 and 8.5 on the Appendix A
//! beam ([`super::beam`]), with its configuration and CSV series; shared by the app and the
//! Python package (`flowmbd.reduce.lin_beam`).

use super::beam::{self, LinBeamConfig, LinBeamSummary, PROFILE_DELTA, ProfileStudy};
use mbd_core::validate::{InvalidField, Validate};
use reduction::error::Result;
use serde::{Deserialize, Serialize};

/// Configuration of `lin-beam`; the defaults are Lin's Appendix A beam and profile (7.1).
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct LinBeamStudyConfig {
    /// The beam (Appendix A).
    pub beam: LinBeamConfig,
    /// Assumed deformation of the profile tests, DOF order ξ1, η1, …, ξ5, η5 \[m\] (Lin (7.1)).
    pub profile_delta_m: [f64; 10],
}

impl Default for LinBeamStudyConfig {
    fn default() -> Self {
        Self {
            beam: LinBeamConfig::default(),
            profile_delta_m: PROFILE_DELTA,
        }
    }
}

impl mbd_core::config::PartialRules for LinBeamStudyConfig {}

impl Validate for LinBeamStudyConfig {
    /// The beam's checks under `beam.` and a finite profile.
    fn validate(&self) -> std::result::Result<(), InvalidField> {
        self.beam.validate_within("beam")?;
        if let Some((i, d)) = self
            .profile_delta_m
            .iter()
            .enumerate()
            .find(|(_, d)| !d.is_finite())
        {
            return Err(InvalidField::new(
                format!("profile_delta_m[{i}]"),
                format!("must be finite, got {d}"),
            ));
        }
        Ok(())
    }
}

/// Columns of `profiles.csv`: the DOF index (ξ1, η1, …, ξ5, η5), the assumed deformation
/// (7.1) and the reconstructed deflections δ* of profiles 1 and 2 (Lin §7.1.1/§7.1.2) with
/// fixed-interface modal truncation, Craig–Bampton and mode condensation \[m\].
pub const PROFILE_COLUMNS: [&str; 8] = [
    "dof_index",
    "reference_m",
    "p1_mt_m",
    "p1_cb_m",
    "p1_mc_m",
    "p2_mt_m",
    "p2_cb_m",
    "p2_mc_m",
];

/// Columns of `frequencies.csv`: the set (0 free-free, 1 Guyan (a), 2 Guyan (b),
/// 3 fixed-interface, 4 mean-axes normal), the mode index and its frequency \[Hz\].
pub const FREQUENCY_COLUMNS: [&str; 3] = ["set_index", "mode_index", "frequency_Hz"];

/// Result of [`lin_beam`].
#[derive(Debug, Clone)]
pub struct LinBeamRun {
    /// The summary.
    pub summary: LinBeamSummary,
    /// The ch. 7.1 profile tests.
    pub profiles: ProfileStudy,
    /// Axial positions ξ of the five nodes \[m\] (Lin Table A-1).
    pub axial_positions_m: [f64; 5],
    /// The assumed deformation (7.1) \[m\].
    pub profile_delta_m: [f64; 10],
}

impl LinBeamRun {
    /// The rows of `profiles.csv` ([`PROFILE_COLUMNS`]), one per DOF.
    pub fn profile_rows(&self) -> Vec<Vec<f64>> {
        (0..10)
            .map(|i| {
                let mut r = vec![i as f64, self.profile_delta_m[i]];
                r.extend(self.profiles.profile1.iter().map(|p| p.delta[i]));
                r.extend(self.profiles.profile2.iter().map(|p| p.delta[i]));
                r
            })
            .collect()
    }

    /// The rows of `frequencies.csv` ([`FREQUENCY_COLUMNS`]).
    pub fn frequency_rows(&self) -> Vec<[f64; 3]> {
        let s = &self.summary;
        [
            &s.free_free_hz,
            &s.guyan_a_hz,
            &s.guyan_b_hz,
            &s.fixed_interface_hz,
            &s.mean_axes_normal_hz,
        ]
        .into_iter()
        .enumerate()
        .flat_map(|(set, v)| {
            v.iter()
                .enumerate()
                .map(move |(i, f)| [set as f64, i as f64, *f])
        })
        .collect()
    }
}

/// Every beam study of Lin ch. 6–8 on the beam of `c` ([`beam::summary_with`],
/// [`beam::profile_study_with`]): free-free, Guyan (a)/(b) (Lin §6.2), fixed-interface
/// (§6.3) and mean-axes (8.45) frequencies, and the profile tests of §7.1.
pub fn lin_beam(c: &LinBeamStudyConfig) -> Result<LinBeamRun> {
    let b = beam::beam_from(&c.beam)?;
    let summary = beam::summary_with(&b, &c.profile_delta_m)?;
    let profiles = beam::profile_study_with(&b, &c.profile_delta_m)?;
    let axial_positions_m = std::array::from_fn(|j| b.s[2 * j]);
    Ok(LinBeamRun {
        summary,
        profiles,
        axial_positions_m,
        profile_delta_m: c.profile_delta_m,
    })
}
