//! Benchmark: lowest 50 modes of the generated truck tire (rim fixed), sparse shift-invert
//! Lanczos with Sturm check. Prints DOF, timings and the safeguard results.
//!
//! Run: `cargo bench -p fe-model --bench tire_modes` (optionally `-- --export DIR` to write
//! M.mtx, K.mtx (free DOFs)). The side-by-side comparison with scipy's eigsh at three sizes is
//! `benches/eigen_vs_scipy.rs`.

mod common;

use common::{arg, free_blocks, k_and_m};
use fe_model::eigen::{SparseEigenOptions, sparse_modes};
use fe_model::generate::{TireConfig, tire};
use fe_model::io::mtx;
use std::time::Instant;

fn main() {
    let export = arg("--export");
    let cfg = TireConfig::default();
    let t0 = Instant::now();
    let tire = tire(&cfg).expect("tire generation");
    let t_gen = t0.elapsed();
    let t1 = Instant::now();
    let (k, m) = k_and_m(&tire);
    let t_asm = t1.elapsed();
    let (kff, mff) = free_blocks(&tire, &k, &m);
    if let Some(dir) = export {
        std::fs::create_dir_all(&dir).expect("export dir");
        mtx::write_sparse(
            format!("{dir}/K.mtx"),
            kff.as_ref(),
            mtx::Symmetry::Symmetric,
        )
        .expect("K.mtx");
        mtx::write_sparse(
            format!("{dir}/M.mtx"),
            mff.as_ref(),
            mtx::Symmetry::Symmetric,
        )
        .expect("M.mtx");
        eprintln!("wrote {dir}/K.mtx, {dir}/M.mtx");
    }
    let t2 = Instant::now();
    let (modes, rep) = sparse_modes(
        kff.as_ref(),
        mff.as_ref(),
        50,
        &SparseEigenOptions::default(),
    )
    .expect("eigen solution");
    let t_eig = t2.elapsed();
    println!(
        "tire: nodes {}, elements {}, total DOF {}, free DOF {}",
        tire.model.mesh.n_nodes(),
        tire.model.elements.len(),
        k.nrows(),
        kff.nrows()
    );
    println!("nnz K_ff {}, nnz L {}", kff.compute_nnz(), rep.factor_nnz);
    println!(
        "generate {:.3} s, assemble K+K_G+M {:.3} s, eigen (50 modes) {:.3} s",
        t_gen.as_secs_f64(),
        t_asm.as_secs_f64(),
        t_eig.as_secs_f64()
    );
    println!(
        "max_dim {}, attempts {}, converged {}, Sturm cut {:.3} Hz: count {} / found {}, max |Φᵀ M Φ − I| {:.2e}, max rel residual {:.2e}",
        rep.max_dim,
        rep.attempts,
        rep.converged,
        fe_model::eigen::frequency_hz(rep.sturm_cut.unwrap_or(0.0)),
        rep.sturm_count.unwrap_or(0),
        rep.found_below_cut.unwrap_or(0),
        rep.max_orthogonality_error,
        rep.max_relative_residual
    );
    println!(
        "eigen breakdown: factor {:.3} s, block Lanczos {:.3} s, Sturm LDLT {:.3} s; rejected attempts: {:?}",
        rep.seconds_factor, rep.seconds_lanczos, rep.seconds_sturm, rep.rejected_attempts
    );
    let f: Vec<String> = modes
        .frequencies_hz
        .iter()
        .map(|f| format!("{f:.3}"))
        .collect();
    println!("frequencies [Hz]: {}", f.join(" "));
}
