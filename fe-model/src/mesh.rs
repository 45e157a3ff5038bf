//! Meshes: node coordinates, uniform node-major DOF numbering, cells (for export) and named
//! node sets.
//!
//! Global DOF `d` of node `n` with local DOF `l` is `n · dofs_per_node + l` (e.g. for a 2D frame
//! `l = 0, 1, 2` are u, v, θ; for a 3D frame u, v, w, θx, θy, θz; for solids u, v, w).

use crate::FeError;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Geometric type of a mesh cell (the VTK cell types used for export).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum CellKind {
    /// Single node (point mass, spring end).
    Vertex,
    /// Two-node line (string, bar, frame).
    Line,
    /// Four-node quadrilateral (surface output, e.g. the plate belt of Kerkkänen ch. 4).
    Quad,
    /// Eight-node hexahedron (VTK node order).
    Hexahedron,
}

impl CellKind {
    /// VTK cell type id.
    pub fn vtk_type(self) -> u8 {
        match self {
            CellKind::Vertex => 1,
            CellKind::Line => 3,
            CellKind::Quad => 9,
            CellKind::Hexahedron => 12,
        }
    }

    /// Number of nodes of the cell.
    pub fn n_nodes(self) -> usize {
        match self {
            CellKind::Vertex => 1,
            CellKind::Line => 2,
            CellKind::Quad => 4,
            CellKind::Hexahedron => 8,
        }
    }
}

/// A mesh cell: kind and node indices.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Cell {
    /// Cell type.
    pub kind: CellKind,
    /// Node indices (VTK order).
    pub nodes: Vec<usize>,
}

/// A finite-element mesh with uniform DOFs per node.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Mesh {
    /// Node coordinates \[m\] (x, y, z; z = 0 for planar models).
    pub nodes: Vec<[f64; 3]>,
    /// DOFs per node.
    pub dofs_per_node: usize,
    /// Cells (geometry for export; the elements carry the physics).
    pub cells: Vec<Cell>,
    /// Named node sets (sorted node indices).
    pub node_sets: BTreeMap<String, Vec<usize>>,
}

impl Mesh {
    /// Empty mesh with `dofs_per_node` DOFs per node.
    pub fn new(dofs_per_node: usize) -> Self {
        Self {
            nodes: Vec::new(),
            dofs_per_node,
            cells: Vec::new(),
            node_sets: BTreeMap::new(),
        }
    }

    /// Append a node, returning its index.
    pub fn add_node(&mut self, x: [f64; 3]) -> usize {
        self.nodes.push(x);
        self.nodes.len() - 1
    }

    /// Number of nodes.
    pub fn n_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// Total number of DOFs.
    pub fn n_dofs(&self) -> usize {
        self.nodes.len() * self.dofs_per_node
    }

    /// Global DOF of `node`'s local DOF `local`.
    pub fn dof(&self, node: usize, local: usize) -> usize {
        node * self.dofs_per_node + local
    }

    /// All global DOFs of a node.
    pub fn node_dofs(&self, node: usize) -> std::ops::Range<usize> {
        node * self.dofs_per_node..(node + 1) * self.dofs_per_node
    }

    /// (node, local DOF) of a global DOF.
    pub fn dof_owner(&self, dof: usize) -> (usize, usize) {
        (dof / self.dofs_per_node, dof % self.dofs_per_node)
    }

    /// Define (or replace) a named node set; node indices are validated, sorted, de-duplicated.
    pub fn set_node_set(&mut self, name: &str, mut nodes: Vec<usize>) -> Result<(), FeError> {
        if let Some(&bad) = nodes.iter().find(|&&n| n >= self.nodes.len()) {
            return Err(FeError::Index {
                context: format!("node set `{name}`"),
                index: bad,
                size: self.nodes.len(),
            });
        }
        nodes.sort_unstable();
        nodes.dedup();
        self.node_sets.insert(name.to_string(), nodes);
        Ok(())
    }

    /// Nodes of a named set.
    pub fn node_set(&self, name: &str) -> Result<&[usize], FeError> {
        self.node_sets
            .get(name)
            .map(|v| v.as_slice())
            .ok_or_else(|| FeError::Unknown {
                what: "node set".into(),
                name: name.to_string(),
                known: self
                    .node_sets
                    .keys()
                    .cloned()
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }

    /// Global DOFs of a node set, restricted to the local DOFs `locals` (all if `None`),
    /// sorted ascending.
    pub fn node_set_dofs(
        &self, name: &str, locals: Option<&[usize]>,
    ) -> Result<Vec<usize>, FeError> {
        let nodes = self.node_set(name)?;
        let mut out = Vec::new();
        for &n in nodes {
            match locals {
                Some(ls) => {
                    for &l in ls {
                        if l >= self.dofs_per_node {
                            return Err(FeError::Index {
                                context: format!("local DOF for node set `{name}`"),
                                index: l,
                                size: self.dofs_per_node,
                            });
                        }
                        out.push(self.dof(n, l));
                    }
                }
                None => out.extend(self.node_dofs(n)),
            }
        }
        out.sort_unstable();
        out.dedup();
        Ok(out)
    }
}
