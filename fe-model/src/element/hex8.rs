//! Eight-node trilinear hexahedron (linear elasticity), with consistent/lumped mass and the
//! geometric (initial-stress) stiffness of a given Cauchy stress state.
//!
//! Standard isoparametric formulation (Bathe, *Finite Element Procedures*, §5.3; Hughes,
//! *The Finite Element Method*, §3.5 and §4.4 for selective reduced integration):
//! - `K = ∫ Bᵀ D B dV`, 2×2×2 Gauss ([`Hex8Integration::Full`]); or with the isotropic `D`
//!   split into deviatoric and volumetric parts, `D = D_dev + κ m mᵀ`, the deviatoric part
//!   at 2×2×2 and the volumetric part at the single centre point
//!   ([`Hex8Integration::SelectiveReduced`]), which removes volumetric locking for nearly
//!   incompressible rubber (ν → 0.5) without hourglass modes;
//! - `K_G = ∫ G_aᵀ σ G_b dV · I₃` (σ the 3×3 Cauchy prestress, `G_a = ∇N_a`), e.g. from tire
//!   inflation (Bathe (6.54), the linearised initial-stress term);
//! - optional smeared fibre families ([`Fibre`], ABAQUS `*REBAR`-like):
//!   `K_f = Σ_families ∫ Bᵀ (E_f φ) m mᵀ B dV` at 2×2×2 Gauss for both integration rules (the
//!   uniaxial fibre strain does not lock), added to the matrix stiffness above;
//! - consistent mass `ρ ∫ N_a N_b dV · I₃` (2×2×2 Gauss, `ρ` = matrix density plus the fibres'
//!   smeared `ρ_f φ`); lumped mass by row sums (equal to HRZ for the trilinear element).
//!
//! Node order is VTK's (`VTK_HEXAHEDRON`): bottom face (ζ = −1) counter-clockwise, then the top.
//! DOFs per node: (u, v, w); element DOF order (u₀, v₀, w₀, u₁, …).

use super::{Element, Fibre, MassKind};
use crate::FeError;
use faer::Mat;
use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};

/// Natural coordinates of the 8 nodes (VTK order).
pub const NODE_XI: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

/// Stiffness integration rule.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum Hex8Integration {
    /// 2×2×2 Gauss for the whole stiffness.
    #[default]
    Full,
    /// Selective reduced integration: deviatoric 2×2×2, volumetric 1 point (locking-free for
    /// nearly incompressible materials).
    SelectiveReduced,
}

/// Isotropic linear-elastic material.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Elastic {
    /// Young's modulus E \[Pa\].
    pub young: f64,
    /// Poisson's ratio ν \[-\] (−1 < ν < 0.5).
    pub poisson: f64,
    /// Density ρ \[kg/m³\].
    pub density: f64,
}

impl mbd_core::Validate for Elastic {
    /// `young > 0` \[Pa\], `density ≥ 0` \[kg/m³\], `−1 < poisson < 0.5` (positive definite
    /// isotropic elasticity).
    fn validate(&self) -> Result<(), mbd_core::InvalidField> {
        use mbd_core::validate::check;
        check::positive("young", self.young, "Pa")?;
        check::non_negative("density", self.density, "kg/m³")?;
        if !(self.poisson > -1.0 && self.poisson < 0.5) {
            return Err(check::reject("poisson", "in (-1, 0.5)", self.poisson));
        }
        Ok(())
    }
}

impl Elastic {
    /// Lamé constants (λ, μ) \[Pa\].
    pub fn lame(&self) -> (f64, f64) {
        let (e, nu) = (self.young, self.poisson);
        let mu = e / (2.0 * (1.0 + nu));
        let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        (lambda, mu)
    }

    /// Bulk modulus κ = λ + 2μ/3 \[Pa\].
    pub fn bulk(&self) -> f64 {
        let (l, m) = self.lame();
        l + 2.0 * m / 3.0
    }
}

/// Eight-node hexahedron.
#[derive(Debug, Clone, PartialEq)]
pub struct Hex8 {
    /// Global DOFs (24, node-major u, v, w).
    pub dofs: [usize; 24],
    /// Node coordinates \[m\] (VTK order).
    pub x: [[f64; 3]; 8],
    /// Material.
    pub material: Elastic,
    /// Integration rule of the stiffness.
    pub integration: Hex8Integration,
    /// Cauchy prestress σ \[Pa\] (symmetric), for the geometric stiffness; `None` = none.
    pub prestress: Option<[[f64; 3]; 3]>,
    /// Smeared uniaxial fibre families (rebar) on top of the matrix material; empty = none.
    pub fibres: Vec<Fibre>,
}

/// Shape functions and natural derivatives at ξ.
fn shape(xi: [f64; 3]) -> ([f64; 8], [[f64; 3]; 8]) {
    let mut n = [0.0; 8];
    let mut dn = [[0.0; 3]; 8];
    for a in 0..8 {
        let [xa, ya, za] = NODE_XI[a];
        let (p, q, r) = (1.0 + xa * xi[0], 1.0 + ya * xi[1], 1.0 + za * xi[2]);
        n[a] = 0.125 * p * q * r;
        dn[a] = [0.125 * xa * q * r, 0.125 * ya * p * r, 0.125 * za * p * q];
    }
    (n, dn)
}

/// 2×2×2 Gauss points (weight 1 each).
fn gauss8() -> [[f64; 3]; 8] {
    let g = 1.0 / 3f64.sqrt();
    let mut p = [[0.0; 3]; 8];
    for (i, pt) in p.iter_mut().enumerate() {
        *pt = [
            if i & 1 == 0 { -g } else { g },
            if i & 2 == 0 { -g } else { g },
            if i & 4 == 0 { -g } else { g },
        ];
    }
    p
}

impl Hex8 {
    /// New element; checks the material and that the Jacobian is positive at all Gauss points
    /// and at the centre (no inverted or degenerate element).
    pub fn new(
        dofs: [usize; 24], x: [[f64; 3]; 8], material: Elastic, integration: Hex8Integration,
        prestress: Option<[[f64; 3]; 3]>,
    ) -> Result<Self, FeError> {
        mbd_core::Validate::validate(&material)?;
        let e = Self {
            dofs,
            x,
            material,
            integration,
            prestress,
            fibres: Vec::new(),
        };
        for xi in gauss8().iter().chain(std::iter::once(&[0.0; 3])) {
            let (_, det) = e.gradients(*xi);
            if !(det > 0.0 && det.is_finite()) {
                return Err(FeError::param(
                    "hex8 Jacobian determinant",
                    det,
                    "must be > 0 (inverted, degenerate or wrongly ordered element nodes)",
                ));
            }
        }
        Ok(e)
    }

    /// The same element with the given fibre families (replacing any previous ones), each
    /// checked by [`Fibre::validate`].
    pub fn with_fibres(mut self, fibres: Vec<Fibre>) -> Result<Self, FeError> {
        for f in &fibres {
            f.validate()?;
        }
        self.fibres = fibres;
        Ok(self)
    }

    /// Fibre stiffness `K_f = Σ ∫ Bᵀ (E_f φ) m mᵀ B dV` (2×2×2 Gauss) alone (24×24); zero
    /// without fibres. See [`Fibre`].
    pub fn fibre_stiffness(&self) -> Mat<f64> {
        let mut k = Mat::zeros(24, 24);
        if self.fibres.is_empty() {
            return k;
        }
        for xi in gauss8() {
            let (g, det) = self.gradients(xi);
            let b = Self::b_matrix(&g);
            for f in &self.fibres {
                let m = f.voigt();
                // Bᵀ m: the fibre strain ε_aa per unit nodal DOF
                let mut bm = [0.0; 24];
                for (c, v) in bm.iter_mut().enumerate() {
                    *v = (0..6).map(|i| b[i][c] * m[i]).sum();
                }
                let w = f.modulus * det;
                for r in 0..24 {
                    let wr = w * bm[r];
                    for c in 0..24 {
                        k[(r, c)] += wr * bm[c];
                    }
                }
            }
        }
        k
    }

    /// Physical shape-function gradients `∇N_a` and `det J` at ξ.
    pub fn gradients(&self, xi: [f64; 3]) -> ([Vector3<f64>; 8], f64) {
        let (_, dn) = shape(xi);
        // J_ij = ∂x_j/∂ξ_i
        let mut j = Matrix3::zeros();
        for (dna, xa) in dn.iter().zip(&self.x) {
            for r in 0..3 {
                for c in 0..3 {
                    j[(r, c)] += dna[r] * xa[c];
                }
            }
        }
        let det = j.determinant();
        let jinv = j.try_inverse().unwrap_or_else(Matrix3::zeros);
        let g = dn.map(|d| jinv * Vector3::new(d[0], d[1], d[2]));
        (g, det)
    }

    /// Strain-displacement matrix B (6×24, Voigt xx, yy, zz, γxy, γyz, γzx) as plain array.
    fn b_matrix(g: &[Vector3<f64>; 8]) -> [[f64; 24]; 6] {
        let mut b = [[0.0; 24]; 6];
        for (a, ga) in g.iter().enumerate() {
            let c = 3 * a;
            let (gx, gy, gz) = (ga[0], ga[1], ga[2]);
            b[0][c] = gx;
            b[1][c + 1] = gy;
            b[2][c + 2] = gz;
            b[3][c] = gy;
            b[3][c + 1] = gx;
            b[4][c + 1] = gz;
            b[4][c + 2] = gy;
            b[5][c] = gz;
            b[5][c + 2] = gx;
        }
        b
    }

    /// Elasticity matrix parts (D_dev, D_vol) in Voigt notation; D = D_dev + D_vol.
    fn d_parts(&self) -> ([[f64; 6]; 6], [[f64; 6]; 6]) {
        let (_, mu) = self.material.lame();
        let kappa = self.material.bulk();
        let mut dev = [[0.0; 6]; 6];
        let mut vol = [[0.0; 6]; 6];
        for i in 0..3 {
            for j in 0..3 {
                vol[i][j] = kappa;
                dev[i][j] = if i == j {
                    2.0 * mu * (1.0 - 1.0 / 3.0)
                } else {
                    -2.0 * mu / 3.0
                };
            }
            dev[i + 3][i + 3] = mu;
        }
        (dev, vol)
    }

    fn add_btdb(k: &mut Mat<f64>, b: &[[f64; 24]; 6], d: &[[f64; 6]; 6], w: f64) {
        // DB (6×24)
        let mut db = [[0.0; 24]; 6];
        for i in 0..6 {
            for kk in 0..6 {
                let dik = d[i][kk];
                if dik != 0.0 {
                    for c in 0..24 {
                        db[i][c] += dik * b[kk][c];
                    }
                }
            }
        }
        for r in 0..24 {
            for c in 0..24 {
                let mut s = 0.0;
                for i in 0..6 {
                    s += b[i][r] * db[i][c];
                }
                k[(r, c)] += w * s;
            }
        }
    }

    /// Element volume \[m³\].
    pub fn volume(&self) -> f64 {
        gauss8().iter().map(|&xi| self.gradients(xi).1).sum()
    }
}

impl Element for Hex8 {
    fn dofs(&self) -> &[usize] {
        &self.dofs
    }

    fn stiffness(&self) -> Mat<f64> {
        let mut k = Mat::zeros(24, 24);
        let (dev, vol) = self.d_parts();
        let mut full = dev;
        for i in 0..6 {
            for j in 0..6 {
                full[i][j] += vol[i][j];
            }
        }
        match self.integration {
            Hex8Integration::Full => {
                for xi in gauss8() {
                    let (g, det) = self.gradients(xi);
                    Self::add_btdb(&mut k, &Self::b_matrix(&g), &full, det);
                }
            }
            Hex8Integration::SelectiveReduced => {
                for xi in gauss8() {
                    let (g, det) = self.gradients(xi);
                    Self::add_btdb(&mut k, &Self::b_matrix(&g), &dev, det);
                }
                let (g, det) = self.gradients([0.0; 3]);
                Self::add_btdb(&mut k, &Self::b_matrix(&g), &vol, 8.0 * det);
            }
        }
        if !self.fibres.is_empty() {
            k += self.fibre_stiffness();
        }
        k
    }

    fn mass(&self, kind: MassKind) -> Mat<f64> {
        let rho = self.material.density + self.fibres.iter().map(|f| f.density).sum::<f64>();
        let mut nn = [[0.0; 8]; 8];
        for xi in gauss8() {
            let (n, _) = shape(xi);
            let (_, det) = self.gradients(xi);
            for a in 0..8 {
                for b in 0..8 {
                    nn[a][b] += rho * n[a] * n[b] * det;
                }
            }
        }
        let mut m = Mat::zeros(24, 24);
        for a in 0..8 {
            let row: f64 = nn[a].iter().sum();
            for b in 0..8 {
                for i in 0..3 {
                    match kind {
                        MassKind::Consistent => m[(3 * a + i, 3 * b + i)] = nn[a][b],
                        MassKind::Lumped => {
                            if a == b {
                                m[(3 * a + i, 3 * a + i)] = row;
                            }
                        }
                    }
                }
            }
        }
        m
    }

    fn geometric_stiffness(&self) -> Option<Mat<f64>> {
        let s = self.prestress?;
        let sigma = Matrix3::from_fn(|i, j| 0.5 * (s[i][j] + s[j][i]));
        let mut kg = Mat::zeros(24, 24);
        for xi in gauss8() {
            let (g, det) = self.gradients(xi);
            for a in 0..8 {
                let sg = sigma * g[a];
                for b in 0..8 {
                    let v = g[b].dot(&sg) * det;
                    for i in 0..3 {
                        kg[(3 * a + i, 3 * b + i)] += v;
                    }
                }
            }
        }
        Some(kg)
    }
}
