//! Finite-difference mode-shape derivatives on non-uniform grids (Ribaric App. A.2).

use super::stencil::fd_weights;
use crate::error::FlowError;
use crate::grid::{FlowGrid, Node};
use faer::sparse::{SparseColMat, Triplet};

/// First-derivative stencil.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
pub enum FirstDifference {
    /// Ribaric (A.1)/(A.2): `(φ_{j+1} − φ_{j−1}) / (h_j + h_{j+1})`. Second order on uniform
    /// grids, first order on non-uniform ones. Equal to the Galerkin operator `M₁⁻¹G₁` with
    /// lumped mass (see [`super::consistent`]).
    Central,
    /// Weighted 3-point formula through the node and its two neighbours, second order on any
    /// grid (Fornberg weights).
    ThreePoint,
}

/// Second-derivative stencil.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
pub enum SecondDifference {
    /// The 3-point second difference `2[h_j φ_{j+1} − (h_j+h_{j+1}) φ_j + h_{j+1} φ_{j−1}] / (h_j h_{j+1} (h_j+h_{j+1}))`,
    /// equal to `−M₁⁻¹K₁` for linear string elements with lumped mass (FE-consistent).
    ThreePoint,
    /// The first-derivative stencil applied twice: Ribaric App. A.2's recipe ("apply the same
    /// finite-difference operator to Ψ_,x"). A 5-point, 2h-wide stencil that biases the
    /// moving-string frequencies (notes §2.1); kept for comparison.
    RepeatedFirst,
}

/// A finite-difference scheme (first and second derivative stencils).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields)]
pub struct FdScheme {
    /// First-derivative stencil.
    pub first: FirstDifference,
    /// Second-derivative stencil.
    pub second: SecondDifference,
}

impl Default for FdScheme {
    /// Ribaric (A.1) for the first derivative, the FE-consistent 3-point second difference.
    fn default() -> Self {
        Self {
            first: FirstDifference::Central,
            second: SecondDifference::ThreePoint,
        }
    }
}

/// A sparse derivative matrix.
pub type SparseOp = SparseColMat<usize, f64>;

/// Sparse `n × n` matrices `(D₁, D₂)` of a finite-difference scheme on `grid`.
///
/// Interior nodes use their two neighbours (a zero-value end acts as a neighbour whose value is
/// known to be zero, Ribaric (A.2) with erratum E20: node spacings, not mode indices); nodes at a
/// free end use the one-sided 3-point stencil (exact for quadratics).
pub fn fd_matrices(grid: &FlowGrid, scheme: FdScheme) -> Result<(SparseOp, SparseOp), FlowError> {
    crate::grid::require_nodes(grid, 3, "finite-difference derivative")?;
    let n = grid.len();
    let mut t1 = Vec::with_capacity(3 * n);
    let mut t2 = Vec::with_capacity(3 * n);
    for j in 0..n {
        let nb = grid.neighbours(j);
        // Stencil points: (column or None for a known zero, position).
        let pts: Vec<(Option<usize>, f64)> = match (nb.left, nb.right) {
            (Node::None, Node::None) => unreachable_stencil(j)?,
            (Node::None, _) => one_sided(grid, j, true),
            (_, Node::None) => one_sided(grid, j, false),
            (l, r) => vec![to_pt(l), (Some(j), nb.s), to_pt(r)],
        };
        let xs: Vec<f64> = pts.iter().map(|p| p.1).collect();
        let w = fd_weights(nb.s, &xs, 2);
        let interior = matches!(
            (nb.left, nb.right),
            (
                Node::Value(..) | Node::Zero(_),
                Node::Value(..) | Node::Zero(_)
            )
        );
        // First derivative.
        if interior && scheme.first == FirstDifference::Central {
            let (l, r) = (pts[0], pts[2]);
            let d = r.1 - l.1;
            if let Some(c) = r.0 {
                t1.push(Triplet::new(j, c, 1.0 / d));
            }
            if let Some(c) = l.0 {
                t1.push(Triplet::new(j, c, -1.0 / d));
            }
        } else {
            for (p, wk) in pts.iter().zip(&w[1]) {
                if let Some(c) = p.0 {
                    t1.push(Triplet::new(j, c, *wk));
                }
            }
        }
        for (p, wk) in pts.iter().zip(&w[2]) {
            if let Some(c) = p.0 {
                t2.push(Triplet::new(j, c, *wk));
            }
        }
    }
    let d1 =
        SparseColMat::try_new_from_triplets(n, n, &t1).map_err(|e| FlowError::LinearAlgebra {
            what: "finite-difference first-derivative matrix".into(),
            reason: format!("{e:?}"),
        })?;
    let d2 = match scheme.second {
        SecondDifference::ThreePoint => {
            SparseColMat::try_new_from_triplets(n, n, &t2).map_err(|e| {
                FlowError::LinearAlgebra {
                    what: "finite-difference second-derivative matrix".into(),
                    reason: format!("{e:?}"),
                }
            })?
        }
        SecondDifference::RepeatedFirst => {
            let dense = d1.to_dense();
            let prod = &dense * &dense;
            let mut t = Vec::new();
            for c in 0..n {
                for r in 0..n {
                    let v = prod[(r, c)];
                    if v != 0.0 {
                        t.push(Triplet::new(r, c, v));
                    }
                }
            }
            SparseColMat::try_new_from_triplets(n, n, &t).map_err(|e| FlowError::LinearAlgebra {
                what: "repeated first-derivative matrix".into(),
                reason: format!("{e:?}"),
            })?
        }
    };
    Ok((d1, d2))
}

fn to_pt(n: Node) -> (Option<usize>, f64) {
    match n {
        Node::Value(i, s) => (Some(i), s),
        Node::Zero(s) => (None, s),
        Node::None => (None, f64::NAN),
    }
}

fn one_sided(grid: &FlowGrid, j: usize, forward: bool) -> Vec<(Option<usize>, f64)> {
    let p = grid.positions();
    if forward {
        (j..j + 3).map(|i| (Some(i), p[i])).collect()
    } else {
        (j - 2..=j).map(|i| (Some(i), p[i])).collect()
    }
}

fn unreachable_stencil(j: usize) -> Result<Vec<(Option<usize>, f64)>, FlowError> {
    Err(crate::error::invalid(
        format!("flow grid: node {j}"),
        "has no neighbour on either side",
    ))
}
