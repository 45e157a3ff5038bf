//! # contact
//!
//! Contact geometry (circles, drums with cleats, planes), normal laws (linear and polynomial
//! penalty, unilateral Lagrange constraints) and friction laws (Coulomb–tanh, creep-rate, Coulomb
//! slip) behind small traits, with distributed contact along elements by Gauss quadrature.
//!
//! * [`geometry`]: [`Surface`] with [`Disk`], [`HalfPlane`], [`CleatedDrum`], [`CleatedRoad`];
//! * [`normal`]: [`NormalLaw`] with [`LinearPenalty`] (Kerkkänen (3.20)) and
//!   [`PolynomialPenalty`] (Ribaric (6.1)), and [`NormalSpec`] for configuration;
//! * [`friction`]: the one [`FrictionLaw`] trait (planar and spatial slip, smooth or
//!   set-valued with the Alart–Curnier projection) with [`CoulombTanh`] (Ribaric (6.2)),
//!   [`CreepRate`] (Kerkkänen Fig. 3.3), [`Coulomb`] (Ribaric §7.3, §8.4.3),
//!   [`SlipRegularized`] (Ribaric U20), [`Stribeck`], and [`FrictionSpec`] for configuration;
//! * [`point`]: nodal contact with exact derivatives;
//! * [`distributed`]: Gauss-quadrature contact along elements (Kerkkänen (3.26)–(3.27));
//! * [`spatial`]: 3D contact — [`spatial::Cylinder`] (optionally crowned),
//!   [`spatial::FlangedCylinder`], [`spatial::CleatedDrum3`], [`spatial::CleatedRoad3`],
//!   [`spatial::HalfSpace`],
//!   [`spatial::point_contact_3d`] with the slip 2-vector of the same friction laws,
//!   [`spatial::SurfaceContact`] for quadrature contact over surface elements;
//! * [`lagrange`]: unilateral constraints with an active set (used by the ancf crate's static
//!   and generalized-α contact solvers).

// Index loops mirror the element and quadrature formulas (several arrays per index).
#![allow(clippy::needless_range_loop)]

pub mod distributed;
pub mod friction;
pub mod geometry;
pub mod lagrange;
pub mod normal;
pub mod point;
pub mod quadrature;
pub mod spatial;

pub use distributed::{ContactRecord, ElementContact, LineContact};
pub use friction::{
    Augmented, Coulomb, CoulombTanh, CreepRate, FrictionForce, FrictionLaw, FrictionSpec,
    Frictionless, SlipRegularized, Stribeck, TangentFriction,
};
pub use geometry::{CleatedDrum, CleatedRoad, Disk, HalfPlane, Surface, SurfacePoint};
pub use lagrange::{ActiveSet, UnilateralRow, unilateral_row};
pub use normal::{LinearPenalty, NormalForce, NormalLaw, NormalSpec, PolynomialPenalty};
pub use point::{PointContact, point_contact};
pub use quadrature::GaussRule;
