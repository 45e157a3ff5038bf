//! Kinematics helpers: Euler parameters ([`euler`]), tilde/stacking helpers ([`tilde`]) and
//! their planar equivalents ([`planar`]).

pub mod euler;
pub mod planar;
pub mod tilde;
