//! CompositeSystem: two separately built models joined by a coupling constraint reproduce the
//! same mechanism built as one MultibodySystem (second formulation as reference).

use mbd_core::body::{BodyKin, BodyState};
use mbd_core::constraints::{Revolute, Spherical};
use mbd_core::forces::Gravity;
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha, State};
use mbd_core::kinematics::tilde::{get3, get4};
use mbd_core::marker::{Carrier, Marker, Term};
use mbd_core::{
    CompositeSystem, Coupling, CouplingEval, MultibodySystem, RigidBody, SecondOrderSystem,
};
use nalgebra::{Vector3, Vector4};

const L: f64 = 0.6;

fn pendulum() -> MultibodySystem {
    let mut s = MultibodySystem::new();
    let b = s.add_body(RigidBody::with_principal("arm", 1.0, [1e-3, 0.03, 0.03]).unwrap());
    s.add_constraint(Revolute {
        name: "hinge".into(),
        i: Marker::new(None, Vector3::zeros(), Vector3::new(0.0, 0.3, 1.0)),
        j: Marker::new(
            Some(b),
            Vector3::new(-L / 2.0, 0.0, 0.0),
            Vector3::new(0.0, 0.3, 1.0),
        ),
    })
    .unwrap();
    s.add_force(Gravity {
        g: Vector3::new(0.0, -9.81, 0.0),
    })
    .unwrap();
    s
}

fn bob() -> RigidBody {
    RigidBody::with_principal("bob", 0.5, [2e-3, 3e-3, 4e-3]).unwrap()
}

fn states() -> [BodyState; 2] {
    let p = Vector4::new(1.0, 0.0, 0.0, 0.0);
    let mut b = BodyState::at_rest(Vector3::new(L, 0.0, 0.0), p);
    b.omega_local = Vector3::new(0.5, -1.0, 2.0);
    [BodyState::at_rest(Vector3::new(L / 2.0, 0.0, 0.0), p), b]
}

/// The spherical joint arm tip ↔ bob centre written on the global coordinates:
/// Φ = d_tip(arm) − r_bob.
struct TipJoint;

impl Coupling for TipJoint {
    fn name(&self) -> &str {
        "tip joint"
    }
    fn n_eq(&self) -> usize {
        3
    }
    fn eval(&self, _t: f64, q: &[f64], v: &[f64], out: &mut CouplingEval) {
        let kin = |qo: usize, vo: usize| {
            BodyKin::new(get3(q, qo), get4(q, qo + 3), get3(v, vo), get3(v, vo + 3))
        };
        let (ka, kb) = (kin(0, 0), kin(7, 6));
        let tip = Marker::point(Some(0), Vector3::new(L / 2.0, 0.0, 0.0));
        let centre = Marker::point(Some(1), Vector3::zeros());
        let d = Term::point(&Carrier::rigid(ka), &tip, 0).sub(&Term::point(
            &Carrier::rigid(kb),
            &centre,
            1,
        ));
        for r in 0..3 {
            let row = d.component(r);
            out.phi[r] = row.phi;
            out.gamma[r] = -row.quad;
            for c in 0..6 {
                out.jacobian.push((r, c, row.di[c]));
                out.jacobian.push((r, 6 + c, row.dj[c]));
            }
        }
    }
}

#[test]
fn composite_matches_single_model() {
    // reference: one MultibodySystem with a Spherical joint
    let mut single = pendulum();
    let bb = single.add_body(bob());
    single
        .add_constraint(Spherical {
            name: "tip".into(),
            i: Marker::point(Some(0), Vector3::new(L / 2.0, 0.0, 0.0)),
            j: Marker::point(Some(bb), Vector3::zeros()),
        })
        .unwrap();
    // (the Gravity element of pendulum() acts on every body of the system, the bob included)
    let s0 = single.state(0.0, &states()).unwrap();

    let mut comp = CompositeSystem::new();
    comp.add_part("arm", pendulum());
    let mut b = MultibodySystem::new();
    b.add_body(bob());
    b.add_force(Gravity {
        g: Vector3::new(0.0, -9.81, 0.0),
    })
    .unwrap();
    comp.add_part("bob", b);
    comp.add_coupling(TipJoint);
    assert_eq!(comp.n_q(), 14);
    assert_eq!(comp.n_c(), 8);
    assert_eq!(
        comp.constraint_name(6),
        "coupling \"tip joint\" (equation 1)"
    );
    assert!(comp.constraint_name(2).contains("hinge"));

    let ga = GeneralizedAlpha::new(AlphaConfig {
        h: 1e-3,
        rho_inf: 0.8,
        ..Default::default()
    });
    let mut ref_hist = Vec::new();
    ga.integrate(&single, s0.clone(), 1.0, |s| ref_hist.push(s.q.clone()))
        .unwrap();
    let mut hist: Vec<Vec<f64>> = Vec::new();
    let sc = State::new(0.0, s0.q.clone(), s0.v.clone());
    let sol = ga
        .integrate(&comp, sc, 1.0, |s| hist.push(s.q.clone()))
        .unwrap();
    assert_eq!(hist.len(), ref_hist.len());
    let mut max_diff = 0.0f64;
    for (a, b) in hist.iter().zip(&ref_hist) {
        for (x, y) in a.iter().zip(b) {
            max_diff = max_diff.max((x - y).abs());
        }
    }
    // identical equations: agreement to the Newton tolerance
    assert!(
        max_diff < 1e-8,
        "composite vs single model: {max_diff:e}, {:?}",
        sol.stats
    );
}
