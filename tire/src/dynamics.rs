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
//!
//! In mass-normalised modal coordinates ([`ReducedTire::modal`]: `M = I`, `K = Λ` diagonal,
//! detected exactly at construction) the residual is evaluated as
//!
//! ```text
//!   r_z = (α + βΛ) ż + Λ z + z̈ + G₁ (2θ̇_R ż + w) + (θ̇_R² G₂ + βθ̇_R K₁) z + θ̇² c_s + m_θ θ̈,
//! ```
//!
//! the same sum with the diagonal blocks applied as such: one pass over the stacked
//! `[G₁ H]` (`H = θ̇_R² G₂ + βθ̇_R K₁`, 2 n_z × n_z) instead of `[C_eff K_eff G₁]`
//! (3 n_z × n_z), a third less data per step (issue #16: the step is bandwidth-bound).

use crate::reduced::ReducedTire;
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatMut, MatRef, Par};
use mbd_core::Workspace;
use mbd_core::parallel::{ProductWorker, SplitProduct};
use mbd_core::{ForceTangent, MbdError, SecondOrderSystem, SysMatrix};
use std::borrow::Cow;
use std::sync::Arc;

/// The rolling tire's smooth dynamics (module documentation).
pub struct TireDynamics<'a> {
    red: Cow<'a, ReducedTire>,
    /// `ω²` of the modal coordinates when `M = I` and `K = diag(ω²)` exactly (module
    /// documentation), else `None`.
    modal: Option<Vec<f64>>,
    /// Rayleigh α \[1/s\].
    alpha: f64,
    /// Rayleigh β \[s\].
    beta: f64,
    /// Spin inertia of wheel and rim `J` \[kg·m²\].
    spin_inertia: f64,
    /// Drive torque about the wheel axis \[N·m\].
    pub drive_torque: f64,
    /// The prescribed spin of the current step, if any: the rheonomic constraint
    /// `θ − θ_p(t) = 0` ([`PrescribedSpin`]).
    prescribed: Option<PrescribedSpin>,
    /// Acceleration `a` of the wheel frame (the spindle's rigid translation) \[m/s²\] in the
    /// wheel frame ([`TireDynamics::set_frame_acceleration`]).
    frame_acceleration: [f64; 3],
    /// Spin rate θ̇_R of the spin-dependent matrices \[rad/s\].
    spin: f64,
    /// The lagged argument `w` of the coupling `G₁ w` (n_z).
    lagged: Vec<f64>,
    /// `Qᵀ` (3 n_z × n): column 0 the spin row `[β k_θ; k_θ + β θ̇_R k_θ,θ; 0]`, column
    /// `1 + i` row `i` of `[C_eff K_eff G₁]`. Modal coordinates: `Qᵀ` (2 n_z × n), column 0
    /// `[0; k_θ + β θ̇_R k_θ,θ]`, column `1 + i` row `i` of `[G₁ H]`.
    qt: Mat<f64>,
    /// `[0 M]ᵀ` (n_z × n), the mass block of `Q` (empty in modal coordinates).
    mt: Mat<f64>,
    /// `β k_θ` (the spin row's `ż` part in modal coordinates).
    spin_c: Vec<f64>,
    /// `G₁ᵀ`, `Mᵀ`, `Kᵀ`, `G₂ᵀ`, `K₁ᵀ` (n_z × n_z each; modal coordinates: `G₂ᵀ`, `K₁ᵀ`):
    /// column `i` is row `i` of the reduced tire's matrix, so that [`TireDynamics::set_spin`]
    /// forms the rows of `C_eff` and `K_eff` from contiguous columns (re-formed many times a
    /// run when θ̇ oscillates after the cleat; the strided row reads of the column-major
    /// matrices made it the third largest cost of a run at h = 0.05 ms).
    rows: Vec<Mat<f64>>,
    /// The product with `Qᵀ`, split between two threads after
    /// [`TireDynamics::set_product_worker`] (bitwise the same result).
    product: SplitProduct,
}

/// A prescribed spin of the wheel over one step `[t₀, t₀ + h]` (issue 38, item 1): the spin
/// rate varies linearly from `ω₀` to `ω₁`, so the prescribed angle is
///
/// ```text
///   θ_p(t) = θ₀ + ω₀ s + ½ (ω₁ − ω₀) s²/h,   s = t − t₀,
///   θ̇_p = ω₀ + (ω₁ − ω₀) s/h,   θ̈_p = (ω₁ − ω₀)/h,
/// ```
///
/// and the end of the step `θ_p(t₀ + h) = θ₀ + h (ω₀ + ω₁)/2` (the trapezoidal rule of the
/// rate). Imposed as the rheonomic constraint `Φ(t, q) = θ − θ_p(t) = 0` with Jacobian
/// `D = [1 0 ⋯ 0]`, `ν = θ̇_p`, `γ = θ̈_p` (the kinematic driver of a coordinate, Haug,
/// *Computer-Aided Kinematics and Dynamics of Mechanical Systems*, §3.4, as
/// `mbd_core::constraints::drivers`) on the shared generalized-α stepper (index 3, Arnold &
/// Brüls 2007). Its multiplier `λ` is the reaction: the torque `−λ` \[N·m\] that the
/// prescribing drive applies to the wheel about +y.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrescribedSpin {
    /// Start of the step `t₀` \[s\].
    pub t0: f64,
    /// Prescribed angle at `t₀` \[rad\].
    pub theta0: f64,
    /// Spin rate at `t₀` \[rad/s\].
    pub omega0: f64,
    /// Spin rate at `t₀ + h` \[rad/s\].
    pub omega1: f64,
    /// Step `h` \[s\] (positive).
    pub h: f64,
}

impl PrescribedSpin {
    /// `θ_p(t)` \[rad\].
    pub fn angle(&self, t: f64) -> f64 {
        let s = t - self.t0;
        self.theta0 + self.omega0 * s + 0.5 * (self.omega1 - self.omega0) * s * s / self.h
    }

    /// `θ̇_p(t)` \[rad/s\].
    pub fn rate(&self, t: f64) -> f64 {
        self.omega0 + (self.omega1 - self.omega0) * (t - self.t0) / self.h
    }

    /// `θ̈_p` \[rad/s²\].
    pub fn acceleration(&self) -> f64 {
        (self.omega1 - self.omega0) / self.h
    }
}

impl<'a> TireDynamics<'a> {
    /// The tire with Rayleigh coefficients `alpha` \[1/s\], `beta` \[s\], the wheel's spin
    /// inertia `wheel_spin_inertia` \[kg·m²\] (the rim's is added) and the spin-dependent
    /// matrices formed at `spin` \[rad/s\].
    pub fn new(
        red: &'a ReducedTire, alpha: f64, beta: f64, wheel_spin_inertia: f64, spin: f64,
    ) -> Self {
        Self::from_cow(Cow::Borrowed(red), alpha, beta, wheel_spin_inertia, spin)
    }

    /// [`TireDynamics::new`] owning its reduced tire (e.g. the modal form of
    /// [`ReducedTire::modal`]).
    pub fn owned(
        red: ReducedTire, alpha: f64, beta: f64, wheel_spin_inertia: f64, spin: f64,
    ) -> TireDynamics<'static> {
        TireDynamics::from_cow(Cow::Owned(red), alpha, beta, wheel_spin_inertia, spin)
    }

    fn from_cow(
        red: Cow<'a, ReducedTire>, alpha: f64, beta: f64, wheel_spin_inertia: f64, spin: f64,
    ) -> Self {
        let nz = red.n_z();
        let modal = is_modal(&red);
        let spin_inertia = wheel_spin_inertia + red.rim_spin_inertia;
        let spin_c = red.kt.row(1).iter().map(|k| beta * k).collect();
        let (qt, mt, rows) = if modal.is_some() {
            let mut qt = Mat::zeros(2 * nz, nz + 1);
            for i in 0..nz {
                let mut col = qt.col_mut(1 + i);
                for j in 0..nz {
                    col[j] = red.g1[(i, j)];
                }
            }
            (
                qt,
                Mat::zeros(0, 0),
                [&red.g2, &red.k1]
                    .map(|a| a.transpose().to_owned())
                    .to_vec(),
            )
        } else {
            let mut qt = Mat::zeros(3 * nz, nz + 1);
            for i in 0..nz {
                let mut col = qt.col_mut(1 + i);
                for j in 0..nz {
                    col[2 * nz + j] = red.g1[(i, j)];
                }
            }
            (
                qt,
                Mat::from_fn(
                    nz,
                    nz + 1,
                    |j, i| if i == 0 { 0.0 } else { red.m[(i - 1, j)] },
                ),
                [&red.g1, &red.m, &red.k, &red.g2, &red.k1]
                    .map(|a| a.transpose().to_owned())
                    .to_vec(),
            )
        };
        let mut d = Self {
            red,
            modal,
            alpha,
            beta,
            spin_inertia,
            drive_torque: 0.0,
            prescribed: None,
            frame_acceleration: [0.0; 3],
            spin,
            lagged: vec![0.0; nz],
            qt,
            mt,
            spin_c,
            rows,
            product: SplitProduct::new(None),
        };
        d.set_spin(spin);
        d
    }

    /// Splits the per-step product with `Qᵀ` between the calling thread and `worker` (`None`:
    /// one thread); the results are the same bit for bit ([`mbd_core::parallel`]).
    pub fn set_product_worker(&mut self, worker: Option<Arc<ProductWorker>>) {
        self.product = SplitProduct::new(worker);
        self.product.set(self.qt.as_ref());
    }

    /// Prescribes the wheel's spin over the next step (`Some`) or leaves it free (`None`, the
    /// drive torque drives it): the rheonomic constraint `Φ = θ − θ_p(t) = 0`
    /// ([`PrescribedSpin`]), one constraint equation of [`SecondOrderSystem::n_c`] whose
    /// multiplier is the reaction torque. A stepper must be re-sized when the count changes
    /// ([`AlphaStepper::resize_constraints`](mbd_core::integrators::AlphaStepper::resize_constraints)).
    pub fn set_prescribed_spin(&mut self, p: Option<PrescribedSpin>) {
        self.prescribed = p;
    }

    /// Sets the acceleration `a` \[m/s²\] of the wheel frame, the rigid translation of the
    /// spindle (wheel frame x, y, z; issue 38 item 2). The frame is then not inertial: every
    /// material point carries the inertial load `−dm a` (d'Alembert), whose generalized force
    /// on the tire's coordinates is `−Tᵀ M e a = −Pᵀ a` with the translational momentum rows
    /// `P = eᵀ M T` ([`ReducedTire::p_e`]); the wheel's spin row sees none (a uniform field has
    /// no moment about the centre of the axisymmetric wheel and rim). 0 (default): the fixed
    /// spindle.
    pub fn set_frame_acceleration(&mut self, a: [f64; 3]) {
        self.frame_acceleration = a;
    }

    /// The acceleration of the wheel frame \[m/s²\] ([`TireDynamics::set_frame_acceleration`]).
    pub fn frame_acceleration(&self) -> [f64; 3] {
        self.frame_acceleration
    }

    /// `r[1 + i] += s (Pᵀ a)_i`: the inertial load of the accelerating frame (nothing when
    /// `a = 0`, so that the fixed spindle's sums are unchanged bit for bit).
    fn add_frame_load(&self, s: f64, r: &mut [f64]) {
        let a = self.frame_acceleration;
        if a == [0.0; 3] {
            return;
        }
        let p = &self.red.p_e;
        for (i, ri) in r[1..].iter_mut().enumerate() {
            *ri += s * (p[(0, i)] * a[0] + p[(1, i)] * a[1] + p[(2, i)] * a[2]);
        }
    }

    /// The prescribed spin of the current step ([`TireDynamics::set_prescribed_spin`]).
    pub fn prescribed_spin(&self) -> Option<&PrescribedSpin> {
        self.prescribed.as_ref()
    }

    /// Whether the tire is in modal coordinates (`M = I`, `K` diagonal; module documentation).
    pub fn is_modal(&self) -> bool {
        self.modal.is_some()
    }

    /// The reduced tire.
    pub fn reduced(&self) -> &ReducedTire {
        &self.red
    }

    /// Spin rate θ̇_R at which the spin-dependent matrices were formed \[rad/s\].
    pub fn spin(&self) -> f64 {
        self.spin
    }

    /// Re-forms the spin-dependent blocks at `spin` \[rad/s\]: the spin row
    /// `β k_θ ż + (k_θ + β θ̇ k_θ,θ) z` and `C_eff = 2θ̇G₁ + αM + βK`,
    /// `K_eff = K + θ̇²G₂ + βθ̇K₁` (Ribaric (7.17) with U15–U17).
    pub fn set_spin(&mut self, spin: f64) {
        let red = &*self.red;
        let nz = red.n_z();
        let (a, b) = (self.alpha, self.beta);
        self.spin = spin;
        let kt = red.kt.row(1);
        let kt1 = red.kt1.row(1);
        if self.modal.is_some() {
            // column i of Qᵀ = row i of [G₁ H], H = θ̇²G₂ + βθ̇K₁ (G₁ set once)
            for j in 0..nz {
                self.qt[(nz + j, 0)] = kt[j] + b * spin * kt1[j];
            }
            let [g2, k1] = [&self.rows[0], &self.rows[1]];
            for i in 0..nz {
                let mut col = self.qt.col_mut(1 + i);
                let (g2, k1) = (g2.col(i), k1.col(i));
                for j in 0..nz {
                    col[nz + j] = spin * spin * g2[j] + b * spin * k1[j];
                }
            }
            self.product.set(self.qt.as_ref());
            return;
        }
        for j in 0..nz {
            self.qt[(j, 0)] = b * kt[j];
            self.qt[(nz + j, 0)] = kt[j] + b * spin * kt1[j];
        }
        // column i of Qᵀ = row i of Q = column i of the transposed matrices (contiguous reads
        // and writes)
        let [g1, m, k, g2, k1] = [
            &self.rows[0],
            &self.rows[1],
            &self.rows[2],
            &self.rows[3],
            &self.rows[4],
        ];
        for i in 0..nz {
            let mut col = self.qt.col_mut(1 + i);
            let (g1, m, k, g2, k1) = (g1.col(i), m.col(i), k.col(i), g2.col(i), k1.col(i));
            for j in 0..nz {
                col[j] = 2.0 * spin * g1[j] + a * m[j] + b * k[j];
                col[nz + j] = k[j] + spin * spin * g2[j] + b * spin * k1[j];
            }
        }
        self.product.set(self.qt.as_ref());
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
        let (kt, kt1) = (self.red.kt.row(1), self.red.kt1.row(1));
        let b = self.beta;
        let nz = self.red.n_z();
        (0..nz)
            .map(|j| b * kt[j])
            .chain((0..nz).map(|j| kt[j] + b * self.spin * kt1[j]))
            .collect()
    }

    /// The residual `M v̇ − f` in modal coordinates (module documentation); `vdot = None`
    /// for `v̇ = 0`.
    fn modal_residual(
        &self, lam: &[f64], q: &[f64], v: &[f64], vdot: Option<&[f64]>, r: &mut [f64],
    ) {
        let nz = lam.len();
        let (a, b) = (self.alpha, self.beta);
        let (z, zd) = (&q[1..], &v[1..]);
        let s2 = 2.0 * self.spin;
        let mut u = Vec::with_capacity(2 * nz);
        u.extend(zd.iter().zip(&self.lagged).map(|(d, w)| s2 * d + w));
        u.extend_from_slice(z);
        self.qt_product(&u, r);
        let th = vdot.map_or(0.0, |a| a[0]);
        r[0] += self.spin_c.iter().zip(zd).map(|(c, d)| c * d).sum::<f64>()
            + self.spin_inertia * th
            - self.drive_torque;
        let w2 = v[0] * v[0];
        for i in 0..nz {
            let acc = vdot.map_or(0.0, |a| a[1 + i]);
            r[1 + i] += (a + b * lam[i]) * zd[i]
                + lam[i] * z[i]
                + acc
                + w2 * self.red.c_s[i]
                + self.red.m_theta[i] * th;
        }
        self.add_frame_load(1.0, r);
    }

    /// `r = Q u` (one pass over the stored `Qᵀ`, split between two threads with a worker).
    fn qt_product(&self, u: &[f64], r: &mut [f64]) {
        self.product.apply(self.qt.as_ref(), u, r);
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

    /// One equation with a prescribed spin ([`PrescribedSpin`]), else none.
    fn n_c(&self) -> usize {
        usize::from(self.prescribed.is_some())
    }

    fn constraint_name(&self, _row: usize) -> String {
        "prescribed wheel spin".into()
    }

    /// `Φ = θ − θ_p(t)`.
    fn constraint_residual(&self, t: f64, q: &[f64], phi: &mut [f64]) -> Result<(), MbdError> {
        if let (Some(p), Some(x)) = (&self.prescribed, phi.first_mut()) {
            *x = q[0] - p.angle(t);
        }
        Ok(())
    }

    /// `D = [1 0 ⋯ 0]`.
    fn constraint_jacobian(&self, _t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        let nc = self.n_c();
        Ok(SysMatrix::Dense(Mat::from_fn(nc, self.n_q(), |_, j| {
            if j == 0 { 1.0 } else { 0.0 }
        })))
    }

    /// `ν = θ̇_p(t)`.
    fn constraint_velocity_rhs(&self, t: f64, _q: &[f64], nu: &mut [f64]) -> Result<(), MbdError> {
        if let (Some(p), Some(x)) = (&self.prescribed, nu.first_mut()) {
            *x = p.rate(t);
        }
        Ok(())
    }

    /// `γ = θ̈_p`.
    fn constraint_gamma(
        &self, _t: f64, _q: &[f64], _v: &[f64], gamma: &mut [f64],
    ) -> Result<(), MbdError> {
        if let (Some(p), Some(x)) = (&self.prescribed, gamma.first_mut()) {
            *x = p.acceleration();
        }
        Ok(())
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
        let red = &*self.red;
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
        &self, _t: f64, q: &[f64], v: &[f64], f: &mut [f64], _ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        if let Some(lam) = &self.modal {
            self.modal_residual(lam, q, v, None, f);
            f.iter_mut().for_each(|x| *x = -*x);
            return Ok(());
        }
        self.block(0, -1.0, &v[1..], f, Accum::Replace);
        self.block(1, -1.0, &q[1..], f, Accum::Add);
        self.block(2, -1.0, &self.lagged, f, Accum::Add);
        f[0] += self.drive_torque;
        let w2 = v[0] * v[0];
        for (fi, c) in f[1..].iter_mut().zip(&self.red.c_s) {
            *fi -= w2 * c;
        }
        self.add_frame_load(-1.0, f);
        Ok(())
    }

    /// `M(q) v̇ − f` in one pass over `Q` (module documentation).
    fn dynamic_residual(
        &self, _t: f64, q: &[f64], v: &[f64], vdot: &[f64], r: &mut [f64], _ws: &mut Workspace,
    ) -> Result<bool, MbdError> {
        if let Some(lam) = &self.modal {
            self.modal_residual(lam, q, v, Some(vdot), r);
            return Ok(true);
        }
        // Q [ż; z; w; z̈] (one product with the stacked [ż; z; w]), plus the J θ̈ and m_θ θ̈
        // columns
        let th = vdot[0];
        let mut u = Vec::with_capacity(self.qt.nrows());
        u.extend_from_slice(&v[1..]);
        u.extend_from_slice(&q[1..]);
        u.extend_from_slice(&self.lagged);
        self.qt_product(&u, r);
        if vdot[1..].iter().any(|&a| a != 0.0) {
            self.block(3, 1.0, &vdot[1..], r, Accum::Add);
        }
        r[0] += self.spin_inertia * th - self.drive_torque;
        let w2 = v[0] * v[0];
        for ((ri, c), mt) in r[1..].iter_mut().zip(&self.red.c_s).zip(&self.red.m_theta) {
            *ri += w2 * c + mt * th;
        }
        self.add_frame_load(1.0, r);
        Ok(true)
    }

    /// The tangent of the frozen matrices: `K = [0 (k_θ + β θ̇_R k_θ,θ)ᵀ; 0 K_eff]`,
    /// `C = [0 β k_θᵀ; 0 C_eff]` (the derivatives in θ̇ of the gyroscopic and centrifugal
    /// forces are left out, as in the iteration matrix of Ribaric's linearly implicit step).
    fn force_tangent(
        &self, _t: f64, _q: &[f64], _v: &[f64], _ws: &mut Workspace,
    ) -> Result<Option<ForceTangent>, MbdError> {
        let nz = self.red.n_z();
        let n = nz + 1;
        let qt = &self.qt;
        if let Some(lam) = &self.modal {
            let (a, b, s2) = (self.alpha, self.beta, 2.0 * self.spin);
            // C = [0 βk_θᵀ; 0 α + βΛ + 2θ̇G₁], K = [0 (k_θ + βθ̇k_θ,θ)ᵀ; 0 Λ + H]
            let c = Mat::<f64>::from_fn(n, n, |i, j| match (i, j) {
                (_, 0) => 0.0,
                (0, j) => self.spin_c[j - 1],
                (i, j) => {
                    let d = if i == j { a + b * lam[i - 1] } else { 0.0 };
                    d + s2 * qt[(j - 1, i)]
                }
            });
            let k = Mat::<f64>::from_fn(n, n, |i, j| match (i, j) {
                (_, 0) => 0.0,
                (i, j) => {
                    let d = if i == j { lam[i - 1] } else { 0.0 };
                    d + qt[(nz + j - 1, i)]
                }
            });
            return Ok(Some(ForceTangent {
                stiffness: SysMatrix::Dense(k),
                damping: SysMatrix::Dense(c),
            }));
        }
        let c = Mat::<f64>::from_fn(n, n, |i, j| if j == 0 { 0.0 } else { qt[(j - 1, i)] });
        let k = Mat::<f64>::from_fn(n, n, |i, j| if j == 0 { 0.0 } else { qt[(nz + j - 1, i)] });
        Ok(Some(ForceTangent {
            stiffness: SysMatrix::Dense(k),
            damping: SysMatrix::Dense(c),
        }))
    }
}

/// `ω²` if `M = I` and `K` is diagonal exactly (the modal coordinates of
/// [`ReducedTire::modal`]).
fn is_modal(red: &ReducedTire) -> Option<Vec<f64>> {
    let n = red.n_z();
    for j in 0..n {
        for i in 0..n {
            let (m, k) = (red.m[(i, j)], red.k[(i, j)]);
            if (i == j && m != 1.0) || (i != j && (m != 0.0 || k != 0.0)) {
                return None;
            }
        }
    }
    Some((0..n).map(|i| red.k[(i, i)]).collect())
}
