//! Spatial (3D) contact: obstacle geometry with nalgebra points and vectors, and the contact of
//! one material point with exact derivatives. The normal laws ([`crate::normal`]) and friction
//! laws ([`crate::friction`]) are the planar ones: the friction law takes the slip 2-vector in
//! the tangent plane ([`crate::FrictionLaw::friction_tangent`]).
//!
//! * [`geometry`]: [`Surface3`] with [`Cylinder`] (pulley or drum, optionally crowned, for the
//!   3D belt of Kerkkänen ch. 4) and [`HalfSpace`] (flat road);
//! * [`flanged`]: [`FlangedCylinder`] (side planes as flanges);
//! * [`cleated`]: [`CleatedDrum3`], [`CleatedRoad3`] (the planar cleated drum and road
//!   extruded along the cleat axis);
//! * [`point`]: [`point_contact_3d`], the spatial counterpart of [`crate::point_contact`];
//! * [`distributed`]: [`SurfaceContact`], quadrature contact over surface elements (the spatial
//!   Kerkkänen (3.26)–(3.27), for the plate belt of his ch. 4).

pub mod cleated;
pub mod distributed;
pub mod flanged;
pub mod geometry;
pub mod point;

pub use cleated::{CleatedDrum3, CleatedRoad3};
pub use distributed::{ContactRecord3, ElementContact3, SurfaceContact, SurfaceQuadPoint};
pub use flanged::FlangedCylinder;
pub use geometry::{Cylinder, HalfSpace, Surface3, SurfacePoint3};
pub use point::{PointContact3, point_contact_3d};
