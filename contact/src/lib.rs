//! # contact
//!
//! Contact in the plane and in space from one implementation: obstacle geometry, normal laws
//! (linear and polynomial penalty, unilateral Lagrange constraints) and friction laws
//! (Coulomb–tanh, creep-rate, Coulomb slip, …) behind small traits, the contact of one point
//! with exact derivatives and distributed contact over elements by quadrature, all generic over
//! the dimension `D = 2, 3` with nalgebra points, vectors and matrices.
//!
//! * [`dim`]: [`ContactDim`] — what differs between the plane and space (the tangent basis,
//!   `t = Ĩ n` of Kerkkänen (3.6) or the projected reference tangent; the friction law's slip
//!   argument; the moment of a force), implemented by [`Dim<2>`] and [`Dim<3>`];
//! * [`geometry`]: [`Surface`] and its closest-point data [`SurfacePoint`], with the planar
//!   [`Disk`], [`HalfPlane`], [`CleatedDrum`], [`CleatedRoad`]; [`spatial`] holds the spatial
//!   shapes ([`spatial::Cylinder`] (optionally crowned), [`spatial::FlangedCylinder`],
//!   [`spatial::CleatedDrum3`], [`spatial::CleatedRoad3`], [`spatial::HalfSpace`]);
//! * [`normal`]: [`NormalLaw`] with [`LinearPenalty`] (Kerkkänen (3.20)) and
//!   [`PolynomialPenalty`] (Ribaric (6.1)), and [`NormalSpec`] for configuration;
//! * [`friction`]: the one [`FrictionLaw`] trait (planar and spatial slip, smooth or
//!   set-valued with the Alart–Curnier projection) with [`CoulombTanh`] (Ribaric (6.2)),
//!   [`CreepRate`] (Kerkkänen Fig. 3.3), [`Coulomb`] (Ribaric §7.3, §8.4.3),
//!   [`SlipRegularized`] (Ribaric U20), [`Stribeck`], and [`FrictionSpec`] for configuration;
//! * [`point`]: [`point_contact`], the contact of one material point with exact derivatives
//!   (Kerkkänen (3.20)–(3.25) and their spatial form);
//! * [`distributed`]: [`element_contact`], quadrature contact over an element (Kerkkänen
//!   (3.26)–(3.27)), with [`LineContact`] (a Gauss rule along line elements) and
//!   [`SurfaceContact`] (quadrature points of surface elements, the plate belt of Kerkkänen
//!   ch. 4);
//! * [`lagrange`]: unilateral constraint rows and an active set (used by the ancf crate's static
//!   and generalized-α contact solvers);
//! * [`solver`]: the shared non-smooth solver of many coupled point contacts, [`ContactSolver`]
//!   (semismooth Newton on the Alart–Curnier equations for any [`FrictionLaw`], over a
//!   Delassus operator supplied by the model through [`DelassusSource`], with warm starts, a
//!   tolerance and a [`ContactSolverReport`]; the normal LCP [`solver::LcpWork`] as its
//!   fallback), used by the rolling tire and by any model that can give its compliance.

// Index loops mirror the element and quadrature formulas (several arrays per index).
#![allow(clippy::needless_range_loop)]

pub mod dim;
pub mod distributed;
pub mod friction;
pub mod geometry;
pub mod lagrange;
mod lanes;
pub mod normal;
pub mod point;
pub mod quadrature;
pub mod solver;
pub mod spatial;

pub use dim::{ContactDim, Dim, TangentialForce};
pub use distributed::{
    BlockQuadrature, BlockShape, ContactRecord, ElementContact, LineContact, QuadPoint,
    ShapeMatrix, SurfaceContact, element_contact, element_forces_blocks,
};
pub use friction::{
    Augmented, Coulomb, CoulombTanh, CreepRate, FrictionForce, FrictionLaw, FrictionSpec,
    Frictionless, SlipRegularized, Stribeck, TangentFriction,
};
pub use geometry::{
    CleatedDrum, CleatedRoad, Disk, HalfPlane, Surface, SurfacePoint, SurfacePoint2, SurfaceValues,
    rot90,
};
pub use lagrange::{ActiveSet, UnilateralRow, unilateral_row};
pub use normal::{LinearPenalty, NormalForce, NormalLaw, NormalSpec, PolynomialPenalty};
pub use point::{
    PointContact, PointContact2, PointContact3, PointForce, point_contact, point_force,
    point_force_at, point_slip,
};
pub use quadrature::GaussRule;
pub use solver::{
    ContactSolver, ContactSolverOptions, ContactSolverReport, DelassusSource, DenseProblem,
};
