//! Shared check of constraint rows against finite differences (second formulation).

use mbd_core::SecondOrderSystem;
use mbd_core::integrators::State;

/// `q ⊕ τ Δv` (constant `ṙ`, body-frame `ω'` and `ż`, so that `v̇ = 0` along the path).
pub fn moved<S: SecondOrderSystem>(sys: &S, s: &State, dv: &[f64], tau: f64) -> Vec<f64> {
    let dq: Vec<f64> = dv.iter().map(|x| x * tau).collect();
    let mut q = vec![0.0; s.q.len()];
    sys.integrate_position(&s.q, &dq, &mut q);
    q
}

/// `Φ̇ = D v − ν` and `Φ̈ = −γ` along `q(τ) = q ⊕ τ v` (definitions of Lin (2.11)–(2.12) /
/// Ribaric (2.16) with rheonomic terms) by central differences with `h = 1e-4` s.
pub fn check_rates<S: SecondOrderSystem>(sys: &S, s: &State, label: &str) {
    let nc = sys.n_c();
    let phi_at = |tau: f64| {
        let mut phi = vec![0.0; nc];
        sys.constraint_residual(s.t + tau, &moved(sys, s, &s.v, tau), &mut phi)
            .unwrap();
        phi
    };
    let h = 1e-4;
    let (pp, p0, pm) = (phi_at(h), phi_at(0.0), phi_at(-h));
    let d = sys.constraint_jacobian(s.t, &s.q).unwrap();
    let mut dv = vec![0.0; nc];
    d.mul_vec(&s.v, &mut dv);
    let mut nu = vec![0.0; nc];
    sys.constraint_velocity_rhs(s.t, &s.q, &mut nu).unwrap();
    let mut gamma = vec![0.0; nc];
    sys.constraint_gamma(s.t, &s.q, &s.v, &mut gamma).unwrap();
    for r in 0..nc {
        let phid = (pp[r] - pm[r]) / (2.0 * h);
        let phidd = (pp[r] - 2.0 * p0[r] + pm[r]) / (h * h);
        assert!(
            (phid - (dv[r] - nu[r])).abs() < 1e-6,
            "{label} row {r}: Φ̇ {phid} vs Dv − ν {}",
            dv[r] - nu[r]
        );
        assert!(
            (phidd + gamma[r]).abs() < 2e-5 * (1.0 + phidd.abs()),
            "{label} row {r}: Φ̈ {phidd} vs −γ {}",
            -gamma[r]
        );
    }
}
