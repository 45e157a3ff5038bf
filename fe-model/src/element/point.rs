//! Point masses and discrete springs.
//!
//! - [`PointMass`]: `M = m I` on the listed DOFs (translations of one node for a particle, or
//!   rotations with `m` = rotary inertia \[kg·m²\]), no stiffness (Lin Appendix A/B nodal masses).
//! - [`Spring`]: scalar spring of stiffness k between two DOFs, `K = k [1 −1; −1 1]`, or to
//!   ground on one DOF, `K = [k]` (ground springs, bearings, contact penalties).

use super::{Element, MassKind};
use crate::FeError;
use faer::Mat;

/// Lumped mass (or rotary inertia) on a set of DOFs.
#[derive(Debug, Clone, PartialEq)]
pub struct PointMass {
    /// DOFs carrying the mass (e.g. u, v, w of one node).
    pub dofs: Vec<usize>,
    /// Mass \[kg\] (or rotary inertia \[kg·m²\] on rotational DOFs).
    pub mass: f64,
}

impl PointMass {
    /// New point mass; `mass ≥ 0`, at least one DOF.
    pub fn new(dofs: Vec<usize>, mass: f64) -> Result<Self, FeError> {
        FeError::check_non_negative("mass", mass)?;
        if dofs.is_empty() {
            return Err(FeError::param(
                "point mass DOFs",
                0.0,
                "need at least one DOF",
            ));
        }
        Ok(Self { dofs, mass })
    }
}

impl Element for PointMass {
    fn dofs(&self) -> &[usize] {
        &self.dofs
    }
    fn stiffness(&self) -> Mat<f64> {
        Mat::zeros(self.dofs.len(), self.dofs.len())
    }
    fn mass(&self, _kind: MassKind) -> Mat<f64> {
        let n = self.dofs.len();
        Mat::from_fn(n, n, |i, j| if i == j { self.mass } else { 0.0 })
    }
}

/// Scalar spring between two DOFs or from one DOF to ground.
#[derive(Debug, Clone, PartialEq)]
pub struct Spring {
    dofs: Vec<usize>,
    /// Stiffness k \[N/m or N·m/rad\].
    pub stiffness: f64,
}

impl Spring {
    /// Spring between DOFs `a` and `b`.
    pub fn between(a: usize, b: usize, stiffness: f64) -> Result<Self, FeError> {
        FeError::check_non_negative("spring stiffness", stiffness)?;
        if a == b {
            return Err(FeError::param(
                "spring DOFs",
                a as f64,
                "the two DOFs must differ",
            ));
        }
        Ok(Self {
            dofs: vec![a, b],
            stiffness,
        })
    }

    /// Spring from DOF `a` to ground.
    pub fn grounded(a: usize, stiffness: f64) -> Result<Self, FeError> {
        FeError::check_non_negative("spring stiffness", stiffness)?;
        Ok(Self {
            dofs: vec![a],
            stiffness,
        })
    }
}

impl Element for Spring {
    fn dofs(&self) -> &[usize] {
        &self.dofs
    }
    fn stiffness(&self) -> Mat<f64> {
        let k = self.stiffness;
        if self.dofs.len() == 1 {
            Mat::from_fn(1, 1, |_, _| k)
        } else {
            Mat::from_fn(2, 2, |i, j| if i == j { k } else { -k })
        }
    }
    fn mass(&self, _kind: MassKind) -> Mat<f64> {
        Mat::zeros(self.dofs.len(), self.dofs.len())
    }
}
