//! The `flowmbd-reduce tire-mesh` study: the generated truck-tire carcass ([`tire`]) with its
//! assembled stiffness and mass matrices (all DOFs; K with the inflation geometric stiffness
//! when enabled) and the summary of its size. Shared by the app (which writes `M.mtx`, `K.mtx`,
//! `mesh.vtu`, `mesh.json`, `node_sets.json` and `rim_dofs.txt`) and the Python package
//! (`flowmbd.reduce.tire_mesh`).

use super::tire::{Tire, TireConfig, tire};
use crate::FeError;
use crate::element::MassKind;
use faer::sparse::SparseColMat;
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Configuration of the `tire-mesh` study.
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct TireMeshConfig {
    /// Tire geometry, mesh divisions, materials and inflation.
    pub tire: TireConfig,
    /// Mass discretisation (`consistent` or `lumped`).
    pub mass: MassKind,
    /// Add the inflation geometric stiffness to K.
    pub geometric_stiffness: bool,
}

impl Default for TireMeshConfig {
    /// The 63 936-DOF truck tire standing in for Ribaric §8.1's >60 000-DOF ABAQUS model, with
    /// consistent mass and the inflation prestress.
    fn default() -> Self {
        Self {
            tire: TireConfig::default(),
            mass: MassKind::Consistent,
            geometric_stiffness: true,
        }
    }
}

impl mbd_core::config::PartialRules for TireMeshConfig {}

impl Validate for TireMeshConfig {
    /// The tire's checks under `tire.`.
    fn validate(&self) -> Result<(), InvalidField> {
        self.tire.validate_within("tire")
    }
}

/// The `meaning` of the `tire-mesh` summary.
pub const TIRE_MESH_MEANING: &str = "The generated truck-tire carcass: the nodes, hexahedra and DOFs of the mesh written \
     as mesh.json, M and K (Matrix Market) and the node sets (rim, contact patch), for \
     flowmbd-reduce and other FE tools.";

/// Summary of `tire-mesh` (the app adds the list of files it wrote).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TireMeshSummary {
    /// Nodes.
    pub nodes: usize,
    /// Hexahedra.
    pub elements: usize,
    /// DOFs (3 per node).
    pub dof: usize,
    /// Stored entries of K (both triangles).
    pub nnz_k: usize,
    /// Node-set sizes.
    pub node_sets: BTreeMap<String, usize>,
    /// Total mass \[kg\] (rigid translation `uᵀ M u` along x).
    pub mass_kg: f64,
    /// What the numbers mean ([`TIRE_MESH_MEANING`]).
    pub meaning: String,
}

/// Failure of `tire-mesh`.
#[derive(Debug, thiserror::Error)]
pub enum TireMeshError {
    /// The generator refused the tire (bad input; the app reports it under `tire`).
    #[error("{0}")]
    Generate(FeError),
    /// Assembling K or M failed (numerical).
    #[error("assembly: {0}")]
    Assembly(FeError),
}

/// Result of [`tire_mesh`].
#[derive(Debug)]
pub struct TireMesh {
    /// The generated tire (mesh with its node sets, elements, zones).
    pub tire: Tire,
    /// Stiffness \[N/m\] (all DOFs, node-major u, v, w).
    pub k: SparseColMat<usize, f64>,
    /// Mass \[kg\] (the configured discretisation).
    pub m: SparseColMat<usize, f64>,
    /// The summary.
    pub summary: TireMeshSummary,
}

/// Generate the tire of `c` ([`tire`]) and assemble K (with the geometric stiffness of the
/// inflation pressure when `geometric_stiffness`) and M.
pub fn tire_mesh(c: &TireMeshConfig) -> Result<TireMesh, TireMeshError> {
    let t = tire(&c.tire).map_err(TireMeshError::Generate)?;
    let (k, m) = t
        .model
        .k_and_m(c.mass, c.geometric_stiffness)
        .map_err(TireMeshError::Assembly)?;
    let mesh = &t.model.mesh;
    let mass_kg = crate::sparse::triplets(m.as_ref())
        .filter(|&(r, c, _)| r % 3 == 0 && c % 3 == 0)
        .map(|t| t.2)
        .sum();
    let summary = TireMeshSummary {
        nodes: mesh.n_nodes(),
        elements: t.model.elements.len(),
        dof: mesh.n_dofs(),
        nnz_k: k.compute_nnz(),
        node_sets: mesh
            .node_sets
            .iter()
            .map(|(k, v)| (k.clone(), v.len()))
            .collect(),
        mass_kg,
        meaning: TIRE_MESH_MEANING.to_string(),
    };
    Ok(TireMesh {
        tire: t,
        k,
        m,
        summary,
    })
}
