//! The checks of an imported tire that catch the easy mistakes before the reduction (each
//! refusal names the import field, the file and, where it applies, the line): K and M
//! physically plausible, K coupling the nodes into one body (not only its diagonal, no node
//! left out), distinct positions of the tire's nodes, and the candidate patch on the tread
//! around the road point.

use super::ImportFiles;
use super::read::{Listed, Nodes, Sparse, import_err};
use crate::error::TireError;
use crate::mesh::{TireFe, node_angle};
use std::f64::consts::PI;

/// The patch nodes must lie in this outer fraction of the section height between the rim
/// (largest rim-node radius) and the tread (largest node radius): the tread's outer surface
/// (the default truck tire's patch lies within its outer 3 %).
pub const TREAD_FRACTION: f64 = 0.25;

/// Some patch node must lie within this angle of the road point θ = π \[deg\] (the reduction
/// keeps the candidates nearest to it, [`crate::reduce::select_contact_nodes`]).
pub const MAX_PATCH_OFFSET_DEG: f64 = 10.0;

/// A check of an imported tire that failed (issue #39, item 7), carried by
/// [`TireError::ImportCheck`]: each names the file it blames (and the line or node) and the
/// numbers that fail the check.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ImportCheckError {
    /// K holds no entry off its diagonal: no DOF is coupled to another (e.g. only the diagonal
    /// of a triangle was written).
    #[error(
        "{file}: K has no off-diagonal entry, so no DOF is coupled to another (only the \
         diagonal was written?): export the assembled stiffness with its coupling terms \
         (Matrix Market `symmetric` with the lower triangle, or `general` with both)"
    )]
    DiagonalStiffness {
        /// The stiffness file.
        file: String,
    },
    /// A node (with the part of the tire it belongs to) that no stiffness entry connects to
    /// the largest connected part: a node of the node file that belongs to no element.
    #[error(
        "{file}: {node} is not connected to the rest of the tire by any stiffness entry (K \
         couples the {nodes} nodes into {parts} separate parts; this one has {part_nodes} \
         nodes): every node of the node file must belong to the tire's elements"
    )]
    DisconnectedNode {
        /// The stiffness file.
        file: String,
        /// The node as the user wrote it (index or label, with its line in the node file).
        node: String,
        /// Nodes of the model.
        nodes: usize,
        /// Connected parts K makes of them.
        parts: usize,
        /// Nodes of the part that holds `node`.
        part_nodes: usize,
    },
    /// The rim nodes reach at least as far from the wheel axis as the other nodes: the
    /// coordinates are not in the wheel frame (or the rim set is not the rim).
    #[error(
        "{file}: the rim nodes reach the radius {rim_radius_m} m, not inside the tire's outer \
         radius {outer_radius_m} m (radius about the wheel axis y): the coordinates must be in \
         the wheel frame (x forward, y along the axle, z up)"
    )]
    RimNotInside {
        /// The rim node-set file.
        file: String,
        /// Largest radius of a rim node about the wheel axis \[m\].
        rim_radius_m: f64,
        /// Largest radius of a non-rim node \[m\].
        outer_radius_m: f64,
    },
    /// A patch node below the tread band (see [`TREAD_FRACTION`]).
    #[error(
        "{file}:{line}: {node} lies at the radius {radius_m:.4} m, below the outer \
         {percent:.0} % of the section between the rim ({rim_radius_m:.4} m) and the tread \
         ({outer_radius_m:.4} m): the patch set must be nodes of the tread's outer surface",
        percent = 100.0 * TREAD_FRACTION
    )]
    PatchOffTread {
        /// The patch node-set file.
        file: String,
        /// The line \[1-based\] of the file listing the node.
        line: usize,
        /// The node as the user wrote it.
        node: String,
        /// Its radius about the wheel axis \[m\].
        radius_m: f64,
        /// Largest rim-node radius \[m\].
        rim_radius_m: f64,
        /// Largest non-rim radius (the tread's outer surface) \[m\].
        outer_radius_m: f64,
    },
    /// No patch node near the road point θ = π (see [`MAX_PATCH_OFFSET_DEG`]).
    #[error(
        "{file}: no node of the patch set lies within {MAX_PATCH_OFFSET_DEG}° of the road \
         point θ = π (the bottom of the tire, −z; the nearest is {nearest_deg:.1}° from it): \
         the patch must surround the point where the tire meets the ground, in the wheel \
         frame x forward, y along the axle, z up"
    )]
    PatchAwayFromRoad {
        /// The patch node-set file.
        file: String,
        /// Angle of the patch node nearest to the road point \[deg\].
        nearest_deg: f64,
    },
}

/// The [`TireError`] of a failed check blaming the file of import field `field`.
fn failed(field: &'static str, check: ImportCheckError) -> TireError {
    TireError::ImportCheck { field, check }
}

/// The physical plausibility of imported K and M (issue #20, item 3): K symmetric positive
/// semi-definite (the free tire's rigid-body modes are allowed), M positive semi-definite
/// (massless DOFs are condensed by the Craig–Bampton reduction), entries finite
/// ([`fe_model::plausibility::check_stiffness_mass`], Géradin & Rixen §2.3). An all-zero or
/// indefinite K is refused with the offending DOFs (1-based rows) instead of giving nonsense
/// frequencies; warnings (DOFs without stiffness or mass) are not errors and are dropped here.
pub(super) fn check_pair(files: &ImportFiles, k: &Sparse, m: &Sparse) -> Result<(), TireError> {
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

/// K is `3n × 3n` for the `n` nodes of the node file.
pub(super) fn check_sizes(
    files: &ImportFiles, k: &Sparse, n_nodes: usize,
) -> Result<(), TireError> {
    let n = 3 * n_nodes;
    if k.nrows() != n || k.ncols() != n {
        return Err(import_err(
            "nodes",
            format!(
                "{}: {n_nodes} nodes (3 DOFs each) need a {n} × {n} stiffness matrix, but {} is \
                 {} × {}",
                files.nodes,
                files.stiffness,
                k.nrows(),
                k.ncols()
            ),
        ));
    }
    Ok(())
}

/// K couples the nodes into one body (issue #39, item 7): a K without any off-diagonal entry
/// (e.g. only its diagonal written) and a node that no stiffness entry connects to the rest
/// (e.g. a node of the node file that belongs to no element) are refused. Connectivity is that
/// of the graph whose edges are the nonzero entries `K_ij` between DOFs of different nodes
/// (union–find over the nodes).
pub(super) fn check_coupling(
    files: &ImportFiles, fe: &TireFe, nodes: &Nodes,
) -> Result<(), TireError> {
    let n = fe.n_nodes();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    let mut off_diagonal = false;
    for (r, c, v) in fe_model::sparse::triplets(fe.stiffness.as_ref()) {
        if r == c || v == 0.0 {
            continue;
        }
        off_diagonal = true;
        let (a, b) = (root(&mut parent, r / 3), root(&mut parent, c / 3));
        if a != b {
            parent[a.max(b)] = a.min(b);
        }
    }
    if !off_diagonal {
        return Err(failed(
            "stiffness",
            ImportCheckError::DiagonalStiffness {
                file: files.stiffness.clone(),
            },
        ));
    }
    let mut size = vec![0usize; n];
    let roots: Vec<usize> = (0..n).map(|i| root(&mut parent, i)).collect();
    for &r in &roots {
        size[r] += 1;
    }
    let body = (0..n)
        .max_by_key(|&r| (size[r], std::cmp::Reverse(r)))
        .unwrap_or(0);
    if let Some(i) = (0..n).find(|&i| roots[i] != body) {
        return Err(failed(
            "stiffness",
            ImportCheckError::DisconnectedNode {
                file: files.stiffness.clone(),
                node: nodes.name(i),
                nodes: n,
                parts: (0..n).filter(|&r| size[r] > 0).count(),
                part_nodes: size[roots[i]],
            },
        ));
    }
    Ok(())
}

/// The tire's (non-rim) nodes lie at distinct points: the flowing-material tire orders each
/// circumferential ring by angle, and coincident nodes (or a node file whose coordinates are
/// all the same) make no ring. Points closer than 10⁻⁹ of the model's extent count as the same.
pub(super) fn check_distinct_positions(
    files: &ImportFiles, fe: &TireFe, nodes: &Nodes,
) -> Result<(), TireError> {
    let rim = fe.rim_mask();
    let mut idx: Vec<usize> = (0..fe.n_nodes()).filter(|&i| !rim[i]).collect();
    let Some(&first) = idx.first() else {
        return Ok(());
    };
    let x = &fe.nodes;
    let extent = idx.iter().fold(0.0f64, |e, &i| {
        (0..3).fold(e, |e, a| e.max((x[i][a] - x[first][a]).abs()))
    });
    if extent == 0.0 && idx.len() > 1 {
        let p = x[first];
        return Err(import_err(
            "nodes",
            format!(
                "{}: all {} tire nodes have the same coordinates ({}, {}, {}): the node file \
                 must give each node's position in the wheel frame [m]",
                files.nodes,
                idx.len(),
                p[0],
                p[1],
                p[2]
            ),
        ));
    }
    let tol = 1e-9 * extent;
    idx.sort_by(|&a, &b| x[a][0].total_cmp(&x[b][0]));
    for (k, &a) in idx.iter().enumerate() {
        for &b in &idx[k + 1..] {
            if x[b][0] - x[a][0] > tol {
                break;
            }
            if (x[b][1] - x[a][1]).abs() <= tol && (x[b][2] - x[a][2]).abs() <= tol {
                let (a, b) = (a.min(b), a.max(b));
                return Err(import_err(
                    "nodes",
                    format!(
                        "{} and {} lie at the same point ({}, {}, {}) m: the tire's nodes must \
                         be distinct (merge coincident nodes in the FE model)",
                        nodes.name(a),
                        nodes.name(b),
                        x[a][0],
                        x[a][1],
                        x[a][2]
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The candidate patch is on the tread (issue #39, item 7): every patch node in the outer
/// [`TREAD_FRACTION`] of the section height (radius `ρ = √(x² + z²)` about the wheel axis `y`)
/// and some patch node within [`MAX_PATCH_OFFSET_DEG`] of the road point θ = π, so that a rim
/// set, an inner-liner set, a set shifted by one (1-based indices) or a model in another frame
/// is refused instead of giving a tire that never touches the ground.
pub(super) fn check_patch_on_tread(
    files: &ImportFiles, fe: &TireFe, nodes: &Nodes, patch: &[Listed],
) -> Result<(), TireError> {
    let rho = |i: usize| fe.nodes[i][0].hypot(fe.nodes[i][2]);
    let rim = fe.rim_mask();
    let (mut outer, mut rim_r) = (0.0f64, 0.0f64);
    for i in 0..fe.n_nodes() {
        if rim[i] {
            rim_r = rim_r.max(rho(i));
        } else {
            outer = outer.max(rho(i));
        }
    }
    let height = outer - rim_r;
    if height.is_nan() || height <= 0.0 {
        return Err(failed(
            "rim_nodes",
            ImportCheckError::RimNotInside {
                file: files.rim_nodes.clone(),
                rim_radius_m: rim_r,
                outer_radius_m: outer,
            },
        ));
    }
    let floor = outer - TREAD_FRACTION * height;
    if let Some(l) = patch.iter().find(|l| rho(l.node) < floor) {
        return Err(failed(
            "patch_nodes",
            ImportCheckError::PatchOffTread {
                file: files.patch_nodes.clone(),
                line: l.line,
                node: nodes.name(l.node),
                radius_m: rho(l.node),
                rim_radius_m: rim_r,
                outer_radius_m: outer,
            },
        ));
    }
    let nearest = patch
        .iter()
        .map(|l| (node_angle(&fe.nodes[l.node]) - PI).abs().to_degrees())
        .fold(f64::INFINITY, f64::min);
    if nearest > MAX_PATCH_OFFSET_DEG {
        return Err(failed(
            "patch_nodes",
            ImportCheckError::PatchAwayFromRoad {
                file: files.patch_nodes.clone(),
                nearest_deg: nearest,
            },
        ));
    }
    Ok(())
}
