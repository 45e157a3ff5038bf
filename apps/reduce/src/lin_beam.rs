//! `flowmbd-reduce lin-beam`: Lin (2005) ch. 6.2, 6.3, 7.1 and 8.5 on the Appendix A beam
//! (configuration, run and series in `flowmbd_cases::lin::beam_study`).

use flowmbd_cases::lin::beam::LinBeamSummary;
use flowmbd_cases::lin::beam_study::{
    FREQUENCY_COLUMNS, LinBeamStudyConfig, PROFILE_COLUMNS, lin_beam,
};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::study::{Study, StudyContext, StudyError};

/// The study.
pub struct LinBeamStudy;

impl Study for LinBeamStudy {
    type Config = LinBeamStudyConfig;
    type Summary = LinBeamSummary;
    const NAME: &'static str = "lin-beam";

    fn run(
        &self, c: &LinBeamStudyConfig, ctx: &mut StudyContext,
    ) -> Result<LinBeamSummary, StudyError> {
        let run = lin_beam(c).map_err(StudyError::numerical)?;
        ctx.out
            .write_csv("profiles.csv", &PROFILE_COLUMNS, run.profile_rows())?;
        ctx.out
            .write_csv("frequencies.csv", &FREQUENCY_COLUMNS, run.frequency_rows())?;
        // deformed profiles: transverse deflection η against the axial position ξ + δξ
        let xi = run.axial_positions_m;
        let curve = |d: &[f64]| -> Vec<(f64, f64)> {
            (0..5).map(|j| (xi[j] + d[2 * j], d[2 * j + 1])).collect()
        };
        let prof = &run.profiles;
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
        Ok(run.summary)
    }
}
