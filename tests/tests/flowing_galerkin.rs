//! The analytical moving string (Ribaric (4.26)–(4.30)).
#![allow(clippy::needless_range_loop)] // index loops mirror the matrix equations

use flowing::{GalerkinString, StringConfig};

// Reference: notes §1.4.4 [DER] values of (4.28) for v = 10 m/s, L = 1 m.
#[test]
fn gyroscopic_matrix_entries_and_skew_symmetry() {
    let g = GalerkinString::new(StringConfig::default(), 10.0, 6).unwrap();
    assert!((g.a[(0, 1)] + 53.333_333).abs() < 1e-3);
    assert!((g.a[(1, 2)] + 96.0).abs() < 1e-9);
    assert!((g.a[(0, 3)] + 21.333_333).abs() < 1e-3);
    for i in 0..6 {
        for j in 0..6 {
            assert!((g.a[(i, j)] + g.a[(j, i)]).abs() < 1e-12);
        }
    }
}

// Reference: exact f_n = n(c²−v²)/(2cL) (notes §2.1 table, STR-2): within 1e-3 relative for
// N ≥ 20 terms, and the error decreases with N (convergence of the Galerkin model).
#[test]
fn galerkin_frequencies_converge_to_exact_moving_string() {
    let p = StringConfig::default();
    // Notes §2.1 table, v = 20 m/s.
    let table = [15.171, 30.341, 45.512, 60.683, 75.854];
    for (n, f) in table.iter().enumerate() {
        assert!((p.exact_moving_frequency_hz(n + 1, 20.0) - f).abs() < 1e-3);
    }
    for v in [0.0, 5.0, 10.0, 20.0, 30.0] {
        let mut prev = f64::INFINITY;
        for terms in [10, 20, 40] {
            let f = GalerkinString::new(p, v, terms)
                .unwrap()
                .system()
                .state_eigen()
                .unwrap()
                .damped_frequencies_hz();
            let err = (0..5)
                .map(|n| {
                    (f[n] - p.exact_moving_frequency_hz(n + 1, v)).abs()
                        / p.exact_moving_frequency_hz(n + 1, v)
                })
                .fold(0.0f64, f64::max);
            if terms >= 20 {
                assert!(err < 1e-3, "v = {v}, N = {terms}: rel. error {err}");
            }
            assert!(
                err <= prev * 1.0001 + 1e-12,
                "v = {v}: error must not grow with N ({prev} -> {err})"
            );
            prev = err;
        }
    }
}

// Reference: at v = 0, f_n = n c/(2L) = 20.137 n Hz (notes STR-1/§2.1).
#[test]
fn galerkin_at_rest_is_the_fixed_string() {
    let f = GalerkinString::new(StringConfig::default(), 0.0, 8)
        .unwrap()
        .system()
        .state_eigen()
        .unwrap()
        .damped_frequencies_hz();
    for n in 0..8 {
        assert!(
            (f[n] - 20.137 * (n + 1) as f64).abs() < 2e-3 * (n + 1) as f64,
            "{f:?}"
        );
    }
}

// Reference: above the critical speed c = 40.27 m/s the truncated Galerkin model has an
// eigenvalue with positive real part (what Ribaric 4.2.3 and notes STR-5 read as instability);
// below it none (positive definite B, skew A). The string itself is neutral above c with the
// frequencies n(v² − c²)/(2cL): the growth is a truncation artefact whose rate rises with the
// number of terms (issue 34; flowing::string_study, where the modes study labels it).
#[test]
fn truncated_galerkin_grows_above_critical_speed_only() {
    let p = StringConfig::default();
    let c = p.wave_speed();
    assert!((c - 40.2735).abs() < 1e-3);
    let below = GalerkinString::new(p, 0.95 * c, 20)
        .unwrap()
        .system()
        .state_eigen()
        .unwrap();
    assert!(
        below.max_real_part() < 1e-6 * below.values.iter().fold(0.0f64, |a, z| a.max(z.norm()))
    );
    let above = GalerkinString::new(p, 1.1 * c, 20)
        .unwrap()
        .system()
        .state_eigen()
        .unwrap();
    assert!(
        above.max_real_part() > 1.0,
        "max Re = {}",
        above.max_real_part()
    );
}

// Reference: invariants of the exact solution of (4.27): q(t) from (4.30) satisfies q̇ = X q
// (central difference in time), and H = ½ȧᵀȧ + ½aᵀBa is conserved because A is skew.
#[test]
fn matrix_exponential_response_satisfies_ode_and_conserves_energy() {
    let g = GalerkinString::new(StringConfig::default(), 20.0, 12).unwrap();
    let sys = g.system();
    let x = sys.state_matrix().unwrap();
    let n = 12;
    let mut q0 = vec![0.0; 2 * n];
    q0[0] = 1e-3;
    q0[2] = -4e-4;
    q0[n + 1] = 0.05;
    let dt = 1e-6;
    let t = 0.0123;
    let r = sys.response(&q0, &[0.0, t - dt, t, t + dt]).unwrap();
    for i in 0..2 * n {
        assert!((r[0][i] - q0[i]).abs() < 1e-12);
    }
    let xq: Vec<f64> = (0..2 * n)
        .map(|i| (0..2 * n).map(|j| x[(i, j)] * r[2][j]).sum())
        .collect();
    let scale = xq.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    for i in 0..2 * n {
        let fd = (r[3][i] - r[1][i]) / (2.0 * dt);
        assert!(
            (fd - xq[i]).abs() < 1e-5 * scale,
            "row {i}: {fd} vs {}",
            xq[i]
        );
    }
    let energy = |q: &[f64]| {
        (0..n)
            .map(|i| 0.5 * q[n + i] * q[n + i] + 0.5 * g.b[(i, i)] * q[i] * q[i])
            .sum::<f64>()
    };
    let e0 = energy(&q0);
    for s in &r[1..] {
        assert!((energy(s) - e0).abs() < 1e-9 * e0);
    }
}

// Reference: second formulation — the matrix-exponential response (4.30) equals mbd-core's
// Dormand–Prince integration of the same gyroscopic system (implemented as a SecondOrderSystem).
#[test]
fn matrix_exponential_equals_dormand_prince_integration() {
    use mbd_core::{DormandPrince, State};
    let g = GalerkinString::new(StringConfig::default(), 15.0, 8).unwrap();
    let sys = g.system();
    let n = 8;
    let q0: Vec<f64> = (0..n).map(|i| 1e-3 / (i + 1) as f64).collect();
    let v0: Vec<f64> = (0..n).map(|i| if i == 1 { 0.2 } else { 0.0 }).collect();
    let t_end = 0.137;
    let sol = DormandPrince::new(1e-11, 1e-14)
        .integrate(&sys, State::new(0.0, q0.clone(), v0.clone()), t_end, |_| {})
        .unwrap();
    let mut s0 = q0.clone();
    s0.extend(&v0);
    let r = sys.response(&s0, &[t_end]).unwrap();
    for i in 0..n {
        assert!(
            (r[0][i] - sol.state.q[i]).abs() < 1e-8,
            "q[{i}]: {} vs {}",
            r[0][i],
            sol.state.q[i]
        );
        assert!(
            (r[0][n + i] - sol.state.v[i]).abs() < 1e-6,
            "v[{i}]: {} vs {}",
            r[0][n + i],
            sol.state.v[i]
        );
    }
}
