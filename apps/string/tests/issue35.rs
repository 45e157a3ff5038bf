//! Issue 35 reproducers for `flowmbd-string`: `--speed -inf` was taken as an unknown flag (a
//! clap error) instead of reaching the check that names the field; an interrupted simulation
//! keeps its samples so far, marked incomplete.

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const EXE: &str = env!("CARGO_BIN_EXE_flowmbd-string");

fn run(args: &[&str]) -> (i32, String, String) {
    flowmbd_cli::testing::run_binary(EXE, args)
}

#[test]
fn negative_infinite_speeds_reach_the_field_check() {
    for study in ["modes", "simulate", "wrap"] {
        for v in ["-inf", "-nan", "-1e400"] {
            let (code, _, err) = run(&[study, "--speed", v, "--print-config"]);
            assert_eq!(code, 2, "{study} --speed {v}: {err}");
            assert_eq!(err.trim().lines().count(), 1, "{err}");
            assert!(err.contains("speed"), "{study} --speed {v}: {err}");
            assert!(!err.contains("unexpected argument"), "{err}");
        }
    }
}

// issue 35 item 3: SIGTERM during `simulate` (RK4 through flowing::travelling::simulate_rk4)
#[test]
fn an_interrupted_simulation_is_marked_incomplete() {
    let dir = flowmbd_cli::testing::fresh_dir("flowmbd-string-i35", "sigterm");
    let (code, text, err) = run(&["simulate", "--print-config"]);
    assert_eq!(code, 0, "{err}");
    let text: String = text
        .lines()
        .map(|l| {
            if l.starts_with("duration") {
                "duration = 500.0".to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    let cfg = dir.join("long.toml");
    std::fs::write(&cfg, text).unwrap();
    let out = dir.join("out");
    let child = Command::new(EXE)
        .args(["simulate", "--quiet", "--config", cfg.to_str().unwrap()])
        .arg("--out")
        .arg(&out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while !out.join("config.toml").exists() && t0.elapsed() < Duration::from_secs(120) {
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(500));
    assert!(
        Command::new("kill")
            .args(["-TERM", &child.id().to_string()])
            .status()
            .unwrap()
            .success()
    );
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(143), "{err}");
    assert!(err.contains("interrupted by SIGTERM"), "{err}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["complete"], false, "{summary}");
    assert!(out.join("modal_history.csv").exists());
    let _ = std::fs::remove_dir_all(dir);
}

// issue 35 (fuzzing): a pulley top 1e300 m off the string's line ran into a step size
// underflow (exit 1); the small-deflection model takes |top| <= the string's length
#[test]
fn a_pulley_far_off_the_line_is_bad_input() {
    let dir = flowmbd_cli::testing::fresh_dir("flowmbd-string-i35", "top");
    let (code, text, err) = run(&["wrap", "--print-config"]);
    assert_eq!(code, 0, "{err}");
    let text = text.replacen("top = 0.015", "top = 1e300", 1);
    let cfg = dir.join("far.toml");
    std::fs::write(&cfg, text).unwrap();
    let (code, _, err) = run(&["wrap", "--config", cfg.to_str().unwrap(), "--print-config"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("pulleys[0].top: must be in ["), "{err}");
    let _ = std::fs::remove_dir_all(dir);
}

// issue 35 (previous hardening pass): `simulate` with `string.area = 1e300` m² was refused as a
// speed above the critical one (the wave speed √(T/ρA) ≈ 1e-151 m/s); it is refused naming the
// area (definition: a string's cross-section side √area is below its length)
#[test]
fn an_absurd_string_area_is_refused_by_name() {
    let dir = flowmbd_cli::testing::fresh_dir("flowmbd-string-i35", "area");
    let (code, text, err) = run(&["simulate", "--print-config"]);
    assert_eq!(code, 0, "{err}");
    let area_line = text.lines().find(|l| l.starts_with("area")).unwrap();
    for v in ["1e300", "1e10"] {
        let file = dir.join(format!("area-{v}.toml"));
        std::fs::write(&file, text.replacen(area_line, &format!("area = {v}"), 1)).unwrap();
        let (code, _, err) = run(&[
            "simulate",
            "--config",
            file.to_str().unwrap(),
            "--print-config",
        ]);
        assert_eq!(code, 2, "area {v}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains("string.area"), "area {v}: {err}");
    }
    let _ = std::fs::remove_dir_all(dir);
}
