//! Benchmark: reading the default truck tire's K and M (free DOFs, symmetric coordinate Matrix
//! Market, as `tire_modes --export` writes them) with fe-model's reader against scipy's
//! `scipy.io.mmread` in the same run (issue #16: "Matrix Market reading at least as fast as
//! scipy `mmread`").
//!
//! Run: `cargo bench --profile release --workspace --bench mtx_read -- [--python PY] [--dir DIR] [--repeat N]
//! [--rounds R]`
//! (PY: a Python with scipy, default `python3`; DIR: scratch folder for the two files, default
//! the system temp folder). R rounds (default 3), each reading N times (default 3) with ours in
//! this process and then N times with the peer in a fresh Python process, so that both see the
//! same machine load; prints the best timings of both readers, alone (entries / COO) and
//! including the conversion to a CSC matrix, and `ratio = ours / peer` for each; ours also
//! straight into CSC (`mtx::read_sparse_with`), against scipy's read + CSC and read alone.

mod common;

use common::{arg, free_blocks, k_and_m};
use fe_model::generate::{TireConfig, tire};
use fe_model::io::mtx;
use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

fn main() {
    let python = arg("--python").unwrap_or_else(|| "python3".into());
    let repeat: usize = arg("--repeat").and_then(|r| r.parse().ok()).unwrap_or(3);
    let rounds: usize = arg("--rounds").and_then(|r| r.parse().ok()).unwrap_or(3);
    let dir = PathBuf::from(arg("--dir").unwrap_or_else(|| {
        std::env::temp_dir()
            .join("flowmbd-mtx-bench")
            .display()
            .to_string()
    }));
    std::fs::create_dir_all(&dir).expect("scratch folder");
    let (kp, mp) = (dir.join("K.mtx"), dir.join("M.mtx"));
    if !(kp.is_file() && mp.is_file()) {
        let t = tire(&TireConfig::default()).expect("tire generation");
        let (k, m) = k_and_m(&t);
        let (kff, mff) = free_blocks(&t, &k, &m);
        mtx::write_sparse(&kp, kff.as_ref(), mtx::Symmetry::Symmetric).expect("K.mtx");
        mtx::write_sparse(&mp, mff.as_ref(), mtx::Symmetry::Symmetric).expect("M.mtx");
    }
    let bytes = std::fs::metadata(&kp).map(|m| m.len()).unwrap_or(0)
        + std::fs::metadata(&mp).map(|m| m.len()).unwrap_or(0);
    // ours and the peer alternate, so both see the same machine load
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/mmread.py");
    let (mut read, mut csc, mut direct) = (f64::INFINITY, f64::INFINITY, f64::INFINITY);
    let (mut pr, mut pc) = (f64::INFINITY, f64::INFINITY);
    let mut peer = String::new();
    let mut nnz = 0;
    let mut n = 0;
    for _ in 0..rounds {
        for _ in 0..repeat {
            let t0 = Instant::now();
            let k = mtx::read_with(&kp, &mtx::ReadOptions::symmetric()).expect("K");
            let m = mtx::read_with(&mp, &mtx::ReadOptions::symmetric()).expect("M");
            let t1 = t0.elapsed().as_secs_f64();
            let (ks, ms) = (k.to_sparse().expect("K csc"), m.to_sparse().expect("M csc"));
            let t2 = t0.elapsed().as_secs_f64();
            read = read.min(t1);
            csc = csc.min(t2);
            nnz = ks.compute_nnz() + ms.compute_nnz();
            n = ks.nrows();
            drop((k, m, ks, ms));
            let t0 = Instant::now();
            let ks = mtx::read_sparse_with(&kp, &mtx::ReadOptions::symmetric()).expect("K");
            let ms = mtx::read_sparse_with(&mp, &mtx::ReadOptions::symmetric()).expect("M");
            direct = direct.min(t0.elapsed().as_secs_f64());
            assert_eq!(ks.compute_nnz() + ms.compute_nnz(), nnz);
            drop((ks, ms));
        }
        let out = Command::new(&python)
            .arg(script)
            .arg(&dir)
            .arg(repeat.to_string())
            .output();
        let line = match out {
            Ok(o) if o.status.success() => String::from_utf8_lossy(&o.stdout).trim().to_string(),
            Ok(o) => {
                println!(
                    "peer: {python} failed: {}",
                    String::from_utf8_lossy(&o.stderr).trim()
                );
                continue;
            }
            Err(e) => {
                println!("peer: cannot run {python}: {e}");
                continue;
            }
        };
        let f: Vec<&str> = line.split_whitespace().collect();
        let (Some(a), Some(b)) = (
            f.get(3).and_then(|s| s.parse::<f64>().ok()),
            f.get(5).and_then(|s| s.parse::<f64>().ok()),
        ) else {
            println!("peer: unexpected output `{line}`");
            continue;
        };
        pr = pr.min(a);
        pc = pc.min(b);
        peer = format!("{} {}", f[0], f[1]);
    }
    println!(
        "files: {} and {} ({:.1} MB), n = {n}, nnz(K) + nnz(M) = {nnz}",
        kp.display(),
        mp.display(),
        bytes as f64 / 1e6
    );
    println!(
        "fe-model mtx: read {read:.3} s, read + CSC {csc:.3} s, read_sparse_with (straight to CSC) {direct:.3} s (best of {rounds} rounds of {repeat}, alternated with the peer)"
    );
    if peer.is_empty() {
        return;
    }
    println!(
        "peer {peer}: mmread {pr:.3} s, mmread + tocsc {pc:.3} s (best of {rounds} rounds of {repeat})"
    );
    println!("ratio = ours / peer = {:.2} (read)", read / pr);
    println!("ratio = ours / peer = {:.2} (read + CSC)", csc / pc);
    println!(
        "ratio = ours / peer = {:.2} (read_sparse_with / mmread + tocsc)",
        direct / pc
    );
    println!(
        "ratio = ours / peer = {:.2} (read_sparse_with / mmread alone)",
        direct / pr
    );
}
