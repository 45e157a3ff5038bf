//! VTK XML unstructured grid (`.vtu`, ASCII) export of a mesh with point data (mode shapes,
//! node-set masks) for ParaView (VTK file formats, "UnstructuredGrid").

use crate::FeError;
use crate::mesh::{Cell, CellKind, Mesh};
use faer::MatRef;
use std::fmt::Write as _;
use std::path::Path;

/// A point-data field: `components` values per node, node-major.
#[derive(Debug, Clone, PartialEq)]
pub struct PointField {
    /// Field name (e.g. `mode_1_12.34Hz`).
    pub name: String,
    /// Components per node (1 = scalar, 3 = vector).
    pub components: usize,
    /// Values, `n_nodes × components`.
    pub values: Vec<f64>,
}

/// Which local DOFs of a node are its x, y, z displacements (`None` = zero), e.g.
/// `[Some(0), Some(1), Some(2)]` for solids and 3D frames, `[Some(0), Some(1), None]` for the
/// planar frame (u, v, θ), `[None, Some(0), None]` for a string deflecting in y.
pub type DisplacementLayout = [Option<usize>; 3];

/// A sensible default layout for a mesh with `dofs_per_node` DOFs per node.
pub fn default_layout(dofs_per_node: usize) -> DisplacementLayout {
    match dofs_per_node {
        1 => [None, Some(0), None],
        2 => [Some(0), Some(1), None],
        3 => [Some(0), Some(1), Some(2)], // solids (u, v, w); for planar frames pass [0, 1, None]
        _ => [Some(0), Some(1), Some(2)],
    }
}

/// Displacement vector fields from mode shapes (full-DOF columns of `vectors`).
pub fn mode_fields(
    mesh: &Mesh, vectors: MatRef<'_, f64>, frequencies_hz: &[f64], layout: DisplacementLayout,
) -> Result<Vec<PointField>, FeError> {
    if vectors.nrows() != mesh.n_dofs() {
        return Err(FeError::Dimension {
            context: "mode_fields: mode-shape rows vs mesh DOFs".into(),
            expected: mesh.n_dofs(),
            got: vectors.nrows(),
        });
    }
    if let Some(&bad) = layout.iter().flatten().find(|&&l| l >= mesh.dofs_per_node) {
        return Err(FeError::Index {
            context: "displacement layout local DOF".into(),
            index: bad,
            size: mesh.dofs_per_node,
        });
    }
    let mut out = Vec::with_capacity(vectors.ncols());
    for j in 0..vectors.ncols() {
        let mut values = Vec::with_capacity(3 * mesh.n_nodes());
        for n in 0..mesh.n_nodes() {
            for l in layout {
                values.push(l.map_or(0.0, |l| vectors[(mesh.dof(n, l), j)]));
            }
        }
        let f = frequencies_hz.get(j).copied().unwrap_or(f64::NAN);
        out.push(PointField {
            name: format!("mode_{}_{:.4}Hz", j + 1, f),
            components: 3,
            values,
        });
    }
    Ok(out)
}

/// Scalar 0/1 masks of all node sets (`set_<name>`).
pub fn node_set_fields(mesh: &Mesh) -> Vec<PointField> {
    mesh.node_sets
        .iter()
        .map(|(name, nodes)| {
            let mut v = vec![0.0; mesh.n_nodes()];
            for &n in nodes {
                v[n] = 1.0;
            }
            PointField {
                name: format!("set_{name}"),
                components: 1,
                values: v,
            }
        })
        .collect()
}

/// The `.vtu` document text.
pub fn vtu_string(mesh: &Mesh, fields: &[PointField]) -> Result<String, FeError> {
    for f in fields {
        if f.values.len() != f.components * mesh.n_nodes() {
            return Err(FeError::Dimension {
                context: format!("point field `{}` length", f.name),
                expected: f.components * mesh.n_nodes(),
                got: f.values.len(),
            });
        }
    }
    let mut s = String::new();
    let _ = writeln!(s, r#"<?xml version="1.0"?>"#);
    let _ = writeln!(
        s,
        r#"<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">"#
    );
    let _ = writeln!(s, "<UnstructuredGrid>");
    let _ = writeln!(
        s,
        r#"<Piece NumberOfPoints="{}" NumberOfCells="{}">"#,
        mesh.n_nodes(),
        mesh.cells.len()
    );
    let _ = writeln!(s, "<PointData>");
    for f in fields {
        let _ = writeln!(
            s,
            r#"<DataArray type="Float64" Name="{}" NumberOfComponents="{}" format="ascii">"#,
            f.name, f.components
        );
        for chunk in f.values.chunks(f.components.max(1)) {
            let line: Vec<String> = chunk.iter().map(|v| format!("{v:e}")).collect();
            let _ = writeln!(s, "{}", line.join(" "));
        }
        let _ = writeln!(s, "</DataArray>");
    }
    let _ = writeln!(s, "</PointData>");
    let _ = writeln!(s, "<Points>");
    let _ = writeln!(
        s,
        r#"<DataArray type="Float64" NumberOfComponents="3" format="ascii">"#
    );
    for p in &mesh.nodes {
        let _ = writeln!(s, "{:e} {:e} {:e}", p[0], p[1], p[2]);
    }
    let _ = writeln!(s, "</DataArray>\n</Points>\n<Cells>");
    let _ = writeln!(
        s,
        r#"<DataArray type="Int64" Name="connectivity" format="ascii">"#
    );
    for c in &mesh.cells {
        let line: Vec<String> = c.nodes.iter().map(|n| n.to_string()).collect();
        let _ = writeln!(s, "{}", line.join(" "));
    }
    let _ = writeln!(s, "</DataArray>");
    let _ = writeln!(
        s,
        r#"<DataArray type="Int64" Name="offsets" format="ascii">"#
    );
    let mut off = 0usize;
    for c in &mesh.cells {
        off += c.nodes.len();
        let _ = writeln!(s, "{off}");
    }
    let _ = writeln!(s, "</DataArray>");
    let _ = writeln!(s, r#"<DataArray type="UInt8" Name="types" format="ascii">"#);
    for c in &mesh.cells {
        let _ = writeln!(s, "{}", c.kind.vtk_type());
    }
    let _ = writeln!(
        s,
        "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>"
    );
    Ok(s)
}

/// A polyline through `points` \[m\] as a mesh of two-node [`CellKind::Line`] cells, the last
/// point joined to the first when `closed` (a belt's centreline): the geometry of a `.vtu`
/// curve with point data.
pub fn polyline(points: &[[f64; 3]], closed: bool) -> Mesh {
    let mut mesh = Mesh::new(3);
    for p in points {
        mesh.add_node(*p);
    }
    let n = points.len();
    let segments = if closed { n } else { n.saturating_sub(1) };
    for i in 0..segments.min(n) {
        let j = (i + 1) % n;
        if j != i {
            mesh.cells.push(Cell {
                kind: CellKind::Line,
                nodes: vec![i, j],
            });
        }
    }
    mesh
}

/// Write a `.vtu` file.
pub fn write_vtu(
    path: impl AsRef<Path>, mesh: &Mesh, fields: &[PointField],
) -> Result<(), FeError> {
    let path = path.as_ref();
    let text = vtu_string(mesh, fields)?;
    crate::io::write_atomic(path, text.as_bytes()).map_err(|source| FeError::Io {
        file: path.display().to_string(),
        source,
    })
}
