//! # fe-model
//!
//! Finite-element models for flowmbd: meshes with node/DOF numbering and named node sets, elements
//! (string, bar, 2D/3D frames, hexahedra, point masses and springs) with stiffness, mass and
//! geometric stiffness, sparse assembly of M, K and Rayleigh C into faer matrices, parametric mesh
//! generators (beam, two-pulley belt loop, truck-tire carcass), Matrix Market / ABAQUS / VTK
//! exchange, and generalized eigen solvers for `K φ = λ M φ` (dense and sparse shift-invert).
