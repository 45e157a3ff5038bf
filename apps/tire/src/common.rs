//! Shared pieces of the tire studies: the tire source (generated truck tire, reduced and saved,
//! or a saved reduced tire reused) and error mapping.

use fe_model::FeError;
use fe_model::generate::TireConfig;
use flowing::tire::{
    GroundKind, ImportFiles, ReducedTire, ReductionConfig, RigConfig, TireError, TireFe,
    generated_tire, imported_tire, reduce,
};
use flowmbd_cli::{InputError, StudyError};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Where the reduced tire comes from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TireSource {
    /// Reduced tire file: loaded when it exists, otherwise written after reducing the generated
    /// tire (empty = always reduce, never save).
    pub reduced_file: String,
    /// Generated tire (fe-model generator; default: 295/80 R22.5 truck tire at 38 psi).
    pub generator: TireConfig,
    /// Imported tire (ABAQUS `*MATRIX GENERATE` or Matrix Market M and K, node coordinates,
    /// rim and candidate patch node sets; see `flowing::tire::ImportFiles`); replaces the
    /// generated one when given. Example:
    /// `[tire.import]` `format = "abaqus"`, `stiffness = "job_STIF1.mtx"`,
    /// `mass = "job_MASS1.mtx"`, `nodes = "nodes.inp"`, `rim_nodes = "rim.inp"`,
    /// `patch_nodes = "patch.inp"`.
    pub import: Option<ImportFiles>,
    /// Reduction (Ribaric §8.2: 95 contact nodes, 50 free-node modes).
    pub reduction: ReductionConfig,
}

impl Default for TireSource {
    fn default() -> Self {
        Self {
            reduced_file: "out/tire/reduced-truck-95c-50m.json".into(),
            generator: TireConfig::default(),
            import: None,
            reduction: ReductionConfig::default(),
        }
    }
}

/// Map a library error: invalid input → exit 2 naming the item, otherwise numerical (exit 1).
pub fn tire_err(e: TireError) -> StudyError {
    match e {
        TireError::Invalid { item, reason } => StudyError::Input(InputError::new(item, reason)),
        TireError::File { path, reason } => StudyError::Input(InputError::new(
            format!("tire.reduced_file `{path}`"),
            reason,
        )),
        // imported matrix files: syntax, size and symmetry errors name file and line (exit 2)
        TireError::Fe(
            e @ (FeError::Matrix { .. } | FeError::Io { .. } | FeError::Parse { .. }),
        ) => StudyError::Input(InputError::new("tire.import", e.to_string())),
        other => StudyError::numerical(other),
    }
}

/// Map an error of the rig (cleat test): like [`tire_err`], with the rig's invalid items named
/// by their configuration path (`rig.damping.mode1`, not `damping.mode1`).
pub fn rig_err(e: TireError) -> StudyError {
    match e {
        TireError::Invalid { item, reason } => {
            StudyError::Input(InputError::new(format!("rig.{item}"), reason))
        }
        other => tire_err(other),
    }
}

/// Map a library validation error to an input error.
pub fn input(e: TireError) -> InputError {
    match e {
        TireError::Invalid { item, reason } => InputError::new(item, reason),
        other => InputError::new("config", other.to_string()),
    }
}

impl TireSource {
    /// The reduced-tire file actually used: with an imported tire and the default (generated
    /// tire's) file name, a name of its own, so that the generated tire's file is never reused
    /// for an imported model.
    pub fn reduced_path(&self) -> String {
        if self.import.is_some() && self.reduced_file == TireSource::default().reduced_file {
            format!(
                "out/tire/reduced-imported-{}c-{}m.json",
                self.reduction.contact_nodes, self.reduction.free_modes
            )
        } else {
            self.reduced_file.clone()
        }
    }

    /// Basic checks.
    pub fn validate(&self) -> Result<(), InputError> {
        if let Some(files) = &self.import {
            for (field, path) in [
                ("stiffness", &files.stiffness),
                ("mass", &files.mass),
                ("nodes", &files.nodes),
                ("rim_nodes", &files.rim_nodes),
                ("patch_nodes", &files.patch_nodes),
            ] {
                flowmbd_cli::check_input_file(
                    &format!("tire.import.{field}"),
                    std::path::Path::new(path),
                )?;
            }
        }
        if self.reduction.contact_nodes == 0 {
            return Err(InputError::new(
                "tire.reduction.contact_nodes",
                "must be positive",
            ));
        }
        if self.reduction.free_modes == 0 {
            return Err(InputError::new(
                "tire.reduction.free_modes",
                "must be positive",
            ));
        }
        Ok(())
    }

    /// What the reduced tire is made from: the generated tire's configuration (or the imported
    /// tire's files) and the reduction settings, as JSON; stored in the reduced file
    /// ([`ReducedTire::source`]) and compared when the file is reused.
    pub fn fingerprint(&self) -> String {
        let model = match &self.import {
            Some(files) => serde_json::json!({ "import": files }),
            None => serde_json::json!({ "generator": self.generator }),
        };
        serde_json::json!({ "model": model, "reduction": self.reduction }).to_string()
    }

    /// The FE model: imported when `import` is given, otherwise generated.
    pub fn fe_model(&self) -> Result<TireFe, StudyError> {
        match &self.import {
            Some(files) => imported_tire(files).map_err(tire_err),
            None => generated_tire(&self.generator).map_err(tire_err),
        }
    }

    /// Load the saved reduced tire, or reduce the generated one (and save it).
    pub fn reduced(&self, quiet: bool) -> Result<ReducedTire, StudyError> {
        let file = self.reduced_path();
        let path = Path::new(&file);
        if !file.is_empty() && path.exists() {
            let red = ReducedTire::load(path).map_err(tire_err)?;
            // a file made with another reduction would silently answer a different question
            let (nc, nf) = (red.n_contact(), red.n_free_modes);
            let want = &self.reduction;
            // the specific diagnosis first (counts), then any other difference (fingerprint)
            if nc != want.contact_nodes || nf != want.free_modes {
                return Err(StudyError::Input(InputError::new(
                    format!("tire.reduced_file `{file}`"),
                    format!(
                        "holds {nc} contact nodes and {nf} free-node modes but \
                         tire.reduction asks for {} and {} (delete the file or name another)",
                        want.contact_nodes, want.free_modes
                    ),
                )));
            }
            let source = self.fingerprint();
            if red.source != source {
                let why = if red.source.is_empty() {
                    "does not record the tire it was made from (an older flowmbd wrote it)"
                } else {
                    "was made from another tire model or reduction than tire.generator / \
                     tire.import and tire.reduction describe"
                };
                return Err(StudyError::Input(InputError::new(
                    format!("tire.reduced_file `{file}`"),
                    format!("{why} (delete the file or name another)"),
                )));
            }
            return Ok(red);
        }
        if !quiet {
            let what = if self.import.is_some() {
                "imported"
            } else {
                "generated"
            };
            eprintln!("reducing the {what} tire (saved to `{file}`)");
        }
        let fe = self.fe_model()?;
        let (mut red, _) = reduce(&fe, &self.reduction).map_err(tire_err)?;
        red.source = self.fingerprint();
        if !file.is_empty() {
            if let Some(dir) = path.parent() {
                let _ = std::fs::create_dir_all(dir);
            }
            red.save(path).map_err(tire_err)?;
        }
        Ok(red)
    }
}

/// Command-line overrides of the rig shared by `cleat` and `sweep` (the sensitivity studies of
/// Ribaric §8.4–8.5 without editing a configuration file).
#[derive(Debug, Clone, Default, clap::Args)]
pub struct RigFlags {
    /// Ground: `drum` (R = 1.25 m) or `road` (overrides `rig.ground.kind`).
    #[arg(long, value_parser = ["drum", "road"])]
    pub ground: Option<String>,
    /// Coulomb friction coefficient (overrides `rig.rolling.friction`; §8.4.3: 0.85 or 0).
    #[arg(long)]
    pub friction: Option<f64>,
    /// Damping ratio at both target modes (overrides `rig.damping.zeta1/zeta2`; §8.4.1: 0.01
    /// or 0.03).
    #[arg(long)]
    pub zeta: Option<f64>,
    /// Roll without the cleat (steady rolling).
    #[arg(long)]
    pub no_cleat: bool,
    // `[s]` stays unescaped: clap prints this doc comment as the --help text.
    /// Time step [s] (overrides `rig.rolling.time_step`).
    #[allow(rustdoc::broken_intra_doc_links)]
    #[arg(long)]
    pub time_step: Option<f64>,
    /// Sub-steps per time step while the cleat passes the patch (overrides
    /// `rig.impact.substeps`; 1 = uniform steps, e.g. with `--time-step 5e-5` for converged
    /// cleat amplitudes).
    #[arg(long)]
    pub substeps: Option<usize>,
    /// Contact nodes of the reduction (overrides `tire.reduction.contact_nodes`; §8.4.2: 95 or
    /// 252). With the default reduced-tire file name, the file name follows the count; the
    /// generated tire's candidate patch is widened when needed.
    #[arg(long)]
    pub contact_nodes: Option<usize>,
}

impl RigFlags {
    /// Apply the overrides.
    pub fn apply(&self, tire: &mut TireSource, rig: &mut RigConfig) {
        if let Some(g) = &self.ground {
            rig.ground.kind = if g == "road" {
                GroundKind::Road
            } else {
                GroundKind::Drum
            };
        }
        if let Some(mu) = self.friction {
            rig.rolling.friction = mu;
        }
        if let Some(z) = self.zeta {
            rig.damping.zeta1 = z;
            rig.damping.zeta2 = z;
        }
        if self.no_cleat {
            rig.ground.cleat = false;
        }
        if let Some(h) = self.time_step {
            rig.rolling.time_step = h;
        }
        if let Some(n) = self.substeps {
            rig.impact.substeps = n;
        }
        if let Some(n) = self.contact_nodes {
            let default_file = TireSource::default().reduced_file;
            if tire.reduced_file == default_file {
                tire.reduced_file = format!(
                    "out/tire/reduced-truck-{n}c-{}m.json",
                    tire.reduction.free_modes
                );
            }
            tire.reduction.contact_nodes = n;
            // the generator's candidate set grows about linearly with the patch angle (99 nodes
            // at the default ±8°): widen it so that n nodes exist (252 nodes: ±25.5°)
            let need = 8.0 * 1.2 * n as f64 / 95.0;
            if tire.generator.patch_half_angle_deg < need {
                tire.generator.patch_half_angle_deg = need;
            }
        }
    }
}
