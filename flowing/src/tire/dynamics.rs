//! The smooth equations of motion of the rolling reduced tire (Ribaric (7.10)/(7.17) with the
//! seed notes' corrections U15–U17) as a [`SecondOrderSystem`], stepped by mbd-core's
//! generalized-α [`AlphaStepper`](mbd_core::integrators::AlphaStepper); the contact is its
//! step correction ([`super::contact_step`]).
//!
//! Coordinates `q = [θ; z]` (wheel spin angle \[rad\] and the reduced coordinates), velocities
//! `v = [θ̇; ż]`. With the spin-dependent matrices frozen at `θ̇_R` (re-formed by
//! [`TireDynamics::set_spin`] when θ̇ drifts by more than `spin_tolerance`):
//!
//! ```text
//!   J θ̈ + β k_θᵀ ż + (k_θ + β θ̇_R k_θ,θ)ᵀ z = τ                         (rim moment, row 2 of (7.10))
//!   m_θ θ̈ + M z̈ + C_eff ż + K_eff z + G₁ w + θ̇² c_s = 0                 (rows 3–4 of (7.17))
//!   C_eff = 2θ̇_R G₁ + αM + βK,   K_eff = K + θ̇_R² G₂ + βθ̇_R K₁
//! ```
//!
//! The coupling `G₁ z θ̈` enters lagged by one step, `w = θ̈ₙ zₙ + 2γ'h(θ̇_R − θ̇_S) z̈ₙ`
//! ([`TireDynamics::set_lagged`]), together with the gyroscopic part of the difference
//! `S(θ̇_R) − S(θ̇_S)` between the iteration matrix at the spin rate of the force matrices and
//! the frozen one at θ̇_S (set by [`super::RollingTire::step`]). The mass matrix is the
//! constant `[J 0; m_θ M]`, the forces `f = [τ − …; −θ̇² c_s − C_eff ż − K_eff z − G₁ w]`; the
//! residual `M v̇ − f` is one pass over the stacked matrix `Q = [C_eff K_eff G₁ M]` (stored
//! transposed, so that the products run over contiguous rows)
//! ([`SecondOrderSystem::dynamic_residual`]; the `M` block is skipped when `z̈ = 0`, the
//! predictor of the linearly implicit step).

use super::reduced::ReducedTire;
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatMut, MatRef, Par};
use mbd_core::Workspace;
use mbd_core::{ForceTangent, MbdError, SecondOrderSystem, SysMatrix};

/// The rolling tire's smooth dynamics (module documentation).
pub struct TireDynamics<'a> {
    red: &'a ReducedTire,
    /// Rayleigh α \[1/s\].
    alpha: f64,
    /// Rayleigh β \[s\].
    beta: f64,
    /// Spin inertia of wheel and rim `J` \[kg·m²\].
    spin_inertia: f64,
    /// Drive torque about the wheel axis \[N·m\].
    pub drive_torque: f64,
    /// Spin rate θ̇_R of the spin-dependent matrices \[rad/s\].
    spin: f64,
    /// The lagged argument `w` of the coupling `G₁ w` (n_z).
    lagged: Vec<f64>,
    /// `Qᵀ` (3 n_z × n): column 0 the spin row `[β k_θ; k_θ + β θ̇_R k_θ,θ; 0]`, column
    /// `1 + i` row `i` of `[C_eff K_eff G₁]`.
    qt: Mat<f64>,
    /// `[0 M]ᵀ` (n_z × n), the mass block of `Q`.
    mt: Mat<f64>,
    /// `G₁ᵀ`, `Mᵀ`, `Kᵀ`, `G₂ᵀ`, `K₁ᵀ` (n_z × n_z each): column `i` is row `i` of the reduced
    /// tire's matrix, so that [`TireDynamics::set_spin`] forms the rows of `C_eff` and `K_eff`
    /// from contiguous columns (re-formed many times a run when θ̇ oscillates after the cleat;
    /// the strided row reads of the column-major matrices made it the third largest cost of a
    /// run at h = 0.05 ms).
    rows: [Mat<f64>; 5],
}

impl<'a> TireDynamics<'a> {
    /// The tire with Rayleigh coefficients `alpha` \[1/s\], `beta` \[s\], the wheel's spin
    /// inertia `wheel_spin_inertia` \[kg·m²\] (the rim's is added) and the spin-dependent
    /// matrices formed at `spin` \[rad/s\].
    pub fn new(
        red: &'a ReducedTire,
        alpha: f64,
        beta: f64,
        wheel_spin_inertia: f64,
        spin: f64,
    ) -> Self {
        let nz = red.n_z();
        let mut d = Self {
            red,
            alpha,
            beta,
            spin_inertia: wheel_spin_inertia + red.rim_spin_inertia,
            drive_torque: 0.0,
            spin,
            lagged: vec![0.0; nz],
            qt: Mat::zeros(3 * nz, nz + 1),
            mt: Mat::from_fn(
                nz,
                nz + 1,
                |j, i| if i == 0 { 0.0 } else { red.m[(i - 1, j)] },
            ),
            rows: [&red.g1, &red.m, &red.k, &red.g2, &red.k1].map(|a| a.transpose().to_owned()),
        };
        let qt = &mut d.qt;
        for i in 0..nz {
            let mut col = qt.col_mut(1 + i);
            for j in 0..nz {
                col[2 * nz + j] = red.g1[(i, j)];
            }
        }
        d.set_spin(spin);
        d
    }

    /// The reduced tire.
    pub fn reduced(&self) -> &'a ReducedTire {
        self.red
    }

    /// Spin rate θ̇_R at which the spin-dependent matrices were formed \[rad/s\].
    pub fn spin(&self) -> f64 {
        self.spin
    }

    /// Re-forms the spin-dependent blocks at `spin` \[rad/s\]: the spin row
    /// `β k_θ ż + (k_θ + β θ̇ k_θ,θ) z` and `C_eff = 2θ̇G₁ + αM + βK`,
    /// `K_eff = K + θ̇²G₂ + βθ̇K₁` (Ribaric (7.17) with U15–U17).
    pub fn set_spin(&mut self, spin: f64) {
        let red = self.red;
        let nz = red.n_z();
        let (a, b) = (self.alpha, self.beta);
        self.spin = spin;
        let kt = red.kt.row(1);
        let kt1 = red.kt1.row(1);
        for j in 0..nz {
            self.qt[(j, 0)] = b * kt[j];
            self.qt[(nz + j, 0)] = kt[j] + b * spin * kt1[j];
        }
        // column i of Qᵀ = row i of Q = column i of the transposed matrices (contiguous reads
        // and writes)
        let [g1, m, k, g2, k1] = &self.rows;
        for i in 0..nz {
            let mut col = self.qt.col_mut(1 + i);
            let (g1, m, k, g2, k1) = (g1.col(i), m.col(i), k.col(i), g2.col(i), k1.col(i));
            for j in 0..nz {
                col[j] = 2.0 * spin * g1[j] + a * m[j] + b * k[j];
                col[nz + j] = k[j] + spin * spin * g2[j] + b * spin * k1[j];
            }
        }
    }

    /// Sets the lagged argument `w = θ̈ₙ zₙ + 2γ'h(θ̇_R − θ̇_S) z̈ₙ` of the coupling `G₁ w`
    /// (module documentation) from the last step's `θ̈ₙ` \[rad/s²\], `zₙ`, `z̈ₙ` and the
    /// coefficient `lag = 2γ'h(θ̇_R − θ̇_S)`.
    pub fn set_lagged(&mut self, theta_dd: f64, z: &[f64], zdd: &[f64], lag: f64) {
        for ((w, zj), aj) in self.lagged.iter_mut().zip(z).zip(zdd) {
            *w = theta_dd * zj + lag * aj;
        }
    }

    /// The spin-row coefficients `[β K_θ; K_θ + β θ̇ K_θ,θ]` (for diagnostics).
    pub fn spin_row(&self) -> Vec<f64> {
        (0..2 * self.red.n_z()).map(|j| self.qt[(j, 0)]).collect()
    }

    /// `out (+)= s · Q_k x` for block `k` of `Q` (0: C_eff, 1: K_eff, 2: G₁, 3: M).
    fn block(&self, k: usize, s: f64, x: &[f64], out: &mut [f64], accum: Accum) {
        let nz = self.red.n_z();
        let a = if k == 3 {
            self.mt.as_ref().transpose()
        } else {
            self.qt.as_ref().subrows(k * nz, nz).transpose()
        };
        let xv = MatRef::from_column_major_slice(x, nz, 1);
        let ov = MatMut::from_column_major_slice_mut(out, nz + 1, 1);
        matmul(ov, accum, a, xv, s, Par::Seq);
    }
}

impl SecondOrderSystem for TireDynamics<'_> {
    fn n_q(&self) -> usize {
        self.red.n_z() + 1
    }

    fn dof_name(&self, dof: usize) -> String {
        if dof == 0 {
            "wheel spin".into()
        } else {
            format!("reduced coordinate z[{}]", dof - 1)
        }
    }

    fn mass_is_constant(&self) -> bool {
        true
    }

    /// `M = [J 0; m_θ M]`.
    fn mass(&self, _t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        let red = self.red;
        let nz = red.n_z();
        let mut m = Mat::<f64>::zeros(nz + 1, nz + 1);
        m[(0, 0)] = self.spin_inertia;
        for i in 0..nz {
            for j in 0..nz {
                m[(1 + i, 1 + j)] = red.m[(i, j)];
            }
            m[(1 + i, 0)] = red.m_theta[i];
        }
        Ok(SysMatrix::Dense(m))
    }

    /// `f = [τ − β k_θᵀ ż − (k_θ + β θ̇_R k_θ,θ)ᵀ z; −θ̇² c_s − C_eff ż − K_eff z − G₁ w]`.
    fn forces(
        &self,
        _t: f64,
        q: &[f64],
        v: &[f64],
        f: &mut [f64],
        _ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        self.block(0, -1.0, &v[1..], f, Accum::Replace);
        self.block(1, -1.0, &q[1..], f, Accum::Add);
        self.block(2, -1.0, &self.lagged, f, Accum::Add);
        f[0] += self.drive_torque;
        let w2 = v[0] * v[0];
        for (fi, c) in f[1..].iter_mut().zip(&self.red.c_s) {
            *fi -= w2 * c;
        }
        Ok(())
    }

    /// `M(q) v̇ − f` in one pass over `Q` (module documentation).
    fn dynamic_residual(
        &self,
        _t: f64,
        q: &[f64],
        v: &[f64],
        vdot: &[f64],
        r: &mut [f64],
        _ws: &mut Workspace,
    ) -> Result<bool, MbdError> {
        // Q [ż; z; w; z̈] (one product with the stacked [ż; z; w]), plus the J θ̈ and m_θ θ̈
        // columns
        let th = vdot[0];
        let mut u = Vec::with_capacity(self.qt.nrows());
        u.extend_from_slice(&v[1..]);
        u.extend_from_slice(&q[1..]);
        u.extend_from_slice(&self.lagged);
        let uv = MatRef::from_column_major_slice(&u, u.len(), 1);
        let rv = MatMut::from_column_major_slice_mut(r, v.len(), 1);
        matmul(
            rv,
            Accum::Replace,
            self.qt.as_ref().transpose(),
            uv,
            1.0,
            Par::Seq,
        );
        if vdot[1..].iter().any(|&a| a != 0.0) {
            self.block(3, 1.0, &vdot[1..], r, Accum::Add);
        }
        r[0] += self.spin_inertia * th - self.drive_torque;
        let w2 = v[0] * v[0];
        for ((ri, c), mt) in r[1..].iter_mut().zip(&self.red.c_s).zip(&self.red.m_theta) {
            *ri += w2 * c + mt * th;
        }
        Ok(true)
    }

    /// The tangent of the frozen matrices: `K = [0 (k_θ + β θ̇_R k_θ,θ)ᵀ; 0 K_eff]`,
    /// `C = [0 β k_θᵀ; 0 C_eff]` (the derivatives in θ̇ of the gyroscopic and centrifugal
    /// forces are left out, as in the iteration matrix of Ribaric's linearly implicit step).
    fn force_tangent(
        &self,
        _t: f64,
        _q: &[f64],
        _v: &[f64],
        _ws: &mut Workspace,
    ) -> Result<Option<ForceTangent>, MbdError> {
        let nz = self.red.n_z();
        let n = nz + 1;
        let qt = &self.qt;
        let c = Mat::<f64>::from_fn(n, n, |i, j| if j == 0 { 0.0 } else { qt[(j - 1, i)] });
        let k = Mat::<f64>::from_fn(n, n, |i, j| if j == 0 { 0.0 } else { qt[(nz + j - 1, i)] });
        Ok(Some(ForceTangent {
            stiffness: SysMatrix::Dense(k),
            damping: SysMatrix::Dense(c),
        }))
    }
}
