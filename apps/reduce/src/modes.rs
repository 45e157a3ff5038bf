//! `flowmbd-reduce modes`: the lowest modes of `K φ = λ M φ` for Matrix Market `M` and `K`,
//! optional fixed DOFs (eliminated), dense or sparse shift-invert solver chosen by size
//! (fe-model `sparse_modes`: shift-invert block Lanczos with the Sturm check). Writes `summary.json`
//! (`{"dof": n, "frequencies_hz": [...]}`), `frequencies.csv`, `report.json` (solver
//! diagnostics) and, with `--mesh mesh.json`, `modes.vtu` with the mode shapes.

use fe_model::eigen::{SparseEigenOptions, sparse_modes};
use fe_model::io::{mtx, vtk};
use fe_model::plausibility::check_stiffness_mass;
use fe_model::{DofSplit, FeError, Mesh};
use flowmbd_cli::{CommonArgs, InputError, Study, StudyContext, StudyError, Validate};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Command-line arguments.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Mass matrix (Matrix Market).
    #[arg(long, value_name = "M.mtx")]
    mass: Option<PathBuf>,
    /// Stiffness matrix (Matrix Market).
    #[arg(long, value_name = "K.mtx")]
    stiffness: Option<PathBuf>,
    /// Fixed DOFs: whitespace-separated 0-based indices, `#` starts a comment.
    #[arg(long, value_name = "DOFS.txt")]
    fixed: Option<PathBuf>,
    /// Number of modes.
    #[arg(long)]
    count: Option<usize>,
    /// Mesh (mesh.json as written by `tire-mesh`) for the VTK export of the modes.
    #[arg(long, value_name = "mesh.json")]
    mesh: Option<PathBuf>,
}

/// Configuration of the `modes` study.
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// Mass matrix file (Matrix Market).
    pub mass: String,
    /// Stiffness matrix file (Matrix Market).
    pub stiffness: String,
    /// Fixed-DOF file ("" = none).
    pub fixed: String,
    /// Mesh file for VTK output ("" = none).
    pub mesh: String,
    /// Number of modes.
    pub count: usize,
    /// Shift σ \[rad²/s²\] for shift-invert (absent = automatic).
    pub shift: Option<f64>,
    /// Models up to this many DOFs are solved densely.
    pub dense_below: usize,
}

impl Default for Config {
    /// The seed's tire case: the lowest 50 modes (Ribaric §8.1), files to be given.
    fn default() -> Self {
        Self {
            mass: String::new(),
            stiffness: String::new(),
            fixed: String::new(),
            mesh: String::new(),
            count: 50,
            shift: None,
            dense_below: 400,
        }
    }
}

impl flowmbd_cli::PartialRules for Config {}

impl Validate for Config {
    fn validate(&self) -> Result<(), InputError> {
        // `mass` and `stiffness` are required, but checked in `run`: the defaults are validated
        // before the command-line overrides are applied
        if self.count == 0 {
            return Err(InputError::new("count", "must be at least 1"));
        }
        if self.shift.is_some_and(|s| !s.is_finite()) {
            return Err(InputError::new("shift", "must be finite"));
        }
        Ok(())
    }
}

/// `summary.json`: exactly the documented interface.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// DOFs of the input matrices.
    pub dof: usize,
    /// Natural frequencies \[Hz\], ascending.
    pub frequencies_hz: Vec<f64>,
}

fn input(field: &str, e: impl std::fmt::Display) -> StudyError {
    StudyError::Input(InputError::new(field, e.to_string()))
}

/// Read the fixed-DOF list (0-based), with line numbers in errors.
fn read_fixed(path: &Path, n: usize) -> Result<Vec<usize>, StudyError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| input("fixed", format!("{}: {e}", path.display())))?;
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let body = line.split('#').next().unwrap_or("");
        for tok in body.split_whitespace() {
            let d: usize = tok.parse().map_err(|_| {
                input(
                    "fixed",
                    format!(
                        "{}:{}: `{tok}` is not a 0-based DOF index",
                        path.display(),
                        i + 1
                    ),
                )
            })?;
            if d >= n {
                return Err(input(
                    "fixed",
                    format!(
                        "{}:{}: DOF {d} out of range (model has {n} DOFs)",
                        path.display(),
                        i + 1
                    ),
                ));
            }
            out.push(d);
        }
    }
    Ok(out)
}

impl Study for Args {
    type Config = Config;
    type Summary = Summary;
    const NAME: &'static str = "modes";
    const MEANING: &'static str = "Natural frequencies [Hz] of the Matrix Market model K phi = lambda M phi (lambda = \
         omega^2 in rad^2/s^2), lowest first, with the fixed DOFs removed; the eigen solver \
         checks its result (Sturm count, M-orthogonality): a missed or ghost mode is \
         reported, not printed.";

    fn apply_overrides(&self, c: &mut Config) {
        let a = self;
        let s = |p: &Option<PathBuf>| p.as_ref().map(|p| p.display().to_string());
        if let Some(v) = s(&a.mass) {
            c.mass = v;
        }
        if let Some(v) = s(&a.stiffness) {
            c.stiffness = v;
        }
        if let Some(v) = s(&a.fixed) {
            c.fixed = v;
        }
        if let Some(v) = s(&a.mesh) {
            c.mesh = v;
        }
        if let Some(v) = a.count {
            c.count = v;
        }
    }

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        if c.mass.is_empty() {
            return Err(input(
                "mass",
                "required (--mass M.mtx or `mass` in the configuration)",
            ));
        }
        if c.stiffness.is_empty() {
            return Err(input(
                "stiffness",
                "required (--stiffness K.mtx or `stiffness` in the configuration)",
            ));
        }
        let bar = ctx.progress(4.0, "modes");
        let opts = mtx::ReadOptions::symmetric().allow_large(self.common.allow_large);
        let read = |field: &str, p: &str| -> Result<_, StudyError> {
            mtx::read_sparse_with(p, &opts).map_err(|e: FeError| input(field, e))
        };
        let m = read("mass", &c.mass)?;
        let k = read("stiffness", &c.stiffness)?;
        bar.set(1.0);
        let n = k.nrows();
        if k.ncols() != n || m.nrows() != n || m.ncols() != n {
            return Err(input(
                "mass",
                format!(
                    "M is {}×{}, K is {}×{}: both must be square and equal",
                    m.nrows(),
                    m.ncols(),
                    k.nrows(),
                    k.ncols()
                ),
            ));
        }
        let fixed = if c.fixed.is_empty() {
            Vec::new()
        } else {
            read_fixed(Path::new(&c.fixed), n)?
        };
        let part = DofSplit::fixed(n, &fixed).map_err(|e| input("fixed", e))?;
        let kff = part
            .block(k.as_ref(), false, false)
            .map_err(|e| input("stiffness", e))?;
        let mff = part
            .block(m.as_ref(), false, false)
            .map_err(|e| input("mass", e))?;
        // M positive definite, K positive semi-definite (Géradin & Rixen §2.3)
        let warnings = check_stiffness_mass(kff.as_ref(), mff.as_ref(), &Default::default())
            .map_err(|e| {
                let numbering = if fixed.is_empty() {
                    ""
                } else {
                    " (DOFs numbered among the free DOFs)"
                };
                let field = match &e {
                    FeError::Implausible { matrix, .. } if matrix == "M" => "mass",
                    _ => "stiffness",
                };
                input(field, format!("{e}{numbering}"))
            })?;
        if !ctx.quiet {
            for w in warnings {
                eprintln!("flowmbd-reduce modes: warning: {w}");
            }
        }
        if c.count > kff.nrows() {
            return Err(input(
                "count",
                format!(
                    "{} modes requested but only {} free DOFs",
                    c.count,
                    kff.nrows()
                ),
            ));
        }
        let mesh: Option<Mesh> = if c.mesh.is_empty() {
            None
        } else {
            let text = std::fs::read_to_string(&c.mesh)
                .map_err(|e| input("mesh", format!("{}: {e}", c.mesh)))?;
            let mesh: Mesh = serde_json::from_str(&text).map_err(|e| {
                input(
                    "mesh",
                    format!("{}:{}:{}: {e}", c.mesh, e.line(), e.column()),
                )
            })?;
            if mesh.n_dofs() != n {
                return Err(input(
                    "mesh",
                    format!("{} has {} DOFs, matrices have {n}", c.mesh, mesh.n_dofs()),
                ));
            }
            Some(mesh)
        };
        bar.set(2.0);
        let opts = SparseEigenOptions {
            shift: c.shift,
            dense_below: c.dense_below,
            ..Default::default()
        };
        let (modes, report) =
            sparse_modes(kff.as_ref(), mff.as_ref(), c.count, &opts).map_err(|e| {
                StudyError::numerical(format!(
                    "eigen solution of the {}-DOF model: {e}",
                    kff.nrows()
                ))
            })?;
        bar.set(3.0);
        ctx.out.write_json("report.json", &report)?;
        ctx.out.write_csv(
            "frequencies.csv",
            &["mode", "frequency_Hz", "eigenvalue_rad2_per_s2"],
            modes
                .frequencies_hz
                .iter()
                .zip(&modes.values)
                .enumerate()
                .map(|(i, (f, l))| [i as f64 + 1.0, *f, *l]),
        )?;
        if let Some(mesh) = mesh {
            let full = part.expand_rest(modes.vectors.as_ref(), 0.0);
            let mut fields = vtk::mode_fields(
                &mesh,
                full.as_ref(),
                &modes.frequencies_hz,
                vtk::default_layout(mesh.dofs_per_node),
            )
            .map_err(|e| input("mesh", e))?;
            fields.extend(vtk::node_set_fields(&mesh));
            let path = ctx.out.path("modes.vtu");
            vtk::write_vtu(&path, &mesh, &fields)
                .map_err(|e| StudyError::numerical(format!("writing {}: {e}", path.display())))?;
        }
        bar.set(4.0);
        bar.finish();
        Ok(Summary {
            dof: n,
            frequencies_hz: modes.frequencies_hz,
        })
    }
}
