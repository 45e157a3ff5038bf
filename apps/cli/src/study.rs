//! A study (one subcommand of an app) and the runner that applies the app conventions.

use crate::args::CommonArgs;
use crate::config::{Validate, read_config, to_toml};
use crate::error::{CliError, InputError};
use crate::output::OutputDir;
use crate::progress::Progress;
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::process::ExitCode;
use thiserror::Error;

/// Why a study stopped.
#[derive(Debug, Error)]
pub enum StudyError {
    /// The input is unusable (exit code 2).
    #[error("{0}")]
    Input(#[from] InputError),
    /// The computation failed (exit code 1); `partial` holds what was computed so far.
    #[error("{message}")]
    Numerical {
        /// What failed, where and when.
        message: String,
        /// Results computed before the failure (written to `summary.json`).
        partial: Option<serde_json::Value>,
    },
    /// Plumbing error (configuration, output files).
    #[error("{0}")]
    Cli(#[from] CliError),
}

impl StudyError {
    /// A numerical failure without partial results.
    pub fn numerical(message: impl std::fmt::Display) -> Self {
        StudyError::Numerical {
            message: message.to_string(),
            partial: None,
        }
    }

    /// The process exit code of this error.
    pub fn exit_code(&self) -> u8 {
        match self {
            StudyError::Input(_) => 2,
            StudyError::Numerical { .. } => 1,
            StudyError::Cli(e) => e.exit_code(),
        }
    }
}

/// What a running study gets from the runner.
pub struct StudyContext {
    /// The output folder.
    pub out: OutputDir,
    /// `--quiet` was given.
    pub quiet: bool,
}

impl StudyContext {
    /// A progress bar over `total` units of work (hidden when quiet or not on a terminal).
    pub fn progress(&self, total: f64, message: &str) -> Progress {
        Progress::new(total, message, self.quiet)
    }
}

/// One study of an app: its configuration type, names and computation.
pub trait Study {
    /// The study's configuration; `Default` reproduces the seed's case.
    type Config: Serialize + DeserializeOwned + Default + Validate;
    /// The study's summary (written to `summary.json`, printed by `--json`).
    type Summary: Serialize;
    /// App name, e.g. `"belt"` (default output folder `out/<app>/<study>`).
    const APP: &'static str;
    /// Study name, e.g. `"speed-loss"`.
    const NAME: &'static str;

    /// One paragraph on what the summary's numbers mean (what is computed, the reference it
    /// is compared with, how to read the result); written as `"meaning"` into
    /// `summary.json` and `--json` unless the summary has a `meaning` of its own (the studies
    /// whose summary is defined in a library crate, shared with Python).
    fn meaning(&self) -> &'static str;

    /// Apply command-line overrides (such as `--speed`) to the loaded configuration.
    fn apply_overrides(&self, _config: &mut Self::Config) {}

    /// TOML comments appended to the printed configuration (`--print-config`, `config.toml`):
    /// e.g. a commented example of an optional table that `config` leaves out (TOML has no
    /// null, so an absent optional table would not show otherwise).
    fn config_notes(&self, _config: &Self::Config) -> String {
        String::new()
    }

    /// Run the study. Write histories into `ctx.out` as they are computed.
    fn run(
        &self,
        config: &Self::Config,
        ctx: &mut StudyContext,
    ) -> Result<Self::Summary, StudyError>;
}

/// Run `study` under the app conventions and return the process exit code:
/// 0 success, 2 bad input (one line naming the field), 1 numerical failure (partial results kept).
pub fn run_study<S: Study>(study: &S, args: &CommonArgs) -> ExitCode {
    match try_run(study, args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!(
                "flowmbd-{} {}: error: {}",
                S::APP,
                S::NAME,
                e.to_string().replace('\n', " ")
            );
            ExitCode::from(e.exit_code())
        }
    }
}

fn try_run<S: Study>(study: &S, args: &CommonArgs) -> Result<(), StudyError> {
    // before any check: the ceilings of sizes and run lengths (`--allow-large`, issue 20)
    mbd_core::validate::limits::set_allow_large(args.allow_large);
    // overrides first, then one validation of the effective configuration
    let (mut config, origin) = read_config::<S::Config>(args.config.as_deref())?;
    study.apply_overrides(&mut config);
    config.validate().map_err(|error| CliError::Invalid {
        origin: format!("{origin} with command-line options"),
        error,
    })?;
    let config_text = to_toml(&config) + &study.config_notes(&config);
    if args.print_config {
        crate::stdout::print_stdout(&config_text).map_err(|e| CliError::Write {
            path: "<stdout>".into(),
            message: e.to_string(),
        })?;
        return Ok(());
    }
    let out = OutputDir::create(args.out_dir(S::APP, S::NAME))?;
    std::fs::write(out.path("config.toml"), &config_text).map_err(|e| CliError::Write {
        path: out.path("config.toml"),
        message: e.to_string(),
    })?;
    let mut ctx = StudyContext {
        out: out.clone(),
        quiet: args.quiet,
    };
    match study.run(&config, &mut ctx) {
        Ok(summary) => {
            let summary = with_meaning(&summary, study.meaning()).map_err(|e| CliError::Write {
                path: out.path("summary.json"),
                message: e.to_string(),
            })?;
            let path = out.write_json("summary.json", &summary)?;
            if args.json {
                let text = serde_json::to_string_pretty(&summary).map_err(|e| CliError::Write {
                    path: path.clone(),
                    message: e.to_string(),
                })?;
                crate::stdout::print_stdout(&(text + "\n")).map_err(|e| CliError::Write {
                    path: "<stdout>".into(),
                    message: e.to_string(),
                })?;
            } else if !args.quiet {
                eprintln!("results written to {}", out.root().display());
            }
            Ok(())
        }
        Err(StudyError::Numerical { message, partial }) => {
            let failed =
                serde_json::json!({ "status": "failed", "error": message, "partial": partial });
            out.write_json("summary.json", &failed)?;
            Err(StudyError::Numerical {
                message: format!("{message} (results so far in {})", out.root().display()),
                partial,
            })
        }
        Err(e) => Err(e),
    }
}

/// `summary` as JSON with `"meaning": meaning` added (a summary object without one).
fn with_meaning<T: Serialize>(
    summary: &T,
    meaning: &str,
) -> Result<serde_json::Value, serde_json::Error> {
    let mut v = serde_json::to_value(summary)?;
    if let serde_json::Value::Object(m) = &mut v
        && !meaning.is_empty()
        && !m.contains_key("meaning")
    {
        m.insert("meaning".into(), meaning.into());
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, Clone, Serialize, Deserialize)]
    #[serde(default, deny_unknown_fields)]
    struct Cfg {
        steps: usize,
    }
    impl Default for Cfg {
        fn default() -> Self {
            Self { steps: 4 }
        }
    }
    impl Validate for Cfg {
        fn validate(&self) -> Result<(), InputError> {
            if self.steps == 0 {
                Err(InputError::new("steps", "must be at least 1"))
            } else {
                Ok(())
            }
        }
    }

    struct Sum {
        steps: Option<usize>,
        fail_after: Option<usize>,
    }
    impl Study for Sum {
        type Config = Cfg;
        type Summary = serde_json::Value;
        const APP: &'static str = "test";
        const NAME: &'static str = "sum";
        fn meaning(&self) -> &'static str {
            "total: the sum 0 + 1 + ... + (steps - 1)"
        }
        fn apply_overrides(&self, c: &mut Cfg) {
            if let Some(s) = self.steps {
                c.steps = s;
            }
        }
        fn run(&self, c: &Cfg, ctx: &mut StudyContext) -> Result<serde_json::Value, StudyError> {
            let mut sink = ctx.out.csv("h.csv", &["i"])?;
            for i in 0..c.steps {
                if Some(i) == self.fail_after {
                    sink.flush()?;
                    return Err(StudyError::Numerical {
                        message: format!("diverged at step {i}"),
                        partial: Some(serde_json::json!({ "done": i })),
                    });
                }
                sink.row(&[i as f64])?;
            }
            sink.finish()?;
            Ok(serde_json::json!({ "total": (0..c.steps).sum::<usize>() }))
        }
    }

    fn args(dir: &std::path::Path) -> CommonArgs {
        CommonArgs {
            out: Some(dir.to_path_buf()),
            quiet: true,
            ..Default::default()
        }
    }

    #[test]
    fn exit_codes_follow_the_conventions() {
        let dir = std::env::temp_dir().join(format!("flowmbd-cli-study-{}", std::process::id()));
        let ok = try_run(
            &Sum {
                steps: Some(5),
                fail_after: None,
            },
            &args(&dir),
        );
        assert!(ok.is_ok());
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(summary["total"], 10);
        assert_eq!(
            summary["meaning"].as_str(),
            Some("total: the sum 0 + 1 + ... + (steps - 1)")
        );

        let bad = try_run(
            &Sum {
                steps: Some(0),
                fail_after: None,
            },
            &args(&dir),
        )
        .unwrap_err();
        assert_eq!(bad.exit_code(), 2);
        assert!(bad.to_string().contains("steps"), "{bad}");

        let failed = try_run(
            &Sum {
                steps: None,
                fail_after: Some(2),
            },
            &args(&dir),
        )
        .unwrap_err();
        assert_eq!(failed.exit_code(), 1);
        let kept = std::fs::read_to_string(dir.join("h.csv")).unwrap();
        assert_eq!(kept.lines().count(), 3, "header + 2 rows kept: {kept}");
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(summary["partial"]["done"], 2);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
