//! The three speed-loss models of issue 8 in one run, side by side: wall time per simulated
//! second of the Ribaric Table 6-1 drive (62.8 rad/s, load 0 → 8 N m, steady-state detection
//! with 0.1 s windows), each at the step that keeps its Δω within 1 % of its own 0.25 ms (ANCF:
//! its default 0.1 ms) value (`flowing/benches/belt.rs` measured the step sweeps):
//! - flowing-material form (5.14), default 56-element stationary mesh, 20 free modes, h = 4 ms;
//! - nodal rotating mesh (5.7), uniform 216-element loop (its Δω within 2 % of the flowing form
//!   on the same loop), h = 0.5 ms;
//! - ANCF belt (Kerkkänen ch. 3), the `--model ancf` adapter (40 elements), h = 0.1 ms.
//!
//! Run: `cargo bench -p drives --bench speed_loss_models` (several minutes).

use belt::BeltModel;
use drives::ancf_model::{AncfBelt, AncfConfig};
use drives::{NodalConfig, SpeedLossConfig, speed_loss_sweep};
use flowing::belt::{FlowingBelt, FlowingSettings, NodalBelt};
use mbd_core::SecondOrderSystem;
use std::time::Instant;

fn run<M: BeltModel>(name: &str, dofs: usize, model: &mut M, step: f64) -> Option<(f64, f64)> {
    let settings = SpeedLossConfig {
        torques: vec![0.0, 8.0],
        window: 0.1,
        tolerance: 1e-3,
        max_hold: 3.0,
        step,
        ..Default::default()
    };
    let start = Instant::now();
    match speed_loss_sweep(model, &settings, |_, _| {}) {
        Ok((points, stats)) => {
            let wall = start.elapsed().as_secs_f64();
            let rate = wall / stats.simulated_time;
            println!(
                "{name:<34} {dofs:>5} {:>7.2} {:>8.3} {wall:>8.2} {rate:>10.3} {:>11.5}",
                1e3 * step,
                stats.simulated_time,
                points[1].delta_omega
            );
            Some((rate, points[1].delta_omega))
        }
        Err(f) => {
            println!("{name:<34} failed: {}", f.error);
            None
        }
    }
}

fn main() {
    println!("belt drive, Table 6-1, 62.8 rad/s, load 0 -> 8 N m (generalized-alpha, rho = 0.6)");
    println!(
        "{:<34} {:>5} {:>7} {:>8} {:>8} {:>10} {:>11}",
        "model", "DOF", "h [ms]", "sim [s]", "wall [s]", "wall/sim", "dw(8) rad/s"
    );
    let cfg = drives::table_6_1::drive();
    let mut flow = FlowingBelt::new(&cfg, &FlowingSettings::default()).expect("flowing model");
    let dofs = flow.n_q();
    let f = run("flowing, 56 el., 20 free modes", dofs, &mut flow, 4e-3);
    let mut nodal = NodalBelt::new(&cfg, &NodalConfig::default().mesh).expect("nodal model");
    let dofs = nodal.n_q();
    let n = run("nodal rotating mesh, 216 el.", dofs, &mut nodal, 5e-4);
    let a = AncfConfig::default();
    let mut ancf = AncfBelt::new(&cfg, &a).expect("ANCF model");
    let dofs = ancf.n_v();
    let an = run(
        &format!("ANCF belt, {} el.", a.elements),
        dofs,
        &mut ancf,
        a.step,
    );
    if let (Some(f), Some(n), Some(an)) = (f, n, an) {
        println!(
            "wall time per simulated second relative to flowing: nodal {:.0}x, ANCF {:.0}x; \
             Δω(8) relative to flowing: nodal {:+.1} %, ANCF {:+.1} %",
            n.0 / f.0,
            an.0 / f.0,
            100.0 * (n.1 / f.1 - 1.0),
            100.0 * (an.1 / f.1 - 1.0)
        );
    }
}
