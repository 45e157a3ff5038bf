//! The floating-frame deformable body: undeformed node positions, local mass and stiffness,
//! basis `Ψ'`, axis condition, and the precomputed inertia shape integrals.

use crate::MbdError;
use faer::{Mat, MatRef};
use nalgebra::{Matrix3, Vector3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// How the body frame of a [`FlexBody`] is defined (Lin ch. 4; Ribaric §2.2.5–2.2.8).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum AxisCondition {
    /// Nodal-fixed axes (Lin §4.1, Table 4-1): the six anchored local coordinates are zero,
    /// i.e. absent from `Ψ'` (use `reduction::axes::remove_anchor_columns` or
    /// `nodal_fixed_selection`). No constraint rows; `[P Ψ']` must have full column rank.
    NodalFixed,
    /// Mean axes (Lin Table 4-2, (4.22), (5.19), (8.29)): `IhᵀM'Ψ'ż = 0` (holonomic:
    /// `IhᵀM'Ψ'z = 0`) and `b~'ᵀM'Ψ'ż = 0` (non-holonomic) as Lagrange-multiplier rows.
    /// `Ψ'` must contain the rigid-body modes (Lin §8.1; check with
    /// `reduction::axes::check_mean_axes_preconditions`).
    MeanAxes,
    /// Principal axes (Lin §4.3, Ribaric (2.42)–(2.44)): translational mean-axis condition plus
    /// zero products of inertia `J'_ξη = J'_ηζ = J'_ζξ = 0` (holonomic). Ill-posed when two
    /// principal moments coincide.
    PrincipalAxes,
}

/// A rigid body that shares the frame of a flexible body (Ribaric (2.45)–(2.52): a rim bonded
/// to a tire). The frame origin is the core's mass centre; the bonded ("w") nodes have zero
/// rows in `Ψ'`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidCore {
    /// Mass `m^o` \[kg\].
    pub mass: f64,
    /// Inertia about the frame origin in the body frame `J^o` \[kg·m²\].
    pub inertia: Matrix3<f64>,
}

/// A floating-frame deformable body (Lin (3.10)–(3.38), (5.12)–(5.17)).
#[derive(Debug, Clone)]
pub struct FlexBody {
    /// Name used in messages.
    pub name: String,
    pub(crate) s: Vec<Vector3<f64>>,
    pub(crate) m: Mat<f64>,
    pub(crate) m_diag: Option<Vec<f64>>,
    pub(crate) psi: Mat<f64>,
    pub(crate) rot: Option<Mat<f64>>,
    pub(crate) k_r: Mat<f64>,
    pub(crate) c_r: Option<Mat<f64>>,
    pub(crate) axis: AxisCondition,
    pub(crate) core: Option<RigidCore>,
    // shape integrals (constant)
    pub(crate) total_mass: f64,
    pub(crate) m_psi: Mat<f64>,
    pub(crate) m_zz: Mat<f64>,
    pub(crate) ih_m_psi: Mat<f64>,
    pub(crate) ih_m_s: Vector3<f64>,
    pub(crate) k_psi: Mat<f64>,
    pub(crate) elastic: ElasticForces,
}

/// Where the linear elastic forces act (they differ at second order in the deflection,
/// because linear elasticity is not rotation invariant).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum ElasticForces {
    /// Only on the elastic coordinates, `−Ψ'ᵀK'Ψ'z` (from the strain energy `½zᵀK_r z`, which
    /// does not depend on the frame motion): energy-conserving. Default.
    #[default]
    Modal,
    /// Nodal forces `−K'δ'` applied at the deformed nodes and projected with `Lᵀ` (Lin (3.33),
    /// (3.37); Ribaric (2.45)–(2.50)): the frame rows receive the resultant and the moment
    /// `Σ b'_j × (−K'δ')_j`.
    Nodal,
}

fn bad(name: &str, field: &str, reason: String) -> MbdError {
    MbdError::InvalidInput {
        item: format!("flexible body \"{name}\": {field}"),
        reason,
    }
}

impl FlexBody {
    /// New body.
    ///
    /// * `s`: undeformed node positions relative to the frame origin, 3 per node \[m\];
    /// * `mass`: local nodal mass `M'` (3n × 3n, symmetric, each 3×3 nodal block a multiple of
    ///   `I3` so that `M = Abar M' Abarᵀ = M'`, Lin (3.26)) \[kg\];
    /// * `stiffness`: local nodal stiffness `K'` (3n × 3n) \[N/m\];
    /// * `psi`: basis `Ψ'` (3n × n_z): identity for the nodal formulation, a reduction basis for
    ///   the modal one;
    /// * `axis`: the axis condition.
    pub fn new(
        name: &str, s: &[f64], mass: MatRef<'_, f64>, stiffness: MatRef<'_, f64>,
        psi: MatRef<'_, f64>, axis: AxisCondition,
    ) -> Result<Self, MbdError> {
        let n = s.len();
        if n == 0 || !n.is_multiple_of(3) {
            return Err(bad(
                name,
                "node positions",
                format!("{n} values is not a positive multiple of 3"),
            ));
        }
        for (what, a) in [("mass matrix", mass), ("stiffness matrix", stiffness)] {
            if a.nrows() != n || a.ncols() != n {
                return Err(bad(
                    name,
                    what,
                    format!("is {}x{}, expected {n}x{n}", a.nrows(), a.ncols()),
                ));
            }
        }
        if psi.nrows() != n {
            return Err(bad(
                name,
                "basis",
                format!("has {} rows, expected {n}", psi.nrows()),
            ));
        }
        for (what, a) in [
            ("mass matrix", mass),
            ("stiffness matrix", stiffness),
            ("basis", psi),
        ] {
            for j in 0..a.ncols() {
                for i in 0..a.nrows() {
                    if !a[(i, j)].is_finite() {
                        return Err(bad(name, what, format!("entry ({i}, {j}) is not finite")));
                    }
                }
            }
        }
        if let Some(i) = s.iter().position(|x| !x.is_finite()) {
            return Err(bad(
                name,
                "node positions",
                format!("entry {i} is not finite"),
            ));
        }
        // block-scalar mass (Lin (3.26): Ṁ = 0 and M = M')
        let nn = n / 3;
        for a in 0..nn {
            for b in 0..nn {
                let blk = |i: usize, j: usize| mass[(3 * a + i, 3 * b + j)];
                let d = blk(0, 0);
                let scale = mass[(3 * a, 3 * a)].abs().max(1e-300);
                let off = (0..3)
                    .flat_map(|i| (0..3).map(move |j| (i, j)))
                    .map(|(i, j)| {
                        if i == j {
                            (blk(i, j) - d).abs()
                        } else {
                            blk(i, j).abs()
                        }
                    })
                    .fold(0.0, f64::max);
                if off > 1e-12 * scale {
                    return Err(bad(
                        name,
                        "mass matrix",
                        format!(
                            "nodal block ({a}, {b}) is not a multiple of I3 (a condensed nodal mass is not allowed, Lin (3.26); project the full mass with the basis instead)"
                        ),
                    ));
                }
            }
        }
        let is_diag = (0..n).all(|j| (0..n).all(|i| i == j || mass[(i, j)] == 0.0));
        let m_diag = is_diag.then(|| (0..n).map(|i| mass[(i, i)]).collect::<Vec<f64>>());
        let sv: Vec<Vector3<f64>> = s
            .chunks(3)
            .map(|c| Vector3::new(c[0], c[1], c[2]))
            .collect();
        let m_psi = mass * psi;
        let m_zz = psi.transpose() * &m_psi;
        let k_psi = stiffness * psi;
        let k_r = psi.transpose() * &k_psi;
        let mut ih_m_psi = Mat::<f64>::zeros(3, psi.ncols());
        for k in 0..psi.ncols() {
            for i in 0..n {
                ih_m_psi[(i % 3, k)] += m_psi[(i, k)];
            }
        }
        let mut total = 0.0;
        for j in 0..n {
            for i in 0..n {
                if i % 3 == 0 && j % 3 == 0 {
                    total += mass[(i, j)];
                }
            }
        }
        if total.is_nan() || total <= 0.0 {
            return Err(bad(
                name,
                "mass matrix",
                format!("total mass {total} kg is not positive"),
            ));
        }
        let ms = mat_vec(mass, &flat(&sv));
        let mut ih_m_s = Vector3::zeros();
        for (i, x) in ms.iter().enumerate() {
            ih_m_s[i % 3] += x;
        }
        let body = Self {
            name: name.into(),
            s: sv,
            m: mass.to_owned(),
            m_diag,
            psi: psi.to_owned(),
            rot: None,
            k_r: symmetric(&k_r),
            c_r: None,
            axis,
            core: None,
            total_mass: total,
            m_psi,
            m_zz: symmetric(&m_zz),
            ih_m_psi,
            ih_m_s,
            k_psi,
            elastic: ElasticForces::Modal,
        };
        Ok(body)
    }

    /// Adds modal/nodal damping from a full local damping matrix `C'` (projected `Ψ'ᵀC'Ψ'`).
    pub fn with_damping(mut self, c: MatRef<'_, f64>) -> Result<Self, MbdError> {
        let n = self.psi.nrows();
        if c.nrows() != n || c.ncols() != n {
            return Err(bad(
                &self.name,
                "damping matrix",
                format!("is {}x{}, expected {n}x{n}", c.nrows(), c.ncols()),
            ));
        }
        self.c_r = Some(symmetric(&(self.psi.transpose() * c * &self.psi)));
        Ok(self)
    }

    /// Gives the nodes small elastic rotations `θ_j = Φ_θ,j z` (body-frame components) with the
    /// slopes `Φ_θ` (3 n × n_z, \[rad\] per unit z; e.g. the rotational rows of the mode shapes
    /// of a beam model), so that markers on nodes rotate with the node
    /// ([`crate::marker`]); without slopes a node frame is the floating frame.
    pub fn with_node_rotations(mut self, slopes: MatRef<'_, f64>) -> Result<Self, MbdError> {
        let (n, nz) = (self.psi.nrows(), self.psi.ncols());
        if slopes.nrows() != n || slopes.ncols() != nz {
            return Err(bad(
                &self.name,
                "node rotation slopes",
                format!(
                    "are {}x{}, expected {n}x{nz}",
                    slopes.nrows(),
                    slopes.ncols()
                ),
            ));
        }
        for j in 0..nz {
            for i in 0..n {
                if !slopes[(i, j)].is_finite() {
                    return Err(bad(
                        &self.name,
                        "node rotation slopes",
                        format!("entry ({i}, {j}) is not finite"),
                    ));
                }
            }
        }
        self.rot = Some(slopes.to_owned());
        Ok(self)
    }

    /// Attaches a rigid body sharing the frame (Ribaric (2.45)–(2.52)).
    pub fn with_rigid_core(mut self, core: RigidCore) -> Result<Self, MbdError> {
        if !(core.mass.is_finite() && core.mass > 0.0) {
            return Err(bad(
                &self.name,
                "rigid core mass",
                format!("must be positive, got {}", core.mass),
            ));
        }
        if !core.inertia.iter().all(|x| x.is_finite()) {
            return Err(bad(
                &self.name,
                "rigid core inertia",
                "non-finite entry".into(),
            ));
        }
        self.core = Some(core);
        Ok(self)
    }

    /// Chooses where the elastic forces act (see [`ElasticForces`]).
    pub fn with_elastic_forces(mut self, e: ElasticForces) -> Self {
        self.elastic = e;
        self
    }

    /// Mass centre of the undeformed nodes in the body frame, `IhᵀM's' / m` \[m\] (zero when the
    /// frame origin is at the mass centre, as mean axes expect, Lin §4.2).
    pub fn undeformed_mass_centre(&self) -> Vector3<f64> {
        self.ih_m_s / self.total_mass
    }

    /// Number of nodes.
    pub fn n_nodes(&self) -> usize {
        self.s.len()
    }

    /// Number of elastic coordinates `n_z`.
    pub fn n_modes(&self) -> usize {
        self.psi.ncols()
    }

    /// Axis condition.
    pub fn axis(&self) -> AxisCondition {
        self.axis
    }

    /// Total mass of the nodes plus the rigid core \[kg\].
    pub fn mass(&self) -> f64 {
        self.total_mass + self.core.map(|c| c.mass).unwrap_or(0.0)
    }

    /// Undeformed position of node `j` in the body frame \[m\].
    pub fn node_position(&self, j: usize) -> Vector3<f64> {
        self.s[j]
    }

    /// Local deflections `δ' = Ψ' z` (Lin (5.12)), 3 per node \[m\].
    pub fn deflection(&self, z: &[f64]) -> Vec<f64> {
        mat_vec(self.psi.as_ref(), z)
    }

    /// Elastic energy `½ zᵀ Ψ'ᵀK'Ψ' z` \[J\].
    pub fn strain_energy(&self, z: &[f64]) -> f64 {
        let kz = mat_vec(self.k_r.as_ref(), z);
        0.5 * z.iter().zip(&kz).map(|(a, b)| a * b).sum::<f64>()
    }

    /// `M' x` (diagonal fast path).
    pub(crate) fn m_mul(&self, x: &[f64]) -> Vec<f64> {
        match &self.m_diag {
            Some(d) => d.iter().zip(x).map(|(a, b)| a * b).collect(),
            None => mat_vec(self.m.as_ref(), x),
        }
    }
}

pub(crate) fn mat_vec(a: MatRef<'_, f64>, x: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; a.nrows()];
    for (j, &xj) in x.iter().enumerate() {
        if xj != 0.0 {
            for (i, yi) in y.iter_mut().enumerate() {
                *yi += a[(i, j)] * xj;
            }
        }
    }
    y
}

pub(crate) fn flat(v: &[Vector3<f64>]) -> Vec<f64> {
    v.iter().flat_map(|x| [x.x, x.y, x.z]).collect()
}

fn symmetric(a: &Mat<f64>) -> Mat<f64> {
    Mat::from_fn(a.nrows(), a.ncols(), |i, j| 0.5 * (a[(i, j)] + a[(j, i)]))
}
