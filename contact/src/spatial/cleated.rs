//! Spatial drums and roads with a cleat: the planar [`crate::CleatedDrum`] and
//! [`crate::CleatedRoad`] (Ribaric ch. 8) extruded along the cleat axis, as the union of the
//! drum cylinder (or the road half-space) and a cleat cylinder; the closest point of the union
//! is the closer of the members' closest-point projections (Wriggers *Computational Contact
//! Mechanics*).

use super::geometry::{Cylinder, HalfSpace};
use crate::geometry::{Surface, SurfacePoint};
use nalgebra::{Point3, Vector3};
use serde::{Deserialize, Serialize};

/// A straight drum ([`Cylinder`], `crown = 0`) with a cleat of radius `cleat_radius` along its
/// full width, the cleat axis on the drum surface at polar angle `cleat_angle` measured from
/// the unit `reference` direction (normal to the drum axis) towards `axis × reference`. The
/// drum turns with `omega`; advance `cleat_angle` with time. With `axis = z`,
/// `reference = x` every cross-section is the planar [`crate::CleatedDrum`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct CleatedDrum3 {
    /// The drum.
    pub drum: Cylinder,
    /// Unit direction of polar angle 0, normal to the drum axis.
    #[schemars(with = "[f64; 3]")]
    pub reference: Vector3<f64>,
    /// Cleat radius \[m\].
    pub cleat_radius: f64,
    /// Polar angle of the cleat axis \[rad\].
    pub cleat_angle: f64,
}

impl CleatedDrum3 {
    /// Radial direction `e_c` of the cleat axis.
    fn cleat_direction(&self) -> Vector3<f64> {
        let (s, c) = self.cleat_angle.sin_cos();
        self.reference * c + self.drum.axis.cross(&self.reference) * s
    }

    /// The cleat as a cylinder moving with the drum surface: axis point `r_o + R e_c`,
    /// velocity `ṙ_o + ω R (a × e_c)`, same angular velocity.
    pub fn cleat(&self) -> Cylinder {
        let d = &self.drum;
        let ec = self.cleat_direction();
        Cylinder {
            center: d.center + ec * d.radius,
            axis: d.axis,
            radius: self.cleat_radius,
            crown: 0.0,
            velocity: d.velocity + d.axis.cross(&ec) * (d.omega * d.radius),
            omega: d.omega,
        }
    }
}

impl Surface<3> for CleatedDrum3 {
    /// The closer of the drum (part 0) and the cleat (part 1). On the cleat the surface moves
    /// rigidly with the drum, `u_s = ṙ_o + ω a × (x_s − r_o)`, so `∂u_s/∂ω = a × (x_s − r_o)`
    /// (the cleat axis moves with `ω` too).
    fn closest(&self, p: &Point3<f64>) -> SurfacePoint<3> {
        let a = self.drum.closest(p);
        let mut b = self.cleat().closest(p);
        if b.gap < a.gap {
            b.part = 1;
            b.dus_domega = self.drum.axis.cross(&(b.point - self.drum.center));
            b
        } else {
            a
        }
    }
    fn center(&self) -> Point3<f64> {
        self.drum.center
    }
}

/// A road ([`HalfSpace`]) with a cleat of radius `cleat_radius` whose axis lies on the road
/// surface along `tangent × normal`, at distance `cleat_offset` from the road origin along the
/// road tangent. The cleat moves with the road material (`road.velocity`) and does not turn.
/// With `normal = y`, `tangent = x` every cross-section is the planar [`crate::CleatedRoad`]
/// (`cleat_x = origin.x + cleat_offset`, `height = origin.y`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct CleatedRoad3 {
    /// The road.
    pub road: HalfSpace,
    /// Cleat radius \[m\].
    pub cleat_radius: f64,
    /// Position of the cleat axis along `road.tangent` from `road.origin` \[m\].
    pub cleat_offset: f64,
}

impl CleatedRoad3 {
    /// The cleat as a non-rotating cylinder moving with the road.
    pub fn cleat(&self) -> Cylinder {
        let r = &self.road;
        Cylinder {
            center: r.origin + r.tangent * self.cleat_offset,
            axis: r.tangent.cross(&r.normal),
            radius: self.cleat_radius,
            crown: 0.0,
            velocity: r.velocity,
            omega: 0.0,
        }
    }
}

impl Surface<3> for CleatedRoad3 {
    /// The closer of the road (part 0) and the cleat (part 1); neither turns, so
    /// `∂u_s/∂ω = 0`.
    fn closest(&self, p: &Point3<f64>) -> SurfacePoint<3> {
        let a = self.road.closest(p);
        let mut b = self.cleat().closest(p);
        if b.gap < a.gap {
            b.part = 1;
            b.dus_domega = Vector3::zeros();
            b
        } else {
            a
        }
    }
    fn center(&self) -> Point3<f64> {
        self.cleat().center
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{CleatedDrum, CleatedRoad, Disk};
    use crate::spatial::geometry::tests::fd_check3;
    use nalgebra::{Point2, Vector2};

    /// The planar and spatial closest points agree in the cross-section.
    fn same(a: &SurfacePoint<2>, b: &SurfacePoint<3>, omega_too: bool) {
        assert_eq!(a.part, b.part);
        assert!((a.gap - b.gap).abs() < 1e-14, "{} vs {}", a.gap, b.gap);
        for i in 0..2 {
            assert!((a.normal[i] - b.normal[i]).abs() < 1e-13);
            assert!((a.point[i] - b.point[i]).abs() < 1e-14);
            assert!((a.surface_velocity[i] - b.surface_velocity[i]).abs() < 1e-13);
            if omega_too {
                assert!((a.dus_domega[i] - b.dus_domega[i]).abs() < 1e-14);
            }
            for j in 0..2 {
                assert!((a.dn_dp[(i, j)] - b.dn_dp[(i, j)]).abs() < 1e-10);
                assert!((a.dus_dp[(i, j)] - b.dus_dp[(i, j)]).abs() < 1e-10);
            }
        }
        assert!(b.normal.z.abs() < 1e-15 && b.surface_velocity.z.abs() < 1e-15);
    }

    // Reference (second formulation): the planar CleatedDrum in every cross-section; central
    // differences of the closest-point map on the drum and on the cleat, off-plane axis.
    #[test]
    fn cleated_drum_is_the_extruded_planar_drum() {
        let planar = CleatedDrum {
            drum: Disk {
                center: Point2::new(0.1, -0.05),
                radius: 1.25,
                velocity: Vector2::new(0.2, 0.1),
                omega: 3.0,
            },
            cleat_radius: 0.01,
            cleat_angle: 1.3,
        };
        let spatial = CleatedDrum3 {
            drum: Cylinder {
                center: Point3::new(0.1, -0.05, 0.0),
                axis: Vector3::z(),
                radius: 1.25,
                crown: 0.0,
                velocity: Vector3::new(0.2, 0.1, 0.0),
                omega: 3.0,
            },
            reference: Vector3::x(),
            cleat_radius: 0.01,
            cleat_angle: 1.3,
        };
        let tip = planar.cleat().center;
        for p in [
            [tip[0] + 0.002, tip[1] + 0.008],
            [tip[0] - 0.003, tip[1] + 0.0],
            [0.1 + 1.2, -0.05 + 0.3],
        ] {
            let a = planar.closest(&Point2::from(p));
            let b = spatial.closest(&Point3::new(p[0], p[1], 0.7));
            same(&a, &b, true);
            fd_check3(&spatial, Point3::new(p[0], p[1], -0.2));
        }
        assert_eq!(
            spatial
                .closest(&Point3::new(tip[0], tip[1] + 0.0105, 0.0))
                .part,
            1
        );
        // a tilted drum: derivatives on the cleat and on the drum
        let mut tilted = spatial;
        tilted.drum.axis = Vector3::new(0.2, -0.1, 1.0).normalize();
        let a = tilted.drum.axis;
        tilted.reference = (Vector3::x() - a * a.x).normalize();
        let c = tilted.cleat();
        let on_cleat = c.center + a * 0.3 + tilted.reference * 0.0098;
        assert_eq!(tilted.closest(&on_cleat).part, 1);
        fd_check3(&tilted, on_cleat);
        // ∂u_s/∂ω by central differences on the cleat (its axis moves with the drum)
        let with = |w: f64| {
            let mut g = tilted;
            g.drum.omega = w;
            g.closest(&on_cleat).surface_velocity
        };
        let fd = (with(3.0 + 1e-6) - with(3.0 - 1e-6)) / 2e-6;
        assert!((fd - tilted.closest(&on_cleat).dus_domega).amax() < 1e-8);
        fd_check3(
            &tilted,
            tilted.drum.center + a * 0.1 - tilted.reference * 1.249,
        );
    }

    // Reference (second formulation): the planar CleatedRoad in every cross-section; central
    // differences on the road and on the cleat.
    #[test]
    fn cleated_road_is_the_extruded_planar_road() {
        let planar = CleatedRoad {
            height: 0.02,
            cleat_radius: 0.01,
            cleat_x: 1.0,
        };
        let spatial = CleatedRoad3 {
            road: HalfSpace {
                origin: Point3::new(0.4, 0.02, 0.0),
                normal: Vector3::y(),
                tangent: Vector3::x(),
                velocity: Vector3::zeros(),
            },
            cleat_radius: 0.01,
            cleat_offset: 0.6,
        };
        for p in [[1.004, 0.032], [0.998, 0.025], [0.5, 0.019], [1.2, 0.021]] {
            let a = planar.closest(&Point2::from(p));
            let b = spatial.closest(&Point3::new(p[0], p[1], -0.3));
            // the planar road's cleat is a fixed disk whose ∂u_s/∂ω is never used
            same(&a, &b, false);
            fd_check3(&spatial, Point3::new(p[0], p[1], 0.4));
        }
        assert_eq!(spatial.closest(&Point3::new(1.004, 0.032, 0.0)).part, 1);
    }
}
