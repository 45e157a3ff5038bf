//! Spatial (3D) obstacle geometry with nalgebra points and vectors. The contact itself — point
//! contact ([`crate::point_contact`]), distributed contact ([`crate::distributed`]) and
//! unilateral rows ([`crate::unilateral_row`]) — is the crate's dimension-generic one with
//! `D = 3`; the friction laws take the slip 2-vector in the tangent plane
//! ([`crate::FrictionLaw::friction_tangent`]).
//!
//! * [`geometry`]: [`Cylinder`] (pulley or drum, optionally crowned, for the 3D belt of
//!   Kerkkänen ch. 4) and [`HalfSpace`] (flat road);
//! * [`flanged`]: [`FlangedCylinder`] (side planes as flanges);
//! * [`cleated`]: [`CleatedDrum3`], [`CleatedRoad3`] (the planar cleated drum and road
//!   extruded along the cleat axis).
//!
//! The aliases [`SurfacePoint3`], [`PointContact3`], [`ElementContact3`], [`ContactRecord3`]
//! and [`SurfaceQuadPoint`] name the generic types at `D = 3`.

pub mod cleated;
pub mod flanged;
pub mod geometry;

pub use crate::point::PointContact3;
pub use cleated::{CleatedDrum3, CleatedRoad3};
pub use flanged::FlangedCylinder;
pub use geometry::{Cylinder, HalfSpace, SurfacePoint3};

/// Distributed contact output in space.
pub type ElementContact3 = crate::distributed::ElementContact<3>;
/// A contact record in space.
pub type ContactRecord3 = crate::distributed::ContactRecord<3>;
/// A quadrature point of a spatial element with `N` coordinates and a full `3 × N` shape matrix.
pub type SurfaceQuadPoint<const N: usize> =
    crate::distributed::QuadPoint<3, nalgebra::SMatrix<f64, 3, N>>;
