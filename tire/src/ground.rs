//! The tire's ground: a drum (radius 1.25 m) or a flat road, optionally carrying the
//! semicircular transverse cleat of Ribaric §8.3 and §8.5 (radius 10 mm; seed note U19, U25),
//! and, beyond it (issue 38 item 2), parametric obstacles ([`Obstacle`]: cleats of any
//! cross-section, transverse or oblique, steps up or down, potholes) and a road surface given
//! as a height grid (`grid_file`, the CSV format of [`contact::spatial::height_grid`]), all
//! queried in 3-D for the gap, normal and surface velocity of a contact node ([`Ground::query`]).
//!
//! # Frames and motion
//! The wheel frame is the ISO 8855 wheel frame of [`crate::rig::WheelInputs`] (x forward, y
//! left along the wheel axis, z up, origin at the wheel centre). The ground surface moves
//! under the fixed spindle with speed `v` opposite to the travel direction (`−x` at the
//! patch; the slip angle adds the lateral velocity `v tan α`, [`Ground::lateral_speed`]), so
//! the tire rolls forwards in `+x`. A point of the road with road coordinates `(X, Y)` (along
//! the travel direction and along the wheel axis, origin at the patch centre at `cleat_time`)
//! is at `x = X − v (t − t₀)`, `y = Y + v tan α (t − t₀)` at time `t` (`t₀ = cleat_time`); on
//! the drum `X` is the arc length along the drum's surface. The cleat, each obstacle's
//! `position` `X` and the height grid's `x = 0` reach the patch centre `x = 0` at
//! `t₀ + X/v`.
//!
//! The drum, the road and the cleat are planar in the wheel's `(x, z)` plane and extruded along
//! the wheel axis: without obstacles or grid they are evaluated, as before issue 38, with the
//! contact crate's [`CleatedDrum`], [`CleatedRoad`], [`Disk`] and [`HalfPlane`]. With obstacles
//! or a grid the ground is the union of the base surface (the [`Cylinder`] of the drum, the
//! road's [`HalfSpace`], a road with [`Pothole`]s cut into it or the [`GridRoad`]) and the
//! obstacles' [`Prism`]s (exact signed distances: the closer of the members,
//! [`contact::spatial::closest_of`]).
//!
//! # Camber
//! A camber angle γ ([`Ground::camber`], `rig.wheel.camber_deg`) tilts the rim by γ about the
//! wheel's x axis; it is applied as the ground tilted by `−γ` relative to the wheel, about the
//! x-parallel line through the contact centre `c = (0, 0, top)`: a wheel-frame point `p` is
//! queried at `c + R_x(γ)(p − c)` in the upright ground and the normal and velocity are turned
//! back by `R_x(γ)ᵀ`, so the road's normal in the wheel frame is `n = (0, sin γ, cos γ)`.
//! Sign (ISO 8855; Pacejka, *Tire and Vehicle Dynamics*, §1.2): γ is a right-handed rotation of
//! the wheel about its x axis, positive when the top of the wheel leans to the right (towards
//! `−y`) seen from behind.
//!
//! # Bounds for the candidate search
//! Every query also returns a static and a moving lower-bound value ([`GroundPoint::bound`])
//! with: `g(p', t') ≥ min(b_s − |p' − p|, b_m − |p' − p| − r |t' − t|)` wherever the
//! right-hand side is non-negative, `r` = [`Ground::bound_rate`]. Per surface:
//! * drum, road (also stepped) and the cleats and steps on them: `b_s = g` (the drum or road
//!   is at least the union's gap, is 1-Lipschitz as a distance and does not depend on time: the
//!   drum turns about its centre, the road moves in its plane), `b_m` the smallest distance to
//!   a cleat or step (exact signed distances: 1-Lipschitz; moving rigidly at `|u|`, the road's
//!   speed, so changing by at most `|u|` per unit time at a fixed point);
//! * a road with potholes: `b_s` the distance to the plane of the road (the solid with holes
//!   is a subset of the half-space, so its signed distance is at least the plane's), `b_m` the
//!   cleats' as above;
//! * a height-grid road: no static part (`b_s = ∞`), `b_m = min(q, cleats)` with the grid's
//!   1-Lipschitz lower bound `q = c (Z − h)` of [`GridRoad::bound`] (it moves by at most
//!   `c (G_x |u_x| + G_y |u_y|) < |u|` per unit time; `g ≥ q` where `q ≥ 0`).
//!
//! The camber's rotation is rigid and constant, so it keeps these bounds.

use crate::error::{TireError, invalid};
use contact::spatial::{
    Cylinder, GridRoad, HalfSpace, HeightGrid, MAX_GRID_POINTS, Pothole, Prism, Section,
    check_simple_polygon,
};
use contact::{CleatedDrum, CleatedRoad, Disk, HalfPlane, Surface, SurfacePoint};
use mbd_core::validate::{InvalidField, Validate, check, escape, limits};
use nalgebra::{Point2, Point3, Vector2, Vector3};
use serde::{Deserialize, Serialize};
use std::f64::consts::FRAC_PI_2;
use std::sync::Arc;

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

/// The cross-section of a cleat ([`Obstacle::Cleat`]) in the plane normal to its axis: `s`
/// across the cleat (along the road in the travel direction for a transverse cleat), `n` up
/// from the road surface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case", tag = "shape", deny_unknown_fields)]
pub enum CleatSection {
    /// A semicircle of radius `radius` centred on the road surface (the cleat of Ribaric §8.3).
    Semicircle {
        /// Radius \[m\].
        radius: f64,
    },
    /// A rectangle `width` wide (along `s`) and `height` high, centred at `s = 0`.
    Rectangle {
        /// Width \[m\].
        width: f64,
        /// Height \[m\].
        height: f64,
    },
    /// A trapezoid `base_width` wide on the road and `top_width` wide at its `height`,
    /// symmetric about `s = 0` (`top_width = 0`: a triangle).
    Trapezoid {
        /// Width on the road \[m\].
        base_width: f64,
        /// Width at the top \[m\].
        top_width: f64,
        /// Height \[m\].
        height: f64,
    },
    /// Any simple polygon `[[s, n], ...]` \[m\] (at most
    /// [`contact::spatial::MAX_SECTION_VERTICES`] vertices) that reaches the road (`n ≤ 0` at
    /// some vertex) and rises above it; it is cut off below `n = 0` by the road itself.
    Polygon {
        /// Vertices `[s, n]` \[m\] in order around the boundary.
        points: Vec<[f64; 2]>,
    },
}

impl CleatSection {
    /// The contact crate's [`Section`], continued below the road by `skirt` \[m\] (so that it
    /// meets a curved drum surface without a gap).
    fn section(&self, skirt: f64) -> Section {
        match self {
            CleatSection::Semicircle { radius } => Section::Disk { radius: *radius },
            CleatSection::Rectangle { width, height } => Section::rectangle(*width, *height, skirt),
            CleatSection::Trapezoid {
                base_width,
                top_width,
                height,
            } => Section::trapezoid(*base_width, *top_width, *height, skirt),
            CleatSection::Polygon { points } => Section::Polygon {
                vertices: points.clone(),
            },
        }
    }

    /// The largest extent of the section \[m\] (its size against a drum's radius).
    fn size(&self) -> f64 {
        match self {
            CleatSection::Semicircle { radius } => 2.0 * radius,
            CleatSection::Rectangle { width, height } => width.max(*height),
            CleatSection::Trapezoid {
                base_width,
                top_width,
                height,
            } => base_width.max(*top_width).max(*height),
            CleatSection::Polygon { points } => {
                let ext = |k: usize| {
                    let lo = points.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
                    let hi = points
                        .iter()
                        .map(|p| p[k])
                        .fold(f64::NEG_INFINITY, f64::max);
                    hi - lo
                };
                ext(0).max(ext(1))
            }
        }
    }

    /// Half of the section's width on the road \[m\] (the chord that must reach the drum).
    fn half_base(&self) -> f64 {
        match self {
            CleatSection::Semicircle { radius } => *radius,
            CleatSection::Rectangle { width, .. } => 0.5 * width,
            CleatSection::Trapezoid { base_width, .. } => 0.5 * base_width,
            CleatSection::Polygon { points } => {
                points.iter().map(|p| p[0].abs()).fold(0.0, f64::max)
            }
        }
    }
}

impl Validate for CleatSection {
    /// Positive, finite dimensions; a trapezoid's top no wider than its base; a polygon that
    /// is simple, reaches the road and rises above it.
    fn validate(&self) -> Result<(), InvalidField> {
        match self {
            CleatSection::Semicircle { radius } => check::positive("radius", *radius, "m"),
            CleatSection::Rectangle { width, height } => {
                check::positive("width", *width, "m")?;
                check::positive("height", *height, "m")
            }
            CleatSection::Trapezoid {
                base_width,
                top_width,
                height,
            } => {
                check::positive("base_width", *base_width, "m")?;
                check::within("top_width", *top_width, 0.0, *base_width, "m")?;
                check::positive("height", *height, "m")
            }
            CleatSection::Polygon { points } => {
                check_simple_polygon(points).map_err(|r| InvalidField::new("points", r))?;
                let lo = points.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
                let hi = points
                    .iter()
                    .map(|p| p[1])
                    .fold(f64::NEG_INFINITY, f64::max);
                if lo > 0.0 || hi <= 0.0 {
                    return Err(InvalidField::new(
                        "points",
                        format!(
                            "must reach the road (some n <= 0) and rise above it (some n > \
                             0); n spans [{}, {}] m",
                            check::show(lo),
                            check::show(hi)
                        ),
                    ));
                }
                Ok(())
            }
        }
    }
}

/// An obstacle on the road or drum (`[[rig.ground.obstacles]]`, issue 38 item 2). Its
/// `position` is the road coordinate `X` \[m\] of its reference line (module documentation):
/// it reaches the patch centre `position / v` after `cleat_time`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case", tag = "type", deny_unknown_fields)]
pub enum Obstacle {
    /// A cleat of any cross-section, infinitely long, its axis on the road surface turned by
    /// `angle_deg` from the wheel axis about the road normal (0: transverse; positive
    /// counter-clockwise seen from above, an oblique cleat: its left end, `y > 0`, reaches the
    /// patch first). On the drum only transverse cleats (the axis along the drum's).
    Cleat {
        /// The cross-section (normal to the cleat's axis).
        section: CleatSection,
        /// Road coordinate of the cleat's axis where it crosses `y = 0` \[m\].
        #[serde(default)]
        position: f64,
        /// Angle of the cleat's axis to the wheel axis \[deg\] (within ±[`MAX_OBLIQUE_DEG`]).
        #[serde(default)]
        angle_deg: f64,
    },
    /// A step in the road (road only): the road rises by `height` (falls for a negative
    /// height) beyond the edge, whose line is turned by `angle_deg` as a cleat's axis.
    Step {
        /// Rise of the road beyond the edge \[m\] (negative: a step down).
        height: f64,
        /// Road coordinate of the edge where it crosses `y = 0` \[m\].
        #[serde(default)]
        position: f64,
        /// Angle of the edge to the wheel axis \[deg\] (within ±[`MAX_OBLIQUE_DEG`]).
        #[serde(default)]
        angle_deg: f64,
    },
    /// A rectangular pothole (road only, not on a height-grid road): `length` along the road,
    /// `width` across, `depth` deep, with vertical walls.
    Pothole {
        /// Length along the road \[m\].
        length: f64,
        /// Width across the road (along the wheel axis) \[m\].
        width: f64,
        /// Depth \[m\].
        depth: f64,
        /// Road coordinate of the pothole's centre \[m\].
        #[serde(default)]
        position: f64,
        /// Lateral offset of its centre from the wheel's mid-plane, left positive \[m\].
        #[serde(default)]
        offset: f64,
    },
}

/// Largest angle of an oblique cleat or step to the wheel axis \[deg\].
pub const MAX_OBLIQUE_DEG: f64 = 75.0;

/// Most obstacles of one ground.
pub const MAX_OBSTACLES: usize = 64;

/// Largest height-grid file read \[bytes\] (256 MiB; raised by `--allow-large`).
pub const MAX_GRID_BYTES: f64 = 268_435_456.0;

impl Obstacle {
    /// The road coordinate of the obstacle's reference line or centre \[m\].
    pub fn position(&self) -> f64 {
        match self {
            Obstacle::Cleat { position, .. }
            | Obstacle::Step { position, .. }
            | Obstacle::Pothole { position, .. } => *position,
        }
    }

    /// The extent along the road about the reference line's crossing of `y = 0` \[m\]:
    /// `(behind, ahead)` within `|y| ≤ reach` \[m\] (the tire's half width): `reach |tan ψ|`
    /// either way for an oblique cleat or step (a transverse one is its reference line, as the
    /// cleat of §8.3), half the length for a pothole.
    fn extent(&self, reach: f64) -> (f64, f64) {
        match self {
            Obstacle::Cleat { angle_deg, .. } | Obstacle::Step { angle_deg, .. } => {
                let e = reach * angle_deg.to_radians().tan().abs();
                (-e, e)
            }
            Obstacle::Pothole { length, .. } => (-0.5 * length, 0.5 * length),
        }
    }

    /// Why the obstacle is not its own mirror image about the wheel's mid-plane `y = 0`
    /// (`None` when it is: transverse cleats and steps, centred potholes).
    fn asymmetry(&self) -> Option<String> {
        match self {
            Obstacle::Cleat { angle_deg, .. } if *angle_deg != 0.0 => Some(format!(
                "an oblique cleat (angle_deg = {}) is not mirror-symmetric about the wheel's \
                 mid-plane",
                check::show(*angle_deg)
            )),
            Obstacle::Step { angle_deg, .. } if *angle_deg != 0.0 => Some(format!(
                "an oblique step (angle_deg = {}) is not mirror-symmetric about the wheel's \
                 mid-plane",
                check::show(*angle_deg)
            )),
            Obstacle::Pothole { offset, .. } if *offset != 0.0 => Some(format!(
                "an off-centre pothole (offset = {} m) is not mirror-symmetric about the \
                 wheel's mid-plane",
                check::show(*offset)
            )),
            _ => None,
        }
    }
}

impl Validate for Obstacle {
    /// Finite positions and offsets, angles within ±[`MAX_OBLIQUE_DEG`], a valid section, a
    /// non-zero step height, positive pothole dimensions.
    fn validate(&self) -> Result<(), InvalidField> {
        match self {
            Obstacle::Cleat {
                section,
                position,
                angle_deg,
            } => {
                section.validate_within("section")?;
                check::finite("position", *position)?;
                check::within(
                    "angle_deg",
                    *angle_deg,
                    -MAX_OBLIQUE_DEG,
                    MAX_OBLIQUE_DEG,
                    "deg",
                )
            }
            Obstacle::Step {
                height,
                position,
                angle_deg,
            } => {
                check::finite("height", *height)?;
                if *height == 0.0 {
                    return Err(InvalidField::new("height", "must not be 0"));
                }
                check::finite("position", *position)?;
                check::within(
                    "angle_deg",
                    *angle_deg,
                    -MAX_OBLIQUE_DEG,
                    MAX_OBLIQUE_DEG,
                    "deg",
                )
            }
            Obstacle::Pothole {
                length,
                width,
                depth,
                position,
                offset,
            } => {
                check::positive("length", *length, "m")?;
                check::positive("width", *width, "m")?;
                check::positive("depth", *depth, "m")?;
                check::finite("position", *position)?;
                check::finite("offset", *offset)
            }
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
    /// Whether the cleat is mounted: the semicircular, transverse, full-width cleat of
    /// Ribaric §8.3, reaching the patch centre at `cleat_time` (other cleats: `obstacles`).
    pub cleat: bool,
    /// Cleat radius \[m\] (10 mm semicircle, Ribaric §8.3).
    pub cleat_radius: f64,
    /// Further obstacles (issue 38 item 2; none by default): tables with `type = "cleat"`
    /// (`section` = a table with `shape = "semicircle" | "rectangle" | "trapezoid" |
    /// "polygon"`, `position`, `angle_deg`), `"step"` (`height`, `position`, `angle_deg`) or
    /// `"pothole"` (`length`, `width`, `depth`, `position`, `offset`). Steps and potholes need
    /// the road; oblique cleats too.
    pub obstacles: Vec<Obstacle>,
    /// Height-grid road (road only): a CSV file of heights \[m\] (format: rustdoc of
    /// `contact::spatial::height_grid`; first row `label, y_0, y_1, ...`, then one row `x_i,
    /// h(x_i, y_0), ...` per station), its `x = 0` reaching the patch centre at `cleat_time`;
    /// "" = the flat road. With a grid, only cleats may be added as obstacles.
    pub grid_file: String,
}

impl Default for GroundConfig {
    fn default() -> Self {
        Self {
            kind: GroundKind::Drum,
            drum_radius: 1.25,
            cleat: true,
            cleat_radius: 0.010,
            obstacles: Vec::new(),
            grid_file: String::new(),
        }
    }
}

impl Validate for GroundConfig {
    /// Positive drum radius (drum) and cleat radius (with a cleat) \[m\], and a cleat smaller
    /// than the drum; each obstacle (`obstacles[k].…`, at most [`MAX_OBSTACLES`]) valid and
    /// possible on this ground: on the drum only transverse cleats smaller than the drum; at
    /// most one step, not with potholes; with a height grid (road only, its file a readable
    /// regular file; its content is read by [`Ground::new`]) only cleats.
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
        check::size("obstacles", self.obstacles.len(), 0, MAX_OBSTACLES)?;
        let grid = !self.grid_file.is_empty();
        if grid && self.kind != GroundKind::Road {
            return Err(InvalidField::new(
                "grid_file",
                "a height grid needs the road (kind = \"road\")",
            ));
        }
        if grid {
            check::input_file("grid_file", std::path::Path::new(&self.grid_file))?;
        }
        let mut steps = 0;
        let potholes = self
            .obstacles
            .iter()
            .filter(|o| matches!(o, Obstacle::Pothole { .. }))
            .count();
        for (k, o) in self.obstacles.iter().enumerate() {
            let field = |f: &str| format!("obstacles[{k}].{f}");
            o.validate_within(&format!("obstacles[{k}]"))?;
            let road_only = |what: &str| {
                InvalidField::new(
                    field("type"),
                    format!("{what} needs the road (kind = \"road\")"),
                )
            };
            match o {
                Obstacle::Cleat {
                    section, angle_deg, ..
                } => {
                    if self.kind == GroundKind::Drum {
                        if *angle_deg != 0.0 {
                            return Err(InvalidField::new(
                                field("angle_deg"),
                                "an oblique cleat needs the road (kind = \"road\"); on the drum \
                                 cleats are transverse (angle_deg = 0)",
                            ));
                        }
                        if section.size() >= 0.5 * self.drum_radius {
                            return Err(InvalidField::new(
                                field("section"),
                                format!(
                                    "is {} m across, not small against drum_radius = {} m \
                                     (at most half of it)",
                                    check::show(section.size()),
                                    check::show(self.drum_radius)
                                ),
                            ));
                        }
                    }
                }
                Obstacle::Step { .. } => {
                    if self.kind != GroundKind::Road {
                        return Err(road_only("a step"));
                    }
                    if grid {
                        return Err(InvalidField::new(
                            field("type"),
                            "a step cannot be added to a height-grid road (make it part of \
                             the grid)",
                        ));
                    }
                    steps += 1;
                    if steps > 1 {
                        return Err(InvalidField::new(
                            field("type"),
                            "at most one step (a raised block is a rectangular cleat)",
                        ));
                    }
                    if potholes > 0 {
                        return Err(InvalidField::new(
                            field("type"),
                            "a step and potholes cannot be combined",
                        ));
                    }
                }
                Obstacle::Pothole { .. } => {
                    if self.kind != GroundKind::Road {
                        return Err(road_only("a pothole"));
                    }
                    if grid {
                        return Err(InvalidField::new(
                            field("type"),
                            "a pothole cannot be cut into a height-grid road (make it part of \
                             the grid)",
                        ));
                    }
                }
            }
        }
        Ok(())
    }
}

impl GroundConfig {
    /// The plain drum or road of this ground: no cleat, obstacles or grid (the ground of the
    /// preload).
    pub fn plain(&self) -> GroundConfig {
        GroundConfig {
            cleat: false,
            obstacles: Vec::new(),
            grid_file: String::new(),
            ..self.clone()
        }
    }

    /// Whether the ground has anything beyond the plain drum or road and the cleat of §8.3
    /// (obstacles or a grid).
    pub fn has_obstacles_or_grid(&self) -> bool {
        !self.obstacles.is_empty() || !self.grid_file.is_empty()
    }

    /// Read the height grid of `grid_file` (`None` for the flat road): a regular file of at
    /// most [`MAX_GRID_BYTES`] with at most [`MAX_GRID_POINTS`] nodes (both raised by
    /// `--allow-large`). Errors name `ground.grid_file`, the file, and the line and column.
    pub fn read_grid(&self) -> Result<Option<HeightGrid>, TireError> {
        if self.grid_file.is_empty() {
            return Ok(None);
        }
        let path = std::path::Path::new(&self.grid_file);
        let item = format!("ground.grid_file `{}`", escape(&self.grid_file));
        let max = limits::ceiling(MAX_GRID_BYTES);
        let text = mbd_core::input::read_text(path, max as u64).map_err(|e| {
            let hint = match e {
                mbd_core::input::InputError::TooLarge { .. } => limits::raise_hint(),
                _ => "",
            };
            invalid(&item, format!("{}{hint}", e.reason()))
        })?;
        let grid = HeightGrid::parse_csv(&text, limits::ceiling_count(MAX_GRID_POINTS))
            .map_err(|e| invalid(&item, e.to_string()))?;
        Ok(Some(grid))
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
    /// Whether the closest point is on the cleat or another obstacle (a pothole's walls,
    /// floor and rim included).
    pub on_cleat: bool,
    /// Speed \[m/s\] at which the ground near this point may approach it (the surface speed on
    /// an obstacle, the grid's slope-times-speed bound on a grid road, else 0): the contact
    /// step widens the candidate margin by `h` times this.
    pub approach: f64,
    /// The lower-bound values `[b_s, b_m]` \[m\] of the candidate search (module
    /// documentation, "Bounds").
    pub bound: [f64; 2],
}

/// The ground at a given surface speed and height.
#[derive(Debug, Clone, PartialEq)]
pub struct Ground {
    /// Settings.
    pub cfg: GroundConfig,
    /// Height `z` of the ground's top (drum apex or road surface) in the wheel frame \[m\]
    /// (before the camber's tilt, which turns the ground about `(0, 0, top)`).
    pub top: f64,
    /// Surface speed `v` \[m/s\] (material moves towards `−x` at the patch).
    pub speed: f64,
    /// Lateral velocity of the ground surface along the wheel axis `y` \[m/s\] (0: straight
    /// ahead). The slip angle α of the wheel over the road (ISO 8855; Pacejka, *Tire and Vehicle
    /// Dynamics*, §1.2: `tan α = −V_y/|V_x|` with the wheel centre's velocity `V` over the road)
    /// is set by the road moving at `u = −V = (−v, v tan α, 0)` under the fixed wheel:
    /// `lateral_speed = v tan α` (see [`crate::rig::WheelInputs`]). Obstacles and the grid
    /// move with it; the extruded drum, road and transverse cleats do not change with it.
    pub lateral_speed: f64,
    /// Time at which the cleat passes `x = 0` \[s\] (the road coordinate origin, module
    /// documentation).
    pub cleat_time: f64,
    /// Camber angle γ \[rad\] (module documentation; 0: upright).
    pub camber: f64,
    /// Half width of the region the tire may touch, `max |y|` of its contact nodes \[m\]: the
    /// extent of an oblique obstacle in the impact window ([`Ground::obstacle_near`]; 0 by
    /// default, set by the rig).
    pub lateral_reach: f64,
    /// The height grid of `cfg.grid_file`, read by [`Ground::new`].
    grid: Option<Arc<HeightGrid>>,
}

/// What [`Ground::query_upright`] found beside the gap: the member, its approach speed and
/// the bound values.
struct Upright {
    sp: SurfacePoint<3>,
    on_obstacle: bool,
    approach: f64,
    bound: [f64; 2],
}

impl Ground {
    /// The ground of `cfg` (its height grid read, [`GroundConfig::read_grid`]) with its top at
    /// `top` \[m\], surface speed `speed` and lateral speed `lateral_speed` \[m/s\], the cleat at
    /// the patch centre at `cleat_time` \[s\], upright (no camber; [`Ground::with_camber`]).
    pub fn new(
        cfg: GroundConfig, top: f64, speed: f64, lateral_speed: f64, cleat_time: f64,
    ) -> Result<Self, TireError> {
        let grid = cfg.read_grid()?.map(Arc::new);
        Ok(Self {
            cfg,
            top,
            speed,
            lateral_speed,
            cleat_time,
            camber: 0.0,
            lateral_reach: 0.0,
            grid,
        })
    }

    /// The ground of `cfg` without a grid file (a plain ground: [`GroundConfig::plain`]),
    /// which cannot fail to build.
    pub(crate) fn without_grid(
        cfg: GroundConfig, top: f64, speed: f64, lateral: f64, t0: f64,
    ) -> Self {
        Self {
            cfg,
            top,
            speed,
            lateral_speed: lateral,
            cleat_time: t0,
            camber: 0.0,
            lateral_reach: 0.0,
            grid: None,
        }
    }

    /// This ground tilted for the camber angle `gamma` \[rad\] (module documentation).
    pub fn with_camber(mut self, gamma: f64) -> Self {
        self.camber = gamma;
        self
    }

    /// The height grid, if any.
    pub fn grid(&self) -> Option<&HeightGrid> {
        self.grid.as_deref()
    }

    /// Distance \[m\] along the ground surface of the cleat ahead of the patch centre (`x = 0`) at
    /// time `t`: positive before it arrives, negative once it has passed; on the drum the
    /// passage nearest to `t` (the cleat comes round every `2πR/v`). `None` without a cleat.
    pub fn cleat_ahead(&self, t: f64) -> Option<f64> {
        if !self.cfg.cleat {
            return None;
        }
        Some(self.ahead(0.0, t))
    }

    /// Distance along the ground of the road coordinate `position` ahead of the patch centre
    /// at time `t` \[m\] (on the drum the nearest passage).
    fn ahead(&self, position: f64, t: f64) -> f64 {
        let s = position + self.speed * (self.cleat_time - t);
        match self.cfg.kind {
            GroundKind::Road => s,
            GroundKind::Drum => {
                let c = 2.0 * std::f64::consts::PI * self.cfg.drum_radius;
                s - c * (s / c).round()
            }
        }
    }

    /// Whether the cleat or an obstacle lies, at time `t`, between `lead` \[m\] ahead of the
    /// patch centre and `trail` \[s\] after passing it (`−v trail` behind): the window of the
    /// rig's impact sub-steps. An obstacle counts with its reference line where it crosses
    /// `y = 0` (as the cleat), extended by a pothole's length and by an oblique obstacle's
    /// run across the tire's width ([`Ground::lateral_reach`]).
    pub fn obstacle_near(&self, t: f64, lead: f64, trail: f64) -> bool {
        let cleat = self
            .cleat_ahead(t)
            .is_some_and(|d| d <= lead && d >= -self.speed * trail);
        cleat
            || self.cfg.obstacles.iter().any(|o| {
                let d = self.ahead(o.position(), t);
                let (lo, hi) = o.extent(self.lateral_reach);
                d + lo <= lead && d + hi >= -self.speed * trail
            })
    }

    /// The cleat's centre `c(t)` in the wheel's `(x, z)` plane at time `t` \[s\] (`None`
    /// without a cleat; upright ground). The cleat part of [`Ground::query`]'s gap is
    /// `|p − c(t)| − r`: it is 1-Lipschitz in the point `p` and moves by at most the surface
    /// speed `|v|` per unit time (the centre moves at `v`, the drum turning at `v/R` about its
    /// centre); the rest of the gap (drum, road) does not depend on time.
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

    /// Why this ground is not its own mirror image about the wheel's mid-plane `y = 0`
    /// (`Ok` when it is): the camber, an oblique cleat or step, an off-centre pothole, a height
    /// grid that is not symmetric in `y` (to 1e-12 m). (The lateral speed of a slip angle is
    /// the caller's to check: it breaks the symmetry of the motion, not of the ground.)
    pub fn mirror_symmetric(&self) -> Result<(), String> {
        if self.camber != 0.0 {
            return Err(format!(
                "the camber angle ({} deg) tilts the road to one side",
                check::show(self.camber.to_degrees())
            ));
        }
        for (k, o) in self.cfg.obstacles.iter().enumerate() {
            if let Some(why) = o.asymmetry() {
                return Err(format!("obstacles[{k}]: {why}"));
            }
        }
        if let Some(g) = &self.grid
            && !g.is_mirror_symmetric_in_y(1e-12)
        {
            return Err(format!(
                "the height grid `{}` is not mirror-symmetric about y = 0",
                escape(&self.cfg.grid_file)
            ));
        }
        Ok(())
    }

    /// The road's velocity `|u| = √(v² + (v tan α)²)` \[m/s\].
    fn road_speed(&self) -> f64 {
        self.speed.hypot(self.lateral_speed)
    }

    /// The grid's rate bound `c (G_x |v| + G_y |v tan α|)` \[m/s\] ([`GridRoad::bound`]), 0
    /// without a grid.
    fn grid_rate(&self) -> f64 {
        self.grid.as_ref().map_or(0.0, |g| {
            let [gx, gy] = g.slope_bounds();
            let c = 1.0 / (1.0 + gx * gx + gy * gy).sqrt();
            c * (gx * self.speed.abs() + gy * self.lateral_speed.abs())
        })
    }

    /// The largest rate \[m/s\] at which the moving bound value `b_m` of [`GroundPoint::bound`]
    /// changes at a fixed point (module documentation, "Bounds"): the surface speed `|v|` with
    /// the cleat of §8.3 alone, the road's `|u|` with obstacles, the grid's slope bound on a
    /// grid road.
    pub fn bound_rate(&self) -> f64 {
        if !self.cfg.has_obstacles_or_grid() {
            return self.speed.abs();
        }
        let members = self.cfg.cleat
            || self
                .cfg
                .obstacles
                .iter()
                .any(|o| !matches!(o, Obstacle::Pothole { .. }));
        let m = if members { self.road_speed() } else { 0.0 };
        m.max(self.grid_rate())
    }

    /// The largest [`GroundPoint::approach`] of this ground \[m/s\].
    pub fn max_approach(&self) -> f64 {
        if !self.cfg.has_obstacles_or_grid() {
            return self.speed.abs();
        }
        let obstacles = self.cfg.cleat || !self.cfg.obstacles.is_empty();
        let m = if obstacles { self.road_speed() } else { 0.0 };
        m.max(self.grid_rate())
    }

    /// Height \[m\] of the height grid under the patch centre `(0, 0)` at time `t` (0 without a
    /// grid): the rig lowers the grid road's reference plane by this much at `t = 0`, so that the
    /// tire preloaded on the flat road starts on the grid's surface.
    pub fn grid_height_at_centre(&self, t: f64) -> f64 {
        self.grid.as_ref().map_or(0.0, |g| {
            let dt = t - self.cleat_time;
            g.height(self.speed * dt, -self.lateral_speed * dt).h
        })
    }

    /// Closest-point query of the wheel-frame point `p` at time `t`.
    pub fn query(&self, t: f64, p: [f64; 3]) -> GroundPoint {
        if self.camber == 0.0 {
            return self.query_upright_point(t, p);
        }
        // p in the upright ground: c + R_x(γ)(p − c), c = (0, 0, top)
        let (s, c) = self.camber.sin_cos();
        let (dy, dz) = (p[1], p[2] - self.top);
        let q = [p[0], c * dy - s * dz, self.top + s * dy + c * dz];
        let g = self.query_upright_point(t, q);
        // back by R_x(γ)ᵀ
        let back = |v: [f64; 3]| [v[0], c * v[1] + s * v[2], -s * v[1] + c * v[2]];
        GroundPoint {
            normal: back(g.normal),
            velocity: back(g.velocity),
            ..g
        }
    }

    /// [`Ground::query`] on the upright ground.
    fn query_upright_point(&self, t: f64, p: [f64; 3]) -> GroundPoint {
        if !self.cfg.has_obstacles_or_grid() {
            return self.query_plain(t, p);
        }
        let u = self.query_upright(t, Point3::new(p[0], p[1], p[2]));
        GroundPoint {
            gap: u.sp.gap,
            normal: [u.sp.normal.x, u.sp.normal.y, u.sp.normal.z],
            velocity: [
                u.sp.surface_velocity.x,
                u.sp.surface_velocity.y,
                u.sp.surface_velocity.z,
            ],
            on_cleat: u.on_obstacle,
            approach: u.approach,
            bound: u.bound,
        }
    }

    /// The drum or road with the cleat of §8.3 only: the planar shapes of the contact crate
    /// extruded along `y` (module documentation).
    fn query_plain(&self, t: f64, p: [f64; 3]) -> GroundPoint {
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
        let on_cleat = sp.part == 1;
        // the cleat's own gap |p − c(t)| − r for the moving bound value (1e-9 m of the skip
        // test covers the ulps by which √(x² + z²) can differ from `hypot`)
        let moving = self.cleat_center(t).map_or(f64::INFINITY, |c| {
            let (dx, dz) = (p[0] - c[0], p[2] - c[1]);
            (dx * dx + dz * dz).sqrt() - self.cfg.cleat_radius
        });
        GroundPoint {
            gap: sp.gap,
            normal: [sp.normal[0], 0.0, sp.normal[1]],
            velocity: [
                sp.surface_velocity[0],
                self.lateral_speed,
                sp.surface_velocity[1],
            ],
            on_cleat,
            approach: if on_cleat { self.speed.abs() } else { 0.0 },
            bound: [sp.gap, moving],
        }
    }

    /// The ground with obstacles or a grid, upright (module documentation): the base surface
    /// and the obstacles' prisms, the closer of them.
    fn query_upright(&self, t: f64, p: Point3<f64>) -> Upright {
        let dt = t - self.cleat_time;
        let (v, lat) = (self.speed, self.lateral_speed);
        let u = Vector3::new(-v, lat, 0.0);
        let speed = self.road_speed();
        let top = self.top;
        // the road's level under a step down
        let level = self
            .cfg
            .obstacles
            .iter()
            .find_map(|o| match o {
                Obstacle::Step { height, .. } if *height < 0.0 => Some(top + height),
                _ => None,
            })
            .unwrap_or(top);
        let plane = HalfSpace {
            origin: Point3::new(0.0, 0.0, level),
            normal: Vector3::z(),
            tangent: Vector3::x(),
            velocity: u,
        };
        // the base surface and the static bound value
        let (base, stat, base_on_obstacle, base_approach) = match self.cfg.kind {
            GroundKind::Drum => {
                let r = self.cfg.drum_radius;
                let drum = Cylinder {
                    center: Point3::new(0.0, 0.0, top - r),
                    axis: Vector3::y(),
                    radius: r,
                    crown: 0.0,
                    velocity: Vector3::new(0.0, lat, 0.0),
                    // about +y, so that the apex moves towards −x
                    omega: -v / r,
                };
                (drum.closest(&p), None, false, 0.0)
            }
            GroundKind::Road => {
                if let Some(grid) = &self.grid {
                    let road = GridRoad {
                        grid,
                        origin: Point3::new(-v * dt, lat * dt, top),
                        along: Vector3::x(),
                        up: Vector3::z(),
                        velocity: u,
                    };
                    let (q, _) = road.bound(&p);
                    let rate = self.grid_rate();
                    (road.closest(&p), Some((f64::INFINITY, q)), false, rate)
                } else {
                    let flat = plane.closest(&p);
                    let mut best: Option<SurfacePoint<3>> = None;
                    for o in &self.cfg.obstacles {
                        if let Obstacle::Pothole {
                            length,
                            width,
                            depth,
                            position,
                            offset,
                        } = o
                        {
                            let hole = Pothole {
                                origin: Point3::new(position - v * dt, offset + lat * dt, top),
                                up: Vector3::z(),
                                along: Vector3::x(),
                                half_length: 0.5 * length,
                                half_width: 0.5 * width,
                                depth: *depth,
                                velocity: u,
                            };
                            // the road with several holes: the largest gap (exact where at
                            // most one hole is near)
                            let s = hole.closest(&p);
                            if best.is_none_or(|b| s.gap > b.gap) {
                                best = Some(s);
                            }
                        }
                    }
                    match best {
                        Some(s) => {
                            let in_hole = s.gap > flat.gap + 1e-12;
                            let a = if in_hole { speed } else { 0.0 };
                            (s, Some((flat.gap, f64::INFINITY)), in_hole, a)
                        }
                        None => (flat, None, false, 0.0),
                    }
                }
            }
        };
        // the members: the cleat of §8.3, the cleats and the step
        let mut best = base;
        let mut on_obstacle = base_on_obstacle;
        let mut approach = base_approach;
        let mut moving = stat.map_or(f64::INFINITY, |s| s.1);
        let mut member = |prism: Prism, best: &mut SurfacePoint<3>| {
            let s = prism.closest(&p);
            moving = moving.min(s.gap);
            if s.gap < best.gap {
                *best = s;
                on_obstacle = true;
                approach = approach.max(speed);
            }
        };
        let across = |angle_deg: f64| {
            let (s, c) = angle_deg.to_radians().sin_cos();
            Vector3::new(-s, c, 0.0)
        };
        let road_prism = |section: Section, position: f64, axis: Vector3<f64>, h: f64| {
            let origin = Point3::new(position - v * dt, lat * dt, h);
            Prism {
                section,
                origin,
                axis,
                up: Vector3::z(),
                center: origin,
                velocity: u,
                omega: 0.0,
            }
        };
        let drum_prism = |section: Section, position: f64| {
            let r = self.cfg.drum_radius;
            let a = FRAC_PI_2 + v / r * dt - position / r;
            let (sn, cs) = a.sin_cos();
            let up = Vector3::new(cs, 0.0, sn);
            let center = Point3::new(0.0, 0.0, top - r);
            Prism {
                section,
                origin: center + up * r,
                axis: Vector3::y(),
                up,
                center,
                velocity: Vector3::new(0.0, lat, 0.0),
                omega: -v / r,
            }
        };
        let prism_of = |section: &CleatSection, position: f64, angle_deg: f64| match self.cfg.kind {
            GroundKind::Road => {
                let skirt = section.size();
                road_prism(section.section(skirt), position, across(angle_deg), top)
            }
            GroundKind::Drum => {
                // below the base chord: the drum's sagitta b²/(2R) and more
                let b = section.half_base();
                let skirt = section.size() + b * b / self.cfg.drum_radius;
                drum_prism(section.section(skirt), position)
            }
        };
        if self.cfg.cleat {
            let semi = CleatSection::Semicircle {
                radius: self.cfg.cleat_radius,
            };
            member(prism_of(&semi, 0.0, 0.0), &mut best);
        }
        for o in &self.cfg.obstacles {
            match o {
                Obstacle::Cleat {
                    section,
                    position,
                    angle_deg,
                } => member(prism_of(section, *position, *angle_deg), &mut best),
                Obstacle::Step {
                    height,
                    position,
                    angle_deg,
                } => {
                    let quadrant = if *height > 0.0 {
                        Section::Quadrant {
                            side: 1.0,
                            height: *height,
                        }
                    } else {
                        Section::Quadrant {
                            side: -1.0,
                            height: 0.0,
                        }
                    };
                    member(
                        road_prism(quadrant, *position, across(*angle_deg), top),
                        &mut best,
                    )
                }
                Obstacle::Pothole { .. } => {}
            }
        }
        let stat = match stat {
            // drum or (stepped) road without holes: the static base is at least the gap
            None => best.gap,
            Some((s, _)) => s,
        };
        Upright {
            sp: best,
            on_obstacle,
            approach,
            bound: [stat, moving],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ground(kind: GroundKind, obstacles: Vec<Obstacle>, cleat: bool) -> Ground {
        let cfg = GroundConfig {
            kind,
            cleat,
            obstacles,
            ..GroundConfig::default()
        };
        Ground::without_grid(cfg, -0.5, 16.0, 0.0, 0.1)
    }

    // Reference (second formulation): the cleat of §8.3 evaluated by the planar shapes and as
    // a semicircle obstacle on the 3-D path (Cylinder / HalfSpace and the disk prism), on the
    // drum and on the road, on the cleat and beside it; the same bound values.
    #[test]
    fn semicircle_obstacle_is_the_cleat() {
        let semi = || {
            vec![Obstacle::Cleat {
                section: CleatSection::Semicircle { radius: 0.01 },
                position: 0.0,
                angle_deg: 0.0,
            }]
        };
        for kind in [GroundKind::Drum, GroundKind::Road] {
            let old = ground(kind, vec![], true);
            let new = ground(kind, semi(), false);
            let t = 0.1 + 0.002 / 16.0;
            let c = old.cleat_center(t).unwrap();
            for p in [
                [c[0] + 0.003, 0.1, c[1] + 0.0095],
                [c[0] - 0.012, -0.05, -0.4995],
                [0.2, 0.0, -0.4990],
            ] {
                let (a, b) = (old.query(t, p), new.query(t, p));
                assert_eq!(a.on_cleat, b.on_cleat, "{kind:?} {p:?}");
                assert!((a.gap - b.gap).abs() < 1e-14, "{kind:?} {p:?}");
                for i in 0..3 {
                    assert!((a.normal[i] - b.normal[i]).abs() < 1e-12);
                    assert!((a.velocity[i] - b.velocity[i]).abs() < 1e-12);
                }
                assert!((a.bound[1] - b.bound[1]).abs() < 1e-14);
            }
        }
    }

    // Reference: the camber's rotation is rigid (the gap of a point and of its image under
    // the same rotation of the ground agree), the road normal is (0, sin γ, cos γ) and the
    // road's velocity keeps its x component.
    #[test]
    fn camber_tilts_the_road_about_the_contact_centre() {
        let g = ground(GroundKind::Road, vec![], false);
        let gamma = 0.05f64;
        let tilted = g.clone().with_camber(gamma);
        let q = tilted.query(0.0, [0.1, 0.08, -0.49]);
        assert!((q.normal[1] - gamma.sin()).abs() < 1e-15);
        assert!((q.normal[2] - gamma.cos()).abs() < 1e-15);
        // the plane through (0, 0, top) with that normal
        let want = gamma.sin() * 0.08 + gamma.cos() * (-0.49 + 0.5);
        assert!((q.gap - want).abs() < 1e-15);
        assert_eq!(q.velocity[0], -16.0);
        assert!(tilted.mirror_symmetric().unwrap_err().contains("camber"));
    }

    // Reference: the configuration rules (one violation each).
    #[test]
    fn configuration_rules() {
        let cleat = |angle_deg| Obstacle::Cleat {
            section: CleatSection::Rectangle {
                width: 0.02,
                height: 0.01,
            },
            position: 0.0,
            angle_deg,
        };
        let on = |kind, obstacles: Vec<Obstacle>| GroundConfig {
            kind,
            obstacles,
            ..GroundConfig::default()
        };
        assert!(on(GroundKind::Drum, vec![cleat(0.0)]).validate().is_ok());
        let e = on(GroundKind::Drum, vec![cleat(10.0)])
            .validate()
            .unwrap_err();
        assert_eq!(e.field, "obstacles[0].angle_deg");
        let e = on(GroundKind::Road, vec![cleat(80.0)])
            .validate()
            .unwrap_err();
        assert_eq!(e.field, "obstacles[0].angle_deg");
        let step = |h| Obstacle::Step {
            height: h,
            position: 0.0,
            angle_deg: 0.0,
        };
        assert_eq!(
            on(GroundKind::Drum, vec![step(0.01)])
                .validate()
                .unwrap_err()
                .field,
            "obstacles[0].type"
        );
        assert_eq!(
            on(GroundKind::Road, vec![step(0.01), step(-0.01)])
                .validate()
                .unwrap_err()
                .field,
            "obstacles[1].type"
        );
        let poly = Obstacle::Cleat {
            section: CleatSection::Polygon {
                points: vec![[0.0, 0.001], [0.01, 0.001], [0.0, 0.01]],
            },
            position: 0.0,
            angle_deg: 0.0,
        };
        assert_eq!(
            on(GroundKind::Road, vec![poly])
                .validate()
                .unwrap_err()
                .field,
            "obstacles[0].section.points"
        );
        let mut grid = on(GroundKind::Drum, vec![]);
        grid.grid_file = "road.csv".into();
        assert_eq!(grid.validate().unwrap_err().field, "grid_file");
        grid.kind = GroundKind::Road;
        grid.grid_file = "/no/such/road.csv".into();
        let e = grid.validate().unwrap_err();
        assert!(
            e.field == "grid_file" && e.reason.contains("does not exist"),
            "{e:?}"
        );
    }
}
