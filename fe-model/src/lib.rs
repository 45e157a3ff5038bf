//! # fe-model
//!
//! Finite-element models for flowmbd: meshes with node/DOF numbering and named node sets, elements
//! (string, bar, 2D/3D frames, hexahedra, point masses and springs) with stiffness, mass and
//! geometric stiffness, sparse assembly of M, K and Rayleigh C into faer matrices, parametric mesh
//! generators (beam, two-pulley belt loop, truck-tire carcass), Matrix Market / ABAQUS / VTK
//! exchange, and generalized eigen solvers for `K φ = λ M φ` (dense and sparse shift-invert).

pub mod assembly;
pub mod damping;
pub mod eigen;
pub mod element;
pub mod error;
pub mod generate;
pub mod io;
pub mod mesh;
pub mod model;
pub mod partition;
pub mod plausibility;
pub mod sparse;

pub use assembly::{Assembler, assemble};
pub use damping::Rayleigh;
pub use eigen::{Modes, SparseEigenOptions, dense_modes, sparse_modes};
pub use element::{Element, MassKind, MatrixKind};
pub use error::FeError;
pub use mesh::{Cell, CellKind, Mesh};
pub use model::FeModel;
pub use partition::DofSplit;
