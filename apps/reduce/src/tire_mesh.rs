//! `flowmbd-reduce tire-mesh`: generate the truck-tire carcass and assemble M and K
//! (`fe_model::generate::tire_mesh`), then write `M.mtx`, `K.mtx` (Matrix Market, symmetric,
//! all DOFs; K includes the inflation geometric stiffness when enabled), `mesh.vtu` (zones and
//! node sets), `mesh.json` (for `modes --mesh`), `node_sets.json` and `rim_dofs.txt` (for
//! `modes --fixed`).

use fe_model::FeError;
use fe_model::generate::TireZone;
use fe_model::generate::tire_mesh::{TireMeshConfig, TireMeshError, TireMeshSummary, tire_mesh};
use fe_model::io::{mtx, vtk};
use flowmbd_cli::{InputError, Study, StudyContext, StudyError};
use serde::Serialize;

/// `summary.json`: the library's summary and the files written.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// Mesh size and mass.
    #[serde(flatten)]
    pub mesh: TireMeshSummary,
    /// Files written.
    pub files: Vec<String>,
}

/// The study.
pub struct TireMesh;

fn numerical(what: &str, e: FeError) -> StudyError {
    StudyError::numerical(format!("{what}: {e}"))
}

impl Study for TireMesh {
    type Config = TireMeshConfig;
    type Summary = Summary;
    const NAME: &'static str = "tire-mesh";

    fn run(&self, c: &TireMeshConfig, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let bar = ctx.progress(4.0, "tire-mesh");
        let r = tire_mesh(c).map_err(|e| match e {
            TireMeshError::Generate(e) => StudyError::Input(InputError::new("tire", e.to_string())),
            e @ TireMeshError::Assembly(_) => StudyError::numerical(e),
        })?;
        bar.set(2.0);
        let mesh = &r.tire.model.mesh;
        let mut files = Vec::new();
        for (name, a) in [("K.mtx", &r.k), ("M.mtx", &r.m)] {
            let p = ctx.out.path(name);
            mtx::write_sparse(&p, a.as_ref(), mtx::Symmetry::Symmetric)
                .map_err(|e| numerical(name, e))?;
            files.push(name.to_string());
        }
        bar.set(3.0);
        let zone = vtk::PointField {
            name: "zone_of_first_element".into(),
            components: 1,
            values: {
                let mut v = vec![0.0; mesh.n_nodes()];
                for (cell, z) in mesh.cells.iter().zip(&r.tire.zones) {
                    for &n in &cell.nodes {
                        v[n] = match z {
                            TireZone::Bead => 0.0,
                            TireZone::Sidewall => 1.0,
                            TireZone::Tread => 2.0,
                        };
                    }
                }
                v
            },
        };
        let mut fields = vtk::node_set_fields(mesh);
        fields.push(zone);
        vtk::write_vtu(ctx.out.path("mesh.vtu"), mesh, &fields)
            .map_err(|e| numerical("mesh.vtu", e))?;
        files.push("mesh.vtu".into());
        ctx.out.write_json("mesh.json", mesh)?;
        ctx.out.write_json("node_sets.json", &mesh.node_sets)?;
        files.push("mesh.json".into());
        files.push("node_sets.json".into());
        let rim = mesh
            .node_set_dofs("rim", None)
            .map_err(|e| numerical("rim set", e))?;
        let text: String = rim.iter().map(|d| format!("{d}\n")).collect();
        ctx.out.write_text(
            "rim_dofs.txt",
            &format!("# 0-based DOFs of the rim node set (bonded to the wheel)\n{text}"),
        )?;
        files.push("rim_dofs.txt".into());
        bar.set(4.0);
        bar.finish();
        Ok(Summary {
            mesh: r.summary,
            files,
        })
    }
}
