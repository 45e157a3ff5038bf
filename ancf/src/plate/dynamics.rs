//! Dynamics of a thin-plate mesh as one [`SecondOrderSystem`]: `M ë = Q_e(e) + Q_g`
//! (Kerkkänen (2.27) with the plate of §4.3), constant sparse mass (2.26), elastic forces with
//! the analytic tangent of [`super::ThinPlate::elastic_tangent`] (bending on or off per element,
//! Kerkkänen's Model 2 has it off) and gravity, supports eliminated. Any of mbd-core's
//! integrators runs it (generalized-α with the sparse tangent, RK4, Dormand–Prince).

use super::mesh::PlateMesh;
use crate::error::{AncfError, invalid};
use crate::plate::PLATE_NDOF;
use crate::sparse::Pattern;
use faer::Mat;
use mbd_core::Workspace;
use mbd_core::system::ForceTangent;
use mbd_core::{MbdError, SecondOrderSystem, SysMatrix};

/// A plate mesh with supports (coordinates held at their initial values) and gravity.
///
/// The system coordinates are the free mesh coordinates in increasing order;
/// [`PlateDynamics::full_coordinates`] and [`PlateDynamics::free_coordinates`] convert.
pub struct PlateDynamics {
    mesh: PlateMesh,
    /// Mesh coordinate → system coordinate (`None`: fixed).
    map: Vec<Option<usize>>,
    /// The mesh coordinates the fixed entries are held at.
    held: Vec<f64>,
    n: usize,
    gravity_forces: Vec<f64>,
    pattern: Pattern,
    mass_values: Vec<f64>,
}

/// Work buffers of [`PlateDynamics`]'s force and tangent evaluations, kept in the caller's
/// [`Workspace`]: the full mesh coordinates (fixed entries at their held values) and one
/// element's forces and tangent.
struct Scratch {
    q: Vec<f64>,
    f: Vec<f64>,
    k: Mat<f64>,
}

impl std::fmt::Debug for PlateDynamics {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PlateDynamics")
            .field("elements", &self.mesh.cells.len())
            .field("n_q", &self.n)
            .finish()
    }
}

impl PlateDynamics {
    /// The mesh with the mesh coordinates `fixed` held at their values in `q0` (all mesh
    /// coordinates) and the gravitational acceleration `gravity` \[m/s²\].
    pub fn new(
        mesh: PlateMesh, q0: &[f64], fixed: &[usize], gravity: [f64; 3],
    ) -> Result<Self, AncfError> {
        let n_all = mesh.n_coords();
        if q0.len() != n_all {
            return Err(invalid(
                "plate dynamics: coordinates",
                format!("expected {n_all} values, got {}", q0.len()),
            ));
        }
        if let Some(&bad) = fixed.iter().find(|&&i| i >= n_all) {
            return Err(invalid(
                "plate dynamics: fixed",
                format!("coordinate {bad} does not exist (mesh has {n_all})"),
            ));
        }
        if gravity.iter().any(|g| !g.is_finite()) {
            return Err(invalid("plate dynamics: gravity", "must be finite"));
        }
        let mut map = vec![None; n_all];
        let mut n = 0;
        for (i, m) in map.iter_mut().enumerate() {
            if !fixed.contains(&i) {
                *m = Some(n);
                n += 1;
            }
        }
        let groups: Vec<Vec<Option<usize>>> = mesh
            .cells
            .iter()
            .map(|c| mesh.cell_dofs(c).iter().map(|&d| map[d]).collect())
            .collect();
        let pattern = Pattern::new(n, &groups);
        let mut mass_values = pattern.zeros();
        let mut me = vec![0.0; PLATE_NDOF * PLATE_NDOF];
        for (el, cell) in mesh.cells.iter().enumerate() {
            let m = cell.plate.mass_matrix();
            for j in 0..PLATE_NDOF {
                for i in 0..PLATE_NDOF {
                    me[i + j * PLATE_NDOF] = m[(i, j)];
                }
            }
            pattern.add_element(&mut mass_values, el, &me, 1.0);
        }
        let gravity_forces = mesh.gravity_forces(gravity);
        Ok(Self {
            held: q0.to_vec(),
            mesh,
            map,
            n,
            gravity_forces,
            pattern,
            mass_values,
        })
    }

    /// The mesh.
    pub fn mesh(&self) -> &PlateMesh {
        &self.mesh
    }

    /// All mesh coordinates for the system coordinates `q` (fixed ones at their held values).
    pub fn full_coordinates(&self, q: &[f64]) -> Vec<f64> {
        let mut out = self.held.clone();
        self.fill_full(q, &mut out);
        out
    }

    /// The system coordinates of the mesh coordinates `q_all`.
    pub fn free_coordinates(&self, q_all: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.n];
        for (i, m) in self.map.iter().enumerate() {
            if let Some(r) = m {
                out[*r] = q_all[i];
            }
        }
        out
    }

    fn fill_full(&self, q: &[f64], out: &mut [f64]) {
        for (i, m) in self.map.iter().enumerate() {
            if let Some(r) = m {
                out[i] = q[*r];
            }
        }
    }

    /// The work buffers in the caller's workspace `ws`, created on first use (the full
    /// coordinates start at the held values, which [`Self::fill_full`] keeps).
    fn scratch<'w>(&self, ws: &'w mut Workspace) -> &'w mut Scratch {
        let fresh = || Scratch {
            q: self.held.clone(),
            f: vec![0.0; PLATE_NDOF],
            k: Mat::zeros(PLATE_NDOF, PLATE_NDOF),
        };
        let s = ws.get_or_insert_with(fresh);
        if s.q.len() != self.held.len() {
            *s = fresh();
        }
        s
    }

    /// Mesh coordinates of element `el` from the full coordinates.
    fn element_coords(&self, el: usize, q_all: &[f64]) -> [f64; PLATE_NDOF] {
        let dofs = self.mesh.cell_dofs(&self.mesh.cells[el]);
        std::array::from_fn(|i| q_all[dofs[i]])
    }

    /// Total energy `T + U − Q_gᵀ q` \[J\] at `(q, v)` (kinetic, strain, gravity potential; the
    /// gravity potential of the constant generalized force).
    pub fn energy(&self, q: &[f64], v: &[f64]) -> Result<f64, AncfError> {
        let q_all = self.full_coordinates(q);
        let mut mv = vec![0.0; self.n];
        self.pattern.mul_vec(&self.mass_values, v, &mut mv);
        let kinetic = 0.5 * mv.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
        let potential: f64 = self
            .gravity_forces
            .iter()
            .zip(&q_all)
            .map(|(f, x)| -f * x)
            .sum();
        Ok(kinetic + self.mesh.strain_energy(&q_all)? + potential)
    }
}

impl SecondOrderSystem for PlateDynamics {
    fn n_q(&self) -> usize {
        self.n
    }
    fn dof_name(&self, dof: usize) -> String {
        match self.map.iter().position(|m| *m == Some(dof)) {
            Some(g) => {
                let names = ["r", "r_x", "r_y"];
                let local = g % 9;
                format!(
                    "plate node {} {}[{}]",
                    g / 9,
                    names[local / 3],
                    ["x", "y", "z"][local % 3]
                )
            }
            None => format!("coordinate {dof}"),
        }
    }
    fn mass_is_constant(&self) -> bool {
        true
    }
    fn mass(&self, _t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        Ok(SysMatrix::Sparse(
            self.pattern.to_matrix(self.mass_values.clone()),
        ))
    }
    /// `Q_e + Q_g` on the free coordinates.
    fn forces(
        &self, _t: f64, q: &[f64], _v: &[f64], f: &mut [f64], ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        let Scratch {
            q: q_all, f: fe, ..
        } = self.scratch(ws);
        self.fill_full(q, q_all);
        for (i, m) in self.map.iter().enumerate() {
            if let Some(r) = m {
                f[*r] = self.gravity_forces[i];
            }
        }
        for (el, cell) in self.mesh.cells.iter().enumerate() {
            let e = self.element_coords(el, q_all);
            cell.plate.elastic_forces(&e, fe);
            for (a, d) in self.mesh.cell_dofs(cell).iter().enumerate() {
                if let Some(r) = self.map[*d] {
                    f[r] += fe[a];
                }
            }
        }
        Ok(())
    }
    /// `K = −∂Q_e/∂q` (analytic), no damping.
    fn force_tangent(
        &self, _t: f64, q: &[f64], _v: &[f64], ws: &mut Workspace,
    ) -> Result<Option<ForceTangent>, MbdError> {
        let Scratch {
            q: q_all,
            f: fe,
            k: ke,
        } = self.scratch(ws);
        self.fill_full(q, q_all);
        let mut kv = self.pattern.zeros();
        let mut kl = vec![0.0; PLATE_NDOF * PLATE_NDOF];
        for (el, cell) in self.mesh.cells.iter().enumerate() {
            let e = self.element_coords(el, q_all);
            cell.plate.elastic_tangent(&e, fe, ke);
            for j in 0..PLATE_NDOF {
                for i in 0..PLATE_NDOF {
                    kl[i + j * PLATE_NDOF] = ke[(i, j)];
                }
            }
            self.pattern.add_element(&mut kv, el, &kl, 1.0);
        }
        Ok(Some(ForceTangent {
            stiffness: SysMatrix::Sparse(self.pattern.to_matrix(kv)),
            damping: SysMatrix::Sparse(self.pattern.to_matrix(self.pattern.zeros())),
        }))
    }
}
