//! Set-up shared by the validation test binaries (each binary uses part of it).
#![allow(dead_code)]

use std::sync::OnceLock;
use tire::{
    GroundKind, ReducedTire, ReductionConfig, RigConfig, TireFe, coarse_tire_config,
    generated_tire, reduce,
};

/// The coarse generated truck tire (96 × 8 elements, one element through the wall, 5 184 DOF)
/// with the isotropic materials of earlier versions (tread 150 MPa, no carcass cords), reduced
/// to 33 contact nodes and 50 free-node modes, built once per test binary.
///
/// Why not the default cord-reinforced materials: on this coarse mesh the stiffer cord tire
/// does not roll steadily with friction; its few patch nodes stick and slip in turn (flat road,
/// μ = 0.85, 60 km/h: Σλ varies by 176 N and Fx by 1.2 kN, against 1.5 N and 75 N with these
/// materials), a mesh artefact that the full-size default tire does not show (BENCHMARKS.md,
/// steady rolling: Fy and Fx constant within a few newtons). The rolling tests check the
/// integrator and the contact against steady states, so they need a tire that has them.
pub fn coarse_reduced_tire() -> &'static ReducedTire {
    static T: OnceLock<ReducedTire> = OnceLock::new();
    T.get_or_init(|| isotropic_reduced_tire(96, 20.0, 33))
}

/// The coarse isotropic tire of [`coarse_reduced_tire`] (8 section elements, tread 150 MPa, no
/// cords, 50 free-node modes) with `circumferential` elements around, the candidate patch
/// ±`patch_deg` degrees and `contact_nodes` contact nodes.
pub fn isotropic_reduced_tire(
    circumferential: usize, patch_deg: f64, contact_nodes: usize,
) -> ReducedTire {
    let mut cfg = coarse_tire_config(circumferential, 8, patch_deg);
    cfg.tread.young = 150e6;
    cfg.carcass = None;
    let fe = generated_tire(&cfg).expect("tire");
    let cfg = ReductionConfig {
        contact_nodes,
        free_modes: 50,
        ..Default::default()
    };
    reduce(&fe, &cfg).expect("reduce").0
}

/// The default cleat rig on the ground `kind`, with or without the cleat, friction `mu`.
pub fn rig(kind: GroundKind, cleat: bool, mu: f64) -> RigConfig {
    let mut rc = RigConfig::default();
    rc.ground.kind = kind;
    rc.ground.cleat = cleat;
    rc.rolling.friction = mu;
    rc
}

/// An imported tire against the generated one it was exported from (independent reference:
/// the same reduction, 12 contact nodes and 20 free-node modes): the first 20 reduced
/// frequencies agree to 1e-9 relative.
pub fn assert_same_reduced_frequencies(generated: &TireFe, imported: &TireFe) {
    let cfg = ReductionConfig {
        contact_nodes: 12,
        free_modes: 20,
        ..Default::default()
    };
    let fa = reduce(generated, &cfg).unwrap().0.frequencies_hz().unwrap();
    let fb = reduce(imported, &cfg).unwrap().0.frequencies_hz().unwrap();
    for (a, b) in fa.iter().zip(&fb).take(20) {
        assert!((b - a).abs() < 1e-9 * a.abs(), "{a} vs {b}");
    }
}
