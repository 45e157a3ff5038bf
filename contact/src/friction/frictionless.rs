//! No friction.

use super::{FrictionForce, FrictionLaw};
use serde::{Deserialize, Serialize};

/// No friction: `f_t = 0`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Frictionless;

impl FrictionLaw for Frictionless {
    fn friction(&self, _slip: f64, _normal: f64) -> FrictionForce {
        FrictionForce::default()
    }
    fn coefficient(&self) -> f64 {
        0.0
    }
}
