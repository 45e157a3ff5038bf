//! Euler-parameter identities on random unit p (Lin (2.7)–(2.21)), including the
//! second-derivative relation against finite differences.

use mbd_core::kinematics::euler::*;
use nalgebra::{Matrix3, Vector3, Vector4};
use proptest::prelude::*;

fn unit4() -> impl Strategy<Value = Vector4<f64>> {
    prop::array::uniform4(-1.0f64..1.0)
        .prop_filter("non-degenerate", |a| {
            a.iter().map(|x| x * x).sum::<f64>() > 0.05
        })
        .prop_map(|a| Vector4::from(a).normalize())
}

fn vec3() -> impl Strategy<Value = Vector3<f64>> {
    prop::array::uniform3(-3.0f64..3.0).prop_map(Vector3::from)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn rotation_matrix_is_orthonormal_and_factorises(p in unit4()) {
        let a = a_matrix(&p);
        // AᵀA = I, det A = 1 (Lin (2.7) with (2.8))
        prop_assert!((a.transpose() * a - Matrix3::identity()).abs().max() < 1e-13);
        prop_assert!((a.determinant() - 1.0).abs() < 1e-13);
        // A = G Lᵀ, G Gᵀ = L Lᵀ = I, G p = L p = 0
        let (g, l) = (g_matrix(&p), l_matrix(&p));
        prop_assert!((g * l.transpose() - a).abs().max() < 1e-13);
        prop_assert!((g * g.transpose() - Matrix3::identity()).abs().max() < 1e-13);
        prop_assert!((l * l.transpose() - Matrix3::identity()).abs().max() < 1e-13);
        prop_assert!((g * p).norm() < 1e-13 && (l * p).norm() < 1e-13);
        // round trip through the rotation matrix (sign convention e0 ≥ 0)
        let p2 = from_rotation_matrix(&a);
        let s = if p[0] < 0.0 { -1.0 } else { 1.0 };
        prop_assert!((p2 - p * s).norm() < 1e-12);
    }

    #[test]
    fn product_composes_rotations(p in unit4(), q in unit4()) {
        // A(p ⊗ q) = A(p) A(q)
        let lhs = a_matrix(&product(&p, &q));
        prop_assert!((lhs - a_matrix(&p) * a_matrix(&q)).abs().max() < 1e-13);
    }

    #[test]
    fn velocity_relations(p in unit4(), w in vec3()) {
        // ṗ = ½ Gᵀ ω (2.11) ⇒ 2 G ṗ = ω (2.10); ω' = Aᵀω, ṗ = ½ Lᵀ ω' (2.14) is the same ṗ
        let pd = pdot_from_omega(&p, &w);
        prop_assert!((omega_from_pdot(&p, &pd) - w).norm() < 1e-12);
        let wl = a_matrix(&p).transpose() * w;
        prop_assert!((pdot_from_omega_local(&p, &wl) - pd).norm() < 1e-12);
        prop_assert!((omega_local_from_pdot(&p, &pd) - wl).norm() < 1e-12);
        // pᵀṗ = 0 keeps the norm
        prop_assert!(p.dot(&pd).abs() < 1e-13);
        // Ȧ Aᵀ = ω̃ via finite differences of A along p(t) = p + t ṗ (normalised)
        let h = 1e-6;
        let ap = a_matrix(&(p + pd * h).normalize());
        let am = a_matrix(&(p - pd * h).normalize());
        let adot = (ap - am) / (2.0 * h);
        let wt = adot * a_matrix(&p).transpose();
        let axial = Vector3::new(wt[(2, 1)], wt[(0, 2)], wt[(1, 0)]);
        prop_assert!((axial - w).norm() < 1e-6 * (1.0 + w.norm()));
    }

    #[test]
    fn second_derivative_matches_finite_differences(
        p0 in unit4(),
        c1 in prop::array::uniform4(-1.0f64..1.0),
        c2 in prop::array::uniform4(-1.0f64..1.0),
    ) {
        // smooth unit curve p(t) = normalise(p0 + t c1 + t² c2); check Lin (2.20), (2.21):
        // p̈ = ½ Gᵀ ω̇ − ¼ (ωᵀω) p,  p̈ = ½ Lᵀ ω̇' − ¼ (ω'ᵀω') p
        let (c1, c2) = (Vector4::from(c1), Vector4::from(c2));
        let curve = |t: f64| (p0 + c1 * t + c2 * (t * t)).normalize();
        let h = 1e-4;
        let pdot_at = |t: f64| (curve(t + h) - curve(t - h)) / (2.0 * h);
        let p = curve(0.0);
        let pdd = (curve(h) - p * 2.0 + curve(-h)) / (h * h);
        let w = omega_from_pdot(&p, &pdot_at(0.0));
        let wl = omega_local_from_pdot(&p, &pdot_at(0.0));
        let wd = (omega_from_pdot(&curve(h), &pdot_at(h)) - omega_from_pdot(&curve(-h), &pdot_at(-h))) / (2.0 * h);
        let wld = (omega_local_from_pdot(&curve(h), &pdot_at(h))
            - omega_local_from_pdot(&curve(-h), &pdot_at(-h))) / (2.0 * h);
        let scale = 1.0 + pdd.norm();
        prop_assert!((pddot(&p, &w, &wd) - pdd).norm() < 1e-5 * scale);
        prop_assert!((pddot_local(&p, &wl, &wld) - pdd).norm() < 1e-5 * scale);
        // the squared norm matters: with |ω| instead of |ω|² the relation fails unless |ω|≈1 or 0
    }

    #[test]
    fn axis_angle_and_exponential_map(u in vec3(), phi in -3.0f64..3.0, p in unit4()) {
        prop_assume!(u.norm() > 0.1);
        // Lin (2.4)-(2.5): A(p(u, φ)) u = u and p is unit
        let q = from_axis_angle(&u, phi);
        prop_assert!((q.norm() - 1.0).abs() < 1e-14);
        let un = u.normalize();
        prop_assert!((a_matrix(&q) * un - un).norm() < 1e-13);
        // body-frame increment: A(p ⊗ exp(θ'/2)) = A(p) A(exp(θ'/2))
        let th = un * phi;
        let r = compose_local_rotation(&p, &th);
        prop_assert!((a_matrix(&r) - a_matrix(&p) * a_matrix(&q)).abs().max() < 1e-12);
    }
}

#[test]
fn non_unit_p_is_rejected() {
    // Lin (2.8)
    let p = Vector4::new(1.0, 0.1, 0.0, 0.0);
    let e = check_unit(&p, "body \"crank\"").unwrap_err();
    assert!(e.to_string().contains("crank"), "{e}");
    assert!(check_unit(&Vector4::new(f64::NAN, 0.0, 0.0, 0.0), "b").is_err());
}
