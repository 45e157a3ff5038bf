//! Parameters of a two-pulley belt drive (defaults: Ribaric Table 6-1).

use contact::friction::FrictionSpec;
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};

/// Geometry of the drive: pulley 1 (driver) at (0, 0), pulley 2 (driven) at (`center_distance`, 0).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DriveGeometry {
    /// Centre distance L_c \[m\].
    pub center_distance: f64,
    /// Driver pulley radius (belt line) \[m\].
    pub radius_driver: f64,
    /// Driven pulley radius (belt line) \[m\].
    pub radius_driven: f64,
}

impl Default for DriveGeometry {
    /// Ribaric Table 6-1: L_c = 0.45 m, R = 0.05 m.
    fn default() -> Self {
        Self {
            center_distance: 0.45,
            radius_driver: 0.05,
            radius_driven: 0.05,
        }
    }
}

/// Belt section and pre-tension.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BeltSection {
    /// Axial stiffness EA \[N\].
    pub ea: f64,
    /// Bending stiffness EI \[N·m²\].
    pub ei: f64,
    /// Mass per unit length ρA \[kg/m\].
    pub mass_per_length: f64,
    /// Pre-tension T0 \[N\] of the reference (mounted) state.
    ///
    /// Ribaric U8: the printed belt length 1.2 m cannot be stretched onto the 1.214 m path at
    /// 310 N; we take the path of L_c and R as printed and make T0 the tension of that
    /// reference state (unstretched length `L_path / (1 + T0/EA)` = 1.2117 m).
    pub tension: f64,
}

impl Default for BeltSection {
    /// Ribaric Table 6-1: EA = 152 000 N, EI = 2.6·10⁻² N m², ρ = 0.096 kg/m; T0 = 310 N (§6.4).
    fn default() -> Self {
        Self {
            ea: 152_000.0,
            ei: 2.6e-2,
            mass_per_length: 0.096,
            tension: 310.0,
        }
    }
}

/// Element counts of the closed loop (shorter elements on the arcs, Ribaric §6.1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BeltMesh {
    /// Elements per straight span.
    pub span_elements: usize,
    /// Elements per pulley arc.
    pub arc_elements: usize,
    /// Extra contact nodes beyond each arc end, on the spans (lift-off margin).
    pub contact_margin_nodes: usize,
}

impl Default for BeltMesh {
    /// 56 elements (Ribaric §6.1): 10 per span (45 mm), 18 per arc (8.7 mm); one margin node.
    fn default() -> Self {
        Self {
            span_elements: 10,
            arc_elements: 18,
            contact_margin_nodes: 1,
        }
    }
}

/// Belt–pulley contact: penalty (6.1) and tanh friction (6.2), or any friction law.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BeltContact {
    /// Quadratic penalty coefficient of (6.1) \[N/m³ per metre of belt\].
    pub penalty_quadratic: f64,
    /// Linear penalty coefficient of (6.1) \[N/m² per metre of belt\].
    pub penalty_linear: f64,
    /// Kinetic friction coefficient μ_kin.
    pub mu: f64,
    /// Slope of the tanh regularisation κ \[s/m\].
    pub kappa: f64,
    /// Friction law table (`{ law = "stribeck", … }`, see [`FrictionSpec`]) replacing the
    /// tanh law of `mu` and `kappa` when given.
    pub friction: Option<FrictionSpec>,
}

impl BeltContact {
    /// The friction law per contact node: `friction` if given, else Ribaric (6.2) with `mu`,
    /// `kappa`.
    pub fn friction_law(&self) -> FrictionSpec {
        self.friction.unwrap_or(FrictionSpec::Tanh {
            mu: self.mu,
            kappa: self.kappa,
        })
    }
}

impl Default for BeltContact {
    /// Ribaric (6.1), (6.2) and Table 6-1: 3025.6·10⁸ N/m³, 6.5·10⁷ N/m², μ = 1.2, κ = 40 s/m.
    fn default() -> Self {
        Self {
            penalty_quadratic: 3025.6e8,
            penalty_linear: 6.5e7,
            mu: 1.2,
            kappa: 40.0,
            friction: None,
        }
    }
}

/// Rayleigh damping `C = α M + β K` (Table 6-1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BeltDamping {
    /// Mass-proportional coefficient α \[1/s\].
    pub alpha: f64,
    /// Stiffness-proportional coefficient β \[s\].
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

/// How the belt's deflection field is reduced.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BeltReduction {
    /// Fixed-interface (free-node) modes kept; `None` keeps all (no truncation). In TOML a
    /// number, or `"all"` for `None` (so that a printed configuration reads back unchanged).
    #[serde(with = "mode_count")]
    pub free_modes: Option<usize>,
}

/// `Option<usize>` as a number or the string `"all"` (`None`): TOML has no null.
mod mode_count {
    use serde::{Deserialize, Deserializer, Serializer, de::Error};

    pub fn serialize<S: Serializer>(v: &Option<usize>, s: S) -> Result<S::Ok, S::Error> {
        match v {
            Some(n) => s.serialize_u64(*n as u64),
            None => s.serialize_str("all"),
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<usize>, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Count {
            N(usize),
            S(String),
        }
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

/// A two-pulley belt drive (Ribaric ch. 5–6, Table 6-1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BeltDriveConfig {
    /// Pulley positions and radii.
    pub geometry: DriveGeometry,
    /// Belt section and pre-tension.
    pub belt: BeltSection,
    /// Mesh.
    pub mesh: BeltMesh,
    /// Contact and friction.
    pub contact: BeltContact,
    /// Rayleigh damping.
    pub damping: BeltDamping,
    /// Reduction of the flowing model.
    pub reduction: BeltReduction,
    /// Moment of inertia of the driven pulley about its axis \[kg m²\] (Table 6-1: 0.013).
    pub driven_inertia: f64,
}

impl Default for BeltDriveConfig {
    fn default() -> Self {
        Self {
            geometry: DriveGeometry::default(),
            belt: BeltSection::default(),
            mesh: BeltMesh::default(),
            contact: BeltContact::default(),
            damping: BeltDamping::default(),
            reduction: BeltReduction::default(),
            driven_inertia: 0.013,
        }
    }
}

impl Validate for BeltDriveConfig {
    /// Every field checked; the error names the field (path relative to this struct).
    fn validate(&self) -> Result<(), InvalidField> {
        let pos = [
            ("geometry.center_distance", self.geometry.center_distance),
            ("geometry.radius_driver", self.geometry.radius_driver),
            ("geometry.radius_driven", self.geometry.radius_driven),
            ("belt.ea", self.belt.ea),
            ("belt.ei", self.belt.ei),
            ("belt.mass_per_length", self.belt.mass_per_length),
            ("belt.tension", self.belt.tension),
            ("contact.penalty_linear", self.contact.penalty_linear),
            ("driven_inertia", self.driven_inertia),
        ];
        for (name, v) in pos {
            if !(v.is_finite() && v > 0.0) {
                return Err(InvalidField::new(
                    name,
                    format!("must be finite and > 0 (got {v})"),
                ));
            }
        }
        let nonneg = [
            ("contact.penalty_quadratic", self.contact.penalty_quadratic),
            ("contact.mu", self.contact.mu),
            ("contact.kappa", self.contact.kappa),
            ("damping.alpha", self.damping.alpha),
            ("damping.beta", self.damping.beta),
        ];
        for (name, v) in nonneg {
            if !(v.is_finite() && v >= 0.0) {
                return Err(InvalidField::new(
                    name,
                    format!("must be finite and >= 0 (got {v})"),
                ));
            }
        }
        if let Some(f) = self.contact.friction {
            f.validate_within("contact.friction")?;
        }
        if self.mesh.span_elements < 2 {
            return Err(InvalidField::new(
                "mesh.span_elements",
                "must be at least 2",
            ));
        }
        if self.mesh.arc_elements < 2 {
            return Err(InvalidField::new("mesh.arc_elements", "must be at least 2"));
        }
        if 2 * self.mesh.contact_margin_nodes + 1 >= self.mesh.span_elements {
            return Err(InvalidField::new(
                "mesh.contact_margin_nodes",
                "leaves no free node on the spans",
            ));
        }
        if self.geometry.center_distance
            <= (self.geometry.radius_driven - self.geometry.radius_driver).abs()
        {
            return Err(InvalidField::new(
                "geometry.center_distance",
                "pulleys overlap: no open-belt path",
            ));
        }
        Ok(())
    }
}
