//! Import of a user's tire from ABAQUS `*MATRIX GENERATE` files (issue 9, deliverable 1): the
//! generated coarse tire is written in ABAQUS's format (one triangle, arbitrary node labels,
//! `*NODE` and `*NSET` style node and set files) and read back; the reduced model must be the
//! same as the one of the generated tire.

use tire::*;

use crate::common;
use std::fmt::Write as _;

#[test]
fn imported_abaqus_tire_matches_the_generated_one() {
    let fe = generated_tire(&coarse_tire_config(24, 8, 40.0)).unwrap();
    let dir = std::env::temp_dir().join(format!("flowmbd_tire_abaqus_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = |n: &str| dir.join(n).display().to_string();
    // non-contiguous labels in a shuffled-looking order: 1001 + 7 i
    let label = |i: usize| 1001 + 7 * i as u64;
    // stiffness: lower triangle (row DOF >= column DOF), 1-based DOFs per node
    let mut k = String::from("** stiffness matrix, FORMAT=MATRIX INPUT\n");
    for e in fe.stiffness.as_ref().triplet_iter() {
        let (r, c) = (e.row, e.col);
        if r < c {
            continue;
        }
        writeln!(
            k,
            "{}, {}, {}, {}, {:e}",
            label(r / 3),
            r % 3 + 1,
            label(c / 3),
            c % 3 + 1,
            e.val
        )
        .unwrap();
    }
    std::fs::write(p("tire_STIF1.mtx"), k).unwrap();
    let mut m = String::new();
    for (d, v) in fe.mass.iter().enumerate() {
        writeln!(
            m,
            "{}, {}, {}, {}, {:e}",
            label(d / 3),
            d % 3 + 1,
            label(d / 3),
            d % 3 + 1,
            v
        )
        .unwrap();
    }
    std::fs::write(p("tire_MASS1.mtx"), m).unwrap();
    let mut nodes = String::from("*NODE\n");
    for (i, x) in fe.nodes.iter().enumerate().rev() {
        writeln!(nodes, "{}, {:e}, {:e}, {:e}", label(i), x[0], x[1], x[2]).unwrap();
    }
    std::fs::write(p("nodes.inp"), nodes).unwrap();
    let nset = |name: &str, v: &[usize]| {
        let mut s = format!("*NSET, NSET={name}\n");
        for chunk in v.chunks(8) {
            let line: Vec<String> = chunk.iter().map(|&i| label(i).to_string()).collect();
            writeln!(s, "{}", line.join(", ")).unwrap();
        }
        s
    };
    std::fs::write(p("rim.inp"), nset("RIM", &fe.rim)).unwrap();
    std::fs::write(p("patch.inp"), nset("PATCH", &fe.candidates)).unwrap();
    let files = ImportFiles {
        format: ImportFormat::Abaqus,
        stiffness: p("tire_STIF1.mtx"),
        mass: p("tire_MASS1.mtx"),
        nodes: p("nodes.inp"),
        rim_nodes: p("rim.inp"),
        patch_nodes: p("patch.inp"),
    };
    let imp = imported_tire(&files).unwrap();
    // independent reference: the same reduction of the generated model
    common::assert_same_reduced_frequencies(&fe, &imp);
    // a set naming a node without coordinates is reported with the file and the label
    std::fs::write(p("bad.inp"), "1001, 5\n").unwrap();
    let e = imported_tire(&ImportFiles {
        patch_nodes: p("bad.inp"),
        ..files.clone()
    })
    .unwrap_err()
    .to_string();
    assert!(e.contains("bad.inp") && e.contains("label 5"), "{e}");
    // rotational DOFs (shell/beam models) are rejected by name
    std::fs::write(p("rot.mtx"), "1001, 4, 1001, 4, 1.0\n").unwrap();
    let e = imported_tire(&ImportFiles {
        stiffness: p("rot.mtx"),
        ..files
    })
    .unwrap_err()
    .to_string();
    assert!(e.contains("DOF 4"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}
