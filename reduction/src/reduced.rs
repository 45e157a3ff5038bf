//! The reduced model: basis, reduced matrices, DOF maps, recovery of full nodal fields, and a
//! versioned file format (so a large reduction is computed once).

use crate::basis::{Basis, Column, Method};
use crate::error::{ReductionError, Result};
use crate::linalg::{check_finite, check_square, congruence, eig_to_hz, sym_gen_eig, symmetrize};
use faer::{Mat, MatRef};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Identifier written in every reduced-model file.
pub const FORMAT_NAME: &str = "flowmbd-reduced-model";
/// Current file-format version. Files with another version are rejected with a clear message.
pub const FORMAT_VERSION: u32 = 1;

/// A reduced (Galerkin-projected) component: `δ = Ψ z`, `M_r = ΨᵀMΨ`, `K_r = ΨᵀKΨ`,
/// `C_r = ΨᵀCΨ` (Lin (6.6)–(6.9), (6.20)–(6.25)).
#[derive(Debug, Clone)]
pub struct ReducedModel {
    /// Method that produced the basis.
    pub method: Method,
    /// Number of DOFs per node of the full model (2 in 2-D, 3 in 3-D), for nodal recovery.
    pub dofs_per_node: usize,
    /// Meaning of each reduced coordinate (DOF map: boundary DOF or normal-mode index).
    pub columns: Vec<Column>,
    /// `n × n_z` basis Ψ, rows in natural DOF order.
    pub psi: Mat<f64>,
    /// Reduced mass `ΨᵀMΨ` \[kg or consistent units\].
    pub mass: Mat<f64>,
    /// Reduced stiffness `ΨᵀKΨ` \[N/m or consistent units\].
    pub stiffness: Mat<f64>,
    /// Reduced damping `ΨᵀCΨ` \[N·s/m\], if the full model had one.
    pub damping: Option<Mat<f64>>,
}

impl ReducedModel {
    /// Projects full dense `M`, `K` (and optional `C`) onto `basis`.
    pub fn from_basis(
        basis: Basis, k: MatRef<'_, f64>, m: MatRef<'_, f64>, c: Option<MatRef<'_, f64>>,
        dofs_per_node: usize,
    ) -> Result<Self> {
        let n = basis.psi.nrows();
        check_square("stiffness matrix K", k, n)?;
        check_square("mass matrix M", m, n)?;
        if dofs_per_node == 0 || !n.is_multiple_of(dofs_per_node) {
            return Err(ReductionError::InvalidParameter {
                name: "dofs_per_node".into(),
                reason: format!("{dofs_per_node} does not divide the number of DOFs {n}"),
            });
        }
        let p = basis.psi.as_ref();
        let damping = match c {
            Some(c) => {
                check_square("damping matrix C", c, n)?;
                Some(symmetrize(&congruence(p, c, p)))
            }
            None => None,
        };
        Ok(Self {
            method: basis.method,
            dofs_per_node,
            mass: symmetrize(&congruence(p, m, p)),
            stiffness: symmetrize(&congruence(p, k, p)),
            damping,
            columns: basis.columns,
            psi: basis.psi,
        })
    }

    /// Number of DOFs of the full model.
    pub fn n_full(&self) -> usize {
        self.psi.nrows()
    }

    /// Number of reduced coordinates.
    pub fn n_reduced(&self) -> usize {
        self.psi.ncols()
    }

    /// Boundary DOFs kept as physical coordinates, with their reduced-coordinate index.
    pub fn boundary_map(&self) -> Vec<(usize, usize)> {
        self.columns
            .iter()
            .enumerate()
            .filter_map(|(c, col)| match col {
                Column::Boundary { dof } => Some((*dof, c)),
                Column::Mode { .. } => None,
            })
            .collect()
    }

    /// Full nodal field `δ = Ψ z` (Lin (5.12)).
    pub fn recover(&self, z: &[f64]) -> Result<Vec<f64>> {
        if z.len() != self.n_reduced() {
            return Err(ReductionError::InvalidParameter {
                name: "reduced coordinates".into(),
                reason: format!("expected {} values, got {}", self.n_reduced(), z.len()),
            });
        }
        let n = self.n_full();
        let mut out = vec![0.0; n];
        for (j, &zj) in z.iter().enumerate() {
            if zj != 0.0 {
                for (i, o) in out.iter_mut().enumerate() {
                    *o += self.psi[(i, j)] * zj;
                }
            }
        }
        Ok(out)
    }

    /// Full field grouped per node (`dofs_per_node` components each).
    pub fn recover_nodal(&self, z: &[f64]) -> Result<Vec<Vec<f64>>> {
        let d = self.recover(z)?;
        Ok(d.chunks(self.dofs_per_node).map(|c| c.to_vec()).collect())
    }

    /// Reduced load `Ψᵀ f` (Lin (6.9)).
    pub fn reduce_load(&self, f: &[f64]) -> Result<Vec<f64>> {
        if f.len() != self.n_full() {
            return Err(ReductionError::InvalidParameter {
                name: "full load vector".into(),
                reason: format!("expected {} values, got {}", self.n_full(), f.len()),
            });
        }
        Ok((0..self.n_reduced())
            .map(|j| (0..f.len()).map(|i| self.psi[(i, j)] * f[i]).sum())
            .collect())
    }

    /// Natural frequencies of the reduced model \[Hz\], ascending (`eig(K_r, M_r)`).
    pub fn natural_frequencies_hz(&self) -> Result<Vec<f64>> {
        let (lam, _) = sym_gen_eig(
            "reduced model (K_r, M_r)",
            self.stiffness.as_ref(),
            self.mass.as_ref(),
        )?;
        Ok(eig_to_hz(&lam))
    }

    /// Serializes to the versioned JSON format.
    pub fn to_json(&self) -> Result<String> {
        let file = ReducedModelFile {
            format: FORMAT_NAME.to_string(),
            version: FORMAT_VERSION,
            method: self.method,
            n_full: self.n_full(),
            dofs_per_node: self.dofs_per_node,
            columns: self.columns.clone(),
            psi: DenseMatrix::from_mat(self.psi.as_ref()),
            mass: DenseMatrix::from_mat(self.mass.as_ref()),
            stiffness: DenseMatrix::from_mat(self.stiffness.as_ref()),
            damping: self
                .damping
                .as_ref()
                .map(|d| DenseMatrix::from_mat(d.as_ref())),
        };
        serde_json::to_string(&file).map_err(|e| ReductionError::File {
            path: "<memory>".into(),
            reason: e.to_string(),
        })
    }

    /// Parses the versioned JSON format; `origin` names the source in error messages.
    pub fn from_json(text: &str, origin: &str) -> Result<Self> {
        let err = |reason: String| ReductionError::File {
            path: origin.to_string(),
            reason,
        };
        // check the header first so that a version mismatch is reported as such
        let header: Header = serde_json::from_str(text).map_err(|e| {
            err(format!(
                "not a reduced-model file (line {}, column {}): {e}",
                e.line(),
                e.column()
            ))
        })?;
        if header.format != FORMAT_NAME {
            return Err(err(format!(
                "field `format` is \"{}\", expected \"{FORMAT_NAME}\"",
                header.format
            )));
        }
        if header.version != FORMAT_VERSION {
            return Err(err(format!(
                "field `version` is {}, this build reads version {FORMAT_VERSION}",
                header.version
            )));
        }
        let f: ReducedModelFile = serde_json::from_str(text)
            .map_err(|e| err(format!("line {}, column {}: {e}", e.line(), e.column())))?;
        let nz = f.columns.len();
        let psi = f.psi.to_mat("psi", f.n_full, nz).map_err(&err)?;
        let mass = f.mass.to_mat("mass", nz, nz).map_err(&err)?;
        let stiffness = f.stiffness.to_mat("stiffness", nz, nz).map_err(&err)?;
        let damping = match f.damping {
            Some(d) => Some(d.to_mat("damping", nz, nz).map_err(&err)?),
            None => None,
        };
        if f.dofs_per_node == 0 || !f.n_full.is_multiple_of(f.dofs_per_node) {
            return Err(err(format!(
                "field `dofs_per_node` = {} does not divide n_full = {}",
                f.dofs_per_node, f.n_full
            )));
        }
        for (c, col) in f.columns.iter().enumerate() {
            if let Column::Boundary { dof } = col
                && *dof >= f.n_full
            {
                return Err(err(format!(
                    "field `columns[{c}]`: boundary DOF {dof} >= n_full = {}",
                    f.n_full
                )));
            }
        }
        check_finite("psi", psi.as_ref()).map_err(|e| err(e.to_string()))?;
        Ok(Self {
            method: f.method,
            dofs_per_node: f.dofs_per_node,
            columns: f.columns,
            psi,
            mass,
            stiffness,
            damping,
        })
    }

    /// Writes the model to `path` (versioned JSON).
    pub fn save(&self, path: &Path) -> Result<()> {
        let text = self.to_json()?;
        fe_model::io::write_atomic(path, text.as_bytes()).map_err(|e| ReductionError::File {
            path: path.display().to_string(),
            reason: e.to_string(),
        })
    }

    /// Reads a model written by [`save`](Self::save).
    pub fn load(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| ReductionError::File {
            path: path.display().to_string(),
            reason: e.to_string(),
        })?;
        Self::from_json(&text, &path.display().to_string())
    }
}

#[derive(Deserialize, schemars::JsonSchema)]
struct Header {
    format: String,
    version: u32,
}

#[derive(Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct ReducedModelFile {
    format: String,
    version: u32,
    method: Method,
    n_full: usize,
    dofs_per_node: usize,
    columns: Vec<Column>,
    psi: DenseMatrix,
    mass: DenseMatrix,
    stiffness: DenseMatrix,
    damping: Option<DenseMatrix>,
}

/// Dense matrix in the file format: column-major values.
#[derive(Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
struct DenseMatrix {
    rows: usize,
    cols: usize,
    col_major: Vec<f64>,
}

impl DenseMatrix {
    fn from_mat(m: MatRef<'_, f64>) -> Self {
        let mut v = Vec::with_capacity(m.nrows() * m.ncols());
        for j in 0..m.ncols() {
            for i in 0..m.nrows() {
                v.push(m[(i, j)]);
            }
        }
        Self {
            rows: m.nrows(),
            cols: m.ncols(),
            col_major: v,
        }
    }

    fn to_mat(
        &self, field: &str, rows: usize, cols: usize,
    ) -> std::result::Result<Mat<f64>, String> {
        if self.rows != rows || self.cols != cols || self.col_major.len() != rows * cols {
            return Err(format!(
                "field `{field}` is {}x{} with {} values, expected {rows}x{cols}",
                self.rows,
                self.cols,
                self.col_major.len()
            ));
        }
        Ok(Mat::from_fn(rows, cols, |i, j| {
            self.col_major[j * rows + i]
        }))
    }
}
