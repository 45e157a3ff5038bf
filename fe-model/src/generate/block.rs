//! Structured hexahedral block `[0, lx] × [0, ly] × [0, lz]`.

use crate::FeError;
use crate::element::{Elastic, Hex8, Hex8Integration};
use crate::mesh::{Cell, CellKind, Mesh};
use crate::model::FeModel;

/// Structured block of `nx × ny × nz` Hex8 elements, DOFs (u, v, w) per node.
///
/// Node `(i, j, k)` has index `(k·(ny+1) + j)·(nx+1) + i`. Node sets: `x0`, `x1`, `y0`, `y1`,
/// `z0`, `z1` (the six faces) and `all`. `map` may move each node (e.g. to distort the mesh);
/// pass `|p| p` for the straight block.
#[allow(clippy::too_many_arguments)]
pub fn hex_block(
    size: [f64; 3], divisions: [usize; 3], material: Elastic, integration: Hex8Integration,
    prestress: Option<[[f64; 3]; 3]>, map: impl Fn([f64; 3]) -> [f64; 3],
) -> Result<FeModel, FeError> {
    for (i, &s) in size.iter().enumerate() {
        FeError::check_positive(["lx", "ly", "lz"][i], s)?;
    }
    let [nx, ny, nz] = divisions;
    if nx == 0 || ny == 0 || nz == 0 {
        return Err(FeError::param("divisions", 0.0, "all must be >= 1"));
    }
    let mut mesh = Mesh::new(3);
    let id = |i: usize, j: usize, k: usize| (k * (ny + 1) + j) * (nx + 1) + i;
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                let p = [
                    size[0] * i as f64 / nx as f64,
                    size[1] * j as f64 / ny as f64,
                    size[2] * k as f64 / nz as f64,
                ];
                mesh.add_node(map(p));
            }
        }
    }
    let mut els = Vec::with_capacity(nx * ny * nz);
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let nodes = [
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1),
                ];
                let mut dofs = [0usize; 24];
                let mut x = [[0.0; 3]; 8];
                for (a, &n) in nodes.iter().enumerate() {
                    x[a] = mesh.nodes[n];
                    for d in 0..3 {
                        dofs[3 * a + d] = mesh.dof(n, d);
                    }
                }
                mesh.cells.push(Cell {
                    kind: CellKind::Hexahedron,
                    nodes: nodes.to_vec(),
                });
                els.push(Hex8::new(dofs, x, material, integration, prestress)?);
            }
        }
    }
    let face = |f: &dyn Fn(usize, usize, usize) -> bool| -> Vec<usize> {
        let mut v = Vec::new();
        for k in 0..=nz {
            for j in 0..=ny {
                for i in 0..=nx {
                    if f(i, j, k) {
                        v.push(id(i, j, k));
                    }
                }
            }
        }
        v
    };
    mesh.set_node_set("x0", face(&|i, _, _| i == 0))?;
    mesh.set_node_set("x1", face(&|i, _, _| i == nx))?;
    mesh.set_node_set("y0", face(&|_, j, _| j == 0))?;
    mesh.set_node_set("y1", face(&|_, j, _| j == ny))?;
    mesh.set_node_set("z0", face(&|_, _, k| k == 0))?;
    mesh.set_node_set("z1", face(&|_, _, k| k == nz))?;
    mesh.set_node_set("all", (0..mesh.n_nodes()).collect())?;
    let mut model = FeModel::new(mesh);
    for e in els {
        model.push(e);
    }
    Ok(model)
}
