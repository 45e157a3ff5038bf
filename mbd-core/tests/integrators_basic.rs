//! Basic checks of the integrators on tiny hand-written systems with analytic references.

use faer::Mat;
use mbd_core::Workspace;
use mbd_core::integrators::{
    AlphaConfig, DormandPrince, Event, GeneralizedAlpha, JacobianMode, NewtonUpdate, Rk4, State,
};
use mbd_core::{MbdError, SecondOrderSystem, SysMatrix};
use std::f64::consts::PI;

use crate::support;
use support::Oscillator;

/// Planar pendulum, point mass in Cartesian coordinates, Φ = (x² + y² − L²)/2, gravity −y.
struct CartPendulum {
    m: f64,
    l: f64,
    g: f64,
}

impl SecondOrderSystem for CartPendulum {
    fn n_q(&self) -> usize {
        2
    }
    fn n_c(&self) -> usize {
        1
    }
    fn mass_is_constant(&self) -> bool {
        true
    }
    fn mass(&self, _t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        Ok(SysMatrix::Dense(Mat::from_fn(2, 2, |i, j| {
            if i == j { self.m } else { 0.0 }
        })))
    }
    fn forces(
        &self, _t: f64, _q: &[f64], _v: &[f64], f: &mut [f64], _ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        f[0] = 0.0;
        f[1] = -self.m * self.g;
        Ok(())
    }
    fn constraint_residual(&self, _t: f64, q: &[f64], phi: &mut [f64]) -> Result<(), MbdError> {
        phi[0] = 0.5 * (q[0] * q[0] + q[1] * q[1] - self.l * self.l);
        Ok(())
    }
    fn constraint_jacobian(&self, _t: f64, q: &[f64]) -> Result<SysMatrix, MbdError> {
        Ok(SysMatrix::Dense(Mat::from_fn(1, 2, |_, j| q[j])))
    }
    fn constraint_gamma(
        &self, _t: f64, _q: &[f64], v: &[f64], gamma: &mut [f64],
    ) -> Result<(), MbdError> {
        gamma[0] = -(v[0] * v[0] + v[1] * v[1]);
        Ok(())
    }
}

/// Minimal-coordinate reference θ̈ = −(g/L) sin θ by RK4 with a tiny step.
fn pendulum_reference(theta0: f64, g: f64, l: f64, t_end: f64) -> f64 {
    let n = 200_000;
    let h = t_end / n as f64;
    let (mut th, mut w) = (theta0, 0.0);
    let f = |th: f64| -g / l * th.sin();
    for _ in 0..n {
        let (k1t, k1w) = (w, f(th));
        let (k2t, k2w) = (w + 0.5 * h * k1w, f(th + 0.5 * h * k1t));
        let (k3t, k3w) = (w + 0.5 * h * k2w, f(th + 0.5 * h * k2t));
        let (k4t, k4w) = (w + h * k3w, f(th + h * k3t));
        th += h / 6.0 * (k1t + 2.0 * k2t + 2.0 * k3t + k4t);
        w += h / 6.0 * (k1w + 2.0 * k2w + 2.0 * k3w + k4w);
    }
    th
}

fn sdof_state() -> State {
    State::new(0.0, vec![1.0], vec![0.0])
}

#[test]
fn rk4_sdof_matches_cosine() {
    // analytic: x = cos(ω t)
    let sys = Oscillator {
        m: 2.0,
        k: 2.0 * (2.0 * PI).powi(2),
        tangent: true,
    };
    let sol = Rk4::new(1e-3)
        .integrate(&sys, sdof_state(), 1.3, |_| {})
        .unwrap();
    let exact = (2.0 * PI * 1.3f64).cos();
    assert!(
        (sol.state.q[0] - exact).abs() < 1e-9,
        "{}",
        sol.state.q[0] - exact
    );
    assert_eq!(sol.stats.steps, 1300);
    assert_eq!(sol.stats.force_evaluations, 4 * 1300);
    assert_eq!(sol.stats.factorizations, 1, "constant mass factored once");
}

#[test]
fn dopri_sdof_matches_cosine() {
    // analytic: x = cos(ω t)
    let sys = Oscillator {
        m: 1.0,
        k: (2.0 * PI).powi(2),
        tangent: true,
    };
    let sol = DormandPrince::new(1e-10, 1e-12)
        .integrate(&sys, sdof_state(), 3.0, |_| {})
        .unwrap();
    let exact = (2.0 * PI * 3.0f64).cos();
    assert!(
        (sol.state.q[0] - exact).abs() < 1e-8,
        "{}",
        sol.state.q[0] - exact
    );
    assert!(sol.stats.steps > 10);
}

#[test]
fn dopri_dense_output_event_is_4th_order() {
    // x = cos(ω t) crosses zero at t = 1/4 s (ω = 2π); loose tolerances so the dense output
    // matters; the located time must agree to the integration accuracy.
    let sys = Oscillator {
        m: 1.0,
        k: (2.0 * PI).powi(2),
        tangent: true,
    };
    let ev = [Event::stop("zero", |s: &State| s.q[0])];
    let sol = DormandPrince::new(1e-9, 1e-11)
        .integrate_with_events(&sys, sdof_state(), 1.0, &ev, |_| {})
        .unwrap();
    assert_eq!(sol.events.len(), 1);
    assert!(
        (sol.events[0].t - 0.25).abs() < 1e-8,
        "{}",
        sol.events[0].t - 0.25
    );
}

#[test]
fn generalized_alpha_sdof_second_order() {
    // analytic x = cos(ω t); generalized-α is 2nd order: error ratio 4 when h halves
    let mut errs = vec![];
    for &h in &[4e-3, 2e-3, 1e-3] {
        for analytic in [true, false] {
            let sys = Oscillator {
                m: 1.0,
                k: (2.0 * PI).powi(2),
                tangent: analytic,
            };
            let ga = GeneralizedAlpha::new(AlphaConfig {
                h,
                rho_inf: 0.9,
                ..Default::default()
            });
            // end at a zero crossing (maximal slope) so that the phase error shows at O(h²)
            let sol = ga.integrate(&sys, sdof_state(), 1.25, |_| {}).unwrap();
            let e = (sol.state.q[0] - (2.0 * PI * 1.25f64).cos()).abs();
            if analytic {
                errs.push(e);
            }
            assert!(e < 1e-3);
        }
    }
    let r1 = errs[0] / errs[1];
    let r2 = errs[1] / errs[2];
    assert!(
        (3.5..4.5).contains(&r1) && (3.5..4.5).contains(&r2),
        "{r1} {r2}"
    );
}

#[test]
fn pendulum_all_integrators_match_minimal_coordinates() {
    // reference: minimal coordinate θ (independent formulation)
    let sys = CartPendulum {
        m: 1.5,
        l: 0.8,
        g: 9.81,
    };
    let th0 = 1.0f64;
    let s0 = State::new(
        0.0,
        vec![sys.l * th0.sin(), -sys.l * th0.cos()],
        vec![0.0, 0.0],
    );
    let t_end = 2.0;
    let th_ref = pendulum_reference(th0, sys.g, sys.l, t_end);
    let angle = |s: &State| s.q[0].atan2(-s.q[1]);

    let rk = Rk4::new(5e-4)
        .with_stabilization(mbd_core::integrators::Stabilization {
            project: true,
            ..Default::default()
        })
        .integrate(&sys, s0.clone(), t_end, |_| {})
        .unwrap();
    assert!(
        (angle(&rk.state) - th_ref).abs() < 1e-7,
        "rk4 {}",
        angle(&rk.state) - th_ref
    );

    let dp = DormandPrince {
        rtol: 1e-10,
        atol: 1e-12,
        stabilization: mbd_core::integrators::Stabilization {
            baumgarte_alpha: 10.0,
            baumgarte_beta: 10.0,
            ..Default::default()
        },
        ..Default::default()
    }
    .integrate(&sys, s0.clone(), t_end, |_| {})
    .unwrap();
    assert!(
        (angle(&dp.state) - th_ref).abs() < 1e-6,
        "dopri {}",
        angle(&dp.state) - th_ref
    );

    for jac in [JacobianMode::Analytic, JacobianMode::FiniteDifference] {
        for update in [NewtonUpdate::EveryIteration, NewtonUpdate::EveryStep] {
            let ga = GeneralizedAlpha::new(AlphaConfig {
                h: 2e-4,
                rho_inf: 0.9,
                jacobian: jac,
                update,
                ..Default::default()
            });
            let sol = ga.integrate(&sys, s0.clone(), t_end, |_| {}).unwrap();
            let mut phi = [0.0];
            sys.constraint_residual(0.0, &sol.state.q, &mut phi)
                .unwrap();
            assert!(phi[0].abs() < 1e-9, "index-3 keeps Φ = 0: {}", phi[0]);
            assert!(
                (angle(&sol.state) - th_ref).abs() < 2e-4,
                "gen-alpha {jac:?} {update:?} {}",
                angle(&sol.state) - th_ref
            );
        }
    }
}

#[test]
fn dopri_dense_output_at_requested_times() {
    // analytic x = cos(ω t) at 101 requested times; 4th-order interpolant between steps
    let sys = Oscillator {
        m: 1.0,
        k: (2.0 * PI).powi(2),
        tangent: true,
    };
    let times: Vec<f64> = (0..=100).map(|k| 0.0137 * k as f64).collect();
    let mut seen = Vec::new();
    let sol = DormandPrince::new(1e-10, 1e-12)
        .integrate_dense(&sys, sdof_state(), &times, &[], |s| {
            seen.push((s.t, s.q[0]))
        })
        .unwrap();
    assert_eq!(seen.len(), times.len());
    // dense output does not change the step sequence
    let plain = DormandPrince::new(1e-10, 1e-12)
        .integrate(&sys, sdof_state(), 1.37, |_| {})
        .unwrap();
    assert_eq!(sol.stats.steps, plain.stats.steps);
    for ((t, x), tr) in seen.iter().zip(&times) {
        assert_eq!(t, tr);
        assert!(
            (x - (2.0 * PI * t).cos()).abs() < 1e-8,
            "t {t}: {}",
            x - (2.0 * PI * t).cos()
        );
    }
    assert!(
        DormandPrince::default()
            .integrate_dense(&sys, sdof_state(), &[0.2, 0.1], &[], |_| {})
            .is_err()
    );
}
