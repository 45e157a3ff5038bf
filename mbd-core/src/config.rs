//! Partial configurations read over the defaults, deeply (issue 39).
//!
//! A study's configuration is a plain `serde` struct whose `Default` is the seed's case. A user
//! who changes one number of it — the installation tension of the default drive, one step size —
//! writes only that key; [`from_partial`] reads it over the defaults:
//!
//! * a table is merged key by key, at every depth (`[drive] tension = 300` keeps the default
//!   drive's pulleys, section and contact);
//! * an array (the pulleys of a drive, a list of torques) and a scalar replace the default whole;
//! * a table that selects another variant of an enum (a [`VARIANT_TAGS`] key whose value differs
//!   from the default's, e.g. `law = "coulomb"` where the default friction is `law = "creep"`) replaces
//!   the default table whole when merging it would mix the two variants' keys: the merge is tried
//!   first and the replacement only when the merged table does not deserialize; likewise an
//!   externally tagged enum (serde's default representation, a one-key table named by its
//!   variant, e.g. `derivative = { Spectral = ... }` over the default
//!   `{ FiniteDifference = ... }`): a one-key table over a one-key default of another key;
//! * a key the user gives drops from the defaults the keys that depend on it or exclude it, as
//!   the configuration type declares ([`PartialRules::DROPPED_BY`]; this crate knows no
//!   domain's keys: the belt drive's rules are `belt::PARTIAL_RULES`, declared by every
//!   configuration that holds a belt layout).
//!
//! The CLI's TOML reader and the Python package's dictionary configurations both go through
//! [`from_partial`], so a partial configuration means the same on both.

use serde::Serialize;
use serde::de::DeserializeOwned;

/// The merge rules a configuration type declares for [`from_partial`] (module documentation).
///
/// Every configuration read with [`from_partial`] implements it; a type without keys that
/// exclude each other takes the default (`impl PartialRules for MyConfig {}`). A type that
/// holds another type with rules (at any depth) declares them too: the rules apply to every
/// table of the tree.
pub trait PartialRules {
    /// `(given, dropped)`: when a user's table gives the key `given`, the default's key
    /// `dropped` in the same table is left out (e.g. a length that excludes a tension, a list
    /// whose indices another key refers to) unless the user gives it too. `dropped` may be a
    /// dotted path into the table's sub-tables (`contact.friction`: the default's friction
    /// goes, the rest of its contact stays). None by default.
    const DROPPED_BY: &'static [(&'static str, &'static str)] = &[];
}

/// The keys that name an enum's variant in the workspace's configurations (`#[serde(tag =
/// ...)]`: a pulley's motion `kind`, a friction `law`): a table whose tag the user changes
/// switches the variant.
pub const VARIANT_TAGS: &[&str] = &["kind", "law"];

/// A partial configuration that does not deserialize over the defaults.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{path}: {message}")]
pub struct PartialConfigError {
    /// Dotted path of the offending key (`drive.pulleys[2].radius`; `<root>` for the top).
    pub path: String,
    /// What the deserializer reported.
    pub message: String,
}

impl PartialConfigError {
    /// The path as its steps (keys and array indices), for locating it in a source text.
    pub fn steps(&self) -> Vec<PathStep> {
        parse_path(&self.path)
    }
}

/// One step of a path into a configuration tree.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PathStep {
    /// A key of a table.
    Key(String),
    /// An index of an array.
    Index(usize),
}

/// `user` read over `C::default()` (module documentation): merged table by table, arrays and
/// scalars replaced, a table that switches an enum's variant replaced whole, the default keys
/// that a given key excludes dropped ([`PartialRules::DROPPED_BY`] of `C`).
pub fn from_partial<C>(user: toml::Table) -> Result<C, PartialConfigError>
where
    C: Serialize + DeserializeOwned + Default + PartialRules,
{
    let Ok(defaults) = toml::Table::try_from(C::default()) else {
        // a default that TOML cannot hold (none in the workspace): the user's table alone
        return deserialize(user);
    };
    let mut switches = Vec::new();
    let merged = merge::<C>(
        defaults.clone(),
        user.clone(),
        &mut Vec::new(),
        &mut switches,
        &[],
    );
    match deserialize::<C>(merged) {
        Ok(c) => Ok(c),
        Err(_) if !switches.is_empty() => {
            let replaced = merge::<C>(defaults, user, &mut Vec::new(), &mut Vec::new(), &switches);
            // both fail: the replaced tables' error is about the keys the user wrote for the
            // variant chosen
            deserialize::<C>(replaced)
        }
        Err(first) => Err(first),
    }
}

fn deserialize<C: DeserializeOwned>(t: toml::Table) -> Result<C, PartialConfigError> {
    serde_path_to_error::deserialize(toml::Value::Table(t)).map_err(|e| {
        let path = e.path().to_string();
        PartialConfigError {
            path: if path == "." { "<root>".into() } else { path },
            message: e.into_inner().message().trim().to_string(),
        }
    })
}

/// `user` merged over `base`. `here` is the path of the tables being merged; the paths of
/// tables that switch a variant are pushed to `switches`; the tables at `replace` are taken from
/// `user` whole; the default keys that a given key excludes are dropped (`C`'s rules).
fn merge<C: PartialRules>(
    mut base: toml::Table, user: toml::Table, here: &mut Vec<PathStep>,
    switches: &mut Vec<Vec<PathStep>>, replace: &[Vec<PathStep>],
) -> toml::Table {
    if replace.iter().any(|r| r == here) {
        return user;
    }
    let switches_variant = user.iter().any(|(k, v)| {
        VARIANT_TAGS.contains(&k.as_str())
            && matches!((v, base.get(k)), (toml::Value::String(a), Some(toml::Value::String(b))) if a != b)
    });
    // an externally tagged enum: one key, the variant's name, in the default and in the user's
    // table, and they differ
    let switches_external = base.len() == 1
        && user.len() == 1
        && base.keys().next() != user.keys().next()
        && !here.is_empty();
    if switches_variant || switches_external {
        switches.push(here.clone());
    }
    for &(given, dropped) in C::DROPPED_BY {
        if user.contains_key(given) && lookup(&user, dropped).is_none() {
            remove(&mut base, dropped);
        }
    }
    for (k, v) in user {
        let merged = match (base.remove(&k), v) {
            (Some(toml::Value::Table(b)), toml::Value::Table(u)) => {
                here.push(PathStep::Key(k.clone()));
                let m = merge::<C>(b, u, here, switches, replace);
                here.pop();
                toml::Value::Table(m)
            }
            (_, v) => v,
        };
        base.insert(k, merged);
    }
    base
}

/// The value at the dotted key path `path` (`contact.friction`) of `table`, through its
/// sub-tables.
fn lookup<'a>(table: &'a toml::Table, path: &str) -> Option<&'a toml::Value> {
    let (head, rest) = match path.split_once('.') {
        Some((h, r)) => (h, Some(r)),
        None => (path, None),
    };
    let v = table.get(head)?;
    match (rest, v) {
        (None, v) => Some(v),
        (Some(r), toml::Value::Table(t)) => lookup(t, r),
        (Some(_), _) => None,
    }
}

/// Remove the dotted key path `path` from `table` (nothing when it is not there).
fn remove(table: &mut toml::Table, path: &str) {
    match path.split_once('.') {
        None => {
            table.remove(path);
        }
        Some((head, rest)) => {
            if let Some(toml::Value::Table(t)) = table.get_mut(head) {
                remove(t, rest);
            }
        }
    }
}

/// The dotted text of a path (`drive.pulleys[2].radius`; `<root>` for the empty path), the
/// inverse of [`PartialConfigError::steps`].
pub fn path_text(steps: &[PathStep]) -> String {
    let mut s = String::new();
    for step in steps {
        match step {
            PathStep::Key(k) => {
                if !s.is_empty() {
                    s.push('.');
                }
                s.push_str(k);
            }
            PathStep::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    if s.is_empty() { "<root>".into() } else { s }
}

fn parse_path(path: &str) -> Vec<PathStep> {
    let mut steps = Vec::new();
    if path == "<root>" {
        return steps;
    }
    for part in path.split('.') {
        let (key, mut rest) = match part.find('[') {
            Some(i) => (&part[..i], &part[i..]),
            None => (part, ""),
        };
        if !key.is_empty() {
            steps.push(PathStep::Key(key.to_string()));
        }
        while let Some(end) = rest.find(']') {
            if let Ok(i) = rest[1..end].parse() {
                steps.push(PathStep::Index(i));
            }
            rest = &rest[end + 1..];
        }
    }
    steps
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
    #[serde(tag = "law", rename_all = "snake_case", deny_unknown_fields)]
    enum Friction {
        Creep { kappa: f64, mu: f64 },
        Coulomb { mu: f64 },
    }

    #[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
    #[serde(deny_unknown_fields)]
    struct Pulley {
        radius: f64,
    }

    #[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
    #[serde(deny_unknown_fields)]
    struct Drive {
        pulleys: Vec<Pulley>,
        tension: f64,
        friction: Friction,
        name: String,
    }

    #[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
    #[serde(deny_unknown_fields)]
    struct Study {
        drive: Drive,
        speeds: Vec<f64>,
    }

    impl PartialRules for Study {}

    impl Default for Study {
        fn default() -> Self {
            Study {
                drive: Drive {
                    pulleys: vec![Pulley { radius: 0.1 }, Pulley { radius: 0.2 }],
                    tension: 400.0,
                    friction: Friction::Creep {
                        kappa: 40.0,
                        mu: 0.5,
                    },
                    name: "seed".into(),
                },
                speeds: vec![1.0, 2.0],
            }
        }
    }

    fn read(text: &str) -> Result<Study, PartialConfigError> {
        from_partial(toml::from_str(text).unwrap())
    }

    #[test]
    fn one_number_changes_alone() {
        // reference: the defaults with that one field set by hand
        let s = read("[drive]\ntension = 300.0\n").unwrap();
        let mut expected = Study::default();
        expected.drive.tension = 300.0;
        assert_eq!(s, expected);
    }

    #[test]
    fn a_string_field_that_is_not_a_tag_merges() {
        let s = read("[drive]\nname = \"mine\"\n").unwrap();
        assert_eq!(s.drive.name, "mine");
        assert_eq!(s.drive.pulleys.len(), 2);
    }

    #[test]
    fn arrays_replace_whole() {
        let s = read("speeds = [5.0]\n[[drive.pulleys]]\nradius = 0.3\n").unwrap();
        assert_eq!(s.speeds, vec![5.0]);
        assert_eq!(s.drive.pulleys, vec![Pulley { radius: 0.3 }]);
        assert_eq!(s.drive.tension, 400.0);
    }

    #[test]
    fn a_variant_switch_replaces_the_table() {
        let s = read("[drive.friction]\nlaw = \"coulomb\"\nmu = 0.3\n").unwrap();
        assert_eq!(s.drive.friction, Friction::Coulomb { mu: 0.3 });
        // the same variant merges: kappa kept
        let s = read("[drive.friction]\nmu = 0.3\n").unwrap();
        assert_eq!(
            s.drive.friction,
            Friction::Creep {
                kappa: 40.0,
                mu: 0.3
            }
        );
    }

    /// An externally tagged enum (serde's default representation): the user's one-key table of
    /// another variant replaces the default's (reference: the value written by hand), and a
    /// table of the same variant merges.
    #[test]
    fn an_external_variant_switch_replaces_the_table() {
        #[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
        #[serde(deny_unknown_fields)]
        enum Derivative {
            Stencil { first: String, second: String },
            Galerkin(String),
            Spectral,
        }
        #[derive(Debug, Serialize, Deserialize, schemars::JsonSchema)]
        #[serde(deny_unknown_fields)]
        struct Reduction {
            modes: usize,
            derivative: Derivative,
        }
        impl PartialRules for Reduction {}
        impl Default for Reduction {
            fn default() -> Self {
                Reduction {
                    modes: 50,
                    derivative: Derivative::Stencil {
                        first: "central".into(),
                        second: "three".into(),
                    },
                }
            }
        }
        let r = |t: &str| from_partial::<Reduction>(toml::from_str(t).unwrap());
        let g = r("[derivative]\nGalerkin = \"lumped\"\n").unwrap();
        assert_eq!(g.derivative, Derivative::Galerkin("lumped".into()));
        assert_eq!(g.modes, 50);
        let sp = r("derivative = \"Spectral\"\n").unwrap();
        assert_eq!(sp.derivative, Derivative::Spectral);
        let m = r("[derivative.Stencil]\nfirst = \"three\"\n").unwrap();
        assert_eq!(
            m.derivative,
            Derivative::Stencil {
                first: "three".into(),
                second: "three".into()
            }
        );
    }

    #[test]
    fn a_given_key_drops_the_defaults_it_excludes() {
        #[derive(Debug, Serialize, Deserialize, schemars::JsonSchema)]
        #[serde(deny_unknown_fields)]
        struct Mount {
            #[serde(default, skip_serializing_if = "Option::is_none")]
            tension: Option<f64>,
            #[serde(default, skip_serializing_if = "Option::is_none")]
            belt_length: Option<f64>,
            pulleys: Vec<f64>,
            #[serde(default, skip_serializing_if = "Option::is_none")]
            tensioner: Option<usize>,
        }
        // the rules of a belt drive's layout (the belt crate's), declared by the type
        impl PartialRules for Mount {
            const DROPPED_BY: &'static [(&'static str, &'static str)] = &[
                ("tension", "belt_length"),
                ("belt_length", "tension"),
                ("pulleys", "tensioner"),
            ];
        }
        impl Default for Mount {
            fn default() -> Self {
                Mount {
                    tension: Some(400.0),
                    belt_length: None,
                    pulleys: vec![0.1, 0.2, 0.3],
                    tensioner: Some(2),
                }
            }
        }
        // new pulleys: the default tensioner (index 2 of the old list) goes
        let m: Mount = from_partial(toml::from_str("pulleys = [0.1, 0.2]").unwrap()).unwrap();
        assert_eq!((m.pulleys.len(), m.tensioner), (2, None));
        let m: Mount =
            from_partial(toml::from_str("pulleys = [0.1, 0.2]\ntensioner = 1").unwrap()).unwrap();
        assert_eq!(m.tensioner, Some(1));
        let m: Mount = from_partial(toml::from_str("belt_length = 1.2").unwrap()).unwrap();
        assert_eq!((m.tension, m.belt_length), (None, Some(1.2)));
        // both given by the user: both kept (the layout's validation refuses them)
        let m: Mount =
            from_partial(toml::from_str("belt_length = 1.2\ntension = 3.0").unwrap()).unwrap();
        assert_eq!((m.tension, m.belt_length), (Some(3.0), Some(1.2)));
    }

    #[test]
    fn a_given_key_drops_a_nested_default() {
        #[derive(Debug, Serialize, Deserialize, schemars::JsonSchema)]
        #[serde(deny_unknown_fields)]
        struct Drive {
            pulleys: Vec<f64>,
            #[serde(default)]
            contact: Contact,
        }
        #[derive(Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
        #[serde(default, deny_unknown_fields)]
        struct Contact {
            stiffness: f64,
            kappa: f64,
        }
        // the type's own default, which a dropped key falls back to
        impl Default for Contact {
            fn default() -> Self {
                Contact {
                    stiffness: 1.0,
                    kappa: 2.0,
                }
            }
        }
        impl PartialRules for Drive {
            const DROPPED_BY: &'static [(&'static str, &'static str)] =
                &[("pulleys", "contact.kappa")];
        }
        // the configuration's default: another contact than the type's
        impl Default for Drive {
            fn default() -> Self {
                Drive {
                    pulleys: vec![0.1, 0.2, 0.3],
                    contact: Contact {
                        stiffness: 5.0,
                        kappa: 40.0,
                    },
                }
            }
        }
        let read = |s: &str| from_partial::<Drive>(toml::from_str(s).unwrap()).unwrap();
        // new pulleys: the default's kappa goes (the type's default), its stiffness stays
        let d = read("pulleys = [0.1]");
        assert_eq!(
            d.contact,
            Contact {
                stiffness: 5.0,
                kappa: 2.0
            }
        );
        let d = read("pulleys = [0.1]\n[contact]\nstiffness = 7.0\n");
        assert_eq!((d.contact.stiffness, d.contact.kappa), (7.0, 2.0));
        // given by the user: kept
        let d = read("pulleys = [0.1]\n[contact]\nkappa = 9.0\n");
        assert_eq!((d.contact.stiffness, d.contact.kappa), (5.0, 9.0));
        // the pulleys not given: the default's contact whole
        let d = read("[contact]\nstiffness = 7.0\n");
        assert_eq!((d.contact.stiffness, d.contact.kappa), (7.0, 40.0));
    }

    #[test]
    fn errors_name_the_path() {
        let e = read("[drive]\ntension = \"high\"\n").unwrap_err();
        assert_eq!(e.path, "drive.tension");
        let e = read("[[drive.pulleys]]\nradius = 0.1\ntypo = 1\n").unwrap_err();
        assert_eq!(e.path, "drive.pulleys[0].typo");
        assert!(e.message.contains("typo"), "{e}");
        assert_eq!(
            e.steps(),
            vec![
                PathStep::Key("drive".into()),
                PathStep::Key("pulleys".into()),
                PathStep::Index(0),
                PathStep::Key("typo".into())
            ]
        );
        assert_eq!(path_text(&e.steps()), e.path);
        assert_eq!(path_text(&[]), "<root>");
        let e = read("[drive.friction]\nlaw = \"coulomb\"\n").unwrap_err();
        assert!(e.message.contains("missing field `mu`"), "{e}");
        // a variant switch with a typo: the typo is named, not the other variant's keys
        let e = read("[drive.friction]\nlaw = \"coulomb\"\nmu = 0.3\ntypo = 1\n").unwrap_err();
        assert!(e.message.contains("typo"), "{e}");
    }
}
