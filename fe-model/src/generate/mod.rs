//! Parametric mesh generators.

pub mod beam;
pub mod belt;
pub mod belt_path;
pub mod block;
pub mod tire;

pub use beam::{straight_beam_2d, straight_string};
pub use belt::{BeltLoopConfig, belt_loop};
pub use belt_path::{BeltPath, PathPoint, PathPulley, WrapSide};
pub use block::hex_block;
pub use tire::{CordLayer, Tire, TireConfig, TireZone, tire};
