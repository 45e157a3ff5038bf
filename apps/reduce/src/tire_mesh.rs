//! `flowmbd-reduce tire-mesh`: generate the truck-tire carcass (fe-model `generate::tire`) and
//! write `M.mtx`, `K.mtx` (Matrix Market, symmetric, all DOFs; K includes the inflation
//! geometric stiffness when enabled), `mesh.vtu` (zones and node sets), `mesh.json` (for
//! `modes --mesh`), `node_sets.json` and `rim_dofs.txt` (for `modes --fixed`).

use fe_model::generate::{TireConfig, TireZone, tire};
use fe_model::io::{mtx, vtk};
use fe_model::{FeError, MassKind};
use flowmbd_cli::{InputError, Study, StudyContext, StudyError, Validate};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Configuration of the `tire-mesh` study.
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// Tire geometry, mesh divisions, materials and inflation.
    pub tire: TireConfig,
    /// Mass discretisation (`consistent` or `lumped`).
    pub mass: MassKind,
    /// Add the inflation geometric stiffness to K.
    pub geometric_stiffness: bool,
}

impl Default for Config {
    /// The 63 936-DOF truck tire standing in for Ribaric §8.1's >60 000-DOF ABAQUS model.
    fn default() -> Self {
        Self {
            tire: TireConfig::default(),
            mass: MassKind::Consistent,
            geometric_stiffness: true,
        }
    }
}

impl flowmbd_cli::PartialRules for Config {}

impl Validate for Config {
    fn validate(&self) -> Result<(), InputError> {
        self.tire.validate_within("tire")
    }
}

/// `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// Nodes.
    pub nodes: usize,
    /// Hexahedra.
    pub elements: usize,
    /// DOFs (3 per node).
    pub dof: usize,
    /// Stored entries of K (both triangles).
    pub nnz_k: usize,
    /// Node-set sizes.
    pub node_sets: BTreeMap<String, usize>,
    /// Total mass \[kg\] (rigid translation uᵀ M u).
    pub mass_kg: f64,
    /// Files written.
    pub files: Vec<String>,
}

/// The study.
pub struct TireMesh;

fn numerical(what: &str, e: FeError) -> StudyError {
    StudyError::numerical(format!("{what}: {e}"))
}

impl Study for TireMesh {
    type Config = Config;
    type Summary = Summary;
    const NAME: &'static str = "tire-mesh";
    const MEANING: &'static str = "The generated truck-tire carcass: the nodes, hexahedra and DOFs of the mesh written \
         as mesh.json, M and K (Matrix Market) and the node sets (rim, contact patch), for \
         flowmbd-reduce and other FE tools.";

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let bar = ctx.progress(4.0, "tire-mesh");
        let t =
            tire(&c.tire).map_err(|e| StudyError::Input(InputError::new("tire", e.to_string())))?;
        bar.set(1.0);
        let (k, m) = t
            .model
            .k_and_m(c.mass, c.geometric_stiffness)
            .map_err(|e| numerical("assembly", e))?;
        bar.set(2.0);
        let mesh = &t.model.mesh;
        let mut files = Vec::new();
        for (name, a) in [("K.mtx", &k), ("M.mtx", &m)] {
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
                for (cell, z) in mesh.cells.iter().zip(&t.zones) {
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
        let mass_kg = fe_model::sparse::triplets(m.as_ref())
            .filter(|&(r, c, _)| r % 3 == 0 && c % 3 == 0)
            .map(|t| t.2)
            .sum();
        Ok(Summary {
            nodes: mesh.n_nodes(),
            elements: t.model.elements.len(),
            dof: mesh.n_dofs(),
            nnz_k: k.compute_nnz(),
            node_sets: mesh
                .node_sets
                .iter()
                .map(|(k, v)| (k.clone(), v.len()))
                .collect(),
            mass_kg,
            files,
        })
    }
}
