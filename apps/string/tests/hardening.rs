//! Issue 20 reproducers for `flowmbd-string`: `modes` at and above the critical speed reports
//! `"unstable": true` with growth rates, near it warns about unconverged frequencies; negative
//! speeds are numbers, not flags; `--nodes 1e9` is refused before allocating; every
//! configuration table rejects unknown keys; CSV headers carry units and summaries a meaning.

use flowmbd_cli::config::{UNKNOWN_KEY, tables_accepting_unknown_keys_by};
use serde_json::Value;
use std::path::{Path, PathBuf};

fn run(args: &[&str]) -> (i32, String, String) {
    flowmbd_cli::testing::run_binary(env!("CARGO_BIN_EXE_flowmbd-string"), args)
}

fn tmp(name: &str) -> PathBuf {
    flowmbd_cli::testing::fresh_dir("flowmbd-string-hard", name)
}

fn modes(speed: &str, dir: &Path) -> (Value, String) {
    let out = dir.join(format!("m{speed}"));
    let (code, json, err) = run(&[
        "modes",
        "--speed",
        speed,
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{speed}: {err}");
    (serde_json::from_str(&json).unwrap(), err)
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

// Issue 20 ("checked by": `modes --speed 45 --json` reports "unstable": true). Reference:
// Ribaric §4.2.3 (the string is unstable for v > c = √(T/ρA) = 40.27 m/s) and the seed note's
// STR-5 (a growing solution); below c the undamped gyroscopic system has no growing solution.
#[test]
fn modes_at_and_above_the_critical_speed_report_instability() {
    let dir = tmp("crit");
    for speed in ["41", "45", "60"] {
        let (v, err) = modes(speed, &dir);
        assert_eq!(v["unstable"].as_bool(), Some(true), "{speed}");
        for key in ["flowing_growth", "analytical_growth"] {
            let g = v[key].as_array().unwrap();
            assert!(!g.is_empty(), "{speed}: {key}");
            assert!(g.iter().all(|x| x["rate_per_s"].as_f64().unwrap() > 0.0));
        }
        assert!(v["exact_hz"].as_array().unwrap().is_empty());
        assert!(
            err.contains("warning:") && err.contains("unstable"),
            "{err}"
        );
        assert!(dir.join(format!("m{speed}/growth.csv")).is_file());
    }
    let (v, _) = modes("39", &dir);
    assert_eq!(v["unstable"].as_bool(), Some(false));
    let _ = std::fs::remove_dir_all(dir);
}

// Issue 20: at 39 m/s the default 20 modes leave the 10th frequency 20-30 % off; the summary
// and stderr say so. Reference: the exact f_n = n(c² − v²)/(2cL) (Wickert & Mote 1990).
#[test]
fn unconverged_frequencies_near_the_critical_speed_are_warned() {
    let dir = tmp("conv");
    let (v, err) = modes("39", &dir);
    let c = v["critical_speed"].as_f64().unwrap();
    let exact: Vec<f64> = (1..=10)
        .map(|n| n as f64 * c * (1.0 - 39.0f64.powi(2) / (c * c)) / 2.0)
        .collect();
    let f = floats(&v["flowing_hz"]);
    let e10 = (f[9] - exact[9]).abs() / exact[9];
    assert!(e10 > 0.2 && e10 < 0.3, "10th frequency off by {e10}");
    assert!((v["flowing_max_rel_error"].as_f64().unwrap() - e10).abs() < 1e-12);
    assert!(
        err.contains("mode 10") && err.contains("raise `modes`"),
        "{err}"
    );
    assert_eq!(v["warnings"].as_array().unwrap().len(), 1);
    let _ = std::fs::remove_dir_all(dir);
}

// Issue 20: `--speed -20` was refused by the argument parser (it needed `=`). A negative speed
// is a number: the string travelling the other way has the same frequencies (f_n depends on
// v² only).
#[test]
fn negative_speed_is_a_number() {
    let dir = tmp("neg");
    let (neg, _) = modes("-20", &dir);
    let (pos, _) = modes("20", &dir);
    assert_eq!(neg["speed"].as_f64(), Some(-20.0));
    let (a, b) = (floats(&neg["flowing_hz"]), floats(&pos["flowing_hz"]));
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() < 1e-9 * y, "{x} vs {y}");
    }
    let _ = std::fs::remove_dir_all(dir);
}

// Issue 20: `string modes --nodes 1e9` aborted on the allocation (exit 134); it is refused by
// the documented ceiling (flowing::string_study::MAX_STRING_NODES) with exit 2
#[test]
fn huge_sizes_are_refused_before_allocating() {
    let dir = tmp("size");
    for args in [
        vec!["modes", "--nodes", "1000000000"],
        vec!["sweep", "--nodes", "1000000000"],
    ] {
        let mut a = args.clone();
        a.extend(["--quiet", "--out", dir.to_str().unwrap()]);
        let (code, _, err) = run(&a);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(
            err.contains("nodes: must lie in [3, 2000], got 1000000000"),
            "{err}"
        );
    }
    let _ = std::fs::remove_dir_all(dir);
}

// every table of every study's configuration rejects an unknown key (exit 2, one line)
#[test]
fn every_table_rejects_an_unknown_key() {
    let dir = tmp("keys");
    let file = dir.join("v.toml");
    for study in ["modes", "sweep", "simulate", "wrap"] {
        let (code, text, err) = run(&[study, "--print-config"]);
        assert_eq!(code, 0, "{err}");
        // the other derivative operators too (FdScheme was a hole)
        for variant in [
            text.clone(),
            text.replace(
                "[derivative]\nConsistent = \"Lumped\"",
                "[derivative.FiniteDifference]\nfirst = \"Central\"\nsecond = \"ThreePoint\"",
            ),
            text.replace(
                "[derivative]\nConsistent = \"Lumped\"",
                "[derivative.Polynomial]\ndegree = 5",
            ),
        ] {
            let holes = tables_accepting_unknown_keys_by(&variant, |t| {
                std::fs::write(&file, t).unwrap();
                let (code, _, err) =
                    run(&[study, "--config", file.to_str().unwrap(), "--print-config"]);
                if code != 0 {
                    assert_eq!(code, 2, "{study}: {err}");
                    // an externally tagged enum's table (`[derivative]`) says it holds more than its one
                    // variant instead of naming the key
                    assert!(
                        err.contains(UNKNOWN_KEY) || err.contains("wanted exactly 1 element"),
                        "{study}: {err}"
                    );
                }
                code == 0
            });
            assert!(holes.is_empty(), "{study}: {holes:?}");
        }
    }
    let _ = std::fs::remove_dir_all(dir);
}

// Item 5 of issue 20 and the sweep's shading: every study's CSV headers carry units, the
// summaries a meaning; the sweep plot shades the unstable speeds
#[test]
fn csv_units_meaning_and_the_shaded_sweep() {
    let dir = tmp("units");
    for (study, extra) in [
        ("modes", vec!["--speed", "45"]),
        ("sweep", vec![]),
        ("simulate", vec![]),
        ("wrap", vec![]),
    ] {
        let out = dir.join(study);
        let mut args = vec![study, "--quiet", "--json", "--out", out.to_str().unwrap()];
        args.extend(extra);
        let (code, json, err) = run(&args);
        assert_eq!(code, 0, "{study}: {err}");
        let v: Value = serde_json::from_str(&json).unwrap();
        assert!(
            v["meaning"].as_str().unwrap_or_default().len() > 100,
            "{study}"
        );
        let bad = flowmbd_cli::output::columns_without_unit(&out);
        assert!(bad.is_empty(), "{study}: {bad:?}");
        if study == "sweep" {
            let from = v["flowing_unstable_from"].as_f64().unwrap();
            let c = v["critical_speed"].as_f64().unwrap();
            assert!(from >= c * (1.0 - 1e-9) && from < 1.1 * c, "{from} vs {c}");
            let svg = std::fs::read_to_string(out.join("sweep.svg")).unwrap();
            assert!(svg.contains("unstable (from"), "the shaded band's legend");
        }
    }
    let _ = std::fs::remove_dir_all(dir);
}

// Issue 20 item 2: the documented ceilings are raised by `--allow-large` (1000-fold, see
// mbd_core::validate::limits): one node above MAX_STRING_NODES = 2000 is refused without the
// flag, naming it, and accepted with it; 10^9 nodes stay refused (2000 × 1000 = 2·10^6).
// `--print-config` validates first and computes nothing, so the test is cheap.
#[test]
fn allow_large_raises_the_node_ceiling_1000_fold() {
    let (code, _, err) = run(&["modes", "--nodes", "2001", "--print-config"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("nodes: must lie in [3, 2000], got 2001") && err.contains("--allow-large"),
        "{err}"
    );
    let (code, out, err) = run(&[
        "modes",
        "--nodes",
        "2001",
        "--print-config",
        "--allow-large",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("nodes = 2001"), "{out}");
    let (code, _, err) = run(&[
        "modes",
        "--nodes",
        "1000000000",
        "--print-config",
        "--allow-large",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("must lie in [3, 2000000]"), "{err}");
}
