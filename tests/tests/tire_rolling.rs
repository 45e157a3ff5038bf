//! Rolling reduced tire with flowing material (Ribaric ch. 7-8, issue 9 validation): steady
//! rolling without ripple, the cleat response and the friction sensitivity, on a coarse
//! generated truck tire (96 x 8 elements, 33 contact nodes, 50 free-node modes).

use flowing::tire::*;
use std::sync::OnceLock;

fn tire() -> &'static ReducedTire {
    static T: OnceLock<ReducedTire> = OnceLock::new();
    T.get_or_init(|| {
        let fe = generated_tire(&coarse_tire_config(96, 8, 20.0)).expect("tire");
        let cfg = ReductionConfig {
            contact_nodes: 33,
            free_modes: 50,
            ..Default::default()
        };
        reduce(&fe, &cfg).expect("reduce").0
    })
}

fn rig(kind: GroundKind, cleat: bool, mu: f64) -> RigConfig {
    let mut rc = RigConfig::default();
    rc.ground.kind = kind;
    rc.ground.cleat = cleat;
    rc.rolling.friction = mu;
    rc
}

#[test]
fn steady_rolling_on_a_flat_road_is_constant_and_carries_the_load() {
    // Seed TIRE-2: the stationary (non-rolling) mesh gives a steady state fixed in the mesh; the
    // vertical spindle force equals the preload and shows no ripple from the discretisation.
    let red = tire();
    let mut rc = rig(GroundKind::Road, false, 0.0);
    rc.settle_time = 0.3;
    rc.record_time = 0.1;
    let r = run_cleat(red, &rc, &mut |_| {}).unwrap();
    let last: Vec<&Sample> = r.samples.iter().filter(|s| s.t > 0.0).collect();
    let fy: Vec<f64> = last.iter().map(|s| s.fy).collect();
    let fx: Vec<f64> = last.iter().map(|s| s.fx).collect();
    let mean = fy.iter().sum::<f64>() / fy.len() as f64;
    let spread =
        fy.iter().cloned().fold(f64::MIN, f64::max) - fy.iter().cloned().fold(f64::MAX, f64::min);
    assert!(
        (mean - rc.load).abs() < 0.01 * rc.load,
        "Fy {mean} vs load {}",
        rc.load
    );
    assert!(spread < 0.005 * rc.load, "Fy ripple {spread} N");
    let sx =
        fx.iter().cloned().fold(f64::MIN, f64::max) - fx.iter().cloned().fold(f64::MAX, f64::min);
    assert!(sx < 0.005 * rc.load, "Fx ripple {sx} N");
    // rolling resistance from the material damping only: small and resisting (Fx of the tire on
    // the wheel points backwards, −x, when the ground moves towards −x under a forward-rolling
    // tire: it drags the spindle along with the ground)
    let fxm = fx.iter().sum::<f64>() / fx.len() as f64;
    assert!(fxm.abs() < 0.02 * rc.load, "rolling resistance {fxm} N");
}

#[test]
fn penalty_contact_converges_to_the_lagrange_solution() {
    // Independent second formulation: a stiff penalty law tends to the rigid constraint.
    let red = tire();
    let mut a = rig(GroundKind::Road, false, 0.0);
    a.settle_time = 0.15;
    a.record_time = 0.05;
    let mut b = a.clone();
    b.rolling.normal = NormalContact::Penalty { stiffness: 1e9 };
    let ra = run_cleat(red, &a, &mut |_| {}).unwrap();
    let rb = run_cleat(red, &b, &mut |_| {}).unwrap();
    let (ya, yb) = (ra.samples.last().unwrap().fy, rb.samples.last().unwrap().fy);
    assert!((ya - yb).abs() < 0.01 * ya, "Lagrange {ya} vs penalty {yb}");
}

#[test]
fn cleat_excites_a_tire_mode_and_friction_mainly_changes_fx() {
    let red = tire();
    let freqs = red.frequencies_hz().unwrap();
    let r85 = run_cleat(red, &rig(GroundKind::Drum, true, 0.85), &mut |_| {}).unwrap();
    let r0 = run_cleat(red, &rig(GroundKind::Drum, true, 0.0), &mut |_| {}).unwrap();
    // the dominant vertical frequency is a natural frequency of the tire (within the spectral
    // resolution 1/T of the record, plus the shift of the rolling, loaded tire)
    let (_, sy) = r85.spectra();
    let (fpk, _) = sy.peak(10.0, 500.0).unwrap();
    let res = 1.0 / 0.3;
    let nearest = freqs
        .iter()
        .map(|f| (f - fpk).abs())
        .fold(f64::MAX, f64::min);
    assert!(
        nearest < 2.0 * res + 0.05 * fpk,
        "Fy peak {fpk} Hz, nearest mode {nearest} Hz away"
    );
    // Ribaric §8.4.3, Fig. 8-11: friction mainly affects Fx
    let (x85, y85) = r85.rms();
    let (x0, y0) = r0.rms();
    let dx = (x85 - x0).abs() / x85.max(x0);
    let dy = (y85 - y0).abs() / y85.max(y0);
    assert!(dx > dy, "relative change Fx {dx} vs Fy {dy}");
}
