//! Benchmark: Craig–Bampton reduction of fe-model's generated truck tire (≈ 64 000 DOF, rim
//! clamped: the fixed set of the partition) with 95 interface nodes on the tread (the
//! contact-patch nodes closest to the patch centre) and 50 fixed-interface modes. Static modes
//! reuse one sparse Cholesky of `K_ii`.
//! Prints the timings of each phase (one run; the figures go into BENCHMARKS.md).
//!
//! Run: `cargo bench -p reduction --bench cb_tire`.

use fe_model::MassKind;
use fe_model::generate::{TireConfig, tire};
use reduction::DofPartition;
use reduction::sparse::{CraigBamptonOptions, craig_bampton_sparse};
use std::time::Instant;

fn main() {
    let t0 = Instant::now();
    let tire = tire(&TireConfig::default()).expect("tire generation");
    let (k, m) = tire
        .model
        .k_and_m(MassKind::Consistent, true)
        .expect("assembly");
    let t_build = t0.elapsed().as_secs_f64();
    let mesh = &tire.model.mesh;
    // the rim is the fixed set (clamped)
    let rim = mesh.node_set_dofs("rim", None).expect("rim set");
    // 95 interface nodes: contact-patch nodes nearest to the patch centre (lowest point)
    let patch = mesh.node_set("contact_patch").expect("patch set").to_vec();
    let zmin = patch
        .iter()
        .map(|&j| mesh.nodes[j][2])
        .fold(f64::INFINITY, f64::min);
    let centre = patch
        .iter()
        .copied()
        .min_by(|&a, &b| {
            let da = (mesh.nodes[a][2] - zmin).abs() + mesh.nodes[a][1].abs();
            let db = (mesh.nodes[b][2] - zmin).abs() + mesh.nodes[b][1].abs();
            da.total_cmp(&db)
        })
        .expect("non-empty patch");
    let c = mesh.nodes[centre];
    let mut sorted = patch.clone();
    sorted.sort_by(|&a, &b| {
        let d = |j: usize| {
            let p = mesh.nodes[j];
            (p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2)
        };
        d(a).total_cmp(&d(b))
    });
    sorted.truncate(95);
    assert_eq!(
        sorted.len(),
        95,
        "the contact patch has fewer than 95 nodes"
    );
    let bdofs: Vec<usize> = sorted
        .iter()
        .flat_map(|&j| (0..3).map(move |comp| mesh.dof(j, comp)))
        .collect();
    let part = DofPartition::new(k.nrows(), &bdofs, &rim).expect("rim / interface partition");
    let t1 = Instant::now();
    let opts = CraigBamptonOptions::with_modes(50);
    let (red, rep) =
        craig_bampton_sparse(k.as_ref(), m.as_ref(), &part, &opts, 3).expect("Craig-Bampton");
    let total = t1.elapsed().as_secs_f64();
    println!(
        "tire: {} DOF ({} fixed), {} interface nodes ({} DOF), {} modes -> {} reduced coordinates",
        k.nrows(),
        rep.n_fixed,
        sorted.len(),
        bdofs.len(),
        rep.n_modes,
        red.n_reduced()
    );
    println!("model generation + assembly {t_build:.2} s (not part of the reduction)");
    println!(
        "static modes (1 Cholesky + {} solves) {:.2} s, fixed-interface modes {:.2} s, projection {:.2} s, total {:.2} s",
        bdofs.len(),
        rep.static_modes_s,
        rep.normal_modes_s,
        rep.projection_s,
        total
    );
    let f = red.natural_frequencies_hz().expect("reduced eigen");
    println!(
        "lowest reduced frequencies [Hz]: {:?}",
        &f[..6.min(f.len())]
    );
}
