//! Belt element meshes (Kerkkänen §3.1–3.3): the free-belt static closure to a circle (§3.3,
//! Figs 3.4/3.5), a belt hoop pressed onto a pulley by its own tension (penalty contact of
//! §3.2 against a one-dimensional analytical solution), and the exactness of the contact
//! tangent inside an `AncfSystem`.

use ancf::belt::{belt_loop, coordinates_on_belt_path, coordinates_on_path, kerkkanen_path};
use ancf::statics::{AncfStaticOptions, solve_static, solve_static_with};
use ancf::system::MeshForce;
use ancf::{AncfElement, AncfSystem, Material, PulleyContact, Section};
use contact::{CreepRate, Disk, Frictionless, GaussRule, LineContact, LinearPenalty};
use mbd_core::SecondOrderSystem;
use nalgebra::{Point2, Vector2};

fn belt_material() -> (Material, Section) {
    (
        Material::new(1e8, 0.3, 1036.0).unwrap(),
        Section::rectangle(0.01, 0.01).unwrap(),
    )
}

// Kerkkänen §3.3 (V9 of the seed note): a free belt of 10 elements (length 1.276 m) released
// from the two-pulley shape converges by Newton–Raphson to a circle of radius L/(2π) =
// 0.20308 m. Supports: node A fixed, node B (opposite) vertically fixed.
#[test]
fn free_belt_closes_to_a_circle() {
    let (mat, sec) = belt_material();
    let mesh = belt_loop(10, 1.276, mat, sec, 1.0, 0.01, 5).unwrap();
    let path = kerkkanen_path();
    let q0 = coordinates_on_belt_path(&mesh, &path);
    let fixed = [
        mesh.node_dof(0, 0),
        mesh.node_dof(0, 1),
        mesh.node_dof(5, 1),
    ];
    let opts = AncfStaticOptions {
        increments: 1,
        max_iterations: 200,
        tolerance: 1e-10,
        line_search: true,
    };
    let sol = solve_static(&mesh, &q0, &fixed, &vec![0.0; mesh.n_dof()], &opts).expect("closure");
    let pts: Vec<[f64; 2]> = (0..mesh.elements().len())
        .flat_map(|i| (0..8).map(move |k| (i, k)))
        .map(|(i, k)| mesh.position(&sol.q, i, mesh.elements()[i].length() * k as f64 / 8.0, 0.0))
        .collect();
    let c = pts
        .iter()
        .fold([0.0, 0.0], |a, p| [a[0] + p[0], a[1] + p[1]]);
    let c = [c[0] / pts.len() as f64, c[1] / pts.len() as f64];
    let radii: Vec<f64> = pts
        .iter()
        .map(|p| ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2)).sqrt())
        .collect();
    let target = 1.276 / (2.0 * std::f64::consts::PI);
    for r in &radii {
        assert!(
            (r - target).abs() < 0.005 * target,
            "radius {r} vs {target}"
        );
    }
    let (rmin, rmax) = radii
        .iter()
        .fold((f64::MAX, 0.0f64), |(a, b), r| (a.min(*r), b.max(*r)));
    assert!(
        (rmax - rmin) / target < 0.005,
        "radius variation {}",
        (rmax - rmin) / target
    );
    assert!(sol.iterations[0] > 1);
}

/// Uniform equilibrium of a hoop of unstretched length L0 on a pulley of radius R (bending
/// neglected): Π(ρ) = L0 \[EA/8 (λ² − 1)² + k (R − ρ)²/2\], λ = 2πρ/L0 ⇒ solve Π'(ρ) = 0.
fn hoop_penetration(ea: f64, k: f64, r: f64, l0: f64) -> f64 {
    let c = 2.0 * std::f64::consts::PI / l0;
    let mut rho = r;
    for _ in 0..100 {
        let lam = c * rho;
        let g = ea / 2.0 * (lam * lam - 1.0) * lam * c - k * (r - rho);
        let dg = ea / 2.0 * (3.0 * lam * lam - 1.0) * c * c + k;
        rho -= g / dg;
    }
    r - rho
}

// Penalty contact of Kerkkänen (3.20)–(3.22), (3.27): a closed belt 2 % shorter than the
// pulley circumference squeezes onto it; the FE penetration matches the hoop solution (bending
// of α₂EI is < 0.1 % of the pressure here).
#[test]
fn belt_hoop_on_pulley_matches_analytical_penetration() {
    let (mat, sec) = belt_material();
    let r = 0.08125;
    let l0 = 0.98 * 2.0 * std::f64::consts::PI * r;
    let n = 16;
    let mesh = belt_loop(n, l0, mat, sec, 1.0, 0.01, 5).unwrap();
    let circle = |s: f64| {
        let a = std::f64::consts::FRAC_PI_2 + s / r;
        ([r * a.cos(), r * a.sin()], [-a.sin(), a.cos()])
    };
    let q0 = coordinates_on_path(&mesh, 2.0 * std::f64::consts::PI * r, circle);
    let k = 1e7;
    let pc = PulleyContact {
        contact: LineContact {
            surface: Disk::fixed(Point2::origin(), r),
            normal: LinearPenalty {
                stiffness: k,
                damping: 0.0,
            },
            friction: Frictionless,
            rule: GaussRule::new(5),
        },
    };
    // node 0 sits at the top: fixing its x removes the free rotation about the pulley
    let fixed = [mesh.node_dof(0, 0)];
    let opts = AncfStaticOptions {
        increments: 1,
        max_iterations: 100,
        tolerance: 1e-12,
        line_search: true,
    };
    let extra: [&dyn MeshForce<_>; 1] = [&pc];
    let sol = solve_static_with(&mesh, &q0, &fixed, &vec![0.0; mesh.n_dof()], &extra, &opts)
        .expect("hoop equilibrium");
    let dist = pc.distribution(&mesh, &sol.q, &vec![0.0; mesh.n_dof()]);
    let (recs, torque) = (dist.records, dist.torque);
    assert_eq!(recs.len(), 5 * n, "every quadrature point in contact");
    let mean = recs.iter().map(|r| r.record.penetration).sum::<f64>() / recs.len() as f64;
    let exact = hoop_penetration(mat.young * sec.area, k, r, l0);
    assert!(
        (mean - exact).abs() < 0.01 * exact,
        "penetration {mean:e} vs hoop {exact:e}"
    );
    for rec in &recs {
        assert!((rec.record.penetration - exact).abs() < 0.03 * exact);
    }
    assert!(torque.abs() < 1e-9, "frictionless contact gives no torque");
}

// The contact tangent assembled by `PulleyContact` inside `AncfSystem::force_tangent` equals
// −∂f/∂q and −∂f/∂v (central differences), with friction in its viscous branch and damping.
#[test]
fn system_tangent_with_contact_matches_finite_differences() {
    let (mat, sec) = belt_material();
    let r = 0.08125;
    let n = 8;
    let l0 = 0.99 * 2.0 * std::f64::consts::PI * r;
    let mesh = belt_loop(n, l0, mat, sec, 1.0, 0.01, 5).unwrap();
    let circle = |s: f64| {
        let a = s / (r - 1e-4);
        (
            [(r - 1e-4) * a.cos(), (r - 1e-4) * a.sin()],
            [-a.sin(), a.cos()],
        )
    };
    let mut q = coordinates_on_path(&mesh, 2.0 * std::f64::consts::PI * (r - 1e-4), circle);
    for (i, x) in q.iter_mut().enumerate() {
        *x += 1e-5 * (i as f64 * 0.37).sin();
    }
    let v: Vec<f64> = (0..q.len())
        .map(|i| 0.01 * (i as f64 * 0.91).cos())
        .collect();
    let pc = PulleyContact {
        contact: LineContact {
            surface: Disk {
                center: Point2::origin(),
                radius: r,
                velocity: Vector2::zeros(),
                omega: 0.3,
            },
            normal: LinearPenalty {
                stiffness: 1e7,
                damping: 10.0,
            },
            friction: CreepRate {
                mu: 1.2,
                creep: 1e3,
            },
            rule: GaussRule::new(7),
        },
    };
    let sys = AncfSystem::new(mesh).with_force(Box::new(pc));
    let nd = sys.n_q();
    let tg = sys
        .force_tangent(0.0, &q, &v, &mut mbd_core::Workspace::new())
        .unwrap()
        .unwrap();
    let (k, c) = (tg.stiffness.to_dense(), tg.damping.to_dense());
    let kmax = (0..nd)
        .flat_map(|i| (0..nd).map(move |j| (i, j)))
        .map(|(i, j)| k[(i, j)].abs())
        .fold(0.0, f64::max);
    let cmax = (0..nd)
        .flat_map(|i| (0..nd).map(move |j| (i, j)))
        .map(|(i, j)| c[(i, j)].abs())
        .fold(0.0, f64::max);
    let mut fp = vec![0.0; nd];
    let mut fm = vec![0.0; nd];
    for j in 0..nd {
        let h = 1e-8;
        let (mut qp, mut qm) = (q.clone(), q.clone());
        qp[j] += h;
        qm[j] -= h;
        sys.forces(0.0, &qp, &v, &mut fp, &mut mbd_core::Workspace::new())
            .unwrap();
        sys.forces(0.0, &qm, &v, &mut fm, &mut mbd_core::Workspace::new())
            .unwrap();
        for i in 0..nd {
            let fd = -(fp[i] - fm[i]) / (2.0 * h);
            assert!(
                (fd - k[(i, j)]).abs() < 1e-5 * kmax,
                "K[{i},{j}] {fd} vs {}",
                k[(i, j)]
            );
        }
        let hv = 1e-7;
        let (mut vp, mut vm) = (v.clone(), v.clone());
        vp[j] += hv;
        vm[j] -= hv;
        sys.forces(0.0, &q, &vp, &mut fp, &mut mbd_core::Workspace::new())
            .unwrap();
        sys.forces(0.0, &q, &vm, &mut fm, &mut mbd_core::Workspace::new())
            .unwrap();
        for i in 0..nd {
            let fd = -(fp[i] - fm[i]) / (2.0 * hv);
            assert!(
                (fd - c[(i, j)]).abs() < 1e-5 * cmax,
                "C[{i},{j}] {fd} vs {}",
                c[(i, j)]
            );
        }
    }
    assert!(cmax > 0.0);
}

// Kerkkänen Table 3.1 belt (1.2727 m, E = 1e8 Pa, 20 elements) mounted on the two pulleys
// (path 1.276273 m) with frictionless penalty contact (k_p = 1e7 N/m²): the static pretension.
// References: global equilibrium of each pulley (the resultant contact force equals the pull of
// the two straight spans, 2N, with N = EA/2 (λ² − 1) λ from the span strain), and the seed
// note's estimate N ≈ 26.5 N, d ≈ 0.033 mm (§7.6).
#[test]
fn belt_pretension_on_two_pulleys() {
    let (mat, sec) = belt_material();
    let n = 20;
    let mesh = belt_loop(n, 1.2727, mat, sec, 1.0, 0.01, 5).unwrap();
    let path = kerkkanen_path();
    let q0 = coordinates_on_belt_path(&mesh, &path);
    let k = 1e7;
    let mk = |c: [f64; 2]| PulleyContact {
        contact: LineContact {
            surface: Disk::fixed(Point2::from(c), path.pulleys()[0].radius),
            normal: LinearPenalty {
                stiffness: k,
                damping: 10.0,
            },
            friction: Frictionless,
            rule: GaussRule::new(5),
        },
    };
    let (p1, p2) = (mk(path.pulleys()[0].center), mk(path.pulleys()[1].center));
    // node 0 is at the top of the left pulley (where the path leaves it), travelling along +x:
    // fix its x
    let fixed = [mesh.node_dof(0, 0)];
    let opts = AncfStaticOptions {
        increments: 1,
        max_iterations: 100,
        tolerance: 1e-11,
        line_search: true,
    };
    let extra: [&dyn MeshForce<_>; 2] = [&p1, &p2];
    let sol = solve_static_with(&mesh, &q0, &fixed, &vec![0.0; mesh.n_dof()], &extra, &opts)
        .expect("pretension equilibrium");
    let zero = vec![0.0; mesh.n_dof()];
    let d1 = p1.distribution(&mesh, &sol.q, &zero);
    let d2 = p2.distribution(&mesh, &sol.q, &zero);
    let pmax = d1
        .records
        .iter()
        .chain(&d2.records)
        .map(|r| r.record.penetration)
        .fold(0.0, f64::max);
    // span strain: the middle element of the upper span (node 2 → 3 lies on it)
    let a = mesh.node_position(&sol.q, 2);
    let b = mesh.node_position(&sol.q, 3);
    let lam = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt() / (1.2727 / n as f64);
    let ea = mat.young * sec.area;
    let tension = ea / 2.0 * (lam * lam - 1.0) * lam;
    // the belt pulls the right pulley towards −x with 2N, the left one towards +x
    assert!(
        (d2.reaction[0] + 2.0 * tension).abs() < 0.02 * tension,
        "{:?} vs 2N = {}",
        d2.reaction,
        2.0 * tension
    );
    assert!(
        (d1.reaction[0] - 2.0 * tension).abs() < 0.02 * tension,
        "{:?}",
        d1.reaction
    );
    assert!(d1.reaction[1].abs() < 0.02 * tension && d1.torque.abs() < 1e-9);
    assert!(
        (tension - 26.5).abs() < 0.05 * 26.5,
        "pretension {tension} N (note: ≈ 26.5 N)"
    );
    // mean penetration ≈ T/(kR) ≈ 0.033 mm for a uniform pressure (4 elements per half pulley
    // make the discrete pressure wavy: the peak is about twice the mean)
    let all: Vec<f64> = d1
        .records
        .iter()
        .chain(&d2.records)
        .map(|r| r.record.penetration)
        .collect();
    let mean = all.iter().sum::<f64>() / all.len() as f64;
    let uniform = tension / (k * path.pulleys()[0].radius);
    assert!(
        (mean - uniform).abs() < 0.25 * uniform,
        "mean penetration {mean} m vs T/(kR) = {uniform} m"
    );
    assert!(pmax < 3.0 * uniform, "peak penetration {pmax} m");
}

// Dynamics through mbd-core's generalized-α with distributed contact and creep-rate friction
// (Kerkkänen (3.20)–(3.27)): a pre-tensioned belt hoop on a pulley spinning at ω is dragged
// along until it co-rotates (no load ⇒ no creep): the belt's mean angular velocity → ω.
#[test]
fn hoop_is_dragged_to_pulley_speed_by_friction() {
    use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha, State};
    let (mat, sec) = belt_material();
    let r = 0.08125;
    let l0 = 0.99 * 2.0 * std::f64::consts::PI * r;
    let n = 12;
    let mesh = belt_loop(n, l0, mat, sec, 1.0, 0.01, 5).unwrap();
    let circle = |s: f64| {
        let a = s / r;
        ([r * a.cos(), r * a.sin()], [-a.sin(), a.cos()])
    };
    let q0 = coordinates_on_path(&mesh, 2.0 * std::f64::consts::PI * r, circle);
    let omega = 5.0;
    let pc = PulleyContact {
        contact: LineContact {
            surface: Disk {
                center: Point2::origin(),
                radius: r,
                velocity: Vector2::zeros(),
                omega,
            },
            normal: LinearPenalty {
                stiffness: 1e7,
                damping: 10.0,
            },
            friction: CreepRate {
                mu: 1.2,
                creep: 100.0,
            },
            rule: GaussRule::new(5),
        },
    };
    let sys = AncfSystem::new(mesh).with_force(Box::new(pc));
    let ga = GeneralizedAlpha::new(AlphaConfig {
        rho_inf: 0.5,
        h: 1e-4,
        ..Default::default()
    });
    let v0 = vec![0.0; q0.len()];
    let sol = ga
        .integrate(&sys, State::new(0.0, q0, v0), 0.02, |_| {})
        .expect("integration");
    let m = sys.mesh();
    let w_belt: f64 = (0..n)
        .map(|i| {
            let k = m.node_dof(i, 0);
            let (p, v) = (
                [sol.state.q[k], sol.state.q[k + 1]],
                [sol.state.v[k], sol.state.v[k + 1]],
            );
            (p[0] * v[1] - p[1] * v[0]) / (p[0] * p[0] + p[1] * p[1])
        })
        .sum::<f64>()
        / n as f64;
    assert!(
        (w_belt - omega).abs() < 0.01 * omega,
        "belt angular velocity {w_belt} rad/s vs ω = {omega}"
    );
}
