//! TOML configuration with embedded defaults.
//!
//! A study's configuration is a plain `serde` struct whose `Default` reproduces the seed's case.
//! A file given with `--config` is merged over the defaults (missing fields keep their default
//! value when the struct is `#[serde(default)]`); unknown fields are rejected when the struct is
//! `#[serde(deny_unknown_fields)]`. Errors name the file, line, column and field.

use crate::error::CliError;
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::path::Path;

/// Semantic checks of a configuration beyond its types: the workspace's one validation trait,
/// [`mbd_core::Validate`] (returns the first offending field with its path).
pub use mbd_core::Validate;

/// Load the configuration: the embedded defaults, or `path` parsed over them, then validated.
pub fn load_config<C>(path: Option<&Path>) -> Result<C, CliError>
where
    C: DeserializeOwned + Default + Validate,
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
    C: DeserializeOwned + Default,
{
    Ok(match path {
        None => (C::default(), "defaults".to_string()),
        Some(p) => {
            let text = std::fs::read_to_string(p).map_err(|source| CliError::ReadConfig {
                path: p.to_path_buf(),
                source,
            })?;
            (parse_config(&text, p)?, p.display().to_string())
        }
    })
}

/// Parse TOML `text` (from `path`, used in messages) into `C`.
pub fn parse_config<C: DeserializeOwned>(text: &str, path: &Path) -> Result<C, CliError> {
    toml::from_str(text).map_err(|e| {
        let (line, column) = e
            .span()
            .map(|s| line_column(text, s.start))
            .unwrap_or((1, 1));
        CliError::ParseConfig {
            path: path.to_path_buf(),
            line,
            column,
            message: e.message().replace('\n', " ").trim().to_string(),
        }
    })
}

/// The configuration as TOML text (what `--print-config` prints).
pub fn to_toml<C: Serialize>(config: &C) -> String {
    toml::to_string_pretty(config)
        .unwrap_or_else(|e| format!("# cannot serialise configuration: {e}\n"))
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

    #[derive(Debug, Serialize, Deserialize, PartialEq)]
    #[serde(default, deny_unknown_fields)]
    struct Demo {
        radius: f64,
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
    }

    #[test]
    fn line_column_counts_from_one() {
        assert_eq!(line_column("ab\ncd", 4), (2, 2));
        assert_eq!(line_column("ab", 0), (1, 1));
    }
}
