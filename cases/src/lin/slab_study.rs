//! The `flowmbd-reduce lin-slab` study: Lin (2005) §7.2 simulations 1–3 on the Appendix B
//! slab ([`super::slab`]), comparing no reduction (NR), Guyan (GR), fixed-interface modal
//! truncation (MT), Craig–Bampton (CB) and mode condensation (MC) by the local deflection of
//! node 8. Simulation 3 first regenerates Lin's acceleration tables with the previous
//! simulation of Fig. 7-12(b) ([`super::slab_sim3`], assumptions in its docs). Configuration,
//! run, summary and CSV series, shared by the app and the Python package
//! (`flowmbd.reduce.lin_slab`).

use super::slab::{self, SlabMethod};
use super::slab_sim::{SlabSimConfig, SlabSimulation, simulate};
use super::slab_sim3::{DRIVEN_NODES, SourceRun, record_source, simulate_emulated};
use mbd_core::validate::{InvalidField, Validate};
use reduction::ReductionError;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::ops::ControlFlow;
use std::sync::Arc;

/// Configuration of `lin-slab`; the defaults reproduce Lin's set-up (6 kept modes, R = 4 m,
/// T = 1 s) with the companion's integrator choice (RK4, 1 ms, 1 s).
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct LinSlabConfig {
    /// Simulations to run (`no-rigid-motion` = Sim 1, `orbit` = Sim 2, `emulated` = Sim 3).
    pub simulations: Vec<SlabSimulation>,
    /// Models to compare (NR must be present: it is the reference).
    pub methods: Vec<SlabMethod>,
    /// Duration, step, kept modes, orbit parameters.
    pub params: SlabSimConfig,
}

impl Default for LinSlabConfig {
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

impl mbd_core::config::PartialRules for LinSlabConfig {}

impl Validate for LinSlabConfig {
    /// The parameters' checks under `params.`, NR among the methods, at least one simulation.
    fn validate(&self) -> Result<(), InvalidField> {
        self.params.validate_within("params")?;
        if !self.methods.contains(&SlabMethod::NoReduction) {
            return Err(InvalidField::new(
                "methods",
                "must contain \"no-reduction\" (the reference)",
            ));
        }
        if self.simulations.is_empty() {
            return Err(InvalidField::new("simulations", "must not be empty"));
        }
        Ok(())
    }
}

/// The `meaning` of the `lin-slab` summary.
pub const LIN_SLAB_MEANING: &str = "Lin 7.2 simulations 1-3 on the Appendix B slab: the local deflections of node 8 [m] \
     in the floating frame for every reduction method (Newton-Raphson on the full model, \
     Guyan, modal truncation, Craig-Bampton, mode condensation), the linearised gravity \
     statics of simulation 1, and simulation 3 against Lin's printed tables; the methods \
     agree where the reduction basis spans the loading.";

/// Per simulation and method: RMS difference from NR per component \[m\], constraint drift \[m\].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MethodResult {
    /// RMS of δ'8 − δ'8(NR) over the run, components ξ, η, ζ \[m\].
    pub rms_vs_nr_m: [f64; 3],
    /// Largest |δ'8| per component \[m\].
    pub peak_m: [f64; 3],
    /// Largest position-level constraint residual \[m\].
    pub max_drift_m: f64,
}

/// Summary of `lin-slab`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LinSlabSummary {
    /// Linearised gravity statics of simulation 1, δ'8 per method \[m\].
    pub sim1_statics_m: BTreeMap<String, [f64; 3]>,
    /// Per simulation (`sim1`, `sim2`, `sim3`), per method (NR, GR, MT, CB, MC).
    pub simulations: BTreeMap<String, BTreeMap<String, MethodResult>>,
    /// Largest |δ'8(CB) − δ'8(MC)| per simulation \[m\] (Lin §6.5.4: zero up to round-off).
    pub cb_mc_max_difference_m: BTreeMap<String, f64>,
    /// Simulation 3 only: the previous simulation that produced the tables.
    pub sim3_source: Option<Sim3Source>,
    /// What the numbers mean ([`LIN_SLAB_MEANING`]).
    pub meaning: String,
}

/// The previous simulation of simulation 3 (Lin Fig. 7-12(b)).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sim3Source {
    /// Number of table rows (samples).
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

/// Failure of `lin-slab`.
#[derive(Debug, thiserror::Error)]
pub enum LinSlabError {
    /// Unusable configuration (the field and why).
    #[error("{0}")]
    Input(InvalidField),
    /// A model or simulation failed; `partial_statics_m` holds the simulation-1 statics when
    /// they were computed before the failure.
    #[error("{source}")]
    Numerical {
        /// The failure.
        #[source]
        source: ReductionError,
        /// [`LinSlabSummary::sim1_statics_m`] computed so far.
        partial_statics_m: Option<BTreeMap<String, [f64; 3]>>,
    },
}

impl From<ReductionError> for LinSlabError {
    fn from(source: ReductionError) -> Self {
        Self::Numerical {
            source,
            partial_statics_m: None,
        }
    }
}

/// The node-8 history of one method in one simulation.
#[derive(Debug, Clone, PartialEq)]
pub struct MethodHistory {
    /// The method.
    pub method: SlabMethod,
    /// Times \[s\].
    pub t: Vec<f64>,
    /// Local deflection δ'8 (ξ, η, ζ) at those times \[m\].
    pub node8_m: Vec<[f64; 3]>,
}

/// The histories of one simulation, one per method in the configuration's order.
#[derive(Debug, Clone, PartialEq)]
pub struct SimulationRun {
    /// `sim1`, `sim2` or `sim3` (the CSV file is `<name>_node8.csv`).
    pub name: &'static str,
    /// One history per method.
    pub histories: Vec<MethodHistory>,
}

impl SimulationRun {
    /// Columns of `<name>_node8.csv`: `t_s`, then `<method>_xi_m`, `<method>_eta_m`,
    /// `<method>_zeta_m` per method (δ'8 \[m\]).
    pub fn node8_header(&self) -> Vec<String> {
        let mut header = vec!["t_s".to_string()];
        for h in &self.histories {
            for comp in ["xi", "eta", "zeta"] {
                header.push(format!("{}_{comp}_m", h.method.label()));
            }
        }
        header
    }

    /// The rows of `<name>_node8.csv` ([`Self::node8_header`]).
    pub fn node8_rows(&self) -> Vec<Vec<f64>> {
        let Some(first) = self.histories.first() else {
            return Vec::new();
        };
        (0..first.t.len())
            .map(|i| {
                let mut r = vec![first.t[i]];
                for h in &self.histories {
                    r.extend_from_slice(&h.node8_m[i]);
                }
                r
            })
            .collect()
    }
}

/// Result of [`lin_slab`].
#[derive(Debug, Clone)]
pub struct LinSlabRun {
    /// The summary.
    pub summary: LinSlabSummary,
    /// The completed simulations' histories.
    pub simulations: Vec<SimulationRun>,
    /// Simulation 3's previous simulation (its tables and node-8 history), when run (also when
    /// the emulations were interrupted afterwards).
    pub sim3_source: Option<SourceRun>,
}

/// Columns of `sim3_tables.csv`: `t_s`, then the x, y, z accelerations of nodes 16, 18, 28, 30
/// (`a<c><node>_m_per_s2` \[m/s²\]).
pub fn sim3_tables_header() -> Vec<String> {
    let mut header = vec!["t_s".to_string()];
    for j in DRIVEN_NODES {
        for c in ["x", "y", "z"] {
            header.push(format!("a{c}{j}_m_per_s2"));
        }
    }
    header
}

/// The rows of `sim3_tables.csv` ([`sim3_tables_header`]).
pub fn sim3_tables_rows(src: &SourceRun) -> Vec<Vec<f64>> {
    src.table
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
        .collect()
}

/// Columns of `sim3_source_node8.csv`: time \[s\] and δ'8 of the source run \[m\].
pub const SIM3_SOURCE_COLUMNS: [&str; 4] = ["t_s", "xi_m", "eta_m", "zeta_m"];

/// The rows of `sim3_source_node8.csv` ([`SIM3_SOURCE_COLUMNS`]).
pub fn sim3_source_rows(src: &SourceRun) -> Vec<[f64; 4]> {
    src.t
        .iter()
        .zip(&src.node8)
        .map(|(t, d)| [*t, d[0], d[1], d[2]])
        .collect()
}

fn sim_name(s: SlabSimulation) -> &'static str {
    match s {
        SlabSimulation::NoRigidMotion => "sim1",
        SlabSimulation::Orbit => "sim2",
        SlabSimulation::Emulated => "sim3",
    }
}

/// Largest componentwise |a − b| over two node-8 histories \[m\].
fn max_difference(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (0..3).map(|k| (x[k] - y[k]).abs()).fold(0.0, f64::max))
        .fold(0.0, f64::max)
}

/// RMS difference from the reference `nr` and peak per component of the history `h` \[m\].
fn method_result(h: &[[f64; 3]], nr: &[[f64; 3]], drift: f64) -> MethodResult {
    let mut rms = [0.0; 3];
    let mut peak = [0.0f64; 3];
    for (a, b) in h.iter().zip(nr) {
        for k in 0..3 {
            rms[k] += (a[k] - b[k]).powi(2);
            peak[k] = peak[k].max(a[k].abs());
        }
    }
    for r in rms.iter_mut() {
        *r = (*r / h.len().max(1) as f64).sqrt();
    }
    MethodResult {
        rms_vs_nr_m: rms,
        peak_m: peak,
        max_drift_m: drift,
    }
}

/// Run the simulations of `c` for every method (Lin §7.2): the gravity statics of simulation
/// 1 per method, then each simulation's node-8 histories and their comparison with NR.
/// `progress` gets the fraction done at every step; a `Break` stops the run, the summary then
/// holds the simulations completed before.
pub fn lin_slab(
    c: &LinSlabConfig, mut progress: impl FnMut(f64) -> ControlFlow<()>,
) -> Result<LinSlabRun, LinSlabError> {
    c.validate().map_err(LinSlabError::Input)?;
    let s = slab::appendix_b_slab()?;
    let mut statics = BTreeMap::new();
    for &m in &c.methods {
        let b = slab::slab_basis(&s, m, c.params.n_modes)?;
        statics.insert(m.label().to_string(), slab::sim1_statics(&s, &b)?);
    }
    let total = (c.simulations.len() * c.methods.len()) as f64;
    let duration = c.params.duration_s;
    let mut done = 0.0;
    let mut stopped = false;
    let mut runs = Vec::new();
    let mut sims = BTreeMap::new();
    let mut cbmc = BTreeMap::new();
    let mut sim3 = None;
    let mut sim3_source = None;
    for &sim in &c.simulations {
        let failed = |source| LinSlabError::Numerical {
            source,
            partial_statics_m: Some(statics.clone()),
        };
        if sim == SlabSimulation::Emulated {
            sim3 = Some(record_source(&s, &c.params).map_err(failed)?);
        }
        let source = sim3.as_ref().filter(|_| sim == SlabSimulation::Emulated);
        let table = source.as_ref().map(|x| Arc::new(x.table.clone()));
        let mut hist: Vec<MethodHistory> = Vec::new();
        let mut drifts = Vec::new();
        for &m in &c.methods {
            let mut t = Vec::new();
            let mut h = Vec::new();
            let obs = |ti: f64, d: [f64; 3]| {
                t.push(ti);
                h.push(d);
                let answer = progress((done + ti / duration) / total);
                stopped |= answer.is_break();
                answer
            };
            let res = match &table {
                Some(tab) => simulate_emulated(&s, m, tab, &c.params, obs),
                None => simulate(&s, m, sim, &c.params, obs),
            };
            drifts.push(res.map_err(failed)?);
            hist.push(MethodHistory {
                method: m,
                t,
                node8_m: h,
            });
            done += 1.0;
            if stopped {
                break;
            }
        }
        if stopped {
            // interrupted: the summary holds the simulations completed before
            break;
        }
        let name = sim_name(sim);
        let get = |x: SlabMethod| hist.iter().find(|y| y.method == x).map(|y| &y.node8_m);
        let Some(nr) = get(SlabMethod::NoReduction) else {
            return Err(LinSlabError::Input(InvalidField::new(
                "methods",
                "must contain \"no-reduction\" (the reference)",
            )));
        };
        let per: BTreeMap<String, MethodResult> = hist
            .iter()
            .zip(&drifts)
            .map(|(x, drift)| {
                let r = method_result(&x.node8_m, nr, *drift);
                (x.method.label().to_string(), r)
            })
            .collect();
        if let (Some(a), Some(b)) = (
            get(SlabMethod::CraigBampton),
            get(SlabMethod::ModeCondensation),
        ) {
            cbmc.insert(name.to_string(), max_difference(a, b));
        }
        if let Some(src) = source {
            sim3_source = Some(Sim3Source {
                samples: src.table.acc.len(),
                interval_s: src.table.interval_s,
                max_drift_m: src.max_drift_m,
                peak_node8_m: src
                    .node8
                    .iter()
                    .flat_map(|x| x.iter().map(|v| v.abs()))
                    .fold(0.0, f64::max),
                nr_emulation_vs_source_m: Some(max_difference(nr, &src.node8)),
            });
        }
        sims.insert(name.to_string(), per);
        runs.push(SimulationRun {
            name,
            histories: hist,
        });
    }
    Ok(LinSlabRun {
        summary: LinSlabSummary {
            sim1_statics_m: statics,
            simulations: sims,
            cb_mc_max_difference_m: cbmc,
            sim3_source,
            meaning: LIN_SLAB_MEANING.to_string(),
        },
        simulations: runs,
        sim3_source: sim3,
    })
}
