//! Consistency of every constraint's Jacobian D, ν and γ with finite differences of Φ along a
//! motion with constant velocities (v̇ = 0): Φ̇ = D v − ν and Φ̈ = −γ (definitions of
//! Lin (2.11)–(2.12) / Ribaric (2.16) with rheonomic terms); and of the force elements with
//! their potential energy (f = −∂V/∂q).

use crate::common;

use mbd_core::body::BodyState;
use mbd_core::constraints::*;
use mbd_core::forces::{Gravity, RotationalSpringDamper, SpringDamper};
use mbd_core::integrators::State;
use mbd_core::kinematics::euler::from_axis_angle;
use mbd_core::marker::Marker;
use mbd_core::{MultibodySystem, RigidBody, SecondOrderSystem};
use nalgebra::Vector3;
use std::sync::Arc;

fn two_bodies() -> (MultibodySystem, State) {
    let mut sys = MultibodySystem::new();
    sys.add_body(RigidBody::with_principal("a", 1.0, [1.0, 1.2, 1.4]).unwrap());
    sys.add_body(RigidBody::with_principal("b", 2.0, [0.5, 0.6, 0.7]).unwrap());
    let sa = BodyState {
        r: Vector3::new(0.1, 0.2, -0.3),
        p: from_axis_angle(&Vector3::new(1.0, -0.4, 0.3), 0.8),
        rdot: Vector3::new(0.3, -0.2, 0.5),
        omega_local: Vector3::new(0.7, -1.1, 0.4),
    };
    let sb = BodyState {
        r: Vector3::new(0.9, -0.4, 0.2),
        p: from_axis_angle(&Vector3::new(-0.2, 0.5, 1.0), -1.3),
        rdot: Vector3::new(-0.4, 0.6, 0.1),
        omega_local: Vector3::new(-0.5, 0.9, 1.3),
    };
    let s = sys.state(0.2, &[sa, sb]).unwrap();
    (sys, s)
}

fn att(b: Option<usize>, p: [f64; 3], a: [f64; 3]) -> Marker {
    Marker::new(b, Vector3::from(p), Vector3::from(a))
}

type AddConstraint = Box<dyn Fn(&mut MultibodySystem)>;

fn all_constraints(bi: Option<usize>) -> Vec<AddConstraint> {
    let ai = move || att(bi, [0.1, -0.2, 0.3], [0.3, 0.4, 1.0]);
    let aj = || att(Some(1), [-0.2, 0.1, 0.05], [0.2, -0.3, 1.0]);
    vec![
        Box::new(move |s| {
            s.add_constraint(Spherical {
                name: "sph".into(),
                i: ai(),
                j: aj(),
            })
            .unwrap();
        }),
        Box::new(move |s| {
            s.add_constraint(Revolute {
                name: "rev".into(),
                i: ai(),
                j: aj(),
            })
            .unwrap();
        }),
        Box::new(move |s| {
            s.add_constraint(Fixed {
                name: "fix".into(),
                i: ai(),
                j: aj(),
            })
            .unwrap();
        }),
        Box::new(move |s| {
            s.add_constraint(Universal {
                name: "uni".into(),
                i: ai(),
                j: aj(),
            })
            .unwrap();
        }),
        Box::new(move |s| {
            s.add_constraint(Prismatic {
                name: "pri".into(),
                i: ai(),
                j: aj(),
                reference_i: Vector3::new(1.0, 0.2, 0.0),
                reference_j: Vector3::new(0.1, 1.0, 0.3),
            })
            .unwrap();
        }),
        Box::new(move |s| {
            s.add_constraint(Distance {
                name: "dist".into(),
                i: ai(),
                j: aj(),
                length: 0.7,
            })
            .unwrap();
        }),
        Box::new(move |s| {
            s.add_constraint(PointOnPlane {
                name: "pop".into(),
                i: ai(),
                j: aj(),
            })
            .unwrap();
        }),
        Box::new(move |s| {
            s.add_constraint(PlanarRevolute {
                name: "prev".into(),
                i: ai(),
                j: aj(),
            })
            .unwrap();
        }),
        Box::new(move |s| {
            s.add_constraint(RotationDriver {
                name: "drv-ramp".into(),
                i: ai(),
                j: aj(),
                reference_i: Vector3::new(1.0, 0.0, 0.0),
                reference_j: Vector3::new(0.0, 1.0, 0.2),
                law: DriverLaw::SpeedRamp {
                    theta0: 0.3,
                    omega: 5.0,
                    ramp: 0.5,
                },
            })
            .unwrap();
        }),
        Box::new(move |s| {
            s.add_constraint(RotationDriver {
                name: "drv-table".into(),
                i: ai(),
                j: aj(),
                reference_i: Vector3::new(1.0, 0.0, 0.0),
                reference_j: Vector3::new(0.0, 1.0, 0.2),
                // t = 0.2 s lies inside the second segment (θ̈ = 30 rad/s² there)
                law: DriverLaw::SpeedTable {
                    theta0: -0.2,
                    times: vec![0.0, 0.1, 0.3],
                    speeds: vec![1.0, 2.0, 8.0],
                },
            })
            .unwrap();
        }),
        Box::new(move |s| {
            s.add_constraint(RotationDriver {
                name: "drv-custom".into(),
                i: ai(),
                j: aj(),
                reference_i: Vector3::new(0.0, 1.0, 0.0),
                reference_j: Vector3::new(1.0, 0.0, 0.0),
                law: DriverLaw::Custom(Arc::new(|t: f64| {
                    (
                        0.4 * (3.0 * t).sin(),
                        1.2 * (3.0 * t).cos(),
                        -3.6 * (3.0 * t).sin(),
                    )
                })),
            })
            .unwrap();
        }),
    ]
}

#[test]
fn jacobian_nu_gamma_match_finite_differences() {
    for ground in [false, true] {
        let bi = if ground { None } else { Some(0) };
        for add in all_constraints(bi) {
            let (mut sys, s) = two_bodies();
            add(&mut sys);
            let name = sys.constraints()[0].name().to_string();
            common::check_rates(&sys, &s, &format!("{name} (ground {ground})"));
        }
    }
}

#[test]
fn force_elements_derive_from_their_potential() {
    // f = −∂V/∂q along q ⊕ ε δ for conservative elements (damping zero)
    let (mut sys, s) = two_bodies();
    sys.add_force(Gravity {
        g: Vector3::new(0.0, -9.81, 1.0),
    })
    .unwrap();
    sys.add_force(SpringDamper {
        name: "spring".into(),
        i: att(Some(0), [0.1, 0.0, 0.2], [0.0, 0.0, 1.0]),
        j: att(Some(1), [0.0, -0.1, 0.1], [0.0, 0.0, 1.0]),
        stiffness: 300.0,
        damping: 0.0,
        free_length: 0.4,
    })
    .unwrap();
    sys.add_force(RotationalSpringDamper {
        name: "torsion".into(),
        i: att(Some(0), [0.0; 3], [0.2, 0.1, 1.0]),
        j: att(Some(1), [0.0; 3], [0.0, 0.0, 1.0]),
        reference_i: Vector3::new(1.0, 0.0, 0.0),
        reference_j: Vector3::new(1.0, 0.3, 0.0),
        stiffness: 40.0,
        damping: 0.0,
        free_angle: 0.2,
    })
    .unwrap();
    let zero_v = vec![0.0; 12];
    let mut f = vec![0.0; 12];
    sys.forces(s.t, &s.q, &zero_v, &mut f, &mut mbd_core::Workspace::new())
        .unwrap();
    for dof in 0..12 {
        let mut dq = vec![0.0; 12];
        let h = 1e-6;
        let v_at = |x: f64, dq: &mut Vec<f64>| {
            dq[dof] = x;
            let mut q = vec![0.0; 14];
            sys.integrate_position(&s.q, dq, &mut q);
            sys.potential_energy(&State::new(s.t, q, zero_v.clone()))
        };
        let dv = (v_at(h, &mut dq) - v_at(-h, &mut dq)) / (2.0 * h);
        assert!(
            (f[dof] + dv).abs() < 1e-5 * (1.0 + dv.abs()),
            "dof {dof}: f {} vs −dV {}",
            f[dof],
            -dv
        );
    }
}

#[test]
fn constraint_force_tangent_matches_global_differences() {
    // K_c = ∂(Dᵀλ)/∂q (through ⊕) against central differences of the whole Dᵀ(q) λ
    for add in all_constraints(Some(0)) {
        let (mut sys, s) = two_bodies();
        add(&mut sys);
        let nc = sys.n_c();
        let lambda: Vec<f64> = (0..nc)
            .map(|k| 1.0 + 0.37 * k as f64 - 0.1 * (k * k) as f64)
            .collect();
        let kc = sys
            .constraint_force_tangent(s.t, &s.q, &lambda)
            .unwrap()
            .unwrap()
            .to_dense();
        let dtl = |q: &[f64]| {
            let mut g = vec![0.0; 12];
            sys.constraint_jacobian(s.t, q)
                .unwrap()
                .tmul_vec_add(1.0, &lambda, &mut g);
            g
        };
        for j in 0..12 {
            let h = 1e-6;
            let mut dq = vec![0.0; 12];
            let mut qp = vec![0.0; 14];
            let mut qm = vec![0.0; 14];
            dq[j] = h;
            sys.integrate_position(&s.q, &dq, &mut qp);
            dq[j] = -h;
            sys.integrate_position(&s.q, &dq, &mut qm);
            let (gp, gm) = (dtl(&qp), dtl(&qm));
            for i in 0..12 {
                let fd = (gp[i] - gm[i]) / (2.0 * h);
                assert!(
                    (fd - kc[(i, j)]).abs() < 1e-5 * (1.0 + fd.abs()),
                    "{} K_c[{i},{j}] = {} vs {fd}",
                    sys.constraints()[0].name(),
                    kc[(i, j)]
                );
            }
        }
    }
}

#[test]
fn driver_laws_are_consistent() {
    // θ̇ and θ̈ are the derivatives of θ (central differences), for every law
    let laws = [
        DriverLaw::ConstantSpeed {
            theta0: 0.1,
            omega: 3.0,
        },
        DriverLaw::SpeedRamp {
            theta0: 0.1,
            omega: 3.0,
            ramp: 0.8,
        },
        DriverLaw::SpeedTable {
            theta0: 0.4,
            times: vec![0.1, 0.5, 0.9],
            speeds: vec![2.0, -1.0, 4.0],
        },
    ];
    for law in &laws {
        for &t in &[-0.3, 0.05, 0.3, 0.7, 1.3] {
            let h = 1e-5;
            let (th_p, w_p, _) = law.eval(t + h);
            let (th_m, w_m, _) = law.eval(t - h);
            let (_, w, a) = law.eval(t);
            assert!(
                ((th_p - th_m) / (2.0 * h) - w).abs() < 1e-6,
                "{law:?} t {t}"
            );
            assert!(((w_p - w_m) / (2.0 * h) - a).abs() < 1e-4, "{law:?} t {t}");
        }
    }
    // table: θ(0.5) = θ0 + ∫ ω = 0.4 + 2·0.1 + (2 + (−1))/2·0.4 = 0.8
    assert!((laws[2].eval(0.5).0 - 0.8).abs() < 1e-14);
}

#[test]
fn invalid_joint_and_force_parameters_are_rejected() {
    let (mut sys, _) = two_bodies();
    let e = sys
        .add_constraint(Distance {
            name: "rope".into(),
            i: att(Some(0), [0.0; 3], [0.0, 0.0, 1.0]),
            j: att(Some(1), [0.0; 3], [0.0, 0.0, 1.0]),
            length: -1.0,
        })
        .unwrap_err();
    assert!(
        e.to_string().contains("rope") && e.to_string().contains("length"),
        "{e}"
    );
    let e = sys
        .add_constraint(Revolute {
            name: "axle".into(),
            i: att(Some(0), [0.0; 3], [0.0, 0.0, 0.0]),
            j: att(Some(1), [0.0; 3], [0.0, 0.0, 1.0]),
        })
        .unwrap_err();
    assert!(
        e.to_string().contains("axle") && e.to_string().contains("axis"),
        "{e}"
    );
    let e = sys
        .add_constraint(RotationDriver {
            name: "motor".into(),
            i: att(None, [0.0; 3], [0.0, 0.0, 1.0]),
            j: att(Some(0), [0.0; 3], [0.0, 0.0, 1.0]),
            reference_i: Vector3::x(),
            reference_j: Vector3::x(),
            law: DriverLaw::SpeedTable {
                theta0: 0.0,
                times: vec![0.0, 0.0],
                speeds: vec![1.0, 2.0],
            },
        })
        .unwrap_err();
    assert!(
        e.to_string().contains("motor") && e.to_string().contains("increase"),
        "{e}"
    );
    let e = sys
        .add_force(SpringDamper {
            name: "strut".into(),
            i: att(Some(0), [0.0; 3], [0.0, 0.0, 1.0]),
            j: att(Some(1), [0.0; 3], [0.0, 0.0, 1.0]),
            stiffness: f64::NAN,
            damping: 0.0,
            free_length: 0.1,
        })
        .unwrap_err();
    assert!(
        e.to_string().contains("strut") && e.to_string().contains("stiffness"),
        "{e}"
    );
}

#[test]
fn non_unit_euler_parameters_in_a_raw_state_are_rejected_with_time() {
    use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha};
    let (sys, mut s) = two_bodies();
    s.q[7 + 3] *= 1.1; // body "b"
    let e = GeneralizedAlpha::new(AlphaConfig::default())
        .integrate(&sys, s, 1.0, |_| {})
        .unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains("\"b\"") && msg.contains("t = 0.2"), "{msg}");
}
