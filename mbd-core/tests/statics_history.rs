//! Static equilibrium helper and CSV time histories.

use mbd_core::body::BodyState;
use mbd_core::constraints::Revolute;
use mbd_core::forces::{Gravity, RotationalSpringDamper};
use mbd_core::integrators::{Rk4, State};
use mbd_core::marker::Marker;
use mbd_core::{History, MultibodySystem, Probe, RigidBody, StaticOptions, static_equilibrium};
use nalgebra::{Vector3, Vector4};

#[test]
fn hinged_bar_with_torsion_spring_static_equilibrium() {
    // Reference (independent scalar equation): k θ + m g (l/2) cos θ = 0, bisection.
    let (m, l, k, g) = (2.0, 1.0, 30.0, 9.81);
    let mut sys = MultibodySystem::new();
    let bar = sys.add_body(
        RigidBody::with_principal("bar", m, [1e-3, m * l * l / 12.0, m * l * l / 12.0]).unwrap(),
    );
    sys.add_constraint(Revolute {
        name: "hinge".into(),
        i: Marker::new(None, Vector3::zeros(), Vector3::z()),
        j: Marker::new(Some(bar), Vector3::new(-l / 2.0, 0.0, 0.0), Vector3::z()),
    })
    .unwrap();
    sys.add_force(RotationalSpringDamper {
        name: "torsion".into(),
        i: Marker::new(None, Vector3::zeros(), Vector3::z()),
        j: Marker::point(Some(bar), Vector3::zeros()),
        reference_i: Vector3::x(),
        reference_j: Vector3::x(),
        stiffness: k,
        damping: 0.0,
        free_angle: 0.0,
    })
    .unwrap();
    sys.add_force(Gravity {
        g: Vector3::new(0.0, -g, 0.0),
    })
    .unwrap();
    let s0 = sys
        .state(
            0.0,
            &[BodyState::at_rest(
                Vector3::new(l / 2.0, 0.0, 0.0),
                Vector4::new(1.0, 0.0, 0.0, 0.0),
            )],
        )
        .unwrap();
    let sol = static_equilibrium(&sys, 0.0, &s0.q, &StaticOptions::default()).unwrap();
    let (mut a, mut b) = (-1.5f64, 0.0f64);
    let fun = |th: f64| k * th + m * g * 0.5 * l * th.cos();
    for _ in 0..200 {
        let c = 0.5 * (a + b);
        if fun(a) * fun(c) <= 0.0 { b = c } else { a = c }
    }
    let th_ref = 0.5 * (a + b);
    let r = Vector3::new(sol.state.q[0], sol.state.q[1], sol.state.q[2]);
    let th = r.y.atan2(r.x);
    assert!((th - th_ref).abs() < 1e-9, "θ {th} vs {th_ref}");
    assert!(sol.iterations < 20);
    // the hinge carries the weight: reaction on the bar = +m g (y)
    let reac = sys.reactions(&sol.state, &sol.lambda).unwrap();
    assert!(
        (reac[0].force_j - Vector3::new(0.0, m * g, 0.0)).norm() < 1e-8,
        "{:?}",
        reac[0].force_j
    );
}

#[test]
fn history_is_written_as_csv() {
    // free fall z = z0 − g t²/2 recorded by probes; CSV read back
    let mut sys = MultibodySystem::new();
    sys.add_body(RigidBody::with_principal("ball", 1.0, [1.0, 1.0, 1.0]).unwrap());
    sys.add_force(Gravity {
        g: Vector3::new(0.0, 0.0, -9.81),
    })
    .unwrap();
    let s0 = sys
        .state(
            0.0,
            &[BodyState::at_rest(
                Vector3::new(0.0, 0.0, 2.0),
                Vector4::new(1.0, 0.0, 0.0, 0.0),
            )],
        )
        .unwrap();
    let mut hist = History::new(vec![
        Probe::new("z [m]", |s: &State| s.q[2]),
        Probe::new("energy [J]", |s: &State| {
            sys.kinetic_energy(s) + sys.potential_energy(s)
        }),
    ]);
    hist.every = 10;
    Rk4::new(1e-3)
        .integrate(&sys, s0, 0.5, |s| hist.observe(s))
        .unwrap();
    assert_eq!(hist.t.len(), 51);
    let z = hist.column("z [m]").unwrap();
    for (t, z) in hist.t.iter().zip(&z) {
        assert!((z - (2.0 - 0.5 * 9.81 * t * t)).abs() < 1e-12);
    }
    let dir = std::env::temp_dir().join(format!("mbd_core_history_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("fall.csv");
    hist.save_csv(&path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap(), "t [s],z [m],energy [J]");
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 51);
    assert!((rows[50][0] - 0.5).abs() < 1e-12);
    assert!((rows[50][1] - z[50]).abs() < 1e-15);
    assert!((rows[50][2] - rows[0][2]).abs() < 1e-9, "energy conserved");
    std::fs::remove_dir_all(&dir).ok();
    // unwritable path: typed error naming the path
    let e = hist
        .save_csv(&dir.join("missing").join("x.csv"))
        .unwrap_err();
    assert!(e.to_string().contains("x.csv"), "{e}");
}
