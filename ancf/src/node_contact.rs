//! Nodal penalty contact as a [`MeshForce`]: the positions of chosen mesh nodes against one
//! obstacle, with the contact crate's [`point_contact`] (normal law, friction law and their
//! exact derivatives). The penalty counterpart of the unilateral Lagrange contact of
//! [`crate::statics::solve_static_unilateral`] (Ribaric (6.1) is a nodal law of this kind).

use crate::element::AncfElement;
use crate::mesh::AncfMesh;
use crate::system::MeshForce;
use contact::{FrictionLaw, NormalLaw, PointContact, Surface, point_contact};
use nalgebra::{Point2, Vector2};

/// Penalty contact of the nodes `nodes` (their position `r`) with `surface`.
#[derive(Debug, Clone)]
pub struct NodalContact<S, NL, FL> {
    /// Obstacle.
    pub surface: S,
    /// Normal law (force per node \[N\]).
    pub normal: NL,
    /// Friction law.
    pub friction: FL,
    /// Contact nodes.
    pub nodes: Vec<usize>,
}

impl<S: Surface<2>, NL: NormalLaw, FL: FrictionLaw> NodalContact<S, NL, FL> {
    /// Contact state of every candidate node (`None` when separated).
    pub fn states<E: AncfElement>(
        &self, mesh: &AncfMesh<E>, q: &[f64], v: &[f64],
    ) -> Vec<Option<PointContact<2>>> {
        self.nodes
            .iter()
            .map(|&nd| {
                let k = mesh.node_dof(nd, 0);
                point_contact(
                    &self.surface,
                    &self.normal,
                    &self.friction,
                    &Point2::new(q[k], q[k + 1]),
                    &Vector2::new(v[k], v[k + 1]),
                )
            })
            .collect()
    }
}

impl<E, S, NL, FL> MeshForce<E> for NodalContact<S, NL, FL>
where
    E: AncfElement,
    S: Surface<2> + Send + Sync,
    NL: NormalLaw + Send + Sync,
    FL: FrictionLaw + Send + Sync,
{
    fn add_forces(&self, mesh: &AncfMesh<E>, _t: f64, q: &[f64], v: &[f64], f: &mut [f64]) {
        for (&nd, c) in self.nodes.iter().zip(self.states(mesh, q, v)) {
            if let Some(c) = c {
                let k = mesh.node_dof(nd, 0);
                f[k] += c.force[0];
                f[k + 1] += c.force[1];
            }
        }
    }

    fn add_tangent(
        &self, mesh: &AncfMesh<E>, _t: f64, q: &[f64], v: &[f64], k_vals: &mut [f64],
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
                        k_vals[p] -= c.df_dp[(i, j)];
                        c_vals[p] -= c.df_dv[(i, j)];
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::ProposedBeam;
    use crate::material::Material;
    use crate::mesh::straight_coordinates;
    use crate::section::Section;
    use contact::{CoulombTanh, Disk, LinearPenalty};

    // Reference: central finite differences of `add_forces` (the tangent is −∂Q/∂q, −∂Q/∂v).
    #[test]
    fn tangent_matches_finite_differences() {
        let mat = Material::new(2.0e9, 0.3, 1000.0).unwrap();
        let sec = Section::rectangle(0.05, 0.01).unwrap();
        let els = (0..3)
            .map(|_| ProposedBeam::new(0.1, mat, sec))
            .collect::<Result<Vec<_>, _>>()
            .unwrap();
        let mesh = AncfMesh::chain(els).unwrap();
        let mut q = straight_coordinates(mesh.layout(), [0.0, 0.0], [0.3, 0.0], 3);
        // nodes 1 and 2 pushed into a rotating disk below the beam, node 3 outside
        q[mesh.node_dof(1, 1)] = -0.004;
        q[mesh.node_dof(2, 1)] = -0.006;
        let v: Vec<f64> = (0..q.len())
            .map(|k| 0.01 * ((k as f64) * 0.7).sin())
            .collect();
        let contact = NodalContact {
            surface: Disk {
                center: Point2::new(0.15, -0.5),
                radius: 0.499,
                velocity: Vector2::zeros(),
                omega: 2.0,
            },
            normal: LinearPenalty {
                stiffness: 1e6,
                damping: 50.0,
            },
            friction: CoulombTanh {
                mu: 0.3,
                kappa: 20.0,
            },
            nodes: vec![1, 2, 3],
        };
        let pat = mesh.pattern();
        let mut kv = pat.zeros();
        let mut cv = pat.zeros();
        contact.add_tangent(&mesh, 0.0, &q, &v, &mut kv, &mut cv);
        let n = q.len();
        let force = |q: &[f64], v: &[f64]| {
            let mut f = vec![0.0; n];
            contact.add_forces(&mesh, 0.0, q, v, &mut f);
            f
        };
        let h = 1e-8;
        let mut worst: f64 = 0.0;
        for j in 0..n {
            for (which, vals) in [(0, &kv), (1, &cv)] {
                let (mut qp, mut qm, mut vp, mut vm) = (q.clone(), q.clone(), v.clone(), v.clone());
                if which == 0 {
                    qp[j] += h;
                    qm[j] -= h;
                } else {
                    vp[j] += h;
                    vm[j] -= h;
                }
                let (fp, fm) = (force(&qp, &vp), force(&qm, &vm));
                for i in 0..n {
                    let fd = -(fp[i] - fm[i]) / (2.0 * h);
                    let an = pat.position(i, j).map_or(0.0, |p| vals[p]);
                    worst = worst.max((fd - an).abs() / (1.0 + fd.abs()));
                }
            }
        }
        assert!(worst < 1e-5, "largest relative tangent error {worst}");
        // the contact is really active with friction
        let states = contact.states(&mesh, &q, &v);
        assert!(states[0].is_some() && states[1].is_some() && states[2].is_none());
        assert!(states[0].unwrap().friction.force.abs() > 0.0);
    }
}
