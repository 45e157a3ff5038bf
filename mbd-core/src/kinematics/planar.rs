//! Planar kinematics: rotation matrix `A(φ)`, its derivative matrix `B(φ) = dA/dφ` and the
//! perpendicular operator (Nikravesh, *Computer-Aided Analysis of Mechanical Systems*, ch. 4;
//! the planar counterparts of Lin (2.1)–(2.3)).

use nalgebra::{Matrix2, Vector2};

/// Planar rotation matrix `A(φ) = [cos φ, −sin φ; sin φ, cos φ]`.
pub fn rot2(phi: f64) -> Matrix2<f64> {
    let (s, c) = phi.sin_cos();
    Matrix2::new(c, -s, s, c)
}

/// `B(φ) = dA/dφ = A(φ) J` with `J` the 90° rotation, so that `ṡ = φ̇ B s'`.
pub fn drot2(phi: f64) -> Matrix2<f64> {
    let (s, c) = phi.sin_cos();
    Matrix2::new(-s, -c, c, -s)
}

/// Perpendicular vector `s⊥ = [−s_y, s_x]` (planar tilde: `ω̃ s = ω s⊥`).
pub fn perp(s: &Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-s.y, s.x)
}
