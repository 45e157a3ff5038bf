//! fe-model: the generated tire carcass (structure, invariants, axisymmetric spectrum).

use fe_model::eigen::{SparseEigenOptions, sparse_modes};
use fe_model::generate::{TireConfig, TireZone, tire};
use fe_model::{DofPartition, MassKind, dense_modes};

fn small() -> TireConfig {
    TireConfig {
        circumferential_divisions: 16,
        section_divisions: 10,
        thickness_divisions: 1,
        bead_elements: 1,
        ..Default::default()
    }
}

/// Mesh structure: node/element counts, node sets, zones; the default configuration has at
/// least 60 000 DOFs like the seed's ABAQUS tire (Ribaric §8.1).
#[test]
fn tire_mesh_structure_and_default_size() {
    let cfg = small();
    let t = tire(&cfg).unwrap();
    let (nc, ns, nt) = (16, 10, 1);
    assert_eq!(t.model.mesh.n_nodes(), nc * (ns + 1) * (nt + 1));
    assert_eq!(t.model.elements.len(), nc * ns * nt);
    assert_eq!(
        t.model.mesh.node_set("rim").unwrap().len(),
        2 * nc * (nt + 1)
    );
    assert!(!t.model.mesh.node_set("contact_patch").unwrap().is_empty());
    for z in [TireZone::Bead, TireZone::Sidewall, TireZone::Tread] {
        assert!(t.zones.contains(&z), "{z:?} missing");
    }
    // outer radius of the tread surface = outer_diameter / 2
    let rmax = t
        .model
        .mesh
        .nodes
        .iter()
        .map(|p| (p[0] * p[0] + p[2] * p[2]).sqrt())
        .fold(0.0, f64::max);
    assert!(
        (rmax - cfg.outer_diameter / 2.0).abs() < 1e-3,
        "outer radius {rmax}"
    );
    let d = TireConfig::default();
    let nodes =
        d.circumferential_divisions * (d.section_divisions + 1) * (d.thickness_divisions + 1);
    assert!(3 * nodes >= 60_000);
    // invalid input: typed error naming the field
    let bad = TireConfig {
        width: 0.01,
        ..small()
    };
    assert!(tire(&bad).unwrap_err().to_string().contains("width"));
}

/// Without inflation prestress and without supports, the tire has exactly six rigid-body
/// modes; with the rim fixed the spectrum shows the axisymmetric double modes, and the sparse
/// solver (Sturm-checked) agrees with the dense one.
#[test]
fn tire_rigid_modes_and_axisymmetric_pairs() {
    let cfg = TireConfig {
        inflation_pressure: 0.0,
        ..small()
    };
    let t = tire(&cfg).unwrap();
    let (k, m) = t.model.k_and_m(MassKind::Consistent, false).unwrap();
    let all = dense_modes(k.to_dense().as_ref(), m.to_dense().as_ref(), 10).unwrap();
    let first_elastic = all.values[6];
    let zeros = all
        .values
        .iter()
        .filter(|l| l.abs() < 1e-8 * first_elastic)
        .count();
    assert_eq!(zeros, 6, "{:?}", &all.values[..8]);
    let cfg = small();
    let t = tire(&cfg).unwrap();
    let (k, m) = t.model.k_and_m(MassKind::Consistent, true).unwrap();
    let fixed = t.model.mesh.node_set_dofs("rim", None).unwrap();
    let p = DofPartition::fixed(k.nrows(), &fixed).unwrap();
    let kff = p.block(k.as_ref(), false, false).unwrap();
    let mff = p.block(m.as_ref(), false, false).unwrap();
    let opts = SparseEigenOptions {
        dense_below: 10,
        max_dim: Some(120),
        ..Default::default()
    };
    let (sp, rep) = sparse_modes(kff.as_ref(), mff.as_ref(), 12, &opts).unwrap();
    assert!(!rep.dense_fallback);
    assert_eq!(rep.sturm_count, rep.found_below_cut);
    let de = dense_modes(kff.to_dense().as_ref(), mff.to_dense().as_ref(), 12).unwrap();
    for i in 0..12 {
        assert!((sp.values[i] - de.values[i]).abs() < 1e-9 * de.values[i]);
    }
    // count coincident neighbours: an axisymmetric structure has many double modes
    let pairs = sp
        .values
        .windows(2)
        .filter(|w| (w[1] - w[0]).abs() < 1e-8 * w[0])
        .count();
    assert!(
        pairs >= 4,
        "expected double modes, got {:?}",
        sp.frequencies_hz
    );
}
