//! TOML configuration with embedded defaults.
//!
//! A study's configuration is a plain `serde` struct whose `Default` reproduces the seed's case.
//! A file given with `--config` is read deeply over the defaults ([`mbd_core::config`]: tables
//! merged key by key at every depth, arrays and scalars replaced, a table switching an enum's
//! variant replaced whole), so one number of the default drive can be changed alone; unknown
//! fields are rejected when the struct is `#[serde(deny_unknown_fields)]`. Errors name the file,
//! line, column and the field's dotted path.

use crate::error::CliError;
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::path::Path;

/// Semantic checks of a configuration beyond its types: the workspace's one validation trait,
/// [`mbd_core::Validate`] (returns the first offending field with its path).
pub use mbd_core::Validate;

/// The merge rules a configuration declares for being read partially over its defaults
/// ([`mbd_core::config::PartialRules`]: none by default; a configuration that holds a belt
/// layout declares `belt::PARTIAL_RULES`).
pub use mbd_core::config::PartialRules;

/// Load the configuration: the embedded defaults, or `path` parsed over them, then validated.
pub fn load_config<C>(path: Option<&Path>) -> Result<C, CliError>
where
    C: DeserializeOwned + Serialize + Default + Validate + PartialRules,
{
    let (config, origin) = read_config::<C>(path)?;
    config
        .validate()
        .map_err(|error| CliError::Invalid { origin, error })?;
    Ok(config)
}

/// The embedded defaults, or `path` parsed over them, not yet validated (so that command-line
/// overrides can be applied first), with the origin used in messages.
pub fn read_config<C>(path: Option<&Path>) -> Result<(C, String), CliError>
where
    C: DeserializeOwned + Serialize + Default + PartialRules,
{
    Ok(match path {
        None => (C::default(), "defaults".to_string()),
        Some(p) => {
            let text = read_config_text(p)?;
            (parse_config(&text, p)?, p.display().to_string())
        }
    })
}

/// Largest configuration file read: 1 MiB (the largest default configuration is a few
/// kilobytes; a larger file is refused before it is read).
pub const MAX_CONFIG_BYTES: u64 = 1 << 20;

/// The text of the configuration file `path`: a regular file (not a folder, FIFO or device
/// such as `/dev/zero`) of at most [`MAX_CONFIG_BYTES`], read through a bounded reader (a
/// file growing while it is read stops at the ceiling too), UTF-8.
pub fn read_config_text(path: &Path) -> Result<String, CliError> {
    use mbd_core::input::InputError as E;
    let bad = |message: String| CliError::ConfigFile {
        path: path.to_path_buf(),
        message,
    };
    mbd_core::input::read_text(path, MAX_CONFIG_BYTES).map_err(|e| match e {
        E::NotFound { source, .. } | E::Io { source, .. } => CliError::ReadConfig {
            path: path.to_path_buf(),
            source,
        },
        E::Directory { .. } => bad("is a directory, expected a TOML file".into()),
        E::NotRegular { .. } => {
            bad("is not a regular file (a device, FIFO or socket); expected a TOML file".into())
        }
        E::TooLarge { size, max, .. } => bad(format!(
            "is larger than {max} bytes ({size} bytes), the most a configuration may have"
        )),
        E::NotUtf8 { offset, .. } => bad(format!(
            "is not UTF-8 text (invalid byte at offset {offset})"
        )),
    })
}

/// Parse TOML `text` (from `path`, used in messages) into `C`, read deeply over `C::default()`
/// ([`mbd_core::config::from_partial`]). A TOML syntax error is located by the parser; an error
/// of a field at the line of the deepest key of its path that the file spells (the line of the
/// table header or key the user wrote), with the field's dotted path in the message.
pub fn parse_config<C>(text: &str, path: &Path) -> Result<C, CliError>
where
    C: DeserializeOwned + Serialize + Default + PartialRules,
{
    let user: toml::Table = toml::from_str(text).map_err(|e| {
        let (line, column) = e
            .span()
            .map(|s| line_column(text, s.start))
            .unwrap_or((1, 1));
        CliError::ParseConfig {
            path: path.to_path_buf(),
            line,
            column,
            message: mbd_core::validate::escape_message(e.message().trim()),
        }
    })?;
    mbd_core::config::from_partial(user).map_err(|e| {
        let (line, column) = locate(text, &e.steps());
        CliError::ParseConfig {
            path: path.to_path_buf(),
            line,
            column,
            message: mbd_core::validate::escape_message(&format!("{}: {}", e.path, e.message)),
        }
    })
}

/// 1-based line and column of the deepest key of `steps` that `text` spells ((1, 1) when it
/// spells none: the error lies in a default the file did not touch).
fn locate(text: &str, steps: &[mbd_core::config::PathStep]) -> (usize, usize) {
    use mbd_core::config::PathStep;
    use toml::de::{DeTable, DeValue};
    let Ok(root) = DeTable::parse(text) else {
        return (1, 1);
    };
    let mut found = None;
    let mut table: Option<&DeTable<'_>> = Some(root.get_ref());
    let mut value: Option<&DeValue<'_>> = None;
    for step in steps {
        match step {
            PathStep::Key(k) => {
                let Some((key, v)) = table.and_then(|t| {
                    t.iter()
                        .find(|(key, _)| key.get_ref().as_ref() == k.as_str())
                }) else {
                    break;
                };
                found = Some(key.span());
                value = Some(v.get_ref());
            }
            PathStep::Index(i) => {
                let Some(item) = value.and_then(|v| match v {
                    DeValue::Array(a) => a.into_iter().nth(*i),
                    _ => None,
                }) else {
                    break;
                };
                found = Some(item.span());
                value = Some(item.get_ref());
            }
        }
        table = match value {
            Some(DeValue::Table(t)) => Some(t),
            _ => None,
        };
    }
    found.map_or((1, 1), |s| line_column(text, s.start))
}

/// The configuration as bare TOML text (`--print-config` prints it with comments:
/// [`crate::commented::to_commented_toml`]).
pub fn to_toml<C: Serialize>(config: &C) -> String {
    toml::to_string(config).unwrap_or_else(|e| format!("# cannot serialise configuration: {e}\n"))
}

/// The key [`unknown_key_variants`] adds to every table.
pub const UNKNOWN_KEY: &str = "zz_unknown_key";

/// One variant of the configuration `text` (TOML, e.g. what `--print-config` prints) per table
/// — the root, every nested table, every table inside an array of tables — with the key
/// [`UNKNOWN_KEY`] added to that table: `(dotted path of the table, the modified text)`.
///
/// Every table of a configuration must reject the key (`#[serde(deny_unknown_fields)]`), but
/// serde's attribute does not reach everywhere: unit variants of internally tagged enums
/// (`{ kind = "none", typo = 1 }`), structs inside newtype variants, `#[serde(flatten)]` and
/// untagged enums ignore unknown keys. Feeding each variant back through the configuration
/// reader finds such holes (issue 20).
pub fn unknown_key_variants(text: &str) -> Result<Vec<(String, String)>, toml::de::Error> {
    let root: toml::Table = toml::from_str(text)?;
    let mut paths = Vec::new();
    collect_tables(&root, &mut Vec::new(), &mut paths);
    Ok(paths
        .into_iter()
        .map(|path| {
            let mut t = root.clone();
            if let Some(table) = table_at(&mut t, &path) {
                table.insert(UNKNOWN_KEY.to_string(), toml::Value::Integer(0));
            }
            (
                mbd_core::config::path_text(&path),
                toml::to_string(&t).unwrap_or_default(),
            )
        })
        .collect())
}

/// The tables of `config` that accept an unknown key: the dotted paths of the variants of
/// [`unknown_key_variants`] (of `config` written as TOML) that still parse as `C`. Empty when
/// every table rejects unknown keys.
pub fn tables_accepting_unknown_keys<C: Serialize + DeserializeOwned>(config: &C) -> Vec<String> {
    tables_accepting_unknown_keys_by(&to_toml(config), |t| toml::from_str::<C>(t).is_ok())
}

/// The tables of the configuration `text` whose [`unknown_key_variants`] `accepts` (e.g. an
/// app run with `--config variant --print-config` that exits 0): their dotted paths.
pub fn tables_accepting_unknown_keys_by(
    text: &str, mut accepts: impl FnMut(&str) -> bool,
) -> Vec<String> {
    match unknown_key_variants(text) {
        Ok(variants) => variants
            .into_iter()
            .filter(|(_, t)| accepts(t))
            .map(|(path, _)| path)
            .collect(),
        Err(e) => vec![format!("<the configuration is not TOML: {e}>")],
    }
}

// a step of a path into a TOML document: a key or an array index
use mbd_core::config::PathStep as Step;

fn collect_tables(t: &toml::Table, here: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
    out.push(here.clone());
    for (k, v) in t {
        here.push(Step::Key(k.clone()));
        match v {
            toml::Value::Table(sub) => collect_tables(sub, here, out),
            toml::Value::Array(items) => {
                for (i, item) in items.iter().enumerate() {
                    if let toml::Value::Table(sub) = item {
                        here.push(Step::Index(i));
                        collect_tables(sub, here, out);
                        here.pop();
                    }
                }
            }
            _ => {}
        }
        here.pop();
    }
}

fn table_at<'a>(t: &'a mut toml::Table, path: &[Step]) -> Option<&'a mut toml::Table> {
    let Some((first, rest)) = path.split_first() else {
        return Some(t);
    };
    let Step::Key(k) = first else { return None };
    let mut v = t.get_mut(k)?;
    let mut rest = rest;
    while let Some(Step::Index(i)) = rest.first() {
        v = v.as_array_mut()?.get_mut(*i)?;
        rest = &rest[1..];
    }
    table_at(v.as_table_mut()?, rest)
}

/// 1-based line and column of byte `offset` in `text`.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::InputError;
    use serde::Deserialize;

    #[derive(Debug, Serialize, Deserialize, schemars::JsonSchema, PartialEq)]
    #[serde(default, deny_unknown_fields)]
    struct Demo {
        /// Radius \[m\].
        radius: f64,
        /// Count.
        count: usize,
    }

    impl Default for Demo {
        fn default() -> Self {
            Self {
                radius: 0.1,
                count: 3,
            }
        }
    }

    impl PartialRules for Demo {}

    impl Validate for Demo {
        fn validate(&self) -> Result<(), InputError> {
            if self.radius > 0.0 {
                Ok(())
            } else {
                Err(InputError::new("radius", "must be positive [m]"))
            }
        }
    }

    fn write(text: &str) -> tempfile_path::TempFile {
        tempfile_path::TempFile::new(text)
    }

    mod tempfile_path {
        use std::path::PathBuf;
        pub struct TempFile(pub PathBuf);
        impl TempFile {
            pub fn new(text: &str) -> Self {
                let n = std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map(|d| d.as_nanos())
                    .unwrap_or(0);
                let p = std::env::temp_dir()
                    .join(format!("flowmbd-cli-{}-{n}.toml", std::process::id()));
                std::fs::write(&p, text).expect("temp file");
                TempFile(p)
            }
        }
        impl Drop for TempFile {
            fn drop(&mut self) {
                let _ = std::fs::remove_file(&self.0);
            }
        }
    }

    #[test]
    fn file_overrides_defaults_field_by_field() {
        let f = write("count = 7\n");
        let c: Demo = load_config(Some(&f.0)).unwrap();
        assert_eq!(
            c,
            Demo {
                radius: 0.1,
                count: 7
            }
        );
    }

    #[test]
    fn unknown_field_names_line_and_field() {
        let f = write("count = 7\nradus = 0.2\n");
        let e = load_config::<Demo>(Some(&f.0)).unwrap_err();
        let msg = e.to_string();
        assert_eq!(e.exit_code(), 2);
        assert!(msg.contains(":2:"), "{msg}");
        assert!(msg.contains("radus"), "{msg}");
        assert!(!msg.contains('\n'), "one line: {msg}");
    }

    #[test]
    fn wrong_type_is_reported_with_line() {
        let f = write("radius = \"big\"\n");
        let msg = load_config::<Demo>(Some(&f.0)).unwrap_err().to_string();
        assert!(msg.contains(":1:"), "{msg}");
    }

    #[test]
    fn semantic_validation_names_field() {
        let f = write("radius = -1.0\n");
        let msg = load_config::<Demo>(Some(&f.0)).unwrap_err().to_string();
        assert!(msg.contains("radius: must be positive"), "{msg}");
    }

    #[test]
    fn print_config_round_trips() {
        let text = to_toml(&Demo::default());
        let back: Demo = parse_config(&text, Path::new("x.toml")).unwrap();
        assert_eq!(back, Demo::default());
        // the commented form (`--print-config`) too
        let text = crate::commented::to_commented_toml(&Demo::default());
        assert!(text.contains("# "), "{text}");
        let back: Demo = parse_config(&text, Path::new("x.toml")).unwrap();
        assert_eq!(back, Demo::default());
    }

    /// A configuration with the holes of issue 20: a unit variant of an internally tagged
    /// enum and a struct without `deny_unknown_fields` inside a newtype variant.
    mod holes {
        use serde::{Deserialize, Serialize};
        #[derive(Debug, Serialize, Deserialize, schemars::JsonSchema)]
        #[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
        pub enum Load {
            None,
            Constant { torque: f64 },
        }
        #[derive(Debug, Serialize, Deserialize, schemars::JsonSchema)]
        pub struct Scheme {
            pub first: String,
        }
        #[derive(Debug, Serialize, Deserialize, schemars::JsonSchema)]
        pub enum Method {
            FiniteDifference(Scheme),
        }
        #[derive(Debug, Serialize, Deserialize, schemars::JsonSchema)]
        #[serde(deny_unknown_fields)]
        pub struct Pulley {
            pub name: String,
            pub load: Load,
        }
        #[derive(Debug, Serialize, Deserialize, schemars::JsonSchema)]
        #[serde(deny_unknown_fields)]
        pub struct Drive {
            pub pulleys: Vec<Pulley>,
            pub derivative: Method,
        }
    }

    // the walker visits the root, nested tables and tables inside arrays, and finds exactly
    // the two holes (definition: serde's documented behaviour for these shapes)
    #[test]
    fn unknown_key_walker_finds_the_holes() {
        use holes::*;
        let d = Drive {
            pulleys: vec![
                Pulley {
                    name: "a".into(),
                    load: Load::Constant { torque: 1.0 },
                },
                Pulley {
                    name: "b".into(),
                    load: Load::None,
                },
            ],
            derivative: Method::FiniteDifference(Scheme { first: "c".into() }),
        };
        let paths: Vec<String> = unknown_key_variants(&to_toml(&d))
            .unwrap()
            .into_iter()
            .map(|(p, _)| p)
            .collect();
        for p in [
            "<root>",
            "pulleys[0]",
            "pulleys[0].load",
            "pulleys[1].load",
            "derivative.FiniteDifference",
        ] {
            assert!(paths.iter().any(|q| q == p), "{p} not visited: {paths:?}");
        }
        assert_eq!(
            tables_accepting_unknown_keys(&d),
            // (tables in key order)
            vec![
                "derivative.FiniteDifference".to_string(),
                "pulleys[1].load".to_string()
            ]
        );
        assert!(tables_accepting_unknown_keys(&Demo::default()).is_empty());
    }

    // issue 35 item 2: devices and oversized files are refused before they are read
    #[test]
    fn non_regular_and_oversized_files_are_refused() {
        #[cfg(unix)]
        for dev in ["/dev/zero", "/dev/urandom"] {
            let e = read_config::<Demo>(Some(Path::new(dev))).unwrap_err();
            assert_eq!(e.exit_code(), 2);
            assert!(e.to_string().contains("not a regular file"), "{e}");
        }
        let f = write(&"# x\n".repeat((MAX_CONFIG_BYTES / 4 + 1) as usize));
        let e = read_config::<Demo>(Some(&f.0)).unwrap_err();
        assert!(e.to_string().contains("larger than"), "{e}");
        let e = read_config::<Demo>(Some(Path::new("/"))).unwrap_err();
        assert!(e.to_string().contains("is a directory"), "{e}");
    }

    #[test]
    fn line_column_counts_from_one() {
        assert_eq!(line_column("ab\ncd", 4), (2, 2));
        assert_eq!(line_column("ab", 0), (1, 1));
    }
}
