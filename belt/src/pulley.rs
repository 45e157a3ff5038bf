//! The pulley: one type for every belt model, planar or spatial.
//!
//! A pulley is a rigid wheel turning about a fixed axis normal to the drive plane through
//! `center` (or a prescribed moving centre, [`CentreShift`]). `radius` is the radius of the
//! belt line on it (the belt's centreline or pitch line: belt thickness is not part of the
//! contact geometry, Kerkkänen §3.2, §4.5). The belt wraps it from inside the loop
//! ([`WrapSide::Inside`], grooved side) or with its back ([`WrapSide::Outside`], a back-side
//! idler). Speeds are counted in the belt's **travel sense**: positive when the pulley's surface
//! moves with the belt travelling along the path ([`crate::path::BeltPath`]): clockwise for
//! pulleys inside the loop, counter-clockwise for back-side pulleys (the loop runs clockwise).
//!
//! A spatial (plate) belt model also reads the surface's crown and flanges (Kerkkänen
//! (4.43)–(4.44)); planar models ignore them.

use crate::motion::Motion;
use crate::signal::Shape;
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// Largest radius accepted \[m\].
pub const MAX_RADIUS: f64 = 10.0;
/// Smallest radius accepted \[m\] (a belt cannot bend round a needle).
pub const MIN_RADIUS: f64 = 1e-3;

/// How the belt wraps a pulley.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema, Default,
)]
#[serde(rename_all = "lowercase")]
pub enum WrapSide {
    /// The pulley lies inside the loop (drive and driven pulleys of an open belt).
    #[default]
    Inside,
    /// The belt's back runs over the pulley (back-side idler, tensioner).
    Outside,
}

impl WrapSide {
    /// `+1` if a positive travel-sense speed of a pulley wrapped on this side is
    /// counter-clockwise, `−1` if clockwise: the belt path runs clockwise around pulleys inside
    /// the loop.
    pub fn ccw_sign(self) -> f64 {
        match self {
            WrapSide::Inside => -1.0,
            WrapSide::Outside => 1.0,
        }
    }

    /// `+1` when the belt turns clockwise on a pulley wrapped on this side, `−1` otherwise.
    pub fn turn(self) -> f64 {
        -self.ccw_sign()
    }
}

/// A prescribed translation of a pulley centre in the drive plane, Kerkkänen (4.46):
/// `u(t) = u₀ t / t₀` for `t < t₀`, `u₀` afterwards (Model 1 tensions its belt this way).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CentreShift {
    /// Final displacement `u₀` \[m\] (Model 1: 0.0025 m).
    pub distance: f64,
    /// Ramp time `t₀` \[s\] (Model 1: not stated, taken as the `t₀ = 0.05 s` of Table 4.1).
    pub time: f64,
    /// Unit direction of the displacement in the drive plane.
    pub direction: [f64; 2],
}

impl CentreShift {
    /// `[u(t), u̇(t)]` \[m, m/s\]: (4.46) is the ramp of (3.29) started at `t = 0`.
    pub fn eval(&self, t: f64) -> [f64; 2] {
        let (u, du) = Shape::Ramp {
            t_start: 0.0,
            t_end: self.time,
            from: 0.0,
            value: self.distance,
        }
        .eval(t);
        [u, du]
    }
}

impl Validate for CentreShift {
    fn validate(&self) -> Result<(), InvalidField> {
        check::non_negative("distance", self.distance, "m")?;
        check::positive("time", self.time, "s")?;
        let n = self.direction[0].hypot(self.direction[1]);
        if !(n.is_finite() && (n - 1.0).abs() < 1e-9) {
            return Err(InvalidField::new(
                "direction",
                format!("must be a unit vector, got {:?}", self.direction),
            ));
        }
        Ok(())
    }
}

/// A pulley of a belt drive (module documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Pulley {
    /// Name (used in messages and outputs; unique within a drive).
    pub name: String,
    /// Centre `(x, y)` in the drive plane \[m\] (for a tensioner's idler: its installed
    /// position, which fixes the arm length).
    #[serde(deserialize_with = "mbd_core::validate::exact_array")]
    pub center: [f64; 2],
    /// Radius of the belt line on the pulley \[m\].
    pub radius: f64,
    /// `inside` (grooved side, pulley inside the loop) or `outside` (back side).
    #[serde(default)]
    pub side: WrapSide,
    /// How it turns.
    pub motion: Motion,
    /// Crown coefficient `c` \[1/m\] of a spatial model's surface: radius `R − c z²`
    /// (Kerkkänen (4.43); 0: straight cylinder).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub crown: f64,
    /// Axial positions `[z_lo, z_hi]` of the inner flange faces \[m\] (spatial models; none: no
    /// flanges).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "mbd_core::validate::exact_array_opt"
    )]
    pub flanges: Option<[f64; 2]>,
    /// Prescribed centre translation, Kerkkänen (4.46) (none: fixed centre).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shift: Option<CentreShift>,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

impl Pulley {
    /// A pulley named `name` at `center` \[m\] with belt-line radius `radius` \[m\] wrapped on
    /// `side`, turning by `motion` (straight, unflanged, fixed centre).
    pub fn new(name: &str, center: [f64; 2], radius: f64, side: WrapSide, motion: Motion) -> Self {
        Self {
            name: name.into(),
            center,
            radius,
            side,
            motion,
            crown: 0.0,
            flanges: None,
            shift: None,
        }
    }

    /// [`WrapSide::ccw_sign`] of the pulley's side.
    pub fn ccw_sign(&self) -> f64 {
        self.side.ccw_sign()
    }

    /// Whether the pulley has its own rotation coordinate.
    pub fn is_free(&self) -> bool {
        self.motion.is_free()
    }

    /// The same pulley with its centre at `center` \[m\].
    pub fn moved_to(&self, center: [f64; 2]) -> Self {
        Self {
            center,
            ..self.clone()
        }
    }
}

impl Validate for Pulley {
    /// Every field checked; the error names the field relative to the pulley.
    fn validate(&self) -> Result<(), InvalidField> {
        if self.name.trim().is_empty() {
            return Err(InvalidField::new("name", "must not be empty"));
        }
        check::finite("center[0]", self.center[0])?;
        check::finite("center[1]", self.center[1])?;
        check::within("radius", self.radius, MIN_RADIUS, MAX_RADIUS, "m")?;
        self.motion.validate_within("motion")?;
        check::non_negative("crown", self.crown, "1/m")?;
        if let Some([lo, hi]) = self.flanges
            && !(lo.is_finite() && hi.is_finite() && lo < hi)
        {
            return Err(InvalidField::new(
                "flanges",
                format!("needs finite z_lo < z_hi, got [{lo}, {hi}]"),
            ));
        }
        if let Some(s) = &self.shift {
            s.validate_within("shift")?;
        }
        Ok(())
    }
}
