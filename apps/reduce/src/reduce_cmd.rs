//! `flowmbd-reduce reduce`: reduce user Matrix Market matrices with a boundary node set and
//! write the reduced model (versioned JSON, `reduction::ReducedModel`).
//!
//! ```text
//! flowmbd-reduce reduce --mass M.mtx --stiffness K.mtx --boundary 1,5,10-12 --method cb \
//!     --modes 20 --out model.json [--fixed 1-4] [--dofs-per-node 3] [--json]
//! ```
//!
//! Craig–Bampton and Guyan (CB without modes) at every size go through the library's one
//! partitioned Craig–Bampton, `reduction::sparse::craig_bampton_sparse` (fixed / boundary /
//! interior DOFs, one sparse Cholesky of `K_ii` for the static modes, shift-invert Lanczos with
//! a Sturm check for the fixed-interface modes). The other methods use the dense bases of
//! `reduction::basis`, limited to [`DENSE_LIMIT`] DOFs; Eitelberg's reduction is
//! `reduction::eitelberg_model` (dense, at most 1000 unclamped DOFs).

use fe_model::io::mtx::{self, ReadOptions};
use fe_model::plausibility::{PairCheckOptions, check_stiffness_mass};
use reduction::basis::{Method, ModeSelection, build_basis};
use reduction::eitelberg_model::EitelbergModel;
use reduction::sparse::{CraigBamptonOptions, craig_bampton_sparse};
use reduction::{DofPartition, ReducedModel};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Largest model reduced with dense matrices (methods other than guyan and cb).
pub const DENSE_LIMIT: usize = 3000;

/// Reduction method on the command line.
#[derive(
    clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum MethodArg {
    /// Static condensation (Guyan).
    Guyan,
    /// Craig–Bampton.
    Cb,
    /// Mode condensation (Nikravesh; same span as CB).
    Mc,
    /// Lin's "modal truncation": boundary DOFs + fixed-interface modes, no static modes.
    FixedInterfaceMt,
    /// Free-free modal truncation (the lowest modes of the whole model).
    FreeFreeMt,
    /// Eitelberg's equation-error reduction of the structure onto the boundary DOFs (Lin
    /// §6.6.4; the state-space system and `M⁻¹K` on the boundary, no basis; dense, at most
    /// 1000 unclamped DOFs).
    Eitelberg,
}

impl MethodArg {
    /// The basis method (`None`: Eitelberg, which makes no basis).
    fn method(self) -> Option<Method> {
        Some(match self {
            MethodArg::Guyan => Method::Guyan,
            MethodArg::Cb => Method::CraigBampton,
            MethodArg::Mc => Method::ModeCondensation,
            MethodArg::FixedInterfaceMt => Method::FixedInterfaceModalTruncation,
            MethodArg::FreeFreeMt => Method::FreeFreeModalTruncation,
            MethodArg::Eitelberg => return None,
        })
    }
}

/// Command-line arguments of `reduce`; each overrides the configuration (`--config`, or the
/// defaults of [`ReduceConfig`]).
#[derive(clap::Args, Debug)]
pub struct Args {
    /// TOML configuration (keys as printed by --print-config); flags override it.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Print the effective configuration as TOML and exit.
    #[arg(long)]
    print_config: bool,
    /// Mass matrix (Matrix Market, symmetric positive definite) [kg].
    #[arg(long, value_name = "M.mtx")]
    mass: Option<PathBuf>,
    /// Stiffness matrix (Matrix Market, symmetric) [N/m].
    #[arg(long, value_name = "K.mtx")]
    stiffness: Option<PathBuf>,
    /// Boundary (interface) nodes, 1-based, comma-separated, ranges allowed: `1,5,10-12`.
    #[arg(long, value_name = "NODES")]
    boundary: Option<String>,
    /// Fixed (clamped) nodes, 1-based, same syntax as --boundary; their DOFs are removed.
    #[arg(long, value_name = "NODES")]
    fixed: Option<String>,
    /// Reduction method [default: cb].
    #[arg(long, value_enum)]
    method: Option<MethodArg>,
    /// Number of kept normal modes (ignored by guyan) [default: 10].
    #[arg(long)]
    modes: Option<usize>,
    /// DOFs per node (node j owns DOFs dofs_per_node·(j−1) .. dofs_per_node·j − 1) [default: 3].
    #[arg(long)]
    dofs_per_node: Option<usize>,
    /// Output file of the reduced model (versioned JSON).
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Print the summary as JSON on stdout.
    #[arg(long)]
    json: bool,
    /// No messages on stderr.
    #[arg(long)]
    quiet: bool,
    /// Accept matrices above the reader's size ceiling (10^7 rows or columns), as every
    /// study's --allow-large.
    #[arg(long)]
    allow_large: bool,
}

/// The configuration of `reduce` (a TOML file given with `--config`; every flag overrides its
/// key). Paths are as given (relative to the working directory).
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema, PartialEq)]
#[serde(default, deny_unknown_fields)]
pub struct ReduceConfig {
    /// Mass matrix (Matrix Market).
    pub mass: String,
    /// Stiffness matrix (Matrix Market).
    pub stiffness: String,
    /// Boundary nodes (`1,5,10-12`).
    pub boundary: String,
    /// Fixed nodes (same syntax; empty: none).
    pub fixed: String,
    /// Reduction method.
    pub method: MethodArg,
    /// Kept normal modes (ignored by guyan).
    pub modes: usize,
    /// DOFs per node.
    pub dofs_per_node: usize,
}

impl flowmbd_cli::PartialRules for ReduceConfig {}

impl Default for ReduceConfig {
    fn default() -> Self {
        Self {
            mass: String::new(),
            stiffness: String::new(),
            boundary: String::new(),
            fixed: String::new(),
            method: MethodArg::Cb,
            modes: 10,
            dofs_per_node: 3,
        }
    }
}

/// Most kept modes a reduction may ask for (raised 1000-fold by `--allow-large`); the
/// library refuses more modes than the model has in any case.
pub const MAX_MODES: usize = 100_000;

/// The configuration from `--config` (or the defaults) with the flags applied.
fn effective_config(a: &Args) -> Result<ReduceConfig, Failure> {
    let mut c: ReduceConfig = match &a.config {
        Some(p) => {
            let text = flowmbd_cli::config::read_config_text(p)
                .map_err(|e| Failure::Input(format!("--config {e}")))?;
            flowmbd_cli::config::parse_config(&text, p)
                .map_err(|e| Failure::Input(format!("--config {e}")))?
        }
        None => ReduceConfig::default(),
    };
    let path = |p: &Option<PathBuf>| p.as_ref().map(|p| p.display().to_string());
    if let Some(v) = path(&a.mass) {
        c.mass = v;
    }
    if let Some(v) = path(&a.stiffness) {
        c.stiffness = v;
    }
    if let Some(v) = &a.boundary {
        c.boundary = v.clone();
    }
    if let Some(v) = &a.fixed {
        c.fixed = v.clone();
    }
    if let Some(v) = a.method {
        c.method = v;
    }
    if let Some(v) = a.modes {
        c.modes = v;
    }
    if let Some(v) = a.dofs_per_node {
        c.dofs_per_node = v;
    }
    Ok(c)
}

/// Summary of a `reduce` run.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// Method.
    pub method: String,
    /// DOFs of the full model.
    pub n_full: usize,
    /// Boundary DOFs kept.
    pub n_boundary: usize,
    /// Fixed (clamped) DOFs.
    pub n_fixed: usize,
    /// Reduced coordinates.
    pub n_reduced: usize,
    /// Lowest natural frequencies of the reduced model \[Hz\] (at most 20).
    pub frequencies_hz: Vec<f64>,
    /// Wall time of the reduction \[s\].
    pub reduction_s: f64,
    /// Written file.
    pub file: String,
    /// What the numbers mean (issue 20: every study's summary says it), [`MEANING`].
    pub meaning: &'static str,
}

/// What the summary of `reduce` means.
pub const MEANING: &str = "The user's Matrix Market model (n_full DOFs) reduced to n_reduced \
     coordinates: the boundary DOFs kept physical (n_boundary; n_fixed clamped DOFs removed) plus, \
     for cb/mc/fixed-interface-mt/free-free-mt, the requested normal modes. frequencies_hz are \
     the lowest natural frequencies of the reduced pair K_r q = lambda M_r q [Hz] (at most 20); \
     the reduction is a Rayleigh-Ritz projection, so each lies at or above the matching \
     frequency of the full model, and Craig-Bampton converges to it from above as modes are \
     added (Lin ch. 6). With eitelberg (Lin §6.6.4) the reduced model is the state-space system \
     of the boundary DOFs and their velocities (n_reduced = 2 n_boundary states), and \
     frequencies_hz come from its M^-1 K on the boundary, which equals Guyan's. reduction_s is \
     the wall time of the reduction [s]; file holds the reduced model (versioned JSON) for the \
     flexible body of a multibody model (eitelberg: the matrices minv_k, a_r, b_r, c_r).";

/// Node ranges `a..=b` (1-based) of a `1,5,10-12` list; nothing is expanded here, so a huge
/// range costs nothing until it is checked against the model ([`expand_nodes`]).
fn parse_nodes(text: &str, flag: &str) -> Result<Vec<(usize, usize)>, String> {
    let mut out = Vec::new();
    for part in text.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let bad = || format!("{flag}: \"{part}\" is not a node number or range a-b (1-based)");
        let (a, b) = match part.split_once('-') {
            Some((a, b)) => (a.trim(), b.trim()),
            None => (part, part),
        };
        let a: usize = a.parse().map_err(|_| bad())?;
        let b: usize = b.parse().map_err(|_| bad())?;
        if a == 0 || b < a {
            return Err(bad());
        }
        out.push((a, b));
    }
    if out.is_empty() {
        return Err(format!("{flag}: no nodes given"));
    }
    Ok(out)
}

/// The 0-based nodes of `ranges`, each checked against the model's `n_nodes` first.
fn expand_nodes(
    ranges: &[(usize, usize)], flag: &str, n_nodes: usize,
) -> Result<Vec<usize>, String> {
    if let Some(&(_, b)) = ranges.iter().find(|r| r.1 > n_nodes) {
        return Err(format!(
            "{flag}: node {b} is out of range (1-based; the model has {n_nodes} nodes)"
        ));
    }
    Ok(ranges.iter().flat_map(|&(a, b)| a - 1..b).collect())
}

enum Failure {
    Input(String),
    Numerical(String),
}

fn run_inner(a: &Args, c: &ReduceConfig) -> Result<Summary, Failure> {
    let input = |e: String| Failure::Input(e);
    let Some(out) = &a.out else {
        return Err(Failure::Input(
            "--out: the output file of the reduced model is required".into(),
        ));
    };
    for (flag, v) in [
        ("--mass", &c.mass),
        ("--stiffness", &c.stiffness),
        ("--boundary", &c.boundary),
    ] {
        if v.is_empty() {
            return Err(Failure::Input(format!(
                "{flag}: required (on the command line or in --config)"
            )));
        }
    }
    let nodes = parse_nodes(&c.boundary, "--boundary").map_err(input)?;
    let fixed = if c.fixed.trim().is_empty() {
        Vec::new()
    } else {
        parse_nodes(&c.fixed, "--fixed").map_err(input)?
    };
    if c.dofs_per_node == 0 {
        return Err(Failure::Input("--dofs-per-node: must be at least 1".into()));
    }
    mbd_core::validate::check::size("--modes", c.modes, 0, MAX_MODES)
        .map_err(|e| Failure::Input(e.to_string()))?;
    let opts = ReadOptions::symmetric().allow_large(a.allow_large);
    let read = |p: &str, what: &str| {
        mtx::read_sparse_with(p, &opts).map_err(|e| Failure::Input(format!("--{what} {p}: {e}")))
    };
    let m = read(&c.mass, "mass")?;
    let k = read(&c.stiffness, "stiffness")?;
    let n = k.nrows();
    if k.ncols() != n || m.nrows() != n || m.ncols() != n {
        return Err(Failure::Input(format!(
            "--mass/--stiffness: matrices are {}x{} and {}x{}, expected equal square sizes",
            m.nrows(),
            m.ncols(),
            k.nrows(),
            k.ncols()
        )));
    }
    if !n.is_multiple_of(c.dofs_per_node) {
        return Err(Failure::Input(format!(
            "--dofs-per-node: {} does not divide the matrix size {n}",
            c.dofs_per_node
        )));
    }
    let n_nodes = n / c.dofs_per_node;
    let nodes = expand_nodes(&nodes, "--boundary", n_nodes).map_err(input)?;
    let fixed = expand_nodes(&fixed, "--fixed", n_nodes).map_err(input)?;
    // K positive semi-definite, M positive semi-definite (massless DOFs are condensed)
    let checks = PairCheckOptions {
        massless_dofs_allowed: true,
    };
    let warnings = check_stiffness_mass(k.as_ref(), m.as_ref(), &checks).map_err(|e| {
        Failure::Input(format!(
            "--stiffness {} / --mass {}: {e}",
            c.stiffness, c.mass
        ))
    })?;
    if !a.quiet {
        for w in warnings {
            eprintln!("flowmbd-reduce reduce: warning: {w}");
        }
    }
    let part = DofPartition::from_nodes(n, c.dofs_per_node, &nodes, &fixed)
        .map_err(|e| Failure::Input(format!("--boundary/--fixed: {e}")))?;
    let t0 = Instant::now();
    let num = |e: reduction::ReductionError| Failure::Numerical(e.to_string());
    let Some(method) = c.method.method() else {
        let red =
            EitelbergModel::reduce_sparse(k.as_ref(), m.as_ref(), &part).map_err(|e| match e {
                reduction::ReductionError::InvalidParameter { .. }
                | reduction::ReductionError::InvalidDofs { .. } => {
                    Failure::Input(format!("--method: {e}"))
                }
                other => Failure::Numerical(other.to_string()),
            })?;
        return eitelberg(red, &part, out, t0);
    };
    let red = match method {
        Method::Guyan | Method::CraigBampton => {
            let modes = if method == Method::Guyan { 0 } else { c.modes };
            let opts = CraigBamptonOptions::with_modes(modes);
            craig_bampton_sparse(k.as_ref(), m.as_ref(), &part, &opts, c.dofs_per_node)
                .map_err(num)?
                .0
        }
        other if n <= DENSE_LIMIT => {
            let (kd, md) = (k.to_dense(), m.to_dense());
            let basis = build_basis(
                kd.as_ref(),
                md.as_ref(),
                &part,
                other,
                &ModeSelection::Lowest(c.modes),
            )
            .map_err(|e| match e {
                reduction::ReductionError::InvalidParameter { .. }
                | reduction::ReductionError::InvalidDofs { .. } => Failure::Input(e.to_string()),
                other => Failure::Numerical(other.to_string()),
            })?;
            ReducedModel::from_basis(basis, kd.as_ref(), md.as_ref(), None, c.dofs_per_node)
                .map_err(num)?
        }
        other => {
            return Err(Failure::Input(format!(
                "--method: {} needs the dense path, limited to {DENSE_LIMIT} DOFs (model has {n}); use guyan or cb",
                other.short_name()
            )));
        }
    };
    let reduction_s = t0.elapsed().as_secs_f64();
    red.save(out)
        .map_err(|e| Failure::Input(format!("--out: {e}")))?;
    let f = red.natural_frequencies_hz().map_err(num)?;
    Ok(Summary {
        method: method.short_name().into(),
        n_full: n,
        n_boundary: part.boundary().len(),
        n_fixed: part.fixed().len(),
        n_reduced: red.n_reduced(),
        frequencies_hz: f.into_iter().take(20).collect(),
        reduction_s,
        file: out.display().to_string(),
        meaning: MEANING,
    })
}

/// `--method eitelberg`: the dense Eitelberg reduction (`reduction::eitelberg_model`) written
/// to `out`, its frequencies in the summary.
fn eitelberg(
    red: EitelbergModel, part: &DofPartition, out: &std::path::Path, t0: Instant,
) -> Result<Summary, Failure> {
    let reduction_s = t0.elapsed().as_secs_f64();
    red.save(out)
        .map_err(|e| Failure::Input(format!("--out: {e}")))?;
    let f = red
        .natural_frequencies_hz()
        .map_err(|e| Failure::Numerical(e.to_string()))?;
    Ok(Summary {
        method: "eitelberg".into(),
        n_full: part.n(),
        n_boundary: part.boundary().len(),
        n_fixed: part.fixed().len(),
        n_reduced: 2 * part.boundary().len(),
        frequencies_hz: f.into_iter().take(20).collect(),
        reduction_s,
        file: out.display().to_string(),
        meaning: MEANING,
    })
}

/// Runs `reduce`: exit 0 on success, 2 on bad input, 1 on numerical failure.
pub fn run(a: Args) -> ExitCode {
    flowmbd_cli::limits::set_allow_large(a.allow_large);
    let result = effective_config(&a).and_then(|c| {
        if a.print_config {
            flowmbd_cli::print_stdout(&flowmbd_cli::commented::to_commented_toml(&c))
                .map_err(|e| Failure::Numerical(format!("<stdout>: {e}")))?;
            return Ok(None);
        }
        run_inner(&a, &c).map(Some)
    });
    let escape = mbd_core::validate::escape_message;
    match result {
        Ok(None) => ExitCode::SUCCESS,
        Ok(Some(s)) => report(&a, s),
        Err(Failure::Input(m)) => {
            eprintln!("flowmbd-reduce reduce: error: {}", escape(&m));
            ExitCode::from(2)
        }
        Err(Failure::Numerical(m)) => {
            eprintln!("flowmbd-reduce reduce: error: {}", escape(&m));
            ExitCode::from(1)
        }
    }
}

/// Print the summary of a successful run (`--json`, or one line unless `--quiet`).
fn report(a: &Args, s: Summary) -> ExitCode {
    if a.json {
        let text = match serde_json::to_string_pretty(&s) {
            Ok(t) => t,
            Err(e) => {
                eprintln!("flowmbd-reduce reduce: error: {e}");
                return ExitCode::from(1);
            }
        };
        if let Err(e) = flowmbd_cli::print_stdout(&(text + "\n")) {
            eprintln!("flowmbd-reduce reduce: error: <stdout>: {e}");
            return ExitCode::from(1);
        }
    } else if !a.quiet {
        eprintln!(
            "reduced {} DOFs to {} coordinates ({}) in {:.2} s; written to {}",
            s.n_full, s.n_reduced, s.method, s.reduction_s, s.file
        );
    }
    ExitCode::SUCCESS
}
