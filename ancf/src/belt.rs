//! Closed planar belts of belt elements (Kerkkänen §3.1, §3.3): the two-pulley belt path,
//! equally spaced nodes along it, and the closed-loop mesh with a shared first node.

use crate::element::{BeltElement, Element, NodeLayout};
use crate::error::{AncfError, invalid};
use crate::material::Material;
use crate::mesh::Mesh;
use crate::section::Section;
use std::f64::consts::PI;

/// Open belt path around two equal pulleys of radius `radius` [m] with centres `left` and
/// `right` on a horizontal line: lower span left→right, arc around the right pulley, upper span
/// right→left, arc around the left pulley (counter-clockwise travel).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoPulleyPath {
    /// Left pulley centre [m].
    pub left: [f64; 2],
    /// Right pulley centre [m].
    pub right: [f64; 2],
    /// Pulley radius [m].
    pub radius: f64,
}

impl TwoPulleyPath {
    /// Kerkkänen Table 3.1 geometry: `O₁ = (−0.191441, 0)`, `O₂ = (0.191441, 0)`,
    /// `R = 0.08125 m` (path length 1.276273 m).
    pub fn kerkkanen() -> Self {
        Self {
            left: [-0.191441, 0.0],
            right: [0.191441, 0.0],
            radius: 0.08125,
        }
    }

    fn span(&self) -> f64 {
        self.right[0] - self.left[0]
    }

    /// Path length `2 l_s + 2πR` [m].
    pub fn length(&self) -> f64 {
        2.0 * self.span() + 2.0 * PI * self.radius
    }

    /// Point and unit tangent at arc length `s` from the start of the lower span (the bottom
    /// of the left pulley).
    pub fn point(&self, s: f64) -> ([f64; 2], [f64; 2]) {
        let (ls, r) = (self.span(), self.radius);
        let arc = PI * r;
        let s = s.rem_euclid(self.length());
        if s < ls {
            ([self.left[0] + s, self.left[1] - r], [1.0, 0.0])
        } else if s < ls + arc {
            let a = -PI / 2.0 + (s - ls) / r;
            (
                [self.right[0] + r * a.cos(), self.right[1] + r * a.sin()],
                [-a.sin(), a.cos()],
            )
        } else if s < 2.0 * ls + arc {
            let u = s - ls - arc;
            ([self.right[0] - u, self.right[1] + r], [-1.0, 0.0])
        } else {
            let a = PI / 2.0 + (s - 2.0 * ls - arc) / r;
            (
                [self.left[0] + r * a.cos(), self.left[1] + r * a.sin()],
                [-a.sin(), a.cos()],
            )
        }
    }
}

/// A closed loop of `n` belt elements of total unstretched length `length` [m]
/// (Kerkkänen §3.3: elements straight and stress-free in their reference configuration).
pub fn belt_loop(
    n: usize,
    length: f64,
    material: Material,
    section: Section,
    alpha1: f64,
    alpha2: f64,
    gauss_x: usize,
) -> Result<Mesh<BeltElement>, AncfError> {
    if n < 3 {
        return Err(invalid(
            "belt: elements",
            format!("a closed loop needs ≥ 3, got {n}"),
        ));
    }
    if !(length.is_finite() && length > 0.0) {
        return Err(invalid(
            "belt: length",
            format!("must be > 0 m, got {length}"),
        ));
    }
    let le = length / n as f64;
    let els = (0..n)
        .map(|_| BeltElement::new(le, material, section, alpha1, alpha2, gauss_x))
        .collect::<Result<Vec<_>, _>>()?;
    Mesh::closed_loop(els)
}

/// Initial coordinates of a closed loop placed on a path `point(s)` of length `path_length`:
/// nodes equally spaced, `r_x = (path_length / belt_length) t` (uniform stretch), `r_y = Ĩ t`
/// (seed note §9, initial conditions).
pub fn coordinates_on_path<E: Element>(
    mesh: &Mesh<E>,
    path_length: f64,
    point: impl Fn(f64) -> ([f64; 2], [f64; 2]),
) -> Vec<f64> {
    let n = mesh.n_nodes();
    let belt_length: f64 = mesh.elements().iter().map(|e| e.length()).sum();
    let stretch = path_length / belt_length;
    let layout: NodeLayout = mesh.layout();
    (0..n)
        .flat_map(|i| {
            let (p, t) = point(path_length * i as f64 / n as f64);
            layout.node_coordinates(p, t, stretch)
        })
        .collect()
}
