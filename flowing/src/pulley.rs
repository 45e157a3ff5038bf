//! Pulley obstacles for the wrapped string (Ribaric Fig. 4-4, 4-7).

use crate::error::{FlowError, invalid};

/// A rigid pulley under Ribaric's travelling string, an obstacle the string wraps (not a
/// belt-drive pulley, which is `belt::Pulley`): a circle of radius `radius` whose top point is at
/// `(center_x, top)` in the string's (axial x, transverse u) plane \[m\].
#[derive(
    Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields)]
pub struct PulleyObstacle {
    /// Axial position of the pulley centre \[m\].
    pub center_x: f64,
    /// Transverse coordinate of the top of the pulley \[m\].
    pub top: f64,
    /// Radius \[m\].
    pub radius: f64,
}

impl PulleyObstacle {
    /// Checks the numbers.
    pub fn validate(&self, name: &str) -> Result<(), FlowError> {
        if !(self.radius.is_finite() && self.radius > 0.0) {
            return Err(invalid(
                format!("{name}: radius"),
                format!("{} is not positive", self.radius),
            ));
        }
        if !(self.center_x.is_finite() && self.top.is_finite()) {
            return Err(invalid(format!("{name}: position"), "not finite"));
        }
        Ok(())
    }

    /// Height of the pulley surface under axial position `x` \[m\] (upper half circle), or `None`
    /// when `x` is not above the pulley.
    pub fn surface(&self, x: f64) -> Option<f64> {
        let d = x - self.center_x;
        (d.abs() < self.radius)
            .then(|| self.top - self.radius + (self.radius * self.radius - d * d).sqrt())
    }
}
