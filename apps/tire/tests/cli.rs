//! End-to-end tests of the `flowmbd-tire` binary (issue 9, app conventions of DEVELOPERS.md):
//! every subcommand (`modes`, `reduce`, `cleat`, `sweep`, `pressure`, `rotating-modes`) on a small generated tire
//! given through `--config`, the embedded defaults against the issue text, the JSON contract of
//! `cleat --speed 60 --json`, the output files, and the exit codes (2 for bad input naming the
//! field, 1 for a numerical failure with the results so far kept).

use crate::common;
use common::*;
use serde_json::Value;
use std::path::Path;

const STUDIES: [&str; 5] = ["modes", "reduce", "cleat", "sweep", "pressure"];

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("{v} is not a number"))
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(f).collect()
}

fn toml_f(v: &toml::Value, path: &str) -> f64 {
    let mut x = v;
    for k in path.split('.') {
        x = x
            .get(k)
            .unwrap_or_else(|| panic!("no `{path}` in the printed configuration"));
    }
    x.as_float()
        .or_else(|| x.as_integer().map(|i| i as f64))
        .unwrap_or_else(|| panic!("`{path}` = {x} is not a number"))
}

fn mtime(p: &Path) -> std::time::SystemTime {
    std::fs::metadata(p).unwrap().modified().unwrap()
}

/// `--print-config` prints TOML that parses back through `--config` to the same text, and the
/// embedded defaults are the case of issue 9 (its text: "295/80 R22.5", "inflated to 38 psi",
/// "1000 lb = 4448 N", "95 by default", "50 kept by default", "a drum (radius 1.25 m)",
/// "semicircular cleat (radius 10 mm)", "mu = 0.85", "the 5th and 12th by default",
/// "speed sweep 20-100 km/h in steps of 10").
#[test]
fn print_config_round_trips_and_defaults_are_the_issue_case() {
    let dir = tmp("print");
    let mut tire_section = None;
    for study in STUDIES {
        let (code, text, err) = outcome(&run(&[study, "--print-config"]));
        assert_eq!(code, 0, "{study}: {err}");
        let v: toml::Value = toml::from_str(&text)
            .unwrap_or_else(|e| panic!("{study} --print-config is not TOML: {e}"));
        // round trip: the printed defaults given back as a file print the same configuration
        let file = dir.join(format!("{study}.toml"));
        std::fs::write(&file, &text).unwrap();
        let (code, again, err) = outcome(&run(&[
            study,
            "--print-config",
            "--config",
            file.to_str().unwrap(),
        ]));
        assert_eq!(code, 0, "{study} round trip: {err}");
        assert_eq!(again, text, "{study}: print → --config → print differs");
        // every study shares the same tire
        let tire = v.get("tire").expect("[tire]").clone();
        match &tire_section {
            None => tire_section = Some(tire),
            Some(t) => assert_eq!(&tire, t, "{study}: [tire] differs between studies"),
        }
    }
    let (_, text, _) = outcome(&run(&["cleat", "--print-config"]));
    let v: toml::Value = toml::from_str(&text).unwrap();
    let g = |p: &str| toml_f(&v, p);
    // 295/80 R22.5: section width 295 mm, rim 22.5 in, aspect ratio 0.80
    assert!((g("tire.generator.width") - 0.295).abs() < 1e-9);
    assert!((g("tire.generator.rim_diameter") - 22.5 * 0.0254).abs() < 1e-9);
    let outer = 22.5 * 0.0254 + 2.0 * 0.80 * 0.295;
    assert!(
        (g("tire.generator.outer_diameter") - outer).abs() < 1e-3,
        "outer diameter {} vs 295/80 R22.5 {outer}",
        g("tire.generator.outer_diameter")
    );
    // 38 psi = 38 × 6894.757 Pa
    let psi38 = 38.0 * 6894.757;
    assert!((g("tire.generator.inflation_pressure") - psi38).abs() < 1e-4 * psi38);
    assert_eq!(g("tire.reduction.contact_nodes"), 95.0);
    assert_eq!(g("tire.reduction.free_modes"), 50.0);
    // 1000 lb = 4448.22 N
    assert!((g("rig.load") - 4448.22).abs() < 0.1);
    assert_eq!(g("rig.ground.drum_radius"), 1.25);
    assert_eq!(g("rig.ground.cleat_radius"), 0.010);
    assert_eq!(v["rig"]["ground"]["kind"].as_str(), Some("drum"));
    assert_eq!(v["rig"]["ground"]["cleat"].as_bool(), Some(true));
    assert_eq!(g("rig.rolling.friction"), 0.85);
    assert_eq!(g("rig.damping.mode1"), 5.0);
    assert_eq!(g("rig.damping.mode2"), 12.0);
    assert_eq!(g("rig.speed_kmh"), 60.0);
    let (_, text, _) = outcome(&run(&["sweep", "--print-config"]));
    let v: toml::Value = toml::from_str(&text).unwrap();
    let speeds: Vec<f64> = v["speeds_kmh"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_float().unwrap())
        .collect();
    assert_eq!(
        speeds,
        (2..=10).map(|k| 10.0 * k as f64).collect::<Vec<_>>()
    );
    let (_, text, _) = outcome(&run(&["pressure", "--print-config"]));
    let v: toml::Value = toml::from_str(&text).unwrap();
    assert!((toml_f(&v, "load") - 4448.22).abs() < 0.1);
    assert_eq!(toml_f(&v, "drum_radius"), 1.25);
    // command-line flags are applied on top of the file before printing
    let (code, text, _) = outcome(&run(&[
        "cleat",
        "--print-config",
        "--speed",
        "80",
        "--friction",
        "0",
    ]));
    assert_eq!(code, 0);
    let v: toml::Value = toml::from_str(&text).unwrap();
    assert_eq!(toml_f(&v, "rig.speed_kmh"), 80.0);
    assert_eq!(toml_f(&v, "rig.rolling.friction"), 0.0);
    std::fs::remove_dir_all(&dir).ok();
}

/// `reduce` writes the reduced tire (6 + 3 n_c + n_f DOF, Ribaric §8.2) and `modes` reuses it
/// (no second reduction: the file's mtime is unchanged and no "reducing" message), with the
/// truncated model's frequencies below 240 Hz within 2 % of the full FE model (issue 9).
#[test]
fn reduce_writes_the_file_and_modes_reuses_it() {
    let (file, s) = shared_reduced();
    // the coarse tire: (section + 1) × (thickness + 1) nodes per cross-section, 3 DOF each
    assert_eq!(f(&s["fe_dof"]), (3 * CIRC * (SECTION + 1) * 2) as f64);
    assert_eq!(f(&s["dof"]), (6 + 3 * CONTACT + MODES) as f64);
    assert_eq!(f(&s["contact_nodes"]), CONTACT as f64);
    assert_eq!(f(&s["free_modes"]), MODES as f64);
    assert_eq!(s["file"].as_str(), Some(file.to_str().unwrap()));
    let t = &s["timings"];
    // the free-node modes and the static modes are computed side by side (rayon::join in
    // reduction::sparse::craig_bampton_modes), the derivatives after both: each of the two with
    // the derivatives fits in the total, their sum need not (it exceeded it by 1 % once)
    for stage in ["modes_s", "static_modes_s"] {
        let parts = f(&t[stage]) + f(&t["derivatives_s"]);
        assert!(parts <= f(&t["total_s"]) + 1e-9, "{stage}: stage times {t}");
    }

    let dir = tmp("modes");
    let before = mtime(file);
    let cfg = config(&dir, "modes.toml", "count = 30", file, "");
    let out = run_study("modes", &["--json"], &cfg, &dir.join("m"));
    let m = json_of(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !stderr.contains("reducing"),
        "modes reduced again: {stderr}"
    );
    assert_eq!(mtime(file), before, "the reduced file was rewritten");
    let (full, red) = (floats(&m["full_hz"]), floats(&m["reduced_hz"]));
    assert_eq!(full.len(), 30);
    assert_eq!(red.len(), 30);
    assert!(full.windows(2).all(|w| w[0] <= w[1]), "ascending {full:?}");
    // loaded-tire modes in a realistic range (issue 9: "tens of Hz")
    assert!(
        full[0] > 10.0 && full[0] < 100.0,
        "lowest mode {} Hz",
        full[0]
    );
    let err = full
        .iter()
        .zip(&red)
        .filter(|(a, _)| **a < 240.0)
        .map(|(a, b)| (b - a).abs() / a)
        .fold(0.0, f64::max);
    assert!(err < 0.02, "truncated model off by {err}");
    assert!((f(&m["max_rel_error_below_240hz"]) - err).abs() < 1e-12);
    // Rayleigh–Ritz: the reduced model's frequencies bound the full model's from above
    assert!(full.iter().zip(&red).all(|(a, b)| *b >= *a * (1.0 - 1e-9)));
    // the CSV table holds the same frequencies (10 significant digits)
    let rows = csv_column(&dir.join("m/modes.csv"), "full_Hz");
    assert_eq!(rows.len(), full.len());
    assert!(
        rows.iter()
            .zip(&full)
            .all(|(a, b)| (a - b).abs() < 1e-9 * b)
    );
    assert_plot(&dir.join("m"), "modes");
    assert!(flowmbd_cli::output::csv_violations(&dir.join("m")).is_empty());
    std::fs::remove_dir_all(&dir).ok();
}

/// `cleat --speed 60 --json` prints the keys of issue 9 with sane values and writes the summary,
/// histories, spectra, plots and the VTK series; it reuses the reduced file.
#[test]
fn cleat_json_contract_and_outputs() {
    let (file, red) = shared_reduced();
    let dir = tmp("cleat");
    let before = mtime(file);
    // the default rig (60 km/h on the drum, μ = 0.85, 0.4 s + 0.3 s at h = 0.2 ms: 3500 steps)
    // with a sparse VTK series
    let cfg = config(
        &dir,
        "cleat.toml",
        "vtk_interval = 0.1\nvtk_tire_interval = 0.2",
        file,
        "",
    );
    let out_dir = dir.join("c");
    let out = run_study("cleat", &["--speed", "60", "--json"], &cfg, &out_dir);
    let s = json_of(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !stderr.contains("reducing"),
        "cleat reduced again: {stderr}"
    );
    assert_eq!(mtime(file), before, "the reduced file was rewritten");
    for key in [
        "speed_kmh",
        "dof",
        "fy_peak_hz",
        "fx_peak_hz",
        "fy_rms",
        "fx_rms",
        "wall_time_s",
    ] {
        assert!(s.get(key).is_some_and(Value::is_number), "key {key}: {s}");
    }
    assert_eq!(f(&s["speed_kmh"]), 60.0);
    // Ribaric §8.2: 6 wheel DOF + 3 per contact node + the free-node modes
    assert_eq!(f(&s["dof"]), (6 + 3 * CONTACT + MODES) as f64);
    assert_eq!(s["dof"], red["dof"]);
    assert!(f(&s["wall_time_s"]) > 0.0 && f(&s["wall_time_s"]).is_finite());
    assert!(f(&s["fy_rms"]) > 0.0 && f(&s["fx_rms"]) > 0.0);
    // the cleat's force fluctuation stays below a few times the preload
    assert!(f(&s["fy_rms"]) < 3.0 * f(&s["load_n"]), "{s}");
    let steps = 3500;
    assert_eq!(f(&s["steps"]), steps as f64);

    // the dominant vertical spindle frequency is a natural frequency of the tire printed by
    // `modes` (issue 9 validation), within the spectral resolution 1/T of the 0.3 s record (the
    // longitudinal peak is not checked: the patch's friction constraint shifts the fore-aft
    // modes of the rolling tire away from the rim-fixed ones printed by `modes`)
    let mcfg = config(&dir, "modes.toml", "count = 40", file, "");
    let m = json_of(&run_study(
        "modes",
        &["--quiet", "--json"],
        &mcfg,
        &dir.join("m"),
    ));
    let full = floats(&m["full_hz"]);
    let res = 1.0 / 0.3;
    let pk = f(&s["fy_peak_hz"]);
    let near = full.iter().map(|x| (x - pk).abs()).fold(f64::MAX, f64::min);
    assert!(
        near <= res,
        "fy_peak_hz = {pk} Hz is {near} Hz from the nearest mode of {full:?}"
    );
    let fx_pk = f(&s["fx_peak_hz"]);
    assert!((10.0..=500.0).contains(&fx_pk), "fx_peak_hz = {fx_pk}");
    // issue 21: each line names the loaded mode at the rolling speed that carries it, a mode
    // within the line's half-power band (3 % damping: ±3 % of its frequency, plus the
    // spectral resolution)
    for (line, key) in [
        ("fx_peak_hz", "fx_line_mode"),
        ("fy_peak_hz", "fy_line_mode"),
    ] {
        let m = &s[key];
        assert_eq!(f(&m["line_hz"]), f(&s[line]), "{key}: {m}");
        let (hz, share) = (f(&m["hz"]), f(&m["share"]));
        assert!((hz - f(&s[line])).abs() <= 0.1 * hz + res, "{key}: {m}");
        assert!(share > 0.3 && share <= 1.0, "{key}: {m}");
    }

    // summary.json is what --json printed (plus the runner's "complete", "status" and
    // "outputs", issue 35); config.toml is the effective configuration
    let mut saved: Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(saved["complete"], true);
    for runner in ["complete", "status", "outputs"] {
        saved.as_object_mut().unwrap().remove(runner);
    }
    assert_eq!(saved, s);
    let effective: toml::Value =
        toml::from_str(&std::fs::read_to_string(out_dir.join("config.toml")).unwrap()).unwrap();
    assert_eq!(toml_f(&effective, "tire.reduction.contact_nodes"), 33.0);
    assert_eq!(toml_f(&effective, "rig.speed_kmh"), 60.0);

    // histories: one row per step, the time axis at h = 0.2 ms ending at the record time
    let t = csv_column(&out_dir.join("forces.csv"), "t_s");
    assert_eq!(t.len(), steps);
    assert!((t[steps - 1] - 0.3).abs() < 1e-9, "last t {}", t[steps - 1]);
    assert!(t.windows(2).all(|w| (w[1] - w[0] - 2e-4).abs() < 1e-9));
    let fy = csv_column(&out_dir.join("forces.csv"), "fy_N");
    assert!(fy.iter().all(|x| x.is_finite()));
    let fr = csv_column(&out_dir.join("spectra.csv"), "f_Hz");
    let amp = csv_column(&out_dir.join("spectra.csv"), "fy_amp_N");
    // the printed peak is the largest spectral line in 10–500 Hz, interpolated between the
    // bins: within half a bin of the largest bin, the bin spacing printed as the resolution
    // (issue 39 item 3)
    let (k, _) = fr
        .iter()
        .zip(&amp)
        .enumerate()
        .filter(|(_, (fq, _))| **fq >= 10.0 && **fq <= 500.0)
        .fold(
            (0, f64::MIN),
            |b, (i, (_, a))| if *a > b.1 { (i, *a) } else { b },
        );
    let df = f(&s["peak_resolution_hz"]);
    assert!((df - (fr[1] - fr[0])).abs() < 1e-9 * df, "{df}");
    assert!((fr[k] - f(&s["fy_peak_hz"])).abs() <= 0.5 * df + 1e-9);
    for stem in ["forces", "spectra"] {
        assert_plot(&out_dir, stem);
    }

    // VTK series: patch every 0.1 s, whole tire every 0.2 s of simulated time (from the first
    // step: as many frames as every 500 and 1000 steps of 0.2 ms)
    let vtk = out_dir.join("vtk");
    let count = |prefix: &str| {
        std::fs::read_dir(&vtk)
            .unwrap()
            .filter(|e| {
                e.as_ref()
                    .unwrap()
                    .file_name()
                    .to_string_lossy()
                    .starts_with(prefix)
            })
            .count()
    };
    assert_eq!(count("patch_"), steps.div_ceil(500));
    assert_eq!(count("tire_"), steps.div_ceil(1000));
    // the ParaView index lists every frame written (flowmbd_cli::VtkSeries)
    let index: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("patch.vtu.series")).unwrap())
            .unwrap();
    assert_eq!(index["files"].as_array().unwrap().len(), count("patch_"));
    let patch = std::fs::read_to_string(vtk.join("patch_0000.vtu")).unwrap();
    assert!(patch.contains("<VTKFile") && patch.contains("normal_force_N"));
    assert!(
        patch.contains(&format!("NumberOfPoints=\"{CONTACT}\"")),
        "one VTK point per contact node"
    );
    let tire = std::fs::read_to_string(vtk.join("tire_0003.vtu")).unwrap();
    assert!(tire.contains("<VTKFile") && tire.contains("displacement_m"));
    // issue 20, item 5 and issue 39, item 3: one unit convention in every CSV header, integer
    // columns written as integers (the active contact nodes: `3`, not `3.0000000000e0`), and
    // what the numbers mean
    let bad = flowmbd_cli::output::csv_violations(&out_dir);
    assert!(bad.is_empty(), "outside the CSV convention: {bad:?}");
    let forces = std::fs::read_to_string(out_dir.join("forces.csv")).unwrap();
    let mut lines = forces.lines();
    assert_eq!(
        lines.next(),
        Some(tire::study::FORCE_COLUMNS.join(",").as_str())
    );
    let active: Vec<&str> = lines.map(|l| l.split(',').nth(5).unwrap()).collect();
    assert!(
        active.iter().all(|c| c.parse::<u64>().is_ok()),
        "{:?}",
        &active[..5]
    );
    assert!(
        active.iter().any(|c| *c != "0"),
        "the tire touches the ground"
    );
    assert!(s["meaning"].as_str().unwrap().contains("cleat"));
    std::fs::remove_dir_all(&dir).ok();
}

/// Steady rolling before the cleat carries the load (issue 9: "the vertical force equals the
/// load"): with frictionless contact the mean vertical spindle force before the cleat equals the
/// configured preload within 1 %, both in the summary and recomputed from `forces.csv`.
#[test]
fn cleat_spindle_force_before_the_cleat_equals_the_load() {
    let (file, _) = shared_reduced();
    let dir = tmp("load");
    let cfg = config(
        &dir,
        "c.toml",
        "vtk_interval = 0\nvtk_tire_interval = 0",
        file,
        "",
    );
    let out_dir = dir.join("c");
    let s = json_of(&run_study(
        "cleat",
        &["--quiet", "--json", "--friction", "0"],
        &cfg,
        &out_dir,
    ));
    let load = f(&s["load_n"]);
    assert!((load - 4448.2).abs() < 1e-9);
    let before = f(&s["fy_mean_before_n"]);
    assert!(
        (before - load).abs() < 0.01 * load,
        "mean Fy before the cleat {before} N vs load {load} N"
    );
    // independent of the summary: the history between 150 ms and 50 ms before the hit (the
    // cleat enters the 33-node patch about 5 ms before t = 0 at 60 km/h)
    let t = csv_column(&out_dir.join("forces.csv"), "t_s");
    let fy = csv_column(&out_dir.join("forces.csv"), "fy_N");
    let w: Vec<f64> = t
        .iter()
        .zip(&fy)
        .filter(|(t, _)| **t > -0.15 && **t < -0.05)
        .map(|(_, y)| *y)
        .collect();
    let mean = w.iter().sum::<f64>() / w.len() as f64;
    assert!(w.len() > 400);
    assert!(
        (mean - load).abs() < 0.01 * load,
        "history mean {mean} N vs load {load} N"
    );
    assert!(
        !out_dir.join("vtk").exists(),
        "VTK series written although disabled"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// `sweep` over three speeds writes the contour/waterfall maps (Ribaric Figs. 8-7, 8-8) and the
/// per-speed files, and each speed of the sweep is the single `cleat` run at that speed (a second
/// path through the app: same summary values, same spectrum row in the speed × frequency matrix).
#[test]
fn sweep_writes_the_maps_and_agrees_with_single_runs() {
    let (file, _) = shared_reduced();
    let dir = tmp("sweep");
    let speeds = [40.0, 60.0, 80.0];
    let cfg = config(&dir, "s.toml", "speeds_kmh = [40.0, 60.0, 80.0]", file, "");
    let sw = dir.join("sw");
    let s = json_of(&run_study("sweep", &["--quiet", "--json"], &cfg, &sw));
    let runs = s["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 3);
    for (r, v) in runs.iter().zip(speeds) {
        assert_eq!(f(&r["speed_kmh"]), v);
    }
    assert_eq!(floats(&s["fy_peak_amplitude_n"]).len(), 3);
    for name in ["fy", "fx"] {
        for kind in ["contour", "waterfall"] {
            assert_plot(&sw, &format!("{name}_map_{kind}"));
        }
        assert!(sw.join(format!("{name}_matrix.csv")).is_file());
    }
    assert_plot(&sw, "peak_vs_speed");
    assert!(sw.join("waterfall.csv").is_file());
    for v in ["v040", "v060", "v080"] {
        for file in ["forces.csv", "spectra.csv"] {
            assert!(sw.join(format!("{v}_{file}")).is_file(), "{v}_{file}");
        }
        assert_plot(&sw, &format!("{v}_forces"));
    }
    let speed_col = csv_column(&sw.join("fy_matrix.csv"), "speed_km_per_h");
    assert_eq!(speed_col, speeds);

    // the single run at 60 km/h
    let ccfg = config(
        &dir,
        "c.toml",
        "vtk_interval = 0\nvtk_tire_interval = 0",
        file,
        "",
    );
    let c = json_of(&run_study(
        "cleat",
        &["--quiet", "--json", "--speed", "60"],
        &ccfg,
        &dir.join("c"),
    ));
    let r60 = &runs[1];
    for key in ["dof", "steps"] {
        assert_eq!(r60[key], c[key], "{key}");
    }
    for key in [
        "fy_peak_hz",
        "fx_peak_hz",
        "fy_rms",
        "fx_rms",
        "fy_mean_before_n",
    ] {
        let (a, b) = (f(&r60[key]), f(&c[key]));
        assert!(
            (a - b).abs() <= 1e-6 * b.abs().max(1.0),
            "{key}: {a} vs {b}"
        );
    }
    // the history `cleat` streams while it runs is the one `sweep` writes from the finished
    // run's samples, row for row
    assert_eq!(
        std::fs::read_to_string(dir.join("c/forces.csv")).unwrap(),
        std::fs::read_to_string(sw.join("v060_forces.csv")).unwrap()
    );
    // the 60 km/h row of the matrix is the single run's spectrum up to 300 Hz
    let fr = csv_column(&dir.join("c/spectra.csv"), "f_Hz");
    let amp = csv_column(&dir.join("c/spectra.csv"), "fy_amp_N");
    let text = std::fs::read_to_string(sw.join("fy_matrix.csv")).unwrap();
    let row: Vec<f64> = text
        .lines()
        .nth(2)
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(row[0], 60.0);
    let n = fr.iter().filter(|x| **x <= 300.0).count();
    assert_eq!(row.len(), 1 + n);
    for k in 0..n {
        assert!(
            (row[1 + k] - amp[k]).abs() <= 1e-6 * amp[k].abs().max(1.0),
            "{} Hz: {} vs {}",
            fr[k],
            row[1 + k],
            amp[k]
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `pressure`: the preloaded patch on the drum and on the flat road (Ribaric Fig. 8-12); the
/// contact-node forces carry the load (static equilibrium of the preload) and the convex drum
/// needs at least the road's deflection for the same load.
#[test]
fn pressure_patch_forces_carry_the_load() {
    let (file, _) = shared_reduced();
    let dir = tmp("pressure");
    let cfg = config(&dir, "p.toml", "load = 4448.2", file, "");
    let out = dir.join("p");
    let s = json_of(&run_study("pressure", &["--quiet", "--json"], &cfg, &out));
    for g in ["drum", "road"] {
        let force = csv_column(&out.join(format!("patch_{g}.csv")), "force_N");
        assert_eq!(force.len(), CONTACT);
        assert!(force.iter().all(|x| *x >= 0.0), "{g}: tension in the patch");
        let total: f64 = force.iter().sum();
        assert!(
            (total - 4448.2).abs() < 0.02 * 4448.2,
            "{g}: patch force {total} N vs load"
        );
        let p = &s[g];
        assert_eq!(
            f(&p["nodes_in_contact"]) as usize,
            force.iter().filter(|x| **x > 0.0).count()
        );
        assert!(f(&p["deflection_m"]) > 0.0 && f(&p["deflection_m"]) < 0.05);
    }
    assert!(f(&s["drum"]["deflection_m"]) >= f(&s["road"]["deflection_m"]));
    assert!(f(&s["drum"]["length_m"]) <= f(&s["road"]["length_m"]) + 1e-12);
    // the meaning compares this run's numbers (issue 39 item 3), not Ribaric's statement
    let (dd, dr) = (f(&s["drum"]["deflection_m"]), f(&s["road"]["deflection_m"]));
    let m = s["meaning"].as_str().unwrap();
    let said = format!("{:.2} mm against {:.2} mm on the road", 1e3 * dd, 1e3 * dr);
    assert!(m.contains("under 4448 N") && m.contains(&said), "{m}");
    let word = if dd > dr { "a larger" } else { "the same" };
    assert!(
        m.contains(&format!("the drum needs {word} deflection")),
        "{m}"
    );
    assert_plot(&out, "patch_forces");
    assert!(flowmbd_cli::output::csv_violations(&out).is_empty());
    std::fs::remove_dir_all(&dir).ok();
}

/// Bad input: exit code 2 and one line on stderr naming the field (and the file line for TOML
/// errors); nothing is computed and the reduced file is left alone.
#[test]
fn bad_input_exits_2_naming_the_field() {
    let (file, _) = shared_reduced();
    let dir = tmp("bad");
    let before = mtime(file);
    // the misspelt key's line: after the tire tables and `[rig]`
    let typo_line = format!(":{}:", tire_tables(file).lines().count() + 2);
    let cases: Vec<(&str, Vec<String>, String, &str)> = vec![
        // (study, extra args, config text, expected text in the message)
        (
            "cleat",
            vec![],
            format!("{}[rig]\nsped_kmh = 60.0\n", tire_tables(file)),
            "sped_kmh",
        ),
        (
            "cleat",
            vec![],
            format!("{}[rig]\nsped_kmh = 60.0\n", tire_tables(file)),
            &typo_line,
        ),
        ("cleat", vec![], "[tire\nfree_modes = 3\n".into(), ":1:"),
        (
            "cleat",
            vec!["--speed=-10".into()],
            tire_tables(file),
            "rig.speed_kmh",
        ),
        (
            "cleat",
            vec!["--time-step=0".into()],
            tire_tables(file),
            "rig.rolling.time_step",
        ),
        (
            "cleat",
            vec!["--time-step=0.5".into()],
            tire_tables(file),
            "rig.rolling.time_step",
        ),
        (
            "cleat",
            vec!["--friction=-0.1".into()],
            tire_tables(file),
            "rig.rolling.friction",
        ),
        (
            "cleat",
            vec!["--substeps=0".into()],
            tire_tables(file),
            "rig.impact.substeps",
        ),
        (
            "cleat",
            vec![],
            format!("{}[rig.damping]\nmode2 = 500\n", tire_tables(file)),
            "rig.damping.mode2",
        ),
        (
            "cleat",
            vec!["--phases=0".into()],
            tire_tables(file),
            "cleat_phases",
        ),
        (
            "sweep",
            vec![],
            format!("speeds_kmh = [20.0, -30.0]\n{}", tire_tables(file)),
            "speeds_kmh[1]",
        ),
        (
            "pressure",
            vec![],
            format!("load = -1.0\n{}", tire_tables(file)),
            "load",
        ),
        // the reduced file holds 33 contact nodes, the configuration asks for 30
        (
            "cleat",
            vec![],
            tire_tables(file).replace("contact_nodes = 33", "contact_nodes = 30"),
            "tire.reduced_file",
        ),
        // the reduced file was made from another tire (its fingerprint records the generator)
        (
            "cleat",
            vec![],
            tire_tables(file).replace("young = 150e6", "young = 120e6"),
            "another tire model",
        ),
        // a reduced file that is not one (a folder)
        ("modes", vec![], tire_tables(&dir), "tire.reduced_file"),
        // an imported tire whose matrix file is missing
        (
            "reduce",
            vec![],
            format!(
                "{}[tire.import]\nstiffness = \"{}/none.mtx\"\nmass = \"m.mtx\"\n\
                 nodes = \"n.txt\"\nrim_nodes = \"r.txt\"\npatch_nodes = \"p.txt\"\n",
                tire_tables(file),
                dir.display()
            ),
            "tire.import.stiffness",
        ),
    ];
    for (i, (study, extra, text, want)) in cases.iter().enumerate() {
        let cfg = dir.join(format!("bad{i}.toml"));
        std::fs::write(&cfg, text).unwrap();
        let mut args = vec![
            study.to_string(),
            "--quiet".into(),
            "--config".into(),
            cfg.display().to_string(),
            "--out".into(),
            dir.join(format!("o{i}")).display().to_string(),
        ];
        args.extend(extra.iter().cloned());
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (code, _, err) = outcome(&run(&args));
        assert_eq!(code, 2, "case {i} ({study} {extra:?}): exit {code}: {err}");
        assert_eq!(
            err.trim_end().lines().count(),
            1,
            "case {i}: one line: {err}"
        );
        assert!(err.contains(want), "case {i}: `{want}` not named in: {err}");
        assert!(!err.contains("panicked"), "case {i}: {err}");
    }
    assert_eq!(mtime(file), before, "bad input touched the reduced file");
    std::fs::remove_dir_all(&dir).ok();
}

/// A numerical failure exits 1 and keeps the results so far: Newmark β = 0.01 < γ/2 is only
/// conditionally stable (stable for ω h ≤ 1/√(γ/2 − β) ≈ 2.0), and the default step h = 0.2 ms
/// is far beyond that limit for the 6.4 kHz contact-node modes, so the run diverges within a few
/// dozen steps; the default β = 1/4 (unconditionally stable trapezoidal rule) runs the same
/// configuration (the other tests). The streamed force history up to the failure stays on disk
/// and `summary.json` says what failed and how far the run got.
#[test]
fn numerical_failure_exits_1_and_keeps_the_history() {
    let (file, _) = shared_reduced();
    let dir = tmp("diverge");
    let cfg = config(
        &dir,
        "d.toml",
        "vtk_interval = 0\nvtk_tire_interval = 0",
        file,
        "[rig.rolling]\nnewmark_beta = 0.01\n",
    );
    let out = dir.join("d");
    let (code, stdout, err) = outcome(&run_study("cleat", &["--quiet", "--json"], &cfg, &out));
    assert_eq!(code, 1, "{err}");
    assert!(stdout.is_empty(), "no summary printed on failure: {stdout}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    assert!(
        err.contains("t = ") && err.contains("results so far"),
        "{err}"
    );
    let s: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["status"].as_str(), Some("failed"));
    let done = f(&s["partial"]["steps_done"]) as usize;
    assert!(done > 0 && done < 3500, "steps done {done}");
    let t = csv_column(&out.join("forces.csv"), "t_s");
    assert_eq!(t.len(), done, "history rows up to the failure");
    assert!((t[done - 1] - f(&s["partial"]["t_last_s"])).abs() < 1e-12);
    // the history starts like a healthy run's: the preload at the first step
    let fy = csv_column(&out.join("forces.csv"), "fy_N");
    assert!((fy[0] - 4448.2).abs() < 0.05 * 4448.2, "first Fy {}", fy[0]);
    // the sweep fails the same way at its first speed: exit 1, the speed named, no run kept
    let cfg = config(
        &dir,
        "s.toml",
        "speeds_kmh = [40.0, 60.0]",
        file,
        "[rig.rolling]\nnewmark_beta = 0.01\n",
    );
    let sw = dir.join("s");
    let (code, _, err) = outcome(&run_study("sweep", &["--quiet"], &cfg, &sw));
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("at 40 km/h"), "{err}");
    let s: Value =
        serde_json::from_str(&std::fs::read_to_string(sw.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["status"].as_str(), Some("failed"));
    assert_eq!(s["partial"].as_array().map(Vec::len), Some(0));
    std::fs::remove_dir_all(&dir).ok();
}

/// A reduced-tire file that does not exist yet is made by the study that needs it (reduce once,
/// then reuse): the first `cleat` run reduces and saves, the second loads it unchanged and gives
/// the same answer.
#[test]
fn missing_reduced_file_is_reduced_once_then_reused() {
    let dir = tmp("fresh");
    let file = dir.join("sub/reduced.json");
    let cfg = config(
        &dir,
        "c.toml",
        "vtk_interval = 0\nvtk_tire_interval = 0",
        &file,
        "[rig]\nsettle_time = 0.05\nrecord_time = 0.05\n",
    );
    let out_dir = dir.join("c");
    let args = [
        "cleat",
        "--json",
        "--config",
        cfg.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
    ];
    let first = run(&args);
    let a = json_of(&first);
    let err = String::from_utf8_lossy(&first.stderr);
    assert!(err.contains("reducing the generated tire"), "{err}");
    assert!(file.is_file());
    let t0 = mtime(&file);
    let second = run(&args);
    let b = json_of(&second);
    assert!(!String::from_utf8_lossy(&second.stderr).contains("reducing"));
    assert_eq!(mtime(&file), t0);
    assert_eq!(a["dof"], b["dof"]);
    assert!((f(&a["fy_rms"]) - f(&b["fy_rms"])).abs() <= 1e-9 * f(&a["fy_rms"]));
    std::fs::remove_dir_all(&dir).ok();
}

/// `rotating-modes --speeds 0,60,120 --json` (issue 21, "checked by"): for each speed labelled
/// modes `{hz, n, direction, damping_ratio}`; zero speed equals `modes` (reduced); the
/// forward/backward split of each in-plane order n = 1..4 grows with speed (linearly: the split
/// at 120 km/h is twice that at 60 within 10 %); Campbell plots and the CSV are written.
#[test]
fn rotating_modes_json_contract_and_split() {
    let (file, _) = shared_reduced();
    let dir = tmp("rotating");
    let cfg = config(&dir, "rm.toml", "", file, "");
    let out_dir = dir.join("r");
    let s = json_of(&run_study(
        "rotating-modes",
        &["--speeds", "0,60,120", "--json"],
        &cfg,
        &out_dir,
    ));
    let speeds = s["speeds"].as_array().unwrap();
    assert_eq!(speeds.len(), 3);
    for (sp, v) in speeds.iter().zip([0.0, 60.0, 120.0]) {
        assert_eq!(f(&sp["speed_kmh"]), v);
        for case in ["free", "loaded"] {
            let modes = sp[case].as_array().unwrap();
            assert!(modes.len() > 10, "{case} at {v} km/h: {modes:?}");
            for m in modes {
                assert!(f(&m["hz"]) > 0.0 && m["n"].is_u64(), "{m}");
                let d = m["direction"].as_str().unwrap();
                assert!(["forward", "backward", "standing"].contains(&d), "{m}");
                assert!(f(&m["damping_ratio"]) > 0.0, "rig damping: {m}");
                if v == 0.0 {
                    assert_eq!(d, "standing");
                }
            }
        }
    }
    assert!(f(&s["zero_speed_max_rel_diff_vs_modes"]) < 1e-6, "{s}");
    let splits = s["splits"].as_array().unwrap();
    for n in 1..=4u64 {
        let sp = splits
            .iter()
            .find(|x| x["n"] == n && x["plane"] == "in_plane")
            .unwrap_or_else(|| panic!("no in-plane n = {n}: {splits:?}"));
        let d = floats(&sp["split_hz"]);
        assert_eq!(d[0], 0.0);
        assert!(d[1] > 0.0 && d[2] > d[1], "n = {n}: {d:?}");
        assert!((d[2] / d[1] - 2.0).abs() < 0.2, "n = {n}: {d:?}");
    }
    assert_plot(&out_dir, "campbell_free");
    assert_plot(&out_dir, "campbell_loaded");
    assert!(!csv_column(&out_dir.join("rotating_modes.csv"), "f_Hz").is_empty());
    assert!(flowmbd_cli::output::csv_violations(&out_dir).is_empty());
}

/// `dips --no-sweep --json` (issue 21 item 4): per ground the enveloping length lies within
/// the contact nodes' extent widened by the cleat (the cleat acts only through contact nodes)
/// and near the undeformed tire's geometric stretch; the road's is the longer (Ribaric §8.5);
/// the predicted dips are local minima of `prediction_<ground>.csv`; a negative profile step
/// is refused with exit 2 naming the field.
#[test]
fn dips_prediction_contract() {
    let (file, _) = shared_reduced();
    let dir = tmp("dips");
    let cfg = config(&dir, "d.toml", "", file, "");
    let out = dir.join("d");
    let s = json_of(&run_study(
        "dips",
        &["--quiet", "--json", "--no-sweep"],
        &cfg,
        &out,
    ));
    let g = s["grounds"].as_array().expect("grounds");
    assert_eq!(g.len(), 2);
    for (k, name) in ["drum", "road"].iter().enumerate() {
        let span = floats(&g[k]["contact_node_span_m"]);
        let l = f(&g[k]["envelope_length_m"]);
        assert!(
            l > 0.0 && l <= span[1] - span[0] + 0.04 + 1e-9,
            "{name}: L = {l}"
        );
        let lg = f(&g[k]["geometric_envelope_length_m"]);
        assert!((l - lg).abs() < 0.08, "{name}: L = {l} vs geometric {lg}");
        let v = csv_column(
            &out.join(format!("prediction_{name}.csv")),
            "speed_km_per_h",
        );
        let a = csv_column(&out.join(format!("prediction_{name}.csv")), "amplitude_N");
        for d in floats(&g[k]["predicted_dips_kmh"]) {
            let i = v.iter().position(|x| *x == d).expect("dip on the grid");
            assert!(
                a[i] < a[i - 1] && a[i] < a[i + 1],
                "{name}: {d} km/h is no minimum"
            );
        }
        assert!(
            g[k]["sweep_speeds_kmh"]
                .as_array()
                .expect("speeds")
                .is_empty()
        );
    }
    assert!(f(&g[1]["envelope_length_m"]) > f(&g[0]["envelope_length_m"]));
    // issue 39 item 3: the profile's count of active nodes is an integer column, written as
    // integers, and every header follows the one unit convention (reference: the convention's
    // definition, `flowmbd_cli::output::column_kind`)
    let profile = std::fs::read_to_string(out.join("profile_drum.csv")).unwrap();
    assert!(
        profile.starts_with("cleat_x_m,dfy_N,fx_N,active_nodes_count\n"),
        "{profile}"
    );
    let bad = flowmbd_cli::output::csv_violations(&out);
    assert!(bad.is_empty(), "outside the CSV convention: {bad:?}");
    let bad = config(&dir, "bad.toml", "[dips]\nprofile_step = -1.0", file, "");
    let (code, _, err) = outcome(&run_study(
        "dips",
        &["--quiet", "--no-sweep"],
        &bad,
        &dir.join("b"),
    ));
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("profile_step"), "{err}");
}

/// `--phases 2`: the summary's `phases` and `phases.csv` hold the run itself (phase 0) and a
/// run with the cleat half an impact step later, which equals the plain study with
/// `rig.settle_time` lengthened by that much (second formulation: the shifted run by hand).
#[test]
fn cleat_phases_are_runs_with_the_cleat_delayed() {
    let (file, _) = shared_reduced();
    let dir = tmp("phases");
    let top = "vtk_interval = 0\nvtk_tire_interval = 0";
    let cfg = config(&dir, "p.toml", top, file, "");
    let s = json_of(&run_study(
        "cleat",
        &["--phases", "2", "--json", "--quiet"],
        &cfg,
        &dir.join("p"),
    ));
    let p = &s["phases"];
    assert_eq!(p["phases"], 2);
    let fy = floats(&p["fy_band_rms_n"]);
    assert_eq!(fy[0], f(&s["fy_band_rms_n"]));
    // the default rig: h = 0.2 ms, 4 sub-steps through the impact
    let delayed = 0.4 + 0.5 * 2e-4 / 4.0;
    let cfg2 = config(
        &dir,
        "q.toml",
        top,
        file,
        &format!("[rig]\nsettle_time = {delayed:e}\n"),
    );
    let q = json_of(&run_study(
        "cleat",
        &["--json", "--quiet"],
        &cfg2,
        &dir.join("q"),
    ));
    assert_eq!(fy[1], f(&q["fy_band_rms_n"]));
    assert_eq!(floats(&p["fx_band_rms_n"])[1], f(&q["fx_band_rms_n"]));
    let mean = 0.5 * (fy[0] + fy[1]);
    assert!((f(&p["fy_band_rms_mean_n"]) - mean).abs() <= 1e-12 * mean);
    let csv = std::fs::read_to_string(dir.join("p/phases.csv")).unwrap();
    assert_eq!(csv.lines().count(), 3, "{csv}");
    // one run: no `phases` key
    assert!(
        json_of(&run_study(
            "cleat",
            &["--json", "--quiet"],
            &cfg,
            &dir.join("r")
        ))
        .get("phases")
        .is_none()
    );
}

// Issue 39 item 2: every key and table of every study's printed configuration has a comment
// (its meaning, from the rustdoc of the configuration types) and every floating-point key's
// comment states its unit in brackets (`flowmbd_cli::commented`).
#[test]
fn printed_configurations_are_commented() {
    flowmbd_cli::testing::assert_printed_configs_commented(env!("CARGO_BIN_EXE_flowmbd-tire"));
}

// Issue 39 item 2: every study has a shipped example under `examples/` (its first line names
// the study: `flowmbd_cli::testing::examples`), and each runs (short: the examples' own run-length
// keys, or the study's options) to a complete summary with its `meaning`.
#[test]
fn shipped_examples_cover_every_study_and_run() {
    use flowmbd_cli::testing::ExampleRun::Short;
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    // the study's options for a short run (the examples are short already)
    flowmbd_cli::testing::assert_examples_run(
        env!("CARGO_BIN_EXE_flowmbd-tire"),
        &dir,
        |study, _| {
            let args: &'static [&'static str] = match study {
                "dips" => &["--no-sweep"],
                "rotating-modes" => &["--speeds", "0,60"],
                _ => &[],
            };
            Short {
                overrides: "",
                args,
            }
        },
    );
}
