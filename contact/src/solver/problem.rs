//! The caller's side of a contact problem: the Delassus (compliance) operator and the free
//! values, supplied lazily.

/// The caller's lazy source of the local Delassus columns and of the free tangential
/// velocities.
pub trait DelassusSource {
    /// Fill the three columns of contact `l` (`λ_l`, `f1_l`, `f2_l`): `cols` is `3 × 3m`
    /// (column-major, leading dimension 3m), rows `(g_k, u1_k, u2_k)` of every contact `k`.
    fn columns(&mut self, l: usize, cols: &mut [f64]);
    /// The free tangential slip velocity `(u1_k, u2_k)` \[m/s\] of contact `k`.
    fn free_slip(&mut self, k: usize) -> [f64; 2];
}

/// A local problem given as a full matrix `D` (column-major, 3m × 3m) and a full `b`.
#[derive(Debug, Clone)]
pub struct DenseProblem<'a> {
    /// Local Delassus matrix, column-major with leading dimension 3m.
    pub d: &'a [f64],
    /// Free values `b` (3m).
    pub b: &'a [f64],
}

impl DelassusSource for DenseProblem<'_> {
    fn columns(&mut self, l: usize, cols: &mut [f64]) {
        let ld = self.b.len();
        cols.copy_from_slice(&self.d[3 * l * ld..(3 * l + 3) * ld]);
    }
    fn free_slip(&mut self, k: usize) -> [f64; 2] {
        [self.b[3 * k + 1], self.b[3 * k + 2]]
    }
}

impl DenseProblem<'_> {
    /// The diagonal compliances `[D_N,kk, (D_T,kk,11 + D_T,kk,22)/2]` of each contact, the
    /// `diag` argument of [`ContactSolver::solve`](super::ContactSolver::solve).
    pub fn diagonal(&self) -> Vec<[f64; 2]> {
        let n = self.b.len();
        (0..n / 3)
            .map(|k| {
                let d = |i: usize| self.d[i * n + i];
                [d(3 * k), 0.5 * (d(3 * k + 1) + d(3 * k + 2))]
            })
            .collect()
    }
}
