//! Lin (2005) beam tables (Appendix A, ch. 6, 7.1, 8.5), to the printed digits.
//!
//! Reference values are the dissertation's printed numbers (seed 002), as transcribed in the
//! reading companion `seed-002-lin.md` §6-§10 and §15. Each test names its table or equation.
#![allow(clippy::needless_range_loop)] // index loops mirror the printed tables

use faer::Mat;
use flowmbd_cases::lin::beam::{self, LinBeam, node_dofs};
use reduction::basis::{
    Method, ModeSelection, build_basis, cb_to_mc_x, condensed_modes, static_modes,
};
use reduction::{DofPartition, ReducedModel};

/// Asserts that `actual` rounds to the printed decimal string `printed` (half a unit of its last
/// printed digit, plus `extra` absolute slack).
fn printed(actual: f64, printed: &str, extra: f64, what: &str) {
    let v: f64 = printed.parse().unwrap();
    let mantissa = printed.split(['e', 'E']).next().unwrap();
    let exp: i32 = printed
        .split(['e', 'E'])
        .nth(1)
        .map(|e| e.parse().unwrap())
        .unwrap_or(0);
    let decimals = mantissa.split('.').nth(1).map(|d| d.len()).unwrap_or(0) as i32;
    let tol = 0.5 * 10f64.powi(exp - decimals) * (1.0 + 1e-9) + extra;
    assert!(
        (actual - v).abs() <= tol,
        "{what}: got {actual}, printed {printed} (tol {tol:e})"
    );
}

fn beam() -> LinBeam {
    beam::appendix_a_beam().unwrap()
}

#[test]
fn appendix_a_stiffness_matches_printed_matrix() {
    // Lin Appendix A, condensed K printed to 6 significant figures (tolerance: print rounding).
    let printed_k: [[f64; 10]; 10] = [
        [60000., 0., -60000., 0., 0., 0., 0., 0., 0., 0.],
        [
            0., 321.439, 0., -728.595, 0., 514.302, 0., -128.576, 0., 21.4293,
        ],
        [-60000., 0., 120000., 0., -60000., 0., 0., 0., 0., 0.],
        [
            0., -728.595, 0., 1971.49, 0., -1885.77, 0., 771.453, 0., -128.576,
        ],
        [0., 0., -60000., 0., 120000., 0., -60000., 0., 0., 0.],
        [
            0., 514.302, 0., -1885.77, 0., 2742.94, 0., -1885.77, 0., 514.302,
        ],
        [0., 0., 0., 0., -60000., 0., 120000., 0., -60000., 0.],
        [
            0., -128.576, 0., 771.453, 0., -1885.77, 0., 1971.49, 0., -728.595,
        ],
        [0., 0., 0., 0., 0., 0., -60000., 0., 60000., 0.],
        [
            0., 21.4293, 0., -128.576, 0., 514.302, 0., -728.595, 0., 321.439,
        ],
    ];
    let b = beam();
    for i in 0..10 {
        for j in 0..10 {
            assert!(
                (b.k[(i, j)] - printed_k[i][j]).abs() <= 0.005,
                "K[{i},{j}] = {} vs printed {}",
                b.k[(i, j)],
                printed_k[i][j]
            );
        }
    }
}

#[test]
fn free_free_frequencies() {
    // Lin §6.2.1: 3 rigid-body modes, first bending 5.94776 Hz, first axial 66.7191 Hz,
    // second axial 123.281 Hz.
    let f = beam::free_free_hz(&beam()).unwrap();
    assert_eq!(f.len(), 10);
    for (i, &x) in f.iter().take(3).enumerate() {
        assert!(x < 1e-3, "rigid mode {i}: {x} Hz");
    }
    printed(f[3], "5.94776", 0.0, "first bending");
    printed(f[6], "66.7191", 0.0, "first axial");
    printed(f[7], "123.281", 0.0, "second axial");
}

#[test]
fn guyan_models_a_and_b() {
    let b = beam();
    // Lin §6.2.1 model (a), masters 1, 3, 5: 5.95823, 71.1763, 123.281 Hz
    let a = beam::guyan_hz(&b, &[1, 3, 5]).unwrap();
    printed(a[0], "5.95823", 0.0, "Guyan (a) bending");
    printed(a[1], "71.1763", 0.0, "Guyan (a) axial");
    printed(a[2], "123.281", 0.0, "Guyan (a) second axial");
    // model (b), masters 1, 2, 5: 6.33897, 69.5245 Hz (third printed nowhere)
    let bb = beam::guyan_hz(&b, &[1, 2, 5]).unwrap();
    printed(bb[0], "6.33897", 0.0, "Guyan (b) bending");
    printed(bb[1], "69.5245", 0.0, "Guyan (b) axial");
    // reduced frequencies are upper bounds of the full ones (Lin §6.2.1 conclusion)
    let full = beam::free_free_hz(&b).unwrap();
    assert!(a[0] >= full[3] && bb[0] >= full[3] && a[1] >= full[6] && bb[1] >= full[6]);
}

#[test]
fn guyan_model_c_constraint_modes_are_linear_interpolation() {
    // Lin §6.2.2 / Fig. 6-5: with θ condensed out the constraint modes of masters 1, 5 are the
    // linear interpolation (pinned ends) (note §6.2.2 [R]).
    let b = beam();
    let part = DofPartition::from_boundary_dofs(10, &node_dofs(&[1, 5])).unwrap();
    let ps = static_modes(b.k.as_ref(), &part).unwrap();
    let expect = [
        [0.75, 0., 0.25, 0.],
        [0., 0.75, 0., 0.25],
        [0.5, 0., 0.5, 0.],
        [0., 0.5, 0., 0.5],
        [0.25, 0., 0.75, 0.],
        [0., 0.25, 0., 0.75],
    ];
    for i in 0..6 {
        for j in 0..4 {
            assert!((ps[(i, j)] - expect[i][j]).abs() < 1e-12);
        }
    }
}

#[test]
fn fixed_interface_frequencies() {
    // Lin §7.1/§8.5 and Fig. 6-7: 3.10366 and 12.3283 Hz; the remaining values are the
    // free-free axial frequencies 66.7191, 123.281 (Lin §6.2.1) and 161.074 ([D] companion §14.3).
    let f = beam::fixed_interface_hz(&beam()).unwrap();
    printed(f[0], "3.10366", 0.0, "fixed-interface 1");
    printed(f[1], "12.3283", 0.0, "fixed-interface 2");
    printed(f[3], "66.7191", 0.0, "fixed-interface axial 1");
    printed(f[4], "123.281", 0.0, "fixed-interface axial 2");
}

#[test]
fn mode_condensation_boundary_modes_and_cb_equivalence() {
    // Lin §6.5.3 (Fig. 6-9) boundary modes Ψm; analytic entries (2−√2)/8 and (1−√2)/4
    // (companion §14.3), and the CB ↔ MC change of coordinates X of (6.34).
    let b = beam();
    let part = DofPartition::from_boundary_dofs(10, &node_dofs(&[1, 5])).unwrap();
    let (lam, phi) =
        reduction::basis::fixed_interface_modes(b.k.as_ref(), b.m.as_ref(), &part).unwrap();
    let psim = condensed_modes(b.k.as_ref(), &part, &lam, &phi, &[0, 1]).unwrap();
    let a = (2.0 - 2f64.sqrt()) / 8.0;
    let c = (1.0 - 2f64.sqrt()) / 4.0;
    let expect = [
        [0.75, 0., 0.25, 0.],
        [0., a, 0., a],
        [0.5, 0., 0.5, 0.],
        [0., c, 0., c],
        [0.25, 0., 0.75, 0.],
        [0., a, 0., a],
    ];
    for i in 0..6 {
        for j in 0..4 {
            assert!((psim[(i, j)] - expect[i][j]).abs() < 1e-10, "Ψm[{i},{j}]");
        }
    }
    // Ψs = Ψm + Ψn^k X (Lin (6.34)), residual at round-off
    let ps = static_modes(b.k.as_ref(), &part).unwrap();
    let x = cb_to_mc_x(b.k.as_ref(), &part, &lam, &phi, &[0, 1]).unwrap();
    let phik = Mat::from_fn(6, 2, |i, j| phi[(i, j)]);
    let r = &psim + &phik * &x - &ps;
    assert!(reduction::linalg::max_abs(r.as_ref()) < 1e-12);
    // |X| entries 0.381721, 0.158114 (companion §14.3; sign follows the mode sign)
    printed(x[(0, 1)].abs(), "0.381721", 0.0, "X[1,η1]");
    printed(x[(1, 1)].abs(), "0.158114", 0.0, "X[2,η1]");
}

/// Sign that aligns column `c` of `mine` with the printed column.
fn align(mine: &Mat<f64>, c: usize, printed_col: &[f64]) -> f64 {
    let d: f64 = (0..printed_col.len())
        .map(|i| mine[(i, c)] * printed_col[i])
        .sum();
    d.signum()
}

#[test]
fn profile1_table() {
    let b = beam();
    // Lin (7.2) printed Ψ (10×10), with the typo −1.1103 read as −1.11803 (companion §7.1.1).
    let p: [[f64; 10]; 10] = [
        [1., 0., 0., 0., 0., 0., 0., 0., 0., 0.],
        [0., 1., 0., 0., 0., 0., 0., 0., 0., 0.],
        [
            0., 0., 0., 0., 0., 0., -0.605076, -1.46078, 1.46078, -0.605076,
        ],
        [0., 0., 0., -1.11803, -1.58114, -1.11803, 0., 0., 0., 0.],
        [
            0., 0., 0., 0., 0., 0., -1.11803, -1.11803, -1.11803, 1.11803,
        ],
        [0., 0., 0., -1.58114, 0., 1.58114, 0., 0., 0., 0.],
        [
            0., 0., 0., 0., 0., 0., -1.46078, 0.605076, -0.605076, -1.46078,
        ],
        [0., 0., 0., -1.11803, 1.58114, -1.11803, 0., 0., 0., 0.],
        [0., 0., 0., 0., 0., 0., -1.58114, 1.58114, 1.58114, 1.58114],
        [0., 0., 1., 0., 0., 0., 0., 0., 0., 0.],
    ];
    let psi = beam::simply_supported_basis(&b).unwrap();
    let mut sgn = [1.0; 10];
    for c in 0..10 {
        let col: Vec<f64> = (0..10).map(|i| p[i][c]).collect();
        sgn[c] = align(&psi, c, &col);
        for i in 0..10 {
            printed(
                sgn[c] * psi[(i, c)],
                &format!("{}", p[i][c]),
                0.0,
                &format!("Ψ[{i},{c}]"),
            );
        }
    }
    let study = beam::profile_study(&b).unwrap();
    // (7.3): z = {0, 0, 0, −0.1367, −0.0696, 0.0025, −0.1001, 0.0159, 0.0185, 0.0237}
    let z73 = [
        "0", "0", "0", "-0.1367", "-0.0696", "0.0025", "-0.1001", "0.0159", "0.0185", "0.0237",
    ];
    for c in 0..10 {
        printed(
            sgn[c] * study.z_simply_supported[c],
            z73[c],
            0.0,
            &format!("z[{c}] (7.3)"),
        );
    }
    // Profile 1 table: δ*_MT, δ*_CB = δ*_MC
    let mt = [
        "0",
        "0",
        "0",
        "0.262782",
        "0",
        "0.216066",
        "0",
        "0.0427817",
        "0.25",
        "0",
    ];
    let cb = [
        "0",
        "0",
        "0.0625",
        "0.262782",
        "0.125",
        "0.216066",
        "0.1875",
        "0.0427817",
        "0.25",
        "0",
    ];
    for i in 0..10 {
        printed(study.profile1[0].delta[i], mt[i], 0.0, "profile 1 δ*_MT");
        printed(study.profile1[1].delta[i], cb[i], 0.0, "profile 1 δ*_CB");
        printed(study.profile1[2].delta[i], cb[i], 0.0, "profile 1 δ*_MC");
    }
    // errors 0.1569 / 0.0826 / 0.0826 (full precision 0.156943 / 0.0825739, companion §14.4)
    printed(study.profile1[0].error, "0.1569", 0.0, "profile 1 error MT");
    printed(study.profile1[1].error, "0.0826", 0.0, "profile 1 error CB");
    printed(study.profile1[2].error, "0.0826", 0.0, "profile 1 error MC");
    printed(
        study.profile1[0].error,
        "0.156943",
        0.0,
        "profile 1 error MT (6 digits)",
    );
    printed(
        study.profile1[1].error,
        "0.0825739",
        0.0,
        "profile 1 error CB (6 digits)",
    );
}

#[test]
fn profile2_table() {
    let b = beam();
    let study = beam::profile_study(&b).unwrap();
    // sign of the kept first/second bending modes relative to the printed ones
    // (η2, η3, η4) = (−1.11803, −1.58114, −1.11803) and (−1.58114, 0, 1.58114) (Lin (7.2)).
    let mt = &study.bases[0];
    let s1 = (mt[3][4] * -1.11803 + mt[5][4] * -1.58114 + mt[7][4] * -1.11803).signum();
    let s2 = (mt[3][5] * -1.58114 + mt[7][5] * 1.58114).signum();
    let sg = [1.0, 1.0, 1.0, 1.0, s1, s2];
    // best-fit modal coordinates table (Lin §7.1.2)
    let z_mt = ["0", "0", "0.25", "0", "-0.136652", "-0.0695701"];
    let z_cb = [
        "-0.01",
        "-0.000781244",
        "0.214",
        "-0.000781244",
        "-0.137249",
        "-0.0695701",
    ];
    let z_mc = [
        "-0.01",
        "-0.000781244",
        "0.214",
        "-0.000781244",
        "-0.136652",
        "-0.0695701",
    ];
    for j in 0..6 {
        printed(sg[j] * study.profile2[0].z[j], z_mt[j], 1e-9, "z*_MT");
        printed(sg[j] * study.profile2[1].z[j], z_cb[j], 1e-9, "z*_CB");
        printed(sg[j] * study.profile2[2].z[j], z_mc[j], 1e-9, "z*_MC");
    }
    // best-fit nodal deflections
    let d_mt = [
        "0",
        "0",
        "0",
        "0.262782",
        "0",
        "0.216066",
        "0",
        "0.0427817",
        "0.25",
        "0",
    ];
    let d_cb = [
        "-0.01",
        "-0.000781244",
        "0.046",
        "0.262667",
        "0.102",
        "0.216228",
        "0.158",
        "0.0426673",
        "0.214",
        "-0.000781244",
    ];
    for i in 0..10 {
        printed(study.profile2[0].delta[i], d_mt[i], 1e-9, "δ*_MT");
        printed(study.profile2[1].delta[i], d_cb[i], 1e-9, "δ*_CB");
        printed(study.profile2[2].delta[i], d_cb[i], 1e-9, "δ*_MC");
        // same column space ⇒ identical fits (Lin §6.5.4)
        assert!((study.profile2[1].delta[i] - study.profile2[2].delta[i]).abs() < 1e-12);
    }
    printed(study.profile2[0].error, "0.1569", 0.0, "profile 2 error MT");
    printed(study.profile2[1].error, "0.0612", 0.0, "profile 2 error CB");
    printed(study.profile2[2].error, "0.0612", 0.0, "profile 2 error MC");
    printed(
        study.profile2[1].error,
        "0.0612346",
        0.0,
        "profile 2 error CB (7 digits)",
    );
}

#[test]
fn eitelberg_equals_guyan_a() {
    // Lin §6.6.4: b = nodes 1, 3, 5, L = [I6 I6]; printed M_⁻¹K_ and frequencies
    // 5.95823, 71.1763, 123.281 Hz (identical to Guyan (a)).
    let b = beam();
    let bd = node_dofs(&[1, 3, 5]);
    let (mk, _) =
        reduction::eitelberg::eitelberg_structure(b.k.as_ref(), b.m.as_ref(), &bd).unwrap();
    let pr: [[&str; 6]; 6] = [
        ["2.5e+005", "0", "-3e+005", "0", "50000", "0"],
        ["0", "416.07", "0", "-832.14", "0", "416.07"],
        ["-1.5e+005", "0", "3e+005", "0", "-1.5e+005", "0"],
        ["0", "-284.68", "0", "569.36", "0", "-284.68"],
        ["50000", "0", "-3e+005", "0", "2.5e+005", "0"],
        ["0", "416.07", "0", "-832.14", "0", "416.07"],
    ];
    for i in 0..6 {
        for j in 0..6 {
            // slack: 1e-5 of the largest entry for the Lyapunov conditioning (companion §12)
            let v: f64 = pr[i][j].parse().unwrap();
            let extra = if v.abs() >= 1e4 { 1e-5 * 3e5 } else { 0.0 };
            printed(
                mk[(i, j)],
                pr[i][j],
                extra,
                &format!("Eitelberg M⁻¹K[{i},{j}]"),
            );
        }
    }
    let ev = mk.eigenvalues().unwrap();
    let mut hz: Vec<f64> = ev
        .iter()
        .map(|z| z.re.max(0.0).sqrt() / (2.0 * std::f64::consts::PI))
        .collect();
    hz.sort_by(|a, b| a.partial_cmp(b).unwrap());
    printed(hz[3], "5.95823", 0.0, "Eitelberg bending");
    printed(hz[4], "71.1763", 0.0, "Eitelberg axial");
    printed(hz[5], "123.281", 0.0, "Eitelberg axial 2");
}

#[test]
fn mean_axes_constraint_modes_with_mode_condensation() {
    // Lin (8.44): printed [Δr;Δθ;Δz]^c_MC and [Δd]^c_MC = [I; Ψs].
    let b = beam();
    let ev = beam::mean_axes_study(&b, Method::ModeCondensation).unwrap();
    let c: [[f64; 4]; 9] = [
        [0.5, 0., 0.5, 0.],
        [0., 0.5, 0., 0.5],
        [0., -1., 0., 1.],
        [0.5, 0., -0.5, 0.],
        [0., 0., 0., 0.],
        [-0.5, 0., 0.5, 0.],
        [0., 0., 0., 0.],
        [0., 0., 0., 0.],
        [0., 0., 0., 0.],
    ];
    // rows 0..3 are Δr, Δθ (sign-free); rows 3.. are Δz whose axial entries do not depend on
    // the sign of the bending modes (their rows 7, 8 are zero).
    for i in 0..9 {
        for j in 0..4 {
            assert!(
                (ev.constraint_coordinates[(i, j)] - c[i][j]).abs() < 1e-10,
                "[Δr;Δθ;Δz]^c[{i},{j}] = {}",
                ev.constraint_coordinates[(i, j)]
            );
        }
    }
    let d: [[f64; 4]; 10] = [
        [1., 0., 0., 0.],
        [0., 1., 0., 0.],
        [0.75, 0., 0.25, 0.],
        [0., 0.75, 0., 0.25],
        [0.5, 0., 0.5, 0.],
        [0., 0.5, 0., 0.5],
        [0.25, 0., 0.75, 0.],
        [0., 0.25, 0., 0.75],
        [0., 0., 1., 0.],
        [0., 0., 0., 1.],
    ];
    for i in 0..10 {
        for j in 0..4 {
            assert!((ev.constraint_modes[(i, j)] - d[i][j]).abs() < 1e-10);
        }
    }
}

fn check_normal_modes(method: Method) {
    // Lin (8.45): exactly two non-zero frequencies 3.10366 and 12.3283 Hz; vectors ∝ printed
    // (sign and scale free), [Δd]^n ∝ printed.
    let b = beam();
    let ev = beam::mean_axes_study(&b, method).unwrap();
    assert_eq!(ev.normal_frequencies_hz.len(), 2);
    printed(
        ev.normal_frequencies_hz[0],
        "3.10366",
        0.0,
        "mean-axes mode 1",
    );
    printed(
        ev.normal_frequencies_hz[1],
        "12.3283",
        0.0,
        "mean-axes mode 2",
    );
    let dd: [[f64; 10]; 2] = [
        [0., 0., 0., 1.1716, 0., 1.6569, 0., 1.1716, 0., 0.],
        [0., 0., 0., 0.75, 0., 0., 0., -0.75, 0., 0.],
    ];
    for (m, col) in dd.iter().enumerate() {
        // align sign and scale on the largest printed entry
        let (imax, _) =
            col.iter().enumerate().fold(
                (0, 0.0),
                |a, (i, &v)| if v.abs() > a.1 { (i, v.abs()) } else { a },
            );
        let scale = col[imax] / ev.normal_modes[(imax, m)];
        for i in 0..10 {
            printed(
                scale * ev.normal_modes[(i, m)],
                &format!("{}", col[i]),
                0.0,
                "[Δd]^n",
            );
        }
    }
    if method == Method::ModeCondensation {
        let q: [[f64; 9]; 2] = [
            [0., 1., 0., 0., -1., 0., -1., -0.28445, 0.],
            [0., 0., -1., 0., -0.5, 0., 0.5, 0., -0.31623],
        ];
        for (m, col) in q.iter().enumerate() {
            // Δr_η (mode 1) and Δθ (mode 2) are independent of the kept-mode sign convention
            let piv = if m == 0 { 1 } else { 2 };
            let scale = col[piv] / ev.normal_coordinates[(piv, m)];
            for i in 0..4 {
                printed(
                    scale * ev.normal_coordinates[(i, m)],
                    &format!("{}", col[i]),
                    0.0,
                    "[Δr;Δθ;Δz]^n",
                );
            }
            // Δz entries up to the sign of the kept-mode columns (companion §8.5 [R])
            for i in 4..9 {
                printed(
                    (scale * ev.normal_coordinates[(i, m)]).abs(),
                    &format!("{}", col[i].abs()),
                    0.0,
                    "|Δz|^n",
                );
            }
        }
    }
}

#[test]
fn mean_axes_normal_modes_with_mode_condensation() {
    check_normal_modes(Method::ModeCondensation);
}

#[test]
fn mean_axes_with_craig_bampton_gives_same_results() {
    // Lin §8.5: "also true for CB" (companion V-CH8-CB)
    check_normal_modes(Method::CraigBampton);
    let b = beam();
    let cb = beam::mean_axes_study(&b, Method::CraigBampton).unwrap();
    let mc = beam::mean_axes_study(&b, Method::ModeCondensation).unwrap();
    let diff = &cb.constraint_modes - &mc.constraint_modes;
    assert!(reduction::linalg::max_abs(diff.as_ref()) < 1e-10);
}

#[test]
fn chapter8_preconditions_on_beam() {
    // Lin §8.1/§8.2.1 (companion V-MA-PRE): CB, MC and Guyan contain the 3 rigid modes; Lin's
    // fixed-interface "modal truncation" does not.
    let b = beam();
    let s = beam::mass_centre_positions(&b);
    let part = DofPartition::from_boundary_dofs(10, &node_dofs(&[1, 5])).unwrap();
    for (method, pass) in [
        (Method::CraigBampton, true),
        (Method::ModeCondensation, true),
        (Method::Guyan, true),
        (Method::FixedInterfaceModalTruncation, false),
    ] {
        let basis = build_basis(
            b.k.as_ref(),
            b.m.as_ref(),
            &part,
            method,
            &ModeSelection::Lowest(2),
        )
        .unwrap();
        let rep = reduction::axes::check_mean_axes_preconditions(
            b.k.as_ref(),
            b.m.as_ref(),
            basis.psi.as_ref(),
            &s,
            2,
        )
        .unwrap();
        assert_eq!(rep.passes, pass, "{method:?}: {rep:?}");
        if pass {
            assert_eq!(rep.n_zero_eigenvalues, 3);
        }
    }
}

#[test]
fn reduced_model_round_trip_and_guyan_a_matrices() {
    // Guyan (a) reduced matrices (companion §14.2 [D], consistent with the printed Eitelberg
    // matrix): MG[0,0] = 0.15, MG[1,1] = 0.134766, KG axial 30000·[1 −1 0; …].
    let b = beam();
    let part = DofPartition::from_boundary_dofs(10, &node_dofs(&[1, 3, 5])).unwrap();
    let basis = build_basis(
        b.k.as_ref(),
        b.m.as_ref(),
        &part,
        Method::Guyan,
        &ModeSelection::Lowest(0),
    )
    .unwrap();
    let red = ReducedModel::from_basis(basis, b.k.as_ref(), b.m.as_ref(), None, 2).unwrap();
    printed(red.mass[(0, 0)], "0.15", 1e-12, "MG[ξ1,ξ1]");
    printed(red.mass[(1, 1)], "0.134766", 0.0, "MG[η1,η1]");
    printed(red.mass[(1, 5)], "-0.015234", 0.0, "MG[η1,η5]");
    printed(red.stiffness[(0, 2)], "-30000", 1e-6, "KG[ξ1,ξ3]");
    printed(red.stiffness[(1, 1)], "37.5012", 0.0, "KG[η1,η1]");
    let dir = std::env::temp_dir().join(format!("flowmbd-red-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("guyan_a.json");
    red.save(&path).unwrap();
    let back = ReducedModel::load(&path).unwrap();
    assert_eq!(back.columns, red.columns);
    assert_eq!(back.n_full(), 10);
    let d = &back.stiffness - &red.stiffness;
    assert_eq!(reduction::linalg::max_abs(d.as_ref()), 0.0);
    // version mismatch is rejected with a message naming the field
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("\"version\":1", "\"version\":99");
    let err = ReducedModel::from_json(&text, "x.json")
        .unwrap_err()
        .to_string();
    assert!(err.contains("version") && err.contains("x.json"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn adaptation_of_modal_coordinates_cancels_the_frame_motion() {
    // Lin (8.13), (8.21): Ψ x = −(Ih Δr + s̆ Δθ) for the MC basis of §8.5 (2-D: Δr_ξ, Δr_η, Δθ).
    let b = beam();
    let part = DofPartition::from_boundary_dofs(10, &node_dofs(&[1, 5])).unwrap();
    let basis = build_basis(
        b.k.as_ref(),
        b.m.as_ref(),
        &part,
        Method::ModeCondensation,
        &ModeSelection::Lowest(2),
    )
    .unwrap();
    let s = beam::mass_centre_positions(&b);
    let rigid = [0.01, -0.02, 0.03];
    let x = reduction::axes::adapting_vector(
        b.k.as_ref(),
        b.m.as_ref(),
        basis.psi.as_ref(),
        &s,
        2,
        &rigid,
    )
    .unwrap();
    let p = reduction::axes::rigid_body_modes(&s, 2).unwrap();
    for i in 0..10 {
        let px: f64 = (0..6).map(|j| basis.psi[(i, j)] * x[j]).sum();
        let pr: f64 = (0..3).map(|j| p[(i, j)] * rigid[j]).sum();
        assert!((px + pr).abs() < 1e-12, "row {i}: Ψx = {px}, −Pθ = {}", -pr);
    }
    // fixed-interface "modal truncation" fails the preconditions (Lin §8.1)
    let mt = build_basis(
        b.k.as_ref(),
        b.m.as_ref(),
        &part,
        Method::FixedInterfaceModalTruncation,
        &ModeSelection::Lowest(2),
    )
    .unwrap();
    assert!(
        reduction::axes::adapting_vector(
            b.k.as_ref(),
            b.m.as_ref(),
            mt.psi.as_ref(),
            &s,
            2,
            &rigid
        )
        .is_err()
    );
}
