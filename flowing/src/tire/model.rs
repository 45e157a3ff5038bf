//! Building the tire FE model from fe-model's generated truck-tire carcass
//! ([`mod@fe_model::generate::tire`]), with the inflation prestress entering through the geometric
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

/// Format of the matrix files of an imported tire.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
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
/// with `#` (and, for ABAQUS, `*`) are comments.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
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

/// An [`TireError::Import`] error of the file named by `field`.
fn import_err(field: &'static str, reason: impl Into<String>) -> TireError {
    TireError::Import {
        field,
        reason: reason.into(),
    }
}

fn read_text(field: &'static str, path: &str) -> Result<String, TireError> {
    std::fs::read_to_string(path).map_err(|e| import_err(field, format!("{path}: {e}")))
}

fn read_indices(field: &'static str, path: &str) -> Result<Vec<usize>, TireError> {
    // plain lists and ABAQUS `*NSET ... GENERATE` blocks, bounded (fe-model, issue 35)
    let labels =
        fe_model::io::abaqus::read_node_set(path).map_err(|e| import_err(field, e.to_string()))?;
    labels
        .into_iter()
        .map(|l| {
            usize::try_from(l)
                .map_err(|_| import_err(field, format!("{path}: label {l} too large")))
        })
        .collect()
}

/// Node coordinates; with `labelled`, each line starts with the node label (returned too).
fn read_nodes_labelled(path: &str, labelled: bool) -> Result<(Vec<u64>, Vec<[f64; 3]>), TireError> {
    let text = read_text("nodes", path)?;
    let mut out = Vec::new();
    let mut labels = Vec::new();
    for (ln, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') || line.starts_with('*') {
            continue;
        }
        let mut v: Vec<&str> = line
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|t| !t.is_empty())
            .collect();
        if labelled {
            let lab = v.first().and_then(|t| t.parse::<u64>().ok());
            match lab {
                Some(l) => {
                    labels.push(l);
                    v.remove(0);
                }
                None => {
                    return Err(import_err(
                        "nodes",
                        format!("{path}:{}: expected `label, x, y, z`, got `{line}`", ln + 1),
                    ));
                }
            }
        }
        let parse = |t: &str| t.parse::<f64>().ok().filter(|x| x.is_finite());
        match (
            v.len(),
            v.iter().map(|t| parse(t)).collect::<Option<Vec<f64>>>(),
        ) {
            (3, Some(x)) => out.push([x[0], x[1], x[2]]),
            _ => {
                return Err(import_err(
                    "nodes",
                    format!(
                        "{path}:{}: expected three finite coordinates, got `{line}`",
                        ln + 1
                    ),
                ));
            }
        }
    }
    Ok((labels, out))
}

/// A stiffness or mass matrix (`field`) from Matrix Market: square and symmetric (a `general`
/// file storing one triangle is refused, see `fe_model::io::mtx`), default size ceiling unless
/// raised (`mbd_core::validate::limits`).
fn read_mtx(
    field: &'static str,
    path: &str,
) -> Result<faer::sparse::SparseColMat<usize, f64>, TireError> {
    // `--allow-large` (mbd_core::validate::limits) lifts the reader's size ceiling too
    let opts = fe_model::io::mtx::ReadOptions::symmetric()
        .allow_large(mbd_core::validate::limits::large_allowed());
    fe_model::io::mtx::read_sparse_with(path, &opts).map_err(|e| import_err(field, e.to_string()))
}

type Sparse = faer::sparse::SparseColMat<usize, f64>;

/// ABAQUS matrices reordered to the node order of the node file (DOF `3 i + d − 1` for node
/// `i`, DOF `d` = 1..3).
fn read_abaqus(files: &ImportFiles, labels: &[u64]) -> Result<(Sparse, Sparse), TireError> {
    let ke = fe_model::io::abaqus::read(&files.stiffness)
        .map_err(|e| import_err("stiffness", e.to_string()))?;
    let me =
        fe_model::io::abaqus::read(&files.mass).map_err(|e| import_err("mass", e.to_string()))?;
    let (map, mats) = fe_model::io::abaqus::assemble(&[&ke, &me])
        .map_err(|e| import_err("stiffness", e.to_string()))?;
    let pos: std::collections::HashMap<u64, usize> =
        labels.iter().enumerate().map(|(i, &l)| (l, i)).collect();
    let mut new_index = Vec::with_capacity(map.len());
    for &(node, dof) in &map.dofs {
        let Some(&i) = pos.get(&node) else {
            return Err(import_err(
                "nodes",
                format!(
                    "{}: node {node} of the ABAQUS matrices has no coordinates",
                    files.nodes
                ),
            ));
        };
        if !(1..=3).contains(&dof) {
            return Err(import_err(
                "stiffness",
                format!(
                    "{}: node {node} has DOF {dof}; only translational DOFs 1-3 (solid \
                     elements) are supported",
                    files.stiffness
                ),
            ));
        }
        new_index.push(3 * i + dof as usize - 1);
    }
    let n = 3 * labels.len();
    let mut out = Vec::with_capacity(2);
    for (a, (field, name)) in mats
        .iter()
        .zip([("stiffness", &files.stiffness), ("mass", &files.mass)])
    {
        let t: Vec<faer::sparse::Triplet<usize, usize, f64>> = a
            .as_ref()
            .triplet_iter()
            .map(|e| faer::sparse::Triplet::new(new_index[e.row], new_index[e.col], *e.val))
            .collect();
        out.push(
            faer::sparse::SparseColMat::try_new_from_triplets(n, n, &t).map_err(|e| {
                import_err(
                    field,
                    format!("{name}: cannot build the sparse matrix: {e:?}"),
                )
            })?,
        );
    }
    let m = out
        .pop()
        .ok_or_else(|| import_err("mass", format!("{}: no mass matrix", files.mass)))?;
    let k = out.pop().ok_or_else(|| {
        import_err(
            "stiffness",
            format!("{}: no stiffness matrix", files.stiffness),
        )
    })?;
    Ok((k, m))
}

/// Node labels of the set named by `field` (file `path`) → 0-based indices in the node file's
/// order.
fn labels_to_indices(
    field: &'static str,
    path: &str,
    set: &[usize],
    labels: &[u64],
) -> Result<Vec<usize>, TireError> {
    let pos: std::collections::HashMap<u64, usize> =
        labels.iter().enumerate().map(|(i, &l)| (l, i)).collect();
    set.iter()
        .map(|&l| {
            pos.get(&(l as u64)).copied().ok_or_else(|| {
                import_err(
                    field,
                    format!("{path}: node label {l} is not in the node file"),
                )
            })
        })
        .collect()
}

/// The physical plausibility of imported K and M (issue #20, item 3): K symmetric positive
/// semi-definite (the free tire's rigid-body modes are allowed), M positive semi-definite
/// (massless DOFs are condensed by the Craig–Bampton reduction), entries finite
/// ([`fe_model::plausibility::check_stiffness_mass`], Géradin & Rixen §2.3). An all-zero or
/// indefinite K is refused with the offending DOFs (1-based rows) instead of giving nonsense
/// frequencies; warnings (DOFs without stiffness or mass) are not errors and are dropped here.
fn check_pair(files: &ImportFiles, k: &Sparse, m: &Sparse) -> Result<(), TireError> {
    let opts = fe_model::plausibility::PairCheckOptions {
        massless_dofs_allowed: true,
    };
    fe_model::plausibility::check_stiffness_mass(k.as_ref(), m.as_ref(), &opts)
        .map(|_warnings| ())
        .map_err(|e| {
            let (field, path) = match &e {
                fe_model::FeError::Implausible { matrix, .. } if matrix == "K" => {
                    ("stiffness", &files.stiffness)
                }
                fe_model::FeError::Dimension { .. } => ("stiffness", &files.stiffness),
                _ => ("mass", &files.mass),
            };
            import_err(field, format!("{path}: {e}"))
        })
}

/// Import a tire FE model from files (see [`ImportFiles`]).
pub fn imported_tire(files: &ImportFiles) -> Result<TireFe, TireError> {
    match files.format {
        ImportFormat::MatrixMarket => {
            let k = read_mtx("stiffness", &files.stiffness)?;
            let m = read_mtx("mass", &files.mass)?;
            check_pair(files, &k, &m)?;
            let (_, nodes) = read_nodes_labelled(&files.nodes, false)?;
            let rim = read_indices("rim_nodes", &files.rim_nodes)?;
            let patch = read_indices("patch_nodes", &files.patch_nodes)?;
            TireFe::from_matrices(nodes, k, &m, rim, patch)
        }
        ImportFormat::Abaqus => {
            let (labels, nodes) = read_nodes_labelled(&files.nodes, true)?;
            let (k, m) = read_abaqus(files, &labels)?;
            check_pair(files, &k, &m)?;
            let rim = labels_to_indices(
                "rim_nodes",
                &files.rim_nodes,
                &read_indices("rim_nodes", &files.rim_nodes)?,
                &labels,
            )?;
            let patch = labels_to_indices(
                "patch_nodes",
                &files.patch_nodes,
                &read_indices("patch_nodes", &files.patch_nodes)?,
                &labels,
            )?;
            TireFe::from_matrices(nodes, k, &m, rim, patch)
        }
    }
}
