//! Contact geometry in `D = 2` or `3` dimensions: the closest-point data [`SurfacePoint`] that
//! every obstacle answers through [`Surface::closest`], and the planar shapes — disks (pulleys,
//! drums; moving and rotating), half-planes (flat road) and unions of them (a drum or a road
//! with a semicircular cleat, Ribaric ch. 8). The spatial shapes are in [`crate::spatial`].
//!
//! Every shape answers [`Surface::closest`]: the signed distance (gap, negative when the point
//! penetrates), the outward unit normal at the closest surface point, the velocity of the
//! surface material there, and the derivatives of normal and surface velocity with respect to
//! the query point (needed for contact Jacobians).

use nalgebra::{Matrix2, Point, Point2, SMatrix, SVector, Vector2};
use serde::{Deserialize, Serialize};

pub use crate::dim::rot90;

/// Closest-point data of a query point `p` against a `D`-dimensional obstacle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint<const D: usize> {
    /// Signed gap \[m\] (> 0 separated, < 0 penetrating; penetration `d = −gap`).
    pub gap: f64,
    /// Outward unit normal `n` of the obstacle at the closest point.
    pub normal: SVector<f64, D>,
    /// `∂g/∂p` (parallel to `n`; `n` itself for an exact distance).
    pub gap_gradient: SVector<f64, D>,
    /// Reference unit tangent: in space the first tangent-plane axis `t₁` before projection
    /// (`t₂ = n × t₁`), e.g. the circumferential direction of a cylinder; in the plane always
    /// `t = Ĩ n` (Kerkkänen (3.6)).
    pub tangent: SVector<f64, D>,
    /// Closest point on the surface \[m\].
    pub point: Point<f64, D>,
    /// Velocity of the obstacle's surface material at the closest point \[m/s\].
    pub surface_velocity: SVector<f64, D>,
    /// `∂n/∂p` \[1/m\].
    pub dn_dp: SMatrix<f64, D, D>,
    /// `∂u_s/∂p` \[1/s\].
    pub dus_dp: SMatrix<f64, D, D>,
    /// `∂u_s/∂ω` \[m\] (surface velocity per unit angular velocity of the obstacle).
    pub dus_domega: SVector<f64, D>,
    /// Index of the primitive that produced the point (0 for simple shapes; for unions the
    /// member index, e.g. 1 for a cleat, 1 and 2 for the flanges of a
    /// [`crate::spatial::FlangedCylinder`]).
    pub part: usize,
}

/// A rigid obstacle surface in `D` dimensions.
pub trait Surface<const D: usize> {
    /// Closest-point query for the point `p` \[m\].
    fn closest(&self, p: &Point<f64, D>) -> SurfacePoint<D>;
    /// [`Surface::closest`] where only the values are needed (gap, normal, gap gradient,
    /// tangent, point, surface velocity, `∂u_s/∂ω`, part): a shape may leave the derivatives
    /// `dn_dp` and `dus_dp` zero to save their cost (force-only evaluations). Default: `closest`.
    fn closest_value(&self, p: &Point<f64, D>) -> SurfacePoint<D> {
        self.closest(p)
    }
    /// [`Surface::closest_value`] of a batch of points given in structure-of-arrays form
    /// (coordinate `i` of point `q` at `p[i][q]`), into `out` (resized to the batch): the
    /// values a force-only evaluation needs. A shape may override it with loops over the
    /// batch (independent square roots and divisions pipelined or vectorised, where one
    /// point at a time waits for each); the default queries point by point.
    fn closest_values(&self, p: &[Vec<f64>; D], out: &mut SurfaceValues<D>) {
        let n = p[0].len();
        out.resize(n);
        for q in 0..n {
            let sp = self.closest_value(&Point::from(SVector::from_fn(|i, _| p[i][q])));
            out.set(q, &sp);
        }
    }
    /// Reference point of the body for moments (pulley axis) \[m\].
    fn center(&self) -> Point<f64, D>;
}

/// Closest-point values of a batch of query points in structure-of-arrays form
/// ([`Surface::closest_values`]): entry `q` of each array belongs to point `q`, component `i`
/// of a vector is in array `i`.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceValues<const D: usize> {
    /// Signed gaps \[m\] ([`SurfacePoint::gap`]).
    pub gap: Vec<f64>,
    /// Outward unit normals ([`SurfacePoint::normal`]).
    pub normal: [Vec<f64>; D],
    /// Reference tangents ([`SurfacePoint::tangent`]).
    pub tangent: [Vec<f64>; D],
    /// Surface material velocities \[m/s\] ([`SurfacePoint::surface_velocity`]).
    pub surface_velocity: [Vec<f64>; D],
}

impl<const D: usize> Default for SurfaceValues<D> {
    fn default() -> Self {
        Self {
            gap: Vec::new(),
            normal: std::array::from_fn(|_| Vec::new()),
            tangent: std::array::from_fn(|_| Vec::new()),
            surface_velocity: std::array::from_fn(|_| Vec::new()),
        }
    }
}

impl<const D: usize> SurfaceValues<D> {
    /// Resizes every array to `n` points (new entries zero).
    pub fn resize(&mut self, n: usize) {
        self.gap.resize(n, 0.0);
        for i in 0..D {
            self.normal[i].resize(n, 0.0);
            self.tangent[i].resize(n, 0.0);
            self.surface_velocity[i].resize(n, 0.0);
        }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.gap.len()
    }

    /// Whether the batch is empty.
    pub fn is_empty(&self) -> bool {
        self.gap.is_empty()
    }

    /// Stores the values of `sp` as point `q`.
    pub fn set(&mut self, q: usize, sp: &SurfacePoint<D>) {
        self.gap[q] = sp.gap;
        for i in 0..D {
            self.normal[i][q] = sp.normal[i];
            self.tangent[i][q] = sp.tangent[i];
            self.surface_velocity[i][q] = sp.surface_velocity[i];
        }
    }
}

impl<const D: usize, S: Surface<D> + ?Sized> Surface<D> for &S {
    fn closest(&self, p: &Point<f64, D>) -> SurfacePoint<D> {
        (**self).closest(p)
    }
    fn closest_value(&self, p: &Point<f64, D>) -> SurfacePoint<D> {
        (**self).closest_value(p)
    }
    fn closest_values(&self, p: &[Vec<f64>; D], out: &mut SurfaceValues<D>) {
        (**self).closest_values(p, out)
    }
    fn center(&self) -> Point<f64, D> {
        (**self).center()
    }
}

/// Closest-point data of a planar obstacle.
pub type SurfacePoint2 = SurfacePoint<2>;

/// A rigid disk (pulley, drum) with centre `center` \[m\], radius `radius` \[m\], translational
/// velocity `velocity` \[m/s\] and angular velocity `omega` \[rad/s\] (counter-clockwise positive).
/// The contacting body is outside the disk.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Disk {
    /// Centre `r_o` \[m\].
    #[schemars(with = "[f64; 2]")]
    pub center: Point2<f64>,
    /// Radius `R` \[m\].
    pub radius: f64,
    /// Velocity of the centre `ṙ_o` \[m/s\].
    #[schemars(with = "[f64; 2]")]
    pub velocity: Vector2<f64>,
    /// Angular velocity `ω` \[rad/s\].
    pub omega: f64,
}

impl Disk {
    /// A fixed, non-rotating disk.
    pub fn fixed(center: Point2<f64>, radius: f64) -> Self {
        Self {
            center,
            radius,
            velocity: Vector2::zeros(),
            omega: 0.0,
        }
    }
}

impl Disk {
    /// The values of [`Surface::closest`] (Kerkkänen (3.21)–(3.22), (3.24)–(3.25)) with the
    /// derivatives `dn_dp`, `dus_dp` zero, and `1/ρ` (`0` at the centre) for them.
    #[inline(always)]
    fn closest_values_of(&self, p: &Point2<f64>) -> (SurfacePoint<2>, f64) {
        let d = [p[0] - self.center[0], p[1] - self.center[1]];
        let rho = (d[0] * d[0] + d[1] * d[1]).sqrt();
        // at the centre any direction is a normal; pick +y to stay finite
        let (n, inv) = if rho > 0.0 {
            (Vector2::new(d[0] / rho, d[1] / rho), 1.0 / rho)
        } else {
            (Vector2::new(0.0, 1.0), 0.0)
        };
        let t = rot90(n);
        let wr = self.omega * self.radius;
        let sp = SurfacePoint {
            gap: rho - self.radius,
            normal: n,
            gap_gradient: n,
            tangent: t,
            point: Point2::new(
                self.center[0] + self.radius * n[0],
                self.center[1] + self.radius * n[1],
            ),
            surface_velocity: Vector2::new(
                self.velocity[0] + wr * t[0],
                self.velocity[1] + wr * t[1],
            ),
            dn_dp: Matrix2::zeros(),
            dus_dp: Matrix2::zeros(),
            dus_domega: Vector2::new(self.radius * t[0], self.radius * t[1]),
            part: 0,
        };
        (sp, inv)
    }
}

impl Surface<2> for Disk {
    /// Kerkkänen (3.21)–(3.22): `d = R − ‖r − r_o‖`, `n = (r − r_o)/‖r − r_o‖`; the surface
    /// velocity is `ṙ_o + ω R t` with `t = Ĩ n` (3.24)–(3.25) (nominal radius `R`).
    fn closest(&self, p: &Point2<f64>) -> SurfacePoint<2> {
        let (mut sp, inv) = self.closest_values_of(p);
        let t = sp.tangent;
        // ∂n/∂p = (I − n nᵀ)/ρ = t tᵀ/ρ
        let dn = Matrix2::new(
            t[0] * t[0] * inv,
            t[0] * t[1] * inv,
            t[1] * t[0] * inv,
            t[1] * t[1] * inv,
        );
        // u_s = ṙ_o + ω R Ĩ n  ⇒ ∂u_s/∂p = ω R Ĩ ∂n/∂p
        let wr = self.omega * self.radius;
        sp.dn_dp = dn;
        sp.dus_dp = Matrix2::new(
            -wr * dn[(1, 0)],
            -wr * dn[(1, 1)],
            wr * dn[(0, 0)],
            wr * dn[(0, 1)],
        );
        sp
    }
    /// [`Surface::closest`] without its derivatives (`dn_dp`, `dus_dp` zero): the same values
    /// by the same operations, for the force-only evaluations.
    fn closest_value(&self, p: &Point2<f64>) -> SurfacePoint<2> {
        self.closest_values_of(p).0
    }
    fn center(&self) -> Point2<f64> {
        self.center
    }
}

/// A half-plane (flat road): material on the side opposite to the unit `normal`, surface
/// through `origin`, moving tangentially with `velocity` \[m/s\] (e.g. a belt-type road).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct HalfPlane {
    /// A point of the surface \[m\].
    #[schemars(with = "[f64; 2]")]
    pub origin: Point2<f64>,
    /// Outward unit normal.
    #[schemars(with = "[f64; 2]")]
    pub normal: Vector2<f64>,
    /// Surface material velocity \[m/s\].
    #[schemars(with = "[f64; 2]")]
    pub velocity: Vector2<f64>,
}

impl HalfPlane {
    /// Fixed ground `y = height` with normal `+y`.
    pub fn ground(height: f64) -> Self {
        Self {
            origin: Point2::new(0.0, height),
            normal: Vector2::new(0.0, 1.0),
            velocity: Vector2::zeros(),
        }
    }
}

impl Surface<2> for HalfPlane {
    fn closest(&self, p: &Point2<f64>) -> SurfacePoint<2> {
        let n = self.normal;
        let g = (p[0] - self.origin[0]) * n[0] + (p[1] - self.origin[1]) * n[1];
        SurfacePoint {
            gap: g,
            normal: n,
            gap_gradient: n,
            tangent: rot90(n),
            point: Point2::new(p[0] - g * n[0], p[1] - g * n[1]),
            surface_velocity: self.velocity,
            dn_dp: Matrix2::zeros(),
            dus_dp: Matrix2::zeros(),
            dus_domega: Vector2::zeros(),
            part: 0,
        }
    }
    fn center(&self) -> Point2<f64> {
        self.origin
    }
}

/// A drum of radius `radius` with a semicircular cleat of radius `cleat_radius` whose centre
/// sits on the drum surface at polar angle `cleat_angle` (Ribaric ch. 8: 10 mm cleat on a
/// 1.25 m drum). The drum rotates with `omega`; advance `cleat_angle` with time.
/// Geometry: union of the drum disk and the cleat disk (signed distance = minimum).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
            center: Point2::new(self.drum.center[0] + r * c, self.drum.center[1] + r * s),
            radius: self.cleat_radius,
            // cleat centre velocity ṙ_o + ω Ĩ (R e)
            velocity: Vector2::new(
                self.drum.velocity[0] - w * r * s,
                self.drum.velocity[1] + w * r * c,
            ),
            omega: w,
        }
    }
}

impl Surface<2> for CleatedDrum {
    fn closest(&self, p: &Point2<f64>) -> SurfacePoint<2> {
        let a = self.drum.closest(p);
        let mut b = self.cleat().closest(p);
        if b.gap < a.gap {
            b.part = 1;
            // the cleat surface moves with the drum: u_s = ṙ_o + ω Ĩ (x_s − r_o)
            b.dus_domega = rot90(b.point - self.drum.center);
            b
        } else {
            a
        }
    }
    fn center(&self) -> Point2<f64> {
        self.drum.center
    }
}

/// Flat road with a semicircular cleat of radius `cleat_radius` centred on the surface at
/// abscissa `cleat_x` (Ribaric §8.5). Union of the half-plane `y ≤ height` and the cleat disk.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct CleatedRoad {
    /// Road surface height \[m\].
    pub height: f64,
    /// Cleat radius \[m\].
    pub cleat_radius: f64,
    /// Cleat centre abscissa \[m\].
    pub cleat_x: f64,
}

impl Surface<2> for CleatedRoad {
    fn closest(&self, p: &Point2<f64>) -> SurfacePoint<2> {
        let a = HalfPlane::ground(self.height).closest(p);
        let mut b =
            Disk::fixed(Point2::new(self.cleat_x, self.height), self.cleat_radius).closest(p);
        if b.gap < a.gap {
            b.part = 1;
            b
        } else {
            a
        }
    }
    fn center(&self) -> Point2<f64> {
        Point2::new(self.cleat_x, self.height)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fd_check(s: &dyn Surface<2>, p: Point2<f64>) {
        let c = s.closest(&p);
        let h = 1e-7;
        for j in 0..2 {
            let mut pp = p;
            let mut pm = p;
            pp[j] += h;
            pm[j] -= h;
            let (a, b) = (s.closest(&pp), s.closest(&pm));
            // ∂gap/∂p = n
            assert!(((a.gap - b.gap) / (2.0 * h) - c.normal[j]).abs() < 1e-6);
            for i in 0..2 {
                let dn = (a.normal[i] - b.normal[i]) / (2.0 * h);
                assert!((dn - c.dn_dp[(i, j)]).abs() < 1e-5, "dn[{i}][{j}]");
                let du = (a.surface_velocity[i] - b.surface_velocity[i]) / (2.0 * h);
                assert!((du - c.dus_dp[(i, j)]).abs() < 1e-5, "dus[{i}][{j}]");
            }
        }
        assert_eq!(c.gap_gradient, c.normal);
        assert_eq!(c.tangent, rot90(c.normal));
    }

    // Reference: finite differences of the closest-point map, and the analytic distance.
    #[test]
    fn disk_closest_point_and_derivatives() {
        let d = Disk {
            center: Point2::new(0.2, -0.1),
            radius: 0.08125,
            velocity: Vector2::new(0.1, 0.0),
            omega: 12.0,
        };
        let p = Point2::new(0.25, -0.03);
        let c = d.closest(&p);
        let rho = ((0.05f64).powi(2) + (0.07f64).powi(2)).sqrt();
        assert!((c.gap - (rho - 0.08125)).abs() < 1e-15);
        // surface speed ω R along t, plus the centre velocity
        let t = rot90(c.normal);
        let us = [0.1 + 12.0 * 0.08125 * t[0], 12.0 * 0.08125 * t[1]];
        assert!((c.surface_velocity[0] - us[0]).abs() < 1e-15);
        assert!((c.surface_velocity[1] - us[1]).abs() < 1e-15);
        fd_check(&d, p);
    }

    // Reference: `Disk::closest` (its values checked above and its derivatives by finite
    // differences): the force-only `closest_value` gives its values to the bit and zero
    // derivatives, also at the centre and on the surface.
    #[test]
    fn disk_closest_value_is_closest_without_derivatives_bit_for_bit() {
        let d = Disk {
            center: Point2::new(0.2, -0.1),
            radius: 0.08125,
            velocity: Vector2::new(0.1, -0.3),
            omega: -37.0,
        };
        let points = [
            Point2::new(0.25, -0.03),
            Point2::new(0.2, -0.1),
            Point2::new(0.2 + 0.08125, -0.1),
            Point2::new(-1.7, 3.3),
            Point2::new(0.21, -0.1 - 1e-9),
        ];
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for p in points {
            let (c, v) = (d.closest(&p), d.closest_value(&p));
            assert_eq!(c.gap.to_bits(), v.gap.to_bits());
            assert_eq!(bits(c.normal.as_slice()), bits(v.normal.as_slice()));
            assert_eq!(
                bits(c.gap_gradient.as_slice()),
                bits(v.gap_gradient.as_slice())
            );
            assert_eq!(bits(c.tangent.as_slice()), bits(v.tangent.as_slice()));
            assert_eq!(
                bits(c.point.coords.as_slice()),
                bits(v.point.coords.as_slice())
            );
            assert_eq!(
                bits(c.surface_velocity.as_slice()),
                bits(v.surface_velocity.as_slice())
            );
            assert_eq!(bits(c.dus_domega.as_slice()), bits(v.dus_domega.as_slice()));
            assert_eq!(c.part, v.part);
            assert_eq!(v.dn_dp, Matrix2::zeros());
            assert_eq!(v.dus_dp, Matrix2::zeros());
        }
    }

    // Reference: the cleat dominates near its crest, the drum elsewhere; union distance.
    #[test]
    fn cleated_drum_and_road() {
        let drum = CleatedDrum {
            drum: Disk::fixed(Point2::new(0.0, 0.0), 1.25),
            cleat_radius: 0.01,
            cleat_angle: std::f64::consts::FRAC_PI_2,
        };
        let top = drum.closest(&Point2::new(0.0, 1.27));
        assert_eq!(top.part, 1);
        assert!((top.gap - 0.01).abs() < 1e-12);
        let side = drum.closest(&Point2::new(1.27, 0.0));
        assert_eq!(side.part, 0);
        assert!((side.gap - 0.02).abs() < 1e-12);
        fd_check(&drum, Point2::new(0.003, 1.262));
        let road = CleatedRoad {
            height: 0.0,
            cleat_radius: 0.01,
            cleat_x: 1.0,
        };
        assert!((road.closest(&Point2::new(1.0, 0.015)).gap - 0.005).abs() < 1e-15);
        assert!((road.closest(&Point2::new(0.5, 0.015)).gap - 0.015).abs() < 1e-15);
        fd_check(&road, Point2::new(1.004, 0.012));
    }
}
