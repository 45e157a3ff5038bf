//! Kerkkänen §2.4 dynamic tests through mbd-core's generalized-α integrator: energy balance of
//! the falling flexible pendulum (2.34) and the steady extension of the spinning beam (2.36).

use flowmbd_cases::ancf_dynamics::{
    PendulumCase, SpinningCase, energy_drift, hub_angle, pendulum, spinning, spinning_extension,
};

// Kerkkänen Fig. 2.7: with 4 elements the total energy T + U + V stays constant; the thesis
// reports a largest deviation of 0.62e-4 J, the issue asks for < 1e-4 J. Generalized-α with
// ρ∞ = 1 (no numerical dissipation), h = 5e-5 s, 1 s of motion.
#[test]
fn pendulum_energy_is_conserved() {
    let case = PendulumCase {
        h: 5e-5,
        t_end: 1.0,
        ..Default::default()
    };
    let s = pendulum(&case, 20, |_| {}).expect("pendulum run");
    let drift = energy_drift(&s);
    assert!(drift < 1e-4, "largest total-energy deviation {drift:e} J");
    // the pendulum really falls: 1.2 kJ exchanged between potential and kinetic energy
    let tmax = s.iter().map(|x| x.energy.kinetic).fold(0.0, f64::max);
    assert!(tmax > 1000.0, "max T = {tmax} J");
    let last = s.last().unwrap();
    assert!(last.energy.strain > 1.0);
    // pin constraint holds: the tip stays within the beam length of the pin
    assert!((last.tip[0].powi(2) + last.tip[1].powi(2)).sqrt() < 2.01);
}

// Kerkkänen (2.36)–(2.37): steady axial extension 1.09545e-4 m of the Wu–Haug beam at 4 rad/s;
// the FE value (3 elements, 20 s) must lie within 2 % (mean of the last 2 s, small vibrations
// persist).
#[test]
fn spinning_beam_steady_extension() {
    let case = SpinningCase::default();
    let s = spinning(&case, 10, |_| {}).expect("spinning run");
    let tail: Vec<f64> = s.iter().filter(|x| x.t >= 18.0).map(|x| x.value).collect();
    let mean = tail.iter().sum::<f64>() / tail.len() as f64;
    let printed = 1.09545e-4;
    assert!(
        (mean - printed).abs() < 0.02 * printed,
        "extension {mean:e} m vs {printed:e} m"
    );
    // and our evaluation of (2.37) agrees with the printed value to 0.03 % (seed note §7.4)
    let exact = spinning_extension(8.0, 2766.67, 6.895e10, 4.0);
    assert!((exact - printed).abs() < 3e-4 * printed);
    // the hub profile (2.35) is C¹ at T_s
    let a = hub_angle(15.0 - 1e-9, 4.0, 15.0);
    let b = hub_angle(15.0, 4.0, 15.0);
    assert!((a[0] - b[0]).abs() < 1e-8 && (a[1] - b[1]).abs() < 1e-8);
}

// Kerkkänen Fig. 2.8: with 8 elements the proposed and the Omar–Shabana element give nearly the
// same tip motion of the falling pendulum (second formulation as reference); 0.6 s, h = 2e-4 s.
#[test]
fn pendulum_proposed_agrees_with_omar_shabana() {
    use ancf::beam_mesh::BeamElementKind;
    let run = |element| {
        let case = PendulumCase {
            element,
            elements: 8,
            t_end: 0.6,
            h: 2e-4,
            ..Default::default()
        };
        pendulum(&case, 50, |_| {}).expect("pendulum run")
    };
    let p = run(BeamElementKind::Proposed);
    let o = run(BeamElementKind::OmarShabana);
    assert_eq!(p.len(), o.len());
    for (a, b) in p.iter().zip(&o) {
        let d = ((a.tip[0] - b.tip[0]).powi(2) + (a.tip[1] - b.tip[1]).powi(2)).sqrt();
        assert!(
            d < 0.02,
            "t = {}: tips differ by {d} m (1 % of L allowed)",
            a.t
        );
    }
    // the tip has fallen by more than a metre by then
    assert!(p.last().unwrap().tip[1] < -1.0);
}
