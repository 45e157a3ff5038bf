//! Nodal penalty contact as a [`MeshForce`]: the positions of chosen mesh nodes against one
//! obstacle, with the contact crate's [`point_contact`] (normal law, friction law and their
//! exact derivatives). The penalty counterpart of the unilateral Lagrange contact of
//! [`crate::statics::solve_static_unilateral`] (Ribaric (6.1) is a nodal law of this kind).

use crate::element::Element;
use crate::mesh::Mesh;
use crate::system::MeshForce;
use contact::{FrictionLaw, NormalLaw, PointContact, Surface, point_contact};

/// Penalty contact of the nodes `nodes` (their position `r`) with `surface`.
#[derive(Debug, Clone)]
pub struct NodalContact<S, NL, FL> {
    /// Obstacle.
    pub surface: S,
    /// Normal law (force per node [N]).
    pub normal: NL,
    /// Friction law.
    pub friction: FL,
    /// Contact nodes.
    pub nodes: Vec<usize>,
}

impl<S: Surface, NL: NormalLaw, FL: FrictionLaw> NodalContact<S, NL, FL> {
    /// Contact state of every candidate node (`None` when separated).
    pub fn states<E: Element>(
        &self,
        mesh: &Mesh<E>,
        q: &[f64],
        v: &[f64],
    ) -> Vec<Option<PointContact>> {
        self.nodes
            .iter()
            .map(|&nd| {
                let k = mesh.node_dof(nd, 0);
                point_contact(
                    &self.surface,
                    &self.normal,
                    &self.friction,
                    [q[k], q[k + 1]],
                    [v[k], v[k + 1]],
                )
            })
            .collect()
    }
}

impl<E, S, NL, FL> MeshForce<E> for NodalContact<S, NL, FL>
where
    E: Element,
    S: Surface + Send + Sync,
    NL: NormalLaw + Send + Sync,
    FL: FrictionLaw + Send + Sync,
{
    fn add_forces(&self, mesh: &Mesh<E>, _t: f64, q: &[f64], v: &[f64], f: &mut [f64]) {
        for (&nd, c) in self.nodes.iter().zip(self.states(mesh, q, v)) {
            if let Some(c) = c {
                let k = mesh.node_dof(nd, 0);
                f[k] += c.force[0];
                f[k + 1] += c.force[1];
            }
        }
    }

    fn add_tangent(
        &self,
        mesh: &Mesh<E>,
        _t: f64,
        q: &[f64],
        v: &[f64],
        k_vals: &mut [f64],
        c_vals: &mut [f64],
    ) {
        let pat = mesh.pattern();
        for (&nd, c) in self.nodes.iter().zip(self.states(mesh, q, v)) {
            let Some(c) = c else { continue };
            let k = mesh.node_dof(nd, 0);
            for i in 0..2 {
                for j in 0..2 {
                    // the two position coordinates of a node share an element block
                    if let Some(p) = pat.position(k + i, k + j) {
                        k_vals[p] -= c.df_dp[i][j];
                        c_vals[p] -= c.df_dv[i][j];
                    }
                }
            }
        }
    }
}
