//! Shared pieces of the tire studies: the tire source (generated truck tire, reduced and saved,
//! or a saved reduced tire reused) and error mapping.

use fe_model::generate::TireConfig;
use flowing::tire::{
    ImportFiles, ReducedTire, ReductionConfig, TireError, TireFe, generated_tire, imported_tire,
    reduce,
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
    /// Imported tire (Matrix Market M and K, nodes, rim and patch node lists); replaces the
    /// generated one when given.
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
        TireError::File { path, reason } => {
            StudyError::Input(InputError::new(format!("reduced_file {path}"), reason))
        }
        other => StudyError::numerical(other),
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
    /// Basic checks.
    pub fn validate(&self) -> Result<(), InputError> {
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

    /// The FE model: imported when `import` is given, otherwise generated.
    pub fn fe_model(&self) -> Result<TireFe, StudyError> {
        match &self.import {
            Some(files) => imported_tire(files).map_err(tire_err),
            None => generated_tire(&self.generator).map_err(tire_err),
        }
    }

    /// Load the saved reduced tire, or reduce the generated one (and save it).
    pub fn reduced(&self, quiet: bool) -> Result<ReducedTire, StudyError> {
        let path = Path::new(&self.reduced_file);
        if !self.reduced_file.is_empty() && path.exists() {
            return ReducedTire::load(path).map_err(tire_err);
        }
        if !quiet {
            eprintln!(
                "reducing the generated tire (saved to `{}`)",
                self.reduced_file
            );
        }
        let fe = self.fe_model()?;
        let (red, _) = reduce(&fe, &self.reduction).map_err(tire_err)?;
        if !self.reduced_file.is_empty() {
            if let Some(dir) = path.parent() {
                let _ = std::fs::create_dir_all(dir);
            }
            red.save(path).map_err(tire_err)?;
        }
        Ok(red)
    }
}
