//! Derivative operators consistent with a linear finite-element discretisation of the flow line.
//!
//! With linear 2-node elements along the flow coordinate, the Galerkin projection of `∂/∂s` and
//! `∂²/∂s²` gives `M₁ D₁ = G₁` and `M₁ D₂ = −K₁` with the unit-density mass `M₁ = ∫NᵀN ds`
//! (lumped or consistent), the convection matrix `G₁ = ∫Nᵀ N' ds` (skew-symmetric with fixed or
//! periodic ends) and the unit-tension stiffness `K₁ = ∫N'ᵀN' ds`.
//!
//! Why it matters (notes on Ribaric §2.1, "pitfall"): in the flowing-material string (4.20) the
//! gyroscopic matrix `2ẋ ΨᵀMΨ_,x = 2ẋ μ ΨᵀG₁Ψ` is then exactly skew and the centrifugal matrix
//! `ẋ² ΨᵀMΨ_,xx = −(ẋ²/c²) Λ` exactly, so the discrete model keeps the energy-like invariant of the
//! continuous one and cannot become falsely unstable below the critical speed, whatever the number
//! of retained modes. With lumped mass `D₁` is Ribaric (A.1) and `D₂` the 3-point second difference.

use crate::error::FlowError;
use crate::grid::{End, FlowGrid, Topology};
use faer::Mat;
use faer::linalg::solvers::Solve;

/// Mass matrix used in the consistent operator.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
pub enum MassKind {
    /// Row-sum lumped mass (the string of Ribaric (4.1)).
    Lumped,
    /// Consistent linear-element mass `h/6 [2 1; 1 2]`.
    Consistent,
}

/// One linear element: its two node columns (`None` = a zero-value end) and its length.
struct Element {
    a: Option<usize>,
    b: Option<usize>,
    h: f64,
}

fn elements(grid: &FlowGrid) -> Vec<Element> {
    let p = grid.positions();
    let n = p.len();
    let mut e = Vec::with_capacity(n + 1);
    match grid.topology() {
        Topology::Open { start, end } => {
            if let End::Zero(a) = start {
                e.push(Element {
                    a: None,
                    b: Some(0),
                    h: p[0] - a,
                });
            }
            for j in 0..n - 1 {
                e.push(Element {
                    a: Some(j),
                    b: Some(j + 1),
                    h: p[j + 1] - p[j],
                });
            }
            if let End::Zero(b) = end {
                e.push(Element {
                    a: Some(n - 1),
                    b: None,
                    h: b - p[n - 1],
                });
            }
        }
        Topology::Closed { period } => {
            for j in 0..n - 1 {
                e.push(Element {
                    a: Some(j),
                    b: Some(j + 1),
                    h: p[j + 1] - p[j],
                });
            }
            e.push(Element {
                a: Some(n - 1),
                b: Some(0),
                h: p[0] + period - p[n - 1],
            });
        }
    }
    e
}

/// Unit-density mass `M₁`, convection `G₁ = ∫NᵀN' ds` and unit-tension stiffness `K₁` of linear
/// elements on `grid` (dense, `n × n`; zero-value ends eliminated as Dirichlet conditions,
/// free ends natural).
pub fn line_fe_matrices(grid: &FlowGrid, mass: MassKind) -> (Mat<f64>, Mat<f64>, Mat<f64>) {
    let n = grid.len();
    let mut m = Mat::<f64>::zeros(n, n);
    let mut g = Mat::<f64>::zeros(n, n);
    let mut k = Mat::<f64>::zeros(n, n);
    for el in elements(grid) {
        let idx = [el.a, el.b];
        let me = match mass {
            MassKind::Lumped => [[el.h / 2.0, 0.0], [0.0, el.h / 2.0]],
            MassKind::Consistent => [[el.h / 3.0, el.h / 6.0], [el.h / 6.0, el.h / 3.0]],
        };
        // ∫ N_a N_b' ds for linear shape functions: N_b' = ±1/h, ∫N_a = h/2.
        let ge = [[-0.5, 0.5], [-0.5, 0.5]];
        let ke = [[1.0 / el.h, -1.0 / el.h], [-1.0 / el.h, 1.0 / el.h]];
        for (r, ir) in idx.iter().enumerate() {
            let Some(ir) = ir else { continue };
            for (c, ic) in idx.iter().enumerate() {
                let Some(ic) = ic else { continue };
                m[(*ir, *ic)] += me[r][c];
                g[(*ir, *ic)] += ge[r][c];
                k[(*ir, *ic)] += ke[r][c];
            }
        }
    }
    (m, g, k)
}

/// Dense `(D₁, D₂) = (M₁⁻¹G₁, −M₁⁻¹K₁)` on `grid`.
pub fn consistent_matrices(
    grid: &FlowGrid, mass: MassKind,
) -> Result<(Mat<f64>, Mat<f64>), FlowError> {
    crate::grid::require_nodes(grid, 2, "FE-consistent derivative")?;
    let (m, g, k) = line_fe_matrices(grid, mass);
    match mass {
        MassKind::Lumped => {
            let n = grid.len();
            let d1 = Mat::from_fn(n, n, |i, j| g[(i, j)] / m[(i, i)]);
            let d2 = Mat::from_fn(n, n, |i, j| -k[(i, j)] / m[(i, i)]);
            Ok((d1, d2))
        }
        MassKind::Consistent => {
            let llt = m
                .llt(faer::Side::Lower)
                .map_err(|e| FlowError::LinearAlgebra {
                    what: "consistent line mass".into(),
                    reason: format!("{e:?}"),
                })?;
            let d1 = llt.solve(&g);
            let d2 = -llt.solve(&k);
            Ok((d1, d2))
        }
    }
}
