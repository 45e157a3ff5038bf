//! A study (one subcommand of an app) and the runner that applies the app conventions.

use crate::args::CommonArgs;
use crate::cancel::Cancel;
use crate::commented::to_commented_toml;
use crate::config::{PartialRules, Validate, read_config};
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
    /// A numerical failure `message` whose partial results are `summary` (what the run had when
    /// it failed).
    pub fn failed_with<T: Serialize>(message: impl Into<String>, summary: &T) -> Self {
        StudyError::Numerical {
            message: message.into(),
            partial: serde_json::to_value(summary).ok(),
        }
    }

    /// An implausible result ([`mbd_core::validate::plausible`]): a numerical failure whose
    /// partial results are the summary that failed the check.
    pub fn implausible<T: Serialize>(
        e: mbd_core::validate::plausible::Implausible, summary: &T,
    ) -> Self {
        Self::failed_with(e.to_string(), summary)
    }

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
    /// Set when SIGINT or SIGTERM arrived: pass [`Cancel::check`] back from the progress or
    /// observer callbacks of library loops; they stop at the next step and return what they
    /// have, the study returns its summary so far, and the runner marks it incomplete.
    pub cancel: Cancel,
}

impl StudyContext {
    /// Update `bar` to `done` and answer the library loop whether to go on (the progress
    /// callback of a cancellable loop: `|t| ctx.tick(&bar, t)`).
    pub fn tick(&self, bar: &Progress, done: f64) -> std::ops::ControlFlow<()> {
        bar.set(done);
        self.cancel.check()
    }

    /// A progress bar over `total` units of work (hidden when quiet or not on a terminal).
    pub fn progress(&self, total: f64, message: &str) -> Progress {
        Progress::new(total, message, self.quiet)
    }
}

/// One study of an app: its configuration type, names and computation.
pub trait Study {
    /// The study's configuration; `Default` reproduces the seed's case. Its `JsonSchema` derive
    /// carries the fields' doc comments into the commented `--print-config`
    /// ([`crate::commented`]).
    type Config: Serialize
        + DeserializeOwned
        + Default
        + Validate
        + PartialRules
        + schemars::JsonSchema;
    /// The study's summary (written to `summary.json`, printed by `--json`).
    type Summary: Serialize;
    /// Study name, e.g. `"speed-loss"` (the app's name is given to [`run_study`]; default
    /// output folder `out/<app>/<study>`).
    const NAME: &'static str;

    /// One paragraph on what the summary's numbers mean (what is computed, the reference it
    /// is compared with, how to read the result); written as `"meaning"` into
    /// `summary.json` and `--json`. A summary with a `meaning` of its own keeps it: the
    /// studies whose summary is defined in a library crate (shared with Python) leave this
    /// empty, the summary carries the library's paragraph (every app's tests check that each
    /// example's summary has a meaning).
    const MEANING: &'static str = "";

    /// Apply command-line overrides (such as `--speed`) to the loaded configuration.
    fn apply_overrides(&self, _config: &mut Self::Config) {}

    /// A short plain-text table of the main results, printed on stdout when the study completes
    /// (not with `--json`, which prints the whole summary): what a user reads first, before
    /// opening `summary.json`. `None`: nothing printed.
    fn result_table(&self, _summary: &Self::Summary) -> Option<String> {
        None
    }

    /// Whether every number of the summary must be finite: the runner then turns a NaN or an
    /// infinity anywhere in it ([`non_finite_fields`]) into a numerical failure (exit 1,
    /// `implausible result FIELD`, the summary kept as `"partial"`) instead of writing it as
    /// `null` (issue 35, item 5). On for every study of every app: a quantity that does not
    /// apply is an `Option` (`null`), never a NaN.
    fn results_must_be_finite(&self) -> bool {
        true
    }

    /// Run the study. Write histories into `ctx.out` as they are computed.
    fn run(
        &self, config: &Self::Config, ctx: &mut StudyContext,
    ) -> Result<Self::Summary, StudyError>;
}

/// Run `study` of the app `app` (e.g. `"belt"` for `flowmbd-belt`: the default output folder
/// `out/<app>/<study>` and the prefix of its messages) under the app conventions and return the
/// process exit code: 0 success, 2 bad input (one line naming the field), 1 numerical failure
/// (partial results kept), 130 / 143 interrupted by SIGINT / SIGTERM (results so far kept,
/// marked incomplete).
pub fn run_study<S: Study>(app: &'static str, study: &S, args: &CommonArgs) -> ExitCode {
    let cancel = Cancel::install();
    match try_run(app, study, args, &cancel, true) {
        Ok(Outcome::Done) => ExitCode::SUCCESS,
        Ok(Outcome::Interrupted { out }) => {
            eprintln!(
                "flowmbd-{} {}: interrupted by {}; results so far in {} (marked \"complete\": false)",
                app,
                S::NAME,
                cancel.signal_name(),
                mbd_core::validate::escape_message(&out.display().to_string())
            );
            ExitCode::from(cancel.exit_code())
        }
        Err(e) => {
            eprintln!(
                "flowmbd-{} {}: error: {}",
                app,
                S::NAME,
                mbd_core::validate::escape_message(&e.to_string())
            );
            ExitCode::from(e.exit_code())
        }
    }
}

/// How a run ended without error.
#[derive(Debug)]
enum Outcome {
    Done,
    Interrupted { out: std::path::PathBuf },
}

/// The names of the non-finite numbers in `summary` (dotted paths), found through its TOML
/// form, which keeps NaN and infinities (JSON would write them as `null`). Empty when the
/// summary has none or cannot be written as TOML.
pub fn non_finite_fields<T: Serialize>(summary: &T) -> Vec<String> {
    fn walk(v: &toml::Value, path: String, out: &mut Vec<String>) {
        match v {
            toml::Value::Float(f) if !f.is_finite() => out.push(path),
            toml::Value::Array(a) => {
                for (i, x) in a.iter().enumerate() {
                    walk(x, format!("{path}[{i}]"), out);
                }
            }
            toml::Value::Table(t) => {
                for (k, x) in t {
                    let p = if path.is_empty() {
                        k.clone()
                    } else {
                        format!("{path}.{k}")
                    };
                    walk(x, p, out);
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    if let Ok(v) = toml::Value::try_from(summary) {
        walk(&v, String::new(), &mut out);
    }
    out
}

/// How long a study has after SIGINT / SIGTERM to stop at its next step and return its results
/// so far before the runner ends the process itself.
pub const CANCEL_GRACE: std::time::Duration = std::time::Duration::from_secs(3);

/// The runner's side of a study that does not poll [`StudyContext::cancel`] (or is inside a
/// long step, such as an eigen solution): once a signal has been pending for
/// [`CANCEL_GRACE`] and the study has not returned, mark the output folder interrupted
/// (`summary.json` with `"complete": false`, `"status": "interrupted"`, the files so far),
/// say so in one line and exit with 128 + the signal (issue 35: `belt wave` and the tire
/// studies ran on after SIGTERM until done). `finished` is set by the runner under its lock
/// once the study returned: from then on the runner writes the summary and the watch stands
/// down.
fn watch_cancel(
    app: &'static str, name: &'static str, out: OutputDir, cancel: Cancel,
    finished: std::sync::Arc<std::sync::Mutex<bool>>,
) {
    let lock =
        |m: &std::sync::Mutex<bool>| -> bool { *m.lock().unwrap_or_else(|e| e.into_inner()) };
    let spawned = std::thread::Builder::new()
        .name("flowmbd-cancel".into())
        .spawn(move || {
            let mut since: Option<std::time::Instant> = None;
            loop {
                std::thread::sleep(std::time::Duration::from_millis(50));
                if lock(&finished) {
                    return;
                }
                if !cancel.is_cancelled() {
                    continue;
                }
                if since.get_or_insert_with(std::time::Instant::now).elapsed() < CANCEL_GRACE {
                    continue;
                }
                let done = finished.lock().unwrap_or_else(|e| e.into_inner());
                if *done {
                    return;
                }
                let signal = cancel.signal_name();
                let mut v = serde_json::json!({
                    "complete": false,
                    "status": "interrupted",
                    "partial": null,
                    "error": format!(
                        "interrupted by {signal}: the study did not stop at a step within {} s; \
                         its files so far are kept, its summary was not computed",
                        CANCEL_GRACE.as_secs()
                    ),
                });
                v["outputs"] = out.files().into();
                let _ = out.write_json("summary.json", &v);
                eprintln!(
                    "flowmbd-{app} {name}: interrupted by {signal}; files so far in {} (marked \
                     \"complete\": false, no summary)",
                    mbd_core::validate::escape_message(&out.root().display().to_string())
                );
                std::process::exit(i32::from(cancel.exit_code()));
            }
        });
    // without the thread a signal ends the run when the study next polls or finishes
    drop(spawned);
}

fn try_run<S: Study>(
    app: &'static str, study: &S, args: &CommonArgs, cancel: &Cancel, watch: bool,
) -> Result<Outcome, StudyError> {
    // before any check: the ceilings of sizes and run lengths (`--allow-large`, issue 20)
    mbd_core::validate::limits::set_allow_large(args.allow_large);
    // overrides first, then one validation of the effective configuration
    let (mut config, origin) = read_config::<S::Config>(args.config.as_deref())?;
    study.apply_overrides(&mut config);
    config.validate().map_err(|error| CliError::Invalid {
        origin: format!("{origin} with command-line options"),
        error,
    })?;
    let config_text = to_commented_toml(&config);
    if args.print_config {
        crate::stdout::print_stdout(&config_text).map_err(|e| CliError::write("<stdout>", e))?;
        return Ok(Outcome::Done);
    }
    let out = OutputDir::create(args.out_dir(app, S::NAME))?;
    // the previous run's files go; until the end summary.json says "complete": false
    out.begin_run()?;
    out.write_text("config.toml", &config_text)?;
    let mut ctx = StudyContext {
        out: out.clone(),
        quiet: args.quiet,
        cancel: cancel.clone(),
    };
    let finished = std::sync::Arc::new(std::sync::Mutex::new(false));
    if watch {
        watch_cancel(app, S::NAME, out.clone(), cancel.clone(), finished.clone());
    }
    // what a run that did not finish leaves in summary.json
    let unfinished = |status: &str, error: Option<String>, partial: Option<serde_json::Value>| {
        let mut v = serde_json::json!({
            "complete": false,
            "status": status,
            "partial": partial,
        });
        if let Some(e) = error {
            v["error"] = e.into();
        }
        v["outputs"] = out.files().into();
        out.write_json("summary.json", &v)
    };
    let result = study.run(&config, &mut ctx);
    // the study returned: the runner writes the summary, the cancel watch stands down
    let mut finished_guard = finished.lock().unwrap_or_else(|e| e.into_inner());
    *finished_guard = true;
    let result = result.and_then(|summary| {
        let bad = if study.results_must_be_finite() {
            non_finite_fields(&summary)
        } else {
            Vec::new()
        };
        if !cancel.is_cancelled()
            && let Some(first) = bad.first()
        {
            return Err(StudyError::failed_with(
                format!(
                    "implausible result {first}: not a finite number{}",
                    if bad.len() > 1 {
                        format!(" (and {} more)", bad.len() - 1)
                    } else {
                        String::new()
                    }
                ),
                &summary,
            ));
        }
        Ok(summary)
    });
    match result {
        Ok(summary) => {
            let table = study.result_table(&summary);
            let summary = with_meaning(&summary, S::MEANING)
                .map_err(|e| CliError::write(out.path("summary.json"), e))?;
            if cancel.is_cancelled() {
                unfinished(
                    "interrupted",
                    Some(format!("interrupted by {}", cancel.signal_name())),
                    Some(summary),
                )?;
                return Ok(Outcome::Interrupted {
                    out: out.root().to_path_buf(),
                });
            }
            // summary.json says the run completed and lists its files; `--json` prints the
            // study's summary alone
            let mut file_summary = summary.clone();
            if let serde_json::Value::Object(m) = &mut file_summary {
                m.insert("complete".into(), true.into());
                m.insert("status".into(), "complete".into());
                let mut files = out.files();
                if !files.iter().any(|f| f == "summary.json") {
                    files.push("summary.json".into());
                }
                m.insert("outputs".into(), files.into());
            }
            let path = out.write_json("summary.json", &file_summary)?;
            if args.json {
                let text = serde_json::to_string_pretty(&summary)
                    .map_err(|e| CliError::write(&path, e))?;
                crate::stdout::print_stdout(&(text + "\n"))
                    .map_err(|e| CliError::write("<stdout>", e))?;
            } else {
                if let Some(table) = table {
                    crate::stdout::print_stdout(&table)
                        .map_err(|e| CliError::write("<stdout>", e))?;
                }
                if !args.quiet {
                    eprintln!("results written to {}", out.root().display());
                }
            }
            Ok(Outcome::Done)
        }
        Err(StudyError::Numerical { message, partial }) => {
            if cancel.is_cancelled() {
                unfinished(
                    "interrupted",
                    Some(format!("interrupted by {}", cancel.signal_name())),
                    partial,
                )?;
                return Ok(Outcome::Interrupted {
                    out: out.root().to_path_buf(),
                });
            }
            unfinished("failed", Some(message.clone()), partial.clone())?;
            Err(StudyError::Numerical {
                message: format!("{message} (results so far in {})", out.root().display()),
                partial,
            })
        }
        Err(e) => {
            let _ = unfinished("failed", Some(e.to_string()), None);
            Err(e)
        }
    }
}

/// `summary` as JSON with `"meaning": meaning` added (a summary object without one).
fn with_meaning<T: Serialize>(
    summary: &T, meaning: &str,
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

    #[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
    #[serde(default, deny_unknown_fields)]
    struct Cfg {
        steps: usize,
    }
    impl Default for Cfg {
        fn default() -> Self {
            Self { steps: 4 }
        }
    }
    impl PartialRules for Cfg {}

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
        const NAME: &'static str = "sum";
        const MEANING: &'static str = "total: the sum 0 + 1 + ... + (steps - 1)";
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

    /// [`Sum`] with `steps` and `fail_after`, run into `out` (unwatched).
    fn run_sum(
        steps: Option<usize>, fail_after: Option<usize>, out: &std::path::Path,
    ) -> Result<Outcome, StudyError> {
        let sum = Sum { steps, fail_after };
        try_run("test", &sum, &args(out), &Cancel::new(), false)
    }

    #[test]
    fn exit_codes_follow_the_conventions() {
        let dir = crate::testing::fresh_dir("flowmbd-cli", "study");
        let ok = run_sum(Some(5), None, &dir);
        assert!(ok.is_ok());
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(summary["total"], 10);
        assert_eq!(
            summary["meaning"].as_str(),
            Some("total: the sum 0 + 1 + ... + (steps - 1)")
        );

        let bad = run_sum(Some(0), None, &dir).unwrap_err();
        assert_eq!(bad.exit_code(), 2);
        assert!(bad.to_string().contains("steps"), "{bad}");

        let failed = run_sum(None, Some(2), &dir).unwrap_err();
        assert_eq!(failed.exit_code(), 1);
        let kept = std::fs::read_to_string(dir.join("h.csv")).unwrap();
        assert_eq!(kept.lines().count(), 3, "header + 2 rows kept: {kept}");
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(summary["partial"]["done"], 2);
        assert_eq!(summary["complete"], false);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A study that stops at its loop's next step when cancelled and returns its sum so far.
    struct Interruptible {
        cancel_at: usize,
    }
    impl Study for Interruptible {
        type Config = Cfg;
        type Summary = serde_json::Value;
        const NAME: &'static str = "interruptible";
        const MEANING: &'static str = "done: steps taken";
        fn run(&self, c: &Cfg, ctx: &mut StudyContext) -> Result<serde_json::Value, StudyError> {
            let mut sink = ctx.out.csv("h.csv", &["i"])?;
            let mut done = 0;
            for i in 0..c.steps {
                if i == self.cancel_at {
                    // what the signal handler does
                    ctx.cancel.request(crate::cancel::SIGINT);
                }
                if ctx.cancel.check().is_break() {
                    break;
                }
                sink.row(&[i as f64])?;
                done += 1;
            }
            sink.finish()?;
            Ok(serde_json::json!({ "done": done }))
        }
    }

    // issue 35 item 3: an interrupted run keeps what it had, marked incomplete; a new run
    // removes the files the previous run listed and never leaves them unmarked
    #[test]
    fn interrupted_runs_are_marked_and_stale_outputs_removed() {
        let dir = crate::testing::fresh_dir("flowmbd-cli", "int");
        // a complete earlier run that wrote an extra file
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("old.csv"), "x\n").unwrap();
        std::fs::write(dir.join("mine.txt"), "user's own file\n").unwrap();
        std::fs::write(
            dir.join("summary.json"),
            r#"{"complete": true, "outputs": ["old.csv", "summary.json", "../escape.txt"]}"#,
        )
        .unwrap();
        let cancel = Cancel::new();
        let r = try_run(
            "test",
            &Interruptible { cancel_at: 2 },
            &args(&dir),
            &cancel,
            false,
        )
        .unwrap();
        assert!(matches!(r, Outcome::Interrupted { .. }));
        assert_eq!(cancel.exit_code(), 130);
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(summary["complete"], false);
        assert_eq!(summary["status"], "interrupted");
        assert_eq!(summary["partial"]["done"], 2);
        assert!(!dir.join("old.csv").exists(), "stale output removed");
        assert!(dir.join("mine.txt").exists(), "files not listed are kept");
        let kept = std::fs::read_to_string(dir.join("h.csv")).unwrap();
        assert_eq!(kept.lines().count(), 3, "header + 2 rows: {kept}");
        let files: Vec<&str> = summary["outputs"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(|f| f.as_str())
            .collect();
        assert!(
            files.contains(&"h.csv") && files.contains(&"config.toml"),
            "{files:?}"
        );
        // no temporary file left behind
        let parts: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .flatten()
            .filter(|e| e.file_name().to_string_lossy().ends_with(".part"))
            .collect();
        assert!(parts.is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    // issue 35 item 5: a NaN in a summary is an error, not `null`
    #[test]
    fn non_finite_summary_values_are_found() {
        #[derive(Serialize)]
        struct S {
            a: f64,
            b: Vec<f64>,
            c: Option<f64>,
        }
        let s = S {
            a: 1.0,
            b: vec![0.0, f64::NAN],
            c: None,
        };
        assert_eq!(non_finite_fields(&s), vec!["b[1]".to_string()]);
        let t = S {
            a: f64::INFINITY,
            b: vec![],
            c: Some(2.0),
        };
        assert_eq!(non_finite_fields(&t), vec!["a".to_string()]);
    }

    // issue 35 item 5: an `--out` that is a file is bad input naming --out
    #[test]
    fn out_that_is_a_file_is_bad_input() {
        let f = std::env::temp_dir().join(format!("flowmbd-cli-outfile-{}", std::process::id()));
        std::fs::write(&f, "x").unwrap();
        let e = run_sum(None, None, &f).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().starts_with("--out "), "{e}");
        std::fs::remove_file(&f).unwrap();
    }
}
