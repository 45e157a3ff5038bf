//! Issue 20 reproducers for `flowmbd-belt`: every table of every study's configuration (the
//! defaults and the shipped Kerkkänen examples, which use the other load and speed profiles)
//! rejects an unknown key; `ancf --t-end 1e300` is refused before it writes anything; every
//! CSV header says its unit and every summary says what its numbers mean.

use flowmbd_cli::config::{UNKNOWN_KEY, tables_accepting_unknown_keys_by};
use std::path::{Path, PathBuf};

fn run(args: &[&str]) -> (i32, String, String) {
    flowmbd_cli::testing::run_binary(env!("CARGO_BIN_EXE_flowmbd-belt"), args)
}

fn tmp(name: &str) -> PathBuf {
    flowmbd_cli::testing::fresh_dir("flowmbd-belt-hard", name)
}

/// The tables of `text` (a configuration of `study`) that the binary accepts with an unknown
/// key; every rejection must be exit 2, one line, naming the key.
fn holes(study: &str, text: &str, dir: &Path) -> Vec<String> {
    let file = dir.join(format!("{study}-variant.toml"));
    tables_accepting_unknown_keys_by(text, |variant| {
        std::fs::write(&file, variant).unwrap();
        let (code, _, err) = run(&[study, "--config", file.to_str().unwrap(), "--print-config"]);
        if code != 0 {
            assert_eq!(code, 2, "{study}: {err}");
            assert!(err.contains(UNKNOWN_KEY), "{study}: {err}");
            assert_eq!(err.trim().lines().count(), 1, "{study}: {err}");
        }
        code == 0
    })
}

// Issue 20: unknown keys were accepted in `[drive.pulleys.drive.load]` (a unit variant of an
// internally tagged enum: `kind = "none"`); every table now rejects them (definition: each
// configuration table is `deny_unknown_fields`)
#[test]
fn every_table_rejects_an_unknown_key() {
    let dir = tmp("keys");
    for study in ["speed-loss", "ancf", "wave", "demo", "plate", "fead"] {
        let (code, text, err) = run(&[study, "--print-config"]);
        assert_eq!(code, 0, "{err}");
        let h = holes(study, &text, &dir);
        assert!(
            h.is_empty(),
            "{study}: tables accepting unknown keys: {h:?}"
        );
    }
    // the shipped examples use constant and cosine loads, constant speeds, other friction laws
    // (Kerkkänen §3.3 for `ancf`, §4.6 for `plate`, Pechstein–Gerstmayr for `fead`)
    // (each example's first line names its studies: `flowmbd_cli::testing::examples`)
    let examples =
        flowmbd_cli::testing::examples(&Path::new(env!("CARGO_MANIFEST_DIR")).join("examples"));
    assert!(
        examples.len() >= 10,
        "kerkkanen-3-3-a … f (ancf), kerkkanen-4-6-model1, -2 (plate), pechstein-gerstmayr, \
         fead-three-pulley (fead): {examples:?}"
    );
    for (studies, p) in examples {
        assert!(!studies.is_empty(), "{}: names no study", p.display());
        for study in &studies {
            let (code, text, err) =
                run(&[study, "--config", p.to_str().unwrap(), "--print-config"]);
            assert_eq!(code, 0, "{err}");
            let h = holes(study, &text, &dir);
            assert!(h.is_empty(), "{}: {h:?}", p.display());
        }
    }
    // the reproducer in today's vocabulary: a load `torque` on an idler (which has
    // none) is refused by name
    let (_, text, _) = run(&["ancf", "--print-config"]);
    let bad = text.replacen("kind = \"load\"\n", "kind = \"idler\"\n", 1);
    assert_ne!(bad, text);
    let f = dir.join("load.toml");
    std::fs::write(&f, bad).unwrap();
    let (code, _, err) = run(&["ancf", "--config", f.to_str().unwrap(), "--print-config"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("unknown field `torque`"), "{err}");
    let _ = std::fs::remove_dir_all(dir);
}

// Issue 20: `belt ancf --t-end 1e300` wrote VTK files until killed; it is refused at once
// (exit 2, one line naming t_end, nothing written), and `-1` reaches the check as a number
#[test]
fn absurd_end_time_is_refused_before_anything_is_written() {
    let dir = tmp("tend");
    let out = dir.join("o");
    let t0 = std::time::Instant::now();
    let (code, _, err) = run(&[
        "ancf",
        "--t-end",
        "1e300",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("t_end") && err.contains("1e300 s"), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(!out.exists(), "nothing is written");
    assert!(t0.elapsed().as_secs() < 30);
    let (code, _, err) = run(&[
        "ancf",
        "--t-end",
        "-1",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("t_end") && err.contains("got -1"), "{err}");
    let _ = std::fs::remove_dir_all(dir);
}

// Item 5 of issue 20: the CSV headers say their units and the summary says what the numbers
// mean (a short ANCF run, the slider-crank demo and the span-wave study)
#[test]
fn csv_headers_carry_units_and_summaries_a_meaning() {
    let dir = tmp("units");
    for (study, extra) in [
        ("ancf", vec!["--t-end", "0.05"]),
        ("demo", vec![]),
        ("wave", vec!["--t-end", "0.05"]),
        ("plate", vec!["--t-end", "0.002"]),
    ] {
        let out = dir.join(study);
        let mut args = vec![study, "--quiet", "--json", "--out", out.to_str().unwrap()];
        args.extend(extra);
        let (code, json, err) = run(&args);
        assert_eq!(code, 0, "{study}: {err}");
        let v: serde_json::Value = serde_json::from_str(&json).unwrap();
        let meaning = v["meaning"].as_str().unwrap_or_default();
        assert!(meaning.len() > 100, "{study}: meaning `{meaning}`");
        let bad = flowmbd_cli::output::csv_violations(&out);
        assert!(bad.is_empty(), "{study}: columns without unit: {bad:?}");
    }
    let _ = std::fs::remove_dir_all(dir);
}

// Issue 20 item 2: `--allow-large` raises the run-length ceilings 1000-fold: 2·10^4 s of the
// ANCF drive are 2·10^7 history rows at the default 1 ms interval, above MAX_HISTORY_ROWS =
// 10^7 (refused, naming t_end), within 10^10 with the flag (`--print-config` computes nothing);
// 10^300 s stay refused.
#[test]
fn allow_large_raises_the_run_length_ceilings() {
    let (code, _, err) = run(&["ancf", "--t-end", "2e4", "--print-config"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("t_end") && err.contains("--allow-large"),
        "{err}"
    );
    let (code, out, err) = run(&["ancf", "--t-end", "2e4", "--print-config", "--allow-large"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("t_end = 20000.0"), "{out}");
    let (code, _, err) = run(&[
        "ancf",
        "--t-end",
        "1e300",
        "--print-config",
        "--allow-large",
    ]);
    assert_eq!(code, 2, "{err}");
}

// Issue 35 reproducers: `drive.belt.alpha1 = 1e300` overflowed the static solve (exit 1,
// "non-finite value") and `integrator.rho_inf = 0` was reported to end in NaN; both are input
// outside the physical range (stiffness multiplier of Kerkkänen (3.18) in [1e-6, 1e6], ρ∞ in
// [ancf::belt_drive::simulate::RHO_INF_MIN, 1]) and are refused up front: exit 2, one line
// naming the field. The in-range neighbours are accepted (the check is not a blanket refusal).
#[test]
fn ancf_stiffness_multiplier_and_spectral_radius_out_of_range_are_refused() {
    let dir = tmp("ancf-range");
    let (code, base, err) = run(&["ancf", "--print-config"]);
    assert_eq!(code, 0, "{err}");
    let file = dir.join("c.toml");
    let cases = [
        ("alpha1 = 1.0", "alpha1 = 1e300", "belt.alpha1", false),
        ("alpha1 = 1.0", "alpha1 = 0.0", "belt.alpha1", false),
        ("alpha1 = 1.0", "alpha1 = 2.0", "belt.alpha1", true),
        ("alpha2 = 0.01", "alpha2 = 1e300", "belt.alpha2", false),
        ("young = 100000000.0", "young = 1e300", "belt.young", false),
        (
            "rho_inf = 0.8",
            "rho_inf = 0.0",
            "integrator.rho_inf",
            false,
        ),
        (
            "rho_inf = 0.8",
            "rho_inf = 1e-300",
            "integrator.rho_inf",
            false,
        ),
        ("rho_inf = 0.8", "rho_inf = 0.5", "integrator.rho_inf", true),
    ];
    for (from, to, field, ok) in cases {
        assert!(base.contains(from), "{from} not in the default config");
        std::fs::write(&file, base.replacen(from, to, 1)).unwrap();
        let (code, _, err) = run(&["ancf", "--config", file.to_str().unwrap(), "--print-config"]);
        if ok {
            assert_eq!(code, 0, "{to}: {err}");
        } else {
            assert_eq!(code, 2, "{to}: {err}");
            assert!(err.contains(field), "{to}: {err}");
            assert_eq!(err.trim().lines().count(), 1, "{to}: {err}");
        }
    }
    let _ = std::fs::remove_dir_all(dir);
}

// Issue 35 (previous hardening pass): `demo` accepted omega = 1e300 rad/s and t_end = 1e9 s
// (2·10¹² steps); both are refused before anything runs (exit 2, one line naming the field:
// |omega| ≤ 1e4 rad/s, |omega|·step ≤ 0.5 rad, t_end/step ≤ 10⁶ steps), and `--allow-large`
// raises the step ceiling only
#[test]
fn demo_refuses_absurd_crank_speed_and_run_length() {
    let dir = tmp("demo35");
    let (code, text, err) = run(&["demo", "--print-config"]);
    assert_eq!(code, 0, "{err}");
    let line = |key: &str| {
        text.lines()
            .find(|l| l.starts_with(key))
            .unwrap()
            .to_string()
    };
    let cases = [
        ("omega", "omega = 1e300", "omega"),
        ("omega", "omega = -2e4", "omega"),
        ("omega", "omega = 1000.0", "step"),
        ("t_end", "t_end = 1e9", "t_end"),
    ];
    for (key, new, field) in cases {
        let file = dir.join("demo.toml");
        std::fs::write(&file, text.replacen(&line(key), new, 1)).unwrap();
        let (code, _, err) = run(&["demo", "--config", file.to_str().unwrap(), "--print-config"]);
        assert_eq!(code, 2, "{new}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains(field), "{new}: {err}");
    }
    // 1e3 s at the default 1 ms step: 10⁶ steps, within the ceiling; 1e4 s needs --allow-large
    let file = dir.join("demo.toml");
    std::fs::write(&file, text.replacen(&line("t_end"), "t_end = 1e4", 1)).unwrap();
    let path = file.to_str().unwrap();
    let (code, _, err) = run(&["demo", "--config", path, "--print-config"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("t_end") && err.contains("--allow-large"),
        "{err}"
    );
    let (code, _, err) = run(&["demo", "--config", path, "--print-config", "--allow-large"]);
    assert_eq!(code, 0, "{err}");
    let _ = std::fs::remove_dir_all(dir);
}

// Issue 35 (previous hardening pass): `fead --quiet` printed its model line and its notes on
// stderr; with `--quiet` a run that succeeds says nothing there (definition of --quiet)
#[test]
fn fead_quiet_is_quiet() {
    use drives::fead::FeadConfig;
    let mut c = FeadConfig::default();
    c.engine.orders.clear();
    c.run.ramp = 0.02;
    c.run.settle = 0.02;
    c.run.window = 0.02;
    let dir = tmp("fead_quiet");
    let file = dir.join("fead.toml");
    std::fs::write(&file, toml::to_string(&c).unwrap()).unwrap();
    let out = dir.join("out");
    let (code, _, err) = run(&[
        "fead",
        "--config",
        file.to_str().unwrap(),
        "--rpm",
        "800",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(err, "", "--quiet must leave stderr empty");
    assert!(out.join("summary.json").exists());
    let _ = std::fs::remove_dir_all(dir);
}
