//! Import of a user's tire FE model from files ([`ImportFiles`]: ABAQUS `*MATRIX GENERATE` or
//! Matrix Market K and M, node coordinates, rim and candidate patch node sets), Ribaric §8.1:
//! M and K "under load and inflation". The files are read (module `read`: regular files of
//! bounded size, errors with file and line) and the model is checked for the easy mistakes
//! before it is reduced (module `checks`: K physically plausible and coupling the nodes into one
//! body, distinct node positions, no node listed twice in a set, the patch set on the tread
//! around the road point), each refusal naming the import field, the file and the line. A file
//! that cannot be read or parsed is a [`TireError::Import`]; a model that reads well but fails
//! a check of the easy mistakes (issue #39, item 7) is a [`TireError::ImportCheck`] with the
//! typed [`ImportCheckError`]: K without any off-diagonal entry, a node no stiffness entry
//! connects, rim nodes not inside the tread, a patch node off the tread (the tread is the outer
//! [`TREAD_FRACTION`] of the section height between the rim and the largest radius about the
//! wheel axis `y`) and a patch set away from the road point θ = π.

mod checks;
mod read;

pub use checks::{ImportCheckError, MAX_PATCH_OFFSET_DEG, TREAD_FRACTION};
pub use read::MAX_IMPORT_TEXT_BYTES;

use crate::error::TireError;
use crate::mesh::TireFe;
use read::{
    Listed, labels_to_indices, read_abaqus, read_indices, read_mtx, read_nodes, unique_in_file,
};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Format of the matrix files of an imported tire.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ImportFormat {
    /// Matrix Market (`3n × 3n`, node-major DOFs x, y, z); nodes, rim and patch sets are
    /// 0-based node indices in the order of the node file.
    #[default]
    MatrixMarket,
    /// ABAQUS `*MATRIX GENERATE` output (`node, dof, node, dof, value` per line, one triangle;
    /// translational DOFs 1–3 only); the node file lists `label, x, y, z` (as in `*NODE`), the
    /// rim and patch files list node labels (as in `*NSET` data lines).
    Abaqus,
}

/// Files of an imported tire model (e.g. exported from ABAQUS, Ribaric §8.1: M and K extracted
/// under load and inflation): stiffness and mass, node coordinates in the wheel frame \[m\], and
/// the rim and candidate patch node sets (separated by white space or commas). Lines starting
/// with `#` and `*` are comments, except that an ABAQUS keyword line with `GENERATE` (e.g.
/// `*NSET, NSET=RIM, GENERATE`) makes the following data lines `first, last[, step]` ranges.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ImportFiles {
    /// Matrix file format (default: Matrix Market).
    #[serde(default)]
    pub format: ImportFormat,
    /// Stiffness matrix (with the inflation prestress).
    pub stiffness: String,
    /// Mass matrix (lumped by row sums if consistent).
    pub mass: String,
    /// Node coordinates (text, `x, y, z` per line; ABAQUS: `label, x, y, z`).
    pub nodes: String,
    /// Rim node indices (ABAQUS: labels).
    pub rim_nodes: String,
    /// Candidate patch node indices (ABAQUS: labels).
    pub patch_nodes: String,
}

/// Import a tire FE model from files (see [`ImportFiles`] and the module documentation).
pub fn imported_tire(files: &ImportFiles) -> Result<TireFe, TireError> {
    let labelled = files.format == ImportFormat::Abaqus;
    let nodes = read_nodes(&files.nodes, labelled)?;
    let (k, m) = match files.format {
        ImportFormat::MatrixMarket => (
            read_mtx("stiffness", &files.stiffness)?,
            read_mtx("mass", &files.mass)?,
        ),
        ImportFormat::Abaqus => read_abaqus(files, &nodes.labels)?,
    };
    checks::check_pair(files, &k, &m)?;
    checks::check_sizes(files, &k, nodes.coords.len())?;
    let set = |field: &'static str, path: &str| -> Result<Vec<Listed>, TireError> {
        let listed = read_indices(field, path)?;
        let listed = if labelled {
            labels_to_indices(field, path, &listed, &nodes.labels)?
        } else {
            listed
        };
        unique_in_file(field, path, &listed, &nodes)?;
        Ok(listed)
    };
    let rim = set("rim_nodes", &files.rim_nodes)?;
    let patch = set("patch_nodes", &files.patch_nodes)?;
    let fe = TireFe::from_matrices(
        nodes.coords.clone(),
        k,
        &m,
        rim.iter().map(|l| l.node).collect(),
        patch.iter().map(|l| l.node).collect(),
    )?;
    checks::check_coupling(files, &fe, &nodes)?;
    checks::check_distinct_positions(files, &fe, &nodes)?;
    checks::check_patch_on_tread(files, &fe, &nodes, &patch)?;
    Ok(fe)
}
