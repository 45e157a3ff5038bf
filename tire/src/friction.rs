//! The rolling tire's `friction_law` setting: a name kept for existing configurations, or any
//! law of the contact crate as a table. It only selects a [`FrictionLaw`]; the contact solve
//! ([`contact::solver`]) calls the law through the trait.

use contact::friction::{Coulomb, FrictionLaw, FrictionSpec, SlipRegularized};
use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::sync::Arc;

/// `friction_law` of [`super::RollingConfig`]: `"coulomb"` (set-valued with stick, Ribaric
/// §7.3/§8.4.3; default) or `"regularized"` (Ribaric's slip-only `f = −μλ u/√(|u|²+ε²)`, seed
/// note U20) take μ from `friction` and ε from `slip_regularization`; a table
/// `{ law = "stribeck", … }` is any [`FrictionSpec`] (its coefficients replace `friction`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum TireFriction {
    /// [`Coulomb`] with `μ = friction`.
    #[default]
    Coulomb,
    /// [`SlipRegularized`] with `μ = friction`, `ε = slip_regularization`.
    Regularized,
    /// Any law given in full.
    Law(FrictionSpec),
}

impl TireFriction {
    /// The law as a configuration value, with μ = `mu` and ε = `epsilon` for the named laws.
    pub fn spec(&self, mu: f64, epsilon: f64) -> FrictionSpec {
        match *self {
            TireFriction::Coulomb => FrictionSpec::Coulomb { mu },
            TireFriction::Regularized => FrictionSpec::Regularized { mu, epsilon },
            TireFriction::Law(spec) => spec,
        }
    }

    /// The law behind the trait, as the contact solve takes it.
    pub fn law(&self, mu: f64, epsilon: f64) -> Arc<dyn FrictionLaw> {
        match *self {
            TireFriction::Coulomb => Arc::new(Coulomb { mu }),
            TireFriction::Regularized => Arc::new(SlipRegularized { mu, epsilon }),
            TireFriction::Law(spec) => Arc::new(spec),
        }
    }
}

impl Serialize for TireFriction {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            TireFriction::Coulomb => s.serialize_str("coulomb"),
            TireFriction::Regularized => s.serialize_str("regularized"),
            TireFriction::Law(spec) => spec.serialize(s),
        }
    }
}

impl schemars::JsonSchema for TireFriction {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "TireFriction".into()
    }

    fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
        schemars::json_schema!({
            "anyOf": [
                { "type": "string", "enum": ["coulomb", "regularized"] },
                generator.subschema_for::<FrictionSpec>()
            ]
        })
    }
}

impl<'de> Deserialize<'de> for TireFriction {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = TireFriction;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("\"coulomb\", \"regularized\" or a friction law table")
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<TireFriction, E> {
                match v {
                    "coulomb" => Ok(TireFriction::Coulomb),
                    "regularized" => Ok(TireFriction::Regularized),
                    _ => Err(E::unknown_variant(v, &["coulomb", "regularized"])),
                }
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<TireFriction, A::Error> {
                FrictionSpec::deserialize(de::value::MapAccessDeserializer::new(map))
                    .map(TireFriction::Law)
            }
        }
        d.deserialize_any(V)
    }
}
