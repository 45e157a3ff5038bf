//! ANCF meshes as [`SecondOrderSystem`]s: constant sparse mass matrix, elastic + gravity +
//! applied forces with the analytic tangent, and prescribed (possibly rheonomic) nodal
//! coordinates as constraints `Φ = q_k − g_k(t)` (Kerkkänen (2.29)–(2.32): joints to ground and
//! hub rotations become linear constraints with `C_e` constant).

use crate::element::AncfElement;
use crate::error::{AncfError, invalid};
use crate::mesh::AncfMesh;
use faer::sparse::{SparseColMat, Triplet};
use mbd_core::Workspace;
use mbd_core::system::ForceTangent;
use mbd_core::{MbdError, SecondOrderSystem, SysMatrix};
use std::sync::Arc;

mod unilateral;
pub use unilateral::{ContactStep, NodeContacts, integrate_unilateral};

/// Prescribed value `g(t)` \[m or -\] and its first two time derivatives.
pub type MotionFn = Arc<dyn Fn(f64) -> [f64; 3] + Send + Sync>;

/// A global coordinate with prescribed motion.
#[derive(Clone)]
pub struct Prescribed {
    /// Global coordinate index.
    pub dof: usize,
    /// Name for error messages (e.g. `"pin x"`).
    pub name: String,
    /// `t ↦ [g, ġ, g̈]`.
    pub motion: MotionFn,
}

impl std::fmt::Debug for Prescribed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Prescribed")
            .field("dof", &self.dof)
            .field("name", &self.name)
            .finish()
    }
}

impl Prescribed {
    /// Coordinate held at `value`.
    pub fn fixed(dof: usize, name: impl Into<String>, value: f64) -> Self {
        Self {
            dof,
            name: name.into(),
            motion: Arc::new(move |_| [value, 0.0, 0.0]),
        }
    }
}

/// An additional force on the mesh (contact, point loads, …): the extension point through
/// which contact enters an ANCF model.
pub trait MeshForce<E: AncfElement>: Send + Sync {
    /// `f += Q(t, q, v)`.
    fn add_forces(&self, mesh: &AncfMesh<E>, t: f64, q: &[f64], v: &[f64], f: &mut [f64]);
    /// `k_vals += −∂Q/∂q`, `c_vals += −∂Q/∂v` in the mesh pattern ([`AncfMesh::pattern`]).
    fn add_tangent(
        &self, mesh: &AncfMesh<E>, t: f64, q: &[f64], v: &[f64], k_vals: &mut [f64],
        c_vals: &mut [f64],
    );
}

/// Energies of Kerkkänen (2.34) \[J\].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Energies {
    /// Kinetic energy `½ vᵀ M v`.
    pub kinetic: f64,
    /// Strain energy `U`.
    pub strain: f64,
    /// Gravity potential `V = −Q_gᵀ q` (zero at `q = 0`).
    pub potential: f64,
    /// `T + U + V`.
    pub total: f64,
}

/// An ANCF mesh with gravity, constant loads, extra forces and prescribed coordinates.
pub struct AncfSystem<E: AncfElement> {
    mesh: AncfMesh<E>,
    gravity: [f64; 2],
    gravity_forces: Vec<f64>,
    load: Vec<f64>,
    prescribed: Vec<Prescribed>,
    extra: Vec<Box<dyn MeshForce<E>>>,
    constraint_jacobian: SparseColMat<usize, f64>,
}

impl<E: AncfElement> AncfSystem<E> {
    /// System of `mesh` without gravity, loads or constraints.
    pub fn new(mesh: AncfMesh<E>) -> Self {
        let n = mesh.n_dof();
        let mut s = Self {
            gravity_forces: vec![0.0; n],
            load: vec![0.0; n],
            gravity: [0.0; 2],
            prescribed: Vec::new(),
            extra: Vec::new(),
            constraint_jacobian: SparseColMat::try_new_from_triplets(0, n, &[])
                .expect("empty matrix"),
            mesh,
        };
        s.rebuild_jacobian();
        s
    }

    /// Gravity acceleration `g` \[m/s²\] (e.g. `[0, −9.81]`).
    pub fn with_gravity(mut self, g: [f64; 2]) -> Self {
        self.gravity = g;
        self.gravity_forces = self.mesh.gravity_forces(g);
        self
    }

    /// Constant generalized load \[N\] (length `n_dof`).
    pub fn with_load(mut self, load: Vec<f64>) -> Result<Self, AncfError> {
        if load.len() != self.mesh.n_dof() {
            return Err(invalid(
                "load",
                format!(
                    "has {} entries, mesh has {} coordinates",
                    load.len(),
                    self.mesh.n_dof()
                ),
            ));
        }
        self.load = load;
        Ok(self)
    }

    /// Add prescribed coordinates (each coordinate at most once).
    pub fn with_prescribed(mut self, p: Vec<Prescribed>) -> Result<Self, AncfError> {
        for c in &p {
            if c.dof >= self.mesh.n_dof() {
                return Err(invalid(
                    format!("prescribed coordinate \"{}\"", c.name),
                    format!("index {} out of range 0..{}", c.dof, self.mesh.n_dof()),
                ));
            }
            if self.prescribed.iter().any(|o| o.dof == c.dof) {
                return Err(invalid(
                    format!("prescribed coordinate \"{}\"", c.name),
                    format!("coordinate {} is already prescribed", c.dof),
                ));
            }
            self.prescribed.push(c.clone());
        }
        self.rebuild_jacobian();
        Ok(self)
    }

    /// Add a force element (contact, …).
    pub fn with_force(mut self, f: Box<dyn MeshForce<E>>) -> Self {
        self.extra.push(f);
        self
    }

    fn rebuild_jacobian(&mut self) {
        let trip: Vec<_> = self
            .prescribed
            .iter()
            .enumerate()
            .map(|(i, p)| Triplet::new(i, p.dof, 1.0))
            .collect();
        self.constraint_jacobian =
            SparseColMat::try_new_from_triplets(self.prescribed.len(), self.mesh.n_dof(), &trip)
                .expect("distinct prescribed coordinates");
    }

    /// The mesh.
    pub fn mesh(&self) -> &AncfMesh<E> {
        &self.mesh
    }

    /// Prescribed coordinates.
    pub fn prescribed(&self) -> &[Prescribed] {
        &self.prescribed
    }

    /// Energies at `(q, v)` (Kerkkänen (2.34)).
    pub fn energies(&self, q: &[f64], v: &[f64]) -> Energies {
        let kinetic = self.mesh.kinetic_energy(v);
        let strain = self.mesh.strain_energy(q);
        let potential = -self
            .gravity_forces
            .iter()
            .zip(q)
            .map(|(a, b)| a * b)
            .sum::<f64>();
        Energies {
            kinetic,
            strain,
            potential,
            total: kinetic + strain + potential,
        }
    }

    /// Initial state consistent with the prescribed motion at `t`: `q0` and zero velocities
    /// except the prescribed rates.
    pub fn consistent_velocity(&self, t: f64) -> Vec<f64> {
        let mut v = vec![0.0; self.mesh.n_dof()];
        for p in &self.prescribed {
            v[p.dof] = (p.motion)(t)[1];
        }
        v
    }
}

impl<E: AncfElement> SecondOrderSystem for AncfSystem<E> {
    fn n_q(&self) -> usize {
        self.mesh.n_dof()
    }
    fn n_c(&self) -> usize {
        self.prescribed.len()
    }
    fn constraint_name(&self, row: usize) -> String {
        self.prescribed
            .get(row)
            .map(|p| p.name.clone())
            .unwrap_or_else(|| format!("constraint {row}"))
    }
    fn dof_name(&self, dof: usize) -> String {
        let cpn = self.mesh.coords_per_node();
        let names: &[&str] = match cpn {
            4 => &["r_x", "r_y", "r,y_x", "r,y_y"],
            _ => &["r_x", "r_y", "r,x_x", "r,x_y", "r,y_x", "r,y_y"],
        };
        format!("node {} {}", dof / cpn, names[dof % cpn])
    }
    fn mass_is_constant(&self) -> bool {
        true
    }
    fn mass(&self, _t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        Ok(SysMatrix::Sparse(self.mesh.mass_matrix()))
    }
    fn forces(
        &self, t: f64, q: &[f64], v: &[f64], f: &mut [f64], _ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        self.mesh.elastic_forces(q, f);
        for ((fi, g), l) in f.iter_mut().zip(&self.gravity_forces).zip(&self.load) {
            *fi += g + l;
        }
        for x in &self.extra {
            x.add_forces(&self.mesh, t, q, v, f);
        }
        Ok(())
    }
    fn force_tangent(
        &self, t: f64, q: &[f64], v: &[f64], _ws: &mut Workspace,
    ) -> Result<Option<ForceTangent>, MbdError> {
        let pat = self.mesh.pattern();
        let mut k = pat.zeros();
        let mut c = pat.zeros();
        let mut f = vec![0.0; self.mesh.n_dof()];
        self.mesh.elastic_tangent_into(q, &mut f, pat, &mut k, 1.0);
        for x in &self.extra {
            x.add_tangent(&self.mesh, t, q, v, &mut k, &mut c);
        }
        Ok(Some(ForceTangent {
            stiffness: SysMatrix::Sparse(pat.to_matrix(k)),
            damping: SysMatrix::Sparse(pat.to_matrix(c)),
        }))
    }
    fn constraint_residual(&self, t: f64, q: &[f64], phi: &mut [f64]) -> Result<(), MbdError> {
        for (p, r) in self.prescribed.iter().zip(phi.iter_mut()) {
            *r = q[p.dof] - (p.motion)(t)[0];
        }
        Ok(())
    }
    fn constraint_jacobian(&self, _t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        Ok(SysMatrix::Sparse(self.constraint_jacobian.clone()))
    }
    fn constraint_velocity_rhs(&self, t: f64, _q: &[f64], nu: &mut [f64]) -> Result<(), MbdError> {
        for (p, r) in self.prescribed.iter().zip(nu.iter_mut()) {
            *r = (p.motion)(t)[1];
        }
        Ok(())
    }
    fn constraint_gamma(
        &self, t: f64, _q: &[f64], _v: &[f64], gamma: &mut [f64],
    ) -> Result<(), MbdError> {
        for (p, r) in self.prescribed.iter().zip(gamma.iter_mut()) {
            *r = (p.motion)(t)[2];
        }
        Ok(())
    }
}
