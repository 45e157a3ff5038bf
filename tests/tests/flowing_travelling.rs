//! The travelling string in flowing-material modal coordinates (Ribaric (4.12)–(4.20)).
//!
//! The FE data here are the closed-form modes of Ribaric's string (4.1) (n interior nodes,
//! h = L/(n+1), lumped mass μh, fixed ends): ψ_k(j) = √(2/((n+1)μh)) sin(jkπ/(n+1)),
//! ω_k² = 4T/(μh²) sin²(kπ/(2(n+1))), an independent reference for the library's pipeline.
#![allow(clippy::needless_range_loop)] // index loops mirror the matrix equations

use faer::Mat;
use flowing::derivative::{FdScheme, FirstDifference, MassKind, SecondDifference};
use flowing::{
    AxialMotion, DerivativeMethod, FlowGrid, FlowLine, FlowingString, ModalBasis, StringConfig,
};
use mbd_core::SysMatrix;
use std::f64::consts::PI;

fn string_model(
    p: &StringConfig, n: usize, modes: usize,
) -> (SysMatrix, ModalBasis, Vec<FlowLine>) {
    let h = p.length / (n + 1) as f64;
    let mu = p.mu();
    let mass = SysMatrix::Dense(Mat::from_fn(n, n, |i, j| if i == j { mu * h } else { 0.0 }));
    let norm = (2.0 / ((n + 1) as f64 * mu * h)).sqrt();
    let psi = Mat::from_fn(n, modes, |j, k| {
        norm * ((j + 1) as f64 * (k + 1) as f64 * PI / (n + 1) as f64).sin()
    });
    let lambda = (1..=modes)
        .map(|k| {
            4.0 * p.tension / (mu * h * h) * (k as f64 * PI / (2.0 * (n + 1) as f64)).sin().powi(2)
        })
        .collect();
    let grid = FlowGrid::uniform_fixed(0.0, p.length, n).unwrap();
    (
        mass,
        ModalBasis::new(psi, lambda).unwrap(),
        vec![FlowLine::strided(grid, 0, 1)],
    )
}

fn flowing(n: usize, modes: usize, method: DerivativeMethod, speed: f64) -> FlowingString {
    let p = StringConfig::default();
    let (m, b, l) = string_model(&p, n, modes);
    FlowingString::new(&m, b, &l, method, AxialMotion::Constant { speed }).unwrap()
}

fn max_rel_err(f: &[f64], v: f64, count: usize) -> f64 {
    let p = StringConfig::default();
    (0..count)
        .map(|i| {
            (f[i] - p.exact_moving_frequency_hz(i + 1, v)).abs()
                / p.exact_moving_frequency_hz(i + 1, v)
        })
        .fold(0.0, f64::max)
}

// Reference: notes STR-3 — discrete flowing-material frequencies within ~0.1 % of the exact
// n(c²−v²)/(2cL) (n = 99, FE-consistent derivatives, lowest 5 modes, ≥ 20 kept modes), and the
// notes' [DER] values 15.171, 30.345, 45.523, 60.709, 75.905 Hz with all 99 modes at v = 20.
#[test]
fn flowing_frequencies_match_exact_moving_string() {
    let m = DerivativeMethod::default();
    let all = flowing(99, 99, m, 20.0)
        .frozen(20.0, 0.0)
        .state_eigen()
        .unwrap()
        .damped_frequencies_hz();
    let der = [15.171, 30.345, 45.523, 60.709, 75.905];
    for i in 0..5 {
        assert!((all[i] - der[i]).abs() < 2e-3, "{:?}", &all[..5]);
    }
    // FE discretisation error of mode 5 at n = 99 is (5πh)²/24 ≈ 1.03e-3 at v = 0; relative
    // errors grow near the critical speed (measured 0.34 % at v = 30, n = 99), so n = 199 there.
    for (v, n, modes) in [
        (0.0, 99, 20),
        (10.0, 99, 20),
        (20.0, 99, 30),
        (30.0, 199, 60),
    ] {
        let f = flowing(n, modes, m, v)
            .frozen(v, 0.0)
            .state_eigen()
            .unwrap()
            .damped_frequencies_hz();
        let e = max_rel_err(&f, v, 5);
        assert!(
            e < 1.1e-3,
            "v = {v}, n = {n}, {modes} modes: rel. error {e}"
        );
    }
}

// Reference: at zero speed the flowing model is the fixed string, f_n ≈ n c/(2L)
// (notes STR-1: 20.136, 40.267, 60.388, 80.494, 100.580 Hz for n = 99).
#[test]
fn zero_speed_gives_fixed_string_frequencies() {
    let f = flowing(99, 10, DerivativeMethod::default(), 0.0)
        .frozen(0.0, 0.0)
        .state_eigen()
        .unwrap()
        .damped_frequencies_hz();
    let str1 = [20.136, 40.267, 60.388, 80.494, 100.580];
    for i in 0..5 {
        assert!((f[i] - str1[i]).abs() < 1.5e-3, "{f:?}");
    }
}

// Reference: convergence to the analytical model as nodes and modes increase (STR-3).
#[test]
fn flowing_frequencies_converge_with_nodes_and_modes() {
    let v = 25.0;
    let errs: Vec<f64> = [(24, 24), (49, 40), (99, 60), (199, 80)]
        .iter()
        .map(|&(n, k)| {
            max_rel_err(
                &flowing(n, k, DerivativeMethod::default(), v)
                    .frozen(v, 0.0)
                    .state_eigen()
                    .unwrap()
                    .damped_frequencies_hz(),
                v,
                5,
            )
        })
        .collect();
    for w in errs.windows(2) {
        assert!(w[1] < w[0], "{errs:?}");
    }
    // Second-order convergence: the error falls ~4× per halving of h.
    assert!(errs[3] < 5e-4, "{errs:?}");
    assert!(errs[2] / errs[3] > 3.5, "{errs:?}");
}

// Reference: Ribaric 4.2.3 / notes STR-5 — above the critical speed c = 40.27 m/s the truncated
// model has growing eigenvalues; below it all eigenvalues are on the imaginary axis
// (FE-consistent operators: skew Coriolis matrix, positive stiffness). Above c the growth is a
// truncation artefact, not an instability of the string (issue 34, flowing::string_study).
#[test]
fn truncated_model_grows_above_critical_speed_only() {
    let c = StringConfig::default().wave_speed();
    let s = flowing(49, 20, DerivativeMethod::default(), 0.0);
    let below = s.frozen(0.9 * c, 0.0).state_eigen().unwrap();
    assert!(
        below.max_real_part().abs() < 1e-6 * 1e3,
        "{}",
        below.max_real_part()
    );
    let above = s.frozen(1.1 * c, 0.0).state_eigen().unwrap();
    assert!(above.max_real_part() > 1.0, "{}", above.max_real_part());
}

// Reference: notes STR-6 pitfall — exact continuous derivatives (here the spectral operator,
// exact on the sampled sine modes) with all FE modes give a spurious instability at v = 30 m/s
// (max Re ≈ 144 for n = 49), while FE-consistent derivatives stay stable; truncation to 20 modes
// removes it too.
#[test]
fn inconsistent_derivatives_with_all_modes_are_falsely_unstable() {
    let spec = flowing(49, 49, DerivativeMethod::Spectral, 30.0)
        .frozen(30.0, 0.0)
        .state_eigen()
        .unwrap();
    assert!(
        (spec.max_real_part() - 144.0).abs() < 5.0,
        "max Re = {}",
        spec.max_real_part()
    );
    let cons = flowing(49, 49, DerivativeMethod::default(), 30.0)
        .frozen(30.0, 0.0)
        .state_eigen()
        .unwrap();
    assert!(
        cons.max_real_part() < 1e-6 * 1e3,
        "{}",
        cons.max_real_part()
    );
    let trunc = flowing(49, 20, DerivativeMethod::Spectral, 30.0)
        .frozen(30.0, 0.0)
        .state_eigen()
        .unwrap();
    assert!(trunc.max_real_part() < 1e-3, "{}", trunc.max_real_part());
}

// Reference: notes §2.1 — Ribaric's own recipe (central difference applied twice) biases the
// v = 20 frequencies upward by ~0.3 % (15.216, 30.444, 45.694, 60.980, 76.312 Hz, n = 99, all modes).
#[test]
fn repeated_central_difference_bias_matches_notes() {
    let m = DerivativeMethod::FiniteDifference(FdScheme {
        first: FirstDifference::Central,
        second: SecondDifference::RepeatedFirst,
    });
    let f = flowing(99, 99, m, 20.0)
        .frozen(20.0, 0.0)
        .state_eigen()
        .unwrap()
        .damped_frequencies_hz();
    let der = [15.216, 30.444, 45.694, 60.980, 76.312];
    for i in 0..5 {
        assert!((f[i] - der[i]).abs() < 3e-3, "{:?}", &f[..5]);
    }
}

// Reference: with FE-consistent operators ΨᵀMΨ_,x is skew and ΨᵀMΨ_,xx = −Λ/c² exactly (notes §2.1
// design rule), also with the consistent-mass variant producing the same matrices for lumped M.
#[test]
fn consistent_operator_gives_skew_coriolis_and_scaled_lambda() {
    let p = StringConfig::default();
    let s = flowing(40, 15, DerivativeMethod::Consistent(MassKind::Lumped), 10.0);
    let c2 = p.wave_speed().powi(2);
    for i in 0..15 {
        for j in 0..15 {
            assert!((s.m_x[(i, j)] + s.m_x[(j, i)]).abs() < 1e-9);
            let expect = if i == j { -s.basis.lambda[i] / c2 } else { 0.0 };
            assert!(
                (s.m_xx[(i, j)] - expect).abs() < 1e-8 * (1.0 + expect.abs()),
                "{i} {j}"
            );
        }
    }
}

// Reference: AxialMotion::Dynamic integrates m ẍ = F − d ẋ; the frozen-speed forces agree with
// the prescribed-speed model at the same (ẋ, ẍ) (second formulation).
#[test]
fn dynamic_axial_motion_forces_match_prescribed() {
    use mbd_core::SecondOrderSystem;
    let p = StringConfig::default();
    let (m, b, l) = string_model(&p, 30, 8);
    let dynm = FlowingString::new(
        &m,
        b.clone(),
        &l,
        DerivativeMethod::default(),
        AxialMotion::Dynamic {
            mass: 2.0,
            damping: 0.5,
            force: 3.0,
        },
    )
    .unwrap();
    assert_eq!(dynm.n_q(), 9);
    let q: Vec<f64> = (0..9).map(|i| 1e-3 * (i as f64 + 1.0).sin()).collect();
    let mut v: Vec<f64> = (0..9).map(|i| 1e-2 * (i as f64 * 0.7).cos()).collect();
    v[8] = 12.0;
    let mut f = vec![0.0; 9];
    dynm.forces(0.0, &q, &v, &mut f, &mut mbd_core::Workspace::new())
        .unwrap();
    assert!((f[8] - (3.0 - 0.5 * 12.0)).abs() < 1e-12);
    let accel = (3.0 - 0.5 * 12.0) / 2.0;
    let pres = FlowingString::new(
        &m,
        b,
        &l,
        DerivativeMethod::default(),
        AxialMotion::Ramp {
            initial_speed: 12.0,
            acceleration: accel,
        },
    )
    .unwrap();
    let mut g = vec![0.0; 8];
    pres.forces(
        0.0,
        &q[..8],
        &v[..8],
        &mut g,
        &mut mbd_core::Workspace::new(),
    )
    .unwrap();
    for i in 0..8 {
        assert!((f[i] - g[i]).abs() < 1e-12 * (1.0 + g[i].abs()));
    }
}

// Reference: notes STR-4 (Fig. 4-6 right analogue): v = 20 m/s, n = 99, 10 modes, triangular pluck
// at 0.3 m (1 mm), 4 s: the FFT peaks of every modal coordinate lie within about one bin of the
// model's eigenfrequencies, which are within 1 % of the exact n(c²−v²)/(2cL) (10-mode truncation:
// notes give 76.372 Hz vs 75.854 for mode 5), and the coordinates show several frequencies each
// (Coriolis coupling).
// The FE model and modes come from fe-model (string element, dense eigen solver).
#[test]
fn pluck_transient_spectra_show_coupled_frequencies() {
    use flowing::spectrum::amplitude_spectrum;
    use flowing::{StringMesh, simulate_rk4, triangular_pluck};
    let p = StringConfig::default();
    let v = 20.0;
    let mesh = StringMesh::uniform(p, 99).unwrap();
    let basis = mesh.modes(10).unwrap();
    let sys = FlowingString::new(
        &mesh.mass_sys(),
        basis,
        &[mesh.flow_line()],
        DerivativeMethod::default(),
        AxialMotion::Constant { speed: v },
    )
    .unwrap();
    let u0 = triangular_pluck(mesh.grid.positions(), 0.0, 1.0, 0.3, 1e-3).unwrap();
    let z0 = sys.project(&u0).unwrap();
    let h = 5e-5;
    let every = 20; // 1 ms sampling
    let hist = simulate_rk4(&sys, z0.clone(), vec![0.0; 10], 4.0, h, every, |_| {}).unwrap();
    let model = sys
        .frozen(v, 0.0)
        .state_eigen()
        .unwrap()
        .damped_frequencies_hz();
    for n in 0..5 {
        let e = p.exact_moving_frequency_hz(n + 1, v);
        assert!((model[n] - e).abs() < 0.01 * e, "{model:?}");
    }
    let h0 = sys.hamiltonian(&z0, &[0.0; 10], v);
    let last = hist.q.len() - 1;
    // Conserved H (skew Coriolis matrix); RK4's own amplitude error (hω)⁶/144 per step bounds the drift.
    let drift = (sys.hamiltonian(&hist.q[last], &hist.v[last], v) - h0).abs() / h0;
    assert!(drift < 1e-5, "H drift {drift}");
    let mut multi = 0;
    for mode in 0..5 {
        let sig: Vec<f64> = hist.q.iter().map(|q| q[mode]).collect();
        let s = amplitude_spectrum(&sig, h * every as f64, 1).unwrap();
        let bin = s.frequencies[1];
        let peaks = s.peaks(0.05);
        assert!(!peaks.is_empty());
        for (f, _) in &peaks {
            let near = model
                .iter()
                .map(|e| (e - f).abs())
                .fold(f64::INFINITY, f64::min);
            assert!(
                near <= 1.5 * bin,
                "mode {}: peak at {f} Hz is {near} Hz from every eigenfrequency",
                mode + 1
            );
        }
        if peaks.len() >= 2 {
            multi += 1;
        }
    }
    assert!(
        multi >= 3,
        "each modal coordinate should show several frequencies"
    );
}

// Reference: analytical axial speed of the dynamic axial motion m ẍ = F − d ẋ:
// ẋ(t) = F/d + (ẋ₀ − F/d) e^{−d t/m}, integrated together with the modal equations by mbd-core.
#[test]
fn dynamic_axial_speed_follows_its_ode() {
    use flowing::simulate_rk4;
    let p = StringConfig::default();
    let (m, b, l) = string_model(&p, 30, 6);
    let (mass, damping, force) = (3.0, 1.5, 30.0);
    let sys = FlowingString::new(
        &m,
        b,
        &l,
        DerivativeMethod::default(),
        AxialMotion::Dynamic {
            mass,
            damping,
            force,
        },
    )
    .unwrap();
    let mut q0 = vec![0.0; 7];
    q0[0] = 1e-4;
    let mut v0 = vec![0.0; 7];
    v0[6] = 2.0;
    let hist = simulate_rk4(&sys, q0, v0, 1.0, 1e-4, 1000, |_| {}).unwrap();
    for (t, v) in hist.t.iter().zip(&hist.v) {
        let exact = force / damping + (2.0 - force / damping) * (-damping * t / mass).exp();
        assert!(
            (v[6] - exact).abs() < 1e-9 * exact.abs().max(1.0),
            "t = {t}: {} vs {exact}",
            v[6]
        );
    }
    // The transverse motion stays bounded below the critical speed (ẋ → 20 m/s < c).
    assert!(hist.q.last().unwrap()[..6].iter().all(|z| z.abs() < 1.0));
}
