//! Helpers shared by the end-to-end tests of `flowmbd-reduce`.

use std::path::PathBuf;
use std::process::{Command, Output};

/// The binary under test.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_flowmbd-reduce"))
}

/// A fresh scratch folder `flowmbd-reduce-<test>-<pid>-<name>` in the system temp dir.
pub fn tmp(test: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "flowmbd-reduce-{test}-{}-{name}",
        std::process::id()
    ));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The JSON summary printed by a successful run (panics with the run's stderr otherwise).
#[allow(dead_code)]
pub fn json_of(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}
