//! fe-model: 3D frame (Euler–Bernoulli and Timoshenko), point masses and springs.

use faer::Mat;
use faer::linalg::solvers::Solve;
use fe_model::element::{
    Element, Frame3d, Frame3dSection, MassKind, MatrixKind, PointMass, Spring,
};
use fe_model::{DofSplit, assemble, dense_modes};
use std::f64::consts::PI;

/// Straight 3D frame along `dir` with `n` elements; returns elements and DOF count.
fn frame(
    n: usize, l: f64, dir: [f64; 3], up: [f64; 3], s: Frame3dSection, axial: f64,
) -> (Vec<Box<dyn Element>>, usize) {
    let norm = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
    let p = |i: usize| {
        let t = l * i as f64 / n as f64 / norm;
        [dir[0] * t, dir[1] * t, dir[2] * t]
    };
    let mut els: Vec<Box<dyn Element>> = Vec::new();
    for e in 0..n {
        let mut dofs = [0usize; 12];
        for (k, d) in dofs.iter_mut().enumerate() {
            *d = 6 * e + k;
        }
        els.push(Box::new(
            Frame3d::new(dofs, p(e), p(e + 1), up, s, axial).unwrap(),
        ));
    }
    (els, 6 * (n + 1))
}

fn section() -> Frame3dSection {
    Frame3dSection {
        ea: 2e8,
        ei_y: 3.0e4,
        ei_z: 1.2e4,
        gj: 8.0e3,
        mass_per_length: 8.0,
        polar_inertia_per_length: 0.02,
        shear_y: None,
        shear_z: None,
    }
}

fn fixed_modes(
    els: &[Box<dyn Element>], n: usize, fixed: &[usize], count: usize,
) -> fe_model::Modes {
    let k = assemble(n, els, MatrixKind::Stiffness).unwrap().to_dense();
    let m = assemble(n, els, MatrixKind::Mass(MassKind::Consistent))
        .unwrap()
        .to_dense();
    let p = DofSplit::fixed(n, fixed).unwrap();
    let kff = p.dense_block(k.as_ref(), false, false).unwrap();
    let mff = p.dense_block(m.as_ref(), false, false).unwrap();
    dense_modes(kff.as_ref(), mff.as_ref(), count).unwrap()
}

/// Cantilever in 3D: bending frequencies in both planes follow EB theory
/// (β₁L = 1.87510407, Blevins Table 8-1) and the torsional one ω = π/(2L)√(GJ/ρIp); the result
/// does not depend on the orientation of the beam in space (frame invariance).
#[test]
fn cantilever_3d_frequencies_and_invariance() {
    let (l, n): (f64, usize) = (2.0, 30);
    let s = section();
    let b1: f64 = 1.875_104_07;
    let mut expect = vec![
        b1 * b1 * (s.ei_z / (s.mass_per_length * l.powi(4))).sqrt(),
        b1 * b1 * (s.ei_y / (s.mass_per_length * l.powi(4))).sqrt(),
        PI / (2.0 * l) * (s.gj / s.polar_inertia_per_length).sqrt(),
    ];
    expect.sort_by(f64::total_cmp);
    let mut reference: Option<Vec<f64>> = None;
    for (dir, up) in [
        ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([1.0, 2.0, -0.5], [0.3, -0.2, 1.0]),
    ] {
        let (els, nd) = frame(n, l, dir, up, s, 0.0);
        let modes = fixed_modes(&els, nd, &(0..6).collect::<Vec<_>>(), 8);
        let om = modes.omegas();
        // the three target modes are among the six lowest (with the second bending pair)
        let mut found = om[..6].to_vec();
        found.sort_by(f64::total_cmp);
        for e in &expect {
            let best = found
                .iter()
                .map(|w| (w - e).abs() / e)
                .fold(f64::INFINITY, f64::min);
            assert!(best < 2e-4, "expected ω = {e}: found {found:?}");
        }
        match &reference {
            None => reference = Some(om.clone()),
            Some(r) => {
                for (a, b) in r.iter().zip(&om) {
                    assert!(
                        (a - b).abs() < 1e-8 * a,
                        "orientation dependence: {a} vs {b}"
                    );
                }
            }
        }
    }
}

/// Timoshenko element with the shear parameter Φ is exact for an end-loaded cantilever:
/// δ = PL³/(3EI) + PL/(κGA) (Timoshenko & Gere), for any number of elements; with shear
/// stiffness → ∞ it reduces to Euler–Bernoulli.
#[test]
fn timoshenko_cantilever_tip_deflection_is_exact() {
    let (l, p): (f64, f64) = (1.5, 1000.0);
    let mut s = section();
    s.shear_y = Some(2.0e5);
    s.shear_z = Some(5.0e5);
    for n in [1usize, 3, 8] {
        let (els, nd) = frame(n, l, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], s, 0.0);
        let k = assemble(nd, &els, MatrixKind::Stiffness)
            .unwrap()
            .to_dense();
        let fixed: Vec<usize> = (0..6).collect();
        let part = DofSplit::fixed(nd, &fixed).unwrap();
        let kff = part.dense_block(k.as_ref(), false, false).unwrap();
        // loads P in y and in z at the tip
        let tip = 6 * n;
        let mut f = Mat::zeros(nd - 6, 2);
        f[(tip + 1 - 6, 0)] = p;
        f[(tip + 2 - 6, 1)] = p;
        let u = kff.partial_piv_lu().solve(&f);
        let dy = u[(tip + 1 - 6, 0)];
        let dz = u[(tip + 2 - 6, 1)];
        let ey = p * l.powi(3) / (3.0 * s.ei_z) + p * l / 2.0e5;
        let ez = p * l.powi(3) / (3.0 * s.ei_y) + p * l / 5.0e5;
        assert!((dy - ey).abs() < 1e-10 * ey, "n={n}: {dy} vs {ey}");
        assert!((dz - ez).abs() < 1e-10 * ez, "n={n}: {dz} vs {ez}");
    }
}

/// Geometric stiffness in 3D: a tensioned pinned–pinned span matches the tensioned-beam
/// formula in both planes (Rao §11.5), as the 2D element does.
#[test]
fn prestressed_span_3d() {
    let (l, t, n) = (0.45, 310.0, 60);
    let mut s = section();
    s.ei_y = 2.6e-2;
    s.ei_z = 5.2e-2;
    s.mass_per_length = 0.096;
    let (els, nd) = frame(n, l, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], s, t);
    let mut k = assemble(nd, &els, MatrixKind::Stiffness)
        .unwrap()
        .to_dense();
    k += assemble(nd, &els, MatrixKind::Geometric)
        .unwrap()
        .to_dense();
    let m = assemble(nd, &els, MatrixKind::Mass(MassKind::Consistent))
        .unwrap()
        .to_dense();
    // pinned: u, v, w, θx at node 0; v, w at the end
    let fixed = [0, 1, 2, 3, 6 * n + 1, 6 * n + 2];
    let p = DofSplit::fixed(nd, &fixed).unwrap();
    let kff = p.dense_block(k.as_ref(), false, false).unwrap();
    let mff = p.dense_block(m.as_ref(), false, false).unwrap();
    let modes = dense_modes(kff.as_ref(), mff.as_ref(), 2).unwrap();
    let f = |ei: f64| {
        1.0 / (2.0 * l) * (t / s.mass_per_length).sqrt() * (1.0 + PI * PI * ei / (t * l * l)).sqrt()
    };
    let (fa, fb) = (f(s.ei_y), f(s.ei_z));
    assert!((modes.frequencies_hz[0] - fa).abs() / fa < 2e-5);
    assert!((modes.frequencies_hz[1] - fb).abs() / fb < 2e-5);
}

/// Point masses and springs: a two-mass chain m1 — k — m2 — k_g — ground has
/// ω² = roots of m1 m2 ω⁴ − (k m2 + (k + k_g) m1) ω² + k k_g = 0.
#[test]
fn point_masses_and_springs() {
    let (m1, m2, k, kg) = (2.0, 3.0, 500.0, 800.0);
    let els: Vec<Box<dyn Element>> = vec![
        Box::new(PointMass::new(vec![0], m1).unwrap()),
        Box::new(PointMass::new(vec![1], m2).unwrap()),
        Box::new(Spring::between(0, 1, k).unwrap()),
        Box::new(Spring::grounded(1, kg).unwrap()),
    ];
    let kk = assemble(2, &els, MatrixKind::Stiffness).unwrap().to_dense();
    let mm = assemble(2, &els, MatrixKind::Mass(MassKind::Lumped))
        .unwrap()
        .to_dense();
    let modes = dense_modes(kk.as_ref(), mm.as_ref(), 2).unwrap();
    let (a, b, c) = (m1 * m2, -(k * m2 + (k + kg) * m1), k * kg);
    let disc = (b * b - 4.0 * a * c).sqrt();
    let w2 = [(-b - disc) / (2.0 * a), (-b + disc) / (2.0 * a)];
    for (got, want) in modes.values.iter().zip(w2) {
        assert!((got - want).abs() < 1e-12 * want);
    }
    assert!(Spring::between(3, 3, 1.0).is_err());
    assert!(PointMass::new(vec![0], -1.0).is_err());
}
