//! Road obstacles in space as exact signed-distance surfaces: a [`Prism`] (a [`Section`] —
//! disk, polygon or step quadrant — extruded along an axis, moving rigidly: a cleat of any
//! cross-section, transverse or oblique, on a road or a drum; a step up or down) and a
//! [`Pothole`] (a rectangular hole of given depth cut into a road). Their gaps are Euclidean
//! signed distances, so they are 1-Lipschitz in the query point and, moving rigidly at speed
//! `|u|`, change by at most `|u|` per unit time at a fixed point (what a candidate search may
//! bound with); the normal is the gradient of the distance. A road with obstacles is the union
//! of the road and the obstacles' solids: the closer of the members' closest points
//! ([`closest_of`]; Wriggers, *Computational Contact Mechanics*), as in
//! [`super::CleatedRoad3`].

use super::section::Section;
use crate::geometry::{Surface, SurfacePoint};
use nalgebra::{Matrix3, Point3, Vector3};

/// A [`Section`] extruded along the unit `axis` (an infinitely long prism): section coordinates
/// `s = (p − o)·e_s`, `n = (p − o)·up` with `e_s = axis × up` and the section origin `o`. The
/// prism moves rigidly with the angular velocity `omega` about `axis` through `center` and the
/// velocity `velocity` of `center`: `u(x) = velocity + ω axis × (x − center)` (a cleat on a
/// turning drum: `center` the drum's axis point; on a road `omega = 0`).
///
/// The gap is the section's exact signed distance in the section plane (the distance of a
/// point to an infinite prism is its distance to the section in the plane normal to the
/// axis), the normal `n = ∇d` lies in that plane, `∂n/∂p = κ t tᵀ` with the section's
/// curvature `κ` and the in-plane tangent `t = axis × n`; the closest point is `x_s = p − d n`,
/// so `∂x_s/∂p = I − n nᵀ − d κ t tᵀ` and `∂u_s/∂p = ω [axis]× ∂x_s/∂p`.
#[derive(Debug, Clone, PartialEq)]
pub struct Prism {
    /// The cross-section.
    pub section: Section,
    /// The section's origin `o` \[m\].
    pub origin: Point3<f64>,
    /// Unit extrusion axis.
    pub axis: Vector3<f64>,
    /// Unit direction of the section's `n` (normal to `axis`).
    pub up: Vector3<f64>,
    /// The point the prism turns about \[m\].
    pub center: Point3<f64>,
    /// Velocity of `center` \[m/s\].
    pub velocity: Vector3<f64>,
    /// Angular velocity about `axis` \[rad/s\].
    pub omega: f64,
}

impl Prism {
    /// The section's `s` direction `e_s = axis × up`.
    pub fn across(&self) -> Vector3<f64> {
        self.axis.cross(&self.up)
    }

    /// Velocity of the prism's material at `x` \[m/s\].
    pub fn velocity_at(&self, x: &Point3<f64>) -> Vector3<f64> {
        self.velocity + self.axis.cross(&(x - self.center)) * self.omega
    }
}

impl Surface<3> for Prism {
    /// The section's closest point in the plane of `p` (type documentation).
    fn closest(&self, p: &Point3<f64>) -> SurfacePoint<3> {
        let es = self.across();
        let q = p - self.origin;
        let along = q.dot(&self.axis);
        let sp = self.section.closest([q.dot(&es), q.dot(&self.up)]);
        let n = es * sp.normal[0] + self.up * sp.normal[1];
        let t = self.axis.cross(&n);
        let dn = t * t.transpose() * sp.curvature;
        let point = self.origin + es * sp.point[0] + self.up * sp.point[1] + self.axis * along;
        let dxs = Matrix3::identity() - n * n.transpose() - dn * sp.dist;
        let arm = point - self.center;
        SurfacePoint {
            gap: sp.dist,
            normal: n,
            gap_gradient: n,
            tangent: t,
            point,
            surface_velocity: self.velocity_at(&point),
            dn_dp: dn,
            dus_dp: self.axis.cross_matrix() * dxs * self.omega,
            dus_domega: self.axis.cross(&arm),
            part: 0,
        }
    }
    fn center(&self) -> Point3<f64> {
        self.center
    }
}

/// A road (the half-space below the plane through `origin` with outward unit normal `up`)
/// with a rectangular hole cut into it: `2 a` long along the unit `along` (in the road
/// plane), `2 b` wide along `up × along`, `depth` deep, centred at `origin`, the whole road
/// moving with `velocity` (in its plane). In local coordinates `(x, y, z)` (along, across, up)
/// the solid is `S = {z ≤ 0} ∖ (R° × (−D, ∞))` with the open rectangle `R° = {|x| < a, |y| < b}`.
///
/// Exact signed distance, by splitting `S` and its complement into products of sets whose
/// distances add in squares: outside `S`, `dist(p, S) = min(√(e² + max(z, 0)²), max(z + D, 0))`
/// with `e` the distance of `(x, y)` to the complement of `R°` (the road beside the hole, and the
/// floor `{z ≤ −D}`); inside `S`, `−min(−z, √(d_R² + max(−D − z, 0)²))` with `d_R` the
/// distance of `(x, y)` to `R` (the air above the road and in the hole). The normal is
/// `±(p − x_s)/|p − x_s|` and `∂n/∂p = (I − n nᵀ)(I − J)/g` with the Jacobian `J` of the
/// closest-point projection (the identity along the free coordinates of the face, edge or
/// vertex reached, zero across).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pothole {
    /// Centre of the hole on the road surface \[m\].
    pub origin: Point3<f64>,
    /// Outward unit normal of the road.
    pub up: Vector3<f64>,
    /// Unit direction of the hole's length (in the road plane).
    pub along: Vector3<f64>,
    /// Half-length `a` along `along` \[m\].
    pub half_length: f64,
    /// Half-width `b` across \[m\].
    pub half_width: f64,
    /// Depth `D` \[m\].
    pub depth: f64,
    /// Velocity of the road material \[m/s\].
    pub velocity: Vector3<f64>,
}

impl Pothole {
    /// The local axes `(along, across, up)` as the columns of a rotation.
    fn frame(&self) -> Matrix3<f64> {
        let across = self.up.cross(&self.along);
        Matrix3::from_columns(&[self.along, across, self.up])
    }

    /// The signed distance in local coordinates: `(gap, closest point, free coordinates of
    /// the projection)`.
    fn local(&self, p: [f64; 3]) -> (f64, [f64; 3], [bool; 3]) {
        let (a, b, dep) = (self.half_length, self.half_width, self.depth);
        let [x, y, z] = p;
        let in_r = x.abs() < a && y.abs() < b;
        let solid = z <= 0.0 && (!in_r || z <= -dep);
        if !solid {
            // beside the hole: (x, y) moved to the nearer side of R, z to the road level
            let (e, cxy, fxy) = if in_r {
                if a - x.abs() <= b - y.abs() {
                    (a - x.abs(), [a.copysign(x), y], [false, true])
                } else {
                    (b - y.abs(), [x, b.copysign(y)], [true, false])
                }
            } else {
                (0.0, [x, y], [true, true])
            };
            let zt = z.min(0.0);
            let d1 = e.hypot(z - zt);
            // the floor
            let d2 = (z + dep).max(0.0);
            if d2 < d1 {
                let zf = z.min(-dep);
                (d2, [x, y, zf], [true, true, z < -dep])
            } else {
                (d1, [cxy[0], cxy[1], zt], [fxy[0], fxy[1], z < 0.0])
            }
        } else {
            // the air above the road
            let u1 = -z;
            // the air in the hole: (x, y) clamped into R, z up to the floor
            let (cx, cy) = (x.clamp(-a, a), y.clamp(-b, b));
            let zf = z.max(-dep);
            let u2 = (x - cx).hypot(y - cy).hypot(z - zf);
            let free2 = [x.abs() <= a, y.abs() <= b, z > -dep];
            if u1 <= u2 {
                (-u1, [x, y, 0.0], [true, true, false])
            } else {
                (-u2, [cx, cy, zf], free2)
            }
        }
    }
}

impl Surface<3> for Pothole {
    /// The exact signed distance (type documentation); the road's material velocity.
    fn closest(&self, p: &Point3<f64>) -> SurfacePoint<3> {
        let f = self.frame();
        let q = f.transpose() * (p - self.origin);
        let (gap, c, free) = self.local([q.x, q.y, q.z]);
        let xs = Vector3::new(c[0], c[1], c[2]);
        let d = q - xs;
        let rho = d.norm();
        let (n_loc, dn_loc) = if rho > 0.0 {
            let n = d * gap.signum() / rho;
            let j = Matrix3::from_diagonal(&Vector3::new(
                free[0] as u8 as f64,
                free[1] as u8 as f64,
                free[2] as u8 as f64,
            ));
            let dn = (Matrix3::identity() - n * n.transpose()) * (Matrix3::identity() - j) / gap;
            (n, dn)
        } else {
            (Vector3::z(), Matrix3::zeros())
        };
        let n = f * n_loc;
        SurfacePoint {
            gap,
            normal: n,
            gap_gradient: n,
            tangent: super::geometry::perpendicular(&n).cross(&n),
            point: self.origin + f * xs,
            surface_velocity: self.velocity,
            dn_dp: f * dn_loc * f.transpose(),
            dus_dp: Matrix3::zeros(),
            dus_domega: Vector3::zeros(),
            part: 0,
        }
    }
    fn center(&self) -> Point3<f64> {
        self.origin
    }
}

/// The closest point of a union of solids: the member with the smallest gap (the first on a
/// tie), its index as [`SurfacePoint::part`] (plus `first_part`). `None` for no members.
pub fn closest_of<'a>(
    members: impl IntoIterator<Item = &'a dyn Surface<3>>, p: &Point3<f64>, first_part: usize,
) -> Option<SurfacePoint<3>> {
    let mut best: Option<SurfacePoint<3>> = None;
    for (k, m) in members.into_iter().enumerate() {
        let mut s = m.closest(p);
        if best.is_none_or(|b| s.gap < b.gap) {
            s.part = first_part + k;
            best = Some(s);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::CleatedRoad3;
    use crate::spatial::geometry::HalfSpace;
    use crate::spatial::geometry::tests::fd_check3;

    fn road() -> HalfSpace {
        HalfSpace {
            origin: Point3::new(0.0, 0.0, 0.02),
            normal: Vector3::z(),
            tangent: Vector3::x(),
            velocity: Vector3::new(-16.0, 0.3, 0.0),
        }
    }

    // Reference (second formulation): a transverse prism of the disk section on the road is
    // the contact crate's CleatedRoad3 (a cylinder), member by member; central differences on
    // an oblique, turning polygon prism (cleat on a drum).
    #[test]
    fn disk_prism_is_the_cleated_road() {
        let r = road();
        let cleated = CleatedRoad3 {
            road: r,
            cleat_radius: 0.01,
            cleat_offset: 0.3,
        };
        let prism = Prism {
            section: Section::Disk { radius: 0.01 },
            origin: Point3::new(0.3, 0.0, 0.02),
            axis: Vector3::y(),
            up: Vector3::z(),
            center: Point3::new(0.3, 0.0, 0.02),
            velocity: r.velocity,
            omega: 0.0,
        };
        for p in [
            Point3::new(0.304, 0.2, 0.032),
            Point3::new(0.297, -0.1, 0.025),
            Point3::new(0.2, 0.0, 0.021),
        ] {
            let a = cleated.closest(&p);
            let b = closest_of([&r as &dyn Surface<3>, &prism], &p, 0).unwrap();
            assert_eq!(a.part, b.part);
            assert!((a.gap - b.gap).abs() < 1e-15);
            assert!((a.normal - b.normal).amax() < 1e-14);
            assert!((a.point - b.point).amax() < 1e-15);
            assert!((a.surface_velocity - b.surface_velocity).amax() < 1e-15);
            assert!((a.dn_dp - b.dn_dp).amax() < 1e-10);
        }
        // an oblique trapezoid on a turning drum: derivatives by central differences
        let axis = Vector3::new(0.3, 1.0, 0.1).normalize();
        let up = (Vector3::z() - axis * axis.z).normalize();
        let drum = Prism {
            section: Section::trapezoid(0.03, 0.01, 0.01, 0.005),
            origin: Point3::new(0.1, 0.0, 0.0),
            axis,
            up,
            center: Point3::new(0.1, 0.0, -1.2),
            velocity: Vector3::new(0.1, -0.2, 0.0),
            omega: 13.0,
        };
        let es = drum.across();
        // three faces and the top corner's vertex region
        for (s, n) in [
            (0.012, 0.006),
            (0.02, 0.012),
            (0.0, 0.013),
            (0.014, 0.002),
            (0.007, 0.013),
        ] {
            fd_check3(&drum, drum.origin + es * s + up * n + axis * 0.2);
        }
    }

    /// Brute-force reference of the pothole: the distance to its boundary faces (the road
    /// outside the rectangle, four walls, the floor) sampled on a fine grid, signed by the
    /// definition of the solid.
    fn brute(h: &Pothole, q: [f64; 3]) -> f64 {
        let (a, b, dep) = (h.half_length, h.half_width, h.depth);
        let n = 600;
        let lin = |lo: f64, hi: f64, k: usize| lo + (hi - lo) * k as f64 / n as f64;
        let mut best = f64::INFINITY;
        let mut at = |x: f64, y: f64, z: f64| {
            best = best.min(((q[0] - x).powi(2) + (q[1] - y).powi(2) + (q[2] - z).powi(2)).sqrt())
        };
        for i in 0..=n {
            for j in 0..=n {
                // the floor and the road ring around the hole (to 3 a, 3 b)
                at(lin(-a, a, i), lin(-b, b, j), -dep);
                let (x, y) = (lin(-3.0 * a, 3.0 * a, i), lin(-3.0 * b, 3.0 * b, j));
                if x.abs() >= a || y.abs() >= b {
                    at(x, y, 0.0);
                }
                // the walls
                at(a, lin(-b, b, i), lin(-dep, 0.0, j));
                at(-a, lin(-b, b, i), lin(-dep, 0.0, j));
                at(lin(-a, a, i), b, lin(-dep, 0.0, j));
                at(lin(-a, a, i), -b, lin(-dep, 0.0, j));
            }
        }
        // the road beside the hole, exactly (the sample above is finite)
        if q[0].abs() >= a || q[1].abs() >= b {
            best = best.min(q[2].abs());
        }
        let in_r = q[0].abs() < a && q[1].abs() < b;
        let solid = q[2] <= 0.0 && (!in_r || q[2] <= -dep);
        if solid { -best } else { best }
    }

    // Reference: the sampled distance to the boundary faces (brute force), and central
    // differences of the gap, normal and velocity away from the medial surfaces.
    #[test]
    fn pothole_distance_is_exact() {
        let h = Pothole {
            origin: Point3::new(0.0, 0.0, 0.0),
            up: Vector3::z(),
            along: Vector3::x(),
            half_length: 0.1,
            half_width: 0.06,
            depth: 0.02,
            velocity: Vector3::new(-16.0, 0.0, 0.0),
        };
        let pts = [
            [0.0, 0.0, 0.01],      // over the hole, above the road
            [0.095, 0.0, -0.005],  // in the hole near the far wall
            [0.0, 0.0, -0.015],    // in the hole near the floor
            [0.104, 0.0, 0.003],   // above the rim edge, outside
            [0.09, 0.0, 0.004],    // above the rim edge, inside the outline
            [0.105, 0.02, -0.004], // in the road beside the wall
            [0.05, 0.0, -0.03],    // under the floor
            [0.3, 0.1, 0.01],      // over the plain road
            [0.3, 0.1, -0.01],     // in the plain road
            [0.097, 0.058, -0.01], // in the hole near a vertical corner
        ];
        for q in pts {
            let d = h.closest(&Point3::from(q)).gap;
            let r = brute(&h, q);
            // the faces near the points are sampled at 1/3 mm at most: error below (1/6 mm)²/(2 d)
            assert!((d - r).abs() < 2e-5, "{q:?}: {d} vs {r}");
        }
        for q in pts {
            fd_check3(&h, Point3::from(q));
        }
        // a turned, moving pothole: the same in local coordinates
        let along = Vector3::new(0.8, 0.6, 0.0);
        let t = Pothole {
            along,
            origin: Point3::new(1.0, 2.0, 0.5),
            ..h
        };
        let f = Matrix3::from_columns(&[along, Vector3::z().cross(&along), Vector3::z()]);
        for q in pts {
            let p = t.origin + f * Vector3::from(q);
            let (a, b) = (t.closest(&p), h.closest(&Point3::from(q)));
            assert!((a.gap - b.gap).abs() < 1e-14);
            assert!((a.normal - f * b.normal).amax() < 1e-12);
            fd_check3(&t, p);
        }
    }
}
