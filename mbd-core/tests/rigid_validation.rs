//! Validation of the rigid multibody layer against analytic references and invariants.

use mbd_core::body::BodyState;
use mbd_core::constraints::*;
use mbd_core::forces::{AppliedForce, Gravity};
use mbd_core::integrators::{
    AlphaConfig, DormandPrince, Event, GeneralizedAlpha, Rk4, Stabilization, State, accelerations,
    project_velocities,
};
use mbd_core::kinematics::euler::{a_matrix, from_axis_angle};
use mbd_core::marker::Marker;
use mbd_core::{MbdError, MultibodySystem, RigidBody, SecondOrderSystem};
use nalgebra::{Vector3, Vector4};
use std::f64::consts::PI;
use std::sync::Arc;

fn ident() -> Vector4<f64> {
    Vector4::new(1.0, 0.0, 0.0, 0.0)
}

// ---------------------------------------------------------------------------------------------
// Torque-free asymmetric body
// ---------------------------------------------------------------------------------------------

fn torque_free() -> (MultibodySystem, State) {
    let mut sys = MultibodySystem::new();
    sys.add_body(RigidBody::with_principal("box", 2.0, [1.0, 2.0, 2.5]).unwrap());
    let p = from_axis_angle(&Vector3::new(1.0, 2.0, 0.5), 0.7);
    let st = BodyState {
        r: Vector3::new(0.1, -0.2, 0.3),
        p,
        rdot: Vector3::new(0.05, 0.0, -0.02),
        // spin close to the intermediate principal axis: unstable, the axis flips
        omega_local: Vector3::new(0.01, 1.0, 0.01),
    };
    let s0 = sys.state(0.0, &[st]).unwrap();
    (sys, s0)
}

#[test]
fn torque_free_body_conserves_momentum_and_energy_and_flips() {
    // Invariants (Lin (2.26) with n' = 0): inertial angular momentum and kinetic energy.
    let (sys, s0) = torque_free();
    let h0 = sys.angular_momentum(&s0);
    let e0 = sys.kinetic_energy(&s0);
    let mut wy_min = f64::INFINITY;
    let mut max_dh = 0.0f64;
    let mut max_de = 0.0f64;
    let dp = DormandPrince::new(1e-11, 1e-12);
    let sol = dp
        .integrate(&sys, s0.clone(), 100.0, |s| {
            wy_min = wy_min.min(s.v[4]);
            max_dh = max_dh.max((sys.angular_momentum(s) - h0).norm() / h0.norm());
            max_de = max_de.max((sys.kinetic_energy(s) - e0).abs() / e0);
        })
        .unwrap();
    assert!((sol.state.t - 100.0).abs() < 1e-12);
    assert!(max_dh < 1e-8, "angular momentum drift {max_dh:e}");
    assert!(max_de < 1e-8, "energy drift {max_de:e}");
    // intermediate-axis (Dzhanibekov) flip: ω'_y reverses
    assert!(wy_min < -0.9, "no flip: min ω'_y = {wy_min}");
    println!(
        "DP5 torque-free: dH {max_dh:e} dE {max_de:e} stats {:?}",
        sol.stats
    );

    // RK4 with a fixed step and generalized-α (ρ∞ = 1, no numerical damping): bounded drift
    let rk = Rk4::new(2e-3)
        .integrate(&sys, s0.clone(), 100.0, |_| {})
        .unwrap();
    let dh = (sys.angular_momentum(&rk.state) - h0).norm() / h0.norm();
    let de = (sys.kinetic_energy(&rk.state) - e0).abs() / e0;
    assert!(dh < 1e-7 && de < 1e-7, "rk4 dH {dh:e} dE {de:e}");
    let ga = GeneralizedAlpha::new(AlphaConfig {
        h: 2e-3,
        rho_inf: 1.0,
        ..Default::default()
    })
    .integrate(&sys, s0, 100.0, |_| {})
    .unwrap();
    let dh = (sys.angular_momentum(&ga.state) - h0).norm() / h0.norm();
    let de = (sys.kinetic_energy(&ga.state) - e0).abs() / e0;
    assert!(dh < 1e-3 && de < 1e-3, "gen-alpha dH {dh:e} dE {de:e}");
}

// ---------------------------------------------------------------------------------------------
// Heavy symmetric top: analytic steady precession
// ---------------------------------------------------------------------------------------------

struct Top {
    sys: MultibodySystem,
    s0: State,
    omega_prec: f64,
    cos_theta: f64,
}

fn heavy_top() -> Top {
    let (m, l, j1c, j3, w3, g) = (1.0, 0.1, 0.012, 0.02, 50.0, 9.81);
    let theta = 30f64.to_radians();
    let mut sys = MultibodySystem::new();
    let b = sys.add_body(RigidBody::with_principal("top", m, [j1c, j1c, j3]).unwrap());
    sys.add_constraint(Spherical {
        name: "pivot".into(),
        i: Marker::point(None, Vector3::zeros()),
        j: Marker::point(Some(b), Vector3::new(0.0, 0.0, -l)),
    })
    .unwrap();
    sys.add_force(Gravity {
        g: Vector3::new(0.0, 0.0, -g),
    })
    .unwrap();
    // steady precession (Goldstein): m g l = Ω (J3 ω3 − J1 Ω cos θ), J1 about the pivot
    let j1 = j1c + m * l * l;
    let c = theta.cos();
    let disc = (j3 * w3).powi(2) - 4.0 * j1 * c * m * g * l;
    let omega_prec = (j3 * w3 - disc.sqrt()) / (2.0 * j1 * c);
    let p = from_axis_angle(&Vector3::x(), theta);
    let a = a_matrix(&p);
    let e3 = a * Vector3::z();
    let w = Vector3::z() * omega_prec + e3 * (w3 - omega_prec * c);
    let r = e3 * l;
    let st = BodyState {
        r,
        p,
        rdot: w.cross(&r),
        omega_local: a.transpose() * w,
    };
    let s0 = sys.state(0.0, &[st]).unwrap();
    Top {
        sys,
        s0,
        omega_prec,
        cos_theta: c,
    }
}

fn top_angles(s: &State) -> (f64, f64) {
    let p = Vector4::new(s.q[3], s.q[4], s.q[5], s.q[6]);
    let e3 = a_matrix(&p) * Vector3::z();
    // tilt cosine and precession angle of the symmetry axis (starts at azimuth −90°)
    (e3.z, e3.y.atan2(e3.x) + PI / 2.0)
}

#[test]
fn heavy_top_steady_precession() {
    let top = heavy_top();
    let t_end = 2.0;
    let e0 = top.sys.kinetic_energy(&top.s0) + top.sys.potential_energy(&top.s0);
    let expected = top.omega_prec * t_end;
    // DP5 with Baumgarte stabilisation
    let mut max_phi = 0.0f64;
    let mut max_tilt = 0.0f64;
    let dp = DormandPrince {
        rtol: 1e-10,
        atol: 1e-12,
        stabilization: Stabilization {
            baumgarte_alpha: 20.0,
            baumgarte_beta: 20.0,
            ..Default::default()
        },
        ..Default::default()
    };
    let sol = dp
        .integrate(&top.sys, top.s0.clone(), t_end, |s| {
            let mut phi = [0.0; 3];
            top.sys.constraint_residual(s.t, &s.q, &mut phi).unwrap();
            max_phi = max_phi.max(phi.iter().fold(0.0f64, |a, x| a.max(x.abs())));
            max_tilt = max_tilt.max((top_angles(s).0 - top.cos_theta).abs());
        })
        .unwrap();
    let (_, prec) = top_angles(&sol.state);
    let e1 = top.sys.kinetic_energy(&sol.state) + top.sys.potential_energy(&sol.state);
    println!(
        "top DP5: precession error {:.2e} rad of {expected:.4} rad, nutation {max_tilt:.2e}, |Φ| {max_phi:.2e}, dE/E {:.2e}",
        (prec - expected).abs(),
        ((e1 - e0) / e0).abs()
    );
    assert!(
        (prec - expected).abs() < 1e-6,
        "DP5 precession {prec} vs {expected}"
    );
    assert!(max_tilt < 1e-7, "nutation {max_tilt:e}");
    assert!(max_phi < 1e-9, "constraint drift {max_phi:e}");
    assert!((e1 - e0).abs() / e0.abs() < 1e-8, "energy {e0} -> {e1}");

    // generalized-α (index 3): constraint satisfied to the Newton tolerance
    let ga = GeneralizedAlpha::new(AlphaConfig {
        h: 1e-3,
        rho_inf: 0.9,
        ..Default::default()
    });
    let mut max_phi = 0.0f64;
    let sol = ga
        .integrate(&top.sys, top.s0.clone(), t_end, |s| {
            let mut phi = [0.0; 3];
            top.sys.constraint_residual(s.t, &s.q, &mut phi).unwrap();
            max_phi = max_phi.max(phi.iter().fold(0.0f64, |a, x| a.max(x.abs())));
        })
        .unwrap();
    let (tilt, prec) = top_angles(&sol.state);
    println!(
        "top gen-alpha: precession rel. error {:.2e}, tilt error {:.2e}, |Φ| {max_phi:.2e}",
        ((prec - expected) / expected).abs(),
        (tilt - top.cos_theta).abs()
    );
    assert!(max_phi < 1e-10, "gen-alpha constraint drift {max_phi:e}");
    assert!(
        (prec - expected).abs() < 2e-3 * expected,
        "gen-alpha precession {prec} vs {expected}"
    );
    assert!((tilt - top.cos_theta).abs() < 1e-3);
    println!("gen-alpha top stats {:?}", sol.stats);
}

// ---------------------------------------------------------------------------------------------
// Slider-crank with a rotational driver
// ---------------------------------------------------------------------------------------------

const CRANK: f64 = 0.1;
const ROD: f64 = 0.3;

fn slider_closed_form(theta: f64) -> f64 {
    CRANK * theta.cos() + (ROD * ROD - (CRANK * theta.sin()).powi(2)).sqrt()
}

#[derive(Clone, Copy, PartialEq)]
enum Wrist {
    /// R-S-U-P: crank revolute, spherical crank pin, universal wrist pin, prismatic.
    Universal,
    /// R-R-planar R-P: the planar loop closed with a planar revolute (2 equations).
    PlanarRevolute,
    /// R-R-R-P with full revolutes: one redundant equation.
    Revolute,
}

fn slider_crank(omega: f64, theta0: f64) -> (MultibodySystem, State) {
    slider_crank_with(omega, theta0, Wrist::Universal).unwrap()
}

fn slider_crank_with(
    omega: f64, theta0: f64, wrist: Wrist,
) -> Result<(MultibodySystem, State), MbdError> {
    let (a, b) = (CRANK, ROD);
    let mut sys = MultibodySystem::new();
    let crank =
        sys.add_body(RigidBody::with_principal("crank", 1.0, [1e-3, 1e-3, 1.5e-3]).unwrap());
    let rod = sys.add_body(RigidBody::with_principal("rod", 2.0, [1e-3, 1.5e-2, 1.5e-2]).unwrap());
    let slider =
        sys.add_body(RigidBody::with_principal("slider", 3.0, [1e-2, 1e-2, 1e-2]).unwrap());
    let z = Vector3::z();
    sys.add_constraint(Revolute {
        name: "crank bearing".into(),
        i: Marker::new(None, Vector3::zeros(), z),
        j: Marker::new(Some(crank), Vector3::new(-a / 2.0, 0.0, 0.0), z),
    })
    .unwrap();
    let pin_i = Marker::new(Some(crank), Vector3::new(a / 2.0, 0.0, 0.0), z);
    let pin_j = Marker::new(Some(rod), Vector3::new(-b / 2.0, 0.0, 0.0), z);
    if wrist == Wrist::Universal {
        sys.add_constraint(Spherical {
            name: "crank pin".into(),
            i: pin_i,
            j: pin_j,
        })
        .unwrap();
    } else {
        sys.add_constraint(Revolute {
            name: "crank pin".into(),
            i: pin_i,
            j: pin_j,
        })
        .unwrap();
    }
    let wrist_rod = Marker::new(Some(rod), Vector3::new(b / 2.0, 0.0, 0.0), z);
    match wrist {
        Wrist::Universal => sys.add_constraint(Universal {
            name: "wrist pin".into(),
            i: wrist_rod,
            j: Marker::new(Some(slider), Vector3::zeros(), Vector3::x()),
        }),
        Wrist::PlanarRevolute => sys.add_constraint(PlanarRevolute {
            name: "wrist pin".into(),
            i: wrist_rod,
            j: Marker::point(Some(slider), Vector3::zeros()),
        }),
        Wrist::Revolute => sys.add_constraint(Revolute {
            name: "wrist pin".into(),
            i: wrist_rod,
            j: Marker::new(Some(slider), Vector3::zeros(), z),
        }),
    }
    .unwrap();
    sys.add_constraint(Prismatic {
        name: "slide".into(),
        i: Marker::new(None, Vector3::zeros(), Vector3::x()),
        j: Marker::new(Some(slider), Vector3::zeros(), Vector3::x()),
        reference_i: Vector3::y(),
        reference_j: Vector3::y(),
    })
    .unwrap();
    sys.add_constraint(RotationDriver {
        name: "motor".into(),
        i: Marker::new(None, Vector3::zeros(), z),
        j: Marker::point(Some(crank), Vector3::zeros()),
        reference_i: Vector3::x(),
        reference_j: Vector3::x(),
        law: DriverLaw::ConstantSpeed { theta0, omega },
    })
    .unwrap();
    sys.add_force(Gravity {
        g: Vector3::new(0.0, -9.81, 0.0),
    })
    .unwrap();
    // consistent initial positions from the closed form
    let pin = Vector3::new(a * theta0.cos(), a * theta0.sin(), 0.0);
    let xs = slider_closed_form(theta0);
    let s = Vector3::new(xs, 0.0, 0.0);
    let beta = (-pin.y).atan2(xs - pin.x);
    let states = [
        BodyState::at_rest(pin / 2.0, from_axis_angle(&z, theta0)),
        BodyState::at_rest((pin + s) / 2.0, from_axis_angle(&z, beta)),
        BodyState::at_rest(s, ident()),
    ];
    let mut s0 = sys.state(0.0, &states).unwrap();
    // consistent velocities: D v = ν (unique: no free DOF left)
    project_velocities(&sys, &mut s0)?;
    Ok((sys, s0))
}

#[test]
fn planar_slider_crank_with_planar_revolute_and_redundant_variant() {
    // R-R-(planar R)-P: same closed-form slider position
    let (omega, theta0) = (-3.0, 1.0);
    let (sys, s0) = slider_crank_with(omega, theta0, Wrist::PlanarRevolute).unwrap();
    assert_eq!(sys.n_c(), 18);
    let mut max_err = 0.0f64;
    GeneralizedAlpha::new(AlphaConfig {
        h: 2e-3,
        rho_inf: 0.5,
        ..Default::default()
    })
    .integrate(&sys, s0, 1.0, |s| {
        max_err = max_err.max((s.q[14] - slider_closed_form(theta0 + omega * s.t)).abs());
    })
    .unwrap();
    assert!(max_err < 1e-9, "planar-revolute slider error {max_err:e}");
    // with a full revolute at the wrist the planar loop is over-constrained (20 equations,
    // 18 coordinates): a typed error naming the redundant joint
    let e = match slider_crank_with(omega, theta0, Wrist::Revolute) {
        Err(e) => e,
        Ok(_) => panic!("redundant slider-crank accepted"),
    };
    assert!(matches!(e, MbdError::Singular { .. }), "{e}");
    assert!(e.to_string().contains("redundant"), "{e}");
    println!("{e}");
}

#[test]
fn slider_crank_matches_closed_form_kinematics() {
    let (omega, theta0) = (2.0 * PI, 0.3);
    let (sys, s0) = slider_crank(omega, theta0);
    assert_eq!(sys.n_c(), 18);
    // slider position vs x = a cos θ + sqrt(b² − a² sin² θ)
    let mut max_err = 0.0f64;
    let ga = GeneralizedAlpha::new(AlphaConfig {
        h: 2e-3,
        rho_inf: 0.8,
        ..Default::default()
    });
    let sol = ga
        .integrate(&sys, s0.clone(), 1.0, |s| {
            let x = s.q[14];
            max_err = max_err.max((x - slider_closed_form(theta0 + omega * s.t)).abs());
        })
        .unwrap();
    println!("slider-crank gen-alpha: max slider error {max_err:.2e} m");
    assert!(max_err < 1e-9, "gen-alpha slider error {max_err:e}");
    println!("slider-crank gen-alpha stats {:?}", sol.stats);

    let mut max_err = 0.0f64;
    let mut max_verr = 0.0f64;
    let dp = DormandPrince {
        rtol: 1e-9,
        atol: 1e-11,
        stabilization: Stabilization {
            project: true,
            ..Default::default()
        },
        ..Default::default()
    };
    dp.integrate(&sys, s0, 1.0, |s| {
        let th = theta0 + omega * s.t;
        max_err = max_err.max((s.q[14] - slider_closed_form(th)).abs());
        // slider velocity: ẋ = −a ω sin θ − a² ω sin θ cos θ / sqrt(b² − a² sin² θ)
        let root = (ROD * ROD - (CRANK * th.sin()).powi(2)).sqrt();
        let xd = -CRANK * omega * th.sin() - CRANK * CRANK * omega * th.sin() * th.cos() / root;
        max_verr = max_verr.max((s.v[12] - xd).abs());
    })
    .unwrap();
    println!("slider-crank DP5: max slider error {max_err:.2e} m, velocity {max_verr:.2e} m/s");
    assert!(max_err < 1e-9, "DP5 slider error {max_err:e}");
    assert!(max_verr < 1e-8, "DP5 slider velocity error {max_verr:e}");
}

#[test]
fn slider_crank_reactions_balance_the_slider() {
    // Slider (mass 3 kg, gravity −y): Newton's law m a = Σ reactions + m g on the slider body.
    let (sys, s0) = slider_crank(2.0 * PI, 0.3);
    let acc = accelerations(&sys, &s0, &Stabilization::default()).unwrap();
    let reactions = sys.reactions(&s0, &acc.lambda).unwrap();
    let mut sum = Vector3::zeros();
    for r in &reactions {
        if r.name == "wrist pin" || r.name == "slide" {
            sum += r.force_j;
        }
    }
    let m = 3.0;
    let a = Vector3::new(acc.vdot[12], acc.vdot[13], acc.vdot[14]);
    let res = m * a - (sum + Vector3::new(0.0, -9.81 * m, 0.0));
    assert!(res.norm() < 1e-9, "slider force balance {res:?}");
    // the prismatic joint carries the weight: its reaction has a +y component
    let slide = reactions.iter().find(|r| r.name == "slide").unwrap();
    assert!(slide.force_j.y > 0.0);
}

// ---------------------------------------------------------------------------------------------
// Event location: falling ball
// ---------------------------------------------------------------------------------------------

#[test]
fn falling_ball_event_time() {
    // analytic: z(t) = z0 − g t²/2 reaches the radius at t* = sqrt(2 (z0 − R)/g)
    let (z0, radius, g) = (1.0, 0.1, 9.81);
    let mut sys = MultibodySystem::new();
    sys.add_body(RigidBody::with_principal("ball", 0.5, [2e-3, 2e-3, 2e-3]).unwrap());
    sys.add_force(Gravity {
        g: Vector3::new(0.0, 0.0, -g),
    })
    .unwrap();
    let st = BodyState {
        r: Vector3::new(0.0, 0.0, z0),
        p: ident(),
        rdot: Vector3::zeros(),
        omega_local: Vector3::new(0.3, -0.2, 1.0),
    };
    let s0 = sys.state(0.0, &[st]).unwrap();
    let ev = [Event::stop("ground contact", move |s: &State| {
        s.q[2] - radius
    })];
    let sol = DormandPrince::new(1e-10, 1e-12)
        .integrate_with_events(&sys, s0, 5.0, &ev, |_| {})
        .unwrap();
    let t_star = (2.0 * (z0 - radius) / g).sqrt();
    assert_eq!(sol.events.len(), 1);
    assert_eq!(sol.events[0].name, "ground contact");
    println!(
        "falling ball: event time error {:.2e} s",
        sol.events[0].t - t_star
    );
    assert!(
        (sol.events[0].t - t_star).abs() < 1e-9,
        "{:e}",
        sol.events[0].t - t_star
    );
    assert!((sol.state.q[2] - radius).abs() < 1e-9);
    assert_eq!(sol.stats.events, 1);
}

// ---------------------------------------------------------------------------------------------
// Bad input: typed errors naming the item and the time
// ---------------------------------------------------------------------------------------------

#[test]
fn bad_bodies_are_rejected() {
    for m in [0.0, -1.0, f64::NAN] {
        let e = RigidBody::with_principal("wheel", m, [1.0, 1.0, 1.0]).unwrap_err();
        assert!(matches!(e, MbdError::InvalidInput { .. }));
        assert!(
            e.to_string().contains("wheel") && e.to_string().contains("mass"),
            "{e}"
        );
    }
    let e = RigidBody::with_principal("wheel", 1.0, [1.0, -1.0, 1.0]).unwrap_err();
    assert!(e.to_string().contains("inertia"), "{e}");
    let e = RigidBody::with_principal("wheel", 1.0, [1.0, 1.0, 5.0]).unwrap_err();
    assert!(e.to_string().contains("triangle"), "{e}");
}

#[test]
fn non_unit_euler_parameters_are_rejected() {
    let mut sys = MultibodySystem::new();
    sys.add_body(RigidBody::with_principal("arm", 1.0, [1.0, 1.0, 1.0]).unwrap());
    let st = BodyState::at_rest(Vector3::zeros(), Vector4::new(1.0, 0.2, 0.0, 0.0));
    let e = sys.state(0.0, &[st]).unwrap_err();
    assert!(
        e.to_string().contains("arm") && e.to_string().contains("Euler"),
        "{e}"
    );
}

#[test]
fn redundant_constraints_are_named() {
    let mut sys = MultibodySystem::new();
    let b = sys.add_body(RigidBody::with_principal("door", 5.0, [1.0, 1.0, 1.5]).unwrap());
    for name in ["hinge A", "hinge B"] {
        sys.add_constraint(Revolute {
            name: name.into(),
            i: Marker::new(None, Vector3::zeros(), Vector3::z()),
            j: Marker::new(Some(b), Vector3::new(-0.5, 0.0, 0.0), Vector3::z()),
        })
        .unwrap();
    }
    sys.add_force(Gravity {
        g: Vector3::new(0.0, -9.81, 0.0),
    })
    .unwrap();
    let s0 = sys
        .state(
            0.7,
            &[BodyState::at_rest(Vector3::new(0.5, 0.0, 0.0), ident())],
        )
        .unwrap();
    let e = accelerations(&sys, &s0, &Stabilization::default()).unwrap_err();
    match &e {
        MbdError::Singular { t, detail } => {
            assert_eq!(*t, 0.7);
            assert!(detail.contains("hinge B"), "{detail}");
        }
        other => panic!("unexpected {other:?}"),
    }
    let e = GeneralizedAlpha::default()
        .integrate(&sys, s0, 1.0, |_| {})
        .unwrap_err();
    assert!(e.to_string().contains("hinge B"), "{e}");
    // a constraint referring to a missing body
    let e = sys
        .add_constraint(Spherical {
            name: "ghost".into(),
            i: Marker::point(Some(7), Vector3::zeros()),
            j: Marker::point(None, Vector3::zeros()),
        })
        .unwrap_err();
    assert!(e.to_string().contains("ghost"), "{e}");
}

#[test]
fn nan_in_state_or_forces_is_reported_with_time() {
    let mut sys = MultibodySystem::new();
    let b = sys.add_body(RigidBody::with_principal("probe", 1.0, [1.0, 1.0, 1.0]).unwrap());
    sys.add_force(AppliedForce {
        name: "thruster".into(),
        body: b,
        point: Vector3::zeros(),
        law: Arc::new(|t, _| {
            if t > 0.5 {
                Vector3::new(f64::NAN, 0.0, 0.0)
            } else {
                Vector3::x()
            }
        }),
    })
    .unwrap();
    let mut s0 = sys
        .state(0.0, &[BodyState::at_rest(Vector3::zeros(), ident())])
        .unwrap();
    // NaN produced by a force element during the run
    for e in [
        Rk4::new(0.01)
            .integrate(&sys, s0.clone(), 1.0, |_| {})
            .unwrap_err(),
        GeneralizedAlpha::new(AlphaConfig {
            h: 0.01,
            ..Default::default()
        })
        .integrate(&sys, s0.clone(), 1.0, |_| {})
        .unwrap_err(),
    ] {
        match e {
            MbdError::NonFinite { what, t } => {
                assert!(what.contains("probe"), "{what}");
                assert!(t > 0.5 && t < 0.52, "{t}");
            }
            other => panic!("unexpected {other:?}"),
        }
    }
    // NaN in the initial state
    s0.v[1] = f64::NAN;
    let e = DormandPrince::default()
        .integrate(&sys, s0, 1.0, |_| {})
        .unwrap_err();
    assert!(
        matches!(e, MbdError::NonFinite { .. }) && e.to_string().contains("probe"),
        "{e}"
    );
}
