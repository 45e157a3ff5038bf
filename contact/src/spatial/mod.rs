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
//!   extruded along the cleat axis);
//! * [`section`], [`obstacle`]: road obstacles as exact signed-distance surfaces — a
//!   [`Prism`] of any [`Section`] (disk, polygon, step quadrant; transverse or oblique, on a
//!   road or turning with a drum) and a [`Pothole`], combined with the road by [`closest_of`];
//! * [`height_grid`]: a road given by heights on a grid ([`HeightGrid`], read from CSV) and its
//!   surface [`GridRoad`].
//!
//! The aliases [`SurfacePoint3`], [`PointContact3`], [`ElementContact3`], [`ContactRecord3`]
//! and [`SurfaceQuadPoint`] name the generic types at `D = 3`.

pub mod cleated;
pub mod flanged;
pub mod geometry;
pub mod height_grid;
pub mod obstacle;
pub mod section;

pub use crate::point::PointContact3;
pub use cleated::{CleatedDrum3, CleatedRoad3};
pub use flanged::FlangedCylinder;
pub use geometry::{Cylinder, HalfSpace, SurfacePoint3};
pub use height_grid::{GridError, GridHeight, GridRoad, HeightGrid, MAX_GRID_POINTS};
pub use obstacle::{Pothole, Prism, closest_of};
pub use section::{MAX_SECTION_VERTICES, Section, SectionPoint, check_simple_polygon};

/// Distributed contact output in space.
pub type ElementContact3 = crate::distributed::ElementContact<3>;
/// A contact record in space.
pub type ContactRecord3 = crate::distributed::ContactRecord<3>;
/// A quadrature point of a spatial element with `N` coordinates and a full `3 × N` shape matrix.
pub type SurfaceQuadPoint<const N: usize> =
    crate::distributed::QuadPoint<3, nalgebra::SMatrix<f64, 3, N>>;
