//! Parametric mesh generators.

pub mod beam;
pub mod belt_path;

pub use beam::{straight_beam_2d, straight_string};
pub use belt_path::{BeltPath, PathPoint, PathPulley, WrapSide};
