//! What the fe-model benchmarks share: their command-line options and the generated tire's
//! matrices on the free DOFs (rim fixed).

// each bench binary compiles this module and uses part of it
#![allow(dead_code)]

use faer::sparse::SparseColMat;
use fe_model::generate::Tire;
use fe_model::{DofSplit, MassKind};

/// The value after the option `name` on the command line.
pub fn arg(name: &str) -> Option<String> {
    std::env::args().skip_while(|a| a != name).nth(1)
}

/// The consistent `K` (with `K_G`) and `M` of the whole tire.
pub fn k_and_m(t: &Tire) -> (SparseColMat<usize, f64>, SparseColMat<usize, f64>) {
    t.model
        .k_and_m(MassKind::Consistent, true)
        .expect("assembly")
}

/// The blocks `K_ff`, `M_ff` of `k`, `m` on the DOFs left free by the fixed rim (node set
/// `rim`).
pub fn free_blocks(
    t: &Tire, k: &SparseColMat<usize, f64>, m: &SparseColMat<usize, f64>,
) -> (SparseColMat<usize, f64>, SparseColMat<usize, f64>) {
    let fixed = t.model.mesh.node_set_dofs("rim", None).expect("rim set");
    let p = DofSplit::fixed(k.nrows(), &fixed).expect("partition");
    let kff = p.block(k.as_ref(), false, false).expect("K_ff");
    let mff = p.block(m.as_ref(), false, false).expect("M_ff");
    (kff, mff)
}
