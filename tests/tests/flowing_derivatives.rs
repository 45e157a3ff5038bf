//! Validation of the mode-shape derivative operators (Ribaric App. A).
#![allow(clippy::needless_range_loop)] // index loops mirror the matrix equations

use faer::Mat;
use flowing::derivative::{
    FdScheme, FirstDifference, MassKind, SecondDifference, line_fe_matrices, spectral::literal_a13,
};
use flowing::{
    DerivativeMethod, End, FlowGrid, FlowLine, LineOperator, Topology, mode_shape_derivatives,
};
use proptest::prelude::*;
use std::f64::consts::PI;

fn column(grid: &FlowGrid, f: impl Fn(f64) -> f64) -> Mat<f64> {
    Mat::from_fn(grid.len(), 1, |j, _| f(grid.positions()[j]))
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

fn rel_err(a: &Mat<f64>, b: &Mat<f64>) -> f64 {
    max_abs(&(a - b)) / max_abs(b)
}

fn nonuniform_open(n: usize, start: End, end: End, seed: u64) -> FlowGrid {
    // Deterministic jittered positions in (0, 1).
    let mut x = seed;
    let mut pos = Vec::new();
    for j in 0..n {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let r = ((x >> 33) as f64) / (1u64 << 31) as f64;
        pos.push((j as f64 + 0.5 + 0.4 * (r - 0.5)) / n as f64);
    }
    FlowGrid::new(pos, Topology::Open { start, end }).unwrap()
}

const THREE_POINT: FdScheme = FdScheme {
    first: FirstDifference::ThreePoint,
    second: SecondDifference::ThreePoint,
};

// Reference: analytical derivatives of quadratics; 3-point stencils are exact for degree 2.
#[test]
fn three_point_fd_exact_on_quadratics_nonuniform() {
    let f = |x: f64| 0.3 - 1.7 * x + 2.2 * x * x;
    let g = nonuniform_open(23, End::Free, End::Free, 7);
    let op = LineOperator::new(&g, DerivativeMethod::FiniteDifference(THREE_POINT)).unwrap();
    let (d1, d2) = op.apply(column(&g, f).as_ref());
    assert!(rel_err(&d1, &column(&g, |x| -1.7 + 4.4 * x)) < 1e-12);
    assert!(rel_err(&d2, &column(&g, |_| 4.4)) < 1e-10);
    // Zero-value ends at 0 and 1: the quadratic x(1-x) vanishes there.
    let gz = nonuniform_open(17, End::Zero(0.0), End::Zero(1.0), 3);
    let op = LineOperator::new(&gz, DerivativeMethod::FiniteDifference(THREE_POINT)).unwrap();
    let (d1, d2) = op.apply(column(&gz, |x| x * (1.0 - x)).as_ref());
    assert!(rel_err(&d1, &column(&gz, |x| 1.0 - 2.0 * x)) < 1e-12);
    assert!(rel_err(&d2, &column(&gz, |_| -2.0)) < 1e-10);
}

// Reference: notes DER-1 (Ribaric (A.1), 99 nodes, sine modes): rel. error of φ' ≈ (kh)²/6 =
// 1.6e-4, 6.6e-4, 1.5e-3, 2.6e-3, 4.1e-3 for modes 1–5.
#[test]
fn ribaric_a1_error_on_sine_modes_matches_notes() {
    let g = FlowGrid::uniform_fixed(0.0, 1.0, 99).unwrap();
    let op =
        LineOperator::new(&g, DerivativeMethod::FiniteDifference(FdScheme::default())).unwrap();
    let expected = [1.6e-4, 6.6e-4, 1.5e-3, 2.6e-3, 4.1e-3];
    for (k, e) in (1..=5).zip(expected) {
        let kf = k as f64 * PI;
        let (d1, _) = op.apply(column(&g, |x| (kf * x).sin()).as_ref());
        let err = rel_err(&d1, &column(&g, |x| kf * (kf * x).cos()));
        assert!((err - e).abs() < 0.06 * e, "mode {k}: {err} vs {e}");
    }
}

// Reference: second formulation. The Galerkin operators of linear elements with lumped mass equal
// Ribaric (A.1) and the 3-point second difference on any grid; M₁D₁ is skew and M₁D₂ = −K₁.
#[test]
fn consistent_lumped_equals_a1_and_three_point_second_difference() {
    for g in [
        nonuniform_open(15, End::Zero(0.0), End::Zero(1.0), 11),
        FlowGrid::new(
            nonuniform_open(12, End::Free, End::Free, 5)
                .positions()
                .to_vec(),
            Topology::Closed { period: 1.0 },
        )
        .unwrap(),
    ] {
        let fd = LineOperator::new(&g, DerivativeMethod::FiniteDifference(FdScheme::default()))
            .unwrap()
            .to_dense();
        let co = LineOperator::new(&g, DerivativeMethod::Consistent(MassKind::Lumped))
            .unwrap()
            .to_dense();
        assert!(max_abs(&(&fd.0 - &co.0)) < 1e-9 * max_abs(&fd.0));
        assert!(max_abs(&(&fd.1 - &co.1)) < 1e-9 * max_abs(&fd.1));
        for mass in [MassKind::Lumped, MassKind::Consistent] {
            let (m1, _, k1) = line_fe_matrices(&g, mass);
            let (d1, d2) = LineOperator::new(&g, DerivativeMethod::Consistent(mass))
                .unwrap()
                .to_dense();
            let md1 = &m1 * &d1;
            let md2 = &m1 * &d2;
            assert!(max_abs(&(&md1 + md1.transpose())) < 1e-12, "M1 D1 skew");
            assert!(max_abs(&(&md2 + &k1)) < 1e-9 * max_abs(&k1), "M1 D2 = -K1");
        }
    }
}

// Reference: exactness of least squares on polynomials of the fitted degree (A.9).
#[test]
fn polynomial_lsq_exact_on_polynomials_of_its_degree() {
    let g = nonuniform_open(30, End::Free, End::Free, 9);
    let p = |x: f64| 1.0 + x - 3.0 * x.powi(2) + 0.5 * x.powi(3) + 2.0 * x.powi(5);
    let dp = |x: f64| 1.0 - 6.0 * x + 1.5 * x.powi(2) + 10.0 * x.powi(4);
    let ddp = |x: f64| -6.0 + 3.0 * x + 40.0 * x.powi(3);
    let op = LineOperator::new(&g, DerivativeMethod::Polynomial { degree: 5 }).unwrap();
    let (d1, d2) = op.apply(column(&g, p).as_ref());
    assert!(rel_err(&d1, &column(&g, dp)) < 1e-9);
    assert!(rel_err(&d2, &column(&g, ddp)) < 1e-8);
    // Boundary-aware: zero-value ends are collocation points; x(1-x)(2+x) vanishes there.
    let gz = nonuniform_open(20, End::Zero(0.0), End::Zero(1.0), 2);
    let op = LineOperator::new(&gz, DerivativeMethod::Polynomial { degree: 3 }).unwrap();
    let (d1, _) = op.apply(column(&gz, |x| x * (1.0 - x) * (2.0 + x)).as_ref());
    assert!(rel_err(&d1, &column(&gz, |x| 2.0 - 2.0 * x - 3.0 * x * x)) < 1e-10);
}

// Reference: notes DER-2 (mode-5 slope error falls from O(1) at degree 5 to ~1e-3 at degree 15).
#[test]
fn polynomial_lsq_converges_with_degree_on_mode_5() {
    let g = FlowGrid::uniform_fixed(0.0, 1.0, 99).unwrap();
    let k = 5.0 * PI;
    let exact = column(&g, |x| k * (k * x).cos());
    let errs: Vec<f64> = [5, 10, 15]
        .iter()
        .map(|&m| {
            let op = LineOperator::new(&g, DerivativeMethod::Polynomial { degree: m }).unwrap();
            rel_err(&op.apply(column(&g, |x| (k * x).sin()).as_ref()).0, &exact)
        })
        .collect();
    assert!(errs[0] > 0.5, "degree 5 cannot represent mode 5: {errs:?}");
    assert!(errs[1] < 0.2 && errs[1] < errs[0], "{errs:?}");
    assert!(errs[2] < 5e-3, "{errs:?}");
}

// Reference: notes DER-3 (corrected FFT, odd extension: rel. error ≤ 1e-12 on sampled sines) and
// erratum E22 (the literal (A.13) has O(1) error).
#[test]
fn spectral_is_exact_on_sines_and_literal_a13_is_not() {
    let g = FlowGrid::uniform_fixed(0.0, 1.0, 99).unwrap();
    let op = LineOperator::new(&g, DerivativeMethod::Spectral).unwrap();
    for k in 1..=10 {
        let kf = k as f64 * PI;
        let f = column(&g, |x| (kf * x).sin());
        let (d1, d2) = op.apply(f.as_ref());
        assert!(
            rel_err(&d1, &column(&g, |x| kf * (kf * x).cos())) < 1e-12,
            "mode {k}"
        );
        // φ'': round-off of k_max² ≈ 1e5 amplifies ε to ~2e-12 (notes: "≤ 1e-12" approx.).
        assert!(
            rel_err(&d2, &column(&g, |x| -kf * kf * (kf * x).sin())) < 1e-11,
            "mode {k}"
        );
    }
    let f = column(&g, |x| (PI * x).sin());
    let (lit, _) = literal_a13(f.as_ref());
    assert!(rel_err(&lit, &column(&g, |x| PI * (PI * x).cos())) > 0.3);
    // Closed loop of period 2: exact on trigonometric fields below Nyquist.
    let c = FlowGrid::uniform_closed(0.0, 2.0, 64).unwrap();
    let op = LineOperator::new(&c, DerivativeMethod::Spectral).unwrap();
    let w = 2.0 * PI / 2.0 * 7.0;
    let (d1, d2) = op.apply(column(&c, |x| (w * x).cos() + 0.5 * (3.0 * PI * x).sin()).as_ref());
    assert!(
        rel_err(
            &d1,
            &column(&c, |x| -w * (w * x).sin() + 1.5 * PI * (3.0 * PI * x).cos())
        ) < 1e-12
    );
    assert!(
        rel_err(
            &d2,
            &column(&c, |x| -w * w * (w * x).cos()
                - 4.5 * PI * PI * (3.0 * PI * x).sin())
        ) < 1e-12
    );
    // A non-uniform grid is rejected with a typed error.
    let nu = nonuniform_open(10, End::Zero(0.0), End::Zero(1.0), 1);
    assert!(LineOperator::new(&nu, DerivativeMethod::Spectral).is_err());
}

// Reference: the periodic 3-point FD truncation error of cos(kx) is (kh)²/12 for D₂ (uniform grid).
#[test]
fn periodic_fd_second_order_on_trig() {
    let w = 2.0 * PI * 3.0;
    let errs: Vec<f64> = [32usize, 64]
        .iter()
        .map(|&n| {
            let g = FlowGrid::uniform_closed(0.0, 1.0, n).unwrap();
            let op =
                LineOperator::new(&g, DerivativeMethod::FiniteDifference(THREE_POINT)).unwrap();
            let (_, d2) = op.apply(column(&g, |x| (w * x).cos()).as_ref());
            rel_err(&d2, &column(&g, |x| -w * w * (w * x).cos()))
        })
        .collect();
    let h = 1.0 / 32.0;
    assert!(
        (errs[0] - (w * h) * (w * h) / 12.0).abs() < 0.05 * errs[0],
        "{errs:?}"
    );
    assert!(
        (errs[0] / errs[1] - 4.0).abs() < 0.1,
        "second order: {errs:?}"
    );
}

// Reference: per-component application equals the scalar operator on each component; DOFs off
// the lines get zero derivatives (Ribaric A.5).
#[test]
fn per_component_derivatives_of_three_dof_nodes() {
    let g = FlowGrid::uniform_closed(0.0, 1.0, 40).unwrap();
    // Nodes stored in reverse flow order with 3 DOFs each, plus 2 extra DOFs (e.g. a pulley).
    let order: Vec<usize> = (0..40).rev().collect();
    let lines = FlowLine::per_component(&g, &order, 3).unwrap();
    let n_dof = 40 * 3 + 2;
    let psi = Mat::from_fn(n_dof, 2, |r, c| {
        if r >= 120 {
            1.0
        } else {
            ((r * 7 + c * 3) % 11) as f64 - 5.0
        }
    });
    let method = DerivativeMethod::Spectral;
    let d = mode_shape_derivatives(&lines, method, psi.as_ref()).unwrap();
    let op = LineOperator::new(&g, method).unwrap();
    for comp in 0..3 {
        let vals = Mat::from_fn(40, 2, |j, c| psi[(order[j] * 3 + comp, c)]);
        let (a, b) = op.apply(vals.as_ref());
        for j in 0..40 {
            for c in 0..2 {
                assert!((d.d1[(order[j] * 3 + comp, c)] - a[(j, c)]).abs() < 1e-12);
                assert!((d.d2[(order[j] * 3 + comp, c)] - b[(j, c)]).abs() < 1e-12);
            }
        }
    }
    for c in 0..2 {
        assert_eq!(d.d1[(120, c)], 0.0);
        assert_eq!(d.d2[(121, c)], 0.0);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]
    // Reference: translation invariance of periodic operators on a uniform loop: the derivative
    // of a shifted periodic mode is the shifted derivative.
    #[test]
    fn shifted_periodic_mode_has_shifted_derivative(
        n in 8usize..40,
        shift in 1usize..7,
        vals in proptest::collection::vec(-1.0f64..1.0, 40),
        which in 0usize..3,
    ) {
        let g = FlowGrid::uniform_closed(0.3, 2.5, n).unwrap();
        let method = [
            DerivativeMethod::FiniteDifference(THREE_POINT),
            DerivativeMethod::Consistent(MassKind::Consistent),
            DerivativeMethod::Spectral,
        ][which];
        let op = LineOperator::new(&g, method).unwrap();
        let f = Mat::from_fn(n, 1, |j, _| vals[j]);
        let fs = Mat::from_fn(n, 1, |j, _| vals[(j + shift) % n]);
        let (a1, a2) = op.apply(f.as_ref());
        let (b1, b2) = op.apply(fs.as_ref());
        let scale = 1.0 + max_abs(&a2);
        for j in 0..n {
            prop_assert!((b1[(j, 0)] - a1[((j + shift) % n, 0)]).abs() < 1e-9 * scale);
            prop_assert!((b2[(j, 0)] - a2[((j + shift) % n, 0)]).abs() < 1e-9 * scale);
        }
    }
}
