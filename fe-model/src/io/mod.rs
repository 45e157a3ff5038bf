//! Matrix and mesh exchange: Matrix Market, ABAQUS matrix output, VTK (.vtu), sprs.

pub mod abaqus;
pub mod mtx;
#[cfg(feature = "sprs")]
pub mod sprs_conv;
pub mod vtk;
