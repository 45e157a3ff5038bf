//! Distributed belt–pulley contact as a [`MeshForce`] (Kerkkänen §3.2): every element is
//! integrated with the contact crate's Gauss-quadrature [`LineContact`], forces and exact
//! Jacobians are scattered into the mesh vectors and sparse pattern.

use crate::element::{AncfElement, MAX_NDOF};
use crate::mesh::AncfMesh;
use crate::system::MeshForce;
use contact::{ContactRecord, ElementContact, FrictionLaw, LineContact, NormalLaw, Surface};
use nalgebra::Vector2;

/// Contact of the mesh centreline with one obstacle (Kerkkänen (3.20)–(3.27)).
#[derive(Debug, Clone)]
pub struct PulleyContact<S, NL, FL> {
    /// Obstacle, laws and quadrature.
    pub contact: LineContact<S, NL, FL>,
}

/// A contact record tagged with its element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElementRecord {
    /// Element index.
    pub element: usize,
    /// Point data.
    pub record: ContactRecord<2>,
}

/// Contact output of one obstacle: point records, torque and resultant force on the obstacle.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactDistribution {
    /// Quadrature points in contact (pressure, friction, slip).
    pub records: Vec<ElementRecord>,
    /// Torque on the obstacle about its centre \[N·m\], Kerkkänen (3.26).
    pub torque: f64,
    /// Resultant force on the obstacle \[N\].
    pub reaction: Vector2<f64>,
}

impl<S: Surface<2>, NL: NormalLaw, FL: FrictionLaw> PulleyContact<S, NL, FL> {
    fn each<E: AncfElement>(
        &self, mesh: &AncfMesh<E>, q: &[f64], v: &[f64], jacobian: bool,
        mut sink: impl FnMut(usize, &ElementContact<2>),
        mut records: Option<&mut Vec<ElementRecord>>,
    ) {
        let mut e = [0.0; MAX_NDOF];
        let mut ed = [0.0; MAX_NDOF];
        let mut out = ElementContact::new(mesh.elements()[0].ndof());
        let mut rec = Vec::new();
        for (i, el) in mesh.elements().iter().enumerate() {
            let n = el.ndof();
            if out.ndof != n {
                out = ElementContact::new(n);
            }
            mesh.gather(q, i, &mut e);
            mesh.gather(v, i, &mut ed);
            let l = el.length();
            rec.clear();
            self.contact.element(
                l,
                n / 2,
                |xi, s| el.shape(xi * l, 0.0, s),
                &e[..n],
                &ed[..n],
                jacobian,
                &mut out,
                records.is_some().then_some(&mut rec),
            );
            if out.active_points > 0 {
                sink(i, &out);
            }
            if let Some(r) = records.as_deref_mut() {
                r.extend(
                    rec.iter()
                        .map(|&record| ElementRecord { element: i, record }),
                );
            }
        }
    }

    /// Contact records (pressure, friction, slip at every quadrature point in contact), torque
    /// and resultant force on the obstacle.
    pub fn distribution<E: AncfElement>(
        &self, mesh: &AncfMesh<E>, q: &[f64], v: &[f64],
    ) -> ContactDistribution {
        let mut records = Vec::new();
        let mut torque = 0.0;
        let mut reaction = Vector2::zeros();
        self.each(
            mesh,
            q,
            v,
            false,
            |_, o| {
                torque += o.moment;
                reaction += o.reaction;
            },
            Some(&mut records),
        );
        ContactDistribution {
            records,
            torque,
            reaction,
        }
    }
}

impl<E, S, NL, FL> MeshForce<E> for PulleyContact<S, NL, FL>
where
    E: AncfElement,
    S: Surface<2> + Send + Sync,
    NL: NormalLaw + Send + Sync,
    FL: FrictionLaw + Send + Sync,
{
    fn add_forces(&self, mesh: &AncfMesh<E>, _t: f64, q: &[f64], v: &[f64], f: &mut [f64]) {
        self.each(
            mesh,
            q,
            v,
            false,
            |i, o| mesh.scatter_add(f, i, &o.q, 1.0),
            None,
        );
    }

    fn add_tangent(
        &self, mesh: &AncfMesh<E>, _t: f64, q: &[f64], v: &[f64], k_vals: &mut [f64],
        c_vals: &mut [f64],
    ) {
        let pat = mesh.pattern();
        self.each(
            mesh,
            q,
            v,
            true,
            |i, o| {
                pat.add_element(k_vals, i, &o.dq_de, -1.0);
                pat.add_element(c_vals, i, &o.dq_dedot, -1.0);
            },
            None,
        );
    }
}
