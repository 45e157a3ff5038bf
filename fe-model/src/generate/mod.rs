//! Parametric mesh generators.

pub mod beam;

pub use beam::{straight_beam_2d, straight_string};
