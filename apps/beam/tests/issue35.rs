//! Issue 35 reproducers for `flowmbd-beam`: silent wrong answers and wrong exit classes are
//! one-line input errors naming the field; `--out` and `--config` paths that cannot be used
//! are refused before the run; a run interrupted by SIGINT or SIGTERM keeps its results so far,
//! marked incomplete, and exits 130 / 143; a new run never leaves an earlier run's files
//! beside its own unmarked.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const EXE: &str = env!("CARGO_BIN_EXE_flowmbd-beam");

fn run(args: &[&str]) -> (i32, String, String) {
    flowmbd_cli::testing::run_binary(EXE, args)
}

fn tmp(name: &str) -> PathBuf {
    flowmbd_cli::testing::fresh_dir("flowmbd-beam-i35", name)
}

/// `study`'s default configuration with `key = value` set, written to `dir/name.toml`.
fn config_with(dir: &Path, study: &str, key: &str, value: &str) -> PathBuf {
    let (code, text, err) = run(&[study, "--print-config"]);
    assert_eq!(code, 0, "{err}");
    let mut found = false;
    let text: Vec<String> = text
        .lines()
        .map(|l| {
            if l.split('=').next().map(str::trim) == Some(key) && !found {
                found = true;
                format!("{key} = {value}")
            } else {
                l.to_string()
            }
        })
        .collect();
    assert!(found, "{study} has no key {key}");
    let f = dir.join(format!("{study}-{key}.toml"));
    std::fs::write(&f, text.join("\n")).unwrap();
    f
}

/// Exit 2 with one line naming `field`, found by validation alone (`--print-config`).
fn refused(study: &str, key: &str, value: &str, field: &str) {
    let dir = tmp(&format!("{study}-{key}"));
    let f = config_with(&dir, study, key, value);
    let (code, _, err) = run(&[study, "--config", f.to_str().unwrap(), "--print-config"]);
    assert_eq!(code, 2, "{study} {key} = {value}: {err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(
        err.contains(&format!("{field}: ")),
        "{study} {key} = {value}: {err}"
    );
    let _ = std::fs::remove_dir_all(dir);
}

// issue 35: width = 1e-300 gave `"midpoint_deflection_mm": null` with exit 0 (the section
// must be between 1e-6 and 1 times the length, flowmbd_cases::ancf_beams::MIN_SECTION_RATIO)
#[test]
fn a_vanishing_section_is_refused() {
    refused("simply-supported", "width", "1e-300", "width");
    refused("simply-supported", "height", "1e-300", "height");
    refused("pendulum", "side", "1e-12", "side");
}

// issue 35: omega = 1e5 rad/s gave an extension of -8 m; the closed form (2.37) diverges at
// the critical speed pi/(2L) sqrt(E/rho) = 980 rad/s of the default beam (Kerkkanen (2.36))
#[test]
fn spinning_above_the_critical_speed_is_refused() {
    refused("spinning", "omega", "100000.0", "omega");
    refused("spinning", "omega", "-1000.0", "omega");
}

// issue 35: `density = 0` was exit 1 "singular system matrix"; h longer than the run accepted
#[test]
fn massless_pendulum_and_steps_longer_than_the_run_are_bad_input() {
    refused("pendulum", "density", "0.0", "density");
    refused("spinning", "h", "30.0", "h");
    refused("pendulum", "h", "3.0", "h");
}

// issue 35: `--speed -inf` was taken as a flag (clap); here `--nu -inf` reaches the check
#[test]
fn negative_infinite_option_values_reach_the_field_check() {
    let (code, _, err) = run(&["cantilever", "--nu", "-inf", "--print-config"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("nu: must be in (-1, 0.5), got -inf"), "{err}");
}

// issue 35: an --out that is a file or /dev/full was exit 1 after the run
#[test]
fn an_unusable_out_is_bad_input_naming_out() {
    let dir = tmp("outfile");
    let file = dir.join("a-file");
    std::fs::write(&file, "x").unwrap();
    for out in [file.to_str().unwrap(), "/dev/full"] {
        let t0 = Instant::now();
        let (code, _, err) = run(&["simply-supported", "--quiet", "--out", out]);
        assert_eq!(code, 2, "{out}: {err}");
        assert!(err.contains(&format!("--out {out}: ")), "{err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(t0.elapsed() < Duration::from_secs(20));
    }
    let _ = std::fs::remove_dir_all(dir);
}

// issue 35: `--config /dev/zero` grew memory without end
#[test]
fn device_configs_are_refused_before_reading() {
    for dev in ["/dev/zero", "/dev/urandom"] {
        let t0 = Instant::now();
        let (code, _, err) = run(&["pendulum", "--config", dev, "--print-config"]);
        assert_eq!(code, 2, "{dev}: {err}");
        assert!(err.contains("not a regular file"), "{err}");
        assert!(t0.elapsed() < Duration::from_secs(10));
    }
}

/// Start `args`, wait until `ready` exists (the run is stepping), send `signal`, and return
/// the exit code and stderr.
fn interrupt(args: &[&str], ready: &Path, signal: &str) -> (i32, String) {
    let child = Command::new(EXE)
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while !ready.exists() && t0.elapsed() < Duration::from_secs(120) {
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(300));
    let status = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

// issue 35 item 3: SIGINT / SIGTERM stop the run at the next step; the samples so far are
// written, summary.json says "complete": false, the exit code is 128 + the signal number
#[test]
fn interrupted_runs_keep_their_results_marked_incomplete() {
    for (signal, code_expected, name) in [("-INT", 130, "SIGINT"), ("-TERM", 143, "SIGTERM")] {
        let dir = tmp(&format!("signal{code_expected}"));
        // a long pendulum: 4 elements, 10^6 steps
        let f = config_with(&dir, "pendulum", "t_end", "50.0");
        let out = dir.join("out");
        // summary.json appears when the run starts ("running")
        let (code, err) = interrupt(
            &[
                "pendulum",
                "--config",
                f.to_str().unwrap(),
                "--quiet",
                "--out",
                out.to_str().unwrap(),
            ],
            &out.join("config.toml"),
            signal,
        );
        assert_eq!(code, code_expected, "{err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains(&format!("interrupted by {name}")), "{err}");
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(summary["complete"], false, "{summary}");
        assert_eq!(summary["status"], "interrupted", "{summary}");
        let tip = summary["partial"]["final_tip"][0].as_f64().unwrap();
        assert!(tip.is_finite(), "{summary}");
        let hist = std::fs::read_to_string(out.join("history.csv")).unwrap();
        assert!(hist.lines().count() >= 2, "{hist}");
        let _ = std::fs::remove_dir_all(dir);
    }
}

// issue 35 item 3: a new run removes the files the previous run listed; summary.json lists
// the files of this run
#[test]
fn a_new_run_clears_the_previous_runs_outputs() {
    let dir = tmp("stale");
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    let (code, _, err) = run(&["cantilever", "--quiet", "--out", o]);
    assert_eq!(code, 0, "{err}");
    assert!(out.join("shape.vtu").exists() && out.join("shape.png").exists());
    std::fs::write(out.join("notes.txt"), "the user's own file").unwrap();
    let (code, _, err) = run(&["simply-supported", "--quiet", "--out", o]);
    assert_eq!(code, 0, "{err}");
    for stale in ["shape.vtu", "shape.png", "shape.svg", "shape.csv"] {
        assert!(
            !out.join(stale).exists(),
            "{stale} left from the earlier run"
        );
    }
    assert!(out.join("notes.txt").exists(), "files of others are kept");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["complete"], true);
    let files: Vec<&str> = summary["outputs"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|v| v.as_str())
        .collect();
    assert_eq!(files, vec!["config.toml", "summary.json"], "{summary}");
    let _ = std::fs::remove_dir_all(dir);
}
