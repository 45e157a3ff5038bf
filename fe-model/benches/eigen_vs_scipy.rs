//! Benchmark (issue 37, item 1): the 50 lowest modes of the generated tire (rim fixed) with
//! fe-model's `sparse_modes` (shift-invert block Lanczos, Sturm check) against scipy's
//! `eigsh(K, 50, M, sigma=0, mode='normal')` with a CHOLMOD shift-invert operator
//! (`benches/peers/eigsh.py`), on the same K and M, at equal thread counts, the two sides
//! alternating (ours, peer, ours, peer, … per size and thread count).
//!
//! Run: `cargo bench -p fe-model --bench eigen_vs_scipy -- --peer-venv /tmp/eigpeer
//! [--divisions 96,192,384] [--threads 1,2] [--repeat 2] [--nev 50] [--tol 1e-12] [--peer-coretype SkylakeX] [--dir DIR] [--block B] [--max-dim M] [--theta-max-test] [--no-peer]` (`--no-peer`: ours only, for profiling;
//! `--block B`, `--max-dim M`: our block width and basis size instead of the defaults;
//! `--theta-max-test`: ours with the looser `‖r‖ ≤ tol·θ_max` test instead of the default
//! per-pair test, which is ARPACK's).
//!
//! **The peer, configured as its users would.** `--peer-venv DIR` installs it on first use by
//! running `benches/peers/setup_eigsh_peer.sh DIR` (Debian's SuiteSparse 5.12 CHOLMOD with
//! `libblas.so.3`/`liblapack.so.3` pointed at Debian's OpenBLAS 0.3.21 pthread build; numpy,
//! scipy and threadpoolctl wheels from PyPI, which bundle scipy-openblas for ARPACK's dense
//! work; scikit-sparse 0.4.15 built against that CHOLMOD); `--python PY` uses an existing
//! Python instead. For `t` threads the bench starts the peer with `OPENBLAS_NUM_THREADS=t` and
//! `OMP_NUM_THREADS=t` (both OpenBLAS builds and CHOLMOD's OpenMP loops read them) and
//! `OPENBLAS_CORETYPE=SkylakeX` (`--peer-coretype NAME`; `auto` leaves the variable as it is):
//! Debian's OpenBLAS 0.3.21 does not know this machine's Xeon (AVX-512 FP16, Sapphire Rapids
//! class) and falls back to its Prescott (SSE3) kernels when left to detect the CPU, which would
//! handicap CHOLMOD about threefold; scipy-openblas 0.3.31 detects SkylakeX by itself. The
//! peer limits numpy's and scipy's bundled OpenBLAS (ARPACK's dense work) to one thread with
//! threadpoolctl (`--scipy-blas-threads 1`): with those at two threads (all that the
//! environment variables can say) the peer took 32.8 s instead of 4.8 s at 30 240 DOF (their
//! two-thread level-2 kernels, on two OpenBLAS pools, fight on two cores). The
//! peer prints the BLAS libraries it loaded, their kernel and thread counts (threadpoolctl),
//! which the bench echoes; its eigenvalues are compared with ours.
//!
//! **Ours at `t` threads**: `sparse_modes` runs inside a rayon pool of `t` threads (faer's
//! `Par::rayon(0)` in the numeric factorisations, the block solves and the dense kernels takes
//! its thread count from the pool).
//!
//! **Work compared.** Peer: CHOLMOD supernodal `L Lᵀ` of K (AMD/METIS ordering as CHOLMOD
//! picks), ARPACK shift-invert Lanczos (ncv = 2·nev + 1, tolerance `--tol`, ARPACK's per-pair
//! test `‖r_i‖ ≤ tol·|θ_i|`), eigenvectors returned; no check of the result. Ours: the default
//! options of `sparse_modes` except `tolerance = --tol` (the same per-pair test on the nev
//! returned modes, `tol·θ_max` on the 4 extra pairs that place the Sturm cut): `L Lᵀ` of K, block Lanczos, back-transform,
//! M-orthogonality check, residuals, and the Sturm `L D Lᵀ` count of `K − cM`. The ratio is
//! printed with all of ours (`ratio`) and without the Sturm factorisation (`ratio w/o Sturm`,
//! the peer's work). Neither side's matrix reading is timed. The eigenvalues are compared
//! (max relative difference).

mod common;

use common::{arg, free_blocks, k_and_m};
use fe_model::eigen::{Modes, SparseEigenOptions, SparseEigenReport, sparse_modes};
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

/// CPU seconds (user + system) of this process so far, from `/proc/self/stat` (10 ms ticks).
fn cpu_seconds() -> f64 {
    let s = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = s.rsplit_once(')').map(|x| x.1).unwrap_or("");
    let f: Vec<&str> = after.split_whitespace().collect();
    let tick = |i: usize| f.get(i).and_then(|v| v.parse::<f64>().ok()).unwrap_or(0.0);
    // fields 14 and 15 of stat (utime, stime) are 12 and 13 after the command name
    (tick(11) + tick(12)) / 100.0
}

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

/// Best-of figures of one side at one thread count.
#[derive(Default)]
struct Best {
    wall: f64,
    cpu: f64,
    sturm: f64,
}

/// Our run's times and counts (up to the Sturm time, parenthesis open).
fn ours_line(ours: &Best, rep: &SparseEigenReport) -> String {
    format!(
        "{:.3} s wall, {:.2} s CPU (factor {:.3} s, nnz(L) {}, block Lanczos {:.3} s [operator {:.3} s, {} vectors, block {}, basis {}, {} restarts], Sturm {:.3} s",
        ours.wall,
        ours.cpu,
        rep.seconds_factor,
        rep.factor_nnz,
        rep.seconds_lanczos,
        rep.seconds_operator,
        rep.operator_applications,
        rep.block_size,
        rep.max_dim,
        rep.restarts,
        rep.seconds_sturm
    )
}

fn main() {
    let repeat: usize = arg("--repeat").and_then(|r| r.parse().ok()).unwrap_or(2);
    let nev: usize = arg("--nev").and_then(|r| r.parse().ok()).unwrap_or(50);
    let tol: f64 = arg("--tol").and_then(|r| r.parse().ok()).unwrap_or(1e-12);
    let divisions = list("--divisions", "96,192,384");
    let threads = list("--threads", "1,2");
    let no_peer = std::env::args().any(|a| a == "--no-peer");
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    let python = match (arg("--python"), arg("--peer-venv")) {
        _ if no_peer => String::new(),
        (Some(p), _) => p,
        (None, Some(venv)) => {
            let st = Command::new("bash")
                .arg(manifest.join("benches/peers/setup_eigsh_peer.sh"))
                .arg(&venv)
                .status()
                .expect("running setup_eigsh_peer.sh");
            assert!(st.success(), "setup_eigsh_peer.sh {venv} failed");
            format!("{venv}/bin/python")
        }
        (None, None) => panic!("give --peer-venv DIR (installed on first use) or --python PY"),
    };
    let base = PathBuf::from(arg("--dir").unwrap_or_else(|| {
        std::env::temp_dir()
            .join("flowmbd-eigen-bench")
            .display()
            .to_string()
    }));
    let coretype = arg("--peer-coretype").unwrap_or_else(|| "SkylakeX".into());
    let script = manifest.join("benches/peers/eigsh.py");
    let defaults = SparseEigenOptions::default();
    let opts = SparseEigenOptions {
        tolerance: tol,
        block_size: arg("--block")
            .and_then(|b| b.parse().ok())
            .unwrap_or(defaults.block_size),
        max_dim: arg("--max-dim").and_then(|b| b.parse().ok()),
        per_pair_test: !std::env::args().any(|a| a == "--theta-max-test"),
        ..defaults
    };
    println!(
        "eigen_vs_scipy: nev {nev}, tol {tol:e} (ours: {} test), threads {threads:?}, repeat {repeat}; peer {python}, OPENBLAS_CORETYPE {coretype}",
        if opts.per_pair_test {
            "per-pair"
        } else {
            "θ_max"
        }
    );
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
        drop((k, m, t));
        let (kp, mp) = (dir.join("K.mtx"), dir.join("M.mtx"));
        mtx::write_sparse(&kp, kff.as_ref(), mtx::Symmetry::Symmetric).expect("K.mtx");
        mtx::write_sparse(&mp, mff.as_ref(), mtx::Symmetry::Symmetric).expect("M.mtx");
        let n = kff.nrows();
        println!(
            "tire {div} divisions: {n} DOF, nnz(K) {} (both triangles)",
            kff.compute_nnz()
        );
        for &nt in &threads {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(nt)
                .build()
                .expect("rayon pool");
            let vals_file = dir.join(format!("peer_values_{nt}.txt"));
            let (mut ours, mut peer) = (
                Best {
                    wall: f64::INFINITY,
                    ..Best::default()
                },
                Best {
                    wall: f64::INFINITY,
                    ..Best::default()
                },
            );
            let mut last: Option<(Modes, SparseEigenReport)> = None;
            let (mut solver, mut solves, mut blas, mut peer_factor) =
                (String::new(), String::new(), String::new(), 0.0);
            for _ in 0..repeat {
                let (t0, c0) = (Instant::now(), cpu_seconds());
                let r = pool
                    .install(|| sparse_modes(kff.as_ref(), mff.as_ref(), nev, &opts))
                    .expect("sparse_modes");
                let (wall, cpu) = (t0.elapsed().as_secs_f64(), cpu_seconds() - c0);
                if wall < ours.wall {
                    ours = Best {
                        wall,
                        cpu,
                        sturm: r.1.seconds_sturm,
                    };
                    // the printed breakdown is that of the fastest run
                    last = Some(r);
                }
                if no_peer {
                    continue;
                }
                let mut cmd = Command::new(&python);
                if coretype != "auto" {
                    cmd.env("OPENBLAS_CORETYPE", &coretype);
                }
                let out = cmd
                    .arg(&script)
                    .arg(&dir)
                    .arg("--nev")
                    .arg(nev.to_string())
                    .arg("--tol")
                    .arg(tol.to_string())
                    .arg("--scipy-blas-threads")
                    .arg("1")
                    .arg("--out")
                    .arg(&vals_file)
                    .env("OPENBLAS_NUM_THREADS", nt.to_string())
                    .env("OMP_NUM_THREADS", nt.to_string())
                    .output()
                    .expect("running the python peer");
                let text = String::from_utf8_lossy(&out.stdout).to_string();
                assert!(
                    out.status.success(),
                    "peer failed: {}",
                    String::from_utf8_lossy(&out.stderr)
                );
                let num = |k: &str| -> f64 {
                    field(&text, k)
                        .and_then(|v| v.parse().ok())
                        .unwrap_or_else(|| panic!("peer printed no {k}"))
                };
                let secs = num("peer_seconds");
                if secs < peer.wall {
                    peer = Best {
                        wall: secs,
                        cpu: num("peer_cpu_seconds"),
                        sturm: 0.0,
                    };
                    peer_factor = num("peer_factor_seconds");
                }
                solver = field(&text, "peer_solver").unwrap_or_default();
                solves = field(&text, "peer_solves").unwrap_or_default();
                blas = field(&text, "peer_blas").unwrap_or_default();
            }
            let (modes, rep) = last.expect("a finite time");
            if no_peer {
                println!("  {nt} thread(s): ours {})", ours_line(&ours, &rep));
                continue;
            }
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
            println!("  {nt} thread(s):");
            println!(
                "    ours: {}: {} below the cut = {} found), max |ΦᵀMΦ − I| {:.1e}, max residual {:.1e}",
                ours_line(&ours, &rep),
                rep.sturm_count.unwrap_or(0),
                rep.found_below_cut.unwrap_or(0),
                rep.max_orthogonality_error,
                rep.max_relative_residual
            );
            println!(
                "    peer: {:.3} s wall, {:.2} s CPU ({solver}, factor {peer_factor:.3} s, {solves} solves; BLAS: {blas})",
                peer.wall, peer.cpu
            );
            println!(
                "    eigenvalues agree to {max_rel:.1e} (relative, {} modes)",
                peer_vals.len().min(modes.len())
            );
            println!(
                "    ratio = ours / peer = {:.3} (CPU {:.3}); w/o Sturm {:.3}",
                ours.wall / peer.wall,
                ours.cpu / peer.cpu,
                (ours.wall - ours.sturm) / peer.wall
            );
        }
    }
}
