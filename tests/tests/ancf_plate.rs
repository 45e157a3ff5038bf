//! Validation of the ANCF thin-plate element (Kerkkänen §4.3): shape functions against the
//! reading note's closed forms, rigid-motion invariants, exact kinetic energy, a uniform
//! membrane state and the linear cantilever strip against beam theory.

use ancf::Material;
use ancf::plate::{PLATE_NDOF, PlateDynamics, PlateMesh, PlateShape, ThinPlate};
use contact::GaussRule;
use faer::Mat;
use faer::prelude::Solve;
use mbd_core::SecondOrderSystem;
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha, State};
use nalgebra::{Rotation3, Vector3};

fn steel(nu: f64) -> Material {
    Material::new(2.1e11, nu, 7800.0).unwrap()
}

/// Flat reference coordinates of one `a × b` element (nodes A, B, C, D).
fn flat(a: f64, b: f64) -> [f64; PLATE_NDOF] {
    let mut e = [0.0; PLATE_NDOF];
    for (n, (x, y)) in [(0.0, 0.0), (a, 0.0), (a, b), (0.0, b)].iter().enumerate() {
        e[9 * n] = *x;
        e[9 * n + 1] = *y;
        e[9 * n + 3] = 1.0;
        e[9 * n + 7] = 1.0;
    }
    e
}

/// Apply `r → R r + t`, `r_x → R r_x`, `r_y → R r_y` node by node.
fn rigid(e: &[f64], rot: &Rotation3<f64>, t: Vector3<f64>) -> Vec<f64> {
    let mut out = e.to_vec();
    for node in 0..e.len() / 9 {
        for kind in 0..3 {
            let o = 9 * node + 3 * kind;
            let v = rot * Vector3::new(e[o], e[o + 1], e[o + 2]);
            let v = if kind == 0 { v + t } else { v };
            out[o..o + 3].copy_from_slice(v.as_slice());
        }
    }
    out
}

/// A smooth, clearly non-rigid perturbation of the coordinates.
fn deformed(e: &[f64], amp: f64) -> Vec<f64> {
    e.iter()
        .enumerate()
        .map(|(i, v)| v + amp * ((1.3 * i as f64).sin() + 0.5 * (0.7 * i as f64).cos()))
        .collect()
}

// Reading note seed-001 §3.6: closed-form Dufva–Shabana shape functions (the element computes
// them by inverting the interpolation matrix: two independent routes).
#[test]
fn shape_functions_match_the_closed_forms_of_the_note() {
    let (a, b) = (0.7, 0.3);
    let sh = PlateShape::new(a, b).unwrap();
    for &(xi, eta) in &[
        (0.2, 0.9),
        (0.5, 0.5),
        (0.81, 0.13),
        (0.0, 0.37),
        (1.0, 0.64),
    ] {
        let s = sh.eval(xi * a, eta * b).s;
        let (x, y) = (xi, eta);
        let want = [
            -(x - 1.0) * (y - 1.0) * (2.0 * y * y - y + 2.0 * x * x - x - 1.0),
            -a * x * (x - 1.0).powi(2) * (y - 1.0),
            -b * y * (y - 1.0).powi(2) * (x - 1.0),
            x * (y - 1.0) * (2.0 * y * y - y + 2.0 * x * x - 3.0 * x),
            -a * x * x * (x - 1.0) * (y - 1.0),
            b * x * y * (y - 1.0).powi(2),
            -x * y * (2.0 * y * y - 3.0 * y + 2.0 * x * x - 3.0 * x + 1.0),
            a * x * x * y * (x - 1.0),
            b * x * y * y * (y - 1.0),
            y * (x - 1.0) * (2.0 * y * y - 3.0 * y + 2.0 * x * x - x),
            a * x * y * (x - 1.0).powi(2),
            -b * y * y * (y - 1.0) * (x - 1.0),
        ];
        for k in 0..12 {
            assert!(
                (s[k] - want[k]).abs() < 1e-12,
                "S{} at ({xi}, {eta}): {} vs {}",
                k + 1,
                s[k],
                want[k]
            );
        }
    }
}

// Invariant: any rigid motion gives zero strain energy and zero elastic forces, and the energy
// of a deformed state is objective (unchanged by a superposed rigid rotation).
#[test]
fn rigid_motion_is_strain_free_and_energy_is_objective() {
    let (a, b, h) = (0.4, 0.25, 0.01);
    let el = ThinPlate::new(a, b, h, steel(0.3), true, 5).unwrap();
    let rot = Rotation3::from_euler_angles(0.3, -1.1, 2.0);
    let t = Vector3::new(0.5, -2.0, 1.0);
    let e0 = flat(a, b);
    let moved = rigid(&e0, &rot, t);
    let eh = 2.1e11 * h;
    assert!(el.strain_energy(&moved) < 1e-20 * eh * a * b);
    let mut q = [0.0; PLATE_NDOF];
    el.elastic_forces(&moved, &mut q);
    let qmax = q.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(qmax < 1e-9 * eh, "rigid-motion forces {qmax} N");

    let d = deformed(&e0, 0.01);
    let u = el.strain_energy(&d);
    assert!(
        u > 1.0,
        "the perturbation must strain the element (U = {u} J)"
    );
    let ur = el.strain_energy(&rigid(&d, &rot, t));
    assert!((ur - u).abs() < 1e-10 * u, "objectivity: {ur} vs {u}");
}

// Invariant: the exact kinetic energy of rigid translation (½ m V²) and of rigid rotation about
// the z axis through the corner (½ ω² m (lx² + ly²)/3) from the constant mass matrix.
#[test]
fn constant_mass_matrix_gives_exact_rigid_kinetic_energy() {
    let (lx, ly, h) = (1.2, 0.3, 0.004);
    let (mesh, q0) = PlateMesh::rectangle(lx, ly, 3, 2, h, steel(0.3), true, 3).unwrap();
    let m = mesh.mass().unwrap().to_dense();
    let mass = 7800.0 * h * lx * ly;
    let ke = |v: &[f64]| {
        let vm = Mat::<f64>::from_fn(v.len(), 1, |i, _| v[i]);
        0.5 * (vm.transpose() * &m * &vm)[(0, 0)]
    };
    let vel = [0.3, -1.2, 2.0];
    let mut v = vec![0.0; q0.len()];
    for node in 0..mesh.n_nodes {
        v[9 * node..9 * node + 3].copy_from_slice(&vel);
    }
    let want = 0.5 * mass * (0.09 + 1.44 + 4.0);
    assert!((ke(&v) - want).abs() < 1e-12 * want);

    let w = 1.7;
    let mut v = vec![0.0; q0.len()];
    for node in 0..mesh.n_nodes {
        let (x, y) = (q0[9 * node], q0[9 * node + 1]);
        v[9 * node] = -w * y;
        v[9 * node + 1] = w * x;
        v[9 * node + 4] = w; // ṙ_x = ω ẑ × x̂
        v[9 * node + 6] = -w; // ṙ_y = ω ẑ × ŷ
    }
    let want = 0.5 * w * w * mass * (lx * lx + ly * ly) / 3.0;
    assert!((ke(&v) - want).abs() < 1e-12 * want, "{} vs {want}", ke(&v));
}

// Analytical: a uniform biaxial stretch has ε_xx = ½(λx² − 1), ε_yy = ½(λy² − 1), no curvature,
// and the plane-stress energy E h/(2(1 − ν²)) [(ε_xx + ε_yy)² − 2(1 − ν) ε_xx ε_yy] · area
// (Kerkkänen (4.16), standard form); the gradient coordinates are exact, so is the energy.
#[test]
fn uniform_biaxial_stretch_has_the_plane_stress_energy() {
    let (lx, ly, h, nu) = (0.8, 0.5, 0.002, 0.3);
    let (lamx, lamy) = (1.02, 0.995);
    for bending in [false, true] {
        let (mesh, q0) = PlateMesh::rectangle(lx, ly, 2, 3, h, steel(nu), bending, 4).unwrap();
        let mut q = q0.clone();
        for node in 0..mesh.n_nodes {
            q[9 * node] *= lamx;
            q[9 * node + 1] *= lamy;
            q[9 * node + 3] = lamx;
            q[9 * node + 7] = lamy;
        }
        let (ex, ey) = (0.5 * (lamx * lamx - 1.0), 0.5 * (lamy * lamy - 1.0));
        let want = 2.1e11 * h / (2.0 * (1.0 - nu * nu))
            * ((ex + ey).powi(2) - 2.0 * (1.0 - nu) * ex * ey)
            * lx
            * ly;
        let u = mesh.strain_energy(&q).unwrap();
        assert!(
            (u - want).abs() < 1e-10 * want,
            "bending {bending}: {u} vs {want}"
        );
    }
}

// Second formulation: the analytic tangent equals central differences of the elastic forces in
// a strongly deformed state.
#[test]
fn tangent_matches_finite_differences_of_the_forces() {
    let (a, b) = (0.3, 0.2);
    let el = ThinPlate::new(a, b, 0.01, steel(0.25), true, 4).unwrap();
    let e = deformed(&flat(a, b), 0.02);
    let mut q = [0.0; PLATE_NDOF];
    let mut k = Mat::<f64>::zeros(PLATE_NDOF, PLATE_NDOF);
    el.elastic_tangent(&e, &mut q, &mut k);
    let mut q2 = [0.0; PLATE_NDOF];
    el.elastic_forces(&e, &mut q2);
    let kmax = (0..PLATE_NDOF)
        .flat_map(|i| (0..PLATE_NDOF).map(move |j| (i, j)))
        .fold(0.0f64, |m, (i, j)| m.max(k[(i, j)].abs()));
    for i in 0..PLATE_NDOF {
        assert!((q[i] - q2[i]).abs() < 1e-9 * kmax);
    }
    let step = 1e-6;
    for j in 0..PLATE_NDOF {
        let (mut ep, mut em) = (e.clone(), e.clone());
        ep[j] += step;
        em[j] -= step;
        let (mut qp, mut qm) = ([0.0; PLATE_NDOF], [0.0; PLATE_NDOF]);
        el.elastic_forces(&ep, &mut qp);
        el.elastic_forces(&em, &mut qm);
        for i in 0..PLATE_NDOF {
            let fd = -(qp[i] - qm[i]) / (2.0 * step);
            assert!(
                (fd - k[(i, j)]).abs() < 1e-6 * kmax,
                "K[{i},{j}] = {} vs FD {fd}",
                k[(i, j)]
            );
        }
    }
}

// Analytical (Euler–Bernoulli): a clamped strip with ν = 0 under a uniform line load P at the
// free edge has the tip deflection P L³ / (3 E I), I = b h³ / 12; the incomplete cubic holds the
// exact cubic deflection, so the linearised plate reproduces it to round-off.
#[test]
fn linear_cantilever_strip_matches_beam_theory() {
    let (lx, ly, h, p) = (1.0, 0.1, 0.01, 10.0);
    let (nx, ny) = (4, 1);
    let (mesh, q0) = PlateMesh::rectangle(lx, ly, nx, ny, h, steel(0.0), true, 4).unwrap();
    let (f0, k) = mesh.elastic_tangent(&q0).unwrap();
    assert!(
        f0.iter().all(|v| v.abs() < 1e-6),
        "reference state must be stress-free"
    );
    let k = k.to_dense();
    let f = tip_edge_load(&mesh, nx, p, ly, 2);
    let free: Vec<usize> = (0..mesh.n_coords())
        .filter(|&i| (i / 9) % (nx + 1) != 0)
        .collect();
    let kff = Mat::<f64>::from_fn(free.len(), free.len(), |i, j| k[(free[i], free[j])]);
    let rhs = Mat::<f64>::from_fn(free.len(), 1, |i, _| f[free[i]]);
    let u = kff.partial_piv_lu().solve(&rhs);
    let tip: Vec<f64> = free
        .iter()
        .enumerate()
        .filter(|&(_, &g)| g % 9 == 2 && (g / 9) % (nx + 1) == nx)
        .map(|(i, _)| u[(i, 0)])
        .collect();
    assert_eq!(tip.len(), ny + 1);
    let ei = 2.1e11 * ly * h.powi(3) / 12.0;
    let want = p * lx.powi(3) / (3.0 * ei);
    for w in tip {
        assert!((w - want).abs() < 1e-8 * want, "tip {w} m vs {want} m");
    }
}

// Bad input never panics: typed errors naming the field.
#[test]
fn invalid_plate_input_is_rejected_with_the_field_named() {
    let e = ThinPlate::new(0.1, 0.1, -1.0, steel(0.3), true, 5).unwrap_err();
    assert!(e.to_string().contains("thickness"), "{e}");
    let e = ThinPlate::new(0.1, 0.1, 0.01, steel(0.3), true, 1).unwrap_err();
    assert!(e.to_string().contains("gauss"), "{e}");
    let e = PlateMesh::rectangle(1.0, 1.0, 0, 1, 0.01, steel(0.3), true, 3).unwrap_err();
    assert!(e.to_string().contains("elements"), "{e}");
    let (mesh, _) = PlateMesh::rectangle(1.0, 1.0, 1, 1, 0.01, steel(0.3), true, 3).unwrap();
    assert!(mesh.strain_energy(&[0.0; 5]).is_err());
}

/// Consistent uniform line load of total `p` \[N\] in direction `dir` on the edge `x = lx`.
fn tip_edge_load(mesh: &PlateMesh, nx: usize, p: f64, ly: f64, dir: usize) -> Vec<f64> {
    let mut f = vec![0.0; mesh.n_coords()];
    let rule = GaussRule::new(4);
    for cell in mesh.cells.iter().skip(nx - 1).step_by(nx) {
        let dofs = mesh.cell_dofs(cell);
        let (a, b) = (cell.plate.shape().a(), cell.plate.shape().b());
        for (eta, w) in rule.iter() {
            let s = cell.plate.shape().eval(a, eta * b).s;
            for kk in 0..12 {
                f[dofs[3 * kk + dir]] += p / ly * s[kk] * w * b;
            }
        }
    }
    f
}

// Analytical (Euler's elastica, Bisshopp & Drucker 1945; re-computed by shooting on
// EI θ'' + P cos θ = 0, θ(0) = 0, θ'(L) = 0): a thin clamped strip (ν = 0, nearly inextensible)
// under a dead tip load with P L² / EI = 2 has the tip displacements 0.493457 L across and
// 0.160642 L along the strip. This exercises the nonlinear curvature (4.18) at large rotation.
#[test]
fn large_deflection_cantilever_strip_follows_the_elastica() {
    let (lx, ly, h) = (1.0, 0.05, 0.005);
    let nx = 16;
    let (mesh, q0) = PlateMesh::rectangle(lx, ly, nx, 1, h, steel(0.0), true, 5).unwrap();
    let ei = 2.1e11 * ly * h.powi(3) / 12.0;
    let p = 2.0 * ei / (lx * lx);
    let load = tip_edge_load(&mesh, nx, p, ly, 2);
    let fixed: Vec<usize> = (0..mesh.n_coords())
        .filter(|&i| (i / 9) % (nx + 1) == 0)
        .collect();
    let opts = ancf::AncfStaticOptions {
        increments: 8,
        max_iterations: 40,
        tolerance: 1e-10,
        line_search: true,
    };
    let sol = ancf::plate::solve_plate_static(&mesh, &q0, &fixed, &load, &opts).unwrap();
    for node in [nx, 2 * nx + 1] {
        let (x, z) = (sol.q[9 * node], sol.q[9 * node + 2]);
        let (dv, dh) = (z / lx, 1.0 - x / lx);
        eprintln!("tip node {node}: across {dv:.6} along {dh:.6} (elastica 0.493457, 0.160642)");
        // 16 elements: 1.5e-5 L from the elastica (8 elements: 6e-4 L)
        assert!(
            (dv - 0.493457).abs() < 1e-4,
            "tip across {dv} (elastica 0.493457)"
        );
        assert!(
            (dh - 0.160642).abs() < 1e-4,
            "tip along {dh} (elastica 0.160642)"
        );
    }
}

// Analytical: a free plate in gravity falls as a rigid body, q(t) = q₀ + ½ g t² on the position
// coordinates with the slopes unchanged: the constant ANCF mass matrix maps the consistent
// gravity force to the uniform acceleration exactly (M e_g = Q_g), and generalized-α integrates
// a constant acceleration exactly.
#[test]
fn free_plate_falls_as_a_rigid_body_under_gravity() {
    let (mesh, q0) = PlateMesh::rectangle(0.6, 0.3, 2, 1, 0.004, steel(0.3), true, 3).unwrap();
    let g = [0.5, -1.0, -9.81];
    let sys = PlateDynamics::new(mesh, &q0, &[], g).unwrap();
    let cfg = AlphaConfig {
        h: 1e-3,
        rho_inf: 0.8,
        newton_atol: 1e-13,
        ..AlphaConfig::default()
    };
    let t = 0.05;
    let s0 = State::new(0.0, sys.free_coordinates(&q0), vec![0.0; sys.n_q()]);
    let sol = GeneralizedAlpha::new(cfg)
        .integrate(&sys, s0, t, |_| {})
        .unwrap();
    let q = sys.full_coordinates(&sol.state.q);
    for node in 0..q.len() / 9 {
        for c in 0..3 {
            let want = q0[9 * node + c] + 0.5 * g[c] * t * t;
            assert!((q[9 * node + c] - want).abs() < 1e-12, "node {node} r[{c}]");
            assert!((sol.state.v[9 * node + c] - g[c] * t).abs() < 1e-11);
            for k in 3..9 {
                assert!((q[9 * node + k] - q0[9 * node + k]).abs() < 1e-12);
            }
        }
    }
}

/// Clamped strip (ν = 0) of `nx` elements: dynamics with the nodes at x = 0 fixed.
fn clamped_strip(nx: usize) -> (PlateDynamics, Vec<f64>) {
    let (mesh, q0) = PlateMesh::rectangle(1.0, 0.1, nx, 1, 0.01, steel(0.0), true, 4).unwrap();
    let fixed: Vec<usize> = (0..mesh.n_coords())
        .filter(|&i| (i / 9) % (nx + 1) == 0)
        .collect();
    let sys = PlateDynamics::new(mesh, &q0, &fixed, [0.0; 3]).unwrap();
    (sys, q0)
}

// Analytical (Euler–Bernoulli): the first bending frequency of a clamped strip is
// ω₁ = 1.875104² √(EI/(ρA L⁴)); the plate's constant mass and analytic tangent at the
// reference state give it to the discretisation error (8 elements: 2e-5), and the mode
// released from rest returns to its initial shape after one period under generalized-α with
// ρ∞ = 1 (period error (ωh)²/12 = 2·10⁻⁵ at h = T/400).
#[test]
fn clamped_strip_vibrates_at_the_euler_bernoulli_frequency() {
    let (sys, q0) = clamped_strip(8);
    let qf = sys.free_coordinates(&q0);
    let v0 = vec![0.0; sys.n_q()];
    let m = sys.mass(0.0, &qf).unwrap().to_dense();
    let k = sys
        .force_tangent(0.0, &qf, &v0, &mut mbd_core::Workspace::new())
        .unwrap()
        .unwrap()
        .stiffness
        .to_dense();
    let modes = fe_model::eigen::dense::dense_modes(k.as_ref(), m.as_ref(), 3).unwrap();
    let ei: f64 = 2.1e11 * 0.1 * 1e-6 / 12.0;
    let rho_a = 7800.0 * 0.1 * 0.01;
    let w1 = 1.875104f64.powi(2) * (ei / rho_a).sqrt();
    let w = modes.values[0].sqrt();
    assert!((w - w1).abs() < 1e-4 * w1, "ω₁ = {w} vs {w1} rad/s");
    // release the mode (tip amplitude 1 mm: linear regime) and integrate one period
    let phi: Vec<f64> = (0..sys.n_q()).map(|i| modes.vectors[(i, 0)]).collect();
    let amp = 1e-3 / phi.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let q_start: Vec<f64> = qf.iter().zip(&phi).map(|(q, p)| q + amp * p).collect();
    let period = std::f64::consts::TAU / w;
    let cfg = AlphaConfig {
        h: period / 400.0,
        rho_inf: 1.0,
        newton_atol: 1e-14,
        ..AlphaConfig::default()
    };
    let s0 = State::new(0.0, q_start.clone(), v0);
    let sol = GeneralizedAlpha::new(cfg)
        .integrate(&sys, s0, period, |_| {})
        .unwrap();
    let err = sol
        .state
        .q
        .iter()
        .zip(&q_start)
        .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
    assert!(
        err < 1e-3 * 1e-3,
        "after one period: {err} m off (amplitude 1 mm)"
    );
}
