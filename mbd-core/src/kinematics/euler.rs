//! Euler parameters `p = (e0, e1, e2, e3)`, `pᵀp = 1` (Lin (2.4)–(2.21); Nikravesh 1988).
//!
//! `ω` is the global angular velocity, `ω'` the body-frame one. All functions take a unit `p`
//! unless stated otherwise; [`check_unit`] validates user input.

use super::tilde::tilde;
use crate::MbdError;
use nalgebra::{Matrix3, Matrix3x4, Vector3, Vector4};

/// Tolerance on `|pᵀp − 1|` accepted for user-supplied Euler parameters.
pub const UNIT_TOL: f64 = 1e-9;

/// Rotation matrix `A = (2e0² − 1) I + 2 (e eᵀ + e0 ẽ)` (Lin (2.7)).
pub fn a_matrix(p: &Vector4<f64>) -> Matrix3<f64> {
    let e0 = p[0];
    let e = Vector3::new(p[1], p[2], p[3]);
    Matrix3::identity() * (2.0 * e0 * e0 - 1.0) + (e * e.transpose() + tilde(&e) * e0) * 2.0
}

/// `G = [−e, ẽ + e0 I]` (Lin (2.12)); `ω = 2 G ṗ` (2.10).
pub fn g_matrix(p: &Vector4<f64>) -> Matrix3x4<f64> {
    let (e0, e1, e2, e3) = (p[0], p[1], p[2], p[3]);
    Matrix3x4::new(-e1, e0, -e3, e2, -e2, e3, e0, -e1, -e3, -e2, e1, e0)
}

/// `L = [−e, −ẽ + e0 I]` (Lin (2.15)); `ω' = 2 L ṗ` (2.13).
pub fn l_matrix(p: &Vector4<f64>) -> Matrix3x4<f64> {
    let (e0, e1, e2, e3) = (p[0], p[1], p[2], p[3]);
    Matrix3x4::new(-e1, e0, e3, -e2, -e2, -e3, e0, e1, -e3, e2, -e1, e0)
}

/// `ṗ = ½ Gᵀ ω` from the global angular velocity (Lin (2.11)).
pub fn pdot_from_omega(p: &Vector4<f64>, omega: &Vector3<f64>) -> Vector4<f64> {
    g_matrix(p).transpose() * omega * 0.5
}

/// `ṗ = ½ Lᵀ ω'` from the body-frame angular velocity (Lin (2.14)).
pub fn pdot_from_omega_local(p: &Vector4<f64>, omega_local: &Vector3<f64>) -> Vector4<f64> {
    l_matrix(p).transpose() * omega_local * 0.5
}

/// `ω = 2 G ṗ` (Lin (2.10)).
pub fn omega_from_pdot(p: &Vector4<f64>, pdot: &Vector4<f64>) -> Vector3<f64> {
    g_matrix(p) * pdot * 2.0
}

/// `ω' = 2 L ṗ` (Lin (2.13)).
pub fn omega_local_from_pdot(p: &Vector4<f64>, pdot: &Vector4<f64>) -> Vector3<f64> {
    l_matrix(p) * pdot * 2.0
}

/// `p̈ = ½ Gᵀ ω̇ − ¼ (ωᵀω) p` (Lin (2.20), with the squared norm of ω, see the note on the OCR).
pub fn pddot(p: &Vector4<f64>, omega: &Vector3<f64>, omega_dot: &Vector3<f64>) -> Vector4<f64> {
    g_matrix(p).transpose() * omega_dot * 0.5 - p * (0.25 * omega.norm_squared())
}

/// `p̈ = ½ Lᵀ ω̇' − ¼ (ω'ᵀω') p` (Lin (2.21)).
pub fn pddot_local(
    p: &Vector4<f64>, omega_local: &Vector3<f64>, omega_local_dot: &Vector3<f64>,
) -> Vector4<f64> {
    l_matrix(p).transpose() * omega_local_dot * 0.5 - p * (0.25 * omega_local.norm_squared())
}

/// `p / ‖p‖` (Lin (2.8)); `None` for a zero or non-finite vector.
pub fn normalized(p: &Vector4<f64>) -> Option<Vector4<f64>> {
    let n = p.norm();
    (n.is_finite() && n > 0.0).then(|| p / n)
}

/// Checks `|pᵀp − 1| ≤` [`UNIT_TOL`] and finiteness; `what` names the body in the error.
pub fn check_unit(p: &Vector4<f64>, what: &str) -> Result<(), MbdError> {
    if !p.iter().all(|x| x.is_finite()) {
        return Err(MbdError::InvalidInput {
            item: format!("{what}: Euler parameters"),
            reason: format!("non-finite value in p = {:?}", p.as_slice()),
        });
    }
    let dev = (p.norm_squared() - 1.0).abs();
    if dev > UNIT_TOL {
        return Err(MbdError::InvalidInput {
            item: format!("{what}: Euler parameters"),
            reason: format!(
                "p is not a unit vector: pᵀp − 1 = {:.3e} (Lin (2.8) requires pᵀp = 1)",
                p.norm_squared() - 1.0
            ),
        });
    }
    Ok(())
}

/// Euler parameters of a rotation by `phi` \[rad\] about the unit axis `u`:
/// `e0 = cos(φ/2)`, `e = sin(φ/2) u` (Lin (2.4), (2.5)). `u` is normalised here.
pub fn from_axis_angle(u: &Vector3<f64>, phi: f64) -> Vector4<f64> {
    let n = u.norm();
    let u = if n > 0.0 { u / n } else { Vector3::x() };
    let (s, c) = (0.5 * phi).sin_cos();
    Vector4::new(c, s * u.x, s * u.y, s * u.z)
}

/// Euler parameters from a rotation matrix (Shepperd's method, sign with `e0 ≥ 0`).
pub fn from_rotation_matrix(a: &Matrix3<f64>) -> Vector4<f64> {
    let tr = a.trace();
    let cands = [tr, a[(0, 0)], a[(1, 1)], a[(2, 2)]];
    let mut k = 0;
    for i in 1..4 {
        if cands[i] > cands[k] {
            k = i;
        }
    }
    let p = match k {
        0 => {
            let e0 = 0.5 * (1.0 + tr).max(0.0).sqrt();
            let f = 0.25 / e0;
            Vector4::new(
                e0,
                (a[(2, 1)] - a[(1, 2)]) * f,
                (a[(0, 2)] - a[(2, 0)]) * f,
                (a[(1, 0)] - a[(0, 1)]) * f,
            )
        }
        1 => {
            let e1 = 0.5 * (1.0 + 2.0 * a[(0, 0)] - tr).max(0.0).sqrt();
            let f = 0.25 / e1;
            Vector4::new(
                (a[(2, 1)] - a[(1, 2)]) * f,
                e1,
                (a[(0, 1)] + a[(1, 0)]) * f,
                (a[(0, 2)] + a[(2, 0)]) * f,
            )
        }
        2 => {
            let e2 = 0.5 * (1.0 + 2.0 * a[(1, 1)] - tr).max(0.0).sqrt();
            let f = 0.25 / e2;
            Vector4::new(
                (a[(0, 2)] - a[(2, 0)]) * f,
                (a[(0, 1)] + a[(1, 0)]) * f,
                e2,
                (a[(1, 2)] + a[(2, 1)]) * f,
            )
        }
        _ => {
            let e3 = 0.5 * (1.0 + 2.0 * a[(2, 2)] - tr).max(0.0).sqrt();
            let f = 0.25 / e3;
            Vector4::new(
                (a[(1, 0)] - a[(0, 1)]) * f,
                (a[(0, 2)] + a[(2, 0)]) * f,
                (a[(1, 2)] + a[(2, 1)]) * f,
                e3,
            )
        }
    };
    if p[0] < 0.0 { -p } else { p }
}

/// Quaternion (Hamilton) product `p ⊗ q`, so that `A(p ⊗ q) = A(p) A(q)`.
pub fn product(p: &Vector4<f64>, q: &Vector4<f64>) -> Vector4<f64> {
    let (a0, a) = (p[0], Vector3::new(p[1], p[2], p[3]));
    let (b0, b) = (q[0], Vector3::new(q[1], q[2], q[3]));
    let s = a0 * b0 - a.dot(&b);
    let v = b * a0 + a * b0 + a.cross(&b);
    Vector4::new(s, v.x, v.y, v.z)
}

/// Exponential map of a body-frame rotation vector `θ'` \[rad\]: `p ⊗ exp(θ'/2)`, the exact
/// composition used by the Lie-group generalized-α (Brüls, Cardona & Arnold 2012).
pub fn compose_local_rotation(p: &Vector4<f64>, theta_local: &Vector3<f64>) -> Vector4<f64> {
    let phi = theta_local.norm();
    let dp = if phi < 1e-12 {
        // second-order series, renormalised below
        Vector4::new(
            1.0 - phi * phi / 8.0,
            0.5 * theta_local.x,
            0.5 * theta_local.y,
            0.5 * theta_local.z,
        )
    } else {
        from_axis_angle(&(theta_local / phi), phi)
    };
    let r = product(p, &dp);
    r / r.norm()
}
