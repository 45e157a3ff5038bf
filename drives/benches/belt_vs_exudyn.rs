//! flowmbd's planar ANCF belt drive against Exudyn (issue 16, target 1): Kerkkänen Table 3.1
//! (20 belt elements, driver ramp (3.29) to 12 rad/s between 0.05 and 0.6 s, 1 s simulated) at
//! E = 1e8 and 1e9 Pa, ours and the peer run alternately so that both see the same load.
//!
//! - ours: `drives::ancf_study` (the code path of `flowmbd-belt ancf`) with its default
//!   integrator settings (generalized-α, `SimulationConfig::default`);
//! - peer: `benches/peers/exudyn_belt.py` (Exudyn `ObjectANCFCable2D` +
//!   `ObjectContactFrictionCircleCable2D`, generalized-α, modified Newton, EigenSparse), run by
//!   the Python of the worktree's venv (`EXUDYN_PYTHON` overrides `<workspace>/.venv/bin/python`).
//!   Its step per modulus is the largest of 1e-4, 2e-4, 4e-4 s whose driven speed stays within
//!   `TOL` of its own converged run (the sweep is in BENCHMARKS.md): 1e-4 s at E = 1e8 (at
//!   2e-4 s its driven speed is off by 0.3 rad/s), 4e-4 s at E = 1e9.
//!
//! Accuracy: each code's driven-pulley speed history (1 ms samples) is compared with the same
//! code at h = 2.5e-5 s, ours with the Newton tolerance 1e-7 m (`BELT_VS_EXUDYN_REFERENCE=0`
//! skips these runs): the largest deviation over [0, 1] s, the mean lag ω_driver − ω_driven
//! over the ramp [0.1, 0.6] s and the mean driven speed over [0.8, 1] s. Timing: wall time of
//! the dynamic run per simulated second, over the whole second and over [0.6, 1] s (after the
//! ramp), median of `BELT_VS_EXUDYN_REPS` (default 3) alternated runs; the static
//! pre-tension solve is not timed in either code.
//!
//! Run: `cargo bench --profile release --workspace --bench belt_vs_exudyn` (a few minutes). Prints
//! `ratio = ours / peer` per modulus. `BELT_VS_EXUDYN_E=1e9` runs one modulus only;
//! `BELT_VS_EXUDYN_H_OURS=4e-4` replaces our default step \[s\] (the scan of BENCHMARKS.md).

use drives::ancf_run::roles;
use drives::ancf_study::{AncfStudyConfig, dynamic_run, dynamic_setup};
use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

/// Accuracy bound on the driven speed for "equal accuracy" \[rad/s\] (0.1 % of 12 rad/s).
const TOL: f64 = 0.012;
/// Reference step of both codes \[s\].
const H_REF: f64 = 2.5e-5;
/// Our Newton tolerance in the reference run \[m\].
const H_REF_NEWTON_ATOL: f64 = 1e-7;

/// One run: sampled driven speed, wall times.
struct Run {
    /// `(t, ω_driver, ω_driven)` every 1 ms \[s, rad/s\].
    samples: Vec<(f64, f64, f64)>,
    wall: f64,
    wall_after_ramp: f64,
    /// CPU time of the dynamic run and after the ramp \[s\] (load-independent up to cache
    /// effects; the machine is shared).
    cpu: f64,
    cpu_after_ramp: f64,
    steps: usize,
    iterations: usize,
}

fn ours(young: f64, h: Option<f64>) -> Run {
    let mut c = AncfStudyConfig::default();
    c.drive.belt.young = young;
    if let Some(h) = h {
        c.integrator.h = h;
    }
    if h == Some(H_REF) {
        // the reference is converged in the Newton tolerance too (the default 5e-6 m is
        // sized for the default step; at h = 2.5e-5 s it would be 10x looser in velocity)
        c.integrator.newton_atol = H_REF_NEWTON_ATOL;
    }
    let (drive, init) = dynamic_setup(&c).expect("Table 3.1 drive");
    let (driver, driven) = roles(&drive);
    let driven = driven.expect("free driven pulley");
    let mut samples = Vec::new();
    let mut ramp_mark = None;
    let mut ramp_cpu = f64::NAN;
    let start = Instant::now();
    let cpu0 = cpu_time();
    let end = dynamic_run(&c, &drive, &init, start, |s, due| -> Result<(), ()> {
        if due.history {
            samples.push((
                s.t,
                drive.pulley_speed(driver, s.t, &s.v),
                drive.pulley_speed(driven, s.t, &s.v),
            ));
        }
        if ramp_mark.is_none() && s.t >= 0.6 - 1e-9 {
            ramp_mark = Some(Instant::now());
            ramp_cpu = cpu_time();
        }
        Ok(())
    })
    .expect("observer never fails");
    let wall = start.elapsed().as_secs_f64();
    let cpu1 = cpu_time();
    if let Some(f) = &end.failure {
        panic!("ours failed at t = {}: {f}", end.state.t);
    }
    Run {
        samples,
        wall,
        wall_after_ramp: ramp_mark.map_or(f64::NAN, |m| m.elapsed().as_secs_f64()),
        cpu: cpu1 - cpu0,
        cpu_after_ramp: cpu1 - ramp_cpu,
        steps: end.summary.run.steps,
        iterations: end.summary.run.newton_iterations,
    }
}

/// CPU time of this process \[s\].
fn cpu_time() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid timespec for clock_gettime to write.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

fn workspace() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("workspace root")
        .to_path_buf()
}

fn peer(young: f64, h: f64) -> Run {
    let root = workspace();
    let python = std::env::var("EXUDYN_PYTHON")
        .map(PathBuf::from)
        .unwrap_or_else(|_| root.join(".venv/bin/python"));
    let script = root.join("drives/benches/peers/exudyn_belt.py");
    let out = Command::new(&python)
        .arg(&script)
        .args(["--young", &young.to_string(), "--h", &h.to_string()])
        .args(["--solver", "sparse"])
        .output()
        .unwrap_or_else(|e| {
            panic!(
                "cannot run {}: {e} (install exudyn and numpy into .venv)",
                python.display()
            )
        });
    assert!(
        out.status.success(),
        "peer failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value =
        serde_json::from_slice(&out.stdout).expect("peer prints one JSON object");
    let arr = |k: &str| -> Vec<f64> {
        v[k].as_array()
            .expect("array")
            .iter()
            .map(|x| x.as_f64().unwrap_or(f64::NAN))
            .collect()
    };
    let (t, wd, w) = (arr("t"), arr("omega_driver"), arr("omega_driven"));
    Run {
        samples: t
            .iter()
            .zip(&wd)
            .zip(&w)
            .map(|((t, a), b)| (*t, *a, *b))
            .collect(),
        wall: v["wall_dynamic_s"].as_f64().unwrap_or(f64::NAN),
        wall_after_ramp: v["wall_after_ramp_s"].as_f64().unwrap_or(f64::NAN),
        cpu: v["cpu_dynamic_s"].as_f64().unwrap_or(f64::NAN),
        cpu_after_ramp: v["cpu_after_ramp_s"].as_f64().unwrap_or(f64::NAN),
        steps: v["stats"]["steps"].as_u64().unwrap_or(0) as usize,
        iterations: v["stats"]["newton_iterations"].as_u64().unwrap_or(0) as usize,
    }
}

/// Driven speed at the 1 ms sample nearest to `t`.
fn at(r: &Run, t: f64) -> f64 {
    r.samples
        .iter()
        .min_by(|a, b| (a.0 - t).abs().total_cmp(&(b.0 - t).abs()))
        .map_or(f64::NAN, |s| s.2)
}

fn mean_over(r: &Run, from: f64, to: f64, f: impl Fn(&(f64, f64, f64)) -> f64) -> f64 {
    let v: Vec<f64> = r
        .samples
        .iter()
        .filter(|s| s.0 >= from - 1e-9 && s.0 <= to + 1e-9)
        .map(f)
        .collect();
    v.iter().sum::<f64>() / v.len() as f64
}

/// Largest |ω_driven − ω_ref| over the common 1 ms samples.
fn max_dev(r: &Run, reference: &Run) -> f64 {
    let key = |t: f64| (t * 1000.0).round() as i64;
    let map: std::collections::HashMap<i64, f64> =
        reference.samples.iter().map(|s| (key(s.0), s.2)).collect();
    r.samples
        .iter()
        .filter_map(|s| map.get(&key(s.0)).map(|w| (s.2 - w).abs()))
        .fold(0.0, f64::max)
}

fn describe(name: &str, r: &Run, reference: Option<&Run>) -> String {
    format!(
        "{name}: {:.3} s wall/simulated s ({:.3} s/s after the ramp; CPU {:.3}, {:.3}), {} steps, {} Newton it.; \
         ω_driven(0.2, 0.6, 0.7, 1.0) = {:.4}, {:.4}, {:.4}, {:.4} rad/s, ramp lag {:.4} rad/s, \
         mean [0.8, 1] {:.4} rad/s{}",
        r.wall,
        r.wall_after_ramp / 0.4,
        r.cpu,
        r.cpu_after_ramp / 0.4,
        r.steps,
        r.iterations,
        at(r, 0.2),
        at(r, 0.6),
        at(r, 0.7),
        at(r, 1.0),
        mean_over(r, 0.1, 0.6, |s| s.1 - s.2),
        mean_over(r, 0.8, 1.0, |s| s.2),
        reference.map_or(String::new(), |f| format!(
            ", max |Δω| vs own h = {H_REF:e} s: {:.2e} rad/s",
            max_dev(r, f)
        ))
    )
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let reps: usize = std::env::var("BELT_VS_EXUDYN_REPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    let with_ref = std::env::var("BELT_VS_EXUDYN_REFERENCE").map_or(true, |v| v != "0");
    // one modulus only (`BELT_VS_EXUDYN_E=1e9`), our step overridden (`BELT_VS_EXUDYN_H_OURS`)
    let only: Option<f64> = std::env::var("BELT_VS_EXUDYN_E")
        .ok()
        .and_then(|s| s.parse().ok());
    let h_env: Option<f64> = std::env::var("BELT_VS_EXUDYN_H_OURS")
        .ok()
        .and_then(|s| s.parse().ok());
    for (young, h_ours, h_peer) in [(1e8, None, 1e-4), (1e9, None, 4e-4)] {
        if only.is_some_and(|e| e != young) {
            continue;
        }
        let h_ours: Option<f64> = h_env.or(h_ours);
        println!(
            "== E = {young:e} Pa (our step {}, peer step {h_peer:e} s)",
            h_ours.map_or("default".to_string(), |h| format!("{h:e} s"))
        );
        let refs = with_ref.then(|| {
            let o = ours(young, Some(H_REF));
            println!("{}", describe("ours, reference", &o, None));
            let p = peer(young, H_REF);
            println!("{}", describe("peer, reference", &p, None));
            println!(
                "model difference (references): max |Δω_driven| {:.3e} rad/s",
                max_dev(&o, &p)
            );
            (o, p)
        });
        let (mut wo, mut wp, mut ao, mut ap) = (vec![], vec![], vec![], vec![]);
        let (mut co, mut cp) = (vec![], vec![]);
        for k in 0..reps {
            let o = ours(young, h_ours);
            println!(
                "{}",
                describe(&format!("ours #{k}"), &o, refs.as_ref().map(|r| &r.0))
            );
            let p = peer(young, h_peer);
            println!(
                "{}",
                describe(&format!("peer #{k}"), &p, refs.as_ref().map(|r| &r.1))
            );
            if let Some((ro, rp)) = &refs {
                let (eo, ep) = (max_dev(&o, ro), max_dev(&p, rp));
                if eo > TOL || ep > TOL {
                    println!(
                        "  (accuracy bound {TOL} rad/s exceeded: ours {eo:.2e}, peer {ep:.2e})"
                    );
                }
            }
            wo.push(o.wall);
            wp.push(p.wall);
            ao.push(o.wall_after_ramp / 0.4);
            ap.push(p.wall_after_ramp / 0.4);
            co.push(o.cpu);
            cp.push(p.cpu);
        }
        let (mo, mp) = (median(wo), median(wp));
        let (mao, map) = (median(ao), median(ap));
        println!(
            "E = {young:e}: wall per simulated second, median of {reps}: ours {mo:.3} s, peer {mp:.3} s; \
             after the ramp ours {mao:.3} s/s, peer {map:.3} s/s"
        );
        println!(
            "ratio = ours / peer = {:.3} (whole run), {:.3} (after the ramp)",
            mo / mp,
            mao / map
        );
    }
}
