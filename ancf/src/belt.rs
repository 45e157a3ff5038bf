//! Closed planar belts of belt elements (Kerkkänen §3.1, §3.3): the two-pulley belt path of
//! Table 3.1 ([`belt::BeltPath`]), equally spaced nodes along a path, and the closed-loop
//! mesh with a shared first node.

use crate::element::{AncfElement, BeltElement, NodeLayout};
use crate::error::{AncfError, check_positive, invalid};
use crate::material::Material;
use crate::mesh::AncfMesh;
use crate::section::Section;
use belt::{BeltPath, Motion, Pulley, WrapSide};

/// Kerkkänen Table 3.1 two-pulley path: `O₁ = (−0.191441, 0)`, `O₂ = (0.191441, 0)`,
/// `R = 0.08125 m` (path length 1.276273 m), as a [`BeltPath`] (the belt leaves the first
/// pulley at the start and runs clockwise around both).
pub fn kerkkanen_path() -> BeltPath {
    let pulley = |name: &str, x: f64| {
        Pulley::new(
            name,
            [x, 0.0],
            0.08125,
            WrapSide::Inside,
            Motion::idler(0.1),
        )
    };
    BeltPath::new(&[pulley("1", -0.191441), pulley("2", 0.191441)])
        .expect("Kerkkänen Table 3.1: two separate pulleys have an open-belt path")
}

/// [`coordinates_on_path`] along a [`BeltPath`].
pub fn coordinates_on_belt_path<E: AncfElement>(mesh: &AncfMesh<E>, path: &BeltPath) -> Vec<f64> {
    coordinates_on_path(mesh, path.length(), |s| {
        let p = path.point(s);
        (p.position, p.tangent)
    })
}

/// A closed loop of `n` belt elements of total unstretched length `length` \[m\]
/// (Kerkkänen §3.3: elements straight and stress-free in their reference configuration).
pub fn belt_loop(
    n: usize, length: f64, material: Material, section: Section, alpha1: f64, alpha2: f64,
    gauss_x: usize,
) -> Result<AncfMesh<BeltElement>, AncfError> {
    if n < 3 {
        return Err(invalid(
            "belt: elements",
            format!("a closed loop needs ≥ 3, got {n}"),
        ));
    }
    check_positive("belt: length", length, " m")?;
    let le = length / n as f64;
    let els = (0..n)
        .map(|_| BeltElement::new(le, material, section, alpha1, alpha2, gauss_x))
        .collect::<Result<Vec<_>, _>>()?;
    AncfMesh::closed_loop(els)
}

/// Initial coordinates of a closed loop placed on a path `point(s)` of length `path_length`:
/// nodes equally spaced, `r_x = (path_length / belt_length) t` (uniform stretch), `r_y = Ĩ t`
/// (seed note §9, initial conditions).
pub fn coordinates_on_path<E: AncfElement>(
    mesh: &AncfMesh<E>, path_length: f64, point: impl Fn(f64) -> ([f64; 2], [f64; 2]),
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
