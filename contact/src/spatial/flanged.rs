//! A flanged pulley: a (crowned) cylinder with two flanges, modelled as side planes normal to
//! the axis, that keep the belt from running off axially (Kerkkänen ch. 4 discusses crowned and
//! flanged pulleys as the means of lateral belt guidance).

use super::geometry::{Cylinder, perpendicular};
use crate::geometry::{Surface, SurfacePoint};
use nalgebra::{Matrix3, Point3};
use serde::{Deserialize, Serialize};

/// A [`Cylinder`] with flanges at the axial positions `ζ_lo < ζ_hi` (`ζ = aᵀ(p − r_o)`): the
/// flange material fills `ζ ≤ ζ_lo` and `ζ ≥ ζ_hi` (side planes of unbounded radius, turning
/// with the pulley). The obstacle is the union of the three solids, so the signed distance is
/// the smallest of the cylinder gap and the flange gaps `g_lo = ζ − ζ_lo` (normal `+a`) and
/// `g_hi = ζ_hi − ζ` (normal `−a`), each the closest-point projection onto that solid's surface
/// (Wriggers *Computational Contact Mechanics*) — the union rule of the planar
/// [`crate::CleatedDrum`].
/// On a flange the surface moves rigidly with the pulley, `u_s = ṙ_o + ω a × (p − r_o)`
/// (the closest point differs from `p` only along `a`), so `∂u_s/∂p = ω [a]×`,
/// `∂u_s/∂ω = a × (p − r_o)`, and `∂n/∂p = 0`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct FlangedCylinder {
    /// The pulley body.
    pub cylinder: Cylinder,
    /// Axial positions of the inner flange faces `[ζ_lo, ζ_hi]` \[m\].
    pub flanges: [f64; 2],
}

impl FlangedCylinder {
    /// The closest of the cylinder's point `cylinder` (part 0) and the two flanges' points
    /// (parts 1, 2) to `p`; ties go to the lower part index.
    fn nearest_of(&self, cylinder: SurfacePoint<3>, p: &Point3<f64>) -> SurfacePoint<3> {
        let mut best = cylinder;
        for k in 0..2 {
            let f = self.flange(k, p);
            if f.gap < best.gap {
                best = f;
            }
        }
        best
    }

    /// Contact data of flange `k` (0: `ζ_lo`, 1: `ζ_hi`) for the point `p`.
    fn flange(&self, k: usize, p: &Point3<f64>) -> SurfacePoint<3> {
        let c = &self.cylinder;
        let a = c.axis;
        let d = p - c.center;
        let zeta = a.dot(&d);
        let (gap, n) = if k == 0 {
            (zeta - self.flanges[0], a)
        } else {
            (self.flanges[1] - zeta, -a)
        };
        let circ = a.cross(&d);
        let tangent = circ.try_normalize(0.0).unwrap_or_else(|| perpendicular(&a));
        SurfacePoint {
            gap,
            normal: n,
            gap_gradient: n,
            tangent,
            point: p - n * gap,
            surface_velocity: c.velocity + circ * c.omega,
            dn_dp: Matrix3::zeros(),
            dus_dp: a.cross_matrix() * c.omega,
            dus_domega: circ,
            part: k + 1,
        }
    }
}

impl Surface<3> for FlangedCylinder {
    /// The closest of the cylinder (part 0), the lower flange (part 1) and the upper flange
    /// (part 2); ties go to the lower part index.
    fn closest(&self, p: &Point3<f64>) -> SurfacePoint<3> {
        self.nearest_of(self.cylinder.closest(p), p)
    }
    fn closest_value(&self, p: &Point3<f64>) -> SurfacePoint<3> {
        self.nearest_of(self.cylinder.closest_value(p), p)
    }
    fn center(&self) -> Point3<f64> {
        self.cylinder.center
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::geometry::tests::{crowned, fd_check3};
    use nalgebra::Vector3;

    fn pulley() -> FlangedCylinder {
        FlangedCylinder {
            cylinder: crowned(),
            flanges: [-0.02, 0.03],
        }
    }

    /// The point at axial position `zeta` and radial distance `rho` (direction `(1, 0, 0)`
    /// made normal to the axis).
    fn at(f: &FlangedCylinder, zeta: f64, rho: f64) -> Point3<f64> {
        let a = f.cylinder.axis;
        let er = (Vector3::x() - a * a.x).normalize();
        f.cylinder.center + a * zeta + er * rho
    }

    // Reference: analytical distances to the side planes and the crowned cylinder, the union
    // rule, and central differences of the closest-point map in each part.
    #[test]
    fn flanges_and_cylinder() {
        let f = pulley();
        // mid-width, just penetrating the cylinder: the cylinder (crowned radius R − cζ²)
        let s = f.closest(&at(&f, 0.0, 0.0795));
        assert_eq!(s.part, 0);
        assert!((s.gap + 0.0005).abs() < 1e-15);
        fd_check3(&f, at(&f, 0.01, 0.0795));
        // pressed into the lower flange near the rim
        let s = f.closest(&at(&f, -0.0203, 0.082));
        assert_eq!(s.part, 1);
        assert!((s.gap + 0.0003).abs() < 1e-14);
        assert!((s.normal - f.cylinder.axis).amax() < 1e-15);
        fd_check3(&f, at(&f, -0.0203, 0.082));
        // pressed into the upper flange
        let s = f.closest(&at(&f, 0.0304, 0.09));
        assert_eq!(s.part, 2);
        assert!((s.gap + 0.0004).abs() < 1e-14);
        fd_check3(&f, at(&f, 0.0304, 0.09));
        // the flange surface turns with the pulley: u_s = ṙ_o + ω a × (x_s − r_o)
        let c = f.cylinder;
        let us = c.velocity + c.axis.cross(&(s.point - c.center)) * c.omega;
        assert!((us - s.surface_velocity).amax() < 1e-15);
        // ∂u_s/∂ω by central differences, on a flange and on the cylinder
        for p in [at(&f, 0.0304, 0.09), at(&f, 0.01, 0.0795)] {
            let with = |w: f64| {
                let mut g = f;
                g.cylinder.omega = w;
                g.closest(&p).surface_velocity
            };
            let fd = (with(12.0 + 1e-6) - with(12.0 - 1e-6)) / 2e-6;
            assert!((fd - f.closest(&p).dus_domega).amax() < 1e-8);
        }
    }
}
