//! # ancf
//!
//! Absolute nodal coordinate formulation elements (Kerkkänen 2006): the 2D shear-deformable
//! linear beam, the Omar–Shabana beam, the 2D belt element, planar belt drives built from them, and the thin plate element.
//!
//! * [`element`]: the [`AncfElement`] trait and the three planar elements;
//! * [`mesh`]: meshes with shared nodes (closed loops), sparse constant mass, assembled forces
//!   and tangents, energies;
//! * [`mounted`]: the one model shell of the ANCF belt drives ([`mounted::MountedBelt`]: the
//!   planar and the plate belt as [`::belt::BeltModel`]s);
//! * [`plate`]: the 36-coordinate thin plate element of Kerkkänen §4.3 and plate meshes;
//! * [`statics`]: Newton–Raphson with load increments and line search, and
//!   [`solve_static_unilateral`] (frictionless node contact by Lagrange multipliers with an
//!   active set);
//! * [`system`]: meshes as mbd-core systems, and [`integrate_unilateral`] (generalized-α with
//!   the same unilateral contact);
//! * [`node_contact`]: nodal penalty contact ([`NodalContact`]), the penalty counterpart;
//! * [`beam_mesh`]: straight chains of the chapter-2 beam elements ([`beam_mesh::BeamElementKind`]).
//!
//! The paper cases built from these (Kerkkänen §2.4 test set-ups) live in `flowmbd-cases`.

// Index loops mirror the element and quadrature formulas (several arrays per index).
#![allow(clippy::needless_range_loop)]

pub mod autodiff;
pub mod beam_mesh;
pub mod belt;
pub mod belt_drive;
pub mod element;
pub mod error;
pub mod material;
pub mod mesh;
pub mod mounted;
pub mod node_contact;
pub mod plate;
pub mod pulley;
pub mod section;
pub mod shape;
pub mod sparse;
pub mod statics;
pub mod system;

pub use element::{AncfElement, BeltElement, NodeLayout, OmarShabanaBeam, ProposedBeam};
pub use error::AncfError;
pub use material::Material;
pub use mesh::AncfMesh;
pub use node_contact::NodalContact;
pub use pulley::{ContactDistribution, PulleyContact};
pub use section::Section;
pub use statics::{
    AncfStaticOptions, AncfStaticSolution, UnilateralOptions, UnilateralSolution, solve_static,
    solve_static_unilateral, solve_static_with,
};
pub use system::{AncfSystem, ContactStep, Energies, MeshForce, Prescribed, integrate_unilateral};
