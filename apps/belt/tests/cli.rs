//! End-to-end checks of the `flowmbd-belt` binary: the speed-loss JSON contract of issue 8, the
//! configuration round trip, the shipped example configurations and the exit-code conventions.

use std::path::PathBuf;

fn run(args: &[&str]) -> (i32, String, String) {
    flowmbd_cli::testing::run_binary(env!("CARGO_BIN_EXE_flowmbd-belt"), args)
}

fn tmp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("flowmbd-belt-{}-{name}", std::process::id()))
}

// Issue 39, item 3: without --json the study prints a short result table on stdout; its
// numbers are summary.json's (reference: the summary the same run wrote).
#[test]
fn speed_loss_prints_its_result_table() {
    let out = tmp("table");
    let (code, stdout, stderr) = run(&[
        "speed-loss",
        "--omega",
        "22.6",
        "--torques",
        "0,4",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let rows: Vec<&str> = stdout.lines().skip(2).collect();
    assert_eq!(rows.len(), 2, "{stdout}");
    for (row, p) in rows.iter().zip(v["points"].as_array().unwrap()) {
        let d = format!("{:.5}", p["delta_omega"].as_f64().unwrap());
        let t1 = format!("{:.1}", p["tension_tight"].as_f64().unwrap());
        assert!(row.contains(&d) && row.contains(&t1), "{row} vs {p}");
    }
    assert!(stdout.starts_with("speed loss, flowing belt"), "{stdout}");
    // issue 39 item 3: the meaning compares this run with Bechtel's line, from its own numbers
    // (reference: the summary's delta_omega and analytical at 4 N m)
    let ratio =
        v["points"][1]["delta_omega"].as_f64().unwrap() / v["analytical"][1].as_f64().unwrap();
    let said = format!("in this run {ratio:.2} times Bechtel's at 4 N m and 22.6 rad/s");
    assert!(
        v["meaning"].as_str().unwrap().contains(&said),
        "{said} not in {}",
        v["meaning"]
    );
    let _ = std::fs::remove_dir_all(out);
}

// Issue 8 contract; physics: unloaded the driven pulley turns at the driver's speed (to the
// steady-state tolerance of the app's default procedure; the 1e-6 relative check with a tight
// tolerance is tests/tests/flowing_belt.rs) and under load Δω > 0 next to a positive Bechtel (6.3).
#[test]
fn speed_loss_json_contract() {
    let out = tmp("sl");
    let (code, stdout, stderr) = run(&[
        "speed-loss",
        "--omega",
        "22.6",
        "--torques",
        "0,4",
        "--json",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(v["omega_driver"].as_f64(), Some(22.6));
    assert_eq!(v["model"].as_str(), Some("flowing"));
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.len(), 2);
    assert_eq!(points[0]["torque"].as_f64(), Some(0.0));
    let d0 = points[0]["delta_omega"].as_f64().unwrap();
    let d4 = points[1]["delta_omega"].as_f64().unwrap();
    assert!(
        d0.abs() <= 1e-3 && d0.abs() < 0.01 * d4,
        "unloaded Δω = {d0}"
    );
    assert!(d4 > 0.0, "loaded Δω = {d4}");
    let analytical = v["analytical"].as_array().unwrap();
    assert_eq!(analytical.len(), 2);
    assert!(analytical[1].as_f64().unwrap() > 0.0);
    for f in ["summary.json", "speed_loss.csv", "config.toml"] {
        assert!(out.join(f).exists(), "{f} missing");
    }
    // issue 20, item 5: units in the CSV headers, and why Δω exceeds Bechtel's line
    let bad = flowmbd_cli::output::csv_violations(&out);
    assert!(bad.is_empty(), "columns without unit: {bad:?}");
    let meaning = v["meaning"].as_str().unwrap();
    assert!(
        meaning.contains("Bechtel") && meaning.contains("(6.1)"),
        "{meaning}"
    );
    let _ = std::fs::remove_dir_all(out);
}

// App conventions: `--print-config` output is a complete configuration that reads back to itself.
#[test]
fn printed_configuration_round_trips() {
    for study in ["speed-loss", "ancf", "wave", "plate", "fead"] {
        let (code, printed, stderr) = run(&[study, "--print-config"]);
        assert_eq!(code, 0, "{study}: {stderr}");
        let file = tmp(&format!("{study}.toml"));
        std::fs::write(&file, &printed).unwrap();
        let (code, again, stderr) =
            run(&[study, "--config", file.to_str().unwrap(), "--print-config"]);
        assert_eq!(code, 0, "{study}: {stderr}");
        assert_eq!(printed, again, "{study}");
        let _ = std::fs::remove_file(file);
    }
}

// The shipped examples are valid input for the studies their first line names
// (`flowmbd_cli::testing::examples`): Kerkkänen's §3.3 ones for `ancf`, his §4.6 ones for
// `plate`, the Pechstein–Gerstmayr drive (issue 34) for `fead`, and every study has one.
#[test]
fn shipped_examples_are_valid() {
    let exe = env!("CARGO_BIN_EXE_flowmbd-belt");
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples");
    let examples = flowmbd_cli::testing::examples(&dir);
    for (studies, path) in &examples {
        assert!(!studies.is_empty(), "{}: names no study", path.display());
        for study in studies {
            let (code, _, stderr) =
                run(&[study, "--config", path.to_str().unwrap(), "--print-config"]);
            assert_eq!(code, 0, "{}: {stderr}", path.display());
        }
    }
    assert!(
        examples.len() >= 10,
        "kerkkanen-3-3-a … f, kerkkanen-4-6-model1, -model2, pechstein-gerstmayr, \
         fead-three-pulley, …: {examples:?}"
    );
    let missing = flowmbd_cli::testing::studies_without_example(exe, &dir);
    assert!(
        missing.is_empty(),
        "studies without an example: {missing:?}"
    );
}

// Every shipped example runs, shortened by its own run-length keys (or the study's time option),
// to a complete summary with its `meaning`. Kerkkänen's Model 1 drives an idler, so its summary
// has no driven slip arc and no NaN in its place (the runner refuses non-finite results).
#[test]
fn shipped_examples_run_short() {
    use flowmbd_cli::testing::ExampleRun::{Short, Skip};
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples");
    flowmbd_cli::testing::assert_examples_run(
        env!("CARGO_BIN_EXE_flowmbd-belt"),
        &dir,
        |study, path| {
            if path.parent().is_some_and(|p| p.ends_with("fead")) {
                return Skip; // examples/fead/ runs in fead_examples.rs, with checks of its own
            }
            // (overrides merged into the example, command-line options)
            let (overrides, args): (&'static str, &'static [&'static str]) = match study {
                "ancf" => ("", &["--t-end", "0.004"]),
                "plate" => ("", &["--t-end", "0.002"]),
                "speed-loss" => (
                    "[procedure]\ntorques = [0.0, 1.0]\nspin_up = 0.05\ntorque_ramp = 0.02\n",
                    &[],
                ),
                "wave" => ("[wave]\nt_end = 0.005\nsamples = 20\n", &[]),
                "demo" => ("t_end = 0.05\n", &[]),
                "fead" => (
                    "[run]\nramp = 0.05\nsettle = 0.02\nwindow = 0.02\nmax_settle = 0.04\n",
                    &[],
                ),
                _ => ("", &[]),
            };
            Short { overrides, args }
        },
    );
}

// Bad input: exit 2 with one line naming the field (file and line for TOML errors).
#[test]
fn bad_input_exits_2_naming_the_field() {
    let file = tmp("bad.toml");
    std::fs::write(&file, "history_every = 10\nno_such_field = 1\n").unwrap();
    let (code, _, stderr) = run(&["speed-loss", "--config", file.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(stderr.contains("no_such_field"), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");

    std::fs::write(&file, "history_every = 0\n").unwrap();
    let (code, _, stderr) = run(&["speed-loss", "--config", file.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(stderr.contains("history_every"), "{stderr}");
    let _ = std::fs::remove_file(file);

    let (code, _, _) = run(&["speed-loss", "--torques", "0,abc"]);
    assert_eq!(code, 2);
}

// Issue 18 contract of `flowmbd-belt plate` (Kerkkänen §4.6, Model 2 by default), on a short
// run: the JSON keys, the output files, and the physics that a 5 ms run already fixes — the
// driver still at rest by the ramp (3.29), both spans at the pre-tension (≈ 48.6 N with the
// strain (4.9), 50 N on the undeformed path less the contact penetration), and Bechtel's
// steady model for the final operating point ≈ 15.2 % below the driver (seed note §6.2).
#[test]
fn plate_json_contract() {
    let out = tmp("plate");
    let (code, stdout, stderr) = run(&[
        "plate",
        "--t-end",
        "0.005",
        "--json",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    for key in [
        "omega_driver_end",
        "omega_driven_end",
        "analytical_omega_driven",
        "tension_tight",
        "tension_slack",
        "wall_time_s",
    ] {
        assert!(v[key].is_number(), "{key} missing in {v}");
    }
    assert_eq!(v["omega_driver_end"].as_f64(), Some(0.0));
    let wa = v["analytical_omega_driven"].as_f64().unwrap();
    assert!((wa / 500.0 - 0.848).abs() < 2e-3, "analytical {wa}");
    for key in ["tension_tight", "tension_slack"] {
        let t = v[key].as_f64().unwrap();
        assert!((t - 48.6).abs() < 0.5, "{key} = {t}");
    }
    // the end report every belt model gives (drives::ancf_run::EndReport): its span forces are
    // the membrane forces of the summary (tight, slack), and each hub load is the pull of both
    // spans on a wrap of π, T_tight + T_slack (force balance of the pulley at rest), within 2 %
    let spans = v["spans"].as_array().expect("spans in the plate summary");
    assert_eq!(spans.len(), 2);
    let membrane: Vec<f64> = v["membrane_forces"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let mut report: Vec<f64> = spans
        .iter()
        .map(|s| s["tension_n"].as_f64().unwrap())
        .collect();
    let mut expected = membrane.clone();
    report.sort_by(f64::total_cmp);
    expected.sort_by(f64::total_cmp);
    for (a, b) in report.iter().zip(&expected) {
        assert!(
            (a - b).abs() <= 1e-9 * b.abs(),
            "report {a} N, summary {b} N"
        );
    }
    let pull = membrane[0] + membrane[1];
    for h in v["hub_loads"].as_array().expect("hub loads") {
        let m = h["magnitude_n"].as_f64().unwrap();
        assert!((m - pull).abs() < 0.02 * pull, "hub {m} N vs {pull} N");
    }
    assert_eq!(v["gross_slip"].as_bool(), Some(false));
    for f in [
        "summary.json",
        "config.toml",
        "history.csv",
        "tension.csv",
        "analytical.csv",
        "contact.csv",
        "belt.vtu.series",
        "vtk/belt_0000.vtu",
        "pulley_speeds.png",
        "tension.svg",
        "speed.png",
        "friction_driven.png",
        "normal_driven.png",
        "area_ratio.png",
    ] {
        assert!(out.join(f).exists(), "{f} missing");
    }
    let _ = std::fs::remove_dir_all(&out);
    // the strain measure of the summary's tensions is selectable: the true strain (4.10) of
    // the same state, 1 − 1/λ = 0.1955 against λ − 1 = 0.2430 (Green (4.9))
    let file = tmp("plate-true.toml");
    std::fs::write(&file, "[output]\nstrain_measure = \"true\"\n").unwrap();
    let (code, stdout, stderr) = run(&[
        "plate",
        "--config",
        file.to_str().unwrap(),
        "--t-end",
        "0.001",
        "--json",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let t = v["tension_tight"].as_f64().unwrap();
    assert!((t - 39.1).abs() < 0.5, "true-strain tension {t}");
    let _ = std::fs::remove_dir_all(out);
    let _ = std::fs::remove_file(file);
}

// Bad plate input: exit 2 with one line naming the field.
#[test]
fn bad_plate_input_exits_2_naming_the_field() {
    let file = tmp("bad-plate.toml");
    std::fs::write(&file, "[drive.belt]\nelements = 1\n").unwrap();
    let (code, _, stderr) = run(&["plate", "--config", file.to_str().unwrap()]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("belt.elements"), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    let _ = std::fs::remove_file(file);
}

// Issue 17: gross slip is a result. 38 N m exceeds the Euler–Eytelwein capacity of Table 6-1's
// fixed-centre drive (33.8 N m at 62.8 rad/s): the point is marked, stderr names the pulley and
// the time, the study goes on with the next torque and exits 0; every point carries the
// engineer's keys, and the new CSV files carry units in their headers.
#[test]
fn gross_slip_is_reported_and_the_study_exits_0() {
    let out = tmp("slip");
    let (code, stdout, stderr) = run(&[
        "speed-loss",
        "--omega",
        "62.8",
        "--torques",
        "0,38,10",
        "--json",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stderr.contains("gross slip at pulley 'driven'") && stderr.contains("at t = "),
        "{stderr}"
    );
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.len(), 3);
    let flags: Vec<bool> = points
        .iter()
        .map(|p| p["gross_slip"].as_bool().unwrap())
        .collect();
    assert_eq!(flags, [false, true, false]);
    for key in [
        "tension_tight",
        "tension_slack",
        "gross_slip",
        "slip_arc_driver_rad",
        "slip_arc_driven_rad",
        "hub_loads",
    ] {
        assert!(points.iter().all(|p| p.get(key).is_some()), "{key} missing");
    }
    let last = &points[2];
    assert!(last["tension_tight"].as_f64().unwrap() > last["tension_slack"].as_f64().unwrap());
    assert_eq!(last["hub_loads"].as_array().unwrap().len(), 2);
    assert!(v["cases"][0]["capacity_euler_eytelwein"].as_f64().unwrap() < 38.0);
    for (f, unit) in [
        ("operating_points.csv", "tension_tight_N"),
        ("wrap_omega_62.8.csv", "pressure_N_per_m"),
    ] {
        let text = std::fs::read_to_string(out.join(f)).unwrap();
        assert!(text.lines().next().unwrap().contains(unit), "{f}");
    }
    let _ = std::fs::remove_dir_all(out);
}

// Issue 17 bad input for any layout: overlapping pulleys, a belt too short for the layout, a
// tensioner outside its travel, a wrap below 10°: exit 2 with one line naming the pulley or
// field (the checks: belt::layout, tested on their own in drives/tests/layout.rs).
#[test]
fn fead_bad_layout_exits_2_naming_the_field() {
    use drives::fead::FeadConfig;
    let check = |name: &str, edit: &dyn Fn(&mut FeadConfig), want: &str| {
        let mut c = FeadConfig::default();
        edit(&mut c);
        let file = tmp(&format!("fead_{name}.toml"));
        std::fs::write(&file, toml::to_string(&c).unwrap()).unwrap();
        // an --out of its own: a case that ran would not write into the working directory
        let out = tmp(&format!("fead_{name}_out"));
        let (code, _, stderr) = run(&[
            "fead",
            "--config",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        let _ = std::fs::remove_dir_all(&out);
        assert_eq!(code, 2, "{name}: {stderr}");
        assert!(
            stderr.contains(want) && stderr.trim().lines().count() == 1,
            "{name}: {stderr}"
        );
        let _ = std::fs::remove_file(file);
    };
    // the water pump moved onto the tensioner idler
    check(
        "overlap",
        &|c| c.drive.pulleys[4].center = [0.15, 0.29],
        "drive.pulleys[4]",
    );
    // a belt 1.25 m long on a ≈ 1.52 m path (a mounting strain above 15 % over the whole arm
    // travel)
    check(
        "short",
        &|c| {
            c.drive.tension = None;
            c.drive.belt_length = Some(1.25);
        },
        "drive.belt_length",
    );
    // both the installation tension and the belt length given
    check(
        "both",
        &|c| c.drive.belt_length = Some(1.5),
        "drive.belt_length",
    );
    // a spring that pushes the arm off its travel
    check(
        "travel",
        &|c| c.drive.tensioner.as_mut().unwrap().preload = -200.0,
        "drive.tensioner",
    );
    // the ANCF belt's own fields (model = "ancf"): too few elements, no step
    type Edit = fn(&mut drives::ancf_model::AncfConfig);
    let ancf_edits: [(&str, Edit); 2] = [
        ("models.ancf.elements", |a| a.elements = 2),
        ("models.ancf.step", |a| a.step = 0.0),
    ];
    for (field, edit) in ancf_edits {
        check(
            field,
            &|c| {
                c.model = drives::ModelKind::Ancf;
                edit(&mut c.models.ancf);
            },
            field,
        );
    }
    // the ANCF belt's spectral radius outside [0, 1]
    check(
        "ancf_rho",
        &|c| c.run.ancf_rho_inf = 1.5,
        "run.ancf_rho_inf",
    );
    // the ANCF belt's travel limit negative
    check(
        "ancf_travel",
        &|c| c.run.ancf_max_travel = -0.5,
        "run.ancf_max_travel",
    );
    // the tensioner idler placed to deflect the alternator–water pump span by 2 mm from
    // outside: a wrap of ≈ 2 (2 mm / 85 mm) rad ≈ 3°, below 10°
    check(
        "wrap",
        &|c| {
            c.drive.tensioner = None;
            let others: Vec<belt::Pulley> = [0, 1, 2, 4, 5]
                .iter()
                .map(|&k| c.drive.pulleys[k].clone())
                .collect();
            let span = belt::BeltPath::new(&others).unwrap().spans()[2];
            // the loop runs clockwise: outside is to the left of the travel direction
            let (d, off) = (span.direction, c.drive.pulleys[3].radius - 0.002);
            c.drive.pulleys[3].center = [
                span.start[0] + 0.5 * span.length * d[0] - off * d[1],
                span.start[1] + 0.5 * span.length * d[1] + off * d[0],
            ];
        },
        "drive.pulleys[3]",
    );
}

// `flowmbd-belt fead` with the ANCF belt (issue 17: every model on any layout): the default
// six-pulley drive at 800 rpm without the crank's fluctuation (so that the window is steady)
// writes the same summary and CSV as the flowing model, and the power the crank puts in leaves
// through the accessories: Σ τ_k ω_k over the pulleys (travel-sense contact torques and speeds,
// crank negative) within 2 % of the crank's power (reference: energy balance; what remains is
// sliding and the belt's damping: measured 0.8 %, 0.2 % in the full 0.3 s run). About 10 s.
#[test]
fn fead_runs_the_ancf_belt() {
    use drives::fead::FeadConfig;
    let mut c = FeadConfig {
        model: drives::ModelKind::Ancf,
        ..Default::default()
    };
    c.engine.orders.clear();
    c.run.settle = 0.05;
    c.run.window = 0.05;
    let file = tmp("fead_ancf.toml");
    std::fs::write(&file, toml::to_string(&c).unwrap()).unwrap();
    let out = tmp("fead_ancf");
    let (code, stdout, stderr) = run(&[
        "fead",
        "--config",
        file.to_str().unwrap(),
        "--rpm",
        "800",
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stderr.contains("fead: ancf: 120 elements"), "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(v["model"], "ancf");
    let p = &v["points"][0];
    assert_eq!(p["spans"].as_array().unwrap().len(), 6);
    assert_eq!(p["report"]["pulleys"].as_array().unwrap().len(), 6);
    assert_eq!(p["gross_slip"], false);
    let power: Vec<f64> = p["report"]["pulleys"]
        .as_array()
        .unwrap()
        .iter()
        .map(|q| q["power_w"].as_f64().unwrap())
        .collect();
    let total: f64 = power.iter().sum();
    eprintln!("pulley powers {power:?} W, sum {total} W");
    assert!(total.abs() < 0.02 * power[0].abs(), "{power:?}");
    let csv = std::fs::read_to_string(out.join("fead_sweep.csv")).unwrap();
    assert!(csv.lines().next().unwrap().contains("span0_tension_min_N"));
    let _ = std::fs::remove_file(file);
    let _ = std::fs::remove_dir_all(out);
}

// Issue 39, item 2: a partial configuration is read deeply over the defaults (reference: the
// default configuration with that one number changed, as --print-config prints it), and an
// error deep inside names the key's dotted path and the file line where it stands.
#[test]
fn partial_configs_change_one_number_of_the_default_drive() {
    let dir = tmp("partial");
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("t.toml");
    std::fs::write(&f, "[drive]\ntension = 300.0\n").unwrap();
    let (code, merged, err) = run(&[
        "speed-loss",
        "--config",
        f.to_str().unwrap(),
        "--print-config",
    ]);
    assert_eq!(code, 0, "{err}");
    let (_, default, _) = run(&["speed-loss", "--print-config"]);
    let mut expected: toml::Table = toml::from_str(&default).unwrap();
    expected["drive"]["tension"] = toml::Value::Float(300.0);
    assert_ne!(toml::from_str::<toml::Table>(&default).unwrap(), expected);
    assert_eq!(toml::from_str::<toml::Table>(&merged).unwrap(), expected);
    // a bad value on line 4, inside an array of tables
    std::fs::write(
        &f,
        "omegas = [22.6]\n\n[[drive.pulleys]]\nradius = \"large\"\n",
    )
    .unwrap();
    let (code, _, err) = run(&[
        "speed-loss",
        "--config",
        f.to_str().unwrap(),
        "--print-config",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("t.toml:4:") && err.contains("drive.pulleys[0].radius"),
        "{err}"
    );
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    let _ = std::fs::remove_dir_all(dir);
}

// Issue 39 item 2: every key and table of every study's printed configuration has a comment
// (its meaning, from the rustdoc of the configuration types) and every floating-point key's
// comment states its unit in brackets (`flowmbd_cli::commented`).
#[test]
fn printed_configurations_are_commented() {
    flowmbd_cli::testing::assert_printed_configs_commented(env!("CARGO_BIN_EXE_flowmbd-belt"));
}
