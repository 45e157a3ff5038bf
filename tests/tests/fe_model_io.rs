//! fe-model exchange: Matrix Market round trips and typed, line-numbered errors; ABAQUS
//! matrix input; VTK export.

use faer::Mat;
use fe_model::error::MatrixFileError;
use fe_model::io::{abaqus, mtx, vtk};
use fe_model::{FeError, MassKind};

fn sample() -> faer::sparse::SparseColMat<usize, f64> {
    // an assembled FE matrix with awkward values (belt loop stiffness)
    let model = fe_model::generate::belt_loop(&fe_model::generate::BeltLoopConfig {
        span_elements: 6,
        arc_elements: 4,
        ..Default::default()
    })
    .unwrap();
    model.stiffness().unwrap()
}

fn same(a: &faer::sparse::SparseColMat<usize, f64>, b: &faer::sparse::SparseColMat<usize, f64>) {
    assert_eq!(a.nrows(), b.nrows());
    let (da, db) = (a.to_dense(), b.to_dense());
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            assert_eq!(
                da[(i, j)].to_bits(),
                db[(i, j)].to_bits(),
                "entry ({i},{j})"
            );
        }
    }
}

/// Write → read is bit-exact for coordinate general/symmetric and array general/symmetric.
#[test]
fn matrix_market_round_trip_is_exact() {
    let k = sample();
    for sym in [mtx::Symmetry::General, mtx::Symmetry::Symmetric] {
        let text = mtx::sparse_to_string(k.as_ref(), sym).unwrap();
        let back = mtx::parse(&text, "mem").unwrap();
        assert_eq!(back.symmetry, sym);
        same(&k, &back.to_sparse().unwrap());
    }
    let d = Mat::from_fn(7, 7, |i, j| {
        ((i * 7 + j) as f64).sin() / 3.0 + if i == j { 1e-300 } else { 0.0 }
    });
    let ds = Mat::from_fn(7, 7, |i, j| d[(i.max(j), i.min(j))]);
    for (a, sym) in [
        (&d, mtx::Symmetry::General),
        (&ds, mtx::Symmetry::Symmetric),
    ] {
        let text = mtx::dense_to_string(a.as_ref(), sym).unwrap();
        let back = mtx::parse(&text, "mem").unwrap().to_dense();
        for i in 0..7 {
            for j in 0..7 {
                assert_eq!(back[(i, j)].to_bits(), a[(i, j)].to_bits());
            }
        }
    }
    // files too
    let dir = std::env::temp_dir().join(format!("fe_model_io_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("K.mtx");
    mtx::write_sparse(&p, k.as_ref(), mtx::Symmetry::Symmetric).unwrap();
    same(&k, &mtx::read(&p).unwrap().to_sparse().unwrap());
    std::fs::remove_dir_all(&dir).ok();
}

fn line_and_kind(r: Result<mtx::MtxMatrix, FeError>) -> (usize, MatrixFileError) {
    match r {
        Err(FeError::Matrix { line, kind, .. }) => (line, kind),
        other => panic!("expected a Matrix error, got {other:?}"),
    }
}

/// Malformed files give typed errors with the right line numbers.
#[test]
fn matrix_market_errors_are_typed_with_line_numbers() {
    let good = "%%MatrixMarket matrix coordinate real symmetric\n% c\n3 3 4\n1 1 2.0\n2 1 -1.0\n2 2 2.0\n3 3 1.0\n";
    assert!(mtx::parse(good, "g").is_ok());
    // truncated
    let (l, k) = line_and_kind(mtx::parse(&good.replace("3 3 1.0\n", ""), "t"));
    assert_eq!(l, 7);
    assert!(matches!(
        k,
        MatrixFileError::Truncated {
            expected: 4,
            found: 3
        }
    ));
    // wrong header
    let (l, k) = line_and_kind(mtx::parse(
        &good.replace("%%MatrixMarket matrix", "%%MatrixMarkt matrix"),
        "h",
    ));
    assert_eq!(l, 1);
    assert!(matches!(k, MatrixFileError::Header(_)));
    let (l, k) = line_and_kind(mtx::parse(&good.replace("real", "complex"), "h"));
    assert_eq!(l, 1);
    assert!(matches!(k, MatrixFileError::Header(_)));
    // index out of range
    let (l, k) = line_and_kind(mtx::parse(&good.replace("2 1 -1.0", "4 1 -1.0"), "i"));
    assert_eq!(l, 5);
    assert!(matches!(
        k,
        MatrixFileError::IndexOutOfRange { row: 4, col: 1, .. }
    ));
    let (l, _) = line_and_kind(mtx::parse(&good.replace("2 1 -1.0", "0 1 -1.0"), "i"));
    assert_eq!(l, 5);
    // NaN
    let (l, k) = line_and_kind(mtx::parse(&good.replace("2 2 2.0", "2 2 NaN"), "n"));
    assert_eq!(l, 6);
    assert!(matches!(k, MatrixFileError::NonFinite(_)));
    // declared symmetric, but both triangles given and different
    let bad = good
        .replace("3 3 4\n", "3 3 5\n")
        .replace("3 3 1.0\n", "3 3 1.0\n1 2 -1.5\n");
    let (l, k) = line_and_kind(mtx::parse(&bad, "s"));
    assert_eq!(l, 8);
    assert!(matches!(
        k,
        MatrixFileError::NotSymmetric { row: 1, col: 2, .. }
    ));
    // a symmetric array must be square / syntax errors
    let (l, k) = line_and_kind(mtx::parse(
        "%%MatrixMarket matrix array real general\n2 2\n1\n2\nx\n4\n",
        "a",
    ));
    assert_eq!(l, 5);
    assert!(matches!(k, MatrixFileError::Syntax(_)));
    let (l, k) = line_and_kind(mtx::parse(
        "%%MatrixMarket matrix array real general\n2 2\n1\n2\n3\n",
        "a",
    ));
    assert_eq!(l, 6);
    assert!(matches!(
        k,
        MatrixFileError::Truncated {
            expected: 4,
            found: 3
        }
    ));
    // writing a non-symmetric matrix as symmetric is refused
    let ns = Mat::from_fn(2, 2, |i, j| (i + 2 * j) as f64);
    assert!(mtx::dense_to_string(ns.as_ref(), mtx::Symmetry::Symmetric).is_err());
    // messages name file and line
    let e = mtx::parse(&good.replace("2 2 2.0", "2 2 NaN"), "K.mtx").unwrap_err();
    assert!(e.to_string().starts_with("K.mtx:6:"), "{e}");
}

/// ABAQUS `*MATRIX OUTPUT, FORMAT=MATRIX INPUT` files (one triangle, node/DOF labels) are
/// read into a common node/DOF map and mirrored: re-reading a matrix we export in that format
/// reproduces it exactly.
#[test]
fn abaqus_matrix_input_reads_with_node_dof_map() {
    let model = fe_model::generate::straight_beam_2d(
        1.0,
        4,
        fe_model::element::Frame2dSection {
            ea: 1e5,
            ei: 10.0,
            mass_per_length: 2.0,
        },
        0.0,
    )
    .unwrap();
    let (k, m) = model.k_and_m(MassKind::Consistent, false).unwrap();
    // node labels 101.. (ABAQUS labels are arbitrary), DOFs 1, 2, 6 (u, v, θz)
    let label = |node: usize| 101 + 10 * node as u64;
    let dofnum = [1u32, 2, 6];
    let export = |a: &faer::sparse::SparseColMat<usize, f64>| {
        let mut s = String::from("** generated\n");
        for (r, c, v) in fe_model::sparse::triplets(a.as_ref()) {
            if r <= c {
                s += &format!(
                    "{},{},{},{},{:e}\n",
                    label(r / 3),
                    dofnum[r % 3],
                    label(c / 3),
                    dofnum[c % 3],
                    v
                );
            }
        }
        s
    };
    let ks = abaqus::parse(&export(&k), "job_STIF1.mtx").unwrap();
    let ms = abaqus::parse(&export(&m), "job_MASS1.mtx").unwrap();
    let (map, mats) = abaqus::assemble(&[&ks, &ms]).unwrap();
    assert_eq!(map.len(), 15);
    assert_eq!(map.index(121, 6), Some(3 * 2 + 2));
    same(&k, &mats[0]);
    same(&m, &mats[1]);
    // errors: bad line
    match abaqus::parse("1,1,1,1,2.0\n1,1,2\n", "bad.mtx") {
        Err(FeError::Matrix {
            line: 2,
            kind: MatrixFileError::Syntax(_),
            ..
        }) => {}
        other => panic!("{other:?}"),
    }
}

/// VTK export: well-formed XML with one point per node, one cell per element and the mode
/// fields; the data array lengths match the declared counts.
#[test]
fn vtu_export_of_modes() {
    let tire = fe_model::generate::tire(&fe_model::generate::TireConfig {
        circumferential_divisions: 12,
        section_divisions: 8,
        thickness_divisions: 1,
        bead_elements: 1,
        ..Default::default()
    })
    .unwrap();
    let mesh = &tire.model.mesh;
    let v = Mat::from_fn(mesh.n_dofs(), 2, |i, j| (i * (j + 1)) as f64);
    let mut fields =
        vtk::mode_fields(mesh, v.as_ref(), &[1.0, 2.0], vtk::default_layout(3)).unwrap();
    fields.extend(vtk::node_set_fields(mesh));
    let s = vtk::vtu_string(mesh, &fields).unwrap();
    assert!(s.contains(&format!(
        r#"NumberOfPoints="{}" NumberOfCells="{}""#,
        mesh.n_nodes(),
        mesh.cells.len()
    )));
    assert!(s.contains(r#"Name="mode_1_1.0000Hz""#));
    assert!(s.contains(r#"Name="set_rim""#));
    assert_eq!(
        s.matches("<DataArray").count(),
        s.matches("</DataArray>").count()
    );
    // mode 2 of node 5, y component = (3·5+1)·2
    let idx = s.find(r#"Name="mode_2_2.0000Hz""#).unwrap();
    let line = s[idx..].lines().nth(6).unwrap();
    let vals: Vec<f64> = line
        .split_whitespace()
        .map(|t| t.parse().unwrap())
        .collect();
    assert_eq!(vals, vec![30.0, 32.0, 34.0]);
    // wrong row count is an error, not a panic
    let bad = Mat::<f64>::zeros(5, 1);
    assert!(vtk::mode_fields(mesh, bad.as_ref(), &[1.0], vtk::default_layout(3)).is_err());
}
