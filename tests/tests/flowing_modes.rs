//! Property tests over random string meshes: mode-shape invariants (Ribaric (4.7)) and the link
//! between flowing's FE-consistent derivative operators and fe-model's string element.
#![allow(clippy::needless_range_loop)] // index loops mirror the matrix equations

use faer::Mat;
use fe_model::MassKind;
use flowing::derivative::{MassKind as OpMass, line_fe_matrices};
use flowing::{
    AxialMotion, DerivativeMethod, End, FlowGrid, FlowingString, StringConfig, StringMesh, Topology,
};
use proptest::prelude::*;

fn random_grid(gaps: &[f64]) -> FlowGrid {
    // Interior nodes at the partial sums of the gaps; fixed ends at 0 and the total.
    let mut x = 0.0;
    let mut pos = Vec::new();
    for g in &gaps[..gaps.len() - 1] {
        x += g;
        pos.push(x);
    }
    let b = x + gaps[gaps.len() - 1];
    FlowGrid::new(
        pos,
        Topology::Open {
            start: End::Zero(0.0),
            end: End::Zero(b),
        },
    )
    .unwrap()
}

fn max_abs(a: &Mat<f64>) -> f64 {
    let mut m: f64 = 0.0;
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            m = m.max(a[(i, j)].abs());
        }
    }
    m
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    // Reference: invariants of mass-normalised modes (Ribaric (4.7)): ΨᵀMΨ = I, ΨᵀKΨ = Λ
    // (diagonal, ascending, positive), and fe-model's sign convention (largest entry positive).
    #[test]
    fn mode_shape_invariants_on_random_meshes(
        gaps in proptest::collection::vec(0.2f64..1.0, 6..30),
        consistent in any::<bool>(),
        tension in 10.0f64..2000.0,
    ) {
        let p = StringConfig { tension, ..StringConfig::default() };
        let grid = random_grid(&gaps);
        let n = grid.len();
        let mesh = StringMesh::new(p, grid, if consistent { MassKind::Consistent } else { MassKind::Lumped }).unwrap();
        let k = n.min(8);
        let b = mesh.modes(k).unwrap();
        let mm = b.psi.transpose() * &mesh.mass * &b.psi;
        let kk = b.psi.transpose() * &mesh.stiffness * &b.psi;
        let lmax = b.lambda[k - 1];
        for i in 0..k {
            for j in 0..k {
                let id = if i == j { 1.0 } else { 0.0 };
                prop_assert!((mm[(i, j)] - id).abs() < 1e-9);
                let l = if i == j { b.lambda[i] } else { 0.0 };
                prop_assert!((kk[(i, j)] - l).abs() < 1e-9 * lmax);
            }
            prop_assert!(b.lambda[i] > 0.0);
            if i > 0 { prop_assert!(b.lambda[i] >= b.lambda[i - 1]); }
            let col: Vec<f64> = (0..n).map(|r| b.psi[(r, i)]).collect();
            let big = col.iter().cloned().fold(0.0f64, |a, x| a.max(x.abs()));
            let first = col.iter().find(|x| x.abs() >= big * (1.0 - 1e-8)).unwrap();
            prop_assert!(*first > 0.0);
        }
    }

    // Reference: the FE-consistent operator is built from the same element matrices as fe-model's
    // string element: M = μ M₁, K = T K₁ on any mesh; hence ΨᵀMΨ_,x is skew and
    // ΨᵀMΨ_,xx = −Λ/c² (no false instability, notes §2.1).
    #[test]
    fn consistent_operator_matches_fe_model_string(
        gaps in proptest::collection::vec(0.2f64..1.0, 6..30),
        consistent in any::<bool>(),
    ) {
        let p = StringConfig::default();
        let grid = random_grid(&gaps);
        let (fe_mass, op_mass) = if consistent { (MassKind::Consistent, OpMass::Consistent) } else { (MassKind::Lumped, OpMass::Lumped) };
        let mesh = StringMesh::new(p, grid.clone(), fe_mass).unwrap();
        let (m1, _, k1) = line_fe_matrices(&grid, op_mass);
        let dm = &mesh.mass - &m1 * faer::Scale(p.mu());
        let dk = &mesh.stiffness - &k1 * faer::Scale(p.tension);
        prop_assert!(max_abs(&dm) < 1e-12 * max_abs(&mesh.mass));
        prop_assert!(max_abs(&dk) < 1e-12 * max_abs(&mesh.stiffness));
        let k = grid.len().min(8);
        let s = FlowingString::new(&mesh.mass_sys(), mesh.modes(k).unwrap(), &[mesh.flow_line()],
            DerivativeMethod::Consistent(op_mass), AxialMotion::Constant { speed: 5.0 }).unwrap();
        let c2 = p.wave_speed().powi(2);
        for i in 0..k {
            for j in 0..k {
                prop_assert!((s.m_x[(i, j)] + s.m_x[(j, i)]).abs() < 1e-8 * (1.0 + s.m_x[(i, j)].abs()));
                let e = if i == j { -s.basis.lambda[i] / c2 } else { 0.0 };
                prop_assert!((s.m_xx[(i, j)] - e).abs() < 1e-8 * (1.0 + s.basis.lambda[k - 1] / c2));
            }
        }
    }
}
