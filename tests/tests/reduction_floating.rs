//! Floating-frame deformable bodies (mbd-core::floating) with bases from `reduction`:
//! invariants of Lin ch. 3-5 and 8 and Ribaric (2.45)-(2.52), integrated with mbd-core's
//! integrators.
#![allow(clippy::needless_range_loop)] // index loops mirror the printed tables

use faer::Mat;
use mbd_core::constraints::Spherical;
use mbd_core::floating::{
    AxisCondition, ElasticForces, FlexBody, FlexState, FloatingSystem, RigidCore,
};
use mbd_core::integrators::{DormandPrince, Stabilization, accelerations};
use mbd_core::kinematics::euler::from_axis_angle;
use mbd_core::marker::Marker;
use mbd_core::{BodyState, RigidBody, SecondOrderSystem};
use nalgebra::{DMatrix, DVector, Matrix3, Vector3, Vector4};
use reduction::DofPartition;
use reduction::axes::{Axis, NodalFixedFrame, remove_anchor_columns};
use reduction::basis::{Method, ModeSelection, build_basis};

/// A 3-D truss block of `nx × ny × nz` nodes, spacing `h` \[m\], bars (EA \[N\]) between all node
/// pairs closer than `1.01·√3·h` (so it is rigid as a structure), lumped masses varying
/// slightly per node \[kg\]; positions relative to the mass centre.
fn truss_block(nx: usize, ny: usize, nz: usize, h: f64, ea: f64) -> (Vec<f64>, Mat<f64>, Mat<f64>) {
    let (s, m, k, _) = truss_block_rotated(nx, ny, nz, h, ea, false);
    (s, m, k)
}

/// As [`truss_block`]; with `principal`, the positions are expressed in the principal axes of
/// the undeformed inertia (so `J'` is diagonal at `z = 0`). Also returns the node masses.
fn truss_block_rotated(
    nx: usize, ny: usize, nz: usize, h: f64, ea: f64, principal: bool,
) -> (Vec<f64>, Mat<f64>, Mat<f64>, Vec<f64>) {
    let mut pos = Vec::new();
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                pos.push(Vector3::new(i as f64 * h, j as f64 * h, k as f64 * h));
            }
        }
    }
    let n = pos.len();
    let masses: Vec<f64> = (0..n).map(|i| 1.0 + 0.1 * ((i * 7) % 5) as f64).collect();
    let mt: f64 = masses.iter().sum();
    let c: Vector3<f64> = pos
        .iter()
        .zip(&masses)
        .map(|(p, m)| p * *m)
        .sum::<Vector3<f64>>()
        / mt;
    for p in pos.iter_mut() {
        *p -= c;
    }
    if principal {
        let mut j = Matrix3::zeros();
        for (p, m) in pos.iter().zip(&masses) {
            j += (Matrix3::identity() * p.norm_squared() - p * p.transpose()) * *m;
        }
        let e = j.symmetric_eigen();
        let r = e.eigenvectors;
        for p in pos.iter_mut() {
            *p = r.transpose() * *p;
        }
    }
    let s: Vec<f64> = pos.iter().flat_map(|p| [p.x, p.y, p.z]).collect();
    let m = Mat::from_fn(
        3 * n,
        3 * n,
        |i, j| if i == j { masses[i / 3] } else { 0.0 },
    );
    let mut k = Mat::<f64>::zeros(3 * n, 3 * n);
    for a in 0..n {
        for b in a + 1..n {
            let d = pos[b] - pos[a];
            let l = d.norm();
            if l <= 1.01 * 3f64.sqrt() * h {
                let e = d / l;
                let ke = e * e.transpose() * (ea / l);
                for r in 0..3 {
                    for cc in 0..3 {
                        k[(3 * a + r, 3 * a + cc)] += ke[(r, cc)];
                        k[(3 * b + r, 3 * b + cc)] += ke[(r, cc)];
                        k[(3 * a + r, 3 * b + cc)] -= ke[(r, cc)];
                        k[(3 * b + r, 3 * a + cc)] -= ke[(r, cc)];
                    }
                }
            }
        }
    }
    (s, m, k, masses)
}

/// Removes the rigid-body content of `x` by M-orthogonal projection (so that the mean-axis
/// conditions hold for `x` as a deflection or deflection rate).
fn project_out_rigid(s: &[f64], m: &Mat<f64>, x: &[f64]) -> Vec<f64> {
    let xm = Mat::from_fn(x.len(), 1, |i, _| x[i]);
    let (_, def) = reduction::axes::mean_axes_decomposition(m.as_ref(), s, 3, xm.as_ref()).unwrap();
    (0..x.len()).map(|i| def[(i, 0)]).collect()
}

#[test]
fn floating_mass_matrix_has_six_fold_rank_deficiency() {
    // Lin (3.37)-(3.39): QᵀMQ with the unreduced nodal deflections has nullity exactly 6;
    // IhᵀMIh = mI; J' = b~'ᵀM'b~' (companion V-FF-1).
    let (s, m, k) = truss_block(3, 2, 2, 0.5, 1e4);
    let n = s.len();
    let id = Mat::<f64>::identity(n, n);
    let body = FlexBody::new(
        "block",
        &s,
        m.as_ref(),
        k.as_ref(),
        id.as_ref(),
        AxisCondition::NodalFixed,
    )
    .unwrap();
    let mtot = body.mass();
    let mut sys = FloatingSystem::new();
    sys.add_flex(body);
    let z: Vec<f64> = (0..n).map(|i| 0.01 * ((i as f64) * 0.37).sin()).collect();
    let st = sys
        .state(
            0.0,
            &[],
            &[FlexState {
                r: Vector3::new(1.0, 2.0, 3.0),
                p: from_axis_angle(&Vector3::new(1.0, 2.0, 2.0).normalize(), 0.7),
                rdot: Vector3::zeros(),
                omega_local: Vector3::zeros(),
                z: z.clone(),
                zdot: vec![0.0; n],
            }],
        )
        .unwrap();
    let mm = sys.mass(0.0, &st.q).unwrap().to_dense();
    let sv = mm.singular_values().unwrap();
    let smax = sv[0];
    let nzero = sv.iter().filter(|&&x| x < 1e-10 * smax).count();
    assert_eq!(nzero, 6, "singular values {sv:?}");
    for c in 0..3 {
        assert!((mm[(c, c)] - mtot).abs() < 1e-12 * mtot);
    }
    // J' from the nodal sum Σ m (|b|² I − b bᵀ)
    let mut j = Matrix3::zeros();
    for i in 0..n / 3 {
        let b = Vector3::new(
            s[3 * i] + z[3 * i],
            s[3 * i + 1] + z[3 * i + 1],
            s[3 * i + 2] + z[3 * i + 2],
        );
        j += (Matrix3::identity() * b.norm_squared() - b * b.transpose()) * m[(3 * i, 3 * i)];
    }
    for a in 0..3 {
        for b in 0..3 {
            assert!((mm[(3 + a, 3 + b)] - j[(a, b)]).abs() < 1e-12 * j.norm());
        }
    }
}

fn free_flight_state(s: &[f64], m: &Mat<f64>, nz_scale: f64) -> FlexState {
    let n = s.len();
    let raw: Vec<f64> = (0..n)
        .map(|i| nz_scale * ((i as f64) * 1.3).sin())
        .collect();
    let rawd: Vec<f64> = (0..n)
        .map(|i| 10.0 * nz_scale * ((i as f64) * 0.7).cos())
        .collect();
    // z with the undeformed positions (translational condition IhᵀM'z = 0), ż with the
    // deformed ones b' = s' + z (the rotational velocity condition uses b~', Lin (4.15))
    let z = project_out_rigid(s, m, &raw);
    let b: Vec<f64> = s.iter().zip(&z).map(|(a, b)| a + b).collect();
    FlexState {
        r: Vector3::zeros(),
        p: from_axis_angle(&Vector3::new(0.0, 0.0, 1.0), 0.3),
        rdot: Vector3::new(0.1, 0.0, 0.2),
        omega_local: Vector3::new(0.3, 1.0, 0.2),
        zdot: project_out_rigid(&b, m, &rawd),
        z,
    }
}

#[test]
fn mean_axes_multipliers_vanish_in_the_nodal_formulation() {
    // Lin §4.4 and (4.22): the axis-condition multipliers are zero (companion V-FF-2: exact
    // for the nodal formulation when elastic forces are nodal, Lin (3.33)).
    let (s, m, k) = truss_block(3, 2, 2, 0.5, 1e4);
    let n = s.len();
    let id = Mat::<f64>::identity(n, n);
    let body = FlexBody::new(
        "block",
        &s,
        m.as_ref(),
        k.as_ref(),
        id.as_ref(),
        AxisCondition::MeanAxes,
    )
    .unwrap()
    .with_elastic_forces(ElasticForces::Nodal);
    let mut sys = FloatingSystem::new();
    sys.gravity = Vector3::new(0.0, 0.0, -9.80665);
    sys.add_flex(body);
    let st = sys
        .state(0.0, &[], &[free_flight_state(&s, &m, 0.01)])
        .unwrap();
    let acc = accelerations(&sys, &st, &Stabilization::default()).unwrap();
    let fscale = 1e4 * 0.01;
    for (i, l) in acc.lambda.iter().enumerate() {
        assert!(l.abs() < 1e-9 * fscale, "λ[{i}] = {l}");
    }
    // with the energy-consistent elastic forces the translational multipliers still vanish and
    // the rotational ones are second order in the deflection (halving δ divides them by 4)
    let body2 = FlexBody::new(
        "block",
        &s,
        m.as_ref(),
        k.as_ref(),
        id.as_ref(),
        AxisCondition::MeanAxes,
    )
    .unwrap();
    let mut sys2 = FloatingSystem::new();
    sys2.add_flex(body2);
    let lam = |scale: f64| {
        let st = sys2
            .state(0.0, &[], &[free_flight_state(&s, &m, scale)])
            .unwrap();
        accelerations(&sys2, &st, &Stabilization::default())
            .unwrap()
            .lambda
    };
    let (l1, l2) = (lam(0.01), lam(0.005));
    for l in &l1[..3] {
        assert!(l.abs() < 1e-9 * fscale);
    }
    let n1: f64 = l1[3..].iter().map(|x| x * x).sum::<f64>().sqrt();
    let n2: f64 = l2[3..].iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!(n1 > 0.0 && (n1 / n2 - 4.0).abs() < 0.2, "ratio {}", n1 / n2);
}

#[test]
fn mean_axes_hold_along_a_free_flight() {
    // Lin Table 4-2 (companion V-FF-3): IhᵀM'δ' = 0, IhᵀM'δ̇' = 0 and b~'ᵀM'δ̇' = 0 along a
    // free flight under gravity; energy is conserved (Modal elastic forces are conservative).
    let (s, m, k) = truss_block(3, 2, 2, 0.5, 1e4);
    let n = s.len();
    let id = Mat::<f64>::identity(n, n);
    let body = FlexBody::new(
        "block",
        &s,
        m.as_ref(),
        k.as_ref(),
        id.as_ref(),
        AxisCondition::MeanAxes,
    )
    .unwrap();
    let mut sys = FloatingSystem::new();
    sys.gravity = Vector3::new(0.0, 0.0, -9.80665);
    sys.add_flex(body);
    let st = sys
        .state(0.0, &[], &[free_flight_state(&s, &m, 0.01)])
        .unwrap();
    let e0 = sys.kinetic_energy(&st).unwrap() + sys.potential_energy(&st);
    let mut worst = [0.0f64; 9];
    let integ = DormandPrince::new(1e-10, 1e-12);
    let sol = integ
        .integrate(&sys, st, 0.5, |x| {
            let r = sys.mean_axis_residuals(x, 0);
            for i in 0..9 {
                worst[i] = worst[i].max(r[i].abs());
            }
        })
        .unwrap();
    let e1 = sys.kinetic_energy(&sol.state).unwrap() + sys.potential_energy(&sol.state);
    assert!(
        worst.iter().all(|&w| w < 1e-8),
        "mean-axis residuals {worst:?}"
    );
    assert!(
        (e1 - e0).abs() < 1e-7 * e0.abs().max(1.0),
        "energy {e0} -> {e1}"
    );
    // the deformation really oscillates (non-trivial test)
    let z1 = &sys.flex_state(&sol.state, 0).z;
    assert!(z1.iter().map(|x| x.abs()).fold(0.0, f64::max) > 1e-3);
}

#[test]
fn craig_bampton_and_mode_condensation_give_identical_trajectories() {
    // Lin §6.5.4 and ch. 7 (companion: "CB ≡ MC in time simulations"): same column space ⇒
    // identical physical trajectories under the nodal-fixed modal formulation (5.18); the
    // body swings under gravity from a ground spherical joint at the anchor node.
    let (s, m, k) = truss_block(4, 2, 2, 0.5, 2e3);
    let n = s.len();
    // bottom corners (0-based): nodes 0, 3 (x-axis), 4, 7
    let boundary = [0usize, 3, 4, 7];
    let part = DofPartition::from_boundary_nodes(n, 3, &boundary).unwrap();
    let frame = NodalFixedFrame {
        origin: 0,
        axis_node: 3,
        axis: Axis::Xi,
        plane_node: 4,
        plane_axis: Axis::Eta,
    };
    let anchors = frame.anchored_dofs(n / 3).unwrap();
    let sel = ModeSelection::Lowest(4);
    let mut tracks = Vec::new();
    for method in [Method::CraigBampton, Method::ModeCondensation] {
        let basis = build_basis(k.as_ref(), m.as_ref(), &part, method, &sel).unwrap();
        let basis = remove_anchor_columns(&basis, &anchors).unwrap();
        assert_eq!(basis.psi.ncols(), 12 - 6 + 4);
        // frame origin at node 0
        let s0: Vec<f64> = (0..n).map(|i| s[i] - s[i % 3]).collect();
        let body = FlexBody::new(
            "block",
            &s0,
            m.as_ref(),
            k.as_ref(),
            basis.psi.as_ref(),
            AxisCondition::NodalFixed,
        )
        .unwrap();
        let mut sys = FloatingSystem::new();
        sys.gravity = Vector3::new(0.0, 0.0, -9.80665);
        let fb = sys.add_flex(body);
        sys.add_constraint(Spherical {
            name: "pivot".into(),
            i: Marker::node(fb, 0),
            j: Marker::point(None, Vector3::zeros()),
        })
        .unwrap();
        let nz = basis.psi.ncols();
        let st = sys
            .state(
                0.0,
                &[],
                &[FlexState {
                    r: Vector3::zeros(),
                    p: from_axis_angle(&Vector3::new(1.0, 0.0, 0.0), 0.2),
                    rdot: Vector3::zeros(),
                    omega_local: Vector3::new(0.0, 0.5, 1.0),
                    z: vec![0.0; nz],
                    zdot: vec![0.0; nz],
                }],
            )
            .unwrap();
        let mut track = Vec::new();
        let far = Marker::node(fb, n / 3 - 1);
        let integ = DormandPrince::new(1e-10, 1e-12);
        integ
            .integrate(&sys, st, 0.6, |x| {
                track.push((x.t, sys.point_position(x, &far)));
            })
            .unwrap();
        tracks.push((sys, track));
    }
    // compare the far node's trajectory at common times via the final state and sampled path
    let (_, a) = &tracks[0];
    let (_, b) = &tracks[1];
    let last_a = a.last().unwrap();
    let last_b = b.last().unwrap();
    assert!((last_a.0 - last_b.0).abs() < 1e-12);
    let d = (last_a.1 - last_b.1).norm();
    assert!(d < 1e-6, "far-node positions differ by {d} m");
    // the body moved and deformed substantially
    assert!((last_a.1 - a[0].1).norm() > 0.05);
}

#[test]
fn rigid_core_matches_ribaric_block_triangular_solution() {
    // Ribaric (2.50)-(2.52): rigid body bonded to the w nodes of a deformable body; the rigid
    // part is solved first (6×6), then the f-node relative accelerations. Compared with the
    // symmetric Kane form of FloatingSystem at a generic state (A = I).
    let (s, m, k) = truss_block(3, 2, 2, 0.5, 1e4);
    let n = s.len();
    let nn = n / 3;
    let w_nodes: Vec<usize> = (0..6).collect(); // bottom layer bonded to the core
    let f_nodes: Vec<usize> = (6..nn).collect();
    let fdofs: Vec<usize> = f_nodes
        .iter()
        .flat_map(|&j| [3 * j, 3 * j + 1, 3 * j + 2])
        .collect();
    let psi = Mat::from_fn(n, fdofs.len(), |i, c| (i == fdofs[c]) as u8 as f64);
    let core = RigidCore {
        mass: 5.0,
        inertia: Matrix3::from_diagonal(&Vector3::new(0.4, 0.6, 0.7)),
    };
    let body = FlexBody::new(
        "tire",
        &s,
        m.as_ref(),
        k.as_ref(),
        psi.as_ref(),
        AxisCondition::NodalFixed,
    )
    .unwrap()
    .with_rigid_core(core)
    .unwrap()
    .with_elastic_forces(ElasticForces::Nodal);
    let mut sys = FloatingSystem::new();
    let g = Vector3::new(0.0, -3.0, -9.80665);
    sys.gravity = g;
    sys.add_flex(body);
    let nf = fdofs.len();
    let z: Vec<f64> = (0..nf).map(|i| 0.02 * ((i as f64) * 0.9).sin()).collect();
    let zd: Vec<f64> = (0..nf).map(|i| 0.3 * ((i as f64) * 0.4).cos()).collect();
    let w = Vector3::new(0.7, -1.1, 2.0);
    let st = sys
        .state(
            0.0,
            &[],
            &[FlexState {
                r: Vector3::zeros(),
                p: Vector4::new(1.0, 0.0, 0.0, 0.0),
                rdot: Vector3::new(0.3, 0.1, 0.0),
                omega_local: w,
                z: z.clone(),
                zdot: zd.clone(),
            }],
        )
        .unwrap();
    let acc = accelerations(&sys, &st, &Stabilization::default()).unwrap();
    // Ribaric reference (global = local since A = I)
    let mass = |j: usize| m[(3 * j, 3 * j)];
    let sv = |j: usize| Vector3::new(s[3 * j], s[3 * j + 1], s[3 * j + 2]);
    let kd = {
        let zz = DVector::from_fn(nf, |i, _| z[i]);
        let kfull = DMatrix::from_fn(n, n, |i, j| k[(i, j)]);
        let kcols = DMatrix::from_fn(n, nf, |i, c| kfull[(i, fdofs[c])]);
        kcols * zz
    };
    let tl = |v: &Vector3<f64>| v.cross_matrix();
    let mut a66 = DMatrix::<f64>::zeros(6, 6);
    let mut rhs = DVector::<f64>::zeros(6);
    let mut mw = core.mass;
    let mut sw_first = Vector3::zeros();
    let mut jw = core.inertia;
    let mut fsum = g * core.mass;
    let mut msum = -w.cross(&(core.inertia * w));
    for &j in &w_nodes {
        let sj = sv(j);
        mw += mass(j);
        sw_first += sj * mass(j);
        jw += tl(&sj).transpose() * tl(&sj) * mass(j);
        let fj = g * mass(j)
            - Vector3::new(kd[3 * j], kd[3 * j + 1], kd[3 * j + 2])
            - w.cross(&w.cross(&sj)) * mass(j);
        fsum += fj;
        msum += sj.cross(&fj);
    }
    let c = -tl(&sw_first);
    for a in 0..3 {
        a66[(a, a)] = mw;
        for b in 0..3 {
            a66[(a, 3 + b)] = c[(a, b)];
            a66[(3 + a, b)] = c[(b, a)];
            a66[(3 + a, 3 + b)] = jw[(a, b)];
        }
        rhs[a] = fsum[a];
        rhs[3 + a] = msum[a];
    }
    let x = a66.lu().solve(&rhs).unwrap();
    let rdd = Vector3::new(x[0], x[1], x[2]);
    let wd = Vector3::new(x[3], x[4], x[5]);
    for a in 0..3 {
        assert!(
            (acc.vdot[a] - rdd[a]).abs() < 1e-9 * (1.0 + rdd.norm()),
            "r̈"
        );
        assert!(
            (acc.vdot[3 + a] - wd[a]).abs() < 1e-9 * (1.0 + wd.norm()),
            "ω̇"
        );
    }
    // (2.52) per f node
    for (c, &j) in f_nodes.iter().enumerate() {
        let b = sv(j) + Vector3::new(z[3 * c], z[3 * c + 1], z[3 * c + 2]);
        let dd = Vector3::new(zd[3 * c], zd[3 * c + 1], zd[3 * c + 2]);
        let wf = w.cross(&w.cross(&b)) + 2.0 * w.cross(&dd);
        let fel = Vector3::new(kd[3 * j], kd[3 * j + 1], kd[3 * j + 2]);
        // d̈ = r̈ − b̃ω̇ + δ̈ + w  with  −b̃ω̇ = ω̇ × b
        let expect = (g * mass(j) - fel - wf * mass(j)) / mass(j) - (rdd + wd.cross(&b));
        for a in 0..3 {
            let got = acc.vdot[6 + 3 * c + a];
            assert!(
                (got - expect[a]).abs() < 1e-8 * (1.0 + expect.norm()),
                "δ̈ node {j}: {got} vs {}",
                expect[a]
            );
        }
    }
}

#[test]
fn rigid_link_joined_to_flexible_node_keeps_constraints_and_energy() {
    // Lin ch. 5 (5.1)-(5.7), (5.19): rigid link hanging from the ground, spherical joint to a
    // node of a mean-axes flexible body; constraint residuals stay small and energy is
    // conserved (no dissipation) with Baumgarte-free Dormand–Prince.
    let (s, m, k) = truss_block(3, 2, 2, 0.5, 5e3);
    let n = s.len();
    let id = Mat::<f64>::identity(n, n);
    let body = FlexBody::new(
        "plank",
        &s,
        m.as_ref(),
        k.as_ref(),
        id.as_ref(),
        AxisCondition::MeanAxes,
    )
    .unwrap();
    let mut sys = FloatingSystem::new();
    sys.gravity = Vector3::new(0.0, 0.0, -9.80665);
    let link = sys
        .add_rigid(RigidBody::with_principal("link", 1.0, [1.0 / 3.0, 1.0 / 3.0, 0.01]).unwrap());
    let fb = sys.add_flex(body);
    // link along z, 2 m, mass centre at (0,0,1) relative to the node; top end at ground
    let node = 11; // top corner (x=1, y=0.5, z=0.5) relative coordinates
    let sn = Vector3::new(s[3 * node], s[3 * node + 1], s[3 * node + 2]);
    let top = sn + Vector3::new(0.0, 0.0, 2.0);
    sys.add_constraint(Spherical {
        name: "A".into(),
        i: Marker::point(Some(link), Vector3::new(0.0, 0.0, 1.0)),
        j: Marker::point(None, top),
    })
    .unwrap();
    sys.add_constraint(Spherical {
        name: "B".into(),
        i: Marker::point(Some(link), Vector3::new(0.0, 0.0, -1.0)),
        j: Marker::node(fb, node),
    })
    .unwrap();
    let st = sys
        .state(
            0.0,
            &[BodyState::at_rest(
                sn + Vector3::new(0.0, 0.0, 1.0),
                Vector4::new(1.0, 0.0, 0.0, 0.0),
            )],
            &[FlexState {
                r: Vector3::zeros(),
                p: Vector4::new(1.0, 0.0, 0.0, 0.0),
                rdot: Vector3::zeros(),
                omega_local: Vector3::zeros(),
                z: vec![0.0; n],
                zdot: vec![0.0; n],
            }],
        )
        .unwrap();
    let e0 = sys.kinetic_energy(&st).unwrap() + sys.potential_energy(&st);
    let integ = DormandPrince::new(1e-9, 1e-11);
    let mut phi_max = 0.0f64;
    let mut phi = vec![0.0; sys.n_c()];
    let sol = integ
        .integrate(&sys, st, 0.5, |x| {
            sys.constraint_residual(x.t, &x.q, &mut phi).unwrap();
            // joints only (rows 6..12); the rotational mean-axis rows have no position residual
            phi_max = phi_max.max(phi[6..].iter().fold(0.0, |a: f64, b| a.max(b.abs())));
        })
        .unwrap();
    let e1 = sys.kinetic_energy(&sol.state).unwrap() + sys.potential_energy(&sol.state);
    assert!(phi_max < 1e-6, "joint drift {phi_max} m");
    assert!(
        (e1 - e0).abs() < 1e-5 * (1.0 + e0.abs()),
        "energy {e0} -> {e1}"
    );
    let r = sys.mean_axis_residuals(&sol.state, 0);
    assert!(r.iter().all(|x| x.abs() < 1e-7), "{r:?}");
    // the body fell: the plank swings from the link
    assert!((sys.flex_state(&sol.state, 0).r).norm() > 0.05);
}

#[test]
fn principal_axes_hold_along_a_free_flight() {
    // Lin §4.3, Ribaric (2.42)-(2.44): translational mean-axis condition plus zero products of
    // inertia; both hold (holonomic) along a free flight with large rotation; energy conserved.
    let (s, m, k, _) = truss_block_rotated(4, 3, 2, 0.5, 1e4, true);
    let n = s.len();
    let id = Mat::<f64>::identity(n, n);
    let body = FlexBody::new(
        "block",
        &s,
        m.as_ref(),
        k.as_ref(),
        id.as_ref(),
        AxisCondition::PrincipalAxes,
    )
    .unwrap();
    let mut sys = FloatingSystem::new();
    sys.add_flex(body);
    let raw: Vec<f64> = (0..n).map(|i| 0.1 * ((i as f64) * 0.7).cos()).collect();
    let mut st = sys
        .state(
            0.0,
            &[],
            &[FlexState {
                r: Vector3::zeros(),
                p: Vector4::new(1.0, 0.0, 0.0, 0.0),
                rdot: Vector3::zeros(),
                omega_local: Vector3::new(0.5, 2.0, -1.0),
                z: vec![0.0; n],
                zdot: vec![0.0; n],
            }],
        )
        .unwrap();
    // consistent initial deformation rate: project onto the null space of the condition rows
    let d = sys.constraint_jacobian(0.0, &st.q).unwrap().to_dense();
    let dz = DMatrix::from_fn(6, n, |i, j| d[(i, 6 + j)]);
    let x = DVector::from_vec(raw);
    let y = &x - dz.transpose() * (&dz * dz.transpose()).lu().solve(&(&dz * &x)).unwrap();
    for i in 0..n {
        st.v[6 + i] = y[i];
    }
    let mut phi = vec![0.0; 6];
    sys.constraint_residual(0.0, &st.q, &mut phi).unwrap();
    assert!(
        phi.iter().all(|p| p.abs() < 1e-12),
        "initial J' not principal: {phi:?}"
    );
    let e0 = sys.kinetic_energy(&st).unwrap() + sys.potential_energy(&st);
    let mut worst = 0.0f64;
    let sol = DormandPrince::new(1e-10, 1e-12)
        .integrate(&sys, st, 0.2, |x| {
            sys.constraint_residual(x.t, &x.q, &mut phi).unwrap();
            worst = worst.max(phi.iter().fold(0.0, |a: f64, b| a.max(b.abs())));
        })
        .unwrap();
    let e1 = sys.kinetic_energy(&sol.state).unwrap() + sys.potential_energy(&sol.state);
    assert!(worst < 1e-8, "principal-axis residual {worst}");
    assert!((e1 - e0).abs() < 1e-7 * e0.abs());
    let z1 = &sys.flex_state(&sol.state, 0).z;
    assert!(z1.iter().map(|x| x.abs()).fold(0.0, f64::max) > 1e-4);
}
