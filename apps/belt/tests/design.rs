//! End-to-end checks of `flowmbd-belt design` (issue 36): the JSON summary names the layout it
//! ran, the outputs follow the app conventions (units in every CSV column, the configuration
//! round trip), bad input exits 2 naming the field, and the findings are reported, not
//! panicked.

use std::path::PathBuf;

fn run(args: &[&str]) -> (i32, String, String) {
    flowmbd_cli::testing::run_binary(env!("CARGO_BIN_EXE_flowmbd-belt"), args)
}

fn tmp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("flowmbd-belt-design-{}-{name}", std::process::id()))
}

// The default drive (the `fead` study's): every engine speed solved, the summary describes the
// six pulleys and the tensioner it ran, each span's tension differs from the previous by the
// pulley's torque over its radius (the traverse, T_k = T_(k−1) + Q_k/r_k: an invariant read
// back from the JSON), the files are written with units.
#[test]
fn design_json_names_the_layout_and_writes_the_files() {
    let out = tmp("default");
    let (code, stdout, stderr) = run(&[
        "design",
        "--rpm",
        "900,2000",
        "--json",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let layout = v["layout"].as_str().unwrap();
    for name in [
        "crankshaft",
        "alternator",
        "tensioner arm on 'tensioner'",
        "6 pulleys",
    ] {
        assert!(layout.contains(name), "{layout}");
    }
    assert!(v["meaning"].as_str().unwrap().contains(layout));
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.len(), 2);
    for p in points {
        let spans = p["spans"].as_array().unwrap();
        let pulleys = p["pulleys"].as_array().unwrap();
        let n = spans.len();
        for k in 0..n {
            let t_in = spans[(k + n - 1) % n]["tension_n"].as_f64().unwrap();
            let t_out = spans[k]["tension_n"].as_f64().unwrap();
            let q = pulleys[k]["torque_n_m"].as_f64().unwrap();
            let r = q / (t_out - t_in);
            if q.abs() > 1e-9 {
                assert!(r > 0.0 && r < 0.1, "pulley {k}: radius {r}");
            }
        }
        assert!(!p["rotational_modes"].as_array().unwrap().is_empty());
    }
    for f in [
        "summary.json",
        "config.toml",
        "design_points.csv",
        "design_spans.csv",
        "design_pulleys.csv",
        "rotational_modes.csv",
        "coupled_modes.csv",
        "campbell.csv",
        "crossings.csv",
        "campbell.png",
        "hub_loads.svg",
        "slip_margins.png",
    ] {
        assert!(out.join(f).exists(), "{f} missing");
    }
    let missing = flowmbd_cli::output::csv_violations(&out);
    assert!(missing.is_empty(), "{missing:?}");
    let _ = std::fs::remove_dir_all(out);
}

// `--print-config` reads back to itself; a bad value exits 2 naming the field.
#[test]
fn design_config_round_trips_and_bad_input_names_the_field() {
    let (code, printed, stderr) = run(&["design", "--print-config"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(printed.contains("[design]") && printed.contains("[engine]"));
    let file = tmp("cfg.toml");
    std::fs::write(&file, &printed).unwrap();
    let (code, again, stderr) = run(&[
        "design",
        "--config",
        file.to_str().unwrap(),
        "--print-config",
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(printed, again);
    let bad = printed.replace("campbell_points = 61", "campbell_points = 1");
    assert_ne!(bad, printed);
    std::fs::write(&file, bad).unwrap();
    let (code, _, stderr) = run(&["design", "--config", file.to_str().unwrap(), "--quiet"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("design.campbell_points"), "{stderr}");
    let _ = std::fs::remove_file(file);
}

// A weak installation (60 N instead of 400 N, the spring's preload scaled with it) is a
// finding, not a failure: the study exits 0 and reports the gross slip or the slack span.
#[test]
fn low_installation_tension_is_reported_as_an_error_finding() {
    let (code, printed, stderr) = run(&["design", "--print-config"]);
    assert_eq!(code, 0, "{stderr}");
    let weak = printed
        .replace("tension = 400.0", "tension = 60.0")
        .replace("preload = -25.0", "preload = -3.75");
    assert_ne!(weak, printed);
    let file = tmp("weak.toml");
    std::fs::write(&file, weak).unwrap();
    let out = tmp("weak");
    let (code, stdout, stderr) = run(&[
        "design",
        "--config",
        file.to_str().unwrap(),
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert!(v["errors"].as_u64().unwrap() > 0, "{}", v["findings"]);
    assert!(stderr.contains("design: error:"), "{stderr}");
    let kinds: Vec<&str> = v["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|f| f["issue"]["kind"].as_str())
        .collect();
    assert!(
        kinds
            .iter()
            .any(|k| *k == "gross_slip" || *k == "slack_span"),
        "{kinds:?}"
    );
    let _ = std::fs::remove_file(file);
    let _ = std::fs::remove_dir_all(out);
}

// Issue 35's mutated configurations (flowmbd_cli::mutation) on the design study alone: it
// runs in milliseconds, so every mutation is validated and every other accepted one run
// under a 30 s limit: exit 0 or a one-line error, never a panic (≈ 45 s on the shared
// 2-core machine, 2026-12-02: ignored; every `cargo test` samples the design study's
// mutations in config_mutation.rs).
#[test]
#[ignore = "long: every mutation of the design configuration (≈ 45 s)"]
fn mutated_design_configs_run_within_bounds() {
    let f = flowmbd_cli::mutation::exhaustive_findings(
        env!("CARGO_BIN_EXE_flowmbd-belt"),
        &["design"],
        "belt-design-mut",
        2,
        std::time::Duration::from_secs(30),
    );
    assert!(f.is_empty(), "{} findings:\n{}", f.len(), f.join("\n"));
}
