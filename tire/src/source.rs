//! Where the reduced tire comes from (the `[tire]` table of the tire studies): the generated
//! or imported FE tire and the reduction of Ribaric §8.2, with the fingerprint that names what a
//! reduced tire is made from. The reduced-tire file and cache are in [`crate::cache`].

use crate::error::TireError;
use crate::files::file_sha256;
use crate::import::{ImportFiles, imported_tire};
use crate::mesh::TireFe;
use crate::model::generated_tire;
use crate::reduce::{ReductionConfig, ReductionTimings, reduce};
use crate::reduced::ReducedTire;
use fe_model::generate::TireConfig;
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The `reduced_file` value that keeps reduced tires in the OS cache folder (`flowmbd-tire`).
pub const CACHE: &str = "cache";

/// The example of an `import` table that the printed configuration of a study with a generated
/// tire ends with, commented out (TOML has no null, so an absent import would not show
/// otherwise): its heading, then the table's lines (`flowmbd_cli::commented`'s
/// `x-commented-example`).
pub const IMPORT_EXAMPLE: &str = "An imported tire replaces the generated one (uncomment and give the files; README, \"Imported tire\"):\n\
format = \"abaqus\"          # or \"matrix_market\" (3n x 3n, node-major x, y, z)\n\
stiffness = \"job_STIF1.mtx\" # K with the inflation prestress (ABAQUS *MATRIX GENERATE)\n\
mass = \"job_MASS1.mtx\"      # M\n\
nodes = \"nodes.inp\"         # `label, x, y, z` per line [m] (Matrix Market: `x, y, z`)\n\
rim_nodes = \"rim.inp\"       # node labels bonded to the rim (Matrix Market: 0-based indices)\n\
patch_nodes = \"patch.inp\"   # candidate contact-patch node labels\n";

/// Where the reduced tire comes from (the `[tire]` table of the tire studies).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct TireSource {
    /// Reduced tire file of `flowmbd-tire`: loaded when it exists, otherwise written after
    /// reducing the tire. `"cache"` (default): a file in the OS cache folder
    /// (`$XDG_CACHE_HOME/flowmbd/tire`, `~/.cache/flowmbd/tire` on Linux) named by what the
    /// tire is made from and the version of the code that reduces it
    /// ([`TireSource::reduced_path`]), so that every tire, reduction and code version has a
    /// file of its own and nothing is written under the working folder (a damaged or stale
    /// cache file is replaced); `""`: always reduce, never save; any other path: that file (a
    /// damaged file or one made from another tire is refused). (The Python package keeps the
    /// reduced tire as an object instead and ignores it.)
    pub reduced_file: String,
    /// Generated tire (fe-model generator; default: 295/80 R22.5 truck tire at 38 psi).
    pub generator: TireConfig,
    /// Imported tire (ABAQUS `*MATRIX GENERATE` or Matrix Market M and K, node coordinates,
    /// rim and candidate patch node sets; see [`ImportFiles`] and the README); replaces the
    /// generated one when given.
    #[schemars(extend("x-commented-example" = IMPORT_EXAMPLE))]
    pub import: Option<ImportFiles>,
    /// Reduction (Ribaric §8.2: 95 contact nodes, 50 free-node modes).
    pub reduction: ReductionConfig,
}

impl Default for TireSource {
    fn default() -> Self {
        Self {
            reduced_file: CACHE.into(),
            generator: TireConfig::default(),
            import: None,
            reduction: ReductionConfig::default(),
        }
    }
}

impl mbd_core::config::PartialRules for TireSource {}

impl Validate for TireSource {
    /// The import files exist and are readable files (or the generator's fields, [`TireConfig`]'s
    /// `Validate`); the reduction's fields. Paths relative to the tire table (`import.mass`,
    /// `generator.…`, `reduction.…`).
    fn validate(&self) -> Result<(), InvalidField> {
        if let Some(files) = &self.import {
            for (field, path) in [
                ("stiffness", &files.stiffness),
                ("mass", &files.mass),
                ("nodes", &files.nodes),
                ("rim_nodes", &files.rim_nodes),
                ("patch_nodes", &files.patch_nodes),
            ] {
                check::input_file(&format!("import.{field}"), std::path::Path::new(path))?;
            }
        } else {
            self.generator.validate_within("generator")?;
        }
        self.reduction.validate_within("reduction")
    }
}

impl TireSource {
    /// What the reduced tire is made from, as JSON: the generated tire's configuration, or the
    /// imported tire's format and the SHA-256 digests of its files' contents (not their paths:
    /// a file edited in place is another tire, the same file elsewhere is the same), and the
    /// reduction settings. Stored in the reduced tire ([`ReducedTire::source`]) and compared
    /// when a saved file is reused; with [`crate::CODE_VERSION`] it keys the cache
    /// ([`TireSource::reduced_path`]). Errors: an import file that cannot be read.
    pub fn fingerprint(&self) -> Result<String, TireError> {
        let model = match &self.import {
            Some(files) => {
                let digest = |field: &'static str, path: &str| {
                    file_sha256(Path::new(path))
                        .map(|h| format!("sha256:{h}"))
                        .map_err(|reason| TireError::Import {
                            field,
                            reason: format!("{path}: {reason}"),
                        })
                };
                serde_json::json!({ "import": {
                    "format": files.format,
                    "stiffness": digest("stiffness", &files.stiffness)?,
                    "mass": digest("mass", &files.mass)?,
                    "nodes": digest("nodes", &files.nodes)?,
                    "rim_nodes": digest("rim_nodes", &files.rim_nodes)?,
                    "patch_nodes": digest("patch_nodes", &files.patch_nodes)?,
                } })
            }
            None => serde_json::json!({ "generator": self.generator }),
        };
        Ok(serde_json::json!({ "model": model, "reduction": self.reduction }).to_string())
    }

    /// The FE model: imported when `import` is given ([`imported_tire`]), otherwise generated
    /// ([`generated_tire`]).
    pub fn fe_model(&self) -> Result<TireFe, TireError> {
        match &self.import {
            Some(files) => imported_tire(files),
            None => generated_tire(&self.generator),
        }
    }

    /// Reduce `fe` (this source's FE model) with this source's reduction settings (Ribaric
    /// §8.2, [`reduce`]) and record the [`TireSource::fingerprint`] in the reduced tire.
    pub fn reduce_fe(&self, fe: &TireFe) -> Result<(ReducedTire, ReductionTimings), TireError> {
        let (mut red, timings) = reduce(fe, &self.reduction)?;
        red.source = self.fingerprint()?;
        Ok((red, timings))
    }
}
