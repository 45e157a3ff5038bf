//! Plain-data description of a three-dimensional plate-belt drive (Kerkkänen §4.6, Table 4.1).

use crate::belt_drive::{BeltDriveSpec, BeltFriction, BeltSpec, ContactSpec};
use crate::error::{AncfError, invalid};
use crate::mounted::DriveSpec;
use belt::{CentreShift, Motion, Pulley, Shape, Signal, WrapSide};
use mbd_core::Validate;
use mbd_core::validate::InvalidField;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The belt: one row of thin-plate elements across the width, closed into a loop along the
/// length (Kerkkänen §4.6: 16 elements, 288 coordinates, Model 1; 20 elements, 360, Model 2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct PlateBeltSpec {
    /// Unstretched belt length \[m\] (the reference, stress-free element configuration).
    pub length: f64,
    /// Number of elements along the belt.
    pub elements: usize,
    /// Belt width `w` \[m\].
    pub width: f64,
    /// Belt thickness `h` \[m\].
    pub thickness: f64,
    /// Young's modulus `E` \[Pa\].
    pub young: f64,
    /// Poisson's ratio `ν` \[-\].
    pub poisson: f64,
    /// Density `ρ` \[kg/m³\].
    pub density: f64,
    /// Bending energy (4.17) on (Model 1) or off (Model 2).
    pub bending: bool,
    /// Gauss points per direction of the strain-energy quadrature (the thesis does not state
    /// its rule).
    pub gauss_points: usize,
}

impl PlateBeltSpec {
    /// Longitudinal stiffness `k = E w h` \[N\] (the `k` of the analytical model (4.1)).
    pub fn axial_stiffness(&self) -> f64 {
        self.young * self.width * self.thickness
    }
    /// Mass per unit length `ρ w h` \[kg/m\].
    pub fn mass_per_length(&self) -> f64 {
        self.density * self.width * self.thickness
    }
}

/// Distributed penalty contact with friction per unit (reference) area, Kerkkänen (3.20),
/// (3.23), (4.43)–(4.45).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct PlateContactSpec {
    /// Penalty stiffness per unit area `k_p` \[N/m³\].
    pub stiffness: f64,
    /// Penalty damping per unit area `c_p` \[N·s/m³\].
    pub damping: f64,
    /// Friction law per unit area (Kerkkänen: the tri-linear creep-rate law, `creep = ν_s`
    /// \[kg/(m²·s)\]). The 3D law acts on the slip 2-vector in the tangent plane of the pulley
    /// surface (circumferential and axial) and is isotropic: the thesis does not define a 3D
    /// friction direction (seed note §11 item 12); the isotropic extension keeps the planar law
    /// in the circumferential direction and lets the belt creep axially under the same law.
    pub friction: BeltFriction,
    /// Gauss points along the belt of the contact quadrature (Kerkkänen: 81 discrete points
    /// per element, layout unstated; 9 along here); the quadrature is `points ×`
    /// [`Self::points_across`] per element.
    pub points: usize,
    /// Gauss points across the width. `None` (the default): [`DEFAULT_POINTS_ACROSS`] = 3 when
    /// every pulley is a flat cylinder (no crown, no flanges), `points` (the square rule)
    /// otherwise ([`PlateContactSpec::points_across_for`]). The plate's shape functions are at
    /// most cubic across the width, so 3 points integrate each `S_k` exactly; on flat pulleys
    /// the pressure and friction across the width are smooth, and on Kerkkänen's Model 2 and
    /// the wide-pulley case 9 × 3 agrees with 9 × 9 within the solution's own sensitivity to
    /// its Newton tolerance (driven speed 3·10⁻⁶, contact torque 1.2·10⁻⁴, end-of-run span
    /// tensions 1.9–2.6·10⁻⁴: BENCHMARKS.md, plate-belt drive) at about 0.7 of the CPU. A
    /// crowned or flanged pulley loads the belt unevenly across its width (tracking, edge
    /// contact), which that study does not cover.
    pub points_across: Option<usize>,
}

/// Gauss points across the width of the plate belt's contact quadrature on flat pulleys when
/// [`PlateContactSpec::points_across`] is not given.
pub const DEFAULT_POINTS_ACROSS: usize = 3;

impl PlateContactSpec {
    /// The Gauss points across the width on the pulleys `pulleys`: [`Self::points_across`]
    /// when given, else [`DEFAULT_POINTS_ACROSS`] if no pulley has a crown or flanges and
    /// [`Self::points`] (the square rule) if one has.
    pub fn points_across_for(&self, pulleys: &[Pulley]) -> usize {
        self.points_across.unwrap_or_else(|| {
            if pulleys
                .iter()
                .all(|p| p.crown == 0.0 && p.flanges.is_none())
            {
                DEFAULT_POINTS_ACROSS
            } else {
                self.points
            }
        })
    }
}

/// A complete three-dimensional plate-belt drive: pulleys in travel order with their crowns,
/// flanges and centre shifts (Kerkkänen (4.43)–(4.46)), belt and contact (the one drive
/// description, [`DriveSpec`]).
pub type PlateDriveSpec = DriveSpec<PlateBeltSpec, PlateContactSpec>;

impl Default for PlateBeltSpec {
    /// Kerkkänen Model 2's belt.
    fn default() -> Self {
        PlateDriveSpec::kerkkanen_model2().belt
    }
}

impl Default for PlateContactSpec {
    /// Kerkkänen Model 2's contact.
    fn default() -> Self {
        PlateDriveSpec::kerkkanen_model2().contact
    }
}

impl Default for PlateDriveSpec {
    /// Kerkkänen Model 2 (Table 4.1).
    fn default() -> Self {
        Self::kerkkanen_model2()
    }
}

/// Two pulleys of radius `r` at `(∓πr/2, 0)` (span `l_s = πr`, Table 4.1), the driver first.
fn two_pulleys(r: f64, driver: Motion, driven: Motion) -> Vec<Pulley> {
    let c = 0.5 * PI * r;
    vec![
        Pulley::new("driver", [-c, 0.0], r, WrapSide::Inside, driver),
        Pulley::new("driven", [c, 0.0], r, WrapSide::Inside, driven),
    ]
}

impl PlateDriveSpec {
    /// Kerkkänen Model 1 (Table 4.1, §4.6): `R = 0.1 m`, belt `4πR` long (the path length:
    /// stress-free when laid on the pulleys), 0.08 m × 0.01 m, `E = 10⁷ Pa`, 16 elements, bending
    /// on (not stated; Model 2 is the one said to neglect it), driver ramped to 12 rad/s by
    /// (3.29) between 0.05 and 0.6 s and shifted by `u₀ = 2.5 mm` away from the driven pulley by
    /// (4.46) with `t₀ = 0.05 s`, free driven pulley with `I = 0.25 kg·m²` and no load (none is
    /// mentioned).
    pub fn kerkkanen_model1() -> Self {
        let r = 0.10;
        let mut pulleys = two_pulleys(
            r,
            Motion::speed(Signal::kerkkanen_ramp(12.0)),
            Motion::load(0.25, Signal::constant(0.0)),
        );
        pulleys[0].shift = Some(CentreShift {
            distance: 0.0025,
            time: 0.05,
            direction: [-1.0, 0.0],
        });
        Self {
            pulleys,
            belt: PlateBeltSpec {
                length: 4.0 * PI * r,
                elements: 16,
                width: 0.08,
                thickness: 0.01,
                young: 1.0e7,
                poisson: 0.3,
                density: 1036.0,
                bending: true,
                gauss_points: 5,
            },
            contact: PlateContactSpec {
                stiffness: 1.0e7,
                damping: 2000.0,
                friction: BeltFriction::CreepRate {
                    mu: 1.2,
                    creep: 1.0e5,
                },
                points: 9,
                points_across: None,
            },
        }
    }

    /// Kerkkänen Model 2 (Table 4.1, §4.6): `R = 0.05 m`, 0.04 m × 0.003 m, `E = 1.6667·10⁶ Pa`
    /// (`k = E A = 0.2 kN`), 20 elements, bending off, driver ramped to 500 rad/s by (3.29)
    /// between 0.05 and 1.0 s, driven pulley `I = 0.00025 kg·m²` loaded by (4.47) up to 2 N·m.
    ///
    /// The belt is shorter than the `4πR` path so that it carries the initial axial force of
    /// 50 N of Bechtel et al. \[5\]; the thesis does not give the length (seed note §11 item 25).
    /// Decision: the unstretched length is `4πR / (1 + 50 N / k)`, the belt whose tension
    /// `k ε` with the strain (4.9) is 50 N when it lies on the path — the same belt as the
    /// analytical model's (its constitutive law (4.1) is `T = k (dl/dl_o − 1)`), so that the two
    /// models compare the same physical belt. (The plate's membrane force at that stretch is
    /// larger, about 70 N: the Green–Lagrange membrane is not the linear law (4.1).)
    pub fn kerkkanen_model2() -> Self {
        let r = 0.05;
        let (young, w, h) = (1.6667e6, 0.04, 0.003);
        let k = young * w * h;
        Self {
            pulleys: two_pulleys(
                r,
                Motion::speed(
                    Shape::Ramp {
                        t_start: 0.05,
                        t_end: 1.0,
                        from: 0.0,
                        value: 500.0,
                    }
                    .into(),
                ),
                // (4.47): T_a = 1 − cos(π t / 1.0) for 0.05 < t ≤ 1.0, 2 N·m afterwards
                // (the printed last branch "0.6 < t" is read as "1.0 < t", seed note §5)
                Motion::load(
                    0.00025,
                    Shape::Cosine {
                        t_start: 0.05,
                        t_end: 1.0,
                        value: 2.0,
                    }
                    .into(),
                ),
            ),
            belt: PlateBeltSpec {
                length: 4.0 * PI * r / (1.0 + 50.0 / k),
                elements: 20,
                width: w,
                thickness: h,
                young,
                poisson: 0.3,
                density: 166.667,
                bending: false,
                gauss_points: 5,
            },
            contact: PlateContactSpec {
                stiffness: 8.0e7,
                damping: 2000.0,
                friction: BeltFriction::CreepRate {
                    mu: 0.6,
                    creep: 2.0e5,
                },
                points: 9,
                points_across: None,
            },
        }
    }

    /// Check every parameter; the error names the field.
    pub fn validate(&self) -> Result<(), AncfError> {
        Validate::validate(self).map_err(AncfError::from)
    }

    /// The planar ANCF belt drive (Kerkkänen ch. 3, [`crate::belt_drive`]) that this drive is
    /// when nothing moves out of the drive plane: the same pulleys, belt length, material and
    /// section (thickness in the plane, width out of it), the contact laws per unit length =
    /// per unit area × width (penalty, damping and the creep-rate slope `ν_s`; the other friction
    /// laws have no per-area parameter), the planar element's bending and shear scaled by
    /// `alpha2` (Kerkkänen (3.18)–(3.19)) and its axial stiffness unscaled. Errors: crowned or
    /// flanged pulleys or a centre shift (the planar drive has none).
    pub fn planar_equivalent(&self, alpha2: f64) -> Result<BeltDriveSpec, AncfError> {
        let mut pulleys = Vec::with_capacity(self.pulleys.len());
        for p in &self.pulleys {
            if p.crown != 0.0 || p.flanges.is_some() || p.shift.is_some() {
                return Err(invalid(
                    format!("pulley \"{}\"", p.name),
                    "a crowned, flanged or shifted pulley has no planar equivalent",
                ));
            }
            pulleys.push(p.clone());
        }
        let (b, c) = (&self.belt, &self.contact);
        let w = b.width;
        let friction = match c.friction {
            BeltFriction::CreepRate { mu, creep } => BeltFriction::CreepRate {
                mu,
                creep: creep * w,
            },
            other => other,
        };
        Ok(BeltDriveSpec {
            pulleys,
            belt: BeltSpec {
                length: b.length,
                elements: b.elements,
                width: w,
                thickness: b.thickness,
                young: b.young,
                poisson: b.poisson,
                density: b.density,
                shear_factor: 5.0 / 6.0,
                alpha1: 1.0,
                alpha2,
                gauss_points: b.gauss_points,
                axial_damping: 0.0,
                law: ::belt::MaterialLaw::StVenantKirchhoff,
            },
            contact: ContactSpec {
                stiffness: c.stiffness * w,
                quadratic: 0.0,
                damping: c.damping * w,
                friction,
                points: c.points,
            },
        })
    }
}

impl Validate for PlateDriveSpec {
    fn validate(&self) -> Result<(), InvalidField> {
        crate::mounted::validate_pulleys(&self.pulleys)?;
        let b = &self.belt;
        for (name, v, unit) in [
            ("length", b.length, "m"),
            ("width", b.width, "m"),
            ("thickness", b.thickness, "m"),
            ("young", b.young, "Pa"),
            ("density", b.density, "kg/m³"),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(InvalidField::new(
                    format!("belt.{name}"),
                    format!("must be > 0 {unit}, got {v}"),
                ));
            }
        }
        if !(b.poisson.is_finite() && b.poisson > -1.0 && b.poisson < 0.5) {
            return Err(InvalidField::new(
                "belt.poisson",
                format!("must lie in (-1, 0.5), got {}", b.poisson),
            ));
        }
        if !(3..=1000).contains(&b.elements) {
            return Err(InvalidField::new(
                "belt.elements",
                format!("a closed loop needs 3 to 1000, got {}", b.elements),
            ));
        }
        if !(2..=10).contains(&b.gauss_points) {
            return Err(InvalidField::new(
                "belt.gauss_points",
                format!("must lie in 2..=10, got {}", b.gauss_points),
            ));
        }
        let c = &self.contact;
        if !(c.stiffness.is_finite() && c.stiffness > 0.0) {
            return Err(InvalidField::new(
                "contact.stiffness",
                format!("must be > 0 N/m³, got {}", c.stiffness),
            ));
        }
        if !(c.damping.is_finite() && c.damping >= 0.0) {
            return Err(InvalidField::new(
                "contact.damping",
                format!("must be ≥ 0 N·s/m³, got {}", c.damping),
            ));
        }
        if !(1..=20).contains(&c.points) {
            return Err(InvalidField::new(
                "contact.points",
                format!("must lie in 1..=20 per direction, got {}", c.points),
            ));
        }
        if let Some(n) = c.points_across
            && !(1..=20).contains(&n)
        {
            return Err(InvalidField::new(
                "contact.points_across",
                format!("must lie in 1..=20, got {n}"),
            ));
        }
        c.friction.validate_within("contact.friction")?;
        Ok(())
    }
}
