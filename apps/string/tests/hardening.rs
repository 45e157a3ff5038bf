//! Issue 20, 34 and 35 reproducers for `flowmbd-string`: `modes` above the critical speed is
//! neutral with truncation growth labelled as such (issue 34), at it divergence, near it warns
//! about unconverged frequencies; bad input is exit 2 naming the field (issue 35); negative
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

// Issue 34 item 9 ("checked by": `modes --speed 45 --json`): above c = √(T/ρA) = 40.27 m/s
// the travelling string between fixed guides is neutrally stable with the exact frequencies
// f_n = n(v² − c²)/(2cL) (Wickert & Mote 1990; the characteristic time τ = t + vx/(c² − v²)
// makes it a fixed string): "unstable" is false, exact_hz is the closed form, and the truncated
// models' growth is listed as truncation growth, whose rate the refined model does not
// reproduce (it grows faster). At c itself the stiffness vanishes: divergence, unstable.
#[test]
fn modes_above_the_critical_speed_are_neutral_with_labelled_truncation_growth() {
    let dir = tmp("crit");
    for speed in ["41", "45", "60"] {
        let (v, err) = modes(speed, &dir);
        let s: f64 = speed.parse().unwrap();
        assert_eq!(v["unstable"].as_bool(), Some(false), "{speed}");
        assert_eq!(v["regime"].as_str(), Some("supercritical"), "{speed}");
        let c = v["critical_speed"].as_f64().unwrap();
        let exact = floats(&v["exact_hz"]);
        assert_eq!(exact.len(), 10);
        for (n, f) in exact.iter().enumerate() {
            let want = (n + 1) as f64 * (s * s - c * c) / (2.0 * c);
            assert!(
                *f > 0.0 && (f - want).abs() < 1e-12 * want,
                "{speed}: {f} vs {want}"
            );
        }
        for key in ["flowing_growth", "analytical_growth"] {
            assert!(v[key].as_array().unwrap().is_empty(), "{speed}: {key}");
        }
        for key in ["flowing_truncation_growth", "analytical_truncation_growth"] {
            let g = v[key].as_array().unwrap();
            assert!(!g.is_empty(), "{speed}: {key}");
            for x in g {
                let (r, r2) = (
                    x["rate_per_s"].as_f64().unwrap(),
                    x["check_rate_per_s"].as_f64().unwrap(),
                );
                assert!(r > 0.0 && r2 > 1.1 * r, "{speed}: {key} {x}");
            }
        }
        // the Galerkin model's neutral frequencies are the exact ones (40 terms)
        let a = floats(&v["analytical_hz"]);
        for n in 0..8 {
            assert!((a[n] - exact[n]).abs() < 2e-3 * exact[n], "{speed}: {a:?}");
        }
        assert!(
            err.contains("warning:") && err.contains("truncation artefacts"),
            "{err}"
        );
        assert!(!err.contains("the model is unstable"), "{err}");
        let growth = std::fs::read_to_string(dir.join(format!("m{speed}/growth.csv"))).unwrap();
        assert!(
            growth.starts_with("model_code,truncation_flag,"),
            "{growth}"
        );
        // no JSON null anywhere in the supercritical summary
        assert!(!v.to_string().contains("null"), "{v}");
    }
    let (v, _) = modes("39", &dir);
    assert_eq!(v["unstable"].as_bool(), Some(false));
    assert_eq!(v["regime"].as_str(), Some("subcritical"));
    // the critical speed of the default string, as printed by `modes` (f64 shortest form)
    let (v, err) = modes("40.27353238346881", &dir);
    assert_eq!(v["regime"].as_str(), Some("critical"));
    assert_eq!(v["unstable"].as_bool(), Some(true));
    assert!(floats(&v["exact_hz"]).iter().all(|f| *f == 0.0));
    assert!(err.contains("divergence"), "{err}");
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
        let bad = flowmbd_cli::output::csv_violations(&out);
        assert!(bad.is_empty(), "{study}: {bad:?}");
        if study == "sweep" {
            // issue 34 item 9: above c the truncated models grow, the string does not; the
            // Galerkin model's neutral frequencies follow the exact n(v² − c²)/(2cL)
            assert!(v["unstable_from"].is_null(), "{v}");
            let from = v["flowing_truncation_growth_from"].as_f64().unwrap();
            let c = v["critical_speed"].as_f64().unwrap();
            assert!(from >= c * (1.0 - 1e-9) && from < 1.1 * c, "{from} vs {c}");
            assert!(
                v["analytical_max_rel_error_above_1_1c"].as_f64().unwrap() < 2e-3,
                "{v}"
            );
            let svg = std::fs::read_to_string(out.join("sweep.svg")).unwrap();
            assert!(
                svg.contains("truncation growth only"),
                "the shaded band's legend"
            );
            assert!(!svg.contains("unstable (from"));
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

/// Runs `study` with the configuration `toml` (and `extra` arguments) and asserts exit 2 with
/// one line naming `field`; returns the line.
fn refused(study: &str, toml: &str, extra: &[&str], field: &str) -> String {
    let dir = tmp(&format!("refuse-{study}-{field}"));
    let file = dir.join("c.toml");
    std::fs::write(&file, toml).unwrap();
    let out = dir.join("out");
    let mut args = vec![
        study,
        "--quiet",
        "--config",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend(extra);
    let (code, _, err) = run(&args);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(code, 2, "{study} {toml:?}: {err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains(&format!("{field}: ")), "{field}: {err}");
    err
}

// Issue 35: `simulate` with tension = 100 N (c = 12.74 m/s, below the 20 m/s speed) exited 0
// with exact_hz = −9.34, −18.67 … Hz and a null energy drift. Above c the fixed–fixed string is
// no initial-value problem (issue 34: both waves travel downstream, the truncation grows
// without bound), so the pluck transient is refused, naming the speed and the critical speed
// √(100/(7850·7.854e-5)) = 12.7356 m/s; at c the same (divergence).
#[test]
fn simulate_above_or_at_the_critical_speed_is_refused() {
    let err = refused(
        "simulate",
        "[string]\nlength = 1.0\ndensity = 7850.0\narea = 7.854e-5\ntension = 100.0\n",
        &[],
        "speed",
    );
    assert!(
        err.contains("12.7356") && err.contains("critical speed"),
        "{err}"
    );
    refused("simulate", "speed = 40.27353238346881\n", &[], "speed");
    refused("simulate", "speed = -45.0\n", &[], "speed");
}

// Issue 35: `wrap` with contact.rtol = -1e9 exited 1 "numerical failure"; every contact setting
// is checked before the run (exit 2 naming it), as are the run's length in periods of its fastest
// motion and the pulley count
#[test]
fn wrap_settings_and_run_length_are_checked() {
    for (toml, field) in [
        ("[contact]\nrtol = -1e9\n", "contact.rtol"),
        ("[contact]\nrtol = 0.0\natol = 0.0\n", "contact.rtol"),
        ("[contact]\natol = -1.0\n", "contact.atol"),
        ("[contact]\ngap_tol = nan\n", "contact.gap_tol"),
        ("[contact]\nforce_tol = inf\n", "contact.force_tol"),
        ("[contact]\nmax_events = 0\n", "contact.max_events"),
        // 10⁹ s in samples of 10³ s: 10⁶ samples, but 1.3·10¹² periods of the FE mesh's top
        // frequency c(n+1)/(πL) = 1282 Hz
        ("duration = 1e9\nsample = 1e3\n", "duration"),
        // a load of 1 THz for the default 0.3 s
        (
            "[load]\nx = 0.6\namplitude = 15.0\nfrequency = 1e12\n",
            "duration",
        ),
        ("sample = 0.5\n", "sample"),
        ("speed = 41.0\n", "speed"),
        ("free_modes = 1000000\n", "free_modes"),
    ] {
        refused("wrap", toml, &[], field);
    }
    let mut many = String::new();
    for i in 0..65 {
        many.push_str(&format!(
            "[[pulleys]]\ncenter_x = {}\ntop = 0.015\nradius = 0.25\n",
            0.01 + 0.015 * i as f64
        ));
    }
    refused("wrap", &many, &[], "pulleys");
}

// Issue 35: run lengths and counts of `simulate` are bounded before the run (a step longer than
// the run, the recorded history samples × modes, the RK4 work steps × modes²), a step beyond
// RK4's stability limit 2√2/|λ|max and a model that grows (a derivative operator that is not
// FE-consistent, notes STR-6: spectral derivatives with all 49 modes at 30 m/s grow at
// ≈ 144 1/s) are refused, naming the field, instead of printing non-finite numbers
#[test]
fn simulate_run_lengths_steps_and_growing_models_are_refused() {
    for (toml, field) in [
        ("duration = 20.0\nstep = 30.0\n", "step"),
        // 2·10⁶ samples of 10 modes: 2·10⁷ recorded values > 10⁷
        ("duration = 100.0\nsample_every = 1\n", "duration"),
        // 8·10⁴ steps × 2000² = 3.2·10¹¹ > 10¹¹
        ("nodes = 2000\nmodes = 2000\n", "duration"),
        ("[pluck]\nx = 0.3\namplitude = 1e300\n", "pluck.amplitude"),
    ] {
        refused("simulate", toml, &["--print-config"], field);
    }
    // |λ|max ≈ 2c(n+1)/L = 8.05·10³ 1/s for 99 modes: the limit is 3.5·10⁻⁴ s
    let err = refused("simulate", "modes = 99\nstep = 1e-3\n", &[], "step");
    assert!(err.contains("stability limit"), "{err}");
    let err = refused(
        "simulate",
        "speed = 30.0\nnodes = 49\nmodes = 49\nderivative = \"Spectral\"\n",
        &[],
        "derivative",
    );
    assert!(err.contains("grows at 1.4"), "{err}");
}

// Issue 35: `modes` and `sweep` bound what they allocate and compute by the input (`report`
// made `exact_hz` of 10¹⁸ entries; the eigen work of a sweep; absurd lengths, densities and
// speeds gave infinite matrices)
#[test]
fn modes_and_sweep_sizes_and_scales_are_refused() {
    for (study, toml, extra, field) in [
        ("modes", "report = 1000000000000000000\n", vec![], "report"),
        ("modes", "report = 41\n", vec![], "report"),
        (
            "modes",
            "[string]\nlength = 1e-300\ndensity = 7850.0\narea = 7.854e-5\ntension = 1000.0\n",
            vec![],
            // the area no longer fits a 1e-300 m string (area below length², issue 35)
            "string.area",
        ),
        (
            "modes",
            "[string]\nlength = 1.0\ndensity = 1e-200\narea = 1e-200\ntension = 1000.0\n",
            vec![],
            "string.density",
        ),
        ("modes", "", vec!["--speed", "1e200"], "speed"),
        (
            "sweep",
            "max_speed_ratio = 1e300\n",
            vec![],
            "max_speed_ratio",
        ),
        (
            "sweep",
            "galerkin_terms = 2000\nsteps = 1000\n",
            vec![],
            "steps",
        ),
    ] {
        let mut args = extra.clone();
        args.push("--print-config");
        refused(study, toml, &args, field);
    }
}
