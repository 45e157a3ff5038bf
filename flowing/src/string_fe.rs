//! The string FE model (Ribaric (4.1)) on a flow grid, built with fe-model's string element,
//! and its fixed-end normal modes (Ribaric (4.4)–(4.7)) from fe-model's eigen solver.

use crate::derivative::FlowLine;
use crate::error::{FlowError, invalid};
use crate::grid::{End, FlowGrid, Topology};
use crate::modal::ModalBasis;
use crate::params::StringConfig;
use faer::Mat;
use fe_model::element::string::StringElement;
use fe_model::{Element, MassKind, MatrixKind, assemble, dense_modes};
use mbd_core::SysMatrix;

/// A string between two fixed ends: interior nodes on a [`FlowGrid`] with zero-value ends,
/// `M` and `K` of the interior DOFs (one transverse DOF per node, DOF `j` = grid node `j`).
#[derive(Debug, Clone)]
pub struct StringMesh {
    /// Interior nodes with fixed (zero-value) ends.
    pub grid: FlowGrid,
    /// Mass matrix of the interior DOFs \[kg\].
    pub mass: Mat<f64>,
    /// Stiffness matrix of the interior DOFs \[N/m\].
    pub stiffness: Mat<f64>,
    /// String parameters (`length` is ignored; the grid's ends define the span).
    pub params: StringConfig,
}

impl StringMesh {
    /// Assembles fe-model [`StringElement`]s between consecutive nodes of `grid` (which must be
    /// open with two zero-value ends) and keeps the interior block (fixed ends, Ribaric (4.4)).
    pub fn new(params: StringConfig, grid: FlowGrid, mass: MassKind) -> Result<Self, FlowError> {
        params.validate()?;
        let Topology::Open {
            start: End::Zero(a),
            end: End::Zero(b),
        } = grid.topology()
        else {
            return Err(invalid(
                "string mesh: grid",
                "needs an open grid with two fixed (zero-value) ends",
            ));
        };
        let n = grid.len();
        let mut x = Vec::with_capacity(n + 2);
        x.push(a);
        x.extend_from_slice(grid.positions());
        x.push(b);
        let mut elements: Vec<Box<dyn Element>> = Vec::with_capacity(n + 1);
        for e in 0..=n {
            elements.push(Box::new(StringElement::new(
                [e, e + 1],
                x[e + 1] - x[e],
                params.tension,
                params.mu(),
            )?));
        }
        let k = assemble(n + 2, &elements, MatrixKind::Stiffness)?.to_dense();
        let m = assemble(n + 2, &elements, MatrixKind::Mass(mass))?.to_dense();
        let interior = |a: &Mat<f64>| Mat::from_fn(n, n, |i, j| a[(i + 1, j + 1)]);
        Ok(Self {
            mass: interior(&m),
            stiffness: interior(&k),
            grid,
            params,
        })
    }

    /// Ribaric's uniform string (4.1): `n` interior nodes, `h = L/(n+1)`, lumped mass.
    pub fn uniform(params: StringConfig, n: usize) -> Result<Self, FlowError> {
        params.validate()?;
        let grid = FlowGrid::uniform_fixed(0.0, params.length, n)?;
        Self::new(params, grid, MassKind::Lumped)
    }

    /// Number of DOFs.
    pub fn n_dofs(&self) -> usize {
        self.grid.len()
    }

    /// The lowest `count` fixed-end normal modes (`ΨᵀMΨ = I`, `ΨᵀKΨ = Λ`, Ribaric (4.7)) from
    /// fe-model's dense generalized eigen solver.
    pub fn modes(&self, count: usize) -> Result<ModalBasis, FlowError> {
        if count == 0 || count > self.n_dofs() {
            return Err(invalid(
                "string modes: count",
                format!(
                    "asked for {count} modes of a model with {} DOFs",
                    self.n_dofs()
                ),
            ));
        }
        let modes = dense_modes(self.stiffness.as_ref(), self.mass.as_ref(), count)?;
        ModalBasis::new(modes.vectors, modes.values)
    }

    /// The flow line of the string's DOFs (DOF `j` at grid node `j`).
    pub fn flow_line(&self) -> FlowLine {
        FlowLine::strided(self.grid.clone(), 0, 1)
    }

    /// Mass matrix as a [`SysMatrix`].
    pub fn mass_sys(&self) -> SysMatrix {
        SysMatrix::Dense(self.mass.clone())
    }
}
