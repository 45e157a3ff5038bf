//! The one stepping interface: the three methods behind [`Stepper`] on a harmonic oscillator
//! (orders of convergence against the analytical solution), the fixed-interval [`Recorder`],
//! and the generalized-α step correction for nonsmooth contact (rigid floor, Coulomb friction).

use mbd_core::integrators::{
    AlphaConfig, AlphaCorrection, DormandPrince, GeneralizedAlpha, Integrator, Recorder, Rk4,
    State, StepCorrection, Stepper, observe_fn,
};
use mbd_core::{History, MbdError, Probe};

use crate::support;
use support::{Oscillator, PointMasses};

/// Error at t = 1 s of the method built by `make(h)` through the boxed `Stepper` factory.
fn error_at_1s(make: &dyn Fn(f64) -> Box<dyn Integrator>, h: f64) -> f64 {
    let sys = Oscillator::unit(2.0);
    let integ = make(h);
    let mut st = integ
        .stepper_dyn(&sys, State::new(0.0, vec![1.0], vec![0.0]))
        .unwrap();
    st.advance_to(&sys, 1.0, &mut ()).unwrap();
    assert_eq!(st.state().t, 1.0, "stop time hit exactly");
    // analytical x(1) = cos 2, ẋ(1) = −2 sin 2; error in the energy norm
    let ex = st.state().q[0] - 2.0f64.cos();
    let ev = (st.state().v[0] + 2.0 * 2.0f64.sin()) / 2.0;
    ex.hypot(ev)
}

fn observed_order(make: &dyn Fn(f64) -> Box<dyn Integrator>, h: f64) -> f64 {
    let e1 = error_at_1s(make, h);
    let e2 = error_at_1s(make, h / 2.0);
    (e1 / e2).log2()
}

#[test]
fn three_methods_converge_at_their_orders_on_the_oscillator() {
    // RK4: order 4 (analytical reference cos ωt)
    let rk4 = |h: f64| Box::new(Rk4::new(h)) as Box<dyn Integrator>;
    let p = observed_order(&rk4, 0.05);
    assert!((p - 4.0).abs() < 0.2, "RK4 order {p}");
    // Dormand–Prince run at a fixed step (tolerances so loose that no step is rejected and the
    // step stays at h_max): order 5
    let dp = |h: f64| {
        Box::new(DormandPrince {
            rtol: 1e6,
            atol: 1e6,
            h0: h,
            h_max: h,
            ..Default::default()
        }) as Box<dyn Integrator>
    };
    let p = observed_order(&dp, 0.05);
    assert!((p - 5.0).abs() < 0.3, "DOPRI5 order {p}");
    // generalized-α: order 2
    let ga = |h: f64| {
        Box::new(GeneralizedAlpha::new(AlphaConfig {
            h,
            rho_inf: 0.8,
            ..Default::default()
        })) as Box<dyn Integrator>
    };
    let p = observed_order(&ga, 0.01);
    assert!((p - 2.0).abs() < 0.1, "generalized-alpha order {p}");
}

#[test]
fn stepper_runs_match_the_integrate_wrappers() {
    // the wrappers are loops over the stepper: same steps, same end state
    let sys = Oscillator::unit(3.0);
    let s0 = State::new(0.0, vec![1.0], vec![0.5]);
    let dp = DormandPrince::new(1e-9, 1e-12);
    let sol = dp.integrate(&sys, s0.clone(), 2.0, |_| {}).unwrap();
    let mut st = dp.stepper(&sys, s0.clone()).unwrap();
    let mut n = 0;
    while st.step_until(&sys, 2.0).unwrap() {
        n += 1;
    }
    assert_eq!(n, sol.stats.steps);
    assert_eq!(Stepper::<Oscillator>::state(&st), &sol.state);
    // step(None) takes the controlled step; dense output at the step end is the end state
    let mut st = dp.stepper(&sys, s0).unwrap();
    st.step(&sys, None).unwrap();
    let t1 = st.state().t;
    assert!(t1 > 0.0);
    assert_eq!(st.dense_output(&sys, t1).unwrap().q, st.state().q);
    assert!(st.dense_output(&sys, 2.0 * t1).is_none());
}

#[test]
fn recorder_samples_at_exact_times_with_dense_output() {
    let omega = 2.0;
    let sys = Oscillator::unit(omega);
    let s0 = State::new(0.0, vec![1.0], vec![0.0]);
    let dt = 0.07;
    let t_end = 2.0;
    let run = |stepper: &mut dyn Stepper<Oscillator>| {
        let hist = History::new(vec![Probe::new("x [m]", |s: &State| s.q[0])]);
        let mut rec = Recorder::new(hist, 0.0, dt).unwrap();
        let mut steps = 0usize;
        rec.run(stepper, &sys, t_end, &mut observe_fn(|_| steps += 1))
            .unwrap();
        assert_eq!(steps, stepper.stats().steps);
        assert_eq!(stepper.state().t, t_end);
        rec.sink
    };
    // Dormand–Prince: own steps, 4th-order dense output between them (rtol 1e-10)
    let mut dp = DormandPrince::new(1e-10, 1e-12)
        .stepper(&sys, s0.clone())
        .unwrap();
    let hist = run(&mut dp);
    let n = (t_end / dt).floor() as usize + 1;
    assert_eq!(hist.t.len(), n);
    let x = hist.column("x [m]").unwrap();
    for (k, (&t, &x)) in hist.t.iter().zip(&x).enumerate() {
        assert_eq!(t, k as f64 * dt, "sample time exact");
        // analytical x = cos ωt; dense-output error O(h⁵) within the tolerance scale
        assert!((x - (omega * t).cos()).abs() < 1e-8, "t = {t}: {x}");
    }
    // sampling did not change the steps: the same run without a recorder takes the same steps
    let mut plain = DormandPrince::new(1e-10, 1e-12)
        .stepper(&sys, s0.clone())
        .unwrap();
    Stepper::advance_to(&mut plain, &sys, t_end, &mut ()).unwrap();
    assert_eq!(plain.stats(), dp.stats());
    assert_eq!(plain.state(), dp.state());
    // RK4 (no dense output): advanced to every sample time, h = 0.01 (4th order, ~1e-8)
    let mut rk = Rk4::new(0.01).stepper(&sys, s0).unwrap();
    let hist = run(&mut rk);
    assert_eq!(hist.t.len(), n);
    for (k, (&t, &x)) in hist
        .t
        .iter()
        .zip(&hist.column("x [m]").unwrap())
        .enumerate()
    {
        assert_eq!(t, k as f64 * dt);
        assert!((x - (omega * t).cos()).abs() < 1e-7, "t = {t}: {x}");
    }
    let mut csv = Vec::new();
    hist.write_csv(&mut csv, "test").unwrap();
    assert_eq!(String::from_utf8(csv).unwrap().lines().count(), n + 1);
}

/// A point mass `m` in the plane (x, y) under gravity −g y.
type Block = PointMasses;

fn block(m: f64, g: f64) -> Block {
    PointMasses {
        m: vec![m],
        dim: 2,
        g,
        lift: f64::INFINITY,
    }
}

/// Rigid floor y ≥ 0 under a block sliding along x: index-3 unilateral contact (gap g = y,
/// J_n = e_y) with set-valued Coulomb friction (J_t = e_x), solved on the Delassus operator
/// W = J S⁻¹ Jᵀ as forces consistent with the generalized-α formulas (the tire's form).
struct SlidingFloor {
    mu: f64,
    /// Normal and tangential contact forces of the last step \[N\].
    force: [f64; 2],
}

impl StepCorrection<Block> for SlidingFloor {
    fn correct(&mut self, _sys: &Block, step: &mut AlphaCorrection<'_>) -> Result<(), MbdError> {
        self.force = [0.0; 2];
        let gap = step.q()[1];
        if gap >= 0.0 {
            return Ok(());
        }
        let (bp, gp) = (step.beta_prime(), step.gamma_prime());
        // columns of S⁻¹ Jᵀ: responses to unit normal and tangential forces
        let (mut xn, mut xt) = ([0.0; 2], [0.0; 2]);
        step.solve(&[0.0, 1.0], &mut xn, &mut [])?;
        step.solve(&[1.0, 0.0], &mut xt, &mut [])?;
        let w = [[xt[0], xn[0]], [xt[1], xn[1]]]; // W = J S⁻¹ Jᵀ, rows (t, n)
        // normal: gap + W_nn λ_n / β' = 0 (closes the gap), λ_n ≥ 0
        let lam_n = (-bp * gap / w[1][1]).max(0.0);
        // tangential: stick if the force that stops the sliding velocity lies in the cone
        // |λ_t| ≤ μ λ_n, else slide with λ_t = −μ λ_n sign(v_t)
        let vt = step.v()[0] + gp / bp * w[0][1] * lam_n;
        let stick = -bp / gp * vt / w[0][0];
        let lam_t = stick.clamp(-self.mu * lam_n, self.mu * lam_n);
        step.apply_force(&[lam_t, lam_n])?;
        self.force = [lam_n, lam_t];
        Ok(())
    }
}

/// Rigid floor y ≥ 0 hit by a falling block: inelastic index-3 contact as in the nonsmooth
/// generalized-α scheme, a position correction closing the gap and a velocity jump with
/// Newton's impact law of restitution 0 (`0 ≤ v_n⁺ ⊥ Λ ≥ 0`).
struct ImpactFloor {
    mass: f64,
    /// Normal impulse of the last step \[N·s\].
    impulse: f64,
}

impl StepCorrection<Block> for ImpactFloor {
    fn correct(&mut self, _sys: &Block, step: &mut AlphaCorrection<'_>) -> Result<(), MbdError> {
        self.impulse = 0.0;
        let gap = step.q()[1];
        if gap >= 0.0 {
            return Ok(());
        }
        // δq = M⁻¹ Jᵀ ν with ν = −m g: the gap closes
        step.apply_position_correction(&[0.0, -gap]);
        // Λ = max(0, −m v_n): the contact keeps zero normal velocity
        let lam = (-self.mass * step.v()[1]).max(0.0);
        step.apply_velocity_jump(&[0.0, lam / self.mass]);
        self.impulse = lam;
        Ok(())
    }
}

#[test]
fn mass_falls_onto_a_rigid_floor_and_rests() {
    let (m, g, y0, h) = (2.0, 9.81, 0.5, 1e-3);
    let sys = block(m, g);
    let ga = GeneralizedAlpha::new(AlphaConfig {
        h,
        rho_inf: 0.5,
        ..Default::default()
    });
    let s0 = State::new(0.0, vec![0.0, y0], vec![0.0, 0.0]);
    let floor = ImpactFloor {
        mass: m,
        impulse: 0.0,
    };
    let mut st = ga.stepper_with(&sys, s0, floor).unwrap();
    let mut impact = None;
    let mut min_y = f64::INFINITY;
    let mut max_y_after = f64::NEG_INFINITY;
    while st.step_until(&sys, 1.0).unwrap() {
        let s = st.state();
        min_y = min_y.min(s.q[1]);
        if impact.is_some() {
            max_y_after = max_y_after.max(s.q[1]);
        }
        if impact.is_none() && st.correction().impulse > 0.0 {
            impact = Some(s.t);
        }
    }
    // analytical free-fall impact time √(2 y₀/g): contact first acts in the step containing it
    let t_star = (2.0 * y0 / g).sqrt();
    let ti = impact.expect("impact");
    assert!(
        ti >= t_star && ti < t_star + h + 1e-12,
        "impact at {ti}, analytical {t_star}"
    );
    // never below the floor, no rebound (inelastic), at rest on it
    assert!(min_y > -1e-12, "penetration {min_y}");
    assert!(max_y_after < 1e-12, "rebound to {max_y_after}");
    let s = st.state();
    assert!(s.q[1].abs() < 1e-12, "rest position {}", s.q[1]);
    assert!(s.v[1].abs() < 1e-12, "rest velocity {}", s.v[1]);
    // at rest the floor carries the weight: impulse m g h per step
    let f = st.correction().impulse / h;
    assert!((f - m * g).abs() < 1e-6 * m * g, "normal force {f}");
}

#[test]
fn block_slides_with_coulomb_friction_at_mu_g() {
    let (m, g, mu, v0, h) = (3.0, 9.81, 0.3, 2.0, 1e-3);
    let sys = block(m, g);
    let ga = GeneralizedAlpha::new(AlphaConfig {
        h,
        rho_inf: 0.5,
        ..Default::default()
    });
    let s0 = State::new(0.0, vec![0.0, 0.0], vec![v0, 0.0]);
    let mut st = ga
        .stepper_with(
            &sys,
            s0,
            SlidingFloor {
                mu,
                force: [0.0; 2],
            },
        )
        .unwrap();
    // analytical: v(t) = v₀ − μ g t until t_s = v₀/(μ g), x(t_s) = v₀²/(2 μ g), then sticking
    let t_s = v0 / (mu * g);
    let mut worst_v = 0.0f64;
    while st.step_until(&sys, 1.2 * t_s).unwrap() {
        let s = st.state();
        let v_ref = (v0 - mu * g * s.t).max(0.0);
        if (s.t - t_s).abs() > 3.0 * h {
            worst_v = worst_v.max((s.v[0] - v_ref).abs());
        }
    }
    assert!(worst_v < 1e-3 * v0, "sliding velocity error {worst_v}");
    let s = st.state();
    assert!(s.v[0].abs() < 1e-9, "sticks: v = {}", s.v[0]);
    let x_s = v0 * v0 / (2.0 * mu * g);
    assert!(
        (s.q[0] - x_s).abs() < 2.0 * v0 * h,
        "stop at {} vs {x_s}",
        s.q[0]
    );
}

/// Hardening spring `ẍ + k₃ x³ = 0` with a finite-difference tangent: Newton needs more
/// iterations the longer the step, so a step can fail where its halves converge.
struct Duffing {
    k3: f64,
}

impl mbd_core::SecondOrderSystem for Duffing {
    fn n_q(&self) -> usize {
        1
    }
    fn mass_is_constant(&self) -> bool {
        true
    }
    fn mass(&self, _t: f64, _q: &[f64]) -> Result<mbd_core::SysMatrix, MbdError> {
        Ok(support::diagonal(&[1.0]))
    }
    fn forces(
        &self, _t: f64, q: &[f64], _v: &[f64], f: &mut [f64], _ws: &mut mbd_core::Workspace,
    ) -> Result<(), MbdError> {
        f[0] = -self.k3 * q[0].powi(3);
        Ok(())
    }
}

/// The step split of the drives' former `robust_step`, written against a stepper without
/// subdivision: one step of `h`, else two halves, recursively `depth` levels.
fn split_by_hand(
    st: &mut mbd_core::integrators::AlphaStepper, sys: &Duffing, h: f64, depth: usize,
) -> Result<(), MbdError> {
    match st.step(sys, Some(h)) {
        Err(MbdError::NoConvergence { .. }) if depth > 0 => {
            split_by_hand(st, sys, 0.5 * h, depth - 1)?;
            split_by_hand(st, sys, 0.5 * h, depth - 1)
        }
        other => other,
    }
}

#[test]
fn alpha_subdivisions_split_a_failed_step_and_keep_the_grid() {
    let sys = Duffing { k3: 1e4 };
    let s0 = State::new(0.0, vec![1.0], vec![0.0]);
    let cfg = AlphaConfig {
        h: 0.02,
        max_newton_iterations: 3,
        ..Default::default()
    };
    // without subdivision the step fails (the premise of the test)
    let mut plain = GeneralizedAlpha::new(cfg)
        .stepper(&sys, s0.clone())
        .unwrap();
    assert!(matches!(
        plain.step(&sys, Some(0.02)),
        Err(MbdError::NoConvergence { .. })
    ));
    assert_eq!(
        plain.state().t,
        0.0,
        "a failed step leaves the state unchanged"
    );
    // with subdivision: ends on t + h exactly, halvings counted, and the same state bit for
    // bit as the hand-written recursive split (second formulation)
    let mut split = GeneralizedAlpha::new(AlphaConfig {
        subdivisions: 6,
        ..cfg
    })
    .stepper(&sys, s0.clone())
    .unwrap();
    let mut by_hand = GeneralizedAlpha::new(cfg).stepper(&sys, s0).unwrap();
    for k in 1..=5 {
        split.step(&sys, Some(0.02)).unwrap();
        split_by_hand(&mut by_hand, &sys, 0.02, 6).unwrap();
        assert_eq!(split.state(), by_hand.state());
        assert!((split.state().t - 0.02 * k as f64).abs() < 1e-15);
    }
    let stats = Stepper::<Duffing>::stats(&split);
    assert!(stats.halvings > 0);
    assert_eq!(stats.halvings, stats.rejected_steps);
    assert!(stats.steps > 5);
}

/// Two unit masses: a spring (`k = 1`) on the first, and on the second a push `F₀` for
/// `t > 0` whose force turns, past `x = q₁`, into a negative stiffness of exactly `k_n`
/// (`f = F₀ + k_n (x − q₁)`), with the analytic tangent. With `k_n = β'` of the step `h₀`
/// (the Newton matrix `M + γ'/β' C + K/β'`) the Newton matrix at any iterate past `q₁` is
/// singular at that step and regular at `h₀/2` (`1 − k_n/(4 β') = 3/4`).
struct SofteningPush {
    f0: f64,
    q1: f64,
    kn: f64,
}

impl mbd_core::SecondOrderSystem for SofteningPush {
    fn n_q(&self) -> usize {
        2
    }
    fn mass_is_constant(&self) -> bool {
        true
    }
    fn mass(&self, _t: f64, _q: &[f64]) -> Result<mbd_core::SysMatrix, MbdError> {
        Ok(support::diagonal(&[1.0, 1.0]))
    }
    fn forces(
        &self, t: f64, q: &[f64], _v: &[f64], f: &mut [f64], _ws: &mut mbd_core::Workspace,
    ) -> Result<(), MbdError> {
        f[0] = -q[0];
        f[1] = if t > 0.0 { self.f0 } else { 0.0 } + self.kn * (q[1] - self.q1).max(0.0);
        Ok(())
    }
    fn force_tangent(
        &self, _t: f64, q: &[f64], _v: &[f64], _ws: &mut mbd_core::Workspace,
    ) -> Result<Option<mbd_core::ForceTangent>, MbdError> {
        let k1 = if q[1] > self.q1 { -self.kn } else { 0.0 };
        Ok(Some(mbd_core::ForceTangent {
            stiffness: support::diagonal(&[1.0, k1]),
            damping: support::diagonal(&[0.0, 0.0]),
        }))
    }
}

// Reference (second formulation): a step whose Newton iterate lands where the Newton matrix is
// singular fails as a Newton failure (NoConvergence, state unchanged), so that the subdivided
// step completes on its halves, bit for bit the two half steps taken by hand; a system whose
// matrix is singular at the step's start still reports Singular (the model's, not the
// iterate's).
#[test]
fn a_singular_newton_matrix_at_an_iterate_halves_the_step() {
    let h0 = 1e-3;
    let cfg = AlphaConfig {
        h: h0,
        ..Default::default()
    };
    let (am, af, beta, _) = cfg.alpha_coefficients();
    let bp = (1.0 - am) / (h0 * h0 * beta * (1.0 - af));
    let f0 = 1.0;
    // the first iterate lands on the linear region's solution, about β h² F₀/(1 − α_m)…
    // q₁ at a fifth of it: past q₁, before the half step's end
    let sys = SofteningPush {
        f0,
        q1: 0.2 * beta * h0 * h0 * f0,
        kn: bp,
    };
    let s0 = State::new(0.0, vec![1e-3, 0.0], vec![0.0, 0.0]);
    let mut plain = GeneralizedAlpha::new(cfg)
        .stepper(&sys, s0.clone())
        .unwrap();
    let r = plain.step(&sys, Some(h0));
    assert!(matches!(r, Err(MbdError::NoConvergence { .. })), "{r:?}");
    assert_eq!(
        plain.state().t,
        0.0,
        "a failed step leaves the state unchanged"
    );
    let mut split = GeneralizedAlpha::new(AlphaConfig {
        subdivisions: 2,
        ..cfg
    })
    .stepper(&sys, s0.clone())
    .unwrap();
    split.step(&sys, Some(h0)).unwrap();
    let mut by_hand = GeneralizedAlpha::new(cfg)
        .stepper(&sys, s0.clone())
        .unwrap();
    by_hand.step(&sys, Some(0.5 * h0)).unwrap();
    by_hand.step(&sys, Some(0.5 * h0)).unwrap();
    assert_eq!(split.state(), by_hand.state());
    assert!(split.state().q[1] > sys.q1, "the step ends past q₁");
    assert!(Stepper::<SofteningPush>::stats(&split).halvings > 0);
    // singular at the step's start (the second mass's whole row is zero there): Singular
    let zero = SofteningPush {
        f0: 0.0,
        q1: -1.0,
        kn: bp,
    };
    let mut at_start = GeneralizedAlpha::new(AlphaConfig {
        subdivisions: 2,
        ..cfg
    })
    .stepper(&zero, s0)
    .unwrap();
    let r = at_start.step(&zero, Some(h0));
    assert!(matches!(r, Err(MbdError::Singular { .. })), "{r:?}");
}
