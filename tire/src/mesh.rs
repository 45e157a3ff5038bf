//! The tire's finite-element model as the reduction sees it (Ribaric (7.1), (7.4)).
//!
//! Frame and conventions (seed note U18): the wheel centre is the origin, `x` is longitudinal
//! (forward), `y` the wheel (spin) axis `η`, `z` vertical (up). A node at radial distance
//! `ρ = √(x² + z²)` has the circumferential angle `θ = atan2(x, z)` (θ = 0 at the top, θ = π at
//! the road); a positive spin `θ̇ = ηᵀω` about `+y` increases θ, so the material at the patch
//! moves backwards (`−x`) while the wheel rolls forwards.
//!
//! The mass is lumped (diagonal, Ribaric §7.2). Rim (bead) nodes are bonded to the rigid wheel
//! (U23) and carry no deflection; their stiffness rows give the spindle forces (7.2).

use crate::error::{TireError, invalid};
use faer::sparse::SparseColMat;
use fe_model::{FeModel, MassKind};
use flowing::grid::{FlowGrid, Topology};
use std::f64::consts::PI;

/// A tire FE model: node coordinates \[m\], stiffness K (3 DOFs per node, node-major, including the
/// inflation geometric stiffness when wanted) \[N/m\], lumped nodal masses \[kg\], the rim node set
/// and the candidate patch nodes.
#[derive(Debug, Clone)]
pub struct TireFe {
    /// Node coordinates in the wheel frame \[m\].
    pub nodes: Vec<[f64; 3]>,
    /// Global stiffness `K` (`3n × 3n`, symmetric) \[N/m\].
    pub stiffness: SparseColMat<usize, f64>,
    /// Lumped mass per DOF (`3n`) \[kg\].
    pub mass: Vec<f64>,
    /// Rim (bead) nodes, bonded to the wheel.
    pub rim: Vec<usize>,
    /// Candidate contact (patch) nodes: the outer tread surface near θ = π.
    pub candidates: Vec<usize>,
}

/// One circumferential ring of nodes (same `ρ` and `y`), sorted by θ.
#[derive(Debug, Clone)]
pub struct Ring {
    /// Node indices in increasing θ.
    pub nodes: Vec<usize>,
    /// Their angles θ \[rad\], strictly increasing within one period.
    pub theta: Vec<f64>,
}

/// Circumferential angle `θ = atan2(x, z)` in `[0, 2π)` \[rad\].
pub fn node_angle(x: &[f64; 3]) -> f64 {
    let t = x[0].atan2(x[2]);
    if t < 0.0 { t + 2.0 * PI } else { t }
}

impl TireFe {
    /// Build from raw matrices (e.g. imported from ABAQUS / Matrix Market).
    ///
    /// `mass` may be consistent: it is lumped by row sums (documented approximation; Ribaric's
    /// formulation assumes a diagonal mass). Errors name the offending node or matrix.
    pub fn from_matrices(
        nodes: Vec<[f64; 3]>, stiffness: SparseColMat<usize, f64>, mass: &SparseColMat<usize, f64>,
        rim: Vec<usize>, candidates: Vec<usize>,
    ) -> Result<Self, TireError> {
        let n = 3 * nodes.len();
        for (name, a) in [("stiffness", &stiffness), ("mass", mass)] {
            if a.nrows() != n || a.ncols() != n {
                return Err(invalid(
                    format!("{name} matrix"),
                    format!(
                        "is {}×{} but {} nodes need {n}×{n}",
                        a.nrows(),
                        a.ncols(),
                        nodes.len()
                    ),
                ));
            }
        }
        let mut lumped = vec![0.0; n];
        for (i, _j, v) in fe_model::sparse::triplets(mass.as_ref()) {
            lumped[i] += v;
        }
        let fe = Self {
            nodes,
            stiffness,
            mass: lumped,
            rim,
            candidates,
        };
        fe.validate()?;
        Ok(fe)
    }

    /// Build from an fe-model [`FeModel`] with 3 DOFs per node and node sets `rim_set` and
    /// `candidate_set`; `with_geometric` adds the (inflation) prestress stiffness `K_G`.
    pub fn from_fe_model(
        model: &FeModel, rim_set: &str, candidate_set: &str, with_geometric: bool,
    ) -> Result<Self, TireError> {
        if model.mesh.dofs_per_node != 3 {
            return Err(invalid(
                "tire mesh",
                format!(
                    "has {} DOFs per node; a solid tire needs 3",
                    model.mesh.dofs_per_node
                ),
            ));
        }
        let (k, m) = model.k_and_m(MassKind::Lumped, with_geometric)?;
        let rim = model.mesh.node_set(rim_set)?.to_vec();
        let cand = model.mesh.node_set(candidate_set)?.to_vec();
        Self::from_matrices(model.mesh.nodes.clone(), k, &m, rim, cand)
    }

    /// Number of nodes.
    pub fn n_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// Number of DOFs (3 per node).
    pub fn n_dofs(&self) -> usize {
        3 * self.nodes.len()
    }

    /// Total tire mass (all nodes) \[kg\].
    pub fn total_mass(&self) -> f64 {
        self.mass.iter().step_by(3).sum()
    }

    /// Check sizes, indices (each listed once), positive masses and that no rim node is a
    /// candidate.
    pub fn validate(&self) -> Result<(), TireError> {
        let nn = self.nodes.len();
        if nn == 0 {
            return Err(invalid("tire mesh", "has no nodes"));
        }
        for (name, set) in [("rim", &self.rim), ("candidate patch", &self.candidates)] {
            if set.is_empty() {
                return Err(invalid(format!("{name} node set"), "is empty"));
            }
            if let Some(&b) = set.iter().find(|&&i| i >= nn) {
                return Err(invalid(
                    format!("{name} node set"),
                    format!("node {b} does not exist ({nn} nodes)"),
                ));
            }
            let mut listed = vec![false; nn];
            for &i in set.iter() {
                if std::mem::replace(&mut listed[i], true) {
                    return Err(invalid(
                        format!("{name} node set"),
                        format!("node {i} is listed twice"),
                    ));
                }
            }
        }
        let mut is_rim = vec![false; nn];
        for &r in &self.rim {
            is_rim[r] = true;
        }
        if let Some(&c) = self.candidates.iter().find(|&&c| is_rim[c]) {
            return Err(invalid(
                "candidate patch node set",
                format!("node {c} is also a rim node"),
            ));
        }
        for (d, &m) in self.mass.iter().enumerate() {
            if !(is_rim[d / 3] || m > 0.0 && m.is_finite()) {
                return Err(invalid(
                    format!("mass of node {} (DOF {d})", d / 3),
                    format!("lumped mass {m} is not positive"),
                ));
            }
        }
        Ok(())
    }

    /// Whether each node is a rim node.
    pub fn rim_mask(&self) -> Vec<bool> {
        let mut m = vec![false; self.nodes.len()];
        for &r in &self.rim {
            m[r] = true;
        }
        m
    }

    /// Group the non-rim nodes into circumferential rings (same `ρ`, `y` within `tol` \[m\]),
    /// Ribaric App. A for the 3-D tire (seed recipe R8: group nodes by (r, y)).
    ///
    /// Every non-rim node must lie on a ring of at least 3 nodes; the error names the first that
    /// does not.
    pub fn rings(&self, tol: f64) -> Result<Vec<Ring>, TireError> {
        let rim = self.rim_mask();
        let q = |v: f64| (v / tol).round() as i64;
        let mut map: std::collections::BTreeMap<(i64, i64), Vec<usize>> = Default::default();
        for (i, x) in self.nodes.iter().enumerate() {
            if rim[i] {
                continue;
            }
            let rho = (x[0] * x[0] + x[2] * x[2]).sqrt();
            map.entry((q(rho), q(x[1]))).or_default().push(i);
        }
        let mut rings = Vec::with_capacity(map.len());
        for (_, mut nodes) in map {
            if nodes.len() < 3 {
                return Err(invalid(
                    format!("node {}", nodes[0]),
                    format!(
                        "is on a circumferential ring of only {} node(s); the flowing-material \
                         tire needs an axisymmetric mesh (rings of ≥ 3 nodes)",
                        nodes.len()
                    ),
                ));
            }
            nodes.sort_by(|&a, &b| {
                node_angle(&self.nodes[a]).total_cmp(&node_angle(&self.nodes[b]))
            });
            let theta: Vec<f64> = nodes.iter().map(|&i| node_angle(&self.nodes[i])).collect();
            rings.push(Ring { nodes, theta });
        }
        Ok(rings)
    }
}

impl Ring {
    /// The closed flow grid of the ring (period 2π).
    pub fn grid(&self) -> Result<FlowGrid, TireError> {
        Ok(FlowGrid::new(
            self.theta.clone(),
            Topology::Closed { period: 2.0 * PI },
        )?)
    }
}
