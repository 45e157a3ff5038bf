//! Spatial obstacle surfaces: a rotating, optionally crowned cylinder and a half-space.
//!
//! Every shape answers [`Surface::closest`] (`D = 3`): the signed gap (negative when
//! penetrating), the outward unit normal, the surface material velocity, a reference tangent,
//! and the derivatives of normal and surface velocity with respect to the query point.

use crate::geometry::{Surface, SurfacePoint};
use nalgebra::{Matrix3, Point3, Vector3};
use serde::{Deserialize, Serialize};

/// Contact data of a query point against a spatial surface.
pub type SurfacePoint3 = SurfacePoint<3>;

/// A unit vector normal to the unit vector `a` (`a × x`, or `y` when `a` is along `x`): the
/// fallback direction where the geometry leaves one undefined (a point on a cylinder's axis, a
/// reference tangent along the normal).
pub fn perpendicular(a: &Vector3<f64>) -> Vector3<f64> {
    a.cross(&Vector3::x())
        .try_normalize(0.0)
        .unwrap_or(Vector3::y())
}

/// A rigid cylinder (pulley, drum) about the unit `axis` through `center`, turning at `omega`
/// \[rad/s\] (right-handed about `axis`), its centre moving with `velocity`. With `crown = c > 0`
/// the radius is parabolic along the axis, `R(ζ) = R − c ζ²` (a crowned pulley, Kerkkänen
/// ch. 4), `ζ = aᵀ(p − r_o)`. The gap is the radial one, `g = ρ − R(ζ)` (ρ the distance from the
/// axis; Kerkkänen (3.21) in each cross-section), with normal `n = ∇g/|∇g|`,
/// `∇g = e_r + 2cζ a`. For `c = 0` this is the planar [`crate::Disk`] in every cross-section.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Cylinder {
    /// Axis point `r_o` \[m\].
    #[schemars(with = "[f64; 3]")]
    pub center: Point3<f64>,
    /// Unit axis `a`.
    #[schemars(with = "[f64; 3]")]
    pub axis: Vector3<f64>,
    /// Radius `R` at `ζ = 0` \[m\].
    pub radius: f64,
    /// Crown coefficient `c` \[1/m\] (0: straight cylinder).
    pub crown: f64,
    /// Velocity of the axis point \[m/s\].
    #[schemars(with = "[f64; 3]")]
    pub velocity: Vector3<f64>,
    /// Angular velocity about `axis` \[rad/s\].
    pub omega: f64,
}

impl Cylinder {
    /// The closest-point data of `p`; the derivatives `dn_dp`, `dus_dp` only when `derivatives`
    /// (zero otherwise).
    fn closest_point(&self, p: &Point3<f64>, derivatives: bool) -> SurfacePoint<3> {
        let a = self.axis;
        let d = p - self.center;
        let zeta = a.dot(&d);
        let radial = d - a * zeta;
        let rho = radial.norm();
        let (er, inv) = if rho > 0.0 {
            (radial / rho, 1.0 / rho)
        } else {
            (perpendicular(&a), 0.0)
        };
        let r = self.radius - self.crown * zeta * zeta;
        let drdz = -2.0 * self.crown * zeta;
        let m = er - a * drdz;
        let mn = m.norm();
        let n = m / mn;
        let circ = a.cross(&er);
        let w = self.omega;
        let (dn, dus) = if derivatives {
            let proj = Matrix3::identity() - a * a.transpose();
            // ∂e_r/∂p = (I − a aᵀ − e_r e_rᵀ)/ρ
            let der = (proj - er * er.transpose()) * inv;
            // ∂m/∂p = ∂e_r/∂p + 2c a aᵀ
            let dm = der + a * a.transpose() * (2.0 * self.crown);
            let dn = (Matrix3::identity() - n * n.transpose()) * dm / mn;
            let cross_a = a.cross_matrix();
            // u_s = ṙ_o + ω R(ζ) a × e_r ⇒ ∂u_s/∂p = ω [(a × e_r) R' aᵀ + R [a]× ∂e_r/∂p]
            let dus = (circ * a.transpose() * drdz + cross_a * der * r) * w;
            (dn, dus)
        } else {
            (Matrix3::zeros(), Matrix3::zeros())
        };
        SurfacePoint {
            gap: rho - r,
            normal: n,
            gap_gradient: m,
            tangent: circ,
            point: self.center + a * zeta + er * r,
            surface_velocity: self.velocity + circ * (w * r),
            dn_dp: dn,
            dus_dp: dus,
            dus_domega: circ * r,
            part: 0,
        }
    }
}

impl Surface<3> for Cylinder {
    /// `u_s = ṙ_o + ω R(ζ) (a × e_r)` (nominal radius, as Kerkkänen (3.24)–(3.25)).
    fn closest(&self, p: &Point3<f64>) -> SurfacePoint<3> {
        self.closest_point(p, true)
    }
    fn closest_value(&self, p: &Point3<f64>) -> SurfacePoint<3> {
        self.closest_point(p, false)
    }
    fn center(&self) -> Point3<f64> {
        self.center
    }
}

/// A half-space (flat road): material opposite to the unit `normal`, surface through `origin`,
/// moving tangentially with `velocity` \[m/s\]; `tangent` is the first tangent axis (e.g. the
/// rolling direction).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct HalfSpace {
    /// A point of the surface \[m\].
    #[schemars(with = "[f64; 3]")]
    pub origin: Point3<f64>,
    /// Outward unit normal.
    #[schemars(with = "[f64; 3]")]
    pub normal: Vector3<f64>,
    /// Unit tangent `t₁` (orthogonal to `normal`).
    #[schemars(with = "[f64; 3]")]
    pub tangent: Vector3<f64>,
    /// Surface material velocity \[m/s\].
    #[schemars(with = "[f64; 3]")]
    pub velocity: Vector3<f64>,
}

impl Surface<3> for HalfSpace {
    fn closest(&self, p: &Point3<f64>) -> SurfacePoint<3> {
        let g = (p - self.origin).dot(&self.normal);
        SurfacePoint {
            gap: g,
            normal: self.normal,
            gap_gradient: self.normal,
            tangent: self.tangent,
            point: p - self.normal * g,
            surface_velocity: self.velocity,
            dn_dp: Matrix3::zeros(),
            dus_dp: Matrix3::zeros(),
            dus_domega: Vector3::zeros(),
            part: 0,
        }
    }
    fn center(&self) -> Point3<f64> {
        self.origin
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::geometry::Disk;
    use nalgebra::{Point2, Vector2};

    /// A crowned, moving cylinder in a general position (shared with the flanged pulley's
    /// tests).
    pub(crate) fn crowned() -> Cylinder {
        Cylinder {
            center: Point3::new(0.1, -0.2, 0.05),
            axis: Vector3::new(0.3, 0.1, 1.0).normalize(),
            radius: 0.08,
            crown: 0.8,
            velocity: Vector3::new(0.1, 0.0, -0.2),
            omega: 12.0,
        }
    }

    /// Central differences of the gap, normal and surface velocity of `c` at `p` against the
    /// closest-point derivatives; the gap gradient lies along the normal.
    pub(crate) fn fd_check3(c: &dyn Surface<3>, p: Point3<f64>) {
        let s = c.closest(&p);
        let h = 1e-7;
        let mut grad = Vector3::zeros();
        for j in 0..3 {
            let mut e = Vector3::zeros();
            e[j] = h;
            let (a, b) = (c.closest(&(p + e)), c.closest(&(p - e)));
            assert_eq!((a.part, b.part), (s.part, s.part), "part switch within h");
            grad[j] = (a.gap - b.gap) / (2.0 * h);
            let dn = (a.normal - b.normal) / (2.0 * h);
            let du = (a.surface_velocity - b.surface_velocity) / (2.0 * h);
            for i in 0..3 {
                assert!((dn[i] - s.dn_dp[(i, j)]).abs() < 1e-5, "dn[{i}][{j}]");
                assert!((du[i] - s.dus_dp[(i, j)]).abs() < 1e-5, "dus[{i}][{j}]");
            }
        }
        // the gap gradient, along the normal
        assert!((grad - s.gap_gradient).amax() < 1e-6);
        assert!((s.gap_gradient.normalize() - s.normal).amax() < 1e-15);
    }

    // Reference: central differences of the gap, normal and surface velocity.
    #[test]
    fn cylinder_derivatives() {
        fd_check3(&crowned(), Point3::new(0.17, -0.16, 0.08));
    }

    // Reference: a straight cylinder about z is the planar disk in every cross-section.
    #[test]
    fn straight_cylinder_is_the_disk() {
        let disk = Disk {
            center: Point2::new(0.2, -0.1),
            radius: 0.08125,
            velocity: Vector2::new(0.1, 0.0),
            omega: 12.0,
        };
        let cyl = Cylinder {
            center: Point3::new(0.2, -0.1, 0.0),
            axis: Vector3::z(),
            radius: 0.08125,
            crown: 0.0,
            velocity: Vector3::new(0.1, 0.0, 0.0),
            omega: 12.0,
        };
        let a = disk.closest(&Point2::new(0.25, -0.03));
        let b = cyl.closest(&Point3::new(0.25, -0.03, 0.4));
        assert!((a.gap - b.gap).abs() < 1e-15);
        for i in 0..2 {
            assert!((a.normal[i] - b.normal[i]).abs() < 1e-15);
            assert!((a.surface_velocity[i] - b.surface_velocity[i]).abs() < 1e-15);
            for j in 0..2 {
                assert!((a.dn_dp[(i, j)] - b.dn_dp[(i, j)]).abs() < 1e-12);
                assert!((a.dus_dp[(i, j)] - b.dus_dp[(i, j)]).abs() < 1e-12);
            }
        }
    }
}
