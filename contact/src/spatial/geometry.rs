//! Spatial obstacle surfaces: a rotating, optionally crowned cylinder and a half-space.
//!
//! Every shape answers [`Surface::closest`] (`D = 3`): the signed gap (negative when
//! penetrating), the outward unit normal, the surface material velocity, a reference tangent,
//! and the derivatives of normal and surface velocity with respect to the query point.

use crate::geometry::{Surface, SurfacePoint, SurfaceValues};
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

/// The closest-point quantities of a query point against a [`Cylinder`] shared by the value
/// and the derivative evaluations.
struct CylinderFrame {
    zeta: f64,
    er: Vector3<f64>,
    inv_rho: f64,
    rho: f64,
    radius: f64,
    drdz: f64,
    m: Vector3<f64>,
    mn: f64,
    n: Vector3<f64>,
    circ: Vector3<f64>,
}

impl Cylinder {
    /// The axial coordinate `ζ`, radial unit vector `e_r`, radius `R(ζ)`, gap gradient `m` and
    /// normal `n = m/|m|` of `p`, and the circumferential direction `a × e_r`.
    #[inline(always)]
    fn frame(&self, p: &Point3<f64>) -> CylinderFrame {
        let a = self.axis;
        let d = p - self.center;
        let zeta = a.dot(&d);
        let radial = d - a * zeta;
        let rho = radial.norm();
        let (er, inv_rho) = if rho > 0.0 {
            (radial / rho, 1.0 / rho)
        } else {
            (perpendicular(&a), 0.0)
        };
        let radius = self.radius - self.crown * zeta * zeta;
        let drdz = -2.0 * self.crown * zeta;
        let m = er - a * drdz;
        let mn = m.norm();
        CylinderFrame {
            zeta,
            er,
            inv_rho,
            rho,
            radius,
            drdz,
            m,
            mn,
            n: m / mn,
            circ: a.cross(&er),
        }
    }

    /// The closest-point data of the frame `f`, with the derivatives `dn_dp`, `dus_dp` given.
    #[inline(always)]
    fn surface_point(
        &self, f: &CylinderFrame, dn_dp: Matrix3<f64>, dus_dp: Matrix3<f64>,
    ) -> SurfacePoint<3> {
        SurfacePoint {
            gap: f.rho - f.radius,
            normal: f.n,
            gap_gradient: f.m,
            tangent: f.circ,
            point: self.center + self.axis * f.zeta + f.er * f.radius,
            surface_velocity: self.velocity + f.circ * (self.omega * f.radius),
            dn_dp,
            dus_dp,
            dus_domega: f.circ * f.radius,
            part: 0,
        }
    }
}

impl Surface<3> for Cylinder {
    /// `u_s = ṙ_o + ω R(ζ) (a × e_r)` (nominal radius, as Kerkkänen (3.24)–(3.25)).
    fn closest(&self, p: &Point3<f64>) -> SurfacePoint<3> {
        let f = self.frame(p);
        let a = self.axis;
        let proj = Matrix3::identity() - a * a.transpose();
        // ∂e_r/∂p = (I − a aᵀ − e_r e_rᵀ)/ρ
        let der = (proj - f.er * f.er.transpose()) * f.inv_rho;
        // ∂m/∂p = ∂e_r/∂p + 2c a aᵀ
        let dm = der + a * a.transpose() * (2.0 * self.crown);
        let dn = (Matrix3::identity() - f.n * f.n.transpose()) * dm / f.mn;
        // u_s = ṙ_o + ω R(ζ) a × e_r ⇒ ∂u_s/∂p = ω [(a × e_r) R' aᵀ + R [a]× ∂e_r/∂p]
        let dus =
            (f.circ * a.transpose() * f.drdz + a.cross_matrix() * der * f.radius) * self.omega;
        self.surface_point(&f, dn, dus)
    }
    #[inline(always)]
    fn closest_value(&self, p: &Point3<f64>) -> SurfacePoint<3> {
        let f = self.frame(p);
        self.surface_point(&f, Matrix3::zeros(), Matrix3::zeros())
    }
    /// The batch of [`Cylinder::closest_value`]s in one loop over the points (same operations
    /// per point, so the same values to the last bit), compiled for the machine's vector width
    /// ([`mbd_core::simd`]).
    fn closest_values(&self, p: &[Vec<f64>; 3], out: &mut SurfaceValues<3>) {
        out.resize(p[0].len());
        mbd_core::simd::dispatch(CylinderValues { c: self, p, out });
    }
    fn center(&self) -> Point3<f64> {
        self.center
    }
}

/// [`Cylinder::closest_values`] as a [`mbd_core::simd::Kernel`] (`out` sized to the batch):
/// the operations of [`Cylinder::closest_value`] (its `frame`) written out component by
/// component on plain `f64`s, with the axis, centre and the rest of the cylinder's constants
/// hoisted and the `ρ > 0` branch as a select, so that the loop runs vectorised (the square
/// roots and divisions of four points at once; with nalgebra's vectors and the branch it ran one
/// point at a time). Every value is formed by the same operations in the same order as
/// nalgebra's (`dot` = `(x₀y₀ + x₁y₁) + x₂y₂`, `norm` = `√(0 + dot)`, the cross product
/// componentwise, division by a scalar componentwise), so the batch equals `closest_value` to
/// the last bit (test `cylinder_batch_equals_point_by_point`).
struct CylinderValues<'a> {
    c: &'a Cylinder,
    p: &'a [Vec<f64>; 3],
    out: &'a mut SurfaceValues<3>,
}

impl mbd_core::simd::Kernel for CylinderValues<'_> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        let (c, p) = (self.c, self.p);
        let n = p[0].len();
        let (px, py, pz) = (&p[0][..n], &p[1][..n], &p[2][..n]);
        let out = self.out;
        let gap = &mut out.gap[..n];
        let [nx, ny, nz] = &mut out.normal;
        let [tx, ty, tz] = &mut out.tangent;
        let [ux, uy, uz] = &mut out.surface_velocity;
        let (nx, ny, nz) = (&mut nx[..n], &mut ny[..n], &mut nz[..n]);
        let (tx, ty, tz) = (&mut tx[..n], &mut ty[..n], &mut tz[..n]);
        let (ux, uy, uz) = (&mut ux[..n], &mut uy[..n], &mut uz[..n]);
        let (a0, a1, a2) = (c.axis.x, c.axis.y, c.axis.z);
        let (c0, c1, c2) = (c.center.x, c.center.y, c.center.z);
        let (v0, v1, v2) = (c.velocity.x, c.velocity.y, c.velocity.z);
        let perp = perpendicular(&c.axis);
        let (radius0, crown, omega) = (c.radius, c.crown, c.omega);
        // groups of LANES points through local arrays (the output arrays are separate `Vec`s
        // the vectoriser cannot prove apart; local arrays it can)
        const LANES: usize = 4;
        let mut start = 0;
        while start < n {
            let len = (n - start).min(LANES);
            let lane = |a: &[f64]| crate::lanes::gather::<LANES>(a, start, len);
            let (x, y, z) = (lane(px), lane(py), lane(pz));
            let mut o = [[0.0; LANES]; 10];
            for l in 0..LANES {
                // d = p − r_o, ζ = aᵀd, radial = d − a ζ, ρ = |radial|
                let (d0, d1, d2) = (x[l] - c0, y[l] - c1, z[l] - c2);
                let zeta = a0 * d0 + a1 * d1 + a2 * d2;
                let (r0, r1, r2) = (d0 - a0 * zeta, d1 - a1 * zeta, d2 - a2 * zeta);
                let rho = (0.0 + (r0 * r0 + r1 * r1 + r2 * r2)).sqrt();
                // e_r = radial/ρ, or perpendicular(a) on the axis
                let on = rho > 0.0;
                let e0 = if on { r0 / rho } else { perp.x };
                let e1 = if on { r1 / rho } else { perp.y };
                let e2 = if on { r2 / rho } else { perp.z };
                let radius = radius0 - crown * zeta * zeta;
                let drdz = -2.0 * crown * zeta;
                // m = e_r − a R', n = m/|m|, circ = a × e_r
                let (m0, m1, m2) = (e0 - a0 * drdz, e1 - a1 * drdz, e2 - a2 * drdz);
                let mn = (0.0 + (m0 * m0 + m1 * m1 + m2 * m2)).sqrt();
                let (k0, k1, k2) = (a1 * e2 - a2 * e1, a2 * e0 - a0 * e2, a0 * e1 - a1 * e0);
                let wr = omega * radius;
                o[0][l] = rho - radius;
                (o[1][l], o[2][l], o[3][l]) = (m0 / mn, m1 / mn, m2 / mn);
                (o[4][l], o[5][l], o[6][l]) = (k0, k1, k2);
                (o[7][l], o[8][l], o[9][l]) = (v0 + k0 * wr, v1 + k1 * wr, v2 + k2 * wr);
            }
            let outs: [&mut [f64]; 10] = [
                &mut gap[start..start + len],
                &mut nx[start..start + len],
                &mut ny[start..start + len],
                &mut nz[start..start + len],
                &mut tx[start..start + len],
                &mut ty[start..start + len],
                &mut tz[start..start + len],
                &mut ux[start..start + len],
                &mut uy[start..start + len],
                &mut uz[start..start + len],
            ];
            for (dst, src) in outs.into_iter().zip(&o) {
                dst.copy_from_slice(&src[..len]);
            }
            start += len;
        }
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

    // Reference (second formulation): the batch `closest_values` of a crowned, moving cylinder
    // against `closest_value` point by point, bit for bit, on points in contact and apart (and
    // the trait's default batch, point by point, on a half-space).
    #[test]
    fn cylinder_batch_equals_point_by_point() {
        let c = crowned();
        let pts: Vec<Point3<f64>> = (0..37)
            .map(|k| {
                let (th, z) = (0.17 * k as f64, -0.05 + 0.003 * k as f64);
                let r = 0.07 + 0.0007 * k as f64;
                c.center + Vector3::new(r * th.cos(), r * th.sin(), z)
            })
            .chain([c.center + c.axis * 0.02, c.center])
            .collect();
        let soa: [Vec<f64>; 3] = std::array::from_fn(|i| pts.iter().map(|p| p[i]).collect());
        let mut out = SurfaceValues::default();
        let bits = |v: &SurfaceValues<3>| {
            let mut b: Vec<u64> = v.gap.iter().map(|x| x.to_bits()).collect();
            for a in v.normal.iter().chain(&v.tangent).chain(&v.surface_velocity) {
                b.extend(a.iter().map(|x| x.to_bits()));
            }
            b
        };
        // crowned, and straight (c = 0); two points on the axis (ρ = 0: e_r = perpendicular(a))
        let mut straight = c;
        straight.crown = 0.0;
        for cyl in [c, straight] {
            cyl.closest_values(&soa, &mut out);
            assert_eq!(out.len(), pts.len());
            assert!(out.gap.iter().any(|g| *g < 0.0) && out.gap.iter().any(|g| *g > 0.0));
            let mut one = SurfaceValues::default();
            one.resize(pts.len());
            for (q, p) in pts.iter().enumerate() {
                one.set(q, &cyl.closest_value(p));
            }
            assert_eq!(bits(&out), bits(&one), "crown {}", cyl.crown);
        }
        let road = HalfSpace {
            origin: Point3::new(0.0, 0.0, 0.01),
            normal: Vector3::z(),
            tangent: Vector3::x(),
            velocity: Vector3::new(3.0, 0.0, 0.0),
        };
        road.closest_values(&soa, &mut out);
        for (q, p) in pts.iter().enumerate() {
            assert_eq!(out.gap[q], road.closest(p).gap);
        }
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
