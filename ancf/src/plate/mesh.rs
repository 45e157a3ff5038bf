//! Meshes of ANCF thin-plate elements: nodes with 9 coordinates `[r, r_x, r_y]` shared between
//! elements, sparse assembly of the constant mass matrix, elastic forces and tangent.

use super::element::{PLATE_NDOF, ThinPlate};
use crate::error::{AncfError, invalid};
use crate::material::Material;
use faer::Mat;
use faer::sparse::{SparseColMat, Triplet};

/// Coordinates per plate node: `r`, `r_x`, `r_y` (3 components each), Kerkkänen (4.14).
pub const PLATE_NODE_COORDS: usize = 9;

/// One element of a [`PlateMesh`]: its corner nodes A, B, C, D (counter-clockwise in the
/// element's `x, y` plane) and the element itself.
#[derive(Debug, Clone, PartialEq)]
pub struct PlateCell {
    /// Global node indices of the corners A (0, 0), B (a, 0), C (a, b), D (0, b).
    pub nodes: [usize; 4],
    /// The element.
    pub plate: ThinPlate,
}

/// A mesh of thin-plate elements with shared nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct PlateMesh {
    /// Number of nodes.
    pub n_nodes: usize,
    /// The elements.
    pub cells: Vec<PlateCell>,
}

impl PlateMesh {
    /// A flat rectangular `lx × ly` plate \[m\] in the global `x, y` plane with its corner at the
    /// origin, `nx × ny` equal elements; returns the mesh and its reference coordinates
    /// (`r = (x, y, 0)`, `r_x = (1, 0, 0)`, `r_y = (0, 1, 0)` at every node). Node `(i, j)` has
    /// index `j (nx + 1) + i`.
    #[allow(clippy::too_many_arguments)]
    pub fn rectangle(
        lx: f64, ly: f64, nx: usize, ny: usize, thickness: f64, material: Material, bending: bool,
        gauss: usize,
    ) -> Result<(Self, Vec<f64>), AncfError> {
        if nx == 0 || ny == 0 {
            return Err(invalid(
                "plate mesh: elements",
                format!("needs at least one element per direction, got {nx} × {ny}"),
            ));
        }
        let plate = ThinPlate::new(
            lx / nx as f64,
            ly / ny as f64,
            thickness,
            material,
            bending,
            gauss,
        )
        .map_err(|e| match e {
            AncfError::InvalidInput { item, reason } => {
                invalid(format!("plate mesh: {item}"), reason)
            }
            other => other,
        })?;
        let node = |i: usize, j: usize| j * (nx + 1) + i;
        let mut cells = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                cells.push(PlateCell {
                    nodes: [
                        node(i, j),
                        node(i + 1, j),
                        node(i + 1, j + 1),
                        node(i, j + 1),
                    ],
                    plate: plate.clone(),
                });
            }
        }
        let n_nodes = (nx + 1) * (ny + 1);
        let mut q = vec![0.0; PLATE_NODE_COORDS * n_nodes];
        for j in 0..=ny {
            for i in 0..=nx {
                let o = PLATE_NODE_COORDS * node(i, j);
                q[o] = lx * i as f64 / nx as f64;
                q[o + 1] = ly * j as f64 / ny as f64;
                q[o + 3] = 1.0;
                q[o + 7] = 1.0;
            }
        }
        Ok((Self { n_nodes, cells }, q))
    }

    /// Number of generalized coordinates (`9 × nodes`).
    pub fn n_coords(&self) -> usize {
        PLATE_NODE_COORDS * self.n_nodes
    }

    /// Global indices of the 36 coordinates of `cell`.
    pub fn cell_dofs(&self, cell: &PlateCell) -> [usize; PLATE_NDOF] {
        std::array::from_fn(|i| PLATE_NODE_COORDS * cell.nodes[i / 9] + i % 9)
    }

    fn check(&self, q: &[f64]) -> Result<(), AncfError> {
        if q.len() != self.n_coords() {
            return Err(invalid(
                "plate mesh: coordinates",
                format!("expected {} values, got {}", self.n_coords(), q.len()),
            ));
        }
        if let Some(i) = q.iter().position(|v| !v.is_finite()) {
            return Err(AncfError::NonFinite {
                what: format!("plate coordinate {i} (node {})", i / PLATE_NODE_COORDS),
            });
        }
        Ok(())
    }

    fn element_coords(&self, cell: &PlateCell, q: &[f64]) -> [f64; PLATE_NDOF] {
        let dofs = self.cell_dofs(cell);
        std::array::from_fn(|i| q[dofs[i]])
    }

    /// Constant sparse mass matrix (Kerkkänen (2.26)) \[kg\].
    pub fn mass(&self) -> Result<SparseColMat<usize, f64>, AncfError> {
        let mut t = Vec::with_capacity(self.cells.len() * PLATE_NDOF * 12);
        for cell in &self.cells {
            let m = cell.plate.mass_matrix();
            push_block(&mut t, &self.cell_dofs(cell), &m);
        }
        self.sparse(&t)
    }

    /// Strain energy of the mesh \[J\].
    pub fn strain_energy(&self, q: &[f64]) -> Result<f64, AncfError> {
        self.check(q)?;
        Ok(self
            .cells
            .iter()
            .map(|c| c.plate.strain_energy(&self.element_coords(c, q)))
            .sum())
    }

    /// Assembled elastic forces `Q_e = −∂U/∂q` \[N\].
    pub fn elastic_forces(&self, q: &[f64]) -> Result<Vec<f64>, AncfError> {
        self.check(q)?;
        let mut f = vec![0.0; self.n_coords()];
        let mut qe = [0.0; PLATE_NDOF];
        for cell in &self.cells {
            cell.plate
                .elastic_forces(&self.element_coords(cell, q), &mut qe);
            for (i, d) in self.cell_dofs(cell).iter().enumerate() {
                f[*d] += qe[i];
            }
        }
        Ok(f)
    }

    /// Assembled elastic forces \[N\] and sparse tangent stiffness `∂²U/∂q²` \[N/m\].
    pub fn elastic_tangent(
        &self, q: &[f64],
    ) -> Result<(Vec<f64>, SparseColMat<usize, f64>), AncfError> {
        let map: Vec<Option<usize>> = (0..self.n_coords()).map(Some).collect();
        self.elastic_tangent_mapped(q, &map, self.n_coords())
    }

    /// Elastic forces \[N\] (all coordinates) and the tangent stiffness \[N/m\] restricted to the
    /// coordinates with `map[i] = Some(row)`, as an `n × n` sparse matrix in those rows (the
    /// unknowns of a solve with supports eliminated).
    pub fn elastic_tangent_mapped(
        &self, q: &[f64], map: &[Option<usize>], n: usize,
    ) -> Result<(Vec<f64>, SparseColMat<usize, f64>), AncfError> {
        self.check(q)?;
        if map.len() != self.n_coords() || map.iter().flatten().any(|&r| r >= n) {
            return Err(invalid(
                "plate mesh: coordinate map",
                format!("needs {} entries with rows below {n}", self.n_coords()),
            ));
        }
        let mut f = vec![0.0; self.n_coords()];
        let mut qe = [0.0; PLATE_NDOF];
        let mut ke = Mat::<f64>::zeros(PLATE_NDOF, PLATE_NDOF);
        let mut t = Vec::with_capacity(self.cells.len() * PLATE_NDOF * PLATE_NDOF);
        for cell in &self.cells {
            cell.plate
                .elastic_tangent(&self.element_coords(cell, q), &mut qe, &mut ke);
            let dofs = self.cell_dofs(cell);
            for (i, d) in dofs.iter().enumerate() {
                f[*d] += qe[i];
            }
            let rows: [Option<usize>; PLATE_NDOF] = std::array::from_fn(|i| map[dofs[i]]);
            for (j, cj) in rows.iter().enumerate() {
                let Some(cj) = cj else { continue };
                for (i, ri) in rows.iter().enumerate() {
                    let Some(ri) = ri else { continue };
                    let v = ke[(i, j)];
                    if v != 0.0 {
                        t.push(Triplet::new(*ri, *cj, v));
                    }
                }
            }
        }
        let k = SparseColMat::try_new_from_triplets(n, n, &t).map_err(|e| {
            invalid(
                "plate mesh: assembly",
                format!("sparse matrix could not be built: {e:?}"),
            )
        })?;
        Ok((f, k))
    }

    /// Assembled gravity forces \[N\] for the acceleration `g` \[m/s²\].
    pub fn gravity_forces(&self, g: [f64; 3]) -> Vec<f64> {
        let mut f = vec![0.0; self.n_coords()];
        for cell in &self.cells {
            let qg = cell.plate.gravity_forces(g);
            for (i, d) in self.cell_dofs(cell).iter().enumerate() {
                f[*d] += qg[i];
            }
        }
        f
    }

    fn sparse(
        &self, t: &[Triplet<usize, usize, f64>],
    ) -> Result<SparseColMat<usize, f64>, AncfError> {
        let n = self.n_coords();
        SparseColMat::try_new_from_triplets(n, n, t).map_err(|e| {
            invalid(
                "plate mesh: assembly",
                format!("sparse matrix could not be built: {e:?}"),
            )
        })
    }
}

fn push_block(t: &mut Vec<Triplet<usize, usize, f64>>, dofs: &[usize; PLATE_NDOF], m: &Mat<f64>) {
    for (j, &dj) in dofs.iter().enumerate() {
        for (i, &di) in dofs.iter().enumerate() {
            let v = m[(i, j)];
            if v != 0.0 {
                t.push(Triplet::new(di, dj, v));
            }
        }
    }
}
