//! Benchmark (issue #16, target 2): the 50 lowest modes of the generated tire (rim fixed) with
//! fe-model's `sparse_modes` (shift-invert block Lanczos, Sturm check) against scipy's
//! `eigsh(K, 50, M, sigma=0, mode='normal')` with a CHOLMOD shift-invert operator
//! (`benches/peers/eigsh.py`; SuperLU with MMD_AT_PLUS_A when scikit-sparse is missing), on the
//! same K and M, the two run alternately. Prints per size the best time of each, the eigenvalue
//! agreement and `ratio = ours / peer`.
//!
//! Run: `cargo bench -p fe-model --bench eigen_vs_scipy -- --python PY [--dir DIR]
//! [--divisions 96,192,288] [--repeat 2] [--nev 50] [--superlu]` (PY: a Python with numpy,
//! scipy and scikit-sparse). The matrices are written once per size into DIR (default: the
//! system temp folder) as `K.mtx`, `M.mtx`; neither side's reading is timed.

mod common;

use common::{arg, free_blocks, k_and_m};
use fe_model::eigen::{SparseEigenOptions, sparse_modes};
use fe_model::generate::{TireConfig, tire};
use fe_model::io::mtx;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// The peer's printed `key = value` line.
fn field(out: &str, key: &str) -> Option<String> {
    out.lines().find_map(|l| {
        l.strip_prefix(key)?
            .trim()
            .strip_prefix('=')
            .map(|v| v.trim().to_string())
    })
}

fn main() {
    let python = arg("--python").unwrap_or_else(|| "python3".into());
    let repeat: usize = arg("--repeat").and_then(|r| r.parse().ok()).unwrap_or(2);
    let nev: usize = arg("--nev").and_then(|r| r.parse().ok()).unwrap_or(50);
    let superlu = std::env::args().any(|a| a == "--superlu");
    let divisions: Vec<usize> = arg("--divisions")
        .unwrap_or_else(|| "96,192,288".into())
        .split(',')
        .map(|d| {
            d.trim()
                .parse()
                .expect("--divisions: comma-separated integers")
        })
        .collect();
    let base = PathBuf::from(arg("--dir").unwrap_or_else(|| {
        std::env::temp_dir()
            .join("flowmbd-eigen-bench")
            .display()
            .to_string()
    }));
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/peers/eigsh.py");
    for &div in &divisions {
        let dir = base.join(format!("tire{div}"));
        std::fs::create_dir_all(&dir).expect("scratch folder");
        let cfg = TireConfig {
            circumferential_divisions: div,
            ..TireConfig::default()
        };
        let t = tire(&cfg).expect("tire generation");
        let (k, m) = k_and_m(&t);
        let (kff, mff) = free_blocks(&t, &k, &m);
        let (kp, mp) = (dir.join("K.mtx"), dir.join("M.mtx"));
        mtx::write_sparse(&kp, kff.as_ref(), mtx::Symmetry::Symmetric).expect("K.mtx");
        mtx::write_sparse(&mp, mff.as_ref(), mtx::Symmetry::Symmetric).expect("M.mtx");
        let n = kff.nrows();
        let vals_file = dir.join("peer_values.txt");
        let (mut ours, mut peer) = (f64::INFINITY, f64::INFINITY);
        let (mut modes, mut rep) = (None, None);
        let (mut solver, mut solves, mut peer_factor) = (String::new(), String::new(), 0.0);
        for _ in 0..repeat {
            let t0 = Instant::now();
            let (md, rp) = sparse_modes(
                kff.as_ref(),
                mff.as_ref(),
                nev,
                &SparseEigenOptions::default(),
            )
            .expect("sparse_modes");
            ours = ours.min(t0.elapsed().as_secs_f64());
            modes = Some(md);
            rep = Some(rp);
            let mut cmd = Command::new(&python);
            cmd.arg(&script)
                .arg(&dir)
                .arg("--nev")
                .arg(nev.to_string())
                .arg("--out")
                .arg(&vals_file);
            if superlu {
                cmd.arg("--superlu");
            }
            let out = cmd.output().expect("running the python peer");
            let text = String::from_utf8_lossy(&out.stdout).to_string();
            assert!(
                out.status.success(),
                "peer failed: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            let secs: f64 = field(&text, "peer_seconds")
                .and_then(|v| v.parse().ok())
                .expect("peer_seconds");
            if secs < peer {
                peer = secs;
                peer_factor = field(&text, "peer_factor_seconds")
                    .and_then(|v| v.parse().ok())
                    .unwrap_or(0.0);
            }
            solver = field(&text, "peer_solver").unwrap_or_default();
            solves = field(&text, "peer_solves").unwrap_or_default();
        }
        let (modes, rep) = (modes.unwrap(), rep.unwrap());
        let peer_vals: Vec<f64> = std::fs::read_to_string(&vals_file)
            .expect("peer values")
            .lines()
            .map(|l| l.parse().expect("peer value"))
            .collect();
        let max_rel = modes
            .values
            .iter()
            .zip(&peer_vals)
            .map(|(a, b)| (a - b).abs() / b.abs())
            .fold(0.0f64, f64::max);
        println!(
            "tire {div} divisions: {n} DOF, nnz(K) {}, nnz(L) {}",
            kff.compute_nnz(),
            rep.factor_nnz
        );
        println!(
            "  ours: {ours:.3} s (factor {:.3} s, block Lanczos {:.3} s [{} vectors, block {}, basis {}, {} restarts], Sturm {:.3} s: {} below the cut = {} found), max |ΦᵀMΦ − I| {:.1e}, max residual {:.1e}",
            rep.seconds_factor,
            rep.seconds_lanczos,
            rep.operator_applications,
            rep.block_size,
            rep.max_dim,
            rep.restarts,
            rep.seconds_sturm,
            rep.sturm_count.unwrap_or(0),
            rep.found_below_cut.unwrap_or(0),
            rep.max_orthogonality_error,
            rep.max_relative_residual
        );
        println!(
            "  peer: {peer:.3} s ({solver}, factor {peer_factor:.3} s, {solves} solves); eigenvalues agree to {max_rel:.1e} (relative, {} modes)",
            peer_vals.len().min(modes.len())
        );
        println!("  ratio = ours / peer = {:.3}", ours / peer);
    }
}
