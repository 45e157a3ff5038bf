//! Mutated configurations for the apps' fuzz tests (issue 35, item 6).
//!
//! Starting from a study's `--print-config` text, [`mutations`] lists every single change a
//! careless user or a hostile file could make: each number replaced by 0, its negative, NaN,
//! infinities, a huge and a tiny value and integers past `u32`/`i64`; each string emptied,
//! lengthened or given a terminal escape sequence; each array emptied, lengthened or replaced
//! by a scalar; each key dropped; each table replaced by a number. [`run_case`] feeds one
//! variant to the app's binary under a wall-clock limit and an address-space limit, and
//! [`judge`] says whether the outcome keeps the app conventions: exit 0, 2 with one line on
//! stderr (bad input), or 1 with one line (a numerical failure), never a panic, an abort, a
//! signal, a run past the time limit or memory past the limit.
//!
//! The apps' tests drive it through proptest (a few cases per study in every `cargo test`,
//! validating through `--print-config`; the long version, which also runs the studies, is
//! `#[ignore]`d).

use std::io::Read;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// One mutated configuration: what was changed and the TOML text.
#[derive(Debug, Clone)]
pub struct Mutation {
    /// `path: change`, e.g. `drive.belt.elements: 4294967297`.
    pub what: String,
    /// The configuration with the change.
    pub text: String,
}

/// The number replacements (TOML literals).
const NUMBERS: &[&str] = &[
    "0",
    "-1",
    "nan",
    "inf",
    "-inf",
    "1e300",
    "1e-300",
    "-1e-300",
    "4294967297",
    "9223372036854775807",
    "1e9",
    "0.5",
];

/// The string replacements (TOML literals).
const STRINGS: &[&str] = &[
    "\"\"",
    "\"x\"",
    "\"\\u001b[31mred\"",
    "\"../../../../dev/zero\"",
    "1",
];

/// Every single mutation of the TOML `text` (module documentation); an unparsable `text`
/// gives none.
pub fn mutations(text: &str) -> Vec<Mutation> {
    let Ok(root) = toml::from_str::<toml::Table>(text) else {
        return Vec::new();
    };
    let mut leaves = Vec::new();
    collect(
        &toml::Value::Table(root.clone()),
        &mut Vec::new(),
        &mut leaves,
    );
    let mut out = Vec::new();
    for (path, value) in leaves {
        let mut edit = |what: String, new: Option<toml::Value>| {
            let mut t = toml::Value::Table(root.clone());
            if set(&mut t, &path, new)
                && let toml::Value::Table(t) = t
                && let Ok(text) = toml::to_string(&t)
            {
                out.push(Mutation {
                    what: format!("{}: {what}", mbd_core::config::path_text(&path)),
                    text,
                });
            }
        };
        let literal = |s: &str| -> Option<toml::Value> {
            toml::from_str::<toml::Table>(&format!("v = {s}"))
                .ok()
                .and_then(|mut t| t.remove("v"))
        };
        match &value {
            toml::Value::Integer(_) | toml::Value::Float(_) => {
                for n in NUMBERS {
                    edit(n.to_string(), literal(n));
                }
                edit("\"ten\"".into(), literal("\"ten\""));
            }
            toml::Value::String(s) => {
                for v in STRINGS {
                    edit(v.to_string(), literal(v));
                }
                edit(
                    "long string".into(),
                    Some(toml::Value::String(s.repeat(200))),
                );
            }
            toml::Value::Boolean(_) => edit("1".into(), literal("1")),
            toml::Value::Array(a) => {
                edit("[]".into(), Some(toml::Value::Array(Vec::new())));
                if let Some(last) = a.last() {
                    let mut longer = a.clone();
                    longer.extend(std::iter::repeat_n(last.clone(), 20));
                    edit("lengthened".into(), Some(toml::Value::Array(longer)));
                }
                edit("scalar".into(), literal("1"));
            }
            toml::Value::Table(_) => edit("a number".into(), literal("1")),
            toml::Value::Datetime(_) => {}
        }
        if !path.is_empty() {
            edit("dropped".into(), None);
        }
    }
    out
}

// a step into a TOML document: a key or an array index
use mbd_core::config::PathStep as Step;

fn collect(v: &toml::Value, here: &mut Vec<Step>, out: &mut Vec<(Vec<Step>, toml::Value)>) {
    if !here.is_empty() {
        out.push((here.clone(), v.clone()));
    }
    match v {
        toml::Value::Table(t) => {
            for (k, x) in t {
                here.push(Step::Key(k.clone()));
                collect(x, here, out);
                here.pop();
            }
        }
        toml::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                here.push(Step::Index(i));
                collect(x, here, out);
                here.pop();
            }
        }
        _ => {}
    }
}

/// Set (or with `None` remove) the value at `path`; `false` when the path does not lead there.
fn set(root: &mut toml::Value, path: &[Step], new: Option<toml::Value>) -> bool {
    let Some((last, init)) = path.split_last() else {
        return false;
    };
    let mut v = root;
    for s in init {
        v = match (s, v) {
            (Step::Key(k), toml::Value::Table(t)) => match t.get_mut(k) {
                Some(x) => x,
                None => return false,
            },
            (Step::Index(i), toml::Value::Array(a)) => match a.get_mut(*i) {
                Some(x) => x,
                None => return false,
            },
            _ => return false,
        };
    }
    match (last, v, new) {
        (Step::Key(k), toml::Value::Table(t), Some(x)) => {
            t.insert(k.clone(), x);
            true
        }
        (Step::Key(k), toml::Value::Table(t), None) => t.remove(k).is_some(),
        (Step::Index(i), toml::Value::Array(a), Some(x)) if *i < a.len() => {
            a[*i] = x;
            true
        }
        (Step::Index(i), toml::Value::Array(a), None) if *i < a.len() => {
            a.remove(*i);
            true
        }
        _ => false,
    }
}

/// How a case is run.
#[derive(Debug, Clone, Copy)]
pub enum Mode {
    /// `--config FILE --print-config`: read and validate only (fast; what CI runs).
    Validate,
    /// `--config FILE --out DIR --quiet`: the whole study, stopped after `timeout`.
    Run {
        /// Wall-clock limit.
        timeout: Duration,
    },
}

/// What a run of the binary did.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// Exit code, `None` when ended by a signal (or killed at the time limit).
    pub code: Option<i32>,
    /// Standard error.
    pub stderr: String,
    /// Stopped at the time limit.
    pub timed_out: bool,
    /// Wall time.
    pub elapsed: Duration,
}

/// Address-space limit of a fuzzed run \[KiB\] (`ulimit -v`): 6 GiB, so an allocation from an
/// unchecked count fails (an abort, which [`judge`] reports) instead of taking the machine.
pub const MEMORY_LIMIT_KIB: u64 = 6 << 20;

/// Run `exe study` on the configuration `text` (written into `scratch`) in `mode`.
pub fn run_case(exe: &str, study: &str, text: &str, scratch: &Path, mode: Mode) -> Outcome {
    let _ = std::fs::create_dir_all(scratch);
    let cfg = scratch.join("config.toml");
    let _ = std::fs::write(&cfg, text);
    let cfg = cfg.display().to_string();
    let out = scratch.join("out").display().to_string();
    let mut args: Vec<String> = vec![study.into(), "--config".into(), cfg];
    let timeout = match mode {
        Mode::Validate => {
            args.push("--print-config".into());
            Duration::from_secs(60)
        }
        Mode::Run { timeout } => {
            args.extend(["--out".into(), out, "--quiet".into()]);
            timeout
        }
    };
    let start = Instant::now();
    let child = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v {MEMORY_LIMIT_KIB} 2>/dev/null; exec \"$0\" \"$@\""
        ))
        .arg(exe)
        .args(&args)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn();
    let Ok(mut child) = child else {
        return Outcome {
            code: None,
            stderr: format!("cannot start {exe}"),
            timed_out: false,
            elapsed: start.elapsed(),
        };
    };
    // stderr is read on a thread so that a chatty child never blocks on a full pipe
    let mut pipe = child.stderr.take();
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        if let Some(p) = pipe.as_mut() {
            let _ = p.take(1 << 20).read_to_string(&mut s);
        }
        s
    });
    let mut timed_out = false;
    let status = loop {
        match child.try_wait() {
            Ok(Some(s)) => break Some(s),
            Ok(None) if start.elapsed() > timeout => {
                timed_out = true;
                let _ = child.kill();
                break child.wait().ok();
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(5)),
            Err(_) => break None,
        }
    };
    let stderr = reader.join().unwrap_or_default();
    Outcome {
        code: status.and_then(|s| s.code()),
        stderr,
        timed_out,
        elapsed: start.elapsed(),
    }
}

/// `Ok` when `o` keeps the app conventions (module documentation); otherwise what is wrong.
pub fn judge(o: &Outcome) -> Result<(), String> {
    let lines: Vec<&str> = o.stderr.lines().filter(|l| !l.trim().is_empty()).collect();
    if o.timed_out {
        return Err(format!(
            "still running after {:.0} s (unbounded run?)",
            o.elapsed.as_secs_f64()
        ));
    }
    if o.stderr.contains("panicked") {
        return Err(format!("panic: {}", o.stderr.trim()));
    }
    if o.stderr.contains("memory allocation") {
        return Err(format!("allocation failure: {}", o.stderr.trim()));
    }
    match o.code {
        Some(0) => Ok(()),
        Some(1) | Some(2) if lines.len() == 1 => Ok(()),
        Some(c @ (1 | 2)) => Err(format!(
            "exit {c} with {} lines on stderr: {}",
            lines.len(),
            o.stderr.trim()
        )),
        Some(c) => Err(format!("exit {c}: {}", o.stderr.trim())),
        None => Err(format!("ended by a signal: {}", o.stderr.trim())),
    }
}

/// The mutations of `study`'s default configuration (`exe study --print-config`); panics (a
/// test harness) when the study cannot print it.
pub fn study_mutations(exe: &str, study: &str) -> Vec<Mutation> {
    let (code, text, err) = crate::testing::run_binary(exe, &[study, "--print-config"]);
    assert_eq!(code, 0, "{study} --print-config: {err}");
    let m = mutations(&text);
    assert!(!m.is_empty(), "{study}: no mutations of\n{text}");
    m
}

/// What breaks the conventions ([`judge`]) among the mutations `pick` (each taken modulo the
/// study's number of mutations) of every study in `studies` of the binary `exe`, validated
/// through `--print-config` ([`Mode::Validate`]); `tag` names the scratch directories.
pub fn sampled_findings(exe: &str, studies: &[&str], pick: &[usize], tag: &str) -> Vec<String> {
    let mut out = Vec::new();
    for study in studies {
        let all = study_mutations(exe, study);
        for (k, p) in pick.iter().enumerate() {
            let m = &all[p % all.len()];
            let dir = crate::testing::fresh_dir(tag, &format!("{study}-{k}"));
            let o = run_case(exe, study, &m.text, &dir, Mode::Validate);
            if let Err(e) = judge(&o) {
                out.push(format!("{study} [{}]: {e}", m.what));
            }
            let _ = std::fs::remove_dir_all(&dir);
        }
    }
    out
}

/// Every mutation of every study validated, and every `run_every`-th accepted one run under
/// `timeout` ([`Mode::Run`]): what breaks the conventions.
pub fn exhaustive_findings(
    exe: &str, studies: &[&str], tag: &str, run_every: usize, timeout: Duration,
) -> Vec<String> {
    let mut report = Vec::new();
    for study in studies {
        let all = study_mutations(exe, study);
        for (i, m) in all.iter().enumerate() {
            let dir = crate::testing::fresh_dir(tag, &format!("{study}-{i}"));
            let v = run_case(exe, study, &m.text, &dir, Mode::Validate);
            if let Err(e) = judge(&v) {
                report.push(format!("{study} [{}] (validate): {e}", m.what));
            } else if v.code == Some(0) && i % run_every.max(1) == 0 {
                let o = run_case(exe, study, &m.text, &dir, Mode::Run { timeout });
                if let Err(e) = judge(&o) {
                    report.push(format!("{study} [{}] (run): {e}", m.what));
                }
            }
            let _ = std::fs::remove_dir_all(&dir);
        }
    }
    report
}

#[cfg(test)]
mod tests {
    use super::*;

    // definition: one mutation per listed change, each still TOML, the rest unchanged
    #[test]
    fn mutations_change_one_thing_each() {
        let base = "a = 1.5\nname = \"x\"\nlist = [1, 2]\n[t]\nn = 3\n";
        let m = mutations(base);
        assert!(
            m.iter()
                .any(|x| x.what == "a: nan" && x.text.contains("a = nan"))
        );
        assert!(
            m.iter()
                .any(|x| x.what == "t.n: dropped" && !x.text.contains("n = "))
        );
        assert!(
            m.iter()
                .any(|x| x.what == "list: []" && x.text.contains("list = []"))
        );
        assert!(
            m.iter()
                .any(|x| x.what == "t: a number" && x.text.contains("t = 1"))
        );
        for x in &m {
            assert!(toml::from_str::<toml::Table>(&x.text).is_ok(), "{}", x.what);
        }
    }

    // definition of the conventions: 0, or 1/2 with one line; nothing else
    #[test]
    fn judge_follows_the_exit_conventions() {
        let o = |code, stderr: &str| Outcome {
            code,
            stderr: stderr.into(),
            timed_out: false,
            elapsed: Duration::ZERO,
        };
        assert!(judge(&o(Some(0), "")).is_ok());
        assert!(judge(&o(Some(2), "app: error: x: bad\n")).is_ok());
        assert!(judge(&o(Some(2), "a\nb\n")).is_err());
        assert!(judge(&o(Some(101), "thread 'main' panicked at x")).is_err());
        assert!(judge(&o(None, "memory allocation of 8 bytes failed")).is_err());
    }
}
