//! Shared pieces of the tire studies: the tire source (generated truck tire, reduced and saved,
//! or a saved reduced tire reused) and error mapping.

use flowmbd_cli::{InputError, StudyError};
use std::path::Path;
use tire::{GroundKind, ReducedTire, RigConfig, TireError, rig_input_error, tire_input_error};

pub use tire::TireSource;
pub use tire::study::CACHE;

/// The commented `[tire.import]` example that `--print-config` appends (TOML has no null, so
/// an absent import would not show otherwise).
pub const IMPORT_EXAMPLE: &str = "\n\
# An imported tire replaces the generated one (uncomment and give the files; README, \"Imported tire\"):\n\
# [tire.import]\n\
# format = \"abaqus\"          # or \"matrix_market\" (3n x 3n, node-major x, y, z)\n\
# stiffness = \"job_STIF1.mtx\" # K with the inflation prestress (ABAQUS *MATRIX GENERATE)\n\
# mass = \"job_MASS1.mtx\"      # M\n\
# nodes = \"nodes.inp\"         # `label, x, y, z` per line [m] (Matrix Market: `x, y, z`)\n\
# rim_nodes = \"rim.inp\"       # node labels bonded to the rim (Matrix Market: 0-based indices)\n\
# patch_nodes = \"patch.inp\"   # candidate contact-patch node labels\n";

/// [`IMPORT_EXAMPLE`] when `tire` has no import (the studies' `config_notes`).
pub fn import_notes(tire: &TireSource) -> String {
    if tire.import.is_none() {
        IMPORT_EXAMPLE.to_string()
    } else {
        String::new()
    }
}

/// Map a library error: invalid input → exit 2 naming the item
/// ([`tire::tire_input_error`]), otherwise numerical (exit 1).
pub fn tire_err(e: TireError) -> StudyError {
    match tire_input_error(e) {
        Ok(field) => StudyError::Input(field),
        Err(other) => StudyError::numerical(other),
    }
}

/// Map an error of the rig (cleat test): like [`tire_err`], with the rig's invalid items named
/// by their configuration path (`rig.damping.mode1`, not `damping.mode1`).
pub fn rig_err(e: TireError) -> StudyError {
    match rig_input_error(e) {
        Ok(field) => StudyError::Input(field),
        Err(other) => StudyError::numerical(other),
    }
}

/// The app's side of [`TireSource`]: the reduced-tire file (cache) and the FE model with the
/// app's error mapping.
pub trait TireSourceExt {
    /// The reduced-tire file actually used (see the implementation).
    fn reduced_path(&self) -> String;
    /// The FE model (imported or generated), errors mapped by [`tire_err`].
    fn fe_model_or_err(&self) -> Result<tire::TireFe, StudyError>;
    /// Load the saved reduced tire, or reduce the tire (and save it).
    fn reduced(&self, quiet: bool) -> Result<ReducedTire, StudyError>;
}

impl TireSourceExt for TireSource {
    /// The reduced-tire file actually used: for [`CACHE`], the file of this tire and reduction
    /// in the OS cache folder (`<cache>/flowmbd/tire/reduced-<nc>c-<nf>m-<hash>.json`, the hash
    /// of [`TireSource::fingerprint`]; without a cache folder, the system's temporary folder);
    /// otherwise `reduced_file` itself (empty: none).
    fn reduced_path(&self) -> String {
        if self.reduced_file != CACHE {
            return self.reduced_file.clone();
        }
        let dir = dirs::cache_dir()
            .unwrap_or_else(std::env::temp_dir)
            .join("flowmbd")
            .join("tire");
        // the name only spreads tires over files; the stored fingerprint is what is compared
        // (a Rust release that changes `DefaultHasher` leaves old files unused, never misread)
        let mut h = std::hash::DefaultHasher::new();
        std::hash::Hash::hash(&self.fingerprint(), &mut h);
        let kind = if self.import.is_some() {
            "imported"
        } else {
            "truck"
        };
        dir.join(format!(
            "reduced-{kind}-{}c-{}m-{:016x}.json",
            self.reduction.contact_nodes,
            self.reduction.free_modes,
            std::hash::Hasher::finish(&h)
        ))
        .display()
        .to_string()
    }

    fn fe_model_or_err(&self) -> Result<tire::TireFe, StudyError> {
        self.fe_model().map_err(tire_err)
    }

    fn reduced(&self, quiet: bool) -> Result<ReducedTire, StudyError> {
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
            if file.is_empty() {
                eprintln!("reducing the {what} tire (not saved: tire.reduced_file is empty)");
            } else {
                eprintln!("reducing the {what} tire (saved to `{file}`)");
            }
        }
        let fe = self.fe_model_or_err()?;
        let (red, _) = self.reduce_fe(&fe).map_err(tire_err)?;
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
    /// 252). The cached reduced tire follows the count; the generated tire's candidate patch
    /// is widened when needed.
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
            // (the cached file's name follows the reduction, see `TireSource::reduced_path`)
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
