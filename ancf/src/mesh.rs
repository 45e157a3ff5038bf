//! Planar ANCF meshes: two-node elements sharing nodes (closed loops share the first node),
//! constant sparse mass matrix, assembled elastic and gravity forces and tangent stiffness,
//! and the energies of Kerkkänen (2.34).

use crate::element::{AncfElement, MAX_NDOF, NodeLayout};
use crate::error::{AncfError, invalid};
use crate::sparse::Pattern;
use faer::sparse::SparseColMat;

/// A mesh of one element type. Global coordinates are ordered node by node
/// (`node · coords_per_node + k`).
#[derive(Debug, Clone)]
pub struct AncfMesh<E: AncfElement> {
    layout: NodeLayout,
    n_nodes: usize,
    elements: Vec<E>,
    connectivity: Vec<[usize; 2]>,
    pattern: Pattern,
    mass_values: Vec<f64>,
    element_mass: Vec<Vec<f64>>,
}

impl<E: AncfElement> AncfMesh<E> {
    /// Mesh of `elements` with `connectivity[i] = [node_I, node_J]` over `n_nodes` nodes.
    pub fn new(
        elements: Vec<E>, connectivity: Vec<[usize; 2]>, n_nodes: usize,
    ) -> Result<Self, AncfError> {
        if elements.is_empty() {
            return Err(invalid("mesh", "has no elements"));
        }
        if elements.len() != connectivity.len() {
            return Err(invalid(
                "mesh: connectivity",
                format!(
                    "{} elements but {} connectivity rows",
                    elements.len(),
                    connectivity.len()
                ),
            ));
        }
        let layout = elements[0].layout();
        for (i, (el, c)) in elements.iter().zip(&connectivity).enumerate() {
            if el.layout() != layout {
                return Err(invalid(format!("mesh: element {i}"), "mixes nodal layouts"));
            }
            if c[0] >= n_nodes || c[1] >= n_nodes || c[0] == c[1] {
                return Err(invalid(
                    format!("mesh: element {i}"),
                    format!("bad nodes {:?} (mesh has {n_nodes} nodes)", c),
                ));
            }
        }
        let cpn = layout.coords_per_node();
        let dofs: Vec<Vec<Option<usize>>> = connectivity
            .iter()
            .map(|c| {
                (0..2 * cpn)
                    .map(|k| Some(c[k / cpn] * cpn + k % cpn))
                    .collect()
            })
            .collect();
        let pattern = Pattern::new(n_nodes * cpn, &dofs);
        let mut mass_values = pattern.zeros();
        let mut element_mass = Vec::with_capacity(elements.len());
        for (i, el) in elements.iter().enumerate() {
            let n = el.ndof();
            let mut m = vec![0.0; n * n];
            el.mass_matrix(&mut m);
            pattern.add_element(&mut mass_values, i, &m, 1.0);
            element_mass.push(m);
        }
        Ok(Self {
            layout,
            n_nodes,
            elements,
            connectivity,
            pattern,
            mass_values,
            element_mass,
        })
    }

    /// Open chain `0–1–…–n` of `elements.len()` elements.
    pub fn chain(elements: Vec<E>) -> Result<Self, AncfError> {
        let n = elements.len();
        Self::new(elements, (0..n).map(|i| [i, i + 1]).collect(), n + 1)
    }

    /// Closed loop: element `i` joins nodes `i` and `(i + 1) mod n` — the last element shares
    /// the first node, which eliminates the closure constraints (Kerkkänen §2.3, option (b)).
    pub fn closed_loop(elements: Vec<E>) -> Result<Self, AncfError> {
        let n = elements.len();
        if n < 3 {
            return Err(invalid(
                "mesh: closed loop",
                format!("needs ≥ 3 elements, got {n}"),
            ));
        }
        Self::new(elements, (0..n).map(|i| [i, (i + 1) % n]).collect(), n)
    }

    /// Nodal layout.
    pub fn layout(&self) -> NodeLayout {
        self.layout
    }
    /// Coordinates per node.
    pub fn coords_per_node(&self) -> usize {
        self.layout.coords_per_node()
    }
    /// Number of nodes.
    pub fn n_nodes(&self) -> usize {
        self.n_nodes
    }
    /// Number of global coordinates.
    pub fn n_dof(&self) -> usize {
        self.n_nodes * self.coords_per_node()
    }
    /// Elements.
    pub fn elements(&self) -> &[E] {
        &self.elements
    }
    /// Connectivity.
    pub fn connectivity(&self) -> &[[usize; 2]] {
        &self.connectivity
    }
    /// Assembly pattern of the full system.
    pub fn pattern(&self) -> &Pattern {
        &self.pattern
    }

    /// Global index of local coordinate `k` of element `el`.
    #[inline]
    pub fn global_dof(&self, el: usize, k: usize) -> usize {
        let cpn = self.coords_per_node();
        self.connectivity[el][k / cpn] * cpn + k % cpn
    }

    /// Global index of coordinate `k` of `node`.
    #[inline]
    pub fn node_dof(&self, node: usize, k: usize) -> usize {
        node * self.coords_per_node() + k
    }

    /// Element coordinates of `el` gathered from the global vector `q` into `buf`: node by
    /// node, the element's coordinates `k` of node `k / cpn` at offset `k % cpn`
    /// ([`AncfMesh::global_dof`]) without a division per coordinate.
    #[inline]
    pub fn gather(&self, q: &[f64], el: usize, buf: &mut [f64]) {
        let n = self.elements[el].ndof();
        let cpn = self.coords_per_node();
        debug_assert!(n <= 2 * cpn);
        for (b, &node) in buf[..n].chunks_mut(cpn).zip(&self.connectivity[el]) {
            let base = node * cpn;
            b.copy_from_slice(&q[base..base + b.len()]);
        }
    }

    /// `f += scale · fe` scattered from element `el` (coordinate by coordinate in the
    /// element's order, node by node as [`AncfMesh::gather`]).
    #[inline]
    pub fn scatter_add(&self, f: &mut [f64], el: usize, fe: &[f64], scale: f64) {
        let n = self.elements[el].ndof();
        let cpn = self.coords_per_node();
        debug_assert!(n <= 2 * cpn);
        for (v, &node) in fe[..n].chunks(cpn).zip(&self.connectivity[el]) {
            let base = node * cpn;
            for (t, x) in f[base..base + v.len()].iter_mut().zip(v) {
                *t += scale * x;
            }
        }
    }

    /// Constant mass matrix values in [`AncfMesh::pattern`] (Kerkkänen (2.26)).
    pub fn mass_values(&self) -> &[f64] {
        &self.mass_values
    }

    /// Constant mass matrix as a faer CSC matrix.
    pub fn mass_matrix(&self) -> SparseColMat<usize, f64> {
        self.pattern.to_matrix(self.mass_values.clone())
    }

    /// Element mass matrix (column-major).
    pub fn element_mass(&self, el: usize) -> &[f64] {
        &self.element_mass[el]
    }

    /// Assembled elastic forces `Q_e(q)` (overwrites `f`) \[N\].
    pub fn elastic_forces(&self, q: &[f64], f: &mut [f64]) {
        f.fill(0.0);
        let mut e = [0.0; MAX_NDOF];
        let mut fe = [0.0; MAX_NDOF];
        for (i, el) in self.elements.iter().enumerate() {
            self.gather(q, i, &mut e);
            el.elastic_forces(&e, &mut fe);
            self.scatter_add(f, i, &fe, 1.0);
        }
    }

    /// Assembled elastic forces into `f` and tangent stiffness `∂²U/∂q²` values (in the
    /// pattern `pattern`, with element-to-pattern scatter as built for this mesh's element order)
    /// added into `k_vals` times `k_scale`. `f` is overwritten, `k_vals` accumulated.
    pub fn elastic_tangent_into(
        &self, q: &[f64], f: &mut [f64], pattern: &Pattern, k_vals: &mut [f64], k_scale: f64,
    ) {
        f.fill(0.0);
        let mut e = [0.0; MAX_NDOF];
        let mut fe = [0.0; MAX_NDOF];
        let mut ke = [0.0; MAX_NDOF * MAX_NDOF];
        for (i, el) in self.elements.iter().enumerate() {
            let n = el.ndof();
            self.gather(q, i, &mut e);
            el.elastic_tangent(&e, &mut fe, &mut ke[..n * n]);
            self.scatter_add(f, i, &fe, 1.0);
            pattern.add_element(k_vals, i, &ke[..n * n], k_scale);
        }
    }

    /// Strain energy `U = Σ Uᵢ` \[J\].
    pub fn strain_energy(&self, q: &[f64]) -> f64 {
        let mut e = [0.0; MAX_NDOF];
        let mut u = 0.0;
        for (i, el) in self.elements.iter().enumerate() {
            self.gather(q, i, &mut e);
            u += el.strain_energy(&e[..el.ndof()]);
        }
        u
    }

    /// Kinetic energy `T = ½ vᵀ M v` \[J\] (Kerkkänen (2.34)).
    pub fn kinetic_energy(&self, v: &[f64]) -> f64 {
        let mut mv = vec![0.0; v.len()];
        self.pattern.mul_vec(&self.mass_values, v, &mut mv);
        0.5 * v.iter().zip(&mv).map(|(a, b)| a * b).sum::<f64>()
    }

    /// Generalized gravity forces `Q_g = Σ ∫ρ Sᵀ g dV` for acceleration `g` \[m/s²\].
    pub fn gravity_forces(&self, g: [f64; 2]) -> Vec<f64> {
        let mut f = vec![0.0; self.n_dof()];
        let mut fe = [0.0; MAX_NDOF];
        for (i, el) in self.elements.iter().enumerate() {
            el.gravity_forces(g, &mut fe);
            self.scatter_add(&mut f, i, &fe, 1.0);
        }
        f
    }

    /// Position of material point `(x, y)` of element `el` \[m\].
    pub fn position(&self, q: &[f64], el: usize, x: f64, y: f64) -> [f64; 2] {
        let mut e = [0.0; MAX_NDOF];
        self.gather(q, el, &mut e);
        self.elements[el].position(&e, x, y)
    }

    /// Position `r` of `node` \[m\].
    pub fn node_position(&self, q: &[f64], node: usize) -> [f64; 2] {
        let k = self.node_dof(node, 0);
        [q[k], q[k + 1]]
    }

    /// Coordinates of the straight, stress-free configuration with nodes at `points` and unit
    /// tangents `tangents` (`r_x = t`, `r_y = Ĩ t`).
    pub fn coordinates_from_nodes(&self, points: &[[f64; 2]], tangents: &[[f64; 2]]) -> Vec<f64> {
        let mut q = Vec::with_capacity(self.n_dof());
        for (p, t) in points.iter().zip(tangents) {
            q.extend(self.layout.node_coordinates(*p, *t, 1.0));
        }
        q
    }
}

/// Reference coordinates of a straight beam from `start` to `end` with `n_el` equal elements.
pub fn straight_coordinates(
    layout: NodeLayout, start: [f64; 2], end: [f64; 2], n_el: usize,
) -> Vec<f64> {
    let d = [end[0] - start[0], end[1] - start[1]];
    let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
    let t = [d[0] / len, d[1] / len];
    (0..=n_el)
        .flat_map(|i| {
            let s = i as f64 / n_el as f64;
            layout.node_coordinates([start[0] + s * d[0], start[1] + s * d[1]], t, 1.0)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::belt_drive::{BeltDrive, BeltDriveSpec};
    use crate::element::AncfElement;

    // Reference: the coordinate-by-coordinate loops through `global_dof` (node `k / cpn`,
    // offset `k % cpn`) that `gather` and `scatter_add` ran before, bit for bit, on every
    // element of a closed belt loop (its last element ends on node 0), with the scatters of
    // all elements summed in the same order.
    #[test]
    fn node_by_node_gather_and_scatter_are_the_coordinate_loops_bit_for_bit() {
        let drive = BeltDrive::new(BeltDriveSpec::default()).unwrap();
        let mesh = drive.mesh();
        let n = mesh.n_dof();
        let q: Vec<f64> = (0..n).map(|i| ((i * 7 + 3) as f64 * 0.37).sin()).collect();
        let (mut f, mut f_ref) = (vec![0.25; n], vec![0.25; n]);
        let last = mesh.elements().len() - 1;
        assert_eq!(mesh.connectivity()[last][1], 0, "a closed loop");
        for el in 0..mesh.elements().len() {
            let nd = mesh.elements()[el].ndof();
            let mut e = vec![f64::NAN; nd];
            mesh.gather(&q, el, &mut e);
            let fe: Vec<f64> = (0..nd)
                .map(|k| ((el * 13 + k) as f64 * 0.91).cos())
                .collect();
            mesh.scatter_add(&mut f, el, &fe, -1.7);
            for k in 0..nd {
                let g = mesh.global_dof(el, k);
                assert_eq!(
                    e[k].to_bits(),
                    q[g].to_bits(),
                    "element {el}, coordinate {k}"
                );
                f_ref[g] += -1.7 * fe[k];
            }
        }
        for (a, b) in f.iter().zip(&f_ref) {
            assert_eq!(a.to_bits(), b.to_bits());
        }
    }
}
