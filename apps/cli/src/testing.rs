//! Helpers for the apps' integration tests: run a study binary and read its exit code and
//! output, and a fresh scratch folder per test.

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
