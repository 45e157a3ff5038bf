//! The ANCF thin plate (Kerkkänen §4.3; Dufva & Shabana \[63\]): a four-node, 36-coordinate
//! Kirchhoff plate element whose nodal coordinates are the position and the two in-plane
//! gradients `[r, r_x, r_y]` (4.14). It has a constant mass matrix, describes any rigid motion
//! exactly and takes membrane (4.16) and, optionally, bending (4.17)-(4.18) strain energy.
//! It is the building block of Kerkkänen's three-dimensional belt models (§4.6).
//!
//! * [`shape`]: the incomplete-cubic shape functions and their derivatives;
//! * [`element`]: [`ThinPlate`], its mass matrix, energies, forces and exact analytic tangent;
//! * [`energy`]: the analytic derivatives of the energy density behind them;
//! * [`mesh`]: [`PlateMesh`], shared nodes and sparse assembly;
//! * [`statics`]: Newton–Raphson equilibrium with load increments;
//! * [`dynamics`]: [`PlateDynamics`], a plate mesh with supports and gravity as an mbd-core
//!   system;
//! * [`strain`]: the fibre strain measures (4.9)–(4.11) for the belt tension;
//! * [`belt_drive`]: Kerkkänen's three-dimensional belt drives (§4.5–4.6).

pub mod belt_drive;
pub mod dynamics;
pub mod element;
pub mod energy;
pub mod mesh;
pub mod shape;
pub mod statics;
pub mod strain;

pub use dynamics::PlateDynamics;
pub use element::{PLATE_NDOF, ThinPlate};
pub use mesh::{PLATE_NODE_COORDS, PlateCell, PlateMesh};
pub use shape::{PlateShape, ShapeValues};
pub use statics::solve_plate_static;
pub use strain::{StrainMeasure, area_ratio};
