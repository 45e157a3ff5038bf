//! The belt: its section (axial and bending stiffness, mass), the material law that turns
//! stretch into axial force, its belt–pulley contact and its damping. Shared by every belt
//! model; model-specific discretisation (meshes, element counts, reduction) lives with the
//! model.
//!
//! # Material law and the one force measure
//!
//! The axial force `N` \[N\] the belt carries at stretch `λ = ds/ds₀` (current over unstretched
//! length) is, per law ([`MaterialLaw`]):
//!
//! ```text
//!   linear (engineering strain):   N = EA (λ − 1)                 (datasheets; Exudyn's cable)
//!   St Venant–Kirchhoff:           N = EA λ (λ² − 1)/2            (Green strain ε = (λ² − 1)/2,
//!                                                                  Kerkkänen (3.18): N = ∂U/∂|r_x|)
//! ```
//!
//! # Ribs
//!
//! A multi-ribbed (V-ribbed, "PK") belt runs its ribs in the grooves of the pulleys it wraps
//! with its inside and its flat back on back-side pulleys. The wedge of included angle `β`
//! raises the normal force on the flanks by `1/sin(β/2)`, so the belt transmits as a flat belt
//! of friction coefficient `μ/sin(β/2)` on grooved pulleys and `μ` on flat ones
//! ([`Section::friction_factor`]; Johnson, *Contact Mechanics* §8.6; ISO 9981 and SAE J1459
//! give `β = 40°` for the PK profile). [`crate::Drive::wrap_friction_law`] makes that law per
//! pulley, once: the contact law with `μ` scaled by [`Section::friction_factor`]
//! (`contact::friction::FrictionSpec::scaled`). Every time-stepped belt model (flowing, nodal,
//! planar ANCF) contacts each pulley's belt-line radius as a flat belt with that pulley's law,
//! the report ([`crate::Report`]) measures friction utilisation and slip arcs against that
//! pulley's `μ`, and the steady design study's capacity check (`drives::fead_design`) uses the
//! same coefficients, so the design study and the simulations cannot disagree. The rib count
//! enters the per-rib loads of the design study only; the section's `EA` and `ρA` are the
//! whole belt's.
//!
//! Both agree to first order (`N ≈ EA (λ − 1)` at small strain) and differ by `3/2 (λ − 1)`
//! relative at finite strain: 7.6 % at 5 %. Every model reports, mounts to and plots the force
//! its elements carry, so the law is part of the belt's definition, not of a report.

use crate::pulley::WrapSide;
use contact::friction::FrictionSpec;
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// How the belt's axial force follows its stretch (module documentation).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema, Default,
)]
#[serde(rename_all = "snake_case")]
pub enum MaterialLaw {
    /// `N = EA λ (λ² − 1)/2`: Green strain, Kerkkänen (3.18) (the ANCF belt element's law).
    #[default]
    StVenantKirchhoff,
    /// `N = EA (λ − 1)`: linear in engineering strain.
    Linear,
}

impl MaterialLaw {
    /// Axial force `N(λ)` \[N\] and `dN/dλ` \[N\] at stretch `λ` for axial stiffness `ea` \[N\].
    pub fn force(self, ea: f64, stretch: f64) -> (f64, f64) {
        let l = stretch;
        match self {
            MaterialLaw::Linear => (ea * (l - 1.0), ea),
            MaterialLaw::StVenantKirchhoff => {
                (0.5 * ea * l * (l * l - 1.0), 0.5 * ea * (3.0 * l * l - 1.0))
            }
        }
    }

    /// The stretch `λ ≥ 1/√3` at which the force is `force` \[N\] (inverse of [`Self::force`];
    /// Newton from the linear estimate, monotone on the branch `λ > 1/√3` of the cubic).
    pub fn stretch(self, ea: f64, force: f64) -> f64 {
        match self {
            MaterialLaw::Linear => 1.0 + force / ea,
            MaterialLaw::StVenantKirchhoff => {
                let mut l = (1.0 + force / ea).max(0.6);
                for _ in 0..60 {
                    let (n, dn) = self.force(ea, l);
                    let step = (n - force) / dn;
                    l -= step;
                    if step.abs() <= 1e-15 * l {
                        break;
                    }
                }
                l
            }
        }
    }

    /// Name for summaries.
    pub fn name(self) -> &'static str {
        match self {
            MaterialLaw::StVenantKirchhoff => "St Venant–Kirchhoff (N = EA λ(λ²−1)/2)",
            MaterialLaw::Linear => "linear in engineering strain (N = EA (λ−1))",
        }
    }
}

/// The belt's section resultants and material law.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Section {
    /// Axial stiffness `EA` \[N\].
    pub ea: f64,
    /// Bending stiffness `EI` \[N m²\].
    pub ei: f64,
    /// Mass per unit length `ρA` \[kg/m\].
    pub mass_per_length: f64,
    /// Material law (default St Venant–Kirchhoff).
    #[serde(default)]
    pub law: MaterialLaw,
    /// Ribs of a multi-ribbed belt (none: a flat belt; module documentation).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ribs: Option<Ribs>,
}

/// The ribs of a multi-ribbed (V-ribbed) belt (module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Ribs {
    /// Number of ribs (a 6PK belt has 6).
    pub count: usize,
    /// Included wedge angle `β` of a rib \[rad\] (PK profile: 40° = 0.698 rad, ISO 9981).
    pub wedge_angle: f64,
}

/// Most ribs of a belt.
pub const MAX_RIBS: usize = 100;

impl Validate for Ribs {
    fn validate(&self) -> Result<(), InvalidField> {
        check::count("count", self.count, 1, MAX_RIBS)?;
        check::within(
            "wedge_angle",
            self.wedge_angle,
            10f64.to_radians(),
            120f64.to_radians(),
            "rad",
        )
    }
}

impl Default for Section {
    /// Ribaric Table 6-1: EA = 152 000 N, EI = 2.6·10⁻² N m², ρA = 0.096 kg/m.
    fn default() -> Self {
        Self {
            ea: 152_000.0,
            ei: 2.6e-2,
            mass_per_length: 0.096,
            law: MaterialLaw::default(),
            ribs: None,
        }
    }
}

impl Section {
    /// Axial force `N` \[N\] and `dN/dλ` \[N\] at stretch `λ` ([`MaterialLaw::force`]).
    pub fn force(&self, stretch: f64) -> (f64, f64) {
        self.law.force(self.ea, stretch)
    }

    /// Stretch at axial force `force` \[N\] ([`MaterialLaw::stretch`]).
    pub fn stretch(&self, force: f64) -> f64 {
        self.law.stretch(self.ea, force)
    }

    /// Axial stiffness per unit strain of the belt stretched to carry `force` \[N\]: `dN/dλ` at
    /// that stretch \[N\] (the `EA` of a model linearised about the mounted belt).
    pub fn tangent_stiffness(&self, force: f64) -> f64 {
        self.force(self.stretch(force)).1
    }

    /// Factor on the friction coefficient of a wrap on `side` (module documentation):
    /// `1/sin(β/2)` for the ribs in a grooved pulley ([`WrapSide::Inside`]), 1 on a flat
    /// back-side pulley or for a flat belt.
    pub fn friction_factor(&self, side: WrapSide) -> f64 {
        match (self.ribs, side) {
            (Some(r), WrapSide::Inside) => 1.0 / (0.5 * r.wedge_angle).sin(),
            _ => 1.0,
        }
    }

    /// Transverse wave speed `c = √(T/ρA)` \[m/s\] of a span at tension `tension` \[N\]
    /// (Ribaric §3).
    pub fn wave_speed(&self, tension: f64) -> f64 {
        (tension / self.mass_per_length).sqrt()
    }
}

impl Validate for Section {
    fn validate(&self) -> Result<(), InvalidField> {
        check::within("ea", self.ea, 1e-3, 1e12, "N")?;
        check::within("ei", self.ei, 1e-12, 1e9, "N m²")?;
        check::within("mass_per_length", self.mass_per_length, 1e-6, 1e4, "kg/m")?;
        if let Some(r) = &self.ribs {
            r.validate_within("ribs")?;
        }
        Ok(())
    }
}

/// Belt–pulley contact: the penalty law per unit belt length, Ribaric (6.1) distributed
/// (`f_n = k₂ d² + k₁ d` \[N/m\] at penetration `d` \[m\]), and the friction law.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct BeltContact {
    /// Quadratic penalty coefficient `k₂` \[N/m³\].
    pub penalty_quadratic: f64,
    /// Linear penalty coefficient `k₁` \[N/m²\].
    pub penalty_linear: f64,
    /// Friction law (default `{ law = "tanh_slip", mu = 1.2 }` at the default slip-velocity
    /// scale [`contact::friction::spec::DEFAULT_SLIP_VELOCITY`], near the Coulomb limit of the
    /// speed loss; Ribaric's `{ law = "tanh", mu = 1.2, kappa = 40.0 }` in Table 6-1 and the
    /// default FEAD drive; see [`FrictionSpec`] and BENCHMARKS.md "friction regularisation").
    pub friction: FrictionSpec,
}

impl Default for BeltContact {
    /// Ribaric's penalty law ([`BeltContact::ribaric`]) with the friction
    /// `μ tanh(v_t / v_s)`, μ = 1.2, at the default slip-velocity scale `v_s` =
    /// [`contact::friction::spec::DEFAULT_SLIP_VELOCITY`] (Ribaric (6.2) with `κ = 1/v_s`;
    /// issue 34 item 3): the friction a layout gets when it states none. Every model's speed
    /// loss lies within 1 % of its Coulomb limit (from its runs at smaller scales) at this scale on the
    /// drives of BENCHMARKS.md ("friction regularisation", "0.3 mm/s as the default"; the nodal
    /// belt's lightly loaded pulley of the FEAD drive the farthest, +0.8 % from its Richardson
    /// limit), where Ribaric's κ = 40 s/m (`v_s` = 25 mm/s)
    /// gives 2.3 times it on Table 6-1 at 10 N m (every model). Ribaric's Table 6-1 ([`crate::Layout::table_6_1`]) and the default FEAD
    /// drive state κ = 40 s/m to reproduce their figures.
    fn default() -> Self {
        Self {
            friction: FrictionSpec::tanh_slip(1.2),
            ..Self::ribaric()
        }
    }
}

impl BeltContact {
    /// Ribaric (6.1), (6.2) and Table 6-1: 3025.6·10⁸ N/m³, 6.5·10⁷ N/m², tanh friction with
    /// μ = 1.2, κ = 40 s/m (`v_s` = 25 mm/s: about three times the Coulomb limit's speed loss
    /// on Table 6-1, kept to reproduce its numbers).
    pub fn ribaric() -> Self {
        Self {
            penalty_quadratic: 3025.6e8,
            penalty_linear: 6.5e7,
            friction: FrictionSpec::Tanh {
                mu: 1.2,
                kappa: 40.0,
            },
        }
    }

    /// Penetration `p₀` \[m\] of the penalty law under the uniform pressure `T/R` of a belt with
    /// tension `tension` \[N\] on a pulley of radius `radius` \[m\]: the root of
    /// `k₂ p² + k₁ p = T/R` (72 µm for Table 6-1, seed-000 note §2.3).
    pub fn mounting_penetration(&self, tension: f64, radius: f64) -> f64 {
        let (k2, k1) = (self.penalty_quadratic, self.penalty_linear);
        let q = tension / radius;
        if k2 > 0.0 {
            (-k1 + (k1 * k1 + 4.0 * k2 * q).sqrt()) / (2.0 * k2)
        } else {
            q / k1
        }
    }
}

impl Validate for BeltContact {
    fn validate(&self) -> Result<(), InvalidField> {
        check::within("penalty_linear", self.penalty_linear, 1e-3, 1e15, "N/m²")?;
        check::within(
            "penalty_quadratic",
            self.penalty_quadratic,
            0.0,
            1e20,
            "N/m³",
        )?;
        self.friction.validate_within("friction")
    }
}

/// Rayleigh damping of the belt, `C = α M + β K_e` (Ribaric Table 6-1): `α` on the mass, `β`
/// on the elastic stiffness acting on the material strain rate (the viscoelastic rubber; the
/// ANCF belt carries it as Kelvin–Voigt axial damping `EA(ε + β ε̇)`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct BeltDamping {
    /// Mass-proportional coefficient `α` \[1/s\].
    pub alpha: f64,
    /// Stiffness-proportional coefficient `β` \[s\].
    pub beta: f64,
}

impl Default for BeltDamping {
    /// Table 6-1: α = 2.8 s⁻¹, β = 1.8·10⁻³ s (as printed; see the seed-000 note U11).
    fn default() -> Self {
        Self {
            alpha: 2.8,
            beta: 1.8e-3,
        }
    }
}

impl Validate for BeltDamping {
    fn validate(&self) -> Result<(), InvalidField> {
        check::within("alpha", self.alpha, 0.0, 1e6, "1/s")?;
        check::within("beta", self.beta, 0.0, 1.0, "s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // N(λ) by hand for both laws; the inverse round-trips; dN/dλ against differences.
    #[test]
    fn laws_and_their_inverse() {
        let ea = 8000.0;
        assert!((MaterialLaw::Linear.force(ea, 1.05).0 - 400.0).abs() < 1e-9);
        let (n, dn) = MaterialLaw::StVenantKirchhoff.force(ea, 1.05);
        assert!((n - ea * 1.05 * (1.05f64 * 1.05 - 1.0) / 2.0).abs() < 1e-9);
        assert!(
            (n / (0.05 * ea) - 1.07625).abs() < 1e-12,
            "7.6 % above linear at 5 %"
        );
        let h = 1e-6;
        let fd = (MaterialLaw::StVenantKirchhoff.force(ea, 1.05 + h).0
            - MaterialLaw::StVenantKirchhoff.force(ea, 1.05 - h).0)
            / (2.0 * h);
        assert!((fd - dn).abs() < 1e-4);
        for law in [MaterialLaw::Linear, MaterialLaw::StVenantKirchhoff] {
            for f in [-300.0, 0.0, 400.0, 2000.0] {
                let l = law.stretch(ea, f);
                assert!((law.force(ea, l).0 - f).abs() < 1e-9 * ea, "{law:?} {f}");
            }
        }
    }

    // The wedge: a 40° rib (PK) raises the friction of a grooved wrap by 1/sin 20° = 2.924;
    // back side and flat belt: 1 (closed form).
    #[test]
    fn ribs_raise_the_grooved_friction() {
        let mut s = Section::default();
        assert_eq!(s.friction_factor(WrapSide::Inside), 1.0);
        s.ribs = Some(Ribs {
            count: 6,
            wedge_angle: 40f64.to_radians(),
        });
        assert!((s.friction_factor(WrapSide::Inside) - 2.923_804_400_163_087).abs() < 1e-12);
        assert_eq!(s.friction_factor(WrapSide::Outside), 1.0);
        s.ribs = Some(Ribs {
            count: 0,
            wedge_angle: 0.7,
        });
        assert_eq!(s.validate().unwrap_err().field, "ribs.count");
    }

    // 72 µm for Table 6-1 (seed-000 note §2.3).
    #[test]
    fn table_6_1_mounting_penetration() {
        let p = BeltContact::default().mounting_penetration(310.0, 0.05);
        assert!((p - 72e-6).abs() < 1e-6, "{p}");
    }
}
