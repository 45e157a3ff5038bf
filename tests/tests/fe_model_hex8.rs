//! fe-model: 8-node hexahedron validation (patch test, rigid modes, cantilever vs beam theory,
//! near-incompressibility, prestress).

use faer::Mat;
use faer::linalg::solvers::Solve;
use fe_model::element::{Elastic, Hex8Integration};
use fe_model::generate::hex_block;
use fe_model::{DofSplit, MassKind, dense_modes};

const STEEL: Elastic = Elastic {
    young: 210e9,
    poisson: 0.3,
    density: 7850.0,
};

/// Solve K_ff u_f = f_f − K_fc u_c for prescribed u_c (sparse Cholesky), return full u.
fn solve_static(
    k: &faer::sparse::SparseColMat<usize, f64>, fixed: &[usize], u_fixed: &[f64], f: &[f64],
) -> Vec<f64> {
    let n = k.nrows();
    let p = DofSplit::fixed(n, fixed).unwrap();
    let kff = p.block(k.as_ref(), false, false).unwrap();
    let kfc = p.block(k.as_ref(), false, true).unwrap();
    // u_fixed is given in the order of `fixed`; map to the sorted selected order
    let mut ucs = Mat::zeros(p.selected().len(), 1);
    for (d, v) in fixed.iter().zip(u_fixed) {
        let i = p.selected().binary_search(d).unwrap();
        ucs[(i, 0)] = *v;
    }
    let mut rhs = Mat::from_fn(p.rest().len(), 1, |i, _| f[p.rest()[i]]);
    rhs -= &kfc * &ucs;
    let llt = kff.sp_cholesky(faer::Side::Lower).unwrap();
    let uf = llt.solve(&rhs);
    let mut u = vec![0.0; n];
    for (i, &d) in p.rest().iter().enumerate() {
        u[d] = uf[(i, 0)];
    }
    for (i, &d) in p.selected().iter().enumerate() {
        u[d] = ucs[(i, 0)];
    }
    u
}

/// Patch test (MacNeal & Harder 1985 style): a distorted 3×3×3 patch with a linear
/// displacement field prescribed on its boundary reproduces that field exactly in the interior
/// (both integration rules).
#[test]
fn patch_test_reproduces_linear_field() {
    for integ in [Hex8Integration::Full, Hex8Integration::SelectiveReduced] {
        let model = hex_block([1.0, 1.0, 1.0], [3, 3, 3], STEEL, integ, None, |p| {
            // distort interior nodes
            let s = |v: f64| (v * 3.0 * std::f64::consts::PI).sin();
            let d = 0.06 * s(p[0]) * s(p[1]) * s(p[2]);
            [p[0] + d, p[1] - 0.7 * d, p[2] + 0.4 * d]
        })
        .unwrap();
        let k = model.stiffness().unwrap();
        let lin = |x: [f64; 3]| {
            [
                1e-3 * (1.0 + 2.0 * x[0] - x[1] + 0.5 * x[2]),
                1e-3 * (-0.5 + 0.3 * x[0] + 1.5 * x[1] - x[2]),
                1e-3 * (0.2 - x[0] + 0.7 * x[1] + 0.9 * x[2]),
            ]
        };
        let mut fixed = Vec::new();
        let mut uc = Vec::new();
        for set in ["x0", "x1", "y0", "y1", "z0", "z1"] {
            for &n in model.mesh.node_set(set).unwrap() {
                for d in 0..3 {
                    let dof = model.mesh.dof(n, d);
                    if !fixed.contains(&dof) {
                        fixed.push(dof);
                        uc.push(lin(model.mesh.nodes[n])[d]);
                    }
                }
            }
        }
        let f = vec![0.0; model.n_dofs()];
        let u = solve_static(&k, &fixed, &uc, &f);
        for (n, x) in model.mesh.nodes.iter().enumerate() {
            let e = lin(*x);
            for d in 0..3 {
                assert!(
                    (u[3 * n + d] - e[d]).abs() < 1e-12,
                    "{integ:?}: node {n} dof {d}"
                );
            }
        }
    }
}

/// A free block has exactly six zero-energy modes (no spurious hourglass modes), for both
/// integration rules and a distorted mesh.
#[test]
fn free_block_has_six_rigid_modes() {
    for integ in [Hex8Integration::Full, Hex8Integration::SelectiveReduced] {
        let model = hex_block([2.0, 1.0, 0.5], [3, 2, 2], STEEL, integ, None, |p| {
            [p[0] + 0.1 * p[1] * p[2], p[1] + 0.05 * p[0], p[2]]
        })
        .unwrap();
        let (k, m) = model.k_and_m(MassKind::Consistent, false).unwrap();
        let modes =
            dense_modes(k.to_dense().as_ref(), m.to_dense().as_ref(), model.n_dofs()).unwrap();
        let lmax = *modes.values.last().unwrap();
        let zero = modes
            .values
            .iter()
            .filter(|l| l.abs() < 1e-9 * lmax)
            .count();
        assert_eq!(zero, 6, "{integ:?}: {:?}", &modes.values[..8]);
        // total mass = ρ V (V = 1 m³ undistorted) for both mass kinds (rigid translation)
        let straight = hex_block([2.0, 1.0, 0.5], [3, 2, 2], STEEL, integ, None, |p| p).unwrap();
        for kind in [MassKind::Consistent, MassKind::Lumped] {
            let m = straight.mass(kind).unwrap().to_dense();
            let ux = Mat::from_fn(model.n_dofs(), 1, |i, _| if i % 3 == 0 { 1.0 } else { 0.0 });
            let mass = (ux.transpose() * &m * &ux)[(0, 0)];
            assert!((mass - 7850.0).abs() < 1e-9 * 7850.0);
        }
    }
}

/// Cantilever of hexahedra, L = 10, b = h = 1, end load P: tip deflection converges to
/// Timoshenko beam theory δ = PL³/(3EI) + PL/(κGA), κ = 5/6 (Timoshenko & Goodier).
#[test]
fn cantilever_tip_deflection_converges_to_beam_theory() {
    let (l, b, h, p) = (10.0, 1.0, 1.0, 1.0e6);
    let mat = Elastic {
        young: 200e9,
        poisson: 0.0,
        density: 0.0,
    };
    let ei = mat.young * b * h * h * h / 12.0;
    let g = mat.young / 2.0;
    let exact = p * l * l * l / (3.0 * ei) + p * l / (5.0 / 6.0 * g * b * h);
    let mut prev = f64::INFINITY;
    for (nx, nyz) in [(10usize, 1usize), (20, 2), (40, 4)] {
        let model = hex_block(
            [l, b, h],
            [nx, nyz, nyz],
            mat,
            Hex8Integration::Full,
            None,
            |p| p,
        )
        .unwrap();
        let k = model.stiffness().unwrap();
        let fixed = model.mesh.node_set_dofs("x0", None).unwrap();
        let tip = model.mesh.node_set("x1").unwrap();
        let mut f = vec![0.0; model.n_dofs()];
        // consistent nodal forces of a uniform shear traction on the end face
        let w = |i: usize| if i == 0 || i == nyz { 0.5 } else { 1.0 };
        let total: f64 = (0..=nyz)
            .flat_map(|j| (0..=nyz).map(move |k| w(j) * w(k)))
            .sum();
        for &n in tip {
            let x = model.mesh.nodes[n];
            let j = (x[1] / b * nyz as f64).round() as usize;
            let kk = (x[2] / h * nyz as f64).round() as usize;
            f[model.mesh.dof(n, 2)] = p * w(j) * w(kk) / total;
        }
        let u = solve_static(&k, &fixed, &vec![0.0; fixed.len()], &f);
        let tip_w: f64 =
            tip.iter().map(|&n| u[model.mesh.dof(n, 2)]).sum::<f64>() / tip.len() as f64;
        let err = (tip_w - exact).abs() / exact;
        assert!(err < prev, "no convergence at nx = {nx}: {err}");
        prev = err;
    }
    // linear hexahedra converge slowly in bending (shear locking): 3 % at 40×4×4
    assert!(prev < 0.04, "finest mesh error {prev}");
}

/// Nearly incompressible rubber (ν = 0.4999): selective reduced integration does not lock — a
/// clamped block under end shear deflects like the ν = 0.4999 beam solution — while full
/// integration is markedly too stiff (volumetric locking).
#[test]
fn selective_reduced_integration_avoids_volumetric_locking() {
    let rubber = Elastic {
        young: 6e6,
        poisson: 0.4999,
        density: 1100.0,
    };
    let (l, b, h, p): (f64, f64, f64, f64) = (4.0, 1.0, 1.0, 100.0);
    let ei = rubber.young * b * h.powi(3) / 12.0;
    let g = rubber.young / (2.0 * (1.0 + rubber.poisson));
    let exact = p * l.powi(3) / (3.0 * ei) + p * l / (5.0 / 6.0 * g * b * h);
    let mut tip = [0.0; 2];
    for (t, integ) in [Hex8Integration::Full, Hex8Integration::SelectiveReduced]
        .iter()
        .enumerate()
    {
        let model = hex_block([l, b, h], [16, 4, 4], rubber, *integ, None, |p| p).unwrap();
        let k = model.stiffness().unwrap();
        let fixed = model.mesh.node_set_dofs("x0", None).unwrap();
        let nodes = model.mesh.node_set("x1").unwrap();
        let mut f = vec![0.0; model.n_dofs()];
        for &n in nodes {
            f[model.mesh.dof(n, 2)] = p / nodes.len() as f64;
        }
        let u = solve_static(&k, &fixed, &vec![0.0; fixed.len()], &f);
        tip[t] = nodes.iter().map(|&n| u[model.mesh.dof(n, 2)]).sum::<f64>() / nodes.len() as f64;
    }
    let (full, sri) = (tip[0] / exact, tip[1] / exact);
    assert!(sri > 0.9 && sri < 1.1, "SRI tip / theory = {sri}");
    assert!(
        full < 0.5,
        "full integration should lock: tip / theory = {full}"
    );
}

/// Geometric stiffness of a uniaxial prestress: a thin hex bar under σ_xx = T/A with its end
/// faces fixed vibrates like a tensioned string/beam,
/// f_n = n/(2L) √(T/ρA) √(1 + (nπ)² EI/(T L²)) (Rao §11.5).
#[test]
fn prestressed_hex_bar_matches_tensioned_beam() {
    let (l, a): (f64, f64) = (1.0, 0.01);
    let mat = Elastic {
        young: 1e7,
        poisson: 0.0,
        density: 1000.0,
    };
    let t = 2000.0;
    let sigma = t / (a * a);
    let pre = [[sigma, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]];
    let model = hex_block(
        [l, a, a],
        [60, 1, 1],
        mat,
        Hex8Integration::Full,
        Some(pre),
        |p| p,
    )
    .unwrap();
    let (k, m) = model.k_and_m(MassKind::Consistent, true).unwrap();
    let mut fixed = Vec::new();
    for set in ["x0", "x1"] {
        fixed.extend(model.mesh.node_set_dofs(set, Some(&[1, 2])).unwrap());
    }
    // axial DOFs fixed at both ends: the prestress also stiffens the axial mode (K_G acts on
    // all three displacement components), which then lies above the first bending pair
    for set in ["x0", "x1"] {
        fixed.extend(model.mesh.node_set_dofs(set, Some(&[0])).unwrap());
    }
    let p = DofSplit::fixed(model.n_dofs(), &fixed).unwrap();
    let kff = p.dense_block(k.to_dense().as_ref(), false, false).unwrap();
    let mff = p.dense_block(m.to_dense().as_ref(), false, false).unwrap();
    let modes = dense_modes(kff.as_ref(), mff.as_ref(), 2).unwrap();
    let rho_a = mat.density * a * a;
    let ei = mat.young * a.powi(4) / 12.0;
    let f1 = 1.0 / (2.0 * l)
        * (t / rho_a).sqrt()
        * (1.0 + std::f64::consts::PI.powi(2) * ei / (t * l * l)).sqrt();
    // first two modes: the y and z bending pair (square section); the clamped-end correction
    // ≈ 2√(EI/T)/L = 0.4 % is inside the tolerance
    for i in 0..2 {
        let rel = (modes.frequencies_hz[i] - f1).abs() / f1;
        assert!(
            rel < 5e-3,
            "mode {i}: {} Hz vs {f1} Hz",
            modes.frequencies_hz[i]
        );
    }
}
