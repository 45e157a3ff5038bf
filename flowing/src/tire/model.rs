//! Building the tire FE model from fe-model's generated truck-tire carcass
//! ([`fe_model::generate::tire`]), with the inflation prestress entering through the geometric
//! stiffness (Ribaric §8.1: M and K "under load and inflation").

use super::error::TireError;
use super::mesh::TireFe;
use fe_model::generate::{TireConfig, tire};

/// The full-size truck tire (295/80 R22.5, 38 psi): fe-model's default generator settings.
pub fn truck_tire_config() -> TireConfig {
    TireConfig::default()
}

/// A coarse version of the truck tire (same dimensions, materials and inflation) for quick
/// tests: `circumferential` elements around, `section` along the cross-section, one through the
/// thickness; the candidate patch covers ±`patch_deg` degrees.
pub fn coarse_tire_config(circumferential: usize, section: usize, patch_deg: f64) -> TireConfig {
    TireConfig {
        circumferential_divisions: circumferential,
        section_divisions: section,
        thickness_divisions: 1,
        bead_elements: 1,
        patch_half_angle_deg: patch_deg,
        ..TireConfig::default()
    }
}

/// Generate the tire and assemble its FE model (lumped mass; `K + K_G` of the inflation
/// prestress). The candidate contact nodes are the generator's `contact_patch` set.
pub fn generated_tire(cfg: &TireConfig) -> Result<TireFe, TireError> {
    let t = tire(cfg)?;
    TireFe::from_fe_model(
        &t.model,
        "rim",
        "contact_patch",
        cfg.inflation_pressure > 0.0,
    )
}

/// Files of an imported tire model (e.g. exported from ABAQUS, Ribaric §8.1: M and K extracted
/// under load and inflation): Matrix Market stiffness and mass (`3n × 3n`, node-major DOFs x, y,
/// z), node coordinates in the wheel frame (one `x, y, z` line per node [m]), and the rim and
/// candidate patch node indices (0-based, separated by white space or commas). Lines starting
/// with `#` are comments.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImportFiles {
    /// Stiffness matrix (Matrix Market).
    pub stiffness: String,
    /// Mass matrix (Matrix Market; lumped by row sums if consistent).
    pub mass: String,
    /// Node coordinates (text, `x, y, z` per line).
    pub nodes: String,
    /// Rim node indices (text).
    pub rim_nodes: String,
    /// Candidate patch node indices (text).
    pub patch_nodes: String,
}

fn read_text(path: &str) -> Result<String, TireError> {
    std::fs::read_to_string(path).map_err(|e| TireError::File {
        path: path.to_string(),
        reason: e.to_string(),
    })
}

fn read_indices(path: &str) -> Result<Vec<usize>, TireError> {
    let text = read_text(path)?;
    let mut out = Vec::new();
    for (ln, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        for tok in line
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|t| !t.is_empty())
        {
            out.push(tok.parse::<usize>().map_err(|_| TireError::File {
                path: format!("{path}:{}", ln + 1),
                reason: format!("`{tok}` is not a node index"),
            })?);
        }
    }
    Ok(out)
}

fn read_nodes(path: &str) -> Result<Vec<[f64; 3]>, TireError> {
    let text = read_text(path)?;
    let mut out = Vec::new();
    for (ln, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let v: Vec<&str> = line
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|t| !t.is_empty())
            .collect();
        let parse = |t: &str| t.parse::<f64>().ok().filter(|x| x.is_finite());
        match (
            v.len(),
            v.iter().map(|t| parse(t)).collect::<Option<Vec<f64>>>(),
        ) {
            (3, Some(x)) => out.push([x[0], x[1], x[2]]),
            _ => {
                return Err(TireError::File {
                    path: format!("{path}:{}", ln + 1),
                    reason: format!("expected three finite coordinates, got `{line}`"),
                });
            }
        }
    }
    Ok(out)
}

fn read_mtx(path: &str) -> Result<faer::sparse::SparseColMat<usize, f64>, TireError> {
    let m = fe_model::io::mtx::read(path)?;
    let t: Vec<faer::sparse::Triplet<usize, usize, f64>> = m
        .entries
        .iter()
        .map(|&(i, j, v)| faer::sparse::Triplet::new(i, j, v))
        .collect();
    faer::sparse::SparseColMat::try_new_from_triplets(m.nrows, m.ncols, &t).map_err(|e| {
        TireError::File {
            path: path.to_string(),
            reason: format!("cannot build the sparse matrix: {e:?}"),
        }
    })
}

/// Import a tire FE model from files (see [`ImportFiles`]).
pub fn imported_tire(files: &ImportFiles) -> Result<TireFe, TireError> {
    let k = read_mtx(&files.stiffness)?;
    let m = read_mtx(&files.mass)?;
    let nodes = read_nodes(&files.nodes)?;
    let rim = read_indices(&files.rim_nodes)?;
    let patch = read_indices(&files.patch_nodes)?;
    TireFe::from_matrices(nodes, k, &m, rim, patch)
}
