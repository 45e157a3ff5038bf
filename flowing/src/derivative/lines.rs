//! Per-component derivatives of mode shapes with several DOFs per node (Ribaric A.5).

use super::{DerivativeMethod, LineOperator};
use crate::error::{FlowError, invalid};
use crate::grid::FlowGrid;
use faer::{Mat, MatRef};

/// One scalar field of a model sampled along a flow line: the grid and, for every grid node (in
/// flow order), the row of that field's DOF in the model's DOF vector (`None` where the DOF is
/// eliminated, i.e. known to be zero, e.g. a node bonded to a fixed support).
///
/// A belt node with `(x, y, θ)` DOFs gives three lines on the same grid; a tire gives three lines
/// per circumferential ring (Ribaric A.5: "split each mode into its coordinate components").
#[derive(Debug, Clone)]
pub struct FlowLine {
    /// Grid of the line.
    pub grid: FlowGrid,
    /// Model DOF row of each grid node (flow order).
    pub dofs: Vec<Option<usize>>,
}

impl FlowLine {
    /// A line whose node `j` is DOF `first + j * stride` (e.g. component `c` of a node-major
    /// layout with `k` DOFs per node: `first = c`, `stride = k`).
    pub fn strided(grid: FlowGrid, first: usize, stride: usize) -> Self {
        let dofs = (0..grid.len()).map(|j| Some(first + j * stride)).collect();
        Self { grid, dofs }
    }

    /// One line per component for nodes with `dofs_per_node` DOFs each, where `node_order[j]` is
    /// the model node index of grid node `j` and the layout is node-major
    /// (`dof = node * dofs_per_node + component`).
    pub fn per_component(
        grid: &FlowGrid, node_order: &[usize], dofs_per_node: usize,
    ) -> Result<Vec<Self>, FlowError> {
        if node_order.len() != grid.len() {
            return Err(invalid(
                "flow line: node order",
                format!(
                    "has {} entries for a grid of {} nodes",
                    node_order.len(),
                    grid.len()
                ),
            ));
        }
        Ok((0..dofs_per_node)
            .map(|c| FlowLine {
                grid: grid.clone(),
                dofs: node_order
                    .iter()
                    .map(|nd| Some(nd * dofs_per_node + c))
                    .collect(),
            })
            .collect())
    }
}

/// Mode-shape derivatives along the flow coordinate: `Ψ_,s` and `Ψ_,ss` (same shape as `Ψ`).
#[derive(Debug, Clone)]
pub struct ModeDerivatives {
    /// First derivative `Ψ_,s` (Ribaric (A.3)/(A.4), with erratum E21: all columns).
    pub d1: Mat<f64>,
    /// Second derivative `Ψ_,ss`.
    pub d2: Mat<f64>,
}

/// Derivatives of the columns of `psi` (`n_dof × m`) along the given flow lines.
///
/// Rows of DOFs not on any line are zero. A DOF on more than one line is an error (the flow
/// derivative of one DOF must be unique).
pub fn mode_shape_derivatives(
    lines: &[FlowLine], method: DerivativeMethod, psi: MatRef<'_, f64>,
) -> Result<ModeDerivatives, FlowError> {
    let n_dof = psi.nrows();
    let m = psi.ncols();
    let mut seen = vec![false; n_dof];
    let mut d1 = Mat::<f64>::zeros(n_dof, m);
    let mut d2 = Mat::<f64>::zeros(n_dof, m);
    for (li, line) in lines.iter().enumerate() {
        if line.dofs.len() != line.grid.len() {
            return Err(invalid(
                format!("flow line {li}"),
                format!(
                    "{} DOF entries for {} grid nodes",
                    line.dofs.len(),
                    line.grid.len()
                ),
            ));
        }
        for (j, d) in line.dofs.iter().enumerate() {
            if let Some(d) = *d {
                if d >= n_dof {
                    return Err(invalid(
                        format!("flow line {li}, node {j}"),
                        format!("DOF {d} is outside the mode-shape matrix ({n_dof} rows)"),
                    ));
                }
                if seen[d] {
                    return Err(invalid(
                        format!("flow line {li}, node {j}"),
                        format!("DOF {d} is on two lines"),
                    ));
                }
                seen[d] = true;
            }
        }
        let op = LineOperator::new(&line.grid, method)?;
        let vals = Mat::from_fn(line.grid.len(), m, |j, c| {
            line.dofs[j].map_or(0.0, |d| psi[(d, c)])
        });
        let (a, b) = op.apply(vals.as_ref());
        for (j, d) in line.dofs.iter().enumerate() {
            if let Some(d) = *d {
                for c in 0..m {
                    d1[(d, c)] = a[(j, c)];
                    d2[(d, c)] = b[(j, c)];
                }
            }
        }
    }
    Ok(ModeDerivatives { d1, d2 })
}
