//! Planar contact geometry: disks (pulleys, drums; moving and rotating), half-planes (flat
//! road) and unions of them (a drum or a road with a semicircular cleat, Ribaric ch. 8).
//!
//! Every shape answers [`Surface::closest`]: the signed distance (gap, negative when the point
//! penetrates), the outward unit normal at the closest surface point, the velocity of the
//! surface material there, and the derivatives of normal and surface velocity with respect to
//! the query point (needed for contact Jacobians).

use serde::{Deserialize, Serialize};

/// 90° rotation `Ĩ = [[0, −1], [1, 0]]`, Kerkkänen (3.6).
#[inline]
pub fn rot90(v: [f64; 2]) -> [f64; 2] {
    [-v[1], v[0]]
}

/// 2×2 matrix, row-major.
pub type Mat2 = [[f64; 2]; 2];

/// Closest-point data of a query point `p`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// Signed distance \[m\] (> 0 separated, < 0 penetrating; penetration `d = −gap`).
    pub gap: f64,
    /// Outward unit normal `n` of the obstacle at the closest point.
    pub normal: [f64; 2],
    /// Closest point on the surface \[m\].
    pub point: [f64; 2],
    /// Velocity of the obstacle's surface material at the closest point \[m/s\].
    pub surface_velocity: [f64; 2],
    /// `∂n/∂p` \[1/m\] (row-major).
    pub dn_dp: Mat2,
    /// `∂u_s/∂p` \[1/s\] (row-major).
    pub dus_dp: Mat2,
    /// `∂u_s/∂ω` \[m\] (surface velocity per unit angular velocity of the obstacle).
    pub dus_domega: [f64; 2],
    /// Index of the primitive that produced the point (0 for simple shapes; for unions the
    /// member index).
    pub part: usize,
}

/// A rigid obstacle surface in the plane.
pub trait Surface {
    /// Closest-point query for the point `p` \[m\].
    fn closest(&self, p: [f64; 2]) -> SurfacePoint;
    /// Centre of the body for torque output (pulley axis) \[m\].
    fn center(&self) -> [f64; 2];
}

/// A rigid disk (pulley, drum) with centre `center` \[m\], radius `radius` \[m\], translational
/// velocity `velocity` \[m/s\] and angular velocity `omega` \[rad/s\] (counter-clockwise positive).
/// The contacting body is outside the disk.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Disk {
    /// Centre `r_o` \[m\].
    pub center: [f64; 2],
    /// Radius `R` \[m\].
    pub radius: f64,
    /// Velocity of the centre `ṙ_o` \[m/s\].
    pub velocity: [f64; 2],
    /// Angular velocity `ω` \[rad/s\].
    pub omega: f64,
}

impl Disk {
    /// A fixed, non-rotating disk.
    pub fn fixed(center: [f64; 2], radius: f64) -> Self {
        Self {
            center,
            radius,
            velocity: [0.0, 0.0],
            omega: 0.0,
        }
    }
}

impl Surface for Disk {
    /// Kerkkänen (3.21)–(3.22): `d = R − ‖r − r_o‖`, `n = (r − r_o)/‖r − r_o‖`; the surface
    /// velocity is `ṙ_o + ω R t` with `t = Ĩ n` (3.24)–(3.25) (nominal radius `R`).
    fn closest(&self, p: [f64; 2]) -> SurfacePoint {
        let d = [p[0] - self.center[0], p[1] - self.center[1]];
        let rho = (d[0] * d[0] + d[1] * d[1]).sqrt();
        // at the centre any direction is a normal; pick +y to stay finite
        let (n, inv) = if rho > 0.0 {
            ([d[0] / rho, d[1] / rho], 1.0 / rho)
        } else {
            ([0.0, 1.0], 0.0)
        };
        let t = rot90(n);
        // ∂n/∂p = (I − n nᵀ)/ρ = t tᵀ/ρ
        let dn = [
            [t[0] * t[0] * inv, t[0] * t[1] * inv],
            [t[1] * t[0] * inv, t[1] * t[1] * inv],
        ];
        // u_s = ṙ_o + ω R Ĩ n  ⇒ ∂u_s/∂p = ω R Ĩ ∂n/∂p
        let wr = self.omega * self.radius;
        let dus = [
            [-wr * dn[1][0], -wr * dn[1][1]],
            [wr * dn[0][0], wr * dn[0][1]],
        ];
        SurfacePoint {
            gap: rho - self.radius,
            normal: n,
            point: [
                self.center[0] + self.radius * n[0],
                self.center[1] + self.radius * n[1],
            ],
            surface_velocity: [self.velocity[0] + wr * t[0], self.velocity[1] + wr * t[1]],
            dn_dp: dn,
            dus_dp: dus,
            dus_domega: [self.radius * t[0], self.radius * t[1]],
            part: 0,
        }
    }
    fn center(&self) -> [f64; 2] {
        self.center
    }
}

/// A half-plane (flat road): material on the side opposite to the unit `normal`, surface
/// through `origin`, moving tangentially with `velocity` \[m/s\] (e.g. a belt-type road).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HalfPlane {
    /// A point of the surface \[m\].
    pub origin: [f64; 2],
    /// Outward unit normal.
    pub normal: [f64; 2],
    /// Surface material velocity \[m/s\].
    pub velocity: [f64; 2],
}

impl HalfPlane {
    /// Fixed ground `y = height` with normal `+y`.
    pub fn ground(height: f64) -> Self {
        Self {
            origin: [0.0, height],
            normal: [0.0, 1.0],
            velocity: [0.0, 0.0],
        }
    }
}

impl Surface for HalfPlane {
    fn closest(&self, p: [f64; 2]) -> SurfacePoint {
        let n = self.normal;
        let g = (p[0] - self.origin[0]) * n[0] + (p[1] - self.origin[1]) * n[1];
        SurfacePoint {
            gap: g,
            normal: n,
            point: [p[0] - g * n[0], p[1] - g * n[1]],
            surface_velocity: self.velocity,
            dn_dp: [[0.0; 2]; 2],
            dus_dp: [[0.0; 2]; 2],
            dus_domega: [0.0, 0.0],
            part: 0,
        }
    }
    fn center(&self) -> [f64; 2] {
        self.origin
    }
}

/// A drum of radius `radius` with a semicircular cleat of radius `cleat_radius` whose centre
/// sits on the drum surface at polar angle `cleat_angle` (Ribaric ch. 8: 10 mm cleat on a
/// 1.25 m drum). The drum rotates with `omega`; advance `cleat_angle` with time.
/// Geometry: union of the drum disk and the cleat disk (signed distance = minimum).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CleatedDrum {
    /// The drum.
    pub drum: Disk,
    /// Cleat radius \[m\].
    pub cleat_radius: f64,
    /// Polar angle of the cleat centre \[rad\].
    pub cleat_angle: f64,
}

impl CleatedDrum {
    /// The cleat as a disk moving with the drum surface.
    pub fn cleat(&self) -> Disk {
        let (s, c) = self.cleat_angle.sin_cos();
        let r = self.drum.radius;
        let w = self.drum.omega;
        Disk {
            center: [self.drum.center[0] + r * c, self.drum.center[1] + r * s],
            radius: self.cleat_radius,
            // cleat centre velocity ṙ_o + ω Ĩ (R e)
            velocity: [
                self.drum.velocity[0] - w * r * s,
                self.drum.velocity[1] + w * r * c,
            ],
            omega: w,
        }
    }
}

impl Surface for CleatedDrum {
    fn closest(&self, p: [f64; 2]) -> SurfacePoint {
        let a = self.drum.closest(p);
        let mut b = self.cleat().closest(p);
        if b.gap < a.gap {
            b.part = 1;
            // the cleat surface moves with the drum: u_s = ṙ_o + ω Ĩ (x_s − r_o)
            b.dus_domega = rot90([
                b.point[0] - self.drum.center[0],
                b.point[1] - self.drum.center[1],
            ]);
            b
        } else {
            a
        }
    }
    fn center(&self) -> [f64; 2] {
        self.drum.center
    }
}

/// Flat road with a semicircular cleat of radius `cleat_radius` centred on the surface at
/// abscissa `cleat_x` (Ribaric §8.5). Union of the half-plane `y ≤ height` and the cleat disk.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CleatedRoad {
    /// Road surface height \[m\].
    pub height: f64,
    /// Cleat radius \[m\].
    pub cleat_radius: f64,
    /// Cleat centre abscissa \[m\].
    pub cleat_x: f64,
}

impl Surface for CleatedRoad {
    fn closest(&self, p: [f64; 2]) -> SurfacePoint {
        let a = HalfPlane::ground(self.height).closest(p);
        let mut b = Disk::fixed([self.cleat_x, self.height], self.cleat_radius).closest(p);
        if b.gap < a.gap {
            b.part = 1;
            b
        } else {
            a
        }
    }
    fn center(&self) -> [f64; 2] {
        [self.cleat_x, self.height]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fd_check(s: &dyn Surface, p: [f64; 2]) {
        let c = s.closest(p);
        let h = 1e-7;
        for j in 0..2 {
            let mut pp = p;
            let mut pm = p;
            pp[j] += h;
            pm[j] -= h;
            let (a, b) = (s.closest(pp), s.closest(pm));
            // ∂gap/∂p = n
            assert!(((a.gap - b.gap) / (2.0 * h) - c.normal[j]).abs() < 1e-6);
            for i in 0..2 {
                let dn = (a.normal[i] - b.normal[i]) / (2.0 * h);
                assert!((dn - c.dn_dp[i][j]).abs() < 1e-5, "dn[{i}][{j}]");
                let du = (a.surface_velocity[i] - b.surface_velocity[i]) / (2.0 * h);
                assert!((du - c.dus_dp[i][j]).abs() < 1e-5, "dus[{i}][{j}]");
            }
        }
    }

    // Reference: finite differences of the closest-point map, and the analytic distance.
    #[test]
    fn disk_closest_point_and_derivatives() {
        let d = Disk {
            center: [0.2, -0.1],
            radius: 0.08125,
            velocity: [0.1, 0.0],
            omega: 12.0,
        };
        let p = [0.25, -0.03];
        let c = d.closest(p);
        let rho = ((0.05f64).powi(2) + (0.07f64).powi(2)).sqrt();
        assert!((c.gap - (rho - 0.08125)).abs() < 1e-15);
        // surface speed ω R along t, plus the centre velocity
        let t = rot90(c.normal);
        let us = [0.1 + 12.0 * 0.08125 * t[0], 12.0 * 0.08125 * t[1]];
        assert!((c.surface_velocity[0] - us[0]).abs() < 1e-15);
        fd_check(&d, p);
    }

    // Reference: the cleat dominates near its crest, the drum elsewhere; union distance.
    #[test]
    fn cleated_drum_and_road() {
        let drum = CleatedDrum {
            drum: Disk::fixed([0.0, 0.0], 1.25),
            cleat_radius: 0.01,
            cleat_angle: std::f64::consts::FRAC_PI_2,
        };
        let top = drum.closest([0.0, 1.27]);
        assert_eq!(top.part, 1);
        assert!((top.gap - 0.01).abs() < 1e-12);
        let side = drum.closest([1.27, 0.0]);
        assert_eq!(side.part, 0);
        assert!((side.gap - 0.02).abs() < 1e-12);
        fd_check(&drum, [0.003, 1.262]);
        let road = CleatedRoad {
            height: 0.0,
            cleat_radius: 0.01,
            cleat_x: 1.0,
        };
        assert!((road.closest([1.0, 0.015]).gap - 0.005).abs() < 1e-15);
        assert!((road.closest([0.5, 0.015]).gap - 0.015).abs() < 1e-15);
        fd_check(&road, [1.004, 0.012]);
    }
}
