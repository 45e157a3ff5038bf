//! Boundary / interior partition of the DOFs of a component (Lin (6.1), Ribaric (3.2)).

use crate::error::{ReductionError, Result};
use serde::{Deserialize, Serialize};

/// Partition of `n` DOFs into boundary DOFs `b` (kept physically: interface, supports, load
/// points) and interior DOFs `i` (Lin (6.1)).
///
/// DOF indices are 0-based positions in the full vector. The boundary order is the order given
/// by the user (it is the order of the boundary columns of every basis); interior DOFs are in
/// ascending order.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct DofPartition {
    n: usize,
    boundary: Vec<usize>,
    interior: Vec<usize>,
}

impl DofPartition {
    /// Partition from a list of boundary DOFs (0-based, distinct, `< n`).
    pub fn from_boundary_dofs(n: usize, boundary: &[usize]) -> Result<Self> {
        let mut seen = vec![false; n];
        for &d in boundary {
            if d >= n {
                return Err(ReductionError::InvalidDofs {
                    what: "boundary DOF set".into(),
                    reason: format!("DOF {d} is out of range (the model has {n} DOFs)"),
                });
            }
            if seen[d] {
                return Err(ReductionError::InvalidDofs {
                    what: "boundary DOF set".into(),
                    reason: format!("DOF {d} is listed twice"),
                });
            }
            seen[d] = true;
        }
        let interior = (0..n).filter(|&d| !seen[d]).collect();
        Ok(Self {
            n,
            boundary: boundary.to_vec(),
            interior,
        })
    }

    /// Partition from boundary nodes (0-based node indices); node `j` owns DOFs
    /// `dofs_per_node·j .. dofs_per_node·(j+1)` (Lin: 2 per node in 2-D, 3 in 3-D).
    pub fn from_boundary_nodes(n: usize, dofs_per_node: usize, nodes: &[usize]) -> Result<Self> {
        if dofs_per_node == 0 || !n.is_multiple_of(dofs_per_node) {
            return Err(ReductionError::InvalidParameter {
                name: "dofs_per_node".into(),
                reason: format!("{dofs_per_node} does not divide the number of DOFs {n}"),
            });
        }
        let nn = n / dofs_per_node;
        let mut dofs = Vec::with_capacity(nodes.len() * dofs_per_node);
        for &j in nodes {
            if j >= nn {
                return Err(ReductionError::InvalidDofs {
                    what: "boundary node set".into(),
                    reason: format!(
                        "node {j} (0-based) is out of range (the model has {nn} nodes)"
                    ),
                });
            }
            dofs.extend((0..dofs_per_node).map(|c| dofs_per_node * j + c));
        }
        Self::from_boundary_dofs(n, &dofs)
    }

    /// Total number of DOFs.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Boundary DOFs, in user order.
    pub fn boundary(&self) -> &[usize] {
        &self.boundary
    }

    /// Interior DOFs, ascending.
    pub fn interior(&self) -> &[usize] {
        &self.interior
    }
}
