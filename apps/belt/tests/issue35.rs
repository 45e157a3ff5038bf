//! Issue 35 reproducers for `flowmbd-belt` (checked against the release binary 2026-12-02):
//! sizes and run lengths refused before anything is allocated or run, coordinates of the wrong
//! length refused, a driver speed above the belt's critical speed refused, a layout without a
//! tensioner giving a result instead of a NaN arm angle, studies that do not stop at a step
//! ended by the runner on SIGINT / SIGTERM with their folder marked incomplete, and files of
//! an earlier run in a sub-folder removed by the next run.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const EXE: &str = env!("CARGO_BIN_EXE_flowmbd-belt");

fn run(args: &[&str]) -> (i32, String, String) {
    flowmbd_cli::testing::run_binary(EXE, args)
}

fn tmp(name: &str) -> PathBuf {
    flowmbd_cli::testing::fresh_dir("flowmbd-belt-i35", name)
}

/// `study`'s printed configuration with the dotted `key` set to the TOML `value` (the first
/// element of an array of tables for a path through one), written to `dir/<name>.toml`.
fn config_with(dir: &Path, study: &str, edits: &[(&str, &str)]) -> PathBuf {
    let (code, text, err) = run(&[study, "--print-config"]);
    assert_eq!(code, 0, "{err}");
    let mut root: toml::Table = toml::from_str(&text).unwrap();
    for (key, value) in edits {
        let v: toml::Value =
            toml::from_str::<toml::Table>(&format!("x = {value}")).unwrap()["x"].clone();
        let parts: Vec<&str> = key.split('.').collect();
        let mut t = &mut root;
        for p in &parts[..parts.len() - 1] {
            t = match t.get_mut(*p).unwrap_or_else(|| panic!("{study}: no {key}")) {
                toml::Value::Table(t) => t,
                toml::Value::Array(a) => a[0].as_table_mut().unwrap(),
                other => panic!("{key}: {other}"),
            };
        }
        t.insert(parts[parts.len() - 1].to_string(), v);
    }
    let name: String = edits
        .iter()
        .map(|(k, _)| k.replace('.', "_"))
        .collect::<Vec<_>>()
        .join("-");
    let f = dir.join(format!("{study}-{name}.toml"));
    std::fs::write(&f, toml::to_string(&root).unwrap()).unwrap();
    f
}

/// Exit 2 with one line containing every `needle`, found by validation alone
/// (`--print-config`), quickly.
fn refused(study: &str, edits: &[(&str, &str)], needles: &[&str]) {
    let dir = tmp(&format!("{study}-{}", edits[0].0));
    let f = config_with(&dir, study, edits);
    let t0 = Instant::now();
    let (code, _, err) = run(&[study, "--config", f.to_str().unwrap(), "--print-config"]);
    assert_eq!(code, 2, "{study} {edits:?}: {err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    for n in needles {
        assert!(err.contains(n), "{study} {edits:?}: `{n}` not in {err}");
    }
    assert!(t0.elapsed() < Duration::from_secs(20), "{study} {edits:?}");
    let _ = std::fs::remove_dir_all(dir);
}

// issue 35: `drive.belt.elements = 2^63 - 1` panicked (capacity overflow), 2^32 + 1 aborted
// asking for 860 GB, 1e5 was a "singular mass matrix" (exit 1), 1e7 was killed by the OOM
// killer; the ceiling is ancf's MAX_ELEMENTS = 2000 (x1000 with --allow-large). Gauss points
// per element likewise (2^32 + 1 asked for 34 GB; at most 20)
#[test]
fn ancf_belt_sizes_are_bounded_before_allocation() {
    for v in ["9223372036854775807", "4294967297", "100000", "10000000"] {
        refused(
            "ancf",
            &[("drive.belt.elements", v)],
            &["drive: belt.elements", "3 to 2000", v],
        );
    }
    refused(
        "ancf",
        &[("drive.belt.gauss_points", "4294967297")],
        &["drive: belt.gauss_points", "1..=20"],
    );
    // the neighbours inside the ranges are accepted
    let dir = tmp("ancf-ok");
    let f = config_with(
        &dir,
        "ancf",
        &[
            ("drive.belt.elements", "2000"),
            ("drive.belt.gauss_points", "20"),
        ],
    );
    let (code, _, err) = run(&["ancf", "--config", f.to_str().unwrap(), "--print-config"]);
    assert_eq!(code, 0, "{err}");
}

// issue 35: `wave.t_end = 1e9` ran without end (2e13 steps; flowing's MAX_WAVE_STEPS = 1e7),
// `wave.samples` had no ceiling (MAX_WAVE_SAMPLES = 1e5) and `vtk_frames = 1e9` was taken
// silently as one frame per sample
#[test]
fn wave_run_lengths_are_refused_up_front() {
    refused(
        "wave",
        &[("wave.t_end", "1e9")],
        &["wave.t_end", "2.000e13 steps", "--allow-large"],
    );
    refused(
        "wave",
        &[("wave.samples", "4294967297")],
        &["wave.samples", "[2, 100000]"],
    );
    refused(
        "wave",
        &[("vtk_frames", "1000000000")],
        &["vtk_frames", "wave.samples = 1000"],
    );
}

// issue 35: `--omega 1e300` ran and failed writing `history_omega_1000…0.0.csv` (exit 1,
// "File name too long"); a driver speed whose belt speed reaches the critical speed
// c = sqrt(T0/(rho A)) of the mounted belt (Wickert and Mote: the span's transverse
// stiffness T0 - rho A v^2 vanishes) is bad input naming the speed
#[test]
fn speed_loss_refuses_a_driver_speed_above_the_critical_speed() {
    let t0 = Instant::now();
    let (code, _, err) = run(&["speed-loss", "--omega", "1e300", "--print-config"]);
    assert_eq!(code, 2, "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(
        err.contains("omegas[0]: 1e300 rad/s") && err.contains("critical speed"),
        "{err}"
    );
    assert!(t0.elapsed() < Duration::from_secs(20));
    let (code, _, err) = run(&["speed-loss", "--omega", "-inf", "--print-config"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("omegas[0]"), "{err}");
    // max_hold shorter than two averaging windows (issue 35 reproducer, fixed before)
    refused(
        "speed-loss",
        &[("procedure.max_hold", "0.04")],
        &["procedure.max_hold", "two averaging windows"],
    );
    // a step of 1e-15 s: 1.3e16 steps (drives::speed_loss MAX_STEPS = 2e7; fixed before)
    refused(
        "speed-loss",
        &[("procedure.step", "1e-15")],
        &["procedure.step", "steps (max 20000000)"],
    );
}

// issue 35: a pulley centre `[0.0, 0.0, 0.5]` was read as `[0.0, 0.0]` (the TOML reader drops
// the rest of a fixed-size array); mbd_core::validate::exact_array refuses it with file and
// line, likewise a tensioner pivot and a schedule knot of three numbers
#[test]
fn coordinates_of_the_wrong_length_are_refused() {
    for (key, value) in [
        ("drive.pulleys.center", "[0.0, 0.0, 0.5]"),
        ("drive.pulleys.center", "[0.0]"),
        ("drive.tensioner.pivot", "[0.05, 0.29, 1.0]"),
        ("drive.tensioner.travel", "[-0.6, 0.0, 0.6]"),
        (
            "drive.pulleys.motion.speed.knots",
            "[[0.0, 0.0, 1.0], [0.1, 2.0]]",
        ),
    ] {
        let edits = [(key, value)];
        let study = "fead";
        if key.ends_with("knots") {
            // the crank runs at a constant speed in fead; the speed-loss driver ramps
            let dir = tmp("knots");
            let f = config_with(
                &dir,
                study,
                &[
                    ("drive.pulleys.motion.speed.kind", "\"schedule\""),
                    ("drive.pulleys.motion.speed.value", "0.0"),
                    (key, value),
                ],
            );
            let (code, _, err) = run(&[study, "--config", f.to_str().unwrap(), "--print-config"]);
            assert_eq!(code, 2, "{key}: {err}");
            assert!(err.contains("exactly two numbers"), "{key}: {err}");
            continue;
        }
        refused(
            study,
            &edits,
            &["invalid length", "exactly 2 numbers", ".toml:"],
        );
    }
}

/// Start `args`, wait until `ready` exists, wait `delay` more, send `signal`; the exit code,
/// stderr and how long the process took to end after the signal.
fn interrupt(
    args: &[&str], ready: &Path, delay: Duration, signal: &str,
) -> (i32, String, Duration) {
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
    std::thread::sleep(delay);
    let status = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let sent = Instant::now();
    let out = child.wait_with_output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        sent.elapsed(),
    )
}

// issue 35 item 3: `belt wave` (and every study whose loops do not poll the cancel token, such
// as `fead --model ancf`) ran on after SIGTERM until done; the runner now ends it after
// flowmbd_cli::study::CANCEL_GRACE (3 s) with summary.json "complete": false,
// "status": "interrupted", its files so far listed, one line, exit 128 + signal
#[test]
fn studies_that_do_not_poll_are_ended_marked_incomplete() {
    for (study, edits, signal, code_expected, name) in [
        (
            "wave",
            vec![("wave.t_end", "10.0"), ("wave.samples", "20000")],
            "-TERM",
            143,
            "SIGTERM",
        ),
        ("fead", vec![("model", "\"ancf\"")], "-INT", 130, "SIGINT"),
    ] {
        let dir = tmp(&format!("signal-{study}"));
        let f = config_with(&dir, study, &edits);
        let out = dir.join("out");
        let (code, err, took) = interrupt(
            &[
                study,
                "--config",
                f.to_str().unwrap(),
                "--quiet",
                "--out",
                out.to_str().unwrap(),
            ],
            &out.join("config.toml"),
            Duration::from_millis(500),
            signal,
        );
        assert_eq!(code, code_expected, "{study}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains(&format!("interrupted by {name}")), "{err}");
        assert!(took < Duration::from_secs(20), "{study}: {took:?}");
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(summary["complete"], false, "{summary}");
        assert_eq!(summary["status"], "interrupted", "{summary}");
        let outputs: Vec<&str> = summary["outputs"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(|v| v.as_str())
            .collect();
        assert!(outputs.contains(&"config.toml"), "{summary}");
        for o in &outputs {
            assert!(out.join(o).exists(), "{o} listed but absent");
        }
        let _ = std::fs::remove_dir_all(dir);
    }
}

// issue 35 item 3: VTK frames of an earlier, longer run stayed in `vtk/` beside the new run's
// (the manifest listed the folder, not its files); the next run removes them
#[test]
fn frames_of_an_earlier_run_in_a_sub_folder_are_removed() {
    let dir = tmp("stale-vtk");
    let out = dir.join("out");
    let count = |out: &Path| std::fs::read_dir(out.join("vtk")).unwrap().count();
    let mut frames = Vec::new();
    for n in ["100", "10"] {
        let f = config_with(
            &dir,
            "wave",
            &[
                ("wave.t_end", "0.02"),
                ("wave.samples", "200"),
                ("vtk_frames", n),
            ],
        );
        let (code, _, err) = run(&[
            "wave",
            "--config",
            f.to_str().unwrap(),
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(code, 0, "{err}");
        frames.push(count(&out));
    }
    // 201 samples: every 3rd (67 frames) per run at 100 frames, every 21st (10) at 10
    assert_eq!(frames, vec![134, 20]);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let listed = summary["outputs"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|v| v.as_str().is_some_and(|s| s.starts_with("vtk/")))
        .count();
    assert_eq!(listed, 20, "{summary}");
    let _ = std::fs::remove_dir_all(dir);
}

// issue 35: a layout without a tensioner (here with the crank on the belt's back side, pushing
// the upper span in) failed as "implausible result points[0].arm_angle.max: not a finite
// number" (exit 1); the arm angle is `null` without a tensioner and the run completes
#[test]
fn a_layout_without_a_tensioner_runs_with_a_back_side_driver() {
    let dir = tmp("no-tensioner");
    let (code, text, err) = run(&["fead", "--print-config"]);
    assert_eq!(code, 0, "{err}");
    let mut root: toml::Table = toml::from_str(&text).unwrap();
    let pulleys: toml::Value = toml::from_str::<toml::Table>(
        r#"
[[p]]
name = "crank"
center = [0.25, 0.07]
radius = 0.04
side = "outside"
motion = { kind = "speed", speed = { kind = "constant", value = 0.0 } }
[[p]]
name = "a"
center = [0.0, 0.0]
radius = 0.1
motion = { kind = "load", inertia = 0.001, damping = 0.0, torque = { kind = "constant", value = 0.5 } }
[[p]]
name = "b"
center = [0.5, 0.0]
radius = 0.1
motion = { kind = "load", inertia = 0.001, damping = 0.0, torque = { kind = "constant", value = 0.5 } }
"#,
    )
    .unwrap()["p"]
        .clone();
    let drive = root["drive"].as_table_mut().unwrap();
    drive.remove("tensioner");
    drive.insert("pulleys".into(), pulleys);
    root["engine"]["speeds_rpm"] = toml::Value::Array(vec![800.0.into()]);
    root["run"]["ramp"] = 0.05.into();
    root["run"]["settle"] = 0.05.into();
    let f = dir.join("fead.toml");
    std::fs::write(&f, toml::to_string(&root).unwrap()).unwrap();
    let out = dir.join("out");
    let (code, stdout, err) = run(&[
        "fead",
        "--config",
        f.to_str().unwrap(),
        "--quiet",
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let s: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let p = &s["points"][0];
    assert!(p["arm_angle"].is_null(), "{p}");
    assert!(p["belt_speed"].as_f64().unwrap() > 0.0, "{p}");
    let csv = std::fs::read_to_string(out.join("fead_sweep.csv")).unwrap();
    assert!(!csv.lines().next().unwrap().contains("arm_angle"), "{csv}");
    assert!(!out.join("arm_angle.png").exists());
    let _ = std::fs::remove_dir_all(dir);
}
