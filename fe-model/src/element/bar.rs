//! Two-node axial bar (truss) element in 1, 2 or 3 dimensions.
//!
//! Linear shape functions along the axis with unit vector `e`:
//! `K = EA/L · [eeᵀ −eeᵀ; −eeᵀ eeᵀ]`; geometric stiffness of an axial force `N` (tension > 0),
//! the linearisation of the rotating force `N e`: `K_G = N/L · [P −P; −P P]` with
//! `P = I − eeᵀ`; consistent mass `ρA L/6 [2I I; I 2I]`, lumped `ρA L/2 I`.

use super::{Element, MassKind};
use crate::FeError;
use faer::Mat;

/// Axial bar element with `dim` translational DOFs per node.
#[derive(Debug, Clone, PartialEq)]
pub struct Bar {
    dofs: Vec<usize>,
    dim: usize,
    /// Unit axis vector (first `dim` entries used).
    axis: [f64; 3],
    /// Length L \[m\].
    pub length: f64,
    /// Axial stiffness EA \[N\].
    pub ea: f64,
    /// Mass per length ρA \[kg/m\].
    pub mass_per_length: f64,
    /// Axial force N \[N\] (tension positive) for the geometric stiffness.
    pub axial_force: f64,
}

impl Bar {
    /// New bar between points `xa` and `xb` (only the first `dofs_a.len()` coordinates are
    /// used, 1 ≤ dim ≤ 3). `dofs_a`/`dofs_b` are the node's translational DOFs.
    pub fn new(
        dofs_a: &[usize], dofs_b: &[usize], xa: [f64; 3], xb: [f64; 3], ea: f64,
        mass_per_length: f64, axial_force: f64,
    ) -> Result<Self, FeError> {
        let dim = dofs_a.len();
        if !(1..=3).contains(&dim) || dofs_b.len() != dim {
            return Err(FeError::Dimension {
                context: "Bar::new DOFs per node (1..=3, equal at both nodes)".into(),
                expected: dim.clamp(1, 3),
                got: dofs_b.len(),
            });
        }
        FeError::check_positive("ea", ea)?;
        FeError::check_non_negative("mass_per_length", mass_per_length)?;
        if !axial_force.is_finite() {
            return Err(FeError::param("axial_force", axial_force, "must be finite"));
        }
        let mut d = [0.0; 3];
        for i in 0..dim {
            d[i] = xb[i] - xa[i];
        }
        let length = d.iter().map(|x| x * x).sum::<f64>().sqrt();
        FeError::check_positive("bar length", length)?;
        let axis = [d[0] / length, d[1] / length, d[2] / length];
        let mut dofs = dofs_a.to_vec();
        dofs.extend_from_slice(dofs_b);
        Ok(Self {
            dofs,
            dim,
            axis,
            length,
            ea,
            mass_per_length,
            axial_force,
        })
    }

    fn two_node(&self, block: impl Fn(usize, usize) -> f64) -> Mat<f64> {
        let d = self.dim;
        Mat::from_fn(2 * d, 2 * d, |i, j| {
            let s = if (i < d) == (j < d) { 1.0 } else { -1.0 };
            s * block(i % d, j % d)
        })
    }
}

impl Element for Bar {
    fn dofs(&self) -> &[usize] {
        &self.dofs
    }

    fn stiffness(&self) -> Mat<f64> {
        let k = self.ea / self.length;
        let e = self.axis;
        self.two_node(|i, j| k * e[i] * e[j])
    }

    fn mass(&self, kind: MassKind) -> Mat<f64> {
        let m = self.mass_per_length * self.length;
        let d = self.dim;
        Mat::from_fn(2 * d, 2 * d, |i, j| match kind {
            MassKind::Consistent => {
                if i == j {
                    m / 3.0
                } else if i % d == j % d {
                    m / 6.0
                } else {
                    0.0
                }
            }
            MassKind::Lumped => {
                if i == j {
                    m / 2.0
                } else {
                    0.0
                }
            }
        })
    }

    fn geometric_stiffness(&self) -> Option<Mat<f64>> {
        let k = self.axial_force / self.length;
        let e = self.axis;
        Some(self.two_node(|i, j| {
            let delta = if i == j { 1.0 } else { 0.0 };
            k * (delta - e[i] * e[j])
        }))
    }
}
