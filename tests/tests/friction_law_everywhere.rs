//! One friction law, every model (issue 15, item 4): the Stribeck law of
//! `contact/src/friction/stribeck.rs` runs in the flowing belt (Ribaric ch. 5–6), the ANCF belt
//! drive (Kerkkänen ch. 3) and the rolling tire (Ribaric ch. 7–8), each through the one
//! `contact::FrictionLaw` trait.
//!
//! Reference (second formulation): with `μ_s = μ_k` the Stribeck law is the Coulomb–tanh law
//! of Ribaric (6.2), so each model must reproduce its run with `CoulombTanh` to 1e-9. With
//! `μ_s > μ_k` the run must differ, and friction must stay dissipative (`f_t·v_t ≤ 0` at every
//! contact point).

use contact::FrictionSpec;
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha, Stepper};

use crate::common;

const KAPPA: f64 = 40.0;

fn stribeck(mu_static: f64, mu_kinetic: f64) -> FrictionSpec {
    FrictionSpec::Stribeck {
        mu_static,
        mu_kinetic,
        stribeck_velocity: 0.05,
        kappa: KAPPA,
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1e-12)
}

/// Flowing belt (Table 6-1 drive): driver spun up to 30 rad/s in 20 ms under a 4 N·m load,
/// 40 ms of generalized-α; returns the driven speed and whether friction dissipated at every
/// contact node of the final state.
fn flowing_run(law: FrictionSpec) -> (f64, bool) {
    use belt::{BeltModel, Motion, Signal};
    use flowing::belt::{ContactVelocity, FlowingBelt, FlowingSettings, ViscousForce};
    let mut cfg = drives::table_6_1::layout();
    cfg.contact.friction = law;
    cfg.pulleys[0].motion = Motion::speed(Signal::schedule(vec![(0.0, 0.0), (0.02, 30.0)]));
    cfg.pulleys[1].motion = Motion::load(0.013, Signal::schedule(vec![(0.0, 0.0), (0.02, 4.0)]));
    // one formulation for every law, stated (the defaults, `auto`, take Ribaric's operator with
    // the tanh law and the chords' with any other)
    let settings = FlowingSettings {
        contact_velocity: ContactVelocity::Ribaric,
        viscous_force: ViscousForce::Linear,
        ..FlowingSettings::default()
    };
    let belt = FlowingBelt::new(&cfg.resolve().unwrap(), &settings).unwrap();
    let s0 = belt.initial_state().unwrap();
    let h = 2.5e-4;
    let mut st = GeneralizedAlpha::new(AlphaConfig {
        h,
        rho_inf: 0.8,
        ..Default::default()
    })
    .stepper(&belt, s0)
    .unwrap();
    for _ in 0..160 {
        st.step(&belt, Some(h)).unwrap();
    }
    let s = st.state();
    let dissipative = belt
        .contact_report(s.t, &s.q, &s.v)
        .iter()
        .all(|r| r.contact.friction * r.contact.slip <= 0.0);
    (belt.pulley_speed(1, s.t, &s.v), dissipative)
}

/// ANCF belt drive (Kerkkänen Table 3.1 drive): driver at a constant 12 rad/s from the
/// pre-strained state with the belt travelling at the pulley surface speed, 10 ms of
/// generalized-α; returns the driven speed and whether friction dissipated at every quadrature
/// point of the final state.
fn ancf_run(law: FrictionSpec) -> (f64, bool) {
    use ancf::belt_drive::{BeltDrive, BeltDriveSpec, InitialOptions, SimulationConfig};
    let mut spec = BeltDriveSpec::default();
    spec.contact.friction = law;
    spec.pulleys[0].motion = belt::Motion::speed(belt::Signal::constant(12.0));
    let d = BeltDrive::new(spec).unwrap();
    let init = d.initial_state(&InitialOptions::default()).unwrap();
    let v0 = d.travelling_velocity(&init.q, 12.0 * 0.08125);
    let state = mbd_core::integrators::State::new(0.0, init.q.clone(), v0);
    let sol = GeneralizedAlpha::new(SimulationConfig::default().alpha_params())
        .integrate(&d, state, 0.01, |_| {})
        .unwrap();
    let s = &sol.state;
    let dissipative = d
        .contact_records(s.t, &s.q, &s.v)
        .iter()
        .all(|r| r.friction_force * r.slip <= 0.0);
    (s.v[d.pulley_dof(1).unwrap()], dissipative)
}

/// Rolling tire (coarse generated tire on a flat road, 60 km/h): 40 ms settling and 10 ms
/// record; returns the last longitudinal and vertical spindle forces \[N\].
fn tire_run(law: FrictionSpec) -> (f64, f64) {
    use tire::{GroundKind, TireFriction, run_cleat};
    let mut rc = common::rig(GroundKind::Road, false, law.mu());
    rc.rolling.friction_law = TireFriction::Law(law);
    rc.settle_time = 0.04;
    rc.record_time = 0.01;
    let r = run_cleat(common::coarse_reduced_tire(), &rc, &mut |_| {}).unwrap();
    let last = r.samples.last().unwrap();
    (last.fx, last.fy)
}

#[test]
fn stribeck_runs_in_flowing_belt_ancf_belt_and_tire() {
    let tanh = |mu| FrictionSpec::Tanh { mu, kappa: KAPPA };

    // flowing belt (Ribaric (6.2): μ = 1.2)
    let (w_ref, diss_ref) = flowing_run(tanh(1.2));
    let (w_same, _) = flowing_run(stribeck(1.2, 1.2));
    let (w_peak, diss_peak) = flowing_run(stribeck(1.6, 1.2));
    println!("flowing belt ω₂: tanh {w_ref}, Stribeck μs = μk {w_same}, μs = 1.6 {w_peak}");
    assert!(close(w_ref, w_same), "flowing: {w_ref} vs {w_same}");
    assert!(diss_ref && diss_peak, "flowing: friction not dissipative");
    assert!(
        (w_peak - w_ref).abs() > 1e-9 * w_ref.abs(),
        "flowing: Stribeck had no effect"
    );

    // ANCF belt
    let (a_ref, adiss_ref) = ancf_run(tanh(1.2));
    let (a_same, _) = ancf_run(stribeck(1.2, 1.2));
    let (a_peak, adiss_peak) = ancf_run(stribeck(1.6, 1.2));
    assert!(a_ref > 1.0, "ANCF: the driven pulley turns ({a_ref} rad/s)");
    println!("ANCF belt ω₂: tanh {a_ref}, Stribeck μs = μk {a_same}, μs = 1.6 {a_peak}");
    assert!(close(a_ref, a_same), "ANCF: {a_ref} vs {a_same}");
    assert!(adiss_ref && adiss_peak, "ANCF: friction not dissipative");
    assert!(
        (a_peak - a_ref).abs() > 1e-9 * a_ref.abs(),
        "ANCF: Stribeck had no effect"
    );

    // rolling tire (Ribaric §8.4.3: μ = 0.85)
    let (fx_ref, fy_ref) = tire_run(tanh(0.85));
    let (fx_same, fy_same) = tire_run(stribeck(0.85, 0.85));
    let (fx_peak, fy_peak) = tire_run(stribeck(1.2, 0.85));
    println!(
        "tire (Fx, Fy): tanh ({fx_ref}, {fy_ref}), Stribeck μs = μk ({fx_same}, {fy_same}), μs = 1.2 ({fx_peak}, {fy_peak})"
    );
    assert!(close(fx_ref, fx_same) && close(fy_ref, fy_same), "tire");
    assert!(
        (fx_peak - fx_ref).abs() > 1e-9 * fy_ref.abs(),
        "tire: Stribeck had no effect"
    );
}
