//! `flowmbd-reduce lin-beam`: Lin (2005) ch. 6.2, 6.3, 7.1 and 8.5 on the Appendix A beam.

use flowmbd_cases::lin::beam::{self, LinBeamConfig, LinBeamSummary, PROFILE_DELTA};
use flowmbd_cli::config::Validate;
use flowmbd_cli::error::InputError;
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::study::{Study, StudyContext, StudyError};
use serde::{Deserialize, Serialize};

/// Configuration; the defaults are Lin's Appendix A beam and profile (7.1).
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// The beam (Appendix A).
    pub beam: LinBeamConfig,
    /// Assumed deformation of the profile tests, DOF order ξ1, η1, …, ξ5, η5 \[m\] (Lin (7.1)).
    pub profile_delta_m: [f64; 10],
}

impl Default for Config {
    fn default() -> Self {
        Self {
            beam: LinBeamConfig::default(),
            profile_delta_m: PROFILE_DELTA,
        }
    }
}

impl flowmbd_cli::PartialRules for Config {}

impl Validate for Config {
    fn validate(&self) -> Result<(), InputError> {
        self.beam.validate_within("beam")?;
        if let Some((i, d)) = self
            .profile_delta_m
            .iter()
            .enumerate()
            .find(|(_, d)| !d.is_finite())
        {
            return Err(InputError::new(
                format!("profile_delta_m[{i}]"),
                format!("must be finite, got {d}"),
            ));
        }
        Ok(())
    }
}

/// The study.
pub struct LinBeamStudy;

impl Study for LinBeamStudy {
    type Config = Config;
    type Summary = LinBeamSummary;
    const NAME: &'static str = "lin-beam";
    const MEANING: &'static str = "Lin ch. 6-8 on the Appendix A beam: the frequencies of the full model and of the \
         reduced models (Guyan, modal truncation, Craig-Bampton, mode condensation) compared \
         with Lin's tables, the deflection profiles of the profile tests [m] and the \
         mean-axis frame: how well each reduction reproduces the full model.";

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<LinBeamSummary, StudyError> {
        let b = beam::beam_from(&c.beam).map_err(StudyError::numerical)?;
        let summary = beam::summary_with(&b, &c.profile_delta_m).map_err(StudyError::numerical)?;
        let prof =
            beam::profile_study_with(&b, &c.profile_delta_m).map_err(StudyError::numerical)?;
        // profiles: one row per DOF
        let header = [
            "dof_index",
            "reference_m",
            "p1_mt_m",
            "p1_cb_m",
            "p1_mc_m",
            "p2_mt_m",
            "p2_cb_m",
            "p2_mc_m",
        ];
        let rows: Vec<Vec<f64>> = (0..10)
            .map(|i| {
                let mut r = vec![i as f64, c.profile_delta_m[i]];
                r.extend(prof.profile1.iter().map(|p| p.delta[i]));
                r.extend(prof.profile2.iter().map(|p| p.delta[i]));
                r
            })
            .collect();
        ctx.out
            .write_csv("profiles.csv", &header, rows.iter().map(|r| r.as_slice()))?;
        let mut fr = ctx.out.csv(
            "frequencies.csv",
            &["set_index", "mode_index", "frequency_Hz"],
        )?;
        for (set, v) in [
            (0.0, &summary.free_free_hz),
            (1.0, &summary.guyan_a_hz),
            (2.0, &summary.guyan_b_hz),
            (3.0, &summary.fixed_interface_hz),
            (4.0, &summary.mean_axes_normal_hz),
        ] {
            for (i, f) in v.iter().enumerate() {
                fr.row(&[set, i as f64, *f])?;
            }
        }
        fr.finish()?;
        // deformed profiles: transverse deflection η against the axial position ξ + δξ
        let xi: Vec<f64> = (0..5).map(|j| b.s[2 * j]).collect();
        let curve = |d: &[f64]| -> Vec<(f64, f64)> {
            (0..5).map(|j| (xi[j] + d[2 * j], d[2 * j + 1])).collect()
        };
        for (k, profile) in [&prof.profile1, &prof.profile2].iter().enumerate() {
            let plot = LinePlot::new(
                format!("Lin beam, profile {} (Fig. 7-{})", k + 1, k + 1),
                "axial position ξ + δξ [m]",
                "transverse deflection δη [m]",
            )
            .with(Series::points("reference (7.1)", curve(&c.profile_delta_m)))
            .with(Series::line("fixed-interface MT", curve(&profile[0].delta)))
            .with(Series::line("Craig-Bampton", curve(&profile[1].delta)))
            .with(Series::line("mode condensation", curve(&profile[2].delta)));
            plot.save(&ctx.out.path(&format!("profile{}", k + 1)))?;
        }
        Ok(summary)
    }
}
