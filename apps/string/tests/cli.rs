//! End-to-end checks of `flowmbd-string` (app conventions and the `modes` output contract).

use std::process::Command;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_flowmbd-string"))
}

fn tmp(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("flowmbd-string-{}-{name}", std::process::id()))
}

// Reference: exact f_n = n(c²−v²)/(2cL) (notes §2.1, v = 20 m/s: 15.171, 30.341, 45.512, 60.683,
// 75.854 Hz) and c = 40.2735 m/s; JSON keys as specified by the issue.
#[test]
fn modes_json_matches_exact_moving_string() {
    let out = bin()
        .args([
            "modes", "--speed", "20", "--nodes", "99", "--modes", "20", "--json", "--quiet",
            "--out",
        ])
        .arg(tmp("modes"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let obj = v.as_object().unwrap();
    let mut keys: Vec<&str> = obj.keys().map(String::as_str).collect();
    keys.sort();
    // the keys, plus those of issue 20 (stability, the exact reference, warnings and
    // what the numbers mean) and issue 34 (regime, truncation growth and its check)
    assert_eq!(
        keys,
        [
            "analytical_growth",
            "analytical_hz",
            "analytical_max_rel_error",
            "analytical_truncation_growth",
            "critical_speed",
            "exact_hz",
            "flowing_growth",
            "flowing_hz",
            "flowing_max_rel_error",
            "flowing_truncation_growth",
            "growth_check",
            "meaning",
            "regime",
            "speed",
            "unstable",
            "warnings"
        ]
    );
    assert_eq!(v["unstable"].as_bool(), Some(false));
    assert!(v["warnings"].as_array().unwrap().is_empty());
    assert_eq!(v["speed"].as_f64().unwrap(), 20.0);
    assert!((v["critical_speed"].as_f64().unwrap() - 40.2735).abs() < 1e-3);
    let exact = [15.171, 30.341, 45.512, 60.683, 75.854];
    // Galerkin (40 terms): 1e-3; flowing (n = 99, 20 modes): FE + truncation error ≈ 0.11 % on f5.
    for (key, tol) in [("analytical_hz", 1e-3), ("flowing_hz", 1.5e-3)] {
        let f: Vec<f64> = v[key]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert!(f.len() >= 5);
        for w in f.windows(2) {
            assert!(w[1] >= w[0], "{key} not ascending");
        }
        for i in 0..5 {
            assert!(
                (f[i] - exact[i]).abs() < tol * exact[i],
                "{key}[{i}] = {} vs {}",
                f[i],
                exact[i]
            );
        }
    }
}

// Reference: app conventions — bad input exits with 2 and a one-line message naming the field;
// unknown configuration fields are rejected with file and line.
#[test]
fn bad_input_exits_with_2_naming_the_field() {
    let out = bin()
        .args(["modes", "--modes", "0", "--quiet", "--out"])
        .arg(tmp("bad"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("modes"), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    let cfg = tmp("cfg.toml");
    std::fs::write(&cfg, "speed = 10.0\nnodez = 5\n").unwrap();
    let out = bin()
        .args(["modes", "--quiet", "--config"])
        .arg(&cfg)
        .arg("--out")
        .arg(tmp("bad2"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("nodez") && err.contains(":2:"), "{err}");
}

// Reference: --print-config round-trips through --config (the defaults are a valid file).
#[test]
fn printed_config_is_accepted_back() {
    for study in ["modes", "sweep", "simulate", "wrap"] {
        let out = bin().args([study, "--print-config"]).output().unwrap();
        assert!(out.status.success(), "{study}");
        let cfg = tmp(&format!("{study}.toml"));
        std::fs::write(&cfg, &out.stdout).unwrap();
        let again = bin()
            .args([study, "--print-config", "--config"])
            .arg(&cfg)
            .output()
            .unwrap();
        assert!(
            again.status.success(),
            "{study}: {}",
            String::from_utf8_lossy(&again.stderr)
        );
        assert_eq!(out.stdout, again.stdout, "{study}");
    }
}

// Issue 39 item 2: every key and table of every study's printed configuration has a comment
// (its meaning, from the rustdoc of the configuration types) and every floating-point key's
// comment states its unit in brackets (`flowmbd_cli::commented`).
#[test]
fn printed_configurations_are_commented() {
    flowmbd_cli::testing::assert_printed_configs_commented(env!("CARGO_BIN_EXE_flowmbd-string"));
}

// Issue 39 item 2: every study has a shipped example under `examples/` (its first line names
// the study: `flowmbd_cli::testing::examples`), and each runs, shortened by its own run-length
// keys, to a complete summary with its `meaning`.
#[test]
fn shipped_examples_cover_every_study_and_run() {
    use flowmbd_cli::testing::ExampleRun::Short;
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    // overrides merged into the example: its run-length keys
    flowmbd_cli::testing::assert_examples_run(
        env!("CARGO_BIN_EXE_flowmbd-string"),
        &dir,
        |study, _| {
            let overrides = match study {
                "simulate" => "duration = 0.05\n",
                "wrap" => "duration = 0.02\n",
                _ => "",
            };
            Short {
                overrides,
                args: &[],
            }
        },
    );
}
