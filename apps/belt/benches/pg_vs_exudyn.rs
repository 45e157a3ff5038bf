//! The Pechstein & Gerstmayr (2013) two-pulley drive (issue 34 item 7) on our belt models and on
//! Exudyn, in one bench, alternating, each side run as its users run it:
//!
//! - ours: `flowmbd-belt fead --config apps/belt/examples/pechstein-gerstmayr.toml --model M
//!   --json --quiet` for each model `M` of `PG_MODELS` (default `ancf,flowing,nodal`), with the
//!   binary this bench was built with, or `FLOWMBD_BELT` (a copy of it, where a shared target
//!   directory may be rebuilt during the run);
//! - peer: `drives/benches/peers/exudyn_pechstein_gerstmayr.py` (Exudyn's ANCF cable with the
//!   example's bristle friction, `drives/benches/peers/PECHSTEIN_GERSTMAYR.md`) with the
//!   arguments `PG_PEER_ARGS` (default `--elements 240 --segments 12`: the contact refined until
//!   the bristle's sticking-position error, ε·L_seg/2 per segment wrapping on, is below its stick
//!   displacement; the example's own 120 elements × 2 segments is `PG_PEER_ARGS=""` and gives a
//!   speed loss 6 % low, see that note), run by `EXUDYN_PYTHON` (default
//!   `<workspace>/.venv/bin/python`, a venv with exudyn and numpy from PyPI).
//!
//! Per round (`PG_REPS`, default 1): the peer, then each of our models; every run under
//! `/usr/bin/time` (user + system CPU and wall of the whole process, both sides single-threaded).
//! Prints per model the driven pulley's mean speed, the speed loss and the tight and slack span
//! tensions with their deviation from Exudyn's, our torque and power balance residuals, and the
//! CPU ratio ours / Exudyn. Accuracy targets (issue 34 item 7): spans within 2 %, ω_driven within
//! 0.5 %, speed loss within 5 %.
//!
//! Run: `cargo bench --profile release -p flowmbd-belt --bench pg_vs_exudyn` (≈ 13 min of CPU
//! with the three models, 2026-12-06: ANCF ≈ 37 s, flowing ≈ 220 s, nodal ≈ 190 s, Exudyn ≈ 340 s;
//! Exudyn ≈ 90 s with the example's contact).

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{SystemTime, UNIX_EPOCH};

/// One process run: its JSON on stdout, CPU (user + system) and wall time \[s\].
struct Timed {
    json: Value,
    cpu: f64,
    wall: f64,
}

/// Runs `cmd` under `/usr/bin/time -f "%U %S %e"` (written to a file, so that the command's
/// own stderr stays apart) and parses its stdout as JSON.
fn timed(cmd: Command, what: &str) -> Timed {
    let stamp = std::env::temp_dir().join(format!(
        "pg-vs-exudyn-time-{}-{}",
        std::process::id(),
        SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos())
    ));
    let program = cmd.get_program().to_owned();
    let args: Vec<_> = cmd.get_args().map(|a| a.to_owned()).collect();
    let mut wrapped = Command::new("/usr/bin/time");
    wrapped
        .arg("-f")
        .arg("%U %S %e")
        .arg("-o")
        .arg(&stamp)
        .arg(program)
        .args(args);
    if let Some(dir) = cmd.get_current_dir() {
        wrapped.current_dir(dir);
    }
    let out = wrapped
        .output()
        .unwrap_or_else(|e| panic!("cannot run {what} under /usr/bin/time: {e}"));
    assert!(
        out.status.success(),
        "{what} failed ({}): {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    let times = std::fs::read_to_string(&stamp).expect("/usr/bin/time output");
    let _ = std::fs::remove_file(&stamp);
    let t: Vec<f64> = times
        .split_whitespace()
        .rev()
        .take(3)
        .filter_map(|x| x.parse().ok())
        .collect();
    assert_eq!(t.len(), 3, "/usr/bin/time printed {times:?}");
    let json = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{what}: stdout is not JSON: {e}"));
    Timed {
        json,
        cpu: t[2] + t[1],
        wall: t[0],
    }
}

/// Our figures from a fead summary: ω_driven, speed loss \[%\], tight and slack span \[N\],
/// torque and power balance residuals.
fn ours_figures(s: &Value) -> [f64; 6] {
    let p = &s["points"][0];
    let num = |v: &Value| v.as_f64().expect("number");
    let spans: Vec<f64> = p["spans"]
        .as_array()
        .expect("spans")
        .iter()
        .map(|sp| num(&sp["tension"]["mean"]))
        .collect();
    let tight = spans.iter().copied().fold(f64::MIN, f64::max);
    let slack = spans.iter().copied().fold(f64::MAX, f64::min);
    let b = &p["report"]["balances"];
    [
        num(&p["pulley_speed"][1]["mean"]),
        num(&p["speed_loss_percent"][1]),
        tight,
        slack,
        100.0 * num(&b["torque_residual_rel"]),
        100.0 * num(&b["power_residual_rel"]),
    ]
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let python = std::env::var_os("EXUDYN_PYTHON")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join(".venv/bin/python"));
    let models = std::env::var("PG_MODELS").unwrap_or_else(|_| "ancf,flowing,nodal".into());
    let reps: usize = std::env::var("PG_REPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let peer_args =
        std::env::var("PG_PEER_ARGS").unwrap_or_else(|_| "--elements 240 --segments 12".into());
    let belt_bin = std::env::var_os("FLOWMBD_BELT")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_flowmbd-belt")));
    let config = root.join("apps/belt/examples/pechstein-gerstmayr.toml");
    let script = root.join("drives/benches/peers/exudyn_pechstein_gerstmayr.py");
    let out_dir = std::env::temp_dir().join(format!("pg-vs-exudyn-{}", std::process::id()));
    let mut peer_runs = Vec::new();
    let mut our_runs: Vec<(String, Timed)> = Vec::new();
    for round in 0..reps {
        let mut peer = Command::new(&python);
        peer.arg(&script).args(peer_args.split_whitespace());
        eprintln!("round {}: Exudyn", round + 1);
        peer_runs.push(timed(peer, "the Exudyn peer"));
        for m in models.split(',').map(str::trim).filter(|m| !m.is_empty()) {
            eprintln!("round {}: ours, {m}", round + 1);
            let mut ours = Command::new(&belt_bin);
            ours.args(["fead", "--config"])
                .arg(&config)
                .args(["--model", m, "--json", "--quiet", "--out"])
                .arg(out_dir.join(m));
            our_runs.push((m.to_string(), timed(ours, m)));
        }
    }
    let _ = std::fs::remove_dir_all(&out_dir);
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let pj = &peer_runs[0].json;
    let pnum = |k: &str| pj[k].as_f64().unwrap_or(f64::NAN);
    let peer = [
        pnum("omega_driven"),
        pnum("speed_loss_pct"),
        pnum("tension_tight_n"),
        pnum("tension_slack_n"),
        pnum("creep_speed_loss_pct"),
    ];
    let peer_cpu = mean(&peer_runs.iter().map(|r| r.cpu).collect::<Vec<_>>());
    let peer_wall = mean(&peer_runs.iter().map(|r| r.wall).collect::<Vec<_>>());
    println!(
        "Exudyn ({peer_args}): omega_driven {:.4} rad/s, speed loss {:.3} % (creep theory of its \
         spans {:.3} %), tight / slack {:.1} / {:.1} N, CPU {peer_cpu:.1} s, wall {peer_wall:.1} s \
         (mean of {reps})",
        peer[0], peer[1], peer[4], peer[2], peer[3]
    );
    let rel = |a: f64, b: f64| 100.0 * (a / b - 1.0);
    for m in models.split(',').map(str::trim).filter(|m| !m.is_empty()) {
        let runs: Vec<&Timed> = our_runs
            .iter()
            .filter(|(k, _)| k == m)
            .map(|(_, t)| t)
            .collect();
        let f = ours_figures(&runs[0].json);
        let cpu = mean(&runs.iter().map(|r| r.cpu).collect::<Vec<_>>());
        let wall = mean(&runs.iter().map(|r| r.wall).collect::<Vec<_>>());
        println!(
            "{m}: omega_driven {:.4} ({:+.2} %), speed loss {:.3} % ({:+.1} %), tight {:.1} N \
             ({:+.2} %), slack {:.1} N ({:+.2} %), torque / power residual {:.3} / {:.3} %, \
             CPU {cpu:.1} s, wall {wall:.1} s, ratio ours / Exudyn CPU {:.2}",
            f[0],
            rel(f[0], peer[0]),
            f[1],
            rel(f[1], peer[1]),
            f[2],
            rel(f[2], peer[2]),
            f[3],
            rel(f[3], peer[3]),
            f[4],
            f[5],
            cpu / peer_cpu
        );
    }
}
