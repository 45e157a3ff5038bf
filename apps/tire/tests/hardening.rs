//! Issue 20 reproducers for `flowmbd-tire`, each run against the binary: the rig and tire
//! configurations that panicked, aborted, hung or ran to a meaningless end now exit 2 with one
//! line naming the field before anything is computed; every configuration table (the
//! defaults and the other normal, friction and derivative variants) rejects unknown keys;
//! `--print-config` shows the tire import; the reduced tire is cached in the OS cache folder,
//! not under the working folder; and the sweep's speed × frequency map carries every speed's
//! spectrum (the 90 km/h row was zero off the 5 Hz grid).

use crate::common;
use common::*;
use flowmbd_cli::config::{UNKNOWN_KEY, tables_accepting_unknown_keys_by};
use std::path::Path;

/// `study --config <text> --print-config`: (exit code, stderr). Validation runs before
/// printing, so nothing is computed either way.
fn check(study: &str, text: &str, extra: &[&str], dir: &Path) -> (i32, String) {
    let f = dir.join("c.toml");
    std::fs::write(&f, text).unwrap();
    let mut args = vec![study, "--config", f.to_str().unwrap(), "--print-config"];
    args.extend_from_slice(extra);
    let (code, _, err) = outcome(&run(&args));
    (code, err)
}

#[test]
fn reproducers_exit_2_naming_the_field() {
    let dir = tmp("repro");
    // (configuration, flags, text the one-line message must contain)
    let cases: Vec<(&str, Vec<&str>, Vec<&str>)> = vec![
        // panicked (capacity overflow); the value printed with an exponent, not 301 digits
        (
            "[rig]\nrecord_time = 1e300\n",
            vec![],
            vec!["rig.record_time", "= 1e300 s", "steps"],
        ),
        // allocation abort
        (
            "[rig]\nrecord_time = 1e6\n",
            vec![],
            vec!["rig.record_time", "steps"],
        ),
        // hang
        (
            "[rig.impact]\nsubsteps = 1000000000\n",
            vec![],
            vec!["rig.impact.substeps"],
        ),
        // fy_peak_hz: 0 from 8 samples
        (
            "[rig.rolling]\ntime_step = 0.05\n",
            vec![],
            vec!["rig.rolling.time_step", "cannot resolve"],
        ),
        // ran to the end
        (
            "[rig.rolling]\nnewmark_beta = 1e9\n",
            vec![],
            vec!["rig.rolling.newmark_beta", "1e9"],
        ),
        (
            "[rig.rolling]\nfriction = 1e300\n",
            vec![],
            vec!["rig.rolling.friction", "[0, 5]"],
        ),
        // allocation abort
        (
            "[tire.generator]\ncircumferential_divisions = 1000000000\n",
            vec![],
            vec!["tire.generator.circumferential_divisions"],
        ),
        (
            "[tire.generator]\nsection_divisions = 1000000000\n",
            vec![],
            vec!["tire.generator.section_divisions"],
        ),
        // 3 x 2e5 x 1 divisions each below the ceiling, their product not
        (
            "[tire.generator]\ncircumferential_divisions = 200000\nsection_divisions = 200\n\
             thickness_divisions = 1\nbead_elements = 1\n",
            vec![],
            vec!["tire.generator.circumferential_divisions", "elements"],
        ),
        // NaN generator values exited 1 (numerical failure)
        (
            "[tire.generator]\nwidth = nan\n",
            vec![],
            vec!["tire.generator.width", "not a number"],
        ),
        (
            "[tire.generator.tread]\nyoung = nan\npoisson = 0.45\ndensity = 1500.0\n",
            vec![],
            vec!["tire.generator.tread.young", "not a number"],
        ),
        (
            "[rig.damping]\nzeta1 = nan\n",
            vec![],
            vec!["rig.damping.zeta1", "not a number"],
        ),
        // "NaN s is negative"
        (
            "[rig.impact]\nlead = nan\n",
            vec![],
            vec!["rig.impact.lead", "not a number"],
        ),
        // unknown keys that were accepted
        (
            "[rig.rolling.normal]\nlaw = \"lagrange\"\nstiffness = 1e7\n",
            vec![],
            vec!["unknown field `stiffness`"],
        ),
        (
            "[tire.reduction.derivative.FiniteDifference]\nfirst = \"Central\"\n\
             second = \"ThreePoint\"\nthird = 1\n",
            vec![],
            vec!["unknown field `third`"],
        ),
        // `--speed -20` was refused by the argument parser
        ("", vec!["--speed", "-20"], vec!["rig.speed_kmh", "got -20"]),
        (
            "",
            vec!["--friction", "-0.5"],
            vec!["rig.rolling.friction", "got -0.5"],
        ),
    ];
    for (i, (text, flags, want)) in cases.iter().enumerate() {
        let t0 = std::time::Instant::now();
        let (code, err) = check("cleat", text, flags, &dir);
        assert_eq!(code, 2, "case {i} {text:?} {flags:?}: exit {code}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "case {i}: {err}");
        for w in want {
            assert!(err.contains(w), "case {i}: `{w}` not in: {err}");
        }
        assert!(
            !err.contains("negative") || text.is_empty(),
            "case {i}: {err}"
        );
        assert!(err.len() < 400, "case {i}: a short line: {err}");
        assert!(
            t0.elapsed().as_secs() < 10,
            "case {i} took {:?}",
            t0.elapsed()
        );
    }
    // the sweep refuses the same rig
    let (code, err) = check("sweep", "[rig.rolling]\ntime_step = 0.05\n", &[], &dir);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("rig.rolling.time_step"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The tables of `text` (a configuration of `study`) that the binary accepts with an unknown key.
fn holes(study: &str, text: &str, dir: &Path) -> Vec<String> {
    tables_accepting_unknown_keys_by(text, |variant| {
        let (code, err) = check(study, variant, &[], dir);
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
    })
}

// every table of every study, with the default and the other variants of the normal law, the
// friction law (table form), the derivative operator and an imported tire
#[test]
fn every_table_rejects_an_unknown_key() {
    let dir = tmp("keys");
    for study in [
        "modes",
        "reduce",
        "cleat",
        "sweep",
        "pressure",
        "rotating-modes",
        "dips",
        "steady",
    ] {
        let (code, text, err) = outcome(&run(&[study, "--print-config"]));
        assert_eq!(code, 0, "{err}");
        let h = holes(study, &text, &dir);
        assert!(
            h.is_empty(),
            "{study}: tables accepting unknown keys: {h:?}"
        );
    }
    let (_, text, _) = outcome(&run(&["cleat", "--print-config"]));
    // the configuration without its comments (the variants below edit its keys)
    let text: String = text
        .lines()
        .filter(|l| !l.trim_start().starts_with('#'))
        .map(|l| format!("{l}\n"))
        .collect();
    let fd = "[tire.reduction.derivative.FiniteDifference]\nfirst = \"Central\"\nsecond = \"ThreePoint\"\n";
    assert!(text.contains(fd));
    let variants = [
        text.replace(
            "[rig.rolling.normal]\nlaw = \"lagrange\"",
            "[rig.rolling.normal]\nlaw = \"penalty\"\nstiffness = 1e7",
        ),
        text.replace(
            "friction_law = \"coulomb\"",
            "friction_law = { law = \"stribeck\", mu_static = 1.0, mu_kinetic = 0.8, \
             stribeck_velocity = 0.1, kappa = 40.0 }",
        ),
        text.replace(
            "friction_law = \"coulomb\"",
            "friction_law = { law = \"frictionless\" }",
        ),
        text.replace(fd, "[tire.reduction.derivative.Polynomial]\ndegree = 5\n"),
        text.replace(fd, "[tire.reduction.derivative]\nConsistent = \"Lumped\"\n"),
        text + "[tire.import]\nformat = \"abaqus\"\nstiffness = \"k\"\nmass = \"m\"\nnodes = \"n\"\n\
                rim_nodes = \"r\"\npatch_nodes = \"p\"\n",
    ];
    for (i, v) in variants.iter().enumerate() {
        // unknown keys are found by the parser, before the import files are looked for
        let h = holes("cleat", v, &dir);
        assert!(h.is_empty(), "variant {i}: {h:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

// Issue 20: the tire import was missing from `--print-config` and from the README
#[test]
fn tire_import_is_documented() {
    for study in ["cleat", "reduce", "sweep"] {
        let (code, text, _) = outcome(&run(&[study, "--print-config"]));
        assert_eq!(code, 0);
        let example: Vec<&str> = text
            .lines()
            .skip_while(|l| !l.starts_with("# [tire.import]"))
            .take_while(|l| l.starts_with('#'))
            .collect();
        assert!(example.len() >= 7, "{study}: {example:?}");
        // the commented example, uncommented, is a valid import table (its files aside)
        let table: String = example
            .iter()
            .map(|l| {
                l.trim_start_matches("# ")
                    .split(" #")
                    .next()
                    .unwrap()
                    .to_string()
                    + "\n"
            })
            .collect();
        let files: toml::Value = toml::from_str(&table).unwrap();
        for k in [
            "format",
            "stiffness",
            "mass",
            "nodes",
            "rim_nodes",
            "patch_nodes",
        ] {
            assert!(files["tire"]["import"].get(k).is_some(), "{k}");
        }
    }
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../README.md"))
            .unwrap();
    assert!(readme.contains("[tire.import]") && readme.contains("matrix_market"));
}

// Issue 20: `flowmbd-tire` wrote its reduced-tire cache under the working folder
// (`out/tire/...`); it goes to the OS cache folder ($XDG_CACHE_HOME/flowmbd/tire), named by
// the tire and reduction, and is reused from there
#[test]
fn reduced_tire_is_cached_in_the_os_cache_folder() {
    let dir = tmp("cache");
    let (work, cache) = (dir.join("work"), dir.join("xdg-cache"));
    std::fs::create_dir_all(&work).unwrap();
    // the small tire without `reduced_file`: the default, "cache"
    let tables = tire_tables(Path::new("unused"));
    let tables: String = tables
        .lines()
        .filter(|l| !l.starts_with("reduced_file"))
        .map(|l| format!("{l}\n"))
        .collect();
    let cfg = dir.join("c.toml");
    std::fs::write(&cfg, &tables).unwrap();
    let go = |study: &str| {
        bin()
            .args([study, "--json", "--config", cfg.to_str().unwrap(), "--out"])
            .arg(dir.join(study))
            .current_dir(&work)
            .env("XDG_CACHE_HOME", &cache)
            .env("HOME", &dir)
            .output()
            .unwrap()
    };
    let first = go("pressure");
    let s = json_of(&first);
    assert!(s["drum"]["deflection_m"].as_f64().unwrap() > 0.0);
    let err = String::from_utf8_lossy(&first.stderr);
    assert!(err.contains("reducing the generated tire"), "{err}");
    let files: Vec<_> = std::fs::read_dir(cache.join("flowmbd/tire"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert_eq!(files.len(), 1, "{files:?}");
    let name = files[0].file_name().unwrap().to_string_lossy().into_owned();
    assert!(
        name.starts_with(&format!("reduced-truck-{CONTACT}c-{MODES}m-")) && name.ends_with(".json"),
        "{name}"
    );
    assert!(
        err.contains(&name),
        "the message names the cached file: {err}"
    );
    assert_eq!(
        std::fs::read_dir(&work).unwrap().count(),
        0,
        "nothing under the working folder"
    );
    // a second study reuses it
    let second = go("modes");
    json_of(&second);
    assert!(!String::from_utf8_lossy(&second.stderr).contains("reducing"));
    std::fs::remove_dir_all(&dir).ok();
}

// Issue 20 reproducer: `sweep` with speeds 30, 60, 90 km/h and record_time = 0.2 s wrote a
// 90 km/h row of fy_matrix.csv that was zero except at 0 Hz (its bins 4.995 Hz apart, off the
// first run's 5 Hz grid). Reference: each run's own spectrum (v090_spectra.csv): the matrix row
// peaks where it peaks (within one bin) with the same amplitude (within the interpolation
// loss of a Hann-windowed line between bins, < 15 %), and every row is non-zero.
#[test]
fn sweep_map_rows_follow_each_speeds_spectrum() {
    let (file, _) = shared_reduced();
    let dir = tmp("sweep-grid");
    let cfg = config(
        &dir,
        "s.toml",
        "speeds_kmh = [30.0, 60.0, 90.0]",
        file,
        "[rig]\nrecord_time = 0.2\n",
    );
    let sw = dir.join("sw");
    let s = json_of(&run_study("sweep", &["--quiet", "--json"], &cfg, &sw));
    assert_eq!(s["runs"].as_array().unwrap().len(), 3);
    let text = std::fs::read_to_string(sw.join("fy_matrix.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let grid: Vec<f64> = header[1..]
        .iter()
        .map(|h| {
            h.trim_start_matches('f')
                .trim_end_matches("Hz_amp_N")
                .parse()
                .unwrap()
        })
        .collect();
    let df = grid[1] - grid[0];
    for (line, v) in lines.zip(["030", "060", "090"]) {
        let row: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let amp = &row[1..];
        let f = csv_column(&sw.join(format!("v{v}_spectra.csv")), "f_Hz");
        let a = csv_column(&sw.join(format!("v{v}_spectra.csv")), "fy_amp_N");
        let (kp, _) = (0..f.len())
            .filter(|&k| f[k] >= 10.0 && f[k] <= 300.0)
            .map(|k| (k, a[k]))
            .fold((0, f64::MIN), |b, x| if x.1 > b.1 { x } else { b });
        let (jm, _) = (0..grid.len())
            .filter(|&j| grid[j] >= 10.0)
            .map(|j| (j, amp[j]))
            .fold((0, f64::MIN), |b, x| if x.1 > b.1 { x } else { b });
        assert!(
            (grid[jm] - f[kp]).abs() <= df + 1e-9,
            "{v} km/h: map peak {} Hz vs spectrum peak {} Hz",
            grid[jm],
            f[kp]
        );
        assert!(
            amp[jm] > 0.85 * a[kp] && amp[jm] <= a[kp] * (1.0 + 1e-9),
            "{v} km/h: {} N vs {} N",
            amp[jm],
            a[kp]
        );
        assert!(amp.iter().skip(1).filter(|x| **x > 0.0).count() > grid.len() / 2);
    }
    assert!(flowmbd_cli::output::csv_violations(&sw).is_empty());
    std::fs::remove_dir_all(&dir).ok();
}

// Issue 20 item 2: `--allow-large` raises the documented ceilings 1000-fold: 3·10^4 s at the
// default 0.2 ms step are 1.5·10^8 rig steps, above MAX_RIG_STEPS = 2·10^7 (refused, naming
// rig.record_time), within 2·10^10 with the flag; `--print-config` validates and computes
// nothing.
#[test]
fn allow_large_raises_the_rig_step_ceiling() {
    let dir = tmp("allow-large");
    let text = "[rig]\nrecord_time = 30000\n";
    let (code, err) = check("cleat", text, &[], &dir);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("rig.record_time") && err.contains("--allow-large"),
        "{err}"
    );
    let (code, err) = check("cleat", text, &["--allow-large"], &dir);
    assert_eq!(code, 0, "{err}");
    // 10^300 s stay refused with the flag
    let (code, err) = check(
        "cleat",
        "[rig]\nrecord_time = 1e300\n",
        &["--allow-large"],
        &dir,
    );
    assert_eq!(code, 2, "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
