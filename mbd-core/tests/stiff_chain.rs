//! Stiff spring-mass chain integrated by generalized-α at a step 100x above the explicit
//! stability limit (issue 2, item 4).
//!
//! Model: `n` dumbbells (two masses `m` joined by a stiff spring `k_s`) in a fixed-free chain
//! of soft springs `k`. Low modes: the dumbbells move rigidly, a fixed-free chain of masses
//! `2m`: `ω_j = 2 sqrt(k/2m) sin((2j − 1) π / (2 (2n + 1)))`, shape
//! `φ_i = sin((2j − 1) i π / (2n + 1))` (exact up to O(k/k_s)). High mode: stretching of a
//! dumbbell, `ω ≈ sqrt(2 k_s / m)`.

use faer::sparse::{SparseColMat, Triplet};
use mbd_core::Workspace;
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha, Rk4, State, Stepper};
use mbd_core::{ForceTangent, MbdError, SecondOrderSystem, SysMatrix};
use std::f64::consts::PI;

use crate::support;
use support::Oscillator;

struct Chain {
    pairs: usize,
    m: f64,
    k: f64,
    ks: f64,
}

impl Chain {
    /// (i, j, stiffness) springs; j = None: spring to the ground.
    fn springs(&self) -> Vec<(Option<usize>, usize, f64)> {
        let mut s = Vec::new();
        for p in 0..self.pairs {
            let (a, b) = (2 * p, 2 * p + 1);
            s.push((if p == 0 { None } else { Some(a - 1) }, a, self.k));
            s.push((Some(a), b, self.ks));
        }
        s
    }
    fn stiffness(&self) -> SparseColMat<usize, f64> {
        let n = 2 * self.pairs;
        let mut t = Vec::new();
        for (i, j, k) in self.springs() {
            t.push(Triplet::new(j, j, k));
            if let Some(i) = i {
                t.push(Triplet::new(i, i, k));
                t.push(Triplet::new(i, j, -k));
                t.push(Triplet::new(j, i, -k));
            }
        }
        SparseColMat::try_new_from_triplets(n, n, &t).unwrap()
    }
    fn omega_low(&self, j: usize) -> f64 {
        let n = self.pairs as f64;
        2.0 * (self.k / (2.0 * self.m)).sqrt()
            * ((2 * j - 1) as f64 * PI / (2.0 * (2.0 * n + 1.0))).sin()
    }
    fn omega_high(&self) -> f64 {
        (2.0 * self.ks / self.m).sqrt()
    }
}

impl SecondOrderSystem for Chain {
    fn n_q(&self) -> usize {
        2 * self.pairs
    }
    fn mass_is_constant(&self) -> bool {
        true
    }
    fn mass(&self, _t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        let n = self.n_q();
        let t: Vec<_> = (0..n).map(|i| Triplet::new(i, i, self.m)).collect();
        Ok(SysMatrix::Sparse(
            SparseColMat::try_new_from_triplets(n, n, &t).unwrap(),
        ))
    }
    fn forces(
        &self, _t: f64, q: &[f64], _v: &[f64], f: &mut [f64], _ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        SysMatrix::Sparse(self.stiffness()).mul_vec(q, f);
        f.iter_mut().for_each(|x| *x = -*x);
        Ok(())
    }
    fn force_tangent(
        &self, _t: f64, _q: &[f64], _v: &[f64], _ws: &mut Workspace,
    ) -> Result<Option<ForceTangent>, MbdError> {
        let n = self.n_q();
        Ok(Some(ForceTangent {
            stiffness: SysMatrix::Sparse(self.stiffness()),
            damping: SysMatrix::Sparse(SparseColMat::try_new_from_triplets(n, n, &[]).unwrap()),
        }))
    }
}

fn chain() -> Chain {
    Chain {
        pairs: 5,
        m: 1.0,
        k: 1.0,
        ks: 1e6,
    }
}

/// Step 100x the RK4 stability limit 2.785/ω_max.
fn big_step(c: &Chain) -> f64 {
    100.0 * 2.785 / c.omega_high()
}

#[test]
fn low_mode_within_one_percent_at_100x_explicit_limit() {
    let c = chain();
    let h = big_step(&c);
    let w1 = c.omega_low(1);
    let n = c.pairs;
    let shape: Vec<f64> = (0..2 * n)
        .map(|i| (((i / 2) + 1) as f64 * PI / (2.0 * n as f64 + 1.0)).sin())
        .collect();
    let s0 = State::new(0.0, shape.clone(), vec![0.0; 2 * n]);
    let period = 2.0 * PI / w1;
    for rho in [0.0, 0.5, 0.9, 1.0] {
        let ga = GeneralizedAlpha::new(AlphaConfig {
            h,
            rho_inf: rho,
            ..Default::default()
        });
        let mut max_err = 0.0f64;
        let sol = ga
            .integrate(&c, s0.clone(), period, |s| {
                // analytic: u(t) = φ cos(ω₁ t)
                for (q, phi) in s.q.iter().zip(&shape) {
                    max_err = max_err.max((q - phi * (w1 * s.t).cos()).abs());
                }
            })
            .unwrap();
        let amp = shape.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        assert!(
            max_err < 0.01 * amp,
            "rho {rho}: low-mode error {:.3e} of amplitude",
            max_err / amp
        );
        // linear model: Newton converges in one correction (+1 check iteration)
        assert!(sol.stats.newton_iterations <= 2 * sol.stats.steps);
        println!(
            "rho {rho}: h = {h:.3e} s, ω_max h = {:.0}, low-mode error {:.2e}, stats {:?}",
            c.omega_high() * h,
            max_err / amp,
            sol.stats
        );
    }
    // the explicit integrator is unstable at this step
    let rk = Rk4::new(h).integrate(&c, s0, 20.0 * h, |_| {});
    let blew_up = match rk {
        Err(_) => true,
        Ok(sol) => sol.state.q.iter().any(|x| !x.is_finite() || x.abs() >= 1e3),
    };
    assert!(
        blew_up,
        "RK4 should be unstable at 100x its stability limit"
    );
}

#[test]
fn high_frequency_damping_is_governed_by_rho_inf() {
    // For ω h → ∞ all three roots of the generalized-α amplification matrix tend to −ρ∞
    // (Chung & Hulbert 1993, with α_m = (2ρ∞−1)/(ρ∞+1), α_f = ρ∞/(ρ∞+1)); the triple root
    // gives an n²ρ∞ⁿ envelope, so the per-step decay is measured with that correction.
    // the stiff mode in isolation
    let sys = Oscillator {
        m: 1.0,
        k: 1e6,
        tangent: false,
    };
    let h = 100.0 * 2.785 / (sys.k / sys.m).sqrt();
    let s0 = State::new(0.0, vec![1e-3], vec![0.0]);
    for rho in [0.0, 0.3, 0.6, 0.9, 1.0] {
        let ga = GeneralizedAlpha::new(AlphaConfig {
            h,
            rho_inf: rho,
            ..Default::default()
        });
        let mut u = Vec::new();
        ga.integrate(&sys, s0.clone(), 201.0 * h, |s| u.push(s.q[0]))
            .unwrap();
        let env = |n: usize| u[n].abs().max(u[n + 1].abs()) / (n * n) as f64;
        let measured = (env(200) / env(100)).powf(0.01);
        if rho == 0.0 {
            // annihilated after the first steps
            assert!(u[10].abs() < 1e-6 * 1e-3, "rho 0 leaves {:e}", u[10]);
        } else {
            assert!(
                (measured - rho).abs() < 0.02,
                "rho {rho}: measured decay {measured}"
            );
            // stable: never grows beyond the initial amplitude times the Jordan factor
            assert!(u.iter().all(|x| x.abs() < 1e-3 * 4e4));
        }
        println!(
            "rho {rho}: ω h = {:.0}, measured spectral radius {measured:.4}",
            h * 1e3
        );
    }

    // in the chain, the stiff mode of one dumbbell is damped out while ρ∞ = 1 keeps it
    let c = chain();
    let h = big_step(&c);
    let n = 2 * c.pairs;
    let mut q0 = vec![0.0; n];
    q0[4] = -1e-3;
    q0[5] = 1e-3;
    let s0 = State::new(0.0, q0, vec![0.0; n]);
    for (rho, lo, hi) in [(0.0, 0.0, 1e-8), (0.5, 0.0, 1e-7), (1.0, 0.5e-3, 4e-2)] {
        let ga = GeneralizedAlpha::new(AlphaConfig {
            h,
            rho_inf: rho,
            ..Default::default()
        });
        let sol = ga.integrate(&c, s0.clone(), 40.0 * h, |_| {}).unwrap();
        let stretch = (sol.state.q[5] - sol.state.q[4]).abs();
        assert!(
            stretch >= lo && stretch <= hi,
            "rho {rho}: stretch {stretch:e}"
        );
    }
}

#[test]
fn sparse_newton_matrix_reuses_its_symbolic_factorisation() {
    // the pattern of M + K/β' + Dᵀ… does not change: one symbolic LU for the whole run
    let c = chain();
    let n = 2 * c.pairs;
    let s0 = State::new(0.0, vec![1e-3; n], vec![0.0; n]);
    let ga = GeneralizedAlpha::new(AlphaConfig {
        h: 0.05,
        ..Default::default()
    });
    let mut st = ga.stepper(&c, s0).unwrap();
    st.advance_to(&c, 2.0, &mut ()).unwrap();
    assert_eq!(st.stats.steps, 40);
    assert!(st.stats.factorizations >= 40);
    assert_eq!(st.symbolic_factorizations(), 1);
}
