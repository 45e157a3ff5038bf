//! Issue 20 reproducers for `flowmbd-beam`: `cantilever --elements 1e9` aborted on the
//! allocation (exit 134); every study refuses element counts above the documented ceiling
//! (`ancf::beam_mesh::MAX_BEAM_ELEMENTS`) with exit 2 before building anything, runs longer than
//! `flowmbd_cases::ancf_beams::MAX_TIME_STEPS` steps are refused, every configuration table
//! rejects unknown keys, and the summaries say what their numbers mean.

use flowmbd_cli::config::{UNKNOWN_KEY, tables_accepting_unknown_keys_by};
use std::path::PathBuf;

const STUDIES: [&str; 5] = [
    "simply-supported",
    "cantilever",
    "pendulum",
    "spinning",
    "ground-contact",
];

fn run(args: &[&str]) -> (i32, String, String) {
    flowmbd_cli::testing::run_binary(env!("CARGO_BIN_EXE_flowmbd-beam"), args)
}

fn tmp(name: &str) -> PathBuf {
    flowmbd_cli::testing::fresh_dir("flowmbd-beam-hard", name)
}

#[test]
fn huge_element_counts_and_runs_are_refused() {
    let dir = tmp("size");
    for study in STUDIES {
        let t0 = std::time::Instant::now();
        let (code, _, err) = run(&[
            study,
            "--elements",
            "1000000000",
            "--quiet",
            "--out",
            dir.to_str().unwrap(),
        ]);
        assert_eq!(code, 2, "{study}: {err}");
        assert!(
            err.contains("elements: must lie in [1, 100000], got 1000000000"),
            "{study}: {err}"
        );
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(
            t0.elapsed().as_secs() < 10,
            "{study} took {:?}",
            t0.elapsed()
        );
    }
    // a pendulum of 10^300 s
    let f = dir.join("p.toml");
    let (_, text, _) = run(&["pendulum", "--print-config"]);
    let text: String = text
        .lines()
        .map(|l| {
            if l.starts_with("t_end") {
                "t_end = 1e300".to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    std::fs::write(&f, text).unwrap();
    let (code, _, err) = run(&[
        "pendulum",
        "--config",
        f.to_str().unwrap(),
        "--print-config",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("t_end") && err.contains("steps"), "{err}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn every_table_rejects_an_unknown_key() {
    let dir = tmp("keys");
    let file = dir.join("v.toml");
    for study in STUDIES {
        let (code, text, err) = run(&[study, "--print-config"]);
        assert_eq!(code, 0, "{err}");
        let holes = tables_accepting_unknown_keys_by(&text, |t| {
            std::fs::write(&file, t).unwrap();
            let (code, _, err) =
                run(&[study, "--config", file.to_str().unwrap(), "--print-config"]);
            if code != 0 {
                assert_eq!(code, 2, "{study}: {err}");
                assert!(err.contains(UNKNOWN_KEY), "{study}: {err}");
            }
            code == 0
        });
        assert!(holes.is_empty(), "{study}: {holes:?}");
    }
    let _ = std::fs::remove_dir_all(dir);
}

// item 5 of issue 20 on the static studies (the dynamic ones are run by cli.rs)
#[test]
fn summaries_say_what_the_numbers_mean() {
    let dir = tmp("meaning");
    for study in ["simply-supported", "cantilever", "ground-contact"] {
        let out = dir.join(study);
        let (code, json, err) = run(&[study, "--quiet", "--json", "--out", out.to_str().unwrap()]);
        assert_eq!(code, 0, "{study}: {err}");
        let v: serde_json::Value = serde_json::from_str(&json).unwrap();
        assert!(
            v["meaning"].as_str().unwrap_or_default().len() > 100,
            "{study}"
        );
        let bad = flowmbd_cli::output::csv_violations(&out);
        assert!(bad.is_empty(), "{study}: {bad:?}");
    }
    let _ = std::fs::remove_dir_all(dir);
}

// Issue 20 item 2: `--allow-large` raises the element ceiling (MAX_BEAM_ELEMENTS = 10^5)
// 1000-fold: 100 001 elements are refused without it and accepted with it (`--print-config`
// validates and computes nothing).
#[test]
fn allow_large_raises_the_element_ceiling() {
    for study in STUDIES {
        let (code, _, err) = run(&[study, "--elements", "100001", "--print-config"]);
        assert_eq!(code, 2, "{study}: {err}");
        assert!(err.contains("--allow-large"), "{study}: {err}");
        let (code, out, err) = run(&[
            study,
            "--elements",
            "100001",
            "--print-config",
            "--allow-large",
        ]);
        assert_eq!(code, 0, "{study}: {err}");
        assert!(out.contains("elements = 100001"), "{study}: {out}");
    }
}
