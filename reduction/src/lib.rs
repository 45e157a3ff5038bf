//! # reduction
//!
//! Reduction bases for deformable bodies (Lin 2005, Ribaric 2012 ch. 3): static condensation
//! (Guyan), fixed-interface and free-free modal truncation, Craig–Bampton, mode condensation and
//! Eitelberg's method (with a Bartels–Stewart Lyapunov solver, [`lyapunov`]); axis (reference)
//! conditions (nodal-fixed, mean, principal axes) applied to them; the [`ReducedModel`] with
//! recovery of nodal fields and a versioned file format. Lin's example models and studies (the
//! Appendix A beam, the Appendix B slab and its simulations 1–3) live in `flowmbd-cases`.
//!
//! Floating-frame bodies that use these bases live in `mbd-core::floating` (layering: the basis
//! is plain data handed down).

pub mod axes;
pub mod basis;
pub mod eitelberg;
pub mod eitelberg_model;
pub mod error;
pub mod linalg;
pub mod lyapunov;
pub mod mean_axes_eval;
pub mod partition;
pub mod reduced;
pub mod sparse;

pub use basis::{Basis, Column, Method, ModeSelection, build_basis};
pub use error::ReductionError;
pub use partition::DofPartition;
pub use reduced::ReducedModel;
