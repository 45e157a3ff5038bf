//! Plain-data description of a planar belt drive (Kerkkänen §3.3, Table 3.1).

use super::friction::{BeltFriction, BeltNormal};
use crate::error::{AncfError, invalid};
use crate::mounted::DriveSpec;
use belt::{MaterialLaw, Motion, Pulley, Signal, WrapSide};
use mbd_core::Validate;
use serde::{Deserialize, Serialize};

/// Most Gauss-Legendre points per belt element ([`BeltSpec::gauss_points`]; Kerkkänen uses 5).
pub const MAX_GAUSS_POINTS: usize = 20;

/// The belt: ANCF belt elements (Kerkkänen §3.1) in a closed loop.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct BeltSpec {
    /// Unstretched belt length \[m\] (Table 3.1 runs: 1.2727 m, shorter than the 1.276273 m path,
    /// which pre-strains the belt on the pulleys).
    pub length: f64,
    /// Number of elements (Kerkkänen: 20, 25, 30).
    pub elements: usize,
    /// Section width (out of plane) \[m\].
    pub width: f64,
    /// Section thickness (in plane) \[m\].
    pub thickness: f64,
    /// Young's modulus `E` \[Pa\].
    pub young: f64,
    /// Poisson's ratio `ν` \[-\].
    pub poisson: f64,
    /// Density `ρ` \[kg/m³\].
    pub density: f64,
    /// Shear correction factor `k_s` \[-\] (not stated for the belt; 5/6 as in Ch. 2).
    pub shear_factor: f64,
    /// Axial stiffness multiplier `α₁` \[-\] (3.18).
    pub alpha1: f64,
    /// Bending/shear stiffness multiplier `α₂` \[-\] (3.18)–(3.19).
    pub alpha2: f64,
    /// Gauss points along each element for the strain energy.
    pub gauss_points: usize,
    /// Stiffness-proportional (Kelvin–Voigt) damping of the axial strain rate `β` \[s\]: axial
    /// force `α₁EA (ε + β ε̇)` with the Green strain `ε = (r_xᵀr_x − 1)/2` (Kerkkänen (3.18)'s
    /// axial term). `0` (Kerkkänen: no material damping) by default. It is the Lagrangian-mesh
    /// counterpart of Ribaric's `β K_e` Rayleigh damping on the material deflection rate; rigid
    /// motions (the belt wrapping a pulley) have `ε̇ = 0` and are not damped.
    pub axial_damping: f64,
    /// Material law of the belt ([`MaterialLaw`]): `"st_venant_kirchhoff"` (Kerkkänen (3.18),
    /// the default) or `"linear"` (axial force `α₁EA(‖r_x‖ − 1)`, as datasheets and Exudyn's
    /// cable). Reported tensions are always the axial force of this law
    /// ([`BeltElement::axial_force`](crate::element::BeltElement::axial_force)).
    pub law: MaterialLaw,
}

impl Default for BeltSpec {
    /// Kerkkänen Table 3.1.
    fn default() -> Self {
        Self {
            length: 1.2727,
            elements: 20,
            width: 0.01,
            thickness: 0.01,
            young: 1.0e8,
            poisson: 0.3,
            density: 1036.0,
            shear_factor: 5.0 / 6.0,
            alpha1: 1.0,
            alpha2: 0.01,
            gauss_points: 5,
            axial_damping: 0.0,
            law: MaterialLaw::StVenantKirchhoff,
        }
    }
}

/// Distributed penalty contact with friction (Kerkkänen (3.20)–(3.27)).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct ContactSpec {
    /// Penalty stiffness per unit length `k_p` \[N/m²\].
    pub stiffness: f64,
    /// Quadratic penalty coefficient per unit length `k₂` \[N/m³\] (Ribaric (6.1):
    /// `f_n = k₂ d² + k_p d`; `0` for Kerkkänen's linear law (3.20)).
    pub quadratic: f64,
    /// Penalty damping per unit length `c_p` \[N·s/m²\].
    pub damping: f64,
    /// Friction law.
    pub friction: BeltFriction,
    /// Gauss points per element for the contact integral (3.27) (Kerkkänen: 5, 7, 11 agree).
    pub points: usize,
}

impl ContactSpec {
    /// The normal law of the `stiffness`, `quadratic` and `damping` keys,
    /// [`BeltNormal::penalty`] (Kerkkänen (3.20), Ribaric (6.1)).
    pub fn normal_law(&self) -> BeltNormal {
        BeltNormal::penalty(self.stiffness, self.quadratic, self.damping)
    }
}

impl Default for ContactSpec {
    /// Kerkkänen Table 3.1.
    fn default() -> Self {
        Self {
            stiffness: 1.0e7,
            quadratic: 0.0,
            damping: 10.0,
            friction: BeltFriction::CreepRate {
                mu: 1.2,
                creep: 1.0e5,
            },
            points: 5,
        }
    }
}

/// A complete planar belt drive: pulleys in travel order, belt and contact (the one drive
/// description, [`DriveSpec`]).
pub type BeltDriveSpec = DriveSpec<BeltSpec, ContactSpec>;

impl Default for BeltDriveSpec {
    /// Kerkkänen Table 3.1 (example 3.3-B): driver at (−0.191441, 0) ramped to 12 rad/s by
    /// (3.29), free driven pulley at (0.191441, 0) with `I = 0.1 kg·m²` and no load, both
    /// `R = 0.08125 m`.
    fn default() -> Self {
        Self::two_pulley(
            0.08125,
            0.08125,
            Signal::kerkkanen_ramp(12.0),
            Signal::constant(0.0),
        )
    }
}

impl BeltDriveSpec {
    /// Kerkkänen's two-pulley layout (Table 3.1 centres, driver first) with the given radii,
    /// driver speed and driven-pulley load.
    pub fn two_pulley(r1: f64, r2: f64, speed: Signal, load: Signal) -> Self {
        Self {
            pulleys: vec![
                Pulley::new(
                    "driver",
                    [-0.191441, 0.0],
                    r1,
                    WrapSide::Inside,
                    Motion::speed(speed),
                ),
                Pulley::new(
                    "driven",
                    [0.191441, 0.0],
                    r2,
                    WrapSide::Inside,
                    Motion::load(0.1, load),
                ),
            ],
            belt: BeltSpec::default(),
            contact: ContactSpec::default(),
        }
    }

    /// Check every parameter; the error names the field.
    pub fn validate(&self) -> Result<(), AncfError> {
        crate::mounted::validate_pulleys(&self.pulleys)?;
        let b = &self.belt;
        let pos = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(invalid(
                    format!("belt.{name}"),
                    format!("must be > 0, got {v}"),
                ))
            }
        };
        // physical ranges (issue 35: 1e300 overflowed the static solve into NaN)
        let within = |name: &str, v: f64, lo: f64, hi: f64, unit: &str| {
            if v.is_finite() && (lo..=hi).contains(&v) {
                Ok(())
            } else {
                Err(invalid(
                    format!("belt.{name}"),
                    format!(
                        "must lie in [{lo:e}, {hi:e}]{unit}, got {}",
                        mbd_core::validate::check::show(v)
                    ),
                ))
            }
        };
        pos("length", b.length)?;
        pos("width", b.width)?;
        pos("thickness", b.thickness)?;
        within("length", b.length, 1e-3, 1e3, " m")?;
        within("width", b.width, 1e-6, 10.0, " m")?;
        within("thickness", b.thickness, 1e-6, 1.0, " m")?;
        // from foams (1e3 Pa) to diamond (1.2e12 Pa)
        within("young", b.young, 1e3, 1e13, " Pa")?;
        within("density", b.density, 1e-3, 1e5, " kg/m³")?;
        within("shear_factor", b.shear_factor, 1e-3, 10.0, "")?;
        // stiffness multipliers of (3.18)–(3.19) (Kerkkänen: α₁ = 1, α₂ = 0.01)
        within("alpha1", b.alpha1, 1e-6, 1e6, "")?;
        within("alpha2", b.alpha2, 1e-6, 1e6, "")?;
        if !(b.poisson.is_finite() && b.poisson > -1.0 && b.poisson < 0.5) {
            return Err(invalid(
                "belt.poisson",
                format!("must lie in (-1, 0.5), got {}", b.poisson),
            ));
        }
        // bounded before anything is allocated (issue 35: 2^63 - 1 elements overflowed a
        // Vec's capacity, 2^32 + 1 asked for 860 GB)
        let max_elements =
            mbd_core::validate::limits::ceiling_count(super::belt_model::MAX_ELEMENTS);
        if !(3..=max_elements).contains(&b.elements) {
            return Err(invalid(
                "belt.elements",
                format!(
                    "a closed loop needs 3 to {max_elements}, got {}{}",
                    b.elements,
                    if b.elements > max_elements {
                        mbd_core::validate::limits::raise_hint()
                    } else {
                        ""
                    }
                ),
            ));
        }
        if !(b.axial_damping.is_finite() && b.axial_damping >= 0.0) {
            return Err(invalid(
                "belt.axial_damping",
                format!("must be ≥ 0 s, got {}", b.axial_damping),
            ));
        }
        // Gauss-Legendre points per element: the rule is built per element (issue 35:
        // 2^32 + 1 points asked for 34 GB)
        if !(1..=MAX_GAUSS_POINTS).contains(&b.gauss_points) {
            return Err(invalid(
                "belt.gauss_points",
                format!("must lie in 1..={MAX_GAUSS_POINTS}, got {}", b.gauss_points),
            ));
        }
        let c = &self.contact;
        if !(c.stiffness.is_finite() && c.stiffness > 0.0) {
            return Err(invalid(
                "contact.stiffness",
                format!("must be > 0 N/m², got {}", c.stiffness),
            ));
        }
        if !(c.quadratic.is_finite() && c.quadratic >= 0.0) {
            return Err(invalid(
                "contact.quadratic",
                format!("must be ≥ 0 N/m³, got {}", c.quadratic),
            ));
        }
        if !(c.damping.is_finite() && c.damping >= 0.0) {
            return Err(invalid(
                "contact.damping",
                format!("must be ≥ 0 N·s/m², got {}", c.damping),
            ));
        }
        if c.points == 0 || c.points > 20 {
            return Err(invalid(
                "contact.points",
                format!("must lie in 1..=20, got {}", c.points),
            ));
        }
        c.friction.validate_within("contact.friction")?;
        Ok(())
    }
}
