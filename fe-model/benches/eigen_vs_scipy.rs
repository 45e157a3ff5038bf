//! Benchmark (issue #16, target 2; issue #37 item 1): the 50 lowest modes of the generated tire
//! (rim fixed) with fe-model's `sparse_modes` (shift-invert block Lanczos, Sturm check) against
//! scipy's `eigsh(K, 50, M, sigma=0, mode='normal', tol)` with a CHOLMOD shift-invert operator
//! (`benches/peers/eigsh.py`, installed by `benches/peers/setup_eigsh.sh`: CHOLMOD on
//! OpenBLAS), on the same K and M, at equal thread counts: for each size and each thread count
//! t the two run alternately, ours in a rayon pool of t threads with `Par::rayon(t)`, the peer
//! with `OPENBLAS_NUM_THREADS = OMP_NUM_THREADS = t`. Prints per size and thread count the best
//! time of each, the eigenvalue agreement and `ratio = ours / peer`, then a table.
//!
//! Run: `cargo bench -p fe-model --bench eigen_vs_scipy -- [--venv DIR | --python PY]
//! [--divisions 96,192,384] [--threads 1,2] [--repeat 2] [--nev 50] [--tol 1e-12] [--dir DIR]
//! [--block B] [--max-dim M] [--no-peer] [--superlu]`.
//! `--venv` (default: `flowmbd-eigsh-venv` in the system temp folder) is created by
//! `setup_eigsh.sh` when it has no scikit-sparse (apt-get for CHOLMOD and OpenBLAS when root,
//! pip for scipy and scikit-sparse); `--python` uses a given interpreter as is. The matrices
//! are written once per size into DIR (default: the system temp folder) as `K.mtx`, `M.mtx`;
//! neither side's reading is timed. `--no-peer` runs ours only (profiling); `--block`,
//! `--max-dim` override the block Lanczos defaults.

mod common;

use common::{arg, free_blocks, k_and_m};
use faer::Par;
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

/// Comma-separated integers of the option `name`.
fn list(name: &str, default: &str) -> Vec<usize> {
    arg(name)
        .unwrap_or_else(|| default.into())
        .split(',')
        .map(|d| {
            d.trim()
                .parse()
                .unwrap_or_else(|_| panic!("{name}: comma-separated integers"))
        })
        .collect()
}

/// The peer's interpreter: `--python` as given, or the venv of `--venv`, set up by
/// `setup_eigsh.sh` when it cannot import scikit-sparse.
fn peer_python(peers: &Path) -> String {
    if let Some(py) = arg("--python") {
        return py;
    }
    let venv = PathBuf::from(arg("--venv").unwrap_or_else(|| {
        std::env::temp_dir()
            .join("flowmbd-eigsh-venv")
            .display()
            .to_string()
    }));
    let py = venv.join("bin/python");
    let ready = Command::new(&py)
        .args(["-c", "import sksparse.cholmod, threadpoolctl"])
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false);
    if !ready {
        eprintln!("setting up the peer in {} ...", venv.display());
        let st = Command::new("bash")
            .arg(peers.join("setup_eigsh.sh"))
            .arg(&venv)
            .status()
            .expect("running setup_eigsh.sh");
        assert!(st.success(), "setup_eigsh.sh failed");
    }
    py.display().to_string()
}

/// One row of the final table.
struct Row {
    dof: usize,
    threads: usize,
    ours: f64,
    peer: f64,
    agree: f64,
}

fn main() {
    let peers = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/peers");
    let no_peer = std::env::args().any(|a| a == "--no-peer");
    let python = if no_peer {
        String::new()
    } else {
        peer_python(&peers)
    };
    let repeat: usize = arg("--repeat").and_then(|r| r.parse().ok()).unwrap_or(2);
    let nev: usize = arg("--nev").and_then(|r| r.parse().ok()).unwrap_or(50);
    let superlu = std::env::args().any(|a| a == "--superlu");
    let divisions = list("--divisions", "96,192,384");
    let threads = list("--threads", "1,2");
    let mut opts = SparseEigenOptions::default();
    if let Some(t) = arg("--tol").and_then(|r| r.parse().ok()) {
        opts.tolerance = t;
    }
    if let Some(b) = arg("--block").and_then(|r| r.parse().ok()) {
        opts.block_size = b;
    }
    opts.max_dim = arg("--max-dim").and_then(|r| r.parse().ok());
    let base = PathBuf::from(arg("--dir").unwrap_or_else(|| {
        std::env::temp_dir()
            .join("flowmbd-eigen-bench")
            .display()
            .to_string()
    }));
    let script = peers.join("eigsh.py");
    let mut rows = Vec::new();
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
        drop((t, k, m));
        let n = kff.nrows();
        if !no_peer {
            let (kp, mp) = (dir.join("K.mtx"), dir.join("M.mtx"));
            mtx::write_sparse(&kp, kff.as_ref(), mtx::Symmetry::Symmetric).expect("K.mtx");
            mtx::write_sparse(&mp, mff.as_ref(), mtx::Symmetry::Symmetric).expect("M.mtx");
        }
        println!(
            "tire {div} divisions: {n} DOF, nnz(K) {}",
            kff.compute_nnz()
        );
        for &nt in &threads {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(nt)
                .build()
                .expect("rayon pool");
            let o = SparseEigenOptions {
                par: if nt == 1 { Par::Seq } else { Par::rayon(nt) },
                ..opts.clone()
            };
            let vals_file = dir.join(format!("peer_values_{nt}.txt"));
            let (mut ours, mut peer) = (f64::INFINITY, f64::INFINITY);
            let (mut modes, mut rep) = (None, None);
            let mut peer_out = String::new();
            for _ in 0..repeat {
                let t0 = Instant::now();
                let (md, rp) = pool
                    .install(|| sparse_modes(kff.as_ref(), mff.as_ref(), nev, &o))
                    .expect("sparse_modes");
                let secs = t0.elapsed().as_secs_f64();
                if secs < ours {
                    ours = secs;
                    rep = Some(rp);
                }
                modes = Some(md);
                if no_peer {
                    continue;
                }
                let mut cmd = Command::new(&python);
                cmd.arg(&script)
                    .arg(&dir)
                    .args(["--nev", &nev.to_string()])
                    .args(["--tol", &o.tolerance.to_string()])
                    .arg("--out")
                    .arg(&vals_file)
                    .env("OPENBLAS_NUM_THREADS", nt.to_string())
                    .env("OMP_NUM_THREADS", nt.to_string());
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
                    peer_out = text;
                }
            }
            let (modes, rep) = (modes.unwrap(), rep.unwrap());
            println!(
                "  {nt} thread(s), ours: {ours:.3} s (factor {:.3} s; block Lanczos {:.3} s = operator {:.3} + orthogonalisation {:.3} + Rayleigh-Ritz {:.3} [{} vectors, block {}, basis {}, {} restarts]; Sturm {:.3} s: {} below the cut = {} found; checks {:.3} s), nnz(L) {}, max |ΦᵀMΦ − I| {:.1e}, max residual {:.1e}",
                rep.seconds_factor,
                rep.seconds_lanczos,
                rep.seconds_operator,
                rep.seconds_orthogonalisation,
                rep.seconds_rayleigh_ritz,
                rep.operator_applications,
                rep.block_size,
                rep.max_dim,
                rep.restarts,
                rep.seconds_sturm,
                rep.sturm_count.unwrap_or(0),
                rep.found_below_cut.unwrap_or(0),
                rep.seconds_checks,
                rep.factor_nnz,
                rep.max_orthogonality_error,
                rep.max_relative_residual
            );
            if no_peer {
                continue;
            }
            let peer_vals: Vec<f64> = std::fs::read_to_string(&vals_file)
                .expect("peer values")
                .lines()
                .map(|l| l.parse().expect("peer value"))
                .collect();
            let agree = modes
                .values
                .iter()
                .zip(&peer_vals)
                .map(|(a, b)| (a - b).abs() / b.abs())
                .fold(0.0f64, f64::max);
            let f = |k: &str| field(&peer_out, k).unwrap_or_default();
            println!(
                "  {nt} thread(s), peer: {peer:.3} s ({}, factor {} s, {} solves); eigenvalues agree to {agree:.1e} (relative, {} modes)",
                f("peer_solver"),
                f("peer_factor_seconds"),
                f("peer_solves"),
                peer_vals.len().min(modes.len())
            );
            println!("    peer BLAS: {}", f("peer_blas"));
            println!("    peer mapped: {}", f("peer_mapped"));
            println!("  {nt} thread(s): ratio = ours / peer = {:.3}", ours / peer);
            rows.push(Row {
                dof: n,
                threads: nt,
                ours,
                peer,
                agree,
            });
        }
    }
    if !rows.is_empty() {
        println!("\n| free DOF | threads | ours [s] | peer [s] | ratio | eigenvalues agree |");
        println!("|---|---|---|---|---|---|");
        for r in &rows {
            println!(
                "| {} | {} | {:.2} | {:.2} | **{:.3}** | {:.1e} |",
                r.dof,
                r.threads,
                r.ours,
                r.peer,
                r.ours / r.peer,
                r.agree
            );
        }
    }
}
