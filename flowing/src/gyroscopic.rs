//! Linear gyroscopic second-order systems `M q̈ + G q̇ + K q = f(t)`: state matrix, eigenvalues,
//! damped frequencies and the matrix-exponential response (Ribaric (4.27), (4.29), (4.30)).

use crate::error::{FlowError, invalid};
use faer::linalg::solvers::Solve;
use faer::{Mat, c64};
use mbd_core::Workspace;
use mbd_core::{MbdError, SecondOrderSystem, SysMatrix};

/// `M q̈ + G q̇ + K q = 0` with constant dense matrices (`M` symmetric positive definite).
#[derive(Debug, Clone)]
pub struct GyroscopicSystem {
    /// Mass matrix `M`.
    pub mass: Mat<f64>,
    /// Velocity-proportional matrix `G` (skew for a conservative gyroscopic system).
    pub gyro: Mat<f64>,
    /// Stiffness `K` (including centrifugal softening).
    pub stiffness: Mat<f64>,
}

/// Eigen decomposition `X L = L T` of the state matrix (Ribaric (4.30)).
#[derive(Debug, Clone)]
pub struct StateEigen {
    /// Eigenvalues `T` \[1/s\].
    pub values: Vec<c64>,
    /// Right eigenvectors `L` (columns).
    pub vectors: Mat<c64>,
}

impl GyroscopicSystem {
    /// Checks dimensions.
    pub fn new(mass: Mat<f64>, gyro: Mat<f64>, stiffness: Mat<f64>) -> Result<Self, FlowError> {
        let n = mass.nrows();
        for (name, m) in [
            ("mass", &mass),
            ("gyroscopic", &gyro),
            ("stiffness", &stiffness),
        ] {
            if m.nrows() != n || m.ncols() != n {
                return Err(invalid(
                    format!("gyroscopic system: {name} matrix"),
                    format!("is {}×{}, expected {n}×{n}", m.nrows(), m.ncols()),
                ));
            }
        }
        Ok(Self {
            mass,
            gyro,
            stiffness,
        })
    }

    /// Number of coordinates.
    pub fn dim(&self) -> usize {
        self.mass.nrows()
    }

    /// State matrix `X = [0 I; −M⁻¹K −M⁻¹G]` for `q = [x; ẋ]` (Ribaric (4.29)).
    pub fn state_matrix(&self) -> Result<Mat<f64>, FlowError> {
        let n = self.dim();
        let llt = self
            .mass
            .llt(faer::Side::Lower)
            .map_err(|e| FlowError::LinearAlgebra {
                what: "gyroscopic system: mass matrix".into(),
                reason: format!("not positive definite ({e:?})"),
            })?;
        let mk = llt.solve(&self.stiffness);
        let mg = llt.solve(&self.gyro);
        Ok(Mat::from_fn(2 * n, 2 * n, |i, j| match (i < n, j < n) {
            (true, true) => 0.0,
            (true, false) => f64::from(i == j - n),
            (false, true) => -mk[(i - n, j)],
            (false, false) => -mg[(i - n, j - n)],
        }))
    }

    /// Eigen decomposition of the state matrix (faer non-symmetric `eigen`).
    pub fn state_eigen(&self) -> Result<StateEigen, FlowError> {
        let x = self.state_matrix()?;
        let evd = x.eigen().map_err(|e| FlowError::LinearAlgebra {
            what: "state-matrix eigen decomposition".into(),
            reason: format!("{e:?}"),
        })?;
        let values = (0..x.nrows()).map(|i| evd.S()[i]).collect();
        Ok(StateEigen {
            values,
            vectors: evd.U().to_owned(),
        })
    }

    /// Matrix-exponential response `q(t) = L e^{T t} L⁻¹ q(0)` (Ribaric (4.30), erratum E14:
    /// the left side is `q(t)`), at each time of `times` \[s\]; rows are times, columns the state.
    pub fn response(&self, q0: &[f64], times: &[f64]) -> Result<Vec<Vec<f64>>, FlowError> {
        let n2 = 2 * self.dim();
        if q0.len() != n2 {
            return Err(invalid(
                "initial state",
                format!("has {} entries, expected {n2}", q0.len()),
            ));
        }
        let eig = self.state_eigen()?;
        let lu = eig.vectors.partial_piv_lu();
        let rhs = Mat::from_fn(n2, 1, |i, _| c64::new(q0[i], 0.0));
        let y = lu.solve(&rhs);
        let cond_check = &eig.vectors * &y - &rhs;
        let mut resid: f64 = 0.0;
        for i in 0..n2 {
            resid = resid.max(cond_check[(i, 0)].norm());
        }
        let scale = q0
            .iter()
            .fold(0.0f64, |a, b| a.max(b.abs()))
            .max(f64::MIN_POSITIVE);
        if resid > 1e-6 * scale {
            return Err(FlowError::LinearAlgebra {
                what: "matrix-exponential response".into(),
                reason: format!("the state matrix is defective (eigenvector residual {resid:e})"),
            });
        }
        Ok(times
            .iter()
            .map(|&t| {
                let z = Mat::from_fn(n2, 1, |i, _| (eig.values[i] * t).exp() * y[(i, 0)]);
                let q = &eig.vectors * &z;
                (0..n2).map(|i| q[(i, 0)].re).collect()
            })
            .collect())
    }
}

impl StateEigen {
    /// Damped natural frequencies `Im(λ)/2π` \[Hz\] of the eigenvalues with positive imaginary
    /// part, ascending.
    pub fn damped_frequencies_hz(&self) -> Vec<f64> {
        let scale = self.values.iter().fold(0.0f64, |a, z| a.max(z.norm()));
        let mut f: Vec<f64> = self
            .values
            .iter()
            .filter(|z| z.im > 1e-9 * scale)
            .map(|z| z.im / (2.0 * std::f64::consts::PI))
            .collect();
        f.sort_by(f64::total_cmp);
        f
    }

    /// Real parts below this are round-off \[1/s\]: `10⁻⁷ max |λ|` (the eigenvalues of an
    /// undamped gyroscopic system lie on the imaginary axis while it is stable).
    pub fn stability_tolerance(&self) -> f64 {
        1e-7 * self.values.iter().fold(0.0f64, |a, z| a.max(z.norm()))
    }

    /// The eigenvalues with positive real part (beyond [`Self::stability_tolerance`]), one per
    /// complex-conjugate pair: `(growth rate Re λ \[1/s\], frequency Im λ/2π \[Hz\] ≥ 0)`, the
    /// fastest growth first. Empty while the system is stable.
    pub fn growth_rates(&self) -> Vec<(f64, f64)> {
        let tol = self.stability_tolerance();
        let mut g: Vec<(f64, f64)> = self
            .values
            .iter()
            .filter(|z| z.re > tol && z.im >= -tol)
            .map(|z| (z.re, z.im.max(0.0) / (2.0 * std::f64::consts::PI)))
            .collect();
        g.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.total_cmp(&b.1)));
        g
    }

    /// Frequencies `Im λ/2π` \[Hz\] of the oscillating eigenvalues that neither grow nor decay
    /// (`|Re λ|` within [`Self::stability_tolerance`]), ascending: the natural frequencies of a
    /// stable undamped system, and what is left of them in an unstable one (whose growing
    /// and decaying flutter pairs are not natural frequencies).
    pub fn neutral_frequencies_hz(&self) -> Vec<f64> {
        let tol = self.stability_tolerance();
        let scale = self.values.iter().fold(0.0f64, |a, z| a.max(z.norm()));
        let mut f: Vec<f64> = self
            .values
            .iter()
            .filter(|z| z.im > 1e-9 * scale && z.re.abs() <= tol)
            .map(|z| z.im / (2.0 * std::f64::consts::PI))
            .collect();
        f.sort_by(f64::total_cmp);
        f
    }

    /// Largest real part of the eigenvalues \[1/s\] (> 0: unstable).
    pub fn max_real_part(&self) -> f64 {
        self.values
            .iter()
            .fold(f64::NEG_INFINITY, |a, z| a.max(z.re))
    }
}

/// The gyroscopic system integrated by mbd-core: `M q̈ = −G q̇ − K q`.
impl SecondOrderSystem for GyroscopicSystem {
    fn n_q(&self) -> usize {
        self.dim()
    }

    fn mass_is_constant(&self) -> bool {
        true
    }

    fn mass(&self, _t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        Ok(SysMatrix::Dense(self.mass.clone()))
    }

    fn forces(
        &self, _t: f64, q: &[f64], v: &[f64], f: &mut [f64], _ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        let n = self.dim();
        for i in 0..n {
            let mut s = 0.0;
            for j in 0..n {
                s -= self.gyro[(i, j)] * v[j] + self.stiffness[(i, j)] * q[j];
            }
            f[i] = s;
        }
        Ok(())
    }
}
