//! End-to-end tests of `flowmbd-reduce reduce`: Matrix Market input written from a known model
//! (Lin's Appendix B slab), the written `ReducedModel` compared with the library's
//! Craig–Bampton, and bad input (exit 2, one line naming the option, file and line).

use crate::common;
use common::{bin, tmp};
use faer::Mat;
use flowmbd_cases::lin::slab::{appendix_b_slab, node_dofs};
use reduction::basis::{Method, ModeSelection, build_basis};
use reduction::{DofPartition, ReducedModel};
use std::path::Path;
use std::process::Output;

/// Symmetric coordinate Matrix Market file (lower triangle, round-trip `{:?}` digits), written
/// here by hand so that the test does not depend on fe-model's writer.
fn write_mtx(path: &Path, a: &Mat<f64>) {
    let n = a.nrows();
    let mut lines = Vec::new();
    for j in 0..n {
        for i in j..n {
            if a[(i, j)] != 0.0 {
                lines.push(format!("{} {} {:?}", i + 1, j + 1, a[(i, j)]));
            }
        }
    }
    let text = format!(
        "%%MatrixMarket matrix coordinate real symmetric\n% written by reduce_cmd.rs\n{n} {n} {}\n{}\n",
        lines.len(),
        lines.join("\n")
    );
    std::fs::write(path, text).unwrap();
}

fn reduce(args: &[&str], m: &Path, k: &Path, out: &Path) -> Output {
    bin()
        .arg("reduce")
        .args(args)
        .arg("--mass")
        .arg(m)
        .arg("--stiffness")
        .arg(k)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap()
}

#[test]
fn cb_of_the_lin_slab_matches_the_library() {
    // Lin App. B slab, boundary nodes 16, 18, 28, 30 and 6 fixed-interface modes (Lin §7.2.1).
    let dir = tmp("cmd", "cb");
    let s = appendix_b_slab().unwrap();
    let (m, k) = (dir.join("M.mtx"), dir.join("K.mtx"));
    write_mtx(&m, &s.m);
    write_mtx(&k, &s.k);
    let file = dir.join("slab_cb.json");
    let out = reduce(
        &[
            "--quiet",
            "--json",
            "--boundary",
            "16,18,28,30",
            "--method",
            "cb",
            "--modes",
            "6",
            "--dofs-per-node",
            "3",
        ],
        &m,
        &k,
        &file,
    );
    let summary = common::json_of(&out);
    assert_eq!(summary["n_full"], 90);
    assert_eq!(summary["n_reduced"], 18);
    // the written file, loaded back
    let red = ReducedModel::load(&file).unwrap();
    assert_eq!(red.method, Method::CraigBampton);
    assert_eq!(red.n_reduced(), 18);
    let f_file = red.natural_frequencies_hz().unwrap();
    // the library's CB on the same (M, K)
    let part = DofPartition::from_boundary_dofs(90, &node_dofs(&[16, 18, 28, 30])).unwrap();
    let b = build_basis(
        s.k.as_ref(),
        s.m.as_ref(),
        &part,
        Method::CraigBampton,
        &ModeSelection::Lowest(6),
    )
    .unwrap();
    let lib = ReducedModel::from_basis(b, s.k.as_ref(), s.m.as_ref(), None, 3).unwrap();
    let f_lib = lib.natural_frequencies_hz().unwrap();
    assert_eq!(f_file.len(), f_lib.len());
    for (i, (a, b)) in f_file.iter().zip(&f_lib).enumerate() {
        // six rigid-body zeros: absolute; elastic: relative 1e-9
        let tol = if i < 6 { 1e-5 } else { 1e-9 * b };
        assert!(
            (a - b).abs() <= tol,
            "frequency {i}: file {a} vs library {b}"
        );
    }
    // and the companion's independent reproduction (seed-002-lin.md §14.6 [D]): CB 7.4987,
    // 9.2934, 13.5888, 14.4126, 21.3825 Hz
    for (i, f) in [7.4987, 9.2934, 13.5888, 14.4126, 21.3825]
        .iter()
        .enumerate()
    {
        assert!((f_file[6 + i] - f).abs() < 5e-5, "{} vs {f}", f_file[6 + i]);
    }
    let printed: Vec<f64> = summary["frequencies_hz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!((printed[6] - f_lib[6]).abs() < 1e-9 * f_lib[6]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn cb_with_a_fixed_set_matches_the_library() {
    // Lin App. B slab clamped at nodes 1-3 and 19 (not colinear: every rigid-body motion
    // restrained; fixed set), boundary nodes 16, 18, 28, 30 and 6
    // fixed-interface modes; reference: the library's dense Craig–Bampton (`build_basis`) on
    // the same three-set partition
    let dir = tmp("cmd", "fixed");
    let s = appendix_b_slab().unwrap();
    let (m, k) = (dir.join("M.mtx"), dir.join("K.mtx"));
    write_mtx(&m, &s.m);
    write_mtx(&k, &s.k);
    let file = dir.join("slab_cb_fixed.json");
    let args = [
        "--quiet",
        "--json",
        "--boundary",
        "16,18,28,30",
        "--modes",
        "6",
    ];
    let out = reduce(&[&args[..], &["--fixed", "1-3,19"]].concat(), &m, &k, &file);
    let summary = common::json_of(&out);
    assert_eq!(summary["n_fixed"], 12);
    assert_eq!(summary["n_reduced"], 18);
    let red = ReducedModel::load(&file).unwrap();
    for d in (0..9).chain(54..57) {
        for j in 0..red.n_reduced() {
            assert_eq!(red.psi[(d, j)], 0.0, "fixed row {d}");
        }
    }
    let part = DofPartition::new(
        90,
        &node_dofs(&[16, 18, 28, 30]),
        &node_dofs(&[1, 2, 3, 19]),
    )
    .unwrap();
    let b = build_basis(
        s.k.as_ref(),
        s.m.as_ref(),
        &part,
        Method::CraigBampton,
        &ModeSelection::Lowest(6),
    )
    .unwrap();
    let lib = ReducedModel::from_basis(b, s.k.as_ref(), s.m.as_ref(), None, 3).unwrap();
    let (f_file, f_lib) = (
        red.natural_frequencies_hz().unwrap(),
        lib.natural_frequencies_hz().unwrap(),
    );
    // clamped: no rigid-body zeros
    assert!(f_lib[0] > 0.1, "{}", f_lib[0]);
    for (i, (a, b)) in f_file.iter().zip(&f_lib).enumerate() {
        assert!(
            (a - b).abs() <= 1e-9 * b,
            "frequency {i}: file {a} vs library {b}"
        );
    }
    // a node both fixed and boundary is rejected naming the options
    let out = reduce(&[&args[..], &["--fixed", "16"]].concat(), &m, &k, &file);
    expect_input_error(&out, &["--fixed", "boundary"]);
    let out = reduce(&[&args[..], &["--fixed", "31"]].concat(), &m, &k, &file);
    expect_input_error(&out, &["--fixed", "31", "30 nodes"]);
    std::fs::remove_dir_all(&dir).ok();
}

fn expect_input_error(out: &Output, needles: &[&str]) {
    assert_eq!(
        out.status.code(),
        Some(2),
        "stderr: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    for n in needles {
        assert!(err.contains(n), "\"{n}\" not in: {err}");
    }
}

#[test]
fn bad_input_exits_2_naming_the_option_file_and_line() {
    let dir = tmp("cmd", "bad");
    let s = appendix_b_slab().unwrap();
    let (m, k) = (dir.join("M.mtx"), dir.join("K.mtx"));
    write_mtx(&m, &s.m);
    write_mtx(&k, &s.k);
    let file = dir.join("o.json");
    // boundary node out of range (30 nodes)
    let out = reduce(&["--boundary", "16,31", "--modes", "6"], &m, &k, &file);
    expect_input_error(&out, &["--boundary", "31", "30 nodes"]);
    // malformed boundary list
    let out = reduce(&["--boundary", "16,x-3"], &m, &k, &file);
    expect_input_error(&out, &["--boundary", "x-3"]);
    // a broken entry on line 4 of the stiffness file
    let bad = dir.join("K_bad.mtx");
    std::fs::write(
        &bad,
        "%%MatrixMarket matrix coordinate real symmetric\n90 90 2\n1 1 1.0\n2 1 oops\n",
    )
    .unwrap();
    let out = reduce(&["--boundary", "16"], &m, &bad, &file);
    expect_input_error(&out, &["--stiffness", "K_bad.mtx:4"]);
    // sizes that do not match
    let small = dir.join("K_small.mtx");
    write_mtx(&small, &Mat::<f64>::identity(6, 6));
    let out = reduce(&["--boundary", "1"], &m, &small, &file);
    expect_input_error(&out, &["--mass/--stiffness", "90x90", "6x6"]);
    // a missing mass file
    let out = reduce(&["--boundary", "1"], &dir.join("none.mtx"), &k, &file);
    expect_input_error(&out, &["--mass", "none.mtx"]);
    // dofs per node that do not divide the size
    let out = reduce(&["--boundary", "1", "--dofs-per-node", "7"], &m, &k, &file);
    expect_input_error(&out, &["--dofs-per-node", "7"]);
    assert!(!file.exists(), "no model written on bad input");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn eitelberg_reproduces_guyan_on_the_clamped_slab() {
    // Lin §6.6.4: Eitelberg's reduction of a structure onto its boundary DOFs gives Guyan's
    // reduced model; reference: `--method guyan` (static condensation, another algorithm) on
    // the Lin App. B slab clamped at nodes 1-3 and 19, boundary nodes 16, 18, 28, 30
    let dir = tmp("cmd", "eitelberg");
    let s = appendix_b_slab().unwrap();
    let (m, k) = (dir.join("M.mtx"), dir.join("K.mtx"));
    write_mtx(&m, &s.m);
    write_mtx(&k, &s.k);
    let args = [
        "--quiet",
        "--json",
        "--boundary",
        "16,18,28,30",
        "--fixed",
        "1-3,19",
    ];
    let (fe, fg) = (dir.join("eitelberg.json"), dir.join("guyan.json"));
    let e = common::json_of(&reduce(
        &[&args[..], &["--method", "eitelberg"]].concat(),
        &m,
        &k,
        &fe,
    ));
    let g = common::json_of(&reduce(
        &[&args[..], &["--method", "guyan"]].concat(),
        &m,
        &k,
        &fg,
    ));
    assert_eq!(e["method"], "eitelberg");
    assert_eq!(e["n_reduced"], 24);
    let (fe_hz, fg_hz) = (
        e["frequencies_hz"].as_array().unwrap(),
        g["frequencies_hz"].as_array().unwrap(),
    );
    assert_eq!(fe_hz.len(), 12);
    for (a, b) in fe_hz.iter().zip(fg_hz) {
        let (a, b) = (a.as_f64().unwrap(), b.as_f64().unwrap());
        assert!(
            (a - b).abs() <= 1e-6 * b,
            "Eitelberg {a} Hz vs Guyan {b} Hz"
        );
    }
    let file: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&fe).unwrap()).unwrap();
    assert_eq!(file["format"], "flowmbd-eitelberg");
    assert_eq!(file["minv_k"].as_array().unwrap().len(), 12);
    assert_eq!(file["a_r"].as_array().unwrap().len(), 24);
    std::fs::remove_dir_all(&dir).ok();
}
