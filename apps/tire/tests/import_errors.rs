//! Bad imported-tire files (`[tire.import]`, issue #20): an ABAQUS matrix file with a syntax
//! error, a Matrix Market `general` file storing one triangle, and a directory given for a
//! file all exit 2 with one line naming the file (and line); nothing panics.

use crate::common;
use common::{outcome, run, tmp};
use std::path::Path;

/// A 2-node, 6-DOF tire "model" in ABAQUS `*MATRIX OUTPUT` form (one triangle, labels 11, 12)
/// plus its node and node-set files; `stiffness` is the stiffness file's text.
fn abaqus_files(dir: &Path, stiffness: &str) -> String {
    let mass = "11,1,11,1,1.0\n11,2,11,2,1.0\n11,3,11,3,1.0\n\
                12,1,12,1,1.0\n12,2,12,2,1.0\n12,3,12,3,1.0\n";
    std::fs::write(dir.join("job_STIF1.mtx"), stiffness).unwrap();
    std::fs::write(dir.join("job_MASS1.mtx"), mass).unwrap();
    std::fs::write(
        dir.join("nodes.inp"),
        "11, 0.5, 0.0, 0.0\n12, 0.0, 0.5, 0.0\n",
    )
    .unwrap();
    std::fs::write(dir.join("rim.inp"), "11\n").unwrap();
    std::fs::write(dir.join("patch.inp"), "12\n").unwrap();
    import_table(
        dir,
        "abaqus",
        &dir.join("job_STIF1.mtx"),
        &dir.join("job_MASS1.mtx"),
    )
}

/// M = I (6 DOFs, Matrix Market) and the node files without labels of the Matrix Market
/// import (2 nodes, rim node 0, patch node 1); returns the path of M.
fn matrix_market_files(dir: &Path) -> std::path::PathBuf {
    let m = dir.join("M.mtx");
    std::fs::write(
        &m,
        "%%MatrixMarket matrix coordinate real symmetric\n6 6 6\n1 1 1\n2 2 1\n3 3 1\n\
         4 4 1\n5 5 1\n6 6 1\n",
    )
    .unwrap();
    std::fs::write(dir.join("nodes.inp"), "0.5 0 0\n0 0.5 0\n").unwrap();
    std::fs::write(dir.join("rim.inp"), "0\n").unwrap();
    std::fs::write(dir.join("patch.inp"), "1\n").unwrap();
    m
}

fn import_table(dir: &Path, format: &str, k: &Path, m: &Path) -> String {
    format!(
        "[tire]\nreduced_file = \"\"\n[tire.import]\nformat = {format:?}\nstiffness = {:?}\n\
         mass = {:?}\nnodes = {:?}\nrim_nodes = {:?}\npatch_nodes = {:?}\n",
        k.display().to_string(),
        m.display().to_string(),
        dir.join("nodes.inp").display().to_string(),
        dir.join("rim.inp").display().to_string(),
        dir.join("patch.inp").display().to_string(),
    )
}

fn reduce_with(dir: &Path, name: &str, cfg: &str) -> (i32, String) {
    let p = dir.join(name);
    std::fs::write(&p, cfg).unwrap();
    let out = dir.join(format!("out-{name}"));
    let (code, _, err) = outcome(&run(&[
        "reduce",
        "--quiet",
        "--config",
        p.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]));
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    (code, err)
}

/// Reproducer of issue #20: an ABAQUS syntax error exited 1 (numerical failure); it is bad
/// input (exit 2) and the message names the file and line (reference: the line we broke).
#[test]
fn abaqus_syntax_error_exits_2_with_file_and_line() {
    let dir = tmp("abaqus-syntax");
    let cfg = abaqus_files(&dir, "11,1,11,1,1.0e6\n11,2,11,2,1.0e6\n11,3,x\n");
    let (code, err) = reduce_with(&dir, "a.toml", &cfg);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("job_STIF1.mtx:3:"), "{err}");
    assert!(err.contains("tire.import"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A Matrix Market K marked `general` that stores one triangle is refused (exit 2, line 1),
/// and a directory given for the mass file is reported as a directory, not as missing.
#[test]
fn one_triangle_general_and_directory_are_refused() {
    let dir = tmp("mtx-import");
    abaqus_files(&dir, "");
    let k = dir.join("K.mtx");
    std::fs::write(
        &k,
        "%%MatrixMarket matrix coordinate real general\n6 6 7\n1 1 2\n2 2 2\n3 3 2\n\
         4 4 2\n5 5 2\n6 6 2\n4 1 -1\n",
    )
    .unwrap();
    let m = matrix_market_files(&dir);
    let (code, err) = reduce_with(&dir, "k.toml", &import_table(&dir, "matrix_market", &k, &m));
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("K.mtx:1:"), "{err}");
    assert!(err.contains("only the lower triangle"), "{err}");
    let sub = dir.join("sub");
    std::fs::create_dir_all(&sub).unwrap();
    let (code, err) = reduce_with(
        &dir,
        "d.toml",
        &import_table(&dir, "matrix_market", &k, &sub),
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("tire.import.mass"), "{err}");
    assert!(err.contains("is a directory"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Item 3 of issue #20 for the tire import: an indefinite or all-zero K is refused (exit 2)
/// naming the field, the file and the offending DOFs instead of reducing a model with
/// imaginary or zero frequencies. Reference: K = 2 I (6 DOFs) with K₁₄ = K₄₁ = −3 has the
/// eigenvalues 2 ∓ 3 on DOFs 1 and 4 (−1 < 0: indefinite).
#[test]
fn indefinite_and_zero_stiffness_are_refused_with_their_dofs() {
    let dir = tmp("mtx-indefinite");
    let m = matrix_market_files(&dir);
    let k = dir.join("K.mtx");
    std::fs::write(
        &k,
        "%%MatrixMarket matrix coordinate real symmetric\n6 6 7\n1 1 2\n2 2 2\n3 3 2\n\
         4 4 2\n5 5 2\n6 6 2\n4 1 -3\n",
    )
    .unwrap();
    let (code, err) = reduce_with(&dir, "i.toml", &import_table(&dir, "matrix_market", &k, &m));
    assert_eq!(code, 2, "{err}");
    for needle in ["tire.import.stiffness", "K.mtx", "indefinite", "DOFs"] {
        assert!(err.contains(needle), "`{needle}` not in {err}");
    }
    let k0 = dir.join("K0.mtx");
    std::fs::write(
        &k0,
        "%%MatrixMarket matrix coordinate real symmetric\n6 6 1\n1 1 0\n",
    )
    .unwrap();
    let (code, err) = reduce_with(
        &dir,
        "z.toml",
        &import_table(&dir, "matrix_market", &k0, &m),
    );
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("tire.import.stiffness") && err.contains("every entry is zero"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
