//! The tire's ground: a drum (radius 1.25 m) or a flat road, each optionally carrying a
//! semicircular transverse cleat (radius 10 mm), Ribaric §8.3 and §8.5 (seed note U19, U25).
//!
//! The geometry is planar in the wheel's `(x, z)` plane (longitudinal, vertical) and extruded
//! along the wheel axis `y`; it is evaluated with the contact crate's [`CleatedDrum`],
//! [`CleatedRoad`], [`Disk`] and [`HalfPlane`]. The ground surface moves under the fixed
//! spindle with speed `v` opposite to the travel direction (`−x` at the patch), so the tire rolls
//! forwards in `+x`; the cleat reaches the bottom of the wheel (`x = 0`) at `cleat_time`.

use contact::{CleatedDrum, CleatedRoad, Disk, HalfPlane, Surface};
use mbd_core::validate::{InvalidField, Validate, check};
use nalgebra::{Point2, Vector2};
use serde::{Deserialize, Serialize};
use std::f64::consts::FRAC_PI_2;

/// Kind of ground.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum GroundKind {
    /// Rotating drum (test rig, Ribaric §8.3).
    Drum,
    /// Flat road (Ribaric §8.5).
    Road,
}

impl GroundKind {
    /// `"drum"` or `"road"` (its configuration value; the studies' file-name suffix).
    pub fn name(self) -> &'static str {
        match self {
            GroundKind::Drum => "drum",
            GroundKind::Road => "road",
        }
    }
}

/// Ground settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct GroundConfig {
    /// Drum or flat road.
    pub kind: GroundKind,
    /// Drum radius \[m\] (1.25 m, Ribaric §8.5).
    pub drum_radius: f64,
    /// Whether the cleat is mounted.
    pub cleat: bool,
    /// Cleat radius \[m\] (10 mm semicircle, Ribaric §8.3).
    pub cleat_radius: f64,
}

impl Default for GroundConfig {
    fn default() -> Self {
        Self {
            kind: GroundKind::Drum,
            drum_radius: 1.25,
            cleat: true,
            cleat_radius: 0.010,
        }
    }
}

impl Validate for GroundConfig {
    /// Positive drum radius (drum) and cleat radius (with a cleat) \[m\], and a cleat smaller
    /// than the drum.
    fn validate(&self) -> Result<(), InvalidField> {
        if self.kind == GroundKind::Drum {
            check::positive("drum_radius", self.drum_radius, "m")?;
        }
        if self.cleat {
            check::positive("cleat_radius", self.cleat_radius, "m")?;
            if self.kind == GroundKind::Drum && self.cleat_radius >= self.drum_radius {
                return Err(InvalidField::new(
                    "cleat_radius",
                    format!(
                        "must be smaller than drum_radius = {} m, got {} m",
                        check::show(self.drum_radius),
                        check::show(self.cleat_radius)
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Closest-point data of a node in 3-D (wheel frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroundPoint {
    /// Signed gap \[m\] (negative = penetration).
    pub gap: f64,
    /// Outward unit normal of the ground.
    pub normal: [f64; 3],
    /// Velocity of the ground material at the closest point \[m/s\].
    pub velocity: [f64; 3],
    /// Whether the closest point is on the cleat.
    pub on_cleat: bool,
}

/// The ground at a given surface speed and height.
#[derive(Debug, Clone, PartialEq)]
pub struct Ground {
    /// Settings.
    pub cfg: GroundConfig,
    /// Height `z` of the ground's top (drum apex or road surface) in the wheel frame \[m\].
    pub top: f64,
    /// Surface speed `v` \[m/s\] (material moves towards `−x` at the patch).
    pub speed: f64,
    /// Lateral velocity of the ground surface along the wheel axis `y` \[m/s\] (0: straight
    /// ahead). The slip angle α of the wheel over the road (ISO 8855; Pacejka, *Tire and Vehicle
    /// Dynamics*, §1.2: `tan α = −V_y/|V_x|` with the wheel centre's velocity `V` over the road)
    /// is set by the road moving at `u = −V = (−v, v tan α, 0)` under the fixed wheel:
    /// `lateral_speed = v tan α` (see [`crate::rig::WheelInputs`]). It enters the slip velocity
    /// of the contact nodes only (the geometry is extruded along `y`, so the gaps do not
    /// depend on it).
    pub lateral_speed: f64,
    /// Time at which the cleat passes `x = 0` \[s\].
    pub cleat_time: f64,
}

impl Ground {
    /// Distance \[m\] along the ground surface of the cleat ahead of the patch centre (`x = 0`) at
    /// time `t`: positive before it arrives, negative once it has passed; on the drum the
    /// passage nearest to `t` (the cleat comes round every `2πR/v`). `None` without a cleat.
    pub fn cleat_ahead(&self, t: f64) -> Option<f64> {
        if !self.cfg.cleat {
            return None;
        }
        let s = self.speed * (self.cleat_time - t);
        Some(match self.cfg.kind {
            GroundKind::Road => s,
            GroundKind::Drum => {
                let c = 2.0 * std::f64::consts::PI * self.cfg.drum_radius;
                s - c * (s / c).round()
            }
        })
    }

    /// The cleat's centre `c(t)` in the wheel's `(x, z)` plane at time `t` \[s\] (`None`
    /// without a cleat). The cleat part of [`Ground::query`]'s gap is `|p − c(t)| − r`: it is
    /// 1-Lipschitz in the point `p` and moves by at most the surface speed `|v|` per unit time
    /// (the centre moves at `v`, the drum turning at `v/R` about its centre); the rest of the
    /// gap (drum, road) does not depend on time.
    pub fn cleat_center(&self, t: f64) -> Option<[f64; 2]> {
        if !self.cfg.cleat {
            return None;
        }
        Some(match self.cfg.kind {
            GroundKind::Drum => {
                let r = self.cfg.drum_radius;
                let a = FRAC_PI_2 + self.speed / r * (t - self.cleat_time);
                let (sn, cs) = a.sin_cos();
                [r * cs, self.top - r + r * sn]
            }
            GroundKind::Road => [-self.speed * (t - self.cleat_time), self.top],
        })
    }

    /// Closest-point query of the wheel-frame point `p` at time `t`.
    pub fn query(&self, t: f64, p: [f64; 3]) -> GroundPoint {
        let q = Point2::new(p[0], p[2]);
        let sp = match self.cfg.kind {
            GroundKind::Drum => {
                let r = self.cfg.drum_radius;
                let w = self.speed / r; // counter-clockwise in (x, z): apex moves to −x
                let drum = Disk {
                    center: Point2::new(0.0, self.top - r),
                    radius: r,
                    velocity: Vector2::zeros(),
                    omega: w,
                };
                if self.cfg.cleat {
                    CleatedDrum {
                        drum,
                        cleat_radius: self.cfg.cleat_radius,
                        cleat_angle: FRAC_PI_2 + w * (t - self.cleat_time),
                    }
                    .closest(&q)
                } else {
                    drum.closest(&q)
                }
            }
            GroundKind::Road => {
                let mut s = if self.cfg.cleat {
                    CleatedRoad {
                        height: self.top,
                        cleat_radius: self.cfg.cleat_radius,
                        cleat_x: -self.speed * (t - self.cleat_time),
                    }
                    .closest(&q)
                } else {
                    HalfPlane::ground(self.top).closest(&q)
                };
                s.surface_velocity = Vector2::new(-self.speed, 0.0);
                s
            }
        };
        GroundPoint {
            gap: sp.gap,
            normal: [sp.normal[0], 0.0, sp.normal[1]],
            velocity: [
                sp.surface_velocity[0],
                self.lateral_speed,
                sp.surface_velocity[1],
            ],
            on_cleat: sp.part == 1,
        }
    }
}
