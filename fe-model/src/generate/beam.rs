//! Straight beams and strings along the x axis.

use crate::FeError;
use crate::element::{Frame2d, Frame2dSection, StringElement};
use crate::mesh::{Cell, CellKind, Mesh};
use crate::model::FeModel;

/// The `n_elements + 1` equally spaced nodes from x = 0 to x = `length` \[m\] of a straight
/// line mesh with `dofs_per_node` DOFs per node (no cells yet), and the element length \[m\].
/// Checks `length > 0` and `n_elements ≥ 1`.
fn line_nodes(
    length: f64, n_elements: usize, dofs_per_node: usize,
) -> Result<(Mesh, f64), FeError> {
    FeError::check_positive("length", length)?;
    if n_elements == 0 {
        return Err(FeError::param("n_elements", 0.0, "must be >= 1"));
    }
    let mut mesh = Mesh::new(dofs_per_node);
    let h = length / n_elements as f64;
    for i in 0..=n_elements {
        mesh.add_node([i as f64 * h, 0.0, 0.0]);
    }
    Ok((mesh, h))
}

/// Straight planar Euler–Bernoulli frame from x = 0 to x = `length` \[m\] with `n_elements`
/// equal elements, DOFs (u, v, θ) per node, all elements with axial force `axial_force` \[N\]
/// (tension > 0) for the geometric stiffness. Node sets: `start`, `end`, `all`.
pub fn straight_beam_2d(
    length: f64, n_elements: usize, section: Frame2dSection, axial_force: f64,
) -> Result<FeModel, FeError> {
    let (mut mesh, _) = line_nodes(length, n_elements, 3)?;
    let mut model_elements = Vec::with_capacity(n_elements);
    for e in 0..n_elements {
        model_elements.push(frame2d_line(&mut mesh, e, e + 1, section, axial_force)?);
    }
    mesh.set_node_set("start", vec![0])?;
    mesh.set_node_set("end", vec![n_elements])?;
    mesh.set_node_set("all", (0..=n_elements).collect())?;
    let mut model = FeModel::new(mesh);
    for e in model_elements {
        model.push(e);
    }
    Ok(model)
}

/// Add a line cell from node `a` to node `b` of `mesh` (3 DOFs per node: u, v, θ) and return
/// the planar frame element on it, global DOFs `(u_a, v_a, θ_a, u_b, v_b, θ_b)` and axial force
/// `axial_force` \[N\] (tension > 0) for the geometric stiffness. Shared by the frame meshes
/// of this module and of [`super::belt`].
pub(crate) fn frame2d_line(
    mesh: &mut Mesh, a: usize, b: usize, section: Frame2dSection, axial_force: f64,
) -> Result<Frame2d, FeError> {
    mesh.cells.push(Cell {
        kind: CellKind::Line,
        nodes: vec![a, b],
    });
    let dofs = [
        mesh.dof(a, 0),
        mesh.dof(a, 1),
        mesh.dof(a, 2),
        mesh.dof(b, 0),
        mesh.dof(b, 1),
        mesh.dof(b, 2),
    ];
    let xa = [mesh.nodes[a][0], mesh.nodes[a][1]];
    let xb = [mesh.nodes[b][0], mesh.nodes[b][1]];
    Frame2d::new(dofs, xa, xb, section, axial_force)
}

/// Straight taut string (Ribaric 4.1) from x = 0 to `length` \[m\], one transverse DOF per node,
/// `n_elements` equal elements, tension `tension` \[N\], mass per length `mass_per_length` \[kg/m\].
/// Node sets: `start`, `end`, `interior`.
pub fn straight_string(
    length: f64, n_elements: usize, tension: f64, mass_per_length: f64,
) -> Result<FeModel, FeError> {
    let (mut mesh, h) = line_nodes(length, n_elements, 1)?;
    let mut els = Vec::new();
    for e in 0..n_elements {
        mesh.cells.push(Cell {
            kind: CellKind::Line,
            nodes: vec![e, e + 1],
        });
        els.push(StringElement::new([e, e + 1], h, tension, mass_per_length)?);
    }
    mesh.set_node_set("start", vec![0])?;
    mesh.set_node_set("end", vec![n_elements])?;
    mesh.set_node_set("interior", (1..n_elements).collect())?;
    let mut model = FeModel::new(mesh);
    for e in els {
        model.push(e);
    }
    Ok(model)
}
