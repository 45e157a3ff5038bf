//! Settings of the flowing-material and nodal belt models (the drive itself is a
//! [`belt::Drive`]): the loop's element lengths and the reduction of the flowing model.

use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// Most belt elements a loop may have (sizes from input are bounded before anything is
/// built: the flowing model's matrices are dense, `(3N)²`).
pub const MAX_ELEMENTS: usize = 1500;

/// Element lengths of the belt loop: each span and each wrap of the path is divided into
/// equal elements no longer than the given length (Ribaric §6.1: shorter elements on the arcs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct BeltMesh {
    /// Element length on the spans \[m\] (at least 4 elements per span, and two more than twice
    /// the contact margin).
    pub span_element: f64,
    /// Element length on the wraps \[m\] (at least 3 elements per wrap).
    pub arc_element: f64,
    /// Extra contact nodes beyond each wrap end, on the spans (lift-off margin).
    pub contact_margin_nodes: usize,
}

impl Default for BeltMesh {
    /// Ribaric §6.1's 56-element loop of Table 6-1: 45 mm on the spans (10 per 450 mm span),
    /// 8.73 mm on the wraps (18 per 157 mm half-wrap of the 50 mm pulleys); one margin node.
    fn default() -> Self {
        Self {
            span_element: 0.045,
            arc_element: 0.00873,
            contact_margin_nodes: 1,
        }
    }
}

impl BeltMesh {
    /// Elements on a piece of length `length` \[m\] with target element length `h` \[m\]:
    /// `⌈length/h⌉` (a ratio within 10⁻⁹ of an integer counts as that integer), at least `min`.
    pub fn count(length: f64, h: f64, min: usize) -> usize {
        let r = length / h;
        let n = if (r - r.round()).abs() < 1e-9 * r.max(1.0) {
            r.round()
        } else {
            r.ceil()
        };
        (n as usize).max(min)
    }

    /// Element counts per piece of `path` ([`belt::BeltPath::pieces`]).
    pub fn counts(&self, path: &belt::BeltPath) -> Vec<usize> {
        path.pieces()
            .iter()
            .map(|p| match p.segment {
                belt::Segment::Span { .. } => Self::count(
                    p.length,
                    self.span_element,
                    (2 * self.contact_margin_nodes + 2).max(4),
                ),
                belt::Segment::Arc { .. } => Self::count(p.length, self.arc_element, 3),
            })
            .collect()
    }

    /// The same mesh with the shorter of the two lengths everywhere (what the rotating-mesh
    /// nodal model needs: its nodes travel from the spans onto the wraps).
    pub fn uniform(&self) -> Self {
        let h = self.span_element.min(self.arc_element);
        Self {
            span_element: h,
            arc_element: h,
            ..*self
        }
    }

    /// Checks the lengths and that the loop of `path` stays within [`MAX_ELEMENTS`].
    pub fn check_on(&self, path: &belt::BeltPath) -> Result<(), InvalidField> {
        self.validate()?;
        let n: f64 = path
            .pieces()
            .iter()
            .map(|p| {
                p.length
                    / match p.segment {
                        belt::Segment::Span { .. } => self.span_element,
                        belt::Segment::Arc { .. } => self.arc_element,
                    }
            })
            .sum();
        if n.is_nan() || n > MAX_ELEMENTS as f64 {
            return Err(InvalidField::new(
                "span_element",
                format!(
                    "the loop would have {n:.3e} elements (max {MAX_ELEMENTS}): lengthen the elements"
                ),
            ));
        }
        Ok(())
    }
}

impl Validate for BeltMesh {
    fn validate(&self) -> Result<(), InvalidField> {
        check::within("span_element", self.span_element, 1e-5, 10.0, "m")?;
        check::within("arc_element", self.arc_element, 1e-5, 10.0, "m")?;
        check::count("contact_margin_nodes", self.contact_margin_nodes, 0, 20)
    }
}

/// How the belt's deflection field is reduced.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct BeltReduction {
    /// Fixed-interface (free-node) modes kept; `None` keeps all (no truncation). In TOML a
    /// number, or `"all"` for `None` (so that a printed configuration reads back unchanged).
    #[serde(with = "mode_count")]
    #[schemars(with = "mode_count::Count")]
    pub free_modes: Option<usize>,
}

/// `Option<usize>` as a number or the string `"all"` (`None`): TOML has no null.
mod mode_count {
    use serde::{Deserialize, Deserializer, Serializer, de::Error};

    /// A number of modes, or `"all"`.
    #[derive(Deserialize, schemars::JsonSchema)]
    #[serde(untagged)]
    pub(super) enum Count {
        N(usize),
        S(String),
    }

    pub fn serialize<S: Serializer>(v: &Option<usize>, s: S) -> Result<S::Ok, S::Error> {
        match v {
            Some(n) => s.serialize_u64(*n as u64),
            None => s.serialize_str("all"),
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<usize>, D::Error> {
        match Count::deserialize(d)? {
            Count::N(n) => Ok(Some(n)),
            Count::S(s) if s == "all" => Ok(None),
            Count::S(s) => Err(D::Error::custom(format!(
                "expected a number of modes or \"all\", got \"{s}\""
            ))),
        }
    }
}

impl Default for BeltReduction {
    /// 20 free-node modes.
    fn default() -> Self {
        Self {
            free_modes: Some(20),
        }
    }
}

/// How the belt elements of the flowing and nodal models carry their axial force.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema, Default,
)]
#[serde(rename_all = "snake_case")]
pub enum AxialForce {
    /// The linear model of Ribaric (5.5): `f0 − (K_e + K_g(T0)) δ`, the increment `EA Δl/l`
    /// along the reference chord. Its elements do not balance moments once the wraps' nodes
    /// turn by `u_t/R` (a torque error of order `Σ N₁ Δv`, 4–5 % of the transmitted torque on
    /// the Pechstein–Gerstmayr drive, issue 34). The flowing model's default: the co-rotated
    /// force closes Table 6-1 at 30 N m (0.22 % against 0.74 %) but not the default fead drive
    /// (at 800 rpm torque / power residuals 0.72 % / −2.8 % against the linear model's
    /// 0.72 % / −1.1 %, and its sweep stops at 1500 rpm), so it is not the default (issue 34,
    /// open).
    #[default]
    Linear,
    /// Each element's force `N = F(λ₀ l/l₀)` of the belt's material law (`belt::Section::law`,
    /// mounted at `F(λ₀) = T0`) along its deformed chord (co-rotated
    /// bar, [`super::model::Bar`]): the belt balances angular momentum at finite rotation.
    /// The nodal model's default.
    CoRotated,
}

/// How the flowing model's belt elements carry the axial part of their Kelvin–Voigt damping
/// force `β EA Dε/Dt` (issue 34 item 2). Selectable in `[models.flowing]` as `viscous_force`.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema, Default,
)]
#[serde(rename_all = "snake_case")]
pub enum ViscousForce {
    /// The linear Rayleigh damping `β K_e (δ̇_m − v ψ′ J δ)` of Ribaric (5.5) on the co-rotated
    /// material rate `δ̇_m = T ż + v T_,s z` of (5.10), along the mesh's (reference) chords.
    /// Its forces do work on the material's slide (on the default fead drive at 800 rpm +10.8 W
    /// where their Kelvin–Voigt dissipation is 29.8 W, issue 34). Table 6-1's figure
    /// (Δω = 0.18630 rad/s at 10 N m) is taken with it; [`Self::Auto`] takes it with Ribaric's
    /// κ law.
    Linear,
    /// Kelvin–Voigt on the material rate of each deformed chord's length, along the deformed
    /// chord: `N_v = (β EA/l₀) (û·ΔT ż + v l₀ ∂λ/∂s)`, the convective part of (5.10) taken on the
    /// chords' stretches `λ = l/l₀` (`super::FlowingBelt`'s `chord_viscous`): no force in a
    /// rigid motion or in the mounted state, and the forces of the Rayleigh function
    /// `R = Σ_e ½ (β EA/l₀)(Dl/Dt)²`, so that with [`BeltEquations::Lagrange`] the belt loses
    /// exactly `2R`. Bending keeps the linear form. Measured 2026-12-06 (torque / power
    /// residual): Table 6-1 at 10 N m 0.14 % / −0.40 % but Δω = 0.19079 rad/s (+2.4 % on
    /// Ribaric's 0.18630, which the linear damping reproduces; the nodal model gives 0.19426);
    /// default fead drive at 800 rpm 0.98 % / −1.63 % (linear damping: 0.72 % / −1.06 %). Not
    /// taken with Ribaric's κ law.
    Chord,
    /// The default: [`Self::Linear`] when the drive's friction is Ribaric's κ law
    /// (`{ law = "tanh", mu, kappa }`, Ribaric (6.2): the seed's formulation), [`Self::Chord`]
    /// with any other law, as [`ContactVelocity::Auto`]: with the chord contact rates the
    /// linear damping's convective term `β K_e v T_,s z` (App. A's operator) still carries the
    /// tangent points' error into the creep, and the speed loss converges in the law's scale
    /// only below 0.05 mm/s (BENCHMARKS.md, "friction regularisation": Table 6-1 at 10 N m,
    /// 0.0775 rad/s at 0.5 mm/s, 0.0814 at 0.125 mm/s, 0.0838 at 0.0125 mm/s); with the chord
    /// damping as well 0.0814, 0.0816 and 0.0823 (0.3 % from the run at `v_s / 4` at 0.5 mm/s;
    /// closed form 0.0824). Resolved once, when the model is built ([`Self::resolve`]).
    #[default]
    Auto,
}

impl ViscousForce {
    /// The damping force taken with the friction law `law`: [`Self::Auto`] resolved (linear
    /// with `FrictionSpec::Tanh`, the chords' otherwise), the others as they are.
    pub fn resolve(self, law: &::contact::friction::FrictionSpec) -> Self {
        match self {
            Self::Auto if law.is_ribaric_tanh() => Self::Linear,
            Self::Auto => Self::Chord,
            other => other,
        }
    }
}

/// Which equations of motion the flowing model integrates for its travel `s_b` and modal
/// coordinates `z` (`super::FlowingBelt`'s module documentation). Selectable in
/// `[models.flowing]` as `equations`.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema, Default,
)]
#[serde(rename_all = "snake_case")]
pub enum BeltEquations {
    /// Ribaric's projection (5.14) of the nodal balance on `[e_t | T]`: the pulleys' torques
    /// close with the spans', the power does not (the elastic and damping forces work on the
    /// slide).
    #[default]
    Ribaric,
    /// Lagrange's equations of `(s_b, z)` (`super::FlowingBelt::with_lagrange_equations`):
    /// energy-exact for any mesh; the same defect then lands on the reference node's tangential
    /// balance, i.e. on the driver's torque (default fead drive at 800 rpm: torque 4.81 %, power
    /// 0.65 %; with [`ViscousForce::Chord`] 3.15 % / 0.71 %).
    Lagrange,
}

/// How the flowing model's belt elements carry their bending moment (issue 34 item 2).
/// Selectable in `[models.flowing]` as `bending`.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema, Default,
)]
#[serde(rename_all = "snake_case")]
pub enum BendingForce {
    /// The Hermite frame element of Ribaric (5.5), linear about the mounted path and stress-free
    /// on it: the belt's natural curvature is the path's, which jumps by `1/R` at every tangent
    /// point, so the bending forces do work on the material's slide (`EI/R²` = 33 N on the
    /// default fead drive's 28 mm pulleys; issue 34).
    #[default]
    Linear,
    /// A naturally straight, co-rotated bending element with its geometric stiffness
    /// ([`super::model::BendElement`]): the bending energy `½ ∫ EI κ² ds` of the true
    /// curvature, so the material flowing through a wrap does no net bending work. Replaces the
    /// bending block of the elastic stiffness `K_e` (the reduction basis stays that of the
    /// linear model); the geometric stiffness of the pre-tension `K_g(T0)` stays linear, and the
    /// bending is undamped (the linear `β K_b` on the advected lift-off deflection dissipated
    /// 70 W on the default fead drive at 800 rpm against the nodal belt's 25.8 W in all).
    /// Measured 2026-12-06 (torque / power residual, default fead drive at 800 rpm): with the
    /// chord damping ([`ViscousForce::Chord`]) 0.46 % / −0.88 % (crank 18.49 N m; the linear
    /// model 0.72 % / −1.06 %, 18.29 N m; nodal 19.00 N m), with the linear damping
    /// 0.48 % / −6.0 %; on Table 6-1 at 10 N m 1.35 % / −0.31 % with Δω = 0.19186 rad/s
    /// (Ribaric's 0.18630: a naturally straight belt is another belt, stiffer to wrap), and
    /// runs on the default fead drive with 4 or 8 mm wraps or 40 free modes stop on a singular
    /// Newton matrix. Not the default (issue 34, open).
    CoRotated,
}

/// How the flowing model takes the material velocity of its contact nodes, whose slip
/// against the pulley drives the friction (Ribaric (5.10), `V = v b + T ż`, `b = e_t + T_,s z`;
/// issue 34 item 3). Selectable in `[models.flowing]` as `contact_velocity`.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema, Default,
)]
#[serde(rename_all = "snake_case")]
pub enum ContactVelocity {
    /// Ribaric's `T_,s`, the three-point difference of each Cartesian component along the path
    /// (his appendix A), the operator of the whole model. At a tangent point it mixes the wrap's
    /// radial deflection (the change of penetration, rotated by the wrap's turn) into the
    /// tangential rate, a spurious slip of about `v Δd/(2R)` at the inlet and lift-off nodes
    /// that a near-Coulomb law answers with a friction force there: on Table 6-1 at 10 N m
    /// with `tanh_slip` at 0.05 mm/s the speed loss is 0.0570 rad/s on the default mesh
    /// against Grashof's creep 0.0824 (−31 %), 0.0775 with 5 mm span elements. Table 6-1's
    /// figure (Δω = 0.18630 rad/s at κ = 40 s/m) is taken with it; [`Self::Auto`] takes it
    /// with Ribaric's κ law.
    Ribaric,
    /// The node's rate taken on its two elements' chords ([`super::BeltFe::chord_rate_rows`]):
    /// each chord's difference quotient split into its stretch and its turn, the two
    /// tributary-weighted and set in the node's frame, so that the tangential material
    /// velocity is `v (1 + ε)` with `ε` the mean strain the node's two elements carry (mass
    /// conservation on the mesh). Only the contact rows change (their slip and its tangent,
    /// and the contact's generalized force on `s_b`). Measured 2026-12-07 (Table 6-1, 10 N m,
    /// `tanh_slip` at 0.05 mm/s; BENCHMARKS.md): 0.0829 rad/s on the default mesh (+0.6 % on
    /// Grashof), 0.0842 on 5 mm span elements; with [`ViscousForce::Chord`] as well 0.0818 and
    /// 0.0822 (−0.7 %, −0.2 %): the creep no longer depends on the span mesh. At κ = 40 s/m
    /// Δω = 0.18934 rad/s with the torque / power residuals unchanged (0.24 % / −0.42 %); on
    /// the default fead drive at 800 rpm 0.75 % / −1.47 % (the default: 0.72 % / −1.06 %).
    /// Not taken with Ribaric's κ law: it moves Table 6-1's figure by +1.6 %.
    Chord,
    /// The default: [`Self::Ribaric`] when the drive's friction is Ribaric's κ law
    /// (`{ law = "tanh", mu, kappa }`, Ribaric (6.2): the seed's formulation, with which
    /// Table 6-1's Δω = 0.18630 rad/s and the studies recorded at κ = 40 s/m were taken),
    /// [`Self::Chord`] with any other law (the layouts' default `tanh_slip`, Coulomb, a
    /// regularised or creep-rate law), whose speed loss near Coulomb is then the elastic creep
    /// of the belt's strain (Grashof; BENCHMARKS.md, "friction regularisation": on Table 6-1
    /// at 10 N m with the default `tanh_slip` the flowing belt lies near the closed form
    /// with the chord rates and 31 % below it with Ribaric's; [`ViscousForce::Auto`] takes the
    /// chord damping with them, without which the speed loss converges in the law's scale only
    /// below 0.05 mm/s). Resolved once, when the model is built ([`Self::resolve`]).
    #[default]
    Auto,
}

impl ContactVelocity {
    /// The rates taken with the friction law `law`: [`Self::Auto`] resolved (Ribaric's with
    /// `FrictionSpec::Tanh`, the chord rates otherwise), the others as they are.
    pub fn resolve(self, law: &::contact::friction::FrictionSpec) -> Self {
        match self {
            Self::Auto if law.is_ribaric_tanh() => Self::Ribaric,
            Self::Auto => Self::Chord,
            other => other,
        }
    }
}

/// The flowing-material model's settings (Ribaric (5.14)).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema, Default)]
#[serde(default, deny_unknown_fields)]
pub struct FlowingSettings {
    /// The stationary loop.
    pub mesh: BeltMesh,
    /// Reduction of the deflection field.
    pub reduction: BeltReduction,
    /// The elements' axial force (default: linear, Ribaric (5.5)).
    pub axial_force: AxialForce,
    /// The axial part of the elements' damping force (default `auto`: linear, Ribaric (5.5),
    /// with Ribaric's κ law, along the deformed chords with any other friction law).
    pub viscous_force: ViscousForce,
    /// The equations of motion (default: Ribaric's projection (5.14)).
    pub equations: BeltEquations,
    /// The elements' bending moment (default: linear, Ribaric (5.5)).
    pub bending: BendingForce,
    /// The contact nodes' material velocity (default `auto`: Ribaric's `T_,s` (5.10) with
    /// Ribaric's κ law, the elements' chords with any other friction law).
    pub contact_velocity: ContactVelocity,
}

impl Validate for FlowingSettings {
    fn validate(&self) -> Result<(), InvalidField> {
        self.mesh.validate_within("mesh")?;
        if let Some(n) = self.reduction.free_modes {
            check::count("reduction.free_modes", n, 0, 3 * MAX_ELEMENTS)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ::contact::friction::FrictionSpec;

    // Reference (the rule of ContactVelocity::Auto and ViscousForce::Auto, by hand): Ribaric's
    // operator with Ribaric's κ law, whatever κ; the chords' with every other law; a stated
    // choice is kept.
    #[test]
    fn auto_takes_ribarics_operator_with_ribarics_law_only() {
        let kappa = FrictionSpec::Tanh {
            mu: 1.2,
            kappa: 1000.0,
        };
        let others = [
            FrictionSpec::tanh_slip(1.2),
            FrictionSpec::Coulomb { mu: 0.5 },
            FrictionSpec::Regularized {
                mu: 0.5,
                epsilon: 4e-3,
            },
        ];
        let s = FlowingSettings::default();
        assert_eq!(s.contact_velocity, ContactVelocity::Auto);
        assert_eq!(s.viscous_force, ViscousForce::Auto);
        assert_eq!(s.contact_velocity.resolve(&kappa), ContactVelocity::Ribaric);
        assert_eq!(s.viscous_force.resolve(&kappa), ViscousForce::Linear);
        for law in &others {
            assert_eq!(s.contact_velocity.resolve(law), ContactVelocity::Chord);
            assert_eq!(s.viscous_force.resolve(law), ViscousForce::Chord);
            assert_eq!(
                ContactVelocity::Ribaric.resolve(law),
                ContactVelocity::Ribaric
            );
            assert_eq!(ViscousForce::Linear.resolve(law), ViscousForce::Linear);
        }
        assert_eq!(
            ContactVelocity::Chord.resolve(&kappa),
            ContactVelocity::Chord
        );
        assert_eq!(ViscousForce::Chord.resolve(&kappa), ViscousForce::Chord);
    }
}
