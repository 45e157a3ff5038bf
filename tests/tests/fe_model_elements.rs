//! fe-model validation: string, bar and 2D frame elements, assembly, Rayleigh damping and the
//! dense generalized eigen solver, against seed tables and closed-form solutions.

use faer::{Mat, MatRef};
use fe_model::element::frame2d::Frame2dSection;
use fe_model::element::{Element, Frame2d, MassKind, MatrixKind};
use fe_model::generate::{straight_beam_2d, straight_string};
use fe_model::{DofSplit, Rayleigh, dense_modes};
use std::f64::consts::PI;

fn dense(a: &faer::sparse::SparseColMat<usize, f64>) -> Mat<f64> {
    a.to_dense()
}

/// Lowest `count` modes of (K, M) with DOFs `fixed` eliminated.
fn fixed_modes(k: MatRef<f64>, m: MatRef<f64>, fixed: &[usize], count: usize) -> fe_model::Modes {
    let p = DofSplit::fixed(k.nrows(), fixed).unwrap();
    let kff = p.dense_block(k, false, false).unwrap();
    let mff = p.dense_block(m, false, false).unwrap();
    dense_modes(kff.as_ref(), mff.as_ref(), count).unwrap()
}

/// Lin Appendix A beam: 4 EB elements, E = 3e6 Pa, b×h = 0.1×0.05 m, I = 1.0417e-6 m⁴ (the
/// rounded value, seed-002 note §10), L = 1 m, rotations condensed out (Guyan on θ).
fn lin_condensed_k() -> Mat<f64> {
    let section = Frame2dSection {
        ea: 3.0e6 * 0.005,
        ei: 3.0e6 * 1.0417e-6,
        mass_per_length: 0.0,
    };
    let model = straight_beam_2d(1.0, 4, section, 0.0).unwrap();
    let k = dense(&model.stiffness().unwrap());
    // θ DOFs = local 2 of every node; masters (ξ, η) in node order
    let theta: Vec<usize> = (0..5).map(|n| model.mesh.dof(n, 2)).collect();
    let p = DofSplit::new(15, &theta).unwrap();
    let krr = p.dense_block(k.as_ref(), false, false).unwrap();
    let krt = p.dense_block(k.as_ref(), false, true).unwrap();
    let ktt = p.dense_block(k.as_ref(), true, true).unwrap();
    let ktr = p.dense_block(k.as_ref(), true, false).unwrap();
    use faer::linalg::solvers::Solve;
    let x = ktt.partial_piv_lu().solve(&ktr);
    &krr - &krt * &x
}

#[test]
fn lin_appendix_a_condensed_stiffness_matches_printed_matrix() {
    // Lin Appendix A, printed condensed K (6 significant figures), DOF order ξ1, η1, ..., ξ5, η5
    let printed: [[f64; 10]; 10] = [
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
    let k = lin_condensed_k();
    for i in 0..10 {
        for j in 0..10 {
            let p = printed[i][j];
            // half a unit of the 6th significant digit
            let tol = if p == 0.0 {
                1e-9
            } else {
                0.5 * 10f64.powf(p.abs().log10().floor() - 5.0)
            };
            assert!(
                (k[(i, j)] - p).abs() <= tol * 1.0001,
                "K[{i},{j}] = {} vs printed {p}",
                k[(i, j)]
            );
        }
    }
    // full-precision entries reproduced in seed-002 note §10
    assert!((k[(1, 1)] - 321.438857).abs() < 1e-6);
    assert!((k[(5, 5)] - 2742.944914).abs() < 1e-6);
    assert!((k[(1, 3)] + 728.594743).abs() < 1e-6);
}

#[test]
fn lin_appendix_a_free_free_frequencies() {
    // Lin §6.2.1: first bending 5.94776 Hz, first axial 66.7191 Hz, second axial 123.281 Hz;
    // masses 0.1, 0.2, 0.2, 0.2, 0.1 kg on both translations (Table A-1)
    let k = lin_condensed_k();
    let masses = [0.1, 0.2, 0.2, 0.2, 0.1];
    let m = Mat::from_fn(10, 10, |i, j| if i == j { masses[i / 2] } else { 0.0 });
    let modes = dense_modes(k.as_ref(), m.as_ref(), 10).unwrap();
    // three rigid modes
    for f in &modes.frequencies_hz[..3] {
        assert!(f.abs() < 1e-4, "rigid mode at {f} Hz");
    }
    let f = &modes.frequencies_hz;
    // to the printed digits: within half a unit of the last printed digit
    assert!((f[3] - 5.94776).abs() <= 0.5e-5, "bending 1: {}", f[3]);
    assert!((f[6] - 66.7191).abs() <= 0.5e-4, "axial 1: {}", f[6]);
    assert!((f[7] - 123.281).abs() <= 0.5e-3, "axial 2: {}", f[7]);
    // M-orthonormality and residual invariants
    let phi = &modes.vectors;
    let g = phi.transpose() * &m * phi;
    for i in 0..10 {
        for j in 0..10 {
            let e = if i == j { 1.0 } else { 0.0 };
            assert!((g[(i, j)] - e).abs() < 1e-12);
        }
    }
}

/// Cantilever Euler–Bernoulli beam, consistent mass: ω_n = (β_n L)² √(EI/(ρA L⁴)) with
/// β_n L = 1.87510407, 4.69409113, 7.85475744, 10.99554073 (Blevins, Table 8-1).
#[test]
fn cantilever_frequencies_converge_to_euler_bernoulli() {
    let sec = Frame2dSection {
        ea: 1e8,
        ei: 2.0e3,
        mass_per_length: 7.8,
    };
    let l = 2.0;
    let beta_l = [1.875_104_07, 4.694_091_13, 7.854_757_44, 10.995_540_73];
    let mut prev_err = f64::INFINITY;
    for n_el in [4usize, 8, 16, 32] {
        let model = straight_beam_2d(l, n_el, sec, 0.0).unwrap();
        let (k, m) = model.k_and_m(MassKind::Consistent, false).unwrap();
        let fixed: Vec<usize> = model.mesh.node_dofs(0).collect();
        let modes = fixed_modes(dense(&k).as_ref(), dense(&m).as_ref(), &fixed, 20);
        // bending modes only (axial modes are far above with EA = 1e8)
        let exact: Vec<f64> = beta_l
            .iter()
            .map(|b| b * b * (sec.ei / (sec.mass_per_length * l.powi(4))).sqrt())
            .collect();
        let om = modes.omegas();
        let err = (om[0] - exact[0]).abs() / exact[0];
        assert!(err < prev_err, "no convergence at {n_el} elements");
        prev_err = err;
        if n_el == 32 {
            for i in 0..4 {
                let e = (om[i] - exact[i]).abs() / exact[i];
                assert!(e < 1e-5, "mode {i}: {} vs {} (rel {e})", om[i], exact[i]);
            }
        }
    }
}

/// Free-free EB beam: three rigid modes, then β_n L = 4.73004074, 7.85320462, 10.9956078.
#[test]
fn free_free_beam_frequencies_converge_to_euler_bernoulli() {
    let sec = Frame2dSection {
        ea: 1e7,
        ei: 1.0e3,
        mass_per_length: 2.0,
    };
    let l = 3.0;
    let model = straight_beam_2d(l, 40, sec, 0.0).unwrap();
    let (k, m) = model.k_and_m(MassKind::Consistent, false).unwrap();
    let modes = dense_modes(dense(&k).as_ref(), dense(&m).as_ref(), 6).unwrap();
    let om = modes.omegas();
    let scale = (sec.ei / (sec.mass_per_length * l.powi(4))).sqrt();
    for w in &om[..3] {
        // rigid modes are zero up to round-off √(ε λ_max), far below the first elastic mode
        assert!(w.abs() < 1e-3 * om[3], "rigid mode ω = {w}");
    }
    for (i, b) in [4.730_040_74, 7.853_204_62, 10.995_607_8]
        .iter()
        .enumerate()
    {
        let exact = b * b * scale;
        let e = (om[3 + i] - exact).abs() / exact;
        assert!(e < 1e-5, "free-free mode {i}: rel err {e}");
    }
}

/// Ribaric §6 belt span: L = 0.45 m, EI = 2.6e-2 N m², EA = 152000 N, ρA = 0.096 kg/m,
/// T0 = 310 N. Pinned–pinned tensioned beam: f_n = n/(2L) √(T/ρA) √(1 + (nπ)² EI/(T L²))
/// (Rao, *Vibration of Continuous Systems*, §11.5): 63.27, 127.31, 192.87 Hz with K_G; without
/// it f_n = (nπ/L)² √(EI/ρA)/2π: 4.04, 16.15, 36.33 Hz (seed-000 note, BELT-2).
#[test]
fn prestressed_pinned_span_matches_tensioned_beam_formula() {
    let sec = Frame2dSection {
        ea: 152_000.0,
        ei: 2.6e-2,
        mass_per_length: 0.096,
    };
    let (l, t) = (0.45, 310.0);
    let model = straight_beam_2d(l, 60, sec, t).unwrap();
    let end = model.mesh.node_set("end").unwrap()[0];
    let fixed = [
        model.mesh.dof(0, 0),
        model.mesh.dof(0, 1),
        model.mesh.dof(end, 1),
    ];
    for with_kg in [true, false] {
        let (k, m) = model.k_and_m(MassKind::Consistent, with_kg).unwrap();
        let modes = fixed_modes(dense(&k).as_ref(), dense(&m).as_ref(), &fixed, 3);
        for n in 1..=3 {
            let nf = n as f64;
            let exact = if with_kg {
                nf / (2.0 * l)
                    * (t / sec.mass_per_length).sqrt()
                    * (1.0 + (nf * PI).powi(2) * sec.ei / (t * l * l)).sqrt()
            } else {
                (nf * PI / l).powi(2) * (sec.ei / sec.mass_per_length).sqrt() / (2.0 * PI)
            };
            let f = modes.frequencies_hz[n - 1];
            assert!(
                (f - exact).abs() / exact < 2e-5,
                "K_G={with_kg} mode {n}: {f} Hz vs {exact} Hz"
            );
        }
        if with_kg {
            assert!((modes.frequencies_hz[0] - 63.27).abs() < 0.01);
        } else {
            assert!((modes.frequencies_hz[0] - 4.04).abs() < 0.01);
        }
    }
}

/// Ribaric (4.1) string, fixed ends: the discrete (lumped) chain has exactly
/// ω_k² = (4 T0/(ρA h²)) sin²(kπ/(2(n+1))) (Rayleigh's beaded string); assembled elements and
/// the closed-form (4.1) matrices must agree with it and with each other.
#[test]
fn ribaric_string_matches_beaded_string_formula() {
    let (n, l, t, rho) = (60usize, 0.45, 310.0, 0.096);
    let h = l / (n as f64 + 1.0);
    let (m41, k41) = fe_model::element::string::ribaric_string_matrices(n, l, t, rho).unwrap();
    let model = straight_string(l, n + 1, t, rho).unwrap();
    let (k, m) = model.k_and_m(MassKind::Lumped, false).unwrap();
    let (k, m) = (dense(&k), dense(&m));
    // K identical; lumped M equal on interior nodes (ends differ by design: seed note U3)
    for i in 0..n + 2 {
        for j in 0..n + 2 {
            assert!((k[(i, j)] - k41[(i, j)]).abs() < 1e-9 * t / h);
        }
    }
    for i in 1..=n {
        assert!((m[(i, i)] - m41[(i, i)]).abs() < 1e-15);
    }
    let fixed = [0, n + 1];
    let modes = fixed_modes(k41.as_ref(), m41.as_ref(), &fixed, n);
    for kk in 1..=n {
        let exact =
            4.0 * t / (rho * h * h) * (kk as f64 * PI / (2.0 * (n as f64 + 1.0))).sin().powi(2);
        assert!((modes.values[kk - 1] - exact).abs() < 1e-10 * exact);
    }
    // continuum limit: f1 → √(T/ρA)/(2L) = 63.14 Hz (seed-000 note §6 derived values)
    assert!((modes.frequencies_hz[0] - 63.14).abs() < 0.05);
}

/// Axial bar fixed–free, consistent mass: the uniform discrete chain has exactly
/// ω_k² = (6c²/h²)(1 − cos θ_k)/(2 + cos θ_k), θ_k = (2k−1)π/(2n), c² = EA/ρA (difference
/// equation of the assembled pencil), and it converges to ω_k = (2k−1)π/(2L) c (Rao §9.3).
#[test]
fn bar_fixed_free_converges() {
    use fe_model::element::Bar;
    let (l, ea, rho, n) = (2.0, 2.1e8, 7.85, 50usize);
    let mut els: Vec<Box<dyn Element>> = Vec::new();
    for e in 0..n {
        let xa = [e as f64 * l / n as f64, 0.0, 0.0];
        let xb = [(e + 1) as f64 * l / n as f64, 0.0, 0.0];
        els.push(Box::new(
            Bar::new(&[e], &[e + 1], xa, xb, ea, rho, 0.0).unwrap(),
        ));
    }
    let k = dense(&fe_model::assemble(n + 1, &els, MatrixKind::Stiffness).unwrap());
    let m =
        dense(&fe_model::assemble(n + 1, &els, MatrixKind::Mass(MassKind::Consistent)).unwrap());
    let modes = fixed_modes(k.as_ref(), m.as_ref(), &[0], 3);
    let om = modes.omegas();
    let c2 = ea / rho;
    let h = l / n as f64;
    for kk in 1..=3 {
        let th = (2.0 * kk as f64 - 1.0) * PI / (2.0 * n as f64);
        let discrete = 6.0 * c2 / (h * h) * (1.0 - th.cos()) / (2.0 + th.cos());
        assert!(
            (modes.values[kk - 1] - discrete).abs() < 1e-10 * discrete,
            "bar mode {kk}"
        );
        let exact = (2.0 * kk as f64 - 1.0) * PI / (2.0 * l) * c2.sqrt();
        // continuum error of the linear element ≈ θ²/24 (≤ 1.03e-3 here)
        assert!((om[kk - 1] - exact).abs() / exact < 1.5e-3, "bar mode {kk}");
    }
}

/// A rotated 2D bar/frame: element matrices are invariant (rigid-body modes stay zero-energy
/// and the geometric stiffness of a bar has no axial component).
#[test]
fn rotated_elements_keep_rigid_modes() {
    let sec = Frame2dSection {
        ea: 1e6,
        ei: 50.0,
        mass_per_length: 1.0,
    };
    let a = 0.7f64;
    let f = Frame2d::new(
        [0, 1, 2, 3, 4, 5],
        [0.3, -0.2],
        [0.3 + a.cos(), -0.2 + a.sin()],
        sec,
        0.0,
    )
    .unwrap();
    let k = f.stiffness();
    // rigid translation x, y and rotation about node a
    let rig = [
        [1.0, 0.0, 0.0, 1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0, -a.sin(), a.cos(), 1.0],
    ];
    for r in rig {
        let x = Mat::from_fn(6, 1, |i, _| r[i]);
        let y = &k * &x;
        for i in 0..6 {
            assert!(y[(i, 0)].abs() < 1e-8 * 1e6, "rigid mode not zero-energy");
        }
    }
    // rotated mass keeps total mass in both directions: uᵀ M u = ρA L for unit translation
    for kind in [MassKind::Consistent, MassKind::Lumped] {
        let m = f.mass(kind);
        for r in &rig[..2] {
            let x = Mat::from_fn(6, 1, |i, _| r[i]);
            let e = (x.transpose() * &m * &x)[(0, 0)];
            assert!((e - 1.0).abs() < 1e-12);
        }
    }
}

/// Rayleigh coefficients from two modal ratios reproduce those ratios, and C = αM + βK is
/// diagonal in the modal basis with 2ζω on the diagonal (Chopra (11.4.9)).
#[test]
fn rayleigh_damping_from_two_ratios() {
    let sec = Frame2dSection {
        ea: 1e7,
        ei: 1e3,
        mass_per_length: 3.0,
    };
    let model = straight_beam_2d(2.0, 10, sec, 0.0).unwrap();
    let (k, m) = model.k_and_m(MassKind::Consistent, false).unwrap();
    let fixed: Vec<usize> = model.mesh.node_dofs(0).collect();
    let modes = fixed_modes(dense(&k).as_ref(), dense(&m).as_ref(), &fixed, 5);
    let om = modes.omegas();
    let r = Rayleigh::from_modal_ratios(om[0], 0.02, om[2], 0.05).unwrap();
    assert!((r.ratio(om[0]) - 0.02).abs() < 1e-14);
    assert!((r.ratio(om[2]) - 0.05).abs() < 1e-14);
    let c = r.matrix(&m, &k).unwrap();
    let p = DofSplit::fixed(k.nrows(), &fixed).unwrap();
    let cff = p.dense_block(c.to_dense().as_ref(), false, false).unwrap();
    let g = modes.vectors.transpose() * &cff * &modes.vectors;
    for i in 0..5 {
        let expect = 2.0 * r.ratio(om[i]) * om[i];
        assert!((g[(i, i)] - expect).abs() < 1e-8 * expect);
        for j in 0..5 {
            if i != j {
                assert!(g[(i, j)].abs() < 1e-8 * expect);
            }
        }
    }
    // same ω twice is a typed error, not a panic
    assert!(Rayleigh::from_modal_ratios(10.0, 0.1, 10.0, 0.2).is_err());
}

/// Dense solver invariants on a generic pencil: residual, M-orthonormality, ascending order,
/// sign convention; non-SPD M is a typed error.
#[test]
fn dense_solver_invariants_and_errors() {
    let n = 30;
    let k = Mat::from_fn(n, n, |i, j| {
        if i == j {
            2.0 + i as f64 * 0.1
        } else if i.abs_diff(j) == 1 {
            -1.0
        } else {
            0.0
        }
    });
    let m = Mat::from_fn(n, n, |i, j| {
        if i == j {
            1.0 + (i % 3) as f64
        } else if i.abs_diff(j) == 1 {
            0.2
        } else {
            0.0
        }
    });
    let modes = dense_modes(k.as_ref(), m.as_ref(), 10).unwrap();
    assert_eq!(modes.len(), 10);
    for w in modes.values.windows(2) {
        assert!(w[0] <= w[1]);
    }
    let phi = &modes.vectors;
    let r = &k * phi
        - &m * phi * faer::Mat::from_fn(10, 10, |i, j| if i == j { modes.values[i] } else { 0.0 });
    assert!(r.norm_max() < 1e-12);
    for j in 0..10 {
        let col: Vec<f64> = (0..n).map(|i| phi[(i, j)]).collect();
        let imax = (0..n)
            .max_by(|&a, &b| col[a].abs().total_cmp(&col[b].abs()))
            .unwrap();
        assert!(col[imax] > 0.0);
    }
    let mut bad = m.clone();
    bad[(3, 3)] = -1.0;
    assert!(matches!(
        dense_modes(k.as_ref(), bad.as_ref(), 3),
        Err(fe_model::FeError::NotPositiveDefinite { .. })
    ));
    assert!(dense_modes(k.as_ref(), Mat::<f64>::zeros(3, 3).as_ref(), 3).is_err());
}
