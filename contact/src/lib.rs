//! # contact
//!
//! Contact geometry (circles, drums with cleats, planes), normal laws (linear and polynomial
//! penalty, unilateral Lagrange constraints) and friction laws (Coulomb–tanh, creep-rate, Coulomb
//! slip) behind small traits, with distributed contact along elements by Gauss quadrature.
//!
//! * [`geometry`]: [`Surface`] with [`Disk`], [`HalfPlane`], [`CleatedDrum`], [`CleatedRoad`];
//! * [`normal`]: [`NormalLaw`] with [`LinearPenalty`] (Kerkkänen (3.20)) and
//!   [`PolynomialPenalty`] (Ribaric (6.1));
//! * [`friction`]: [`FrictionLaw`] with [`CoulombTanh`] (Ribaric (6.2)), [`CreepRate`]
//!   (Kerkkänen Fig. 3.3), [`CoulombSlip`] (Ribaric §8.4.3);
//! * [`point`]: nodal contact with exact derivatives;
//! * [`distributed`]: Gauss-quadrature contact along elements (Kerkkänen (3.26)–(3.27));
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

pub use distributed::{ContactRecord, ElementContact, LineContact};
pub use friction::{CoulombSlip, CoulombTanh, CreepRate, FrictionForce, FrictionLaw, Frictionless};
pub use geometry::{CleatedDrum, CleatedRoad, Disk, HalfPlane, Surface, SurfacePoint};
pub use lagrange::{ActiveSet, UnilateralRow, unilateral_row};
pub use normal::{LinearPenalty, NormalForce, NormalLaw, PolynomialPenalty};
pub use point::{PointContact, point_contact};
pub use quadrature::GaussRule;
