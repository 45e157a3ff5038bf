//! End-to-end checks of the `flowmbd-beam` binary: JSON outputs against Kerkkänen's tables and
//! the exit-code conventions.

use std::process::Command;

fn run(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_flowmbd-beam"))
        .args(args)
        .output()
        .expect("binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
    )
}

fn tmp(name: &str) -> String {
    std::env::temp_dir()
        .join(format!("flowmbd-beam-{}-{name}", std::process::id()))
        .display()
        .to_string()
}

// Kerkkänen Table 2.2, proposed element, n = 4: −0.091333 mm.
#[test]
fn simply_supported_json() {
    let out = tmp("ss");
    let (code, stdout) = run(&[
        "simply-supported",
        "--element",
        "proposed",
        "--nu",
        "0.3",
        "--elements",
        "4",
        "--json",
        "--quiet",
        "--out",
        &out,
    ]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let d = v["midpoint_deflection_mm"].as_f64().unwrap();
    assert!((d + 0.091333).abs() < 0.5e-6, "{d}");
    let _ = std::fs::remove_dir_all(out);
}

// Kerkkänen Table 2.3, proposed element, n = 4: (1.86351, −0.66320) m.
#[test]
fn cantilever_json() {
    let out = tmp("c");
    let (code, stdout) = run(&[
        "cantilever",
        "--element",
        "proposed",
        "--h",
        "0.1",
        "--nu",
        "0.3",
        "--elements",
        "4",
        "--json",
        "--quiet",
        "--out",
        &out,
    ]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let tip = [v["tip"][0].as_f64().unwrap(), v["tip"][1].as_f64().unwrap()];
    assert!(
        (tip[0] - 1.86351).abs() < 0.5e-5 && (tip[1] + 0.66320).abs() < 0.5e-5,
        "{tip:?}"
    );
    assert!(std::path::Path::new(&out).join("shape.vtu").exists());
    let _ = std::fs::remove_dir_all(out);
}

// App conventions: bad input exits with code 2.
#[test]
fn bad_input_exits_2() {
    let out = tmp("bad");
    let (code, _) = run(&[
        "simply-supported",
        "--elements",
        "3",
        "--quiet",
        "--out",
        &out,
    ]);
    assert_eq!(code, 2);
    let (code, _) = run(&["cantilever", "--h=-0.1", "--quiet", "--out", &out]);
    assert_eq!(code, 2);
    let _ = std::fs::remove_dir_all(out);
}

// ground-contact: total contact force of the default case (q = 4q*) within 1e-3 of the
// Euler–Bernoulli value qL − 2qa/3 (see tests/tests/ancf_contact_lagrange.rs).
#[test]
fn ground_contact_json() {
    let out = tmp("g");
    let (code, stdout) = run(&["ground-contact", "--json", "--quiet", "--out", &out]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let total = v["total_force"].as_f64().unwrap();
    let eb = v["euler_bernoulli_total_force"].as_f64().unwrap();
    assert!(((total - eb) / eb).abs() < 1e-3, "{total} N vs {eb} N");
    assert!(std::path::Path::new(&out).join("contact.csv").exists());
    let (code, _) = run(&[
        "ground-contact",
        "--load-factor=-1",
        "--quiet",
        "--out",
        &out,
    ]);
    assert_eq!(code, 2);
    let _ = std::fs::remove_dir_all(out);
}

// Issue 39 item 2: every key and table of every study's printed configuration has a comment
// (its meaning, from the rustdoc of the configuration types) and every floating-point key's
// comment states its unit in brackets (`flowmbd_cli::commented`).
#[test]
fn printed_configurations_are_commented() {
    flowmbd_cli::testing::assert_printed_configs_commented(env!("CARGO_BIN_EXE_flowmbd-beam"));
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
        env!("CARGO_BIN_EXE_flowmbd-beam"),
        &dir,
        |study, _| {
            let overrides = match study {
                "pendulum" => "t_end = 0.01\n",
                "spinning" => "t_end = 0.2\nh = 0.01\n",
                _ => "",
            };
            Short {
                overrides,
                args: &[],
            }
        },
    );
}
