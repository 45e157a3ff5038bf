//! Tilde (skew-symmetric cross-product) matrix and stacking helpers for flat `f64` slices.

use nalgebra::{Matrix3, Vector3, Vector4};

/// Skew-symmetric matrix `ã` with `ã b = a × b` (Lin (2.2), Nikravesh's tilde operator).
pub fn tilde(a: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -a.z, a.y, a.z, 0.0, -a.x, -a.y, a.x, 0.0)
}

/// Reads a 3-vector from `s[at..at + 3]`.
pub fn get3(s: &[f64], at: usize) -> Vector3<f64> {
    Vector3::new(s[at], s[at + 1], s[at + 2])
}

/// Reads a 4-vector from `s[at..at + 4]`.
pub fn get4(s: &[f64], at: usize) -> Vector4<f64> {
    Vector4::new(s[at], s[at + 1], s[at + 2], s[at + 3])
}

/// Writes a 3-vector into `s[at..at + 3]`.
pub fn put3(s: &mut [f64], at: usize, v: &Vector3<f64>) {
    s[at..at + 3].copy_from_slice(v.as_slice());
}

/// Adds a 3-vector into `s[at..at + 3]`.
pub fn add3(s: &mut [f64], at: usize, v: &Vector3<f64>) {
    for k in 0..3 {
        s[at + k] += v[k];
    }
}

/// Writes a 4-vector into `s[at..at + 4]`.
pub fn put4(s: &mut [f64], at: usize, v: &Vector4<f64>) {
    s[at..at + 4].copy_from_slice(v.as_slice());
}
