//! `flowmbd-reduce lin-slab`: Lin (2005) §7.2 simulations 1–3 on the Appendix B slab,
//! comparing no reduction (NR), Guyan (GR), fixed-interface modal truncation (MT),
//! Craig–Bampton (CB) and mode condensation (MC); local deflections of node 8. Simulation 3
//! first regenerates Lin's acceleration tables with the previous simulation of Fig. 7-12(b)
//! (`flowmbd_cases::lin::slab_sim3`, assumptions in its docs) and writes them to
//! `sim3_tables.csv`.

use flowmbd_cases::lin::slab::{self, SlabMethod};
use flowmbd_cases::lin::slab_sim::{SlabSimConfig, SlabSimulation, simulate};
use flowmbd_cases::lin::slab_sim3::{DRIVEN_NODES, record_source, simulate_emulated};
use flowmbd_cli::config::Validate;
use flowmbd_cli::error::InputError;
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::study::{Study, StudyContext, StudyError};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::sync::Arc;

/// Configuration; the defaults reproduce Lin's set-up (6 kept modes, R = 4 m, T = 1 s) with the
/// companion's integrator choice (RK4, 1 ms, 1 s).
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// Simulations to run (`no-rigid-motion` = Sim 1, `orbit` = Sim 2, `emulated` = Sim 3).
    pub simulations: Vec<SlabSimulation>,
    /// Models to compare (NR must be present: it is the reference).
    pub methods: Vec<SlabMethod>,
    /// Duration, step, kept modes, orbit parameters.
    pub params: SlabSimConfig,
}

impl Default for Config {
    fn default() -> Self {
        Self {
            simulations: vec![
                SlabSimulation::NoRigidMotion,
                SlabSimulation::Orbit,
                SlabSimulation::Emulated,
            ],
            methods: SlabMethod::ALL.to_vec(),
            params: SlabSimConfig::default(),
        }
    }
}

impl flowmbd_cli::PartialRules for Config {}

impl Validate for Config {
    fn validate(&self) -> Result<(), InputError> {
        self.params.validate_within("params")?;
        if !self.methods.contains(&SlabMethod::NoReduction) {
            return Err(InputError::new(
                "methods",
                "must contain \"no-reduction\" (the reference)",
            ));
        }
        if self.simulations.is_empty() {
            return Err(InputError::new("simulations", "must not be empty"));
        }
        Ok(())
    }
}

/// Per simulation and method: RMS difference from NR per component \[m\], constraint drift \[m\].
#[derive(Debug, Clone, Serialize)]
pub struct MethodResult {
    /// RMS of δ'8 − δ'8(NR) over the run, components ξ, η, ζ \[m\].
    pub rms_vs_nr_m: [f64; 3],
    /// Largest |δ'8| per component \[m\].
    pub peak_m: [f64; 3],
    /// Largest position-level constraint residual \[m\].
    pub max_drift_m: f64,
}

/// Summary of `lin-slab`.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// Linearised gravity statics of simulation 1, δ'8 per method \[m\].
    pub sim1_statics_m: BTreeMap<String, [f64; 3]>,
    /// Per simulation, per method.
    pub simulations: BTreeMap<String, BTreeMap<String, MethodResult>>,
    /// Largest |δ'8(CB) − δ'8(MC)| per simulation \[m\] (Lin §6.5.4: zero up to round-off).
    pub cb_mc_max_difference_m: BTreeMap<String, f64>,
    /// Simulation 3 only: the previous simulation that produced the tables.
    pub sim3_source: Option<Sim3Source>,
}

/// The previous simulation of simulation 3 (Lin Fig. 7-12(b)).
#[derive(Debug, Clone, Serialize)]
pub struct Sim3Source {
    /// Number of table rows (samples) and their interval \[s\].
    pub samples: usize,
    /// Sampling interval \[s\].
    pub interval_s: f64,
    /// Largest position-level constraint residual of the source run \[m\].
    pub max_drift_m: f64,
    /// Largest |δ'8| of the source run \[m\].
    pub peak_node8_m: f64,
    /// Largest |δ'8(NR emulation) − δ'8(source)| \[m\]: the table interpolation error.
    pub nr_emulation_vs_source_m: Option<f64>,
}

/// The study.
pub struct LinSlabStudy;

fn sim_name(s: SlabSimulation) -> &'static str {
    match s {
        SlabSimulation::NoRigidMotion => "sim1",
        SlabSimulation::Orbit => "sim2",
        SlabSimulation::Emulated => "sim3",
    }
}

impl Study for LinSlabStudy {
    type Config = Config;
    type Summary = Summary;
    const NAME: &'static str = "lin-slab";
    const MEANING: &'static str = "Lin 7.2 simulations 1-3 on the Appendix B slab: the local deflections of node 8 [m] \
         in the floating frame for every reduction method (Newton-Raphson on the full model, \
         Guyan, modal truncation, Craig-Bampton, mode condensation), the linearised gravity \
         statics of simulation 1, and simulation 3 against Lin's printed tables; the methods \
         agree where the reduction basis spans the loading.";

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let s = slab::appendix_b_slab().map_err(StudyError::numerical)?;
        let mut statics = BTreeMap::new();
        for &m in &c.methods {
            let b = slab::slab_basis(&s, m, c.params.n_modes).map_err(StudyError::numerical)?;
            statics.insert(
                m.label().to_string(),
                slab::sim1_statics(&s, &b).map_err(StudyError::numerical)?,
            );
        }
        let total = (c.simulations.len() * c.methods.len()) as f64;
        let bar = ctx.progress(total, "slab simulations");
        let mut done = 0.0;
        let mut sims = BTreeMap::new();
        let mut cbmc = BTreeMap::new();
        let mut sim3_source = None;
        for &sim in &c.simulations {
            let mut hist: Vec<(SlabMethod, Vec<f64>, Vec<[f64; 3]>)> = Vec::new();
            let mut drifts = Vec::new();
            let source = if sim == SlabSimulation::Emulated {
                let src = record_source(&s, &c.params).map_err(StudyError::numerical)?;
                write_sim3_tables(ctx, &src)?;
                Some(src)
            } else {
                None
            };
            let table = source.as_ref().map(|x| Arc::new(x.table.clone()));
            for &m in &c.methods {
                let mut t = Vec::new();
                let mut h = Vec::new();
                let cancel = ctx.cancel.clone();
                let obs = |ti: f64, d: [f64; 3]| {
                    t.push(ti);
                    h.push(d);
                    cancel.check()
                };
                let res = match &table {
                    Some(tab) => simulate_emulated(&s, m, tab, &c.params, obs),
                    None => simulate(&s, m, sim, &c.params, obs),
                };
                let drift = res.map_err(|e| StudyError::Numerical {
                    message: e.to_string(),
                    partial: serde_json::to_value(&statics).ok(),
                })?;
                drifts.push(drift);
                hist.push((m, t, h));
                done += 1.0;
                bar.set(done);
                if ctx.cancel.is_cancelled() {
                    break;
                }
            }
            if ctx.cancel.is_cancelled() {
                // interrupted: the summary holds the simulations completed before
                break;
            }
            let name = sim_name(sim);
            // CSV: t, then ξ, η, ζ per method
            let mut header = vec!["t_s".to_string()];
            for (m, _, _) in &hist {
                for comp in ["xi", "eta", "zeta"] {
                    header.push(format!("{}_{comp}_m", m.label()));
                }
            }
            let n = hist[0].1.len();
            let rows: Vec<Vec<f64>> = (0..n)
                .map(|i| {
                    let mut r = vec![hist[0].1[i]];
                    for (_, _, h) in &hist {
                        r.extend_from_slice(&h[i]);
                    }
                    r
                })
                .collect();
            ctx.out.write_csv(
                &format!("{name}_node8.csv"),
                &header,
                rows.iter().map(|r| r.as_slice()),
            )?;
            for (comp, label) in ["ξ", "η", "ζ"].iter().enumerate() {
                let mut plot = LinePlot::new(
                    format!("Lin slab {name}: local deflection δ'{label} of node 8"),
                    "time [s]",
                    format!("δ'{label}8 [m]"),
                );
                for (m, t, h) in &hist {
                    plot = plot.with(Series::line(
                        m.label(),
                        t.iter().zip(h).map(|(a, b)| (*a, b[comp])).collect(),
                    ));
                }
                plot.save(
                    &ctx.out
                        .path(&format!("{name}_{}", ["xi", "eta", "zeta"][comp])),
                )?;
            }
            let nr = &hist
                .iter()
                .find(|x| x.0 == SlabMethod::NoReduction)
                .expect("validated")
                .2;
            let mut per = BTreeMap::new();
            for ((m, _, h), drift) in hist.iter().zip(&drifts) {
                let mut rms = [0.0; 3];
                let mut peak = [0.0f64; 3];
                for (a, b) in h.iter().zip(nr) {
                    for k in 0..3 {
                        rms[k] += (a[k] - b[k]).powi(2);
                        peak[k] = peak[k].max(a[k].abs());
                    }
                }
                for r in rms.iter_mut() {
                    *r = (*r / h.len() as f64).sqrt();
                }
                per.insert(
                    m.label().to_string(),
                    MethodResult {
                        rms_vs_nr_m: rms,
                        peak_m: peak,
                        max_drift_m: *drift,
                    },
                );
            }
            let get = |x: SlabMethod| hist.iter().find(|y| y.0 == x).map(|y| &y.2);
            if let (Some(a), Some(b)) = (
                get(SlabMethod::CraigBampton),
                get(SlabMethod::ModeCondensation),
            ) {
                let d = a
                    .iter()
                    .zip(b)
                    .map(|(x, y)| (0..3).map(|k| (x[k] - y[k]).abs()).fold(0.0, f64::max))
                    .fold(0.0, f64::max);
                cbmc.insert(name.to_string(), d);
            }
            if let Some(src) = &source {
                let vs = get(SlabMethod::NoReduction).map(|h| {
                    h.iter()
                        .zip(&src.node8)
                        .map(|(x, y)| (0..3).map(|k| (x[k] - y[k]).abs()).fold(0.0, f64::max))
                        .fold(0.0, f64::max)
                });
                sim3_source = Some(Sim3Source {
                    samples: src.table.acc.len(),
                    interval_s: src.table.interval_s,
                    max_drift_m: src.max_drift_m,
                    peak_node8_m: src
                        .node8
                        .iter()
                        .flat_map(|x| x.iter().map(|v| v.abs()))
                        .fold(0.0, f64::max),
                    nr_emulation_vs_source_m: vs,
                });
            }
            sims.insert(name.to_string(), per);
        }
        bar.finish();
        Ok(Summary {
            sim1_statics_m: statics,
            simulations: sims,
            cb_mc_max_difference_m: cbmc,
            sim3_source,
        })
    }
}

/// Writes the regenerated tables (`sim3_tables.csv`: t, then x, y, z accelerations of nodes 16,
/// 18, 28, 30 \[m/s²\]) and the source's node-8 history (`sim3_source_node8.csv`).
fn write_sim3_tables(
    ctx: &mut StudyContext, src: &flowmbd_cases::lin::slab_sim3::SourceRun,
) -> Result<(), StudyError> {
    let mut header = vec!["t_s".to_string()];
    for j in DRIVEN_NODES {
        for c in ["x", "y", "z"] {
            header.push(format!("a{c}{j}_m_per_s2"));
        }
    }
    let rows: Vec<Vec<f64>> = src
        .table
        .acc
        .iter()
        .enumerate()
        .map(|(k, a)| {
            let mut r = vec![k as f64 * src.table.interval_s];
            for v in a {
                r.extend_from_slice(&[v.x, v.y, v.z]);
            }
            r
        })
        .collect();
    ctx.out.write_csv(
        "sim3_tables.csv",
        &header,
        rows.iter().map(|r| r.as_slice()),
    )?;
    let rows: Vec<[f64; 4]> = src
        .t
        .iter()
        .zip(&src.node8)
        .map(|(t, d)| [*t, d[0], d[1], d[2]])
        .collect();
    ctx.out.write_csv(
        "sim3_source_node8.csv",
        &["t_s", "xi_m", "eta_m", "zeta_m"],
        rows.iter().map(|r| r.as_slice()),
    )?;
    Ok(())
}
