//! Set-up shared by the validation test binaries (each binary uses part of it).
#![allow(dead_code)]

use flowing::tire::{
    GroundKind, ReducedTire, ReductionConfig, RigConfig, coarse_tire_config, generated_tire, reduce,
};
use std::sync::OnceLock;

/// The coarse generated truck tire (96 × 8 elements, 5 184 DOF) reduced to 33 contact nodes
/// and 50 free-node modes, built once per test binary.
pub fn coarse_reduced_tire() -> &'static ReducedTire {
    static T: OnceLock<ReducedTire> = OnceLock::new();
    T.get_or_init(|| {
        let fe = generated_tire(&coarse_tire_config(96, 8, 20.0)).expect("tire");
        let cfg = ReductionConfig {
            contact_nodes: 33,
            free_modes: 50,
            ..Default::default()
        };
        reduce(&fe, &cfg).expect("reduce").0
    })
}

/// The default cleat rig on the ground `kind`, with or without the cleat, friction `mu`.
pub fn rig(kind: GroundKind, cleat: bool, mu: f64) -> RigConfig {
    let mut rc = RigConfig::default();
    rc.ground.kind = kind;
    rc.ground.cleat = cleat;
    rc.rolling.friction = mu;
    rc
}
