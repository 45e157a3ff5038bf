//! Finite elements: the [`Element`] extension point and the element library.
//!
//! An element is plain data: its global DOF indices (in element order) and whatever geometry and
//! material it needs. It returns dense element matrices (faer [`Mat`]) in that DOF order; the
//! [`crate::assembly`] module scatters them into sparse global matrices.

use faer::Mat;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

pub mod bar;
pub mod fibre;
pub mod frame2d;
pub mod frame3d;
mod hermite;
pub mod hex8;
pub mod point;
pub mod string;

pub use bar::Bar;
pub use fibre::Fibre;
pub use frame2d::{Frame2d, Frame2dSection};
pub use frame3d::{Frame3d, Frame3dSection};
pub use hex8::{Elastic, Hex8, Hex8Integration};
pub use point::{PointMass, Spring};
pub use string::StringElement;

/// Mass discretisation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum MassKind {
    /// Consistent mass (same shape functions as the stiffness).
    #[default]
    Consistent,
    /// Diagonal (lumped) mass; each element documents its lumping rule.
    Lumped,
}

/// Which global matrix an assembly produces.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MatrixKind {
    /// Elastic stiffness K \[N/m, N/rad, ...\].
    Stiffness,
    /// Mass M \[kg, kg·m², ...\].
    Mass(MassKind),
    /// Geometric (prestress) stiffness K_G from the element's stored stress state.
    Geometric,
}

/// A finite element (the extension point of the crate).
///
/// Implementations return square matrices of size `dofs().len()`, symmetric, in the order of
/// [`Element::dofs`].
pub trait Element: Send + Sync + std::fmt::Debug {
    /// Global DOF indices of the element, in the order of its matrices.
    fn dofs(&self) -> &[usize];

    /// Elastic stiffness matrix.
    fn stiffness(&self) -> Mat<f64>;

    /// Mass matrix of the requested kind.
    fn mass(&self, kind: MassKind) -> Mat<f64>;

    /// Geometric (initial-stress) stiffness from the element's prestress, or `None` when the
    /// element has none (zero matrix).
    fn geometric_stiffness(&self) -> Option<Mat<f64>> {
        None
    }

    /// The element matrix of the given kind (`None` for an absent geometric stiffness).
    fn matrix(&self, kind: MatrixKind) -> Option<Mat<f64>> {
        match kind {
            MatrixKind::Stiffness => Some(self.stiffness()),
            MatrixKind::Mass(m) => Some(self.mass(m)),
            MatrixKind::Geometric => self.geometric_stiffness(),
        }
    }
}

/// A frame element formulated in its local axes: its DOFs, the rotation `T` from global to
/// local DOFs and its local matrices. Every frame element is an [`Element`] whose global
/// matrices are the congruences `Tᵀ A_local T` of its local ones
/// (Przemieniecki, Theory of Matrix Structural Analysis, §6.1).
pub trait FrameElement: Send + Sync + std::fmt::Debug {
    /// Global DOF indices of the element, in the order of its matrices.
    fn dofs(&self) -> &[usize];
    /// Rotation `T` of the element's DOFs (`u_local = T u_global`).
    fn rotation(&self) -> Mat<f64>;
    /// Local elastic stiffness (element axes).
    fn local_stiffness(&self) -> Mat<f64>;
    /// Local mass of the requested kind (element axes).
    fn local_mass(&self, kind: MassKind) -> Mat<f64>;
    /// Local geometric stiffness of the element's axial force (element axes).
    fn local_geometric_stiffness(&self) -> Mat<f64>;
}

impl<F: FrameElement> Element for F {
    fn dofs(&self) -> &[usize] {
        FrameElement::dofs(self)
    }

    fn stiffness(&self) -> Mat<f64> {
        transform(&self.local_stiffness(), &self.rotation())
    }

    fn mass(&self, kind: MassKind) -> Mat<f64> {
        transform(&self.local_mass(kind), &self.rotation())
    }

    fn geometric_stiffness(&self) -> Option<Mat<f64>> {
        Some(transform(
            &self.local_geometric_stiffness(),
            &self.rotation(),
        ))
    }
}

/// Transform a local element matrix to global axes: `Tᵀ k T` (dense, small).
pub(crate) fn transform(k_local: &Mat<f64>, t: &Mat<f64>) -> Mat<f64> {
    t.transpose() * k_local * t
}

/// Build a symmetric matrix from a row-major list (helper for element formulas).
pub(crate) fn from_rows<const N: usize>(rows: [[f64; N]; N]) -> Mat<f64> {
    Mat::from_fn(N, N, |i, j| rows[i][j])
}
