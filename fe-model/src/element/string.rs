//! Taut string element: one transverse DOF per node (Ribaric 4.1).
//!
//! A two-node element of length `h` under constant tension `T0` with mass per length `ρA`:
//! `K_e = T0/h [1 −1; −1 1]`, consistent `M_e = ρA h/6 [2 1; 1 2]`, lumped `M_e = ρA h/2 I`.
//! The tension stiffness *is* a geometric stiffness, but for the string it is the only stiffness,
//! so it is returned by [`Element::stiffness`] (and [`Element::geometric_stiffness`] is `None`).

use super::{Element, MassKind, from_rows};
use crate::FeError;
use faer::Mat;

/// Two-node string element (Ribaric (4.1)).
#[derive(Debug, Clone, PartialEq)]
pub struct StringElement {
    /// Global DOFs (transverse deflection of node a, node b).
    pub dofs: [usize; 2],
    /// Element length h \[m\].
    pub length: f64,
    /// Tension T0 \[N\].
    pub tension: f64,
    /// Mass per unit length ρA \[kg/m\].
    pub mass_per_length: f64,
}

impl StringElement {
    /// New string element; checks that length, tension and mass are positive.
    pub fn new(
        dofs: [usize; 2], length: f64, tension: f64, mass_per_length: f64,
    ) -> Result<Self, FeError> {
        FeError::check_positive("length", length)?;
        FeError::check_non_negative("tension", tension)?;
        FeError::check_non_negative("mass_per_length", mass_per_length)?;
        Ok(Self {
            dofs,
            length,
            tension,
            mass_per_length,
        })
    }
}

impl Element for StringElement {
    fn dofs(&self) -> &[usize] {
        &self.dofs
    }

    fn stiffness(&self) -> Mat<f64> {
        let k = self.tension / self.length;
        from_rows([[k, -k], [-k, k]])
    }

    fn mass(&self, kind: MassKind) -> Mat<f64> {
        let m = self.mass_per_length * self.length;
        match kind {
            MassKind::Consistent => from_rows([[m / 3.0, m / 6.0], [m / 6.0, m / 3.0]]),
            MassKind::Lumped => from_rows([[m / 2.0, 0.0], [0.0, m / 2.0]]),
        }
    }
}

/// The uniform string matrices of Ribaric (4.1), free–free, including the two end nodes.
///
/// `n` interior nodes, `n + 2` nodes in all, element length `h = L/(n+1)`:
/// `M = ρ0A0 h I` (the same mass on *every* node, end nodes included, exactly as printed) and
/// `K = T0/h · tridiag(−1, 2, −1)` with corner entries 1. Ribaric's notation is kept; see
/// seed note U3 (the end-node masses are irrelevant for fixed ends, where only the interior
/// `n × n` block is used). Returns `(M, K)` of size `(n+2) × (n+2)`, units kg and N/m.
pub fn ribaric_string_matrices(
    n_interior: usize, length: f64, tension: f64, mass_per_length: f64,
) -> Result<(Mat<f64>, Mat<f64>), FeError> {
    FeError::check_positive("length", length)?;
    FeError::check_non_negative("tension", tension)?;
    FeError::check_non_negative("mass_per_length", mass_per_length)?;
    let n = n_interior + 2;
    let h = length / (n_interior as f64 + 1.0);
    let m = Mat::from_fn(n, n, |i, j| if i == j { mass_per_length * h } else { 0.0 });
    let kt = tension / h;
    let k = Mat::from_fn(n, n, |i, j| {
        if i == j {
            if i == 0 || i == n - 1 { kt } else { 2.0 * kt }
        } else if i.abs_diff(j) == 1 {
            -kt
        } else {
            0.0
        }
    });
    Ok((m, k))
}
