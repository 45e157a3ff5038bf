//! Helpers for the apps' integration tests: run a study binary and read its exit code and
//! output, a fresh scratch folder per test, the studies of a binary, the comment check of
//! their printed configurations, and the shipped examples with the study each is for.

use std::path::PathBuf;
use std::process::Command;

/// Run the binary `exe` with `args`: (exit code, or −1 when killed by a signal; stdout;
/// stderr).
pub fn run_binary(exe: &str, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(exe).args(args).output().expect("binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// An empty folder `<temp>/<tag>-<pid>-<name>` (removed first if it exists).
pub fn fresh_dir(tag: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("{tag}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp folder");
    d
}

/// The studies (subcommands) of the app binary `exe`, read from its `--help` (the
/// `Commands:` section, without `help`).
pub fn subcommands(exe: &str) -> Vec<String> {
    let (_, help, _) = run_binary(exe, &["--help"]);
    help.lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|name| *name != "help")
        .map(str::to_string)
        .collect()
}

/// Where `study --print-config` of the app binary `exe` breaks the comment rule of
/// [`crate::commented`] (keys without a comment, floats without a unit), each prefixed with
/// the study; also when the study fails to print or prints a text that is not TOML.
pub fn print_config_violations(exe: &str, study: &str) -> Vec<String> {
    let (code, text, stderr) = run_binary(exe, &[study, "--print-config"]);
    if code != 0 {
        return vec![format!("{study}: --print-config exits {code}: {stderr}")];
    }
    match crate::commented::comment_violations(&text) {
        Ok(v) => v.into_iter().map(|x| format!("{study}: {x}")).collect(),
        Err(e) => vec![format!("{study}: not TOML: {e}")],
    }
}

/// The shipped example configurations under `dir` (and its sub-folders), sorted, each with the
/// studies it is for: an example's first line names them, `# flowmbd-<app> <study>: <the
/// case>` or `# flowmbd-<app> <study>, <study>: <the case>`. Examples whose first line does
/// not are returned with no study.
pub fn examples(dir: &std::path::Path) -> Vec<(Vec<String>, PathBuf)> {
    fn walk(dir: &std::path::Path, out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().and_then(|e| e.to_str()) == Some("toml")
                && !p
                    .file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| n.starts_with('.'))
            {
                out.push(p);
            }
        }
    }
    let mut paths = Vec::new();
    walk(dir, &mut paths);
    paths.sort();
    paths
        .into_iter()
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap_or_default();
            let first = text.lines().next().unwrap_or("");
            let studies = first
                .strip_prefix("# flowmbd-")
                .and_then(|rest| rest.split_once(':'))
                .and_then(|(app_studies, _)| app_studies.split_once(' '))
                .map(|(_, studies)| {
                    studies
                        .split(',')
                        .map(|s| s.trim().to_string())
                        .filter(|s| !s.is_empty())
                        .collect()
                })
                .unwrap_or_default();
            (studies, p)
        })
        .collect()
}

/// `text` (a TOML configuration) with the tables and keys of `overrides` (TOML) merged into
/// it, table by table (e.g. the run-length keys of a short test run of a shipped example).
pub fn with_overrides(text: &str, overrides: &str) -> String {
    fn merge(base: &mut toml::Table, over: toml::Table) {
        for (k, v) in over {
            match (base.get_mut(&k), v) {
                (Some(toml::Value::Table(b)), toml::Value::Table(o)) => merge(b, o),
                (_, v) => {
                    base.insert(k, v);
                }
            }
        }
    }
    let mut base: toml::Table = toml::from_str(text).expect("example is TOML");
    let over: toml::Table = toml::from_str(overrides).expect("overrides are TOML");
    merge(&mut base, over);
    toml::to_string(&base).expect("TOML")
}

/// Run the shipped example `path` for `study` with the app binary `exe` from the repository
/// root (`--json --quiet`, output into a scratch folder, removed after), with `overrides` (TOML; e.g. the run-length
/// keys of a short run; empty: the example as it is) merged in and `args` appended: (exit
/// code, stdout, stderr). The merged copy is written next to the example, so that the files
/// it names relative to itself are found, and removed after the run.
pub fn run_example(
    exe: &str, study: &str, path: &std::path::Path, overrides: &str, args: &[&str],
) -> (i32, String, String) {
    /// A file removed when dropped (also when the test panics).
    struct Scratch(PathBuf);
    impl Drop for Scratch {
        fn drop(&mut self) {
            let _ = std::fs::remove_file(&self.0);
        }
    }
    let name = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("example")
        .to_string();
    let out = fresh_dir("flowmbd-example", &format!("{study}-{name}"));
    let mut _scratch = None;
    let config = if overrides.trim().is_empty() {
        path.to_path_buf()
    } else {
        let text = std::fs::read_to_string(path).expect("example readable");
        // in the run's own scratch folder, not beside the example: a copy in the examples'
        // folder is listed by any test walking it meanwhile ([`examples`]); the paths inside
        // an example are written from the repository root (below), not from its folder
        let copy = out.join(format!("{name}.test.toml"));
        std::fs::write(&copy, with_overrides(&text, overrides)).expect("scratch copy");
        _scratch = Some(Scratch(copy.clone()));
        copy
    };
    let config = config.to_string_lossy().into_owned();
    let out_s = out.to_string_lossy().into_owned();
    let mut all = vec![
        study, "--config", &config, "--json", "--quiet", "--out", &out_s,
    ];
    all.extend_from_slice(args);
    // from the repository root (the folder holding Cargo.lock above the example), as the guide
    // runs the examples: paths in them are written from there
    let root = path
        .ancestors()
        .find(|d| d.join("Cargo.lock").is_file())
        .unwrap_or(std::path::Path::new("."));
    let output = Command::new(exe)
        .args(&all)
        .current_dir(root)
        .output()
        .expect("binary runs");
    let result = (
        output.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    );
    let _ = std::fs::remove_dir_all(&out);
    result
}

/// The studies of the app binary `exe` ([`subcommands`]) that no example under `dir`
/// ([`examples`]) is for.
pub fn studies_without_example(exe: &str, dir: &std::path::Path) -> Vec<String> {
    let shipped = examples(dir);
    subcommands(exe)
        .into_iter()
        .filter(|s| !shipped.iter().any(|(studies, _)| studies.contains(s)))
        .collect()
}

/// Asserts that every study of the app binary `exe` ([`subcommands`]) prints a configuration
/// that keeps the comment rule ([`print_config_violations`]); the panic lists every violation.
pub fn assert_printed_configs_commented(exe: &str) {
    let studies = subcommands(exe);
    assert!(!studies.is_empty(), "{exe}: no studies in --help");
    let bad: Vec<String> = studies
        .iter()
        .flat_map(|s| print_config_violations(exe, s))
        .collect();
    assert!(
        bad.is_empty(),
        "{} violations:\n{}",
        bad.len(),
        bad.join("\n")
    );
}

/// How a test runs one shipped example: skipped (another test runs it), or with overrides
/// merged into it and command-line options ([`run_example`]) that keep the run short.
pub enum ExampleRun {
    /// Not run here.
    Skip,
    /// Run with these overrides (TOML merged into the example) and options.
    Short {
        /// TOML merged into the example (its run-length keys).
        overrides: &'static str,
        /// Options added to the command line.
        args: &'static [&'static str],
    },
}

/// Asserts that every study of the app binary `exe` has a shipped example under `dir`
/// ([`studies_without_example`]), that every example names its studies, and that each
/// (study, example) pair run as `how(study, example)` says exits 0 with a summary holding its
/// `meaning`.
pub fn assert_examples_run(
    exe: &str, dir: &std::path::Path, how: impl Fn(&str, &std::path::Path) -> ExampleRun,
) {
    let missing = studies_without_example(exe, dir);
    assert!(
        missing.is_empty(),
        "studies without an example: {missing:?}"
    );
    for (studies, path) in examples(dir) {
        assert!(!studies.is_empty(), "{}: names no study", path.display());
        for study in studies {
            let ExampleRun::Short { overrides, args } = how(&study, &path) else {
                continue;
            };
            let (code, stdout, stderr) = run_example(exe, &study, &path, overrides, args);
            assert_eq!(code, 0, "{study} {}: {stderr}", path.display());
            let v: serde_json::Value = serde_json::from_str(&stdout)
                .unwrap_or_else(|e| panic!("{study} {}: summary not JSON: {e}", path.display()));
            assert!(v["meaning"].is_string(), "{study} {}: {v}", path.display());
        }
    }
}
