//! Eitelberg's method (Lin §6.6, Appendix C) with the Bartels–Stewart Lyapunov solver.
//!
//! References: the dense Kronecker solver (an independent formulation, ≤ 24 DOFs); the
//! defining equation `A S + S Aᵀ + Q = 0` itself (200 DOFs); Lin §6.6.4 (Eitelberg reproduces
//! Guyan reduction with the same boundary set).

use faer::Mat;
use faer::linalg::solvers::{DenseSolveCore, Solve};
use flowmbd_cases::lin::beam::{appendix_a_beam, node_dofs};
use reduction::basis::{Method, ModeSelection, build_basis};
use reduction::eitelberg::{
    LyapunovSolver, eitelberg_structure_with, eitelberg_with, lyapunov_kronecker,
};
use reduction::lyapunov::lyapunov;
use reduction::{DofPartition, ReducedModel};

fn max_abs(a: &Mat<f64>) -> f64 {
    let mut m = 0.0f64;
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            m = m.max(a[(i, j)].abs());
        }
    }
    m
}

fn rel_diff(a: &Mat<f64>, b: &Mat<f64>) -> f64 {
    max_abs(&(a - b)) / max_abs(b)
}

/// Free-free chain of `n` unit masses \[kg\] and springs `k` \[N/m\], with a deterministic
/// ±30 % variation of masses and stiffnesses so that no two modes coincide.
fn chain(n: usize, k: f64) -> (Mat<f64>, Mat<f64>) {
    let mut kk = Mat::<f64>::zeros(n, n);
    let mut mm = Mat::<f64>::zeros(n, n);
    let var = |i: usize| 1.0 + 0.3 * ((i as f64 * 1.618_033_988_7).fract() - 0.5) * 2.0;
    for i in 0..n {
        mm[(i, i)] = var(3 * i + 1);
    }
    for e in 0..n - 1 {
        let ke = k * var(7 * e + 2);
        kk[(e, e)] += ke;
        kk[(e + 1, e + 1)] += ke;
        kk[(e, e + 1)] -= ke;
        kk[(e + 1, e)] -= ke;
    }
    (kk, mm)
}

/// Stable test matrix `A − B L C` of Lin §6.6.4 and `Q = P Pᵀ`, `P = A⁻¹B`.
fn feedback_system(k: &Mat<f64>, m: &Mat<f64>, boundary: &[usize]) -> (Mat<f64>, Mat<f64>) {
    let n = k.nrows();
    let nb = boundary.len();
    let minv = m.partial_piv_lu().inverse();
    let minvk = &minv * k;
    let mut a = Mat::<f64>::zeros(2 * n, 2 * n);
    for i in 0..n {
        a[(i, n + i)] = 1.0;
        for j in 0..n {
            a[(n + i, j)] = -minvk[(i, j)];
        }
    }
    let b = Mat::from_fn(2 * n, nb, |i, j| {
        if i < n {
            0.0
        } else {
            minv[(i - n, boundary[j])]
        }
    });
    // B L C with L = [I I], C selecting {δ_b; δ̇_b}
    for (jb, &d) in boundary.iter().enumerate() {
        for i in 0..2 * n {
            a[(i, d)] -= b[(i, jb)];
            a[(i, n + d)] -= b[(i, jb)];
        }
    }
    let p = a.partial_piv_lu().solve(&b);
    let q = &p * p.transpose();
    (a, q)
}

/// Deterministic pseudo-random numbers in (−1, 1) (a fixed LCG: reproducible, no dependency).
fn lcg(seed: u64) -> impl FnMut() -> f64 {
    let mut x = seed;
    move || {
        x = x
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((x >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}

/// Relative residual of `A S + S Aᵀ + Q = 0` in max norms.
fn lyap_residual(a: &Mat<f64>, s: &Mat<f64>, q: &Mat<f64>) -> f64 {
    max_abs(&(a * s + s * a.transpose() + q)) / (2.0 * max_abs(a) * max_abs(s) + max_abs(q))
}

/// 2-norm condition number of the Kronecker operator `I⊗A + A⊗I`.
fn kronecker_condition(a: &Mat<f64>) -> f64 {
    let n = a.nrows();
    let big = Mat::from_fn(n * n, n * n, |r, c| {
        let (i, j) = (r % n, r / n);
        let (k, l) = (c % n, c / n);
        let mut v = 0.0;
        if l == j {
            v += a[(i, k)];
        }
        if k == i {
            v += a[(j, l)];
        }
        v
    });
    let sv = big.singular_values().unwrap();
    let max = sv.iter().cloned().fold(0.0, f64::max);
    let min = sv.iter().cloned().fold(f64::INFINITY, f64::min);
    max / min
}

#[test]
fn bartels_stewart_equals_the_kronecker_solver_up_to_24_dofs() {
    // Well-conditioned cases at the Kronecker limit (48 states): a 24-DOF chain with output
    // feedback (Lin §6.6.4 set-up) and a random stable 48×48 matrix. Eitelberg's reduced
    // matrices and the Lyapunov solutions agree to 1e-10 (relative, max norm).
    let (kc, mc) = chain(24, 1e4);
    let bd = vec![0, 7, 15, 23];
    let (a, q) = feedback_system(&kc, &mc, &bd);
    let mut rnd = lcg(42);
    let g = Mat::from_fn(48, 48, |_, _| rnd());
    let ar = &g - Mat::<f64>::identity(48, 48) * 8.0; // spectral abscissa < 0 (Gershgorin-ish)
    let br = Mat::from_fn(48, 5, |_, _| rnd());
    let qr = &br * br.transpose();
    assert!(ar.eigenvalues().unwrap().iter().all(|z| z.re < 0.0));
    for (name, a, q) in [("chain-24", &a, &q), ("random-48", &ar, &qr)] {
        let s_bs = lyapunov(a.as_ref(), q.as_ref()).unwrap();
        let s_kr = lyapunov_kronecker(a.as_ref(), q.as_ref()).unwrap();
        let ds = rel_diff(&s_bs, &s_kr);
        eprintln!(
            "{name}: S differs by {ds:e}; residual BS {:e}, Kronecker {:e}",
            lyap_residual(a, &s_bs, q),
            lyap_residual(a, &s_kr, q)
        );
        assert!(ds < 1e-10, "{name}: S differs by {ds:e}");
    }
    // Eitelberg (Lin App. C) on the random stable system: B 48×5, R = C selecting 12 states
    let r = Mat::from_fn(12, 48, |i, j| (j == 4 * i) as u8 as f64);
    let e_bs = eitelberg_with(
        ar.as_ref(),
        br.as_ref(),
        r.as_ref(),
        r.as_ref(),
        LyapunovSolver::BartelsStewart,
    )
    .unwrap();
    let e_kr = eitelberg_with(
        ar.as_ref(),
        br.as_ref(),
        r.as_ref(),
        r.as_ref(),
        LyapunovSolver::Kronecker,
    )
    .unwrap();
    for (what, d) in [
        ("A_r", rel_diff(&e_bs.a_r, &e_kr.a_r)),
        ("B_r", rel_diff(&e_bs.b_r, &e_kr.b_r)),
        ("C_r", rel_diff(&e_bs.c_r, &e_kr.c_r)),
    ] {
        eprintln!("random-48 Eitelberg {what}: {d:e}");
        assert!(d < 1e-10, "random-48: {what} differs by {d:e}");
    }
    // the structural chain: S agrees to 1e-10 (above), but (R S Rᵀ)⁻¹ amplifies it: the
    // lightly damped feedback poles make the reduced matrices conditioning-limited (measured
    // 1.0e-7); both equal Guyan (Lin §6.6.4) to that level
    let (mk_bs, _) = eitelberg_structure_with(
        kc.as_ref(),
        mc.as_ref(),
        &bd,
        LyapunovSolver::BartelsStewart,
    )
    .unwrap();
    let (mk_kr, _) =
        eitelberg_structure_with(kc.as_ref(), mc.as_ref(), &bd, LyapunovSolver::Kronecker).unwrap();
    let d = rel_diff(&mk_bs, &mk_kr);
    eprintln!("chain-24 Eitelberg M⁻¹K: {d:e}");
    assert!(d < 1e-6, "chain-24: M⁻¹K differs by {d:e}");
}

#[test]
fn bartels_stewart_on_the_ill_conditioned_lin_beam_case() {
    // Lin App. A beam with b = nodes 1, 3, 5 (Lin §6.6.4): the feedback system has lightly
    // damped poles, sep(A, −Aᵀ) is tiny and the Lyapunov equation itself is ill-conditioned
    // (κ of I⊗A + A⊗I ≈ 1e9 here), so no two backward-stable solvers can agree to 1e-10.
    // Both solutions have round-off residuals; their difference stays within the
    // perturbation bound κ·ε, and the printed Lin results are reproduced by both
    // (tests/tests/reduction_lin_beam.rs, eitelberg_equals_guyan_a).
    let beam = appendix_a_beam().unwrap();
    let bd = node_dofs(&[1, 3, 5]);
    let (a, q) = feedback_system(&beam.k, &beam.m, &bd);
    let s_bs = lyapunov(a.as_ref(), q.as_ref()).unwrap();
    let s_kr = lyapunov_kronecker(a.as_ref(), q.as_ref()).unwrap();
    let (rb, rk) = (lyap_residual(&a, &s_bs, &q), lyap_residual(&a, &s_kr, &q));
    let kappa = kronecker_condition(&a);
    let ds = rel_diff(&s_bs, &s_kr);
    eprintln!("beam: κ {kappa:e}; S differs by {ds:e}; residual BS {rb:e}, Kronecker {rk:e}");
    assert!(rb < 1e-14 && rk < 1e-14);
    assert!(
        ds < kappa * 10.0 * f64::EPSILON,
        "difference {ds:e} above κ·ε"
    );
}

#[test]
fn bartels_stewart_satisfies_the_lyapunov_equation_on_200_dofs_and_eitelberg_equals_guyan() {
    // 200-DOF chain (400 states), 20 boundary DOFs; far beyond the Kronecker limit (48 states).
    let n = 200;
    let (k, m) = chain(n, 1e4);
    let bd: Vec<usize> = (0..n).step_by(10).collect();
    let (a, q) = feedback_system(&k, &m, &bd);
    let s = lyapunov(a.as_ref(), q.as_ref()).unwrap();
    let r = &a * &s + &s * a.transpose() + &q;
    let rel = max_abs(&r) / (2.0 * max_abs(&a) * max_abs(&s) + max_abs(&q));
    eprintln!("200 DOFs: relative Lyapunov residual {rel:e}");
    assert!(rel < 1e-12, "residual {rel:e}");
    // S is symmetric positive semi-definite (a controllability Gramian of P)
    assert!(rel_diff(&s, &s.transpose().to_owned()) < 1e-14);
    // Lin §6.6.4: Eitelberg with R = C = {δ_b; δ̇_b} reproduces Guyan: M_⁻¹K_ = M_G⁻¹K_G
    let (mk, _) =
        eitelberg_structure_with(k.as_ref(), m.as_ref(), &bd, LyapunovSolver::BartelsStewart)
            .unwrap();
    let part = DofPartition::from_boundary_dofs(n, &bd).unwrap();
    let g = build_basis(
        k.as_ref(),
        m.as_ref(),
        &part,
        Method::Guyan,
        &ModeSelection::Lowest(0),
    )
    .unwrap();
    let red = ReducedModel::from_basis(g, k.as_ref(), m.as_ref(), None, 1).unwrap();
    let mg = red.mass.partial_piv_lu().inverse() * &red.stiffness;
    let d = rel_diff(&mk, &mg);
    eprintln!("200 DOFs: |M⁻¹K (Eitelberg) − M_G⁻¹K_G| / max = {d:e}");
    assert!(d < 1e-6, "Eitelberg vs Guyan {d:e}");
}
