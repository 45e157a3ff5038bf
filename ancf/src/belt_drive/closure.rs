//! Example 3.3-A of Kerkkänen: static closure of a free belt. A belt of stress-free straight
//! elements is placed on the two-pulley path of Table 3.1 (the pulleys are absent: no contact)
//! and released; Newton–Raphson finds the equilibrium, a circle of circumference equal to the
//! belt length (seed note §7.5: radius `1.276/(2π) = 0.20308 m`).

use super::BeltDrive;
use super::spec::BeltDriveSpec;
use crate::error::AncfError;
use crate::statics::{AncfStaticOptions, solve_static};

/// Result of the free-belt closure.
#[derive(Debug, Clone)]
pub struct ClosureResult {
    /// Equilibrium coordinates.
    pub q: Vec<f64>,
    /// Newton iterations (total).
    pub iterations: usize,
    /// Centre of the node positions \[m\].
    pub center: [f64; 2],
    /// Mean distance of the nodes and element mid-points from the centre \[m\].
    pub mean_radius: f64,
    /// Smallest and largest distance \[m\].
    pub radius_range: [f64; 2],
}

/// Solve example 3.3-A for the belt of `spec` placed on the path of its pulleys: the belt length
/// is set to the path length (the thesis uses 1.276 m, 10 elements). Rigid motion is removed as
/// in the thesis: point A (node 0) fixed in x and y, point B (the node half-way round the loop)
/// fixed in y.
pub fn free_belt_closure(spec: &BeltDriveSpec) -> Result<ClosureResult, AncfError> {
    let drive = BeltDrive::new(spec.clone())?;
    let q0 = drive.placed_coordinates();
    let nb = drive.n_belt();
    let nn = drive.mesh().n_nodes();
    let fixed = [0, 1, 6 * (nn / 2) + 1];
    let opts = AncfStaticOptions {
        increments: 1,
        max_iterations: 200,
        tolerance: 1e-10,
        line_search: true,
    };
    let sol = solve_static(drive.mesh(), &q0[..nb], &fixed, &vec![0.0; nb], &opts)?;
    let q = sol.q;
    let mesh = drive.mesh();
    let mut pts = Vec::new();
    let l = drive.element_length();
    for el in 0..mesh.elements().len() {
        pts.push(mesh.position(&q, el, 0.0, 0.0));
        pts.push(mesh.position(&q, el, 0.5 * l, 0.0));
    }
    let nodes: Vec<[f64; 2]> = (0..nn).map(|i| mesh.node_position(&q, i)).collect();
    let c = [
        nodes.iter().map(|p| p[0]).sum::<f64>() / nn as f64,
        nodes.iter().map(|p| p[1]).sum::<f64>() / nn as f64,
    ];
    let d: Vec<f64> = pts
        .iter()
        .map(|p| ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2)).sqrt())
        .collect();
    let mean = d.iter().sum::<f64>() / d.len() as f64;
    let lo = d.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = d.iter().copied().fold(0.0, f64::max);
    Ok(ClosureResult {
        q,
        iterations: sol.iterations.iter().sum(),
        center: c,
        mean_radius: mean,
        radius_range: [lo, hi],
    })
}
