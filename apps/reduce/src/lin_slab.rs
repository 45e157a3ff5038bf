//! `flowmbd-reduce lin-slab`: Lin (2005) §7.2 simulations 1–3 on the Appendix B slab
//! (configuration, run, summary and series in `flowmbd_cases::lin::slab_study`); writes
//! `<sim>_node8.csv`, `sim3_tables.csv`, `sim3_source_node8.csv` and the plots.

use flowmbd_cases::lin::slab_study::{
    self as study, LinSlabConfig, LinSlabError, LinSlabSummary, SIM3_SOURCE_COLUMNS,
};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::study::{Study, StudyContext, StudyError};

/// The study.
pub struct LinSlabStudy;

impl Study for LinSlabStudy {
    type Config = LinSlabConfig;
    type Summary = LinSlabSummary;
    const NAME: &'static str = "lin-slab";

    fn run(&self, c: &LinSlabConfig, ctx: &mut StudyContext) -> Result<LinSlabSummary, StudyError> {
        let bar = ctx.progress(1.0, "slab simulations");
        let run = study::lin_slab(c, |f| ctx.tick(&bar, f)).map_err(|e| match e {
            LinSlabError::Input(e) => StudyError::Input(e),
            LinSlabError::Numerical {
                source,
                partial_statics_m,
            } => StudyError::Numerical {
                message: source.to_string(),
                partial: partial_statics_m.and_then(|p| serde_json::to_value(p).ok()),
            },
        })?;
        bar.finish();
        if let Some(src) = &run.sim3_source {
            let header = study::sim3_tables_header();
            ctx.out
                .write_csv("sim3_tables.csv", &header, study::sim3_tables_rows(src))?;
            ctx.out.write_csv(
                "sim3_source_node8.csv",
                &SIM3_SOURCE_COLUMNS,
                study::sim3_source_rows(src),
            )?;
        }
        for sim in &run.simulations {
            let name = sim.name;
            ctx.out.write_csv(
                &format!("{name}_node8.csv"),
                &sim.node8_header(),
                sim.node8_rows(),
            )?;
            for (comp, label) in ["ξ", "η", "ζ"].iter().enumerate() {
                let mut plot = LinePlot::new(
                    format!("Lin slab {name}: local deflection δ'{label} of node 8"),
                    "time [s]",
                    format!("δ'{label}8 [m]"),
                );
                for h in &sim.histories {
                    plot = plot.with(Series::line(
                        h.method.label(),
                        h.t.iter()
                            .zip(&h.node8_m)
                            .map(|(a, b)| (*a, b[comp]))
                            .collect(),
                    ));
                }
                plot.save(
                    &ctx.out
                        .path(&format!("{name}_{}", ["xi", "eta", "zeta"][comp])),
                )?;
            }
        }
        Ok(run.summary)
    }
}
