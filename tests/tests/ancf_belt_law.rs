//! The belt element's material laws (issue 34 item 1): St Venant–Kirchhoff (Kerkkänen
//! (3.18)–(3.19)) and linear in the engineering strain (Exudyn's `ANCFCable2D`), their
//! closed-form forces and tangents, and the axial force the element carries at a point
//! ([`BeltElement::axial_force`]).

use ancf::element::{AncfElement, BeltElement};
use ancf::mesh::straight_coordinates;
use ancf::shape;
use ancf::{Material, Section};
use belt::MaterialLaw;

const LAWS: [MaterialLaw; 2] = [MaterialLaw::StVenantKirchhoff, MaterialLaw::Linear];

fn material() -> Material {
    Material::new(1e8, 0.3, 1036.0).unwrap()
}

/// An element of length `l` whose centreline is a circular arc of radius `r` stretched by
/// `lam` (so its material curvature is `k = lam/r`), with unit unsheared cross-section slopes
/// (`sin γ = 0` at both nodes).
fn arc(r: f64, l: f64, lam: f64) -> Vec<f64> {
    let phi = lam * l / r;
    vec![
        0.0,
        r,
        lam,
        0.0,
        0.0,
        1.0,
        r * phi.sin(),
        r * phi.cos(),
        lam * phi.cos(),
        -lam * phi.sin(),
        phi.sin(),
        phi.cos(),
    ]
}

fn perturbed(el: &BeltElement, amp: f64) -> Vec<f64> {
    let mut e = straight_coordinates(el.layout(), [0.0, 0.0], [el.length(), 0.0], 1);
    for (k, v) in e.iter_mut().enumerate() {
        *v += amp * ((k as f64 * 1.7 + 0.3).sin());
    }
    e
}

fn states(el: &BeltElement) -> Vec<Vec<f64>> {
    vec![
        perturbed(el, 0.08),
        perturbed(el, -0.2),
        // Pechstein–Gerstmayr's tight span: 8 % strain, wrapped on r = 0.1 m
        arc(0.1, el.length(), 1.08),
        // pre-stretched on Table 3.1's pulley
        arc(0.08125, el.length(), 1.0028),
    ]
}

// Second formulation and finite differences (issue 34 item 1: the element uses analytic
// Jacobians): for both laws, the closed-form energy, forces and tangent equal the energy
// written term by term with first- and second-order AD to 1e-10, the forces are −∂U/∂e and the
// tangent is −∂Q/∂e by central differences (1e-6 of the largest entry), and K is symmetric.
#[test]
fn both_laws_closed_form_match_ad_and_finite_differences() {
    let sec = Section::rectangle(0.01, 0.01).unwrap();
    for law in LAWS {
        let el = BeltElement::new(0.064, material(), sec, 1.0, 0.01, 5)
            .unwrap()
            .with_law(law);
        for e in states(&el) {
            let (mut q1, mut q2) = (vec![0.0; 12], vec![0.0; 12]);
            let (mut k1, mut k2) = (vec![0.0; 144], vec![0.0; 144]);
            el.elastic_tangent(&e, &mut q1, &mut k1);
            el.elastic_tangent_reference(&e, &mut q2, &mut k2);
            let (u1, u2) = (el.strain_energy(&e), el.strain_energy_reference(&e));
            assert!(
                (u1 - u2).abs() < 1e-10 * u2.abs(),
                "{law:?}: U {u1} vs {u2}"
            );
            let qs = q2.iter().map(|v| v.abs()).fold(0.0, f64::max);
            let ks = k2.iter().map(|v| v.abs()).fold(0.0, f64::max);
            for i in 0..12 {
                assert!((q1[i] - q2[i]).abs() < 1e-10 * qs, "{law:?} q[{i}]");
                for j in 0..12 {
                    assert!(
                        (k1[i + 12 * j] - k2[i + 12 * j]).abs() < 1e-10 * ks,
                        "{law:?} K[{i},{j}]: {} vs {}",
                        k1[i + 12 * j],
                        k2[i + 12 * j]
                    );
                    assert!((k1[i + 12 * j] - k1[j + 12 * i]).abs() < 1e-10 * ks);
                }
            }
            let h = 1e-7;
            for i in 0..12 {
                let (mut ep, mut em) = (e.clone(), e.clone());
                ep[i] += h;
                em[i] -= h;
                let du = (el.strain_energy(&ep) - el.strain_energy(&em)) / (2.0 * h);
                assert!(
                    (du + q1[i]).abs() < 1e-6 * qs,
                    "{law:?} dof {i}: FD {du}, −Q {}",
                    -q1[i]
                );
                let (mut qp, mut qm) = (vec![0.0; 12], vec![0.0; 12]);
                el.elastic_forces(&ep, &mut qp);
                el.elastic_forces(&em, &mut qm);
                for j in 0..12 {
                    let fd = -(qp[j] - qm[j]) / (2.0 * h);
                    assert!(
                        (fd - k1[j + 12 * i]).abs() < 1e-6 * ks,
                        "{law:?} K[{j},{i}]: FD {fd}, {}",
                        k1[j + 12 * i]
                    );
                }
            }
        }
    }
}

// Closed form: a straight, uniformly stretched element (λ = 1.08, 8 % as in Pechstein and
// Gerstmayr's tight span) carries N = EA λ(λ² − 1)/2 (St Venant–Kirchhoff, the Green strain of
// (3.13) times E, mapped to force by λ) or N = EA(λ − 1) (linear) at every point, and stores
// the energies EA/8 (λ² − 1)² l and EA/2 (λ − 1)² l.
#[test]
fn axial_force_of_a_uniform_stretch() {
    let sec = Section::rectangle(0.08, 0.01).unwrap();
    let ea = 1e7 * sec.area;
    let l = 0.05;
    let lam: f64 = 1.08;
    for law in LAWS {
        let el = BeltElement::new(
            l,
            Material::new(1e7, 0.3, 1036.0).unwrap(),
            sec,
            1.0,
            0.02,
            5,
        )
        .unwrap()
        .with_law(law);
        let mut e = straight_coordinates(el.layout(), [0.0, 0.0], [l * lam, 0.0], 1);
        e[2] = lam;
        e[8] = lam;
        let (n_exact, u_exact) = match law {
            MaterialLaw::StVenantKirchhoff => (
                ea * lam * (lam * lam - 1.0) / 2.0,
                ea / 8.0 * (lam * lam - 1.0).powi(2) * l,
            ),
            MaterialLaw::Linear => (ea * (lam - 1.0), ea / 2.0 * (lam - 1.0).powi(2) * l),
        };
        for xi in [0.0, 0.2, 0.5, 0.9, 1.0] {
            let n = el.axial_force(&e, xi);
            assert!(
                (n - n_exact).abs() < 1e-9 * n_exact,
                "{law:?} ξ = {xi}: N = {n} N, exact {n_exact} N"
            );
        }
        let u = el.strain_energy(&e);
        assert!(
            (u - u_exact).abs() < 1e-9 * u_exact,
            "{law:?}: U {u} vs {u_exact}"
        );
    }
    // the engineering-strain measure reads the St Venant–Kirchhoff force 11 % low at 8 %
    let svk = lam * (lam * lam - 1.0) / 2.0;
    assert!(((lam - 1.0) / svk - 0.890).abs() < 1e-3);
}

// Second formulation: the axial force equals the derivative of the energy density written term
// by term (AD of W(μ r_{c,x}, μ r_{c,xx}) in μ, which stretches the section without bending
// it), for both laws, at points of strongly deformed and wrapped elements.
#[test]
fn axial_force_is_the_stretch_derivative_of_the_reference_energy() {
    let sec = Section::rectangle(0.01, 0.01).unwrap();
    for law in LAWS {
        let el = BeltElement::new(0.064, material(), sec, 1.0, 0.01, 5)
            .unwrap()
            .with_law(law);
        for e in states(&el) {
            for xi in [0.0, 0.13, 0.5, 0.77, 1.0] {
                let (n, nr) = (el.axial_force(&e, xi), el.axial_force_reference(&e, xi));
                let scale = nr.abs().max(1.0);
                assert!(
                    (n - nr).abs() < 1e-9 * scale,
                    "{law:?} ξ = {xi}: {n} vs {nr}"
                );
            }
        }
    }
}

// Continuum reference (Kerkkänen (3.13), (3.18) with α₁ = α₂ = 1): on a stretched arc without
// shear the St Venant–Kirchhoff axial force is the section integral of the first
// Piola–Kirchhoff traction's tangential part, N = ∫ E ε_xx(y) (r_{p,x}(y)·t) dA with
// r_{p,x} = r_{c,x} + y r_{s,x}, ε_xx = ½(r_{p,x}ᵀr_{p,x} − 1) (Gauss in y, exact for the cubic
// integrand; r_{s,x} = n_x by central differences of the normal along the element). It includes
// the bending–stretching coupling ≈ 1.5 EI κ²; the linear law carries EA(λ − 1) at any
// curvature.
#[test]
fn svk_axial_force_is_the_section_integral_of_the_traction() {
    let (b, h) = (0.02, 0.0064);
    let sec = Section::rectangle(b, h).unwrap();
    let mat = Material::new(1.2e9, 0.3, 1036.0).unwrap();
    let (r, l, lam) = (0.05, 0.03, 1.004);
    for law in LAWS {
        let el = BeltElement::new(l, mat, sec, 1.0, 1.0, 5)
            .unwrap()
            .with_law(law);
        let e = arc(r, l, lam);
        let centre = |xi: f64| {
            let sx = shape::cubic(l, xi * l, 0.0).sx;
            let mut rx = [0.0; 2];
            for k in 0..6 {
                rx[0] += sx[k] * e[2 * k];
                rx[1] += sx[k] * e[2 * k + 1];
            }
            rx
        };
        let normal = |xi: f64| {
            let rx = centre(xi);
            let n = rx[0].hypot(rx[1]);
            [-rx[1] / n, rx[0] / n]
        };
        for xi in [0.2, 0.5, 0.8] {
            let rx = centre(xi);
            let lam_p = rx[0].hypot(rx[1]);
            let t = [rx[0] / lam_p, rx[1] / lam_p];
            let dxi = 1e-5;
            let (np, nm) = (normal(xi + dxi), normal(xi - dxi));
            let rsx = [
                (np[0] - nm[0]) / (2.0 * dxi * l),
                (np[1] - nm[1]) / (2.0 * dxi * l),
            ];
            let gauss = [
                (-0.906_179_845_938_664, 0.236_926_885_056_189),
                (-0.538_469_310_105_683, 0.478_628_670_499_366),
                (0.0, 0.568_888_888_888_889),
                (0.538_469_310_105_683, 0.478_628_670_499_366),
                (0.906_179_845_938_664, 0.236_926_885_056_189),
            ];
            let mut n_cont = 0.0;
            for (g, w) in gauss {
                let y = 0.5 * h * g;
                let rpx = [rx[0] + y * rsx[0], rx[1] + y * rsx[1]];
                let eps = 0.5 * (rpx[0] * rpx[0] + rpx[1] * rpx[1] - 1.0);
                n_cont += 0.5 * h * w * b * mat.young * eps * (rpx[0] * t[0] + rpx[1] * t[1]);
            }
            let n = el.axial_force(&e, xi);
            let ea = mat.young * sec.area;
            match law {
                MaterialLaw::StVenantKirchhoff => {
                    assert!(
                        (n - n_cont).abs() < 1e-6 * n_cont,
                        "ξ = {xi}: N = {n} N, section integral {n_cont} N"
                    );
                    // the coupling term of (3.18) above EA λ ε_G: EI λ(s² + ½c) = 1.5 EI λ k²
                    // without shear, k = (r_x × r_xx)/‖r_x‖² the material curvature
                    let sxx = shape::cubic_xx(l, xi * l);
                    let mut rxx = [0.0; 2];
                    for k in 0..6 {
                        rxx[0] += sxx[k] * e[2 * k];
                        rxx[1] += sxx[k] * e[2 * k + 1];
                    }
                    let k_mat = (rx[0] * rxx[1] - rx[1] * rxx[0]) / (lam_p * lam_p);
                    let coupling = n - ea * lam_p * (lam_p * lam_p - 1.0) / 2.0;
                    let expected = 1.5 * mat.young * sec.i2 * lam_p * k_mat * k_mat;
                    assert!(
                        (coupling - expected).abs() < 1e-6 * expected,
                        "coupling {coupling} N, 1.5 EI λ k² = {expected} N"
                    );
                    // ≈ 1.5 EI κ² on the pulley (κ = 1/r; the cubic arc's curvature varies)
                    let ei_k2 = mat.young * sec.i2 / (r * r);
                    assert!((coupling / ei_k2 - 1.5).abs() < 0.1);
                }
                MaterialLaw::Linear => {
                    assert!(
                        (n - ea * (lam_p - 1.0)).abs() < 1e-9 * n.abs(),
                        "ξ = {xi}: N = {n}, EA(λ − 1) = {}",
                        ea * (lam_p - 1.0)
                    );
                }
            }
        }
    }
}
