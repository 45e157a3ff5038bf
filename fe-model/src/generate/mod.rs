//! Parametric mesh generators.

pub mod beam;
pub mod belt;
pub mod block;
pub mod tire;
pub mod tire_mesh;

pub use beam::{straight_beam_2d, straight_string};
pub use belt::{BeltLoopConfig, belt_loop};
pub use block::hex_block;
pub use tire::{CordLayer, Tire, TireConfig, TireZone, tire};
