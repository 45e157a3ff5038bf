//! The reduced tire of Ribaric §8.2: the projected matrices of the flowing-material modal form
//! (7.17), saved as a versioned JSON file and reused by every simulation.
//!
//! Basis (7.11): `δ = T z`, `z = [z^f; z^c]`, `T = [Ψ^f  Ψ_s Ψ^c; 0  Ψ^c]` on the tire DOFs
//! (rim DOFs carry no deflection). With the lumped mass `M`, stiffness `K`, the circumferential
//! derivatives `T_,θ`, `T_,θθ` (App. A, per Cartesian component along each ring), the rigid
//! rotation fields `s_,θ = η × s` and `s_,θθ = η × (η × s)` the stored matrices are
//!
//! ```text
//!   M_z = TᵀMT,  K_z = TᵀKT,  G₁ = TᵀMT_,θ,  G₂ = TᵀMT_,θθ,  K₁ = TᵀKT_,θ,
//!   m_θ = TᵀM s_,θ,  c_s = TᵀM s_,θθ,
//!   K_r = Σ_rim K_{rim,·} T,  K_θ = Σ_rim s̃ K_{rim,·} T  (and the same with T_,θ)   (7.2)
//! ```
//! plus the contact-node rows `T_c`, `T_c,θ` (and the upwind differences of `T_c` along the
//! rings that transport the contact nodes' slip), the undeformed contact-node positions `s^c` and
//! the translational momentum projections `P = eᵀM T`, `P₁ = eᵀM T_,θ`, `P₂ = eᵀM T_,θθ`,
//! `eᵀM s_,θ`, `eᵀM s_,θθ` (e = the three Cartesian directions; tire nodes only) of the
//! momentum-balance spindle force ([`crate::SpindleForceMethod`]).

mod file;

pub use file::{FORMAT, MAX_REDUCED_TIRE_BYTES, VERSION};

use crate::error::TireError;
use faer::Mat;
use flowing::derivative::DerivativeMethod;

/// The reduced flowing-material tire (see the module documentation for the definitions).
#[derive(Debug, Clone)]
pub struct ReducedTire {
    /// Number of kept free-node modes `n_f`.
    pub n_free_modes: usize,
    /// FE node index of each contact node (c-node), in `z^c` order.
    pub contact_nodes: Vec<usize>,
    /// Undeformed contact-node positions `s^c` in the wheel frame \[m\].
    pub contact_positions: Vec<[f64; 3]>,
    /// Frequencies of the kept free-node modes (contact and rim nodes fixed) \[Hz\].
    pub free_mode_hz: Vec<f64>,
    /// Frequencies of the contact-node modes (free and rim nodes fixed) \[Hz\].
    pub contact_mode_hz: Vec<f64>,
    /// Tire mass without the rim nodes \[kg\].
    pub tire_mass: f64,
    /// Mass of the rim nodes (added to the wheel) \[kg\].
    pub rim_mass: f64,
    /// Spin inertia of the rim nodes about the wheel axis (added to the wheel) \[kg·m²\].
    pub rim_spin_inertia: f64,
    /// Unloaded outer radius of the contact nodes (largest `ρ`) \[m\].
    pub outer_radius: f64,
    /// Derivative method used for `T_,θ`, `T_,θθ`.
    pub derivative: DerivativeMethod,
    /// `M_z = TᵀMT` \[kg\].
    pub m: Mat<f64>,
    /// `K_z = TᵀKT` \[N/m\].
    pub k: Mat<f64>,
    /// `G₁ = TᵀMT_,θ` \[kg/rad\].
    pub g1: Mat<f64>,
    /// `G₂ = TᵀMT_,θθ` \[kg/rad²\].
    pub g2: Mat<f64>,
    /// `K₁ = TᵀKT_,θ` \[N/(m·rad)\].
    pub k1: Mat<f64>,
    /// `m_θ = TᵀM s_,θ` \[kg·m/rad\].
    pub m_theta: Vec<f64>,
    /// `c_s = TᵀM s_,θθ` \[kg·m/rad²\].
    pub c_s: Vec<f64>,
    /// Rim force per coordinate `K_r = Σ_rim K T` (3 × n_z) \[N/m\], Ribaric (7.2).
    pub kr: Mat<f64>,
    /// `Σ_rim K T_,θ` (3 × n_z).
    pub kr1: Mat<f64>,
    /// Rim moment per coordinate `K_θ = Σ_rim s̃ K T` (3 × n_z) \[N\], Ribaric (7.2).
    pub kt: Mat<f64>,
    /// `Σ_rim s̃ K T_,θ` (3 × n_z).
    pub kt1: Mat<f64>,
    /// Contact-node rows of `T` (3 n_c × n_z).
    pub tc: Mat<f64>,
    /// Contact-node rows of `T_,θ` (3 n_c × n_z) \[1/rad\].
    pub tc_theta: Mat<f64>,
    /// Contact-node rows of the upwind difference of `T` along the rings (3 n_c × n_z)
    /// \[1/rad\]: `[0]` from each node's predecessor in θ (spin `Ω ≥ 0`), `[1]` towards its
    /// successor (`Ω < 0`). The transport `Ω T_c,θ z` of the contact nodes' slip velocity,
    /// Ribaric (7.10), uses these (see `upwind_rows` in [`mod@crate::reduce`]).
    pub tc_theta_upwind: [Mat<f64>; 2],
    /// Translational momentum per coordinate `P = eᵀM T` (3 × n_z, rows x, y, z) \[kg\].
    pub p_e: Mat<f64>,
    /// `P₁ = eᵀM T_,θ` (3 × n_z) \[kg/rad\]; zero up to round-off for uniform rings (the periodic
    /// derivative of any field sums to zero around a ring).
    pub p_e1: Mat<f64>,
    /// `P₂ = eᵀM T_,θθ` (3 × n_z) \[kg/rad²\]; zero up to round-off for uniform rings.
    pub p_e2: Mat<f64>,
    /// `[eᵀM s_,θ, eᵀM s_,θθ]` of the rigid rotation field \[kg·m\]; zero for an axisymmetric
    /// tire.
    pub p_s: [[f64; 3]; 2],
    /// Rows of `T` for visualising the whole deforming tire (optional).
    pub viz: Option<VizBasis>,
    /// Rows of `T` at every node of the tread's crown and edge rings, for the circumferential
    /// order of a mode ([`super::harmonics`]); `None` in files written before it existed.
    pub tread: Option<TreadBasis>,
    /// Description of the FE model and reduction settings the tire was made from
    /// ([`crate::TireSource::fingerprint`]: the generator configuration or the imported files'
    /// SHA-256 digests, and the reduction settings, as JSON), so that a saved file is not
    /// reused for another tire; empty when unknown.
    pub source: String,
    /// The version of the code that reduced the tire ([`crate::CODE_VERSION`] of the build
    /// that made it; empty when unknown): a cached tire is reused only by the same code.
    pub code_version: String,
}

/// Rows of the basis `T` at a subset of the tire's nodes (every ring at equally spaced
/// circumferential stations), so that the deformed shape of the whole tire,
/// `xᵢ = sᵢ + (T z)ᵢ`, can be drawn from the reduced coordinates (VTK series).
#[derive(Debug, Clone, PartialEq)]
pub struct VizBasis {
    /// FE node indices.
    pub nodes: Vec<usize>,
    /// Their undeformed positions `sᵢ` \[m\].
    pub positions: Vec<[f64; 3]>,
    /// Line segments (pairs of indices into `nodes`) along the rings.
    pub lines: Vec<[usize; 2]>,
    /// Rows of `T` (3 n_v × n_z).
    pub rows: Mat<f64>,
}

impl VizBasis {
    /// Deformed positions for the reduced coordinates `z` \[m\].
    pub fn deformed(&self, z: &[f64]) -> Vec<[f64; 3]> {
        let zr = faer::MatRef::from_column_major_slice(z, z.len(), 1);
        let d = &self.rows * zr;
        self.positions
            .iter()
            .enumerate()
            .map(|(i, s)| {
                [
                    s[0] + d[(3 * i, 0)],
                    s[1] + d[(3 * i + 1, 0)],
                    s[2] + d[(3 * i + 2, 0)],
                ]
            })
            .collect()
    }
}

/// Rows of the basis `T` at all nodes of a few whole circumferential rings of the tread (the
/// crown ring and the two edge rings of the candidate patch), `d = T_t z`: the displacement
/// over the full circumference from which [`super::harmonics`] takes a mode's circumferential
/// order `n` and travelling direction.
#[derive(Debug, Clone, PartialEq)]
pub struct TreadBasis {
    /// FE node indices (ring after ring, each in increasing θ).
    pub nodes: Vec<usize>,
    /// Circumferential angle θ of each node (`atan2(x, z)`, [`super::mesh::node_angle`]) \[rad\].
    pub theta: Vec<f64>,
    /// Ring number of each node (0, 1, …).
    pub ring: Vec<usize>,
    /// Rows of `T` (3 n_t × n_z, Cartesian x, y, z per node).
    pub rows: Mat<f64>,
}

/// The reduced tire in mass-normalised modal coordinates (see [`ReducedTire::modal`]).
#[derive(Debug, Clone)]
pub struct ModalTire {
    /// The same tire in the coordinates `y` (`z = Φ y`): `M_y = I`, `K_y = Λ` diagonal.
    pub tire: ReducedTire,
    /// `Φ` (n_z × n_z): the eigenvectors of `K_z φ = ω² M_z φ`, `ΦᵀM_zΦ = I`.
    pub phi: Mat<f64>,
    /// `Φᵀ M_z` = `Φ⁻¹`, the map `y = Φᵀ M_z z` (n_z × n_z).
    pub phi_inv: Mat<f64>,
    /// Largest deviation of `ΦᵀM_zΦ` from `I` and of `ΦᵀK_zΦ` from `Λ` relative to the largest
    /// `ω²` (the round-off of the change of coordinates; the asymmetry of `M_z`, `K_z` counts
    /// into it).
    pub deviation: f64,
}

impl ReducedTire {
    /// The same tire in the mass-normalised modal coordinates of its zero-spin pencil,
    /// `z = Φ y` with `K_z Φ = M_z Φ Λ`, `ΦᵀM_zΦ = I` (fe-model's dense generalized eigen
    /// solver): `M_y = I`, `K_y = Λ` (set exactly; [`ModalTire::deviation`] reports what that
    /// drops), `G₁`, `G₂`, `K₁` congruent (`ΦᵀAΦ`), `m_θ`, `c_s` projected (`Φᵀ·`), and every
    /// row map of `z` (`T_c`, `T_c,θ`, `K_r`, `K_θ`, `P`, …) multiplied by `Φ`. An exact change
    /// of coordinates (Ribaric (7.17) is invariant under it): the rolling tire's products with
    /// `M` and the stiffness part of `K_eff` become diagonal (issue #16). The visualisation
    /// and tread bases are dropped (map `y` back with [`ModalTire::phi`]).
    pub fn modal(&self) -> Result<ModalTire, TireError> {
        let n = self.n_z();
        let modes = fe_model::dense_modes(self.k.as_ref(), self.m.as_ref(), n)?;
        let phi = modes.vectors;
        let lam = modes.values;
        let cong = |a: &Mat<f64>| phi.transpose() * a * &phi;
        let right = |a: &Mat<f64>| a * &phi;
        let proj = |v: &[f64]| -> Vec<f64> {
            (0..n)
                .map(|j| (0..n).map(|i| phi[(i, j)] * v[i]).sum())
                .collect()
        };
        let mut tire = self.with_coordinates(cong, right, proj);
        let (my, ky) = (&tire.m, &tire.k);
        let lmax = lam.iter().fold(0.0f64, |a, &b| a.max(b.abs())).max(1e-300);
        let mut deviation = 0.0f64;
        for j in 0..n {
            for i in 0..n {
                let (em, ek) = if i == j {
                    (my[(i, j)] - 1.0, ky[(i, j)] - lam[i])
                } else {
                    (my[(i, j)], ky[(i, j)])
                };
                deviation = deviation.max(em.abs()).max(ek.abs() / lmax);
            }
        }
        tire.m = Mat::identity(n, n);
        tire.k = Mat::from_fn(n, n, |i, j| if i == j { lam[i] } else { 0.0 });
        let phi_inv = phi.transpose() * &self.m;
        Ok(ModalTire {
            tire,
            phi,
            phi_inv,
            deviation,
        })
    }

    /// The same tire in new coordinates `z = P y` (Ribaric (7.17) is invariant under a change
    /// of coordinates): `square(A)` = `PᵀAP` for `M`, `K`, `G₁`, `G₂`, `K₁`; `right(A)` = `AP`
    /// for every row map of `z` (`K_r`, `K_θ`, `T_c`, `T_c,θ`, `P`, …); `vector(v)` = `Pᵀv` for
    /// `m_θ`, `c_s`. The visualisation and tread bases are dropped (map `y` back with `P`). Used
    /// by [`ReducedTire::modal`] (`P = Φ`) and the mirror half model
    /// ([`super::mirror::half_tire`], `P` a selection of coordinates).
    pub fn with_coordinates(
        &self, square: impl Fn(&Mat<f64>) -> Mat<f64>, right: impl Fn(&Mat<f64>) -> Mat<f64>,
        vector: impl Fn(&[f64]) -> Vec<f64>,
    ) -> ReducedTire {
        let mut tire = self.clone();
        for (t, a) in [
            (&mut tire.m, &self.m),
            (&mut tire.k, &self.k),
            (&mut tire.g1, &self.g1),
            (&mut tire.g2, &self.g2),
            (&mut tire.k1, &self.k1),
        ] {
            *t = square(a);
        }
        tire.m_theta = vector(&self.m_theta);
        tire.c_s = vector(&self.c_s);
        for (t, a) in [
            (&mut tire.kr, &self.kr),
            (&mut tire.kr1, &self.kr1),
            (&mut tire.kt, &self.kt),
            (&mut tire.kt1, &self.kt1),
            (&mut tire.tc, &self.tc),
            (&mut tire.tc_theta, &self.tc_theta),
            (&mut tire.p_e, &self.p_e),
            (&mut tire.p_e1, &self.p_e1),
            (&mut tire.p_e2, &self.p_e2),
        ] {
            *t = right(a);
        }
        tire.tc_theta_upwind = [
            right(&self.tc_theta_upwind[0]),
            right(&self.tc_theta_upwind[1]),
        ];
        tire.viz = None;
        tire.tread = None;
        tire
    }

    /// Number of contact nodes `n_c`.
    pub fn n_contact(&self) -> usize {
        self.contact_nodes.len()
    }

    /// Number of tire coordinates `n_z = n_f + 3 n_c`.
    pub fn n_z(&self) -> usize {
        self.m.nrows()
    }

    /// Number of DOF of the wheel–tire model: 6 wheel DOF + `n_z` (Ribaric §8.2: 6 + 285 + 50 =
    /// 341).
    pub fn dof(&self) -> usize {
        6 + self.n_z()
    }

    /// Eigenfrequencies of the reduced tire with the wheel fixed, not rolling: `K_z φ = ω² M_z φ`
    /// \[Hz\], ascending.
    pub fn frequencies_hz(&self) -> Result<Vec<f64>, TireError> {
        let modes = fe_model::dense_modes(self.k.as_ref(), self.m.as_ref(), self.n_z())?;
        Ok(modes.frequencies_hz)
    }
}
