//! Cross-sections of road obstacles (cleats, steps) in their plane `(s, n)`: `s` across the
//! obstacle (along the road, normal to the obstacle's axis), `n` along the road's outward
//! normal, the origin on the road surface. A [`Section`] answers its exact signed distance
//! ([`Section::closest`]): the Euclidean distance to the section's boundary, negative inside,
//! with the outward unit normal `∇d` and the curvature of its level set, so that a
//! [`super::Prism`] extruding it is an exact signed-distance surface (1-Lipschitz in the query
//! point, which the tire's candidate search relies on).
//!
//! The distance of a polygon is the smallest distance to its edges, signed by the even–odd
//! crossing test (the closest-point projection onto line segments; e.g. Ericson, *Real-Time
//! Collision Detection*, §5.1.2); the distance of a disk and of the quadrant (a box with two
//! faces at infinity) are closed forms.

use serde::{Deserialize, Serialize};

/// Largest number of vertices of a [`Section::Polygon`] (bounds the work of every query).
pub const MAX_SECTION_VERTICES: usize = 64;

/// A cross-section in the obstacle's `(s, n)` plane (module documentation) \[m\].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub enum Section {
    /// A disk of radius `radius` \[m\] centred at the origin: the semicircular cleat of Ribaric
    /// §8.3 (its lower half lies inside the road).
    Disk {
        /// Radius \[m\].
        radius: f64,
    },
    /// A simple polygon (no self-intersections; either orientation) with vertices `(s, n)`
    /// \[m\]: rectangular and trapezoidal cleats ([`Section::rectangle`], [`Section::trapezoid`])
    /// or any profile.
    Polygon {
        /// Vertices `(s, n)` \[m\] in order around the boundary.
        vertices: Vec<[f64; 2]>,
    },
    /// The quadrant `{σ s ≥ 0, n ≤ height}` with `σ = side` (±1): the raised side of a step
    /// whose edge is the line `s = 0`, its plateau at `n = height` \[m\].
    Quadrant {
        /// `+1`: the plateau lies at `s ≥ 0`; `−1`: at `s ≤ 0`.
        side: f64,
        /// Height of the plateau above the origin \[m\].
        height: f64,
    },
}

/// The closest boundary point of a [`Section`] to a query point `q = (s, n)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionPoint {
    /// Signed distance \[m\] (negative inside the section).
    pub dist: f64,
    /// Outward unit normal `∇d` at `q`.
    pub normal: [f64; 2],
    /// The closest boundary point \[m\] (`q − d ∇d`).
    pub point: [f64; 2],
    /// Curvature `κ` of the level set through `q` \[1/m\]: `∂∇d/∂q = κ t tᵀ` with the unit
    /// tangent `t ⊥ ∇d` (0 where the closest point is inside an edge, `1/d` where it is a
    /// vertex, `1/ρ` for a disk of centre distance `ρ`).
    pub curvature: f64,
}

impl Section {
    /// A rectangular cleat `width` wide and `height` high \[m\] on the road (`n = 0`), centred at
    /// `s = 0`, continued `skirt` \[m\] below the road so that it meets a curved road (a drum)
    /// without a gap (any `skirt > 0` on a flat road; the part below lies inside the road).
    pub fn rectangle(width: f64, height: f64, skirt: f64) -> Self {
        let w = 0.5 * width;
        Section::Polygon {
            vertices: vec![[-w, -skirt], [w, -skirt], [w, height], [-w, height]],
        }
    }

    /// A trapezoidal cleat `base` wide on the road and `top` wide at its `height` \[m\],
    /// symmetric about `s = 0`, with a vertical `skirt` below the road as
    /// [`Section::rectangle`].
    pub fn trapezoid(base: f64, top: f64, height: f64, skirt: f64) -> Self {
        let (b, t) = (0.5 * base, 0.5 * top);
        Section::Polygon {
            vertices: vec![
                [-b, -skirt],
                [b, -skirt],
                [b, 0.0],
                [t, height],
                [-t, height],
                [-b, 0.0],
            ],
        }
    }

    /// The extent of the section along `s` \[m\]: `(s_min, s_max)` (infinite on the plateau side
    /// of a quadrant).
    pub fn s_extent(&self) -> (f64, f64) {
        match self {
            Section::Disk { radius } => (-radius, *radius),
            Section::Polygon { vertices } => vertices
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                    (lo.min(v[0]), hi.max(v[0]))
                }),
            Section::Quadrant { side, .. } => {
                if *side > 0.0 {
                    (0.0, f64::INFINITY)
                } else {
                    (f64::NEG_INFINITY, 0.0)
                }
            }
        }
    }

    /// Whether the section is its own mirror image under `s ↦ −s` (a polygon whose vertex set
    /// is mirrored to `tol` \[m\]; the disk; never a quadrant).
    pub fn is_symmetric_in_s(&self, tol: f64) -> bool {
        match self {
            Section::Disk { .. } => true,
            Section::Quadrant { .. } => false,
            Section::Polygon { vertices } => vertices.iter().all(|v| {
                vertices
                    .iter()
                    .any(|w| (w[0] + v[0]).abs() <= tol && (w[1] - v[1]).abs() <= tol)
            }),
        }
    }

    /// The exact signed distance of `q = (s, n)` to the section (module documentation).
    pub fn closest(&self, q: [f64; 2]) -> SectionPoint {
        match self {
            Section::Disk { radius } => {
                let rho = (q[0] * q[0] + q[1] * q[1]).sqrt();
                let (normal, curvature) = if rho > 0.0 {
                    ([q[0] / rho, q[1] / rho], 1.0 / rho)
                } else {
                    ([0.0, 1.0], 0.0)
                };
                SectionPoint {
                    dist: rho - radius,
                    normal,
                    point: [normal[0] * radius, normal[1] * radius],
                    curvature,
                }
            }
            Section::Quadrant { side, height } => quadrant(q, *side, *height),
            Section::Polygon { vertices } => polygon(q, vertices),
        }
    }
}

/// The signed distance to the quadrant `{σ s ≥ 0, n ≤ h}`: a box with the faces `σ s = 0`
/// (outward normal `(−σ, 0)`) and `n = h` (outward normal `(0, 1)`); beyond both faces the
/// corner `(0, h)` is closest.
fn quadrant(q: [f64; 2], side: f64, h: f64) -> SectionPoint {
    let sigma = if side < 0.0 { -1.0 } else { 1.0 };
    // distances beyond the two faces (positive outside)
    let d1 = -sigma * q[0];
    let d2 = q[1] - h;
    if d1 > 0.0 && d2 > 0.0 {
        let rho = d1.hypot(d2);
        let normal = [-sigma * d1 / rho, d2 / rho];
        return SectionPoint {
            dist: rho,
            normal,
            point: [0.0, h],
            curvature: 1.0 / rho,
        };
    }
    // one face: the one the point is beyond, or inside the nearer one
    if d1 > d2 {
        SectionPoint {
            dist: d1,
            normal: [-sigma, 0.0],
            point: [0.0, q[1]],
            curvature: 0.0,
        }
    } else {
        SectionPoint {
            dist: d2,
            normal: [0.0, 1.0],
            point: [q[0], h],
            curvature: 0.0,
        }
    }
}

/// The signed distance to a simple polygon: the nearest point of its edges, the sign by the
/// even–odd crossing test, the normal from the nearest feature (the edge's outward normal
/// inside an edge, the direction from the vertex otherwise).
fn polygon(q: [f64; 2], v: &[[f64; 2]]) -> SectionPoint {
    let m = v.len();
    // orientation: the outward normal of an edge a → b is (e_n, −e_s)/|e| for a
    // counter-clockwise polygon (positive area)
    let area2: f64 = (0..m)
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % m]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum();
    let orient = if area2 >= 0.0 { 1.0 } else { -1.0 };
    let mut best = f64::INFINITY;
    // the nearest point, its edge and whether it lies inside the edge (not at a vertex)
    let mut near = ([0.0, 0.0], 0usize, false);
    let mut inside = false;
    for i in 0..m {
        let (a, b) = (v[i], v[(i + 1) % m]);
        let e = [b[0] - a[0], b[1] - a[1]];
        let w = [q[0] - a[0], q[1] - a[1]];
        let ee = e[0] * e[0] + e[1] * e[1];
        let t = if ee > 0.0 {
            ((w[0] * e[0] + w[1] * e[1]) / ee).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let c = [a[0] + e[0] * t, a[1] + e[1] * t];
        let d2 = (q[0] - c[0]).powi(2) + (q[1] - c[1]).powi(2);
        if d2 < best {
            best = d2;
            near = (c, i, t > 0.0 && t < 1.0);
        }
        // even–odd: the edge crosses the horizontal ray from q towards +s
        if (a[1] > q[1]) != (b[1] > q[1]) {
            let x = a[0] + (q[1] - a[1]) / (b[1] - a[1]) * e[0];
            if q[0] < x {
                inside = !inside;
            }
        }
    }
    let rho = best.sqrt();
    let sign = if inside { -1.0 } else { 1.0 };
    let (c, i, on_edge) = near;
    let (a, b) = (v[i], v[(i + 1) % m]);
    let e = [b[0] - a[0], b[1] - a[1]];
    let el = e[0].hypot(e[1]);
    let edge_normal = if el > 0.0 {
        [orient * e[1] / el, -orient * e[0] / el]
    } else {
        [0.0, 1.0]
    };
    let (normal, curvature) = if on_edge || rho == 0.0 {
        (edge_normal, 0.0)
    } else {
        // from the vertex: ∇(±|q − c|) = ±(q − c)/|q − c|
        (
            [sign * (q[0] - c[0]) / rho, sign * (q[1] - c[1]) / rho],
            1.0 / (sign * rho),
        )
    };
    SectionPoint {
        dist: sign * rho,
        normal,
        point: c,
        curvature,
    }
}

/// Whether the polygon `v` is simple: at least three vertices, no two non-adjacent edges
/// intersecting, no edge of zero length and a non-zero area \[m²\]. `Err` with the reason.
pub fn check_simple_polygon(v: &[[f64; 2]]) -> Result<(), String> {
    let m = v.len();
    if m < 3 {
        return Err(format!("has {m} vertices, at least 3 are needed"));
    }
    if m > MAX_SECTION_VERTICES {
        return Err(format!(
            "has {m} vertices, more than the {MAX_SECTION_VERTICES} allowed"
        ));
    }
    if let Some(i) = v
        .iter()
        .position(|p| !(p[0].is_finite() && p[1].is_finite()))
    {
        return Err(format!("vertex {i} is not finite"));
    }
    for i in 0..m {
        let (a, b) = (v[i], v[(i + 1) % m]);
        if a == b {
            return Err(format!("vertices {i} and {} coincide", (i + 1) % m));
        }
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    // closed segments [a, b] and [c, d] intersect (collinear overlaps included)
    let on = |a: [f64; 2], b: [f64; 2], p: [f64; 2]| {
        p[0] >= a[0].min(b[0])
            && p[0] <= a[0].max(b[0])
            && p[1] >= a[1].min(b[1])
            && p[1] <= a[1].max(b[1])
    };
    let meet = |a, b, c, d| {
        let (d1, d2) = (cross(c, d, a), cross(c, d, b));
        let (d3, d4) = (cross(a, b, c), cross(a, b, d));
        if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
            && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
        {
            return true;
        }
        (d1 == 0.0 && on(c, d, a))
            || (d2 == 0.0 && on(c, d, b))
            || (d3 == 0.0 && on(a, b, c))
            || (d4 == 0.0 && on(a, b, d))
    };
    for i in 0..m {
        for j in i + 1..m {
            // adjacent edges share a vertex
            if j == i + 1 || (i == 0 && j == m - 1) {
                continue;
            }
            if meet(v[i], v[(i + 1) % m], v[j], v[(j + 1) % m]) {
                return Err(format!(
                    "edges {i} and {j} intersect (not a simple polygon)"
                ));
            }
        }
    }
    let area2: f64 = (0..m)
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % m]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum();
    if area2 == 0.0 {
        return Err("has zero area".into());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute-force reference: the distance to the boundary sampled densely (every edge at
    /// 20 000 points), and the sign by the winding number.
    fn brute(q: [f64; 2], v: &[[f64; 2]]) -> f64 {
        let m = v.len();
        let mut best = f64::INFINITY;
        let mut winding = 0.0;
        for i in 0..m {
            let (a, b) = (v[i], v[(i + 1) % m]);
            for k in 0..=20_000 {
                let t = k as f64 / 20_000.0;
                let c = [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
                best = best.min((q[0] - c[0]).hypot(q[1] - c[1]));
            }
            let (u, w) = ([a[0] - q[0], a[1] - q[1]], [b[0] - q[0], b[1] - q[1]]);
            winding += (u[0] * w[1] - u[1] * w[0]).atan2(u[0] * w[0] + u[1] * w[1]);
        }
        if winding.abs() > 3.0 { -best } else { best }
    }

    // Reference: the dense boundary sample with the winding number (independent of the
    // crossing test), a non-convex polygon of both orientations; the normal against central
    // differences of the distance and the curvature against differences of the normal.
    #[test]
    fn polygon_distance_is_exact() {
        // an L-shaped step with a notch (non-convex)
        let ccw = vec![
            [-0.02, -0.01],
            [0.03, -0.01],
            [0.03, 0.004],
            [0.01, 0.004],
            [0.01, 0.012],
            [-0.02, 0.012],
        ];
        let cw: Vec<[f64; 2]> = ccw.iter().rev().copied().collect();
        check_simple_polygon(&ccw).unwrap();
        for v in [&ccw, &cw] {
            let sec = Section::Polygon {
                vertices: v.clone(),
            };
            for q in [
                [0.0, 0.02],
                [0.02, 0.008],
                [0.015, 0.006],
                [0.0, 0.0],
                [0.029, 0.0],
                [0.04, 0.01],
                [-0.03, -0.02],
                [0.012, 0.0045],
            ] {
                let p = sec.closest(q);
                let r = brute(q, v);
                assert!((p.dist - r).abs() < 1e-7, "{q:?}: {} vs {r}", p.dist);
                let h = 1e-7;
                let f = |dq: [f64; 2]| sec.closest([q[0] + dq[0], q[1] + dq[1]]);
                let g = [
                    (f([h, 0.0]).dist - f([-h, 0.0]).dist) / (2.0 * h),
                    (f([0.0, h]).dist - f([0.0, -h]).dist) / (2.0 * h),
                ];
                assert!((g[0] - p.normal[0]).abs() < 1e-6, "{q:?} {g:?}");
                assert!((g[1] - p.normal[1]).abs() < 1e-6, "{q:?} {g:?}");
                // ∂n/∂q = κ t tᵀ
                let t = [-p.normal[1], p.normal[0]];
                for (j, dq) in [[h, 0.0], [0.0, h]].into_iter().enumerate() {
                    let (a, b) = (f(dq), f([-dq[0], -dq[1]]));
                    for i in 0..2 {
                        let fd = (a.normal[i] - b.normal[i]) / (2.0 * h);
                        assert!((fd - p.curvature * t[i] * t[j]).abs() < 1e-4, "{q:?}");
                    }
                }
                // the closest point lies on the boundary at the distance
                assert!(
                    ((q[0] - p.point[0]).hypot(q[1] - p.point[1]) - p.dist.abs()).abs() < 1e-15
                );
            }
        }
    }

    // Reference: the rectangle as the box distance in closed form, the trapezoid's slanted face
    // by the line distance; the disk's distance `ρ − r`.
    #[test]
    fn rectangle_trapezoid_and_disk() {
        let r = Section::rectangle(0.02, 0.01, 0.005);
        // beyond the top-right corner, above the top, inside near the right face
        for (q, d) in [
            ([0.013, 0.014], (0.003f64).hypot(0.004)),
            ([0.0, 0.016], 0.006),
            ([0.009, 0.005], -0.001),
        ] {
            assert!((r.closest(q).dist - d).abs() < 1e-15, "{q:?}");
        }
        let t = Section::trapezoid(0.03, 0.01, 0.01, 0.005);
        // the right face runs from (0.015, 0) to (0.005, 0.01): normal (1, 1)/√2
        let q = [0.012, 0.006];
        let d = ((q[0] - 0.015) + (q[1] - 0.0)) / 2f64.sqrt();
        let p = t.closest(q);
        assert!((p.dist - d).abs() < 1e-15);
        assert!((p.normal[0] - 0.5f64.sqrt()).abs() < 1e-15);
        let disk = Section::Disk { radius: 0.01 };
        let p = disk.closest([0.006, 0.008]);
        assert!(p.dist.abs() < 1e-17 && (p.normal[0] - 0.6).abs() < 1e-15);
        assert!(
            t.is_symmetric_in_s(0.0)
                && !Section::Quadrant {
                    side: 1.0,
                    height: 0.01
                }
                .is_symmetric_in_s(1.0)
        );
    }

    // Reference: the quadrant as the limit of a large rectangle (the dense-sample polygon
    // distance), both sides.
    #[test]
    fn quadrant_is_a_large_box() {
        for side in [1.0, -1.0] {
            let q = Section::Quadrant { side, height: 0.01 };
            let big = 10.0 * side;
            let poly = vec![[0.0, -10.0], [big, -10.0], [big, 0.01], [0.0, 0.01]];
            let poly = Section::Polygon { vertices: poly };
            for p in [
                [-0.005 * side, 0.02],
                [-0.005 * side, 0.0],
                [0.004 * side, 0.02],
                [0.004 * side, 0.008],
                [0.001 * side, 0.005],
            ] {
                let (a, b) = (q.closest(p), poly.closest(p));
                assert!((a.dist - b.dist).abs() < 1e-15, "{side} {p:?}");
                assert!((a.normal[0] - b.normal[0]).abs() < 1e-15);
                assert!((a.normal[1] - b.normal[1]).abs() < 1e-15);
                assert!((a.curvature - b.curvature).abs() < 1e-9);
            }
        }
    }

    // Reference: the definition of a simple polygon (hand-made cases).
    #[test]
    fn simple_polygon_check() {
        assert!(check_simple_polygon(&[[0.0, 0.0], [1.0, 0.0]]).is_err());
        // a bow tie
        let bow = [[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]];
        assert!(
            check_simple_polygon(&bow)
                .unwrap_err()
                .contains("intersect")
        );
        assert!(check_simple_polygon(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]).is_err());
        assert!(check_simple_polygon(&[[0.0, 0.0], [1.0, 0.0], [f64::NAN, 1.0]]).is_err());
        assert!(check_simple_polygon(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]).is_ok());
    }
}
