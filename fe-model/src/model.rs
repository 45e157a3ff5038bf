//! A finite-element model: a [`Mesh`] plus its elements, with global matrix assembly.

use crate::FeError;
use crate::assembly::Assembler;
use crate::element::{Element, MassKind, MatrixKind};
use crate::mesh::Mesh;
use faer::sparse::SparseColMat;

/// Sparse global matrix type.
type SpMat = SparseColMat<usize, f64>;

/// Mesh and elements. Element DOFs are global DOFs of the mesh numbering.
#[derive(Debug)]
pub struct FeModel {
    /// Mesh (nodes, cells, node sets).
    pub mesh: Mesh,
    /// Elements.
    pub elements: Vec<Box<dyn Element>>,
}

impl FeModel {
    /// New model.
    pub fn new(mesh: Mesh) -> Self {
        Self {
            mesh,
            elements: Vec::new(),
        }
    }

    /// Add an element.
    pub fn push(&mut self, e: impl Element + 'static) {
        self.elements.push(Box::new(e));
    }

    /// Number of DOFs.
    pub fn n_dofs(&self) -> usize {
        self.mesh.n_dofs()
    }

    /// Build the reusable assembly pattern.
    pub fn assembler(&self) -> Result<Assembler, FeError> {
        Assembler::new(self.n_dofs(), &self.elements)
    }

    /// Assemble one global matrix (pattern built on the fly; keep an [`Assembler`] to reuse it).
    pub fn assemble(&self, kind: MatrixKind) -> Result<SparseColMat<usize, f64>, FeError> {
        self.assembler()?.assemble(&self.elements, kind)
    }

    /// Global elastic stiffness K.
    pub fn stiffness(&self) -> Result<SparseColMat<usize, f64>, FeError> {
        self.assemble(MatrixKind::Stiffness)
    }

    /// Global mass M.
    pub fn mass(&self, kind: MassKind) -> Result<SparseColMat<usize, f64>, FeError> {
        self.assemble(MatrixKind::Mass(kind))
    }

    /// Global geometric stiffness K_G.
    pub fn geometric_stiffness(&self) -> Result<SparseColMat<usize, f64>, FeError> {
        self.assemble(MatrixKind::Geometric)
    }

    /// Global matrices (K, M) with one shared pattern; `with_geometric` adds K_G to K.
    pub fn k_and_m(&self, mass: MassKind, with_geometric: bool) -> Result<(SpMat, SpMat), FeError> {
        let asm = self.assembler()?;
        let mut k = asm.assemble(&self.elements, MatrixKind::Stiffness)?;
        if with_geometric {
            let g = asm.assemble(&self.elements, MatrixKind::Geometric)?;
            // same pattern: add values in place
            for (a, b) in k.val_mut().iter_mut().zip(g.val().iter()) {
                *a += *b;
            }
        }
        let m = asm.assemble(&self.elements, MatrixKind::Mass(mass))?;
        Ok((k, m))
    }
}
