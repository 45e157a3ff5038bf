//! Fixed / boundary / interior partition of the DOFs of a component (Lin (6.1), Ribaric (3.2);
//! Ribaric §8.2 for the three-set rim / contact / free split of the tire).

use crate::error::{ReductionError, Result};
use serde::{Deserialize, Serialize};

/// Partition of `n` DOFs into fixed DOFs (clamped, e.g. a rim: zero rows in every basis),
/// boundary DOFs `b` (kept physically: interface, supports, load points, contact nodes) and
/// interior DOFs `i` (condensed by static modes and truncated by fixed-interface modes,
/// Lin (6.1)).
///
/// DOF indices are 0-based positions in the full vector. The boundary order is the order given
/// by the user (it is the order of the boundary columns of every basis); interior and fixed DOFs
/// are in ascending order.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct DofPartition {
    n: usize,
    boundary: Vec<usize>,
    interior: Vec<usize>,
    /// Clamped DOFs (absent in files written before the fixed set existed).
    #[serde(default)]
    fixed: Vec<usize>,
}

impl DofPartition {
    /// Partition from a list of boundary DOFs (0-based, distinct, `< n`); no fixed DOFs.
    pub fn from_boundary_dofs(n: usize, boundary: &[usize]) -> Result<Self> {
        Self::new(n, boundary, &[])
    }

    /// Three-set partition: `boundary` DOFs (user order), `fixed` DOFs (clamped) and the
    /// interior = all others. Every DOF must be `< n` and appear at most once in the two lists.
    pub fn new(n: usize, boundary: &[usize], fixed: &[usize]) -> Result<Self> {
        // 0 = interior, 1 = boundary, 2 = fixed
        let mut set = vec![0u8; n];
        for (what, list, tag) in [("boundary", boundary, 1u8), ("fixed", fixed, 2u8)] {
            for &d in list {
                if d >= n {
                    return Err(ReductionError::InvalidDofs {
                        what: format!("{what} DOF set"),
                        reason: format!("DOF {d} is out of range (the model has {n} DOFs)"),
                    });
                }
                match set[d] {
                    0 => set[d] = tag,
                    t if t == tag => {
                        return Err(ReductionError::InvalidDofs {
                            what: format!("{what} DOF set"),
                            reason: format!("DOF {d} is listed twice"),
                        });
                    }
                    _ => {
                        return Err(ReductionError::InvalidDofs {
                            what: "fixed DOF set".into(),
                            reason: format!("DOF {d} is also a boundary DOF"),
                        });
                    }
                }
            }
        }
        let pick = |tag: u8| (0..n).filter(|&d| set[d] == tag).collect::<Vec<_>>();
        Ok(Self {
            n,
            boundary: boundary.to_vec(),
            interior: pick(0),
            fixed: pick(2),
        })
    }

    /// Partition from boundary nodes (0-based node indices); node `j` owns DOFs
    /// `dofs_per_node·j .. dofs_per_node·(j+1)` (Lin: 2 per node in 2-D, 3 in 3-D).
    pub fn from_boundary_nodes(n: usize, dofs_per_node: usize, nodes: &[usize]) -> Result<Self> {
        Self::from_nodes(n, dofs_per_node, nodes, &[])
    }

    /// Three-set partition from boundary and fixed nodes (0-based node indices, every DOF of a
    /// listed node), see [`DofPartition::new`].
    pub fn from_nodes(
        n: usize, dofs_per_node: usize, boundary_nodes: &[usize], fixed_nodes: &[usize],
    ) -> Result<Self> {
        if dofs_per_node == 0 || !n.is_multiple_of(dofs_per_node) {
            return Err(ReductionError::InvalidParameter {
                name: "dofs_per_node".into(),
                reason: format!("{dofs_per_node} does not divide the number of DOFs {n}"),
            });
        }
        let nn = n / dofs_per_node;
        let dofs = |what: &str, nodes: &[usize]| {
            let mut dofs = Vec::with_capacity(nodes.len() * dofs_per_node);
            for &j in nodes {
                if j >= nn {
                    return Err(ReductionError::InvalidDofs {
                        what: format!("{what} node set"),
                        reason: format!(
                            "node {j} (0-based) is out of range (the model has {nn} nodes)"
                        ),
                    });
                }
                dofs.extend((0..dofs_per_node).map(|c| dofs_per_node * j + c));
            }
            Ok(dofs)
        };
        Self::new(
            n,
            &dofs("boundary", boundary_nodes)?,
            &dofs("fixed", fixed_nodes)?,
        )
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

    /// Fixed (clamped) DOFs, ascending; empty for a two-set partition.
    pub fn fixed(&self) -> &[usize] {
        &self.fixed
    }

    /// The DOFs that are not fixed (boundary and interior), ascending.
    pub fn unfixed(&self) -> Vec<usize> {
        let mut is_fixed = vec![false; self.n];
        for &d in &self.fixed {
            is_fixed[d] = true;
        }
        (0..self.n).filter(|&d| !is_fixed[d]).collect()
    }
}
