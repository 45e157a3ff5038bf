//! End-to-end tests of `flowmbd-reduce tire-mesh` and `modes` (app conventions: JSON summary,
//! exit code 2 with a one-line message naming the field on bad input).

use crate::common;
use common::{bin, tmp};

/// tire-mesh writes M, K, mesh and node sets; modes on them with the rim fixed returns
/// ascending frequencies whose axisymmetric pairs coincide, matching a run without the mesh.
#[test]
fn tire_mesh_then_modes() {
    let dir = tmp("e2e", "e2e");
    let cfg = dir.join("small.toml");
    std::fs::write(
        &cfg,
        "[tire]\ncircumferential_divisions = 16\nsection_divisions = 10\nthickness_divisions = 1\nbead_elements = 1\n",
    )
    .unwrap();
    let tm = dir.join("tm");
    let out = bin()
        .args(["tire-mesh", "--quiet", "--json", "--config"])
        .arg(&cfg)
        .arg("--out")
        .arg(&tm)
        .output()
        .unwrap();
    let s = common::json_of(&out);
    assert_eq!(s["dof"], 3 * 16 * 11 * 2);
    // issue 20: the summary says what its numbers mean
    assert!(s["meaning"].as_str().unwrap().contains("carcass"), "{s}");
    for f in [
        "K.mtx",
        "M.mtx",
        "mesh.vtu",
        "mesh.json",
        "node_sets.json",
        "rim_dofs.txt",
    ] {
        assert!(tm.join(f).exists(), "{f}");
    }
    let md = dir.join("md");
    let out = bin()
        .args(["modes", "--quiet", "--json", "--count", "6"])
        .arg("--mass")
        .arg(tm.join("M.mtx"))
        .arg("--stiffness")
        .arg(tm.join("K.mtx"))
        .arg("--fixed")
        .arg(tm.join("rim_dofs.txt"))
        .arg("--mesh")
        .arg(tm.join("mesh.json"))
        .arg("--out")
        .arg(&md)
        .output()
        .unwrap();
    let s = common::json_of(&out);
    // exactly dof and frequencies_hz, and (issue 20) what the numbers mean
    assert_eq!(
        s.as_object().unwrap().len(),
        3,
        "exactly dof, frequencies_hz and meaning: {s}"
    );
    assert!(
        s["meaning"]
            .as_str()
            .unwrap()
            .contains("Natural frequencies")
    );
    assert_eq!(s["dof"], 3 * 16 * 11 * 2);
    let f: Vec<f64> = s["frequencies_hz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(f.len(), 6);
    assert!(f.windows(2).all(|w| w[0] <= w[1]));
    assert!(f[0] > 1.0);
    assert!(md.join("modes.vtu").exists());
    // issue 39 item 3: `frequencies.csv` follows the one CSV convention, the mode number an
    // integer (reference: the convention's definition, `flowmbd_cli::output::column_kind`)
    let csv = std::fs::read_to_string(md.join("frequencies.csv")).unwrap();
    assert!(
        csv.starts_with("mode,frequency_Hz,eigenvalue_rad2_per_s2\n1,"),
        "{csv}"
    );
    let bad = flowmbd_cli::output::csv_violations(&md);
    assert!(bad.is_empty(), "outside the CSV convention: {bad:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Bad input exits with code 2 and names the field (and the file line for matrix errors).
#[test]
fn bad_input_exits_2_naming_the_field() {
    let dir = tmp("e2e", "bad");
    let m = dir.join("M.mtx");
    std::fs::write(
        &m,
        "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1.0\n2 3 1.0\n",
    )
    .unwrap();
    let out = bin()
        .args(["modes", "--quiet", "--count", "1"])
        .arg("--mass")
        .arg(&m)
        .arg("--stiffness")
        .arg(&m)
        .arg("--out")
        .arg(dir.join("o"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("mass") && err.contains("M.mtx:4"), "{err}");
    let cfg = dir.join("c.toml");
    std::fs::write(&cfg, "[tire]\nwidth = -1.0\n").unwrap();
    let out = bin()
        .args(["tire-mesh", "--quiet", "--config"])
        .arg(&cfg)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("tire.width"));
    let cfg2 = dir.join("c2.toml");
    std::fs::write(&cfg2, "[tire]\nwheel = 3\n").unwrap();
    let out = bin()
        .args(["tire-mesh", "--quiet", "--config"])
        .arg(&cfg2)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    std::fs::remove_dir_all(&dir).ok();
}

// Issue 39 item 2: every key and table of every study's printed configuration has a comment
// (its meaning, from the rustdoc of the configuration types) and every floating-point key's
// comment states its unit in brackets (`flowmbd_cli::commented`).
#[test]
fn printed_configurations_are_commented() {
    flowmbd_cli::testing::assert_printed_configs_commented(env!("CARGO_BIN_EXE_flowmbd-reduce"));
}

// Issue 39 item 2: every study has a shipped example under `examples/` (its first line names
// the study: `flowmbd_cli::testing::examples`), and each runs, shortened by its own run-length
// keys, to a complete summary with its `meaning`.
#[test]
fn shipped_examples_cover_every_study_and_run() {
    use flowmbd_cli::testing::ExampleRun::{Short, Skip};
    let exe = env!("CARGO_BIN_EXE_flowmbd-reduce");
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    flowmbd_cli::testing::assert_examples_run(exe, &dir, |study, path| {
        if study == "reduce" {
            // `reduce` writes one file (`--out FILE`), not a folder: run here
            let out = std::env::temp_dir().join(format!(
                "flowmbd-reduce-{}-example.json",
                std::process::id()
            ));
            let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
            let run = std::process::Command::new(exe)
                .args(["reduce", "--json", "--quiet", "--config"])
                .arg(path)
                .arg("--out")
                .arg(&out)
                .current_dir(root)
                .output()
                .unwrap();
            let err = String::from_utf8_lossy(&run.stderr);
            assert!(run.status.success(), "reduce {}: {err}", path.display());
            assert!(out.is_file(), "{}", out.display());
            let _ = std::fs::remove_file(out);
            return Skip;
        }
        // overrides merged into the example: its run-length keys
        let overrides = match study {
            "lin-slab" => "[params]\nduration_s = 0.05\n",
            _ => "",
        };
        Short {
            overrides,
            args: &[],
        }
    });
}
