//! Joints between rigid bodies and flexible nodes, evaluated by the floating-frame container
//! with the same constraint code as the rigid container:
//! * every joint's `D` and `γ` against finite differences of `Φ` (second formulation, as in
//!   `constraint_consistency.rs`) on markers at flexible nodes with and without node rotations;
//! * a rigid link and a very stiff flexible bar joined by a revolute joint against the same
//!   double pendulum built from rigid bodies in `MultibodySystem` (the rigid model).

use crate::common;

use faer::Mat;
use mbd_core::body::BodyState;
use mbd_core::constraints::*;
use mbd_core::floating::{AxisCondition, FlexBody, FlexState, FloatingSystem};
use mbd_core::forces::Gravity;
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha, State};
use mbd_core::kinematics::euler::from_axis_angle;
use mbd_core::marker::Marker;
use mbd_core::{MultibodySystem, RigidBody, SecondOrderSystem};
use nalgebra::{Matrix3, Vector3, Vector4};

/// A small generic flexible body: 4 nodes, lumped masses, a 5-column basis and (optionally)
/// node rotation slopes with arbitrary entries (kinematics only; K' = 1e3 I).
fn generic_flex(rotations: bool) -> FlexBody {
    let s = [
        0.3, -0.1, 0.05, -0.2, 0.25, 0.1, 0.05, 0.1, -0.3, -0.15, -0.2, 0.12,
    ];
    let n = s.len();
    let m = Mat::<f64>::from_fn(n, n, |i, j| {
        if i == j {
            0.5 + 0.1 * (i / 3) as f64
        } else {
            0.0
        }
    });
    let k = Mat::<f64>::from_fn(n, n, |i, j| if i == j { 1e3 } else { 0.0 });
    let nz = 5;
    let psi = Mat::<f64>::from_fn(n, nz, |i, j| ((1 + i * 7 + j * 3) as f64).sin());
    let body = FlexBody::new(
        "flex",
        &s,
        m.as_ref(),
        k.as_ref(),
        psi.as_ref(),
        AxisCondition::NodalFixed,
    )
    .unwrap();
    if rotations {
        let slopes = Mat::<f64>::from_fn(n, nz, |i, j| 0.8 * ((2 + i * 5 + j * 11) as f64).cos());
        body.with_node_rotations(slopes.as_ref()).unwrap()
    } else {
        body
    }
}

/// One rigid and one flexible body in generic motion (non-zero z, ż, ω', ṙ).
fn rigid_and_flex(rotations: bool) -> (FloatingSystem, State) {
    let mut sys = FloatingSystem::new();
    sys.add_rigid(RigidBody::with_principal("a", 1.0, [1.0, 1.2, 1.4]).unwrap());
    sys.add_flex(generic_flex(rotations));
    let sa = BodyState {
        r: Vector3::new(0.1, 0.2, -0.3),
        p: from_axis_angle(&Vector3::new(1.0, -0.4, 0.3), 0.8),
        rdot: Vector3::new(0.3, -0.2, 0.5),
        omega_local: Vector3::new(0.7, -1.1, 0.4),
    };
    let sf = FlexState {
        r: Vector3::new(0.9, -0.4, 0.2),
        p: from_axis_angle(&Vector3::new(-0.2, 0.5, 1.0), -1.3),
        rdot: Vector3::new(-0.4, 0.6, 0.1),
        omega_local: Vector3::new(-0.5, 0.9, 1.3),
        z: vec![0.04, -0.03, 0.02, 0.05, -0.01],
        zdot: vec![0.3, 0.5, -0.4, 0.2, -0.6],
    };
    let s = sys.state(0.2, &[sa], &[sf]).unwrap();
    (sys, s)
}

type AddConstraint = Box<dyn Fn(&mut FloatingSystem, Marker, Marker)>;

/// Every joint and driver of the vocabulary between markers `i` and `j`.
fn all_constraints() -> Vec<AddConstraint> {
    fn add(s: &mut FloatingSystem, c: impl Constraint + 'static) {
        s.add_constraint(c).unwrap();
    }
    // joints with fields name, i, j only
    macro_rules! simple {
        ($t:ident, $n:expr) => {
            Box::new(|s: &mut FloatingSystem, i: Marker, j: Marker| {
                add(
                    s,
                    $t {
                        name: $n.into(),
                        i,
                        j,
                    },
                )
            }) as AddConstraint
        };
    }
    let law = || DriverLaw::SpeedRamp {
        theta0: 0.3,
        omega: 2.0,
        ramp: 0.5,
    };
    vec![
        simple!(Spherical, "sph"),
        simple!(Revolute, "rev"),
        simple!(Fixed, "fix"),
        simple!(Universal, "uni"),
        Box::new(|s, i, j| {
            add(
                s,
                Prismatic {
                    name: "pri".into(),
                    i,
                    j,
                    reference_i: Vector3::new(1.0, 0.2, 0.0),
                    reference_j: Vector3::new(0.1, 1.0, 0.3),
                },
            )
        }),
        Box::new(|s, i, j| {
            add(
                s,
                Distance {
                    name: "dist".into(),
                    i,
                    j,
                    length: 0.7,
                },
            )
        }),
        simple!(PointOnPlane, "pop"),
        simple!(PlanarRevolute, "prev"),
        Box::new(move |s, i, j| {
            add(
                s,
                RotationDriver {
                    name: "drv".into(),
                    i,
                    j,
                    reference_i: Vector3::new(1.0, 0.0, 0.0),
                    reference_j: Vector3::new(0.0, 1.0, 0.2),
                    law: law(),
                },
            )
        }),
        Box::new(move |s, _, j| {
            add(
                s,
                PointDriver {
                    name: "pdrv".into(),
                    point: j,
                    component: 1,
                    law: law(),
                },
            )
        }),
    ]
}

#[test]
fn joints_on_flexible_nodes_match_finite_differences() {
    // Second formulation: Φ̇ = D v − ν and Φ̈ = −γ along q ⊕ τ v (v̇ = 0), and every column of
    // D against central differences of Φ along q ⊕ h e_k.
    let rigid = Marker::new(
        Some(0),
        Vector3::new(0.1, -0.2, 0.3),
        Vector3::new(0.3, 0.4, 1.0),
    );
    let node = Marker::node_frame(
        0,
        2,
        Vector3::new(-0.05, 0.08, 0.02),
        Vector3::new(0.2, -0.3, 1.0),
    );
    let node_b = Marker::node_frame(
        0,
        1,
        Vector3::new(0.03, 0.0, -0.04),
        Vector3::new(1.0, 0.3, 0.1),
    );
    let ground = Marker::new(
        None,
        Vector3::new(0.2, 0.1, -0.1),
        Vector3::new(0.0, 0.6, 1.0),
    );
    let pairs = [
        ("rigid-node", rigid, node),
        ("node-rigid", node, rigid),
        ("ground-node", ground, node),
        ("node-node", node_b, node),
    ];
    for rotations in [true, false] {
        for (label, mi, mj) in pairs {
            for add in all_constraints() {
                let (mut sys, s) = rigid_and_flex(rotations);
                add(&mut sys, mi, mj);
                let name = format!(
                    "{} ({label}, rotations {rotations})",
                    sys.constraints()[0].name()
                );
                let nc = sys.n_c();
                let nv = sys.n_v();
                common::check_rates(&sys, &s, &name);
                let d = sys.constraint_jacobian(s.t, &s.q).unwrap().to_dense();
                let phi_at = |q: &[f64]| {
                    let mut phi = vec![0.0; nc];
                    sys.constraint_residual(s.t, q, &mut phi).unwrap();
                    phi
                };
                for k in 0..nv {
                    let mut e = vec![0.0; nv];
                    e[k] = 1.0;
                    let (fp, fm) = (
                        phi_at(&common::moved(&sys, &s, &e, 1e-6)),
                        phi_at(&common::moved(&sys, &s, &e, -1e-6)),
                    );
                    for r in 0..nc {
                        let fd = (fp[r] - fm[r]) / 2e-6;
                        assert!(
                            (fd - d[(r, k)]).abs() < 1e-7 * (1.0 + fd.abs()),
                            "{name} D[{r},{k}] = {} vs {fd}",
                            d[(r, k)]
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn markers_are_validated_against_the_container() {
    let (mut sys, _) = rigid_and_flex(false);
    let bad_node = sys.add_constraint(Spherical {
        name: "pin".into(),
        i: Marker::point(Some(0), Vector3::zeros()),
        j: Marker::node(0, 4),
    });
    let msg = bad_node.unwrap_err().to_string();
    assert!(msg.contains("pin") && msg.contains("node 4"), "{msg}");
    let bad_flex = sys.add_constraint(Spherical {
        name: "pin".into(),
        i: Marker::point(None, Vector3::zeros()),
        j: Marker::node(1, 0),
    });
    assert!(
        bad_flex
            .unwrap_err()
            .to_string()
            .contains("flexible body 1")
    );
    let mut rigid_only = MultibodySystem::new();
    rigid_only.add_body(RigidBody::with_principal("a", 1.0, [1.0, 1.0, 1.0]).unwrap());
    let e = rigid_only
        .add_constraint(Spherical {
            name: "pin".into(),
            i: Marker::point(None, Vector3::zeros()),
            j: Marker::node(0, 0),
        })
        .unwrap_err();
    assert!(e.to_string().contains("flexible"), "{e}");
}

/// A truss bar along x: `ns` stations `h` apart, 2×2 nodes of a square section of side `w`
/// per station, bars (EA \[N\]) between all nodes of the same or adjacent stations, node mass
/// `m_node` \[kg\]. Returns positions (3 per node), M', K'.
fn truss_bar(ns: usize, h: f64, w: f64, ea: f64, m_node: f64) -> (Vec<f64>, Mat<f64>, Mat<f64>) {
    let mut s = Vec::new();
    for k in 0..ns {
        for (y, z) in [(0.0, 0.0), (w, 0.0), (0.0, w), (w, w)] {
            s.extend([k as f64 * h, y - 0.5 * w, z - 0.5 * w]);
        }
    }
    let n = s.len() / 3;
    let m = Mat::<f64>::from_fn(3 * n, 3 * n, |i, j| if i == j { m_node } else { 0.0 });
    let mut kk = Mat::<f64>::zeros(3 * n, 3 * n);
    let node = |a: usize| Vector3::new(s[3 * a], s[3 * a + 1], s[3 * a + 2]);
    for a in 0..n {
        for b in a + 1..n {
            if (a / 4).abs_diff(b / 4) > 1 {
                continue;
            }
            let d = node(b) - node(a);
            let l = d.norm();
            let e = d / l;
            let kb = e * e.transpose() * (ea / l);
            for i in 0..3 {
                for j in 0..3 {
                    kk[(3 * a + i, 3 * a + j)] += kb[(i, j)];
                    kk[(3 * b + i, 3 * b + j)] += kb[(i, j)];
                    kk[(3 * a + i, 3 * b + j)] -= kb[(i, j)];
                    kk[(3 * b + i, 3 * a + j)] -= kb[(i, j)];
                }
            }
        }
    }
    (s, m, kk)
}

/// Nodal-fixed basis (3-2-1 anchors, Lin §4.1, Table 4-1): identity without node 0 (x, y, z),
/// node 1 (x, z; it lies along y from node 0) and node 2 (x; along z from node 0). Nodes 0–2
/// lie in the section x = 0, so the frame follows that section.
fn nodal_fixed_basis(n: usize) -> Mat<f64> {
    let anchored = [0usize, 1, 2, 3, 5, 6];
    let free: Vec<usize> = (0..3 * n).filter(|d| !anchored.contains(d)).collect();
    Mat::<f64>::from_fn(
        3 * n,
        free.len(),
        |i, j| if free[j] == i { 1.0 } else { 0.0 },
    )
}

/// The link (body `link`, length `link_len` \[m\] along its x) hinged to the ground at the
/// origin about z, and the bar marker `bar` hinged to the link tip about z.
fn hinge_and_pin(link: usize, link_len: f64, bar: Marker) -> [Revolute; 2] {
    let end = |x: f64| {
        Marker::new(
            Some(link),
            Vector3::new(x * link_len, 0.0, 0.0),
            Vector3::z(),
        )
    };
    [
        Revolute {
            name: "hinge".into(),
            i: Marker::new(None, Vector3::zeros(), Vector3::z()),
            j: end(-0.5),
        },
        Revolute {
            name: "pin".into(),
            i: end(0.5),
            j: bar,
        },
    ]
}

#[test]
fn stiff_flexible_bar_on_a_rigid_link_matches_the_rigid_model() {
    // A double pendulum: rigid link (0.5 m) hinged to the ground about z, a 1 m bar hinged to the
    // link tip about z at its end node 0; both start horizontal at rest under gravity. Model 1:
    // the bar is a very stiff floating-frame truss; model 2 (reference): the bar is a rigid body
    // with the same mass and inertia in MultibodySystem. Same revolute code, same integrator.
    let (ns, h, w, m_node) = (6, 0.2, 0.1, 0.05);
    let g = Vector3::new(0.0, -9.81, 0.0);
    let link_len = 0.5;
    let link = || RigidBody::with_principal("link", 1.0, [1e-3, 0.0215, 0.0215]).unwrap();
    let p0 = Vector4::new(1.0, 0.0, 0.0, 0.0);
    let link_state = BodyState::at_rest(Vector3::new(0.5 * link_len, 0.0, 0.0), p0);
    let tip = Vector3::new(link_len, 0.0, 0.0);
    let alpha = GeneralizedAlpha::new(AlphaConfig {
        h: 1e-3,
        rho_inf: 0.6,
        ..Default::default()
    });
    let t_end = 0.4;

    // model 2: rigid bar; node 0 of the truss at (0, −w/2, −w/2) relative to the section centre
    let (s, _, _) = truss_bar(ns, h, w, 1.0, m_node);
    let n = s.len() / 3;
    let mass = m_node * n as f64;
    let nodes: Vec<Vector3<f64>> = s
        .chunks(3)
        .map(|c| Vector3::new(c[0], c[1], c[2]))
        .collect();
    let c = nodes.iter().sum::<Vector3<f64>>() / n as f64;
    let inertia = nodes.iter().fold(Matrix3::zeros(), |acc, x| {
        let d = x - c;
        acc + (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * m_node
    });
    let pin_local = nodes[0] - c; // pin at node 0, relative to the mass centre
    let mut rig = MultibodySystem::new();
    let l = rig.add_body(link());
    let bar = rig.add_body(RigidBody::new("bar", mass, inertia).unwrap());
    for joint in hinge_and_pin(l, link_len, Marker::new(Some(bar), pin_local, Vector3::z())) {
        rig.add_constraint(joint).unwrap();
    }
    rig.add_force(Gravity { g }).unwrap();
    let bar_state = BodyState::at_rest(tip - pin_local, p0);
    let s0 = rig.state(0.0, &[link_state, bar_state]).unwrap();
    let far = Marker::point(Some(bar), nodes[n - 1] - c);
    let rigid_far = {
        let sol = alpha.integrate(&rig, s0, t_end, |_| {}).unwrap();
        let k = rig.body_state(&sol.state, bar);
        k.r + mbd_core::kinematics::euler::a_matrix(&k.p) * far.point
    };

    // model 1: stiff truss bar, frame origin at node 0 (the pin), nodal-fixed axes
    let flex_far = |ea: f64| {
        let (s, m, k) = truss_bar(ns, h, w, ea, m_node);
        let s_rel: Vec<f64> = s
            .chunks(3)
            .flat_map(|x| [x[0] - s[0], x[1] - s[1], x[2] - s[2]])
            .collect();
        let psi = nodal_fixed_basis(n);
        let body = FlexBody::new(
            "bar",
            &s_rel,
            m.as_ref(),
            k.as_ref(),
            psi.as_ref(),
            AxisCondition::NodalFixed,
        )
        .unwrap();
        let nz = psi.ncols();
        let mut sys = FloatingSystem::new();
        sys.gravity = g;
        let l = sys.add_rigid(link());
        let fb = sys.add_flex(body);
        for joint in hinge_and_pin(l, link_len, Marker::node(fb, 0)) {
            sys.add_constraint(joint).unwrap();
        }
        let st = sys
            .state(
                0.0,
                &[link_state],
                &[FlexState {
                    r: tip,
                    p: p0,
                    rdot: Vector3::zeros(),
                    omega_local: Vector3::zeros(),
                    z: vec![0.0; nz],
                    zdot: vec![0.0; nz],
                }],
            )
            .unwrap();
        let sol = alpha.integrate(&sys, st, t_end, |_| {}).unwrap();
        sys.point_position(&sol.state, &Marker::node(fb, n - 1))
    };
    let travel = (rigid_far - (tip + nodes[n - 1] - nodes[0])).norm();
    assert!(travel > 0.1, "the bar swings ({travel} m)");
    let (soft, stiff) = (
        (flex_far(2e5) - rigid_far).norm(),
        (flex_far(2e8) - rigid_far).norm(),
    );
    eprintln!(
        "tip travel {travel:.4} m; |flex − rigid| {soft:.3e} m (EA 2e5 N), {stiff:.3e} m (EA 2e8 N)"
    );
    // measured: 4.0e-5 m and 2.2e-6 m; the floor at EA → ∞ is the two models' different
    // discretisation errors (h = 1 ms), the excess at EA 2e5 N the bar's elastic deflection
    assert!(stiff < 1e-5 * travel, "EA 2e8: {stiff} m");
    assert!(
        soft > 5.0 * stiff,
        "elastic deflection visible: {soft} m vs {stiff} m"
    );
}
