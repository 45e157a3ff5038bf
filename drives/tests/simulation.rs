//! The stepping API (`drives::AnySimulation`, issue 39 item 6) against independent references:
//! the prescribed driver schedule (Ribaric §6.4's C¹ smooth step), Newton's second law of the
//! loaded pulley in a steady state, and the refused inputs.

use drives::belt::Signal;
use drives::{AnySimulation, DriveSimulationConfig, ModelKind, SimulationBuildError};
use mbd_core::integrators::State;

/// Ribaric §6.4's schedule between two knots: `y0 + (y1 − y0)(3τ² − 2τ³)`.
fn smoothstep(t: f64, t1: f64, y1: f64) -> f64 {
    let tau = (t / t1).clamp(0.0, 1.0);
    y1 * tau * tau * (3.0 - 2.0 * tau)
}

#[test]
fn driver_follows_its_schedule_and_the_load_is_carried() {
    let c = DriveSimulationConfig::default();
    let mut sim = AnySimulation::new(&c).unwrap();
    assert_eq!(sim.kind(), ModelKind::Flowing);
    let mut seen = 0;
    sim.run_to(0.05, |_| seen += 1).unwrap();
    assert_eq!(seen, 200);
    let w = sim.pulley_speeds();
    // the driver's speed is prescribed: 0 -> 62.8 rad/s over 0.3 s (the default schedule)
    assert!(
        (w[0] - smoothstep(sim.state().t, 0.3, 62.8)).abs() < 1e-9,
        "{w:?}"
    );
    // held at 62.8 rad/s and loaded with 4 N m from now on; steady after 0.5 s: the contact
    // torque on the driven pulley equals its load (J ω̇ = τ − M with ω̇ → 0)
    sim.set_signal(0, Signal::constant(62.8)).unwrap();
    sim.set_signal(1, Signal::constant(4.0)).unwrap();
    sim.run_to(0.6, |_| {}).unwrap();
    let r = sim.report().unwrap();
    let tau = r.pulleys[1].torque_n_m;
    assert!(
        (tau - 4.0).abs() < 0.02,
        "driven contact torque {tau} N m against the 4 N m load"
    );
    assert!(
        sim.pulley_speeds()[1] < 62.8,
        "the driven pulley lags: speed loss"
    );
}

#[test]
fn refused_inputs_name_the_field() {
    let mut c = DriveSimulationConfig {
        step: 0.0,
        ..Default::default()
    };
    match AnySimulation::new(&c) {
        Err(SimulationBuildError::Input(f)) => assert_eq!(f.field, "step"),
        other => panic!("step 0 accepted: {:?}", other.err()),
    }
    c.step = 2.5e-4;
    c.drive.belt.ea = -1.0;
    match AnySimulation::new(&c) {
        Err(SimulationBuildError::Input(f)) => assert_eq!(f.field, "drive.belt.ea"),
        other => panic!("negative EA accepted: {:?}", other.err()),
    }
    let mut sim = AnySimulation::new(&DriveSimulationConfig::default()).unwrap();
    let n = sim.coordinates();
    assert!(
        sim.set_state(State::new(0.0, vec![0.0; n + 1], vec![0.0; n + 1]))
            .is_err()
    );
    assert!(sim.set_signal(5, Signal::constant(1.0)).is_err());
}
