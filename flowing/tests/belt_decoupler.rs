//! Decoupler on an accessory pulley (issue 36 item 4, `belt::decoupler`) in the flowing and
//! nodal belt models, against independent references:
//!
//! * overrunning after a speed ramp down, the accessory is held only by its own viscous damper
//!   `c`: `J_a ω̇_a = −c ω_a`, so `ω_a(t) = ω_a(t₁) exp(−c (t − t₁)/J_a)` (closed form);
//! * engaged with a stiff spring, the decoupled accessory turns as the rigid accessory of
//!   inertia `J_p + J_r + J_a` (a second formulation: the plain `Motion::Load`).

use belt::{BeltModel, ClutchState, Decoupler, Layout, Motion, Section, Shape, Signal};
use flowing::belt::{BeltMesh, FlowingBelt, FlowingSettings, NodalBelt};
use mbd_core::SecondOrderSystem;
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha, Stepper};

const H: f64 = 2.5e-4;
const J_A: f64 = 0.013;

fn decoupler(stiffness: f64) -> Decoupler {
    Decoupler {
        pulley_inertia: 1e-3,
        stiffness,
        damping: 0.05,
        clutch: true,
        carrier_inertia: 2e-5,
        lock_damping: 1000.0,
        lock_speed: 1e-3,
    }
}

/// Ribaric Table 6-1's geometry (450 mm, two 50 mm pulleys, T0 = 310 N) with the driver's
/// speed `speed` and the driven pulley's `motion`.
fn drive(speed: Signal, motion: Motion) -> belt::Drive {
    let mut l = Layout::two_pulley(
        0.45,
        0.05,
        0.05,
        speed,
        J_A,
        Signal::constant(0.0),
        Section::default(),
        310.0,
    );
    l.pulleys[1].motion = motion;
    l.contact = belt::BeltContact::ribaric();
    l.resolve().unwrap()
}

/// Step `model` to `t_end`, calling `each(t, q, v)` after every step.
fn run<M: BeltModel>(model: &M, t_end: f64, mut each: impl FnMut(&M, f64, &[f64], &[f64])) {
    let alpha = GeneralizedAlpha::new(AlphaConfig {
        h: H,
        rho_inf: 0.8,
        newton_line_search: true,
        ..Default::default()
    });
    let s0 = model.initial_state().unwrap();
    let mut st = alpha.stepper(model, s0).unwrap();
    while st.state().t < t_end - 0.5 * H {
        st.step(model, Some(H)).unwrap();
        let s = st.state();
        each(model, s.t, &s.q, &s.v);
    }
}

/// Up to 60 rad/s in 0.1 s, held to 0.15 s, down to 10 rad/s by 0.2 s.
fn ramp_down() -> Signal {
    Shape::Trace(vec![(0.0, 0.0), (0.1, 60.0), (0.15, 60.0), (0.2, 10.0)]).into()
}

fn coast_down<M: BeltModel>(model: &M) {
    let c = 0.013;
    let (t1, t_end) = (0.25, 0.45);
    let mut w1 = None;
    let mut worst: f64 = 0.0;
    let mut last = None;
    run(model, t_end, |m, t, q, v| {
        let s = m.decoupler_state(1, q, v).unwrap();
        if t >= t1 - 0.5 * H {
            assert_eq!(s.clutch, Some(ClutchState::Overrunning), "t = {t}");
            let (t0, w0) = *w1.get_or_insert((t, s.accessory_speed));
            let exact = w0 * (-c * (t - t0) / J_A).exp();
            worst = worst.max((s.accessory_speed - exact).abs() / exact);
            last = Some((t, s.accessory_speed, m.pulley_speed(1, t, v)));
        }
    });
    let (t, wa, wp) = last.unwrap();
    // the accessory coasts well above the pulley (belt speed 10 rad/s × 50/50 mm)
    assert!(
        wa > 40.0 && wp < 11.0,
        "t = {t}: accessory {wa}, pulley {wp}"
    );
    assert!(worst < 1e-4, "coast-down against exp(−c t/J): {worst:e}");
}

fn decoupled(stiffness: f64, c: f64) -> Motion {
    Motion::Load {
        inertia: J_A,
        torque: Signal::constant(0.0),
        damping: c,
        decoupler: Some(decoupler(stiffness)),
    }
}

#[test]
fn overrunning_accessory_coasts_down_exponentially_flowing() {
    let d = drive(ramp_down(), decoupled(50.0, 0.013));
    let m = FlowingBelt::new(&d, &FlowingSettings::default()).unwrap();
    let plain = FlowingBelt::new(
        &drive(ramp_down(), Motion::load(J_A, Signal::constant(0.0))),
        &FlowingSettings::default(),
    )
    .unwrap();
    // the clutch adds the carrier's and the accessory's coordinates
    assert_eq!(m.n_q(), plain.n_q() + 2);
    coast_down(&m);
}

#[test]
fn overrunning_accessory_coasts_down_exponentially_nodal() {
    let d = drive(ramp_down(), decoupled(50.0, 0.013));
    let m = NodalBelt::new(&d, &BeltMesh::default()).unwrap();
    assert!(m.dof_name(m.n_q() - 1).contains("accessory"));
    coast_down(&m);
}

/// A load step of 3 N m at 60 rad/s: the accessory's mean speed over the last 0.1 s, decoupled
/// (stiff spring, engaged) and rigid.
#[test]
fn engaged_stiff_decoupler_matches_the_rigid_accessory() {
    let speed = Signal::schedule(vec![(0.0, 0.0), (0.1, 60.0)]);
    let load = Signal::schedule(vec![(0.1, 0.0), (0.2, 3.0)]);
    let c = 0.005;
    let dc = decoupler(2000.0);
    let with = Motion::Load {
        inertia: J_A,
        torque: load.clone(),
        damping: c,
        decoupler: Some(dc),
    };
    let rigid = Motion::Load {
        inertia: J_A + dc.pulley_inertia + dc.carrier_inertia,
        torque: load,
        damping: c,
        decoupler: None,
    };
    let settings = FlowingSettings::default();
    let mean = |motion: Motion, accessory: bool| {
        let m = FlowingBelt::new(&drive(speed.clone(), motion), &settings).unwrap();
        let (mut sum, mut n, mut engaged) = (0.0, 0, 0);
        run(&m, 0.4, |m, t, q, v| {
            if t > 0.3 {
                let w = match m.decoupler_state(1, q, v) {
                    Some(s) if accessory => {
                        engaged += usize::from(s.clutch == Some(ClutchState::Engaged));
                        s.accessory_speed
                    }
                    _ => m.pulley_speed(1, t, v),
                };
                sum += w;
                n += 1;
            }
        });
        if accessory {
            assert_eq!(engaged, n, "the clutch opened under a steady load");
        }
        sum / n as f64
    };
    let (wa, wp, wr) = (
        mean(with.clone(), true),
        mean(with, false),
        mean(rigid, false),
    );
    // the belt's speed loss at 3 N m (≈ 0.06 rad/s) is resolved
    assert!((wr - 60.0).abs() > 0.03, "rigid accessory at {wr} rad/s");
    assert!(
        (wp - wr).abs() < 1e-4,
        "decoupled pulley {wp} vs rigid {wr} rad/s"
    );
    // the engaged clutch (D2) creeps by x = C/c_l with C = M_load + c ω
    let creep = (3.0 + c * wr) / dc.lock_damping;
    assert!(
        (wr - wa - creep).abs() < 1e-4,
        "decoupled accessory {wa} vs rigid {wr} − creep {creep} rad/s"
    );
}
