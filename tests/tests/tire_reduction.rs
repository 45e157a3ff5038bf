//! Reduced FE tire (Ribaric §8.2): exactness of the untruncated reduction against the full FE
//! model, truncation accuracy, statics of the preload, and the reduced-tire file.

use tire::statics::{full_flexibility, reduced_flexibility};
use tire::*;

use crate::common;

/// A coarse generated truck tire (295/80 R22.5 dimensions, 38 psi prestress), 1296 DOF.
fn small() -> TireFe {
    generated_tire(&coarse_tire_config(24, 8, 40.0)).expect("tire")
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn untruncated_reduction_reproduces_the_full_model() {
    let fe = small();
    // reference: the full FE model with the rim fixed (dense eigen solver)
    let full = full_frequencies_hz(&fe, 30).unwrap();
    let cfg = ReductionConfig {
        contact_nodes: 12,
        free_modes: usize::MAX,
        ..Default::default()
    };
    let (red, _) = reduce(&fe, &cfg).unwrap();
    assert_eq!(red.n_z(), fe.n_dofs() - 3 * fe.rim.len());
    let f = red.frequencies_hz().unwrap();
    // issue 9 validation: within 0.1 % (the reduction is exact up to round-off)
    for (i, (a, b)) in f.iter().zip(&full).enumerate() {
        assert!(
            rel(*a, *b) < 1e-6,
            "mode {i}: reduced {a} Hz vs full {b} Hz"
        );
    }
    // realistic range: lowest modes of the truck tire in the tens of Hz
    assert!(
        full[0] > 20.0 && full[0] < 100.0,
        "lowest mode {} Hz",
        full[0]
    );
    // statics of the preload (4448 N on the drum): reduced vs full FE flexibility
    let (y_red, _) = reduced_flexibility(&red).unwrap();
    let y_full = full_flexibility(&fe, &red.contact_nodes).unwrap();
    let g = GroundConfig::default();
    let a = solve_patch(&y_red, &red.contact_positions, &g, 4448.2).unwrap();
    let b = solve_patch(&y_full, &red.contact_positions, &g, 4448.2).unwrap();
    assert!(
        rel(a.deflection, b.deflection) < 1e-2 * 1e-3,
        "deflection {} vs {}",
        a.deflection,
        b.deflection
    );
    assert!(rel(a.force, 4448.2) < 1e-6 && rel(b.force, 4448.2) < 1e-6);
    for (la, lb) in a.lambda.iter().zip(&b.lambda) {
        assert!((la - lb).abs() < 1e-3 * 4448.2, "patch force {la} vs {lb}");
    }
}

#[test]
fn static_modes_keep_patch_statics_exact_under_truncation() {
    // Craig-Bampton property (Ribaric §3.3): loads on the contact nodes are represented exactly
    // by the static modes, so the preload does not depend on the number of free-node modes.
    let fe = small();
    let cfg = ReductionConfig {
        contact_nodes: 12,
        free_modes: 10,
        ..Default::default()
    };
    let (red, _) = reduce(&fe, &cfg).unwrap();
    assert_eq!(red.dof(), 6 + 10 + 36);
    let y_full = full_flexibility(&fe, &red.contact_nodes).unwrap();
    let (y_red, _) = reduced_flexibility(&red).unwrap();
    let g = GroundConfig {
        kind: GroundKind::Road,
        ..Default::default()
    };
    let a = solve_patch(&y_red, &red.contact_positions, &g, 4448.2).unwrap();
    let b = solve_patch(&y_full, &red.contact_positions, &g, 4448.2).unwrap();
    // issue 9: static patch force and deflection within 1 %
    assert!(
        rel(a.deflection, b.deflection) < 1e-6,
        "{} vs {}",
        a.deflection,
        b.deflection
    );
    let pa = preload(&red, &g, 4448.2).unwrap();
    assert!(rel(pa.patch.deflection, b.deflection) < 1e-6);
}

#[test]
fn truncated_reduction_is_accurate_below_240_hz() {
    // 96 x 8 tire (5 184 DOF): full model by the sparse shift-invert solver
    let fe = generated_tire(&coarse_tire_config(96, 8, 20.0)).unwrap();
    let cfg = ReductionConfig {
        contact_nodes: 33,
        free_modes: 50,
        ..Default::default()
    };
    let (red, _) = reduce(&fe, &cfg).unwrap();
    let full = full_frequencies_hz(&fe, 40).unwrap();
    let f = red.frequencies_hz().unwrap();
    let mut checked = 0;
    for (i, b) in full.iter().enumerate().filter(|(_, b)| **b < 240.0) {
        // issue 9: truncated to 50 modes, the frequencies below 240 Hz within 2 %; the reduced
        // ones are Rayleigh-Ritz upper bounds
        assert!(rel(f[i], *b) < 0.02, "mode {i}: {} vs {b} Hz", f[i]);
        assert!(f[i] >= b * (1.0 - 1e-9));
        checked += 1;
    }
    assert!(checked >= 10, "only {checked} modes below 240 Hz");
}

#[test]
fn reduced_tire_file_round_trip_and_errors() {
    let fe = small();
    let cfg = ReductionConfig {
        contact_nodes: 6,
        free_modes: 8,
        ..Default::default()
    };
    let (red, _) = reduce(&fe, &cfg).unwrap();
    let text = red.to_json().unwrap();
    let back = ReducedTire::from_json(&text, "memory").unwrap();
    assert_eq!(back.contact_nodes, red.contact_nodes);
    // JSON keeps 17 significant digits; serde_json's default parser may differ in the last ulp
    let close = |a: &faer::Mat<f64>, b: &faer::Mat<f64>| {
        let scale = (0..b.ncols())
            .flat_map(|j| (0..b.nrows()).map(move |i| (i, j)))
            .fold(0.0f64, |m, (i, j)| m.max(b[(i, j)].abs()));
        (0..b.ncols())
            .all(|j| (0..b.nrows()).all(|i| (a[(i, j)] - b[(i, j)]).abs() <= 1e-14 * scale))
    };
    assert!(
        close(&back.k, &red.k) && close(&back.g1, &red.g1) && close(&back.tc_theta, &red.tc_theta)
    );
    let current = format!("\"version\":{}", tire::reduced::VERSION);
    assert!(text.contains(&current), "the file states its version");
    let bad = text.replacen(&current, "\"version\":99", 1);
    let e = ReducedTire::from_json(&bad, "t.json")
        .unwrap_err()
        .to_string();
    assert!(e.contains("t.json") && e.contains("version"), "{e}");
    let e = reduce(
        &fe,
        &ReductionConfig {
            contact_nodes: 10_000,
            ..Default::default()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("contact_nodes"), "{e}");
}

#[test]
fn rings_are_uniform_circumferential_grids() {
    // Ribaric App. A for the tire: every non-rim node lies on a ring of equal (ρ, y) and the
    // generated mesh spaces each ring uniformly, 2π/24 apart (mesh invariant).
    let fe = small();
    let rings = fe.rings(1e-6).unwrap();
    let on_rings: usize = rings.iter().map(|r| r.nodes.len()).sum();
    assert_eq!(on_rings, fe.n_nodes() - fe.rim.len());
    for r in &rings {
        assert_eq!(r.nodes.len(), 24);
        for w in r.theta.windows(2) {
            assert!((w[1] - w[0] - 2.0 * std::f64::consts::PI / 24.0).abs() < 1e-9);
        }
    }
}

#[test]
fn imported_matrix_market_tire_matches_the_generated_one() {
    // Import path of issue 9 (M, K from Matrix Market with nodes, rim and patch sets): export
    // the generated tire and read it back; the reduced frequencies must agree (same model).
    use fe_model::io::mtx::{Symmetry, write_sparse};
    let fe = small();
    let dir = std::env::temp_dir().join(format!("flowmbd_tire_import_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = |n: &str| dir.join(n).display().to_string();
    write_sparse(p("k.mtx"), fe.stiffness.as_ref(), Symmetry::General).unwrap();
    let mt: Vec<faer::sparse::Triplet<usize, usize, f64>> = fe
        .mass
        .iter()
        .enumerate()
        .map(|(i, &m)| faer::sparse::Triplet::new(i, i, m))
        .collect();
    let m =
        faer::sparse::SparseColMat::try_new_from_triplets(fe.n_dofs(), fe.n_dofs(), &mt).unwrap();
    write_sparse(p("m.mtx"), m.as_ref(), Symmetry::General).unwrap();
    let nodes: String = fe
        .nodes
        .iter()
        .map(|x| format!("{:e}, {:e}, {:e}\n", x[0], x[1], x[2]))
        .collect();
    std::fs::write(p("nodes.csv"), format!("# x, y, z\n{nodes}")).unwrap();
    let list = |v: &[usize]| {
        v.iter()
            .map(|i| i.to_string())
            .collect::<Vec<_>>()
            .join(" ")
    };
    std::fs::write(p("rim.txt"), list(&fe.rim)).unwrap();
    std::fs::write(p("patch.txt"), list(&fe.candidates)).unwrap();
    let files = ImportFiles {
        format: ImportFormat::MatrixMarket,
        stiffness: p("k.mtx"),
        mass: p("m.mtx"),
        nodes: p("nodes.csv"),
        rim_nodes: p("rim.txt"),
        patch_nodes: p("patch.txt"),
    };
    let imp = imported_tire(&files).unwrap();
    // independent reference: the same reduction of the generated model
    common::assert_same_reduced_frequencies(&fe, &imp);
    // a bad coordinate line is reported with file and line
    std::fs::write(p("bad.csv"), "0, 0, 0\n1, x, 2\n").unwrap();
    let e = imported_tire(&ImportFiles {
        nodes: p("bad.csv"),
        ..files
    })
    .unwrap_err()
    .to_string();
    assert!(e.contains("bad.csv:2"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The isotropic truck tire of earlier versions (tread 150 MPa, no carcass cords).
fn isotropic_truck_tire() -> fe_model::generate::TireConfig {
    let mut cfg = fe_model::generate::TireConfig {
        carcass: None,
        ..Default::default()
    };
    cfg.tread.young = 150e6;
    cfg
}

#[test]
#[ignore = "the full 63 936-DOF isotropic truck tire: two reductions and a 110-mode eigen solve, ~2 min"]
fn isotropic_truck_tire_needs_110_modes_for_the_240_hz_band() {
    // Why the default tire has carcass cords. The isotropic tire of earlier versions has 95
    // modes below 240 Hz, about twice Ribaric's tire, whose 50 free-node modes reached 240 Hz.
    // With 50 free-node modes (reaching 190.9 Hz) every full-model mode up to 184 Hz is within
    // 2 %; with 110 (reaching 268 Hz) every mode below 240 Hz is. Reduced frequencies are
    // Rayleigh–Ritz upper bounds of the full ones.
    let fe = generated_tire(&isotropic_truck_tire()).unwrap();
    let full = full_frequencies_hz(&fe, 110).unwrap();
    let below_240 = full.iter().filter(|&&f| f < 240.0).count();
    assert!(below_240 > 90, "{below_240} full-model modes below 240 Hz");
    for (modes, band) in [(50, 184.0), (110, 240.0)] {
        let cfg = ReductionConfig {
            free_modes: modes,
            ..Default::default()
        };
        let f = reduce(&fe, &cfg).unwrap().0.frequencies_hz().unwrap();
        for (i, b) in full.iter().enumerate().filter(|(_, b)| **b < band) {
            assert!(
                rel(f[i], *b) < 0.02,
                "{modes} modes, mode {i}: {} vs {b} Hz",
                f[i]
            );
            assert!(f[i] >= b * (1.0 - 1e-9));
        }
    }
}

#[test]
#[ignore = "the full 63 936-DOF truck tire: reduction and a 60-mode eigen solve, ~1 min"]
fn default_truck_tire_meets_the_50_mode_240_hz_criterion() {
    // Issue 9, "truncated to 50 modes, the frequencies below 240 Hz stay within 2 % of the full
    // model", on the default generated truck tire (carcass cords E_fφ = 5 GPa with their steel
    // mass, tread rubber 50 MPa: 5th mode 64.2 Hz and 49 modes below 240 Hz). Measured:
    // largest error 1.12 % (mode 38).
    let fe = generated_tire(&fe_model::generate::TireConfig::default()).unwrap();
    let full = full_frequencies_hz(&fe, 60).unwrap();
    let below: Vec<(usize, f64)> = full
        .iter()
        .copied()
        .enumerate()
        .filter(|(_, b)| *b < 240.0)
        .collect();
    assert!(
        (45..=50).contains(&below.len()),
        "{} modes below 240 Hz",
        below.len()
    );
    let f = reduce(&fe, &ReductionConfig::default())
        .unwrap()
        .0
        .frequencies_hz()
        .unwrap();
    for (i, b) in below {
        assert!(rel(f[i], b) < 0.02, "mode {}: {} vs {b} Hz", i + 1, f[i]);
        assert!(f[i] >= b * (1.0 - 1e-9));
    }
}
